/* Deterministic elementary functions: the same bits on every x86-64 CPU.
 *
 * glibc's libm picks, per CPU at load time, between builds of sin, cos,
 * tan, asin, acos, atan2, exp, log and pow (and their float versions) made
 * with and without FMA; the two round differently, so a plant grown on a
 * CPU with FMA would differ in its bytes from one grown without (docs/api.md,
 * "Determinism"). Every transcendental the library and the CLI compute
 * goes through here instead, to SLEEF 3.3's scalar functions, compiled
 * from the source in third_party/sleef (its README) into the library and
 * the CLI on every platform: plain SSE2 arithmetic, no FMA (built with
 * -ffp-contract=off), no CPU dispatch, and the same source on Linux and
 * Windows. sqrt, floor, round, fmin, fmax, ldexp and lrint are exact in
 * IEEE arithmetic and stay libm's. The deterministic_math test (tests/isa)
 * fails if an object of the library or the CLI calls one of the
 * dispatched functions. */
#ifndef BANYAN_DMATH_H
#define BANYAN_DMATH_H

#include <float.h>

/* third_party/sleef/src/libm/sleefdp.c, under the names its rename.h
 * gives them. */
#ifdef __cplusplus
extern "C" {
#endif
double Sleef_sin_u35(double x);
double Sleef_cos_u35(double x);
double Sleef_tan_u35(double x);
double Sleef_asin_u35(double x);
double Sleef_acos_u35(double x);
double Sleef_atan2_u35(double y, double x);
double Sleef_exp_u10(double x);
double Sleef_log_u35(double x);
double Sleef_cbrt_u35(double x);
double Sleef_hypot_u35(double x, double y);
double Sleef_pow_u10(double x, double y);
#ifdef __cplusplus
}
#endif

/* Most at 3.5 ulp (SLEEF's u35: as fast as glibc); exp at 1 ulp. */
static inline double dm_sin(double x) { return Sleef_sin_u35(x); }
static inline double dm_cos(double x) { return Sleef_cos_u35(x); }
static inline double dm_tan(double x) { return Sleef_tan_u35(x); }
static inline double dm_asin(double x) { return Sleef_asin_u35(x); }
static inline double dm_acos(double x) { return Sleef_acos_u35(x); }
static inline double dm_atan2(double y, double x) { return Sleef_atan2_u35(y, x); }
static inline double dm_exp(double x) { return Sleef_exp_u10(x); }
static inline double dm_log(double x) { return Sleef_log_u35(x); }
static inline double dm_cbrt(double x) { return Sleef_cbrt_u35(x); }
static inline double dm_hypot(double x, double y) { return Sleef_hypot_u35(x, y); }

/* x^y as exp(y log x) for x > 0 (a third of SLEEF's own pow's time; the
 * relative error grows with |y log x|, about 1e-14 for the exponents and
 * bases here), SLEEF's pow for the rest. */
static inline double dm_pow(double x, double y) {
    if (x > 0 && x <= DBL_MAX && y == y) return y == 0 ? 1.0 : Sleef_exp_u10(y * Sleef_log_u35(x));
    return Sleef_pow_u10(x, y);
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
