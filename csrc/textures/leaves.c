/* leaves.c - leaf atlases (issues #17, #20; docs/materials.md, "Keyaki leaves"):
 * keyaki (Zelkova serrata) and Boston ivy (Parthenocissus tricuspidata).
 * Each leaf is an implicit shape evaluated per pixel inside its bounding
 * box: keyaki blades by a half-width profile along the midrib (ovate,
 * acuminate tip, slightly lopsided base) whose margin carries one
 * forward-pointing tooth at the end of each straight lateral vein; ivy
 * blades by a polar radius around the petiole junction (three pointed
 * lobes or one, cordate base, coarse teeth) with five palmate primary
 * veins. Profiles are tabulated per leaf, the edge is antialiased from its
 * distance in pixels. Both atlases are 4 x 4 cells of one leaf each,
 * except keyaki's bottom row: two sprays of leaves on a twig, each two
 * cells wide (leaf_look.h, LEAF_KEYAKI_SPRAY_*), for leaf-cluster cards; a
 * keyaki leaf fills the box textures/leaf_look.h gives its mesh quad (issue
 * #20: midrib up the cell's centre, petiole below, blade and teeth within
 * LEAF_KEYAKI_HALF_U of it), so the drawn leaf and the quad have the same
 * length. Colour is straight alpha; pixels outside leaves get the cell's
 * mean leaf colour at alpha 0, so mipmaps and texture filtering do not
 * bleed a dark fringe. */
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
static void span_begin(cell *k) {
    for (int r = 0; r < k->size; r++) k->xmin[r] = INT32_MAX, k->xmax[r] = INT32_MIN;
    k->lo = INT32_MAX, k->hi = INT32_MIN;
}

/* An outline edge from (u0, v0) to (u1, v1), cell units. */
static void span_edge(cell *k, float u0, float v0, float u1, float v1) {
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
static void span_end(cell *k, int *y0, int *y1) {
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
static void fill_cell(const cell *k, const float rgb[3]) {
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
static void put_row(tex_canvas *c, size_t row, int m, const int *x, const float *r, const float *g, const float *b,
                    const float *h, const float *cov) {
    for (int i = 0; i < m; i++) {
        const float col[3] = {r[i], g[i], b[i]};
        put(c, row + (size_t)x[i], cov[i], col, h[i]);
    }
}

/* Pixel bounds of a box in cell units, clipped to the cell's inner area. */
static void bounds(const cell *k, float umin, float umax, float vmin, float vmax, int *x0, int *x1, int *y0,
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
static void stroke(const cell *k, float ax, float ay, float bx, float by, float wa, float wb, const float col[3],
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

/* ------------------------------------------------------------- keyaki */

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

/* Smooth half-width (without teeth) at t in 0..1 for one side; p puts
 * the widest point at ymax. */
static float keyaki_w0(const kleaf *L, float p, float t) {
    if (t <= 0.0f || t >= 1.0f) return 0.0f;
    float f = dm_sinf(PI_F * dm_powf(t, p));
    float e = 1.0f + L->acum * tex_smooth(0.45f, 1.0f, t);
    if (e != 1.0f) f = dm_powf(f, e); /* below 0.45 it is 1: powf would return f */
    return L->half * f;
}

/* Margin tooth: phase 0 = tooth tip (a vein's end), the margin drops into
 * the notch over the first 18 % of the period, then bulges out to the
 * next tip: forward-pointing crenate-serrate teeth. */
static float keyaki_tooth(float ph) {
    float f = ph - floorf(ph);
    if (f < 0.18f) return 1.0f - f / 0.18f;
    float t = (f - 0.18f) / 0.82f;
    return 1.0f - (1.0f - t) * (1.0f - t);
}

typedef struct ktab {
    float w[2][KT + 1]; /* half-widths with teeth, left (0) and right (1), from the midrib */
    float m[KT + 1];    /* the midrib's sideways offset (bend) */
    float g[2][KT + 1]; /* 1 / sqrt(1 + x'^2), x the margin m -+ w: edge distance from the horizontal one */
    float q0, dq;       /* lateral veins: q = y - |x| * slope, vein j at q0 + j * dq */
} ktab;

static void keyaki_table(const kleaf *L, ktab *T) {
    T->q0 = 0.06f;
    T->dq = (0.93f - T->q0) / (float)L->veins;
    const float p = dm_logf(0.5f) / dm_logf(L->ymax); /* the widest point's exponent, once a leaf */
    for (int side = 0; side < 2; side++) {
        float sk = side ? L->skew : 0.0f, sc = side ? 0.95f : 1.0f;
        for (int i = 0; i <= KT; i++) {
            float y = (float)i / KT;
            float t = (y - sk) / (1.0f - sk);
            float w0 = sc * keyaki_w0(L, p, t);
            float ph = (y - w0 * L->slope - T->q0) / T->dq; /* vein index reaching the margin here */
            float env = tex_smooth(L->env0, L->env0 + 0.16f, y) * (1.0f - tex_smooth(L->env1 - 0.13f, L->env1, y));
            float depth = tex_minf(L->tooth * env, 0.35f * w0); /* no tooth cuts a thin tip off */
            float w = w0 - depth * (1.0f - keyaki_tooth(ph));
            /* A hair-thin tip would fade out below a pixel before its end. */
            if (y > 0.5f) w = tex_maxf(w, L->minw * tex_clampf((1.0f - y) * 40.0f, 0.0f, 1.0f));
            T->w[side][i] = w > 0.0f ? w : 0.0f;
            T->m[i] = L->bend * y * y;
        }
        const float sg = side ? 1.0f : -1.0f;
        for (int i = 0; i <= KT; i++) {
            int a = i > 0 ? i - 1 : 0, b = i < KT ? i + 1 : KT;
            float d = ((T->m[b] + sg * T->w[side][b]) - (T->m[a] + sg * T->w[side][a])) * KT / (float)(b - a);
            T->g[side][i] = 1.0f / sqrtf(1.0f + d * d);
        }
    }
}

/* Constants of one keyaki blade for its shading pass. */
typedef struct keyaki_consts {
    float col[3], edge[3], vein[3], blot[3];
    float lp, slope, q0, dq, veins, ivslope, blot_k; /* length px; laterals; blotch strength */
} keyaki_consts;

/* One colour channel of a keyaki blade pixel. */
static inline float keyaki_shade(float col, float edge_c, float blot_c, float vein_c, float toward, float shade,
                                 float bl, float vein, float edge) {
    float cc = tex_mix(col, edge_c, toward) * shade;
    cc = tex_mix(cc, blot_c, bl);
    cc = tex_mix(cc, vein_c, vein * 0.8f);
    return tex_mix(cc, edge_c * 0.8f, edge * 0.6f);
}

/* Pass 2 of keyaki_leaf over a row's m covered pixels (separate, with
 * restrict arrays, so it vectorises): colour into r, g, b, height into h. */
static void keyaki_shade_row(const keyaki_consts *Cp, int m, const float *restrict sY, const float *restrict sA,
                             const float *restrict sS, const float *restrict sW, const float *restrict sD,
                             const float *restrict sGr, const float *restrict sMb, float *restrict sR,
                             float *restrict sG, float *restrict sB, float *restrict sH) {
    const keyaki_consts C = *Cp;
    const float lp = C.lp;
    for (int i = 0; i < m; i++) {
        const float y = sY[i], ax = sA[i], w = sW[i], dpx = sD[i], gr = sGr[i];
        float rel = w > 1e-5f ? ax / w : 1.0f;
        /* Veins: midrib, then the straight laterals (q = const lines). */
        float mid_w = (0.0075f * (1.0f - y) + 0.0025f) * lp;
        float vm = 1.0f - tex_smooth(mid_w, mid_w + 0.9f, ax * lp);
        float q = y - ax * C.slope;
        float j = (q - C.q0) / C.dq;
        float dj = fabsf(j - (float)(int)(j + 1.5f) + 1.0f) * C.dq * C.ivslope * lp; /* px to the nearest lateral; j > -0.3: int() floors */
        float lw = (0.0036f * (1.0f - 0.6f * rel)) * lp;
        float vl0 = (1.0f - tex_smooth(lw, lw + 0.9f, dj)) * (1.0f - tex_smooth(0.82f, 1.0f, rel));
        vl0 *= tex_smooth(0.0f, 0.05f, ax);
        float vl = (j > -0.3f) & (j < C.veins) ? vl0 : 0.0f;
        float vein = tex_maxf(vm, 0.75f * vl);
        float shade = sS[i] * (0.93f + 0.07f * gr);
        float edge = 1.0f - tex_smooth(0.5f, 3.0f, dpx);           /* a dark rim */
        float toward = tex_smooth(0.55f, 1.0f, rel) * 0.35f;        /* darker toward the margin */
        float bl = C.blot_k * tex_smooth(0.15f, 0.55f, sMb[i]); /* blot_k >= 0; 0 in summer */
        sR[i] = keyaki_shade(C.col[0], C.edge[0], C.blot[0], C.vein[0], toward, shade, bl, vein, edge);
        sG[i] = keyaki_shade(C.col[1], C.edge[1], C.blot[1], C.vein[1], toward, shade, bl, vein, edge);
        sB[i] = keyaki_shade(C.col[2], C.edge[2], C.blot[2], C.vein[2], toward, shade, bl, vein, edge);
        /* Domed across; a blade under a few pixels wide (the tip) stays low. */
        sH[i] = (2.0f * (1.0f - rel * rel) - 1.2f * vl - 0.8f * vm + 0.3f * gr) * tex_clampf(w * lp * 0.25f, 0.0f, 1.0f);
    }
}

static void keyaki_leaf(cell *k, const kleaf *L) {
    ktab T;
    keyaki_table(L, &T);
    const float s = (float)k->size, lp = L->len * s; /* blade length in pixels */
    const int n = k->c->n;
    const int tile = n < TEX_TILE ? n : TEX_TILE, tm = tile - 1;
    int msh = 0; /* mottle: image pixel to tile pixel shift */
    while ((tile << msh) < n) msh++;
    float nx = L->dy, ny = -L->dx; /* to the right of the midrib */
    /* The outline (both margins, base to tip) into row spans. */
    span_begin(k);
    for (int side = 0; side < 2; side++) {
        float pu0 = L->bx, pv0 = L->by;
        for (int i = 1; i <= KT; i++) {
            float y = (float)i / KT, x = T.m[i] + (side ? 1.0f : -1.0f) * T.w[side][i];
            float pu1 = L->bx + (L->dx * y + nx * x) * L->len, pv1 = L->by + (L->dy * y + ny * x) * L->len;
            span_edge(k, pu0, pv0, pu1, pv1);
            pu0 = pu1, pv0 = pv1;
        }
    }
    int r0, r1;
    span_end(k, &r0, &r1);
    const float ivslope = 1.0f / sqrtf(1.0f + L->slope * L->slope), il = 1.0f / L->len;
    /* Locals: the canvas stores below could otherwise alias the leaf. */
    tex_canvas *const cv = k->c;
    const float ldx = L->dx, ldy = L->dy, bx0 = L->bx, slope = L->slope, blot = L->blot;
    const float veins = (float)L->veins - 0.2f, q0 = T.q0, dq = T.dq;
    float lcol[3], ledge[3], lvein[3], lblot[3];
    for (int ch = 0; ch < 3; ch++) lcol[ch] = L->col[ch], ledge[ch] = L->edge[ch], lvein[ch] = L->vein[ch], lblot[ch] = L->blotcol[ch];
    const keyaki_consts C = {{lcol[0], lcol[1], lcol[2]}, {ledge[0], ledge[1], ledge[2]}, {lvein[0], lvein[1], lvein[2]},
                             {lblot[0], lblot[1], lblot[2]}, lp, slope, q0, dq, veins, ivslope, blot};
    for (int r = r0; r <= r1; r++) {
        const int yy = k->y0 + r;
        const float v = pv(k, yy) - L->by, vdy = v * ldy, vny = v * ny;
        const float *grow = cv->grain + (size_t)(yy & tm) * tile;
        const float *mrow = cv->mottle + (size_t)((yy >> msh) & tm) * tile;
        const int xa = k->x0 + k->xmin[r], xb = k->x0 + k->xmax[r];
        /* Pass 1: the covered pixels and their distances; pass 2 shades them. */
        float *const sY = k->scr, *const sA = sY + k->size, *const sS = sA + k->size, *const sW = sS + k->size;
        float *const sD = sW + k->size, *const sCov = sD + k->size, *const sGr = sCov + k->size;
        float *const sMb = sGr + k->size, *const sR = sMb + k->size, *const sG = sR + k->size;
        float *const sB = sG + k->size, *const sH = sB + k->size;
        int *const sXX = k->cols;
        int m = 0;
        for (int xx = xa; xx <= xb; xx++) {
            float u = pu(k, xx) - bx0;
            float y = (u * ldx + vdy) * il, x = (u * nx + vny) * il;
            if (y <= 0.0f || y >= 1.0f) continue;
            float fi = y * KT;
            int i = (int)fi;
            float fr = fi - (float)i;
            if (i >= KT) i = KT - 1, fr = 1.0f;
            x -= T.m[i] + (T.m[i + 1] - T.m[i]) * fr; /* from the (bent) midrib */
            int side = x > 0.0f;
            float ax = fabsf(x);
            const float *tw = T.w[side], *tg = T.g[side];
            float w = tw[i] + (tw[i + 1] - tw[i]) * fr;
            float g = tg[i] + (tg[i + 1] - tg[i]) * fr;
            float dpx = (w - ax) * lp * g; /* signed distance to the margin, pixels */
            if (dpx + 0.5f <= 0.0f) continue; /* coverage 0 */
            /* A blade thinner than a pixel (the drawn-out tip) fades out. */
            float cov = tex_clampf(dpx + 0.5f, 0.0f, 1.0f) * tex_clampf(w * lp, 0.0f, 1.0f);
            if (cov <= 0.0f) continue;
            sY[m] = y, sA[m] = ax, sS[m] = side ? 0.96f : 1.0f, sW[m] = w, sD[m] = dpx, sCov[m] = cov;
            sGr[m] = grow[xx & tm], sMb[m] = blot > 0.0f ? mrow[(xx >> msh) & tm] : 0.0f;
            sXX[m++] = xx;
        }
        keyaki_shade_row(&C, m, sY, sA, sS, sW, sD, sGr, sMb, sR, sG, sB, sH);
        put_row(cv, (size_t)yy * n, m, sXX, sR, sG, sB, sH, sCov);
    }
}

/* Colours (sRGB 0..255). Summer: `light` in -1..1 from a darker, bluer
 * green (shade) through mid green to a lighter, yellower one (sun); tone 1
 * a young leaf, light yellow-green. Autumn: tone 0..3 yellow, orange,
 * rust, red-purple [plants.md 3: S 43, 57], `light` the brightness. */
static void keyaki_colours(kleaf *L, int season, int tone, float light, pcg32 *r) {
    float c[3];
    if (season == BANYAN_SEASON_SUMMER) {
        const float mid[3] = {78, 118, 44}, yel[3] = {112, 140, 52}, blu[3] = {50, 88, 46}, young[3] = {136, 160, 62};
        float b = tex_unif(r, 0.94f, 1.06f);
        for (int i = 0; i < 3; i++) {
            c[i] = light > 0 ? tex_mix(mid[i], yel[i], light * 0.8f) : tex_mix(mid[i], blu[i], -light);
            if (tone == 1) c[i] = tex_mix(young[i], yel[i], tex_unif(r, 0.0f, 0.3f));
            c[i] *= b;
        }
        for (int i = 0; i < 3; i++) {
            L->col[i] = c[i];
            L->vein[i] = tex_mix(c[i], 200.0f - (float)i * 40.0f, 0.30f);
            L->edge[i] = c[i] * 0.72f;
        }
        L->blot = 0.0f;
        memcpy(L->blotcol, L->col, sizeof c);
        return;
    }
    static const float pal[5][3] = {{224, 180, 46}, {214, 118, 36}, {158, 78, 36}, {136, 40, 46}, {136, 40, 46}};
    float b = 0.88f + 0.09f * (light + 1.0f);
    float m = tex_unif(r, 0.0f, 0.15f); /* a little towards the next tone: still one tone */
    for (int i = 0; i < 3; i++) c[i] = tex_mix(pal[tone][i], pal[tone + 1][i], m) * b;
    float green = rng_uniform(r) < 0.15 ? tex_unif(r, 0.1f, 0.3f) : 0.0f; /* a leaf still turning */
    const float g[3] = {110, 128, 50};
    for (int i = 0; i < 3; i++) {
        c[i] = tex_mix(c[i], g[i], green);
        L->col[i] = c[i];
        L->vein[i] = tex_mix(c[i], 230.0f - (float)i * 50.0f, 0.28f);
        L->edge[i] = c[i] * 0.7f;
        L->blotcol[i] = c[i] * 0.62f;
    }
    L->blot = tex_unif(r, 0.0f, 0.35f);
}

/* A keyaki blade's shape: base (bx, by), unit direction (dx, dy) and
 * length len in cell units, `ratio` its length / width, `lance` narrows
 * the widest point towards the base, `bend` curves the midrib; the rest
 * drawn from r. */
static void keyaki_shape(kleaf *L, float bx, float by, float dx, float dy, float len, float ratio, int lance,
                         float bend, float cs, pcg32 *r) {
    memset(L, 0, sizeof *L);
    L->bx = bx, L->by = by, L->dx = dx, L->dy = dy;
    L->len = len;
    L->half = 1.0f / (1.95f * ratio); /* the right half is 0.95 of the left (keyaki_table) */
    L->ymax = lance ? tex_unif(r, 0.26f, 0.32f) : tex_unif(r, 0.30f, 0.40f);
    L->acum = lance ? tex_unif(r, 1.0f, 1.6f) : tex_unif(r, 0.7f, 1.4f);
    L->veins = 8 + (int)rng_below(r, 8); /* 8-15 pairs */
    L->slope = tex_unif(r, 0.75f, 1.05f);
    L->skew = tex_unif(r, 0.01f, 0.05f);
    L->tooth = 0.028f, L->env0 = 0.10f, L->env1 = 0.99f;
    L->bend = bend;
    L->minw = 0.8f / (L->len * cs); /* 0.8 px: the tip stays visible to within 2.5 % of its end */
}

/* One keyaki leaf filling its cell's box (leaf_look.h): midrib up u = 0.5,
 * blade from LEAF_KEYAKI_BLADE_V0 to its tip at LEAF_KEYAKI_BLADE_V1,
 * petiole below; `ratio` its length / width, `lance` narrows the widest
 * point towards the base, `bend` curves the midrib. Blade and antialiased
 * edge stay within LEAF_KEYAKI_HALF_U of the centre line: a broad or bent
 * leaf that would reach past it is narrowed (half-width and bend scaled). */
static void keyaki_cell(cell *k, int season, int tone, float light, float ratio, int lance, float bend, pcg32 *r) {
    kleaf L;
    const float cs = (float)k->size;
    keyaki_shape(&L, 0.5f, (float)LEAF_KEYAKI_BLADE_V0, 0.0f, 1.0f, (float)(LEAF_KEYAKI_BLADE_V1 - LEAF_KEYAKI_BLADE_V0),
                 ratio, lance, bend, cs, r);
    keyaki_colours(&L, season, tone, light, r);
    /* Fit sideways: margin extents from the table, antialiased edge 0.75 px. */
    const float lim = ((float)LEAF_KEYAKI_HALF_U - 0.75f / cs) / L.len;
    ktab T;
    for (int it = 0; it < 6; it++) {
        keyaki_table(&L, &T);
        float ext = 0.0f;
        for (int i = 0; i <= KT; i++) ext = tex_maxf(ext, tex_maxf(T.m[i] + T.w[1][i], T.w[0][i] - T.m[i]));
        if (ext <= lim) break;
        float f = lim / ext * 0.998f;
        L.half *= f, L.bend *= f;
    }
    fill_cell(k, L.col);
    /* Petiole: short, darker and browner than the blade, into the midrib. */
    const float pb[3] = {season ? 116.0f : 92.0f, season ? 80.0f : 88.0f, season ? 42.0f : 42.0f};
    float pc[3];
    for (int ch = 0; ch < 3; ch++) pc[ch] = tex_mix(pb[ch], L.col[ch], 0.35f);
    stroke(k, 0.5f, 0.0f, 0.5f, (float)LEAF_KEYAKI_BLADE_V0 + 0.03f, 0.009f, 0.007f, pc, 0.2f);
    keyaki_leaf(k, &L);
}

/* A keyaki spray (leaf_look.h, LEAF_KEYAKI_SPRAY_*) in k: a square cell
 * twice the spray's height whose upper half is kept clear (k->top), so
 * cell units u 0..1 run along the spray and v 0..0.5 across it. A thin
 * twig along v = 0.25 from U0 to U1, leaves alternately left and right at
 * 40-70 deg forward on short petioles, smaller toward the tip, and one
 * leaf on from the twig's end. Summer: each leaf its own light and some
 * young ones; autumn: each leaf its own tone (yellow to red-purple). */
static void keyaki_spray(cell *k, int season, pcg32 *r) {
    const float cs = (float)k->size, vc = 0.5f * (float)LEAF_KEYAKI_SPRAY_V;
    const float u0 = (float)LEAF_KEYAKI_SPRAY_U0, u1 = (float)LEAF_KEYAKI_SPRAY_U1;
    const float half = 0.25f - (float)(k->margin + 2) / cs; /* room either side of the twig */
    /* The cell's fill colour: a mid leaf of the season. */
    kleaf M;
    memset(&M, 0, sizeof M);
    pcg32 fr = *r;
    keyaki_colours(&M, season, season == BANYAN_SEASON_SUMMER ? 0 : 1, 0.0f, &fr);
    {
        uint8_t px[4] = {tex_byte(M.col[0]), tex_byte(M.col[1]), tex_byte(M.col[2]), 0};
        int ya = k->y0 + k->top, yb = k->y0 + k->size;
        for (int y = ya; y < yb; y++) {
            uint8_t *p = k->c->rgba + 4 * ((size_t)y * k->c->n + k->x0);
            for (int x = 0; x < k->size; x++) memcpy(p + 4 * x, px, 4);
            memset(k->c->height + (size_t)y * k->c->n + k->x0, 0, sizeof(float) * (size_t)k->size);
        }
    }
    /* The twig: a slight curve, thinning to the tip. */
    const float bow = tex_unif(r, -0.012f, 0.012f);
    const float tw[3] = {season ? 108.0f : 92.0f, season ? 84.0f : 80.0f, season ? 60.0f : 58.0f};
    enum { TS = 8 };
    float px_[TS + 1], py_[TS + 1];
    for (int i = 0; i <= TS; i++) {
        float t = (float)i / TS;
        px_[i] = u0 + (u1 - u0) * t;
        py_[i] = vc + bow * 4.0f * t * (1.0f - t);
    }
    for (int i = 0; i < TS; i++)
        stroke(k, px_[i], py_[i], px_[i + 1], py_[i + 1], tex_mix(0.0042f, 0.0022f, (float)i / TS),
               tex_mix(0.0042f, 0.0022f, (float)(i + 1) / TS), tw, 0.4f);
    /* Leaves: a node every `step` along the twig, sides alternating. */
    const float step = 0.031f;
    int side = rng_uniform(r) < 0.5 ? 1 : -1;
    for (float s = u0 + 0.05f; s < u1 - 0.01f && !tex_stopped(k->c); s += step * tex_unif(r, 0.9f, 1.1f), side = -side) {
        float t = (s - u0) / (u1 - u0);
        float th = tex_unif(r, 40.0f, 62.0f) * PI_F / 180.0f;
        float dx = dm_cosf(th), dy = (float)side * dm_sinf(th);
        float ratio = tex_unif(r, 1.8f, 2.4f), wmax = 0.55f / ratio; /* widest half-width / length, with teeth */
        float len = 0.27f * (1.0f - 0.3f * t) * tex_unif(r, 0.9f, 1.1f);
        float pet = 0.06f; /* petiole / blade length */
        float reach = (1.0f + pet) * fabsf(dy) + wmax * dx; /* sideways per unit length */
        if (len * reach > half) len = half / reach;
        float ty = vc + bow * 4.0f * t * (1.0f - t);
        float bx = s + pet * len * dx, by = ty + pet * len * dy;
        kleaf L;
        float bend = tex_unif(r, -0.03f, 0.03f);
        keyaki_shape(&L, bx, by, dx, dy, len, ratio, ratio > 2.45f, bend, cs, r);
        int tone = season == BANYAN_SEASON_SUMMER ? rng_uniform(r) < 0.12 : (int)rng_below(r, 4);
        keyaki_colours(&L, season, tone, tex_unif(r, -1.0f, 1.0f), r);
        float pc[3];
        for (int ch = 0; ch < 3; ch++) pc[ch] = tex_mix(tw[ch], L.col[ch], 0.35f);
        stroke(k, s, ty, bx, by, 0.0026f, 0.002f, pc, 0.3f);
        keyaki_leaf(k, &L);
    }
    /* The tip leaf, on from the twig's end. */
    {
        float ratio = tex_unif(r, 2.0f, 2.6f), len = (1.0f - (float)(k->margin + 2) / cs - u1) / 1.05f;
        float wmax = 0.55f / ratio;
        if (len * wmax > half) len = half / wmax;
        kleaf L;
        keyaki_shape(&L, u1 + 0.04f * len, vc, 1.0f, 0.0f, len * 0.96f, ratio, ratio > 2.45f, 0.0f, cs, r);
        int tone = season == BANYAN_SEASON_SUMMER ? rng_uniform(r) < 0.12 : (int)rng_below(r, 4);
        keyaki_colours(&L, season, tone, tex_unif(r, -1.0f, 1.0f), r);
        keyaki_leaf(k, &L);
    }
}

/* ---------------------------------------------------------------- ivy */

/* A Boston ivy blade: three lobes from the petiole junction, each shaped
 * like a keyaki blade (ovate, acuminate, a coarse forward tooth at the end
 * of each secondary vein), their union the leaf. The side lobes' lower
 * halves reach below the junction: the heart-shaped base. Young leaves of
 * long shoots: short broad side lobes, so the outline is a toothed heart. */
typedef struct ivleaf {
    float jx, jy;      /* petiole junction (cell units) */
    int lobed;
    kleaf lobe[3];     /* central, right, left; bx, by = the junction */
    ktab tab[3];
    float basal;       /* basal veins: angle off the side lobes' axes, towards the base */
    float col[3], vein[3], edge[3], inner[3];
} ivleaf;

/* Lobe shapes in units of the central lobe's length, junction at 0. */
static void ivy_shape(ivleaf *L, pcg32 *r) {
    float side_a, side_len, side_half, c_half;
    if (L->lobed) {
        side_a = tex_unif(r, 0.92f, 1.08f), side_len = tex_unif(r, 0.72f, 0.85f);
        side_half = tex_unif(r, 0.36f, 0.42f), c_half = tex_unif(r, 0.29f, 0.34f);
    } else {
        /* One broad ovate blade; the "side lobes" are its rounded basal lobes. */
        side_a = tex_unif(r, 1.45f, 1.6f), side_len = tex_unif(r, 0.40f, 0.46f);
        side_half = tex_unif(r, 0.5f, 0.56f), c_half = tex_unif(r, 0.44f, 0.5f);
    }
    int teeth = L->lobed ? 6 + (int)rng_below(r, 3) : 8 + (int)rng_below(r, 3);
    float depth = L->lobed ? tex_unif(r, 0.045f, 0.06f) : tex_unif(r, 0.035f, 0.045f);
    for (int i = 0; i < 3; i++) {
        kleaf *B = &L->lobe[i];
        float a = i == 0 ? tex_unif(r, -0.04f, 0.04f) : (i == 1 ? 1.0f : -1.0f) * side_a * tex_unif(r, 0.95f, 1.05f);
        B->dx = dm_sinf(a), B->dy = dm_cosf(a);
        B->len = i == 0 ? 1.0f : side_len * tex_unif(r, 0.95f, 1.05f);
        B->half = i == 0 ? c_half : side_half;
        B->ymax = i == 0 ? (L->lobed ? tex_unif(r, 0.36f, 0.44f) : tex_unif(r, 0.3f, 0.36f)) : tex_unif(r, 0.3f, 0.38f);
        B->acum = L->lobed ? (i == 0 ? tex_unif(r, 0.9f, 1.4f) : tex_unif(r, 0.6f, 1.0f))
                           : (i == 0 ? tex_unif(r, 0.5f, 0.9f) : 0.2f);
        B->veins = i == 0 ? teeth : L->lobed ? teeth - 1 : 4;
        B->slope = tex_unif(r, 0.85f, 1.1f);
        B->skew = 0.0f;
        B->tooth = depth / B->len;
        B->env0 = i == 0 ? 0.28f : 0.12f, B->env1 = 0.97f;
        B->bend = B->minw = 0.0f;
        B->bx = B->by = 0.0f;
    }
    L->basal = 0.8f;
}

/* Scales the lobes (lengths in cell units) and places the junction. */
static void ivy_place(ivleaf *L, float scale, float jx, float jy) {
    L->jx = jx, L->jy = jy;
    for (int i = 0; i < 3; i++) {
        L->lobe[i].len *= scale;
        L->lobe[i].bx = jx, L->lobe[i].by = jy; /* the tables (ivy_extent) do not depend on these */
    }
}

/* The lobes' tables, and the extents of their outlines around the
 * junction (units of the lobes' lengths as set). */
static void ivy_extent(ivleaf *L, float *side, float *up, float *down) {
    *side = *up = *down = 0.0f;
    for (int i = 0; i < 3; i++) {
        kleaf *B = &L->lobe[i];
        ktab *T = &L->tab[i];
        keyaki_table(B, T); /* in units of the length: ivy_place keeps it */
        float nx = B->dy, ny = -B->dx;
        for (int j = 0; j <= KT; j += 4)
            for (int sd = 0; sd < 2; sd++) {
                float y = (float)j / KT, x = (sd ? 1.0f : -1.0f) * T->w[sd][j];
                float pu = (B->dx * y + nx * x) * B->len, pv = (B->dy * y + ny * x) * B->len;
                *side = tex_maxf(*side, fabsf(pu));
                *up = tex_maxf(*up, pv);
                *down = tex_maxf(*down, -pv);
            }
    }
}

/* A basal vein's darkening folded into vp (pass 2 of ivy_leaf). */
static inline float ivy_basal(float vp, float u, float bvx, float bvy, float vby, float vbx, float blen, float s,
                              float lp) {
    float al = u * bvx + vby;
    float pd = fabsf(u * bvy - vbx) * s;
    float ab = al / blen;
    float bw2 = (0.006f * (1.0f - ab) + 0.002f) * lp;
    float vb = tex_maxf(vp, (1.0f - tex_smooth(bw2, bw2 + 0.9f, pd)) * (1.0f - tex_smooth(0.7f, 1.0f, ab)));
    return (al <= 0.0f) | (al > blen) ? vp : vb;
}

/* One colour channel of an ivy blade pixel. */
static inline float ivy_shade(float inner, float col, float edge_c, float vein_c, float tin, float toward, float sh,
                              float vein, float edge) {
    float cc = tex_mix(inner, col, tin);
    cc = tex_mix(cc, edge_c, toward * 0.4f) * sh;
    cc = tex_mix(cc, vein_c, vein * 0.7f);
    return tex_mix(cc, edge_c * 0.8f, edge * 0.6f);
}

/* Constants of one row of an ivy blade for its shading pass. */
typedef struct ivy_consts {
    float bvx[2], bvy[2], vbx[2], vby[2], blen[2]; /* basal veins: directions, v times them, lengths */
    float inner[3], col[3], edge[3], vein[3];
    float s, vv, len0; /* cell side px, v^2, the central lobe's length */
} ivy_consts;

/* Pass 2 of ivy_leaf over the row's m covered pixels (separate, with
 * restrict arrays, so it vectorises): colour into r, g, b, height into u. */
static void ivy_shade_row(const ivy_consts *Cp, int m, float *restrict sU, const float *restrict sD,
                          const float *restrict sY, const float *restrict sX, const float *restrict sW,
                          const float *restrict sLp, const float *restrict sSl, const float *restrict sQ0,
                          const float *restrict sDq, const float *restrict sVe, const float *restrict sVs,
                          const float *restrict sGr, float *restrict sR, float *restrict sG, float *restrict sB) {
    const ivy_consts C = *Cp;
    const float s = C.s, vv = C.vv, len0 = C.len0;
    for (int i = 0; i < m; i++) {
        const float u = sU[i], dpx = sD[i], by = sY[i], bw = sW[i], lp = sLp[i], gr = sGr[i];
        float ax = fabsf(sX[i]), rel = bw > 1e-5f ? ax / bw : 1.0f;
        /* Primary vein: the lobe's midrib; secondaries: straight to the teeth. */
        float mid_w = (0.011f * (1.0f - by) + 0.003f) * lp;
        float vp = 1.0f - tex_smooth(mid_w, mid_w + 0.9f, ax * lp);
        float q = by - ax * sSl[i], j = (q - sQ0[i]) / sDq[i];
        float dj = fabsf(j - (float)(int)(j + 1.5f) + 1.0f) * sDq[i] * sVs[i] * lp; /* j > -0.3: int() floors */
        float lw = 0.004f * (1.0f - 0.6f * rel) * lp;
        float vs0 = (1.0f - tex_smooth(lw, lw + 0.9f, dj)) * (1.0f - tex_smooth(0.8f, 1.0f, rel)) *
                    tex_smooth(0.0f, 0.04f, ax);
        float vs = (j > -0.3f) & (j < sVe[i]) ? vs0 : 0.0f;
        /* Basal veins (the two lowest of the five from the junction). */
        vp = ivy_basal(vp, u, C.bvx[0], C.bvy[0], C.vby[0], C.vbx[0], C.blen[0], s, lp);
        vp = ivy_basal(vp, u, C.bvx[1], C.bvy[1], C.vby[1], C.vbx[1], C.blen[1], s, lp);
        float vein = tex_maxf(vp, 0.6f * vs);
        float rho = sqrtf(u * u + vv) / len0; /* 0 at the junction, 1 at the tip */
        float toward = tex_smooth(0.55f, 1.0f, rel);
        float edge = 1.0f - tex_smooth(0.5f, 3.0f, dpx);
        float tin = tex_smooth(0.0f, 0.45f, rho), sh = 0.93f + 0.07f * gr;
        sR[i] = ivy_shade(C.inner[0], C.col[0], C.edge[0], C.vein[0], tin, toward, sh, vein, edge);
        sG[i] = ivy_shade(C.inner[1], C.col[1], C.edge[1], C.vein[1], tin, toward, sh, vein, edge);
        sB[i] = ivy_shade(C.inner[2], C.col[2], C.edge[2], C.vein[2], tin, toward, sh, vein, edge);
        /* Puckered between the veins: veins sunken, blade domed. */
        sU[i] = (1.5f * (1.0f - rel * rel) - 1.0f * vp - 0.6f * vs + 0.12f * gr) * tex_clampf(bw * lp * 0.25f, 0.0f, 1.0f);
    }
}

static void ivy_leaf(cell *k, const ivleaf *L) {
    const float s = (float)k->size;
    const int n = k->c->n;
    const int tile = n < TEX_TILE ? n : TEX_TILE, tm = tile - 1;
    span_begin(k);
    for (int i = 0; i < 3; i++) {
        const kleaf *B = &L->lobe[i];
        float nx = B->dy, ny = -B->dx;
        for (int sd = 0; sd < 2; sd++) {
            float pu0 = B->bx, pv0 = B->by;
            for (int j = 1; j <= KT; j++) {
                float y = (float)j / KT, x = (sd ? 1.0f : -1.0f) * L->tab[i].w[sd][j];
                float pu1 = B->bx + (B->dx * y + nx * x) * B->len, pv1 = B->by + (B->dy * y + ny * x) * B->len;
                span_edge(k, pu0, pv0, pu1, pv1);
                pu0 = pu1, pv0 = pv1;
            }
        }
    }
    float inv_len[3], lens[3], vslope[3]; /* per lobe: 1 / length, length in pixels, 1 / |(1, slope)| */
    for (int i = 0; i < 3; i++) {
        inv_len[i] = 1.0f / L->lobe[i].len;
        lens[i] = L->lobe[i].len * s;
        vslope[i] = 1.0f / sqrtf(1.0f + L->lobe[i].slope * L->lobe[i].slope);
    }
    /* Basal veins: from the junction into the lower halves of the side lobes. */
    float bvx[2], bvy[2], blen[2];
    for (int sd = 0; sd < 2; sd++) {
        const kleaf *B = &L->lobe[1 + sd];
        float a = dm_atan2f(B->dx, B->dy) + (sd ? -1.0f : 1.0f) * L->basal;
        bvx[sd] = dm_sinf(a), bvy[sd] = dm_cosf(a), blen[sd] = 0.42f * B->len;
    }
    /* Lobe i can only matter where 0 < y < 1 and its distance is over
     * -0.5 px (else coverage is 0, whichever lobe is nearest): |x| under
     * wmax + 0.5 px / (length * gmin), wmax and gmin the table's largest
     * half-width and smallest slope factor (interpolation stays within
     * them); 1 px is used. Per row that is a span of columns, one pixel
     * wider each way for rounding. */
    float wlim[3];
    for (int i = 0; i < 3; i++) {
        float wm = 0.0f, gm = 1.0f;
        for (int sd = 0; sd < 2; sd++)
            for (int j = 0; j <= KT; j++) wm = tex_maxf(wm, L->tab[i].w[sd][j]), gm = tex_minf(gm, L->tab[i].g[sd][j]);
        wlim[i] = wm + 1.0f / (lens[i] * gm);
    }
    tex_canvas *const cv = k->c;
    const float *const grain = cv->grain;
    const float len0 = L->lobe[0].len;
    float ldx[3], ldy[3], lslope[3], lq0[3], ldq[3], lveins[3], llen[3];
    for (int i = 0; i < 3; i++) {
        ldx[i] = L->lobe[i].dx, ldy[i] = L->lobe[i].dy, lslope[i] = L->lobe[i].slope, llen[i] = L->lobe[i].len;
        lq0[i] = L->tab[i].q0, ldq[i] = L->tab[i].dq, lveins[i] = (float)L->lobe[i].veins - 0.2f;
    }
    float lcol[3], ledge[3], lvein[3], linner[3];
    for (int ch = 0; ch < 3; ch++) lcol[ch] = L->col[ch], ledge[ch] = L->edge[ch], lvein[ch] = L->vein[ch], linner[ch] = L->inner[ch];
    int r0, r1;
    span_end(k, &r0, &r1);
    for (int r = r0; r <= r1; r++) {
        const int yy = k->y0 + r;
        const float v = pv(k, yy) - L->jy;
        const int xa = k->x0 + k->xmin[r], xb = k->x0 + k->xmax[r];
        float vdy[3], vdx[3];
        int lo[3], hi[3];
        for (int i = 0; i < 3; i++) {
            vdy[i] = v * ldy[i], vdx[i] = v * ldx[i];
            /* u range with 0 < (u dx + v dy) / len < 1 and |u dy - v dx| / len < wlim. */
            float ulo = -1e9f, uhi = 1e9f;
            const float c[2] = {ldx[i], ldy[i]}, b[2] = {vdy[i], -vdx[i]};
            const float lim_lo[2] = {0.0f, -wlim[i] * llen[i]}, lim_hi[2] = {llen[i], wlim[i] * llen[i]};
            for (int e = 0; e < 2; e++) {
                if (fabsf(c[e]) < 1e-6f) {
                    if (b[e] < lim_lo[e] - 1e-4f || b[e] > lim_hi[e] + 1e-4f) ulo = 1e9f, uhi = -1e9f;
                    continue;
                }
                float t0 = (lim_lo[e] - b[e]) / c[e], t1 = (lim_hi[e] - b[e]) / c[e];
                ulo = tex_maxf(ulo, tex_minf(t0, t1)), uhi = tex_minf(uhi, tex_maxf(t0, t1));
            }
            if (ulo > uhi) {
                lo[i] = 1, hi[i] = 0;
                continue;
            }
            /* u = (xx - x0 + 0.5) / s - jx */
            float xl = (ulo + L->jx) * s + (float)k->x0 - 0.5f, xh = (uhi + L->jx) * s + (float)k->x0 - 0.5f;
            lo[i] = xl < (float)xa ? xa : (int)floorf(xl) - 1;
            hi[i] = xh > (float)xb ? xb : (int)ceilf(xh) + 1;
        }
        const float vbx[2] = {v * bvx[0], v * bvx[1]}, vby[2] = {v * bvy[0], v * bvy[1]};
        const float vv = v * v;
        const float *grow = grain + (size_t)(yy & tm) * tile;
        /* Pass 1: the nearest lobe of each pixel; covered ones listed. */
        float *const sU = k->scr, *const sD = sU + k->size, *const sY = sD + k->size, *const sX = sY + k->size;
        float *const sW = sX + k->size, *const sCov = sW + k->size, *const sLp = sCov + k->size;
        float *const sSl = sLp + k->size, *const sQ0 = sSl + k->size, *const sDq = sQ0 + k->size;
        float *const sVe = sDq + k->size, *const sVs = sVe + k->size, *const sGr = sVs + k->size;
        float *const sR = sGr + k->size, *const sG = sR + k->size, *const sB = sG + k->size;
        int *const sXX = k->cols;
        int m = 0;
        for (int xx = xa; xx <= xb; xx++) {
            float u = pu(k, xx) - L->jx;
            /* The lobe the pixel is deepest inside: its distance is the leaf's. */
            float best = -1e9f, by = 0.0f, bx = 0.0f, bw = 1.0f;
            int bi = 0;
            for (int i = 0; i < 3; i++) {
                if (xx < lo[i] || xx > hi[i]) continue;
                float il = inv_len[i];
                float y = (u * ldx[i] + vdy[i]) * il, x = (u * ldy[i] - vdx[i]) * il;
                if (y <= 0.0f || y >= 1.0f) continue;
                int side = x > 0.0f;
                float fi = y * KT;
                int ti = (int)fi;
                float fr = fi - (float)ti;
                if (ti >= KT) ti = KT - 1, fr = 1.0f;
                const float *tw = L->tab[i].w[side], *tg = L->tab[i].g[side];
                float w = tw[ti] + (tw[ti + 1] - tw[ti]) * fr;
                float g = tg[ti] + (tg[ti + 1] - tg[ti]) * fr;
                float d = (w - fabsf(x)) * lens[i] * g;
                if (d > best) best = d, bi = i, by = y, bx = x, bw = w;
            }
            float dpx = best;
            if (dpx + 0.5f <= 0.0f) continue; /* coverage 0 */
            float cov = tex_clampf(dpx + 0.5f, 0.0f, 1.0f) * tex_clampf(bw * llen[bi] * s, 0.0f, 1.0f);
            if (cov <= 0.0f) continue;
            sU[m] = u, sD[m] = dpx, sY[m] = by, sX[m] = bx, sW[m] = bw, sCov[m] = cov, sLp[m] = lens[bi];
            sSl[m] = lslope[bi], sQ0[m] = lq0[bi], sDq[m] = ldq[bi], sVe[m] = lveins[bi], sVs[m] = vslope[bi];
            sGr[m] = grow[xx & tm];
            sXX[m++] = xx;
        }
        /* Pass 2: shading, no branches. */
        const ivy_consts C = {{bvx[0], bvx[1]}, {bvy[0], bvy[1]}, {vbx[0], vbx[1]}, {vby[0], vby[1]}, {blen[0], blen[1]},
                              {linner[0], linner[1], linner[2]}, {lcol[0], lcol[1], lcol[2]},
                              {ledge[0], ledge[1], ledge[2]}, {lvein[0], lvein[1], lvein[2]}, s, vv, len0};
        ivy_shade_row(&C, m, sU, sD, sY, sX, sW, sLp, sSl, sQ0, sDq, sVe, sVs, sGr, sR, sG, sB);
        /* Pass 3: into the canvas. */
        put_row(cv, (size_t)yy * n, m, sXX, sR, sG, sB, sU, sCov);
    }
}

static void ivy_colours(ivleaf *L, int season, pcg32 *r) {
    float c[3], in[3];
    if (season == BANYAN_SEASON_SUMMER) {
        /* Rich green (the gloss is the material's roughness), a little
         * lighter now and then; the young unlobed leaves of the right-hand
         * column flush reddish-bronze, some more olive (plants.md). */
        const float dark[3] = {56, 96, 30}, light[3] = {96, 124, 46};
        const float bronze[3] = {150, 80, 44}, olive[3] = {128, 96, 42};
        float b = tex_unif(r, 0.88f, 1.12f);
        if (L->lobed) {
            float y = tex_unif(r, 0.0f, 0.2f);
            for (int i = 0; i < 3; i++) c[i] = tex_mix(dark[i], light[i], y) * b;
        } else {
            float y = tex_unif(r, 0.0f, 0.45f);
            for (int i = 0; i < 3; i++) c[i] = tex_mix(bronze[i], olive[i], y) * b;
        }
        for (int i = 0; i < 3; i++) in[i] = c[i] * 1.05f;
        for (int i = 0; i < 3; i++) {
            L->vein[i] = tex_mix(c[i], 175.0f - (float)i * 35.0f, 0.33f);
            L->edge[i] = c[i] * 0.75f;
        }
    } else {
        /* Scarlet, crimson, burgundy-purple, orange; greener-orange near
         * the petiole where the colour turns last. */
        static const float pal[5][3] = {{186, 32, 26}, {150, 18, 36}, {96, 22, 52}, {204, 84, 28}, {170, 50, 30}};
        static const float w[5] = {0.3f, 0.28f, 0.2f, 0.1f, 0.12f};
        float x = (float)rng_uniform(r), acc = 0.0f;
        int p = 4;
        for (int i = 0; i < 5; i++) {
            acc += w[i];
            if (x < acc) { p = i; break; }
        }
        float b = tex_unif(r, 0.88f, 1.1f);
        for (int i = 0; i < 3; i++) c[i] = pal[p][i] * b;
        const float warm[3] = {200, 110, 40};
        float m = tex_unif(r, 0.0f, 0.45f);
        for (int i = 0; i < 3; i++) in[i] = tex_mix(c[i], warm[i], m);
        for (int i = 0; i < 3; i++) {
            L->vein[i] = tex_mix(c[i], 225.0f - (float)i * 60.0f, 0.25f);
            L->edge[i] = c[i] * 0.7f;
        }
    }
    memcpy(L->col, c, sizeof c);
    memcpy(L->inner, in, sizeof in);
}

/* ------------------------------------------------------------ atlases */

/* The grain (cells of 4 px) and mottle tiles, TEX_TILE pixels a side (or
 * the image's side when smaller): grain repeats across the atlas, mottle
 * is stretched over it. */
static void free_fields(tex_canvas *c) {
    free(c->grain);
    free(c->mottle);
    c->grain = c->mottle = NULL;
}

static int leaf_fields(tex_canvas *c, pcg32 *rng) {
    const int t = c->n < TEX_TILE ? c->n : TEX_TILE;
    c->grain = malloc(sizeof(float) * (size_t)t * t);
    c->mottle = malloc(sizeof(float) * (size_t)t * t);
    tex_fbm g, m;
    memset(&g, 0, sizeof g);
    memset(&m, 0, sizeof m);
    int rc = !c->grain || !c->mottle || tex_fbm_init(&g, t, t / 4, t / 4, 1, 1.0f, 0.5f, 4, rng) ||
             tex_fbm_init(&m, t, 8, 8, 3, 1.0f, 0.5f, 4, rng);
    if (!rc) {
        tex_fbm_rows(&g, c->grain, 0, t);
        tex_fbm_rows(&m, c->mottle, 0, t);
    }
    tex_fbm_free(&g);
    tex_fbm_free(&m);
    if (rc) free_fields(c);
    return rc ? -1 : 0;
}

int tex_paint_keyaki_leaves(tex_canvas *c, int season, pcg32 *rng) {
    int cols, rows;
    float aspect;
    tex_leaf_grid(BANYAN_TEX_KEYAKI_LEAF, &cols, &rows, &aspect);
    if (leaf_fields(c, rng)) return -1;
    int cs = c->n / cols;
    int *spans = malloc(sizeof(int) * 3 * (size_t)cs);
    float *scr = malloc(sizeof(float) * LEAF_SCR * (size_t)cs);
    int ss = c->n / LEAF_KEYAKI_SPRAYS; /* a spray's square cell */
    int *spans2 = malloc(sizeof(int) * 3 * (size_t)ss);
    float *scr2 = malloc(sizeof(float) * LEAF_SCR * (size_t)ss);
    if (!spans || !scr || !spans2 || !scr2) {
        free(spans);
        free(scr);
        free(spans2);
        free(scr2);
        free_fields(c);
        return -1;
    }
    /* 12 single leaves in the rows above the sprays, each its own: length
     * / width and summer lightness spread evenly over their ranges
     * (shuffled over 16 draws, so the 12 keep the 4 x 4 atlas's), up to
     * three young leaves in summer, a bent midrib in about a third; in
     * autumn atlas row j (from the top) is tone j: yellow, orange, rust
     * (red-purple leaves are in the sprays, whose leaves mix all four). */
    int nc = cols * rows, pr[64], pl[64], py[64];
    for (int i = 0; i < nc && i < 64; i++) pr[i] = pl[i] = py[i] = i;
    for (int i = nc - 1; i > 0; i--) {
        int a = (int)rng_below(rng, (uint32_t)i + 1), b = (int)rng_below(rng, (uint32_t)i + 1),
            d = (int)rng_below(rng, (uint32_t)i + 1), t;
        t = pr[i], pr[i] = pr[a], pr[a] = t;
        t = pl[i], pl[i] = pl[b], pl[b] = t;
        t = py[i], py[i] = py[d], py[d] = t;
    }
    for (int j = 0; j + 1 < rows; j++)
        for (int i = 0; i < cols && !tex_stopped(c); i++) {
            int id = i + j * cols;
            cell k = {c, i * cs, j * cs, cs, cs >= 64 ? 2 : 1, spans, spans + cs, 0, 0, scr, spans + 2 * cs, 0};
            float ratio = 1.85f + 1.05f * ((float)pr[id] + tex_unif(rng, 0.0f, 1.0f)) / (float)nc;
            float light = -1.0f + 2.0f * ((float)pl[id] + tex_unif(rng, 0.0f, 1.0f)) / (float)nc;
            float bend = rng_uniform(rng) < 0.35 ? (rng_uniform(rng) < 0.5 ? -1.0f : 1.0f) * tex_unif(rng, 0.025f, 0.06f)
                                                 : tex_unif(rng, -0.008f, 0.008f);
            int tone = season == BANYAN_SEASON_SUMMER ? py[id] < 3 : j % 4;
            keyaki_cell(&k, season, tone, light, ratio, ratio > 2.45f, bend, rng);
        }
    /* The bottom row: LEAF_KEYAKI_SPRAYS sprays, each a square cell of
     * twice the side whose lower half is the spray. */
    for (int i = 0; i < LEAF_KEYAKI_SPRAYS && !tex_stopped(c); i++) {
        int ss = c->n / LEAF_KEYAKI_SPRAYS;
        cell k = {c, i * ss, (rows - 1) * cs - (ss - cs), ss, cs >= 64 ? 2 : 1, spans2, spans2 + ss, 0, 0, scr2,
                  spans2 + 2 * ss, ss - cs};
        keyaki_spray(&k, season, rng);
    }
    free(spans2);
    free(scr2);
    free(spans);
    free(scr);
    free_fields(c);
    c->relief = 1.2f * (float)c->n / 1024.0f; /* the same slopes at every size */
    c->wrap = 0;
    return 0;
}

int tex_paint_ivy_leaves(tex_canvas *c, int season, pcg32 *rng) {
    int cols, rows;
    float aspect;
    tex_leaf_grid(BANYAN_TEX_IVY_LEAF, &cols, &rows, &aspect);
    if (leaf_fields(c, rng)) return -1;
    int cs = c->n / cols;
    int *spans = malloc(sizeof(int) * 3 * (size_t)cs);
    float *scr = malloc(sizeof(float) * LEAF_SCR * (size_t)cs);
    if (!spans || !scr) {
        free(spans);
        free(scr);
        free_fields(c);
        return -1;
    }
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < cols && !tex_stopped(c); i++) {
            cell k = {c, i * cs, j * cs, cs, cs >= 64 ? 2 : 1, spans, spans + cs, 0, 0, scr, spans + 2 * cs, 0};
            ivleaf L;
            /* A quarter of the cells: young unlobed leaves (long shoots). */
            L.lobed = ((i + j * cols) % 4) != 3;
            ivy_shape(&L, rng);
            ivy_colours(&L, season, rng);
            /* Fit: the widest extent sideways and the height, junction placed
             * so the tip reaches 4 % below the top; a petiole stub below it. */
            float side, up, down;
            ivy_extent(&L, &side, &up, &down);
            float R = tex_minf(0.45f / side, 0.80f / (up + down)) * tex_unif(rng, 0.92f, 1.0f);
            ivy_place(&L, R, 0.5f, 0.96f - up * R);
            const float pet[3] = {season ? 150.0f : 96.0f, season ? 60.0f : 110.0f, season ? 40.0f : 50.0f};
            float mean[3];
            for (int ch = 0; ch < 3; ch++) mean[ch] = 0.5f * (L.col[ch] + L.inner[ch]);
            fill_cell(&k, mean);
            stroke(&k, 0.5f, 0.0f, L.jx, L.jy, 0.011f, 0.008f, pet, 0.2f);
            ivy_leaf(&k, &L);
        }
    free(spans);
    free(scr);
    free_fields(c);
    c->relief = 1.2f * (float)c->n / 1024.0f; /* the same slopes at every size */
    c->wrap = 0;
    return 0;
}
