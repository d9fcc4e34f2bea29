/* shape.c - the tubes of a composed segment tree's mesh (docs/segments.md,
 * "Mesh and line set"): where each line's rings go and how thick they are.
 * The line set itself (the reference's lines) is not touched; only the
 * mesh is shaped:
 *
 * - Taper. A line's radius falls linearly from its nominal base radius
 *   rb to its tip radius rt = max(radius_min, SEG_TAPER rb) (never above
 *   rb). rb is the level's radius (radius x radius_ratio^code; the trunk:
 *   trunk_radius), but at most the parent's inner radius / SEG_FLARE,
 *   so a child is never thicker than where it leaves its parent, and
 *   never below radius_min. The inner radius is the parent's local
 *   radius x cos(pi / sides): what a polygonal ring of `sides` sides
 *   holds.
 * - Junction. The base ring sits on the parent's centre line with radius
 *   min(SEG_FLARE rb, the parent's inner radius): inside the parent, a
 *   little wider than the line, narrowing to the line's radius just
 *   outside the parent's surface (the exit ring), so the joint reads as
 *   grown. (Where both are at radius_min the base ring is the narrower,
 *   by at most cos(pi / sides), and hidden in the parent.)
 * - Closed tip. The tube ends in a dome of the tip radius: a ring of rt
 *   one rt before the tip, two rings on a quarter circle towards it, and
 *   the sweeper's end cap.
 * - Zigzag. A segment's axis bends at each twig's node D_i: the node is
 *   moved SEG_ZIGZAG x the node spacing sideways, towards the side its
 *   twig leaves (alternating with the twigs), so the axis kinks a few
 *   degrees there like a sympodial twig, the twig at the outer corner.
 *   The twig (and its forks) moves with its node; a segment attached to
 *   an axis moves with the point of that axis it starts on, and its
 *   children with it, so everything stays attached. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../base/vec.h"
#include "segment_core.h"

#define SEG_TAPER 0.5   /* tip radius / base radius of every line */
#define SEG_FLARE 1.3   /* base ring radius / the line's base radius */
#define SEG_ZIGZAG 0.02 /* node offset / node spacing: about 4.6 degrees of turn per node */
#define SEG_EXIT_SHARE 0.25 /* the exit ring lies within this share of the line (of the axis's first node) */

static const double dome_sin[SEG_DOME_RINGS] = {0.7660444431189780, 0.9848077530122080}; /* 50, 80 degrees */
static const double dome_cos[SEG_DOME_RINGS] = {0.6427876096865394, 0.1736481776669303};

int seg_tube_points(int line, int twigs) {
    if (line < 0) return 2 + SEG_DOME_RINGS;              /* trunk: base, dome start, dome */
    return 3 + SEG_DOME_RINGS + (line == 0 ? twigs : 0); /* base, exit, [nodes], dome start, dome */
}

static double tip_of(double rb, double radius_min) {
    double rt = SEG_TAPER * rb;
    rt = rt > radius_min ? rt : radius_min;
    return rt < rb ? rt : rb;
}

/* Nominal base radius of a line of level radius r_level leaving a parent
 * of inner radius rp (rp <= 0: no parent), never below radius_min (a
 * parent is never thinner than that either). */
static double base_of(double r_level, double rp, double radius_min) {
    double rb = rp > 0 && rp / SEG_FLARE < r_level ? rp / SEG_FLARE : r_level;
    return rb > radius_min ? rb : radius_min;
}

/* Base ring radius of a line of base radius rb in a parent of inner
 * radius rp (rp <= 0: none). */
static double flare_of(double rb, double rp) {
    return rp > 0 ? fmin(SEG_FLARE * rb, rp) : rb;
}

/* Sideways move of segment s's node i (1..n): towards its twig,
 * perpendicular to the axis. */
static v3 node_offset(const seg_shaper *sh, const banyan_segment_input *s, int i) {
    v3 C = v3_norm(v3_load(s->A));
    double sa = (i & 1) ? sh->sa : -sh->sa;
    v3 F = v3_make(sh->ca * C.x - sa * C.y, sa * C.x + sh->ca * C.y, C.z);
    v3 perp = v3_madd(F, C, -v3_dot(F, C));
    double len = v3_len(perp);
    if (len < 1e-6) return v3_make(0, 0, 0); /* a vertical axis: the twigs run along it */
    return v3_scale(perp, SEG_ZIGZAG * s->l / (s->n + 1) / len);
}

/* The axis's sideways move at parameter t in [0, 1]: 0 at both ends,
 * linear between the nodes. */
static v3 axis_offset(const seg_shaper *sh, const banyan_segment_input *s, double t) {
    int n = s->n;
    if (n == 0) return v3_make(0, 0, 0);
    double x = (t < 0 ? 0 : t > 1 ? 1 : t) * (n + 1);
    int i = (int)floor(x);
    if (i > n) i = n;
    double f = x - i;
    v3 a = i >= 1 ? node_offset(sh, s, i) : v3_make(0, 0, 0);
    v3 b = i + 1 <= n ? node_offset(sh, s, i + 1) : v3_make(0, 0, 0);
    return v3_lerp(a, b, f);
}

/* Parameter of p's foot on the line a + (b - a) t, clamped to [0, 1]. */
static double foot_t(v3 p, v3 a, v3 b) {
    v3 ab = v3_sub(b, a);
    double L2 = v3_len2(ab), t = L2 > 0 ? v3_dot(v3_sub(p, a), ab) / L2 : 0;
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

static double lerp(double a, double b, double t) { return a + (b - a) * t; }

int seg_shaper_init(seg_shaper *sh, const banyan_segments_params *p, const banyan_segment_input *segs,
                    uint32_t count, const double *trunk, const int32_t *parent) {
    memset(sh, 0, sizeof *sh);
    sh->p = p;
    sh->segs = segs;
    sh->trunk = trunk;
    sh->ca = dm_cos(deg2rad(p->alpha_deg));
    sh->sa = dm_sin(deg2rad(p->alpha_deg));
    sh->inner = dm_cos(BANYAN_PI / p->sides);
    sh->shift = malloc(sizeof(v3) * (count ? count : 1));
    sh->rb = malloc(sizeof(double) * 2 * (count ? count : 1));
    if (!sh->shift || !sh->rb) {
        seg_shaper_free(sh);
        return 1;
    }
    sh->rt = sh->rb + count;
    sh->trunk_rb = p->trunk_radius;
    sh->trunk_rt = tip_of(p->trunk_radius, p->radius_min);
    double r_axis = seg_level_radius(p->radius, p->radius_ratio, p->radius_min, BANYAN_SEGMENT_LEVEL_AXIS);
    for (uint32_t i = 0; i < count; i++) {
        const banyan_segment_input *s = &segs[i];
        v3 S = v3_load(s->S);
        int32_t q = parent[i];
        double rp = 0;
        sh->shift[i] = v3_make(0, 0, 0);
        if (q >= 0) { /* on axis q: move with that point of it */
            const banyan_segment_input *a = &segs[q];
            v3 A0 = v3_load(a->S), A1 = v3_madd(A0, v3_norm(v3_load(a->A)), a->l);
            double t = foot_t(S, A0, A1);
            sh->shift[i] = v3_add(sh->shift[q], axis_offset(sh, a, t));
            rp = sh->inner * lerp(sh->rb[q], sh->rt[q], t);
        } else if (q == -1) {
            rp = sh->inner * lerp(sh->trunk_rb, sh->trunk_rt, foot_t(S, v3_load(trunk), v3_load(trunk + 3)));
        }
        sh->rb[i] = base_of(r_axis, rp, p->radius_min);
        sh->rt[i] = tip_of(sh->rb[i], p->radius_min);
    }
    sh->parent = parent;
    return 0;
}

void seg_shaper_free(seg_shaper *sh) {
    free(sh->shift);
    free(sh->rb);
    sh->shift = NULL;
    sh->rb = sh->rt = NULL;
}

/* Fills the rings of one line a -> b (moved by w): base ring of radius
 * rf, the exit ring (past the parent's inner radius rp and the line's
 * own, at most t_cap along), the axis's nodes (axis != NULL: they move
 * by the axis's offsets on top of w), the dome. */
static void line_rings(const seg_shaper *sh, seg_tube *tb, v3 a, v3 b, v3 w, const banyan_segment_input *axis,
                       double rf, double rp, double t_cap) {
    double L = v3_dist(a, b), rb = tb->rb, rt = tb->rt;
    int k = 0;
#define RING(T, R)                                                                                                  \
    do {                                                                                                            \
        double t_ = (T);                                                                                            \
        v3 o_ = axis ? v3_add(w, axis_offset(sh, axis, t_)) : w;                                                    \
        tb->c[k] = v3_add(v3_lerp(a, b, t_), o_);                                                                   \
        tb->r[k] = (R);                                                                                             \
        tb->s[k] = t_ * L;                                                                                          \
        k++;                                                                                                        \
    } while (0)
    RING(0.0, rf);
    double te = L > 0 ? (rp + rb) / L : 0;
    te = te < t_cap ? te : t_cap;
    RING(te, lerp(rb, rt, te));
    double t_prev = te;
    for (int i = 1; axis && i <= axis->n; i++) {
        t_prev = (double)i / (axis->n + 1);
        RING(t_prev, lerp(rb, rt, t_prev));
    }
    double td = L > rt ? 1 - rt / L : 0;
    td = td > t_prev ? td : t_prev;
    RING(td, rt);
    for (int d = 0; d < SEG_DOME_RINGS; d++) RING(td + (1 - td) * dome_sin[d], rt * dome_cos[d]);
#undef RING
    tb->n = k;
}

void seg_shaper_trunk(const seg_shaper *sh, seg_tube *tb) {
    v3 a = v3_load(sh->trunk), b = v3_load(sh->trunk + 3);
    double L = v3_dist(a, b), rt = sh->trunk_rt;
    tb->rb = sh->trunk_rb;
    tb->rt = rt;
    tb->parent = -2;
    int k = 0;
    double td = L > rt ? 1 - rt / L : 0;
    double ts[2 + SEG_DOME_RINGS] = {0, td}, rs[2 + SEG_DOME_RINGS] = {sh->trunk_rb, rt};
    for (int d = 0; d < SEG_DOME_RINGS; d++) ts[2 + d] = td + (1 - td) * dome_sin[d], rs[2 + d] = rt * dome_cos[d];
    for (k = 0; k < 2 + SEG_DOME_RINGS; k++) {
        tb->c[k] = v3_lerp(a, b, ts[k]);
        tb->r[k] = rs[k];
        tb->s[k] = ts[k] * L;
    }
    tb->n = k;
}

void seg_shaper_line(const seg_shaper *sh, uint32_t i, const float *xyz, const uint8_t *lev, const uint8_t *par,
                     const seg_tube *tubes, int j, seg_tube *tb) {
    const banyan_segments_params *p = sh->p;
    const banyan_segment_input *s = &sh->segs[i];
    v3 a = v3_make(xyz[6 * j], xyz[6 * j + 1], xyz[6 * j + 2]);
    v3 b = v3_make(xyz[6 * j + 3], xyz[6 * j + 4], xyz[6 * j + 5]);
    if (j == 0) { /* the axis, on its parent axis, the trunk, or free */
        int32_t q = sh->parent[i];
        double rp = 0;
        if (q >= 0) {
            const banyan_segment_input *ps = &sh->segs[q];
            v3 A0 = v3_load(ps->S), A1 = v3_madd(A0, v3_norm(v3_load(ps->A)), ps->l);
            rp = sh->inner * lerp(sh->rb[q], sh->rt[q], foot_t(a, A0, A1));
        } else if (q == -1) {
            rp = sh->inner * lerp(sh->trunk_rb, sh->trunk_rt, foot_t(a, v3_load(sh->trunk), v3_load(sh->trunk + 3)));
        }
        tb->rb = sh->rb[i];
        tb->rt = sh->rt[i];
        tb->parent = q == -2 ? -2 : -1; /* another tube of the tree, not of this segment */
        line_rings(sh, tb, a, b, sh->shift[i], s, flare_of(tb->rb, rp), rp, SEG_EXIT_SHARE / (s->n + 1));
        return;
    }
    /* A twig or fork: moved with its twig's node; leaves line par[j]. */
    int root = j;
    while (root > s->n) root = par[root];
    v3 w = v3_add(sh->shift[i], node_offset(sh, s, root));
    int q = par[j];
    const seg_tube *pt = &tubes[q];
    v3 qa = v3_make(xyz[6 * q], xyz[6 * q + 1], xyz[6 * q + 2]), qb = v3_make(xyz[6 * q + 3], xyz[6 * q + 4], xyz[6 * q + 5]);
    double rp = sh->inner * lerp(pt->rb, pt->rt, foot_t(a, qa, qb));
    double r_level = seg_level_radius(p->radius, p->radius_ratio, p->radius_min, lev[2 * j]);
    tb->rb = base_of(r_level, rp, p->radius_min);
    tb->rt = tip_of(tb->rb, p->radius_min);
    tb->parent = q;
    line_rings(sh, tb, a, b, w, NULL, flare_of(tb->rb, rp), rp, SEG_EXIT_SHARE);
}
