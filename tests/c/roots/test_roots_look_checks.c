/* The measures of roots_look_checks.h on meshes of known answer:
 *   - sleeve gap: a box host 1 m x 1 m x 2 m and an open cylinder of
 *     radius R round its lower metre. R = 0.9: every ray of the lower
 *     metre meets it within 0.5 m (gap 0.5 overall, 0 at the foot);
 *     R = 1.1: a ray at w across a face meets it at sqrt(R^2 - w^2) - 0.5,
 *     within 0.5 m for |w| >= sqrt(0.21), so 1 - 2 (0.5 - 0.458) of the
 *     lower metre's rays are open;
 *   - foot reach: vertices 0.1 m up at 1 m and 0.4 m beyond a 1 m x 2 m
 *     footprint, one 0.5 m up at 3 m (too high to count);
 *   - self-intersections: two crossing quads (2 pairs), a closed cube
 *     (0), the same cube with every triangle on its own copies of the
 *     vertices (0: welded by position), a cube inside a cube (0); pairs
 *     within a distance: parallel triangles and edges fractions of a mm
 *     apart;
 *   - the .glb size: a small roots mesh's, the size of the file written. */
#include <stdio.h>

#include "check.h"
#include "roots_look_checks.h"
#include "test_hosts.h"

static banyan_mesh bare(float *pos, uint32_t nv, uint32_t *idx, uint32_t ni) {
    banyan_mesh m;
    memset(&m, 0, sizeof m);
    m.positions = pos, m.vertex_count = nv, m.indices = idx, m.index_count = ni;
    return m;
}

static void sleeve(void) {
    enum { SIDES = 512, RINGS = 11 };
    static float pos[3 * SIDES * RINGS];
    static uint32_t idx[6 * SIDES * (RINGS - 1)];
    double host_lo[3] = {-0.5, -0.5, 0}, host_hi[3] = {0.5, 0.5, 2};
    double R[2] = {0.9, 1.1};
    for (int c = 0; c < 2; c++) {
        for (int k = 0; k < RINGS; k++)
            for (int i = 0; i < SIDES; i++) {
                double a = 2 * 3.14159265358979323846 * i / SIDES;
                float *p = pos + 3 * (k * SIDES + i);
                p[0] = (float)(R[c] * cos(a)), p[1] = (float)(R[c] * sin(a)), p[2] = (float)(0.1 * k);
            }
        uint32_t n = 0;
        for (int k = 0; k + 1 < RINGS; k++)
            for (int i = 0; i < SIDES; i++) {
                uint32_t a = k * SIDES + i, b = k * SIDES + (i + 1) % SIDES, d = a + SIDES, e = b + SIDES;
                idx[n++] = a, idx[n++] = b, idx[n++] = e, idx[n++] = a, idx[n++] = e, idx[n++] = d;
            }
        banyan_mesh m = bare(pos, SIDES * RINGS, idx, n);
        rl_grid g;
        CHECK(rl_grid_build(&m, 0.05, 0.0, &g) == 0, "grid");
        rl_sleeve s;
        CHECK(rl_sleeve_gap(&m, &g, host_lo, host_hi, 0.0, &s) == 0, "sleeve");
        rl_grid_free(&g);
        double foot = c == 0 ? 0.0 : 1 - 2 * (0.5 - sqrt(R[1] * R[1] - 1.0)) / 1.0;
        double all = (foot + 1.0) / 2;
        printf("cylinder R %.1f: gap %.4f (expected %.4f), foot %.4f (expected %.4f), %lld rays\n", R[c], s.gap, all,
               s.gap_foot, foot, (long long)s.rays);
        CHECK(s.rays == 4 * 50 * 100, "%lld rays, expected 4 faces x 50 x 100", (long long)s.rays);
        CHECK(s.rays_foot == 4 * 50 * 25, "%lld rays at the foot", (long long)s.rays_foot);
        CHECK(fabs(s.gap - all) < 0.01, "R %.1f: gap %.4f, expected %.4f", R[c], s.gap, all);
        CHECK(fabs(s.gap_foot - foot) < 0.02, "R %.1f: foot gap %.4f, expected %.4f", R[c], s.gap_foot, foot);
    }
    /* no mesh near: everything open */
    float far[9] = {10, 10, 0, 11, 10, 0, 10, 11, 1};
    uint32_t ti[3] = {0, 1, 2};
    banyan_mesh m = bare(far, 3, ti, 3);
    rl_grid g;
    rl_sleeve s;
    CHECK(rl_grid_build(&m, 0.05, 0.0, &g) == 0, "grid");
    CHECK(rl_sleeve_gap(&m, &g, host_lo, host_hi, 0.0, &s) == 0 && s.gap == 1 && s.gap_foot == 1,
          "a far triangle covers: gap %.3f", s.gap);
    rl_grid_free(&g);
}

static void reach(void) {
    float pos[12] = {1.5f, 0.5f, 0.1f, 0.0f, 1.4f, 0.1f, 3.5f, 0.0f, 0.5f, 0.2f, 0.2f, -0.1f};
    banyan_mesh m = bare(pos, 4, NULL, 0);
    double lo[2] = {-0.5, -1.0}, hi[2] = {0.5, 1.0};
    rl_reach r;
    rl_foot_reach(&m, lo, hi, 0.0, &r);
    printf("reach %.3f m, width %.3f m, fraction %.3f\n", r.reach, r.width, r.fraction);
    CHECK(fabs(r.reach - 1.0) < 1e-6, "reach %.6f, expected 1", r.reach);
    CHECK(fabs(r.width - 1.0) < 1e-12 && fabs(r.fraction - 1.0) < 1e-6, "width %.3f fraction %.3f", r.width,
          r.fraction);
    /* with the origin: the same vertices one metre lower in the mesh's frame */
    for (int i = 0; i < 4; i++) pos[3 * i + 2] -= 1.0f;
    m.origin[2] = 1.0;
    rl_foot_reach(&m, lo, hi, 0.0, &r);
    CHECK(fabs(r.reach - 1.0) < 1e-6, "reach with an origin %.6f, expected 1", r.reach);
}

/* A cube [c - h, c + h]^3 as 12 triangles on 8 vertices, appended. */
static void cube(float *pos, uint32_t *nv, uint32_t *idx, uint32_t *ni, double c, double h) {
    static const int F[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    uint32_t b = *nv;
    for (int i = 0; i < 8; i++) {
        pos[3 * (b + i)] = (float)(c + (i & 1 ? h : -h));
        pos[3 * (b + i) + 1] = (float)(c + (i & 2 ? h : -h));
        pos[3 * (b + i) + 2] = (float)(c + (i & 4 ? h : -h));
    }
    *nv += 8;
    for (int f = 0; f < 12; f++)
        for (int j = 0; j < 3; j++) idx[(*ni)++] = b + F[f][j];
}

static void self_intersections(void) {
    /* quad A on z = 0, quad B upright at x = 0.3 across A's upper triangle */
    float pos[24] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0.3f, 0.5f, -1, 0.3f, 0.8f, -1, 0.3f, 0.8f, 1, 0.3f, 0.5f, 1};
    uint32_t idx[12] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    banyan_mesh m = bare(pos, 8, idx, 12);
    int64_t n = rl_self_intersections(&m, NULL, 0);
    printf("crossing quads: %lld pairs\n", (long long)n);
    CHECK(n == 2, "crossing quads: %lld pairs, expected 2", (long long)n);
    /* B moved off A: none */
    for (int i = 4; i < 8; i++) pos[3 * i] = 1.5f;
    n = rl_self_intersections(&m, NULL, 0);
    CHECK(n == 0, "quads apart: %lld pairs", (long long)n);

    float cp[3 * 36];
    uint32_t ci[72], nv = 0, ni = 0;
    cube(cp, &nv, ci, &ni, 0.0, 1.0);
    m = bare(cp, nv, ci, ni);
    n = rl_self_intersections(&m, NULL, 0);
    CHECK(n == 0, "closed cube: %lld pairs", (long long)n);
    /* every triangle on its own vertices: welded, still none */
    float sp[3 * 36];
    uint32_t si[36];
    for (uint32_t i = 0; i < 36; i++) {
        memcpy(sp + 3 * i, cp + 3 * ci[i], 3 * sizeof(float));
        si[i] = i;
    }
    m = bare(sp, 36, si, 36);
    n = rl_self_intersections(&m, NULL, 0);
    CHECK(n == 0, "unwelded cube: %lld pairs", (long long)n);
    /* a cube in a cube: none; a cube through a cube's face: some */
    cube(cp, &nv, ci, &ni, 0.0, 0.5);
    m = bare(cp, nv, ci, ni);
    n = rl_self_intersections(&m, NULL, 0);
    CHECK(n == 0, "nested cubes: %lld pairs", (long long)n);
    nv = ni = 0;
    cube(cp, &nv, ci, &ni, 0.0, 1.0);
    cube(cp, &nv, ci, &ni, 1.0, 0.5);
    m = bare(cp, nv, ci, ni);
    double z[64];
    n = rl_self_intersections(&m, z, 64);
    printf("overlapping cubes: %lld pairs\n", (long long)n);
    CHECK(n > 0, "overlapping cubes: no pair found");
    for (int64_t i = 0; i < n && i < 64; i++) CHECK(z[i] > -1.01 && z[i] < 1.51, "pair height %.3f", z[i]);

    /* close pairs: two parallel triangles 0.3 mm apart (not within 0.2 mm,
     * within 0.5 mm), one 1 mm off */
    float tp[27] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2f, 0.2f, 0.0003f, 1.2f, 0.2f, 0.0003f, 0.2f, 1.2f, 0.0003f,
                    5, 5, 0, 6, 5, 0, 5, 6, 0.001f};
    uint32_t tix[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    m = bare(tp, 9, tix, 6);
    CHECK(rl_self_intersections(&m, NULL, 0) == 0, "parallel triangles intersect");
    CHECK(rl_close_pairs(&m, 2e-4, NULL, 0) == 0, "0.3 mm apart within 0.2 mm");
    CHECK(rl_close_pairs(&m, 5e-4, NULL, 0) == 1, "0.3 mm apart not within 0.5 mm: %lld",
          (long long)rl_close_pairs(&m, 5e-4, NULL, 0));
    /* edge to edge, 0.4 mm apart across a gap in x, boxes not overlapping */
    float ep[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 1.0004f, 0, 0, 2, 0, 0, 2, 1, 0};
    uint32_t eix[6] = {0, 1, 2, 3, 4, 5};
    m = bare(ep, 6, eix, 6);
    CHECK(rl_close_pairs(&m, 5e-4, NULL, 0) == 1, "edges 0.4 mm apart: %lld", (long long)rl_close_pairs(&m, 5e-4, NULL, 0));
    CHECK(rl_close_pairs(&m, 3e-4, NULL, 0) == 0, "edges 0.4 mm apart within 0.3 mm");
}

static void glb_size(const char *dir) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.surface = BANYAN_ROOTS_TUBES;
    p.growth_points = 10;
    banyan_box trunk = banyan_box_make(0, 0, 1, 0.4, 0.4, 1);
    banyan_mesh *m = NULL;
    banyan_error err;
    banyan_status s = test_roots_boxes(&p, &trunk, 1, &m, &err);
    CHECK(s == BANYAN_OK, "roots: %s", err.message);
    if (s) return;
    long long size = rl_glb_size(m, dir, NULL, &err);
    CHECK(size > 0, "glb size: %s", err.message);
    char path[4096];
    snprintf(path, sizeof path, "%s/roots_look_checks_size.glb", dir);
    const banyan_mesh *ms[1] = {m};
    CHECK(banyan_gltf_write_ex(path, ms, NULL, 1, NULL, &err) == BANYAN_OK, "write: %s", err.message);
    struct stat st;
    CHECK(stat(path, &st) == 0 && (long long)st.st_size == size, "glb size %lld, the file %lld", size,
          (long long)st.st_size);
    printf("small roots mesh: %lld bytes as .glb\n", size);
    banyan_mesh_free(m);
}

int main(int argc, char **argv) {
    sleeve();
    reach();
    self_intersections();
    glb_size(argc > 1 ? argv[1] : "/tmp");
    return check_done("test_roots_look_checks");
}
