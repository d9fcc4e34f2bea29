/* leaf_look.c - atlas cells, per-leaf tints and seasonal leaf materials
 * (leaf_look.h). */
#include "leaf_look.h"

#include "base/noise.h"
#include "base/rng.h"

/* Streams of the per-leaf generators: the index spread over the stream
 * space (an odd multiplier) so neighbouring leaves' streams differ in
 * many bits. */
#define LEAF_LOOK_SALT 0x1eaf100cULL
#define LEAF_LOOK_MUL 0x9E3779B97F4A7C15ULL
#define LEAF_IVY_CELL_SALT 0x1eafce11ULL /* the ivy's young / grown cell draw */

void leaf_atlas_grid(int32_t kind, int32_t *cols, int32_t *rows, double *aspect) {
    banyan_atlas_layout L;
    *cols = *rows = 1;
    if (aspect) *aspect = 1.0;
    if (banyan_texture_layout(kind, &L, NULL) == BANYAN_OK && L.cols >= 1 && L.rows >= 1) {
        *cols = L.cols;
        *rows = L.rows;
        if (aspect && L.leaf_aspect > 0.05f && L.leaf_aspect < 20.0f) *aspect = L.leaf_aspect;
    }
}

void leaf_look_of(uint64_t seed, uint64_t index, int32_t cols, int32_t rows, int32_t season, leaf_look *out) {
    pcg32 r;
    pcg32_seed(&r, seed, (index + 1) * LEAF_LOOK_MUL ^ LEAF_LOOK_SALT);
    uint32_t cells = (uint32_t)(cols * rows), c = rng_below(&r, cells);
    out->du = 1.0 / cols;
    out->dv = 1.0 / rows;
    out->u0 = (double)(c % (uint32_t)cols) * out->du;
    out->v0 = (double)(c / (uint32_t)cols) * out->dv;
    /* Leaves of one plant differ a little in light and hue; autumn leaves
     * turn at their own pace, so their green and blue vary more (from
     * yellow through orange to red). */
    double f = 0.80 + 0.20 * rng_uniform(&r), a = rng_uniform(&r), b = rng_uniform(&r);
    if (season == BANYAN_SEASON_AUTUMN) {
        out->tint[0] = f;
        out->tint[1] = f * (0.55 + 0.45 * a);
        out->tint[2] = f * (0.60 + 0.40 * b);
    } else {
        out->tint[0] = f * (0.85 + 0.15 * a);
        out->tint[1] = f;
        out->tint[2] = f * (0.80 + 0.20 * b);
    }
    out->tint[3] = 1.0;
}

void leaf_look_ivy(uint64_t seed, uint64_t index, int32_t cols, int32_t rows, int young, int32_t season,
                   leaf_look *out) {
    leaf_look_of(seed, index, cols, rows, season, out);
    const uint64_t cells = (uint64_t)cols * (uint64_t)rows, young_cells = cells / 4, grown = cells - young_cells;
    const uint64_t h = noise_mix(noise_mix(seed ^ LEAF_IVY_CELL_SALT) + index);
    uint64_t c;
    if (young && young_cells) c = 4 * (h % young_cells) + 3;
    else c = 4 * ((h % grown) / 3) + (h % grown) % 3;
    out->u0 = (double)(c % (uint64_t)cols) * out->du;
    out->v0 = (double)(c / (uint64_t)cols) * out->dv;
}

void leaf_look_keyaki(uint64_t seed, uint64_t index, int spray, int32_t season, leaf_look *out) {
    /* A single leaf: leaf_look_of over a 4 x 3 grid (the cells above the
     * spray row), shifted up a row; the same draws, so the same tint. */
    leaf_look_of(seed, index, 4, 3, season, out);
    out->dv = 0.25;
    out->v0 = out->v0 * 0.75 + 0.25;
    if (spray) { /* the same stream's cell draw picks a spray: its parity */
        int32_t c = (int32_t)(out->u0 * 4.0 + 0.5) + 4 * (int32_t)((out->v0 - 0.25) * 4.0 + 0.5);
        out->u0 = (double)(c % LEAF_KEYAKI_SPRAYS) / LEAF_KEYAKI_SPRAYS;
        out->du = 1.0 / LEAF_KEYAKI_SPRAYS;
        out->v0 = 0.0;
        out->dv = 0.25;
    }
}

void leaf_material_set(banyan_material *m, int32_t kind, int32_t season, const double summer_rgba[4]) {
    /* Flat autumn colours (linear): keyaki orange-rust, Boston ivy scarlet
     * (shared/reference/plants.md). */
    static const double keyaki_autumn[3] = {0.51, 0.13, 0.021}, ivy_autumn[3] = {0.40, 0.013, 0.017};
    m->texture = kind;
    m->season = season;
    m->alpha_cutoff = 0.5f;
    m->translucency = 0.3f;
    if (season == BANYAN_SEASON_AUTUMN) {
        const double *c = kind == BANYAN_TEX_IVY_LEAF ? ivy_autumn : keyaki_autumn;
        for (int i = 0; i < 3; i++) m->base_color[i] = (float)c[i];
    } else {
        for (int i = 0; i < 3; i++) m->base_color[i] = (float)summer_rgba[i];
    }
    m->base_color[3] = (float)summer_rgba[3];
}

void bark_material_set(banyan_material *m, int32_t kind) {
    m->texture = kind;
    m->season = 0;
    m->alpha_cutoff = 0.0f;
    m->translucency = 0.0f;
}
