/* Ivy sag (spec/ivy.md, "Sag of unattached stems"). For every growing
 * tip on an unattached run: P0 is the last held bud before it and
 * P1..Pnum the unattached buds after it (with any branches hanging from
 * them). While the moment of their weight about P0,
 *     F = |C - P0| M g sin(phi) = M g * (horizontal distance of C from P0),
 * exceeds the joint's strength (moment_max x (r / r0)^sag_stiffening, r
 * the pivot's stem radius by age: older stems are stiffer), they rotate
 * down about P0 in sag_step increments (the last one cut to the angle
 * that reaches the strength);
 * then the pivot moves to P1, and so on towards the tip. A bud that would
 * enter a host is put back on its surface (clearance off it; a bud whose
 * turn would carry it through a mesh surface, which a thin open mesh
 * cannot tell by its inside, stops short of it), and a bud
 * with a sucker that ends within reach of a surface grips it. Last, the
 * tip turns up (geotropism): the last tip_hook_length of a free stem
 * bends up into a hook (a J; P0 then holds the hooked stem), and the
 * tip's growth direction rises to at least tip_elevation.
 *
 * P0 is the first bud up from the tip that is held: attached, lying on
 * the ground, or held by its other branch (so a lateral hanging from a
 * dormant bud of an attached stem sags about that bud). Only dangling runs
 * sag: when a bud hanging below P1 is held, the run is held at both ends.
 *
 * The sweep from P0 to the tip repeats (up to SAG_PASSES times) until no
 * pivot turns, since turning a part about a later pivot can move weight
 * away from an earlier one. The turns of all pivots run on copies of the positions; every bud then
 * moves once, which is what the light cache hears of (grid.c). A step's
 * turns are bounded (SAG_BUDGET_PER_BUD); the pivots past it go on the
 * next step. */
#include <string.h>

#include "ivy_internal.h"

/* Most sweeps over the pivots of one stem per step. */
#define SAG_PASSES 8

/* Is bud b held in place: attached, or lying on the ground (which carries
 * a stem's weight like a ledge)? */
static int held(const banyan_ivy *iv, const ivy_bud *b) {
    return b->attached || (iv->p.ground && b->P.z <= iv->p.ground_z + iv->p.clearance + 1e-9);
}

/* Is a held bud within the first `limit` buds of the subtree under
 * `root`? A larger subtree counts as held. */
static int holds(const banyan_ivy *iv, int32_t root, int32_t *scratch, int32_t limit) {
    int32_t n = 0, top = 0;
    scratch[n++] = root;
    while (top < n) {
        const ivy_bud *b = &iv->buds[scratch[top++]];
        if (held(iv, b)) return 1;
        for (int k = 0; k < 2; k++)
            if (b->child[k] >= 0) {
                if (n == limit) return 1;
                scratch[n++] = b->child[k];
            }
    }
    return 0;
}

/* The moment about the pivot of the n buds at q[0..n-1] (moment_of: of
 * the n buds whose positions sum to `sum`). Below the
 * horizontal it is the spec's |C - P0| M g sin(phi). Above it a thin stem
 * cannot balance upright, so the full arm |C - P0| counts (docs/ivy.md):
 * an upright run that is too heavy falls over and hangs instead of
 * standing like a small tree. */
static double moment_of(const banyan_ivy *iv, v3 pivot, v3 sum, int32_t n, v3 *C) {
    v3 c = v3_scale(sum, 1.0 / n);
    *C = c;
    double dx = c.x - pivot.x, dy = c.y - pivot.y, dz = c.z - pivot.z;
    double arm = dz > 0 ? sqrt(dx * dx + dy * dy + dz * dz) : sqrt(dx * dx + dy * dy);
    return n * iv->p.internode_mass * iv->p.gravity * arm;
}

static double moment(const banyan_ivy *iv, v3 pivot, const v3 *q, int32_t n, v3 *C) {
    v3 c = v3_make(0, 0, 0);
    for (int32_t k = 0; k < n; k++) c = v3_add(c, q[k]);
    return moment_of(iv, pivot, c, n, C);
}

/* Rotation by angle (cos c, sin s) about a horizontal unit axis k. */
static m3 rotation_h(v3 k, double c, double s) {
    double t = 1.0 - c;
    m3 r = {{c + k.x * k.x * t, k.x * k.y * t, k.y * s,
             k.x * k.y * t, c + k.y * k.y * t, -k.x * s,
             -k.y * s, k.x * s, c}};
    return r;
}

/* What every pivot uses, found once per step: the turn of one increment
 * (sag_step in radians, its cos, sin and half-angle tangent, most
 * increments), the sine and cosine of tip_elevation, and the bud turns
 * left this step. */
typedef struct sag_consts {
    double step, cs, sn, tan_half;
    int max_iter;
    double el_s, el_c;
    int64_t budget;
    int32_t hook;        /* internodes of the tip hook (tip_hook_length / internode) */
    double hook_el;      /* elevation of its last internode, rad */
} sag_consts;

/* Bud turns (a bud moved by one increment) per step: at least
 * SAG_BUDGET_PER_BUD for every bud of the plant. The presets need under
 * 6,000 a step; with moment_max near 0 every free stem swings all the way
 * at every pivot each step, and 110 buds took 7.8 M (the fuzzer's find).
 * Past the budget, the pivots left wait for the next step. */
#define SAG_BUDGET_PER_BUD 64
#define SAG_BUDGET_MIN 65536

/* atan2(|a x a2|, a . a2) < t, the angle from a to a2 below t: a clear
 * case is told by comparing tangents (tan_t = tan(t); 0 when unknown)
 * instead. The band of 1e-9 is far wider than the rounding of either
 * side, so the answer is always atan2's. */
static int angle_below(v3 a, v3 a2, double t, double tan_t) {
    double y = v3_len(v3_cross(a, a2)), x = v3_dot(a, a2);
    if (tan_t > 0 && x > 1e-100) {
        double lim = x * tan_t;
        if (y < lim * (1 - 1e-9)) return 1;
        if (y > lim * (1 + 1e-9)) return 0;
    }
    return dm_atan2(y, x) < t;
}

/* sag_pivot's answer: it turned; it stopped at max_iter still too heavy
 * (else another call on the same positions would not turn). */
enum { SAG_TURNED = 1, SAG_UNSETTLED = 2 };

/* Turns the copies q[0..n-1] (directions qv) down about the pivot in
 * sag_step increments while their moment passes the strength of the
 * joint at bud `joint`. A turn that a surface undoes (the push-out brings
 * C back) ends it: the stem rests on that surface. qn is scratch for n
 * positions. */
/* Would the turn of q[0..n-1] (a subtree in preorder, set[0..n-1] its
 * buds, set[0] hanging from the pivot) to qn carry an internode through a
 * mesh surface? Bud paths are stopped by ivy_move_out, but an internode
 * between two buds can still sweep over a mesh edge (a wall's top, a
 * cylinder's rim) into or through the mesh. The turn is then held, as by
 * the push-out; one that already crossed before the turn does not count. */
static int turn_crosses_mesh(const banyan_ivy *iv, const int32_t *set, int32_t lo, v3 pivot, const v3 *q,
                             const v3 *qn, int32_t n) {
    for (int32_t k = 0; k < n; k++) {
        int32_t par = k ? iv->buds[iv->buds[set[k]].parent].mark - lo : -1;
        v3 a = par >= 0 ? qn[par] : pivot;
        if (ivy_segment_meets_mesh(iv, a, qn[k]) && !ivy_segment_meets_mesh(iv, par >= 0 ? q[par] : pivot, q[k]))
            return 1;
    }
    return 0;
}

/* The joint at bud b holds moment_max * (r / r0)^sag_stiffening, r its
 * stem radius by age (the mesh's): bending strength goes with the cube of
 * the radius, so the old base of a free stem holds it out from the edge
 * while the young part droops, an arch instead of a plumb line. */
static double joint_strength(const banyan_ivy *iv, const ivy_bud *b) {
    const banyan_ivy_params *p = &iv->p;
    if (p->sag_stiffening <= 0) return p->moment_max;
    double x = ivy_stem_radius(iv, b) / p->stem_radius;
    return p->moment_max * (p->sag_stiffening == 3 ? x * x * x : dm_pow(x, p->sag_stiffening));
}

static int sag_pivot(const banyan_ivy *iv, sag_consts *sc, v3 pivot, const ivy_bud *joint, v3 *q, v3 *qv, v3 *qn,
                     int32_t n, const int32_t *set, int32_t lo) {
    const double step = sc->step;
    v3 C, *cur = q, *nxt = qn; /* the positions now and after the turn being tried */
    double F = moment(iv, pivot, q, n, &C);
    if (F <= iv->p.moment_max) return 0; /* within the least a joint holds */
    double mmax = joint_strength(iv, joint);
    int turned = 0, it = 0;
    for (; it < sc->max_iter && F > mmax && sc->budget > 0; it++) {
        v3 a = v3_sub(C, pivot);
        v3 axis = v3_make(-a.y, a.x, 0); /* a x G with G = (0, 0, -1): turns a towards G */
        double al = v3_len(axis);
        if (al < 1e-12) {
            if (a.z <= 0) break; /* hanging straight down */
            /* Straight up: fall away from the nearest surface. */
            v3 out = ivy_nearest_any(iv, C).normal;
            axis = v3_make(-out.y, out.x, 0);
            al = v3_len(axis);
            if (al < 1e-12) axis = v3_make(1, 0, 0), al = 1;
        }
        /* Below the horizontal, the last increment is cut to the angle that
         * brings the moment to moment_max, so a long stem does not swing
         * across the vertical forever. */
        double ang = step;
        m3 R = rotation_h(v3_scale(axis, 1.0 / al), sc->cs, sc->sn);
        if (a.z < 0) {
            double arm = v3_len(a);
            double weight = F / al; /* below the horizontal F = weight * horizontal arm */
            double s_eq = mmax / (weight * arm), s1 = s_eq < 1 ? s_eq : 1;
            /* need < step asks sin(phi - step) < s1 (asin is steeper than
             * 1): when it is clearly not so, skip atan2 and asin. */
            if (al * sc->cs + a.z * sc->sn < (s1 + 1e-7) * arm) {
                double phi = dm_atan2(al, -a.z);
                double need = phi - dm_asin(s1) + 1e-9;
                if (need < step) {
                    ang = need;
                    R = rotation_h(v3_scale(axis, 1.0 / al), dm_cos(need), dm_sin(need));
                }
            }
        }
        v3 sum = v3_make(0, 0, 0), C2;
        sc->budget -= n;
        for (int32_t k = 0; k < n; k++) {
            nxt[k] = ivy_move_out(iv, cur[k], v3_add(pivot, m3_mul_v3(&R, v3_sub(cur[k], pivot))));
            sum = v3_add(sum, nxt[k]);
        }
        if (iv->n_mesh && turn_crosses_mesh(iv, set, lo, pivot, cur, nxt, n)) break; /* held by a mesh edge */
        double F2 = moment_of(iv, pivot, sum, n, &C2);
        if (angle_below(a, v3_sub(C2, pivot), 0.5 * ang, ang == step ? sc->tan_half : 0)) break; /* held by a surface */
        for (int32_t k = 0; k < n; k++) qv[k] = m3_mul_v3(&R, qv[k]); /* normalised once, at the end */
        v3 *t = cur;
        cur = nxt;
        nxt = t;
        C = C2;
        F = F2;
        turned = SAG_TURNED;
    }
    if (cur != q) memcpy(q, cur, sizeof(v3) * (size_t)n);
    return turned | ((it == sc->max_iter || sc->budget <= 0) && F > mmax ? SAG_UNSETTLED : 0);
}

/* The tip hook (geotropism of the growing end): on the copies q, the last
 * K = sc->hook internodes of a hanging stem rise to at least a ramp of
 * elevations, from straight down at the hook's root to tip_hook_angle at
 * the tip, each keeping its length and heading (a plumb one takes the
 * hook's). So a hanging stem ends in a J, not an L. It runs after the
 * sweeps (before them, they flattened it again). chain[0] is the tip,
 * chain[m-1] P0. Returns whether a bud moved. */
static int hook_tip(const banyan_ivy *iv, const sag_consts *sc, const int32_t *chain, int32_t m, v3 *q, v3 *qv) {
    int32_t K = sc->hook;
    if (K > m - 2) K = m - 2; /* the hook's root chain[K] is in the moving set */
    for (int32_t k = 1; k < K; k++)
        if (iv->buds[chain[k]].child[1] >= 0) { K = k; break; } /* a lateral would be left behind */
    if (K < 1) return 0;
#define QP(c) q[iv->buds[c].mark]
    /* The hook's heading: where the hook already points, else the tip's
     * (a new hook of a plumb stem). */
    v3 root = QP(chain[K]), h = v3_sub(QP(chain[0]), root);
    h.z = 0;
    if (v3_len(h) < 0.1 * iv->p.internode) h = v3_make(iv->buds[chain[0]].V.x, iv->buds[chain[0]].V.y, 0);
    h = v3_norm_or(h, v3_make(1, 0, 0));
    int moved = 0;
    v3 prev_old = root, prev_new = root;
    for (int32_t k = K - 1; k >= 0; k--) {
        v3 *P = &QP(chain[k]);
        v3 d = v3_sub(*P, prev_old);
        double len = v3_len(d);
        prev_old = *P;
        double el = -0.5 * BANYAN_PI + (sc->hook_el + 0.5 * BANYAN_PI) * (double)(K - k) / K;
        v3 to = v3_add(prev_new, d);
        if (len > 1e-12 && d.z < len * dm_sin(el)) {
            v3 hk = v3_make(d.x, d.y, 0);
            hk = v3_len(hk) > 0.5 * len ? v3_norm(hk) : h;
            v3 dir = v3_add(v3_scale(hk, dm_cos(el)), v3_make(0, 0, dm_sin(el)));
            to = v3_add(prev_new, v3_scale(dir, len));
        }
        if (v3_dist(to, *P) > 1e-12) {
            *P = ivy_move_out(iv, *P, to);
            moved = 1;
        }
        /* V is the bud's internode; the tip's is its growth direction,
         * left to the geotropism below (at least tip_elevation): growing
         * on up the hook climbed the free stems back up (15 % more buds). */
        if (k > 0) qv[iv->buds[chain[k]].mark] = v3_norm_or(v3_sub(*P, prev_new), qv[iv->buds[chain[k]].mark]);
        prev_new = *P;
    }
#undef QP
    return moved;
}

static void sag_tip(banyan_ivy *iv, sag_consts *sc, int32_t tip) {
    const banyan_ivy_params *p = &iv->p;
    int32_t *chain = iv->chain, m = 0;
    /* Walk up to the anchor P0: a held bud, or one held by its other
     * branch (a dormant bud between two attached buds holds the lateral
     * that grew from it). */
    int32_t j = tip, prev = -1;
    while (j >= 0) {
        const ivy_bud *b = &iv->buds[j];
        if (held(iv, b)) break;
        if (prev >= 0) {
            int32_t other = b->child[0] == prev ? b->child[1] : b->child[0];
            if (other >= 0 && holds(iv, other, iv->moving, 256)) break;
        }
        chain[m++] = j;
        prev = j;
        j = b->parent;
    }
    if (j >= 0 && m > 0) {
        chain[m++] = j;
        /* chain[m-1] is P0, chain[m-2] P1, ..., chain[0] the tip. The
         * subtree of P1 in preorder: every bud's subtree is a contiguous
         * range starting at its own index (mark). */
        int32_t *set = iv->moving, *stack = iv->stack, *size = iv->sizes, n = 0, top = 0;
        stack[top++] = chain[m - 2];
        while (top > 0) {
            int32_t x = stack[--top];
            ivy_bud *b = &iv->buds[x];
            if (held(iv, b)) { n = -1; break; } /* held at both ends */
            b->mark = n;
            set[n++] = x;
            for (int k = 1; k >= 0; k--)
                if (b->child[k] >= 0) stack[top++] = b->child[k];
        }
        if (n > 0) {
            v3 *q = iv->tmp, *qv = q + iv->cap, *qn = qv + iv->cap;
            for (int32_t k = 0; k < n; k++) {
                size[k] = 1;
                q[k] = iv->buds[set[k]].P;
                qv[k] = iv->buds[set[k]].V;
            }
            for (int32_t k = n - 1; k > 0; k--) size[iv->buds[iv->buds[set[k]].parent].mark] += size[k];
            /* Turning a part about a later pivot can move the weight away
             * from an earlier one: sweep again until nothing turns. A
             * pivot that holds changes nothing, so the pivots 1..settled,
             * which held on the positions as the last turn left them, need
             * not be asked again while nothing above them turns. */
            int32_t settled = 0;
            int moved = 0;
            for (int pass = 0, turned = 1; turned && pass < SAG_PASSES; pass++) {
                turned = 0;
                for (int32_t k = m - 1; k >= 1; k--) {
                    if (!turned && k <= settled) break;
                    v3 pivot = k == m - 1 ? iv->buds[chain[k]].P : q[iv->buds[chain[k]].mark];
                    int32_t lo = iv->buds[chain[k - 1]].mark;
                    int r = sag_pivot(iv, sc, pivot, &iv->buds[chain[k]], q + lo, qv + lo, qn, size[lo], set + lo, lo);
                    if (r & SAG_TURNED) {
                        turned = moved = 1;
                        settled = r & SAG_UNSETTLED ? k - 1 : k;
                    }
                }
            }
            /* The tip hook comes last, as the spec's tip turning up, on a
             * stem that hangs (its tip below P0: a free stem standing
             * out keeps its tip as the geotropism leaves it; hooked, it crossed
             * more stems on the wall, density +18 % instead of +7 %); the
             * pivot P0 then holds the hooked stem (one rigid turn: the
             * hook keeps its shape), so F about P0 is within its
             * strength as the spec asks. */
            if (sc->hook > 0 && iv->buds[tip].run * p->internode > p->free_length &&
                q[iv->buds[tip].mark].z < iv->buds[chain[m - 1]].P.z - p->internode &&
                hook_tip(iv, sc, chain, m, q, qv)) {
                moved = 1;
                int32_t lo = iv->buds[chain[m - 2]].mark;
                sag_pivot(iv, sc, iv->buds[chain[m - 1]].P, &iv->buds[chain[m - 1]], q + lo,
                          qv + lo, qn, size[lo], set + lo, lo);
            }
            /* Move once (when anything turned); grip where a sucker now
             * reaches a surface; runs follow (preorder: parents first). */
            if (moved) ivy_grid_move_many(iv, set, q, n);
            for (int32_t k = 0; k < n; k++) {
                ivy_bud *b = &iv->buds[set[k]];
                b->V = v3_norm_or(qv[k], b->V);
                if (b->sucker && ivy_grip_distance(iv, b->P, p->sucker_length) <= p->sucker_length) b->attached = 1;
                b->run = b->attached ? 0 : iv->buds[b->parent].run + 1;
            }
        }
    }
    /* Geotropism: a long free tip points up. */
    ivy_bud *t = &iv->buds[tip];
    if (!t->attached && t->run * p->internode > p->free_length && t->V.z < sc->el_s) {
        v3 h = v3_make(t->V.x, t->V.y, 0);
        if (v3_len(h) < 1e-9 && t->parent >= 0) {
            v3 d = v3_sub(t->P, iv->buds[t->parent].P);
            h = v3_make(d.x, d.y, 0);
        }
        h = v3_norm_or(h, v3_make(1, 0, 0));
        t->V = v3_add(v3_scale(h, sc->el_c), v3_make(0, 0, sc->el_s));
    }
}

void ivy_sag(banyan_ivy *iv) {
    const banyan_ivy_params *p = &iv->p;
    sag_consts sc;
    sc.step = deg2rad(p->sag_step);
    sc.cs = dm_cos(sc.step);
    sc.sn = dm_sin(sc.step);
    sc.tan_half = dm_tan(0.5 * sc.step);
    sc.max_iter = (int)(180.0 / p->sag_step) + 2;
    double el = deg2rad(p->tip_elevation);
    sc.el_s = dm_sin(el);
    sc.el_c = dm_cos(el);
    sc.hook = (int32_t)floor(p->tip_hook_length / p->internode + 0.5);
    sc.hook_el = deg2rad(p->tip_hook_angle);
    sc.budget = (int64_t)SAG_BUDGET_PER_BUD * (iv->n > SAG_BUDGET_MIN / SAG_BUDGET_PER_BUD ? iv->n : SAG_BUDGET_MIN / SAG_BUDGET_PER_BUD);
    for (int32_t k = 0; k < iv->n_act; k++) {
        int32_t i = iv->act[k];
        const ivy_bud *b = &iv->buds[i];
        if (b->state <= BANYAN_IVY_A2 && !b->attached) sag_tip(iv, &sc, i);
    }
}
