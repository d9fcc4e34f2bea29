/* Instanced avenues (variants > 0, csrc/keyaki/variants.c): instance i
 * stands exactly where the unique avenue's tree i stands (its trunk base,
 * read from the unique mesh's skeleton) with the layout's heading; the
 * first variants are the unique trees themselves, turned and moved by
 * their instance; variant count, groups and tree_id; the same bytes on 1
 * and 2 threads; variants past the tree count; budget, cancel and bad
 * values refused with *out == NULL; a glb for the validator.
 *
 *   test_avenue_variants OUTDIR */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"

static char g_dir[1024];

static void small(banyan_avenue_params *p) {
    banyan_avenue_params_init(p);
    p->tree.levels = 10; /* small trees keep the test quick */
    p->tree.alpha = 1.45;
    p->tree.unit = 0.5;
    p->placement = BANYAN_AVENUE_COUNT;
    p->count = 4;
    p->rows = 2; /* 8 trees */
    p->end[0] = 30;
}

/* The trunk bases of a merged avenue: skeleton points that end no edge,
 * in index order, which is tree order. */
static uint32_t roots(const banyan_mesh *m, uint32_t *out, uint32_t cap) {
    char *child = calloc(m->skel_point_count, 1);
    uint32_t n = 0;
    if (!child) return 0;
    for (uint32_t e = 0; e < m->skel_edge_count; e++) child[m->skel_edges[2 * e + 1]] = 1;
    for (uint32_t i = 0; i < m->skel_point_count; i++)
        if (!child[i] && n < cap) out[n++] = i;
    free(child);
    return n;
}

static const float *attr(const banyan_mesh *m, const char *name) { return banyan_mesh_attribute(m, name); }

/* The skeleton of tree (or variant) k of m, turned by rz and moved by t,
 * against tree k2's of u: the largest distance (m), or -1 when the point
 * counts differ. Trees' skeletons run from one trunk base to the next. */
static double skeleton_match(const banyan_mesh *m, const uint32_t *mb, uint32_t mn, uint32_t k, float rz,
                             const float t[3], const banyan_mesh *u, const uint32_t *ub, uint32_t un, uint32_t k2) {
    uint32_t a0 = mb[k], a1 = k + 1 < mn ? mb[k + 1] : m->skel_point_count;
    uint32_t b0 = ub[k2], b1 = k2 + 1 < un ? ub[k2 + 1] : u->skel_point_count;
    /* The branches only: the twig points after them (skel_tag bit 17,
     * docs/keyaki.md) are grown at heading 0 and differ in detail. */
    for (uint32_t i = a0; i < a1; i++)
        if (m->skel_tag[i] & (1 << 17)) { a1 = i; break; }
    for (uint32_t i = b0; i < b1; i++)
        if (u->skel_tag[i] & (1 << 17)) { b1 = i; break; }
    if (a1 - a0 != b1 - b0 || a1 == a0) return -1;
    double c = cos(rz), s = sin(rz), worst = 0;
    for (uint32_t i = 0; i < a1 - a0; i++) {
        const float *p = m->skel_points + 3 * (size_t)(a0 + i), *q = u->skel_points + 3 * (size_t)(b0 + i);
        double x = c * p[0] - s * p[1] + t[0], y = s * p[0] + c * p[1] + t[1], z = p[2] + t[2];
        double d = sqrt((x - q[0]) * (x - q[0]) + (y - q[1]) * (y - q[1]) + (z - q[2]) * (z - q[2]));
        if (d > worst) worst = d;
    }
    return worst;
}

static void placements(void) {
    banyan_avenue_params p;
    small(&p);
    banyan_error err;
    banyan_mesh *uni = NULL, *ins = NULL;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &uni, NULL, &err) == BANYAN_OK, "unique: %s", err.message);
    p.variants = 3;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &ins, NULL, &err) == BANYAN_OK, "variants: %s", err.message);
    banyan_keyaki_params trees[8];
    uint32_t n = 0;
    CHECK(banyan_avenue_layout(&p, NULL, 0, trees, 8, &n, &err) == BANYAN_OK && n == 8, "layout: %u trees", n);
    if (!uni || !ins || n != 8) goto out;

    CHECK(uni->instance_count == 0 && uni->instances == NULL, "the unique avenue has %u instances", uni->instance_count);
    CHECK(ins->instance_count == 8 && ins->instances, "%u instances for 8 trees", ins->instance_count);
    CHECK(memcmp(ins->origin, uni->origin, sizeof uni->origin) == 0, "origins differ");
    /* Groups are the variants 0 .. 2, tree_id says the same. */
    int bad_group = 0, seen[3] = {0, 0, 0};
    const float *tid = attr(ins, "tree_id");
    for (uint32_t q = 0; q < ins->part_count; q++) {
        const banyan_part *pt = &ins->parts[q];
        if (pt->group >= 3) {
            bad_group++;
            continue;
        }
        seen[pt->group] = 1;
        for (uint32_t v = 0; tid && v < pt->vertex_count; v++) bad_group += tid[pt->vertex_offset + v] != (float)pt->group;
    }
    CHECK(tid && bad_group == 0 && seen[0] && seen[1] && seen[2], "%d parts or vertices outside variants 0..2", bad_group);

    /* Instance i at the unique tree i's trunk base, with its heading. */
    uint32_t base[8];
    CHECK(roots(uni, base, 8) == 8, "the unique avenue's skeleton has not 8 trunks");
    int off = 0, turned = 0, drawn = 0;
    for (uint32_t i = 0; i < 8; i++) {
        const banyan_instance *in = &ins->instances[i];
        const float *b = uni->skel_points + 3 * (size_t)base[i];
        for (int c = 0; c < 3; c++) off += fabsf(in->translation[c] - b[c]) > 1e-5f;
        turned += fabs(in->rotation_z - trees[i].heading * (3.14159265358979323846 / 180.0)) > 1e-6 || in->variant >= 8 ||
                  fabs(in->scale - trees[i].unit / trees[in->variant < 8 ? in->variant : 0].unit) > 1e-6 ||
                  (i < 3 && in->scale != 1.0f);
        drawn += in->variant == (i < 3 ? i : in->variant) && in->variant < 3;
    }
    CHECK(off == 0, "%d instance coordinates off the unique trees' trunk bases", off);
    CHECK(turned == 0, "%d instances not turned by their tree's heading, or not scaled to their tree's size", turned);
    CHECK(drawn == 8, "instances 0..2 must show variants 0..2, the others one of them (%d right)", drawn);
    /* The first variants are the unique trees' skeletons, turned and
     * moved by their instance (twigs and leaves are drawn at heading 0,
     * so they differ in detail). */
    uint32_t vbase[3];
    CHECK(roots(ins, vbase, 3) == 3, "the variants' skeleton has not 3 trunks");
    for (uint32_t k = 0; k < 3; k++) {
        double d = skeleton_match(ins, vbase, 3, k, ins->instances[k].rotation_z, ins->instances[k].translation, uni,
                                  base, 8, k);
        CHECK(d >= 0 && d < 1e-4, "variant %u placed as instance %u is %g m from the unique tree %u", k, k, d, k);
    }

    /* Sizes spread over the instances too (scale_jitter): variant k's
     * height (its group's highest vertex over its lowest) times the
     * instance's scale is tree i's own height, as grown alone; leans stay
     * within lean_jitter. */
    {
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        for (uint32_t q = 0; q < ins->part_count; q++) {
            const banyan_part *pt = &ins->parts[q];
            for (uint32_t v = pt->vertex_offset; pt->group < 3 && v < pt->vertex_offset + pt->vertex_count; v++) {
                float z = ins->positions[3 * (size_t)v + 2];
                lo[pt->group] = z < lo[pt->group] ? z : lo[pt->group];
                hi[pt->group] = z > hi[pt->group] ? z : hi[pt->group];
            }
        }
        double sum = 0, sq = 0;
        int leaning = 0, bad_lean = 0;
        for (uint32_t i = 0; i < 8; i++) {
            double h = (hi[ins->instances[i].variant] - lo[ins->instances[i].variant]) * ins->instances[i].scale;
            sum += h;
            sq += h * h;
            leaning += trees[i].lean > 0;
            bad_lean += trees[i].lean < 0 || trees[i].lean > p.lean_jitter;
        }
        double mean = sum / 8, cv = sqrt(fmax(sq / 8 - mean * mean, 0)) / mean;
        CHECK(cv >= 0.04, "instance heights vary by %.3f (sd / mean) with scale_jitter %g", cv, p.scale_jitter);
        CHECK(leaning == 8 && bad_lean == 0, "%d trees leaning, %d beyond lean_jitter %g", leaning, bad_lean,
              p.lean_jitter);
    }

    /* The same bytes on 1 thread. */
    banyan_mesh *one = NULL;
    p.threads = 1;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &one, NULL, &err) == BANYAN_OK, "1 thread: %s", err.message);
    CHECK(one && banyan_mesh_hash(one) == banyan_mesh_hash(ins), "1 and 2 threads differ");
    banyan_mesh_free(one);

    /* A glb for the validator (tests/gltf/validate.mjs). */
    char path[1200];
    snprintf(path, sizeof path, "%s/test_avenue_variants.glb", g_dir);
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 64;
    CHECK(banyan_gltf_write_ex(path, (const banyan_mesh *const *)&ins, NULL, 1, &o, &err) == BANYAN_OK, "write: %s",
          err.message);
out:
    banyan_mesh_free(uni);
    banyan_mesh_free(ins);
}

/* More variants than trees: one variant a tree, each its own. A long row
 * with few variants draws them all, not a fixed cycle. */
static void counts(void) {
    banyan_avenue_params p;
    small(&p);
    p.variants = 50;
    banyan_error err;
    banyan_mesh *m = NULL;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_OK, "%s", err.message);
    if (m) {
        uint32_t top = 0, own = 0;
        for (uint32_t q = 0; q < m->part_count; q++)
            if (m->parts[q].group > top) top = m->parts[q].group;
        for (uint32_t i = 0; i < m->instance_count; i++) own += m->instances[i].variant == i;
        CHECK(top == 7 && m->instance_count == 8 && own == 8, "50 variants for 8 trees: groups up to %u, %u own", top,
              own);
    }
    banyan_mesh_free(m);

    uint32_t n = 0;
    banyan_avenue_params_init(&p);
    p.placement = BANYAN_AVENUE_COUNT;
    p.count = 200;
    p.rows = 1;
    p.variants = 4;
    CHECK(banyan_avenue_layout(&p, NULL, 0, NULL, 0, &n, &err) == BANYAN_OK && n == 200, "layout: %u", n);
    p.tree.levels = 4; /* the draws, not the trees, are tested */
    m = NULL;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_OK, "%s", err.message);
    if (m) {
        uint32_t used[4] = {0, 0, 0, 0}, cycle = 0;
        for (uint32_t i = 0; i < m->instance_count; i++) {
            if (m->instances[i].variant < 4) used[m->instances[i].variant]++;
            cycle += m->instances[i].variant == i % 4;
        }
        CHECK(used[0] > 20 && used[1] > 20 && used[2] > 20 && used[3] > 20, "variants drawn %u %u %u %u times",
              used[0], used[1], used[2], used[3]);
        CHECK(cycle < 150, "the variants repeat a cycle of 4 (%u of 200 trees)", cycle);
    }
    banyan_mesh_free(m);
}

static int32_t cancel_at_half(void *user, double done) {
    double *last = user;
    if (done < *last) *last = 2; /* went back: recorded as a failure */
    else if (*last <= 1) *last = done;
    return done > 0.5;
}

static int32_t note(void *user, double done) {
    double *last = user;
    if (done < *last) *last = 2;
    else if (*last <= 1) *last = done;
    return 0;
}

static void refusals(void) {
    banyan_avenue_params p;
    small(&p);
    p.variants = 4;
    banyan_error err;
    banyan_mesh *m = (banyan_mesh *)&err; /* must come back NULL */
    p.variants = -1;
    p.threads = 1;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_E_RANGE && !m &&
              strstr(err.message, "variants"),
          "variants -1: %s", err.message);
    p.variants = BANYAN_AVENUE_MAX_VARIANTS + 1;
    m = (banyan_mesh *)&err;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_E_RANGE && !m &&
              strstr(err.message, "variants"),
          "variants 4097: %s", err.message);
    p.variants = 4;
    m = (banyan_mesh *)&err;
    p.threads = BANYAN_AVENUE_MAX_THREADS + 1;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_E_RANGE && !m &&
              strstr(err.message, "threads"),
          "threads: %s", err.message);
    /* The vertices of the variants, not of the instances, meet max_vertices. */
    p.max_vertices = 20000;
    m = (banyan_mesh *)&err;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_E_LIMIT && !m &&
              strstr(err.message, "max_vertices"),
          "max_vertices: %s", err.message);
    p.max_vertices = 32000000;
    p.max_seconds = 0.01;
    p.tree.levels = 16;
    m = (banyan_mesh *)&err;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_E_LIMIT && !m &&
              strstr(err.message, "max_seconds"),
          "max_seconds: %s", err.message);
    p.max_seconds = 600;
    p.tree.levels = 14;
    p.max_memory_mb = 16;
    p.variants = 8;
    m = (banyan_mesh *)&err;
    banyan_status s = banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err);
    CHECK(s == BANYAN_E_LIMIT && !m && strstr(err.message, "max_memory_mb"), "max_memory_mb 16: %d %s", s, err.message);
    p.max_memory_mb = 8192;
    p.tree.levels = 10;
    /* Progress rises to 1; a cancel half way returns nothing. */
    double last = 0;
    banyan_progress pr = {note, &last};
    m = NULL;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, &pr, &err) == BANYAN_OK && last == 1.0, "progress ended at %g: %s",
          last, err.message);
    banyan_mesh_free(m);
    last = 0;
    pr.fn = cancel_at_half;
    m = (banyan_mesh *)&err;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, &pr, &err) == BANYAN_E_CANCELLED && !m && last <= 1,
          "cancel: %s", err.message);
}

int main(int argc, char **argv) {
    snprintf(g_dir, sizeof g_dir, "%s", argc > 1 ? argv[1] : ".");
    placements();
    counts();
    refusals();
    return check_done("test_avenue_variants");
}
