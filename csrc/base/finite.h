/* finite.h - whether an array of floats is all finite, fast: a mesh's
 * validation scans every vertex's attributes before anything is written
 * or reduced. The exponent bits are tested without a branch per float,
 * so the compiler vectorises the scan; a block with a bad float stops it.
 * Callers that name the bad float look for it again, the slow way, only
 * then. C and C++. */
#ifndef BANYAN_BASE_FINITE_H
#define BANYAN_BASE_FINITE_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

static inline int floats_finite(const float *a, size_t n) {
    const size_t block = 4096;
    for (size_t at = 0; at < n; at += block) {
        const size_t end = n - at < block ? n : at + block;
        uint32_t bad = 0;
        for (size_t i = at; i < end; i++) {
            uint32_t u;
            memcpy(&u, a + i, sizeof u);
            bad |= (uint32_t)((u & 0x7f800000u) == 0x7f800000u);
        }
        if (bad) return 0;
    }
    return 1;
}

#endif
