/* The ivy's leaf colour and gloss (docs/ivy.md "Leaf material";
 * reference/plants.md section 2: glossy, rich green in summer, young
 * leaves flushing reddish-bronze) on presets/ivy_wall, seeds 1 and 2, in
 * summer, at GROWING steps (a plant still spreading: its growth front has
 * young leaves) and at the preset's 450 (the wall covered: old leaves).
 *
 * A blade's colour is what a glTF viewer shows, texture x COLOR_0: its
 * vertex colour (the per-leaf tint) times the mean linear colour of the
 * atlas cell it shows (the summer IVY_LEAF texture at 256 px, texels
 * weighted by alpha). Age = the plant's step - the blade's birth_step.
 *   - young (age < YOUNG steps, the growth front, at GROWING): every blade red above
 *     green (r > g), and their area-weighted mean reddish-bronze: r > g > b,
 *     hue 5-40 deg;
 *   - old (age >= leaf_size_steps, at 450): every blade green (g > r), the mean's
 *     hue 75-140 deg, and not the flat dark green: the mean's linear
 *     luminance >= OLD_LUM;
 *   - the whole plant (area-weighted) reads green at both: g > r, g > b, hue 70-140;
 * and the material ivy_leaf is glossy (roughness 0.25-0.45), ivy_stem matte
 * (>= 0.7). Every figure is printed (the table in docs/ivy.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan/textures.h"
#include "check.h"
#include "ivy_look.h"
#include "test_hosts.h"

#define YOUNG 10     /* steps: the growth front's leaves */
#define GROWING 200  /* steps: ivy_wall still spreading (at its 450 the wall is covered and the front still) */
#define OLD_LUM 0.06 /* linear luminance of the old leaves' mean: a rich green, not the flat dark one */
#define TEX 256

static double to_linear(unsigned char c) {
    double x = c / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

static int to_srgb(double x) {
    x = x < 0 ? 0 : (x > 1 ? 1 : x);
    x = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
    return (int)(255 * x + 0.5);
}

static double hue(const double c[3]) {
    double mx = fmax(c[0], fmax(c[1], c[2])), mn = fmin(c[0], fmin(c[1], c[2])), d = mx - mn, h;
    if (d <= 0) return 0;
    if (mx == c[0]) h = fmod((c[1] - c[2]) / d, 6.0);
    else if (mx == c[1]) h = (c[2] - c[0]) / d + 2;
    else h = (c[0] - c[1]) / d + 4;
    h *= 60;
    return h < 0 ? h + 360 : h;
}

static double lum(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

typedef struct group {
    double rgb[3], area;
    int n, wrong; /* blades; blades of the wrong hue order */
    int cell_wrong; /* blades on a young cell when grown, or on a grown cell when young */
} group;

#define YOUNG_CELL_STEPS 12 /* IVY_YOUNG_STEPS (csrc/ivy/mesh.c): younger blades show the atlas's young cells */

static void add(group *g, const double c[3], double area) {
    for (int k = 0; k < 3; k++) g->rgb[k] += c[k] * area;
    g->area += area;
    g->n++;
}

static void mean(const group *g, double out[3]) {
    for (int k = 0; k < 3; k++) out[k] = g->area > 0 ? g->rgb[k] / g->area : 0;
}

static void print(const char *name, const group *g) {
    double c[3];
    mean(g, c);
    printf("  %-28s %6d blades  linear %.4f %.4f %.4f  sRGB %3d %3d %3d  hue %5.1f  luminance %.4f\n", name, g->n, c[0],
           c[1], c[2], to_srgb(c[0]), to_srgb(c[1]), to_srgb(c[2]), hue(c), lum(c));
}

/* Alpha-weighted mean linear colour of each atlas cell (cols x rows); the
 * image's first row is the top, v = 1. */
static int cell_means(int32_t cols, int32_t rows, double *out) {
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.kind = BANYAN_TEX_IVY_LEAF;
    tp.season = BANYAN_SEASON_SUMMER;
    tp.size = TEX;
    banyan_image *img = NULL;
    banyan_error err = {0, ""};
    if (banyan_texture_generate(&tp, &img, NULL, &err) != BANYAN_OK || !img || img->channels != 4) {
        CHECK(0, "ivy leaf texture: %s", err.message);
        banyan_image_free(img);
        return 0;
    }
    double *w = calloc((size_t)cols * rows, sizeof(double));
    memset(out, 0, sizeof(double) * 3 * (size_t)cols * rows);
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++) {
            const unsigned char *p = img->pixels + 4 * ((size_t)y * img->width + x);
            double u = (x + 0.5) / img->width, v = 1.0 - (y + 0.5) / img->height, a = p[3] / 255.0;
            int c = (int)(u * cols) + cols * (int)(v * rows);
            for (int k = 0; k < 3; k++) out[3 * c + k] += a * to_linear(p[k]);
            w[c] += a;
        }
    for (int c = 0; c < cols * rows; c++)
        for (int k = 0; k < 3; k++) out[3 * c + k] /= w[c] > 0 ? w[c] : 1;
    free(w);
    banyan_image_free(img);
    return 1;
}

/* Blade colours of one mesh of iv into young, old and all; prints them. */
static int measure(const banyan_ivy *iv, const banyan_mesh *m, int32_t cols, int32_t rows, const double *cell,
                   group *young, group *old, group *all) {
    int32_t ab = -1;
    for (uint32_t a = 0; a < m->attribute_count; a++)
        if (!strcmp(m->attributes[a].name, "birth_step")) ab = (int32_t)a;
    uint32_t nb = 0;
    ivy_blade *bl = ivy_look_blades(m, &nb);
    if (!bl || nb < 500 || !m->colors || ab < 0) {
        free(bl);
        return 0;
    }
    static const int edge[] = {10, 20, 40, 80, 150, 300, 1 << 30};
    double hist[7] = {0};
    for (uint32_t k = 0; k < nb; k++) {
        const ivy_blade *b = &bl[k];
        double uv[2] = {0, 0};
        for (uint32_t v = b->first; v < b->first + b->count; v++) uv[0] += m->uvs[2 * v], uv[1] += m->uvs[2 * v + 1];
        int cu = (int)(uv[0] / b->count * cols), cv = (int)(uv[1] / b->count * rows);
        cu = cu < 0 ? 0 : (cu >= cols ? cols - 1 : cu);
        cv = cv < 0 ? 0 : (cv >= rows ? rows - 1 : cv);
        const float *t = m->colors + 4 * (size_t)b->first;
        double c[3];
        for (int q = 0; q < 3; q++) c[q] = t[q] * cell[3 * (cu + cols * cv) + q];
        double age = (double)iv->step - m->attributes[ab].data[b->first];
        add(all, c, b->area);
        all->cell_wrong += ((cu + cols * cv) % 4 == 3) != (age < YOUNG_CELL_STEPS); /* young cells: every 4th */
        for (int e = 0; e < 7; e++)
            if (age < edge[e]) {
                hist[e] += b->area;
                break;
            }
        if (age < YOUNG) {
            add(young, c, b->area);
            young->wrong += !(c[0] > c[1]);
        } else if (age >= iv->p.leaf_size_steps) {
            add(old, c, b->area);
            old->wrong += !(c[1] > c[0]);
        }
    }
    printf(" seed %llu, %d steps (young: age < %d steps, old: age >= %d)\n", (unsigned long long)iv->p.seed, iv->step,
           YOUNG, iv->p.leaf_size_steps);
    print("young", young);
    print("old", old);
    print("all", all);
    printf("  leaf area share by age (steps) <10 %.4f, <20 %.4f, <40 %.4f, <80 %.4f, <150 %.4f, <300 %.4f, older %.4f\n",
           hist[0] / all->area, hist[1] / all->area, hist[2] / all->area, hist[3] / all->area, hist[4] / all->area,
           hist[5] / all->area, hist[6] / all->area);
    free(bl);
    return 1;
}

static void check_green(const group *all, unsigned long long seed, int steps) {
    double a[3];
    mean(all, a);
    CHECK(a[1] > a[0] && a[1] > a[2] && hue(a) >= 70 && hue(a) <= 140,
          "seed %llu, %d steps: the plant's mean %.4f %.4f %.4f (hue %.1f) does not read green", seed, steps, a[0], a[1],
          a[2], hue(a));
}

int main(int argc, char **argv) {
    (void)argc, (void)argv;
    banyan_ivy_params base;
    banyan_box hosts[8];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    if (ivy_look_preset("ivy_wall", &base, hosts, 8, &nh, &err) != BANYAN_OK) {
        CHECK(0, "ivy_wall: %s", err.message);
        return check_done("test_ivy_leaf_colour");
    }
    banyan_atlas_layout L;
    CHECK(banyan_texture_layout(BANYAN_TEX_IVY_LEAF, &L, &err) == BANYAN_OK, "layout: %s", err.message);
    const int32_t cols = L.cols, rows = L.rows;
    double *cell = malloc(sizeof(double) * 3 * (size_t)cols * rows);
    if (!cell || !cell_means(cols, rows, cell)) return check_done("test_ivy_leaf_colour");
    printf("ivy_wall, summer: blade colour = COLOR_0 x atlas cell mean (linear), area-weighted\n");
    banyan_hosts *H = TEST_HOSTS(hosts, nh);
    for (uint64_t seed = 1; seed <= 2; seed++) {
        const unsigned long long sd = (unsigned long long)seed;
        banyan_ivy_params p = base;
        p.seed = seed;
        banyan_ivy *iv = NULL;
        banyan_mesh *m = NULL;
        group young = {{0}, 0, 0, 0, 0}, old = young, all = young;
        /* Growing: the front's young leaves flush bronze, the plant stays green. */
        int ok = banyan_ivy_create(&p, H, &iv, &err) == BANYAN_OK &&
                 banyan_ivy_step(iv, GROWING, &err) == BANYAN_OK && banyan_ivy_mesh(iv, &m, &err) == BANYAN_OK;
        CHECK(ok && measure(iv, m, cols, rows, cell, &young, &old, &all), "seed %llu, %d steps: %s", sd, GROWING,
              err.message);
        if (ok && seed == 1) {
            printf("  roughness: ivy_leaf %.3f, ivy_stem %.3f\n", m->materials[1].roughness, m->materials[0].roughness);
            CHECK(m->material_count == 2 && !strcmp(m->materials[1].name, "ivy_leaf") &&
                      m->materials[1].roughness >= 0.25f && m->materials[1].roughness <= 0.45f,
                  "ivy_leaf roughness %.3f: want glossy, 0.25-0.45", m->materials[1].roughness);
            CHECK(m->materials[0].roughness >= 0.7f, "ivy_stem roughness %.3f: want matte, >= 0.7",
                  m->materials[0].roughness);
        }
        double y[3], o[3];
        mean(&young, y);
        CHECK(young.n >= 100 && young.wrong == 0, "seed %llu: %d of %d young blades not red above green", sd,
              young.wrong, young.n);
        CHECK(y[0] > y[1] && y[1] > y[2] && hue(y) >= 5 && hue(y) <= 40,
              "seed %llu: young mean %.4f %.4f %.4f (hue %.1f) is not reddish-bronze", sd, y[0], y[1], y[2], hue(y));
        CHECK(all.cell_wrong == 0 && lum(y) >= 0.05, "seed %llu: %d blades on a cell of the wrong age; young luminance "
              "%.4f (want >= 0.05: bronze, not dark brown)", sd, all.cell_wrong, lum(y));
        check_green(&all, sd, GROWING);
        banyan_mesh_free(m);
        m = NULL;
        /* Grown: the old leaves a rich green. */
        group young2 = {{0}, 0, 0, 0, 0}, all2 = young2;
        old = young2;
        ok = ok && banyan_ivy_step(iv, p.steps - GROWING, &err) == BANYAN_OK && banyan_ivy_mesh(iv, &m, &err) == BANYAN_OK;
        CHECK(ok && measure(iv, m, cols, rows, cell, &young2, &old, &all2), "seed %llu, %d steps: %s", sd, p.steps,
              err.message);
        mean(&old, o);
        CHECK(old.n >= 1000 && old.wrong == 0, "seed %llu: %d of %d old blades not green above red", sd, old.wrong,
              old.n);
        CHECK(hue(o) >= 75 && hue(o) <= 140 && lum(o) >= OLD_LUM,
              "seed %llu: old mean hue %.1f, luminance %.4f: want green, 75-140, >= %.3f", sd, hue(o), lum(o), OLD_LUM);
        check_green(&all2, sd, p.steps);
        banyan_mesh_free(m);
        banyan_ivy_free(iv);
    }
    banyan_hosts_free(H);
    free(cell);
    return check_done("test_ivy_leaf_colour");
}
