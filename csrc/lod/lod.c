/* lod.c - levels of detail (banyan/lod.h; issue #22). Contract stub: the
 * LOD work replaces it. */
#include <string.h>

#include "banyan.h"
#include "core/error.h"

void banyan_lod_params_init(banyan_lod_params *p) {
    if (!p) return;
    memset(p, 0, sizeof *p);
    p->ratio = 0.5;
    p->billboard = 0;
    p->billboard_planes = 2;
    p->billboard_size = 256;
    p->seed = 1;
}

size_t banyan_sizeof_lod_params(void) { return sizeof(banyan_lod_params); }

banyan_status banyan_mesh_lod(const banyan_mesh *mesh, const banyan_lod_params *p, banyan_mesh **out,
                              banyan_error *err) {
    if (out) *out = NULL;
    (void)mesh; (void)p;
    return banyan_fail(err, BANYAN_E_INTERNAL, "banyan_mesh_lod is not built yet");
}
