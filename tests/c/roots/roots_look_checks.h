/* roots_look_checks.h - how a strangler fig's roots close round their
 * host, measured on a banyan_mesh:
 *   - sleeve gap fraction: rays start on a 2 cm grid on the four side faces
 *     of an axis-aligned host box (from the ground, or the box's foot if
 *     higher, to its top) and run outward along the face's normal; a ray
 *     that meets root surface within 0.5 m is covered. The gap is the share
 *     of rays that are not, over the whole side and over its lowest 0.5 m;
 *   - foot reach: the largest horizontal distance beyond the hosts'
 *     footprint (the XY box of their bounds, 0 inside) of a root vertex
 *     between the ground and 0.3 m above it, also as a fraction of the
 *     footprint's smaller width; and the sprawl limit of test_roots_look.c
 *     (95th percentile of that distance above the ground);
 *   - self-intersecting triangle pairs: two triangles that share no vertex
 *     (vertices welded by position: the uv seam's copies are one vertex)
 *     and intersect, found through a uniform grid of the triangles' bounds;
 *     and the pairs within a distance (sheets that nearly touch, which a
 *     tolerant intersection test counts);
 *   - the size of the mesh written as .glb with the writer's defaults.
 * Shared by test_roots_look_checks.c (the measures on meshes of known
 * answer), look_roots.c (the figures of the presets, and the acceptance
 * test of the closing foot) and test_roots_surface.c. */
#ifndef BANYAN_ROOTS_LOOK_CHECKS_H
#define BANYAN_ROOTS_LOOK_CHECKS_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "banyan.h"

/* ------------------------------------------------------------ the grid */

/* A uniform grid of triangle bounds (cell lists in one array). */
typedef struct rl_grid {
    double lo[3], cell;
    int32_t n[3];
    uint32_t *start; /* n0 n1 n2 + 1 */
    uint32_t *items; /* triangle indices */
} rl_grid;

static inline void rl_tri_box(const banyan_mesh *m, uint32_t t, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; k++) lo[k] = 1e300, hi[k] = -1e300;
    for (int j = 0; j < 3; j++) {
        const float *p = m->positions + 3 * (size_t)m->indices[3 * (size_t)t + j];
        for (int k = 0; k < 3; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
    }
}

static inline int32_t rl_cell_of(const rl_grid *g, int k, double x) {
    int32_t i = (int32_t)floor((x - g->lo[k]) / g->cell);
    return i < 0 ? 0 : (i >= g->n[k] ? g->n[k] - 1 : i);
}

/* Builds the grid with cells about `cell` metres (grown so that there are
 * at most about 8 M cells), each triangle listed in the cells its bounds,
 * grown by pad, meet. 0 on success. */
static inline int rl_grid_build(const banyan_mesh *m, double cell, double pad, rl_grid *g) {
    memset(g, 0, sizeof *g);
    uint32_t nt = m->index_count / 3;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            double x = m->positions[3 * (size_t)v + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    if (nt == 0) lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
    for (;;) {
        double cells = 1;
        for (int k = 0; k < 3; k++) cells *= floor((hi[k] - lo[k]) / cell) + 1;
        if (cells <= 8e6) break;
        cell *= 1.25;
    }
    g->cell = cell;
    size_t total = 1;
    for (int k = 0; k < 3; k++) {
        g->lo[k] = lo[k];
        g->n[k] = (int32_t)floor((hi[k] - lo[k]) / cell) + 1;
        total *= (size_t)g->n[k];
    }
    g->start = calloc(total + 1, sizeof *g->start);
    if (!g->start) return -1;
    size_t count = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t t = 0; t < nt; t++) {
            double a[3], b[3];
            rl_tri_box(m, t, a, b);
            for (int k = 0; k < 3; k++) a[k] -= pad, b[k] += pad;
            int32_t i0 = rl_cell_of(g, 0, a[0]), i1 = rl_cell_of(g, 0, b[0]);
            int32_t j0 = rl_cell_of(g, 1, a[1]), j1 = rl_cell_of(g, 1, b[1]);
            int32_t k0 = rl_cell_of(g, 2, a[2]), k1 = rl_cell_of(g, 2, b[2]);
            for (int32_t i = i0; i <= i1; i++)
                for (int32_t j = j0; j <= j1; j++)
                    for (int32_t k = k0; k <= k1; k++) {
                        size_t c = ((size_t)i * g->n[1] + j) * g->n[2] + k;
                        if (pass == 0)
                            g->start[c + 1]++, count++;
                        else
                            g->items[g->start[c]++] = t;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < total; c++) g->start[c + 1] += g->start[c];
            g->items = malloc(sizeof *g->items * (count ? count : 1));
            if (!g->items) {
                free(g->start);
                return -1;
            }
        } else {
            /* start[c] now holds the end of cell c: shift back */
            for (size_t c = total; c > 0; c--) g->start[c] = g->start[c - 1];
            g->start[0] = 0;
        }
    }
    return 0;
}

static inline void rl_grid_free(rl_grid *g) {
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}

/* --------------------------------------------------------- ray queries */

/* Segment o + t d, t in [0, tmax], against triangle (a, b, c): 1 on a hit. */
static inline int rl_seg_tri(const double o[3], const double d[3], double tmax, const double a[3],
                             const double b[3], const double c[3]) {
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabs(det) < 1e-18) return 0;
    double inv = 1.0 / det, s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0 || u > 1) return 0;
    double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0 || u + v > 1) return 0;
    double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    return t >= 0 && t <= tmax;
}

static inline void rl_corner(const banyan_mesh *m, uint32_t t, int j, double out[3]) {
    const float *p = m->positions + 3 * (size_t)m->indices[3 * (size_t)t + j];
    out[0] = p[0], out[1] = p[1], out[2] = p[2];
}

/* 1 when the axis-aligned segment from o, `len` metres along +-axis
 * (dir = +1 or -1), meets a triangle. stamp/mark: a mailbox per triangle. */
static inline int rl_axis_ray(const banyan_mesh *m, const rl_grid *g, const double o[3], int axis, int dir,
                              double len, uint32_t *mark, uint32_t stamp) {
    double d[3] = {0, 0, 0};
    d[axis] = dir;
    int32_t c[3];
    for (int k = 0; k < 3; k++) c[k] = rl_cell_of(g, k, o[k]);
    /* the ray's end may leave the grid: clamp its cell range */
    int32_t c_end = rl_cell_of(g, axis, o[axis] + dir * len);
    /* a point outside the grid across the other axes meets nothing */
    for (int k = 0; k < 3; k++)
        if (k != axis && (o[k] < g->lo[k] || o[k] > g->lo[k] + g->cell * g->n[k])) return 0;
    for (int32_t i = c[axis];; i += dir) {
        c[axis] = i;
        size_t cell = ((size_t)c[0] * g->n[1] + c[1]) * g->n[2] + c[2];
        for (uint32_t e = g->start[cell]; e < g->start[cell + 1]; e++) {
            uint32_t t = g->items[e];
            if (mark[t] == stamp) continue;
            mark[t] = stamp;
            double a[3], b[3], cc[3];
            rl_corner(m, t, 0, a), rl_corner(m, t, 1, b), rl_corner(m, t, 2, cc);
            if (rl_seg_tri(o, d, len, a, b, cc)) return 1;
        }
        if (i == c_end) break;
    }
    return 0;
}

/* ----------------------------------------------------- the sleeve gap */

typedef struct rl_sleeve {
    double gap, gap_foot; /* shares of rays not covered: whole side, lowest 0.5 m */
    int64_t rays, rays_foot;
} rl_sleeve;

/* Sleeve gap of the box [lo, hi] (world metres) standing from max(lo z,
 * ground_z). The grid g is of m (rl_grid_build). -1 on no memory. */
static inline int rl_sleeve_gap(const banyan_mesh *m, const rl_grid *g, const double lo[3], const double hi[3],
                                double ground_z, rl_sleeve *out) {
    const double step = 0.02, reach = 0.5, foot = 0.5, eps = 1e-4;
    memset(out, 0, sizeof *out);
    uint32_t nt = m->index_count / 3;
    uint32_t *mark = calloc(nt ? nt : 1, sizeof *mark);
    if (!mark) return -1;
    uint32_t stamp = 0;
    double z0 = lo[2] > ground_z ? lo[2] : ground_z;
    int64_t open = 0, open_foot = 0;
    for (int face = 0; face < 4; face++) {
        int axis = face >> 1, dir = face & 1 ? 1 : -1, across = 1 - axis;
        double w0 = lo[across], w1 = hi[across];
        int32_t nw = (int32_t)floor((w1 - w0) / step + 1e-9), nz = (int32_t)floor((hi[2] - z0) / step + 1e-9);
        for (int32_t iz = 0; iz < nz; iz++)
            for (int32_t iw = 0; iw < nw; iw++) {
                double o[3];
                o[axis] = (dir > 0 ? hi[axis] : lo[axis]) + dir * eps;
                o[across] = w0 + (iw + 0.5) * step;
                o[2] = z0 + (iz + 0.5) * step;
                int at_foot = o[2] < z0 + foot;
                for (int k = 0; k < 3; k++) o[k] -= m->origin[k]; /* the mesh's local frame */
                int hit = rl_axis_ray(m, g, o, axis, dir, reach, mark, ++stamp);
                out->rays++;
                out->rays_foot += at_foot;
                if (!hit) open++, open_foot += at_foot;
            }
    }
    free(mark);
    out->gap = out->rays ? (double)open / out->rays : 0;
    out->gap_foot = out->rays_foot ? (double)open_foot / out->rays_foot : 0;
    return 0;
}

/* -------------------------------------------------------- the foot reach */

typedef struct rl_reach {
    double reach;    /* m beyond the footprint, of vertices in [ground_z, ground_z + 0.3] */
    double width;    /* the footprint's smaller width, m */
    double fraction; /* reach / width */
} rl_reach;

/* Footprint: the XY box [lo, hi] (x, y) of the hosts. */
static inline void rl_foot_reach(const banyan_mesh *m, const double lo[2], const double hi[2], double ground_z,
                                 rl_reach *out) {
    double best = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *q = m->positions + 3 * (size_t)v;
        double x = q[0] + m->origin[0], y = q[1] + m->origin[1], z = q[2] + m->origin[2];
        if (z < ground_z || z > ground_z + 0.3) continue;
        double dx = x < lo[0] ? lo[0] - x : (x > hi[0] ? x - hi[0] : 0);
        double dy = y < lo[1] ? lo[1] - y : (y > hi[1] ? y - hi[1] : 0);
        double d = sqrt(dx * dx + dy * dy);
        if (d > best) best = d;
    }
    out->reach = best;
    double wx = hi[0] - lo[0], wy = hi[1] - lo[1];
    out->width = wx < wy ? wx : wy;
    out->fraction = out->width > 0 ? best / out->width : 0;
}

/* The sprawl limit of the roots' look (test_roots_look.c): the 95th
 * percentile of the horizontal distance beyond the footprint of the
 * vertices more than 1 cm above the ground, in metres; *diag the
 * footprint's diagonal. -1 on no memory. */
static inline int rl_dbl_cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static inline double rl_sprawl_p95(const banyan_mesh *m, const double lo[2], const double hi[2], double ground_z,
                                   double *diag) {
    *diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]));
    double *d = malloc(sizeof *d * (m->vertex_count ? m->vertex_count : 1));
    if (!d) return -1;
    uint32_t k = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *q = m->positions + 3 * (size_t)v;
        double x = q[0] + m->origin[0], y = q[1] + m->origin[1], z = q[2] + m->origin[2];
        if (z <= ground_z + 0.01) continue;
        double dx = x < lo[0] ? lo[0] - x : (x > hi[0] ? x - hi[0] : 0);
        double dy = y < lo[1] ? lo[1] - y : (y > hi[1] ? y - hi[1] : 0);
        d[k++] = sqrt(dx * dx + dy * dy);
    }
    qsort(d, k, sizeof *d, rl_dbl_cmp);
    double p95 = k ? d[(size_t)(0.95 * (k - 1))] : 0;
    free(d);
    return p95;
}

/* ------------------------------------------ self-intersecting pairs */

/* Welded vertex ids: vertices at the same position get the lowest index
 * among them. Returns NULL on no memory. */
static inline int rl_pos_cmp_m(const float *a, const float *b) {
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}
static const float *rl_sort_pos; /* qsort has no context: set only while sorting */
static inline int rl_idx_cmp(const void *pa, const void *pb) {
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    int c = rl_pos_cmp_m(rl_sort_pos + 3 * (size_t)a, rl_sort_pos + 3 * (size_t)b);
    return c ? c : (a < b ? -1 : a > b);
}
static inline uint32_t *rl_weld(const banyan_mesh *m) {
    uint32_t nv = m->vertex_count;
    uint32_t *ord = malloc(sizeof *ord * (nv ? nv : 1)), *id = malloc(sizeof *id * (nv ? nv : 1));
    if (!ord || !id) {
        free(ord);
        free(id);
        return NULL;
    }
    for (uint32_t i = 0; i < nv; i++) ord[i] = i;
    rl_sort_pos = m->positions;
    qsort(ord, nv, sizeof *ord, rl_idx_cmp);
    rl_sort_pos = NULL;
    for (uint32_t i = 0; i < nv; i++)
        id[ord[i]] = i > 0 && !rl_pos_cmp_m(m->positions + 3 * (size_t)ord[i], m->positions + 3 * (size_t)ord[i - 1])
                         ? id[ord[i - 1]]
                         : ord[i];
    free(ord);
    return id;
}

/* Two triangles intersect: an edge of one crosses the other. */
static inline int rl_tri_tri(double A[3][3], double B[3][3]) {
    for (int s = 0; s < 2; s++) {
        double(*P)[3] = s ? B : A, (*Q)[3] = s ? A : B;
        for (int e = 0; e < 3; e++) {
            const double *a = P[e], *b = P[(e + 1) % 3];
            double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            if (rl_seg_tri(a, d, 1.0, Q[0], Q[1], Q[2])) return 1;
        }
    }
    return 0;
}

static inline double rl_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Squared distance from p to triangle (a, b, c) (Ericson, Real-Time
 * Collision Detection 5.1.5). */
static inline double rl_pt_tri2(const double p[3], const double a[3], const double b[3], const double c[3]) {
    double ab[3], ac[3], ap[3], q[3];
    for (int k = 0; k < 3; k++) ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k];
    double d1 = rl_dot(ab, ap), d2 = rl_dot(ac, ap), v, w;
    if (d1 <= 0 && d2 <= 0) {
        for (int k = 0; k < 3; k++) q[k] = a[k];
        goto out;
    }
    double bp[3], cp[3];
    for (int k = 0; k < 3; k++) bp[k] = p[k] - b[k], cp[k] = p[k] - c[k];
    double d3 = rl_dot(ab, bp), d4 = rl_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        for (int k = 0; k < 3; k++) q[k] = b[k];
        goto out;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        v = d1 / (d1 - d3);
        for (int k = 0; k < 3; k++) q[k] = a[k] + v * ab[k];
        goto out;
    }
    double d5 = rl_dot(ab, cp), d6 = rl_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        for (int k = 0; k < 3; k++) q[k] = c[k];
        goto out;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        w = d2 / (d2 - d6);
        for (int k = 0; k < 3; k++) q[k] = a[k] + w * ac[k];
        goto out;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int k = 0; k < 3; k++) q[k] = b[k] + w * (c[k] - b[k]);
        goto out;
    }
    {
        double den = 1.0 / (va + vb + vc);
        v = vb * den, w = vc * den;
        for (int k = 0; k < 3; k++) q[k] = a[k] + ab[k] * v + ac[k] * w;
    }
out:;
    double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
    return rl_dot(d, d);
}

static inline double rl_clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }

/* Squared distance between segments p1-q1 and p2-q2 (Ericson 5.1.9). */
static inline double rl_seg_seg2(const double p1[3], const double q1[3], const double p2[3], const double q2[3]) {
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) d1[k] = q1[k] - p1[k], d2[k] = q2[k] - p2[k], r[k] = p1[k] - p2[k];
    double a = rl_dot(d1, d1), e = rl_dot(d2, d2), f = rl_dot(d2, r), s, t;
    if (a <= 1e-30 && e <= 1e-30) return rl_dot(r, r);
    if (a <= 1e-30) {
        s = 0, t = rl_clamp01(f / e);
    } else {
        double c = rl_dot(d1, r);
        if (e <= 1e-30) {
            t = 0, s = rl_clamp01(-c / a);
        } else {
            double b = rl_dot(d1, d2), den = a * e - b * b;
            s = den > 0 ? rl_clamp01((b * f - c * e) / den) : 0;
            t = (b * s + f) / e;
            if (t < 0)
                t = 0, s = rl_clamp01(-c / a);
            else if (t > 1)
                t = 1, s = rl_clamp01((b - c) / a);
        }
    }
    double x[3];
    for (int k = 0; k < 3; k++) x[k] = p1[k] + d1[k] * s - (p2[k] + d2[k] * t);
    return rl_dot(x, x);
}

/* Squared distance between two triangles that do not intersect. */
static inline double rl_tri_tri2(double A[3][3], double B[3][3]) {
    double best = 1e300;
    for (int i = 0; i < 3; i++) {
        double d = rl_pt_tri2(A[i], B[0], B[1], B[2]);
        if (d < best) best = d;
        d = rl_pt_tri2(B[i], A[0], A[1], A[2]);
        if (d < best) best = d;
        for (int j = 0; j < 3; j++) {
            d = rl_seg_seg2(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3]);
            if (d < best) best = d;
        }
    }
    return best;
}

/* The number of triangle pairs sharing no (welded) vertex that intersect
 * or, with tol > 0, come within tol metres of each other (two sheets
 * almost touching); -1 on no memory. With at_z non-NULL, also the heights
 * of the pairs' first triangle centres (up to cap of them). */
static inline int64_t rl_close_pairs(const banyan_mesh *m, double tol, double *at_z, int64_t cap) {
    uint32_t nt = m->index_count / 3;
    if (nt < 2) return 0;
    /* cells about twice the mean edge */
    double el = 0;
    for (uint32_t t = 0; t < nt; t++) {
        double a[3], b[3];
        rl_corner(m, t, 0, a), rl_corner(m, t, 1, b);
        el += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    el /= nt;
    rl_grid g;
    if (rl_grid_build(m, el > 0 ? 2 * el : 1, 0.5 * tol, &g)) return -1;
    uint32_t *id = rl_weld(m);
    if (!id) {
        rl_grid_free(&g);
        return -1;
    }
    int64_t count = 0;
    size_t cells = (size_t)g.n[0] * g.n[1] * g.n[2];
    for (size_t c = 0; c < cells; c++) {
        int32_t ci = (int32_t)(c / ((size_t)g.n[1] * g.n[2])), cj = (int32_t)(c / g.n[2] % g.n[1]),
                ck = (int32_t)(c % g.n[2]);
        for (uint32_t e = g.start[c]; e < g.start[c + 1]; e++)
            for (uint32_t f = e + 1; f < g.start[c + 1]; f++) {
                uint32_t s = g.items[e], t = g.items[f];
                double sl[3], sh[3], tl[3], th[3];
                rl_tri_box(m, s, sl, sh);
                rl_tri_box(m, t, tl, th);
                int apart = 0;
                for (int k = 0; k < 3; k++) apart |= sl[k] > th[k] + tol || tl[k] > sh[k] + tol;
                if (apart) continue;
                /* the pair is counted in the cell of the low corner of its boxes'
                 * overlap (the boxes grown by tol / 2) */
                double ol[3];
                for (int k = 0; k < 3; k++) ol[k] = (sl[k] > tl[k] ? sl[k] : tl[k]) - 0.5 * tol;
                if (rl_cell_of(&g, 0, ol[0]) != ci || rl_cell_of(&g, 1, ol[1]) != cj || rl_cell_of(&g, 2, ol[2]) != ck)
                    continue;
                const uint32_t *S = m->indices + 3 * (size_t)s, *T = m->indices + 3 * (size_t)t;
                int share = 0;
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) share |= id[S[i]] == id[T[j]];
                if (share) continue;
                double A[3][3], B[3][3];
                for (int j = 0; j < 3; j++) rl_corner(m, s, j, A[j]), rl_corner(m, t, j, B[j]);
                if (rl_tri_tri(A, B) || (tol > 0 && rl_tri_tri2(A, B) < tol * tol)) {
                    if (at_z && count < cap)
                        at_z[count] = (A[0][2] + A[1][2] + A[2][2]) / 3 + m->origin[2];
                    count++;
                }
            }
    }
    free(id);
    rl_grid_free(&g);
    return count;
}

/* Intersecting triangle pairs sharing no (welded) vertex. */
static inline int64_t rl_self_intersections(const banyan_mesh *m, double *at_z, int64_t cap) {
    return rl_close_pairs(m, 0.0, at_z, cap);
}

/* ------------------------------------------------------ the .glb size */

/* Bytes of m written as .glb with banyan_gltf_write_ex's defaults (opt
 * NULL) or opt, to a temporary file in dir that is removed again; -1 on
 * failure (err says why). */
static inline long long rl_glb_size(const banyan_mesh *m, const char *dir, const banyan_gltf_options *opt,
                                    banyan_error *err) {
    char path[4096];
    snprintf(path, sizeof path, "%s/rl_size_%ld.glb", dir ? dir : "/tmp", (long)getpid());
    const banyan_mesh *ms[1] = {m};
    if (banyan_gltf_write_ex(path, ms, NULL, 1, opt, err) != BANYAN_OK) return -1;
    struct stat st;
    long long size = stat(path, &st) == 0 ? (long long)st.st_size : -1;
    remove(path);
    return size;
}

#endif
