/* rng.h - PCG32 (O'Neill, pcg32_random_r, XSH RR 64/32), the one seeded
 * generator every generator passes down explicitly. No global state. */
#ifndef BANYAN_RNG_H
#define BANYAN_RNG_H

#include <stdint.h>

typedef struct pcg32 { uint64_t state, inc; } pcg32;

/* Seeds a stream; different `stream` values give independent sequences
 * for the same seed (used for per-tree and per-root streams). */
void pcg32_seed(pcg32 *r, uint64_t seed, uint64_t stream);

/* The draws are inline: the random walks draw millions of them. */
static inline uint32_t pcg32_next(pcg32 *r) {
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}
/* Uniform in [0, 1), 53 random bits. */
static inline double rng_uniform(pcg32 *r) {
    int32_t hi = (int32_t)(pcg32_next(r) >> 5), lo = (int32_t)(pcg32_next(r) >> 6); /* 27 + 26 bits */
    return (hi * 67108864.0 + lo) * (1.0 / 9007199254740992.0); /* exact up to the last product */
}
/* Uniform real in [a, b]; I(a <= x <= b) in the specs. */
static inline double rng_range(pcg32 *r, double a, double b) { return a + (b - a) * rng_uniform(r); }
/* Unbiased integer in [0, n); n >= 1. I(a, b, c) picks with this. */
uint32_t rng_below(pcg32 *r, uint32_t n);
/* Standard normal (Box-Muller on two uniforms, no cached spare so the
 * stream position depends only on the number of calls). */
double rng_normal(pcg32 *r);

#endif
