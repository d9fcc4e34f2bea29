/* Tube sweeper: on random polylines the mesh is closed (every edge shared
 * by two triangles once seam and cap copies are welded by position),
 * winds counter-clockwise from outside (positive volume, face normals
 * agree with vertex normals), side normals point away from the axis, and
 * a straight tube has the volume of its polygonal prism. Frames are
 * orthonormal and do not twist on a planar curve. Writes tube.glb. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "base/rng.h"
#include "mesh/tube.h"
#include "mesh_checks.h"

typedef struct { float p[3]; } key3;

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Number of undirected edges not shared by exactly two triangles, after
 * welding vertices with identical float positions. */
static int open_edges(const banyan_mesh *m) {
    uint32_t nv = m->vertex_count;
    uint32_t *weld = malloc(sizeof(uint32_t) * nv);
    for (uint32_t i = 0; i < nv; i++) {
        weld[i] = i;
        for (uint32_t j = 0; j < i; j++)
            if (memcmp(m->positions + 3 * j, m->positions + 3 * i, 12) == 0) { weld[i] = weld[j]; break; }
    }
    uint32_t ne = m->index_count;
    uint64_t *e = malloc(sizeof(uint64_t) * ne);
    for (uint32_t t = 0; t < ne / 3; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = weld[m->indices[3 * t + k]], b = weld[m->indices[3 * t + (k + 1) % 3]];
            e[3 * t + k] = a < b ? a << 32 | b : b << 32 | a;
        }
    qsort(e, ne, sizeof *e, cmp_u64);
    int bad = 0;
    for (uint32_t i = 0; i < ne;) {
        uint32_t j = i;
        while (j < ne && e[j] == e[i]) j++;
        if (j - i != 2) bad++;
        i = j;
    }
    free(e);
    free(weld);
    return bad;
}

static double volume(const banyan_mesh *m) {
    double v = 0;
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        const float *a = m->positions + 3 * m->indices[3 * t], *b = m->positions + 3 * m->indices[3 * t + 1],
                    *c = m->positions + 3 * m->indices[3 * t + 2];
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    return v;
}

int main(int argc, char **argv) {
    pcg32 r;
    pcg32_seed(&r, 99, 0);
    int bad_open = 0, bad_vol = 0, bad_wind = 0, bad_out = 0, bad_count = 0, bad_uv = 0;
    for (int trial = 0; trial < 60; trial++) {
        uint32_t n = 2 + rng_below(&r, 12);
        int sides = 3 + (int)rng_below(&r, 14);
        double pts[3 * 16], rad[16];
        v3 p = v3_make(0, 0, 0), d = v3_make(0, 0, 1);
        for (uint32_t i = 0; i < n; i++) {
            pts[3 * i] = p.x; pts[3 * i + 1] = p.y; pts[3 * i + 2] = p.z;
            rad[i] = rng_range(&r, 0.02, 0.05);
            /* Gentle random turns: a tube of radius < segment/2 never folds. */
            d = v3_norm(v3_add(d, v3_make(rng_range(&r, -.5, .5), rng_range(&r, -.5, .5), rng_range(&r, -.5, .5))));
            p = v3_madd(p, d, rng_range(&r, 0.2, 0.4));
        }
        banyan_mesh *m = NULL;
        banyan_status s = banyan_tube_generate(pts, rad, n, sides, 1, &m, NULL);
        CHECK(s == BANYAN_OK && m, "tube %d failed with %d", trial, s);
        if (!m) continue;
        uint32_t ev, ei;
        tube_counts(n, sides, 1, 1, &ev, &ei);
        if (m->vertex_count != ev || m->index_count != ei) bad_count++;
        if (open_edges(m)) bad_open++;
        if (!(volume(m) > 0)) bad_vol++;
        bad_wind += mc_wound_against_normals(m, 1e-12);
        /* Side vertices: the normal points away from the nearest axis segment. */
        uint32_t side_verts = n * (uint32_t)(sides + 1);
        for (uint32_t v = 0; v < side_verts; v++) {
            v3 q = v3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
            v3 nn = v3_make(m->normals[3 * v], m->normals[3 * v + 1], m->normals[3 * v + 2]);
            double best = 1e30;
            v3 foot = q;
            for (uint32_t i = 0; i + 1 < n; i++) {
                v3 a = v3_load(pts + 3 * i), b = v3_load(pts + 3 * i + 3), ab = v3_sub(b, a);
                double t = v3_dot(v3_sub(q, a), ab) / v3_len2(ab);
                t = t < 0 ? 0 : t > 1 ? 1 : t;
                v3 f = v3_madd(a, ab, t);
                if (v3_dist(q, f) < best) { best = v3_dist(q, f); foot = f; }
            }
            if (v3_dot(nn, v3_sub(q, foot)) <= 0 || fabs(v3_len(nn) - 1) > 1e-5) bad_out++;
            if (m->uvs[2 * v] < 0 || m->uvs[2 * v] > 1) bad_uv++;
        }
        banyan_mesh_free(m);
    }
    CHECK(bad_count == 0, "%d tubes with unexpected vertex/index counts", bad_count);
    CHECK(bad_open == 0, "%d tubes not closed", bad_open);
    CHECK(bad_vol == 0, "%d tubes with non-positive volume", bad_vol);
    CHECK(bad_wind == 0, "%d triangles wound against their normals", bad_wind);
    CHECK(bad_out == 0, "%d side normals not outward unit", bad_out);
    CHECK(bad_uv == 0, "%d u outside [0,1]", bad_uv);

    /* A straight tube of 32 sides: volume of the prism n r^2 sin(2pi/n) L / 2. */
    double pts[6] = {0, 0, 0, 0, 0, 2}, rad[2] = {0.5, 0.5};
    banyan_mesh *m = NULL;
    CHECK(banyan_tube_generate(pts, rad, 2, 32, 1, &m, NULL) == BANYAN_OK, "straight tube");
    double want = 32 * 0.25 * sin(2 * BANYAN_PI / 32) * 2 / 2;
    CHECK(m && fabs(volume(m) - want) < 1e-5, "volume %g, want %g", m ? volume(m) : 0, want);
    /* Per-corner UVs gather uv[indices[k]]; a short buffer is refused. */
    if (m) {
        float *cu = malloc(sizeof(float) * 2 * m->index_count);
        CHECK(banyan_mesh_corner_uvs(m, cu, 2ull * m->index_count, NULL) == BANYAN_OK, "corner uvs");
        int bad_cu = 0;
        for (uint32_t k = 0; k < m->index_count; k++)
            bad_cu += cu[2 * k] != m->uvs[2 * m->indices[k]] || cu[2 * k + 1] != m->uvs[2 * m->indices[k] + 1];
        CHECK(bad_cu == 0, "%d corner uvs differ from their vertex's uv", bad_cu);
        CHECK(banyan_mesh_corner_uvs(m, cu, 2ull * m->index_count - 1, NULL) == BANYAN_E_RANGE, "short buffer accepted");
        free(cu);
    }
    banyan_mesh_free(m);

    /* Frames on a planar curve stay perpendicular to the plane's normal or
     * in it: no twist. */
    v3 arc[50], T[50], N[50];
    for (int i = 0; i < 50; i++) arc[i] = v3_make(cos(i * 0.1), sin(i * 0.1), 0);
    tube_frames(arc, 50, v3_make(0, 0, 1), T, N);
    int twist = 0;
    for (int i = 0; i < 50; i++)
        if (fabs(fabs(N[i].z) - 1) > 1e-9 || fabs(v3_dot(N[i], T[i])) > 1e-9 || fabs(v3_len(T[i]) - 1) > 1e-12) twist++;
    CHECK(twist == 0, "%d frames twisted off a planar curve's normal", twist);

    /* Bad input. */
    banyan_error err;
    double p3[9] = {0, 0, 0, 0, 0, 1, 0, 0, 2}, r3[3] = {0.1, 0.1, 0.1};
    m = (banyan_mesh *)&err; /* must be reset to NULL on failure */
    CHECK(banyan_tube_generate(p3, r3, 3, 2, 1, &m, &err) == BANYAN_E_RANGE && m == NULL && strstr(err.message, "sides"),
          "sides 2: %s", err.message);
    r3[1] = -1;
    CHECK(banyan_tube_generate(p3, r3, 3, 8, 1, &m, &err) == BANYAN_E_RANGE && strstr(err.message, "radii[1]"),
          "negative radius: %s", err.message);
    r3[1] = 0.1;
    p3[4] = NAN;
    CHECK(banyan_tube_generate(p3, r3, 3, 8, 1, &m, &err) == BANYAN_E_RANGE && strstr(err.message, "points[1]"),
          "NaN point: %s", err.message);
    p3[4] = 0;
    p3[5] = 0;
    CHECK(banyan_tube_generate(p3, r3, 3, 8, 1, &m, &err) == BANYAN_E_RANGE && strstr(err.message, "repeats"),
          "repeated point: %s", err.message);
    CHECK(banyan_tube_generate(p3, r3, 1, 8, 1, &m, &err) == BANYAN_E_RANGE, "one point accepted");
    CHECK(banyan_tube_generate(NULL, r3, 3, 8, 1, &m, &err) == BANYAN_E_INVALID_ARG, "NULL points accepted");
    CHECK(banyan_tube_generate(p3, r3, 3, 8, 1, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL out accepted");

    /* A tube for the validator. */
    if (argc > 1) {
        double hp[30], hr[10];
        for (int i = 0; i < 10; i++) {
            hp[3 * i] = 0.3 * cos(i * 0.6);
            hp[3 * i + 1] = 0.3 * sin(i * 0.6);
            hp[3 * i + 2] = 0.1 * i;
            hr[i] = 0.05 - 0.003 * i;
        }
        CHECK(banyan_tube_generate(hp, hr, 10, 12, 1, &m, &err) == BANYAN_OK, "helix: %s", err.message);
        char path[1024];
        snprintf(path, sizeof path, "%s/tube.glb", argv[1]);
        CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write %s: %s", path,
              err.message);
        banyan_mesh_free(m);
    }
    return check_done("test_tube");
}
