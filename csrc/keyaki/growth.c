/* growth.c - the keyaki skeleton: a binary branching process grown level
 * by level (spec/keyaki.md, "Common terms" and models 1-4).
 *
 * Every branch of level l < levels ends in a fork whose children (level
 * l + 1) leave it at +-angle(l) = fork_angle + step * (l - 1) inside one
 * fork plane through the parent (rules 1, 3). With the parent d and the
 * plane's unit normal n, the in-plane perpendicular is e = n x d and the
 * children are d cos(a) +- e sin(a), so they are coplanar with d by
 * construction. What differs between the models is the plane, the energy
 * split, the lengths and when a fork stops or breaks:
 *   simple       plane by rule 2, 1:1 split, equal lengths, never stops.
 *   strong_weak  plane by rule 2, strong/weak split with probability p
 *                (rule 5), lengths from energy, stops below stop_energy.
 *   twisted      the parent's plane turned by tau at strong/weak forks
 *                (rule 6), kept at 1:1 forks; lengths equal or energy.
 *   edaore       split drawn from ten ratios (rule 7); the weak child
 *                breaks off below alpha^-l (rule 8) and the survivor,
 *                carrying all the energy, springs back (rule 9); twist by
 *                the parent's tilt, none at a break (rule 10); equal
 *                lengths; every tip reaches `levels`.
 * "Turn the way that raises the strong child": of the two twist senses the
 * one whose upper child climbs higher is taken, and the strong child is
 * the upper one. Nodes are stored breadth first, so the growth order, and
 * with it every random draw, is fixed by the seed alone. No allocation
 * per node: one flat array that grows by doubling and is reused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/error.h"
#include "keyaki_internal.h"

void keyaki_skeleton_free(keyaki_skeleton *sk) {
    if (!sk) return;
    free(sk->nodes);
    sk->nodes = NULL;
    sk->count = sk->cap = 0;
}

static banyan_status reserve(keyaki_skeleton *sk, int32_t need, int32_t max_nodes, banyan_error *err) {
    if (need > max_nodes)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the skeleton passes max_nodes = %d branches; raise max_nodes or lower levels", max_nodes);
    if (need <= sk->cap) return BANYAN_OK;
    int64_t cap = sk->cap ? (int64_t)sk->cap * 2 : 1024;
    while (cap < need) cap *= 2;
    if (cap > max_nodes) cap = max_nodes;
    if (keyaki_reserve_bytes(sk->run, (double)sizeof(keyaki_node) * (double)(cap - sk->cap))) return keyaki_stop_status(err);
    keyaki_node *n = realloc(sk->nodes, sizeof(keyaki_node) * (size_t)cap);
    if (!n) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %lld skeleton branches", (long long)cap);
    sk->nodes = n;
    sk->cap = (int32_t)cap;
    return BANYAN_OK;
}

/* Unit vector along a with a component along unit d removed. */
static inline v3 perp_to(v3 a, v3 d, v3 fallback) { return v3_norm_or(v3_madd(a, d, -v3_dot(a, d)), fallback); }

/* Rule 2: the plane normal for parent direction d. */
static v3 rule2_plane(v3 d, v3 own_plane, int vertical) {
    double h = d.x * d.x + d.y * d.y;
    if (h < 1e-18) return perp_to(own_plane, d, v3_any_perp(d)); /* vertical parent: random heading */
    if (vertical) return v3_norm(v3_cross(d, v3_make(0, 0, 1)));
    return perp_to(v3_make(0, 0, 1), d, v3_any_perp(d)); /* d is the steepest line of the plane */
}

/* The parent's plane n0 turned about d by the twist (cos ct, sin st).
 * With e = n x d the children are d cos(a) +- e sin(a). side 0: the sense
 * that raises the upper child most (maximises |e.z|); side +-1: the sense
 * that raises the child on that side (maximises side * e.z). Turning n0
 * by sigma * tau turns e into w cos(tau) + sigma n0 sin(tau), w = n0 x d. */
static v3 twist_plane(v3 n0, v3 d, double ct, double st, int side) {
    if (st == 0) return n0;
    v3 w = v3_cross(n0, d);
    /* Ties (a horizontal n0: both senses rise alike) take +1; the 1e-12
     * keeps rounding from deciding, so the choice turns with the tree. */
    double q = side == 0 ? w.z * n0.z : side * n0.z;
    double sigma = q < -1e-12 ? -1.0 : 1.0;
    /* Rodrigues about d for n0 perpendicular to d. */
    return v3_norm(v3_add(v3_scale(n0, ct), v3_scale(v3_cross(d, n0), sigma * st)));
}

typedef struct level_table {
    double angle[BANYAN_KEYAKI_MAX_LEVELS + 1];   /* deg, per child level */
    double c[BANYAN_KEYAKI_MAX_LEVELS + 1], s[BANYAN_KEYAKI_MAX_LEVELS + 1];
    double sprung[BANYAN_KEYAKI_MAX_LEVELS + 1];  /* deg after a break */
    double cs[BANYAN_KEYAKI_MAX_LEVELS + 1], ss[BANYAN_KEYAKI_MAX_LEVELS + 1];
    double threshold[BANYAN_KEYAKI_MAX_LEVELS + 1];
    double ct_lo, st_lo, ct_mid, st_mid, ct_hi, st_hi; /* the twists' cosines and sines: low, mid, high */
    double z_mid, z_high;                              /* the tilts' cosines: where mid and high begin */
} level_table;

static void add_child(keyaki_node *nodes, int32_t *count, int32_t parent, v3 dir, v3 plane, double length,
                      double energy, double angle, uint32_t flags) {
    keyaki_node *P = &nodes[parent];
    int32_t i = (*count)++;
    keyaki_node *c = &nodes[i];
    c->start = v3_madd(P->start, P->dir, P->length);
    c->dir = dir;
    c->plane = plane;
    c->length = length;
    c->energy = energy;
    c->share = P->share;
    c->angle = angle;
    c->radius = 0;
    c->parent = parent;
    c->child[0] = c->child[1] = -1;
    c->level = P->level + 1;
    c->order = 0;
    c->flags = flags;
    if (P->child[0] < 0) P->child[0] = i;
    else P->child[1] = i;
}

/* Energy-rule lengths (rule 5): 1/e1 : 1/e2 with mean seg, ratio capped. */
static void energy_lengths(double seg, double fs, double cap, double *ls, double *lw) {
    double fw = 1.0 - fs;
    if (fs / fw > cap) {
        *ls = seg * 2.0 / (1.0 + cap);
        *lw = seg * 2.0 * cap / (1.0 + cap);
    } else {
        *ls = seg * 2.0 * fw;
        *lw = seg * 2.0 * fs;
    }
}

/* The first split (beyond the paper; docs/keyaki.md "First branching"):
 * the trunk (node 0, trunk_length) ends where the first limb leaves; a
 * chain of vertical trunk pieces (KN_TRUNK) climbs limb_zone, each ending
 * in a binary fork into the next piece and one limb, the last fork into
 * the last two limbs, so the skeleton stays binary and Strahler works
 * unchanged. Limbs are level 0 with an equal share of the energy: each
 * then grows under the model exactly as the paper's whole tree does from
 * its trunk (rules read energy / share), so the model's statistics hold
 * above the split. Limb j leans limb_angle (+-15 %) from vertical at
 * azimuth heading + 2 pi slot(j) / limbs (+-25 % of a slot), the slots
 * stepping about 0.38 of a turn so that successive limbs face apart; its
 * plane is the vertical plane through it turned +-twist about it, so its
 * forks raise one child (the limb curves up) and lean the other out. */
static banyan_status first_split(const banyan_keyaki_params *p, keyaki_skeleton *sk, pcg32 *r, banyan_error *err) {
    const int k = p->limbs;
    banyan_status s = reserve(sk, 2 * k - 1, p->max_nodes, err);
    if (s) return s;
    int step = (int)floor(0.382 * k + 0.5);
    if (step < 1) step = 1;
    while (k % step == 0 && step > 1) step--; /* coprime with k: every slot taken once */
    const double unit = p->unit, zone = p->limb_zone * unit, share = 1.0 / k;
    const double phi0 = dm_atan2(sk->nodes[0].plane.y, sk->nodes[0].plane.x);
    int32_t piece = 0; /* the trunk piece whose end is the next fork */
    for (int j = 0; j < k; j++) {
        double az = phi0 + 2.0 * BANYAN_PI * (((j * step) % k) + rng_range(r, -0.25, 0.25)) / k;
        double lean = deg2rad(p->limb_angle * (1.0 + rng_range(r, -0.15, 0.15)));
        double turn = deg2rad(p->twist * rng_range(r, -1.0, 1.0));
        v3 d = v3_make(dm_sin(lean) * dm_cos(az), dm_sin(lean) * dm_sin(az), dm_cos(lean));
        v3 n = v3_make(-dm_sin(az), dm_cos(az), 0); /* normal of the vertical plane through d */
        n = v3_norm(v3_add(v3_scale(n, dm_cos(turn)), v3_scale(v3_cross(d, n), dm_sin(turn))));
        add_child(sk->nodes, &sk->count, piece, d, n, p->segment_length * unit, share, p->limb_angle, 0);
        keyaki_node *limb = &sk->nodes[sk->count - 1];
        limb->level = 0;
        limb->share = share;
        if (j < k - 2) { /* the trunk climbs on to the next fork */
            double len = k > 2 ? zone / (k - 2) : 0.0;
            add_child(sk->nodes, &sk->count, piece, v3_make(0, 0, 1), sk->nodes[piece].plane, len > 1e-6 ? len : 1e-6,
                      1.0 - share * (j + 1), 0.0, KN_TRUNK);
            keyaki_node *next = &sk->nodes[sk->count - 1];
            next->level = 0;
            piece = sk->count - 1;
        }
    }
    sk->nodes[0].flags |= KN_TRUNK;
    return BANYAN_OK;
}

/* Lean (docs/keyaki.md "Lean"): the grown skeleton turned as one about
 * its foot (position) by `lean` about the horizontal axis across
 * heading + lean_direction, so the top moves that way; the growth rules
 * never see it. */
static void lean_tree(const banyan_keyaki_params *p, keyaki_skeleton *sk) {
    double a = deg2rad(p->heading + p->lean_direction), t = deg2rad(p->lean);
    v3 k = v3_make(-dm_sin(a), dm_cos(a), 0.0), o = v3_load(p->position);
    double c = dm_cos(t), sn = dm_sin(t);
    /* Rodrigues: v c + (k x v) s + k (k . v)(1 - c). */
#define LEAN_TURN(v) v3_add(v3_add(v3_scale(v, c), v3_scale(v3_cross(k, v), sn)), v3_scale(k, v3_dot(k, v) * (1.0 - c)))
    for (int32_t i = 0; i < sk->count; i++) {
        keyaki_node *x = &sk->nodes[i];
        x->start = v3_add(o, LEAN_TURN(v3_sub(x->start, o)));
        x->dir = v3_norm_or(LEAN_TURN(x->dir), x->dir);
        x->plane = v3_norm_or(LEAN_TURN(x->plane), x->plane);
    }
#undef LEAN_TURN
}

/* The per level fork table: each child level's fork angle and its angle
 * sprung back after a break (with their cosines and sines) and the energy
 * threshold under which a fork breaks; the three twists and the tilts
 * where the mid and high twists begin. */
static void level_table_init(const banyan_keyaki_params *p, level_table *t) {
    const int L = p->levels;
    for (int l = 1; l <= L; l++) {
        double a = p->fork_angle + p->fork_angle_step * (l - 1);
        double sp = a * (1.0 - p->springback * (1.0 - (double)l / L));
        t->angle[l] = a;
        t->c[l] = dm_cos(deg2rad(a));
        t->s[l] = dm_sin(deg2rad(a));
        t->sprung[l] = sp;
        t->cs[l] = dm_cos(deg2rad(sp));
        t->ss[l] = dm_sin(deg2rad(sp));
        t->threshold[l] = dm_pow(p->alpha, -l);
    }
    t->ct_lo = dm_cos(deg2rad(p->twist));
    t->st_lo = dm_sin(deg2rad(p->twist));
    t->ct_mid = dm_cos(deg2rad(p->twist_mid));
    t->st_mid = dm_sin(deg2rad(p->twist_mid));
    t->ct_hi = dm_cos(deg2rad(p->twist_high));
    t->st_hi = dm_sin(deg2rad(p->twist_high));
    t->z_mid = dm_cos(deg2rad(p->tilt_mid));
    t->z_high = dm_cos(deg2rad(p->tilt_high));
}

/* Forks node i (room for two children reserved): draws the strong
 * child's side, picks the fork plane and the energy split by the model,
 * and adds the two children, or one sprung-back child where the weak one
 * breaks. The draws from r are those of the model, in this order. */
static void fork_node(const banyan_keyaki_params *p, const level_table *t, keyaki_skeleton *sk, int32_t i, pcg32 *r) {
    const int model = p->model;
    const double seg = p->segment_length * p->unit;
    keyaki_node *P = &sk->nodes[i];
    const int l = sk->nodes[i].level + 1;
    const v3 d = P->dir;
    const v3 n0 = perp_to(P->plane, d, v3_any_perp(d));
    const double E = P->energy, Er = E / P->share; /* Er: the limb's own scale (rule 8) */
    v3 n;
    double fs = 0.5, ls = seg, lw = seg, c = t->c[l], sn = t->s[l], angle = t->angle[l];
    int strong = 0, broken = 0, strong_upper = 1;
    /* Side of the strong child: 0 = the upper one, else +-1 drawn. */
    int side = 0;
    if (p->strong_side == BANYAN_KEYAKI_SIDE_RANDOM &&
        (model == BANYAN_KEYAKI_TWISTED || model == BANYAN_KEYAKI_EDAORE)) {
        int bit = (int)rng_below(r, 2); /* drawn always: the stream does not depend on the tilt */
        if (d.z > t->z_mid) side = bit ? 1 : -1;
    }

    switch (model) {
    case BANYAN_KEYAKI_SIMPLE:
        n = rule2_plane(d, n0, p->fork_plane == BANYAN_KEYAKI_PLANE_VERTICAL);
        break;
    case BANYAN_KEYAKI_STRONG_WEAK:
        n = rule2_plane(d, n0, p->fork_plane == BANYAN_KEYAKI_PLANE_VERTICAL);
        if (rng_uniform(r) < p->strong_probability) {
            strong = 1;
            fs = p->strong_ratio;
            strong_upper = (int)rng_below(r, 2); /* 7:3 and 3:7 share p */
        }
        break;
    case BANYAN_KEYAKI_TWISTED:
        if (rng_uniform(r) < p->strong_probability) {
            strong = 1;
            fs = p->strong_ratio;
            n = twist_plane(n0, d, t->ct_lo, t->st_lo, side);
        } else {
            n = n0;
        }
        break;
    default: { /* edaore */
        uint32_t k;
        if (p->distribution == BANYAN_KEYAKI_NORMAL) {
            double u = rng_uniform(r) + rng_uniform(r) + rng_uniform(r);
            k = (uint32_t)floor(10.0 * u / 3.0);
            if (k > 9) k = 9;
        } else {
            k = rng_below(r, 10);
        }
        double ratio = 0.05 + 0.1 * k;
        fs = ratio > 0.5 ? ratio : 1.0 - ratio;
        strong = 1;
        if (Er * (1.0 - fs) < t->threshold[l]) {
            broken = 1;
            n = n0; /* a fork that breaks never twists */
            c = t->cs[l];
            sn = t->ss[l];
            angle = t->sprung[l];
        } else if (d.z > t->z_mid) {
            n = twist_plane(n0, d, t->ct_lo, t->st_lo, side);
        } else if (d.z > t->z_high) {
            n = twist_plane(n0, d, t->ct_mid, t->st_mid, side);
        } else {
            n = twist_plane(n0, d, t->ct_hi, t->st_hi, side);
        }
        break;
    }
    }

    v3 e = v3_cross(n, d);
    v3 up = v3_add(v3_scale(d, c), v3_scale(e, sn)), down = v3_sub(v3_scale(d, c), v3_scale(e, sn));
    /* Equal heights (e.z ~ 0, e.g. rule 2's steepest plane): break the
     * tie by the parent's own in-plane perpendicular, which turns with
     * the tree, so `heading` turns the skeleton exactly. */
    double ez = fabs(e.z) > 1e-12 ? e.z : v3_dot(e, v3_cross(n0, d));
    if (side ? side < 0 : ez < 0) {
        v3 tmp = up;
        up = down;
        down = tmp;
    }
    if (model == BANYAN_KEYAKI_STRONG_WEAK && strong && !strong_upper) {
        v3 tmp = up;
        up = down;
        down = tmp;
    }
    /* `up` is now the strong (or first) child. */
    if (strong && !broken && model != BANYAN_KEYAKI_EDAORE && p->length_rule == BANYAN_KEYAKI_LENGTH_ENERGY &&
        model != BANYAN_KEYAKI_SIMPLE)
        energy_lengths(seg, fs, p->max_length_ratio, &ls, &lw);
    if (broken) {
        sk->nodes[i].flags |= KN_BROKEN;
        add_child(sk->nodes, &sk->count, i, up, n, seg, E, angle, KN_SPRUNG);
    } else {
        add_child(sk->nodes, &sk->count, i, up, n, ls, E * fs, angle, strong ? KN_STRONG : 0);
        add_child(sk->nodes, &sk->count, i, down, n, lw, E - E * fs, angle, 0);
    }
}

banyan_status keyaki_grow(const banyan_keyaki_params *p, keyaki_skeleton *sk, banyan_error *err) {
    const int L = p->levels, model = p->model;
    const double unit = p->unit;
    level_table t;
    level_table_init(p, &t);

    pcg32 r;
    pcg32_seed(&r, p->seed, KEYAKI_STREAM_GROWTH);
    sk->count = 0;
    banyan_status s = reserve(sk, 1, p->max_nodes, err);
    if (s) return s;
    /* The trunk: vertical, in a vertical plane of random heading (turned
     * by `heading`, which so turns the whole tree). */
    double phi = rng_uniform(&r) * 2.0 * BANYAN_PI + deg2rad(p->heading);
    keyaki_node *trunk = &sk->nodes[0];
    trunk->start = v3_load(p->position);
    trunk->dir = v3_make(0, 0, 1);
    trunk->plane = v3_make(dm_cos(phi), dm_sin(phi), 0);
    trunk->length = p->trunk_length * unit;
    trunk->energy = 1.0;
    trunk->share = 1.0;
    trunk->angle = 0;
    trunk->radius = 0;
    trunk->parent = -1;
    trunk->child[0] = trunk->child[1] = -1;
    trunk->level = 0;
    trunk->order = 0;
    trunk->flags = 0;
    sk->count = 1;
    if (p->limbs > 1 && (s = first_split(p, sk, &r, err))) return s;

    const int G = keyaki_grown_levels(p);
    for (int32_t i = 0; i < sk->count; i++) {
        int level = sk->nodes[i].level;
        /* The budget, and the size known so far: before level G every
         * branch is kept and is at least one ring of sides_min + 1
         * vertices, so a tree past max_vertices stops here, not after a
         * whole skeleton. */
        if ((i & 1023) == 0 && sk->run) {
            if (keyaki_stopped(sk->run)) return keyaki_stop_status(err);
            if (level < G) {
                char what[64];
                snprintf(what, sizeof what, "the skeleton's first %d branches", sk->count);
                if ((s = keyaki_promise(sk->run, (uint64_t)sk->count * (uint64_t)(p->sides_min + 1), what,
                                        "levels (or sides_min)", err)))
                    return s;
            }
        }
        if (level >= L || (sk->nodes[i].flags & KN_TRUNK)) continue;
        if ((model == BANYAN_KEYAKI_STRONG_WEAK || model == BANYAN_KEYAKI_TWISTED) &&
            sk->nodes[i].energy / sk->nodes[i].share < p->stop_energy) {
            sk->nodes[i].flags |= KN_STOPPED;
            continue;
        }
        if ((s = reserve(sk, sk->count + 2, p->max_nodes, err))) return s;
        fork_node(p, &t, sk, i, &r);
    }
    keyaki_radii(sk->nodes, sk->count, p->tip_radius * unit, p->pipe_exponent);
    /* Twigs from segments: the finest levels go, after the radii, so the
     * limbs keep the thickness of the full tree (twigs.c). */
    if (p->twigs_from_segments) keyaki_truncate(sk, keyaki_grown_levels(p));
    if (p->lean > 0) lean_tree(p, sk);
    return BANYAN_OK;
}
