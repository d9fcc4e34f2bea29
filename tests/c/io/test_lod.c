/* test_lod.c - levels of detail (banyan_mesh_lod, banyan/lod.h):
 * on every generator's mesh, ratios 0.5 and 0.15 keep that share of the
 * triangles (within 10 %), the bounding box (within 5 % of its size on
 * every axis), the leaf area (within 10 %), every part, material and
 * attribute, and make no degenerate triangle (also 0.15 made from the 0.5
 * level, as the CLI makes it); the same seed gives the same
 * bytes and another seed other leaves; the billboard level is 2 * planes
 * vertical half quads and a top card per tree with a picture neither empty
 * nor full (test_lod_look.c compares the pictures with the plant); bad
 * params and
 * bad meshes are refused with *out NULL. Prints the figures. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "lod_plants.h"

typedef struct bounds {
    double lo[3], hi[3];
} bounds;

static bounds mesh_bounds(const banyan_mesh *m) {
    bounds b;
    for (int j = 0; j < 3; j++) b.lo[j] = INFINITY, b.hi[j] = -INFINITY;
    for (uint32_t k = 0; k < m->index_count; k++) {
        const float *P = m->positions + 3 * (size_t)m->indices[k];
        for (int j = 0; j < 3; j++) b.lo[j] = fmin(b.lo[j], P[j]), b.hi[j] = fmax(b.hi[j], P[j]);
    }
    return b;
}

/* Largest shift of a bound face, as a share of that axis's extent. */
static double bounds_change(const bounds *a, const bounds *b) {
    double worst = 0;
    for (int j = 0; j < 3; j++) {
        double ext = a->hi[j] - a->lo[j];
        if (ext <= 0) continue;
        worst = fmax(worst, fabs(b->lo[j] - a->lo[j]) / ext);
        worst = fmax(worst, fabs(b->hi[j] - a->hi[j]) / ext);
    }
    return worst;
}

static double tri_area(const banyan_mesh *m, uint32_t k) {
    const float *A = m->positions + 3 * (size_t)m->indices[k], *B = m->positions + 3 * (size_t)m->indices[k + 1],
                *C = m->positions + 3 * (size_t)m->indices[k + 2];
    double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static double leaf_area(const banyan_mesh *m) {
    double a = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (m->materials[pt->material].alpha_cutoff <= 0) continue;
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k += 3) a += tri_area(m, k);
    }
    return a;
}

/* 1 when the mesh is well formed: parts in order covering everything,
 * indices inside their part, no triangle with a repeated vertex or no
 * area. why gets the first fault. */
static int well_formed(const banyan_mesh *m, char *why, size_t n) {
    uint32_t v_at = 0, i_at = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->vertex_offset != v_at || pt->index_offset != i_at || pt->index_count % 3) {
            snprintf(why, n, "part %u does not follow the one before", q);
            return 0;
        }
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k += 3) {
            uint32_t a = m->indices[k], b = m->indices[k + 1], c = m->indices[k + 2];
            for (int j = 0; j < 3; j++)
                if (m->indices[k + j] - pt->vertex_offset >= pt->vertex_count) {
                    snprintf(why, n, "index %u = %u outside part %u", k + j, m->indices[k + j], q);
                    return 0;
                }
            if (a == b || b == c || a == c || !(tri_area(m, k) > 0)) {
                snprintf(why, n, "triangle %u (%u %u %u) is degenerate", k / 3, a, b, c);
                return 0;
            }
        }
        v_at += pt->vertex_count;
        i_at += pt->index_count;
    }
    if (v_at != m->vertex_count || i_at != m->index_count) {
        snprintf(why, n, "parts cover %u of %u vertices, %u of %u indices", v_at, m->vertex_count, i_at,
                 m->index_count);
        return 0;
    }
    return 1;
}

/* The CLI's levels (csrc/cli/lod_write.c) come each from the one before:
 * 0.15 made from the 0.5 level (its ratio 0.15 x the plant's triangles
 * over the 0.5 level's) keeps 0.15 of the plant's
 * triangles within 10 %, the plant's bounds within 5 % and its leaf area
 * within 10 %, well formed; printed beside the 0.15 level made from the
 * plant itself. */
static void check_chain(const char *name, const banyan_mesh *m) {
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    banyan_error err = {0, ""};
    banyan_mesh *half = NULL, *chain = NULL, *direct = NULL;
    p.ratio = 0.5;
    CHECK(banyan_mesh_lod(m, &p, &half, &err) == BANYAN_OK && half, "%s 0.5: %s", name, err.message);
    if (half) p.ratio = 0.15 * ((double)m->index_count / half->index_count); /* as the CLI asks */
    if (half)
        CHECK(banyan_mesh_lod(half, &p, &chain, &err) == BANYAN_OK && chain, "%s 0.5 -> 0.15: %s", name,
              err.message);
    p.ratio = 0.15;
    CHECK(banyan_mesh_lod(m, &p, &direct, &err) == BANYAN_OK && direct, "%s 0.15: %s", name, err.message);
    if (chain && direct) {
        double tris = m->index_count / 3.0, got = chain->index_count / 3.0, want = 0.15 * tris;
        bounds b0 = mesh_bounds(m), b1 = mesh_bounds(chain), b2 = mesh_bounds(direct);
        double la0 = leaf_area(m), la1 = leaf_area(chain), la2 = leaf_area(direct);
        double bc = bounds_change(&b0, &b1);
        printf("%-13s 0.5 -> 0.15: %9.0f triangles (%.3f; from the plant %.0f, %.3f), bounds moved %.2f %% (%.2f %%), "
               "leaf area %.2f %% (%.2f %%)\n",
               name, got, got / tris, direct->index_count / 3.0, direct->index_count / 3.0 / tris, 100 * bc,
               100 * bounds_change(&b0, &b2), la0 > 0 ? 100 * la1 / la0 : 100.0, la0 > 0 ? 100 * la2 / la0 : 100.0);
        CHECK(fabs(got - want) <= 0.10 * want, "%s 0.5 -> 0.15: %.0f triangles, want %.0f within 10 %%", name, got,
              want);
        CHECK(bc <= 0.05, "%s 0.5 -> 0.15: the bounding box moved %.1f %% of its size", name, 100 * bc);
        if (la0 > 0)
            CHECK(fabs(la1 - la0) <= 0.10 * la0, "%s 0.5 -> 0.15: leaf area %g, was %g", name, la1, la0);
        char why[200];
        CHECK(well_formed(chain, why, sizeof why), "%s 0.5 -> 0.15: %s", name, why);
        CHECK(chain->part_count == m->part_count && chain->attribute_count == m->attribute_count,
              "%s 0.5 -> 0.15: parts %u/%u, attributes %u/%u", name, chain->part_count, m->part_count,
              chain->attribute_count, m->attribute_count);
    }
    banyan_mesh_free(half);
    banyan_mesh_free(chain);
    banyan_mesh_free(direct);
}

/* banyan_mesh_lods: its levels are the chain made level by level (the
 * 0.5 level, then the 0.15 level from it with the CLI's corrected ratio)
 * and the billboard of the plant itself, the same bytes on 1 and 2
 * threads; bad requests are refused with every out NULL. */
static void check_lods_call(const char *name, const banyan_mesh *m) {
    banyan_error err = {0, ""};
    banyan_lod_params p, bb;
    banyan_lod_params_init(&p);
    banyan_lod_params_init(&bb);
    bb.billboard = 1;
    banyan_mesh *half = NULL, *chain = NULL, *card = NULL;
    p.ratio = 0.5;
    CHECK(banyan_mesh_lod(m, &p, &half, &err) == BANYAN_OK, "%s 0.5: %s", name, err.message);
    if (half) {
        p.ratio = 0.15 * ((double)m->index_count / half->index_count);
        CHECK(banyan_mesh_lod(half, &p, &chain, &err) == BANYAN_OK, "%s 0.5 -> 0.15: %s", name, err.message);
    }
    CHECK(banyan_mesh_lod(m, &bb, &card, &err) == BANYAN_OK, "%s billboard: %s", name, err.message);
    const double ratios[2] = {0.5, 0.15};
    for (int32_t threads = 1; threads <= 2 && half && chain && card; threads++) {
        banyan_mesh *out[3] = {NULL, NULL, NULL};
        CHECK(banyan_mesh_lods(m, ratios, 2, &bb, threads, NULL, out, &err) == BANYAN_OK, "%s lods, %d threads: %s",
              name, threads, err.message);
        if (out[0] && out[1] && out[2])
            CHECK(banyan_mesh_hash(out[0]) == banyan_mesh_hash(half) && banyan_mesh_hash(out[1]) == banyan_mesh_hash(chain) &&
                      banyan_mesh_hash(out[2]) == banyan_mesh_hash(card),
                  "%s lods, %d threads: levels differ from the chain made level by level", name, threads);
        for (int k = 0; k < 3; k++) banyan_mesh_free(out[k]);
    }
    /* Refusals: out NULL, the parameter named. */
    struct {
        double r[2];
        uint32_t n;
        int bb;
        const char *names;
    } bad[] = {{{0.15, 0.5}, 2, 0, "ratios[1]"}, {{0.5, 0.0 / 0.0}, 2, 0, "ratios[1]"}, {{1.0, 0.5}, 2, 0, "ratios[0]"},
               {{0.5, 0.15}, 0, 0, "billboard"}, {{0.5, 0.15}, 9, 1, "ratio_count"}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        banyan_mesh *out[3] = {(banyan_mesh *)1, (banyan_mesh *)1, (banyan_mesh *)1};
        banyan_status st = banyan_mesh_lods(m, bad[k].r, bad[k].n, bad[k].bb ? &bb : NULL, 2, NULL, out, &err);
        CHECK(st != BANYAN_OK && strstr(err.message, bad[k].names), "%s lods refusal %zu: status %d, '%s'", name, k,
              (int)st, err.message);
        if (bad[k].n >= 1 && bad[k].n <= 2) CHECK(out[0] == NULL, "%s lods refusal %zu: out[0] not NULL", name, k);
    }
    banyan_lod_params off = bb;
    off.billboard = 0;
    banyan_mesh *out1[2] = {NULL, NULL};
    CHECK(banyan_mesh_lods(m, ratios, 1, &off, 2, NULL, out1, &err) == BANYAN_E_INVALID_ARG && !out1[0] && !out1[1],
          "%s lods: a billboard without billboard = 1 accepted", name);
    CHECK(banyan_mesh_lods(NULL, ratios, 2, NULL, 2, NULL, out1, &err) == BANYAN_E_INVALID_ARG, "%s lods: NULL mesh", name);
    CHECK(banyan_mesh_lods(m, ratios, 2, NULL, 2, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "%s lods: NULL out", name);
    banyan_mesh_free(half);
    banyan_mesh_free(chain);
    banyan_mesh_free(card);
}

/* One reduced level of m: its figures printed, its invariants checked. */
static void check_level(const char *name, const banyan_mesh *m, double ratio) {
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    p.ratio = ratio;
    banyan_error err = {0, ""};
    banyan_mesh *o = NULL, *o2 = NULL, *o3 = NULL;
    CHECK(banyan_mesh_lod(m, &p, &o, &err) == BANYAN_OK && o, "%s %.2f: %s", name, ratio, err.message);
    if (!o) return;
    double tris = m->index_count / 3.0, got = o->index_count / 3.0, want = ratio * tris;
    bounds b0 = mesh_bounds(m), b1 = mesh_bounds(o);
    double la0 = leaf_area(m), la1 = leaf_area(o), bc = bounds_change(&b0, &b1);
    printf("%-13s ratio %.2f: %9.0f -> %9.0f triangles (%.3f of the original, target %.2f), bounds moved %.2f %%, "
           "leaf area %.2f %%\n",
           name, ratio, tris, got, got / tris, ratio, 100 * bc, la0 > 0 ? 100 * la1 / la0 : 100.0);
    CHECK(fabs(got - want) <= 0.10 * want, "%s %.2f: %.0f triangles, want %.0f within 10 %%", name, ratio, got, want);
    CHECK(bc <= 0.05, "%s %.2f: the bounding box moved %.1f %% of its size", name, ratio, 100 * bc);
    if (la0 > 0) CHECK(fabs(la1 - la0) <= 0.10 * la0, "%s %.2f: leaf area %g, was %g", name, ratio, la1, la0);
    char why[200];
    CHECK(well_formed(o, why, sizeof why), "%s %.2f: %s", name, ratio, why);
    CHECK(o->part_count == m->part_count && o->material_count == m->material_count &&
              o->attribute_count == m->attribute_count,
          "%s %.2f: parts %u/%u, materials %u/%u, attributes %u/%u", name, ratio, o->part_count, m->part_count,
          o->material_count, m->material_count, o->attribute_count, m->attribute_count);
    for (uint32_t q = 0; q < o->part_count && q < m->part_count; q++)
        CHECK(o->parts[q].material == m->parts[q].material && o->parts[q].group == m->parts[q].group,
              "%s: part %u changed its material or group", name, q);
    for (uint32_t a = 0; a < o->attribute_count && a < m->attribute_count; a++)
        CHECK(!strcmp(o->attributes[a].name, m->attributes[a].name), "%s: attribute %u renamed", name, a);
    CHECK(o->instance_count == m->instance_count && o->image_count == m->image_count &&
              !memcmp(o->origin, m->origin, sizeof o->origin),
          "%s: instances, images or origin not carried over", name);
    CHECK(banyan_mesh_lod(m, &p, &o2, &err) == BANYAN_OK && o2 && banyan_mesh_hash(o) == banyan_mesh_hash(o2),
          "%s %.2f: the same seed gave other bytes", name, ratio);
    if (la0 > 0) {
        p.seed = 2;
        CHECK(banyan_mesh_lod(m, &p, &o3, &err) == BANYAN_OK && o3 && banyan_mesh_hash(o) != banyan_mesh_hash(o3),
              "%s %.2f: seeds 1 and 2 kept the same leaves", name, ratio);
    }
    banyan_mesh_free(o);
    banyan_mesh_free(o2);
    banyan_mesh_free(o3);
}

static void check_billboard(const char *name, const banyan_mesh *m, int32_t planes) {
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    p.billboard = 1;
    p.billboard_planes = planes;
    banyan_error err = {0, ""};
    banyan_mesh *o = NULL;
    CHECK(banyan_mesh_lod(m, &p, &o, &err) == BANYAN_OK && o, "%s billboard: %s", name, err.message);
    if (!o) return;
    uint32_t groups = 0;
    for (uint32_t q = 0; q < m->part_count; q++) groups = m->parts[q].group + 1 > groups ? m->parts[q].group + 1 : groups;
    CHECK(o->part_count == 2 * groups && o->image_count == groups, "%s billboard: %u parts, %u images for %u groups",
          name, o->part_count, o->image_count, groups);
    char why[200];
    CHECK(well_formed(o, why, sizeof why), "%s billboard: %s", name, why);
    for (uint32_t q = 0; q < o->part_count; q++) {
        const banyan_part *pt = &o->parts[q];
        /* Per group: the vertical half quads (double sided), then the top
         * card (single sided, facing up), one picture. */
        int top = q % 2;
        CHECK(pt->index_count == (top ? 6u : 12u * planes), "%s billboard: part %u has %u indices, want %d quads", name,
              q, pt->index_count, top ? 1 : 2 * planes);
        const banyan_material *mt = &o->materials[pt->material];
        CHECK(mt->image > 0 && (uint32_t)mt->image <= o->image_count && mt->alpha_cutoff == 0.5f &&
                  mt->double_sided == !top && (uint32_t)mt->image == q / 2 + 1,
              "%s billboard: material %u", name, pt->material);
        for (uint32_t v = pt->vertex_offset; top && v < pt->vertex_offset + pt->vertex_count; v++)
            CHECK(o->normals[3 * (size_t)v + 2] == 1.0f, "%s billboard: the top card's vertex %u does not face up", name,
                  v);
        if (mt->image <= 0 || (uint32_t)mt->image > o->image_count) continue;
        const banyan_image *im = &o->images[mt->image - 1];
        uint32_t longer = im->width > im->height ? im->width : im->height;
        size_t cover = 0, n = (size_t)im->width * im->height;
        for (size_t i = 0; i < n; i++) cover += im->pixels[4 * i + 3] >= 128; /* the engine's cutoff 0.5 */
        double share = n ? (double)cover / n : 0;
        if (q == 0)
            printf("%-13s billboard %d planes: %ux%u picture, %.1f %% covered\n", name, planes, im->width, im->height,
                   100 * share);
        /* Tiles are whole pixels: the longer side may fall short by a few. */
        CHECK(im->channels == 4 && longer <= (uint32_t)p.billboard_size && longer + 2 * (planes + 1) >= (uint32_t)p.billboard_size,
              "%s billboard: %ux%u image", name, im->width, im->height);
        CHECK(share >= 0.05 && share <= 0.95, "%s billboard: %.1f %% of the picture covered", name, 100 * share);
    }
    {
        bounds b0 = mesh_bounds(m), b1 = mesh_bounds(o);
        double bc = bounds_change(&b0, &b1);
        CHECK(bc <= 0.05, "%s billboard: bounds moved %.1f %%", name, 100 * bc);
    }
    const float *st = banyan_mesh_attribute(o, BANYAN_ATTR_WIND_STIFFNESS), *bi = banyan_mesh_attribute(o, BANYAN_ATTR_BIRTH);
    CHECK(bi != NULL, "%s billboard: no birth", name);
    /* stiffness 1 at a card's foot, 0.5 at its top, linear between (the
     * top card) */
    for (uint32_t q = 0; st && q < o->part_count; q++) {
        const banyan_part *pt = &o->parts[q], *vert = &o->parts[q & ~1u]; /* the group's height: its vertical cards */
        float zlo = INFINITY, zhi = -INFINITY;
        for (uint32_t v = vert->vertex_offset; v < vert->vertex_offset + vert->vertex_count; v++) {
            zlo = fminf(zlo, o->positions[3 * (size_t)v + 2]);
            zhi = fmaxf(zhi, o->positions[3 * (size_t)v + 2]);
        }
        for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count; v++) {
            float want = 1.0f - 0.5f * (o->positions[3 * (size_t)v + 2] - zlo) / (zhi - zlo);
            if (fabsf(st[v] - want) > 1e-4f) {
                CHECK(0, "%s billboard: vertex %u stiffness %g, want %g", name, v, (double)st[v], (double)want);
                break;
            }
        }
    }
    banyan_mesh_free(o);
}

static void check_refusals(const banyan_mesh *m) {
    banyan_lod_params p;
    banyan_error err;
    banyan_mesh *o = (banyan_mesh *)&err; /* not NULL: a refusal must clear it */
    struct {
        const char *field;
        double ratio;
        int32_t bb, planes, size, reserved;
    } bad[] = {{"ratio", 0.0, 0, 2, 256, 0},        {"ratio", NAN, 0, 2, 256, 0},
               {"ratio", 1.5, 0, 2, 256, 0},        {"ratio", 0.0005, 0, 2, 256, 0},
               {"billboard", 0.5, 2, 2, 256, 0},    {"billboard_planes", 0.5, 1, 1, 256, 0},
               {"billboard_planes", 0.5, 1, 9, 256, 0}, {"billboard_size", 0.5, 1, 2, 16, 0},
               {"billboard_size", 0.5, 1, 2, 8192, 0},  {"billboard_size", 0.5, 1, 2, 384, 0},
               {"reserved", 0.5, 0, 2, 256, 3}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        banyan_lod_params_init(&p);
        p.ratio = bad[i].ratio;
        p.billboard = bad[i].bb;
        p.billboard_planes = bad[i].planes;
        p.billboard_size = bad[i].size;
        p.reserved = bad[i].reserved;
        o = (banyan_mesh *)&err;
        banyan_status s = banyan_mesh_lod(m, &p, &o, &err);
        CHECK(s == BANYAN_E_RANGE && o == NULL && strstr(err.message, bad[i].field),
              "bad %s: status %d, message '%s'", bad[i].field, s, err.message);
    }
    banyan_lod_params_init(&p);
    CHECK(banyan_mesh_lod(m, &p, NULL, &err) == BANYAN_E_INVALID_ARG, "out NULL accepted");
    o = (banyan_mesh *)&err;
    CHECK(banyan_mesh_lod(NULL, &p, &o, &err) == BANYAN_E_INVALID_ARG && !o, "NULL mesh accepted");
    /* NULL params: the defaults. */
    CHECK(banyan_mesh_lod(m, NULL, &o, &err) == BANYAN_OK && o, "NULL params: %s", err.message);
    banyan_mesh_free(o);

    /* Broken meshes: a shallow copy with one thing wrong. */
    banyan_mesh c;
    uint32_t *idx = malloc(sizeof(uint32_t) * m->index_count);
    float *pos = malloc(3 * sizeof(float) * m->vertex_count);
    banyan_part *parts = malloc(sizeof(banyan_part) * m->part_count);
    if (!idx || !pos || !parts) {
        CHECK(0, "out of memory");
        free(idx), free(pos), free(parts);
        return;
    }
    memcpy(idx, m->indices, sizeof(uint32_t) * m->index_count);
    memcpy(pos, m->positions, 3 * sizeof(float) * m->vertex_count);
    memcpy(parts, m->parts, sizeof(banyan_part) * m->part_count);
    for (int t = 0; t < 8; t++) {
        c = *m;
        c.indices = idx;
        c.positions = pos;
        c.parts = parts;
        banyan_status want = BANYAN_E_INVALID_ARG;
        const char *what = "";
        if (t == 0) c.vertex_count = 0, what = "empty";
        if (t == 1) c.index_count = 0, what = "empty";
        if (t == 2) idx[5] = m->vertex_count, what = "indices[5]";
        if (t == 3) pos[7] = NAN, want = BANYAN_E_RANGE, what = "positions[7]";
        if (t == 4) c.positions = NULL, what = "positions";
        if (t == 5) parts[0].material = m->material_count, what = "material";
        if (t == 6) c.part_count = 0, what = "part_count";
        if (t == 7) c.index_count -= 1, what = "multiple of 3";
        o = (banyan_mesh *)&err;
        banyan_status s = banyan_mesh_lod(&c, &p, &o, &err);
        CHECK(s == want && !o && strstr(err.message, what), "broken mesh %d (%s): status %d, '%s'", t, what, s,
              err.message);
        memcpy(idx, m->indices, sizeof(uint32_t) * m->index_count);
        memcpy(pos, m->positions, 3 * sizeof(float) * m->vertex_count);
        memcpy(parts, m->parts, sizeof(banyan_part) * m->part_count);
    }
    free(idx);
    free(pos);
    free(parts);
}

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    const char *plants[] = {"keyaki_mature", "keyaki_young", "roots_tubes", "roots_fused", "ivy_wall", "segments",
                            "avenue_small"};
    for (size_t i = 0; i < sizeof plants / sizeof plants[0]; i++) {
        banyan_error err = {0, ""};
        banyan_mesh *m = lod_plant(plants[i], 0, &err);
        CHECK(m != NULL, "%s: %s", plants[i], err.message);
        if (!m) continue;
        check_level(plants[i], m, 0.5);
        check_level(plants[i], m, 0.15);
        check_chain(plants[i], m);
        if (!strncmp(plants[i], "keyaki", 6) || !strncmp(plants[i], "avenue", 6)) {
            check_billboard(plants[i], m, 2);
            check_billboard(plants[i], m, 4);
        }
        if (i == 0) check_refusals(m);
        if (i == 1) check_lods_call(plants[i], m);
        if (i == 1) {
            /* The tree as the one variant of three instances: every level
             * keeps the instances as they are. */
            banyan_instance in[3] = {{0, {0, 0, 0}, 0, 1}, {0, {8, 0, 0}, 1.5f, 0.9f}, {0, {16, 0, 0}, 3, 1.1f}};
            m->instances = in;
            m->instance_count = 3;
            banyan_lod_params p;
            banyan_lod_params_init(&p);
            for (int bb = 0; bb < 2; bb++) {
                banyan_mesh *o = NULL;
                p.billboard = bb;
                CHECK(banyan_mesh_lod(m, &p, &o, &err) == BANYAN_OK && o && o->instance_count == 3 &&
                          !memcmp(o->instances, in, sizeof in),
                      "instances not kept (billboard %d): %s", bb, err.message);
                banyan_mesh_free(o);
            }
            m->instances = NULL;
            m->instance_count = 0;
        }
        banyan_mesh_free(m);
    }
    /* An instanced avenue: reduced variant by variant, instances kept. */
    banyan_error err = {0, ""};
    banyan_mesh *inst = lod_plant("avenue_small", 2, &err);
    if (inst && inst->instance_count) {
        check_level("avenue_inst", inst, 0.5);
        check_billboard("avenue_inst", inst, 2);
    } else {
        printf("instanced avenue: not available in this build (%s)\n", inst ? "no instances" : err.message);
    }
    banyan_mesh_free(inst);
    return check_done("test_lod");
}
