/* leaves_ivy.c - the Boston ivy leaf atlas (leaves.c says how the atlases
 * are drawn): three-lobed and young unlobed blades, one a cell. */
#include "leaf_paint.h"

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
        tex_blade_table(B, T); /* in units of the length: ivy_place keeps it */
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

int tex_paint_ivy_leaves(tex_canvas *c, int season, pcg32 *rng) {
    int cols, rows;
    float aspect;
    tex_leaf_grid(BANYAN_TEX_IVY_LEAF, &cols, &rows, &aspect);
    if (tex_leaf_fields(c, rng)) return -1;
    int cs = c->n / cols;
    int *spans = malloc(sizeof(int) * 3 * (size_t)cs);
    float *scr = malloc(sizeof(float) * LEAF_SCR * (size_t)cs);
    if (!spans || !scr) {
        free(spans);
        free(scr);
        tex_leaf_fields_free(c);
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
    tex_leaf_fields_free(c);
    c->relief = 1.2f * (float)c->n / 1024.0f; /* the same slopes at every size */
    c->wrap = 0;
    return 0;
}
