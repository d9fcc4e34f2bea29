/* Main roots by the 5-move sphere walk (spec roots.md 1). Each root starts
 * on a small circle around G and moves a sphere of radius r up to `moves`
 * times per growth point along V/|V| (forward draw) and V/|V| x U (lateral
 * draw), with V = S - Lambda - U while it grows from above downwards and
 * V = S - Lambda once it crawls.
 *
 * Paper mode (hugging off): a move that would touch a host or the ground
 * ends the growth point at the last free position.
 * Hugging mode (default): a move that would touch slides along the
 * surface it meets (its normal component is taken away, the centre stays
 * at distance r); while a host face is within hug_range r the downward
 * direction projected onto that face is added to V, and the centre is
 * pulled back to distance r from the face, so roots stay pressed against
 * the host and wrap over its edges (the distance-field normal turns round
 * an edge).
 * In both modes a root that lands on the ground or on an upward face
 * crawls; it grows down again once nothing supports it.
 *
 * Soil entry (on by default): a real fig root that reaches the
 * ground goes into it close to the host and thickens into a buttress; it
 * does not wander off over the soil. So a root that touches the ground
 * stops its walk there (its later growth points repeat that point) and
 * gets an underground end: it dips a few r below the ground and runs on
 * outwards, away from the host, for up to soil_reach r past the host's
 * surface (ROOTS_SOIL_PTS points, clear of the hosts only). With it, a
 * root that hangs free (no host face within hug_range, not crawling)
 * keeps only a slight outward pull (ROOTS_HANG) instead of S - Lambda:
 * aerial roots hang down towards the soil instead of spreading like an
 * umbrella. */
#include "roots_internal.h"

static const v3 UP = {0, 0, 1};

/* Outward pull of a root hanging free under soil_entry, times `descent`:
 * about 3 degrees off the vertical. */
#define ROOTS_HANG 0.05

/* The underground end of main root a entering the soil at E, drafted:
 * outwards (the host's normal, else away from G) for the rest of
 * soil_reach (plus 1.5 r), and down to 3 r below the ground. Its points
 * give the end's heading and its place in the polyline; paths.c's
 * buttress() sets their final positions once the radii are known. */
static void soil_end(roots_net *net, const banyan_roots_params *p, int a, v3 E, v3 head) {
    const roots_world *w = &net->w;
    roots_world sw = roots_soil_world(w);
    double r = net->r;
    v3 n;
    int which;
    double ch = world_clearance_in(w, E, 0, HUGE_VAL, &n, &which);
    v3 h = which >= 0 ? v3_make(n.x, n.y, 0) : v3_make(E.x - net->G.x, E.y - net->G.y, 0);
    h = v3_norm_or(h, head);
    double run = p->soil_reach * r - ch;
    if (run < 0) run = 0;
    run += 1.5 * r;
    double drop = E.z - (w->ground_z - 3.0 * r);
    for (int j = 0; j < ROOTS_SOIL_PTS; j++) {
        double t = (double)(j + 1) / ROOTS_SOIL_PTS;
        v3 q = v3_madd(E, h, run * t);
        q.z = E.z - drop * (1.0 - (1.0 - t) * (1.0 - t)); /* steep at first: into the soil, then outwards */
        world_push_out(&sw, &q); /* a host that reaches below the ground */
        net->soil_pts[(size_t)a * ROOTS_SOIL_PTS + j] = q;
    }
}

/* Within `support` below p lies the ground or a host. (q is within the
 * free ball of p, so outside every mesh, when support < r: the hugging
 * case; paper mode's longer reach asks with the sign.) */
static int supported(const roots_world *w, v3 p, double support) {
    v3 q = v3_madd(p, UP, -support);
    double c = support < w->r ? world_clearance_outside(w, q, w->r) : world_clearance_in(w, q, 1, w->r, NULL, NULL);
    return c < w->r * (1.0 - 1e-3);
}

/* Slides the sphere from *S along D (hugging). Sets *crawl on landing on
 * the ground or an upward face, *ground when it touches the ground. */
static void slide(const roots_world *w, v3 *S, v3 D, int *crawl, int *ground) {
    for (int it = 0; it < 4; it++) {
        v3 n;
        int which;
        double t = world_trace(w, *S, D, &n, &which);
        *S = v3_madd(*S, D, t);
        if (t >= 1.0) return;
        if (which == -1 || n.z > 0.5) *crawl = 1;
        if (which == -1) *ground = 1;
        D = v3_scale(D, 1.0 - t);
        double dn = v3_dot(D, n);
        if (dn < 0) D = v3_madd(D, n, -dn);
        if (v3_len2(D) < 1e-24) return;
    }
}

void roots_grow_mains(roots_net *net, const banyan_roots_params *p) {
    const roots_world *w = &net->w;
    const double u = net->u, r = net->r, two_pi = 2.0 * BANYAN_PI;
    const int N = net->N, B = net->B;
    pcg32 shared;
    pcg32_seed(&shared, p->seed, STREAM_SHARED);
    double rot = rng_range(&shared, 0.0, two_pi); /* one rotation shared by all main roots */
    double fwd_lo = p->forward_min * u, fwd_hi = p->forward_max * u, lat = p->lateral * u;
    double max_step = sqrt(fwd_hi * fwd_hi + lat * lat);
    /* A stopped paper-mode root rests up to one move above what it hit. */
    double support = p->hugging ? 0.5 * r : (max_step > 0.5 * r ? max_step : 0.5 * r);
    double hug_range = p->hug_range * r;
    /* Nearest-host queries only matter within this (exact for boxes at any
     * distance; a mesh is only searched this far). */
    double look = hug_range + max_step;
    /* A face whose normal points further down than this lets a root go:
     * with soil_entry roots follow an overhang's underside down to the
     * ground (a rock's, a face's brow) and only a near-flat ceiling drops
     * them; without, any face steeper than 60 degrees past vertical. */
    const double overhang = p->soil_entry ? -0.95 : -0.5;

    for (int a = 0; a < N; a++) {
        pcg32 g;
        pcg32_seed(&g, p->seed, (uint64_t)STREAM_MAIN + (uint64_t)a);
        double ang = rot + two_pi * a / N;
        v3 head = v3_make(dm_cos(ang), dm_sin(ang), 0);
        v3 S = v3_madd(net->G, head, p->start_radius * u);
        world_push_out(w, &S);
        v3 *M = net->M_grown + (size_t)a * B;
        M[0] = S;
        int crawl = 0, ground = 0;
        net->soil_b[a] = B;
        int pressed = 0; /* hugging: the last move ended pressed against a host */
        int cached = 0;  /* hc, hn0, hw hold the nearest host of the current S */
        double hc = 0;
        v3 hn0 = UP;
        int hw = -2;
        for (int b = 1; b < B; b++) {
            if (roots_stop(net)) return;
            for (int i = 0; i < p->moves; i++) {
                v3 V = v3_make(S.x - net->G.x, S.y - net->G.y, 0.0); /* S - Lambda */
                int hugged = 0; /* a host face lies within hug_range before the move */
                v3 hn = UP;
                if (p->hugging && !crawl) {
                    if (!cached) hc = world_clearance_in(w, S, 0, look, &hn0, &hw);
                    int which = hw;
                    double c = hc;
                    hn = hn0;
                    hugged = which >= 0 && hn.z > overhang && (c < hug_range || (pressed && c < hug_range + max_step));
                    /* Keep only the part of S - Lambda across the face: along
                     * the face it would herd every root onto the box's
                     * vertical edges. */
                    if (hugged) V = v3_scale(hn, v3_dot(V, hn) > 0 ? v3_dot(V, hn) : 0.0);
                }
                /* Soil entry's fig: a root hanging free (no host face near,
                 * nothing under it) hangs, as aerial roots do, instead of
                 * flying outward like an umbrella. */
                if (p->soil_entry && !crawl && !hugged) V = v3_scale(v3_norm_or(V, head), ROOTS_HANG * p->descent);
                if (!crawl) V.z -= p->descent;
                if (hugged && p->hug_pull > 0) {
                    /* Down projected onto the face's plane. */
                    v3 down = v3_make(hn.x * hn.z, hn.y * hn.z, -1.0 + hn.z * hn.z);
                    double lv = v3_len(V);
                    V = v3_madd(V, down, p->hug_pull * (lv > r ? lv : r));
                }
                v3 Vn = v3_norm_or(V, crawl ? head : v3_neg(UP));
                v3 L = v3_cross(Vn, UP);
                if (v3_len2(L) < 1e-18) L = v3_cross(head, UP);
                double f = rng_range(&g, fwd_lo, fwd_hi), l = rng_range(&g, -lat, lat);
                if (ground) {
                    /* On the ground the roots slow down (real ones enter the
                     * soil), so the net stays near the host. */
                    f *= p->ground_step;
                    l *= p->ground_step;
                }
                v3 D = v3_add(v3_scale(Vn, f), v3_scale(L, l));
                if (!p->hugging) {
                    v3 n;
                    int which;
                    double t = world_trace(w, S, D, &n, &which);
                    if (t < 1.0) {
                        /* The paper: stop at the last position that touched nothing. */
                        if (which == -1 || n.z > 0.5) crawl = 1;
                        if (which == -1) ground = 1;
                        break;
                    }
                    S = v3_add(S, D);
                } else {
                    slide(w, &S, D, &crawl, &ground);
                }
                if (p->soil_entry && w->ground && ground) break; /* into the soil here */
                if (crawl && !supported(w, S, support)) crawl = 0;
                if (p->hugging) {
                    v3 n;
                    int which;
                    double c = world_clearance_in(w, S, 0, look, &n, &which);
                    if (!crawl && (hugged || pressed) && which >= 0 && c > r && c < hug_range + max_step &&
                        n.z > overhang) {
                        /* Back to distance r from the host it was pressed
                         * against, however far the move (or a step off an
                         * edge) took it: this wraps edges. */
                        v3 pull = v3_scale(n, -(c - r));
                        /* The pull stays in the free ball of radius c round S
                         * (c is exact: below look), so it keeps r from every
                         * host; only the ground can stop it. From a mesh's
                         * nearest point q, S = q + c n, so a full pull ends
                         * at exactly r from q: the clearance is r, same
                         * normal and host, with no query. (Boxes keep their
                         * traces and queries, and their bytes.) */
                        int on_mesh = which >= (int)w->n_hosts;
                        v3 n0 = n;
                        int w0 = which;
                        double t = world_trace_ex(w, S, pull, on_mesh, &n, &which);
                        S = v3_madd(S, pull, t);
                        if (on_mesh && t >= 1.0) {
                            c = r;
                            n = n0;
                            which = w0;
                        } else {
                            c = world_clearance_in(w, S, 0, look, &n, &which);
                        }
                    }
                    pressed = which >= 0 && c < hug_range;
                    hc = c;
                    hn0 = n;
                    hw = which;
                    cached = 1;
                }
            }
            M[b] = S;
            if (w->ground && S.z - w->ground_z <= r * (1.0 + 1e-6)) ground = 1;
            if (p->soil_entry && w->ground && ground) {
                net->soil_b[a] = b;
                soil_end(net, p, a, S, head);
                for (int c = b + 1; c < B; c++) M[c] = S;
                break;
            }
        }
        net->ground_hit[a] = ground;
        if (prog_at(net->prog, ROOTS_AT_MAINS * (a + 1) / N)) return; /* cancelled */
    }
}
