/* Aerial roots (csrc/roots/aerial.c, docs/roots.md "Aerial roots") on
 * roots_mature_fig and roots_old_fig, seeds 1-3, and a few hostile
 * settings:
 *   - at least half of round(aerial_roots maturity) threads hang, and at
 *     least 10 on each fig (on a small host: what fits);
 *   - their diameters: p10 >= 3 mm and p90 <= 20 mm (reference/plants.md:
 *     hanging roots 3-20 mm);
 *   - each hangs: after it leaves its root no point rises;
 *   - every point above the soil keeps r from the hosts and the ground;
 *     some threads reach the soil, some end in the air;
 *   - on the mesh: root_kind 4 on every thread vertex, their first ring
 *     within 2 mm of the bark they leave (no gap that shows: 9 in 10 of
 *     them at least), a free tip
 *     softer in the wind than where the thread starts;
 *   - aerial_roots 0: none; aerial_roots 200 on a small host: no more
 *     than fit, the same bytes on a second run. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "hosts/closest.h"
#include "roots/roots_internal.h"
#include "test_files.h"

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Invariants of the net's threads; returns how many. */
static int net_threads(const char *name, const banyan_roots_params *p, const roots_net *net, int strict) {
    const roots_world *w = &net->w;
    roots_world soil = roots_soil_world(w);
    double d[1024];
    int n = 0, rooted = 0, free_ = 0, rising = 0, close = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind != ROOT_AERIAL) continue;
        const v3 *P = net->pts + pl->off;
        if (n < 1024) d[n] = 2.0 * net->rad[pl->off + 2];
        n++;
        if (pl->soil_from < pl->n) rooted++;
        else free_++;
        for (uint32_t i = 2; i < pl->n; i++) rising += P[i].z > P[i - 1].z + 1e-9;
        for (uint32_t i = 1; i < pl->soil_from; i++)
            close += world_clearance_in(w, P[i], 1, net->r, NULL, NULL) < net->r * (1 - 1e-6);
        for (uint32_t i = pl->soil_from; i < pl->n; i++)
            close += world_clearance_in(&soil, P[i], 0, net->r, NULL, NULL) < net->r * (1 - 1e-6);
        CHECK(pl->from != UINT32_MAX && v3_dist(P[0], net->pts[pl->from]) == 0, "%s: thread %u does not start on the net",
              name, t);
    }
    int want = (int)(p->aerial_roots * p->maturity + 0.5);
    qsort(d, (size_t)(n < 1024 ? n : 1024), sizeof(double), cmp_d);
    double p10 = n ? d[(size_t)(0.1 * (n - 1))] : 0, p90 = n ? d[(size_t)(0.9 * (n - 1))] : 0;
    printf("%-28s %3d threads (want %d): %d rooted, %d free; diameter p10 %.1f mm, p90 %.1f mm\n", name, n, want,
           rooted, free_, 1e3 * p10, 1e3 * p90);
    if (strict) CHECK(2 * n >= want, "%s: %d threads, want at least half of %d", name, n, want);
    CHECK(rising == 0, "%s: %d thread points rise", name, rising);
    CHECK(close == 0, "%s: %d thread points nearer than r to a host or the ground", name, close);
    if (n >= 10) {
        CHECK(p10 >= 0.003 && p90 <= 0.020, "%s: diameters p10 %.4f p90 %.4f m, want 3-20 mm", name, p10, p90);
        CHECK(rooted > 0 && free_ > 0, "%s: %d rooted, %d free threads, want both", name, rooted, free_);
    }
    return n;
}

/* The mesh's threads: kind, start on the bark, the wind. */
static void mesh_threads(const char *name, const banyan_mesh *m) {
    const float *kind = banyan_mesh_attribute(m, "root_kind"), *id = banyan_mesh_attribute(m, "root_id");
    const float *st = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_STIFFNESS);
    CHECK(kind && id && st, "%s: attributes missing", name);
    if (!kind || !id || !st) return;
    /* threads are swept one after the other, after the surface */
    uint32_t v = 0, threads = 0, gaps = 0, stiff_tips = 0, free_tips = 0;
    double worst = 0;
    while (v < m->vertex_count && kind[v] != 4.0f) v++;
    const uint32_t surface_v = v;
    while (v < m->vertex_count) {
        uint32_t a = v;
        while (v < m->vertex_count && id[v] == id[a]) v++;
        CHECK(kind[a] == 4.0f, "%s: vertex %u after the threads began has root_kind %g", name, a, kind[a]);
        threads++;
        /* ring 0 touches the bark: its nearest vertex within 2 mm of the
         * surface (leaving a slanting surface the ring leans on it) */
        double best = HUGE_VAL;
        for (uint32_t c = 0; c <= ROOTS_AERIAL_SIDES && a + c < v; c++) {
            const float *q = m->positions + 3 * (size_t)(a + c);
            v3 Q = v3_make(q[0], q[1], q[2]);
            for (uint32_t f = 0; f + 2 < m->index_count; f += 3) {
                const uint32_t *I = m->indices + f;
                if (I[0] >= surface_v) break;
                v3 X[3];
                for (int j = 0; j < 3; j++) {
                    const float *c = m->positions + 3 * (size_t)I[j];
                    X[j] = v3_make(c[0], c[1], c[2]);
                }
                int region;
                double d = v3_dist(Q, tri_closest(Q, X[0], X[1], X[2], &region));
                if (d < best) best = d;
            }
        }
        if (best > worst) worst = best;
        gaps += best > 0.002;
        /* the tip: the cap's centre, the last vertex */
        if (st[v - 1] < 1.0f) {
            free_tips++;
            stiff_tips += st[v - 1] >= st[a];
        }
    }
    printf("%-28s mesh: %u threads, %u start off the bark (farthest %.1f mm), %u of %u tips not softer than their start\n",
           name, threads, gaps, 1e3 * worst, stiff_tips, free_tips);
    CHECK(gaps * 10 <= threads, "%s: %u of %u threads start off the bark", name, gaps, threads);
    CHECK(stiff_tips == 0, "%s: %u free tips as stiff as their start", name, stiff_tips);
}

static void run(const char *name, const banyan_roots_params *p, const banyan_hosts *H, int min_threads) {
    roots_net net;
    banyan_error err;
    if (roots_net_build_hosts(p, H, &net, &err) != BANYAN_OK) {
        CHECK(0, "%s: %s", name, err.message);
        return;
    }
    int n = net_threads(name, p, &net, 1);
    CHECK(n >= min_threads, "%s: %d threads, want at least %d", name, n, min_threads);
    roots_net_free(&net);
    banyan_mesh *m = NULL;
    if (banyan_roots_generate(p, H, &m, NULL, NULL, &err) != BANYAN_OK) {
        CHECK(0, "%s: %s", name, err.message);
        return;
    }
    mesh_threads(name, m);
    banyan_mesh_free(m);
}

int main(void) {
    const char *figs[] = {"roots_mature_fig", "roots_old_fig"};
    for (int f = 0; f < 2; f++) {
        banyan_roots_params p;
        banyan_hosts *H = NULL;
        banyan_error err;
        char path[512];
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, figs[f]);
        if (test_load_roots(path, &p, &H, &err) != BANYAN_OK) {
            CHECK(0, "%s: %s", figs[f], err.message);
            continue;
        }
        for (uint64_t seed = 1; seed <= 3; seed++) {
            char name[64];
            snprintf(name, sizeof name, "%s seed %llu", figs[f], (unsigned long long)seed);
            p.seed = seed;
            run(name, &p, H, 10);
        }
        banyan_hosts_free(H);
    }

    /* None asked, none made; many asked on a small host: what fits. */
    banyan_box trunk = banyan_box_make(0, 0, 1.5, 0.25, 0.25, 1.5);
    banyan_hosts *H = NULL;
    banyan_error err;
    CHECK(banyan_hosts_create(&trunk, 1, NULL, 0, &H, &err) == BANYAN_OK, "trunk: %s", err.message);
    if (H) {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        p.aerial_roots = 0;
        roots_net net;
        if (roots_net_build_hosts(&p, H, &net, &err) == BANYAN_OK) {
            int n = 0;
            for (uint32_t t = 0; t < net.n_poly; t++) n += net.poly[t].kind == ROOT_AERIAL;
            CHECK(n == 0, "aerial_roots 0: %d threads", n);
            roots_net_free(&net);
        }
        p.aerial_roots = 200;
        p.maturity = 1;
        banyan_mesh *a = NULL, *b = NULL;
        CHECK(banyan_roots_generate(&p, H, &a, NULL, NULL, &err) == BANYAN_OK, "200 threads: %s", err.message);
        CHECK(banyan_roots_generate(&p, H, &b, NULL, NULL, &err) == BANYAN_OK, "200 threads: %s", err.message);
        if (a && b) {
            CHECK(a->vertex_count == b->vertex_count &&
                      !memcmp(a->positions, b->positions, sizeof(float) * 3 * (size_t)a->vertex_count),
                  "200 threads: two runs differ");
            mesh_threads("small trunk, 200 asked", a);
        }
        banyan_mesh_free(a);
        banyan_mesh_free(b);
        if (roots_net_build_hosts(&p, H, &net, &err) == BANYAN_OK) {
            net_threads("small trunk, 200 asked", &p, &net, 0);
            roots_net_free(&net);
        }
        banyan_hosts_free(H);
    }
    return check_done("test_roots_aerial");
}
