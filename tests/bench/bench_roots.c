/* Benchmark of the roots generator: the default net (6 main roots x 40
 * growth points, all branch kinds, junction smoothing, hugging) with
 * n = 16 sides round the CLI's default trunk, single-threaded, seeds 1..20
 * in turn. Prints the median time per net in two allocation patterns:
 *   fresh  - each mesh is freed before the next is made, so the C library
 *            returns the memory to the system and the next mesh's output
 *            arrays are page-faulted in anew (a one-shot call);
 *   reused - the previous mesh is freed only after the next is made, so
 *            the output lands in memory the process already owns (a redo
 *            loop in an editor);
 * the split between building the net and sweeping the mesh, triangles per
 * second, and the output rate against this machine's memory write
 * bandwidth (bench.h).
 *   bench_roots [runs]   (default 200) */
#include "bench.h"

#include "banyan.h"
#include "roots/roots_internal.h"

static double run(int runs, int keep_previous, banyan_box *host, uint32_t *tris, uint32_t *verts, size_t *bytes) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.sides = 16;
    double *t = malloc(sizeof(double) * (size_t)runs);
    banyan_mesh *prev = NULL;
    for (int i = 0; i < runs + 5; i++) {
        p.seed = 1 + (uint64_t)(i % 20);
        banyan_mesh *m = NULL;
        banyan_error err;
        double t0 = bench_now();
        banyan_status s = banyan_roots_generate(&p, host, 1, &m, &err);
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

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 200;
    if (runs < 5) runs = 5;
    banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4); /* the CLI's default trunk */
    uint32_t tris = 0, verts = 0;
    size_t bytes = 0;
    double fresh = run(runs, 0, &host, &tris, &verts, &bytes);
    double reused = run(runs, 1, &host, NULL, NULL, NULL);

    /* The net alone (growth, branches, correction, repair), no mesh. */
    banyan_roots_params p;
    banyan_roots_params_init(&p);
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
    printf("bench_roots: default net, 6 main roots x 40 points, n = 16, %d runs per figure, 1 thread\n", runs);
    printf("  mesh (seed 1):          %u vertices, %u triangles, %.2f MB of output\n", verts, tris, bytes / 1e6);
    printf("  median per net, fresh:  %.3f ms  (output memory faulted in anew each call)\n", fresh * 1e3);
    printf("  median per net, reused: %.3f ms  (output memory reused)\n", reused * 1e3);
    printf("  of which the net:       %.3f ms  (the rest is the tube mesh)\n", net_ms * 1e3);
    printf("  triangles/s:            %.3g fresh, %.3g reused\n", tris / fresh, tris / reused);
    printf("  memory write bandwidth: %.3g B/s\n", bw);
    printf("  output rate / bandwidth: %.1f%% fresh, %.1f%% reused\n", 100.0 * bytes / fresh / bw,
           100.0 * bytes / reused / bw);
    return 0;
}
