/* PCG32 as published by M. O'Neill (pcg-random.org, pcg_basic.c), with
 * Lemire-free rejection for bounded draws, so streams are portable. */
#include "rng.h"

#include "dmath.h"

#include <math.h>

void pcg32_seed(pcg32 *r, uint64_t seed, uint64_t stream) {
    r->state = 0u;
    r->inc = (stream << 1u) | 1u;
    pcg32_next(r);
    r->state += seed;
    pcg32_next(r);
}

uint32_t rng_below(pcg32 *r, uint32_t n) {
    if (n <= 1) return 0;
    uint32_t threshold = (uint32_t)(-n) % n; /* 2^32 mod n */
    for (;;) {
        uint32_t x = pcg32_next(r);
        if (x >= threshold) return x % n;
    }
}

double rng_normal(pcg32 *r) {
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    if (u1 < 1e-300) u1 = 1e-300;
    return sqrt(-2.0 * dm_log(u1)) * dm_cos(6.283185307179586 * u2);
}
