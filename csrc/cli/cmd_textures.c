/* `banyan textures -o DIR [--size N] [--seed N]`: writes every texture
 * the library draws (banyan/textures.h) as PNG files into DIR, named
 * <kind>[_<season>]_{color,normal}.png; docs/img/materials/ is made with
 * it. It is not a mesh generator, so main() hands it argv directly. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "core/atomic_file.h"

static const char *const kind_names[BANYAN_TEX_COUNT] = {"keyaki_leaf", "ivy_leaf", "keyaki_bark", "fig_bark",
                                                         "ivy_stem"};

static int write_png(const char *dir, const char *name, const banyan_image *im) {
    uint8_t *png = NULL;
    size_t len = 0;
    banyan_error e;
    if (banyan_image_png(im, &png, &len, &e) != BANYAN_OK) {
        fprintf(stderr, "banyan textures: %s\n", e.message);
        return 1;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    int bad = atomic_write(path, png, len); /* a failed write leaves the old PNG */
    banyan_png_free(png);
    if (bad) {
        fprintf(stderr, "banyan textures: cannot write %s: %s\n", path, strerror(bad));
        return 1;
    }
    printf("%s\n", path);
    return 0;
}

/* A decimal number of at most 18 digits (no sign, no trailing junk). */
static int whole(const char *s) {
    size_t n = strlen(s);
    if (n == 0 || n > 18) return 0;
    for (size_t i = 0; i < n; i++)
        if (s[i] < '0' || s[i] > '9') return 0;
    return 1;
}

int cli_textures_main(int argc, char **argv) {
    const char *dir = NULL;
    banyan_texture_params p;
    banyan_texture_params_init(&p);
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if ((!strcmp(a, "-o") || !strcmp(a, "--out")) && has) dir = argv[++i];
        else if (!strcmp(a, "--size") && has && whole(argv[i + 1])) p.size = (int32_t)strtol(argv[++i], NULL, 10);
        else if (!strcmp(a, "--seed") && has && whole(argv[i + 1])) p.seed = strtoull(argv[++i], NULL, 10);
        else {
            fprintf(stderr, "usage: banyan textures -o DIR [--size N] [--seed N]\n");
            return 2;
        }
    }
    if (!dir) {
        fprintf(stderr, "usage: banyan textures -o DIR [--size N] [--seed N]\n");
        return 2;
    }
    /* The folder is checked before any texture is drawn. */
    char first[4096], why[4400];
    snprintf(first, sizeof first, "%s/%s_summer_color.png", dir, kind_names[0]);
    if (atomic_check(first, why, sizeof why)) {
        fprintf(stderr, "banyan textures: -o %s: %s\n", dir, why);
        return 1;
    }
    for (int k = 0; k < BANYAN_TEX_COUNT; k++) {
        int leaf = k == BANYAN_TEX_KEYAKI_LEAF || k == BANYAN_TEX_IVY_LEAF;
        for (int s = 0; s < (leaf ? 2 : 1); s++) {
            p.kind = k;
            p.season = s;
            banyan_image *bc = NULL, *nm = NULL;
            banyan_error e;
            if (banyan_texture_generate(&p, &bc, &nm, &e) != BANYAN_OK) {
                fprintf(stderr, "banyan textures: %s\n", e.message);
                return 1;
            }
            char name[128];
            snprintf(name, sizeof name, "%s%s", kind_names[k], leaf ? (s ? "_autumn" : "_summer") : "");
            char cn[160], nn[160];
            snprintf(cn, sizeof cn, "%s_color", name);
            snprintf(nn, sizeof nn, "%s_normal", name);
            int rc = write_png(dir, cn, bc) || write_png(dir, nn, nm);
            banyan_image_free(bc);
            banyan_image_free(nm);
            if (rc) return 1;
        }
    }
    return 0;
}
