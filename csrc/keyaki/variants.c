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
 * The variants are built as the unique avenue's trees are (avenue_build:
 * sized first, then each built straight into its slice of one mesh, in
 * parallel), in variant order (parts' group = variant, tree_id =
 * variant), so the bytes do not depend on the thread count. max_vertices
 * covers the variants' vertices, not the instances'. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "base/progress.h"
#include "keyaki_internal.h"

#define VARIANT_STREAM 0x76617269616e74ull /* "variant" */

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

    prog g;
    prog_init(&g, progress);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    banyan_mesh *merged = NULL;
    banyan_keyaki_params *trees = malloc(sizeof *trees * n);
    banyan_keyaki_params *vars = malloc(sizeof *vars * nv);
    banyan_instance *inst = malloc(sizeof *inst * n);
    if (!trees || !vars || !inst) {
        s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u trees", n);
        goto done;
    }
    if ((s = banyan_avenue_layout(p, path_xyz, path_point_count, trees, n, &n, err))) goto done;
    v3 O; /* the unique avenue's frame, from the trees' feet */
    if ((s = avenue_frame(trees, n, path_xyz != NULL, &O, err))) goto done;
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
    if ((s = avenue_build(vars, nv, p->threads, p->max_vertices, O, &g, "variants",
                          "variants, tree.leaf_density, tree.sides_max or tree.levels", &merged, err)))
        goto done;
    merged->instances = inst;
    merged->instance_count = n;
    inst = NULL;
    *out = merged;
    merged = NULL;
    banyan_error_clear(err);
done:
    banyan_mesh_free(merged);
    free(trees);
    free(vars);
    free(inst);
    return s;
}
