/* banyan_gltf_write_nodes (csrc/gltf/gltf_writer.cpp), read back from the
 * .glb with a small loader here (cJSON for the JSON chunk, floats from the
 * BIN chunk):
 *   - wind: a keyaki's seven wind attributes go out as float scalars,
 *     _WIND_PIVOT_X/_Y/_Z in glTF's axes ((x, z, -y), like POSITION) and
 *     _WIND_LEVEL, ... as they are; birth stays _BIRTH; every custom
 *     attribute of every file here is SCALAR (Blender's importer before
 *     5.2 fails on mixed element counts); engine_uvs adds TEXCOORD_1 .. 4
 *     with the documented packing; a mesh with only some pivot components
 *     keeps them as they are;
 *   - MSFT_lod: levels as nodes outside the scene's roots, listed on the
 *     primary node, with MSFT_screencoverage (defaults and given);
 *   - EXT_mesh_gpu_instancing: an instanced avenue as one mesh and node
 *     per variant under the origin node, the instances' TRANSLATION,
 *     ROTATION (about +Y) and SCALE equal to banyan_instance's, Y up; its
 *     LOD carries the same instancing;
 *   - material.image: an embedded PNG baseColorTexture (flat without
 *     textures);
 *   - banyan_gltf_write_ex writes the same bytes as write_nodes;
 *   - bad nodes, LODs, instances, images and options refused naming the
 *     field, with no file written.
 * The files stay in OUTDIR for tests/gltf/validate.mjs (0 errors, 0
 * warnings).
 *
 *   test_gltf_nodes OUTDIR */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "test_files.h" /* banyan.h */
#include "banyan/lod.h"

static char g_dir[1024];

#define out_path(name) test_join(g_dir, name)

/* ------------------------------------------------------------ loader */

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

static cJSON *arr(const cJSON *o, const char *key) { return cJSON_GetObjectItemCaseSensitive(o, key); }
static cJSON *item(const glb *g, const char *list, int i) { return cJSON_GetArrayItem(arr(g->json, list), i); }
static int num(const cJSON *o, const char *key, int dflt) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valueint : dflt;
}
static int has_string(const cJSON *list, const char *s) {
    const cJSON *v;
    cJSON_ArrayForEach(v, list) if (cJSON_IsString(v) && !strcmp(v->valuestring, s)) return 1;
    return 0;
}
static int has_int(const cJSON *list, int x) {
    const cJSON *v;
    cJSON_ArrayForEach(v, list) if (cJSON_IsNumber(v) && v->valueint == x) return 1;
    return 0;
}

/* Accessor `a` as floats: its count, components (from `type`), NULL when
 * it is not a tightly packed float accessor inside the BIN chunk. */
static const float *floats(const glb *g, int a, int *count, int *comps, const char **type) {
    const cJSON *acc = item(g, "accessors", a);
    if (!acc || num(acc, "componentType", 0) != 5126) return NULL;
    const cJSON *bv = item(g, "bufferViews", num(acc, "bufferView", -1));
    const char *t = cJSON_GetStringValue(arr(acc, "type"));
    if (!bv || !t) return NULL;
    int c = !strcmp(t, "SCALAR") ? 1 : !strcmp(t, "VEC2") ? 2 : !strcmp(t, "VEC3") ? 3 : !strcmp(t, "VEC4") ? 4 : 0;
    size_t off = (size_t)num(bv, "byteOffset", 0) + (size_t)num(acc, "byteOffset", 0);
    size_t n = (size_t)num(acc, "count", 0);
    if (!c || num(bv, "byteStride", 0) || off + n * c * 4 > g->bin_len) return NULL;
    *count = (int)n;
    *comps = c;
    if (type) *type = t;
    return (const float *)(g->bin + off);
}

/* Attribute `name` of primitive p of mesh mi, or -1. */
static int prim_attr(const glb *g, int mi, int p, const char *name) {
    const cJSON *prim = cJSON_GetArrayItem(arr(item(g, "meshes", mi), "primitives"), p);
    return num(arr(prim, "attributes"), name, -1);
}

/* ------------------------------------------------------------ meshes */

static void *xcalloc(size_t n, size_t s) {
    void *p = calloc(n ? n : 1, s);
    if (!p) abort();
    return p;
}

/* The eight wind attributes every generator writes (banyan.h). */
static const char *const WIND_NAMES[8] = {BANYAN_ATTR_WIND_PIVOT_X, BANYAN_ATTR_WIND_PIVOT_Y, BANYAN_ATTR_WIND_PIVOT_Z,
                                          BANYAN_ATTR_WIND_LEVEL,   BANYAN_ATTR_WIND_STIFFNESS, BANYAN_ATTR_WIND_PHASE,
                                          BANYAN_ATTR_WIND_FLUTTER, BANYAN_ATTR_BIRTH};

/* 1 when the generator wrote all eight; a failure naming each missing one
 * otherwise (nothing is made up in their place). */
/* x rounded to the nearest IEEE half (10-bit mantissa; subnormal below
 * 2^-14), as an engine that stores a UV set at half precision keeps it. */
static double to_half(double x) {
    if (x == 0 || !isfinite(x)) return x;
    int e;
    frexp(fabs(x), &e); /* |x| in [2^(e-1), 2^e) */
    double step = ldexp(1.0, (e - 1 < -14 ? -14 : e - 1) - 10);
    return nearbyint(x / step) * step;
}

static int has_wind(const banyan_mesh *m, const char *what) {
    int ok = 1;
    for (int k = 0; k < 8; k++) {
        int here = banyan_mesh_attribute(m, WIND_NAMES[k]) != NULL;
        CHECK(here, "%s: the generator wrote no %s attribute", what, WIND_NAMES[k]);
        ok &= here;
    }
    return ok;
}

static banyan_mesh *keyaki(int levels) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.levels = levels;
    p.alpha = 1.45;
    p.unit = 0.5;
    banyan_error err;
    banyan_mesh *m = NULL;
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK, "keyaki: %s", err.message);
    return m;
}

/* A billboard-like mesh: two crossed vertical quads 2 m wide, 4 m tall,
 * carrying one RGBA picture (16 x 32) through material.image. */
static banyan_mesh *billboard(void) {
    banyan_mesh *m = xcalloc(1, sizeof *m);
    m->vertex_count = 8;
    m->index_count = 12;
    m->positions = xcalloc(24, sizeof(float));
    m->normals = xcalloc(24, sizeof(float));
    m->uvs = xcalloc(16, sizeof(float));
    m->indices = xcalloc(12, sizeof(uint32_t));
    for (int q = 0; q < 2; q++)
        for (int c = 0; c < 4; c++) {
            int v = 4 * q + c;
            float s = (c == 1 || c == 2) ? 1.0f : -1.0f, h = c >= 2 ? 4.0f : 0.0f;
            m->positions[3 * v + 0] = q == 0 ? s : 0.0f;
            m->positions[3 * v + 1] = q == 0 ? 0.0f : s;
            m->positions[3 * v + 2] = h;
            m->normals[3 * v + 0] = q == 0 ? 0.0f : 1.0f;
            m->normals[3 * v + 1] = q == 0 ? -1.0f : 0.0f;
            m->uvs[2 * v] = 0.5f * (s + 1.0f) * 0.5f + 0.5f * q;
            m->uvs[2 * v + 1] = h / 4.0f;
        }
    static const uint32_t idx[12] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    memcpy(m->indices, idx, sizeof idx);
    m->material_count = 1;
    m->materials = xcalloc(1, sizeof(banyan_material));
    snprintf(m->materials[0].name, BANYAN_NAME_MAX, "billboard");
    for (int c = 0; c < 4; c++) m->materials[0].base_color[c] = c == 3 ? 1.0f : 0.3f;
    m->materials[0].roughness = 0.8f;
    m->materials[0].double_sided = 1;
    m->materials[0].texture = BANYAN_TEX_NONE;
    m->materials[0].alpha_cutoff = 0.5f;
    m->materials[0].image = 1; /* images[0] */
    m->part_count = 1;
    m->parts = xcalloc(1, sizeof(banyan_part));
    m->parts[0] = (banyan_part){0, 8, 0, 12, 0, 0};
    m->image_count = 1;
    m->images = xcalloc(1, sizeof(banyan_image));
    m->images[0] = (banyan_image){16, 32, 4, xcalloc(16 * 32 * 4, 1)};
    for (int i = 0; i < 16 * 32; i++) {
        uint8_t *px = m->images[0].pixels + 4 * i;
        px[0] = (uint8_t)(i * 7);
        px[1] = 120;
        px[2] = (uint8_t)(i / 16 * 8);
        px[3] = (i % 16 > 3 && i % 16 < 12) ? 255 : 0;
    }
    return m;
}

static banyan_gltf_options small_textures(void) {
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 64;
    return o;
}

/* Primitives of the file without _WIND_PIVOT_X and _WIND_LEVEL (real
 * generators' meshes, and banyan_mesh_lod's levels of them, carry wind). */
static int windless_prims(const glb *g) {
    int bad = 0;
    for (int mi = 0; mi < cJSON_GetArraySize(arr(g->json, "meshes")); mi++)
        for (int p = 0; p < cJSON_GetArraySize(arr(item(g, "meshes", mi), "primitives")); p++)
            bad += prim_attr(g, mi, p, "_WIND_PIVOT_X") < 0 || prim_attr(g, mi, p, "_WIND_LEVEL") < 0;
    return bad;
}

/* Custom ("_"-prefixed) attributes of the file that are not float
 * SCALARs: Blender's glTF importer before 5.2 fails on a mesh whose custom
 * attributes differ in element count. */
static int non_scalar_custom(const glb *g) {
    int bad = 0;
    for (int mi = 0; mi < cJSON_GetArraySize(arr(g->json, "meshes")); mi++)
        for (int p = 0; p < cJSON_GetArraySize(arr(item(g, "meshes", mi), "primitives")); p++) {
            const cJSON *at;
            cJSON_ArrayForEach(at, arr(cJSON_GetArrayItem(arr(item(g, "meshes", mi), "primitives"), p), "attributes")) {
                if (at->string[0] != '_') continue;
                const cJSON *acc = item(g, "accessors", cJSON_IsNumber(at) ? at->valueint : -1);
                const char *t = cJSON_GetStringValue(arr(acc, "type"));
                bad += !t || strcmp(t, "SCALAR") || num(acc, "componentType", 0) != 5126;
            }
        }
    return bad;
}

/* ------------------------------------------------------------ tests */

static void wind(void) {
    banyan_mesh *m = keyaki(8);
    if (!m) return;
    if (!has_wind(m, "keyaki")) {
        banyan_mesh_free(m);
        return;
    }
    banyan_gltf_options o = small_textures();
    o.engine_uvs = 1;
    banyan_error err;
    banyan_gltf_node node = {m, "keyaki", 0, NULL, NULL};
    const char *path = out_path("test_gltf_nodes_wind.glb");
    CHECK(banyan_gltf_write_nodes(path, &node, 1, &o, &err) == BANYAN_OK, "wind: %s", err.message);
    glb g;
    CHECK(glb_load(path, &g), "cannot read %s back", path);
    const float *W[7], *B = banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH);
    const char *const *wn = WIND_NAMES;
    for (int k = 0; k < 7; k++) W[k] = banyan_mesh_attribute(m, wn[k]);
    /* The generator's values must be able to show a wrong packing: pivots
     * off the ground (y != 0, so (x, z, -y) differs from (x, y, z)) and
     * more than one level, phase and birth. */
    {
        uint32_t lifted = 0, lv = 0, ph = 0, br = 0;
        for (uint32_t i = 0; i < m->vertex_count; i++) {
            lifted += W[1][i] != 0 && W[1][i] != W[2][i];
            lv += W[3][i] != W[3][0];
            ph += W[5][i] != W[5][0];
            br += B[i] != B[0];
        }
        CHECK(lifted > 0 && lv > 0 && ph > 0 && br > 0,
              "keyaki's wind values cannot show a packing error: %u pivots with y != 0, %u/%u/%u vertices whose "
              "level/phase/birth differ from vertex 0's", lifted, lv, ph, br);
    }
    CHECK(non_scalar_custom(&g) == 0, "wind: %d custom attributes not float SCALAR", non_scalar_custom(&g));
    int prims = cJSON_GetArraySize(arr(item(&g, "meshes", 0), "primitives"));
    CHECK(g.json && prims == (int)m->part_count, "%d primitives for %u parts", prims, m->part_count);
    for (int p = 0; g.json && p < prims && p < (int)m->part_count; p++) {
        const uint32_t base = m->parts[p].vertex_offset, vc = m->parts[p].vertex_count;
        int n, c, bad = 0;
        const char *t;
        const float *pv[3];
        for (int k = 0; k < 3; k++) {
            static const char *const key[3] = {"_WIND_PIVOT_X", "_WIND_PIVOT_Y", "_WIND_PIVOT_Z"};
            pv[k] = floats(&g, prim_attr(&g, 0, p, key[k]), &n, &c, &t);
            CHECK(pv[k] && c == 1 && n == (int)vc, "prim %d: %s is not a float scalar of %u", p, key[k], vc);
        }
        for (uint32_t i = 0; pv[0] && pv[1] && pv[2] && i < vc; i++)
            bad += pv[0][i] != W[0][base + i] || pv[1][i] != W[2][base + i] || pv[2][i] != -W[1][base + i];
        CHECK(bad == 0, "prim %d: %d pivots not (x, z, -y)", p, bad);
        for (int k = 3; k < 7; k++) {
            char key[40];
            snprintf(key, sizeof key, "_%s", wn[k]);
            for (char *q = key; *q; q++) *q = (char)(*q >= 'a' && *q <= 'z' ? *q - 32 : *q);
            const float *w = floats(&g, prim_attr(&g, 0, p, key), &n, &c, &t);
            CHECK(w && c == 1 && n == (int)vc, "prim %d: %s is not a float scalar of %u", p, key, vc);
            bad = 0;
            for (uint32_t i = 0; w && i < vc; i++) bad += w[i] != W[k][base + i];
            CHECK(bad == 0, "prim %d: %d %s values differ from the mesh's", p, bad, key);
        }
        CHECK(prim_attr(&g, 0, p, "_WIND_PIVOT") < 0 && prim_attr(&g, 0, p, "_WIND_PARAMS") < 0,
              "prim %d: a packed _WIND_PIVOT or _WIND_PARAMS is written", p);
        const float *birth = floats(&g, prim_attr(&g, 0, p, "_BIRTH"), &n, &c, &t);
        CHECK(birth && c == 1, "prim %d: _BIRTH is not a float scalar", p);
        const float *tc[5];
        for (int s = 1; s <= 4; s++) {
            char key[16];
            snprintf(key, sizeof key, "TEXCOORD_%d", s);
            tc[s] = floats(&g, prim_attr(&g, 0, p, key), &n, &c, &t);
            CHECK(tc[s] && c == 2 && n == (int)vc, "prim %d: %s is not a float VEC2 of %u", p, key, vc);
        }
        bad = 0;
        const float *P = m->positions;
        double worst_half = 0; /* the pivot from arms rounded to half precision, off by this share of the arm */
        for (uint32_t i = 0; tc[1] && tc[2] && tc[3] && tc[4] && i < vc; i++) {
            uint32_t j = base + i;
            bad += tc[1][2 * i] != W[0][j] - P[3 * j] || tc[1][2 * i + 1] != W[2][j] - P[3 * j + 2];
            bad += tc[2][2 * i] != -(W[1][j] - P[3 * j + 1]) || tc[2][2 * i + 1] != W[3][j];
            const double arm[3] = {tc[1][2 * i], tc[1][2 * i + 1], tc[2][2 * i]};
            double len = sqrt(arm[0] * arm[0] + arm[1] * arm[1] + arm[2] * arm[2]), off = 0;
            for (int k = 0; k < 3; k++) off = fmax(off, fabs(to_half(arm[k]) - arm[k]));
            if (len > 1e-4 && off / len > worst_half) worst_half = off / len;
            bad += tc[3][2 * i] != W[4][j] || tc[3][2 * i + 1] != W[5][j];
            bad += tc[4][2 * i] != W[6][j] || tc[4][2 * i + 1] != B[j];
        }
        CHECK(bad == 0, "prim %d: %d engine UV values off the documented packing", p, bad);
        /* Half precision (an engine's compressed UV set) keeps the pivot
         * within 2^-11 of the arm's length, whatever the plant's size. */
        CHECK(worst_half <= ldexp(1.0, -11) + 1e-9, "prim %d: half precision moves a pivot by %.3g of its arm", p,
              worst_half);
    }
    glb_free(&g);

    /* Without engine_uvs: no TEXCOORD_1. */
    o.engine_uvs = 0;
    path = out_path("test_gltf_nodes_wind_plain.glb");
    CHECK(banyan_gltf_write_nodes(path, &node, 1, &o, &err) == BANYAN_OK, "wind plain: %s", err.message);
    CHECK(glb_load(path, &g) && prim_attr(&g, 0, 0, "_WIND_PIVOT_X") >= 0 && prim_attr(&g, 0, 0, "TEXCOORD_1") < 0,
          "engine_uvs 0 still writes TEXCOORD_1, or no _WIND_PIVOT_X");
    glb_free(&g);

    /* Only two pivot components: they go out as they are (no axis swap).
     * Synthetic (wind_pivot_z renamed away), since no generator writes a
     * partial set: it tests the writer's fallback for meshes from
     * elsewhere. */
    for (uint32_t a = 0; a < m->attribute_count; a++)
        if (!strcmp(m->attributes[a].name, BANYAN_ATTR_WIND_PIVOT_Z)) strcpy(m->attributes[a].name, "pivot_z_x");
    path = out_path("test_gltf_nodes_wind_partial.glb");
    CHECK(banyan_gltf_write_nodes(path, &node, 1, &o, &err) == BANYAN_OK, "partial: %s", err.message);
    if (glb_load(path, &g)) {
        const uint32_t vc = m->parts[0].vertex_count;
        int n, c, bad = 0;
        const char *t;
        const float *py = floats(&g, prim_attr(&g, 0, 0, "_WIND_PIVOT_Y"), &n, &c, &t);
        CHECK(py && c == 1 && prim_attr(&g, 0, 0, "_WIND_PIVOT_Z") < 0 && prim_attr(&g, 0, 0, "_PIVOT_Z_X") >= 0,
              "partial: no scalar _WIND_PIVOT_Y, or a _WIND_PIVOT_Z made up");
        for (uint32_t i = 0; py && i < vc; i++) bad += py[i] != W[1][m->parts[0].vertex_offset + i];
        CHECK(bad == 0, "partial: %d _WIND_PIVOT_Y values converted though the pivot is incomplete", bad);
    } else {
        CHECK(0, "cannot read %s back", path);
    }
    glb_free(&g);
    banyan_mesh_free(m);
}

/* A coarser level from banyan_mesh_lod; NULL, with a failure, if it
 * refuses. */
static banyan_mesh *coarser(const banyan_mesh *m, double ratio) {
    banyan_lod_params lp;
    banyan_lod_params_init(&lp);
    lp.ratio = ratio;
    banyan_mesh *out = NULL;
    banyan_error err;
    CHECK(banyan_mesh_lod(m, &lp, &out, &err) == BANYAN_OK, "banyan_mesh_lod ratio %g: %s", ratio, err.message);
    return out;
}

static void lods(void) {
    banyan_mesh *m = keyaki(9);
    if (!m) return;
    banyan_mesh *l1 = coarser(m, 0.5), *l2 = coarser(m, 0.15);
    if (!l1 || !l2) goto out;
    const banyan_mesh *chain[2] = {l1, l2};
    const double cover[3] = {0.6, 0.3, 0.05};
    banyan_gltf_node nodes[2] = {{m, "tree", 2, chain, NULL}, {m, "tree_b", 2, chain, cover}};
    banyan_gltf_options o = small_textures();
    banyan_error err;
    const char *path = out_path("test_gltf_nodes_lod.glb");
    CHECK(banyan_gltf_write_nodes(path, nodes, 2, &o, &err) == BANYAN_OK, "lod: %s", err.message);
    glb g;
    CHECK(glb_load(path, &g), "cannot read %s back", path);
    if (!g.json) goto out;
    const cJSON *roots = arr(item(&g, "scenes", 0), "nodes");
    CHECK(cJSON_GetArraySize(roots) == 2, "the scene has %d roots, not 2", cJSON_GetArraySize(roots));
    CHECK(has_string(arr(g.json, "extensionsUsed"), "MSFT_lod") && !arr(g.json, "extensionsRequired"),
          "MSFT_lod not in extensionsUsed, or something required");
    static const double want[2][3] = {{0.5, 0.25, 0.125}, {0.6, 0.3, 0.05}};
    for (int r = 0; r < 2; r++) {
        int ni = cJSON_GetArrayItem(roots, r)->valueint;
        const cJSON *node = item(&g, "nodes", ni);
        const cJSON *ids = arr(arr(arr(node, "extensions"), "MSFT_lod"), "ids");
        CHECK(cJSON_GetArraySize(ids) == 2, "node %d: MSFT_lod ids has %d levels", ni, cJSON_GetArraySize(ids));
        int seen_mesh = 0;
        const cJSON *id;
        cJSON_ArrayForEach(id, ids) {
            CHECK(!has_int(roots, id->valueint), "LOD node %d is a scene root", id->valueint);
            const cJSON *ln = item(&g, "nodes", id->valueint);
            seen_mesh += num(ln, "mesh", -1) >= 0 && num(ln, "mesh", -1) != num(node, "mesh", -1);
        }
        CHECK(seen_mesh == 2, "node %d: its levels are not nodes with their own meshes", ni);
        const cJSON *cov = arr(arr(node, "extras"), "MSFT_screencoverage");
        CHECK(cJSON_GetArraySize(cov) == 3, "node %d: %d screen coverages", ni, cJSON_GetArraySize(cov));
        for (int k = 0; k < 3 && cJSON_GetArraySize(cov) == 3; k++)
            CHECK(fabs(cJSON_GetArrayItem(cov, k)->valuedouble - want[r][k]) < 1e-12, "node %d coverage %d = %g, not %g",
                  ni, k, cJSON_GetArrayItem(cov, k)->valuedouble, want[r][k]);
    }
    CHECK(windless_prims(&g) == 0, "lod: %d primitives (of the tree or its levels) without wind", windless_prims(&g));
    CHECK(non_scalar_custom(&g) == 0, "lod: %d custom attributes not float SCALAR", non_scalar_custom(&g));
    glb_free(&g);
out:
    banyan_mesh_free(m);
    banyan_mesh_free(l1);
    banyan_mesh_free(l2);
}

/* The instances of variant v of m, in order, as glTF would hold them. */
static int instance_check(const glb *g, int node_index, const banyan_mesh *m, uint32_t v, int *count) {
    const cJSON *ext = arr(arr(item(g, "nodes", node_index), "extensions"), "EXT_mesh_gpu_instancing");
    const cJSON *at = arr(ext, "attributes");
    int n[3], c[3], bad = 0;
    const float *T = floats(g, num(at, "TRANSLATION", -1), &n[0], &c[0], NULL);
    const float *R = floats(g, num(at, "ROTATION", -1), &n[1], &c[1], NULL);
    const float *S = floats(g, num(at, "SCALE", -1), &n[2], &c[2], NULL);
    if (!T || !R || !S || c[0] != 3 || c[1] != 4 || c[2] != 3 || n[0] != n[1] || n[0] != n[2]) return -1;
    int j = 0;
    for (uint32_t i = 0; i < m->instance_count; i++) {
        const banyan_instance *in = &m->instances[i];
        if (in->variant != v) continue;
        if (j >= n[0]) return -1;
        double h = 0.5 * in->rotation_z;
        bad += T[3 * j] != in->translation[0] || T[3 * j + 1] != in->translation[2] ||
               T[3 * j + 2] != -in->translation[1];
        bad += R[4 * j] != 0 || fabs(R[4 * j + 1] - sin(h)) > 1e-6 || R[4 * j + 2] != 0 ||
               fabs(R[4 * j + 3] - cos(h)) > 1e-6;
        bad += S[3 * j] != in->scale || S[3 * j + 1] != in->scale || S[3 * j + 2] != in->scale;
        j++;
    }
    *count = j;
    return j == n[0] ? bad : -1;
}

static void instanced(void) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    p.tree.levels = 8;
    p.tree.alpha = 1.45;
    p.tree.unit = 0.5;
    p.placement = BANYAN_AVENUE_COUNT;
    p.count = 3;
    p.end[0] = 20;
    p.variants = 2;
    banyan_error err;
    banyan_mesh *m = NULL;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &err) == BANYAN_OK, "avenue: %s", err.message);
    if (!m) return;
    CHECK(m->instance_count == 6, "%u instances", m->instance_count);
    banyan_mesh *lod = NULL;
    banyan_lod_params lp;
    banyan_lod_params_init(&lp);
    CHECK(banyan_mesh_lod(m, &lp, &lod, &err) == BANYAN_OK, "banyan_mesh_lod of the avenue: %s", err.message);
    if (!lod) goto out;
    const banyan_mesh *chain[1] = {lod};
    banyan_gltf_node node = {m, "avenue", 1, chain, NULL};
    banyan_gltf_options o = small_textures();
    const char *path = out_path("test_gltf_nodes_instanced.glb");
    CHECK(banyan_gltf_write_nodes(path, &node, 1, &o, &err) == BANYAN_OK, "instanced: %s", err.message);
    glb g;
    CHECK(glb_load(path, &g), "cannot read %s back", path);
    if (!g.json) goto out;
    CHECK(has_string(arr(g.json, "extensionsUsed"), "EXT_mesh_gpu_instancing") && !arr(g.json, "extensionsRequired"),
          "EXT_mesh_gpu_instancing not used, or required");
    int root = cJSON_GetArrayItem(arr(item(&g, "scenes", 0), "nodes"), 0)->valueint;
    const cJSON *lod_ids = arr(arr(arr(item(&g, "nodes", root), "extensions"), "MSFT_lod"), "ids");
    int lod_root = cJSON_GetArraySize(lod_ids) == 1 ? cJSON_GetArrayItem(lod_ids, 0)->valueint : -1;
    CHECK(lod_root >= 0, "the instanced node has no MSFT_lod level");
    for (int which = 0; which < 2; which++) {
        int parent = which ? lod_root : root;
        const banyan_mesh *mm = which ? chain[0] : m;
        if (parent < 0) continue;
        const cJSON *pn = item(&g, "nodes", parent);
        const cJSON *kids = arr(pn, "children");
        CHECK(num(pn, "mesh", -1) < 0 && cJSON_GetArraySize(kids) == 2, "node %d: %d variant children, mesh %d", parent,
              cJSON_GetArraySize(kids), num(pn, "mesh", -1));
        int total = 0, k = 0;
        const cJSON *kid;
        cJSON_ArrayForEach(kid, kids) {
            int cnt = 0, bad = instance_check(&g, kid->valueint, mm, (uint32_t)k, &cnt);
            CHECK(bad == 0, "node %d (variant %d): %d instance values differ from banyan_instance (Y up)", kid->valueint,
                  k, bad);
            uint32_t parts = 0;
            for (uint32_t q = 0; q < mm->part_count; q++) parts += mm->parts[q].group == (uint32_t)k;
            int prims = cJSON_GetArraySize(arr(item(&g, "meshes", num(item(&g, "nodes", kid->valueint), "mesh", -1)),
                                               "primitives"));
            CHECK(prims == (int)parts, "variant %d: %d primitives for %u parts", k, prims, parts);
            total += cnt;
            k++;
        }
        CHECK(total == (int)mm->instance_count, "node %d: %d instances written of %u", parent, total,
              mm->instance_count);
    }
    CHECK(windless_prims(&g) == 0, "instanced: %d primitives (of the variants or their level) without wind",
          windless_prims(&g));
    CHECK(non_scalar_custom(&g) == 0, "instanced: %d custom attributes not float SCALAR", non_scalar_custom(&g));
    glb_free(&g);
out:
    banyan_mesh_free(lod);
    banyan_mesh_free(m);
}

static void images(void) {
    banyan_mesh *m = billboard();
    banyan_gltf_options o = small_textures();
    banyan_error err;
    banyan_gltf_node node = {m, "billboard", 0, NULL, NULL};
    const char *path = out_path("test_gltf_nodes_image.glb");
    CHECK(banyan_gltf_write_nodes(path, &node, 1, &o, &err) == BANYAN_OK, "image: %s", err.message);
    glb g;
    CHECK(glb_load(path, &g), "cannot read %s back", path);
    if (g.json) {
        const cJSON *mat = item(&g, "materials", 0), *pbr = arr(mat, "pbrMetallicRoughness");
        int tex = num(arr(pbr, "baseColorTexture"), "index", -1);
        const cJSON *t = item(&g, "textures", tex);
        const cJSON *im = item(&g, "images", num(t, "source", -1));
        const cJSON *bv = item(&g, "bufferViews", num(im, "bufferView", -1));
        CHECK(cJSON_GetArraySize(arr(g.json, "images")) == 1 && im && bv &&
                  !strcmp(cJSON_GetStringValue(arr(im, "mimeType")), "image/png"),
              "the picture is not one embedded PNG");
        CHECK(!arr(mat, "normalTexture") && !strcmp(cJSON_GetStringValue(arr(mat, "alphaMode")), "MASK"),
              "the picture's material has a normal map or is not alpha-tested");
        CHECK(bv && memcmp(g.bin + num(bv, "byteOffset", 0), "\x89PNG", 4) == 0, "the image bytes are not a PNG");
        CHECK(num(item(&g, "samplers", num(t, "sampler", -1)), "wrapS", 0) == 33071, "the picture does not clamp");
    }
    glb_free(&g);
    /* Textures off, and a zeroed material (image 0) on a mesh that has
     * an image: flat, no image. */
    for (int k = 0; k < 2; k++) {
        o.textures = k;
        m->materials[0].image = k ? 0 : 1;
        path = out_path(k ? "test_gltf_nodes_image_none.glb" : "test_gltf_nodes_image_flat.glb");
        CHECK(banyan_gltf_write_nodes(path, &node, 1, &o, &err) == BANYAN_OK, "image flat %d: %s", k, err.message);
        CHECK(glb_load(path, &g) && !arr(g.json, "images") &&
                  !arr(arr(item(&g, "materials", 0), "pbrMetallicRoughness"), "baseColorTexture"),
              k ? "image 0 embeds the mesh's images[0]" : "textures off still embeds the picture");
        glb_free(&g);
    }
    banyan_mesh_free(m);
}

/* write_ex is write_nodes with one plain node per mesh: the same bytes. */
static void one_writer(void) {
    banyan_mesh *m = keyaki(7);
    if (!m) return;
    has_wind(m, "keyaki(7)"); /* the same bytes with the wind packing in */
    banyan_gltf_options o = small_textures();
    banyan_error err;
    const char *a = out_path("test_gltf_nodes_ex.glb"), *b = out_path("test_gltf_nodes_same.glb");
    const char *name = "tree";
    banyan_gltf_node node = {m, name, 0, NULL, NULL};
    CHECK(banyan_gltf_write_ex(a, (const banyan_mesh *const *)&m, &name, 1, &o, &err) == BANYAN_OK, "%s", err.message);
    CHECK(banyan_gltf_write_nodes(b, &node, 1, &o, &err) == BANYAN_OK, "%s", err.message);
    size_t la = 0, lb = 0;
    char *x = test_read_file(a, &la), *y = test_read_file(b, &lb);
    CHECK(x && y && la == lb && memcmp(x, y, la) == 0, "write_ex and write_nodes differ (%zu, %zu bytes)", la, lb);
    free(x);
    free(y);
    banyan_mesh_free(m);
}

static int exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

static void refuse(const char *what, const banyan_gltf_node *nodes, uint32_t count, const banyan_gltf_options *o,
                   banyan_status want, const char *needle) {
    const char *path = out_path("test_gltf_nodes_refused.glb");
    unlink(path);
    banyan_error err;
    memset(&err, 0, sizeof err);
    banyan_status s = banyan_gltf_write_nodes(path, nodes, count, o, &err);
    CHECK(s == want && strstr(err.message, needle) && !exists(path), "%s: status %d (want %d), \"%s\" lacks \"%s\"%s",
          what, s, want, err.message, needle, exists(path) ? ", file written" : "");
}

static void refusals(void) {
    banyan_mesh *m = billboard();
    banyan_gltf_options o = small_textures();
    banyan_gltf_node node = {m, "b", 0, NULL, NULL};
    refuse("count 0", &node, 0, &o, BANYAN_E_INVALID_ARG, "count");
    refuse("count 65537", &node, 65537, &o, BANYAN_E_RANGE, "count");
    refuse("nodes NULL", NULL, 1, &o, BANYAN_E_INVALID_ARG, "nodes");
    o.engine_uvs = 2;
    refuse("engine_uvs", &node, 1, &o, BANYAN_E_RANGE, "engine_uvs");
    o.engine_uvs = 0;
    o.sync = 2;
    refuse("sync", &node, 1, &o, BANYAN_E_RANGE, "sync");
    o.sync = 0;
    banyan_gltf_node two[2] = {node, {NULL, "x", 0, NULL, NULL}};
    refuse("mesh NULL", two, 2, &o, BANYAN_E_INVALID_ARG, "nodes[1].mesh");
    node.lod_count = 8;
    refuse("lod_count", &node, 1, &o, BANYAN_E_RANGE, "nodes[0].lod_count");
    node.lod_count = 1;
    refuse("lods NULL", &node, 1, &o, BANYAN_E_INVALID_ARG, "nodes[0].lods");
    banyan_mesh empty;
    memset(&empty, 0, sizeof empty);
    const banyan_mesh *bad_chain[1] = {&empty};
    node.lods = bad_chain;
    refuse("bad lod", &node, 1, &o, BANYAN_E_INVALID_ARG, "nodes[0].lods[0]");
    const banyan_mesh *chain[1] = {m};
    node.lods = chain;
    const double rising[2] = {0.5, 0.6}, zero[2] = {0.5, 0.0};
    node.lod_coverage = rising;
    refuse("coverage rising", &node, 1, &o, BANYAN_E_RANGE, "lod_coverage[1]");
    node.lod_coverage = zero;
    refuse("coverage 0", &node, 1, &o, BANYAN_E_RANGE, "lod_coverage[1]");
    node.lod_count = 0;
    node.lod_coverage = NULL;

    banyan_instance in[2] = {{0, {1, 2, 0}, 0.5f, 1.0f}, {0, {3, 2, 0}, 0.5f, 1.0f}};
    m->instances = in;
    m->instance_count = 2;
    in[1].variant = 3;
    refuse("variant", &node, 1, &o, BANYAN_E_RANGE, "nodes[0].mesh.instances[1].variant");
    in[1].variant = 0;
    in[1].translation[2] = NAN;
    refuse("translation", &node, 1, &o, BANYAN_E_RANGE, "instances[1].translation[2]");
    in[1].translation[2] = 0;
    in[0].scale = 0;
    refuse("scale", &node, 1, &o, BANYAN_E_RANGE, "instances[0].scale");
    in[0].scale = 1;
    in[0].rotation_z = INFINITY;
    refuse("rotation", &node, 1, &o, BANYAN_E_RANGE, "instances[0].rotation_z");
    in[0].rotation_z = 0;
    m->instances = NULL;
    refuse("instances NULL", &node, 1, &o, BANYAN_E_INVALID_ARG, "instances");
    m->instance_count = 0;
    /* A valid instanced billboard passes (and is validated). */
    m->instances = in;
    m->instance_count = 2;
    banyan_error err;
    CHECK(banyan_gltf_write_nodes(out_path("test_gltf_nodes_cards.glb"), &node, 1, &o, &err) == BANYAN_OK,
          "instanced cards: %s", err.message);
    m->instances = NULL;
    m->instance_count = 0;

    m->materials[0].image = 2;
    refuse("image index", &node, 1, &o, BANYAN_E_RANGE, "materials[0].image");
    m->materials[0].image = -1;
    refuse("image -1", &node, 1, &o, BANYAN_E_RANGE, "materials[0].image");
    m->materials[0].image = 1;
    m->images[0].channels = 2;
    refuse("channels", &node, 1, &o, BANYAN_E_RANGE, "images[0].channels");
    m->images[0].channels = 4;
    m->images[0].width = 0;
    refuse("width", &node, 1, &o, BANYAN_E_RANGE, "images[0]");
    m->images[0].width = 16;
    float *uvs = m->uvs;
    m->uvs = NULL;
    refuse("image without uvs", &node, 1, &o, BANYAN_E_INVALID_ARG, "uvs");
    m->uvs = uvs;
    banyan_mesh_free(m);
}

int main(int argc, char **argv) {
    snprintf(g_dir, sizeof g_dir, "%s", argc > 1 ? argv[1] : ".");
    wind();
    lods();
    instanced();
    images();
    one_writer();
    refusals();
    return check_done("test_gltf_nodes");
}
