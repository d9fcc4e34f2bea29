/* bench.h - shared helpers for the benchmarks in tests/bench/: a
 * monotonic clock, medians, and this machine's memory write bandwidth
 * (the bound a mesh generator cannot beat: every triangle it emits is
 * bytes written). Benchmarks print figures; they assert nothing. */
#ifndef BANYAN_BENCH_H
#define BANYAN_BENCH_H

#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static inline double bench_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static int bench_cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Sorts v[0..n-1] and returns the median. */
static inline double bench_median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Bytes per second of `runs` passes of a plain store loop over a 256 MiB
 * buffer (past every cache) into rates[0..runs-1]; 0 if out of memory.
 * fresh = 0: one buffer, its pages faulted in before the first pass (the
 * bandwidth alone); fresh = 1: a new buffer each pass, so every pass also
 * pays the kernel's page faults, as output memory of a one-shot call does. */
static inline int bench_memory_write_rates(double *rates, int runs, int fresh) {
    size_t n = (size_t)256 << 20, count = n / sizeof(float);
    float *buf = NULL;
    volatile float sink = 0;
    for (int r = 0; r < runs; r++) {
        if (!buf) {
            if (!(buf = malloc(n))) return 0;
            if (!fresh) memset(buf, 1, n); /* fault the pages in first */
        }
        double t0 = bench_now();
        for (size_t i = 0; i < count; i++) buf[i] = (float)(i & 1023);
        double t1 = bench_now();
        rates[r] = n / (t1 - t0);
        sink += buf[12345 + r];
        if (fresh) {
            free(buf);
            buf = NULL;
        }
    }
    (void)sink;
    free(buf);
    return runs;
}

/* Median of five passes of bench_memory_write_rates. */
static inline double bench_memory_write_bandwidth(void) {
    double rates[5];
    return bench_memory_write_rates(rates, 5, 0) ? bench_median(rates, 5) : 0;
}

/* Bytes one mesh triangle costs as output when vertices are shared by a
 * tube's quads (about one vertex per two triangles): 3 indices plus half
 * a vertex of position, normal and uv. */
#define BENCH_BYTES_PER_TUBE_TRIANGLE (3 * 4 + (3 + 3 + 2) * 4 / 2)

#endif
