/* lod_internal.h - the pieces of banyan_mesh_lod (csrc/lod/): the wood
 * simplifier (simplify_meshopt.cpp, the one C++ file) and the billboard
 * painter (billboard.c), called by lod.c. */
#ifndef BANYAN_LOD_INTERNAL_H
#define BANYAN_LOD_INTERNAL_H

#include <stdint.h>

#include "banyan.h"
#include "base/progress.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Simplifies one part's triangles toward target_tris. pos/nrm/uv are the
 * part's own vertices (nv of them; nrm and uv may be NULL), idx its ni
 * indices, 0-based within the part. Vertices at one position are welded
 * for the simplifier (tube seams, caps), and each kept corner is mapped
 * back to the member of its weld whose uv and normal fit the triangle,
 * so seams keep their uvs. *out_idx (malloc'd, part-local, into the
 * original vertices) and *out_ni get the result; *used_sloppy says whether
 * the grid fallback ran. Returns 0, or -1 when out of memory. */
int lod_simplify_part(const float *pos, const float *nrm, const float *uv, uint32_t nv, const uint32_t *idx,
                      uint32_t ni, uint32_t target_tris, uint32_t **out_idx, uint32_t *out_ni, int *used_sloppy);

/* Copies origin, skeleton and instances of m into o, and with
 * materials_images its materials and images too. BANYAN_E_NOMEM on
 * failure (o is then the caller's to free). */
banyan_status lod_copy_common(const banyan_mesh *m, banyan_mesh *o, int materials_images);

/* The billboard level (vertical cards and a top card) of `m` (validated by the caller) into *out,
 * checking the call's budget `pg` per tree (group) and card. */
banyan_status lod_billboard(const banyan_mesh *m, const banyan_lod_params *p, prog *pg, banyan_mesh **out,
                            banyan_error *err);

#ifdef __cplusplus
}
#endif
#endif
