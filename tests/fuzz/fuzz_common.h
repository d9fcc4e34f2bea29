/* fuzz_common.h - what the generator harnesses share: raw bytes turned
 * into hostile but type-correct params through the generator's parameter
 * table, hosts and segment inputs from bytes, and the invariants every
 * answer must keep (a failure aborts, which libFuzzer reports as a crash).
 *
 * Input format: a sequence of records, each a tag byte and its payload
 * (missing bytes read as 0):
 *   tag < 0xF0   a parameter: row = tag % row count, then a mode byte and
 *                8 payload bytes. Mode & 7: 0 raw bits (doubles may be
 *                NaN or inf; ints any int32), 1 uniform in [min, max],
 *                2 min, 3 max, 4 just below min, 5 just above max,
 *                6 a small signed integer, 7 log-uniform in [min, max].
 *                (mode >> 3) & 3 picks the component of a vector.
 *   0xF0         a host, compact: centre 3 x int16 / 2000 m, half 3 x u8
 *                (0 -> 0 m, else 0.02 + b / 25 m), rotation 3 x u8 Euler
 *                XYZ (b * 360 / 256 deg), a flags byte (1: scale the
 *                rotation by 1.5, 2: mirror it).
 *   0xF1         a host, raw: the 120 bytes of a banyan_box.
 *   0xF2         a segment input, raw: the bytes of a banyan_segment_input.
 *   0xF3         a segment input, compact: S 3 x int16 / 1000 m, A 3 x int8,
 *                l u8 / 32 m, n u8 % 70, s u8 % 70.
 *   0xF4         the trunk line, raw: 6 doubles.
 *   0xF5         a control byte for the harness (threads, stepping).
 *   0xF6         real size: the harness keeps the input's sizes (levels,
 *                steps, growth points...) instead of shrinking them, and
 *                relies on the run budget (fz_budget) to stop in time.
 *   others       skipped.
 * tests/fuzz/fuzz_seeds.c writes presets in this format. */
#ifndef BANYAN_FUZZ_COMMON_H
#define BANYAN_FUZZ_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"

#define FZ_MAX_HOSTS 8
#define FZ_MAX_SEGS 256
#define FZ_MAX_CONTROL 8

enum { FZ_HOST_COMPACT = 0xF0, FZ_HOST_RAW, FZ_SEG_RAW, FZ_SEG_COMPACT, FZ_TRUNK, FZ_CONTROL, FZ_REAL };

typedef struct fz_input {
    banyan_box hosts[FZ_MAX_HOSTS];
    uint32_t n_hosts;
    banyan_segment_input segs[FZ_MAX_SEGS];
    uint32_t n_segs;
    double trunk[6];
    int has_trunk;
    uint8_t control[FZ_MAX_CONTROL];
    int n_control;
    int real; /* an FZ_REAL record: keep the input's sizes */
} fz_input;

typedef struct fz_reader {
    const uint8_t *p;
    size_t n, i;
} fz_reader;

static inline int fz_more(const fz_reader *r) { return r->i < r->n; }
static inline uint8_t fz_u8(fz_reader *r) { return r->i < r->n ? r->p[r->i++] : 0; }
static inline void fz_bytes(fz_reader *r, void *out, size_t k) {
    unsigned char *o = out;
    for (size_t j = 0; j < k; j++) o[j] = fz_u8(r);
}
static inline int16_t fz_i16(fz_reader *r) {
    uint16_t lo = fz_u8(r), hi = fz_u8(r);
    return (int16_t)(uint16_t)(lo | hi << 8);
}

/* The generator's params_init, by generator. */
static inline void fz_params_init(banyan_generator g, void *p) {
    switch (g) {
    case BANYAN_GEN_ROOTS: banyan_roots_params_init(p); break;
    case BANYAN_GEN_KEYAKI: banyan_keyaki_params_init(p); break;
    case BANYAN_GEN_AVENUE: banyan_avenue_params_init(p); break;
    case BANYAN_GEN_IVY: banyan_ivy_params_init(p); break;
    default: banyan_segments_params_init(p); break;
    }
}

static inline int fz_components(int type) { return type == BANYAN_PT_VEC3 ? 3 : type == BANYAN_PT_COLOR ? 4 : 1; }

static inline int fz_choices(const char *c) {
    int n = 1;
    for (; c && *c; c++) n += *c == '|';
    return n;
}

/* The value a mode asks for; raw modes are handled by the caller. */
static inline double fz_value(const banyan_param_info *info, int mode, const uint8_t pay[8]) {
    double lo = info->min, hi = info->max;
    if (info->type == BANYAN_PT_ENUM) lo = 0, hi = fz_choices(info->choices) - 1;
    uint64_t u;
    memcpy(&u, pay, 8);
    double t = (double)(u >> 11) / 9007199254740992.0; /* [0, 1) */
    double span = hi - lo, v;
    switch (mode) {
    case 1: v = lo + t * span; break;
    case 2: v = lo; break;
    case 3: v = hi; break;
    case 4: v = lo - (span > 0 ? span * 1e-3 : 1.0) - (info->type == BANYAN_PT_DOUBLE ? 0.0 : 1.0); break;
    case 5: v = hi + (span > 0 ? span * 1e-3 : 1.0) + (info->type == BANYAN_PT_DOUBLE ? 0.0 : 1.0); break;
    case 6: v = (double)(int8_t)pay[0]; break;
    default: /* 7: log-uniform where the range is positive, else uniform */
        if (lo > 0) v = exp(log(lo) + t * (log(hi) - log(lo)));
        else v = lo + t * span;
        break;
    }
    if (info->type != BANYAN_PT_DOUBLE && info->type != BANYAN_PT_VEC3 && info->type != BANYAN_PT_COLOR)
        v = floor(v + 0.5);
    return v;
}

/* Writes one parameter record into params. */
static inline void fz_param(banyan_generator g, void *params, uint8_t tag, fz_reader *r) {
    int32_t count = banyan_param_count(g);
    uint8_t mode = fz_u8(r), pay[8];
    fz_bytes(r, pay, 8);
    if (count <= 0) return;
    const banyan_param_info *info = banyan_param_get(g, tag % count);
    char *f = (char *)params + info->offset;
    int comp = ((mode >> 3) & 3) % fz_components(info->type);
    switch (info->type) {
    case BANYAN_PT_SEED: memcpy(f, pay, 8); return;
    case BANYAN_PT_INT:
    case BANYAN_PT_BOOL:
    case BANYAN_PT_ENUM: {
        int32_t x;
        if ((mode & 7) == 0) memcpy(&x, pay, 4);
        else {
            double v = fz_value(info, mode & 7, pay);
            x = v <= INT32_MIN ? INT32_MIN : v >= INT32_MAX ? INT32_MAX : (int32_t)v;
        }
        memcpy(f, &x, 4);
        return;
    }
    default: {
        double v;
        if ((mode & 7) == 0) memcpy(&v, pay, 8);
        else v = fz_value(info, mode & 7, pay);
        memcpy(f + sizeof(double) * (size_t)comp, &v, 8);
        return;
    }
    }
}

static inline void fz_rotation(double rx, double ry, double rz, double out[9]) {
    /* Blender's XYZ Euler, R = Rz Ry Rx, row-major. */
    double cx = cos(rx), sx = sin(rx), cy = cos(ry), sy = sin(ry), cz = cos(rz), sz = sin(rz);
    double R[9] = {cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx,
                   sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx,
                   -sy,     cy * sx,                cy * cx};
    memcpy(out, R, sizeof R);
}

/* Reads every record: params into `params` (may be NULL to skip them),
 * the rest into *in. */
static inline void fz_read(banyan_generator g, void *params, const uint8_t *data, size_t size, fz_input *in) {
    memset(in, 0, sizeof *in);
    fz_reader r = {data, size, 0};
    while (fz_more(&r)) {
        uint8_t tag = fz_u8(&r);
        if (tag < 0xF0) {
            if (params) fz_param(g, params, tag, &r);
            else fz_bytes(&r, (uint8_t[9]){0}, 9);
        } else if (tag == FZ_HOST_COMPACT) {
            banyan_box b;
            for (int k = 0; k < 3; k++) b.center[k] = fz_i16(&r) / 2000.0;
            for (int k = 0; k < 3; k++) {
                uint8_t h = fz_u8(&r);
                b.half[k] = h ? 0.02 + h / 25.0 : 0.0;
            }
            double e[3];
            for (int k = 0; k < 3; k++) e[k] = fz_u8(&r) * (2.0 * 3.14159265358979323846 / 256.0);
            fz_rotation(e[0], e[1], e[2], b.rotation);
            uint8_t flags = fz_u8(&r);
            if (flags & 1)
                for (int k = 0; k < 9; k++) b.rotation[k] *= 1.5;
            if (flags & 2)
                for (int k = 0; k < 3; k++) b.rotation[3 * k] = -b.rotation[3 * k];
            if (in->n_hosts < FZ_MAX_HOSTS) in->hosts[in->n_hosts++] = b;
        } else if (tag == FZ_HOST_RAW) {
            banyan_box b;
            fz_bytes(&r, &b, sizeof b);
            if (in->n_hosts < FZ_MAX_HOSTS) in->hosts[in->n_hosts++] = b;
        } else if (tag == FZ_SEG_RAW) {
            banyan_segment_input s;
            fz_bytes(&r, &s, sizeof s);
            if (in->n_segs < FZ_MAX_SEGS) in->segs[in->n_segs++] = s;
        } else if (tag == FZ_SEG_COMPACT) {
            banyan_segment_input s;
            for (int k = 0; k < 3; k++) s.S[k] = fz_i16(&r) / 1000.0;
            for (int k = 0; k < 3; k++) s.A[k] = (int8_t)fz_u8(&r);
            s.l = fz_u8(&r) / 32.0;
            s.n = fz_u8(&r) % 70;
            s.s = fz_u8(&r) % 70;
            if (in->n_segs < FZ_MAX_SEGS) in->segs[in->n_segs++] = s;
        } else if (tag == FZ_TRUNK) {
            fz_bytes(&r, in->trunk, sizeof in->trunk);
            in->has_trunk = 1;
        } else if (tag == FZ_CONTROL) {
            uint8_t c = fz_u8(&r);
            if (in->n_control < FZ_MAX_CONTROL) in->control[in->n_control++] = c;
        } else if (tag == FZ_REAL) {
            in->real = 1;
        }
    }
}

/* ----------------------------------------------------------- invariants */

#define FZ_ASSERT(cond, ...)                                                     \
    do {                                                                         \
        if (!(cond)) {                                                           \
            fprintf(stderr, "fuzz invariant failed at %s:%d: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                        \
            fputc('\n', stderr);                                                 \
            abort();                                                             \
        }                                                                        \
    } while (0)

/* A failed call: a real status, the error filled and terminated, no mesh. */
static inline void fz_check_failure(banyan_status s, const banyan_error *e, const void *out) {
    FZ_ASSERT(s > BANYAN_OK && s <= BANYAN_E_INTERNAL, "status %d", (int)s);
    FZ_ASSERT(s != BANYAN_E_INTERNAL, "an internal error: %s", e->message);
    FZ_ASSERT(e->code == (int32_t)s, "err.code %d for status %d", e->code, (int)s);
    FZ_ASSERT(memchr(e->message, 0, sizeof e->message) != NULL, "message not terminated");
    FZ_ASSERT(e->message[0] != 0, "empty message for %s", banyan_status_name(s));
    for (const unsigned char *c = (const unsigned char *)e->message; *c; c++) /* printed escaped */
        FZ_ASSERT(*c >= 0x20 && *c != 0x7F, "control character 0x%02x in: %s", *c, e->message);
    FZ_ASSERT(out == NULL, "out is not NULL after %s", banyan_status_name(s));
}

static inline int fz_finite(const float *a, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (!isfinite(a[i])) return 0;
    return 1;
}

/* A returned mesh: every array as long as its count, indices and parts in
 * range, positions and normals finite, the hash readable. */
static inline void fz_check_mesh(const banyan_mesh *m, uint32_t max_vertices) {
    FZ_ASSERT(m != NULL, "OK without a mesh");
    FZ_ASSERT(m->vertex_count > 0 && m->vertex_count <= max_vertices, "vertex_count %u (max %u)", m->vertex_count,
              max_vertices);
    FZ_ASSERT(m->index_count % 3 == 0, "index_count %u", m->index_count);
    FZ_ASSERT(m->positions && m->normals && m->uvs && m->indices, "missing arrays");
    for (uint32_t i = 0; i < m->index_count; i++)
        FZ_ASSERT(m->indices[i] < m->vertex_count, "index %u = %u of %u", i, m->indices[i], m->vertex_count);
    FZ_ASSERT(fz_finite(m->positions, 3 * (size_t)m->vertex_count), "a position is not finite");
    FZ_ASSERT(fz_finite(m->normals, 3 * (size_t)m->vertex_count), "a normal is not finite");
    FZ_ASSERT(fz_finite(m->uvs, 2 * (size_t)m->vertex_count), "a uv is not finite");
    FZ_ASSERT(m->material_count >= 1 && m->part_count >= 1, "materials %u parts %u", m->material_count,
              m->part_count);
    uint64_t v_end = 0, i_end = 0;
    for (uint32_t p = 0; p < m->part_count; p++) {
        const banyan_part *q = &m->parts[p];
        FZ_ASSERT(q->material < m->material_count, "part %u material %u", p, q->material);
        FZ_ASSERT((uint64_t)q->vertex_offset + q->vertex_count <= m->vertex_count, "part %u vertices", p);
        FZ_ASSERT((uint64_t)q->index_offset + q->index_count <= m->index_count, "part %u indices", p);
        v_end = (uint64_t)q->vertex_offset + q->vertex_count;
        i_end = (uint64_t)q->index_offset + q->index_count;
    }
    FZ_ASSERT(v_end == m->vertex_count && i_end == m->index_count, "parts do not end at the mesh's end");
    for (uint32_t a = 0; a < m->attribute_count; a++)
        FZ_ASSERT(m->attributes[a].data && memchr(m->attributes[a].name, 0, BANYAN_NAME_MAX), "attribute %u", a);
    for (uint32_t k = 0; k < 2 * m->skel_edge_count; k++)
        FZ_ASSERT(m->skel_edges[k] < m->skel_point_count, "skeleton edge end %u = %u of %u", k, m->skel_edges[k],
                  m->skel_point_count);
    if (m->skel_point_count) FZ_ASSERT(fz_finite(m->skel_points, 3 * (size_t)m->skel_point_count), "skeleton point");
    (void)banyan_mesh_hash(m);
}

/* Either a valid mesh or a clean failure; frees the mesh. */
static inline void fz_check(banyan_status s, const banyan_error *e, banyan_mesh *m, uint32_t max_vertices) {
    if (s == BANYAN_OK) {
        FZ_ASSERT(e->code == BANYAN_OK, "OK with err.code %d", e->code);
        fz_check_mesh(m, max_vertices);
        banyan_mesh_free(m);
    } else {
        fz_check_failure(s, e, m);
    }
}

static inline int32_t fz_clamp_i32(int32_t v, int32_t hi) { return v > hi ? hi : v; }

/* ------------------------------------------------------------ run budget */

/* Seconds one generator call may run before its budget stops it with
 * BANYAN_E_LIMIT: well under tools/fuzz.sh's per-input limit (libFuzzer
 * -timeout), which is for hangs the budget cannot see. */
#define FZ_MAX_SECONDS "5"
/* Resident memory a call may add: under libFuzzer's -rss_limit_mb 2048
 * with ASan's own overhead on top. */
#define FZ_MAX_MEMORY_MB "1024"
/* Vertex cap of a real-size input: a real keyaki tree, ivy or root net
 * fits; an avenue of many trees is refused after counting (the time and
 * memory of building it under ASan are past the per-input limit). */
#define FZ_REAL_MAX_VERTICES 2000000

/* Sets the run budget on params of generator g when its table has it
 * (max_seconds, max_memory_mb): by name, so the harness builds with and
 * without those fields. Every harness calls it
 * after reading its input, so the input cannot lift the budget. */
static inline void fz_budget(banyan_generator g, void *params) {
    banyan_error e;
    if (banyan_param_find(g, "max_seconds")) banyan_param_set_text(g, params, "max_seconds", FZ_MAX_SECONDS, &e);
    if (banyan_param_find(g, "max_memory_mb"))
        banyan_param_set_text(g, params, "max_memory_mb", FZ_MAX_MEMORY_MB, &e);
}

/* Did the run budget stop the call? Then a repeat of it (another thread
 * count, stepping against one shot) may end differently. */
static inline int fz_budget_stop(banyan_status s, const banyan_error *e) {
    return s == BANYAN_E_LIMIT && (strstr(e->message, "max_seconds") || strstr(e->message, "max_memory_mb"));
}

#endif
