/* rng.h - PCG32 (O'Neill, pcg32_random_r, XSH RR 64/32), the one seeded
 * generator every generator passes down explicitly. No global state. */
#ifndef BANYAN_RNG_H
#define BANYAN_RNG_H

#include <stdint.h>

typedef struct pcg32 { uint64_t state, inc; } pcg32;

/* Seeds a stream; different `stream` values give independent sequences
 * for the same seed (used for per-tree and per-root streams). */
void pcg32_seed(pcg32 *r, uint64_t seed, uint64_t stream);
uint32_t pcg32_next(pcg32 *r);
/* Uniform in [0, 1), 53 random bits. */
double rng_uniform(pcg32 *r);
/* Uniform real in [a, b]; I(a <= x <= b) in the specs. */
double rng_range(pcg32 *r, double a, double b);
/* Unbiased integer in [0, n); n >= 1. I(a, b, c) picks with this. */
uint32_t rng_below(pcg32 *r, uint32_t n);
/* Standard normal (Box-Muller on two uniforms, no cached spare so the
 * stream position depends only on the number of calls). */
double rng_normal(pcg32 *r);

#endif
