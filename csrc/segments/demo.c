/* demo.c - a random tree of attached segments, for `banyan segments`
 * without a preset, the tests and the benchmark. The spec gives no tree
 * shape ("Composing a tree" only asks that every segment sit on an earlier
 * axis or the trunk), so this is banyan's own: a vertical trunk, a third of
 * the segments leaving it in the upper half at random yaws, each later
 * segment leaving a random earlier segment's axis, turned 20..60 degrees
 * and 45..70% as long. One PCG32 stream from params->seed. */
#include <math.h>

#include "../base/error.h"
#include "../base/rng.h"
#include "../base/vec.h"
#include "segment_core.h"

static void store(banyan_segment_input *o, v3 S, v3 A, double l, pcg32 *r) {
    o->S[0] = S.x; o->S[1] = S.y; o->S[2] = S.z;
    o->A[0] = A.x; o->A[1] = A.y; o->A[2] = A.z;
    o->l = l;
    o->n = 2 + (int32_t)rng_below(r, 6);
    o->s = (int32_t)rng_below(r, 3);
}

banyan_status banyan_segments_demo(const banyan_segments_params *params, banyan_segment_input *out, uint32_t cap,
                                   uint32_t *count, double trunk[6], banyan_error *err) {
    if (count) *count = 0;
    if (!params || !out || !count || !trunk)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "params, out, count and trunk must not be NULL");
    banyan_status s = banyan_params_check(BANYAN_GEN_SEGMENTS, params, err);
    if (s) return s;
    uint32_t n = (uint32_t)params->demo_segments;
    if (cap < n) return banyan_fail(err, BANYAN_E_RANGE, "cap = %u is less than demo_segments = %u", cap, n);
    double h = params->demo_height;
    pcg32 r;
    pcg32_seed(&r, params->seed, 0x5e95);
    trunk[0] = trunk[1] = trunk[2] = 0;
    trunk[3] = trunk[4] = 0;
    trunk[5] = h;
    uint32_t on_trunk = n < 3 ? 1 : (n + 2) / 3;
    for (uint32_t i = 0; i < n; i++) {
        if (i < on_trunk) {
            double z = h * rng_range(&r, 0.45, 1.0), yaw = rng_range(&r, 0, 2 * BANYAN_PI);
            double el = deg2rad(rng_range(&r, 15, 60));
            v3 A = v3_make(dm_cos(el) * dm_cos(yaw), dm_cos(el) * dm_sin(yaw), dm_sin(el));
            store(&out[i], v3_make(0, 0, z), A, h * rng_range(&r, 0.25, 0.45), &r);
        } else {
            const banyan_segment_input *p = &out[rng_below(&r, i)];
            v3 u = v3_norm(v3_load(p->A));
            v3 S = v3_madd(v3_load(p->S), u, p->l * rng_range(&r, 0.35, 1.0));
            double turn = deg2rad(rng_range(&r, 20, 60)) * (rng_below(&r, 2) ? 1 : -1);
            v3 A = v3_rotate_z(u, turn);
            A.z += rng_range(&r, -0.2, 0.3);
            store(&out[i], S, v3_norm(A), p->l * rng_range(&r, 0.45, 0.7), &r);
        }
    }
    *count = n;
    banyan_error_clear(err);
    return BANYAN_OK;
}
