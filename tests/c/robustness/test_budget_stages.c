/* test_budget_stages.c - the stages after generation keep a budget:
 * banyan_mesh_lod_budget (simplifier and billboards), the textures
 * (refused up front from their size, stopped while drawing or encoding)
 * and the glTF writer (its textures refused up front, a late write
 * stopped with the old file left); the fused roots surface's OpenVDB
 * meshing asks its stop between pieces; an output name longer than the
 * folder allows is refused before any work. A budget that is not reached
 * changes no byte. A stop is wanted within 0.5 s of its budget, as the
 * generators' (test_budget.c), on a noisy 2-core VM under ASan too. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "banyan.h"
#include "check.h"
#include "base/atomic_file.h"
#include "lod_plants.h"
#include "roots/fused_vdb.h"
#include "test_files.h"

/* stb_image decodes the library's PNGs for the byte-exact check. */
#if defined(__GNUC__)
#  pragma GCC diagnostic push
#  pragma GCC diagnostic ignored "-Wunused-function"
#  pragma GCC diagnostic ignored "-Wpedantic"
#  pragma GCC diagnostic ignored "-Wsign-compare"
#  pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#if defined(__GNUC__)
#  pragma GCC diagnostic pop
#  pragma GCC diagnostic ignored "-Wunused-function"
#endif

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

static banyan_budget budget(double seconds, double mb) {
    banyan_budget b;
    banyan_budget_init(&b);
    if (seconds != 0) b.max_seconds = seconds; /* 0: the default; NaN set as is */
    if (mb != 0) b.max_memory_mb = mb;
    return b;
}

/* within: the budget plus what a stop may take (scaled by CHECK_SLACK). */
static void limited(const char *name, banyan_status s, const void *out, const banyan_error *e, double t,
                    const char *what, double budget_s, double slack) {
    double within = budget_s + CHECK_SLACK * slack;
    printf("%s: status %d after %.3f s: %s\n", name, (int)s, t, e->message);
    CHECK(s == BANYAN_E_LIMIT, "%s: status %d, want BANYAN_E_LIMIT (%s)", name, (int)s, e->message);
    CHECK(out == NULL, "%s: an output came with the failure", name);
    CHECK(strstr(e->message, what) != NULL, "%s: message does not name %s: %s", name, what, e->message);
    CHECK(t < within, "%s: took %.3f s, want < %.3f s", name, t, within);
}

static int same_mesh(const banyan_mesh *a, const banyan_mesh *b) {
    return a && b && a->vertex_count == b->vertex_count && a->index_count == b->index_count &&
           !memcmp(a->positions, b->positions, 3 * sizeof(float) * a->vertex_count) &&
           !memcmp(a->indices, b->indices, sizeof(uint32_t) * a->index_count);
}

static void test_budget_args(void) {
    banyan_budget b = budget(0.001, 0);
    banyan_mesh *o = (banyan_mesh *)1;
    banyan_error e;
    banyan_status s = banyan_mesh_lod_budget(NULL, NULL, &b, &o, &e);
    CHECK(s != BANYAN_OK && o == NULL, "lod: a NULL mesh accepted");
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    banyan_image *bc = (banyan_image *)1;
    s = banyan_texture_generate_budget(&tp, &b, &bc, NULL, &e);
    CHECK(s == BANYAN_E_RANGE && bc == NULL && strstr(e.message, "budget->max_seconds"),
          "max_seconds 0.001: %d %s", (int)s, e.message);
    b = budget(1, NAN);
    s = banyan_texture_generate_budget(&tp, &b, &bc, NULL, &e);
    CHECK(s == BANYAN_E_RANGE && strstr(e.message, "budget->max_memory_mb"), "max_memory_mb nan: %d %s", (int)s,
          e.message);
    CHECK(banyan_sizeof_budget() == sizeof(banyan_budget), "sizeof budget");
}

/* A small avenue (four trees, two parts each): stopped between parts and
 * between the billboards' trees and cards; with room, the same bytes as
 * without. */
static void test_lod(void) {
    banyan_error e;
    banyan_mesh *m = lod_plant("avenue_small", 0, &e);
    CHECK(m != NULL, "avenue: %s", e.message);
    if (!m) return;
    banyan_lod_params p;
    banyan_lod_params_init(&p);
    banyan_budget b = budget(0.01, 0);
    for (int bb = 0; bb < 2; bb++) {
        p.billboard = bb;
        p.billboard_size = 1024;
        banyan_mesh *o = NULL;
        double t0 = now();
        banyan_status s = banyan_mesh_lod_budget(m, &p, &b, &o, &e);
        limited(bb ? "billboard, 0.01 s" : "simplify, 0.01 s", s, o, &e, now() - t0, "max_seconds", 0.01, 0.49);
        banyan_mesh_free(o);
        banyan_mesh *free_run = NULL, *roomy = NULL;
        banyan_budget big = budget(600, 0);
        CHECK(!banyan_mesh_lod(m, &p, &free_run, &e), "lod: %s", e.message);
        CHECK(!banyan_mesh_lod_budget(m, &p, &big, &roomy, &e), "lod with room: %s", e.message);
        CHECK(same_mesh(free_run, roomy), "lod: a budget not reached changed the mesh (billboard %d)", bb);
        banyan_mesh_free(free_run);
        banyan_mesh_free(roomy);
    }
    banyan_mesh_free(m);
}

static void test_textures(void) {
    banyan_error e;
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.kind = BANYAN_TEX_KEYAKI_BARK;
    tp.size = 8192;
    banyan_image *bc = NULL, *nm = NULL;
    /* 8192^2 x 11 bytes is 704 MB: refused before a byte is drawn. */
    banyan_budget b = budget(0, 200);
    double t0 = now();
    banyan_status s = banyan_texture_generate_budget(&tp, &b, &bc, &nm, &e);
    limited("texture 8192, 200 MB", s, bc, &e, now() - t0, "max_memory_mb", 0, 0.5);
    CHECK(nm == NULL && strstr(e.message, "texture size"), "texture 8192: %s", e.message);
    /* Drawing past the time: stopped inside the painter. */
    tp.size = 4096;
    b = budget(0.05, 0);
    t0 = now();
    s = banyan_texture_generate_budget(&tp, &b, &bc, &nm, &e);
    limited("texture 4096, 0.05 s", s, bc, &e, now() - t0, "max_seconds", 0.05, 0.5);
    CHECK(nm == NULL, "texture 4096: a normal map came with the failure");
    /* Leaves, stopped between cells. */
    tp.kind = BANYAN_TEX_KEYAKI_LEAF;
    t0 = now();
    s = banyan_texture_generate_budget(&tp, &b, &bc, NULL, &e);
    limited("leaves 4096, 0.05 s", s, bc, &e, now() - t0, "max_seconds", 0.05, 0.5);
    /* With room: the same pixels as the call without a budget. */
    tp.size = 256;
    banyan_image *a = NULL, *c = NULL;
    b = budget(600, 0);
    CHECK(!banyan_texture_generate(&tp, &a, NULL, &e), "texture: %s", e.message);
    CHECK(!banyan_texture_generate_budget(&tp, &b, &c, NULL, &e), "texture with room: %s", e.message);
    CHECK(a && c && !memcmp(a->pixels, c->pixels, (size_t)256 * 256 * 4), "a budget not reached changed a texture");
    banyan_image_free(a);
    banyan_image_free(c);
}

static int file_equals(const char *path, const char *bytes, size_t len) {
    size_t n = 0;
    char *got = test_read_file(path, &n);
    int same = got && n == len && !memcmp(got, bytes, len);
    free(got);
    return same;
}

static void test_writer(const char *dir) {
    banyan_error e;
    banyan_mesh *m = lod_plant("keyaki_young", 0, &e);
    CHECK(m != NULL, "keyaki_young: %s", e.message);
    if (!m) return;
    const char *path = test_join(dir, "budget_stages_writer.glb");
    FILE *f = fopen(path, "wb");
    static const char old[] = "the old file";
    if (f) fwrite(old, 1, sizeof old, f), fclose(f);
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 8192;
    const banyan_mesh *const ms[1] = {m};
    banyan_budget b = budget(0, 200);
    double t0 = now();
    banyan_status s = banyan_gltf_write_ex_budget(path, ms, NULL, 1, &o, &b, &e);
    limited("write, textures 8192, 200 MB", s, NULL, &e, now() - t0, "max_memory_mb", 0, 0.5);
    CHECK(strstr(e.message, "texture size") != NULL, "write 8192: says not what to change: %s", e.message);
    CHECK(file_equals(path, old, sizeof old), "write 8192: the old file changed");
    /* Out of time while the textures are drawn and encoded. */
    o.texture_size = 4096;
    b = budget(0.1, 0);
    t0 = now();
    s = banyan_gltf_write_ex_budget(path, ms, NULL, 1, &o, &b, &e);
    limited("write, textures 4096, 0.1 s", s, NULL, &e, now() - t0, "max_seconds", 0.1, 0.5);
    CHECK(file_equals(path, old, sizeof old), "write 0.1 s: the old file changed");
    /* Nodes too (the CLI's --lod path). */
    banyan_gltf_node node = {m, "k", 0, NULL, NULL};
    t0 = now();
    s = banyan_gltf_write_nodes_budget(path, &node, 1, &o, &b, &e);
    limited("write nodes, 0.1 s", s, NULL, &e, now() - t0, "max_seconds", 0.1, 0.5);
    /* With room: the bytes of the call without a budget. */
    o.texture_size = 64;
    const char *p2 = test_join(dir, "budget_stages_free.glb");
    b = budget(600, 0);
    CHECK(!banyan_gltf_write_ex(p2, ms, NULL, 1, &o, &e), "write: %s", e.message);
    CHECK(!banyan_gltf_write_ex_budget(path, ms, NULL, 1, &o, &b, &e), "write with room: %s", e.message);
    size_t n = 0;
    char *want = test_read_file(p2, &n);
    CHECK(want && file_equals(path, want, n), "a budget not reached changed the .glb");
    free(want);
    banyan_mesh_free(m);
}

/* A sphere of radius R voxels as 8^3 blocks of its narrow band. */
typedef struct sphere {
    int32_t *origin;
    float *values;
    size_t n;
} sphere;

static sphere sphere_band(int R) {
    sphere s = {NULL, NULL, 0};
    int nb = (2 * R) / 8 + 4, c = nb * 4, cap = 0;
    for (int bx = 0; bx < nb; bx++)
        for (int by = 0; by < nb; by++)
            for (int bz = 0; bz < nb; bz++) {
                double cx = bx * 8 + 4 - c, cy = by * 8 + 4 - c, cz = bz * 8 + 4 - c;
                double d = sqrt(cx * cx + cy * cy + cz * cz) - R;
                if (fabs(d) > 10.0) continue;
                if ((int)s.n == cap) {
                    cap = cap ? 2 * cap : 256;
                    s.origin = realloc(s.origin, sizeof(int32_t) * 3 * (size_t)cap);
                    s.values = realloc(s.values, sizeof(float) * 512 * (size_t)cap);
                }
                int32_t *o = s.origin + 3 * s.n;
                o[0] = bx * 8 - c, o[1] = by * 8 - c, o[2] = bz * 8 - c;
                for (int i = 0; i < 512; i++) {
                    double x = o[0] + i / 64, y = o[1] + (i / 8) % 8, z = o[2] + i % 8;
                    s.values[512 * s.n + (size_t)i] = (float)(sqrt(x * x + y * y + z * z) - R);
                }
                s.n++;
            }
    return s;
}

typedef struct stop_count {
    int calls, stop_at;
} stop_count;

static int count_stop(void *user) {
    stop_count *c = user;
    return ++c->calls >= c->stop_at;
}

static void test_fused_stop(void) {
    sphere sp = sphere_band(80);
    fused_vdb_out out;
    stop_count free_run = {0, 1 << 30};
    fused_vdb_in in = {sp.origin, sp.values, sp.n, 3.0f, count_stop, &free_run};
    int rc = fused_vdb_mesh(&in, &out);
    printf("fused stop: %zu blocks, %u vertices, %u triangles, stop asked %d times\n", sp.n, out.n_pos, out.n_tri,
           free_run.calls);
    CHECK(rc == FUSED_VDB_OK && out.n_tri > 0, "sphere: rc %d", rc);
    /* Asked between the stages and every few hundred leaves, not once. */
    CHECK(free_run.calls >= 8, "stop asked only %d times while meshing %zu blocks", free_run.calls, sp.n);
    fused_vdb_out first = out;
    for (int at = 1; at <= free_run.calls; at += free_run.calls / 4 > 0 ? free_run.calls / 4 : 1) {
        stop_count c = {0, at};
        in.stop_user = &c;
        rc = fused_vdb_mesh(&in, &out);
        CHECK(rc == FUSED_VDB_STOPPED && out.pos == NULL && out.tri == NULL && c.calls == at,
              "stop at call %d: rc %d after %d calls", at, rc, c.calls);
        free(out.pos);
        free(out.tri);
    }
    /* No stop: the same mesh again. */
    in.stop = NULL;
    rc = fused_vdb_mesh(&in, &out);
    CHECK(rc == FUSED_VDB_OK && out.n_pos == first.n_pos && out.n_tri == first.n_tri &&
              !memcmp(out.pos, first.pos, sizeof(float) * 3 * out.n_pos) &&
              !memcmp(out.tri, first.tri, sizeof(uint32_t) * 3 * out.n_tri),
          "meshing again gave another mesh");
    free(out.pos);
    free(out.tri);
    free(first.pos);
    free(first.tri);
    free(sp.origin);
    free(sp.values);
}

/* A name the folder's file system cannot hold is refused by the check
 * the CLI makes before generating, not by the rename after it. */
static void test_long_name(const char *dir) {
    char name[300], path[1600], why[8400];
    memset(name, 'a', 251);
    memcpy(name + 251, ".glb", 5); /* 255 bytes: fits */
    snprintf(path, sizeof path, "%s/%s", dir, name);
    int e = atomic_check(path, why, sizeof why);
    CHECK(e == 0, "a 255-byte name refused: %s", why);
    memset(name, 'a', 252);
    memcpy(name + 252, ".glb", 5); /* 256 bytes */
    snprintf(path, sizeof path, "%s/%s", dir, name);
    e = atomic_check(path, why, sizeof why);
    CHECK(e == ENAMETOOLONG && strstr(why, "256 bytes") && strstr(why, "shorter name"),
          "a 256-byte name: %d %s", e, why);
}

/* The stoppable PNG encoder's bytes decode (stb_image) to the pixels
 * given, and two calls give the same bytes: textures, and odd sizes with
 * 1 to 4 channels (noise, flat runs). */
static void test_png_bytes(void) {
    banyan_error e;
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.size = 1024; /* 4 MB of filtered rows */
    banyan_image *bc = NULL, *nm = NULL;
    CHECK(!banyan_texture_generate(&tp, &bc, &nm, &e), "texture: %s", e.message);
    uint8_t noise[37 * 23 * 4];
    uint32_t x = 12345;
    for (size_t i = 0; i < sizeof noise; i++) x = x * 1103515245u + 12345u, noise[i] = i % 97 < 40 ? 7 : (uint8_t)(x >> 16);
    banyan_image odd[4] = {{37, 23, 1, noise}, {37, 23, 2, noise}, {5, 1, 3, noise}, {1, 37, 4, noise}};
    const banyan_image *ims[6] = {bc, nm, &odd[0], &odd[1], &odd[2], &odd[3]};
    for (int k = 0; k < 6; k++) {
        const banyan_image *im = ims[k];
        if (!im) continue;
        uint8_t *png = NULL;
        size_t len = 0;
        CHECK(!banyan_image_png(im, &png, &len, &e), "png %d: %s", k, e.message);
        int w = 0, h = 0, c = 0;
        unsigned char *dec = png ? stbi_load_from_memory(png, (int)len, &w, &h, &c, 0) : NULL;
        CHECK(dec && w == (int)im->width && h == (int)im->height && c == (int)im->channels &&
                  !memcmp(dec, im->pixels, (size_t)w * h * c),
              "png %d (%u x %u x %u): does not decode to its pixels", k, im->width, im->height, im->channels);
        uint8_t *again = NULL;
        size_t len2 = 0;
        CHECK(!banyan_image_png(im, &again, &len2, &e) && again && len2 == len && !memcmp(again, png, len),
              "png %d: two calls give different bytes", k);
        stbi_image_free(dec);
        banyan_png_free(png);
        banyan_png_free(again);
    }
    banyan_image_free(bc);
    banyan_image_free(nm);
}

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : ".";
    test_budget_args();
    test_lod();
    test_textures();
    test_png_bytes();
    test_writer(dir);
    test_fused_stop();
    test_long_name(dir);
    return check_done("test_budget_stages");
}
