/* The ivy light look-up's spatial hash (csrc/ivy/grid.c): each cell keeps
 * its buds in one run of a pool. After growth (which adds buds and moves
 * hanging ones in the sag correction) and after random moves made here,
 * every bud is in exactly one run, the run of its own cell, with its
 * position and birth step; no two runs overlap; and the shade sum H0 /
 * V_l and the stem-crossing query agree with brute force over all buds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy/ivy_internal.h"
#include "ivy_checks.h"
#include "test_files.h"
#include "test_hosts.h"

static int32_t coord(double v, double inv) { return (int32_t)floor(v * inv); }

static int cmp_run(const void *a, const void *b) {
    const ivy_cell *x = *(const ivy_cell *const *)a, *y = *(const ivy_cell *const *)b;
    return (x->at > y->at) - (x->at < y->at);
}

/* Every bud in its own cell's run once, runs disjoint and within the pool. */
static void check_grid(const banyan_ivy *iv, const char *what) {
    int32_t *found = calloc((size_t)iv->n, sizeof(int32_t));
    const ivy_cell **runs = malloc(sizeof *runs * (iv->cmask + 1));
    int bad_cell = 0, bad_copy = 0, bad_id = 0, cells = 0, n_runs = 0;
    int64_t total = 0;
    for (uint32_t k = 0; k <= iv->cmask; k++) {
        const ivy_cell *c = &iv->cells[k];
        if (c->x == INT32_MIN) continue;
        cells++;
        if (c->cap) runs[n_runs++] = c;
        total += c->n;
        for (int32_t e = 0; e < c->n; e++) {
            const ivy_gnode *g = &iv->pool[c->at + e];
            if (g->id < 0 || g->id >= iv->n) {
                bad_id++;
                continue;
            }
            found[g->id]++;
            const ivy_bud *b = &iv->buds[g->id];
            if (coord(b->P.x, iv->inv_cell) != c->x || coord(b->P.y, iv->inv_cell) != c->y ||
                coord(b->P.z, iv->inv_cell) != c->z)
                bad_cell++;
            if (memcmp(&g->P, &b->P, sizeof(v3)) || g->step_c != (b->step_c | (b->follow > 0 ? IVY_GNODE_FOLLOW : 0))) bad_copy++;
        }
    }
    int missing = 0, twice = 0;
    for (int32_t i = 0; i < iv->n; i++) missing += found[i] == 0, twice += found[i] > 1;
    qsort(runs, (size_t)n_runs, sizeof *runs, cmp_run);
    int overlap = 0;
    for (int k = 0; k < n_runs; k++) {
        if (runs[k]->n > runs[k]->cap || runs[k]->at < 0 || runs[k]->at + runs[k]->cap > iv->pool_n) overlap++;
        if (k && runs[k - 1]->at + runs[k - 1]->cap > runs[k]->at) overlap++;
    }
    CHECK(!bad_cell && !bad_copy && !bad_id && !missing && !twice && total == iv->n,
          "%s: %d in the wrong cell, %d stale copies, %d bad ids, %d missing, %d twice, %lld entries for %d buds",
          what, bad_cell, bad_copy, bad_id, missing, twice, (long long)total, iv->n);
    CHECK(cells == iv->n_cells && 2 * (int64_t)cells <= (int64_t)iv->cmask + 1, "%s: %d cells, %d counted, %u slots",
          what, cells, iv->n_cells, iv->cmask + 1);
    CHECK(!overlap, "%s: %d runs overlap or leave the pool", what, overlap);
    free(found);
    free(runs);
}

/* ivy_crosses over every internode (the same test, no hash). */
static int brute_crosses(const banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer) {
    const double r = 1.5 * iv->p.internode;
    const v3 m = v3_scale(v3_add(a, b), 0.5), u = v3_any_perp(n), w = v3_cross(n, u);
    const double ax = v3_dot(a, u), ay = v3_dot(a, w), bx = v3_dot(b, u), by = v3_dot(b, w), ex = bx - ax, ey = by - ay;
    for (int32_t j = 0; j < iv->n; j++) {
        const int32_t pj = iv->buds[j].parent;
        const v3 P = iv->buds[j].P;
        if (pj < 0 || j == self || pj == self) continue;
        if (v3_len2(v3_sub(P, m)) >= r * r || fabs(v3_dot(v3_sub(P, a), n)) > layer) continue;
        v3 c = iv->buds[pj].P;
        double cx = v3_dot(c, u), cy = v3_dot(c, w), dx = v3_dot(P, u) - cx, dy = v3_dot(P, w) - cy;
        double s1 = ex * (cy - ay) - ey * (cx - ax), s2 = ex * (cy + dy - ay) - ey * (cx + dx - ax);
        if ((s1 > 0) == (s2 > 0) || s1 == 0 || s2 == 0) continue;
        double s3 = dx * (ay - cy) - dy * (ax - cx), s4 = dx * (by - cy) - dy * (bx - cx);
        if ((s3 > 0) != (s4 > 0) && s3 != 0 && s4 != 0) return 1;
    }
    return 0;
}

/* Random points near buds (and some far from any): the hash's H0, V_l,
 * early stop and crossings against brute force. */
static void check_queries(const banyan_ivy *iv, uint64_t seed, const char *what) {
    pcg32 r;
    pcg32_seed(&r, seed, 99);
    int bad_h = 0, bad_v = 0, bad_stop = 0, bad_cross = 0, shaded = 0, crossed = 0;
    const int q = 400;
    for (int k = 0; k < q; k++) {
        int32_t i = (int32_t)rng_below(&r, (uint32_t)iv->n);
        double s = k % 5 == 0 ? 1.0 : 0.06;
        v3 p = v3_add(iv->buds[i].P, v3_make(rng_range(&r, -s, s), rng_range(&r, -s, s), rng_range(&r, -s, s)));
        int32_t self = k % 3 ? -1 : i;
        if (self >= 0) p = iv->buds[i].P;
        v3 want_vl, vl = v3_make(0, 0, 0);
        double want = brute_shade(iv, p, self, &want_vl), got = ivy_shade(iv, p, self, HUGE_VAL, &vl);
        bad_h += fabs(got - want) > 1e-9 * (1.0 + want);
        bad_v += v3_dist(vl, want_vl) > 1e-9 * (1.0 + want);
        shaded += want > 2.0;
        double stop = rng_range(&r, 0.5, 6.0);
        bad_stop += (ivy_shade(iv, p, self, stop, NULL) > stop) != (want > stop);
        int32_t j = iv->buds[i].parent >= 0 ? iv->buds[i].parent : i;
        v3 a = iv->buds[j].P, d = v3_norm_or(v3_make(rng_range(&r, -1, 1), 0.0, rng_range(&r, -1, 1)), v3_make(0, 0, 1));
        v3 b = v3_madd(a, d, iv->p.internode), n = v3_make(0, 1, 0);
        int want_c = brute_crosses(iv, a, b, n, j, iv->p.sucker_length);
        crossed += want_c;
        bad_cross += ivy_crosses(iv, a, b, n, j, iv->p.sucker_length) != want_c;
    }
    CHECK(!bad_h && !bad_v && !bad_stop && !bad_cross,
          "%s: of %d queries H0 off %d, V_l off %d, early stop off %d, crossings off %d", what, q, bad_h, bad_v,
          bad_stop, bad_cross);
    /* Not a vacuous comparison: the queries met shade and crossings. */
    CHECK(shaded > q / 10 && crossed > 0, "%s: %d shaded queries, %d crossings", what, shaded, crossed);
}

/* ivy_crosses_near (the random walk's: many internodes from one point, its
 * stems gathered once) against brute force: 10 internodes from each of
 * 300 buds, turned up to 40 degrees off the bud's direction (as the walk's
 * candidates), then the first bud again, so that a later call starts at the
 * point the gathered stems were found for (stale after moves unless the
 * hash's changes are heard). */
static void check_crosses_near(banyan_ivy *iv, uint64_t seed, const char *what) {
    pcg32 r;
    pcg32_seed(&r, seed, 5);
    int bad = 0, crossed = 0, asked = 0;
    int32_t first = -1;
    for (int k = 0; k <= 300; k++) {
        int32_t i = k < 300 ? (int32_t)rng_below(&r, (uint32_t)iv->n) : first;
        if (k == 0) first = i;
        const v3 a = iv->buds[i].P, n = k % 2 ? v3_make(0, 1, 0) : v3_make(1, 0, 0);
        for (int c = 0; c < 10; c++) {
            v3 t = v3_make(rng_range(&r, -0.7, 0.7), rng_range(&r, -0.7, 0.7), rng_range(&r, -0.7, 0.7));
            v3 d = v3_norm_or(v3_add(iv->buds[i].V, t), v3_make(0, 0, 1));
            v3 b = v3_madd(a, d, iv->p.internode);
            int want = brute_crosses(iv, a, b, n, i, iv->p.sucker_length);
            crossed += want;
            bad += ivy_crosses_near(iv, a, b, n, i, iv->p.sucker_length) != want;
            asked++;
        }
    }
    CHECK(!bad && crossed > 0, "%s: of %d crossing queries from shared points %d off, %d crossings", what, asked, bad,
          crossed);
}

/* The gathered stems follow the hash: an internode that crosses a stem,
 * asked again after every other bud near its start has moved away. */
static void check_crosses_stale(banyan_ivy *iv) {
    const double l = iv->p.internode, layer = iv->p.sucker_length;
    const v3 n = v3_make(0, 1, 0);
    int32_t i = 0;
    v3 b = v3_make(0, 0, 0);
    for (; i < iv->n; i++) {
        if (iv->buds[i].parent < 0) continue;
        int c = 0;
        for (; c < 36; c++) {
            b = v3_madd(iv->buds[i].P, v3_make(cos(c * 0.1745), 0, sin(c * 0.1745)), l);
            if (brute_crosses(iv, iv->buds[i].P, b, n, i, layer) && ivy_crosses_near(iv, iv->buds[i].P, b, n, i, layer))
                break;
        }
        if (c < 36) break;
    }
    CHECK(i < iv->n, "no crossing found to move away");
    if (i == iv->n) return;
    const v3 a = iv->buds[i].P;
    int32_t *set = malloc(sizeof(int32_t) * (size_t)iv->n), m = 0;
    v3 *q = malloc(sizeof(v3) * (size_t)iv->n);
    for (int32_t j = 0; j < iv->n; j++)
        if (j != i && j != iv->buds[i].parent && v3_dist(iv->buds[j].P, a) < 4 * l) {
            set[m] = j;
            q[m++] = v3_add(iv->buds[j].P, v3_make(0, 0, 50));
        }
    ivy_grid_move_many(iv, set, q, m);
    iv->n_wake = 0;
    int want = brute_crosses(iv, a, b, n, i, layer);
    CHECK(!want && ivy_crosses_near(iv, a, b, n, i, layer) == want, "after its stems moved away: %d, brute force %d",
          ivy_crosses_near(iv, a, b, n, i, layer), want);
    free(set);
    free(q);
}

/* Moves a third of the buds to random places (some far, into new cells),
 * as the sag correction does, then checks again. */
static void check_moves(banyan_ivy *iv, uint64_t seed) {
    pcg32 r;
    pcg32_seed(&r, seed, 7);
    int32_t n = iv->n / 3, *set = malloc(sizeof(int32_t) * (size_t)n);
    v3 *q = malloc(sizeof(v3) * (size_t)n);
    for (int32_t k = 0; k < n; k++) {
        set[k] = (int32_t)rng_below(&r, (uint32_t)iv->n); /* repeats too: a bud moved twice */
        double s = k % 4 ? 0.1 : 5.0;
        q[k] = v3_add(iv->buds[set[k]].P, v3_make(rng_range(&r, -s, s), rng_range(&r, -s, s), rng_range(&r, -s, s)));
    }
    /* The order a cell's buds are read in (from the run's end) is the
     * light sums' order, kept to keep results byte-identical: buds that
     * stay keep theirs, the moved ones are read first, latest move first. */
    int32_t *rank = malloc(sizeof(int32_t) * (size_t)iv->n), *last = malloc(sizeof(int32_t) * (size_t)iv->n);
    for (uint32_t k = 0; k <= iv->cmask; k++)
        for (int32_t e = 0; e < iv->cells[k].n; e++) rank[iv->pool[iv->cells[k].at + e].id] = e;
    for (int32_t i = 0; i < iv->n; i++) last[i] = -1;
    for (int32_t k = 0; k < n; k++) last[set[k]] = k;
    check_crosses_near(iv, seed + 2, "before random moves");
    ivy_grid_move_many(iv, set, q, n);
    iv->n_wake = 0; /* the woken buds are not stepped here */
    int bad_order = 0;
    for (uint32_t k = 0; k <= iv->cmask; k++) {
        const ivy_cell *c = &iv->cells[k];
        int32_t prev_rank = -1, prev_move = -1;
        for (int32_t e = 0; e < c->n; e++) {
            int32_t id = iv->pool[c->at + e].id;
            if (last[id] < 0) {
                bad_order += prev_move >= 0 || rank[id] <= prev_rank;
                prev_rank = rank[id];
            } else {
                bad_order += last[id] <= prev_move;
                prev_move = last[id];
            }
        }
    }
    CHECK(bad_order == 0, "after random moves: %d buds out of the reading order", bad_order);
    free(rank);
    free(last);
    check_grid(iv, "after random moves");
    check_queries(iv, seed + 1, "after random moves");
    check_crosses_near(iv, seed + 2, "after random moves");
    check_crosses_stale(iv);
    free(set);
    free(q);
}

int main(void) {
    const char *names[] = {"ivy_wall", "ivy_pillar"};
    for (int k = 0; k < 2; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, names[k]);
        banyan_ivy_params p;
        banyan_box hosts[8];
        uint32_t nh = 0;
        banyan_error err = {0, ""};
        banyan_ivy_params_init(&p);
        if (test_load_preset(BANYAN_GEN_IVY, &p, path, hosts, 8, &nh, &err)) {
            CHECK(0, "%s: %s", names[k], err.message);
            continue;
        }
        banyan_ivy *iv = NULL;
        banyan_hosts *H = TEST_HOSTS(hosts, nh);
        CHECK(banyan_ivy_create(&p, H, &iv, &err) == BANYAN_OK, "%s: %s", names[k], err.message);
        if (!iv) {
            banyan_hosts_free(H);
            continue;
        }
        /* Checked along the way: past the reorderings at 2,049 and 8,193
         * buds, with the sag's moves in between. */
        for (int s = 0; s < 3; s++) {
            CHECK(banyan_ivy_step(iv, p.steps / 3, &err) == BANYAN_OK, "%s: %s", names[k], err.message);
            char what[64];
            snprintf(what, sizeof what, "%s at step %d (%d buds)", names[k], iv->step, iv->n);
            check_grid(iv, what);
            check_queries(iv, (uint64_t)(10 * k + s), what);
            check_crosses_near(iv, (uint64_t)(10 * k + s), what);
        }
        CHECK(iv->n > 8193 || k == 1, "%s: %d buds, past the last reordering checked", names[k], iv->n);
        check_moves(iv, (uint64_t)k + 40);
        banyan_ivy_free(iv);
        banyan_hosts_free(H);
    }
    return check_done("test_ivy_grid");
}
