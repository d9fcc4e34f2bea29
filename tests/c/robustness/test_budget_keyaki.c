/* The run budget of keyaki and avenue (docs/keyaki.md
 * "Budget"):
 *   - a tree and an avenue under max_seconds = 2 on inputs that take
 *     longer stop within 2.5 s (CHECK_SLACK looser under sanitizers) with BANYAN_E_LIMIT naming max_seconds,
 *     *out NULL; a small max_memory_mb stops them naming max_memory_mb;
 *   - a tree past max_vertices is refused while its skeleton grows: its
 *     peak resident set stays far below the 2.2 GB a whole skeleton of
 *     max_nodes = 2^24 takes;
 *   - an avenue's peak resident set on 8 threads is within 1.2x of 1
 *     thread, refused (every tree grows part way) and built alike; the
 *     bytes are the same on 1, 3 and 8 threads;
 *   - threads past BANYAN_AVENUE_MAX_THREADS are refused naming threads.
 * Each peak is measured in a child process (ru_maxrss of that child only):
 * this program run again as `test_budget_keyaki --child CASE THREADS FD`
 * (posix_spawn, not a bare fork: ThreadSanitizer cannot start threads in a
 * forked child), which sends its result back through the pipe FD. */
#define _DEFAULT_SOURCE /* wait4 */
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "banyan.h"
#include "check.h"

static double now(void) {
    struct timespec t;
    timespec_get(&t, TIME_UTC);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* A tree that takes 35 s and 2.9 GB unbounded (35 M vertices). */
static void big_tree(banyan_keyaki_params *p) {
    banyan_keyaki_params_init(p);
    p->levels = 30;
    p->limbs = 12;
    p->alpha = 1.45;
    p->max_nodes = 16000000;
    p->max_vertices = 1 << 30;
}

/* Every tree's skeleton never breaks and passes max_vertices (32 M over
 * the avenue) long before max_nodes = 2^24: refused while growing. */
static void refused_avenue(banyan_avenue_params *a) {
    banyan_avenue_params_init(a);
    a->tree.levels = 30;
    a->tree.alpha = 10;
    a->tree.max_nodes = 1 << 24;
    a->max_vertices = 8000000;
}

typedef struct run_result {
    int32_t status;
    uint32_t vertices;
    uint64_t hash;
    char message[256];
} run_result;

static uint64_t hash_mesh(const banyan_mesh *m) {
    uint64_t h = 1469598103934665603ull;
    const unsigned char *b = (const unsigned char *)m->positions;
    for (size_t i = 0; i < sizeof(float) * 3 * (size_t)m->vertex_count; i++) h = (h ^ b[i]) * 1099511628211ull;
    b = (const unsigned char *)m->indices;
    for (size_t i = 0; i < sizeof(uint32_t) * (size_t)m->index_count; i++) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

/* The cases the children run. */
static void child_case(const char *name, banyan_avenue_params *a, banyan_keyaki_params *k) {
    if (!strcmp(name, "refused_tree")) { /* a single tree past max_vertices: refused while its skeleton grows */
        banyan_keyaki_params_init(k);
        k->levels = 30, k->alpha = 10, k->max_nodes = 1 << 24;
    } else if (!strcmp(name, "refused_avenue")) {
        refused_avenue(a);
    } else { /* default_avenue: 16 trees */
        banyan_avenue_params_init(a);
    }
}

/* In the child: grows `name` on `threads` and writes a run_result to fd. */
static int run_child(const char *name, int threads, int fd) {
    banyan_avenue_params a;
    banyan_keyaki_params k;
    child_case(name, &a, &k);
    run_result r;
    memset(&r, 0, sizeof r);
    banyan_mesh *m = NULL;
    banyan_error e = {0, ""};
    int tree = !strcmp(name, "refused_tree");
    a.threads = threads;
    r.status = tree ? banyan_keyaki_generate(&k, &m, NULL, NULL, &e) : banyan_avenue_generate(&a, NULL, 0, &m, NULL, &e);
    if (m) {
        r.vertices = m->vertex_count;
        r.hash = hash_mesh(m);
    }
    memcpy(r.message, e.message, sizeof r.message);
    banyan_mesh_free(m);
    return write(fd, &r, sizeof r) == (ssize_t)sizeof r ? 0 : 1;
}

extern char **environ;

/* A sanitizer's shadow memory (and ASan's quarantine of freed blocks)
 * counts in the resident set: the absolute peak bound is that much looser
 * under one (the ratios are not). */
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
#define RSS_SCALE 3.0
#else
#define RSS_SCALE 1.0
#endif
/* ASan's allocator keeps per-thread caches and a quarantine: 8 threads
 * hold more freed memory than 1 there. Still far below the 8x of eight
 * trees in flight at once, which is what the ratio catches. */
#if defined(__SANITIZE_ADDRESS__)
#define THREADS_RSS_RATIO 1.5
#else
#define THREADS_RSS_RATIO 1.2
#endif

/* Runs case `name` on `threads` in a child; returns the child's peak
 * resident set in MB (-1 when the child failed). */
static double in_child(const char *name, int threads, run_result *out) {
    int fd[2];
    if (pipe(fd)) return -1;
    char ts[16], fs[16];
    snprintf(ts, sizeof ts, "%d", threads);
    snprintf(fs, sizeof fs, "%d", fd[1]);
    char *argv[] = {"test_budget_keyaki", "--child", (char *)name, ts, fs, NULL};
    pid_t pid;
    int err = posix_spawn(&pid, "/proc/self/exe", NULL, NULL, argv, environ);
    close(fd[1]);
    if (err) {
        close(fd[0]);
        return -1;
    }
    ssize_t got = read(fd[0], out, sizeof *out);
    close(fd[0]);
    int st = 0;
    struct rusage ru;
    if (wait4(pid, &st, 0, &ru) != pid || !WIFEXITED(st) || WEXITSTATUS(st) || got != (ssize_t)sizeof *out) return -1;
    return ru.ru_maxrss / 1024.0;
}

static void memory_of_threads(void) {
    run_result r1, r8;
    double mb = in_child("refused_tree", 1, &r1);
    printf("refused tree (levels 30, alpha 10, max_nodes 2^24): %.0f MB peak: %s\n", mb, r1.message);
    CHECK(mb > 0 && r1.status == BANYAN_E_LIMIT && strstr(r1.message, "max_vertices"), "refused tree: %d %s",
          r1.status, r1.message);
    CHECK(mb > 0 && mb < 400 * RSS_SCALE, "the refused tree peaked at %.0f MB (a whole skeleton: 2200 MB)", mb);

    /* The refused avenue: every thread's tree grows part way. */
    double m1 = in_child("refused_avenue", 1, &r1), m8 = in_child("refused_avenue", 8, &r8);
    printf("refused avenue: %.0f MB peak on 1 thread, %.0f MB on 8 (%.2fx): %s\n", m1, m8, m8 / m1, r8.message);
    CHECK(m1 > 0 && m8 > 0 && r1.status == BANYAN_E_LIMIT && r8.status == BANYAN_E_LIMIT,
          "refused avenue: %d / %d: %s", r1.status, r8.status, r8.message);
    CHECK(m1 > 0 && m8 <= THREADS_RSS_RATIO * m1, "refused avenue: %.0f MB on 8 threads, %.0f MB on 1", m8, m1);

    /* A built avenue (the default: 16 trees). */
    run_result r3;
    m1 = in_child("default_avenue", 1, &r1);
    m8 = in_child("default_avenue", 8, &r8);
    double m3 = in_child("default_avenue", 3, &r3);
    printf("default avenue: %.0f MB peak on 1 thread, %.0f MB on 8 (%.2fx), %u vertices\n", m1, m8, m8 / m1,
           r8.vertices);
    CHECK(m1 > 0 && m8 > 0 && m3 > 0 && !r1.status && !r8.status && !r3.status, "default avenue: %d / %d / %d",
          r1.status, r8.status, r3.status);
    CHECK(m1 > 0 && m8 <= THREADS_RSS_RATIO * m1, "default avenue: %.0f MB on 8 threads, %.0f MB on 1", m8, m1);
    CHECK(r1.vertices > 0 && r1.hash == r8.hash && r1.hash == r3.hash && r1.vertices == r8.vertices,
          "the avenue differs between 1, 3 and 8 threads");
}

/* A status that stops the run for its budget: LIMIT naming `field`,
 * within `seconds`. */
static void check_stop(const char *what, banyan_status s, const banyan_mesh *m, const banyan_error *e,
                       const char *field, double took, double seconds) {
    printf("%s: %.2f s: %s\n", what, took, e->message);
    CHECK(s == BANYAN_E_LIMIT && e->code == BANYAN_E_LIMIT, "%s: status %d: %s", what, s, e->message);
    CHECK(strstr(e->message, field) != NULL, "%s: the message does not name %s: %s", what, field, e->message);
    CHECK(m == NULL, "%s: *out set after a stop", what);
    CHECK(took < seconds, "%s: stopped after %.2f s, allowed %.2f s", what, took, seconds);
}

static void time_and_memory_budgets(void) {
    banyan_mesh *m = NULL;
    banyan_error e;
    banyan_keyaki_params k;
    big_tree(&k);
    k.max_seconds = 2;
    double t = now();
    banyan_status s = banyan_keyaki_generate(&k, &m, NULL, NULL, &e);
    check_stop("tree, max_seconds 2", s, m, &e, "max_seconds", now() - t, 2 + 0.5 * CHECK_SLACK);
    banyan_mesh_free(m);

    big_tree(&k);
    k.max_memory_mb = 64;
    m = NULL;
    s = banyan_keyaki_generate(&k, &m, NULL, NULL, &e);
    check_stop("tree, max_memory_mb 64", s, m, &e, "max_memory_mb", 0, 1);
    banyan_mesh_free(m);

    /* The statistics keep the same budget. */
    banyan_keyaki_stats st;
    k.levels = 30, k.alpha = 10, k.max_nodes = 1 << 24, k.max_memory_mb = 64;
    s = banyan_keyaki_skeleton_stats(&k, &st, &e);
    check_stop("statistics, max_memory_mb 64", s, NULL, &e, "max_memory_mb", 0, 1);

    /* An avenue of 16 trees of 30 levels, on 2 and 8 threads: every
     * thread's tree stops, not only the caller's. */
    banyan_avenue_params a;
    for (int threads = 2; threads <= 8; threads += 6) {
        banyan_avenue_params_init(&a);
        a.tree.levels = 30;
        a.tree.limbs = 12;
        a.max_vertices = 1 << 30;
        a.max_seconds = 2;
        m = NULL;
        t = now();
        a.threads = threads;
        s = banyan_avenue_generate(&a, NULL, 0, &m, NULL, &e);
        check_stop(threads == 2 ? "avenue, max_seconds 2, 2 threads" : "avenue, max_seconds 2, 8 threads", s, m, &e,
                   "max_seconds", now() - t, 2 + 0.5 * CHECK_SLACK);
        banyan_mesh_free(m);
    }
    banyan_avenue_params_init(&a);
    a.max_memory_mb = 32;
    m = NULL;
    a.threads = 2;
    s = banyan_avenue_generate(&a, NULL, 0, &m, NULL, &e);
    check_stop("avenue, max_memory_mb 32", s, m, &e, "max_memory_mb", 0, 1);
    banyan_mesh_free(m);
}

static void thread_cap(void) {
    banyan_avenue_params a;
    banyan_avenue_params_init(&a);
    a.count = 1, a.rows = 1, a.placement = BANYAN_AVENUE_COUNT, a.tree.levels = 6;
    banyan_mesh *m = NULL;
    banyan_error e;
    a.threads = BANYAN_AVENUE_MAX_THREADS + 1;
    banyan_status s = banyan_avenue_generate(&a, NULL, 0, &m, NULL, &e);
    CHECK(s == BANYAN_E_RANGE && strstr(e.message, "threads") && strstr(e.message, "64"), "threads 65: %d %s", s,
          e.message);
    a.threads = BANYAN_AVENUE_MAX_THREADS;
    s = banyan_avenue_generate(&a, NULL, 0, &m, NULL, &e);
    CHECK(s == BANYAN_OK && m, "threads 64: %d %s", s, e.message);
    banyan_mesh_free(m);
    /* The budget's own ranges. */
    a.max_seconds = 0;
    m = NULL;
    a.threads = 1;
    s = banyan_avenue_generate(&a, NULL, 0, &m, NULL, &e);
    CHECK(s == BANYAN_E_RANGE && strstr(e.message, "max_seconds"), "avenue max_seconds 0: %d %s", s, e.message);
    banyan_keyaki_params k;
    banyan_keyaki_params_init(&k);
    k.max_memory_mb = 1;
    s = banyan_keyaki_generate(&k, &m, NULL, NULL, &e);
    CHECK(s == BANYAN_E_RANGE && strstr(e.message, "max_memory_mb"), "keyaki max_memory_mb 1: %d %s", s, e.message);
}

int main(int argc, char **argv) {
    if (argc == 5 && !strcmp(argv[1], "--child")) return run_child(argv[2], atoi(argv[3]), atoi(argv[4]));
    memory_of_threads();
    time_and_memory_budgets();
    thread_cap();
    return check_done("test_budget_keyaki");
}
