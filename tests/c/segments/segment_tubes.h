/* segment_tubes.h - the tubes of a composed segment tree as the composer
 * lays them out (csrc/segments/shape.c), for tests that look at each
 * tube's rings in the mesh: every line of the tree in mesh order (trunk
 * first), its shape, its parent line, whether it got a tube and where its
 * vertices start. Built in the mesh's own frame (segments moved by
 * m->origin), as banyan_segments_generate builds it. */
#ifndef BANYAN_TEST_SEGMENT_TUBES_H
#define BANYAN_TEST_SEGMENT_TUBES_H

#include <stdlib.h>

#include "banyan.h"
#include "mesh/tube.h"
#include "segments/segment_core.h"

typedef struct plan_tube {
    seg_tube t;
    int32_t parent; /* the line it leaves, index into plan.tubes; -1 none */
    int meshed;     /* got a tube (line >= 1e-9 m) */
    uint32_t first; /* its first mesh vertex */
    int level;      /* level code, -1 the trunk */
} plan_tube;

typedef struct seg_plan {
    plan_tube *tubes;
    uint32_t n, vertices, indices;
} seg_plan;

static inline int seg_plan_make(const banyan_segments_params *p, const banyan_segment_input *segs, uint32_t count,
                                const double *trunk, const banyan_mesh *m, seg_plan *pl) {
    banyan_segment_input *loc = malloc(sizeof *loc * (count ? count : 1));
    int32_t *parent = malloc(sizeof *parent * (count ? count : 1));
    uint32_t *base = malloc(sizeof *base * (count ? count : 1));
    uint64_t lines = trunk ? 1 : 0;
    for (uint32_t i = 0; i < count; i++) lines += (uint64_t)banyan_segment_vertex_count(segs[i].n, segs[i].s) / 2;
    pl->tubes = calloc(lines ? lines : 1, sizeof *pl->tubes);
    pl->n = pl->vertices = pl->indices = 0;
    double tl[6];
    for (uint32_t i = 0; i < count; i++) {
        loc[i] = segs[i];
        for (int c = 0; c < 3; c++) loc[i].S[c] -= m->origin[c];
    }
    for (int c = 0; trunk && c < 6; c++) tl[c] = trunk[c] - m->origin[c % 3];
    const double *tr = trunk ? tl : NULL;
    banyan_status st;
    seg_attach_parents(loc, count, tr, p->attach_tolerance, 0, parent, NULL, &st, NULL);
    seg_shaper sh;
    banyan_segment_params sp;
    seg_params_from_tree(p, &sp);
    seg_consts k;
    if (!loc || !parent || !base || !pl->tubes || st || seg_consts_make(&sp, p->unit, &k, NULL) ||
        seg_shaper_init(&sh, p, loc, count, tr, parent)) {
        free(loc), free(parent), free(base);
        return 1;
    }
    float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
    uint8_t lev[BANYAN_SEGMENT_MAX_VERTICES], par[BANYAN_SEGMENT_MAX_VERTICES / 2];
    seg_tube *tubes = malloc(sizeof *tubes * (BANYAN_SEGMENT_MAX_VERTICES / 2));
    uint32_t tv, ti;
    if (tr) {
        plan_tube *t = &pl->tubes[pl->n++];
        seg_shaper_trunk(&sh, &t->t);
        t->parent = -1, t->meshed = 1, t->first = 0, t->level = -1;
        tube_counts((uint32_t)t->t.n, p->sides, 0, 1, &tv, &ti);
        pl->vertices += tv, pl->indices += ti;
    }
    for (uint32_t i = 0; i < count; i++) {
        int nv = seg_run_tree(&k, &loc[i], xyz, lev, par);
        base[i] = pl->n;
        for (int j = 0; j < nv / 2; j++) {
            seg_shaper_line(&sh, i, xyz, lev, par, tubes, j, &tubes[j]);
            plan_tube *t = &pl->tubes[pl->n++];
            t->t = tubes[j];
            t->level = lev[2 * j];
            t->parent = j ? (int32_t)(base[i] + par[j]) : parent[i] >= 0 ? (int32_t)base[parent[i]] : parent[i] == -1 ? 0 : -1;
            v3 a = v3_make(xyz[6 * j], xyz[6 * j + 1], xyz[6 * j + 2]), b = v3_make(xyz[6 * j + 3], xyz[6 * j + 4], xyz[6 * j + 5]);
            t->meshed = v3_dist(a, b) >= 1e-9;
            t->first = pl->vertices;
            if (!t->meshed) continue;
            tube_counts((uint32_t)t->t.n, p->sides, 0, 1, &tv, &ti);
            pl->vertices += tv, pl->indices += ti;
        }
    }
    seg_shaper_free(&sh);
    free(tubes), free(loc), free(parent), free(base);
    return 0;
}

static inline void seg_plan_free(seg_plan *pl) {
    free(pl->tubes);
    pl->tubes = NULL;
    pl->n = 0;
}

/* Mesh position of vertex v. */
static inline v3 plan_vertex(const banyan_mesh *m, uint32_t v) {
    return v3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
}

/* Centroid and mean radius of ring k of a tube in the mesh (its `sides`
 * vertices, the seam's copy left out). */
static inline v3 plan_ring(const banyan_mesh *m, const plan_tube *t, int sides, int k, double *radius) {
    uint32_t v0 = t->first + (uint32_t)k * (uint32_t)(sides + 1);
    v3 c = v3_make(0, 0, 0);
    for (int j = 0; j < sides; j++) c = v3_add(c, plan_vertex(m, v0 + (uint32_t)j));
    c = v3_scale(c, 1.0 / sides);
    double r = 0;
    for (int j = 0; j < sides; j++) r += v3_dist(plan_vertex(m, v0 + (uint32_t)j), c);
    *radius = r / sides;
    return c;
}

#endif
