/* leaf_look.h - how leaf cards and their materials look:
 * which atlas cell a card shows, its per-leaf colour tint (vertex colours,
 * COLOR_0) and the season's material. A card's cell and tint come from a
 * PCG32 stream of its own, seeded with the generator's seed and the
 * leaf's index, never from the generator's stream: choosing them moves no
 * vertex, and the same leaf keeps its look when the plant grows on. */
#ifndef BANYAN_LEAF_LOOK_H
#define BANYAN_LEAF_LOOK_H

#include "banyan.h"

typedef struct leaf_look {
    double u0, v0, du, dv; /* the cell: card uv (s, t) in 0..1 maps to (u0 + s du, v0 + t dv) */
    double tint[4];        /* linear RGBA multiplier, each in [0, 1] */
} leaf_look;

/* The atlas grid of a leaf texture (banyan_texture_layout) and its cells'
 * width / height (aspect may be NULL); 1 x 1 and 1 when the kind has none. */
void leaf_atlas_grid(int32_t kind, int32_t *cols, int32_t *rows, double *aspect);

/* Where an ivy atlas cell's blade lies (csrc/textures/leaves.c fits each
 * blade within 0.45 of the cell's centre line sideways and 0.80 tall, its
 * tip 4 % below the top, a petiole stub below): ivy cards map their
 * outline's bounds to this box, so the drawn blade and the card agree. */
#define LEAF_IVY_BLADE_V0 0.16
#define LEAF_IVY_BLADE_V1 0.96
#define LEAF_IVY_BLADE_HALF_U 0.45

/* Where a keyaki atlas cell's leaf lies (one real-size leaf a
 * cell, 4 x 4 cells): the blade's midrib runs up the cell's centre line
 * u = 0.5, its petiole from v = 0 to LEAF_KEYAKI_BLADE_V0, the blade from
 * there to its tip at LEAF_KEYAKI_BLADE_V1; blade and teeth stay within
 * LEAF_KEYAKI_HALF_U of the centre line. A leaf quad therefore maps the
 * cell's strip u in [0.5 - HALF_U, 0.5 + HALF_U], v in [0, 1]: its length
 * is petiole + blade and its width 2 HALF_U times that. */
#define LEAF_KEYAKI_BLADE_V0 0.08
#define LEAF_KEYAKI_BLADE_V1 0.98
#define LEAF_KEYAKI_HALF_U 0.25

/* Spray cells of the keyaki atlas: its bottom row (v in [0, 0.25]) holds
 * LEAF_KEYAKI_SPRAYS sprays instead of single leaves, each two cells wide
 * (u in [0, 0.5] and [0.5, 1]): a thin twig along the cell's centre line
 * from LEAF_KEYAKI_SPRAY_U0 (its base) to LEAF_KEYAKI_SPRAY_U1, carrying
 * two-ranked leaves at 40-70 deg forward, alternately on each side and
 * smaller toward the tip, and one leaf on from its end. Units: the spray
 * cell's, u 0..1 along the twig, v 0..1 across it. The leaves cover about
 * LEAF_KEYAKI_SPRAY_COVER of the cell (alpha >= 0.5). Single leaves use
 * the rows above (leaf_look_keyaki). A spray card is LEAF_KEYAKI_SPRAY_ASPECT
 * times as long as it is wide; its painted twig starts U0 of its length
 * from the card's base edge. */
#define LEAF_KEYAKI_SPRAYS 2
#define LEAF_KEYAKI_SPRAY_ASPECT 2.0
#define LEAF_KEYAKI_SPRAY_U0 0.03
#define LEAF_KEYAKI_SPRAY_U1 0.78
#define LEAF_KEYAKI_SPRAY_V 0.5
#define LEAF_KEYAKI_SPRAY_COVER 0.45

/* The look of leaf `index` of a plant grown from `seed`. */
void leaf_look_of(uint64_t seed, uint64_t index, int32_t cols, int32_t rows, int32_t season, leaf_look *out);

/* The look of Boston ivy leaf `index` on a cols x rows ivy atlas, whose
 * every fourth cell (cell number % 4 == 3: the right-hand column of the
 * 4 x 4 atlas) holds a young unlobed leaf, bronze in summer, the others
 * grown three-lobed ones (csrc/textures/leaves.c): a young leaf takes one
 * of the young cells, a grown one one of the others, from a hash of the
 * seed and the index. The tint as leaf_look_of's. */
void leaf_look_ivy(uint64_t seed, uint64_t index, int32_t cols, int32_t rows, int young, int32_t season,
                   leaf_look *out);

/* The look of keyaki card `index` (a 4 x 4 keyaki atlas): spray 0, a
 * single leaf from the 12 single-leaf cells (rows v >= 0.25); spray 1, one
 * of the LEAF_KEYAKI_SPRAYS spray cells (u0, v0, du, dv its whole spray
 * cell). The tint as leaf_look_of's. */
void leaf_look_keyaki(uint64_t seed, uint64_t index, int spray, int32_t season, leaf_look *out);

/* Sets a leaf material for a season: texture kind, season, alpha cutoff,
 * translucency, and the flat colour (summer: `summer_rgba`, the user's
 * leaf colour; autumn: the kind's autumn colour). */
void leaf_material_set(banyan_material *m, int32_t kind, int32_t season, const double summer_rgba[4]);

/* The keyaki's default bark colour (linear RGBA), also the segments
 * trees' trunk and axes colour, so both trees show the same bark. */
#define LEAF_KEYAKI_BARK_RGBA {0.16, 0.13, 0.10, 1.0}

/* Sets a bark or stem material's texture (opaque, no translucency). */
void bark_material_set(banyan_material *m, int32_t kind);

#endif
