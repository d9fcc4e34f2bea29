/* leaves.c - leaf atlases (docs/materials.md, "Keyaki leaves"):
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
 * keyaki leaf fills the box textures/leaf_look.h gives its mesh quad
 * (midrib up the cell's centre, petiole below, blade and teeth within
 * LEAF_KEYAKI_HALF_U of it), so the drawn leaf and the quad have the same
 * length. Colour is straight alpha; pixels outside leaves get the cell's
 * mean leaf colour at alpha 0, so mipmaps and texture filtering do not
 * bleed a dark fringe. This file: the keyaki painter and the fields both
 * atlases share; the ivy painter is in leaves_ivy.c, the shared cell
 * painting in leaf_paint.h. */
#include "leaf_paint.h"

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


void tex_blade_table(const kleaf *L, ktab *T) {
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
    tex_blade_table(L, &T);
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
        tex_blade_table(&L, &T);
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

/* ------------------------------------------------------------ atlases */

/* The grain (cells of 4 px) and mottle tiles, TEX_TILE pixels a side (or
 * the image's side when smaller): grain repeats across the atlas, mottle
 * is stretched over it. */
void tex_leaf_fields_free(tex_canvas *c) {
    free(c->grain);
    free(c->mottle);
    c->grain = c->mottle = NULL;
}

int tex_leaf_fields(tex_canvas *c, pcg32 *rng) {
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
    if (rc) tex_leaf_fields_free(c);
    return rc ? -1 : 0;
}

int tex_paint_keyaki_leaves(tex_canvas *c, int season, pcg32 *rng) {
    int cols, rows;
    float aspect;
    tex_leaf_grid(BANYAN_TEX_KEYAKI_LEAF, &cols, &rows, &aspect);
    if (tex_leaf_fields(c, rng)) return -1;
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
        tex_leaf_fields_free(c);
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
    tex_leaf_fields_free(c);
    c->relief = 1.2f * (float)c->n / 1024.0f; /* the same slopes at every size */
    c->wrap = 0;
    return 0;
}
