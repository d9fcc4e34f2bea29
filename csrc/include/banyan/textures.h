/* Textures drawn by the library: leaf atlases and tileable
 * bark, deterministic from a seed, as RGBA8 / RGB8 images and PNG bytes
 * (stb_image_write). Materials of a banyan_mesh name the texture they use
 * (banyan_material.texture); the glTF writer embeds the images it needs,
 * the Blender add-on packs them. Docs: docs/materials.md. */
#ifndef BANYAN_TEXTURES_H
#define BANYAN_TEXTURES_H
#include <stddef.h>
#include <stdint.h>

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a texture depicts. NONE (0): a material with no texture (flat
 * colour), so a zeroed banyan_material names none. */
typedef enum banyan_texture_kind {
    BANYAN_TEX_NONE = 0,
    BANYAN_TEX_KEYAKI_LEAF = 1, /* atlas of keyaki (Zelkova serrata) leaves: ovate, pointed, serrated, 3-7 cm */
    BANYAN_TEX_IVY_LEAF = 2,    /* atlas of Boston ivy (Parthenocissus tricuspidata) leaves: three-lobed, toothed */
    BANYAN_TEX_KEYAKI_BARK = 3, /* tileable: smooth grey, flaking in small muted orange-brown patches; a smooth
                                   grey-brown lane (BANYAN_KEYAKI_BARK_SMOOTH_U0 .. _U1) for thin branches */
    BANYAN_TEX_FIG_BARK = 4,    /* tileable: smooth pale grey-brown (strangler fig roots) */
    BANYAN_TEX_IVY_STEM = 5,    /* tileable: woody brown */
    BANYAN_TEX_COUNT = 6        /* one past the last kind */
} banyan_texture_kind;

typedef enum banyan_season {
    BANYAN_SEASON_SUMMER = 0,
    BANYAN_SEASON_AUTUMN = 1
} banyan_season;

/* Leaf atlases are a grid of cols x rows equal cells, one leaf per cell,
 * the petiole's end at the cell's bottom centre (u = 0.5, v = 0 of the
 * cell, v up), the tip towards the cell's top. The keyaki atlas's bottom
 * row (v < 1 / rows) holds two spray cells instead, each two cells wide:
 * a twig along the row's centre line from its left end, carrying leaves
 * on both sides (the crown's spray cards; docs/materials.md). Bark textures are one
 * tile: 1 in u = once around, 1 in v = `BANYAN_BARK_TILE_ASPECT`
 * circumferences along (the tube's uvs already run in circumferences). */
#define BANYAN_BARK_TILE_ASPECT 1.0f
/* The keyaki bark's smooth lane: u in [U0, U1] of its tile (every v) is
 * young bark, smooth grey-brown with lenticels and no flakes. The keyaki
 * maps the u of its thin branches and twigs into it (docs/keyaki.md
 * "Trunk: flare and bark"); on the trunk it is a narrow flake-free strip. */
#define BANYAN_KEYAKI_BARK_SMOOTH_U0 0.08f
#define BANYAN_KEYAKI_BARK_SMOOTH_U1 0.20f

typedef struct banyan_atlas_layout {
    int32_t cols, rows;      /* 1 x 1 for bark */
    float leaf_aspect;       /* leaf cell width / height, for the cards' shape */
} banyan_atlas_layout;

BANYAN_API banyan_status banyan_texture_layout(int32_t kind, banyan_atlas_layout *out, banyan_error *err);

/* banyan_image is declared in banyan.h (meshes carry images too). */

typedef struct banyan_texture_params {
    int32_t kind;            /* banyan_texture_kind, not NONE */
    int32_t season;          /* banyan_season; bark ignores it */
    int32_t size;            /* pixels per side: a power of two, 64 .. 8192. Default 1024 */
    int32_t reserved;
    uint64_t seed;           /* default 1 */
} banyan_texture_params;

BANYAN_API void banyan_texture_params_init(banyan_texture_params *p);

/* Draws the base colour (RGBA) and normal (RGB) images of one texture.
 * Either out pointer may be NULL to skip that image. Refuses a bad kind,
 * season or size naming the field and its range; on failure the outputs
 * are NULL. The same params give the same bytes on every run. */
BANYAN_API banyan_status banyan_texture_generate(const banyan_texture_params *p, banyan_image **base_color,
                                                 banyan_image **normal, banyan_error *err);
/* banyan_texture_generate under a budget (banyan.h, banyan_budget; NULL:
 * the defaults, which banyan_texture_generate uses): refused up front with
 * BANYAN_E_LIMIT when the pictures' size (size^2 x 11 bytes with the
 * normal map, 8 without) passes max_memory_mb, stopped with BANYAN_E_LIMIT
 * once drawing passes max_seconds. */
BANYAN_API banyan_status banyan_texture_generate_budget(const banyan_texture_params *p, const banyan_budget *budget,
                                                        banyan_image **base_color, banyan_image **normal,
                                                        banyan_error *err);
BANYAN_API void banyan_image_free(banyan_image *image);

/* PNG bytes of an image (stb_image_write, deterministic). *png is freed
 * with banyan_png_free. */
BANYAN_API banyan_status banyan_image_png(const banyan_image *image, uint8_t **png, size_t *size,
                                          banyan_error *err);
BANYAN_API void banyan_png_free(uint8_t *png);

BANYAN_API size_t banyan_sizeof_image(void);
BANYAN_API size_t banyan_sizeof_texture_params(void);

#ifdef __cplusplus
}
#endif

#endif
