/*
 * test_pivot_painter.c - banyan_pivot_painter_write and the glTF writer's
 * pivot_painter UV set (banyan/pivot_painter.h), decoded back.
 *
 *   test_pivot_painter OUTDIR
 *
 * For keyaki_mature, a 2 x 2 avenue and the same avenue as instances of
 * two variants: the two textures are read back (the EXR through tinyexr,
 * the PNG through stb_image) and the .glb's UV set is followed, vertex by
 * vertex, to its texel:
 *   - every UV is a texel's centre, inside the elements written;
 *   - the texel's pivot is the vertex's own _WIND_PIVOT in Unreal's axes
 *     and centimetres within half-float rounding, or else the vertex was
 *     merged: its texel is on the deepest level kept;
 *   - every element in use has vertices of its own with its pivot;
 *   - the parent indices form trees of at most four levels, one root per
 *     tree (part group);
 *   - each X axis is a unit vector (8-bit), and every vertex lies within
 *     its element's extent along it;
 *   - the UVs are exact at half precision (an engine's 16-bit UVs);
 *   - the bytes are the same when written again, and a .glb written
 *     without the option has no extra UV set.
 * Then bad input: NaN and out-of-range options, a mesh without vertices,
 * without wind attributes or with a NaN pivot, a prefix in a missing
 * folder: each refused naming the parameter, with no file left.
 */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "lod_plants.h" /* banyan.h, test_files.h */
#include "pp2/exr_half.h"

/* stb_image's PNG decoder, compiled here (as the texture tests do) */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC diagnostic ignored "-Wunused-function"
#endif

static char g_dir[1024];

static int file_exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* ------------------------------------------------------------ .glb */

typedef struct glb {
    char *file;
    size_t size;
    cJSON *json;
    const unsigned char *bin;
    size_t bin_len;
} glb;

static void glb_free(glb *g) {
    cJSON_Delete(g->json);
    free(g->file);
    memset(g, 0, sizeof *g);
}

static int glb_load(const char *path, glb *g) {
    memset(g, 0, sizeof *g);
    g->file = test_read_file(path, &g->size);
    if (!g->file || g->size < 28 || memcmp(g->file, "glTF", 4)) return 0;
    uint32_t jl, bl;
    memcpy(&jl, g->file + 12, 4);
    if (20 + (size_t)jl + 8 > g->size) return 0;
    g->json = cJSON_ParseWithLength(g->file + 20, jl);
    memcpy(&bl, g->file + 20 + jl, 4);
    g->bin = (const unsigned char *)g->file + 28 + jl;
    g->bin_len = bl;
    return g->json != NULL && 28 + (size_t)jl + bl <= g->size;
}

static cJSON *key(const cJSON *o, const char *k) { return cJSON_GetObjectItemCaseSensitive(o, k); }
static int num(const cJSON *o, const char *k, int dflt) {
    const cJSON *v = key(o, k);
    return cJSON_IsNumber(v) ? v->valueint : dflt;
}

/* Float accessor `a` with `comps` components: its floats and count, or NULL. */
static const float *floats(const glb *g, int a, int comps, int *count) {
    const cJSON *acc = cJSON_GetArrayItem(key(g->json, "accessors"), a);
    if (!acc || num(acc, "componentType", 0) != 5126) return NULL;
    const cJSON *bv = cJSON_GetArrayItem(key(g->json, "bufferViews"), num(acc, "bufferView", -1));
    const char *t = cJSON_GetStringValue(key(acc, "type"));
    if (!bv || !t) return NULL;
    int c = !strcmp(t, "SCALAR") ? 1 : !strcmp(t, "VEC2") ? 2 : !strcmp(t, "VEC3") ? 3 : 0;
    size_t off = (size_t)num(bv, "byteOffset", 0) + (size_t)num(acc, "byteOffset", 0);
    size_t n = (size_t)num(acc, "count", 0);
    if (c != comps || num(bv, "byteStride", 0) || off + n * c * 4 > g->bin_len) return NULL;
    *count = (int)n;
    return (const float *)(g->bin + off);
}

/* ------------------------------------------------------------ decoded textures */

typedef struct pp2 {
    uint32_t w, h;
    uint16_t *half; /* R, G, B, A */
    uint8_t *rgba;  /* the X vector texture */
} pp2;

static void pp2_release(pp2 *t) {
    free(t->half);
    stbi_image_free(t->rgba);
    memset(t, 0, sizeof *t);
}

static int pp2_load(const char *prefix, pp2 *t) {
    char path[1200];
    memset(t, 0, sizeof *t);
    snprintf(path, sizeof path, "%s_PivotPos_Index.exr", prefix);
    size_t len = 0;
    char *exr = test_read_file(path, &len), why[200] = "";
    int ok = exr && exr_half_decode((const uint8_t *)exr, len, &t->w, &t->h, &t->half, why, sizeof why) == 0;
    CHECK(ok, "%s: %s", path, why);
    free(exr);
    snprintf(path, sizeof path, "%s_XVector_Extent.png", prefix);
    int w = 0, h = 0, c = 0;
    t->rgba = stbi_load(path, &w, &h, &c, 4);
    CHECK(t->rgba && (uint32_t)w == t->w && (uint32_t)h == t->h && c == 4, "%s: %d x %d x %d, not %u x %u RGBA", path,
          w, h, c, t->w, t->h);
    return ok && t->rgba && (uint32_t)w == t->w && (uint32_t)h == t->h;
}

static uint32_t parent_of(const pp2 *t, uint32_t k) { return (uint32_t)t->half[4 * k + 3] - 1024u; }

/* Within half-float rounding of want: half an ulp at want's size. */
static int half_close(double got, double want) {
    double a = fabs(want);
    double ulp = a < ldexp(1.0, -14) ? ldexp(1.0, -24) : ldexp(1.0, (int)floor(log2(a)) - 10);
    return fabs(got - want) <= 0.5 * ulp * (1 + 1e-9);
}

static int same_file(const char *a, const char *b) {
    size_t la = 0, lb = 0;
    char *x = test_read_file(a, &la), *y = test_read_file(b, &lb);
    int same = x && y && la == lb && memcmp(x, y, la) == 0;
    free(x);
    free(y);
    return same;
}

/* ------------------------------------------------------------ one plant */

static void check_plant(const char *name, banyan_mesh *m, int engine_uvs) {
    char prefix[1100], glb_path[1200], again[1200];
    snprintf(prefix, sizeof prefix, "%s", test_join(g_dir, name));
    banyan_pivot_painter_info info;
    banyan_error err = {0, ""};
    banyan_status s = banyan_pivot_painter_write(prefix, m, NULL, &info, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (s) return;
    CHECK(info.elements > 0 && info.depth >= 1 && info.depth <= 4 && info.width * info.height >= info.elements,
          "%s: %u elements, depth %u, %u x %u", name, info.elements, info.depth, info.width, info.height);

    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.textures = 0;
    o.pivot_painter = 1;
    o.engine_uvs = engine_uvs;
    snprintf(glb_path, sizeof glb_path, "%s.glb", prefix);
    const banyan_mesh *list[1] = {m};
    s = banyan_gltf_write_ex(glb_path, list, NULL, 1, &o, &err);
    CHECK(s == BANYAN_OK, "%s: glTF: %s", name, err.message);

    pp2 t;
    glb g;
    if (s || !pp2_load(prefix, &t)) return;
    CHECK(t.w == info.width && t.h == info.height, "%s: EXR %u x %u, info %u x %u", name, t.w, t.h, info.width,
          info.height);
    const uint32_t E = info.elements;

    /* the hierarchy: every parent in use, trees of at most four levels */
    uint32_t roots = 0, deepest = 0, bad_parent = 0;
    uint32_t *depth = calloc(E, sizeof *depth);
    for (uint32_t k = 0; k < E; ++k) {
        uint32_t d = 0, x = k;
        while (parent_of(&t, x) != x && parent_of(&t, x) < E && d < 8) x = parent_of(&t, x), d++;
        if (parent_of(&t, x) >= E || d >= 8) bad_parent++;
        depth[k] = d;
        if (d + 1 > deepest) deepest = d + 1;
        roots += parent_of(&t, k) == k;
    }
    uint32_t groups = 0;
    for (uint32_t p = 0; p < m->part_count; ++p) {
        int seen = 0;
        for (uint32_t q = 0; q < p; ++q) seen |= m->parts[q].group == m->parts[p].group;
        groups += !seen;
    }
    CHECK(bad_parent == 0, "%s: %u elements whose parents do not lead to a root", name, bad_parent);
    CHECK(deepest == info.depth && deepest <= 4, "%s: %u levels deep, info says %u", name, deepest, info.depth);
    CHECK(roots == groups, "%s: %u roots for %u trees (part groups)", name, roots, groups);
    uint32_t unused_bad = 0;
    for (uint32_t k = E; k < t.w * t.h; ++k) unused_bad += parent_of(&t, k) != k;
    CHECK(unused_bad == 0, "%s: %u unused texels not roots of their own", name, unused_bad);

    /* the X vectors are unit vectors */
    uint32_t not_unit = 0;
    for (uint32_t k = 0; k < E; ++k) {
        double a[3], len = 0;
        for (int c = 0; c < 3; ++c) a[c] = t.rgba[4 * k + c] / 255.0 * 2.0 - 1.0, len += a[c] * a[c];
        not_unit += fabs(sqrt(len) - 1.0) > 0.02;
    }
    CHECK(not_unit == 0, "%s: %u X vectors are not unit vectors", name, not_unit);

    /* every vertex of the .glb to its texel */
    uint8_t *owned = calloc(E, 1);
    uint64_t vertices = 0, own = 0, merged = 0, off_centre = 0, outside = 0, unmerged_mismatch = 0, past_extent = 0;
    uint64_t not_half = 0;
    char set[16];
    snprintf(set, sizeof set, "TEXCOORD_%d", engine_uvs ? 5 : 1);
    CHECK(glb_load(glb_path, &g), "%s: cannot read the .glb", glb_path);
    const cJSON *mesh_json;
    int prims = 0;
    cJSON_ArrayForEach(mesh_json, key(g.json, "meshes")) {
        const cJSON *prim;
        cJSON_ArrayForEach(prim, key(mesh_json, "primitives")) {
            const cJSON *at = key(prim, "attributes");
            int n[5] = {0, 0, 0, 0, 0};
            const float *uv = floats(&g, num(at, set, -1), 2, &n[0]);
            const float *pos = floats(&g, num(at, "POSITION", -1), 3, &n[1]);
            const float *pv[3] = {floats(&g, num(at, "_WIND_PIVOT_X", -1), 1, &n[2]),
                                  floats(&g, num(at, "_WIND_PIVOT_Y", -1), 1, &n[3]),
                                  floats(&g, num(at, "_WIND_PIVOT_Z", -1), 1, &n[4])};
            prims++;
            CHECK(uv && pos && pv[0] && pv[1] && pv[2] && n[0] == n[1] && n[0] == n[2], "%s: primitive %d lacks %s",
                  name, prims, set);
            CHECK(num(at, engine_uvs ? "TEXCOORD_6" : "TEXCOORD_2", -1) < 0, "%s: a UV set past %s", name, set);
            if (!uv || !pos || !pv[0] || !pv[1] || !pv[2] || n[0] != n[1] || n[0] != n[2]) continue;
            for (int i = 0; i < n[0]; ++i) {
                vertices++;
                const double u = uv[2 * i], v = uv[2 * i + 1];
                const uint32_t col = (uint32_t)floor(u * t.w), row = (uint32_t)floor(v * t.h);
                const uint32_t k = row * t.w + col;
                if (col >= t.w || row >= t.h || k >= E) {
                    outside++;
                    continue;
                }
                off_centre += (float)u != (float)((col + 0.5) / t.w) || (float)v != (float)((row + 0.5) / t.h);
                /* an engine's 16-bit UVs keep it exactly */
                not_half += exr_half_to_float(exr_half_from_float(uv[2 * i])) != uv[2 * i] ||
                            exr_half_to_float(exr_half_from_float(uv[2 * i + 1])) != uv[2 * i + 1];
                /* glTF (x, z, -y) -> Unreal (x, -y, z) * 100: (gx, gz, gy) * 100 */
                const double want[3] = {100.0 * pv[0][i], 100.0 * pv[2][i], 100.0 * pv[1][i]};
                double got[3];
                int match = 1;
                for (int c = 0; c < 3; ++c) {
                    got[c] = exr_half_to_float(t.half[4 * k + c]);
                    match &= half_close(got[c], want[c]);
                }
                if (match) {
                    own++;
                    owned[k] = 1;
                } else if (depth[k] + 1 == info.depth) {
                    merged++;
                } else {
                    unmerged_mismatch++;
                }
                /* within the extent along the X axis (8-bit axis and extent, half pivot) */
                const double p[3] = {100.0 * pos[3 * i], 100.0 * pos[3 * i + 2], 100.0 * pos[3 * i + 1]};
                double a[3], len = 0, d = 0, r2 = 0;
                for (int c = 0; c < 3; ++c) a[c] = t.rgba[4 * k + c] / 255.0 * 2.0 - 1.0, len += a[c] * a[c];
                len = sqrt(len);
                for (int c = 0; c < 3; ++c) d += (p[c] - got[c]) * a[c] / len, r2 += (p[c] - got[c]) * (p[c] - got[c]);
                const double extent = t.rgba[4 * k + 3] / 255.0 * 2048.0;
                past_extent += d > extent + 2048.0 / 255.0 + 0.03 * sqrt(r2) + 1.0 && extent < 2047.0;
            }
        }
    }
    uint32_t unowned = 0;
    for (uint32_t k = 0; k < E; ++k) {
        unowned += !owned[k];
        if (!owned[k] && unowned <= 3)
            printf("%s: texel %u (depth %u) pivot %g %g %g has no vertex of its own\n", name, k, depth[k],
                   exr_half_to_float(t.half[4 * k]), exr_half_to_float(t.half[4 * k + 1]),
                   exr_half_to_float(t.half[4 * k + 2]));
    }
    CHECK(vertices == m->vertex_count, "%s: %llu vertices in the .glb, %u in the mesh", name,
          (unsigned long long)vertices, m->vertex_count);
    CHECK(outside == 0, "%s: %llu vertices' UVs outside the elements", name, (unsigned long long)outside);
    CHECK(off_centre == 0, "%s: %llu UVs not at a texel's centre", name, (unsigned long long)off_centre);
    CHECK(not_half == 0, "%s: %llu UVs change at half precision", name, (unsigned long long)not_half);
    CHECK(unmerged_mismatch == 0, "%s: %llu vertices whose texel is neither their pivot nor a merged branch", name,
          (unsigned long long)unmerged_mismatch);
    CHECK(own > 0 && unowned == 0, "%s: %u elements without vertices of their own pivot (%llu own vertices)", name,
          unowned, (unsigned long long)own);
    CHECK((info.merged > 0) == (merged > 0), "%s: %llu merged vertices, %u merged elements", name,
          (unsigned long long)merged, info.merged);
    CHECK(past_extent == 0, "%s: %llu vertices past their element's X extent", name, (unsigned long long)past_extent);
    printf("%s: %u elements (%u merged), %u x %u, %u levels; %llu vertices on their own pivot, %llu merged\n", name,
           E, info.merged, t.w, t.h, info.depth, (unsigned long long)own, (unsigned long long)merged);
    glb_free(&g);
    free(owned);
    free(depth);

    /* the same bytes again */
    snprintf(again, sizeof again, "%s_again", prefix);
    s = banyan_pivot_painter_write(again, m, NULL, NULL, &err);
    char a1[1300], a2[1300];
    for (int f = 0; f < 2 && s == BANYAN_OK; ++f) {
        const char *suffix = f ? "_XVector_Extent.png" : "_PivotPos_Index.exr";
        snprintf(a1, sizeof a1, "%s%s", prefix, suffix);
        snprintf(a2, sizeof a2, "%s%s", again, suffix);
        CHECK(same_file(a1, a2), "%s: %s differs when written again", name, suffix);
    }
    CHECK(s == BANYAN_OK, "%s again: %s", name, err.message);
    pp2_release(&t);

    /* without the option: no UV set past the engine's */
    o.pivot_painter = 0;
    snprintf(glb_path, sizeof glb_path, "%s_plain.glb", prefix);
    CHECK(banyan_gltf_write_ex(glb_path, list, NULL, 1, &o, &err) == BANYAN_OK, "%s plain: %s", name, err.message);
    if (glb_load(glb_path, &g)) {
        const cJSON *prim = cJSON_GetArrayItem(key(cJSON_GetArrayItem(key(g.json, "meshes"), 0), "primitives"), 0);
        CHECK(num(key(prim, "attributes"), set, -1) < 0, "%s: %s written without pivot_painter", name, set);
    }
    glb_free(&g);
}

/* ------------------------------------------------------------ refusals */

static void check_none(const char *prefix, const char *what) {
    char path[1200];
    for (int f = 0; f < 2; ++f) {
        snprintf(path, sizeof path, "%s%s", prefix, f ? "_XVector_Extent.png" : "_PivotPos_Index.exr");
        CHECK(!file_exists(path), "%s: %s was left", what, path);
    }
}

static void refuse(const char *what, const char *prefix, const banyan_mesh *m, const banyan_pivot_painter_options *o,
                   banyan_status want, const char *named) {
    banyan_error err = {0, ""};
    banyan_pivot_painter_info info;
    memset(&info, 0xab, sizeof info);
    banyan_status s = banyan_pivot_painter_write(prefix, m, o, &info, &err);
    CHECK(s == want && strstr(err.message, named) && info.elements == 0, "%s: status %d, '%s' (wanted %d naming %s)",
          what, s, err.message, want, named);
    if (prefix) check_none(prefix, what);
}

static void check_refusals(banyan_mesh *m) {
    char prefix[1100];
    snprintf(prefix, sizeof prefix, "%s", test_join(g_dir, "pp2_refused"));
    banyan_pivot_painter_options o = {NAN, 0};
    refuse("NaN scale", prefix, m, &o, BANYAN_E_RANGE, "opt->scale");
    o.scale = -1;
    refuse("negative scale", prefix, m, &o, BANYAN_E_RANGE, "opt->scale");
    o.scale = 1e5;
    refuse("huge scale", prefix, m, &o, BANYAN_E_RANGE, "opt->scale");
    o.scale = 0;
    o.sync = 2;
    refuse("sync 2", prefix, m, &o, BANYAN_E_RANGE, "opt->sync");
    refuse("NULL prefix", NULL, m, NULL, BANYAN_E_INVALID_ARG, "prefix");
    refuse("empty prefix", "", m, NULL, BANYAN_E_INVALID_ARG, "prefix");
    refuse("NULL mesh", prefix, NULL, NULL, BANYAN_E_INVALID_ARG, "mesh");
    char missing[1200];
    snprintf(missing, sizeof missing, "%s/no_such_folder/tree", g_dir);
    refuse("missing folder", missing, m, NULL, BANYAN_E_IO, "prefix");

    banyan_mesh c = *m;
    c.vertex_count = 0;
    refuse("no vertices", prefix, &c, NULL, BANYAN_E_RANGE, "vertex_count");
    c = *m;
    c.attribute_count = 0;
    refuse("no wind", prefix, &c, NULL, BANYAN_E_INVALID_ARG, "wind_pivot_x");
    float *px = (float *)banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X);
    const float keep = px[7];
    px[7] = NAN;
    refuse("NaN pivot", prefix, m, NULL, BANYAN_E_RANGE, "wind_pivot_x[7]");
    px[7] = keep;
    float *pos = m->positions;
    const float keep_pos = pos[4];
    pos[4] = INFINITY;
    refuse("infinite position", prefix, m, NULL, BANYAN_E_RANGE, "positions[4]");
    pos[4] = keep_pos;

    /* the glTF writer's option */
    banyan_gltf_options go;
    banyan_gltf_options_init(&go);
    go.textures = 0;
    const banyan_mesh *list[1] = {m};
    banyan_error err = {0, ""};
    char path[1200];
    snprintf(path, sizeof path, "%s.glb", prefix);
    go.pivot_painter = 2;
    CHECK(banyan_gltf_write_ex(path, list, NULL, 1, &go, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "opt->pivot_painter") && !file_exists(path),
          "glTF pivot_painter 2: '%s'", err.message);
    go.pivot_painter = 1;
    c = *m;
    c.attribute_count = 0;
    list[0] = &c;
    CHECK(banyan_gltf_write_ex(path, list, NULL, 1, &go, &err) == BANYAN_E_INVALID_ARG &&
              strstr(err.message, "meshes[0]") && strstr(err.message, "wind_pivot_x") && !file_exists(path),
          "glTF pivot_painter without wind: '%s'", err.message);
    banyan_gltf_node node = {m, "tree", 1, NULL, NULL};
    const banyan_mesh *lods[1] = {m};
    node.lods = lods;
    CHECK(banyan_gltf_write_nodes(path, &node, 1, &go, &err) == BANYAN_E_INVALID_ARG &&
              strstr(err.message, "lod_count") && !file_exists(path),
          "glTF pivot_painter with levels of detail: '%s'", err.message);
    snprintf(path, sizeof path, "%s.usda", prefix);
    node.lod_count = 0;
    CHECK(banyan_usd_write_nodes(path, &node, 1, &go, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "opt->pivot_painter") && !file_exists(path),
          "USD pivot_painter: '%s'", err.message);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: test_pivot_painter OUTDIR\n");
        return 2;
    }
    snprintf(g_dir, sizeof g_dir, "%s", argv[1]);
    struct {
        const char *plant, *name;
        int32_t variants;
        int engine_uvs;
    } cases[] = {{"keyaki_mature", "pp2_keyaki_mature", 0, 0},
                 {"avenue_small", "pp2_avenue", 0, 1},
                 {"avenue_small", "pp2_avenue_variants", 2, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        banyan_error err = {0, ""};
        banyan_mesh *m = lod_plant(cases[i].plant, cases[i].variants, &err);
        CHECK(m != NULL, "%s: %s", cases[i].plant, err.message);
        if (!m) continue;
        check_plant(cases[i].name, m, cases[i].engine_uvs);
        if (i == 0) check_refusals(m);
        banyan_mesh_free(m);
    }
    return check_done("test_pivot_painter");
}
