/* Roots generator (spec roots.md): invariants over many seeds and host
 * layouts, not snapshots.
 *   - Clearance: every skeleton point of every kind of root, in hugging and
 *     paper mode, is at least r - tol from every host and the ground
 *     (tol = 1e-3 r; the skeleton is stored in float); the underground ends
 *     of roots entering the soil (soil_entry) keep clear of the
 *     hosts only, and their tubes may go below the ground.
 *   - Branch slots whose ends lie past a main root's soil entry grow no
 *     first branch root (so not all N x nb are present).
 *   - Every first branch root starts exactly on M(a,b) and ends exactly on
 *     M(a+1,b); every second branch root joins the middles of its two first
 *     branch roots; none is missing; no step sags into a host; the skeleton
 *     is one connected graph.
 *   - Trunk preset: every main root reaches the ground; first branch roots
 *     cover all four side faces.
 *   - Same seed, same bytes; another seed, another mesh.
 *   - n = 4 gives square tubes; odd n, n < 4, r <= 0, NaN, no hosts and a
 *     germination point inside a host are refused with clear messages.
 *   - Every tube is closed (caps on), has positive volume and outward
 *     normals; attributes and colours are as documented.
 * Writes roots_*.glb for the validator. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_checks.h"
#include "roots/roots_internal.h"
#include "test_files.h"
#include "test_hosts.h"

#define TOL 1e-3 /* times r */

typedef struct layout {
    const char *name;
    banyan_box hosts[4];
    uint32_t n;
    int hugging;
    int crowded; /* hosts touch, leaving crevices narrower than 2 r */
} layout;

static banyan_box rotated(double cx, double cy, double cz, double hx, double hy, double hz, double rx, double ry,
                          double rz) {
    banyan_box b = banyan_box_make(cx, cy, cz, hx, hy, hz);
    m3 X = m3_rotation(v3_make(1, 0, 0), deg2rad(rx)), Y = m3_rotation(v3_make(0, 1, 0), deg2rad(ry)),
       Z = m3_rotation(v3_make(0, 0, 1), deg2rad(rz));
    m3 ZY = m3_mul(&Z, &Y), R = m3_mul(&ZY, &X);
    memcpy(b.rotation, R.m, sizeof R.m);
    return b;
}


/* Loads presets/<name> into p and hosts; returns the host count, 0 on failure. */
static uint32_t load_preset(const char *name, banyan_roots_params *p, banyan_box *hosts) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s", BANYAN_SOURCE_DIR, name);
    banyan_error err;
    uint32_t n = 0;
    banyan_roots_params_init(p);
    banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, p, path, hosts, 8, &n, &err);
    CHECK(s == BANYAN_OK && n > 0, "preset %s: %s", name, err.message);
    return s ? 0 : n;
}

/* ---------------------------------------------------------------- mesh */

static const float *P(const banyan_mesh *m, uint32_t v) { return m->positions + 3 * (size_t)v; }

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

typedef struct tube_report {
    int tubes, open, nonpositive, inward_normals;
    long triangles, flipped, radial_checked;
} tube_report;

/* Side vertices of round rings: the normal points away from the ring's
 * centre (the skeleton point the ring was swept round). Junction loops of
 * smoothed first branch roots are not round and are left out. */
static void check_radial(const roots_net *net, const banyan_roots_params *p, const banyan_mesh *m, tube_report *rep) {
    uint32_t base = 0;
    int S = p->sides;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2) continue;
        uint32_t nv = pl->n * (uint32_t)(S + 1) + 2 * (uint32_t)(S + 2);
        if (!(pl->kind == ROOT_FIRST && p->smoothing))
            for (uint32_t i = 0; i < pl->n; i++) {
                v3 c = net->pts[pl->off + i];
                for (int j = 0; j <= S; j++) {
                    uint32_t v = base + i * (uint32_t)(S + 1) + (uint32_t)j;
                    const float *q = P(m, v), *nn = m->normals + 3 * (size_t)v;
                    double d = (q[0] - c.x) * nn[0] + (q[1] - c.y) * nn[1] + (q[2] - c.z) * nn[2];
                    rep->radial_checked++;
                    if (!(d > 0)) rep->inward_normals++;
                }
            }
        base += nv;
    }
}

/* Every tube is closed: its vertices are welded by their place in the
 * sweep (the seam copy of ring vertex 0 and the cap rings are the ring
 * vertices they duplicate) and every edge must then be shared by exactly
 * two triangles. Also: positive volume, unit normals, and the count of
 * triangles wound against their vertex normals. */
static void check_tubes(const roots_net *net, const banyan_roots_params *p, const banyan_mesh *m, tube_report *rep) {
    uint32_t S = (uint32_t)p->sides, base = 0, ibase = 0;
    uint32_t *weld = malloc(sizeof(uint32_t) * m->vertex_count);
    uint64_t *edges = malloc(sizeof(uint64_t) * m->index_count);
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2) continue;
        uint32_t n = pl->n, ring = S + 1, nv = n * ring + 2 * (S + 2), ni = (n - 1) * S * 6 + 2 * S * 3;
        for (uint32_t i = 0; i < n; i++)
            for (uint32_t j = 0; j <= S; j++) weld[base + i * ring + j] = base + i * ring + j % S;
        uint32_t c0 = base + n * ring, c1 = c0 + S + 2;
        weld[c0] = c0;
        weld[c1] = c1;
        for (uint32_t j = 0; j <= S; j++) {
            weld[c0 + 1 + j] = base + j % S;
            weld[c1 + 1 + j] = base + (n - 1) * ring + j % S;
        }
        double vol = 0;
        const float *o = P(m, base);
        for (uint32_t k = 0; k < ni; k += 3) {
            const uint32_t *I = m->indices + ibase + k;
            for (int e = 0; e < 3; e++) {
                uint64_t a = weld[I[e]], b = weld[I[(e + 1) % 3]];
                edges[k + (uint32_t)e] = a < b ? a << 32 | b : b << 32 | a;
            }
            const float *a = P(m, I[0]), *b = P(m, I[1]), *c = P(m, I[2]);
            double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2], bx = b[0] - o[0], by = b[1] - o[1],
                   bz = b[2] - o[2], cx = c[0] - o[0], cy = c[1] - o[1], cz = c[2] - o[2];
            vol += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6.0;
            double ux = bx - ax, uy = by - ay, uz = bz - az, wx = cx - ax, wy = cy - ay, wz = cz - az;
            double fx = uy * wz - uz * wy, fy = uz * wx - ux * wz, fz = ux * wy - uy * wx;
            const float *na = m->normals + 3 * (size_t)I[0], *nb = m->normals + 3 * (size_t)I[1],
                        *nc = m->normals + 3 * (size_t)I[2];
            double dot = fx * (na[0] + nb[0] + nc[0]) + fy * (na[1] + nb[1] + nc[1]) + fz * (na[2] + nb[2] + nc[2]);
            rep->triangles++;
            if (sqrt(fx * fx + fy * fy + fz * fz) > 1e-12 && dot <= 0) rep->flipped++;
        }
        qsort(edges, ni, sizeof(uint64_t), cmp_u64);
        int open = 0;
        for (uint32_t i = 0; i < ni;) {
            uint32_t j = i;
            while (j < ni && edges[j] == edges[i]) j++;
            if (j - i != 2) open++;
            i = j;
        }
        rep->tubes++;
        if (open) rep->open++;
        if (!(vol > 0)) rep->nonpositive++;
        base += nv;
        ibase += ni;
    }
    if (base != m->vertex_count || ibase != m->index_count) rep->open++; /* layout not as documented */
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *nn = m->normals + 3 * (size_t)v;
        if (fabs(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2] - 1.0) > 1e-4) rep->inward_normals++;
    }
    free(weld);
    free(edges);
}

/* ----------------------------------------------------------- net checks */

typedef struct net_report {
    int nets;
    int clearance_bad;        /* skeleton points closer than r - tol */
    int pts_bad;              /* net points (double) closer than r (1 - 1e-6) */
    double worst;             /* least clearance / r seen */
    int first_missing, first_bad_ends, second_missing, second_bad_ends;
    int sag_bad;              /* segments sagging more than 0.2 r into a host */
    long segments;
    int disconnected;
    int stats_bad;
    long verts_inside;        /* mesh vertices more than 0.1 mm inside a host or the ground */
    double deepest;
} net_report;

static double clearance_g(const roots_world *w, const obb *hosts, uint32_t n, v3 p, int ground) {
    double c = w->ground && ground ? p.z - w->ground_z : 1e300;
    for (uint32_t i = 0; i < n; i++) {
        double d = obb_signed_distance(&hosts[i], p);
        if (d < c) c = d;
    }
    return c;
}

static double clearance(const roots_world *w, const obb *hosts, uint32_t n, v3 p) {
    return clearance_g(w, hosts, n, p, 1);
}

/* p is one of the points of an underground end (soil_entry), to float precision. */
static int in_soil_end(const roots_net *net, v3 p) {
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        for (uint32_t i = pl->soil_from; i < pl->n; i++)
            if (v3_dist(net->pts[pl->off + i], p) < 1e-5) return 1;
    }
    return 0;
}

static void check_net(const roots_net *net, const banyan_roots_params *p, const banyan_mesh *m,
                      const banyan_roots_stats *st, net_report *rep) {
    const roots_world *w = &net->w;
    double r = net->r;
    rep->nets++;
    /* Clearance of every skeleton point (float) to every host, exact box distance. */
    for (uint32_t i = 0; i < m->skel_point_count; i++) {
        v3 q = v3_make(m->skel_points[3 * i], m->skel_points[3 * i + 1], m->skel_points[3 * i + 2]);
        double c = clearance(w, w->hosts, w->n_hosts, q);
        if (c < r - TOL * r && in_soil_end(net, q)) c = clearance_g(w, w->hosts, w->n_hosts, q, 0);
        if (c / r < rep->worst) rep->worst = c / r;
        if (c < r - TOL * r) rep->clearance_bad++;
    }
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        for (uint32_t i = 0; i < pl->n; i++)
            if (clearance_g(w, w->hosts, w->n_hosts, net->pts[pl->off + i], i < pl->soil_from) < r * (1 - 1e-6))
                rep->pts_bad++;
    }
    /* No mesh vertex enters a host or the ground (the tube surface, not only
     * its axis; 0.1 mm for float storage), except the tubes of roots that
     * enter the soil, which go below the ground (tubes follow the polylines
     * in order, n (sides + 1) + 2 (sides + 2) vertices each). */
    uint32_t vbase = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2) continue;
        uint32_t nv = pl->n * (uint32_t)(p->sides + 1) + 2 * (uint32_t)(p->sides + 2);
        for (uint32_t v = vbase; v < vbase + nv && v < m->vertex_count; v++) {
            const float *q = m->positions + 3 * (size_t)v;
            double c = clearance_g(w, w->hosts, w->n_hosts, v3_make(q[0], q[1], q[2]), pl->soil_from >= pl->n);
            if (c < -1e-4) {
                rep->verts_inside++;
                if (-c > rep->deepest) rep->deepest = -c;
            }
        }
        vbase += nv;
    }
    /* Segments: none sags more than 0.2 r into a host (sampled densely). */
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        for (uint32_t i = 1; i < pl->n; i++) {
            v3 a = net->pts[pl->off + i - 1], b = net->pts[pl->off + i];
            rep->segments++;
            int bad = 0;
            for (int k = 1; k < 16 && !bad; k++)
                if (clearance_g(w, w->hosts, w->n_hosts, v3_lerp(a, b, k / 16.0), i < pl->soil_from) <
                    0.8 * r - TOL * r)
                    bad = 1;
            rep->sag_bad += bad;
        }
    }
    /* Branch roots: all present, ends exactly on their targets. */
    int N = net->N, B = net->B, nb = net->nb, firsts = 0, seconds = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        const v3 *Pp = net->pts + pl->off;
        if (pl->kind == ROOT_FIRST) {
            firsts++;
            int b = roots_branch_b(p, pl->k), be = roots_branch_end_b(net, p, pl->a * nb + pl->k);
            v3 s = net->M[(size_t)pl->a * B + b], e = net->M[(size_t)((pl->a + 1) % N) * B + be];
            const v3 *K = net->K + (size_t)(pl->a * nb + pl->k) * net->S1;
            if (memcmp(&Pp[0], &s, sizeof s) || memcmp(&Pp[pl->n - 1], &e, sizeof e) ||
                memcmp(&K[0], &s, sizeof s) || memcmp(&K[net->S1 - 1], &e, sizeof e) || pl->n < 2)
                rep->first_bad_ends++;
        } else if (pl->kind == ROOT_SECOND) {
            seconds++;
            int slot = pl->a * nb + pl->k, mid = (net->S1 - 1) / 2;
            v3 s = net->K[(size_t)slot * net->S1 + mid], e = net->K[(size_t)(slot + 1) * net->S1 + mid];
            if (memcmp(&Pp[0], &s, sizeof s) || memcmp(&Pp[pl->n - 1], &e, sizeof e) || pl->n < 2)
                rep->second_bad_ends++;
        }
    }
    /* Slots open on both main roots (above their soil entries). */
    int want_first = 0, want_second = 0;
    for (int a = 0; a < N && p->first_branches && N >= 2; a++)
        for (int k = 0; k < nb; k++) {
            if (!roots_slot_open(net, p, a, k)) continue;
            want_first++;
            if (p->second_branches && k + 1 < nb && roots_slot_open(net, p, a, k + 1)) want_second++;
        }
    if (firsts != want_first) rep->first_missing++;
    if (seconds != want_second) rep->second_missing++;
    if (mc_skeleton_pieces(m) != 1) rep->disconnected++; /* one connected graph */
    if (st->first_reached != st->first_roots || st->first_roots != (uint32_t)want_first ||
        st->min_clearance < r * (1 - 1e-6) || st->vertices != m->vertex_count || st->triangles != m->index_count / 3)
        rep->stats_bad++;
}

static void run(const banyan_roots_params *p, const banyan_box *hosts, uint32_t n, net_report *nr, tube_report *tr,
                int mesh_checks) {
    /* The tube checks read the tubes' layout: tube mode (test_roots_fused
     * checks the fused surface). */
    banyan_roots_params tubes = *p;
    tubes.surface = BANYAN_ROOTS_TUBES;
    p = &tubes;
    roots_net net;
    banyan_error err;
    banyan_status s = roots_net_build(p, hosts, n, &net, &err);
    CHECK(s == BANYAN_OK, "seed %llu: %s", (unsigned long long)p->seed, err.message);
    if (s) return;
    banyan_mesh *m = NULL;
    banyan_roots_stats st = net.stats;
    s = roots_net_mesh(&net, p, &m, &st, &err);
    CHECK(s == BANYAN_OK, "seed %llu mesh: %s", (unsigned long long)p->seed, err.message);
    if (!s) {
        check_net(&net, p, m, &st, nr);
        if (mesh_checks) {
            check_tubes(&net, p, m, tr);
            check_radial(&net, p, m, tr);
        }
    }
    banyan_mesh_free(m);
    roots_net_free(&net);
}

static void write_glb(const char *dir, const char *name, const banyan_roots_params *p, const banyan_box *hosts,
                      uint32_t n) {
    banyan_mesh *m = NULL;
    banyan_error err;
    CHECK(test_roots_boxes(p, hosts, n, &m, &err) == BANYAN_OK, "%s: %s", name, err.message);
    if (!m || !dir) {
        banyan_mesh_free(m);
        return;
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write %s: %s", path,
          err.message);
    banyan_mesh_free(m);
}

/* A refusal: the status, *out left NULL and the message naming `needle`.
 * Bad boxes are refused by the host set, the rest by the generator. */
static void refused(const banyan_roots_params *p, const banyan_box *hosts, uint32_t n, banyan_status want,
                    const char *needle, const char *what) {
    banyan_error err;
    memset(&err, 0, sizeof err);
    banyan_mesh *m = NULL;
    banyan_hosts *H = NULL;
    banyan_status s = banyan_hosts_create(hosts, n, NULL, 0, &H, &err);
    if (!s) {
        m = (banyan_mesh *)&err;
        s = banyan_roots_generate(p, H, &m, NULL, NULL, &err);
    }
    banyan_hosts_free(H);
    CHECK(s == want && m == NULL && strstr(err.message, needle) != NULL, "%s: status %d (want %d), message '%s'", what,
          s, want, err.message);
}

/* One shipped preset: its net keeps the invariants, it writes a glb, and
 * the presets whose descriptions promise something keep the promise. */
static void roots_preset(const char *path, const char *name, void *ctx) {
    (void)path;
    char file[300], glb[320];
    snprintf(file, sizeof file, "%s.json", name);
    banyan_roots_params p;
    banyan_box hosts[8];
    uint32_t n = load_preset(file, &p, hosts);
    if (!n) return;
    net_report nr;
    tube_report tr;
    memset(&nr, 0, sizeof nr);
    memset(&tr, 0, sizeof tr);
    nr.worst = 1e300;
    run(&p, hosts, n, &nr, &tr, 1);
    CHECK(nr.nets == 1 && nr.clearance_bad == 0 && nr.verts_inside == 0 && nr.disconnected == 0 && tr.open == 0,
          "%s: %d nets, %d points too close, %ld vertices inside, %d disconnected, %d open tubes", name, nr.nets,
          nr.clearance_bad, nr.verts_inside, nr.disconnected, tr.open);
    banyan_mesh *m = NULL;
    banyan_roots_stats st;
    banyan_error err;
    banyan_hosts *H = TEST_HOSTS(hosts, n);
    CHECK(banyan_roots_generate(&p, H, &m, &st, NULL, &err) == BANYAN_OK, "%s: %s", name, err.message);
    banyan_hosts_free(H);
    if (!strcmp(name, "roots_paper")) CHECK(p.hugging == 0, "the paper preset must turn hugging off");
    /* Every shipped preset touches the ground (the young fig's
     * cords have just reached it). */
    CHECK(m && st.mains_on_ground > 0, "%s: no main root reached the ground", name);
    if (!strcmp(name, "roots_trunk") || !strcmp(name, "roots_ruin"))
        CHECK(m && st.mains_on_ground == (uint32_t)p.main_roots, "%s: %u of %d main roots reached the ground", name,
              st.mains_on_ground, p.main_roots);
    banyan_mesh_free(m);
    snprintf(glb, sizeof glb, "roots_preset_%s.glb", name + 6);
    write_glb(ctx, glb, &p, hosts, n);
}

int main(int argc, char **argv) {
    const char *out = argc > 1 ? argv[1] : NULL;
    layout layouts[6];
    memset(layouts, 0, sizeof layouts);
    layouts[0] = (layout){"trunk", {banyan_box_make(0, 0, 4, 0.4, 0.4, 4)}, 1, 1, 0};
    layouts[1] = (layout){"rotated",
                          {rotated(0, 0, 3, 0.35, 0.3, 3, 8, 0, 25), rotated(1.1, 0.5, 0.5, 0.5, 0.4, 0.5, 0, 15, 40)},
                          2, 1, 0};
    layouts[2] = (layout){"stacked", {banyan_box_make(0.1, 0, 2.5, 0.3, 0.3, 0.5), banyan_box_make(0, 0, 1, 0.8, 0.8, 1)},
                          2, 1, 0};
    layouts[3] = (layout){"boulder", {rotated(0, 0, 0.7, 1.6, 1.2, 0.7, 0, 0, 20)}, 1, 1, 0};
    layouts[4] = (layout){"paper_trunk", {banyan_box_make(0, 0, 4, 0.4, 0.4, 4)}, 1, 0, 0};
    layouts[5] = (layout){"paper_stacked_rotated",
                          {rotated(0, 0, 2.6, 0.3, 0.25, 0.6, 0, 0, 30), banyan_box_make(0, 0, 1, 0.8, 0.8, 1),
                           rotated(1.3, -0.6, 0.4, 0.4, 0.4, 0.4, 20, 10, 0)},
                          3, 0, 1};

    /* 1. Invariants over 200 seeds per layout. */
    for (int L = 0; L < 6; L++) {
        net_report nr;
        tube_report tr;
        memset(&nr, 0, sizeof nr);
        memset(&tr, 0, sizeof tr);
        nr.worst = 1e300;
        for (uint64_t seed = 1; seed <= 200; seed++) {
            banyan_roots_params p;
            banyan_roots_params_init(&p);
            p.seed = seed * 7919 + (uint64_t)L;
            p.hugging = layouts[L].hugging;
            p.sides = 4 + 2 * (int)(seed % 3);
            p.growth_points = 24 + (int)(seed % 17);
            /* Vary the switches now and then. */
            if (seed % 11 == 0) p.correction = 0;
            if (seed % 13 == 0) p.smoothing = 0;
            if (seed % 17 == 0) p.second_branches = 0;
            if (seed % 23 == 0) p.maturity = 1.0;
            if (seed % 29 == 0) p.bezier_uniform = 1;
            if (seed % 31 == 0) p.ground = 0;
            run(&p, layouts[L].hosts, layouts[L].n, &nr, &tr, seed % 8 == 0);
        }
        printf("layout %-22s nets %d, least clearance %.6f r, tubes checked %d\n", layouts[L].name, nr.nets, nr.worst,
               tr.tubes);
        CHECK(nr.nets == 200, "%s: %d nets", layouts[L].name, nr.nets);
        CHECK(nr.clearance_bad == 0, "%s: %d skeleton points closer than r - tol (least %.6f r)", layouts[L].name,
              nr.clearance_bad, nr.worst);
        CHECK(nr.pts_bad == 0, "%s: %d path points closer than r", layouts[L].name, nr.pts_bad);
        CHECK(nr.verts_inside == 0, "%s: %ld mesh vertices inside a host (deepest %.5f m)", layouts[L].name,
              nr.verts_inside, nr.deepest);
        /* Segment repair is local: where touching hosts leave crevices
         * narrower than 2 r it can miss a way round (docs/roots.md). */
        if (layouts[L].crowded)
            CHECK(nr.sag_bad * 1000 <= nr.segments, "%s: %d of %ld segments sag into a host", layouts[L].name,
                  nr.sag_bad, nr.segments);
        else
            CHECK(nr.sag_bad == 0, "%s: %d of %ld segments sag into a host", layouts[L].name, nr.sag_bad, nr.segments);
        printf("  segments sagging more than 0.2 r into a host: %d of %ld\n", nr.sag_bad, nr.segments);
        CHECK(nr.first_missing == 0 && nr.first_bad_ends == 0, "%s: first branch roots missing in %d nets, %d with wrong ends",
              layouts[L].name, nr.first_missing, nr.first_bad_ends);
        CHECK(nr.second_missing == 0 && nr.second_bad_ends == 0,
              "%s: second branch roots missing in %d nets, %d with wrong ends", layouts[L].name, nr.second_missing,
              nr.second_bad_ends);
        CHECK(nr.disconnected == 0, "%s: %d skeletons not connected", layouts[L].name, nr.disconnected);
        CHECK(nr.stats_bad == 0, "%s: %d nets with inconsistent stats", layouts[L].name, nr.stats_bad);
        CHECK(tr.tubes > 0 && tr.open == 0, "%s: %d of %d tubes not closed", layouts[L].name, tr.open, tr.tubes);
        CHECK(tr.nonpositive == 0, "%s: %d tubes with non-positive volume", layouts[L].name, tr.nonpositive);
        CHECK(tr.inward_normals == 0 && tr.radial_checked > 0, "%s: %d normals not unit or pointing inwards",
              layouts[L].name, tr.inward_normals);
        /* Where a jittered branch root turns back within r its tube folds
         * over itself and some triangles face inwards, inside the tube;
         * they stay a small minority. */
        CHECK(tr.flipped * 20 <= tr.triangles, "%s: %ld of %ld triangles wound against their normals",
              layouts[L].name, tr.flipped, tr.triangles);
        printf("  triangles wound against their vertex normals (folds): %ld of %ld\n", tr.flipped, tr.triangles);
    }

    /* 2. The trunk preset: roots reach the ground and wrap all four faces. */
    {
        banyan_roots_params p;
        banyan_box hosts[8];
        uint32_t n = load_preset("roots_trunk.json", &p, hosts);
        int not_down = 0, faces_missed = 0, nets = 0;
        for (uint64_t seed = 1; n && seed <= 60; seed++) {
            p.seed = seed;
            roots_net net;
            banyan_error err;
            if (roots_net_build(&p, hosts, n, &net, &err)) {
                CHECK(0, "trunk seed %llu: %s", (unsigned long long)seed, err.message);
                continue;
            }
            nets++;
            for (int a = 0; a < net.N; a++) {
                double low = 1e300;
                for (int b = 0; b < net.B; b++) {
                    double z = net.M[(size_t)a * net.B + b].z - p.ground_z;
                    if (z < low) low = z;
                }
                if (!net.ground_hit[a] || low > net.r * (1 + 1e-6)) not_down++;
            }
            int cover[4] = {0, 0, 0, 0};
            const obb *o = &net.w.hosts[0];
            for (uint32_t t = 0; t < net.n_poly; t++) {
                const roots_poly *pl = &net.poly[t];
                if (pl->kind != ROOT_FIRST) continue;
                for (uint32_t i = 1; i + 1 < pl->n; i++) {
                    v3 l = obb_to_local(o, net.pts[pl->off + i]);
                    double lc[3] = {l.x, l.y, l.z};
                    for (int ax = 0; ax < 2; ax++) {
                        int other = 1 - ax;
                        double d = fabs(lc[ax]) - o->h[ax];
                        if (d > 0 && d <= 1.5 * net.r && fabs(lc[other]) <= o->h[other] && fabs(l.z) <= o->h[2])
                            cover[2 * ax + (lc[ax] > 0)] = 1;
                    }
                }
            }
            if (!(cover[0] && cover[1] && cover[2] && cover[3])) faces_missed++;
            roots_net_free(&net);
        }
        printf("trunk preset: %d nets, %d main roots short of the ground, %d nets missing a side face\n", nets, not_down,
               faces_missed);
        CHECK(nets == 60, "trunk preset: %d nets", nets);
        CHECK(not_down == 0, "trunk preset: %d main roots never reached the ground", not_down);
        CHECK(faces_missed == 0, "trunk preset: %d nets whose first branch roots miss a side face", faces_missed);
    }

    /* 3. Every presets/roots_*.json loads and generates. */
    {
        int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "roots_", roots_preset, (void *)out);
        CHECK(n >= 5, "found %d presets/roots_*.json", n);
    }

    /* 4. Determinism. */
    {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        banyan_mesh *a = NULL, *b = NULL, *c = NULL;
        p.seed = 42;
        test_roots_boxes(&p, &host, 1, &a, NULL);
        test_roots_boxes(&p, &host, 1, &b, NULL);
        p.seed = 43;
        test_roots_boxes(&p, &host, 1, &c, NULL);
        CHECK(a && b && c, "generate failed");
        if (a && b && c) {
            CHECK(banyan_mesh_hash(a) == banyan_mesh_hash(b), "same seed, different meshes");
            CHECK(a->vertex_count == b->vertex_count &&
                      memcmp(a->positions, b->positions, sizeof(float) * 3 * a->vertex_count) == 0,
                  "same seed, different positions");
            CHECK(banyan_mesh_hash(a) != banyan_mesh_hash(c), "seeds 42 and 43 gave the same mesh");
        }
        banyan_mesh_free(a);
        banyan_mesh_free(b);
        banyan_mesh_free(c);
    }

    /* 5. n = 4: square tubes; counts follow the polylines. */
    {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        p.sides = 4;
        p.surface = BANYAN_ROOTS_TUBES;
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        roots_net net;
        banyan_error err;
        CHECK(roots_net_build(&p, &host, 1, &net, &err) == BANYAN_OK, "n = 4: %s", err.message);
        banyan_mesh *m = NULL;
        banyan_roots_stats st = net.stats;
        CHECK(roots_net_mesh(&net, &p, &m, &st, &err) == BANYAN_OK, "n = 4 mesh: %s", err.message);
        if (m) {
            uint64_t want_i = 0, want_v = 0;
            for (uint32_t t = 0; t < net.n_poly; t++) {
                want_i += (uint64_t)(net.poly[t].n - 1) * 4 * 6 + 2 * 4 * 3;
                want_v += (uint64_t)net.poly[t].n * 5 + 2 * 6;
            }
            CHECK(m->index_count == want_i && m->vertex_count == want_v, "n = 4: %u indices, %u vertices (want %llu, %llu)",
                  m->index_count, m->vertex_count, (unsigned long long)want_i, (unsigned long long)want_v);
            /* The first ring of the first main root: a square of side rad sqrt 2
             * round G (rad: the pipe model's radius there, tip_radius r). */
            v3 g = net.pts[0];
            double r0 = net.rad[0];
            int square = 1;
            for (int j = 0; j < 4; j++) {
                const float *a = P(m, (uint32_t)j), *b = P(m, (uint32_t)(j + 1) % 4);
                double ra = sqrt((a[0] - g.x) * (a[0] - g.x) + (a[1] - g.y) * (a[1] - g.y) + (a[2] - g.z) * (a[2] - g.z));
                double side = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
                if (fabs(ra - r0) > 1e-5 || fabs(side - r0 * sqrt(2.0)) > 1e-5) square = 0;
            }
            CHECK(square && fabs(r0 - p.tip_radius * net.r) < 1e-9, "n = 4: the first ring is not a square of radius "
                  "tip_radius r");
            tube_report tr;
            memset(&tr, 0, sizeof tr);
            check_tubes(&net, &p, m, &tr);
            CHECK(tr.open == 0 && tr.nonpositive == 0, "n = 4: %d open, %d inside-out tubes", tr.open, tr.nonpositive);
            if (out) {
                char path[1024];
                snprintf(path, sizeof path, "%s/roots_n4.glb", out);
                CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write: %s",
                      err.message);
            }
        }
        banyan_mesh_free(m);
        roots_net_free(&net);
    }

    /* 6. Attributes, colour, material, skeleton tags. */
    {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        p.color[0] = 0.3;
        p.color[1] = 0.2;
        p.color[2] = 0.1;
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        roots_net net;
        banyan_error err;
        roots_net_build(&p, &host, 1, &net, &err);
        banyan_mesh *m = NULL;
        banyan_roots_stats st = net.stats;
        roots_net_mesh(&net, &p, &m, &st, &err);
        CHECK(m != NULL, "attributes mesh: %s", err.message);
        if (m) {
            const float *kind = banyan_mesh_attribute(m, "root_kind"), *id = banyan_mesh_attribute(m, "root_id");
            CHECK(kind && id && m->colors, "root_kind, root_id and colours must be present");
            int bad = 0, kinds[5] = {0, 0, 0, 0, 0};
            for (uint32_t v = 0; kind && id && m->colors && v < m->vertex_count; v++) {
                int k = (int)kind[v], i = (int)id[v];
                if (k < 0 || k > ROOT_AERIAL || kind[v] != k || i < 0 || (uint32_t)i >= net.n_poly || net.poly[i].kind != k) bad++;
                else kinds[k]++;
                if (m->colors[4 * v] != 0.3f || m->colors[4 * v + 1] != 0.2f || m->colors[4 * v + 2] != 0.1f ||
                    m->colors[4 * v + 3] != 1.0f)
                    bad++;
            }
            CHECK(bad == 0, "%d vertices with bad root_kind, root_id or colour", bad);
            CHECK(kinds[0] && kinds[1] && kinds[2], "kinds present: %d %d %d", kinds[0], kinds[1], kinds[2]);
            CHECK(m->material_count == 1 && m->materials[0].base_color[0] == 0.3f && m->materials[0].base_color[2] == 0.1f,
                  "material base colour");
            int tags = 0;
            for (uint32_t i = 0; i < m->skel_point_count; i++) tags += m->skel_tag[i] < 0 || m->skel_tag[i] > ROOT_AERIAL;
            CHECK(tags == 0 && m->skel_edge_count > 0, "%d skeleton tags out of range", tags);
        }
        banyan_mesh_free(m);
        roots_net_free(&net);
    }

    /* 7. Switches. */
    {
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        p.first_branches = 0;
        roots_net net;
        banyan_error err;
        int kinds[5] = {0, 0, 0, 0, 0}; /* ROOT_MAIN .. ROOT_AERIAL */
        roots_net_build(&p, &host, 1, &net, &err);
        for (uint32_t t = 0; t < net.n_poly; t++) kinds[net.poly[t].kind]++;
        CHECK(kinds[0] == 6 && kinds[1] == 0 && kinds[2] == 0, "first_branches off: kinds %d %d %d", kinds[0], kinds[1],
              kinds[2]);
        roots_net_free(&net);
        banyan_roots_params_init(&p);
        p.second_branches = 0;
        memset(kinds, 0, sizeof kinds);
        roots_net_build(&p, &host, 1, &net, &err);
        for (uint32_t t = 0; t < net.n_poly; t++) kinds[net.poly[t].kind]++;
        int open = 0;
        for (int a = 0; a < net.N; a++)
            for (int k = 0; k < net.nb; k++) open += roots_slot_open(&net, &p, a, k);
        CHECK(kinds[1] == open && open > 0 && kinds[2] == 0, "second_branches off: kinds %d %d %d (%d open slots)",
              kinds[0], kinds[1], kinds[2], open);
        roots_net_free(&net);
        banyan_roots_params_init(&p);
        p.correction = 0;
        roots_net_build(&p, &host, 1, &net, &err);
        CHECK(memcmp(net.M, net.M_grown, sizeof(v3) * (size_t)net.N * net.B) == 0, "correction off moved main roots");
        roots_net_free(&net);
        banyan_roots_params_init(&p);
        roots_net_build(&p, &host, 1, &net, &err);
        CHECK(memcmp(net.M, net.M_grown, sizeof(v3) * (size_t)net.N * net.B) != 0, "correction on moved nothing");
        roots_net_free(&net);
        /* Smoothing off: round first rings (all at distance r from their centre);
         * junction smoothing shapes the tubes (the fused surface has fillets). */
        banyan_roots_params_init(&p);
        p.surface = BANYAN_ROOTS_TUBES;
        banyan_mesh *a = NULL, *b = NULL;
        test_roots_boxes(&p, &host, 1, &a, NULL);
        p.smoothing = 0;
        test_roots_boxes(&p, &host, 1, &b, NULL);
        CHECK(a && b && a->vertex_count == b->vertex_count && banyan_mesh_hash(a) != banyan_mesh_hash(b),
              "smoothing off changed nothing");
        banyan_mesh_free(a);
        banyan_mesh_free(b);
    }

    /* 8. Refusals with clear messages. */
    {
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        banyan_roots_params p;
        int odd[] = {3, 5, 7, 2, 0, -4, 258};
        for (int i = 0; i < 7; i++) {
            banyan_roots_params_init(&p);
            p.sides = odd[i];
            char what[32];
            snprintf(what, sizeof what, "sides = %d", odd[i]);
            refused(&p, &host, 1, BANYAN_E_RANGE, "sides", what);
        }
        double radii[] = {0.0, -0.5, NAN, INFINITY};
        for (int i = 0; i < 4; i++) {
            banyan_roots_params_init(&p);
            p.radius = radii[i];
            refused(&p, &host, 1, BANYAN_E_RANGE, "radius", "bad radius");
        }
        banyan_roots_params_init(&p);
        refused(&p, &host, 0, BANYAN_E_NO_HOSTS, "n_boxes + n_meshes = 0", "no hosts");
        refused(&p, NULL, 1, BANYAN_E_INVALID_ARG, "boxes is NULL", "NULL hosts");
        p.germination_auto = 0;
        p.germination[0] = 0.1;
        p.germination[2] = 3.0;
        refused(&p, &host, 1, BANYAN_E_START_INSIDE, "inside hosts[0]", "G inside the trunk");
        p.germination[2] = -1.0;
        p.germination[0] = 5.0;
        refused(&p, &host, 1, BANYAN_E_START_INSIDE, "below the ground", "G below the ground");
        banyan_roots_params_init(&p);
        banyan_box stacked[2] = {banyan_box_make(0, 0, 1, 0.8, 0.8, 1), banyan_box_make(0, 0, 2.5, 0.3, 0.3, 0.5)};
        stacked[1].center[2] = 2.2; /* overlaps the top of hosts[0]: auto G is inside hosts[1] */
        refused(&p, stacked, 2, BANYAN_E_START_INSIDE, "hosts[1]", "auto G inside another host");
        banyan_roots_params_init(&p);
        p.unit = NAN;
        refused(&p, &host, 1, BANYAN_E_RANGE, "unit", "NaN unit");
        banyan_roots_params_init(&p);
        p.forward_min = 5;
        refused(&p, &host, 1, BANYAN_E_RANGE, "forward_min", "forward_min > forward_max");
        banyan_roots_params_init(&p);
        p.max_vertices = 1000;
        refused(&p, &host, 1, BANYAN_E_LIMIT, "max_vertices", "vertex limit");
        banyan_roots_params_init(&p);
        banyan_box flat = banyan_box_make(0, 0, 1, 0.5, 0, 1);
        refused(&p, &flat, 1, BANYAN_E_BAD_HOST, "hosts[0].half[1]", "flat host");
        refused(NULL, &host, 1, BANYAN_E_INVALID_ARG, "params", "NULL params");
        CHECK(test_roots_boxes(&p, &host, 1, NULL, NULL) == BANYAN_E_INVALID_ARG, "NULL out accepted");
        banyan_roots_stats st;
        st.vertices = 77;
        banyan_mesh *m = NULL;
        p.sides = 9;
        banyan_hosts *H = TEST_HOSTS(&host, 1);
        CHECK(banyan_roots_generate(&p, H, &m, &st, NULL, NULL) == BANYAN_E_RANGE && st.vertices == 0,
              "stats not cleared on failure");
        banyan_hosts_free(H);
    }

    /* 9. Layout meshes for the validator. */
    for (int L = 0; L < 6; L++) {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        p.hugging = layouts[L].hugging;
        char name[64];
        snprintf(name, sizeof name, "roots_layout_%s.glb", layouts[L].name);
        write_glb(out, name, &p, layouts[L].hosts, layouts[L].n);
    }
    return check_done("test_roots");
}
