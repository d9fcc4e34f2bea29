/* Wind and birth attributes of the roots, the ivy and the tube demo
 * (docs/roots.md and docs/ivy.md "Wind and growth
 * attributes"), as invariants (wind_checks.h and below), not snapshots:
 *   - every attribute present and in range; pivots on the mesh's own
 *     skeleton (within 1 mm); mean wood stiffness per level never rising
 *     toward the tips (not the ivy's: contact holds it at any level);
 *     leaves flutter 1, wood 0; birth 0..1 with 0 (the
 *     first root or stem) and 1 both reached;
 *   - roots (every presets/roots_*.json, tubes and fused surface): one
 *     pivot, phase and level per root (root_id), the level its kind;
 *     a net point whose tube touches a host or the ground has stiffness 1,
 *     one well clear of them less; the fused surface's values are those
 *     of its nearest root;
 *   - ivy (ivy_wall, ivy_pillar, and the step API): birth never falls as
 *     birth_step rises; a leaf's pivot is its bud, its stiffness 1 on a
 *     held bud and below 1 on a free one; the step API's mesh is the
 *     one-shot generation's;
 *   - the tube: pivot its first point, stiffness rising with the radius,
 *     birth rising with the arc length from 0 to 1;
 *   - wind = 0: no wind attributes, birth still there; same seed, same
 *     hash. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy/ivy_internal.h"
#include "roots/roots_internal.h"
#include "test_files.h"
/* GCC 12 takes wind_pivot_worst's g.items, set in its first pass, for
 * maybe unset (the header is shared: not edited here). */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "wind_checks.h"
#include "test_hosts.h"
#pragma GCC diagnostic pop

#define ATTR(m, name) banyan_mesh_attribute(m, name)
#define LEVEL_TOL 0.05

/* The checks every mesh gets; `leaf` (may be NULL) tells leaf vertices;
 * `by_level`: mean stiffness must not rise with the level. */
static void common_checks(const char *what, const banyan_mesh *m, const float *leaf, int by_level) {
    char why[256];
    CHECK(wind_attrs_check(m, why, sizeof why), "%s: %s", what, why);
    uint32_t wv = 0;
    double worst = wind_pivot_worst(m, 0.05, &wv);
    CHECK(worst >= 0 && worst <= 1e-3, "%s: pivot of vertex %u lies %.4f m off the skeleton", what, wv, worst);
    double means[16];
    /* A tolerance: contact holds branch roots and lateral stems (stiffness
     * 1) as much as, or a little more than, their parents. */
    int bad = wind_level_stiffness(m, LEVEL_TOL, means);
    CHECK(!by_level || bad < 0, "%s: mean stiffness rises at level %d (%.3f after %.3f)", what, bad, bad >= 0 ? means[bad] : 0,
          bad > 0 ? means[bad - 1] : 0);
    printf("%-28s stiffness by level:", what);
    for (int l = 0; l < 16; l++)
        if (means[l] >= 0) printf(" %d: %.3f", l, means[l]);
    printf("\n");
    const float *fl = ATTR(m, BANYAN_ATTR_WIND_FLUTTER), *bi = ATTR(m, BANYAN_ATTR_BIRTH);
    if (!fl || !bi) return;
    long wrong = 0;
    float lo = 2, hi = -1;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        int is_leaf = leaf && leaf[v] > 0.5f;
        if (is_leaf ? fl[v] != 1.0f : (!leaf && fl[v] != 0.0f)) wrong++;
        lo = bi[v] < lo ? bi[v] : lo;
        hi = bi[v] > hi ? bi[v] : hi;
    }
    CHECK(wrong == 0, "%s: %ld vertices with the wrong flutter", what, wrong);
    CHECK(lo == 0.0f && hi == 1.0f, "%s: birth runs %g .. %g, not 0 .. 1", what, (double)lo, (double)hi);
}

/* wind = 0: birth only. */
static void no_wind_checks(const char *what, const banyan_mesh *m) {
    int any = 0;
    for (int k = 0; k < 7; k++) any |= ATTR(m, wind_attr_names[k]) != NULL;
    CHECK(!any && ATTR(m, BANYAN_ATTR_BIRTH), "%s, wind 0: wind attributes %s, birth %s", what,
          any ? "present" : "absent", ATTR(m, BANYAN_ATTR_BIRTH) ? "present" : "missing");
}

/* ------------------------------------------------------------- roots */

/* Per root_id: one pivot, phase and level, the level its kind. */
static void roots_per_root(const char *what, const banyan_mesh *m) {
    const float *id = ATTR(m, "root_id"), *kind = ATTR(m, "root_kind"), *lv = ATTR(m, BANYAN_ATTR_WIND_LEVEL),
                *ph = ATTR(m, BANYAN_ATTR_WIND_PHASE), *px = ATTR(m, BANYAN_ATTR_WIND_PIVOT_X),
                *py = ATTR(m, BANYAN_ATTR_WIND_PIVOT_Y), *pz = ATTR(m, BANYAN_ATTR_WIND_PIVOT_Z);
    if (!id || !kind || !lv || !ph || !px || !py || !pz) return;
    uint32_t n_id = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) n_id = (uint32_t)id[v] + 1 > n_id ? (uint32_t)id[v] + 1 : n_id;
    uint32_t *first = malloc(sizeof(uint32_t) * (n_id ? n_id : 1));
    for (uint32_t i = 0; i < n_id; i++) first[i] = UINT32_MAX;
    long bad = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        uint32_t r = (uint32_t)id[v];
        if (first[r] == UINT32_MAX) first[r] = v;
        uint32_t f = first[r];
        /* foot roots (kind 3) sway with the main roots: level 0; aerial roots (4) as the second branch roots */
        bad += lv[v] != (kind[v] == 3.0f ? 0.0f : kind[v] == 4.0f ? 2.0f : kind[v]) || ph[v] != ph[f] || px[v] != px[f] || py[v] != py[f] || pz[v] != pz[f];
    }
    CHECK(bad == 0, "%s: %ld vertices whose pivot, phase or level is not their root's", what, bad);
    free(first);
}

typedef struct roots_tally {
    long contact, contact_soft, free_pts, free_stiff;
} roots_tally;

/* On the net: a point whose tube touches a host or the ground (centre
 * within its radius + r / 4) has stiffness 1; one farther than its radius
 * + 3 r from every obstacle less than 1. */
static void roots_contact(const roots_net *net, const banyan_roots_params *p, roots_tally *t) {
    roots_wind rw;
    if (roots_wind_build(net, p, &rw)) {
        CHECK(0, "roots_wind_build: out of memory");
        return;
    }
    for (uint32_t i = 0; i < net->n_pts; i++) {
        double R = net->rad[i] > net->r ? net->rad[i] : net->r;
        double c = world_clearance_in(&net->w, net->pts[i], 1, HUGE_VAL, NULL, NULL);
        if (c <= R + 0.25 * net->r) t->contact++, t->contact_soft += rw.stiff[i] != 1.0;
        else if (c > R + 3 * net->r) t->free_pts++, t->free_stiff += !(rw.stiff[i] < 1.0);
    }
    roots_wind_free(&rw);
}

static void roots_one(const char *name, banyan_roots_params p, const banyan_box *boxes, uint32_t n_boxes,
                      const banyan_hosts *hs, roots_tally *t) {
    for (int surface = 0; surface < 2; surface++) {
        p.surface = surface ? BANYAN_ROOTS_FUSED : BANYAN_ROOTS_TUBES;
        char what[160];
        snprintf(what, sizeof what, "%s %s", name, surface ? "fused" : "tubes");
        roots_net net;
        banyan_error err;
        banyan_status st = hs ? roots_net_build_hosts(&p, hs, &net, &err) : roots_net_build(&p, boxes, n_boxes, &net, &err);
        CHECK(st == BANYAN_OK, "%s: %s", what, err.message);
        if (st) continue;
        banyan_mesh *m = NULL;
        st = roots_net_mesh(&net, &p, &m, NULL, &err);
        CHECK(st == BANYAN_OK && m, "%s: %s", what, err.message);
        if (m) roots_soil_line(&net, &p, m); /* as banyan_roots_generate does */
        if (m) {
            common_checks(what, m, NULL, 1);
            roots_per_root(what, m);
            const float *st_ = ATTR(m, BANYAN_ATTR_WIND_STIFFNESS);
            uint32_t soft = 0;
            for (uint32_t v = 0; st_ && v < m->vertex_count; v++) soft += st_[v] < 0.99f;
            printf("%-28s %8u vertices, %5.1f %% below stiffness 0.99\n", what, m->vertex_count,
                   100.0 * soft / m->vertex_count);
        }
        if (surface == 0) roots_contact(&net, &p, t);
        /* Same seed, same hash; wind 0 keeps birth and its values. */
        banyan_mesh *b = NULL, *c = NULL;
        banyan_roots_params q = p;
        st = hs ? banyan_roots_generate(&p, hs, &b, NULL, NULL, &err) : test_roots_boxes(&p, boxes, n_boxes, &b, &err);
        CHECK(st == BANYAN_OK && m && banyan_mesh_hash(b) == banyan_mesh_hash(m), "%s: not the same hash twice", what);
        q.wind = 0;
        st = hs ? banyan_roots_generate(&q, hs, &c, NULL, NULL, &err) : test_roots_boxes(&q, boxes, n_boxes, &c, &err);
        CHECK(st == BANYAN_OK && c, "%s wind 0: %s", what, err.message);
        if (c && m) {
            no_wind_checks(what, c);
            const float *b0 = ATTR(c, BANYAN_ATTR_BIRTH), *b1 = ATTR(m, BANYAN_ATTR_BIRTH);
            CHECK(c->vertex_count == m->vertex_count && b0 && b1 &&
                      !memcmp(b0, b1, sizeof(float) * m->vertex_count) &&
                      !memcmp(c->positions, m->positions, sizeof(float) * 3 * m->vertex_count),
                  "%s: wind 0 changes the mesh or its birth", what);
        }
        banyan_mesh_free(b);
        banyan_mesh_free(c);
        banyan_mesh_free(m);
        roots_net_free(&net);
    }
}

static void roots_box_preset(const char *path, const char *name, void *vt) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_box hosts[8];
    uint32_t n = 0;
    banyan_error err;
    banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, &p, path, hosts, 8, &n, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (!s) roots_one(name, p, hosts, n, NULL, vt);
}

static void roots_mesh_preset(const char *path, const char *name, void *vt) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_error err;
    banyan_hosts *hs = NULL;
    banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, &p, path, NULL, 0, NULL, &err);
    if (!s) s = test_load_host_set(path, &hs, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (!s) roots_one(name, p, NULL, 0, hs, vt);
    banyan_hosts_free(hs);
}

/* ---------------------------------------------------------------- ivy */

/* Skeleton points sorted by position, to find a bud by its pivot. */
static const float *sort_skel;
static int pt_cmp(const float *x, const float *y) {
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}
static int skel_cmp(const void *a, const void *b) {
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    int c = pt_cmp(sort_skel + 3 * (size_t)i, sort_skel + 3 * (size_t)j);
    return c ? c : (i < j ? -1 : i > j);
}
static int skel_key_cmp(const void *key, const void *b) {
    return pt_cmp(key, sort_skel + 3 * (size_t)*(const uint32_t *)b);
}

/* The checks of an ivy plant, with its handle for the buds. */
static void ivy_checks(const char *what, const banyan_ivy *iv, const banyan_mesh *m) {
    const float *part = ATTR(m, "part"), *bs = ATTR(m, "birth_step"), *bi = ATTR(m, BANYAN_ATTR_BIRTH);
    const float *fl = ATTR(m, BANYAN_ATTR_WIND_FLUTTER), *st = ATTR(m, BANYAN_ATTR_WIND_STIFFNESS);
    const float *lv = ATTR(m, BANYAN_ATTR_WIND_LEVEL), *px = ATTR(m, BANYAN_ATTR_WIND_PIVOT_X),
                *py = ATTR(m, BANYAN_ATTR_WIND_PIVOT_Y), *pz = ATTR(m, BANYAN_ATTR_WIND_PIVOT_Z);
    CHECK(part && bs && bi && fl && st && lv && px && py && pz, "%s: attributes missing", what);
    if (!part || !bs || !bi || !fl || !st || !lv || !px || !py || !pz) return;
    /* Contact holds an ivy stem at any level (a run alongside another,
     * a lateral on the wall): its stiffness follows hold, checked per leaf
     * below, and the means by level are printed only. */
    common_checks(what, m, part, 0);
    /* Flutter 1 on the stem part only on petioles: 6 vertices a leaf. */
    uint32_t blades = 0, stem_flutter = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        blades += part[v] > 0.5f;
        stem_flutter += part[v] < 0.5f && fl[v] > 0;
    }
    CHECK(stem_flutter * 13 == blades * 6, "%s: %u petiole vertices for %u blade vertices", what, stem_flutter,
          blades);
    /* Birth never falls as birth_step rises. */
    int32_t S = iv->step + 2;
    float *lo = malloc(sizeof(float) * S), *hi = malloc(sizeof(float) * S);
    for (int32_t s = 0; s < S; s++) lo[s] = 2, hi[s] = -1;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        int32_t s = (int32_t)bs[v];
        if (s < 0 || s >= S) continue;
        lo[s] = bi[v] < lo[s] ? bi[v] : lo[s];
        hi[s] = bi[v] > hi[s] ? bi[v] : hi[s];
    }
    float run = -1;
    int falls = -1;
    for (int32_t s = 0; s < S; s++) {
        if (hi[s] < 0) continue;
        if (lo[s] < run && falls < 0) falls = s;
        run = hi[s];
    }
    CHECK(falls < 0, "%s: birth falls at birth_step %d", what, falls);
    free(lo);
    free(hi);
    /* Leaves: the pivot is the bud's own skeleton point (bud i is
     * skeleton point i); stiffness 1 on a held bud, below on a free one. */
    long not_bud = 0, held_soft = 0, free_stiff = 0, held_n = 0, free_n = 0;
    uint32_t *ord = malloc(sizeof(uint32_t) * (m->skel_point_count + 1));
    for (uint32_t i = 0; i < m->skel_point_count; i++) ord[i] = i;
    sort_skel = m->skel_points;
    qsort(ord, m->skel_point_count, sizeof *ord, skel_cmp);
    const banyan_ivy_params *p = &iv->p;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        if (part[v] < 0.5f) continue;
        float key[3] = {px[v], py[v], pz[v]};
        const uint32_t *hit = bsearch(key, ord, m->skel_point_count, sizeof *ord, skel_key_cmp);
        int32_t found = hit ? (int32_t)*hit : -1;
        if (found < 0 || found >= iv->n) {
            not_bud++;
            continue;
        }
        const ivy_bud *b = &iv->buds[found];
        int held = b->attached || (p->ground && b->P.z <= p->ground_z + p->clearance + 1e-9);
        /* a free bud right next to its held parent may round to 1 */
        int far = 0;
        if (!held && b->parent >= 0) far = v3_dist(b->P, iv->buds[b->parent].P) > 1e-3;
        if (held) held_n++, held_soft += st[v] != 1.0f;
        else if (far) free_n++, free_stiff += !(st[v] < 1.0f);
    }
    free(ord);
    CHECK(not_bud == 0, "%s: %ld leaf vertices whose pivot is no bud", what, not_bud);
    CHECK(held_soft == 0 && free_stiff == 0,
          "%s: %ld of %ld leaf vertices on held buds below stiffness 1, %ld of %ld on free ones at 1", what, held_soft,
          held_n, free_stiff, free_n);
    printf("%-28s %8u vertices, leaf vertices %ld on held buds, %ld on free ones\n", what, m->vertex_count, held_n,
           free_n);
}

static void ivy_preset(const char *name, int32_t steps_cap) {
    char path[512];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    banyan_box hosts[8];
    uint32_t n = 0;
    banyan_error err;
    banyan_status s = test_load_preset(BANYAN_GEN_IVY, &p, path, hosts, 8, &n, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (s) return;
    if (steps_cap && p.steps > steps_cap) p.steps = steps_cap;
    banyan_hosts *H = TEST_HOSTS(hosts, n);
    /* The step API, in two calls, then the one-shot generation. */
    banyan_ivy *iv = NULL;
    banyan_mesh *m = NULL, *g = NULL, *c = NULL;
    s = banyan_ivy_create(&p, H, &iv, &err);
    if (!s) s = banyan_ivy_step(iv, p.steps / 3, &err);
    if (!s) s = banyan_ivy_step(iv, p.steps - p.steps / 3, &err);
    if (!s) s = banyan_ivy_mesh(iv, &m, &err);
    CHECK(s == BANYAN_OK && m, "%s: %s", name, err.message);
    if (m) ivy_checks(name, iv, m);
    s = banyan_ivy_generate(&p, H, &g, NULL, NULL, &err);
    CHECK(s == BANYAN_OK && g && m && banyan_mesh_hash(g) == banyan_mesh_hash(m),
          "%s: the step API's mesh is not the one-shot one (%s)", name, s ? err.message : "");
    banyan_mesh_free(g);
    g = NULL;
    s = banyan_ivy_generate(&p, H, &g, NULL, NULL, &err);
    CHECK(s == BANYAN_OK && g && m && banyan_mesh_hash(g) == banyan_mesh_hash(m), "%s: not the same hash twice",
          name);
    p.wind = 0;
    s = banyan_ivy_generate(&p, H, &c, NULL, NULL, &err);
    CHECK(s == BANYAN_OK && c, "%s wind 0: %s", name, err.message);
    if (c && m) {
        no_wind_checks(name, c);
        const float *b0 = ATTR(c, BANYAN_ATTR_BIRTH), *b1 = ATTR(m, BANYAN_ATTR_BIRTH);
        CHECK(c->vertex_count == m->vertex_count && b0 && b1 && !memcmp(b0, b1, sizeof(float) * m->vertex_count),
              "%s: wind 0 changes the mesh or its birth", name);
    }
    /* A young plant from the step API: a few steps, meshed as it grows. */
    banyan_ivy_free(iv);
    iv = NULL;
    p.wind = 1;
    s = banyan_ivy_create(&p, H, &iv, &err);
    for (int k = 0; k < 3 && !s; k++) {
        banyan_mesh *y = NULL;
        s = banyan_ivy_step(iv, 10, &err);
        if (!s) s = banyan_ivy_mesh(iv, &y, &err);
        CHECK(s == BANYAN_OK && y, "%s young: %s", name, err.message);
        char what[96];
        snprintf(what, sizeof what, "%s after %d steps", name, 10 * (k + 1));
        if (y) ivy_checks(what, iv, y);
        banyan_mesh_free(y);
    }
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
    banyan_mesh_free(m);
    banyan_mesh_free(g);
    banyan_mesh_free(c);
}

/* --------------------------------------------------------------- tube */

static void tube_checks(void) {
    enum { N = 24 };
    double pts[3 * N], rad[N];
    for (int i = 0; i < N; i++) {
        double t = (double)i / (N - 1);
        pts[3 * i] = 0.3 * sin(3 * t), pts[3 * i + 1] = 0.2 * t * t, pts[3 * i + 2] = 2.0 * t;
        rad[i] = 0.1 * (1.0 - 0.8 * t);
    }
    for (int caps = 0; caps < 2; caps++) {
        banyan_mesh *m = NULL, *b = NULL;
        banyan_error err;
        banyan_status s = banyan_tube_generate(pts, rad, N, 8, caps, &m, &err);
        CHECK(s == BANYAN_OK && m, "tube: %s", err.message);
        if (!m) continue;
        common_checks("tube", m, NULL, 1);
        const float *st = ATTR(m, BANYAN_ATTR_WIND_STIFFNESS), *bi = ATTR(m, BANYAN_ATTR_BIRTH),
                    *px = ATTR(m, BANYAN_ATTR_WIND_PIVOT_X), *py = ATTR(m, BANYAN_ATTR_WIND_PIVOT_Y),
                    *pz = ATTR(m, BANYAN_ATTR_WIND_PIVOT_Z), *lv = ATTR(m, BANYAN_ATTR_WIND_LEVEL);
        if (st && bi && px && py && pz && lv) {
            /* Rings of 9 vertices in point order: stiffness falls with the
             * radius, birth rises along; the pivot is point 0. */
            long bad = 0;
            for (uint32_t v = 0; v < N * 9u; v++) {
                uint32_t i = v / 9;
                bad += fabs(st[v] - sqrt(rad[i] / rad[0])) > 1e-6;
                if (i) bad += !(bi[v] > bi[v - 9]) || !(st[v] < st[v - 9]);
                bad += fabs(px[v] - pts[0]) > 1e-6 || fabs(py[v] - pts[1]) > 1e-6 || fabs(pz[v] - pts[2]) > 1e-6 ||
                       lv[v] != 0;
            }
            CHECK(bad == 0 && bi[0] == 0 && bi[N * 9 - 1] == 1, "tube: %ld ring values wrong", bad);
        }
        s = banyan_tube_generate(pts, rad, N, 8, caps, &b, &err);
        CHECK(s == BANYAN_OK && b && banyan_mesh_hash(b) == banyan_mesh_hash(m), "tube: not the same hash twice");
        banyan_mesh_free(b);
        banyan_mesh_free(m);
    }
}

int main(void) {
    tube_checks();

    /* Every shipped roots preset (box and mesh hosts), and the default. */
    roots_tally t;
    memset(&t, 0, sizeof t);
    {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        roots_one("default", p, &host, 1, NULL, &t);
    }
    int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "roots_", roots_box_preset, &t);
    n += test_each_mesh_preset(BANYAN_SOURCE_DIR "/presets", "roots_", roots_mesh_preset, &t);
    CHECK(n >= 5, "found %d presets/roots_*.json", n);
    printf("roots net points: %ld touching (%ld below stiffness 1), %ld free (%ld at 1)\n", t.contact,
           t.contact_soft, t.free_pts, t.free_stiff);
    CHECK(t.contact > 0 && t.contact_soft == 0, "roots: %ld of %ld touching points below stiffness 1", t.contact_soft,
          t.contact);
    CHECK(t.free_pts > 0 && t.free_stiff == 0, "roots: %ld of %ld free points at stiffness 1", t.free_stiff,
          t.free_pts);

    ivy_preset("ivy_wall", 0);
    ivy_preset("ivy_pillar", 0);
    return check_done("test_wind_roots_ivy");
}
