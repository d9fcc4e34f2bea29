/* roots_host_meshes.h - triangle meshes built in code for the tests and
 * benchmarks of roots on mesh hosts: a UV sphere, a closed cylinder
 * (column or finely tessellated trunk), an open quad wall and a
 * self-intersecting two-shell mesh. Counter-clockwise seen from outside. */
#ifndef BANYAN_ROOTS_HOST_MESHES_H
#define BANYAN_ROOTS_HOST_MESHES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "core/vec.h"

typedef struct tmesh {
    float *pos;
    uint32_t *idx;
    uint32_t nv, nt;
} tmesh;

static inline void tm_alloc(tmesh *m, uint32_t nv, uint32_t nt) {
    m->pos = malloc(sizeof(float) * 3 * nv);
    m->idx = malloc(sizeof(uint32_t) * 3 * nt);
    m->nv = m->nt = 0;
}
static inline uint32_t tm_v(tmesh *m, double x, double y, double z) {
    m->pos[3 * m->nv] = (float)x;
    m->pos[3 * m->nv + 1] = (float)y;
    m->pos[3 * m->nv + 2] = (float)z;
    return m->nv++;
}
static inline void tm_t(tmesh *m, uint32_t a, uint32_t b, uint32_t c) {
    m->idx[3 * m->nt] = a;
    m->idx[3 * m->nt + 1] = b;
    m->idx[3 * m->nt + 2] = c;
    m->nt++;
}
static inline void tm_free(tmesh *m) {
    free(m->pos);
    free(m->idx);
}

/* UV sphere of radius R round (cx, cy, cz), counter-clockwise outside,
 * appended to m (room for (seg * (rings - 1) + 2) vertices and 2 seg (rings
 * - 1) triangles). */
static inline void tm_sphere(tmesh *m, double cx, double cy, double cz, double R, int seg, int rings) {
    uint32_t top = tm_v(m, cx, cy, cz + R), first = m->nv;
    for (int i = 1; i < rings; i++) {
        double th = BANYAN_PI * i / rings;
        for (int j = 0; j < seg; j++) {
            double ph = 2.0 * BANYAN_PI * j / seg;
            tm_v(m, cx + R * sin(th) * cos(ph), cy + R * sin(th) * sin(ph), cz + R * cos(th));
        }
    }
    uint32_t bottom = tm_v(m, cx, cy, cz - R);
    for (int j = 0; j < seg; j++) {
        uint32_t j1 = (uint32_t)((j + 1) % seg);
        tm_t(m, top, first + (uint32_t)j, first + j1);
        for (int i = 0; i + 2 < rings; i++) {
            uint32_t a = first + (uint32_t)(i * seg + j), b = first + (uint32_t)(i * seg) + j1;
            uint32_t c = a + (uint32_t)seg, d = b + (uint32_t)seg;
            tm_t(m, a, c, d);
            tm_t(m, a, d, b);
        }
        uint32_t last = first + (uint32_t)((rings - 2) * seg);
        tm_t(m, bottom, last + j1, last + (uint32_t)j);
    }
}

static inline tmesh uv_sphere(double R, double cz, int seg, int rings) {
    tmesh m;
    tm_alloc(&m, (uint32_t)(seg * (rings - 1) + 2), (uint32_t)(2 * seg * (rings - 1)));
    tm_sphere(&m, 0, 0, cz, R, seg, rings);
    return m;
}

/* Closed cylinder round the z axis from z = 0 to h, `sides` sides, the
 * side split into `stacks` rows (a finely tessellated trunk for the
 * benchmark uses the same code). */
static inline tmesh cylinder(double R, double h, int sides, int stacks) {
    tmesh m;
    tm_alloc(&m, (uint32_t)(sides * (stacks + 1) + 2), (uint32_t)(2 * sides * stacks + 2 * sides));
    for (int i = 0; i <= stacks; i++)
        for (int j = 0; j < sides; j++) {
            double ph = 2.0 * BANYAN_PI * j / sides;
            tm_v(&m, R * cos(ph), R * sin(ph), h * i / stacks);
        }
    uint32_t bc = tm_v(&m, 0, 0, 0), tc = tm_v(&m, 0, 0, h), S = (uint32_t)sides;
    for (int j = 0; j < sides; j++) {
        uint32_t j1 = (uint32_t)((j + 1) % sides);
        for (int i = 0; i < stacks; i++) {
            uint32_t a = (uint32_t)i * S + (uint32_t)j, b = (uint32_t)i * S + j1;
            tm_t(&m, a, b, b + S);
            tm_t(&m, a, b + S, a + S);
        }
        tm_t(&m, bc, j1, (uint32_t)j);
        tm_t(&m, tc, (uint32_t)stacks * S + (uint32_t)j, (uint32_t)stacks * S + j1);
    }
    return m;
}

/* An open vertical quad in the plane y = 0: x in [-w/2, w/2], z in [0, h]. */
static inline tmesh quad_wall(double w, double h) {
    tmesh m;
    tm_alloc(&m, 4, 2);
    tm_v(&m, -0.5 * w, 0, 0);
    tm_v(&m, 0.5 * w, 0, 0);
    tm_v(&m, 0.5 * w, 0, h);
    tm_v(&m, -0.5 * w, 0, h);
    tm_t(&m, 0, 1, 2);
    tm_t(&m, 0, 2, 3);
    return m;
}

/* Two spheres that cut through each other, in one mesh: closed, two
 * shells, self-intersecting (what Suzanne's head and eyes do). */
static inline tmesh two_shells(void) {
    tmesh m;
    int seg = 24, rings = 12;
    uint32_t nv = (uint32_t)(seg * (rings - 1) + 2), nt = (uint32_t)(2 * seg * (rings - 1));
    tm_alloc(&m, 2 * nv, 2 * nt);
    tm_sphere(&m, -0.35, 0, 0.9, 0.7, seg, rings);
    tm_sphere(&m, 0.45, 0.1, 1.2, 0.55, seg, rings);
    return m;
}

static inline banyan_host_mesh host_of(const tmesh *t, double x, double y, double z, int32_t closed) {
    banyan_host_mesh h;
    memset(&h, 0, sizeof h);
    h.positions = t->pos;
    h.indices = t->idx;
    h.vertex_count = t->nv;
    h.triangle_count = t->nt;
    h.transform[0] = h.transform[5] = h.transform[10] = 1.0;
    h.transform[3] = x;
    h.transform[7] = y;
    h.transform[11] = z;
    h.closed = closed;
    return h;
}

#endif
