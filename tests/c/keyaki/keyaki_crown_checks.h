/* keyaki_crown_checks.h - plan-view measures of a keyaki crown,
 * shared by test_keyaki_crown.c and test_keyaki_look.c: leaf centres
 * binned into square plan cells, the crown's outline as the convex hull of
 * the leaf centres, the share of cells inside it holding leaves, and the
 * leaves per cell. */
#ifndef BANYAN_KEYAKI_CROWN_CHECKS_H
#define BANYAN_KEYAKI_CROWN_CHECKS_H

#include <math.h>
#include <stdlib.h>

#include "keyaki/keyaki_internal.h"

typedef struct crown_plan {
    int32_t inside;   /* cells whose centre lies inside the outline */
    int32_t filled;   /* of those, cells holding at least one leaf centre */
    double p95;       /* 95th percentile of leaves per non-empty cell */
    int32_t max;      /* most leaves in one cell */
} crown_plan;

static inline v3 crown_leaf_centre(const keyaki_leaf *q) { return v3_madd(q->base, q->axis, 0.5 * q->length); }

static int crown_pt_cmp(const void *a, const void *b) {
    const double *A = a, *B = b;
    if (A[0] != B[0]) return A[0] < B[0] ? -1 : 1;
    return A[1] < B[1] ? -1 : A[1] > B[1];
}

static int crown_int_cmp(const void *a, const void *b) {
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return x < y ? -1 : x > y;
}

static inline double crown_cross(const double *o, const double *a, const double *b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Measures the plan of c's leaves on cells of side `cell` m. */
static inline void crown_plan_measure(const keyaki_crown *c, double cell, crown_plan *out) {
    out->inside = out->filled = out->max = 0;
    out->p95 = 0;
    int32_t n = c->n_leaves;
    if (n < 3) return;
    double *pt = malloc(sizeof(double) * 2 * (size_t)n), *h = malloc(sizeof(double) * 4 * (size_t)n + 32);
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (int32_t i = 0; i < n; i++) {
        v3 m = crown_leaf_centre(&c->leaves[i]);
        pt[2 * i] = m.x;
        pt[2 * i + 1] = m.y;
        x0 = fmin(x0, m.x), x1 = fmax(x1, m.x), y0 = fmin(y0, m.y), y1 = fmax(y1, m.y);
    }
    /* Convex hull (monotone chain), counter-clockwise. */
    double *s = malloc(sizeof(double) * 2 * (size_t)n);
    for (int32_t i = 0; i < 2 * n; i++) s[i] = pt[i];
    qsort(s, (size_t)n, 2 * sizeof(double), crown_pt_cmp);
    int32_t k = 0;
    for (int32_t i = 0; i < n; i++) {
        while (k >= 2 && crown_cross(h + 2 * (k - 2), h + 2 * (k - 1), s + 2 * i) <= 0) k--;
        h[2 * k] = s[2 * i], h[2 * k + 1] = s[2 * i + 1], k++;
    }
    for (int32_t i = n - 2, t = k + 1; i >= 0; i--) {
        while (k >= t && crown_cross(h + 2 * (k - 2), h + 2 * (k - 1), s + 2 * i) <= 0) k--;
        h[2 * k] = s[2 * i], h[2 * k + 1] = s[2 * i + 1], k++;
    }
    k--; /* the last point repeats the first */
    int32_t nx = (int32_t)ceil((x1 - x0) / cell) + 1, ny = (int32_t)ceil((y1 - y0) / cell) + 1;
    int32_t *cnt = calloc((size_t)nx * (size_t)ny, sizeof(int32_t));
    for (int32_t i = 0; i < n; i++) {
        int32_t a = (int32_t)floor((pt[2 * i] - x0) / cell), b = (int32_t)floor((pt[2 * i + 1] - y0) / cell);
        cnt[(size_t)b * (size_t)nx + (size_t)a]++;
    }
    int32_t *full = malloc(sizeof(int32_t) * (size_t)nx * (size_t)ny), nf = 0;
    for (int32_t b = 0; b < ny; b++)
        for (int32_t a = 0; a < nx; a++) {
            double q[2] = {x0 + (a + 0.5) * cell, y0 + (b + 0.5) * cell};
            int in = k >= 3;
            for (int32_t e = 0; e < k && in; e++)
                if (crown_cross(h + 2 * e, h + 2 * ((e + 1) % k), q) < 0) in = 0;
            int32_t v = cnt[(size_t)b * (size_t)nx + (size_t)a];
            if (v) full[nf++] = v;
            if (!in) continue;
            out->inside++;
            out->filled += v > 0;
        }
    qsort(full, (size_t)nf, sizeof(int32_t), crown_int_cmp);
    if (nf) {
        out->p95 = full[(int32_t)floor(0.95 * (nf - 1))];
        out->max = full[nf - 1];
    }
    free(pt);
    free(h);
    free(s);
    free(cnt);
    free(full);
}

#endif
