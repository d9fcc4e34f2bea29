/* bench_keyaki: one mature tree with its mesh (all cores, and 1
 * thread); the 100-tree boulevard preset on 1 and 2 threads, mesh
 * included, each thread count in a forked
 * child whose peak resident set (wait4's ru_maxrss) is its memory peak,
 * against the targets (< 1.5 s on 2 threads, < 2 GB); 10,000 skeleton-only edaore
 * trees with Strahler statistics; and the Strahler means over 1,000 seeds
 * for the uniform and normal split distributions. Medians of several
 * runs; nothing is asserted. */
#define _DEFAULT_SOURCE /* wait4 */
#include "bench.h"

#include <math.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "banyan.h"
#include "test_files.h"


static int load(banyan_generator g, void *params, const char *name) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    size_t len;
    char *text = test_read_file(path, &len);
    banyan_error err;
    int ok = text && banyan_preset_apply(g, params, text, len, path, &err) == BANYAN_OK;
    if (!ok) fprintf(stderr, "cannot load %s: %s\n", path, text ? err.message : "unreadable");
    free(text);
    return ok;
}

typedef struct {
    double ms; /* median of 7 */
    uint32_t vertices, triangles, parts;
    int ok;
    char message[256];
} boulevard_result;

/* The boulevard 7 times on `threads` threads in a forked child (so its peak
 * resident set is the boulevard's alone, not this process's history): the
 * child sends its result down a pipe; *mb is the child's peak in MiB. */
static int boulevard(const banyan_avenue_params *ap, int threads, boulevard_result *out, double *mb) {
    int fd[2];
    if (pipe(fd)) return perror("pipe"), 1;
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0) return perror("fork"), 1;
    if (pid == 0) {
        boulevard_result b = {0};
        banyan_avenue_params q = *ap;
        q.threads = threads;
        double t[7];
        b.ok = 1;
        for (int r = 0; r < 7 && b.ok; r++) {
            banyan_mesh *m = NULL;
            banyan_error err;
            double t0 = bench_now();
            if (banyan_avenue_generate(&q, NULL, 0, &m, NULL, &err)) {
                b.ok = 0;
                snprintf(b.message, sizeof b.message, "%s", err.message);
                break;
            }
            t[r] = bench_now() - t0;
            b.vertices = m->vertex_count;
            b.triangles = m->index_count / 3;
            b.parts = m->part_count;
            banyan_mesh_free(m);
        }
        if (b.ok) b.ms = 1e3 * bench_median(t, 7);
        ssize_t n = write(fd[1], &b, sizeof b);
        _exit(n == (ssize_t)sizeof b ? 0 : 1);
    }
    close(fd[1]);
    ssize_t n = read(fd[0], out, sizeof *out);
    close(fd[0]);
    int status = 0;
    struct rusage u;
    if (wait4(pid, &status, 0, &u) < 0) return perror("wait4"), 1;
    if (n != (ssize_t)sizeof *out || !WIFEXITED(status) || WEXITSTATUS(status)) {
        fprintf(stderr, "boulevard (%d threads): the child failed (status %d)\n", threads, status);
        return 1;
    }
    if (!out->ok) {
        fprintf(stderr, "boulevard: %s\n", out->message);
        return 1;
    }
    *mb = u.ru_maxrss / 1024.0; /* kilobytes on Linux */
    return 0;
}

int main(void) {
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    if (!load(BANYAN_GEN_KEYAKI, &kp, "keyaki_mature")) return 1;
    /* threads 0 (the preset's default: all cores) and 1, alternating run
     * by run so load drifts hit both alike. */
    double tm[2][31];
    banyan_mesh *m = NULL;
    uint32_t nv = 0, nt = 0;
    for (int r = 0; r < 62; r++) {
        kp.threads = r & 1;
        double t0 = bench_now();
        banyan_keyaki_generate(&kp, &m, NULL, NULL, NULL);
        tm[r & 1][r / 2] = bench_now() - t0;
        nv = m ? m->vertex_count : 0;
        nt = m ? m->index_count / 3 : 0;
        banyan_mesh_free(m);
    }
    printf("mature tree (keyaki_mature): %.2f ms median of 31, %u vertices, %u triangles\n", 1e3 * bench_median(tm[0], 31),
           nv, nt);
    printf("mature tree, threads 1: %.2f ms median of 31\n", 1e3 * bench_median(tm[1], 31));

    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    if (!load(BANYAN_GEN_AVENUE, &ap, "avenue_boulevard")) return 1;
    double ms2 = 0, mb2 = 0;
    for (int threads = 1; threads <= 2; threads++) {
        boulevard_result b;
        double mb;
        if (boulevard(&ap, threads, &b, &mb)) return 1;
        printf("boulevard (avenue_boulevard, %d thread%s): %.1f ms median of 7, %.0f MB peak, %u vertices, "
               "%u triangles, %u parts\n",
               threads, threads > 1 ? "s" : "", b.ms, mb, b.vertices, b.triangles, b.parts);
        ms2 = b.ms;
        mb2 = mb;
    }
    printf("boulevard targets (2 threads): time %.1f ms < 1500 ms %s; peak %.0f MB < 2048 MB %s\n", ms2,
           ms2 < 1500 ? "PASS" : "MISS", mb2, mb2 < 2048 ? "PASS" : "MISS");

    /* 10,000 skeleton-only edaore trees with statistics. */
    double t[31];
    banyan_keyaki_params sp;
    banyan_keyaki_params_init(&sp);
    long long tips = 0, nodes = 0;
    int tmin = 1 << 30, tmax = 0;
    for (int r = 0; r < 5; r++) {
        double t0 = bench_now();
        tips = nodes = 0;
        for (int s = 0; s < 10000; s++) {
            banyan_keyaki_stats st;
            sp.seed = (uint64_t)s;
            banyan_keyaki_skeleton_stats(&sp, &st, NULL);
            tips += st.tip_count;
            nodes += st.node_count;
            if (st.tip_count < tmin) tmin = st.tip_count;
            if (st.tip_count > tmax) tmax = st.tip_count;
        }
        t[r] = bench_now() - t0;
    }
    printf("10,000 edaore skeletons + stats: %.1f ms median of 5 (%.1f us per tree); tips mean %.1f (min %d, max %d), "
           "branches mean %.1f\n",
           1e3 * bench_median(t, 5), 1e6 * bench_median(t, 5) / 10000, tips / 1e4, tmin, tmax, nodes / 1e4);

    /* Strahler over 1,000 seeds per distribution. */
    for (int d = 0; d < 2; d++) {
        banyan_keyaki_params q;
        banyan_keyaki_params_init(&q);
        q.distribution = d;
        double mean = 0, sum_r[BANYAN_KEYAKI_MAX_ORDER] = {0}, run = 0, tip = 0, brk = 0, K = 0;
        int cnt_r[BANYAN_KEYAKI_MAX_ORDER] = {0};
        for (int s = 0; s < 1000; s++) {
            banyan_keyaki_stats st;
            q.seed = (uint64_t)s;
            banyan_keyaki_skeleton_stats(&q, &st, NULL);
            mean += st.mean_bifurcation_ratio;
            run += st.mean_run_length;
            tip += st.tip_count;
            brk += st.break_count;
            K += st.max_order;
            for (int k = 0; k + 1 < st.max_order; k++) {
                sum_r[k] += st.bifurcation_ratio[k];
                cnt_r[k]++;
            }
        }
        printf("strahler, %s (1,000 seeds): mean bifurcation ratio %.3f; mean order %.2f; R_k means:",
               d ? "normal" : "uniform", mean / 1000, K / 1000);
        for (int k = 0; k < BANYAN_KEYAKI_MAX_ORDER && cnt_r[k]; k++)
            printf(" R%d %.3f (n=%d)", k + 1, sum_r[k] / cnt_r[k], cnt_r[k]);
        printf("; tips %.1f, breaks %.1f, run between forks %.2f levels (1/ln(alpha) = %.2f)\n", tip / 1000,
               brk / 1000, run / 1000, 1.0 / log(q.alpha));
    }
    return 0;
}
