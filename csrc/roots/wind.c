/* Wind and birth values of the roots net (docs/roots.md "Wind
 * and growth attributes"), per polyline point and per polyline, shared by
 * the tubes (mesh.c) and the fused surface (fused.c).
 *
 * Birth follows the growth order: a main root's growth point b (growth.c)
 * is reached at time b + 1 (G at 0), points between by arc length; a
 * branch root grows at the main roots' mean speed from its start on its
 * parent, no earlier than lets it reach its far end after that end grew.
 * Times are divided by the latest one.
 *
 * Stiffness: a root gripping a host or lying on (or in) the ground does
 * not sway: 1 where the tube's surface is within r / 2 of an obstacle
 * (the germination point G too). Between such anchors it falls with the
 * arc length to the nearest one as exp(-s / (ROOTS_WIND_REACH r)); a
 * branch root's ends hang on their parents, so they take the parent's
 * stiffness there (a first branch root's start and end, a second's: the
 * joint does not tear) and count as anchors. A free part is never softer
 * than 0.9 sqrt(R / R_max), every generator's wood stiffness (R the
 * pipe-model radius, R_max the net's thickest) kept below 1: the thick
 * main roots sway less than the thin branch roots. Foot roots (foot.c)
 * lie on the host or the ground or stand as planks: 1. Aerial roots
 * (aerial.c) hang free: only their start on the root and an end in the
 * soil hold them. Pivot: the root's start on its parent (G for main roots),
 * the very skeleton point; level: main 0, first branch 1, second 2 (aerial 2, foot
 * roots 0: roots_wind_level); phase: per root id. */
#include <stdlib.h>

#include "mesh/wind.h"
#include "roots_internal.h"

/* A free root softens over this many r of arc from its last anchor. */
#define ROOTS_WIND_REACH 20.0
/* The thickest free root's stiffness (below 1: only a held root is 1). */
#define ROOTS_WIND_THICK 0.9

static void arc_of(const v3 *P, uint32_t n, double *arc) {
    arc[0] = 0;
    for (uint32_t i = 1; i < n; i++) arc[i] = arc[i - 1] + v3_dist(P[i], P[i - 1]);
}

/* Skeleton point of polyline pl's end (0 start, 1 end) on its parent, or
 * UINT32_MAX for a main root's end (G is handled by the caller). */
static uint32_t parent_point(const roots_net *net, const banyan_roots_params *p, const roots_poly *pl, int end) {
    if (pl->kind == ROOT_FIRST) {
        int b = end ? roots_branch_end_b(net, p, pl->a * net->nb + pl->k) : roots_branch_b(p, pl->k);
        int a = end ? (pl->a + 1) % net->N : pl->a;
        return net->M_at[(size_t)a * net->B + b];
    }
    if (pl->kind == ROOT_SECOND) return net->K_mid_at[pl->a * net->nb + pl->k + (end ? 1 : 0)];
    if (pl->kind == ROOT_FOOT || pl->kind == ROOT_AERIAL) return end ? UINT32_MAX : pl->from; /* a free end */
    return UINT32_MAX;
}

int roots_wind_build(const roots_net *net, const banyan_roots_params *p, roots_wind *rw) {
    uint32_t n = net->n_pts ? net->n_pts : 1, np = net->n_poly ? net->n_poly : 1, longest = 2;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].n > longest) longest = net->poly[t].n;
    rw->birth = malloc(sizeof(double) * 2 * n);
    rw->pivot = malloc(sizeof(v3) * np);
    rw->phase = malloc(sizeof(double) * np);
    double *arc = malloc(sizeof(double) * longest);
    if (!rw->birth || !rw->pivot || !rw->phase || !arc) {
        free(arc);
        roots_wind_free(rw);
        return -1;
    }
    rw->stiff = rw->birth + n;
    double *time = rw->birth, *st = rw->stiff;
    const int B = net->B;
    const double r = net->r, fall = 1.0 / (ROOTS_WIND_REACH * r);
    double r_max = 0;
    for (uint32_t i = 0; i < net->n_pts; i++) r_max = net->rad[i] > r_max ? net->rad[i] : r_max;

    /* Main roots: knots at the growth points, then the mean speed. */
    double arc_sum = 0, time_sum = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind != ROOT_MAIN || pl->n == 0) continue;
        const v3 *P = net->pts + pl->off;
        arc_of(P, pl->n, arc);
        uint32_t ki = 0; /* last knot */
        double kt = 0;
        time[pl->off] = 0;
        for (int b = 0; b < B; b++) {
            uint32_t at = net->M_at[(size_t)pl->a * B + b];
            if (at < pl->off || at >= pl->off + pl->n || at - pl->off <= ki) continue;
            uint32_t j = at - pl->off;
            double t1 = b + 1.0, span = arc[j] - arc[ki];
            for (uint32_t i = ki + 1; i <= j; i++)
                time[pl->off + i] = span > 0 ? kt + (t1 - kt) * (arc[i] - arc[ki]) / span : t1;
            ki = j, kt = t1;
        }
        if (kt > 0 && arc[ki] > 0) arc_sum += arc[ki], time_sum += kt;
        /* the rest (the underground end) at this root's own speed */
        double speed = kt > 0 && arc[ki] > 0 ? arc[ki] / kt : r;
        for (uint32_t i = ki + 1; i < pl->n; i++) time[pl->off + i] = kt + (arc[i] - arc[ki]) / speed;
    }
    const double speed = time_sum > 0 ? arc_sum / time_sum : r;
    /* Branch roots, in order (first before second: a second starts on a
     * first's middle). */
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind == ROOT_MAIN || pl->n == 0) continue;
        arc_of(net->pts + pl->off, pl->n, arc);
        double dur = arc[pl->n - 1] / speed;
        uint32_t e1 = parent_point(net, p, pl, 1);
        double t0 = time[parent_point(net, p, pl, 0)], te = e1 == UINT32_MAX ? t0 : time[e1] - dur;
        if (te > t0) t0 = te;
        for (uint32_t i = 0; i < pl->n; i++) time[pl->off + i] = t0 + arc[i] / speed;
    }
    double tmax = 0;
    for (uint32_t i = 0; i < net->n_pts; i++) tmax = time[i] > tmax ? time[i] : tmax;
    for (uint32_t i = 0; i < net->n_pts; i++) time[i] = tmax > 0 ? time[i] / tmax : 0;

    /* Stiffness: anchors, then the fall-off both ways along each root. */
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n == 0) continue;
        const v3 *P = net->pts + pl->off;
        const double *R = net->rad + pl->off;
        double *s = st + pl->off;
        if (pl->kind == ROOT_FOOT) { /* buttresses, surface and drop roots: held along their length */
            for (uint32_t i = 0; i < pl->n; i++) s[i] = 1.0;
            continue;
        }
        for (uint32_t i = 0; i < pl->n; i++) {
            double reach = (R[i] > r ? R[i] : r) + 0.5 * r;
            if (pl->kind == ROOT_AERIAL) /* hangs free of the hosts (aerial.c): only the ground holds it */
                s[i] = net->w.ground && P[i].z - net->w.ground_z < reach ? 1.0 : 0.0;
            else
                s[i] = world_clearance_in(&net->w, P[i], 1, reach, NULL, NULL) < reach ? 1.0 : 0.0;
        }
        if (pl->kind == ROOT_MAIN) s[0] = 1.0; /* G */
        else {
            uint32_t e1 = parent_point(net, p, pl, 1);
            s[0] = st[parent_point(net, p, pl, 0)];
            if (e1 != UINT32_MAX) s[pl->n - 1] = st[e1];
        }
        double *k = arc; /* k[i]: the fall over segment i-1 .. i, one exp each */
        for (uint32_t i = 1; i < pl->n; i++) {
            k[i] = dm_exp(-v3_dist(P[i], P[i - 1]) * fall);
            double v = s[i - 1] * k[i];
            if (v > s[i]) s[i] = v;
        }
        for (uint32_t i = pl->n - 1; i-- > 0;) {
            double v = s[i + 1] * k[i + 1];
            if (v > s[i]) s[i] = v;
        }
        /* a branch's ends are its parents' */
        uint32_t end = parent_point(net, p, pl, 1) == UINT32_MAX ? pl->n : pl->n - 1;
        for (uint32_t i = 1; i < end && r_max > 0; i++) {
            double v = ROOTS_WIND_THICK * sqrt(R[i] / r_max);
            if (v > s[i]) s[i] = v;
        }
    }

    /* Per root: pivot and phase. G is the first main root's first point
     * (the skeleton's). */
    v3 G = net->G;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].kind == ROOT_MAIN && net->poly[t].n) {
            G = net->pts[net->poly[t].off];
            break;
        }
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        rw->pivot[t] = pl->kind == ROOT_MAIN ? G : net->pts[parent_point(net, p, pl, 0)];
        rw->phase[t] = wind_phase_of(p->seed, (uint64_t)(uint32_t)pl->id);
    }
    free(arc);
    return 0;
}

void roots_wind_free(roots_wind *rw) {
    free(rw->birth);
    free(rw->pivot);
    free(rw->phase);
    rw->birth = rw->stiff = rw->phase = NULL;
    rw->pivot = NULL;
}
