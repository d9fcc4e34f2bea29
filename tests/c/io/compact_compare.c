/* compact_compare.c - a compact .glb (banyan_gltf_options.compact) against
 * the plain .glb of the same plant, decoded here with meshoptimizer's own
 * decoders and dequantized by the node transforms:
 *
 *   compact_compare [--engine-uvs] PLAIN.glb COMPACT.glb [MAX_RATIO]
 *
 * Checks: both extensions required; the same nodes (MSFT_lod ids and
 * coverage kept), meshes, primitives, attribute names and triangles (the
 * same corners in the same winding); every POSITION and wind pivot, through its node's
 * translation and scale, within one quantization step of the plain one
 * (pivots in the positions' frame: position - pivot is the same arm);
 * normals and tangents within 8-bit octahedral error; TEXCOORD_0 within
 * its mantissa rounding; every other attribute bit for bit; and, given
 * MAX_RATIO, compact size <= MAX_RATIO * plain size. Exit 0 when all hold. */
#include "check.h"

#include <cjson/cJSON.h>
#include <meshoptimizer.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    unsigned char *file;
    size_t size;
    cJSON *json;
    const unsigned char *bin;
    size_t bin_len;
    unsigned char **decoded; /* per bufferView, compressed ones decoded */
    int n_views;
} Glb;

static uint32_t le32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static cJSON *item(const cJSON *o, const char *k) { return o ? cJSON_GetObjectItemCaseSensitive(o, k) : NULL; }
static double num(const cJSON *o, const char *k, double def) {
    const cJSON *v = item(o, k);
    return cJSON_IsNumber(v) ? v->valuedouble : def;
}

static int glb_open(Glb *g, const char *path) {
    memset(g, 0, sizeof *g);
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    g->file = malloc((size_t)n);
    g->size = (size_t)n;
    if (!g->file || fread(g->file, 1, g->size, f) != g->size) {
        fclose(f);
        return 0;
    }
    fclose(f);
    if (g->size < 28 || memcmp(g->file, "glTF", 4)) return 0;
    uint32_t jl = le32(g->file + 12);
    g->json = cJSON_ParseWithLength((const char *)g->file + 20, jl);
    if (!g->json) return 0;
    if (20 + jl + 8 <= g->size) {
        g->bin_len = le32(g->file + 20 + jl);
        g->bin = g->file + 28 + jl;
    }
    g->n_views = cJSON_GetArraySize(item(g->json, "bufferViews"));
    g->decoded = calloc((size_t)g->n_views + 1, sizeof *g->decoded);
    return g->decoded != NULL;
}

static void glb_close(Glb *g) {
    for (int i = 0; i < g->n_views; ++i) free(g->decoded[i]);
    free(g->decoded);
    cJSON_Delete(g->json);
    free(g->file);
}

/* A bufferView's bytes: raw, or decoded from its EXT_meshopt_compression data. */
static const unsigned char *view_bytes(Glb *g, int v) {
    if (v < 0 || v >= g->n_views) return NULL;
    const cJSON *bv = cJSON_GetArrayItem(item(g->json, "bufferViews"), v);
    const cJSON *ext = item(item(bv, "extensions"), "EXT_meshopt_compression");
    if (!ext) {
        if (num(bv, "buffer", 0) != 0) return NULL;
        return g->bin + (size_t)num(bv, "byteOffset", 0);
    }
    if (g->decoded[v]) return g->decoded[v];
    size_t count = (size_t)num(ext, "count", 0), stride = (size_t)num(ext, "byteStride", 0);
    const unsigned char *src = g->bin + (size_t)num(ext, "byteOffset", 0);
    size_t len = (size_t)num(ext, "byteLength", 0);
    const char *mode = cJSON_GetStringValue(item(ext, "mode"));
    const char *filter = cJSON_GetStringValue(item(ext, "filter"));
    unsigned char *out = calloc(count ? count : 1, stride);
    int rc = -1;
    if (mode && !strcmp(mode, "ATTRIBUTES")) {
        rc = meshopt_decodeVertexBuffer(out, count, stride, src, len);
        if (rc == 0 && filter && !strcmp(filter, "OCTAHEDRAL")) meshopt_decodeFilterOct(out, count, stride);
        else if (rc == 0 && filter && strcmp(filter, "NONE")) rc = -2; /* not written by banyan */
    } else if (mode && !strcmp(mode, "TRIANGLES")) {
        rc = meshopt_decodeIndexBuffer(out, count, stride, src, len);
    } else if (mode && !strcmp(mode, "INDICES")) {
        rc = meshopt_decodeIndexSequence(out, count, stride, src, len);
    }
    CHECK(rc == 0, "bufferView %d (%s) does not decode: %d", v, mode ? mode : "?", rc);
    if (rc != 0) {
        free(out);
        return NULL;
    }
    g->decoded[v] = out;
    return out;
}

static int width_of(const char *t) {
    return !strcmp(t, "SCALAR") ? 1 : !strcmp(t, "VEC2") ? 2 : !strcmp(t, "VEC3") ? 3 : !strcmp(t, "VEC4") ? 4 : 0;
}

/* Accessor a as doubles (count * width), normalized integers as glTF defines them. */
static double *read_accessor(Glb *g, int a, uint32_t *count, int *width) {
    const cJSON *j = cJSON_GetArrayItem(item(g->json, "accessors"), a);
    int ct = (int)num(j, "componentType", 0), w = width_of(cJSON_GetStringValue(item(j, "type")));
    int norm = cJSON_IsTrue(item(j, "normalized"));
    int v = (int)num(j, "bufferView", -1);
    const cJSON *bv = cJSON_GetArrayItem(item(g->json, "bufferViews"), v);
    const unsigned char *base = view_bytes(g, v);
    if (!base || !w) return NULL;
    base += (size_t)num(j, "byteOffset", 0);
    size_t cs = ct == 5120 || ct == 5121 ? 1 : ct == 5122 || ct == 5123 ? 2 : 4;
    size_t stride = (size_t)num(bv, "byteStride", (double)(cs * (size_t)w));
    *count = (uint32_t)num(j, "count", 0);
    *width = w;
    double *out = malloc(sizeof(double) * *count * (size_t)w + 1);
    for (uint32_t i = 0; i < *count; ++i)
        for (int k = 0; k < w; ++k) {
            const unsigned char *p = base + i * stride + (size_t)k * cs;
            double x = 0;
            switch (ct) {
            case 5120: x = norm ? fmax(*(const int8_t *)p / 127.0, -1.0) : *(const int8_t *)p; break;
            case 5121: x = norm ? *p / 255.0 : *p; break;
            case 5122: { int16_t s; memcpy(&s, p, 2); x = norm ? fmax(s / 32767.0, -1.0) : s; } break;
            case 5123: { uint16_t s; memcpy(&s, p, 2); x = norm ? s / 65535.0 : s; } break;
            case 5125: { uint32_t s; memcpy(&s, p, 4); x = s; } break;
            case 5126: { float s; memcpy(&s, p, 4); x = s; } break;
            }
            out[(size_t)i * (size_t)w + (size_t)k] = x;
        }
    return out;
}

/* Node n's translation and (uniform) scale. */
static void node_frame(const cJSON *n, double t[3], double s[3]) {
    for (int k = 0; k < 3; ++k) {
        const cJSON *e = cJSON_GetArrayItem(item(n, "translation"), k);
        const cJSON *f = cJSON_GetArrayItem(item(n, "scale"), k);
        t[k] = cJSON_IsNumber(e) ? e->valuedouble : 0;
        s[k] = cJSON_IsNumber(f) ? f->valuedouble : 1;
    }
}

static int has_required(const cJSON *root, const char *name) {
    const cJSON *e;
    cJSON_ArrayForEach(e, item(root, "extensionsRequired")) if (cJSON_IsString(e) && !strcmp(e->valuestring, name)) return 1;
    return 0;
}

/* The axis of a pivot value: component k of attribute `key` (-1: not a pivot).
 * With --engine-uvs, TEXCOORD_1 holds the arm's (pivot - position) x and
 * y, TEXCOORD_2 its z and the level (docs/game-engines.md); an arm is a
 * difference, scaled by the node but not moved. */
static int engine_uvs;
static int pivot_axis(const char *key, int k) {
    if (!strcmp(key, "_WIND_PIVOT_X")) return 0;
    if (!strcmp(key, "_WIND_PIVOT_Y")) return 1;
    if (!strcmp(key, "_WIND_PIVOT_Z")) return 2;
    if (engine_uvs && !strcmp(key, "TEXCOORD_1")) return k;
    if (engine_uvs && !strcmp(key, "TEXCOORD_2") && k == 0) return 2;
    return -1;
}

static long compared_values, compared_attributes;
static double worst_position, worst_pivot; /* in steps */

/* One primitive's attribute `key` of plain node pn against compact node cn. */
static void compare_attribute(Glb *p, Glb *c, const cJSON *pn, const cJSON *cn, const char *key, int pa, int ca) {
    uint32_t np, nc;
    int wp, wc;
    double *a = read_accessor(p, pa, &np, &wp), *b = read_accessor(c, ca, &nc, &wc);
    CHECK(a && b && np == nc && wp == wc, "%s: %u x %d values against %u x %d", key, np, wp, nc, wc);
    if (!a || !b || np != nc || wp != wc) {
        free(a);
        free(b);
        return;
    }
    double pt[3], ps[3], ct[3], cs[3];
    node_frame(pn, pt, ps);
    node_frame(cn, ct, cs);
    const int is_pos = !strcmp(key, "POSITION"), pivots = pivot_axis(key, 0) >= 0;
    const int is_dir = !strcmp(key, "NORMAL") || !strcmp(key, "TANGENT");
    const int framed = item(cn, "scale") != NULL;
    long bad = 0;
    for (uint32_t i = 0; i < np; ++i) {
        const double *x = a + (size_t)i * (size_t)wp, *y = b + (size_t)i * (size_t)wp;
        if (is_pos || pivots) {
            /* Both through their nodes: the plain node has no scale. */
            for (int k = 0; k < wp; ++k) {
                const int ax = is_pos ? k : pivot_axis(key, k);
                if (ax < 0) { /* the level beside pivot z */
                    if (x[k] != y[k]) bad++;
                    continue;
                }
                const int arm = !is_pos && key[0] == 'T'; /* TEXCOORD_1, _2 */
                const double want = (arm ? 0.0 : pt[ax]) + x[k], got = (arm ? 0.0 : ct[ax]) + cs[ax] * y[k];
                const double step = cs[ax], err = fabs(got - want) / step;
                if (framed && is_pos && err > worst_position) worst_position = err;
                if (framed && !is_pos && err > worst_pivot) worst_pivot = err;
                /* Quantized (the node has a scale): half a step from rounding, plus
                 * float rounding of the plain value; else the same floats. */
                if (framed ? fabs(got - want) > 0.5 * step + 1e-6 * (1 + fabs(want)) : x[k] != y[k]) bad++;
            }
        } else if (is_dir) {
            double dot = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
            double ly = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
            if (!(dot > 0.995 * ly) || fabs(ly - 1) > 0.02) bad++; /* under 6 degrees off, unit length */
            if (wp == 4 && x[3] != y[3]) bad++;                    /* handedness */
        } else if (!strcmp(key, "TEXCOORD_0")) {
            for (int k = 0; k < wp; ++k)
                if (fabs(x[k] - y[k]) > fabs(x[k]) * ldexp(1.0, -13) + 1e-30) bad++;
        } else {
            for (int k = 0; k < wp; ++k)
                if (x[k] != y[k]) bad++;
        }
        compared_values += wp;
    }
    CHECK(bad == 0, "%s: %ld of %u values out of tolerance", key, bad, np);
    compared_attributes++;
    free(a);
    free(b);
}

static size_t count_keys(const cJSON *o) {
    size_t n = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, o) n++;
    return n;
}

/* Plain node pi and compact node ci: their meshes, primitive by primitive. */
static void compare_node(Glb *p, Glb *c, int pi, int ci, long *triangles) {
    const cJSON *pn = cJSON_GetArrayItem(item(p->json, "nodes"), pi);
    const cJSON *cn = cJSON_GetArrayItem(item(c->json, "nodes"), ci);
    const int pm = (int)num(pn, "mesh", -1), cm = (int)num(cn, "mesh", -1);
    CHECK(pm == cm, "node %d: mesh %d against %d", pi, pm, cm);
    if (pm < 0 || pm != cm) return;
    const cJSON *pp = item(cJSON_GetArrayItem(item(p->json, "meshes"), pm), "primitives");
    const cJSON *cp = item(cJSON_GetArrayItem(item(c->json, "meshes"), cm), "primitives");
    CHECK(cJSON_GetArraySize(pp) == cJSON_GetArraySize(cp), "mesh %d: primitive counts differ", pm);
    for (int k = 0; k < cJSON_GetArraySize(pp) && k < cJSON_GetArraySize(cp); ++k) {
        const cJSON *a = cJSON_GetArrayItem(pp, k), *b = cJSON_GetArrayItem(cp, k);
        const cJSON *aa = item(a, "attributes"), *ba = item(b, "attributes");
        CHECK(count_keys(aa) == count_keys(ba), "mesh %d primitive %d: %zu attributes against %zu", pm, k,
              count_keys(aa), count_keys(ba));
        const cJSON *at;
        cJSON_ArrayForEach(at, aa) {
            const cJSON *bt = item(ba, at->string);
            CHECK(bt != NULL, "mesh %d primitive %d: %s is missing", pm, k, at->string);
            if (bt) compare_attribute(p, c, pn, cn, at->string, at->valueint, bt->valueint);
        }
        uint32_t ni, nj;
        int w1, w2;
        double *x = read_accessor(p, (int)num(a, "indices", -1), &ni, &w1);
        double *y = read_accessor(c, (int)num(b, "indices", -1), &nj, &w2);
        CHECK(x && y && ni == nj, "mesh %d primitive %d: %u indices against %u", pm, k, ni, nj);
        if (x && y && ni == nj) {
            /* The index codec may rotate a triangle's corners (the winding stays). */
            long moved = 0;
            for (uint32_t t = 0; t + 2 < ni; t += 3) {
                int same = 0;
                for (int r = 0; r < 3 && !same; ++r)
                    same = x[t] == y[t + r] && x[t + 1] == y[t + (r + 1) % 3] && x[t + 2] == y[t + (r + 2) % 3];
                moved += !same;
            }
            CHECK(moved == 0, "mesh %d primitive %d: %ld triangles differ", pm, k, moved);
            *triangles += ni / 3;
        }
        free(x);
        free(y);
    }
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: compact_compare [--engine-uvs] PLAIN.glb COMPACT.glb [MAX_RATIO]\n");
        return 2;
    }
    if (!strcmp(argv[1], "--engine-uvs")) {
        engine_uvs = 1;
        argv++;
        argc--;
    }
    Glb p, c;
    int okp = glb_open(&p, argv[1]), okc = glb_open(&c, argv[2]);
    CHECK(okp && okc, "cannot read %s or %s as .glb", argv[1], argv[2]);
    if (!okp || !okc) return 1;
    CHECK(has_required(c.json, "EXT_meshopt_compression") && has_required(c.json, "KHR_mesh_quantization"),
          "the compact file does not require both extensions");
    CHECK(!item(p.json, "extensionsRequired"), "the plain file requires an extension");
    const cJSON *pnodes = item(p.json, "nodes"), *cnodes = item(c.json, "nodes");
    CHECK(cJSON_GetArraySize(pnodes) == cJSON_GetArraySize(cnodes), "node counts differ");
    CHECK(cJSON_GetArraySize(item(p.json, "meshes")) == cJSON_GetArraySize(item(c.json, "meshes")), "mesh counts differ");
    long tp = 0;
    int lods = 0;
    for (int i = 0; i < cJSON_GetArraySize(pnodes) && i < cJSON_GetArraySize(cnodes); ++i) {
        compare_node(&p, &c, i, i, &tp);
        const cJSON *pl = item(item(cJSON_GetArrayItem(pnodes, i), "extensions"), "MSFT_lod");
        const cJSON *cl = item(item(cJSON_GetArrayItem(cnodes, i), "extensions"), "MSFT_lod");
        char *a = pl ? cJSON_PrintUnformatted(pl) : NULL, *b = cl ? cJSON_PrintUnformatted(cl) : NULL;
        CHECK((!a && !b) || (a && b && !strcmp(a, b)), "node %d: MSFT_lod %s against %s", i, a ? a : "none", b ? b : "none");
        char *x = cJSON_PrintUnformatted(item(cJSON_GetArrayItem(pnodes, i), "extras"));
        char *y = cJSON_PrintUnformatted(item(cJSON_GetArrayItem(cnodes, i), "extras"));
        CHECK((!x && !y) || (x && y && !strcmp(x, y)), "node %d: extras (MSFT_screencoverage) differ", i);
        lods += pl != NULL;
        cJSON_free(a);
        cJSON_free(b);
        cJSON_free(x);
        cJSON_free(y);
    }
    CHECK(compared_attributes > 0 && tp > 0, "nothing compared");
    const double ratio = (double)c.size / (double)p.size;
    printf("%s: %ld triangles, %ld attributes (%ld values) compared, %d nodes with MSFT_lod; worst position %.3f "
           "steps, worst pivot %.3f steps; size %zu / %zu = %.3f\n",
           argv[2], tp, compared_attributes, compared_values, lods, worst_position, worst_pivot, c.size, p.size, ratio);
    if (argc > 3) {
        const double max_ratio = atof(argv[3]);
        CHECK(ratio <= max_ratio, "compact / plain size %.4f is over %.4f", ratio, max_ratio);
    }
    glb_close(&p);
    glb_close(&c);
    printf("%d passed, %d failed\n", check_passed, check_failed);
    return check_failed ? 1 : 0;
}
