/* look_roots: roots_look_checks.h's figures of the roots presets, seeds
 * 1..N: the default net (default params on the CLI's trunk, 0.8 m x 0.8 m
 * x 8 m), roots_mature_fig, roots_old_fig, roots_column and roots_rock.
 * Prints a markdown table, one row per net: triangles, the .glb size
 * (writer defaults), the sleeve gap of host 0's bounding box (for a mesh
 * host its box, so only a rough figure), over the whole side and its lowest
 * 0.5 m, the foot reach beyond the footprint below 0.3 m (m and times the
 * footprint's smaller width), the self-intersecting triangle pairs, the
 * share of them 2-8 m up and the pairs within 0.5 mm (sheets nearly
 * touching; intersecting ones included). Exits 1 on a library error.
 *   look_roots [SEEDS] [key=value ...]   (default 5; key=value: --set on every net)
 *
 *   look_roots --accept [OUT_DIR]
 * is the acceptance test of the strangler-fig foot ("How we will know" of
 * the roots' foot work, docs/roots.md): over seeds 1-5, the sleeve gap in
 * the lowest 0.5 m <= 0.3 on roots_mature_fig and roots_old_fig and <= 0.5
 * on the default net; the foot reach >= 0.5 x the footprint's smaller
 * width on roots_mature_fig and roots_old_fig; the sprawl limit of
 * test_roots_look.c (95th percentile beyond the footprint <= 0.5 x its
 * diagonal) on all five; 0 intersecting triangle pairs on all five; the
 * default net's .glb <= 6 MB. It prints every bound that fails and exits
 * 1 when any does; ctest runs it as test_roots_foot.
 *
 *   look_roots --doc docs/roots.md
 * writes the foot's figures (seeds 1-5 of the five nets) into the page's
 * block between "<!-- figures: look_roots -->" and "<!-- end figures -->". */
#include <stdio.h>
#include <time.h>

#include "roots_look_checks.h"
#include "test_files.h"

static const char *out_dir = "/tmp"; /* where the .glb files are written to be sized */

typedef struct figures {
    uint32_t triangles;
    long long glb;
    rl_sleeve sleeve;
    rl_reach reach;
    double p95, diag;
    int64_t pairs, mid, close;
    double gen_s, pairs_s;
} figures;

/* The figures of one net: 0, or 1 on a library error. */
static int measure(const char *label, const banyan_roots_params *p, const banyan_hosts *H, figures *f) {
    banyan_error err = {0, ""};
    banyan_mesh *m = NULL;
    memset(f, 0, sizeof *f);
    clock_t t0 = clock();
    if (banyan_roots_generate(p, H, &m, NULL, NULL, &err)) {
        fprintf(stderr, "%s seed %llu: %s\n", label, (unsigned long long)p->seed, err.message);
        return 1;
    }
    f->gen_s = (double)(clock() - t0) / CLOCKS_PER_SEC;
    f->triangles = m->index_count / 3;
    banyan_host_info hi;
    double flo[2] = {1e300, 1e300}, fhi[2] = {-1e300, -1e300}, blo[3] = {0}, bhi[3] = {0};
    for (uint32_t h = 0; h < banyan_hosts_count(H); h++) {
        banyan_hosts_info(H, h, &hi, &err);
        if (h == 0) memcpy(blo, hi.lo, sizeof blo), memcpy(bhi, hi.hi, sizeof bhi);
        for (int k = 0; k < 2; k++) {
            if (hi.lo[k] < flo[k]) flo[k] = hi.lo[k];
            if (hi.hi[k] > fhi[k]) fhi[k] = hi.hi[k];
        }
    }
    double ground = p->ground ? p->ground_z : blo[2];
    rl_grid g;
    if (rl_grid_build(m, 0.05, 0.0, &g) == 0) {
        rl_sleeve_gap(m, &g, blo, bhi, ground, &f->sleeve);
        rl_grid_free(&g);
    }
    rl_foot_reach(m, flo, fhi, ground, &f->reach);
    f->p95 = rl_sprawl_p95(m, flo, fhi, ground, &f->diag);
    enum { CAP = 1 << 16 };
    static double z[CAP];
    clock_t t1 = clock();
    f->pairs = rl_self_intersections(m, z, CAP);
    f->pairs_s = (double)(clock() - t1) / CLOCKS_PER_SEC;
    f->close = rl_close_pairs(m, 5e-4, NULL, 0);
    for (int64_t i = 0; i < f->pairs && i < CAP; i++) f->mid += z[i] >= ground + 2 && z[i] <= ground + 8;
    f->glb = rl_glb_size(m, out_dir, NULL, &err);
    banyan_mesh_free(m);
    return 0;
}

static int row(const char *label, const banyan_roots_params *p, const banyan_hosts *H) {
    figures f;
    if (measure(label, p, H, &f)) return 1;
    printf("| %s | %llu | %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %lld | %.0f %% | %lld | %.1f s | %.1f s |\n",
           label, (unsigned long long)p->seed, f.triangles, f.glb / 1e6, f.sleeve.gap, f.sleeve.gap_foot,
           f.reach.reach, f.reach.fraction, f.diag > 0 ? f.p95 / f.diag : 0, (long long)f.pairs,
           f.pairs ? 100.0 * f.mid / (f.pairs < (1 << 16) ? f.pairs : (1 << 16)) : 0.0, (long long)f.close, f.gen_s,
           f.pairs_s);
    fflush(stdout);
    return 0;
}

/* The params and hosts of a net: "default" or a preset's name. 0 on success. */
static int load(const char *name, banyan_roots_params *p, banyan_hosts **H) {
    banyan_roots_params_init(p);
    banyan_error err;
    *H = NULL;
    if (!strcmp(name, "default")) {
        banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        if (banyan_hosts_create(&trunk, 1, NULL, 0, H, &err) == BANYAN_OK) return 0;
    } else {
        char path[4096];
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
        if (!test_load_roots(path, p, H, &err)) return 0;
    }
    fprintf(stderr, "%s: %s\n", name, err.message);
    return 1;
}

static const char *const NAMES[5] = {"default", "roots_mature_fig", "roots_old_fig", "roots_column", "roots_rock"};

static int accept(void) {
    int failed = 0, errors = 0;
    for (int k = 0; k < 5; k++) {
        banyan_roots_params p;
        banyan_hosts *H;
        if (load(NAMES[k], &p, &H)) return 1;
        int fig = k == 1 || k == 2;
        double gap_max = fig ? 0.3 : 0.5;
        for (uint64_t seed = 1; seed <= 5; seed++) {
            p.seed = seed;
            figures f;
            if (measure(NAMES[k], &p, H, &f)) {
                errors++;
                continue;
            }
            const char *n = NAMES[k];
            unsigned long long s = (unsigned long long)seed;
            if ((k <= 2) && f.sleeve.gap_foot > gap_max)
                failed++, printf("FAIL %s seed %llu: sleeve gap in the lowest 0.5 m %.2f, want <= %.1f\n", n, s,
                                 f.sleeve.gap_foot, gap_max);
            if (fig && f.reach.fraction < 0.5)
                failed++, printf("FAIL %s seed %llu: foot reach %.2f m = %.2f x the smaller width, want >= 0.5\n", n,
                                 s, f.reach.reach, f.reach.fraction);
            if (f.p95 > 0.5 * f.diag)
                failed++, printf("FAIL %s seed %llu: 95th percentile beyond the footprint %.2f m, want <= %.2f\n", n,
                                 s, f.p95, 0.5 * f.diag);
            if (f.pairs != 0)
                failed++, printf("FAIL %s seed %llu: %lld intersecting triangle pairs, want 0\n", n, s,
                                 (long long)f.pairs);
            if (k == 0 && !(f.glb > 0 && f.glb <= 6000000))
                failed++, printf("FAIL default seed %llu: .glb %lld bytes, want <= 6 MB\n", s, f.glb);
        }
        banyan_hosts_free(H);
    }
    printf("%s: %d bounds failed\n", failed || errors ? "NOT ACCEPTED" : "ACCEPTED", failed);
    return failed || errors;
}

/* The figures block of docs/roots.md (see the header). */
static int doc(const char *path) {
    static const char open_tag[] = "<!-- figures: look_roots -->", close_tag[] = "<!-- end figures -->";
    size_t len = 0;
    char *page = test_read_file(path, &len);
    char *a = page ? strstr(page, open_tag) : NULL, *b = a ? strstr(a, close_tag) : NULL;
    if (!b) return fprintf(stderr, "%s: no %s ... %s block\n", path, open_tag, close_tag), 1;
    size_t cap = 1 << 16, n = 0;
    char *t = malloc(cap);
    if (!t) return 1;
    n += (size_t)snprintf(t + n, cap - n,
                          "%s\n<!-- written by `build/tests/look_roots --doc docs/roots.md`, do not edit -->\n\n"
                          "| net | seed | .glb MB | sleeve gap | gap lowest 0.5 m | foot reach / width | "
                          "p95 beyond footprint / diagonal | intersecting pairs |\n|---|---|---|---|---|---|---|---|\n",
                          open_tag);
    for (int k = 0; k < 5; k++) {
        banyan_roots_params p;
        banyan_hosts *H;
        if (load(NAMES[k], &p, &H)) return free(t), 1;
        for (uint64_t seed = 1; seed <= 5; seed++) {
            figures f;
            p.seed = seed;
            if (measure(NAMES[k], &p, H, &f)) return free(t), banyan_hosts_free(H), 1;
            n += (size_t)snprintf(t + n, cap - n, "| %s%s%s | %llu | %.2f | %.2f | %.2f | %.2f | %.3f | %lld |\n",
                                  k ? "`" : "", NAMES[k], k ? "`" : "", (unsigned long long)seed, f.glb / 1e6,
                                  f.sleeve.gap, f.sleeve.gap_foot, f.reach.fraction, f.diag > 0 ? f.p95 / f.diag : 0,
                                  (long long)f.pairs);
        }
        banyan_hosts_free(H);
    }
    FILE *o = fopen(path, "wb");
    int rc = !o || fwrite(page, 1, (size_t)(a - page), o) != (size_t)(a - page) || fwrite(t, 1, n, o) != n ||
             fputs("\n", o) < 0 || fputs(b, o) < 0;
    if (o && fclose(o)) rc = 1;
    free(t);
    free(page);
    return rc;
}

int main(int argc, char **argv) {
    if (argc > 2 && !strcmp(argv[1], "--doc")) return doc(argv[2]);
    if (argc > 1 && !strcmp(argv[1], "--accept")) {
        if (argc > 2) out_dir = argv[2];
        return accept();
    }
    int seeds = argc > 1 ? atoi(argv[1]) : 5, rc = 0;
    printf("| preset | seed | triangles | .glb MB | sleeve gap | gap lowest 0.5 m | foot reach m | reach / width | "
           "p95 beyond footprint / diagonal | self-intersecting pairs | of them 2-8 m up | pairs within 0.5 mm | "
           "generate | pairs search |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < 5 && !rc; k++) {
        banyan_roots_params p;
        banyan_hosts *H;
        if (load(NAMES[k], &p, &H)) return 1;
        rc |= test_param_overrides(BANYAN_GEN_ROOTS, &p, 2, argc, argv);
        for (int s = 1; s <= seeds && !rc; s++) {
            p.seed = (uint64_t)s;
            rc |= row(NAMES[k], &p, H);
        }
        banyan_hosts_free(H);
    }
    return rc;
}
