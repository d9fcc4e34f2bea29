/* billboard.c - the last level of detail of a tree: cards.
 *
 * Method (docs/lod.md, "Billboard"): `billboard_planes` vertical planes
 * through the vertical axis of the plant's bounding box centre, at equal
 * angles, plus one horizontal card at BB_TOP_AT of the plant's height
 * (about where a crown is widest) so the plant does not vanish seen from
 * above. Each vertical plane is as wide as the plant's vertices reach
 * along it and as tall as the plant, split at the axis into two quads
 * (so an engine can sort the halves); the top card covers the plant's
 * footprint. Each card shows an orthographic picture of the plant seen
 * along its normal, drawn here by a small software rasteriser:
 *   - z-buffered triangles, BB_SS x BB_SS samples per pixel; a textured
 *     material (its leaf atlas or bark drawn at BB_TEX_SIZE, or the
 *     mesh's own image) is sampled at each sample's interpolated uv, a
 *     texel with alpha below one half covers nothing (as the engine's
 *     alpha test), and its colour times the vertex colour is the colour;
 *   - light: the sun and sky of the docs' studio scene, a Lambert term
 *     with translucency on the face seen (double-sided leaves), over the
 *     light the card itself gets (its two faces averaged), so the card,
 *     lit by the engine, shows the plant as lit;
 *   - a pixel's alpha is the share of its samples covered, scaled per
 *     picture so that as many pixels pass the cutoff 0.5 as the plant
 *     covers (coverage-preserving alpha, Castano 2010): the card is as
 *     see-through as the tree;
 *   - the colour dilated into the empty pixels so mipmaps do not halo.
 * The pictures sit in a grid of tiles (verticals in order, then the top)
 * in one RGBA image per group (tree, or variant of an instanced avenue),
 * billboard_size pixels on its longer side at most. Each group has two
 * parts and materials on that image: the vertical cards (double sided)
 * and the top card (single sided, facing up). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/error.h"
#include "mesh/wind.h"
#include "lod_internal.h"
#include "srgb8.h"

#define BB_MAX_PLANES 8
#define BB_MAX_TILES (BB_MAX_PLANES + 1)
#define BB_PI 3.14159265358979323846
/* Height of the top card, a share of the plant's. */
#define BB_TOP_AT 0.65
/* Pixels per side of the textures sampled. */
#define BB_TEX_SIZE 256
/* Light: toward the sun of docs/render_scene.py's studio (45 degrees up,
 * from -x -y), and the sky's share of the light on a face turned away. */
static const double BB_SUN[3] = {-0.4545, -0.5417, 0.7071};
#define BB_SKY 0.4

static float linear_of_srgb(float c) { return c <= 0.04045f ? c / 12.92f : dm_powf((c + 0.055f) / 1.055f, 2.4f); }

/* Samples per pixel side: fewer on the large pictures (memory). */
#define BB_MAX_SS 4
static uint32_t bb_ss(uint32_t size) { return size <= 512 ? 4 : size <= 1024 ? 2 : 1; }

/* What the rasteriser knows of one material: a texture to sample (the
 * mesh's image, or a generated one), else a flat linear colour. */
typedef struct bb_mat {
    const banyan_image *tex;
    float flat[3];
    float translucency;
} bb_mat;

typedef struct bb_paint {
    bb_mat *mat;
    banyan_image **owned; /* generated textures, one per material at most */
    uint32_t n_owned;
    float lin[256];       /* sRGB byte -> linear */
    float to8[256];       /* linear -> sRGB byte: to8[b] is the least linear value whose byte is b (srgb8_build) */
} bb_paint;

static void paint_free(bb_paint *pa) {
    if (!pa) return;
    for (uint32_t i = 0; i < pa->n_owned; i++) banyan_image_free(pa->owned[i]);
    free(pa->owned);
    free(pa->mat);
}

static banyan_status paint_init(const banyan_mesh *m, bb_paint *pa) {
    memset(pa, 0, sizeof *pa);
    for (int i = 0; i < 256; i++) pa->lin[i] = linear_of_srgb(i / 255.0f);
    srgb8_build(pa->to8);
    pa->mat = calloc(m->material_count, sizeof(bb_mat));
    pa->owned = calloc(m->material_count, sizeof(banyan_image *));
    if (!pa->mat || !pa->owned) return BANYAN_E_NOMEM;
    int32_t *kinds = malloc(sizeof(int32_t) * 2 * m->material_count);
    if (!kinds) return BANYAN_E_NOMEM;
    for (uint32_t i = 0; i < m->material_count; i++) {
        const banyan_material *mt = &m->materials[i];
        bb_mat *b = &pa->mat[i];
        for (int c = 0; c < 3; c++) b->flat[c] = mt->base_color[c];
        b->translucency = !(mt->translucency > 0) ? 0 : mt->translucency > 1 ? 1 : mt->translucency;
        if (mt->image > 0) {
            b->tex = &m->images[mt->image - 1];
            continue;
        }
        if (mt->texture <= BANYAN_TEX_NONE || mt->texture >= BANYAN_TEX_COUNT) continue;
        for (uint32_t j = 0; j < pa->n_owned; j++)
            if (kinds[2 * j] == mt->texture && kinds[2 * j + 1] == mt->season) b->tex = pa->owned[j];
        if (b->tex) continue;
        banyan_texture_params tp;
        banyan_texture_params_init(&tp);
        tp.kind = mt->texture;
        tp.season = mt->season;
        tp.size = BB_TEX_SIZE;
        banyan_image *im = NULL;
        banyan_status st = banyan_texture_generate(&tp, &im, NULL, NULL);
        if (st == BANYAN_E_NOMEM) {
            free(kinds);
            return st;
        }
        if (st || !im) continue; /* a texture the library cannot draw: the flat colour */
        kinds[2 * pa->n_owned] = mt->texture, kinds[2 * pa->n_owned + 1] = mt->season;
        pa->owned[pa->n_owned++] = im;
        b->tex = im;
    }
    free(kinds);
    return BANYAN_OK;
}

/* One picture: a card's view of the plant. Picture x runs along r, y
 * down along -up; depth grows toward the viewer (along v). */
typedef struct bb_view {
    double r[3], up[3], v[3];
    double rmin, rmax, umin, umax;
    uint32_t x0, y0, w, h; /* its tile in the image */
} bb_view;

/* The light on a face of unit normal n seen from v (the face turned to
 * the viewer, so a double-sided leaf shows its lit or its back-lit side). */
static double bb_light(const double n[3], const double v[3], double translucency) {
    double s = n[0] * v[0] + n[1] * v[1] + n[2] * v[2] < 0 ? -1 : 1;
    double c = s * (n[0] * BB_SUN[0] + n[1] * BB_SUN[1] + n[2] * BB_SUN[2]);
    return BB_SKY + (1 - BB_SKY) * (c > 0 ? c : -c * translucency);
}

/* A triangle's unit normal: its vertex normals' mean, else its plane's. */
static int tri_normal(const banyan_mesh *m, const uint32_t *I, double n[3]) {
    n[0] = n[1] = n[2] = 0;
    if (m->normals)
        for (int j = 0; j < 3; j++)
            for (int e = 0; e < 3; e++) n[e] += m->normals[3 * (size_t)I[j] + e];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l > 1e-12)) {
        const float *A = m->positions + 3 * (size_t)I[0], *B = m->positions + 3 * (size_t)I[1],
                    *C = m->positions + 3 * (size_t)I[2];
        double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(l > 0)) return 0;
    }
    for (int e = 0; e < 3; e++) n[e] /= l;
    return 1;
}

/* The light the card of view w gets itself, its two faces averaged
 * (an engine's card material has no translucency): the picture of w
 * carries the plant's light / this, so the card, lit by the engine, shows
 * the plant as lit. */
static double card_light(const bb_view *w) {
    double back[3] = {-w->v[0], -w->v[1], -w->v[2]};
    return 0.5 * (bb_light(w->v, w->v, 0) + bb_light(back, back, 0));
}

/* The group's area-weighted mean roughness (the cards' material's). */
static float mean_roughness(const banyan_mesh *m, uint32_t g) {
    double sum = 0, wsum = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group != g) continue;
        double r = m->materials[pt->material].roughness, a = 0;
        if (!(r >= 0 && r <= 1)) continue;
        for (uint32_t k = pt->index_offset; k + 2 < pt->index_offset + pt->index_count; k += 3) {
            const float *A = m->positions + 3 * (size_t)m->indices[k], *B = m->positions + 3 * (size_t)m->indices[k + 1],
                        *C = m->positions + 3 * (size_t)m->indices[k + 2];
            double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
            double f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            a += sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        }
        if (isfinite(a)) sum += a * r, wsum += a;
    }
    return wsum > 0 ? (float)(sum / wsum) : 0.9f;
}

/* The tile's samples: depth (-inf where empty) and linear colour. */
typedef struct bb_tile {
    uint32_t sw, sh;
    float *depth;
    float *rgb;
} bb_tile;

/* floor(x) as a long for |x| < 1e15: the same value without a libm call. */
static inline long floor_l(double x) {
    long t = (long)x;
    return (double)t > x ? t - 1 : t;
}

/* The texel under (u, v), repeating: its alpha first (a texel under one
 * half covers nothing, and its colour is not read), then its linear
 * colour into out. Returns the alpha. */
static inline float texel(const bb_paint *pa, const banyan_image *im, double u, double v, float out[3]) {
    double x = u * im->width, y = (1.0 - v) * im->height;
    if (!(fabs(x) < 1e9) || !(fabs(y) < 1e9)) x = y = 0; /* NaN or far off: the first texel */
    long ix = floor_l(x), iy = floor_l(y);
    long w = (long)im->width, h = (long)im->height;
    if (!(w & (w - 1)) && !(h & (h - 1))) { /* powers of two: the remainder in [0, size) is the low bits */
        ix &= w - 1, iy &= h - 1;
    } else {
        ix %= w, iy %= h;
        ix += ix < 0 ? w : 0, iy += iy < 0 ? h : 0;
    }
    const uint8_t *c = im->pixels + ((size_t)iy * im->width + (size_t)ix) * im->channels;
    float a = im->channels == 4 ? c[3] / 255.0f : 1.0f;
    if (a < 0.5f) return a;
    for (int e = 0; e < 3; e++) out[e] = pa->lin[c[e]];
    return a;
}

/* What a triangle brings to every view, worked out once per group: its
 * vertex colours' mean and its unit normal (has_n 0: none, lit flat). */
typedef struct bb_tri {
    double tint[3];
    double n[3];
    int has_n;
} bb_tri;

/* The group's triangles in drawing order (parts in order) into tri. */
static void tris_of_group(const banyan_mesh *m, uint32_t g, bb_tri *tri) {
    size_t at = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group != g) continue;
        for (uint32_t k = pt->index_offset; k + 2 < pt->index_offset + pt->index_count; k += 3) {
            const uint32_t *I = m->indices + k;
            bb_tri *b = &tri[at++];
            b->tint[0] = b->tint[1] = b->tint[2] = 0;
            for (int j = 0; j < 3; j++)
                for (int e = 0; e < 3; e++) b->tint[e] += (m->colors ? m->colors[4 * (size_t)I[j] + e] : 1.0f) / 3.0;
            b->has_n = tri_normal(m, I, b->n);
        }
    }
}

static inline double dmin3(double a, double b, double c) {
    double m = b < c ? b : c;
    return a < m ? a : m;
}

static inline double dmax3(double a, double b, double c) {
    double m = b > c ? b : c;
    return a > m ? a : m;
}

/* One sample of a triangle at barycentrics (w0, w1, w2): nearer than
 * what the sample holds and, textured, over the alpha cutoff, it takes
 * the triangle's colour there. */
static inline void put_sample(const bb_paint *pa, const banyan_image *tex, bb_tile *t, long x, long y, double w0,
                              double w1, double w2, const double Z[3], const double U[3], const double V[3],
                              const double tint[3], double light, const double flat[3]) {
    double z = w0 * Z[0] + w1 * Z[1] + w2 * Z[2];
    size_t s = (size_t)y * t->sw + (size_t)x;
    if (!(z > t->depth[s])) return;
    float *c = t->rgb + 3 * s;
    if (tex) {
        float tx[3];
        if (texel(pa, tex, w0 * U[0] + w1 * U[1] + w2 * U[2], w0 * V[0] + w1 * V[1] + w2 * V[2], tx) < 0.5f) return;
        for (int e = 0; e < 3; e++) c[e] = (float)(tx[e] * tint[e] * light);
    } else {
        for (int e = 0; e < 3; e++) c[e] = (float)flat[e];
    }
    t->depth[s] = (float)z;
}

/* Draws the triangles of group g (tri: tris_of_group's) into one tile's
 * samples. */
static void draw_view(const banyan_mesh *m, uint32_t g, const bb_paint *pa, const bb_tri *tri, double *proj,
                      double gain, const bb_view *vw, bb_tile *t) {
    double sx = t->sw / (vw->rmax - vw->rmin), sy = t->sh / (vw->umax - vw->umin);
    size_t at = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group != g) continue;
        const bb_mat *bm = &pa->mat[pt->material];
        const banyan_image *tex = m->uvs ? bm->tex : NULL;
        /* A single-sided material shows its front faces only, as the
         * engine draws it: counter-clockwise seen from the viewer is a
         * negative area here (picture y runs down). */
        const int cull = !m->materials[pt->material].double_sided;
        /* The part's vertices in picture space, once (a vertex has several
         * corners): proj holds x, y and depth of each. */
        for (uint32_t v = 0; v < pt->vertex_count; v++) {
            const float *P = m->positions + 3 * ((size_t)pt->vertex_offset + v);
            double *o = proj + 3 * (size_t)v;
            o[0] = (P[0] * vw->r[0] + P[1] * vw->r[1] + P[2] * vw->r[2] - vw->rmin) * sx;
            o[1] = (vw->umax - (P[0] * vw->up[0] + P[1] * vw->up[1] + P[2] * vw->up[2])) * sy;
            o[2] = P[0] * vw->v[0] + P[1] * vw->v[1] + P[2] * vw->v[2];
        }
        for (uint32_t k = pt->index_offset; k + 2 < pt->index_offset + pt->index_count; k += 3) {
            const uint32_t *I = m->indices + k;
            const bb_tri *b = &tri[at++];
            const double *tint = b->tint;
            double X[3], Y[3], Z[3], U[3] = {0, 0, 0}, V[3] = {0, 0, 0};
            for (int j = 0; j < 3; j++) {
                const double *o = proj + 3 * (size_t)(I[j] - pt->vertex_offset);
                X[j] = o[0], Y[j] = o[1], Z[j] = o[2];
            }
            double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
            if (cull && area > 0) continue;
            /* Finite here (positions are checked, views are finite): plain
             * compares give fmin's and fmax's values. */
            double bx0 = dmin3(X[0], X[1], X[2]), bx1 = dmax3(X[0], X[1], X[2]);
            double by0 = dmin3(Y[0], Y[1], Y[2]), by1 = dmax3(Y[0], Y[1], Y[2]);
            if (!(bx1 >= 0 && by1 >= 0 && bx0 < t->sw && by0 < t->sh)) continue; /* off the tile (as x0 > x1) */
            long fx0 = floor_l(bx0), fx1 = floor_l(bx1), fy0 = floor_l(by0), fy1 = floor_l(by1);
            long x0 = fx0, x1 = fx1, y0 = fy0, y1 = fy1;
            x0 = x0 < 0 ? 0 : x0;
            x1 = x1 > (long)t->sw - 1 ? (long)t->sw - 1 : x1;
            y0 = y0 < 0 ? 0 : y0;
            y1 = y1 > (long)t->sh - 1 ? (long)t->sh - 1 : y1;
            if (x0 > x1 || y0 > y1) continue;
            /* Thin triangles seen edge-on still cover what they pass: a
             * sliver smaller than a sample lights the sample at its centre. */
            int sliver = fabs(area) < 1e-12 || (x0 == x1 && y0 == y1);
            long cx = 0, cy = 0;
            if (sliver) {
                cx = floor_l((X[0] + X[1] + X[2]) / 3), cy = floor_l((Y[0] + Y[1] + Y[2]) / 3);
                if (!(cx >= x0 && cx <= x1 && cy >= y0 && cy <= y1)) continue;
            } else {
                /* Only the samples whose centre lies in the triangle's box
                 * can be inside it: the rows and columns of the box's
                 * pixels whose centres fall outside it are skipped, and a
                 * triangle with no such sample is left without its colour
                 * and light looked up. */
                /* ceil(bx0 - 0.5) and floor(bx1 - 0.5), from the floors: */
                long xc0 = fx0 + (bx0 - (double)fx0 > 0.5), xc1 = fx1 - (bx1 - (double)fx1 < 0.5);
                long yc0 = fy0 + (by0 - (double)fy0 > 0.5), yc1 = fy1 - (by1 - (double)fy1 < 0.5);
                x0 = xc0 > x0 ? xc0 : x0, x1 = xc1 < x1 ? xc1 : x1;
                y0 = yc0 > y0 ? yc0 : y0, y1 = yc1 < y1 ? yc1 : y1;
                if (x0 > x1 || y0 > y1) continue;
            }
            if (tex)
                for (int j = 0; j < 3; j++) U[j] = m->uvs[2 * (size_t)I[j]], V[j] = m->uvs[2 * (size_t)I[j] + 1];
            double light = (b->has_n ? bb_light(b->n, vw->v, bm->translucency) : 1.0) / gain;
            double flat[3] = {0, 0, 0};
            if (!tex)
                for (int e = 0; e < 3; e++) flat[e] = bm->flat[e] * tint[e] * light;
            if (sliver) {
                put_sample(pa, tex, t, cx, cy, 1.0 / 3, 1.0 / 3, 1.0 / 3, Z, U, V, tint, light, flat);
                continue;
            }
            /* The edge functions e0, e1 (w0 = e0 / area, w1 = e1 / area)
             * at the row's first sample, then a step per sample to the
             * right, signed so that inside is >= 0 whatever the winding. */
            double sg = area < 0 ? -1.0 : 1.0, sa = sg * area;
            double s0 = sg * (Y[1] - Y[2]), s1 = sg * (Y[2] - Y[0]);
            for (long y = y0; y <= y1; y++) {
                double py_ = y + 0.5, dy0 = Y[0] - py_, dy1 = Y[1] - py_, dy2 = Y[2] - py_, px_ = x0 + 0.5;
                double e0 = sg * ((X[1] - px_) * dy2 - (X[2] - px_) * dy1);
                double e1 = sg * ((X[2] - px_) * dy0 - (X[0] - px_) * dy2);
                for (long x = x0; x <= x1; x++, e0 += s0, e1 += s1) {
                    /* w0 < 0 exactly when e0 < 0 (no quotient here is
                     * small enough to round to 0): most samples outside
                     * are left without dividing. */
                    if (e0 < -1e-250 || e1 < -1e-250) continue;
                    double w0 = e0 / sa, w1 = e1 / sa, w2 = 1 - w0 - w1;
                    if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                    put_sample(pa, tex, t, x, y, w0, w1, w2, Z, U, V, tint, light, flat);
                }
            }
        }
    }
}

/* Tile samples -> the image's pixels: the covered samples' mean colour,
 * alpha the covered share scaled (by one factor per tile, found by
 * bisection) so the pixels at alpha >= 0.5 are as many as the tile's
 * covered share of samples says. */
static void resolve(const bb_tile *t, uint32_t ss, const bb_view *vw, const float to8[256], uint8_t *img, uint32_t W,
                    float *share) {
    double total = 0;
    size_t hist[BB_MAX_SS * BB_MAX_SS + 1] = {0}; /* pixels by covered samples */
    for (uint32_t y = 0; y < vw->h; y++)
        for (uint32_t x = 0; x < vw->w; x++) {
            double sum[3] = {0, 0, 0};
            uint32_t n = 0;
            for (uint32_t j = 0; j < ss; j++)
                for (uint32_t i = 0; i < ss; i++) {
                    size_t s = (size_t)(y * ss + j) * t->sw + (x * ss + i);
                    if (t->depth[s] == -INFINITY) continue;
                    for (int e = 0; e < 3; e++) sum[e] += t->rgb[3 * s + e];
                    n++;
                }
            uint8_t *px = img + 4 * ((size_t)(vw->y0 + y) * W + vw->x0 + x);
            share[(size_t)y * vw->w + x] = (float)n / (float)(ss * ss);
            hist[n]++;
            total += (double)n / (ss * ss);
            for (int e = 0; e < 3; e++)
                px[e] = n ? srgb8(to8, (float)(sum[e] / n)) : 0;
            px[3] = 0;
        }
    /* A pixel's share is one of ss * ss + 1 values (n / (ss * ss)): the
     * pixels that pass at a scale are counted per value. */
    double want = total; /* pixels that should pass the cutoff */
    double lo = 0.5, hi = 16, scale = 1;
    uint32_t nss = ss * ss;
    for (int it = 0; it < 40; it++) {
        double mid = 0.5 * (lo + hi);
        size_t pass = 0;
        for (uint32_t n = 1; n <= nss; n++)
            pass += lrint(255.0 * fmin(1.0, mid * (double)((float)n / (float)nss))) >= 128 ? hist[n] : 0;
        if ((double)pass < want) lo = mid;
        else hi = mid;
    }
    /* Of the two ends, the one nearer the covered share. */
    size_t p_lo = 0, p_hi = 0;
    for (uint32_t n = 1; n <= nss; n++) {
        float sh = (float)n / (float)nss;
        p_lo += lrint(255.0 * fmin(1.0, lo * sh)) >= 128 ? hist[n] : 0;
        p_hi += lrint(255.0 * fmin(1.0, hi * sh)) >= 128 ? hist[n] : 0;
    }
    scale = fabs((double)p_lo - want) <= fabs((double)p_hi - want) ? lo : hi;
    for (uint32_t y = 0; y < vw->h; y++)
        for (uint32_t x = 0; x < vw->w; x++) {
            float a = share[(size_t)y * vw->w + x];
            if (!(a > 0)) continue;
            long a8 = lrint(255.0 * fmin(1.0, scale * a));
            img[4 * ((size_t)(vw->y0 + y) * W + vw->x0 + x) + 3] = (uint8_t)(a8 < 1 ? 1 : a8);
        }
}

/* Colour into the empty pixels, ring by ring from the covered ones (the
 * mean of their filled 8-neighbours), then the picture's mean colour
 * beyond 16 rings; alpha stays 0 there. */
static int dilate(uint8_t *img, uint32_t W, uint32_t H) {
    size_t n = (size_t)W * H;
    uint8_t *filled = malloc(n), *next = malloc(n);
    if (!filled || !next) {
        free(filled);
        free(next);
        return -1;
    }
    double mean[3] = {0, 0, 0}, cnt = 0;
    for (size_t i = 0; i < n; i++) {
        filled[i] = img[4 * i + 3] != 0;
        if (filled[i]) {
            for (int e = 0; e < 3; e++) mean[e] += img[4 * i + e];
            cnt++;
        }
    }
    for (int ring = 0; ring < 16; ring++) {
        memcpy(next, filled, n);
        int any = 0;
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                size_t i = (size_t)y * W + x;
                if (filled[i]) continue;
                unsigned sum[3] = {0, 0, 0}, k = 0;
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        long xx = (long)x + dx, yy = (long)y + dy;
                        if (xx < 0 || yy < 0 || xx >= (long)W || yy >= (long)H) continue;
                        size_t j = (size_t)yy * W + (size_t)xx;
                        if (!filled[j]) continue;
                        for (int e = 0; e < 3; e++) sum[e] += img[4 * j + e];
                        k++;
                    }
                if (!k) continue;
                for (int e = 0; e < 3; e++) img[4 * i + e] = (uint8_t)((sum[e] + k / 2) / k);
                next[i] = 1;
                any = 1;
            }
        memcpy(filled, next, n);
        if (!any) break;
    }
    for (size_t i = 0; i < n; i++)
        if (!filled[i])
            for (int e = 0; e < 3; e++) img[4 * i + e] = (uint8_t)(cnt ? lrint(mean[e] / cnt) : 128);
    free(filled);
    free(next);
    return 0;
}

/* Tiles in a grid of `cols` columns, rows as tall as their tallest tile:
 * pixel sizes at ppm pixels per metre; returns the image's W and H. */
static void grid_at(bb_view *vw, uint32_t n, uint32_t cols, double ppm, uint32_t *W, uint32_t *H) {
    uint32_t y = 0, wmax = 0;
    for (uint32_t r0 = 0; r0 < n; r0 += cols) {
        uint32_t x = 0, hrow = 0;
        for (uint32_t k = r0; k < n && k < r0 + cols; k++) {
            long w = lrint((vw[k].rmax - vw[k].rmin) * ppm), h = lrint((vw[k].umax - vw[k].umin) * ppm);
            vw[k].w = w < 1 ? 1 : (uint32_t)w;
            vw[k].h = h < 1 ? 1 : (uint32_t)h;
            vw[k].x0 = x, vw[k].y0 = y;
            x += vw[k].w;
            hrow = vw[k].h > hrow ? vw[k].h : hrow;
        }
        wmax = x > wmax ? x : wmax;
        y += hrow;
    }
    *W = wmax, *H = y;
}

/* The grid (columns, then pixels per metre) that draws the tiles largest
 * with the longer side of the image at most `size`. */
static void layout(bb_view *vw, uint32_t n, uint32_t size, uint32_t *W, uint32_t *H) {
    uint32_t best_c = 1;
    double best_ppm = 0;
    for (uint32_t c = 1; c <= n; c++) {
        double wm = 0, hm = 0;
        for (uint32_t r0 = 0; r0 < n; r0 += c) {
            double x = 0, hr = 0;
            for (uint32_t k = r0; k < n && k < r0 + c; k++) {
                x += vw[k].rmax - vw[k].rmin;
                hr = fmax(hr, vw[k].umax - vw[k].umin);
            }
            wm = fmax(wm, x);
            hm += hr;
        }
        double ppm = size / fmax(wm, hm);
        if (ppm > best_ppm * (1 + 1e-9)) best_ppm = ppm, best_c = c;
    }
    /* Rounding may push a side past `size` (each tile at least a pixel):
     * shrink until it fits, which it does once every tile is one pixel
     * (at most 9 tiles in a side of 32 or more). */
    double ppm = best_ppm;
    for (int it = 0; it < 2000; it++) {
        grid_at(vw, n, best_c, ppm, W, H);
        if (*W <= size && *H <= size) return;
        ppm *= 0.995;
    }
    grid_at(vw, n, best_c, 0, W, H);
}

/* Which vertices the mesh's triangles use (1) into used[vertex_count]. */
static void used_vertices(const banyan_mesh *m, unsigned char *used) {
    memset(used, 0, m->vertex_count);
    for (uint32_t k = 0; k < m->index_count; k++) used[m->indices[k]] = 1;
}

/* Each group's bounds over the vertices its parts' triangles use (lo and
 * hi start empty: a group without triangles keeps lo above hi). */
static void group_bounds(const banyan_mesh *m, const unsigned char *used, double (*lo)[3], double (*hi)[3]) {
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count; v++) {
            if (!used[v]) continue;
            const float *P = m->positions + 3 * (size_t)v;
            for (int j = 0; j < 3; j++) {
                lo[pt->group][j] = P[j] < lo[pt->group][j] ? P[j] : lo[pt->group][j]; /* finite: fmin's value */
                hi[pt->group][j] = P[j] > hi[pt->group][j] ? P[j] : hi[pt->group][j];
            }
        }
    }
}

/* Group g's views: `planes` vertical ones about its centre c (seen from
 * +n, picture x along -d, not mirrored), each spanning the group's extent
 * across it and zmin .. zmax up, then the top view (from +z, x to the
 * right, y up the picture); a flat extent is widened to 1e-6 m. */
static void group_views(const banyan_mesh *m, const unsigned char *used, uint32_t g, uint32_t planes,
                        const double lo[3], const double hi[3], double c[2], double *zmin_out, double *zmax_out,
                        bb_view *vw) {
    c[0] = 0.5 * (lo[0] + hi[0]), c[1] = 0.5 * (lo[1] + hi[1]);
    double zmin = lo[2], zmax = hi[2];
    if (zmax - zmin < 1e-6) zmax = zmin + 1e-6;
    double dk[BB_MAX_PLANES][2], smin[BB_MAX_PLANES], smax[BB_MAX_PLANES];
    for (uint32_t k = 0; k < planes; k++) {
        double a = BB_PI * k / planes;
        dk[k][0] = dm_cos(a), dk[k][1] = dm_sin(a);
        smin[k] = INFINITY, smax[k] = -INFINITY;
    }
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group != g) continue;
        for (uint32_t i = pt->vertex_offset; i < pt->vertex_offset + pt->vertex_count; i++) {
            if (!used[i]) continue;
            const float *P = m->positions + 3 * (size_t)i;
            for (uint32_t v = 0; v < planes; v++) {
                double s = (P[0] - c[0]) * dk[v][0] + (P[1] - c[1]) * dk[v][1];
                smin[v] = s < smin[v] ? s : smin[v]; /* finite: fmin's value */
                smax[v] = s > smax[v] ? s : smax[v];
            }
        }
    }
    /* Vertical views: seen from +n, picture x along -d (not mirrored). */
    for (uint32_t k = 0; k < planes; k++) {
        if (smax[k] - smin[k] < 1e-6) smin[k] -= 5e-7, smax[k] += 5e-7;
        bb_view *w = &vw[k];
        double n2[2] = {-dk[k][1], dk[k][0]};
        w->r[0] = -dk[k][0], w->r[1] = -dk[k][1], w->r[2] = 0;
        w->up[0] = 0, w->up[1] = 0, w->up[2] = 1;
        w->v[0] = n2[0], w->v[1] = n2[1], w->v[2] = 0;
        double rc = c[0] * w->r[0] + c[1] * w->r[1];
        w->rmin = rc - smax[k], w->rmax = rc - smin[k];
        w->umin = zmin, w->umax = zmax;
    }
    /* The top view: from +z, x to the right, y up the picture. */
    {
        bb_view *w = &vw[planes];
        double x0 = lo[0], x1 = hi[0], y0 = lo[1], y1 = hi[1];
        if (x1 - x0 < 1e-6) x0 -= 5e-7, x1 += 5e-7;
        if (y1 - y0 < 1e-6) y0 -= 5e-7, y1 += 5e-7;
        w->r[0] = 1, w->r[1] = 0, w->r[2] = 0;
        w->up[0] = 0, w->up[1] = 1, w->up[2] = 0;
        w->v[0] = 0, w->v[1] = 0, w->v[2] = 1;
        w->rmin = x0, w->rmax = x1, w->umin = y0, w->umax = y1;
    }
    *zmin_out = zmin, *zmax_out = zmax;
}

/* Two parts and materials per group, one picture: the vertical
 * cards, double sided, and the top card, single sided facing up
 * (an engine that culls back faces does not show its unlit
 * underside from the ground). */
static void card_parts(const banyan_mesh *m, banyan_mesh *o, uint32_t g, uint32_t cd, uint32_t planes) {
    const uint32_t nvc = planes * 8 + 4, nic = planes * 12 + 6; /* per card set */
    float rough = mean_roughness(m, g);
    for (uint32_t h = 0; h < 2; h++) {
        banyan_material *mt = &o->materials[2 * cd + h];
        snprintf(mt->name, sizeof mt->name, h ? "billboard_top_%u" : "billboard_%u", g);
        mt->base_color[0] = mt->base_color[1] = mt->base_color[2] = mt->base_color[3] = 1.0f;
        mt->roughness = rough;
        mt->double_sided = !h;
        mt->texture = BANYAN_TEX_NONE;
        mt->alpha_cutoff = 0.5f;
        mt->translucency = 0.3f;
        mt->image = (int32_t)cd + 1; /* images[cd] */
        banyan_part *pp = &o->parts[2 * cd + h];
        pp->vertex_offset = cd * nvc + (h ? planes * 8 : 0);
        pp->vertex_count = h ? 4 : planes * 8;
        pp->index_offset = cd * nic + (h ? planes * 12 : 0);
        pp->index_count = h ? 6 : planes * 12;
        pp->material = 2 * cd + h;
        pp->group = g;
    }
}

/* Card set cd's quads: two half planes per vertical view (split at the
 * axis), then the top card; corners counter-clockwise seen from +v, their
 * UVs in the W x H picture, and birth 1 with (when wind) the group's pivot
 * at its centre's foot, its level 0, a stiffness falling to 0.5 at the top
 * and its phase. */
static void card_quads(banyan_mesh *o, uint32_t cd, const bb_view *vw, uint32_t planes, const double c[2], double zmin,
                       double zmax, uint32_t W, uint32_t H, int wind, float phase) {
    const uint32_t tiles = planes + 1;
    const banyan_part *op = &o->parts[2 * cd];
    for (uint32_t k = 0; k < tiles; k++) {
        const bb_view *w = &vw[k];
        uint32_t halves = k < planes ? 2 : 1;
        double rc = c[0] * w->r[0] + c[1] * w->r[1];
        double r_mid = k < planes ? fmin(fmax(rc, w->rmin), w->rmax) : w->rmax;
        double rv[3] = {w->rmin, r_mid, w->rmax};
        double depth = k < planes ? c[0] * w->v[0] + c[1] * w->v[1] : zmin + BB_TOP_AT * (zmax - zmin);
        for (uint32_t h = 0; h < halves; h++) {
            uint32_t base = op->vertex_offset + (k * 2 + h) * 4;
            double ra = rv[h], rb = k < planes ? rv[h + 1] : w->rmax;
            double corner[4][2] = {{ra, w->umin}, {rb, w->umin}, {rb, w->umax}, {ra, w->umax}};
            for (int e = 0; e < 4; e++) {
                uint32_t v = base + (uint32_t)e;
                double rr = corner[e][0], uu = corner[e][1];
                float *P = o->positions + 3 * (size_t)v, *N = o->normals + 3 * (size_t)v, *T = o->uvs + 2 * (size_t)v;
                for (int j = 0; j < 3; j++) {
                    P[j] = (float)(rr * w->r[j] + uu * w->up[j] + depth * w->v[j]);
                    N[j] = (float)w->v[j];
                }
                T[0] = (float)((w->x0 + (rr - w->rmin) / (w->rmax - w->rmin) * w->w) / W);
                T[1] = (float)(1.0 - (w->y0 + (w->umax - uu) / (w->umax - w->umin) * w->h) / H);
                float t = (float)((P[2] - zmin) / (zmax - zmin));
                o->attributes[0].data[v] = 1.0f;
                if (wind) {
                    o->attributes[1].data[v] = (float)c[0];
                    o->attributes[2].data[v] = (float)c[1];
                    o->attributes[3].data[v] = (float)zmin;
                    o->attributes[4].data[v] = 0.0f;
                    o->attributes[5].data[v] = 1.0f - 0.5f * t;
                    o->attributes[6].data[v] = phase;
                    o->attributes[7].data[v] = 0.0f;
                }
            }
            uint32_t *I = o->indices + op->index_offset + (k * 2 + h) * 6;
            I[0] = base, I[1] = base + 1, I[2] = base + 2;
            I[3] = base, I[4] = base + 2, I[5] = base + 3;
        }
    }
}

banyan_status lod_billboard(const banyan_mesh *m, const banyan_lod_params *p, prog *pg, banyan_mesh **out,
                            banyan_error *err) {
    uint32_t planes = (uint32_t)p->billboard_planes, size = (uint32_t)p->billboard_size, ss = bb_ss(size);
    uint32_t tiles = planes + 1, nvc = planes * 8 + 4, nic = planes * 12 + 6; /* per card set */
    uint32_t n_groups = 0;
    for (uint32_t q = 0; q < m->part_count; q++)
        if (m->parts[q].group + 1 > n_groups) n_groups = m->parts[q].group + 1;
    /* Which groups have vertices, and their bounds. */
    double (*lo)[3] = malloc(sizeof(double[3]) * n_groups), (*hi)[3] = malloc(sizeof(double[3]) * n_groups);
    uint32_t *slot = malloc(sizeof(uint32_t) * n_groups);
    unsigned char *used = malloc(m->vertex_count);
    banyan_mesh *o = calloc(1, sizeof *o);
    bb_paint pa;
    memset(&pa, 0, sizeof pa);
    bb_tile tl = {0, 0, NULL, NULL};
    size_t tile_cap = 0, tri_cap = 0, proj_cap = 0;
    bb_tri *tri = NULL;
    double *proj = NULL;
    float *share = NULL;
    banyan_status st = BANYAN_E_NOMEM;
    if (!lo || !hi || !slot || !used || !o) goto fail;
    for (uint32_t g = 0; g < n_groups; g++) {
        slot[g] = UINT32_MAX;
        for (int j = 0; j < 3; j++) lo[g][j] = INFINITY, hi[g][j] = -INFINITY;
    }
    used_vertices(m, used);
    group_bounds(m, used, lo, hi);
    uint32_t n_cards = 0;
    for (uint32_t g = 0; g < n_groups; g++)
        if (lo[g][0] <= hi[g][0]) slot[g] = n_cards++;
    if ((st = paint_init(m, &pa))) goto fail;
    st = BANYAN_E_NOMEM;
    int wind = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X) || !banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH);
    uint32_t n_attr = wind ? 8 : 1;
    static const char *const names[8] = {BANYAN_ATTR_BIRTH,          BANYAN_ATTR_WIND_PIVOT_X,
                                         BANYAN_ATTR_WIND_PIVOT_Y,   BANYAN_ATTR_WIND_PIVOT_Z,
                                         BANYAN_ATTR_WIND_LEVEL,     BANYAN_ATTR_WIND_STIFFNESS,
                                         BANYAN_ATTR_WIND_PHASE,     BANYAN_ATTR_WIND_FLUTTER};
    size_t nv = (size_t)n_cards * nvc, ni = (size_t)n_cards * nic;
    o->vertex_count = (uint32_t)nv;
    o->index_count = (uint32_t)ni;
    o->positions = malloc(3 * sizeof(float) * nv);
    o->normals = malloc(3 * sizeof(float) * nv);
    o->uvs = malloc(2 * sizeof(float) * nv);
    o->indices = malloc(sizeof(uint32_t) * ni);
    o->attributes = calloc(n_attr, sizeof(banyan_attribute));
    o->materials = calloc(2 * (size_t)n_cards, sizeof(banyan_material));
    o->parts = calloc(2 * (size_t)n_cards, sizeof(banyan_part));
    o->images = calloc(n_cards, sizeof(banyan_image));
    if (!o->positions || !o->normals || !o->uvs || !o->indices || !o->attributes || !o->materials || !o->parts ||
        !o->images)
        goto fail;
    o->attribute_count = n_attr;
    for (uint32_t a = 0; a < n_attr; a++) {
        strncpy(o->attributes[a].name, names[a], BANYAN_NAME_MAX - 1);
        if (!(o->attributes[a].data = malloc(sizeof(float) * nv))) goto fail;
    }
    o->material_count = o->part_count = 2 * n_cards;
    o->image_count = n_cards;
    if ((st = lod_copy_common(m, o, 0))) goto fail;
    st = BANYAN_E_NOMEM;

    for (uint32_t g = 0; g < n_groups; g++) {
        uint32_t cd = slot[g];
        if (cd == UINT32_MAX) continue;
        if (prog_at(pg, (double)g / n_groups)) {
            st = BANYAN_E_LIMIT;
            goto fail;
        }
        double c[2], zmin, zmax;
        bb_view vw[BB_MAX_TILES];
        group_views(m, used, g, planes, lo[g], hi[g], c, &zmin, &zmax, vw);
        uint32_t W, H;
        layout(vw, tiles, size, &W, &H);
        banyan_image *im = &o->images[cd];
        im->width = W;
        im->height = H;
        im->channels = 4;
        im->pixels = calloc((size_t)W * H, 4);
        if (!im->pixels) goto fail;
        size_t n_tri = 0;
        for (uint32_t q = 0; q < m->part_count; q++)
            if (m->parts[q].group == g) n_tri += m->parts[q].index_count / 3;
        if (n_tri > tri_cap) {
            free(tri);
            tri_cap = n_tri;
            if (!(tri = malloc(sizeof(bb_tri) * tri_cap))) goto fail;
        }
        tris_of_group(m, g, tri);
        size_t n_vtx = 0;
        for (uint32_t q = 0; q < m->part_count; q++)
            if (m->parts[q].group == g && m->parts[q].vertex_count > n_vtx) n_vtx = m->parts[q].vertex_count;
        if (n_vtx > proj_cap) {
            free(proj);
            proj_cap = n_vtx;
            if (!(proj = malloc(3 * sizeof(double) * proj_cap))) goto fail;
        }
        for (uint32_t k = 0; k < tiles; k++) {
            if (prog_at(pg, (double)g / n_groups)) {
                st = BANYAN_E_LIMIT;
                goto fail;
            }
            tl.sw = vw[k].w * ss, tl.sh = vw[k].h * ss;
            size_t ns = (size_t)tl.sw * tl.sh;
            if (ns > tile_cap) { /* one set of buffers for every tile, grown as needed */
                free(tl.depth), free(tl.rgb), free(share);
                tile_cap = ns;
                tl.depth = malloc(sizeof(float) * ns);
                tl.rgb = malloc(3 * sizeof(float) * ns);
                share = malloc(sizeof(float) * ns); /* a pixel has at least one sample */
                if (!tl.depth || !tl.rgb || !share) goto fail;
            }
            for (size_t i = 0; i < ns; i++) tl.depth[i] = -INFINITY;
            draw_view(m, g, &pa, tri, proj, card_light(&vw[k]), &vw[k], &tl);
            resolve(&tl, ss, &vw[k], pa.to8, im->pixels, W, share);
        }
        if (dilate(im->pixels, W, H)) goto fail;

        card_parts(m, o, g, cd, planes);
        card_quads(o, cd, vw, planes, c, zmin, zmax, W, H, wind, (float)wind_phase_of(p->seed, g));
    }
    free(lo); free(hi); free(slot); free(used); free(tl.depth); free(tl.rgb); free(share); free(tri); free(proj);
    paint_free(&pa);
    *out = o;
    banyan_error_clear(err);
    return BANYAN_OK;
fail:
    free(lo); free(hi); free(slot); free(used); free(tl.depth); free(tl.rgb); free(share); free(tri); free(proj);
    paint_free(&pa);
    banyan_mesh_free(o);
    if (st == BANYAN_E_LIMIT) return prog_fail(pg, err, "the billboard level of detail");
    return banyan_fail(err, st ? st : BANYAN_E_NOMEM, "out of memory drawing the billboards of %u vertices",
                       m->vertex_count);
}
