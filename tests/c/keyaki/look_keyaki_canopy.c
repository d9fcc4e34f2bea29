/* look_keyaki_canopy: keyaki_canopy.h's figures of the keyaki presets in
 * summer leaf, seeds 1..N: keyaki_mature, keyaki_young and the tree of
 * avenue_boulevard (its tree params, seed = the avenue's seed + index as
 * the avenue gives its trees, without the avenue's height and position
 * jitter). Prints one row per tree; exits 1 on a library error.
 *   look_keyaki_canopy [SEEDS]   (default 5) */
#include "keyaki_canopy.h"

static int row(const char *label, const banyan_keyaki_params *p, keyaki_canopy_cache *c) {
    canopy_figures f;
    banyan_error err = {0, ""};
    int r = keyaki_canopy_of(p, c, &f, &err);
    if (r < 0) {
        fprintf(stderr, "%s: %s\n", label, err.message);
        return 1;
    }
    if (r)
        printf("| %s | %llu | %.1f | %.0f | %.0f | %.2f | %.2f | %.2f | %lld |\n", label, (unsigned long long)p->seed,
               f.height_m, f.outline_m2, f.leaf_m2, f.lai, f.gap_below, f.low_share, (long long)f.triangles);
    else
        printf("| %s | %llu | no leaves |\n", label, (unsigned long long)p->seed);
    fflush(stdout);
    return 0;
}

int main(int argc, char **argv) {
    int seeds = argc > 1 ? atoi(argv[1]) : 5, rc = 0;
    keyaki_canopy_cache cache = {.n = 0};
    printf("| preset | seed | height m | outline m2 | leaf m2 (alpha >= 0.5) | LAI | gap from below | leaf area below "
           "half height | triangles |\n|---|---|---|---|---|---|---|---|---|\n");
    const char *names[2] = {"keyaki_mature", "keyaki_young"};
    banyan_error err = {0, ""};
    banyan_keyaki_params p;
    for (int k = 0; k < 2; k++) {
        if (!keyaki_canopy_preset(names[k], &p, &err)) {
            fprintf(stderr, "%s: %s\n", names[k], err.message);
            return 1;
        }
        for (int s = 1; s <= seeds; s++) {
            p.seed = (uint64_t)s;
            rc |= row(names[k], &p, &cache);
        }
    }
    for (int s = 0; s < seeds; s++) {
        if (!keyaki_canopy_boulevard_tree(s, &p, &err)) {
            fprintf(stderr, "avenue_boulevard: %s\n", err.message);
            return 1;
        }
        rc |= row("avenue_boulevard tree", &p, &cache);
    }
    keyaki_canopy_cache_free(&cache);
    return rc;
}
