/*
 * banyan/pivot_painter.h - Unreal Engine's Pivot Painter 2 textures
 * (docs/game-engines.md "Unreal Engine and Pivot Painter 2"). Included by
 * banyan.h.
 *
 * A mesh with the wind attributes (banyan.h: wind_pivot_x/y/z,
 * wind_level, wind_phase; wind_flutter when present) is cut into
 * elements, the sub-objects Pivot Painter 2 animates:
 *   - an element is the set of vertices of one part group (an avenue's
 *     tree) that share pivot, level and phase: the trunk, a branch, a
 *     twig, a leaf;
 *   - its parent is the element of the wood vertex (wind_flutter 0) of a
 *     lower level, in the same group, nearest to its pivot (ties: the
 *     lowest vertex index); a level 0 element, or one with no such
 *     vertex, is a root;
 *   - PivotPainter2FoliageShader follows at most four levels (an element
 *     and three ancestors), so the hierarchy keeps four levels, or the
 *     most of three, two, one whose elements fit the
 *     BANYAN_PP2_MAX_ELEMENTS texels a parent index can name; an element
 *     deeper than that is merged into its ancestor on the last level kept:
 *     its vertices move with that branch (and read its texel);
 *   - the elements left are numbered in the order of their first vertex;
 *     element i is texel (i % width, i / width), rows top to bottom.
 * Two textures, the layout of the Pivot Painter 2 MAXScript's defaults:
 *   <prefix>_PivotPos_Index.exr  half-float RGBA OpenEXR: RGB the pivot in
 *       Unreal's axes, (x, -y, z) * scale from the mesh's frame (Z up,
 *       relative to the mesh's origin; scale 100: centimetres), A the
 *       parent's index as Pivot Painter's "integer as float": the half
 *       whose bits are 1024 + index (a root names itself);
 *   <prefix>_XVector_Extent.png  8-bit RGBA PNG: RGB the element's X axis
 *       (from its pivot to its own vertex farthest from it; +Z when all
 *       sit on the pivot), in Unreal's axes, as 0.5 + 0.5 * axis; A its
 *       extent along that axis over every vertex it draws (merged ones
 *       too) in the same units, divided by 2048 (Unreal's
 *       ms_PivotPainter2_Decode8BitAlphaAxisExtent reads max(8, A * 2048)).
 * The texture is width x height texels, both powers of two: width the
 * smallest with width^2 >= elements, height the smallest with
 * width * height >= elements. Texels past the last element hold a root at
 * the origin pointing up with extent 0. The glTF writer's
 * opt->pivot_painter = 1 writes each vertex's texel centre as a UV set
 * (banyan.h, banyan_gltf_options).
 */
#ifndef BANYAN_PIVOT_PAINTER_H
#define BANYAN_PIVOT_PAINTER_H

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Pivot Painter's parent index is a half float's bits less 1024: at most
 * 30720 elements (0x7C00 - 1024) fit. */
#define BANYAN_PP2_MAX_ELEMENTS 30720

/* How banyan_pivot_painter_write writes; all zeros means the defaults. */
typedef struct banyan_pivot_painter_options {
    double scale;   /* texture units per metre, in (0, 10000]; 0: 100 (Unreal's centimetres) */
    int32_t sync;   /* 0/1: fsync each file before renaming it over its target. Default 0 */
} banyan_pivot_painter_options;

/* What was written. */
typedef struct banyan_pivot_painter_info {
    uint32_t elements;  /* texels in use */
    uint32_t merged;    /* elements merged into their ancestor on the last level kept */
    uint32_t width, height;
    uint32_t depth;     /* levels in use, root to deepest element: 1 (roots only) .. 4 (merged elements are on
                           the deepest) */
} banyan_pivot_painter_info;

/* Writes <prefix>_PivotPos_Index.exr and <prefix>_XVector_Extent.png
 * for mesh (see the top of this header). prefix: a path without the
 * suffix, in an existing folder, shorter than 4000 bytes. opt NULL: the
 * defaults; info may be NULL. Refuses a mesh without the wind
 * attributes, with no vertices, or whose pivots or positions are not
 * finite, more than BANYAN_PP2_MAX_ELEMENTS roots, a pivot past a half
 * float's 65504 texture units, and a bad option, naming it and its range.
 * Each file is replaced whole (docs/formats.md "Writing files"): both are
 * written to temporary files first and renamed over their targets only
 * when both are complete, so a failure before the renames changes
 * neither. */
BANYAN_API banyan_status banyan_pivot_painter_write(const char *prefix, const banyan_mesh *mesh,
                                                    const banyan_pivot_painter_options *opt,
                                                    banyan_pivot_painter_info *info, banyan_error *err);

#ifdef __cplusplus
}
#endif
#endif
