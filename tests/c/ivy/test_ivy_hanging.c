/* Hanging stems (spec/ivy.md, "Sag of unattached stems": no
 * straight parallel curtains), on ivy_pillar and ivy_wall, seeds 1..5,
 * the presets' 450 steps.
 * A hanging run is what hangs from a stem's last held bud: from the end
 * of a stem (a bud without a continuation) up to the first held bud (as
 * sag.c's held: attached or on the ground) on that stem, at least 8 free
 * buds, whose lowest bud lies more than one internode below that anchor.
 * (A free lateral of a free stem is not a run of its own: it would count
 * its parent's path twice.)
 *   - The runs curve: the median straightness (chord anchor -> end over
 *     the path length) is below 0.8 on each preset and 0.1 below that of
 *     the bare sag (sag_stiffening = tip_hook_length = 0) measured in
 *     the same run (0.884 on the pillar).
 *   - Every run, growing or ended, turns its end up: its last 3 buds'
 *     V.z > 0 (the bare sag's: few); and at least 95 % rise over
 *     their last three internodes (the bare sag's: none).
 *   - Enough runs that this means something: at least 100 on the pillar.
 * Printed too, not checked: the median angle between the overall
 * directions (anchor -> lowest bud) of neighbouring runs (anchors within
 * 15 cm), and between their end headings. The runs still hang near
 * plumb, so the first stays small (docs/ivy.md, "Sag"). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy_look.h"
#include "ivy/ivy_internal.h"
#include "test_files.h"
#include "test_hosts.h"

static int held(const banyan_ivy *iv, const ivy_bud *b) {
    return b->attached || (iv->p.ground && b->P.z <= iv->p.ground_z + iv->p.clearance + 1e-9);
}

typedef struct run {
    int32_t anchor, end, n;
    double straight;  /* chord / path */
    int live;         /* its end is a growing tip */
    int v_up;         /* the last 3 buds' V.z > 0 */
    int rise;         /* the last 3 internodes rise */
    double tip_angle; /* of the last 3 internodes together above the horizontal, deg */
    v3 dir;           /* anchor -> lowest bud, unit */
    v3 head;          /* horizontal heading of the last 3 internodes, unit (0 when vertical) */
} run;

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n) {
    if (n == 0) return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The hanging runs of iv, appended to r (at most cap). */
static int find_runs(const banyan_ivy *iv, run *r, int n_r, int cap) {
    const banyan_ivy_params *p = &iv->p;
    for (int32_t i = 0; i < iv->n && n_r < cap; i++) {
        const ivy_bud *e = &iv->buds[i];
        if (e->child[0] >= 0 || held(iv, e)) continue;
        int32_t j = i, m = 0;
        double path = 0, zmin = HUGE_VAL;
        v3 low = e->P;
        int own = 1; /* the run stays on this stem */
        while (j >= 0 && !held(iv, &iv->buds[j])) {
            const ivy_bud *b = &iv->buds[j];
            if (b->P.z < zmin) zmin = b->P.z, low = b->P;
            if (b->parent >= 0) path += v3_dist(b->P, iv->buds[b->parent].P);
            m++;
            if (b->parent >= 0 && iv->buds[b->parent].child[1] == j && !held(iv, &iv->buds[b->parent])) own = 0;
            j = b->parent;
        }
        if (j < 0 || m < 8 || !own) continue;
        v3 A = iv->buds[j].P;
        if (zmin >= A.z - p->internode) continue;
        run *u = &r[n_r++];
        u->anchor = j;
        u->end = i;
        u->n = m;
        u->straight = v3_dist(A, e->P) / path;
        u->live = e->state <= BANYAN_IVY_A2;
        int32_t b3 = i;
        u->v_up = 1;
        u->rise = 1;
        for (int k = 0; k < 3; k++) {
            const ivy_bud *b = &iv->buds[b3];
            u->v_up &= b->V.z > 0;
            u->rise &= b->P.z > iv->buds[b->parent].P.z;
            b3 = b->parent;
        }
        v3 d = v3_sub(e->P, iv->buds[b3].P);
        u->tip_angle = (180.0 / BANYAN_PI) * atan2(d.z, sqrt(d.x * d.x + d.y * d.y));
        u->head = v3_norm_or(v3_make(d.x, d.y, 0), v3_make(0, 0, 0));
        u->dir = v3_norm_or(v3_sub(low, A), v3_make(0, 0, -1));
    }
    return n_r;
}

typedef struct figures {
    int runs, live, live_v_up, live_rise, all_v_up, all_rise, pairs;
    double straight, tip_angle, pair_angle, head_angle;
} figures;

/* Overrides key=value from the command line (after the output folder):
 * to see the figures of other settings; the checks then stay off. */
static int n_set;
static char **sets;
/* The sag as the spec's bare rule leaves it (one joint strength, no hook):
 * straight curtains, measured in the same run to compare. */
static const char *plumb[2] = {"sag_stiffening=0", "tip_hook_length=0"};

static figures measure(const char *name, int n_over, char *const *over) {
    figures f;
    memset(&f, 0, sizeof f);
    banyan_ivy_params base;
    banyan_box hosts[8];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    if (ivy_look_preset(name, &base, hosts, 8, &nh, &err) != BANYAN_OK) {
        CHECK(0, "%s: %s", name, err.message);
        return f;
    }
    for (int k = 0; k < n_over; k++) {
        char key[64];
        const char *eq = strchr(over[k], '=');
        if (!eq || eq - over[k] >= (int)sizeof key) continue;
        memcpy(key, over[k], (size_t)(eq - over[k]));
        key[eq - over[k]] = 0;
        CHECK(banyan_param_set_text(BANYAN_GEN_IVY, &base, key, eq + 1, &err) == BANYAN_OK, "%s", err.message);
    }
    enum { CAP = 4096 };
    run *r = malloc(sizeof *r * CAP);
    double *straight = malloc(sizeof(double) * CAP), *tip = malloc(sizeof(double) * CAP);
    double *ang = malloc(sizeof(double) * CAP * 16), *hang = malloc(sizeof(double) * CAP * 16);
    int n_ang = 0, n_hang = 0;
    banyan_hosts *H = TEST_HOSTS(hosts, nh);
    for (uint64_t seed = 1; seed <= 5; seed++) {
        banyan_ivy_params p = base;
        p.seed = seed;
        banyan_ivy *iv = NULL;
        if (banyan_ivy_create(&p, H, &iv, &err) != BANYAN_OK || banyan_ivy_step(iv, p.steps, &err) != BANYAN_OK) {
            CHECK(0, "%s seed %llu: %s", name, (unsigned long long)seed, err.message);
            banyan_ivy_free(iv);
            continue;
        }
        int n0 = f.runs;
        f.runs = find_runs(iv, r, f.runs, CAP);
        /* Neighbours: anchors within 15 cm, each pair once. */
        for (int a = n0; a < f.runs; a++)
            for (int b = a + 1; b < f.runs && n_ang < CAP * 16; b++)
                if (v3_dist(iv->buds[r[a].anchor].P, iv->buds[r[b].anchor].P) < 0.15) {
                    ang[n_ang++] = (180.0 / BANYAN_PI) * acos(fmax(-1, fmin(1, v3_dot(r[a].dir, r[b].dir))));
                    if (v3_len(r[a].head) > 0 && v3_len(r[b].head) > 0)
                        hang[n_hang++] = (180.0 / BANYAN_PI) * acos(fmax(-1, fmin(1, v3_dot(r[a].head, r[b].head))));
                }
        banyan_ivy_free(iv);
    }
    banyan_hosts_free(H);
    for (int k = 0; k < f.runs; k++) {
        straight[k] = r[k].straight;
        tip[k] = r[k].tip_angle;
        f.all_v_up += r[k].v_up;
        f.all_rise += r[k].rise;
        if (r[k].live) {
            f.live++;
            f.live_v_up += r[k].v_up;
            f.live_rise += r[k].rise;
        }
    }
    f.straight = median(straight, f.runs);
    f.tip_angle = median(tip, f.runs);
    f.pairs = n_ang;
    f.pair_angle = median(ang, n_ang);
    f.head_angle = median(hang, n_hang);
    printf("%s%s: %d hanging runs (%d growing): median straightness %.3f; V.z > 0 at the last 3 buds: %d of all, %d "
           "of the growing; last 3 internodes rising: %d of all, %d of the growing; median end angle %.1f deg; %d neighbour "
           "pairs, median angle between them %.1f deg, between their end headings %.1f deg\n",
           name, n_over ? " (overrides)" : "", f.runs, f.live, f.straight, f.all_v_up, f.live_v_up, f.all_rise, f.live_rise, f.tip_angle, f.pairs, f.pair_angle, f.head_angle);
    free(r);
    free(straight);
    free(tip);
    free(ang);
    free(hang);
    return f;
}

int main(int argc, char **argv) {
    n_set = argc > 2 ? argc - 2 : 0;
    sets = argv + 2;
    const char *names[2] = {"ivy_pillar", "ivy_wall"};
    for (int k = 0; k < 2; k++) {
        figures f = measure(names[k], n_set, sets);
        if (n_set) continue;
        figures f0 = measure(names[k], 2, (char *const *)plumb);
        /* The wall loses few stems (about 10 runs over 5 seeds): its
         * figures are checked when there are enough to mean something. */
        CHECK(k == 1 || f.runs >= 40, "%s: only %d hanging runs: the checks are not exercised", names[k], f.runs);
        if (f.runs < 5) {
            printf("%s: too few runs to check (%d)\n", names[k], f.runs);
            continue;
        }
        CHECK(f.straight < 0.8 && (f0.runs < 5 || f.straight < f0.straight - 0.1),
              "%s: median straightness %.3f (plumb sag %.3f): the hanging runs are straight curtains", names[k],
              f.straight, f0.straight);
        CHECK(f.all_v_up == f.runs, "%s: %d of %d hanging runs do not turn their end up (V.z)", names[k],
              f.runs - f.all_v_up, f.runs);
        /* The anchor's last turn may tip a hook of a stem hanging close
         * to plumb down a little: the rise holds for nearly all. */
        CHECK(f.all_rise >= 0.95 * f.runs, "%s: %d of %d hanging runs do not rise at the end", names[k],
              f.runs - f.all_rise, f.runs);
    }
    return check_done("test_ivy_hanging");
}
