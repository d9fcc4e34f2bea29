/* png_write.h - the PNG encoder of every image banyan writes (textures,
 * billboard pictures): 8-bit grey, grey-alpha, RGB or RGBA, one filter for
 * every row and libdeflate's whole-buffer zlib stream in one IDAT chunk.
 * The same pixels give the same bytes on every run and CPU (libdeflate's
 * output does not depend on the CPU features it uses). */
#ifndef BANYAN_PNG_WRITE_H
#define BANYAN_PNG_WRITE_H

#include <stddef.h>
#include <stdint.h>

#include "base/progress.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The filter and level the writer uses (png_write.c says why). */
#define PNG_WRITE_FILTER 2 /* Up */
#define PNG_WRITE_LEVEL 1

/* PNG bytes of w x h pixels of `channels` (1 .. 4) bytes each, rows top to
 * bottom, into *out (malloc'd, *len bytes). filter: 0 .. 4 (None, Sub, Up,
 * Average, Paeth) for every row, level: libdeflate's 1 .. 12. Returns 0,
 * -1 when out of memory, 1 when `stop` (NULL: none) passed while filtering
 * or before deflating (nothing in *out). */
int png_write(const uint8_t *pixels, int w, int h, int channels, int filter, int level, const prog_deadline *stop,
              uint8_t **out, size_t *len);

#ifdef __cplusplus
}
#endif
#endif
