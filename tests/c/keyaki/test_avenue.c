/* avenue: layout (counts by spacing and count, rows, stagger, row offset,
 * polylines), per-tree seeds (tree i is the keyaki of seed base + i),
 * the merged mesh grouped by tree, byte-identical output on 1, 2 and all
 * threads, trees that differ, mixed ages (levels_jitter), sizes and
 * leans (scale_jitter, lean_jitter), refusals with clear messages, every
 * avenue preset, and a glb for the validator. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "keyaki/keyaki_internal.h"
#include "test_files.h"

static void small(banyan_avenue_params *p) {
    banyan_avenue_params_init(p);
    /* Small trees keep the test quick. */
    p->tree.levels = 12;
    p->tree.alpha = 1.45;
    p->tree.unit = 0.5;
}

static double dist_to_line_xy(const double *pos, v3 a, v3 b) {
    v3 ab = v3_sub(b, a), q = v3_sub(v3_make(pos[0], pos[1], pos[2]), a);
    double t = v3_dot(q, ab) / v3_len2(ab);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    v3 f = v3_madd(a, ab, t);
    return hypot(pos[0] - f.x, pos[1] - f.y);
}

static void layout(void) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    uint32_t n = 0;
    banyan_error err;
    /* 60 m every 8 m: 8 per row, centred (first at 2 m), 2 rows. */
    CHECK(banyan_avenue_layout(&p, NULL, 0, NULL, 0, &n, &err) == BANYAN_OK && n == 16, "spacing: %u trees", n);
    banyan_keyaki_params t[64];
    p.position_jitter = 0;
    CHECK(banyan_avenue_layout(&p, NULL, 0, t, 64, &n, &err) == BANYAN_OK, "%s", err.message);
    int bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t k = i % 8;
        double want_x = 2.0 + 8.0 * k, want_y = i < 8 ? 6.0 : -6.0;
        bad += fabs(t[i].position[0] - want_x) > 1e-9 || fabs(t[i].position[1] - want_y) > 1e-9;
        bad += t[i].seed != p.seed + i || t[i].max_vertices != p.max_vertices;
        bad += fabs(t[i].heading) > p.heading_jitter ||
               fabs(t[i].trunk_length / p.tree.trunk_length - 1) > p.height_jitter + 1e-12;
    }
    CHECK(bad == 0, "%d misplaced trees", bad);
    /* Stagger: row 1 shifted by 4 m loses its last tree (62 m > 60 m). */
    p.stagger = 1;
    CHECK(banyan_avenue_layout(&p, NULL, 0, t, 64, &n, &err) == BANYAN_OK && n == 15 &&
              fabs(t[8].position[0] - 6.0) < 1e-9,
          "stagger: %u trees, row 1 starts at %g", n, t[8].position[0]);
    /* Count: 5 per row from end to end; one row on the path. */
    p.stagger = 0;
    p.placement = BANYAN_AVENUE_COUNT;
    p.count = 5;
    p.rows = 1;
    CHECK(banyan_avenue_layout(&p, NULL, 0, t, 64, &n, &err) == BANYAN_OK && n == 5 && t[0].position[0] == 0 &&
              fabs(t[4].position[0] - 60) < 1e-9 && t[2].position[1] == 0,
          "count: %u trees", n);
    /* Jitter stays within its disc; a polyline keeps trees at the row
     * offset from the path. */
    p.rows = 2;
    p.row_offset = 10;
    p.placement = BANYAN_AVENUE_SPACING;
    p.spacing = 5;
    p.position_jitter = 0.5;
    double path[] = {0, 0, 0, 40, 0, 0, 40, 30, 0, 10, 60, 1};
    CHECK(banyan_avenue_layout(&p, path, 4, t, 64, &n, &err) == BANYAN_OK, "polyline: %s", err.message);
    double length = 40 + 30 + hypot(30, 30) + 0 * 1;
    length = 40 + 30 + sqrt(30 * 30 + 30 * 30 + 1);
    CHECK(n == 2 * (uint32_t)(floor(length / 5) + 1), "polyline: %u trees for %g m", n, length);
    bad = 0;
    for (uint32_t i = 0; i < n && i < 64; i++) {
        double best = 1e30;
        for (int s = 0; s < 3; s++) {
            double d = dist_to_line_xy(t[i].position, v3_load(path + 3 * s), v3_load(path + 3 * s + 3));
            if (d < best) best = d;
        }
        /* Within the offset +- jitter of the nearest segment (corners
         * bring the other leg closer, never farther). */
        bad += best > 5 + 0.5 + 1e-9;
    }
    CHECK(bad == 0, "%d polyline trees off their row", bad);
}

/* levels_jitter: levels within [levels - jitter, levels], never below 1,
 * several ages present; nothing else in the layout moves. */
static void mixed_ages(void) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    p.end[0] = 200; /* 25 trees per row */
    banyan_keyaki_params same[64], mixed[64];
    uint32_t n0 = 0, n1 = 0;
    banyan_error err;
    CHECK(banyan_avenue_layout(&p, NULL, 0, same, 64, &n0, &err) == BANYAN_OK, "%s", err.message);
    p.levels_jitter = 6;
    CHECK(banyan_avenue_layout(&p, NULL, 0, mixed, 64, &n1, &err) == BANYAN_OK && n1 == n0, "%s", err.message);
    int moved = 0, outside = 0, seen[32] = {0}, ages = 0;
    for (uint32_t i = 0; i < n1; i++) {
        moved += same[i].levels != p.tree.levels || memcmp(same[i].position, mixed[i].position, sizeof same[i].position) ||
                 same[i].heading != mixed[i].heading || same[i].trunk_length != mixed[i].trunk_length;
        outside += mixed[i].levels < p.tree.levels - 6 || mixed[i].levels > p.tree.levels;
        if (mixed[i].levels >= 0 && mixed[i].levels < 32 && !seen[mixed[i].levels]++) ages++;
    }
    CHECK(moved == 0, "levels_jitter moved %d trees", moved);
    CHECK(outside == 0 && ages >= 4, "%d trees outside [15, 21] levels, %d distinct ages", outside, ages);
    /* Never below one level. */
    p.tree.levels = 3;
    p.tree.fork_angle_step = 0;
    p.levels_jitter = 20;
    CHECK(banyan_avenue_layout(&p, NULL, 0, mixed, 64, &n1, &err) == BANYAN_OK, "%s", err.message);
    int low = 0, ones = 0;
    for (uint32_t i = 0; i < n1; i++) {
        low += mixed[i].levels < 1;
        ones += mixed[i].levels == 1;
    }
    CHECK(low == 0 && ones > 0, "%d trees below 1 level, %d at 1", low, ones);
}

static void refusals(void) {
    banyan_avenue_params p;
    banyan_error err = {0, ""};
    banyan_mesh *m;
    uint32_t n;
#define REFUSE(call, code, needle, what)                                                                         \
    do {                                                                                                        \
        m = (banyan_mesh *)&err;                                                                                \
        banyan_status s_ = (call);                                                                              \
        CHECK(s_ == (code) && m == NULL && strstr(err.message, needle), "%s: status %d, '%s'", what, s_,        \
              err.message);                                                                                     \
    } while (0)
    small(&p);
    p.threads = -1;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_RANGE, "threads = -1", "threads -1");
    p.threads = 65;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_RANGE, "threads = 65", "threads 65");
    p.end[0] = 0;
    p.threads = 1;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_RANGE, "start and end must differ", "no length");
    small(&p);
    double bad_path[] = {0, 0, 0, 1, NAN, 0};
    p.threads = 1;
    REFUSE(banyan_avenue_generate(&p, bad_path, 2, &m, NULL, &err), BANYAN_E_RANGE, "path point 1", "NaN path");
    double rep_path[] = {0, 0, 0, 5, 0, 0, 5, 0, 0};
    REFUSE(banyan_avenue_generate(&p, rep_path, 3, &m, NULL, &err), BANYAN_E_RANGE, "repeats", "repeated path point");
    REFUSE(banyan_avenue_generate(&p, rep_path, 1, &m, NULL, &err), BANYAN_E_RANGE, "path_point_count", "one point");
    p.spacing = 0.1;
    p.end[0] = 1e5;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_LIMIT, "more than 10000", "too many trees");
    small(&p);
    p.max_vertices = 5000;
    p.threads = 2;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_LIMIT, "more than max_vertices = 5000",
           "vertex limit");
    small(&p);
    p.tree.alpha = 1.0;
    p.threads = 2;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_RANGE, "tree.alpha = 1", "tree alpha 1");
    small(&p);
    /* The jitter keeps each trunk within trunk_length's own range, so the
     * range's ends are valid for an avenue too. */
    p.tree.trunk_length = 90;
    p.height_jitter = 0.5;
    {
        static banyan_keyaki_params jt[64];
        uint32_t nt = 0, at_max = 0, bad = 0;
        CHECK(banyan_avenue_layout(&p, NULL, 0, jt, 64, &nt, &err) == BANYAN_OK && nt > 0, "jittered trunk: %s",
              err.message);
        for (uint32_t i = 0; i < nt && i < 64; i++) {
            at_max += jt[i].trunk_length == 100;
            bad += !(jt[i].trunk_length >= 45 && jt[i].trunk_length <= 100);
        }
        CHECK(at_max > 0 && bad == 0, "jittered trunks: %u of %u at the max, %u outside [45, 100]", at_max, nt, bad);
    }
    small(&p);
    p.rows = 3;
    p.threads = 2;
    REFUSE(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err), BANYAN_E_RANGE, "rows = 3", "three rows");
    CHECK(banyan_avenue_generate(&p, NULL, 0, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL out");
    CHECK(banyan_avenue_layout(NULL, NULL, 0, NULL, 0, &n, &err) == BANYAN_E_INVALID_ARG, "NULL params");
    /* The table takes tree.* keys. */
    small(&p);
    CHECK(banyan_param_set_text(BANYAN_GEN_AVENUE, &p, "tree.levels", "9", &err) == BANYAN_OK && p.tree.levels == 9,
          "set tree.levels: %s", err.message);
    CHECK(banyan_param_set_text(BANYAN_GEN_AVENUE, &p, "tree.seed", "9", &err) == BANYAN_E_UNKNOWN_KEY,
          "tree.seed must not be settable (the avenue sets it)");
#undef REFUSE
}

/* banyan_group_localize on tree copies: 0-based indices, the origin at the
 * bottom centre of the tree's bounds, positions moved by it; a wrong
 * first_vertex is refused with both buffers untouched. Returns failures. */
static int localize_tree(const banyan_mesh *m, uint32_t v0, uint32_t nv, uint32_t i0, uint32_t ni) {
    float *pos = malloc(12 * (size_t)nv);
    uint32_t *idx = malloc(4 * (size_t)ni);
    if (!pos || !idx) abort();
    memcpy(pos, m->positions + 3 * (size_t)v0, 12 * (size_t)nv);
    memcpy(idx, m->indices + i0, 4 * (size_t)ni);
    int bad = 0;
    double o[3];
    banyan_error err;
    bad += banyan_group_localize(pos, nv, idx, ni, v0 + 1, o, &err) != BANYAN_E_RANGE || !strstr(err.message, "indices[");
    bad += memcmp(pos, m->positions + 3 * (size_t)v0, 12 * (size_t)nv) != 0 || memcmp(idx, m->indices + i0, 4 * (size_t)ni) != 0;
    bad += banyan_group_localize(pos, nv, idx, ni, v0, o, &err) != BANYAN_OK;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f}, zmin = 1e30f;
    for (uint32_t j = 0; j < nv; j++)
        for (int c = 0; c < 3; c++) {
            float a = m->positions[3 * (size_t)(v0 + j) + c], b = pos[3 * (size_t)j + c];
            lo[c] = a < lo[c] ? a : lo[c];
            hi[c] = a > hi[c] ? a : hi[c];
            if (c == 2 && b < zmin) zmin = b;
            bad += fabs((double)(a - (float)o[c]) - b) > 1e-4 * (1 + fabs(a));
        }
    bad += fabs(o[0] - 0.5 * (lo[0] + hi[0])) > 1e-4 || fabs(o[1] - 0.5 * (lo[1] + hi[1])) > 1e-4 || o[2] != lo[2] || zmin != 0;
    for (uint32_t j = 0; j < ni; j++) bad += idx[j] >= nv || idx[j] + v0 != m->indices[i0 + j];
    free(pos);
    free(idx);
    return bad != 0;
}

static void merged(const char *outdir) {
    banyan_avenue_params p;
    small(&p);
    p.end[0] = 40;
    banyan_mesh *m1 = NULL, *m2 = NULL, *m0 = NULL, *again = NULL;
    banyan_error err;
    p.threads = 1;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m1, NULL, &err) == BANYAN_OK, "1 thread: %s", err.message);
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m2, NULL, &err) == BANYAN_OK, "2 threads: %s", err.message);
    p.threads = 0;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m0, NULL, &err) == BANYAN_OK, "all cores: %s", err.message);
    p.threads = 7;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &again, NULL, &err) == BANYAN_OK, "7 threads: %s", err.message);
    if (!m1 || !m2 || !m0 || !again) return;
    uint64_t h = banyan_mesh_hash(m1);
    CHECK(h == banyan_mesh_hash(m2) && h == banyan_mesh_hash(m0) && h == banyan_mesh_hash(again),
          "thread counts change the bytes");
    CHECK(m1->vertex_count == m2->vertex_count && memcmp(m1->positions, m2->positions, 12 * (size_t)m1->vertex_count) == 0,
          "positions differ between 1 and 2 threads");

    /* Tree i's vertices are contiguous, its parts have group i, its
     * tree_id is i, and they equal the keyaki of the layout's params i. */
    uint32_t n = 0;
    banyan_keyaki_params t[32];
    CHECK(banyan_avenue_layout(&p, NULL, 0, t, 32, &n, &err) == BANYAN_OK && n == 12, "layout: %u", n);
    const float *tid = banyan_mesh_attribute(m1, "tree_id");
    CHECK(tid && banyan_mesh_attribute(m1, "level") && banyan_mesh_attribute(m1, "order"), "attributes");
    CHECK(m1->material_count == 2, "%u materials", m1->material_count);
    uint32_t part = 0, v = 0, x = 0;
    int bad_group = 0, bad_same = 0, bad_tid = 0, bad_local = 0;
    for (uint32_t i = 0; i < n && tid; i++) {
        banyan_mesh *k = NULL;
        CHECK(banyan_keyaki_generate(&t[i], &k, NULL, NULL, &err) == BANYAN_OK, "tree %u: %s", i, err.message);
        if (!k) continue;
        for (uint32_t q = 0; q < k->part_count; q++, part++) {
            const banyan_part *a = &m1->parts[part], *b = &k->parts[q];
            bad_group += a->group != i || a->material != b->material || a->vertex_offset != v + b->vertex_offset ||
                         a->vertex_count != b->vertex_count || a->index_offset != x + b->index_offset;
        }
        bad_same += memcmp(m1->positions + 3 * (size_t)v, k->positions, 12 * (size_t)k->vertex_count) != 0;
        for (uint32_t j = 0; j < k->index_count; j++) bad_same += m1->indices[x + j] != k->indices[j] + v;
        for (uint32_t j = 0; j < k->vertex_count; j++) bad_tid += tid[v + j] != (float)i;
        bad_local += localize_tree(m1, v, k->vertex_count, x, k->index_count);
        v += k->vertex_count;
        x += k->index_count;
        banyan_mesh_free(k);
    }
    CHECK(part == m1->part_count && v == m1->vertex_count && x == m1->index_count, "coverage: %u parts %u verts", part,
          v);
    CHECK(bad_group == 0 && bad_same == 0 && bad_tid == 0, "grouping %d, tree bytes %d, tree_id %d", bad_group,
          bad_same, bad_tid);
    CHECK(bad_local == 0, "%d trees localized wrongly", bad_local);

    /* Trees differ: tip counts and crown widths vary across the avenue. */
    int distinct = 0;
    for (uint32_t i = 1; i < n; i++) {
        banyan_keyaki_stats a, b;
        banyan_keyaki_skeleton_stats(&t[i - 1], &a, NULL);
        banyan_keyaki_skeleton_stats(&t[i], &b, NULL);
        distinct += a.crown_width != b.crown_width || a.tip_count != b.tip_count;
    }
    CHECK(distinct == (int)n - 1, "only %d of %u neighbours differ", distinct, n - 1);

    /* Another base seed, another avenue. */
    p.seed++;
    banyan_mesh *other = NULL;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &other, NULL, &err) == BANYAN_OK, "seed+1");
    CHECK(other && banyan_mesh_hash(other) != h, "base seed does not change the avenue");
    banyan_mesh_free(other);

    if (outdir) {
        char path[1024];
        snprintf(path, sizeof path, "%s/avenue_small.glb", outdir);
        const char *name = "avenue";
        CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m1, &name, 1, &err) == BANYAN_OK, "write: %s",
              err.message);
    }
    banyan_mesh_free(m1);
    banyan_mesh_free(m2);
    banyan_mesh_free(m0);
    banyan_mesh_free(again);
}


/* Coefficient of variation (sd / mean) of tree heights: each group's
 * highest vertex over its lowest. */
static double height_cv(const banyan_mesh *m, uint32_t n) {
    double h[64], sum = 0, sq = 0;
    for (uint32_t i = 0; i < n && i < 64; i++) h[i] = 0;
    float lo[64], hi[64];
    for (uint32_t i = 0; i < 64; i++) lo[i] = 1e30f, hi[i] = -1e30f;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group >= 64) continue;
        for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count; v++) {
            float z = m->positions[3 * (size_t)v + 2];
            lo[pt->group] = z < lo[pt->group] ? z : lo[pt->group];
            hi[pt->group] = z > hi[pt->group] ? z : hi[pt->group];
        }
    }
    for (uint32_t i = 0; i < n && i < 64; i++) {
        h[i] = hi[i] - lo[i];
        sum += h[i];
        sq += h[i] * h[i];
    }
    double mean = sum / n, var = sq / n - mean * mean;
    return mean > 0 ? sqrt(var > 0 ? var : 0) / mean : 0;
}

/* scale_jitter and lean_jitter: drawn from a stream of their own (the
 * feet, headings, trunks and levels stay those of an avenue without
 * them), unit within 1 +- scale_jitter of tree.unit, leans within
 * lean_jitter (the trunk's tilt as grown), and the heights spread. */
static void size_and_lean(void) {
    banyan_avenue_params p, q;
    small(&p);
    p.end[0] = 56; /* 8 a row */
    p.tree.leaves = 0;
    p.scale_jitter = 0.15;
    p.lean_jitter = 4.0;
    q = p;
    q.scale_jitter = 0;
    q.lean_jitter = 0;
    banyan_keyaki_params a[32], b[32];
    uint32_t n = 0, nb = 0;
    banyan_error err;
    CHECK(banyan_avenue_layout(&p, NULL, 0, a, 32, &n, &err) == BANYAN_OK && n == 16, "layout: %u trees", n);
    CHECK(banyan_avenue_layout(&q, NULL, 0, b, 32, &nb, &err) == BANYAN_OK && nb == n, "layout without: %u trees", nb);
    if (n != 16 || nb != n) return;
    int moved = 0, off_unit = 0, off_lean = 0, none = 0, dirs = 0;
    double umin = 1e9, umax = 0, lmax = 0;
    for (uint32_t i = 0; i < n; i++) {
        moved += memcmp(a[i].position, b[i].position, sizeof a[i].position) || a[i].heading != b[i].heading ||
                 a[i].trunk_length != b[i].trunk_length || a[i].levels != b[i].levels || a[i].seed != b[i].seed;
        double s = a[i].unit / p.tree.unit;
        off_unit += s < 1 - p.scale_jitter - 1e-12 || s > 1 + p.scale_jitter + 1e-12;
        umin = s < umin ? s : umin;
        umax = s > umax ? s : umax;
        none += b[i].unit != p.tree.unit || b[i].lean != 0;
        dirs += a[i].lean_direction > 0;
        /* The grown trunk's tilt is the lean; its foot stays. */
        keyaki_skeleton sk = {NULL, 0, 0, NULL};
        if (keyaki_grow(&a[i], &sk, NULL) != BANYAN_OK || sk.count < 1) {
            off_lean++;
            keyaki_skeleton_free(&sk);
            continue;
        }
        const keyaki_node *t = &sk.nodes[0];
        double tilt = acos(t->dir.z < 1 ? t->dir.z : 1) * 180.0 / BANYAN_PI;
        off_lean += tilt > p.lean_jitter + 1e-6 || fabs(tilt - a[i].lean) > 1e-6 ||
                    v3_dist(t->start, v3_load(a[i].position)) > 1e-9;
        lmax = tilt > lmax ? tilt : lmax;
        keyaki_skeleton_free(&sk);
    }
    CHECK(moved == 0, "%d trees whose feet, heading, trunk or levels move with scale_jitter / lean_jitter", moved);
    CHECK(none == 0, "%d trees sized or leaning without the jitters", none);
    CHECK(off_unit == 0 && umax - umin > p.scale_jitter, "units %.3f .. %.3f of tree.unit (%d outside +-%g)", umin, umax,
          off_unit, p.scale_jitter);
    CHECK(off_lean == 0 && lmax > 0.5 * p.lean_jitter, "%d trunks tilted otherwise than their lean (up to %g); largest %.2f deg",
          off_lean, p.lean_jitter, lmax);
    CHECK(dirs > 2 && dirs < (int)n - 2, "lean directions one-sided: %d of %u positive", dirs, n);
    /* Heights spread: more than without the jitters, and by at least 5 %. */
    banyan_mesh *m = NULL, *m0 = NULL;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_OK, "avenue: %s", err.message);
    q.threads = 2;
    CHECK(banyan_avenue_generate(&q, NULL, 0, &m0, NULL, &err) == BANYAN_OK, "avenue without: %s", err.message);
    if (m && m0) {
        double cv = height_cv(m, n), cv0 = height_cv(m0, n);
        CHECK(cv >= 0.05 && cv > cv0, "tree heights vary by %.3f (sd / mean), %.3f without scale_jitter", cv, cv0);
    }
    banyan_mesh_free(m);
    banyan_mesh_free(m0);
}

/* Tree counts of the presets whose layout the docs quote; 0: not checked. */
static uint32_t want_trees(const char *name) {
    if (!strcmp(name, "avenue_boulevard")) return 100;
    if (!strcmp(name, "avenue_street")) return 10;
    return 0;
}

/* One presets/avenue_*.json: it loads and generates within max_vertices;
 * the young planting (small) also goes to the validator. */
static void preset(const char *path, const char *name, void *ctx) {
    const char *outdir = ctx;
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    banyan_error err = {0, ""};
    banyan_status s = test_load_preset(BANYAN_GEN_AVENUE, &p, path, NULL, 0, NULL, &err);
    CHECK(s == BANYAN_OK, "%s: %s", path, err.message);
    uint32_t n = 0, want = want_trees(name);
    CHECK(banyan_avenue_layout(&p, NULL, 0, NULL, 0, &n, &err) == BANYAN_OK && n > 0 && (!want || n == want),
          "%s: %u trees", name, n);
    banyan_mesh *m = NULL;
    p.threads = 0;
    if (!s) s = banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err);
    /* Bark and leaves per tree (per variant when instanced, each variant
     * shown by at least one tree); bark only in winter. */
    uint32_t shown = p.variants > 0 && (uint32_t)p.variants < n ? (uint32_t)p.variants : n;
    uint32_t parts = (p.tree.leaves ? 2 : 1) * shown;
    CHECK(p.variants == 0 || (m == NULL && s) || (m && m->instance_count == n), "%s: %u instances, want %u", name,
          m ? m->instance_count : 0, n);
    CHECK(s == BANYAN_OK && m && m->part_count == parts, "%s: %s (%u parts, want %u)", name, err.message,
          m ? m->part_count : 0, parts);
    CHECK(m == NULL || m->vertex_count <= (uint32_t)p.max_vertices, "%s: over max_vertices", name);
    if (m && outdir && !strcmp(name, "avenue_young")) {
        char out[1024];
        snprintf(out, sizeof out, "%s/%s.glb", outdir, name);
        CHECK(banyan_gltf_write(out, (const banyan_mesh *const *)&m, &name, 1, &err) == BANYAN_OK, "write: %s",
              err.message);
    }
    banyan_mesh_free(m);
}

static void presets(const char *outdir) {
    int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "avenue_", preset, (void *)outdir);
    CHECK(n >= 3, "found %d presets/avenue_*.json", n);
}

int main(int argc, char **argv) {
    const char *outdir = argc > 1 ? argv[1] : NULL;
    layout();
    mixed_ages();
    refusals();
    merged(outdir);
    size_and_lean();
    presets(outdir);
    return check_done("test_avenue");
}
