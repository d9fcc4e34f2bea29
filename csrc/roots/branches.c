/* First branch roots (spec roots.md 2), main-root correction (3) and
 * second branch roots (4).
 *
 * A first branch root joins M(a,b) to M(a+1,b) along a cubic Bezier with
 * vertical control-point draws, sampled at even t with vertical jitter.
 * When a sample would touch a host (or the step to it would cut through
 * one), it is turned about the vertical axis through the previous point in
 * 1-degree steps, in a direction drawn once per event, until it is free;
 * the rest of the root is then re-planned from the turned point to the
 * same end, so every root ends exactly on M(a+1,b). The spec's I(-15, 15)
 * is read with its notation: a pick of -15 or +15 (bezier_uniform draws
 * in between instead). */
#include "roots_internal.h"

#include "base/bezier.h"

static const v3 UP = {0, 0, 1};

/* A branch step may sag ROOTS_SAG r into the r-offset of a host before it
 * counts as cutting through (the same test as segment repair). */
#define STEP_SAG ROOTS_SAG

static double vertical_draw(pcg32 *g, double v, int uniform) {
    if (uniform) return rng_range(g, -v, v);
    return rng_below(g, 2) ? v : -v;
}

static int step_free(const roots_world *w, v3 from, v3 q) {
    if (!world_free(w, q)) return 0;
    double stop = w->r * (1.0 - STEP_SAG);
    return world_segment_clearance(w, from, q, stop) >= stop;
}

/* Turns *q about the vertical axis through `from` in 1-degree steps in
 * direction dir (+1 left, -1 right) until the step is free; 0 when a full
 * turn finds nothing. Same result as testing all 359 angles, but angles
 * whose point provably cannot be free yet are skipped: the clearance is
 * 1-Lipschitz and turning by k degrees moves the point by the chord
 * 2 h sin(k delta / 2), h its horizontal distance from the axis. */
static int turn(const roots_world *w, const double *cs, v3 from, v3 *q, double dir) {
    const double delta = deg2rad(1.0);
    v3 off = v3_sub(*q, from);
    double h = sqrt(off.x * off.x + off.y * off.y);
    /* Turning keeps the height: below the ground's free height no angle
     * can succeed. */
    if (w->ground && q->z < w->ground_z + w->r - w->eps) return 0;
    int deg = 1;
    while (deg < 360) {
        double c = cs[2 * deg], s = dir * cs[2 * deg + 1];
        v3 cand = v3_add(from, v3_make(c * off.x - s * off.y, s * off.x + c * off.y, off.z));
        double clear = world_clearance_in(w, cand, 1, w->r, NULL, NULL), need; /* exact below r */
        if (clear >= w->r - w->eps) {
            double stop = w->r * (1.0 - STEP_SAG);
            double seg = world_segment_clearance(w, from, cand, stop);
            if (seg >= stop) {
                *q = cand;
                return 1;
            }
            /* The step's clearance is 1-Lipschitz in its end point too. */
            need = stop - seg;
        } else {
            need = w->r - w->eps - clear;
        }
        if (need >= 2.0 * h) return 0; /* no angle moves the point far enough */
        /* Angles deg+1 .. deg+k stay closer than the chord allows. */
        double span = 2.0 * dm_asin(need / (2.0 * h)) / delta;
        int k = (int)ceil(span) - 1;
        deg += 1 + (k > 0 ? k : 0);
    }
    return 0;
}

/* Control points for a root from P0 to P3 (spec 2). */
static void plan(pcg32 *g, const banyan_roots_params *p, double u, v3 P0, v3 P3, v3 c[4]) {
    v3 gv = v3_sub(P3, P0);
    double z1 = vertical_draw(g, p->branch_vertical * u, p->bezier_uniform);
    double z2 = vertical_draw(g, p->branch_vertical * u, p->bezier_uniform);
    c[0] = P0;
    c[1] = v3_add(v3_madd(P0, gv, 1.0 / 3.0), v3_make(0, 0, z1));
    c[2] = v3_add(v3_madd(P0, gv, 2.0 / 3.0), v3_make(0, 0, z2));
    c[3] = P3;
}

/* The end slot of each first branch root (net->K_end): level (k) or, for
 * a branch_tilt share, one slot lower or higher on the next main root, a
 * diamond lattice instead of rungs at one height round the host. An end
 * stays above that root's soil entry, and ends never decrease along a main
 * root (slot k ending lower than slot k + 1 would cross it). Slot indices
 * are points the correction (spec 3) never moves, so every end keeps its
 * junction. One stream per main root: branch_tilt 0 draws nothing. */
static void pick_ends(roots_net *net, const banyan_roots_params *p) {
    const int N = net->N, nb = net->nb;
    for (int a = 0; a < N; a++) {
        pcg32 g;
        pcg32_seed(&g, p->seed, (uint64_t)STREAM_TILT + (uint64_t)a);
        int a2 = (a + 1) % N, prev = 0;
        for (int k = 0; k < nb; k++) {
            int e = k;
            if (p->branch_tilt > 0 && rng_uniform(&g) < p->branch_tilt) {
                int d = rng_below(&g, 2) ? 1 : -1;
                if (k + d < prev || k + d >= nb || roots_branch_b(p, k + d) >= net->soil_b[a2]) d = -d;
                if (k + d >= prev && k + d >= 0 && k + d < nb && roots_branch_b(p, k + d) < net->soil_b[a2]) e = k + d;
            }
            net->K_end[a * nb + k] = e;
            if (roots_slot_open(net, p, a, k)) prev = e;
        }
    }
}

void roots_grow_first(roots_net *net, const banyan_roots_params *p) {
    if (!p->first_branches || net->N < 2) return;
    pick_ends(net, p);
    const roots_world *w = &net->w;
    const int N = net->N, B = net->B, nb = net->nb, m = net->S1 - 1;
    const double u = net->u;
    double cs[720]; /* cos, sin of 0 .. 359 degrees */
    for (int d = 0; d < 360; d++) {
        cs[2 * d] = dm_cos(deg2rad(d));
        cs[2 * d + 1] = dm_sin(deg2rad(d));
    }
    for (int a = 0; a < N; a++) {
        for (int k = 0; k < nb; k++) {
            if (roots_stop(net)) return;
            int b = roots_branch_b(p, k);
            int slot = a * nb + k;
            if (b < 0 || b >= B || !roots_slot_open(net, p, a, k)) continue;
            pcg32 g;
            pcg32_seed(&g, p->seed, (uint64_t)STREAM_FIRST + (uint64_t)slot);
            v3 P0 = net->M_grown[(size_t)a * B + b];
            v3 P3 = net->M_grown[(size_t)((a + 1) % N) * B + roots_branch_end_b(net, p, slot)];
            v3 *K = net->K + (size_t)slot * net->S1;
            v3 c[4];
            plan(&g, p, u, P0, P3, c);
            int i0 = 0;
            K[0] = P0;
            for (int i = 0; i + 1 < m; i++) {
                double t = (double)(i + 1 - i0) / (double)(m - i0);
                v3 q = bezier3(c[0], c[1], c[2], c[3], t);
                q.z += rng_range(&g, -p->branch_jitter * u, p->branch_jitter * u);
                uint8_t ok = 1;
                if (!step_free(w, K[i], q)) {
                    net->stats.reroute_events++;
                    double dir = rng_below(&g, 2) ? 1.0 : -1.0;
                    int found = turn(w, cs, K[i], &q, dir);
                    if (!found) {
                        world_push_out(w, &q);
                        net->stats.reroute_pushouts++;
                        ok = 0;
                    }
                    /* Re-plan the rest: P0' = the turned point, P3' = P3. */
                    plan(&g, p, u, q, P3, c);
                    i0 = i + 1;
                }
                K[i + 1] = q;
                net->K_ok[(size_t)slot * net->S1 + i + 1] = ok;
            }
            K[m] = P3;
            net->K_valid[slot] = 1;
            net->stats.first_roots++;
            net->stats.first_points += (uint32_t)net->S1;
        }
    }
}

/* Hugging: a branch point farther than 1.5 r from the host
 * it runs over, but within 4 hug_range r of it, goes back to distance r
 * from it (along the distance-field normal; less when the full pull
 * would leave it unfree), so branch roots lie on the bark instead of
 * standing off it like tents. Returns 1 when it moved. */
int roots_press_point(const roots_world *w, const banyan_roots_params *p, v3 *q) {
    /* Four times the main roots' hug range: a second branch root's wide
     * sideways draw (+-20 u) otherwise leaves loops of rope in the air. */
    double r = w->r, range = 4.0 * p->hug_range * r;
    v3 n;
    int which;
    double c = world_clearance_in(w, *q, 0, range, &n, &which);
    if (which < 0 || c <= 1.5 * r || c >= range) return 0;
    for (double f = 1.0; f > 0.1; f -= 0.25) {
        v3 t = v3_madd(*q, n, -(c - r * 1.02) * f);
        if (world_free(w, t)) {
            *q = t;
            return 1;
        }
    }
    return 0;
}

void roots_press_first(roots_net *net, const banyan_roots_params *p) {
    const int N = net->N, nb = net->nb, S1 = net->S1;
    const roots_world *w = &net->w;
    for (int slot = 0; slot < N * nb; slot++) {
        if (roots_stop(net)) return;
        if (!net->K_valid[slot]) continue;
        v3 *K = net->K + (size_t)slot * S1;
        uint8_t *ok = net->K_ok + (size_t)slot * S1;
        /* Re-routing turns a point about the vertical through the last one,
         * and the re-planned curve runs back into the host, so a root round
         * a trunk zigzags point by point. Relaxing each point halfway to its
         * neighbours' middle (pushed back out when that cuts into a host)
         * irons that out; the ends stay. */
        if (p->smooth_paths)
            for (int it = 0; it < 12; it++)
                for (int i = 1; i + 1 < S1; i++) {
                    v3 q = v3_lerp(K[i], v3_lerp(K[i - 1], K[i + 1], 0.5), 0.5);
                    if (!world_free(w, q)) { /* most are free: tested once */
                        world_push_out(w, &q);
                        if (!world_free(w, q)) continue;
                    }
                    K[i] = q;
                    ok[i] = ok[i + 1] = 0; /* steps to check again: segment repair */
                }
        if (p->hugging)
            for (int i = 1; i + 1 < S1; i++)
                if (roots_press_point(w, p, &K[i])) ok[i] = ok[i + 1] = 0;
    }
}

/* Spec 3: where a first branch root leaves M(a,b) the main root follows
 * the Bezier M(a,b), K^1 + 2e, M(a,b+2), M(a,b+5), e = M(a,b+1) - K^1,
 * sampled at t = j/5. Generalised to any spacing s >= 2: P3 = M(a,b+s),
 * t = j/s. Moved points are pushed out of hosts. */
void roots_correct_mains(roots_net *net, const banyan_roots_params *p) {
    const int N = net->N, B = net->B, nb = net->nb, s = p->branch_spacing;
    if (!p->correction || s < 2) return;
    const roots_world *w = &net->w;
    for (int a = 0; a < N; a++) {
        if (roots_stop(net)) return;
        const v3 *Mg = net->M_grown + (size_t)a * B;
        v3 *M = net->M + (size_t)a * B;
        for (int k = 0; k < nb; k++) {
            int slot = a * nb + k, b = roots_branch_b(p, k);
            if (!net->K_valid[slot] || b + s > B - 1 || b + s > net->soil_b[a]) continue;
            v3 K1 = net->K[(size_t)slot * net->S1 + 1];
            v3 e = v3_sub(Mg[b + 1], K1);
            v3 P0 = Mg[b], P1 = v3_madd(K1, e, 2.0), P2 = Mg[b + 2], P3 = Mg[b + s];
            for (int j = 1; j < s; j++) {
                v3 q = bezier3(P0, P1, P2, P3, (double)j / s);
                if (world_push_out(w, &q)) net->stats.correction_pushouts++;
                M[b + j] = q;
            }
        }
    }
}

/* Spec 4: a second branch root joins the midpoints K^10 and K'^10 of the
 * first branch roots leaving main root a at M(a,b) and M(a,b+5). */
void roots_grow_second(roots_net *net, const banyan_roots_params *p) {
    if (!p->second_branches) return;
    const roots_world *w = &net->w;
    const int N = net->N, nb = net->nb, mid = (net->S1 - 1) / 2, m = net->S2 - 1;
    const double u = net->u;
    for (int a = 0; a < N; a++) {
        for (int k = 0; k + 1 < nb; k++) {
            if (roots_stop(net)) return;
            int slot = a * nb + k;
            if (!net->K_valid[slot] || !net->K_valid[slot + 1]) continue;
            pcg32 g;
            pcg32_seed(&g, p->seed, (uint64_t)STREAM_SECOND + (uint64_t)slot);
            v3 P0 = net->K[(size_t)slot * net->S1 + mid], P3 = net->K[(size_t)(slot + 1) * net->S1 + mid];
            v3 f = v3_sub(P3, P0);
            v3 D = v3_madd(P0, f, 1.0 / 3.0), D2 = v3_madd(P0, f, 2.0 / 3.0);
            /* W points away from G's vertical axis; W x U is the sideways
             * direction round it. Right under G, fall back to f's side. */
            v3 side_f = v3_norm_or(v3_cross(v3_make(f.x, f.y, 0), UP), v3_make(1, 0, 0));
            v3 W = v3_make(D.x - net->G.x, D.y - net->G.y, 0), W2 = v3_make(D2.x - net->G.x, D2.y - net->G.y, 0);
            v3 s1 = v3_len2(W) > 1e-24 ? v3_cross(v3_norm(W), UP) : side_f;
            v3 s2 = v3_len2(W2) > 1e-24 ? v3_cross(v3_norm(W2), UP) : side_f;
            v3 P1 = v3_madd(D, s1, vertical_draw(&g, p->second_lateral * u, p->bezier_uniform));
            v3 P2 = v3_madd(D2, s2, vertical_draw(&g, p->second_lateral * u, p->bezier_uniform));
            v3 *Q = net->Q + (size_t)slot * net->S2;
            Q[0] = P0;
            for (int j = 1; j < m; j++) {
                v3 q = bezier3(P0, P1, P2, P3, (double)j / m);
                if (world_push_out(w, &q)) net->stats.second_pushouts++;
                if (p->hugging) roots_press_point(w, p, &q);
                Q[j] = q;
            }
            Q[m] = P3;
            net->Q_valid[slot] = 1;
            net->stats.second_roots++;
            net->stats.second_points += (uint32_t)net->S2;
        }
    }
}
