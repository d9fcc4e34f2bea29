/* pp2.h - Pivot Painter 2 elements of a mesh (banyan/pivot_painter.h
 * says how they are made): the table both the textures
 * (banyan_pivot_painter_write) and the glTF writer's UV set
 * (banyan_gltf_options.pivot_painter) come from. */
#ifndef BANYAN_PP2_H
#define BANYAN_PP2_H

#include "banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pp2_table {
    uint32_t vertex_count;
    uint32_t *texel;      /* per vertex: its element's texel (the element's index) */
    uint32_t elements;    /* texels in use */
    uint32_t merged;      /* elements merged into their ancestor on the last level kept */
    uint32_t width, height;
    uint32_t depth;       /* levels in use, root to deepest element, 1 .. 4 */
    float *pivot;         /* 3 per element, the mesh's frame (metres) */
    float *axis;          /* 3 per element, unit, the mesh's frame */
    float *extent;        /* per element, metres along axis */
    uint32_t *parent;     /* per element; a root names itself */
} pp2_table;

/* The elements of m. `what` names the mesh in messages ("mesh"). On
 * failure *t is cleared. */
banyan_status pp2_build(const banyan_mesh *m, const char *what, pp2_table *t, banyan_error *err);
void pp2_free(pp2_table *t);
/* The centre of texel k in glTF's (and Unreal's) uv: v runs down the image. */
void pp2_texel_uv(const pp2_table *t, uint32_t k, float uv[2]);

#ifdef __cplusplus
}
#endif
#endif
