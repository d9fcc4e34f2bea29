/* The look of a real strangler fig (docs/roots.md "The look of
 * a real fig"), measured in tube mode on the default net (the CLI's
 * trunk) and on every presets/roots_*.json, 5 seeds each:
 *   - roots stay near the host: of the root vertices above the ground
 *     (z > ground_z + 1 cm), the 95th percentile of the horizontal distance
 *     beyond the hosts' footprint (the XY box of their world bounds, 0
 *     inside) is at most half the footprint's diagonal;
 *   - every shipped preset touches the ground (some main root enters it);
 *   - the pipe model: every main root that enters the soil is thicker
 *     there than at its tip (the thin end at G); a net with maturity 1 has
 *     thicker main roots than the same net with maturity 0;
 *   - tubes: under 0.5 % of triangles wound against their vertex normals;
 *   - no root vertex inside a host; the skeleton is one connected graph;
 *   - branch roots lie on the host: within hug range, no branch point
 *     stands farther than 1.5 r off it (up to 2 %, where a point cannot
 *     be pulled in free). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_checks.h"
#include "roots/roots_internal.h"
#include "test_files.h"

typedef struct look {
    double p95, diag;   /* m */
    int mains, entering, thin_entries;
    long tris, folded, inside, branch_pts, tents;
    int pieces;
    double mean_main_rad; /* m */
} look;

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void measure(const roots_net *net, const banyan_roots_params *p, const banyan_mesh *m, look *L) {
    const banyan_hosts *H = net->hosts;
    uint32_t nh = H->n_boxes + H->n_meshes;
    double lx = 1e300, ly = 1e300, hx = -1e300, hy = -1e300;
    for (uint32_t h = 0; h < nh; h++) {
        if (H->lo[h].x < lx) lx = H->lo[h].x;
        if (H->lo[h].y < ly) ly = H->lo[h].y;
        if (H->hi[h].x > hx) hx = H->hi[h].x;
        if (H->hi[h].y > hy) hy = H->hi[h].y;
    }
    L->diag = hypot(hx - lx, hy - ly);
    double *d = malloc(sizeof(double) * (m->vertex_count ? m->vertex_count : 1));
    uint32_t k = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *q = m->positions + 3 * (size_t)v;
        if (q[2] > p->ground_z + 0.01) {
            double dx = q[0] < lx ? lx - q[0] : (q[0] > hx ? q[0] - hx : 0);
            double dy = q[1] < ly ? ly - q[1] : (q[1] > hy ? q[1] - hy : 0);
            d[k++] = hypot(dx, dy);
        }
        /* inside a host (0.1 mm for float storage) */
        if (world_clearance_in(&net->w, v3_make(q[0], q[1], q[2]), 0, net->r, NULL, NULL) < -1e-4) L->inside++;
    }
    qsort(d, k, sizeof(double), cmp_d);
    L->p95 = k ? d[(size_t)(0.95 * (k - 1))] : 0;
    free(d);
    double rsum = 0;
    long rn = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        const double *R = net->rad + pl->off;
        if (pl->kind == ROOT_MAIN) {
            L->mains++;
            for (uint32_t i = 0; i < pl->n; i++) rsum += R[i], rn++;
            if (pl->soil_from < pl->n) {
                L->entering++;
                if (!(R[pl->soil_from - 1] > R[0])) L->thin_entries++;
            }
        } else if (p->hugging && pl->kind != ROOT_FOOT && pl->kind != ROOT_AERIAL) { /* planks, surface roots and
                                                                                       hanging roots stand out on purpose */
            for (uint32_t i = 1; i + 1 < pl->n; i++) {
                v3 n;
                int which;
                double c = world_clearance_in(&net->w, net->pts[pl->off + i], 0, p->hug_range * net->r, &n, &which);
                L->branch_pts++;
                if (which >= 0 && c > 1.5 * net->r * (1 + 1e-6) && c < p->hug_range * net->r) L->tents++;
            }
        }
    }
    L->mean_main_rad = rn ? rsum / rn : 0;
    for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
        const uint32_t *I = m->indices + i;
        const float *a = m->positions + 3 * (size_t)I[0], *b = m->positions + 3 * (size_t)I[1],
                    *c = m->positions + 3 * (size_t)I[2];
        double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2], wx = c[0] - a[0], wy = c[1] - a[1],
               wz = c[2] - a[2];
        double fx = uy * wz - uz * wy, fy = uz * wx - ux * wz, fz = ux * wy - uy * wx;
        const float *na = m->normals + 3 * (size_t)I[0], *nb = m->normals + 3 * (size_t)I[1],
                    *nc = m->normals + 3 * (size_t)I[2];
        double dot = fx * (na[0] + nb[0] + nc[0]) + fy * (na[1] + nb[1] + nc[1]) + fz * (na[2] + nb[2] + nc[2]);
        L->tris++;
        if (sqrt(fx * fx + fy * fy + fz * fz) > 1e-12 && dot <= 0) L->folded++;
    }
    L->pieces = mc_skeleton_pieces(m);
}

/* One net in tube mode: 0 on failure. */
static int grow(const banyan_roots_params *p0, const banyan_hosts *H, const banyan_box *box, look *L) {
    banyan_roots_params p = *p0;
    p.surface = BANYAN_ROOTS_TUBES;
    roots_net net;
    banyan_error err;
    banyan_status s = H ? roots_net_build_hosts(&p, H, &net, &err) : roots_net_build(&p, box, 1, &net, &err);
    CHECK(s == BANYAN_OK, "seed %llu: %s", (unsigned long long)p.seed, err.message);
    if (s) return 0;
    banyan_mesh *m = NULL;
    banyan_roots_stats st = net.stats;
    s = roots_net_mesh(&net, &p, &m, &st, &err);
    CHECK(s == BANYAN_OK, "seed %llu mesh: %s", (unsigned long long)p.seed, err.message);
    memset(L, 0, sizeof *L);
    if (!s) measure(&net, &p, m, L);
    banyan_mesh_free(m);
    roots_net_free(&net);
    return s == BANYAN_OK;
}

static void judge(const char *name, const banyan_roots_params *p0, const banyan_hosts *H, const banyan_box *box) {
    double worst_ratio = 0;
    long tris = 0, folded = 0, inside = 0, bpts = 0, tents = 0;
    int entering = 0, thin = 0, mains = 0, pieces_bad = 0, nets = 0;
    for (uint64_t s = 0; s < 5; s++) {
        banyan_roots_params p = *p0;
        p.seed = p0->seed + s * 101;
        look L;
        if (!grow(&p, H, box, &L)) continue;
        nets++;
        double ratio = L.p95 / L.diag;
        if (ratio > worst_ratio) worst_ratio = ratio;
        tris += L.tris, folded += L.folded, inside += L.inside, bpts += L.branch_pts, tents += L.tents;
        entering += L.entering, thin += L.thin_entries, mains += L.mains;
        if (L.pieces != 1) pieces_bad++;
    }
    printf("%-18s p95 beyond footprint <= %.3f x diagonal; mains entering the soil %d of %d (%d not thicker there); "
           "folded %ld of %ld (%.3f %%); inside %ld; branch points standing off %ld of %ld\n",
           name, worst_ratio, entering, mains, thin, folded, tris, tris ? 100.0 * folded / tris : 0.0, inside, tents,
           bpts);
    CHECK(nets == 5, "%s: %d of 5 nets", name, nets);
    CHECK(worst_ratio <= 0.5, "%s: p95 of the horizontal distance beyond the footprint is %.3f x its diagonal",
          name, worst_ratio);
    CHECK(entering > 0, "%s: no main root enters the soil in 5 seeds", name);
    CHECK(thin == 0, "%s: %d main roots not thicker where they enter the ground than at their tip", name, thin);
    CHECK(folded * 200 < tris, "%s: %ld of %ld tube triangles folded against their normals", name, folded, tris);
    CHECK(inside == 0, "%s: %ld root vertices inside a host", name, inside);
    CHECK(pieces_bad == 0, "%s: %d nets not connected", name, pieces_bad);
    CHECK(tents * 50 <= bpts, "%s: %ld of %ld branch points stand off the host", name, tents, bpts);
}

static void preset(const char *path, const char *name, void *ctx) {
    (void)ctx;
    banyan_roots_params p;
    banyan_error err;
    banyan_hosts *H = NULL;
    banyan_status s = test_load_roots(path, &p, &H, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    if (!s) judge(name, &p, H, NULL);
    banyan_hosts_free(H);
}

int main(void) {
    /* The default net: default params on the CLI's trunk. */
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    judge("default", &p, NULL, &trunk);

    /* Maturity thickens: the same net, young and old. */
    banyan_roots_params y = p, o = p;
    y.maturity = 0;
    o.maturity = 1;
    look Ly, Lo;
    if (grow(&y, NULL, &trunk, &Ly) && grow(&o, NULL, &trunk, &Lo)) {
        printf("mean main-root radius: maturity 0 %.4f m, maturity 1 %.4f m (r = %.4f m)\n", Ly.mean_main_rad,
               Lo.mean_main_rad, p.radius * p.unit);
        CHECK(Lo.mean_main_rad > 1.5 * Ly.mean_main_rad, "maturity 1 main roots (%.4f m) not clearly thicker than "
              "maturity 0 (%.4f m)", Lo.mean_main_rad, Ly.mean_main_rad);
        CHECK(Ly.mean_main_rad < 1.3 * p.radius * p.unit, "maturity 0 main roots %.4f m: not cords of about r",
              Ly.mean_main_rad);
    }

    int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "roots_", preset, NULL);
    n += test_each_mesh_preset(BANYAN_SOURCE_DIR "/presets", "roots_", preset, NULL);
    CHECK(n >= 7, "found %d presets/roots_*.json", n);
    return check_done("test_roots_look");
}
