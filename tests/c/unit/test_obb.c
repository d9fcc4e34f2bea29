/* Oriented-box queries on random rotated boxes: closest points really are
 * closest, surface points lie on the surface with outward normals, the
 * spec's quad test agrees with exact overlap, segment hits are the first
 * contact, and bad boxes are refused. */
#include <string.h>

#include "check.h"
#include "hosts/obb.h"
#include "base/rng.h"

static v3 rand_v3(pcg32 *r, double s) { return v3_make(rng_range(r, -s, s), rng_range(r, -s, s), rng_range(r, -s, s)); }

static banyan_box rand_box(pcg32 *r) {
    v3 k = v3_norm(rand_v3(r, 1));
    m3 m = m3_rotation(k, rng_range(r, -3.2, 3.2));
    banyan_box b;
    for (int i = 0; i < 3; i++) {
        b.center[i] = rng_range(r, -2, 2);
        b.half[i] = rng_range(r, 0.05, 1.5);
    }
    for (int i = 0; i < 9; i++) b.rotation[i] = m.m[i];
    return b;
}

int main(void) {
    pcg32 r;
    pcg32_seed(&r, 2024, 3);
    int bad_closest = 0, bad_surface = 0, bad_normal = 0, bad_sd = 0, bad_quad = 0, bad_seg = 0, quad_hits = 0;
    for (int trial = 0; trial < 300; trial++) {
        banyan_box b = rand_box(&r);
        obb o;
        CHECK(obb_from_box(&b, 0, &o, NULL) == BANYAN_OK, "random rotation box refused");
        for (int q = 0; q < 40; q++) {
            v3 p = rand_v3(&r, 4);
            v3 c = obb_closest_point(&o, p);
            double dc = v3_dist(p, c);
            /* No sampled point of the solid box is closer. */
            for (int s = 0; s < 50; s++) {
                v3 l = v3_make(rng_range(&r, -o.h[0], o.h[0]), rng_range(&r, -o.h[1], o.h[1]), rng_range(&r, -o.h[2], o.h[2]));
                if (v3_dist(p, obb_to_world(&o, l)) < dc - 1e-9) bad_closest++;
            }
            v3 n;
            v3 sp = obb_closest_surface(&o, p, &n);
            v3 ls = obb_to_local(&o, sp);
            double m = fmax(fabs(ls.x) - o.h[0], fmax(fabs(ls.y) - o.h[1], fabs(ls.z) - o.h[2]));
            if (fabs(m) > 1e-9) bad_surface++;
            /* Outward: a small step along n leaves the box; a step back enters or touches it. */
            if (obb_contains(&o, v3_madd(sp, n, 1e-6), 0) || fabs(v3_len(n) - 1) > 1e-9) bad_normal++;
            double sd = obb_signed_distance(&o, p);
            int inside = obb_contains(&o, p, 0);
            if ((sd < 0) != inside && fabs(sd) > 1e-12) bad_sd++;
            if (fabs(fabs(sd) - v3_dist(p, sp)) > 1e-9) bad_sd++;
            /* Quad test: touching a face means overlapping the box; and an
             * outside centre whose nearest point is inside a face (not on an
             * edge) touches by the quad test whenever it overlaps. */
            double rad = rng_range(&r, 0.01, 0.8);
            int quad = obb_sphere_touches_faces(&o, p, rad), exact = obb_sphere_overlaps(&o, p, rad);
            quad_hits += quad;
            if (quad && !exact) bad_quad++;
            if (!inside && exact && !quad) {
                v3 lc = obb_to_local(&o, c);
                int on_edge = (fabs(fabs(lc.x) - o.h[0]) < 1e-12) + (fabs(fabs(lc.y) - o.h[1]) < 1e-12) +
                              (fabs(fabs(lc.z) - o.h[2]) < 1e-12);
                if (on_edge < 2) bad_quad++;
            }
            /* Segment: the entry point is on the boundary and nothing
             * before it is inside; a miss has no inside samples. */
            v3 a = rand_v3(&r, 4), e = rand_v3(&r, 4);
            double t;
            int hit = obb_segment_hit(&o, a, e, &t);
            int first_inside = -1;
            for (int s = 0; s <= 200; s++)
                if (obb_contains(&o, v3_lerp(a, e, s / 200.0), 0)) { first_inside = s; break; }
            if (!hit && first_inside >= 0) bad_seg++;
            if (hit) {
                if (first_inside >= 0 && first_inside / 200.0 < t - 1e-9) bad_seg++;
                if (!obb_contains(&o, v3_lerp(a, e, t), 1e-9)) bad_seg++;
                if (t > 0 && obb_contains(&o, v3_lerp(a, e, t - 1e-6), -1e-9)) bad_seg++;
            }
        }
    }
    CHECK(bad_closest == 0, "%d sampled box points beat obb_closest_point", bad_closest);
    CHECK(bad_surface == 0, "%d closest-surface points off the surface", bad_surface);
    CHECK(bad_normal == 0, "%d surface normals not outward unit", bad_normal);
    CHECK(bad_sd == 0, "%d signed distances inconsistent", bad_sd);
    CHECK(bad_quad == 0, "%d quad tests disagree with exact overlap", bad_quad);
    CHECK(quad_hits > 100, "only %d quad hits: the test exercised too little", quad_hits);
    CHECK(bad_seg == 0, "%d segment hits wrong", bad_seg);

    /* Face winding: (B-A) x (C-A) points away from the centre. */
    banyan_box b = rand_box(&r);
    obb o;
    obb_from_box(&b, 0, &o, NULL);
    for (int f = 0; f < 6; f++) {
        v3 A, B, C;
        obb_face(&o, f, &A, &B, &C);
        v3 N = v3_cross(v3_sub(B, A), v3_sub(C, A));
        CHECK(v3_dot(N, v3_sub(A, o.c)) > 0, "face %d normal points inwards", f);
    }

    /* Refusals. */
    banyan_error err;
    banyan_box bad = banyan_box_make(0, 0, 0, 1, 0, 1);
    CHECK(banyan_box_validate(&bad, 3, &err) == BANYAN_E_BAD_HOST && strstr(err.message, "hosts[3].half[1]"),
          "zero extent: %s", err.message);
    bad = banyan_box_make(0, 0, NAN, 1, 1, 1);
    CHECK(banyan_box_validate(&bad, 0, &err) == BANYAN_E_BAD_HOST, "NaN centre accepted");
    bad = banyan_box_make(0, 0, 0, 1, 1, 1);
    bad.rotation[0] = 2; /* scale in the matrix */
    CHECK(banyan_box_validate(&bad, 0, &err) == BANYAN_E_BAD_HOST && strstr(err.message, "orthonormal"),
          "scaled rotation: %s", err.message);
    bad = banyan_box_make(0, 0, 0, 1, 1, 1);
    bad.rotation[8] = -1; /* mirror */
    CHECK(banyan_box_validate(&bad, 0, &err) == BANYAN_E_BAD_HOST, "mirrored rotation accepted");
    bad = banyan_box_make(0, 0, 0, 1, 1, 1);
    CHECK(banyan_box_validate(&bad, 0, &err) == BANYAN_OK && err.code == 0, "unit box refused: %s", err.message);
    CHECK(banyan_box_validate(NULL, 0, NULL) == BANYAN_E_INVALID_ARG, "NULL box accepted");
    return check_done("test_obb");
}
