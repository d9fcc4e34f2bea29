/* keyaki_trunk: the trunk's root flare and the bark uvs (docs/keyaki.md
 * "Trunk: flare and bark"). Over models and seeds: the ground
 * ring's mean radius is (1 + flare) x the trunk's, the mean radius falls
 * monotonically to the trunk's by flare_height, the ground ring has
 * flare_lobes maxima round it (none with 0 lobes), normals face out,
 * flare 0 gives the plain trunk ring; every tube wraps a whole number of
 * bark tiles (tube_bark_tiles of its first branch's radius), the trunk's
 * texels are square and a tile spans bark_tile; no NaN; the plan's counts
 * are exact; the flare leaves the skeleton alone; same seed same bytes;
 * a leaning trunk's sunk ring stays under the ground. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh/tube.h"
#include "keyaki/keyaki_internal.h"

typedef struct trunk_mesh {
    banyan_keyaki_params p;
    keyaki_skeleton sk;
    keyaki_body body;
    mesh_builder mb;
} trunk_mesh;

static int build(trunk_mesh *t) {
    memset(&t->sk, 0, sizeof t->sk);
    if (keyaki_grow(&t->p, &t->sk, NULL) != BANYAN_OK) return 0;
    keyaki_strahler(t->sk.nodes, t->sk.count);
    keyaki_radii(t->sk.nodes, t->sk.count, t->p.tip_radius * t->p.unit, t->p.pipe_exponent);
    if (keyaki_body_plan(&t->p, t->sk.nodes, t->sk.count, 0, NULL, &t->body, NULL) != BANYAN_OK) return 0;
    mb_init(&t->mb, 1u << 26, 0);
    int attr[3] = {mb_add_attr(&t->mb, "tree_id"), mb_add_attr(&t->mb, "level"), mb_add_attr(&t->mb, "order")};
    keyaki_body_mesh(&t->p, t->sk.nodes, t->sk.count, &t->body, &t->mb, attr, 0, 0, 0, 0);
    return 1;
}

static void release(trunk_mesh *t) {
    mb_free(&t->mb);
    keyaki_body_free(&t->body);
    keyaki_skeleton_free(&t->sk);
}

static v3 vert(const mesh_builder *mb, uint32_t v) {
    const float *q = mb->pos + 3 * (size_t)v;
    return v3_make(q[0], q[1], q[2]);
}

/* Ring r of the trunk: its height s along the trunk's axis, each vertex's
 * distance from the axis (rho, sides of them) and their mean. */
static double trunk_ring(const trunk_mesh *t, int32_t r, double *s, double *rho) {
    const keyaki_node *x = &t->sk.nodes[0];
    int sides = t->body.limbs[0].sides;
    uint32_t v0 = t->body.limbs[0].vertex_offset + (uint32_t)r * (uint32_t)(sides + 1);
    double sum = 0, ss = 0;
    for (int j = 0; j < sides; j++) {
        v3 d = v3_sub(vert(&t->mb, v0 + (uint32_t)j), x->start);
        double a = v3_dot(d, x->dir);
        ss += a;
        rho[j] = v3_len(v3_madd(d, x->dir, -a));
        sum += rho[j];
    }
    *s = ss / sides;
    return sum / sides;
}

/* Local maxima of a closed ring of values (a plateau counts once). */
static int maxima(const double *r, int n) {
    int c = 0;
    for (int j = 0; j < n; j++)
        c += r[j] > r[(j + n - 1) % n] && r[j] >= r[(j + 1) % n];
    return c;
}

/* The child a limb continues into (body.c's main_child). */
static int32_t main_of(const keyaki_node *n, int32_t i) {
    int32_t a = n[i].child[0], b = n[i].child[1];
    if (a < 0) return b;
    if (b < 0) return a;
    return n[b].radius > n[a].radius ? b : a;
}

static int finite_mesh(const mesh_builder *mb) {
    int bad = 0;
    for (uint32_t v = 0; v < mb->nv; v++) {
        for (int k = 0; k < 3; k++) bad += !isfinite(mb->pos[3 * v + k]) || !isfinite(mb->nrm[3 * v + k]);
        for (int k = 0; k < 2; k++) bad += !isfinite(mb->uv[2 * v + k]);
    }
    return bad;
}

/* The flare's shape, normals and counts on one tree. */
static void flare_shape_check(uint64_t seed, int model, double flare, int lobes) {
    trunk_mesh t;
    banyan_keyaki_params_init(&t.p);
    t.p.seed = seed;
    t.p.model = model;
    if (model == BANYAN_KEYAKI_SIMPLE) t.p.levels = 6;
    t.p.flare = flare;
    t.p.flare_lobes = lobes;
    if (!build(&t)) {
        CHECK(0, "build seed %llu model %d", (unsigned long long)seed, model);
        release(&t);
        return;
    }
    CHECK(t.mb.status == BANYAN_OK && t.mb.nv == t.body.vertices && t.mb.ni == t.body.indices,
          "plan %u/%u vs mesh %u/%u", t.body.vertices, t.body.indices, t.mb.nv, t.mb.ni);
    CHECK(finite_mesh(&t.mb) == 0, "seed %llu: NaN or inf in the mesh", (unsigned long long)seed);
    const keyaki_node *x = &t.sk.nodes[0];
    const double r0 = x->radius, h = fmin(t.p.flare_height * t.p.unit, 0.8 * x->length);
    const keyaki_limb *L = &t.body.limbs[0];
    const int want_lobes = flare > 0 ? lobes : 0;
    double rho[256], s, prev = INFINITY;
    int ground = -1, rising = 0, flare_rings = 0, bad_normals = 0;
    double at_h = -1, ground_mean = 0;
    for (int32_t r = 0; r < L->points; r++) {
        double mean = trunk_ring(&t, r, &s, rho);
        if (s > x->length + 1e-9) break;
        if (fabs(s) < 1e-5 * (1 + h)) {
            ground = r;
            ground_mean = mean;
            if (want_lobes > 0)
                CHECK(maxima(rho, L->sides) == want_lobes,
                      "seed %llu flare %g: %d maxima round the ground ring, want %d", (unsigned long long)seed, flare,
                      maxima(rho, L->sides), want_lobes);
            else {
                double lo = rho[0], hi = rho[0];
                for (int j = 1; j < L->sides; j++) lo = fmin(lo, rho[j]), hi = fmax(hi, rho[j]);
                CHECK(hi - lo < 1e-5 * r0, "lobes 0: ground ring not round (%g .. %g)", lo, hi);
            }
        }
        const double tol = 1e-5 * (1 + h); /* float positions */
        if (s >= -tol && s <= h + tol) {
            flare_rings++;
            rising += mean > prev * (1 + 1e-6);
            prev = mean;
            if (fabs(s - h) < tol) at_h = mean;
        }
        /* Inner rings of the foot: each normal is unit and close to the
         * surface's, from central differences round and along. */
        int sides = L->sides;
        uint32_t ring = (uint32_t)(sides + 1), v0 = L->vertex_offset + (uint32_t)r * ring;
        for (int j = 0; j < sides && r > 0 && s < h - 1e-3; j++) {
            uint32_t a = v0 + (uint32_t)(j + sides - 1) % (uint32_t)sides, b = v0 + (uint32_t)(j + 1);
            v3 round = v3_sub(vert(&t.mb, b), vert(&t.mb, a));
            v3 along = v3_sub(vert(&t.mb, v0 + ring + (uint32_t)j), vert(&t.mb, v0 - ring + (uint32_t)j));
            v3 fd = v3_norm(v3_cross(round, along));
            const float *nn = t.mb.nrm + 3 * (size_t)(v0 + (uint32_t)j);
            v3 nv = v3_make(nn[0], nn[1], nn[2]);
            bad_normals += fabs(v3_len(nv) - 1) > 1e-4 || v3_dot(nv, fd) < 0.9;
        }
    }
    CHECK(bad_normals == 0, "seed %llu flare %g lobes %d: %d trunk normals not facing out", (unsigned long long)seed,
          flare, lobes, bad_normals);
    CHECK(ground >= 0, "no ring at the ground");
    CHECK(fabs(ground_mean / r0 - (1 + flare)) < 0.1 * (1 + flare), "ground ring %g x the trunk, want %g",
          ground_mean / r0, 1 + flare);
    if (flare > 0) {
        CHECK(flare_rings >= 6 && rising == 0, "flare: %d rings, %d rising", flare_rings, rising);
        CHECK(fabs(at_h - r0) < 1e-3 * r0, "flare: %g at flare_height, trunk %g", at_h, r0);
        CHECK(ground == 1, "flare: the ground ring is ring %d, want 1 (one sunk below)", ground);
        double s0;
        trunk_ring(&t, 0, &s0, rho);
        CHECK(s0 < -0.05 * r0, "flare: the lowest ring is %g below the ground, want a few cm", -s0);
    } else {
        CHECK(ground == 0 && fabs(ground_mean - r0) < 1e-5 * r0, "flare 0: ground ring %d radius %g, trunk %g",
              ground, ground_mean, r0);
    }
    release(&t);
}

/* The flare changes the trunk's mesh only: the skeleton is the same, and
 * flare 0 has exactly the rings of a tree without one. */
static void flare_leaves_growth(void) {
    trunk_mesh a, b;
    banyan_keyaki_params_init(&a.p);
    a.p.seed = 77;
    b.p = a.p;
    b.p.flare = 0;
    CHECK(build(&a) && build(&b), "build");
    CHECK(a.sk.count == b.sk.count && !memcmp(a.sk.nodes, b.sk.nodes, sizeof(keyaki_node) * (size_t)a.sk.count),
          "the flare changed the skeleton");
    CHECK(a.body.limbs[0].points == b.body.limbs[0].points + 9, "flare rings: %d vs %d", a.body.limbs[0].points,
          b.body.limbs[0].points);
    CHECK(b.body.limbs[0].sides == b.p.sides_max, "flare 0: trunk sides %d", b.body.limbs[0].sides);
    /* Beyond the trunk, both meshes are the same bytes. */
    uint32_t ta = a.body.limbs[1].vertex_offset, tb = b.body.limbs[1].vertex_offset, n = a.mb.nv - ta;
    CHECK(b.mb.nv - tb == n && !memcmp(a.mb.pos + 3 * (size_t)ta, b.mb.pos + 3 * (size_t)tb, 12 * (size_t)n) &&
              !memcmp(a.mb.uv + 2 * (size_t)ta, b.mb.uv + 2 * (size_t)tb, 8 * (size_t)n),
          "the flare changed other limbs");
    release(&a);
    release(&b);
}

/* Bark uvs: on every tube at least bark_flake_radius thick u wraps
 * tube_bark_tiles(radius of its first branch) whole tiles, on every
 * thinner one it runs once over the smooth lane (U0 .. U1), and a flaking
 * limb turns smooth (for good) where, and only where, its chain thins
 * past the radius; both kinds of tube occur; on the trunk above the flare texels are square and a tile spans
 * bark_tile +- 30 %. */
static void bark_uvs(uint64_t seed, double unit, double tile, double flare) {
    trunk_mesh t;
    banyan_keyaki_params_init(&t.p);
    t.p.seed = seed;
    t.p.unit = unit;
    t.p.bark_tile = tile;
    t.p.flare = flare;
    if (!build(&t)) {
        CHECK(0, "build");
        release(&t);
        return;
    }
    int bad_k = 0, ones = 0, many = 0, smooth = 0, flaky = 0;
    for (int32_t k = 0; k < t.body.limb_count; k++) {
        const keyaki_limb *L = &t.body.limbs[k];
        int want = tube_bark_tiles(t.sk.nodes[L->first].radius, tile);
        int lane = t.sk.nodes[L->first].radius < t.p.bark_flake_radius, thin = 0;
        for (int32_t j = L->first; j >= 0; j = main_of(t.sk.nodes, j)) thin |= t.sk.nodes[j].radius < t.p.bark_flake_radius;
        int was_lane = lane, lane_rings = 0;
        for (int32_t r = 0; r < L->points; r++) {
            const float *uv = t.mb.uv + 2 * (size_t)(L->vertex_offset + (uint32_t)r * (uint32_t)(L->sides + 1));
            int on = fabsf(uv[0] - BANYAN_KEYAKI_BARK_SMOOTH_U0) <= 1e-6f &&
                     fabsf(uv[2 * L->sides] - BANYAN_KEYAKI_BARK_SMOOTH_U1) <= 1e-6f;
            int tiled = uv[0] == 0.0f && uv[2 * L->sides] == (float)want;
            /* A flaking limb turns smooth once, never back. */
            bad_k += !(on || tiled) || (lane && !on) || (was_lane && !on);
            was_lane |= on;
            lane_rings += on;
        }
        bad_k += thin != (lane_rings > 0); /* smooth where, and only where, the chain thins past the radius */
        ones += want == 1;
        many += want > 1;
        smooth += lane;
        flaky += !lane;
    }
    CHECK(bad_k == 0, "unit %g tile %g: %d rings whose u does not run 0..k (smooth: U0..U1)", unit, tile, bad_k);
    CHECK((smooth > 0 || unit > 1) && flaky > 0, "unit %g tile %g: %d smooth tubes, %d flaking", unit, tile, smooth,
          flaky); /* at unit 2 even the tips are over bark_flake_radius */
    CHECK(ones > 0 && many > 0, "unit %g tile %g: %d tubes with one tile, %d with more", unit, tile, ones, many);
    /* The trunk: the ring at the top of the first branch and the one
     * below it, both at the trunk's radius. */
    const keyaki_limb *L = &t.body.limbs[0];
    int32_t top = flare > 0 ? 10 : 1; /* flare: 0 sunk, 1 .. 9 from the ground to flare_height */
    int sides = L->sides;
    uint32_t va = L->vertex_offset + (uint32_t)(top - 1) * (uint32_t)(sides + 1), vb = va + (uint32_t)(sides + 1);
    double perim = 0;
    v3 ca = v3_make(0, 0, 0), cb = ca;
    for (int j = 0; j < sides; j++) {
        perim += v3_dist(vert(&t.mb, va + (uint32_t)j), vert(&t.mb, va + (uint32_t)(j + 1) % (uint32_t)sides));
        ca = v3_add(ca, v3_scale(vert(&t.mb, va + (uint32_t)j), 1.0 / sides));
        cb = v3_add(cb, v3_scale(vert(&t.mb, vb + (uint32_t)j), 1.0 / sides));
    }
    double ds = v3_dist(ca, cb), k = t.mb.uv[2 * (size_t)(va + (uint32_t)sides)];
    double dv = t.mb.uv[2 * (size_t)vb + 1] - t.mb.uv[2 * (size_t)va + 1];
    double across = perim / k, along = ds / dv;
    CHECK(fabs(across / along - 1) < 0.05, "unit %g tile %g: trunk texel aspect %g (tile %g across, %g along)", unit,
          tile, across / along, across, along);
    CHECK(fabs(across / tile - 1) < 0.3, "unit %g: trunk tile %g m across, want %g +- 30 %%", unit, across, tile);
    /* On the flare's foot too: across its rings' perimeter, along the
     * slant between them. */
    for (int32_t r = 1; flare > 0 && r <= 8; r++) {
        uint32_t a = L->vertex_offset + (uint32_t)r * (uint32_t)(sides + 1), b = a + (uint32_t)(sides + 1);
        double pa = 0, pb = 0;
        v3 c1 = v3_make(0, 0, 0), c2 = c1;
        for (int j = 0; j < sides; j++) {
            uint32_t jn = (uint32_t)(j + 1) % (uint32_t)sides;
            pa += v3_dist(vert(&t.mb, a + (uint32_t)j), vert(&t.mb, a + jn));
            pb += v3_dist(vert(&t.mb, b + (uint32_t)j), vert(&t.mb, b + jn));
            c1 = v3_add(c1, v3_scale(vert(&t.mb, a + (uint32_t)j), 1.0 / sides));
            c2 = v3_add(c2, v3_scale(vert(&t.mb, b + (uint32_t)j), 1.0 / sides));
        }
        double dz = v3_dist(c1, c2), dr = (pb - pa) / (2 * BANYAN_PI), slant = sqrt(dz * dz + dr * dr);
        double dvf = t.mb.uv[2 * (size_t)b + 1] - t.mb.uv[2 * (size_t)a + 1];
        double asp = (0.5 * (pa + pb) / k) / (slant / dvf);
        CHECK(fabs(asp - 1) < 0.05, "unit %g tile %g: texel aspect %g between foot rings %d and %d", unit, tile, asp, r,
              r + 1);
    }
    CHECK(finite_mesh(&t.mb) == 0, "NaN in the mesh");
    release(&t);
}

static void same_bytes(void) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.seed = 5;
    banyan_mesh *a = NULL, *b = NULL, *c = NULL;
    CHECK(banyan_keyaki_generate(&p, &a, NULL, NULL, NULL) == BANYAN_OK, "gen a");
    CHECK(banyan_keyaki_generate(&p, &b, NULL, NULL, NULL) == BANYAN_OK, "gen b");
    p.flare_lobes = 6;
    CHECK(banyan_keyaki_generate(&p, &c, NULL, NULL, NULL) == BANYAN_OK, "gen c");
    if (a && b && c) {
        CHECK(banyan_mesh_hash(a) == banyan_mesh_hash(b), "same seed, different bytes");
        CHECK(banyan_mesh_hash(a) != banyan_mesh_hash(c), "flare_lobes changes nothing");
    }
    banyan_mesh_free(a);
    banyan_mesh_free(b);
    banyan_mesh_free(c);
}

/* A leaning trunk's foot (with a flare): the sunk ring lies wholly under
 * level ground (the foot's z), so the flare's high side shows no gap. */
static void leaning_foot(double lean, double flare) {
    trunk_mesh t;
    banyan_keyaki_params_init(&t.p);
    t.p.seed = 9;
    t.p.levels = 10;
    t.p.flare = flare;
    t.p.lean = lean;
    t.p.lean_direction = 40;
    if (!build(&t)) {
        CHECK(0, "build");
        release(&t);
        return;
    }
    const keyaki_limb *L = &t.body.limbs[0];
    double top = -1e9, foot = t.p.position[2];
    for (int j = 0; j < L->sides; j++) {
        double z = t.mb.pos[3 * ((size_t)L->vertex_offset + (size_t)j) + 2];
        top = z > top ? z : top;
    }
    CHECK(top < foot, "lean %g flare %g: the sunk ring reaches %g m over the ground", lean, flare, top - foot);
    release(&t);
}

int main(void) {
    static const double flares[] = {0.5, 0.0, 1.2, 3.0};
    static const int lobes[] = {5, 0, 3, 8, 1, 16};
    for (int m = 0; m < 4; m++)
        for (uint64_t s = 1; s <= 4; s++)
            for (int f = 0; f < 4; f++)
                flare_shape_check(s * 31 + (uint64_t)m, m, flares[f], lobes[(s + (uint64_t)f) % 6]);
    flare_leaves_growth();
    bark_uvs(3, 1.0, 0.4, 0.5);
    bark_uvs(4, 1.0, 0.4, 0.0);
    bark_uvs(5, 1.0, 0.25, 0.5);
    bark_uvs(6, 2.0, 0.6, 0.5);
    bark_uvs(7, 1.0, 0.4, 3.0);
    same_bytes();
    leaning_foot(4.0, 0.5);
    leaning_foot(15.0, 1.2);
    leaning_foot(28.0, 3.0);
    return check_done("test_keyaki_trunk");
}
