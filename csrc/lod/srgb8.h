/* srgb8.h - linear colour -> sRGB byte for the billboards' pictures
 * (billboard.c): the direct formula (a powf per channel) and a lookup of
 * 255 thresholds that gives the same byte for every float. */
#ifndef BANYAN_SRGB8_H
#define BANYAN_SRGB8_H

#include <stdint.h>

/* lrintf(255 * sRGB(c)), c clamped to [0, 1] (NaN reads as 0). */
uint8_t srgb8_direct(float c);

/* to8[b] = the least float whose srgb8_direct is b or more (to8[0] = -inf). */
void srgb8_build(float to8[256]);

/* srgb8_direct(c) through the thresholds: 8 comparisons. */
static inline uint8_t srgb8(const float to8[256], float c) {
    if (!(c > 0)) return 0; /* NaN too, as srgb8_direct */
    uint32_t b = 0;
    for (uint32_t step = 128; step; step >>= 1)
        if (to8[b + step] <= c) b += step;
    return (uint8_t)b;
}

#endif
