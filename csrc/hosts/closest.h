/* closest.h - closest points (Ericson, Real-Time Collision Detection 5.1):
 * of a triangle to a point, and between two segments; shared by the mesh
 * hosts' queries (host_queries.c) and the roots' aerial threads. */
#ifndef BANYAN_CLOSEST_H
#define BANYAN_CLOSEST_H

#include "base/vec.h"

/* Closest point of triangle abc to p (Ericson, Real-Time Collision
 * Detection 5.1.5). *region: 0 face, 1..3 vertex a, b, c, 4..6 edge ab,
 * bc, ca. */
static inline v3 tri_closest(v3 p, v3 a, v3 b, v3 c, int *region) {
    v3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a);
    double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) { *region = 1; return a; }
    v3 bp = v3_sub(p, b);
    double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) { *region = 2; return b; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        *region = 4;
        return v3_madd(a, ab, d1 / (d1 - d3));
    }
    v3 cp = v3_sub(p, c);
    double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) { *region = 3; return c; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        *region = 6;
        return v3_madd(a, ac, d2 / (d2 - d6));
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        *region = 5;
        return v3_madd(b, v3_sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    double den = 1.0 / (va + vb + vc);
    *region = 0;
    return v3_madd(v3_madd(a, ab, vb * den), ac, vc * den);
}

/* Squared distance between segments p1-q1 and p2-q2 (Ericson 5.1.9). */
static inline double seg_seg_dist2(v3 p1, v3 q1, v3 p2, v3 q2) {
    v3 d1 = v3_sub(q1, p1), d2 = v3_sub(q2, p2), r = v3_sub(p1, p2);
    double a = v3_dot(d1, d1), e = v3_dot(d2, d2), f = v3_dot(d2, r), s, t;
    if (a <= 1e-300 && e <= 1e-300) return v3_len2(r);
    if (a <= 1e-300) {
        s = 0;
        t = f / e;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
    } else {
        double c = v3_dot(d1, r);
        if (e <= 1e-300) {
            t = 0;
            s = -c / a;
            s = s < 0 ? 0 : s > 1 ? 1 : s;
        } else {
            double b = v3_dot(d1, d2), den = a * e - b * b;
            s = den > 0 ? (b * f - c * e) / den : 0;
            s = s < 0 ? 0 : s > 1 ? 1 : s;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = -c / a;
                s = s < 0 ? 0 : s > 1 ? 1 : s;
            } else if (t > 1) {
                t = 1;
                s = (b - c) / a;
                s = s < 0 ? 0 : s > 1 ? 1 : s;
            }
        }
    }
    return v3_len2(v3_sub(v3_madd(p1, d1, s), v3_madd(p2, d2, t)));
}

#endif
