/* billboard.c - the last level of detail of a tree: crossed cards.
 *
 * Method: `billboard_planes` vertical planes through the vertical axis of
 * the plant's bounding box centre, at equal angles (two: a cross). Each
 * plane is as wide as the plant's vertices reach along it and as tall as
 * the plant, split at the axis into two quads (so an engine can sort the
 * halves), and shows an orthographic picture of the plant seen along the
 * plane's normal. The pictures are drawn here by a small software
 * rasteriser (z-buffered triangles, one flat colour each: the material's
 * base colour, or its leaf texture's average colour, times the vertex
 * colour, lit by a Lambert term from the vertex normals), alpha 255 where
 * the plant covers the pixel, and the colour dilated into the empty
 * pixels so mipmaps do not halo. The planes' pictures sit side by side
 * in one RGBA image per group (tree, or variant of an instanced avenue),
 * billboard_size pixels on its longer side. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "core/error.h"
#include "core/wind.h"
#include "lod_internal.h"

#define BB_MAX_PLANES 8
#define BB_PI 3.14159265358979323846

static float srgb_of_linear(float c) {
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * dm_powf(c, 1.0f / 2.4f) - 0.055f;
}

static float linear_of_srgb(float c) { return c <= 0.04045f ? c / 12.92f : dm_powf((c + 0.055f) / 1.055f, 2.4f); }

/* Linear RGB of each material as the picture shows it: a leaf texture's
 * mean colour over its opaque pixels (drawn small), else base_color. */
static banyan_status material_colours(const banyan_mesh *m, float (*rgb)[3]) {
    float tex[BANYAN_TEX_COUNT][2][3];
    int have[BANYAN_TEX_COUNT][2] = {{0}};
    for (uint32_t i = 0; i < m->material_count; i++) {
        const banyan_material *mt = &m->materials[i];
        for (int c = 0; c < 3; c++) rgb[i][c] = mt->base_color[c];
        int k = mt->texture, s = mt->season == BANYAN_SEASON_AUTUMN;
        if (mt->image >= 0 || (k != BANYAN_TEX_KEYAKI_LEAF && k != BANYAN_TEX_IVY_LEAF)) continue;
        if (!have[k][s]) {
            banyan_texture_params tp;
            banyan_texture_params_init(&tp);
            tp.kind = k;
            tp.season = s;
            tp.size = 64;
            banyan_image *im = NULL;
            banyan_status st = banyan_texture_generate(&tp, &im, NULL, NULL);
            if (st == BANYAN_E_NOMEM) return st;
            double sum[3] = {0, 0, 0}, n = 0;
            for (size_t px = 0; im && px < (size_t)im->width * im->height; px++) {
                const uint8_t *c = im->pixels + 4 * px;
                if (c[3] < 128) continue;
                for (int j = 0; j < 3; j++) sum[j] += linear_of_srgb(c[j] / 255.0f);
                n++;
            }
            banyan_image_free(im);
            for (int j = 0; j < 3; j++) tex[k][s][j] = n > 0 ? (float)(sum[j] / n) : mt->base_color[j];
            have[k][s] = 1;
        }
        for (int c = 0; c < 3; c++) rgb[i][c] = tex[k][s][c];
    }
    return BANYAN_OK;
}

typedef struct bb_view {
    double d[2], n[2];       /* the plane's horizontal direction and normal */
    double smin, smax;       /* the plant's reach along d from the axis */
    uint32_t x0, w;          /* its tile in the image */
} bb_view;

/* Draws the triangles of group g into one tile: seen from +n, picture x
 * runs along -d (so the picture is not mirrored), y down from zmax. */
static void draw_view(const banyan_mesh *m, uint32_t g, const float (*rgb)[3], const double c[2], double zmin,
                      double zmax, const bb_view *vw, uint8_t *img, float *depth, uint32_t W, uint32_t H) {
    double sx = vw->w / (vw->smax - vw->smin), sy = H / (zmax - zmin);
    double L[3] = {0.5 * vw->n[0], 0.5 * vw->n[1], 0.8}, ll = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    for (int j = 0; j < 3; j++) L[j] /= ll;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->group != g) continue;
        const float *mc = rgb[pt->material];
        for (uint32_t k = pt->index_offset; k + 2 < pt->index_offset + pt->index_count; k += 3) {
            double X[3], Y[3], Z[3], col[3] = {0, 0, 0}, nn[3] = {0, 0, 0};
            for (int j = 0; j < 3; j++) {
                uint32_t v = m->indices[k + j];
                const float *P = m->positions + 3 * (size_t)v;
                double s = (P[0] - c[0]) * vw->d[0] + (P[1] - c[1]) * vw->d[1];
                X[j] = (vw->smax - s) * sx + vw->x0;
                Y[j] = (zmax - P[2]) * sy;
                Z[j] = (P[0] - c[0]) * vw->n[0] + (P[1] - c[1]) * vw->n[1];
                for (int e = 0; e < 3; e++) {
                    col[e] += mc[e] * (m->colors ? m->colors[4 * (size_t)v + e] : 1.0f) / 3.0;
                    if (m->normals) nn[e] += m->normals[3 * (size_t)v + e];
                }
            }
            double nl = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            double lam = nl > 0 ? fabs(nn[0] * L[0] + nn[1] * L[1] + nn[2] * L[2]) / nl : 1.0;
            double shade = 0.35 + 0.65 * lam;
            uint8_t rgb8[3];
            for (int e = 0; e < 3; e++) rgb8[e] = (uint8_t)lrintf(255.0f * srgb_of_linear((float)(col[e] * shade)));
            double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
            /* Thin triangles seen edge-on still cover what they pass: a
             * sliver smaller than a pixel lights the pixel at its centre. */
            long x0 = (long)floor(fmin(X[0], fmin(X[1], X[2]))), x1 = (long)floor(fmax(X[0], fmax(X[1], X[2])));
            long y0 = (long)floor(fmin(Y[0], fmin(Y[1], Y[2]))), y1 = (long)floor(fmax(Y[0], fmax(Y[1], Y[2])));
            long lo = vw->x0, hi = (long)vw->x0 + vw->w - 1;
            x0 = x0 < lo ? lo : x0;
            x1 = x1 > hi ? hi : x1;
            y0 = y0 < 0 ? 0 : y0;
            y1 = y1 > (long)H - 1 ? (long)H - 1 : y1;
            if (x0 > x1 || y0 > y1) continue;
            if (fabs(area) < 1e-12 || (x0 == x1 && y0 == y1)) {
                double zc = (Z[0] + Z[1] + Z[2]) / 3;
                long cx = (long)floor((X[0] + X[1] + X[2]) / 3), cy = (long)floor((Y[0] + Y[1] + Y[2]) / 3);
                if (cx < x0 || cx > x1 || cy < y0 || cy > y1) continue;
                size_t px = (size_t)cy * W + (size_t)cx;
                if (zc > depth[px]) {
                    depth[px] = (float)zc;
                    memcpy(img + 4 * px, rgb8, 3);
                    img[4 * px + 3] = 255;
                }
                continue;
            }
            for (long y = y0; y <= y1; y++)
                for (long x = x0; x <= x1; x++) {
                    double px_ = x + 0.5, py_ = y + 0.5;
                    double w0 = ((X[1] - px_) * (Y[2] - py_) - (X[2] - px_) * (Y[1] - py_)) / area;
                    double w1 = ((X[2] - px_) * (Y[0] - py_) - (X[0] - px_) * (Y[2] - py_)) / area;
                    double w2 = 1 - w0 - w1;
                    if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                    double z = w0 * Z[0] + w1 * Z[1] + w2 * Z[2];
                    size_t px = (size_t)y * W + (size_t)x;
                    if (z > depth[px]) {
                        depth[px] = (float)z;
                        memcpy(img + 4 * px, rgb8, 3);
                        img[4 * px + 3] = 255;
                    }
                }
        }
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

banyan_status lod_billboard(const banyan_mesh *m, const banyan_lod_params *p, prog *pg, banyan_mesh **out,
                            banyan_error *err) {
    uint32_t planes = (uint32_t)p->billboard_planes, size = (uint32_t)p->billboard_size;
    uint32_t n_groups = 0;
    for (uint32_t q = 0; q < m->part_count; q++)
        if (m->parts[q].group + 1 > n_groups) n_groups = m->parts[q].group + 1;
    /* Which groups have vertices, and their bounds. */
    double (*lo)[3] = malloc(sizeof(double[3]) * n_groups), (*hi)[3] = malloc(sizeof(double[3]) * n_groups);
    uint32_t *slot = malloc(sizeof(uint32_t) * n_groups);
    float (*rgb)[3] = malloc(sizeof(float[3]) * m->material_count);
    banyan_mesh *o = calloc(1, sizeof *o);
    float *depth = NULL;
    banyan_status st = BANYAN_E_NOMEM;
    if (!lo || !hi || !slot || !rgb || !o) goto fail;
    for (uint32_t g = 0; g < n_groups; g++) {
        slot[g] = UINT32_MAX;
        for (int j = 0; j < 3; j++) lo[g][j] = INFINITY, hi[g][j] = -INFINITY;
    }
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k++) {
            const float *P = m->positions + 3 * (size_t)m->indices[k];
            for (int j = 0; j < 3; j++) {
                lo[pt->group][j] = fmin(lo[pt->group][j], P[j]);
                hi[pt->group][j] = fmax(hi[pt->group][j], P[j]);
            }
        }
    }
    uint32_t n_cards = 0;
    for (uint32_t g = 0; g < n_groups; g++)
        if (lo[g][0] <= hi[g][0]) slot[g] = n_cards++;
    if ((st = material_colours(m, rgb))) goto fail;
    st = BANYAN_E_NOMEM;
    int wind = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X) || !banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH);
    uint32_t n_attr = wind ? 8 : 1;
    static const char *const names[8] = {BANYAN_ATTR_BIRTH,          BANYAN_ATTR_WIND_PIVOT_X,
                                         BANYAN_ATTR_WIND_PIVOT_Y,   BANYAN_ATTR_WIND_PIVOT_Z,
                                         BANYAN_ATTR_WIND_LEVEL,     BANYAN_ATTR_WIND_STIFFNESS,
                                         BANYAN_ATTR_WIND_PHASE,     BANYAN_ATTR_WIND_FLUTTER};
    size_t nv = (size_t)n_cards * planes * 8, ni = (size_t)n_cards * planes * 12;
    o->vertex_count = (uint32_t)nv;
    o->index_count = (uint32_t)ni;
    o->positions = malloc(3 * sizeof(float) * nv);
    o->normals = malloc(3 * sizeof(float) * nv);
    o->uvs = malloc(2 * sizeof(float) * nv);
    o->indices = malloc(sizeof(uint32_t) * ni);
    o->attributes = calloc(n_attr, sizeof(banyan_attribute));
    o->materials = calloc(n_cards, sizeof(banyan_material));
    o->parts = calloc(n_cards, sizeof(banyan_part));
    o->images = calloc(n_cards, sizeof(banyan_image));
    if (!o->positions || !o->normals || !o->uvs || !o->indices || !o->attributes || !o->materials || !o->parts ||
        !o->images)
        goto fail;
    o->attribute_count = n_attr;
    for (uint32_t a = 0; a < n_attr; a++) {
        strncpy(o->attributes[a].name, names[a], BANYAN_NAME_MAX - 1);
        if (!(o->attributes[a].data = malloc(sizeof(float) * nv))) goto fail;
    }
    o->material_count = o->part_count = o->image_count = n_cards;
    if ((st = lod_copy_common(m, o, 0))) goto fail;
    st = BANYAN_E_NOMEM;

    for (uint32_t g = 0; g < n_groups; g++) {
        uint32_t cd = slot[g];
        if (cd == UINT32_MAX) continue;
        if (prog_at(pg, (double)g / n_groups)) {
            st = BANYAN_E_LIMIT;
            goto fail;
        }
        double c[2] = {0.5 * (lo[g][0] + hi[g][0]), 0.5 * (lo[g][1] + hi[g][1])};
        double zmin = lo[g][2], zmax = hi[g][2];
        if (zmax - zmin < 1e-6) zmax = zmin + 1e-6;
        bb_view vw[BB_MAX_PLANES];
        double total_w = 0;
        for (uint32_t k = 0; k < planes; k++) {
            double a = BB_PI * k / planes;
            vw[k].d[0] = dm_cos(a), vw[k].d[1] = dm_sin(a);
            vw[k].n[0] = -dm_sin(a), vw[k].n[1] = dm_cos(a);
            vw[k].smin = INFINITY, vw[k].smax = -INFINITY;
        }
        for (uint32_t q = 0; q < m->part_count; q++) {
            const banyan_part *pt = &m->parts[q];
            if (pt->group != g) continue;
            for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k++) {
                const float *P = m->positions + 3 * (size_t)m->indices[k];
                for (uint32_t v = 0; v < planes; v++) {
                    double s = (P[0] - c[0]) * vw[v].d[0] + (P[1] - c[1]) * vw[v].d[1];
                    vw[v].smin = fmin(vw[v].smin, s);
                    vw[v].smax = fmax(vw[v].smax, s);
                }
            }
        }
        for (uint32_t k = 0; k < planes; k++) {
            if (vw[k].smax - vw[k].smin < 1e-6) vw[k].smin -= 5e-7, vw[k].smax += 5e-7;
            total_w += vw[k].smax - vw[k].smin;
        }
        /* Pixels: the longer side of the strip of pictures is `size`. */
        double ppm = size / fmax(total_w, zmax - zmin);
        uint32_t H, W;
        for (;;) {
            H = (uint32_t)lrint((zmax - zmin) * ppm), W = 0;
            H = H < 1 ? 1 : H > size ? size : H;
            /* Tile edges rounded from the running sum: the widths add up to
             * the strip's rounded width exactly, unless a tile thinner than
             * a pixel takes one of its own. */
            double run = 0;
            for (uint32_t k = 0; k < planes; k++) {
                run += (vw[k].smax - vw[k].smin) * ppm;
                uint32_t edge = (uint32_t)lrint(run);
                edge = edge > size ? size : edge;
                vw[k].x0 = W;
                vw[k].w = edge > W ? edge - W : 1;
                W += vw[k].w;
            }
            if (W <= size) break;
            /* Those pixels pushed the strip past `size`: leave room for one
             * a tile (planes <= 8 < 32 <= size), which always fits. */
            ppm *= (double)(size - planes) / (double)size;
        }
        banyan_image *im = &o->images[cd];
        im->width = W;
        im->height = H;
        im->channels = 4;
        im->pixels = calloc((size_t)W * H, 4);
        free(depth);
        depth = malloc(sizeof(float) * (size_t)W * H);
        if (!im->pixels || !depth) goto fail;
        for (size_t i = 0; i < (size_t)W * H; i++) depth[i] = -INFINITY;
        for (uint32_t k = 0; k < planes; k++) {
            if (prog_at(pg, (double)g / n_groups)) {
                st = BANYAN_E_LIMIT;
                goto fail;
            }
            draw_view(m, g, (const float(*)[3])rgb, c, zmin, zmax, &vw[k], im->pixels, depth, W, H);
        }
        if (dilate(im->pixels, W, H)) goto fail;

        banyan_material *mt = &o->materials[cd];
        snprintf(mt->name, sizeof mt->name, "billboard_%u", g);
        mt->base_color[0] = mt->base_color[1] = mt->base_color[2] = mt->base_color[3] = 1.0f;
        mt->roughness = 0.9f;
        mt->double_sided = 1;
        mt->texture = BANYAN_TEX_NONE;
        mt->alpha_cutoff = 0.5f;
        mt->translucency = 0.3f;
        mt->image = (int32_t)cd;
        banyan_part *op = &o->parts[cd];
        op->vertex_offset = cd * planes * 8;
        op->vertex_count = planes * 8;
        op->index_offset = cd * planes * 12;
        op->index_count = planes * 12;
        op->material = cd;
        op->group = g;
        float phase = (float)wind_phase_of(p->seed, g);
        for (uint32_t k = 0; k < planes; k++) {
            /* Two half quads, split at the axis: s in [smin, 0] and [0, smax]. */
            double s_mid = fmin(fmax(0.0, vw[k].smin), vw[k].smax);
            double sv[3] = {vw[k].smin, s_mid, vw[k].smax};
            for (uint32_t h = 0; h < 2; h++) {
                uint32_t base = op->vertex_offset + (k * 2 + h) * 4;
                double corner[4][2] = {{sv[h], zmin}, {sv[h + 1], zmin}, {sv[h + 1], zmax}, {sv[h], zmax}};
                for (int e = 0; e < 4; e++) {
                    uint32_t v = base + (uint32_t)e;
                    double s = corner[e][0], z = corner[e][1];
                    float *P = o->positions + 3 * (size_t)v, *N = o->normals + 3 * (size_t)v, *T = o->uvs + 2 * (size_t)v;
                    P[0] = (float)(c[0] + s * vw[k].d[0]);
                    P[1] = (float)(c[1] + s * vw[k].d[1]);
                    P[2] = (float)z;
                    N[0] = (float)vw[k].n[0], N[1] = (float)vw[k].n[1], N[2] = 0;
                    T[0] = (float)((vw[k].x0 + (vw[k].smax - s) / (vw[k].smax - vw[k].smin) * vw[k].w) / W);
                    T[1] = (float)((z - zmin) / (zmax - zmin));
                    float t = (float)((z - zmin) / (zmax - zmin));
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
                /* counter-clockwise seen from +n */
                uint32_t *I = o->indices + op->index_offset + (k * 2 + h) * 6;
                I[0] = base, I[1] = base + 2, I[2] = base + 1;
                I[3] = base, I[4] = base + 3, I[5] = base + 2;
            }
        }
    }
    free(lo); free(hi); free(slot); free(rgb); free(depth);
    *out = o;
    banyan_error_clear(err);
    return BANYAN_OK;
fail:
    free(lo); free(hi); free(slot); free(rgb); free(depth);
    banyan_mesh_free(o);
    if (st == BANYAN_E_LIMIT) return prog_fail(pg, err, "the billboard level of detail");
    return banyan_fail(err, st ? st : BANYAN_E_NOMEM, "out of memory drawing the billboards of %u vertices",
                       m->vertex_count);
}
