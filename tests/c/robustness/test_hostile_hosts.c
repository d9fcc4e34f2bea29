/* Hostile host files and presets: crafted .glb files (offsets near 2^64,
 * invalid primitive modes, 2 GB files that are not glTF or whose header is
 * valid, nodes instancing one mesh, primitives sharing one accessor, many
 * preset entries naming one file) are refused with a clear status and
 * message, quickly and in little memory, and reads inside a budget stop
 * at it; messages keep their cause under a long prefix, name preset
 * entries rather than internal numbers, and escape control characters.
 * Big files are sparse (ftruncate): small on disk, fast to make. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "banyan.h"
#include "check.h"

/* A budget of s seconds and mb megabytes, for the _budget calls. */
#define budget(s, mb) (&(banyan_budget){(s), (mb)})

static char outdir[1024];

static const char *path_in(const char *name) {
    static char buf[4][1200];
    static int slot;
    char *p = buf[slot++ & 3];
    snprintf(p, sizeof buf[0], "%s/%s", outdir, name);
    return p;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A .glb of `json` and a BIN chunk of bin_len bytes: `bin` (bin_len bytes)
 * or, when NULL, zeros left as a hole in the file (sparse). */
static void write_glb(const char *name, const char *json, const void *bin, uint64_t bin_len) {
    uint32_t jl = (uint32_t)strlen(json), jp = (jl + 3) & ~3u;
    uint64_t bp = (bin_len + 3) & ~(uint64_t)3;
    uint64_t total = 20 + (uint64_t)jp + (bin_len ? 8 + bp : 0);
    int fd = open(path_in(name), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) return;
    uint32_t h[5] = {0x46546C67u, 2, (uint32_t)total, jp, 0x4E4F534Au};
    char *j = malloc(jp);
    memset(j, ' ', jp);
    memcpy(j, json, jl);
    int ok = write(fd, h, 20) == 20 && write(fd, j, jp) == (ssize_t)jp;
    if (bin_len) {
        uint32_t c[2] = {(uint32_t)bp, 0x004E4942u};
        ok = ok && write(fd, c, 8) == 8;
        if (bin) ok = ok && write(fd, bin, (size_t)bin_len) == (ssize_t)bin_len;
    }
    ok = ok && ftruncate(fd, (off_t)total) == 0;
    if (!ok) fprintf(stderr, "cannot write %s\n", name);
    free(j);
    close(fd);
}

/* One tetrahedron: 4 float positions then 12 uint32 indices. */
static const float tet_pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const uint32_t tet_idx[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

static void write_tet_count(const char *name, const char *prim_extra, const char *acc0_extra, const char *count0) {
    unsigned char bin[96];
    memcpy(bin, tet_pos, 48);
    memcpy(bin + 48, tet_idx, 48);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1%s}]}],"
             "\"buffers\":[{\"byteLength\":96}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48}],\"accessors\":[{\"bufferView\":0,"
             "\"componentType\":5126,\"count\":%s,\"type\":\"VEC3\"%s},{\"bufferView\":1,\"componentType\":5125,"
             "\"count\":12,\"type\":\"SCALAR\"}]}",
             prim_extra, count0, acc0_extra);
    write_glb(name, json, bin, sizeof bin);
}

static void write_tet(const char *name, const char *prim_extra, const char *acc0_extra) {
    write_tet_count(name, prim_extra, acc0_extra, "4");
}

/* Reads path with the plain call (600 s, 8192 MB); checks the status, a
 * message with the file's name and `needle`, *out NULL, and the time. */
static void refused(const char *name, banyan_status want, const char *needle, double max_s) {
    banyan_host_mesh *m = (banyan_host_mesh *)&m; /* must come back NULL */
    banyan_error e = {0, ""};
    double t0 = now();
    banyan_status s = banyan_glb_read_host(path_in(name), NULL, -1, &m, &e);
    double dt = now() - t0;
    CHECK(s == want && m == NULL && strstr(e.message, name) && strstr(e.message, needle) && dt < max_s,
          "%s: got %s '%s' in %.2f s, want %s '%s' within %.1f s", name, banyan_status_name(s), e.message, dt,
          banyan_status_name(want), needle, max_s);
    CHECK(!strstr(e.message, "vector") && !strstr(e.message, "_M_") && !strstr(e.message, "std::"),
          "%s: internal text in '%s'", name, e.message);
    if (s == BANYAN_OK) banyan_host_mesh_free(m);
}

/* Accessor offsets near 2^64: the end of the accessor must not wrap back
 * into the buffer (a read before it: SIGSEGV, or heap metadata read as a
 * vertex). */
static void wrapping_offsets(void) {
    /* 2^64 - 64 MiB plus 5592406 vertices of 12 bytes ends at byte 8. */
    write_tet_count("wrap_64mib.glb", "", ",\"byteOffset\":18446744073642442752", "5592406");
    write_tet("wrap_8.glb", "", ",\"byteOffset\":18446744073709551608");    /* 2^64 - 8 */
    refused("wrap_64mib.glb", BANYAN_E_PARSE, "reaches past", 1);
    refused("wrap_8.glb", BANYAN_E_PARSE, "reaches past", 1);
    /* A count whose stride product wraps: 2^62 elements of 12 bytes. */
    {
        unsigned char bin[96];
        memcpy(bin, tet_pos, 48);
        memcpy(bin + 48, tet_idx, 48);
        write_glb("wrap_count.glb",
                  "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                  "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
                  "\"buffers\":[{\"byteLength\":96}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},"
                  "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48,\"byteStride\":4}],\"accessors\":[{\"bufferView\":0,"
                  "\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5125,"
                  "\"count\":4611686018427387905,\"type\":\"SCALAR\"}]}",
                  bin, sizeof bin);
    }
    refused("wrap_count.glb", BANYAN_E_LIMIT, "triangles", 1);
    /* The good file still reads. */
    write_tet("good.glb", "", "");
    banyan_host_mesh *m = NULL;
    banyan_error e = {0, ""};
    CHECK(banyan_glb_read_host(path_in("good.glb"), NULL, -1, &m, &e) == BANYAN_OK && m && m->triangle_count == 4,
          "good.glb: %s", e.message);
    banyan_host_mesh_free(m);
}

/* glTF's modes are 0 .. 6: anything else is refused, not read as triangles. */
static void modes(void) {
    write_tet("mode_minus5.glb", ",\"mode\":-5", "");
    write_tet("mode_7.glb", ",\"mode\":7", "");
    refused("mode_minus5.glb", BANYAN_E_PARSE, "mode = -5", 1);
    refused("mode_7.glb", BANYAN_E_PARSE, "strips (5) and fans (6)", 1);
}

/* 2 GB files: refused from the header and the JSON, not read whole. */
static void big_files(void) {
    const uint64_t two_gb = 2000000000u;
    int fd = open(path_in("not_gltf_2gb.glb"), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        CHECK(write(fd, "PK\003\004 not a glTF file", 21) == 21 && ftruncate(fd, (off_t)two_gb) == 0, "write");
        close(fd);
    }
    refused("not_gltf_2gb.glb", BANYAN_E_PARSE, "does not start with \"glTF\"", 0.5);
    /* A valid header and JSON over 2 GB: 50 M triangles of byte indices. */
    char json[1024];
    uint64_t bin = two_gb - 20 - 8 - 512;
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             "\"buffers\":[{\"byteLength\":%llu}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":12000000},"
             "{\"buffer\":0,\"byteOffset\":12000000,\"byteLength\":150000000}],\"accessors\":[{\"bufferView\":0,"
             "\"componentType\":5126,\"count\":1000000,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5121,"
             "\"count\":150000000,\"type\":\"SCALAR\"}]}",
             (unsigned long long)bin);
    char padded[1100];
    snprintf(padded, sizeof padded, "%-512s", json);
    write_glb("valid_header_2gb.glb", padded, NULL, bin);
    refused("valid_header_2gb.glb", BANYAN_E_LIMIT, "33554432", 0.5);
    /* The header's length disagrees with the file: refused from 28 bytes. */
    if (truncate(path_in("valid_header_2gb.glb"), (off_t)(two_gb - 4)) == 0)
        refused("valid_header_2gb.glb", BANYAN_E_PARSE, "(truncated?)", 0.5);
    /* A JSON chunk over 64 MB is refused from its length (here a hole). */
    fd = open(path_in("json_65mb.glb"), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        uint32_t h[5] = {0x46546C67u, 2, 20 + (65u << 20), 65u << 20, 0x4E4F534Au};
        CHECK(write(fd, h, 20) == 20 && ftruncate(fd, 20 + (65 << 20)) == 0, "write");
        close(fd);
    }
    refused("json_65mb.glb", BANYAN_E_LIMIT, "JSON chunk has 68157440 bytes", 0.5);
    unlink(path_in("json_65mb.glb"));
    /* A 16 MB JSON of small numbers: its parse alone would pass 64 MB. */
    size_t jn = (size_t)16 << 20;
    char *big = malloc(jn + 1);
    if (big) {
        const char *head = "{\"asset\":{\"version\":\"2.0\",\"extras\":[0";
        size_t hl = strlen(head);
        memcpy(big, head, hl);
        for (size_t i = hl; i + 4 < jn; i += 2) memcpy(big + i, ",0", 2);
        memcpy(big + jn - 4 - (jn - hl) % 2, "]}} ", 4);
        big[jn - (jn - hl) % 2] = '\0';
        write_glb("json_16mb.glb", big, NULL, 0);
        free(big);
        banyan_host_mesh *m = NULL;
        banyan_error e = {0, ""};
        double t0 = now();
        banyan_status s = banyan_glb_read_host_budget(path_in("json_16mb.glb"), NULL, -1, budget(10, 64), &m, &e);
        double dt = now() - t0;
        CHECK(s == BANYAN_E_LIMIT && !m && strstr(e.message, "reading the JSON of") &&
                  strstr(e.message, "max_memory_mb = 64") && dt < 0.5,
              "16 MB JSON in 64 MB: %s '%s' in %.2f s", banyan_status_name(s), e.message, dt);
        unlink(path_in("json_16mb.glb"));
    }
    unlink(path_in("not_gltf_2gb.glb"));
    unlink(path_in("valid_header_2gb.glb"));
}

/* A mesh of nv non-indexed vertices (zeros, sparse) instanced by n_nodes
 * root nodes. */
static void write_instanced(const char *name, int n_nodes, uint32_t nv) {
    size_t cap = 400 + 40 * (size_t)n_nodes;
    char *json = malloc(cap);
    size_t len = (size_t)snprintf(json, cap, "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[");
    for (int i = 0; i < n_nodes; i++) len += (size_t)snprintf(json + len, cap - len, "%s%d", i ? "," : "", i);
    len += (size_t)snprintf(json + len, cap - len, "]}],\"nodes\":[");
    for (int i = 0; i < n_nodes; i++)
        len += (size_t)snprintf(json + len, cap - len, "%s{\"mesh\":0,\"translation\":[%d,0,0]}", i ? "," : "", i);
    snprintf(json + len, cap - len,
             "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],\"buffers\":[{\"byteLength\":%u}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%u}],\"accessors\":[{\"bufferView\":0,"
             "\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\"}]}",
             12 * nv, 12 * nv, nv);
    write_glb(name, json, NULL, 12 * (uint64_t)nv);
    free(json);
}

/* The work of instancing and of shared accessors is counted before it is
 * done: over the limits it is refused up front, within them the budget
 * refuses or stops it. */
static void counted_work(void) {
    write_instanced("inst_2000.glb", 2000, 99999); /* 200 M vertex reads */
    refused("inst_2000.glb", BANYAN_E_LIMIT, "each node's instance", 0.5);
    /* 5,000 primitives sharing one 200k-vertex accessor, one triangle each. */
    size_t cap = 600 + 48 * 5000;
    char *json = malloc(cap);
    size_t len = (size_t)snprintf(json, cap, "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],"
                                             "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[");
    for (int i = 0; i < 5000; i++)
        len += (size_t)snprintf(json + len, cap - len, "%s{\"attributes\":{\"POSITION\":0},\"indices\":1}", i ? "," : "");
    snprintf(json + len, cap - len,
             "]}],\"buffers\":[{\"byteLength\":2400012}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":2400000},"
             "{\"buffer\":0,\"byteOffset\":2400000,\"byteLength\":12}],\"accessors\":[{\"bufferView\":0,"
             "\"componentType\":5126,\"count\":200000,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5125,"
             "\"count\":3,\"type\":\"SCALAR\"}]}");
    write_glb("shared_5000.glb", json, NULL, 2400012);
    free(json);
    refused("shared_5000.glb", BANYAN_E_LIMIT, "vertices to read", 0.5);

    /* 100 nodes x 100k vertices: 10 M reads, over 64 MB by its estimate. */
    write_instanced("inst_100.glb", 100, 99999);
    banyan_host_mesh *m = NULL;
    banyan_error e = {0, ""};
    double t0 = now();
    banyan_status s = banyan_glb_read_host_budget(path_in("inst_100.glb"), NULL, -1, budget(2, 64), &m, &e);
    double dt = now() - t0;
    CHECK(s == BANYAN_E_LIMIT && !m && strstr(e.message, "max_memory_mb = 64") && strstr(e.message, "inst_100.glb") &&
              dt < 0.5,
          "inst_100 in 2 s / 64 MB: %s '%s' in %.2f s", banyan_status_name(s), e.message, dt);
    /* Within the memory budget but not the time: stopped while it reads. */
    write_instanced("inst_20.glb", 20, 99999);
    t0 = now();
    s = banyan_glb_read_host_budget(path_in("inst_20.glb"), NULL, -1, budget(0.01, 4096), &m, &e);
    dt = now() - t0;
    CHECK(s == BANYAN_E_LIMIT && !m && strstr(e.message, "max_seconds = 0.01") && dt < 0.5,
          "inst_20 in 0.01 s: %s '%s' in %.2f s", banyan_status_name(s), e.message, dt);
    /* The budget's own range is checked, naming it. */
    s = banyan_glb_read_host_budget(path_in("good.glb"), NULL, -1, budget(0, 64), &m, &e);
    CHECK(s == BANYAN_E_RANGE && !m && strstr(e.message, "max_seconds"), "max_seconds 0: %s", e.message);
    s = banyan_glb_read_host_budget(path_in("good.glb"), NULL, -1, budget(10, 64), &m, &e);
    CHECK(s == BANYAN_OK && m && m->triangle_count == 4, "good.glb within a budget: %s", e.message);
    banyan_host_mesh_free(m);
}

static banyan_status preset_set(const char *text, const char *source, double max_s, double max_mb, banyan_hosts **H,
                                banyan_error *e) {
    return banyan_preset_host_set_budget(text, strlen(text), source, outdir, NULL, 0, budget(max_s, max_mb), H, e);
}

/* Many entries naming one 1 M-triangle file: the set-wide limit holds
 * before the files are read; a preset's host set keeps its budget. */
static void presets(void) {
    /* 1 M triangles of byte indices on 3 vertices (a sparse 3 MB file). */
    write_glb("one_m.glb",
              "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
              "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
              "\"buffers\":[{\"byteLength\":3000036}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
              "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":3000000}],\"accessors\":[{\"bufferView\":0,"
              "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5121,"
              "\"count\":3000000,\"type\":\"SCALAR\"}]}",
              NULL, 3000036);
    size_t cap = 64 + 40 * 150;
    char *text = malloc(cap);
    size_t len = (size_t)snprintf(text, cap, "{\"hosts\": [");
    for (int i = 0; i < 150; i++) len += (size_t)snprintf(text + len, cap - len, "%s{\"mesh\": \"one_m.glb\"}", i ? "," : "");
    snprintf(text + len, cap - len, "]}");
    banyan_hosts *H = (banyan_hosts *)&H;
    banyan_error e = {0, ""};
    double t0 = now();
    banyan_status s = banyan_preset_host_set(text, strlen(text), "many.json", outdir, NULL, 0, &H, &e);
    double dt = now() - t0;
    CHECK(s == BANYAN_E_LIMIT && !H && strstr(e.message, "many.json") && strstr(e.message, "33554432") && dt < 1.0,
          "150 x one_m.glb: %s '%s' in %.2f s", banyan_status_name(s), e.message, dt);
    free(text);

    /* A preset's budget covers reading its meshes. */
    H = (banyan_hosts *)&H;
    t0 = now();
    s = preset_set("{\"hosts\": [{\"mesh\": \"inst_100.glb\"}]}", "inst.json", 2, 64, &H, &e);
    dt = now() - t0;
    CHECK(s == BANYAN_E_LIMIT && !H && strstr(e.message, "max_memory_mb = 64") && dt < 0.5,
          "inst_100 preset in 2 s / 64 MB: %s '%s' in %.2f s", banyan_status_name(s), e.message, dt);
    s = preset_set("{\"hosts\": [{\"mesh\": \"inst_20.glb\"}]}", "inst.json", 0.01, 4096, &H, &e);
    CHECK(s == BANYAN_E_LIMIT && !H && strstr(e.message, "max_seconds = 0.01"), "inst_20 preset in 0.01 s: %s '%s'",
          banyan_status_name(s), e.message);
    s = preset_set("{\"hosts\": [{\"mesh\": \"good.glb\"}]}", "inst.json", 2, 1e7, &H, &e);
    CHECK(s == BANYAN_E_RANGE && !H && strstr(e.message, "max_memory_mb"), "max_memory_mb 1e7: %s", e.message);
    s = preset_set("{\"hosts\": [{\"mesh\": \"good.glb\"}]}", "inst.json", 10, 256, &H, &e);
    CHECK(s == BANYAN_OK && H && banyan_hosts_count(H) == 1, "good.glb preset within a budget: %s", e.message);
    banyan_hosts_free(H);
}

/* Messages keep their cause, say what to change, and escape controls. */
static void messages(void) {
    /* 60 meshes then a flat one: the set's message names the entry and keeps
     * its cause (a prefix listing every entry would fill the message). */
    unsigned char bin[48];
    const float flat[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    const uint32_t tri[3] = {0, 1, 2};
    memcpy(bin, flat, 36);
    memcpy(bin + 36, tri, 12);
    write_glb("flat.glb",
              "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
              "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
              "\"buffers\":[{\"byteLength\":48}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
              "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":12}],\"accessors\":[{\"bufferView\":0,"
              "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5125,"
              "\"count\":3,\"type\":\"SCALAR\"}]}",
              bin, sizeof bin);
    char text[4096];
    size_t len = (size_t)snprintf(text, sizeof text, "{\"hosts\": [");
    for (int i = 0; i < 60; i++) len += (size_t)snprintf(text + len, sizeof text - len, "{\"mesh\": \"good.glb\"},");
    snprintf(text + len, sizeof text - len, "{\"mesh\": \"flat.glb\"}]}");
    banyan_hosts *H = NULL;
    banyan_error e = {0, ""};
    banyan_status s = banyan_preset_host_set(text, strlen(text), "set.json", outdir, NULL, 0, &H, &e);
    CHECK(s == BANYAN_E_BAD_HOST && !H && strstr(e.message, "set.json") && strstr(e.message, "hosts[60]") &&
              strstr(e.message, "zero area"),
          "61 meshes, the last flat: %s '%s'", banyan_status_name(s), e.message);

    /* A long source name gives up its middle, not the cause. */
    char source[400];
    memset(source, 'd', sizeof source);
    memcpy(source, "/long/", 6);
    snprintf(source + 300, sizeof source - 300, "/preset.json");
    const char *missing = "{\"hosts\": [{\"mesh\": \"missing.glb\"}]}";
    s = banyan_preset_host_set(missing, strlen(missing), source, outdir, NULL, 0, &H, &e);
    CHECK(s == BANYAN_E_IO && !H && strstr(e.message, "/long/") && strstr(e.message, "...") &&
              strstr(e.message, "missing.glb: cannot open") && strlen(e.message) < sizeof e.message,
          "long source: '%s'", e.message);

    /* So does a long path at the start of a message. */
    char long_path[2048];
    snprintf(long_path, sizeof long_path, "%s/%0600d/missing.glb", outdir, 0);
    banyan_host_mesh *m = NULL;
    s = banyan_glb_read_host(long_path, NULL, -1, &m, &e);
    CHECK(s == BANYAN_E_IO && !m && strstr(e.message, "...") && strstr(e.message, "missing.glb: cannot open"),
          "long path: '%s'", e.message);

    /* ESC and other controls in a path are printed escaped. */
    const char *esc = "{\"hosts\": [{\"mesh\": \"a\\u001b[2J\\u009bb\\u0007.glb\"}]}";
    s = banyan_preset_host_set(esc, strlen(esc), "esc\033]0;title\007.json", outdir, NULL, 0, &H, &e);
    CHECK(s == BANYAN_E_IO && !H && !strchr(e.message, '\033') && !strchr(e.message, '\007') &&
              !strstr(e.message, "\302\233") && strstr(e.message, "a\\x1b[2J\\xc2\\x9bb\\x07.glb") &&
              strstr(e.message, "esc\\x1b]0;title\\x07.json"),
          "controls: '%s'", e.message);
    s = banyan_glb_read_host_budget("tab\there\n.glb", NULL, -1, budget(10, 64), (banyan_host_mesh **)&H, &e);
    CHECK(s == BANYAN_E_IO && strstr(e.message, "tab\\x09here\\x0a.glb"), "tab and newline: '%s'", e.message);
    /* Text that is already UTF-8 stays as it is. */
    s = banyan_glb_read_host_budget("caf\xc3\xa9 \xe6\x9c\xa8.glb", NULL, -1, budget(10, 64),
                                    (banyan_host_mesh **)&H, &e);
    CHECK(s == BANYAN_E_IO && strstr(e.message, "caf\xc3\xa9 \xe6\x9c\xa8.glb") && !strstr(e.message, "\\x"),
          "UTF-8 kept: '%s'", e.message);

    /* A mesh host's rotation error says where its scale goes. */
    const char *rot = "{\"hosts\": [{\"mesh\": \"good.glb\", \"rotation\": [1,0,0, 0,1,0, 0,0,-1]}]}";
    s = banyan_preset_host_set(rot, strlen(rot), "rot.json", outdir, NULL, 0, &H, &e);
    CHECK(s == BANYAN_E_BAD_HOST && strstr(e.message, "negative \"scale\"") && !strstr(e.message, "half"),
          "mirroring rotation: '%s'", e.message);
}

int main(int argc, char **argv) {
    snprintf(outdir, sizeof outdir, "%s/hostile_hosts", argc > 1 ? argv[1] : ".");
    mkdir(outdir, 0777);
    wrapping_offsets();
    modes();
    big_files();
    counted_work();
    presets();
    messages();
    /* Nothing above may have held much: each refusal came from the sizes. */
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    CHECK(ru.ru_maxrss < 400 * 1024, "peak resident memory %ld MB", ru.ru_maxrss / 1024);
    return check_done("test_hostile_hosts");
}
