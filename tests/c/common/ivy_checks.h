/* ivy_checks.h - ivy invariants shared by the ivy tests and the light
 * grid's (unit/test_ivy_grid.c). */
#ifndef BANYAN_IVY_CHECKS_H
#define BANYAN_IVY_CHECKS_H

#include <stdlib.h>

#include "ivy/ivy_internal.h"

/* The light H0 at p and its direction V_l summed over every bud but self
 * (spec/ivy.md), with no grid: what the look-up must equal. */
static inline double brute_shade(const banyan_ivy *iv, v3 p, int32_t self, v3 *vl) {
    double H = 0;
    *vl = v3_make(0, 0, 0);
    for (int32_t j = 0; j < iv->n; j++) {
        if (j == self) continue;
        const ivy_bud *b = &iv->buds[j];
        double d = v3_dist(p, b->P);
        if (d >= iv->p.leaf_max) continue;
        double dl = ivy_leaf_diameter(iv, b);
        double h = d < dl ? 1.0 : 1.0 - (d - dl) / iv->p.leaf_max;
        if (h <= 0) continue;
        if (b->follow > 0) h *= IVY_FOLLOW_LEAF; /* a stem grown alongside another */
        H += h;
        if (d > 1e-12) *vl = v3_madd(*vl, v3_sub(p, b->P), h / d);
    }
    return H;
}

/* Stem crossings by brute force over every pair of internodes, each seen
 * on its end bud's face chart (docs/ivy.md): a box face in the box's
 * axes, a mesh's cube-map face in the world plane across its axis. */
static inline int32_t brute_crossings(const banyan_ivy *iv) {
    int32_t n = iv->n, count = 0;
    int32_t *face = malloc(sizeof(int32_t) * (size_t)n);
    double (*uv)[4] = malloc(sizeof *uv * (size_t)n);
    for (int32_t i = 0; i < n; i++) {
        const ivy_bud *b = &iv->buds[i];
        ivy_near nr = ivy_nearest_any(iv, b->P);
        face[i] = nr.host * 6 + nr.face;
        if (b->parent < 0) continue;
        int k = nr.face / 2, a = (k + 1) % 3, c = (k + 2) % 3;
        v3 p0 = b->P, p1 = iv->buds[b->parent].P;
        if ((uint32_t)nr.host < iv->n_hosts) {
            const obb *o = &iv->hosts[nr.host];
            v3 d0 = v3_sub(p0, o->c), d1 = v3_sub(p1, o->c);
            uv[i][0] = v3_dot(d0, o->ax[a]);
            uv[i][1] = v3_dot(d0, o->ax[c]);
            uv[i][2] = v3_dot(d1, o->ax[a]);
            uv[i][3] = v3_dot(d1, o->ax[c]);
        } else {
            const double q0[3] = {p0.x, p0.y, p0.z}, q1[3] = {p1.x, p1.y, p1.z};
            uv[i][0] = q0[a];
            uv[i][1] = q0[c];
            uv[i][2] = q1[a];
            uv[i][3] = q1[c];
        }
    }
    for (int32_t i = 1; i < n; i++)
        for (int32_t j = i + 1; j < n; j++) {
            const ivy_bud *s = &iv->buds[i], *t = &iv->buds[j];
            if (face[i] != face[j] || s->parent < 0 || t->parent < 0) continue;
            if (s->parent == t->parent || s->parent == j || t->parent == i) continue;
            const double *A = uv[i], *B = uv[j];
#define X2(o0, o1, a0, a1, b0, b1) (((a0) - (o0)) * ((b1) - (o1)) - ((a1) - (o1)) * ((b0) - (o0)))
            double d1 = X2(A[0], A[1], A[2], A[3], B[0], B[1]), d2 = X2(A[0], A[1], A[2], A[3], B[2], B[3]);
            double d3 = X2(B[0], B[1], B[2], B[3], A[0], A[1]), d4 = X2(B[0], B[1], B[2], B[3], A[2], A[3]);
#undef X2
            if ((d1 > 0) != (d2 > 0) && d1 != 0 && d2 != 0 && (d3 > 0) != (d4 > 0) && d3 != 0 && d4 != 0) count++;
        }
    free(face);
    free(uv);
    return count;
}

#endif
