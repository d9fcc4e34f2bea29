/* banyan_triangle_edges: on hand-made and random triangle lists (crowded
 * fans and degenerate triangles included) and on a swept tube, every
 * corner's edge joins that corner and the next, edges are distinct pairs
 * with the lower vertex first, each is used, they are numbered by first use
 * and their number matches a sort-based count; bad input is refused.
 * Memory follows the corners, not vertex_count: one triangle of a
 * 1e9-vertex mesh runs under a 256 MB address-space cap, and a sparse list
 * gives the same edges with a vertex_count far above its indices. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <sys/resource.h>
#include <string.h>

#include <stdio.h>

#include "banyan.h"
#include "check.h"
#include "base/rng.h"

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static uint64_t pair_key(uint32_t a, uint32_t b) { return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a; }

/* The distinct sides of the triangles, counted by sorting. */
static uint64_t distinct_sides(const uint32_t *idx, uint32_t n) {
    uint64_t *e = malloc(sizeof(uint64_t) * n + 1);
    if (!e) abort();
    for (uint32_t k = 0; k < n; k++) e[k] = pair_key(idx[k], idx[k % 3 == 2 ? k - 2 : k + 1]);
    qsort(e, n, sizeof *e, cmp_u64);
    uint64_t d = 0;
    for (uint32_t k = 0; k < n; k++) d += k == 0 || e[k] != e[k - 1];
    free(e);
    return d;
}

/* Calls banyan_triangle_edges and checks its outputs; returns failures. */
static int check_edges(const char *what, const uint32_t *idx, uint32_t n, uint32_t nv) {
    uint32_t *ce = malloc(sizeof(uint32_t) * n + 1), *ed = malloc(sizeof(uint32_t) * 2 * n + 1),
             *fs = malloc(sizeof(uint32_t) * (n / 3) + 1);
    uint64_t *keys = malloc(sizeof(uint64_t) * n + 1);
    if (!ce || !ed || !fs || !keys) abort();
    uint64_t ne = 99;
    banyan_error err;
    int bad = 0;
    banyan_status st = banyan_triangle_edges(idx, n, nv, ce, ed, n, &ne, fs, &err);
    CHECK(st == BANYAN_OK, "%s: %s", what, err.message);
    if (st != BANYAN_OK) goto out;
    CHECK(ne == distinct_sides(idx, n), "%s: %llu edges, sorting finds %llu", what, (unsigned long long)ne,
          (unsigned long long)distinct_sides(idx, n));
    uint64_t seen = 0; /* edges numbered by first use: a new edge is the next number */
    for (uint32_t k = 0; k < n; k++) {
        uint32_t a = idx[k], b = idx[k % 3 == 2 ? k - 2 : k + 1], e = ce[k];
        if (e >= ne) { bad++; continue; }
        bad += ed[2 * e] != (a < b ? a : b) || ed[2 * e + 1] != (a < b ? b : a);
        if (e == seen) seen++;
        else bad += e > seen;
    }
    CHECK(bad == 0 && seen == ne, "%s: %d corners with a wrong edge, %llu of %llu edges used in order", what, bad,
          (unsigned long long)seen, (unsigned long long)ne);
    int dup = 0;
    for (uint64_t e = 0; e < ne; e++) {
        keys[e] = pair_key(ed[2 * e], ed[2 * e + 1]);
        dup += ed[2 * e] > ed[2 * e + 1];
    }
    qsort(keys, ne, sizeof *keys, cmp_u64);
    for (uint64_t e = 1; e < ne; e++) dup += keys[e] == keys[e - 1];
    CHECK(dup == 0, "%s: %d repeated or unordered edges", what, dup);
    int badfs = 0;
    for (uint32_t t = 0; t < n / 3; t++) badfs += fs[t] != 3 * t;
    CHECK(badfs == 0, "%s: %d wrong face starts", what, badfs);
    /* too little room is refused */
    if (ne > 0) {
        st = banyan_triangle_edges(idx, n, nv, ce, ed, ne - 1, &ne, NULL, &err);
        CHECK(st == BANYAN_E_RANGE && ne == 0 && strstr(err.message, "edge_capacity"), "%s: capacity ne - 1: %d %s",
              what, (int)st, err.message);
    }
out:
    free(ce);
    free(ed);
    free(fs);
    free(keys);
    return bad;
}

static void hand_made(void) {
    /* a quad of two triangles: 5 edges, the diagonal shared */
    const uint32_t quad[] = {0, 1, 2, 0, 2, 3};
    uint32_t ce[6], ed[12];
    uint64_t ne = 0;
    banyan_error err;
    CHECK(banyan_triangle_edges(quad, 6, 4, ce, ed, 6, &ne, NULL, &err) == BANYAN_OK, "quad: %s", err.message);
    const uint32_t want_ce[] = {0, 1, 2, 2, 3, 4}, want_ed[] = {0, 1, 1, 2, 0, 2, 2, 3, 0, 3};
    CHECK(ne == 5 && memcmp(ce, want_ce, sizeof want_ce) == 0 && memcmp(ed, want_ed, sizeof want_ed) == 0,
          "quad: %llu edges, corner edges %u %u %u %u %u %u", (unsigned long long)ne, ce[0], ce[1], ce[2], ce[3],
          ce[4], ce[5]);
    check_edges("quad", quad, 6, 4);
    /* a degenerate triangle keeps its (v, v) side, as Blender's own edges do */
    const uint32_t degen[] = {0, 1, 2, 3, 3, 4};
    check_edges("degenerate", degen, 6, 5);
    CHECK(banyan_triangle_edges(degen, 6, 5, ce, ed, 6, &ne, NULL, &err) == BANYAN_OK && ne == 5 &&
              ed[2 * ce[3]] == 3 && ed[2 * ce[3] + 1] == 3, "degenerate: %llu edges", (unsigned long long)ne);
    /* a closed fan of 200 triangles round vertex 0 (the qsort path) */
    enum { FAN = 200 };
    uint32_t fan[3 * FAN];
    for (uint32_t t = 0; t < FAN; t++) {
        fan[3 * t] = 0;
        fan[3 * t + 1] = 1 + t;
        fan[3 * t + 2] = 1 + (t + 1) % FAN;
    }
    check_edges("fan", fan, 3 * FAN, FAN + 1);
    CHECK(banyan_triangle_edges(fan, 3 * FAN, FAN + 1, ce, ed, 0, &ne, NULL, &err) ==
              BANYAN_E_RANGE, "fan with no room");
    /* nothing in, nothing out */
    ne = 7;
    CHECK(banyan_triangle_edges(NULL, 0, 0, NULL, NULL, 0, &ne, NULL, &err) == BANYAN_OK && ne == 0, "empty: %s",
          err.message);
}

static void random_lists(void) {
    pcg32 r;
    pcg32_seed(&r, 7, 1);
    for (int round = 0; round < 40; round++) {
        uint32_t nv = 3 + rng_below(&r, round < 20 ? 12 : 3000);
        uint32_t n = 3 * (1 + rng_below(&r, 4000));
        uint32_t *idx = malloc(sizeof(uint32_t) * n);
        if (!idx) abort();
        for (uint32_t k = 0; k < n; k++) idx[k] = rng_below(&r, nv);
        char what[64];
        snprintf(what, sizeof what, "random %d (%u vertices, %u corners)", round, nv, n);
        check_edges(what, idx, n, nv);
        free(idx);
    }
}

static void tube(void) {
    double pts[3 * 40], rad[40];
    for (int i = 0; i < 40; i++) {
        pts[3 * i] = 0.1 * i;
        pts[3 * i + 1] = 0.3 * (i % 7);
        pts[3 * i + 2] = 0.02 * i * i;
        rad[i] = 0.05 + 0.001 * i;
    }
    banyan_mesh *m = NULL;
    banyan_error err;
    CHECK(banyan_tube_generate(pts, rad, 40, 12, 1, &m, &err) == BANYAN_OK, "tube: %s", err.message);
    if (m) check_edges("tube", m->indices, m->index_count, m->vertex_count);
    banyan_mesh_free(m);
}

static void refused(void) {
    const uint32_t tri[] = {0, 1, 2, 0, 2, 5};
    uint32_t ce[6], ed[12];
    uint64_t ne = 3;
    banyan_error err;
    CHECK(banyan_triangle_edges(tri, 6, 5, ce, ed, 6, &ne, NULL, &err) == BANYAN_E_RANGE && ne == 0 &&
              strstr(err.message, "indices[5] = 5"), "index out of range: %s", err.message);
    CHECK(banyan_triangle_edges(tri, 5, 6, ce, ed, 6, &ne, NULL, &err) == BANYAN_E_INVALID_ARG &&
              strstr(err.message, "multiple of 3"), "index_count 5: %s", err.message);
    CHECK(banyan_triangle_edges(NULL, 6, 6, ce, ed, 6, &ne, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL indices");
    CHECK(banyan_triangle_edges(tri, 6, 6, NULL, ed, 6, &ne, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL corner_edges");
    CHECK(banyan_triangle_edges(tri, 6, 6, ce, NULL, 6, &ne, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL edges");
    CHECK(banyan_triangle_edges(tri, 6, 6, ce, ed, 6, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL edge_count");
    CHECK(banyan_triangle_edges(tri, (uint64_t)UINT32_MAX + 3, 6, ce, ed, 6, &ne, NULL, &err) == BANYAN_E_RANGE,
          "index_count past 32 bits");
}

/* Caps the address space at what the test has now plus 256 MB, so that
 * tables sized by vertex_count (a regression) fail with NOMEM instead of
 * taking gigabytes. 1 when capped (not under the sanitizers, which
 * reserve terabytes of shadow up front); uncap with the saved limit. */
static int cap_memory(struct rlimit *old) {
    int capped = 0;
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
    unsigned long pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f && fscanf(f, "%lu", &pages) == 1 && getrlimit(RLIMIT_AS, old) == 0) {
        struct rlimit cap = {(rlim_t)pages * 4096 + (256u << 20), old->rlim_max};
        capped = setrlimit(RLIMIT_AS, &cap) == 0;
    }
    if (f) fclose(f);
#else
    (void)old;
#endif
    return capped;
}

/* The same indices with vertex_count just enough and far above: the
 * outputs are equal (the second numbers the used vertices first). */
static void sparse(void) {
    struct rlimit old;
    int capped = cap_memory(&old);
    pcg32 r;
    pcg32_seed(&r, 11, 1);
    for (int round = 0; round < 12; round++) {
        uint32_t nv = 3 + rng_below(&r, round < 6 ? 12 : 3000), n = 3 * (1 + rng_below(&r, 3000));
        uint32_t *idx = malloc(sizeof(uint32_t) * n), *ce[2], *ed[2];
        uint64_t ne[2] = {0, 0};
        banyan_error err;
        for (int k = 0; k < 2; k++) {
            ce[k] = malloc(sizeof(uint32_t) * n);
            ed[k] = malloc(sizeof(uint32_t) * 2 * n);
        }
        if (!idx || !ce[0] || !ce[1] || !ed[0] || !ed[1]) abort();
        for (uint32_t k = 0; k < n; k++) idx[k] = rng_below(&r, nv);
        CHECK(banyan_triangle_edges(idx, n, nv, ce[0], ed[0], n, &ne[0], NULL, &err) == BANYAN_OK, "%s", err.message);
        CHECK(banyan_triangle_edges(idx, n, UINT32_MAX, ce[1], ed[1], n, &ne[1], NULL, &err) == BANYAN_OK, "%s",
              err.message);
        CHECK(ne[0] == ne[1] && !memcmp(ce[0], ce[1], sizeof(uint32_t) * n) &&
                  !memcmp(ed[0], ed[1], sizeof(uint32_t) * 2 * ne[0]),
              "sparse %d: %llu and %llu edges, or other edges with vertex_count 2^32-1", round,
              (unsigned long long)ne[0], (unsigned long long)ne[1]);
        /* spread over the whole 32-bit range, crowded fans included */
        for (uint32_t k = 0; k < n; k++) idx[k] = idx[k] * (UINT32_MAX / nv);
        char what[64];
        snprintf(what, sizeof what, "spread %d (%u corners)", round, n);
        check_edges(what, idx, n, UINT32_MAX);
        for (int k = 0; k < 2; k++) {
            free(ce[k]);
            free(ed[k]);
        }
        free(idx);
    }
    if (capped) setrlimit(RLIMIT_AS, &old);
}

/* One triangle of a 1e9-vertex mesh (3.9 GB as per-vertex tables)
 * within 256 MB more address space than the test has. */
static void one_triangle_of_many(void) {
    const uint32_t tri[3] = {999999999u, 7, 500000000u};
    uint32_t ce[3], ed[6];
    uint64_t ne = 0;
    banyan_error err;
    struct rlimit old;
    int capped = cap_memory(&old);
    banyan_status st = banyan_triangle_edges(tri, 3, 1000000000u, ce, ed, 3, &ne, NULL, &err);
    if (capped) setrlimit(RLIMIT_AS, &old);
    CHECK(st == BANYAN_OK && ne == 3 && ed[0] == 7 && ed[1] == 999999999u && ed[2] == 7 && ed[3] == 500000000u &&
              ed[4] == 500000000u && ed[5] == 999999999u && ce[0] == 0 && ce[1] == 1 && ce[2] == 2,
          "one triangle of 1e9 vertices%s: %s %s", capped ? " (256 MB cap)" : "", banyan_status_name(st),
          err.message);
}

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    hand_made();
    random_lists();
    tube();
    refused();
    sparse();
    one_triangle_of_many();
    return check_done("test_mesh_edges");
}
