/* mesh_checks.h - mesh invariants shared by the tests. */
#ifndef BANYAN_MESH_CHECKS_H
#define BANYAN_MESH_CHECKS_H

#include <stdlib.h>

#include "banyan.h"
#include "base/vec.h"

static inline v3 mc_pos(const banyan_mesh *m, uint32_t v) {
    return v3_make(m->positions[3 * (size_t)v], m->positions[3 * (size_t)v + 1], m->positions[3 * (size_t)v + 2]);
}

/* Triangles (with area above min_cross) whose counter-clockwise face
 * normal points against their first vertex's normal. */
static inline int mc_wound_against_normals(const banyan_mesh *m, double min_cross) {
    int bad = 0;
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        const uint32_t *I = m->indices + 3 * (size_t)t;
        v3 a = mc_pos(m, I[0]), b = mc_pos(m, I[1]), c = mc_pos(m, I[2]);
        v3 fn = v3_cross(v3_sub(b, a), v3_sub(c, a));
        v3 vn = v3_make(m->normals[3 * (size_t)I[0]], m->normals[3 * (size_t)I[0] + 1], m->normals[3 * (size_t)I[0] + 2]);
        if (v3_len(fn) > min_cross && v3_dot(fn, vn) <= 0) bad++;
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
