/* test_far_origin.c - precision far from the world origin
 * (docs/api.md "Far from the origin"). Every generator grows the same
 * plant at the origin and moved to (999999, -500000, 5000) m: the moved
 * mesh carries a whole-metre origin, and its world positions (origin +
 * position, in double) match the near plant's moved, vertex by vertex, to
 * 1 mm; the near plant keeps origin 0. A scene wider than one mesh can keep
 * is refused naming its input. A far mesh written to glTF carries its
 * origin as the node's translation, and reads back as a host where it was.
 *
 *   test_far_origin OUTDIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "host_meshes.h"
#include "test_hosts.h"

static const double FAR[3] = {999999.0, -500000.0, 5000.0};
/* A trunk standing on the ground moved to x = 999,999
 * m alone; the near axes keep a 0 origin, so nothing but x moves. */
static const double FAR_X[3] = {999999.0, 0.0, 0.0};
static const double *shift = FAR; /* the move same_world compares */
static const char *outdir = ".";

static const char *out_path(const char *name) {
    static char buf[1024];
    snprintf(buf, sizeof buf, "%s/%s", outdir, name);
    return buf;
}

static int origin_zero(const banyan_mesh *m) { return m->origin[0] == 0 && m->origin[1] == 0 && m->origin[2] == 0; }

/* near moved by FAR equals far in the world, to 1 mm, vertex by vertex
 * (and skeleton point by point); near keeps origin 0, far has a whole
 * metre origin within 8192 m of every vertex. Frees both. */
static void same_world(const char *what, banyan_mesh *near, banyan_mesh *far) {
    CHECK(near && far, "%s: a mesh is missing", what);
    if (!near || !far) goto done;
    CHECK(origin_zero(near), "%s: near the origin, origin = (%g, %g, %g) (must stay 0: the same bytes)", what,
          near->origin[0], near->origin[1], near->origin[2]);
    CHECK(!origin_zero(far), "%s: far away, origin is 0", what);
    for (int k = 0; k < 3; k++)
        CHECK(far->origin[k] == floor(far->origin[k]) && fabs(far->origin[k] - shift[k]) < 8192, "%s: origin[%d] = %.17g",
              what, k, far->origin[k]);
    CHECK(near->vertex_count == far->vertex_count && near->index_count == far->index_count &&
              near->skel_point_count == far->skel_point_count,
          "%s: %u / %u vertices, %u / %u indices, %u / %u skeleton points", what, near->vertex_count, far->vertex_count,
          near->index_count, far->index_count, near->skel_point_count, far->skel_point_count);
    if (near->vertex_count != far->vertex_count || near->skel_point_count != far->skel_point_count) goto done;
    double worst = 0, worst_skel = 0, local = 0;
    for (uint32_t i = 0; i < 3 * near->vertex_count; i++) {
        double a = (double)near->positions[i] + shift[i % 3], b = far->origin[i % 3] + (double)far->positions[i];
        worst = fmax(worst, fabs(a - b));
        local = fmax(local, fabs((double)far->positions[i]));
    }
    for (uint32_t i = 0; i < 3 * near->skel_point_count; i++) {
        double a = (double)near->skel_points[i] + shift[i % 3], b = far->origin[i % 3] + (double)far->skel_points[i];
        worst_skel = fmax(worst_skel, fabs(a - b));
    }
    printf("%s: %u vertices, world positions within %.3g m (skeleton %.3g m), local coordinates up to %.1f m\n", what,
           far->vertex_count, worst, worst_skel, local);
    CHECK(worst <= 1e-3 && worst_skel <= 1e-3, "%s: world positions differ by up to %g m (skeleton %g m)", what, worst,
          worst_skel);
    CHECK(banyan_mesh_hash(near) != banyan_mesh_hash(far), "%s: the hash ignores the origin", what);
done:
    banyan_mesh_free(near);
    banyan_mesh_free(far);
}

static void refused(const char *what, banyan_status s, banyan_mesh *m, const banyan_error *e, const char *needle) {
    CHECK(s == BANYAN_E_RANGE && m == NULL && strstr(e->message, needle) && strstr(e->message, "split"),
          "%s: status %d, '%s' (want BANYAN_E_RANGE naming '%s')", what, (int)s, e->message, needle);
    banyan_mesh_free(m);
}

static banyan_box box_at(const double at[3], double x, double y, double z, double hx, double hy, double hz) {
    return banyan_box_make(at[0] + x, at[1] + y, at[2] + z, hx, hy, hz);
}

static void small_roots(banyan_roots_params *p) {
    banyan_roots_params_init(p);
    p->main_roots = 4;
    p->growth_points = 16;
}

static banyan_mesh *roots_boxes(const double at[3], int surface) {
    banyan_roots_params p;
    small_roots(&p);
    p.surface = surface;
    p.ground_z = at[2] - 1.5;
    banyan_box trunk = box_at(at, 0, 0, 0, 0.4, 0.4, 1.5); /* centred: the frame's origin is `at` itself */
    banyan_mesh *m = NULL;
    banyan_error e;
    banyan_status s = test_roots_boxes(&p, &trunk, 1, &m, &e);
    CHECK(s == BANYAN_OK, "roots at (%g, %g, %g): %s", at[0], at[1], at[2], e.message);
    return m;
}

/* A trunk standing on the ground at `at` (not centred on it). */
static banyan_mesh *roots_standing(const double at[3]) {
    banyan_roots_params p;
    small_roots(&p);
    p.ground_z = at[2];
    banyan_box trunk = box_at(at, 0, 0, 1.5, 0.4, 0.4, 1.5);
    banyan_mesh *m = NULL;
    banyan_error e;
    CHECK(test_roots_boxes(&p, &trunk, 1, &m, &e) == BANYAN_OK, "standing roots: %s", e.message);
    return m;
}

static banyan_mesh *roots_mesh(const double at[3]) {
    tm_mesh cyl = {0};
    tm_cylinder(&cyl, 0, 0, 0, 0.5, 3, 24, 4);
    banyan_host_mesh hm = tm_host(&cyl, at[0], at[1], at[2], BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = NULL;
    banyan_error e;
    banyan_mesh *m = NULL;
    CHECK(banyan_hosts_create(NULL, 0, &hm, 1, &H, &e) == BANYAN_OK, "mesh host: %s", e.message);
    if (H) {
        banyan_roots_params p;
        small_roots(&p);
        p.ground_z = at[2];
        p.surface = BANYAN_ROOTS_TUBES;
        CHECK(banyan_roots_generate(&p, H, &m, NULL, NULL, &e) == BANYAN_OK, "roots on a mesh: %s", e.message);
        /* The public queries stay in world coordinates. */
        banyan_host_info info;
        double q[3] = {at[0] - 2, at[1], at[2] + 1};
        banyan_host_hit hit;
        CHECK(banyan_hosts_info(H, 0, &info, NULL) == BANYAN_OK && fabs(info.lo[0] - (at[0] - 0.5)) < 1e-3 &&
                  fabs(info.hi[2] - (at[2] + 3)) < 1e-3,
              "info: lo %g hi %g", info.lo[0], info.hi[2]);
        banyan_status cs = banyan_hosts_closest(H, q, HUGE_VAL, &hit, &e);
        CHECK(cs == BANYAN_OK && hit.host == 0 &&
                  fabs(hit.distance - 1.5) < 1e-2 && fabs(hit.point[0] - (at[0] - 0.5)) < 1e-2 &&
                  fabs(hit.point[2] - (at[2] + 1)) < 1e-3,
              "closest at (%.17g, %g, %g): distance %g (%s)", hit.point[0], hit.point[1], hit.point[2], hit.distance, e.message);
        double down[3] = {0, 0, -1}, top[3] = {at[0], at[1], at[2] + 10};
        CHECK(banyan_hosts_raycast(H, top, down, 100, &hit, NULL) == BANYAN_OK && hit.host == 0 &&
                  fabs(hit.point[2] - (at[2] + 3)) < 1e-3 && fabs(hit.distance - 7) < 1e-3,
              "raycast: host %d at z %.17g", hit.host, hit.point[2]);
        double in[3] = {at[0], at[1], at[2] + 1};
        CHECK(banyan_hosts_inside(H, in) == 1 && banyan_hosts_inside(H, q) == 0, "inside");
    }
    banyan_hosts_free(H);
    tm_free(&cyl);
    return m;
}

static banyan_mesh *ivy_at(const double at[3]) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = 120;
    /* Offsets in eighths: exact beside 1e6 in double as at 0. (0.1 is not:
     * -500000 + 0.1 rounds by 3.5e-11 m, and the ivy's growth, like its
     * growth near 0 moved by 0.1 m, amplifies such a difference into
     * another plant; no frame can undo a rounding of the inputs.) */
    p.start[0] = at[0], p.start[1] = at[1] - 0.125, p.start[2] = at[2] + 0.0625;
    p.ground_z = at[2];
    banyan_box wall = box_at(at, 0, 0.125, 2, 3, 0.125, 2);
    banyan_mesh *m = NULL;
    banyan_error e;
    CHECK(test_ivy_boxes(&p, &wall, 1, &m, &e) == BANYAN_OK, "ivy at (%g, %g, %g): %s", at[0], at[1], at[2],
          e.message);
    return m;
}

static void small_tree(banyan_keyaki_params *p) {
    banyan_keyaki_params_init(p);
    p->levels = 12;
    p->alpha = 1.45;
    p->unit = 0.5;
}

static banyan_mesh *keyaki_at(const double at[3]) {
    banyan_keyaki_params p;
    small_tree(&p);
    for (int k = 0; k < 3; k++) p.position[k] = at[k] + 0.25; /* not whole metres */
    banyan_mesh *m = NULL;
    banyan_error e;
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &e) == BANYAN_OK, "keyaki: %s", e.message);
    return m;
}

static void avenue_params(banyan_avenue_params *p, const double at[3]) {
    banyan_avenue_params_init(p);
    p->tree.levels = 12;
    p->tree.alpha = 1.45;
    p->tree.unit = 0.5;
    p->count = 3;
    p->placement = BANYAN_AVENUE_COUNT;
    for (int k = 0; k < 3; k++) p->start[k] = at[k], p->end[k] = at[k];
    p->end[0] -= 20; /* x = 999,999 is near the end of the range */
}

static banyan_mesh *avenue_at(const double at[3]) {
    banyan_avenue_params p;
    avenue_params(&p, at);
    banyan_mesh *m = NULL;
    banyan_error e;
    p.threads = 2;
    CHECK(banyan_avenue_generate(&p, NULL, 0, &m, NULL, &e) == BANYAN_OK, "avenue: %s", e.message);
    return m;
}

static banyan_mesh *segments_at(const double at[3]) {
    banyan_segments_params p;
    banyan_segments_params_init(&p);
    banyan_segment_input in[64];
    uint32_t n = 0;
    double trunk[6];
    banyan_error e;
    CHECK(banyan_segments_demo(&p, in, 64, &n, trunk, &e) == BANYAN_OK, "segments demo: %s", e.message);
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) in[i].S[k] += at[k];
    for (int k = 0; k < 6; k++) trunk[k] += at[k % 3];
    banyan_mesh *m = NULL;
    CHECK(banyan_segments_generate(&p, in, n, trunk, &m, NULL, NULL, &e) == BANYAN_OK, "segments: %s", e.message);
    return m;
}

static banyan_mesh *tube_at(const double at[3]) {
    double pts[3 * 5], radii[5];
    for (int i = 0; i < 5; i++) {
        pts[3 * i] = at[0] + 0.3 * sin(i), pts[3 * i + 1] = at[1] + 0.2 * i, pts[3 * i + 2] = at[2] + 0.7 * i;
        radii[i] = 0.1 + 0.01 * i;
    }
    banyan_mesh *m = NULL;
    banyan_error e;
    CHECK(banyan_tube_generate(pts, radii, 5, 12, 1, &m, &e) == BANYAN_OK, "tube: %s", e.message);
    return m;
}

/* Inputs wider than one mesh keeps are refused, naming them. */
static void refusals(void) {
    banyan_error e;
    banyan_mesh *m = NULL;
    double pts[6] = {FAR[0] - 20000, FAR[1], FAR[2], FAR[0], FAR[1], FAR[2]}, radii[2] = {0.1, 0.1};
    refused("tube 20 km long", banyan_tube_generate(pts, radii, 2, 8, 0, &m, &e), m, &e, "points");

    banyan_roots_params rp;
    small_roots(&rp);
    rp.ground = 0;
    banyan_box two[2] = {box_at(FAR, 0, 0, 1.5, 0.4, 0.4, 1.5), box_at(FAR, -20000, 0, 1.5, 0.4, 0.4, 1.5)};
    m = NULL;
    refused("roots on hosts 20 km apart", test_roots_boxes(&rp, two, 2, &m, &e), m, &e, "germination");

    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    ip.ground = 0;
    ip.start[0] = FAR[0], ip.start[1] = FAR[1] - 0.5, ip.start[2] = FAR[2] + 1;
    m = NULL;
    refused("ivy on hosts 20 km apart", test_ivy_boxes(&ip, two, 2, &m, &e), m, &e, "start");

    banyan_avenue_params ap;
    avenue_params(&ap, FAR);
    ap.start[0] -= 19990;
    m = NULL;
    ap.threads = 1;
    refused("avenue 20 km long", banyan_avenue_generate(&ap, NULL, 0, &m, NULL, &e), m, &e, "trees");

    banyan_segments_params sp;
    banyan_segments_params_init(&sp);
    banyan_segment_input segs[2] = {{{FAR[0], FAR[1], FAR[2]}, {0, 0, 1}, 1, 2, 1},
                                    {{FAR[0] - 20000, FAR[1], FAR[2]}, {0, 0, 1}, 1, 2, 1}};
    m = NULL;
    refused("segments 20 km apart", banyan_segments_generate(&sp, segs, 2, NULL, &m, NULL, NULL, &e), m, &e,
            "segments");
}

/* The first number after `key` in json, and the two after it. */
static int json_vec3(const char *json, const char *key, double v[3]) {
    const char *p = strstr(json, key);
    if (!p) return 0;
    p = strchr(p, '[');
    return p && sscanf(p, "[%lf,%lf,%lf", &v[0], &v[1], &v[2]) == 3;
}

static char *glb_json(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char h[20];
    char *json = NULL;
    if (fread(h, 1, 20, f) == 20) {
        uint32_t jl = (uint32_t)h[12] | (uint32_t)h[13] << 8 | (uint32_t)h[14] << 16 | (uint32_t)h[15] << 24;
        json = malloc((size_t)jl + 1);
        if (json && fread(json, 1, jl, f) == jl) json[jl] = 0;
        else free(json), json = NULL;
    }
    fclose(f);
    return json;
}

/* A far mesh in glTF: the node's translation is its origin, Y up; read
 * back as a host, it stands where it was, to 1 mm. */
static void gltf_far(void) {
    banyan_mesh *m = tube_at(FAR);
    if (!m) return;
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.textures = 0;
    const banyan_mesh *one[1] = {m};
    banyan_error e;
    const char *path = out_path("test_far_origin_tube.glb");
    CHECK(banyan_gltf_write_ex(path, one, NULL, 1, &o, &e) == BANYAN_OK, "write: %s", e.message);
    char *json = glb_json(path);
    double t[3] = {0, 0, 0};
    CHECK(json && json_vec3(json, "\"translation\"", t) && t[0] == m->origin[0] && t[1] == m->origin[2] &&
              t[2] == -m->origin[1],
          "node translation (%.17g, %.17g, %.17g) for origin (%g, %g, %g)", t[0], t[1], t[2], m->origin[0],
          m->origin[1], m->origin[2]);
    free(json);
    banyan_host_mesh *h = NULL;
    CHECK(banyan_glb_read_host(path, NULL, BANYAN_HOST_CLOSED_AUTO, &h, &e) == BANYAN_OK, "read back: %s", e.message);
    if (h) {
        double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        double mlo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, mhi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        for (uint32_t i = 0; i < h->vertex_count; i++)
            for (int r = 0; r < 3; r++) {
                const float *p = h->positions + 3 * (size_t)i;
                const double *T = h->transform + 4 * r;
                double w = T[0] * p[0] + T[1] * p[1] + T[2] * p[2] + T[3];
                lo[r] = fmin(lo[r], w), hi[r] = fmax(hi[r], w);
            }
        for (uint32_t i = 0; i < 3 * m->vertex_count; i++) {
            double w = m->origin[i % 3] + (double)m->positions[i];
            mlo[i % 3] = fmin(mlo[i % 3], w), mhi[i % 3] = fmax(mhi[i % 3], w);
        }
        double worst = 0;
        for (int r = 0; r < 3; r++) worst = fmax(worst, fmax(fabs(lo[r] - mlo[r]), fabs(hi[r] - mhi[r])));
        printf("glTF: far tube read back within %.3g m\n", worst);
        CHECK(worst <= 1e-3, "read back: bounds differ by %g m", worst);
    }
    banyan_host_mesh_free(h);
    /* Near the origin no translation is written (the bytes stay). */
    banyan_mesh *n = tube_at((const double[3]){0, 0, 0});
    one[0] = n;
    path = out_path("test_far_origin_near.glb");
    CHECK(n && banyan_gltf_write_ex(path, one, NULL, 1, &o, &e) == BANYAN_OK, "write near: %s", e.message);
    json = glb_json(path);
    CHECK(json && !strstr(json, "translation"), "a near mesh got a translation");
    free(json);
    banyan_mesh_free(n);
    banyan_mesh_free(m);
}

int main(int argc, char **argv) {
    if (argc > 1) outdir = argv[1];
    const double zero[3] = {0, 0, 0};
    same_world("roots (box, fused)", roots_boxes(zero, BANYAN_ROOTS_FUSED), roots_boxes(FAR, BANYAN_ROOTS_FUSED));
    same_world("roots (mesh host, tubes)", roots_mesh(zero), roots_mesh(FAR));
    same_world("ivy", ivy_at(zero), ivy_at(FAR));
    same_world("keyaki", keyaki_at(zero), keyaki_at(FAR));
    same_world("avenue", avenue_at(zero), avenue_at(FAR));
    same_world("segments", segments_at(zero), segments_at(FAR));
    same_world("tube", tube_at(zero), tube_at(FAR));
    shift = FAR_X;
    same_world("roots (standing trunk, fused, x only)", roots_standing(zero), roots_standing(FAR_X));
    shift = FAR;
    refusals();
    gltf_far();
    return check_done("test_far_origin");
}
