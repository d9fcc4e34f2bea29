/* chain.c - a plant's levels of detail in one call (banyan_mesh_lods):
 * each ratio's level is simplified from the level before it, asked for
 * the share of that level's triangles that leaves ratio[k] of the mesh's
 * (the simplifier may stop a little short of a ratio: the next level
 * makes up for it), so each pass starts from fewer triangles; the
 * billboard pictures the mesh itself, drawn on a second thread while the
 * ratios' chain runs (threads != 1). The same levels on any thread count.
 * One budget covers the whole call: each level gets what is left of it. */
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/error.h"
#include "base/platform.h"
#include "base/progress.h"
#include "lod_internal.h"

typedef struct bb_job {
    const banyan_mesh *mesh;
    banyan_lod_params p;
    banyan_budget left;
    banyan_mesh *out;
    banyan_status s;
    banyan_error err;
} bb_job;

static void *bb_run(void *arg) {
    bb_job *j = arg;
    j->s = banyan_mesh_lod_budget(j->mesh, &j->p, &j->left, &j->out, &j->err);
    return NULL;
}

/* What is left of g's budget for the next level (BANYAN_E_LIMIT when
 * nothing is). */
static banyan_status left_of(const prog *g, banyan_budget *out, banyan_error *err) {
    banyan_budget_init(out);
    double spent = process_now() - g->t_start, used = process_rss_mb() - g->rss0_mb;
    out->max_seconds = g->max_seconds - spent;
    out->max_memory_mb = g->max_mb - (used > 0 ? used : 0);
    if (out->max_seconds < PROG_MAX_SECONDS_MIN)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the levels of detail stopped: %.2f s spent of max_seconds = %g; raise max_seconds or ask "
                           "for fewer levels",
                           spent, g->max_seconds);
    if (out->max_memory_mb < PROG_MAX_MEMORY_MIN)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the levels of detail stopped: %.0f MB held of max_memory_mb = %g; raise max_memory_mb or "
                           "ask for fewer levels",
                           used, g->max_mb);
    return BANYAN_OK;
}

static banyan_status check_ratios(const double *ratios, uint32_t n, const banyan_lod_params *billboard,
                                  banyan_error *err) {
    const uint32_t most = BANYAN_LOD_MAX_LEVELS - (billboard ? 1 : 0);
    if (n > most) return banyan_fail(err, BANYAN_E_RANGE, "ratio_count = %u must be within [0, %u]", n, most);
    if (n && !ratios) return banyan_fail(err, BANYAN_E_INVALID_ARG, "ratios is NULL with ratio_count = %u", n);
    if (!n && !billboard)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "no level asked for: ratio_count = 0 and billboard is NULL");
    double last = 1.0;
    for (uint32_t k = 0; k < n; k++) {
        if (!(ratios[k] >= 0.001 && ratios[k] < last))
            return banyan_fail(err, BANYAN_E_RANGE,
                               "ratios[%u] = %g must be within [0.001, 1) and below the ratio before it (%g)", k,
                               ratios[k], last);
        last = ratios[k];
    }
    if (billboard && !billboard->billboard)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "billboard->billboard = %d must be 1 (or billboard NULL: none)",
                           billboard->billboard);
    return BANYAN_OK;
}

banyan_status banyan_mesh_lods(const banyan_mesh *mesh, const double *ratios, uint32_t ratio_count,
                               const banyan_lod_params *billboard, int32_t threads, const banyan_budget *budget,
                               banyan_mesh **out, banyan_error *err) {
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    const uint64_t n = (uint64_t)ratio_count + (billboard ? 1 : 0);
    banyan_status s;
    if (n <= BANYAN_LOD_MAX_LEVELS) /* out holds n entries only when n is in range */
        for (uint64_t k = 0; k < n; k++) out[k] = NULL;
    if ((s = check_ratios(ratios, ratio_count, billboard, err))) return s;
    if ((s = banyan_check_int(err, "threads", threads, 0, 1024))) return s;
    if (!mesh) return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh is NULL");
    prog g;
    if ((s = prog_budget_from(&g, budget, err))) return s;
    bb_job bj;
    plat_thread th;
    int running = 0;
    if (billboard) {
        memset(&bj, 0, sizeof bj);
        bj.mesh = mesh;
        bj.p = *billboard;
        if ((s = left_of(&g, &bj.left, err))) return s;
        running = threads != 1 && ratio_count > 0 && plat_thread_start(&th, bb_run, &bj) == 0;
    }
    for (uint32_t k = 0; !s && k < ratio_count; k++) {
        banyan_lod_params p;
        banyan_lod_params_init(&p);
        p.ratio = ratios[0];
        if (k) { /* of the level before's triangles, the share that leaves ratio[k] of the mesh's */
            double r = ratios[k] * ((double)mesh->index_count / (double)(out[k - 1]->index_count ? out[k - 1]->index_count : 1));
            p.ratio = r > 1 ? 1 : r < 0.001 ? 0.001 : r;
        }
        banyan_budget left;
        s = left_of(&g, &left, err);
        if (!s) s = banyan_mesh_lod_budget(k ? out[k - 1] : mesh, &p, &left, &out[k], err);
    }
    if (billboard) {
        if (running) plat_thread_join(&th);
        else if (!s) bb_run(&bj);
        if (!s && bj.s && err) *err = bj.err;
        if (!s) s = bj.s;
        out[n - 1] = bj.out;
    }
    if (s)
        for (uint64_t k = 0; k < n; k++) {
            banyan_mesh_free(out[k]);
            out[k] = NULL;
        }
    return s;
}
