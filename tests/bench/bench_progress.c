/* bench_progress: how honest the progress fraction is and how soon a
 * cancel is heard (docs/api.md, "Progress and cancel").
 *   usage: bench_progress [ivy_steps (900)] [avenue_trees (100)] [ivy_preset.json] [segments (2000)]
 * For ivy on the wall (one host set box; or the preset's params and hosts;
 * max_buds and max_vertices raised), an avenue, the default roots and a
 * demo segment tree it prints: the run's time,
 * the number of callbacks, the share of the run's time at which the
 * fraction passed 0.25, 0.5, 0.75 and 0.9 (honest: close to the fraction
 * itself), the longest gap between two callbacks, and for a cancel at
 * 30 %, 60 % and 90 % the time from the callback's nonzero return to the
 * call's return. */
#include "bench.h"

#include "banyan.h"

typedef struct rec {
    double t0, cancel_at, t_cancel, gap, last_t;
    double at[4]; /* time when done passed 0.25, 0.5, 0.75, 0.9 */
    int calls;
} rec;

static const double marks[4] = {0.25, 0.5, 0.75, 0.9};

static int32_t on_progress(void *user, double done) {
    rec *r = user;
    double t = bench_now();
    if (t - r->last_t > r->gap) r->gap = t - r->last_t;
    r->last_t = t;
    r->calls++;
    if (getenv("BENCH_PROGRESS_TRACE")) printf("  %.4f s %.3f\n", t - r->t0, done);
    for (int k = 0; k < 4; k++)
        if (done >= marks[k] && r->at[k] < 0) r->at[k] = t - r->t0;
    if (done >= r->cancel_at) {
        r->t_cancel = t;
        return 1;
    }
    return 0;
}

typedef banyan_status (*run_fn)(const void *ctx, const banyan_progress *pr, banyan_mesh **out, banyan_error *e);

static void measure(const char *name, run_fn run, const void *ctx) {
    rec r;
    memset(&r, 0, sizeof r);
    for (int k = 0; k < 4; k++) r.at[k] = -1;
    r.cancel_at = 2.0;
    r.t0 = r.last_t = bench_now();
    banyan_progress pr = {on_progress, &r};
    banyan_mesh *m = NULL;
    banyan_error e;
    if (run(ctx, &pr, &m, &e)) {
        printf("%s: %s\n", name, e.message);
        return;
    }
    double total = bench_now() - r.t0;
    printf("%-7s %7.2f s, %3d calls, longest gap %.3f s, %u vertices; time share at 25/50/75/90 %%: %.2f %.2f %.2f "
           "%.2f\n",
           name, total, r.calls, r.gap, m->vertex_count, r.at[0] / total, r.at[1] / total, r.at[2] / total,
           r.at[3] / total);
    banyan_mesh_free(m);
    printf("        cancel:");
    for (int c = 0; c < 3; c++) {
        memset(&r, 0, sizeof r);
        for (int k = 0; k < 4; k++) r.at[k] = -1;
        r.cancel_at = 0.3 * (c + 1);
        r.t0 = r.last_t = bench_now();
        banyan_status s = run(ctx, &pr, &m, &e);
        double back = bench_now();
        printf(" at %.0f %% %s after %.3f s, returned %.4f s later;", 100 * r.cancel_at,
               s == BANYAN_E_CANCELLED ? "cancelled" : banyan_status_name(s), r.t_cancel - r.t0, back - r.t_cancel);
        banyan_mesh_free(m);
    }
    printf("\n");
}

typedef struct ivy_ctx {
    banyan_ivy_params p;
    banyan_hosts *H;
} ivy_ctx;

static banyan_status run_ivy(const void *ctx, const banyan_progress *pr, banyan_mesh **out, banyan_error *e) {
    const ivy_ctx *c = ctx;
    return banyan_ivy_generate(&c->p, c->H, out, NULL, pr, e);
}

static banyan_status run_avenue(const void *ctx, const banyan_progress *pr, banyan_mesh **out, banyan_error *e) {
    return banyan_avenue_generate(ctx, NULL, 0, out, pr, e);
}

typedef struct roots_ctx {
    banyan_roots_params p;
    banyan_hosts *H;
} roots_ctx;

static banyan_status run_roots(const void *ctx, const banyan_progress *pr, banyan_mesh **out, banyan_error *e) {
    const roots_ctx *c = ctx;
    return banyan_roots_generate(&c->p, c->H, out, NULL, pr, e);
}

typedef struct segments_ctx {
    banyan_segments_params p;
    banyan_segment_input *segs;
    uint32_t n;
    double trunk[6];
} segments_ctx;

static banyan_status run_segments(const void *ctx, const banyan_progress *pr, banyan_mesh **out, banyan_error *e) {
    const segments_ctx *c = ctx;
    return banyan_segments_generate(&c->p, c->segs, c->n, c->trunk, out, NULL, pr, e);
}

int main(int argc, char **argv) {
    int steps = argc > 1 ? atoi(argv[1]) : 900, trees = argc > 2 ? atoi(argv[2]) : 100;
    banyan_error e;
    ivy_ctx ic;
    banyan_ivy_params_init(&ic.p);
    ic.p.steps = steps;
    ic.p.max_buds = 5000000;
    ic.p.max_vertices = 200000000;
    banyan_box wall = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    if (argc > 3) {
        FILE *f = fopen(argv[3], "rb");
        static char text[1 << 16];
        size_t n = f ? fread(text, 1, sizeof text, f) : 0;
        if (f) fclose(f);
        char dir[4096];
        snprintf(dir, sizeof dir, "%s", argv[3]);
        char *slash = strrchr(dir, '/');
        if (slash) *slash = '\0';
        if (!n || banyan_preset_apply(BANYAN_GEN_IVY, &ic.p, text, n, argv[3], &e) ||
            banyan_preset_host_set(text, n, argv[3], slash ? dir : NULL, NULL, 0, &ic.H, &e))
            return printf("%s: %s\n", argv[3], e.message), 1;
        ic.p.steps = steps;
        ic.p.max_buds = 5000000;
        ic.p.max_vertices = 200000000;
    } else if (banyan_hosts_create(&wall, 1, NULL, 0, &ic.H, &e)) {
        return printf("%s\n", e.message), 1;
    }
    measure("ivy", run_ivy, &ic);
    banyan_hosts_free(ic.H);

    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    ap.placement = BANYAN_AVENUE_COUNT;
    ap.count = trees / 2 > 1 ? trees / 2 : 2;
    ap.max_vertices = 200000000;
    measure("avenue", run_avenue, &ap);

    roots_ctx rc;
    banyan_roots_params_init(&rc.p);
    banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    if (banyan_hosts_create(&trunk, 1, NULL, 0, &rc.H, &e)) return printf("%s\n", e.message), 1;
    measure("roots", run_roots, &rc);
    banyan_hosts_free(rc.H);

    segments_ctx sc;
    banyan_segments_params_init(&sc.p);
    sc.p.demo_segments = argc > 4 ? atoi(argv[4]) : 2000;
    sc.p.max_vertices = 1 << 30;
    sc.segs = malloc(sizeof *sc.segs * (size_t)(sc.p.demo_segments > 0 ? sc.p.demo_segments : 1));
    if (!sc.segs || banyan_segments_demo(&sc.p, sc.segs, (uint32_t)sc.p.demo_segments, &sc.n, sc.trunk, &e))
        return printf("segments demo: %s\n", sc.segs ? e.message : "out of memory"), 1;
    measure("segments", run_segments, &sc);
    free(sc.segs);
    return 0;
}
