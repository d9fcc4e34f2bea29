/* keyaki: the rules of spec/keyaki.md hold on grown skeletons of all four
 * models over many seeds (coplanar forks, the fork-angle schedule except
 * where a break sprang back, one survivor carrying all the energy at a
 * break, energy conserved, every edaore tip at level L_max, the twist by
 * tilt and none at a break, the strong child upper, rule 2 planes, energy
 * lengths and the stop threshold); Strahler ordering on hand-built
 * skeletons with known answers; determinism and variety; crack-free fork
 * starts; bad input refused with a clear message; the stats of
 * banyan_keyaki_generate are banyan_keyaki_skeleton_stats' for the same
 * params (zeroed on failure); presets load; glb files for the validator. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "keyaki/keyaki_internal.h"
#include "test_files.h"

/* atan2 keeps small angles exact (acos loses them near 1). */
static double angle_deg(v3 a, v3 b) { return atan2(v3_len(v3_cross(a, b)), v3_dot(a, b)) * 180.0 / BANYAN_PI; }

static v3 end_of(const keyaki_node *x) { return v3_madd(x->start, x->dir, x->length); }

typedef struct rule_fail {
    int plane, angle, equal_angle, energy, broken, tip_level, twist, upper, rule2, lengths, stop, ratio, joined;
} rule_fail;

/* Expected twist (deg) of an edaore fork by the parent's tilt. */
static double edaore_twist(const banyan_keyaki_params *p, v3 d) {
    double tilt = angle_deg(d, v3_make(0, 0, 1));
    return tilt < p->tilt_mid ? p->twist : tilt < p->tilt_high ? p->twist_mid : p->twist_high;
}

/* Where the strong child must be the upper one (strong_side). */
static int upper_rule(const banyan_keyaki_params *p, v3 d) {
    return p->strong_side == BANYAN_KEYAKI_SIDE_UPPER || angle_deg(d, v3_make(0, 0, 1)) >= p->tilt_mid - 1e-9;
}

static void check_rules(const banyan_keyaki_params *p, const keyaki_skeleton *sk, rule_fail *f) {
    const keyaki_node *n = sk->nodes;
    const int L = p->levels;
    for (int32_t i = 0; i < sk->count; i++) {
        const keyaki_node *P = &n[i];
        int32_t a = P->child[0], b = P->child[1];
        int kids = (a >= 0) + (b >= 0);
        for (int k = 0; k < kids; k++) {
            const keyaki_node *c = &n[P->child[k]];
            if (c->parent != i || v3_dist(c->start, end_of(P)) > 1e-9) f->joined++;
            /* Rule 1: the child and its parent lie in the child's recorded fork plane. */
            if (fabs(v3_dot(c->dir, c->plane)) > 1e-9 || fabs(v3_dot(P->dir, c->plane)) > 1e-9) f->plane++;
            /* Rule 3 schedule; a survivor of a break springs back (rule 9). */
            double want = p->fork_angle + p->fork_angle_step * (c->level - 1);
            if (c->flags & KN_SPRUNG) want *= 1.0 - p->springback * (1.0 - (double)c->level / L);
            if (fabs(angle_deg(P->dir, c->dir) - want) > 1e-6) f->angle++;
        }
        if (kids == 2) {
            const keyaki_node *A = &n[a], *B = &n[b];
            /* Coplanar: the triple product of parent and children vanishes. */
            if (fabs(v3_dot(P->dir, v3_cross(A->dir, B->dir))) > 1e-9) f->plane++;
            if (fabs(angle_deg(P->dir, A->dir) - angle_deg(P->dir, B->dir)) > 1e-6) f->equal_angle++;
            if (fabs(A->energy + B->energy - P->energy) > 1e-12 * P->energy) f->energy++;
            if (P->flags & KN_BROKEN) f->broken++;
        }
        if (kids == 1) {
            /* Only a break leaves one child, and the survivor carries all. */
            if (!(P->flags & KN_BROKEN) || !(n[a].flags & KN_SPRUNG) || n[a].energy != P->energy || b >= 0) f->broken++;
        }
        if (kids == 0 && (P->flags & KN_BROKEN)) f->broken++;
        if (p->model == BANYAN_KEYAKI_EDAORE) {
            if (kids == 0 && P->level != L) f->tip_level++;
            if (kids == 2) {
                /* Rule 7: the split is one of the ten ratios; rule 8: the
                 * weak child kept its energy above alpha^-l. */
                double fs = n[a].energy / P->energy, k = (fs - 0.05) / 0.1;
                if (fs < 0.5 || fabs(k - floor(k + 0.5)) > 1e-6) f->ratio++;
                if (n[b].energy < pow(p->alpha, -(P->level + 1))) f->ratio++;
                /* Rule 10: twist by tilt, measured between the planes. */
                double tw = angle_deg(n[a].plane, P->plane);
                if (tw > 90) tw = 180 - tw;
                if (fabs(tw - edaore_twist(p, P->dir)) > 1e-6) f->twist++;
                if (upper_rule(p, P->dir) && n[a].dir.z < n[b].dir.z - 1e-12) f->upper++;
            }
            if (kids == 1) {
                /* The survivor: the upper side wherever the upper rule holds. */
                v3 other = v3_sub(v3_scale(P->dir, 2 * v3_dot(P->dir, n[a].dir)), n[a].dir);
                if (upper_rule(p, P->dir) && n[a].dir.z < other.z - 1e-12) f->upper++;
                double tw = angle_deg(n[a].plane, P->plane);
                if (tw > 1e-6 && tw < 180 - 1e-6) f->twist++; /* a break never twists */
            }
        }
        if (p->model == BANYAN_KEYAKI_TWISTED && kids == 2) {
            double tw = angle_deg(n[a].plane, P->plane);
            if (tw > 90) tw = 180 - tw;
            int sw = fabs(n[a].energy - n[b].energy) > 1e-12;
            if (fabs(tw - (sw ? p->twist : 0.0)) > 1e-6) f->twist++;
            if (sw && upper_rule(p, P->dir) && n[a].dir.z < n[b].dir.z - 1e-12) f->upper++;
        }
        if ((p->model == BANYAN_KEYAKI_SIMPLE || p->model == BANYAN_KEYAKI_STRONG_WEAK) && kids == 2) {
            v3 d = P->dir;
            if (p->fork_plane == BANYAN_KEYAKI_PLANE_STEEPEST) {
                /* d is the steepest line: its children rise equally. */
                if (fabs(n[a].dir.z - n[b].dir.z) > 1e-9) f->rule2++;
            } else if (d.x * d.x + d.y * d.y > 1e-12) {
                /* The plane is vertical: its normal is horizontal. */
                if (fabs(n[a].plane.z) > 1e-9) f->rule2++;
            }
        }
        if (p->model == BANYAN_KEYAKI_SIMPLE && kids == 2 &&
            (n[a].energy != 0.5 * P->energy || n[b].energy != 0.5 * P->energy))
            f->energy++;
        if ((p->model == BANYAN_KEYAKI_STRONG_WEAK || p->model == BANYAN_KEYAKI_TWISTED)) {
            if (kids == 2 && P->energy < p->stop_energy) f->stop++;
            if (kids == 0 && P->level < L && P->energy >= p->stop_energy) f->stop++;
            if (kids == 2 && p->length_rule == BANYAN_KEYAKI_LENGTH_ENERGY) {
                double fs = n[a].energy / P->energy, fw = n[b].energy / P->energy;
                double want = fs / fw > p->max_length_ratio ? p->max_length_ratio : fs / fw;
                double seg = p->segment_length * p->unit;
                if (fabs(n[b].length / n[a].length - want) > 1e-9 || fabs(n[a].length + n[b].length - 2 * seg) > 1e-9)
                    f->lengths++;
            }
        }
    }
}

static int rule_total(const rule_fail *f) {
    return f->plane + f->angle + f->equal_angle + f->energy + f->broken + f->tip_level + f->twist + f->upper + f->rule2 +
           f->lengths + f->stop + f->ratio + f->joined;
}

static int upper_side; /* run with strong_side = upper */

static void rules_over_seeds(int model, int dist, int fork_plane, int levels, int seeds) {
    rule_fail f;
    memset(&f, 0, sizeof f);
    keyaki_skeleton sk = {NULL, 0, 0, NULL};
    int grown = 0, breaks = 0, sprung = 0;
    for (int s = 0; s < seeds; s++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        p.model = model;
        p.distribution = dist;
        p.fork_plane = fork_plane;
        p.levels = levels;
        p.seed = 1000 + (uint64_t)s * 7919;
        p.heading = fmod(s * 13.0, 360.0);
        if (upper_side) p.strong_side = BANYAN_KEYAKI_SIDE_UPPER;
        if (model == BANYAN_KEYAKI_TWISTED && s % 2) p.length_rule = BANYAN_KEYAKI_LENGTH_EQUAL;
        if (model == BANYAN_KEYAKI_STRONG_WEAK && s % 3 == 0) p.strong_ratio = 0.9; /* hits the 3:1 length cap */
        banyan_error err;
        if (keyaki_params_validate(&p, &err) || keyaki_grow(&p, &sk, &err)) {
            CHECK(0, "model %d seed %d: %s", model, s, err.message);
            continue;
        }
        grown++;
        check_rules(&p, &sk, &f);
        for (int32_t i = 0; i < sk.count; i++) {
            breaks += (sk.nodes[i].flags & KN_BROKEN) != 0;
            sprung += (sk.nodes[i].flags & KN_SPRUNG) != 0;
        }
        if (model == BANYAN_KEYAKI_SIMPLE)
            CHECK(sk.count == (1 << (levels + 1)) - 1, "simple: %d branches, want %d", sk.count, (1 << (levels + 1)) - 1);
    }
    keyaki_skeleton_free(&sk);
    CHECK(grown == seeds, "model %d: grew %d of %d", model, grown, seeds);
    CHECK(rule_total(&f) == 0,
          "model %d dist %d plane %d: plane %d angle %d equal %d energy %d broken %d tip_level %d twist %d upper %d "
          "rule2 %d lengths %d stop %d ratio %d joined %d",
          model, dist, fork_plane, f.plane, f.angle, f.equal_angle, f.energy, f.broken, f.tip_level, f.twist, f.upper,
          f.rule2, f.lengths, f.stop, f.ratio, f.joined);
    if (model == BANYAN_KEYAKI_EDAORE) CHECK(breaks > 0 && breaks == sprung, "edaore: %d breaks, %d sprung", breaks, sprung);
    else CHECK(breaks == 0, "model %d broke %d forks", model, breaks);
}

/* ------------------------------------------------------------ Strahler */

typedef struct hand {
    keyaki_node n[64];
    int32_t count;
} hand;

static int32_t hnode(hand *h, int32_t parent) {
    int32_t i = h->count++;
    memset(&h->n[i], 0, sizeof h->n[i]);
    h->n[i].parent = parent;
    h->n[i].child[0] = h->n[i].child[1] = -1;
    h->n[i].dir = v3_make(0, 0, 1);
    h->n[i].length = 1;
    h->n[i].level = parent < 0 ? 0 : h->n[parent].level + 1;
    h->n[i].start = parent < 0 ? v3_make(0, 0, 0) : v3_madd(h->n[parent].start, h->n[parent].dir, 1);
    if (parent >= 0) {
        if (h->n[parent].child[0] < 0) h->n[parent].child[0] = i;
        else h->n[parent].child[1] = i;
    }
    return i;
}

static void check_strahler(hand *h, const char *name, int K, const int *N, int trunk_order) {
    banyan_keyaki_stats st;
    CHECK(keyaki_strahler(h->n, h->count) == BANYAN_OK, "%s: strahler refused", name);
    keyaki_measure(h->n, h->count, v3_make(0, 0, 0), &st);
    CHECK(st.max_order == K && h->n[0].order == trunk_order, "%s: K %d (want %d), trunk %d", name, st.max_order, K,
          h->n[0].order);
    double sum = 0;
    for (int k = 0; k < K; k++) {
        CHECK(st.stream_count[k] == N[k], "%s: N_%d = %d, want %d", name, k + 1, st.stream_count[k], N[k]);
        if (k + 1 < K) {
            double r = (double)N[k] / N[k + 1];
            sum += r;
            CHECK(fabs(st.bifurcation_ratio[k] - r) < 1e-12, "%s: R_%d = %g, want %g", name, k + 1,
                  st.bifurcation_ratio[k], r);
        }
    }
    double mean = K > 1 ? sum / (K - 1) : 0;
    CHECK(fabs(st.mean_bifurcation_ratio - mean) < 1e-12, "%s: mean %g, want %g", name, st.mean_bifurcation_ratio, mean);
    for (int k = K; k < BANYAN_KEYAKI_MAX_ORDER; k++) CHECK(st.stream_count[k] == 0, "%s: N_%d set", name, k + 1);
}

static void strahler_known(void) {
    hand h;
    { /* One branch. */
        h.count = 0;
        hnode(&h, -1);
        int N[] = {1};
        check_strahler(&h, "single", 1, N, 1);
    }
    { /* A chain of single children (runs after breaks) is one stream. */
        h.count = 0;
        int32_t x = hnode(&h, -1);
        for (int i = 0; i < 5; i++) x = hnode(&h, x);
        int N[] = {1};
        check_strahler(&h, "chain", 1, N, 1);
    }
    { /* Perfect binary tree of depth 3: 8 tips, orders 1..4, ratios 2. */
        h.count = 0;
        hnode(&h, -1);
        for (int32_t i = 0; h.count < 15; i++) {
            hnode(&h, i);
            hnode(&h, i);
        }
        int N[] = {8, 4, 2, 1};
        check_strahler(&h, "perfect", 4, N, 4);
    }
    { /* Unequal orders: trunk -> (fork of two tips, one tip). The order-2
       * stream runs from the trunk into the fork: N_2 = 1, N_1 = 3. */
        h.count = 0;
        int32_t t = hnode(&h, -1);
        int32_t a = hnode(&h, t);
        hnode(&h, t);
        hnode(&h, a);
        hnode(&h, a);
        int N[] = {3, 1};
        check_strahler(&h, "unequal", 2, N, 2);
    }
    { /* Single-child chains inside a tree: trunk -> chain of 3 -> fork;
       * left: chain of 2 -> fork of two tips; right: chain of 4 -> tip.
       * Orders: left 2, right 1, fork 2, trunk chain 2. Streams: order 2
       * = trunk..fork..left fork (one), order 1 = two tips + right (3). */
        h.count = 0;
        int32_t x = hnode(&h, -1);
        for (int i = 0; i < 3; i++) x = hnode(&h, x);
        int32_t l = hnode(&h, x), r = hnode(&h, x);
        for (int i = 0; i < 2; i++) l = hnode(&h, l);
        for (int i = 0; i < 4; i++) r = hnode(&h, r);
        hnode(&h, l);
        hnode(&h, l);
        int N[] = {3, 1};
        check_strahler(&h, "chains", 2, N, 2);
        CHECK(h.n[0].order == 2 && h.n[r].order == 1, "chains: orders trunk %d right %d", h.n[0].order, h.n[r].order);
    }
    { /* Two order-2 subtrees meet: order 3 at the trunk; one order-2
       * subtree behind a chain. N = {4, 2, 1}. */
        h.count = 0;
        int32_t t = hnode(&h, -1);
        int32_t a = hnode(&h, t), b = hnode(&h, t);
        int32_t bc = hnode(&h, b);
        bc = hnode(&h, bc);
        hnode(&h, a);
        hnode(&h, a);
        hnode(&h, bc);
        hnode(&h, bc);
        int N[] = {4, 2, 1};
        check_strahler(&h, "order3", 3, N, 3);
    }
    { /* A malformed skeleton (child before parent) is refused. */
        h.count = 0;
        hnode(&h, -1);
        hnode(&h, 0);
        h.n[1].child[0] = 0;
        CHECK(keyaki_strahler(h.n, h.count) == BANYAN_E_INTERNAL, "child index before parent accepted");
    }
}

/* Strahler of grown trees against an independent recursive count. */
static int rec_order(const keyaki_node *n, int32_t i) {
    int32_t a = n[i].child[0], b = n[i].child[1];
    if (a < 0 && b < 0) return 1;
    if (b < 0) return rec_order(n, a);
    int oa = rec_order(n, a), ob = rec_order(n, b);
    return oa == ob ? oa + 1 : oa > ob ? oa : ob;
}

static void strahler_grown(void) {
    keyaki_skeleton sk = {NULL, 0, 0, NULL};
    int bad = 0;
    for (int s = 0; s < 20; s++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        p.seed = 77 + (uint64_t)s;
        p.distribution = s % 2;
        if (keyaki_grow(&p, &sk, NULL) || keyaki_strahler(sk.nodes, sk.count)) {
            bad++;
            continue;
        }
        for (int32_t i = 0; i < sk.count; i += 7) bad += rec_order(sk.nodes, i) != sk.nodes[i].order;
        banyan_keyaki_stats st, st2;
        keyaki_measure(sk.nodes, sk.count, v3_load(p.position), &st);
        /* Stream counts from scratch: every tip starts an order-1 stream... */
        bad += st.stream_count[0] != st.tip_count;
        /* ...and the public call agrees with the internal pipeline. */
        bad += banyan_keyaki_skeleton_stats(&p, &st2, NULL) != BANYAN_OK || memcmp(&st, &st2, sizeof st) != 0;
    }
    keyaki_skeleton_free(&sk);
    CHECK(bad == 0, "%d Strahler disagreements on grown trees", bad);
}

/* -------------------------------------------------------- mesh checks */

/* Distance from q to segment ab and the parameter of the foot. */
static double seg_dist(v3 q, v3 a, v3 b, double *t) {
    v3 ab = v3_sub(b, a);
    double u = v3_dot(v3_sub(q, a), ab) / v3_len2(ab);
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    *t = u;
    return v3_dist(q, v3_madd(a, ab, u));
}

/* Every side limb's first ring lies inside its parent's tube or the main
 * continuation's: the child's tube leaves the parent with no gap and no
 * spike. */
static void crack_free(uint64_t seed, int model) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.seed = seed;
    p.model = model;
    if (model == BANYAN_KEYAKI_SIMPLE) p.levels = 6;
    keyaki_skeleton sk = {NULL, 0, 0, NULL};
    CHECK(keyaki_grow(&p, &sk, NULL) == BANYAN_OK, "grow");
    keyaki_strahler(sk.nodes, sk.count);
    keyaki_radii(sk.nodes, sk.count, p.tip_radius * p.unit, p.pipe_exponent);
    keyaki_body body;
    CHECK(keyaki_body_plan(&p, sk.nodes, sk.count, 0, NULL, &body, NULL) == BANYAN_OK, "plan");
    mesh_builder mb;
    mb_init(&mb, 1u << 26, 0);
    int attr[3] = {mb_add_attr(&mb, "tree_id"), mb_add_attr(&mb, "level"), mb_add_attr(&mb, "order")};
    keyaki_body_mesh(&p, sk.nodes, sk.count, &body, &mb, attr, 0, 0, 0, 0);
    CHECK(mb.status == BANYAN_OK && mb.nv == body.vertices && mb.ni == body.indices, "plan %u/%u vs mesh %u/%u",
          body.vertices, body.indices, mb.nv, mb.ni);
    const keyaki_node *n = sk.nodes;
    int outside = 0, checked = 0, bad_radius = 0;
    for (int32_t k = 0; k < body.limb_count && !mb.status; k++) {
        const keyaki_limb *L = &body.limbs[k];
        if (L->first == 0) continue;
        const keyaki_node *c = &n[L->first], *P = &n[c->parent];
        int32_t sib = P->child[0] == L->first ? P->child[1] : P->child[0];
        if (fabs(L->start_radius - KEYAKI_SIDE_START * c->radius) > 1e-12) bad_radius++;
        /* The parent's sides and the radii on both sides of the fork. */
        int sides_p = body.limbs[0].sides;
        for (int32_t j = 0; j < body.limb_count; j++) {
            /* The limb through P: the one whose chain contains P. */
            int32_t x = body.limbs[j].first;
            for (int32_t y = x; y >= 0;) {
                if (y == c->parent) { sides_p = body.limbs[j].sides; break; }
                int32_t a = n[y].child[0], b = n[y].child[1];
                y = (a >= 0 && b >= 0) ? (n[b].radius > n[a].radius ? b : a) : (a >= 0 ? a : b);
            }
        }
        double inr = cos(BANYAN_PI / sides_p);
        /* The first two rings: set back inside the parent, and at the fork. */
        for (int v = 0; v < 2 * (L->sides + 1); v++) {
            const float *q = mb.pos + 3 * (size_t)(L->vertex_offset + (uint32_t)v);
            v3 Q = v3_make(q[0], q[1], q[2]);
            double t1, t2;
            /* The parent's tube at the fork has the parent's radius; the
             * sibling continues from it with at least its own. */
            double d1 = seg_dist(Q, P->start, end_of(P), &t1);
            double d2 = sib >= 0 ? seg_dist(Q, n[sib].start, end_of(&n[sib]), &t2) : 1e30;
            (void)t1;
            double sib_end = 0;
            if (sib >= 0)
                sib_end = n[sib].child[0] < 0 && n[sib].child[1] < 0 ? p.tip_radius * p.unit * p.tip_taper
                                                                      : n[sib].radius;
            double r1 = P->radius, r2 = sib >= 0 ? P->radius + (sib_end - P->radius) * t2 : 0;
            checked++;
            if (!(d1 <= r1 * inr * (1 + 1e-5) || d2 <= r2 * inr * (1 + 1e-5))) outside++;
        }
    }
    CHECK(checked > 0 && outside == 0 && bad_radius == 0,
          "model %d seed %llu: %d of %d side-limb start vertices outside the parent, %d radius mismatches", model,
          (unsigned long long)seed, outside, checked, bad_radius);
    mb_free(&mb);
    keyaki_body_free(&body);
    keyaki_skeleton_free(&sk);
}

/* levels: the skeleton's; twigs and leaves (order 0) lie up
 * to twig_levels deeper. */
static void mesh_sanity(const banyan_mesh *m, int levels, const char *name) {
    levels += 3; /* twig_levels <= 3 */
    const float *tid = banyan_mesh_attribute(m, "tree_id"), *lev = banyan_mesh_attribute(m, "level"),
                *ord = banyan_mesh_attribute(m, "order");
    CHECK(tid && lev && ord, "%s: attributes missing", name);
    if (!tid || !lev || !ord) return;
    int bad = 0, bad_n = 0, bad_uv = 0, bad_idx = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        bad += tid[v] != 0 || lev[v] < 0 || lev[v] > levels || lev[v] != floorf(lev[v]) || ord[v] < 0 ||
               (ord[v] == 0 && lev[v] < 1); /* order 0: a twig or leaf, below some branch */
        const float *nn = m->normals + 3 * v;
        bad_n += fabs(sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]) - 1) > 1e-4;
        for (int k = 0; k < 3; k++) bad_n += !isfinite(m->positions[3 * v + k]);
    }
    for (uint32_t i = 0; i < m->index_count; i++) bad_idx += m->indices[i] >= m->vertex_count;
    CHECK(m->material_count == 2 && m->part_count >= 1 && m->part_count <= 2 && m->parts[0].material == 0,
          "%s: %u materials %u parts", name, m->material_count, m->part_count);
    if (m->part_count == 2) {
        const banyan_part *lp = &m->parts[1];
        CHECK(lp->material == 1 && m->materials[1].double_sided, "%s: leaf part", name);
        for (uint32_t v = lp->vertex_offset; v < lp->vertex_offset + lp->vertex_count; v++)
            bad_uv += m->uvs[2 * v] < 0 || m->uvs[2 * v] > 1 || m->uvs[2 * v + 1] < 0 || m->uvs[2 * v + 1] > 1;
    }
    CHECK(bad == 0 && bad_n == 0 && bad_uv == 0 && bad_idx == 0, "%s: attrs %d normals %d leaf uvs %d indices %d", name,
          bad, bad_n, bad_uv, bad_idx);
    CHECK(m->skel_point_count == m->skel_edge_count + 1, "%s: skeleton %u points %u edges", name, m->skel_point_count,
          m->skel_edge_count);
}


static void write_glb(const char *dir, const char *name, const banyan_mesh *m) {
    if (!dir) return;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.glb", dir, name);
    banyan_error err;
    CHECK(banyan_gltf_write(path, &m, &name, 1, &err) == BANYAN_OK, "write %s: %s", path, err.message);
}

/* One presets/keyaki_*.json: it loads, generates a sane mesh and writes a glb. */
static void preset(const char *path, const char *name, void *ctx) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    banyan_error err = {0, ""};
    banyan_status s = test_load_preset(BANYAN_GEN_KEYAKI, &p, path, NULL, 0, NULL, &err);
    CHECK(s == BANYAN_OK, "%s: %s", path, err.message);
    banyan_mesh *m = NULL;
    if (!s) s = banyan_keyaki_generate(&p, &m, NULL, NULL, &err);
    CHECK(s == BANYAN_OK && m, "%s: generate: %s", name, err.message);
    if (m) {
        /* Segment twigs carry their own levels; test_keyaki_twigs checks them. */
        if (!p.twigs_from_segments) mesh_sanity(m, p.levels, name);
        write_glb(ctx, name, m);
    }
    banyan_mesh_free(m);
}

static void presets(const char *outdir) {
    int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "keyaki_", preset, (void *)outdir);
    CHECK(n >= 6, "found %d presets/keyaki_*.json", n);
}

/* ------------------------------------------------------------ refusals */

static void refuse(banyan_keyaki_params *p, banyan_status want, const char *needle, const char *what) {
    banyan_error err = {0, ""};
    banyan_mesh *m = (banyan_mesh *)&err; /* must come back NULL */
    banyan_keyaki_stats st;
    memset(&st, 0xff, sizeof st);
    banyan_status s = banyan_keyaki_generate(p, &m, &st, NULL, &err);
    CHECK(s == want && m == NULL && strstr(err.message, needle), "%s: status %d (want %d), message '%s'", what, s, want,
          err.message);
    CHECK(st.node_count == 0 && st.height == 0 && st.stream_count[0] == 0, "%s: stats not zeroed on failure", what);
    s = banyan_keyaki_skeleton_stats(p, &st, &err);
    if (want != BANYAN_E_LIMIT || strstr(needle, "max_vertices") == NULL)
        CHECK(s == want && strstr(err.message, needle), "%s (stats): status %d, '%s'", what, s, err.message);
    banyan_keyaki_params_init(p);
}

static void bad_input(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.alpha = 1.0;
    refuse(&p, BANYAN_E_RANGE, "alpha = 1 must be within [1.001, 10]", "alpha 1");
    p.alpha = 0.5;
    refuse(&p, BANYAN_E_RANGE, "alpha", "alpha 0.5");
    p.levels = 31;
    refuse(&p, BANYAN_E_RANGE, "levels = 31 must be within [1, 30]", "levels 31");
    p.segment_length = -1;
    refuse(&p, BANYAN_E_RANGE, "segment_length = -1 must be within", "negative segment");
    p.unit = NAN;
    refuse(&p, BANYAN_E_RANGE, "unit", "NaN unit");
    p.position[1] = INFINITY;
    refuse(&p, BANYAN_E_RANGE, "position", "inf position");
    p.sides_min = 20;
    refuse(&p, BANYAN_E_RANGE, "sides_min = 20 must be <= sides_max = 14", "sides order");
    p.fork_angle = 80;
    refuse(&p, BANYAN_E_RANGE, "fork_angle + fork_angle_step", "fork angle past 90");
    p.threads = -1;
    refuse(&p, BANYAN_E_RANGE, "threads = -1 must be within [0, 64]", "threads -1");
    p.threads = 65;
    refuse(&p, BANYAN_E_RANGE, "threads = 65 must be within [0, 64]", "threads 65");
    p.tilt_mid = 70;
    refuse(&p, BANYAN_E_RANGE, "tilt_mid", "tilt order");
    p.model = 4;
    refuse(&p, BANYAN_E_RANGE, "model", "model 4");
    p.max_vertices = 1000;
    refuse(&p, BANYAN_E_LIMIT, "more than max_vertices = 1000", "vertex limit");
    p.model = BANYAN_KEYAKI_SIMPLE;
    refuse(&p, BANYAN_E_LIMIT, "max_nodes", "simple with 21 levels");
    p.max_nodes = 50;
    refuse(&p, BANYAN_E_LIMIT, "max_nodes = 50", "node limit");
    banyan_error err;
    CHECK(banyan_keyaki_generate(NULL, &(banyan_mesh *){NULL}, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL params");
    CHECK(banyan_keyaki_generate(&p, NULL, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL out");
    CHECK(banyan_keyaki_skeleton_stats(&p, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL stats out");
    /* The table refuses the same through --set. */
    CHECK(banyan_param_set_text(BANYAN_GEN_KEYAKI, &p, "alpha", "1", &err) == BANYAN_E_RANGE, "set alpha=1");
    CHECK(banyan_param_set_text(BANYAN_GEN_KEYAKI, &p, "model", "edaore", &err) == BANYAN_OK &&
              banyan_param_set_text(BANYAN_GEN_KEYAKI, &p, "distribution", "normal", &err) == BANYAN_OK &&
              p.distribution == BANYAN_KEYAKI_NORMAL,
          "set enums");
}

/* The stats of banyan_keyaki_generate, byte for byte those of
 * banyan_keyaki_skeleton_stats for the same params: every model, first
 * branching, lean, twigs from segments, a tree far from the origin (its
 * own frame) and small trees. */
static void generate_stats_match(void) {
    for (int v = 0; v < 8; v++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        p.seed = 31 + (uint64_t)v;
        p.model = v % 4;
        p.levels = p.model == BANYAN_KEYAKI_SIMPLE ? 7 : 13;
        p.leaf_density = 4;
        if (v == 4) p.limbs = 4, p.lean = 12, p.lean_direction = 40, p.heading = 70;
        if (v == 5) p.twigs_from_segments = 1, p.segment_levels = 3;
        if (v == 6) p.position[0] = 123456.75, p.position[1] = -50000.5, p.position[2] = 9000.25, p.unit = 0.7;
        if (v == 7) p.levels = 1, p.leaves = 0;
        banyan_keyaki_stats a, b;
        memset(&a, 0xff, sizeof a);
        banyan_mesh *m = NULL;
        banyan_error err = {0, ""};
        CHECK(banyan_keyaki_generate(&p, &m, &a, NULL, &err) == BANYAN_OK && m, "variant %d: %s", v, err.message);
        CHECK(banyan_keyaki_skeleton_stats(&p, &b, &err) == BANYAN_OK, "variant %d stats: %s", v, err.message);
        CHECK(!memcmp(&a, &b, sizeof a), "variant %d: generate's stats differ from the skeleton's (%d / %d branches, "
              "height %.17g / %.17g)", v, a.node_count, b.node_count, a.height, b.height);
        CHECK(a.node_count >= 1 && a.max_order >= 1, "variant %d: %d branches, order %d", v, a.node_count, a.max_order);
        /* The mesh's skeleton has one edge per branch of the measured skeleton. */
        if (m) CHECK(m->skel_edge_count >= (uint32_t)a.node_count, "variant %d: %u skeleton edges, %d branches", v,
                     m->skel_edge_count, a.node_count);
        banyan_mesh_free(m);
    }
}

/* ------------------------------------------------ determinism, variety */

static double stdev(const double *v, int n) {
    double m = 0, s = 0;
    for (int i = 0; i < n; i++) m += v[i];
    m /= n;
    for (int i = 0; i < n; i++) s += (v[i] - m) * (v[i] - m);
    return sqrt(s / n);
}

/* One tree meshed on 1, 2, 3 and all cores: the same bytes (wind on and
 * off, leaves in several chunks and none). */
static void threads_same_mesh(void) {
    for (int v = 0; v < 3; v++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        p.seed = 9 + (uint64_t)v;
        p.wind = v != 1;
        p.leaves = v != 2;
        uint64_t h[4] = {0, 0, 0, 0};
        const int threads[4] = {1, 2, 3, 0};
        for (int t = 0; t < 4; t++) {
            banyan_mesh *m = NULL;
            banyan_error err = {0, ""};
            p.threads = threads[t];
            CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK, "threads %d: %s", threads[t], err.message);
            if (m) h[t] = banyan_mesh_hash(m);
            if (m && t == 0 && v == 0) CHECK(m->part_count == 2 && m->parts[1].vertex_count > 4 * 8192 * 2,
                                           "variant %d: too few leaves to split (%u parts)", v, m->part_count);
            banyan_mesh_free(m);
        }
        for (int t = 1; t < 4; t++)
            CHECK(h[t] && h[t] == h[0], "variant %d: threads %d gives other bytes than 1 thread", v, threads[t]);
    }
}

static void determinism_variety(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.seed = 42;
    banyan_mesh *a = NULL, *b = NULL, *c = NULL;
    CHECK(banyan_keyaki_generate(&p, &a, NULL, NULL, NULL) == BANYAN_OK, "gen a");
    CHECK(banyan_keyaki_generate(&p, &b, NULL, NULL, NULL) == BANYAN_OK, "gen b");
    p.seed = 43;
    CHECK(banyan_keyaki_generate(&p, &c, NULL, NULL, NULL) == BANYAN_OK, "gen c");
    if (a && b && c) {
        CHECK(banyan_mesh_hash(a) == banyan_mesh_hash(b), "same seed, different bytes");
        CHECK(banyan_mesh_hash(a) != banyan_mesh_hash(c), "different seeds, same bytes");
        mesh_sanity(a, p.levels, "seed 42");
    }
    banyan_mesh_free(a);
    banyan_mesh_free(b);
    banyan_mesh_free(c);

    for (int model = 0; model < 4; model++) {
        enum { S = 100 };
        double tips[S], width[S];
        keyaki_skeleton s1 = {NULL, 0, 0, NULL}, s2 = {NULL, 0, 0, NULL};
        int same_skeleton = 0;
        for (int s = 0; s < S; s++) {
            banyan_keyaki_params q;
            banyan_keyaki_params_init(&q);
            q.model = model;
            if (model == BANYAN_KEYAKI_SIMPLE) q.levels = 6;
            q.seed = 5000 + (uint64_t)s;
            banyan_keyaki_stats st;
            CHECK(banyan_keyaki_skeleton_stats(&q, &st, NULL) == BANYAN_OK, "stats");
            tips[s] = st.tip_count;
            width[s] = st.crown_width;
            /* Consecutive seeds give different skeletons. */
            keyaki_grow(&q, &s1, NULL);
            q.seed++;
            keyaki_grow(&q, &s2, NULL);
            if (s1.count == s2.count && memcmp(s1.nodes, s2.nodes, sizeof(keyaki_node) * (size_t)s1.count) == 0)
                same_skeleton++;
        }
        keyaki_skeleton_free(&s1);
        keyaki_skeleton_free(&s2);
        CHECK(same_skeleton == 0, "model %d: %d seed pairs with identical skeletons", model, same_skeleton);
        CHECK(stdev(width, S) > 0, "model %d: crown widths do not vary", model);
        if (model != BANYAN_KEYAKI_SIMPLE) CHECK(stdev(tips, S) > 0, "model %d: tip counts do not vary", model);
        else CHECK(tips[0] == 64 && stdev(tips, S) == 0, "simple: %g tips, want 64 always", tips[0]);
    }
}


/* Rule 5's p: the share of strong/weak forks among model-2 forks; and
 * `heading` turns the whole skeleton about the trunk (the rules only look
 * at the vertical, so growth commutes with turns about Z). */
static void fractions_and_heading(void) {
    keyaki_skeleton sk = {NULL, 0, 0, NULL}, sk2 = {NULL, 0, 0, NULL};
    long forks = 0, sw = 0;
    for (int s = 0; s < 40; s++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        p.model = BANYAN_KEYAKI_STRONG_WEAK;
        p.strong_probability = 0.3;
        p.seed = 300 + (uint64_t)s;
        keyaki_grow(&p, &sk, NULL);
        for (int32_t i = 0; i < sk.count; i++)
            if (sk.nodes[i].child[1] >= 0) {
                forks++;
                sw += sk.nodes[sk.nodes[i].child[0]].energy != sk.nodes[sk.nodes[i].child[1]].energy;
            }
    }
    double f = (double)sw / (double)forks;
    CHECK(forks > 1000 && fabs(f - 0.3) < 0.03, "strong/weak share %g of %ld forks, want 0.3", f, forks);
    int bad = 0;
    for (int model = 0; model < 4; model++) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        p.model = model;
        if (model == 0) p.levels = 6;
        p.seed = 99;
        p.position[0] = 3;
        p.position[1] = -2;
        keyaki_grow(&p, &sk, NULL);
        p.heading = 70;
        keyaki_grow(&p, &sk2, NULL);
        bad += sk.count != sk2.count;
        for (int32_t i = 0; i < sk.count && sk.count == sk2.count; i++) {
            v3 a = v3_sub(end_of(&sk.nodes[i]), v3_load(p.position)), b = v3_sub(end_of(&sk2.nodes[i]), v3_load(p.position));
            if (v3_dist(v3_rotate_z(a, deg2rad(70)), b) > 1e-9) {
                if (bad < 3) fprintf(stderr, "model %d node %d level %d: %g\n", model, i, sk.nodes[i].level, v3_dist(v3_rotate_z(a, deg2rad(70)), b));
                bad++;
            }
        }
    }
    CHECK(bad == 0, "%d branches not turned by heading", bad);
    keyaki_skeleton_free(&sk);
    keyaki_skeleton_free(&sk2);
}

/* `unit` scales the tree's body: same vertex count, positions scaled.
 * Twigs and leaves are real sizes in metres: left out; so is
 * bark_flake_radius (metres: where a limb's flakes end, one more ring). */
static void unit_scales(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.seed = 31;
    p.leaf_levels = 0;
    p.bark_flake_radius = 0;
    banyan_mesh *a = NULL, *b = NULL;
    banyan_keyaki_generate(&p, &a, NULL, NULL, NULL);
    p.unit = 2.5;
    banyan_keyaki_generate(&p, &b, NULL, NULL, NULL);
    CHECK(a && b && a->vertex_count == b->vertex_count && a->index_count == b->index_count, "unit changes the counts");
    int bad = 0;
    for (uint32_t i = 0; a && b && a->vertex_count == b->vertex_count && i < 3 * a->vertex_count; i++)
        bad += fabs(2.5 * a->positions[i] - b->positions[i]) > 1e-4 * (1 + fabs(b->positions[i]));
    CHECK(bad == 0, "%d coordinates not scaled by unit", bad);
    banyan_mesh_free(a);
    banyan_mesh_free(b);
}

int main(int argc, char **argv) {
    const char *outdir = argc > 1 ? argv[1] : NULL;
    for (int d = 0; d < 2; d++) rules_over_seeds(BANYAN_KEYAKI_EDAORE, d, 0, 21, 60);
    upper_side = 1;
    rules_over_seeds(BANYAN_KEYAKI_EDAORE, 0, 0, 21, 30);
    rules_over_seeds(BANYAN_KEYAKI_TWISTED, 0, 0, 21, 30);
    upper_side = 0;
    rules_over_seeds(BANYAN_KEYAKI_EDAORE, 0, 0, 9, 30);
    for (int fp = 0; fp < 2; fp++) {
        rules_over_seeds(BANYAN_KEYAKI_SIMPLE, 0, fp, 6, 20);
        rules_over_seeds(BANYAN_KEYAKI_STRONG_WEAK, 0, fp, 21, 40);
    }
    rules_over_seeds(BANYAN_KEYAKI_TWISTED, 0, 0, 21, 40);
    fractions_and_heading();
    unit_scales();
    strahler_known();
    strahler_grown();
    for (int m = 0; m < 4; m++)
        for (uint64_t s = 1; s <= 6; s++) crack_free(s * 101, m);
    bad_input();
    generate_stats_match();
    determinism_variety();
    threads_same_mesh();
    presets(outdir);
    return check_done("test_keyaki");
}
