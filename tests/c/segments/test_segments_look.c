/* The look of a composed segment tree's mesh (docs/segments.md, "Mesh and
 * line set"), on presets/segments_paper.json, segments_bushy.json and
 * demo trees, measured on the mesh's rings (segment_tubes.h, beside this
 * file, gives where each tube's rings are):
 * - taper: every tube above radius_min narrows to its tip; ring radii never grow from a tube's exit ring (where it
 *   leaves its parent's surface) to its tip, and a child's base and exit
 *   rings are no wider than its parent's ring radius where it leaves it;
 * - closed tips: with positions welded, the only open edges are the base
 *   rings' (one open ring per tube);
 * - junctions: every vertex of a child's base ring lies inside its
 *   parent's polygonal tube (within its inner radius of its centre line);
 * - bark colours: no vertex is green-dominant (green never above red);
 * - the reference's per-segment vertex counts of segments_paper stay
 *   116 / 114 / 128, and the same input gives the same bytes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "segment_tubes.h"
#include "test_files.h"

/* Radius of tube t's mesh at the point of its centre line nearest q
 * (rings linearly between ring centres); *dist gets q's distance to that
 * line, *s the arc length there. */
static double radius_near(const banyan_mesh *m, const plan_tube *t, int sides, v3 q, double *dist, double *s) {
    double best = HUGE_VAL, r_at = 0, s_at = 0, rp, acc = 0;
    v3 cp = plan_ring(m, t, sides, 0, &rp);
    for (int k = 1; k < t->t.n; k++) {
        double rk;
        v3 ck = plan_ring(m, t, sides, k, &rk), d = v3_sub(ck, cp);
        double L2 = v3_len2(d), u = L2 > 0 ? v3_dot(v3_sub(q, cp), d) / L2 : 0;
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        double e = v3_dist(q, v3_madd(cp, d, u));
        if (e < best) best = e, r_at = rp + (rk - rp) * u, s_at = acc + u * sqrt(L2);
        acc += sqrt(L2);
        cp = ck, rp = rk;
    }
    *dist = best;
    *s = s_at;
    return r_at;
}

typedef struct look_counts {
    int grow, flat, thick, open_tip, poke, green, checked_joints;
} look_counts;

/* Position key for welding: the three floats' bits. */
typedef struct wkey { float x, y, z; uint32_t id; } wkey;
static int wkey_cmp(const void *a, const void *b) {
    const wkey *p = a, *q = b;
    int c = memcmp(&p->x, &q->x, 12);
    return c ? c : (p->id > q->id) - (p->id < q->id);
}

static int edge_cmp(const void *a, const void *b) {
    uint64_t p = *(const uint64_t *)a, q = *(const uint64_t *)b;
    return (p > q) - (p < q);
}

/* Open edges (welded by position) that are not on a base ring. */
static int open_edges_off_bases(const banyan_mesh *m, const seg_plan *pl, int sides, uint32_t *open_total) {
    uint32_t nv = m->vertex_count;
    wkey *k = malloc(sizeof *k * nv);
    uint32_t *weld = malloc(sizeof *weld * nv);
    for (uint32_t v = 0; v < nv; v++) {
        memcpy(&k[v].x, m->positions + 3 * v, 12);
        k[v].id = v;
    }
    qsort(k, nv, sizeof *k, wkey_cmp);
    for (uint32_t i = 0; i < nv; i++) weld[k[i].id] = i && !memcmp(&k[i].x, &k[i - 1].x, 12) ? weld[k[i - 1].id] : k[i].id;
    /* Edges as sorted welded pairs; an open edge appears once. */
    uint32_t ne = m->index_count;
    uint64_t *e = malloc(sizeof *e * ne);
    uint32_t n = 0;
    for (uint32_t t = 0; t + 2 < m->index_count; t += 3)
        for (int c = 0; c < 3; c++) {
            uint32_t a = weld[m->indices[t + c]], b = weld[m->indices[t + (c + 1) % 3]];
            if (a == b) continue;
            e[n++] = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
        }
    qsort(e, n, sizeof *e, edge_cmp);
    /* The base ring's welded ids. */
    char *base = calloc(nv, 1);
    for (uint32_t i = 0; i < pl->n; i++)
        if (pl->tubes[i].meshed)
            for (int j = 0; j <= sides; j++) base[weld[pl->tubes[i].first + (uint32_t)j]] = 1;
    int bad = 0;
    *open_total = 0;
    for (uint32_t i = 0; i < n;) {
        uint32_t j = i;
        while (j < n && e[j] == e[i]) j++;
        if (j - i == 1) {
            (*open_total)++;
            if (!base[e[i] >> 32] || !base[e[i] & 0xffffffffu]) bad++;
        }
        i = j;
    }
    free(k), free(weld), free(e), free(base);
    return bad;
}

static void check_look(const banyan_segments_params *p, const banyan_segment_input *segs, uint32_t count,
                       const double *trunk, const char *what) {
    banyan_error err;
    banyan_mesh *m = NULL, *m2 = NULL;
    CHECK(banyan_segments_generate(p, segs, count, trunk, &m, NULL, NULL, &err) == BANYAN_OK, "%s: %s", what,
          err.message);
    CHECK(banyan_segments_generate(p, segs, count, trunk, &m2, NULL, NULL, &err) == BANYAN_OK &&
              banyan_mesh_hash(m) == banyan_mesh_hash(m2),
          "%s: same input, same bytes", what);
    banyan_mesh_free(m2);
    if (!m) return;
    seg_plan pl;
    int sides = p->sides;
    CHECK(seg_plan_make(p, segs, count, trunk, m, &pl) == 0 && pl.vertices == m->vertex_count, "%s: layout", what);
    look_counts c = {0};
    uint32_t tubes = 0;
    for (uint32_t i = 0; i < pl.n && pl.vertices == m->vertex_count; i++) {
        const plan_tube *t = &pl.tubes[i];
        if (!t->meshed) continue;
        tubes++;
        double r_prev, r, r0, r1;
        v3 c0 = plan_ring(m, t, sides, 0, &r0);
        plan_ring(m, t, sides, 1, &r1);
        r_prev = r1;
        for (int k = 2; k < t->t.n; k++) {
            plan_ring(m, t, sides, k, &r);
            if (r > r_prev * 1.002 + 1e-7 && getenv("LOOK_DEBUG"))
                fprintf(stderr, "grow tube %u ring %d/%d: %g > %g (plan %g %g) level %d\n", i, k, t->t.n, r, r_prev,
                        t->t.r[k], t->t.r[k - 1], t->level);
            if (r > r_prev * 1.002 + 1e-7) c.grow++;
            r_prev = r;
        }
        /* It tapers: the last whole ring (the dome's start) is narrower
         * than the exit ring (the trunk: its base), unless the tube is at radius_min. */
        double r_last;
        plan_ring(m, t, sides, t->t.n - 1 - SEG_DOME_RINGS, &r_last);
        double r_from = t->level < 0 ? r0 : r1; /* the trunk has no exit ring */
        if (!(r_last < r_from * 0.999) && r_from > p->radius_min * 1.01) c.flat++;
        if (t->parent < 0 || !pl.tubes[t->parent].meshed) continue;
        const plan_tube *pt = &pl.tubes[t->parent];
        double dist, s;
        double rp = radius_near(m, pt, sides, c0, &dist, &s);
        if (r0 > rp * 1.002 + 1e-7 && getenv("LOOK_DEBUG"))
            fprintf(stderr, "thick tube %u (parent %d): %g > %g at s %g dist %g, level %d\n", i, t->parent, r0, rp, s,
                    dist, t->level);
        /* Where the parent's rings are whole, before its dome (a child on
         * the dome, the last tip radius of its parent, goes on from it). */
        if (s > pt->t.s[pt->t.n - 1 - SEG_DOME_RINGS]) continue;
        if (fmax(r0, r1) > rp * 1.002 + 1e-7) c.thick++;
        c.checked_joints++;
        for (int j = 0; j < sides; j++) {
            v3 q = plan_vertex(m, t->first + (uint32_t)j);
            double rq = radius_near(m, pt, sides, q, &dist, &s);
            if (dist > rq * dm_cos(BANYAN_PI / sides) + p->attach_tolerance + 1e-6) c.poke++;
        }
    }
    uint32_t open = 0;
    c.open_tip = open_edges_off_bases(m, &pl, sides, &open);
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *col = m->colors + 4 * v;
        if (col[1] > col[0]) c.green++;
    }
    CHECK(c.grow == 0, "%s: %d rings wider than the ring before them", what, c.grow);
    CHECK(c.flat == 0, "%s: %d tubes thicker than radius_min that do not taper", what, c.flat);
    CHECK(c.thick == 0, "%s: %d children wider at their base than their parent there", what, c.thick);
    CHECK(c.open_tip == 0 && open == tubes * (uint32_t)sides, "%s: %d open edges off the bases, %u open in all for %u tubes",
          what, c.open_tip, open, tubes);
    CHECK(c.checked_joints > 0 && c.poke == 0, "%s: %d base-ring vertices outside their parent (%d joints)", what,
          c.poke, c.checked_joints);
    CHECK(c.green == 0, "%s: %d green-dominant vertices", what, c.green);
    seg_plan_free(&pl);
    banyan_mesh_free(m);
}

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    banyan_error err;
    enum { CAP = 4096 };
    banyan_segment_input *segs = malloc(sizeof *segs * CAP);
    double trunk[6];
    int32_t has_trunk = 0;
    uint32_t n = 0;
    const char *names[2] = {"segments_paper", "segments_bushy"};
    for (int f = 0; f < 2; f++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, names[f]);
        banyan_segments_params p;
        banyan_segments_params_init(&p);
        size_t len = 0;
        char *text = test_read_file(path, &len);
        CHECK(text && banyan_preset_apply(BANYAN_GEN_SEGMENTS, &p, text, len, path, &err) == BANYAN_OK,
              "%s: %s", path, err.message);
        CHECK(banyan_segments_preset_read(text, len, path, segs, CAP, &n, trunk, &has_trunk, &err) == BANYAN_OK,
              "%s segments: %s", path, err.message);
        free(text);
        if (n == 0) {
            CHECK(banyan_segments_demo(&p, segs, CAP, &n, trunk, &err) == BANYAN_OK, "%s demo", path);
            has_trunk = 1;
        }
        if (f == 0) { /* the reference's per-segment counts of the paper's chain */
            CHECK(n == 3 && banyan_segment_vertex_count(segs[0].n, segs[0].s) == 116 &&
                      banyan_segment_vertex_count(segs[1].n, segs[1].s) == 114 &&
                      banyan_segment_vertex_count(segs[2].n, segs[2].s) == 128,
                  "segments_paper: vertex counts 116 / 114 / 128");
            banyan_segment_params sp;
            banyan_segment_params_init(&sp);
            sp.m = p.m * p.unit;
            float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
            int32_t got[3] = {0};
            for (uint32_t i = 0; i < n && i < 3; i++) banyan_segment_lines(&segs[i], &sp, xyz, NULL, &got[i], &err);
            CHECK(got[0] == 116 && got[1] == 114 && got[2] == 128, "segments_paper: generated %d / %d / %d", got[0],
                  got[1], got[2]);
        }
        check_look(&p, segs, n, has_trunk ? trunk : NULL, names[f]);
    }
    /* Demo trees of other seeds and sides, and one without a trunk. */
    banyan_segments_params p;
    for (int trial = 0; trial < 4; trial++) {
        banyan_segments_params_init(&p);
        p.seed = (uint64_t)trial + 11;
        p.demo_segments = 80;
        p.sides = 3 + 3 * trial;
        CHECK(banyan_segments_demo(&p, segs, CAP, &n, trunk, &err) == BANYAN_OK, "demo %d", trial);
        char what[64];
        snprintf(what, sizeof what, "demo seed %d sides %d%s", trial + 11, p.sides, trial == 3 ? " no trunk" : "");
        check_look(&p, segs, n, trial == 3 ? NULL : trunk, what);
    }
    free(segs);
    return check_done("test_segments_look");
}
