/*
 * test_gltf.c - banyan_gltf_write on hand-built meshes.
 *
 *   test_gltf OUTDIR
 *
 * Writes test_gltf_*.glb / .gltf into OUTDIR (which must exist) for
 * tests/gltf/validate.mjs to check, and checks that bad input fails with
 * the right status, a message, and no file. Uses only banyan_gltf_write,
 * so it does not depend on the rest of the library; the meshes are freed
 * with free(). Ends with "N passed, N failed"; exits 1 on any failure.
 */
#define _POSIX_C_SOURCE 200809L /* symlink */

#include "banyan.h"
#include "test_files.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#if defined(__linux__)
#include <unistd.h>
#endif

static int g_passed, g_failed;

#define CHECK(cond, ...)                                     \
    do {                                                     \
        if (cond) {                                          \
            g_passed++;                                      \
        } else {                                             \
            g_failed++;                                      \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);      \
            printf(__VA_ARGS__);                             \
            printf("\n");                                    \
        }                                                    \
    } while (0)

static char g_dir[1024];

#define out_path(name) test_join(g_dir, name)

static int file_exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* Reads a whole file; *size gets its length. NULL on failure. */
static unsigned char *read_all(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *data = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? cap * 2 : 65536;
            unsigned char *d = realloc(data, cap + 1);
            if (!d) {
                free(data);
                fclose(f);
                return NULL;
            }
            data = d;
        }
        size_t r = fread(data + n, 1, cap - n, f);
        n += r;
        if (r == 0) break;
    }
    fclose(f);
    data[n] = 0;
    *size = n;
    return data;
}

static uint32_t rd32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The JSON text of a .glb or .gltf file (malloc'd, NUL-terminated). */
static char *json_of(const char *path, int binary) {
    size_t size = 0;
    unsigned char *data = read_all(path, &size);
    if (!data) return NULL;
    if (!binary) return (char *)data;
    char *json = NULL;
    if (size >= 20 && memcmp(data, "glTF", 4) == 0 && rd32(data + 4) == 2 &&
        rd32(data + 8) == size && rd32(data + 16) == 0x4E4F534Au && 20 + (size_t)rd32(data + 12) <= size) {
        size_t jl = rd32(data + 12);
        json = malloc(jl + 1);
        if (json) {
            memcpy(json, data + 20, jl);
            json[jl] = 0;
        }
    }
    free(data);
    return json;
}

/* ------------------------------------------------------------- meshes */

static banyan_mesh *mesh_alloc(uint32_t vc, uint32_t ic, int colors, uint32_t nattr,
                               uint32_t nmat, uint32_t nparts) {
    banyan_mesh *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    m->vertex_count = vc;
    m->index_count = ic;
    m->positions = calloc((size_t)vc * 3, sizeof(float));
    m->normals = calloc((size_t)vc * 3, sizeof(float));
    m->uvs = calloc((size_t)vc * 2, sizeof(float));
    m->colors = colors ? calloc((size_t)vc * 4, sizeof(float)) : NULL;
    m->indices = calloc(ic, sizeof(uint32_t));
    m->attribute_count = nattr;
    m->attributes = nattr ? calloc(nattr, sizeof(banyan_attribute)) : NULL;
    for (uint32_t a = 0; a < nattr && m->attributes; ++a)
        m->attributes[a].data = calloc(vc, sizeof(float));
    m->material_count = nmat;
    m->materials = nmat ? calloc(nmat, sizeof(banyan_material)) : NULL;
    m->part_count = nparts;
    m->parts = nparts ? calloc(nparts, sizeof(banyan_part)) : NULL;
    return m;
}

static void mesh_destroy(banyan_mesh *m) {
    if (!m) return;
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->colors);
    free(m->indices);
    for (uint32_t a = 0; a < m->attribute_count && m->attributes; ++a) free(m->attributes[a].data);
    free(m->attributes);
    free(m->materials);
    free(m->parts);
    free(m->skel_points);
    free(m->skel_radius);
    free(m->skel_tag);
    free(m->skel_edges);
    free(m);
}

static void set3(float *a, uint32_t i, float x, float y, float z) {
    a[3 * i] = x;
    a[3 * i + 1] = y;
    a[3 * i + 2] = z;
}

static void set_material(banyan_material *m, const char *name, float r, float g, float b,
                         float a, float rough, int ds) {
    snprintf(m->name, sizeof m->name, "%s", name);
    m->base_color[0] = r;
    m->base_color[1] = g;
    m->base_color[2] = b;
    m->base_color[3] = a;
    m->roughness = rough;
    m->double_sided = ds;
    /* texture is left as calloc made it: 0, BANYAN_TEX_NONE */
}

/* Mesh A: part 0 = a tetrahedron of bark (4 vertices, 4 triangles, some
 * normals not unit length and one zero), part 1 = a double-sided leaf card
 * (4 vertices, 2 triangles). Colours, two custom attributes, two
 * materials. */
static banyan_mesh *make_mesh_a(void) {
    banyan_mesh *m = mesh_alloc(8, 18, 1, 2, 2, 2);
    if (!m || !m->positions || !m->normals || !m->uvs || !m->colors || !m->indices ||
        !m->attributes || !m->attributes[0].data || !m->attributes[1].data || !m->materials ||
        !m->parts) {
        mesh_destroy(m);
        return NULL;
    }
    /* tetrahedron, Z up */
    set3(m->positions, 0, 0, 0, 0);
    set3(m->positions, 1, 1, 0, 0);
    set3(m->positions, 2, 0, 1, 0);
    set3(m->positions, 3, 0.3f, 0.3f, 2.0f);
    set3(m->normals, 0, -1, -1, -1);  /* not unit: renormalised */
    set3(m->normals, 1, 2, 0, 0);     /* not unit */
    set3(m->normals, 2, 0, 1, 0);
    set3(m->normals, 3, 0, 0, 0);     /* zero: written as +Y */
    static const uint32_t tet[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    memcpy(m->indices, tet, sizeof tet);
    /* leaf card in the plane x = 0.5, from z = 1 to z = 1.5 */
    set3(m->positions, 4, 0.5f, -0.2f, 1.0f);
    set3(m->positions, 5, 0.5f, 0.2f, 1.0f);
    set3(m->positions, 6, 0.5f, 0.2f, 1.5f);
    set3(m->positions, 7, 0.5f, -0.2f, 1.5f);
    for (uint32_t i = 4; i < 8; ++i) set3(m->normals, i, 1, 0, 0);
    static const uint32_t card[6] = {4, 5, 6, 4, 6, 7};
    memcpy(m->indices + 12, card, sizeof card);
    for (uint32_t i = 0; i < 8; ++i) {
        m->uvs[2 * i] = (float)(i % 4) / 4.0f;
        m->uvs[2 * i + 1] = (float)i * 0.5f;
        m->colors[4 * i] = 0.1f * (float)i;
        m->colors[4 * i + 1] = 0.5f;
        m->colors[4 * i + 2] = 1.0f - 0.1f * (float)i;
        m->colors[4 * i + 3] = 1.0f;
        m->attributes[0].data[i] = i < 4 ? 1.0f : 2.0f;
        m->attributes[1].data[i] = (float)i * 3.0f;
    }
    snprintf(m->attributes[0].name, BANYAN_NAME_MAX, "root_kind");
    snprintf(m->attributes[1].name, BANYAN_NAME_MAX, "birth_step");
    set_material(&m->materials[0], "bark", 0.35f, 0.25f, 0.18f, 1.0f, 0.9f, 0);
    set_material(&m->materials[1], "leaf \xe8\x91\x89", 0.2f, 0.6f, 0.15f, 1.0f, 0.5f, 1);
    m->parts[0] = (banyan_part){0, 4, 0, 12, 0, 0};
    m->parts[1] = (banyan_part){4, 4, 12, 6, 1, 1};
    return m;
}

/* Mesh B: one quad, no colours, no attributes, one material, one part.
 * Spans x 1..3, y -1..2, z 0..5 (Z up). */
static banyan_mesh *make_mesh_b(void) {
    banyan_mesh *m = mesh_alloc(4, 6, 0, 0, 1, 1);
    if (!m || !m->positions || !m->normals || !m->uvs || !m->indices || !m->materials ||
        !m->parts) {
        mesh_destroy(m);
        return NULL;
    }
    set3(m->positions, 0, 1, -1, 0);
    set3(m->positions, 1, 3, 2, 0);
    set3(m->positions, 2, 3, 2, 5);
    set3(m->positions, 3, 1, -1, 5);
    for (uint32_t i = 0; i < 4; ++i) set3(m->normals, i, 0.8320503f, -0.5547002f, 0);
    static const uint32_t q[6] = {0, 1, 2, 0, 2, 3};
    memcpy(m->indices, q, sizeof q);
    for (uint32_t i = 0; i < 4; ++i) {
        m->uvs[2 * i] = (i == 1 || i == 2) ? 1.0f : 0.0f;
        m->uvs[2 * i + 1] = i >= 2 ? 3.0f : 0.0f;
    }
    set_material(&m->materials[0], "trunk", 0.4f, 0.3f, 0.2f, 1.0f, 0.8f, 0);
    m->parts[0] = (banyan_part){0, 4, 0, 6, 0, 0};
    return m;
}

/* Parses the 3 numbers after `key` (e.g. "\"max\"") in json. */
static int parse_vec3(const char *json, const char *key, double out[3]) {
    const char *p = strstr(json, key);
    if (!p) return 0;
    p = strchr(p, '[');
    if (!p) return 0;
    ++p;
    for (int k = 0; k < 3; ++k) {
        char *end;
        out[k] = strtod(p, &end);
        if (end == p) return 0;
        p = end;
        while (*p == ',' || *p == ' ' || *p == '\n') ++p;
    }
    return 1;
}

static void check_written(const char *name, int binary, const char *const *must) {
    const char *path = out_path(name);
    char *json = json_of(path, binary);
    CHECK(json != NULL, "%s: cannot read it back as %s", path, binary ? "GLB" : "glTF JSON");
    if (!json) return;
    for (int i = 0; must[i]; ++i)
        CHECK(strstr(json, must[i]) != NULL, "%s: JSON lacks %s", name, must[i]);
    free(json);
}

static void expect_fail(const char *what, const char *path, const banyan_mesh *const *meshes,
                        const char *const *names, uint32_t count, banyan_status code,
                        const char *needle) {
    banyan_error err;
    memset(&err, 0, sizeof err);
    if (path) remove(path);
    banyan_status s = banyan_gltf_write(path, meshes, names, count, &err);
    CHECK(s == code, "%s: status %d, expected %d (message: %s)", what, (int)s, (int)code,
          err.message);
    CHECK(err.code == (int32_t)code, "%s: err.code %d, expected %d", what, (int)err.code,
          (int)code);
    CHECK(memchr(err.message, 0, sizeof err.message) != NULL && err.message[0] != 0,
          "%s: empty or unterminated message", what);
    if (needle)
        CHECK(strstr(err.message, needle) != NULL, "%s: message \"%s\" lacks \"%s\"", what,
              err.message, needle);
    if (path) CHECK(!file_exists(path), "%s: %s was created", what, path);
    /* err == NULL must work too */
    if (path) remove(path);
    s = banyan_gltf_write(path, meshes, names, count, NULL);
    CHECK(s == code, "%s (err NULL): status %d, expected %d", what, (int)s, (int)code);
    if (path) CHECK(!file_exists(path), "%s (err NULL): %s was created", what, path);
    printf("ok: %-34s -> %d \"%s\"\n", what, (int)s, err.message);
}

/* COLOR_0 of every primitive of the .glb at path (mesh 0, one primitive per
 * part of m, each over its part's vertices): UNSIGNED_BYTE (5121)
 * normalized VEC4, its bytes m's colours clamped to [0, 1] and rounded
 * (c x 255 + 0.5, truncated). Returns how many primitives carried it. */
static int check_color_bytes(const char *path, const banyan_mesh *m) {
    size_t size = 0;
    unsigned char *d = read_all(path, &size);
    int found = 0;
    if (!d || size < 28) {
        CHECK(0, "%s: cannot read", path);
        free(d);
        return 0;
    }
    uint32_t jl = rd32(d + 12);
    const unsigned char *bin = d + 20 + jl + 8;
    cJSON *j = cJSON_ParseWithLength((const char *)d + 20, jl);
    CHECK(j != NULL, "%s: JSON does not parse", path);
    const cJSON *prims = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "meshes"), 0), "primitives");
    const cJSON *accs = cJSON_GetObjectItemCaseSensitive(j, "accessors");
    const cJSON *views = cJSON_GetObjectItemCaseSensitive(j, "bufferViews");
    const cJSON *prim;
    int k = 0;
    cJSON_ArrayForEach(prim, prims) {
        const cJSON *ai = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(prim, "attributes"), "COLOR_0");
        const uint32_t base = (uint32_t)k < m->part_count ? m->parts[k].vertex_offset : 0;
        k++;
        if (!cJSON_IsNumber(ai)) continue;
        found++;
        const cJSON *a = cJSON_GetArrayItem(accs, ai->valueint);
        const cJSON *ct = cJSON_GetObjectItemCaseSensitive(a, "componentType");
        const cJSON *nz = cJSON_GetObjectItemCaseSensitive(a, "normalized");
        const char *type = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(a, "type"));
        CHECK(cJSON_IsNumber(ct) && ct->valueint == 5121, "%s: COLOR_0 componentType %d, want 5121 (UNSIGNED_BYTE)",
              path, cJSON_IsNumber(ct) ? ct->valueint : -1);
        CHECK(cJSON_IsTrue(nz), "%s: COLOR_0 is not normalized", path);
        CHECK(type && strcmp(type, "VEC4") == 0, "%s: COLOR_0 type %s, want VEC4", path, type ? type : "?");
        const cJSON *cnt = cJSON_GetObjectItemCaseSensitive(a, "count");
        const cJSON *v = cJSON_GetArrayItem(views, (int)cJSON_GetNumberValue(cJSON_GetObjectItemCaseSensitive(a, "bufferView")));
        const cJSON *vo = cJSON_GetObjectItemCaseSensitive(v, "byteOffset");
        const cJSON *vl = cJSON_GetObjectItemCaseSensitive(v, "byteLength");
        uint32_t n = cJSON_IsNumber(cnt) ? (uint32_t)cnt->valueint : 0;
        size_t off = cJSON_IsNumber(vo) ? (size_t)vo->valuedouble : 0;
        CHECK(cJSON_IsNumber(vl) && (size_t)vl->valuedouble == 4 * (size_t)n, "%s: COLOR_0 view of %g bytes for %u colours",
              path, cJSON_IsNumber(vl) ? vl->valuedouble : -1.0, n);
        int wrong = 0;
        for (uint32_t i = 0; i < 4 * n && 20 + jl + 8 + off + i < size && base + i / 4 < m->vertex_count; ++i) {
            float c = m->colors[4 * (size_t)base + i];
            c = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
            wrong += bin[off + i] != (unsigned char)(c * 255.0f + 0.5f);
        }
        CHECK(wrong == 0, "%s: %d COLOR_0 bytes are not the colours rounded", path, wrong);
    }
    cJSON_Delete(j);
    free(d);
    return found;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    snprintf(g_dir, sizeof g_dir, "%s", argv[1]);
    struct stat st;
    if (stat(g_dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "test_gltf: %s is not a directory\n", g_dir);
        return 2;
    }

    banyan_mesh *a = make_mesh_a(), *b = make_mesh_b();
    if (!a || !b) {
        fprintf(stderr, "test_gltf: out of memory\n");
        return 1;
    }
    const banyan_mesh *both[2] = {a, b};
    const char *names[2] = {"strangler fig", NULL};
    banyan_error err;
    banyan_status s;

    /* ------------------------------------------------- good writes */
    memset(&err, 0, sizeof err);
    s = banyan_gltf_write(out_path("test_gltf_two.glb"), both, names, 2, &err);
    CHECK(s == BANYAN_OK, "two.glb: %d %s", (int)s, err.message);
    static const char *const two_must[] = {
        "\"generator\":\"banyan\"", "\"COLOR_0\"", "\"_ROOT_KIND\"", "\"_BIRTH_STEP\"",
        "\"TEXCOORD_0\"", "\"NORMAL\"", "\"strangler fig\"", "\"banyan_1\"", "\"bark\"",
        "\"leaf \xe8\x91\x89\"", "\"trunk\"", "\"doubleSided\":true", "\"metallicFactor\":0",
        NULL};
    if (s == BANYAN_OK) check_written("test_gltf_two.glb", 1, two_must);
    if (s == BANYAN_OK)
        CHECK(check_color_bytes(out_path("test_gltf_two.glb"), a) == 2, "two.glb: mesh A's primitives lack COLOR_0");
    if (s == BANYAN_OK) { /* zeroed materials name no texture: none is embedded, textures on or not */
        char *json = json_of(out_path("test_gltf_two.glb"), 1);
        CHECK(a->materials[0].texture == BANYAN_TEX_NONE && json && !strstr(json, "baseColorTexture") &&
                  !strstr(json, "\"images\""),
              "two.glb: a zeroed material got a texture");
        free(json);
    }

    s = banyan_gltf_write(out_path("test_gltf_two.gltf"), both, names, 2, &err);
    CHECK(s == BANYAN_OK, "two.gltf: %d %s", (int)s, err.message);
    static const char *const two_json_must[] = {
        "\"generator\": \"banyan\"", "data:application/octet-stream;base64,", "\"COLOR_0\"",
        "\"_ROOT_KIND\"", "\"banyan_1\"", NULL};
    if (s == BANYAN_OK) check_written("test_gltf_two.gltf", 0, two_json_must);

    /* upper-case extension, names == NULL */
    s = banyan_gltf_write(out_path("test_gltf_upper.GLB"), both, NULL, 2, &err);
    CHECK(s == BANYAN_OK, "upper.GLB: %d %s", (int)s, err.message);
    static const char *const upper_must[] = {"\"banyan_0\"", "\"banyan_1\"", NULL};
    if (s == BANYAN_OK) check_written("test_gltf_upper.GLB", 1, upper_must);

    /* Same input, same bytes. */
    s = banyan_gltf_write(out_path("test_gltf_again.glb"), both, names, 2, &err);
    CHECK(s == BANYAN_OK, "again.glb: %d %s", (int)s, err.message);
    {
        size_t n1 = 0, n2 = 0;
        unsigned char *d1 = read_all(out_path("test_gltf_two.glb"), &n1);
        unsigned char *d2 = read_all(out_path("test_gltf_again.glb"), &n2);
        CHECK(d1 && d2 && n1 == n2 && memcmp(d1, d2, n1) == 0,
              "writing the same meshes twice gave different bytes");
        free(d1);
        free(d2);
    }

    /* Z up -> Y up: mesh B alone; POSITION min/max are (x, z, -y). */
    const banyan_mesh *only_b[1] = {b};
    s = banyan_gltf_write(out_path("test_gltf_b.glb"), only_b, NULL, 1, &err);
    CHECK(s == BANYAN_OK, "b.glb: %d %s", (int)s, err.message);
    if (s == BANYAN_OK) {
        char *json = json_of(out_path("test_gltf_b.glb"), 1);
        double mn[3] = {0}, mx[3] = {0};
        CHECK(json && parse_vec3(json, "\"max\"", mx) && parse_vec3(json, "\"min\"", mn),
              "b.glb: no POSITION min/max");
        CHECK(mn[0] == 1 && mn[1] == 0 && mn[2] == -2, "b.glb: min = %g %g %g, expected 1 0 -2",
              mn[0], mn[1], mn[2]);
        CHECK(mx[0] == 3 && mx[1] == 5 && mx[2] == 1, "b.glb: max = %g %g %g, expected 3 5 1",
              mx[0], mx[1], mx[2]);
        CHECK(json && !strstr(json, "COLOR_0"), "b.glb: has COLOR_0 without colours");
        free(json);
    }

    /* Parts whose indices reach into another part's vertices: the primitives
     * then share whole-mesh accessors. Still valid glTF. */
    {
        banyan_mesh *c = make_mesh_a();
        if (c) {
            c->indices[12] = 0; /* leaf card triangle uses a bark vertex */
            const banyan_mesh *one[1] = {c};
            s = banyan_gltf_write(out_path("test_gltf_shared.gltf"), one, NULL, 1, &err);
            CHECK(s == BANYAN_OK, "shared.gltf: %d %s", (int)s, err.message);
            mesh_destroy(c);
        }
    }

    /* Vertex colours that repeat their part's material colour are left out
     * (glTF would square the colour); one differing vertex brings them back. */
    {
        banyan_mesh *c = make_mesh_a();
        if (c) {
            for (uint32_t p = 0; p < c->part_count; ++p)
                for (uint32_t v = c->parts[p].vertex_offset; v < c->parts[p].vertex_offset + c->parts[p].vertex_count; ++v)
                    memcpy(c->colors + 4 * v, c->materials[c->parts[p].material].base_color, 4 * sizeof(float));
            const banyan_mesh *one[1] = {c};
            s = banyan_gltf_write(out_path("test_gltf_same_colour.glb"), one, NULL, 1, &err);
            char *json = s == BANYAN_OK ? json_of(out_path("test_gltf_same_colour.glb"), 1) : NULL;
            CHECK(json && !strstr(json, "COLOR_0"), "same_colour.glb: COLOR_0 repeats the materials");
            free(json);
            c->colors[0] += 0.25f;
            c->colors[5] = 1.5f;  /* clamped to 255 */
            c->colors[6] = -0.5f; /* clamped to 0 */
            s = banyan_gltf_write(out_path("test_gltf_same_colour.glb"), one, NULL, 1, &err);
            json = s == BANYAN_OK ? json_of(out_path("test_gltf_same_colour.glb"), 1) : NULL;
            CHECK(json && strstr(json, "COLOR_0"), "same_colour.glb: differing colours left out");
            free(json);
            if (s == BANYAN_OK) check_color_bytes(out_path("test_gltf_same_colour.glb"), c);
            mesh_destroy(c);
        }
    }

    /* No parts and no materials: one primitive without material. No normals
     * or uvs either: only POSITION is written. */
    {
        banyan_mesh *d = make_mesh_b();
        if (d) {
            d->part_count = 0;
            d->material_count = 0;
            free(d->normals);
            free(d->uvs);
            d->normals = NULL;
            d->uvs = NULL;
            const banyan_mesh *one[1] = {d};
            s = banyan_gltf_write(out_path("test_gltf_bare.glb"), one, NULL, 1, &err);
            CHECK(s == BANYAN_OK, "bare.glb: %d %s", (int)s, err.message);
            mesh_destroy(d);
        }
    }

    /* ------------------------------------------------- bad input */
    const char *bad = out_path("test_gltf_bad.glb");
    expect_fail("path NULL", NULL, both, names, 2, BANYAN_E_INVALID_ARG, "path");
    expect_fail("extension .obj", out_path("test_gltf_bad.obj"), both, names, 2,
                BANYAN_E_INVALID_ARG, ".glb");
    expect_fail("no extension", out_path("test_gltf_bad"), both, names, 2,
                BANYAN_E_INVALID_ARG, ".gltf");
    expect_fail("meshes NULL", bad, NULL, names, 2, BANYAN_E_INVALID_ARG, "meshes");
    expect_fail("count 0", bad, both, names, 0, BANYAN_E_INVALID_ARG, "count");
    {
        const banyan_mesh *with_null[2] = {a, NULL};
        expect_fail("meshes[1] NULL", bad, with_null, names, 2, BANYAN_E_INVALID_ARG,
                    "meshes[1]");
    }

    uint32_t saved_u;
    saved_u = b->vertex_count;
    b->vertex_count = 0;
    expect_fail("vertex_count 0", bad, both, names, 2, BANYAN_E_INVALID_ARG,
                "meshes[1].vertex_count");
    b->vertex_count = saved_u;

    saved_u = b->index_count;
    b->index_count = 0;
    expect_fail("index_count 0", bad, both, names, 2, BANYAN_E_INVALID_ARG,
                "meshes[1].index_count");
    b->index_count = 5;
    expect_fail("index_count 5", bad, both, names, 2, BANYAN_E_INVALID_ARG, "multiple of 3");
    b->index_count = saved_u;

    saved_u = b->indices[4];
    b->indices[4] = 900;
    expect_fail("index out of range", bad, both, names, 2, BANYAN_E_RANGE,
                "meshes[1].indices[4] = 900 is out of range [0, 3]");
    b->indices[4] = 4; /* == vertex_count: one past the end */
    expect_fail("index == vertex_count", bad, both, names, 2, BANYAN_E_RANGE,
                "meshes[1].indices[4] = 4");
    b->indices[4] = saved_u;

    float saved_f = a->positions[7];
    a->positions[7] = NAN;
    expect_fail("position NaN", bad, both, names, 2, BANYAN_E_RANGE, "meshes[0].positions[7]");
    a->positions[7] = INFINITY;
    expect_fail("position inf", bad, both, names, 2, BANYAN_E_RANGE, "meshes[0].positions[7]");
    a->positions[7] = saved_f;

    saved_f = a->normals[0];
    a->normals[0] = NAN;
    expect_fail("normal NaN", bad, both, names, 2, BANYAN_E_RANGE, "meshes[0].normals[0]");
    a->normals[0] = saved_f;

    saved_f = a->attributes[1].data[2];
    a->attributes[1].data[2] = -INFINITY;
    expect_fail("attribute inf", bad, both, names, 2, BANYAN_E_RANGE, "attributes[1].data[2]");
    a->attributes[1].data[2] = saved_f;

    saved_u = a->parts[1].material;
    a->parts[1].material = 2;
    expect_fail("part material out of range", bad, both, names, 2, BANYAN_E_INVALID_ARG,
                "meshes[0].parts[1].material");
    a->parts[1].material = saved_u;

    saved_u = a->parts[1].index_count;
    a->parts[1].index_count = 9;
    expect_fail("part indices past the end", bad, both, names, 2, BANYAN_E_INVALID_ARG,
                "meshes[0].parts[1]");
    a->parts[1].index_count = saved_u;

    saved_f = a->materials[0].base_color[3];
    a->materials[0].base_color[3] = 1.5f;
    expect_fail("base_color out of [0, 1]", bad, both, names, 2, BANYAN_E_RANGE,
                "meshes[0].materials[0].base_color[3]");
    a->materials[0].base_color[3] = saved_f;

    snprintf(a->attributes[1].name, BANYAN_NAME_MAX, "Root_Kind");
    expect_fail("duplicate attribute name", bad, both, names, 2, BANYAN_E_INVALID_ARG,
                "attributes[1]");
    snprintf(a->attributes[1].name, BANYAN_NAME_MAX, "birth-step");
    expect_fail("attribute name with '-'", bad, both, names, 2, BANYAN_E_INVALID_ARG,
                "attributes[1]");
    snprintf(a->attributes[1].name, BANYAN_NAME_MAX, "birth_step");

    {
        const char *bad_names[2] = {"ok", "bad \xff utf8"};
        expect_fail("name not UTF-8", bad, both, bad_names, 2, BANYAN_E_INVALID_ARG,
                    "names[1]");
    }

    expect_fail("directory missing", out_path("no_such_dir/test_gltf.glb"), both, names, 2,
                BANYAN_E_IO, "no_such_dir");

#if defined(__linux__)
    /* A write that fails part-way (disk full) is BANYAN_E_IO and leaves
     * what was there: a .glb symlink to /dev/full stays that link. */
    if (file_exists("/dev/full")) {
        const char *full = out_path("test_gltf_full.glb");
        remove(full);
        if (symlink("/dev/full", full) == 0) {
            memset(&err, 0, sizeof err);
            s = banyan_gltf_write(full, both, names, 2, &err);
            CHECK(s == BANYAN_E_IO, "disk full: status %d, expected %d (%s)", (int)s,
                  (int)BANYAN_E_IO, err.message);
            CHECK(strstr(err.message, "test_gltf_full.glb") != NULL,
                  "disk full: message \"%s\" lacks the path", err.message);
            struct stat st;
            char to[64] = "";
            CHECK(lstat(full, &st) == 0 && S_ISLNK(st.st_mode) && readlink(full, to, sizeof to - 1) > 0 &&
                      !strcmp(to, "/dev/full"),
                  "disk full: the link %s is gone or changed", full);
            printf("ok: %-34s -> %d \"%s\"\n", "disk full", (int)s, err.message);
            remove(full);
        }
    }
#endif

    /* The good input still works after all that. */
    s = banyan_gltf_write(out_path("test_gltf_two.glb"), both, names, 2, &err);
    CHECK(s == BANYAN_OK, "two.glb again: %d %s", (int)s, err.message);

    mesh_destroy(a);
    mesh_destroy(b);
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
