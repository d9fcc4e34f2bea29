/* crown_light.c - the keyaki crown's light and crowding model (crown.c
 * says how growth uses it): the plan-view shade grid of clusters' plan
 * rectangles, the sky's oblique layers, holes, and the convex outline the
 * crown is planned to fill. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crown_internal.h"

rect crown_cluster_rect(const banyan_keyaki_params *p, v3 at, v3 d, v3 h, double len, double wlen) {
    rect r;
    double hx = sqrt(d.x * d.x + d.y * d.y);
    r.ox = at.x;
    r.oy = at.y;
    if (hx > 0.2) {
        r.ax = d.x / hx;
        r.ay = d.y / hx;
    } else { /* a steep cluster: its spray spreads along h */
        double hh = sqrt(h.x * h.x + h.y * h.y);
        r.ax = hh > 1e-9 ? h.x / hh : 1.0;
        r.ay = hh > 1e-9 ? h.y / hh : 0.0;
    }
    double reach = p->leaf_size * 1.2;
    double sub = p->twig_levels >= 2 ? fmin(len, wlen) * p->twig_ratio * dm_sin(deg2rad(p->twig_angle)) : 0.0;
    r.w = sub + reach;
    r.len = len * (hx > 0.2 ? hx : 0.2) + reach;
    if (r.len < r.w) r.len = r.w;
    return r;
}

/* Visits the cells whose centres lie in r: side -1 left half, +1 right. */
#define FOR_RECT_CELLS(g, r, BODY)                                                                                 \
    do {                                                                                                           \
        /* the rectangle's bounding box: half extents about its centre */                                        \
        double ex_ = 0.5 * fabs((r).ax) * (r).len + fabs((r).ay) * (r).w, ey_ = 0.5 * fabs((r).ay) * (r).len + fabs((r).ax) * (r).w; \
        double cx_ = (r).ox + 0.5 * (r).ax * (r).len, cy_ = (r).oy + 0.5 * (r).ay * (r).len;                       \
        int32_t i0_ = (int32_t)floor((cx_ - ex_ - (g)->x0) / CELL), i1_ = (int32_t)floor((cx_ + ex_ - (g)->x0) / CELL); \
        int32_t j0_ = (int32_t)floor((cy_ - ey_ - (g)->y0) / CELL), j1_ = (int32_t)floor((cy_ + ey_ - (g)->y0) / CELL); \
        if (i0_ < 0) i0_ = 0;                                                                                      \
        if (j0_ < 0) j0_ = 0;                                                                                      \
        if (i1_ > (g)->nx - 1) i1_ = (g)->nx - 1;                                                                  \
        if (j1_ > (g)->ny - 1) j1_ = (g)->ny - 1;                                                                  \
        for (int32_t j_ = j0_; j_ <= j1_; j_++)                                                                    \
            for (int32_t i_ = i0_; i_ <= i1_; i_++) {                                                              \
                double qx_ = (g)->x0 + (i_ + 0.5) * CELL - (r).ox, qy_ = (g)->y0 + (j_ + 0.5) * CELL - (r).oy;     \
                double along_ = qx_ * (r).ax + qy_ * (r).ay, across_ = -qx_ * (r).ay + qy_ * (r).ax;               \
                if (along_ < 0 || along_ > (r).len || fabs(across_) > (r).w) continue;                             \
                int side = across_ > 0 ? -1 : 1;                                                                   \
                int32_t *cell = &(g)->n[(size_t)j_ * (size_t)(g)->nx + (size_t)i_];                                \
                (void)side;                                                                                        \
                BODY;                                                                                              \
            }                                                                                                      \
    } while (0)

/* Shaded fractions of r's left and right halves. */
static void shade_of(const grid *g, rect r, double layers, double *fl, double *fr) {
    int32_t nl = 0, nr = 0, sl = 0, sr = 0;
    FOR_RECT_CELLS(g, r, {
        int sh = *cell >= layers;
        if (side < 0) { nl++; sl += sh; } else { nr++; sr += sh; }
    });
    *fl = nl ? (double)sl / nl : 0.0;
    *fr = nr ? (double)sr / nr : 0.0;
}

static void stamp(grid *g, rect r) { FOR_RECT_CELLS(g, r, { (*cell)++; }); }

/* Oblique layer k of g as a grid of its own, and r as that layer sees a
 * cluster at height z. */
static grid sky_layer(const grid *g, int k, rect r, double z, rect *rk) {
    grid gk = *g;
    gk.n = g->sky + (size_t)k * (size_t)g->nx * (size_t)g->ny;
    double a = 2.0 * BANYAN_PI * k / SKY_OBLIQUE, t = (z - g->zref) / dm_tan(deg2rad(SKY_ELEVATION_DEG));
    *rk = r;
    rk->ox -= t * dm_cos(a);
    rk->oy -= t * dm_sin(a);
    return gk;
}

/* Shaded fractions of r's halves under the whole sky: the weighted mean
 * of the zenith's and every oblique direction's. */
void crown_sky_shade(const grid *g, rect r, double z, double layers, double *fl, double *fr) {
    shade_of(g, r, layers, fl, fr);
    if (!g->sky) return;
    double wo = (1.0 - SKY_ZENITH_WEIGHT) / SKY_OBLIQUE;
    *fl *= SKY_ZENITH_WEIGHT;
    *fr *= SKY_ZENITH_WEIGHT;
    for (int k = 0; k < SKY_OBLIQUE; k++) {
        rect rk;
        grid gk = sky_layer(g, k, r, z, &rk);
        double l, q;
        shade_of(&gk, rk, layers, &l, &q);
        *fl += wo * l;
        *fr += wo * q;
    }
}

void crown_sky_stamp(grid *g, rect r, double z) {
    stamp(g, r);
    for (int k = 0; g->sky && k < SKY_OBLIQUE; k++) {
        rect rk;
        grid gk = sky_layer(g, k, r, z, &rk);
        stamp(&gk, rk);
    }
}

/* Is the cell at (x, y) a hole: inside the outline, no cluster above it? */
int crown_hole_at(const grid *g, double x, double y) {
    int32_t i = (int32_t)floor((x - g->x0) / CELL), j = (int32_t)floor((y - g->y0) / CELL);
    if (i < 0 || j < 0 || i >= g->nx || j >= g->ny) return 0;
    size_t k = (size_t)j * (size_t)g->nx + (size_t)i;
    return g->in[k] && g->n[k] == 0;
}


static int xy_cmp(const void *a, const void *b) {
    const double *A = a, *B = b;
    if (A[0] != B[0]) return A[0] < B[0] ? -1 : 1;
    return A[1] < B[1] ? -1 : A[1] > B[1];
}

static double turn2(const double *o, const double *a, const double *b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* pts: m points (x, y), sorted in place; h->xy needs room for 2 m + 2. */
int crown_hull_of(double *pts, int32_t m, hull *h, keyaki_run *run) {
    if (keyaki_sort(pts, (size_t)m, 2 * sizeof(double), xy_cmp, run)) return 1;
    double *H = h->xy;
    int32_t k = 0;
    for (int32_t i = 0; i < m; i++) {
        while (k >= 2 && turn2(H + 2 * (k - 2), H + 2 * (k - 1), pts + 2 * i) <= 0) k--;
        H[2 * k] = pts[2 * i], H[2 * k + 1] = pts[2 * i + 1], k++;
    }
    for (int32_t i = m - 2, t = k + 1; i >= 0; i--) {
        while (k >= t && turn2(H + 2 * (k - 2), H + 2 * (k - 1), pts + 2 * i) <= 0) k--;
        H[2 * k] = pts[2 * i], H[2 * k + 1] = pts[2 * i + 1], k++;
    }
    h->n = k > 1 ? k - 1 : k;
    return 0;
}

/* Marks the grid cells whose centres lie inside the convex hull h: one
 * interval a row (the hull is convex). */
void crown_hull_mask(const hull *h, grid *g) {
    for (int32_t j = 0; j < g->ny; j++) {
        double y = g->y0 + (j + 0.5) * CELL, xl = 1e300, xr = -1e300;
        for (int32_t e = 0; e < h->n && h->n >= 3; e++) {
            const double *A = h->xy + 2 * e, *B = h->xy + 2 * ((e + 1) % h->n);
            if ((A[1] > y && B[1] > y) || (A[1] < y && B[1] < y)) continue;
            double x = A[1] == B[1] ? A[0] : A[0] + (y - A[1]) * (B[0] - A[0]) / (B[1] - A[1]);
            double x2 = A[1] == B[1] ? B[0] : x;
            xl = fmin(xl, fmin(x, x2)), xr = fmax(xr, fmax(x, x2));
        }
        for (int32_t i = 0; i < g->nx; i++) {
            double x = g->x0 + (i + 0.5) * CELL;
            g->in[(size_t)j * (size_t)g->nx + (size_t)i] = x >= xl && x <= xr;
        }
    }
}
