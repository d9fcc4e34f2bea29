/* canopy_checks.h - how much a crown in leaf hides the sky, measured on a
 * banyan_mesh the way a viewer sees it: leaves count where their texture's
 * alpha is >= 0.5 (the materials' MASK cutoff), wood always.
 *   - outline: the convex hull, in plan, of the leaf vertices;
 *   - alpha-weighted leaf area index (LAI): one-sided leaf area whose texels
 *     pass the cutoff, over the outline's area;
 *   - gap fraction from below: the share of vertical rays, on a square grid
 *     inside the outline, from `eye` metres above the lowest vertex upwards,
 *     that meet neither wood nor a passing leaf texel;
 *   - the share of that leaf area below half the height.
 * Shared by test_canopy_checks.c (the measures on meshes of known answer)
 * and look_keyaki_canopy.c (the figures of the presets). */
#ifndef BANYAN_CANOPY_CHECKS_H
#define BANYAN_CANOPY_CHECKS_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"

/* A material's alpha plane: width x height bytes, row 0 at the image's top
 * (v = 1 in banyan's uvs, whose v runs up). NULL pixels: opaque (wood). */
typedef struct canopy_alpha {
    int32_t width, height;
    const uint8_t *pixels; /* one byte per texel */
} canopy_alpha;

typedef struct canopy_figures {
    double outline_m2;     /* plan area of the convex hull of the leaf vertices */
    double leaf_m2;        /* one-sided leaf area whose texels pass alpha >= 0.5 */
    double lai;            /* leaf_m2 / outline_m2 */
    double gap_below;      /* share of upward rays inside the outline that reach the sky */
    double low_share;      /* share of leaf_m2 whose triangle centre lies below half the height */
    double height_m;       /* highest - lowest vertex */
    int64_t rays, triangles;
} canopy_figures;

/* Alpha at banyan uv (u, v), nearest texel, repeating. */
static inline int canopy_passes(const canopy_alpha *a, double u, double v) {
    if (!a || !a->pixels) return 1;
    u -= floor(u);
    v -= floor(v);
    int32_t x = (int32_t)(u * a->width), y = (int32_t)((1.0 - v) * a->height);
    x = x < 0 ? 0 : x >= a->width ? a->width - 1 : x;
    y = y < 0 ? 0 : y >= a->height ? a->height - 1 : y;
    return a->pixels[(size_t)y * (size_t)a->width + (size_t)x] >= 128;
}

static int canopy_pt_cmp(const void *pa, const void *pb) {
    const double *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return a[1] < b[1] ? -1 : a[1] > b[1];
}

static inline double canopy_cross(const double *o, const double *a, const double *b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Convex hull (monotone chain, counter-clockwise) of n points (x, y) in
 * pt, sorted in place; into h (room for 2 n + 2 doubles). Returns its size. */
static inline int32_t canopy_hull(double *pt, int32_t n, double *h) {
    qsort(pt, (size_t)n, 2 * sizeof(double), canopy_pt_cmp);
    int32_t k = 0;
    for (int32_t i = 0; i < n; i++) {
        while (k >= 2 && canopy_cross(h + 2 * (k - 2), h + 2 * (k - 1), pt + 2 * i) <= 0) k--;
        h[2 * k] = pt[2 * i], h[2 * k + 1] = pt[2 * i + 1], k++;
    }
    for (int32_t i = n - 2, t = k + 1; i >= 0; i--) {
        while (k >= t && canopy_cross(h + 2 * (k - 2), h + 2 * (k - 1), pt + 2 * i) <= 0) k--;
        h[2 * k] = pt[2 * i], h[2 * k + 1] = pt[2 * i + 1], k++;
    }
    return k > 1 ? k - 1 : k;
}

static inline int canopy_in_hull(const double *h, int32_t k, double x, double y) {
    const double p[2] = {x, y};
    for (int32_t i = 0; i < k; i++)
        if (canopy_cross(h + 2 * i, h + 2 * ((i + 1) % k), p) < 0) return 0;
    return k >= 3;
}

/* Barycentric (b1, b2) of (x, y) in the plan of triangle a, b, c; 0 when
 * outside or edge-on in plan. */
static inline int canopy_plan_bary(const float *a, const float *b, const float *c, double x, double y, double *b1,
                                   double *b2) {
    double e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = c[0] - a[0], e2y = c[1] - a[1];
    double d = e1x * e2y - e1y * e2x;
    if (fabs(d) < 1e-14) return 0;
    double px = x - a[0], py = y - a[1];
    double s = (px * e2y - py * e2x) / d, t = (e1x * py - e1y * px) / d;
    if (s < 0 || t < 0 || s + t > 1) return 0;
    *b1 = s, *b2 = t;
    return 1;
}

/* The figures of the triangles of m whose part has group `group` (-1: all),
 * alpha[k] the alpha plane of material k (NULL entry: opaque), rays every
 * `spacing` metres from `eye` metres above the lowest vertex. Returns 0
 * when the parts hold no leaf (nothing measured). */
static inline int canopy_measure(const banyan_mesh *m, int64_t group, const canopy_alpha *const *alpha, double spacing,
                                 double eye, canopy_figures *out) {
    memset(out, 0, sizeof *out);
    const float *P = m->positions, *UV = m->uvs;
    double zlo = INFINITY, zhi = -INFINITY;
    int64_t nleafv = 0, ntri = 0;
    for (uint32_t pi = 0; pi < m->part_count; pi++) {
        const banyan_part *p = &m->parts[pi];
        if (group >= 0 && p->group != (uint32_t)group) continue;
        const canopy_alpha *a = alpha[p->material];
        for (uint32_t v = p->vertex_offset; v < p->vertex_offset + p->vertex_count; v++) {
            zlo = fmin(zlo, P[3 * v + 2]), zhi = fmax(zhi, P[3 * v + 2]);
        }
        if (a && a->pixels) nleafv += p->vertex_count;
        ntri += p->index_count / 3;
    }
    if (nleafv < 3) return 0;
    double *pt = malloc(sizeof(double) * 2 * (size_t)nleafv), *h = malloc(sizeof(double) * (2 * (size_t)nleafv + 4));
    int64_t k = 0;
    for (uint32_t pi = 0; pi < m->part_count; pi++) {
        const banyan_part *p = &m->parts[pi];
        const canopy_alpha *a = alpha[p->material];
        if ((group >= 0 && p->group != (uint32_t)group) || !a || !a->pixels) continue;
        for (uint32_t v = p->vertex_offset; v < p->vertex_offset + p->vertex_count; v++, k++)
            pt[2 * k] = P[3 * v], pt[2 * k + 1] = P[3 * v + 1];
    }
    int32_t nh = canopy_hull(pt, (int32_t)nleafv, h);
    double area = 0, x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int32_t i = 0; i < nh; i++) {
        const double *p0 = h + 2 * i, *p1 = h + 2 * ((i + 1) % nh);
        area += p0[0] * p1[1] - p1[0] * p0[1];
        x0 = fmin(x0, p0[0]), x1 = fmax(x1, p0[0]), y0 = fmin(y0, p0[1]), y1 = fmax(y1, p0[1]);
    }
    out->outline_m2 = 0.5 * area;
    out->height_m = zhi - zlo;
    out->triangles = ntri;

    /* Leaf area passing the cutoff: S x S sample points per triangle. */
    enum { S = 6 };
    const double zmid = zlo + 0.5 * (zhi - zlo), z0 = zlo + eye;
    double leaf = 0, low = 0;
    /* Plan grid of triangle lists for the rays (cells of 4 ray spacings). */
    const double cell = 4 * spacing;
    int64_t gx = (int64_t)((x1 - x0) / cell) + 1, gy = (int64_t)((y1 - y0) / cell) + 1;
    int64_t *count = calloc((size_t)(gx * gy + 1), sizeof(int64_t));
    uint32_t *tmat = malloc(sizeof(uint32_t) * (m->index_count / 3 + 1)); /* each triangle's material */
    for (uint32_t pi = 0; pi < m->part_count; pi++)
        for (uint32_t t = m->parts[pi].index_offset / 3; t < (m->parts[pi].index_offset + m->parts[pi].index_count) / 3; t++)
            tmat[t] = m->parts[pi].material;
    for (int pass = 0; pass < 2; pass++) {
        int64_t *slot = NULL;
        uint32_t *list = NULL;
        if (pass == 1) {
            for (int64_t c = 0, s = 0; c <= gx * gy; c++) {
                int64_t n = count[c];
                count[c] = s;
                s += n;
            }
            list = malloc(sizeof(uint32_t) * (size_t)(count[gx * gy] + 1));
            slot = malloc(sizeof(int64_t) * (size_t)(gx * gy + 1));
            memcpy(slot, count, sizeof(int64_t) * (size_t)(gx * gy + 1));
        }
        for (uint32_t pi = 0; pi < m->part_count; pi++) {
            const banyan_part *p = &m->parts[pi];
            if (group >= 0 && p->group != (uint32_t)group) continue;
            const canopy_alpha *a = alpha[p->material];
            for (uint32_t t = p->index_offset; t < p->index_offset + p->index_count; t += 3) {
                const uint32_t *ix = m->indices + t;
                const float *A = P + 3 * ix[0], *B = P + 3 * ix[1], *C = P + 3 * ix[2];
                if (pass == 0 && a && a->pixels) {
                    double ux = B[0] - A[0], uy = B[1] - A[1], uz = B[2] - A[2];
                    double vx = C[0] - A[0], vy = C[1] - A[1], vz = C[2] - A[2];
                    double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
                    double ar = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
                    int pass_n = 0;
                    for (int i = 0; i < S; i++)
                        for (int j = 0; i + j < S; j++) {
                            for (int up = 0; up < 2 && i + j + up < S; up++) {
                                double b1 = (i + (up ? 2.0 : 1.0) / 3.0) / S, b2 = (j + (up ? 2.0 : 1.0) / 3.0) / S;
                                double b0 = 1 - b1 - b2;
                                double u = b0 * UV[2 * ix[0]] + b1 * UV[2 * ix[1]] + b2 * UV[2 * ix[2]];
                                double v = b0 * UV[2 * ix[0] + 1] + b1 * UV[2 * ix[1] + 1] + b2 * UV[2 * ix[2] + 1];
                                pass_n += canopy_passes(a, u, v);
                            }
                        }
                    double w = ar * pass_n / (double)(S * S);
                    leaf += w;
                    if ((A[2] + B[2] + C[2]) / 3.0 < zmid) low += w;
                }
                if (fmax(A[2], fmax(B[2], C[2])) <= z0) continue;
                int64_t cx0 = (int64_t)floor((fmin(A[0], fmin(B[0], C[0])) - x0) / cell);
                int64_t cx1 = (int64_t)floor((fmax(A[0], fmax(B[0], C[0])) - x0) / cell);
                int64_t cy0 = (int64_t)floor((fmin(A[1], fmin(B[1], C[1])) - y0) / cell);
                int64_t cy1 = (int64_t)floor((fmax(A[1], fmax(B[1], C[1])) - y0) / cell);
                cx0 = cx0 < 0 ? 0 : cx0, cy0 = cy0 < 0 ? 0 : cy0;
                cx1 = cx1 >= gx ? gx - 1 : cx1, cy1 = cy1 >= gy ? gy - 1 : cy1;
                for (int64_t yy = cy0; yy <= cy1; yy++)
                    for (int64_t xx = cx0; xx <= cx1; xx++) {
                        if (pass == 0) count[yy * gx + xx]++;
                        else list[slot[yy * gx + xx]++] = t;
                    }
            }
        }
        if (pass == 0) continue;
        /* Rays: the centres of a spacing grid inside the outline. */
        int64_t rays = 0, open = 0;
        for (double y = y0 + 0.5 * spacing; y < y1; y += spacing)
            for (double x = x0 + 0.5 * spacing; x < x1; x += spacing) {
                if (!canopy_in_hull(h, nh, x, y)) continue;
                rays++;
                int64_t c = (int64_t)((y - y0) / cell) * gx + (int64_t)((x - x0) / cell);
                int blocked = 0;
                for (int64_t q = count[c]; q < count[c + 1] && !blocked; q++) {
                    const uint32_t *ix = m->indices + list[q];
                    const float *A = P + 3 * ix[0], *B = P + 3 * ix[1], *C = P + 3 * ix[2];
                    double b1, b2;
                    if (!canopy_plan_bary(A, B, C, x, y, &b1, &b2)) continue;
                    double b0 = 1 - b1 - b2;
                    if (b0 * A[2] + b1 * B[2] + b2 * C[2] <= z0) continue;
                    const canopy_alpha *a = alpha[tmat[list[q] / 3]];
                    double u = b0 * UV[2 * ix[0]] + b1 * UV[2 * ix[1]] + b2 * UV[2 * ix[2]];
                    double v = b0 * UV[2 * ix[0] + 1] + b1 * UV[2 * ix[1] + 1] + b2 * UV[2 * ix[2] + 1];
                    blocked = canopy_passes(a, u, v);
                }
                open += !blocked;
            }
        out->rays = rays;
        out->gap_below = rays ? (double)open / (double)rays : 1.0;
        free(list);
        free(slot);
    }
    out->leaf_m2 = leaf;
    out->lai = out->outline_m2 > 0 ? leaf / out->outline_m2 : 0;
    out->low_share = leaf > 0 ? low / leaf : 0;
    free(count);
    free(tmat);
    free(pt);
    free(h);
    return 1;
}

#endif
