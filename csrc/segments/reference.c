/* reference.c - the CPU reference of one branch segment (spec segments.md,
 * "Steps" 1-4), the source of truth the GLSL shader (csrc/shaders/
 * segment.geom) mirrors line by line.
 *
 * Method: the axis B1 -> B2, then n twigs D_i -> E_i turned +-alpha about
 * the vertical, then the fork hierarchy breadth-first. The breadth-first
 * queue is the list of lines itself: a read cursor walks the lines from the
 * first twig on, and every line whose depth is below its twig's limit
 * (s + i - 1) appends its two children at the end. Children therefore come
 * level by level, within a level in twig order, then in parent order, as
 * the spec asks. Before each fork the 128-vertex budget is checked; the
 * first fork that does not fit ends the segment.
 *
 * Everything is float, every expression is written out with its order of
 * operations fixed (no dot()/cross() helpers whose summation order the
 * shader compiler might choose), so the shader can reproduce it. Branch
 * directions are carried per line (unit by construction), not recomputed
 * from the end points, which keeps sqrt out of the hierarchy. Nothing is
 * allocated: line data lives in fixed arrays of 64 lines. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../base/error.h"
#include "../base/vec.h"
#include "segment_core.h"

#define SEG_MAX_LINES (BANYAN_SEGMENT_MAX_VERTICES / 2)

typedef struct f3 { float x, y, z; } f3;

/* Rotation about the vertical (Z) axis by the angle with cosine c, sine s. */
static inline f3 rot_z(f3 v, float c, float s) {
    f3 r;
    r.x = c * v.x - s * v.y;
    r.y = s * v.x + c * v.y;
    r.z = v.z;
    return r;
}

/* Rodrigues rotation of v about unit k: v c + (k x v) s + k (k.v)(1 - c). */
static inline f3 rot_axis(f3 k, f3 v, float c, float s) {
    float cx = k.y * v.z - k.z * v.y;
    float cy = k.z * v.x - k.x * v.z;
    float cz = k.x * v.y - k.y * v.x;
    float d = (k.x * v.x + k.y * v.y) + k.z * v.z;
    float w = d * (1.0f - c);
    f3 r;
    r.x = (v.x * c + cx * s) + k.x * w;
    r.y = (v.y * c + cy * s) + k.y * w;
    r.z = (v.z * c + cz * s) + k.z * w;
    return r;
}

void banyan_segment_params_init(banyan_segment_params *p) {
    if (!p) return;
    p->alpha_deg = 40.0;
    p->beta_deg = 30.0;
    p->gamma_deg = -30.0;
    p->omega_deg = 10.0;
    p->m = 10.0;
}

size_t banyan_sizeof_segment_params(void) { return sizeof(banyan_segment_params); }
size_t banyan_sizeof_segment_input(void) { return sizeof(banyan_segment_input); }

banyan_status seg_consts_make(const banyan_segment_params *p, double m_scale, seg_consts *k, banyan_error *err) {
    memset(k, 0, sizeof *k);
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    banyan_status s;
    if ((s = banyan_check_range(err, "alpha_deg", p->alpha_deg, -360, 360, "deg")) ||
        (s = banyan_check_range(err, "beta_deg", p->beta_deg, -360, 360, "deg")) ||
        (s = banyan_check_range(err, "gamma_deg", p->gamma_deg, -360, 360, "deg")) ||
        (s = banyan_check_range(err, "omega_deg", p->omega_deg, -360, 360, "deg")))
        return s;
    double m = p->m * m_scale;
    if (m_scale == 1.0) {
        if ((s = banyan_check_range(err, "m", p->m, 1e-6, 1e6, ""))) return s;
    } else if (!(isfinite(m) && m >= 1e-6 && m <= 1e6)) {
        return banyan_fail(err, BANYAN_E_RANGE, "m * unit = %g m must be within [1e-06, 1e+06] m", m);
    }
    k->ca = (float)dm_cos(deg2rad(p->alpha_deg));
    k->sa = (float)dm_sin(deg2rad(p->alpha_deg));
    k->cb = (float)dm_cos(deg2rad(p->beta_deg));
    k->sb = (float)dm_sin(deg2rad(p->beta_deg));
    k->cg = (float)dm_cos(deg2rad(p->gamma_deg));
    k->sg = (float)dm_sin(deg2rad(p->gamma_deg));
    k->co = (float)dm_cos(deg2rad(p->omega_deg));
    k->so = (float)dm_sin(deg2rad(p->omega_deg));
    k->m = (float)m;
    return BANYAN_OK;
}

banyan_status seg_check_input(const banyan_segment_input *in, const char *prefix, banyan_error *err) {
    if (!prefix) prefix = "";
    if (!in) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%sinput is NULL", prefix);
    /* Names are formatted only on failure: this runs once per segment. */
    char name[96];
    const double M = BANYAN_SEGMENT_MAX_COORD;
    for (int c = 0; c < 3; c++) {
        double v = in->S[c];
        if (isfinite(v) && v >= -M && v <= M) continue;
        snprintf(name, sizeof name, "%sS[%d]", prefix, c);
        if (!isfinite(v)) return banyan_fail(err, BANYAN_E_RANGE, "%s = %g must be finite", name, v);
        return banyan_check_range(err, name, v, -M, M, "m");
    }
    for (int c = 0; c < 3; c++)
        if (!isfinite(in->A[c]))
            return banyan_fail(err, BANYAN_E_RANGE, "%sA[%d] = %g must be finite", prefix, c, in->A[c]);
    double len = sqrt(in->A[0] * in->A[0] + in->A[1] * in->A[1] + in->A[2] * in->A[2]);
    if (!(len >= BANYAN_SEGMENT_MIN_DIR && len <= M))
        return banyan_fail(err, BANYAN_E_RANGE,
                           "%sA = (%g, %g, %g) has length %g; the axis direction's length must be within [%g, %g]",
                           prefix, in->A[0], in->A[1], in->A[2], len, BANYAN_SEGMENT_MIN_DIR, M);
    if (!(in->l >= 0 && in->l <= M)) {
        snprintf(name, sizeof name, "%sl", prefix);
        return banyan_check_range(err, name, in->l, 0, M, "m");
    }
    if (in->n < 0 || in->n > BANYAN_SEGMENT_MAX_TWIGS) {
        snprintf(name, sizeof name, "%sn", prefix);
        return banyan_check_int(err, name, in->n, 0, BANYAN_SEGMENT_MAX_TWIGS);
    }
    if (in->s < 0 || in->s > BANYAN_SEGMENT_MAX_DEPTH) {
        snprintf(name, sizeof name, "%ss", prefix);
        return banyan_check_int(err, name, in->s, 0, BANYAN_SEGMENT_MAX_DEPTH);
    }
    return BANYAN_OK;
}

banyan_status banyan_segment_check(const banyan_segment_input *in, const banyan_segment_params *params,
                                   banyan_error *err) {
    seg_consts k;
    banyan_status s = seg_consts_make(params, 1.0, &k, err);
    if (!s) s = seg_check_input(in, "", err);
    if (!s) banyan_error_clear(err);
    return s;
}

static inline void put(float *xyz, int v, f3 p) {
    xyz[3 * v] = p.x;
    xyz[3 * v + 1] = p.y;
    xyz[3 * v + 2] = p.z;
}

int seg_run(const seg_consts *k, const banyan_segment_input *in, float *xyz, uint8_t *level) {
    return seg_run_tree(k, in, xyz, level, NULL);
}

int seg_run_tree(const seg_consts *k, const banyan_segment_input *in, float *xyz, uint8_t *level, uint8_t *parent) {
    /* Per line: start, end, unit direction, depth below its twig (0 for
     * the twig itself) and the depth its twig forks to. */
    f3 p0[SEG_MAX_LINES], p1[SEG_MAX_LINES], dir[SEG_MAX_LINES];
    int depth[SEG_MAX_LINES], limit[SEG_MAX_LINES];

    f3 S = {(float)in->S[0], (float)in->S[1], (float)in->S[2]};
    f3 A = {(float)in->A[0], (float)in->A[1], (float)in->A[2]};
    float l = (float)in->l, m = k->m;
    int n = in->n, s = in->s;

    /* 1. Axis: B1 = S, C1 = A / |A|, B2 = B1 + C1 l. */
    float len = sqrtf((A.x * A.x + A.y * A.y) + A.z * A.z);
    f3 C = {A.x / len, A.y / len, A.z / len};
    f3 B2 = {S.x + C.x * l, S.y + C.y * l, S.z + C.z * l};
    p0[0] = S;
    p1[0] = B2;
    dir[0] = C;
    depth[0] = limit[0] = 0;
    if (parent) parent[0] = 0;

    /* 2. Twigs: D_i on the axis at i / (n + 1), E_i = D_i + m R_z(+-alpha) C1. */
    for (int i = 1; i <= n; i++) {
        float t = (float)i / (float)(n + 1);
        f3 D = {S.x + (B2.x - S.x) * t, S.y + (B2.y - S.y) * t, S.z + (B2.z - S.z) * t};
        f3 F = rot_z(C, k->ca, (i & 1) ? k->sa : -k->sa);
        f3 E = {D.x + F.x * m, D.y + F.y * m, D.z + F.z * m};
        p0[i] = D;
        p1[i] = E;
        dir[i] = F;
        depth[i] = 0;
        limit[i] = s + i - 1;
        if (parent) parent[i] = 0;
    }

    /* 3-4. Hierarchy, breadth-first over the line list, budget first. */
    int nl = n + 1;
    for (int q = 1; q < nl; q++) {
        if (depth[q] >= limit[q]) continue;
        if (2 * nl + 4 > BANYAN_SEGMENT_MAX_VERTICES) break;
        f3 I1 = p0[q], I2 = p1[q], L = dir[q];
        f3 d = {I2.x - I1.x, I2.y - I1.y, I2.z - I1.z};
        f3 G1 = {I1.x + d.x * 0.3f, I1.y + d.y * 0.3f, I1.z + d.z * 0.3f};
        f3 G2 = {I1.x + d.x * 0.7f, I1.y + d.y * 0.7f, I1.z + d.z * 0.7f};
        f3 J1 = rot_axis(L, rot_z(L, k->cb, k->sb), k->cg, k->sg);
        f3 J2 = rot_axis(L, rot_z(L, k->cb, -k->sb), k->co, k->so);
        f3 H1 = {G1.x + J1.x * m, G1.y + J1.y * m, G1.z + J1.z * m};
        f3 H2 = {G2.x + J2.x * m, G2.y + J2.y * m, G2.z + J2.z * m};
        p0[nl] = G1;
        p1[nl] = H1;
        dir[nl] = J1;
        depth[nl] = depth[q] + 1;
        limit[nl] = limit[q];
        if (parent) parent[nl] = (uint8_t)q;
        nl++;
        p0[nl] = G2;
        p1[nl] = H2;
        dir[nl] = J2;
        depth[nl] = depth[q] + 1;
        limit[nl] = limit[q];
        if (parent) parent[nl] = (uint8_t)q;
        nl++;
    }

    for (int j = 0; j < nl; j++) {
        put(xyz, 2 * j, p0[j]);
        put(xyz, 2 * j + 1, p1[j]);
        if (level) level[2 * j] = level[2 * j + 1] = (uint8_t)(j == 0 ? BANYAN_SEGMENT_LEVEL_AXIS : 1 + depth[j]);
    }
    return 2 * nl;
}

banyan_status banyan_segment_lines(const banyan_segment_input *in, const banyan_segment_params *params,
                                      float out_xyz[BANYAN_SEGMENT_MAX_VERTICES * 3],
                                      uint8_t out_level[BANYAN_SEGMENT_MAX_VERTICES], int32_t *out_count,
                                      banyan_error *err) {
    if (out_count) *out_count = 0;
    if (!out_xyz || !out_count) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out_xyz and out_count must not be NULL");
    seg_consts k;
    banyan_status s = seg_consts_make(params, 1.0, &k, err);
    if (!s) s = seg_check_input(in, "", err);
    if (s) return s;
    *out_count = seg_run(&k, in, out_xyz, out_level);
    banyan_error_clear(err);
    return BANYAN_OK;
}

banyan_status banyan_segment_lines_many(const banyan_segment_input *ins, uint32_t count,
                                           const banyan_segment_params *params, float *out_xyz, uint8_t *out_level,
                                           int32_t *out_counts, banyan_error *err) {
    banyan_status s;
    if ((s = banyan_check_int(err, "count", count, 0, 1 << 24))) return s;
    if (count && (!ins || !out_xyz || !out_counts))
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "ins, out_xyz and out_counts must not be NULL");
    seg_consts k;
    if ((s = seg_consts_make(params, 1.0, &k, err))) return s;
    for (uint32_t i = 0; i < count; i++)
        if (seg_check_input(&ins[i], "", NULL)) {
            char prefix[32];
            snprintf(prefix, sizeof prefix, "ins[%u].", i);
            return seg_check_input(&ins[i], prefix, err);
        }
    for (uint32_t i = 0; i < count; i++)
        out_counts[i] = seg_run(&k, &ins[i], out_xyz + (size_t)i * 3 * BANYAN_SEGMENT_MAX_VERTICES,
                                out_level ? out_level + (size_t)i * BANYAN_SEGMENT_MAX_VERTICES : NULL);
    banyan_error_clear(err);
    return BANYAN_OK;
}

int32_t banyan_segment_vertex_count(int32_t n, int32_t s) {
    if (n < 0 || n > BANYAN_SEGMENT_MAX_TWIGS || s < 0 || s > BANYAN_SEGMENT_MAX_DEPTH) return -1;
    int64_t room = (BANYAN_SEGMENT_MAX_VERTICES - 2 - 2 * n) / 4, forks = 0;
    for (int32_t i = 1; i <= n && forks < room; i++) {
        int32_t e = s + i - 1;
        forks += e >= 40 ? room : ((int64_t)1 << e) - 1;
    }
    if (forks > room) forks = room;
    return (int32_t)(2 + 2 * n + 4 * forks);
}

banyan_status banyan_segment_uniforms(const banyan_segment_params *params, float out[9], banyan_error *err) {
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    seg_consts k;
    banyan_status s = seg_consts_make(params, 1.0, &k, err);
    if (s) return s;
    out[0] = k.ca; out[1] = k.sa;
    out[2] = k.cb; out[3] = k.sb;
    out[4] = k.cg; out[5] = k.sg;
    out[6] = k.co; out[7] = k.so;
    out[8] = k.m;
    banyan_error_clear(err);
    return BANYAN_OK;
}
