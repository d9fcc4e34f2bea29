/* Segments: CPU reference speed over 1e6 random segments (n uniform in
 * 0..63, s in 0..10, as in the segment tests; most of them reach the
 * 128-vertex budget), one banyan_segment_lines call per segment and in
 * batches of 4096 (banyan_segment_lines_many); then the composer on a
 * random demo tree and the attachment check on a large list. Median of 5
 * runs. The llvmpipe shader's figure comes from
 * `test_segments_gl --bench` (tests/gl/). */
#include "bench.h"

#include <math.h>

#include "banyan.h"
#include "base/rng.h"

enum { N = 1000000, RUNS = 5, BATCH = 4096 };

int main(void) {
    banyan_segment_input *in = malloc(sizeof *in * N);
    float *xyz = malloc(sizeof(float) * 3 * BANYAN_SEGMENT_MAX_VERTICES * BATCH);
    uint8_t *lev = malloc((size_t)BANYAN_SEGMENT_MAX_VERTICES * BATCH);
    int32_t *counts = malloc(sizeof *counts * BATCH);
    if (!in || !xyz || !lev || !counts) return 1;
    pcg32 r;
    pcg32_seed(&r, 1, 6);
    for (int i = 0; i < N; i++) {
        for (int c = 0; c < 3; c++) in[i].S[c] = rng_range(&r, -50, 50);
        for (int c = 0; c < 3; c++) in[i].A[c] = rng_range(&r, -1, 1);
        in[i].A[2] += 2;
        in[i].l = rng_range(&r, 0, 20);
        in[i].n = (int32_t)rng_below(&r, 64);
        in[i].s = (int32_t)rng_below(&r, 11);
    }
    banyan_segment_params p;
    banyan_segment_params_init(&p);
    double single[RUNS], batch[RUNS];
    long long verts = 0;
    volatile float sink = 0;
    for (int k = 0; k < RUNS; k++) {
        verts = 0;
        double t0 = bench_now();
        for (int i = 0; i < N; i++) {
            int32_t c;
            banyan_segment_lines(&in[i], &p, xyz, lev, &c, NULL);
            verts += c;
        }
        double t1 = bench_now();
        for (int i = 0; i < N; i += BATCH) {
            uint32_t b = (uint32_t)(N - i < BATCH ? N - i : BATCH);
            banyan_segment_lines_many(in + i, b, &p, xyz, lev, counts, NULL);
        }
        double t2 = bench_now();
        sink += xyz[7];
        single[k] = N / (t1 - t0);
        batch[k] = N / (t2 - t1);
    }
    double s1 = bench_median(single, RUNS), s2 = bench_median(batch, RUNS);
    printf("segment reference, %d random segments (n 0..63, s 0..10; %.1f vertices each on average):\n", N,
           (double)verts / N);
    printf("  one call per segment:   %.3g segments/s, %.3g vertices/s\n", s1, s1 * verts / N);
    printf("  batches of %d:        %.3g segments/s, %.3g vertices/s\n", BATCH, s2, s2 * verts / N);

    /* Composer: a random demo tree meshed with tubes. */
    banyan_segments_params tp;
    banyan_segments_params_init(&tp);
    tp.demo_segments = 5000;
    tp.max_vertices = 1 << 30;
    uint32_t n;
    double trunk[6];
    banyan_segments_demo(&tp, in, N, &n, trunk, NULL);
    double mesh_rate[RUNS];
    uint32_t tris = 0, lines = 0;
    for (int k = 0; k < RUNS; k++) {
        banyan_mesh *m = NULL;
        banyan_segments_stats st;
        double t0 = bench_now();
        banyan_error err;
        if (banyan_segments_generate(&tp, in, n, trunk, &m, &st, NULL, &err)) {
            printf("composer failed: %s\n", err.message);
            break;
        }
        double t1 = bench_now();
        tris = m ? m->index_count / 3 : 0;
        lines = st.lines;
        mesh_rate[k] = n / (t1 - t0);
        banyan_mesh_free(m);
    }
    double mr = bench_median(mesh_rate, RUNS);
    printf("composer, demo tree of %u segments (%u lines, %u triangles, sides %d): %.3g segments/s, %.3g "
           "triangles/s\n", n, lines, tris, tp.sides, mr, mr * tris / n);

    /* Attachment check on a large attached list (uniform grid). */
    tp.demo_segments = 100000;
    banyan_segments_demo(&tp, in, N, &n, trunk, NULL);
    uint32_t *un = malloc(sizeof *un * n), nu = 0;
    double att[RUNS];
    for (int k = 0; k < RUNS; k++) {
        double t0 = bench_now();
        banyan_segments_find_unattached(&tp, in, n, trunk, un, &nu, NULL);
        att[k] = n / (bench_now() - t0);
    }
    printf("attachment check, %u segments (%u unattached): %.3g segments/s\n", n, nu, bench_median(att, RUNS));
    printf("memory write bandwidth: %.3g GB/s\n", bench_memory_write_bandwidth() / 1e9);
    free(un);
    free(in);
    free(xyz);
    free(lev);
    free(counts);
    return sink == 12345 ? 1 : 0;
}
