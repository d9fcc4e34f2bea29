/* Segment tree composer (spec segments.md, "Composing a tree"): unattached
 * segments are flagged, exactly (moved off every axis, attached only to a
 * later axis, off the trunk), and the grid search agrees with the brute
 * force one; the line set is the reference's lines in order; the tube mesh
 * has one tube per line with radius by level, outward normals, CCW winding,
 * a line-set skeleton and the attributes; limits and bad inputs are
 * refused; every presets/segments_*.json loads through the generic preset
 * reader and the segment reader and generates; the segment reader refuses
 * malformed entries with source:line. Writes .glb files for the validator. */
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "base/rng.h"
#include "mesh/tube.h"
#include "base/vec.h"
#include "segments/segment_core.h"
#include "test_files.h"
#include "mesh_checks.h"
#include "segment_tubes.h"

#define MAXV BANYAN_SEGMENT_MAX_VERTICES


static void write_glb(const char *dir, const char *name, const banyan_mesh *m) {
    if (!dir || !m) return;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    banyan_error err;
    CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write %s: %s", path,
          err.message);
}

/* Mesh invariants: finite, unit normals, triangles wound with their
 * normals, ring vertices at their ring's radius with normals pointing
 * away from its centre, vertex count as the tubes' layout says,
 * skeleton = line set with the tubes' base and tip radii. */
static void check_mesh(const banyan_mesh *m, const banyan_segments_params *p, const banyan_segment_input *segs,
                       uint32_t count, const double *trunk, const char *what) {
    uint32_t nv = 0;
    banyan_error err;
    CHECK(banyan_segments_lines(p, segs, count, trunk, NULL, NULL, 0, &nv, &err) == BANYAN_OK, "%s lines: %s", what,
          err.message);
    float *xyz = malloc(sizeof(float) * 3 * nv);
    int8_t *lev = malloc(nv);
    CHECK(banyan_segments_lines(p, segs, count, trunk, xyz, lev, nv, &nv, &err) == BANYAN_OK, "%s lines", what);
    uint32_t lines = nv / 2;
    seg_plan pl;
    CHECK(seg_plan_make(p, segs, count, trunk, m, &pl) == 0 && pl.n == lines, "%s: tube layout", what);
    CHECK(m->vertex_count == pl.vertices && m->index_count == pl.indices, "%s: %u vertices / %u indices, laid out %u / %u",
          what, m->vertex_count, m->index_count, pl.vertices, pl.indices);
    /* Skeleton: the line set, point for point, tag = level. */
    CHECK(m->skel_point_count == nv && m->skel_edge_count == lines, "%s: skeleton %u points %u edges for %u lines", what,
          m->skel_point_count, m->skel_edge_count, lines);
    int bad_skel = 0;
    for (uint32_t i = 0; i < nv && m->skel_point_count == nv; i++) {
        if (memcmp(m->skel_points + 3 * i, xyz + 3 * i, 12) || m->skel_tag[i] != lev[i]) bad_skel++;
        double want = i / 2 < pl.n ? (i & 1 ? pl.tubes[i / 2].t.rt : pl.tubes[i / 2].t.rb) : 0;
        if (fabs(m->skel_radius[i] - want) > 1e-6 * want) bad_skel++;
    }
    for (uint32_t e = 0; e < m->skel_edge_count; e++)
        if (m->skel_edges[2 * e] != 2 * e || m->skel_edges[2 * e + 1] != 2 * e + 1) bad_skel++;
    CHECK(bad_skel == 0, "%s: %d skeleton mismatches", what, bad_skel);
    const float *alevel = banyan_mesh_attribute(m, "level"), *aseg = banyan_mesh_attribute(m, "segment");
    CHECK(alevel && aseg && m->colors, "%s: level / segment attributes and colours", what);
    int bad_attr = 0, bad_n = 0, bad_wind = 0, bad_out = 0;
    for (uint32_t v = 0; v < m->vertex_count && alevel && aseg; v++) {
        if (!(alevel[v] >= -1 && alevel[v] <= 9) || !(aseg[v] >= -1 && aseg[v] < count)) bad_attr++;
        const float *n = m->normals + 3 * v;
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (fabs(len - 1) > 1e-4) bad_n++;
        for (int k = 0; k < 3; k++)
            if (!isfinite(m->positions[3 * v + k])) bad_n++;
    }
    bad_wind += mc_wound_against_normals(m, 1e-14);
    /* Ring vertices lie at their ring's radius round its centre (within
     * the sweeper's widening across the zigzag's bends), normals pointing
     * away from it; each carries its line's level. */
    for (uint32_t i = 0; i < lines && pl.vertices == m->vertex_count; i++) {
        const plan_tube *t = &pl.tubes[i];
        if (!t->meshed) continue;
        for (int k = 0; k < t->t.n; k++)
            for (uint32_t j = 0; j <= (uint32_t)p->sides; j++) {
                uint32_t v = t->first + (uint32_t)k * (uint32_t)(p->sides + 1) + j;
                v3 q = plan_vertex(m, v), d = v3_sub(q, t->t.c[k]);
                v3 nn = v3_make(m->normals[3 * v], m->normals[3 * v + 1], m->normals[3 * v + 2]);
                double r = t->t.r[k];
                if (fabs(v3_len(d) - r) > 3e-3 * r + 1e-6 * (1 + v3_len(q)) || v3_dot(nn, d) <= 0) bad_out++;
                if (alevel && alevel[v] != lev[2 * i]) bad_attr++;
            }
    }
    seg_plan_free(&pl);
    CHECK(bad_attr == 0, "%s: %d vertices with wrong attributes", what, bad_attr);
    CHECK(bad_n == 0, "%s: %d non-unit normals or non-finite positions", what, bad_n);
    CHECK(bad_wind == 0, "%s: %d triangles wound against their normals", what, bad_wind);
    CHECK(bad_out == 0, "%s: %d ring vertices off radius or facing in", what, bad_out);
    free(xyz);
    free(lev);
}

/* No later segment starts on segment i's axis (so moving i detaches i
 * alone). */
static int is_leaf(const banyan_segment_input *segs, uint32_t n, uint32_t i, double tol) {
    v3 a = v3_load(segs[i].S), u = v3_norm(v3_load(segs[i].A));
    for (uint32_t k = i + 1; k < n; k++) {
        v3 q = v3_load(segs[k].S);
        double t = fmin(fmax(v3_dot(v3_sub(q, a), u), 0), segs[i].l);
        if (v3_dist(q, v3_madd(a, u, t)) <= 10 * tol) return 0;
    }
    return 1;
}

/* Each refusal names the right line. */
static void expect_refusal(const char *text, banyan_status want, const char *needle, const char *what) {
    banyan_segment_input segs[8];
    uint32_t n = 77;
    banyan_error err;
    banyan_status s = banyan_segments_preset_read(text, strlen(text), "x.json", segs, 8, &n, NULL, NULL, &err);
    CHECK(s == want && n == 0 && strstr(err.message, needle), "%s: status %d (want %d), '%s' lacks '%s'", what, s, want,
          err.message, needle);
}

int main(int argc, char **argv) {
    const char *out_dir = argc > 1 ? argv[1] : NULL;
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    banyan_error err;
    CHECK(banyan_params_check(BANYAN_GEN_SEGMENTS, &p, &err) == BANYAN_OK, "defaults pass the table: %s", err.message);
    CHECK(banyan_param_count(BANYAN_GEN_SEGMENTS) == 19 && banyan_param_find(BANYAN_GEN_SEGMENTS, "attach_tolerance") &&
              banyan_param_find(BANYAN_GEN_SEGMENTS, "wind"),
          "param table");

    /* --- Demo trees are fully attached; moved segments are flagged. */
    enum { CAP = 2000 };
    banyan_segment_input *segs = malloc(sizeof *segs * CAP);
    uint32_t *un = malloc(sizeof *un * CAP), *un2 = malloc(sizeof *un2 * CAP);
    double trunk[6];
    uint32_t n = 0, nu = 0;
    pcg32 r;
    pcg32_seed(&r, 66, 0);
    int bad_flag = 0;
    for (int trial = 0; trial < 20; trial++) {
        p.seed = (uint64_t)trial + 1;
        p.demo_segments = 20 + (int32_t)rng_below(&r, 400);
        CHECK(banyan_segments_demo(&p, segs, CAP, &n, trunk, &err) == BANYAN_OK, "demo: %s", err.message);
        CHECK(banyan_segments_find_unattached(&p, segs, n, trunk, un, &nu, &err) == BANYAN_OK && nu == 0,
              "demo tree %d: %u unattached (first %u)", trial, nu, nu ? un[0] : 0);
        /* Move some segments far off every axis: exactly those are flagged. */
        uint32_t moved[8], k = 0;
        for (uint32_t i = 1 + rng_below(&r, 5); i < n && k < 8; i += 1 + rng_below(&r, n / 4 + 1)) {
            if (!is_leaf(segs, n, i, p.attach_tolerance)) continue;
            segs[i].S[0] += 1000;
            moved[k++] = i;
        }
        CHECK(k > 0, "tree %d: no leaf segment to move", trial);
        banyan_segments_find_unattached(&p, segs, n, trunk, un, &nu, &err);
        if (nu != k) bad_flag++;
        for (uint32_t q = 0; q < k && nu == k; q++)
            if (un[q] != moved[q]) bad_flag++;
    }
    CHECK(bad_flag == 0, "%d trees where the moved segments were not flagged exactly", bad_flag);

    /* Only earlier axes count; the trunk counts; without one, 0 is the root. */
    banyan_segment_input chain[3] = {
        {{0, 0, 2}, {0.6, 0, 0.8}, 2.5, 5, 0},
        {{0.9, 0, 3.2}, {0, 0.6, 0.8}, 1.5, 4, 1},
        {{0.9, 0.6, 4.0}, {-0.6, 0, 0.8}, 1.0, 3, 2},
    };
    double tr[6] = {0, 0, 0, 0, 0, 3};
    CHECK(banyan_segments_find_unattached(&p, chain, 3, tr, un, &nu, &err) == BANYAN_OK && nu == 0, "chain: %u", nu);
    CHECK(banyan_segments_find_unattached(&p, chain, 3, NULL, un, &nu, &err) == BANYAN_OK && nu == 0, "chain, no trunk");
    banyan_segment_input swapped[3] = {chain[0], chain[2], chain[1]}; /* 2 now starts on a LATER axis */
    CHECK(banyan_segments_find_unattached(&p, swapped, 3, tr, un, &nu, &err) == BANYAN_OK && nu == 1 && un[0] == 1,
          "later axis must not count: %u unattached, first %u", nu, un[0]);
    double tr_low[6] = {0, 0, 0, 0, 0, 1.5};
    CHECK(banyan_segments_find_unattached(&p, chain, 3, tr_low, un, &nu, &err) == BANYAN_OK && nu == 1 && un[0] == 0,
          "segment 0 above a short trunk: %u", nu);
    banyan_segment_input off = chain[1];
    off.S[2] += 2 * p.attach_tolerance; /* just beyond the tolerance */
    banyan_segment_input near = chain[1];
    near.S[2] += 0.5 * p.attach_tolerance; /* within it */
    banyan_segment_input pair[2] = {chain[0], off};
    CHECK(banyan_segments_find_unattached(&p, pair, 2, tr, un, &nu, &err) == BANYAN_OK && nu == 1, "2 tol off: %u", nu);
    pair[1] = near;
    CHECK(banyan_segments_find_unattached(&p, pair, 2, tr, un, &nu, &err) == BANYAN_OK && nu == 0, "tol/2 off: %u", nu);
    pair[1] = chain[1];
    pair[1].S[0] = 0.6 * 2.5 + 0.6 * 0.2; /* beyond the axis end B2 (t = l + 0.2) */
    pair[1].S[2] = 2 + 0.8 * 2.7;
    CHECK(banyan_segments_find_unattached(&p, pair, 2, tr, un, &nu, &err) == BANYAN_OK && nu == 1,
          "past the axis end counted as attached");

    /* Grid search == brute force on random near-misses. */
    int bad_grid = 0, flagged = 0;
    for (int trial = 0; trial < 12; trial++) {
        uint32_t cnt = 65 + rng_below(&r, 1500);
        double tol = trial % 4 == 0 ? 0 : pow(10, rng_range(&r, -4, 0));
        for (uint32_t i = 0; i < cnt; i++) {
            banyan_segment_input *s = &segs[i];
            if (i > 0 && rng_below(&r, 4)) {
                const banyan_segment_input *q = &segs[rng_below(&r, i)];
                v3 u = v3_norm(v3_load(q->A)), pt = v3_madd(v3_load(q->S), u, rng_range(&r, -0.1, 1.1) * q->l);
                v3 jit = v3_make(rng_range(&r, -2, 2), rng_range(&r, -2, 2), rng_range(&r, -2, 2));
                pt = v3_madd(pt, jit, tol);
                s->S[0] = pt.x; s->S[1] = pt.y; s->S[2] = pt.z;
            } else {
                for (int c = 0; c < 3; c++) s->S[c] = rng_range(&r, -20, 20);
            }
            for (int c = 0; c < 3; c++) s->A[c] = rng_range(&r, -1, 1);
            s->A[2] += 1.5;
            s->l = rng_range(&r, 0, trial % 3 ? 5 : 40);
            s->n = 3;
            s->s = 1;
        }
        banyan_status st;
        uint32_t a = seg_find_unattached(segs, cnt, trial % 2 ? tr : NULL, tol, 0, un, &st, NULL);
        uint32_t b = seg_find_unattached(segs, cnt, trial % 2 ? tr : NULL, tol, 1, un2, &st, NULL);
        if (a != b || memcmp(un, un2, sizeof *un * a)) bad_grid++;
        flagged += (int)a;
    }
    CHECK(bad_grid == 0, "%d lists where the grid and brute force disagree", bad_grid);
    CHECK(flagged > 100, "the near-miss lists flagged only %d", flagged);

    /* --- The mesh of a demo tree, and the same bytes twice. */
    banyan_segments_params_init(&p);
    p.demo_segments = 60;
    p.seed = 3;
    CHECK(banyan_segments_demo(&p, segs, CAP, &n, trunk, &err) == BANYAN_OK, "demo");
    banyan_mesh *m = NULL, *m2 = NULL;
    banyan_segments_stats st;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, &st, NULL, &err) == BANYAN_OK, "generate: %s", err.message);
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m2, NULL, NULL, &err) == BANYAN_OK, "generate again");
    CHECK(m && m2 && banyan_mesh_hash(m) == banyan_mesh_hash(m2), "same input, same bytes");
    if (m) {
        check_mesh(m, &p, segs, n, trunk, "demo");
        uint32_t sum = 0, lines = 1;
        for (int k = 0; k < 8; k++) sum += st.lines_per_level[k];
        for (uint32_t i = 0; i < n; i++) lines += (uint32_t)banyan_segment_vertex_count(segs[i].n, segs[i].s) / 2;
        CHECK(st.segments == n && st.lines == lines && sum + 1 == lines && st.unattached == 0 && st.max_level >= 2,
              "stats: %u segments %u lines (want %u) unattached %u", st.segments, st.lines, lines, st.unattached);
        write_glb(out_dir, "segments_demo.glb", m);
    }
    banyan_mesh_free(m);
    banyan_mesh_free(m2);

    /* Line set == the reference's segments in order, trunk first. */
    uint32_t nv;
    CHECK(banyan_segments_lines(&p, segs, n, trunk, NULL, NULL, 0, &nv, &err) == BANYAN_OK, "line count");
    float *lx = malloc(sizeof(float) * 3 * nv);
    int8_t *ll = malloc(nv);
    uint32_t need = 0;
    CHECK(banyan_segments_lines(&p, segs, n, trunk, lx, ll, nv - 1, &need, &err) == BANYAN_E_LIMIT && need == nv,
          "small cap accepted, or the needed count not reported (%u for %u)", need, nv);
    CHECK(banyan_segments_lines(&p, segs, n, trunk, lx, ll, nv, &nv, &err) == BANYAN_OK, "lines: %s", err.message);
    banyan_segment_params sp;
    banyan_segment_params_init(&sp);
    sp.m = p.m * p.unit;
    float xyz[3 * MAXV];
    uint8_t lev[MAXV];
    int32_t cnt;
    int bad_lines = ll[0] != -1 || ll[1] != -1 || lx[5] != (float)trunk[5];
    uint32_t v = 2;
    for (uint32_t i = 0; i < n; i++) {
        banyan_segment_lines(&segs[i], &sp, xyz, lev, &cnt, NULL);
        if (memcmp(lx + 3 * v, xyz, sizeof(float) * 3 * cnt)) bad_lines++;
        for (int32_t j = 0; j < cnt; j++) bad_lines += ll[v + j] != (int8_t)lev[j];
        v += (uint32_t)cnt;
    }
    CHECK(bad_lines == 0 && v == nv, "%d line-set mismatches against the reference", bad_lines);
    free(lx);
    free(ll);

    /* Unattached segments are still built and reported. */
    uint32_t leaf = n / 3;
    while (leaf < n - 1 && !is_leaf(segs, n, leaf, p.attach_tolerance)) leaf++;
    segs[leaf].S[1] += 500;
    segs[n - 1].S[1] -= 500;
    m = NULL;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, &st, NULL, &err) == BANYAN_OK && st.unattached == 2,
          "two moved segments: %u unattached", st.unattached);
    CHECK(banyan_segments_find_unattached(&p, segs, n, trunk, un, &nu, &err) == BANYAN_OK && nu == 2 &&
              un[0] == leaf && un[1] == n - 1, "two moved segments: %u listed", nu);
    banyan_mesh_free(m);

    /* --- Limits and bad input. */
    m = (banyan_mesh *)&err;
    p.max_vertices = 1000;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, &st, NULL, &err) == BANYAN_E_LIMIT && m == NULL &&
              strstr(err.message, "max_vertices = 1000"), "limit: %s", err.message);
    banyan_segments_params_init(&p);
    p.radius = NAN;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, NULL, NULL, &err) == BANYAN_E_RANGE && strstr(err.message, "radius"),
          "radius NaN: %s", err.message);
    banyan_segments_params_init(&p);
    p.sides = 2;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, NULL, NULL, &err) == BANYAN_E_RANGE && strstr(err.message, "sides"),
          "sides 2: %s", err.message);
    banyan_segments_params_init(&p);
    segs[3].n = 64;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, NULL, NULL, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "segs[3].n = 64"), "segs[3].n: %s", err.message);
    segs[3].n = 2;
    segs[4].A[0] = segs[4].A[1] = segs[4].A[2] = 0;
    CHECK(banyan_segments_generate(&p, segs, n, trunk, &m, NULL, NULL, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "segs[4].A"), "segs[4].A: %s", err.message);
    segs[4].A[2] = 1;
    double bad_trunk[6] = {0, 0, 0, 0, 0, 0};
    CHECK(banyan_segments_generate(&p, segs, n, bad_trunk, &m, NULL, NULL, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "trunk"), "zero trunk: %s", err.message);
    CHECK(banyan_segments_generate(&p, segs, 0, trunk, &m, NULL, NULL, &err) == BANYAN_E_RANGE, "count 0 accepted");
    CHECK(banyan_segments_generate(&p, NULL, 3, trunk, &m, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL segs");
    CHECK(banyan_segments_generate(&p, segs, n, trunk, NULL, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL out");
    banyan_segment_input dot = {{0, 0, 0}, {0, 0, 1}, 0, 0, 0};
    CHECK(banyan_segments_generate(&p, &dot, 1, NULL, &m, NULL, NULL, &err) == BANYAN_E_RANGE && m == NULL &&
              strstr(err.message, "nothing to mesh"), "empty tree: %s", err.message);
    p.demo_segments = 100;
    CHECK(banyan_segments_demo(&p, segs, 50, &n, trunk, &err) == BANYAN_E_RANGE, "demo cap");

    /* --- Presets: every presets/segments_*.json loads and generates. */
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/presets", BANYAN_SOURCE_DIR);
    DIR *d = opendir(dir);
    int presets = 0, paper = 0;
    for (struct dirent *e; d && (e = readdir(d));) {
        if (strncmp(e->d_name, "segments_", 9) || !strstr(e->d_name, ".json")) continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t len;
        char *text = test_read_file(path, &len);
        CHECK(text != NULL, "cannot read %s", path);
        if (!text) continue;
        presets++;
        banyan_segments_params_init(&p);
        banyan_box hosts[4];
        uint32_t nh;
        int32_t has_trunk;
        CHECK(banyan_preset_apply(BANYAN_GEN_SEGMENTS, &p, text, len, path, &err) == BANYAN_OK, "%s", err.message);
        CHECK(banyan_preset_hosts(text, len, path, hosts, 4, &nh, &err) == BANYAN_OK, "%s", err.message);
        CHECK(banyan_segments_preset_read(text, len, path, NULL, 0, &n, NULL, NULL, &err) == BANYAN_OK, "%s", err.message);
        CHECK(banyan_segments_preset_read(text, len, path, segs, CAP, &n, trunk, &has_trunk, &err) == BANYAN_OK, "%s",
              err.message);
        if (n == 0) {
            CHECK(banyan_segments_demo(&p, segs, CAP, &n, trunk, &err) == BANYAN_OK, "%s demo: %s", path, err.message);
            has_trunk = 1;
        }
        m = NULL;
        CHECK(banyan_segments_generate(&p, segs, n, has_trunk ? trunk : NULL, &m, &st, NULL, &err) == BANYAN_OK &&
                  st.unattached == 0, "%s: %s (%u unattached)", path, err.message, st.unattached);
        if (m) {
            check_mesh(m, &p, segs, n, has_trunk ? trunk : NULL, e->d_name);
            char name[300];
            snprintf(name, sizeof name, "preset_%.*s.glb", (int)(strlen(e->d_name) - 5), e->d_name);
            write_glb(out_dir, name, m);
        }
        if (!strcmp(e->d_name, "segments_paper.json")) {
            paper = 1;
            /* Three segments chained: 0 on the trunk, 1 on 0's axis, 2 on
             * 1's axis (and not on 0's). */
            CHECK(n == 3 && has_trunk, "paper preset: %u segments", n);
            CHECK(banyan_segments_find_unattached(&p, segs, 1, trunk, un, &nu, &err) == BANYAN_OK && nu == 0, "0 on trunk");
            banyan_segment_input two[2] = {segs[1], segs[2]};
            CHECK(banyan_segments_find_unattached(&p, two, 2, NULL, un, &nu, &err) == BANYAN_OK && nu == 0, "2 on 1");
            two[0] = segs[0];
            CHECK(banyan_segments_find_unattached(&p, two, 2, NULL, un, &nu, &err) == BANYAN_OK && nu == 1, "2 not on 0");
            CHECK(st.budget_hits >= 1, "the paper preset should show one segment at the budget");
        }
        banyan_mesh_free(m);
        free(text);
    }
    if (d) closedir(d);
    CHECK(presets >= 2 && paper, "found %d segment presets (paper %d) in %s", presets, paper, dir);

    /* --- Preset reader refusals, with lines. */
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": 1},\n"
                   "{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2}\n]}",
                   BANYAN_E_PARSE, "x.json:3: segments[1] needs \"s\"", "missing s");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": 1,\n \"k\": 3}]}",
                   BANYAN_E_UNKNOWN_KEY, "x.json:3: segments[0]: unknown key 'k'", "unknown key");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1,\n \"n\": 64, \"s\": 1}]}",
                   BANYAN_E_RANGE, "x.json:3: segments[0].n = 64 must be within [0, 63]", "n 64");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2.5, \"s\": 1}]}",
                   BANYAN_E_TYPE, "x.json:2: segments[0].n = 2.5 must be a whole number", "n 2.5");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": 1}]}",
                   BANYAN_E_TYPE, "x.json:2: segments[0].S must be [x, y, z]", "S of 2");
    expect_refusal("{\"segments\": [{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": 1},\n\n"
                   "{\"S\": [0,0,0],\n \"A\": [0,0,0], \"l\": 1, \"n\": 2, \"s\": 1}]}",
                   BANYAN_E_RANGE, "x.json:4: segments[1].A = (0, 0, 0)", "A zero");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0],\n\"l\": -2, \"n\": 2, \"s\": 1}]}",
                   BANYAN_E_RANGE, "x.json:3: segments[0].l = -2", "l negative");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": -1}]}",
                   BANYAN_E_RANGE, "x.json:2: segments[0].s = -1", "s negative");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": 1, \"n\": 3}]}",
                   BANYAN_E_PARSE, "x.json:2: segments[0].n is given twice", "duplicate n");
    expect_refusal("{\"segments\": [\n 3]}", BANYAN_E_TYPE, "x.json:2: segments[0] must be an object", "entry 3");
    expect_refusal("{\"generator\": \"segments\",\n\"segments\": {}}", BANYAN_E_TYPE, "x.json:2: segments must be an array",
                   "not an array");
    expect_refusal("{\"generator\": \"ivy\", \"segments\": []}", BANYAN_E_TYPE, "generator must be \"segments\"",
                   "other generator");
    expect_refusal("{\n\"trunk\": {\"start\": [0,0,0]}}", BANYAN_E_TYPE, "x.json:2: trunk must be", "trunk half");
    expect_refusal("{\n\"trunk\": {\"start\": [0,0,0], \"end\": [0,0,0]}}", BANYAN_E_RANGE, "x.json:2: trunk start and end",
                   "trunk zero");
    expect_refusal("{\"segments\": [\n{\"S\": [0,0,0]", BANYAN_E_PARSE, "x.json:2: malformed JSON", "truncated");
    expect_refusal("", BANYAN_E_PARSE, "empty", "empty file");
    /* The generic reader accepts the two new top-level keys and still
     * refuses unknown ones. */
    banyan_segments_params_init(&p);
    const char *ok_text = "{\"generator\": \"segments\", \"trunk\": {\"start\": [0,0,0], \"end\": [0,0,1]}, \"segments\": []}";
    CHECK(banyan_preset_apply(BANYAN_GEN_SEGMENTS, &p, ok_text, strlen(ok_text), "y.json", &err) == BANYAN_OK,
          "generic reader refuses segments/trunk: %s", err.message);
    const char *bad_text = "{\"generator\": \"segments\", \"segmints\": []}";
    CHECK(banyan_preset_apply(BANYAN_GEN_SEGMENTS, &p, bad_text, strlen(bad_text), "y.json", &err) == BANYAN_E_UNKNOWN_KEY,
          "a misspelt key passed");
    int32_t ht = 9;
    /* An empty list is refused (it would read as none: the demo tree). */
    CHECK(banyan_segments_preset_read(ok_text, strlen(ok_text), "y.json", segs, 4, &n, trunk, &ht, &err) ==
                  BANYAN_E_RANGE && n == 0 && ht == 0 && strstr(err.message, "y.json:1: segments is an empty list"),
          "empty list with trunk: %s", err.message);
    const char *trunk_only = "{\"generator\": \"segments\", \"trunk\": {\"start\": [0,0,0], \"end\": [0,0,1]}}";
    CHECK(banyan_segments_preset_read(trunk_only, strlen(trunk_only), "y.json", segs, 4, &n, trunk, &ht, &err) ==
                  BANYAN_OK && n == 0 && ht == 1 && trunk[5] == 1, "no list, a trunk: %s", err.message);
    const char *two = "{\"segments\": [{\"S\": [0,0,0], \"A\": [1,0,0], \"l\": 1, \"n\": 2, \"s\": 1},"
                      "{\"S\": [1,0,0], \"A\": [0,0,1], \"l\": 2, \"n\": 63, \"s\": 64}]}";
    CHECK(banyan_segments_preset_read(two, strlen(two), "z.json", segs, 1, &n, NULL, NULL, &err) == BANYAN_E_RANGE,
          "cap 1 accepted 2 segments");
    CHECK(banyan_segments_preset_read(two, strlen(two), "z.json", segs, 2, &n, NULL, NULL, &err) == BANYAN_OK && n == 2 &&
              segs[1].n == 63 && segs[1].s == 64 && segs[1].l == 2 && segs[1].A[2] == 1, "two segments read");

    free(segs);
    free(un);
    free(un2);
    return check_done("test_segments_compose");
}
