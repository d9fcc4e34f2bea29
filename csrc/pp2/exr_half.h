/* exr_half.h - half-float RGBA OpenEXR in memory, through tinyexr
 * (exr_half.cpp, the only file that includes it). */
#ifndef BANYAN_EXR_HALF_H
#define BANYAN_EXR_HALF_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* EXR bytes (ZIP-compressed scanlines, channels A, B, G, R as OpenEXR
 * stores them) of w x h texels of four halves each, rgba interleaved
 * R, G, B, A, rows top to bottom, into *out (malloc'd, *len bytes).
 * Returns 0, or -1 with a reason in why (cap bytes). */
int exr_half_encode(const uint16_t *rgba, uint32_t w, uint32_t h, uint8_t **out, size_t *len, char *why, size_t cap);

/* The reverse: an EXR with half channels R, G, B and A (any order) into
 * *rgba (malloc'd, R, G, B, A interleaved, rows top to bottom). Returns
 * 0, or -1 with a reason in why. */
int exr_half_decode(const uint8_t *bytes, size_t len, uint32_t *w, uint32_t *h, uint16_t **rgba, char *why,
                    size_t cap);

/* float -> half, rounded to nearest even; beyond 65504 it is infinite. */
uint16_t exr_half_from_float(float f);
/* half -> float, exactly. */
float exr_half_to_float(uint16_t h);

#ifdef __cplusplus
}
#endif
#endif
