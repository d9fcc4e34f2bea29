/* banyan_tube_generate: the public face of the shared sweeper (mesh/tube.h),
 * used by the CLI's `tube` demo and the tests. A generator of its own
 * (one folder per generator, above csrc/mesh), not part of the sweeper. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/error.h"
#include "base/frame.h"
#include "mesh/tube.h"
#include "mesh/wind.h"

banyan_status banyan_tube_generate(const double *points, const double *radii, uint32_t point_count, int32_t sides,
                                   int32_t caps, banyan_mesh **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    if (!points || !radii) return banyan_fail(err, BANYAN_E_INVALID_ARG, "points and radii must not be NULL");
    banyan_status s;
    if ((s = banyan_check_int(err, "point_count", point_count, 2, 1000000))) return s;
    if ((s = banyan_check_int(err, "sides", sides, 3, 256))) return s;
    if ((s = banyan_check_int(err, "caps", caps, 0, 1))) return s;
    uint32_t nv, ni;
    tube_counts(point_count, sides, caps, caps, &nv, &ni);
    if (nv > BANYAN_TUBE_MAX_VERTICES)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "point_count = %u with sides = %d makes %u vertices, more than %u; lower point_count or "
                           "sides", point_count, sides, nv, (unsigned)BANYAN_TUBE_MAX_VERTICES);
    /* The points are read in place: v3 is three doubles, as the array is. */
    _Static_assert(sizeof(v3) == 3 * sizeof(double), "v3 must be three packed doubles");
    const v3 *pts = (const v3 *)(const void *)points;
    for (uint32_t i = 0; i < point_count; i++) {
        if (!v3_finite(pts[i]) || fabs(pts[i].x) > 1e6 || fabs(pts[i].y) > 1e6 || fabs(pts[i].z) > 1e6)
            s = banyan_fail(err, BANYAN_E_RANGE, "points[%u] = (%g, %g, %g) must be finite, within [-1e6, 1e6] m", i,
                            pts[i].x, pts[i].y, pts[i].z);
        else if (!(radii[i] > 0))
            s = banyan_fail(err, BANYAN_E_RANGE, "radii[%u] = %g must be > 0 m", i, radii[i]);
        else if (!(radii[i] >= 1e-9 && radii[i] <= 1e6)) { /* the name is formatted only on failure */
            char name[48];
            snprintf(name, sizeof name, "radii[%u]", i);
            s = banyan_check_range(err, name, radii[i], 1e-9, 1e6, "m");
        }
        if (!s && i && v3_dist(pts[i], pts[i - 1]) < 1e-9)
            s = banyan_fail(err, BANYAN_E_RANGE, "points[%u] repeats points[%u]; consecutive points must differ", i, i - 1);
        if (s) return s;
    }
    /* The frame (frame.h): points moved near 0 when they lie far from it. */
    v3 lo, hi;
    frame_empty(&lo, &hi);
    for (uint32_t i = 0; i < point_count; i++) frame_add(&lo, &hi, pts[i]);
    v3 O = frame_pick(lo, hi);
    if ((s = frame_check(lo, hi, O, "points", err))) return s;
    v3 *local = NULL;
    if (O.x != 0 || O.y != 0 || O.z != 0) {
        if (!(local = malloc(sizeof *local * point_count)))
            return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u points", point_count);
        for (uint32_t i = 0; i < point_count; i++) local[i] = v3_sub(pts[i], O);
        pts = local;
    }
    /* Wind (no params: always on): one branch swaying about its first
     * point, stiffness by radius, birth by arc length. */
    double *ring_val = malloc(sizeof(double) * 2 * point_count);
    if (!ring_val) {
        free(local);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u points", point_count);
    }
    double *ring_birth = ring_val + point_count, r_ref = 0, arc = 0;
    for (uint32_t i = 0; i < point_count; i++) r_ref = radii[i] > r_ref ? radii[i] : r_ref;
    for (uint32_t i = 0; i < point_count; i++) {
        ring_val[i] = sqrt(radii[i] / r_ref);
        if (i) arc += v3_dist(pts[i], pts[i - 1]);
        ring_birth[i] = arc;
    }
    for (uint32_t i = 0; i < point_count; i++) ring_birth[i] = arc > 0 ? ring_birth[i] / arc : 0;
    mesh_builder mb;
    mb_init(&mb, BANYAN_TUBE_MAX_VERTICES, 0);
    wind_slots ws;
    wind_declare(&mb, 1, &ws);
    wind_set(&mb, &ws, pts[0], 0, 1, wind_phase_of(0, 0), 0);
    tube_opts o = {sides, caps, caps, {0, 0, 0}, 0.0, NULL, 0, 1};
    uint32_t first = mb.nv;
    tube_sweep(&mb, pts, radii, point_count, &o);
    wind_tube_rings(&mb, first, point_count, sides, caps, caps, ws.stiffness, ring_val);
    wind_tube_rings(&mb, first, point_count, sides, caps, caps, ws.birth, ring_birth);
    free(ring_val);
    mb_skel_reserve(&mb, point_count, point_count - 1);
    for (uint32_t i = 0; i < point_count; i++) {
        uint32_t k = mb_skel_point(&mb, pts[i], radii[i], 0);
        if (i) mb_skel_edge(&mb, k - 1, k);
    }
    free(local);
    s = mb_finish(&mb, out, err);
    if (!s) frame_set(*out, O);
    return s;
}
