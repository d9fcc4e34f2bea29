/* The fused roots surface is clean and light (docs/roots.md "Fused
 * surface"), measured with roots_look_checks.h:
 *   - on the default net (default params on the CLI's trunk) and every
 *     presets/roots_*.json (box and mesh hosts), seed 1: no two triangles
 *     that share no vertex intersect or come within 0.5 mm of each other
 *     (sheets nearly touching, which a tolerant intersection test counts);
 *   - the default net written as .glb with the writer's defaults (bark
 *     textures included) is at most 6 MB, seeds 1-5. */
#include <stdio.h>

#include "check.h"
#include "roots_look_checks.h"
#include "test_files.h"

static const char *out_dir = "/tmp";

static void clean(const char *name, const banyan_roots_params *p, const banyan_hosts *H) {
    banyan_mesh *m = NULL;
    banyan_error err;
    banyan_status s = banyan_roots_generate(p, H, &m, NULL, NULL, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (s) return;
    int64_t crossing = rl_self_intersections(m, NULL, 0), close = rl_close_pairs(m, 5e-4, NULL, 0);
    printf("%-18s %u triangles: %lld intersecting pairs, %lld within 0.5 mm\n", name, m->index_count / 3,
           (long long)crossing, (long long)close);
    CHECK(crossing == 0, "%s: %lld intersecting triangle pairs", name, (long long)crossing);
    CHECK(close == 0, "%s: %lld triangle pairs within 0.5 mm", name, (long long)close);
    banyan_mesh_free(m);
}

static void preset(const char *path, const char *name, void *ctx) {
    (void)ctx;
    banyan_roots_params p;
    banyan_error err;
    banyan_hosts *H = NULL;
    banyan_status s = test_load_roots(path, &p, &H, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (!s) {
        p.seed = 1;
        clean(name, &p, H);
    }
    banyan_hosts_free(H);
}

int main(int argc, char **argv) {
    if (argc > 1) out_dir = argv[1];
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    banyan_hosts *H = NULL;
    banyan_error err;
    CHECK(banyan_hosts_create(&trunk, 1, NULL, 0, &H, &err) == BANYAN_OK, "trunk: %s", err.message);
    if (!H) return check_done("test_roots_surface");
    p.seed = 1;
    clean("default", &p, H);

    for (uint64_t seed = 1; seed <= 5; seed++) {
        p.seed = seed;
        banyan_mesh *m = NULL;
        banyan_status s = banyan_roots_generate(&p, H, &m, NULL, NULL, &err);
        CHECK(s == BANYAN_OK, "default seed %llu: %s", (unsigned long long)seed, err.message);
        if (s) continue;
        long long size = rl_glb_size(m, out_dir, NULL, &err);
        printf("default seed %llu: %u triangles, .glb %lld bytes\n", (unsigned long long)seed, m->index_count / 3,
               size);
        CHECK(size > 0, "default seed %llu: writing: %s", (unsigned long long)seed, err.message);
        CHECK(size <= 6000000, "default seed %llu: .glb %lld bytes, more than 6 MB", (unsigned long long)seed, size);
        banyan_mesh_free(m);
    }
    banyan_hosts_free(H);

    int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "roots_", preset, NULL);
    n += test_each_mesh_preset(BANYAN_SOURCE_DIR "/presets", "roots_", preset, NULL);
    CHECK(n >= 7, "found %d presets/roots_*.json", n);
    return check_done("test_roots_surface");
}
