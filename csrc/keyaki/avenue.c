/* avenue.c - keyaki avenues (spec/keyaki.md, "Avenues"): trees placed
 * along a line or polyline in one or two rows, each with its own seed
 * (base seed + index), a random heading and jitter of trunk height,
 * position, size (unit), lean and (for mixed ages) levels, grown in
 * parallel on the library's thread pool (base/pool.c).
 *
 * Layout (banyan_avenue_layout, avenue_layout.c): where the trees stand.
 * Parallelism: workers take tree indices from an atomic counter; tree i
 * draws only from its own PCG32 streams (seed + i) and is meshed straight
 * into its own slice of the merged mesh and skeleton; slices follow index
 * order, so the bytes never depend on the thread
 * count or on scheduling. A first parallel pass sizes every tree exactly
 * (vertices, indices, parts, skeleton), so max_vertices is checked and
 * the merged arrays are allocated once, before any mesh is built. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/big_alloc.h"
#include "base/error.h"
#include "base/frame.h"
#include "base/pool.h"
#include "base/progress.h"
#include "keyaki_internal.h"

#define AVENUE_ATTRS 11 /* the merged mesh's attributes with wind (alloc_merged) */

/* ------------------------------------------------------------ workers */

typedef struct avenue_job {
    const banyan_keyaki_params *trees;
    uint32_t n;
    int phase; /* 0: count, 1: build and copy into out */
    atomic_uint next;
    keyaki_counts *counts;
    uint64_t *voff, *ioff, *soff, *poff, *eoff; /* where tree i goes in out (skeleton points soff, edges eoff) */
    banyan_mesh *out;
    banyan_status *status;
    banyan_error *errs;
    /* Pass 1 stops early once a tree fails or the trees counted so far
     * pass max_vertices: the answer is then BANYAN_E_LIMIT either way, and
     * thousands of trees are not grown for nothing. */
    uint64_t max_vertices;
    atomic_ullong counted; /* vertices of the trees counted so far, and promised by those growing (keyaki_run) */
    atomic_int stop;
    /* Progress and budget: the calling thread, itself a worker, keeps the
     * budget inside its trees and, once its own work is done, while it
     * waits for the others; it reports the trees finished by all after
     * each tree it finishes. A cancel or a spent budget sets `cancel`,
     * which every worker's tree watches in its loops. */
    prog *prog;
    atomic_uint finished; /* trees of this pass done */
    atomic_int cancel;
    double base, share;   /* this pass's part of the fraction */
} avenue_job;

/* Building, each thread holds one tree's skeleton, crown and body plan:
 * about this many bytes a vertex of its tree (measured: 22-30 on
 * avenue_boulevard and the default avenue). Threads beyond the first are
 * used only while their scratch stays within AVENUE_SCRATCH_SHARE of the
 * merged mesh, so the peak does not multiply with --threads. */
#define AVENUE_SCRATCH_PER_VERTEX 32.0
#define AVENUE_SCRATCH_SHARE 0.15

/* Sizing a tree grows its skeleton; building grows it again and meshes
 * it: the count pass's part of the time (bench_progress, 100 trees). */
#define AVENUE_COUNT_SHARE 0.06

/* Builds tree i straight into its slice of the merged mesh and skeleton
 * (sized by the count pass: nothing is copied, no page is touched twice),
 * then offsets its indices, parts and skeleton edges to their merged
 * places. Slices
 * are disjoint, so workers write in parallel without locks. */
static banyan_status build_in_place(avenue_job *J, uint32_t i, keyaki_skeleton *sk, banyan_error *err) {
    banyan_mesh *o = J->out;
    const keyaki_counts *c = &J->counts[i];
    uint64_t v = J->voff[i], x = J->ioff[i], s = J->soff[i], e = J->eoff[i], pp = J->poff[i];
    float *attr[AVENUE_ATTRS];
    const char *names[AVENUE_ATTRS];
    uint32_t na = o->attribute_count < AVENUE_ATTRS ? o->attribute_count : AVENUE_ATTRS;
    for (uint32_t a = 0; a < na; a++) {
        attr[a] = o->attributes[a].data + v;
        names[a] = o->attributes[a].name;
    }
    mesh_builder mb;
    mb_init_external(&mb, c->vertices, c->indices, o->positions + 3 * v, o->normals + 3 * v, o->uvs + 2 * v,
                     o->colors + 4 * v, o->indices + x, attr, names, na);
    mb_external_skeleton(&mb, o->skel_points + 3 * s, o->skel_radius + s, o->skel_tag + s, c->skel_points,
                         o->skel_edges + 2 * e, c->skel_edges);
    banyan_status st = keyaki_build_into(&J->trees[i], (double)i, i, sk, &mb, err);
    if (!st && !mb.status) mb_close(&mb);
    if (!st && mb.status) st = mb_fail(&mb, err);
    if (!st && (mb.nv != c->vertices || mb.ni != c->indices || mb.n_part != c->parts || mb.n_skel != c->skel_points ||
                mb.n_edge != c->skel_edges || mb.n_attr != o->attribute_count))
        st = banyan_fail(err, BANYAN_E_INTERNAL, "planned and built sizes differ");
    if (!st) {
        uint32_t *I = o->indices + x;
        for (uint32_t k = 0; k < mb.ni; k++) I[k] += (uint32_t)v;
        for (uint32_t k = 0; k < mb.n_part; k++) {
            banyan_part q = mb.part[k];
            q.vertex_offset += (uint32_t)v;
            q.index_offset += (uint32_t)x;
            o->parts[pp + k] = q;
        }
        uint32_t *E = o->skel_edges + 2 * e; /* built in place, numbered from the tree's first point */
        for (uint32_t k = 0; k < 2 * mb.n_edge; k++) E[k] += (uint32_t)s;
        if (i == 0) memcpy(o->materials, mb.mat, sizeof(banyan_material) * o->material_count);
    }
    mb_free(&mb);
    return st;
}

static void work(avenue_job *J, int caller) {
    /* Counting, every tree promises into J->counted what it is sure to
     * need while it grows, so the refusal comes at the same total on any
     * number of threads, each tree stopped part way. */
    keyaki_run run = {caller ? J->prog : NULL, &J->cancel, J->phase == 0 ? &J->counted : NULL,
                      J->phase == 0 ? J->max_vertices : UINT64_MAX, 0, 1, 0}; /* one thread a tree */
    keyaki_skeleton sk = {NULL, 0, 0, &run};
    for (;;) {
        if (atomic_load(&J->cancel)) break;
        uint32_t i = atomic_fetch_add(&J->next, 1u);
        if (i >= J->n) break;
        if (J->phase == 0) {
            if (atomic_load(&J->stop)) break;
            run.promised = 0;
            J->status[i] = keyaki_count(&J->trees[i], &sk, &J->counts[i], &J->errs[i]);
            uint64_t v = J->counts[i].vertices, total = 0;
            if (!J->status[i] && v >= run.promised)
                total = atomic_fetch_add(&J->counted, v - run.promised) + (v - run.promised);
            else if (!J->status[i])
                total = atomic_fetch_sub(&J->counted, run.promised - v) - (run.promised - v);
            if (J->status[i] || total > J->max_vertices) atomic_store(&J->stop, 1);
        } else {
            J->status[i] = build_in_place(J, i, &sk, &J->errs[i]);
        }
        unsigned done = atomic_fetch_add(&J->finished, 1u) + 1u;
        if (caller && J->prog && prog_at(J->prog, J->base + J->share * done / J->n)) atomic_store(&J->cancel, 1);
    }
    keyaki_skeleton_free(&sk);
}

static void work_any(void *job, int caller) { work(job, caller); }

/* Runs one pass on `threads` threads (base/pool.h). */
static void run_job(avenue_job *J, int threads) {
    atomic_store(&J->next, 0u);
    atomic_store(&J->finished, 0u);
    pool_run(threads, work_any, J, J->prog, &J->cancel);
}

/* The merged mesh's arrays, sized exactly; NULL when out of memory. The
 * attributes as keyaki_build_into declares them: tree_id, level, order,
 * birth, then with wind the seven wind ones. */
static banyan_mesh *alloc_merged(uint64_t nv, uint64_t ni, uint64_t ns, uint64_t ne, uint64_t np, int wind) {
    static const char *const attrs[AVENUE_ATTRS] = {
        "tree_id", "level", "order", BANYAN_ATTR_BIRTH, BANYAN_ATTR_WIND_PIVOT_X, BANYAN_ATTR_WIND_PIVOT_Y,
        BANYAN_ATTR_WIND_PIVOT_Z, BANYAN_ATTR_WIND_LEVEL, BANYAN_ATTR_WIND_STIFFNESS, BANYAN_ATTR_WIND_PHASE,
        BANYAN_ATTR_WIND_FLUTTER};
    const uint32_t na = wind ? AVENUE_ATTRS : 4;
    banyan_mesh *o = calloc(1, sizeof *o);
    if (!o) return NULL;
    o->vertex_count = (uint32_t)nv;
    o->index_count = (uint32_t)ni;
    o->positions = big_malloc(sizeof(float) * 3 * nv);
    o->normals = big_malloc(sizeof(float) * 3 * nv);
    o->uvs = big_malloc(sizeof(float) * 2 * nv);
    o->colors = big_malloc(sizeof(float) * 4 * nv);
    o->indices = big_malloc(sizeof(uint32_t) * ni);
    o->attribute_count = na;
    o->attributes = calloc(na, sizeof(banyan_attribute));
    o->material_count = 2;
    o->materials = calloc(2, sizeof(banyan_material));
    o->part_count = (uint32_t)np;
    o->parts = malloc(sizeof(banyan_part) * np);
    o->skel_point_count = (uint32_t)ns;
    o->skel_points = big_malloc(sizeof(float) * 3 * ns);
    o->skel_radius = big_malloc(sizeof(float) * ns);
    o->skel_tag = big_malloc(sizeof(int32_t) * ns);
    o->skel_edge_count = (uint32_t)ne;
    o->skel_edges = big_malloc(sizeof(uint32_t) * 2 * ne);
    int ok = o->positions && o->normals && o->uvs && o->colors && o->indices && o->attributes && o->materials && o->parts &&
             o->skel_points && o->skel_radius && o->skel_tag && o->skel_edges;
    for (uint32_t a = 0; ok && a < na; a++) {
        strcpy(o->attributes[a].name, attrs[a]);
        if (!(o->attributes[a].data = big_malloc(sizeof(float) * nv))) ok = 0;
    }
    if (!ok) {
        banyan_mesh_free(o);
        return NULL;
    }
    return o;
}

banyan_status avenue_frame(const banyan_keyaki_params *trees, uint32_t n, int on_path, v3 *O, banyan_error *err) {
    v3 lo, hi;
    frame_empty(&lo, &hi);
    for (uint32_t i = 0; i < n; i++) frame_add(&lo, &hi, v3_load(trees[i].position));
    *O = frame_pick(lo, hi);
    return frame_check(lo, hi, *O, on_path ? "the path's trees" : "the trees from start to end", err);
}

banyan_status avenue_build(const banyan_keyaki_params *trees, uint32_t n, int threads, int max_vertices, v3 origin,
                           prog *g, const char *what, const char *lower, banyan_mesh **out, banyan_error *err) {
    *out = NULL;
    banyan_status s = BANYAN_OK;
    avenue_job J;
    memset(&J, 0, sizeof J);
    J.prog = g;
    atomic_store(&J.cancel, 0);
    J.counts = calloc(n, sizeof *J.counts);
    J.voff = calloc(5 * (size_t)n, sizeof *J.voff);
    J.status = calloc(n, sizeof *J.status);
    J.errs = calloc(n, sizeof *J.errs);
    if (!J.counts || !J.voff || !J.status || !J.errs) {
        s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u %s", n, what);
        goto done;
    }
    J.ioff = J.voff + n;
    J.soff = J.ioff + n;
    J.poff = J.soff + n;
    J.eoff = J.poff + n;
    J.trees = trees;
    J.n = n;
    const int wind = trees[0].wind;
    int t = pool_threads(threads, BANYAN_AVENUE_MAX_THREADS);
    if ((uint32_t)t > n) t = (int)n;

    /* Pass 1: exact sizes of every tree, before any mesh memory. */
    J.phase = 0;
    J.max_vertices = (uint64_t)max_vertices;
    atomic_store(&J.counted, 0ull);
    atomic_store(&J.stop, 0);
    J.base = 0.0;
    J.share = AVENUE_COUNT_SHARE;
    run_job(&J, t);
    if (atomic_load(&J.cancel)) {
        s = prog_fail(J.prog, err, "avenue");
        goto done;
    }
    if (atomic_load(&J.stop)) {
        /* Which trees were counted depends on the threads; the status does
         * not: a failed count is a limit (or out of memory), and so is a
         * sum past max_vertices. */
        for (uint32_t i = 0; i < n; i++)
            if (J.status[i]) {
                s = banyan_fail(err, J.status[i], "tree %u: %s", i, J.errs[i].message);
                goto done;
            }
        s = banyan_fail(err, BANYAN_E_LIMIT,
                        "the avenue's %u %s need more than max_vertices = %d vertices (at least %llu counted "
                        "before stopping); raise max_vertices or lower %s",
                        n, what, max_vertices, (unsigned long long)atomic_load(&J.counted), lower);
        goto done;
    }
    uint64_t nv = 0, ni = 0, ns = 0, ne = 0, np = 0, vmax = 1;
    for (uint32_t i = 0; i < n; i++) {
        if (J.counts[i].vertices > vmax) vmax = J.counts[i].vertices;
        if (J.status[i]) {
            s = banyan_fail(err, J.status[i], "tree %u: %s", i, J.errs[i].message);
            goto done;
        }
        J.voff[i] = nv;
        J.ioff[i] = ni;
        J.soff[i] = ns;
        J.poff[i] = np;
        J.eoff[i] = ne;
        nv += J.counts[i].vertices;
        ni += J.counts[i].indices;
        ns += J.counts[i].skel_points;
        ne += J.counts[i].skel_edges;
        np += J.counts[i].parts;
    }
    if (nv > (uint64_t)max_vertices || ni > 0xFFFFFFF0u || ns > 0xFFFFFFF0u || ne > 0xFFFFFFF0u) {
        s = banyan_fail(err, BANYAN_E_LIMIT,
                        "the avenue's %u %s need %llu vertices, more than max_vertices = %d; raise max_vertices or "
                        "lower %s",
                        n, what, (unsigned long long)nv, max_vertices, lower);
        goto done;
    }
    /* Pass 2: every tree built straight into its slice, in parallel. */
    if (prog_reserve(g, keyaki_mesh_bytes(nv, ni, wind))) {
        s = prog_fail(g, err, "avenue");
        goto done;
    }
    J.out = alloc_merged(nv, ni, ns, ne, np, wind);
    if (!J.out) {
        s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the avenue's %llu vertices", (unsigned long long)nv);
        goto done;
    }
    double extra = AVENUE_SCRATCH_SHARE * keyaki_mesh_bytes(nv, ni, wind) / (AVENUE_SCRATCH_PER_VERTEX * (double)vmax);
    if (t - 1 > extra) t = 1 + (int)extra;
    J.phase = 1;
    J.base = AVENUE_COUNT_SHARE;
    J.share = 1.0 - AVENUE_COUNT_SHARE;
    run_job(&J, t);
    if (atomic_load(&J.cancel)) {
        s = prog_fail(J.prog, err, "avenue");
        goto done;
    }
    for (uint32_t i = 0; i < n; i++) {
        if (J.status[i]) {
            s = banyan_fail(err, J.status[i], "tree %u: %s", i, J.errs[i].message);
            goto done;
        }
    }
    if (prog_finish(J.prog)) {
        s = prog_fail(J.prog, err, "avenue");
        goto done;
    }
    frame_set(J.out, origin);
    *out = J.out;
    J.out = NULL;
done:
    banyan_mesh_free(J.out);
    free(J.counts);
    free(J.voff);
    free(J.status);
    free(J.errs);
    return s;
}

banyan_status banyan_avenue_generate(const banyan_avenue_params *p, const double *path_xyz, uint32_t path_point_count,
                                     banyan_mesh **out, const banyan_progress *progress, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    if (p->variants > 0) /* instanced: variants.c */
        return avenue_variants_generate(p, path_xyz, path_point_count, out, progress, err);
    banyan_status s;
    if ((s = banyan_check_int(err, "threads", p->threads, 0, BANYAN_AVENUE_MAX_THREADS))) return s;
    if ((s = prog_check(progress, err))) return s;
    uint32_t n = 0;
    if ((s = banyan_avenue_layout(p, path_xyz, path_point_count, NULL, 0, &n, err))) return s;
    if (n == 0) return banyan_fail(err, BANYAN_E_RANGE, "the path is too short for any tree");
    prog g;
    prog_init(&g, progress);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    banyan_mesh *m = NULL;
    banyan_keyaki_params *trees = malloc(sizeof *trees * n);
    if (!trees) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u trees", n);
    if ((s = banyan_avenue_layout(p, path_xyz, path_point_count, trees, n, &n, err))) goto done;
    /* The trees grow in a frame picked from their feet (base/frame.h). */
    v3 O;
    if ((s = avenue_frame(trees, n, path_xyz != NULL, &O, err))) goto done;
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) trees[i].position[k] -= (&O.x)[k];
    if ((s = avenue_build(trees, n, p->threads, p->max_vertices, O, &g, "trees",
                          "tree.leaf_density, tree.sides_max, tree.levels or the tree count", &m, err)))
        goto done;
    *out = m;
    m = NULL;
    banyan_error_clear(err);
done:
    banyan_mesh_free(m);
    free(trees);
    return s;
}
