/* Ivy benchmark: the wall preset (presets/ivy_wall.json: 3 m x 3 m wall,
 * 450 steps, t0 = 20), mesh included, single-threaded. Prints
 *   - the median wall time of generate (grow + mesh) over several runs,
 *     and buds per second;
 *   - the time per step over the first and the last 50 steps, also per
 *     growing bud, to show that the spatial index keeps a step's cost per
 *     bud flat while the plant grows a hundredfold;
 *   - the light look-up alone at 100 to 100,000 buds;
 *   - the same preset with its wall given as a closed 12-triangle mesh
 *     (a host set, Embree queries) against the box: both times and the
 *     ratio (the target: within 1.5x).
 * Usage: bench_ivy [runs]
 *        bench_ivy --large [max_buds [preset]]: growth alone of
 *     presets/ivy_wall_large.json (or presets/<preset>.json) (12 m x 12 m wall, 1,800 steps), stepped
 *     one step at a time, with a table at 50k, 100k, 150k, ... 600k buds: time so far, and microseconds per bud over all buds so far
 *     (cumulative) and over the buds since the row before (marginal);
 *     the target: flat within 1.5x from 50k to 600k. */
#include "bench.h"

#include "host_meshes.h"

#include "ivy/ivy_internal.h"
#include "test_files.h"
#include "test_hosts.h"


/* CPU seconds of this process: on a shared machine a less noisy figure
 * than wall time for comparing two runs. */
static double cpu_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

/* Mean time of one light look-up at random bud positions of the plant;
 * *mean_h gets the mean H0 found (how crowded the plant is there). */
static double lookup_us(const banyan_ivy *iv, double *mean_h) {
    pcg32 r;
    pcg32_seed(&r, 5, 5);
    const int q = 20000;
    double sink = 0, t0 = bench_now();
    for (int k = 0; k < q; k++) {
        int32_t i = (int32_t)rng_below(&r, (uint32_t)iv->n);
        v3 vl = v3_make(0, 0, 0);
        sink += ivy_shade(iv, iv->buds[i].P, i, HUGE_VAL, &vl);
    }
    double t = (bench_now() - t0) / q * 1e6;
    *mean_h = sink / q;
    return t;
}

/* Loads presets/<name>.json (or tests/bench/<name>.json: walls for the
 * benchmark alone) into p and its hosts; 0 on failure. */
static int load_preset(const char *name, banyan_ivy_params *p, banyan_box *hosts, uint32_t cap, uint32_t *nh) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    FILE *probe = fopen(path, "rb");
    if (probe) fclose(probe);
    else snprintf(path, sizeof path, "%s/tests/bench/%s.json", BANYAN_SOURCE_DIR, name);
    size_t len;
    char *text = test_read_file(path, &len);
    banyan_error err = {0, ""};
    banyan_ivy_params_init(p);
    int ok = text && !banyan_preset_apply(BANYAN_GEN_IVY, p, text, len, path, &err) &&
             !banyan_preset_hosts(text, len, path, hosts, cap, nh, &err);
    if (!ok) fprintf(stderr, "bench_ivy: cannot load %s: %s\n", path, err.message);
    free(text);
    return ok;
}

/* The large wall's per-bud table (growth only: the mesh is not built). */
static int large(int32_t stop_at, const char *preset) {
    banyan_ivy_params p;
    banyan_box hosts[4];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    if (!load_preset(preset, &p, hosts, 4, &nh)) return 1;
    banyan_hosts *H = TEST_HOSTS(hosts, nh);
    banyan_ivy *iv = NULL;
    if (banyan_ivy_create(&p, H, &iv, &err)) {
        fprintf(stderr, "bench_ivy: %s\n", err.message);
        return 1;
    }
    const int32_t at[] = {50000, 100000, 150000, 200000, 250000, 300000, 400000, 500000, 600000};
    const int n_at = (int)(sizeof at / sizeof at[0]);
    int next = 0;
    double t_prev = 0, c_prev = 0, t = 0, c = 0;
    int32_t n_prev = iv->n;
    printf("%s: %d steps, growth only, one step per call\n", preset, p.steps);
    printf("  %8s %6s %9s %9s %12s %12s %12s\n", "buds", "step", "wall s", "CPU s", "us/bud cum", "us/bud marg",
           "CPU us/marg");
    while (iv->step < p.steps && next < n_at && iv->n < stop_at) {
        double a = bench_now(), ca = cpu_now();
        if (banyan_ivy_step(iv, 1, &err)) {
            fprintf(stderr, "bench_ivy: step %d: %s\n", iv->step, err.message);
            break;
        }
        t += bench_now() - a;
        c += cpu_now() - ca;
        if (iv->n >= at[next]) {
            printf("  %8d %6d %9.3f %9.3f %12.2f %12.2f %12.2f\n", iv->n, iv->step, t, c, t / iv->n * 1e6,
                   (t - t_prev) / (iv->n - n_prev) * 1e6, (c - c_prev) / (iv->n - n_prev) * 1e6);
            fflush(stdout);
            t_prev = t;
            c_prev = c;
            n_prev = iv->n;
            while (next < n_at && iv->n >= at[next]) next++;
        }
    }
    printf("  end: %d buds at step %d, %.3f s wall, %.3f s CPU, %.2f us per bud\n", iv->n, iv->step, t, c,
           t / iv->n * 1e6);
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
    return 0;
}

int main(int argc, char **argv) {
    if (argc > 1 && !strcmp(argv[1], "--large")) return large(argc > 2 && atoi(argv[2]) > 0 ? atoi(argv[2]) : INT32_MAX, argc > 3 ? argv[3] : "ivy_wall_large");
    int runs = argc > 1 ? atoi(argv[1]) : 7;
    if (runs < 1) runs = 1;
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/ivy_wall.json", BANYAN_SOURCE_DIR);
    size_t len;
    char *text = test_read_file(path, &len);
    banyan_ivy_params p;
    banyan_box hosts[4];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    banyan_ivy_params_init(&p);
    if (!text || banyan_preset_apply(BANYAN_GEN_IVY, &p, text, len, path, &err) ||
        banyan_preset_hosts(text, len, path, hosts, 4, &nh, &err)) {
        fprintf(stderr, "bench_ivy: cannot load %s: %s\n", path, err.message);
        return 1;
    }
    free(text);
    banyan_hosts *B = TEST_HOSTS(hosts, nh); /* the wall as a box */

    double *t = malloc(sizeof(double) * (size_t)runs), *tg = malloc(sizeof(double) * (size_t)runs);
    uint32_t verts = 0;
    int32_t buds = 0;
    for (int r = 0; r < runs; r++) {
        banyan_ivy *iv = NULL;
        banyan_mesh *m = NULL;
        double a = bench_now();
        if (banyan_ivy_create(&p, B, &iv, &err) || banyan_ivy_step(iv, p.steps, &err)) {
            fprintf(stderr, "bench_ivy: %s\n", err.message);
            return 1;
        }
        double b = bench_now();
        if (banyan_ivy_mesh(iv, &m, &err)) {
            fprintf(stderr, "bench_ivy: %s\n", err.message);
            return 1;
        }
        double c = bench_now();
        t[r] = c - a;
        tg[r] = b - a;
        verts = m->vertex_count;
        buds = iv->n;
        banyan_mesh_free(m);
        banyan_ivy_free(iv);
    }
    double med = bench_median(t, runs), medg = bench_median(tg, runs);
    printf("ivy wall preset: %d steps, %d buds, %u vertices\n", p.steps, buds, verts);
    printf("  generate (grow + mesh): median %.3f s over %d runs (grow %.3f s, mesh %.3f s)\n", med, runs, medg,
           med - medg);
    printf("  buds per second: %.0f (whole generate), %.0f (growth alone)\n", buds / med, buds / medg);

    /* The wall as a 12-triangle closed mesh against the box, runs
     * interleaved so that the machine's load falls on both alike. */
    {
        const banyan_box *w = &hosts[0];
        tm_mesh bm = {0};
        tm_box(&bm, 0, 0, 0, w->half[0], w->half[1], w->half[2]);
        banyan_host_mesh hm = tm_host(&bm, w->center[0], w->center[1], w->center[2], BANYAN_HOST_CLOSED_AUTO);
        banyan_hosts *H = NULL;
        if (nh != 1 || banyan_hosts_create(NULL, 0, &hm, 1, &H, &err)) {
            fprintf(stderr, "bench_ivy: wall mesh: %s\n", err.message);
            return 1;
        }
        double *tb = malloc(sizeof(double) * (size_t)runs * 4), *tm = tb + runs, *cb = tb + 2 * runs, *cm = tb + 3 * runs;
        int32_t nb_box = 0, nb_mesh = 0;
        for (int r = 0; r < runs; r++) {
            for (int k = 0; k < 2; k++) {
                banyan_ivy *iv = NULL;
                banyan_mesh *m = NULL;
                double a = bench_now(), ca = cpu_now();
                banyan_status s = banyan_ivy_create(&p, k ? H : B, &iv, &err);
                if (!s) s = banyan_ivy_step(iv, p.steps, &err);
                if (!s) s = banyan_ivy_mesh(iv, &m, &err);
                if (s) {
                    fprintf(stderr, "bench_ivy: %s\n", err.message);
                    return 1;
                }
                (k ? tm : tb)[r] = bench_now() - a;
                (k ? cm : cb)[r] = cpu_now() - ca;
                *(k ? &nb_mesh : &nb_box) = iv->n;
                banyan_mesh_free(m);
                banyan_ivy_free(iv);
            }
        }
        double mb = bench_median(tb, runs), mm = bench_median(tm, runs);
        double mcb = bench_median(cb, runs), mcm = bench_median(cm, runs);
        printf("  wall as a box: median %.3f s wall, %.3f s CPU (%d buds); as a 12-triangle mesh: median %.3f s wall, "
               "%.3f s CPU (%d buds)\n",
               mb, mcb, nb_box, mm, mcm, nb_mesh);
        printf("  mesh / box: %.2fx wall, %.2fx CPU; per bud %.2fx CPU\n", mm / mb, mcm / mcb,
               (mcm / nb_mesh) / (mcb / nb_box));
        free(tb);
        banyan_hosts_free(H);
        tm_free(&bm);
    }

    /* Time per step at the start and at the end. */
    banyan_ivy *iv = NULL;
    banyan_ivy_create(&p, B, &iv, &err);
    double first = 0, last = 0;
    int64_t grow_first = 0, grow_last = 0;
    int32_t n_first = 0, n_last0 = 0;
    double probe[4] = {0, 0, 0, 0}, probe_h[4] = {0, 0, 0, 0};
    int32_t probe_n[4] = {0, 0, 0, 0}, next_probe = 0;
    const int32_t probe_at[4] = {100, 1000, 10000, 30000};
    for (int s = 0; s < p.steps; s++) {
        int64_t act = iv->active;
        double a = bench_now();
        banyan_ivy_step(iv, 1, &err);
        double d = bench_now() - a;
        if (s < 50) { first += d; grow_first += act; n_first = iv->n; }
        if (s == p.steps - 50) n_last0 = iv->n;
        if (s >= p.steps - 50) { last += d; grow_last += act; }
        while (next_probe < 4 && iv->n >= probe_at[next_probe]) {
            probe[next_probe] = lookup_us(iv, &probe_h[next_probe]);
            probe_n[next_probe++] = iv->n;
        }
    }
    printf("  time per step: first 50 steps %.3f ms (%d buds at step 50), last 50 steps %.3f ms (%d..%d buds)\n",
           first / 50 * 1e3, n_first, last / 50 * 1e3, n_last0, iv->n);
    printf("  per growing bud and step: first 50 steps %.2f us, last 50 steps %.2f us\n",
           grow_first ? first / grow_first * 1e6 : 0.0, grow_last ? last / grow_last * 1e6 : 0.0);
    banyan_ivy_free(iv);

    /* The light look-up alone, up to 100,000 buds: the same ivy (t0 = 20)
     * on a wall 12 m wide and 6 m high, grown longer. */
    banyan_box wide = banyan_box_make(0, 0.1, 3, 6, 0.1, 3);
    banyan_hosts *W = TEST_HOSTS(&wide, 1);
    iv = NULL;
    banyan_ivy_create(&p, W, &iv, &err);
    double tb = bench_now();
    int64_t grow_big = 0;
    double last_big = 0;
    while (iv->n < 100000 && iv->step < 3000) {
        int64_t act = iv->active;
        double a = bench_now();
        if (banyan_ivy_step(iv, 1, &err)) break;
        if (iv->n > 90000) { last_big += bench_now() - a; grow_big += act; }
    }
    printf("  12 m x 6 m wall to %d buds (%d steps, %.2f s): per growing bud and step over the last 10%%: %.2f us\n",
           iv->n, iv->step, bench_now() - tb, grow_big ? last_big / grow_big * 1e6 : 0.0);
    printf("  light look-up (H0 + V_l at a bud, no early stop):");
    for (int k = 0; k < 4; k++)
        if (probe_n[k]) printf(" %.2f us at %d buds (mean H0 %.1f),", probe[k], probe_n[k], probe_h[k]);
    double hb, tbig = lookup_us(iv, &hb);
    printf(" %.2f us at %d buds (mean H0 %.1f)\n", tbig, iv->n, hb);
    banyan_ivy_free(iv);
    banyan_hosts_free(W);
    banyan_hosts_free(B);
    free(t);
    free(tg);
    return 0;
}
