/* test_keyaki_look: the measures of a keyaki that reads as a
 * keyaki, on the shipped presets over seeds 1..10.
 *   - keyaki_mature and keyaki_young: at least 3 limbs of at least 0.4 of
 *     the trunk's diameter leave the trunk below 0.35 of the tree's height
 *     (the trunk: the vertical chain from the base through the thicker
 *     child; a limb: a branch leaving it, leaning more than 14 deg).
 *   - the skeleton's Strahler statistics: the body (twigs, light, leaves,
 *     flare) never changes them; a limb of keyaki_mature, grown as the
 *     model's whole tree, has the whole tree's bifurcation ratios.
 *   - keyaki_mature: >= 3,000 twig tips, >= 20,000 leaves; on every preset
 *     leaf length p10 >= 3 cm, p90 <= 8 cm, and >= 85 % of the 0.5 m plan
 *     cells inside the crown's outline (convex hull of the leaves, plan
 *     view) hold a leaf. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "keyaki/keyaki_internal.h"
#include "textures/leaf_look.h"
#include "keyaki_crown_checks.h"
#include "test_files.h"

#define SEEDS 10

static int load(const char *name, uint64_t seed, banyan_keyaki_params *p) {
    char path[512];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    banyan_keyaki_params_init(p);
    banyan_error err = {0, ""};
    banyan_status s = test_load_preset(BANYAN_GEN_KEYAKI, p, path, NULL, 0, NULL, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    p->seed = seed;
    return s == BANYAN_OK;
}

/* The child the trunk continues into: the thicker one. */
static int32_t thicker(const keyaki_node *n, int32_t i) {
    int32_t a = n[i].child[0], b = n[i].child[1];
    if (a < 0) return b;
    if (b < 0) return a;
    return n[b].radius > n[a].radius ? b : a;
}

static double node_top(const keyaki_node *x) { return x->start.z + x->dir.z * x->length; }

/* Limbs of at least 0.4 of the trunk's radius leaving the trunk below
 * `below` metres above the base. The trunk is walked from the base
 * through the thicker child while it stays within 14 deg of vertical; a
 * child of a trunk branch that is not the trunk's next branch, or the
 * thicker child where the trunk stops being vertical, is a limb. */
static int big_limbs(const keyaki_node *n, double below) {
    const double r0 = n[0].radius, base = n[0].start.z, vertical = cos(14.0 * BANYAN_PI / 180.0);
    int count = 0;
    for (int32_t i = 0; i >= 0;) {
        int32_t next = thicker(n, i);
        if (next >= 0 && n[next].dir.z < vertical) next = -1; /* the trunk ends in this fork */
        for (int c = 0; c < 2; c++) {
            int32_t k = n[i].child[c];
            if (k < 0 || k == next) continue;
            if (n[k].radius >= 0.4 * r0 && n[k].start.z - base < below) count++;
        }
        i = next;
    }
    return count;
}

static void limbs(const char *name) {
    int worst = 1 << 30;
    for (uint64_t seed = 1; seed <= SEEDS; seed++) {
        banyan_keyaki_params p;
        if (!load(name, seed, &p)) return;
        keyaki_skeleton sk = {NULL, 0, 0, NULL};
        CHECK(keyaki_grow(&p, &sk, NULL) == BANYAN_OK, "%s: grow", name);
        double top = p.position[2];
        for (int32_t i = 0; i < sk.count; i++)
            if (node_top(&sk.nodes[i]) > top) top = node_top(&sk.nodes[i]);
        int k = big_limbs(sk.nodes, 0.35 * (top - p.position[2]));
        if (k < worst) worst = k;
        CHECK(k >= 3, "%s seed %d: %d limbs of >= 0.4 trunk diameter below 0.35 of the height", name, (int)seed, k);
        keyaki_skeleton_free(&sk);
    }
    printf("%s: at least %d big limbs below 0.35 of the height (seeds 1..%d)\n", name, worst, SEEDS);
}

/* The paper's single trunk splits high into one Y: the measure must see
 * fewer than 3 limbs there, or it measures nothing. */
static void limbs_measure_sees_the_paper_tree(void) {
    int most = 0;
    for (uint64_t seed = 1; seed <= SEEDS; seed++) {
        banyan_keyaki_params p;
        if (!load("keyaki_model_edaore", seed, &p)) return;
        keyaki_skeleton sk = {NULL, 0, 0, NULL};
        CHECK(keyaki_grow(&p, &sk, NULL) == BANYAN_OK, "grow");
        int k = big_limbs(sk.nodes, 0.35 * 17.0);
        if (k > most) most = k;
        keyaki_skeleton_free(&sk);
    }
    CHECK(most < 3, "the paper's tree has %d big low limbs: the limb measure cannot tell", most);
}

/* The body never changes the skeleton: the statistics with every body
 * feature off equal those with the preset's. */
static void body_keeps_skeleton(const char *name) {
    for (uint64_t seed = 1; seed <= SEEDS; seed++) {
        banyan_keyaki_params p, q;
        if (!load(name, seed, &p)) return;
        q = p;
        q.twig_levels = 0;
        q.light = 0;
        q.leaves = 0;
        q.flare = 0;
        q.leaf_levels = 0;
        banyan_keyaki_stats a, b;
        CHECK(banyan_keyaki_skeleton_stats(&p, &a, NULL) == BANYAN_OK && banyan_keyaki_skeleton_stats(&q, &b, NULL) == BANYAN_OK,
              "%s: stats", name);
        CHECK(memcmp(&a, &b, sizeof a) == 0, "%s seed %d: the body changed the skeleton's statistics", name,
              (int)seed);
    }
}

/* Copies the subtree of node r into out (indices renumbered, parents
 * first as in the skeleton) and returns its size. */
static int32_t subtree(const keyaki_node *n, int32_t count, int32_t r, keyaki_node *out, int32_t *map) {
    int32_t m = 0;
    for (int32_t i = 0; i < count; i++) map[i] = -1;
    for (int32_t i = r; i < count; i++) {
        if (i != r && (n[i].parent < 0 || map[n[i].parent] < 0)) continue;
        map[i] = m;
        out[m] = n[i];
        out[m].parent = i == r ? -1 : map[n[i].parent];
        out[m].child[0] = out[m].child[1] = -1;
        if (i != r) {
            keyaki_node *P = &out[out[m].parent];
            if (P->child[0] < 0) P->child[0] = m;
            else P->child[1] = m;
        }
        m++;
    }
    return m;
}

/* keyaki_mature's limbs each grow as the edaore model's whole tree of the
 * same levels: their mean bifurcation ratios and tip counts agree with
 * those of single-trunk trees (limbs = 1) over the same seeds. */
static void limb_statistics(void) {
    double limb_r = 0, tree_r = 0, limb_tips = 0, tree_tips = 0;
    int nl = 0, nt = 0;
    for (uint64_t seed = 1; seed <= SEEDS; seed++) {
        banyan_keyaki_params p;
        if (!load("keyaki_mature", seed, &p)) return;
        keyaki_skeleton sk = {NULL, 0, 0, NULL};
        CHECK(keyaki_grow(&p, &sk, NULL) == BANYAN_OK, "grow");
        keyaki_node *sub = malloc(sizeof *sub * (size_t)sk.count);
        int32_t *map = malloc(sizeof *map * (size_t)sk.count);
        int limbs_seen = 0;
        for (int32_t i = 1; i < sk.count && sub && map; i++) {
            if ((sk.nodes[i].flags & KN_TRUNK) || sk.nodes[i].level != 0) continue;
            int32_t m = subtree(sk.nodes, sk.count, i, sub, map);
            banyan_keyaki_stats st;
            CHECK(keyaki_strahler(sub, m) == BANYAN_OK, "strahler");
            keyaki_measure(sub, m, sub[0].start, &st);
            limb_r += st.mean_bifurcation_ratio;
            limb_tips += st.tip_count;
            nl++;
            limbs_seen++;
        }
        CHECK(limbs_seen == p.limbs, "seed %d: %d limbs, want %d", (int)seed, limbs_seen, p.limbs);
        free(sub);
        free(map);
        keyaki_skeleton_free(&sk);
        for (uint64_t s2 = 1; s2 <= 5; s2++) { /* 5 single-trunk trees per seed: as many as limbs */
            banyan_keyaki_params q = p;
            q.limbs = 1;
            q.seed = seed * 100 + s2;
            banyan_keyaki_stats st;
            CHECK(banyan_keyaki_skeleton_stats(&q, &st, NULL) == BANYAN_OK, "stats");
            tree_r += st.mean_bifurcation_ratio;
            tree_tips += st.tip_count;
            nt++;
        }
    }
    limb_r /= nl, tree_r /= nt, limb_tips /= nl, tree_tips /= nt;
    printf("keyaki_mature limbs: mean bifurcation ratio %.3f, %.1f tips (%d limbs); single trunks of the same levels "
           "%.3f, %.1f tips (%d trees)\n",
           limb_r, limb_tips, nl, tree_r, tree_tips, nt);
    CHECK(fabs(limb_r - tree_r) < 0.15, "limb bifurcation ratio %.3f vs whole tree %.3f", limb_r, tree_r);
    CHECK(fabs(limb_tips - tree_tips) < 0.2 * tree_tips, "limb tips %.1f vs whole tree %.1f", limb_tips, tree_tips);
}

static int dbl_cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Twigs, leaves and the crown's plan on a preset over the seeds: counts
 * (when min_tips / min_leaves > 0), blade lengths and plan coverage. */
static void crown(const char *name, int min_tips, int min_leaves, double min_filled) {
    int tips_lo = 1 << 30, leaves_lo = 1 << 30;
    double p10_lo = 1, p90_hi = 0, filled_lo = 1;
    for (uint64_t seed = 1; seed <= SEEDS; seed++) {
        banyan_keyaki_params p;
        if (!load(name, seed, &p)) return;
        keyaki_skeleton sk = {NULL, 0, 0, NULL};
        keyaki_crown c;
        if (keyaki_grow(&p, &sk, NULL) || keyaki_strahler(sk.nodes, sk.count) ||
            keyaki_crown_grow(&p, sk.nodes, sk.count, 0, NULL, &c, NULL)) {
            CHECK(0, "%s seed %d: crown grows", name, (int)seed);
            keyaki_skeleton_free(&sk);
            continue;
        }
        double *len = malloc(sizeof(double) * (size_t)(c.n_leaves + 1));
        const double blade = LEAF_KEYAKI_BLADE_V1 - LEAF_KEYAKI_BLADE_V0;
        int32_t singles = 0; /* single leaves: spray cards carry many painted leaves */
        for (int32_t i = 0; i < c.n_leaves; i++)
            if (!c.leaves[i].card) len[singles++] = c.leaves[i].length * blade;
        qsort(len, (size_t)singles, sizeof(double), dbl_cmp);
        double p10 = singles ? len[singles / 10] : 0, p90 = singles ? len[(singles * 9) / 10] : 1;
        crown_plan pl;
        crown_plan_measure(&c, 0.5, &pl);
        double filled = pl.inside ? (double)pl.filled / pl.inside : 0;
        CHECK(p10 >= 0.03 && p90 <= 0.08, "%s seed %d: blade length p10 %.4f p90 %.4f m", name, (int)seed, p10, p90);
        CHECK(filled >= min_filled, "%s seed %d: %.1f %% of the 0.5 m plan cells in the crown's outline hold leaves",
              name, (int)seed, 100 * filled);
        if (min_tips) CHECK(c.tips >= min_tips, "%s seed %d: %d twig tips", name, (int)seed, c.tips);
        if (min_leaves) CHECK(c.n_leaves >= min_leaves, "%s seed %d: %d leaves", name, (int)seed, c.n_leaves);
        if (c.tips < tips_lo) tips_lo = c.tips;
        if (c.n_leaves < leaves_lo) leaves_lo = c.n_leaves;
        if (p10 < p10_lo) p10_lo = p10;
        if (p90 > p90_hi) p90_hi = p90;
        if (filled < filled_lo) filled_lo = filled;
        free(len);
        keyaki_crown_free(&c);
        keyaki_skeleton_free(&sk);
    }
    printf("%s (seeds 1..%d): at least %d twig tips and %d leaves; blade p10 >= %.1f cm, p90 <= %.1f cm; "
           "plan cells filled >= %.1f %%\n",
           name, SEEDS, tips_lo, leaves_lo, 100 * p10_lo, 100 * p90_hi, 100 * filled_lo);
}

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    limbs("keyaki_mature");
    limbs("keyaki_young");
    limbs_measure_sees_the_paper_tree();
    const char *models[] = {"keyaki_model_simple", "keyaki_model_strong_weak", "keyaki_model_twisted",
                            "keyaki_model_edaore", "keyaki_mature", "keyaki_young"};
    for (int i = 0; i < 6; i++) body_keeps_skeleton(models[i]);
    limb_statistics();
    crown("keyaki_mature", 3000, 20000, 0.85);
    crown("keyaki_young", 0, 0, 0.85);
    for (int i = 0; i < 4; i++) crown(models[i], 0, 0, 0.85);
    return check_done("test_keyaki_look");
}
