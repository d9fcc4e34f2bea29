/* Benchmark of host sets: building a set from a closed UV
 * sphere of about 1M triangles (welding, adjacency, pseudonormals and
 * Embree's BVH, one build thread), and the query rates on it and on a
 * 50k-triangle one: closest point near the surface (capped at 5 cm, as the
 * generators ask) and unlimited, the inside test, and short rays.
 *   bench_hosts [runs]   (default 5 builds) */
#include "bench.h"

#include <math.h>

#include "banyan.h"
#include "hosts/hosts.h"
#include "base/rng.h"
#include "host_meshes.h"

static void queries(const char *name, const banyan_hosts *H) {
    const host_mesh *m = &H->meshes[0];
    pcg32 r;
    pcg32_seed(&r, 1, 1);
    enum { N = 200000 };
    v3 *pts = malloc(sizeof(v3) * N);
    for (int i = 0; i < N; i++) { /* within 10 cm of the unit sphere */
        v3 d = v3_norm(v3_make(rng_normal(&r), rng_normal(&r), rng_normal(&r)));
        pts[i] = v3_scale(d, 1.0 + rng_range(&r, -0.1, 0.1));
    }
    double sink = 0, t0 = bench_now();
    for (int i = 0; i < N; i++) sink += hmesh_distance(m, pts[i], 0.05);
    double t1 = bench_now();
    for (int i = 0; i < N; i++) sink += hmesh_distance(m, pts[i], HUGE_VAL);
    double t2 = bench_now();
    for (int i = 0; i < N; i++) sink += hmesh_inside(m, pts[i]);
    double t3 = bench_now();
    for (int i = 0; i < N; i++) {
        double t;
        sink += hmesh_segment_hit(m, pts[i], v3_scale(pts[i], 0.9), &t, NULL);
    }
    double t4 = bench_now();
    printf("  %-10s closest (cap 5 cm) %6.2f us   closest (no cap) %6.2f us   inside %6.2f us   ray %6.2f us  "
           "(%g)\n",
           name, (t1 - t0) / N * 1e6, (t2 - t1) / N * 1e6, (t3 - t2) / N * 1e6, (t4 - t3) / N * 1e6, sink > 0 ? 1.0 : 0.0);
    free(pts);
}

static banyan_hosts *build(const tm_mesh *m, double *seconds) {
    banyan_host_mesh hm = tm_host(m, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = NULL;
    banyan_error err;
    double t0 = bench_now();
    if (banyan_hosts_create(NULL, 0, &hm, 1, &H, &err)) {
        fprintf(stderr, "bench_hosts: %s\n", err.message);
        exit(1);
    }
    *seconds = bench_now() - t0;
    return H;
}

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 5;
    if (runs < 1) runs = 1;
    tm_mesh big = {0}, mid = {0};
    tm_uv_sphere(&big, 0, 0, 0, 1.0, 1000, 501); /* 1,000,000 triangles */
    tm_uv_sphere(&mid, 0, 0, 0, 1.0, 224, 113);  /* about 50,000 */
    double *t = malloc(sizeof(double) * (size_t)runs), s;
    banyan_hosts *H = NULL;
    for (int i = 0; i < runs; i++) {
        banyan_hosts_free(H);
        H = build(&big, &s);
        t[i] = s;
    }
    printf("bench_hosts: host set build, %u triangles, one build thread: median %.3f s over %d runs "
           "(target < 0.5 s)\n", big.nt, bench_median(t, runs), runs);
    queries("1M tris", H);
    banyan_hosts_free(H);
    H = build(&mid, &s);
    printf("bench_hosts: host set build, %u triangles: %.4f s\n", mid.nt, s);
    queries("50k tris", H);
    banyan_hosts_free(H);
    tm_free(&big);
    tm_free(&mid);
    free(t);
    return 0;
}
