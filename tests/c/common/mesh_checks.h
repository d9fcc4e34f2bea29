/* mesh_checks.h - mesh invariants shared by the tests. */
#ifndef BANYAN_MESH_CHECKS_H
#define BANYAN_MESH_CHECKS_H

#include <math.h>
#include <stdlib.h>

#include "banyan.h"

/* Triangles (with area above min_cross) whose counter-clockwise face
 * normal points against their first vertex's normal. */
static inline int mc_wound_against_normals(const banyan_mesh *m, double min_cross) {
    int bad = 0;
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        const uint32_t *I = m->indices + 3 * (size_t)t;
        const float *a = m->positions + 3 * (size_t)I[0], *b = m->positions + 3 * (size_t)I[1],
                    *c = m->positions + 3 * (size_t)I[2], *n = m->normals + 3 * (size_t)I[0];
        double u[3], w[3];
        for (int k = 0; k < 3; k++) u[k] = (double)b[k] - a[k], w[k] = (double)c[k] - a[k];
        double fn[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        double len = sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
        if (len > min_cross && fn[0] * n[0] + fn[1] * n[1] + fn[2] * n[2] <= 0) bad++;
    }
    return bad;
}

/* Connected pieces of the mesh's skeleton graph (1: all joined). */
static inline int mc_skeleton_pieces(const banyan_mesh *m) {
    uint32_t np = m->skel_point_count;
    uint32_t *parent = (uint32_t *)malloc(sizeof(uint32_t) * (np ? np : 1));
    for (uint32_t i = 0; i < np; i++) parent[i] = i;
    for (uint32_t e = 0; e < m->skel_edge_count; e++) {
        uint32_t a = m->skel_edges[2 * e], b = m->skel_edges[2 * e + 1];
        while (parent[a] != a) a = parent[a] = parent[parent[a]];
        while (parent[b] != b) b = parent[b] = parent[parent[b]];
        parent[a] = b;
    }
    int pieces = 0;
    for (uint32_t i = 0; i < np; i++) pieces += parent[i] == i;
    free(parent);
    return pieces;
}

#endif
