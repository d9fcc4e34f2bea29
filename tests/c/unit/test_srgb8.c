/* test_srgb8.c - the billboards' linear -> sRGB byte lookup (csrc/lod/srgb8.h)
 * gives the direct formula's byte for every float in [2^-16, 1] and every
 * 997th below (where the byte is 0: 255 * 12.92 * 2^-16 < 0.06), the
 * formula's byte never falling as the colour grows (what makes a table of
 * thresholds exact), and for the clamped ends: negatives, zeros, NaN,
 * values past 1, infinities. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "lod/srgb8.h"

int main(void) {
    float to8[256];
    srgb8_build(to8);
    for (int b = 2; b < 256; b++) CHECK(to8[b] > to8[b - 1], "thresholds %d and %d out of order", b - 1, b);
    uint64_t wrong = 0, falls = 0;
    uint8_t prev = 0;
    float first_wrong = 0;
    for (uint32_t bits = 0; bits <= 0x3f800000u; bits += bits < 0x37800000u ? 997 : 1) { /* 0.0f .. 1.0f in order */
        float c;
        memcpy(&c, &bits, sizeof c);
        uint8_t d = srgb8_direct(c);
        if (d < prev) falls++;
        prev = d;
        if (srgb8(to8, c) != d) {
            if (!wrong) first_wrong = c;
            wrong++;
        }
    }
    CHECK(!falls, "srgb8_direct falls %llu times over [0, 1]", (unsigned long long)falls);
    CHECK(!wrong, "the lookup differs from the formula on %llu floats, the first %.9g", (unsigned long long)wrong,
          (double)first_wrong);
    CHECK(srgb8_direct(1.0f) == 255 && srgb8_direct(0.0f) == 0 && srgb8_direct(0.5f) == 188,
          "formula ends: %u %u %u", srgb8_direct(1.0f), srgb8_direct(0.0f), srgb8_direct(0.5f));
    const float odd[] = {-0.0f, -1e-30f, -1.0f, -INFINITY, NAN, 1.0000001f, 2.0f, 1e30f, INFINITY};
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++)
        CHECK(srgb8(to8, odd[i]) == srgb8_direct(odd[i]), "%g: lookup %u, formula %u", (double)odd[i],
              srgb8(to8, odd[i]), srgb8_direct(odd[i]));
    printf("srgb8: the lookup matches the formula on every float in [2^-16, 1]\n");
    return check_done("test_srgb8");
}
