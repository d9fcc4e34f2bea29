/* test_keyaki_canopy: a keyaki in summer leaf hides the sky as a real
 * broadleaf crown does (docs/keyaki.md "Twigs and leaves";
 * ../shared/reference/plants.md: leaf area index 3-5). Over seeds 1-5 of
 * keyaki_mature and five trees of avenue_boulevard, measured by
 * keyaki_canopy.h as the glTF file ships them:
 *   - alpha-weighted leaf area index 3 to 5;
 *   - gap fraction seen from below (vertical rays from 1.6 m, inside the
 *     leaves' plan outline) <= 0.25;
 *   - at least 15 % of that leaf area in the lower half of the height;
 *   - at most 1.5 M triangles at the finest level.
 * The crown is grown below the skeleton and never moves it: the model
 * presets' Strahler statistics are the paper's (spec/keyaki.md, figures
 * 5-8) as the skeleton growth gives them. */
#include "check.h"
#include "keyaki_canopy.h"

#define LAI_MIN 3.0
#define LAI_MAX 5.0
#define GAP_MAX 0.25
#define LOW_SHARE_MIN 0.15
#define TRIANGLES_MAX 1500000

static void summer_crown(const char *label, const banyan_keyaki_params *p, keyaki_canopy_cache *c) {
    canopy_figures f;
    banyan_error err = {0, ""};
    int r = keyaki_canopy_of(p, c, &f, &err);
    CHECK(r == 1, "%s seed %llu: %s", label, (unsigned long long)p->seed, r ? err.message : "no leaves");
    if (r != 1) return;
    printf("%s seed %llu: LAI %.2f, gap from below %.3f, low share %.3f, %lld triangles, %.1f m tall\n", label,
           (unsigned long long)p->seed, f.lai, f.gap_below, f.low_share, (long long)f.triangles, f.height_m);
    CHECK(f.lai >= LAI_MIN && f.lai <= LAI_MAX, "%s seed %llu: leaf area index %.2f, want %.1f to %.1f", label,
          (unsigned long long)p->seed, f.lai, LAI_MIN, LAI_MAX);
    CHECK(f.gap_below <= GAP_MAX, "%s seed %llu: gap fraction from below %.3f, want <= %.2f", label,
          (unsigned long long)p->seed, f.gap_below, GAP_MAX);
    CHECK(f.low_share >= LOW_SHARE_MIN, "%s seed %llu: %.3f of the leaf area below half the height, want >= %.2f",
          label, (unsigned long long)p->seed, f.low_share, LOW_SHARE_MIN);
    CHECK(f.triangles <= TRIANGLES_MAX, "%s seed %llu: %lld triangles, want <= %d", label,
          (unsigned long long)p->seed, (long long)f.triangles, TRIANGLES_MAX);
}

/* The skeletons of the model presets, recorded from the skeleton growth
 * (keyaki_grow): branches, tips, forks, breaks, deepest level, the trunk's
 * Strahler order and the stream counts N_1 .. N_K. */
typedef struct strahler_row {
    const char *preset;
    int32_t nodes, tips, forks, breaks, max_level, max_order;
    int32_t streams[8];
} strahler_row;

static const strahler_row STRAHLER[] = {
    {"keyaki_model_simple", 127, 64, 63, 0, 6, 7, {64, 32, 16, 8, 4, 2, 1}},
    {"keyaki_model_strong_weak", 307, 154, 153, 0, 11, 6, {154, 60, 21, 9, 3, 1}},
    {"keyaki_model_twisted", 313, 157, 156, 0, 11, 6, {157, 63, 22, 8, 3, 1}},
    {"keyaki_model_edaore", 470, 109, 108, 253, 21, 6, {109, 45, 18, 6, 2, 1}},
};

static void strahler_unchanged(void) {
    for (size_t k = 0; k < sizeof STRAHLER / sizeof STRAHLER[0]; k++) {
        const strahler_row *w = &STRAHLER[k];
        banyan_keyaki_params p;
        banyan_keyaki_stats s;
        banyan_error err = {0, ""};
        int ok = keyaki_canopy_preset(w->preset, &p, &err) && banyan_keyaki_skeleton_stats(&p, &s, &err) == BANYAN_OK;
        CHECK(ok, "%s: %s", w->preset, err.message);
        if (!ok) continue;
        int same = s.node_count == w->nodes && s.tip_count == w->tips && s.fork_count == w->forks &&
                   s.break_count == w->breaks && s.max_level == w->max_level && s.max_order == w->max_order;
        for (int i = 0; i < w->max_order && i < 8; i++) same = same && s.stream_count[i] == w->streams[i];
        CHECK(same, "%s: %d branches, %d tips, %d forks, %d breaks, level %d, order %d (want %d, %d, %d, %d, %d, %d)",
              w->preset, s.node_count, s.tip_count, s.fork_count, s.break_count, s.max_level, s.max_order, w->nodes,
              w->tips, w->forks, w->breaks, w->max_level, w->max_order);
    }
}

int main(void) {
    keyaki_canopy_cache cache = {.n = 0};
    banyan_keyaki_params p;
    banyan_error err = {0, ""};
    CHECK(keyaki_canopy_preset("keyaki_mature", &p, &err), "keyaki_mature: %s", err.message);
    for (uint64_t s = 1; s <= 5; s++) {
        p.seed = s;
        summer_crown("keyaki_mature", &p, &cache);
    }
    for (int i = 0; i < 5; i++) {
        int ok = keyaki_canopy_boulevard_tree(i, &p, &err);
        CHECK(ok, "avenue_boulevard: %s", err.message);
        if (ok) summer_crown("avenue_boulevard tree", &p, &cache);
    }
    keyaki_canopy_cache_free(&cache);
    strahler_unchanged();
    return check_done("test_keyaki_canopy");
}
