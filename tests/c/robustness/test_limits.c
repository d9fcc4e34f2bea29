/* test_limits.c - vertex limits refuse before large buffers exist.
 * The test links with -Wl,--wrap for malloc, calloc and
 * realloc (tests/CMakeLists.txt), so every allocation the library's
 * objects make passes the counters below: a generation that would pass
 * max_vertices must fail with BANYAN_E_LIMIT, return no mesh, and never
 * ask for a block larger than a few megabytes - although the mesh it was
 * asked for would take gigabytes. Successful generations are measured too,
 * to show the counters see the mesh when there is one. Leaks on these
 * paths are LeakSanitizer's job (the ASan build) and valgrind's
 * (docs/reliability.md). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <errno.h>

#include "banyan.h"
#include "check.h"
#include "host_meshes.h"
#include "test_hosts.h"

/* The counters: the largest single request and the sum of requests;
 * the calls since reset(), and which of them fails (0: none). */
static size_t alloc_largest;
static unsigned long long alloc_total;
static long alloc_calls, alloc_fail_at;

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t m);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t m);
void *__wrap_realloc(void *p, size_t n);
/* big_alloc's arrays of 4 MiB and more come from posix_memalign. */
int __real_posix_memalign(void **p, size_t align, size_t n);
int __wrap_posix_memalign(void **p, size_t align, size_t n);

/* Counts a request; returns 1 when it is the one to fail. */
static int count(size_t n) {
    if (n > alloc_largest) alloc_largest = n;
    alloc_total += n;
    return ++alloc_calls == alloc_fail_at;
}
void *__wrap_malloc(size_t n) {
    return count(n) ? NULL : __real_malloc(n);
}
void *__wrap_calloc(size_t n, size_t m) {
    return count(m && n > SIZE_MAX / m ? SIZE_MAX : n * m) ? NULL : __real_calloc(n, m);
}
void *__wrap_realloc(void *p, size_t n) {
    return count(n) ? NULL : __real_realloc(p, n);
}
int __wrap_posix_memalign(void **p, size_t align, size_t n) {
    return count(n) ? ENOMEM : __real_posix_memalign(p, align, n);
}

static void reset(void) {
    alloc_largest = 0;
    alloc_total = 0;
    alloc_calls = 0;
}

#define MB (1024.0 * 1024.0)
/* A refusal may allocate its bookkeeping (hosts, per-tree params, the
 * skeleton it grows to count), never the mesh. */
#define REFUSAL_LARGEST (8u << 20)

/* One refused generation: status, NULL out, allocations small. The
 * `wanted` text says what the mesh would have needed. */
static void refused(const char *what, banyan_status s, const banyan_mesh *m, const banyan_error *e) {
    CHECK(s == BANYAN_E_LIMIT, "%s: got %s: %s", what, banyan_status_name(s), e->message);
    CHECK(m == NULL, "%s: out is not NULL", what);
    CHECK(alloc_largest < REFUSAL_LARGEST, "%s: largest allocation %.1f MB before refusing", what,
          alloc_largest / MB);
    printf("%-58s refused, largest allocation %8.3f MB, %8.3f MB in all\n", what, alloc_largest / MB,
           (double)alloc_total / MB);
}

/* Out of memory at every allocation (a failed call leaves *out
 * NULL, leaks nothing and never crashes). The generation runs once to
 * count its allocations, then once per allocation with that one failing:
 * each run must give a mesh (the paths that can do without the memory,
 * such as the ivy light cache's edges) or BANYAN_E_NOMEM and no mesh.
 * Leaks on these paths are the ASan build's (LeakSanitizer). */
typedef banyan_status (*generate_fn)(const void *ctx, banyan_mesh **out, banyan_error *e);

static void fail_each(const char *what, generate_fn gen, const void *ctx) {
    banyan_error e;
    banyan_mesh *m = NULL;
    reset();
    banyan_status s = gen(ctx, &m, &e);
    long total = alloc_calls;
    CHECK(s == BANYAN_OK && m, "%s: %s", what, e.message);
    banyan_mesh_free(m);
    int ok = 0, nomem = 0, bad = 0;
    for (long k = 1; k <= total; k++) {
        reset();
        alloc_fail_at = k;
        m = NULL;
        s = gen(ctx, &m, &e);
        alloc_fail_at = 0;
        if (s == BANYAN_OK && m) ok++;
        else if (s == BANYAN_E_NOMEM && !m) nomem++;
        else if (bad++ < 3)
            fprintf(stderr, "%s, allocation %ld of %ld failing: %s, mesh %p: %s\n", what, k, total,
                    banyan_status_name(s), (void *)m, e.message);
        banyan_mesh_free(m);
    }
    CHECK(bad == 0, "%s: %d of %ld failing allocations gave a wrong result", what, bad, total);
    CHECK(nomem > 0, "%s: no failing allocation was reported", what);
    printf("%-58s %ld allocations failed one at a time: %d reported, %d did without\n", what, total, nomem, ok);
}

/* The host set is built inside, so its failure paths count. */
static banyan_status gen_roots(const void *ctx, banyan_mesh **out, banyan_error *e) {
    banyan_hosts *H = NULL;
    banyan_status s = banyan_hosts_create((const banyan_box *)ctx, 1, NULL, 0, &H, e);
    if (s) return s;
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    s = banyan_roots_generate(&p, H, out, NULL, NULL, e);
    banyan_hosts_free(H);
    return s;
}
static banyan_status gen_roots_mesh(const void *ctx, banyan_mesh **out, banyan_error *e) {
    banyan_hosts *H = NULL;
    banyan_status s = banyan_hosts_create(NULL, 0, (const banyan_host_mesh *)ctx, 1, &H, e);
    if (s) return s;
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.growth_points = 12;
    s = banyan_roots_generate(&p, H, out, NULL, NULL, e);
    banyan_hosts_free(H);
    return s;
}
static banyan_status gen_ivy_mesh(const void *ctx, banyan_mesh **out, banyan_error *e) {
    banyan_hosts *H = NULL;
    banyan_status s = banyan_hosts_create(NULL, 0, (const banyan_host_mesh *)ctx, 1, &H, e);
    if (s) return s;
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = 60;
    p.start[0] = 0, p.start[1] = -0.6, p.start[2] = 0.1;
    s = banyan_ivy_generate(&p, H, out, NULL, NULL, e);
    banyan_hosts_free(H);
    return s;
}
static banyan_status gen_keyaki(const void *ctx, banyan_mesh **out, banyan_error *e) {
    (void)ctx;
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    return banyan_keyaki_generate(&p, out, NULL, NULL, e);
}
static banyan_status gen_avenue(const void *ctx, banyan_mesh **out, banyan_error *e) {
    (void)ctx;
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    p.placement = BANYAN_AVENUE_COUNT, p.count = 2;
    p.threads = 1;
    return banyan_avenue_generate(&p, NULL, 0, out, NULL, e); /* one thread: the counters are not atomic */
}
static banyan_status gen_ivy(const void *ctx, banyan_mesh **out, banyan_error *e) {
    banyan_hosts *H = NULL;
    banyan_status s = banyan_hosts_create((const banyan_box *)ctx, 1, NULL, 0, &H, e);
    if (s) return s;
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = 160;
    s = banyan_ivy_generate(&p, H, out, NULL, NULL, e);
    banyan_hosts_free(H);
    return s;
}
static banyan_status gen_segments(const void *ctx, banyan_mesh **out, banyan_error *e) {
    (void)ctx;
    banyan_segment_input segs[3] = {{{0, 0, 0}, {0, 0, 1}, 1.0, 12, 3}, {{0, 0, 1}, {1, 0, 1}, 0.6, 10, 3},
                                    {{0, 0, 1}, {-1, 0, 1}, 0.6, 10, 3}};
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    return banyan_segments_generate(&p, segs, 3, NULL, out, NULL, NULL, e);
}
static banyan_status gen_tube(const void *ctx, banyan_mesh **out, banyan_error *e) {
    (void)ctx;
    double pts[3 * 16], radii[16];
    for (int i = 0; i < 16; i++) pts[3 * i] = 0.1 * i, pts[3 * i + 1] = 0, pts[3 * i + 2] = 0.01 * i * i, radii[i] = 0.05;
    return banyan_tube_generate(pts, radii, 16, 8, 1, out, e);
}

int main(void) {
    banyan_error e;
    banyan_mesh *m;
    banyan_box trunk = banyan_box_make(0, 0, 1, 0.3, 0.3, 1), wall = banyan_box_make(0, 0.1, 1.5, 1.5, 0.1, 1.5);

    /* The counters work: a real tree allocates its mesh. */
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    kp.leaf_density = 60; /* a mesh far larger than the skeleton */
    reset();
    m = NULL;
    banyan_status s = banyan_keyaki_generate(&kp, &m, NULL, NULL, &e);
    CHECK(s == BANYAN_OK && m, "keyaki: %s", e.message);
    size_t positions = m ? sizeof(float) * 3 * (size_t)m->vertex_count : 0;
    CHECK(m && alloc_largest >= positions, "the counters see the mesh: largest %zu < positions %zu", alloc_largest,
          positions);
    printf("%-58s ok, %u vertices, largest allocation %.3f MB\n", "keyaki, leaf_density 60", m ? m->vertex_count : 0,
           alloc_largest / MB);
    banyan_mesh_free(m);

    /* Roots: about 1.2e9 vertices asked for, refused from the estimate,
     * under the default cap and under the largest cap. */
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    rp.growth_points = 10000, rp.main_roots = 64, rp.sides = 256;
    int32_t caps[2] = {4000000, 1 << 30};
    for (int k = 0; k < 2; k++) {
        rp.max_vertices = caps[k];
        reset();
        m = NULL;
        s = test_roots_boxes(&rp, &trunk, 1, &m, &e);
        refused(k ? "roots 64 x 10000 points x 256 sides, max 2^30" : "roots 64 x 10000 points x 256 sides, max 4e6",
                s, m, &e);
    }

    /* Keyaki: the skeleton is grown to count, the mesh is not made. */
    banyan_keyaki_params_init(&kp);
    kp.max_vertices = 1000;
    reset();
    m = NULL;
    s = banyan_keyaki_generate(&kp, &m, NULL, NULL, &e);
    refused("keyaki default tree, max_vertices 1000", s, m, &e);
    banyan_keyaki_params_init(&kp);
    kp.model = BANYAN_KEYAKI_SIMPLE, kp.levels = 30, kp.max_nodes = 1 << 24;
    reset();
    m = NULL;
    s = banyan_keyaki_generate(&kp, &m, NULL, NULL, &e);
    refused("keyaki simple, 30 levels (2^31 branches)", s, m, &e);

    /* Avenue: 10,000 trees, stops counting once max_vertices is passed. */
    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    ap.placement = BANYAN_AVENUE_COUNT, ap.count = 5000, ap.max_vertices = 1000;
    reset();
    m = NULL;
    ap.threads = 2;
    s = banyan_avenue_generate(&ap, NULL, 0, &m, NULL, &e);
    refused("avenue 2 x 5000 trees, max_vertices 1000", s, m, &e);
    CHECK(strstr(e.message, "counted before stopping") != NULL || strstr(e.message, "with the other trees") != NULL,
          "the avenue stopped counting early: %s", e.message);
    ap.max_vertices = 1000000;
    reset();
    m = NULL;
    s = banyan_avenue_generate(&ap, NULL, 0, &m, NULL, &e);
    refused("avenue 2 x 5000 trees, max_vertices 1e6", s, m, &e);

    /* Ivy: 100,000 steps with a small cap stops growing early. */
    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    ip.steps = BANYAN_IVY_MAX_STEPS, ip.max_vertices = 50000, ip.t0 = 1e6;
    reset();
    m = NULL;
    s = test_ivy_boxes(&ip, &wall, 1, &m, &e);
    refused("ivy 100000 steps, max_vertices 50000", s, m, &e);

    /* Segments: 131,072 segments of 64 lines, each a 64-sided tube. */
    uint32_t n = 1u << 17;
    banyan_segment_input *segs = malloc(sizeof *segs * n);
    for (uint32_t i = 0; i < n; i++) segs[i] = (banyan_segment_input){{0, 0, 0.001 * i}, {1, 0, 1}, 1.0, 20, 3};
    banyan_segments_params sp;
    banyan_segments_params_init(&sp);
    sp.max_vertices = 1 << 30;
    sp.sides = 64;
    reset();
    m = NULL;
    s = banyan_segments_generate(&sp, segs, n, NULL, &m, NULL, NULL, &e);
    refused("segments 2^17 x 64 lines x 64 sides, max_vertices 2^30", s, m, &e);
    free(segs);

    /* The tube demo: 1e6 points x 257 vertices. */
    double *pts = malloc(sizeof(double) * 3 * 1000000), *radii = malloc(sizeof(double) * 1000000);
    for (int i = 0; i < 1000000; i++) {
        pts[3 * i] = 0, pts[3 * i + 1] = 0, pts[3 * i + 2] = 0.01 * i;
        radii[i] = 0.1;
    }
    reset();
    m = NULL;
    s = banyan_tube_generate(pts, radii, 1000000, 256, 1, &m, &e);
    refused("tube 1e6 points x 256 sides", s, m, &e);
    free(pts);
    free(radii);

    fail_each("out of memory: roots default", gen_roots, &trunk);
    fail_each("out of memory: keyaki default", gen_keyaki, NULL);
    fail_each("out of memory: avenue of 2", gen_avenue, NULL);
    fail_each("out of memory: ivy, 160 steps on a wall", gen_ivy, &wall);
    fail_each("out of memory: segments, 3", gen_segments, NULL);
    fail_each("out of memory: tube, 16 points", gen_tube, NULL);
    tm_mesh sphere = {0}; /* made before any allocation is failed */
    tm_uv_sphere(&sphere, 0, 0, 0.5, 0.5, 16, 8);
    banyan_host_mesh host = tm_host(&sphere, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    fail_each("out of memory: roots on a mesh (host set inside)", gen_roots_mesh, &host);
    fail_each("out of memory: ivy on a mesh (host set inside)", gen_ivy_mesh, &host);
    tm_free(&sphere);
    return check_done("test_limits");
}
