/* test_ivy_wood - the ivy mesh's wood (csrc/ivy/wood.c) on ivy_wall:
 * stems never thicken towards their tips, a leading stem's foot is a
 * trunk, a trunk lies on the wall and not in it, old wood carries no
 * leaf, and stem_pipe 0 is the spec's age rule alone; seeds 1-5. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "ivy_look.h"

/* Radii, trunks and the gap to the wall. */
static void wood_shape(const banyan_ivy *iv, const double *r, const v3 *P) {
    const banyan_ivy_params *p = &iv->p;
    int thicker = 0, inside = 0, roots = 0;
    double worst = 0, foot = 0;
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        if (b->parent >= 0 && r[i] > r[b->parent] * (1 + 1e-12)) thicker++;
        if (b->parent < 0) {
            roots++;
            foot = r[i] > foot ? r[i] : foot;
        }
        /* Every tube's centre at least its radius off every surface. */
        double d = ivy_nearest_any(iv, P[i]).dist, in = r[i] - d;
        if (in > 1e-6) inside++, worst = in > worst ? in : worst;
    }
    CHECK(thicker == 0, "%d buds' stems thicker than their parent's", thicker);
    CHECK(roots > 0 && foot >= 5 * p->stem_radius_max, "the thickest of %d leading stems' feet: %.4f m, under 5 x %.4f m",
          roots, foot, p->stem_radius_max);
    CHECK(inside == 0, "%d stems reach into a surface (by up to %.4f m)", inside, worst);
}

/* Is (x, z) inside the triangle's xz projection? */
static int inside_xz(v3 a, v3 b, v3 c, double x, double z) {
    double d1 = (x - b.x) * (a.z - b.z) - (a.x - b.x) * (z - b.z);
    double d2 = (x - c.x) * (b.z - c.z) - (b.x - c.x) * (z - c.z);
    double d3 = (x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z);
    int neg = d1 < 0 || d2 < 0 || d3 < 0, pos = d1 > 0 || d2 > 0 || d3 > 0;
    return !(neg && pos);
}

/* Old wood sheds its leaves (ivy_wood_leaf_shares): no blade grows on a
 * bud whose wood keeps none; buds of old wood (share under a half) are
 * leafed less than half as often as the rest; and the trunks at the foot
 * show: of the buds of shed wood on the wall's front face in its lowest
 * FOOT_Z, at least FOOT_SEEN are seen from the front (a ray along +y
 * crosses no blade in front of them), over seeds 1 .. FOOT_SEEDS (one
 * plant's foot is a few trunks: its share swings by a quarter from seed
 * to seed). */
#define FOOT_Z 0.5
#define FOOT_SEEN 0.5
#define FOOT_SEEDS 5
static void wood_leaves(const banyan_ivy *iv, const double *r, uint32_t *foot_n, uint32_t *foot_seen) {
    banyan_mesh *m = NULL;
    banyan_error err = {0, ""};
    CHECK(banyan_ivy_mesh(iv, &m, &err) == BANYAN_OK && m, "mesh: %s", err.message);
    if (!m) return;
    uint32_t nb = 0, n_old = 0, n_young = 0, leaf_old = 0, leaf_young = 0, dead = 0, n_foot = 0, seen = 0;
    ivy_blade *bl = ivy_look_blades(m, &nb);
    char *leafed = calloc((size_t)iv->n, 1);
    double *share = malloc(sizeof(double) * ((size_t)iv->n + 1));
    if (share) ivy_wood_leaf_shares(iv, r, share);
    /* A blade's bud is the one at its petiole's base; of buds at one
     * point (the leading stems' first buds) the thinnest. */
    for (uint32_t k = 0; k < nb && leafed; k++) {
        int32_t best = -1;
        double bd = HUGE_VAL;
        for (int32_t i = 0; i < iv->n; i++) {
            double d = v3_dist(iv->buds[i].P, bl[k].base);
            if (d < bd - 1e-9 || (d < bd + 1e-9 && best >= 0 && r[i] < r[best])) bd = d < bd ? d : bd, best = i;
        }
        if (best >= 0) leafed[best] = 1;
    }
    const banyan_part *lp = &m->parts[1];
    for (int32_t i = 0; i < iv->n && leafed && share; i++) {
        if (share[i] < 0.5) n_old++, leaf_old += leafed[i];
        else n_young++, leaf_young += leafed[i];
        dead += share[i] <= 0 && leafed[i];
        const v3 P = iv->buds[i].P;
        if (share[i] > 0 || P.z > FOOT_Z || P.y > 0.05 || fabs(P.x) > 1.5) continue;
        n_foot++;
        int hidden = 0;
        for (uint32_t t = lp->index_offset; !hidden && t + 2 < lp->index_offset + lp->index_count; t += 3) {
            v3 a = ivy_look_vert(m, m->indices[t]), b = ivy_look_vert(m, m->indices[t + 1]), c = ivy_look_vert(m, m->indices[t + 2]);
            if (a.y < P.y && inside_xz(a, b, c, P.x, P.z)) hidden = 1;
        }
        seen += !hidden;
    }
    CHECK(nb > 1000 && n_old > 20 && n_young > 1000, "%u blades, %u buds of old wood, %u of the rest", nb, n_old, n_young);
    if (n_old && n_young)
        CHECK(2.0 * leaf_old / n_old < (double)leaf_young / n_young && dead == 0,
              "leafed: %u of %u buds of old wood, %u of %u of the rest; %u on shed wood", leaf_old, n_old, leaf_young,
              n_young, dead);
    *foot_n += n_foot;
    *foot_seen += seen;
    printf("  leafed: %u of %u buds of old wood, %u of %u of the rest; the foot's trunks: %u of %u buds seen\n", leaf_old,
           n_old, leaf_young, n_young, seen, n_foot);
    free(share);
    free(leafed);
    free(bl);
    banyan_mesh_free(m);
}

/* One seed's plant: every check on it; its foot's buds added to the counts. */
static void one_plant(banyan_ivy_params p, const banyan_hosts *H, uint32_t *foot_n, uint32_t *foot_seen) {
    banyan_ivy *iv = ivy_look_grow(&p, H);
    CHECK(iv, "ivy_wall seed %llu did not grow", (unsigned long long)p.seed);
    if (!iv) return;
    double *r = malloc(sizeof(double) * (size_t)iv->n);
    v3 *P = malloc(sizeof(v3) * (size_t)iv->n);
    CHECK(r && P && ivy_wood(iv, r, P) == BANYAN_OK, "ivy_wood");
    if (r && P) {
        double rmax = 0;
        for (int32_t i = 0; i < iv->n; i++) rmax = r[i] > rmax ? r[i] : rmax;
        printf("  ivy_wall seed %llu: %d buds, thickest stem %.4f m (age rule's cap %.4f m)\n",
               (unsigned long long)p.seed, iv->n, rmax, p.stem_radius_max);
        wood_shape(iv, r, P);
        wood_leaves(iv, r, foot_n, foot_seen);
        /* stem_pipe 0: the age rule alone, the buds where they are. */
        iv->p.stem_pipe = 0;
        CHECK(ivy_wood(iv, r, P) == BANYAN_OK, "ivy_wood, no pipe");
        int off = 0;
        for (int32_t i = 0; i < iv->n; i++) off += r[i] != ivy_stem_radius(iv, &iv->buds[i]);
        CHECK(off == 0, "stem_pipe 0: %d radii differ from the age rule", off);
    }
    free(r);
    free(P);
    banyan_ivy_free(iv);
}

int main(void) {
    banyan_ivy_params p;
    banyan_hosts *H = ivy_look_wall(&p);
    if (!H) return 1;
    uint32_t n_foot = 0, seen = 0;
    for (int s = 1; s <= FOOT_SEEDS; s++) {
        p.seed = (uint64_t)s;
        one_plant(p, H, &n_foot, &seen);
    }
    CHECK(n_foot >= 10 * FOOT_SEEDS && seen >= FOOT_SEEN * n_foot,
          "the foot's trunks: %u of %u buds of shed wood seen from the front over %d seeds", seen, n_foot, FOOT_SEEDS);
    printf("  the foot's trunks over %d seeds: %u of %u buds seen\n", FOOT_SEEDS, seen, n_foot);
    banyan_hosts_free(H);
    return check_done("test_ivy_wood");
}
