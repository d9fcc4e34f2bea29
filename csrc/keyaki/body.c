/* body.c - the keyaki's body (spec/keyaki.md, "Body and leaves", beyond
 * the paper): tapered tubes through the shared sweeper, and the crown
 * (crown.c: twigs and leaves) planned and meshed with them.
 *
 * Crack-free forks: every chain of branches that always continues into
 * the thicker child (a "limb") is swept as ONE tube, so a limb bends at a
 * fork without any seam. The other child starts a new limb whose first
 * ring sits inside the parent, set back along its own direction by
 * 0.3 x the parent's radius, with the child's own radius; its tube
 * therefore leaves the parent's surface with no gap and no spike; it
 * starts at 0.75 x its radius there and widens to it at the fork point,
 * so the seam where the tubes cross is short. Pipe
 * radii shrink towards the tips: the ring where branch a ends has a's
 * radius, so each branch tapers from its parent's radius to its own;
 * tips narrow to tip_taper x tip_radius and are capped.
 * Tube sides fall with the radius: sides_min + (sides_max - sides_min)
 * sqrt(r / r_trunk). The crown's twig tubes close the bark part; its
 * leaves (one atlas quad each, leaf_look.h) make the leaf part.
 * Root flare (docs/keyaki.md "Trunk: flare and bark"): the trunk tube
 * gains FLARE_RINGS + 1 rings at its foot, widened by `flare` with a
 * (1 - t)^2 fall-off over flare_height and ridged by flare_lobes
 * buttresses, swept as given rings with their surface's normals. Bark
 * uvs: every tube wraps a whole number of bark_tile-wide tiles round
 * (tube_bark_tiles of its first branch's radius), v in the same tiles; a
 * tube whose first branch is thinner than bark_flake_radius, and every
 * twig, takes its u from the bark texture's smooth lane instead
 * (keyaki_bark_smooth), and so does a flaking limb from one more ring
 * just past its first branch thinner than that on (flake_end): flakes
 * only on the trunk and the old limbs.
 * Everything is counted exactly before meshing (keyaki_body_plan) so the
 * vertex limit is checked before any mesh memory is allocated.
 * Wind and birth (docs/keyaki.md "Wind and growth attributes"), after
 * Pivot Painter 2's sub-objects: a wind branch is what one tube sweeps
 * (a limb continuing into its thicker child keeps its pivot, level and
 * phase), except that the trunk (branch 0 and the trunk pieces below the
 * limbs) is one of its own, level 0; the limbs are level 1, a side
 * branch its parent's + 1; its pivot is where it leaves its parent (a
 * skeleton point). Stiffness ring by ring: (1 - p / P)^1.5, p the path
 * length from the trunk base (as birth), P the tree's longest; a leaf its
 * wood's.
 * Birth: path length from the trunk base along the skeleton, ring by
 * ring, over the tree's longest; a leaf its wood's + LEAF_DELAY. The
 * crown's twigs and the segment twig lines join the mesh's skeleton (tag
 * KEYAKI_SKEL_TWIG), so every pivot lies on it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "textures/leaf_look.h"
#include "base/pool.h"
#include "mesh/tube.h"
#include "keyaki_internal.h"

/* A leaf appears this much (of the tree's growth) after its wood. */
#define LEAF_DELAY 0.03

void keyaki_body_free(keyaki_body *b) {
    if (!b) return;
    free(b->limbs);
    keyaki_crown_free(&b->crown);
    memset(b, 0, sizeof *b);
}

/* The child a limb continues into: the thicker one, child[0] on a tie. */
static int32_t main_child(const keyaki_node *n, int32_t i) {
    int32_t a = n[i].child[0], b = n[i].child[1];
    if (a < 0) return b;
    if (b < 0) return a;
    return n[b].radius > n[a].radius ? b : a;
}

static inline v3 node_end(const keyaki_node *x) { return v3_madd(x->start, x->dir, x->length); }

/* --- root flare --------------------------------------------------------
 * Along the trunk's first branch, s from the ground and t = s / h with h
 * = flare_height (at most 0.8 of the branch): the mean radius is r0 (1 +
 * flare (1 - t)^2) and each ring's radius is modulated by 1 + a cos(lobes
 * theta + phase), a = amp (1 - t)^3 with amp = 0.6 flare / (1 + flare)
 * (at most 2 / lobes): ridges to r0 (1 + 1.6 flare) and hollows to r0 (1 +
 * 0.4 flare) at the ground, so the hollows never dip under the trunk. Rings at t = 0, 1/F,
 * .., 1, and one more sunk 0.15 r0 below the ground (the same curves,
 * carried on) so uneven ground shows no gap. The phase comes from a
 * stream of its own: the growth never sees it. */
#define FLARE_RINGS 8                        /* F: rings from the ground (t = 0) up to t = (F - 1) / F */
#define KEYAKI_STREAM_FLARE 0x666c617265ull /* "flare" */

typedef struct flare_shape {
    double r0, h, sink, flare, amp, phase, t0; /* t0: the sunk ring's shape (its place is sink down) */
    int lobes;
} flare_shape;

/* Extra trunk rings the flare adds (the sunk ring and t = 1/F .. 1). */
static int32_t flare_points(const banyan_keyaki_params *p) { return p->flare > 0 ? FLARE_RINGS + 1 : 0; }

/* Trunk sides: at least 6 a buttress, so each ridge and hollow is round. */
static int trunk_sides(const banyan_keyaki_params *p, int sides) {
    int want = p->flare > 0 && p->flare_lobes > 0 ? 6 * p->flare_lobes : 0;
    return want > sides ? want : sides; /* <= 96 (16 lobes) */
}

static void flare_setup(const banyan_keyaki_params *p, const keyaki_node *trunk, flare_shape *f) {
    f->r0 = trunk->radius;
    f->h = p->flare_height * p->unit;
    if (f->h > 0.8 * trunk->length) f->h = 0.8 * trunk->length;
    f->flare = p->flare;
    f->lobes = p->flare_lobes;
    f->amp = f->lobes > 0 ? 0.6 * p->flare / (1.0 + p->flare) : 0.0;
    /* Many lobes: shallower, so a ridge's flank is at most 2:1 round the
     * trunk (rho_theta / rho = amp lobes) and the rings still sample it. */
    if (f->amp * f->lobes > 2.0) f->amp = 2.0 / f->lobes;
    /* The sunk ring has the shape of the curves carried on to 0.15 r0
     * under the ground (t0); a leaning trunk's sits deeper along its axis,
     * by its widest reach x tan(lean), so its high side stays under level
     * ground too. */
    f->t0 = -0.15 * f->r0 / f->h;
    double w0 = 1.0 - f->t0, reach = f->r0 * (1.0 + f->flare * w0 * w0) * (1.0 + f->amp * w0 * w0 * w0);
    double hz = sqrt(trunk->dir.x * trunk->dir.x + trunk->dir.y * trunk->dir.y);
    f->sink = 0.15 * f->r0 + (trunk->dir.z > 0.1 ? reach * hz / trunk->dir.z : 0.0);
    pcg32 r;
    pcg32_seed(&r, p->seed, KEYAKI_STREAM_FLARE);
    f->phase = rng_uniform(&r) * 2.0 * BANYAN_PI;
}

/* t of flare ring i: ring 0 sunk, ring 1 + i at i / F (i = 0 .. F). */
static double flare_t(const flare_shape *f, int i) { return i == 0 ? -f->sink / f->h : (double)(i - 1) / FLARE_RINGS; }

/* t of flare ring i's shape: the sunk ring's t0, else its place's. */
static double flare_shape_t(const flare_shape *f, int i) { return i == 0 ? f->t0 : flare_t(f, i); }

/* The flare's points and mean radii; pts[F + 1] is the trunk at r0. */
static void flare_points_put(const flare_shape *f, const keyaki_node *trunk, v3 *pts, double *rad) {
    for (int i = 0; i <= FLARE_RINGS + 1; i++) {
        double t = flare_t(f, i), w = 1.0 - flare_shape_t(f, i);
        pts[i] = v3_madd(trunk->start, trunk->dir, f->h * t);
        rad[i] = f->r0 * (1.0 + f->flare * w * w);
    }
}

/* Ridges the flare's rings (0 .. F + 1 of rings / normals, round rings
 * from tube_round_rings on frames T, N) and gives each vertex the normal
 * of the surface p = c + rho(theta, s) d(theta): n ~ rho d - rho_theta
 * d_perp - rho rho_s T. */
static void flare_ridge(const flare_shape *f, const v3 *pts, const v3 *T, const v3 *N, int sides, v3 *rings,
                        v3 *normals) {
    for (int i = 0; i <= FLARE_RINGS + 1; i++) {
        double w = 1.0 - flare_shape_t(f, i);
        double R = f->r0 * (1.0 + f->flare * w * w), dR = -2.0 * f->r0 * f->flare * w / f->h;
        double a = f->amp * w * w * w, da = -3.0 * f->amp * w * w / f->h;
        v3 B = v3_cross(T[i], N[i]);
        for (int j = 0; j < sides; j++) {
            double th = 2.0 * BANYAN_PI * j / sides, c = dm_cos(th), sn = dm_sin(th);
            double ph = f->lobes * th + f->phase, m = 1.0 + a * dm_cos(ph);
            double rho = R * m, rho_th = -R * a * f->lobes * dm_sin(ph), rho_s = dR * m + R * da * dm_cos(ph);
            v3 d = v3_add(v3_scale(N[i], c), v3_scale(B, sn)), dp = v3_add(v3_scale(N[i], -sn), v3_scale(B, c));
            rings[(size_t)i * sides + j] = v3_madd(pts[i], d, rho);
            v3 nr = v3_madd(v3_madd(v3_scale(d, rho), dp, -rho_th), T[i], -rho * rho_s);
            normals[(size_t)i * sides + j] = v3_norm_or(nr, d);
        }
    }
}

/* v of the trunk's rings from ring `first` of the mesh: the sweeper's
 * (arc length over each ring's perimeter, times the tiles) but over the
 * flare's slant length, sqrt(ds^2 + dr^2) with r the perimeter / 2 pi,
 * so the bark is not drawn out along a steep foot. */
static void flare_v(mesh_builder *mb, uint32_t first, const v3 *pts, const v3 *rings, uint32_t np, int sides,
                    int tiles) {
    double v = 0, r_prev = 0;
    for (uint32_t i = 0; i < np; i++) {
        const v3 *ring = rings + (size_t)i * sides;
        double c = 0;
        for (int j = 0; j < sides; j++) c += v3_dist(ring[j], ring[j + 1 < sides ? j + 1 : 0]);
        double r = c / (2.0 * BANYAN_PI);
        if (i) {
            double ds = v3_dist(pts[i], pts[i - 1]), dr = i <= FLARE_RINGS + 1 ? r - r_prev : 0.0;
            v += tiles * tube_dv(sqrt(ds * ds + dr * dr), r_prev, r, r_prev);
        }
        r_prev = r;
        float *uv = mb->uv + 2 * ((size_t)first + (size_t)i * (size_t)(sides + 1));
        for (int j = 0; j <= sides; j++) uv[2 * j + 1] = (float)v;
    }
}

/* Sweeps the trunk (limb 0, np points of which the first F + 2 are the
 * flare's) as given rings: round rings on rotation-minimising frames
 * (tube_round_rings: the bytes tube_sweep would make above the flare),
 * the flare's ridged; u by arc length round each ring (ridges do not
 * stretch the bark), v by flare_v. */
static void flare_sweep(mesh_builder *mb, const flare_shape *f, const v3 *pts, const double *rad, uint32_t np,
                        int sides, int tiles) {
    v3 *T = malloc(sizeof(v3) * 2 * np), *rings = malloc(sizeof(v3) * 2 * (size_t)np * (size_t)sides);
    if (!T || !rings) {
        free(T);
        free(rings);
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    v3 *N = T + np, *normals = rings + (size_t)np * sides;
    double cs[256], sn[256];
    for (int j = 0; j < sides; j++) {
        double a = 6.283185307179586 * j / sides;
        cs[j] = dm_cos(a);
        sn[j] = dm_sin(a);
    }
    tube_frames(pts, np, v3_make(0, 0, 0), T, N);
    tube_round_rings(pts, rad, np, T, N, cs, sn, sides, rings, normals, NULL);
    flare_ridge(f, pts, T, N, sides, rings, normals);
    tube_opts o = {sides, 1, 1, {0, 0, 0}, 0.0, normals, 1, tiles};
    uint32_t first = mb->nv;
    tube_sweep_rings(mb, pts, rings, np, &o);
    if (!mb->status) flare_v(mb, first, pts, rings, np, sides, tiles);
    free(T);
    free(rings);
}

/* keyaki_bark_smooth from v = vb on (v - vb scaled, so a limb's lane
 * goes on from where its flakes end). */
static void bark_lane(mesh_builder *mb, uint32_t from, int tiles, float vb) {
    if (mb->status) return;
    const float u0 = BANYAN_KEYAKI_BARK_SMOOTH_U0;
    const float k = (BANYAN_KEYAKI_BARK_SMOOTH_U1 - u0) / (float)(tiles > 1 ? tiles : 1);
    for (uint32_t v = from; v < mb->nv; v++) {
        float *t = mb->uv + 2 * (size_t)v;
        t[0] = u0 + k * t[0];
        t[1] = vb + k * (t[1] - vb);
    }
}

void keyaki_bark_smooth(mesh_builder *mb, uint32_t from, int tiles) { bark_lane(mb, from, tiles, 0.0f); }

/* A limb at least bark_flake_radius thick at its first branch keeps its
 * flakes down to the first branch of its chain thinner than that, which
 * this returns (-1: none); a ring just past that branch's start (0.3 of
 * the radius there, at most a quarter of the branch) begins the smooth
 * lane, so the change of uvs spans a few cm. */
static int32_t flake_end(const banyan_keyaki_params *p, const keyaki_node *n, int32_t first) {
    if (n[first].radius < p->bark_flake_radius) return -1;
    for (int32_t j = main_child(n, first); j >= 0; j = main_child(n, j))
        if (n[j].radius < p->bark_flake_radius) return j;
    return -1;
}

static void no_wind(wind_slots *ws) {
    memset(ws, 0, sizeof *ws);
    ws->birth = ws->level = ws->stiffness = ws->phase = ws->flutter = -1;
    for (int k = 0; k < 3; k++) ws->pivot[k] = -1;
}

banyan_status keyaki_body_plan(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, int count_only,
                               keyaki_run *run, keyaki_body *body, banyan_error *err) {
    memset(body, 0, sizeof *body);
    body->run = run;
    no_wind(&body->ws);
    int32_t limbs = 0;
    for (int32_t i = 0; i < count; i++)
        if (i == 0 || main_child(n, n[i].parent) != i) limbs++;
    body->limbs = malloc(sizeof *body->limbs * (size_t)limbs);
    if (!body->limbs) {
        keyaki_body_free(body);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory planning %d branches", count);
    }
    uint64_t bv = 0, bi = 0;
    double r_trunk = n[0].radius;
    for (int32_t i = 0; i < count; i++) {
        if ((i & 4095) == 0 && keyaki_stopped(run)) {
            keyaki_body_free(body);
            return keyaki_stop_status(err);
        }
        if (!(i == 0 || main_child(n, n[i].parent) != i)) continue;
        keyaki_limb *L = &body->limbs[body->limb_count++];
        int32_t m = 1;
        for (int32_t j = main_child(n, i); j >= 0; j = main_child(n, j)) m++;
        L->first = i;
        L->points = m + 1 + (i != 0) + (i == 0 ? flare_points(p) : 0) + (flake_end(p, n, i) >= 0);
        double f = r_trunk > 0 ? sqrt(n[i].radius / r_trunk) : 1.0;
        int sides = (int)floor(p->sides_min + (p->sides_max - p->sides_min) * f + 0.5);
        L->sides = sides < p->sides_min ? p->sides_min : sides > p->sides_max ? p->sides_max : sides;
        if (i == 0) L->sides = trunk_sides(p, L->sides);
        if (i == 0) {
            L->start = n[0].start;
        } else {
            /* Set back inside the parent so the child's tube leaves from
             * within it; never past half the child's own length. */
            double back = 0.3 * n[n[i].parent].radius, cap = 0.45 * n[i].length;
            L->start = v3_madd(n[i].start, n[i].dir, -(back < cap ? back : cap));
        }
        L->start_radius = i == 0 ? n[i].radius : KEYAKI_SIDE_START * n[i].radius;
        L->vertex_offset = 0;
        uint32_t tv, ti;
        tube_counts((uint32_t)L->points, L->sides, i == 0, 1, &tv, &ti);
        bv += tv;
        bi += ti;
    }
    uint64_t twv, twi, lines; /* twigs from segments join the bark part */
    keyaki_twigs_plan(p, n, count, &twv, &twi, &lines);
    bv += twv;
    bi += twi;
    /* The bark is known exactly: refuse before growing the crown. */
    banyan_status cs = keyaki_promise(run, bv, "the tree's bark", "levels or sides_max", err);
    if (cs) {
        keyaki_body_free(body);
        return cs;
    }
    /* The crown: twigs (bark part) and leaves, grown into flat arrays. */
    cs = keyaki_crown_grow(p, n, count, count_only, run, &body->crown, err);
    if (cs) {
        keyaki_body_free(body);
        return cs;
    }
    bv += body->crown.vertices;
    bi += body->crown.indices;
    uint64_t cards = (uint64_t)body->crown.n_leaves;
    uint64_t tv = bv + 4 * cards, ti = bi + 6 * cards;
    body->bark_vertices = bv > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)bv;
    body->bark_indices = bi > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)bi;
    body->vertices = tv > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)tv;
    body->indices = ti > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)ti;
    /* Skeleton: branches, twig lines (2 points, 2 edges each), twigs. */
    uint64_t sp, se;
    keyaki_crown_skel_counts(&body->crown, &sp, &se);
    sp += (uint64_t)count + 1 + 2 * lines;
    se += (uint64_t)count + 2 * lines;
    body->skel_points = sp > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)sp;
    body->skel_edges = se > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)se;
    return BANYAN_OK;
}

/* The wind branches of every skeleton branch (keyaki_wind). */
static int wind_setup(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, const wind_slots *ws,
                      uint32_t skel0, keyaki_wind *w) {
    memset(w, 0, sizeof *w);
    w->ws = ws;
    w->n = n;
    w->seed = p->seed;
    w->skel0 = skel0;
    w->root = malloc(sizeof(int32_t) * 2 * ((size_t)count + 1));
    w->path = malloc(sizeof(double) * ((size_t)count + 1));
    if (!w->root || !w->path) {
        free(w->root);
        free(w->path);
        return 1;
    }
    w->level = w->root + count + 1;
    keyaki_node_paths(n, count, w->path);
    for (int32_t i = 0; i < count; i++) {
        int32_t P = n[i].parent;
        int trunk = i == 0 || (n[i].flags & KN_TRUNK);
        if (P < 0 || trunk) { /* the trunk: one branch from its base */
            w->root[i] = 0;
            w->level[i] = 0;
        } else if (main_child(n, P) == i && !(P == 0 || (n[P].flags & KN_TRUNK))) { /* the tube goes on */
            w->root[i] = w->root[P];
            w->level[i] = w->level[P];
        } else { /* a new tube, or a limb leaving the trunk */
            w->root[i] = i;
            w->level[i] = w->level[P] + 1;
        }
    }
    return 0;
}

static void wind_free(keyaki_wind *w) {
    free(w->root);
    free(w->path);
    w->root = w->level = NULL;
    w->path = NULL;
}

/* Wind and birth of the limb just swept from vertex v0: ring i closes
 * branch ids[i] at pts[i] (stiffness: from the birth, when the tree is
 * done). */
static void wind_limb(mesh_builder *mb, const keyaki_wind *w, const keyaki_limb *L, uint32_t v0, const v3 *pts,
                      const int32_t *ids, int32_t m, double *vals) {
    if (mb->status || (w->ws->birth < 0 && !w->ws->on)) return;
    const keyaki_node *n = w->n;
    uint32_t np = (uint32_t)(m + 1);
    int cs = L->first == 0;
    double *bt = vals, *lv = vals + 2 * np, *ph = vals + 3 * np, *px = vals + 4 * np;
    for (uint32_t i = 0; i < np; i++) {
        const keyaki_node *x = &n[ids[i]];
        double t = v3_dot(v3_sub(pts[i], x->start), x->dir);
        bt[i] = w->path[ids[i]] + (t < 0 ? 0 : t > x->length ? x->length : t);
        int32_t r = w->root[ids[i]];
        lv[i] = w->level[ids[i]];
        ph[i] = wind_phase_of(w->seed, (uint64_t)r);
        for (int k = 0; k < 3; k++) px[(size_t)k * np + i] = (&n[r].start.x)[k];
    }
    wind_tube_rings(mb, v0, np, L->sides, cs, 1, w->ws->birth, bt);
    if (!w->ws->on) return;
    wind_tube_rings(mb, v0, np, L->sides, cs, 1, w->ws->level, lv);
    wind_tube_rings(mb, v0, np, L->sides, cs, 1, w->ws->phase, ph);
    for (int k = 0; k < 3; k++) wind_tube_rings(mb, v0, np, L->sides, cs, 1, w->ws->pivot[k], px + (size_t)k * np);
}

static void set_attrs(mesh_builder *mb, const int attr[3], uint32_t from, uint32_t to, const keyaki_node *x) {
    if (mb->status || to > mb->nv) return;
    for (uint32_t v = from; v < to; v++) {
        mb->attr[attr[1]][v] = (float)x->level;
        mb->attr[attr[2]][v] = (float)x->order;
    }
}

/* The bark part from the current vertex on: every limb's tube, the
 * segment twigs and the crown's twigs. On the caller's thread (it alone
 * polls the run's prog). */
static void mesh_bark(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, keyaki_body *body,
                      mesh_builder *mb, const int attr[3], const keyaki_wind *wp, uint32_t base) {
    const keyaki_wind w = *wp;
    int32_t max_pts = 2;
    for (int32_t k = 0; k < body->limb_count; k++)
        if (body->limbs[k].points > max_pts) max_pts = body->limbs[k].points;
    v3 *pts = malloc(sizeof(v3) * (size_t)max_pts);
    double *rad = malloc(sizeof(double) * (size_t)max_pts);
    int32_t *ids = malloc(sizeof(int32_t) * (size_t)max_pts);
    double *vals = malloc(sizeof(double) * 7 * (size_t)max_pts); /* wind_limb's per-ring values */
    if (!pts || !rad || !ids || !vals) {
        free(pts); free(rad); free(ids); free(vals);
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    for (int32_t k = 0; k < body->limb_count; k++) {
        if ((k & 255) == 0 && keyaki_stopped(body->run)) {
            mb->status = BANYAN_E_CANCELLED;
            break;
        }
        keyaki_limb *L = &body->limbs[k];
        int32_t m = 0;
        pts[0] = L->start;
        rad[0] = L->start_radius;
        ids[0] = L->first;
        flare_shape fl;
        if (L->first == 0 && flare_points(p)) { /* the foot's rings, all of the trunk's branch */
            flare_setup(p, &n[0], &fl);
            flare_points_put(&fl, &n[0], pts, rad);
            m = FLARE_RINGS + 1;
            for (int32_t i = 1; i <= m; i++) ids[i] = 0;
        }
        if (L->first != 0) { /* the fork point, at the child's full radius */
            m = 1;
            pts[1] = n[L->first].start;
            rad[1] = n[L->first].radius;
            ids[1] = L->first;
        }
        int32_t lane = flake_end(p, n, L->first), lane_ring = -1;
        for (int32_t j = L->first; j >= 0; j = main_child(n, j)) {
            if (j == lane) { /* the smooth lane's first ring, just past j's start */
                double r_end = main_child(n, j) < 0 ? n[j].radius * p->tip_taper : n[j].radius;
                double d = 0.3 * rad[m] < 0.25 * n[j].length ? 0.3 * rad[m] : 0.25 * n[j].length;
                m++;
                pts[m] = v3_madd(n[j].start, n[j].dir, d);
                rad[m] = rad[m - 1] + (r_end - rad[m - 1]) * (n[j].length > 0 ? d / n[j].length : 0.0);
                ids[m] = j;
                lane_ring = m;
            }
            m++;
            pts[m] = node_end(&n[j]);
            int32_t next = main_child(n, j);
            /* A tip (radius tip_radius, or a cut subtree's with twigs from
             * segments) narrows to tip_taper of its radius. */
            rad[m] = next < 0 ? n[j].radius * p->tip_taper : n[j].radius;
            ids[m] = j;
        }
        uint32_t v0 = mb->nv;
        L->vertex_offset = v0 - base;
        mb_set_attr(mb, attr[1], n[L->first].level);
        mb_set_attr(mb, attr[2], n[L->first].order);
        int32_t wr = w.root[L->first];
        wind_set(mb, &body->ws, n[wr].start, w.level[L->first], 1, wind_phase_of(w.seed, (uint64_t)wr), 0);
        int tiles = tube_bark_tiles(n[L->first].radius, p->bark_tile);
        if (L->first == 0 && flare_points(p)) {
            flare_sweep(mb, &fl, pts, rad, (uint32_t)(m + 1), L->sides, tiles);
        } else {
            tube_opts o = {L->sides, L->first == 0, 1, {0, 0, 0}, 0.0, NULL, 0, tiles};
            tube_sweep(mb, pts, rad, (uint32_t)(m + 1), &o);
        }
        if (n[L->first].radius < p->bark_flake_radius) keyaki_bark_smooth(mb, v0, tiles);
        uint32_t ring_v = (uint32_t)L->sides + 1;
        if (lane_ring > 0 && !mb->status) /* v goes on from the ring before */
            bark_lane(mb, v0 + (uint32_t)lane_ring * ring_v, tiles, mb->uv[2 * ((size_t)v0 + (size_t)(lane_ring - 1) * ring_v) + 1]);
        /* Ring i > 0 closes branch ids[i]; the end cap belongs to the tip. */
        uint32_t ring = (uint32_t)L->sides + 1;
        for (int32_t i = 1; i <= m; i++) set_attrs(mb, attr, v0 + i * ring, v0 + (i + 1) * ring, &n[ids[i]]);
        uint32_t caps_from = v0 + (uint32_t)(m + 1) * ring + (L->first == 0 ? ring + 1 : 0);
        set_attrs(mb, attr, caps_from, caps_from + ring + 1, &n[ids[m]]);
        wind_limb(mb, &w, L, v0, pts, ids, m, vals);
    }
    free(pts);
    free(rad);
    free(ids);
    free(vals);
    if (mb->status) return;
    keyaki_twigs_mesh(p, n, count, mb, attr, &w);
    keyaki_crown_mesh_twigs(&body->crown, mb, attr, &w);
}

/* One tree meshed on up to run->threads threads (docs/keyaki.md
 * "Threads"): the caller sweeps the bark while the others mesh the leaves,
 * LEAF_CHUNK at a time, into the slices the plan gives them; the caller
 * then takes the chunks left. A leaf's bytes come from its index alone,
 * so any thread count writes the same mesh. */
#define LEAF_CHUNK 2048
/* Vertices per chunk of the birth and stiffness pass. */
#define BIRTH_CHUNK 16384

typedef struct mesh_job {
    const banyan_keyaki_params *p;
    const keyaki_node *n;
    int32_t count;
    keyaki_body *body;
    mesh_builder *mb;         /* the caller's builder: only the bark's thread touches it while the job runs */
    mesh_builder tmpl;        /* the builder as the leaves start from, copied per chunk */
    const int *attr;
    const keyaki_wind *w;
    uint32_t base, leaves_from, leaf_i0; /* tree's first vertex; the leaves' first vertex and index */
    int32_t chunks;
    atomic_int next;          /* next chunk */
    atomic_int status;        /* first failure of a leaf chunk */
    atomic_int stop;          /* the run's stop seen by every thread */
    keyaki_run crun, wrun;    /* the caller's run (polls the prog) and the others' (the stop flag only) */
    /* the birth pass */
    double inv;
    int birth, stiff;
} mesh_job;

static void leaf_chunk(mesh_job *J, int32_t c, keyaki_run *run) {
    int32_t k0 = c * LEAF_CHUNK, k1 = k0 + LEAF_CHUNK;
    if (k1 > J->body->crown.n_leaves) k1 = J->body->crown.n_leaves;
    mesh_builder v = J->tmpl; /* a view on the leaves' slice: never grown, never freed */
    v.nv = J->leaves_from + 4 * (uint32_t)k0;
    v.ni = J->leaf_i0 + 6 * (uint32_t)k0;
    v.cap_v = J->leaves_from + 4 * (uint32_t)k1;
    v.cap_i = J->leaf_i0 + 6 * (uint32_t)k1;
    v.external = 1;
    keyaki_crown_mesh_leaves(J->p, &J->body->crown, &v, J->attr, J->w, k0, k1, run);
    int st = v.status ? (int)v.status : v.nv != v.cap_v || v.ni != v.cap_i ? BANYAN_E_INTERNAL : 0;
    int none = 0;
    if (st) atomic_compare_exchange_strong(&J->status, &none, st);
}

static void mesh_work(void *job, int caller) {
    mesh_job *J = job;
    if (caller) {
        mesh_bark(J->p, J->n, J->count, J->body, J->mb, J->attr, J->w, J->base);
        if (J->mb->status && J->crun.stop == &J->stop) atomic_store(&J->stop, 1); /* the leaves are moot */
    }
    keyaki_run *run = caller ? &J->crun : &J->wrun;
    for (int32_t c; (c = atomic_fetch_add(&J->next, 1)) < J->chunks;) leaf_chunk(J, c, run);
}

/* Birth over the tree's longest wood (a leaf LEAF_DELAY later) and the
 * stiffness from it, vertices from .. to - 1. Rings and leaves share one
 * birth over several vertices: the pow is taken once for each run. */
static void birth_range(mesh_job *J, uint32_t from, uint32_t to) {
    mesh_builder *mb = J->mb;
    float *bt = mb->attr[J->birth], *st = J->stiff >= 0 ? mb->attr[J->stiff] : NULL;
    float last_b = 0, last_s = 0;
    int have = 0;
    for (uint32_t v = from; v < to && st; v++) {
        if (!have || bt[v] != last_b) {
            double u = 1.0 - bt[v] * J->inv;
            last_b = bt[v];
            last_s = (float)(u > 0 ? (u < 1 ? dm_pow(u, KEYAKI_STIFF_POWER) : 1.0) : 0.0);
            have = 1;
        }
        st[v] = last_s;
    }
    for (uint32_t v = from; v < to; v++) {
        double b = bt[v] * J->inv + (v >= J->leaves_from ? LEAF_DELAY : 0.0);
        bt[v] = (float)(b < 1.0 ? b : 1.0);
    }
}

static void birth_work(void *job, int caller) {
    (void)caller;
    mesh_job *J = job;
    uint32_t end = J->mb->nv;
    for (int32_t c; (c = atomic_fetch_add(&J->next, 1)) < J->chunks;) {
        uint32_t from = J->base + (uint32_t)c * BIRTH_CHUNK, to = end - from > BIRTH_CHUNK ? from + BIRTH_CHUNK : end;
        birth_range(J, from, to);
    }
}

void keyaki_body_mesh(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, keyaki_body *body,
                      mesh_builder *mb, const int attr[3], uint32_t bark_mat, uint32_t leaf_mat, uint32_t group,
                      double tree_id) {
    uint32_t base = mb->nv, ibase = mb->ni;
    if (mb_reserve(mb, body->vertices, body->indices)) return;
    keyaki_wind w;
    if (wind_setup(p, n, count, &body->ws, mb->n_skel, &w)) {
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    /* Skeleton: point 0 the trunk base, point i + 1 the end of branch i;
     * then the twig lines and twigs as they are meshed. */
    mb_skel_reserve(mb, body->skel_points, body->skel_edges);
    for (int32_t i = -1; i < count; i++) {
        const keyaki_node *x = &n[i < 0 ? 0 : i];
        int32_t tag = x->level | x->order << 8 | (x->flags & KN_BROKEN ? 1 << 16 : 0);
        mb_skel_point(mb, i < 0 ? x->start : node_end(x), x->radius, tag);
    }
    for (int32_t i = 0; i < count; i++)
        mb_skel_edge(mb, w.skel0 + (uint32_t)(n[i].parent < 0 ? 0 : n[i].parent + 1), w.skel0 + (uint32_t)i + 1);
    mb_begin_part(mb, bark_mat, group);
    mb_set_attr(mb, attr[0], tree_id);
    if (mb->status) {
        wind_free(&w);
        return;
    }
    mesh_job *J = malloc(sizeof *J);
    if (!J) {
        wind_free(&w);
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    int32_t leaves = body->vertices > body->bark_vertices ? body->crown.n_leaves : 0;
    J->p = p;
    J->n = n;
    J->count = count;
    J->body = body;
    J->mb = mb;
    J->tmpl = *mb;
    J->attr = attr;
    J->w = &w;
    J->base = base;
    J->leaves_from = base + body->bark_vertices;
    J->leaf_i0 = ibase + body->bark_indices;
    J->chunks = (leaves + LEAF_CHUNK - 1) / LEAF_CHUNK;
    atomic_init(&J->next, 0);
    atomic_init(&J->status, 0);
    atomic_init(&J->stop, 0);
    memset(&J->crun, 0, sizeof J->crun);
    if (body->run) J->crun = *body->run;
    if (!J->crun.stop) J->crun.stop = &J->stop;
    J->wrun = J->crun;
    J->wrun.g = NULL;
    int threads = J->crun.threads > 1 ? J->crun.threads : 1;
    if (threads > J->chunks + 1) threads = J->chunks + 1;
    /* While the leaves are written beside it, the bark must stay in its
     * slice: a plan that was not exact fails (BANYAN_E_INTERNAL) rather
     * than moving the arrays under the other threads. */
    uint32_t cap_v = mb->cap_v, cap_i = mb->cap_i;
    int external = mb->external;
    mb->cap_v = J->leaves_from;
    mb->cap_i = J->leaf_i0;
    mb->external = 1;
    /* No heartbeat while the caller waits: it waits only for the chunks
     * already taken, and its own chunks kept the budget. */
    pool_run(threads, mesh_work, J, NULL, NULL);
    mb->cap_v = cap_v;
    mb->cap_i = cap_i;
    mb->external = external;
    wind_free(&w);
    if (!mb->status && mb->nv != J->leaves_from) mb->status = BANYAN_E_INTERNAL;
    if (!mb->status && atomic_load(&J->status)) mb->status = (banyan_status)atomic_load(&J->status);
    if (!mb->status && leaves) {
        mb_begin_part(mb, leaf_mat, group);
        mb->nv = J->leaves_from + 4 * (uint32_t)leaves;
        mb->ni = J->leaf_i0 + 6 * (uint32_t)leaves;
    }
    /* Birth was written as path length (m): the longest wood is 1, a leaf
     * comes LEAF_DELAY after its wood. Stiffness follows from the path p
     * (a leaf's its wood's): (1 - p / P)^KEYAKI_STIFF_POWER. */
    if (mb->status || body->ws.birth < 0) {
        free(J);
        return;
    }
    float *bt = mb->attr[body->ws.birth], top = 0;
    for (uint32_t v = base; v < J->leaves_from; v++) top = bt[v] > top ? bt[v] : top;
    J->inv = top > 0 ? 1.0 / top : 0.0; /* top * inv rounds to 1.0f */
    J->birth = body->ws.birth;
    J->stiff = body->ws.stiffness;
    J->chunks = (int32_t)((mb->nv - base + BIRTH_CHUNK - 1) / BIRTH_CHUNK);
    atomic_store(&J->next, 0);
    threads = J->crun.threads > 1 ? J->crun.threads : 1;
    if (threads > J->chunks) threads = J->chunks > 0 ? J->chunks : 1;
    pool_run(threads, birth_work, J, NULL, NULL);
    free(J);
}

/* Grows the skeleton, orders it and plans its body: what counting and
 * building share. */
static banyan_status grow_and_plan(const banyan_keyaki_params *p, keyaki_skeleton *sk, int count_only,
                                   keyaki_body *body, banyan_error *err) {
    banyan_status s = keyaki_grow(p, sk, err);
    if (s) return s;
    if (keyaki_strahler(sk->nodes, sk->count))
        return banyan_fail(err, BANYAN_E_INTERNAL, "skeleton children out of order");
    if (keyaki_stage(sk->run, KEYAKI_AT_GROWN)) return keyaki_stop_status(err);
    s = keyaki_body_plan(p, sk->nodes, sk->count, count_only, sk->run, body, err);
    if (!s && keyaki_stage(sk->run, KEYAKI_AT_PLANNED)) {
        keyaki_body_free(body);
        return keyaki_stop_status(err);
    }
    return s;
}

banyan_status keyaki_count(const banyan_keyaki_params *p, keyaki_skeleton *sk, keyaki_counts *c, banyan_error *err) {
    keyaki_body body;
    banyan_status s = grow_and_plan(p, sk, 1, &body, err); /* sizes only: leaves counted, not placed */
    if (s) return s;
    c->vertices = body.vertices;
    c->indices = body.indices;
    c->nodes = (uint32_t)sk->count;
    c->skel_points = body.skel_points;
    c->skel_edges = body.skel_edges;
    c->parts = body.vertices > body.bark_vertices ? 2 : 1;
    keyaki_body_free(&body);
    return BANYAN_OK;
}

banyan_status keyaki_build_into(const banyan_keyaki_params *p, double tree_id, uint32_t group, keyaki_skeleton *sk,
                                mesh_builder *mb, banyan_error *err) {
    keyaki_body body;
    banyan_status s = grow_and_plan(p, sk, 0, &body, err);
    if (s) return s;
    if (body.vertices > (uint32_t)p->max_vertices) {
        uint32_t v = body.vertices;
        keyaki_body_free(&body);
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the tree needs %u vertices, more than max_vertices = %d; raise max_vertices or lower "
                           "leaf_density, sides_max or levels",
                           v, p->max_vertices);
    }
    /* The mesh's memory, before it is allocated (an avenue's merged mesh
     * was reserved whole by the avenue). */
    if (!mb->external && keyaki_reserve_bytes(sk->run, keyaki_mesh_bytes(body.vertices, body.indices, p->wind))) {
        keyaki_body_free(&body);
        return keyaki_stop_status(err);
    }
    uint32_t bark = mb_add_material(mb, "keyaki_bark", p->bark_color, 0.9, 0);
    uint32_t leaf = mb_add_material(mb, "keyaki_leaf", p->leaf_color, 0.6, 1);
    if (!mb->status) {
        bark_material_set(&mb->mat[bark], BANYAN_TEX_KEYAKI_BARK);
        leaf_material_set(&mb->mat[leaf], BANYAN_TEX_KEYAKI_LEAF, p->season, p->leaf_color);
    }
    int attr[3];
    attr[0] = mb_add_attr(mb, "tree_id");
    attr[1] = mb_add_attr(mb, "level");
    attr[2] = mb_add_attr(mb, "order");
    wind_declare(mb, p->wind, &body.ws);
    keyaki_body_mesh(p, sk->nodes, sk->count, &body, mb, attr, bark, leaf, group, tree_id);
    uint32_t planned = body.vertices;
    keyaki_body_free(&body);
    if (!mb->status && mb->nv != planned) mb->status = BANYAN_E_INTERNAL; /* the plan must be exact */
    if (!mb->status && keyaki_stage(sk->run, KEYAKI_AT_MESHED)) return keyaki_stop_status(err);
    return BANYAN_OK;
}

banyan_status keyaki_build(const banyan_keyaki_params *p, double tree_id, uint32_t group, keyaki_skeleton *sk,
                           banyan_mesh **out, banyan_error *err) {
    *out = NULL;
    mesh_builder mb;
    mb_init(&mb, (uint32_t)p->max_vertices, 1); /* colours: white bark, tinted leaves */
    banyan_status s = keyaki_build_into(p, tree_id, group, sk, &mb, err);
    if (s) {
        mb_free(&mb);
        return s;
    }
    return mb_finish(&mb, out, err);
}
