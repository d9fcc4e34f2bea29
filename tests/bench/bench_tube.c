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
 * Each figure is the median of `runs` runs with min and max.
 *   bench_tube [runs]      (default 7)
 * The last line, "JSON {...}", is for tests/bench/peers/peers.py. */
#include "bench.h"

#include <math.h>

#include "banyan.h"
#include "core/tube.h"

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
    tube_opts o = {SIDES, 0, 0, {0, 0, 0}, 0.0, NULL};
    for (uint32_t k = 0; k < w->tubes; k++)
        tube_sweep(mb, w->pts + (size_t)k * w->points, w->radii + (size_t)k * w->points, w->points, &o);
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

static figure run_reused(const workload *w, int runs, double *t, uint32_t *nv, uint32_t *ni) {
    mesh_builder mb;
    mb_init(&mb, MB_VERTEX_CEILING, 0);
    sweep_all(&mb, w); /* allocates and touches the arrays */
    *nv = mb.nv;
    *ni = mb.ni;
    for (int r = 0; r < runs; r++) {
        mb.nv = mb.ni = 0;
        double t0 = bench_now();
        sweep_all(&mb, w);
        t[r] = bench_now() - t0;
    }
    if (mb.status) fprintf(stderr, "bench_tube: builder status %d\n", (int)mb.status);
    mb_free(&mb);
    return summarise(t, runs);
}

static figure run_fresh(const workload *w, int runs, double *t) {
    for (int r = 0; r < runs; r++) {
        mesh_builder mb;
        banyan_mesh *m = NULL;
        banyan_error err;
        double t0 = bench_now();
        mb_init(&mb, MB_VERTEX_CEILING, 0);
        sweep_all(&mb, w);
        banyan_status s = mb_finish(&mb, &m, &err);
        t[r] = bench_now() - t0;
        if (s) fprintf(stderr, "bench_tube: %s\n", err.message);
        banyan_mesh_free(m);
    }
    return summarise(t, runs);
}

static figure run_api(const workload *w, int runs, double *t) {
    double *flat = malloc(sizeof(double) * 3 * w->points);
    for (uint32_t i = 0; i < w->points; i++) {
        flat[3 * i] = w->pts[i].x;
        flat[3 * i + 1] = w->pts[i].y;
        flat[3 * i + 2] = w->pts[i].z;
    }
    for (int r = 0; r < runs; r++) {
        banyan_mesh *m = NULL;
        banyan_error err;
        double t0 = bench_now();
        banyan_status s = banyan_tube_generate(flat, w->radii, w->points, SIDES, 0, &m, &err);
        t[r] = bench_now() - t0;
        if (s) fprintf(stderr, "bench_tube: %s\n", err.message);
        banyan_mesh_free(m);
    }
    free(flat);
    return summarise(t, runs);
}

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 7;
    if (runs < 5) runs = 5;
    double *t = malloc(sizeof(double) * (size_t)runs);

    bench_memory_write_rates(t, runs, 0);
    figure bw = summarise(t, runs); /* bytes per second, not seconds */
    bench_memory_write_rates(t, runs, 1);
    figure bwf = summarise(t, runs);
    printf("bench_tube: %d runs per figure (median [min .. max]), 1 thread, %d sides\n", runs, SIDES);
    printf("  store loop, 256 MiB:  %.2f GB/s [%.2f .. %.2f] touched memory, %.2f GB/s [%.2f .. %.2f] fresh\n",
           bw.med / 1e9, bw.min / 1e9, bw.max / 1e9, bwf.med / 1e9, bwf.min / 1e9, bwf.max / 1e9);

    workload ws[2];
    workload_make(&ws[0], "branches", 4000, 24);
    workload_make(&ws[1], "long", 1, 200000);
    char json[4096];
    int len = snprintf(json, sizeof json, "{\"runs\": %d, \"sides\": %d, \"store_bytes_per_s\": [%.6g, %.6g, %.6g], "
                       "\"fresh_store_bytes_per_s\": [%.6g, %.6g, %.6g], \"cases\": [", runs, SIDES, bw.med, bw.min,
                       bw.max, bwf.med, bwf.min, bwf.max);
    int first = 1;
    for (int k = 0; k < 2; k++) {
        const workload *w = &ws[k];
        uint32_t nv, ni;
        figure f[3];
        const char *how[3] = {"reused", "fresh", "api"};
        f[0] = run_reused(w, runs, t, &nv, &ni);
        f[1] = run_fresh(w, runs, t);
        int n_how = w->tubes == 1 ? 3 : 2;
        if (n_how == 3) f[2] = run_api(w, runs, t);
        double tris = ni / 3.0;
        double bytes = (double)nv * 32 + (double)ni * 4; /* pos + nrm + uv, indices */
        double bound = bw.med / (bytes / tris);          /* tris/s the store loop allows */
        double bound_fresh = bwf.med / (bytes / tris);   /* the same into fresh memory */
        printf("  %s: %u tubes x %u points, %u vertices, %.0f triangles, %.1f bytes per triangle, "
               "bound %.1f M tris/s (%.1f into fresh memory)\n", w->name, w->tubes, w->points, nv, tris,
               bytes / tris, bound / 1e6, bound_fresh / 1e6);
        for (int h = 0; h < n_how; h++) {
            printf("    %-7s %.2f ms [%.2f .. %.2f], %.1f M tris/s, %.1f%% of the bound, %.1f%% of the fresh bound\n",
                   how[h], f[h].med * 1e3, f[h].min * 1e3, f[h].max * 1e3, tris / f[h].med / 1e6,
                   100.0 * tris / f[h].med / bound, 100.0 * tris / f[h].med / bound_fresh);
            len += snprintf(json + len, sizeof json - (size_t)len,
                            "%s{\"workload\": \"%s\", \"how\": \"%s\", \"tubes\": %u, \"points\": %u, "
                            "\"vertices\": %u, \"triangles\": %.0f, \"bytes_per_triangle\": %.4g, "
                            "\"bound_tris_per_s\": %.6g, \"bound_fresh_tris_per_s\": %.6g, "
                            "\"seconds\": [%.6g, %.6g, %.6g]}",
                            first ? "" : ", ", w->name, how[h], w->tubes, w->points, nv, tris, bytes / tris, bound,
                            bound_fresh, f[h].med, f[h].min, f[h].max);
            first = 0;
        }
        free(ws[k].pts);
        free(ws[k].radii);
    }
    snprintf(json + len, sizeof json - (size_t)len, "]}");
    printf("JSON %s\n", json);
    free(t);
    return 0;
}
