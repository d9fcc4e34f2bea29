/* noise.c - seeded value noise (noise.h). */
#include "noise.h"

#include <math.h>

uint64_t noise_mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

double noise_unit(uint64_t h) { return (double)(h >> 11) * (1.0 / 9007199254740992.0); }

/* The lattice value of cell (i, j, k), in [0, 1). */
static double lattice(uint64_t key, int64_t i, int64_t j, int64_t k) {
    return noise_unit(noise_mix(key ^ noise_mix((uint64_t)i * 0x9e3779b97f4a7c15ULL +
                                                (uint64_t)j * 0xc2b2ae3d27d4eb4fULL + (uint64_t)k * 0x165667b19e3779f9ULL)));
}

double noise_smooth01(double t) {
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}

static double lerp(double a, double b, double t) { return a + (b - a) * t; }

double noise_value2(uint64_t key, double x, double y, double cell) {
    double u = x / cell, v = y / cell, fu = floor(u), fv = floor(v);
    int64_t i = (int64_t)fu, j = (int64_t)fv;
    double s = noise_smooth01(u - fu), t = noise_smooth01(v - fv);
    return lerp(lerp(lattice(key, i, j, 0), lattice(key, i + 1, j, 0), s),
                lerp(lattice(key, i, j + 1, 0), lattice(key, i + 1, j + 1, 0), s), t);
}

double noise_value3(uint64_t key, double x, double y, double z, double cell) {
    double u = x / cell, v = y / cell, w = z / cell, fu = floor(u), fv = floor(v), fw = floor(w);
    int64_t i = (int64_t)fu, j = (int64_t)fv, k = (int64_t)fw;
    double s = noise_smooth01(u - fu), t = noise_smooth01(v - fv), r = noise_smooth01(w - fw);
    double a = lerp(lerp(lattice(key, i, j, k), lattice(key, i + 1, j, k), s),
                    lerp(lattice(key, i, j + 1, k), lattice(key, i + 1, j + 1, k), s), t);
    double b = lerp(lerp(lattice(key, i, j, k + 1), lattice(key, i + 1, j, k + 1), s),
                    lerp(lattice(key, i, j + 1, k + 1), lattice(key, i + 1, j + 1, k + 1), s), t);
    return lerp(a, b, r);
}
