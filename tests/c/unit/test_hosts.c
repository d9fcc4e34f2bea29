/* Host sets on real triangles: distances on a UV sphere agree
 * with the sphere they approximate; inside/outside is right for a closed
 * sphere, the same sphere wound inside out, one with a hole, and a mesh of
 * overlapping shells (Suzanne's case); an open quad has no inside; rays
 * and sphere sweeps meet the surface where they should; a box-only set
 * answers as the exact box queries do; a mesh far from the origin keeps
 * its precision; bad meshes are refused naming the host. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "hosts/hosts.h"
#include "base/rng.h"
#include "host_meshes.h"

static double hd(const banyan_hosts *H, v3 p, banyan_host_hit *hit) {
    double q[3] = {p.x, p.y, p.z};
    banyan_host_hit h;
    banyan_hosts_closest(H, q, HUGE_VAL, hit ? hit : &h, NULL);
    return (hit ? hit : &h)->distance;
}

static int inside(const banyan_hosts *H, v3 p) {
    double q[3] = {p.x, p.y, p.z};
    return banyan_hosts_inside(H, q);
}

/* Random points in a cube, kept `band` away from the sphere |p - c| = R. */
static v3 point_off(pcg32 *r, v3 c, double R, double s, double band) {
    for (;;) {
        v3 p = v3_make(c.x + rng_range(r, -s, s), c.y + rng_range(r, -s, s), c.z + rng_range(r, -s, s));
        if (fabs(v3_dist(p, c) - R) > band) return p;
    }
}

static void sphere_checks(void) {
    pcg32 r;
    pcg32_seed(&r, 15, 1);
    const double R = 1.0;
    tm_mesh m = {0};
    tm_uv_sphere(&m, 0, 0, 0, R, 64, 32);
    /* The tessellation lies within R (1 - cos(pi / 32)) ~ 0.005 of the sphere. */
    const double tess = R * (1 - cos(3.14159265358979 / 32)) + 1e-6;
    banyan_host_mesh hm = tm_host(&m, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = NULL;
    banyan_error err;
    CHECK(banyan_hosts_create(NULL, 0, &hm, 1, &H, &err) == BANYAN_OK, "%s", err.message);
    banyan_host_info info;
    CHECK(banyan_hosts_info(H, 0, &info, NULL) == BANYAN_OK && info.kind == 1 && info.closed == 1 &&
              info.boundary_edges == 0 && info.shells == 1 && info.triangle_count == m.nt,
          "sphere info: closed %d boundary %u shells %u tris %u", info.closed, info.boundary_edges, info.shells,
          info.triangle_count);
    int bad_d = 0, bad_in = 0, bad_n = 0, bad_pt = 0;
    for (int i = 0; i < 2000; i++) {
        v3 p = point_off(&r, v3_make(0, 0, 0), R, 2.0, 2 * tess);
        banyan_host_hit hit;
        double d = hd(H, p, &hit), want = v3_len(p) - R;
        if (!(fabs(d - want) <= tess)) bad_d++;
        if (inside(H, p) != (want < 0)) bad_in++;
        v3 n = v3_load(hit.normal), radial = v3_norm(p);
        if (v3_dot(n, radial) < 0.95) bad_n++;
        if (fabs(v3_len(v3_load(hit.point)) - R) > tess) bad_pt++;
    }
    CHECK(bad_d == 0, "%d of 2000 sphere distances off by more than the tessellation", bad_d);
    CHECK(bad_in == 0, "%d of 2000 inside tests wrong on the sphere", bad_in);
    CHECK(bad_n == 0, "%d of 2000 normals not radial", bad_n);
    CHECK(bad_pt == 0, "%d of 2000 closest points off the surface", bad_pt);

    /* Ray from outside along -x hits at x = R (within the tessellation). */
    double o[3] = {5, 0.01, 0.02}, dir[3] = {-1, 0, 0};
    banyan_host_hit hit;
    CHECK(banyan_hosts_raycast(H, o, dir, 100, &hit, NULL) == BANYAN_OK && hit.host == 0 &&
              fabs(hit.distance - (5 - R)) <= tess && hit.normal[0] > 0.9,
          "ray: host %d t %g normal %g", hit.host, hit.distance, hit.normal[0]);
    double o2[3] = {5, 3, 0};
    CHECK(banyan_hosts_raycast(H, o2, dir, 100, &hit, NULL) == BANYAN_OK && hit.host == -1, "ray past the sphere hit %d",
          hit.host);
    /* A sphere of 0.25 m swept from x = 3 to x = -3 touches at x = R + 0.25. */
    double from[3] = {3, 0, 0}, to[3] = {-3, 0, 0};
    CHECK(banyan_hosts_sweep_sphere(H, from, to, 0.25, &hit, NULL) == BANYAN_OK && hit.host == 0 &&
              fabs((3 - 6 * hit.distance) - (R + 0.25)) <= tess + 1e-6,
          "sweep: host %d t %g -> x %g", hit.host, hit.distance, 3 - 6 * hit.distance);
    double from2[3] = {3, 2, 0}, to2[3] = {-3, 2, 0};
    CHECK(banyan_hosts_sweep_sphere(H, from2, to2, 0.25, &hit, NULL) == BANYAN_OK && hit.host == -1,
          "a sweep that passes by hit host %d at %g", hit.host, hit.distance);
    /* max_distance: nothing within 0.1 of a point 1 m out. */
    double far[3] = {2, 0, 0};
    CHECK(banyan_hosts_closest(H, far, 0.1, &hit, NULL) == BANYAN_OK && hit.host == -1, "capped query found %d",
          hit.host);
    banyan_hosts_free(H);

    /* Wound inside out, and through a mirroring transform: the same solid. */
    tm_mesh f = {0};
    tm_uv_sphere(&f, 0, 0, 0, R, 64, 32);
    for (uint32_t t = 0; t < f.nt; t++) {
        uint32_t x = f.idx[3 * t + 1];
        f.idx[3 * t + 1] = f.idx[3 * t + 2];
        f.idx[3 * t + 2] = x;
    }
    banyan_host_mesh hf = tm_host(&f, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_host_mesh hmir = tm_host(&m, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    hmir.transform[0] = -1; /* mirrored in x */
    /* With a hole: one triangle left out; closed is detected (a small hole). */
    tm_mesh h = {0};
    tm_uv_sphere(&h, 0, 0, 0, R, 64, 32);
    memmove(h.idx + 3 * 100, h.idx + 3 * 101, sizeof(uint32_t) * 3 * (h.nt - 101));
    h.nt--;
    banyan_host_mesh hh = tm_host(&h, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    const banyan_host_mesh *variants[3] = {&hf, &hmir, &hh};
    const char *names[3] = {"inside-out", "mirrored", "holed"};
    for (int v = 0; v < 3; v++) {
        banyan_hosts *G = NULL;
        CHECK(banyan_hosts_create(NULL, 0, variants[v], 1, &G, &err) == BANYAN_OK, "%s: %s", names[v], err.message);
        if (!G) continue;
        int wrong = 0, wrong_d = 0;
        for (int i = 0; i < 1000; i++) {
            v3 p = point_off(&r, v3_make(0, 0, 0), R, 2.0, 0.05);
            double want = v3_len(p) - R;
            if (inside(G, p) != (want < 0)) wrong++;
            if (!(fabs(hd(G, p, NULL) - want) <= (v == 2 ? 0.2 : tess))) wrong_d++;
        }
        CHECK(wrong == 0, "%s sphere: %d of 1000 inside tests wrong", names[v], wrong);
        CHECK(wrong_d == 0, "%s sphere: %d of 1000 signed distances wrong", names[v], wrong_d);
        banyan_hosts_free(G);
    }
    tm_free(&m);
    tm_free(&f);
    tm_free(&h);
}

/* Overlapping shells in one mesh: inside is the union. */
static void shells_checks(void) {
    pcg32 r;
    pcg32_seed(&r, 15, 2);
    tm_mesh m = {0};
    tm_two_shell_head(&m, 1.0);
    banyan_host_mesh hm = tm_host(&m, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = NULL;
    banyan_error err;
    CHECK(banyan_hosts_create(NULL, 0, &hm, 1, &H, &err) == BANYAN_OK, "%s", err.message);
    banyan_host_info info;
    banyan_hosts_info(H, 0, &info, NULL);
    CHECK(info.closed == 1 && info.shells == 3, "head: closed %d shells %u", info.closed, info.shells);
    v3 c[3] = {v3_make(0, 0, 1), v3_make(-0.4, -0.8, 1.25), v3_make(0.4, -0.8, 1.25)};
    double rad[3] = {1, 0.35, 0.35};
    int wrong = 0, wrong_sign = 0;
    for (int i = 0; i < 3000; i++) {
        v3 p = v3_make(rng_range(&r, -1.5, 1.5), rng_range(&r, -1.5, 1.5), rng_range(&r, -0.5, 2.5));
        int in = 0, near = 0;
        for (int k = 0; k < 3; k++) {
            double d = v3_dist(p, c[k]) - rad[k];
            in |= d < 0;
            near |= fabs(d) < 0.03;
        }
        if (near) continue;
        if (inside(H, p) != in) wrong++;
        if ((hd(H, p, NULL) < 0) != in) wrong_sign++;
    }
    CHECK(wrong == 0, "overlapping shells: %d inside tests wrong", wrong);
    CHECK(wrong_sign == 0, "overlapping shells: %d distance signs wrong", wrong_sign);
    banyan_hosts_free(H);
    tm_free(&m);
}

/* An open quad: unsigned distance, no inside, both sides. */
static void quad_checks(void) {
    tm_mesh m = {0};
    tm_quad(&m, -1, 1, 0, 0, 2);
    banyan_host_mesh hm = tm_host(&m, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = NULL;
    CHECK(banyan_hosts_create(NULL, 0, &hm, 1, &H, NULL) == BANYAN_OK, "quad refused");
    banyan_host_info info;
    banyan_hosts_info(H, 0, &info, NULL);
    CHECK(info.closed == 0 && info.boundary_edges == 4, "quad: closed %d boundary %u", info.closed,
          info.boundary_edges);
    banyan_host_hit hit;
    double a = hd(H, v3_make(0.2, -0.3, 1), &hit);
    CHECK(fabs(a - 0.3) < 1e-6 && hit.normal[1] < -0.99, "front: %g, normal y %g", a, hit.normal[1]);
    double b = hd(H, v3_make(0.2, 0.4, 1), &hit);
    CHECK(fabs(b - 0.4) < 1e-6 && hit.normal[1] > 0.99, "back: %g, normal y %g", b, hit.normal[1]);
    double c = hd(H, v3_make(2, 0, 1), NULL);
    CHECK(fabs(c - 1.0) < 1e-6, "beside the edge: %g", c);
    CHECK(!inside(H, v3_make(0, 0.001, 1)) && !inside(H, v3_make(0, -0.001, 1)), "an open quad has no inside");
    banyan_hosts_free(H);
    tm_free(&m);
}

/* Boxes in a set answer as the obb queries; boxes and meshes mix. */
static void box_checks(void) {
    pcg32 r;
    pcg32_seed(&r, 15, 3);
    banyan_box boxes[2] = {banyan_box_make(0, 0, 1, 0.5, 0.5, 1), banyan_box_make(3, 0, 0.5, 1, 1, 0.5)};
    tm_mesh m = {0};
    tm_uv_sphere(&m, 0, 0, 0, 0.5, 32, 16);
    banyan_host_mesh hm = tm_host(&m, -3, 0, 0.5, BANYAN_HOST_CLOSED);
    banyan_hosts *H = NULL;
    CHECK(banyan_hosts_create(boxes, 2, &hm, 1, &H, NULL) == BANYAN_OK && banyan_hosts_count(H) == 3, "mixed set");
    obb o[2];
    for (uint32_t i = 0; i < 2; i++) obb_from_box(&boxes[i], i, &o[i], NULL);
    int bad = 0;
    for (int i = 0; i < 1000; i++) {
        v3 p = v3_make(rng_range(&r, -1, 5), rng_range(&r, -2, 2), rng_range(&r, -1, 3));
        banyan_host_hit hit;
        double d = hd(H, p, &hit);
        double want = fmin(obb_signed_distance(&o[0], p), obb_signed_distance(&o[1], p));
        want = fmin(want, v3_dist(p, v3_make(-3, 0, 0.5)) - 0.5);
        if (fabs(d - want) > 0.01) bad++;
    }
    CHECK(bad == 0, "mixed set: %d of 1000 distances wrong", bad);
    banyan_hosts_free(H);
    tm_free(&m);
}

/* Far from the origin (x = 999,990 m, points within 2 m of it) the mesh
 * keeps its precision. */
static void far_checks(void) {
    tm_mesh m = {0};
    tm_uv_sphere(&m, 0, 0, 0, 1.0, 64, 32);
    banyan_host_mesh near = tm_host(&m, 0, 0, 0, BANYAN_HOST_CLOSED);
    banyan_host_mesh far = tm_host(&m, 999990.0, 0, 0, BANYAN_HOST_CLOSED);
    banyan_hosts *A = NULL, *B = NULL;
    banyan_hosts_create(NULL, 0, &near, 1, &A, NULL);
    banyan_hosts_create(NULL, 0, &far, 1, &B, NULL);
    pcg32 r;
    pcg32_seed(&r, 15, 4);
    double worst = 0;
    for (int i = 0; i < 500 && A && B; i++) {
        v3 p = point_off(&r, v3_make(0, 0, 0), 1.0, 2.0, 0.01);
        double a = hd(A, p, NULL), b = hd(B, v3_add(p, v3_make(999990.0, 0, 0)), NULL);
        worst = fmax(worst, fabs(a - b));
    }
    CHECK(A && B && worst < 1e-4, "at x = 999,990 m distances differ by up to %g m from the origin's", worst);
    banyan_hosts_free(A);
    banyan_hosts_free(B);
    tm_free(&m);
}

static void expect_refusal(const banyan_host_mesh *hm, banyan_status code, const char *needle, const char *what) {
    banyan_hosts *H = (banyan_hosts *)(uintptr_t)1;
    banyan_error err;
    memset(&err, 0, sizeof err);
    banyan_box box = banyan_box_make(0, 0, 1, 1, 1, 1);
    banyan_status s = banyan_hosts_create(&box, 1, hm, 1, &H, &err);
    CHECK(s == code && H == NULL && strstr(err.message, needle) && strstr(err.message, "hosts[1]"),
          "%s: status %d, message '%s'", what, (int)s, err.message);
}

static void bad_input_checks(void) {
    tm_mesh m = {0};
    tm_uv_sphere(&m, 0, 0, 0, 1, 8, 4);
    banyan_host_mesh hm = tm_host(&m, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_host_mesh e = hm;
    e.triangle_count = 0;
    expect_refusal(&e, BANYAN_E_BAD_HOST, "empty", "empty mesh");
    float saved = m.pos[4];
    m.pos[4] = NAN;
    expect_refusal(&hm, BANYAN_E_BAD_HOST, "not finite", "NaN vertex");
    m.pos[4] = INFINITY;
    expect_refusal(&hm, BANYAN_E_BAD_HOST, "not finite", "inf vertex");
    m.pos[4] = saved;
    uint32_t si = m.idx[7];
    m.idx[7] = m.nv + 5;
    expect_refusal(&hm, BANYAN_E_BAD_HOST, "out of range", "index out of range");
    m.idx[7] = si;
    banyan_host_mesh s = hm;
    s.transform[10] = 0; /* flattened */
    expect_refusal(&s, BANYAN_E_BAD_HOST, "singular", "singular transform");
    s = hm;
    s.transform[0] = s.transform[5] = s.transform[10] = 1e-9; /* a 2 nm sphere */
    expect_refusal(&s, BANYAN_E_BAD_HOST, "1e-6", "a speck");
    s = hm;
    s.transform[3] = NAN;
    expect_refusal(&s, BANYAN_E_BAD_HOST, "finite", "NaN transform");
    s = hm;
    s.transform[3] = 2e6;
    expect_refusal(&s, BANYAN_E_BAD_HOST, "1e6", "beyond the world");
    /* Every triangle of zero area. */
    float flat[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    uint32_t ft[3] = {0, 1, 2};
    banyan_host_mesh z = hm;
    z.positions = flat, z.indices = ft, z.vertex_count = 3, z.triangle_count = 1;
    expect_refusal(&z, BANYAN_E_BAD_HOST, "zero area", "zero-area mesh");
    /* 10^8 triangles: refused from the counts, before reading anything. */
    banyan_host_mesh big = hm;
    big.triangle_count = 100000000u;
    expect_refusal(&big, BANYAN_E_LIMIT, "triangles", "1e8 triangles");
    /* Some zero-area triangles among good ones are dropped, not refused. */
    tm_mesh d = {0};
    tm_uv_sphere(&d, 0, 0, 0, 1, 16, 8);
    tm_tri(&d, 0, 0, 1);
    banyan_host_mesh hd_ = tm_host(&d, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = NULL;
    banyan_host_info info;
    CHECK(banyan_hosts_create(NULL, 0, &hd_, 1, &H, NULL) == BANYAN_OK &&
              banyan_hosts_info(H, 0, &info, NULL) == BANYAN_OK && info.dropped_triangles == 1 && info.closed == 1,
          "a degenerate triangle among good ones: dropped %u", H ? info.dropped_triangles : 0);
    banyan_hosts_free(H);
    banyan_hosts_free(NULL);
    /* Queries refuse bad points. */
    banyan_hosts_create(NULL, 0, &hm, 1, &H, NULL);
    double nanp[3] = {NAN, 0, 0};
    banyan_host_hit hit;
    CHECK(banyan_hosts_closest(H, nanp, 1, &hit, NULL) == BANYAN_E_RANGE && hit.host == -1, "NaN query point");
    double p[3] = {0, 0, 3}, z0[3] = {0, 0, 0};
    CHECK(banyan_hosts_raycast(H, p, z0, 1, &hit, NULL) == BANYAN_E_RANGE, "zero ray direction");
    CHECK(banyan_hosts_sweep_sphere(H, p, z0, -1, &hit, NULL) == BANYAN_E_RANGE, "negative sweep radius");
    banyan_hosts_free(H);
    CHECK(banyan_hosts_create(NULL, 0, NULL, 0, &H, NULL) == BANYAN_E_NO_HOSTS && H == NULL, "an empty set");
    tm_free(&m);
    tm_free(&d);
}

int main(void) {
    sphere_checks();
    shells_checks();
    quad_checks();
    box_checks();
    far_checks();
    bad_input_checks();
    return check_done("test_hosts");
}
