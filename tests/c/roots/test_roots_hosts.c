/* Roots on host sets with meshes (spec README "Hosts", roots.md
 * 1): invariants over seeds on meshes built in code
 * (tests/c/common/host_meshes.h), not snapshots.
 *   - A UV sphere resting on the ground, a 32-sided closed cylinder column
 *     (0.4 m radius, 3 m tall, standing on the ground), an open quad wall
 *     and Suzanne's stand-in (one closed mesh of three shells that cut each
 *     other), alone and mixed with a box.
 *   - No skeleton point closer than r - tol to any host or the ground; no
 *     tube vertex inside a closed host (a float's worth of tolerance); at
 *     most 2 % of the skeleton edges through a mesh, none of main roots
 *     round the open wall alone (a thin box does as much, see below); the
 *     skeleton is one connected graph; every first branch root reaches
 *     its end.
 *   - Cylinder: of the tube vertices more than 1 m above the ground, at
 *     least 90 % lie within 3 r of its surface (the roots wrap the curve);
 *     most main roots reach the ground.
 *   - germination_auto on a mesh: G on top of host 0, lifted by r.
 *   - Same seed, same bytes; another seed, another mesh.
 *   - Two host sets made apart from the same boxes give the same bytes and
 *     stats, for every roots preset and the default.
 *   - Bad input refused before any growth, *out NULL: no host set, bad
 *     params, G inside a mesh host, G far from it, bad meshes.
 * Writes roots_host_*.glb for the validator. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_checks.h"
#include "host_meshes.h"
#include "roots/roots_internal.h"
#include "test_files.h"

#define TOL 1e-3 /* times r: the skeleton is stored in float */

/* ------------------------------------------------------------ checks */

/* Signed distance to the nearest host (exact, uncapped) and the ground. */
static double host_clearance(const banyan_hosts *H, const banyan_roots_params *p, v3 q, int with_ground) {
    double c = with_ground && p->ground ? q.z - p->ground_z : 1e300;
    for (uint32_t i = 0; i < H->n_boxes; i++) {
        double d = obb_signed_distance(&H->boxes[i], q);
        if (d < c) c = d;
    }
    for (uint32_t j = 0; j < H->n_meshes; j++) {
        double d = hmesh_distance(&H->meshes[j], q, HUGE_VAL);
        if (d < c) c = d;
    }
    return c;
}

typedef struct report {
    int nets;
    long skel_close, skel_inside, verts_inside, edges, edges_through, main_edges_through, high, high_near;
    int disconnected, first_unreached, on_ground, mains;
    double worst_skel, deepest_vert;
} report;

/* Grows on H with p and checks the invariants into rep. `cyl` (mesh
 * index, or -1) is the column whose 3 r hugging figure is counted. */
static banyan_mesh *grow_check(const banyan_hosts *H, const banyan_roots_params *p, int cyl, report *rep) {
    banyan_mesh *m = NULL;
    banyan_roots_stats st;
    banyan_error err;
    banyan_status s = banyan_roots_generate(p, H, &m, &st, NULL, &err);
    CHECK(s == BANYAN_OK && m, "seed %llu: %s", (unsigned long long)p->seed, err.message);
    if (s) return NULL;
    double r = p->radius * p->unit;
    rep->nets++;
    /* Skeleton points: clearance >= r (less float storage); below the
     * ground only the underground ends of roots entering the soil
     * (soil_entry), which keep clear of the hosts only. */
    for (uint32_t i = 0; i < m->skel_point_count; i++) {
        v3 q = v3_make(m->skel_points[3 * i], m->skel_points[3 * i + 1], m->skel_points[3 * i + 2]);
        int under = p->soil_entry && p->ground && q.z < p->ground_z + r * (1.0 - TOL);
        double c = host_clearance(H, p, q, !under);
        if (c / r < rep->worst_skel) rep->worst_skel = c / r;
        if (c < r * (1.0 - TOL)) rep->skel_close++;
        double qd[3] = {q.x, q.y, q.z};
        if (banyan_hosts_inside(H, qd)) rep->skel_inside++;
    }
    /* Tube vertices: none inside a closed host (float storage and the
     * pressing of stretched rings onto the surface: 0.01 r or 0.1 mm). */
    double vtol = 0.01 * r > 1e-4 ? 0.01 * r : 1e-4;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        v3 q = v3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
        double c = host_clearance(H, p, q, 0);
        if (c < -vtol) {
            rep->verts_inside++;
            if (-c > rep->deepest_vert) rep->deepest_vert = -c;
        }
        if (cyl >= 0 && q.z - p->ground_z > 1.0) {
            rep->high++;
            if (hmesh_distance(&H->meshes[cyl], q, HUGE_VAL) <= 3.0 * r) rep->high_near++;
        }
    }
    /* Edges through a mesh (open walls have no inside, so this is their
     * test). Where main roots pass both sides of a thin wall, a branch
     * chord or a main-root correction can join points on its two sides,
     * and segment repair gives up after 16 splits: a thin box does the
     * same (0.4 to 1.1 % of the segments round a 1 cm box wall, seeds
     * 401-404). At most 2 %; main roots alone round an open wall: none. */
    for (uint32_t e = 0; e < m->skel_edge_count; e++) {
        uint32_t ia = m->skel_edges[2 * e], ib = m->skel_edges[2 * e + 1];
        const float *a = m->skel_points + 3 * ia, *b = m->skel_points + 3 * ib;
        rep->edges++;
        for (uint32_t j = 0; j < H->n_meshes; j++) {
            double t;
            v3 n;
            if (hmesh_segment_hit(&H->meshes[j], v3_make(a[0], a[1], a[2]), v3_make(b[0], b[1], b[2]), &t, &n)) {
                if (m->skel_tag[ia] == ROOT_MAIN && m->skel_tag[ib] == ROOT_MAIN) rep->main_edges_through++;
                rep->edges_through++;
                break;
            }
        }
    }
    if (mc_skeleton_pieces(m) != 1) rep->disconnected++; /* one connected graph */
    if (st.first_reached != st.first_roots) rep->first_unreached++;
    rep->on_ground += (int)st.mains_on_ground;
    rep->mains += p->main_roots;
    if (st.min_clearance < r * (1.0 - TOL)) rep->skel_close++;
    return m;
}

static void expect_clean(const char *name, const report *rep) {
    printf("  %-16s %d nets: worst skeleton clearance %.4f r, %ld vertices inside (deepest %.2g m), %d/%d mains on "
           "the ground, %ld/%ld edges through a mesh (%ld of main roots)\n",
           name, rep->nets, rep->worst_skel, rep->verts_inside, rep->deepest_vert, rep->on_ground, rep->mains,
           rep->edges_through, rep->edges, rep->main_edges_through);
    CHECK(rep->skel_close == 0, "%s: %ld skeleton points closer than r (worst %.4f r)", name, rep->skel_close,
          rep->worst_skel);
    CHECK(rep->skel_inside == 0, "%s: %ld skeleton points inside a host", name, rep->skel_inside);
    CHECK(rep->verts_inside == 0, "%s: %ld tube vertices inside a closed host (deepest %g m)", name,
          rep->verts_inside, rep->deepest_vert);
    CHECK(rep->edges_through * 50 <= rep->edges, "%s: %ld of %ld skeleton edges pass through a mesh host", name,
          rep->edges_through, rep->edges);
    CHECK(rep->disconnected == 0, "%s: %d nets not connected", name, rep->disconnected);
    CHECK(rep->first_unreached == 0, "%s: %d nets with first branch roots short of their end", name,
          rep->first_unreached);
}

static void write_glb(const char *dir, const char *name, const banyan_mesh *m) {
    if (!dir || !m) return;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.glb", dir, name);
    banyan_error err;
    CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write %s: %s", path,
          err.message);
}

static banyan_hosts *make(const banyan_box *boxes, uint32_t nb, const banyan_host_mesh *meshes, uint32_t nm) {
    banyan_hosts *H = NULL;
    banyan_error err;
    banyan_status s = banyan_hosts_create(boxes, nb, meshes, nm, &H, &err);
    CHECK(s == BANYAN_OK && H, "host set: %s", err.message);
    return H;
}

/* ------------------------------------------------------------ tests */

#define SEEDS 4

static void test_cylinder(const char *dir) {
    tm_mesh t = {0};
    tm_cylinder(&t, 0, 0, 0, 0.4, 3.0, 32, 1);
    banyan_host_mesh hm = tm_host(&t, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = make(NULL, 0, &hm, 1);
    if (!H) {
        tm_free(&t);
        return;
    }
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    /* How closely the roots wrap, counted on the tubes' vertices (rings
     * evenly along each root); the fused surface spreads its vertices by
     * area, fillets included (test_roots_fused checks it on hosts). */
    p.surface = BANYAN_ROOTS_TUBES;
    double r = p.radius * p.unit;
    report rep = {0};
    rep.worst_skel = 1e300;
    for (int s = 1; s <= SEEDS; s++) {
        p.seed = (uint64_t)s;
        banyan_mesh *m = grow_check(H, &p, 0, &rep);
        if (s == 1) write_glb(dir, "roots_host_cylinder", m);
        banyan_mesh_free(m);
    }
    expect_clean("cylinder", &rep);
    double frac = rep.high ? (double)rep.high_near / (double)rep.high : 0;
    printf("  cylinder: %.1f %% of %ld vertices above 1 m within 3 r of the surface\n", 100 * frac, rep.high);
    CHECK(rep.high > 1000 && frac >= 0.90, "cylinder: %.1f %% of %ld vertices above 1 m within 3 r (want >= 90 %%)",
          100 * frac, rep.high);
    CHECK(rep.on_ground * 4 >= rep.mains * 3, "cylinder: only %d of %d main roots reached the ground",
          rep.on_ground, rep.mains);

    /* G auto: on the top cap's centre, lifted by r. */
    roots_net net;
    banyan_error err;
    p.seed = 1;
    if (roots_net_build_hosts(&p, H, &net, &err) == BANYAN_OK) {
        CHECK(fabs(net.G.x) < 1e-6 && fabs(net.G.y) < 1e-6 && fabs(net.G.z - (3.0 + r)) < 1e-5,
              "cylinder: G = (%g, %g, %g), want (0, 0, %g)", net.G.x, net.G.y, net.G.z, 3.0 + r);
        roots_net_free(&net);
    } else {
        CHECK(0, "cylinder net: %s", err.message);
    }

    /* Same seed, same bytes; another seed, another mesh. */
    banyan_mesh *a = NULL, *b = NULL, *c = NULL;
    p.seed = 42;
    banyan_roots_generate(&p, H, &a, NULL, NULL, &err);
    banyan_roots_generate(&p, H, &b, NULL, NULL, &err);
    p.seed = 43;
    banyan_roots_generate(&p, H, &c, NULL, NULL, &err);
    CHECK(a && b && c && banyan_mesh_hash(a) == banyan_mesh_hash(b), "cylinder: same seed, different meshes");
    CHECK(a && c && banyan_mesh_hash(a) != banyan_mesh_hash(c), "cylinder: seeds 42 and 43 gave the same mesh");
    banyan_mesh_free(a);
    banyan_mesh_free(b);
    banyan_mesh_free(c);

    /* Paper mode (stop on contact) keeps the invariants too. */
    report pr = {0};
    pr.worst_skel = 1e300;
    p.hugging = 0;
    for (int s = 1; s <= 2; s++) {
        p.seed = (uint64_t)s;
        banyan_mesh_free(grow_check(H, &p, -1, &pr));
    }
    expect_clean("cylinder/paper", &pr);
    banyan_hosts_free(H);
    tm_free(&t);
}

static void test_sphere(const char *dir) {
    tm_mesh t = {0};
    tm_uv_sphere(&t, 0, 0, 1.0, 1.0, 32, 16);
    banyan_host_mesh hm = tm_host(&t, 0.5, -0.25, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = make(NULL, 0, &hm, 1);
    if (!H) {
        tm_free(&t);
        return;
    }
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    double r = p.radius * p.unit;
    report rep = {0};
    rep.worst_skel = 1e300;
    for (int s = 1; s <= SEEDS; s++) {
        p.seed = (uint64_t)(100 + s);
        banyan_mesh *m = grow_check(H, &p, -1, &rep);
        if (s == 1) write_glb(dir, "roots_host_sphere", m);
        banyan_mesh_free(m);
    }
    expect_clean("sphere", &rep);
    /* G auto: the sphere's pole (a vertex of the UV sphere), lifted by r. */
    roots_net net;
    banyan_error err;
    if (roots_net_build_hosts(&p, H, &net, &err) == BANYAN_OK) {
        CHECK(fabs(net.G.x - 0.5) < 1e-6 && fabs(net.G.y + 0.25) < 1e-6 && fabs(net.G.z - (2.0 + r)) < 1e-5,
              "sphere: G = (%g, %g, %g), want (0.5, -0.25, %g)", net.G.x, net.G.y, net.G.z, 2.0 + r);
        roots_net_free(&net);
    } else {
        CHECK(0, "sphere net: %s", err.message);
    }
    banyan_hosts_free(H);
    tm_free(&t);
}

/* The two-shell mesh, and beside it an open wall the roots must not pass
 * through, with a box standing in the mix (host numbers: box 0, meshes
 * 1, 2). */
static void test_shells_wall_box(const char *dir) {
    tm_mesh sh = {0}, wall = {0};
    tm_two_shell_head(&sh, 0.7);
    tm_quad(&wall, -1.5, 1.5, 0, 0, 2.0);
    banyan_host_mesh hm[2] = {tm_host(&sh, 0, 0, 0, BANYAN_HOST_CLOSED), tm_host(&wall, 0, -1.0, 0, BANYAN_HOST_OPEN)};
    banyan_box box = banyan_box_make(1.2, 0.6, 0.3, 0.3, 0.3, 0.3);
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    report rep = {0};
    rep.worst_skel = 1e300;
    /* The shells alone, G on top of them. */
    banyan_hosts *H = make(NULL, 0, hm, 1);
    for (int s = 1; H && s <= SEEDS; s++) {
        p.seed = (uint64_t)(200 + s);
        banyan_mesh *m = grow_check(H, &p, -1, &rep);
        if (s == 1) write_glb(dir, "roots_host_shells", m);
        banyan_mesh_free(m);
    }
    banyan_hosts_free(H);
    expect_clean("two shells", &rep);

    /* Box first (G on it), then the shells and the wall. */
    memset(&rep, 0, sizeof rep);
    rep.worst_skel = 1e300;
    H = make(&box, 1, hm, 2);
    for (int s = 1; H && s <= SEEDS; s++) {
        p.seed = (uint64_t)(300 + s);
        banyan_mesh *m = grow_check(H, &p, -1, &rep);
        if (s == 1) write_glb(dir, "roots_host_mixed", m);
        banyan_mesh_free(m);
    }
    banyan_hosts_free(H);
    expect_clean("box+shells+wall", &rep);

    /* The wall alone with G in front of it: roots run down its face and
     * never through it. */
    memset(&rep, 0, sizeof rep);
    rep.worst_skel = 1e300;
    banyan_host_mesh w0 = tm_host(&wall, 0, 0, 0, BANYAN_HOST_OPEN);
    H = make(NULL, 0, &w0, 1);
    p.germination_auto = 0;
    p.germination[0] = 0.2;
    p.germination[1] = 0.15;
    p.germination[2] = 2.1;
    for (int s = 1; H && s <= SEEDS; s++) {
        p.seed = (uint64_t)(400 + s);
        banyan_mesh_free(grow_check(H, &p, -1, &rep));
    }
    banyan_hosts_free(H);
    expect_clean("open wall", &rep);
    CHECK(rep.main_edges_through == 0, "open wall: %ld main-root edges pass through it", rep.main_edges_through);
    tm_free(&sh);
    tm_free(&wall);
}

/* Two host sets of the same boxes: the same bytes and stats, for every
 * roots preset and the default trunk. */
static void test_box_sets(void) {
    static const char *presets[] = {"roots_trunk.json", "roots_paper.json", "roots_ruin.json", "roots_boulder.json",
                                    "roots_young_fig.json", NULL};
    for (int k = 0; k <= 5; k++) {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        banyan_box boxes[8];
        uint32_t n = 1;
        banyan_error err;
        if (presets[k]) {
            char path[1024];
            snprintf(path, sizeof path, "%s/presets/%s", BANYAN_SOURCE_DIR, presets[k]);
            banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, &p, path, boxes, 8, &n, &err);
            CHECK(s == BANYAN_OK && n > 0, "preset %s: %s", presets[k], err.message);
            if (s) continue;
        } else {
            boxes[0] = banyan_box_make(0, 0, 4, 0.4, 0.4, 4); /* the CLI's default trunk */
        }
        banyan_mesh *a = NULL, *b = NULL;
        banyan_roots_stats sa, sb;
        banyan_hosts *H = make(boxes, n, NULL, 0), *H2 = make(boxes, n, NULL, 0);
        CHECK(H && banyan_roots_generate(&p, H, &a, &sa, NULL, &err) == BANYAN_OK, "host set: %s", err.message);
        CHECK(H2 && banyan_roots_generate(&p, H2, &b, &sb, NULL, &err) == BANYAN_OK, "second set: %s", err.message);
        const char *name = presets[k] ? presets[k] : "default";
        CHECK(a && b && a->vertex_count > 0 && banyan_mesh_hash(a) == banyan_mesh_hash(b) &&
                  a->vertex_count == b->vertex_count && memcmp(&sa, &sb, sizeof sa) == 0,
              "%s: two host sets of the same boxes differ", name);
        banyan_mesh_free(a);
        banyan_mesh_free(b);
        banyan_hosts_free(H);
        banyan_hosts_free(H2);
    }
}

#define REFUSED(code, what, call)                                                                              \
    do {                                                                                                      \
        banyan_mesh *m_ = (banyan_mesh *)&m_;                                                                 \
        banyan_error e_;                                                                                      \
        banyan_roots_stats st_;                                                                               \
        memset(&st_, 0x5a, sizeof st_);                                                                       \
        e_.message[0] = 0;                                                                                    \
        banyan_status s_ = call;                                                                              \
        CHECK(s_ == (code) && m_ == NULL, "%s: status %d (want %d), out %p", what, (int)s_, (int)(code),       \
              (void *)m_);                                                                                    \
        CHECK(strlen(e_.message) > 0, "%s: no message", what);                                                \
        CHECK(st_.vertices == 0 && st_.main_points == 0, "%s: stats not zeroed", what);                       \
        if (s_ != (code)) fprintf(stderr, "  %s: %s\n", what, e_.message);                                    \
    } while (0)

static void test_refusals(void) {
    tm_mesh t = {0};
    tm_cylinder(&t, 0, 0, 0, 0.4, 3.0, 32, 1);
    banyan_host_mesh hm = tm_host(&t, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = make(NULL, 0, &hm, 1);
    banyan_roots_params p;
    banyan_roots_params_init(&p);

    REFUSED(BANYAN_E_NO_HOSTS, "no host set", banyan_roots_generate(&p, NULL, &m_, &st_, NULL, &e_));
    REFUSED(BANYAN_E_INVALID_ARG, "params NULL", banyan_roots_generate(NULL, H, &m_, &st_, NULL, &e_));
    {
        banyan_error e;
        CHECK(banyan_roots_generate(&p, H, NULL, NULL, NULL, &e) == BANYAN_E_INVALID_ARG, "out NULL accepted");
    }
    p.radius = -1;
    REFUSED(BANYAN_E_RANGE, "radius < 0", banyan_roots_generate(&p, H, &m_, &st_, NULL, &e_));
    p.radius = NAN;
    REFUSED(BANYAN_E_RANGE, "radius NaN", banyan_roots_generate(&p, H, &m_, &st_, NULL, &e_));
    banyan_roots_params_init(&p);
    p.germination_auto = 0;
    p.germination[0] = 0.1;
    p.germination[1] = 0;
    p.germination[2] = 1.5;
    {
        banyan_error e;
        banyan_mesh *m = NULL;
        CHECK(banyan_roots_generate(&p, H, &m, NULL, NULL, &e) == BANYAN_E_START_INSIDE && !m &&
                  strstr(e.message, "hosts[0]"),
              "G inside the column: %s", e.message);
    }
    p.germination[0] = 5000;
    REFUSED(BANYAN_E_START_FAR, "G 5 km away", banyan_roots_generate(&p, H, &m_, &st_, NULL, &e_));
    p.germination[0] = 0;
    p.germination[2] = -1;
    REFUSED(BANYAN_E_START_INSIDE, "G under the ground", banyan_roots_generate(&p, H, &m_, &st_, NULL, &e_));
    banyan_hosts_free(H);

    /* Bad meshes never make a host set, so nothing grows on them. */
    struct {
        const char *what;
        int fault;
    } bad[] = {{"NaN vertex", 0}, {"index out of range", 1}, {"no triangles", 2}, {"all zero area", 3}};
    for (int k = 0; k < 4; k++) {
        tm_mesh b = {0};
        tm_cylinder(&b, 0, 0, 0, 0.4, 3.0, 8, 1);
        banyan_host_mesh bm = tm_host(&b, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
        if (bad[k].fault == 0) b.pos[7] = NAN;
        if (bad[k].fault == 1) b.idx[5] = b.nv;
        if (bad[k].fault == 2) bm.triangle_count = 0;
        if (bad[k].fault == 3)
            for (uint32_t i = 0; i < 3 * b.nv; i++) b.pos[i] = 1.0f;
        banyan_hosts *Hb = (banyan_hosts *)&Hb;
        banyan_error e;
        e.message[0] = 0;
        banyan_status s = banyan_hosts_create(NULL, 0, &bm, 1, &Hb, &e);
        CHECK(s != BANYAN_OK && Hb == NULL && strstr(e.message, "hosts[0]"), "%s: status %d, set %p, '%s'",
              bad[k].what, (int)s, (void *)Hb, e.message);
        banyan_hosts_free(Hb);
        tm_free(&b);
    }
    tm_free(&t);
}

/* The exact mesh queries the roots use (hosts/hosts.c), against dense
 * sampling with the nearest-point query: a segment's distance is the least
 * over its points; a swept sphere is free before its contact t and touches
 * at t; pressed against a face and moved along it, it slides. */
static void test_exact_queries(void) {
    tm_mesh shapes[2] = {{0}, {0}}, flat = {0};
    tm_cylinder(&shapes[0], 0, 0, 0, 0.4, 3.0, 32, 3);
    tm_uv_sphere(&shapes[1], 0, 0, 1.0, 1.0, 32, 16);
    tm_box(&flat, 0, 0, 1, 0.5, 0.5, 1);
    pcg32 g;
    pcg32_seed(&g, 7, 1);
    long seg_bad = 0, sweep_free_bad = 0, sweep_touch_bad = 0, contacts = 0, n = 0;
    for (int s = 0; s < 2; s++) {
        banyan_host_mesh hm = tm_host(&shapes[s], 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
        banyan_hosts *H = make(NULL, 0, &hm, 1);
        if (!H) continue;
        const host_mesh *m = &H->meshes[0];
        for (int k = 0; k < 300; k++) {
            /* From around the shape towards somewhere near its middle, half of them. */
            v3 a = v3_make(rng_range(&g, -1.2, 1.2), rng_range(&g, -1.2, 1.2), rng_range(&g, -0.2, 2.4));
            v3 aim = k % 2 ? v3_make(rng_range(&g, -0.5, 0.5), rng_range(&g, -0.5, 0.5), rng_range(&g, 0.5, 1.5))
                           : v3_add(a, v3_make(rng_range(&g, -0.6, 0.6), rng_range(&g, -0.6, 0.6),
                                               rng_range(&g, -0.6, 0.6)));
            v3 b = v3_lerp(a, aim, rng_range(&g, 0.2, 1.0));
            if (hmesh_distance(m, a, HUGE_VAL) < 0.05) continue; /* start outside, free of r = 0.05 */
            n++;
            /* Segment: the sampled least within one spacing above, never below. */
            double sd = hmesh_segment_distance(m, a, b, HUGE_VAL, 0), least = 1e300, L = v3_dist(a, b);
            for (int i = 0; i <= 1000; i++) {
                double d = fabs(hmesh_distance(m, v3_lerp(a, b, i / 1000.0), HUGE_VAL));
                if (d < least) least = d;
            }
            if (least < sd - 1e-6 || least > sd + L / 1000.0 + 1e-6) seg_bad++;
            /* `first` with cap 0.1: below it when the least is, and then no less than the least. */
            double sf = hmesh_segment_distance(m, a, b, 0.1, 1);
            if ((sd < 0.1) != (sf < 0.1) || (sf < 0.1 && sf < sd - 1e-12)) seg_bad++;
            /* Sweep of r = 0.05 from a by b - a. */
            v3 nrm;
            double t = hmesh_sweep(m, a, v3_sub(b, a), 0.05, 1e-11, &nrm);
            for (int i = 0; i < 200; i++) {
                double u = t * i / 200.0;
                if (fabs(hmesh_distance(m, v3_lerp(a, b, u), HUGE_VAL)) < 0.05 - 1e-6) {
                    sweep_free_bad++;
                    break;
                }
            }
            if (t < 1.0) {
                contacts++;
                if (fabs(fabs(hmesh_distance(m, v3_lerp(a, b, t), HUGE_VAL)) - 0.05) > 1e-6) sweep_touch_bad++;
            }
        }
        banyan_hosts_free(H);
    }
    printf("  exact queries: %ld segments and sweeps (%ld contacts)\n", n, contacts);
    CHECK(seg_bad == 0, "segment distance disagrees with dense sampling %ld times", seg_bad);
    CHECK(sweep_free_bad == 0, "swept sphere closer than r before its contact %ld times", sweep_free_bad);
    CHECK(sweep_touch_bad == 0, "swept sphere not touching at its contact %ld times", sweep_touch_bad);
    CHECK(contacts > 100, "only %ld sweeps met the surface", contacts);
    /* Sliding: a sphere r from the face x = 0.5 of a 12-triangle box moved
     * along the face (across its diagonal edges) is not stopped; moved in,
     * it stops at once. */
    banyan_host_mesh fm = tm_host(&flat, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_hosts *H = make(NULL, 0, &fm, 1);
    if (H) {
        v3 nrm, p = v3_make(0.5 + 0.05, -0.3, 0.2);
        CHECK(hmesh_sweep(&H->meshes[0], p, v3_make(0, 0.6, 1.5), 0.05, 1e-11, &nrm) == 1.0,
              "a sphere pressed against a face does not slide along it");
        double t = hmesh_sweep(&H->meshes[0], p, v3_make(-0.2, 0.1, 0), 0.05, 1e-11, &nrm);
        CHECK(t < 1e-9 && nrm.x > 0.999, "a sphere pressed against a face and moved in: t = %g, n = (%g, %g, %g)", t,
              nrm.x, nrm.y, nrm.z);
        banyan_hosts_free(H);
    }
    tm_free(&shapes[0]);
    tm_free(&shapes[1]);
    tm_free(&flat);
}

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : NULL;
    test_exact_queries();
    test_box_sets();
    test_refusals();
    test_cylinder(dir);
    test_sphere(dir);
    test_shells_wall_box(dir);
    return check_done("test_roots_hosts");
}
