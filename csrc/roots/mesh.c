/* The tube mesh of the net (spec roots.md 5), through the shared sweeper
 * (tube_frames + tube_sweep_rings): rings of n vertices on
 * rotation-minimising frames, joined by quads, both ends capped.
 *
 * Junction smoothing of a first branch root: its first ring becomes an
 * elongated loop round M(a,b-3) and M(a,b+2) (half the vertices round
 * each centre), its last ring a loop round M(a+1,b-2) and M(a+1,b+2); the
 * rings between blend from the loops to the round ring of radius r,
 * reaching it at the branch's middle. The spec splits the ring by index
 * (upper half round M(a,b-3)); here each vertex goes round the centre on
 * its side of the line between the two centres, which is the same for a
 * vertical main root and stays a convex loop when the main root runs
 * sideways. Every ring vertex that would enter a host or the ground is
 * pressed onto its surface. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "mesh/tube.h"
#include "mesh/wind.h"
#include "roots_internal.h"

static const v3 UP = {0, 0, 1};

typedef struct work {
    int sides;
    double *cs, *sn;      /* cos, sin of ring angles */
    v3 *T, *N;            /* frames, per point */
    v3 *rings, *normals;  /* per point * sides */
    double *arc;          /* arc length per point */
    double *extent;       /* per point: the farthest ring vertex from the centre */
    double *rad;          /* per point: the ring radius (net->rad, eased at tight bends) */
    v3 *ls, *le, *ds, *de;/* loop offsets from the end point and loop directions, world */
    unsigned char *clear; /* per point: unfold_rings' pairs known not to fold */
} work;

/* Loop for one end of a first branch root: for every ring direction d of
 * the frame at P, the point of the stadium round C1 and C2 (radius rl) in
 * that direction, stored as a world offset from P and a unit direction.
 * The spec stands the loop in the vertical plane across the heading gamma;
 * here it stands in the ring's own plane (across the branch's tangent),
 * with C1 and C2 projected into it. For a branch leaving horizontally, as
 * the spec pictures it, the two planes are the same; for one that leaves
 * steeply, a loop in the vertical plane would lie along the tube and turn
 * it inside out. The rings towards the middle blend these world offsets
 * (not frame-relative ones), so the thick part keeps lying along the main
 * root instead of turning with the branch. */
static void end_loop(work *wk, v3 P, v3 T, v3 N, v3 C1, v3 C2, double rl, v3 *off, v3 *dir) {
    v3 Bv = v3_cross(T, N);
    C1 = v3_madd(C1, T, -v3_dot(v3_sub(C1, P), T));
    C2 = v3_madd(C2, T, -v3_dot(v3_sub(C2, P), T));
    v3 e = v3_sub(C1, C2);
    for (int j = 0; j < wk->sides; j++) {
        v3 d = v3_add(v3_scale(N, wk->cs[j]), v3_scale(Bv, wk->sn[j]));
        v3 C = v3_dot(d, e) >= 0 ? C1 : C2;
        v3 o = v3_sub(v3_madd(C, d, rl), P);
        /* In the frame's own coordinates: applied in each ring's frame, the
         * loop stays in order however far the branch turns (a world offset
         * projected onto a ring across it flattens and folds). */
        off[j] = v3_make(v3_dot(o, N), v3_dot(o, Bv), 0);
        dir[j] = v3_make(v3_dot(d, N), v3_dot(d, Bv), 0);
    }
}

static v3 clamp_reach(v3 from, v3 to, double reach) {
    v3 d = v3_sub(to, from);
    double l = v3_len(d);
    return l > reach ? v3_madd(from, d, reach / l) : to;
}

/* Ring i of a junction-smoothed first branch root: the round ring of
 * radius rad blended with the start loop (weight ws) and the end loop (we). */
static void junction_ring(work *wk, v3 Pi, uint32_t i, double ws, double we, double rad) {
    int sides = wk->sides;
    if (ws < 1e-4) ws = 0; /* below a hundredth of a millimetre at r = 4 cm */
    if (we < 1e-4) we = 0;
    double wr = 1.0 - ws - we;
    v3 T = wk->T[i], N = wk->N[i], Bv = v3_cross(T, N);
    v3 *ring = wk->rings + (size_t)i * sides, *nr = wk->normals + (size_t)i * sides;
    for (int j = 0; j < sides; j++) {
        v3 dir = v3_add(v3_scale(N, wk->cs[j]), v3_scale(Bv, wk->sn[j]));
        if (ws == 0 && we == 0) { /* round */
            ring[j] = v3_madd(Pi, dir, rad);
            nr[j] = dir;
            continue;
        }
        v3 o = v3_scale(dir, wr * rad), d = v3_scale(dir, wr);
        /* Loop offsets in the ring's plane only: along the tangent
         * they would slide rings past each other. */
        if (ws > 0) {
            v3 lo = wk->ls[j], ld = wk->ds[j];
            o = v3_madd(o, v3_add(v3_scale(N, lo.x), v3_scale(Bv, lo.y)), ws);
            d = v3_madd(d, v3_add(v3_scale(N, ld.x), v3_scale(Bv, ld.y)), ws);
        }
        if (we > 0) {
            v3 lo = wk->le[j], ld = wk->de[j];
            o = v3_madd(o, v3_add(v3_scale(N, lo.x), v3_scale(Bv, lo.y)), we);
            d = v3_madd(d, v3_add(v3_scale(N, ld.x), v3_scale(Bv, ld.y)), we);
        }
        ring[j] = v3_add(Pi, o);
        nr[j] = d; /* normalised below only where the outline's fails */
    }
    if (ws == 0 && we == 0) return;
    /* Normals from the loop's own outline (counter-clockwise about T),
     * so they agree with the faces however the blend bends it. */
    for (int j = 0; j < sides; j++) {
        v3 tj = v3_sub(ring[j + 1 < sides ? j + 1 : 0], ring[j ? j - 1 : sides - 1]), c = v3_cross(tj, T);
        double l = v3_len(c);
        nr[j] = l > 1e-300 ? v3_scale(c, 1.0 / l)
                           : v3_norm_or(nr[j], v3_add(v3_scale(N, wk->cs[j]), v3_scale(Bv, wk->sn[j])));
    }
}

/* Rings of a first branch root with junction smoothing; also their
 * normals. */
static void junction_rings(work *wk, const roots_net *net, const banyan_roots_params *p, const roots_poly *pl) {
    const v3 *P = net->pts + pl->off;
    uint32_t n = pl->n;
    int sides = wk->sides, B = net->B;
    int b = roots_branch_b(p, pl->k), a2 = (pl->a + 1) % net->N;
    int be = roots_branch_end_b(net, p, pl->a * net->nb + pl->k);
#define MAT(a, i) net->M[(size_t)(a) * B + ((i) < 0 ? 0 : ((i) >= B ? B - 1 : (i)))]
    v3 C1 = MAT(pl->a, b - 3), C2 = MAT(pl->a, b + 2), E1 = MAT(a2, be - 2), E2 = MAT(a2, be + 2);
#undef MAT
    /* Growth points lie several r apart; on a root crawling over the ground
     * five of them make a sheet metres long, so the loop's reach is capped. */
    double reach = p->junction_reach * net->r;
    C1 = clamp_reach(P[0], C1, reach);
    C2 = clamp_reach(P[0], C2, reach);
    E1 = clamp_reach(P[n - 1], E1, 0.8 * reach);
    E2 = clamp_reach(P[n - 1], E2, 0.8 * reach);
    double L = wk->arc[n - 1], half = 0.5 * L;
    end_loop(wk, P[0], wk->T[0], wk->N[0], C1, C2, net->r * p->junction_start_scale, wk->ls, wk->ds);
    end_loop(wk, P[n - 1], wk->T[n - 1], wk->N[n - 1], E1, E2, net->r * p->junction_end_scale, wk->le, wk->de);
    for (uint32_t i = 0; i < n; i++) {
        double s = wk->arc[i];
        double ws = half > 0 && s < half ? dm_pow(1.0 - s / half, p->junction_falloff) : 0.0;
        double we = half > 0 && L - s < half ? dm_pow(1.0 - (L - s) / half, p->junction_falloff) : 0.0;
        if (i == 0) ws = 1.0, we = 0.0;
        if (i == n - 1) we = 1.0, ws = 0.0;
        double rad = wk->rad[i];
        v3 *ring = wk->rings + (size_t)i * sides;
        junction_ring(wk, P[i], i, ws, we, rad);
        double e2 = rad * rad;
        for (int j = 0; j < sides; j++) {
            double l2 = v3_len2(v3_sub(ring[j], P[i]));
            if (l2 > e2) e2 = l2;
        }
        wk->extent[i] = sqrt(e2);
    }
}

/* Ring radii that keep a bend's inside from folding: rings i and i+1 on
 * a segment of length d, tilted by half their turning angles, meet on the
 * inside once R_i tan(th_i / 2) + R_i+1 tan(th_i+1 / 2) > d. So each ring
 * is kept to 0.45 d / tan(th / 2) of its shorter segment (not below
 * `floor`). Only the tubes: the fused surface has no rings to fold. */
static void ease_bends(double *out, const v3 *P, const double *rad, uint32_t n, double floor) {
    for (uint32_t i = 0; i < n; i++) {
        out[i] = rad[i];
        if (i == 0 || i + 1 == n) continue;
        v3 a = v3_sub(P[i], P[i - 1]), b = v3_sub(P[i + 1], P[i]);
        double la = v3_len(a), lb = v3_len(b);
        if (la < 1e-12 || lb < 1e-12) continue;
        double c = v3_dot(a, b) / (la * lb);
        if (c > 0.9999) continue;
        if (c < -1) c = -1;
        /* tan(th / 2) = sqrt((1 - c) / (1 + c)) (>= the clamped one below):
         * a ring well inside that bound is left without acos and tan. */
        double m = la < lb ? la : lb;
        if (c > -0.999 && out[i] * (1.0 + 1e-6) < 0.45 * m * sqrt((1.0 + c) / (1.0 - c))) continue;
        double th = dm_acos(c), lim = 0.45 * (la < lb ? la : lb) / dm_tan(0.5 * (th < 3.0 ? th : 3.0));
        if (lim < floor) lim = floor;
        if (out[i] > lim) out[i] = lim;
    }
}

/* 1 when a triangle of the sweep between rings a and b faces against
 * its vertex normals. */
static int ring_folds(const v3 *a, const v3 *b, const v3 *na, const v3 *nb, int sides) {
    for (int j = 0; j < sides; j++) {
        int k = j + 1 < sides ? j + 1 : 0;
        v3 p00 = a[j], p01 = a[k], p10 = b[j], p11 = b[k];
        /* the sweep's two triangles: (p00, p01, p11) and (p00, p11, p10) */
        v3 e = v3_sub(p11, p00);
        v3 f1 = v3_cross(v3_sub(p01, p00), e), f2 = v3_cross(e, v3_sub(p10, p00));
        v3 n1 = v3_add(v3_add(na[j], na[k]), nb[k]), n2 = v3_add(v3_add(na[j], nb[k]), nb[j]);
        /* facing tested first: the sizes only for the rare one against */
        if ((v3_dot(f1, n1) <= 0 && v3_len2(f1) > 1e-24) || (v3_dot(f2, n2) <= 0 && v3_len2(f2) > 1e-24)) return 1;
    }
    return 0;
}

/* One step of unfold_rings: each vertex a quarter of the way in, if free.
 * With boxes and the ground only (exact distances), a vertex closer to
 * the centre c than c's clearance *cc (asked once per ring, < 0 until
 * then) is free without a query. */
static void shrink_ring(v3 *ring, const roots_world *w, v3 c, int sides, double *cc) {
    if (!w->n_meshes && *cc < 0) *cc = world_clearance_in(w, c, 1, HUGE_VAL, NULL, NULL);
    double sure = w->n_meshes ? -1.0 : *cc - 1e-9 * w->r; /* rounding's margin */
    for (int j = 0; j < sides; j++) {
        v3 q = v3_lerp(c, ring[j], 0.75);
        if ((sure > 0 && v3_dist(q, c) < sure) || world_clearance_in(w, q, 1, w->r, NULL, NULL) >= 0) ring[j] = q;
    }
}

/* Rings that fold the tube back over the ring before them (a tight bend,
 * a wide junction loop, a ring pressed flat) shrink towards their centre,
 * a quarter at a time, as far as the hosts let each vertex go. */
static void unfold_rings(work *wk, const roots_world *w, const v3 *P, uint32_t n) {
    int sides = wk->sides, any = 0;
    /* clear[i]: the pair (i - 1, i) is known not to fold once ring i is
     * done (so the backward pass need not test it again unless ring i
     * changes there). */
    unsigned char *clear = wk->clear;
    clear[0] = 1;
    for (uint32_t i = 1; i < n; i++) {
        v3 *ring = wk->rings + (size_t)i * sides, *nr = wk->normals + (size_t)i * sides;
        const v3 *prev = ring - sides, *np = nr - sides;
        clear[i] = 1;
        if (!ring_folds(prev, ring, np, nr, sides)) continue;
        any = 1;
        int folds = 1;
        double cc = -1;
        for (int tries = 0; tries < 6 && folds;) {
            shrink_ring(ring, w, P[i], sides, &cc);
            folds = ++tries < 6 ? ring_folds(prev, ring, np, nr, sides) : -1; /* -1: not tested */
        }
        if (folds && ring_folds(prev, ring, np, nr, sides)) {
            clear[i] = 0;
            /* Still folded (a loop bent over itself): a small round ring
             * across the segment, its vertices in the same directions. */
            v3 t = v3_norm_or(v3_sub(P[i], P[i - 1]), v3_make(0, 0, 1));
            double rad = 0.5 * wk->rad[i], c = world_clearance_in(w, P[i], 1, rad, NULL, NULL);
            if (rad > 0.95 * c) rad = 0.95 * c; /* stays out of the hosts */
            for (int j = 0; j < sides; j++) {
                v3 d = v3_sub(ring[j], P[i]);
                d = v3_norm_or(v3_madd(d, t, -v3_dot(d, t)), nr[j]);
                ring[j] = v3_madd(P[i], d, rad);
                nr[j] = d;
            }
        }
    }
    /* Then backwards: a wide ring before a narrow one shrinks too (only
     * in a tube that had folds: most have none). */
    int next_moved = 0; /* ring i + 1 shrank in this pass */
    for (uint32_t i = any ? n - 1 : 0; i-- > 0;) {
        v3 *ring = wk->rings + (size_t)i * sides, *nr = wk->normals + (size_t)i * sides;
        const v3 *next = ring + sides, *nn = nr + sides;
        int moved = 0;
        double cc = -1;
        if (!clear[i + 1] || next_moved)
            for (int tries = 0; tries < 6 && ring_folds(ring, next, nr, nn, sides); tries++) {
                shrink_ring(ring, w, P[i], sides, &cc);
                moved = 1;
            }
        next_moved = moved;
    }
}

/* Ring vertices that a bend's stretch or a junction loop put inside a host
 * or under the ground go onto its surface: the tube flattens against the
 * bark instead of entering it (onto a mesh: back along the spoke from the
 * ring's free centre). A ring whose centre is farther from every obstacle
 * than its widest vertex is left alone, which is most. */
static void press_rings(work *wk, const roots_world *w, const v3 *P, uint32_t n) {
    int sides = wk->sides;
    for (uint32_t i = 0; i < n; i++) {
        v3 *ring = wk->rings + (size_t)i * sides;
        /* Obstacles within reach of the ring, and per vertex the tangent-
         * plane bound c + n.o, exact for the ground and for a face (for a
         * mesh the Lipschitz bound c - |o|). (A ring of radius r round a
         * centre r from a face just touches it: 1e-6 r of slack keeps
         * those out.) */
        enum { CAP = 8 };
        double oc[CAP];
        v3 on[CAP];
        int k = world_near(w, P[i], wk->extent[i] * (1.0 + 1e-9) - 1e-6 * w->r, oc, on, CAP);
        if (k == 0) continue;
        int all = k == CAP; /* more obstacles than we track: test every vertex */
        for (int j = 0; j < sides; j++) {
            v3 q = ring[j], o = v3_sub(q, P[i]);
            int maybe = all;
            for (int t = 0; t < k && !maybe; t++) maybe = world_near_bound(oc[t], on[t], o) < 1e-6 * w->r;
            if (!maybe) continue;
            /* Meshes: back along the spoke from the free centre to the
             * first surface it crosses (one ray; the Lipschitz bound above
             * leaves many vertices to look at). */
            if (w->n_meshes) q = world_spoke(w, P[i], q);
            /* Boxes and the ground only: world_clearance has the sign of
             * world_clearance_boxes, so one query serves both. */
            v3 nrm;
            int which;
            double d = w->n_meshes ? world_clearance_boxes(w, q) : world_clearance(w, q, &nrm, &which);
            if (d >= 0) {
                ring[j] = q;
                continue;
            }
            for (int it = 0; it < 4; it++) {
                if (it || w->n_meshes) d = world_clearance(w, q, &nrm, &which);
                if (d >= 0) break;
                /* onto a mesh's surface the sign is a coin toss: a hair beyond */
                q = v3_madd(q, nrm, -d + (which >= (int)w->n_hosts ? w->eps : 0.0));
            }
            if (d < 0) {
                /* A sharp wedge between two obstacles: the farthest free
                 * point between the ring's centre (free) and the vertex. */
                double lo = 0, hi = 1;
                for (int it = 0; it < 30; it++) {
                    double m = 0.5 * (lo + hi);
                    if (world_clearance_in(w, v3_lerp(P[i], ring[j], m), 1, w->r, NULL, NULL) >= 0) lo = m;
                    else hi = m;
                }
                q = v3_lerp(P[i], ring[j], lo);
            }
            ring[j] = q;
        }
    }
}

banyan_status roots_net_mesh(const roots_net *net, const banyan_roots_params *p, banyan_mesh **out,
                             banyan_roots_stats *stats, banyan_error *err) {
    if (p->surface == BANYAN_ROOTS_FUSED) return roots_net_mesh_fused(net, p, out, stats, err);
    const int sides = p->sides;
    uint64_t total_v = 0, total_i = 0;
    uint32_t longest = 2;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2) continue;
        uint32_t v, i;
        tube_counts(pl->n, sides, 1, 1, &v, &i);
        total_v += v;
        total_i += i;
        if (pl->n > longest) longest = pl->n;
    }
    if (total_v > (uint64_t)p->max_vertices)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the roots mesh needs %llu vertices, more than max_vertices = %d; raise max_vertices or "
                           "lower sides, growth_points or main_roots",
                           (unsigned long long)total_v, p->max_vertices);
    if (total_v == 0) return banyan_fail(err, BANYAN_E_INTERNAL, "the roots net has no tube to sweep");

    work wk;
    memset(&wk, 0, sizeof wk);
    wk.sides = sides;
    size_t nr = (size_t)longest * sides;
    void *block = malloc(sizeof(double) * 2 * sides + sizeof(v3) * 2 * longest + sizeof(v3) * 2 * nr +
                         sizeof(double) * 3 * longest + sizeof(v3) * 4 * sides + longest);
    if (!block) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the roots mesh workspace");
    wk.cs = block;
    wk.sn = wk.cs + sides;
    wk.T = (v3 *)(wk.sn + sides);
    wk.N = wk.T + longest;
    wk.rings = wk.N + longest;
    wk.normals = wk.rings + nr;
    wk.ls = wk.normals + nr;
    wk.ds = wk.ls + sides;
    wk.le = wk.ds + sides;
    wk.de = wk.le + sides;
    wk.arc = (double *)(wk.de + sides);
    wk.extent = wk.arc + longest;
    wk.rad = wk.extent + longest;
    wk.clear = (unsigned char *)(wk.rad + longest);
    for (int j = 0; j < sides; j++) {
        /* Half-step offset: each half of a junction loop is symmetric. */
        double ang = 2.0 * BANYAN_PI * (j + 0.5) / sides;
        wk.cs[j] = dm_cos(ang);
        wk.sn[j] = dm_sin(ang);
    }

    roots_wind rw;
    if (roots_wind_build(net, p, &rw)) {
        free(block);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the roots' wind attributes");
    }
    mesh_builder mb;
    int a_kind, a_id;
    wind_slots ws;
    roots_mesh_init(&mb, p, &a_kind, &a_id, &ws);
    mb_reserve(&mb, (uint32_t)total_v, (uint32_t)total_i);

    for (uint32_t t = 0; t < net->n_poly && !mb.status; t++) {
        if (prog_at(net->prog, ROOTS_AT_MESH + (1.0 - ROOTS_AT_MESH) * t / net->n_poly)) {
            free(block);
            roots_wind_free(&rw);
            mb_free(&mb);
            return prog_fail(net->prog, err, "roots mesh");
        }
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2) continue;
        const v3 *P = net->pts + pl->off;
        mb_set_attr(&mb, a_kind, pl->kind);
        mb_set_attr(&mb, a_id, pl->id);
        /* stiffness and birth ring by ring after the sweep */
        wind_set(&mb, &ws, rw.pivot[t], roots_wind_level(pl->kind), 1.0, rw.phase[t], 0.0);
        int smooth = pl->kind == ROOT_FIRST && p->smoothing;
        v3 first_normal = v3_make(0, 0, 0);
        if (smooth) {
            /* Start the frames in the loop's plane: horizontal, across the heading. */
            v3 h = v3_make(P[pl->n - 1].x - P[0].x, P[pl->n - 1].y - P[0].y, 0);
            v3 d0 = v3_sub(P[1], P[0]);
            if (v3_dot(h, d0) < 0) h = v3_neg(h);
            first_normal = v3_cross(UP, h);
        }
        tube_frames(P, pl->n, first_normal, wk.T, wk.N);
        ease_bends(wk.rad, P, net->rad + pl->off, pl->n, 0.25 * net->r);
        /* Both ring kinds come with their normals. */
        tube_opts o = {sides, 1, 1, {0, 0, 0}, 0.0, wk.normals, 1, 1}; /* pressed rings: arc-length uvs */
        if (smooth) {
            wk.arc[0] = 0;
            for (uint32_t i = 1; i < pl->n; i++) wk.arc[i] = wk.arc[i - 1] + v3_dist(P[i], P[i - 1]);
            junction_rings(&wk, net, p, pl);
        } else {
            /* Round rings (spec 5 "Rings"). */
            tube_round_rings(P, wk.rad, pl->n, wk.T, wk.N, wk.cs, wk.sn, sides, wk.rings, wk.normals,
                             wk.extent);
        }
        /* A root entering the soil goes below the ground: only the hosts press it. */
        roots_world soil_w = roots_soil_world(&net->w);
        press_rings(&wk, pl->soil_from < pl->n ? &soil_w : &net->w, P, pl->n);
        /* Round rings are eased at bends already (ease_bends): only junction
         * loops are checked ring by ring, which costs as much as the sweep. */
        if (smooth) unfold_rings(&wk, pl->soil_from < pl->n ? &soil_w : &net->w, P, pl->n);
        uint32_t first = mb.nv;
        tube_sweep_rings(&mb, P, wk.rings, pl->n, &o);
        wind_tube_rings(&mb, first, pl->n, sides, 1, 1, ws.stiffness, rw.stiff + pl->off);
        wind_tube_rings(&mb, first, pl->n, sides, 1, 1, ws.birth, rw.birth + pl->off);
    }
    roots_wind_free(&rw);

    if (roots_mesh_skeleton(&mb, net, p)) {
        free(block);
        mb_free(&mb);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the roots skeleton");
    }
    free(block);
    uint32_t nv = mb.nv, ni = mb.ni;
    banyan_status s = mb_finish(&mb, out, err);
    if (s == BANYAN_OK && stats) {
        stats->vertices = nv;
        stats->triangles = ni / 3;
    }
    return s;
}
