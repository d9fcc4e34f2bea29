/* leaves.c - leaf atlases (issue #17; docs/materials.md "Leaves"):
 * keyaki (Zelkova serrata) and Boston ivy (Parthenocissus tricuspidata).
 * Each leaf is an implicit shape evaluated per pixel inside its bounding
 * box: keyaki blades by a half-width profile along the midrib (ovate,
 * acuminate tip, slightly lopsided base) whose margin carries one
 * forward-pointing tooth at the end of each straight lateral vein; ivy
 * blades by a polar radius around the petiole junction (three pointed
 * lobes or one, cordate base, coarse teeth) with five palmate primary
 * veins. Profiles are tabulated per leaf, the edge is antialiased from its
 * distance in pixels. Keyaki cells hold a small spray (leaves alternate on
 * a zigzag twiglet), ivy cells one leaf. Colour is straight alpha; pixels
 * outside leaves get the cell's mean leaf colour at alpha 0, so mipmaps
 * and texture filtering do not bleed a dark fringe. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "textures/tex_internal.h"

#define PI_F 3.14159265f

/* A cell of the atlas in pixels: u right, v up, both 0..1 over the cell. */
typedef struct cell {
    tex_canvas *c;
    int x0, y0, size; /* top-left pixel, side */
    int margin;       /* pixels kept clear at the cell's border */
} cell;

/* Straight-alpha "over" of one covered pixel. */
static inline void put(tex_canvas *c, size_t i, float cov, const float col[3], float h) {
    uint8_t *p = c->rgba + 4 * i;
    float a0 = (float)p[3] * (1.0f / 255.0f);
    float a = cov + a0 * (1.0f - cov);
    if (a <= 0.0f) return;
    float wb = a0 * (1.0f - cov) / a, wf = cov / a;
    for (int ch = 0; ch < 3; ch++) p[ch] = tex_byte(col[ch] * wf + (float)p[ch] * wb);
    p[3] = tex_byte(a * 255.0f);
    c->height[i] = h * cov + c->height[i] * (1.0f - cov);
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
    int lo_y = k->y0 + k->margin, hi_y = k->y0 + k->size - 1 - k->margin;
    if (*x0 < lo_x) *x0 = lo_x;
    if (*x1 > hi_x) *x1 = hi_x;
    if (*y0 < lo_y) *y0 = lo_y;
    if (*y1 > hi_y) *y1 = hi_y;
}

/* Cell coordinates of a pixel centre. */
static inline float pu(const cell *k, int x) { return ((float)(x - k->x0) + 0.5f) / (float)k->size; }
static inline float pv(const cell *k, int y) { return 1.0f - ((float)(y - k->y0) + 0.5f) / (float)k->size; }

/* A tapered round stroke (twig, petiole) from a to b, widths in cell units. */
static void stroke(const cell *k, float ax, float ay, float bx, float by, float wa, float wb, const float col[3],
                   float h) {
    float pad = (wa > wb ? wa : wb) + 2.0f / (float)k->size;
    int x0, x1, y0, y1;
    bounds(k, fminf(ax, bx) - pad, fmaxf(ax, bx) + pad, fminf(ay, by) - pad, fmaxf(ay, by) + pad, &x0, &x1, &y0,
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
    float blot;           /* autumn: strength of brown blotches */
    float blotcol[3];
} kleaf;

/* Smooth half-width (without teeth) at t in 0..1 for one side. */
static float keyaki_w0(const kleaf *L, float t) {
    if (t <= 0.0f || t >= 1.0f) return 0.0f;
    float p = logf(0.5f) / logf(L->ymax);
    float f = sinf(PI_F * powf(t, p));
    f = powf(f, 1.0f + L->acum * tex_smooth(0.45f, 1.0f, t));
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
    float w[2][KT + 1]; /* half-widths with teeth, left (0) and right (1) */
    float g[2][KT + 1]; /* 1 / sqrt(1 + w'^2): edge distance from the horizontal one */
    float q0, dq;       /* lateral veins: q = y - |x| * slope, vein j at q0 + j * dq */
} ktab;

static void keyaki_table(const kleaf *L, ktab *T) {
    T->q0 = 0.06f;
    T->dq = (0.93f - T->q0) / (float)L->veins;
    for (int side = 0; side < 2; side++) {
        float sk = side ? L->skew : 0.0f, sc = side ? 0.95f : 1.0f;
        for (int i = 0; i <= KT; i++) {
            float y = (float)i / KT;
            float t = (y - sk) / (1.0f - sk);
            float w0 = sc * keyaki_w0(L, t);
            float ph = (y - w0 * L->slope - T->q0) / T->dq; /* vein index reaching the margin here */
            float env = tex_smooth(0.10f, 0.26f, y) * (1.0f - tex_smooth(0.86f, 0.99f, y));
            float depth = 0.028f * env;
            float w = w0 - depth * (1.0f - keyaki_tooth(ph));
            T->w[side][i] = w > 0.0f ? w : 0.0f;
        }
        for (int i = 0; i <= KT; i++) {
            int a = i > 0 ? i - 1 : 0, b = i < KT ? i + 1 : KT;
            float d = (T->w[side][b] - T->w[side][a]) * KT / (float)(b - a);
            T->g[side][i] = 1.0f / sqrtf(1.0f + d * d);
        }
    }
}

static void keyaki_leaf(const cell *k, const kleaf *L, const tex_noise *grain) {
    ktab T;
    keyaki_table(L, &T);
    const float s = (float)k->size, lp = L->len * s; /* blade length in pixels */
    const int n = k->c->n;
    float nx = L->dy, ny = -L->dx; /* to the right of the midrib */
    /* Box of the blade: base, tip and the widest points. */
    float hw = L->half * L->len * 1.05f;
    float tipx = L->bx + L->dx * L->len, tipy = L->by + L->dy * L->len;
    float umin = fminf(L->bx, tipx) - hw, umax = fmaxf(L->bx, tipx) + hw;
    float vmin = fminf(L->by, tipy) - hw, vmax = fmaxf(L->by, tipy) + hw;
    int x0, x1, y0, y1;
    bounds(k, umin, umax, vmin, vmax, &x0, &x1, &y0, &y1);
    const float vslope = sqrtf(1.0f + L->slope * L->slope);
    for (int yy = y0; yy <= y1; yy++) {
        for (int xx = x0; xx <= x1; xx++) {
            float u = pu(k, xx) - L->bx, v = pv(k, yy) - L->by;
            float y = (u * L->dx + v * L->dy) / L->len, x = (u * nx + v * ny) / L->len;
            if (y <= 0.0f || y >= 1.0f) continue;
            int side = x > 0.0f;
            float ax = fabsf(x);
            float fi = y * KT;
            int i = (int)fi;
            float fr = fi - (float)i;
            if (i >= KT) i = KT - 1, fr = 1.0f;
            float w = T.w[side][i] + (T.w[side][i + 1] - T.w[side][i]) * fr;
            float g = T.g[side][i] + (T.g[side][i + 1] - T.g[side][i]) * fr;
            float dpx = (w - ax) * lp * g; /* signed distance to the margin, pixels */
            float cov = tex_clampf(dpx + 0.5f, 0.0f, 1.0f);
            if (cov <= 0.0f) continue;
            /* Veins: midrib, then the straight laterals (q = const lines). */
            float mid_w = (0.010f * (1.0f - y) + 0.003f) * lp;
            float vm = 1.0f - tex_smooth(mid_w, mid_w + 0.9f, ax * lp);
            float q = y - ax * L->slope;
            float j = (q - T.q0) / T.dq;
            float vl = 0.0f;
            if (j > -0.3f && j < (float)L->veins - 0.2f) {
                float dj = fabsf(j - floorf(j + 0.5f)) * T.dq / vslope * lp; /* px to the nearest lateral */
                float rel = w > 1e-5f ? ax / w : 1.0f;
                float lw = (0.0045f * (1.0f - 0.6f * rel)) * lp;
                vl = (1.0f - tex_smooth(lw, lw + 0.9f, dj)) * (1.0f - tex_smooth(0.82f, 1.0f, rel));
                vl *= tex_smooth(0.0f, 0.05f, ax);
            }
            float vein = fmaxf(vm, 0.75f * vl);
            float rel = w > 1e-5f ? ax / w : 1.0f;
            float gr = tex_noise_at(grain, (float)xx * 0.25f, (float)yy * 0.25f);
            float shade = (side ? 0.96f : 1.0f) * (0.93f + 0.07f * gr);
            float edge = 1.0f - tex_smooth(0.5f, 3.0f, dpx);           /* a dark rim */
            float toward = tex_smooth(0.55f, 1.0f, rel) * 0.35f;        /* darker toward the margin */
            float col[3];
            float bl = 0.0f;
            if (L->blot > 0.0f) {
                float b = tex_noise_at(grain, (float)xx * 0.06f + 17.0f, (float)yy * 0.06f + 5.0f);
                bl = L->blot * tex_smooth(0.15f, 0.55f, b);
            }
            for (int ch = 0; ch < 3; ch++) {
                float cc = tex_mix(L->col[ch], L->edge[ch], toward) * shade;
                cc = tex_mix(cc, L->blotcol[ch], bl);
                cc = tex_mix(cc, L->vein[ch], vein * 0.8f);
                col[ch] = tex_mix(cc, L->edge[ch] * 0.8f, edge * 0.6f);
            }
            float h = 2.0f * (1.0f - rel * rel) - 1.2f * vl - 0.8f * vm + 0.15f * gr;
            put(k->c, (size_t)yy * n + xx, cov, col, h);
        }
    }
}

/* Colours (sRGB 0..255). */
static void keyaki_colours(kleaf *L, int season, int tone, pcg32 *r) {
    float c[3];
    if (season == BANYAN_SEASON_SUMMER) {
        /* Mid green; some leaves yellower (sun), some bluer and darker. */
        const float mid[3] = {78, 118, 44}, yel[3] = {112, 140, 52}, blu[3] = {56, 96, 50};
        float a = tex_unif(r, -1.0f, 1.0f), b = tex_unif(r, 0.88f, 1.08f);
        for (int i = 0; i < 3; i++) c[i] = (a > 0 ? tex_mix(mid[i], yel[i], a * 0.8f) : tex_mix(mid[i], blu[i], -a)) * b;
        for (int i = 0; i < 3; i++) {
            L->col[i] = c[i];
            L->vein[i] = tex_mix(c[i], 200.0f - (float)i * 40.0f, 0.30f);
            L->edge[i] = c[i] * 0.72f;
        }
        L->blot = 0.0f;
        memcpy(L->blotcol, L->col, sizeof c);
        return;
    }
    /* Autumn: each spray leans to one tone (trees differ), leaves mix. */
    static const float pal[4][3] = {{212, 168, 48}, {214, 118, 36}, {156, 76, 36}, {128, 46, 34}};
    int t2 = (int)rng_below(r, 4);
    float m = tex_unif(r, 0.0f, 0.6f);
    float b = tex_unif(r, 0.9f, 1.07f);
    for (int i = 0; i < 3; i++) c[i] = tex_mix(pal[tone][i], pal[t2][i], m) * b;
    float green = rng_uniform(r) < 0.15 ? tex_unif(r, 0.15f, 0.4f) : 0.0f; /* a leaf still turning */
    const float g[3] = {110, 128, 50};
    for (int i = 0; i < 3; i++) {
        c[i] = tex_mix(c[i], g[i], green);
        L->col[i] = c[i];
        L->vein[i] = tex_mix(c[i], 230.0f - (float)i * 50.0f, 0.28f);
        L->edge[i] = c[i] * 0.7f;
        L->blotcol[i] = c[i] * 0.62f;
    }
    L->blot = tex_unif(r, 0.0f, 0.5f);
}

/* One spray: a zigzag twiglet from the cell's bottom centre with leaves
 * alternate on it (two-ranked), largest below the middle, small at the
 * tip; one or two side twiglets. Built in cell units, then scaled about
 * the base so everything fits the cell. */
#define KMAX 40
typedef struct kseg { float ax, ay, bx, by, wa, wb; } kseg;

static void keyaki_spray(const cell *k, int season, pcg32 *r, const tex_noise *grain) {
    kleaf leaves[KMAX];
    kseg segs[KMAX];
    int nl = 0, ns = 0;
    int tone = (int)rng_below(r, 3);
    /* Axes: 0 main, then side twiglets from the lower nodes. */
    struct axis { float x, y, a; int nodes; float lmax, w; } axes[3];
    int na = 1;
    axes[0].x = 0.5f, axes[0].y = 0.0f, axes[0].a = tex_unif(r, -0.12f, 0.12f);
    axes[0].nodes = 7 + (int)rng_below(r, 3), axes[0].lmax = tex_unif(r, 0.17f, 0.21f), axes[0].w = 0.0085f;
    int sides = 1 + (int)rng_below(r, 2);
    float side_sign = rng_uniform(r) < 0.5 ? -1.0f : 1.0f;
    for (int ax = 0; ax < na && ax < 3; ax++) {
        float x = axes[ax].x, y = axes[ax].y, a = axes[ax].a, w = axes[ax].w;
        int nodes = axes[ax].nodes;
        float internode = (ax == 0 ? 0.86f : 0.42f) / (float)(nodes + 1);
        /* A bare stretch before the first leaf. */
        float first = ax == 0 ? 0.10f : 0.03f;
        float nxp = x + sinf(a) * first, nyp = y + cosf(a) * first;
        segs[ns++] = (kseg){x, y, nxp, nyp, w, w * 0.95f};
        x = nxp, y = nyp, w *= 0.95f;
        float side = rng_uniform(r) < 0.5 ? -1.0f : 1.0f;
        for (int i = 0; i < nodes && nl < KMAX - 1 && ns < KMAX - 1; i++) {
            float t = (float)i / (float)(nodes - 1 > 0 ? nodes - 1 : 1);
            kleaf *L = &leaves[nl++];
            float size = axes[ax].lmax * (0.62f + 0.38f * sinf(PI_F * (0.25f + 0.6f * t))) * (1.0f - 0.45f * t * t);
            size *= tex_unif(r, 0.9f, 1.08f);
            float la = a + side * tex_unif(r, 0.55f, 0.95f);       /* leaf angle off the twig, forward */
            float pet = size * tex_unif(r, 0.04f, 0.08f);          /* short petiole */
            float dx = sinf(la), dy = cosf(la);
            L->bx = x + dx * pet, L->by = y + dy * pet, L->dx = dx, L->dy = dy;
            L->len = size;
            L->half = tex_unif(r, 0.19f, 0.25f);
            L->ymax = tex_unif(r, 0.28f, 0.38f);
            L->acum = tex_unif(r, 0.7f, 1.5f);
            L->veins = 8 + (int)rng_below(r, 6);
            L->slope = tex_unif(r, 0.75f, 1.05f);
            L->skew = tex_unif(r, 0.0f, 0.05f) * (side > 0 ? 1.0f : -1.0f);
            if (L->skew < 0) L->skew = -L->skew; /* the lower half on the twig's outer side */
            keyaki_colours(L, season, tone, r);
            /* Side twiglet from this node's axil (main axis, lower nodes). */
            if (ax == 0 && na < 1 + sides && i >= 1 && i <= 3 && rng_uniform(r) < 0.6) {
                axes[na].x = x, axes[na].y = y;
                axes[na].a = a + side_sign * tex_unif(r, 0.5f, 0.8f);
                side_sign = -side_sign;
                axes[na].nodes = 3 + (int)rng_below(r, 3);
                axes[na].lmax = axes[0].lmax * 0.85f;
                axes[na].w = w * 0.6f;
                na++;
            }
            /* Zigzag: the twig bends away from the leaf at each node. */
            a -= side * tex_unif(r, 0.08f, 0.2f);
            a = tex_clampf(a, axes[ax].a - 0.35f, axes[ax].a + 0.35f);
            float l = internode * tex_unif(r, 0.85f, 1.15f);
            float x2 = x + sinf(a) * l, y2 = y + cosf(a) * l;
            segs[ns++] = (kseg){x, y, x2, y2, w, w * 0.9f};
            x = x2, y = y2, w *= 0.9f;
            side = -side;
        }
    }
    /* Fit: scale about the base (0.5, 0) so blades stay inside the cell. */
    float sc = 1.0f;
    for (int i = 0; i < nl; i++) {
        const kleaf *L = &leaves[i];
        float px[3] = {L->bx + L->dx * L->len, L->bx + L->dx * L->len * 0.35f + L->dy * L->half * L->len,
                       L->bx + L->dx * L->len * 0.35f - L->dy * L->half * L->len};
        float py[3] = {L->by + L->dy * L->len, L->by + L->dy * L->len * 0.35f - L->dx * L->half * L->len,
                       L->by + L->dy * L->len * 0.35f + L->dx * L->half * L->len};
        for (int j = 0; j < 3; j++) {
            float ex = fabsf(px[j] - 0.5f), ey = py[j];
            if (ex * sc > 0.45f) sc = 0.45f / ex;
            if (ey * sc > 0.95f) sc = 0.95f / ey;
        }
    }
    const float twig[3] = {112, 92, 72};
    const float pcol[3] = {120, 130, 60};
    for (int i = 0; i < nl; i++) {
        kleaf *L = &leaves[i];
        float ox = 0.5f + (L->bx - L->dx * L->len * 0.06f - 0.5f) * sc, oy = (L->by - L->dy * L->len * 0.06f) * sc;
        L->bx = 0.5f + (L->bx - 0.5f) * sc, L->by *= sc, L->len *= sc;
        float pc[3];
        for (int c = 0; c < 3; c++) pc[c] = tex_mix(pcol[c], L->col[c], 0.5f);
        stroke(k, ox, oy, L->bx + L->dx * 0.01f, L->by + L->dy * 0.01f, 0.0032f, 0.0025f, pc, 0.5f);
        keyaki_leaf(k, L, grain);
    }
    for (int i = 0; i < ns; i++) {
        kseg g = segs[i];
        stroke(k, 0.5f + (g.ax - 0.5f) * sc, g.ay * sc, 0.5f + (g.bx - 0.5f) * sc, g.by * sc, g.wa * sc, g.wb * sc,
               twig, 1.0f);
    }
}

/* ---------------------------------------------------------------- ivy */

#define IT 1024 /* polar samples around an ivy blade */

typedef struct ivleaf {
    float jx, jy;       /* petiole junction (cell units) */
    float R;            /* scale of the radius profile, cell units */
    int lobed;
    float lob_a, lob_c; /* angle of the side lobes from the tip (rad), their relative length */
    float col[3], vein[3], edge[3], inner[3];
} ivleaf;

static float ivy_radius(const ivleaf *L, float phi, float teeth_amp, int nt) {
    float a = fabsf(phi);
    /* Round core, cordate base: the radius falls into the petiole sinus. */
    float core = (L->lobed ? 0.50f : 0.62f) * (1.0f - 0.92f * powf(tex_smooth(0.62f * PI_F, PI_F, a), 0.6f));
    float r4 = powf(core, 4.0f);
    /* Pointed lobes: radius linear in the angle off the lobe's axis (a cusp). */
    float wc = L->lobed ? 0.55f : 1.2f;
    float dc = a / wc;
    if (dc < 1.0f) r4 += powf(1.0f * powf(1.0f - dc, L->lobed ? 1.25f : 1.6f), 4.0f);
    if (L->lobed) {
        float ds = fabsf(a - L->lob_a) / 0.55f;
        if (ds < 1.0f) r4 += powf(L->lob_c * powf(1.0f - ds, 1.25f), 4.0f);
    }
    float r = powf(r4, 0.25f);
    /* Coarse teeth, none along the basal sinus. */
    float f = (a / PI_F) * (float)nt;
    f -= floorf(f);
    float tooth = powf(1.0f - fabsf(2.0f * f - 1.0f), 0.8f);
    float env = 1.0f - tex_smooth(0.7f * PI_F, 0.85f * PI_F, a);
    return r * (1.0f - teeth_amp * env * (1.0f - tooth));
}

/* atan2 good to ~1e-4 rad. */
static inline float fast_atan2(float y, float x) {
    float ax = fabsf(x), ay = fabsf(y);
    float mn = fminf(ax, ay), mx = fmaxf(ax, ay);
    if (mx == 0.0f) return 0.0f;
    float a = mn / mx, s = a * a;
    float r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
    if (ay > ax) r = 1.57079637f - r;
    if (x < 0) r = PI_F - r;
    if (y < 0) r = -r;
    return r;
}

static void ivy_leaf(const cell *k, const ivleaf *L, int nt, float teeth_amp, const tex_noise *grain) {
    static const int NV = 5;
    float rt[IT + 1], gt[IT + 1];
    float rmax = 0.0f;
    for (int i = 0; i <= IT; i++) {
        float phi = -PI_F + 2.0f * PI_F * (float)i / IT;
        rt[i] = ivy_radius(L, phi, teeth_amp, nt);
        if (rt[i] > rmax) rmax = rt[i];
    }
    for (int i = 0; i <= IT; i++) {
        int a = i > 0 ? i - 1 : 0, b = i < IT ? i + 1 : IT;
        float d = (rt[b] - rt[a]) / ((float)(b - a) * 2.0f * PI_F / IT);
        float rr = rt[i] > 1e-4f ? rt[i] : 1e-4f;
        gt[i] = 1.0f / sqrtf(1.0f + (d / rr) * (d / rr));
    }
    /* Primary veins: to the three lobe tips and into the basal lobes. */
    float va[5] = {0.0f, L->lob_a, -L->lob_a, L->lob_a + 0.75f, -(L->lob_a + 0.75f)};
    if (!L->lobed) va[1] = 0.9f, va[2] = -0.9f, va[3] = 1.75f, va[4] = -1.75f;
    float vx[5], vy[5];
    for (int i = 0; i < NV; i++) vx[i] = sinf(va[i]), vy[i] = cosf(va[i]);
    const float s = (float)k->size, Rp = L->R * s;
    const int n = k->c->n;
    float ext = rmax * L->R + 2.0f / s;
    int x0, x1, y0, y1;
    bounds(k, L->jx - ext, L->jx + ext, L->jy - ext, L->jy + ext, &x0, &x1, &y0, &y1);
    for (int yy = y0; yy <= y1; yy++) {
        for (int xx = x0; xx <= x1; xx++) {
            float u = (pu(k, xx) - L->jx) / L->R, v = (pv(k, yy) - L->jy) / L->R;
            float rho = sqrtf(u * u + v * v);
            if (rho > rmax + 2.0f / Rp) continue;
            float phi = fast_atan2(u, v); /* 0 = up, + to the right */
            float fi = (phi + PI_F) * (IT / (2.0f * PI_F));
            int i = (int)fi;
            if (i >= IT) i = IT - 1;
            if (i < 0) i = 0;
            float fr = fi - (float)i;
            float r = rt[i] + (rt[i + 1] - rt[i]) * fr, g = gt[i] + (gt[i + 1] - gt[i]) * fr;
            float dpx = (r - rho) * Rp * g;
            float cov = tex_clampf(dpx + 0.5f, 0.0f, 1.0f);
            if (cov <= 0.0f) continue;
            /* Nearest primary vein by angle; distance to it; secondaries
             * leave it at about 50 degrees towards the margin. */
            int best = 0;
            float bc = -2.0f;
            for (int j = 0; j < NV; j++) {
                float c = (u * vx[j] + v * vy[j]);
                if (c > bc) bc = c, best = j;
            }
            float along = bc, perp = u * vy[best] - v * vx[best];
            float ap = fabsf(perp);
            float rel = rho / (r > 1e-4f ? r : 1e-4f);
            float pw = ((best == 0 ? 0.016f : best < 3 ? 0.013f : 0.008f) * (1.0f - 0.8f * rel) + 0.002f) * Rp;
            float vp = along > 0.0f ? 1.0f - tex_smooth(pw, pw + 0.9f, ap * Rp) : 0.0f;
            vp *= 1.0f - tex_smooth(0.85f, 1.0f, rel);
            float q = (along - ap * 0.9f) / 0.11f;
            float dq = fabsf(q - floorf(q + 0.5f)) * 0.11f / 1.345f * Rp;
            float sw = 0.0035f * Rp * (1.0f - 0.7f * rel);
            float vs = along > 0.05f ? (1.0f - tex_smooth(sw, sw + 0.8f, dq)) * (1.0f - tex_smooth(0.75f, 0.97f, rel)) : 0.0f;
            vs *= tex_smooth(0.0f, 0.06f, ap);
            float vein = fmaxf(vp, 0.6f * vs);
            float gr = tex_noise_at(grain, (float)xx * 0.3f, (float)yy * 0.3f);
            float toward = tex_smooth(0.5f, 1.0f, rel);
            float edge = 1.0f - tex_smooth(0.5f, 3.0f, dpx);
            float col[3];
            for (int ch = 0; ch < 3; ch++) {
                float cc = tex_mix(L->inner[ch], L->col[ch], tex_smooth(0.0f, 0.5f, rel));
                cc = tex_mix(cc, L->edge[ch], toward * 0.45f) * (0.93f + 0.07f * gr);
                cc = tex_mix(cc, L->vein[ch], vein * 0.75f);
                col[ch] = tex_mix(cc, L->edge[ch] * 0.8f, edge * 0.6f);
            }
            /* Puckered between the veins: veins sunken, blade domed. */
            float h = 1.5f * (1.0f - rel * rel) - 1.0f * vp - 0.6f * vs + 0.12f * gr;
            put(k->c, (size_t)yy * n + xx, cov, col, h);
        }
    }
}

static void ivy_colours(ivleaf *L, int season, pcg32 *r) {
    float c[3], in[3];
    if (season == BANYAN_SEASON_SUMMER) {
        /* Glossy dark green; young (unlobed) leaves lighter, a bronze hint. */
        const float dark[3] = {40, 74, 30}, young[3] = {88, 112, 46};
        float b = tex_unif(r, 0.88f, 1.12f);
        float y = L->lobed ? tex_unif(r, 0.0f, 0.2f) : tex_unif(r, 0.45f, 0.8f);
        for (int i = 0; i < 3; i++) c[i] = tex_mix(dark[i], young[i], y) * b;
        if (!L->lobed) c[0] += tex_unif(r, 0.0f, 14.0f);
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

/* Alpha-0 pixels of a cell take the mean colour of its leaf pixels. */
static void fill_background(tex_canvas *c, const cell *k) {
    double sum[3] = {0, 0, 0};
    double wsum = 0;
    for (int y = k->y0; y < k->y0 + k->size; y++)
        for (int x = k->x0; x < k->x0 + k->size; x++) {
            const uint8_t *p = c->rgba + 4 * ((size_t)y * c->n + x);
            if (p[3] < 128) continue;
            for (int ch = 0; ch < 3; ch++) sum[ch] += p[ch];
            wsum += 1;
        }
    uint8_t mean[3] = {64, 96, 40};
    if (wsum > 0)
        for (int ch = 0; ch < 3; ch++) mean[ch] = (uint8_t)(sum[ch] / wsum + 0.5);
    for (int y = k->y0; y < k->y0 + k->size; y++)
        for (int x = k->x0; x < k->x0 + k->size; x++) {
            uint8_t *p = c->rgba + 4 * ((size_t)y * c->n + x);
            if (p[3] == 0) p[0] = mean[0], p[1] = mean[1], p[2] = mean[2];
        }
}

int tex_paint_keyaki_leaves(tex_canvas *c, int season, pcg32 *rng) {
    int cols, rows;
    float aspect;
    tex_leaf_grid(BANYAN_TEX_KEYAKI_LEAF, &cols, &rows, &aspect);
    tex_noise grain;
    if (tex_noise_init(&grain, 64, 64, rng)) return -1;
    int cs = c->n / cols;
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < cols; i++) {
            cell k = {c, i * cs, j * cs, cs, cs >= 64 ? 2 : 1};
            keyaki_spray(&k, season, rng, &grain);
            fill_background(c, &k);
        }
    tex_noise_free(&grain);
    c->relief = 0.6f;
    c->wrap = 0;
    return 0;
}

int tex_paint_ivy_leaves(tex_canvas *c, int season, pcg32 *rng) {
    int cols, rows;
    float aspect;
    tex_leaf_grid(BANYAN_TEX_IVY_LEAF, &cols, &rows, &aspect);
    tex_noise grain;
    if (tex_noise_init(&grain, 64, 64, rng)) return -1;
    int cs = c->n / cols;
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < cols; i++) {
            cell k = {c, i * cs, j * cs, cs, cs >= 64 ? 2 : 1};
            ivleaf L;
            /* A quarter of the cells: young unlobed leaves (long shoots). */
            L.lobed = ((i + j * cols) % 4) != 3;
            L.lob_a = tex_unif(rng, 0.85f, 1.05f);
            L.lob_c = tex_unif(rng, 0.72f, 0.9f);
            int nt = 9 + (int)rng_below(rng, 5);
            float amp = L.lobed ? tex_unif(rng, 0.05f, 0.08f) : tex_unif(rng, 0.03f, 0.05f);
            ivy_colours(&L, season, rng);
            /* Fit: widest extent sideways and upwards, junction placed so the
             * tip reaches 4 % below the top; a petiole stub below it. */
            float side = 0.0f, up = 0.0f, down = 0.0f;
            for (int t = 0; t < 256; t++) {
                float phi = -PI_F + 2.0f * PI_F * (float)t / 256.0f;
                float rr = ivy_radius(&L, phi, 0.0f, nt);
                side = fmaxf(side, fabsf(sinf(phi)) * rr);
                up = fmaxf(up, cosf(phi) * rr);
                down = fmaxf(down, -cosf(phi) * rr);
            }
            float R = fminf(0.44f / side, 0.80f / (up + down)) * tex_unif(rng, 0.9f, 1.0f);
            L.R = R;
            L.jx = 0.5f;
            L.jy = 0.96f - up * R;
            const float pet[3] = {season ? 150.0f : 96.0f, season ? 60.0f : 110.0f, season ? 40.0f : 50.0f};
            stroke(&k, 0.5f, 0.0f, L.jx, L.jy - down * R * 0.2f, 0.012f, 0.008f, pet, 0.6f);
            ivy_leaf(&k, &L, nt, amp, &grain);
            fill_background(c, &k);
        }
    tex_noise_free(&grain);
    c->relief = 0.6f;
    c->wrap = 0;
    return 0;
}
