/* test_textures.c - the texture calls of banyan/textures.h,
 * by invariants, at 64, 256 and 1024 pixels: image sizes and channels; leaf atlases have alpha where
 * each cell's leaf is (its centre, or for keyaki some pixel of the cell's
 * middle third) and alpha 0 at every cell corner and along its border;
 * keyaki's 4 x 4 leaves lie in the box textures/leaf_look.h gives the mesh
 * and are 1.8-3.2 times longer than wide; bark is opaque and tiles (the wrap-around column and row steps
 * are like the steps inside); normal maps are unit vectors pointing out;
 * the PNG decodes (stb_image) to the same pixels; the same params give the
 * same bytes (twice, and from two threads at once), another seed other
 * bytes; bad input is refused naming the field, outputs NULL. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "textures/leaf_look.h"

#if defined(__GNUC__)
#  pragma GCC diagnostic push
#  pragma GCC diagnostic ignored "-Wunused-function"
#  pragma GCC diagnostic ignored "-Wsign-compare"
#  pragma GCC diagnostic ignored "-Wpedantic"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#include <stb/stb_image.h>
#if defined(__GNUC__)
#  pragma GCC diagnostic pop
#  pragma GCC diagnostic ignored "-Wunused-function"
#endif

static const char *const names[BANYAN_TEX_COUNT] = {"none", "keyaki_leaf", "ivy_leaf", "keyaki_bark", "fig_bark",
                                                    "ivy_stem"};

static uint64_t fnv(const uint8_t *p, size_t n) {
    uint64_t h = 1469598103934665603ULL;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ULL;
    return h;
}

static int is_leaf(int kind) { return kind == BANYAN_TEX_KEYAKI_LEAF || kind == BANYAN_TEX_IVY_LEAF; }

static void gen(int kind, int season, int size, uint64_t seed, banyan_image **bc, banyan_image **nm) {
    banyan_texture_params p;
    banyan_texture_params_init(&p);
    p.kind = kind;
    p.season = season;
    p.size = size;
    p.seed = seed;
    banyan_error e;
    banyan_status s = banyan_texture_generate(&p, bc, nm, &e);
    CHECK(s == BANYAN_OK, "%s season %d size %d: %s", names[kind], season, size, e.message);
}

static uint8_t alpha_at(const banyan_image *im, int x, int y) { return im->pixels[4 * ((size_t)y * im->width + x) + 3]; }

/* Leaf atlases: a leaf in each cell, clear corners and border. */
static void check_atlas(int kind, int season, const banyan_image *im) {
    banyan_atlas_layout L;
    banyan_error e;
    CHECK(banyan_texture_layout(kind, &L, &e) == BANYAN_OK, "%s", e.message);
    CHECK(L.cols >= 1 && L.rows >= 1 && L.cols * L.rows >= 4, "%s: %d x %d cells", names[kind], L.cols, L.rows);
    CHECK(L.leaf_aspect > 0.2f && L.leaf_aspect <= 1.0f, "%s: aspect %g", names[kind], L.leaf_aspect);
    int cw = (int)im->width / L.cols, ch = (int)im->height / L.rows;
    /* Keyaki's bottom row: sprays (check_keyaki_sprays). */
    int rows = kind == BANYAN_TEX_KEYAKI_LEAF ? L.rows - 1 : L.rows;
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < L.cols; i++) {
            int x0 = i * cw, y0 = j * ch, x1 = x0 + cw - 1, y1 = y0 + ch - 1;
            int cx = x0 + cw / 2, cy = y0 + ch / 2;
            if (kind == BANYAN_TEX_IVY_LEAF) {
                CHECK(alpha_at(im, cx, cy) == 255, "%s s%d cell %d,%d: centre alpha %d", names[kind], season, i, j,
                      alpha_at(im, cx, cy));
            } else {
                /* A keyaki leaf is narrower than the cell: somewhere in its middle third. */
                int found = 0;
                for (int y = y0 + ch / 3; y < y0 + 2 * ch / 3 && !found; y++)
                    for (int x = x0 + cw / 3; x < x0 + 2 * cw / 3; x++)
                        if (alpha_at(im, x, y) == 255) found = 1;
                CHECK(found, "%s s%d cell %d,%d: no opaque pixel in the middle third", names[kind], season, i, j);
            }
            /* The petiole or twig reaches the bottom centre (the card's anchor). */
            CHECK(alpha_at(im, cx, y1 - 2) > 0 || alpha_at(im, cx - 1, y1 - 2) > 0, "%s s%d cell %d,%d: nothing at the bottom centre",
                  names[kind], season, i, j);
            CHECK(alpha_at(im, x0, y0) == 0 && alpha_at(im, x1, y0) == 0 && alpha_at(im, x0, y1) == 0 &&
                      alpha_at(im, x1, y1) == 0,
                  "%s s%d cell %d,%d: a corner is not transparent", names[kind], season, i, j);
            int border = 0;
            for (int t = 0; t < cw; t++)
                border += alpha_at(im, x0 + t, y0) + alpha_at(im, x0 + t, y1) + alpha_at(im, x0, y0 + t) + alpha_at(im, x1, y0 + t);
            CHECK(border == 0, "%s s%d cell %d,%d: leaf touches the cell border", names[kind], season, i, j);
            long covered = 0;
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++) covered += alpha_at(im, x, y) > 127;
            double frac = (double)covered / ((double)cw * ch);
            CHECK(frac > 0.12 && frac < 0.8, "%s s%d cell %d,%d: leaf covers %.2f of the cell", names[kind], season, i,
                  j, frac);
        }
}

/* Keyaki: 4 x 4 cells of one leaf each, where leaf_look.h says
 * the mesh expects it. Per cell (u right, v up, pixel centres): every
 * pixel with any alpha lies within LEAF_KEYAKI_HALF_U of u = 0.5 and below
 * LEAF_KEYAKI_BLADE_V1, a 1.5 pixel allowance for the antialiased edge;
 * the opaque (alpha > 0.5) blade's top is near BLADE_V1 and its lowest row
 * (wider than the petiole) near BLADE_V0; the blade is 1.8-3.2 times longer
 * than its widest extent, which reaches half of the box's width or more,
 * and the broadest leaf of the atlas reaches 80 % of it. */
static void check_keyaki_cells(int season, const banyan_image *im) {
    banyan_atlas_layout L;
    CHECK(banyan_texture_layout(BANYAN_TEX_KEYAKI_LEAF, &L, NULL) == BANYAN_OK, "keyaki layout");
    CHECK(L.cols == 4 && L.rows == 4 && L.leaf_aspect == 1.0f, "keyaki layout %d x %d, aspect %g", L.cols, L.rows,
          L.leaf_aspect);
    if (L.cols != 4 || L.rows != 4) return;
    const int cw = (int)im->width / 4;
    const double px = 1.0 / cw, allow = 1.5 * px, hu = LEAF_KEYAKI_HALF_U;
    double broadest = 0.0;
    for (int j = 0; j < 3; j++) /* the bottom row holds sprays */
        for (int i = 0; i < 4; i++) {
            int x0 = i * cw, y0 = j * cw, opaque = 0, outside = 0;
            double top = -1.0, umin = 1.0, umax = 0.0, base = 2.0;
            for (int y = y0; y < y0 + cw; y++) {
                double v = 1.0 - (y - y0 + 0.5) * px, rmin = 1.0, rmax = 0.0;
                for (int x = x0; x < x0 + cw; x++) {
                    uint8_t a = alpha_at(im, x, y);
                    if (!a) continue;
                    double u = (x - x0 + 0.5) * px;
                    if (fabs(u - 0.5) > hu + allow || v > LEAF_KEYAKI_BLADE_V1 + allow) outside++;
                    if (a <= 127) continue;
                    opaque++;
                    if (v > top) top = v;
                    rmin = u < rmin ? u : rmin, rmax = u > rmax ? u : rmax;
                }
                if (rmax < rmin) continue;
                umin = rmin < umin ? rmin : umin, umax = rmax > umax ? rmax : umax;
                /* A row wider than the petiole (under 0.03 of the cell) is blade. */
                if (rmax - rmin + px > 0.05 + 2 * px && v < base) base = v;
            }
            CHECK(opaque > 0 && outside == 0, "keyaki s%d %d px cell %d,%d: %d opaque pixels, %d outside the leaf box",
                  season, (int)im->width, i, j, opaque, outside);
            if (!opaque) continue;
            double tol = 0.03 + 2 * px;
            CHECK(top > LEAF_KEYAKI_BLADE_V1 - tol, "keyaki s%d %d px cell %d,%d: the tip at v %.3f, not near %.2f",
                  season, (int)im->width, i, j, top, LEAF_KEYAKI_BLADE_V1);
            CHECK(fabs(base - LEAF_KEYAKI_BLADE_V0) < tol, "keyaki s%d %d px cell %d,%d: the blade starts at v %.3f, not near %.2f",
                  season, (int)im->width, i, j, base, LEAF_KEYAKI_BLADE_V0);
            double width = umax - umin + px, length = top - base + px;
            broadest = width > broadest ? width : broadest;
            /* Below 64 pixels a cell the blade is too few pixels for widths and ratios. */
            if (cw < 64) continue;
            CHECK(width > 0.5 * 2 * hu, "keyaki s%d %d px cell %d,%d: %.3f wide, under half the box's %.2f", season,
                  (int)im->width, i, j, width, 2 * hu);
            CHECK(length / width >= 1.8 && length / width <= 3.2, "keyaki s%d %d px cell %d,%d: length / width %.2f",
                  season, (int)im->width, i, j, length / width);
        }
    if (cw >= 64)
        CHECK(broadest > 0.8 * 2 * hu, "keyaki s%d %d px: the broadest leaf is %.3f wide, under 0.8 of the box's %.2f",
              season, (int)im->width, broadest, 2 * hu);
}

/* Keyaki's spray cells (leaf_look.h LEAF_KEYAKI_SPRAY_*): the bottom row,
 * LEAF_KEYAKI_SPRAYS cells each LEAF_KEYAKI_SPRAY_ASPECT times as wide as
 * tall. In each: the twig's base (u = U0 on the centre line) drawn, clear
 * corners and border, the leaves covering 0.3-0.75 of the cell. */
static void check_keyaki_sprays(int season, const banyan_image *im) {
    const int n = (int)im->width, h = n / 4, w = n / LEAF_KEYAKI_SPRAYS;
    CHECK(fabs((double)w / h - LEAF_KEYAKI_SPRAY_ASPECT) < 1e-9, "keyaki sprays: %d x %d px", w, h);
    for (int i = 0; i < LEAF_KEYAKI_SPRAYS; i++) {
        int x0 = i * w, y0 = n - h, x1 = x0 + w - 1, y1 = n - 1;
        int bx = x0 + (int)(LEAF_KEYAKI_SPRAY_U0 * w + 1.5), by = y0 + (int)((1.0 - LEAF_KEYAKI_SPRAY_V) * h);
        CHECK(alpha_at(im, bx, by) > 0 || alpha_at(im, bx, by - 1) > 0, "keyaki s%d spray %d: no twig at its base",
              season, i);
        int border = 0;
        for (int t = 0; t < w; t++) border += alpha_at(im, x0 + t, y0) + alpha_at(im, x0 + t, y1);
        for (int t = 0; t < h; t++) border += alpha_at(im, x0, y0 + t) + alpha_at(im, x1, y0 + t);
        CHECK(border == 0, "keyaki s%d spray %d: a leaf touches the cell border", season, i);
        long covered = 0;
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++) covered += alpha_at(im, x, y) > 127;
        double frac = (double)covered / ((double)w * h);
        CHECK(frac > 0.3 && frac < 0.75 && fabs(frac - LEAF_KEYAKI_SPRAY_COVER) < 0.12, /* small atlases lose edges */
              "keyaki s%d spray %d: leaves cover %.2f of the cell (LEAF_KEYAKI_SPRAY_COVER %.2f)", season, i, frac,
              LEAF_KEYAKI_SPRAY_COVER);
    }
}

/* Mean absolute step between two columns (or rows) a and b, all channels. */
static double step(const banyan_image *im, int a, int b, int rows) {
    int n = (int)im->width, c = (int)im->channels;
    double sum = 0;
    for (int t = 0; t < n; t++)
        for (int k = 0; k < c; k++) {
            size_t pa = rows ? ((size_t)a * n + t) : ((size_t)t * n + a);
            size_t pb = rows ? ((size_t)b * n + t) : ((size_t)t * n + b);
            sum += fabs((double)im->pixels[c * pa + k] - (double)im->pixels[c * pb + k]);
        }
    return sum / n;
}

/* A tile's wrap-around step (last column to first) is like the steps
 * next to it (a seam stands out from its neighbours, while a fissure that
 * happens to run along the edge raises them all) and within the steps
 * inside the image. */
static int seam_ok(const banyan_image *im, int a, int rows, double *seam, double *near) {
    int n = (int)im->width;
    int b = (a + 1) % n;
    *seam = step(im, a, b, rows);
    double l = step(im, (a + n - 1) % n, a, rows), r = step(im, b, (b + 1) % n, rows);
    *near = l > r ? l : r;
    return *seam <= 1.6 * *near + 1.0;
}

static void check_tiles(int kind, const banyan_image *im, const char *what) {
    int n = (int)im->width;
    for (int rows = 0; rows < 2; rows++) {
        double seam, near, mx = 0;
        int ok = seam_ok(im, n - 1, rows, &seam, &near);
        for (int a = 0; a < n - 1; a++) {
            double s = step(im, a, a + 1, rows);
            if (s > mx) mx = s;
        }
        CHECK(ok && seam <= mx, "%s %s: %s seam step %.2f vs %.2f next to it, inner max %.2f", names[kind], what,
              rows ? "top/bottom" : "left/right", seam, near, mx);
    }
    /* The check can fail: columns x >= n/2 taken from x + n/4 put a cut
     * between columns n/2 - 1 and n/2. From 256 px: at 64 a flake is four
     * pixels across, and neighbouring columns differ as much as a cut. */
    if (kind == BANYAN_TEX_KEYAKI_BARK && !strcmp(what, "colour") && n >= 256) {
        banyan_image sw = *im;
        int c = (int)im->channels;
        sw.pixels = malloc((size_t)n * n * c);
        for (int y = 0; y < n && sw.pixels; y++)
            for (int x = 0; x < n; x++)
                memcpy(sw.pixels + c * ((size_t)y * n + x),
                       im->pixels + c * ((size_t)y * n + (x < n / 2 ? x : (x + n / 4) % n)), (size_t)c);
        double seam = 0, near = 0;
        CHECK(sw.pixels && !seam_ok(&sw, n / 2 - 1, 0, &seam, &near),
              "%s %d px: the seam test does not see a cut (%.2f vs %.2f)", names[kind], n, seam, near);
        free(sw.pixels);
    }
}

static void check_opaque(int kind, const banyan_image *im) {
    size_t n = (size_t)im->width * im->height, bad = 0;
    for (size_t i = 0; i < n; i++) bad += im->pixels[4 * i + 3] != 255;
    CHECK(bad == 0, "%s: %zu pixels not opaque", names[kind], bad);
}

/* Unit normals with z > 0; leaves: flat (128,128,255) away from leaves
 * is not required, but some texels must tilt (the relief is there). */
static void check_normals(int kind, const banyan_image *nm) {
    size_t n = (size_t)nm->width * nm->height, bad = 0, tilted = 0;
    for (size_t i = 0; i < n; i++) {
        double x = nm->pixels[3 * i] / 127.5 - 1, y = nm->pixels[3 * i + 1] / 127.5 - 1, z = nm->pixels[3 * i + 2] / 127.5 - 1;
        double l = sqrt(x * x + y * y + z * z);
        if (fabs(l - 1) > 0.03 || z <= 0) bad++;
        if (z < 0.995) tilted++; /* about 6 degrees */
    }
    CHECK(bad == 0, "%s normal map: %zu texels not unit / not facing out", names[kind], bad);
    /* At 64 pixels the veins and wrinkles are under a texel: no relief to ask for. */
    if (nm->width >= 256) CHECK(tilted > n / 100, "%s normal map: only %zu of %zu texels tilt", names[kind], tilted, n);
}

static void check_png(const banyan_image *im, const char *what) {
    uint8_t *png = NULL;
    size_t len = 0;
    banyan_error e;
    CHECK(banyan_image_png(im, &png, &len, &e) == BANYAN_OK && png && len > 8, "%s png: %s", what, e.message);
    if (!png) return;
    CHECK(!memcmp(png, "\x89PNG\r\n\x1a\n", 8), "%s: not a PNG signature", what);
    int w = 0, h = 0, c = 0;
    uint8_t *dec = stbi_load_from_memory(png, (int)len, &w, &h, &c, 0);
    CHECK(dec && w == (int)im->width && h == (int)im->height && c == (int)im->channels, "%s: decoded %dx%dx%d", what,
          w, h, c);
    if (dec && w == (int)im->width && h == (int)im->height && c == (int)im->channels)
        CHECK(!memcmp(dec, im->pixels, (size_t)w * h * c), "%s: decoded pixels differ", what);
    stbi_image_free(dec);
    /* The same image gives the same bytes. */
    uint8_t *png2 = NULL;
    size_t len2 = 0;
    CHECK(banyan_image_png(im, &png2, &len2, &e) == BANYAN_OK, "%s", e.message);
    CHECK(png2 && len2 == len && !memcmp(png, png2, len), "%s: PNG bytes differ between two calls", what);
    banyan_png_free(png);
    banyan_png_free(png2);
}

/* ------------------------------------------------------------- threads */

typedef struct job { int kind, season; uint64_t hash_bc, hash_nm; } job;

static void *run_job(void *arg) {
    job *j = arg;
    banyan_texture_params p;
    banyan_texture_params_init(&p);
    p.kind = j->kind;
    p.season = j->season;
    p.size = 256;
    banyan_image *bc = NULL, *nm = NULL;
    if (banyan_texture_generate(&p, &bc, &nm, NULL) == BANYAN_OK) {
        j->hash_bc = fnv(bc->pixels, (size_t)bc->width * bc->height * bc->channels);
        j->hash_nm = fnv(nm->pixels, (size_t)nm->width * nm->height * nm->channels);
    }
    banyan_image_free(bc);
    banyan_image_free(nm);
    return NULL;
}

/* ------------------------------------------------------------ bad input */

static void bad(const char *what, int kind, int season, int size, int reserved, const char *needle) {
    banyan_texture_params p;
    banyan_texture_params_init(&p);
    p.kind = kind;
    p.season = season;
    p.size = size;
    p.reserved = reserved;
    banyan_image *bc = (banyan_image *)&p, *nm = (banyan_image *)&p; /* sentinels */
    banyan_error e;
    banyan_status s = banyan_texture_generate(&p, &bc, &nm, &e);
    CHECK(s == BANYAN_E_RANGE, "%s: status %s", what, banyan_status_name(s));
    CHECK(strstr(e.message, needle) != NULL, "%s: message '%s' lacks '%s'", what, e.message, needle);
    CHECK(bc == NULL && nm == NULL, "%s: outputs not NULL", what);
}

int main(void) {
    CHECK(banyan_sizeof_image() == sizeof(banyan_image), "sizeof image");
    CHECK(banyan_sizeof_texture_params() == sizeof(banyan_texture_params), "sizeof params");

    /* Every kind and season at two sizes. */
    const int sizes[] = {64, 256, 1024};
    for (int si = 0; si < 3; si++)
        for (int kind = BANYAN_TEX_NONE + 1; kind < BANYAN_TEX_COUNT; kind++)
            for (int season = 0; season < (is_leaf(kind) ? 2 : 1); season++) {
                banyan_image *bc = NULL, *nm = NULL;
                gen(kind, season, sizes[si], 1, &bc, &nm);
                if (!bc || !nm) continue;
                CHECK(bc->width == (uint32_t)sizes[si] && bc->height == bc->width && bc->channels == 4, "%s bc %ux%ux%u",
                      names[kind], bc->width, bc->height, bc->channels);
                CHECK(nm->width == bc->width && nm->height == bc->height && nm->channels == 3, "%s nm %ux%ux%u",
                      names[kind], nm->width, nm->height, nm->channels);
                if (is_leaf(kind)) {
                    check_atlas(kind, season, bc);
                    if (kind == BANYAN_TEX_KEYAKI_LEAF) check_keyaki_cells(season, bc), check_keyaki_sprays(season, bc);
                } else {
                    check_opaque(kind, bc);
                    check_tiles(kind, bc, "colour");
                    check_tiles(kind, nm, "normal");
                }
                check_normals(kind, nm);
                if (si == 0) {
                    check_png(bc, names[kind]);
                    check_png(nm, names[kind]);
                }
                /* Determinism: the same params again, then another seed. */
                banyan_image *bc2 = NULL, *nm2 = NULL;
                gen(kind, season, sizes[si], 1, &bc2, &nm2);
                size_t nb = (size_t)bc->width * bc->height;
                CHECK(bc2 && !memcmp(bc->pixels, bc2->pixels, nb * 4), "%s: colour differs between runs", names[kind]);
                CHECK(nm2 && !memcmp(nm->pixels, nm2->pixels, nb * 3), "%s: normal differs between runs", names[kind]);
                banyan_image_free(bc2);
                banyan_image_free(nm2);
                if (si == 0) {
                    gen(kind, season, sizes[si], 2, &bc2, NULL);
                    CHECK(bc2 && memcmp(bc->pixels, bc2->pixels, nb * 4), "%s: seed 2 gives the same image", names[kind]);
                    banyan_image_free(bc2);
                }
                banyan_image_free(bc);
                banyan_image_free(nm);
            }

    /* Summer and autumn atlases differ in colour, not only in noise: the
     * mean red/green ratio of the leaves rises in autumn. */
    for (int kind = BANYAN_TEX_KEYAKI_LEAF; kind <= BANYAN_TEX_IVY_LEAF; kind++) {
        double ratio[2];
        for (int season = 0; season < 2; season++) {
            banyan_image *bc = NULL;
            gen(kind, season, 256, 1, &bc, NULL);
            double r = 0, g = 0;
            for (size_t i = 0; bc && i < (size_t)bc->width * bc->height; i++)
                if (bc->pixels[4 * i + 3] == 255) r += bc->pixels[4 * i], g += bc->pixels[4 * i + 1];
            ratio[season] = r / (g + 1);
            banyan_image_free(bc);
        }
        CHECK(ratio[0] < 0.9 && ratio[1] > 1.1, "%s: red/green summer %.2f autumn %.2f", names[kind], ratio[0], ratio[1]);
    }

    /* glTF's normal convention: an ivy blade is domed along its midrib, so
     * right of the midrib the normals lean to +X (red above 128) and left
     * of it to -X; near the tip (the dome falls towards +v) they lean to +Y. */
    {
        banyan_image *nm = NULL;
        gen(BANYAN_TEX_IVY_LEAF, 0, 512, 1, NULL, &nm);
        int cs = nm ? (int)nm->width / 4 : 0, wrong = 0;
        for (int c = 0; nm && c < 16; c++) {
            int x0 = (c % 4) * cs, y0 = (c / 4) * cs, cx = x0 + cs / 2;
            double right = 0, left = 0;
            int cnt = 0;
            for (int y = y0 + cs * 30 / 100; y < y0 + cs * 45 / 100; y++)
                for (int d = cs * 6 / 100; d < cs * 14 / 100; d++) {
                    right += nm->pixels[3 * ((size_t)y * nm->width + cx + d)];
                    left += nm->pixels[3 * ((size_t)y * nm->width + cx - d)];
                    cnt++;
                }
            if (!(right / cnt > 129 && left / cnt < 127 && right - left > 4 * cnt)) wrong++;
        }
        CHECK(nm && wrong == 0, "ivy normal map: %d cells with red not > 128 right of the midrib and < 128 left", wrong);
        banyan_image_free(nm);
    }

    /* Either output may be skipped; the other is the same as when both are made. */
    {
        banyan_image *bc = NULL, *nm = NULL, *only = NULL;
        gen(BANYAN_TEX_FIG_BARK, 0, 128, 5, &bc, &nm);
        gen(BANYAN_TEX_FIG_BARK, 0, 128, 5, NULL, &only);
        CHECK(only && nm && !memcmp(only->pixels, nm->pixels, 128 * 128 * 3), "normal alone differs");
        banyan_image_free(only);
        only = NULL;
        gen(BANYAN_TEX_FIG_BARK, 0, 128, 5, &only, NULL);
        CHECK(only && bc && !memcmp(only->pixels, bc->pixels, 128 * 128 * 4), "colour alone differs");
        banyan_image_free(only);
        banyan_image_free(bc);
        banyan_image_free(nm);
    }

    /* Two threads at once give the bytes one thread gives. */
    {
        job a[BANYAN_TEX_COUNT], b[BANYAN_TEX_COUNT];
        pthread_t ta[BANYAN_TEX_COUNT];
        for (int k = BANYAN_TEX_NONE + 1; k < BANYAN_TEX_COUNT; k++) {
            a[k] = (job){k, 1, 0, 0};
            b[k] = a[k];
            pthread_create(&ta[k], NULL, run_job, &a[k]);
        }
        for (int k = BANYAN_TEX_NONE + 1; k < BANYAN_TEX_COUNT; k++) run_job(&b[k]);
        for (int k = BANYAN_TEX_NONE + 1; k < BANYAN_TEX_COUNT; k++) {
            pthread_join(ta[k], NULL);
            CHECK(a[k].hash_bc && a[k].hash_bc == b[k].hash_bc && a[k].hash_nm == b[k].hash_nm,
                  "%s: threads give other bytes", names[k]);
        }
    }

    /* Bad input. */
    bad("size 0", BANYAN_TEX_KEYAKI_LEAF, 0, 0, 0, "size");
    bad("size 1000", BANYAN_TEX_KEYAKI_LEAF, 0, 1000, 0, "power of two");
    bad("size 32", BANYAN_TEX_IVY_LEAF, 0, 32, 0, "[64, 8192]");
    bad("size 16384", BANYAN_TEX_KEYAKI_BARK, 0, 16384, 0, "[64, 8192]");
    bad("size -1024", BANYAN_TEX_KEYAKI_BARK, 0, -1024, 0, "size");
    bad("kind 7", 7, 0, 1024, 0, "kind");
    bad("kind 6 (COUNT)", BANYAN_TEX_COUNT, 0, 1024, 0, "kind = 6 must be within [1, 5]");
    bad("kind 0 (NONE)", BANYAN_TEX_NONE, 0, 1024, 0, "kind = 0 must be within [1, 5]");
    bad("kind -1", -1, 0, 1024, 0, "kind");
    bad("season 3", BANYAN_TEX_KEYAKI_LEAF, 3, 1024, 0, "season");
    bad("season -1", BANYAN_TEX_FIG_BARK, -1, 1024, 0, "season");
    bad("reserved", BANYAN_TEX_KEYAKI_LEAF, 0, 1024, 9, "reserved");
    {
        banyan_error e;
        banyan_image *bc = (banyan_image *)&e;
        CHECK(banyan_texture_generate(NULL, &bc, NULL, &e) == BANYAN_E_INVALID_ARG && bc == NULL &&
                  strstr(e.message, "params"),
              "NULL params: %s", e.message);
        banyan_atlas_layout L;
        CHECK(banyan_texture_layout(BANYAN_TEX_COUNT, &L, &e) == BANYAN_E_RANGE && strstr(e.message, "kind"),
              "layout kind 6: %s", e.message);
        CHECK(banyan_texture_layout(BANYAN_TEX_NONE, &L, &e) == BANYAN_E_RANGE && strstr(e.message, "kind"),
              "layout kind 0 (NONE): %s", e.message);
        CHECK(banyan_texture_layout(BANYAN_TEX_KEYAKI_LEAF, NULL, &e) == BANYAN_E_INVALID_ARG, "layout NULL out");
        uint8_t *png = (uint8_t *)&e;
        size_t len = 7;
        CHECK(banyan_image_png(NULL, &png, &len, &e) == BANYAN_E_INVALID_ARG && png == NULL && len == 0 &&
                  strstr(e.message, "image"),
              "png of NULL: %s", e.message);
        banyan_image zero = {0, 0, 4, NULL};
        uint8_t px[4] = {1, 2, 3, 4};
        zero.pixels = px;
        CHECK(banyan_image_png(&zero, &png, &len, &e) == BANYAN_E_RANGE && png == NULL && strstr(e.message, "width"),
              "png of 0x0: %s", e.message);
        banyan_image five = {1, 1, 5, px};
        CHECK(banyan_image_png(&five, &png, &len, &e) == BANYAN_E_RANGE && strstr(e.message, "channels"),
              "png of 5 channels: %s", e.message);
        banyan_image_free(NULL);
        banyan_png_free(NULL);
        banyan_texture_params_init(NULL);
    }
    return check_done("test_textures");
}
