/* attach.c - which segments of a tree are attached (spec segments.md,
 * "Composing a tree": S must lie on the axis S_j + A_j t, t in [0, l_j],
 * of an earlier segment j, or on a trunk).
 *
 * Distances are exact point-to-segment distances in double, with A_j
 * normalised, compared with the tolerance. To avoid the O(n^2) scan,
 * every axis is sampled at steps of the cell size h (h >= 2 tol) and each
 * sample's cell of a uniform grid lists the axis. A point within tol of an
 * axis is then within tol + h/2 <= h of some sample, so the sample's cell
 * is one of the 27 cells around the point's own cell: those are the only
 * candidates to test. h is also chosen so that the samples number at most
 * about 8 per axis and the grid at most 2 cbrt(count) (<= 128) cells a
 * side. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../base/progress.h"
#include "../base/vec.h"
#include "segment_core.h"

#define GRID_MAX_DIM 128
#define BRUTE_MAX 64

static v3 axis_dir(const banyan_segment_input *s) {
    return v3_norm(v3_load(s->A));
}

static double dist_to_axis(v3 p, const banyan_segment_input *s) {
    v3 a = v3_load(s->S), u = axis_dir(s);
    double t = v3_dot(v3_sub(p, a), u);
    t = t < 0 ? 0 : t > s->l ? s->l : t;
    return v3_dist(p, v3_madd(a, u, t));
}

static double dist_to_line(v3 p, const double *trunk) {
    v3 a = v3_load(trunk), b = v3_load(trunk + 3), ab = v3_sub(b, a);
    double L2 = v3_len2(ab);
    double t = L2 > 0 ? v3_dot(v3_sub(p, a), ab) / L2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return v3_dist(p, v3_madd(a, ab, t));
}

static int on_trunk(const banyan_segment_input *segs, uint32_t i, const double *trunk, double tol) {
    if (!trunk) return i == 0;
    return dist_to_line(v3_load(segs[i].S), trunk) <= tol;
}

typedef struct grid {
    v3 lo;
    double h;
    int dim[3];
    uint32_t *start; /* cells + 1 offsets into items */
    uint32_t *items; /* axis indices */
} grid;

static size_t cell_of(const grid *g, v3 p, int c[3]) {
    double q[3] = {(p.x - g->lo.x) / g->h, (p.y - g->lo.y) / g->h, (p.z - g->lo.z) / g->h};
    for (int k = 0; k < 3; k++) {
        double f = floor(q[k]);
        c[k] = f < 0 ? 0 : f >= g->dim[k] ? g->dim[k] - 1 : (int)f;
    }
    return ((size_t)c[2] * g->dim[1] + c[1]) * g->dim[0] + c[0];
}

/* Calls back (pass 0: count, pass 1: fill) for every distinct cell the
 * samples of axis j fall into, consecutive repeats skipped. */
static void sample_axis(grid *g, const banyan_segment_input *s, uint32_t j, uint32_t *fill) {
    v3 a = v3_load(s->S), u = axis_dir(s);
    double l = s->l;
    uint64_t steps = (uint64_t)ceil(l / g->h);
    size_t prev = (size_t)-1;
    for (uint64_t k = 0; k <= steps; k++) {
        double t = k == steps ? l : (double)k * g->h;
        int c[3];
        size_t cell = cell_of(g, v3_madd(a, u, t), c);
        if (cell == prev) continue;
        prev = cell;
        if (fill) g->items[fill[cell]++] = j;
        else g->start[cell + 1]++;
    }
}

/* The nearest parent so far of segment i: axis j at distance d (within
 * tol) replaces it when nearer, or as near with a lower j; the trunk
 * (-1, set first) wins ties. */
static void nearer(int32_t *best, double *best_d, uint32_t j, double d) {
    if (d < *best_d || (d == *best_d && *best >= 0 && (int32_t)j < *best)) *best = (int32_t)j, *best_d = d;
}

/* Segment i's start: 1 if on the trunk (parent -1) or, without one, the
 * root; best and best_d start the search. */
static int start_of(const banyan_segment_input *segs, uint32_t i, const double *trunk, double tol, int32_t *best,
                    double *best_d) {
    *best = -2;
    *best_d = HUGE_VAL;
    if (!on_trunk(segs, i, trunk, tol)) return 0;
    if (trunk) *best = -1, *best_d = dist_to_line(v3_load(segs[i].S), trunk);
    return 1;
}

static uint32_t brute_scan(const banyan_segment_input *segs, uint32_t count, const double *trunk, double tol,
                           uint32_t *out, int32_t *parent, prog *g) {
    uint32_t n = 0;
    for (uint32_t i = 0; i < count; i++) {
        if ((i & 63) == 0 && prog_at(g, 0.0)) return 0;
        int32_t best;
        double best_d;
        int ok = start_of(segs, i, trunk, tol, &best, &best_d);
        v3 p = v3_load(segs[i].S);
        for (uint32_t j = 0; j < i && (!ok || parent); j++) {
            double d = dist_to_axis(p, &segs[j]);
            if (d > tol) continue;
            ok = 1;
            nearer(&best, &best_d, j, d);
        }
        if (parent) parent[i] = best;
        if (!ok) {
            if (out) out[n] = i;
            n++;
        }
    }
    return n;
}

uint32_t seg_find_unattached(const banyan_segment_input *segs, uint32_t count, const double *trunk, double tol,
                             int brute, uint32_t *out, banyan_status *status, prog *pg) {
    return seg_attach_parents(segs, count, trunk, tol, brute, NULL, out, status, pg);
}

uint32_t seg_attach_parents(const banyan_segment_input *segs, uint32_t count, const double *trunk, double tol,
                            int brute, int32_t *parent, uint32_t *out, banyan_status *status, prog *pg) {
    *status = BANYAN_OK;
    if (brute || count <= BRUTE_MAX) {
        uint32_t n = brute_scan(segs, count, trunk, tol, out, parent, pg);
        if (prog_stopped(pg)) *status = BANYAN_E_LIMIT;
        return n;
    }

    /* Bounds of every axis and the total axis length. */
    v3 lo = v3_load(segs[0].S), hi = lo;
    double total = 0;
    for (uint32_t j = 0; j < count; j++) {
        v3 a = v3_load(segs[j].S), b = v3_madd(a, axis_dir(&segs[j]), segs[j].l);
        lo = v3_make(fmin(lo.x, fmin(a.x, b.x)), fmin(lo.y, fmin(a.y, b.y)), fmin(lo.z, fmin(a.z, b.z)));
        hi = v3_make(fmax(hi.x, fmax(a.x, b.x)), fmax(hi.y, fmax(a.y, b.y)), fmax(hi.z, fmax(a.z, b.z)));
        total += segs[j].l;
    }
    double ext = fmax(hi.x - lo.x, fmax(hi.y - lo.y, hi.z - lo.z));
    grid g;
    g.lo = lo;
    /* About 8 cells per axis at most: a small tree gets a small grid. */
    double maxdim = fmin(GRID_MAX_DIM, fmax(4, ceil(2 * dm_cbrt((double)count))));
    g.h = fmax(fmax(2 * tol, ext / maxdim), fmax(total / (8.0 * count), 1e-9 * (1 + ext)));
    double span[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
    size_t cells = 1;
    for (int k = 0; k < 3; k++) {
        double d = floor(span[k] / g.h) + 1;
        g.dim[k] = d > GRID_MAX_DIM + 1 ? GRID_MAX_DIM + 1 : (int)d;
        cells *= (size_t)g.dim[k];
    }
    g.start = calloc(cells + 1, sizeof *g.start);
    uint32_t *fill = malloc(sizeof *fill * cells);
    if (!g.start || !fill) {
        free(g.start);
        free(fill);
        *status = BANYAN_E_NOMEM;
        return 0;
    }
    for (uint32_t j = 0; j < count; j++) sample_axis(&g, &segs[j], j, NULL);
    for (size_t c = 0; c < cells; c++) g.start[c + 1] += g.start[c];
    g.items = malloc(sizeof *g.items * (g.start[cells] ? g.start[cells] : 1));
    if (!g.items) {
        free(g.start);
        free(fill);
        *status = BANYAN_E_NOMEM;
        return 0;
    }
    memcpy(fill, g.start, sizeof *fill * cells);
    for (uint32_t j = 0; j < count; j++) sample_axis(&g, &segs[j], j, fill);

    uint32_t n = 0;
    for (uint32_t i = 0; i < count; i++) {
        if (prog_at(pg, 0.0)) { /* a point may test every axis: each one */
            *status = BANYAN_E_LIMIT;
            break;
        }
        v3 p = v3_load(segs[i].S);
        int32_t best;
        double best_d;
        int ok = start_of(segs, i, trunk, tol, &best, &best_d);
        int c[3];
        cell_of(&g, p, c);
        /* With parents wanted, every candidate is measured (the nearest
         * wins, whatever the cells' order). */
        for (int dz = -1; dz <= 1 && (!ok || parent); dz++)
            for (int dy = -1; dy <= 1 && (!ok || parent); dy++)
                for (int dx = -1; dx <= 1 && (!ok || parent); dx++) {
                    int x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
                    if (x < 0 || y < 0 || z < 0 || x >= g.dim[0] || y >= g.dim[1] || z >= g.dim[2]) continue;
                    size_t cell = ((size_t)z * g.dim[1] + y) * g.dim[0] + x;
                    for (uint32_t e = g.start[cell]; e < g.start[cell + 1] && (!ok || parent); e++) {
                        uint32_t j = g.items[e];
                        if (j >= i) continue;
                        double d = dist_to_axis(p, &segs[j]);
                        if (d > tol) continue;
                        ok = 1;
                        nearer(&best, &best_d, j, d);
                    }
                }
        if (parent) parent[i] = best;
        if (!ok) {
            if (out) out[n] = i;
            n++;
        }
    }
    free(g.start);
    free(fill);
    free(g.items);
    return n;
}
