/* The ivy's look (docs/ivy.md "Stem architecture", "How the
 * look is measured", "Geometry"; reference/plants.md section 2) on the
 * presets ivy_wall and ivy_pillar, seeds 1..5, at their 450 steps.
 * Stems:
 *   - they fan out: of the attached stem length on the faces facing the
 *     wall's front (-y), at most 35 % within 15 deg of vertical and 55 %
 *     within 30 deg;
 *   - the ground is crossed, not carpeted (ivy_wall): at most 3 % of the
 *     leaf area grows from buds lying nearer the ground than any host;
 *   - density (branch points + crossings per m^2 of covered face) within
 *     [70, 110] on ivy_wall at the default t0 (the real wall: about 88);
 *     that it rises with t0 is test_ivy_density's.
 * Leaves (blades: connected components of the leaf part), every bud
 * leafed but where old wood sheds (leaf_share 1, no clumps: look_ivy
 * measures the cover they make):
 *   (a) they face out, tilted a little: the median angle between a
 *       blade's normal and the nearest host surface's normal at its centre
 *       is 8-25 deg, and 9 in 10 lie within 45 deg of it (blades nearest
 *       the ground left out, as in (b));
 *   (b) they stand off on petioles: the median distance of blade centres
 *       from the nearest host is at least 4 cm (real 5-15 cm);
 *   (c) sizes vary with age: size p90 / p10 >= 2, p10 >= 4 cm, p90 <= 22 cm;
 * and no blade vertex closer than `clearance` to a host or the ground, no
 * blade triangle (edge midpoints, centroid) or petiole vertex inside one,
 * every normal unit length. Every figure is printed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy_look.h"
#include "test_files.h"
#include "test_hosts.h"

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double quantile(double *v, size_t n, double q) {
    if (!n) return NAN;
    qsort(v, n, sizeof(double), cmp_d);
    return v[(size_t)(q * (double)(n - 1) + 0.5)];
}

typedef struct figures {
    ivy_stem_angles stem;
    double leaf_area, ground_area, density, leafed;
    double *cosv, *dist, *size;
    size_t ncos, nsize, cap;
    int blades, buds, near_host, inside, tri_inside, pet_inside, bad_normal, base_off;
} figures;

/* The leaves the plant's wood keeps (ivy_wood_leaf_shares: old wood
 * sheds its own; a stem grown alongside another keeps IVY_FOLLOW_LEAF of
 * them): the blades expected with every bud leafed. */
static double wood_keeps(const banyan_ivy *iv) {
    double *r = malloc(sizeof(double) * ((size_t)iv->n + 1)), *share = malloc(sizeof(double) * ((size_t)iv->n + 1)), sum = 0;
    v3 *P = malloc(sizeof(v3) * ((size_t)iv->n + 1));
    if (r && share && P && ivy_wood(iv, r, P) == BANYAN_OK) {
        ivy_wood_leaf_shares(iv, r, share);
        for (int32_t i = 0; i < iv->n; i++) sum += share[i] * (iv->buds[i].follow > 0 ? IVY_FOLLOW_LEAF : 1.0);
    }
    free(r);
    free(share);
    free(P);
    return sum;
}

static int push(figures *f, size_t more) {
    if (f->nsize + more <= f->cap) return 1;
    f->cap = 2 * (f->nsize + more);
    double *a = realloc(f->cosv, sizeof(double) * f->cap), *b = a ? realloc(f->dist, sizeof(double) * f->cap) : NULL,
           *c = b ? realloc(f->size, sizeof(double) * f->cap) : NULL;
    if (a) f->cosv = a;
    if (b) f->dist = b;
    if (c) f->size = c;
    return a && b && c;
}

/* The leaf measures of one plant's mesh into f. */
static void measure_leaves(const banyan_ivy *iv, const banyan_mesh *m, figures *f) {
    const int has_ground = iv->n_hosts > iv->n_given;
    uint32_t nb = 0;
    ivy_blade *bl = ivy_look_blades(m, &nb);
    CHECK(bl != NULL, "no leaf blades");
    if (!bl || !push(f, nb)) {
        free(bl);
        return;
    }
    for (uint32_t k = 0; k < nb; k++) {
        const ivy_blade *b = &bl[k];
        f->size[f->nsize++] = b->size;
        f->leaf_area += b->area;
        /* The bud a blade grows from: its petiole's foot. */
        ivy_near at = ivy_nearest_any(iv, b->base);
        if (has_ground && at.host == (int32_t)iv->n_given) f->ground_area += b->area;
        if (!ivy_shade(iv, b->base, -1, 0.5, NULL)) f->base_off++; /* no bud within d_max of the foot */
        for (uint32_t v = b->first; v < b->first + b->count; v++) {
            double d = ivy_nearest_any(iv, ivy_look_vert(m, v)).dist;
            if (d < iv->p.clearance - 1e-5) f->near_host++;
            if (d < 0) f->inside++;
        }
        ivy_near any = ivy_nearest_any(iv, b->centre);
        if (!(has_ground && any.host == (int32_t)iv->n_given)) {
            ivy_near h = ivy_nearest_of(iv, b->centre, iv->n_given);
            f->cosv[f->ncos] = fabs(v3_dot(b->normal, h.normal));
            f->dist[f->ncos++] = h.dist;
        }
    }
    /* Triangles too: a blade over a box's edge can have every vertex
     * outside and a triangle through it. */
    const banyan_part *lp = &m->parts[1], *sp = &m->parts[0];
    for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3) {
        v3 a = ivy_look_vert(m, m->indices[t]), b = ivy_look_vert(m, m->indices[t + 1]), c = ivy_look_vert(m, m->indices[t + 2]);
        v3 q[4] = {v3_lerp(a, b, 0.5), v3_lerp(b, c, 0.5), v3_lerp(c, a, 0.5), v3_scale(v3_add(v3_add(a, b), c), 1.0 / 3)};
        for (int j = 0; j < 4; j++)
            if (ivy_nearest_any(iv, q[j]).dist < 0) f->tri_inside++;
    }
    uint32_t np = IVY_LOOK_PETIOLE_VERTS * nb;
    CHECK(sp->vertex_count > np, "part 0 has %u vertices, fewer than %u petiole vertices", sp->vertex_count, np);
    for (uint32_t v = sp->vertex_offset + sp->vertex_count - np; v < sp->vertex_offset + sp->vertex_count; v++)
        if (ivy_nearest_any(iv, ivy_look_vert(m, v)).dist < 0) f->pet_inside++;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *n = m->normals + 3 * v;
        if (fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-4) f->bad_normal++;
    }
    f->blades += (int)nb;
    free(bl);
}

int main(void) {
    const char *names[2] = {"ivy_wall", "ivy_pillar"};
    for (int pi = 0; pi < 2; pi++) {
        banyan_ivy_params base;
        banyan_box hosts[8];
        uint32_t nh = 0;
        banyan_error err = {0, ""};
        if (ivy_look_preset(names[pi], &base, hosts, 8, &nh, &err) != BANYAN_OK) {
            CHECK(0, "%s: %s", names[pi], err.message);
            continue;
        }
        base.leaf_share = 1;
        base.leaf_clump = 0;
        figures f;
        memset(&f, 0, sizeof f);
        banyan_hosts *H = TEST_HOSTS(hosts, nh);
        for (uint64_t seed = 1; seed <= 5; seed++) {
            banyan_ivy_params p = base;
            p.seed = seed;
            banyan_ivy *iv = NULL;
            banyan_mesh *m = NULL;
            banyan_ivy_stats st;
            memset(&st, 0, sizeof st);
            if (banyan_ivy_create(&p, H, &iv, &err) != BANYAN_OK || banyan_ivy_step(iv, p.steps, &err) != BANYAN_OK ||
                banyan_ivy_get_stats(iv, &st, &err) != BANYAN_OK || banyan_ivy_mesh(iv, &m, &err) != BANYAN_OK) {
                CHECK(0, "%s seed %llu: %s", names[pi], (unsigned long long)seed, err.message);
                banyan_mesh_free(m);
                banyan_ivy_free(iv);
                continue;
            }
            ivy_stem_angles a = ivy_look_stem_angles(iv, v3_make(0, -1, 0));
            double g0 = f.ground_area, l0 = f.leaf_area;
            measure_leaves(iv, m, &f);
            printf("%s seed %llu: %d buds; front stem %.1f m, within 15 deg %.1f %%, within 30 deg %.1f %%; leaf area "
                   "on the ground %.2f %%; density %.1f /m^2 (%d branch points, %d crossings, %.1f m^2)\n",
                   names[pi], (unsigned long long)seed, st.buds, a.length, 100 * a.within15 / a.length,
                   100 * a.within30 / a.length, 100 * (f.ground_area - g0) / (f.leaf_area - l0), st.density,
                   st.branch_points, st.crossings, st.covered_area);
            f.stem.length += a.length;
            f.stem.within15 += a.within15;
            f.stem.within30 += a.within30;
            f.density += st.density / 5;
            f.buds += iv->n;
            f.leafed += wood_keeps(iv);
            banyan_mesh_free(m);
            banyan_ivy_free(iv);
        }
        banyan_hosts_free(H);
        const double L = f.stem.length, ground = f.leaf_area > 0 ? f.ground_area / f.leaf_area : 1;
        /* |cos| falls as the angle grows: its median is the angle's, its
         * 10th percentile the angle's 90th. */
        const double a50 = acos(quantile(f.cosv, f.ncos, 0.5)) * 180 / BANYAN_PI;
        const double a90 = acos(quantile(f.cosv, f.ncos, 0.1)) * 180 / BANYAN_PI, dmed = quantile(f.dist, f.ncos, 0.5);
        const double s10 = quantile(f.size, f.nsize, 0.1), s90 = quantile(f.size, f.nsize, 0.9);
        printf("%s, 5 seeds: within 15 deg %.1f %%, within 30 deg %.1f %%; leaf area on the ground %.2f %%; mean "
               "density %.1f /m^2\n",
               names[pi], 100 * f.stem.within15 / L, 100 * f.stem.within30 / L, 100 * ground, f.density);
        printf("%s, 5 seeds: %d buds, %d blades (%zu off a host face): angle to the host normal median %.1f, p90 %.1f deg; centre "
               "distance median %.3f m; size p10 %.3f p90 %.3f m (ratio %.2f); %d blade vertices within clearance, "
               "%d inside, %d triangle points inside, %d petiole vertices inside, %d normals not unit, %d petioles "
               "not at a bud\n",
               names[pi], f.buds, f.blades, f.ncos, a50, a90, dmed, s10, s90, s90 / s10, f.near_host, f.inside,
               f.tri_inside, f.pet_inside, f.bad_normal, f.base_off);
        CHECK(L > 1.0, "%s: only %.2f m of attached stem on the front faces", names[pi], L);
        CHECK(f.stem.within15 <= 0.35 * L, "%s: %.1f %% of the front stem length within 15 deg of vertical (<= 35 %%)",
              names[pi], 100 * f.stem.within15 / L);
        CHECK(f.stem.within30 <= 0.55 * L, "%s: %.1f %% of the front stem length within 30 deg of vertical (<= 55 %%)",
              names[pi], 100 * f.stem.within30 / L);
        if (pi == 0) {
            CHECK(ground <= 0.03, "%s: %.2f %% of the leaf area on the ground (<= 3 %%)", names[pi], 100 * ground);
            CHECK(f.density >= 70 && f.density <= 110, "%s: mean density %.1f per m^2 not within [70, 110]", names[pi],
                  f.density);
        }
        CHECK(f.blades > 1000 && f.ncos > 500 && f.blades >= 0.99 * f.leafed,
              "%s: %d blades for %d buds (%.0f whose wood keeps its leaf), %zu off a host face", names[pi], f.blades,
              f.buds, f.leafed, f.ncos);
        CHECK(f.base_off == 0, "%s: %d petioles whose foot is not at a bud", names[pi], f.base_off);
        CHECK(a50 >= 8 && a50 <= 25, "%s: median blade angle to the host normal %.1f deg, not 8-25", names[pi], a50);
        CHECK(a90 <= 45, "%s: p90 blade angle to the host normal %.1f deg > 45 (edge-on)", names[pi], a90);
        CHECK(dmed >= 0.04, "%s: median blade centre %.3f m off the host, under 4 cm", names[pi], dmed);
        CHECK(s90 / s10 >= 2, "%s: blade size p90 / p10 = %.2f < 2", names[pi], s90 / s10);
        CHECK(s10 >= 0.04 && s90 <= 0.22, "%s: blade sizes p10 %.3f p90 %.3f m outside 4-22 cm", names[pi], s10, s90);
        CHECK(f.near_host == 0 && f.inside == 0, "%s: %d blade vertices within clearance of a host, %d inside", names[pi],
              f.near_host, f.inside);
        CHECK(f.tri_inside == 0, "%s: %d triangle edge midpoints or centroids of blades inside a host", names[pi],
              f.tri_inside);
        CHECK(f.pet_inside == 0, "%s: %d petiole vertices inside a host or the ground", names[pi], f.pet_inside);
        CHECK(f.bad_normal == 0, "%s: %d normals not unit length", names[pi], f.bad_normal);
        free(f.cosv);
        free(f.dist);
        free(f.size);
    }
    return check_done("test_ivy_look");
}
