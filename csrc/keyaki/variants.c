/* variants.c - instanced avenues (docs/keyaki.md "Variants"):
 * an avenue whose trees are drawn from `variants` distinct keyaki trees
 * placed as instances (banyan_instance), instead of every tree grown and
 * merged (avenue.c).
 *
 * Method. The layout is the unique avenue's (banyan_avenue_layout): the
 * same feet, headings and frame. Variant k is tree k's params (seed + k,
 * its height, size, lean and levels jitter) grown at the frame's origin
 * with heading 0 (its lean direction relative to it), so it stands on its
 * foot, k = 0 .. V - 1 with V = min(variants, tree
 * count). Tree i is shown by variant i when i < V (so the first V trees
 * are the unique avenue's own, turned by their heading), else by a
 * variant drawn uniformly from tree i's own PCG32 stream (seed + i,
 * "variant"): neighbours do not repeat a fixed cycle along the row. The
 * instance stands at tree i's foot (in the mesh's frame) turned by tree
 * i's heading, scaled by tree i's unit over variant k's (so every tree
 * keeps its own size; its lean is the variant's).
 * Parallelism and budget as in the avenue: workers take variant indices
 * from an atomic counter and grow each into its own mesh; the calling
 * thread keeps the budget (max_seconds, max_memory_mb) and the progress
 * callback, the others watch a shared stop flag. The meshes are merged in
 * variant order (parts' group = variant, tree_id = variant), so the bytes
 * do not depend on the thread count. max_vertices covers the variants'
 * vertices, not the instances'. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/big_alloc.h"
#include "base/error.h"
#include "base/frame.h"
#include "base/pool.h"
#include "base/progress.h"
#include "keyaki_internal.h"

#define VARIANT_STREAM 0x76617269616e74ull /* "variant" */
/* Growing the variants is most of the work; merging the rest. */
#define VARIANT_GROW_SHARE 0.95

typedef struct variant_job {
    const banyan_keyaki_params *vars;
    uint32_t n;
    uint64_t max_vertices;
    banyan_mesh **meshes;
    banyan_status *status;
    banyan_error *errs;
    prog *prog;
    atomic_uint next, finished;
    atomic_ullong vertices; /* of the variants grown so far */
    atomic_int cancel;      /* budget spent, cancelled, or a variant failed */
} variant_job;

static void work(variant_job *J, int caller) {
    keyaki_run run = {caller ? J->prog : NULL, &J->cancel, NULL, J->max_vertices, 0, 1, 0}; /* one thread a tree */
    keyaki_skeleton sk = {NULL, 0, 0, &run};
    for (;;) {
        if (atomic_load(&J->cancel)) break;
        uint32_t k = atomic_fetch_add(&J->next, 1u);
        if (k >= J->n) break;
        run.promised = 0;
        J->status[k] = keyaki_build(&J->vars[k], (double)k, k, &sk, &J->meshes[k], &J->errs[k]);
        uint64_t total = 0;
        if (!J->status[k]) total = atomic_fetch_add(&J->vertices, J->meshes[k]->vertex_count) + J->meshes[k]->vertex_count;
        /* A failed variant or a sum past max_vertices ends the run: the
         * answer no longer depends on the others. */
        if (J->status[k] || total > J->max_vertices) atomic_store(&J->cancel, 1);
        unsigned done = atomic_fetch_add(&J->finished, 1u) + 1u;
        if (caller && prog_at(J->prog, VARIANT_GROW_SHARE * done / J->n)) atomic_store(&J->cancel, 1);
    }
    keyaki_skeleton_free(&sk);
}

static void work_any(void *job, int caller) { work(job, caller); }

/* The variants' meshes as one: vertices, indices, parts, skeletons in
 * variant order; materials from variant 0 (every variant has the same). */
static banyan_status merge(banyan_mesh *const *v, uint32_t n, prog *g, banyan_mesh **out, banyan_error *err) {
    const banyan_mesh *a = v[0];
    uint64_t nv = 0, ni = 0, np = 0, ns = 0, ne = 0;
    for (uint32_t k = 0; k < n; k++) {
        const banyan_mesh *m = v[k];
        if (m->attribute_count != a->attribute_count || m->material_count != a->material_count ||
            !m->colors != !a->colors || !m->skel_points != !a->skel_points)
            return banyan_fail(err, BANYAN_E_INTERNAL, "variant %u's mesh differs in layout from variant 0's", k);
        for (uint32_t t = 0; t < m->attribute_count; t++)
            if (strcmp(m->attributes[t].name, a->attributes[t].name))
                return banyan_fail(err, BANYAN_E_INTERNAL, "variant %u's attribute %u is %s, variant 0's %s", k, t,
                                   m->attributes[t].name, a->attributes[t].name);
        nv += m->vertex_count;
        ni += m->index_count;
        np += m->part_count;
        ns += m->skel_point_count;
        ne += m->skel_edge_count;
    }
    if (ni > 0xFFFFFFF0u || nv > MB_VERTEX_CEILING)
        return banyan_fail(err, BANYAN_E_LIMIT, "the variants need %llu vertices and %llu indices together; lower variants",
                           (unsigned long long)nv, (unsigned long long)ni);
    /* more than tree_id, level, order and birth: the wind attributes */
    if (prog_reserve(g, keyaki_mesh_bytes(nv, ni, a->attribute_count > 4))) return prog_fail(g, err, "avenue");
    banyan_mesh *o = calloc(1, sizeof *o);
    if (!o) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the avenue's variants");
    o->vertex_count = (uint32_t)nv;
    o->index_count = (uint32_t)ni;
    o->positions = big_malloc(sizeof(float) * 3 * nv);
    o->normals = big_malloc(sizeof(float) * 3 * nv);
    o->uvs = big_malloc(sizeof(float) * 2 * nv);
    o->colors = a->colors ? big_malloc(sizeof(float) * 4 * nv) : NULL;
    o->indices = big_malloc(sizeof(uint32_t) * (ni ? ni : 1));
    o->attribute_count = a->attribute_count;
    o->attributes = calloc(a->attribute_count ? a->attribute_count : 1, sizeof(banyan_attribute));
    o->material_count = a->material_count;
    o->materials = malloc(sizeof(banyan_material) * (a->material_count ? a->material_count : 1));
    o->part_count = (uint32_t)np;
    o->parts = malloc(sizeof(banyan_part) * (np ? np : 1));
    o->skel_point_count = (uint32_t)ns;
    o->skel_edge_count = (uint32_t)ne;
    if (a->skel_points) {
        o->skel_points = malloc(sizeof(float) * 3 * (ns ? ns : 1));
        o->skel_radius = malloc(sizeof(float) * (ns ? ns : 1));
        o->skel_tag = malloc(sizeof(int32_t) * (ns ? ns : 1));
        o->skel_edges = malloc(sizeof(uint32_t) * 2 * (ne ? ne : 1));
    }
    int ok = o->positions && o->normals && o->uvs && (o->colors || !a->colors) && o->indices && o->attributes &&
             o->materials && o->parts &&
             (!a->skel_points || (o->skel_points && o->skel_radius && o->skel_tag && o->skel_edges));
    for (uint32_t t = 0; ok && t < a->attribute_count; t++) {
        memcpy(o->attributes[t].name, a->attributes[t].name, BANYAN_NAME_MAX);
        if (!(o->attributes[t].data = big_malloc(sizeof(float) * (nv ? nv : 1)))) ok = 0;
    }
    if (!ok) {
        banyan_mesh_free(o);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the avenue's %llu variant vertices",
                           (unsigned long long)nv);
    }
    memcpy(o->materials, a->materials, sizeof(banyan_material) * a->material_count);
    uint64_t V = 0, I = 0, P = 0, S = 0, E = 0;
    for (uint32_t k = 0; k < n; k++) {
        const banyan_mesh *m = v[k];
        size_t c = m->vertex_count;
        memcpy(o->positions + 3 * V, m->positions, sizeof(float) * 3 * c);
        memcpy(o->normals + 3 * V, m->normals, sizeof(float) * 3 * c);
        memcpy(o->uvs + 2 * V, m->uvs, sizeof(float) * 2 * c);
        if (o->colors) memcpy(o->colors + 4 * V, m->colors, sizeof(float) * 4 * c);
        for (uint32_t t = 0; t < m->attribute_count; t++)
            memcpy(o->attributes[t].data + V, m->attributes[t].data, sizeof(float) * c);
        for (uint32_t i = 0; i < m->index_count; i++) o->indices[I + i] = m->indices[i] + (uint32_t)V;
        for (uint32_t i = 0; i < m->part_count; i++) {
            banyan_part q = m->parts[i];
            q.vertex_offset += (uint32_t)V;
            q.index_offset += (uint32_t)I;
            q.group = k; /* keyaki_build set it; the variant by contract */
            o->parts[P + i] = q;
        }
        if (o->skel_points) {
            memcpy(o->skel_points + 3 * S, m->skel_points, sizeof(float) * 3 * m->skel_point_count);
            memcpy(o->skel_radius + S, m->skel_radius, sizeof(float) * m->skel_point_count);
            memcpy(o->skel_tag + S, m->skel_tag, sizeof(int32_t) * m->skel_point_count);
            for (uint32_t i = 0; i < 2 * m->skel_edge_count; i++) o->skel_edges[2 * E + i] = m->skel_edges[i] + (uint32_t)S;
        }
        V += c;
        I += m->index_count;
        P += m->part_count;
        S += m->skel_point_count;
        E += m->skel_edge_count;
    }
    *out = o;
    return BANYAN_OK;
}

banyan_status avenue_variants_generate(const banyan_avenue_params *p, const double *path_xyz, uint32_t path_point_count,
                                       banyan_mesh **out, const banyan_progress *progress, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    banyan_status s;
    if ((s = banyan_check_int(err, "threads", p->threads, 0, BANYAN_AVENUE_MAX_THREADS))) return s;
    if ((s = prog_check(progress, err))) return s;
    uint32_t n = 0;
    if ((s = banyan_avenue_layout(p, path_xyz, path_point_count, NULL, 0, &n, err))) return s;
    if (n == 0) return banyan_fail(err, BANYAN_E_RANGE, "the path is too short for any tree");
    if ((s = banyan_check_int(err, "variants", p->variants, 1, BANYAN_AVENUE_MAX_VARIANTS))) return s;
    const uint32_t nv = (uint32_t)p->variants < n ? (uint32_t)p->variants : n;

    variant_job J;
    memset(&J, 0, sizeof J);
    prog g;
    prog_init(&g, progress);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    J.prog = &g;
    banyan_mesh *merged = NULL;
    banyan_keyaki_params *trees = malloc(sizeof *trees * n);
    banyan_keyaki_params *vars = malloc(sizeof *vars * nv);
    J.meshes = calloc(nv, sizeof *J.meshes);
    J.status = calloc(nv, sizeof *J.status);
    J.errs = calloc(nv, sizeof *J.errs);
    banyan_instance *inst = malloc(sizeof *inst * n);
    if (!trees || !vars || !J.meshes || !J.status || !J.errs || !inst) {
        s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u trees", n);
        goto done;
    }
    if ((s = banyan_avenue_layout(p, path_xyz, path_point_count, trees, n, &n, err))) goto done;
    /* The unique avenue's frame, from the trees' feet (avenue.c). */
    v3 lo, hi, O;
    frame_empty(&lo, &hi);
    for (uint32_t i = 0; i < n; i++) frame_add(&lo, &hi, v3_load(trees[i].position));
    O = frame_pick(lo, hi);
    if ((s = frame_check(lo, hi, O, path_xyz ? "the path's trees" : "the trees from start to end", err))) goto done;
    for (uint32_t k = 0; k < nv; k++) {
        vars[k] = trees[k];
        vars[k].position[0] = vars[k].position[1] = vars[k].position[2] = 0.0;
        vars[k].heading = 0.0;
    }
    for (uint32_t i = 0; i < n; i++) {
        uint32_t k = i;
        if (i >= nv) {
            pcg32 r;
            pcg32_seed(&r, p->seed + i, VARIANT_STREAM);
            k = rng_below(&r, nv);
        }
        inst[i].variant = k;
        for (int c = 0; c < 3; c++) inst[i].translation[c] = (float)(trees[i].position[c] - (&O.x)[c]);
        inst[i].rotation_z = (float)deg2rad(trees[i].heading);
        /* Tree i's size (scale_jitter) on whichever variant shows it. */
        inst[i].scale = (float)(trees[i].unit / trees[k].unit);
    }

    int t = pool_threads(p->threads, BANYAN_AVENUE_MAX_THREADS);
    if ((uint32_t)t > nv) t = (int)nv;
    J.vars = vars;
    J.n = nv;
    J.max_vertices = (uint64_t)p->max_vertices;
    pool_run(t, work_any, &J, J.prog, &J.cancel);
    /* Which variants ran depends on the threads; the status does not: the
     * budget or a cancel first, then a failed variant (its own limit or
     * memory), then the sum past max_vertices. */
    if (prog_stopped(&g)) {
        s = prog_fail(&g, err, "avenue");
        goto done;
    }
    for (uint32_t k = 0; k < nv; k++)
        if (J.status[k] && J.status[k] != BANYAN_E_CANCELLED) {
            s = banyan_fail(err, J.status[k], "variant %u (tree %u): %s", k, k, J.errs[k].message);
            goto done;
        }
    if (atomic_load(&J.cancel)) {
        s = banyan_fail(err, BANYAN_E_LIMIT,
                        "the avenue's %u variants need more than max_vertices = %d vertices (at least %llu grown "
                        "before stopping); raise max_vertices or lower variants, tree.leaf_density, tree.sides_max or "
                        "tree.levels",
                        nv, p->max_vertices, (unsigned long long)atomic_load(&J.vertices));
        goto done;
    }
    if ((s = merge(J.meshes, nv, &g, &merged, err))) goto done;
    for (uint32_t k = 0; k < nv; k++) {
        banyan_mesh_free(J.meshes[k]);
        J.meshes[k] = NULL;
    }
    merged->instances = inst;
    merged->instance_count = n;
    inst = NULL;
    if (prog_finish(&g)) {
        s = prog_fail(&g, err, "avenue");
        goto done;
    }
    frame_set(merged, O);
    *out = merged;
    merged = NULL;
    banyan_error_clear(err);
done:
    banyan_mesh_free(merged);
    for (uint32_t k = 0; J.meshes && k < nv; k++) banyan_mesh_free(J.meshes[k]);
    free(J.meshes);
    free(J.status);
    free(J.errs);
    free(trees);
    free(vars);
    free(inst);
    return s;
}
