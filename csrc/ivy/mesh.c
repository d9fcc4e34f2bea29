/* Ivy geometry (spec/ivy.md, "Geometry"). Stems: the bud tree split into
 * chains (the first bud's stem, then each lateral branch from its dormant
 * bud), each swept as one tube through the shared sweeper with radius
 * r = r0 + k * age, capped. Leaves: one leaf per bud (the leaf of the
 * internode that ends there), as Boston ivy shows them (reference
 * plants.md section 2): a petiole, a thin three-sided tube in the stem
 * part, from the bud out from the surface to the blade's base; the blade a
 * three-lobed outline fanned from its centre, folded a little along the
 * midrib, sized by age (young small, old large), turned off the surface
 * towards the sky with its tip hanging down and out, kept `clearance` off
 * every surface; up and out when the stem hangs free. Its uvs fit the
 * outline into one cell of the ivy leaf atlas (a young, bronze cell while
 * the leaf is young) and its vertex colour is a per-leaf tint
 * (leaf_look.h). Per-leaf choices come
 * from a PCG32 stream of the leaf's own, so the growth is not disturbed.
 * Every vertex carries `birth_step` (the step its bud was created) and
 * `part` (0 stem and petiole, 1 leaf blade), and the wind and birth
 * attributes (mesh/wind.h; docs/ivy.md "Wind and growth attributes"):
 * birth = birth_step / the last bud's (a leaf half a step later); a
 * chain's pivot is its first point (a lateral's parent bud), its level the
 * number of laterals from a first bud; a stem held by its suckers or lying
 * on the ground has stiffness 1, a free one softens with the arc length
 * from its last held bud as exp(-s / (IVY_WIND_REACH internode)), but
 * never below 0.9 sqrt(r / r_max) (r its radius by age, r_max the
 * thickest's), every generator's wood stiffness kept below 1: old stems
 * sway less. A leaf
 * and its petiole sway about their bud with its stiffness, level + 1,
 * flutter 1, a phase of their own. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/platform.h"
#include "textures/leaf_look.h"
#include "mesh/mesh_builder.h"
#include "base/noise.h"
#include "hosts/obb.h"
#include "base/pool.h"
#include "mesh/tube.h"
#include "mesh/wind.h"
#include "ivy_internal.h"

#define LEAF_OUTLINE 12 /* outline points; the card has LEAF_OUTLINE + 1 vertices */
#define PETIOLE_SIDES 3 /* a petiole is two rings of 3, no caps: 1 mm across, a triangle reads as round */
#define PETIOLE_VERTS (2 * PETIOLE_SIDES)
#define LEAF_FOLD 0.25  /* rad each half of a blade turns up about the midrib: a flat card reads as paper */
/* The leaf material's roughness: Boston ivy's upper side is glossy (a
 * waxy cuticle, plants.md), where ivy_stem's bark is 0.85. One glTF
 * material shades both sides alike; the add-on gives the underside its
 * own rougher, paler look (blender_addon/banyan/materials.py). */
#define IVY_LEAF_ROUGHNESS 0.35
#define LEAF_STREAM 0x1eaf5e7cULL /* the blade's own stream, apart from leaf_look's */
#define CLUMP_SALT 0xc1d3bULL     /* the clumps' noise and the keep draws */
#define IVY_YOUNG_STEPS 12         /* a leaf this many steps old leaves the atlas's young (bronze) cells */
#define FRAY_SALT 0xf4a7e0ULL      /* the frayed edges' noise */
#define EDGE_LEAN 1.5              /* a petiole at the edge leans out this much (the rest of its direction is unit) */
#define RELIEF_STEP 0.5  /* the relief is read over steps of this x the largest blade */
#define IVY_WIND_REACH 8.0 /* a free stem softens over this many internodes from its last hold */
#define IVY_WIND_LEAF 0x1eaf0000000ULL /* leaves' phase ids, apart from the stems' (bud numbers) */

/* Outline angles from the leaf tip (radians, increasing): the notch, the
 * base, the side lobe, the sinus, the tip's shoulder and the tip. */
static const double leaf_angle[LEAF_OUTLINE] = {-BANYAN_PI, -2.5, -1.85, -1.25, -0.75, -0.35,
                                               0.0,        0.35, 0.75,  1.25,  1.85,  2.5};

/* Leaf outline radius at angle th from the tip (th = 0), per unit of leaf
 * diameter: a tip lobe, two side lobes at +-72 deg and a notch where the
 * petiole joins (th = pi). */
static double leaf_radius(double th) {
    double a = fabs(th);
    double r = 0.22 + 0.28 * dm_exp(-(a / 0.32) * (a / 0.32)) + 0.22 * dm_exp(-((a - 1.25) / 0.32) * ((a - 1.25) / 0.32)) +
               0.08 * dm_exp(-((a - 2.2) / 0.4) * ((a - 2.2) / 0.4)) - 0.12 * dm_exp(-((a - BANYAN_PI) / 0.25) * ((a - BANYAN_PI) / 0.25));
    return 1.1 * r;
}

/* The blade outline, its uvs and the shape constants, shared by all leaves. */
typedef struct leaf_shape {
    double ox[LEAF_OUTLINE], oy[LEAF_OUTLINE]; /* outline per unit of blade size (its largest extent) */
    double ou[LEAF_OUTLINE + 1], ov[LEAF_OUTLINE + 1]; /* the centre, then the outline, in 0..1 of a cell */
    double rnotch, reach; /* centre to notch, centre to the farthest point, per unit of size */
} leaf_shape;

static void leaf_shape_init(leaf_shape *sh) {
    double ext = 0;
    for (int k = 0; k < LEAF_OUTLINE; k++) {
        double r = leaf_radius(leaf_angle[k]);
        sh->ox[k] = r * dm_cos(leaf_angle[k]);
        sh->oy[k] = r * dm_sin(leaf_angle[k]);
    }
    for (int k = 0; k < LEAF_OUTLINE; k++)
        for (int j = k + 1; j < LEAF_OUTLINE; j++)
            ext = fmax(ext, dm_hypot(sh->ox[k] - sh->ox[j], sh->oy[k] - sh->oy[j]));
    /* Per unit of extent: `size` is what one would measure across the side lobes. */
    sh->reach = 0;
    for (int k = 0; k < LEAF_OUTLINE; k++) {
        sh->ox[k] /= ext;
        sh->oy[k] /= ext;
        sh->reach = fmax(sh->reach, dm_hypot(sh->ox[k], sh->oy[k]));
    }
    sh->rnotch = leaf_radius(BANYAN_PI) / ext;
    /* Card uvs: the outline's bounds fill the blade's box in one atlas
     * cell (leaf_look.h), the basal lobes low, the tip at the top, as
     * the atlas draws its leaves. */
    double ymax = 0, xmin = 0, xmax = 0;
    for (int k = 0; k < LEAF_OUTLINE; k++) {
        if (fabs(sh->oy[k]) > ymax) ymax = fabs(sh->oy[k]);
        if (sh->ox[k] < xmin) xmin = sh->ox[k];
        if (sh->ox[k] > xmax) xmax = sh->ox[k];
    }
    const double bv = LEAF_IVY_BLADE_V1 - LEAF_IVY_BLADE_V0;
    sh->ou[0] = 0.5;
    sh->ov[0] = LEAF_IVY_BLADE_V0 + bv * -xmin / (xmax - xmin);
    for (int k = 0; k < LEAF_OUTLINE; k++) {
        sh->ou[k + 1] = 0.5 + LEAF_IVY_BLADE_HALF_U * sh->oy[k] / ymax;
        sh->ov[k + 1] = LEAF_IVY_BLADE_V0 + bv * (sh->ox[k] - xmin) / (xmax - xmin);
    }
}

/* One leaf as placed. */
typedef struct leaf_geo {
    v3 base;       /* the blade's base (the outline's notch): the petiole's end */
    v3 c;          /* the blade's centre (the fan's hub) */
    v3 a, bb, nb;  /* tip direction, across (nb x a), blade normal */
    double size;   /* largest extent, m */
    int ok;        /* 0: no leaf (zero size, or no room clear of the hosts) */
} leaf_geo;

/* Outline point (x, y) per unit of size, the halves folded up by tf. */
static inline v3 leaf_vertex(const leaf_geo *g, double x, double y, double tf) {
    return v3_madd(v3_madd(v3_madd(g->c, g->a, x * g->size), g->bb, y * g->size), g->nb, fabs(y) * tf * g->size);
}

static double petiole_radius(const banyan_ivy_params *p) { return 0.6 * p->stem_radius; }

/* Moves the blade by d (its petiole follows: it ends at base). */
static void leaf_shift(leaf_geo *g, v3 d) {
    g->base = v3_add(g->base, d);
    g->c = v3_add(g->c, d);
}

/* Deepest a blade vertex reaches into the `margin` around the nearest
 * surface (<= 0: none), with that surface's normal. A point whose centre
 * is clear by the blade's reach needs no vertex query (distance is
 * 1-Lipschitz). */
static double leaf_intrusion(const banyan_ivy *iv, const leaf_geo *g, const leaf_shape *sh, double margin, v3 *dir) {
    const double tf = dm_tan(LEAF_FOLD);
    double worst = 0;
    if (!iv->n_mesh) {
        /* Boxes only: the distance alone per point (ivy_nearest_any's,
         * the least over the boxes), the normal only for the deepest. */
        int at = -2;
        v3 qa = g->c;
        for (int k = -1; k < LEAF_OUTLINE; k++) {
            v3 q = k < 0 ? g->c : leaf_vertex(g, sh->ox[k], sh->oy[k], tf);
            double d = HUGE_VAL;
            for (uint32_t h = 0; h < iv->n_hosts; h++) {
                double dh = obb_signed_distance(&iv->hosts[h], q);
                if (dh < d) d = dh;
            }
            if (k < 0 && d - sh->reach * g->size * 1.05 >= margin) return 0;
            if (margin - d > worst) worst = margin - d, at = k, qa = q;
        }
        if (at >= -1) *dir = ivy_nearest_any(iv, qa).normal;
        return worst;
    }
    ivy_near nc = ivy_nearest_any(iv, g->c);
    if (nc.dist - sh->reach * g->size * 1.05 >= margin) return 0;
    for (int k = -1; k < LEAF_OUTLINE; k++) {
        v3 q = k < 0 ? g->c : leaf_vertex(g, sh->ox[k], sh->oy[k], tf);
        ivy_near nr = k < 0 ? nc : ivy_nearest_any(iv, q);
        if (margin - nr.dist > worst) {
            worst = margin - nr.dist;
            *dir = nr.normal;
        }
    }
    return worst;
}

/* Does triangle abc (in a box's local frame) meet the box of half
 * extents h centred at the origin? Separating axes (Akenine-Moller): the
 * box's 3, the triangle's normal and the 9 edge crosses. */
static int tri_box(v3 a, v3 b, v3 c, const double h[3]) {
    const v3 e[3] = {v3_sub(b, a), v3_sub(c, b), v3_sub(a, c)};
    const v3 u[3] = {v3_make(1, 0, 0), v3_make(0, 1, 0), v3_make(0, 0, 1)};
    for (int i = 0; i < 3; i++) {
        double pa = i == 0 ? a.x : (i == 1 ? a.y : a.z), pb = i == 0 ? b.x : (i == 1 ? b.y : b.z),
               pc = i == 0 ? c.x : (i == 1 ? c.y : c.z);
        if (fmin(pa, fmin(pb, pc)) > h[i] || fmax(pa, fmax(pb, pc)) < -h[i]) return 0;
    }
    v3 axes[10];
    axes[0] = v3_cross(e[0], e[1]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) axes[1 + 3 * i + j] = v3_cross(u[i], e[j]);
    for (int k = 0; k < 10; k++) {
        v3 x = axes[k];
        double pa = v3_dot(a, x), pb = v3_dot(b, x), pc = v3_dot(c, x);
        double r = h[0] * fabs(x.x) + h[1] * fabs(x.y) + h[2] * fabs(x.z);
        if (fmin(pa, fmin(pb, pc)) > r || fmax(pa, fmax(pb, pc)) < -r) return 0;
    }
    return 1;
}

/* The blade's outline points, folded by tf. */
static void leaf_outline(const leaf_geo *g, const leaf_shape *sh, double tf, v3 q[LEAF_OUTLINE]) {
    for (int k = 0; k < LEAF_OUTLINE; k++) q[k] = leaf_vertex(g, sh->ox[k], sh->oy[k], tf);
}

/* Does the blade's surface (not only its vertices) come within `margin`
 * of a box, or cross a mesh host? A blade over a box's edge (a pillar's
 * corner) can have every vertex clear and a triangle through the box.
 * Boxes: exact, against the box grown by margin; meshes: the fan's edges.
 * *dir: the way out, the normal of the surface nearest the centre. */
static int leaf_overlaps(const banyan_ivy *iv, const leaf_geo *g, const leaf_shape *sh, double margin, v3 *dir) {
    const double tf = dm_tan(LEAF_FOLD), span = sh->reach * g->size * 1.05 + margin;
    v3 q[LEAF_OUTLINE];
    int have = 0, hit = 0;
    for (uint32_t hb = 0; hb < iv->n_hosts && !hit; hb++) {
        if (ivy_far_from(iv, hb, g->c, span)) continue;
        const obb *o = &iv->hosts[hb];
        if (!have++) leaf_outline(g, sh, tf, q);
        const double h[3] = {o->h[0] + margin, o->h[1] + margin, o->h[2] + margin};
        /* The fan in the box's frame, each point once (every triangle
         * shares the centre and two neighbours share an outline point). */
        v3 lc = obb_to_local(o, g->c), lq[LEAF_OUTLINE];
        for (int k = 0; k < LEAF_OUTLINE; k++) lq[k] = obb_to_local(o, q[k]);
        /* The whole fan past one face of the grown box: tri_box's first
         * test fails for every triangle (a leaf lying on a wall). */
        int apart = 0;
        for (int i = 0; i < 3 && !apart; i++) {
            double lo = i == 0 ? lc.x : (i == 1 ? lc.y : lc.z), hi = lo;
            for (int k = 0; k < LEAF_OUTLINE; k++) {
                double c = i == 0 ? lq[k].x : (i == 1 ? lq[k].y : lq[k].z);
                lo = fmin(lo, c);
                hi = fmax(hi, c);
            }
            apart = lo > h[i] || hi < -h[i];
        }
        for (int k = 0; k < LEAF_OUTLINE && !hit && !apart; k++)
            hit = tri_box(lc, lq[k], lq[(k + 1) % LEAF_OUTLINE], h);
    }
    for (uint32_t m = 0; m < iv->n_mesh && !hit; m++) {
        if (ivy_far_from(iv, iv->mesh0 + m, g->c, span)) continue;
        if (!have++) leaf_outline(g, sh, tf, q);
        for (int k = 0; k < LEAF_OUTLINE && !hit; k++)
            hit = ivy_segment_meets_mesh(iv, g->c, q[k]) || ivy_segment_meets_mesh(iv, q[k], q[(k + 1) % LEAF_OUTLINE]);
    }
    if (hit) *dir = ivy_nearest_any(iv, g->c).normal;
    return hit;
}

/* The clumps' field at R, a position relative to the first bud (so a
 * plant moved, far from the origin too, keeps its leaves): a 3-D value
 * noise over cells of clump_size, -1 thin .. 1 dense. */
static double clump_field(const banyan_ivy *iv, v3 R) {
    const banyan_ivy_params *p = &iv->p;
    return 2 * noise_value3(noise_mix(p->seed ^ CLUMP_SALT), R.x, R.y, R.z, p->clump_size) - 1;
}

/* Does bud i carry a leaf? Of the buds, leaf_share do where the cover is
 * average; the share varies over the clumps (1 +- leaf_clump times the
 * clump field) and halves towards the growing tips (age 0: a new bud; 1:
 * leaf_size_steps old), so the cover has dense and thin patches and a
 * thinner growth front; a stem grown alongside another keeps
 * IVY_FOLLOW_LEAF of that (leaf_share 1 with no clumps: every bud, and
 * that share of those). Drawn from a hash of the seed and the bud, apart
 * from every stream. */
static int leaf_kept(const banyan_ivy *iv, int32_t i, double age, double wood) {
    const banyan_ivy_params *p = &iv->p;
    if (wood <= 0) return 0;
    const double along = iv->buds[i].follow > 0 ? IVY_FOLLOW_LEAF : 1.0; /* a stem grown alongside another */
    double share;
    if (p->leaf_share >= 1 && p->leaf_clump <= 0 && wood >= 1) { /* every bud, the tips too */
        if (along >= 1) return 1;
        share = along;
    } else {
        share = p->leaf_share * (1 + p->leaf_clump * clump_field(iv, v3_sub(iv->buds[i].P, iv->buds[0].P))) *
                (0.5 + 0.5 * age) * wood * along;
    }
    return noise_unit(noise_mix(noise_mix(noise_mix(p->seed ^ CLUMP_SALT) + 1) ^ (uint64_t)i)) < share;
}

/* The envelope's height over the clumps per unit of clump_relief: the
 * clump field steepened (slope 2 about its mean, flat at +-1), so a
 * clump is a mound with flanks rather than a gentle wave. */
static double clump_height(const banyan_ivy *iv, v3 R) {
    const double c = clump_field(iv, R);
    return c * (2 - fabs(c));
}

/* The foliage's envelope over the clumps: dense clumps stand up to
 * clump_relief further out than the average, thin zones as much nearer
 * the surface. Returns that height at bud P and, in *env, the envelope's
 * normal over a surface of normal n (n tilted against the height's slope
 * along the surface), so the blades of a clump's flanks face along them
 * and a clump reads by its light and shade from afar. */
static double clump_envelope(const banyan_ivy *iv, v3 P, v3 n, v3 *env) {
    const double relief = iv->p.clump_relief, e = 0.05 * iv->p.clump_size;
    P = v3_sub(P, iv->buds[0].P); /* the steps below are exact beside small numbers */
    v3 g = v3_make((clump_height(iv, v3_add(P, v3_make(e, 0, 0))) - clump_height(iv, v3_sub(P, v3_make(e, 0, 0)))) / (2 * e),
                   (clump_height(iv, v3_add(P, v3_make(0, e, 0))) - clump_height(iv, v3_sub(P, v3_make(0, e, 0)))) / (2 * e),
                   (clump_height(iv, v3_add(P, v3_make(0, 0, e))) - clump_height(iv, v3_sub(P, v3_make(0, 0, e)))) / (2 * e));
    g = v3_scale(v3_sub(g, v3_scale(n, v3_dot(n, g))), relief);
    *env = v3_norm_or(v3_sub(n, g), n);
    return relief * clump_height(iv, P);
}

/* The cover frays at a box's edges: within a band of edge_fray, its width
 * varying along the edge by half either way (value noise over clumps of
 * half clump_size), a leaf's petiole leans out across the edge, the more
 * the nearer it is, so blades stand past the outline, raggedly. Returns
 * the lean (0 none .. 1 at the edge) and the way out in *out. */
static double leaf_edge_lean(const banyan_ivy *iv, int32_t i, ivy_near nr, v3 *out) {
    const banyan_ivy_params *p = &iv->p;
    double e = ivy_edge_distance(iv, nr, 1.5 * p->edge_fray, out);
    if (e == HUGE_VAL) return 0;
    const uint64_t key = noise_mix(p->seed ^ FRAY_SALT);
    v3 P = v3_sub(iv->buds[i].P, iv->buds[0].P);
    double width = p->edge_fray * (0.5 + noise_value3(key, P.x, P.y, P.z, 0.5 * p->clump_size));
    return 1.0 - noise_smooth01(e / width);
}

/* Places bud i's leaf (module comment); returns 0 when it has no size
 * or finds no room clear of the hosts. */
static int leaf_place(const banyan_ivy *iv, int32_t i, const leaf_shape *sh, double wood, leaf_geo *g) {
    const banyan_ivy_params *p = &iv->p;
    const ivy_bud *b = &iv->buds[i];
    pcg32 r; /* the leaf's own stream: draws here move no stem */
    pcg32_seed(&r, p->seed, ((uint64_t)i + 1) * 0x9E3779B97F4A7C15ULL ^ LEAF_STREAM);
    double u_size = rng_uniform(&r), u_pet = rng_uniform(&r), u_tilt = rng_uniform(&r), u_az = rng_uniform(&r),
           u_head = rng_uniform(&r);
    /* Size by age: young leaves at the growing tips small, old ones large
     * (as x^1.5: they stay small a while), and leaves of one age differ
     * (plants.md: long-shoot leaves are smaller than spur leaves). */
    double age = (double)(iv->step - b->step_c) / p->leaf_size_steps;
    age = age < 0 ? 0 : (age > 1 ? 1 : age);
    if (!leaf_kept(iv, i, age, wood)) return 0;
    g->size = (p->leaf_size_min + (p->leaf_size_max - p->leaf_size_min) * age * sqrt(age)) * p->leaf_scale *
              (0.8 + 0.45 * u_size);
    if (!(g->size > 0)) return 0;

    const v3 up = v3_make(0, 0, 1);
    const double reach = p->sucker_length > p->internode ? p->sucker_length : p->internode;
    ivy_near nr = ivy_nearest_any(iv, b->P);
    /* On a mesh host's tight relief (a nose, a brow, an eye's rim) the
     * blade stays smaller than the feature, so the form reads. */
    if (p->leaf_relief > 0 && nr.dist <= reach) {
        const double fit = p->leaf_relief * ivy_relief_radius(iv, nr, RELIEF_STEP * p->leaf_size_max * p->leaf_scale);
        if (g->size > fit) {
            g->size = fit;
            if (g->size < p->leaf_size_min * p->leaf_scale) return 0;
        }
    }
    /* The surface's normal, blending towards "up and out" as the stem leaves it. */
    double w = (nr.dist - p->sucker_length) / (4.0 * reach);
    w = w < 0 ? 0 : (w > 1 ? 1 : w);
    v3 free_n = v3_norm(v3_add(v3_scale(nr.normal, 0.5), up));
    v3 n = v3_norm_or(v3_lerp(nr.normal, free_n, w), nr.normal), env;
    double lift = 0;
    if (p->clump_relief > 0 && w < 1) {
        lift = clump_envelope(iv, b->P, n, &env) * (1 - w);
        n = v3_norm_or(v3_lerp(n, env, 1 - w), n);
    }
    v3 t = b->parent >= 0 ? v3_norm_or(v3_sub(b->P, iv->buds[b->parent].P), b->V) : b->V;
    v3 side = v3_norm_or(v3_cross(n, t), v3_any_perp(n));
    if (!b->L) side = v3_neg(side);
    /* The sky along the surface; on a floor or under a ceiling the leaf's side. */
    v3 sky = v3_sub(up, v3_scale(n, v3_dot(n, up)));
    sky = v3_len2(sky) > 0.04 ? v3_norm(sky) : side;
    const double spread = deg2rad(p->leaf_spread);
    /* Blade normal: the surface's, turned towards the sky by the tilt,
     * the turn's heading spread twice as wide as its angle. A free stem's
     * normal already looks up and out: the tilt fades with w, the
     * spread stays. */
    double th = deg2rad(p->leaf_tilt) * (1 - w) + spread * (2 * u_tilt - 1);
    th = th < -BANYAN_PI / 2 ? -BANYAN_PI / 2 : (th > BANYAN_PI / 2 ? BANYAN_PI / 2 : th);
    v3 toward = v3_rotate(sky, n, 2 * spread * (2 * u_az - 1));
    g->nb = v3_norm_or(v3_add(v3_scale(n, dm_cos(th)), v3_scale(toward, dm_sin(th))), n);
    /* Tip: down the blade (it hangs on its petiole), leaning to the leaf's side. */
    v3 down = v3_sub(v3_neg(up), v3_scale(g->nb, -v3_dot(g->nb, up)));
    const int flat = v3_len2(down) < 0.04;
    if (flat) down = v3_sub(side, v3_scale(g->nb, v3_dot(g->nb, side)));
    down = v3_norm_or_perp(down, g->nb);
    /* Lean to the leaf's side; a blade lying flat points to its side
     * already (there the test below is 0 but for rounding), so it leans
     * by the bud's side, the same in any frame. */
    double lean = flat ? (b->L ? 0.3 : -0.3) : v3_dot(side, v3_cross(g->nb, down)) >= 0 ? 0.3 : -0.3;
    g->a = v3_norm_or_perp(v3_rotate(down, g->nb, lean + spread * (2 * u_head - 1)), g->nb);
    g->a = v3_norm_or_perp(v3_sub(g->a, v3_scale(g->nb, v3_dot(g->nb, g->a))), g->nb);
    g->bb = v3_cross(g->nb, g->a);
    /* Petiole: it rises from the node out, up and to the leaf's side,
     * about 45 deg off the surface (straight out it read as a ladder
     * from the side). */
    v3 pd = v3_norm(v3_add(v3_add(v3_scale(n, 0.8), v3_scale(sky, 0.55)), v3_scale(side, 0.45)));
    v3 out;
    double out_lean = p->edge_fray > 0 && nr.dist <= reach ? leaf_edge_lean(iv, i, nr, &out) : 0;
    if (out_lean > 0) pd = v3_norm(v3_madd(pd, out, EDGE_LEAN * out_lean));
    double lp = p->leaf_petiole * g->size * (0.8 + 0.4 * u_pet);
    if (lift != 0 && lp > 0) {
        /* The petiole carries the blade to the envelope's height: its
         * reach along n changes by lift, keeping at least a quarter. */
        const double h = lp * v3_dot(pd, n);
        v3 reach_v = v3_madd(v3_scale(pd, lp), n, fmax(lift, -0.75 * h));
        lp = v3_len(reach_v);
        pd = v3_scale(reach_v, 1 / lp);
    }
    g->base = v3_madd(b->P, pd, lp);
    g->c = v3_madd(g->base, g->a, sh->rnotch * g->size);
    /* Keep clear of every surface (the ground too): push the blade out
     * along the normal of the surface it reaches into. In a corner (the
     * wall's foot) pushes can chase each other: then the blade turns its
     * tip up, then also halves, and as a last resort the leaf is left out. */
    const double margin = p->clearance + petiole_radius(p);
    const leaf_geo first = *g;
    for (int attempt = 0; attempt < 3; attempt++) {
        if (attempt) {
            *g = first;
            g->a = v3_neg(g->a);
            g->bb = v3_neg(g->bb);
            if (attempt == 2) g->size *= 0.5;
            g->base = v3_madd(b->P, pd, lp * (attempt == 2 ? 0.5 : 1));
            g->c = v3_madd(g->base, g->a, sh->rnotch * g->size);
        }
        for (int it = 0; it < 5; it++) {
            v3 dir = n;
            double in = leaf_intrusion(iv, g, sh, margin, &dir);
            if (in > 0) {
                leaf_shift(g, v3_scale(dir, in + 1e-4));
                continue;
            }
            if (!leaf_overlaps(iv, g, sh, margin, &dir)) return 1;
            leaf_shift(g, v3_scale(dir, 0.25 * margin + 0.005)); /* a triangle over an edge: step out */
        }
        v3 dir;
        if (leaf_intrusion(iv, g, sh, margin, &dir) <= 0 && !leaf_overlaps(iv, g, sh, margin, &dir)) return 1;
    }
    return 0;
}

/* Young Boston ivy leaves flush reddish-bronze, then turn a rich green
 * (plants.md). A leaf younger than IVY_YOUNG_STEPS shows one of the
 * atlas's young cells, bronze in summer (leaf_look_ivy), its tint as
 * drawn. An older one shows a grown, green cell whose tint keeps its red
 * while it loses some green and blue as the flush fades, weight w =
 * exp(-(age / 20)^2) (age in steps: green by about 40), and darkens a
 * little up to leaf_size_steps. Autumn has its own spread. */
static int leaf_young(const banyan_ivy *iv, const ivy_bud *b) { return iv->step - b->step_c < IVY_YOUNG_STEPS; }

static void leaf_age_tint(const banyan_ivy *iv, const ivy_bud *b, int32_t season, double tint[4]) {
    if (season == BANYAN_SEASON_AUTUMN || leaf_young(iv, b)) return;
    double age = (double)(iv->step - b->step_c), a = age / 20.0;
    double young = dm_exp(-a * a), old = fmin(1.0, age / iv->p.leaf_size_steps);
    tint[0] *= 1.0 - 0.08 * old;
    tint[1] *= (1.0 - 0.55 * young) * (1.0 - 0.04 * old);
    tint[2] *= (1.0 - 0.55 * young) * (1.0 - 0.08 * old);
}

uint64_t ivy_mesh_vertex_floor(const banyan_ivy_params *p, int64_t n) {
    uint64_t per_bud = (uint64_t)p->stem_sides + 1 + (p->leaves ? LEAF_OUTLINE + 1 + PETIOLE_VERTS : 0);
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

/* Wind and birth of bud i's leaf (petiole and blade): see the header. The
 * pivot is the bud's point on its stem's axis (`at`: the skeleton's). */
static void leaf_wind(mesh_builder *mb, const wind_slots *ws, const banyan_ivy *iv, int32_t i, v3 at, double stiffness,
                      int32_t level, double birth_scale) {
    const ivy_bud *b = &iv->buds[i];
    wind_set(mb, ws, at, level + 1, stiffness, wind_phase_of(iv->p.seed, IVY_WIND_LEAF + (uint64_t)i), 1.0);
    double birth = (b->step_c + 0.5) * birth_scale;
    wind_birth(mb, ws, birth_scale > 0 ? birth : 0.0);
}

/* The mesh on up to p->threads threads (base/pool.h), the same bytes on
 * any count: every stem, petiole and blade has its place in the output
 * planned before it is written, so items write disjoint ranges. Items,
 * in queue order: leaf placement by blocks of buds (the costly part:
 * host queries), stems by blocks of chains (their sizes known from the
 * plan), then petioles and blades by the same blocks of buds, which
 * start once every leaf is placed (where each block's leaves go is the
 * count of placed leaves before it). */
#define MESH_LEAF_BLOCK 256 /* buds per leaf item */
#define MESH_STEM_ITEMS 64  /* stem items, cut by points: enough for a few threads to even out */
#define MESH_MIN_BUDS 2048  /* fewer buds: one thread (a thread costs more than such a mesh gains) */

typedef struct mesh_job {
    const banyan_ivy *iv;
    const leaf_shape *sh;
    mesh_builder *out;          /* the output's arrays, sized for the most the plan allows */
    const int32_t *pts, *chn;   /* the chains (banyan_ivy_mesh) */
    const uint32_t *cv, *ci;    /* per chain: its first vertex and index; [n_chains]: the stems' end */
    const int32_t *sblk;        /* per stem item its first chain; [n_sblk]: n_chains */
    int32_t n_sblk, n_lblk;     /* stem items; leaf blocks (0 without leaves) */
    uint32_t max_pts;
    const double *bst;
    const int32_t *blv;
    const double *wood_r;       /* per bud: the stem's radius and tube centre (ivy_wood) */
    const double *leaf_wood;    /* per bud: the share of its leaf its wood keeps (ivy_wood_leaf_shares) */
    const v3 *wood_P;
    double birth_scale;
    leaf_geo *lg;
    uint32_t *lok;              /* per leaf block: leaves placed; once `ready`, the leaves before it ([n_lblk]: all) */
    int32_t cols, rows;         /* leaf atlas */
    atomic_int next, placed, ready, done, cancel;
    atomic_int status;          /* the first failure */
} mesh_job;

static void job_fail(mesh_job *J, banyan_status s) {
    int ok = 0;
    atomic_compare_exchange_strong(&J->status, &ok, (int)s);
}

/* A builder over the output's vertices v0 .. v0 + nv and indices i0 ..
 * i0 + ni, with the output's attributes in the same slots. */
static void sub_builder(const mesh_job *J, mesh_builder *sb, uint32_t v0, uint32_t nv, uint32_t i0, uint32_t ni,
                        wind_slots *ws, int *a_birth, int *a_part) {
    const mesh_builder *o = J->out;
    float *attr[MB_MAX_ATTRS];
    const char *names[MB_MAX_ATTRS];
    for (uint32_t a = 0; a < o->n_attr; a++) {
        attr[a] = o->attr[a] + v0;
        names[a] = o->attr_name[a];
    }
    mb_init_external(sb, nv, ni, o->pos + 3 * (size_t)v0, o->nrm + 3 * (size_t)v0, o->uv + 2 * (size_t)v0,
                     o->col + 4 * (size_t)v0, o->idx + i0, attr, names, o->n_attr);
    *a_birth = mb_add_attr(sb, "birth_step");
    *a_part = mb_add_attr(sb, "part");
    wind_declare(sb, J->iv->p.wind, ws);
}

/* Checks that the builder filled its range exactly, then numbers its
 * indices from the output's first vertex instead of the range's. */
static void sub_close(mesh_job *J, mesh_builder *sb, uint32_t v0, uint32_t nv, uint32_t ni) {
    if (!sb->status && (sb->nv != nv || sb->ni != ni)) sb->status = BANYAN_E_INTERNAL; /* the plan was wrong */
    if (sb->status) {
        job_fail(J, sb->status);
        return;
    }
    for (uint32_t k = 0; k < ni; k++) sb->idx[k] += v0;
}

/* Stem item k: its chains as tubes. P .. wr: scratch of max_pts points. */
static void mesh_stems(mesh_job *J, int32_t k, v3 *P, double *R, float *birth, double *wr) {
    const banyan_ivy *iv = J->iv;
    const banyan_ivy_params *p = &iv->p;
    const int sides = p->stem_sides;
    const int32_t c0 = J->sblk[k], c1 = J->sblk[k + 1];
    const uint32_t v0 = J->cv[c0], nv = J->cv[c1] - v0, i0 = J->ci[c0], ni = J->ci[c1] - i0;
    double *wr_birth = wr + J->max_pts;
    mesh_builder mb;
    wind_slots ws;
    int a_birth, a_part;
    sub_builder(J, &mb, v0, nv, i0, ni, &ws, &a_birth, &a_part);
    mb_set_attr(&mb, a_part, 0.0);
    for (int32_t c = c0; c < c1 && !mb.status; c++) {
        const int32_t i = J->chn[2 * c];
        const int32_t *pt = J->pts + J->chn[2 * c + 1];
        uint32_t n = (uint32_t)(J->chn[2 * c + 3] - J->chn[2 * c + 1]);
        const ivy_bud *s = &iv->buds[i];
        for (uint32_t q = 0; q < n; q++) {
            const ivy_bud *b = &iv->buds[pt[q]];
            P[q] = J->wood_P[pt[q]];
            /* A branch's base ring sits in its parent and appears with it. */
            const ivy_bud *own = (q == 0 && pt[0] != i) ? s : b;
            R[q] = J->wood_r[(q == 0 && pt[0] != i) ? i : pt[q]];
            birth[q] = (float)own->step_c;
            wr[q] = J->bst[pt[q]];
            wr_birth[q] = own->step_c * J->birth_scale;
        }
        if (n == 1) { /* a lone first bud: a short stub along its direction */
            P[1] = v3_madd(P[0], s->V, 2.0 * R[0]);
            R[1] = R[0];
            birth[1] = birth[0];
            wr[1] = wr[0], wr_birth[1] = wr_birth[0];
            n = 2;
        }
        wind_set(&mb, &ws, P[0], J->blv[i], 1.0, wind_phase_of(p->seed, (uint64_t)i), 0.0);
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
        uint32_t ring = (uint32_t)sides + 1, q = 0;
        for (; q < n; q++)
            for (uint32_t j = 0; j < ring; j++) attr[first + q * ring + j] = birth[q];
        uint32_t v = first + n * ring;
        if (o.cap_start)
            for (uint32_t j = 0; j < ring + 1; j++) attr[v++] = birth[0];
        for (; v < mb.nv; v++) attr[v] = birth[n - 1];
        wind_tube_rings(&mb, first, n, sides, o.cap_start, o.cap_end, ws.stiffness, wr);
        wind_tube_rings(&mb, first, n, sides, o.cap_start, o.cap_end, ws.birth, wr_birth);
    }
    sub_close(J, &mb, v0, nv, ni);
    mb_free(&mb);
}

/* Leaf block k: each bud's leaf placed; the last block placed sums the
 * blocks into where each one's leaves go, and opens the leaf writing. */
static void mesh_place(mesh_job *J, int32_t k) {
    const int32_t i0 = k * MESH_LEAF_BLOCK, i1 = i0 + MESH_LEAF_BLOCK < J->iv->n ? i0 + MESH_LEAF_BLOCK : J->iv->n;
    uint32_t ok = 0;
    for (int32_t i = i0; i < i1; i++) ok += (uint32_t)(J->lg[i].ok = leaf_place(J->iv, i, J->sh, J->leaf_wood[i], &J->lg[i]));
    J->lok[k] = ok;
    if (atomic_fetch_add(&J->placed, 1) + 1 < J->n_lblk) return;
    uint32_t sum = 0;
    for (int32_t b = 0; b <= J->n_lblk; b++) {
        uint32_t c = b < J->n_lblk ? J->lok[b] : 0;
        J->lok[b] = sum;
        sum += c;
    }
    atomic_store(&J->ready, 1);
}

/* Leaf block k written: its petioles (in the stem part, after the
 * stems), then its blades (the leaf part, after every petiole). */
static void mesh_leaves(mesh_job *J, int32_t k) {
    const banyan_ivy *iv = J->iv;
    const banyan_ivy_params *p = &iv->p;
    const leaf_shape *sh = J->sh;
    const leaf_geo *lg = J->lg;
    const int32_t i0 = k * MESH_LEAF_BLOCK, i1 = i0 + MESH_LEAF_BLOCK < iv->n ? i0 + MESH_LEAF_BLOCK : iv->n;
    const uint32_t before = J->lok[k], count = J->lok[k + 1] - before, all = J->lok[J->n_lblk];
    if (!count) return;
    const uint32_t v_pet = J->cv[J->sblk[J->n_sblk]], i_pet = J->ci[J->sblk[J->n_sblk]];
    mesh_builder mb;
    wind_slots ws;
    int a_birth, a_part;

    const double rp = petiole_radius(p);
    double pc[PETIOLE_SIDES], ps[PETIOLE_SIDES]; /* the ring's directions, the same for every petiole */
    for (int q = 0; q < PETIOLE_SIDES; q++) {
        double th = 2 * BANYAN_PI * q / PETIOLE_SIDES;
        pc[q] = dm_cos(th);
        ps[q] = dm_sin(th);
    }
    uint32_t v0 = v_pet + PETIOLE_VERTS * before, nv = PETIOLE_VERTS * count, ni = 6 * PETIOLE_SIDES * count;
    sub_builder(J, &mb, v0, nv, i_pet + 6 * PETIOLE_SIDES * before, ni, &ws, &a_birth, &a_part);
    mb_set_attr(&mb, a_part, 0.0);
    for (int32_t i = i0; i < i1 && !mb.status; i++) {
        if (!lg[i].ok) continue;
        v3 a0 = iv->buds[i].P, ax = v3_norm_or(v3_sub(lg[i].base, a0), lg[i].nb);
        v3 e1 = v3_any_perp(ax), e2 = v3_cross(ax, e1);
        mb_set_attr(&mb, a_birth, (double)iv->buds[i].step_c);
        leaf_wind(&mb, &ws, iv, i, J->wood_P[i], J->bst[i], J->blv[i], J->birth_scale);
        uint32_t vc = mb_vertices(&mb, PETIOLE_VERTS);
        uint32_t *I = mb_indices(&mb, 6 * PETIOLE_SIDES);
        if (!I) break;
        for (int q = 0; q < PETIOLE_SIDES; q++) {
            v3 rn = v3_add(v3_scale(e1, pc[q]), v3_scale(e2, ps[q]));
            mb_put(&mb, vc + (uint32_t)q, v3_madd(a0, rn, rp), rn, (double)q / PETIOLE_SIDES, 0.0);
            mb_put(&mb, vc + PETIOLE_SIDES + (uint32_t)q, v3_madd(lg[i].base, rn, rp), rn, (double)q / PETIOLE_SIDES, 1.0);
            uint32_t q1 = (uint32_t)(q + 1) % PETIOLE_SIDES, r0 = vc + (uint32_t)q, r1 = vc + q1;
            I[6 * q + 0] = r0; I[6 * q + 1] = r1; I[6 * q + 2] = r1 + PETIOLE_SIDES;
            I[6 * q + 3] = r0; I[6 * q + 4] = r1 + PETIOLE_SIDES; I[6 * q + 5] = r0 + PETIOLE_SIDES;
        }
    }
    sub_close(J, &mb, v0, nv, ni);
    mb_free(&mb);
    if (atomic_load(&J->status)) return;

    /* The blade's template, per vertex (the centre, then the outline):
     * its offsets along the tip, across and (the fold) the normal per
     * unit of size, and which normal it takes (0 the blade's, 1 the
     * +y half's, 2 the -y half's). A leaf is then this template moved
     * and scaled. */
    const double tf = dm_tan(LEAF_FOLD);
    double tx[LEAF_OUTLINE + 1], ty[LEAF_OUTLINE + 1], tz[LEAF_OUTLINE + 1];
    int tn[LEAF_OUTLINE + 1];
    for (int q = 0; q <= LEAF_OUTLINE; q++) {
        double x = q ? sh->ox[q - 1] : 0, y = q ? sh->oy[q - 1] : 0;
        tx[q] = x;
        ty[q] = y;
        tz[q] = fabs(y) * tf;
        tn[q] = fabs(y) < 1e-9 ? 0 : (y > 0 ? 1 : 2);
    }
    const uint32_t v_leaf = v_pet + PETIOLE_VERTS * all, i_leaf = i_pet + 6 * PETIOLE_SIDES * all;
    v0 = v_leaf + (LEAF_OUTLINE + 1) * before, nv = (LEAF_OUTLINE + 1) * count, ni = 3 * LEAF_OUTLINE * count;
    sub_builder(J, &mb, v0, nv, i_leaf + 3 * LEAF_OUTLINE * before, ni, &ws, &a_birth, &a_part);
    mb_set_attr(&mb, a_part, 1.0);
    for (int32_t i = i0; i < i1 && !mb.status; i++) {
        const leaf_geo *g = &lg[i];
        if (!g->ok) continue;
        const ivy_bud *b = &iv->buds[i];
        leaf_look lk; /* by bud: a leaf keeps its look as the plant grows */
        leaf_look_ivy(p->seed, (uint64_t)i, J->cols, J->rows, leaf_young(iv, b), p->season, &lk);
        leaf_age_tint(iv, b, p->season, lk.tint);
        mb_set_color(&mb, lk.tint); /* the output has colours */
        mb_set_attr(&mb, a_birth, (double)b->step_c);
        leaf_wind(&mb, &ws, iv, i, J->wood_P[i], J->bst[i], J->blv[i], J->birth_scale);
        uint32_t vc = mb_vertices(&mb, LEAF_OUTLINE + 1);
        uint32_t *I = mb_indices(&mb, 3 * LEAF_OUTLINE);
        if (!I) break;
        /* The fold: each half turns up about the midrib, so its normal leans away from it. */
        v3 nrm[3] = {g->nb, v3_norm(v3_madd(g->nb, g->bb, -tf)), v3_norm(v3_madd(g->nb, g->bb, tf))};
        float fn[3][3];
        for (int j = 0; j < 3; j++) fn[j][0] = (float)nrm[j].x, fn[j][1] = (float)nrm[j].y, fn[j][2] = (float)nrm[j].z;
        float *P = mb.pos + 3 * (size_t)vc, *N = mb.nrm + 3 * (size_t)vc, *UV = mb.uv + 2 * (size_t)vc;
        for (int q = 0; q <= LEAF_OUTLINE; q++, P += 3, N += 3, UV += 2) {
            v3 x = v3_madd(v3_madd(v3_madd(g->c, g->a, tx[q] * g->size), g->bb, ty[q] * g->size), g->nb,
                           tz[q] * g->size);
            P[0] = (float)x.x, P[1] = (float)x.y, P[2] = (float)x.z;
            memcpy(N, fn[tn[q]], sizeof fn[0]);
            UV[0] = (float)(lk.u0 + sh->ou[q] * lk.du);
            UV[1] = (float)(lk.v0 + sh->ov[q] * lk.dv);
        }
        for (uint32_t q = 0; q < LEAF_OUTLINE; q++, I += 3) {
            I[0] = vc;
            I[1] = vc + 1 + q;
            I[2] = vc + 1 + (q + 1) % LEAF_OUTLINE;
        }
    }
    sub_close(J, &mb, v0, nv, ni);
    mb_free(&mb);
}

/* A wait for another thread's item: asleep, not spinning, so that on a
 * busy machine the waiting thread does not take the time of the one it
 * waits for (a process's threads share one scheduler group). */
static void mesh_pause(void) {
    plat_sleep_us(50);
}

/* One thread's share: items from the shared counter until none are
 * left, the job fails or is cancelled. The caller reports progress, by
 * items done, from iv->mesh_from to 1. */
static void mesh_work(void *job, int caller) {
    mesh_job *J = job;
    const int32_t n_items = 2 * J->n_lblk + J->n_sblk;
    v3 *P = NULL;
    double *R = NULL, *wr = NULL;
    float *birth = NULL;
    for (;;) {
        if (atomic_load(&J->cancel) || atomic_load(&J->status)) break;
        int32_t k = atomic_fetch_add(&J->next, 1);
        if (k >= n_items) break;
        if (k < J->n_lblk) {
            mesh_place(J, k);
        } else if (k < J->n_lblk + J->n_sblk) {
            if (!P) { /* this thread's scratch, on its first stem item */
                P = malloc(sizeof(v3) * J->max_pts);
                R = malloc(sizeof(double) * J->max_pts);
                birth = malloc(sizeof(float) * J->max_pts);
                wr = malloc(sizeof(double) * 2 * J->max_pts);
                if (!P || !R || !birth || !wr) {
                    job_fail(J, BANYAN_E_NOMEM);
                    break;
                }
            }
            mesh_stems(J, k - J->n_lblk, P, R, birth, wr);
        } else {
            /* Every leaf placed first: a block's place depends on the
             * leaves before it. The queue hands out placement first, so
             * this waits at most for the other threads' last blocks. */
            while (!atomic_load(&J->ready) && !atomic_load(&J->cancel) && !atomic_load(&J->status)) mesh_pause();
            if (!atomic_load(&J->ready)) break;
            mesh_leaves(J, k - J->n_lblk - J->n_sblk);
        }
        int32_t d = atomic_fetch_add(&J->done, 1) + 1;
        const banyan_ivy *iv = J->iv;
        if (caller && prog_at(iv->prog, iv->mesh_from + (1.0 - iv->mesh_from) * (double)d / n_items))
            atomic_store(&J->cancel, 1);
    }
    free(P); free(R); free(birth); free(wr);
}

/* Walks every chain once: its points into pts, its first bud and where
 * its points start into chn (an end after the last), and counts the
 * vertices and indices of its tube and of the leaves, so the mesh can be
 * refused before it is allocated. */
static void mesh_count(const banyan_ivy *iv, int32_t *pts, int32_t *chn, int32_t *n_chains_out, uint32_t *max_pts_out,
                       uint64_t *need_v_out, uint64_t *need_i_out) {
    uint64_t need_v = 0, need_i = 0;
    uint32_t max_pts = 2;
    int32_t n_chains = 0, n_pts = 0;
    const int sides = iv->p.stem_sides;
    for (int32_t i = 0; i < iv->n; i++) {
        if (!chain_start(iv, i)) continue;
        uint32_t n = chain_points(iv, i, pts + n_pts), v, ix;
        chn[2 * n_chains] = i;
        chn[2 * n_chains++ + 1] = n_pts;
        n_pts += (int32_t)n;
        if (n < 2) n = 2; /* a lone bud gets a stub */
        if (n > max_pts) max_pts = n;
        tube_counts(n, sides, iv->buds[i].parent < 0, 1, &v, &ix);
        need_v += v;
        need_i += ix;
    }
    chn[2 * n_chains + 1] = n_pts;
    if (iv->p.leaves) {
        need_v += (uint64_t)iv->n * (LEAF_OUTLINE + 1 + PETIOLE_VERTS);
        need_i += (uint64_t)iv->n * (LEAF_OUTLINE + 2 * PETIOLE_SIDES) * 3;
    }
    *n_chains_out = n_chains, *max_pts_out = max_pts, *need_v_out = need_v, *need_i_out = need_i;
}

/* Each bud's wind stiffness into bst: 1 where it is held (attached, or on
 * the ground), else falling with the free arc length since the last held
 * bud, yet never under 0.9 sqrt of its wood radius share of the thickest;
 * its branching level into blv (at most 63, wind_level's range). Returns
 * the last growth step. */
static int32_t wind_stiffness(const banyan_ivy *iv, const double *wood_r, double *bst, int32_t *blv) {
    const banyan_ivy_params *p = &iv->p;
    int32_t last_step = 0;
    /* Buds come in creation order: a parent before its children. bst
     * holds the arc length from the last held bud until it becomes the
     * stiffness. */
    const double fall = 1.0 / (IVY_WIND_REACH * p->internode);
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        int held = b->attached || (p->ground && b->P.z <= p->ground_z + p->clearance + 1e-9);
        last_step = b->step_c > last_step ? b->step_c : last_step;
        if (b->parent < 0) {
            bst[i] = 0, blv[i] = 0;
            continue;
        }
        bst[i] = held ? 0 : bst[b->parent] + v3_dist(b->P, iv->buds[b->parent].P);
        blv[i] = blv[b->parent] + (chain_start(iv, i) ? 1 : 0);
        if (blv[i] > 63) blv[i] = 63; /* wind_level's range; the tips past it share it */
    }
    double r_max = 0;
    for (int32_t i = 0; i < iv->n; i++) r_max = wood_r[i] > r_max ? wood_r[i] : r_max;
    for (int32_t i = 0; i < iv->n; i++) {
        if (bst[i] == 0) { /* held */
            bst[i] = 1;
            continue;
        }
        double s = dm_exp(-bst[i] * fall), t = r_max > 0 ? 0.9 * sqrt(wood_r[i] / r_max) : 0;
        bst[i] = s > t ? s : t;
    }
    return last_step;
}

/* The stem plan: each chain's first vertex and index into cv and ci (their
 * totals after the last), and the stem items, chains of about equal vertex
 * counts (a chain is never split), as their first chains in sblk with an
 * end. Returns the item count. */
static int32_t plan_items(const banyan_ivy *iv, const int32_t *chn, int32_t n_chains, uint32_t *cv, uint32_t *ci,
                          int32_t *sblk) {
    int32_t n_sblk = 0;
    const int sides = iv->p.stem_sides;
    uint32_t v = 0, x = 0;
    for (int32_t c = 0; c < n_chains; c++) {
        uint32_t n = (uint32_t)(chn[2 * c + 3] - chn[2 * c + 1]), tv, ti;
        tube_counts(n < 2 ? 2 : n, sides, iv->buds[chn[2 * c]].parent < 0, 1, &tv, &ti);
        cv[c] = v, ci[c] = x;
        v += tv, x += ti;
    }
    cv[n_chains] = v, ci[n_chains] = x;
    /* Items of about equal vertex counts (a chain is never split). */
    const uint32_t per = v / MESH_STEM_ITEMS + 1;
    sblk[0] = 0;
    for (int32_t c = 1; c < n_chains; c++)
        if (cv[c] >= per * (uint32_t)(n_sblk + 1)) sblk[++n_sblk] = c;
    sblk[++n_sblk] = n_chains;
    return n_sblk;
}

banyan_status banyan_ivy_mesh(const banyan_ivy *iv, banyan_mesh **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    if (!iv) return banyan_fail(err, BANYAN_E_INVALID_ARG, "ivy is NULL");
    const banyan_ivy_params *p = &iv->p;

    /* Size first: refuse before allocating the mesh. */
    /* Every chain's points, walked once here and read again by the
     * sweep (a chain's buds lie far apart in creation order): at most 2n
     * (each chain adds its parent), then per chain its first bud and
     * where its points start, and an end. */
    int32_t *pts = malloc(sizeof(int32_t) * (4 * (size_t)iv->n + 3));
    if (!pts) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    int32_t *chn = pts + 2 * (size_t)iv->n + 1;
    uint64_t need_v, need_i;
    uint32_t max_pts;
    int32_t n_chains;
    mesh_count(iv, pts, chn, &n_chains, &max_pts, &need_v, &need_i);
    /* need_v >= ivy_mesh_vertex_floor(p, iv->n): the floor must stay a floor. */
    if (need_v > (uint64_t)p->max_vertices) {
        free(pts);
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the ivy mesh needs %llu vertices, over max_vertices = %d; raise max_vertices or lower "
                           "steps or stem_sides",
                           (unsigned long long)need_v, p->max_vertices);
    }
    /* The budget, and the mesh's memory before it is allocated (about 64
     * bytes a vertex with its attributes; 4 more for birth, 32 with the wind too; 4 an
     * index). */
    ivy_budget_start(iv);
    double per_v = p->wind ? 96.0 : 68.0;
    if (prog_stopped(iv->prog) || prog_reserve(iv->prog, (double)need_v * per_v + (double)need_i * 4.0)) {
        free(pts);
        return prog_fail(iv->prog, err, "ivy mesh");
    }
    /* wind: per bud stiffness and level */
    double *bst = malloc(sizeof(double) * ((size_t)iv->n + 1));
    int32_t *blv = malloc(sizeof(int32_t) * ((size_t)iv->n + 1));
    double *wood_r = malloc(sizeof(double) * 2 * ((size_t)iv->n + 1)), *leaf_wood = wood_r ? wood_r + iv->n + 1 : NULL;
    v3 *wood_P = malloc(sizeof(v3) * ((size_t)iv->n + 1));
    if (!bst || !blv || !wood_r || !wood_P || ivy_wood(iv, wood_r, wood_P)) {
        free(pts); free(bst); free(blv); free(wood_r); free(wood_P);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    ivy_wood_leaf_shares(iv, wood_r, leaf_wood);
    const int32_t last_step = wind_stiffness(iv, wood_r, bst, blv);
    const double birth_scale = last_step > 0 ? 1.0 / last_step : 0.0;

    mesh_builder mb;
    mb_init(&mb, (uint32_t)p->max_vertices, 1); /* colours: white stems, tinted leaves */
    mb_add_attr(&mb, "birth_step");
    mb_add_attr(&mb, "part");
    wind_slots ws;
    wind_declare(&mb, p->wind, &ws);
    uint32_t m_stem = mb_add_material(&mb, "ivy_stem", p->stem_color, 0.85, 0);
    uint32_t m_leaf = mb_add_material(&mb, "ivy_leaf", p->leaf_color, IVY_LEAF_ROUGHNESS, 1);
    if (!mb.status) {
        bark_material_set(&mb.mat[m_stem], BANYAN_TEX_IVY_STEM);
        leaf_material_set(&mb.mat[m_leaf], BANYAN_TEX_IVY_LEAF, p->season, p->leaf_color);
    }
    /* The whole mesh at once (every leaf counted; the pages of those left
     * out are never touched, and mb_finish trims them). */
    mb_reserve(&mb, (uint32_t)need_v, need_i > UINT32_MAX ? UINT32_MAX : (uint32_t)need_i);
    mb_begin_part(&mb, m_stem, 0);

    /* The plan: each chain's first vertex and index, the stem items, the leaf blocks. */
    const int32_t n_lblk = p->leaves ? (int32_t)((iv->n + MESH_LEAF_BLOCK - 1) / MESH_LEAF_BLOCK) : 0;
    uint32_t *cv = malloc(sizeof(uint32_t) * 2 * ((size_t)n_chains + 1)), *ci = cv ? cv + n_chains + 1 : NULL;
    int32_t *sblk = malloc(sizeof(int32_t) * (MESH_STEM_ITEMS + 2));
    uint32_t *lok = malloc(sizeof(uint32_t) * ((size_t)n_lblk + 1));
    leaf_geo *lg = p->leaves ? malloc(sizeof(leaf_geo) * ((size_t)iv->n + 1)) : NULL;
    if (!cv || !sblk || !lok || (p->leaves && !lg)) {
        free(pts); free(bst); free(blv); free(wood_r); free(wood_P); free(cv); free(sblk); free(lok); free(lg);
        mb_free(&mb);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    const int32_t n_sblk = mb.status ? 0 : plan_items(iv, chn, n_chains, cv, ci, sblk);
    leaf_shape sh;
    leaf_shape_init(&sh);
    mesh_job J;
    memset(&J, 0, sizeof J);
    J.iv = iv, J.sh = &sh, J.out = &mb, J.pts = pts, J.chn = chn, J.cv = cv, J.ci = ci, J.sblk = sblk;
    J.n_sblk = n_sblk, J.n_lblk = n_lblk, J.max_pts = max_pts, J.bst = bst, J.blv = blv, J.birth_scale = birth_scale;
    J.lg = lg, J.lok = lok, J.wood_r = wood_r, J.leaf_wood = leaf_wood, J.wood_P = wood_P;
    leaf_atlas_grid(BANYAN_TEX_IVY_LEAF, &J.cols, &J.rows, NULL);
    atomic_init(&J.next, 0);
    atomic_init(&J.placed, 0);
    atomic_init(&J.ready, 0);
    atomic_init(&J.done, 0);
    atomic_init(&J.cancel, 0);
    atomic_init(&J.status, 0);
    int threads = pool_threads(p->threads, BANYAN_IVY_MAX_THREADS);
    if (iv->n < MESH_MIN_BUDS) threads = 1;
    if (!mb.status) pool_run(threads, mesh_work, &J, iv->prog, &J.cancel);
    int cancelled = atomic_load(&J.cancel);
    if (!mb.status && atomic_load(&J.status)) mb.status = (banyan_status)atomic_load(&J.status);
    if (!mb.status && !cancelled) {
        /* Every range is written: the parts over them. */
        const uint32_t all = p->leaves ? lok[n_lblk] : 0;
        mb.nv = cv[n_chains] + PETIOLE_VERTS * all;
        mb.ni = ci[n_chains] + 6 * PETIOLE_SIDES * all;
        if (p->leaves) {
            mb_begin_part(&mb, m_leaf, 0);
            mb.nv += (LEAF_OUTLINE + 1) * all;
            mb.ni += 3 * LEAF_OUTLINE * all;
        }
    }
    free(lg); free(cv); free(sblk); free(lok);

    /* Skeleton: one point per bud, one edge per internode. */
    for (int32_t i = 0; i < iv->n && !mb.status; i++)
        mb_skel_point(&mb, wood_P[i], wood_r[i], iv->buds[i].state);
    for (int32_t i = 0; i < iv->n && !mb.status; i++)
        if (iv->buds[i].parent >= 0) mb_skel_edge(&mb, (uint32_t)iv->buds[i].parent, (uint32_t)i);

    free(pts); free(bst); free(blv); free(wood_r); free(wood_P);
    if (cancelled) {
        mb_free(&mb);
        return prog_fail(iv->prog, err, "ivy mesh");
    }
    banyan_status s = mb_finish(&mb, out, err);
    if (!s) frame_set(*out, iv->origin);
    return s;
}
