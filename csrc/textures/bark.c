/* bark.c - tileable bark (issue #17; docs/materials.md "Bark"): keyaki
 * (smooth grey with lenticels, old scales flaking off into orange-brown
 * patches), strangler fig (smooth pale grey-brown with fine horizontal
 * wrinkles around the root) and the ivy's woody stem (brown, fibrous,
 * a few longitudinal fissures). Each is periodic value noise (noise.c)
 * shaped per kind; the tile spans one circumference around (u, image
 * columns) and BANYAN_BARK_TILE_ASPECT circumferences along (v, rows), so
 * features stay round on the tube. Lenticels are small ellipses drawn
 * with wrap-around. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "textures/tex_internal.h"

/* A small elliptical mark (lenticel) at (cx, cy) px, half axes rx, ry,
 * wrapping around the tile: blends colour and adds height. */
static void mark(tex_canvas *c, float cx, float cy, float rx, float ry, const float col[3], float opacity,
                 float dh) {
    const int n = c->n;
    int x0 = (int)floorf(cx - rx - 1), x1 = (int)ceilf(cx + rx + 1);
    int y0 = (int)floorf(cy - ry - 1), y1 = (int)ceilf(cy + ry + 1);
    for (int y = y0; y <= y1; y++) {
        int yy = y & (n - 1);
        float dy = ((float)y + 0.5f - cy) / ry;
        for (int x = x0; x <= x1; x++) {
            float dx = ((float)x + 0.5f - cx) / rx;
            float r2 = dx * dx + dy * dy;
            if (r2 >= 1.0f) continue;
            float k = (1.0f - r2);
            float a = opacity * tex_smooth(0.0f, 0.35f, k);
            size_t i = (size_t)yy * n + (size_t)(x & (n - 1));
            uint8_t *p = c->rgba + 4 * i;
            for (int ch = 0; ch < 3; ch++) p[ch] = tex_byte(tex_mix(p[ch], col[ch], a));
            c->height[i] += dh * sqrtf(k);
        }
    }
}

/* Scratch fields, freed together. */
static float *field(int n) { return calloc((size_t)n * n, sizeof(float)); }

int tex_paint_keyaki_bark(tex_canvas *c, pcg32 *rng) {
    const int n = c->n;
    float *patch = field(n), *tone = field(n);
    if (!patch || !tone) goto fail;
    /* Scales: patches elongated along the trunk (fewer lattice cells in v). */
    if (tex_fbm_add(patch, n, 4, 2, 6, 1.0f, 0.55f, rng)) goto fail;
    if (tex_fbm_add(tone, n, 8, 8, 5, 1.0f, 0.6f, rng)) goto fail;
    if (tex_fbm_add(c->height, n, 8, 4, 6, 0.25f, 0.6f, rng)) goto fail;
    const float grey[3] = {152, 150, 142}, grey2[3] = {118, 118, 112};
    const float orange[3] = {182, 112, 62}, brown[3] = {140, 92, 58};
    const float thr = 0.32f; /* about a fifth of the bark has shed */
    for (size_t i = 0; i < (size_t)n * n; i++) {
        float p = patch[i], t = tone[i];
        float m = tex_smooth(thr - 0.02f, thr + 0.02f, p);       /* inside a shed patch */
        float rim = tex_smooth(thr - 0.10f, thr - 0.02f, p) * (1.0f - m); /* curled edge of the old scale */
        float g = tex_clampf(0.5f + 0.9f * t, 0.0f, 1.0f);
        float o = tex_clampf(0.5f + 1.4f * t, 0.0f, 1.0f);
        uint8_t *px = c->rgba + 4 * i;
        for (int ch = 0; ch < 3; ch++) {
            float bark = tex_mix(grey2[ch], grey[ch], g) * (1.0f - 0.25f * rim);
            float under = tex_mix(brown[ch], orange[ch], o);
            px[ch] = tex_byte(tex_mix(bark, under, m));
        }
        px[3] = 255;
        c->height[i] += 0.6f * (1.0f - m) + 0.35f * rim;
    }
    /* Lenticels: short pale dashes across the trunk. */
    int count = 420;
    float s = (float)n / 1024.0f;
    const float lcol[3] = {178, 168, 150};
    for (int k = 0; k < count; k++) {
        float cx = tex_unif(rng, 0, (float)n), cy = tex_unif(rng, 0, (float)n);
        float rx = tex_unif(rng, 2.5f, 6.0f) * s, ry = tex_unif(rng, 0.7f, 1.3f) * s;
        size_t i = (size_t)((int)cy & (n - 1)) * n + (size_t)((int)cx & (n - 1));
        if (patch[i] > thr - 0.05f) continue; /* none on the fresh under-bark */
        mark(c, cx, cy, rx < 1.0f ? 1.0f : rx, ry < 0.6f ? 0.6f : ry, lcol, 0.8f, 0.25f);
    }
    c->relief = 6.0f * s;
    c->wrap = 1;
    free(patch);
    free(tone);
    return 0;
fail:
    free(patch);
    free(tone);
    return -1;
}

int tex_paint_fig_bark(tex_canvas *c, pcg32 *rng) {
    const int n = c->n;
    float *warp = field(n), *seg = field(n), *tone = field(n);
    if (!warp || !seg || !tone) goto fail;
    if (tex_fbm_add(warp, n, 4, 4, 4, 1.0f, 0.5f, rng)) goto fail;
    if (tex_fbm_add(seg, n, 16, 32, 3, 1.0f, 0.5f, rng)) goto fail;
    if (tex_fbm_add(tone, n, 4, 4, 6, 1.0f, 0.6f, rng)) goto fail;
    if (tex_fbm_add(c->height, n, 16, 16, 4, 0.05f, 0.5f, rng)) goto fail;
    const float pale[3] = {170, 160, 145}, dark[3] = {132, 122, 108}, crease[3] = {98, 88, 76};
    const int rings = 40; /* wrinkles per tile along the root */
    /* cos^k profile of one wrinkle as a table over its period. */
    float prof[256];
    for (int k = 0; k < 256; k++) {
        float cs = cosf(6.2831853f * (float)k / 256.0f);
        prof[k] = cs > 0 ? powf(cs, 10.0f) : 0.0f;
    }
    for (int y = 0; y < n; y++) {
        for (int x = 0; x < n; x++) {
            size_t i = (size_t)y * n + x;
            float w = (float)y * rings / (float)n + 1.2f * warp[i];
            float f = w - floorf(w);
            float wr = prof[(int)(f * 256.0f) & 255] * tex_smooth(-0.1f, 0.35f, seg[i]);
            float t = tex_clampf(0.5f + 0.8f * tone[i], 0.0f, 1.0f);
            uint8_t *px = c->rgba + 4 * i;
            for (int ch = 0; ch < 3; ch++) px[ch] = tex_byte(tex_mix(tex_mix(dark[ch], pale[ch], t), crease[ch], 0.7f * wr));
            px[3] = 255;
            c->height[i] -= 0.5f * wr;
        }
    }
    float s = (float)n / 1024.0f;
    const float lcol[3] = {190, 180, 160};
    for (int k = 0; k < 160; k++) {
        float cx = tex_unif(rng, 0, (float)n), cy = tex_unif(rng, 0, (float)n);
        float r = tex_unif(rng, 1.2f, 2.4f) * s;
        mark(c, cx, cy, r * 1.6f < 1.0f ? 1.0f : r * 1.6f, r < 0.6f ? 0.6f : r, lcol, 0.6f, 0.2f);
    }
    c->relief = 4.0f * s;
    c->wrap = 1;
    free(warp);
    free(seg);
    free(tone);
    return 0;
fail:
    free(warp);
    free(seg);
    free(tone);
    return -1;
}

int tex_paint_ivy_stem(tex_canvas *c, pcg32 *rng) {
    const int n = c->n;
    float *fib = field(n), *crack = field(n), *tone = field(n);
    if (!fib || !crack || !tone) goto fail;
    /* Fibres run along the stem: many lattice cells around, few along. */
    if (tex_fbm_add(fib, n, 32, 2, 5, 1.0f, 0.6f, rng)) goto fail;
    if (tex_fbm_add(crack, n, 8, 1, 5, 1.0f, 0.55f, rng)) goto fail;
    if (tex_fbm_add(tone, n, 4, 4, 5, 1.0f, 0.6f, rng)) goto fail;
    const float wood[3] = {122, 96, 70}, grey[3] = {128, 116, 100}, groove[3] = {70, 52, 38};
    for (size_t i = 0; i < (size_t)n * n; i++) {
        float f = fib[i], cr = crack[i];
        float fis = 1.0f - tex_smooth(0.0f, 0.06f, fabsf(cr)); /* fissure along a zero line */
        float t = tex_clampf(0.5f + 0.9f * tone[i], 0.0f, 1.0f);
        float sh = tex_clampf(0.5f + 0.8f * f, 0.0f, 1.0f);
        uint8_t *px = c->rgba + 4 * i;
        for (int ch = 0; ch < 3; ch++) {
            float base = tex_mix(wood[ch], grey[ch], t) * (0.8f + 0.35f * sh);
            px[ch] = tex_byte(tex_mix(base, groove[ch], 0.8f * fis));
        }
        px[3] = 255;
        c->height[i] = 0.6f * f - 0.8f * fis;
    }
    float s = (float)n / 1024.0f;
    const float lcol[3] = {160, 130, 100};
    for (int k = 0; k < 90; k++) {
        float cx = tex_unif(rng, 0, (float)n), cy = tex_unif(rng, 0, (float)n);
        float r = tex_unif(rng, 1.5f, 3.0f) * s;
        mark(c, cx, cy, r < 0.8f ? 0.8f : r, 1.8f * r < 1.0f ? 1.0f : 1.8f * r, lcol, 0.7f, 0.3f);
    }
    c->relief = 5.0f * s;
    c->wrap = 1;
    free(fib);
    free(crack);
    free(tone);
    return 0;
fail:
    free(fib);
    free(crack);
    free(tone);
    return -1;
}
