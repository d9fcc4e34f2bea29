/* bench_keyaki: one mature tree with its mesh; the 100-tree boulevard
 * preset on 1 and 2 threads, mesh included; 10,000 skeleton-only edaore
 * trees with Strahler statistics; and the Strahler means over 1,000 seeds
 * for the uniform and normal split distributions. Medians of several
 * runs; nothing is asserted. */
#include "bench.h"

#include <math.h>

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

int main(void) {
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    if (!load(BANYAN_GEN_KEYAKI, &kp, "keyaki_mature")) return 1;
    double t[31];
    banyan_mesh *m = NULL;
    for (int r = 0; r < 31; r++) {
        double t0 = bench_now();
        banyan_keyaki_generate(&kp, &m, NULL);
        t[r] = bench_now() - t0;
        if (r < 30) banyan_mesh_free(m);
    }
    printf("mature tree (keyaki_mature): %.2f ms median of 31, %u vertices, %u triangles\n", 1e3 * bench_median(t, 31),
           m ? m->vertex_count : 0, m ? m->index_count / 3 : 0);
    banyan_mesh_free(m);

    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    if (!load(BANYAN_GEN_AVENUE, &ap, "avenue_boulevard")) return 1;
    for (int threads = 1; threads <= 2; threads++) {
        for (int r = 0; r < 7; r++) {
            double t0 = bench_now();
            banyan_error err;
            if (banyan_avenue_generate(&ap, NULL, 0, threads, &m, NULL, &err)) {
                fprintf(stderr, "boulevard: %s\n", err.message);
                return 1;
            }
            t[r] = bench_now() - t0;
            if (r < 6) banyan_mesh_free(m);
        }
        printf("boulevard (avenue_boulevard, %d thread%s): %.1f ms median of 7, %u vertices, %u triangles, %u parts\n",
               threads, threads > 1 ? "s" : "", 1e3 * bench_median(t, 7), m->vertex_count, m->index_count / 3,
               m->part_count);
        banyan_mesh_free(m);
    }

    /* 10,000 skeleton-only edaore trees with statistics. */
    banyan_keyaki_params sp;
    banyan_keyaki_params_init(&sp);
    long long tips = 0, nodes = 0;
    int tmin = 1 << 30, tmax = 0;
    for (int r = 0; r < 5; r++) {
        double t0 = bench_now();
        tips = nodes = 0;
        for (int s = 0; s < 10000; s++) {
            banyan_keyaki_statistics st;
            sp.seed = (uint64_t)s;
            banyan_keyaki_stats(&sp, &st, NULL);
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
            banyan_keyaki_statistics st;
            q.seed = (uint64_t)s;
            banyan_keyaki_stats(&q, &st, NULL);
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
