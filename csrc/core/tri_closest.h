/* tri_closest.h - the closest point of a triangle to a point, shared by
 * the mesh hosts' queries (host_queries.c) and the roots' aerial threads. */
#ifndef BANYAN_TRI_CLOSEST_H
#define BANYAN_TRI_CLOSEST_H

#include "vec.h"

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

#endif
