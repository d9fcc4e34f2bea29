/* avenue_layout.c - banyan_avenue_layout: where an avenue's trees stand
 * (spec/keyaki.md, "Avenues"). Trees sit at arc lengths along the path,
 * every `spacing` metres centred on it, or `count` per row from end to
 * end; row 0 lies row_offset / 2 to the left of the path (left of its
 * direction, seen from above), row 1 as far to the right, optionally
 * staggered by half a step. Tree order: row 0 along the path, then row 1.
 * Used by the avenue (avenue.c) and its instanced variants (variants.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "keyaki_internal.h"

#define AVENUE_MAX_PATH_POINTS 1000000u

typedef struct path_walk {
    const v3 *pts;
    double *cum; /* cumulative length at each point */
    uint32_t n;
} path_walk;

/* Point and unit horizontal left normal at arc length s. */
static void path_at(const path_walk *w, double s, v3 *pos, v3 *left) {
    uint32_t lo = 0, hi = w->n - 1;
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (w->cum[mid] <= s) lo = mid;
        else hi = mid;
    }
    double len = w->cum[hi] - w->cum[lo], t = len > 0 ? (s - w->cum[lo]) / len : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    *pos = v3_lerp(w->pts[lo], w->pts[hi], t);
    v3 dir = v3_sub(w->pts[hi], w->pts[lo]);
    *left = v3_norm_or(v3_make(-dir.y, dir.x, 0), v3_make(0, 1, 0));
}

banyan_status banyan_avenue_layout(const banyan_avenue_params *p, const double *path_xyz, uint32_t path_point_count,
                                   banyan_keyaki_params *trees, uint32_t capacity, uint32_t *tree_count,
                                   banyan_error *err) {
    if (!p || !tree_count) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params and tree_count must not be NULL");
    *tree_count = 0;
    banyan_status s = banyan_params_check(BANYAN_GEN_AVENUE, p, err);
    if (s) return s;
    if (trees == NULL && capacity) return banyan_fail(err, BANYAN_E_INVALID_ARG, "trees is NULL but capacity = %u", capacity);
    path_walk w;
    v3 line[2];
    if (path_xyz) {
        if ((s = banyan_check_int(err, "path_point_count", path_point_count, 2, AVENUE_MAX_PATH_POINTS))) return s;
        for (uint32_t i = 0; i < 3 * path_point_count; i++)
            if (!isfinite(path_xyz[i]) || fabs(path_xyz[i]) > 1e6)
                return banyan_fail(err, BANYAN_E_RANGE, "path point %u = (%g, %g, %g) must be finite and within 1e6 m",
                                   i / 3, path_xyz[i / 3 * 3], path_xyz[i / 3 * 3 + 1], path_xyz[i / 3 * 3 + 2]);
        w.pts = (const v3 *)NULL;
        w.n = path_point_count;
    } else {
        line[0] = v3_load(p->start);
        line[1] = v3_load(p->end);
        w.pts = line;
        w.n = 2;
    }
    v3 *own = NULL;
    if (path_xyz) {
        own = malloc(sizeof(v3) * w.n);
        if (!own) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u path points", w.n);
        for (uint32_t i = 0; i < w.n; i++) own[i] = v3_load(path_xyz + 3 * (size_t)i);
        w.pts = own;
    }
    w.cum = malloc(sizeof(double) * w.n);
    if (!w.cum) {
        free(own);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u path points", w.n);
    }
    w.cum[0] = 0;
    for (uint32_t i = 1; i < w.n; i++) {
        double d = v3_dist(w.pts[i], w.pts[i - 1]);
        if (d < 1e-9) {
            free(own);
            free(w.cum);
            if (!path_xyz) return banyan_fail(err, BANYAN_E_RANGE, "start and end must differ (the path has no length)");
            return banyan_fail(err, BANYAN_E_RANGE, "path point %u repeats point %u; consecutive points must differ", i,
                               i - 1);
        }
        w.cum[i] = w.cum[i - 1] + d;
    }
    const double length = w.cum[w.n - 1];

    /* Arc lengths of row 0; row 1 the same, shifted when staggered. */
    double step, first;
    double per_row;
    if (p->placement == BANYAN_AVENUE_COUNT) {
        per_row = p->count;
        step = p->count > 1 ? length / (p->count - 1) : 0;
        first = p->count > 1 ? 0 : 0.5 * length;
    } else {
        per_row = floor(length / p->spacing + 1e-9) + 1;
        step = p->spacing;
        first = per_row <= BANYAN_AVENUE_MAX_TREES ? 0.5 * (length - (per_row - 1) * step) : 0;
    }
    if (per_row * p->rows > BANYAN_AVENUE_MAX_TREES) {
        free(own);
        free(w.cum);
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the avenue would have %.0f trees, more than %d; raise spacing or shorten the path",
                           per_row * p->rows, BANYAN_AVENUE_MAX_TREES);
    }
    uint32_t n_row = (uint32_t)per_row, total = 0;
    const banyan_param_info *trunk = banyan_param_find(BANYAN_GEN_KEYAKI, "trunk_length");
    const banyan_param_info *unit = banyan_param_find(BANYAN_GEN_KEYAKI, "unit");
    for (int row = 0; row < p->rows; row++) {
        double shift = row == 1 && p->stagger ? 0.5 * step : 0.0;
        double offset = p->rows == 2 ? (row == 0 ? 0.5 : -0.5) * p->row_offset : 0.0;
        for (uint32_t k = 0; k < n_row; k++) {
            double sdist = first + k * step + shift;
            if (sdist > length + 1e-9) continue; /* a staggered row loses its last tree */
            uint32_t i = total++;
            if (i >= capacity) continue;
            banyan_keyaki_params *t = &trees[i];
            *t = p->tree;
            t->seed = p->seed + i;
            t->max_vertices = p->max_vertices;
            t->max_seconds = p->max_seconds; /* the avenue's budget covers its trees */
            t->max_memory_mb = p->max_memory_mb;
            pcg32 r;
            pcg32_seed(&r, p->seed + i, AVENUE_STREAM_JITTER);
            t->heading = rng_range(&r, -p->heading_jitter, p->heading_jitter);
            /* Jittered within the trunk's own range, so that tree.trunk_length
             * at its min or max still gives valid trees. */
            double h = p->tree.trunk_length * (1.0 + rng_range(&r, -p->height_jitter, p->height_jitter));
            t->trunk_length = h < trunk->min ? trunk->min : h > trunk->max ? trunk->max : h;
            double jr = p->position_jitter * sqrt(rng_uniform(&r)), ja = 2.0 * BANYAN_PI * rng_uniform(&r);
            v3 at, left;
            path_at(&w, sdist, &at, &left);
            at = v3_madd(at, left, offset);
            at = v3_add(at, v3_make(jr * dm_cos(ja), jr * dm_sin(ja), 0));
            t->position[0] = at.x;
            t->position[1] = at.y;
            t->position[2] = at.z;
            /* Drawn last, so the draws above (and every avenue without
             * levels_jitter) stay as they were. */
            if (p->levels_jitter > 0) {
                int32_t drop = (int32_t)rng_below(&r, (uint32_t)p->levels_jitter + 1);
                t->levels = p->tree.levels - drop < 1 ? 1 : p->tree.levels - drop;
            }
            /* Size and lean from a stream of their own: the draws above
             * keep every avenue's feet, headings and trunks. */
            pcg32 q;
            pcg32_seed(&q, p->seed + i, AVENUE_STREAM_SHAPE);
            double u = p->tree.unit * (1.0 + rng_range(&q, -p->scale_jitter, p->scale_jitter));
            t->unit = u < unit->min ? unit->min : u > unit->max ? unit->max : u;
            t->lean = p->lean_jitter * rng_uniform(&q);
            t->lean_direction = rng_range(&q, -180.0, 180.0);
        }
    }
    free(own);
    free(w.cum);
    *tree_count = total;
    if (trees && total > capacity)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "capacity = %u is less than the %u trees", capacity, total);
    /* Check every tree as banyan_keyaki_generate would. */
    for (uint32_t i = 0; trees && i < total; i++) {
        if ((s = keyaki_params_validate(&trees[i], err))) {
            char prefix[48];
            snprintf(prefix, sizeof prefix, "tree %u: tree.", i);
            banyan_error_prefix(err, prefix);
            return s;
        }
    }
    banyan_error_clear(err);
    return BANYAN_OK;
}
