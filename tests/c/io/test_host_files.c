/* Mesh hosts from files: banyan_glb_read_host reads what banyan_gltf_write
 * wrote back to the same triangles (Y up -> Z up undone exactly), applies
 * node transforms (mirrors keep outward winding), reads strips and fans,
 * and refuses bad files naming the file and the fault; the shipped host
 * meshes read as closed solids of the size tools/make_host_meshes.py
 * says; banyan_preset_host_set builds mixed box + mesh sets from presets
 * and refuses bad mesh entries naming hosts[i], leaving *out NULL. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "banyan.h"
#include "check.h"
#include "test_files.h"

static char outdir[1024];

static void path_in(char *buf, size_t n, const char *name) { snprintf(buf, n, "%s/%s", outdir, name); }

static void write_bytes(const char *path, const void *data, size_t len) {
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fwrite(data, 1, len, f);
    fclose(f);
}

/* A .glb from a JSON text and a binary chunk (padded here). */
static void write_glb(const char *name, const char *json, const void *bin, uint32_t bin_len) {
    uint32_t jl = (uint32_t)strlen(json), jp = (jl + 3) & ~3u, bp = (bin_len + 3) & ~3u;
    uint32_t total = 12 + 8 + jp + (bin ? 8 + bp : 0);
    unsigned char *b = calloc(1, total);
    if (!b) return;
    uint32_t h[5] = {0x46546C67u, 2, total, jp, 0x4E4F534Au};
    memcpy(b, h, 20);
    memset(b + 20, ' ', jp);
    memcpy(b + 20, json, jl);
    if (bin) {
        uint32_t c[2] = {bp, 0x004E4942u};
        memcpy(b + 20 + jp, c, 8);
        memcpy(b + 28 + jp, bin, bin_len);
    }
    char path[1200];
    path_in(path, sizeof path, name);
    write_bytes(path, b, total);
    free(b);
}

/* A binary chunk of 4 vertices of a tetrahedron (glTF frame) then the
 * indices of its 4 outward faces. */
typedef struct tet_bin {
    float pos[12];
    uint32_t idx[12];
} tet_bin;

static tet_bin tet(void) {
    /* In glTF's frame; outward winding there (checked by volume below). */
    tet_bin t = {{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}};
    return t;
}

#define ACCESSORS                                                                                             \
    "\"buffers\":[{\"byteLength\":96}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,"     \
    "\"byteOffset\":48,\"byteLength\":48}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4," \
    "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,1]},{\"bufferView\":1,\"componentType\":5125,\"count\":12,"  \
    "\"type\":\"SCALAR\"}]"

static double volume(const banyan_host_mesh *m) {
    double v = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const float *a = m->positions + 3 * m->indices[3 * t], *b = m->positions + 3 * m->indices[3 * t + 1],
                    *c = m->positions + 3 * m->indices[3 * t + 2];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6;
}

static void bounds(const banyan_host_mesh *m, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; k++) lo[k] = 1e300, hi[k] = -1e300;
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            double x = m->positions[3 * v + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
}

/* What banyan_gltf_write writes comes back as the same triangles. */
static void round_trip(void) {
    double pts[3 * 5], radii[5];
    for (int i = 0; i < 5; i++) {
        pts[3 * i] = 0.2 * i, pts[3 * i + 1] = 0.1 * i * i - 0.3, pts[3 * i + 2] = 0.4 * i + 0.05;
        radii[i] = 0.05 + 0.01 * i;
    }
    banyan_mesh *tube = NULL;
    banyan_error e;
    CHECK(banyan_tube_generate(pts, radii, 5, 7, 1, &tube, &e) == BANYAN_OK, "tube: %s", e.message);
    if (!tube) return;
    char path[1200];
    path_in(path, sizeof path, "host_files_tube.glb");
    CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&tube, NULL, 1, &e) == BANYAN_OK, "write: %s", e.message);
    banyan_host_mesh *m = NULL;
    double tr[12] = {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0};
    CHECK(banyan_glb_read_host(path, tr, BANYAN_HOST_CLOSED, &m, &e) == BANYAN_OK && m, "read: %s", e.message);
    if (m) {
        CHECK(m->triangle_count == tube->index_count / 3, "%u triangles read, %u written", m->triangle_count,
              tube->index_count / 3);
        CHECK(m->vertex_count < tube->vertex_count, "equal positions (the tube's seam) must merge: %u of %u",
              m->vertex_count, tube->vertex_count);
        CHECK(m->closed == BANYAN_HOST_CLOSED && m->transform[3] == 5 && m->transform[0] == 1 && m->reserved == 0,
              "closed and transform are passed through");
        uint32_t wrong = 0;
        for (uint32_t t = 0; t < m->triangle_count && t < tube->index_count / 3; t++)
            for (int c = 0; c < 3; c++) {
                const float *a = m->positions + 3 * m->indices[3 * t + c];
                const float *b = tube->positions + 3 * tube->indices[3 * t + c];
                wrong += a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
            }
        CHECK(wrong == 0, "%u triangle corners differ from the written mesh (Y-up undone exactly?)", wrong);
        /* A capped tube is a closed solid; the round trip keeps it so. */
        banyan_hosts *H = NULL;
        CHECK(banyan_hosts_create(NULL, 0, m, 1, &H, &e) == BANYAN_OK, "host set of the tube: %s", e.message);
        banyan_host_info info;
        if (H && banyan_hosts_info(H, 0, &info, &e) == BANYAN_OK)
            CHECK(info.kind == 1 && info.boundary_edges == 0 && fabs(info.lo[0] - (5 + m->positions[0])) < 1,
                  "tube host: kind %d, %u boundary edges", info.kind, info.boundary_edges);
        banyan_hosts_free(H);
    }
    banyan_host_mesh_free(m);
    banyan_mesh_free(tube);
}

/* Node transforms, the axis change, mirrors, strips and fans. */
static void transforms(void) {
    tet_bin b = tet();
    char json[2048];
    banyan_error e;
    banyan_host_mesh *m = NULL;
    char path[1200];

    /* A translation (1, 2, 3) in glTF is (1, -3, 2) in banyan; a child
     * inherits its parent's. */
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"translation\":"
             "[1,2,3],\"children\":[1]},{\"mesh\":0,\"scale\":[2,2,2]}],\"meshes\":[{\"primitives\":[{\"attributes\":"
             "{\"POSITION\":0},\"indices\":1}]}]," ACCESSORS "}");
    write_glb("host_files_node.glb", json, &b, sizeof b);
    path_in(path, sizeof path, "host_files_node.glb");
    CHECK(banyan_glb_read_host(path, NULL, BANYAN_HOST_CLOSED_AUTO, &m, &e) == BANYAN_OK && m, "node: %s", e.message);
    if (m) {
        double lo[3], hi[3];
        bounds(m, lo, hi);
        CHECK(m->triangle_count == 4 && m->vertex_count == 4, "tetrahedron: %u triangles", m->triangle_count);
        CHECK(lo[0] == 1 && hi[0] == 3 && lo[1] == -5 && hi[1] == -3 && lo[2] == 2 && hi[2] == 4,
              "node transforms + Y up -> Z up: bounds (%g %g %g) .. (%g %g %g)", lo[0], lo[1], lo[2], hi[0], hi[1],
              hi[2]);
        CHECK(volume(m) > 0, "tetrahedron wound inwards after conversion: volume %g", volume(m));
        CHECK(m->transform[0] == 1 && m->transform[5] == 1 && m->transform[10] == 1 && m->transform[3] == 0,
              "NULL transform gives identity");
    }
    banyan_host_mesh_free(m);

    /* A mirroring node: the winding is reversed so the volume stays positive. */
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":"
             "[-1,1,1]}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]," ACCESSORS "}");
    write_glb("host_files_mirror.glb", json, &b, sizeof b);
    path_in(path, sizeof path, "host_files_mirror.glb");
    m = NULL;
    CHECK(banyan_glb_read_host(path, NULL, -1, &m, &e) == BANYAN_OK && m, "mirror: %s", e.message);
    if (m) CHECK(volume(m) > 0, "a mirrored node must keep outward winding: volume %g", volume(m));
    banyan_host_mesh_free(m);

    /* A strip of 6 indices is 4 triangles; a fan of 6 is 4; no indices
     * reads the vertices in order; points are skipped. */
    float strip[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0};
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":["
             "{\"attributes\":{\"POSITION\":0},\"mode\":5},{\"attributes\":{\"POSITION\":0},\"mode\":6},"
             "{\"attributes\":{\"POSITION\":0},\"mode\":0}]}],\"buffers\":[{\"byteLength\":72}],\"bufferViews\":"
             "[{\"buffer\":0,\"byteLength\":72}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":6,"
             "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,2,0]}]}");
    write_glb("host_files_strip.glb", json, strip, sizeof strip);
    path_in(path, sizeof path, "host_files_strip.glb");
    m = NULL;
    CHECK(banyan_glb_read_host(path, NULL, 0, &m, &e) == BANYAN_OK && m, "strip + fan (no scenes): %s", e.message);
    if (m) {
        CHECK(m->triangle_count == 8 && m->vertex_count == 6, "strip + fan: %u triangles, %u vertices",
              m->triangle_count, m->vertex_count);
        /* Strip triangles all face the same way (+y in banyan: the glTF
         * quad faces +z, which becomes -y... checked by sign agreement). */
        int up = 0, down = 0;
        for (uint32_t t = 0; t < 4; t++) {
            const float *a = m->positions + 3 * m->indices[3 * t], *p = m->positions + 3 * m->indices[3 * t + 1],
                        *q = m->positions + 3 * m->indices[3 * t + 2];
            double ux = p[0] - a[0], uz = p[2] - a[2], vx = q[0] - a[0], vz = q[2] - a[2];
            double ny = uz * vx - ux * vz; /* y of (p - a) x (q - a) */
            up += ny > 0, down += ny < 0;
        }
        CHECK(up == 4 || down == 4, "strip winding alternates wrongly: %d up, %d down", up, down);
    }
    banyan_host_mesh_free(m);
}

/* Bad files: each refused with *out NULL, the file named, the fault said. */
static void bad_files(void) {
    tet_bin b = tet();
    char json[2048], path[1200];
    banyan_error e;
    struct {
        const char *name;
        banyan_status want;
        const char *needle;
    } cases[] = {
        {"host_files_missing.glb", BANYAN_E_IO, "cannot open"},
        {"host_files_text.glb", BANYAN_E_PARSE, "does not start with \"glTF\""},
        {"host_files_json.glb", BANYAN_E_PARSE, ".gltf JSON"},
        {"host_files_truncated.glb", BANYAN_E_PARSE, "(truncated?)"},
        {"host_files_bin_past.glb", BANYAN_E_PARSE, "runs past the end"},
        {"host_files_version.glb", BANYAN_E_PARSE, "version 1"},
        {"host_files_points.glb", BANYAN_E_BAD_HOST, "has no triangles"},
        {"host_files_empty_scene.glb", BANYAN_E_BAD_HOST, "has no triangles"},
        {"host_files_nan.glb", BANYAN_E_BAD_HOST, "not finite"},
        {"host_files_index.glb", BANYAN_E_BAD_HOST, "out of range"},
        {"host_files_overrun.glb", BANYAN_E_PARSE, "reaches past"},
        {"host_files_cycle.glb", BANYAN_E_PARSE, "reached twice"},
        {"host_files_draco.glb", BANYAN_E_PARSE, "KHR_draco_mesh_compression"},
        {"host_files_int_pos.glb", BANYAN_E_PARSE, "not float VEC3"},
        {"host_files_node_nan.glb", BANYAN_E_BAD_HOST, "non-finite transform"},
        {"host_files_external.glb", BANYAN_E_PARSE, "external file"},
    };
    char p[1200];
    path_in(p, sizeof p, "host_files_text.glb");
    write_bytes(p, "this is not a mesh\n", 19);
    path_in(p, sizeof p, "host_files_json.glb");
    write_bytes(p, "{\"asset\": {\"version\": \"2.0\"}}", 29);
    const char *head = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],";
    snprintf(json, sizeof json, "%s\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":0}]}],"
             ACCESSORS "}", head);
    write_glb("host_files_points.glb", json, &b, sizeof b);
    write_glb("host_files_empty_scene.glb", "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[]}]}", NULL, 0);
    tet_bin nb = b;
    nb.pos[4] = NAN;
    snprintf(json, sizeof json, "%s\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             ACCESSORS "}", head);
    write_glb("host_files_nan.glb", json, &nb, sizeof nb);
    tet_bin ib = b;
    ib.idx[7] = 4;
    write_glb("host_files_index.glb", json, &ib, sizeof ib);
    /* Truncated: the first 60 bytes of a good file. */
    {
        path_in(p, sizeof p, "host_files_good.glb");
        write_glb("host_files_good.glb", json, &b, sizeof b);
        FILE *f = fopen(p, "rb");
        unsigned char buf[60];
        size_t got = f ? fread(buf, 1, sizeof buf, f) : 0;
        if (f) fclose(f);
        path_in(p, sizeof p, "host_files_truncated.glb");
        write_bytes(p, buf, got);
        /* A BIN chunk claiming 8 bytes more than the file holds (the header
         * length fixed up to match the file), and a version-1 header. */
        path_in(p, sizeof p, "host_files_good.glb");
        f = fopen(p, "rb");
        unsigned char whole[4096];
        size_t n = f ? fread(whole, 1, sizeof whole, f) : 0;
        if (f) fclose(f);
        uint32_t jl, bl;
        memcpy(&jl, whole + 12, 4);
        memcpy(&bl, whole + 20 + jl, 4);
        bl += 8;
        memcpy(whole + 20 + jl, &bl, 4);
        path_in(p, sizeof p, "host_files_bin_past.glb");
        write_bytes(p, whole, n);
        bl -= 8;
        memcpy(whole + 20 + jl, &bl, 4);
        whole[4] = 1;
        path_in(p, sizeof p, "host_files_version.glb");
        write_bytes(p, whole, n);
        banyan_host_mesh *m = NULL;
        path_in(p, sizeof p, "host_files_good.glb");
        CHECK(banyan_glb_read_host(p, NULL, -1, &m, &e) == BANYAN_OK, "the good file: %s", e.message);
        banyan_host_mesh_free(m);
    }
    /* The indices accessor claims more than its view holds. */
    char over[2048];
    snprintf(over, sizeof over, "%s", json);
    char *cnt = strstr(over, "\"count\":12");
    if (cnt) memcpy(cnt, "\"count\":99", 10);
    write_glb("host_files_overrun.glb", over, &b, sizeof b);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[1]},"
             "{\"children\":[0]}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             ACCESSORS "}");
    write_glb("host_files_cycle.glb", json, &b, sizeof b);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
             "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"scenes\":[{\"nodes\":[0]}],\"nodes\":"
             "[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             ACCESSORS "}");
    write_glb("host_files_draco.glb", json, &b, sizeof b);
    snprintf(json, sizeof json, "%s\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             "\"buffers\":[{\"byteLength\":96}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,"
             "\"byteOffset\":48,\"byteLength\":48}],\"accessors\":[{\"bufferView\":0,\"componentType\":5125,"
             "\"count\":4,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5125,\"count\":12,"
             "\"type\":\"SCALAR\"}]}", head);
    write_glb("host_files_int_pos.glb", json, &b, sizeof b);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"scale\":[1e200,1,1],"
             "\"children\":[1]},{\"mesh\":0,\"scale\":[1e200,1,1]}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             ACCESSORS "}");
    write_glb("host_files_node_nan.glb", json, &b, sizeof b);
    /* A buffer in another file (here the good .glb itself): not opened. */
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":"
             "[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],\"buffers\":[{\"byteLength\":96,"
             "\"uri\":\"host_files_good.glb\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,"
             "\"byteOffset\":48,\"byteLength\":48}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,"
             "\"count\":4,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5125,\"count\":12,"
             "\"type\":\"SCALAR\"}]}");
    write_glb("host_files_external.glb", json, NULL, 0);

    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        path_in(path, sizeof path, cases[i].name);
        banyan_host_mesh *m = (banyan_host_mesh *)&e; /* must be reset to NULL */
        memset(&e, 0, sizeof e);
        banyan_status s = banyan_glb_read_host(path, NULL, -1, &m, &e);
        CHECK(s == cases[i].want && m == NULL && strstr(e.message, cases[i].name) && strstr(e.message, cases[i].needle),
              "%s: got %s '%s', want %s '%s'", cases[i].name, banyan_status_name(s), e.message,
              banyan_status_name(cases[i].want), cases[i].needle);
        if (s == BANYAN_OK) banyan_host_mesh_free(m);
    }
    /* Arguments. */
    banyan_host_mesh *m = NULL;
    double bad[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, NAN};
    path_in(path, sizeof path, "host_files_good.glb");
    CHECK(banyan_glb_read_host(path, bad, -1, &m, &e) == BANYAN_E_RANGE && !m && strstr(e.message, "transform[11]"),
          "NaN transform: %s", e.message);
    CHECK(banyan_glb_read_host(path, NULL, 2, &m, &e) == BANYAN_E_RANGE && !m && strstr(e.message, "closed = 2"),
          "closed 2: %s", e.message);
    CHECK(banyan_glb_read_host(NULL, NULL, -1, &m, &e) == BANYAN_E_INVALID_ARG && !m, "NULL path");
    CHECK(banyan_glb_read_host(path, NULL, -1, NULL, &e) == BANYAN_E_INVALID_ARG, "NULL out");
    CHECK(banyan_glb_read_host(outdir, NULL, -1, &m, &e) == BANYAN_E_IO && !m && strstr(e.message, "regular file"),
          "a directory: %s", e.message);
    CHECK(banyan_glb_read_host("/dev/zero", NULL, -1, &m, &e) == BANYAN_E_IO && !m, "a device: %s", e.message);
    banyan_host_mesh_free(NULL);
}

/* The shipped host meshes: closed solids of the advertised size. */
static void shipped(void) {
    struct {
        const char *name;
        uint32_t triangles;
        double zlo, zhi, rmax;
    } want[] = {{"column", 3456, 0, 3.5, 0.48}, {"statue", 6400, 0, 2.28, 0.61}, {"rock", 5120, -0.1, 1.45, 2.0}};
    for (size_t i = 0; i < 3; i++) {
        char path[1200];
        snprintf(path, sizeof path, "%s/presets/hosts/%s.glb", BANYAN_SOURCE_DIR, want[i].name);
        banyan_host_mesh *m = NULL;
        banyan_error e;
        CHECK(banyan_glb_read_host(path, NULL, -1, &m, &e) == BANYAN_OK && m, "%s: %s", want[i].name, e.message);
        if (!m) continue;
        double lo[3], hi[3];
        bounds(m, lo, hi);
        CHECK(m->triangle_count == want[i].triangles, "%s: %u triangles", want[i].name, m->triangle_count);
        CHECK(fabs(lo[2] - want[i].zlo) < 1e-3 && hi[2] <= want[i].zhi && hi[2] > 0.9 * want[i].zhi,
              "%s: z %g .. %g (Z up?)", want[i].name, lo[2], hi[2]);
        CHECK(fabs(lo[0]) <= want[i].rmax && hi[0] <= want[i].rmax && fabs(lo[1]) <= want[i].rmax &&
                  hi[1] <= want[i].rmax, "%s: footprint (%g %g) .. (%g %g)", want[i].name, lo[0], lo[1], hi[0], hi[1]);
        CHECK(volume(m) > 0, "%s: wound inwards", want[i].name);
        banyan_hosts *H = NULL;
        CHECK(banyan_hosts_create(NULL, 0, m, 1, &H, &e) == BANYAN_OK, "%s: %s", want[i].name, e.message);
        banyan_host_info info;
        if (H && banyan_hosts_info(H, 0, &info, &e) == BANYAN_OK)
            CHECK(info.closed == 1 && info.boundary_edges == 0 && info.shells == 1 && info.dropped_triangles == 0,
                  "%s: closed %d, %u boundary edges, %u shells, %u dropped", want[i].name, info.closed,
                  info.boundary_edges, info.shells, info.dropped_triangles);
        /* Inside at the middle of the body, outside above it. */
        double mid[3] = {0, 0, 0.5 * (lo[2] + hi[2])}, above[3] = {0, 0, hi[2] + 0.1};
        if (H) CHECK(banyan_hosts_inside(H, mid) == 1 && banyan_hosts_inside(H, above) == 0, "%s: inside test",
                     want[i].name);
        banyan_hosts_free(H);
        banyan_host_mesh_free(m);
    }
}

static banyan_status host_set(const char *text, const char *base, const banyan_host_mesh *extra, uint32_t n_extra,
                              banyan_hosts **H, banyan_error *e) {
    *H = (banyan_hosts *)e; /* must be reset */
    return banyan_preset_host_set(text, strlen(text), "t.json", base, extra, n_extra, H, e);
}

static void presets(void) {
    char base[1200];
    snprintf(base, sizeof base, "%s/presets", BANYAN_SOURCE_DIR);
    banyan_hosts *H = NULL;
    banyan_error e;
    banyan_host_info info;

    /* A box and a placed mesh: boxes first, the mesh where it was put. */
    const char *mixed = "{\n \"generator\": \"roots\",\n \"hosts\": [\n"
                        "  {\"mesh\": \"hosts/column.glb\", \"translation\": [10, 0, 0], \"scale\": 2,\n"
                        "   \"rotation_euler_deg\": [0, 0, 90], \"closed\": \"closed\", \"name\": \"col\"},\n"
                        "  {\"center\": [0, 0, 1], \"half\": [1, 1, 1]}\n ]\n}\n";
    CHECK(host_set(mixed, base, NULL, 0, &H, &e) == BANYAN_OK && H, "mixed: %s", e.message);
    if (H) {
        CHECK(banyan_hosts_count(H) == 2, "mixed: %u hosts", banyan_hosts_count(H));
        CHECK(banyan_hosts_info(H, 0, &info, &e) == BANYAN_OK && info.kind == 0, "host 0 must be the box");
        CHECK(banyan_hosts_info(H, 1, &info, &e) == BANYAN_OK && info.kind == 1 && info.closed == 1 &&
                  info.triangle_count == 3456,
              "host 1 must be the column: kind %d, %u triangles", info.kind, info.triangle_count);
        CHECK(fabs(info.lo[2]) < 1e-6 && fabs(info.hi[2] - 7) < 1e-3 && info.lo[0] > 9 && info.hi[0] < 11,
              "column scaled 2 at x = 10: (%g %g %g) .. (%g %g %g)", info.lo[0], info.lo[1], info.lo[2], info.hi[0],
              info.hi[1], info.hi[2]);
        banyan_hosts_free(H);
    }

    /* Extra meshes come after the preset's. */
    char path[1300];
    snprintf(path, sizeof path, "%s/hosts/rock.glb", base);
    banyan_host_mesh *rock = NULL;
    CHECK(banyan_glb_read_host(path, NULL, -1, &rock, &e) == BANYAN_OK, "rock: %s", e.message);
    if (rock) {
        CHECK(host_set(mixed, base, rock, 1, &H, &e) == BANYAN_OK && H && banyan_hosts_count(H) == 3,
              "mixed + rock: %s", e.message);
        if (H && banyan_hosts_info(H, 2, &info, &e) == BANYAN_OK)
            CHECK(info.kind == 1 && info.triangle_count == 5120, "host 2 must be the extra rock");
        banyan_hosts_free(H);
        /* A preset without hosts plus an extra mesh is that mesh. */
        CHECK(host_set("{\"generator\": \"ivy\"}", NULL, rock, 1, &H, &e) == BANYAN_OK && H &&
                  banyan_hosts_count(H) == 1, "extra only: %s", e.message);
        banyan_hosts_free(H);
    }

    /* Box-only presets build box-only sets; banyan_preset_hosts still reads them. */
    const char *boxes = "{\"hosts\": [{\"center\": [0, 0, 1], \"half\": [1, 1, 1]}]}";
    CHECK(host_set(boxes, NULL, NULL, 0, &H, &e) == BANYAN_OK && H && banyan_hosts_count(H) == 1,
          "boxes: %s", e.message);
    banyan_hosts_free(H);
    banyan_box bx[4];
    uint32_t n = 9;
    CHECK(banyan_preset_hosts(mixed, strlen(mixed), "t.json", bx, 4, &n, &e) == BANYAN_E_UNSUPPORTED && n == 0 &&
              strstr(e.message, "hosts[0] is a mesh") && strstr(e.message, "roots, ivy") &&
              !strstr(e.message, "banyan_"), /* says what to do, in the user's terms */
          "banyan_preset_hosts on a mesh preset: %s", e.message);
    CHECK(host_set("{\"hosts\": []}", NULL, NULL, 0, &H, &e) == BANYAN_E_NO_HOSTS && H == NULL, "no hosts: %s",
          e.message);
    CHECK(host_set("{\"generator\": \"roots\"}", NULL, NULL, 0, &H, &e) == BANYAN_E_NO_HOSTS && H == NULL,
          "no hosts key: %s", e.message);
    CHECK(banyan_preset_host_set(boxes, strlen(boxes), "t.json", NULL, NULL, 1, &H, &e) == BANYAN_E_INVALID_ARG &&
              H == NULL, "extra NULL, n_extra 1");
    CHECK(banyan_preset_host_set(boxes, strlen(boxes), "t.json", NULL, NULL, 0, NULL, &e) == BANYAN_E_INVALID_ARG,
          "out NULL");

    /* Bad mesh entries: refused naming hosts[i] and the fault. */
    char bad_dir[1200];
    snprintf(bad_dir, sizeof bad_dir, "%s", outdir);
    struct {
        const char *entry;
        banyan_status want;
        const char *needle;
    } cases[] = {
        {"{\"mesh\": \"nope.glb\"}", BANYAN_E_IO, "cannot open"},
        {"{\"mesh\": \"host_files_text.glb\"}", BANYAN_E_PARSE, "not a glTF binary"},
        {"{\"mesh\": \"host_files_points.glb\"}", BANYAN_E_BAD_HOST, "has no triangles"},
        {"{\"mesh\": \"host_files_nan.glb\"}", BANYAN_E_BAD_HOST, "not finite"},
        {"{\"mesh\": \"host_files_good.glb\", \"translation\": [1e999, 0, 0]}", BANYAN_E_BAD_HOST, "translation[0]"},
        {"{\"mesh\": \"host_files_good.glb\", \"translation\": [999999.5, 0, 0]}", BANYAN_E_BAD_HOST,
         "outside [-1e6, 1e6]"},
        {"{\"mesh\": \"host_files_good.glb\", \"scale\": 0}", BANYAN_E_BAD_HOST, "scale[0]"},
        {"{\"mesh\": \"host_files_good.glb\", \"scale\": [1, 2]}", BANYAN_E_TYPE, "scale"},
        {"{\"mesh\": \"host_files_good.glb\", \"rotation\": [2,0,0, 0,1,0, 0,0,1]}", BANYAN_E_BAD_HOST,
         "in \"scale\""}, /* a mesh host's scale goes in "scale", not "half" */
        {"{\"mesh\": \"host_files_good.glb\", \"rotation_euler_deg\": [0, 1e999, 0]}", BANYAN_E_BAD_HOST,
         "rotation_euler_deg[1]"},
        {"{\"mesh\": \"host_files_good.glb\", \"colour\": 1}", BANYAN_E_TYPE, ".colour is unknown"},
        {"{\"mesh\": \"host_files_good.glb\", \"half\": [1, 1, 1]}", BANYAN_E_UNKNOWN_KEY, ".half is unknown"},
        {"{\"mesh\": \"host_files_good.glb\", \"closed\": \"maybe\"}", BANYAN_E_RANGE, "\"auto\", \"open\""},
        {"{\"mesh\": \"host_files_good.glb\", \"center\": [0,0,0], \"translation\": [0,0,0]}", BANYAN_E_PARSE,
         "one of translation and center"},
        {"{\"mesh\": \"host_files_good.glb\", \"rotation_euler_deg\": [0,0,0], \"rotation\": [1,0,0,0,1,0,0,0,1]}",
         BANYAN_E_PARSE, "one of rotation and rotation_euler_deg"},
        {"{\"mesh\": \"\"}", BANYAN_E_TYPE, "must name a .glb file"},
        {"{\"mesh\": 3}", BANYAN_E_TYPE, "must name a .glb file"},
        {"{\"center\": [0, 0, 1], \"half\": [1, 1, 1], \"scale\": 2}", BANYAN_E_TYPE, ".scale is unknown"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text, "{\n \"hosts\": [\n  {\"center\": [0, 0, 1], \"half\": [1, 1, 1]},\n  %s\n ]\n}\n",
                 cases[i].entry);
        banyan_status s = host_set(text, bad_dir, NULL, 0, &H, &e);
        CHECK(s == cases[i].want && H == NULL && strstr(e.message, "t.json:") && strstr(e.message, "hosts[1]") &&
                  strstr(e.message, cases[i].needle),
              "entry %zu %s: got %s '%s', want %s '%s'", i, cases[i].entry, banyan_status_name(s), e.message,
              banyan_status_name(cases[i].want), cases[i].needle);
        if (s == BANYAN_OK) banyan_hosts_free(H);
    }
    /* The line of the mesh entry is named. */
    const char *lined = "{\n \"hosts\": [\n  {\"half\": [1, 1, 1]},\n\n  {\"mesh\": \"nope.glb\"}\n ]\n}\n";
    CHECK(host_set(lined, bad_dir, NULL, 0, &H, &e) == BANYAN_E_IO && strstr(e.message, "t.json:5: hosts[1]"),
          "line of the mesh entry: %s", e.message);
    banyan_host_mesh_free(rock);
}

/* Every shipped preset with a mesh host: its params apply, its host set
 * builds with its meshes, and the box-preset walker leaves it out. */
static void mesh_preset(const char *path, const char *name, void *ctx) {
    int *meshes = ctx;
    banyan_error e;
    banyan_hosts *H = NULL;
    CHECK(test_load_host_set(path, &H, &e) == BANYAN_OK && H, "%s: %s", name, e.message);
    uint32_t n_mesh = 0;
    for (uint32_t i = 0; H && i < banyan_hosts_count(H); i++) {
        banyan_host_info info;
        if (banyan_hosts_info(H, i, &info, &e) == BANYAN_OK && info.kind == 1) {
            n_mesh++;
            CHECK(info.closed == 1 && info.boundary_edges == 0, "%s: host %u is not a closed solid", name, i);
        }
    }
    CHECK(n_mesh >= 1, "%s: no mesh host", name);
    *meshes += n_mesh > 0;
    banyan_hosts_free(H);
    unsigned char params[8192];
    banyan_generator g = strncmp(name, "ivy_", 4) == 0 ? BANYAN_GEN_IVY : BANYAN_GEN_ROOTS;
    if (g == BANYAN_GEN_IVY) banyan_ivy_params_init((banyan_ivy_params *)params);
    else banyan_roots_params_init((banyan_roots_params *)params);
    size_t len;
    char *text = test_read_file(path, &len);
    CHECK(text && banyan_preset_apply(g, params, text, len, path, &e) == BANYAN_OK, "%s params: %s", name,
          text ? e.message : "unreadable");
    free(text);
}

static void box_preset(const char *path, const char *name, void *ctx) {
    (void)name;
    (*(int *)ctx)++;
    CHECK(!test_preset_has_mesh_hosts(path), "%s: the box walker reached a mesh preset", path);
}

static void shipped_presets(void) {
    int with_meshes = 0, boxes = 0;
    int n = test_each_mesh_preset(BANYAN_SOURCE_DIR "/presets", "", mesh_preset, &with_meshes);
    CHECK(n >= 3 && with_meshes == n, "%d mesh presets, %d with a mesh host (want roots_column, roots_rock, "
          "ivy_statue)", n, with_meshes);
    int nb = test_each_preset(BANYAN_SOURCE_DIR "/presets", "", box_preset, &boxes);
    CHECK(nb >= 20 && nb == boxes, "%d box presets walked", nb);
}

/* banyan_preset_meshes: the mixed preset's one mesh entry, its transform
 * (x = 10 + Rz(90) * 2p: (1, 0, 0) -> (10, 2, 0)), name, path and closed
 * mode; a nameless entry is named for its file; a box-only preset has
 * none; refusals name hosts[i], count and cap. */
static void preset_meshes(void) {
    banyan_preset_mesh m[2];
    uint32_t n = 99;
    banyan_error e;
    const char *mixed = "{\"generator\": \"roots\", \"hosts\": [{\"center\": [0, 0, 1], \"half\": [1, 1, 1]},\n"
                        " {\"mesh\": \"hosts/column.glb\", \"translation\": [10, 0, 0], \"scale\": 2,\n"
                        "  \"rotation_euler_deg\": [0, 0, 90], \"closed\": \"closed\", \"name\": \"col\"},\n"
                        " {\"mesh\": \"/abs/rock.v2.glb\"}]}";
    CHECK(banyan_sizeof_preset_mesh() == sizeof(banyan_preset_mesh), "sizeof");
    CHECK(banyan_preset_meshes(mixed, strlen(mixed), "mixed", "base", m, 2, &n, &e) == BANYAN_OK && n == 2,
          "mixed: %u entries, %s", n, e.message);
    if (n == 2) {
        const double *t = m[0].transform, p[3] = {1, 0, 0};
        double x[3];
        for (int r = 0; r < 3; r++) x[r] = t[4 * r] * p[0] + t[4 * r + 1] * p[1] + t[4 * r + 2] * p[2] + t[4 * r + 3];
        CHECK(fabs(x[0] - 10) < 1e-12 && fabs(x[1] - 2) < 1e-12 && fabs(x[2]) < 1e-12, "(1, 0, 0) -> (%g, %g, %g)",
              x[0], x[1], x[2]);
        CHECK(m[0].index == 1 && m[0].closed == 1 && !strcmp(m[0].name, "col") && !strcmp(m[0].path, "base/hosts/column.glb"),
              "entry 0: index %u, closed %d, name '%s', path '%s'", m[0].index, m[0].closed, m[0].name, m[0].path);
        CHECK(m[1].index == 2 && m[1].closed == -1 && !strcmp(m[1].name, "rock.v2") && !strcmp(m[1].path, "/abs/rock.v2.glb"),
              "entry 1: index %u, closed %d, name '%s', path '%s'", m[1].index, m[1].closed, m[1].name, m[1].path);
    }
    CHECK(banyan_preset_meshes(mixed, strlen(mixed), "mixed", NULL, m, 1, &n, &e) == BANYAN_E_RANGE && n == 0 &&
              strstr(e.message, "cap = 1"),
          "cap 1: %s", e.message);
    CHECK(banyan_preset_meshes(mixed, strlen(mixed), "mixed", NULL, NULL, 0, NULL, &e) == BANYAN_E_INVALID_ARG &&
              strstr(e.message, "count"),
          "count NULL: %s", e.message);
    const char *boxes = "{\"hosts\": [{\"center\": [0, 0, 1], \"half\": [1, 1, 1]}]}";
    CHECK(banyan_preset_meshes(boxes, strlen(boxes), "boxes", NULL, NULL, 0, &n, &e) == BANYAN_OK && n == 0,
          "boxes: %u, %s", n, e.message);
    const char *bad = "{\"hosts\": [{\"center\": [0, 0, 1], \"half\": [1, 1, 1]}, {\"mesh\": \"a.glb\", \"scale\": 0}]}";
    CHECK(banyan_preset_meshes(bad, strlen(bad), "bad", NULL, m, 2, &n, &e) == BANYAN_E_BAD_HOST &&
              strstr(e.message, "hosts[1].scale"),
          "scale 0: %s", e.message);
}

int main(int argc, char **argv) {
    /* A folder of its own: the validator checks every .glb directly in argv[1]. */
    snprintf(outdir, sizeof outdir, "%s/host_files", argc > 1 ? argv[1] : ".");
    mkdir(outdir, 0777);
    round_trip();
    transforms();
    bad_files();
    shipped();
    presets();
    preset_meshes();
    shipped_presets();
    return check_done("test_host_files");
}
