/* vec.h - double-precision 3-vectors and 3x3 matrices, all inline.
 * Generators compute in double and store float only in the final mesh, so
 * long random walks do not drift and hashes stay stable. */
#ifndef BANYAN_VEC_H
#define BANYAN_VEC_H

#include <math.h>

#include "dmath.h"

typedef struct v3 { double x, y, z; } v3;
/* Row-major: m[3*r + c]. */
typedef struct m3 { double m[9]; } m3;

static inline v3 v3_make(double x, double y, double z) { v3 r = {x, y, z}; return r; }
static inline v3 v3_load(const double *p) { return v3_make(p[0], p[1], p[2]); }
static inline v3 v3_add(v3 a, v3 b) { return v3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline v3 v3_sub(v3 a, v3 b) { return v3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline v3 v3_scale(v3 a, double s) { return v3_make(a.x * s, a.y * s, a.z * s); }
static inline v3 v3_madd(v3 a, v3 b, double s) { return v3_make(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
static inline v3 v3_neg(v3 a) { return v3_make(-a.x, -a.y, -a.z); }
static inline double v3_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline v3 v3_cross(v3 a, v3 b) {
    return v3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double v3_len2(v3 a) { return v3_dot(a, a); }
static inline double v3_len(v3 a) { return sqrt(v3_dot(a, a)); }
static inline double v3_dist(v3 a, v3 b) { return v3_len(v3_sub(a, b)); }
static inline v3 v3_lerp(v3 a, v3 b, double t) { return v3_madd(a, v3_sub(b, a), t); }
static inline int v3_finite(v3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* Unit vector along a, or `fallback` when |a| is below 1e-300. */
static inline v3 v3_norm_or(v3 a, v3 fallback) {
    double l = v3_len(a);
    return l > 1e-300 ? v3_scale(a, 1.0 / l) : fallback;
}
static inline v3 v3_norm(v3 a) { return v3_norm_or(a, v3_make(0, 0, 1)); }

/* Some unit vector perpendicular to unit n (stable for every n). */
static inline v3 v3_any_perp(v3 n) {
    v3 a = fabs(n.x) < 0.6 ? v3_make(1, 0, 0) : v3_make(0, 1, 0);
    return v3_norm(v3_cross(n, a));
}

/* Unit vector along a, or v3_any_perp(n) when |a| is below 1e-300: as
 * v3_norm_or(a, v3_any_perp(n)), but the fallback is made only when used. */
static inline v3 v3_norm_or_perp(v3 a, v3 n) {
    double l = v3_len(a);
    return l > 1e-300 ? v3_scale(a, 1.0 / l) : v3_any_perp(n);
}

/* Rodrigues rotation of v by `angle` radians about unit axis k. */
static inline v3 v3_rotate(v3 v, v3 k, double angle) {
    double c = dm_cos(angle), s = dm_sin(angle);
    v3 r = v3_scale(v, c);
    r = v3_madd(r, v3_cross(k, v), s);
    return v3_madd(r, k, v3_dot(k, v) * (1.0 - c));
}

/* Rotation about the vertical (Z) axis. */
static inline v3 v3_rotate_z(v3 v, double angle) {
    double c = dm_cos(angle), s = dm_sin(angle);
    return v3_make(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
}

static inline m3 m3_identity(void) { m3 r = {{1, 0, 0, 0, 1, 0, 0, 0, 1}}; return r; }
static inline m3 m3_load(const double *p) { m3 r; for (int i = 0; i < 9; i++) r.m[i] = p[i]; return r; }
static inline v3 m3_col(const m3 *a, int c) { return v3_make(a->m[c], a->m[3 + c], a->m[6 + c]); }
static inline v3 m3_mul_v3(const m3 *a, v3 v) {
    return v3_make(a->m[0] * v.x + a->m[1] * v.y + a->m[2] * v.z,
                   a->m[3] * v.x + a->m[4] * v.y + a->m[5] * v.z,
                   a->m[6] * v.x + a->m[7] * v.y + a->m[8] * v.z);
}
/* Transpose times v: world -> local for a rotation. */
static inline v3 m3_tmul_v3(const m3 *a, v3 v) {
    return v3_make(a->m[0] * v.x + a->m[3] * v.y + a->m[6] * v.z,
                   a->m[1] * v.x + a->m[4] * v.y + a->m[7] * v.z,
                   a->m[2] * v.x + a->m[5] * v.y + a->m[8] * v.z);
}
static inline m3 m3_mul(const m3 *a, const m3 *b) {
    m3 r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.m[3 * i + j] = a->m[3 * i] * b->m[j] + a->m[3 * i + 1] * b->m[3 + j] + a->m[3 * i + 2] * b->m[6 + j];
    return r;
}
static inline double m3_det(const m3 *a) {
    const double *m = a->m;
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}
/* Rotation matrix about unit axis k by angle radians. */
static inline m3 m3_rotation(v3 k, double angle) {
    m3 r;
    v3 ex = v3_rotate(v3_make(1, 0, 0), k, angle), ey = v3_rotate(v3_make(0, 1, 0), k, angle),
       ez = v3_rotate(v3_make(0, 0, 1), k, angle);
    r.m[0] = ex.x; r.m[1] = ey.x; r.m[2] = ez.x;
    r.m[3] = ex.y; r.m[4] = ey.y; r.m[5] = ez.y;
    r.m[6] = ex.z; r.m[7] = ey.z; r.m[8] = ez.z;
    return r;
}

#define BANYAN_PI 3.14159265358979323846
static inline double deg2rad(double d) { return d * (BANYAN_PI / 180.0); }

#endif
