/* test_threads.c - concurrent calls give the sequential results.
 * Every generator, the preset reader and the tube run first one after
 * another, then from several threads at once on different
 * params, each thread in its own order and several rounds; every mesh
 * hash (banyan_mesh_hash) must equal the sequential one. The avenue runs
 * its own worker threads inside these. Built under ThreadSanitizer too
 * (BANYAN_TSAN, tools/test.sh), where a data race fails the run. Roots
 * and ivy on meshes share one host set between all the threads; one
 * ivy meshes on two threads of its own inside them. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "host_meshes.h"
#include "test_files.h"
#include "test_hosts.h"

#define THREADS 4
#define ROUNDS 2

typedef struct job {
    const char *name;
    uint64_t (*run)(int variant); /* the mesh hash, 0 on failure */
    int variant;
} job;

/* The hash of *m, freed; m is passed by address because the call that
 * fills it is evaluated in the same argument list. */
static uint64_t finish(banyan_status s, banyan_mesh **m, const banyan_error *e, const char *what) {
    if (s != BANYAN_OK) {
        fprintf(stderr, "%s: %s\n", what, e->message);
        return 0;
    }
    uint64_t h = banyan_mesh_hash(*m);
    banyan_mesh_free(*m);
    return h;
}

static uint64_t run_roots(int v) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.seed = 11 + (uint64_t)v;
    p.growth_points = 16;
    p.main_roots = 4 + v;
    banyan_box h = banyan_box_make(0, 0, 1, 0.3 + 0.1 * v, 0.3, 1);
    banyan_mesh *m = NULL;
    banyan_error e;
    return finish(test_roots_boxes(&p, &h, 1, &m, &e), &m, &e, "roots");
}

static uint64_t run_keyaki(int v) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.seed = 5 + (uint64_t)v;
    p.levels = 10 + v;
    p.model = v % 4;
    banyan_mesh *m = NULL;
    banyan_error e;
    return finish(banyan_keyaki_generate(&p, &m, NULL, NULL, &e), &m, &e, "keyaki");
}

static uint64_t run_avenue(int v) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    p.seed = 100 + (uint64_t)v;
    p.placement = BANYAN_AVENUE_COUNT;
    p.count = 3;
    p.tree.levels = 9;
    banyan_mesh *m = NULL;
    banyan_error e;
    p.threads = 1 + v;
    return finish(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &e), &m, &e, "avenue");
}

static uint64_t run_ivy(int v) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.seed = 3 + (uint64_t)v;
    p.steps = 40 + 10 * v;
    if (v == 2) { /* large enough (4.7k buds) that the mesh runs on threads of its own */
        p.steps = 160;
        p.threads = 2;
    }
    banyan_box h = banyan_box_make(0, 0.1, 1.5, 1.5, 0.1, 1.5);
    banyan_mesh *m = NULL;
    banyan_error e;
    return finish(test_ivy_boxes(&p, &h, 1, &m, &e), &m, &e, "ivy");
}

/* One host set (a sphere and a column) shared by every thread. */
static banyan_hosts *shared_hosts;

static uint64_t run_roots_mesh(int v) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.seed = 31 + (uint64_t)v;
    p.growth_points = 14;
    banyan_mesh *m = NULL;
    banyan_error e;
    return finish(banyan_roots_generate(&p, shared_hosts, &m, NULL, NULL, &e), &m, &e, "roots on meshes");
}

static uint64_t run_ivy_mesh(int v) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.seed = 41 + (uint64_t)v;
    p.steps = 50;
    p.start[0] = 0, p.start[1] = -0.45, p.start[2] = 0.1;
    banyan_mesh *m = NULL;
    banyan_error e;
    return finish(banyan_ivy_generate(&p, shared_hosts, &m, NULL, NULL, &e), &m, &e, "ivy on meshes");
}

static uint64_t run_segments(int v) {
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    p.seed = 21 + (uint64_t)v;
    p.demo_segments = 8 + 4 * v;
    banyan_segment_input segs[64];
    double trunk[6];
    uint32_t n = 0;
    banyan_error e;
    if (banyan_segments_demo(&p, segs, 64, &n, trunk, &e))
        return finish((banyan_status)e.code, NULL, &e, "segments demo");
    banyan_mesh *m = NULL;
    return finish(banyan_segments_generate(&p, segs, n, trunk, &m, NULL, NULL, &e), &m, &e, "segments");
}

/* A preset read into params, then a tube whose radius comes from them:
 * the JSON reader's answer shows in the hash. */
static uint64_t run_preset(int v) {
    static const char *const names[] = {"roots_trunk", "roots_paper", "roots_boulder"};
    char path[4096];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, names[v % 3]);
    size_t len = 0;
    char *text = test_read_file(path, &len);
    if (!text) return 0;
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_error e;
    banyan_box hosts[8];
    uint32_t n = 0;
    banyan_status s = banyan_preset_apply(BANYAN_GEN_ROOTS, &p, text, len, path, &e);
    if (!s) s = banyan_preset_hosts(text, len, path, hosts, 8, &n, &e);
    free(text);
    if (s) return finish(s, NULL, &e, "preset");
    double pts[9] = {0, 0, 0, 0, 0, 1, hosts[0].half[0], 0, 2}, radii[3];
    for (int i = 0; i < 3; i++) radii[i] = p.radius * p.unit;
    banyan_mesh *m = NULL;
    return finish(banyan_tube_generate(pts, radii, 3, p.sides, 1, &m, &e), &m, &e, "tube");
}

static job jobs[] = {
    {"roots", run_roots, 0},       {"roots", run_roots, 1},       {"keyaki", run_keyaki, 0},
    {"keyaki", run_keyaki, 1},     {"keyaki", run_keyaki, 2},     {"avenue", run_avenue, 0},
    {"avenue", run_avenue, 1},     {"ivy", run_ivy, 0},           {"ivy", run_ivy, 1},
    {"ivy", run_ivy, 2},
    {"segments", run_segments, 0}, {"segments", run_segments, 1}, {"preset", run_preset, 0},
    {"preset", run_preset, 1},     {"preset", run_preset, 2},     {"roots_mesh", run_roots_mesh, 0},
    {"roots_mesh", run_roots_mesh, 1}, {"ivy_mesh", run_ivy_mesh, 0}, {"ivy_mesh", run_ivy_mesh, 1},
};
#define N_JOBS (sizeof jobs / sizeof jobs[0])

typedef struct worker_arg {
    int index;
    uint64_t hash[ROUNDS][N_JOBS];
} worker_arg;

static void *worker(void *p) {
    worker_arg *a = p;
    for (int r = 0; r < ROUNDS; r++)
        for (size_t k = 0; k < N_JOBS; k++) {
            /* Each thread starts at another job and walks the other way
             * every other thread, so different generators overlap. */
            size_t j = (a->index % 2 ? N_JOBS - 1 - k : k);
            j = (j + (size_t)a->index * 3 + (size_t)r) % N_JOBS;
            a->hash[r][j] = jobs[j].run(jobs[j].variant);
        }
    return NULL;
}

int main(void) {
    tm_mesh column = {0}, sphere = {0};
    tm_cylinder(&column, 0, 0, 0, 0.4, 2.0, 32, 4);
    tm_uv_sphere(&sphere, 1.5, 0, 0.5, 0.5, 24, 12);
    banyan_host_mesh hm[2] = {tm_host(&column, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO),
                              tm_host(&sphere, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO)};
    CHECK(banyan_hosts_create(NULL, 0, hm, 2, &shared_hosts, NULL) == BANYAN_OK, "the shared host set");
    uint64_t want[N_JOBS];
    for (size_t j = 0; j < N_JOBS; j++) {
        want[j] = jobs[j].run(jobs[j].variant);
        CHECK(want[j] != 0, "%s %d runs", jobs[j].name, jobs[j].variant);
    }
    /* Different params give different meshes (else equal hashes say little). */
    for (size_t j = 1; j < N_JOBS; j++)
        if (strcmp(jobs[j].name, jobs[j - 1].name) == 0)
            CHECK(want[j] != want[j - 1], "%s variants %d and %d differ", jobs[j].name, jobs[j - 1].variant,
                  jobs[j].variant);

    static worker_arg args[THREADS];
    pthread_t tid[THREADS];
    for (int t = 0; t < THREADS; t++) {
        args[t].index = t;
        CHECK(pthread_create(&tid[t], NULL, worker, &args[t]) == 0, "thread %d starts", t);
    }
    for (int t = 0; t < THREADS; t++) pthread_join(tid[t], NULL);
    int same = 0;
    for (int t = 0; t < THREADS; t++)
        for (int r = 0; r < ROUNDS; r++)
            for (size_t j = 0; j < N_JOBS; j++) {
                CHECK(args[t].hash[r][j] == want[j], "thread %d round %d: %s %d hash %016llx, sequential %016llx", t,
                      r, jobs[j].name, jobs[j].variant, (unsigned long long)args[t].hash[r][j],
                      (unsigned long long)want[j]);
                same += args[t].hash[r][j] == want[j];
            }
    printf("%d concurrent results of %zu jobs on %d threads x %d rounds equal the sequential ones\n", same, N_JOBS,
           THREADS, ROUNDS);
    banyan_hosts_free(shared_hosts);
    tm_free(&column);
    tm_free(&sphere);
    return check_done("test_threads");
}
