/* pp2.c - Pivot Painter 2 elements and textures (banyan/pivot_painter.h,
 * pp2.h). Everything is derived from the mesh's own wind attributes, in
 * vertex order, so the same mesh gives the same bytes on every run. */
#include "pp2/pp2.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "pp2/exr_half.h"
#include "textures/png_write.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* PivotPainter2FoliageShader follows an element and three ancestors. */
#define PP2_LEVELS 4
#define NONE UINT32_MAX

typedef struct elem {
    uint32_t group, first;
    float key[5];     /* pivot x, y, z, level, phase: compared bitwise */
    uint32_t parent;  /* an element; itself for a root */
    uint32_t rep;     /* the element whose texel it reads: itself, or its ancestor on the last level kept */
    uint32_t depth;   /* steps below its root */
    uint32_t far;     /* its own vertex farthest from its pivot */
    double far_d2;
    uint32_t index;   /* its texel when rep is itself */
} elem;

typedef struct build {
    const banyan_mesh *m;
    const float *att[5]; /* pivot x, y, z, level, phase */
    const float *flutter;
    uint32_t *vgroup, *velem;
    elem *e;
    uint32_t n, cap;
    uint32_t *slots; /* hash of keys -> element + 1 */
    uint32_t slot_mask;
} build;

static uint32_t key_hash(uint32_t group, const float *k) {
    uint32_t h = 2166136261u ^ group;
    for (int i = 0; i < 5; ++i) {
        uint32_t w;
        memcpy(&w, &k[i], 4);
        h = (h ^ w) * 16777619u;
        h ^= h >> 15;
    }
    return h;
}

static int rehash(build *B, uint32_t size) {
    uint32_t *s = calloc(size, sizeof *s);
    if (!s) return -1;
    free(B->slots);
    B->slots = s;
    B->slot_mask = size - 1;
    for (uint32_t i = 0; i < B->n; ++i) {
        uint32_t h = key_hash(B->e[i].group, B->e[i].key) & B->slot_mask;
        while (s[h]) h = (h + 1) & B->slot_mask;
        s[h] = i + 1;
    }
    return 0;
}

/* The element of vertex v, added when new. NONE when out of memory. */
static uint32_t element_of(build *B, uint32_t v) {
    float k[5];
    for (int i = 0; i < 5; ++i) k[i] = B->att[i][v];
    const uint32_t g = B->vgroup[v];
    uint32_t h = key_hash(g, k) & B->slot_mask;
    for (; B->slots[h]; h = (h + 1) & B->slot_mask) {
        const elem *x = &B->e[B->slots[h] - 1];
        if (x->group == g && memcmp(x->key, k, sizeof k) == 0) return B->slots[h] - 1;
    }
    if (B->n == B->cap) {
        uint32_t cap = B->cap ? 2 * B->cap : 256;
        elem *e = realloc(B->e, cap * sizeof *e);
        if (!e) return NONE;
        B->e = e;
        B->cap = cap;
    }
    elem *x = &B->e[B->n];
    memset(x, 0, sizeof *x);
    x->group = g;
    x->first = v;
    memcpy(x->key, k, sizeof k);
    x->parent = B->n;
    x->far = v;
    x->far_d2 = -1.0;
    B->slots[h] = ++B->n;
    if (2ull * B->n > B->slot_mask && rehash(B, 2 * (B->slot_mask + 1)) != 0) return NONE;
    return B->n - 1;
}

/* ------------------------------------------------------------ nearest wood vertex */

/* Vertices hashed by grid cell; queries return the nearest within it. */
typedef struct grid {
    double lo[3], h;
    int32_t reach;      /* shells that cover the whole box */
    uint32_t mask;
    uint32_t *start;    /* mask + 2 */
    uint32_t *items;
} grid;

/* Cells are counted within +-2^40 (a query further out is scanned, not looked up). */
static void cell_of(const grid *G, const float *p, int64_t c[3]) {
    for (int k = 0; k < 3; ++k) c[k] = (int64_t)fmin(fmax(floor(((double)p[k] - G->lo[k]) / G->h), -0x1p40), 0x1p40);
}

static uint32_t cell_hash(const grid *G, int64_t x, int64_t y, int64_t z) {
    uint32_t h = (uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u;
    return (h ^ (h >> 13)) & G->mask;
}

static void grid_free(grid *G) {
    free(G->start);
    free(G->items);
    memset(G, 0, sizeof *G);
}

/* A grid over vs[0 .. n - 1] (n > 0). */
static int grid_make(grid *G, const float *P, const uint32_t *vs, uint32_t n) {
    memset(G, 0, sizeof *G);
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = P[3 * (size_t)vs[0] + k];
    for (uint32_t i = 1; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            double x = P[3 * (size_t)vs[i] + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double cells = 2.0 * cbrt((double)n);
    if (cells < 8.0) cells = 8.0;
    if (cells > 256.0) cells = 256.0;
    G->h = diag / cells;
    if (!(G->h > 1e-6)) G->h = 1e-6;
    for (int k = 0; k < 3; ++k) G->lo[k] = lo[k];
    G->reach = (int32_t)ceil(diag / G->h) + 2;
    uint32_t size = 1;
    while (size < n && size < (1u << 30)) size <<= 1;
    G->mask = size - 1;
    G->start = calloc((size_t)size + 2, sizeof *G->start);
    G->items = malloc((size_t)n * sizeof *G->items);
    if (!G->start || !G->items) {
        grid_free(G);
        return -1;
    }
    int64_t c[3];
    for (uint32_t i = 0; i < n; ++i) {
        cell_of(G, P + 3 * (size_t)vs[i], c);
        G->start[cell_hash(G, c[0], c[1], c[2]) + 2]++;
    }
    for (uint32_t b = 0; b <= size; ++b) G->start[b + 1] += G->start[b];
    for (uint32_t i = 0; i < n; ++i) {
        cell_of(G, P + 3 * (size_t)vs[i], c);
        G->items[G->start[cell_hash(G, c[0], c[1], c[2]) + 1]++] = vs[i];
    }
    return 0;
}

static void visit(const grid *G, const float *P, const double q[3], int64_t x, int64_t y, int64_t z, double *best,
                  uint32_t *bi) {
    uint32_t b = cell_hash(G, x, y, z);
    for (uint32_t j = G->start[b]; j < G->start[b + 1]; ++j) {
        uint32_t v = G->items[j];
        const float *p = P + 3 * (size_t)v;
        double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
        double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < *best || (d2 == *best && v < *bi)) {
            *best = d2;
            *bi = v;
        }
    }
}

/* The grid's vertex nearest q (ties: the lowest index), NONE when empty.
 * After shell r every vertex not yet seen is at least r * h away. */
static uint32_t grid_nearest(const grid *G, const float *P, const float *qf) {
    const double q[3] = {qf[0], qf[1], qf[2]};
    int64_t c[3];
    cell_of(G, qf, c);
    double out = 0.0; /* how far q is outside the box, in cells */
    for (int k = 0; k < 3; ++k) {
        double t = fabs(((double)qf[k] - G->lo[k]) / G->h);
        if (t > out) out = t;
    }
    double best = INFINITY;
    uint32_t bi = NONE;
    if (out > (double)G->reach) { /* far outside the vertices' box: every one of them */
        for (uint32_t j = 0; j < G->start[G->mask + 1]; ++j) {
            uint32_t v = G->items[j];
            const float *p = P + 3 * (size_t)v;
            double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
            double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 < best || (d2 == best && v < bi)) {
                best = d2;
                bi = v;
            }
        }
        return bi;
    }
    const int64_t reach = 2 * (int64_t)G->reach + 2;
    for (int64_t r = 0; r <= reach; ++r) {
        for (int64_t dx = -r; dx <= r; ++dx)
            for (int64_t dy = -r; dy <= r; ++dy) {
                const int edge = dx == -r || dx == r || dy == -r || dy == r;
                for (int64_t dz = -r; dz <= r; dz += edge ? 1 : (r > 0 ? 2 * r : 1))
                    visit(G, P, q, c[0] + dx, c[1] + dy, c[2] + dz, &best, &bi);
            }
        if (bi != NONE && sqrt(best) <= (double)r * G->h) break;
    }
    return bi;
}

/* ------------------------------------------------------------ parents */

/* Sorting index arrays by (key, index) with a context, portably: pairs. */
typedef struct pair {
    float k;
    uint32_t i;
} pair;

static int pair_cmp(const void *a, const void *b) {
    const pair *x = a, *y = b;
    if (x->k != y->k) return x->k < y->k ? -1 : 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

typedef struct gpair {
    uint32_t g;
    float k;
    uint32_t i;
} gpair;

static int gpair_cmp(const void *a, const void *b) {
    const gpair *x = a, *y = b;
    if (x->g != y->g) return x->g < y->g ? -1 : 1;
    if (x->k != y->k) return x->k < y->k ? -1 : 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

/* Each element's parent: the element of the nearest wood vertex of a
 * lower level in its group. */
static int find_parents(build *B) {
    const banyan_mesh *m = B->m;
    const uint32_t V = m->vertex_count;
    /* wood vertices by (group, level, index); elements likewise */
    gpair *wood = malloc((size_t)V * sizeof *wood);
    gpair *el = malloc((size_t)B->n * sizeof *el);
    uint32_t *vs = malloc((size_t)V * sizeof *vs);
    if (!wood || !el || !vs) {
        free(wood);
        free(el);
        free(vs);
        return -1;
    }
    uint32_t nw = 0;
    for (uint32_t v = 0; v < V; ++v)
        if (!B->flutter || B->flutter[v] == 0.0f) wood[nw++] = (gpair){B->vgroup[v], B->att[3][v], v};
    for (uint32_t i = 0; i < B->n; ++i) el[i] = (gpair){B->e[i].group, B->e[i].key[3], i};
    qsort(wood, nw, sizeof *wood, gpair_cmp);
    qsort(el, B->n, sizeof *el, gpair_cmp);
    int rc = 0;
    uint32_t w0 = 0; /* the group's first wood vertex */
    for (uint32_t a = 0; a < B->n && rc == 0;) {
        const uint32_t g = el[a].g;
        uint32_t z = a;
        while (z < B->n && el[z].g == g) z++;
        while (w0 < nw && wood[w0].g < g) w0++;
        uint32_t w1 = w0;
        while (w1 < nw && wood[w1].g == g) w1++;
        /* levels ascending: the candidates are the group's wood below the level */
        grid G;
        memset(&G, 0, sizeof G);
        uint32_t built = 0; /* wood vertices in G */
        for (uint32_t i = a; i < z && rc == 0;) {
            const float L = el[i].k;
            uint32_t j = i;
            while (j < z && el[j].k == L) j++;
            uint32_t below = w0;
            while (below < w1 && wood[below].k < L) below++;
            const uint32_t cand = below - w0;
            if (cand > 0 && cand != built) {
                grid_free(&G);
                for (uint32_t t = 0; t < cand; ++t) vs[t] = wood[w0 + t].i;
                if (grid_make(&G, m->positions, vs, cand) != 0) rc = -1;
                built = cand;
            }
            for (uint32_t t = i; t < j && rc == 0; ++t) {
                elem *x = &B->e[el[t].i];
                if (cand == 0) continue; /* a root */
                uint32_t v = grid_nearest(&G, m->positions, x->key);
                if (v != NONE) x->parent = B->velem[v];
            }
            i = j;
        }
        grid_free(&G);
        a = z;
    }
    free(wood);
    free(el);
    free(vs);
    return rc;
}

/* ------------------------------------------------------------ the table */

void pp2_free(pp2_table *t) {
    if (!t) return;
    free(t->texel);
    free(t->pivot);
    free(t->axis);
    free(t->extent);
    free(t->parent);
    memset(t, 0, sizeof *t);
}

void pp2_texel_uv(const pp2_table *t, uint32_t k, float uv[2]) {
    uv[0] = (float)(((double)(k % t->width) + 0.5) / (double)t->width);
    uv[1] = (float)(((double)(k / t->width) + 0.5) / (double)t->height);
}

static void build_free(build *B) {
    free(B->vgroup);
    free(B->velem);
    free(B->e);
    free(B->slots);
}

static banyan_status nomem(build *B, pp2_table *t, banyan_error *err) {
    build_free(B);
    pp2_free(t);
    return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the Pivot Painter elements");
}

banyan_status pp2_build(const banyan_mesh *m, const char *what, pp2_table *t, banyan_error *err) {
    memset(t, 0, sizeof *t);
    if (!m) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s is NULL", what);
    static const char *const names[5] = {BANYAN_ATTR_WIND_PIVOT_X, BANYAN_ATTR_WIND_PIVOT_Y,
                                         BANYAN_ATTR_WIND_PIVOT_Z, BANYAN_ATTR_WIND_LEVEL, BANYAN_ATTR_WIND_PHASE};
    build B;
    memset(&B, 0, sizeof B);
    B.m = m;
    for (int k = 0; k < 5; ++k)
        if (!(B.att[k] = banyan_mesh_attribute(m, names[k])))
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                               "%s has no %s attribute: Pivot Painter needs the wind attributes (params wind = 1)",
                               what, names[k]);
    B.flutter = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_FLUTTER);
    const uint32_t V = m->vertex_count;
    if (V == 0) return banyan_fail(err, BANYAN_E_RANGE, "%s->vertex_count = 0: no vertices to paint", what);
    if (!m->positions) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s->positions is NULL", what);
    for (uint64_t i = 0; i < 3ull * V; ++i)
        if (!isfinite(m->positions[i]))
            return banyan_fail(err, BANYAN_E_RANGE, "%s->positions[%llu] = %g is not finite", what,
                               (unsigned long long)i, (double)m->positions[i]);
    for (int k = 0; k < 5; ++k)
        for (uint32_t v = 0; v < V; ++v)
            if (!isfinite(B.att[k][v]))
                return banyan_fail(err, BANYAN_E_RANGE, "%s attribute %s[%u] = %g is not finite", what, names[k], v,
                                   (double)B.att[k][v]);

    B.vgroup = calloc(V, sizeof *B.vgroup);
    B.velem = malloc((size_t)V * sizeof *B.velem);
    if (!B.vgroup || !B.velem || rehash(&B, 1024) != 0) return nomem(&B, t, err);
    for (uint32_t p = 0; p < m->part_count; ++p) {
        const banyan_part *pt = &m->parts[p];
        for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count && v < V; ++v)
            B.vgroup[v] = pt->group;
    }
    /* elements in the order of their first vertex, and each one's farthest own vertex */
    for (uint32_t v = 0; v < V; ++v) {
        uint32_t e = element_of(&B, v);
        if (e == NONE) return nomem(&B, t, err);
        B.velem[v] = e;
        elem *x = &B.e[e];
        const float *p = m->positions + 3 * (size_t)v;
        double dx = (double)p[0] - x->key[0], dy = (double)p[1] - x->key[1], dz = (double)p[2] - x->key[2];
        double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 > x->far_d2) {
            x->far_d2 = d2;
            x->far = v;
        }
    }
    if (find_parents(&B) != 0) return nomem(&B, t, err);

    /* depth, parents first (a parent's level is lower) */
    pair *order = malloc((size_t)B.n * sizeof *order);
    if (!order) return nomem(&B, t, err);
    for (uint32_t i = 0; i < B.n; ++i) order[i] = (pair){B.e[i].key[3], i};
    qsort(order, B.n, sizeof *order, pair_cmp);
    uint32_t at_depth[PP2_LEVELS] = {0, 0, 0, 0};
    for (uint32_t o = 0; o < B.n; ++o) {
        elem *x = &B.e[order[o].i];
        x->depth = x->parent == order[o].i ? 0 : B.e[x->parent].depth + 1;
        if (x->depth < PP2_LEVELS) at_depth[x->depth]++;
    }
    /* the levels kept: four, or fewer when four need more texels than an index can name */
    uint32_t levels = PP2_LEVELS, kept = 0;
    for (; levels > 1; --levels) {
        kept = 0;
        for (uint32_t d = 0; d < levels; ++d) kept += at_depth[d];
        if (kept <= BANYAN_PP2_MAX_ELEMENTS) break;
    }
    if (levels == 1) kept = at_depth[0];
    if (kept > BANYAN_PP2_MAX_ELEMENTS) {
        free(order);
        build_free(&B);
        return banyan_fail(err, BANYAN_E_RANGE,
                           "%s has %u roots (Pivot Painter elements with no parent), more than the %u a texture's "
                           "parent index can name",
                           what, kept, BANYAN_PP2_MAX_ELEMENTS);
    }
    /* an element deeper than the levels kept reads its ancestor levels - 1 steps below the root */
    for (uint32_t o = 0; o < B.n; ++o) {
        elem *x = &B.e[order[o].i];
        const elem *p = &B.e[x->parent];
        if (x->depth < levels) x->rep = order[o].i;
        else x->rep = p->depth == levels - 1 ? x->parent : p->rep;
    }
    free(order);
    uint32_t depth = 0;
    kept = 0;
    for (uint32_t i = 0; i < B.n; ++i) {
        if (B.e[i].rep != i) continue;
        B.e[i].index = kept++;
        if (B.e[i].depth + 1 > depth) depth = B.e[i].depth + 1;
    }

    t->vertex_count = V;
    t->elements = kept;
    t->merged = B.n - kept;
    t->depth = depth;
    uint32_t w = 1, h = 1;
    while ((uint64_t)w * w < kept) w <<= 1;
    while ((uint64_t)w * h < kept) h <<= 1;
    t->width = w;
    t->height = h;
    t->texel = malloc((size_t)V * sizeof *t->texel);
    t->pivot = malloc(3 * (size_t)kept * sizeof *t->pivot);
    t->axis = malloc(3 * (size_t)kept * sizeof *t->axis);
    t->extent = calloc(kept, sizeof *t->extent);
    t->parent = malloc((size_t)kept * sizeof *t->parent);
    if (!t->texel || !t->pivot || !t->axis || !t->extent || !t->parent) return nomem(&B, t, err);
    for (uint32_t i = 0; i < B.n; ++i) {
        const elem *x = &B.e[i];
        if (x->rep != i) continue;
        const uint32_t k = x->index;
        for (int c = 0; c < 3; ++c) t->pivot[3 * k + c] = x->key[c];
        t->parent[k] = B.e[x->parent].index; /* a kept element's parent is kept */
        const float *f = m->positions + 3 * (size_t)x->far;
        double a[3] = {(double)f[0] - x->key[0], (double)f[1] - x->key[1], (double)f[2] - x->key[2]};
        double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (int c = 0; c < 3; ++c) t->axis[3 * k + c] = len > 0.0 ? (float)(a[c] / len) : (c == 2 ? 1.0f : 0.0f);
    }
    for (uint32_t v = 0; v < V; ++v) {
        const uint32_t k = B.e[B.e[B.velem[v]].rep].index;
        t->texel[v] = k;
        const float *p = m->positions + 3 * (size_t)v, *q = t->pivot + 3 * k, *a = t->axis + 3 * k;
        double d = ((double)p[0] - q[0]) * a[0] + ((double)p[1] - q[1]) * a[1] + ((double)p[2] - q[2]) * a[2];
        if (d > t->extent[k]) t->extent[k] = (float)d;
    }
    build_free(&B);
    return BANYAN_OK;
}

/* ------------------------------------------------------------ the files */

static uint8_t unit_byte(double x) { /* [0, 1] -> 0 .. 255, nearest */
    if (!(x > 0.0)) return 0;
    if (x >= 1.0) return 255;
    return (uint8_t)floor(x * 255.0 + 0.5);
}

/* d as the nearest half (ties to even), rounded once: when d's float is
 * inexact and sits on a tie between two halves, the float one step
 * towards d decides, as d itself would. */
static uint16_t half_of(double d) {
    float f = (float)d;
    uint32_t bits;
    memcpy(&bits, &f, 4);
    if ((double)f != d && (bits & 0x1fffu) == 0x1000u) f = nextafterf(f, d > (double)f ? INFINITY : -INFINITY);
    return exr_half_from_float(f);
}

static const char kPosSuffix[] = "_PivotPos_Index.exr";
static const char kAxisSuffix[] = "_XVector_Extent.png";

banyan_status banyan_pivot_painter_write(const char *prefix, const banyan_mesh *mesh,
                                         const banyan_pivot_painter_options *opt, banyan_pivot_painter_info *info,
                                         banyan_error *err) {
    if (info) memset(info, 0, sizeof *info);
    if (!prefix) return banyan_fail(err, BANYAN_E_INVALID_ARG, "prefix is NULL");
    const size_t plen = strlen(prefix);
    if (plen == 0) return banyan_fail(err, BANYAN_E_INVALID_ARG, "prefix is empty: give a path without the suffix");
    if (plen >= 4000) return banyan_fail(err, BANYAN_E_RANGE, "prefix is %zu bytes long, more than 3999", plen);
    if (!mesh) return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh is NULL");
    double scale = 100.0;
    int sync = 0;
    if (opt) {
        if (opt->scale != 0.0) {
            if (!(opt->scale > 0.0 && opt->scale <= 10000.0))
                return banyan_fail(err, BANYAN_E_RANGE,
                                   "opt->scale = %g must be 0 (100: centimetres) or within (0, 10000] texture units "
                                   "per metre",
                                   opt->scale);
            scale = opt->scale;
        }
        if (opt->sync != 0 && opt->sync != 1)
            return banyan_fail(err, BANYAN_E_RANGE, "opt->sync = %d must be 0 (no fsync) or 1 (fsync before the rename)",
                               opt->sync);
        sync = opt->sync;
    }
    char *paths[2] = {malloc(plen + sizeof kPosSuffix), malloc(plen + sizeof kAxisSuffix)};
    if (!paths[0] || !paths[1]) {
        free(paths[0]);
        free(paths[1]);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    }
    memcpy(paths[0], prefix, plen);
    memcpy(paths[0] + plen, kPosSuffix, sizeof kPosSuffix);
    memcpy(paths[1], prefix, plen);
    memcpy(paths[1] + plen, kAxisSuffix, sizeof kAxisSuffix);
    banyan_status s = BANYAN_OK;
    char why[200];
    for (int f = 0; f < 2 && s == BANYAN_OK; ++f)
        if (atomic_check(paths[f], why, sizeof why) != 0)
            s = banyan_fail(err, BANYAN_E_IO, "prefix '%.200s': cannot write %.300s: %s", prefix, paths[f], why);

    pp2_table t;
    memset(&t, 0, sizeof t);
    if (s == BANYAN_OK) s = pp2_build(mesh, "mesh", &t, err);
    uint16_t *half = NULL;
    uint8_t *bytes = NULL, *exr = NULL, *png = NULL;
    size_t exr_len = 0, png_len = 0;
    if (s == BANYAN_OK) {
        const size_t n = (size_t)t.width * t.height;
        half = malloc(4 * n * sizeof *half);
        bytes = malloc(4 * n);
        if (!half || !bytes) s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the textures");
        for (size_t k = 0; k < n && s == BANYAN_OK; ++k) {
            uint16_t *o = half + 4 * k;
            uint8_t *b = bytes + 4 * k;
            if (k >= t.elements) { /* a root at the origin, pointing up */
                o[0] = o[1] = o[2] = 0;
                o[3] = (uint16_t)(1024u + k);
                b[0] = b[1] = 128;
                b[2] = 255;
                b[3] = 0;
                continue;
            }
            const float *p = t.pivot + 3 * k, *a = t.axis + 3 * k;
            const double u[3] = {scale * p[0], -scale * p[1], scale * p[2]}; /* Unreal: (x, -y, z) */
            for (int c = 0; c < 3; ++c) {
                if (fabs(u[c]) > 65504.0) {
                    s = banyan_fail(err, BANYAN_E_RANGE,
                                    "mesh element %zu's pivot is %g texture units from the mesh's origin, past a half "
                                    "float's 65504: lower opt->scale (%g)",
                                    k, fabs(u[c]), scale);
                    break;
                }
                o[c] = half_of(u[c]);
            }
            o[3] = (uint16_t)(1024u + t.parent[k]);
            b[0] = unit_byte(0.5 + 0.5 * a[0]);
            b[1] = unit_byte(0.5 - 0.5 * a[1]);
            b[2] = unit_byte(0.5 + 0.5 * a[2]);
            b[3] = unit_byte(scale * t.extent[k] / 2048.0);
        }
    }
    if (s == BANYAN_OK && exr_half_encode(half, t.width, t.height, &exr, &exr_len, why, sizeof why) != 0)
        s = banyan_fail(err, BANYAN_E_NOMEM, "the Pivot Position texture: %s", why);
    if (s == BANYAN_OK) {
        int r = png_write(bytes, (int)t.width, (int)t.height, 4, PNG_WRITE_FILTER, PNG_WRITE_LEVEL, NULL, &png, &png_len);
        if (r != 0) s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the X Vector texture");
    }
    /* both files whole in their temporaries before either is renamed */
    atomic_file af[2];
    memset(af, 0, sizeof af);
    const uint8_t *data[2] = {exr, png};
    const size_t len[2] = {exr_len, png_len};
    for (int f = 0; f < 2 && s == BANYAN_OK; ++f) {
        int e = atomic_open(&af[f], paths[f]);
        if (e == 0) {
            af[f].sync = sync;
            if (fwrite(data[f], 1, len[f], af[f].f) != len[f] || fflush(af[f].f) != 0) e = errno ? errno : EIO;
        }
        if (e != 0) s = banyan_fail(err, BANYAN_E_IO, "cannot write %.300s: %s", paths[f], strerror(e));
    }
    for (int f = 0; f < 2; ++f) {
        if (s != BANYAN_OK) {
            atomic_abort(&af[f]);
            continue;
        }
        int e = atomic_commit(&af[f]);
        if (e != 0) s = banyan_fail(err, BANYAN_E_IO, "cannot write %.300s: %s", paths[f], strerror(e));
    }
    if (s == BANYAN_OK && info) {
        info->elements = t.elements;
        info->merged = t.merged;
        info->width = t.width;
        info->height = t.height;
        info->depth = t.depth;
    }
    pp2_free(&t);
    free(half);
    free(bytes);
    free(exr);
    free(png);
    free(paths[0]);
    free(paths[1]);
    return s;
}
