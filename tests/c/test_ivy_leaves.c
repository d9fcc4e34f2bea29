/* Ivy leaves as the real plant shows them (issue #19; docs/ivy.md,
 * "Geometry"; reference plants.md section 2), measured from the mesh of
 * presets ivy_wall and ivy_pillar, 450 steps, seeds 1..5. Blades are the
 * connected components of the leaf part's triangles.
 *   (a) Blades tilt off the wall: the 90th percentile of |cos| between a
 *       blade's normal (area-weighted, from positions) and the normal of
 *       the nearest host surface at its centre is at most 0.97 (blades
 *       whose nearest surface is the ground left out, as in (b)).
 *   (b) Blades stand off on petioles: the median distance of blade centres
 *       from the nearest host surface is at least 4 cm (real 5-15 cm).
 *   (c) Sizes vary with age: blade size (largest vertex-to-vertex
 *       distance) p90 / p10 >= 2, p10 >= 4 cm, p90 <= 22 cm.
 * And: no blade vertex closer than `clearance` to a host or the ground, no
 * petiole vertex inside one (petioles are the last part-0 vertices, one
 * per blade), every normal unit length. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy/ivy_internal.h"
#include "test_files.h"

#define PETIOLE_VERTS 6 /* 3 sides x 2 rings (mesh.c) */

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double quantile(double *v, size_t n, double q) {
    if (!n) return NAN;
    qsort(v, n, sizeof(double), cmp_d);
    size_t k = (size_t)(q * (double)(n - 1) + 0.5);
    return v[k];
}

static uint32_t find(uint32_t *up, uint32_t a) {
    while (up[a] != a) a = up[a] = up[up[a]];
    return a;
}

static v3 vert(const banyan_mesh *m, uint32_t v) {
    return v3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
}

typedef struct figures {
    double *cosv, *dist, *size;
    size_t ncos, nsize;
    int near_host, inside, tri_inside, pet_inside, bad_normal, blades, buds;
} figures;

/* Measures one plant's mesh into f (arrays grown by the caller's bound). */
static void measure(const banyan_ivy *iv, const banyan_mesh *m, figures *f) {
    const banyan_part *lp = &m->parts[1], *sp = &m->parts[0];
    uint32_t v0 = lp->vertex_offset, nv = lp->vertex_count;
    uint32_t *up = malloc(sizeof(uint32_t) * nv);
    for (uint32_t k = 0; k < nv; k++) up[k] = k;
    for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3)
        for (int e = 1; e < 3; e++) {
            uint32_t a = find(up, m->indices[t] - v0), b = find(up, m->indices[t + e] - v0);
            if (a != b) up[a] = b;
        }
    /* Components: vertices of one blade are consecutive (mesh.c); walk runs of one root. */
    v3 *nsum = calloc(nv, sizeof(v3));
    for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3) {
        v3 a = vert(m, m->indices[t]), b = vert(m, m->indices[t + 1]), c = vert(m, m->indices[t + 2]);
        uint32_t r = find(up, m->indices[t] - v0);
        nsum[r] = v3_add(nsum[r], v3_cross(v3_sub(b, a), v3_sub(c, a)));
    }
    /* Triangles too: edge midpoints and centroids (a blade over a box's
     * edge can have every vertex outside and a triangle through it). */
    for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3) {
        v3 a = vert(m, m->indices[t]), b = vert(m, m->indices[t + 1]), c = vert(m, m->indices[t + 2]);
        v3 q[4] = {v3_lerp(a, b, 0.5), v3_lerp(b, c, 0.5), v3_lerp(c, a, 0.5),
                   v3_scale(v3_add(v3_add(a, b), c), 1.0 / 3)};
        for (int j = 0; j < 4; j++)
            if (ivy_nearest_any(iv, q[j]).dist < 0) f->tri_inside++;
    }
    int blades = 0;
    for (uint32_t s = 0; s < nv;) {
        uint32_t r = find(up, s), e = s;
        while (e < nv && find(up, e) == r) e++;
        blades++;
        v3 c = v3_make(0, 0, 0);
        double big = 0;
        for (uint32_t k = s; k < e; k++) {
            v3 q = vert(m, v0 + k);
            c = v3_add(c, q);
            for (uint32_t j = k + 1; j < e; j++) {
                double d = v3_dist(q, vert(m, v0 + j));
                if (d > big) big = d;
            }
            if (ivy_nearest_any(iv, q).dist < iv->p.clearance - 1e-5) f->near_host++;
            if (ivy_nearest_any(iv, q).dist < 0 || q.z < iv->p.ground_z) f->inside++;
        }
        c = v3_scale(c, 1.0 / (e - s));
        f->size[f->nsize++] = big;
        ivy_near any = ivy_nearest_any(iv, c);
        if (!(iv->n_hosts > iv->n_given && any.host == (int32_t)iv->n_given)) { /* not the ground */
            ivy_near h = ivy_nearest_of(iv, c, iv->n_given);
            v3 n = v3_norm(nsum[r]);
            f->cosv[f->ncos] = fabs(v3_dot(n, h.normal));
            f->dist[f->ncos++] = h.dist;
        }
        s = e;
    }
    f->blades += blades;
    /* Petioles: the last PETIOLE_VERTS * blades vertices of part 0. */
    uint32_t np = PETIOLE_VERTS * (uint32_t)blades;
    CHECK(sp->vertex_count > np, "part 0 has %u vertices, fewer than %u petiole vertices", sp->vertex_count, np);
    for (uint32_t v = sp->vertex_offset + sp->vertex_count - np; v < sp->vertex_offset + sp->vertex_count; v++) {
        v3 q = vert(m, v);
        if (ivy_nearest_any(iv, q).dist < 0 || q.z < iv->p.ground_z) f->pet_inside++;
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *n = m->normals + 3 * v;
        if (fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-4) f->bad_normal++;
    }
    free(up);
    free(nsum);
}

int main(void) {
    const char *presets[2] = {"ivy_wall", "ivy_pillar"};
    for (int k = 0; k < 2; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, presets[k]);
        size_t len;
        char *text = test_read_file(path, &len);
        CHECK(text != NULL, "cannot read %s", path);
        if (!text) continue;
        banyan_ivy_params base;
        banyan_box hosts[8];
        uint32_t nh = 0;
        banyan_error err = {0, ""};
        banyan_ivy_params_init(&base);
        CHECK(banyan_preset_apply(BANYAN_GEN_IVY, &base, text, len, path, &err) == BANYAN_OK &&
                  banyan_preset_hosts(text, len, path, hosts, 8, &nh, &err) == BANYAN_OK,
              "preset %s: %s", presets[k], err.message);
        free(text);
        figures f;
        memset(&f, 0, sizeof f);
        size_t cap = 0;
        for (uint64_t seed = 1; seed <= 5; seed++) {
            banyan_ivy_params p = base;
            p.seed = seed;
            banyan_ivy *iv = NULL;
            banyan_mesh *m = NULL;
            if (banyan_ivy_create(&p, hosts, nh, &iv, &err) != BANYAN_OK || banyan_ivy_step(iv, p.steps, &err) != BANYAN_OK ||
                banyan_ivy_mesh(iv, &m, &err) != BANYAN_OK || m->part_count != 2) {
                CHECK(0, "%s seed %llu: %s", presets[k], (unsigned long long)seed, err.message);
                banyan_mesh_free(m);
                banyan_ivy_free(iv);
                continue;
            }
            size_t need = f.nsize + m->parts[1].vertex_count;
            if (need > cap) {
                cap = 2 * need;
                f.cosv = realloc(f.cosv, sizeof(double) * cap);
                f.dist = realloc(f.dist, sizeof(double) * cap);
                f.size = realloc(f.size, sizeof(double) * cap);
            }
            measure(iv, m, &f);
            f.buds += iv->n;
            banyan_mesh_free(m);
            banyan_ivy_free(iv);
        }
        double c90 = quantile(f.cosv, f.ncos, 0.9), dmed = quantile(f.dist, f.ncos, 0.5);
        double s10 = quantile(f.size, f.nsize, 0.1), s90 = quantile(f.size, f.nsize, 0.9);
        double smin = f.nsize ? f.size[0] : NAN, smax = f.nsize ? f.size[f.nsize - 1] : NAN;
        printf("%s, 5 seeds: %d buds, %d blades (%zu off a host face): |cos| to the host normal p90 %.3f; centre distance "
               "median %.3f m; size p10 %.3f p90 %.3f m (ratio %.2f, min %.3f max %.3f); %d blade vertices within "
               "clearance, %d inside, %d triangle points inside, %d petiole vertices inside, %d normals not unit\n",
               presets[k], f.buds, f.blades, f.ncos, c90, dmed, s10, s90, s90 / s10, smin, smax, f.near_host, f.inside,
               f.tri_inside, f.pet_inside, f.bad_normal);
        CHECK(f.blades > 1000 && f.ncos > 500 && f.blades * 100 >= 99 * f.buds,
              "%s: %d blades for %d buds, %zu off a host face", presets[k], f.blades, f.buds, f.ncos);
        CHECK(c90 <= 0.97, "%s: p90 of |cos| to the host normal %.3f > 0.97 (blades lie flat)", presets[k], c90);
        CHECK(dmed >= 0.04, "%s: median blade centre %.3f m off the host, under 4 cm", presets[k], dmed);
        CHECK(s90 / s10 >= 2, "%s: blade size p90 / p10 = %.2f < 2", presets[k], s90 / s10);
        CHECK(s10 >= 0.04 && s90 <= 0.22, "%s: blade sizes p10 %.3f p90 %.3f m outside 4-22 cm", presets[k], s10, s90);
        CHECK(f.near_host == 0 && f.inside == 0, "%s: %d blade vertices within clearance of a host, %d inside",
              presets[k], f.near_host, f.inside);
        CHECK(f.tri_inside == 0, "%s: %d triangle edge midpoints or centroids of blades inside a host", presets[k],
              f.tri_inside);
        CHECK(f.pet_inside == 0, "%s: %d petiole vertices inside a host or the ground", presets[k], f.pet_inside);
        CHECK(f.bad_normal == 0, "%s: %d normals not unit length", presets[k], f.bad_normal);
        free(f.cosv);
        free(f.dist);
        free(f.size);
    }
    return check_done("test_ivy_leaves");
}
