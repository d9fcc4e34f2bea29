/* Levels of detail (docs/game-engines.md "Levels of detail").
 * banyan_mesh_lod makes a coarser copy of any generator's mesh: wood is
 * simplified with meshoptimizer, leaves are thinned whole (survivors grow
 * about their petiole so the leaf area stays), or, with `billboard`, the
 * plant becomes vertical cards and a top card carrying pictures of it
 * drawn by the library (an image of the output mesh). */
#ifndef BANYAN_LOD_H
#define BANYAN_LOD_H
#include <stddef.h>
#include <stdint.h>

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct banyan_lod_params {
    double ratio;             /* share of the triangles kept, 0.001 .. 1. Default 0.5 */
    int32_t billboard;        /* bool: cards (vertical ones and a top one) instead (ratio ignored). Default 0 */
    int32_t billboard_planes; /* vertical cards about the plant's axis (a top card is added), 2 .. 8. Default 3 */
    int32_t billboard_size;   /* pixels of the picture's longer side: a power of two, 32 .. 4096. Default 256 */
    int32_t reserved;
    uint64_t seed;            /* which leaves stay. Default 1 */
} banyan_lod_params;

BANYAN_API void banyan_lod_params_init(banyan_lod_params *p);
BANYAN_API size_t banyan_sizeof_lod_params(void);

/* A coarser copy of `mesh` (any generator's, an avenue's too; instances and
 * images are carried over): about ratio * its triangles (within 10 %
 * where the simplifier can reach it), the same parts, materials, groups,
 * attributes (wind, birth) and origin, and a bounding box within 5 % of
 * the original's. *out is the caller's to free with banyan_mesh_free; on
 * failure *out is NULL. */
BANYAN_API banyan_status banyan_mesh_lod(const banyan_mesh *mesh, const banyan_lod_params *p, banyan_mesh **out,
                                         banyan_error *err);
/* banyan_mesh_lod under a budget (banyan.h, banyan_budget; NULL: the
 * defaults, which banyan_mesh_lod uses): checked between parts (the
 * simplifier runs one part at a time) and between the billboards' trees
 * and cards; past it BANYAN_E_LIMIT naming max_seconds or max_memory_mb. */
BANYAN_API banyan_status banyan_mesh_lod_budget(const banyan_mesh *mesh, const banyan_lod_params *p,
                                                const banyan_budget *budget, banyan_mesh **out, banyan_error *err);

/* The most levels banyan_mesh_lods makes in one call (ratios and the
 * billboard together). */
#define BANYAN_LOD_MAX_LEVELS 7

/* A plant's levels of detail in one call: out[k] for each of the falling
 * ratios[0 .. ratio_count) (each within [0.001, 1), below the one
 * before), each simplified from the level before it so it keeps about
 * ratios[k] of mesh's triangles, then, when billboard is not NULL (its
 * `billboard` 1), the billboard level of mesh in out[ratio_count]. out
 * holds ratio_count + (billboard ? 1 : 0) pointers, each the caller's to
 * free with banyan_mesh_free; on failure every one is NULL (none is
 * written when ratio_count is out of range). threads: 1
 * draws the billboard after the chain, any other value beside it (0 =
 * the same as 2); the levels are the same bytes either way. budget
 * (NULL: the defaults) covers the whole call. */
BANYAN_API banyan_status banyan_mesh_lods(const banyan_mesh *mesh, const double *ratios, uint32_t ratio_count,
                                          const banyan_lod_params *billboard, int32_t threads,
                                          const banyan_budget *budget, banyan_mesh **out, banyan_error *err);

#ifdef __cplusplus
}
#endif
#endif
