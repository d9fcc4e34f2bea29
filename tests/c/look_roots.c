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
 *   look_roots [SEEDS] [key=value ...]   (default 5; key=value: --set on every net) */
#include <stdio.h>
#include <time.h>


#include "roots_look_checks.h"
#include "test_files.h"

static int overrides(banyan_roots_params *p, int argc, char **argv) {
    for (int i = 2; i < argc; i++) {
        char key[256];
        const char *eq = strchr(argv[i], '=');
        if (!eq || eq - argv[i] >= (long)sizeof key) return fprintf(stderr, "bad override %s\n", argv[i]), 1;
        memcpy(key, argv[i], (size_t)(eq - argv[i]));
        key[eq - argv[i]] = 0;
        banyan_error err;
        if (banyan_param_set_text(BANYAN_GEN_ROOTS, p, key, eq + 1, &err)) {
            fprintf(stderr, "%s: %s\n", argv[i], err.message);
            return 1;
        }
    }
    return 0;
}

static int row(const char *label, const banyan_roots_params *p, const banyan_hosts *H) {
    banyan_error err = {0, ""};
    banyan_mesh *m = NULL;
    clock_t t0 = clock();
    if (banyan_roots_generate_hosts(p, H, &m, NULL, NULL, &err)) {
        fprintf(stderr, "%s seed %llu: %s\n", label, (unsigned long long)p->seed, err.message);
        return 1;
    }
    double gen_s = (double)(clock() - t0) / CLOCKS_PER_SEC;
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
    rl_sleeve s = {0, 0, 0, 0};
    if (rl_grid_build(m, 0.05, 0.0, &g) == 0) {
        rl_sleeve_gap(m, &g, blo, bhi, ground, &s);
        rl_grid_free(&g);
    }
    rl_reach r;
    rl_foot_reach(m, flo, fhi, ground, &r);
    enum { CAP = 1 << 16 };
    static double z[CAP];
    clock_t t1 = clock();
    int64_t pairs = rl_self_intersections(m, z, CAP);
    double si_s = (double)(clock() - t1) / CLOCKS_PER_SEC;
    int64_t close = rl_close_pairs(m, 5e-4, NULL, 0);
    int64_t mid = 0;
    for (int64_t i = 0; i < pairs && i < CAP; i++) mid += z[i] >= ground + 2 && z[i] <= ground + 8;
    long long glb = rl_glb_size(m, "/tmp", NULL, &err);
    printf("| %s | %llu | %u | %.2f | %.2f | %.2f | %.2f | %.2f | %lld | %.0f %% | %lld | %.1f s | %.1f s |\n", label,
           (unsigned long long)p->seed, m->index_count / 3, glb / 1e6, s.gap, s.gap_foot, r.reach, r.fraction,
           (long long)pairs, pairs ? 100.0 * mid / (pairs < CAP ? pairs : CAP) : 0.0, (long long)close, gen_s, si_s);
    fflush(stdout);
    banyan_mesh_free(m);
    return 0;
}

static int preset(const char *name, int seeds, int argc, char **argv) {
    char path[4096];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_error err;
    uint32_t n = 0;
    banyan_hosts *H = NULL;
    if (test_load_preset(BANYAN_GEN_ROOTS, &p, path, NULL, 0, &n, &err) || test_load_host_set(path, &H, &err)) {
        fprintf(stderr, "%s: %s\n", name, err.message);
        return 1;
    }
    int rc = overrides(&p, argc, argv);
    for (int s = 1; s <= seeds && !rc; s++) {
        p.seed = (uint64_t)s;
        rc |= row(name, &p, H);
    }
    banyan_hosts_free(H);
    return rc;
}

int main(int argc, char **argv) {
    int seeds = argc > 1 ? atoi(argv[1]) : 5, rc = 0;
    printf("| preset | seed | triangles | .glb MB | sleeve gap | gap lowest 0.5 m | foot reach m | reach / width | "
           "self-intersecting pairs | of them 2-8 m up | pairs within 0.5 mm | generate | pairs search |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    rc |= overrides(&p, argc, argv);
    banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    banyan_hosts *H = NULL;
    banyan_error err;
    if (banyan_hosts_create(&trunk, 1, NULL, 0, &H, &err)) {
        fprintf(stderr, "trunk: %s\n", err.message);
        return 1;
    }
    for (int s = 1; s <= seeds && !rc; s++) {
        p.seed = (uint64_t)s;
        rc |= row("default", &p, H);
    }
    banyan_hosts_free(H);
    const char *names[4] = {"roots_mature_fig", "roots_old_fig", "roots_column", "roots_rock"};
    for (int k = 0; k < 4 && !rc; k++) rc |= preset(names[k], seeds, argc, argv);
    return rc;
}
