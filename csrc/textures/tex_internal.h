/* tex_internal.h - shared pieces of the texture painters:
 * the canvas they draw into, the periodic value noise, small colour
 * helpers. Every painter draws its base colour into `rgba` (sRGB,
 * straight alpha) and a height field into `height`; textures.c turns
 * the height into the normal map. Randomness comes only from the PCG32
 * stream a painter is handed. */
#ifndef BANYAN_TEX_INTERNAL_H
#define BANYAN_TEX_INTERNAL_H

#include <stdint.h>
#include <string.h>

#include "base/progress.h"
#include "base/rng.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#  error "tex_pack_rgba assumes a little-endian machine"
#endif

#define TEX_TILE 256

typedef struct tex_canvas {
    int n;            /* pixels per side (power of two) */
    uint8_t *rgba;    /* n * n * 4, rows top to bottom */
    float *height;    /* n * n, arbitrary units: metres of relief / pixel pitch come from `relief` */
    float relief;     /* normal-map strength: slope = relief * height difference per pixel */
    int wrap;         /* 1: tileable (bark), Sobel wraps around the edges */
    float *grain;     /* TEX_TILE^2 fine noise about [-1, 1] for leaf surfaces, tiled (leaf painters make it) */
    float *mottle;    /* TEX_TILE^2 noise a few spots per leaf (autumn blotches), stretched over the image */
    const prog_deadline *stop; /* NULL: none. Past it, painters stop early (their image is then dropped) */
} tex_canvas;

/* 1 once the canvas's deadline has passed: painters check it per band or
 * leaf cell and stop; banyan_texture_generate then refuses the picture. */
static inline int tex_stopped(const tex_canvas *c) { return prog_deadline_passed(c->stop); }

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
 * Value noise on a lattice of fx x fy cells (powers of two dividing the
 * image size n) that wraps around, so it tiles. The lattice values are
 * drawn from the rng once (no hashing), uniform in [-1, 1]. */
typedef struct tex_noise {
    int fx, fy, n;
    float *v;   /* fx * fy lattice values */
    float *w;   /* n / fx smoothstep weights across a cell */
    float *col; /* fx + 1 scratch: one lattice row interpolated */
} tex_noise;

int tex_noise_init(tex_noise *t, int fx, int fy, int n, pcg32 *rng);
void tex_noise_free(tex_noise *t);
/* Noise at a point in lattice units (wraps). */
float tex_noise_at(const tex_noise *t, float x, float y);

/* Fractal sum: octaves from f0x x f0y cells, doubling, amplitude times
 * gain each; octaves finer than min_cell pixels a cell are left out. */
#define TEX_MAX_OCTAVES 8
typedef struct tex_fbm {
    int n, octaves;
    tex_noise t[TEX_MAX_OCTAVES];
    float amp[TEX_MAX_OCTAVES];
} tex_fbm;
int tex_fbm_init(tex_fbm *f, int n, int f0x, int f0y, int octaves, float amp, float gain, int min_cell,
                 pcg32 *rng);
/* Rows y0 .. y0 + rows - 1 of the field into band (rows x n, overwritten). */
void tex_fbm_rows(tex_fbm *f, float *band, int y0, int rows);
void tex_fbm_free(tex_fbm *f);
/* The field at one pixel position (x, y), as tex_fbm_rows gives it. */
float tex_fbm_at(const tex_fbm *f, float x, float y);

/* Rows a painter makes at once (scratch of a few fields stays in cache). */
#define TEX_BAND 16

static inline float tex_clampf(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }
static inline float tex_smooth(float e0, float e1, float x) {
    float t = tex_clampf((x - e0) * (1.0f / (e1 - e0)), 0.0f, 1.0f); /* constant edges fold to a multiply */
    return t * t * (3.0f - 2.0f * t);
}
static inline float tex_mix(float a, float b, float t) { return a + (b - a) * t; }
static inline uint8_t tex_byte(float v) { /* 0..255 float to byte, rounded */
    v = tex_clampf(v, 0.0f, 255.0f);
    return (uint8_t)(v + 0.5f);
}
/* Packs float channels (0..255) of `count` pixels into opaque RGBA8,
 * rounded; loops the compiler vectorises. */
static inline void tex_pack_rgba(uint8_t *dst, const float *r, const float *g, const float *b, int count) {
    for (int i = 0; i < count; i++) {
        uint32_t R = (uint32_t)(int32_t)(tex_clampf(r[i], 0.0f, 255.0f) + 0.5f);
        uint32_t G = (uint32_t)(int32_t)(tex_clampf(g[i], 0.0f, 255.0f) + 0.5f);
        uint32_t B = (uint32_t)(int32_t)(tex_clampf(b[i], 0.0f, 255.0f) + 0.5f);
        uint32_t v = R | G << 8 | B << 16 | 0xff000000u; /* little-endian: bytes R, G, B, A */
        memcpy(dst + 4 * (size_t)i, &v, 4);
    }
}
static inline float tex_unif(pcg32 *r, float a, float b) { return (float)rng_range(r, a, b); }

/* Four floats (ints) in one SSE / NEON register: the GCC and Clang vector
 * extension, lane by lane the same IEEE operations as scalar code, so
 * the same bytes. Loads and stores go through memcpy: unaligned. */
typedef float tex_v4 __attribute__((vector_size(16)));
typedef int32_t tex_v4i __attribute__((vector_size(16)));
static inline tex_v4 v4_load(const float *p) {
    tex_v4 v;
    memcpy(&v, p, sizeof v);
    return v;
}
static inline void v4_store(float *p, tex_v4 v) { memcpy(p, &v, sizeof v); }
/* m ? a : b lane by lane, m a comparison's result (all bits set or none). */
static inline tex_v4 v4_sel(tex_v4i m, tex_v4 a, tex_v4 b) { return (tex_v4)(((tex_v4i)a & m) | ((tex_v4i)b & ~m)); }

#endif
