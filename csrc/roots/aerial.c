/* Aerial roots (docs/roots.md "Aerial roots"): a fig drops thin roots
 * that hang free in tassels (reference/plants.md, Fig: hanging roots 3-20
 * mm across, tens of them on a mature tree); those that reach the soil
 * root there. Here round(aerial_roots maturity) threads hang from sites on
 * the sideways-running roots of the net, 1 to 4 a site, each a ROOT_AERIAL
 * polyline: the net point it hangs from, the point where it leaves the
 * root's surface (out and down from the host), then points every
 * AERIAL_STEP straight down with a slight sway. A thread hangs clear of
 * everything: of the hosts by 1.5 r (past where the wind counts a root
 * as held), of the ground by r, of the
 * fused surface by its radius and a margin, and of the other threads.
 * Where a root or a plank lies below, it slides out from the host over it
 * (up to AERIAL_SLIDE) and hangs on from there; where it cannot, its tip
 * ends in the air. Radii are drawn log-uniform in 1.5-10 mm, thinning a
 * third to a free tip. Some threads (0.2 + 0.3 maturity of them) run on to
 * the ground and into the soil; the others end 0.2-0.8 of the way down.
 *
 * The clearance from the fused surface is the fused field itself
 * (capsule.h: the same capsules, per polyline their minimum, merged by
 * the smooth minimum), so a thread hangs a few millimetres off the bark
 * however the roots flatten and fuse. As tubes (surface = tubes) it is
 * the round capsules: fuse_radius and voxel_size change nothing there. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "capsule.h"
#include "hosts/closest.h"
#include "mesh/tube.h"
#include "mesh/wind.h"

/* m between a thread's points, and the most it slides out over a root. */
#define AERIAL_STEP 0.08
#define AERIAL_SLIDE 0.4
#define AERIAL_MAX_PTS 160
#define AERIAL_MAX_THREADS 200
/* A thread keeps this far (times r) from the hosts: hanging free, past
 * where the wind counts a root as held by one (wind.c). */
#define AERIAL_HOST 1.5
/* A straight run keeps a point every AERIAL_SPAN at most, and points off
 * the chord by AERIAL_FLAT. */
#define AERIAL_SPAN 0.36
#define AERIAL_FLAT 0.002
/* Thread radius range, m (log-uniform). */
#define AERIAL_R_LO 0.0015
#define AERIAL_R_HI 0.010
/* Room between a thread and the fused field's zero, besides its radius:
 * the surface's snap and marching error (0.25 voxel) and 3 mm. */
#define AERIAL_GAP_VOXELS 0.25
#define AERIAL_GAP 0.003
/* As tubes: the room past the round capsules (times r). */
#define AERIAL_TUBE_SLACK 0.1
/* A thread's first ring stops this far off the surface it leaves (m),
 * and the tube between it and the next ring half as far: out of reach of
 * a 0.5 mm "sheets nearly touching" test, far below what a render
 * shows. */
#define AERIAL_TOUCH 0.0012

typedef struct aerial {
    roots_net *net;
    const banyan_roots_params *p;
    roots_world soil;     /* the hosts without the ground */
    pcg32 rng;
    capsule *caps;        /* the net's capsules before the threads, in polyline order */
    uint32_t n_caps;
    v3 *cap_lo, *cap_hi;  /* per capsule: bounds of its axis */
    double *cap_reach;    /* per capsule: the farthest its surface lies from the axis */
    /* A grid over the capsules: cell c lists (in capsule order) those
     * whose surface comes within near of it: the field is exact up to
     * near - k (twice the most room a thread asks), a lower bound beyond. */
    double near;
    v3 g_lo;
    double g_cell;
    int32_t g_n[3];
    uint32_t *g_start, *g_items;
    v3 th_lo[AERIAL_MAX_THREADS], th_hi[AERIAL_MAX_THREADS]; /* bounds of the threads hung, with their radius */
    double k, margin;     /* the field's fillet; the gap a thread keeps besides its radius */
    uint32_t first_thread; /* the first aerial polyline */
    int id, oom;
    v3 pt[AERIAL_MAX_PTS];
    double rad[AERIAL_MAX_PTS];
    uint32_t n, soil_from;
} aerial;

/* min and max as plain compares (libm's fmin and fmax are calls here). */
static inline double dmin(double a, double b) { return a < b ? a : b; }
static inline double dmax(double a, double b) { return a > b ? a : b; }
static inline double v3_at(v3 a, int k) { return k == 0 ? a.x : k == 1 ? a.y : a.z; }

static double smin_d(double a, double b, double k) {
    double h = k - fabs(a - b);
    h = (h > 0 ? h : 0) / k;
    return (a < b ? a : b) - h * h * k * 0.25;
}

/* Distance from q to the box lo-hi. */
static double box_dist(v3 q, v3 lo, v3 hi) {
    double x = q.x < lo.x ? lo.x - q.x : (q.x > hi.x ? q.x - hi.x : 0);
    double y = q.y < lo.y ? lo.y - q.y : (q.y > hi.y ? q.y - hi.y : 0);
    double z = q.z < lo.z ? lo.z - q.z : (q.z > hi.z ? q.z - hi.z : 0);
    return sqrt(x * x + y * y + z * z);
}

/* Grid cell of q along axis k, clamped. */
static int32_t cell_of(const aerial *A, int k, double x) {
    int32_t c = (int32_t)floor((x - (k == 0 ? A->g_lo.x : k == 1 ? A->g_lo.y : A->g_lo.z)) / A->g_cell);
    return c < 0 ? 0 : (c >= A->g_n[k] ? A->g_n[k] - 1 : c);
}

/* The fused field at q (capsule.h, merged in polyline order), exact up
 * to near - k, a lower bound beyond. A capsule whose bound lies
 * past the polyline's minimum so far, or past the merged value by the
 * fillet (where the smooth minimum is the plain one), changes nothing. */
static double field_at(const aerial *A, v3 q) {
    double far = A->near - A->k;
    if (q.x < A->g_lo.x || q.y < A->g_lo.y || q.z < A->g_lo.z || q.x > A->g_lo.x + A->g_n[0] * A->g_cell ||
        q.y > A->g_lo.y + A->g_n[1] * A->g_cell || q.z > A->g_lo.z + A->g_n[2] * A->g_cell)
        return far;
    size_t c = ((size_t)cell_of(A, 0, q.x) * A->g_n[1] + cell_of(A, 1, q.y)) * A->g_n[2] + cell_of(A, 2, q.z);
    double acc = HUGE_VAL, pm = HUGE_VAL;
    uint32_t cur = UINT32_MAX;
    for (uint32_t j = A->g_start[c]; j < A->g_start[c + 1]; j++) {
        uint32_t ci = A->g_items[j];
        const capsule *cp = &A->caps[ci];
        if (cp->poly != cur) {
            if (cur != UINT32_MAX) acc = A->k > 0 ? smin_d(acc, pm, A->k) : dmin(acc, pm);
            cur = cp->poly, pm = HUGE_VAL;
        }
        if (box_dist(q, A->cap_lo[ci], A->cap_hi[ci]) - A->cap_reach[ci] >= dmin(pm, acc + A->k)) continue;
        double d = capsule_field(cp, q);
        if (d < pm) pm = d;
    }
    if (cur != UINT32_MAX) acc = A->k > 0 ? smin_d(acc, pm, A->k) : dmin(acc, pm);
    return acc < far ? acc : far;
}

/* Fills the grid (0 when out of memory): cells of about near,
 * at most about 4 million of them. */
static int build_grid(aerial *A) {
    v3 lo = v3_make(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi = v3_make(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
    for (uint32_t c = 0; c < A->n_caps; c++) {
        double e = A->cap_reach[c] + A->near;
        lo = v3_make(dmin(lo.x, A->cap_lo[c].x - e), dmin(lo.y, A->cap_lo[c].y - e), dmin(lo.z, A->cap_lo[c].z - e));
        hi = v3_make(dmax(hi.x, A->cap_hi[c].x + e), dmax(hi.y, A->cap_hi[c].y + e), dmax(hi.z, A->cap_hi[c].z + e));
    }
    if (!A->n_caps) lo = hi = v3_make(0, 0, 0);
    double cell = A->near, vol = (hi.x - lo.x + cell) * (hi.y - lo.y + cell) * (hi.z - lo.z + cell);
    if (vol / (cell * cell * cell) > 4e6) cell = dm_cbrt(vol / 4e6);
    A->g_lo = lo, A->g_cell = cell;
    A->g_n[0] = (int32_t)ceil((hi.x - lo.x) / cell) + 1;
    A->g_n[1] = (int32_t)ceil((hi.y - lo.y) / cell) + 1;
    A->g_n[2] = (int32_t)ceil((hi.z - lo.z) / cell) + 1;
    size_t cells = (size_t)A->g_n[0] * A->g_n[1] * A->g_n[2];
    A->g_start = calloc(cells + 1, sizeof(uint32_t));
    if (!A->g_start) return 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t c = 0; c < A->n_caps; c++) {
            double e = A->cap_reach[c] + A->near;
            int32_t i0 = cell_of(A, 0, A->cap_lo[c].x - e), i1 = cell_of(A, 0, A->cap_hi[c].x + e);
            int32_t j0 = cell_of(A, 1, A->cap_lo[c].y - e), j1 = cell_of(A, 1, A->cap_hi[c].y + e);
            int32_t k0 = cell_of(A, 2, A->cap_lo[c].z - e), k1 = cell_of(A, 2, A->cap_hi[c].z + e);
            for (int32_t i = i0; i <= i1; i++)
                for (int32_t j = j0; j <= j1; j++)
                    for (int32_t k = k0; k <= k1; k++) {
                        size_t at = ((size_t)i * A->g_n[1] + j) * A->g_n[2] + k;
                        if (pass == 0) A->g_start[at + 1]++;
                        else A->g_items[A->g_start[at]++] = c;
                    }
        }
        if (pass == 0) {
            for (size_t i = 0; i < cells; i++) A->g_start[i + 1] += A->g_start[i];
            A->g_items = malloc(sizeof(uint32_t) * (A->g_start[cells] ? A->g_start[cells] : 1));
            if (!A->g_items) return 0;
        }
    }
    for (size_t i = cells; i > 0; i--) A->g_start[i] = A->g_start[i - 1]; /* the fill moved every start on */
    A->g_start[0] = 0;
    return 1;
}

/* Least distance from segment a-b to the threads hung so far, less their
 * radius there (their first segments too, from inside the root they
 * leave). */
static double threads_at(const aerial *A, v3 a, v3 b) {
    const roots_net *net = A->net;
    double best = HUGE_VAL;
    v3 lo = v3_make(dmin(a.x, b.x), dmin(a.y, b.y), dmin(a.z, b.z));
    v3 hi = v3_make(dmax(a.x, b.x), dmax(a.y, b.y), dmax(a.z, b.z));
    for (uint32_t t = A->first_thread; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        uint32_t th = t - A->first_thread;
        double gx = dmax(dmax(A->th_lo[th].x - hi.x, lo.x - A->th_hi[th].x), 0);
        double gy = dmax(dmax(A->th_lo[th].y - hi.y, lo.y - A->th_hi[th].y), 0);
        double gz = dmax(dmax(A->th_lo[th].z - hi.z, lo.z - A->th_hi[th].z), 0);
        if (gx * gx + gy * gy + gz * gz >= best * best) continue;
        for (uint32_t i = 0; i + 1 < pl->n; i++) {
            const v3 *P = net->pts + pl->off + i;
            double d = sqrt(seg_seg_dist2(a, b, P[0], P[1])) - dmax(net->rad[pl->off + i], net->rad[pl->off + i + 1]);
            if (d < best) best = d;
        }
    }
    return best;
}

/* How much room a thread of radius tr has at q from the hosts, the fused
 * surface and the ground (< 0: none); a lower bound of it moves at most
 * as fast as q. */
static double room_at(const aerial *A, v3 q, double tr) {
    const roots_net *net = A->net;
    double room = field_at(A, q) - tr - A->margin;
    if (room < 0) return room;
    double host = world_clearance_in(&A->soil, q, 0, AERIAL_HOST * net->r + room, NULL, NULL) - AERIAL_HOST * net->r;
    if (host < room) room = host;
    if (net->w.ground && q.z - net->w.ground_z - net->r < room) room = q.z - net->w.ground_z - net->r;
    return room;
}

static int free_at(const aerial *A, v3 q, double tr) {
    return room_at(A, q, tr) >= 0 && threads_at(A, q, q) >= tr + AERIAL_GAP;
}

/* The segment a-b (a free) is free: the other threads exactly, the rest
 * by steps of the room left (at least 1 mm). */
static int free_seg(const aerial *A, v3 a, v3 b, double tr) {
    if (threads_at(A, a, b) < tr + AERIAL_GAP) return 0;
    double L = v3_dist(a, b), s = 0;
    v3 d = v3_scale(v3_sub(b, a), L > 0 ? 1.0 / L : 0);
    for (;;) {
        double room = room_at(A, v3_madd(a, d, s), tr);
        if (room < 0) return 0;
        if (s >= L) return 1;
        s = dmin(L, s + dmax(room, 0.001));
    }
}

/* The segment a-b into the soil keeps clear of the roots and the other
 * threads (not of the ground). */
static int free_into_soil(const aerial *A, v3 a, v3 b, double tr) {
    if (threads_at(A, a, b) < tr + AERIAL_GAP) return 0;
    for (int i = 1; i <= 16; i++)
        if (field_at(A, v3_lerp(a, b, i / 16.0)) < tr + A->margin) return 0;
    return 1;
}

/* Where a thread of radius tr hanging from net point `at` leaves its
 * root: along out-and-down from the host until it is free (0: never
 * within 6 R of the axis, or the way comes nearer than r to a host). */
static int leave_root(const aerial *A, uint32_t at, v3 o, v3 side, double tr, v3 *P1) {
    const roots_net *net = A->net;
    v3 P = net->pts[at];
    double R = net->rad[at];
    v3 d = v3_norm(v3_add(v3_add(v3_scale(o, 0.6), v3_make(0, 0, -1)), side));
    for (double s = 0.005; s <= 6.0 * R; s += 0.005) {
        v3 q = v3_madd(P, d, s);
        /* the way out keeps r from the hosts, as every root's segments do
         * (a root on a host's top would leave through its edge) */
        if (world_clearance_in(&A->soil, q, 0, net->r, NULL, NULL) < net->r) return 0;
        if (s < 0.5 * R || !free_at(A, q, tr)) continue;
        /* the part outside the root keeps clear of the other threads */
        for (double b = s - 0.005; b > 0; b -= 0.005) {
            v3 e = v3_madd(P, d, b);
            if (field_at(A, e) < -2.0 * tr) break;
            if (threads_at(A, e, e) < tr + AERIAL_GAP) return 0;
        }
        *P1 = q;
        return 1;
    }
    return 0;
}

/* Distance from q to the segment a-b. */
static double pt_seg(v3 q, v3 a, v3 b) {
    v3 ba = v3_sub(b, a);
    double l2 = v3_len2(ba), t = l2 > 0 ? v3_dot(v3_sub(q, a), ba) / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return v3_dist(q, v3_madd(a, ba, t));
}

/* Straight runs of A->pt keep fewer points: from each kept point the
 * next is the farthest whose chord passes within AERIAL_FLAT of the
 * points it skips, is at most AERIAL_SPAN long and is free. Points 0 and
 * 1 and the end in the soil stay. */
static void simplify(aerial *A, double tr) {
    const uint32_t last = A->soil_from < A->n ? A->soil_from - 1 : A->n - 1, n = A->n;
    uint32_t out = 2, k = 1;
    while (k < last) {
        uint32_t best = k + 1;
        for (uint32_t j = k + 2; j <= last && v3_dist(A->pt[k], A->pt[j]) <= AERIAL_SPAN; j++) {
            int flat = 1;
            for (uint32_t i = k + 1; i < j && flat; i++) flat = pt_seg(A->pt[i], A->pt[k], A->pt[j]) < AERIAL_FLAT;
            if (!flat) break;
            best = j;
        }
        while (best > k + 1 && !free_seg(A, A->pt[k], A->pt[best], tr)) best--;
        A->pt[out] = A->pt[best], A->rad[out] = A->rad[best];
        out++;
        k = best;
    }
    for (uint32_t i = last + 1; i < n; i++) A->pt[out] = A->pt[i], A->rad[out] = A->rad[i], out++;
    if (A->soil_from < n) A->soil_from = out - (n - A->soil_from);
    A->n = out;
    if (A->soil_from > A->n) A->soil_from = A->n;
}

/* Hangs one thread from net point `at` into A->pt (n = 0: none). */
static void hang(aerial *A, uint32_t at, v3 o, v3 along) {
    const roots_net *net = A->net;
    const double gz = net->w.ground ? net->w.ground_z : -HUGE_VAL;
    double tr = AERIAL_R_LO * dm_exp(dm_log(AERIAL_R_HI / AERIAL_R_LO) * rng_uniform(&A->rng));
    int rooted = net->w.ground && rng_uniform(&A->rng) < 0.2 + 0.3 * A->p->maturity;
    double frac = rng_range(&A->rng, 0.2, 0.8);
    v3 side = v3_scale(along, rng_range(&A->rng, -0.8, 0.8));
    double sx = 0, sy = 0;
    A->n = 0, A->soil_from = 0;
    v3 P1;
    if (!leave_root(A, at, o, side, tr, &P1)) return;
    double drop = net->w.ground ? P1.z - gz : 3.0;
    double len = rooted ? HUGE_VAL : frac * drop, hung = 0;
    A->pt[0] = net->pts[at], A->rad[0] = 1.5 * tr;
    A->pt[1] = P1, A->rad[1] = 1.3 * tr;
    A->n = 2;
    v3 q = P1;
    while (A->n + 1 < AERIAL_MAX_PTS && hung < len) {
        if (A->n == 2 || rng_uniform(&A->rng) < 0.1) { /* a new lean now and then */
            sx = rng_range(&A->rng, -0.06, 0.06);
            sy = rng_range(&A->rng, -0.06, 0.06);
        }
        v3 next = v3_madd(q, v3_norm(v3_make(sx, sy, -1)), AERIAL_STEP);
        if (rooted && next.z < gz + net->r) {
            /* into the soil beside the last point */
            v3 s = v3_make(q.x, q.y, gz - 0.03), m = q;
            if (world_clearance_in(&A->soil, s, 0, net->r, NULL, NULL) < net->r) break;
            if (q.z - gz > 0.12 && A->n + 2 < AERIAL_MAX_PTS) {
                m = v3_make(q.x, q.y, gz + 1.02 * net->r);
                if (!free_seg(A, q, m, tr)) break;
            }
            if (!free_into_soil(A, m, s, tr)) break;
            if (m.z != q.z) A->pt[A->n] = m, A->rad[A->n++] = tr;
            A->soil_from = A->n;
            A->pt[A->n] = s, A->rad[A->n++] = 1.2 * tr;
            simplify(A, tr);
            return;
        }
        int ok = free_seg(A, q, next, tr);
        for (double slide = 0.01; !ok && slide <= AERIAL_SLIDE;) {
            v3 t = v3_madd(next, o, slide);
            double room = room_at(A, t, tr);
            if (room < 0) { /* the field is about 1-Lipschitz: out by at least what is missing */
                slide += dmax(0.01, -room);
                continue;
            }
            ok = free_seg(A, q, t, tr);
            if (ok) next = t;
            slide += 0.01;
        }
        if (!ok) break; /* the tip ends here, in the air */
        hung += v3_dist(q, next);
        q = next;
        A->pt[A->n] = q, A->rad[A->n++] = tr;
    }
    if (A->n < 4) {
        A->n = 0;
        return;
    }
    A->soil_from = A->n;
    simplify(A, tr);
    /* a free tip thins a third towards its end, by length */
    double total = 0, s = 0;
    for (uint32_t i = 2; i < A->n; i++) total += v3_dist(A->pt[i], A->pt[i - 1]);
    for (uint32_t i = 2; i < A->n; i++) {
        s += v3_dist(A->pt[i], A->pt[i - 1]);
        A->rad[i] = tr * (1.0 - 0.33 * (total > 0 ? s / total : 0));
    }
}

/* Appends A->pt as an aerial polyline hanging from `at`. */
static void emit(aerial *A, uint32_t at, int a, int k) {
    roots_net *net = A->net;
    if (!roots_reserve_pts(net, A->n)) {
        A->oom = 1;
        return;
    }
    uint32_t off = net->n_pts;
    for (uint32_t i = 0; i < A->n; i++) net->pts[off + i] = A->pt[i], net->rad[off + i] = A->rad[i];
    net->n_pts += A->n;
    if (!roots_add_poly(net, off, A->n, ROOT_AERIAL, A->id++, a, k)) {
        A->oom = 1;
        return;
    }
    roots_poly *pl = &net->poly[net->n_poly - 1];
    pl->from = at;
    pl->soil_from = A->soil_from;
    uint32_t th = net->n_poly - 1 - A->first_thread;
    v3 lo = A->pt[0], hi = A->pt[0];
    double rmax = 0;
    for (uint32_t i = 0; i < A->n; i++) {
        v3 q = A->pt[i];
        lo = v3_make(dmin(lo.x, q.x), dmin(lo.y, q.y), dmin(lo.z, q.z));
        hi = v3_make(dmax(hi.x, q.x), dmax(hi.y, q.y), dmax(hi.z, q.z));
        rmax = dmax(rmax, A->rad[i]);
    }
    A->th_lo[th] = v3_make(lo.x - rmax, lo.y - rmax, lo.z - rmax);
    A->th_hi[th] = v3_make(hi.x + rmax, hi.y + rmax, hi.z + rmax);
}

/* Sites: interior points of the net's roots above ground that run
 * sideways (rise under 0.55 per unit length), at least 1 m and a quarter
 * of G's height up. */
static uint32_t *sites(const aerial *A, uint32_t *n_out) {
    const roots_net *net = A->net;
    uint32_t *s = malloc(sizeof(uint32_t) * (net->n_pts ? net->n_pts : 1)), n = 0;
    if (!s) return NULL;
    double gz = net->w.ground ? net->w.ground_z : net->G.z - 4.0;
    double zmin = gz + dmax(1.0, 0.25 * (net->G.z - gz));
    for (uint32_t t = 0; t < A->first_thread; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind == ROOT_FOOT) continue;
        for (uint32_t i = 1; i + 1 < pl->n && i + 1 < pl->soil_from; i++) {
            v3 a = net->pts[pl->off + i - 1], b = net->pts[pl->off + i + 1], q = net->pts[pl->off + i];
            double l = v3_dist(a, b);
            if (q.z < zmin || l <= 0 || fabs(b.z - a.z) > 0.55 * l) continue;
            s[n++] = pl->off + i;
        }
    }
    *n_out = n;
    return s;
}

banyan_status roots_grow_aerial(roots_net *net, const banyan_roots_params *p) {
    int want = (int)(p->aerial_roots * p->maturity + 0.5);
    if (want > AERIAL_MAX_THREADS) want = AERIAL_MAX_THREADS;
    if (want <= 0 || p->unit <= 0) return BANYAN_OK;
    aerial A = {0};
    A.net = net, A.p = p, A.soil = roots_soil_world(&net->w);
    A.first_thread = net->n_poly;
    /* The fused surface's field; the tubes are the plain round capsules
     * (their junction loops and bend widening reach a tenth of r past them). */
    const int fused = p->surface == BANYAN_ROOTS_FUSED;
    A.k = fused ? p->fuse_radius * net->r * (0.25 + 0.75 * p->maturity) : 0.0;
    A.margin = (fused ? AERIAL_GAP_VOXELS * p->voxel_size * net->r : AERIAL_TUBE_SLACK * net->r) + AERIAL_GAP;
    A.near = A.k + 2.0 * (AERIAL_R_HI + A.margin);
    pcg32_seed(&A.rng, p->seed, STREAM_AERIAL);
    A.id = roots_next_id(net);
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].n >= 2) A.n_caps += net->poly[t].n - 1;
    uint32_t n_sites = 0, *site = NULL;
    A.caps = malloc(sizeof(capsule) * (A.n_caps ? A.n_caps : 1));
    A.cap_lo = malloc(sizeof(v3) * 2 * (A.n_caps ? A.n_caps : 1));
    A.cap_reach = malloc(sizeof(double) * (A.n_caps ? A.n_caps : 1));
    if (A.caps && A.cap_lo && A.cap_reach) site = sites(&A, &n_sites);
    if (!site) {
        free(A.caps), free(A.cap_lo), free(A.cap_reach);
        return BANYAN_E_NOMEM;
    }
    A.cap_hi = A.cap_lo + A.n_caps;
    A.n_caps = 0;
    for (uint32_t t = 0; t < net->n_poly; t++)
        for (uint32_t i = 0; i + 1 < net->poly[t].n; i++) {
            capsule *c = &A.caps[A.n_caps];
            roots_capsule_set(c, net, p, t, net->poly[t].off + i);
            if (!fused) c->sq = 1.0, c->fn = v3_make(0, 0, 0);
            A.cap_lo[A.n_caps] = v3_make(dmin(c->a.x, c->b.x), dmin(c->a.y, c->b.y), dmin(c->a.z, c->b.z));
            A.cap_hi[A.n_caps] = v3_make(dmax(c->a.x, c->b.x), dmax(c->a.y, c->b.y), dmax(c->a.z, c->b.z));
            /* a flat section: sq R wide, its centre (1 - 1 / sq) R off the axis */
            A.cap_reach[A.n_caps++] = dmax(c->ra, c->rb) * (c->sq + 1.0 - 1.0 / c->sq);
        }
    if (!build_grid(&A)) A.oom = 1;
    v3 used[64];
    int n_used = 0, made = 0;
    for (int tries = 0; made < want && n_sites && tries < 4 * want && !A.oom && !roots_stop(net); tries++) {
        uint32_t at = site[rng_below(&A.rng, n_sites)];
        v3 P = net->pts[at];
        int near_used = 0;
        for (int u = 0; u < n_used; u++) near_used |= v3_dist(used[u], P) < 0.35;
        if (near_used) continue;
        if (n_used < 64) used[n_used++] = P;
        /* out from the host, along the root */
        v3 n, o;
        int which;
        world_clearance_in(&A.soil, P, 0, HUGE_VAL, &n, &which);
        o = v3_make(n.x, n.y, 0);
        if (which < 0 || v3_len(o) < 1e-6) o = v3_make(P.x - net->G.x, P.y - net->G.y, 0);
        o = v3_norm_or(o, v3_make(1, 0, 0));
        uint32_t j = at + 1 < net->n_pts ? at + 1 : at - 1;
        v3 along = v3_sub(net->pts[j], P);
        along = v3_norm_or(v3_madd(along, o, -v3_dot(along, o)), v3_cross(o, v3_make(0, 0, 1)));
        along = v3_scale(along, net->rad[at]);
        int tassel = 1 + (int)rng_below(&A.rng, 4);
        for (int k = 0; k < tassel && made < want && !A.oom; k++) {
            hang(&A, at, o, along);
            if (A.n) emit(&A, at, n_used - 1, k), made++;
        }
    }
    free(A.caps);
    free(A.g_start);
    free(A.g_items);
    free(A.cap_lo);
    free(A.cap_reach);
    free(site);
    return A.oom ? BANYAN_E_NOMEM : BANYAN_OK;
}

void roots_aerial_counts(const roots_poly *pl, uint32_t *verts, uint32_t *indices) {
    *verts = *indices = 0;
    if (pl->n >= 3) tube_counts(pl->n, ROOTS_AERIAL_SIDES, 1, 1, verts, indices);
}

/* The centre of a thread's start cap: the mean of ring a moved along -d
 * (off the surface the ring sits on) half way to its farthest vertex: a
 * flat fan, clear of a bark that bulges under the ring. It stays on the
 * near side of ring 1 (centre c1, the thread's tangent t1 there), half
 * way at most, so the cap faces away from the thread. */
static v3 cap_apex(const v3 *a, v3 d, v3 c1, v3 t1, int S) {
    v3 c = v3_make(0, 0, 0);
    for (int j = 0; j < S; j++) c = v3_add(c, a[j]);
    c = v3_scale(c, 1.0 / S);
    double up = 0;
    for (int j = 0; j < S; j++) up = dmax(up, -v3_dot(v3_sub(a[j], c), d));
    double ahead = v3_dot(v3_sub(c1, c), t1), rate = -v3_dot(d, t1); /* how far ring 1 lies on; per unit of -d */
    double move = 0.5 * up;
    if (rate > 1e-9 && move * rate > 0.5 * ahead) move = dmax(0, 0.5 * ahead / rate);
    return v3_madd(c, d, -move);
}

/* Where o + s d meets triangle A B C (Moller-Trumbore): s, or HUGE_VAL. */
static double seg_tri(v3 o, v3 d, v3 A, v3 B, v3 C) {
    v3 e1 = v3_sub(B, A), e2 = v3_sub(C, A), pv = v3_cross(d, e2);
    double det = v3_dot(e1, pv);
    if (fabs(det) < 1e-18) return HUGE_VAL;
    double inv = 1.0 / det;
    v3 tv = v3_sub(o, A);
    double u = v3_dot(tv, pv) * inv;
    if (u < 0 || u > 1) return HUGE_VAL;
    v3 qv = v3_cross(tv, e1);
    double v = v3_dot(d, qv) * inv;
    if (v < 0 || u + v > 1) return HUGE_VAL;
    return v3_dot(e2, qv) * inv;
}

static void corners(const float *pos, const uint32_t *I, v3 *X) {
    for (int j = 0; j < 3; j++) X[j] = v3_make(pos[3 * I[j]], pos[3 * I[j] + 1], pos[3 * I[j] + 2]);
}

/* First hit of the ray o + s d (0 < s <= smax) on triangles cand[0..nc-1]
 * of the fused surface, smax when none; *cosine: |d . the triangle's
 * normal| there. */
static double ray_hit(const float *pos, const uint32_t *tri, const uint32_t *cand, uint32_t nc, v3 o, v3 d,
                      double smax, double *cosine) {
    double best = smax;
    *cosine = 1;
    for (uint32_t j = 0; j < nc; j++) {
        v3 X[3];
        corners(pos, tri + 3 * (size_t)cand[j], X);
        double s = seg_tri(o, d, X[0], X[1], X[2]);
        if (s > 0 && s < best) best = s, *cosine = fabs(v3_dot(d, v3_norm(v3_cross(v3_sub(X[1], X[0]), v3_sub(X[2], X[0])))));
    }
    return best;
}

/* Distance between triangles P and Q that do not cross: the least of
 * their corners to the other and of their edge pairs. */
static double tri_tri_dist(const v3 *P, const v3 *Q) {
    double best = HUGE_VAL;
    int region;
    for (int i = 0; i < 3; i++) {
        best = dmin(best, v3_dist(P[i], tri_closest(P[i], Q[0], Q[1], Q[2], &region)));
        best = dmin(best, v3_dist(Q[i], tri_closest(Q[i], P[0], P[1], P[2], &region)));
        for (int j = 0; j < 3; j++) best = dmin(best, sqrt(seg_seg_dist2(P[i], P[(i + 1) % 3], Q[j], Q[(j + 1) % 3])));
    }
    return best;
}

/* The first segment of the tube (rings a and b, either diagonal of each
 * quad) keeps half of AERIAL_TOUCH from every candidate triangle (its
 * corners on ring a keep all of it: a chord across a bulge comes
 * nearer). */
static int start_clear(const float *pos, const uint32_t *tri, const uint32_t *cand, uint32_t nc, const v3 *a,
                       const v3 *b, v3 apex, int S) {
    const double need = 0.5 * AERIAL_TOUCH;
    for (uint32_t c = 0; c < nc; c++) {
        v3 X[3];
        corners(pos, tri + 3 * (size_t)cand[c], X);
        for (int j = 0; j < S; j++) {
            int k = (j + 1) % S;
            v3 q[5][3] = {{a[j], a[k], b[k]}, {a[j], b[k], b[j]}, {a[j], a[k], b[j]}, {a[k], b[k], b[j]},
                          {apex, a[j], a[k]}};
            for (int m = 0; m < 5; m++)
                if (tri_tri_dist(q[m], X) < need) return 0;
        }
    }
    return 1;
}

/* The first segment of the tube (rings a and b, S vertices each, either
 * diagonal of each quad) crosses a candidate triangle, or one of its
 * edges crosses the segment. */
static int start_crosses(const float *pos, const uint32_t *tri, const uint32_t *cand, uint32_t nc,
                         const v3 *a, const v3 *b, v3 apex, int S) {
    for (uint32_t c = 0; c < nc; c++) {
        v3 X[3];
        corners(pos, tri + 3 * (size_t)cand[c], X);
        for (int j = 0; j < S; j++) {
            int k = (j + 1) % S;
            v3 e[5][2] = {{a[j], a[k]}, {a[j], b[j]}, {a[j], b[k]}, {a[k], b[j]}, {a[j], apex}};
            for (int m = 0; m < 5; m++) {
                double s = seg_tri(e[m][0], v3_sub(e[m][1], e[m][0]), X[0], X[1], X[2]);
                if (s >= 0 && s <= 1) return 1;
            }
            v3 q[5][3] = {{a[j], a[k], b[k]}, {a[j], b[k], b[j]}, {a[j], a[k], b[j]}, {a[k], b[k], b[j]},
                          {apex, a[j], a[k]}};
            for (int m = 0; m < 5; m++)
                for (int t = 0; t < 3; t++) {
                    double s = seg_tri(X[t], v3_sub(X[(t + 1) % 3], X[t]), q[m][0], q[m][1], q[m][2]);
                    if (s >= 0 && s <= 1) return 1;
                }
        }
    }
    return 0;
}

/* The start folds on itself: two of its triangles (the cap over ring a,
 * the quads to ring b with either diagonal) that share no corner come
 * nearer than half AERIAL_TOUCH, as where one corner of ring a runs far
 * back along a slanting surface and its neighbours do not. */
static int start_folds(const v3 *a, const v3 *b, v3 apex, int S) {
    enum { MAXT = 5 * ROOTS_AERIAL_SIDES };
    v3 q[MAXT][3];
    int id[MAXT][3], n = 0;
    for (int j = 0; j < S; j++) {
        int k = (j + 1) % S;
        const int ids[5][3] = {{j, k, S + k}, {j, S + k, S + j}, {j, k, S + j}, {k, S + k, S + j}, {2 * S, j, k}};
        for (int m = 0; m < 5; m++, n++)
            for (int c = 0; c < 3; c++) {
                int v = ids[m][c];
                id[n][c] = v;
                q[n][c] = v < S ? a[v] : v < 2 * S ? b[v - S] : apex;
            }
    }
    for (int s = 0; s < n; s++)
        for (int t = s + 1; t < n; t++) {
            int share = 0;
            for (int c = 0; c < 9; c++) share |= id[s][c / 3] == id[t][c % 3];
            if (!share && tri_tri_dist(q[s], q[t]) < 0.5 * AERIAL_TOUCH) return 1;
        }
    return 0;
}

/* How far from a thread's second point the surface it leaves can lie:
 * the way back to its first point and two radii. */
static double start_reach(const roots_net *net, const roots_poly *pl) {
    return v3_dist(net->pts[pl->off], net->pts[pl->off + 1]) + 2.0 * net->rad[pl->off + 1];
}

/* Sweeps one thread (pl, n >= 3); cand[0..nc-1]: the surface's triangles
 * within start_reach of its second point; near: room for nc more. */
static void sweep_one(mesh_builder *mb, const roots_net *net, const roots_poly *pl, const uint32_t *cand, uint32_t nc,
                      uint32_t *near, int slot_stiff, int slot_birth, const double *stiff, const double *birth) {
    enum { S = ROOTS_AERIAL_SIDES };
    /* Rings: the one where the thread leaves the surface, then one per
     * point from the second on (the first lies inside its root). */
    const uint32_t n = pl->n;
    v3 *C = malloc(sizeof(v3) * (3 * (size_t)n + 2 * (size_t)n * S));
    double *R = malloc(sizeof(double) * 3 * n);
    if (!C || !R) {
        free(C), free(R);
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    v3 *T = C + n, *N = T + n, *ring = N + n, *nrm = ring + (size_t)n * S;
    const float *pos = mb->pos; /* the surface: the builder's first nt triangles (held: reserved) */
    const uint32_t *tri = mb->idx;
    double *ws = R + n, *wb = ws + n;
    const v3 *P = net->pts + pl->off;
    for (uint32_t i = 1; i < n; i++) {
        C[i] = P[i], R[i] = net->rad[pl->off + i];
        ws[i] = stiff[pl->off + i], wb[i] = birth[pl->off + i];
    }
    C[0] = P[1], R[0] = R[1], ws[0] = ws[1], wb[0] = wb[1];
    double cs[S], sn[S];
    for (int j = 0; j < S; j++) cs[j] = dm_cos(2.0 * BANYAN_PI * j / S), sn[j] = dm_sin(2.0 * BANYAN_PI * j / S);
    tube_frames(C + 1, n - 1, v3_make(0, 0, 0), T + 1, N + 1);
    tube_round_rings(C + 1, R + 1, n - 1, T + 1, N + 1, cs, sn, S, ring + S, nrm + S, NULL);
    /* Ring 0: ring 1 moved back along the first segment (towards the
     * root's axis) onto the surface it leaves, AERIAL_TOUCH short: every
     * edge from it to ring 1 lies outside (the first hit from outside). */
    v3 d = v3_norm(v3_sub(P[0], P[1]));
    double reach = start_reach(net, pl);
    double hit[S], shortest = HUGE_VAL;
    int missed[S];
    for (int j = 0; j < S; j++) {
        double cosine, s = ray_hit(pos, tri, cand, nc, ring[S + j], d, reach, &cosine);
        double back = AERIAL_TOUCH / dmax(cosine, 0.25); /* AERIAL_TOUCH off the surface, along its normal */
        missed[j] = !(s < reach);
        hit[j] = missed[j] ? 0 : s > back ? s - back : 0;
        if (!missed[j]) shortest = dmin(shortest, hit[j]);
        nrm[j] = nrm[S + j];
    }
    /* a corner whose ray passes the root's side goes as far as the
     * shortest that met it (not nowhere: the ring would fold) */
    for (int j = 0; j < S; j++)
        if (missed[j] && shortest < HUGE_VAL) hit[j] = shortest;
    /* Where the surface runs slantwise a quad's diagonal may cut it, the
     * ring come nearer than AERIAL_TOUCH or the start fold on itself: the
     * ring then stops shorter (the tries below); where none fits the tube
     * starts at ring 1 (the thread then stands off the bark by its
     * margin). */
    /* each vertex back from the nearest surface to AERIAL_TOUCH */
    for (int it = 0; it < 4; it++)
        for (int j = 0; j < S; j++) {
            v3 q = v3_madd(ring[S + j], d, hit[j]);
            double best = HUGE_VAL;
            for (uint32_t c = 0; c < nc; c++) {
                v3 X[3];
                int region;
                corners(pos, tri + 3 * (size_t)cand[c], X);
                best = dmin(best, v3_dist(q, tri_closest(q, X[0], X[1], X[2], &region)));
            }
            if (best < AERIAL_TOUCH) hit[j] = dmax(0, hit[j] - 2.0 * (AERIAL_TOUCH - best) - 0.0001);
        }
    /* and out of the hosts: a ray past a root's edge may reach one */
    for (int j = 0; j < S; j++)
        for (int it = 0; it < 20 && hit[j] > 0; it++) {
            v3 q = v3_madd(ring[S + j], d, hit[j]);
            if (world_clearance_in(&net->w, q, 0, AERIAL_TOUCH, NULL, NULL) >= AERIAL_TOUCH) break;
            hit[j] = it == 19 ? 0 : 0.8 * hit[j];
        }
    /* Tries: half a millimetre shorter each (so the start stays within
     * a few of the bark); then each corner's way drawn towards the least
     * of them by quarters (ring 1's shape moved back: a start that cannot
     * fold); then that by tenths of the way. */
    double least = hit[0];
    for (int j = 1; j < S; j++) least = dmin(least, hit[j]);
    uint32_t skip = 1; /* no ring 0 fits: the tube starts at ring 1, capped */
    for (int tries = 0; tries < 23 && skip; tries++) {
        double back = tries < 10 ? 0.0005 * tries : 0.0;
        double keep = tries < 10 ? 1.0 : tries < 14 ? 0.25 * (13 - tries) : 0.0; /* of hit[j] - least */
        double f = tries < 14 ? 1.0 : 0.1 * (23 - tries);
        for (int j = 0; j < S; j++)
            ring[j] = v3_madd(ring[S + j], d, dmax(f * (least + keep * (hit[j] - least)) - back, 0.001));
        /* the candidates near the strip between rings 0 and 1 */
        v3 lo = ring[0], hi = ring[0];
        for (int j = 0; j < 2 * S; j++)
            lo = v3_make(dmin(lo.x, ring[j].x), dmin(lo.y, ring[j].y), dmin(lo.z, ring[j].z)),
            hi = v3_make(dmax(hi.x, ring[j].x), dmax(hi.y, ring[j].y), dmax(hi.z, ring[j].z));
        uint32_t ns = 0;
        for (uint32_t c = 0; c < nc; c++) {
            v3 X[3];
            corners(pos, tri + 3 * (size_t)cand[c], X);
            int apart = 0;
            for (int k = 0; k < 3 && !apart; k++) {
                double tl = dmin(dmin(v3_at(X[0], k), v3_at(X[1], k)), v3_at(X[2], k));
                double th = dmax(dmax(v3_at(X[0], k), v3_at(X[1], k)), v3_at(X[2], k));
                apart = tl > v3_at(hi, k) + AERIAL_TOUCH || th < v3_at(lo, k) - AERIAL_TOUCH;
            }
            if (!apart) near[ns++] = cand[c];
        }
        C[0] = cap_apex(ring, d, C[1], T[1], S);
        if (!start_folds(ring, ring + S, C[0], S) && !start_crosses(pos, tri, near, ns, ring, ring + S, C[0], S) &&
            start_clear(pos, tri, near, ns, ring, ring + S, C[0], S))
            skip = 0;
    }
    uint32_t first = mb->nv, nr = n - skip;
    tube_opts o = {S, 1, 1, {0, 0, 0}, 0.0, nrm + skip * S, 0, 1};
    tube_sweep_rings(mb, C + skip, ring + skip * S, nr, &o); /* both ends capped: each thread a closed shell */
    /* uvs at the roots' bark scale (a tile is the circumference of a root
     * of radius r across and as tall), not the thread's own: a whole tile
     * round a few millimetres would fold its relief into one dark line. */
    if (!mb->status) {
        double arc = 0;
        for (uint32_t i = 0; i < nr; i++) {
            if (i) arc += v3_dist(C[skip + i], C[skip + i - 1]);
            float v = (float)(arc / (2.0 * BANYAN_PI * net->r));
            for (int j = 0; j <= S; j++) {
                float *uv = mb->uv + 2 * ((size_t)first + (size_t)i * (S + 1) + j);
                uv[0] = (float)((double)j / S * R[skip + i] / net->r), uv[1] = v;
            }
        }
    }
    wind_tube_rings(mb, first, nr, S, 1, 1, slot_stiff, ws + skip);
    wind_tube_rings(mb, first, nr, S, 1, 1, slot_birth, wb + skip);
    free(C);
    free(R);
}

void roots_aerial_sweep_all(mesh_builder *mb, const roots_net *net, uint32_t nt, int a_kind, int a_id,
                            const wind_slots *wsl, const roots_wind *rw) {
    /* The threads, by the x of their second point; each surface triangle
     * goes to the lists of the threads whose start it can come within
     * reach of (two passes: count, then fill). */
    uint32_t nth = 0;
    double reach_max = 0;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].kind == ROOT_AERIAL && net->poly[t].n >= 3) nth++;
    if (!nth || mb->status) return;
    uint32_t *th = malloc(sizeof(uint32_t) * (2 * (size_t)nth + 1)), *start = th + nth;
    if (!th) {
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    nth = 0;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].kind == ROOT_AERIAL && net->poly[t].n >= 3) {
            th[nth++] = t;
            reach_max = dmax(reach_max, start_reach(net, &net->poly[t]));
        }
    for (uint32_t i = 1; i < nth; i++) /* insertion sort by x, then by polyline (at most AERIAL_MAX_THREADS) */
        for (uint32_t j = i; j > 0; j--) {
            double x0 = net->pts[net->poly[th[j - 1]].off + 1].x, x1 = net->pts[net->poly[th[j]].off + 1].x;
            if (x0 < x1 || (x0 == x1 && th[j - 1] < th[j])) break;
            uint32_t sw = th[j];
            th[j] = th[j - 1], th[j - 1] = sw;
        }
    const float *pos = mb->pos; /* the surface: the builder's first nt triangles (held: reserved) */
    const uint32_t *tri = mb->idx;
    uint32_t *list = NULL, total = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 0) memset(start, 0, sizeof(uint32_t) * (nth + 1));
        for (uint32_t f = 0; f < nt; f++) {
            v3 X[3];
            corners(pos, tri + 3 * (size_t)f, X);
            v3 lo = v3_make(dmin(dmin(X[0].x, X[1].x), X[2].x), dmin(dmin(X[0].y, X[1].y), X[2].y),
                            dmin(dmin(X[0].z, X[1].z), X[2].z));
            v3 hi = v3_make(dmax(dmax(X[0].x, X[1].x), X[2].x), dmax(dmax(X[0].y, X[1].y), X[2].y),
                            dmax(dmax(X[0].z, X[1].z), X[2].z));
            uint32_t a = 0, b = nth; /* the first thread whose x reaches lo.x - reach_max */
            while (a < b) {
                uint32_t m = (a + b) / 2;
                if (net->pts[net->poly[th[m]].off + 1].x < lo.x - reach_max) a = m + 1;
                else b = m;
            }
            for (uint32_t i = a; i < nth; i++) {
                const roots_poly *pl = &net->poly[th[i]];
                v3 c = net->pts[pl->off + 1];
                if (c.x > hi.x + reach_max) break;
                double reach = start_reach(net, pl);
                if (box_dist(c, lo, hi) >= reach) continue;
                if (pass == 0) start[i + 1]++;
                else list[start[i]++] = f;
            }
        }
        if (pass == 0) {
            for (uint32_t i = 0; i < nth; i++) start[i + 1] += start[i];
            total = start[nth];
            list = malloc(sizeof(uint32_t) * (2 * (size_t)total + 1));
            if (!list) {
                free(th);
                mb->status = BANYAN_E_NOMEM;
                return;
            }
        }
    }
    for (uint32_t i = nth; i > 0; i--) start[i] = start[i - 1]; /* the fill moved every start on */
    start[0] = 0;
    /* in the polylines' order (the mesh's bytes do not depend on x) */
    for (uint32_t t = 0; t < net->n_poly && !mb->status; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind != ROOT_AERIAL || pl->n < 3) continue;
        uint32_t i = 0;
        while (th[i] != t) i++;
        mb_set_attr(mb, a_kind, pl->kind);
        mb_set_attr(mb, a_id, pl->id);
        wind_set(mb, wsl, rw->pivot[t], roots_wind_level(pl->kind), 1.0, rw->phase[t], 0.0);
        sweep_one(mb, net, pl, list + start[i], start[i + 1] - start[i], list + total, wsl->stiffness, wsl->birth,
                  rw->stiff, rw->birth);
    }
    free(list);
    free(th);
}
