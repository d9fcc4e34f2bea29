/*
 * banyan/usd.h - USD export (docs/usd.md). Included by banyan.h.
 *
 * Writes the same nodes as banyan_gltf_write_nodes (banyan_gltf_node: a
 * mesh, its levels of detail) as one USD layer in the text format
 * (.usda, or .usd holding text), for the pipelines that take USD:
 *   - the stage in the library's own frame: upAxis "Z", metersPerUnit 1;
 *     each node an Xform (kind "component") translated to the mesh's
 *     origin (double precision), its defaultPrim the first node;
 *   - one Mesh per part (an avenue's tree, or a variant, an Xform of its
 *     parts), triangles, vertex normals, primvars:st (the uvs),
 *     primvars:displayColor (the vertex colours, when the mesh has them),
 *     every custom attribute as a float primvar of its own name and the
 *     wind pivot as one float3 primvar `wind_pivot`, all "vertex"
 *     interpolated and in the mesh's frame, like the points;
 *   - one UsdPreviewSurface material per banyan_material, bound with
 *     MaterialBindingAPI: the library's textures (base colour in sRGB,
 *     tangent-space normal map raw with scale 2 and bias -1) and a mesh's
 *     own images as PNG files beside the layer, the alpha cutoff as
 *     opacityThreshold; flat materials their base colour;
 *   - the skeleton as BasisCurves (linear, one two-point curve an edge,
 *     widths the diameters), purpose "guide";
 *   - instances (banyan_mesh.instance_count) as one PointInstancer whose
 *     prototypes are the variants beneath it;
 *   - levels of detail as a variant set "LOD" ("lod0" the mesh itself,
 *     "lod1" ... its levels), "lod0" selected.
 * Options: banyan_gltf_options' textures, texture_size, texture_seed,
 * texture_cache, texture_cache_dir and sync mean what they mean for glTF;
 * image_dir (NULL or "": "textures") is the folder, relative to the
 * layer's, of the image files, which are always files: a texture file
 * already there is kept. engine_uvs and compact are glTF's only and are
 * refused. The layer is replaced whole or not at all, as the glTF writer's
 * files are. The crate formats (.usdc, .usdz) are refused with
 * BANYAN_E_UNSUPPORTED: convert with OpenUSD's usdcat.
 */
#ifndef BANYAN_USD_H
#define BANYAN_USD_H

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

BANYAN_API banyan_status banyan_usd_write_nodes(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                                                const banyan_gltf_options *opt, banyan_error *err);
/* The same within a budget (banyan_budget; NULL: the defaults): past
 * max_seconds the write stops between meshes and inside the texture
 * painters, with BANYAN_E_LIMIT, and the old file is left as it was. */
BANYAN_API banyan_status banyan_usd_write_nodes_budget(const char *path, const banyan_gltf_node *nodes,
                                                       uint32_t count, const banyan_gltf_options *opt,
                                                       const banyan_budget *budget, banyan_error *err);

#ifdef __cplusplus
}
#endif
#endif
