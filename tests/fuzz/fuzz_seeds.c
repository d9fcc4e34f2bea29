/* fuzz_seeds.c - seed corpora for the generator harnesses, made from the
 * presets: each preset is applied to its generator's defaults and every
 * field that differs becomes a raw parameter record, every host a raw host
 * record, every segment and the trunk raw records (format: fuzz_common.h).
 * Each preset gives two seeds: <name>, which the harness shrinks, and
 * <name>.real with an FZ_REAL record, run at the preset's real size.
 * Also one seed of plain defaults per harness, and an ivy seed that steps.
 *   fuzz_seeds PRESET_DIR OUT_DIR   writes OUT_DIR/fuzz_<harness>/<name> */
#define _DEFAULT_SOURCE
#include <dirent.h>
#include <errno.h>
#include <sys/stat.h>

#include "../c/common/test_files.h"
#include "fuzz_common.h"

typedef struct seed {
    unsigned char *b;
    size_t n, cap;
} seed;

static void put(seed *s, const void *p, size_t k) {
    if (s->n + k > s->cap) s->b = realloc(s->b, s->cap = 2 * (s->n + k) + 256);
    memcpy(s->b + s->n, p, k);
    s->n += k;
}
static void put8(seed *s, uint8_t v) { put(s, &v, 1); }

static void write_seed(const char *out, const char *harness, const char *name, const seed *s) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", out, harness);
    mkdir(path, 0777);
    snprintf(path, sizeof path, "%s/%s/%s", out, harness, name);
    FILE *f = fopen(path, "wb");
    if (!f || (s->n && fwrite(s->b, 1, s->n, f) != s->n)) {
        fprintf(stderr, "fuzz_seeds: cannot write %s\n", path);
        exit(1);
    }
    fclose(f);
}

/* Raw records for every field where params differs from defaults. */
static void put_params(seed *s, banyan_generator g, const unsigned char *params, const unsigned char *defaults) {
    for (int32_t r = 0; r < banyan_param_count(g); r++) {
        const banyan_param_info *info = banyan_param_get(g, r);
        int comps = fz_components(info->type);
        size_t width = info->type == BANYAN_PT_INT || info->type == BANYAN_PT_BOOL || info->type == BANYAN_PT_ENUM
                           ? 4 : 8;
        for (int c = 0; c < comps; c++) {
            const unsigned char *f = params + info->offset + width * (size_t)c;
            if (memcmp(f, defaults + info->offset + width * (size_t)c, width) == 0) continue;
            uint8_t pay[8] = {0};
            memcpy(pay, f, width);
            put8(s, (uint8_t)r);
            put8(s, (uint8_t)(c << 3)); /* mode 0: raw */
            put(s, pay, 8);
        }
    }
}

static const char *harness_of(banyan_generator g) {
    switch (g) {
    case BANYAN_GEN_ROOTS: return "fuzz_roots";
    case BANYAN_GEN_KEYAKI:
    case BANYAN_GEN_AVENUE: return "fuzz_keyaki";
    case BANYAN_GEN_IVY: return "fuzz_ivy";
    default: return "fuzz_segments";
    }
}

/* The seed of one preset text for generator g. */
static void preset_seed(const char *out, const char *name, banyan_generator g, const char *text, size_t len) {
    static unsigned char params[8192], defaults[8192];
    fz_params_init(g, params);
    fz_params_init(g, defaults);
    banyan_error e;
    if (banyan_preset_apply(g, params, text, len, name, &e)) return; /* another generator's preset */
    seed s = {NULL, 0, 0};
    if (g == BANYAN_GEN_KEYAKI || g == BANYAN_GEN_AVENUE) put8(&s, g == BANYAN_GEN_AVENUE ? 1 : 0);
    put_params(&s, g, params, defaults);
    banyan_box hosts[BANYAN_MAX_HOSTS];
    uint32_t n = 0;
    if (banyan_preset_hosts(text, len, name, hosts, BANYAN_MAX_HOSTS, &n, &e) == BANYAN_OK)
        for (uint32_t i = 0; i < n && i < FZ_MAX_HOSTS; i++) {
            put8(&s, FZ_HOST_RAW);
            put(&s, &hosts[i], sizeof hosts[i]);
        }
    if (g == BANYAN_GEN_SEGMENTS) {
        uint32_t count = 0;
        double trunk[6];
        int32_t has = 0;
        if (banyan_segments_preset_read(text, len, name, NULL, 0, &count, NULL, NULL, &e) == BANYAN_OK && count) {
            banyan_segment_input *segs = malloc(sizeof *segs * count);
            if (banyan_segments_preset_read(text, len, name, segs, count, &count, trunk, &has, &e) == BANYAN_OK) {
                for (uint32_t i = 0; i < count && i < FZ_MAX_SEGS; i++) {
                    put8(&s, FZ_SEG_RAW);
                    put(&s, &segs[i], sizeof segs[i]);
                }
                if (has) {
                    put8(&s, FZ_TRUNK);
                    put(&s, trunk, sizeof trunk);
                }
            }
            free(segs);
        }
    }
    write_seed(out, harness_of(g), name, &s);
    char real[512];
    snprintf(real, sizeof real, "%s.real", name);
    put8(&s, FZ_REAL);
    write_seed(out, harness_of(g), real, &s);
    free(s.b);
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: fuzz_seeds PRESET_DIR OUT_DIR\n");
        return 2;
    }
    const char *dir = argv[1], *out = argv[2];
    if (mkdir(out, 0777) && errno != EEXIST) {
        fprintf(stderr, "fuzz_seeds: cannot make %s\n", out);
        return 1;
    }
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "fuzz_seeds: cannot open %s\n", dir);
        return 1;
    }
    int made = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        size_t k = strlen(de->d_name);
        if (k < 6 || strcmp(de->d_name + k - 5, ".json") != 0) continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        size_t len = 0;
        char *text = test_read_file(path, &len);
        if (!text) continue;
        for (int g = 0; g < BANYAN_GEN_COUNT; g++) preset_seed(out, de->d_name, (banyan_generator)g, text, len);
        free(text);
        made++;
    }
    closedir(d);
    /* Defaults, and the ivy's stepping path. */
    seed s = {NULL, 0, 0};
    write_seed(out, "fuzz_roots", "defaults", &s);
    write_seed(out, "fuzz_ivy", "defaults", &s);
    write_seed(out, "fuzz_segments", "defaults", &s);
    put8(&s, 0);
    write_seed(out, "fuzz_keyaki", "defaults_tree", &s);
    s.n = 0;
    put8(&s, 1);
    write_seed(out, "fuzz_keyaki", "defaults_avenue", &s);
    s.n = 0;
    const uint8_t steps[] = {FZ_CONTROL, 20, FZ_CONTROL, 130, FZ_CONTROL, 5, FZ_CONTROL, 200};
    put(&s, steps, sizeof steps);
    write_seed(out, "fuzz_ivy", "stepping", &s);
    free(s.b);
    printf("fuzz_seeds: %d presets -> %s\n", made, out);
    return 0;
}
