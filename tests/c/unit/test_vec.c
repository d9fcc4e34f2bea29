/* vec3/mat3 and cubic Bezier: identities on random inputs. */
#include "check.h"
#include "base/bezier.h"
#include "base/rng.h"
#include "base/vec.h"

static v3 rand_v3(pcg32 *r, double s) { return v3_make(rng_range(r, -s, s), rng_range(r, -s, s), rng_range(r, -s, s)); }

int main(void) {
    pcg32 r;
    pcg32_seed(&r, 1, 1);
    int bad_cross = 0, bad_rot = 0, bad_perp = 0, bad_mat = 0, bad_bez = 0;
    for (int i = 0; i < 10000; i++) {
        v3 a = rand_v3(&r, 10), b = rand_v3(&r, 10);
        v3 c = v3_cross(a, b);
        if (fabs(v3_dot(c, a)) > 1e-9 * (1 + v3_len2(a) * v3_len(b)) || fabs(v3_dot(c, b)) > 1e-9 * (1 + v3_len2(b) * v3_len(a)))
            bad_cross++;
        v3 k = v3_norm(rand_v3(&r, 1));
        double ang = rng_range(&r, -7, 7);
        v3 ra = v3_rotate(a, k, ang);
        if (fabs(v3_len(ra) - v3_len(a)) > 1e-9 * (1 + v3_len(a)) || fabs(v3_dot(ra, k) - v3_dot(a, k)) > 1e-9 * (1 + v3_len(a)))
            bad_rot++;
        m3 m = m3_rotation(k, ang);
        if (v3_dist(m3_mul_v3(&m, a), ra) > 1e-9 * (1 + v3_len(a)) || fabs(m3_det(&m) - 1) > 1e-12 ||
            v3_dist(m3_tmul_v3(&m, ra), a) > 1e-9 * (1 + v3_len(a)))
            bad_mat++;
        v3 p = v3_any_perp(k);
        if (fabs(v3_dot(p, k)) > 1e-12 || fabs(v3_len(p) - 1) > 1e-12) bad_perp++;
        /* Bezier: endpoints, t = 0.5 by de Casteljau, tangent by finite differences. */
        v3 p0 = rand_v3(&r, 5), p1 = rand_v3(&r, 5), p2 = rand_v3(&r, 5), p3 = rand_v3(&r, 5);
        v3 m01 = v3_lerp(p0, p1, .5), m12 = v3_lerp(p1, p2, .5), m23 = v3_lerp(p2, p3, .5);
        v3 mid = v3_lerp(v3_lerp(m01, m12, .5), v3_lerp(m12, m23, .5), .5);
        double t = rng_uniform(&r) * 0.98 + 0.01, h = 1e-6;
        v3 fd = v3_scale(v3_sub(bezier3(p0, p1, p2, p3, t + h), bezier3(p0, p1, p2, p3, t - h)), 0.5 / h);
        if (v3_dist(bezier3(p0, p1, p2, p3, 0), p0) > 1e-12 || v3_dist(bezier3(p0, p1, p2, p3, 1), p3) > 1e-12 ||
            v3_dist(bezier3(p0, p1, p2, p3, .5), mid) > 1e-12 || v3_dist(fd, bezier3_tangent(p0, p1, p2, p3, t)) > 1e-5)
            bad_bez++;
    }
    CHECK(bad_cross == 0, "%d cross products not perpendicular", bad_cross);
    CHECK(bad_rot == 0, "%d Rodrigues rotations changed length or axial part", bad_rot);
    CHECK(bad_mat == 0, "%d rotation matrices disagree with Rodrigues", bad_mat);
    CHECK(bad_perp == 0, "%d any_perp results not unit perpendicular", bad_perp);
    CHECK(bad_bez == 0, "%d Bezier identities failed", bad_bez);
    v3 z = v3_rotate_z(v3_make(1, 0, 0), BANYAN_PI / 2);
    CHECK(v3_dist(z, v3_make(0, 1, 0)) < 1e-12, "R_z(90) x = (%g, %g, %g)", z.x, z.y, z.z);
    CHECK(v3_len(v3_norm(v3_make(0, 0, 0))) == 1.0, "norm of zero falls back to a unit vector");
    return check_done("test_vec");
}
