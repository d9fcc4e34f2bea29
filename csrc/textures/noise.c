/* noise.c - periodic value noise for the tileable textures:
 * lattice values drawn from the painter's PCG32 stream, interpolated with
 * a smoothstep; the lattice wraps, so a sum of octaves whose cell counts
 * divide the image size tiles without a seam. Fields are made a band of
 * rows at a time, so a painter's scratch stays in cache and only its
 * outputs take fresh memory (page faults were a third of the time). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "textures/tex_internal.h"

int tex_noise_init(tex_noise *t, int fx, int fy, int n, pcg32 *rng) {
    t->fx = fx;
    t->fy = fy;
    t->n = n;
    int cx = n / fx;
    t->v = malloc(((size_t)fx * fy + (size_t)cx + (size_t)fx + 1) * sizeof *t->v);
    if (!t->v) return -1;
    for (int i = 0; i < fx * fy; i++) t->v[i] = (float)rng_range(rng, -1.0, 1.0);
    t->w = t->v + (size_t)fx * fy;
    t->col = t->w + cx;
    for (int k = 0; k < cx; k++) {
        float tx = (float)k / (float)cx;
        t->w[k] = tx * tx * (3.0f - 2.0f * tx);
    }
    return 0;
}

void tex_noise_free(tex_noise *t) {
    free(t->v);
    t->v = t->w = t->col = NULL;
}

float tex_noise_at(const tex_noise *t, float x, float y) {
    float fx = floorf(x), fy = floorf(y);
    float tx = x - fx, ty = y - fy;
    int ix = (int)fx & (t->fx - 1), iy = (int)fy & (t->fy - 1); /* powers of two: wraps negatives too */
    int ix1 = (ix + 1) & (t->fx - 1), iy1 = (iy + 1) & (t->fy - 1);
    tx = tx * tx * (3.0f - 2.0f * tx);
    ty = ty * ty * (3.0f - 2.0f * ty);
    const float *r0 = t->v + (size_t)iy * t->fx, *r1 = t->v + (size_t)iy1 * t->fx;
    float a = r0[ix] + (r0[ix1] - r0[ix]) * tx, b = r1[ix] + (r1[ix1] - r1[ix]) * tx;
    return a + (b - a) * ty;
}

/* One row of one octave: per lattice cell cx texels (a power of two >= 4)
 * of a0 + d * w[k], written (first) or added. Inlined with cx and first
 * constant, the small cells unroll completely. */
static inline __attribute__((always_inline)) void cells_row(float *restrict o, const float *restrict col,
                                                            const float *restrict w, int fx, int cx, int first) {
    for (int ix = 0; ix < fx; ix++, o += cx) {
        float a0 = col[ix], d = col[ix + 1] - a0;
        const tex_v4 A = {a0, a0, a0, a0}, D = {d, d, d, d};
        for (int k = 0; k < cx; k += 4) {
            tex_v4 v = A + D * v4_load(w + k);
            v4_store(o + k, first ? v : v4_load(o + k) + v);
        }
    }
}

/* Rows y0 .. y0 + rows - 1 of the noise times amp, added into band
 * (rows x n; `first`: written, not added). Per row the lattice row is interpolated down once; per
 * pixel one multiply-add with a smoothstep weight from the table. */
static void noise_rows(tex_noise *t, float *band, int y0, int rows, float amp, int first) {
    const int n = t->n, cx = n / t->fx, cy = n / t->fy;
    float *col = t->col;
    for (int y = y0; y < y0 + rows; y++) {
        int iy = y / cy, iy1 = iy + 1 == t->fy ? 0 : iy + 1;
        float ty = (float)(y - iy * cy) / (float)cy;
        ty = ty * ty * (3.0f - 2.0f * ty);
        const float *r0 = t->v + (size_t)iy * t->fx, *r1 = t->v + (size_t)iy1 * t->fx;
        for (int ix = 0; ix < t->fx; ix++) col[ix] = amp * (r0[ix] + (r1[ix] - r0[ix]) * ty);
        col[t->fx] = col[0]; /* wraps */
        float *o = band + (size_t)(y - y0) * n;
        /* cx >= 4 (tex_fbm_init's min_cell); the finest cells unrolled. */
        if (first) {
            if (cx == 4) cells_row(o, col, t->w, t->fx, 4, 1);
            else if (cx == 8) cells_row(o, col, t->w, t->fx, 8, 1);
            else cells_row(o, col, t->w, t->fx, cx, 1);
        } else {
            if (cx == 4) cells_row(o, col, t->w, t->fx, 4, 0);
            else if (cx == 8) cells_row(o, col, t->w, t->fx, 8, 0);
            else if (cx == 16) cells_row(o, col, t->w, t->fx, 16, 0);
            else cells_row(o, col, t->w, t->fx, cx, 0);
        }
    }
}

int tex_fbm_init(tex_fbm *f, int n, int f0x, int f0y, int octaves, float amp, float gain, int min_cell,
                 pcg32 *rng) {
    memset(f, 0, sizeof *f);
    f->n = n;
    int fx = f0x, fy = f0y;
    if (min_cell < 4) min_cell = 4; /* noise_rows makes four texels a step */
    /* Octaves finer than min_cell pixels a cell: left out (they cost the
     * most per pixel and add little but aliasing). */
    for (int o = 0; o < octaves && o < TEX_MAX_OCTAVES && fx * min_cell <= n && fy * min_cell <= n; o++) {
        if (tex_noise_init(&f->t[o], fx, fy, n, rng) != 0) {
            tex_fbm_free(f);
            return -1;
        }
        f->amp[o] = amp;
        f->octaves = o + 1;
        fx *= 2;
        fy *= 2;
        amp *= gain;
    }
    return 0;
}

void tex_fbm_rows(tex_fbm *f, float *band, int y0, int rows) {
    if (f->octaves == 0) memset(band, 0, sizeof(float) * (size_t)rows * f->n);
    for (int o = 0; o < f->octaves; o++) noise_rows(&f->t[o], band, y0, rows, f->amp[o], o == 0);
}

void tex_fbm_free(tex_fbm *f) {
    for (int o = 0; o < TEX_MAX_OCTAVES; o++)
        if (f->t[o].v) tex_noise_free(&f->t[o]);
    f->octaves = 0;
}

float tex_fbm_at(const tex_fbm *f, float x, float y) {
    float sum = 0.0f;
    for (int o = 0; o < f->octaves; o++) {
        const tex_noise *t = &f->t[o];
        sum += f->amp[o] * tex_noise_at(t, x * (float)t->fx / (float)t->n, y * (float)t->fy / (float)t->n);
    }
    return sum;
}
