/* srgb8.c - linear colour -> sRGB byte (srgb8.h). srgb8_direct grows with
 * c (test_srgb8 checks every float in [0, 1]), so its byte is the count of
 * thresholds at or below c: the thresholds are found by bisection on the
 * float's bits (their order is the floats' order for c >= 0). */
#include "srgb8.h"

#include <math.h>
#include <string.h>

#include "base/dmath.h"

uint8_t srgb8_direct(float c) {
    c = !(c > 0) ? 0 : c > 1 ? 1 : c; /* NaN (a hostile colour) reads as black */
    float s = c <= 0.0031308f ? 12.92f * c : 1.055f * dm_powf(c, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)lrintf(255.0f * s);
}

void srgb8_build(float to8[256]) {
    to8[0] = -INFINITY;
    for (int b = 1; b < 256; b++) {
        uint32_t lo = 0, hi = 0x3f800000u; /* 0.0f .. 1.0f */
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2;
            float f;
            memcpy(&f, &mid, sizeof f);
            if (srgb8_direct(f) >= b) hi = mid;
            else lo = mid + 1;
        }
        memcpy(&to8[b], &lo, sizeof lo);
    }
}
