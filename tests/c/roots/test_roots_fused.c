/* The fused roots surface (docs/roots.md "Fused surface"):
 * invariants on the default net and every presets/roots_*.json (box and
 * mesh hosts), 5 seeds each, not snapshots.
 *   - Closed and consistently oriented: with seam copies welded (same
 *     position), every directed edge is used exactly once and its reverse
 *     exactly once (so every edge has exactly two faces, wound opposite).
 *   - Outward: positive signed volume; vertex normals agree with the faces.
 *   - No two faces intersect (faces sharing a vertex are skipped): a
 *     triangle-triangle test over the pairs a uniform grid leaves.
 *   - No vertex inside a host: clearance >= -0.05 r.
 *   - Same seed, same bytes; the attributes, colour and material are there.
 * Writes roots_fused_*.glb for the validator. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "roots/roots_internal.h"
#include "test_files.h"
#include "test_hosts.h"

#define SEEDS 5

static v3 P(const banyan_mesh *m, uint32_t v) {
    const float *f = m->positions + 3 * (size_t)v;
    return v3_make(f[0], f[1], f[2]);
}

static const banyan_mesh *sort_mesh;
static int pos_cmp(const void *a, const void *b) {
    const float *x = sort_mesh->positions + 3 * (size_t)*(const uint32_t *)a,
                *y = sort_mesh->positions + 3 * (size_t)*(const uint32_t *)b;
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}
static int u64_cmp(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Weld map: vertices at the same position get one id. */
static uint32_t *weld(const banyan_mesh *m) {
    uint32_t n = m->vertex_count, *ord = malloc(sizeof(uint32_t) * n), *id = malloc(sizeof(uint32_t) * n);
    for (uint32_t i = 0; i < n; i++) ord[i] = i;
    sort_mesh = m;
    qsort(ord, n, sizeof *ord, pos_cmp);
    for (uint32_t i = 0; i < n; i++)
        id[ord[i]] = i && pos_cmp(&ord[i], &ord[i - 1]) == 0 ? id[ord[i - 1]] : ord[i];
    free(ord);
    return id;
}

/* Directed edges: returns faces with a bad edge (missing reverse, used
 * twice or degenerate). */
static long edge_defects(const banyan_mesh *m, const uint32_t *id) {
    uint32_t nt = m->index_count / 3;
    uint64_t *e = malloc(sizeof(uint64_t) * 3 * nt);
    long bad = 0;
    for (uint32_t f = 0; f < nt; f++)
        for (int j = 0; j < 3; j++) {
            uint32_t a = id[m->indices[3 * f + j]], b = id[m->indices[3 * f + (j + 1) % 3]];
            if (a == b) bad++;
            e[3 * (size_t)f + j] = (uint64_t)a << 32 | b;
        }
    size_t n = 3 * (size_t)nt;
    qsort(e, n, sizeof *e, u64_cmp);
    for (size_t i = 0; i < n; i++) {
        if (i && e[i] == e[i - 1]) bad++;
        uint64_t rev = e[i] << 32 | e[i] >> 32;
        if (!bsearch(&rev, e, n, sizeof *e, u64_cmp)) bad++;
    }
    free(e);
    return bad;
}

static double signed_volume(const banyan_mesh *m) {
    double vol = 0;
    for (uint32_t f = 0; f < m->index_count / 3; f++) {
        v3 a = P(m, m->indices[3 * f]), b = P(m, m->indices[3 * f + 1]), c = P(m, m->indices[3 * f + 2]);
        vol += v3_dot(a, v3_cross(b, c)) / 6;
    }
    return vol;
}

/* Vertex normals that point against the summed normals of their faces
 * (seam copies welded: a copy has only some of the faces). */
static long normals_against(const banyan_mesh *m, const uint32_t *id) {
    double *acc = calloc(3 * (size_t)m->vertex_count, sizeof(double));
    for (uint32_t f = 0; f < m->index_count / 3; f++) {
        const uint32_t *I = m->indices + 3 * (size_t)f;
        v3 n = v3_cross(v3_sub(P(m, I[1]), P(m, I[0])), v3_sub(P(m, I[2]), P(m, I[0])));
        for (int j = 0; j < 3; j++) {
            uint32_t w = id[I[j]];
            acc[3 * w] += n.x, acc[3 * w + 1] += n.y, acc[3 * w + 2] += n.z;
        }
    }
    long bad = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *n = m->normals + 3 * (size_t)v;
        uint32_t w = id[v];
        if (acc[3 * w] * n[0] + acc[3 * w + 1] * n[1] + acc[3 * w + 2] * n[2] <= 0) bad++;
    }
    free(acc);
    return bad;
}

/* Triangle-triangle intersection (Moller's interval test; coplanar pairs
 * by their 2D edges and corners). Touching in a single point or along a
 * line of zero overlap does not count. */
static int seg2_cross(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
    double d1 = (dx - cx) * (ay - cy) - (dy - cy) * (ax - cx), d2 = (dx - cx) * (by - cy) - (dy - cy) * (bx - cx);
    double d3 = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax), d4 = (bx - ax) * (dy - ay) - (by - ay) * (dx - ax);
    return d1 * d2 < 0 && d3 * d4 < 0;
}
static int in_tri2(double px, double py, const double *x, const double *y) {
    double s0 = (x[1] - x[0]) * (py - y[0]) - (y[1] - y[0]) * (px - x[0]);
    double s1 = (x[2] - x[1]) * (py - y[1]) - (y[2] - y[1]) * (px - x[1]);
    double s2 = (x[0] - x[2]) * (py - y[2]) - (y[0] - y[2]) * (px - x[2]);
    return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}
static int coplanar(const v3 *A, const v3 *B, v3 n) {
    double ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
    int i0 = ax >= ay && ax >= az ? 1 : 0, i1 = ax >= ay && ax >= az ? 2 : (ay >= az ? 2 : 1);
    double xa[3], ya[3], xb[3], yb[3];
    for (int k = 0; k < 3; k++) {
        const double *a = &A[k].x, *b = &B[k].x;
        xa[k] = a[i0], ya[k] = a[i1], xb[k] = b[i0], yb[k] = b[i1];
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (seg2_cross(xa[i], ya[i], xa[(i + 1) % 3], ya[(i + 1) % 3], xb[j], yb[j], xb[(j + 1) % 3],
                           yb[(j + 1) % 3]))
                return 1;
    return in_tri2(xa[0], ya[0], xb, yb) || in_tri2(xb[0], yb[0], xa, ya);
}
static int interval(const v3 *T, const double *d, v3 D, double *lo, double *hi) {
    double t[6];
    int n = 0;
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3;
        double pi = v3_dot(T[i], D), pj = v3_dot(T[j], D);
        if (d[i] == 0) t[n++] = pi;
        if ((d[i] < 0 && d[j] > 0) || (d[i] > 0 && d[j] < 0)) t[n++] = pi + (pj - pi) * d[i] / (d[i] - d[j]);
    }
    if (!n) return 0;
    *lo = *hi = t[0];
    for (int i = 1; i < n; i++) *lo = fmin(*lo, t[i]), *hi = fmax(*hi, t[i]);
    return 1;
}
static int tri_tri(const v3 *A, const v3 *B) {
    v3 n2 = v3_cross(v3_sub(B[1], B[0]), v3_sub(B[2], B[0]));
    double da[3], db[3];
    for (int i = 0; i < 3; i++) da[i] = v3_dot(n2, v3_sub(A[i], B[0]));
    if ((da[0] > 0 && da[1] > 0 && da[2] > 0) || (da[0] < 0 && da[1] < 0 && da[2] < 0)) return 0;
    v3 n1 = v3_cross(v3_sub(A[1], A[0]), v3_sub(A[2], A[0]));
    for (int i = 0; i < 3; i++) db[i] = v3_dot(n1, v3_sub(B[i], A[0]));
    if ((db[0] > 0 && db[1] > 0 && db[2] > 0) || (db[0] < 0 && db[1] < 0 && db[2] < 0)) return 0;
    if (da[0] == 0 && da[1] == 0 && da[2] == 0) return coplanar(A, B, n1);
    v3 D = v3_cross(n1, n2);
    double l1, h1, l2, h2;
    if (!interval(A, da, D, &l1, &h1) || !interval(B, db, D, &l2, &h2)) return 0;
    double s = 1e-12 * (fabs(l1) + fabs(h1) + fabs(l2) + fabs(h2));
    return fmax(l1, l2) < fmin(h1, h2) - s;
}

typedef struct cell_tri {
    uint64_t cell;
    uint32_t tri;
} cell_tri;
static int cell_cmp(const void *a, const void *b) {
    const cell_tri *x = a, *y = b;
    if (x->cell != y->cell) return x->cell < y->cell ? -1 : 1;
    return x->tri < y->tri ? -1 : x->tri > y->tri;
}

/* Intersecting face pairs, sharing no (welded) vertex. */
static long intersecting_pairs(const banyan_mesh *m, const uint32_t *id) {
    uint32_t nt = m->index_count / 3;
    v3 lo = P(m, 0), hi = lo;
    double edge = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        v3 q = P(m, v);
        lo = v3_make(fmin(lo.x, q.x), fmin(lo.y, q.y), fmin(lo.z, q.z));
        hi = v3_make(fmax(hi.x, q.x), fmax(hi.y, q.y), fmax(hi.z, q.z));
    }
    for (uint32_t f = 0; f < nt; f++) edge += v3_dist(P(m, m->indices[3 * f]), P(m, m->indices[3 * f + 1]));
    double cs = 2.0 * edge / nt;
    size_t cap = (size_t)nt * 4, n = 0;
    cell_tri *ct = malloc(sizeof *ct * cap);
    v3 *bl = malloc(sizeof(v3) * nt), *bh = malloc(sizeof(v3) * nt);
    for (uint32_t f = 0; f < nt; f++) {
        v3 a = P(m, m->indices[3 * f]), b = P(m, m->indices[3 * f + 1]), c = P(m, m->indices[3 * f + 2]);
        bl[f] = v3_make(fmin(a.x, fmin(b.x, c.x)), fmin(a.y, fmin(b.y, c.y)), fmin(a.z, fmin(b.z, c.z)));
        bh[f] = v3_make(fmax(a.x, fmax(b.x, c.x)), fmax(a.y, fmax(b.y, c.y)), fmax(a.z, fmax(b.z, c.z)));
        int x0 = (int)((bl[f].x - lo.x) / cs), x1 = (int)((bh[f].x - lo.x) / cs);
        int y0 = (int)((bl[f].y - lo.y) / cs), y1 = (int)((bh[f].y - lo.y) / cs);
        int z0 = (int)((bl[f].z - lo.z) / cs), z1 = (int)((bh[f].z - lo.z) / cs);
        for (int x = x0; x <= x1; x++)
            for (int y = y0; y <= y1; y++)
                for (int z = z0; z <= z1; z++) {
                    if (n == cap) ct = realloc(ct, sizeof *ct * (cap *= 2));
                    ct[n++] = (cell_tri){(uint64_t)x << 42 | (uint64_t)y << 21 | (uint64_t)z, f};
                }
    }
    qsort(ct, n, sizeof *ct, cell_cmp);
    long bad = 0;
    for (size_t s = 0, e; s < n; s = e) {
        for (e = s; e < n && ct[e].cell == ct[s].cell; e++) {}
        for (size_t i = s; i < e; i++)
            for (size_t j = i + 1; j < e; j++) {
                uint32_t f = ct[i].tri, g = ct[j].tri;
                /* each pair once: in the cell of its boxes' overlap's low corner */
                v3 ol = v3_make(fmax(bl[f].x, bl[g].x), fmax(bl[f].y, bl[g].y), fmax(bl[f].z, bl[g].z));
                if (ol.x > fmin(bh[f].x, bh[g].x) || ol.y > fmin(bh[f].y, bh[g].y) || ol.z > fmin(bh[f].z, bh[g].z))
                    continue;
                uint64_t own = (uint64_t)(int)((ol.x - lo.x) / cs) << 42 | (uint64_t)(int)((ol.y - lo.y) / cs) << 21 |
                               (uint64_t)(int)((ol.z - lo.z) / cs);
                if (own != ct[s].cell) continue;
                const uint32_t *I = m->indices + 3 * (size_t)f, *J = m->indices + 3 * (size_t)g;
                int share = 0;
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) share |= id[I[a]] == id[J[b]];
                if (share) continue;
                v3 A[3] = {P(m, I[0]), P(m, I[1]), P(m, I[2])}, B[3] = {P(m, J[0]), P(m, J[1]), P(m, J[2])};
                bad += tri_tri(A, B);
            }
    }
    free(ct);
    free(bl);
    free(bh);
    return bad;
}

static int same_bytes(const banyan_mesh *a, const banyan_mesh *b) {
    if (a->vertex_count != b->vertex_count || a->index_count != b->index_count ||
        a->attribute_count != b->attribute_count)
        return 0;
    size_t nv = a->vertex_count;
    if (memcmp(a->positions, b->positions, 12 * nv) || memcmp(a->normals, b->normals, 12 * nv) ||
        memcmp(a->uvs, b->uvs, 8 * nv) || memcmp(a->colors, b->colors, 16 * nv) ||
        memcmp(a->indices, b->indices, 4 * (size_t)a->index_count))
        return 0;
    for (uint32_t i = 0; i < a->attribute_count; i++)
        if (memcmp(a->attributes[i].data, b->attributes[i].data, 4 * nv)) return 0;
    return 1;
}

typedef struct tally {
    int nets, failed;
    long edges, against, pairs, inside;
    int inward;
    double worst_clear; /* times r */
    uint64_t verts;
} tally;

/* Grows the net (boxes, or the host set when hs), meshes it fused and
 * checks every invariant; the first seed also checks same bytes and may
 * write a glb. */
static void check_net(const char *what, const banyan_roots_params *p0, const banyan_box *boxes, uint32_t n_boxes,
                      const banyan_hosts *hs, int seeds, const char *glb, tally *t) {
    for (int s = 0; s < seeds; s++) {
        banyan_roots_params p = *p0;
        p.seed = p0->seed + (uint64_t)s;
        roots_net net;
        banyan_error err;
        banyan_status st = hs ? roots_net_build_hosts(&p, hs, &net, &err) : roots_net_build(&p, boxes, n_boxes, &net, &err);
        CHECK(st == BANYAN_OK, "%s seed %llu: %s", what, (unsigned long long)p.seed, err.message);
        if (st) {
            t->failed++;
            continue;
        }
        banyan_mesh *m = NULL;
        banyan_roots_stats rs;
        memset(&rs, 0, sizeof rs);
        st = roots_net_mesh(&net, &p, &m, &rs, &err);
        CHECK(st == BANYAN_OK && m, "%s seed %llu: %s", what, (unsigned long long)p.seed, err.message);
        if (m) roots_soil_line(&net, &p, m); /* as banyan_roots_generate does */
        if (!m) {
            roots_net_free(&net);
            t->failed++;
            continue;
        }
        t->nets++;
        t->verts += m->vertex_count;
        CHECK(rs.vertices == m->vertex_count && rs.triangles == m->index_count / 3, "%s: stats", what);
        uint32_t *id = weld(m);
        long e = edge_defects(m, id), a = normals_against(m, id), x = intersecting_pairs(m, id);
        double vol = signed_volume(m);
        long inside = 0;
        double worst = HUGE_VAL;
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            double c = world_clearance_in(&net.w, P(m, v), 0, net.r, NULL, NULL) / net.r;
            if (c < worst) worst = c;
            if (c < -0.05) inside++;
        }
        CHECK(e == 0 && a == 0 && x == 0 && vol > 0 && inside == 0,
              "%s seed %llu: %ld bad edges, %ld normals against their faces, %ld intersecting face pairs, volume %g, "
              "%ld vertices inside a host (worst clearance %.3f r)",
              what, (unsigned long long)p.seed, e, a, x, vol, inside, worst);
        t->edges += e, t->against += a, t->pairs += x, t->inside += inside, t->inward += vol <= 0;
        if (worst < t->worst_clear) t->worst_clear = worst;
        CHECK(banyan_mesh_attribute(m, "root_kind") && banyan_mesh_attribute(m, "root_id") && m->colors &&
                  m->material_count == 1 && m->skel_point_count > 0 && m->skel_edge_count > 0,
              "%s: attributes, colours, material and skeleton", what);
        if (s == 0) {
            banyan_mesh *b = NULL;
            st = hs ? banyan_roots_generate(&p, hs, &b, NULL, NULL, &err)
                    : test_roots_boxes(&p, boxes, n_boxes, &b, &err);
            CHECK(st == BANYAN_OK && b && same_bytes(m, b), "%s seed %llu: not the same bytes twice", what,
                  (unsigned long long)p.seed);
            banyan_mesh_free(b);
            if (glb) {
                const banyan_mesh *list[1] = {m};
                CHECK(banyan_gltf_write(glb, (const banyan_mesh *const *)list, NULL, 1, &err) == BANYAN_OK, "%s: %s", glb, err.message);
            }
        }
        free(id);
        banyan_mesh_free(m);
        roots_net_free(&net);
    }
}

typedef struct ctx {
    const char *out;
    tally t;
} ctx;

static void box_preset(const char *path, const char *name, void *vc) {
    ctx *c = vc;
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_box hosts[8];
    uint32_t n = 0;
    banyan_error err;
    banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, &p, path, hosts, 8, &n, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (s) return;
    p.surface = BANYAN_ROOTS_FUSED; /* a preset may pick tubes; this test is about the fused surface */
    char glb[2400];
    snprintf(glb, sizeof glb, "%s/roots_fused_%s.glb", c->out ? c->out : ".", name + 6);
    tally t;
    memset(&t, 0, sizeof t);
    t.worst_clear = HUGE_VAL;
    check_net(name, &p, hosts, n, NULL, SEEDS, c->out ? glb : NULL, &t);
    printf("%-20s %d nets, %6.0f vertices avg, worst host clearance %.3f r\n", name, t.nets,
           t.nets ? (double)t.verts / t.nets : 0, t.worst_clear);
    c->t.nets += t.nets;
}

static void mesh_preset(const char *path, const char *name, void *vc) {
    ctx *c = vc;
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_error err;
    banyan_hosts *hs = NULL;
    banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, &p, path, NULL, 0, NULL, &err);
    if (!s) s = test_load_host_set(path, &hs, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (s) return;
    p.surface = BANYAN_ROOTS_FUSED;
    char glb[2400];
    snprintf(glb, sizeof glb, "%s/roots_fused_%s.glb", c->out ? c->out : ".", name + 6);
    tally t;
    memset(&t, 0, sizeof t);
    t.worst_clear = HUGE_VAL;
    check_net(name, &p, NULL, 0, hs, SEEDS, c->out ? glb : NULL, &t);
    printf("%-20s %d nets, %6.0f vertices avg, worst host clearance %.3f r\n", name, t.nets,
           t.nets ? (double)t.verts / t.nets : 0, t.worst_clear);
    c->t.nets += t.nets;
    banyan_hosts_free(hs);
}

int main(int argc, char **argv) {
    ctx c;
    memset(&c, 0, sizeof c);
    c.out = argc > 1 ? argv[1] : NULL;

    /* 1. The default net on the default trunk (0.8 m wide, 8 m tall). */
    {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        CHECK(p.surface == BANYAN_ROOTS_FUSED, "the default surface is fused");
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        char glb[2400];
        snprintf(glb, sizeof glb, "%s/roots_fused_default.glb", c.out ? c.out : ".");
        tally t;
        memset(&t, 0, sizeof t);
        t.worst_clear = HUGE_VAL;
        check_net("default", &p, &host, 1, NULL, SEEDS, c.out ? glb : NULL, &t);
        printf("%-20s %d nets, %6.0f vertices avg, worst host clearance %.3f r\n", "default", t.nets,
               t.nets ? (double)t.verts / t.nets : 0, t.worst_clear);
        CHECK(t.nets == SEEDS, "default: %d nets", t.nets);

        /* Young separate cords and an old sleeve, and no fusing at all. */
        p.maturity = 0;
        check_net("maturity 0", &p, &host, 1, NULL, 1, NULL, &t);
        p.maturity = 1;
        p.fuse_radius = 4;
        check_net("maturity 1, fuse_radius 4", &p, &host, 1, NULL, 1, NULL, &t);
        p.fuse_radius = 0;
        check_net("fuse_radius 0", &p, &host, 1, NULL, 1, NULL, &t);

        /* The finest and the coarsest voxels, on a small net. */
        banyan_roots_params_init(&p);
        p.main_roots = 3;
        p.growth_points = 12;
        p.voxel_size = 0.1;
        p.maturity = 1;
        check_net("voxel_size 0.1", &p, &host, 1, NULL, 1, NULL, &t);
        p.voxel_size = 2;
        check_net("voxel_size 2", &p, &host, 1, NULL, 2, NULL, &t);
    }

    /* 2. Every shipped roots preset, box and mesh hosts. */
    {
        int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "roots_", box_preset, &c);
        n += test_each_mesh_preset(BANYAN_SOURCE_DIR "/presets", "roots_", mesh_preset, &c);
        CHECK(n >= 5, "found %d presets/roots_*.json", n);
    }

    /* 3. max_vertices is respected: refused with BANYAN_E_LIMIT, *out NULL. */
    {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        banyan_box host = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
        banyan_mesh *m = NULL;
        banyan_error err;
        p.max_vertices = 20000;
        banyan_status s = test_roots_boxes(&p, &host, 1, &m, &err);
        CHECK(s == BANYAN_E_LIMIT && m == NULL && strstr(err.message, "max_vertices"), "limit: status %d, '%s'", s,
              err.message);
        /* One vertex short of the mesh: refused on the final count. */
        banyan_roots_params_init(&p);
        p.main_roots = 3;
        p.growth_points = 12;
        s = test_roots_boxes(&p, &host, 1, &m, &err);
        uint32_t n = m ? m->vertex_count : 0;
        banyan_mesh_free(m);
        m = NULL;
        p.max_vertices = (int32_t)n - 1;
        banyan_status s2 = test_roots_boxes(&p, &host, 1, &m, &err);
        CHECK(s == BANYAN_OK && n > 1 && s2 == BANYAN_E_LIMIT && m == NULL && strstr(err.message, "max_vertices"),
              "limit n - 1 = %u: status %d, '%s'", n - 1, s2, err.message);
        p.max_vertices = (int32_t)n;
        s2 = test_roots_boxes(&p, &host, 1, &m, &err);
        CHECK(s2 == BANYAN_OK && m && m->vertex_count == n, "limit n = %u: status %d", n, s2);
        banyan_mesh_free(m);
    }
    return check_done("test_roots_fused");
}
