/* Ivy geometry (spec/ivy.md, "Geometry"). Stems: the bud tree split into
 * chains (the first bud's stem, then each lateral branch from its dormant
 * bud), each swept as one tube through the shared sweeper with radius
 * r = r0 + k * age, capped. Leaves: one leaf-shaped card per bud (the
 * leaf of the internode that ends there), a three-lobed Boston ivy outline
 * fanned from its centre, sized by age, on alternating sides, facing away
 * from the nearest host surface, or up and out when the stem hangs free;
 * its uvs fit the outline into one cell of the ivy leaf atlas and its
 * vertex colour is a per-leaf tint (leaf_look.h).
 * Every vertex carries `birth_step` (the step its bud was created) and
 * `part` (0 stem, 1 leaf). */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/leaf_look.h"
#include "core/mesh_builder.h"
#include "core/tube.h"
#include "ivy_internal.h"

#define LEAF_OUTLINE 12 /* outline points; the card has LEAF_OUTLINE + 1 vertices */

/* Outline angles from the leaf tip (radians, increasing): the notch, the
 * base, the side lobe, the sinus, the tip's shoulder and the tip. */
static const double leaf_angle[LEAF_OUTLINE] = {-BANYAN_PI, -2.5, -1.85, -1.25, -0.75, -0.35,
                                               0.0,        0.35, 0.75,  1.25,  1.85,  2.5};

/* Leaf outline radius at angle th from the tip (th = 0), per unit of leaf
 * diameter: a tip lobe, two side lobes at +-72 deg and a notch where the
 * petiole joins (th = pi). */
static double leaf_radius(double th) {
    double a = fabs(th);
    double r = 0.22 + 0.28 * exp(-(a / 0.32) * (a / 0.32)) + 0.22 * exp(-((a - 1.25) / 0.32) * ((a - 1.25) / 0.32)) +
               0.08 * exp(-((a - 2.2) / 0.4) * ((a - 2.2) / 0.4)) - 0.12 * exp(-((a - BANYAN_PI) / 0.25) * ((a - BANYAN_PI) / 0.25));
    return 1.1 * r;
}

uint64_t ivy_mesh_vertex_floor(const banyan_ivy_params *p, int64_t n) {
    uint64_t per_bud = (uint64_t)p->stem_sides + 1 + (p->leaves ? LEAF_OUTLINE + 1 : 0);
    return (uint64_t)(n > 0 ? n : 0) * per_bud;
}

/* Points of the chain starting at bud s; returns the count. */
static uint32_t chain_points(const banyan_ivy *iv, int32_t s, int32_t *out) {
    uint32_t n = 0;
    int32_t par = iv->buds[s].parent;
    if (par >= 0 && iv->buds[par].child[1] == s) out[n++] = par;
    for (int32_t j = s; j >= 0; j = iv->buds[j].child[0]) out[n++] = j;
    return n;
}

static int chain_start(const banyan_ivy *iv, int32_t i) {
    int32_t par = iv->buds[i].parent;
    return par < 0 || iv->buds[par].child[1] == i;
}

/* Progress of the mesh of a one-shot generation: stems then leaves, by
 * bud, every 256 buds, from iv->mesh_from to 1. Returns 1 once cancelled. */
static int mesh_progress(const banyan_ivy *iv, int32_t i, double half) {
    if (!iv->prog || (i & 255)) return 0;
    return prog_at(iv->prog, iv->mesh_from + (1.0 - iv->mesh_from) * 0.5 * (half + (double)i / iv->n));
}

banyan_status banyan_ivy_mesh(const banyan_ivy *iv, banyan_mesh **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    if (!iv) return banyan_fail(err, BANYAN_E_INVALID_ARG, "ivy is NULL");
    const banyan_ivy_params *p = &iv->p;
    const int sides = p->stem_sides;

    /* Size first: refuse before allocating the mesh. */
    int32_t *pts = malloc(sizeof(int32_t) * ((size_t)iv->n + 1));
    if (!pts) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    uint64_t need_v = 0, need_i = 0;
    uint32_t max_pts = 2;
    for (int32_t i = 0; i < iv->n; i++) {
        if (!chain_start(iv, i)) continue;
        uint32_t n = chain_points(iv, i, pts), v, ix;
        if (n < 2) n = 2; /* a lone bud gets a stub */
        if (n > max_pts) max_pts = n;
        tube_counts(n, sides, iv->buds[i].parent < 0, 1, &v, &ix);
        need_v += v;
        need_i += ix;
    }
    if (p->leaves) {
        need_v += (uint64_t)iv->n * (LEAF_OUTLINE + 1);
        need_i += (uint64_t)iv->n * LEAF_OUTLINE * 3;
    }
    /* need_v >= ivy_mesh_vertex_floor(p, iv->n): the floor must stay a floor. */
    if (need_v > (uint64_t)p->max_vertices) {
        free(pts);
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the ivy mesh needs %llu vertices, over max_vertices = %d; raise max_vertices or lower "
                           "steps or stem_sides",
                           (unsigned long long)need_v, p->max_vertices);
    }
    v3 *P = malloc(sizeof(v3) * max_pts);
    double *R = malloc(sizeof(double) * max_pts);
    float *birth = malloc(sizeof(float) * max_pts);
    if (!P || !R || !birth) {
        free(pts); free(P); free(R); free(birth);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }

    mesh_builder mb;
    mb_init(&mb, (uint32_t)p->max_vertices, 1); /* colours: white stems, tinted leaves */
    int a_birth = mb_add_attr(&mb, "birth_step"), a_part = mb_add_attr(&mb, "part");
    uint32_t m_stem = mb_add_material(&mb, "ivy_stem", p->stem_color, 0.85, 0);
    uint32_t m_leaf = mb_add_material(&mb, "ivy_leaf", p->leaf_color, 0.6, 1);
    if (!mb.status) {
        bark_material_set(&mb.mat[m_stem], BANYAN_TEX_IVY_STEM);
        leaf_material_set(&mb.mat[m_leaf], BANYAN_TEX_IVY_LEAF, p->season, p->leaf_color);
    }
    /* The whole mesh at once: no copies as the arrays grow. */
    mb_reserve(&mb, (uint32_t)need_v, need_i > UINT32_MAX ? UINT32_MAX : (uint32_t)need_i);

    /* Stems. */
    mb_begin_part(&mb, m_stem, 0);
    mb_set_attr(&mb, a_part, 0.0);
    int cancelled = 0;
    for (int32_t i = 0; i < iv->n && !mb.status; i++) {
        if (mesh_progress(iv, i, 0.0)) {
            cancelled = 1;
            break;
        }
        if (!chain_start(iv, i)) continue;
        uint32_t n = chain_points(iv, i, pts);
        const ivy_bud *s = &iv->buds[i];
        for (uint32_t k = 0; k < n; k++) {
            const ivy_bud *b = &iv->buds[pts[k]];
            P[k] = b->P;
            /* A branch's base ring sits in its parent and appears with it. */
            const ivy_bud *own = (k == 0 && pts[0] != i) ? s : b;
            R[k] = ivy_stem_radius(iv, own);
            birth[k] = (float)own->step_c;
        }
        if (n == 1) { /* a lone first bud: a short stub along its direction */
            P[1] = v3_madd(P[0], s->V, 2.0 * R[0]);
            R[1] = R[0];
            birth[1] = birth[0];
            n = 2;
        }
        tube_opts o;
        memset(&o, 0, sizeof o); /* fields the sweeper may gain stay zero */
        o.sides = sides;
        o.cap_start = s->parent < 0;
        o.cap_end = 1;
        o.first_normal = ivy_nearest_any(iv, s->P).normal;
        uint32_t first = mb.nv;
        tube_sweep(&mb, P, R, n, &o);
        if (mb.status) break;
        /* Rings come first (sides + 1 vertices each), then the caps. */
        float *attr = mb.attr[a_birth];
        uint32_t ring = (uint32_t)sides + 1, k = 0;
        for (; k < n; k++)
            for (uint32_t j = 0; j < ring; j++) attr[first + k * ring + j] = birth[k];
        uint32_t v = first + n * ring;
        if (o.cap_start)
            for (uint32_t j = 0; j < ring + 1; j++) attr[v++] = birth[0];
        for (; v < mb.nv; v++) attr[v] = birth[n - 1];
    }

    /* Leaves. */
    if (p->leaves && !mb.status && !cancelled) {
        mb_begin_part(&mb, m_leaf, 0);
        mb_set_attr(&mb, a_part, 1.0);
        pcg32 rng;
        pcg32_seed(&rng, p->seed, 0x1eaf);
        const v3 up = v3_make(0, 0, 1);
        double rnotch = leaf_radius(BANYAN_PI);
        double rad[LEAF_OUTLINE], ox[LEAF_OUTLINE], oy[LEAF_OUTLINE];
        for (int k = 0; k < LEAF_OUTLINE; k++) {
            rad[k] = leaf_radius(leaf_angle[k]);
            ox[k] = rad[k] * cos(leaf_angle[k]); /* the outline, per unit of leaf diameter */
            oy[k] = rad[k] * sin(leaf_angle[k]);
        }
        /* Card uvs: the outline's bounds fill the blade's box in one atlas
         * cell (leaf_look.h), the basal lobes low, the tip at the top, as
         * the atlas draws its leaves. */
        double ymax = 0, xmin = 0, xmax = 0;
        for (int k = 0; k < LEAF_OUTLINE; k++) {
            if (fabs(oy[k]) > ymax) ymax = fabs(oy[k]);
            if (ox[k] < xmin) xmin = ox[k];
            if (ox[k] > xmax) xmax = ox[k];
        }
        double ou[LEAF_OUTLINE + 1], ov[LEAF_OUTLINE + 1]; /* the centre, then the outline, in 0..1 */
        const double bv = LEAF_IVY_BLADE_V1 - LEAF_IVY_BLADE_V0;
        ou[0] = 0.5;
        ov[0] = LEAF_IVY_BLADE_V0 + bv * -xmin / (xmax - xmin);
        for (int k = 0; k < LEAF_OUTLINE; k++) {
            ou[k + 1] = 0.5 + LEAF_IVY_BLADE_HALF_U * oy[k] / ymax;
            ov[k + 1] = LEAF_IVY_BLADE_V0 + bv * (ox[k] - xmin) / (xmax - xmin);
        }
        int32_t cols, rows;
        leaf_atlas_grid(BANYAN_TEX_IVY_LEAF, &cols, &rows, NULL);
        const double reach = p->sucker_length > p->internode ? p->sucker_length : p->internode;
        for (int32_t i = 0; i < iv->n && !mb.status; i++) {
            if (mesh_progress(iv, i, 1.0)) {
                cancelled = 1;
                break;
            }
            const ivy_bud *b = &iv->buds[i];
            double jitter = rng_range(&rng, -0.35, 0.35); /* one draw per bud: leaves keep their look as the plant grows */
            double d = ivy_leaf_diameter(iv, b) * p->leaf_scale;
            if (!(d > 0)) continue;
            ivy_near nr = ivy_nearest_any(iv, b->P);
            double w = (nr.dist - p->sucker_length) / (4.0 * reach);
            w = w < 0 ? 0 : (w > 1 ? 1 : w);
            v3 free_n = v3_norm(v3_add(v3_scale(nr.normal, 0.5), up)); /* up and out */
            v3 n = v3_norm_or(v3_lerp(nr.normal, free_n, w), nr.normal);
            v3 t = b->parent >= 0 ? v3_norm_or(v3_sub(b->P, iv->buds[b->parent].P), b->V) : b->V;
            v3 side = v3_norm_or(v3_cross(n, t), v3_any_perp(n));
            if (!b->L) side = v3_neg(side);
            v3 t_in = v3_norm_or(v3_sub(t, v3_scale(n, v3_dot(n, t))), v3_cross(side, n));
            v3 a = v3_rotate(v3_norm(v3_madd(side, t_in, 0.7)), n, jitter);
            a = v3_norm_or(v3_sub(a, v3_scale(n, v3_dot(n, a))), side);
            v3 bb = v3_cross(n, a);
            v3 base = v3_madd(b->P, n, p->leaf_lift);
            v3 c = v3_madd(base, a, rnotch * d);
            mb_set_attr(&mb, a_birth, (double)b->step_c);
            uint32_t vc = mb_vertices(&mb, LEAF_OUTLINE + 1);
            uint32_t *I = mb_indices(&mb, 3 * LEAF_OUTLINE);
            if (!I) break;
            float *pos = mb.pos + 3 * (size_t)vc, *nrm = mb.nrm + 3 * (size_t)vc, *uv = mb.uv + 2 * (size_t)vc;
            float *col = mb.col + 4 * (size_t)vc; /* the builder was made with colours */
            const float fn[3] = {(float)n.x, (float)n.y, (float)n.z};
            leaf_look lk; /* by bud: a leaf keeps its look as the plant grows */
            leaf_look_of(p->seed, (uint64_t)i, cols, rows, p->season, &lk);
            const float tint[4] = {(float)lk.tint[0], (float)lk.tint[1], (float)lk.tint[2], (float)lk.tint[3]};
            for (int k = 0; k <= LEAF_OUTLINE; k++, pos += 3, nrm += 3, uv += 2, col += 4) {
                /* The centre, then the outline. */
                v3 q = k ? v3_madd(v3_madd(c, a, ox[k - 1] * d), bb, oy[k - 1] * d) : c;
                pos[0] = (float)q.x; pos[1] = (float)q.y; pos[2] = (float)q.z;
                memcpy(nrm, fn, sizeof fn);
                uv[0] = (float)(lk.u0 + ou[k] * lk.du);
                uv[1] = (float)(lk.v0 + ov[k] * lk.dv);
                memcpy(col, tint, sizeof tint);
            }
            for (uint32_t k = 0; k < LEAF_OUTLINE; k++, I += 3) {
                I[0] = vc;
                I[1] = vc + 1 + k;
                I[2] = vc + 1 + (k + 1) % LEAF_OUTLINE;
            }
        }
    }

    /* Skeleton: one point per bud, one edge per internode. */
    for (int32_t i = 0; i < iv->n && !mb.status; i++)
        mb_skel_point(&mb, iv->buds[i].P, ivy_stem_radius(iv, &iv->buds[i]), iv->buds[i].state);
    for (int32_t i = 0; i < iv->n && !mb.status; i++)
        if (iv->buds[i].parent >= 0) mb_skel_edge(&mb, (uint32_t)iv->buds[i].parent, (uint32_t)i);

    free(pts); free(P); free(R); free(birth);
    if (cancelled) {
        mb_free(&mb);
        return prog_fail(err, "ivy mesh");
    }
    return mb_finish(&mb, out, err);
}
