/*
 * test_gltf_stream.c - the streamed glTF buffer (gltf_writer.cpp).
 *
 *   test_gltf_stream OUTDIR
 *
 * The writer plans the views, lets tinygltf write the JSON for an empty
 * buffer, patches its byteLength and streams the bytes after it. Checks:
 *   - a .glb is one header, a JSON chunk and one BIN chunk whose lengths
 *     add up to the file, with buffers[0].byteLength the BIN's bytes and
 *     every view inside them;
 *   - the .gltf's base64 data URI decodes to the same bytes as the .glb's
 *     BIN chunk, and the two JSONs agree but for the URI;
 *   - POSITION min / max (computed before the bytes are written) are
 *     those of the written positions;
 *   - tangents computed per primitive (parts that keep to their own
 *     vertices) equal the whole mesh's, bit for bit, and so do those of
 *     primitives that share vertices (computed from the whole mesh);
 *   - NORMAL and COLOR_0 (converted several at a time) are, bit for bit,
 *     the one-at-a-time rule: (x, z, -y) renormalised in double, a zero
 *     normal +Y, signed zeros kept; colours clamped to [0, 1] and rounded
 *     to 0..255, on an odd vertex count (the tail too).
 * Ends with "N passed, N failed"; exits 1 on any failure.
 */
#include "banyan.h"
#include "check.h"
#include "test_files.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char g_dir[1024];

#define out_path(name) test_join(g_dir, name)

static uint32_t rd32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* A parsed .glb: its JSON and BIN chunk (pointing into data). */
typedef struct {
    unsigned char *data;
    size_t size;
    cJSON *json;
    const unsigned char *bin;
    size_t bin_len; /* buffers[0].byteLength */
} glb;

static void glb_free(glb *g) {
    cJSON_Delete(g->json);
    free(g->data);
    memset(g, 0, sizeof *g);
}

static double num(const cJSON *o, const char *key, double dflt) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : dflt;
}

/* Reads and checks the container; 0 on success. */
static int glb_read(const char *path, glb *g) {
    memset(g, 0, sizeof *g);
    g->data = (unsigned char *)test_read_file(path, &g->size);
    CHECK(g->data != NULL, "%s: cannot read", path);
    if (!g->data) return 1;
    const unsigned char *d = g->data;
    int ok = g->size >= 28 && memcmp(d, "glTF", 4) == 0 && rd32(d + 4) == 2;
    CHECK(ok, "%s: no glTF 2 header", path);
    if (!ok) return 1;
    CHECK(rd32(d + 8) == g->size, "%s: header length %u, file %zu bytes", path, rd32(d + 8), g->size);
    uint32_t jl = rd32(d + 12);
    ok = jl % 4 == 0 && rd32(d + 16) == 0x4E4F534Au && 20 + (size_t)jl + 8 <= g->size;
    CHECK(ok, "%s: bad JSON chunk (length %u)", path, jl);
    if (!ok) return 1;
    g->json = cJSON_ParseWithLength((const char *)d + 20, jl);
    CHECK(g->json != NULL, "%s: JSON chunk does not parse", path);
    if (!g->json) return 1;
    const unsigned char *b = d + 20 + jl;
    uint32_t bl = rd32(b);
    CHECK(rd32(b + 4) == 0x004E4942u, "%s: second chunk is not BIN", path);
    CHECK(bl % 4 == 0 && 20 + (size_t)jl + 8 + bl == g->size, "%s: BIN chunk of %u bytes does not end the file", path,
          bl);
    const cJSON *buf0 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g->json, "buffers"), 0);
    double n = num(buf0, "byteLength", -1);
    CHECK(n >= 0 && n <= bl && bl - n < 4, "%s: buffers[0].byteLength %.0f for a BIN chunk of %u", path, n, bl);
    CHECK(cJSON_GetObjectItemCaseSensitive(buf0, "uri") == NULL, "%s: buffer 0 has a uri", path);
    g->bin = b + 8;
    g->bin_len = n >= 0 && n <= bl ? (size_t)n : 0;
    const cJSON *v;
    cJSON_ArrayForEach(v, cJSON_GetObjectItemCaseSensitive(g->json, "bufferViews")) {
        double off = num(v, "byteOffset", 0), len = num(v, "byteLength", -1);
        CHECK(len >= 0 && off + len <= (double)g->bin_len, "%s: view [%.0f, +%.0f) outside the %zu bytes", path, off,
              len, g->bin_len);
    }
    return 0;
}

/* An accessor's floats (tightly packed views only); NULL when it is not. */
static const float *accessor_floats(const glb *g, int index, size_t *count, int *width) {
    const cJSON *a = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g->json, "accessors"), index);
    if (!a || num(a, "componentType", 0) != 5126) return NULL;
    const char *type = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(a, "type"));
    *width = !type ? 0 : !strcmp(type, "SCALAR") ? 1 : !strcmp(type, "VEC2") ? 2 : !strcmp(type, "VEC3") ? 3 : 4;
    const cJSON *v = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g->json, "bufferViews"),
                                        (int)num(a, "bufferView", -1));
    if (!v) return NULL;
    *count = (size_t)num(a, "count", 0);
    size_t off = (size_t)num(v, "byteOffset", 0) + (size_t)num(a, "byteOffset", 0);
    if (off % 4 || off + *count * (size_t)*width * 4 > g->bin_len) return NULL;
    return (const float *)(const void *)(g->bin + off);
}

static int attribute(const cJSON *prim, const char *name) {
    return (int)num(cJSON_GetObjectItemCaseSensitive(prim, "attributes"), name, -1);
}

static const cJSON *primitives(const glb *g, int mesh) {
    return cJSON_GetObjectItemCaseSensitive(
        cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g->json, "meshes"), mesh), "primitives");
}

/* Decodes standard base64 (with '=' padding); NULL on a bad character. */
static unsigned char *unbase64(const char *s, size_t n, size_t *out) {
    unsigned char *o = malloc(n / 4 * 3 + 3);
    size_t k = 0;
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = 0; o && i < n && s[i] != '='; ++i) {
        const char *al = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char *c = strchr(al, s[i]);
        if (!c || !*c) {
            free(o);
            return NULL;
        }
        acc = acc << 6 | (uint32_t)(c - al);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            o[k++] = (unsigned char)(acc >> bits & 0xFF);
        }
    }
    *out = k;
    return o;
}

static banyan_mesh *keyaki(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.levels = 8;
    p.seed = 11;
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK && m, "keyaki: %s", err.message);
    return m;
}

/* The .glb and the .gltf of one mesh: the same buffer, the same JSON but
 * for buffer 0's uri; POSITION min / max are the data's. */
static void check_containers(const banyan_mesh *m, const banyan_gltf_options *o) {
    banyan_error err = {0, ""};
    const char *pb = out_path("test_gltf_stream.glb"), *pj = out_path("test_gltf_stream.gltf");
    CHECK(banyan_gltf_write_ex(pb, &m, NULL, 1, o, &err) == BANYAN_OK, "write .glb: %s", err.message);
    CHECK(banyan_gltf_write_ex(pj, &m, NULL, 1, o, &err) == BANYAN_OK, "write .gltf: %s", err.message);
    glb g;
    if (glb_read(pb, &g) != 0) {
        glb_free(&g);
        return;
    }
    size_t jn = 0;
    char *text = test_read_file(pj, &jn);
    cJSON *j = text ? cJSON_Parse(text) : NULL;
    CHECK(j != NULL, ".gltf does not parse");
    cJSON *buf0 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "buffers"), 0);
    const char *uri = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(buf0, "uri"));
    const char *prefix = "data:application/octet-stream;base64,";
    CHECK(uri && !strncmp(uri, prefix, strlen(prefix)), ".gltf: buffer 0 is not a base64 data URI");
    if (uri && !strncmp(uri, prefix, strlen(prefix))) {
        size_t n = 0;
        unsigned char *bytes = unbase64(uri + strlen(prefix), strlen(uri) - strlen(prefix), &n);
        CHECK(bytes && n == g.bin_len && num(buf0, "byteLength", -1) == (double)n,
              ".gltf: data URI holds %zu bytes, byteLength %.0f, the .glb %zu", n, num(buf0, "byteLength", -1),
              g.bin_len);
        CHECK(bytes && n == g.bin_len && memcmp(bytes, g.bin, n) == 0, ".gltf: data URI bytes differ from the .glb's");
        free(bytes);
        cJSON_DeleteItemFromObjectCaseSensitive(buf0, "uri");
        CHECK(cJSON_Compare(j, g.json, 1), ".gltf and .glb JSON differ beyond the buffer's uri");
    }
    cJSON_Delete(j);
    free(text);

    /* POSITION min / max against the written data. */
    const cJSON *prim;
    int checked = 0;
    cJSON_ArrayForEach(prim, primitives(&g, 0)) {
        int a = attribute(prim, "POSITION"), w = 0;
        size_t count = 0;
        const float *p = accessor_floats(&g, a, &count, &w);
        const cJSON *acc = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g.json, "accessors"), a);
        if (!p || w != 3 || count == 0) continue;
        for (int k = 0; k < 3; ++k) {
            float lo = p[k], hi = p[k];
            for (size_t i = 1; i < count; ++i) {
                lo = fminf(lo, p[3 * i + k]);
                hi = fmaxf(hi, p[3 * i + k]);
            }
            const cJSON *mn = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(acc, "min"), k);
            const cJSON *mx = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(acc, "max"), k);
            CHECK(cJSON_IsNumber(mn) && cJSON_IsNumber(mx) && (float)mn->valuedouble == lo && (float)mx->valuedouble == hi,
                  "POSITION %d: min / max (%g, %g) are not the data's (%g, %g)", k, mn ? mn->valuedouble : 0.0,
                  mx ? mx->valuedouble : 0.0, (double)lo, (double)hi);
        }
        checked++;
    }
    CHECK(checked > 0, "no POSITION accessor checked");
    glb_free(&g);
}

/* TANGENT of every primitive of `name` against the one-primitive mesh's
 * (whole), vertex by vertex: base[k] is primitive k's first vertex. */
static void check_tangents(const char *label, const glb *g, const glb *whole, const uint32_t *base, int nprims) {
    int w = 0, ww = 0;
    size_t wn = 0, n = 0;
    const cJSON *wp = cJSON_GetArrayItem(primitives(whole, 0), 0);
    const float *wt = accessor_floats(whole, attribute(wp, "TANGENT"), &wn, &ww);
    CHECK(wt && ww == 4 && wn > 0, "%s: the whole mesh has no TANGENT", label);
    if (!wt) return;
    int k = 0, same = 1;
    const cJSON *prim;
    cJSON_ArrayForEach(prim, primitives(g, 0)) {
        const float *t = accessor_floats(g, attribute(prim, "TANGENT"), &n, &w);
        CHECK(t && w == 4 && k < nprims && base[k] + n <= wn, "%s: primitive %d has no usable TANGENT", label, k);
        if (!t || k >= nprims || base[k] + n > wn) return;
        if (memcmp(t, wt + 4 * (size_t)base[k], n * 4 * sizeof(float)) != 0) same = 0;
        k++;
    }
    CHECK(k == nprims, "%s: %d primitives, expected %d", label, k, nprims);
    CHECK(same, "%s: tangents differ from the whole mesh's", label);
}

/* NORMAL and COLOR_0 of a small mesh with the conversions' edge cases
 * against the rule computed here one value at a time. */
static void check_conversions(const banyan_mesh *like) {
    enum { NV = 7 };
    float pos[3 * NV], nrm[3 * NV] = {0, 0, 1,  0, 0, 0,  1e-30f, 0, 0,  3, 4, 12,  -0.0f, -0.0f, -1,
                                      0, -1, 0,  0.6f, -0.8f, 0};
    float col[4 * NV] = {-1, 0, 1, 2,  0.5f, 0.998f, 1.0f / 255, 0.5f / 255,  127.5f / 255, 0.25f, -0.0f, 1,
                         1e-9f, 0.999999f, 3, 0.75f,  0.1f, 0.2f, 0.3f, 0.4f,  0.6f, 0.7f, 0.8f, 0.9f,
                         0.0019607f, 0.00196079f, 0.5019608f, 0.9980392f};
    uint32_t idx[3 * (NV - 2)];
    for (int v = 0; v < NV; ++v) pos[3 * v] = (float)v, pos[3 * v + 1] = (float)(v % 2), pos[3 * v + 2] = 0;
    for (int t = 0; t < NV - 2; ++t) idx[3 * t] = (uint32_t)t, idx[3 * t + 1] = (uint32_t)t + 1, idx[3 * t + 2] = (uint32_t)t + 2;
    banyan_mesh c;
    memset(&c, 0, sizeof c);
    c.vertex_count = NV;
    c.index_count = 3 * (NV - 2);
    c.positions = pos, c.normals = nrm, c.colors = col, c.indices = idx;
    c.material_count = 1, c.materials = like->materials;
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.textures = 0;
    banyan_error err = {0, ""};
    const banyan_mesh *cm = &c;
    const char *path = out_path("test_gltf_stream_conversions.glb");
    CHECK(banyan_gltf_write_ex(path, &cm, NULL, 1, &o, &err) == BANYAN_OK, "conversions: %s", err.message);
    glb g = {NULL, 0, NULL, NULL, 0};
    if (glb_read(path, &g) != 0) {
        CHECK(0, "conversions: cannot read %s", path);
        return;
    }
    const cJSON *prim = cJSON_GetArrayItem(primitives(&g, 0), 0);
    size_t n = 0;
    int w = 0;
    const float *got = accessor_floats(&g, attribute(prim, "NORMAL"), &n, &w);
    int same = got && n == NV && w == 3;
    for (int v = 0; same && v < NV; ++v) {
        double q[3] = {nrm[3 * v], nrm[3 * v + 2], -(double)nrm[3 * v + 1]};
        double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        float want[3] = {0.0f, 1.0f, 0.0f};
        if (len > 0.0)
            for (int k = 0; k < 3; ++k) want[k] = (float)(q[k] / len);
        same = memcmp(want, got + 3 * v, sizeof want) == 0;
        CHECK(same, "conversions: NORMAL %d is (%g, %g, %g), not (%g, %g, %g)", v, got[3 * v], got[3 * v + 1],
              got[3 * v + 2], want[0], want[1], want[2]);
    }
    CHECK(got && n == NV && w == 3, "conversions: NORMAL is %zu x %d floats", n, w);
    const cJSON *a = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g.json, "accessors"), attribute(prim, "COLOR_0"));
    const cJSON *bv = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(g.json, "bufferViews"),
                                         (int)num(a, "bufferView", -1));
    size_t off = (size_t)num(bv, "byteOffset", 0) + (size_t)num(a, "byteOffset", 0);
    int ok = a && bv && num(a, "componentType", 0) == 5121 && num(a, "count", 0) == NV && off + 4 * NV <= g.bin_len;
    CHECK(ok, "conversions: COLOR_0 is not %d unsigned-byte RGBA values", NV);
    for (int i = 0; ok && i < 4 * NV; ++i) {
        float x = col[i];
        x = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
        unsigned want = (unsigned)(uint8_t)(x * 255.0f + 0.5f), have = g.bin[off + (size_t)i];
        ok = want == have;
        CHECK(ok, "conversions: COLOR_0 component %d of %g is %u, not %u", i, col[i], have, want);
    }
    glb_free(&g);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    snprintf(g_dir, sizeof g_dir, "%s", argv[1]);
    banyan_mesh *m = keyaki();
    if (!m) return 1;
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 64;
    check_containers(m, &o);
    check_conversions(m);

    /* Parts that keep to their own vertices: tangents per primitive. */
    banyan_error err = {0, ""};
    int nprims = 0;
    uint32_t base[64];
    for (uint32_t p = 0; p < m->part_count && nprims < 64; ++p)
        if (m->parts[p].index_count > 0) base[nprims++] = m->parts[p].vertex_offset;
    CHECK(nprims >= 2 && nprims < 64 && m->uvs && m->normals && m->material_count > 0 &&
              m->materials[0].texture != BANYAN_TEX_NONE,
          "the keyaki is not the textured, two-part mesh this test needs (%d parts)", nprims);
    const banyan_mesh *mm = m;
    const char *p_parts = out_path("test_gltf_stream_parts.glb");
    CHECK(banyan_gltf_write_ex(p_parts, &mm, NULL, 1, &o, &err) == BANYAN_OK, "parts: %s", err.message);

    /* The same arrays as one primitive: the whole mesh's tangents. */
    banyan_mesh one = *m;
    one.part_count = 0;
    one.parts = NULL;
    one.material_count = 1;
    const banyan_mesh *om = &one;
    const char *p_one = out_path("test_gltf_stream_one.glb");
    CHECK(banyan_gltf_write_ex(p_one, &om, NULL, 1, &o, &err) == BANYAN_OK, "one: %s", err.message);

    /* Parts over all the vertices (they share them): each primitive gets
     * every vertex, its tangents from the whole mesh. */
    banyan_mesh shared = *m;
    banyan_part parts[64];
    memcpy(parts, m->parts, m->part_count * sizeof *parts);
    uint32_t zero[64] = {0};
    for (uint32_t p = 0; p < m->part_count; ++p) {
        parts[p].vertex_offset = 0;
        parts[p].vertex_count = m->vertex_count;
    }
    shared.parts = parts;
    const banyan_mesh *sm = &shared;
    const char *p_shared = out_path("test_gltf_stream_shared.glb");
    CHECK(banyan_gltf_write_ex(p_shared, &sm, NULL, 1, &o, &err) == BANYAN_OK, "shared: %s", err.message);

    glb gp = {NULL, 0, NULL, NULL, 0}, g1 = gp, gs = gp;
    if (glb_read(p_parts, &gp) == 0 && glb_read(p_one, &g1) == 0 && glb_read(p_shared, &gs) == 0) {
        check_tangents("parts", &gp, &g1, base, nprims);
        check_tangents("shared", &gs, &g1, zero, nprims);
    }
    glb_free(&gp);
    glb_free(&g1);
    glb_free(&gs);
    banyan_mesh_free(m);
    return check_done("test_gltf_stream");
}
