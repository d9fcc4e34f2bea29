/* Ivy growth (spec/ivy.md, "Rules" and "Placement"): the parametric
 * L-system p0..p6 applied bud by bud, and the directed random walk that
 * places every new bud. One step = one pass over the buds that existed
 * when the step began, in creation order; a bud placed earlier in the
 * pass already shades and repels the ones placed after it (sequential
 * rewriting keeps neighbouring tips from landing on the same spot). Then
 * the sag correction runs (sag.c).
 *
 * Also the handle's life: create (checks, start snapping, first bud),
 * step, free and the one-shot generate, on boxes or on a host set (whose
 * meshes the handle reads through its pointer; grid.c asks them). */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/platform.h"
#include "ivy_internal.h"

static double now_seconds(void) { return plat_wall(); }

/* sin and cos; for the small angles of the random walk a short series
 * (error below 1e-11 for |x| <= 0.8) is several times cheaper than libm. */
static inline void sin_cos(double x, double *s, double *c) {
    if (fabs(x) > 0.8) {
        *s = dm_sin(x);
        *c = dm_cos(x);
        return;
    }
    double x2 = x * x;
    *s = x + x * x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 + x2 * (-1.0 / 39916800 + x2 * (1.0 / 6227020800.0))))));
    *c = 1 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 + x2 * (1.0 / 479001600.0 - x2 / 87178291200.0))))));
}

/* Rotation about the world X, then Y, then Z axis: R(theta_x, theta_y, theta_z). */
static v3 rotate_xyz(v3 v, double ax, double ay, double az) {
    double c, s;
    sin_cos(ax, &s, &c);
    v = v3_make(v.x, c * v.y - s * v.z, s * v.y + c * v.z);
    sin_cos(ay, &s, &c);
    v = v3_make(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
    sin_cos(az, &s, &c);
    return v3_make(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
}

/* Not where FMA is on: a compiler may contract the scalar code's a * b + c
 * there, and the lanes would no longer match it. */
#if defined(__SSE2__) && !defined(__FMA__)
#define IVY_LANES 1

#include <emmintrin.h>
/* Two candidates' directions at once, each lane by exactly the operations
 * of sin_cos, rotate_xyz and v3_norm_or (IEEE products and sums are the
 * same in a lane as alone; no FMA): the same bits, about half the
 * instructions. a[0..2] and a[3..5] are the two candidates' turns; 0 when
 * one of them is past the series' range (the caller then takes the scalar
 * way). */
static inline __m128d sin_series2(__m128d x) {
    const __m128d x2 = _mm_mul_pd(x, x);
    __m128d t = _mm_mul_pd(x2, _mm_set1_pd(1.0 / 6227020800.0));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 39916800), t));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 362880), t));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 5040), t));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 120), t));
    t = _mm_add_pd(_mm_set1_pd(-1.0 / 6), t);
    return _mm_add_pd(x, _mm_mul_pd(_mm_mul_pd(x, x2), t));
}

static inline __m128d cos_series2(__m128d x) {
    const __m128d x2 = _mm_mul_pd(x, x);
    __m128d t = _mm_sub_pd(_mm_set1_pd(1.0 / 479001600.0), _mm_div_pd(x2, _mm_set1_pd(87178291200.0)));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 3628800), _mm_mul_pd(x2, t)));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 40320), t));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 720), t));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 24), t));
    t = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-0.5), t));
    return _mm_add_pd(_mm_set1_pd(1.0), t);
}

static int turn_pair(v3 v, const double a[6], v3 *d0, v3 *d1) {
    for (int k = 0; k < 6; k++)
        if (!(fabs(a[k]) <= 0.8)) return 0;
    const __m128d ax = _mm_set_pd(a[3], a[0]), ay = _mm_set_pd(a[4], a[1]), az = _mm_set_pd(a[5], a[2]);
    __m128d s = sin_series2(ax), c = cos_series2(ax);
    const __m128d bx = _mm_set1_pd(v.x), by = _mm_set1_pd(v.y), bz = _mm_set1_pd(v.z);
    __m128d x = bx, y = _mm_sub_pd(_mm_mul_pd(c, by), _mm_mul_pd(s, bz));
    __m128d z = _mm_add_pd(_mm_mul_pd(s, by), _mm_mul_pd(c, bz));
    s = sin_series2(ay), c = cos_series2(ay);
    __m128d x2 = _mm_add_pd(_mm_mul_pd(c, x), _mm_mul_pd(s, z));
    z = _mm_add_pd(_mm_mul_pd(_mm_xor_pd(s, _mm_set1_pd(-0.0)), x), _mm_mul_pd(c, z));
    x = x2;
    s = sin_series2(az), c = cos_series2(az);
    x2 = _mm_sub_pd(_mm_mul_pd(c, x), _mm_mul_pd(s, y));
    y = _mm_add_pd(_mm_mul_pd(s, x), _mm_mul_pd(c, y));
    x = x2;
    const __m128d len = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)), _mm_mul_pd(z, z)));
    const __m128d inv = _mm_div_pd(_mm_set1_pd(1.0), len);
    double X[2], Y[2], Z[2], L[2];
    _mm_storeu_pd(X, _mm_mul_pd(x, inv));
    _mm_storeu_pd(Y, _mm_mul_pd(y, inv));
    _mm_storeu_pd(Z, _mm_mul_pd(z, inv));
    _mm_storeu_pd(L, len);
    *d0 = L[0] > 1e-300 ? v3_make(X[0], Y[0], Z[0]) : v;
    *d1 = L[1] > 1e-300 ? v3_make(X[1], Y[1], Z[1]) : v;
    return 1;
}
#endif

/* Candidate order of the host queries: the larger bound first, then
 * the one drawn first. */
static inline int cand_before(const ivy_cand *a, const ivy_cand *b) {
    return a->f_max > b->f_max || (a->f_max == b->f_max && a->k < b->k);
}

static int cmp_cand(const void *x, const void *y) {
    const ivy_cand *a = x, *b = y;
    return cand_before(a, b) ? -1 : cand_before(b, a) ? 1 : 0;
}

/* The walk's winner so far. */
typedef struct walk_best {
    double f, dist;
    int32_t k;
    int crosses;
    v3 q, d;
} walk_best;

/* One round of the directed random walk from bud i along `base`: K
 * candidates turned up to tm (radians) about each axis, host collisions
 * discarded, the best weighted sum of the fitness terms kept in *w. */
static void walk(banyan_ivy *iv, int32_t i, v3 base, double tm, int sucker, int grav_on, v3 vlh, int helio_on,
                 v3 surf_n, double w_cross, double w_tendril, walk_best *w) {
    const banyan_ivy_params *p = &iv->p;
    const ivy_bud *b = &iv->buds[i];
    const double l = p->internode, D = p->sucker_length;
    /* A free candidate is at least clearance off every box (ivy_blocked
     * refuses nearer ones), so f_d < 1 - 0.999 clearance / D there (the
     * 0.999 covers the rounding of the boxes' bounds); a mesh's float
     * surface gets no such margin. */
    const double fd_max = !(sucker && D > 0) ? 0.0 : iv->n_mesh ? 1.0 : 1.0 - 0.999 * p->clearance / D;
    /* Every candidate's free terms first, with the most it could score
     * (f_d or f_grav, and f_cross, at their most). Then the host
     * queries, the costly part, in order of that bound, best first: once
     * the bound cannot beat the best found, no later candidate can. The
     * winner is the one the spec's order gives: the highest score, and on
     * a tie the first drawn. */
    ivy_cand *cd = iv->cand;
    const int32_t K = p->candidates;
#ifdef IVY_LANES
    v3 dn = base; /* the next candidate's direction, when turned with the one before */
#endif
    for (int32_t k = 0; k < K; k++) {
        v3 d;
#ifdef IVY_LANES
        if (k & 1) {
            d = dn;
        } else if (k + 1 < K) {
            double a[6];
            for (int j = 0; j < 6; j++) a[j] = rng_range(&iv->rng, -tm, tm); /* the draws' order as below */
            if (!turn_pair(base, a, &d, &dn)) {
                d = v3_norm_or(rotate_xyz(base, a[0], a[1], a[2]), base);
                dn = v3_norm_or(rotate_xyz(base, a[3], a[4], a[5]), base);
            }
        } else
#endif
        {
            double ax = rng_range(&iv->rng, -tm, tm), ay = rng_range(&iv->rng, -tm, tm), az = rng_range(&iv->rng, -tm, tm);
            d = v3_norm_or(rotate_xyz(base, ax, ay, az), base);
        }
        ivy_cand *c = &cd[k];
        c->d = d;
        c->k = k;
        c->fv = (v3_dot(base, d) + 1.0) * 0.5;
        c->fgeo = (1.0 + d.z) * 0.5;                      /* G = (0, 0, -1): (1 - G.V')/2 */
        c->fhelio = helio_on ? (1.0 + v3_dot(vlh, d)) * 0.5 : 0.0;
        c->ftendril = w_tendril > 0 ? (1.0 - v3_dot(surf_n, d)) * 0.5 : 0.0;
        double fgrav_max = grav_on && d.z < 1.0 ? (1.0 - d.z) * 0.5 : 0.0;
        /* f_d and f_grav exclude each other (f_grav only while free): the
         * bound is the larger of the two cases, each summed as the score
         * is, so that rounding keeps it a bound. */
        const double on = p->w_d * fd_max + p->w_v * c->fv + p->w_geo * c->fgeo + p->w_grav * 0.0 +
                          p->w_helio * c->fhelio + w_tendril * c->ftendril + w_cross;
        const double off = p->w_d * 0.0 + p->w_v * c->fv + p->w_geo * c->fgeo + p->w_grav * fgrav_max +
                           p->w_helio * c->fhelio + w_tendril * c->ftendril + w_cross;
        c->f_max = on >= off ? on : off > on ? off : on + off; /* NaN stays NaN */
    }
    /* The order of the queries: by cand_before, a total order unless a
     * bound is NaN. Up to 32 candidates an insertion sort of their
     * numbers (most walks ask most of them); a NaN keeps the selection of
     * the next one as it always was, so the same ones are asked. */
    int32_t *ord = iv->cand_ord;
    int sorted = K > 32;
    if (sorted) qsort(cd, (size_t)K, sizeof *cd, cmp_cand);
    if (!sorted) {
        sorted = 1;
        for (int32_t k = 0; k < K; k++) {
            if (cd[k].f_max != cd[k].f_max) {
                sorted = 0;
                break;
            }
            /* cand_before(k, o): the ones placed so far were drawn before k */
            const double f = cd[k].f_max;
            int32_t j = k;
            for (; j > 0 && f > cd[ord[j - 1]].f_max; j--) ord[j] = ord[j - 1];
            ord[j] = k;
        }
    } else {
        for (int32_t k = 0; k < K; k++) ord[k] = k;
    }
    for (int32_t n = 0; n < K; n++) {
        if (!sorted) { /* pick the next by selection */
            int32_t m = n;
            for (int32_t j = n + 1; j < K; j++)
                if (cand_before(&cd[j], &cd[m])) m = j;
            if (m != n) {
                ivy_cand t = cd[n];
                cd[n] = cd[m];
                cd[m] = t;
            }
        }
        const ivy_cand *c = &cd[sorted ? ord[n] : n];
        if (!(c->f_max >= w->f)) break; /* (NaN too) */
        if (c->f_max == w->f && c->k > w->k) continue; /* at most a tie, drawn later */
        v3 d = c->d, q = v3_madd(b->P, d, l);
        double dist;
        if (ivy_blocked(iv, b->P, q, D, &dist)) continue;
        int attach = sucker && dist <= D;
        double fd = attach && D > 0 ? 1.0 - dist / D : 0.0;
        double fgrav = !attach && grav_on ? (1.0 - d.z) * 0.5 : 0.0;
        double f = p->w_d * fd + p->w_v * c->fv + p->w_geo * c->fgeo + p->w_grav * fgrav + p->w_helio * c->fhelio +
                   w_tendril * c->ftendril;
        /* f_cross = 1 when the internode crosses no stem; asked only when
         * it can decide the winner (the stem query costs more than a box
         * query: asked first it took 23 times as many). */
        int crosses = 0;
        if (w_cross > 0) {
            double top = f + w_cross;
            if (!(top > w->f || (top == w->f && c->k < w->k))) continue;
            crosses = ivy_crosses_near(iv, b->P, q, surf_n, i, D);
            if (!crosses) f = top;
        }
        if (f > w->f || (f == w->f && c->k < w->k)) {
            w->f = f;
            w->k = c->k;
            w->q = q;
            w->d = d;
            w->dist = dist;
            w->crosses = crosses;
        }
    }
}

/* Free buds after the last held one that may still wrap over the
 * surface (wrap_angle): a suckerless bud and the one after it. */
#define WRAP_RUN 2

/* Aims the internode from P at `target` (a point `clearance` off a
 * surface) and takes it unless it meets a host, or, with `grip`, ends
 * farther than D from a surface: the sucker's pull and the wrap over a
 * curve. */
static void aim_onto(const banyan_ivy *iv, v3 P, v3 target, double D, int grip, v3 *q, v3 *d, double *dist) {
    v3 nd = v3_norm_or(v3_sub(target, P), *d);
    v3 nq = v3_madd(P, nd, iv->p.internode);
    double g;
    if (ivy_blocked(iv, P, nq, D, &g) || (grip && !(g <= D))) return;
    *q = nq;
    *d = nd;
    *dist = g;
}

/* The spacing a stem that runs alongside another keeps from it. */
#define FOLLOW_GAP 0.015
/* No run alongside starts within this of the planting point (m). */
#define FOLLOW_FOOT 1.0
/* A stem is followed towards the light: cos of the largest angle between the two. */
#define FOLLOW_LIGHT_COS 0.26

/* The next bud along a followed stem from bud j in `sense`, -1 at its end. */
static int32_t follow_next(const banyan_ivy *iv, int32_t j, int32_t sense) {
    return sense > 0 ? iv->buds[j].child[0] : iv->buds[j].parent;
}

/* One internode from bud i alongside the followed stem's internode from
 * bud j to k (on the surface of normal n), edging off the stem's line up
 * to FOLLOW_GAP, into w. Returns 0 (w untouched) when that internode
 * leads away from the light (`up`), or the new internode meets a host,
 * leaves the surface (its end out of the sucker's reach D) or crosses a
 * stem. */
static int follow_along(banyan_ivy *iv, int32_t i, int32_t j, int32_t k, v3 n, v3 up, double D, walk_best *w) {
    const ivy_bud *b = &iv->buds[i];
    const double l = iv->p.internode;
    const v3 c = iv->buds[j].P;
    v3 t = v3_sub(iv->buds[k].P, c);
    t = v3_sub(t, v3_scale(n, v3_dot(t, n)));
    const double tl = v3_len(t);
    if (!(tl > 1e-12)) return 0;
    t = v3_scale(t, 1.0 / tl);
    if (v3_dot(t, up) < FOLLOW_LIGHT_COS) return 0;
    /* Off the stem's line, across it on the surface. */
    v3 off = v3_sub(b->P, c);
    off = v3_sub(off, v3_scale(t, v3_dot(off, t)));
    off = v3_sub(off, v3_scale(n, v3_dot(off, n)));
    const double gap = v3_len(off);
    const double edge = gap < FOLLOW_GAP && gap > 1e-12 ? fmin(FOLLOW_GAP - gap, 0.5 * l) / gap : 0.0;
    v3 d = v3_norm_or(v3_madd(v3_scale(t, l), off, edge), t);
    v3 q = v3_madd(b->P, d, l);
    /* A run lies a hair past `clearance` off the surface: at exactly
     * clearance along a wall its buds would sit on ivy_blocked's d < c
     * edge, where the rounding of coordinates far from the origin decides. */
    const ivy_near nr = ivy_nearest_within(iv, q, D + iv->p.clearance);
    if (nr.dist <= D + iv->p.clearance) {
        q = v3_madd(q, nr.normal, ivy_clear_hair(iv) - nr.dist);
        d = v3_norm_or(v3_sub(q, b->P), d);
    }
    double dist;
    if (ivy_blocked(iv, b->P, q, D, &dist) || !(dist <= D) || ivy_crosses_near(iv, b->P, q, n, i, D)) return 0;
    w->q = q;
    w->d = d;
    w->dist = dist;
    w->crosses = 0;
    return 1;
}

/* A tip whose every way on crosses a stem turns alongside that stem
 * (follow_length): the winner w is replaced by an internode along the
 * crossed stem, in its sense towards `up` (the light). *fj, *fs: the
 * followed bud and sense for the new bud. Returns 0 (w untouched) when
 * the run is long enough, the stem is old or seen end on or leads away
 * from the light, or the turned internode meets a host or crosses a
 * stem. */
static int follow_stem(banyan_ivy *iv, int32_t i, v3 n, v3 up, double D, walk_best *w, int32_t *fj, int32_t *fs) {
    const banyan_ivy_params *p = &iv->p;
    const ivy_bud *b = &iv->buds[i];
    if (!((b->follow + 1) * p->internode <= p->follow_length)) return 0;
    /* No run starts at the foot, where every stem starts: the trunks there stay bare. */
    if (v3_dist(b->P, iv->buds[0].P) < FOLLOW_FOOT) return 0;
    const int32_t j = ivy_crossed_stem(iv, b->P, w->q, n, i, D);
    /* Only young wood: a tip meeting the plant's first stems, at its foot,
     * ends there, and the old trunks stay bare (wood.c). */
    if (j < 0 || 2 * (iv->step - iv->buds[j].step_c) > iv->step) return 0;
    const int32_t c = iv->buds[j].parent;
    const int32_t sense = v3_dot(v3_sub(iv->buds[j].P, iv->buds[c].P), up) >= 0 ? 1 : -1;
    if (!(sense > 0 ? follow_along(iv, i, c, j, n, up, D, w) : follow_along(iv, i, j, c, n, up, D, w))) return 0;
    *fj = sense > 0 ? j : c;
    *fs = sense;
    return 1;
}

/* A tip that follows a stem keeps to it (follow_length): the next
 * internode alongside the followed stem's next one. Returns 0 when the
 * run is long enough, the followed stem ends, or follow_along refuses. */
static int follow_on(banyan_ivy *iv, int32_t i, v3 n, v3 up, double D, walk_best *w, int32_t *fj, int32_t *fs) {
    const ivy_bud *b = &iv->buds[i];
    const int32_t j = b->followed - 1;
    if (j < 0 || !((b->follow + 1) * iv->p.internode <= iv->p.follow_length)) return 0;
    const int32_t k = follow_next(iv, j, b->follow_sense);
    if (k < 0 || !follow_along(iv, i, j, k, n, up, D, w)) return 0;
    *fj = k;
    *fs = b->follow_sense;
    return 1;
}

/* The directed random walk from bud i along `base` (spec "Placement",
 * with the additions of docs/ivy.md "Stem architecture"). Appends the new
 * bud (state `st`, nourishment `N`) as child `slot` of bud i and returns
 * its index; -1 when every candidate collided (the bud waits), -2 when
 * every free one crosses a stem and crossing_ends is set (it ends). */
static int32_t place(banyan_ivy *iv, int32_t i, v3 base, v3 vl, int32_t st, double N, int slot) {
    const banyan_ivy_params *p = &iv->p;
    ivy_bud *b = &iv->buds[i];
    const int sucker = st != BANYAN_IVY_A2; /* the third apical bud has none */
    const double D = p->sucker_length;
    const int grav_on = (b->run + 1) * p->internode > p->free_length;
    /* The surface the bud is near (within surface_reach): light is taken
     * along it, f_cross sees stems along its normal, and a free bud's
     * tendrils reach for it. */
    int near_surface = 0;
    double surf_dist = HUGE_VAL;
    v3 surf_n = v3_make(0, 0, 1);
    const double reach = p->surface_reach > D ? p->surface_reach : D;
    if (p->helio_in_plane || p->w_cross > 0 || p->w_tendril > 0) {
        /* Most buds lie within D: that query is the cheaper one on meshes. */
        ivy_near nr = ivy_nearest_within(iv, b->P, D);
        if (!(nr.dist <= D) && reach > D) nr = ivy_nearest_within(iv, b->P, reach);
        near_surface = nr.dist <= reach;
        surf_dist = nr.dist;
        surf_n = nr.normal;
    }
    if (p->helio_in_plane && near_surface) {
        /* Stems on a wall spread along it: light comes off the wall for
         * every bud alike, so only the tangential part of V_l steers. */
        vl = v3_sub(vl, v3_scale(surf_n, v3_dot(vl, surf_n)));
    }
    double vlen = v3_len(vl);
    const int helio_on = vlen > 1e-12;
    v3 vlh = helio_on ? v3_scale(vl, 1.0 / vlen) : vl;
    const double w_cross = near_surface ? p->w_cross : 0.0;
    const double w_tendril = sucker && near_surface && surf_dist > 0.5 * D ? p->w_tendril : 0.0;

    walk_best w = {-HUGE_VAL, 0, -1, 0, b->P, base};
    const v3 up = helio_on ? vlh : v3_make(0, 0, 1);
    int32_t fj = -1, fs = 0; /* the followed stem's bud and sense (follow_length) */
    /* A continuation that runs alongside a stem keeps to it; else the walk. */
    if (!(slot == 0 && p->crossing_ends && near_surface && follow_on(iv, i, surf_n, up, D, &w, &fj, &fs))) {
        const double tm = deg2rad(p->theta_max);
        walk(iv, i, base, tm, sucker, grav_on, vlh, helio_on, surf_n, w_cross, w_tendril, &w);
        if (w.crosses || w.k < 0) {
            /* Every candidate crossed a stem, or met a host: look again with
             * turns twice as wide, so a tip meeting a stem can turn alongside
             * it, and one facing the ground or a corner can turn away (with the
             * narrow cone alone such a tip waited and retried every step). */
            walk_best w2 = {-HUGE_VAL, 0, -1, 0, b->P, base};
            walk(iv, i, base, fmin(2.0 * tm, 0.5 * BANYAN_PI), sucker, grav_on, vlh, helio_on, surf_n, w_cross,
                 w_tendril, &w2);
            if (w2.k >= 0 && (w.k < 0 || !w2.crosses)) w = w2;
        }
        if (w.k < 0) return -1;
        /* Stems meet side by side: a bud whose every way on crosses a stem
         * turns alongside it (follow_stem) or ends (the caller makes it Z). */
        if (w.crosses && p->crossing_ends && !(b->leader && slot == 0) &&
            !follow_stem(iv, i, surf_n, up, D, &w, &fj, &fs))
            return -2;
    }
    const int follow = fj >= 0;
    v3 best_q = w.q, best_d = w.d;
    double best_dist = w.dist;

    if (p->wrap_angle > 0 && b->run <= WRAP_RUN && best_dist > D) {
        /* The surface of a mesh host falls away under a stem that lay on
         * it: over a rounded form or a gentle edge (the normal turns by at
         * most wrap_angle) the stem bends over, aimed at the point
         * `clearance` off the surface below the chosen candidate; over a
         * sharper edge it grows on free and may hang. A box's edges turn
         * by a right angle: its stems never wrap. */
        const double cap = D + p->internode;
        ivy_near at = ivy_nearest_within(iv, b->P, cap);
        ivy_near nr = ivy_nearest_within(iv, best_q, cap);
        if (!(nr.dist <= cap)) nr = at;
        const int on_mesh = at.dist <= cap && nr.dist <= cap && at.host >= (int32_t)iv->mesh0 && nr.host >= (int32_t)iv->mesh0;
        if (on_mesh && v3_dot(at.normal, nr.normal) >= dm_cos(deg2rad(p->wrap_angle)))
            aim_onto(iv, b->P, v3_madd(nr.point, nr.normal, p->clearance), D, 1, &best_q, &best_d, &best_dist);
    }
    if (sucker && !follow && best_dist <= D && p->sucker_pull && best_dist > p->clearance) {
        /* The sucker draws the stem onto the surface: aim the internode at
         * the point `clearance` off the surface below the candidate (a run
         * alongside a stem lies there already: follow_along). */
        ivy_near nr = ivy_nearest_within(iv, best_q, D + p->clearance);
        aim_onto(iv, b->P, v3_madd(best_q, nr.normal, p->clearance - nr.dist), D, 0, &best_q, &best_d, &best_dist);
    }

    int32_t j = iv->n++;
    iv->act[iv->n_act++] = j;
    ivy_bud *c = &iv->buds[j];
    memset(c, 0, sizeof *c);
    c->P = best_q;
    c->V = best_d;
    c->N = N;
    c->state = st;
    c->L = 1 - b->L;
    c->sucker = sucker;
    c->attached = sucker && best_dist <= D;
    c->run = c->attached ? 0 : b->run + 1;
    c->step_c = iv->step;
    c->step_d = -1;
    c->parent = i;
    c->leader = slot == 0 && b->leader;
    c->follow = follow ? b->follow + 1 : 0;
    c->followed = fj + 1;
    c->follow_sense = fs;
    c->child[0] = c->child[1] = -1;
    b->child[slot] = j;
    ivy_grid_insert(iv, j);
    return j;
}

static void end_bud(banyan_ivy *iv, ivy_bud *b) {
    b->state = BANYAN_IVY_Z;
    b->N = 0.0;
    b->step_d = iv->step;
    iv->active--;
}

/* One pass of the rules over the buds that exist now. */
static int cmp_i32(const void *a, const void *b) {
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* The woken buds join the awake list, which stays in creation order. */
static void wake_up(banyan_ivy *iv) {
    if (!iv->n_wake) return;
    qsort(iv->wake, (size_t)iv->n_wake, sizeof(int32_t), cmp_i32);
    int32_t a = 0, w = 0, m = 0;
    while (a < iv->n_act || w < iv->n_wake) {
        if (w == iv->n_wake || (a < iv->n_act && iv->act[a] < iv->wake[w])) iv->merge[m++] = iv->act[a++];
        else iv->merge[m++] = iv->wake[w++];
    }
    memcpy(iv->act, iv->merge, sizeof(int32_t) * (size_t)m);
    iv->n_act = m;
    iv->n_wake = 0;
}

/* Reports growth at visit k of this step's n0 to the progress callback:
 * done = visits so far / (visits so far + the visits left, guessed at n0
 * + 1 per step left). Returns 1 once cancelled. */
static int ivy_progress(banyan_ivy *iv, int32_t k, int32_t n0) {
    double w = (double)n0 + 1.0, so_far = iv->work + k;
    double left = (n0 - k) + (double)(iv->goal - iv->step) * w;
    return prog_at(iv->prog, iv->grow_share * so_far / (so_far + left));
}

/* A pass of the rules; returns early (the plant is then only fit to be
 * freed) when a progress callback cancels. */
static void rules(banyan_ivy *iv) {
    const banyan_ivy_params *p = &iv->p;
    wake_up(iv);
    const int32_t n0 = iv->n_act;
    for (int32_t k = 0; k < n0; k++) {
        if ((k & 31) == 0 && ivy_progress(iv, k, n0)) return;
        const int32_t i = iv->act[k];
        ivy_bud *b = &iv->buds[i];
        if (b->run > 0 && b->run * p->internode > p->bmax) { /* p6 */
            end_bud(iv, b);
            continue;
        }
        v3 vl = v3_make(0, 0, 0);
        if (b->state == BANYAN_IVY_D) {
            if (b->N < p->t2) { /* p5 */
                b->N += p->beta;
                continue;
            }
            /* p3 when H1 <= t0: H0 here plus H0 at the h1_buds buds before. */
            if (b->shaded) continue;
            if (!p->ground_branching && p->ground == 1 && b->P.z <= p->ground_z + p->sucker_length &&
                ivy_grip_distance(iv, b->P, p->sucker_length) > p->sucker_length) {
                /* Lying on the ground, away from every host: the ground is
                 * crossed, not carpeted, so this bud never sprouts. */
                end_bud(iv, b);
                continue;
            }
            ivy_test_begin(iv);
            double H = ivy_shade_watch(iv, b->P, i, p->t0, &vl);
            int32_t a = b->parent;
            for (int32_t k = 0; k < p->h1_buds && a >= 0 && H <= p->t0; k++, a = iv->buds[a].parent)
                H += ivy_shade_watch(iv, iv->buds[a].P, a, p->t0 - H, NULL);
            if (H > p->t0) {
                ivy_sleep(iv, i);
                continue;
            }
            v3 axis = ivy_nearest_any(iv, b->P).normal;
            double ang = deg2rad(p->branch_angle) * (b->L ? 1.0 : -1.0);
            v3 base = v3_norm_or(v3_rotate(b->V, axis, ang), b->V);
            int32_t r = place(iv, i, base, vl, BANYAN_IVY_A0, b->N, 1);
            if (r == -2) end_bud(iv, &iv->buds[i]);
            if (r < 0) continue;
            b = &iv->buds[i];
            end_bud(iv, b); /* D -> Z, the new A0 takes its place among the active */
            iv->active++;
            iv->branch_points++;
        } else {
            if (b->N < p->t1) { /* p4 */
                b->N += p->beta;
                continue;
            }
            if (b->shaded) continue;
            ivy_test_begin(iv);
            double H = ivy_shade_watch(iv, b->P, i, p->t0, &vl);
            if (H > p->t0) {
                ivy_sleep(iv, i);
                continue;
            }
            int32_t st = b->state;
            double keep = st == BANYAN_IVY_A2 ? p->alpha * b->N : b->N;
            int32_t r = place(iv, i, b->V, vl, (st + 1) % 3, keep, 0);
            if (r == -2) end_bud(iv, &iv->buds[i]);
            if (r < 0) continue;
            b = &iv->buds[i];
            iv->active++;
            if (st == BANYAN_IVY_A2) { /* p2: the suckerless bud stays as a dormant bud */
                b->state = BANYAN_IVY_D;
                b->N = (1.0 - p->alpha) * b->N;
            } else { /* p0, p1 */
                end_bud(iv, b);
            }
        }
    }
    /* Drop the buds that ended or fell asleep; the list stays in creation
     * order. */
    int32_t m = 0;
    for (int32_t k = 0; k < iv->n_act; k++) {
        const ivy_bud *b = &iv->buds[iv->act[k]];
        if (b->state != BANYAN_IVY_Z && !b->shaded) iv->act[m++] = iv->act[k];
    }
    iv->n_act = m;
}

static banyan_status reserve(banyan_ivy *iv, int32_t need, banyan_error *err) {
    if (need <= iv->cap) return BANYAN_OK;
    int64_t cap = iv->cap > 256 ? iv->cap : 256;
    while (cap < need) cap *= 2;
    if (cap > iv->p.max_buds) cap = need > iv->p.max_buds ? need : iv->p.max_buds;
    /* The per-bud arrays below, known before they grow. */
    const double per_bud = sizeof(ivy_bud) + 3 * sizeof(ivy_gnode) + 13 * sizeof(int32_t) + 3 * sizeof(v3);
    if (prog_reserve(iv->prog, (double)(cap - iv->cap) * per_bud)) return prog_fail(iv->prog, err, "ivy growth");
    ivy_bud *b = realloc(iv->buds, sizeof(ivy_bud) * (size_t)cap);
    if (!b) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %lld buds", (long long)cap);
    iv->buds = b;
    int32_t(*g)[3] = realloc(iv->bcell, sizeof *g * (size_t)cap);
    if (!g) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %lld buds", (long long)cap);
    iv->bcell = g;
    /* Per bud: the light cache's first edge and test stamp (grid.c). */
    int32_t *w = realloc(iv->dep_head, sizeof(int32_t) * (size_t)cap * 2);
    if (!w) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %lld buds", (long long)cap);
    if (iv->cap) memmove(w + cap, w + iv->cap, sizeof(int32_t) * (size_t)iv->cap);
    for (int64_t k = iv->cap; k < cap; k++) w[k] = -1;
    memset(w + cap + iv->cap, 0, sizeof(int32_t) * (size_t)(cap - iv->cap));
    iv->dep_head = w;
    iv->seen = w + cap;
    int32_t *c = realloc(iv->chain, sizeof(int32_t) * (size_t)cap * 8);
    if (!c) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %lld buds", (long long)cap);
    /* The awake and wake lists (at 4 and 5 caps) keep their contents: move
     * them, the higher one first, to their places in the larger block. */
    if (iv->cap) {
        memmove(c + 5 * cap, c + 5 * (int64_t)iv->cap, sizeof(int32_t) * (size_t)iv->n_wake);
        memmove(c + 4 * cap, c + 4 * (int64_t)iv->cap, sizeof(int32_t) * (size_t)iv->n_act);
    }
    iv->chain = c;
    iv->moving = c + cap;
    iv->stack = c + 2 * cap;
    iv->sizes = c + 3 * cap;
    iv->act = c + 4 * cap;
    iv->wake = c + 5 * cap;
    iv->merge = c + 6 * cap;
    iv->counted = c + 7 * cap; /* a test counts each bud once */
    v3 *t = realloc(iv->tmp, sizeof(v3) * (size_t)cap * 3);
    if (!t) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %lld buds", (long long)cap);
    iv->tmp = t;
    iv->cap = (int32_t)cap;
    return BANYAN_OK;
}

banyan_status ivy_grow(banyan_ivy *iv, int32_t n, int vertex_stop, banyan_error *err) {
    if (!iv) return banyan_fail(err, BANYAN_E_INVALID_ARG, "ivy is NULL");
    banyan_status s = banyan_check_int(err, "n (steps)", n, 0, BANYAN_IVY_MAX_STEPS);
    if (s) return s;
    ivy_budget_start(iv);
    if (prog_stopped(iv->prog)) return prog_fail(iv->prog, err, "ivy growth");
    if (iv->grid_oom)
        return banyan_fail(err, BANYAN_E_NOMEM, "an earlier step ran out of memory for the spatial hash (%d buds)", iv->n);
    double t0 = now_seconds();
    for (int32_t k = 0; k < n; k++) {
        /* Every growing bud adds at most one bud per step. */
        int64_t worst = (int64_t)iv->n + iv->active;
        if (worst > iv->p.max_buds) {
            iv->step_seconds += now_seconds() - t0;
            return banyan_fail(err, BANYAN_E_LIMIT,
                               "max_buds = %d could be exceeded at step %d (%d buds, %d growing); raise max_buds or "
                               "lower t0 or steps",
                               iv->p.max_buds, iv->step + 1, iv->n, iv->active);
        }
        uint64_t floor_v = ivy_mesh_vertex_floor(&iv->p, iv->n);
        if (vertex_stop && floor_v > (uint64_t)iv->p.max_vertices) {
            iv->step_seconds += now_seconds() - t0;
            return banyan_fail(err, BANYAN_E_LIMIT,
                               "the ivy mesh would need at least %llu vertices after step %d (%d buds), over "
                               "max_vertices = %d; raise max_vertices or lower steps or stem_sides",
                               (unsigned long long)floor_v, iv->step, iv->n, iv->p.max_vertices);
        }
        if ((s = reserve(iv, (int32_t)worst, err))) {
            iv->step_seconds += now_seconds() - t0;
            return s;
        }
        iv->step++;
        int32_t n0 = iv->n_act + iv->n_wake;
        rules(iv);
        if (prog_stopped(iv->prog)) {
            iv->step_seconds += now_seconds() - t0;
            return prog_fail(iv->prog, err, "ivy growth");
        }
        ivy_sag(iv);
        if (iv->grid_oom) { /* a bud is missing from the light look-up: the plant is only fit to be freed */
            iv->step_seconds += now_seconds() - t0;
            return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the spatial hash at step %d (%d buds)",
                               iv->step, iv->n);
        }
        iv->work += n0 + 1.0;
    }
    iv->step_seconds += now_seconds() - t0;
    banyan_error_clear(err);
    return BANYAN_OK;
}

/* The step API keeps max_vertices as it grows, like the one shot (#21). */
banyan_status banyan_ivy_step(banyan_ivy *iv, int32_t n, banyan_error *err) { return ivy_grow(iv, n, 1, err); }

void banyan_ivy_free(banyan_ivy *iv) {
    if (!iv) return;
    free(iv->hosts);
    free(iv->box_lo);
    free(iv->buds);
    free(iv->bcell);
    free(iv->dep_head);
    free(iv->dep);
    free(iv->cells);
    free(iv->cnb);
    free(iv->cslot);
    free(iv->pool);
    free(iv->chain);
    free(iv->tmp);
    free(iv->cand);
    free(iv->cand_ord);
    free(iv->xs);
    free(iv);
}

/* The start: the point `clearance` off the nearest given host surface
 * when a stem can grow from there, else the nearest such point on any
 * given host's side (docs/ivy.md, "Hosts and start"). A side can take the
 * start when its outward normal is less than 45 degrees below the
 * horizon (not a bottom face) and the point is at least one internode
 * above the ground and clear of every other host. */
static int start_growable(const banyan_ivy *iv, v3 P, v3 n) {
    if (n.z < -0.70710678118654752) return 0;
    return !iv->p.ground || P.z >= iv->p.ground_z + iv->p.internode - 1e-9;
}

/* Tries q (a side's point nearest s) with outward normal n as the start. */
static void try_start(const banyan_ivy *iv, v3 s, v3 q, v3 n, double *best, v3 *out) {
    v3 P = v3_madd(q, n, iv->p.clearance);
    double d = v3_dist(q, s);
    if (!(d < *best) || !start_growable(iv, P, n)) return;
    /* Not buried in another host (or the ground). */
    if (ivy_nearest_any(iv, P).dist < 0.5 * iv->p.clearance) return;
    *best = d;
    *out = P;
}

static v3 growable_start(const banyan_ivy *iv, v3 start, v3 fallback) {
    const banyan_ivy_params *p = &iv->p;
    v3 s = start;
    /* Looked for from the start lifted to the lowest height allowed, so a
     * wall's nearest side point is that high, not at its foot. */
    if (p->ground && s.z < p->ground_z + p->internode) s.z = p->ground_z + p->internode;
    double best = HUGE_VAL;
    v3 out = fallback;
    for (uint32_t h = 0; h < iv->n_given; h++) {
        const obb *o = &iv->hosts[h];
        v3 l = obb_to_local(o, s);
        for (int f = 0; f < 6; f++) {
            int k = f / 2;
            double sg = f % 2 ? 1.0 : -1.0, c[3] = {l.x, l.y, l.z};
            for (int i = 0; i < 3; i++) c[i] = i == k ? sg * o->h[i] : fmax(-o->h[i], fmin(o->h[i], c[i]));
            try_start(iv, s, obb_to_world(o, v3_make(c[0], c[1], c[2])), v3_scale(o->ax[k], sg), &best, &out);
        }
    }
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        const host_mesh *hm = &iv->meshes[m];
        for (uint32_t t = 0; t < hm->nt; t++) {
            v3 n = f3(hm->fnrm + 3 * (size_t)t), q = hmesh_prim_closest(hm, t, s);
            if (!hm->closed && v3_dot(v3_sub(s, q), n) < 0) n = v3_neg(n); /* an open sheet: the start's side */
            try_start(iv, s, q, n, &best, &out);
        }
    }
    return out;
}

/* A start far from the world's origin: the status of frame_check on the
 * box around the start, the boxes and the meshes (in world coordinates). */
static banyan_status far_start(const banyan_ivy *iv, const banyan_ivy_params *params, uint32_t nb, v3 O,
                               banyan_error *err) {
    v3 lo, hi;
    frame_empty(&lo, &hi);
    frame_add(&lo, &hi, v3_load(params->start));
    for (uint32_t h = 0; h < nb; h++) {
        v3 a, b;
        obb_bounds(&iv->hosts[h], &a, &b);
        frame_add(&lo, &hi, v3_add(a, O)), frame_add(&lo, &hi, v3_add(b, O));
    }
    for (uint32_t m = 0; m < iv->n_mesh; m++)
        frame_add(&lo, &hi, v3_add(iv->meshes[m].lo, O)), frame_add(&lo, &hi, v3_add(iv->meshes[m].hi, O));
    return frame_check(lo, hi, O, "the hosts and start", err);
}

/* The ground: the top face of a box far larger than the hosts, at
 * ground_z under the first box or mesh, added after the given hosts (a
 * host that grips when ground is 2). */
static void add_ground(banyan_ivy *iv, const banyan_ivy_params *params, uint32_t nb) {
    obb *g = &iv->hosts[iv->n_hosts++];
    const double G = 1e5, depth = 1e3;
    v3 mid = nb ? iv->hosts[0].c : v3_scale(v3_add(iv->meshes[0].lo, iv->meshes[0].hi), 0.5);
    g->c = v3_make(mid.x, mid.y, iv->p.ground_z - depth);
    g->ax[0] = v3_make(1, 0, 0);
    g->ax[1] = v3_make(0, 1, 0);
    g->ax[2] = v3_make(0, 0, 1);
    g->h[0] = g->h[1] = G;
    g->h[2] = depth;
    if (params->ground == 2) iv->n_grip++;
}

/* The first bud's place and direction: the start snapped to its nearest
 * host surface (nr), `clearance` off it, moved where it can grow and out
 * of the hosts; its direction up along the surface there (sideways on a
 * ceiling). nr becomes the nearest surface to that place. */
static void first_place(const banyan_ivy *iv, const banyan_ivy_params *params, uint32_t nb, v3 start, ivy_near *nr,
                        v3 *P_out, v3 *V_out) {
    v3 nrm, surf;
    if (nr->host < (int32_t)nb) {
        surf = obb_closest_surface(&iv->hosts[nr->host], start, &nrm);
    } else {
        surf = nr->point;
        nrm = nr->normal;
    }
    v3 P = v3_madd(surf, nrm, params->clearance);
    if (!start_growable(iv, P, nrm)) P = growable_start(iv, start, P);
    P = ivy_push_out(iv, P);
    *nr = ivy_nearest(iv, P);
    /* First growth direction: up along the surface (sideways on a ceiling). */
    v3 up = v3_make(0, 0, 1);
    v3 V = v3_sub(up, v3_scale(nr->normal, v3_dot(up, nr->normal)));
    V = v3_len(V) > 1e-6 ? v3_norm(V) : v3_any_perp(nr->normal);
    *P_out = P, *V_out = V;
}

/* The leading stems: start_stems first buds at the start, their
 * directions fanned over +-start_fan about up along the surface, each
 * jittered within its share of the fan. One stem keeps the paper's
 * single first bud (and draws no random number). Returns their count. */
static int32_t plant_stems(banyan_ivy *iv, const banyan_ivy_params *params, v3 P, v3 V, const ivy_near *nr) {
    const int32_t ns = params->start_stems < params->max_buds ? params->start_stems : params->max_buds;
    const double fan = deg2rad(params->start_fan);
    for (int32_t k = 0; k < ns; k++) {
        v3 Vk = V;
        if (ns > 1) {
            double share = 2.0 * fan / ns, a = -fan + share * (k + 0.5) + rng_range(&iv->rng, -0.35, 0.35) * share;
            Vk = v3_norm_or(v3_rotate(V, nr->normal, a), V);
        }
        ivy_bud *b = &iv->buds[k];
        memset(b, 0, sizeof *b);
        b->P = P;
        b->V = Vk;
        b->N = params->n_start;
        b->state = BANYAN_IVY_A0;
        b->L = k & 1;
        b->leader = 1;
        b->sucker = 1;
        b->attached = nr->dist <= params->sucker_length;
        b->run = b->attached ? 0 : 1;
        b->step_d = -1;
        b->parent = b->child[0] = b->child[1] = -1;
        iv->n = k + 1;
        iv->act[k] = k;
        ivy_grid_insert(iv, k);
    }
    return ns;
}

/* The handle on the boxes and meshes of `set`, checked when it was made. */
static banyan_status create(const banyan_ivy_params *params, const banyan_hosts *set, banyan_ivy **out,
                            banyan_error *err) {
    const uint32_t nb = set->n_boxes;
    banyan_status s;
    banyan_ivy *iv = calloc(1, sizeof *iv);
    if (!iv) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    iv->p = *params;
    iv->rss0_mb = process_rss_mb();
    prog_init(&iv->own, NULL);
    iv->prog = &iv->own;
    iv->set = set;
    iv->meshes = set->meshes;
    iv->n_mesh = set->n_meshes;
    iv->mesh0 = nb + 1; /* after the ground's slot */
    const size_t nbound = (size_t)nb + 1 + iv->n_mesh;
    iv->hosts = malloc(sizeof(obb) * (nb + 1));
    iv->box_lo = malloc(sizeof(v3) * 4 * nbound);
    iv->box_hi = iv->box_lo ? iv->box_lo + nbound : NULL;
    iv->clear_lo = iv->box_lo ? iv->box_lo + 2 * nbound : NULL;
    iv->clear_hi = iv->box_lo ? iv->box_lo + 3 * nbound : NULL;
    if (!iv->hosts || !iv->box_lo) {
        banyan_ivy_free(iv);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    iv->n_hosts = iv->n_given = iv->n_grip = nb;
    if (nb) memcpy(iv->hosts, set->boxes, sizeof(obb) * nb);
    /* The set's frame (base/frame.h): its boxes are already in it. */
    const v3 O = set->origin;
    iv->origin = O;
    for (int k = 0; k < 3; k++) iv->p.start[k] -= (&O.x)[k];
    iv->p.ground_z -= O.z;
    /* The meshes' bounds (boxes and ground follow, after the ground). */
    ivy_host_boxes(iv);

    /* Snap the start to the nearest given host surface, `clearance` off it. */
    v3 start = v3_load(iv->p.start);
    ivy_near nr = ivy_nearest(iv, start);
    if (nr.dist > params->start_snap_max) {
        /* Host numbers as the caller gave them: boxes, then meshes. */
        int32_t host = nr.host < (int32_t)nb ? nr.host : (int32_t)(nb + ((uint32_t)nr.host - iv->mesh0));
        banyan_ivy_free(iv);
        return banyan_fail(err, BANYAN_E_START_FAR,
                           "start = (%g, %g, %g) is %g m from the nearest host surface (hosts[%d]); it must be within "
                           "start_snap_max = %g m",
                           params->start[0], params->start[1], params->start[2], nr.dist, host,
                           params->start_snap_max);
    }
    if (fmax(fmax(fabs(start.x), fabs(start.y)), fabs(start.z)) > FRAME_KEEP) { /* the plant grows near its start */
        s = far_start(iv, params, nb, O, err);
        banyan_ivy_free(iv);
        return s;
    }
    if (params->ground) add_ground(iv, params, nb);
    ivy_host_boxes(iv);
    v3 P, V;
    first_place(iv, params, nb, start, &nr, &P, &V);

    /* 1024 buds hold the leading stems (start_stems <= 64). */
    if ((s = reserve(iv, params->max_buds < 1024 ? params->max_buds : 1024, err)) != BANYAN_OK) {
        banyan_ivy_free(iv);
        return s;
    }
    iv->cand = malloc(sizeof(ivy_cand) * (size_t)params->candidates);
    iv->cand_ord = malloc(sizeof(int32_t) * (size_t)params->candidates);
    if (!iv->cand || !iv->cand_ord) {
        banyan_ivy_free(iv);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    iv->inv_cell = 1.0 / (IVY_CELL_SCALE * params->leaf_max);


    if (ivy_grid_init(iv, 1024) != BANYAN_OK) {
        banyan_ivy_free(iv);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    pcg32_seed(&iv->rng, params->seed, 0x1517);

    const int32_t ns = plant_stems(iv, params, P, V, &nr);
    if (iv->grid_oom) {
        banyan_ivy_free(iv);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    iv->active = iv->n_act = iv->roots = ns;
    *out = iv;
    banyan_error_clear(err);
    return BANYAN_OK;
}

banyan_status banyan_ivy_create(const banyan_ivy_params *params, const banyan_hosts *hosts, banyan_ivy **out,
                                banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    banyan_status s = ivy_params_check(params, err);
    if (s) return s;
    if (!hosts) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts is NULL: ivy needs a host set (banyan_hosts_create)");
    if (hosts->n_boxes + hosts->n_meshes == 0)
        return banyan_fail(err, BANYAN_E_NO_HOSTS, "the host set is empty: ivy needs at least one host to climb");
    return create(params, hosts, out, err);
}

/* The parts of a one-shot generation's time (bench_progress, the wall
 * at 450 steps): growth, then the stats when asked, then the mesh. */
#define IVY_GROW_SHARE 0.8
#define IVY_STATS_SHARE 0.05

banyan_status banyan_ivy_generate(const banyan_ivy_params *params, const banyan_hosts *hosts, banyan_mesh **out,
                                  banyan_ivy_stats *stats, const banyan_progress *progress, banyan_error *err) {
    if (stats) memset(stats, 0, sizeof *stats);
    BANYAN_CHECK_OUT(out, err);
    banyan_status s = prog_check(progress, err);
    if (s) return s;
    prog g; /* with or without a callback: it keeps the budget, from the start */
    prog_init(&g, progress);
    if (params) prog_budget(&g, params->max_seconds, params->max_memory_mb);
    banyan_ivy *iv = NULL;
    if ((s = banyan_ivy_create(params, hosts, &iv, err))) return s;
    iv->prog = &g;
    iv->goal = banyan_ivy_steps(params);
    iv->grow_share = IVY_GROW_SHARE;
    iv->mesh_from = IVY_GROW_SHARE + (stats ? IVY_STATS_SHARE : 0.0);
    s = ivy_grow(iv, banyan_ivy_steps(params), 1, err);
    if (!s && prog_at(iv->prog, IVY_GROW_SHARE)) s = prog_fail(iv->prog, err, "ivy");
    if (!s && stats) s = banyan_ivy_get_stats(iv, stats, err);
    if (!s && prog_at(iv->prog, iv->mesh_from)) s = prog_fail(iv->prog, err, "ivy");
    if (!s) s = banyan_ivy_mesh(iv, out, err);
    if (!s && prog_finish(iv->prog)) {
        banyan_mesh_free(*out);
        *out = NULL;
        s = prog_fail(iv->prog, err, "ivy");
    }
    banyan_ivy_free(iv);
    if (s && stats) memset(stats, 0, sizeof *stats);
    return s;
}
