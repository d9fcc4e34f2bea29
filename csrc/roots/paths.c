/* Final polylines of the net: every root's growth points in order (a main
 * root runs G -> M(a,1) -> ... -> M(a,B), spec 1 "Start"), with segment
 * repair. Growth points are sphere centres the walk checked, but the
 * straight segment between two of them can still cut a host's corner (a
 * main root wraps an edge within one growth point's moves; a branch chord
 * ends on the far side of a trunk). Such a segment is split at its deepest
 * point, pushed out to distance r, and both parts are checked again, so
 * the tube follows the host round the corner instead of through it.
 *
 * The look of a real fig (docs/roots.md):
 * - smooth_paths: the polyline is a centripetal Catmull-Rom curve through
 *   the growth points (which it keeps exactly, so junctions stay shared),
 *   resampled about every 2 r; a sample closer than r to a host is pushed
 *   out, and segment repair runs on the samples as above.
 * - A main root that entered the soil (growth.c) gets its underground end
 *   after its entry point, repaired against the hosts only.
 * - Radii by the pipe model: a root is as thick as what feeds into it.
 *   Flow is counted in units of a cord of radius r (r^e, e =
 *   pipe_exponent): a first branch root carries tip^e for itself and for
 *   each second branch root joined to it, scaled up by 2 maturity; half
 *   of it goes into each main root it joins, and a main root's flow grows
 *   downwards from G by what joins it (plus its own cord of r, reached 8 r
 *   below G). Radius = r flow^(1/e), smoothed along the root; growing tips
 *   and branch ends thin to tip_radius r; a root entering the soil ends
 *   in a buttress (buttress() below). */
#include <stdlib.h>
#include <string.h>

#include "roots_internal.h"

#define REPAIR_SAG ROOTS_SAG
#define REPAIR_DEPTH 16

int roots_reserve_pts(roots_net *net, uint32_t more) {
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
    const roots_world *w; /* what segment repair keeps clear of */
    uint32_t start;       /* first point of the polyline being built */
    int oom;
    int smooth;           /* smooth_paths */
    const banyan_roots_params *press; /* branch roots when hugging: curve samples pressed onto the host */
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
    if (!roots_reserve_pts(net, 1)) {
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
    const roots_world *w = bd->w;
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

/* Centripetal Catmull-Rom (alpha 0.5, Barry-Goldman) on p1-p2 at u in [0,1]. */
static v3 catmull_rom(v3 p0, v3 p1, v3 p2, v3 p3, double u) {
    double d01 = sqrt(v3_dist(p0, p1)), d12 = sqrt(v3_dist(p1, p2)), d23 = sqrt(v3_dist(p2, p3));
    if (d01 < 1e-9) d01 = d12;
    if (d23 < 1e-9) d23 = d12;
    double t0 = 0, t1 = d01, t2 = t1 + d12, t3 = t2 + d23, t = t1 + u * d12;
    v3 a1 = v3_add(v3_scale(p0, (t1 - t) / (t1 - t0)), v3_scale(p1, (t - t0) / (t1 - t0)));
    v3 a2 = v3_add(v3_scale(p1, (t2 - t) / (t2 - t1)), v3_scale(p2, (t - t1) / (t2 - t1)));
    v3 a3 = v3_add(v3_scale(p2, (t3 - t) / (t3 - t2)), v3_scale(p3, (t - t2) / (t3 - t2)));
    v3 b1 = v3_add(v3_scale(a1, (t2 - t) / (t2 - t0)), v3_scale(a2, (t - t0) / (t2 - t0)));
    v3 b2 = v3_add(v3_scale(a2, (t3 - t) / (t3 - t1)), v3_scale(a3, (t - t1) / (t3 - t1)));
    return v3_add(v3_scale(b1, (t2 - t) / (t2 - t1)), v3_scale(b2, (t - t1) / (t2 - t1)));
}

/* The neighbour of src[i] on the side `dir`, skipping repeats; mirrored
 * past the ends. */
static v3 neighbour(const v3 *src, uint32_t n, uint32_t i, int dir, double tiny) {
    for (long j = (long)i + dir; j >= 0 && j < (long)n; j += dir)
        if (v3_dist(src[j], src[i]) > tiny) return src[j];
    long o = (long)i - dir;
    while (o >= 0 && o < (long)n && v3_dist(src[o], src[i]) <= tiny) o -= dir;
    if (o < 0 || o >= (long)n) return src[i];
    return v3_sub(v3_scale(src[i], 2.0), src[o]);
}

/* Spacing of the smooth curve's samples, times r: finer looks no
 * smoother on a tube of 8 to 16 sides and costs vertices. */
#define ROOTS_SMOOTH_STEP 2.0

/* The smooth curve's samples strictly between src[i-1] and src[i]:
 * about one every ROOTS_SMOOTH_STEP r (at most 8), each free of the hosts. */
static void smooth_between(builder *bd, const v3 *src, uint32_t n, uint32_t i, v3 *prev) {
    const roots_world *w = bd->w;
    double len = v3_dist(src[i - 1], src[i]), tiny = 1e-6 * w->r;
    if (len < ROOTS_SMOOTH_STEP * 1.25 * w->r) return;
    int k = (int)ceil(len / (ROOTS_SMOOTH_STEP * w->r)) - 1;
    if (k > 8) k = 8;
    v3 p0 = neighbour(src, n, i - 1, -1, tiny), p3 = neighbour(src, n, i, +1, tiny);
    for (int j = 1; j <= k; j++) {
        v3 q = catmull_rom(p0, src[i - 1], src[i], p3, (double)j / (k + 1));
        if (!world_free(w, q)) world_push_out(w, &q);
        if (bd->press) roots_press_point(w, bd->press, &q);
        repair(bd, *prev, q, 0, 0, 0);
        put(bd, q, 0, 0);
        *prev = q;
    }
}

/* Appends the polyline src[0..n-1] with repair (and smoothing); idx[i]
 * (when non-NULL) gets where src[i] landed; ok[i] (when non-NULL) marks
 * steps into src[i] already checked with the same test. Returns the
 * number of points added. */
static uint32_t polyline(builder *bd, const v3 *src, uint32_t n, uint32_t *idx, const uint8_t *ok) {
    bd->start = bd->net->n_pts;
    v3 prev = src[0];
    for (uint32_t i = 0; i < n; i++) {
        if ((i & 63) == 0 && roots_stop(bd->net)) break; /* the caller drops the net */
        if (i && bd->smooth) smooth_between(bd, src, n, i, &prev);
        if (i && (!(ok && ok[i]) || v3_dist(prev, src[i - 1]) > 0)) repair(bd, prev, src[i], 0, 0, 0);
        uint32_t k = put(bd, src[i], 0, i == 0 || i + 1 == n);
        prev = src[i];
        if (idx) idx[i] = k;
    }
    return bd->net->n_pts - bd->start;
}

int roots_add_poly(roots_net *net, uint32_t off, uint32_t n, int kind, int id, int a, int k) {
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
    pl->soil_from = n;
    pl->from = UINT32_MAX;
    return 1;
}

static double smoothstep(double x) {
    x = x < 0 ? 0 : (x > 1 ? 1 : x);
    return x * x * (3.0 - 2.0 * x);
}

/* Arc length along a polyline, into arc[0..n-1]. */
static void arc_of(const v3 *P, uint32_t n, double *arc) {
    arc[0] = 0;
    for (uint32_t i = 1; i < n; i++) arc[i] = arc[i - 1] + v3_dist(P[i - 1], P[i]);
}

/* Thins both ends of a branch root to tip r over `len`. */
static void thin_ends(double *R, const double *arc, uint32_t n, double tip, double len) {
    double L = arc[n - 1];
    for (uint32_t i = 0; i < n; i++) {
        double d = arc[i] < L - arc[i] ? arc[i] : L - arc[i];
        double f = smoothstep(d / len);
        R[i] = tip + (R[i] - tip) * f;
    }
}

/* Drops path points closer than 0.4 r to the last kept one (smooth
 * paths: curve samples pushed out round a corner bunch up there, and a
 * tube's rings that close together fold at any bend) or where the path
 * turns back on itself, unless a junction
 * or an end sits on them or the step over them would sag into a host.
 * Indices into pts (M_at, K_mid_at, polylines) follow. */
static int decimate(roots_net *net) {
    uint32_t n = net->n_pts;
    uint8_t *keep = calloc(n ? n : 1, 1);
    uint32_t *to = malloc(sizeof(uint32_t) * (n ? n : 1));
    if (!keep || !to) {
        free(keep); free(to);
        return 0;
    }
    size_t NB = (size_t)net->N * net->B, slots = (size_t)net->N * net->nb;
    for (size_t i = 0; i < NB; i++) keep[net->M_at[i]] = 1;
    for (size_t s = 0; s < slots; s++)
        if (net->K_valid[s]) keep[net->K_mid_at[s]] = 1;
    const roots_world *w = &net->w;
    double gap = 0.4 * w->r, stop = w->r * (1.0 - REPAIR_SAG);
    uint32_t out = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        roots_poly *pl = &net->poly[t];
        uint32_t off = out, soil = UINT32_MAX;
        for (uint32_t i = 0; i < pl->n; i++) {
            uint32_t k = pl->off + i;
            int must = keep[k] || i == 0 || i + 1 == pl->n || i + 1 >= pl->soil_from;
            int drop = 0;
            if (!must) {
                v3 in = v3_sub(net->pts[k], net->pts[out - 1]), on = v3_sub(net->pts[k + 1], net->pts[k]);
                int back = v3_dot(in, on) < -0.3 * v3_len(in) * v3_len(on); /* the path turns back here */
                drop = (v3_len(in) < gap || back) &&
                       world_segment_clearance(w, net->pts[out - 1], net->pts[k + 1], stop) >= stop;
            }
            if (drop) {
                to[k] = out - 1;
                continue;
            }
            if (i == pl->soil_from) soil = out - off;
            net->pts[out] = net->pts[k];
            to[k] = out++;
        }
        pl->off = off;
        pl->n = out - off;
        if (soil != UINT32_MAX) pl->soil_from = soil;
        else pl->soil_from = pl->n;
    }
    for (size_t i = 0; i < NB; i++) net->M_at[i] = to[net->M_at[i]];
    for (size_t s = 0; s < slots; s++)
        if (net->K_valid[s]) net->K_mid_at[s] = to[net->K_mid_at[s]];
    net->n_pts = out;
    free(keep);
    free(to);
    return 1;
}

/* The buttress of a main root entering the soil (see the header): over
 * the last stretch above the ground (max(12 r, 4 Re), Re the radius there)
 * the root widens like a trumpet to `flare` times Re, and its underground
 * end goes on down into the soil, drifting a little away from the host,
 * to 1.5 flare Re under the ground: the ground cuts a flared foot, as at a
 * tree's base. (An end that turned outward at the ground showed as a dome
 * or a boot.) Points keep their number, so the net's indices hold; they
 * stay clear of the hosts only. */
static void buttress(roots_net *net, const banyan_roots_params *p, const roots_poly *pl, const double *arc) {
    v3 *P = net->pts + pl->off;
    double *R = net->rad + pl->off;
    const uint32_t n = pl->n, ie = pl->soil_from - 1;
    const double r = net->r, Re = R[ie], Rf = Re * p->flare;
    const double len = 12.0 * r > 4.0 * Re ? 12.0 * r : 4.0 * Re;
    for (uint32_t i = 0; i <= ie; i++) {
        double x = 1.0 - (arc[ie] - arc[i]) / len;
        R[i] *= 1.0 + (p->flare - 1.0) * (x > 0 ? x * x * x : 0.0); /* concave: a trumpet */
    }
    const v3 E = P[ie];
    v3 h = v3_norm_or(v3_make(P[n - 1].x - E.x, P[n - 1].y - E.y, 0), v3_make(1, 0, 0));
    const double gz = net->w.ground_z, depth = 1.5 * Rf, drift = 0.6 * Rf;
    roots_world sw = roots_soil_world(&net->w);
    for (uint32_t i = ie + 1; i < n; i++) {
        double t = (double)(i - ie) / (double)(n - 1 - ie);
        v3 q = v3_madd(E, h, drift * t * t);
        q.z = gz + (E.z - gz) * (1.0 - t) - depth * t;
        world_push_out(&sw, &q); /* a host that reaches below the ground */
        P[i] = q;
        R[i] = Rf * (1.0 - 0.3 * t);
    }
}

/* The pipe model (see the header). */
static int set_radii(roots_net *net, const banyan_roots_params *p) {
    const int N = net->N, B = net->B, nb = net->nb;
    const double r = net->r, e = p->pipe_exponent, tipf = dm_pow(p->tip_radius, e), tip = p->tip_radius * r;
    const double gain = 2.0 * p->maturity;
    uint32_t longest = 2;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].n > longest) longest = net->poly[t].n;
    double *arc = malloc(sizeof(double) * longest), *F = malloc(sizeof(double) * longest);
    double *f1 = malloc(sizeof(double) * (size_t)(N * (nb ? nb : 1)));
    if (!arc || !F || !f1) {
        free(arc); free(F); free(f1);
        return 0;
    }
    for (int a = 0; a < N; a++)
        for (int k = 0; k < nb; k++) {
            int slot = a * nb + k;
            int n2 = net->Q_valid[slot] + (k > 0 ? net->Q_valid[slot - 1] : 0);
            f1[slot] = net->K_valid[slot] ? tipf * (1.0 + gain * (1.0 + n2)) : 0.0;
        }
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        const v3 *P = net->pts + pl->off;
        double *R = net->rad + pl->off;
        uint32_t n = pl->n;
        arc_of(P, n, arc);
        if (pl->kind == ROOT_MAIN) {
            int a = pl->a, ap = (a + N - 1) % N;
            for (uint32_t i = 0; i < n; i++) F[i] = 0;
            /* Half of each first branch root's flow joins at its start (on
             * a) and half at its end (on a from a - 1's slots). */
            for (int k = 0; k < nb; k++)
                for (int side = 0; side < (N > 1 ? 2 : 1); side++) {
                    int slot = (side ? ap : a) * nb + k;
                    int b = side ? (f1[slot] > 0 ? roots_branch_end_b(net, p, slot) : -1) : roots_branch_b(p, k);
                    if (b < 0 || b >= B) continue;
                    uint32_t at = net->M_at[(size_t)a * B + b] - pl->off;
                    if (at < n) F[at] += gain * 0.5 * f1[slot];
                }
            double sum = 0, x_prev = -1, R_prev = 0; /* x is constant along most of a root: one pow per run */
            for (uint32_t i = 0; i < n; i++) {
                sum += F[i];
                double own = tipf + (1.0 - tipf) * (arc[i] / (8.0 * r) < 1 ? arc[i] / (8.0 * r) : 1.0);
                double x = own + sum;
                if (x != x_prev) R_prev = r * dm_pow(x, 1.0 / e), x_prev = x;
                R[i] = R_prev;
            }
        } else {
            double f = pl->kind == ROOT_FIRST ? f1[pl->a * nb + pl->k] : tipf * (1.0 + gain);
            double Rf = r * dm_pow(f, 1.0 / e);
            for (uint32_t i = 0; i < n; i++) R[i] = Rf;
        }
        /* No steps where branches join: three passes of a [1 2 1] filter. */
        for (int pass = 0; pass < 3 && n > 2; pass++) {
            double prev = R[0];
            for (uint32_t i = 1; i + 1 < n; i++) {
                double cur = R[i];
                R[i] = 0.25 * prev + 0.5 * cur + 0.25 * R[i + 1];
                prev = cur;
            }
        }
        if (pl->kind != ROOT_MAIN) {
            thin_ends(R, arc, n, tip, 3.0 * r);
            continue;
        }
        if (pl->soil_from >= n) {
            /* A growing tip: thins to tip r over its last 6 r. */
            double L = arc[n - 1];
            for (uint32_t i = 0; i < n; i++) R[i] = tip + (R[i] - tip) * smoothstep((L - arc[i]) / (6.0 * r));
            continue;
        }
        buttress(net, p, pl, arc);
    }
    free(arc);
    free(F);
    free(f1);
    return 1;
}

banyan_status roots_make_paths(roots_net *net, const banyan_roots_params *p) {
    const int N = net->N, B = net->B, nb = net->nb;
    size_t longest = (size_t)B + 1;
    if ((size_t)net->S1 > longest) longest = (size_t)net->S1;
    if ((size_t)net->S2 > longest) longest = (size_t)net->S2;
    v3 *src = malloc(sizeof(v3) * longest);
    uint32_t *idx = malloc(sizeof(uint32_t) * longest);
    roots_world soil_w = roots_soil_world(&net->w);
    builder bd = {net, &net->w, 0, 0, p->smooth_paths, NULL};
    if (!src || !idx || !roots_reserve_pts(net, (uint32_t)(N * (B + 1) + N * nb * (net->S1 + net->S2)) + 64)) {
        free(src); free(idx);
        return BANYAN_E_NOMEM;
    }
    int id = 0;
    for (int a = 0; a < N && !bd.oom; a++) {
        src[0] = net->G;
        for (int b = 0; b < B; b++) src[b + 1] = net->M[(size_t)a * B + b];
        uint32_t off = net->n_pts;
        bd.w = &net->w;
        polyline(&bd, src, (uint32_t)B + 1, idx, NULL);
        if (prog_stopped(net->prog)) break;
        memcpy(net->M_at + (size_t)a * B, idx + 1, sizeof(uint32_t) * B);
        uint32_t soil_from = UINT32_MAX;
        if (net->soil_b[a] < B) {
            /* The underground end: clear of the hosts only. */
            bd.w = &soil_w;
            v3 prev = net->pts[net->n_pts - 1];
            soil_from = net->n_pts - off;
            for (int j = 0; j < ROOTS_SOIL_PTS; j++) {
                v3 q = net->soil_pts[(size_t)a * ROOTS_SOIL_PTS + j];
                repair(&bd, prev, q, 0, 0, 0);
                put(&bd, q, 0, j + 1 == ROOTS_SOIL_PTS);
                prev = q;
            }
            bd.w = &net->w;
        }
        uint32_t n = net->n_pts - off;
        if (!roots_add_poly(net, off, n, ROOT_MAIN, id++, a, -1)) bd.oom = 1;
        else if (soil_from != UINT32_MAX) net->poly[net->n_poly - 1].soil_from = soil_from;
    }
    bd.press = p->hugging ? p : NULL;
    for (int a = 0; a < N && !bd.oom; a++)
        for (int k = 0; k < nb; k++) {
            int slot = a * nb + k;
            if (!net->K_valid[slot]) continue;
            uint32_t off = net->n_pts;
            uint32_t n = polyline(&bd, net->K + (size_t)slot * net->S1, (uint32_t)net->S1, idx,
                                  net->K_ok + (size_t)slot * net->S1);
            if (prog_stopped(net->prog)) break;
            net->K_mid_at[slot] = idx[(net->S1 - 1) / 2];
            if (!roots_add_poly(net, off, n, ROOT_FIRST, id++, a, k)) bd.oom = 1;
        }
    for (int a = 0; a < N && !bd.oom; a++)
        for (int k = 0; k < nb; k++) {
            int slot = a * nb + k;
            if (!net->Q_valid[slot]) continue;
            uint32_t off = net->n_pts;
            uint32_t n = polyline(&bd, net->Q + (size_t)slot * net->S2, (uint32_t)net->S2, NULL, NULL);
            if (!roots_add_poly(net, off, n, ROOT_SECOND, id++, a, k)) bd.oom = 1;
        }
    free(src);
    free(idx);
    if (prog_stopped(net->prog)) return BANYAN_OK; /* build_hosts reports the stop */
    if (!bd.oom && p->smooth_paths && !decimate(net)) bd.oom = 1;
    if (!bd.oom && !set_radii(net, p)) bd.oom = 1;
    return bd.oom ? BANYAN_E_NOMEM : BANYAN_OK;
}
