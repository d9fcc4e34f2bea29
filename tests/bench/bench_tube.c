/* bench_tube: triangles per second of the shared tube sweeper (tube.h)
 * against this machine's memory write bandwidth, measured in the same run
 * by a plain store loop (bench.h), into touched memory and into fresh
 * memory (page faults included). The sweeper cannot beat the store loop:
 * every triangle it emits is 12 bytes of indices plus its share of
 * vertices (32 bytes each: position, normal, uv). The bound in triangles
 * per second is bandwidth / (bytes the workload writes per triangle).
 *
 * Workloads, 8 sides, no caps:
 *   branches  4,000 short tapered tubes of 24 points (a tree's worth)
 *   long      one tube of 200,000 points
 * and three ways of running them:
 *   reused    tube_sweep into a builder whose arrays are already allocated
 *             and touched (what the store loop gets: no page faults)
 *   fresh     mb_init + tube_sweep + mb_finish: new output memory each run,
 *             page faults included (a one-shot generate call)
 *   api       banyan_tube_generate (long only): validation, fresh memory,
 *             skeleton
 * Each row gives its fraction of the bound (the store loop into touched
 * memory: the target is >= 25 % for the api row) and of the
 * fresh-memory bound, and the page faults one run takes (getrusage: a
 * count, steadier than times on a loaded machine). A third store loop
 * writes fresh memory from big_malloc (2 MiB-aligned, huge pages where the
 * kernel offers them): what the output arrays get.
 * Each figure is the median of `runs` runs with min and max; each run
 * measures the store loops and every case once, so that on a shared
 * machine the sweeper and its bound see the same load.
 *   bench_tube [runs]      (default 7)
 * The last line, "JSON {...}", is for tests/bench/peers/peers.py. */
#include "bench.h"

#include <math.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <sys/resource.h>

#include "banyan.h"
#include "base/big_alloc.h"
#include "mesh/tube.h"

#define SIDES 8

typedef struct workload {
    const char *name;
    uint32_t tubes, points; /* points per tube */
    v3 *pts;                /* tubes * points */
    double *radii;
} workload;

/* Gently curving tapered polylines; tube k starts at a point of a grid. */
static void workload_make(workload *w, const char *name, uint32_t tubes, uint32_t points) {
    w->name = name;
    w->tubes = tubes;
    w->points = points;
    w->pts = malloc(sizeof(v3) * tubes * points);
    w->radii = malloc(sizeof(double) * tubes * points);
    for (uint32_t k = 0; k < tubes; k++) {
        double x0 = (k % 64) * 0.5, y0 = (k / 64) * 0.5;
        for (uint32_t i = 0; i < points; i++) {
            double t = i * 0.05;
            w->pts[k * points + i] = v3_make(x0 + 0.1 * sin(t + k), y0 + 0.1 * cos(0.7 * t + k), t);
            w->radii[k * points + i] = 0.05 * (1.0 - 0.5 * i / points);
        }
    }
}

static void sweep_all(mesh_builder *mb, const workload *w) {
    tube_opts o = {SIDES, 0, 0, {0, 0, 0}, 0.0, NULL, 0, 1};
    for (uint32_t k = 0; k < w->tubes; k++)
        tube_sweep(mb, w->pts + (size_t)k * w->points, w->radii + (size_t)k * w->points, w->points, &o);
}

/* Minor page faults of the process so far. */
static double faults_now(void) {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (double)u.ru_minflt;
}

/* Bytes per second of one store-loop pass over a new 256 MiB big_malloc
 * buffer: the fresh-memory bound for output arrays. 0 if out of memory. */
static double big_store_rate(void) {
    size_t n = (size_t)256 << 20, count = n / sizeof(float);
    float *buf = big_malloc(n);
    if (!buf) return 0;
    double t0 = bench_now();
    for (size_t i = 0; i < count; i++) buf[i] = (float)(i & 1023);
    double t1 = bench_now();
    volatile float sink = buf[12345];
    (void)sink;
    free(buf);
    return n / (t1 - t0);
}

typedef struct figure {
    double med, min, max; /* seconds */
} figure;

static figure summarise(double *t, int runs) {
    figure f;
    f.med = bench_median(t, runs); /* sorts t */
    f.min = t[0];
    f.max = t[runs - 1];
    return f;
}

/* One sweep of w into mb, whose arrays earlier sweeps allocated and touched. */
static double reused_once(mesh_builder *mb, const workload *w) {
    mb->nv = mb->ni = 0;
    double t0 = bench_now();
    sweep_all(mb, w);
    return bench_now() - t0;
}

/* mb_init + the sweeps + mb_finish: new output memory. */
static double fresh_once(const workload *w) {
    mesh_builder mb;
    banyan_mesh *m = NULL;
    banyan_error err;
    double t0 = bench_now();
    mb_init(&mb, MB_VERTEX_CEILING, 0);
    sweep_all(&mb, w);
    banyan_status s = mb_finish(&mb, &m, &err);
    double t = bench_now() - t0;
    if (s) fprintf(stderr, "bench_tube: %s\n", err.message);
    banyan_mesh_free(m);
    return t;
}

/* banyan_tube_generate on a single-tube workload (flat: its points as doubles). */
static double api_once(const workload *w, const double *flat) {
    banyan_mesh *m = NULL;
    banyan_error err;
    double t0 = bench_now();
    banyan_status s = banyan_tube_generate(flat, w->radii, w->points, SIDES, 0, &m, &err);
    double t = bench_now() - t0;
    if (s) fprintf(stderr, "bench_tube: %s\n", err.message);
    banyan_mesh_free(m);
    return t;
}

enum { N_CASES = 5 }; /* branches reused, fresh; long reused, fresh, api */

/* Times case c of run r and counts its page faults into fl. */
#define MEASURE(c, expr)                                                                                          \
    do {                                                                                                          \
        double f0 = faults_now();                                                                                 \
        ct[(c) * runs + r] = (expr);                                                                              \
        fl[(c) * runs + r] = faults_now() - f0;                                                                   \
    } while (0)

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 7;
    if (runs < 5) runs = 5;
#ifdef __GLIBC__
    /* A fixed mmap threshold: every large output array is a new mapping
     * and its pages are new, as in a one-shot process. glibc's sliding
     * threshold would otherwise serve later runs from freed heap pages,
     * and "fresh" would be partly reused memory. */
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
    workload ws[2];
    workload_make(&ws[0], "branches", 4000, 24);
    workload_make(&ws[1], "long", 1, 200000);
    double *flat = malloc(sizeof(double) * 3 * ws[1].points);
    for (uint32_t i = 0; i < ws[1].points; i++) {
        flat[3 * i] = ws[1].pts[i].x;
        flat[3 * i + 1] = ws[1].pts[i].y;
        flat[3 * i + 2] = ws[1].pts[i].z;
    }
    mesh_builder mb[2];
    uint32_t nv[2], ni[2];
    for (int k = 0; k < 2; k++) {
        mb_init(&mb[k], MB_VERTEX_CEILING, 0);
        sweep_all(&mb[k], &ws[k]); /* allocates and touches the arrays */
        nv[k] = mb[k].nv;
        ni[k] = mb[k].ni;
    }

    /* Run r measures everything once, store loops first, so that the
     * sweeper and its bound see the same load on a shared machine. */
    double *t = malloc(sizeof(double) * (size_t)runs * (2 * N_CASES + 3));
    double *bw_t = t, *bwf_t = t + runs, *bwh_t = t + 2 * runs;
    double *ct = t + 3 * runs, *fl = ct + N_CASES * runs; /* ct[c * runs + r], fl likewise */
    for (int r = 0; r < runs; r++) {
        bench_memory_write_rates(&bw_t[r], 1, 0);
        bench_memory_write_rates(&bwf_t[r], 1, 1);
        bwh_t[r] = big_store_rate();
        MEASURE(0, reused_once(&mb[0], &ws[0]));
        MEASURE(1, fresh_once(&ws[0]));
        MEASURE(2, reused_once(&mb[1], &ws[1]));
        MEASURE(3, fresh_once(&ws[1]));
        MEASURE(4, api_once(&ws[1], flat));
    }
    for (int k = 0; k < 2; k++) {
        if (mb[k].status) fprintf(stderr, "bench_tube: builder status %d\n", (int)mb[k].status);
        mb_free(&mb[k]);
    }
    free(flat);

    figure bw = summarise(bw_t, runs); /* bytes per second, not seconds */
    figure bwf = summarise(bwf_t, runs);
    figure bwh = summarise(bwh_t, runs);
    printf("bench_tube: %d runs per figure (median [min .. max]), 1 thread, %d sides\n", runs, SIDES);
    printf("  store loop, 256 MiB:  %.2f GB/s [%.2f .. %.2f] touched memory, %.2f GB/s [%.2f .. %.2f] fresh, "
           "%.2f GB/s [%.2f .. %.2f] fresh from big_malloc\n", bw.med / 1e9, bw.min / 1e9, bw.max / 1e9,
           bwf.med / 1e9, bwf.min / 1e9, bwf.max / 1e9, bwh.med / 1e9, bwh.min / 1e9, bwh.max / 1e9);
    char json[6144];
    int len = snprintf(json, sizeof json, "{\"runs\": %d, \"sides\": %d, \"store_bytes_per_s\": [%.6g, %.6g, %.6g], "
                       "\"fresh_store_bytes_per_s\": [%.6g, %.6g, %.6g], "
                       "\"fresh_big_store_bytes_per_s\": [%.6g, %.6g, %.6g], \"cases\": [", runs, SIDES, bw.med,
                       bw.min, bw.max, bwf.med, bwf.min, bwf.max, bwh.med, bwh.min, bwh.max);
    double api_fraction = 0;
    const char *how[N_CASES] = {"reused", "fresh", "reused", "fresh", "api"};
    const int which[N_CASES] = {0, 0, 1, 1, 1};
    for (int c = 0; c < N_CASES; c++) {
        int k = which[c];
        const workload *w = &ws[k];
        figure f = summarise(ct + c * runs, runs);
        double faults = bench_median(fl + c * runs, runs);
        double tris = ni[k] / 3.0;
        double bytes = (double)nv[k] * 32 + (double)ni[k] * 4; /* pos + nrm + uv, indices */
        double bound = bw.med / (bytes / tris);                /* tris/s the store loop allows */
        double bound_fresh = bwf.med / (bytes / tris);         /* the same into fresh memory */
        if (c == 0 || which[c - 1] != k)
            printf("  %s: %u tubes x %u points, %u vertices, %.0f triangles, %.1f bytes per triangle, "
                   "bound %.1f M tris/s (%.1f into fresh memory)\n", w->name, w->tubes, w->points, nv[k], tris,
                   bytes / tris, bound / 1e6, bound_fresh / 1e6);
        double frac = tris / f.med / bound, frac_fresh = tris / f.med / bound_fresh;
        if (c == 4) api_fraction = frac;
        printf("    %-7s %.2f ms [%.2f .. %.2f], %.1f M tris/s, %.1f%% of the bound", how[c], f.med * 1e3,
               f.min * 1e3, f.max * 1e3, tris / f.med / 1e6, 100.0 * frac);
        if (strcmp(how[c], "reused")) printf(", %.1f%% of the fresh-memory bound", 100.0 * frac_fresh);
        printf(", %.0f page faults\n", faults);
        len += snprintf(json + len, sizeof json - (size_t)len,
                        "%s{\"workload\": \"%s\", \"how\": \"%s\", \"tubes\": %u, \"points\": %u, "
                        "\"vertices\": %u, \"triangles\": %.0f, \"bytes_per_triangle\": %.4g, "
                        "\"bound_tris_per_s\": %.6g, \"bound_fresh_tris_per_s\": %.6g, "
                        "\"seconds\": [%.6g, %.6g, %.6g], \"fraction_of_bound\": %.4f, "
                        "\"fraction_of_fresh_bound\": %.4f, \"page_faults\": %.0f}",
                        c ? ", " : "", w->name, how[c], w->tubes, w->points, nv[k], tris, bytes / tris, bound,
                        bound_fresh, f.med, f.min, f.max, frac, frac_fresh, faults);
    }
    for (int k = 0; k < 2; k++) {
        free(ws[k].pts);
        free(ws[k].radii);
    }
    printf("  one-shot generate (api, long): %.1f%% of the store-loop bound (target >= 25%%): %s\n",
           100.0 * api_fraction, api_fraction >= 0.25 ? "met" : "missed");
    snprintf(json + len, sizeof json - (size_t)len, "]}");
    printf("JSON %s\n", json);
    free(t);
    return 0;
}
