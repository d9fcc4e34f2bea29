/* Benchmark of the roots generator: the default net (6 main roots x 40
 * growth points, all branch kinds, junction smoothing, hugging) round the
 * CLI's default trunk, single-threaded.
 * Fused surface (the default): seeds 1..10, the median time per
 * net, the split net / fused mesh, and the memory peak of one call (the
 * growth of the process's peak resident set over its size before the
 * first call: the level set's blocks, OpenVDB's grid and mesh, the output).
 * Tubes with n = 16 sides, seeds 1..20 in turn: the median time per net in
 * two allocation patterns:
 *   fresh  - each mesh is freed before the next is made, so the C library
 *            returns the memory to the system and the next mesh's output
 *            arrays are page-faulted in anew (a one-shot call);
 *   reused - the previous mesh is freed only after the next is made, so
 *            the output lands in memory the process already owns (a redo
 *            loop in an editor);
 * the split between building the net and sweeping the mesh, triangles per
 * second, and the output rate against this machine's memory write
 * bandwidth (bench.h). Then the default params as they are (n = 8 sides,
 * tubes), fresh and reused.
 *   bench_roots [runs]   (default 200) */
#include "bench.h"

#include <sys/resource.h>

#include "banyan.h"
#include "roots/roots_internal.h"
#include "test_hosts.h"

static double run(int runs, int keep_previous, int sides, banyan_box *host, uint32_t *tris, uint32_t *verts,
                  size_t *bytes) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.surface = BANYAN_ROOTS_TUBES;
    if (sides) p.sides = sides; /* 0: the params' default */
    double *t = malloc(sizeof(double) * (size_t)runs);
    banyan_mesh *prev = NULL;
    for (int i = 0; i < runs + 5; i++) {
        p.seed = 1 + (uint64_t)(i % 20);
        banyan_mesh *m = NULL;
        banyan_error err;
        double t0 = bench_now();
        banyan_status s = test_roots_boxes(&p, host, 1, &m, &err);
        double t1 = bench_now();
        if (s) {
            fprintf(stderr, "bench_roots: %s\n", err.message);
            exit(1);
        }
        if (i >= 5) t[i - 5] = t1 - t0; /* the first five warm up */
        if (i == 5 && tris) {
            *tris = m->index_count / 3;
            *verts = m->vertex_count;
            *bytes = (size_t)m->vertex_count * (3 + 3 + 2 + 4 + (size_t)m->attribute_count) * 4 +
                     (size_t)m->index_count * 4;
        }
        if (keep_previous) {
            banyan_mesh_free(prev);
            prev = m;
        } else {
            banyan_mesh_free(m);
        }
    }
    banyan_mesh_free(prev);
    double med = bench_median(t, runs);
    free(t);
    return med;
}

/* Resident set now, kB (Linux /proc/self/statm). */
static long rss_kb(void) {
    long pages = 0, res = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &res) != 2) res = 0;
        fclose(f);
    }
    return res * 4;
}

static long peak_kb(void) {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

/* The fused surface, first (so the peak is its own). */
static void fused(const banyan_box *host) {
    enum { RUNS = 10 };
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    double t[RUNS], tn[RUNS];
    long before = rss_kb(), peak = 0;
    uint32_t verts = 0, tris = 0;
    for (int i = 0; i < RUNS; i++) {
        p.seed = 1 + (uint64_t)i;
        banyan_mesh *m = NULL;
        banyan_error err;
        double t0 = bench_now();
        banyan_status s = test_roots_boxes(&p, host, 1, &m, &err);
        t[i] = bench_now() - t0;
        if (s) {
            fprintf(stderr, "bench_roots: fused: %s\n", err.message);
            exit(1);
        }
        if (i == 0) {
            peak = peak_kb() - before;
            verts = m->vertex_count;
            tris = m->index_count / 3;
        }
        banyan_mesh_free(m);
        roots_net net;
        t0 = bench_now();
        roots_net_build(&p, host, 1, &net, &err);
        tn[i] = bench_now() - t0;
        roots_net_free(&net);
    }
    double med = bench_median(t, RUNS), net_ms = bench_median(tn, RUNS);
    printf("bench_roots: default net, fused surface (voxel %.2g r, fuse_radius %.2g r, maturity %.2g), %d runs, "
           "1 thread\n", p.voxel_size, p.fuse_radius, p.maturity, RUNS);
    printf("  mesh (seed 1):          %u vertices, %u triangles\n", verts, tris);
    printf("  median per net:         %.1f ms  (of which the net %.3f ms)\n", med * 1e3, net_ms * 1e3);
    printf("  memory peak of a call:  %.1f MB  (peak resident set growth, seed 1)\n", peak / 1024.0);
}

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 200;
    if (runs < 5) runs = 5;
    banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4); /* the CLI's default trunk */
    fused(&host);
    uint32_t tris = 0, verts = 0;
    size_t bytes = 0;
    double fresh = run(runs, 0, 16, &host, &tris, &verts, &bytes);
    double reused = run(runs, 1, 16, &host, NULL, NULL, NULL);
    /* The default params as they are (n = 8 sides). */
    uint32_t tris8 = 0, verts8 = 0;
    size_t bytes8 = 0;
    double fresh8 = run(runs, 0, 0, &host, &tris8, &verts8, &bytes8);
    double reused8 = run(runs, 1, 0, &host, NULL, NULL, NULL);
    banyan_roots_params p8;
    banyan_roots_params_init(&p8);

    /* The net alone (growth, branches, correction, repair), no mesh. */
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.surface = BANYAN_ROOTS_TUBES;
    p.sides = 16;
    double *t = malloc(sizeof(double) * (size_t)runs);
    for (int i = 0; i < runs; i++) {
        p.seed = 1 + (uint64_t)(i % 20);
        roots_net net;
        banyan_error err;
        double t0 = bench_now();
        roots_net_build(&p, &host, 1, &net, &err);
        t[i] = bench_now() - t0;
        roots_net_free(&net);
    }
    double net_ms = bench_median(t, runs);
    free(t);

    double bw = bench_memory_write_bandwidth();
    printf("bench_roots: default net, tubes, 6 main roots x 40 points, n = 16, %d runs per figure, 1 thread\n", runs);
    printf("  mesh (seed 1):          %u vertices, %u triangles, %.2f MB of output\n", verts, tris, bytes / 1e6);
    printf("  median per net, fresh:  %.3f ms  (output memory faulted in anew each call)\n", fresh * 1e3);
    printf("  median per net, reused: %.3f ms  (output memory reused)\n", reused * 1e3);
    printf("  of which the net:       %.3f ms  (the rest is the tube mesh)\n", net_ms * 1e3);
    printf("  triangles/s:            %.3g fresh, %.3g reused\n", tris / fresh, tris / reused);
    printf("  memory write bandwidth: %.3g B/s\n", bw);
    printf("  output rate / bandwidth: %.1f%% fresh, %.1f%% reused\n", 100.0 * bytes / fresh / bw,
           100.0 * bytes / reused / bw);
    printf("bench_roots: default params, tubes (n = %d), %d runs per figure, 1 thread\n", p8.sides, runs);
    printf("  mesh (seed 1):          %u vertices, %u triangles, %.2f MB of output\n", verts8, tris8, bytes8 / 1e6);
    printf("  median per net:         %.3f ms fresh, %.3f ms reused\n", fresh8 * 1e3, reused8 * 1e3);
    return 0;
}
