/* test_lod_look.c - levels of detail that look like the plant they stand
 * for (docs/lod.md):
 *   - the billboard: 2 x planes vertical half quads (one part) and one
 *     horizontal top card at 0.6 .. 0.7 of the height over the plant's
 *     footprint (the next part, its vertices right after); each
 *     card's picture, compared with this file's own rendering of the full
 *     mesh along the card's normal (z-buffered, the leaf texture's alpha
 *     tested at 0.5 per sample, 6 x 6 samples per picture pixel, colour =
 *     texel x vertex colour, no light), covers the same share of the tile
 *     at the engine's cutoff 0.5 (within 10 %), and over all cards the
 *     covered pixels are 0.85 .. 1.25 x as bright as the plant's own
 *     colours (the pictures carry the plant's light over the card's own,
 *     near 1 on average: a card no darker than the tree);
 *   - the 0.15 level keeps round limbs: a skeleton segment is round when
 *     the bark vertices around it spread as much one way as the other
 *     across the axis (the square root of the ratio of the section's
 *     second moments >= 0.5); at 0.15, at least 90 % of the segments of
 *     radius >= 5 cm are round, and of those >= 2 cm at least 0.9 x the
 *     share the plant has (twigs sprouting at a limb's surface make a few
 *     segments read flat on the plant too); the level still holds 0.15 of
 *     the triangles within 10 %.
 * Prints the figures. With an argument (a directory), writes each
 * billboard picture there as PNG. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "lod_plants.h"

static float lin_of(uint8_t c) {
    double x = c / 255.0;
    return (float)(x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4));
}

static double lum(const float c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

typedef struct tex_cache {
    int32_t kind[16], season[16];
    banyan_image *im[16];
    int n;
} tex_cache;

static const banyan_image *tex_of(const banyan_mesh *m, const banyan_material *mt, tex_cache *tc) {
    if (mt->image > 0) return &m->images[mt->image - 1];
    if (mt->texture == BANYAN_TEX_NONE) return NULL;
    for (int i = 0; i < tc->n; i++)
        if (tc->kind[i] == mt->texture && tc->season[i] == mt->season) return tc->im[i];
    if (tc->n == 16) return NULL;
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.kind = mt->texture;
    tp.season = mt->season;
    tp.size = 512;
    banyan_image *im = NULL;
    if (banyan_texture_generate(&tp, &im, NULL, NULL)) return NULL;
    tc->kind[tc->n] = mt->texture, tc->season[tc->n] = mt->season, tc->im[tc->n] = im;
    return tc->im[tc->n++];
}

/* The full mesh's group g seen along n (depth grows toward +n) over the
 * rectangle [r0, r1] x [u0, u1] of the axes r, up, at sw x sh samples:
 * returns the covered share, and the covered samples' mean luminance. */
static double render_ref(const banyan_mesh *m, uint32_t g, const double r[3], const double up[3], const double n[3],
                         double r0, double r1, double u0, double u1, uint32_t sw, uint32_t sh, tex_cache *tc,
                         double *mean_lum) {
    size_t ns = (size_t)sw * sh;
    float *depth = malloc(sizeof(float) * ns), *col = malloc(3 * sizeof(float) * ns);
    if (!depth || !col) {
        free(depth), free(col);
        return -1;
    }
    for (size_t i = 0; i < ns; i++) depth[i] = -INFINITY;
    double sx = sw / (r1 - r0), sy = sh / (u1 - u0);
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group != g) continue;
        const banyan_material *mt = &m->materials[pt->material];
        const banyan_image *tex = m->uvs ? tex_of(m, mt, tc) : NULL;
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k += 3) {
            double X[3], Y[3], Z[3], U[3] = {0}, V[3] = {0}, tint[3] = {0, 0, 0};
            for (int j = 0; j < 3; j++) {
                uint32_t v = m->indices[k + j];
                const float *P = m->positions + 3 * (size_t)v;
                X[j] = (P[0] * r[0] + P[1] * r[1] + P[2] * r[2] - r0) * sx;
                Y[j] = (u1 - (P[0] * up[0] + P[1] * up[1] + P[2] * up[2])) * sy;
                Z[j] = P[0] * n[0] + P[1] * n[1] + P[2] * n[2];
                if (m->uvs) U[j] = m->uvs[2 * (size_t)v], V[j] = m->uvs[2 * (size_t)v + 1];
                for (int e = 0; e < 3; e++) tint[e] += (m->colors ? m->colors[4 * (size_t)v + e] : 1.0f) / 3;
            }
            double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
            if (fabs(area) < 1e-12) continue;
            long x0 = (long)floor(fmin(X[0], fmin(X[1], X[2]))), x1 = (long)ceil(fmax(X[0], fmax(X[1], X[2])));
            long y0 = (long)floor(fmin(Y[0], fmin(Y[1], Y[2]))), y1 = (long)ceil(fmax(Y[0], fmax(Y[1], Y[2])));
            x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
            x1 = x1 > (long)sw - 1 ? (long)sw - 1 : x1, y1 = y1 > (long)sh - 1 ? (long)sh - 1 : y1;
            for (long y = y0; y <= y1; y++)
                for (long x = x0; x <= x1; x++) {
                    double px = x + 0.5, py = y + 0.5;
                    double w0 = ((X[1] - px) * (Y[2] - py) - (X[2] - px) * (Y[1] - py)) / area;
                    double w1 = ((X[2] - px) * (Y[0] - py) - (X[0] - px) * (Y[2] - py)) / area;
                    double w2 = 1 - w0 - w1;
                    if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                    double z = w0 * Z[0] + w1 * Z[1] + w2 * Z[2];
                    size_t s = (size_t)y * sw + (size_t)x;
                    if (!(z > depth[s])) continue;
                    float c[3];
                    if (tex) {
                        double tu = w0 * U[0] + w1 * U[1] + w2 * U[2], tv = w0 * V[0] + w1 * V[1] + w2 * V[2];
                        double fx = tu - floor(tu), fy = (1 - tv) - floor(1 - tv);
                        uint32_t ix = (uint32_t)(fx * tex->width) % tex->width,
                                 iy = (uint32_t)(fy * tex->height) % tex->height;
                        const uint8_t *t = tex->pixels + ((size_t)iy * tex->width + ix) * tex->channels;
                        if (tex->channels == 4 && t[3] < 128) continue;
                        for (int e = 0; e < 3; e++) c[e] = lin_of(t[e]) * (float)tint[e];
                    } else {
                        for (int e = 0; e < 3; e++) c[e] = mt->base_color[e] * (float)tint[e];
                    }
                    depth[s] = (float)z;
                    memcpy(col + 3 * s, c, sizeof c);
                }
        }
    }
    size_t cov = 0;
    double ls = 0;
    for (size_t i = 0; i < ns; i++)
        if (depth[i] > -INFINITY) cov++, ls += lum(col + 3 * i);
    *mean_lum = cov ? ls / cov : 0;
    free(depth), free(col);
    return (double)cov / ns;
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The billboard of `name` against the full mesh. */
static void check_billboard_look(const char *name, const banyan_mesh *m, const char *png_dir) {
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    p.billboard = 1;
    CHECK(p.billboard_planes >= 3 && p.billboard_planes <= 4, "default billboard_planes %d, want 3 or 4",
          p.billboard_planes);
    banyan_error err = {0, ""};
    banyan_mesh *o = NULL;
    CHECK(banyan_mesh_lod(m, &p, &o, &err) == BANYAN_OK && o, "%s billboard: %s", name, err.message);
    if (!o) return;
    tex_cache tc;
    memset(&tc, 0, sizeof tc);
    uint32_t planes = (uint32_t)p.billboard_planes;
    double zlo = INFINITY, zhi = -INFINITY;
    for (uint32_t v = 0; v < m->vertex_count; v++)
        zlo = fmin(zlo, m->positions[3 * (size_t)v + 2]), zhi = fmax(zhi, m->positions[3 * (size_t)v + 2]);
    double cov_card_all = 0, cov_tree_all = 0, lum_card_all = 0, lum_tree_all = 0;
    for (uint32_t q = 0; q < o->part_count && q < 1; q++) {
        const banyan_part *pt = &o->parts[q], *tp = &o->parts[q + 1];
        CHECK(o->part_count == 2 && pt->index_count == planes * 12 && pt->vertex_count == planes * 8 &&
                  tp->index_count == 6 && tp->vertex_count == 4 && tp->vertex_offset == pt->vertex_count,
              "%s billboard: %u parts, %u + %u indices, %u + %u vertices for %u planes and a top card", name,
              o->part_count, pt->index_count, tp->index_count, pt->vertex_count, tp->vertex_count, planes);
        if (o->part_count != 2 || tp->vertex_offset != pt->vertex_count) continue;
        const banyan_image *im = &o->images[o->materials[pt->material].image - 1];
        if (png_dir) {
            uint8_t *png = NULL;
            size_t sz = 0;
            char path[1024];
            snprintf(path, sizeof path, "%s/%s_billboard.png", png_dir, name);
            FILE *f = fopen(path, "wb");
            if (f && !banyan_image_png(im, &png, &sz, NULL)) fwrite(png, 1, sz, f);
            if (f) fclose(f);
            banyan_png_free(png);
        }
        for (uint32_t k = 0; k <= planes; k++) {
            uint32_t base = pt->vertex_offset + k * 8, nvk = k < planes ? 8 : 4;
            const float *P0 = o->positions + 3 * (size_t)base, *P1 = P0 + 3, *P3 = P0 + 9;
            double n[3], r[3], up[3];
            for (int j = 0; j < 3; j++)
                n[j] = o->normals[3 * (size_t)base + j], r[j] = P1[j] - P0[j], up[j] = P3[j] - P0[j];
            double lr = sqrt(dot3(r, r)), lu = sqrt(dot3(up, up));
            for (int j = 0; j < 3; j++) r[j] /= lr, up[j] /= lu;
            if (k == planes) {
                CHECK(fabs(n[2] - 1) < 1e-6, "%s: the top card's normal is (%g %g %g)", name, n[0], n[1], n[2]);
                double t = (P0[2] - zlo) / (zhi - zlo);
                CHECK(t >= 0.6 && t <= 0.7, "%s: the top card at %.2f of the height", name, t);
            } else {
                CHECK(fabs(n[2]) < 1e-6, "%s: card %u is not vertical", name, k);
            }
            double r0 = INFINITY, r1 = -INFINITY, u0 = INFINITY, u1 = -INFINITY, tu0 = 2, tu1 = -1, tv0 = 2, tv1 = -1;
            for (uint32_t e = 0; e < nvk; e++) {
                const float *P = o->positions + 3 * (size_t)(base + e), *T = o->uvs + 2 * (size_t)(base + e);
                double Pd[3] = {P[0], P[1], P[2]};
                r0 = fmin(r0, dot3(Pd, r)), r1 = fmax(r1, dot3(Pd, r));
                u0 = fmin(u0, dot3(Pd, up)), u1 = fmax(u1, dot3(Pd, up));
                tu0 = fmin(tu0, T[0]), tu1 = fmax(tu1, T[0]), tv0 = fmin(tv0, T[1]), tv1 = fmax(tv1, T[1]);
            }
            long px0 = lrint(tu0 * im->width), px1 = lrint(tu1 * im->width);
            long py0 = lrint((1 - tv1) * im->height), py1 = lrint((1 - tv0) * im->height);
            size_t cov = 0, np = (size_t)(px1 - px0) * (size_t)(py1 - py0);
            double lc = 0;
            for (long y = py0; y < py1; y++)
                for (long x = px0; x < px1; x++) {
                    const uint8_t *c = im->pixels + 4 * ((size_t)y * im->width + (size_t)x);
                    if (c[3] < 128) continue;
                    float f[3] = {lin_of(c[0]), lin_of(c[1]), lin_of(c[2])};
                    cov++, lc += lum(f);
                }
            double lt = 0;
            double ct = render_ref(m, pt->group, r, up, n, r0, r1, u0, u1, (uint32_t)(px1 - px0) * 6,
                                   (uint32_t)(py1 - py0) * 6, &tc, &lt);
            double cc = np ? (double)cov / np : 0;
            lc = cov ? lc / cov : 0;
            printf("%-13s card %u (%s): %ldx%ld px, covered %.3f (tree %.3f, ratio %.3f), luminance %.4f (tree %.4f, "
                   "ratio %.3f)\n",
                   name, k, k < planes ? "vertical" : "top", px1 - px0, py1 - py0, cc, ct, ct > 0 ? cc / ct : 0, lc, lt,
                   lt > 0 ? lc / lt : 0);
            CHECK(ct > 0 && fabs(cc / ct - 1) <= 0.10, "%s card %u: covers %.3f of its tile, the tree %.3f", name, k,
                  cc, ct);
            cov_card_all += cc * np, cov_tree_all += ct * np;
            lum_card_all += lc * cc * np, lum_tree_all += lt * ct * np;
        }
    }
    double lr = lum_tree_all > 0 ? lum_card_all / lum_tree_all * cov_tree_all / cov_card_all : 0;
    printf("%-13s all cards: coverage ratio %.3f, luminance ratio %.3f\n", name,
           cov_tree_all > 0 ? cov_card_all / cov_tree_all : 0, lr);
    CHECK(lr >= 0.85 && lr <= 1.25, "%s: the cards' luminance is %.3f of the tree's", name, lr);
    for (int i = 0; i < tc.n; i++) banyan_image_free(tc.im[i]);
    banyan_mesh_free(o);
}

/* Roundness of the bark of m around its skeleton: share of sampled
 * segments (radius >= rmin) whose section's second moments across the
 * axis have sqrt(min / max) >= 0.5, and the median of that figure. */
static double roundness(const banyan_mesh *m, double rmin, double *median, uint32_t *n_seg) {
    *median = 0, *n_seg = 0;
    if (!m->skel_edge_count || !m->skel_radius) return -1;
    unsigned char *wood = calloc(m->vertex_count, 1);
    uint32_t ne = m->skel_edge_count, n_big = 0;
    for (uint32_t e = 0; e < ne; e++)
        n_big += fmin(m->skel_radius[m->skel_edges[2 * e]], m->skel_radius[m->skel_edges[2 * e + 1]]) >= rmin;
    uint32_t step = n_big / 300 ? n_big / 300 : 1, cap = n_big / step + 1, seen = 0;
    double *fig = malloc(sizeof(double) * cap);
    if (!wood || !fig) {
        free(wood), free(fig);
        return -1;
    }
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (m->materials[pt->material].alpha_cutoff > 0) continue;
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k++) wood[m->indices[k]] = 1;
    }
    uint32_t n = 0, good = 0;
    for (uint32_t e = 0; e < ne && n < cap; e++) {
        uint32_t a = m->skel_edges[2 * e], b = m->skel_edges[2 * e + 1];
        double ra = m->skel_radius[a], rb = m->skel_radius[b];
        if (fmin(ra, rb) < rmin || seen++ % step) continue;
        const float *A = m->skel_points + 3 * (size_t)a, *B = m->skel_points + 3 * (size_t)b;
        double ax[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, len = sqrt(dot3(ax, ax));
        if (len < 1e-6) continue;
        for (int j = 0; j < 3; j++) ax[j] /= len;
        double e1[3] = {0, 0, 0};
        e1[fabs(ax[0]) < 0.6 ? 0 : fabs(ax[1]) < 0.6 ? 1 : 2] = 1;
        double d = dot3(e1, ax);
        for (int j = 0; j < 3; j++) e1[j] -= d * ax[j];
        double l1 = sqrt(dot3(e1, e1));
        for (int j = 0; j < 3; j++) e1[j] /= l1;
        double e2[3] = {ax[1] * e1[2] - ax[2] * e1[1], ax[2] * e1[0] - ax[0] * e1[2], ax[0] * e1[1] - ax[1] * e1[0]};
        double reach = 1.6 * fmax(ra, rb) + 0.01, sxx = 0, syy = 0, sxy = 0;
        uint32_t cnt = 0;
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            if (!wood[v]) continue;
            const float *P = m->positions + 3 * (size_t)v;
            double w[3] = {P[0] - A[0], P[1] - A[1], P[2] - A[2]}, t = dot3(w, ax);
            if (t < -ra || t > len + rb) continue;
            double x = dot3(w, e1), y = dot3(w, e2);
            if (x * x + y * y > reach * reach) continue;
            sxx += x * x, syy += y * y, sxy += x * y, cnt++;
        }
        if (cnt < 3) continue;
        double tr = sxx + syy, det = sxx * syy - sxy * sxy, disc = sqrt(fmax(0, tr * tr / 4 - det));
        double l_hi = tr / 2 + disc, l_lo = tr / 2 - disc;
        double f = l_hi > 0 ? sqrt(fmax(0, l_lo) / l_hi) : 0;
        fig[n++] = f;
        good += f >= 0.5;
    }
    for (uint32_t i = 1; i < n; i++) /* insertion sort: a few hundred */
        for (uint32_t j = i; j > 0 && fig[j - 1] > fig[j]; j--) {
            double t = fig[j];
            fig[j] = fig[j - 1], fig[j - 1] = t;
        }
    *median = n ? fig[n / 2] : 0;
    *n_seg = n;
    free(wood), free(fig);
    return n ? (double)good / n : -1;
}

static void check_round(const char *name, const banyan_mesh *m) {
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    p.ratio = 0.15;
    banyan_error err = {0, ""};
    banyan_mesh *o = NULL;
    CHECK(banyan_mesh_lod(m, &p, &o, &err) == BANYAN_OK && o, "%s 0.15: %s", name, err.message);
    if (!o) return;
    static const double rmins[3] = {0.02, 0.05, 0.10};
    for (int i = 0; i < 3; i++) {
        double med0, med1;
        uint32_t n0, n1;
        double s0 = roundness(m, rmins[i], &med0, &n0), s1 = roundness(o, rmins[i], &med1, &n1);
        printf("%-13s radius >= %.2f m: round (>= 0.5) on %.3f of %u segments (median %.2f), at 0.15 on %.3f of %u "
               "(median %.2f)\n",
               name, rmins[i], s0, n0, med0, s1, n1, med1);
        if (i == 0)
            CHECK(s1 >= 0.9 * s0, "%s 0.15: round on %.3f of the segments of %.2f m or more, the plant on %.3f", name,
                  s1, rmins[i], s0);
        if (i == 1) CHECK(s1 >= 0.9, "%s 0.15: round on %.3f of the limbs of %.2f m or more", name, s1, rmins[i]);
    }
    double got = o->index_count / 3.0, want = 0.15 * m->index_count / 3.0;
    CHECK(fabs(got - want) <= 0.10 * want, "%s 0.15: %.0f triangles, want %.0f", name, got, want);
    banyan_mesh_free(o);
}

int main(int argc, char **argv) {
    const char *png_dir = argc > 1 ? argv[1] : NULL;
    const char *plants[] = {"keyaki_mature", "keyaki_young"};
    for (size_t i = 0; i < sizeof plants / sizeof plants[0]; i++) {
        banyan_error err = {0, ""};
        banyan_mesh *m = lod_plant(plants[i], 0, &err);
        CHECK(m != NULL, "%s: %s", plants[i], err.message);
        if (!m) continue;
        check_billboard_look(plants[i], m, png_dir);
        check_round(plants[i], m);
        banyan_mesh_free(m);
    }
    return check_done("test_lod_look");
}
