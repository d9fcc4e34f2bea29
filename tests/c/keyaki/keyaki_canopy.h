/* keyaki_canopy.h - canopy_checks.h's figures of a keyaki tree as the
 * glTF writer ships it: leaves alpha-tested against the atlas the writer
 * draws (1024 px, texture seed 1), rays every 5 cm from 1.6 m above the
 * tree's foot. Shared by look_keyaki_canopy.c (figures to read) and
 * test_keyaki_canopy.c (the summer crown's bounds). */
#ifndef BANYAN_KEYAKI_CANOPY_H
#define BANYAN_KEYAKI_CANOPY_H

#include <stdio.h>
#include <stdlib.h>

#include "banyan/keyaki.h"
#include "banyan/textures.h"
#include "canopy_checks.h"
#include "test_files.h"

/* The alpha planes of the leaf atlases met so far, one per kind and season. */
typedef struct keyaki_canopy_cache {
    struct {
        int32_t kind, season;
        canopy_alpha a;
        uint8_t *bytes;
    } plane[8];
    int n;
} keyaki_canopy_cache;

static inline void keyaki_canopy_cache_free(keyaki_canopy_cache *c) {
    for (int i = 0; i < c->n; i++) free(c->plane[i].bytes);
    c->n = 0;
}

/* The alpha plane of a leaf material's atlas (drawn once per kind and
 * season); NULL for an opaque material, or when the atlas cannot be drawn
 * (err then says why and *failed is set). */
static const canopy_alpha *keyaki_canopy_plane(const banyan_material *mat, keyaki_canopy_cache *c, int *failed,
                                               banyan_error *err) {
    if (mat->texture == BANYAN_TEX_NONE || mat->alpha_cutoff <= 0) return NULL;
    for (int i = 0; i < c->n; i++)
        if (c->plane[i].kind == mat->texture && c->plane[i].season == mat->season) return &c->plane[i].a;
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.kind = mat->texture, tp.season = mat->season, tp.size = 1024, tp.seed = 1;
    banyan_image *img = NULL;
    if (c->n >= 8 || banyan_texture_generate(&tp, &img, NULL, err) != BANYAN_OK || img->channels != 4) {
        banyan_image_free(img);
        *failed = 1;
        return NULL;
    }
    size_t px = (size_t)img->width * img->height;
    uint8_t *bytes = malloc(px);
    if (!bytes) {
        banyan_image_free(img);
        *failed = 1;
        return NULL;
    }
    for (size_t k = 0; k < px; k++) bytes[k] = img->pixels[4 * k + 3];
    c->plane[c->n].kind = mat->texture, c->plane[c->n].season = mat->season;
    c->plane[c->n].bytes = bytes;
    c->plane[c->n].a = (canopy_alpha){(int32_t)img->width, (int32_t)img->height, bytes};
    banyan_image_free(img);
    return &c->plane[c->n++].a;
}

/* Grows tree p and measures it into f: 1 when measured, 0 when the tree
 * has no leaves, -1 on a library error (err says which). */
static int keyaki_canopy_of(const banyan_keyaki_params *p, keyaki_canopy_cache *c, canopy_figures *f,
                            banyan_error *err) {
    banyan_mesh *m = NULL;
    if (banyan_keyaki_generate(p, &m, NULL, NULL, err) != BANYAN_OK) return -1;
    const canopy_alpha *alpha[64] = {0};
    int failed = 0;
    for (uint32_t k = 0; k < m->material_count && k < 64; k++)
        alpha[k] = keyaki_canopy_plane(&m->materials[k], c, &failed, err);
    int r = failed ? -1 : canopy_measure(m, -1, alpha, 0.05, 1.6, f) ? 1 : 0;
    banyan_mesh_free(m);
    return r;
}

/* The keyaki params of presets/<name>.json (1, or 0 with err set). */
static inline int keyaki_canopy_preset(const char *name, banyan_keyaki_params *p, banyan_error *err) {
    char path[512];
    banyan_keyaki_params_init(p);
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    return test_load_preset(BANYAN_GEN_KEYAKI, p, path, NULL, 0, NULL, err) == BANYAN_OK;
}

/* Tree i of presets/avenue_boulevard.json as the avenue seeds it (the
 * avenue's seed + i), without its height and position jitter. */
static inline int keyaki_canopy_boulevard_tree(int i, banyan_keyaki_params *p, banyan_error *err) {
    char path[512];
    banyan_avenue_params a;
    banyan_avenue_params_init(&a);
    snprintf(path, sizeof path, "%s/presets/avenue_boulevard.json", BANYAN_SOURCE_DIR);
    if (test_load_preset(BANYAN_GEN_AVENUE, &a, path, NULL, 0, NULL, err) != BANYAN_OK) return 0;
    *p = a.tree;
    p->seed = a.seed + (uint64_t)i;
    return 1;
}

#endif
