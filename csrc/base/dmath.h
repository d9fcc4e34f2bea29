/* Deterministic elementary functions: the same bits on every x86-64 CPU.
 *
 * glibc's libm picks, per CPU at load time, between builds of sin, cos,
 * tan, asin, acos, atan2, exp, log and pow (and their float versions) made
 * with and without FMA; the two round differently, so a plant grown on a
 * CPU with FMA would differ in its bytes from one grown without (docs/api.md,
 * "Determinism"). Every transcendental the library and the CLI compute
 * goes through here instead, to SLEEF's pure-C scalar builds ("purec":
 * plain SSE2 arithmetic, no FMA, no CPU dispatch). sqrt, floor, round,
 * fmin, fmax, ldexp and lrint are exact in IEEE arithmetic and stay libm's.
 * The deterministic_math test (tests/isa) fails if an object of the
 * library or the CLI calls one of the dispatched functions. */
#ifndef BANYAN_DMATH_H
#define BANYAN_DMATH_H

#include <float.h>
#include <sleef.h>

/* Most at 3.5 ulp (SLEEF's u35: as fast as glibc); exp at 1 ulp. */
static inline double dm_sin(double x) { return Sleef_sind1_u35purec(x); }
static inline double dm_cos(double x) { return Sleef_cosd1_u35purec(x); }
static inline double dm_tan(double x) { return Sleef_tand1_u35purec(x); }
static inline double dm_asin(double x) { return Sleef_asind1_u35purec(x); }
static inline double dm_acos(double x) { return Sleef_acosd1_u35purec(x); }
static inline double dm_atan2(double y, double x) { return Sleef_atan2d1_u35purec(y, x); }
static inline double dm_exp(double x) { return Sleef_expd1_u10purec(x); }
static inline double dm_log(double x) { return Sleef_logd1_u35purec(x); }
static inline double dm_cbrt(double x) { return Sleef_cbrtd1_u35purec(x); }
static inline double dm_hypot(double x, double y) { return Sleef_hypotd1_u35purec(x, y); }

/* x^y as exp(y log x) for x > 0 (a third of SLEEF's own pow's time; the
 * relative error grows with |y log x|, about 1e-14 for the exponents and
 * bases here), SLEEF's pow for the rest. */
static inline double dm_pow(double x, double y) {
    if (x > 0 && x <= DBL_MAX && y == y) return y == 0 ? 1.0 : Sleef_expd1_u10purec(y * Sleef_logd1_u35purec(x));
    return Sleef_powd1_u10purec(x, y);
}

/* Floats through the double functions: as fast as SLEEF's float ones at
 * 1 ulp, and the double result rounds to the float nearest or next to it. */
static inline float dm_sinf(float x) { return (float)dm_sin(x); }
static inline float dm_cosf(float x) { return (float)dm_cos(x); }
static inline float dm_acosf(float x) { return (float)dm_acos(x); }
static inline float dm_atan2f(float y, float x) { return (float)dm_atan2(y, x); }
static inline float dm_logf(float x) { return (float)dm_log(x); }
static inline float dm_powf(float x, float y) { return (float)dm_pow(x, y); }

#endif
