/* test_wind_keyaki: the wind and birth attributes (banyan.h,
 * BANYAN_ATTR_WIND_*; docs/keyaki.md and docs/segments.md "Wind and
 * growth attributes") on keyaki trees (keyaki_mature, keyaki_young, the
 * four model presets, keyaki_segment_twigs), an avenue and the segments
 * demo (several seeds):
 *   - all eight attributes present and in range (wind_checks.h);
 *   - every pivot within 1 mm of the mesh's own skeleton;
 *   - keyaki: wood stiffness never rises along a path from the foot (as
 *     birth rises); segments: mean wood stiffness per level never rises
 *     toward the tips; and in every branch (vertices sharing pivot, level and phase) the vertex
 *     nearest the pivot is at least as stiff as the farthest;
 *   - phase: the vertices of a triangle that share a pivot share a phase,
 *     and branches (pivot, level) mostly have phases of their own;
 *   - flutter 1 on the leaf part, 0 on the bark part;
 *   - birth: 0 at the trunk base (the minimum), 1 the maximum, a leaf
 *     never before the wood it hangs on;
 *   - wind = 0: birth only; the same seed gives the same bytes; the
 *     avenue's bytes do not depend on the thread count. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "test_files.h"
#include "wind_checks.h"

typedef struct attrs {
    const float *px, *py, *pz, *lv, *st, *ph, *fl, *bt;
} attrs;

static int get_attrs(const banyan_mesh *m, attrs *a) {
    a->px = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X);
    a->py = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Y);
    a->pz = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Z);
    a->lv = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_LEVEL);
    a->st = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_STIFFNESS);
    a->ph = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PHASE);
    a->fl = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_FLUTTER);
    a->bt = banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH);
    return a->px && a->py && a->pz && a->lv && a->st && a->ph && a->fl && a->bt;
}

/* Sorting vertices into branches: by pivot, level, phase. */
static const attrs *g_a;
static int branch_cmp(const void *x, const void *y) {
    uint32_t i = *(const uint32_t *)x, j = *(const uint32_t *)y;
    const float *k[5] = {g_a->px, g_a->py, g_a->pz, g_a->lv, g_a->ph};
    for (int c = 0; c < 5; c++)
        if (k[c][i] != k[c][j]) return k[c][i] < k[c][j] ? -1 : 1;
    return i < j ? -1 : i > j;
}

static int same_branch(const attrs *a, uint32_t i, uint32_t j, int with_phase) {
    return a->px[i] == a->px[j] && a->py[i] == a->py[j] && a->pz[i] == a->pz[j] && a->lv[i] == a->lv[j] &&
           (!with_phase || a->ph[i] == a->ph[j]);
}

static double pivot_dist(const banyan_mesh *m, const attrs *a, uint32_t v) {
    double d2 = 0;
    const float *p = m->positions + 3 * (size_t)v, q[3] = {a->px[v], a->py[v], a->pz[v]};
    for (int k = 0; k < 3; k++) d2 += ((double)p[k] - q[k]) * ((double)p[k] - q[k]);
    return sqrt(d2);
}

/* Wood vertices (flutter 0) in a grid of cells h wide, for the leaves'
 * nearest-wood queries. */
typedef struct vgrid {
    double lo[3], h;
    int n[3];
    uint32_t *start, *items;
} vgrid;

static long vg_cell(const vgrid *g, const float *p, int c[3]) {
    for (int k = 0; k < 3; k++) {
        int i = (int)floor((p[k] - g->lo[k]) / g->h);
        c[k] = i < 0 ? 0 : i >= g->n[k] ? g->n[k] - 1 : i;
    }
    return ((long)c[2] * g->n[1] + c[1]) * g->n[0] + c[0];
}

static int vg_build(vgrid *g, const banyan_mesh *m, const attrs *a, double h) {
    double hi[3];
    for (int k = 0; k < 3; k++) g->lo[k] = 1e300, hi[k] = -1e300;
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            double x = m->positions[3 * (size_t)v + k];
            g->lo[k] = fmin(g->lo[k], x), hi[k] = fmax(hi[k], x);
        }
    g->h = h;
    long cells = 1;
    for (int k = 0; k < 3; k++) {
        g->n[k] = (int)((hi[k] - g->lo[k]) / h) + 1;
        if (g->n[k] > 1024) g->n[k] = 1024;
        cells *= g->n[k];
    }
    for (int k = 0; k < 3; k++) g->h = fmax(g->h, (hi[k] - g->lo[k]) / g->n[k] * 1.000001);
    g->start = calloc((size_t)cells + 1, sizeof(uint32_t));
    g->items = malloc(sizeof(uint32_t) * (m->vertex_count + 1));
    if (!g->start || !g->items) return 0;
    int c[3];
    for (uint32_t v = 0; v < m->vertex_count; v++)
        if (a->fl[v] == 0) g->start[vg_cell(g, m->positions + 3 * (size_t)v, c) + 1]++;
    for (long i = 0; i < cells; i++) g->start[i + 1] += g->start[i];
    for (uint32_t v = 0; v < m->vertex_count; v++)
        if (a->fl[v] == 0) g->items[g->start[vg_cell(g, m->positions + 3 * (size_t)v, c)]++] = v;
    for (long i = cells; i > 0; i--) g->start[i] = g->start[i - 1];
    g->start[0] = 0;
    return 1;
}

/* Nearest wood vertex of wind level `level` to p (within the 27 cells);
 * also the least birth of those within `near` metres. UINT32_MAX: none. */
static uint32_t vg_nearest(const vgrid *g, const banyan_mesh *m, const attrs *a, const float *p, float level,
                           double near, float *min_birth) {
    int c[3];
    vg_cell(g, p, c);
    uint32_t best = UINT32_MAX;
    double bd = 1e300;
    *min_birth = 2;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int i = c[0] + dx, j = c[1] + dy, k = c[2] + dz;
                if (i < 0 || j < 0 || k < 0 || i >= g->n[0] || j >= g->n[1] || k >= g->n[2]) continue;
                long cell = ((long)k * g->n[1] + j) * g->n[0] + i;
                for (uint32_t s = g->start[cell]; s < g->start[cell + 1]; s++) {
                    uint32_t v = g->items[s];
                    if (a->lv[v] != level) continue;
                    const float *q = m->positions + 3 * (size_t)v;
                    double d = sqrt(((double)q[0] - p[0]) * ((double)q[0] - p[0]) +
                                    ((double)q[1] - p[1]) * ((double)q[1] - p[1]) +
                                    ((double)q[2] - p[2]) * ((double)q[2] - p[2]));
                    if (d < bd) bd = d, best = v;
                    if (d <= near && a->bt[v] < *min_birth) *min_birth = a->bt[v];
                }
            }
    return best;
}

static int fcmp(const void *x, const void *y) {
    float a = *(const float *)x, b = *(const float *)y;
    return a < b ? -1 : a > b;
}

static const float *g_sort_bt;
static int by_birth(const void *x, const void *y) {
    float a = g_sort_bt[*(const uint32_t *)x], b = g_sort_bt[*(const uint32_t *)y];
    return a < b ? -1 : a > b;
}

/* 1 when, over the wood (flutter 0) sorted by birth, stiffness never
 * rises by more than 1e-5; *rise gets the largest rise. */
static int stiffness_follows_path(const banyan_mesh *m, const attrs *a, float *rise) {
    uint32_t n = 0, *v = malloc(sizeof(uint32_t) * (m->vertex_count ? m->vertex_count : 1));
    if (!v) return 0;
    for (uint32_t i = 0; i < m->vertex_count; i++)
        if (a->fl[i] == 0) v[n++] = i;
    g_sort_bt = a->bt;
    qsort(v, n, sizeof *v, by_birth);
    float lo = 2;
    *rise = 0;
    for (uint32_t k = 0; k < n; k++) { /* lo: the least stiffness of all wood born earlier or at once */
        float s = a->st[v[k]];
        if (s - lo > *rise) *rise = s - lo;
        if (s < lo) lo = s;
    }
    free(v);
    return *rise <= 1e-5f;
}

/* Every check on one mesh with wind. trunk_base: where birth starts.
 * by_path: keyaki's stiffness falls with the path from the foot (checked
 * along every path); the segments generator's with the radius by level
 * (checked by the per-level means). */
static void check_wind(const banyan_mesh *m, const char *name, const double trunk_base[3], int by_path) {
    char why[256];
    int ok = wind_attrs_check(m, why, sizeof why);
    CHECK(ok, "%s: %s", name, why);
    attrs a;
    if (!ok || !get_attrs(m, &a)) return;
    uint32_t wv = 0;
    double worst = wind_pivot_worst(m, 0.25, &wv);
    CHECK(worst >= 0 && worst <= 1e-3, "%s: pivot of vertex %u is %.4g m from the skeleton (%u points)", name, wv,
          worst, m->skel_point_count);
    double means[16];
    /* Stiffness grows toward the base along every path: wood's stiffness
     * never rises as its birth (the path length from the trunk's foot)
     * does. The per-level means (printed) are only a proxy: on strong_weak
     * the level-8 branches stand nearer the foot than level 7's. */
    float worst_rise = 0;
    if (by_path)
        CHECK(stiffness_follows_path(m, &a, &worst_rise),
              "%s: wood stiffness rises by %g along a path from the foot", name, (double)worst_rise);
    int bad_level = wind_level_stiffness(m, 0.01, means);
    if (!by_path)
        CHECK(bad_level < 0, "%s: mean wood stiffness rises at level %d (%.3f after %.3f)", name, bad_level,
              bad_level > 0 ? means[bad_level] : 0, bad_level > 0 ? means[bad_level - 1] : 0);
    int levels = 0;
    printf("%s: mean wood stiffness by level:", name);
    for (int l = 0; l < 16; l++) {
        levels += means[l] >= 0;
        if (means[l] >= 0) printf(" %d: %.3f", l, means[l]);
    }
    printf("\n");
    CHECK(levels >= 3, "%s: wood on %d levels only", name, levels);

    /* Branches: base (nearest the pivot) at least as stiff as the tip. */
    uint32_t n = m->vertex_count, *ord = malloc(sizeof(uint32_t) * n);
    if (!ord) return;
    for (uint32_t v = 0; v < n; v++) ord[v] = v;
    g_a = &a;
    qsort(ord, n, sizeof(uint32_t), branch_cmp);
    uint32_t branches = 0, groups = 0, soft_base = 0, phases = 0;
    for (uint32_t s = 0; s < n;) {
        uint32_t e = s + 1;
        while (e < n && same_branch(&a, ord[s], ord[e], 1)) e++;
        if (s == 0 || !same_branch(&a, ord[s - 1], ord[s], 0)) groups++; /* a new pivot and level */
        branches++;
        if (a.fl[ord[s]] == 0) {
            uint32_t near = ord[s], far = ord[s];
            for (uint32_t k = s; k < e; k++) {
                if (pivot_dist(m, &a, ord[k]) < pivot_dist(m, &a, near)) near = ord[k];
                if (pivot_dist(m, &a, ord[k]) > pivot_dist(m, &a, far)) far = ord[k];
            }
            soft_base += a.st[near] + 1e-6f < a.st[far];
        }
        s = e;
    }
    /* Distinct phases (floats: a few collide among 10^5 leaves). */
    float *ph = malloc(sizeof(float) * n);
    if (ph) {
        memcpy(ph, a.ph, sizeof(float) * n);
        qsort(ph, n, sizeof(float), fcmp);
        for (uint32_t v = 0; v < n; v++) phases += v == 0 || ph[v] != ph[v - 1];
        free(ph);
    }
    CHECK(soft_base == 0, "%s: %u of %u branches stiffer at the tip than at the base", name, soft_base, branches);
    /* Two branches may share a pivot and level (limbs leaving one fork),
     * never a phase there. */
    CHECK(branches >= groups && phases >= 0.95 * branches && groups > 10,
          "%s: %u branches (pivot, level, phase) for %u pivots and levels; %u distinct phases", name, branches,
          groups, phases);
    free(ord);

    /* Phase constant along a branch: a triangle whose corners share a
     * pivot and level shares one phase. */
    uint32_t mixed = 0;
    for (uint32_t t = 0; t + 2 < m->index_count; t += 3) {
        uint32_t i = m->indices[t], j = m->indices[t + 1], k = m->indices[t + 2];
        if (same_branch(&a, i, j, 0) && same_branch(&a, i, k, 0))
            mixed += a.ph[i] != a.ph[j] || a.ph[i] != a.ph[k];
    }
    CHECK(mixed == 0, "%s: %u triangles of one branch with mixed phases", name, mixed);

    /* Flutter: leaves 1, wood 0 (material 1 is the leaves). */
    uint32_t bad_fl = 0, leaves = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *P = &m->parts[q];
        int leaf = m->material_count > 1 && P->material == 1 && m->materials[1].double_sided;
        for (uint32_t v = P->vertex_offset; v < P->vertex_offset + P->vertex_count; v++) {
            bad_fl += a.fl[v] != (leaf ? 1.0f : 0.0f);
            leaves += leaf;
        }
    }
    CHECK(bad_fl == 0, "%s: %u vertices with the wrong flutter", name, bad_fl);

    /* Birth: 0 at the trunk base, 1 the last. */
    uint32_t vmin = 0;
    float bmax = 0;
    for (uint32_t v = 0; v < n; v++) {
        if (a.bt[v] < a.bt[vmin]) vmin = v;
        if (a.bt[v] > bmax) bmax = a.bt[v];
    }
    const float *q = m->positions + 3 * (size_t)vmin;
    double dh = hypot(q[0] - trunk_base[0], q[1] - trunk_base[1]), dz = q[2] - trunk_base[2];
    CHECK(a.bt[vmin] == 0 && dh < 1.5 && fabs(dz) < 0.5 && bmax == 1,
          "%s: birth %g (min) at %.2f m from the trunk base (%.2f m up), max %g", name, (double)a.bt[vmin], dh, dz,
          (double)bmax);
    /* Leaves: never before the wood they hang on (the least birth of wood
     * of their level - 1 within 0.6 m of the petiole: a segment twig line
     * has rings only at its ends), and, but for the odd leaf whose nearest
     * ring is another twig's, not long after the nearest ring. */
    if (leaves) {
        vgrid g;
        memset(&g, 0, sizeof g);
        if (vg_build(&g, m, &a, 0.6)) {
            uint32_t early = 0, far = 0, none = 0, checked = 0;
            for (uint32_t qn = 0; qn < m->part_count; qn++) {
                const banyan_part *P = &m->parts[qn];
                if (P->material != 1) continue;
                for (uint32_t v = P->vertex_offset; v < P->vertex_offset + P->vertex_count; v += 4) {
                    float piv[3] = {a.px[v], a.py[v], a.pz[v]}, mb;
                    uint32_t w = vg_nearest(&g, m, &a, piv, a.lv[v] - 1, 0.6, &mb);
                    checked++;
                    if (w == UINT32_MAX || mb > 1) {
                        none++;
                        continue;
                    }
                    early += a.bt[v] < mb;
                    far += a.bt[v] > a.bt[w] + 0.1f;
                }
            }
            printf("%s: %u leaves, %u born long after the nearest ring of their wood\n", name, checked, far);
            CHECK(checked > 0 && early == 0 && far <= checked / 100 && none == 0,
                  "%s: of %u leaves, %u born before their wood, %u long after it, %u with no wood of their level "
                  "- 1 near",
                  name, checked, early, far, none);
        }
        free(g.start);
        free(g.items);
    }
}

static uint64_t mesh_hash(const banyan_mesh *m) {
    uint64_t h = 1469598103934665603ull;
#define HASH(ptr, bytes)                                                                                           \
    do {                                                                                                           \
        const unsigned char *b_ = (const unsigned char *)(ptr);                                                   \
        for (size_t k_ = 0; b_ && k_ < (size_t)(bytes); k_++) h = (h ^ b_[k_]) * 1099511628211ull;                 \
    } while (0)
    HASH(m->positions, sizeof(float) * 3 * m->vertex_count);
    HASH(m->indices, sizeof(uint32_t) * m->index_count);
    for (uint32_t k = 0; k < m->attribute_count; k++) {
        HASH(m->attributes[k].name, strlen(m->attributes[k].name));
        HASH(m->attributes[k].data, sizeof(float) * m->vertex_count);
    }
    HASH(m->skel_points, sizeof(float) * 3 * m->skel_point_count);
    HASH(m->skel_edges, sizeof(uint32_t) * 2 * m->skel_edge_count);
#undef HASH
    return h;
}

static int load(banyan_generator g, void *p, const char *name) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    banyan_error err = {0, ""};
    banyan_status s = test_load_preset(g, p, path, NULL, 0, NULL, &err);
    CHECK(s == BANYAN_OK, "%s: %s", path, err.message);
    return s == BANYAN_OK;
}

static void keyaki_preset(const char *name) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    if (!load(BANYAN_GEN_KEYAKI, &p, name)) return;
    CHECK(p.wind == 1, "%s: wind is on by default", name);
    banyan_mesh *m = NULL, *m2 = NULL;
    banyan_error err = {0, ""};
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK, "%s: %s", name, err.message);
    if (!m) return;
    double base[3];
    for (int k = 0; k < 3; k++) base[k] = p.position[k] - m->origin[k];
    check_wind(m, name, base, 1);
    CHECK(banyan_keyaki_generate(&p, &m2, NULL, NULL, &err) == BANYAN_OK && mesh_hash(m) == mesh_hash(m2),
          "%s: the same seed gives other bytes", name);
    printf("%s: %u vertices, %u skeleton points\n", name, m->vertex_count, m->skel_point_count);
    banyan_mesh_free(m);
    banyan_mesh_free(m2);
}

static void no_wind(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.wind = 0;
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK, "wind 0: %s", err.message);
    if (!m) return;
    int wind = 0;
    for (int k = 0; k < 7; k++) wind += banyan_mesh_attribute(m, wind_attr_names[k]) != NULL;
    const float *bt = banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH);
    float bmax = 0;
    for (uint32_t v = 0; bt && v < m->vertex_count; v++) bmax = bt[v] > bmax ? bt[v] : bmax;
    CHECK(wind == 0 && bt && bmax == 1 && m->attribute_count == 4, "wind 0: %d wind attributes, birth %s (max %g)",
          wind, bt ? "there" : "missing", (double)bmax);
    banyan_mesh_free(m);

    banyan_segments_params sp;
    banyan_segments_params_init(&sp);
    sp.wind = 0;
    banyan_segment_input segs[64];
    uint32_t count = 0;
    double trunk[6];
    CHECK(banyan_segments_demo(&sp, segs, 64, &count, trunk, &err) == BANYAN_OK, "demo: %s", err.message);
    m = NULL;
    CHECK(banyan_segments_generate(&sp, segs, count, trunk, &m, NULL, NULL, &err) == BANYAN_OK, "segments: %s",
          err.message);
    if (!m) return;
    wind = 0;
    for (int k = 0; k < 7; k++) wind += banyan_mesh_attribute(m, wind_attr_names[k]) != NULL;
    CHECK(wind == 0 && banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH), "segments wind 0: %d wind attributes", wind);
    banyan_mesh_free(m);
}

static int same_bytes(const banyan_mesh *a, const banyan_mesh *b) {
    if (a->vertex_count != b->vertex_count || a->index_count != b->index_count ||
        a->attribute_count != b->attribute_count || a->skel_point_count != b->skel_point_count)
        return 0;
    return mesh_hash(a) == mesh_hash(b) &&
           !memcmp(a->normals, b->normals, sizeof(float) * 3 * a->vertex_count) &&
           !memcmp(a->uvs, b->uvs, sizeof(float) * 2 * a->vertex_count);
}

static void avenue(void) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    p.placement = BANYAN_AVENUE_COUNT;
    p.count = 3;
    p.rows = 2;
    banyan_mesh *m1 = NULL, *m2 = NULL;
    banyan_error err = {0, ""};
    p.threads = 1;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m1, NULL, &err) == BANYAN_OK, "avenue: %s", err.message);
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m2, NULL, &err) == BANYAN_OK, "avenue (2 threads): %s",
          err.message);
    if (m1 && m2) CHECK(same_bytes(m1, m2), "the avenue's bytes differ on 1 and 2 threads");
    if (m1) {
        /* Per tree (group): the checks of one tree, on a copy of its slice. */
        uint32_t trees = 0;
        for (uint32_t q = 0; q < m1->part_count; q++) trees = m1->parts[q].group + 1 > trees ? m1->parts[q].group + 1 : trees;
        CHECK(trees == 6, "avenue: %u trees", trees);
        banyan_keyaki_params t[6];
        uint32_t nt = 0;
        CHECK(banyan_avenue_layout(&p, NULL, 0, t, 6, &nt, &err) == BANYAN_OK && nt == 6, "layout: %s", err.message);
        /* The whole avenue: pivots, levels, phases, flutter, birth range. */
        char why[256];
        CHECK(wind_attrs_check(m1, why, sizeof why), "avenue: %s", why);
        double worst = wind_pivot_worst(m1, 0.25, NULL);
        CHECK(worst >= 0 && worst <= 1e-3, "avenue: a pivot %.4g m off the skeleton", worst);
        attrs a1;
        float rise = 0;
        CHECK(get_attrs(m1, &a1) && stiffness_follows_path(m1, &a1, &rise),
              "avenue: wood stiffness rises by %g along a path from a foot", (double)rise);
        /* Birth per tree: 0 at its own trunk base, 1 at its last growth. */
        const float *bt = banyan_mesh_attribute(m1, BANYAN_ATTR_BIRTH), *tid = banyan_mesh_attribute(m1, "tree_id");
        int bad = 0;
        for (uint32_t k = 0; bt && tid && k < nt; k++) {
            float lo = 2, hi = -1;
            uint32_t at = 0;
            for (uint32_t v = 0; v < m1->vertex_count; v++) {
                if (tid[v] != (float)k) continue;
                if (bt[v] < lo) lo = bt[v], at = v;
                hi = bt[v] > hi ? bt[v] : hi;
            }
            const float *q = m1->positions + 3 * (size_t)at;
            double dx = q[0] + m1->origin[0] - t[k].position[0], dy = q[1] + m1->origin[1] - t[k].position[1];
            bad += lo != 0 || hi != 1 || hypot(dx, dy) > 1.5;
        }
        CHECK(bt && tid && bad == 0, "avenue: %d trees whose birth does not run 0 (trunk base) .. 1", bad);
    }
    banyan_mesh_free(m1);
    banyan_mesh_free(m2);
}

static void segments_demo(uint64_t seed) {
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    p.seed = seed;
    p.demo_segments = 40;
    banyan_segment_input segs[64];
    uint32_t count = 0;
    double trunk[6];
    banyan_error err = {0, ""};
    char name[64];
    snprintf(name, sizeof name, "segments demo seed %llu", (unsigned long long)seed);
    CHECK(banyan_segments_demo(&p, segs, 64, &count, trunk, &err) == BANYAN_OK, "%s: %s", name, err.message);
    banyan_mesh *m = NULL, *m2 = NULL;
    CHECK(banyan_segments_generate(&p, segs, count, trunk, &m, NULL, NULL, &err) == BANYAN_OK, "%s: %s", name,
          err.message);
    if (!m) return;
    double base[3] = {trunk[0] - m->origin[0], trunk[1] - m->origin[1], trunk[2] - m->origin[2]};
    check_wind(m, name, base, 0);
    /* A segment's axis pivots at its S, which lies on its parent's axis. */
    attrs a;
    const float *sg = banyan_mesh_attribute(m, "segment"), *lc = banyan_mesh_attribute(m, "level");
    int bad = 0;
    if (get_attrs(m, &a) && sg && lc)
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            if (sg[v] < 0 || lc[v] != 0) continue;
            const banyan_segment_input *s = &segs[(int)sg[v]];
            bad += fabs(a.px[v] - (s->S[0] - m->origin[0])) > 1e-5 || fabs(a.py[v] - (s->S[1] - m->origin[1])) > 1e-5 ||
                   fabs(a.pz[v] - (s->S[2] - m->origin[2])) > 1e-5 || a.lv[v] < 1;
        }
    CHECK(bad == 0, "%s: %d axis vertices not pivoting at their S", name, bad);
    CHECK(banyan_segments_generate(&p, segs, count, trunk, &m2, NULL, NULL, &err) == BANYAN_OK &&
              mesh_hash(m) == mesh_hash(m2),
          "%s: the same input gives other bytes", name);
    banyan_mesh_free(m);
    banyan_mesh_free(m2);
}

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    static const char *const presets[] = {"keyaki_mature",          "keyaki_young",         "keyaki_model_simple",
                                          "keyaki_model_strong_weak", "keyaki_model_twisted", "keyaki_model_edaore",
                                          "keyaki_segment_twigs"};
    for (size_t k = 0; k < sizeof presets / sizeof presets[0]; k++) keyaki_preset(presets[k]);
    avenue();
    for (uint64_t seed = 1; seed <= 4; seed++) segments_demo(seed);
    no_wind();
    return check_done("test_wind_keyaki");
}
