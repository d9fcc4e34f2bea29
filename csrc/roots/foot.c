/* The foot of the net (docs/roots.md "The foot"): where a strangler fig
 * meets the soil its roots close round the host and spread over the
 * ground. Three kinds of ROOT_FOOT polyline, added once the radii are set
 * (paths.c), each starting on a point of the net (`from`):
 * - Drop roots: round(foot_roots maturity N) roots (N main roots) run
 *   down the host to the ground, each from the lowest point of the net
 *   near the widest gap (in angle round G) left between the roots at the
 *   soil, leaning (up to 0.6 m per m) to land in its middle, so they run
 *   diagonally and cross; they thicken downwards, flare at the soil line
 *   and go on into the soil, so the lattice reaches the ground and its
 *   feet merge into a skirt.
 * - Plank buttresses: a main root that enters the soil grows a plank on
 *   the host's outward normal there: a fin from the root down to the
 *   ground, 0.6 of the buttress reach long and 0.7 of that high at the
 *   root, with a concave top edge. It is a stack of strands (scaled copies
 *   of the top edge) whose capsules overlap, which the fused surface
 *   merges into one thin wall (the fused surface only: as tubes the
 *   strands would read as a comb).
 *   Mains that reach the soil within 0.3 of the reach of one that has a
 *   buttress share it.
 * - Surface roots: under each plank a root runs on along the ground, half
 *   in the soil, meandering, to the buttress reach past the host's
 *   surface (buttress x the host's smallest extent x maturity), with a
 *   side root on figs of maturity 0.8 and more; both end in the soil.
 * Their points keep r from the hosts; points on or in the soil (soil_from
 * on) do not keep r from the ground. */
#include <stdlib.h>
#include <math.h>

#include "roots_internal.h"

static const v3 UP = {0, 0, 1};

/* Longest polyline this stage makes (points). */
#define FOOT_MAX_PTS 160

typedef struct foot {
    roots_net *net;
    const banyan_roots_params *p;
    roots_world soil; /* the hosts without the ground */
    int id;           /* next root_id */
    int oom;
    v3 pt[FOOT_MAX_PTS];
    double rad[FOOT_MAX_PTS];
    uint32_t n, soil_from;
} foot;

static void add_pt(foot *f, v3 q, double R) {
    if (f->n < FOOT_MAX_PTS) f->pt[f->n] = q, f->rad[f->n++] = R;
}

/* Appends the polyline in f->pt as a ROOT_FOOT starting on net point
 * `from`; returns its first point's index (UINT32_MAX when none). */
static uint32_t emit(foot *f, uint32_t from, int a, int k) {
    roots_net *net = f->net;
    if (f->oom || f->n < 2) return UINT32_MAX;
    if (!roots_reserve_pts(net, f->n)) {
        f->oom = 1;
        return UINT32_MAX;
    }
    uint32_t off = net->n_pts;
    for (uint32_t i = 0; i < f->n; i++) net->pts[off + i] = f->pt[i], net->rad[off + i] = f->rad[i];
    net->n_pts += f->n;
    if (!roots_add_poly(net, off, f->n, ROOT_FOOT, f->id++, a, k)) {
        f->oom = 1;
        return UINT32_MAX;
    }
    roots_poly *pl = &net->poly[net->n_poly - 1];
    pl->from = from;
    pl->soil_from = f->soil_from < f->n ? f->soil_from : f->n;
    return off;
}

/* q moved out of the hosts to clearance r (not the ground); 0 when it
 * could not be. */
static int keep_clear(const foot *f, v3 *q) {
    if (world_clearance_in(&f->soil, *q, 0, f->net->r, NULL, NULL) >= f->net->r * (1.0 - 1e-6)) return 1;
    world_push_out(&f->soil, q);
    return world_clearance_in(&f->soil, *q, 0, f->net->r, NULL, NULL) >= f->net->r * (1.0 - 1e-3);
}

/* q as the next point: clear of the hosts, and the step to it does not
 * sag into one (ROOTS_SAG, as segment repair asks). */
static int next_ok(const foot *f, v3 *q) {
    const double stop = f->net->r * (1.0 - ROOTS_SAG);
    if (!keep_clear(f, q)) return 0;
    return f->n == 0 || world_segment_clearance(&f->soil, f->pt[f->n - 1], *q, stop) >= stop;
}

/* ------------------------------------------------------------ drop roots */

/* Angle of q round the vertical through G. */
static double angle_of(const roots_net *net, v3 q) { return dm_atan2(q.y - net->G.y, q.x - net->G.x); }

/* a - b turned into [-pi, pi). */
static double angle_diff(double a, double b) {
    double d = a - b;
    return d - 2.0 * BANYAN_PI * floor(d / (2.0 * BANYAN_PI) + 0.5);
}

/* One drop root from net point `from` down the host to the soil, leaning
 * `lean` metres sideways (counter-clockwise round G) per metre down. */
static void drop_root(foot *f, uint32_t from, double lean, int a, int k, pcg32 *g) {
    roots_net *net = f->net;
    const banyan_roots_params *p = f->p;
    const roots_world *w = &net->w;
    const double r = net->r, gz = w->ground_z, step = 2.0 * r, stop = r * (1.0 - ROOTS_SAG);
    v3 S = net->pts[from];
    double z0 = S.z;
    if (z0 - gz < 4.0 * r) return; /* roots_grow_foot asks for the ground */
    /* as thick as a branch root, even from a main root's point */
    double R0 = net->rad[from] < 1.2 * r ? net->rad[from] : 1.2 * r;
    f->n = 0;
    add_pt(f, S, R0);
    double slope = 0; /* wander about the lean per step, a random walk */
    while (f->n < FOOT_MAX_PTS - 4) {
        v3 prev = f->pt[f->n - 1], n;
        int which;
        double c = world_clearance_in(w, prev, 0, p->hug_range * r, &n, &which);
        v3 side = which >= 0 ? v3_norm_or(v3_cross(UP, n), v3_make(1, 0, 0)) : v3_make(0, 0, 0);
        slope = 0.8 * slope + rng_range(g, -0.06, 0.06);
        v3 q = v3_madd(v3_madd(prev, UP, -step), side, (lean + slope) * step);
        if (q.z < gz + r) q.z = gz + r;
        if (!world_free(w, q)) world_push_out(w, &q);
        if (c < p->hug_range * r) roots_press_point(w, p, &q);
        if (!world_free(w, q) || q.z > prev.z - 0.25 * step) break; /* a ledge: the drop ends here */
        if (world_segment_clearance(w, prev, q, stop) < stop) break;
        add_pt(f, q, R0);
        if (q.z <= gz + r * (1.0 + 1e-6)) break;
    }
    v3 E = f->pt[f->n - 1];
    if (E.z > gz + 1.5 * r) { /* did not reach the ground */
        f->n = 0;
        return;
    }
    /* Radii: thicker downwards by the flow the drop gathers, and a flare at
     * the soil line over max(8 R, 0.35 m). */
    const double m = p->maturity, gain = 0.6 * m, ff = 1.0 + 0.8 * m;
    double Rg = R0 * (1.0 + gain), hf = 8.0 * Rg > 0.35 ? 8.0 * Rg : 0.35;
    for (uint32_t i = 0; i < f->n; i++) {
        double down = (z0 - f->pt[i].z) / (z0 - gz);
        double x = 1.0 - (f->pt[i].z - gz) / hf;
        f->rad[i] = R0 * (1.0 + gain * down) * (1.0 + (ff - 1.0) * (x > 0 ? x * x * x : 0.0));
    }
    /* Into the soil, straight down with a little drift outward. */
    f->soil_from = f->n - 1;
    v3 n;
    int which;
    world_clearance_in(&f->soil, E, 0, HUGE_VAL, &n, &which);
    v3 out = v3_norm_or(v3_make(n.x, n.y, 0), v3_make(0, 0, 0));
    double Rf = f->rad[f->n - 1];
    for (int j = 1; j <= 2; j++) {
        v3 q = v3_madd(E, out, 0.3 * Rf * j);
        q.z = gz - 1.5 * Rf * j;
        if (!next_ok(f, &q)) break;
        add_pt(f, q, Rf * (1.0 - 0.1 * j));
    }
    emit(f, from, a, k);
}

static int dbl_cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The lowest point of a branch root (or of a main root above its soil
 * entry) on the host within `half` of angle th, at least 4 r above the
 * ground; UINT32_MAX when there is none. */
static uint32_t drop_source(const foot *f, double th, double half) {
    const roots_net *net = f->net;
    const double r = net->r, gz = net->w.ground_z, near = f->p->hug_range * r;
    uint32_t best = UINT32_MAX;
    double bz = HUGE_VAL;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind == ROOT_FOOT) continue;
        uint32_t end = pl->kind == ROOT_MAIN ? (pl->soil_from < pl->n ? pl->soil_from - 1 : pl->n) : pl->n;
        for (uint32_t i = 1; i < end; i++) {
            v3 q = net->pts[pl->off + i];
            if (q.z >= bz || q.z - gz < 4.0 * r) continue;
            double d = angle_diff(angle_of(net, q), th);
            if (d < -half || d > half) continue;
            if (world_clearance_in(&net->w, q, 0, near, NULL, NULL) >= near) continue;
            bz = q.z, best = pl->off + i;
        }
    }
    return best;
}

/* Drop roots where the foot is most open: each goes into the middle of
 * the widest gap of angle (round G) between the roots already at the
 * soil, from the lowest point of the net above it. */
static void drop_roots(foot *f) {
    roots_net *net = f->net;
    const double two_pi = 2.0 * BANYAN_PI;
    int want = (int)(f->p->foot_roots * f->p->maturity * net->N + 0.5);
    if (want <= 0) return;
    int cap = want + net->N + 1;
    double *ang = malloc(sizeof(double) * (size_t)cap * 2), *shut = ang + cap;
    if (!ang) {
        f->oom = 1;
        return;
    }
    int n = 0, n_shut = 0; /* shut: middles of gaps no drop can fill */
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind == ROOT_MAIN && pl->soil_from < pl->n) ang[n++] = angle_of(net, net->pts[pl->off + pl->soil_from - 1]);
    }
    pcg32 g;
    pcg32_seed(&g, f->p->seed, (uint64_t)STREAM_FOOT);
    for (int d = 0; d < want && !f->oom && n < cap && !roots_stop(net); d++) { /* a scan of the net each */
        /* the widest gap not shut */
        qsort(ang, (size_t)n, sizeof(double), dbl_cmp);
        double best = -1, mid = 0;
        for (int i = 0; i < (n ? n : 1); i++) {
            double a0 = n ? ang[i] : -BANYAN_PI, a1 = n ? (i + 1 < n ? ang[i + 1] : ang[0] + two_pi) : BANYAN_PI;
            double w = a1 - a0, c = a0 + 0.5 * w;
            int closed = 0;
            for (int j = 0; j < n_shut; j++) {
                double e = angle_diff(shut[j], c);
                if (e > -0.25 * w && e < 0.25 * w) closed = 1;
            }
            if (!closed && w > best) best = w, mid = c;
        }
        if (best <= 0) break;
        uint32_t from = drop_source(f, mid, 0.4 * best);
        uint32_t before = net->n_poly;
        if (from != UINT32_MAX) {
            /* lean so as to land in the gap's middle */
            v3 S = net->pts[from];
            double e = angle_diff(mid, angle_of(net, S));
            double rho = sqrt((S.x - net->G.x) * (S.x - net->G.x) + (S.y - net->G.y) * (S.y - net->G.y));
            double lean = e * rho / (S.z - net->w.ground_z);
            lean = lean > 0.6 ? 0.6 : (lean < -0.6 ? -0.6 : lean);
            drop_root(f, from, lean, d, 0, &g);
        }
        if (net->n_poly > before) {
            const roots_poly *pl = &net->poly[net->n_poly - 1];
            ang[n++] = angle_of(net, net->pts[pl->off + (pl->soil_from < pl->n ? pl->soil_from : pl->n - 1)]);
        } else if (n_shut < cap) {
            shut[n_shut++] = mid;
        } else {
            break;
        }
    }
    free(ang);
}

/* ----------------------------------------------- buttresses, surface roots */

/* The point of main root pl at height z above its soil entry (searching
 * up from the entry), and the index of the nearest net point. */
static v3 main_at_height(const roots_net *net, const roots_poly *pl, uint32_t ie, double z, uint32_t *at) {
    const v3 *P = net->pts + pl->off;
    for (uint32_t i = ie; i > 0; i--) {
        if (P[i - 1].z >= z && P[i].z <= z) {
            double t = P[i - 1].z > P[i].z ? (P[i - 1].z - z) / (P[i - 1].z - P[i].z) : 0;
            *at = pl->off + (t < 0.5 ? i - 1 : i);
            return v3_lerp(P[i - 1], P[i], t);
        }
    }
    *at = pl->off + ie;
    return P[ie];
}

/* The plank of main root t entering the soil at E = its point ie. */
static void plank(foot *f, uint32_t t, uint32_t ie, v3 h, v3 side, double L, pcg32 *g) {
    roots_net *net = f->net;
    const double r = net->r, gz = net->w.ground_z;
    const roots_poly pl = net->poly[t];
    const double Re = net->rad[pl.off + ie], Lp = 0.6 * L;
    double Hb = 0.7 * Lp;
    double top = net->pts[pl.off].z - gz - 2.0 * r; /* the root must reach that high */
    if (Hb > top) Hb = top;
    const double w0 = 0.45 * Re > 0.9 * r ? 0.45 * Re : 0.9 * r;
    if (Hb < 2.0 * w0 || Lp < 3.0 * r) return;
    int m = (int)(Hb / (0.9 * w0)) + 1, nx = (int)(Lp / (1.5 * r)) + 1;
    if (m > 16) m = 16;
    if (nx > 40) nx = 40;
    const double bend = rng_range(g, -0.2, 0.2);
    for (int j = 0; j < m && !f->oom; j++) {
        double fj = 1.0 - (double)j / m;
        uint32_t from;
        v3 s = main_at_height(net, &net->poly[t], ie, gz + fj * Hb, &from);
        f->n = 0;
        f->soil_from = FOOT_MAX_PTS;
        for (int i = 0; i <= nx; i++) {
            double x = (double)i / nx;
            /* strands start where the root passes their height and meet at the
             * plank's far end, so a root crossing the face does not shear
             * the plank into fingers */
            v3 base = v3_lerp(s, net->pts[pl.off + ie], x);
            v3 q = v3_madd(v3_madd(base, h, Lp * x), side, bend * Lp * x * x);
            q.z = gz + fj * Hb * dm_pow(1.0 - x, 1.6);
            if (!next_ok(f, &q)) break;
            if (q.z < gz + r && f->soil_from == FOOT_MAX_PTS) f->soil_from = f->n;
            add_pt(f, q, w0 * (1.0 - 0.5 * x));
        }
        if (f->n < 3) continue;
        v3 q = v3_madd(f->pt[f->n - 1], h, w0);
        q.z = gz - 2.0 * w0;
        if (next_ok(f, &q)) add_pt(f, q, 0.5 * w0);
        if (f->soil_from > f->n) f->soil_from = f->n - 1;
        emit(f, from, pl.a, j);
    }
}

/* A surface root from point s (net point `from`) along heading h for
 * length L, radius R0 tapering; returns its first point's index. */
static uint32_t surface_root(foot *f, uint32_t from, v3 s, v3 h, double L, double R0, int a, int k, pcg32 *g) {
    roots_net *net = f->net;
    const double r = net->r, gz = net->w.ground_z, tip = f->p->tip_radius * r;
    int ns = (int)(L / (2.0 * r)) + 1;
    if (ns > FOOT_MAX_PTS - 3) ns = FOOT_MAX_PTS - 3;
    if (ns < 3) return UINT32_MAX;
    double step = L / ns, turn = 0;
    f->n = 0;
    f->soil_from = 0;
    v3 q = s, head = h;
    add_pt(f, q, R0);
    for (int i = 1; i <= ns; i++) {
        turn = 0.7 * turn + rng_range(g, -0.12, 0.12);
        double c = dm_cos(turn), sn = dm_sin(turn);
        head = v3_norm_or(v3_make(head.x * c - head.y * sn, head.x * sn + head.y * c, 0), h);
        /* back towards h when it strays past 35 degrees */
        if (v3_dot(head, h) < 0.82) head = v3_norm_or(v3_lerp(head, h, 0.3), h);
        double x = (double)i / ns, R = tip + (R0 - tip) * dm_pow(1.0 - x, 1.2);
        v3 nq = v3_madd(q, head, step);
        nq.z = gz - 0.25 * R;
        if (!next_ok(f, &nq)) break;
        q = nq;
        add_pt(f, q, R);
    }
    if (f->n < 3) return UINT32_MAX;
    v3 e = v3_madd(q, head, 2.0 * f->rad[f->n - 1]);
    e.z = gz - 2.5 * f->rad[f->n - 1];
    if (next_ok(f, &e)) add_pt(f, e, f->rad[f->n - 1]);
    return emit(f, from, a, k);
}

static void buttresses(foot *f) {
    roots_net *net = f->net;
    const banyan_roots_params *p = f->p;
    const roots_world *w = &net->w;
    if (p->buttress <= 0 || p->maturity <= 0) return; /* roots_grow_foot asks for the ground */
    uint32_t n_poly = net->n_poly; /* mains only: the loop appends */
    v3 *done = malloc(sizeof(v3) * (size_t)(net->N ? net->N : 1)); /* entries that have a buttress */
    int n_done = 0;
    if (!done) {
        f->oom = 1;
        return;
    }
    for (uint32_t t = 0; t < n_poly && !f->oom && !roots_stop(net); t++) {
        if (net->poly[t].kind != ROOT_MAIN || net->poly[t].soil_from >= net->poly[t].n) continue;
        uint32_t ie = net->poly[t].soil_from - 1;
        const int a = net->poly[t].a;
        v3 E = net->pts[net->poly[t].off + ie], n;
        int which;
        world_clearance_in(&f->soil, E, 0, HUGE_VAL, &n, &which);
        if (which < 0) continue;
        v3 h = v3_norm_or(v3_make(n.x, n.y, 0), v3_norm_or(v3_make(E.x - net->G.x, E.y - net->G.y, 0), v3_make(1, 0, 0)));
        v3 side = v3_cross(UP, h);
        const banyan_hosts *H = net->hosts;
        double wx = H->hi[which].x - H->lo[which].x, wy = H->hi[which].y - H->lo[which].y;
        double wz = H->hi[which].z - H->lo[which].z, wmin = wx < wy ? wx : wy;
        double L = p->buttress * (wz < wmin ? wz : wmin) * p->maturity; /* a low rock: by its height */
        /* mains that reach the soil side by side share one buttress (each
         * its own spread them like the fingers of a hand) */
        int shared = 0;
        for (int j = 0; j < n_done; j++) shared |= v3_dist(done[j], E) < 0.3 * L;
        if (shared || n_done >= net->N) continue;
        done[n_done++] = E;
        pcg32 g;
        pcg32_seed(&g, p->seed, (uint64_t)STREAM_FOOT + 0x8000u + (uint64_t)a);
        const double Re = net->rad[net->poly[t].off + ie];
        if (p->surface == BANYAN_ROOTS_FUSED) plank(f, t, ie, h, side, L, &g); /* as tubes: a comb */
        /* The surface root under the plank, from the entry's foot on the
         * ground, and a side root from a third of the way out. */
        v3 s = E;
        s.z = w->ground_z - 0.25 * Re;
        if (!keep_clear(f, &s)) continue;
        double R0 = 0.9 * Re > net->r ? 0.9 * Re : net->r;
        uint32_t at = surface_root(f, net->poly[t].off + ie, s, h, L, R0, a, 100, &g);
        if (at == UINT32_MAX || p->maturity < 0.8) continue;
        uint32_t n_s = net->poly[net->n_poly - 1].n, i = n_s / 3;
        v3 s2 = net->pts[at + i];
        double turn = (rng_uniform(&g) < 0.5 ? -1.0 : 1.0) * rng_range(&g, 0.6, 1.0);
        v3 h2 = v3_make(h.x * dm_cos(turn) - h.y * dm_sin(turn), h.x * dm_sin(turn) + h.y * dm_cos(turn), 0);
        surface_root(f, at + i, s2, h2, 0.5 * L, 0.6 * net->rad[at + i], a, 101, &g);
    }
    free(done);
}

banyan_status roots_grow_foot(roots_net *net, const banyan_roots_params *p) {
    foot *f = calloc(1, sizeof *f);
    if (!f) return BANYAN_E_NOMEM;
    f->net = net;
    f->p = p;
    f->soil = roots_soil_world(&net->w);
    f->id = roots_next_id(net);
    if (net->w.ground) {
        drop_roots(f);
        if (!f->oom) buttresses(f);
    }
    int oom = f->oom;
    free(f);
    return oom ? BANYAN_E_NOMEM : BANYAN_OK;
}
