/* Final polylines of the net: every root's growth points in order (a main
 * root runs G -> M(a,1) -> ... -> M(a,B), spec 1 "Start"), with segment
 * repair. Growth points are sphere centres the walk checked, but the
 * straight segment between two of them can still cut a host's corner (a
 * main root wraps an edge within one growth point's moves; a branch chord
 * ends on the far side of a trunk). Such a segment is split at its deepest
 * point, pushed out to distance r, and both parts are checked again, so
 * the tube follows the host round the corner instead of through it. */
#include <stdlib.h>
#include <string.h>

#include "roots_internal.h"

#define REPAIR_SAG ROOTS_SAG
#define REPAIR_DEPTH 16

static int reserve_pts(roots_net *net, uint32_t more) {
    if (net->n_pts + more <= net->cap_pts) return 1;
    uint32_t cap = net->cap_pts ? net->cap_pts : 1024;
    while (cap < net->n_pts + more) cap *= 2;
    v3 *np = realloc(net->pts, sizeof(v3) * cap);
    if (!np) return 0;
    net->pts = np;
    double *nr = realloc(net->rad, sizeof(double) * cap);
    if (!nr) return 0;
    net->rad = nr;
    net->cap_pts = cap;
    return 1;
}

typedef struct builder {
    roots_net *net;
    uint32_t start; /* first point of the polyline being built */
    int oom;
} builder;

/* Appends q unless it repeats the previous point; returns its index.
 * `exact` keeps q's position when it replaces a near duplicate (ends). */
static uint32_t put(builder *bd, v3 q, double rad, int exact) {
    roots_net *net = bd->net;
    if (net->n_pts > bd->start) {
        uint32_t last = net->n_pts - 1;
        if (v3_dist(net->pts[last], q) < 1e-4 * net->r) {
            if (exact) net->pts[last] = q;
            return last;
        }
    }
    if (!reserve_pts(net, 1)) {
        bd->oom = 1;
        return net->n_pts ? net->n_pts - 1 : 0;
    }
    net->pts[net->n_pts] = q;
    net->rad[net->n_pts] = rad;
    return net->n_pts++;
}

/* The point to route a-b through: from the deepest point m0, the nearest
 * free point across the segment (eight directions perpendicular to it),
 * so a chord round a corner gets a point on the rounded corner and a chord
 * straight through a trunk goes round its side. Only when no direction
 * frees it within reach, m0 pushed out of the hosts. */
static v3 split_point(const roots_world *w, v3 a, v3 b, v3 m0) {
    /* Usually pushing m0 out along the distance field is the answer (a
     * chord round an edge); it is not when that lands back near a or b. */
    v3 ab = v3_sub(b, a), quick = m0;
    world_push_out(w, &quick);
    double along = v3_dot(v3_sub(quick, a), ab) / v3_len2(ab);
    if (along > 0.15 && along < 0.85 && v3_dist(quick, m0) < 0.5 * v3_len(ab)) return quick;
    v3 axis = v3_norm_or(ab, v3_make(0, 0, 1)), n;
    /* Start with the obstacle's own way out, so the later directions are
     * cut short by the best distance found so far. */
    world_clearance(w, m0, &n, NULL);
    v3 e1 = v3_norm_or_perp(v3_madd(n, axis, -v3_dot(n, axis)), axis), e2 = v3_cross(axis, e1);
    static const double c8[8] = {1, 0.70710678118654752, 0, -0.70710678118654752, -1, -0.70710678118654752, 0,
                                 0.70710678118654752};
    double reach = v3_dist(a, b) + 2.0 * w->r, best_s = 1e300;
    v3 best = m0;
    for (int k = 0; k < 8; k++) {
        v3 dir = v3_add(v3_scale(e1, c8[k]), v3_scale(e2, c8[(k + 6) % 8])); /* cos, sin of k 45 deg */
        double lo = 0, hi = -1;
        for (double s = w->r * 0.125; s <= reach && s < best_s; s *= 2.0) {
            if (world_free(w, v3_madd(m0, dir, s))) {
                hi = s;
                break;
            }
            lo = s;
        }
        if (hi < 0) continue;
        for (int it = 0; it < 8; it++) { /* to 1/256 of the bracket: free is what counts */
            double m = 0.5 * (lo + hi);
            if (world_free(w, v3_madd(m0, dir, m))) hi = m;
            else lo = m;
        }
        if (hi < best_s) {
            best_s = hi;
            best = v3_madd(m0, dir, hi);
        }
    }
    if (best_s > 1e299) world_push_out(w, &best);
    return best;
}

static void repair(builder *bd, v3 a, v3 b, double ra, double rb, int depth) {
    const roots_world *w = &bd->net->w;
    double stop = w->r * (1.0 - REPAIR_SAG);
    if (depth >= REPAIR_DEPTH || v3_dist(a, b) < 0.05 * w->r) return;
    if (world_segment_clearance(w, a, b, stop) >= stop) return;
    /* Split where the segment goes deepest (round a corner that is the
     * corner itself), not in the middle. */
    double t;
    world_segment_deepest(w, a, b, &t);
    if (t < 0.1 || t > 0.9) t = 0.5;
    v3 m = split_point(w, a, b, v3_lerp(a, b, t));
    double rm = ra + (rb - ra) * t;
    repair(bd, a, m, ra, rm, depth + 1);
    uint32_t before = bd->net->n_pts;
    put(bd, m, rm, 0);
    if (bd->net->n_pts > before) bd->net->stats.repair_points++;
    repair(bd, m, b, rm, rb, depth + 1);
}

/* Appends the polyline src[0..n-1] with repair; idx[i] (when non-NULL)
 * gets where src[i] landed; ok[i] (when non-NULL) marks steps into src[i]
 * already checked with the same test. Returns the number of points added. */
static uint32_t polyline(builder *bd, const v3 *src, const double *rad, uint32_t n, uint32_t *idx, const uint8_t *ok) {
    bd->start = bd->net->n_pts;
    for (uint32_t i = 0; i < n; i++) {
        if (i && !(ok && ok[i])) repair(bd, src[i - 1], src[i], rad[i - 1], rad[i], 0);
        uint32_t k = put(bd, src[i], rad[i], i == 0 || i + 1 == n);
        if (idx) idx[i] = k;
    }
    return bd->net->n_pts - bd->start;
}

static int add_poly(roots_net *net, uint32_t off, uint32_t n, int kind, int id, int a, int k) {
    if (net->n_poly >= net->cap_poly) {
        uint32_t cap = net->cap_poly ? net->cap_poly * 2 : 64;
        roots_poly *np = realloc(net->poly, sizeof *np * cap);
        if (!np) return 0;
        net->poly = np;
        net->cap_poly = cap;
    }
    roots_poly *pl = &net->poly[net->n_poly++];
    pl->off = off;
    pl->n = n;
    pl->kind = kind;
    pl->id = id;
    pl->a = a;
    pl->k = k;
    pl->ring_off = UINT32_MAX;
    return 1;
}

banyan_status roots_make_paths(roots_net *net, const banyan_roots_params *p) {
    (void)p; /* #18: the pipe model and smooth paths read it */
    const int N = net->N, B = net->B, nb = net->nb;
    size_t longest = (size_t)B + 1;
    if ((size_t)net->S1 > longest) longest = (size_t)net->S1;
    if ((size_t)net->S2 > longest) longest = (size_t)net->S2;
    v3 *src = malloc(sizeof(v3) * longest);
    double *rad = malloc(sizeof(double) * longest);
    uint32_t *idx = malloc(sizeof(uint32_t) * longest);
    builder bd = {net, 0, 0};
    if (!src || !rad || !idx || !reserve_pts(net, (uint32_t)(N * (B + 1) + N * nb * (net->S1 + net->S2)) + 64)) {
        free(src); free(rad); free(idx);
        return BANYAN_E_NOMEM;
    }
    int id = 0;
    for (int a = 0; a < N && !bd.oom; a++) {
        src[0] = net->G;
        rad[0] = net->r;
        for (int b = 0; b < B; b++) {
            src[b + 1] = net->M[(size_t)a * B + b];
            rad[b + 1] = net->r; /* #18: the pipe model sets radii */
        }
        uint32_t off = net->n_pts;
        uint32_t n = polyline(&bd, src, rad, (uint32_t)B + 1, idx, NULL);
        memcpy(net->M_at + (size_t)a * B, idx + 1, sizeof(uint32_t) * B);
        if (!add_poly(net, off, n, ROOT_MAIN, id++, a, -1)) bd.oom = 1;
    }
    for (int a = 0; a < N && !bd.oom; a++)
        for (int k = 0; k < nb; k++) {
            int slot = a * nb + k;
            if (!net->K_valid[slot]) continue;
            for (int i = 0; i < net->S1; i++) rad[i] = net->r;
            uint32_t off = net->n_pts;
            uint32_t n = polyline(&bd, net->K + (size_t)slot * net->S1, rad, (uint32_t)net->S1, idx,
                                  net->K_ok + (size_t)slot * net->S1);
            net->K_mid_at[slot] = idx[(net->S1 - 1) / 2];
            if (!add_poly(net, off, n, ROOT_FIRST, id++, a, k)) bd.oom = 1;
        }
    for (int a = 0; a < N && !bd.oom; a++)
        for (int k = 0; k < nb; k++) {
            int slot = a * nb + k;
            if (!net->Q_valid[slot]) continue;
            for (int i = 0; i < net->S2; i++) rad[i] = net->r;
            uint32_t off = net->n_pts;
            uint32_t n = polyline(&bd, net->Q + (size_t)slot * net->S2, rad, (uint32_t)net->S2, NULL, NULL);
            if (!add_poly(net, off, n, ROOT_SECOND, id++, a, k)) bd.oom = 1;
        }
    free(src);
    free(rad);
    free(idx);
    return bd.oom ? BANYAN_E_NOMEM : BANYAN_OK;
}
