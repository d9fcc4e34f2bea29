/* bezier.h - cubic Bezier Q(t) = (1-t)^3 P0 + 3t(1-t)^2 P1 + 3t^2(1-t) P2 + t^3 P3,
 * as used by the roots spec (first/second branch roots, path correction). */
#ifndef BANYAN_BEZIER_H
#define BANYAN_BEZIER_H

#include "vec.h"

static inline v3 bezier3(v3 p0, v3 p1, v3 p2, v3 p3, double t) {
    double s = 1.0 - t;
    double b0 = s * s * s, b1 = 3.0 * t * s * s, b2 = 3.0 * t * t * s, b3 = t * t * t;
    return v3_make(b0 * p0.x + b1 * p1.x + b2 * p2.x + b3 * p3.x,
                   b0 * p0.y + b1 * p1.y + b2 * p2.y + b3 * p3.y,
                   b0 * p0.z + b1 * p1.z + b2 * p2.z + b3 * p3.z);
}

/* Derivative dQ/dt. */
static inline v3 bezier3_tangent(v3 p0, v3 p1, v3 p2, v3 p3, double t) {
    double s = 1.0 - t;
    v3 a = v3_scale(v3_sub(p1, p0), 3.0 * s * s);
    v3 b = v3_scale(v3_sub(p2, p1), 6.0 * s * t);
    v3 c = v3_scale(v3_sub(p3, p2), 3.0 * t * t);
    return v3_add(v3_add(a, b), c);
}

#endif
