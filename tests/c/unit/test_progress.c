/* Progress and cancel of the long calls (banyan_progress, docs/api.md) and
 * the ivy start placement and its "cannot grow" flag (docs/ivy.md):
 *   - roots, ivy, keyaki, avenue and segments report a fraction that never
 *     decreases, end with exactly one 1.0, and call back a bounded number
 *     of times;
 *   - a callback that never cancels leaves the output's hash unchanged
 *     (avenue on 1 and 2 threads too), and the keyaki's stats are
 *     banyan_keyaki_skeleton_stats' for the same params (the segment
 *     tree's, those of a run without one);
 *   - a cancel at 30 % returns BANYAN_E_CANCELLED, *out NULL, stats
 *     zeroed, and no call after the one that cancelled (leaks: this test
 *     also runs under valgrind, `test_progress DIR valgrind`);
 *   - a cancel at the final 1.0 still cancels;
 *   - ivy started at the foot of a cube resting on the ground (box and
 *     triangle mesh) grows a plant, and so does the wall started on its
 *     bottom face; a start boxed in a closed cavity is flagged (blocked
 *     in a 2 cm one, stunted in a 6 cm one). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "banyan.h"
#include "check.h"
#include "host_meshes.h"

typedef struct rec {
    int calls, ones, decreasing, out_of_range, after_cancel;
    double last, cancel_at; /* cancel once done >= cancel_at (> 1: never) */
    int cancelled;
    double t0, t_cancel, t_return;
} rec;

static double now(void) {
    struct timespec t;
    timespec_get(&t, TIME_UTC);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

static int32_t on_progress(void *user, double done) {
    rec *r = user;
    if (r->cancelled) r->after_cancel++;
    r->calls++;
    if (done < r->last) r->decreasing++;
    if (!(done >= 0.0 && done <= 1.0)) r->out_of_range++;
    if (done == 1.0) r->ones++;
    r->last = done;
    if (done >= r->cancel_at) {
        r->cancelled = 1;
        r->t_cancel = now();
        return 1;
    }
    return 0;
}

static void rec_init(rec *r, double cancel_at) {
    memset(r, 0, sizeof *r);
    r->cancel_at = cancel_at;
    r->t0 = now();
}

/* A finished, uncancelled run: monotone, one final 1.0, at most about 100
 * calls plus one per 0.1 s of the run. */
static void check_full(const rec *r, const char *what) {
    double secs = now() - r->t0;
    CHECK(r->calls >= 2, "%s: %d progress calls", what, r->calls);
    CHECK(r->decreasing == 0 && r->out_of_range == 0, "%s: %d decreasing, %d out of [0, 1]", what, r->decreasing,
          r->out_of_range);
    CHECK(r->ones == 1 && r->last == 1.0, "%s: %d calls with 1.0, last %g", what, r->ones, r->last);
    CHECK(r->calls <= 102 + (int)(secs / 0.1), "%s: %d calls in %.2f s", what, r->calls, secs);
}

static void check_cancelled(const rec *r, banyan_status s, const banyan_error *e, const banyan_mesh *m,
                            const char *what) {
    CHECK(s == BANYAN_E_CANCELLED && m == NULL, "%s: status %s, mesh %p", what, banyan_status_name(s), (void *)m);
    CHECK(e->code == BANYAN_E_CANCELLED && strstr(e->message, "cancelled"), "%s: error '%s'", what, e->message);
    CHECK(r->cancelled && r->after_cancel == 0, "%s: %d calls after the cancel", what, r->after_cancel);
}

/* Under valgrind no threads of our own and no mesh host (Embree's TBB
 * pool): glibc keeps a joined thread's stack in a cache that valgrind
 * reports as possibly lost. And lean: only the runs that cancel (what
 * valgrind is here for: everything freed), on smaller plants; the full
 * runs' checks are the plain run's. */
static int max_threads = 3, with_meshes = 1, lean = 0;

static banyan_hosts *box_set(const banyan_box *b, uint32_t n) {
    banyan_hosts *H = NULL;
    banyan_error e;
    CHECK(banyan_hosts_create(b, n, NULL, 0, &H, &e) == BANYAN_OK, "host set: %s", e.message);
    return H;
}

static void test_ivy(void) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = lean ? 100 : 250;
    banyan_box wall = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    banyan_hosts *H = box_set(&wall, 1);
    if (!H) return;
    banyan_error e;
    rec r;
    banyan_progress pr = {on_progress, &r};
    banyan_ivy_stats st;
    if (!lean) {
        banyan_mesh *a = NULL, *b = NULL;
        CHECK(banyan_ivy_generate(&p, H, &a, NULL, NULL, &e) == BANYAN_OK, "ivy: %s", e.message);
        rec_init(&r, 2.0);
        CHECK(banyan_ivy_generate(&p, H, &b, &st, &pr, &e) == BANYAN_OK, "ivy + progress: %s", e.message);
        check_full(&r, "ivy");
        CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b), "ivy: the hash changed with a progress callback");
        CHECK(st.steps == p.steps && st.buds > 100 && st.cannot_grow == BANYAN_IVY_GREW, "ivy stats: %d steps, %d buds, %d",
              st.steps, st.buds, st.cannot_grow);
        /* The stats of the one shot are the stepping API's. */
        banyan_ivy *iv = NULL;
        banyan_ivy_stats st2;
        if (banyan_ivy_create(&p, H, &iv, &e) == BANYAN_OK && banyan_ivy_step(iv, p.steps, &e) == BANYAN_OK &&
            banyan_ivy_get_stats(iv, &st2, &e) == BANYAN_OK)
            CHECK(st2.buds == st.buds && st2.crossings == st.crossings && st2.cannot_grow == st.cannot_grow,
                  "stepped stats differ: %d / %d buds", st2.buds, st.buds);
        else
            CHECK(0, "stepping: %s", e.message);
        banyan_ivy_free(iv);
        banyan_mesh_free(a);
        banyan_mesh_free(b);
    }

    /* Cancel at 30 %. */
    rec_init(&r, 0.3);
    banyan_mesh *m = NULL;
    st.buds = 7;
    banyan_status s = banyan_ivy_generate(&p, H, &m, &st, &pr, &e);
    check_cancelled(&r, s, &e, m, "ivy at 30 %");
    CHECK(st.buds == 0 && st.steps == 0, "ivy: stats not zeroed on cancel (%d buds)", st.buds);
    CHECK(r.last >= 0.3 && r.last < 0.5, "ivy: cancelled at %g", r.last);
    /* At the very end. */
    rec_init(&r, 1.0);
    s = banyan_ivy_generate(&p, H, &m, NULL, &pr, &e);
    check_cancelled(&r, s, &e, m, "ivy at 1.0");
    banyan_hosts_free(H);
}

static void test_roots(void) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    banyan_hosts *H = box_set(&trunk, 1);
    if (!H) return;
    banyan_error e;
    banyan_roots_stats sb;
    rec r;
    banyan_progress pr = {on_progress, &r};
    if (lean) p.growth_points = 12;
    if (!lean) {
        banyan_mesh *a = NULL, *b = NULL;
        banyan_roots_stats sa;
        CHECK(banyan_roots_generate(&p, H, &a, &sa, NULL, &e) == BANYAN_OK, "roots: %s", e.message);
        rec_init(&r, 2.0);
        CHECK(banyan_roots_generate(&p, H, &b, &sb, &pr, &e) == BANYAN_OK, "roots + progress: %s", e.message);
        check_full(&r, "roots");
        CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b), "roots: the hash changed with a progress callback");
        banyan_mesh_free(a);
        banyan_mesh_free(b);
    }
    rec_init(&r, 0.3);
    banyan_mesh *m = NULL;
    sb.main_points = 7;
    banyan_status s = banyan_roots_generate(&p, H, &m, &sb, &pr, &e);
    check_cancelled(&r, s, &e, m, "roots at 30 %");
    CHECK(sb.main_points == 0, "roots: stats not zeroed on cancel");
    rec_init(&r, 1.0);
    s = banyan_roots_generate(&p, H, &m, NULL, &pr, &e);
    check_cancelled(&r, s, &e, m, "roots at 1.0");
    banyan_hosts_free(H);
}

static void test_keyaki(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.levels = lean ? 8 : 14;
    p.threads = max_threads;
    banyan_error e;
    rec r;
    banyan_progress pr = {on_progress, &r};
    banyan_keyaki_stats st;
    if (!lean) {
        banyan_mesh *a = NULL, *b = NULL;
        banyan_keyaki_stats sk;
        CHECK(banyan_keyaki_generate(&p, &a, NULL, NULL, &e) == BANYAN_OK, "keyaki: %s", e.message);
        rec_init(&r, 2.0);
        CHECK(banyan_keyaki_generate(&p, &b, &st, &pr, &e) == BANYAN_OK, "keyaki + progress: %s", e.message);
        check_full(&r, "keyaki");
        CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b), "keyaki: the hash changed with a progress callback");
        CHECK(banyan_keyaki_skeleton_stats(&p, &sk, &e) == BANYAN_OK, "keyaki skeleton stats: %s", e.message);
        CHECK(!memcmp(&st, &sk, sizeof st) && st.node_count > 20, "keyaki: stats differ from the skeleton's (%d / %d)",
              st.node_count, sk.node_count);
        banyan_mesh_free(a);
        banyan_mesh_free(b);
    }
    rec_init(&r, 0.3);
    banyan_mesh *m = NULL;
    st.node_count = 7;
    banyan_status s = banyan_keyaki_generate(&p, &m, &st, &pr, &e);
    check_cancelled(&r, s, &e, m, "keyaki at 30 %");
    CHECK(st.node_count == 0 && st.max_order == 0, "keyaki: stats not zeroed on cancel (%d branches)", st.node_count);
    rec_init(&r, 1.0);
    st.node_count = 7;
    s = banyan_keyaki_generate(&p, &m, &st, &pr, &e);
    check_cancelled(&r, s, &e, m, "keyaki at 1.0");
    CHECK(st.node_count == 0, "keyaki: stats not zeroed on a cancel at 1.0");
    /* A callback struct without fn is refused, as elsewhere. */
    banyan_progress no_fn = {NULL, NULL};
    m = (banyan_mesh *)&e;
    s = banyan_keyaki_generate(&p, &m, NULL, &no_fn, &e);
    CHECK(s == BANYAN_E_INVALID_ARG && m == NULL && strstr(e.message, "progress->fn"), "keyaki, progress->fn NULL: %s",
          e.message);
}

static void test_avenue(void) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    p.count = lean ? 3 : 12;
    p.placement = BANYAN_AVENUE_COUNT;
    banyan_error e;
    banyan_mesh *a = NULL;
    p.threads = 1;
    if (!lean) CHECK(banyan_avenue_generate(&p, NULL, 0, &a, NULL, &e) == BANYAN_OK, "avenue: %s", e.message);
    for (int threads = 1; threads <= max_threads; threads++) {
        rec r;
        banyan_progress pr = {on_progress, &r};
        p.threads = threads;
        if (!lean) {
            rec_init(&r, 2.0);
            banyan_mesh *b = NULL;
            CHECK(banyan_avenue_generate(&p, NULL, 0, &b, &pr, &e) == BANYAN_OK, "avenue + progress: %s",
                  e.message);
            check_full(&r, "avenue");
            CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b), "avenue on %d threads: the hash changed",
                  threads);
            banyan_mesh_free(b);
        }
        rec_init(&r, 0.3);
        banyan_mesh *m = NULL;
        banyan_status s = banyan_avenue_generate(&p, NULL, 0, &m, &pr, &e);
        check_cancelled(&r, s, &e, m, "avenue at 30 %");
        rec_init(&r, 1.0);
        s = banyan_avenue_generate(&p, NULL, 0, &m, &pr, &e);
        check_cancelled(&r, s, &e, m, "avenue at 1.0");
    }
    banyan_mesh_free(a);
}
static void test_segments(void) {
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    p.demo_segments = lean ? 300 : 1000;
    p.seed = 5;
    banyan_error e;
    uint32_t n = 0;
    double trunk[6];
    banyan_segment_input *segs = malloc(sizeof *segs * (size_t)p.demo_segments);
    CHECK(segs && banyan_segments_demo(&p, segs, (uint32_t)p.demo_segments, &n, trunk, &e) == BANYAN_OK && n > 256,
          "segments demo: %s", e.message);
    if (!segs || n <= 256) {
        free(segs);
        return;
    }
    rec r;
    banyan_progress pr = {on_progress, &r};
    banyan_segments_stats st;
    if (!lean) { /* without and with a callback: the same mesh and stats */
        banyan_mesh *m2[2] = {NULL, NULL};
        banyan_segments_stats s2[2];
        rec_init(&r, 2.0);
        for (int k = 0; k < 2; k++)
            CHECK(banyan_segments_generate(&p, segs, n, trunk, &m2[k], &s2[k], k ? &pr : NULL, &e) == BANYAN_OK,
                  "segments, progress %d: %s", k, e.message);
        check_full(&r, "segments");
        CHECK(m2[0] && m2[1] && banyan_mesh_hash(m2[0]) == banyan_mesh_hash(m2[1]) &&
                  !memcmp(&s2[0], &s2[1], sizeof st) && s2[1].segments == n,
              "segments: the hash or the stats changed with a progress callback");
        banyan_mesh_free(m2[0]);
        banyan_mesh_free(m2[1]);
    }
    rec_init(&r, 0.3);
    banyan_mesh *m = NULL;
    st.segments = 7;
    banyan_status s = banyan_segments_generate(&p, segs, n, trunk, &m, &st, &pr, &e);
    check_cancelled(&r, s, &e, m, "segments at 30 %");
    CHECK(st.segments == 0 && st.lines == 0, "segments: stats not zeroed on cancel (%u segments)", st.segments);
    rec_init(&r, 1.0);
    st.segments = 7;
    s = banyan_segments_generate(&p, segs, n, trunk, &m, &st, &pr, &e);
    check_cancelled(&r, s, &e, m, "segments at 1.0");
    CHECK(st.segments == 0, "segments: stats not zeroed on a cancel at 1.0");
    banyan_progress no_fn = {NULL, NULL};
    m = (banyan_mesh *)&e;
    s = banyan_segments_generate(&p, segs, n, trunk, &m, NULL, &no_fn, &e);
    CHECK(s == BANYAN_E_INVALID_ARG && m == NULL && strstr(e.message, "progress->fn"),
          "segments, progress->fn NULL: %s", e.message);
    free(segs);
}

/* Grows ivy from `start` on H and returns its stats (buds < 0 on error). */
static banyan_ivy_stats grow(banyan_hosts *H, double x, double y, double z, int steps) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = steps;
    p.start[0] = x, p.start[1] = y, p.start[2] = z;
    banyan_ivy_stats st;
    memset(&st, 0, sizeof st);
    banyan_mesh *m = NULL;
    banyan_error e;
    if (banyan_ivy_generate(&p, H, &m, &st, NULL, &e)) {
        fprintf(stderr, "ivy: %s\n", e.message);
        st.buds = -1;
    }
    banyan_mesh_free(m);
    return st;
}

static void test_start(void) {
    /* Blender's default cube lifted onto the ground; the start at the
     * origin, on its bottom face. */
    banyan_box cube = banyan_box_make(0, 0, 1, 1, 1, 1);
    banyan_hosts *H = box_set(&cube, 1);
    if (H) {
        for (int k = 0; k < 3; k++) {
            double z = k == 0 ? 0.0 : k == 1 ? 0.05 : -0.01;
            banyan_ivy_stats st = grow(H, 0, 0, z, 150);
            CHECK(st.buds > 200 && st.cannot_grow == BANYAN_IVY_GREW, "box cube, start z = %g: %d buds, flag %d", z,
                  st.buds, st.cannot_grow);
        }
        banyan_hosts_free(H);
    }
    tm_mesh cm = {0};
    tm_box(&cm, 0, 0, 1, 1, 1, 1);
    banyan_host_mesh hm = tm_host(&cm, 0, 0, 0, BANYAN_HOST_CLOSED);
    banyan_hosts *M = NULL;
    banyan_error e;
    if (with_meshes)
        CHECK(banyan_hosts_create(NULL, 0, &hm, 1, &M, &e) == BANYAN_OK, "mesh cube: %s", e.message);
    if (M) {
        banyan_ivy_stats st = grow(M, 0, 0, 0, 150);
        CHECK(st.buds > 200 && st.cannot_grow == BANYAN_IVY_GREW, "mesh cube: %d buds, flag %d", st.buds,
              st.cannot_grow);
        banyan_hosts_free(M);
    }
    tm_free(&cm);
    /* The CLI's wall, started on its bottom face. */
    banyan_box wall = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    H = box_set(&wall, 1);
    if (H) {
        banyan_ivy_stats st = grow(H, 0, 0.1, 0, 150);
        CHECK(st.buds > 200 && st.cannot_grow == BANYAN_IVY_GREW, "wall bottom: %d buds, flag %d", st.buds,
              st.cannot_grow);
        banyan_hosts_free(H);
    }
    /* A closed 2 cm cavity of six plates: no internode (3 cm) fits. */
    banyan_box cave[6] = {
        banyan_box_make(0, 0, 0.985, 0.05, 0.05, 0.005), banyan_box_make(0, 0, 1.015, 0.05, 0.05, 0.005),
        banyan_box_make(-0.015, 0, 1, 0.005, 0.05, 0.05), banyan_box_make(0.015, 0, 1, 0.005, 0.05, 0.05),
        banyan_box_make(0, -0.015, 1, 0.05, 0.005, 0.05), banyan_box_make(0, 0.015, 1, 0.05, 0.005, 0.05)};
    H = box_set(cave, 6);
    if (H) {
        banyan_ivy_stats st = grow(H, 0, 0, 1, 50);
        banyan_ivy_params d;
        banyan_ivy_params_init(&d); /* one first bud per leading stem */
        CHECK(st.buds == d.start_stems && st.cannot_grow == BANYAN_IVY_BLOCKED, "cavity: %d buds, flag %d", st.buds,
              st.cannot_grow);
        st = grow(H, 0, 0, 1, 0);
        CHECK(st.cannot_grow == BANYAN_IVY_GREW, "no steps asked, no warning: flag %d", st.cannot_grow);
        banyan_hosts_free(H);
    }
    /* A closed 6 cm cavity: one internode fits, then nothing. */
    banyan_box room[6];
    for (int k = 0; k < 6; k++) {
        double c[3] = {0, 0, 1}, h[3] = {0.04, 0.04, 0.04};
        c[k / 2] += (k % 2 ? 1 : -1) * 0.035;
        h[k / 2] = 0.005;
        room[k] = banyan_box_make(c[0], c[1], c[2], h[0], h[1], h[2]);
    }
    H = box_set(room, 6);
    if (H) {
        banyan_ivy_stats st = grow(H, 0, 0, 1, 50);
        banyan_ivy_params d;
        banyan_ivy_params_init(&d);
        CHECK(st.buds > d.start_stems && st.buds < 6 * d.start_stems && st.cannot_grow == BANYAN_IVY_STUNTED,
              "6 cm room: %d buds, flag %d",
              st.buds, st.cannot_grow);
        banyan_hosts_free(H);
    }
    CHECK(strstr(banyan_ivy_growth_text(BANYAN_IVY_BLOCKED), "blocked") != NULL, "text of BLOCKED");
    CHECK(strstr(banyan_ivy_growth_text(BANYAN_IVY_STUNTED), "could not grow") != NULL, "text of STUNTED");
    CHECK(banyan_ivy_growth_text(99) != NULL, "text of an unknown value");
    CHECK(!strcmp(banyan_status_name(BANYAN_E_CANCELLED), "BANYAN_E_CANCELLED"), "status name");
}

int main(int argc, char **argv) {
    if (argc > 2 && !strcmp(argv[2], "valgrind")) max_threads = 1, with_meshes = 0, lean = 1;
    test_ivy();
    test_roots();
    test_keyaki();
    test_avenue();
    test_segments();
    if (!lean) test_start();
    return check_done("test_progress");
}
