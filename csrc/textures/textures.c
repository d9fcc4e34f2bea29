/* textures.c - the public texture calls of banyan/textures.h:
 * input checks, the atlas layout, the canvas each painter draws into, the
 * normal map (Sobel on the painter's height field, glTF's tangent-space
 * convention) and PNG bytes (png_write.c), under the caller's deadline
 * (tex_budget.h). Painters: leaves.c (keyaki and Boston ivy atlases), bark.c (tileable bark). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/big_alloc.h"
#include "base/error.h"
#include "textures/tex_budget.h"
#include "textures/png_write.h"
#include "textures/tex_internal.h"

#define TEX_MIN_SIZE 64
#define TEX_MAX_SIZE 8192

void tex_leaf_grid(int kind, int *cols, int *rows, float *aspect) {
    /* Keyaki and ivy: 4 x 4 square cells of one leaf each (keyaki's placed
     * as textures/leaf_look.h says; docs/materials.md). */
    if (kind == BANYAN_TEX_KEYAKI_LEAF || kind == BANYAN_TEX_IVY_LEAF) *cols = 4, *rows = 4, *aspect = 1.0f;
    else *cols = 1, *rows = 1, *aspect = 1.0f;
}

void banyan_texture_params_init(banyan_texture_params *p) {
    if (!p) return;
    memset(p, 0, sizeof *p);
    p->kind = BANYAN_TEX_KEYAKI_LEAF;
    p->season = BANYAN_SEASON_SUMMER;
    p->size = 1024;
    p->seed = 1;
}

static banyan_status check_kind(int32_t kind, banyan_error *err) {
    if (kind > BANYAN_TEX_NONE && kind < BANYAN_TEX_COUNT) return BANYAN_OK;
    return banyan_fail(err, BANYAN_E_RANGE,
                       "kind = %d must be within [%d, %d] (keyaki_leaf 1, ivy_leaf 2, keyaki_bark 3, fig_bark 4, "
                       "ivy_stem 5)",
                       (int)kind, BANYAN_TEX_NONE + 1, BANYAN_TEX_COUNT - 1);
}

banyan_status banyan_texture_layout(int32_t kind, banyan_atlas_layout *out, banyan_error *err) {
    banyan_error_clear(err);
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    banyan_status s = check_kind(kind, err);
    if (s != BANYAN_OK) return s;
    int cols, rows;
    float aspect;
    tex_leaf_grid(kind, &cols, &rows, &aspect);
    out->cols = cols;
    out->rows = rows;
    out->leaf_aspect = aspect;
    return BANYAN_OK;
}

static banyan_status check_params(const banyan_texture_params *p, banyan_error *err) {
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    banyan_status s = check_kind(p->kind, err);
    if (s != BANYAN_OK) return s;
    if (p->season != BANYAN_SEASON_SUMMER && p->season != BANYAN_SEASON_AUTUMN)
        return banyan_fail(err, BANYAN_E_RANGE, "season = %d must be within [0, 1] (summer 0, autumn 1)",
                           (int)p->season);
    if (p->size < TEX_MIN_SIZE || p->size > TEX_MAX_SIZE || (p->size & (p->size - 1)) != 0)
        return banyan_fail(err, BANYAN_E_RANGE, "size = %d must be a power of two within [%d, %d]", (int)p->size,
                           TEX_MIN_SIZE, TEX_MAX_SIZE);
    if (p->reserved != 0)
        return banyan_fail(err, BANYAN_E_RANGE, "reserved = %d must be 0", (int)p->reserved);
    return BANYAN_OK;
}

static banyan_image *image_new(uint32_t n, uint32_t channels) {
    banyan_image *im = calloc(1, sizeof *im);
    if (!im) return NULL;
    im->width = im->height = n;
    im->channels = channels;
    im->pixels = big_malloc((size_t)n * n * channels); /* written whole: huge pages, fewer faults */
    if (!im->pixels) {
        free(im);
        return NULL;
    }
    return im;
}

void banyan_image_free(banyan_image *image) {
    if (!image) return;
    free(image->pixels);
    free(image);
}

/* Texels a normal-map row is made in (divides every size, >= 64). */
#define NM_CHUNK 32

static inline int32_t tex_to_byte_i(float v) { return (int32_t)(v < 255.0f ? v : 255.0f); }

/* Tangent-space normals from the height field: Sobel gradient, glTF's
 * convention (+X towards +u, +Y towards +v; rows run top to bottom, so
 * v grows upwards = towards row - 1). Edges wrap for tiles, clamp else.
 * Rows are copied once each, with one pixel of padding each side, into
 * three buffers that take turns, so the inner loop has no branches (it
 * vectorises). */
typedef struct nm_row {
    int y;          /* image row held, -1 none */
    float *p;       /* n + 2 padded heights */
    uint8_t *flat;  /* per chunk: 1 when the chunk and its neighbours either side are all height 0 */
} nm_row;

static const nm_row *nm_fetch(const tex_canvas *c, nm_row slot[3], int yy, int keep0, int keep1) {
    const int n = c->n;
    for (int i = 0; i < 3; i++)
        if (slot[i].y == yy) return &slot[i];
    int i = 0;
    while (slot[i].y == keep0 || slot[i].y == keep1) i++; /* a slot no other row of this one needs */
    nm_row *s = &slot[i];
    s->y = yy;
    float *p = s->p;
    memcpy(p + 1, c->height + (size_t)yy * n, sizeof(float) * (size_t)n);
    p[0] = c->wrap ? p[n] : p[1];
    p[n + 1] = c->wrap ? p[1] : p[n];
    if (!c->wrap) /* tiles have relief everywhere: no flat chunks to look for */
        for (int x0 = 0; x0 < n; x0 += NM_CHUNK) {
            int any = 0;
            for (int x = x0; x < x0 + NM_CHUNK + 2; x++) any |= p[x] != 0.0f;
            s->flat[x0 / NM_CHUNK] = !any;
        }
    return s;
}

static int normal_map(const tex_canvas *c, uint8_t *out) {
    const int n = c->n;
    const float k = c->relief / 8.0f;
    float *pad = malloc(sizeof(float) * 3 * (size_t)(n + 2));
    uint8_t *flat = malloc(3 * (size_t)(n / NM_CHUNK));
    uint32_t *px = malloc(sizeof(uint32_t) * (size_t)n); /* a row's texels as R | G << 8 | B << 16 */
    if (!pad || !flat || !px) {
        free(pad);
        free(flat);
        free(px);
        return -1;
    }
    nm_row slot[3];
    for (int i = 0; i < 3; i++)
        slot[i] = (nm_row){-1, pad + (size_t)i * (n + 2), flat + (size_t)i * (n / NM_CHUNK)};
    for (int y = 0; y < n && !((y & 63) == 0 && tex_stopped(c)); y++) {
        int rows[3] = {y - 1, y, y + 1};
        for (int r = 0; r < 3; r++) {
            if (c->wrap) rows[r] = (rows[r] + n) & (n - 1);
            else rows[r] = rows[r] < 0 ? 0 : rows[r] >= n ? n - 1 : rows[r];
        }
        const nm_row *s0 = nm_fetch(c, slot, rows[0], rows[1], rows[2]);
        const nm_row *s1 = nm_fetch(c, slot, rows[1], rows[0], rows[2]);
        const nm_row *s2 = nm_fetch(c, slot, rows[2], rows[0], rows[1]);
        const float *r0 = s0->p + 1, *r1 = s1->p + 1, *r2 = s2->p + 1;
        uint8_t *o = out + (size_t)y * n * 3;
        for (int x0 = 0; x0 < n; x0 += NM_CHUNK) {
            /* Chunks of NM_CHUNK texels whose 3 x 3 neighbourhoods are all at
             * height 0 (around the leaves of an atlas) are flat: (128, 128,
             * 255) exactly as the Sobel below gives them, written directly. */
            int ci = x0 / NM_CHUNK;
            if (!c->wrap && s0->flat[ci] && s1->flat[ci] && s2->flat[ci]) {
                for (int x = x0; x < x0 + NM_CHUNK; x++) o[3 * x] = 128, o[3 * x + 1] = 128, o[3 * x + 2] = 255;
                continue;
            }
            for (int x = x0; x < x0 + NM_CHUNK; x++) {
                float gx = (r0[x + 1] + 2.0f * r1[x + 1] + r2[x + 1]) - (r0[x - 1] + 2.0f * r1[x - 1] + r2[x - 1]);
                float gy = (r2[x - 1] + 2.0f * r2[x] + r2[x + 1]) - (r0[x - 1] + 2.0f * r0[x] + r0[x + 1]); /* down the rows */
                float nx = -k * gx, ny = k * gy; /* dh/dv = -dh/drow */
                float iv = 1.0f / sqrtf(nx * nx + ny * ny + 1.0f);
                /* (n * 0.5 + 0.5) * 255 + 0.5, truncated: rounded to a byte */
                px[x] = (uint32_t)tex_to_byte_i(nx * iv * 127.5f + 128.0f) |
                        (uint32_t)tex_to_byte_i(ny * iv * 127.5f + 128.0f) << 8 |
                        (uint32_t)tex_to_byte_i(iv * 127.5f + 128.0f) << 16;
            }
            /* Three bytes a texel: four texels as three little-endian words
             * (tex_internal.h checks the byte order). */
            for (int x = x0; x < x0 + NM_CHUNK; x += 4) {
                const uint32_t *q = px + x;
                uint32_t w[3] = {q[0] | q[1] << 24, q[1] >> 8 | q[2] << 16, q[2] >> 16 | q[3] << 8};
                memcpy(o + 3 * (size_t)x, w, 12);
            }
        }
    }
    free(pad);
    free(flat);
    free(px);
    return 0;
}

/* Streams per kind and season, so the five textures of one seed differ:
 * numbered from the first kind (BANYAN_TEX_KEYAKI_LEAF). */
static uint64_t stream_of(int kind, int season) {
    return 0x7e47u + (uint64_t)(kind - BANYAN_TEX_KEYAKI_LEAF) * 2u + (uint64_t)season;
}

static banyan_status over_time(banyan_error *err, const char *what, int32_t size, double seconds) {
    return banyan_fail(err, BANYAN_E_LIMIT,
                       "%s a %d-pixel texture passed max_seconds = %g (%g .. %.0f); raise max_seconds or lower the "
                       "texture size (a power of two, %d .. %d)",
                       what, (int)size, seconds, PROG_MAX_SECONDS_MIN, PROG_MAX_SECONDS_MAX, TEX_MIN_SIZE, TEX_MAX_SIZE);
}

uint64_t tex_peak_bytes(int32_t size, int normal) {
    const uint64_t px = (uint64_t)size * (uint64_t)size;
    /* Drawing: RGBA + float heights (+ RGB normals); encoding the RGBA
     * picture beside them: its filter rows and about as many deflated bytes. */
    return px * (4 + 4 + (normal ? 3 : 0)) + 2 * px * 4;
}

banyan_status tex_generate(const banyan_texture_params *p, const prog_deadline *stop, double seconds,
                           banyan_image **base_color, banyan_image **normal, banyan_error *err) {
    banyan_error_clear(err);
    if (base_color) *base_color = NULL;
    if (normal) *normal = NULL;
    banyan_status s = check_params(p, err);
    if (s != BANYAN_OK) return s;
    if (!base_color && !normal) return BANYAN_OK; /* nothing asked */

    const int n = p->size;
    tex_canvas c = {n, NULL, NULL, 1.0f, 0, NULL, NULL, stop};
    banyan_image *bc = image_new((uint32_t)n, 4), *nm = normal ? image_new((uint32_t)n, 3) : NULL;
    c.height = big_malloc((size_t)n * n * sizeof *c.height); /* every painter writes all of it */
    if (!bc || (normal && !nm) || !c.height) goto nomem;
    c.rgba = bc->pixels; /* every painter writes all of it */

    pcg32 rng;
    pcg32_seed(&rng, p->seed, stream_of(p->kind, p->season));
    int rc = -1;
    switch (p->kind) {
    case BANYAN_TEX_KEYAKI_LEAF: rc = tex_paint_keyaki_leaves(&c, p->season, &rng); break;
    case BANYAN_TEX_IVY_LEAF: rc = tex_paint_ivy_leaves(&c, p->season, &rng); break;
    case BANYAN_TEX_KEYAKI_BARK: rc = tex_paint_keyaki_bark(&c, &rng); break;
    case BANYAN_TEX_FIG_BARK: rc = tex_paint_fig_bark(&c, &rng); break;
    case BANYAN_TEX_IVY_STEM: rc = tex_paint_ivy_stem(&c, &rng); break;
    default: break;
    }
    if (rc != 0 || (nm && !tex_stopped(&c) && normal_map(&c, nm->pixels) != 0)) goto nomem;
    free(c.height);
    if (tex_stopped(&c)) { /* the painter or the normal map stopped early */
        banyan_image_free(bc);
        banyan_image_free(nm);
        return over_time(err, "drawing", n, seconds);
    }
    if (base_color) *base_color = bc;
    else banyan_image_free(bc);
    if (normal) *normal = nm;
    return BANYAN_OK;
nomem:
    free(c.height);
    banyan_image_free(bc);
    banyan_image_free(nm);
    return banyan_fail(err, BANYAN_E_NOMEM, "texture of size %d: out of memory", n);
}

banyan_status banyan_texture_generate(const banyan_texture_params *p, banyan_image **base_color,
                                      banyan_image **normal, banyan_error *err) {
    return banyan_texture_generate_budget(p, NULL, base_color, normal, err);
}

banyan_status banyan_texture_generate_budget(const banyan_texture_params *p, const banyan_budget *budget,
                                             banyan_image **base_color, banyan_image **normal, banyan_error *err) {
    banyan_error_clear(err);
    if (base_color) *base_color = NULL;
    if (normal) *normal = NULL;
    banyan_status s = check_params(p, err);
    if (s != BANYAN_OK) return s;
    prog g;
    if ((s = prog_budget_from(&g, budget, err)) != BANYAN_OK) return s;
    if (!base_color && !normal) return BANYAN_OK; /* nothing asked */
    const double need = (double)tex_peak_bytes(p->size, normal != NULL);
    if (prog_reserve(&g, need - 2.0 * 4.0 * p->size * p->size)) /* drawing only: no PNG here */
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "a %d-pixel texture needs %.0f MB to draw, past max_memory_mb = %g (%.0f .. %.0f); "
                           "lower the texture size (a power of two, %d .. %d) or raise max_memory_mb",
                           (int)p->size, g.over_value, g.max_mb, PROG_MAX_MEMORY_MIN, PROG_MAX_MEMORY_MAX,
                           TEX_MIN_SIZE, TEX_MAX_SIZE);
    prog_deadline d = prog_deadline_of(&g);
    return tex_generate(p, &d, g.max_seconds, base_color, normal, err);
}

banyan_status tex_png(const banyan_image *image, const prog_deadline *stop, double seconds, uint8_t **png,
                      size_t *size, banyan_error *err) {
    banyan_error_clear(err);
    if (png) *png = NULL;
    if (size) *size = 0;
    if (!png) return banyan_fail(err, BANYAN_E_INVALID_ARG, "png is NULL");
    if (!size) return banyan_fail(err, BANYAN_E_INVALID_ARG, "size is NULL");
    if (!image) return banyan_fail(err, BANYAN_E_INVALID_ARG, "image is NULL");
    if (!image->pixels) return banyan_fail(err, BANYAN_E_INVALID_ARG, "image->pixels is NULL");
    if (image->channels < 1 || image->channels > 4)
        return banyan_fail(err, BANYAN_E_RANGE, "image->channels = %u must be within [1, 4]", image->channels);
    if (image->width < 1 || image->width > TEX_MAX_SIZE || image->height < 1 || image->height > TEX_MAX_SIZE)
        return banyan_fail(err, BANYAN_E_RANGE, "image->width x height = %u x %u must be within [1, %d] each",
                           image->width, image->height, TEX_MAX_SIZE);
    int rc = png_write(image->pixels, (int)image->width, (int)image->height, (int)image->channels, PNG_WRITE_FILTER,
                       PNG_WRITE_LEVEL, stop, png, size);
    if (rc > 0)
        return over_time(err, "encoding (PNG)", (int32_t)(image->width > image->height ? image->width : image->height),
                         seconds);
    if (rc < 0) return banyan_fail(err, BANYAN_E_NOMEM, "PNG of %u x %u: out of memory", image->width, image->height);
    return BANYAN_OK;
}


banyan_status banyan_image_png(const banyan_image *image, uint8_t **png, size_t *size, banyan_error *err) {
    return tex_png(image, NULL, 0.0, png, size, err);
}

void banyan_png_free(uint8_t *png) { free(png); }

size_t banyan_sizeof_image(void) { return sizeof(banyan_image); }
size_t banyan_sizeof_texture_params(void) { return sizeof(banyan_texture_params); }
