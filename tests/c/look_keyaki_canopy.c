/* look_keyaki_canopy: canopy_checks.h's figures of the keyaki presets in
 * summer leaf, seeds 1..5: keyaki_mature, keyaki_young and the tree of
 * avenue_boulevard (its tree params, seed = the avenue's seed + index as
 * the avenue gives its trees, without the avenue's height and position
 * jitter). Leaves are alpha-tested against the atlas the glTF writer
 * draws (1024 px, texture seed 1); rays every 5 cm from 1.6 m above the
 * tree's foot. Prints one row per tree; exits 1 on a library error.
 *   look_keyaki_canopy [SEEDS]   (default 5) */
#include <stdio.h>
#include <stdlib.h>

#include "banyan/keyaki.h"
#include "banyan/textures.h"
#include "canopy_checks.h"
#include "test_files.h"

typedef struct alpha_plane {
    int32_t kind, season;
    canopy_alpha a;
    uint8_t *bytes;
} alpha_plane;

/* The alpha plane of a leaf material's atlas (drawn once per kind and season). */
static const canopy_alpha *plane_of(const banyan_material *mat, alpha_plane *cache, int *n) {
    if (mat->texture < 0 || mat->alpha_cutoff <= 0) return NULL;
    for (int i = 0; i < *n; i++)
        if (cache[i].kind == mat->texture && cache[i].season == mat->season) return &cache[i].a;
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.kind = mat->texture, tp.season = mat->season, tp.size = 1024, tp.seed = 1;
    banyan_image *img = NULL;
    banyan_error err = {0, ""};
    if (banyan_texture_generate(&tp, &img, NULL, &err) != BANYAN_OK || img->channels != 4) {
        fprintf(stderr, "texture %d: %s\n", mat->texture, err.message);
        exit(1);
    }
    alpha_plane *c = &cache[(*n)++];
    c->kind = mat->texture, c->season = mat->season;
    c->bytes = malloc((size_t)img->width * img->height);
    for (size_t k = 0; k < (size_t)img->width * img->height; k++) c->bytes[k] = img->pixels[4 * k + 3];
    c->a = (canopy_alpha){(int32_t)img->width, (int32_t)img->height, c->bytes};
    banyan_image_free(img);
    return &c->a;
}

static int measure(const char *label, const banyan_keyaki_params *p, alpha_plane *cache, int *n_cache) {
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    if (banyan_keyaki_generate(p, &m, &err) != BANYAN_OK) {
        fprintf(stderr, "%s: %s\n", label, err.message);
        return 1;
    }
    const canopy_alpha *alpha[64] = {0};
    for (uint32_t k = 0; k < m->material_count && k < 64; k++) alpha[k] = plane_of(&m->materials[k], cache, n_cache);
    canopy_figures f;
    if (canopy_measure(m, -1, alpha, 0.05, 1.6, &f))
        printf("| %s | %llu | %.1f | %.0f | %.0f | %.2f | %.2f | %.2f | %lld |\n", label, (unsigned long long)p->seed,
               f.height_m, f.outline_m2, f.leaf_m2, f.lai, f.gap_below, f.low_share, (long long)f.triangles);
    else
        printf("| %s | %llu | no leaves |\n", label, (unsigned long long)p->seed);
    fflush(stdout);
    banyan_mesh_free(m);
    return 0;
}

int main(int argc, char **argv) {
    int seeds = argc > 1 ? atoi(argv[1]) : 5, rc = 0, n_cache = 0;
    alpha_plane cache[8];
    printf("| preset | seed | height m | outline m2 | leaf m2 (alpha >= 0.5) | LAI | gap from below | leaf area below "
           "half height | triangles |\n|---|---|---|---|---|---|---|---|---|\n");
    const char *names[2] = {"keyaki_mature", "keyaki_young"};
    char path[512];
    banyan_error err = {0, ""};
    for (int k = 0; k < 2; k++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, names[k]);
        if (test_load_preset(BANYAN_GEN_KEYAKI, &p, path, NULL, 0, NULL, &err) != BANYAN_OK) {
            fprintf(stderr, "%s: %s\n", names[k], err.message);
            return 1;
        }
        for (int s = 1; s <= seeds; s++) {
            p.seed = (uint64_t)s;
            rc |= measure(names[k], &p, cache, &n_cache);
        }
    }
    banyan_avenue_params a;
    banyan_avenue_params_init(&a);
    snprintf(path, sizeof path, "%s/presets/avenue_boulevard.json", BANYAN_SOURCE_DIR);
    if (test_load_preset(BANYAN_GEN_AVENUE, &a, path, NULL, 0, NULL, &err) != BANYAN_OK) {
        fprintf(stderr, "avenue_boulevard: %s\n", err.message);
        return 1;
    }
    for (int s = 0; s < seeds; s++) {
        banyan_keyaki_params t = a.tree;
        t.seed = a.seed + (uint64_t)s;
        rc |= measure("avenue_boulevard tree", &t, cache, &n_cache);
    }
    for (int i = 0; i < n_cache; i++) free(cache[i].bytes);
    return rc;
}
