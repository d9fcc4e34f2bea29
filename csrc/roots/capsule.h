/* capsule.h - one segment of a root as the fused surface sees it
 * (fused.c): a tapered capsule between two polyline points, flattened
 * where it presses on a host. The fused field and the aerial roots'
 * clearance (aerial.c) measure the same distance. */
#ifndef BANYAN_ROOTS_CAPSULE_H
#define BANYAN_ROOTS_CAPSULE_H

#include <math.h>

#include "roots_internal.h"

typedef struct capsule {
    v3 a, b;
    v3 ba;     /* b - a, and its squared length: kept for the many queries */
    double l2;
    double ra, rb;
    /* Flattening against a host (ROOTS_FLAT): the cross-section is an
     * ellipse sq R wide along the host and R / sq thick across it (normal
     * fn, outward), its centre moved (1 - 1 / sq) R towards the host so
     * that it grips as deep as the round root did; sq = 1: round. */
    v3 fn;
    double sq;
    uint32_t poly, at; /* polyline, its point index in net->pts of a */
} capsule;

/* Signed distance to a tapered capsule: distance to the axis point at the
 * projection's t, less the radius there (near enough to exact for the
 * tapers of a root, and 1-Lipschitz up to the taper's slope). *t_out gets t. */
static inline double capsule_dist(const capsule *c, v3 p, double *t_out) {
    v3 ba = c->ba, pa = v3_sub(p, c->a);
    double l2 = c->l2, t = l2 > 0 ? v3_dot(pa, ba) / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    if (t_out) *t_out = t;
    return v3_len(v3_madd(pa, ba, -t)) - (c->ra + (c->rb - c->ra) * t);
}

/* Signed distance to the flattened section of c at the axis offset e
 * (p minus the axis point at t) for radius tr: the ellipse's first-order
 * distance (|q|_E (|q|_E - 1) / |grad|, exact on the surface). */
static inline double flat_dist(const capsule *c, v3 e, double tr) {
    double sh = (1.0 - 1.0 / c->sq) * tr;
    e = v3_madd(e, c->fn, sh);
    double qn = v3_dot(e, c->fn), qt2 = v3_len2(e) - qn * qn;
    if (qt2 < 0) qt2 = 0;
    double A = tr * c->sq, B = tr / c->sq, iA2 = 1.0 / (A * A), iB2 = 1.0 / (B * B);
    double k0 = sqrt(qt2 * iA2 + qn * qn * iB2), k1 = sqrt(qt2 * iA2 * iA2 + qn * qn * iB2 * iB2);
    return k1 > 1e-12 ? k0 * (k0 - 1.0) / k1 : -B;
}

/* The field value of capsule c at p: the distance rasterise_capsule
 * writes (round, or the flattened section's). */
static inline double capsule_field(const capsule *c, v3 p) {
    double t;
    double d = capsule_dist(c, p, &t);
    if (c->sq == 1.0) return d;
    v3 e = v3_sub(p, v3_madd(c->a, c->ba, t));
    return flat_dist(c, e, c->ra + (c->rb - c->ra) * t);
}

/* A root pressed on a host flattens against it, as a fig's roots do on a
 * trunk: where the capsule's middle lies within R of the host (full
 * contact; the flattening fades out as the gap opens to r) its section is
 * ROOTS_FLAT_LO + (ROOTS_FLAT_HI - ROOTS_FLAT_LO) maturity times as wide
 * as thick; the
 * part of the host normal across the capsule's axis is the thin
 * direction, so a root leaving the host along the normal stays round. */
#define ROOTS_FLAT_LO 1.5
#define ROOTS_FLAT_HI 3.0
/* Capsule of polyline t from its point `at` (index into net->pts) to the
 * next: ends, radii, and the flattening against the hosts. */
void roots_capsule_set(capsule *c, const roots_net *net, const banyan_roots_params *p, uint32_t t, uint32_t at);

#endif
