/* twigs.c - a keyaki whose finest levels are geometry-shader segments
 * (spec/segments.md, "Composing a tree": "place segments along the outer
 * branches of a keyaki skeleton, so that the fine twigs come from the
 * shader"). Enabled by twigs_from_segments.
 *
 * The skeleton is grown to levels - segment_levels (growth.c stops early,
 * so it is the first nodes of the full tree). Every tip of it is the axis
 * of one segment: S = the branch start, A = its direction, l = its length,
 * n = segment_twigs, s = segment_depth, the paper's angles and
 * m = segment_twig_length * unit. The CPU reference
 * (banyan_segment_lines) gives the lines; the twig and fork lines are
 * meshed as thin closed tubes with the segment composer's tube code
 * (seg_line_tube, seg_level_radius) into the bark part. The axis line is
 * not meshed: it is the branch's own tube. Every S is the start of its
 * branch, so every segment is attached to the skeleton by construction.
 *
 * Thickness. The full tree is grown and its pipe-model radii set before
 * the cut (growth.c), so trunk and limbs keep the thickness of the plain
 * tree and an outer branch keeps the radius r of the subtree it stands
 * for. It tapers to tip_taper * r like any tip; a line of level code
 * c >= 1 (twig 1, fork depth d: 1 + d) has radius
 * tip_taper * r * 2^(-(c - 1) / pipe_exponent) (the pipe model's halving
 * per fork), never less than tip_taper * tip_radius, the end radius of a
 * plain tree's tip. Tubes have sides_min sides.
 *
 * Wind (docs/keyaki.md "Wind and growth attributes"): each line is a
 * branch with its pivot at its start (on the axis, or on the line it
 * forks from), level = its tip branch's wind level + its level code; the
 * lines join the mesh's skeleton (two points and a joining edge along
 * the line they leave, then the line itself). */
#include <math.h>

#include "base/error.h"
#include "mesh/tube.h"
#include "keyaki_internal.h"
#include "segments/segment_ref.h"

void keyaki_truncate(keyaki_skeleton *sk, int max_level) {
    int32_t count = 0;
    while (count < sk->count && sk->nodes[count].level <= max_level) count++;
    for (int32_t i = 0; i < count; i++) {
        keyaki_node *x = &sk->nodes[i];
        if (x->level < max_level) continue;
        x->child[0] = x->child[1] = -1;
        x->flags &= ~(uint32_t)KN_BROKEN;
    }
    sk->count = count;
}

void keyaki_twig_params(const banyan_keyaki_params *p, banyan_segment_params *sp) {
    banyan_segment_params_init(sp);
    sp->m = p->segment_twig_length * p->unit;
}

void keyaki_twig_input(const banyan_keyaki_params *p, const keyaki_node *x, banyan_segment_input *in) {
    in->S[0] = x->start.x;
    in->S[1] = x->start.y;
    in->S[2] = x->start.z;
    in->A[0] = x->dir.x;
    in->A[1] = x->dir.y;
    in->A[2] = x->dir.z;
    in->l = x->length;
    in->n = p->segment_twigs;
    in->s = p->segment_depth;
}

double keyaki_twig_radius(const banyan_keyaki_params *p, const keyaki_node *x, int level_code) {
    double r_end = x->radius * p->tip_taper, r_min = p->tip_radius * p->unit * p->tip_taper;
    return seg_level_radius(r_end, dm_pow(2.0, -1.0 / p->pipe_exponent), r_min, level_code - 1);
}

static int is_tip(const keyaki_node *x) { return x->child[0] < 0 && x->child[1] < 0; }

void keyaki_twigs_plan(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, uint64_t *vertices,
                       uint64_t *indices, uint64_t *all_lines) {
    *vertices = *indices = *all_lines = 0;
    if (!p->twigs_from_segments) return;
    uint64_t tips = 0;
    for (int32_t i = 0; i < count; i++) tips += is_tip(&n[i]);
    /* Every segment has the same n and s, hence the same line count; every
     * twig and fork line is m long (>= 1e-6 m), so each gets its tube. */
    uint64_t lines = (uint64_t)(banyan_segment_vertex_count(p->segment_twigs, p->segment_depth) / 2 - 1);
    uint32_t tv, ti;
    tube_counts(2, p->sides_min, 0, 1, &tv, &ti);
    *vertices = tips * lines * tv;
    *indices = tips * lines * ti;
    *all_lines = tips * lines;
}

int32_t keyaki_twig_lines(const banyan_keyaki_params *p, const keyaki_node *x, double path_x, float *xyz,
                          uint8_t *level, uint8_t *parent, double *path) {
    banyan_segment_params sp;
    keyaki_twig_params(p, &sp);
    banyan_segment_input in;
    keyaki_twig_input(p, x, &in);
    seg_consts k;
    if (seg_consts_make(&sp, 1.0, &k, NULL) || seg_check_input(&in, "", NULL)) return 0;
    int32_t nv = seg_run_tree(&k, &in, xyz, level, parent);
    for (int32_t j = 0; j < nv; j += 2) {
        int q = parent[j / 2];
        v3 a = v3_make(xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]);
        v3 qa = v3_make(xyz[6 * q], xyz[6 * q + 1], xyz[6 * q + 2]);
        path[j / 2] = j == 0 ? path_x : path[q] + v3_dist(a, qa);
    }
    return nv;
}

void keyaki_twigs_mesh(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, mesh_builder *mb,
                       const int attr[3], const keyaki_wind *w) {
    if (!p->twigs_from_segments) return;
    float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
    uint8_t lev[BANYAN_SEGMENT_MAX_VERTICES], par[BANYAN_SEGMENT_MAX_VERTICES / 2];
    double path[BANYAN_SEGMENT_MAX_VERTICES / 2];
    uint32_t start[BANYAN_SEGMENT_MAX_VERTICES / 2]; /* each line's first skeleton point */
    mb_set_attr(mb, attr[2], 0); /* order 0: finer than any skeleton branch */
    for (int32_t i = 0; i < count && !mb->status; i++) {
        if (!is_tip(&n[i])) continue;
        int32_t nv = keyaki_twig_lines(p, &n[i], w ? w->path[i] : 0.0, xyz, lev, par, path);
        if (nv == 0) {
            mb->status = BANYAN_E_INTERNAL;
            return;
        }
        for (int32_t j = 2; j < nv; j += 2) { /* line 0 is the axis: the branch itself */
            v3 a = v3_make(xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]);
            v3 b = v3_make(xyz[3 * j + 3], xyz[3 * j + 4], xyz[3 * j + 5]);
            double r = keyaki_twig_radius(p, &n[i], lev[j]);
            mb_set_attr(mb, attr[1], n[i].level + lev[j]);
            uint32_t first = mb->nv;
            if (w) wind_set(mb, w->ws, a, w->level[i] + lev[j], 1, /* stiffness: from the birth, later */
                            wind_phase_of(w->seed, KEYAKI_PHASE_LINE + (uint64_t)i * 64 + (uint64_t)(j / 2)), 0);
            seg_line_tube(mb, a, b, r, p->sides_min);
            keyaki_bark_smooth(mb, first, 1); /* a twig's own smooth bark */
            if (!w) continue;
            double bt[2] = {path[j / 2], path[j / 2] + v3_dist(a, b)};
            wind_tube_rings(mb, first, 2, p->sides_min, 0, 1, w->ws->birth, bt);
            /* Skeleton: the line, joined along the line it leaves. */
            int q = par[j / 2];
            uint32_t from = q == 0 ? keyaki_skel_start(w, i) : start[q];
            int32_t tag = (n[i].level + lev[j]) | KEYAKI_SKEL_TWIG;
            start[j / 2] = mb_skel_point(mb, a, r, tag);
            mb_skel_point(mb, b, r, tag);
            mb_skel_edge(mb, from, start[j / 2]);
            mb_skel_edge(mb, start[j / 2], start[j / 2] + 1);
        }
    }
}
