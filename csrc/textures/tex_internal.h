/* tex_internal.h - shared pieces of the texture painters (issue #17):
 * the canvas they draw into, the periodic value noise, small colour
 * helpers. Every painter draws its base colour into `rgba` (sRGB,
 * straight alpha) and a height field into `height`; textures.c turns
 * the height into the normal map. Randomness comes only from the PCG32
 * stream a painter is handed. */
#ifndef BANYAN_TEX_INTERNAL_H
#define BANYAN_TEX_INTERNAL_H

#include <stdint.h>

#include "core/rng.h"

typedef struct tex_canvas {
    int n;            /* pixels per side (power of two) */
    uint8_t *rgba;    /* n * n * 4, rows top to bottom */
    float *height;    /* n * n, arbitrary units: metres of relief / pixel pitch come from `relief` */
    float relief;     /* normal-map strength: slope = relief * height difference per pixel */
    int wrap;         /* 1: tileable (bark), Sobel wraps around the edges */
} tex_canvas;

/* Leaf atlases (leaves.c) and bark (bark.c); season only for leaves.
 * Return 0 on success, -1 when a scratch allocation failed. */
int tex_paint_keyaki_leaves(tex_canvas *c, int season, pcg32 *rng);
int tex_paint_ivy_leaves(tex_canvas *c, int season, pcg32 *rng);
int tex_paint_keyaki_bark(tex_canvas *c, pcg32 *rng);
int tex_paint_fig_bark(tex_canvas *c, pcg32 *rng);
int tex_paint_ivy_stem(tex_canvas *c, pcg32 *rng);

/* Grid of a leaf atlas (the public layout). */
void tex_leaf_grid(int kind, int *cols, int *rows, float *aspect);

/* ---------------------------------------------------------- periodic noise
 * Value noise on a lattice of fx x fy cells that wraps around, so an image
 * of n pixels made of it tiles when fx and fy divide n. The lattice values
 * are drawn from the rng once (no hashing), uniform in [-1, 1]. */
typedef struct tex_noise {
    int fx, fy;
    float *v; /* fx * fy */
} tex_noise;

int tex_noise_init(tex_noise *t, int fx, int fy, pcg32 *rng);
void tex_noise_free(tex_noise *t);
/* Adds amp * noise over the whole n x n buffer (fx, fy divide n). */
void tex_noise_add(const tex_noise *t, float *buf, int n, float amp);
/* Noise at a point in lattice units (wraps). */
float tex_noise_at(const tex_noise *t, float x, float y);
/* Fractal sum: octaves of value noise starting at f0 x (f0 * ay) cells,
 * doubling, gain per octave; added into buf. */
int tex_fbm_add(float *buf, int n, int f0x, int f0y, int octaves, float amp, float gain, pcg32 *rng);

static inline float tex_clampf(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }
static inline float tex_smooth(float e0, float e1, float x) {
    float t = tex_clampf((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
static inline float tex_mix(float a, float b, float t) { return a + (b - a) * t; }
static inline uint8_t tex_byte(float v) { /* 0..255 float to byte, rounded */
    v = tex_clampf(v, 0.0f, 255.0f);
    return (uint8_t)(v + 0.5f);
}
static inline float tex_unif(pcg32 *r, float a, float b) { return (float)rng_range(r, a, b); }

#endif
