/* Ivy (spec/ivy.md): invariants over several seeds and scenes.
 *   - Rules: states, suckers (every third apical bud has none), leaves on
 *     alternating sides, nourishment accumulating before the first growth,
 *     runs no longer than Bmax (p6), branch points counted right.
 *   - Light: the spatial hash gives the brute-force H0 and V_l; every bud
 *     the light cache skips is still too shaded.
 *   - No stem point inside a host; attached buds within sucker reach.
 *   - Sag: long free stems hang below their anchor with tips turned up,
 *     and their moment about the anchor is within the anchor's joint
 *     strength (moment_max x (r / r0)^sag_stiffening).
 *   - Stats: crossings equal a brute-force count; parts add up.
 *   - Mesh: materials, parts, `part` and `birth_step` attributes, leaf blades
 *     facing out from the wall but tilted off it, skeleton; same seed, same bytes;
 *     stepping in pieces equals stepping at once.
 *   - The mesh is the same bytes on 1, 2, 3 and all threads (with and
 *     without leaves and wind).
 *   - Bad input refused with a clear message and *out == NULL.
 *   - Every presets/ivy_*.json loads and generates; glb files for the
 *     validator. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy_checks.h"
#include "hosts/obb.h"
#include "ivy/ivy_internal.h"
#include "test_files.h"
#include "test_hosts.h"

static banyan_box wall_box(void) { return banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5); }


/* Loads presets/<name>.json into p and hosts. */
static int load_preset(const char *name, banyan_ivy_params *p, banyan_box *hosts, uint32_t *n_hosts) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    banyan_error err = {0, ""};
    banyan_ivy_params_init(p);
    banyan_status s = test_load_preset(BANYAN_GEN_IVY, p, path, hosts, 8, n_hosts, &err);
    CHECK(s == BANYAN_OK, "%s: %s", name, err.message);
    return s == BANYAN_OK;
}

static banyan_ivy *grow(const banyan_ivy_params *p, const banyan_hosts *hosts, int32_t steps) {
    banyan_ivy *iv = NULL;
    banyan_error err = {0, ""};
    banyan_status s = banyan_ivy_create(p, hosts, &iv, &err);
    CHECK(s == BANYAN_OK, "create: %s", err.message);
    if (s) return NULL;
    s = banyan_ivy_step(iv, steps, &err);
    CHECK(s == BANYAN_OK, "step: %s", err.message);
    return iv;
}

/* Min signed distance of p to every host the plant keeps out of. */
static double all_host_distance(const banyan_ivy *iv, v3 p) {
    double best = HUGE_VAL;
    for (uint32_t h = 0; h < iv->n_hosts; h++) {
        double d = obb_signed_distance(&iv->hosts[h], p);
        if (d < best) best = d;
    }
    return best;
}

/* Structure, rules and geometry invariants of one grown plant. */
static void invariants(const banyan_ivy *iv, const char *what) {
    const banyan_ivy_params *p = &iv->p;
    int bad_inside = 0, bad_attach = 0, bad_side = 0, bad_sucker = 0, bad_state = 0, bad_run = 0, bad_tree = 0,
        bad_pattern = 0, bad_cache = 0;
    int32_t branches = 0, by_state[5] = {0, 0, 0, 0, 0}, attached = 0;
    double worst_inside = HUGE_VAL;
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        double d = all_host_distance(iv, b->P);
        if (d < worst_inside) worst_inside = d;
        if (d < 0) bad_inside++;
        if (b->attached) {
            attached++;
            if (!(ivy_grip_distance(iv, b->P, HUGE_VAL) <= p->sucker_length + 1e-9)) bad_attach++;
            if (!b->sucker) bad_attach++;
        }
        if (b->state < 0 || b->state > 4) bad_state++;
        else by_state[b->state]++;
        /* A0 and A1 have suckers; A2 and D (a former A2) have none. */
        if ((b->state == BANYAN_IVY_A0 || b->state == BANYAN_IVY_A1) && !b->sucker) bad_sucker++;
        if ((b->state == BANYAN_IVY_A2 || b->state == BANYAN_IVY_D) && b->sucker) bad_sucker++;
        if (b->run * p->internode > p->bmax + p->internode + 1e-9) bad_run++;
        if (b->parent >= 0) {
            const ivy_bud *a = &iv->buds[b->parent];
            if (b->L != 1 - a->L) bad_side++;
            if (a->child[0] != i && a->child[1] != i) bad_tree++;
            if (b->parent >= i) bad_tree++;
            /* Along a stem: never two suckerless buds in a row, never three
             * suckered ones. */
            if (a->child[0] == i) {
                if (!a->sucker && !b->sucker) bad_pattern++;
                if (a->sucker && b->sucker && a->parent >= 0 && iv->buds[a->parent].child[0] == b->parent &&
                    iv->buds[a->parent].sucker)
                    bad_pattern++;
            }
        } else if (i >= iv->p.start_stems) bad_tree++; /* only the leading stems' first buds are roots */
        if (b->child[1] >= 0) {
            branches++;
            if (b->state != BANYAN_IVY_Z) bad_state++; /* p3 ends the dormant bud */
        }
        /* The light cache: a bud marked too shaded is still too shaded. */
        if (b->shaded && b->state != BANYAN_IVY_Z) {
            v3 vl;
            double H = brute_shade(iv, b->P, i, &vl);
            if (b->state == BANYAN_IVY_D) {
                int32_t a = b->parent;
                for (int32_t k = 0; k < p->h1_buds && a >= 0; k++, a = iv->buds[a].parent) H += brute_shade(iv, iv->buds[a].P, a, &vl);
            }
            if (!(H > p->t0 - 1e-9)) bad_cache++;
        }
    }
    CHECK(bad_inside == 0, "%s: %d stem points inside a host (worst %g m)", what, bad_inside, worst_inside);
    CHECK(worst_inside >= p->clearance - 1e-6, "%s: a stem point is %g m off a host, under clearance %g", what,
          worst_inside, p->clearance);
    CHECK(bad_attach == 0, "%s: %d attached buds out of sucker reach or without a sucker", what, bad_attach);
    CHECK(bad_side == 0, "%s: %d leaves not alternating sides", what, bad_side);
    CHECK(bad_sucker == 0, "%s: %d buds whose sucker does not match their state", what, bad_sucker);
    CHECK(bad_pattern == 0, "%s: %d breaks of the sucker, sucker, none pattern", what, bad_pattern);
    CHECK(bad_state == 0, "%s: %d bad states", what, bad_state);
    CHECK(bad_run == 0, "%s: %d buds on unattached runs past Bmax", what, bad_run);
    CHECK(bad_tree == 0, "%s: %d broken tree links", what, bad_tree);
    CHECK(bad_cache == 0, "%s: %d buds the light cache skips though they have light", what, bad_cache);

    banyan_ivy_stats st;
    banyan_error err;
    CHECK(banyan_ivy_get_stats(iv, &st, &err) == BANYAN_OK, "%s: stats: %s", what, err.message);
    CHECK(st.buds == iv->n && st.branch_points == branches, "%s: stats buds %d / %d, branch points %d / %d", what,
          st.buds, iv->n, st.branch_points, branches);
    int sum = 0;
    for (int k = 0; k < 5; k++) {
        sum += st.by_state[k];
        CHECK(st.by_state[k] == by_state[k], "%s: state %d count %d, want %d", what, k, st.by_state[k], by_state[k]);
    }
    CHECK(sum == st.buds, "%s: states add to %d of %d buds", what, sum, st.buds);
    CHECK(st.attached == attached && fabs(st.attached_fraction - (double)attached / iv->n) < 1e-12,
          "%s: attached %d / %d", what, st.attached, attached);
    CHECK(st.covered_area > 0 && fabs(st.density - (st.branch_points + st.crossings) / st.covered_area) < 1e-9,
          "%s: density %g with area %g", what, st.density, st.covered_area);
}

/* Long free stems: hanging below their anchor, tips up, moment held. */
typedef struct sag_tally {
    int chains, droop, tip_up, moment_ok;
} sag_tally;

/* Held as the sag sees it: attached or lying on the ground. */
static int held(const banyan_ivy *iv, const ivy_bud *b) {
    return b->attached || (iv->p.ground && b->P.z <= iv->p.ground_z + iv->p.clearance + 1e-9);
}

static int held_by(const banyan_ivy *iv, int32_t root) {
    int32_t stack[512], top = 0, seen = 0;
    stack[top++] = root;
    while (top > 0) {
        const ivy_bud *b = &iv->buds[stack[--top]];
        if (held(iv, b) || ++seen > 256) return 1;
        for (int k = 0; k < 2; k++)
            if (b->child[k] >= 0 && top < 510) stack[top++] = b->child[k];
    }
    return 0;
}

static void sag_check(const banyan_ivy *iv, sag_tally *t) {
    const banyan_ivy_params *p = &iv->p;
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *tip = &iv->buds[i];
        if (tip->state > BANYAN_IVY_A2 || tip->attached) continue;
        int32_t j = i, prev = -1, m = 0, chain[4096];
        while (j >= 0 && m < 4096) {
            const ivy_bud *b = &iv->buds[j];
            if (held(iv, b)) break;
            if (prev >= 0) {
                int32_t other = b->child[0] == prev ? b->child[1] : b->child[0];
                if (other >= 0 && held_by(iv, other)) break;
            }
            chain[m++] = j;
            prev = j;
            j = b->parent;
        }
        if (j < 0 || m < 8) continue;
        /* The subtree of P1: free of every surface, also one sag step on
         * (a stem that rests on a surface may keep more moment). */
        int32_t set[4096], n = 0, top = 0, stack[4096];
        stack[top++] = chain[m - 1];
        while (top > 0 && n < 4096) {
            int32_t x = stack[--top];
            set[n++] = x;
            for (int k = 0; k < 2; k++)
                if (iv->buds[x].child[k] >= 0 && top < 4096) stack[top++] = iv->buds[x].child[k];
        }
        double reach = 0;
        for (int32_t k = 0; k < n; k++) reach = fmax(reach, v3_dist(iv->buds[set[k]].P, iv->buds[j].P));
        int touching = 0;
        for (int32_t k = 0; k < n; k++)
            if (all_host_distance(iv, iv->buds[set[k]].P) < p->clearance + reach * p->sag_step * BANYAN_PI / 180 + 1e-3)
                touching = 1;
        if (touching) continue;
        v3 P0 = iv->buds[j].P, C = v3_make(0, 0, 0);
        double zmin = HUGE_VAL;
        for (int32_t k = 0; k < n; k++) {
            C = v3_add(C, iv->buds[set[k]].P);
            if (iv->buds[set[k]].P.z < zmin) zmin = iv->buds[set[k]].P.z;
        }
        C = v3_scale(C, 1.0 / n);
        double dx = C.x - P0.x, dy = C.y - P0.y, dz = C.z - P0.z;
        double arm = dz > 0 ? sqrt(dx * dx + dy * dy + dz * dz) : sqrt(dx * dx + dy * dy);
        double F = n * p->internode_mass * p->gravity * arm;
        t->chains++;
        t->droop += zmin < P0.z - p->internode;
        t->tip_up += tip->V.z > 0;
        /* The anchor's joint holds moment_max * (r / r0)^sag_stiffening
         * (r its stem radius by age), which grows; still a bound. */
        double strength = p->moment_max * pow(ivy_stem_radius(iv, &iv->buds[j]) / p->stem_radius, p->sag_stiffening);
        t->moment_ok += F <= strength * 1.01; /* the sweeps stop after SAG_PASSES */
    }
}


static void test_light_and_stats(void) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    banyan_box w = wall_box();
    banyan_hosts *W = TEST_HOSTS(&w, 1);
    for (uint64_t seed = 1; seed <= 3; seed++) {
        p.seed = seed;
        banyan_ivy *iv = grow(&p, W, 170);
        if (!iv) continue;
        pcg32 r;
        pcg32_seed(&r, seed, 77);
        int bad_h = 0, bad_v = 0, bad_stop = 0;
        for (int k = 0; k < 300; k++) {
            int32_t i = (int32_t)rng_below(&r, (uint32_t)iv->n);
            v3 q = v3_add(iv->buds[i].P, v3_make(rng_range(&r, -.05, .05), rng_range(&r, -.05, .05), rng_range(&r, -.05, .05)));
            int32_t self = k % 2 ? i : -1;
            v3 want_vl, vl = v3_make(0, 0, 0);
            double want = brute_shade(iv, self >= 0 ? iv->buds[i].P : q, self, &want_vl);
            double got = ivy_shade(iv, self >= 0 ? iv->buds[i].P : q, self, HUGE_VAL, &vl);
            if (fabs(got - want) > 1e-9) bad_h++;
            if (v3_dist(vl, want_vl) > 1e-9) bad_v++;
            double stopped = ivy_shade(iv, q, -1, 3.0, NULL);
            brute_shade(iv, q, -1, &want_vl);
            if ((stopped > 3.0) != (brute_shade(iv, q, -1, &want_vl) > 3.0)) bad_stop++;
        }
        CHECK(bad_h == 0 && bad_v == 0 && bad_stop == 0, "seed %llu: hash H0 off %d, V_l off %d, early stop off %d",
              (unsigned long long)seed, bad_h, bad_v, bad_stop);
        banyan_ivy_stats st;
        banyan_ivy_get_stats(iv, &st, NULL);
        int32_t want = brute_crossings(iv);
        CHECK(st.crossings == want, "seed %llu: %d crossings, brute force %d", (unsigned long long)seed, st.crossings,
              want);
        CHECK(want > 0, "seed %llu: no crossings at all: the count is not exercised", (unsigned long long)seed);
        banyan_ivy_free(iv);
    }
    banyan_hosts_free(W);
}

static void test_nourishment(void) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    banyan_box w = wall_box();
    banyan_hosts *W = TEST_HOSTS(&w, 1);
    p.start_stems = 1; /* the paper's single first bud */
    /* From N = 0 the first bud waits while N accumulates by beta to t1. */
    p.n_start = 0.0;
    banyan_ivy *iv = grow(&p, W, 3);
    CHECK(iv && iv->n == 1, "grew before nourishment reached t1: %d buds", iv ? iv->n : -1);
    banyan_error err;
    if (iv) banyan_ivy_step(iv, 2, &err);
    CHECK(iv && iv->n == 2, "after 5 steps of beta = 0.05 the bud should have grown once: %d buds", iv ? iv->n : -1);
    banyan_ivy_free(iv);
    /* Without nourishment nothing grows. */
    p.beta = 0.0;
    iv = grow(&p, W, 40);
    CHECK(iv && iv->n == 1, "beta = 0 grew %d buds", iv ? iv->n : -1);
    banyan_ivy_free(iv);
    /* Apical growth: three internodes, then the split of p2. */
    banyan_ivy_params_init(&p);
    p.start_stems = 1;
    iv = grow(&p, W, 3);
    CHECK(iv && iv->n == 4 && iv->buds[3].state == BANYAN_IVY_A0 && iv->buds[2].state == BANYAN_IVY_D &&
              fabs(iv->buds[3].N - p.alpha * p.n_start) < 1e-12 && fabs(iv->buds[2].N - (1 - p.alpha) * p.n_start) < 1e-12,
          "A0 A1 A2 -> Z Z D A0 with alpha split");
    banyan_ivy_free(iv);
    banyan_hosts_free(W);
}

static void test_scenes(void) {
    sag_tally tally = {0, 0, 0, 0};
    banyan_ivy_params p;
    banyan_box hosts[8];
    uint32_t nh = 0;
    if (load_preset("ivy_wall", &p, hosts, &nh)) {
        banyan_hosts *H = TEST_HOSTS(hosts, nh);
        for (uint64_t seed = 1; seed <= 3; seed++) {
            p.seed = seed;
            banyan_ivy *iv = grow(&p, H, 300);
            if (!iv) continue;
            char what[64];
            snprintf(what, sizeof what, "wall seed %llu", (unsigned long long)seed);
            invariants(iv, what);
            sag_check(iv, &tally);
            banyan_ivy_free(iv);
        }
        banyan_hosts_free(H);
    }
    /* Seeds until at least 8 long free stems have been checked (about 3 to 5
     * seeds; at most 8): each plant's hanging stems are chance. */
    if (load_preset("ivy_pillar", &p, hosts, &nh)) {
        banyan_hosts *H = TEST_HOSTS(hosts, nh);
        for (uint64_t seed = 1; seed <= 8 && (seed <= 3 || tally.chains < 8); seed++) {
            p.seed = seed;
            banyan_ivy *iv = grow(&p, H, 380);
            if (!iv) continue;
            char what[64];
            snprintf(what, sizeof what, "pillar seed %llu", (unsigned long long)seed);
            invariants(iv, what);
            sag_check(iv, &tally);
            banyan_ivy_free(iv);
        }
        banyan_hosts_free(H);
    }
    /* An oriented host: a wall turned 30 deg about Z and leaning 10 deg,
     * and a tilted slab across its foot. */
    {
        banyan_box hb[2];
        m3 r1 = m3_rotation(v3_make(0, 0, 1), deg2rad(30)), r2 = m3_rotation(v3_make(1, 0, 0), deg2rad(10));
        m3 r = m3_mul(&r1, &r2);
        hb[0] = banyan_box_make(0, 0.1, 1.0, 1.0, 0.1, 1.0);
        memcpy(hb[0].rotation, r.m, sizeof r.m);
        hb[1] = banyan_box_make(0.5, -0.4, 0.1, 0.6, 0.3, 0.05);
        m3 r3 = m3_rotation(v3_norm(v3_make(1, 1, 0)), deg2rad(15));
        memcpy(hb[1].rotation, r3.m, sizeof r3.m);
        banyan_ivy_params_init(&p);
        p.start[0] = 0;
        p.start[1] = -0.2;
        p.start[2] = 0.8;
        banyan_hosts *H = TEST_HOSTS(hb, 2);
        for (uint64_t seed = 1; seed <= 2; seed++) {
            p.seed = seed;
            banyan_ivy *iv = grow(&p, H, 220);
            if (!iv) continue;
            char what[64];
            snprintf(what, sizeof what, "oriented hosts seed %llu", (unsigned long long)seed);
            CHECK(iv->n > 500, "%s: only %d buds", what, iv->n);
            invariants(iv, what);
            banyan_ivy_free(iv);
        }
        banyan_hosts_free(H);
    }
    printf("free hanging stems: %d, drooping %d, tips up %d, moment held %d\n", tally.chains, tally.droop,
           tally.tip_up, tally.moment_ok);
    CHECK(tally.chains >= 5, "only %d long free stems: the sag check is not exercised", tally.chains);
    CHECK(tally.droop == tally.chains, "%d of %d long free stems do not hang below their anchor", tally.chains - tally.droop,
          tally.chains);
    CHECK(tally.tip_up == tally.chains, "%d of %d free tips do not point up", tally.chains - tally.tip_up, tally.chains);
    CHECK(tally.moment_ok == tally.chains, "%d of %d free stems exceed moment_max about their anchor",
          tally.chains - tally.moment_ok, tally.chains);
}

static int32_t attr_index(const banyan_mesh *m, const char *name) {
    for (uint32_t a = 0; a < m->attribute_count; a++)
        if (!strcmp(m->attributes[a].name, name)) return (int32_t)a;
    return -1;
}

static void test_mesh(const char *outdir) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    banyan_box w = wall_box();
    banyan_mesh *m = NULL, *m2 = NULL;
    banyan_error err0;
    /* Zero steps: the leading stems' first buds alone still make a mesh. */
    p.steps = 0;
    CHECK(test_ivy_boxes(&p, &w, 1, &m, &err0) == BANYAN_OK && m && m->vertex_count > 0 &&
              m->skel_point_count == (uint32_t)p.start_stems,
          "zero steps: %s", err0.message);
    banyan_mesh_free(m);
    m = NULL;
    p.steps = 200;
    banyan_error err;
    CHECK(test_ivy_boxes(&p, &w, 1, &m, &err) == BANYAN_OK, "generate: %s", err.message);
    CHECK(test_ivy_boxes(&p, &w, 1, &m2, &err) == BANYAN_OK, "generate again: %s", err.message);
    if (!m || !m2) return;
    CHECK(banyan_mesh_hash(m) == banyan_mesh_hash(m2), "same seed, different bytes");
    banyan_mesh_free(m2);

    /* Stepping in pieces is the same plant. */
    banyan_ivy *iv = NULL;
    banyan_hosts *W = TEST_HOSTS(&w, 1);
    CHECK(banyan_ivy_create(&p, W, &iv, &err) == BANYAN_OK, "create: %s", err.message);
    int32_t pieces[4] = {1, 49, 0, 150};
    for (int k = 0; k < 4 && iv; k++) banyan_ivy_step(iv, pieces[k], &err);
    m2 = NULL;
    if (iv) banyan_ivy_mesh(iv, &m2, &err);
    CHECK(m2 && banyan_mesh_hash(m2) == banyan_mesh_hash(m), "steps 1+49+0+150 differ from 200 at once");
    /* A stem vertex carries the birth step of a bud it was swept around
     * (a branch's base ring, in its parent, that of the branch's bud); so
     * does a petiole's first ring (the last 6 vertices per blade of part 0,
     * 3 at its bud then 3 at its blade). */
    int32_t ab2 = m2 ? attr_index(m2, "birth_step") : -1;
    double *wood_r = iv ? malloc(sizeof(double) * (size_t)iv->n) : NULL;
    v3 *wood_P = iv ? malloc(sizeof(v3) * (size_t)iv->n) : NULL;
    if (iv && ab2 >= 0 && m2->part_count == 2 && wood_r && wood_P && ivy_wood(iv, wood_r, wood_P) == BANYAN_OK) {
        int bad = 0, tried = 0;
        const banyan_part *sp = &m2->parts[0];
        uint32_t pet0 = sp->vertex_offset + sp->vertex_count - 6 * (m2->parts[1].vertex_count / 13);
        for (uint32_t v = sp->vertex_offset; v < sp->vertex_offset + sp->vertex_count; v += 37) {
            if (v >= pet0 && (v - pet0) % 6 >= 3) continue; /* a petiole's blade end */
            v3 q = v3_make(m2->positions[3 * v], m2->positions[3 * v + 1], m2->positions[3 * v + 2]);
            int32_t b = (int32_t)m2->attributes[ab2].data[v];
            int ok = 0;
            for (int32_t i = 0; i < iv->n && !ok; i++) {
                /* A ring at a sharp bend reaches out up to 5 radii (tube.c's stretch cap). */
                const double reach = 5 * (wood_r[i] > p.stem_radius_max ? wood_r[i] : p.stem_radius_max) + 1e-4;
                ok = iv->buds[i].step_c == b &&
                     (v3_dist(wood_P[i], q) < reach || /* a branch's base ring: */
                      (iv->buds[i].parent >= 0 && v3_dist(wood_P[iv->buds[i].parent], q) < reach));
            }
            tried++;
            bad += !ok;
        }
        CHECK(tried > 50 && bad == 0, "%d of %d stem vertices with a birth_step of no bud they surround", bad, tried);
    }
    free(wood_r);
    free(wood_P);
    banyan_mesh_free(m2);
    banyan_ivy_free(iv);
    banyan_hosts_free(W);
    p.seed = 2;
    CHECK(test_ivy_boxes(&p, &w, 1, &m2, &err) == BANYAN_OK && banyan_mesh_hash(m2) != banyan_mesh_hash(m),
          "seed 2 gave the same mesh as seed 1");
    banyan_mesh_free(m2);
    p.seed = 1;

    CHECK(m->material_count == 2 && !strcmp(m->materials[0].name, "ivy_stem") && !strcmp(m->materials[1].name, "ivy_leaf") &&
              m->materials[1].double_sided == 1 && m->materials[0].double_sided == 0,
          "materials ivy_stem and ivy_leaf (double-sided)");
    CHECK(m->part_count == 2 && m->parts[0].material == 0 && m->parts[1].material == 1, "%u parts", m->part_count);
    int32_t ab = attr_index(m, "birth_step"), ap = attr_index(m, "part");
    CHECK(ab >= 0 && ap >= 0, "attributes birth_step and part");
    if (ab >= 0 && ap >= 0 && m->part_count == 2) {
        int bad_part = 0, bad_birth = 0, bad_normal = 0, bad_face = 0, leaves = 0;
        for (uint32_t q = 0; q < 2; q++) {
            const banyan_part *pt = &m->parts[q];
            for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count; v++) {
                if (m->attributes[ap].data[v] != (float)q) bad_part++;
                float b = m->attributes[ab].data[v];
                if (!(b >= 0 && b <= p.steps && b == floorf(b))) bad_birth++;
                const float *n = m->normals + 3 * v;
                if (fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-4) bad_normal++;
            }
        }
        /* Leaf blades in front of the wall (its face is y = 0, outward -y)
         * face out, within 60 deg of its normal, and are tilted off it,
         * not flat (vertex 0, the blade's centre, carries the blade's
         * normal). */
        const banyan_part *lp = &m->parts[1];
        for (uint32_t v = lp->vertex_offset; v < lp->vertex_offset + lp->vertex_count; v += 13) {
            leaves++;
            const float *pos = m->positions + 3 * v, *n = m->normals + 3 * v;
            if (pos[1] < 0.0f && pos[1] > -0.3f && pos[2] > 0.1f && pos[2] < 2.9f && fabsf(pos[0]) < 1.4f &&
                !(n[1] < -0.5f && n[1] > -0.9995f))
                bad_face++;
        }
        CHECK(bad_part == 0, "%d vertices with a part attribute not matching their part", bad_part);
        CHECK(bad_birth == 0, "%d vertices with birth_step outside [0, steps]", bad_birth);
        CHECK(bad_normal == 0, "%d normals not unit", bad_normal);
        CHECK(leaves > 100 && bad_face * 20 < leaves, "%d of %d wall leaves face into the wall or lie flat on it",
              bad_face, leaves);
        int bad_tri = 0;
        for (uint32_t q = 0; q < 2; q++)
            for (uint32_t t = m->parts[q].index_offset; t < m->parts[q].index_offset + m->parts[q].index_count; t++)
                if (m->indices[t] < m->parts[q].vertex_offset ||
                    m->indices[t] >= m->parts[q].vertex_offset + m->parts[q].vertex_count)
                    bad_tri++;
        CHECK(bad_tri == 0, "%d indices outside their part", bad_tri);
    }
    CHECK(m->skel_point_count > 100 && m->skel_edge_count == m->skel_point_count - (uint32_t)p.start_stems,
          "skeleton %u points %u edges (one root per leading stem)", m->skel_point_count, m->skel_edge_count);
    int bad_tag = 0;
    for (uint32_t i = 0; i < m->skel_point_count; i++)
        if (m->skel_tag[i] < 0 || m->skel_tag[i] > 4 || !(m->skel_radius[i] > 0)) bad_tag++;
    CHECK(bad_tag == 0, "%d skeleton points with bad tag or radius", bad_tag);
    char path[1024];
    snprintf(path, sizeof path, "%s/ivy_wall_200.glb", outdir);
    CHECK(banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write: %s", err.message);
    banyan_mesh_free(m);

    /* Without leaves: one part. */
    p.leaves = 0;
    CHECK(test_ivy_boxes(&p, &w, 1, &m, &err) == BANYAN_OK && m->part_count == 1, "leaves off");
    banyan_mesh_free(m);
}

/* The mesh on any number of threads is the one-thread mesh, byte for
 * byte: its stems and leaves are planned, then written into disjoint
 * ranges. A plant large enough that the threads are used. */
/* years: 0 grows `steps`; years x shoot_growth / internode steps else,
 * rounded to the nearest, the same plant as those steps. */
static void test_years(void) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    CHECK(p.years == 0 && banyan_ivy_steps(&p) == p.steps, "years 0: %d steps, want %d", banyan_ivy_steps(&p), p.steps);
    p.years = 2, p.shoot_growth = 1.5, p.internode = 0.03, p.steps = 7;
    CHECK(banyan_ivy_steps(&p) == 100, "2 years at 1.5 m / 0.03 m: %d steps, want 100", banyan_ivy_steps(&p));
    p.years = 0.0101; /* 0.505 steps: the nearest is 1 */
    CHECK(banyan_ivy_steps(&p) == 1, "0.0101 years: %d steps, want 1", banyan_ivy_steps(&p));
    banyan_box w = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    banyan_mesh *a = NULL, *b = NULL;
    banyan_error err;
    banyan_ivy_params q = p;
    p.years = 1.2; /* 60 steps */
    q.years = 0, q.steps = 60;
    CHECK(test_ivy_boxes(&p, &w, 1, &a, &err) == BANYAN_OK, "years 1.2: %s", err.message);
    CHECK(test_ivy_boxes(&q, &w, 1, &b, &err) == BANYAN_OK, "steps 60: %s", err.message);
    CHECK(a && b && banyan_mesh_hash(a) == banyan_mesh_hash(b), "1.2 years and 60 steps differ");
    banyan_mesh_free(a);
    banyan_mesh_free(b);
}

/* The frayed edges: ivy_edge_distance on box faces (a face's edge, one on
 * the ground, a seam where a second box carries the face on), and blades
 * standing past the wall's outline with edge_fray and not without. */
static void test_edges(void) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    p.steps = 0;
    banyan_box two[2] = {banyan_box_make(-0.75, 0.1, 1.5, 0.75, 0.1, 1.5), banyan_box_make(0.75, 0.1, 1.5, 0.75, 0.1, 1.5)};
    banyan_ivy *iv = NULL;
    banyan_error err;
    banyan_hosts *H = TEST_HOSTS(two, 2);
    CHECK(banyan_ivy_create(&p, H, &iv, &err) == BANYAN_OK, "create: %s", err.message);
    if (iv) {
        v3 out = v3_make(0, 0, 0);
        double e = ivy_edge_distance(iv, ivy_nearest_any(iv, v3_make(1.4, -0.01, 1.5)), 0.3, &out);
        CHECK(fabs(e - 0.1) < 1e-9 && out.x == 1, "right edge: %g, out (%g, %g, %g)", e, out.x, out.y, out.z);
        e = ivy_edge_distance(iv, ivy_nearest_any(iv, v3_make(0.8, -0.01, 2.9)), 0.3, &out);
        CHECK(fabs(e - 0.1) < 1e-9 && out.z == 1, "top edge: %g", e);
        e = ivy_edge_distance(iv, ivy_nearest_any(iv, v3_make(0.8, -0.01, 1.5)), 0.3, &out);
        CHECK(e == HUGE_VAL, "face centre: %g", e);
        e = ivy_edge_distance(iv, ivy_nearest_any(iv, v3_make(0.05, -0.01, 1.5)), 0.3, &out);
        CHECK(e == HUGE_VAL, "the seam between the boxes is no edge: %g", e);
        e = ivy_edge_distance(iv, ivy_nearest_any(iv, v3_make(0.8, -0.01, 0.05)), 0.3, &out);
        CHECK(p.ground && e == HUGE_VAL, "the edge on the ground is no edge: %g", e);
        banyan_ivy_free(iv);
    }
    banyan_hosts_free(H);
    banyan_box w = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    int past[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        banyan_ivy_params q;
        banyan_ivy_params_init(&q);
        q.edge_fray = k ? 0.2 : 0;
        banyan_mesh *m = NULL;
        CHECK(test_ivy_boxes(&q, &w, 1, &m, &err) == BANYAN_OK, "edge_fray %g: %s", q.edge_fray, err.message);
        if (!m || m->part_count < 2) continue;
        const banyan_part *lp = &m->parts[1];
        for (uint32_t v = lp->vertex_offset; v < lp->vertex_offset + lp->vertex_count; v += 13) /* blade centres */
            past[k] += m->positions[3 * v + 1] < -0.01 && /* before the front face, past its outline */
                       (fabs(m->positions[3 * v]) > 1.52 || m->positions[3 * v + 2] > 3.02);
        banyan_mesh_free(m);
    }
    CHECK(4 * past[1] > 5 * past[0] && past[1] > past[0] + 100, "blades past the outline: %d with edge_fray 0.2, %d without", past[1], past[0]);
    printf("  blades past the wall's outline: %d with edge_fray 0.2, %d without\n", past[1], past[0]);
}

static void test_mesh_threads(void) {
    banyan_ivy_params p;
    banyan_box hosts[8];
    uint32_t nh = 0;
    if (!load_preset("ivy_wall", &p, hosts, &nh)) return;
    p.steps = 320;
    banyan_hosts *H = TEST_HOSTS(hosts, nh);
    banyan_ivy *iv = grow(&p, H, p.steps);
    if (!iv) {
        banyan_hosts_free(H);
        return;
    }
    CHECK(iv->n > 8000, "only %d buds: too few for the threads to share the mesh", iv->n);
    const int32_t counts[] = {2, 3, 0, 16};
    for (int variant = 0; variant < 3; variant++) {
        iv->p.leaves = variant != 1;
        iv->p.wind = variant != 2;
        banyan_error err;
        banyan_mesh *one = NULL;
        iv->p.threads = 1;
        CHECK(banyan_ivy_mesh(iv, &one, &err) == BANYAN_OK, "1 thread: %s", err.message);
        for (int k = 0; k < 4 && one; k++) {
            banyan_mesh *m = NULL;
            iv->p.threads = counts[k];
            CHECK(banyan_ivy_mesh(iv, &m, &err) == BANYAN_OK, "%d threads: %s", counts[k], err.message);
            CHECK(m && banyan_mesh_hash(m) == banyan_mesh_hash(one) && m->vertex_count == one->vertex_count,
                  "leaves %d, wind %d: %d threads (0: all cores) give other bytes than one", iv->p.leaves, iv->p.wind,
                  counts[k]);
            banyan_mesh_free(m);
        }
        banyan_mesh_free(one);
    }
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
}

static void test_bad_input(void) {
    banyan_ivy_params p;
    banyan_box w = wall_box();
    banyan_hosts *W = TEST_HOSTS(&w, 1);
    banyan_error err;
    banyan_mesh *m;
    banyan_ivy *iv;
#define REFUSED(code, needle, hosts_)                                                                    \
    do {                                                                                                  \
        m = (banyan_mesh *)&err;                                                                         \
        banyan_status s_ = banyan_ivy_generate(&p, hosts_, &m, NULL, NULL, &err);                         \
        CHECK(s_ == (code) && m == NULL && strstr(err.message, needle), "want %s with '%s', got %s: %s", \
              banyan_status_name(code), needle, banyan_status_name(s_), err.message);                    \
        banyan_ivy_params_init(&p);                                                                       \
    } while (0)
    banyan_ivy_params_init(&p);
    p.t1 = 0.5;
    p.t2 = 0.3;
    REFUSED(BANYAN_E_RANGE, "t2 = 0.3 must be >= t1 = 0.5", W);
    p.alpha = 0.4;
    REFUSED(BANYAN_E_RANGE, "alpha = 0.4 must be within [0.5, 1]", W);
    p.alpha = 1.2;
    REFUSED(BANYAN_E_RANGE, "alpha = 1.2 must be within [0.5, 1]", W);
    p.steps = BANYAN_IVY_MAX_STEPS + 1;
    REFUSED(BANYAN_E_RANGE, "steps = 100001 must be within [0, 100000]", W);
    p.years = 1000, p.shoot_growth = 10, p.internode = 0.01;
    REFUSED(BANYAN_E_RANGE, "years = 1000 gives 1000000 steps", W);
    p.years = -1;
    REFUSED(BANYAN_E_RANGE, "years", W);
    p.years = NAN;
    REFUSED(BANYAN_E_RANGE, "years", W);
    CHECK(banyan_ivy_steps(NULL) == -1, "banyan_ivy_steps(NULL)");
    {   /* Before any check: a negative rate or internode is -1, no overflow. */
        banyan_ivy_params q = p;
        q.years = 2, q.shoot_growth = -1e60, q.internode = 0.03;
        CHECK(banyan_ivy_steps(&q) == -1, "banyan_ivy_steps with shoot_growth -1e60: %d", banyan_ivy_steps(&q));
        q.shoot_growth = 1.5, q.internode = -1e-300;
        CHECK(banyan_ivy_steps(&q) == -1, "banyan_ivy_steps with internode -1e-300: %d", banyan_ivy_steps(&q));
    }
    p.threads = -1;
    REFUSED(BANYAN_E_RANGE, "threads = -1 must be within [0, 64]", W);
    p.threads = BANYAN_IVY_MAX_THREADS + 1;
    REFUSED(BANYAN_E_RANGE, "threads = 65 must be within [0, 64]", W);
    p.start[0] = 10;
    REFUSED(BANYAN_E_START_FAR, "start_snap_max", W);
    p.t0 = NAN;
    REFUSED(BANYAN_E_RANGE, "t0", W);
    p.internode = -1;
    REFUSED(BANYAN_E_RANGE, "internode", W);
    p.stem_radius_max = 0.0001;
    REFUSED(BANYAN_E_RANGE, "stem_radius_max", W);
    p.max_vertices = 1000;
    REFUSED(BANYAN_E_LIMIT, "max_vertices", W);
    p.max_buds = 20;
    REFUSED(BANYAN_E_LIMIT, "max_buds", W);
    REFUSED(BANYAN_E_INVALID_ARG, "hosts is NULL", NULL);
    CHECK(banyan_ivy_generate(&p, W, NULL, NULL, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL out accepted");
    CHECK(banyan_ivy_generate(NULL, W, &m, NULL, NULL, &err) == BANYAN_E_INVALID_ARG && m == NULL,
          "NULL params accepted");
#undef REFUSED
    /* The stepping calls. */
    iv = (banyan_ivy *)&err;
    p.t2 = 0.1;
    CHECK(banyan_ivy_create(&p, W, &iv, &err) == BANYAN_E_RANGE && iv == NULL, "create with t2 < t1");
    banyan_ivy_params_init(&p);
    CHECK(banyan_ivy_create(&p, W, &iv, &err) == BANYAN_OK, "create: %s", err.message);
    CHECK(banyan_ivy_step(iv, BANYAN_IVY_MAX_STEPS + 1, &err) == BANYAN_E_RANGE && strstr(err.message, "100000"),
          "step above the cap: %s", err.message);
    CHECK(banyan_ivy_step(iv, -1, &err) == BANYAN_E_RANGE, "negative step");
    CHECK(banyan_ivy_step(NULL, 1, &err) == BANYAN_E_INVALID_ARG, "NULL handle");
    CHECK(banyan_ivy_get_stats(iv, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL stats");
    CHECK(banyan_ivy_mesh(NULL, &m, &err) == BANYAN_E_INVALID_ARG && m == NULL, "NULL handle mesh");
    banyan_ivy_free(iv);
    banyan_ivy_free(NULL);
    /* max_buds stops stepping before the limit; the plant stays usable. */
    p.max_buds = 200;
    CHECK(banyan_ivy_create(&p, W, &iv, &err) == BANYAN_OK, "create: %s", err.message);
    banyan_status s = banyan_ivy_step(iv, 450, &err);
    CHECK(s == BANYAN_E_LIMIT && iv->n <= 200 && strstr(err.message, "max_buds = 200"), "max_buds: %s", err.message);
    m = NULL;
    CHECK(banyan_ivy_mesh(iv, &m, &err) == BANYAN_OK && m, "mesh after a refused step: %s", err.message);
    banyan_mesh_free(m);
    banyan_ivy_free(iv);
    /* The start inside a host snaps out to its surface. */
    banyan_ivy_params_init(&p);
    p.start[1] = 0.03; /* inside, nearer the front face y = 0 */
    p.start[2] = 1.0;
    CHECK(banyan_ivy_create(&p, W, &iv, &err) == BANYAN_OK && fabs(iv->buds[0].P.y + p.clearance) < 1e-9,
          "start inside the wall: %s", err.message);
    banyan_ivy_free(iv);
    banyan_hosts_free(W);
}

/* One presets/ivy_*.json: it loads, has hosts and generates; the pillar
 * scene also goes to the validator. */
static void ivy_preset(const char *path, const char *name, void *ctx) {
    (void)path;
    banyan_ivy_params p;
    banyan_box hosts[8];
    uint32_t nh = 0;
    if (!load_preset(name, &p, hosts, &nh)) return;
    CHECK(nh >= 1, "%s has no hosts", name);
    /* A *_large preset is a benchmark (ivy_wall_large: 250k buds, 7 M
     * vertices): checked here on its first 300 steps. */
    size_t len = strlen(name);
    if (len > 6 && !strcmp(name + len - 6, "_large") && p.steps > 300) p.steps = 300;
    banyan_mesh *m = NULL;
    banyan_error err;
    banyan_status s = test_ivy_boxes(&p, hosts, nh, &m, &err);
    CHECK(s == BANYAN_OK && m && m->vertex_count > 0, "%s: %s", name, err.message);
    if (m && !strcmp(name, "ivy_pillar")) {
        char out[1024];
        snprintf(out, sizeof out, "%s/ivy_pillar.glb", (const char *)ctx);
        CHECK(banyan_gltf_write(out, (const banyan_mesh *const *)&m, NULL, 1, &err) == BANYAN_OK, "write: %s",
              err.message);
    }
    banyan_mesh_free(m);
}

static void test_presets(const char *outdir) {
    int n = test_each_preset(BANYAN_SOURCE_DIR "/presets", "ivy_", ivy_preset, (void *)outdir);
    CHECK(n >= 4, "found %d presets/ivy_*.json", n);
}

int main(int argc, char **argv) {
    const char *outdir = argc > 1 ? argv[1] : ".";
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    banyan_error err;
    CHECK(banyan_params_check(BANYAN_GEN_IVY, &p, &err) == BANYAN_OK, "defaults fail their table: %s", err.message);
    CHECK(banyan_param_count(BANYAN_GEN_IVY) > 30, "ivy table has %d rows", banyan_param_count(BANYAN_GEN_IVY));
    CHECK(p.internode == 0.03 && p.sucker_length == 0.03 && p.leaf_max == 0.06 && p.t1 == 0.2 && p.t2 == 2.0 &&
              p.alpha == 0.8 && p.beta == 0.05 && p.t0 == 20 && p.steps == 450 && p.gravity == 9.8,
          "defaults are not the paper's Table 3");
    CHECK(banyan_sizeof_ivy_params() == sizeof(banyan_ivy_params), "sizeof");
    test_bad_input();
    test_nourishment();
    test_light_and_stats();
    test_scenes();
    test_mesh(outdir);
    test_mesh_threads();
    test_years();
    test_edges();
    test_presets(outdir);
    return check_done("test_ivy");
}
