/*
 * test_usd.c - banyan_usd_write_nodes (banyan/usd.h) through the public
 * API: refusals name the argument and leave no file; a tube and a small
 * keyaki write a USD text layer in the library's frame with one Mesh a
 * part, the counts of the mesh, the textures as files under image_dir,
 * a LOD variant set for levels; the same bytes on every run; a spent
 * budget stops the write and keeps the old file. OpenUSD's
 * own checks of the files are tests/usd/test_usd_presets.py.
 *
 *   test_usd OUTDIR
 */
#include "banyan.h"
#include "check.h"
#include "test_files.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *g_dir;

static int exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* How many times `needle` occurs in `hay`. */
static size_t count_of(const char *hay, const char *needle) {
    size_t n = 0, k = strlen(needle);
    for (const char *p = strstr(hay, needle); p; p = strstr(p + k, needle)) n++;
    return n;
}

static void refusals(const banyan_mesh *m) {
    banyan_gltf_node node = {m, "tube", 0, NULL, NULL};
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    banyan_error err;
    struct {
        const char *name;
        banyan_status want;
        const char *says;
    } paths[] = {{"refused.glb", BANYAN_E_INVALID_ARG, ".usda"},
                 {"refused.usdc", BANYAN_E_UNSUPPORTED, "usdcat"},
                 {"refused.usdz", BANYAN_E_UNSUPPORTED, "usdcat"}};
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
        const char *p = test_join(g_dir, paths[i].name);
        banyan_status s = banyan_usd_write_nodes(p, &node, 1, &o, &err);
        CHECK(s == paths[i].want && strstr(err.message, paths[i].says) && !exists(p), "%s: %s %s", paths[i].name,
              banyan_status_name(s), err.message);
    }
    const char *p = test_join(g_dir, "refused.usda");
    CHECK(banyan_usd_write_nodes(NULL, &node, 1, &o, &err) == BANYAN_E_INVALID_ARG, "NULL path: %s", err.message);
    CHECK(banyan_usd_write_nodes(p, NULL, 1, &o, &err) == BANYAN_E_INVALID_ARG && strstr(err.message, "nodes"),
          "NULL nodes: %s", err.message);
    CHECK(banyan_usd_write_nodes(p, &node, 0, &o, &err) == BANYAN_E_INVALID_ARG && strstr(err.message, "count"),
          "count 0: %s", err.message);
    banyan_gltf_node empty = {NULL, "x", 0, NULL, NULL};
    CHECK(banyan_usd_write_nodes(p, &empty, 1, &o, &err) != BANYAN_OK, "a node without a mesh is refused");
    o.compact = 1;
    CHECK(banyan_usd_write_nodes(p, &node, 1, &o, &err) == BANYAN_E_RANGE && strstr(err.message, "compact"),
          "compact: %s", err.message);
    o.compact = 0, o.engine_uvs = 1;
    CHECK(banyan_usd_write_nodes(p, &node, 1, &o, &err) == BANYAN_E_RANGE && strstr(err.message, "engine_uvs"),
          "engine_uvs: %s", err.message);
    o.engine_uvs = 0, o.texture_size = 100;
    CHECK(banyan_usd_write_nodes(p, &node, 1, &o, &err) == BANYAN_E_RANGE && strstr(err.message, "texture_size"),
          "texture_size 100: %s", err.message);
    o.texture_size = 64;
    CHECK(banyan_usd_write_nodes(test_join(g_dir, "no_such_folder/x.usda"), &node, 1, &o, &err) == BANYAN_E_IO,
          "a missing folder: %s", err.message);
    CHECK(!exists(p), "no file after the refusals");
}

static void tube(const banyan_mesh *m) {
    banyan_gltf_node node = {m, "a tube!", 0, NULL, NULL};
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.textures = 0;
    banyan_error err;
    const char *p = test_join(g_dir, "usd_tube.usda");
    CHECK(banyan_usd_write_nodes(p, &node, 1, &o, &err) == BANYAN_OK, "tube: %s", err.message);
    size_t len = 0, len2 = 0;
    char *a = test_read_file(p, &len);
    CHECK(a && !strncmp(a, "#usda 1.0\n", 10), "the layer starts with #usda 1.0");
    if (!a) return;
    CHECK(strstr(a, "upAxis = \"Z\"") && strstr(a, "metersPerUnit = 1"), "the stage in the library's frame");
    CHECK(strstr(a, "defaultPrim = \"a_tube_\"") && strstr(a, "def Xform \"a_tube_\""), "the node's name made an identifier");
    CHECK(count_of(a, "def Mesh ") == m->part_count, "%zu meshes for %u parts", count_of(a, "def Mesh "), m->part_count);
    const char *fvc = strstr(a, "int[] faceVertexCounts = [");
    if (fvc) fvc += strlen("int[] faceVertexCounts = [");
    const char *end = fvc ? strchr(fvc, ']') : NULL;
    size_t threes = 0;
    for (const char *q = fvc; q && q < end; q++) threes += *q == '3';
    CHECK(fvc && threes == m->index_count / 3, "%zu triangles written for %u", threes, m->index_count / 3);
    CHECK(count_of(a, "UsdPreviewSurface") == m->material_count && !strstr(a, "UsdUVTexture"),
          "flat materials with textures off");
    CHECK(banyan_usd_write_nodes(p, &node, 1, &o, &err) == BANYAN_OK, "again: %s", err.message);
    char *b = test_read_file(p, &len2);
    CHECK(b && len == len2 && !memcmp(a, b, len), "the same bytes twice");
    free(a);
    free(b);
}

static void keyaki(void) {
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    kp.levels = 5;
    banyan_mesh *m = NULL;
    banyan_error err;
    CHECK(banyan_keyaki_generate(&kp, &m, NULL, NULL, &err) == BANYAN_OK, "keyaki: %s", err.message);
    if (!m) return;
    banyan_lod_params lp;
    banyan_lod_params_init(&lp);
    lp.ratio = 0.5;
    banyan_mesh *half = NULL;
    CHECK(banyan_mesh_lod(m, &lp, &half, &err) == BANYAN_OK, "lod: %s", err.message);
    const banyan_mesh *levels[1] = {half};
    banyan_gltf_node node = {m, "keyaki", half ? 1 : 0, levels, NULL};
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 64;
    o.texture_cache = 0;
    o.image_dir = "tex/usd";
    const char *p = test_join(g_dir, "usd_keyaki.usda");
    CHECK(banyan_usd_write_nodes(p, &node, 1, &o, &err) == BANYAN_OK, "keyaki layer: %s", err.message);
    char *a = test_read_file(p, NULL);
    CHECK(a && strstr(a, "prepend variantSets = \"LOD\"") && strstr(a, "\"lod0\" {") && strstr(a, "\"lod1\" {"),
          "a LOD variant set of two levels");
    CHECK(a && strstr(a, "@tex/usd/keyaki_bark-64-s1.png@") && strstr(a, "@tex/usd/keyaki_bark_normal-64-s1.png@"),
          "the bark's textures referenced under image_dir");
    CHECK(exists(test_join(g_dir, "tex/usd/keyaki_bark-64-s1.png")) &&
              exists(test_join(g_dir, "tex/usd/keyaki_leaf_summer_normal-64-s1.png")),
          "the texture files beside the layer");
    CHECK(a && strstr(a, "float3[] primvars:wind_pivot") && strstr(a, "float[] primvars:wind_level"),
          "the wind data as primvars");
    CHECK(a && strstr(a, "def BasisCurves \"Skeleton\""), "the skeleton as curves");
    free(a);
    banyan_mesh_free(half);
    banyan_mesh_free(m);
}

/* Past the budget's max_seconds the write stops: BANYAN_E_LIMIT naming
 * it, the old file as it was. */
static void budget(void) {
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    kp.levels = 12;
    banyan_mesh *m = NULL;
    banyan_error err;
    CHECK(banyan_keyaki_generate(&kp, &m, NULL, NULL, &err) == BANYAN_OK, "keyaki 12: %s", err.message);
    if (!m) return;
    banyan_gltf_node node = {m, "keyaki", 0, NULL, NULL};
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.textures = 0;
    const char *p = test_join(g_dir, "usd_budget.usda");
    FILE *f = fopen(p, "wb");
    if (f) fputs("old", f), fclose(f);
    banyan_budget b;
    banyan_budget_init(&b);
    b.max_seconds = 0.01;
    banyan_status s = banyan_usd_write_nodes_budget(p, &node, 1, &o, &b, &err);
    size_t len = 0;
    char *text = test_read_file(p, &len);
    CHECK(s == BANYAN_E_LIMIT && strstr(err.message, "max_seconds") && text && !strcmp(text, "old"),
          "a 10 ms budget on %u vertices: %s %s, the old file %s", m->vertex_count, banyan_status_name(s), err.message,
          text && !strcmp(text, "old") ? "kept" : "changed");
    free(text);
    banyan_mesh_free(m);
}

int main(int argc, char **argv) {
    g_dir = argc > 1 ? argv[1] : ".";
    const double pts[9] = {0, 0, 0, 0, 0, 1, 0.2, 0, 2};
    const double radii[3] = {0.2, 0.15, 0.05};
    banyan_mesh *m = NULL;
    banyan_error err;
    CHECK(banyan_tube_generate(pts, radii, 3, 8, 1, &m, &err) == BANYAN_OK, "tube: %s", err.message);
    if (m) {
        refusals(m);
        tube(m);
    }
    banyan_mesh_free(m);
    keyaki();
    budget();
    return check_done("test_usd");
}
