/* test_budget.c - every run keeps its budget:
 * long ivy, roots and segments runs under max_seconds = 2 stop within 2.5 s of wall time
 * with BANYAN_E_LIMIT and a message naming max_seconds; a memory budget
 * stops with BANYAN_E_LIMIT naming max_memory_mb before the process holds
 * 1.5 times it; the step API keeps max_vertices while it grows. The
 * margins are wide (a noisy 2-core VM, ASan): the budget is checked every
 * few milliseconds, so a stop within 0.5 s of it is a loose bound. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "banyan.h"
#include "check.h"
#include "test_hosts.h"

#define BUDGET 2.0
#define WITHIN 2.5
#define MEMORY 32.0 /* MB */

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* The generators' default budget (max_seconds, max_memory_mb). */
static banyan_budget default_budget(void) {
    banyan_budget b;
    banyan_budget_init(&b);
    return b;
}

/* The resident size in MB, every thread counted: what the budget reads
 * (statm's second field), here read on its own. */
static double rss_mb(void) {
    unsigned long long pages[2] = {0, 0};
    FILE *f = fopen("/proc/self/statm", "r");
    int n = f ? fscanf(f, "%llu %llu", &pages[0], &pages[1]) : 0;
    if (f) fclose(f);
    return n == 2 ? (double)pages[1] * 4096.0 / (1024.0 * 1024.0) : 0.0;
}

/* One stopped run: BANYAN_E_LIMIT naming `what`, no mesh, in time. */
static void stopped(const char *name, banyan_status s, const banyan_mesh *m, const banyan_error *e, double t,
                    const char *what, double within) {
    printf("%s: status %d after %.2f s: %s\n", name, (int)s, t, e->message);
    CHECK(s == BANYAN_E_LIMIT, "%s: status %d, want BANYAN_E_LIMIT (%s)", name, (int)s, e->message);
    CHECK(m == NULL, "%s: a mesh came with the failure", name);
    CHECK(strstr(e->message, what) != NULL, "%s: message does not name %s: %s", name, what, e->message);
    CHECK(t < within, "%s: stopped after %.2f s, want < %.2f s", name, t, within);
}

/* The CLI's default wall, and one 1 km wide and high. */
static banyan_box wall_3m(void) { return banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5); }
static banyan_box wall_1km(void) { return banyan_box_make(0.0, 0.1, 500.0, 500.0, 0.1, 500.0); }

/* Ivy that never shades itself (t0 = 1e6) with the caps out of the way:
 * only the budget can stop it. */
static void ivy_unbounded(banyan_ivy_params *p) {
    banyan_ivy_params_init(p);
    p->t0 = 1e6;
    p->steps = BANYAN_IVY_MAX_STEPS;
    p->max_buds = 50000000;
    p->max_vertices = 1 << 30;
    p->max_seconds = BUDGET;
}

/* A memory budget, first while the process is small: the peak resident
 * size it reaches stays under 1.5 times the budget above the start. */
static void ivy_memory(void) {
    banyan_ivy_params p;
    ivy_unbounded(&p);
    p.max_seconds = 60;
    p.max_memory_mb = MEMORY;
    banyan_box w = wall_1km();
    banyan_ivy *iv = NULL;
    banyan_error e;
    banyan_hosts *W = TEST_HOSTS(&w, 1);
    double rss0 = rss_mb(), peak = 0;
    banyan_status s = banyan_ivy_create(&p, W, &iv, &e);
    CHECK(s == BANYAN_OK, "ivy create: %s", e.message);
    double t = now();
    /* Steps in parts, reading the resident size between them. */
    for (int k = 0; !s && k < 10000; k++) {
        s = banyan_ivy_step(iv, 10, &e);
        double mb = rss_mb() - rss0;
        if (mb > peak) peak = mb;
    }
    stopped("ivy memory", s, NULL, &e, now() - t, "max_memory_mb", 60);
    printf("ivy memory: peak %.0f MB above the start, budget %g MB\n", peak, MEMORY);
    CHECK(peak < 1.5 * MEMORY, "ivy memory: %.0f MB above the start, budget %g MB", peak, MEMORY);
    banyan_mesh *m = NULL;
    CHECK(banyan_ivy_mesh(iv, &m, &e) == BANYAN_E_LIMIT && m == NULL, "a stopped plant still meshes");
    banyan_ivy_free(iv);
    banyan_hosts_free(W);
}

/* `banyan ivy --set t0=1000000` through the step API as the
 * CLI calls it, and through the one-shot call. */
static void ivy_time(void) {
    banyan_ivy_params p;
    ivy_unbounded(&p);
    banyan_box w = wall_3m();
    banyan_hosts *H = TEST_HOSTS(&w, 1);
    banyan_error e;
    banyan_ivy *iv = NULL;
    CHECK(banyan_ivy_create(&p, H, &iv, &e) == BANYAN_OK, "ivy create: %s", e.message);
    double t = now();
    banyan_status s = banyan_ivy_step(iv, p.steps, &e);
    stopped("ivy t0=1e6, step API", s, NULL, &e, now() - t, "max_seconds", WITHIN);
    /* The handle stays stopped: the next step and the mesh refuse at once. */
    t = now();
    CHECK(banyan_ivy_step(iv, 1, &e) == BANYAN_E_LIMIT && strstr(e.message, "max_seconds"), "second step: %s",
          e.message);
    banyan_mesh *m = NULL;
    CHECK(banyan_ivy_mesh(iv, &m, &e) == BANYAN_E_LIMIT && m == NULL, "mesh after the stop: %s", e.message);
    CHECK(now() - t < 0.5, "a stopped handle took %.2f s to refuse", now() - t);
    banyan_ivy_free(iv);

    m = NULL;
    t = now();
    s = banyan_ivy_generate(&p, H, &m, NULL, NULL, &e);
    stopped("ivy t0=1e6, generate", s, m, &e, now() - t, "max_seconds", WITHIN);

    /* The step budget adds up over the calls (step_seconds). */
    CHECK(banyan_ivy_create(&p, H, &iv, &e) == BANYAN_OK, "ivy create: %s", e.message);
    t = now();
    s = BANYAN_OK;
    for (int k = 0; !s && k < 100000; k++) s = banyan_ivy_step(iv, 1, &e);
    stopped("ivy t0=1e6, one step a call", s, NULL, &e, now() - t, "max_seconds", WITHIN);
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
}

/* A 1 km wall. With the default max_vertices the step API
 * refuses as soon as the plant could not be meshed (as the one shot
 * does); with that cap raised, the time budget stops it. */
static void ivy_wall(void) {
    banyan_ivy_params p;
    ivy_unbounded(&p);
    banyan_box w = wall_1km(), small = wall_3m();
    banyan_hosts *W = TEST_HOSTS(&w, 1), *S = TEST_HOSTS(&small, 1);
    banyan_error e;
    banyan_ivy *iv = NULL;
    CHECK(banyan_ivy_create(&p, W, &iv, &e) == BANYAN_OK, "ivy create: %s", e.message);
    double t = now();
    banyan_status s = banyan_ivy_step(iv, p.steps, &e);
    stopped("ivy t0=1e6, 1 km wall", s, NULL, &e, now() - t, "max_seconds", WITHIN);
    banyan_ivy_free(iv);

    /* max_vertices while stepping: refused between steps, and the plant
     * stays usable (its mesh within the cap). */
    p.max_vertices = 200000;
    p.max_seconds = default_budget().max_seconds;
    CHECK(banyan_ivy_create(&p, S, &iv, &e) == BANYAN_OK, "ivy create: %s", e.message);
    t = now();
    s = banyan_ivy_step(iv, p.steps, &e);
    stopped("ivy t0=1e6, step API, max_vertices 200000", s, NULL, &e, now() - t, "max_vertices", 30);
    banyan_ivy_stats st;
    CHECK(banyan_ivy_get_stats(iv, &st, &e) == BANYAN_OK && st.steps > 0 && st.steps < 1000, "steps %d", st.steps);
    banyan_ivy_free(iv);
    banyan_hosts_free(W);
    banyan_hosts_free(S);
}

/* 256 hosts, 64 roots, 10,000 growth points, 100 moves. A
 * trunk in the middle (G on it) among 255 posts on a 16 x 16 grid. */
static void roots_time(banyan_roots_surface surface) {
    banyan_box boxes[256];
    boxes[0] = banyan_box_make(0, 0, 2.0, 0.3, 0.3, 2.0);
    for (int i = 1; i < 256; i++) {
        double x = (i % 16 - 7.5) * 1.5, y = (i / 16 - 7.5) * 1.5;
        boxes[i] = banyan_box_make(x + 0.4, y + 0.4, 0.5, 0.15, 0.15, 0.5);
    }
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.main_roots = 64;
    p.growth_points = 10000;
    p.moves = 100;
    p.surface = surface;
    p.max_vertices = 1 << 30;
    p.max_seconds = BUDGET;
    p.ground = 0; /* nothing ends the roots early: every move of every point is made */
    banyan_error e;
    banyan_mesh *m = NULL;
    double t = now();
    banyan_status s = test_roots_boxes(&p, boxes, 256, &m, &e);
    stopped(surface == BANYAN_ROOTS_FUSED ? "roots 256 hosts, fused" : "roots 256 hosts, tubes", s, m, &e,
            now() - t, "max_seconds", WITHIN);
    banyan_mesh_free(m);
}

/* Segments: the mesh's memory is known before it is built (refused up
 * front), and a big tree stops on the clock. */
static void segments(void) {
    uint32_t n = 1u << 14;
    banyan_segment_input *segs = malloc(sizeof *segs * n);
    CHECK(segs != NULL, "out of memory");
    if (!segs) return;
    for (uint32_t i = 0; i < n; i++) segs[i] = (banyan_segment_input){{0, 0, 0.001 * i}, {1, 0, 1}, 1.0, 20, 3};
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    p.max_vertices = 1 << 30;
    p.sides = 64;
    p.max_memory_mb = 64;
    banyan_error e;
    banyan_mesh *m = NULL;
    double rss0 = rss_mb(), t = now();
    banyan_status s = banyan_segments_generate(&p, segs, n, NULL, &m, NULL, NULL, &e);
    stopped("segments 2^14 x 64 lines x 64 sides, 64 MB", s, m, &e, now() - t, "max_memory_mb", WITHIN);
    CHECK(rss_mb() - rss0 < 64, "segments: refused after taking %.0f MB", rss_mb() - rss0);

    p.sides = 3;
    p.max_memory_mb = default_budget().max_memory_mb;
    p.max_seconds = 0.05;
    t = now();
    s = banyan_segments_generate(&p, segs, n, NULL, &m, NULL, NULL, &e);
    stopped("segments 2^14 x 64 lines, 0.05 s", s, m, &e, now() - t, "max_seconds", 0.05 + 0.5);
    free(segs);
}

int main(void) {
    ivy_memory();
    ivy_time();
    ivy_wall();
    roots_time(BANYAN_ROOTS_FUSED);
    roots_time(BANYAN_ROOTS_TUBES);
    segments();
    return check_done("test_budget");
}
