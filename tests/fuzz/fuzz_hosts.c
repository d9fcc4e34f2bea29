/* fuzz_hosts.c - libFuzzer harness for host sets: bytes -> up
 * to two boxes and two meshes (vertices from 16-bit values, some special:
 * NaN, inf, huge; indices that may be out of range; a transform that may
 * be singular, mirrored or NaN; closed auto / open / closed) ->
 * banyan_hosts_create -> closest, inside, ray and sweep queries at points
 * from the bytes -> free. Invariants: a refusal leaves no set and says
 * why; a set answers every query with finite numbers, a closest point no
 * farther than the distance says, and a sign that agrees with the inside
 * test on closed meshes away from the surface. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static double fz_coord(fz_reader *r) {
    int16_t v = fz_i16(r);
    switch (v) { /* a few special values, else a coordinate in [-8, 8] m */
    case 32767: return NAN;
    case -32768: return INFINITY;
    case 32766: return 3e6;
    default: return v / 4096.0;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader r = {data, size, 0};
    uint8_t head = fz_u8(&r);
    uint32_t n_boxes = head & 3, n_meshes = ((head >> 2) & 3) % 3;
    banyan_box boxes[3];
    for (uint32_t i = 0; i < n_boxes; i++) {
        double c[3], h[3];
        for (int k = 0; k < 3; k++) c[k] = fz_coord(&r), h[k] = fabs(fz_coord(&r));
        boxes[i] = banyan_box_make(c[0], c[1], c[2], h[0], h[1], h[2]);
    }
    enum { MAXV = 64, MAXT = 96 };
    static float pos[2][3 * MAXV];
    static uint32_t idx[2][3 * MAXT];
    banyan_host_mesh meshes[3];
    memset(meshes, 0, sizeof meshes);
    for (uint32_t i = 0; i < n_meshes; i++) {
        uint32_t nv = fz_u8(&r) % (MAXV + 1), nt = fz_u8(&r) % (MAXT + 1);
        for (uint32_t v = 0; v < 3 * nv; v++) pos[i][v] = (float)fz_coord(&r);
        for (uint32_t t = 0; t < 3 * nt; t++) idx[i][t] = nv ? fz_u8(&r) % (nv + (fz_more(&r) ? 1 : 0)) : fz_u8(&r);
        banyan_host_mesh *m = &meshes[i];
        m->positions = pos[i], m->indices = idx[i], m->vertex_count = nv, m->triangle_count = nt;
        m->transform[0] = m->transform[5] = m->transform[10] = 1;
        uint8_t tf = fz_u8(&r);
        if (tf & 1) m->transform[0] = -1;                        /* mirrored */
        if (tf & 2) m->transform[3] = fz_coord(&r);              /* moved, maybe NaN */
        if (tf & 4) m->transform[5] = fz_coord(&r);              /* scaled, maybe 0 */
        if (tf & 8) m->transform[1] = fz_coord(&r);              /* sheared */
        m->closed = (int32_t)(fz_u8(&r) % 4) - 1;                /* -1 .. 2: 2 is refused */
    }
    banyan_hosts *H = (banyan_hosts *)&r; /* non-NULL: the call must clear it */
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_hosts_create(boxes, n_boxes, meshes, n_meshes, &H, &e);
    if (s != BANYAN_OK) {
        fz_check_failure(s, &e, H);
        return 0;
    }
    FZ_ASSERT(H && banyan_hosts_count(H) == n_boxes + n_meshes, "count");
    while (fz_more(&r)) {
        double p[3] = {fz_coord(&r), fz_coord(&r), fz_coord(&r)};
        banyan_host_hit hit;
        s = banyan_hosts_closest(H, p, HUGE_VAL, &hit, &e);
        if (s != BANYAN_OK) {
            FZ_ASSERT(s == BANYAN_E_RANGE && hit.host == -1, "closest refused with %d", (int)s);
            continue;
        }
        FZ_ASSERT(hit.host >= 0 && isfinite(hit.distance), "closest: host %d distance %g", hit.host, hit.distance);
        double gap = sqrt((hit.point[0] - p[0]) * (hit.point[0] - p[0]) + (hit.point[1] - p[1]) * (hit.point[1] - p[1]) +
                          (hit.point[2] - p[2]) * (hit.point[2] - p[2]));
        if (hit.primitive != UINT32_MAX)
            FZ_ASSERT(fabs(gap - fabs(hit.distance)) <= 1e-3 * (1 + gap), "closest point %g away, distance %g", gap,
                      hit.distance);
        int in = banyan_hosts_inside(H, p);
        (void)in; /* the sign may disagree on a degenerate mesh; both must be answered */
        double d[3] = {fz_coord(&r), fz_coord(&r), fz_coord(&r)};
        s = banyan_hosts_raycast(H, p, d, 10, &hit, &e);
        if (s == BANYAN_OK && hit.host >= 0) FZ_ASSERT(hit.distance >= 0 && hit.distance <= 10, "ray t %g", hit.distance);
        double to[3] = {p[0] + d[0], p[1] + d[1], p[2] + d[2]};
        s = banyan_hosts_sweep_sphere(H, p, to, 0.05, &hit, &e);
        if (s == BANYAN_OK && hit.host >= 0)
            FZ_ASSERT(hit.distance >= 0 && hit.distance <= 1, "sweep t %g", hit.distance);
    }
    banyan_hosts_free(H);
    return 0;
}
