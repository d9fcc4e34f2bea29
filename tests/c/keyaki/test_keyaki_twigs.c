/* keyaki_twigs: a keyaki with twigs_from_segments (spec segments.md,
 * "Composing a tree"; docs/keyaki.md). Over many seeds and models: the cut
 * skeleton is the full tree's first nodes with its radii and is
 * segment_levels shallower; every segment (and every skeleton branch, as
 * an axis) is attached by the composer's check, and the check fails when
 * a segment is moved off; no segment exceeds 128 vertices; the mesh holds
 * exactly the planned twig tubes, at their radii, facing out, wound with
 * their normals, with sensible attributes; same seed same bytes (tree and
 * avenue on 1 and 2 threads); bad values refused; the preset and the
 * avenue's tree.* keys work; glb files for the validator. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh/tube.h"
#include "keyaki/keyaki_internal.h"
#include "segments/segment_core.h"
#include "test_files.h"
#include "mesh_checks.h"

static banyan_keyaki_params twig_params(uint64_t seed, int model) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.seed = seed;
    p.model = model;
    if (model == BANYAN_KEYAKI_SIMPLE) p.levels = 7;
    p.twigs_from_segments = 1;
    return p;
}

static v3 tip_of(const keyaki_node *x) { return v3_madd(x->start, x->dir, x->length); }

/* Skeleton: a prefix of the full tree, radii kept, depth reduced; every
 * segment attached and within budget. */
static void skeleton_and_segments(uint64_t seed, int model) {
    banyan_keyaki_params p = twig_params(seed, model), q = p;
    q.twigs_from_segments = 0;
    keyaki_skeleton cut = {NULL, 0, 0, NULL}, full = {NULL, 0, 0, NULL};
    CHECK(keyaki_params_validate(&p, NULL) == BANYAN_OK, "validate");
    if (keyaki_grow(&p, &cut, NULL) || keyaki_grow(&q, &full, NULL)) {
        CHECK(0, "grow seed %llu model %d", (unsigned long long)seed, model);
        goto done;
    }
    const int stop = p.levels - p.segment_levels;
    int32_t want = 0, max_level = 0, full_max = 0;
    for (int32_t i = 0; i < full.count; i++) {
        want += full.nodes[i].level <= stop;
        if (full.nodes[i].level > full_max) full_max = full.nodes[i].level;
    }
    int bad_prefix = 0, bad_tips = 0;
    for (int32_t i = 0; i < cut.count && cut.count == want; i++) {
        const keyaki_node *a = &cut.nodes[i], *b = &full.nodes[i];
        if (memcmp(&a->start, &b->start, sizeof a->start) || memcmp(&a->dir, &b->dir, sizeof a->dir) ||
            a->length != b->length || a->radius != b->radius || a->level != b->level || a->parent != b->parent)
            bad_prefix++;
        if (a->level > max_level) max_level = a->level;
        for (int k = 0; k < 2; k++)
            if (a->child[k] >= cut.count) bad_tips++;
        if (a->level == stop && (a->child[0] >= 0 || a->child[1] >= 0 || (a->flags & KN_BROKEN))) bad_tips++;
    }
    CHECK(cut.count == want && bad_prefix == 0 && bad_tips == 0,
          "seed %llu model %d: %d nodes (want %d), %d differ from the full tree, %d bad tips", (unsigned long long)seed,
          model, cut.count, want, bad_prefix, bad_tips);
    /* Depth reduced by segment_levels (edaore and simple reach every level). */
    if (model == BANYAN_KEYAKI_EDAORE || model == BANYAN_KEYAKI_SIMPLE)
        CHECK(max_level == stop && full_max == p.levels, "seed %llu model %d: depth %d (full %d), want %d",
              (unsigned long long)seed, model, max_level, full_max, stop);
    else
        CHECK(max_level <= stop, "model %d: depth %d > %d", model, max_level, stop);

    /* Segment list for the composer's check: every branch as a bare axis
     * (n = 0, parents first), then one segment per tip. */
    banyan_segment_input *segs = malloc(sizeof *segs * 2 * (size_t)cut.count);
    uint32_t ns = 0;
    for (int32_t i = 0; i < cut.count; i++) {
        keyaki_twig_input(&p, &cut.nodes[i], &segs[ns]);
        segs[ns].n = segs[ns].s = 0;
        ns++;
    }
    banyan_segment_params sp;
    keyaki_twig_params(&p, &sp);
    int over = 0, tips = 0, bad_count = 0, bad_start = 0;
    for (int32_t i = 0; i < cut.count; i++) {
        const keyaki_node *x = &cut.nodes[i];
        if (x->child[0] >= 0 || x->child[1] >= 0) continue;
        tips++;
        keyaki_twig_input(&p, x, &segs[ns]);
        float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
        int32_t nv = 0;
        CHECK(banyan_segment_lines(&segs[ns], &sp, xyz, NULL, &nv, NULL) == BANYAN_OK, "segment generate");
        over += nv > BANYAN_SEGMENT_MAX_VERTICES;
        bad_count += nv != banyan_segment_vertex_count(p.segment_twigs, p.segment_depth);
        /* The axis line is the branch: from its start to its tip. */
        v3 a = v3_make(xyz[0], xyz[1], xyz[2]), b = v3_make(xyz[3], xyz[4], xyz[5]);
        bad_start += v3_dist(a, x->start) > 1e-5 * (1 + v3_len(x->start)) || v3_dist(b, tip_of(x)) > 1e-5 * (1 + v3_len(b));
        ns++;
    }
    CHECK(tips > 0 && over == 0 && bad_count == 0 && bad_start == 0,
          "seed %llu model %d: %d tips, %d over budget, %d counts, %d axes off their branch", (unsigned long long)seed,
          model, tips, over, bad_count, bad_start);
    banyan_segments_params cp;
    banyan_segments_params_init(&cp);
    uint32_t nun = 99;
    banyan_error err = {0, ""};
    CHECK(banyan_segments_find_unattached(&cp, segs, ns, NULL, NULL, &nun, &err) == BANYAN_OK && nun == 0,
          "seed %llu model %d: %u of %u unattached (%s)", (unsigned long long)seed, model, nun, ns, err.message);
    /* The check can fail: the last segment moved 0.1 m off its branch. */
    v3 off = v3_scale(v3_any_perp(v3_load(segs[ns - 1].A)), 0.1);
    segs[ns - 1].S[0] += off.x;
    segs[ns - 1].S[1] += off.y;
    segs[ns - 1].S[2] += off.z;
    uint32_t which = 0;
    nun = 0;
    uint32_t *list = malloc(sizeof *list * ns);
    banyan_segments_find_unattached(&cp, segs, ns, NULL, list, &nun, NULL);
    if (nun == 1) which = list[0];
    CHECK(nun == 1 && which == ns - 1, "moved segment: %u unattached", nun);
    free(list);
    free(segs);
done:
    keyaki_skeleton_free(&cut);
    keyaki_skeleton_free(&full);
}

/* A budget-hitting segment shape still stays within 128 vertices. */
static void budget(void) {
    banyan_keyaki_params p = twig_params(5, BANYAN_KEYAKI_EDAORE);
    p.segment_twigs = 20;
    p.segment_depth = 6;
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK, "budget tree: %s", err.message);
    banyan_mesh_free(m);
    /* 2 + 40 vertices, then forks until the budget: (128 - 42) / 4 = 21 of them. */
    CHECK(banyan_segment_vertex_count(20, 6) == 42 + 4 * 21, "20 twigs, depth 6: %d vertices",
          banyan_segment_vertex_count(20, 6));
}

/* The twig tubes in the mesh: count, radius, outward normals, winding,
 * attributes. */
static void mesh_checks(uint64_t seed, int model) {
    banyan_keyaki_params p = twig_params(seed, model);
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    if (banyan_keyaki_generate(&p, &m, NULL, NULL, &err)) {
        CHECK(0, "generate seed %llu: %s", (unsigned long long)seed, err.message);
        return;
    }
    keyaki_skeleton sk = {NULL, 0, 0, NULL};
    keyaki_grow(&p, &sk, NULL);
    keyaki_strahler(sk.nodes, sk.count);
    banyan_segment_params sp;
    keyaki_twig_params(&p, &sp);
    uint32_t tv, ti;
    tube_counts(2, p.sides_min, 0, 1, &tv, &ti);
    int lines = banyan_segment_vertex_count(p.segment_twigs, p.segment_depth) / 2 - 1;
    uint32_t tips = 0;
    for (int32_t i = 0; i < sk.count; i++) tips += sk.nodes[i].child[0] < 0 && sk.nodes[i].child[1] < 0;
    uint32_t twig_v = tips * (uint32_t)lines * tv;
    const float *tid = banyan_mesh_attribute(m, "tree_id"), *lev = banyan_mesh_attribute(m, "level"),
                *ord = banyan_mesh_attribute(m, "order");
    CHECK(tid && lev && ord && m->part_count >= 1 && m->parts[0].material == 0, "attributes / bark part");
    if (!tid || !lev || !ord) goto done;
    const banyan_part *bark = &m->parts[0];
    uint32_t zero_order = 0;
    /* The bark part's order-0 vertices: the twigs (leaves are order 0 too, in part 1). */
    for (uint32_t v = bark->vertex_offset; v < bark->vertex_offset + bark->vertex_count; v++) zero_order += ord[v] == 0;
    CHECK(bark->vertex_count > twig_v && zero_order == twig_v,
          "seed %llu: %u vertices of order 0, want %u twig vertices (%u tips x %d lines x %u)", (unsigned long long)seed,
          zero_order, twig_v, tips, lines, tv);
    /* Twig tubes close the bark part, segment by segment, line by line. */
    uint32_t v0 = bark->vertex_offset + bark->vertex_count - twig_v;
    int bad_r = 0, bad_attr = 0;
    float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
    uint8_t lc[BANYAN_SEGMENT_MAX_VERTICES];
    for (int32_t i = 0; i < sk.count; i++) {
        const keyaki_node *x = &sk.nodes[i];
        if (x->child[0] >= 0 || x->child[1] >= 0) continue;
        banyan_segment_input in;
        keyaki_twig_input(&p, x, &in);
        int32_t nv = 0;
        banyan_segment_lines(&in, &sp, xyz, lc, &nv, NULL);
        for (int32_t j = 2; j < nv; j += 2, v0 += tv) {
            v3 a = v3_make(xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]);
            v3 ab = v3_sub(v3_make(xyz[3 * j + 3], xyz[3 * j + 4], xyz[3 * j + 5]), a);
            double r = keyaki_twig_radius(&p, x, lc[j]);
            if (!(r >= p.tip_radius * p.unit * p.tip_taper * (1 - 1e-12) && r <= x->radius)) bad_r++;
            for (uint32_t k = 0; k < tv; k++) {
                uint32_t v = v0 + k;
                if (tid[v] != 0 || ord[v] != 0 || lev[v] != (float)(x->level + lc[j])) bad_attr++;
                if (k >= 2 * (uint32_t)(p.sides_min + 1)) continue; /* side rings only */
                v3 q = v3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
                double t = v3_dot(v3_sub(q, a), ab) / v3_len2(ab);
                v3 foot = v3_madd(a, ab, t), nn = v3_make(m->normals[3 * v], m->normals[3 * v + 1], m->normals[3 * v + 2]);
                if (fabs(v3_dist(q, foot) - r) > 1e-4 * r + 1e-5 || v3_dot(nn, v3_sub(q, foot)) <= 0) bad_r++;
            }
        }
    }
    CHECK(bad_r == 0 && bad_attr == 0, "seed %llu: %d twig vertices off radius / facing in, %d with wrong attributes",
          (unsigned long long)seed, bad_r, bad_attr);
    /* Whole mesh: finite, unit normals, triangles wound with their normals,
     * skeleton = the cut tree (max level in the tags = levels - segment_levels). */
    int bad_n = 0, bad_wind = 0, skel_max = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *n = m->normals + 3 * v;
        bad_n += fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-4;
        for (int k = 0; k < 3; k++) bad_n += !isfinite(m->positions[3 * v + k]);
    }
    bad_wind += mc_wound_against_normals(m, 1e-14);
    /* The branch skeleton: the points without KEYAKI_SKEL_TWIG (twig lines
     * follow it, two points and two edges a line). */
    uint32_t branch_points = 0, twig_points = 0;
    for (uint32_t s = 0; s < m->skel_point_count; s++) {
        if (m->skel_tag[s] & KEYAKI_SKEL_TWIG) {
            twig_points++;
            continue;
        }
        branch_points++;
        if ((m->skel_tag[s] & 0xff) > skel_max) skel_max = m->skel_tag[s] & 0xff;
    }
    CHECK(bad_n == 0 && bad_wind == 0, "seed %llu: %d bad normals, %d triangles wound against them",
          (unsigned long long)seed, bad_n, bad_wind);
    CHECK(branch_points == (uint32_t)sk.count + 1 && m->skel_edge_count == (uint32_t)sk.count + twig_points &&
              (model != BANYAN_KEYAKI_EDAORE || skel_max == p.levels - p.segment_levels),
          "seed %llu: skeleton %u points, max level %d", (unsigned long long)seed, m->skel_point_count, skel_max);
done:
    keyaki_skeleton_free(&sk);
    banyan_mesh_free(m);
}

static int same_mesh(const banyan_mesh *a, const banyan_mesh *b) {
    if (!a || !b || a->vertex_count != b->vertex_count || a->index_count != b->index_count ||
        a->attribute_count != b->attribute_count)
        return 0;
    if (memcmp(a->positions, b->positions, sizeof(float) * 3 * a->vertex_count) ||
        memcmp(a->normals, b->normals, sizeof(float) * 3 * a->vertex_count) ||
        memcmp(a->indices, b->indices, sizeof(uint32_t) * a->index_count))
        return 0;
    for (uint32_t k = 0; k < a->attribute_count; k++)
        if (memcmp(a->attributes[k].data, b->attributes[k].data, sizeof(float) * a->vertex_count)) return 0;
    return 1;
}

static void determinism(void) {
    banyan_keyaki_params p = twig_params(77, BANYAN_KEYAKI_EDAORE), q = p;
    q.twigs_from_segments = 0;
    banyan_mesh *a = NULL, *b = NULL, *c = NULL;
    banyan_keyaki_generate(&p, &a, NULL, NULL, NULL);
    banyan_keyaki_generate(&p, &b, NULL, NULL, NULL);
    banyan_keyaki_generate(&q, &c, NULL, NULL, NULL);
    CHECK(same_mesh(a, b), "same seed, different bytes");
    CHECK(a && c && !same_mesh(a, c), "the flag changes nothing");
    banyan_mesh_free(a);
    banyan_mesh_free(b);
    banyan_mesh_free(c);
}

static void write_glb(const char *dir, const char *name, const banyan_mesh *m) {
    if (!dir || !m) return;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.glb", dir, name);
    banyan_error err;
    CHECK(banyan_gltf_write(path, &m, &name, 1, &err) == BANYAN_OK, "write %s: %s", path, err.message);
}

/* The avenue: tree.* keys, the same bytes on 1 and 2 threads. */
static void avenue(const char *outdir) {
    banyan_avenue_params a;
    banyan_avenue_params_init(&a);
    banyan_error err = {0, ""};
    CHECK(banyan_param_set_text(BANYAN_GEN_AVENUE, &a, "tree.twigs_from_segments", "true", &err) == BANYAN_OK &&
              banyan_param_set_text(BANYAN_GEN_AVENUE, &a, "tree.segment_levels", "3", &err) == BANYAN_OK &&
              a.tree.twigs_from_segments == 1 && a.tree.segment_levels == 3,
          "avenue tree.* keys: %s", err.message);
    a.placement = BANYAN_AVENUE_COUNT;
    a.count = 3;
    a.tree.levels = 15;
    banyan_mesh *m1 = NULL, *m2 = NULL;
    a.threads = 1;
    CHECK(banyan_avenue_generate(&a, NULL, 0, &m1, NULL, &err) == BANYAN_OK, "avenue: %s", err.message);
    a.threads = 2;
    CHECK(banyan_avenue_generate(&a, NULL, 0, &m2, NULL, &err) == BANYAN_OK, "avenue 2 threads: %s", err.message);
    CHECK(same_mesh(m1, m2), "avenue differs between 1 and 2 threads");
    const float *ord = m1 ? banyan_mesh_attribute(m1, "order") : NULL;
    uint32_t zero = 0;
    for (uint32_t v = 0; ord && v < m1->vertex_count; v++) zero += ord[v] == 0;
    CHECK(zero > 0, "avenue has no twig vertices");
    write_glb(outdir, "keyaki_twigs_avenue", m1);
    banyan_mesh_free(m1);
    banyan_mesh_free(m2);
    a.tree.segment_levels = a.tree.levels;
    m1 = (banyan_mesh *)&err;
    a.threads = 1;
    CHECK(banyan_avenue_generate(&a, NULL, 0, &m1, NULL, &err) == BANYAN_E_RANGE && !m1 && strstr(err.message, "segment_levels"),
          "avenue segment_levels = levels: '%s'", err.message);
}

static void refuse(const char *key, const char *value, banyan_status want, const char *needle) {
    banyan_keyaki_params p = twig_params(1, BANYAN_KEYAKI_EDAORE);
    banyan_error err = {0, ""};
    banyan_status s = banyan_param_set_text(BANYAN_GEN_KEYAKI, &p, key, value, &err);
    CHECK(s == want && strstr(err.message, needle), "--set %s=%s: status %d '%s'", key, value, s, err.message);
}

static void bad_input(void) {
    refuse("segment_levels", "0", BANYAN_E_RANGE, "segment_levels");
    refuse("segment_levels", "30", BANYAN_E_RANGE, "segment_levels");
    refuse("segment_twigs", "64", BANYAN_E_RANGE, "segment_twigs");
    refuse("segment_depth", "-1", BANYAN_E_RANGE, "segment_depth");
    refuse("segment_twig_length", "0", BANYAN_E_RANGE, "segment_twig_length");
    refuse("segment_twig_length", "nan", BANYAN_E_RANGE, "segment_twig_length");
    /* Direct struct values, through generate. */
    banyan_keyaki_params p = twig_params(1, BANYAN_KEYAKI_EDAORE);
    struct { const char *needle; int which; } cases[] = {
        {"segment_levels", 0}, {"segment_levels", 1}, {"segment_twig_length", 2}, {"segment_twigs", 3}, {"segment_depth", 4}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        p = twig_params(1, BANYAN_KEYAKI_EDAORE);
        switch (cases[c].which) {
        case 0: p.segment_levels = p.levels; break;
        case 1: p.segment_levels = 0; break;
        case 2: p.segment_twig_length = INFINITY; break;
        case 3: p.segment_twigs = -2; break;
        default: p.segment_depth = 17; break;
        }
        banyan_error err = {0, ""};
        banyan_mesh *m = (banyan_mesh *)&err;
        banyan_status s = banyan_keyaki_generate(&p, &m, NULL, NULL, &err);
        CHECK(s == BANYAN_E_RANGE && m == NULL && strstr(err.message, cases[c].needle), "case %zu: %d '%s'", c, s,
              err.message);
    }
    /* Too many vertices: refused before meshing. */
    p = twig_params(1, BANYAN_KEYAKI_EDAORE);
    p.max_vertices = 20000;
    banyan_error err = {0, ""};
    banyan_mesh *m = (banyan_mesh *)&err;
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_E_LIMIT && m == NULL, "max_vertices: '%s'", err.message);
    /* segment_levels must be < levels only with the flag on. */
    p = twig_params(1, BANYAN_KEYAKI_EDAORE);
    p.twigs_from_segments = 0;
    p.levels = 3;
    m = NULL;
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK, "flag off, segment_levels 4 > levels 3: %s", err.message);
    banyan_mesh_free(m);
}

static void preset(const char *outdir) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/keyaki_segment_twigs.json", BANYAN_SOURCE_DIR);
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    banyan_error err = {0, ""};
    banyan_status s = test_load_preset(BANYAN_GEN_KEYAKI, &p, path, NULL, 0, NULL, &err);
    CHECK(s == BANYAN_OK && p.twigs_from_segments, "%s: %s", path, err.message);
    banyan_mesh *m = NULL;
    if (!s) s = banyan_keyaki_generate(&p, &m, NULL, NULL, &err);
    CHECK(s == BANYAN_OK && m, "preset generate: %s", err.message);
    write_glb(outdir, "keyaki_segment_twigs", m);
    banyan_mesh_free(m);
}

int main(int argc, char **argv) {
    const char *outdir = argc > 1 ? argv[1] : NULL;
    for (uint64_t s = 1; s <= 20; s++) skeleton_and_segments(s * 7919, BANYAN_KEYAKI_EDAORE);
    for (int model = 0; model < 3; model++)
        for (uint64_t s = 1; s <= 5; s++) skeleton_and_segments(s * 31, model);
    for (uint64_t s = 1; s <= 6; s++) mesh_checks(s * 13, BANYAN_KEYAKI_EDAORE);
    mesh_checks(3, BANYAN_KEYAKI_STRONG_WEAK);
    budget();
    determinism();
    bad_input();
    avenue(outdir);
    preset(outdir);
    return check_done("test_keyaki_twigs");
}
