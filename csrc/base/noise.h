/* noise.h - seeded value noise: smooth, in [0, 1), from a 64-bit key and
 * no state. A lattice of hashed values (splitmix64's finaliser) blended
 * with smoothsteps, so the same key and point give the same value on every
 * machine (no libm). */
#ifndef BANYAN_BASE_NOISE_H
#define BANYAN_BASE_NOISE_H

#include <stdint.h>

/* A well-mixed 64-bit hash (splitmix64's finaliser): derive keys from a
 * seed, e.g. noise_mix(seed ^ SALT), noise_mix(key + 1). */
uint64_t noise_mix(uint64_t z);

/* A hash's top 53 bits as a uniform in [0, 1). */
double noise_unit(uint64_t h);

/* Value noise at (x, y) over square cells of `cell` (> 0) units. */
double noise_value2(uint64_t key, double x, double y, double cell);

/* Value noise at (x, y, z) over cubic cells of `cell` (> 0) units. */
double noise_value3(uint64_t key, double x, double y, double z, double cell);

/* 3 t^2 - 2 t^3 of t clamped to [0, 1]. */
double noise_smooth01(double t);

#endif
