/* crown_mesh.c - the keyaki crown's grown twigs and leaves into the mesh
 * (and the twigs into the skeleton). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "mesh/tube.h"
#include "textures/leaf_look.h"
#include "crown_internal.h"

void keyaki_crown_skel_counts(const keyaki_crown *c, uint64_t *points, uint64_t *edges) {
    /* A first-order twig: its points, its edges and one joining it along
     * its branch; a sub-twig starts on a point of its parent's. */
    uint64_t p = 0, e = 0;
    for (int32_t t = 0; t < c->n_twigs; t++) {
        int32_t k = c->twigs[t].count, first = c->twigs[t].parent < 0;
        p += (uint64_t)(k - 1 + first);
        e += (uint64_t)(k - 1 + first);
    }
    *points = p;
    *edges = e;
}

void keyaki_crown_mesh_twigs(const keyaki_crown *c, mesh_builder *mb, const int attr[3], const keyaki_wind *w) {
    mb_set_attr(mb, attr[2], 0); /* order 0: finer than any skeleton branch */
    /* Skeleton: point k >= 1 of twig t is skel[t] + k; point 0 is skel0[t]. */
    uint32_t *skel = w ? malloc(sizeof(uint32_t) * 2 * ((size_t)c->n_twigs + 1)) : NULL;
    if (w && !skel) {
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    uint32_t *skel0 = skel ? skel + c->n_twigs + 1 : NULL;
    for (int32_t t = 0; t < c->n_twigs && !mb->status; t++) {
        if ((t & 1023) == 0 && keyaki_stopped(c->run)) {
            mb->status = BANYAN_E_CANCELLED;
            break;
        }
        const keyaki_twig *T = &c->twigs[t];
        const v3 *P = c->pts + T->first;
        const double *R = c->rad + T->first;
        mb_set_attr(mb, attr[1], T->level);
        uint32_t first = mb->nv;
        double ph = 0;
        int32_t level = 0;
        if (w) {
            /* A branch of its own: pivot its base on the parent, level its
             * branch's wind level + its order. */
            level = w->level[T->node] + (T->level - w->n[T->node].level);
            ph = wind_phase_of(w->seed, KEYAKI_PHASE_TWIG + (uint64_t)t);
            wind_set(mb, w->ws, P[0], level, 1, ph, 0); /* stiffness: from the birth, later */
        }
        /* A twig tip's end is hidden in its last leaves: no cap. */
        tube_opts o = {T->sides, 0, T->children > 0, {0, 0, 0}, 0.0, NULL, 0, 1}; /* a twig: one bark tile round */
        tube_sweep(mb, P, R, (uint32_t)T->count, &o);
        keyaki_bark_smooth(mb, first, 1); /* a twig's own smooth bark */
        if (!w || mb->status) continue;
        /* Per ring: birth by path length (stiffness follows from it). */
        double bt[MAX_TWIG_PTS];
        for (int32_t k = 0; k < T->count; k++) bt[k] = k ? bt[k - 1] + v3_dist(P[k - 1], P[k]) : T->path0;
        wind_tube_rings(mb, first, (uint32_t)T->count, T->sides, 0, T->children > 0, w->ws->birth, bt);
        /* Skeleton: a first-order twig joined along its branch from the
         * branch's start; a sub-twig from its parent's point it leaves. */
        int32_t tag = T->level | KEYAKI_SKEL_TWIG;
        uint32_t from;
        if (T->parent < 0) {
            from = keyaki_skel_start(w, T->node);
            skel0[t] = mb_skel_point(mb, P[0], R[0], tag);
            mb_skel_edge(mb, from, skel0[t]);
        } else {
            const keyaki_twig *U = &c->twigs[T->parent];
            const v3 *Q = c->pts + U->first;
            int32_t best = 0;
            double bd = HUGE_VAL;
            for (int32_t k = 0; k < U->count; k++) {
                double d = v3_dist(Q[k], P[0]);
                if (d < bd) bd = d, best = k;
            }
            skel0[t] = best == 0 ? skel0[T->parent] : skel[T->parent] + (uint32_t)best;
        }
        skel[t] = mb->n_skel - 1;
        for (int32_t k = 1; k < T->count; k++) {
            uint32_t a = k == 1 ? skel0[t] : mb->n_skel - 1;
            uint32_t b = mb_skel_point(mb, P[k], R[k], tag);
            mb_skel_edge(mb, a, b);
        }
    }
    free(skel);
}

void keyaki_crown_mesh_leaves(const banyan_keyaki_params *p, const keyaki_crown *c, mesh_builder *mb,
                              const int attr[3], const keyaki_wind *w, int32_t k0, int32_t k1, keyaki_run *run) {
    int32_t cols = 1, rows = 1;
    leaf_atlas_grid(BANYAN_TEX_KEYAKI_LEAF, &cols, &rows, NULL);
    const int keyaki_atlas = cols == 4 && rows == 4; /* the spray row's layout (leaf_look.h) */
    mb_set_attr(mb, attr[2], 0);
    const double hu = LEAF_KEYAKI_HALF_U;
    if (k1 > c->n_leaves) k1 = c->n_leaves;
    for (int32_t k = k0; k < k1 && !mb->status; k++) {
        if ((k & 4095) == 0 && keyaki_stopped(run)) {
            mb->status = BANYAN_E_CANCELLED;
            return;
        }
        const keyaki_leaf *q = &c->leaves[k];
        mb_set_attr(mb, attr[1], q->level);
        if (w) {
            /* Pivot the petiole base, on its wood; level that wood's + 1;
             * birth its path, delayed when the tree is done; stiffness the
             * wood's there (from the undelayed birth, when the tree is done). */
            double ph = wind_phase_of(w->seed, KEYAKI_PHASE_LEAF + (uint64_t)k);
            if ((float)ph >= 1.0f) ph = 0.0; /* stored as a float: one turn is none */
            wind_set(mb, w->ws, q->base, w->level[q->node] + (q->level - w->n[q->node].level) + 1, 1, ph, 1);
            if (w->ws->birth >= 0) mb_set_attr(mb, w->ws->birth, q->path);
        }
        uint32_t v0 = mb_vertices(mb, 4);
        uint32_t *I = mb_indices(mb, 6);
        if (v0 == UINT32_MAX || !I) return;
        leaf_look lk;
        if (keyaki_atlas) leaf_look_keyaki(p->seed, (uint64_t)k, q->card, p->season, &lk);
        else leaf_look_of(p->seed, (uint64_t)k, cols, rows, p->season, &lk);
        v3 nrm = v3_cross(q->width, q->axis);
        if (q->card) {
            /* A spray cell: u along the twig (the card's axis), v across. */
            double hw = 0.5 * q->length / LEAF_KEYAKI_SPRAY_ASPECT;
            v3 o = v3_madd(q->base, q->axis, -LEAF_KEYAKI_SPRAY_U0 * q->length);
            v3 p0 = v3_madd(o, q->width, -hw), p1 = v3_madd(o, q->width, hw);
            v3 p2 = v3_madd(p1, q->axis, q->length), p3 = v3_madd(p0, q->axis, q->length);
            double u1 = lk.u0 + lk.du, v1 = lk.v0 + lk.dv;
            mb_put(mb, v0, p0, nrm, lk.u0, lk.v0);
            mb_put(mb, v0 + 1, p1, nrm, lk.u0, v1);
            mb_put(mb, v0 + 2, p2, nrm, u1, v1);
            mb_put(mb, v0 + 3, p3, nrm, u1, lk.v0);
        } else {
            double hw = hu * q->length; /* the quad's width: 2 HALF_U x its length */
            v3 p0 = v3_madd(q->base, q->width, -hw), p1 = v3_madd(q->base, q->width, hw);
            v3 p2 = v3_madd(p1, q->axis, q->length), p3 = v3_madd(p0, q->axis, q->length);
            double ua = lk.u0 + lk.du * (0.5 - hu), ub = lk.u0 + lk.du * (0.5 + hu), v1 = lk.v0 + lk.dv;
            mb_put(mb, v0, p0, nrm, ua, lk.v0);
            mb_put(mb, v0 + 1, p1, nrm, ub, lk.v0);
            mb_put(mb, v0 + 2, p2, nrm, ub, v1);
            mb_put(mb, v0 + 3, p3, nrm, ua, v1);
        }
        for (uint32_t j = 0; j < 4 && mb->with_color; j++)
            for (int m = 0; m < 4; m++) mb->col[4 * ((size_t)v0 + j) + m] = (float)lk.tint[m];
        I[0] = v0; I[1] = v0 + 1; I[2] = v0 + 2;
        I[3] = v0; I[4] = v0 + 2; I[5] = v0 + 3;
    }
}
