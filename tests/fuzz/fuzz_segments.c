/* fuzz_segments.c - libFuzzer harness for geometry-shader segments:
 * bytes -> segments params, segment inputs (compact or raw, hostile ones
 * included) and a trunk. Without inputs the demo tree is used (at most
 * 256 segments). Every segment call runs: uniforms, check and generate of
 * each segment (its count must be banyan_segment_vertex_count), the batch
 * (it must match the single calls byte for byte), the line set (count,
 * then filled), the attachment check and the tube mesh (max_vertices at
 * most 50,000; with an FZ_REAL record FZ_REAL_MAX_VERTICES, and the run
 * budget). */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static fz_input in; /* large: keep it off the stack */
static float one_xyz[FZ_MAX_SEGS][3 * BANYAN_SEGMENT_MAX_VERTICES];
static float many_xyz[FZ_MAX_SEGS][3 * BANYAN_SEGMENT_MAX_VERTICES];
static uint8_t one_lev[FZ_MAX_SEGS][BANYAN_SEGMENT_MAX_VERTICES], many_lev[FZ_MAX_SEGS][BANYAN_SEGMENT_MAX_VERTICES];
static float lines_xyz[3 * (FZ_MAX_SEGS * BANYAN_SEGMENT_MAX_VERTICES + 2)];
static int8_t lines_lev[FZ_MAX_SEGS * BANYAN_SEGMENT_MAX_VERTICES + 2];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    fz_read(BANYAN_GEN_SEGMENTS, &p, data, size, &in);
    p.max_vertices = fz_clamp_i32(p.max_vertices, in.real ? FZ_REAL_MAX_VERTICES : 50000);
    fz_budget(BANYAN_GEN_SEGMENTS, &p);
    p.demo_segments = fz_clamp_i32(p.demo_segments, FZ_MAX_SEGS);
    banyan_error e;
    memset(&e, 0, sizeof e);
    const double *trunk = in.has_trunk ? in.trunk : NULL;
    if (in.n_segs == 0) {
        double t[6];
        uint32_t n = 0;
        banyan_status s = banyan_segments_demo(&p, in.segs, FZ_MAX_SEGS, &n, t, &e);
        if (s) {
            fz_check_failure(s, &e, NULL);
            return 0;
        }
        FZ_ASSERT(n == (uint32_t)p.demo_segments, "demo made %u of %d", n, p.demo_segments);
        in.n_segs = n;
        if (!trunk) {
            memcpy(in.trunk, t, sizeof t);
            trunk = in.trunk;
        }
    }

    /* One segment at a time, through the reference's own params. */
    banyan_segment_params sp = {p.alpha_deg, p.beta_deg, p.gamma_deg, p.omega_deg, p.m};
    float u[9];
    banyan_status su = banyan_segment_uniforms(&sp, u, &e);
    if (su) fz_check_failure(su, &e, NULL);
    int32_t counts[FZ_MAX_SEGS];
    int all_ok = 1;
    for (uint32_t i = 0; i < in.n_segs; i++) {
        const banyan_segment_input *g = &in.segs[i];
        banyan_status sc = banyan_segment_check(g, &sp, &e);
        int32_t c = -7;
        banyan_status s = banyan_segment_lines(g, &sp, one_xyz[i], one_lev[i], &c, &e);
        FZ_ASSERT(s == sc, "check %s, generate %s", banyan_status_name(sc), banyan_status_name(s));
        if (s) {
            fz_check_failure(s, &e, NULL);
            FZ_ASSERT(c == 0, "count %d on failure", c);
            all_ok = 0;
            continue;
        }
        FZ_ASSERT(c == banyan_segment_vertex_count(g->n, g->s), "segment %u: %d vertices, vertex_count says %d", i, c,
                  banyan_segment_vertex_count(g->n, g->s));
        FZ_ASSERT(c >= 2 && c <= BANYAN_SEGMENT_MAX_VERTICES && c % 2 == 0, "count %d", c);
        FZ_ASSERT(fz_finite(one_xyz[i], 3 * (size_t)c), "segment %u: a vertex is not finite", i);
        counts[i] = c;
    }
    if (in.n_segs && all_ok && !su) {
        int32_t mc[FZ_MAX_SEGS];
        banyan_status s =
            banyan_segment_lines_many(in.segs, in.n_segs, &sp, &many_xyz[0][0], &many_lev[0][0], mc, &e);
        FZ_ASSERT(s == BANYAN_OK, "batch: %s", e.message);
        for (uint32_t i = 0; i < in.n_segs; i++) {
            FZ_ASSERT(mc[i] == counts[i], "batch count %u", i);
            FZ_ASSERT(memcmp(many_xyz[i], one_xyz[i], sizeof(float) * 3 * (size_t)counts[i]) == 0 &&
                          memcmp(many_lev[i], one_lev[i], (size_t)counts[i]) == 0,
                      "batch segment %u differs from the single call", i);
        }
    }

    /* The composed tree. */
    uint32_t nv = 0;
    banyan_status sl = banyan_segments_lines(&p, in.segs, in.n_segs, trunk, NULL, NULL, 0, &nv, &e);
    if (sl) fz_check_failure(sl, &e, NULL);
    else {
        FZ_ASSERT(nv <= sizeof lines_lev, "line set of %u vertices", nv);
        uint32_t nv2 = 0;
        banyan_status s = banyan_segments_lines(&p, in.segs, in.n_segs, trunk, lines_xyz, lines_lev,
                                                (uint32_t)sizeof lines_lev, &nv2, &e);
        FZ_ASSERT(s == BANYAN_OK && nv2 == nv, "lines filled %u, counted %u", nv2, nv);
        if (nv) {
            s = banyan_segments_lines(&p, in.segs, in.n_segs, trunk, lines_xyz, lines_lev, nv - 1, &nv2, &e);
            FZ_ASSERT(s == BANYAN_E_LIMIT && nv2 == nv, "a cap one short: %s", banyan_status_name(s));
        }
    }
    uint32_t unattached[FZ_MAX_SEGS], nu = 0;
    banyan_status sa = banyan_segments_find_unattached(&p, in.segs, in.n_segs, trunk, unattached, &nu, &e);
    FZ_ASSERT(sa == sl, "lines %s, attachment %s", banyan_status_name(sl), banyan_status_name(sa));
    for (uint32_t k = 0; !sa && k < nu; k++)
        FZ_ASSERT(unattached[k] < in.n_segs && (k == 0 || unattached[k] > unattached[k - 1]), "unattached list");
    banyan_mesh *m = (banyan_mesh *)&p;
    banyan_segments_stats st;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_segments_generate(&p, in.segs, in.n_segs, trunk, &m, &st, NULL, &e);
    if (s == BANYAN_OK) FZ_ASSERT(st.unattached == nu && st.segments == in.n_segs, "stats");
    fz_check(s, &e, m, (uint32_t)(p.max_vertices > 0 ? p.max_vertices : 0));
    return 0;
}
