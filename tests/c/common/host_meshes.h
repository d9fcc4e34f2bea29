/* host_meshes.h - the test hosts, built in code: a UV sphere,
 * an n-sided closed cylinder, an open quad wall, and a two-shell mesh of
 * overlapping spheres that stands in for Suzanne (closed, self-
 * intersecting). Shared by the host, roots and ivy tests and the
 * benchmarks. Positions are object space; tm_host wraps one as a
 * banyan_host_mesh with a translation. */
#ifndef BANYAN_TEST_HOST_MESHES_H
#define BANYAN_TEST_HOST_MESHES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"

typedef struct tm_mesh {
    float *pos;      /* 3 * nv */
    uint32_t *idx;   /* 3 * nt */
    uint32_t nv, nt;
    uint32_t cap_v, cap_t;
} tm_mesh;

static inline void tm_free(tm_mesh *m) {
    free(m->pos);
    free(m->idx);
    memset(m, 0, sizeof *m);
}

static inline void tm_reserve(tm_mesh *m, uint32_t nv, uint32_t nt) {
    if (m->nv + nv > m->cap_v) {
        m->cap_v = (m->nv + nv) * 2;
        m->pos = (float *)realloc(m->pos, sizeof(float) * 3 * m->cap_v);
        if (!m->pos) abort();
    }
    if (m->nt + nt > m->cap_t) {
        m->cap_t = (m->nt + nt) * 2;
        m->idx = (uint32_t *)realloc(m->idx, sizeof(uint32_t) * 3 * m->cap_t);
        if (!m->idx) abort();
    }
}

static inline uint32_t tm_vert(tm_mesh *m, double x, double y, double z) {
    tm_reserve(m, 1, 0);
    float *p = m->pos + 3 * (size_t)m->nv;
    p[0] = (float)x, p[1] = (float)y, p[2] = (float)z;
    return m->nv++;
}

static inline void tm_tri(tm_mesh *m, uint32_t a, uint32_t b, uint32_t c) {
    tm_reserve(m, 0, 1);
    uint32_t *t = m->idx + 3 * (size_t)m->nt++;
    t[0] = a, t[1] = b, t[2] = c;
}

/* UV sphere of radius r about c: `seg` around, `rings` from pole to pole,
 * outward winding, watertight (poles shared). */
static inline void tm_uv_sphere(tm_mesh *m, double cx, double cy, double cz, double r, int seg, int rings) {
    const double PI = 3.14159265358979323846;
    uint32_t top = tm_vert(m, cx, cy, cz + r), first = m->nv;
    for (int j = 1; j < rings; j++) {
        double th = PI * j / rings;
        for (int i = 0; i < seg; i++) {
            double ph = 2 * PI * i / seg;
            tm_vert(m, cx + r * sin(th) * cos(ph), cy + r * sin(th) * sin(ph), cz + r * cos(th));
        }
    }
    uint32_t bottom = tm_vert(m, cx, cy, cz - r);
    for (int i = 0; i < seg; i++) {
        int i1 = (i + 1) % seg;
        tm_tri(m, top, first + i, first + i1);
        for (int j = 0; j < rings - 2; j++) {
            uint32_t a = first + j * seg + i, b = first + j * seg + i1;
            uint32_t c = a + seg, d = b + seg;
            tm_tri(m, a, c, d);
            tm_tri(m, a, d, b);
        }
        uint32_t last = first + (rings - 2) * seg;
        tm_tri(m, last + i, bottom, last + i1);
    }
}

/* Closed cylinder about the z axis through (cx, cy): radius r, from z0 to
 * z0 + h, `sides` around, `stacks` rows along the side, capped by fans. */
static inline void tm_cylinder(tm_mesh *m, double cx, double cy, double z0, double r, double h, int sides,
                               int stacks) {
    const double PI = 3.14159265358979323846;
    uint32_t base = m->nv;
    for (int j = 0; j <= stacks; j++)
        for (int i = 0; i < sides; i++) {
            double a = 2 * PI * i / sides;
            tm_vert(m, cx + r * cos(a), cy + r * sin(a), z0 + h * j / stacks);
        }
    for (int j = 0; j < stacks; j++)
        for (int i = 0; i < sides; i++) {
            uint32_t a = base + j * sides + i, b = base + j * sides + (i + 1) % sides;
            tm_tri(m, a, b, b + sides);
            tm_tri(m, a, b + sides, a + sides);
        }
    uint32_t cb = tm_vert(m, cx, cy, z0), ct = tm_vert(m, cx, cy, z0 + h);
    uint32_t topring = base + stacks * sides;
    for (int i = 0; i < sides; i++) {
        int i1 = (i + 1) % sides;
        tm_tri(m, cb, base + i1, base + i);
        tm_tri(m, ct, topring + i, topring + i1);
    }
}

/* An open, two-triangle quad wall in the plane y = y0, x in [x0, x1], z in
 * [z0, z1], facing -y. */
static inline void tm_quad(tm_mesh *m, double x0, double x1, double y0, double z0, double z1) {
    uint32_t a = tm_vert(m, x0, y0, z0), b = tm_vert(m, x1, y0, z0);
    uint32_t c = tm_vert(m, x1, y0, z1), d = tm_vert(m, x0, y0, z1);
    tm_tri(m, a, b, c);
    tm_tri(m, a, c, d);
}

/* A closed box as 12 triangles (centre c, half extents h), outward. */
static inline void tm_box(tm_mesh *m, double cx, double cy, double cz, double hx, double hy, double hz) {
    uint32_t v[8];
    for (int k = 0; k < 8; k++)
        v[k] = tm_vert(m, cx + (k & 1 ? hx : -hx), cy + (k & 2 ? hy : -hy), cz + (k & 4 ? hz : -hz));
    static const int f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int i = 0; i < 6; i++) {
        tm_tri(m, v[f[i][0]], v[f[i][1]], v[f[i][2]]);
        tm_tri(m, v[f[i][0]], v[f[i][2]], v[f[i][3]]);
    }
}

/* Suzanne's stand-in: a head sphere with two eye spheres sunk into it, all
 * one mesh (three shells that intersect), resting on z = 0. */
static inline void tm_two_shell_head(tm_mesh *m, double r) {
    tm_uv_sphere(m, 0, 0, r, r, 32, 16);
    tm_uv_sphere(m, -0.4 * r, -0.8 * r, 1.25 * r, 0.35 * r, 16, 8);
    tm_uv_sphere(m, 0.4 * r, -0.8 * r, 1.25 * r, 0.35 * r, 16, 8);
}

/* The mesh as a host, translated by (tx, ty, tz). */
static inline banyan_host_mesh tm_host(const tm_mesh *m, double tx, double ty, double tz, int32_t closed) {
    banyan_host_mesh h;
    memset(&h, 0, sizeof h);
    h.positions = m->pos;
    h.indices = m->idx;
    h.vertex_count = m->nv;
    h.triangle_count = m->nt;
    h.transform[0] = h.transform[5] = h.transform[10] = 1.0;
    h.transform[3] = tx, h.transform[7] = ty, h.transform[11] = tz;
    h.closed = closed;
    return h;
}

#endif
