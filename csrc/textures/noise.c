/* noise.c - periodic value noise for the tileable textures (issue #17):
 * lattice values drawn from the painter's PCG32 stream, interpolated with
 * a smoothstep; the lattice wraps, so a sum of octaves whose cell counts
 * divide the image size tiles without a seam. */
#include <math.h>
#include <stdlib.h>

#include "textures/tex_internal.h"

int tex_noise_init(tex_noise *t, int fx, int fy, pcg32 *rng) {
    t->fx = fx;
    t->fy = fy;
    t->v = malloc((size_t)fx * fy * sizeof *t->v);
    if (!t->v) return -1;
    for (int i = 0; i < fx * fy; i++) t->v[i] = (float)rng_range(rng, -1.0, 1.0);
    return 0;
}

void tex_noise_free(tex_noise *t) {
    free(t->v);
    t->v = NULL;
}

float tex_noise_at(const tex_noise *t, float x, float y) {
    float fx = floorf(x), fy = floorf(y);
    float tx = x - fx, ty = y - fy;
    int ix = (int)fx % t->fx, iy = (int)fy % t->fy;
    if (ix < 0) ix += t->fx;
    if (iy < 0) iy += t->fy;
    int ix1 = ix + 1 == t->fx ? 0 : ix + 1, iy1 = iy + 1 == t->fy ? 0 : iy + 1;
    tx = tx * tx * (3.0f - 2.0f * tx);
    ty = ty * ty * (3.0f - 2.0f * ty);
    const float *r0 = t->v + (size_t)iy * t->fx, *r1 = t->v + (size_t)iy1 * t->fx;
    float a = r0[ix] + (r0[ix1] - r0[ix]) * tx, b = r1[ix] + (r1[ix1] - r1[ix]) * tx;
    return a + (b - a) * ty;
}

void tex_noise_add(const tex_noise *t, float *buf, int n, float amp) {
    /* One row of x weights, reused down the image. */
    int cx = n / t->fx, cy = n / t->fy; /* pixels per lattice cell */
    for (int y = 0; y < n; y++) {
        int iy = y / cy, iy1 = iy + 1 == t->fy ? 0 : iy + 1;
        float ty = (float)(y - iy * cy) / (float)cy;
        ty = ty * ty * (3.0f - 2.0f * ty);
        const float *r0 = t->v + (size_t)iy * t->fx, *r1 = t->v + (size_t)iy1 * t->fx;
        float *o = buf + (size_t)y * n;
        for (int ix = 0; ix < t->fx; ix++) {
            int ix1 = ix + 1 == t->fx ? 0 : ix + 1;
            float a0 = r0[ix] + (r1[ix] - r0[ix]) * ty, a1 = r0[ix1] + (r1[ix1] - r0[ix1]) * ty;
            float d = a1 - a0;
            float inv = 1.0f / (float)cx;
            for (int k = 0; k < cx; k++) {
                float tx = (float)k * inv;
                tx = tx * tx * (3.0f - 2.0f * tx);
                o[ix * cx + k] += amp * (a0 + d * tx);
            }
        }
    }
}

int tex_fbm_add(float *buf, int n, int f0x, int f0y, int octaves, float amp, float gain, pcg32 *rng) {
    int fx = f0x, fy = f0y;
    for (int o = 0; o < octaves && fx <= n && fy <= n; o++) {
        tex_noise t;
        if (tex_noise_init(&t, fx, fy, rng) != 0) return -1;
        tex_noise_add(&t, buf, n, amp);
        tex_noise_free(&t);
        fx *= 2;
        fy *= 2;
        amp *= gain;
    }
    return 0;
}
