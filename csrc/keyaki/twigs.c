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
 * (banyan_segment_generate) gives the lines; the twig and fork lines are
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
 * plain tree's tip. Tubes have sides_min sides. */
#include <math.h>

#include "core/error.h"
#include "core/tube.h"
#include "keyaki_internal.h"
#include "segments/segment_core.h"

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
    return seg_level_radius(r_end, pow(2.0, -1.0 / p->pipe_exponent), r_min, level_code - 1);
}

static int is_tip(const keyaki_node *x) { return x->child[0] < 0 && x->child[1] < 0; }

void keyaki_twigs_plan(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, uint64_t *vertices,
                       uint64_t *indices) {
    *vertices = *indices = 0;
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
}

void keyaki_twigs_mesh(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, mesh_builder *mb,
                       const int attr[3]) {
    if (!p->twigs_from_segments) return;
    banyan_segment_params sp;
    keyaki_twig_params(p, &sp);
    float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
    uint8_t lev[BANYAN_SEGMENT_MAX_VERTICES];
    mb_set_attr(mb, attr[2], 0); /* order 0: finer than any skeleton branch */
    for (int32_t i = 0; i < count && !mb->status; i++) {
        if (!is_tip(&n[i])) continue;
        banyan_segment_input in;
        keyaki_twig_input(p, &n[i], &in);
        int32_t nv = 0;
        if (banyan_segment_generate(&in, &sp, xyz, lev, &nv, NULL)) {
            mb->status = BANYAN_E_INTERNAL;
            return;
        }
        for (int32_t j = 2; j < nv; j += 2) { /* line 0 is the axis: the branch itself */
            v3 a = v3_make(xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]);
            v3 b = v3_make(xyz[3 * j + 3], xyz[3 * j + 4], xyz[3 * j + 5]);
            mb_set_attr(mb, attr[1], n[i].level + lev[j]);
            seg_line_tube(mb, a, b, keyaki_twig_radius(p, &n[i], lev[j]), p->sides_min);
        }
    }
}
