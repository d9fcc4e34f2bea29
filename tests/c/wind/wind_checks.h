/* wind_checks.h - invariants of the wind and birth attributes (banyan.h,
 * BANYAN_ATTR_WIND_*), shared by every generator's wind test.
 *
 *   wind_attrs_check     all eight attributes present, finite, in range
 *   wind_pivot_worst     farthest any vertex's pivot lies from the mesh's
 *                        own skeleton (its edges as segments)
 *   wind_level_stiffness mean wood stiffness per level never rises with
 *                        the level (stiffness grows toward the base)
 */
#ifndef BANYAN_WIND_CHECKS_H
#define BANYAN_WIND_CHECKS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"

static const char *const wind_attr_names[8] = {
    BANYAN_ATTR_WIND_PIVOT_X, BANYAN_ATTR_WIND_PIVOT_Y, BANYAN_ATTR_WIND_PIVOT_Z, BANYAN_ATTR_WIND_LEVEL,
    BANYAN_ATTR_WIND_STIFFNESS, BANYAN_ATTR_WIND_PHASE, BANYAN_ATTR_WIND_FLUTTER, BANYAN_ATTR_BIRTH};

/* 1 when every attribute is there and sane; else 0 with why[] filled. */
static inline int wind_attrs_check(const banyan_mesh *m, char *why, size_t why_len) {
    for (int k = 0; k < 8; k++) {
        const float *a = banyan_mesh_attribute(m, wind_attr_names[k]);
        if (!a) {
            snprintf(why, why_len, "attribute %s missing", wind_attr_names[k]);
            return 0;
        }
        for (uint32_t i = 0; i < m->vertex_count; i++) {
            float v = a[i];
            int bad = !isfinite(v);
            if (k == 3) bad |= v < 0 || v != floorf(v) || v > 64;
            if (k >= 4) bad |= v < 0 || v > 1;
            if (k == 5) bad |= v >= 1;
            if (bad) {
                snprintf(why, why_len, "%s[%u] = %g is outside its range", wind_attr_names[k], i, (double)v);
                return 0;
            }
        }
    }
    return 1;
}

typedef struct wind_grid {
    double lo[3], h;
    int n[3];
    uint32_t *start, *items; /* CSR: cell c holds items[start[c] .. start[c+1]) (edge numbers) */
} wind_grid;

static inline long wind_cell(const wind_grid *g, int i, int j, int k) {
    return ((long)k * g->n[1] + j) * g->n[0] + i;
}

static inline int wind_ci(const wind_grid *g, int axis, double x) {
    int c = (int)floor((x - g->lo[axis]) / g->h);
    return c < 0 ? 0 : c >= g->n[axis] ? g->n[axis] - 1 : c;
}

static inline double wind_seg_dist(const float *a, const float *b, const double p[3]) {
    double ab[3], ap[3], t = 0, l2 = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = (double)b[k] - a[k];
        ap[k] = p[k] - a[k];
        t += ab[k] * ap[k];
        l2 += ab[k] * ab[k];
    }
    t = l2 > 0 ? t / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
        double d = ap[k] - t * ab[k];
        d2 += d * d;
    }
    return sqrt(d2);
}

/* The largest distance from a vertex's pivot to the nearest skeleton edge,
 * searched within `reach` metres (a pivot farther than that counts as
 * `reach`); -1 when the mesh has no skeleton or no pivots. *worst_vertex
 * (may be NULL) gets the vertex. Segments are bucketed in a grid of
 * cells `reach` wide, so the search is linear in the mesh. */
static inline double wind_pivot_worst(const banyan_mesh *m, double reach, uint32_t *worst_vertex) {
    const float *px = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X);
    const float *py = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Y);
    const float *pz = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Z);
    if (!px || !py || !pz || !m->skel_edge_count || !m->skel_points) return -1;
    wind_grid g = {{0, 0, 0}, 0, {0, 0, 0}, NULL, NULL};
    double hi[3];
    for (int k = 0; k < 3; k++) g.lo[k] = 1e300, hi[k] = -1e300;
    for (uint32_t i = 0; i < m->skel_point_count; i++)
        for (int k = 0; k < 3; k++) {
            double v = m->skel_points[3 * (size_t)i + k];
            g.lo[k] = v < g.lo[k] ? v : g.lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    g.h = reach;
    long cells = 1;
    for (int k = 0; k < 3; k++) {
        g.lo[k] -= reach;
        g.n[k] = (int)((hi[k] + reach - g.lo[k]) / g.h) + 1;
        if (g.n[k] > 2048) { /* keep the grid small: coarser cells on huge meshes */
            g.h = (hi[k] + reach - g.lo[k]) / 2047.0;
        }
    }
    for (int k = 0; k < 3; k++) g.n[k] = (int)((hi[k] + reach - g.lo[k]) / g.h) + 1, cells *= g.n[k];
    if (cells > 64L * 1024 * 1024) return -1;
    g.start = calloc((size_t)cells + 1, sizeof(uint32_t));
    if (!g.start) return -1;
    /* two passes: count, then fill (each edge in every cell its bounds touch) */
    uint64_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t e = 0; e < m->skel_edge_count; e++) {
            const float *a = m->skel_points + 3 * (size_t)m->skel_edges[2 * (size_t)e];
            const float *b = m->skel_points + 3 * (size_t)m->skel_edges[2 * (size_t)e + 1];
            int c0[3], c1[3];
            for (int k = 0; k < 3; k++) {
                double lo = a[k] < b[k] ? a[k] : b[k], up = a[k] < b[k] ? b[k] : a[k];
                c0[k] = wind_ci(&g, k, lo);
                c1[k] = wind_ci(&g, k, up);
            }
            for (int k = c0[2]; k <= c1[2]; k++)
                for (int j = c0[1]; j <= c1[1]; j++)
                    for (int i = c0[0]; i <= c1[0]; i++) {
                        long c = wind_cell(&g, i, j, k);
                        if (pass == 0) g.start[c + 1]++, total++;
                        else g.items[g.start[c]++] = e;
                    }
        }
        if (pass == 0) {
            for (long c = 0; c < cells; c++) g.start[c + 1] += g.start[c];
            g.items = malloc(sizeof(uint32_t) * (total ? total : 1));
            if (!g.items) {
                free(g.start);
                return -1;
            }
        } else {
            for (long c = cells; c > 0; c--) g.start[c] = g.start[c - 1];
            g.start[0] = 0;
        }
    }
    double worst = 0;
    uint32_t wv = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        double p[3] = {px[v], py[v], pz[v]}, best = reach;
        int ci[3];
        for (int k = 0; k < 3; k++) ci[k] = wind_ci(&g, k, p[k]);
        for (int dk = -1; dk <= 1; dk++)
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    int i = ci[0] + di, j = ci[1] + dj, k = ci[2] + dk;
                    if (i < 0 || j < 0 || k < 0 || i >= g.n[0] || j >= g.n[1] || k >= g.n[2]) continue;
                    long c = wind_cell(&g, i, j, k);
                    for (uint32_t s = g.start[c]; s < g.start[c + 1]; s++) {
                        uint32_t e = g.items[s];
                        double d = wind_seg_dist(m->skel_points + 3 * (size_t)m->skel_edges[2 * (size_t)e],
                                                 m->skel_points + 3 * (size_t)m->skel_edges[2 * (size_t)e + 1], p);
                        best = d < best ? d : best;
                    }
                }
        if (best > worst) worst = best, wv = v;
    }
    free(g.start);
    free(g.items);
    if (worst_vertex) *worst_vertex = wv;
    return worst;
}

/* Mean stiffness of wood (flutter 0) per level; returns the first level
 * whose mean exceeds the level above it (toward the base) by more than
 * tol, or -1 when stiffness never rises toward the tips. */
static inline int wind_level_stiffness(const banyan_mesh *m, double tol, double means_out[16]) {
    const float *lv = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_LEVEL);
    const float *st = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_STIFFNESS);
    const float *fl = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_FLUTTER);
    double sum[16] = {0}, cnt[16] = {0};
    if (!lv || !st || !fl) return 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        if (fl[v] > 0) continue;
        int l = (int)lv[v];
        l = l < 0 ? 0 : l > 15 ? 15 : l;
        sum[l] += st[v];
        cnt[l] += 1;
    }
    double prev = 2;
    int bad = -1;
    for (int l = 0; l < 16; l++) {
        double mean = cnt[l] ? sum[l] / cnt[l] : -1;
        if (means_out) means_out[l] = mean;
        if (mean < 0) continue;
        if (bad < 0 && mean > prev + tol) bad = l;
        prev = mean;
    }
    return bad;
}

#endif
