/*
 * test_gltf_textures.c - textures and materials in the glTF the library
 * writes: leaf materials are alpha-masked, double sided and
 * textured; the embedded PNGs decode (stb_image) with alpha where the
 * leaves are and opaque bark; images are shared per kind and season; the
 * same seed gives the same bytes; textures off writes no image; the season
 * swaps the material but not the geometry; leaf cards show one atlas cell
 * each and carry per-leaf colours. Small texture sizes keep it quick. The
 * files stay in OUTDIR for the Khronos validator (ctest gltf_validator:
 * 0 errors, 0 warnings).
 */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "test_files.h"
#include "test_hosts.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#if defined(__GNUC__) /* stb_image's unused static functions, reported at the end of the file */
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image.h>

static char g_dir[1024];

static const char *out_path(const char *name) {
    static char buf[4][1200];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", g_dir, name);
    return buf[k];
}

/* ------------------------------------------------------------ .glb */

typedef struct glb {
    unsigned char *data;
    size_t size;
    cJSON *json;
    const unsigned char *bin;
    size_t bin_size;
} glb;

static void glb_free(glb *g) {
    cJSON_Delete(g->json);
    free(g->data);
    memset(g, 0, sizeof *g);
}

static uint32_t rd32(const unsigned char *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }

static int glb_read(const char *path, glb *g) {
    memset(g, 0, sizeof *g);
    g->data = (unsigned char *)test_read_file(path, &g->size);
    if (!g->data || g->size < 20 || rd32(g->data) != 0x46546C67u) return 0;
    size_t off = 12;
    while (off + 8 <= g->size) {
        uint32_t n = rd32(g->data + off), kind = rd32(g->data + off + 4);
        if (off + 8 + n > g->size) return 0;
        if (kind == 0x4E4F534Au) g->json = cJSON_ParseWithLength((const char *)g->data + off + 8, n);
        if (kind == 0x004E4942u) {
            g->bin = g->data + off + 8;
            g->bin_size = n;
        }
        off += 8 + (size_t)n;
    }
    return g->json != NULL;
}

static cJSON *arr(const glb *g, const char *key) { return cJSON_GetObjectItemCaseSensitive(g->json, key); }
static int num(const cJSON *o, const char *key, double *out) {
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsNumber(x)) return 0;
    *out = x->valuedouble;
    return 1;
}
static const char *str(const cJSON *o, const char *key) {
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(x) ? x->valuestring : NULL;
}

/* The material called `name`, or NULL. */
static const cJSON *material_named(const glb *g, const char *name) {
    const cJSON *m;
    cJSON_ArrayForEach(m, arr(g, "materials")) {
        const char *n = str(m, "name");
        if (n && !strcmp(n, name)) return m;
    }
    return NULL;
}

/* Image `index` of texture `tex`, decoded; NULL when missing or bad. */
static unsigned char *texture_pixels(const glb *g, int tex, int *w, int *h, int *ch, const cJSON **image_out) {
    const cJSON *t = cJSON_GetArrayItem(arr(g, "textures"), tex);
    double src, view, off = 0, len;
    if (!t || !num(t, "source", &src)) return NULL;
    const cJSON *im = cJSON_GetArrayItem(arr(g, "images"), (int)src);
    if (image_out) *image_out = im;
    if (!im || !num(im, "bufferView", &view)) return NULL;
    const char *mime = str(im, "mimeType");
    if (!mime || strcmp(mime, "image/png")) return NULL;
    const cJSON *v = cJSON_GetArrayItem(arr(g, "bufferViews"), (int)view);
    if (!v || !num(v, "byteLength", &len)) return NULL;
    num(v, "byteOffset", &off);
    if (off + len > (double)g->bin_size) return NULL;
    return stbi_load_from_memory(g->bin + (size_t)off, (int)len, w, h, ch, 0);
}

/* The texture index of a material's baseColorTexture / normalTexture. */
static int base_texture(const cJSON *m) {
    const cJSON *pbr = cJSON_GetObjectItemCaseSensitive(m, "pbrMetallicRoughness");
    const cJSON *bt = pbr ? cJSON_GetObjectItemCaseSensitive(pbr, "baseColorTexture") : NULL;
    double i;
    return bt && num(bt, "index", &i) ? (int)i : -1;
}
static int normal_texture(const cJSON *m) {
    const cJSON *nt = cJSON_GetObjectItemCaseSensitive(m, "normalTexture");
    double i;
    return nt && num(nt, "index", &i) ? (int)i : -1;
}
static int wrap_of(const glb *g, int tex) {
    const cJSON *t = cJSON_GetArrayItem(arr(g, "textures"), tex);
    double s, w = -1;
    if (!t || !num(t, "sampler", &s)) return -1;
    const cJSON *sm = cJSON_GetArrayItem(arr(g, "samplers"), (int)s);
    if (!sm || !num(sm, "wrapS", &w)) return -1;
    double wt = -2;
    num(sm, "wrapT", &wt);
    return w == wt ? (int)w : -1;
}

/* ------------------------------------------------------------ meshes */

static banyan_mesh *keyaki(int32_t season, uint64_t seed) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.levels = 9;
    p.seed = seed;
    p.season = season;
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK && m, "keyaki: %s", err.message);
    return m;
}

static banyan_mesh *ivy(int32_t season) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = 60;
    p.season = season;
    banyan_box w = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    CHECK(test_ivy_boxes(&p, &w, 1, &m, &err) == BANYAN_OK && m, "ivy: %s", err.message);
    return m;
}

static banyan_gltf_options small_textures(void) {
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 128;
    return o;
}

static banyan_status write1(const char *name, const banyan_mesh *m, const banyan_gltf_options *o, banyan_error *err) {
    const banyan_mesh *one[1] = {m};
    return banyan_gltf_write_ex(out_path(name), one, NULL, 1, o, err);
}

/* ------------------------------------------------------------ tests */

/* The leaf material: MASK at 0.5, double sided, white factor, base colour
 * and normal textures; the base colour has transparent and opaque texels,
 * and opaque texels in every atlas cell; the sampler clamps. The bark's:
 * opaque, repeating, fully opaque texels. */
static void check_materials(const char *file, const char *leaf, const char *bark, int32_t leaf_kind) {
    glb g;
    CHECK(glb_read(out_path(file), &g), "%s: not a readable .glb", file);
    if (!g.json) {
        glb_free(&g);
        return;
    }
    const cJSON *lm = material_named(&g, leaf), *bm = material_named(&g, bark);
    CHECK(lm && bm, "%s: materials %s and %s", file, leaf, bark);
    if (lm) {
        const char *mode = str(lm, "alphaMode");
        double cutoff = 0.5; /* glTF's default when absent */
        num(lm, "alphaCutoff", &cutoff);
        CHECK(mode && !strcmp(mode, "MASK") && cutoff == 0.5, "%s: %s alphaMode %s cutoff %g", file, leaf,
              mode ? mode : "OPAQUE", cutoff);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(lm, "doubleSided")), "%s: %s not double sided", file, leaf);
        const cJSON *f = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(lm, "pbrMetallicRoughness"),
                                                          "baseColorFactor");
        CHECK(!f || (cJSON_GetArrayItem(f, 0)->valuedouble == 1 && cJSON_GetArrayItem(f, 1)->valuedouble == 1 &&
                     cJSON_GetArrayItem(f, 2)->valuedouble == 1),
              "%s: %s baseColorFactor is not white: the texture's colour would be darkened", file, leaf);
        int bt = base_texture(lm), nt = normal_texture(lm);
        CHECK(bt >= 0 && nt >= 0 && bt != nt, "%s: %s base %d normal %d textures", file, leaf, bt, nt);
        CHECK(wrap_of(&g, bt) == 33071, "%s: %s atlas sampler must clamp (wrap %d)", file, leaf, wrap_of(&g, bt));
        int w = 0, h = 0, ch = 0;
        unsigned char *px = bt >= 0 ? texture_pixels(&g, bt, &w, &h, &ch, NULL) : NULL;
        CHECK(px && w == 128 && h == 128 && ch == 4, "%s: %s base colour decodes as 128 x 128 RGBA (%d x %d x %d)", file,
              leaf, w, h, ch);
        if (px && ch == 4) {
            banyan_atlas_layout L;
            CHECK(banyan_texture_layout(leaf_kind, &L, NULL) == BANYAN_OK, "layout");
            long clear = 0, solid = 0, empty_cells = 0;
            for (int32_t r = 0; r < L.rows; r++)
                for (int32_t c = 0; c < L.cols; c++) {
                    long in_cell = 0;
                    for (int y = r * h / L.rows; y < (r + 1) * h / L.rows; y++)
                        for (int x = c * w / L.cols; x < (c + 1) * w / L.cols; x++) {
                            unsigned a = px[4 * ((size_t)y * w + x) + 3];
                            clear += a < 128;
                            solid += a >= 128;
                            in_cell += a >= 128;
                        }
                    empty_cells += in_cell == 0;
                }
            double share = (double)solid / (double)(clear + solid);
            CHECK(share > 0.05 && share < 0.95, "%s: %s atlas is %.0f %% opaque: no leaf shapes", file, leaf, 100 * share);
            CHECK(empty_cells == 0, "%s: %s atlas has %ld cells without a leaf", file, leaf, empty_cells);
        }
        stbi_image_free(px);
        px = nt >= 0 ? texture_pixels(&g, nt, &w, &h, &ch, NULL) : NULL;
        CHECK(px && w == 128 && h == 128 && ch == 3, "%s: %s normal map decodes as 128 x 128 RGB", file, leaf);
        stbi_image_free(px);
    }
    if (bm) {
        const char *mode = str(bm, "alphaMode");
        CHECK(!mode || !strcmp(mode, "OPAQUE"), "%s: %s alphaMode %s", file, bark, mode);
        int bt = base_texture(bm), nt = normal_texture(bm);
        CHECK(bt >= 0 && nt >= 0, "%s: %s textures %d %d", file, bark, bt, nt);
        CHECK(wrap_of(&g, bt) == 10497, "%s: %s bark sampler must repeat", file, bark);
        int w = 0, h = 0, ch = 0;
        unsigned char *px = bt >= 0 ? texture_pixels(&g, bt, &w, &h, &ch, NULL) : NULL;
        CHECK(px && w == 128 && h == 128 && (ch == 4 || ch == 3), "%s: %s base colour decodes", file, bark);
        long clear = 0;
        for (long i = 0; px && ch == 4 && i < (long)w * h; i++) clear += px[4 * i + 3] < 255;
        CHECK(clear == 0, "%s: %s bark has %ld texels not opaque", file, bark, clear);
        stbi_image_free(px);
    }
    /* Every primitive of a textured material has the tangents its normal map needs. */
    const cJSON *mesh, *prim;
    int missing = 0;
    cJSON_ArrayForEach(mesh, arr(&g, "meshes")) {
        cJSON_ArrayForEach(prim, cJSON_GetObjectItemCaseSensitive(mesh, "primitives")) {
            const cJSON *at = cJSON_GetObjectItemCaseSensitive(prim, "attributes");
            missing += !cJSON_GetObjectItemCaseSensitive(at, "TANGENT") || !cJSON_GetObjectItemCaseSensitive(at, "TEXCOORD_0");
        }
    }
    CHECK(missing == 0, "%s: %d primitives without TANGENT or TEXCOORD_0", file, missing);
    glb_free(&g);
}

/* Leaf cards: each card's uvs lie in one atlas cell and the cards use
 * several cells; leaves carry varied vertex colours in [0, 1], one per
 * card; bark vertices are white. */
static void check_cards(const banyan_mesh *m, int32_t kind, const char *what) {
    banyan_atlas_layout L;
    if (banyan_texture_layout(kind, &L, NULL) != BANYAN_OK || !m) return;
    CHECK(m->colors != NULL, "%s: no vertex colours", what);
    if (!m->colors || m->part_count < 2) return;
    const banyan_part *bark = &m->parts[0], *leaf = &m->parts[1];
    long not_white = 0;
    for (uint32_t v = bark->vertex_offset; v < bark->vertex_offset + bark->vertex_count; v++)
        for (int c = 0; c < 4; c++) not_white += m->colors[4 * v + c] != 1.0f;
    CHECK(not_white == 0, "%s: %ld bark colour components are not 1 (they would tint the texture)", what, not_white);
    /* Cards are the leaf part's triangles' connected runs: keyaki 4
     * vertices, ivy 13, consecutive. */
    uint32_t per = kind == BANYAN_TEX_KEYAKI_LEAF ? 4 : 13;
    CHECK(leaf->vertex_count % per == 0, "%s: %u leaf vertices, not whole cards of %u", what, leaf->vertex_count, per);
    int used[64] = {0};
    long straddle = 0, mixed = 0, out_of_range = 0, distinct = 0;
    float prev[4] = {-1, -1, -1, -1};
    for (uint32_t c0 = leaf->vertex_offset; c0 + per <= leaf->vertex_offset + leaf->vertex_count; c0 += per) {
        double u = m->uvs[2 * c0], v = m->uvs[2 * c0 + 1];
        int cu = (int)floor(u * L.cols + 1e-6), cv = (int)floor(v * L.rows + 1e-6);
        if (cu >= L.cols) cu = L.cols - 1;
        if (cv >= L.rows) cv = L.rows - 1;
        /* Keyaki's bottom row (v < 0.25): spray cells two cells wide
         * (textures/leaf_look.h). */
        int span = kind == BANYAN_TEX_KEYAKI_LEAF && cv == 0 ? 2 : 1;
        cu -= cu % span;
        for (uint32_t k = 0; k < per; k++) {
            double a = m->uvs[2 * (c0 + k)] * L.cols - cu, b = m->uvs[2 * (c0 + k) + 1] * L.rows - cv;
            straddle += a < -1e-4 || a > span + 1e-4 || b < -1e-4 || b > 1 + 1e-4;
            for (int c = 0; c < 4; c++) {
                float x = m->colors[4 * (c0 + k) + c];
                out_of_range += !(x >= 0.0f && x <= 1.0f);
                mixed += x != m->colors[4 * c0 + c];
            }
        }
        if (cv * L.cols + cu < 64) used[cv * L.cols + cu] = 1;
        distinct += memcmp(prev, m->colors + 4 * c0, sizeof prev) != 0;
        memcpy(prev, m->colors + 4 * c0, sizeof prev);
    }
    int cells = 0;
    for (int i = 0; i < 64; i++) cells += used[i];
    long cards = leaf->vertex_count / per;
    CHECK(straddle == 0, "%s: %ld card uvs leave their atlas cell", what, straddle);
    int want = kind == BANYAN_TEX_KEYAKI_LEAF ? L.cols * (L.rows - 1) + L.cols / 2 : L.cols * L.rows; /* sprays: 2 */
    CHECK(cards >= 8L * L.cols * L.rows && cells == want, "%s: %ld cards use %d of %d cells", what, cards, cells, want);
    CHECK(out_of_range == 0 && mixed == 0, "%s: leaf colours out of [0, 1] (%ld) or varying within a card (%ld)", what,
          out_of_range, mixed);
    CHECK(distinct > cards / 2, "%s: %ld colour changes over %ld cards: no per-leaf variation", what, distinct, cards);
}

/* Alpha where the leaves are: the ivy atlas, sampled at each leaf card's
 * centre and halfway from it to the tip (outline point 6 is the tip), is
 * opaque; sampled at the card's outline corners it is mostly clear. */
static void check_ivy_alpha(const banyan_mesh *m, const char *file) {
    glb g;
    if (!m || m->part_count < 2 || !glb_read(out_path(file), &g)) {
        CHECK(0, "%s: cannot read", file);
        return;
    }
    int w = 0, h = 0, ch = 0;
    unsigned char *px = texture_pixels(&g, base_texture(material_named(&g, "ivy_leaf")), &w, &h, &ch, NULL);
    CHECK(px && ch == 4, "%s: ivy atlas", file);
    const banyan_part *leaf = &m->parts[1];
    long inside = 0, cards = 0;
    for (uint32_t c0 = leaf->vertex_offset; px && ch == 4 && c0 + 13 <= leaf->vertex_offset + leaf->vertex_count;
         c0 += 13, cards++) {
        const float *uc = m->uvs + 2 * c0, *ut = m->uvs + 2 * (c0 + 1 + 6);
        double s[2][2] = {{uc[0], uc[1]}, {0.5 * (uc[0] + ut[0]), 0.5 * (uc[1] + ut[1])}};
        for (int k = 0; k < 2; k++) {
            int x = (int)(s[k][0] * w), y = (int)((1.0 - s[k][1]) * h); /* banyan v runs up the image */
            x = x < 0 ? 0 : x >= w ? w - 1 : x;
            y = y < 0 ? 0 : y >= h ? h - 1 : y;
            inside += px[4 * ((size_t)y * w + x) + 3] >= 128;
        }
    }
    CHECK(cards > 0 && inside >= (long)(2 * cards * 0.95), "%s: %ld of %ld leaf centre samples opaque", file, inside,
          2 * cards);
    stbi_image_free(px);
    glb_free(&g);
}

/* Positions, normals, indices and counts equal: the same geometry. */
static int same_geometry(const banyan_mesh *a, const banyan_mesh *b) {
    return a && b && a->vertex_count == b->vertex_count && a->index_count == b->index_count &&
           !memcmp(a->positions, b->positions, sizeof(float) * 3 * a->vertex_count) &&
           !memcmp(a->normals, b->normals, sizeof(float) * 3 * a->vertex_count) &&
           !memcmp(a->indices, b->indices, sizeof(uint32_t) * a->index_count) &&
           !memcmp(a->uvs, b->uvs, sizeof(float) * 2 * a->vertex_count);
}

static int files_equal(const char *x, const char *y) {
    size_t n1 = 0, n2 = 0;
    char *a = test_read_file(x, &n1), *b = test_read_file(y, &n2);
    int eq = a && b && n1 == n2 && !memcmp(a, b, n1);
    free(a);
    free(b);
    return eq;
}

static int count_of(const char *file, const char *key) {
    glb g;
    int n = -1;
    if (glb_read(out_path(file), &g)) n = cJSON_GetArraySize(arr(&g, key));
    glb_free(&g);
    return n;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    snprintf(g_dir, sizeof g_dir, "%s", argv[1]);
    banyan_error err = {0, ""};
    banyan_gltf_options o = small_textures();

    banyan_mesh *ks = keyaki(BANYAN_SEASON_SUMMER, 1), *ka = keyaki(BANYAN_SEASON_AUTUMN, 1);
    banyan_mesh *is = ivy(BANYAN_SEASON_SUMMER), *ia = ivy(BANYAN_SEASON_AUTUMN);

    /* Materials the generators set. */
    if (ks && ka && is && ia) {
        CHECK(ks->materials[0].texture == BANYAN_TEX_KEYAKI_BARK && ks->materials[1].texture == BANYAN_TEX_KEYAKI_LEAF &&
                  is->materials[0].texture == BANYAN_TEX_IVY_STEM && is->materials[1].texture == BANYAN_TEX_IVY_LEAF,
              "generators name their textures");
        CHECK(ks->materials[1].alpha_cutoff == 0.5f && ks->materials[0].alpha_cutoff == 0.0f &&
                  ks->materials[1].translucency > 0.0f && is->materials[1].alpha_cutoff == 0.5f,
              "leaves alpha-tested and translucent, bark opaque");
        CHECK(ks->materials[1].season == BANYAN_SEASON_SUMMER && ka->materials[1].season == BANYAN_SEASON_AUTUMN &&
                  ia->materials[1].season == BANYAN_SEASON_AUTUMN,
              "season on the leaf material");
        CHECK(memcmp(ks->materials[1].base_color, ka->materials[1].base_color, sizeof(float) * 3) != 0 &&
                  ka->materials[1].base_color[0] > ka->materials[1].base_color[1],
              "autumn keyaki flat colour is not the summer one, or not reddish");
        /* The season swaps the material, not the geometry. */
        CHECK(same_geometry(ks, ka), "keyaki: summer and autumn geometry differ");
        CHECK(same_geometry(is, ia), "ivy: summer and autumn geometry differ");
        CHECK(banyan_mesh_hash(ks) != banyan_mesh_hash(ka), "keyaki: the season changed nothing");
        check_cards(ks, BANYAN_TEX_KEYAKI_LEAF, "keyaki");
        check_cards(is, BANYAN_TEX_IVY_LEAF, "ivy");
    }

    /* Textures in the files. */
    CHECK(write1("tex_keyaki_summer.glb", ks, &o, &err) == BANYAN_OK, "write keyaki: %s", err.message);
    CHECK(write1("tex_keyaki_autumn.glb", ka, &o, &err) == BANYAN_OK, "write keyaki autumn: %s", err.message);
    CHECK(write1("tex_ivy_summer.glb", is, &o, &err) == BANYAN_OK, "write ivy: %s", err.message);
    CHECK(write1("tex_ivy_autumn.gltf", ia, &o, &err) == BANYAN_OK, "write ivy autumn (.gltf): %s", err.message);
    check_materials("tex_keyaki_summer.glb", "keyaki_leaf", "keyaki_bark", BANYAN_TEX_KEYAKI_LEAF);
    check_materials("tex_keyaki_autumn.glb", "keyaki_leaf", "keyaki_bark", BANYAN_TEX_KEYAKI_LEAF);
    check_materials("tex_ivy_summer.glb", "ivy_leaf", "ivy_stem", BANYAN_TEX_IVY_LEAF);
    check_ivy_alpha(is, "tex_ivy_summer.glb");
    {
        /* The ivy's leaves glossy (docs/ivy.md "Leaf material"), its stems matte. */
        glb g;
        double rl = -1, rs = -1;
        if (glb_read(out_path("tex_ivy_summer.glb"), &g)) {
            const cJSON *l = material_named(&g, "ivy_leaf"), *st = material_named(&g, "ivy_stem");
            const cJSON *pl = l ? cJSON_GetObjectItemCaseSensitive(l, "pbrMetallicRoughness") : NULL,
                        *ps = st ? cJSON_GetObjectItemCaseSensitive(st, "pbrMetallicRoughness") : NULL;
            if (pl) num(pl, "roughnessFactor", &rl);
            if (ps) num(ps, "roughnessFactor", &rs);
        }
        glb_free(&g);
        CHECK(rl >= 0.25 && rl <= 0.45 && rs >= 0.7, "tex_ivy_summer.glb: roughnessFactor ivy_leaf %g (want 0.25-0.45), ivy_stem %g (want >= 0.7)",
              rl, rs);
    }
    CHECK(count_of("tex_keyaki_summer.glb", "images") == 4, "keyaki: %d images, want leaf + bark, base + normal",
          count_of("tex_keyaki_summer.glb", "images"));
    {
        /* Summer and autumn leaves differ in their images; the bark is the same. */
        glb a, b;
        if (glb_read(out_path("tex_keyaki_summer.glb"), &a) && glb_read(out_path("tex_keyaki_autumn.glb"), &b)) {
            int wa, ha, ca, wb, hb, cb;
            int ta = base_texture(material_named(&a, "keyaki_leaf")), tb = base_texture(material_named(&b, "keyaki_leaf"));
            unsigned char *pa = texture_pixels(&a, ta, &wa, &ha, &ca, NULL), *pb = texture_pixels(&b, tb, &wb, &hb, &cb, NULL);
            CHECK(pa && pb && wa == wb && ha == hb && ca == cb && memcmp(pa, pb, (size_t)wa * ha * ca) != 0,
                  "summer and autumn keyaki atlases are the same image");
            stbi_image_free(pa);
            stbi_image_free(pb);
            int ba = base_texture(material_named(&a, "keyaki_bark")), bb = base_texture(material_named(&b, "keyaki_bark"));
            pa = texture_pixels(&a, ba, &wa, &ha, &ca, NULL);
            pb = texture_pixels(&b, bb, &wb, &hb, &cb, NULL);
            CHECK(pa && pb && wa == wb && ca == cb && !memcmp(pa, pb, (size_t)wa * ha * ca), "bark changed with the season");
            stbi_image_free(pa);
            stbi_image_free(pb);
        }
        glb_free(&a);
        glb_free(&b);
    }

    /* One image per (kind, season, map), shared by every mesh using it. */
    {
        banyan_mesh *k2 = keyaki(BANYAN_SEASON_SUMMER, 2);
        const banyan_mesh *four[4] = {ks, k2, ka, is};
        CHECK(banyan_gltf_write_ex(out_path("tex_shared.glb"), four, NULL, 4, &o, &err) == BANYAN_OK, "shared: %s",
              err.message);
        /* keyaki leaf summer + autumn, keyaki bark, ivy leaf, ivy stem: 5 textures, 10 images */
        CHECK(count_of("tex_shared.glb", "images") == 10 && count_of("tex_shared.glb", "textures") == 10,
              "%d images for 5 textures", count_of("tex_shared.glb", "images"));
        CHECK(count_of("tex_shared.glb", "samplers") == 2, "%d samplers, want repeat + clamp",
              count_of("tex_shared.glb", "samplers"));
        banyan_mesh_free(k2);
    }

    /* Same seed, same bytes; another texture seed, other images. */
    CHECK(write1("tex_keyaki_again.glb", ks, &o, &err) == BANYAN_OK, "write again: %s", err.message);
    CHECK(files_equal(out_path("tex_keyaki_summer.glb"), out_path("tex_keyaki_again.glb")),
          "the same mesh and options gave different bytes");
    banyan_gltf_options o2 = o;
    o2.texture_seed = 7;
    CHECK(write1("tex_keyaki_seed7.glb", ks, &o2, &err) == BANYAN_OK, "write seed 7: %s", err.message);
    CHECK(!files_equal(out_path("tex_keyaki_summer.glb"), out_path("tex_keyaki_seed7.glb")),
          "texture_seed 7 gave the same file as seed 1");

    /* Textures off: no image, no texture; flat colours, geometry kept. */
    banyan_gltf_options off = o;
    off.textures = 0;
    CHECK(write1("tex_keyaki_off.glb", ks, &off, &err) == BANYAN_OK, "write off: %s", err.message);
    CHECK(count_of("tex_keyaki_off.glb", "images") <= 0 && count_of("tex_keyaki_off.glb", "textures") <= 0 &&
              count_of("tex_keyaki_off.glb", "samplers") <= 0,
          "textures off wrote %d images", count_of("tex_keyaki_off.glb", "images"));
    {
        glb g;
        if (glb_read(out_path("tex_keyaki_off.glb"), &g)) {
            const cJSON *lm = material_named(&g, "keyaki_leaf");
            const cJSON *f = lm ? cJSON_GetObjectItemCaseSensitive(
                                      cJSON_GetObjectItemCaseSensitive(lm, "pbrMetallicRoughness"), "baseColorFactor")
                                : NULL;
            CHECK(f && fabs(cJSON_GetArrayItem(f, 1)->valuedouble - ks->materials[1].base_color[1]) < 1e-6,
                  "textures off: the leaf keeps its flat colour");
        }
        glb_free(&g);
        size_t n_off = 0, n_on = 0;
        char *a = test_read_file(out_path("tex_keyaki_off.glb"), &n_off), *b = test_read_file(out_path("tex_keyaki_summer.glb"), &n_on);
        CHECK(a && b && n_off < n_on, "textures off (%zu bytes) is not smaller than on (%zu)", n_off, n_on);
        free(a);
        free(b);
    }

    /* The default options: textures on at 1024. */
    banyan_gltf_options d;
    memset(&d, 0x5a, sizeof d);
    banyan_gltf_options_init(&d);
    CHECK(d.textures == 1 && d.texture_size == 1024 && d.texture_seed == 1, "defaults %d %d %llu", d.textures,
          d.texture_size, (unsigned long long)d.texture_seed);
    CHECK(banyan_sizeof_gltf_options() == sizeof(banyan_gltf_options), "sizeof");

    /* Bad options: refused, named, and no file. */
    struct {
        int32_t textures, size;
        const char *names;
    } bad[] = {{1, 0, "texture_size"},    {1, 100, "texture_size"}, {1, 16384, "texture_size"},
               {1, 32, "texture_size"},   {1, -64, "texture_size"}, {2, 128, "textures"},
               {-1, 128, "textures"},     {0, 0, "texture_size"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        banyan_gltf_options b = o;
        b.textures = bad[i].textures;
        b.texture_size = bad[i].size;
        const char *path = out_path("tex_bad.glb");
        remove(path);
        banyan_error e = {0, ""};
        banyan_status s = write1("tex_bad.glb", ks, &b, &e);
        FILE *f = fopen(path, "rb");
        CHECK(s == BANYAN_E_RANGE && strstr(e.message, bad[i].names) && !f, "textures %d size %d: status %d '%s'%s",
              bad[i].textures, bad[i].size, s, e.message, f ? ", file written" : "");
        if (f) fclose(f);
        remove(path);
    }
    /* A material naming a texture kind that does not exist. */
    if (ks) {
        ks->materials[1].texture = BANYAN_TEX_COUNT;
        banyan_error e = {0, ""};
        CHECK(write1("tex_bad.glb", ks, &o, &e) == BANYAN_E_RANGE && strstr(e.message, "materials[1].texture"),
              "bad texture kind: '%s'", e.message);
        ks->materials[1].texture = BANYAN_TEX_KEYAKI_LEAF;
        ks->materials[1].season = 5;
        CHECK(write1("tex_bad.glb", ks, &o, &e) == BANYAN_E_RANGE && strstr(e.message, "materials[1].season"),
              "bad season: '%s'", e.message);
        ks->materials[1].season = 0;
        remove(out_path("tex_bad.glb"));
    }

    banyan_mesh_free(ks);
    banyan_mesh_free(ka);
    banyan_mesh_free(is);
    banyan_mesh_free(ia);
    return check_done("test_gltf_textures");
}
