/* bark.c - tileable bark (docs/materials.md "Bark"): keyaki (smooth grey
 * with lenticels, small old scales flaking off into muted orange-brown
 * patches, and a smooth grey-brown lane for thin branches and twigs),
 * strangler fig (smooth pale grey-brown with fine horizontal
 * wrinkles around the root) and the ivy's woody stem (brown, fibrous,
 * a few longitudinal fissures). Each is periodic value noise (noise.c)
 * shaped per kind, made a band of rows at a time; the tile spans one
 * circumference around (u, image columns) and BANYAN_BARK_TILE_ASPECT
 * circumferences along (v, rows), so features stay round on the tube.
 * Lenticels are small ellipses drawn with wrap-around. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "textures/tex_internal.h"

/* A small elliptical mark (lenticel) at (cx, cy) px, half axes rx, ry,
 * wrapping around the tile: blends colour and adds height. */
static void mark(tex_canvas *c, float cx, float cy, float rx, float ry, const float col[3], float opacity,
                 float dh) {
    const int n = c->n;
    int x0 = (int)floorf(cx - rx - 1), x1 = (int)ceilf(cx + rx + 1);
    int y0 = (int)floorf(cy - ry - 1), y1 = (int)ceilf(cy + ry + 1);
    for (int y = y0; y <= y1; y++) {
        int yy = y & (n - 1);
        float dy = ((float)y + 0.5f - cy) / ry;
        for (int x = x0; x <= x1; x++) {
            float dx = ((float)x + 0.5f - cx) / rx;
            float r2 = dx * dx + dy * dy;
            if (r2 >= 1.0f) continue;
            float k = (1.0f - r2);
            float a = opacity * tex_smooth(0.0f, 0.35f, k);
            size_t i = (size_t)yy * n + (size_t)(x & (n - 1));
            uint8_t *p = c->rgba + 4 * i;
            for (int ch = 0; ch < 3; ch++) p[ch] = tex_byte(tex_mix(p[ch], col[ch], a));
            c->height[i] += dh * sqrtf(k);
        }
    }
}

/* Up to four fields and their band scratch. */
typedef struct fields {
    tex_fbm f[4];
    int count;
    float *band; /* count * TEX_BAND * n */
    float *rgb;  /* 3 * n: one row's colour channels before packing */
} fields;

static void fields_free(fields *F) {
    for (int i = 0; i < F->count; i++) tex_fbm_free(&F->f[i]);
    free(F->band);
}

/* Makes the fields from (f0x, f0y, octaves, gain) rows; -1 on no memory. */
static int fields_init(fields *F, int n, int count, const float spec[][4], pcg32 *rng) {
    memset(F, 0, sizeof *F);
    for (int i = 0; i < count; i++) {
        if (tex_fbm_init(&F->f[i], n, (int)spec[i][0], (int)spec[i][1], (int)spec[i][2], 1.0f, spec[i][3], 8, rng)) {
            fields_free(F);
            return -1;
        }
        F->count = i + 1;
    }
    F->band = malloc(sizeof(float) * ((size_t)count * TEX_BAND * n + 3 * (size_t)n));
    F->rgb = F->band ? F->band + (size_t)count * TEX_BAND * n : NULL;
    if (!F->band) {
        fields_free(F);
        return -1;
    }
    return 0;
}

/* Field i's band for rows y0 .. y0 + TEX_BAND - 1. */
static float *fields_rows(fields *F, int i, int y0) {
    float *b = F->band + (size_t)i * TEX_BAND * F->f[0].n;
    tex_fbm_rows(&F->f[i], b, y0, TEX_BAND);
    return b;
}

/* Keyaki's scales: a periodic jittered grid of gx x gy cells (cellular
 * noise), warped, so the flakes are rounded polygons a little taller than
 * wide, a few cm on a 0.4 m tile. Each cell is a scale: grey (its own
 * shade) or, for a few, shed, showing the under-bark, muted orange-brown
 * (fresh) to a duller brown (older). No scale is shed near the smooth
 * lane, u in BANYAN_KEYAKI_BARK_SMOOTH_U0 .. _U1 (textures.h): there the
 * tile is smooth grey-brown young bark with lenticels, and the bodies map
 * their thin branches' and twigs' u into it. */
typedef struct scales {
    int gx, gy, pw;       /* cells across and along; padded row width */
    float *px, *py, *val; /* padded by SPAD cells each side (copies wrapped round): point, value */
    int *id;              /* padded: the cell's index in 0 .. gx * gy - 1 */
    float *vals;          /* gx * gy: each cell's value */
} scales;

#define KEYAKI_SHED 0.13f     /* fraction of scales shed */
#define KEYAKI_GX 16          /* scales across the tile */
#define KEYAKI_GY 12          /* scales along it */
#define KEYAKI_LANE_FADE 0.03f /* u over which the lane's colour fades in at each side */
#define SPAD 3                /* covers the warp (under a cell) and the 3 x 3 search */

static int scales_init(scales *S, int gx, int gy, pcg32 *rng) {
    S->gx = gx, S->gy = gy, S->pw = gx + 2 * SPAD;
    size_t cells = (size_t)gx * gy, padded = (size_t)S->pw * (gy + 2 * SPAD);
    float *jx = malloc(sizeof(float) * 3 * cells);
    S->px = malloc(sizeof(float) * (3 * padded + cells));
    S->id = malloc(sizeof(int) * padded);
    if (!jx || !S->px || !S->id) {
        free(jx);
        free(S->px);
        free(S->id);
        return -1;
    }
    float *jy = jx + cells, *v = jy + cells;
    /* A scale whose point lies within 1.2 cells of the lane (its reach
     * with the warp) stays on: its value is moved above KEYAKI_SHED. */
    const float lo = BANYAN_KEYAKI_BARK_SMOOTH_U0 * (float)gx - 1.2f, hi = BANYAN_KEYAKI_BARK_SMOOTH_U1 * (float)gx + 1.2f;
    for (size_t i = 0; i < cells; i++) {
        jx[i] = tex_unif(rng, 0.1f, 0.9f);
        jy[i] = tex_unif(rng, 0.1f, 0.9f);
        v[i] = tex_unif(rng, 0.0f, 1.0f);
        float x = (float)(i % (size_t)gx) + jx[i];
        if (x > lo && x < hi) v[i] = KEYAKI_SHED + (1.0f - KEYAKI_SHED) * v[i];
    }
    S->py = S->px + padded, S->val = S->py + padded, S->vals = S->val + padded;
    memcpy(S->vals, v, sizeof(float) * cells);
    for (int j = -SPAD; j < gy + SPAD; j++)
        for (int i = -SPAD; i < gx + SPAD; i++) {
            int ii = (i + gx) % gx, jj = (j + gy) % gy, c = jj * gx + ii;
            size_t p = (size_t)(j + SPAD) * S->pw + (size_t)(i + SPAD);
            S->px[p] = (float)i + jx[c], S->py[p] = (float)j + jy[c], S->val[p] = v[c], S->id[p] = c;
        }
    free(jx);
    return 0;
}

static void scales_free(scales *S) {
    free(S->px);
    free(S->id);
}

/* Nearest and second-nearest scale points to (px, py) in cell units,
 * px in [-2, gx + 2), py likewise (the warp is under a cell): distances
 * and the nearest one's padded index. */
static inline void scales_at(const scales *S, float px, float py, float *f1, float *f2, int *pid) {
    int i0 = (int)(px + (float)SPAD) - SPAD, j0 = (int)(py + (float)SPAD) - SPAD; /* floor */
    float d1 = 1e9f, d2 = 1e9f;
    int best = 0;
    for (int dj = -1; dj <= 1; dj++) {
        int base = (j0 + dj + SPAD) * S->pw + i0 + SPAD;
        for (int di = -1; di <= 1; di++) {
            int p = base + di;
            float dx = S->px[p] - px, dy = S->py[p] - py;
            float d = dx * dx + dy * dy;
            if (d < d1) d2 = d1, d1 = d, best = p;
            else if (d < d2) d2 = d;
        }
    }
    *f1 = sqrtf(d1), *f2 = sqrtf(d2), *pid = best;
}

/* scales_at for four points with the same nearest cell (KB = 4 pixels
 * of a block), one vector lane each, branch-free but step for step the
 * scalar search (so the same results, ties included): the scale value
 * into B[x0 ..] and the gap f2 - f1 into H[x0 ..]. */
static void scales_at4(const scales *S, const float qx[4], const float qy[4], int x0, float *B, float *H) {
    int i0 = (int)(qx[0] + (float)SPAD) - SPAD, j0 = (int)(qy[0] + (float)SPAD) - SPAD; /* floor */
    const tex_v4 PX = v4_load(qx), PY = v4_load(qy);
    tex_v4 d1 = {1e9f, 1e9f, 1e9f, 1e9f}, d2 = d1;
    tex_v4i best = {0, 0, 0, 0};
    for (int dj = -1; dj <= 1; dj++) {
        int base = (j0 + dj + SPAD) * S->pw + i0 + SPAD;
        for (int di = -1; di <= 1; di++) {
            int p = base + di;
            tex_v4 dx = S->px[p] - PX, dy = S->py[p] - PY;
            tex_v4 d = dx * dx + dy * dy;
            tex_v4i lt1 = d < d1, lt2 = d < d2;
            /* if (d < d1) d2 = d1, d1 = d, best = p; else if (d < d2) d2 = d; */
            d2 = v4_sel(lt1, d1, v4_sel(lt2, d, d2));
            d1 = v4_sel(lt1, d, d1);
            best = (lt1 & p) | (~lt1 & best);
        }
    }
    for (int l = 0; l < 4; l++) B[x0 + l] = S->vals[S->id[best[l]]], H[x0 + l] = sqrtf(d2[l]) - sqrtf(d1[l]);
}

/* One row: scales (cellular, warped by fields wx, wy), tone t, relief h.
 * The scale search (nine cells) runs only where a block of 4 x 4 pixels
 * may hold a border: blocks whose corners (cid, cgap: the band's coarse
 * samples) lie in one scale clear of its border take that scale, and a
 * border's edge terms are 0 there. */
#define KB 4
static void keyaki_row(int n, int y, int r, const scales *S, const float *wx, const float *wy,
                       const float *restrict tr, const float *restrict hr, const int *cid, const float *cgap,
                       float *restrict R, float *restrict G, float *restrict B, float *restrict H) {
    const float grey[3] = {162, 160, 153}, grey2[3] = {120, 120, 115};
    const float orange[3] = {164, 134, 108}, brown[3] = {132, 118, 102};
    const float lane[3] = {156, 148, 138}, lane2[3] = {120, 112, 103}; /* young bark: grey-brown */
    const float sx = (float)S->gx / (float)n, sy = (float)S->gy / (float)n;
    const int cw = n / KB + 1, by = r / KB;
    /* The border term is 0 beyond a gap of 0.07; inside a block the gap
     * changes by under 0.06 at 1024 on a 12 x 8 grid (the block spans
     * fewer cells on a larger image, more on a finer grid): the same
     * bytes as searching every pixel. */
    const float fx = (float)S->gx / 12.0f, fy = (float)S->gy / 8.0f;
    const float kb_gap = 0.08f + 0.06f * 1024.0f / (float)n * (fx > fy ? fx : fy);
    /* Pass 1: each pixel's scale value (into B) and gap (into H). */
    for (int bx = 0; bx < n / KB; bx++) {
        int c00 = by * cw + bx, c01 = c00 + 1, c10 = c00 + cw, c11 = c10 + 1, id = cid[c00];
        if (cid[c01] == id && cid[c10] == id && cid[c11] == id && cgap[c00] > kb_gap && cgap[c01] > kb_gap &&
            cgap[c10] > kb_gap && cgap[c11] > kb_gap) {
            for (int x = bx * KB; x < bx * KB + KB; x++) B[x] = S->vals[id], H[x] = 1.0f; /* inside one scale */
            continue;
        }
        const int x0 = bx * KB;
        float qx[KB], qy[KB];
        int same = 1;
        for (int l = 0; l < KB; l++) {
            qx[l] = ((float)(x0 + l) + 0.5f) * sx + 0.5f * wx[x0 + l], qy[l] = ((float)y + 0.5f) * sy + 0.5f * wy[x0 + l];
            same &= (int)(qx[l] + (float)SPAD) == (int)(qx[0] + (float)SPAD) &&
                    (int)(qy[l] + (float)SPAD) == (int)(qy[0] + (float)SPAD);
        }
        if (same) { /* one 3 x 3 neighbourhood for the block: its four pixels at once */
            scales_at4(S, qx, qy, x0, B, H);
            continue;
        }
        for (int x = x0; x < x0 + KB; x++) {
            float f1, f2;
            int p;
            scales_at(S, qx[x - x0], qy[x - x0], &f1, &f2, &p);
            B[x] = S->vals[S->id[p]], H[x] = f2 - f1;
        }
    }
    /* Pass 2: shading, both looks computed and one picked (no branch: the
     * loop vectorises). */
    for (int x = 0; x < n; x++) {
        float v = B[x];
        float edge = 1.0f - tex_smooth(0.0f, 0.07f, H[x]); /* the border between two scales */
        float t = tr[x];
        float g = tex_clampf(0.55f + 0.6f * t + (v - 0.5f) * 0.4f, 0.0f, 1.0f); /* soft mottling, no camouflage */
        /* Shed: fresh (orange) to older (duller brown), mottled; the
         * scales around it end in a torn, shadowed edge. */
        float fresh = tex_clampf(v / KEYAKI_SHED * 1.4f - 0.2f + 0.8f * t, 0.0f, 1.0f);
        float m = (0.88f + 0.24f * tex_clampf(0.5f + 1.5f * hr[x], 0.0f, 1.0f)) * (1.0f - 0.3f * edge);
        float sr = tex_mix(brown[0], orange[0], fresh) * m;
        float sg = tex_mix(brown[1], orange[1], fresh) * m;
        float sb = tex_mix(brown[2], orange[2], fresh) * m;
        float sh = 0.1f * hr[x] - 0.35f - 0.2f * edge;
        /* Grey bark: continuous over the scale borders (they show only
         * where a scale has gone), a faint seam at most. */
        float dark = 1.0f - 0.05f * edge;
        float gr = tex_mix(grey2[0], grey[0], g) * dark;
        float gg = tex_mix(grey2[1], grey[1], g) * dark;
        float gb = tex_mix(grey2[2], grey[2], g) * dark;
        float gh = 0.25f * hr[x] - 0.1f * edge;
        int shed = v < KEYAKI_SHED;
        /* The smooth lane: young bark over the scales, faded in at its sides. */
        float u = ((float)x + 0.5f) / (float)n;
        float k = tex_smooth(BANYAN_KEYAKI_BARK_SMOOTH_U0 - KEYAKI_LANE_FADE, BANYAN_KEYAKI_BARK_SMOOTH_U0, u) *
                  (1.0f - tex_smooth(BANYAN_KEYAKI_BARK_SMOOTH_U1, BANYAN_KEYAKI_BARK_SMOOTH_U1 + KEYAKI_LANE_FADE, u));
        float lt = tex_clampf(0.5f + 0.6f * t, 0.0f, 1.0f);
        float lr = tex_mix(lane2[0], lane[0], lt), lg = tex_mix(lane2[1], lane[1], lt), lb = tex_mix(lane2[2], lane[2], lt);
        R[x] = tex_mix(shed ? sr : gr, lr, k), G[x] = tex_mix(shed ? sg : gg, lg, k);
        B[x] = tex_mix(shed ? sb : gb, lb, k), H[x] = tex_mix(shed ? sh : gh, 0.1f * hr[x], k);
    }
}

int tex_paint_keyaki_bark(tex_canvas *c, pcg32 *rng) {
    const int n = c->n;
    /* Warp (x, y), the grey's tone, fine relief. */
    static const float spec[4][4] = {{8, 8, 4, 0.55f}, {8, 8, 4, 0.55f}, {8, 8, 5, 0.6f}, {16, 16, 4, 0.6f}};
    fields F;
    if (fields_init(&F, n, 4, spec, rng)) return -1;
    scales S;
    if (scales_init(&S, KEYAKI_GX, KEYAKI_GY, rng)) {
        fields_free(&F);
        return -1;
    }
    const int cw = n / KB + 1, ch = TEX_BAND / KB + 1;
    int *cid = malloc(sizeof(int) * (size_t)cw * ch);
    float *cgap = malloc(sizeof(float) * (size_t)cw * ch);
    if (!cid || !cgap) {
        free(cid);
        free(cgap);
        scales_free(&S);
        fields_free(&F);
        return -1;
    }
    const float sx = (float)S.gx / (float)n, sy = (float)S.gy / (float)n;
    for (int y0 = 0; y0 < n && !tex_stopped(c); y0 += TEX_BAND) {
        const float *wx = fields_rows(&F, 0, y0), *wy = fields_rows(&F, 1, y0), *tone = fields_rows(&F, 2, y0),
                    *hf = fields_rows(&F, 3, y0);
        /* Coarse samples every KB pixels (the band's last row stands in
         * for the next band's first: only the test above reads them). */
        for (int j = 0; j < ch; j++) {
            int r = j * KB < TEX_BAND ? j * KB : TEX_BAND - 1;
            for (int i = 0; i < cw; i++) {
                int x = (i * KB) & (n - 1);
                size_t o = (size_t)r * n + x;
                float f1, f2;
                int p;
                scales_at(&S, ((float)(i * KB) + 0.5f) * sx + 0.5f * wx[o], ((float)(y0 + r) + 0.5f) * sy + 0.5f * wy[o],
                          &f1, &f2, &p);
                cid[j * cw + i] = S.id[p];
                cgap[j * cw + i] = f2 - f1;
            }
        }
        for (int r = 0; r < TEX_BAND; r++) {
            size_t row = (size_t)(y0 + r) * n, o = (size_t)r * n;
            keyaki_row(n, y0 + r, r, &S, wx + o, wy + o, tone + o, hf + o, cid, cgap, F.rgb, F.rgb + n,
                       F.rgb + 2 * n, c->height + row);
            tex_pack_rgba(c->rgba + 4 * row, F.rgb, F.rgb + n, F.rgb + 2 * n, n);
        }
    }
    free(cid);
    free(cgap);
    /* Lenticels: short pale dashes across the trunk, on the grey scales. */
    float s = (float)n / 1024.0f;
    const float lcol[3] = {184, 172, 152};
    for (int k = 0; k < 500; k++) {
        float cx = tex_unif(rng, 0, (float)n), cy = tex_unif(rng, 0, (float)n);
        float rx = tex_unif(rng, 2.5f, 6.0f) * s, ry = tex_unif(rng, 0.7f, 1.3f) * s;
        float f1, f2;
        int p;
        scales_at(&S, cx * S.gx / (float)n + 0.5f * tex_fbm_at(&F.f[0], cx, cy),
                  cy * S.gy / (float)n + 0.5f * tex_fbm_at(&F.f[1], cx, cy), &f1, &f2, &p);
        if (S.val[p] < KEYAKI_SHED) continue; /* none on the under-bark */
        mark(c, cx, cy, rx < 1.0f ? 1.0f : rx, ry < 0.6f ? 0.6f : ry, lcol, 0.8f, 0.25f);
    }
    c->relief = 6.0f * s;
    c->wrap = 1;
    scales_free(&S);
    fields_free(&F);
    return 0;
}

#define FIG_FOLDS 20 /* longitudinal folds round the root per tile */

/* One row: a fig root's smooth bark: longitudinal folds (across u, warped,
 * fading in and out in broad patches with the warp), tone, fine relief.
 * No rings across the root, low contrast and low relief: the fused
 * surface's uv jumps where the nearest root changes, and lines across
 * the uv drew staircases there. */
static void fig_row(int n, const float *restrict warp, const float *restrict tr, const float *restrict hr,
                    float *restrict R, float *restrict G, float *restrict B, float *restrict H) {
    const float pale[3] = {168, 159, 146}, dark[3] = {136, 127, 114}, crease[3] = {112, 102, 90};
    for (int x = 0; x < n; x++) {
        float a = (float)x * FIG_FOLDS / (float)n + 1.5f * warp[x] + 64.0f; /* positive: truncation floors */
        float d = fabsf(2.0f * (a - (float)(int)a) - 1.0f);                 /* 0 on a fold's crease */
        float fold = (1.0f - tex_smooth(0.0f, 0.3f, d)) * tex_smooth(-0.6f, 0.2f, warp[x]);
        float t = tex_clampf(0.5f + 0.8f * tr[x], 0.0f, 1.0f), m = 0.5f * fold;
        R[x] = tex_mix(tex_mix(dark[0], pale[0], t), crease[0], m);
        G[x] = tex_mix(tex_mix(dark[1], pale[1], t), crease[1], m);
        B[x] = tex_mix(tex_mix(dark[2], pale[2], t), crease[2], m);
        H[x] = 0.05f * hr[x] - 0.45f * fold;
    }
}

int tex_paint_fig_bark(tex_canvas *c, pcg32 *rng) {
    const int n = c->n;
    static const float spec[3][4] = {{4, 4, 4, 0.5f}, {4, 4, 6, 0.6f}, {16, 16, 4, 0.5f}};
    fields F;
    if (fields_init(&F, n, 3, spec, rng)) return -1;
    for (int y0 = 0; y0 < n && !tex_stopped(c); y0 += TEX_BAND) {
        const float *warp = fields_rows(&F, 0, y0), *tone = fields_rows(&F, 1, y0), *hf = fields_rows(&F, 2, y0);
        for (int r = 0; r < TEX_BAND; r++) {
            size_t row = (size_t)(y0 + r) * n, o = (size_t)r * n;
            fig_row(n, warp + o, tone + o, hf + o, F.rgb, F.rgb + n, F.rgb + 2 * n, c->height + row);
            tex_pack_rgba(c->rgba + 4 * row, F.rgb, F.rgb + n, F.rgb + 2 * n, n);
        }
    }
    float s = (float)n / 1024.0f;
    const float lcol[3] = {182, 174, 158}; /* lenticels: short, pale, faint */
    for (int k = 0; k < 220; k++) {
        float cx = tex_unif(rng, 0, (float)n), cy = tex_unif(rng, 0, (float)n);
        float r = tex_unif(rng, 0.8f, 1.6f) * s;
        mark(c, cx, cy, r * 1.4f < 1.0f ? 1.0f : r * 1.4f, r < 0.6f ? 0.6f : r, lcol, 0.35f, 0.15f);
    }
    c->relief = 2.5f * s;
    c->wrap = 1;
    fields_free(&F);
    return 0;
}

/* One row: fibres as wavy ridges along the stem (stripe coordinate
 * across it, warped: fw), their strength (fs), fissures along the zero
 * lines of a field (cr), tone (t). */
static void stem_row(int n, const float *restrict fw, const float *restrict fs, const float *restrict crr,
                     const float *restrict tr, float *restrict R, float *restrict G, float *restrict B,
                     float *restrict H) {
    const float wood[3] = {124, 100, 76}, grey[3] = {132, 122, 108}, groove[3] = {64, 48, 36};
    const int stripes = 56; /* fibres around the stem */
    for (int x = 0; x < n; x++) {
        float w = (float)x * stripes / (float)n + 2.0f * fw[x] + 64.0f; /* positive: truncation floors */
        /* One fibre's cross-section: a broad rounded ridge, a narrow groove at its edge. */
        float d = fabsf(2.0f * (w - (float)(int)w) - 1.0f);
        float ridge = d * (2.0f - d) * tex_clampf(0.6f + 0.8f * fs[x], 0.0f, 1.0f);
        float fis = 1.0f - tex_smooth(0.0f, 0.05f, fabsf(crr[x])); /* fissure along a zero line */
        float t = tex_clampf(0.5f + 0.9f * tr[x], 0.0f, 1.0f);
        float sh = 0.78f + 0.3f * ridge;
        R[x] = tex_mix(tex_mix(wood[0], grey[0], t) * sh, groove[0], 0.85f * fis);
        G[x] = tex_mix(tex_mix(wood[1], grey[1], t) * sh, groove[1], 0.85f * fis);
        B[x] = tex_mix(tex_mix(wood[2], grey[2], t) * sh, groove[2], 0.85f * fis);
        H[x] = 0.5f * ridge - 0.9f * fis + 0.1f * tr[x];
    }
}

int tex_paint_ivy_stem(tex_canvas *c, pcg32 *rng) {
    const int n = c->n;
    /* Fibre warp (smooth, longer along the stem), fibre strength, fissures, tone. */
    static const float spec[4][4] = {{8, 2, 4, 0.5f}, {16, 4, 3, 0.5f}, {8, 1, 5, 0.55f}, {4, 4, 5, 0.6f}};
    fields F;
    if (fields_init(&F, n, 4, spec, rng)) return -1;
    for (int y0 = 0; y0 < n && !tex_stopped(c); y0 += TEX_BAND) {
        const float *fw = fields_rows(&F, 0, y0), *fs = fields_rows(&F, 1, y0), *crack = fields_rows(&F, 2, y0),
                    *tone = fields_rows(&F, 3, y0);
        for (int r = 0; r < TEX_BAND; r++) {
            size_t row = (size_t)(y0 + r) * n, o = (size_t)r * n;
            stem_row(n, fw + o, fs + o, crack + o, tone + o, F.rgb, F.rgb + n, F.rgb + 2 * n, c->height + row);
            tex_pack_rgba(c->rgba + 4 * row, F.rgb, F.rgb + n, F.rgb + 2 * n, n);
        }
    }
    float s = (float)n / 1024.0f;
    const float lcol[3] = {160, 130, 100};
    for (int k = 0; k < 90; k++) {
        float cx = tex_unif(rng, 0, (float)n), cy = tex_unif(rng, 0, (float)n);
        float r = tex_unif(rng, 1.5f, 3.0f) * s;
        mark(c, cx, cy, r < 0.8f ? 0.8f : r, 1.8f * r < 1.0f ? 1.0f : 1.8f * r, lcol, 0.7f, 0.3f);
    }
    c->relief = 5.0f * s;
    c->wrap = 1;
    fields_free(&F);
    return 0;
}
