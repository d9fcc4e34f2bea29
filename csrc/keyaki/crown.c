/* crown.c - the keyaki's twigs, leaves and the light-and-crowding model
 * (beyond the paper; spec/keyaki.md "Sun model" is its proposed future
 * work; docs/keyaki.md "Twigs and leaves", "Light and crowding").
 *
 * Below the edaore skeleton: the skeleton branches within leaf_levels of a
 * tip carry first-order twigs every twig_spacing, alternating sides along
 * the branch's horizontal perpendicular, at twig_angle; every skeleton tip
 * continues in one. A first-order twig with its sub-twigs and leaves is a
 * cluster: a flat, zigzag spray (+-12 deg at each node) carrying the next
 * order every twig_spacing x twig_ratio^k, twig_ratio^k as long, to
 * twig_levels orders. Radii follow the pipe model inside the cluster from
 * twig_radius at every tip, never above 0.8 of the branch they sit on.
 * Leaves: one quad each, two-ranked (left, right, ...) every
 * 1 / leaf_density along the finest twigs and the distal part of coarser
 * ones, the last at the tip, so no twig sticks out bare. Spray cards (one
 * quad showing a painted spray of the leaf atlas, leaf_look.h) give the
 * crown its leaf mass: on from every twig's end, beside the nodes and
 * along long finest twigs. Branches deeper than leaf_levels carry shoots
 * of spray cards where they lie on the crown's outer shell, from
 * SHELL_FROM of the height up (crown_shell.c).
 *
 * Light and crowding: a cluster is approximated by its plan-view
 * rectangle (what it shades under a zenith sun). Clusters grow from the
 * highest down over a plan grid of 0.2 m cells counting the clusters
 * above; a cell is shaded once it holds >= shade_layers. Before growing,
 * a cluster measures the shaded fraction of its rectangle's left and
 * right halves: lit -> grows, on into empty cells past its length (holes
 * fill); one side shaded -> turns up to light_steer towards the lit side;
 * both shaded -> a short leafy spur; all shaded -> dropped. Then its
 * rectangle is stamped (a shell cluster never breaks nor stops). The
 * skeleton is never touched: its Strahler
 * statistics stay the paper's.
 *
 * Everything lands in flat arrays first (counted exactly for
 * keyaki_body_plan), then meshed. Random draws come from the "twigs" and
 * "leaves" streams keyed by (seed, cluster), so light on or off changes
 * no other cluster's draws. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "textures/leaf_look.h"
#include "mesh/tube.h"
#include "crown_internal.h"

#define EXTEND 6.0         /* a cluster grows at most this x its length on into empty cells */
#define HOLE_SHARE 0.6     /* a cluster grows on while this share of the cells ahead are holes */
#define ZIGZAG_DEG 12.0     /* a twig's turn at each node, alternately */
#define TWIG_SETBACK_CAP 0.8 /* a twig's base radius: at most this x its parent's there */
#define CARD_LENGTH 5.5     /* a spray card's length / leaf_size: its painted leaves come out leaf-sized */
#define CARD_ROLL_DEG 35.0  /* a spray card's largest roll about its twig */
#define CARD_EVERY 0.6      /* cards along a long finest twig: one every this many card lengths */
#define SHOOT_FAN_DEG 50.0  /* the side cards at a shoot's end: this far either side of it */
#define CARD_LAYERS 3        /* spray cards one plan cell of a height band holds in the crown's upper half */
#define CARD_LAYERS_LOW 6    /* ... and in its lower half (its skirt, lit from the side) */
#define CARD_BAND 2.0        /* m: the height bands of that cap */
#define CARD_CELLS_MAX 16e6  /* cells (int32) of the cap's grid, bands included: 64 MB */

void keyaki_crown_free(keyaki_crown *c) {
    if (!c) return;
    free(c->twigs);
    free(c->pts);
    free(c->rad);
    free(c->leaves);
    memset(c, 0, sizeof *c);
}

static int add_points(keyaki_crown *c, int32_t k) {
    int32_t cap = c->cap_pts;
    if (crown_grow_array((void **)&c->pts, &cap, c->n_pts + k, sizeof(v3))) return 1;
    cap = c->cap_pts;
    if (crown_grow_array((void **)&c->rad, &cap, c->n_pts + k, sizeof(double))) return 1;
    c->cap_pts = cap;
    return 0;
}

/* The grown state one cluster needs. */
typedef struct ctx {
    const banyan_keyaki_params *p;
    keyaki_crown *c;
    pcg32 tw, lf; /* twig and leaf draws of this cluster */
    int32_t node, base_level;
    int cards_only; /* a shell cluster: spray cards, no single leaves */
    double sub_base; /* m: the cluster's planned length (its sub-twigs' lengths follow it); 0: len's */
    int oom; /* 1: out of memory, 2: past max_vertices, 3: the run stopped, 4: refused (err set) */
    keyaki_run *run;
    uint64_t base; /* vertices the tree needs besides the crown (promised by the body's plan) */
    banyan_status st; /* the refusal of oom 4 */
    const double *npath; /* per skeleton branch: path length from the trunk base to its start, m */
    int32_t *cards;      /* per plan cell of the light grid: spray cards centred there so far (NULL: no cap) */
    double gx0, gy0;     /* the light grid's corner, m */
    int32_t gnx, gny, gnb; /* its cells, and CARD_BAND height bands up from z0 */
    double z0, half_z;     /* m: the trunk's foot and half the skeleton's height */
    double band;           /* m: the bands' height (CARD_BAND, more on a giant tree) */
} ctx;

static int over_budget(ctx *x, int64_t more_leaves, int64_t more_points) {
    int64_t v = 4 * ((int64_t)x->c->n_leaves + more_leaves) + 6 * ((int64_t)x->c->n_pts + more_points);
    if (v > crown_budget(x->p, x->c->count_only)) x->oom = 2;
    return x->oom != 0;
}

/* The run's budget, every few clusters: its stop, and the crown so far
 * (at least 4 vertices a twig point, a ring of 3 sides or more, and 4 a
 * leaf) promised with the rest of the tree. */
static int keep_budget(ctx *x, banyan_error *err) {
    if (!x->run || x->oom) return x->oom != 0;
    if (keyaki_stopped(x->run)) x->oom = 3;
    else if ((x->st = keyaki_promise(x->run, x->base + 4 * ((uint64_t)x->c->n_pts + (uint64_t)x->c->n_leaves),
                            "the tree with the twigs and leaves grown so far",
                            "leaf_density, leaf_levels, twig_levels or raise twig_spacing", err)))
        x->oom = 4;
    return x->oom != 0;
}

/* Point and unit tangent at arc length s along polyline pts[0..n-1];
 * *r (may be NULL) the radius there, rad linear between points. */
static v3 along_r(const v3 *pts, const double *rad, int32_t n, double s, v3 *t, double *r) {
    for (int32_t i = 0; i + 1 < n; i++) {
        double l = v3_dist(pts[i], pts[i + 1]);
        if (s <= l || i + 2 == n) {
            *t = v3_norm_or(v3_sub(pts[i + 1], pts[i]), v3_make(0, 0, 1));
            double u = l > 0 ? clampd(s, 0, l) : 0;
            if (r) *r = rad[i] + (rad[i + 1] - rad[i]) * (l > 0 ? u / l : 0);
            return v3_madd(pts[i], *t, u);
        }
        s -= l;
    }
    *t = v3_make(0, 0, 1);
    if (r) *r = rad[0];
    return pts[0];
}

static double poly_length(const v3 *pts, int32_t n) {
    double l = 0;
    for (int32_t i = 0; i + 1 < n; i++) l += v3_dist(pts[i], pts[i + 1]);
    return l;
}

/* Two-ranked leaves along pts[0..n-1] from arc length s0 to the end (the
 * last at the end), every 1 / leaf_density; `up` is the spray's normal:
 * the ranks lie left and right of the twig in the spray plane. rad: the
 * wood's radius at each point, path0: the path length from the trunk
 * base to pts[0] (a leaf's stiffness and birth). */
/* The width of a blade or card of unit axis a: level across a, rolled by
 * `roll` (rad) about a, turned so that width x axis faces the sky. */
static v3 rolled_width(v3 a, double roll) {
    v3 w = v3_norm_or_perp(v3_cross(v3_make(0, 0, 1), a), a);
    w = v3_add(v3_scale(w, dm_cos(roll)), v3_scale(v3_cross(a, w), dm_sin(roll)));
    return v3_cross(w, a).z < 0 ? v3_neg(w) : w;
}

static void leaves_along(ctx *x, const v3 *pts, const double *rad, int32_t n, double s0, v3 up, int32_t twig,
                         int32_t level, double path0) {
    const banyan_keyaki_params *p = x->p;
    if (!p->leaves || p->leaf_density <= 0 || n < 2) return;
    double L = poly_length(pts, n), step = 1.0 / p->leaf_density;
    if (L <= 0) return;
    int32_t k = (int32_t)floor((L - s0) / step) + 1;
    if (k < 1) k = 1;
    if (k > 100000) k = 100000;
    keyaki_crown *c = x->c;
    if (over_budget(x, k, 0)) return;
    if (c->count_only) { /* the same k as placing them: only the twig decides it */
        c->n_leaves += k;
        return;
    }
    if (crown_grow_array((void **)&c->leaves, &c->cap_leaves, c->n_leaves + k, sizeof(keyaki_leaf))) {
        x->oom = 1;
        return;
    }
    int side = rng_uniform(&x->lf) < 0.5 ? 1 : -1;
    const v3 Z = v3_make(0, 0, 1);
    double V = LEAF_KEYAKI_BLADE_V1 - LEAF_KEYAKI_BLADE_V0;
    for (int32_t j = 0; j < k; j++, side = -side) {
        /* j = 0 apart: a density so small (1e-317) that step overflows to
         * inf gives k = 1, and 0 x inf would be NaN. */
        double s = j ? L - j * step : L;
        double r_at;
        v3 t, at = along_r(pts, rad, n, s, &t, &r_at);
        v3 sv = v3_norm_or_perp(v3_cross(up, t), t);
        /* Out from the twig at 45-70 deg on its side, drooping a little. */
        double th = deg2rad(rng_range(&x->lf, 45.0, 70.0));
        v3 a = v3_add(v3_scale(t, dm_cos(th)), v3_scale(sv, side * dm_sin(th)));
        a = v3_norm(v3_madd(a, Z, -rng_range(&x->lf, 0.0, 0.4)));
        /* Blade facing the sky, rolled up to +-45 deg about its midrib: a
         * crown of only level blades is edge-on, nearly invisible, from
         * the side; real blades turn every way to the light. */
        v3 w = rolled_width(a, deg2rad(rng_range(&x->lf, -45.0, 45.0)));
        /* Smaller near the twig's base and tip. */
        double f = 0.8 + 0.25 * dm_sin(BANYAN_PI * clampd(s / L, 0, 1));
        double blade = p->leaf_size * f * (1.0 + p->leaf_size_spread * rng_range(&x->lf, -1.0, 1.0));
        keyaki_leaf *q = &c->leaves[c->n_leaves++];
        q->base = at;
        q->axis = a;
        q->width = w;
        q->length = blade / V;
        q->twig = twig;
        q->node = x->node;
        q->side = side;
        q->level = level;
        q->path = (float)(path0 + s);
        q->card = 0;
    }
}

/* A spray card continuing a twig from its end `at` along t (leaf_look.h,
 * LEAF_KEYAKI_SPRAY_*): CARD_LENGTH x leaf_size long, lying in the spray
 * plane of normal `up` drooping a little, rolled up to +-CARD_ROLL_DEG
 * about its twig; the painted twig's base sits on `at`. One card: the
 * count never depends on a draw. */
static void card_at(ctx *x, v3 at, v3 t, v3 up, int32_t twig, int32_t level, double path) {
    const banyan_keyaki_params *p = x->p;
    if (!p->leaves || p->leaf_density <= 0) return;
    keyaki_crown *c = x->c;
    if (x->cards) {
        /* Deep shade sheds leaves: a card whose centre falls in a plan cell
         * already holding CARD_LAYERS cards (placed by the clusters above:
         * they grow highest first) is not grown. From the twig alone, so
         * counting and placing agree. */
        v3 mid = v3_madd(at, t, 0.5 * CARD_LENGTH * p->leaf_size);
        int32_t i = (int32_t)floor((mid.x - x->gx0) / CELL), j = (int32_t)floor((mid.y - x->gy0) / CELL);
        int32_t b = (int32_t)clampd(floor((mid.z - x->z0) / x->band), 0, x->gnb - 1);
        if (i >= 0 && j >= 0 && i < x->gnx && j < x->gny) {
            int32_t *k = &x->cards[((size_t)b * (size_t)x->gny + (size_t)j) * (size_t)x->gnx + (size_t)i];
            if (*k >= (mid.z < x->half_z ? CARD_LAYERS_LOW : CARD_LAYERS)) return;
            (*k)++;
        }
    }
    if (over_budget(x, 1, 0)) return;
    if (c->count_only) {
        c->n_leaves++;
        return;
    }
    if (crown_grow_array((void **)&c->leaves, &c->cap_leaves, c->n_leaves + 1, sizeof(keyaki_leaf))) {
        x->oom = 1;
        return;
    }
    const v3 Z = v3_make(0, 0, 1);
    /* Turned a little aside in the spray plane, drooping a little. */
    v3 a = v3_rotate(t, up, deg2rad(rng_range(&x->lf, -15.0, 15.0)));
    a = v3_norm(v3_madd(a, Z, -rng_range(&x->lf, 0.0, 0.3)));
    v3 w = rolled_width(a, deg2rad(rng_range(&x->lf, -CARD_ROLL_DEG, CARD_ROLL_DEG)));
    double len = CARD_LENGTH * p->leaf_size * (1.0 + 0.5 * p->leaf_size_spread * rng_range(&x->lf, -1.0, 1.0));
    keyaki_leaf *q = &c->leaves[c->n_leaves++];
    q->base = at; /* the card's base edge lies LEAF_KEYAKI_SPRAY_U0 x len behind it */
    q->axis = a;
    q->width = w;
    q->length = len;
    q->twig = twig;
    q->node = x->node;
    q->side = 1;
    q->level = level;
    q->path = (float)path;
    q->card = 1;
}

/* Grows one twig of `order` from point `at` (on its parent's axis, whose
 * radius there is r_host) along d in the spray plane of normal `up`,
 * `len` long; appends its sub-twigs and leaves. Returns the tips in its
 * subtree (0 on failure). The tube starts on the parent's axis with
 * KEYAKI_SIDE_START of its base radius and reaches its full radius at
 * the parent's surface, as the body's side limbs do. */
static int32_t grow_twig(ctx *x, int32_t order, int32_t parent, v3 at, v3 d, v3 up, double len, double r_host,
                         int leafy_only, double path0) {
    const banyan_keyaki_params *p = x->p;
    keyaki_crown *c = x->c;
    /* A shell cluster is one shoot of spray cards: no sub-twigs. */
    int card_shoot = x->cards_only && order == 1;
    int finest = order >= p->twig_levels || leafy_only || card_shoot;
    double sub_spacing = p->twig_spacing * dm_pow(p->twig_ratio, order);
    /* A shoot grown on into a gap keeps its planned sub-twigs. */
    double sub_len = (order == 1 && x->sub_base > 0 ? fmin(len, x->sub_base) : len) * p->twig_ratio;
    /* Nodes: where sub-twigs attach (coarse), where cards sit (a card
     * shoot) or every few leaves (finest). */
    int32_t segs;
    if (card_shoot) segs = (int32_t)clampd(floor(len / sub_spacing + 0.5), 2, MAX_TWIG_PTS - 3);
    else if (finest) segs = (int32_t)clampd(floor(len * p->leaf_density / 4.0 + 0.5), 1, 3);
    else segs = (int32_t)clampd(floor(len / sub_spacing + 0.5), 1, MAX_TWIG_PTS - 3);
    /* A first-order twig leaves a thick branch: an axis point inside it,
     * then one on its surface. A sub-twig's parent is a few mm thick: its
     * first node is the point where it leaves the parent's axis. */
    int surface = parent < 0;
    int32_t np = segs + 1 + surface;
    if (over_budget(x, 0, np)) return 0;
    if (crown_grow_array((void **)&c->twigs, &c->cap_twigs, c->n_twigs + 1, sizeof(keyaki_twig)) || add_points(c, np)) {
        x->oom = 1;
        return 0;
    }
    int32_t me = c->n_twigs++;
    keyaki_twig *T = &c->twigs[me];
    T->first = c->n_pts;
    T->count = np;
    T->parent = parent;
    T->node = x->node;
    T->order = order;
    T->level = x->base_level + order;
    T->sides = order <= 1 && !finest ? 4 : 3;
    T->children = 0;
    T->path0 = path0;
    c->n_pts += np;
    v3 *P = c->pts + T->first;
    double *R = c->rad + T->first;
    double seg = len / segs;
    P[0] = at;
    if (surface) P[1] = v3_madd(at, d, r_host < seg * 0.45 ? r_host : seg * 0.45);
    int zig = rng_uniform(&x->tw) < 0.5 ? 1 : -1;
    v3 dir = d;
    for (int32_t i = 0; i < segs; i++, zig = -zig) {
        v3 di = v3_rotate(dir, up, deg2rad(zig * ZIGZAG_DEG * rng_range(&x->tw, 0.8, 1.2)));
        P[surface + 1 + i] = v3_madd(P[surface + i], di, seg);
    }
    /* Sub-twigs at the nodes up to 0.7 of the length, alternating sides,
     * each on the outer side of the zigzag's bend. */
    int32_t sub_tips[MAX_TWIG_PTS];
    memset(sub_tips, 0, sizeof sub_tips);
    double cum[MAX_TWIG_PTS]; /* path length at each point */
    cum[0] = path0;
    for (int32_t k = 1; k < np; k++) cum[k] = cum[k - 1] + v3_dist(P[k - 1], P[k]);
    int32_t tips = 1; /* its own end */
    if (!finest) {
        int side = rng_uniform(&x->tw) < 0.5 ? 1 : -1;
        for (int32_t i = 1; i <= segs && !x->oom; i++, side = -side) {
            if (i * seg > 0.7 * len + 1e-9 && i > 1) break;
            int32_t k = surface + i; /* point index of node i */
            v3 t = v3_norm(v3_sub(P[k], P[k - 1]));
            v3 sd = v3_rotate(t, up, deg2rad(side * p->twig_angle * rng_range(&x->tw, 0.85, 1.15)));
            double l = sub_len * rng_range(&x->tw, 0.8, 1.2);
            /* The parent's radius here is not known yet: the pipe model
             * of what it carries; twig_radius is its floor. */
            int32_t st = grow_twig(x, order + 1, me, P[k], sd, up, l, p->twig_radius, 0, cum[k]);
            P = c->pts + c->twigs[me].first; /* the arrays may have moved */
            R = c->rad + c->twigs[me].first;
            /* A spray card on every other node's other side. */
            if (i % 2 == 0)
                card_at(x, P[k], v3_rotate(t, up, deg2rad(-side * p->twig_angle)), up, me, c->twigs[me].level, cum[k]);
            sub_tips[k] = st;
            tips += st;
            c->twigs[me].children++;
        }
    }
    /* Pipe radii from the tip back: ring k carries the sub-twigs attached
     * beyond it. */
    double pe = p->pipe_exponent;
    int32_t carried = 1;
    for (int32_t k = np - 1; k >= 0; k--) {
        R[k] = p->twig_radius * dm_pow((double)carried, 1.0 / pe);
        carried += sub_tips[k];
    }
    double cap = TWIG_SETBACK_CAP * r_host;
    for (int32_t k = 0; k < np; k++)
        if (parent < 0 && R[k] > cap && cap >= p->twig_radius) R[k] = cap;
    if (surface) R[0] = KEYAKI_SIDE_START * R[1];
    /* Leaves: all along a finest twig, the distal 35 % of a coarser one. */
    double L = poly_length(P + surface, np - surface);
    int32_t level = c->twigs[me].level;
    v3 pts_copy[MAX_TWIG_PTS];
    double rad_copy[MAX_TWIG_PTS];
    memcpy(pts_copy, P + surface, sizeof(v3) * (size_t)(np - surface));
    memcpy(rad_copy, R + surface, sizeof(double) * (size_t)(np - surface));
    if (!x->cards_only)
        leaves_along(x, pts_copy, rad_copy, np - surface, finest ? 0.1 * L : 0.65 * L, up, me, level, cum[surface]);
    /* A long finest twig (a gap-filling shoot's) carries cards along it
     * every CARD_EVERY card lengths back from its end, sides alternating. */
    if (finest && !card_shoot && np - surface >= 2) {
        double every = CARD_EVERY * CARD_LENGTH * p->leaf_size;
        int32_t m = every > 0 ? (int32_t)clampd(floor(L / every), 0, 1000) : 0;
        for (int32_t j = 1, sd = 1; j <= m; j++, sd = -sd) {
            v3 t;
            v3 at = along_r(pts_copy, rad_copy, np - surface, L - j * every, &t, NULL);
            card_at(x, at, v3_rotate(t, up, deg2rad(sd * p->twig_angle)), up, me, level, cum[surface] + L - j * every);
        }
    }
    /* A card shoot: a card at every node, sides alternating. */
    for (int32_t i = 1, sd = 1; card_shoot && i < segs; i++, sd = -sd) {
        v3 t = v3_norm_or(v3_sub(pts_copy[i], pts_copy[i - 1]), up);
        card_at(x, pts_copy[i], v3_rotate(t, up, deg2rad(sd * p->twig_angle)), up, me, level, cum[surface + i]);
    }
    /* A spray card on from every twig's end; a shoot's end (a twig with
     * sub-twigs, or a card shoot) fans two more either side, filling the
     * crown's edge. */
    if (np - surface >= 2) {
        const v3 *E = pts_copy + (np - surface - 1);
        v3 te = v3_norm_or(v3_sub(*E, E[-1]), up);
        card_at(x, *E, te, up, me, level, cum[np - 1]);
        for (int sgn = -1; sgn <= 1 && (!finest || card_shoot); sgn += 2)
            card_at(x, *E, v3_rotate(te, up, deg2rad(sgn * SHOOT_FAN_DEG)), up, me, level, cum[np - 1]);
    }
    if (c->twigs[me].children == 0) c->tips++;
    return tips;
}

static int cand_cmp(const void *a, const void *b) {
    const cand *A = a, *B = b;
    if (A->z != B->z) return A->z > B->z ? -1 : 1;
    return A->index < B->index ? -1 : A->index > B->index;
}

/* Leaves along the segment lines of skeleton tip x (twigs_from_segments). */
static void segment_leaves(ctx *x, const keyaki_node *n, int32_t i) {
    float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
    uint8_t lev[BANYAN_SEGMENT_MAX_VERTICES], par[BANYAN_SEGMENT_MAX_VERTICES / 2];
    double path[BANYAN_SEGMENT_MAX_VERTICES / 2];
    int32_t nv = keyaki_twig_lines(x->p, &n[i], x->npath[i], xyz, lev, par, path);
    for (int32_t j = 2; j + 1 < nv && !x->oom; j += 2) {
        v3 ab[2] = {v3_make(xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]),
                    v3_make(xyz[3 * j + 3], xyz[3 * j + 4], xyz[3 * j + 5])};
        double l = v3_dist(ab[0], ab[1]);
        if (l < 1e-6) continue;
        v3 t = v3_scale(v3_sub(ab[1], ab[0]), 1.0 / l);
        v3 up = v3_norm_or_perp(v3_cross(crown_horizontal_perp(t), t), t);
        if (up.z < 0) up = v3_neg(up);
        double r = keyaki_twig_radius(x->p, &n[i], lev[j]), rr[2] = {r, r};
        leaves_along(x, ab, rr, 2, 0.1 * l, up, -1, n[i].level + lev[j], path[j / 2]);
    }
}

/* The draws of cluster (or skeleton branch) `index`: a stream of its
 * own, so dropping or reshaping one cluster moves no other's. */
static void cluster_stream(pcg32 *r, const banyan_keyaki_params *p, int32_t index, uint64_t stream) {
    pcg32_seed(r, p->seed * 0x9e3779b97f4a7c15ull + (uint64_t)index, stream);
}

/* A twig direction nearly level (rising FLAT_RISE of its plan length) in
 * its plan direction; a vertical one kept. */
#define FLAT_RISE 0.15
static v3 flat_dir(v3 d) {
    double hx = sqrt(d.x * d.x + d.y * d.y);
    if (hx < 0.05) return d;
    return v3_norm(v3_make(d.x / hx, d.y / hx, FLAT_RISE));
}

/* Turns a cluster's twig, side vector and spray normal about the vertical. */
static void turn_cluster(cand *q, v3 *up, double a) {
    q->d = v3_rotate_z(q->d, a);
    q->h = v3_rotate_z(q->h, a);
    *up = v3_rotate_z(*up, a);
}

static banyan_status crown_fail(keyaki_crown *c, int why, banyan_status st, const banyan_keyaki_params *p,
                                banyan_error *err) {
    int count_only = c->count_only;
    keyaki_crown_free(c);
    if (why == 3) return keyaki_stop_status(err);
    if (why == 4) return st;
    if (why == 2)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the tree's twigs and leaves need more than max_vertices = %lld vertices; raise "
                           "max_vertices or lower leaf_density, leaf_levels, twig_levels or raise twig_spacing",
                           (long long)crown_budget(p, count_only));
    return banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
}

/* No twigs of ours: leaves on the segment lines (twigs_from_segments), or
 * on the skeleton branches within leaf_levels of a tip. */
static void leaves_without_twigs(ctx *x, const keyaki_node *n, int32_t count, const int32_t *depth,
                                 const double *npath, banyan_error *err) {
    const banyan_keyaki_params *p = x->p;
    for (int32_t i = 0; i < count && !x->oom; i++) {
        if ((i & 255) == 0 && keep_budget(x, err)) break;
        int tip = n[i].child[0] < 0 && n[i].child[1] < 0;
        x->node = i;
        cluster_stream(&x->lf, p, i, KEYAKI_STREAM_LEAVES);
        if (p->twigs_from_segments) {
            if (tip) segment_leaves(x, n, i);
        } else if (depth[i] < p->leaf_levels) {
            v3 ab[2] = {n[i].start, v3_madd(n[i].start, n[i].dir, n[i].length)};
            v3 up = v3_norm_or_perp(v3_cross(crown_horizontal_perp(n[i].dir), n[i].dir), n[i].dir);
            if (up.z < 0) up = v3_neg(up);
            double rr[2] = {crown_branch_radius(p, n, &n[i], 0), crown_branch_radius(p, n, &n[i], n[i].length)};
            leaves_along(x, ab, rr, 2, 0.0, up, -1, n[i].level, npath[i]);
        }
    }
}

/* Plans the clusters of skeleton branch i (within leaf_levels of a tip):
 * first-order twigs every twig_spacing, alternating sides, and a skeleton
 * tip's continuation; appended to *pcs. 0, or 1 when out of memory, 2 past
 * the budget. */
static int plan_branch(const banyan_keyaki_params *p, const keyaki_node *n, int32_t i, pcg32 *plan, double path,
                       cand **pcs, int32_t *pnc, int32_t *cap, int count_only) {
    int32_t nc = *pnc;
    const keyaki_node *b = &n[i];
    int tip = b->child[0] < 0 && b->child[1] < 0;
    v3 h = crown_horizontal_perp(b->dir);
    int side = rng_uniform(plan) < 0.5 ? 1 : -1;
    double s = p->twig_spacing * rng_uniform(plan);
    int32_t k = (int32_t)((b->length - s) / p->twig_spacing) + 1 + tip;
    if (k < 0) k = 0;
    /* Every cluster, even one the light drops, would be a tube of 8
     * vertices or more: refuse absurd counts before storing them. */
    if (8.0 * ((double)nc + k) > (double)crown_budget(p, count_only)) return 2;
    if (crown_grow_array((void **)pcs, cap, nc + k, sizeof(cand))) return 1;
    cand *cs = *pcs;
    for (; s < b->length; s += p->twig_spacing, side = -side) {
        cand *q = &cs[nc];
        double a = deg2rad(p->twig_angle * rng_range(plan, 0.85, 1.15));
        q->at = v3_madd(b->start, b->dir, s);
        q->d = v3_norm(v3_add(v3_scale(b->dir, dm_cos(a)), v3_scale(h, side * dm_sin(a))));
        q->h = h;
        q->len = p->twig_length * rng_range(plan, 0.75, 1.25);
        q->r_host = crown_branch_radius(p, n, b, s);
        q->path = path + s;
        q->node = i;
        q->index = nc;
        q->tip = 0;
        q->shell = 0;
        nc++;
    }
    if (tip) {
        cand *q = &cs[nc];
        q->at = v3_madd(b->start, b->dir, b->length);
        q->d = b->dir;
        q->h = h;
        q->len = p->twig_length * rng_range(plan, 0.75, 1.25);
        q->r_host = crown_branch_radius(p, n, b, b->length);
        q->path = path + b->length;
        q->node = i;
        q->index = nc;
        q->tip = 1;
        q->shell = 0;
        nc++;
    }
    *pnc = nc;
    return 0;
}

/* One cluster in the light model (grid g): shaded on both sides under 0.9
 * of the sky it breaks (returns 1) unless a tip or shell cluster; half
 * shaded it stays a short leafy spur (*spur, *len); else it turns towards
 * the lit side and grows on into the gaps ahead, up to EXTEND x its
 * length. Its reach is then stamped into the sky. Counts in c. */
static int light_cluster(const banyan_keyaki_params *p, grid *g, keyaki_crown *c, cand *q, v3 *up, double *len,
                         int *spur) {
    rect r = crown_cluster_rect(p, q->at, q->d, q->h, *len, *len);
    double fl, fr;
    crown_sky_shade(g, r, q->z, p->shade_layers, &fl, &fr);
    double lo = fmin(fl, fr), hi = fmax(fl, fr);
    if (lo >= 0.9 && !q->tip && !q->shell) { /* all shaded: the cluster breaks */
        c->dropped++;
        return 1;
    }
    if (lo >= 0.5 && !q->shell) { /* both sides shaded: a short leafy spur */
        *spur = 1;
        *len = fmin(*len, fmax(0.3 * *len, 3.0 / fmax(p->leaf_density, 1e-9)));
        c->stopped++;
    } else {
        if (hi >= 0.25) { /* one side shaded: turn towards the lit one */
            /* left is +90 deg about z from the plan axis: turning left is a positive angle */
            double a = deg2rad(p->light_steer * fmin(1.0, 2.0 * (hi - lo)) * (fl > fr ? -1.0 : 1.0));
            turn_cluster(q, up, a);
            c->steered++;
        } else {
            c->grown++;
        }
        /* Lit ahead: grow on into empty cells inside the outline, up
         * to EXTEND x the length, heading straight on or up to
         * light_steer aside, whichever reaches furthest into the
         * hole (straight on a tie). */
        double best = 0, best_a = 0;
        for (int h = 0; h < 5 && hypot(q->d.x, q->d.y) >= 0.05; h++) {
            double a = deg2rad(p->light_steer * (h == 0 ? 0 : h == 1 ? 1 : h == 2 ? -1 : h == 3 ? 2 : -2));
            rect r2 = crown_cluster_rect(p, q->at, flat_dir(v3_rotate_z(q->d, a)), v3_rotate_z(q->h, a), *len, *len);
            /* As far as the cells ahead stay mostly (HOLE_SHARE) holes. */
            double ext = 0;
            int32_t seen = 0, holes = 0;
            for (double t = 0; t < EXTEND * q->len; t += p->twig_spacing) {
                double ex = r2.ox + r2.ax * (r2.len + t + 0.5 * CELL);
                double ey = r2.oy + r2.ay * (r2.len + t + 0.5 * CELL);
                int hole = crown_hole_at(g, ex, ey);
                seen++, holes += hole;
                if (hole && holes >= HOLE_SHARE * seen) ext = t + p->twig_spacing;
                if (holes < HOLE_SHARE * seen - 2) break;
            }
            if (ext > best) best = ext, best_a = a;
        }
        if (best_a != 0) turn_cluster(q, up, best_a);
        if (best > 0) { /* a shoot into a gap grows out sideways, toward the light */
            q->d = flat_dir(q->d);
            *up = v3_norm_or_perp(v3_cross(q->d, q->h), q->d);
            if (up->z < 0) *up = v3_neg(*up);
        }
        *len += best;
    }
    crown_sky_stamp(g, crown_cluster_rect(p, q->at, q->d, q->h, *spur ? *len * 0.5 : *len, q->len), q->z);
    return 0;
}

/* The plan grid over every cluster's reach, with room for the oblique
 * layers' shifts, and its arrays (none over ~400 m across: no light
 * model, g->nx 0); the card cap's height bands into x. The caller checks
 * the allocations. */
static void plan_grid(const banyan_keyaki_params *p, const cand *cs, int32_t nc, const shell *sh, grid *g, ctx *x) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (int32_t k = 0; k < nc; k++) {
        x0 = fmin(x0, cs[k].at.x), x1 = fmax(x1, cs[k].at.x);
        y0 = fmin(y0, cs[k].at.y), y1 = fmax(y1, cs[k].at.y);
    }
    double z0 = 1e300, z1 = -1e300;
    for (int32_t k = 0; k < nc; k++) z0 = fmin(z0, cs[k].z), z1 = fmax(z1, cs[k].z);
    g->zref = 0.5 * (z0 + z1);
    /* Room for the oblique layers' shifts, at most half the crown's depth. */
    double m = 3.0 * p->twig_length + 1.0 + 0.5 * (z1 - z0) / dm_tan(deg2rad(SKY_ELEVATION_DEG));
    g->x0 = x0 - m;
    g->y0 = y0 - m;
    g->nx = (int32_t)ceil((x1 - x0 + 2 * m) / CELL) + 1;
    g->ny = (int32_t)ceil((y1 - y0 + 2 * m) / CELL) + 1;
    if ((double)g->nx * g->ny > 4e6) g->nx = g->ny = 0; /* a crown over ~400 m across: no light model */
    else {
        /* The card cap's height bands: CARD_BAND, fewer and taller on a
         * giant tree, so its grid stays within CARD_CELLS_MAX cells. */
        double reach = sh->height + 2.0 * p->twig_length, most = CARD_CELLS_MAX / ((double)g->nx * g->ny);
        double nb = fmin(ceil(reach / CARD_BAND) + 1.0, fmax(1.0, floor(most)));
        x->z0 = sh->z0, x->half_z = sh->z0 + 0.5 * sh->height;
        x->gnb = (int32_t)nb, x->band = fmax(CARD_BAND, reach / nb);
        x->gx0 = g->x0, x->gy0 = g->y0, x->gnx = g->nx, x->gny = g->ny;
        g->n = calloc((size_t)g->nx * (size_t)g->ny, sizeof(int32_t));
        g->in = malloc((size_t)g->nx * (size_t)g->ny);
        g->sky = calloc((size_t)SKY_OBLIQUE * (size_t)g->nx * (size_t)g->ny, sizeof(int32_t));
        x->cards = calloc((size_t)g->nx * (size_t)g->ny * (size_t)x->gnb, sizeof(int32_t));
    }
}

/* Each node's depth: the fewest forks from it down to a tip (0 at a tip). */
static void branch_depths(const keyaki_node *n, int32_t count, int32_t *depth) {
    for (int32_t i = count - 1; i >= 0; i--) {
        int32_t a = n[i].child[0], b = n[i].child[1];
        if (a < 0 && b < 0) depth[i] = 0;
        else if (a < 0 || b < 0) depth[i] = depth[a >= 0 ? a : b] + 1;
        else depth[i] = 1 + (depth[a] < depth[b] ? depth[a] : depth[b]);
    }
}

banyan_status keyaki_crown_grow(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, int count_only,
                                keyaki_run *run, keyaki_crown *c, banyan_error *err) {
    memset(c, 0, sizeof *c);
    c->count_only = count_only;
    c->run = run;
    if (count <= 0 || p->leaf_levels <= 0) return BANYAN_OK;
    int32_t *depth = malloc(sizeof(int32_t) * (size_t)count);
    double *npath = malloc(sizeof(double) * (size_t)count);
    if (!depth || !npath) {
        free(depth);
        free(npath);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
    }
    keyaki_node_paths(n, count, npath);
    branch_depths(n, count, depth);
    ctx x = {p, c, {0, 0}, {0, 0}, 0, 0, 0, 0, 0.0, run, run ? run->promised : 0, BANYAN_OK, npath, NULL, 0, 0, 0, 0,
             0, 0, 0, CARD_BAND};
    if (p->twigs_from_segments || p->twig_levels == 0) {
        leaves_without_twigs(&x, n, count, depth, npath, err);
        free(depth);
        free(npath);
        if (x.oom) return crown_fail(c, x.oom, x.st, p, err);
        return BANYAN_OK;
    }
    /* The clusters planned on the skeleton, from the "twigs" stream. */
    pcg32 plan;
    pcg32_seed(&plan, p->seed, KEYAKI_STREAM_TWIGS);
    cand *cs = NULL;
    int32_t nc = 0, cap = 0;
    shell sh;
    if (crown_shell_of(&sh, n, count)) {
        free(depth);
        free(npath);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
    }
    for (int32_t i = 0; i < count; i++) {
        if ((i & 4095) == 0 && keyaki_stopped(run)) {
            free(depth);
            free(npath);
            free(cs);
            free(sh.env);
            return crown_fail(c, 3, BANYAN_OK, p, err);
        }
        if (depth[i] >= p->leaf_levels) {
            if (crown_shell_clusters(&sh, p, n, i, &plan, npath[i], &cs, &nc, &cap, count_only)) {
                int why = sh.why;
                free(depth);
                free(npath);
                free(cs);
                free(sh.env);
                return why == 2 ? crown_fail(c, 2, BANYAN_E_LIMIT, p, err)
                                : banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
            }
            continue;
        }
        int why = plan_branch(p, n, i, &plan, npath[i], &cs, &nc, &cap, count_only);
        if (why) {
            free(depth);
            free(npath);
            free(cs);
            free(sh.env);
            return why == 2 ? crown_fail(c, 2, BANYAN_E_LIMIT, p, err)
                            : banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
        }
    }
    free(depth);
    free(npath);
    free(sh.env);
    x.npath = NULL;
    for (int32_t k = 0; k < nc; k++) {
        v3 e = v3_madd(cs[k].at, cs[k].d, 0.5 * cs[k].len);
        cs[k].z = e.z;
    }
    if (keyaki_sort(cs, (size_t)nc, sizeof(cand), cand_cmp, run)) {
        free(cs);
        return crown_fail(c, 3, BANYAN_OK, p, err);
    }
    /* The plan grid over every cluster's reach. */
    grid g = {0, 0, 0, 0, NULL, NULL, NULL, 0};
    hull hl = {NULL, 0};
    if (p->light && nc > 0) {
        double *xy = malloc(sizeof(double) * 4 * (size_t)nc);
        hl.xy = malloc(sizeof(double) * (4 * (size_t)nc + 4));
        if (!xy || !hl.xy) {
            free(xy);
            free(hl.xy);
            free(cs);
            return banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
        }
        for (int32_t k = 0; k < nc; k++) {
            v3 e = v3_madd(cs[k].at, cs[k].d, cs[k].len);
            xy[4 * k] = cs[k].at.x, xy[4 * k + 1] = cs[k].at.y, xy[4 * k + 2] = e.x, xy[4 * k + 3] = e.y;
        }
        int stopped = crown_hull_of(xy, 2 * nc, &hl, run);
        free(xy);
        if (stopped) {
            free(hl.xy);
            free(cs);
            return crown_fail(c, 3, BANYAN_OK, p, err);
        }
        plan_grid(p, cs, nc, &sh, &g, &x);
        if (g.nx && (!g.n || !g.in || !g.sky || !x.cards)) {
            free(g.n);
            free(g.in);
            free(g.sky);
            free(x.cards);
            free(cs);
            free(hl.xy);
            return banyan_fail(err, BANYAN_E_NOMEM, "out of memory growing the crown");
        }
        if (g.nx) crown_hull_mask(&hl, &g);
    }
    c->clusters = nc;
    for (int32_t k = 0; k < nc && !x.oom; k++) {
        if ((k & 7) == 0 && keep_budget(&x, err)) break; /* a cluster may be a long shoot */
        cand q = cs[k];
        x.node = q.node;
        x.base_level = n[q.node].level;
        x.cards_only = q.shell;
        cluster_stream(&x.tw, p, q.index, KEYAKI_STREAM_TWIGS);
        cluster_stream(&x.lf, p, q.index, KEYAKI_STREAM_LEAVES);
        v3 up = v3_norm_or_perp(v3_cross(q.d, q.h), q.d);
        if (up.z < 0) up = v3_neg(up);
        double len = q.len;
        int spur = 0;
        if (g.n && light_cluster(p, &g, c, &q, &up, &len, &spur)) continue;
        x.sub_base = q.len;
        grow_twig(&x, 1, -1, q.at, q.d, up, len, q.r_host, spur, q.path);
    }
    free(g.n);
    free(g.in);
    free(g.sky);
    free(x.cards);
    free(hl.xy);
    free(cs);
    if (x.oom) return crown_fail(c, x.oom, x.st, p, err);
    for (int32_t t = 0; t < c->n_twigs; t++) {
        uint32_t v, i;
        tube_counts((uint32_t)c->twigs[t].count, c->twigs[t].sides, 0, c->twigs[t].children > 0, &v, &i);
        c->vertices += v;
        c->indices += i;
    }
    return BANYAN_OK;
}
