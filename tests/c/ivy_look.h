/* ivy_look.h - the look measures of issue #19 on a grown ivy (docs/ivy.md,
 * "How the look is measured"): the stem architecture seen on one face
 * and the share of leaf area lying on the ground. */
#ifndef BANYAN_IVY_LOOK_H
#define BANYAN_IVY_LOOK_H

#include <stdlib.h>

#include "ivy/ivy_internal.h"

/* Stem length of the attached internodes on the faces whose outward normal
 * is within 25 deg of `face_n` (an internode belongs to its end bud's
 * nearest face), and the parts of it within 15 and 30 deg of vertical
 * (up or down), the internode seen along that face. */
typedef struct ivy_stem_angles {
    double length, within15, within30;
} ivy_stem_angles;

static inline ivy_stem_angles ivy_look_stem_angles(const banyan_ivy *iv, v3 face_n) {
    ivy_stem_angles a = {0, 0, 0};
    const double c15 = cos(15.0 * BANYAN_PI / 180), c30 = cos(30.0 * BANYAN_PI / 180);
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        if (b->parent < 0 || !b->attached) continue;
        ivy_near nr = ivy_nearest_any(iv, b->P);
        if ((uint32_t)nr.host == iv->n_given || v3_dot(nr.normal, face_n) < 0.906) continue;
        v3 d = v3_sub(b->P, iv->buds[b->parent].P);
        d = v3_sub(d, v3_scale(nr.normal, v3_dot(d, nr.normal)));
        double len = v3_len(d);
        if (!(len > 1e-9)) continue;
        double c = fabs(d.z) / len;
        a.length += len;
        if (c >= c15) a.within15 += len;
        if (c >= c30) a.within30 += len;
    }
    return a;
}

/* Leaf blades: the connected components of the leaf part's triangles.
 * Returns the share of the blades' area whose blade centre lies nearer
 * the ground than any host (0 when the plant has no ground or no leaf). */
static inline int32_t ivy_look_find(int32_t *up, int32_t x) {
    while (up[x] != x) x = up[x] = up[up[x]];
    return x;
}

static inline double ivy_look_ground_leaf_share(const banyan_ivy *iv, const banyan_mesh *m) {
    const float *part = banyan_mesh_attribute(m, "part");
    if (!part || !iv->p.ground) return 0.0;
    int32_t nv = (int32_t)m->vertex_count;
    int32_t *up = malloc(sizeof(int32_t) * (size_t)nv);
    double *acc = calloc((size_t)nv * 4, sizeof(double)); /* area, area-weighted centre */
    if (!up || !acc) {
        free(up);
        free(acc);
        return -1.0;
    }
    for (int32_t v = 0; v < nv; v++) up[v] = v;
    for (uint32_t t = 0; t + 2 < m->index_count; t += 3) {
        const uint32_t *I = m->indices + t;
        if (part[I[0]] != 1.0f) continue;
        int32_t a = ivy_look_find(up, (int32_t)I[0]);
        for (int k = 1; k < 3; k++) {
            int32_t b = ivy_look_find(up, (int32_t)I[k]);
            if (a != b) up[b] = a;
        }
    }
    for (uint32_t t = 0; t + 2 < m->index_count; t += 3) {
        const uint32_t *I = m->indices + t;
        if (part[I[0]] != 1.0f) continue;
        v3 p[3];
        for (int k = 0; k < 3; k++) p[k] = v3_make(m->positions[3 * I[k]], m->positions[3 * I[k] + 1], m->positions[3 * I[k] + 2]);
        double area = 0.5 * v3_len(v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0])));
        double *c = acc + 4 * (size_t)ivy_look_find(up, (int32_t)I[0]);
        c[0] += area;
        for (int k = 0; k < 3; k++) {
            c[1] += area * (&p[k].x)[0] / 3;
            c[2] += area * (&p[k].x)[1] / 3;
            c[3] += area * (&p[k].x)[2] / 3;
        }
    }
    double total = 0, ground = 0;
    for (int32_t v = 0; v < nv; v++) {
        const double *c = acc + 4 * (size_t)v;
        if (up[v] != v || !(c[0] > 0)) continue;
        v3 centre = v3_make(c[1] / c[0], c[2] / c[0], c[3] / c[0]);
        total += c[0];
        if ((uint32_t)ivy_nearest_any(iv, centre).host == iv->n_given) ground += c[0];
    }
    free(up);
    free(acc);
    return total > 0 ? ground / total : 0.0;
}

#endif
