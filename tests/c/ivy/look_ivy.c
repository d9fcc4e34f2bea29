/* look_ivy - the cover figures of Boston ivy on ivy_wall's front face
 * (docs/ivy.md, "How the cover is measured"), seeds 1..SEEDS:
 *   - cover: the share of rays perpendicular to the wall (2 cm grid over
 *     the face, from the front) that cross a leaf blade;
 *   - layers: the blades such a ray crosses, mean over the covered rays
 *     (and p90);
 *   - patchiness: the coefficient of variation of the leaf area over the
 *     face's 0.5 m x 0.5 m cells (a blade counts in the cell of its centre);
 *   - facing: the area-weighted median angle between the blades' triangle
 *     normals and the wall's normal (0: flat on the wall, 90: edge-on);
 *   - density: the library's branch points + crossings per m^2;
 *   - depth: how far the blades' centres stand off the wall (p10 and p90;
 *     the real leaf plane 5-15 cm) and the relief of the clumps, the
 *     standard deviation of that height averaged per 0.5 m cell;
 *   - blade size p90 (printed; the real leaves reach 17 cm);
 *   - stem ends against a stem (printed): tips that ended (Z, no
 *     continuation) within 2 internodes of another stem's bud, per m^2 of
 *     the face: the T-endings of a net; and the stem length grown
 *     alongside another stem (follow_length), m per m^2.
 * Blades are those whose centre lies in front of the face (ivy_look.h).
 *
 *   look_ivy [SEEDS] [key=value ...]   (default 5; key=value: --set on every plant)
 *   look_ivy --accept                  the bounds below over seeds 1-5; exit 1 when one fails */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ivy/ivy_internal.h"
#include "ivy_look.h"
#include "test_files.h"
#include "test_hosts.h"

#define CELL 0.02   /* ray grid, m */
#define PATCH 0.5   /* patchiness cells, m */

/* Bounds (--accept). */
#define COVER_MIN 0.9
#define LAYERS_MAX 3.5
#define CV_MIN 0.2
#define ANGLE_MIN 8.0
#define ANGLE_MAX 25.0
#define DENSITY_MIN 70.0
#define DENSITY_MAX 110.0
#define RELIEF_MIN 0.02

typedef struct figures {
    double cover, layers, layers_p90, cv, angle, density, size_p90, depth_p10, depth_p90, relief, t_ends, alongside;
    int blades;
} figures;

typedef struct wt {
    double angle, area;
} wt;

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int cmp_wt(const void *a, const void *b) { return cmp_d(&((const wt *)a)->angle, &((const wt *)b)->angle); }

/* Is (x, z) inside the triangle's xz projection? */
static int inside_xz(v3 a, v3 b, v3 c, double x, double z) {
    double d1 = (x - b.x) * (a.z - b.z) - (a.x - b.x) * (z - b.z);
    double d2 = (x - c.x) * (b.z - c.z) - (b.x - c.x) * (z - c.z);
    double d3 = (x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z);
    int neg = d1 < 0 || d2 < 0 || d3 < 0, pos = d1 > 0 || d2 > 0 || d3 > 0;
    return !(neg && pos);
}

/* The figures of one plant on the face x in [x0, x1], z in [z0, z1] at
 * y = yf, facing -y. */
static int measure(const banyan_mesh *m, double x0, double x1, double z0, double z1, double yf, figures *f) {
    uint32_t nb = 0;
    ivy_blade *bl = ivy_look_blades(m, &nb);
    if (!bl) return 1;
    const int nx = (int)((x1 - x0) / CELL + 0.5), nz = (int)((z1 - z0) / CELL + 0.5);
    const int px = (int)((x1 - x0) / PATCH + 0.5), pz = (int)((z1 - z0) / PATCH + 0.5);
    /* Blade triangles in front of the face, binned by the ray cells their xz box covers. */
    const banyan_part *lp = &m->parts[1];
    uint32_t *blade_of = malloc(sizeof(uint32_t) * (m->vertex_count ? m->vertex_count : 1));
    uint32_t *count = calloc((size_t)nx * nz + 1, sizeof(uint32_t)), *items = NULL;
    int *seen = malloc(sizeof(int) * (nb ? nb : 1));
    double *patch = calloc((size_t)px * pz, sizeof(double));
    wt *w = malloc(sizeof(wt) * (lp->index_count / 3 + 1));
    if (!blade_of || !count || !seen || !patch || !w) return 1;
    for (uint32_t k = 0; k < nb; k++)
        for (uint32_t v = bl[k].first; v < bl[k].first + bl[k].count; v++) blade_of[v] = k;
    size_t nw = 0;
    double area_sum = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3) {
            v3 a = ivy_look_vert(m, m->indices[t]), b = ivy_look_vert(m, m->indices[t + 1]),
               c = ivy_look_vert(m, m->indices[t + 2]);
            const ivy_blade *B = &bl[blade_of[m->indices[t]]];
            if (!(B->centre.y < yf)) continue;
            if (pass == 0) {
                v3 x = v3_cross(v3_sub(b, a), v3_sub(c, a));
                double ar = 0.5 * v3_len(x);
                if (ar > 0) {
                    w[nw].angle = acos(fmin(1.0, fabs(x.y) / (2 * ar))) * 180.0 / BANYAN_PI;
                    w[nw++].area = ar;
                    area_sum += ar;
                }
            }
            int i0 = (int)floor((fmin(fmin(a.x, b.x), c.x) - x0) / CELL), i1 = (int)floor((fmax(fmax(a.x, b.x), c.x) - x0) / CELL);
            int k0 = (int)floor((fmin(fmin(a.z, b.z), c.z) - z0) / CELL), k1 = (int)floor((fmax(fmax(a.z, b.z), c.z) - z0) / CELL);
            for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < nx; i++)
                for (int k = k0 < 0 ? 0 : k0; k <= k1 && k < nz; k++) {
                    size_t cell = (size_t)i * nz + k;
                    if (pass == 0) count[cell + 1]++;
                    else items[count[cell]++] = t;
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < (size_t)nx * nz; c++) count[c + 1] += count[c];
            items = malloc(sizeof(uint32_t) * (count[(size_t)nx * nz] + 1));
            if (!items) return 1;
        } else {
            for (size_t c = (size_t)nx * nz; c > 0; c--) count[c] = count[c - 1];
            count[0] = 0;
        }
    }
    /* Rays: the blades each crosses (a blade once, however many of its triangles). */
    for (uint32_t k = 0; k < nb; k++) seen[k] = -1;
    long covered = 0;
    double layer_sum = 0;
    int *layers = malloc(sizeof(int) * (size_t)nx * nz);
    if (!layers) return 1;
    for (int i = 0; i < nx; i++)
        for (int k = 0; k < nz; k++) {
            size_t cell = (size_t)i * nz + k;
            double x = x0 + (i + 0.5) * CELL, z = z0 + (k + 0.5) * CELL;
            int n = 0;
            for (uint32_t e = count[cell]; e < count[cell + 1]; e++) {
                uint32_t t = items[e], bk = blade_of[m->indices[t]];
                if (seen[bk] == (int)cell) continue;
                if (inside_xz(ivy_look_vert(m, m->indices[t]), ivy_look_vert(m, m->indices[t + 1]),
                              ivy_look_vert(m, m->indices[t + 2]), x, z)) {
                    seen[bk] = (int)cell;
                    n++;
                }
            }
            layers[cell] = n;
            if (n) covered++, layer_sum += n;
        }
    /* Patchiness: leaf area by the cell of the blade's centre. Depth: each
     * blade's centre off the face (yf is 5 cm in front of it), all of them
     * and summed per cell with the cell's count. */
    double *hc = calloc((size_t)px * pz * 2, sizeof(double)), *dp = malloc(sizeof(double) * (nb ? nb : 1));
    size_t nd = 0;
    if (!hc || !dp) return 1;
    for (uint32_t k = 0; k < nb; k++) {
        const ivy_blade *B = &bl[k];
        if (!(B->centre.y < yf)) continue;
        double d = yf - 0.05 - B->centre.y;
        dp[nd++] = d;
        int i = (int)floor((B->centre.x - x0) / PATCH), j = (int)floor((B->centre.z - z0) / PATCH);
        if (i >= 0 && i < px && j >= 0 && j < pz) {
            size_t c = (size_t)i * pz + j;
            patch[c] += B->area;
            hc[2 * c] += d, hc[2 * c + 1] += 1;
        }
        f->blades++;
    }
    if (nd) qsort(dp, nd, sizeof(double), cmp_d);
    f->depth_p10 = nd ? dp[(size_t)(0.1 * (double)(nd - 1) + 0.5)] : 0;
    f->depth_p90 = nd ? dp[(size_t)(0.9 * (double)(nd - 1) + 0.5)] : 0;
    double hm = 0, hv = 0;
    int hn = 0;
    for (int c = 0; c < px * pz; c++)
        if (hc[2 * c + 1] > 0) hm += hc[2 * c] / hc[2 * c + 1], hn++;
    hm = hn ? hm / hn : 0;
    for (int c = 0; c < px * pz; c++)
        if (hc[2 * c + 1] > 0) hv += (hc[2 * c] / hc[2 * c + 1] - hm) * (hc[2 * c] / hc[2 * c + 1] - hm);
    f->relief = hn ? sqrt(hv / hn) : 0;
    free(hc), free(dp);
    double *sz = malloc(sizeof(double) * (nb ? nb : 1));
    size_t ns = 0;
    for (uint32_t k = 0; k < nb && sz; k++)
        if (bl[k].centre.y < yf) sz[ns++] = bl[k].size;
    if (sz && ns) qsort(sz, ns, sizeof(double), cmp_d);
    f->size_p90 = sz && ns ? sz[(size_t)(0.9 * (double)(ns - 1) + 0.5)] : 0;
    free(sz);
    double mean = 0, var = 0;
    for (int c = 0; c < px * pz; c++) mean += patch[c] / (px * pz);
    for (int c = 0; c < px * pz; c++) var += (patch[c] - mean) * (patch[c] - mean) / (px * pz);
    /* The area-weighted median angle. */
    qsort(w, nw, sizeof(wt), cmp_wt);
    double acc = 0;
    f->angle = NAN;
    for (size_t e = 0; e < nw; e++)
        if ((acc += w[e].area) >= 0.5 * area_sum) {
            f->angle = w[e].angle;
            break;
        }
    double *lv = malloc(sizeof(double) * (size_t)(covered ? covered : 1));
    size_t nl = 0;
    for (size_t c = 0; c < (size_t)nx * nz && lv; c++)
        if (layers[c]) lv[nl++] = layers[c];
    if (lv && nl) qsort(lv, nl, sizeof(double), cmp_d);
    f->cover = (double)covered / ((double)nx * nz);
    f->layers = covered ? layer_sum / covered : 0;
    f->layers_p90 = lv && nl ? lv[(size_t)(0.9 * (double)(nl - 1) + 0.5)] : 0;
    f->cv = mean > 0 ? sqrt(var) / mean : 0;
    free(lv), free(layers), free(items), free(w), free(patch), free(seen), free(count), free(blade_of), free(bl);
    return 0;
}

/* Stem ends against a stem and length grown alongside (see the top),
 * per m^2 of `area`. Buds are bucketed in cells of 2 internodes, sorted
 * by cell. */
typedef struct cell_bud {
    int64_t key;
    int32_t i;
} cell_bud;

static int cmp_cb(const void *a, const void *b) {
    const cell_bud *x = a, *y = b;
    return (x->key > y->key) - (x->key < y->key);
}

static int64_t cell_key(int64_t x, int64_t y, int64_t z) { return ((x + 100000) * 200000 + (y + 100000)) * 200000 + z + 100000; }

static int stem_ends(const banyan_ivy *iv, double area, figures *f) {
    const double h = 2 * iv->p.internode;
    cell_bud *cb = malloc(sizeof *cb * ((size_t)iv->n + 1));
    if (!cb) return 1;
    for (int32_t i = 0; i < iv->n; i++) {
        v3 P = iv->buds[i].P;
        cb[i].key = cell_key((int64_t)floor(P.x / h), (int64_t)floor(P.y / h), (int64_t)floor(P.z / h));
        cb[i].i = i;
    }
    qsort(cb, (size_t)iv->n, sizeof *cb, cmp_cb);
    int32_t ends = 0, along = 0;
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        along += b->follow > 0;
        if (b->state != BANYAN_IVY_Z || b->child[0] >= 0 || b->parent < 0) continue;
        int64_t cx = (int64_t)floor(b->P.x / h), cy = (int64_t)floor(b->P.y / h), cz = (int64_t)floor(b->P.z / h);
        int near = 0;
        for (int d = 0; d < 27 && !near; d++) {
            cell_bud k = {cell_key(cx + d % 3 - 1, cy + d / 3 % 3 - 1, cz + d / 9 - 1), 0};
            size_t lo = 0, hi = (size_t)iv->n;
            while (lo < hi) { /* the first entry of the cell */
                size_t mid = (lo + hi) / 2;
                if (cb[mid].key < k.key) lo = mid + 1;
                else hi = mid;
            }
            for (size_t q = lo; q < (size_t)iv->n && cb[q].key == k.key && !near; q++) {
                const int32_t j = cb[q].i;
                const ivy_bud *c = &iv->buds[j];
                if (j == i || j == b->parent || c->parent == b->parent || c->parent == i) continue;
                /* Not its own stem: neither of the two buds is within 3 internodes up the other's line. */
                int own = 0;
                for (int32_t u = b->parent, s = 0; u >= 0 && s < 3 && !own; u = iv->buds[u].parent, s++) own = u == j;
                for (int32_t u = c->parent, s = 0; u >= 0 && s < 3 && !own; u = iv->buds[u].parent, s++) own = u == i;
                near = !own && v3_dist(c->P, b->P) < h;
            }
        }
        ends += near;
    }
    free(cb);
    f->t_ends = ends / area;
    f->alongside = along * iv->p.internode / area;
    return 0;
}

int main(int argc, char **argv) {
    int accept = argc > 1 && !strcmp(argv[1], "--accept");
    int seeds = accept ? 5 : argc > 1 ? atoi(argv[1]) : 5;
    banyan_ivy_params base;
    banyan_box hosts[8];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    if (ivy_look_preset("ivy_wall", &base, hosts, 8, &nh, &err) != BANYAN_OK || nh < 1)
        return fprintf(stderr, "ivy_wall: %s\n", err.message), 1;
    if (!accept && test_param_overrides(BANYAN_GEN_IVY, &base, 2, argc, argv)) return 1;
    /* The wall's front face (-y): the first host, an axis-aligned box. */
    const banyan_box *W = &hosts[0];
    const double x0 = W->center[0] - W->half[0], x1 = W->center[0] + W->half[0];
    const double z0 = W->center[2] - W->half[2], z1 = W->center[2] + W->half[2], yf = W->center[1] - W->half[1] + 0.05;
    printf("| seed | blades | cover | mean layers | layers p90 | CV per %.1f m cell | median angle to the wall, deg | "
           "density /m^2 | blade size p90, m | depth p10-p90, m | relief, m | stem ends at a stem /m^2 | grown alongside, "
           "m/m^2 |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n", PATCH);
    figures all = {0};
    int fails = 0;
    banyan_hosts *H = TEST_HOSTS(hosts, nh);
    for (int s = 1; s <= seeds; s++) {
        banyan_ivy_params p = base;
        p.seed = (uint64_t)s;
        banyan_ivy *iv = NULL;
        banyan_mesh *m = NULL;
        banyan_ivy_stats st;
        if (banyan_ivy_create(&p, H, &iv, &err) || banyan_ivy_step(iv, p.steps, &err) ||
            banyan_ivy_get_stats(iv, &st, &err) || banyan_ivy_mesh(iv, &m, &err))
            return fprintf(stderr, "seed %d: %s\n", s, err.message), 1;
        figures f = {0};
        if (measure(m, x0, x1, z0, z1, yf, &f)) return fprintf(stderr, "seed %d: out of memory\n", s), 1;
        f.density = st.density;
        if (stem_ends(iv, (x1 - x0) * (z1 - z0), &f)) return fprintf(stderr, "seed %d: out of memory\n", s), 1;
        printf("| %d | %d | %.3f | %.2f | %.0f | %.2f | %.1f | %.1f | %.3f | %.3f-%.3f | %.3f | %.1f | %.2f |\n", s, f.blades,
               f.cover, f.layers, f.layers_p90, f.cv, f.angle, f.density, f.size_p90, f.depth_p10, f.depth_p90, f.relief,
               f.t_ends, f.alongside);
        all.cover += f.cover / seeds, all.layers += f.layers / seeds, all.cv += f.cv / seeds;
        all.angle += f.angle / seeds, all.density += f.density / seeds, all.relief += f.relief / seeds;
        if (accept) {
            int bad = f.cover < COVER_MIN || f.layers > LAYERS_MAX || f.cv < CV_MIN || !(f.angle >= ANGLE_MIN) ||
                      !(f.angle <= ANGLE_MAX) || f.density < DENSITY_MIN || f.density > DENSITY_MAX || f.relief < RELIEF_MIN;
            if (bad) printf("seed %d outside the bounds\n", s);
            fails += bad;
        }
        banyan_mesh_free(m);
        banyan_ivy_free(iv);
    }
    banyan_hosts_free(H);
    printf("mean over %d seeds: cover %.3f, layers %.2f, CV %.2f, median angle %.1f deg, density %.1f /m^2, relief %.3f m\n",
           seeds, all.cover, all.layers, all.cv, all.angle, all.density, all.relief);
    if (accept) {
        printf("bounds: cover >= %.2f, mean layers <= %.1f, CV >= %.2f, median angle %.0f-%.0f deg, density %.0f-%.0f, "
               "relief >= %.2f m\n",
               COVER_MIN, LAYERS_MAX, CV_MIN, ANGLE_MIN, ANGLE_MAX, DENSITY_MIN, DENSITY_MAX, RELIEF_MIN);
        printf("%s: %d seeds outside the bounds\n", fails ? "NOT ACCEPTED" : "ACCEPTED", fails);
    }
    return fails ? 1 : 0;
}
