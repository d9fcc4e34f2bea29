/* leaf_paint.h - the leaf atlases' shared painting: a cell of the atlas,
 * the covered spans of a blade's rows, straight-alpha compositing of a
 * row's shaded pixels, and tapered strokes (twigs, petioles). Used by the
 * keyaki painter (leaves.c) and the ivy painter (leaves_ivy.c); inline,
 * so each painter's per-pixel loops keep them in line. */
#ifndef BANYAN_TEXTURES_LEAF_PAINT_H
#define BANYAN_TEXTURES_LEAF_PAINT_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/dmath.h"
#include "leaf_look.h"
#include "textures/tex_internal.h"

#define PI_F 3.14159265f

static inline float tex_maxf(float a, float b) { return a > b ? a : b; }
static inline float tex_minf(float a, float b) { return a < b ? a : b; }

/* A cell of the atlas in pixels: u right, v up, both 0..1 over the cell. */
typedef struct cell {
    tex_canvas *c;
    int x0, y0, size; /* top-left pixel, side */
    int margin;       /* pixels kept clear at the cell's border */
    int *xmin, *xmax; /* size entries each: a shape's pixel span per row of the cell (spans below) */
    int lo, hi;       /* rows (of the cell) the span covers */
    float *scr;       /* LEAF_SCR * size floats: one row's covered pixels, shaded together */
    int *cols;        /* size entries: their columns */
    int top;          /* rows kept clear at the top besides the margin (a spray cell: the lower half only) */
} cell;

/* Per covered pixel of a row, the blade painters first find the leaf's
 * distance (a table lookup each: scalar), then shade the row's covered
 * pixels in one branch-free loop over these arrays (it vectorises). */
#define LEAF_SCR 16

/* ---------------------------------------------------------------- spans
 * A leaf's outline rasterised into one [xmin, xmax] pixel interval per
 * row: the per-pixel shape test then runs only there, not over the whole
 * bounding box (most of which is empty around a lobed or slanted leaf). */
static inline void span_begin(cell *k) {
    for (int r = 0; r < k->size; r++) k->xmin[r] = INT32_MAX, k->xmax[r] = INT32_MIN;
    k->lo = INT32_MAX, k->hi = INT32_MIN;
}

/* An outline edge from (u0, v0) to (u1, v1), cell units. */
static inline void span_edge(cell *k, float u0, float v0, float u1, float v1) {
    float s = (float)k->size;
    float X0 = u0 * s, Y0 = (1.0f - v0) * s, X1 = u1 * s, Y1 = (1.0f - v1) * s;
    if (Y0 > Y1) {
        float t = X0; X0 = X1; X1 = t;
        t = Y0; Y0 = Y1; Y1 = t;
    }
    int r0 = (int)floorf(Y0), r1 = (int)floorf(Y1);
    if (r0 < 0) r0 = 0;
    if (r1 > k->size - 1) r1 = k->size - 1;
    float dy = Y1 - Y0, slope = dy > 1e-6f ? (X1 - X0) / dy : 0.0f;
    for (int r = r0; r <= r1; r++) {
        float ya = tex_clampf((float)r, Y0, Y1), yb = tex_clampf((float)r + 1.0f, Y0, Y1);
        float xa = X0 + (ya - Y0) * slope, xb = X0 + (yb - Y0) * slope;
        if (dy <= 1e-6f) xa = X0, xb = X1;
        int lo = (int)floorf(tex_minf(xa, xb)), hi = (int)ceilf(tex_maxf(xa, xb));
        if (lo < k->xmin[r]) k->xmin[r] = lo;
        if (hi > k->xmax[r]) k->xmax[r] = hi;
        if (r < k->lo) k->lo = r;
        if (r > k->hi) k->hi = r;
    }
}

/* Widens each row's span by the rows next to it and 2 pixels, for the
 * antialiased edge; returns the absolute pixel rows to visit. */
static inline void span_end(cell *k, int *y0, int *y1) {
    if (k->lo > k->hi) {
        *y0 = 1, *y1 = 0;
        return;
    }
    int lo = k->lo > 0 ? k->lo - 1 : 0, hi = k->hi < k->size - 1 ? k->hi + 1 : k->size - 1;
    int pmin = INT32_MAX, pmax = INT32_MIN; /* the previous row's span before widening */
    for (int r = lo; r <= hi; r++) {
        int cmin = k->xmin[r], cmax = k->xmax[r];
        int nmin = r + 1 <= hi ? k->xmin[r + 1] : INT32_MAX, nmax = r + 1 <= hi ? k->xmax[r + 1] : INT32_MIN;
        int a = cmin < pmin ? cmin : pmin, b = cmax > pmax ? cmax : pmax;
        if (nmin < a) a = nmin;
        if (nmax > b) b = nmax;
        pmin = cmin, pmax = cmax;
        k->xmin[r] = a == INT32_MAX ? INT32_MAX : a - 2;
        k->xmax[r] = b == INT32_MIN ? INT32_MIN : b + 2;
    }
    int m = k->margin;
    for (int r = lo; r <= hi; r++) {
        if (k->xmin[r] < m) k->xmin[r] = m;
        if (k->xmax[r] > k->size - 1 - m) k->xmax[r] = k->size - 1 - m;
    }
    *y0 = lo < m + k->top ? m + k->top : lo;
    *y1 = hi > k->size - 1 - m ? k->size - 1 - m : hi;
}

/* Every pixel of the cell: the colour `rgb` at alpha 0, so texture
 * filtering and mipmaps next to a leaf blend towards the leaf's colour
 * instead of black; height 0. Leaves are drawn over it. */
static inline void fill_cell(const cell *k, const float rgb[3]) {
    uint8_t px[4] = {tex_byte(rgb[0]), tex_byte(rgb[1]), tex_byte(rgb[2]), 0};
    /* The first row texel by texel, the others copied from it. */
    uint8_t *first = k->c->rgba + 4 * ((size_t)k->y0 * k->c->n + k->x0);
    for (int x = 0; x < k->size; x++) memcpy(first + 4 * x, px, 4);
    for (int y = k->y0; y < k->y0 + k->size; y++) {
        uint8_t *p = k->c->rgba + 4 * ((size_t)y * k->c->n + k->x0);
        if (y > k->y0) memcpy(p, first, 4 * (size_t)k->size);
        memset(k->c->height + (size_t)y * k->c->n + k->x0, 0, sizeof(float) * (size_t)k->size);
    }
}

/* Straight-alpha "over" of one covered pixel. */
static inline void put(tex_canvas *c, size_t i, float cov, const float col[3], float h) {
    uint8_t *p = c->rgba + 4 * i;
    if (cov >= 1.0f) {
        p[0] = tex_byte(col[0]), p[1] = tex_byte(col[1]), p[2] = tex_byte(col[2]), p[3] = 255;
        c->height[i] = h;
        return;
    }
    float a0 = (float)p[3] * (1.0f / 255.0f);
    float a = cov + a0 * (1.0f - cov);
    if (a <= 0.0f) return;
    float wb = a0 * (1.0f - cov) / a, wf = cov / a;
    for (int ch = 0; ch < 3; ch++) p[ch] = tex_byte(col[ch] * wf + (float)p[ch] * wb);
    p[3] = tex_byte(a * 255.0f);
    c->height[i] = h * cov + c->height[i] * (1.0f - cov);
}

/* A row's shaded pixels (x, colour, height, coverage) into the canvas at
 * row offset `row`: put() for each. */
static inline void put_row(tex_canvas *c, size_t row, int m, const int *x, const float *r, const float *g, const float *b,
                    const float *h, const float *cov) {
    for (int i = 0; i < m; i++) {
        const float col[3] = {r[i], g[i], b[i]};
        put(c, row + (size_t)x[i], cov[i], col, h[i]);
    }
}

/* Pixel bounds of a box in cell units, clipped to the cell's inner area. */
static inline void bounds(const cell *k, float umin, float umax, float vmin, float vmax, int *x0, int *x1, int *y0,
                   int *y1) {
    float s = (float)k->size;
    *x0 = k->x0 + (int)floorf(umin * s) - 1;
    *x1 = k->x0 + (int)ceilf(umax * s) + 1;
    *y0 = k->y0 + (int)floorf((1.0f - vmax) * s) - 1;
    *y1 = k->y0 + (int)ceilf((1.0f - vmin) * s) + 1;
    int lo_x = k->x0 + k->margin, hi_x = k->x0 + k->size - 1 - k->margin;
    int lo_y = k->y0 + k->margin + k->top, hi_y = k->y0 + k->size - 1 - k->margin;
    if (*x0 < lo_x) *x0 = lo_x;
    if (*x1 > hi_x) *x1 = hi_x;
    if (*y0 < lo_y) *y0 = lo_y;
    if (*y1 > hi_y) *y1 = hi_y;
}

/* Cell coordinates of a pixel centre. The side is a power of two, so
 * times its reciprocal is exactly the division. */
static inline float pu(const cell *k, int x) { return ((float)(x - k->x0) + 0.5f) * (1.0f / (float)k->size); }
static inline float pv(const cell *k, int y) { return 1.0f - ((float)(y - k->y0) + 0.5f) * (1.0f / (float)k->size); }

/* A tapered round stroke (twig, petiole) from a to b, widths in cell units. */
static inline void stroke(const cell *k, float ax, float ay, float bx, float by, float wa, float wb, const float col[3],
                   float h) {
    float pad = (wa > wb ? wa : wb) + 2.0f / (float)k->size;
    int x0, x1, y0, y1;
    bounds(k, tex_minf(ax, bx) - pad, tex_maxf(ax, bx) + pad, tex_minf(ay, by) - pad, tex_maxf(ay, by) + pad, &x0, &x1, &y0,
           &y1);
    float dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    if (l2 <= 0.0f) return;
    float s = (float)k->size;
    const int n = k->c->n;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            float u = pu(k, x), v = pv(k, y);
            float t = tex_clampf(((u - ax) * dx + (v - ay) * dy) / l2, 0.0f, 1.0f);
            float ex = u - (ax + t * dx), ey = v - (ay + t * dy);
            float d = sqrtf(ex * ex + ey * ey), w = tex_mix(wa, wb, t);
            float cov = tex_clampf((w - d) * s + 0.5f, 0.0f, 1.0f);
            if (cov <= 0.0f) continue;
            float r = tex_clampf(d / (w > 1e-6f ? w : 1e-6f), 0.0f, 1.0f);
            float shade = 1.0f - 0.35f * r * r;
            float cc[3] = {col[0] * shade, col[1] * shade, col[2] * shade};
            put(k->c, (size_t)y * n + x, cov, cc, h + w * s * 0.5f * sqrtf(1.0f - r * r));
        }
}

/* A blade's profile (the keyaki's, and each lobe of an ivy leaf's). */
#define KT 160 /* profile samples along a keyaki blade */

typedef struct kleaf {
    float bx, by, dx, dy; /* blade base (cell units) and unit direction to the tip */
    float len;            /* blade length, cell units */
    float half;           /* widest half-width / length */
    float slope;          /* lateral veins: dy/dx away from the midrib */
    int veins;            /* lateral vein pairs (= teeth per side) */
    float skew;           /* lopsided base: right half starts this far up */
    float ymax;           /* widest point, 0..1 along the blade */
    float acum;           /* acuminate tip: > 0 makes the tip's sides concave */
    float col[3], vein[3], edge[3];
    float tooth;          /* tooth depth / length (keyaki 0.028) */
    float env0, env1;     /* teeth grow in from env0 along the blade and fade out by env1 */
    float bend;           /* midrib curved sideways by bend * y^2 (units of length; 0 = straight) */
    float minw;           /* the drawn-out tip keeps this half-width (units of length) to near its end */
    float blot;           /* autumn: strength of brown blotches */
    float blotcol[3];
} kleaf;

typedef struct ktab {
    float w[2][KT + 1]; /* half-widths with teeth, left (0) and right (1), from the midrib */
    float m[KT + 1];    /* the midrib's sideways offset (bend) */
    float g[2][KT + 1]; /* 1 / sqrt(1 + x'^2), x the margin m -+ w: edge distance from the horizontal one */
    float q0, dq;       /* lateral veins: q = y - |x| * slope, vein j at q0 + j * dq */
} ktab;

/* L's profile tables (leaves.c). */
void tex_blade_table(const kleaf *L, ktab *T);

/* The grain (cells of 4 px) and mottle tiles of a leaf atlas (leaves.c);
 * -1 when out of memory. tex_leaf_fields_free frees them. */
int tex_leaf_fields(tex_canvas *c, pcg32 *rng);
void tex_leaf_fields_free(tex_canvas *c);

#endif
