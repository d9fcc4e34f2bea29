/* tex_budget.h - the texture calls under a deadline, for the glTF writer
 * (C++, which draws textures on its own threads) and banyan/textures.h's
 * _budget calls: the painters, the normal map and the PNG encoder check
 * the deadline as they go and give BANYAN_E_LIMIT once it has passed. */
#ifndef BANYAN_TEX_BUDGET_H
#define BANYAN_TEX_BUDGET_H

#include <stddef.h>
#include <stdint.h>

#include "banyan.h"
#include "base/progress.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes one texture of `size` pixels a side holds at its peak while drawn
 * and encoded: the RGBA picture, the height field, the RGB normal map,
 * the PNG filter rows and the deflated bytes (with normal = 0: no normal
 * map). The up-front memory check of the texture calls and the writer. */
uint64_t tex_peak_bytes(int32_t size, int normal);

/* banyan_texture_generate, stopping with BANYAN_E_LIMIT (max_seconds,
 * seconds = the budget in seconds) once `stop` has passed. */
banyan_status tex_generate(const banyan_texture_params *p, const prog_deadline *stop, double seconds,
                           banyan_image **base_color, banyan_image **normal, banyan_error *err);
/* banyan_image_png under the same deadline; the same bytes. */
banyan_status tex_png(const banyan_image *image, const prog_deadline *stop, double seconds, uint8_t **png,
                      size_t *size, banyan_error *err);

#ifdef __cplusplus
}
#endif
#endif
