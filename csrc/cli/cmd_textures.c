/* `banyan textures -o DIR [--size N] [--seed N]`: writes every texture
 * the library draws (banyan/textures.h) as PNG files into DIR, named
 * <kind>[_<season>]_{color,normal}.png; docs/img/materials/ is made with
 * it. It is not a mesh generator, so main() hands it argv directly. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "cli.h"
#include "base/atomic_file.h"
#include "base/numparse.h"

static const char *const kind_names[BANYAN_TEX_COUNT] = {
    [BANYAN_TEX_KEYAKI_LEAF] = "keyaki_leaf", [BANYAN_TEX_IVY_LEAF] = "ivy_leaf",
    [BANYAN_TEX_KEYAKI_BARK] = "keyaki_bark", [BANYAN_TEX_FIG_BARK] = "fig_bark", [BANYAN_TEX_IVY_STEM] = "ivy_stem"};

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

static int usage_textures(void) {
    fprintf(stderr, "usage: banyan textures -o DIR [--size N] [--seed N]\n");
    return 2;
}

int cli_textures_main(int argc, char **argv) {
    const char *dir = NULL;
    banyan_texture_params p;
    banyan_texture_params_init(&p);
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if ((!strcmp(a, "-o") || !strcmp(a, "--out")) && has) dir = argv[++i];
        else if (!strcmp(a, "--size") && has) {
            long long n; /* the library checks the range, with its message */
            if (!num_parse_int(argv[++i], 0, INT32_MAX, &n)) {
                fprintf(stderr, "banyan textures: --size '%s' must be a whole number (a power of two in [64, 8192])\n",
                        argv[i]);
                return 2;
            }
            p.size = (int32_t)n;
        } else if (!strcmp(a, "--seed") && has) {
            if (!num_parse_u64(argv[++i], &p.seed)) {
                fprintf(stderr, "banyan textures: --seed '%s' must be a whole number in [0, 2^64-1] (digits only)\n",
                        argv[i]);
                return 2;
            }
        } else
            return usage_textures();
    }
    if (!dir) return usage_textures();
    /* The folder is checked before any texture is drawn. */
    char first[4096], why[4400];
    snprintf(first, sizeof first, "%s/%s_summer_color.png", dir, kind_names[BANYAN_TEX_KEYAKI_LEAF]);
    if (atomic_check(first, why, sizeof why)) {
        fprintf(stderr, "banyan textures: -o %s: %s\n", dir, why);
        return 2; /* a bad command line, as for the mesh commands */
    }
    for (int k = BANYAN_TEX_NONE + 1; k < BANYAN_TEX_COUNT; k++) {
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
