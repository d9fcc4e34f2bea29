/* tex_cache.h - the library textures' PNG bytes through an on-disk cache
 * (docs/gltf.md "Texture cache"): one file per (kind, season, size, seed)
 * and build of the texture code, holding the base colour's and the normal
 * map's PNGs. A hit gives exactly the bytes drawing and encoding would. */
#ifndef BANYAN_TEX_CACHE_H
#define BANYAN_TEX_CACHE_H

#include <stddef.h>
#include <stdint.h>

#include "banyan.h"
#include "base/progress.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes the cache's folder keeps at most: past it the least recently used
 * files go. A texture whose two PNGs take more than a quarter of it is
 * not kept. */
#define TEX_CACHE_MAX_BYTES (512ull << 20)

/* The cache folder into out (cap bytes) and 1, or 0 when there is no
 * cache: `enabled` 0, the environment's BANYAN_TEXTURE_CACHE "off" (or
 * "0", "no", "false"), or no folder to be had. The folder: `dir` when not
 * NULL or "", else BANYAN_TEXTURE_CACHE when it is set to a folder, else
 * $XDG_CACHE_HOME/banyan/textures, else $HOME/.cache/banyan/textures. */
int tex_cache_dir(int32_t enabled, const char *dir, char *out, size_t cap);

/* The PNGs of p's base colour and normal map (malloc'd, free with
 * banyan_png_free): read from the cache folder `cache` when it holds them
 * whole, else drawn and encoded under `stop` (tex_generate, tex_png) and
 * then stored there. cache NULL: drawn and encoded only. The cache never
 * makes the call fail: a folder that cannot be read or written, or a file
 * that is cut, corrupt or from another build, is passed over (and
 * rewritten). */
banyan_status tex_cached_pngs(const banyan_texture_params *p, const char *cache, const prog_deadline *stop,
                              double seconds, uint8_t **base, size_t *base_len, uint8_t **normal, size_t *normal_len,
                              banyan_error *err);

#ifdef __cplusplus
}
#endif
#endif
