/* ivy_internal.h - the ivy plant between steps (spec/ivy.md, "Buds"):
 * a binary tree of buds in creation order, a spatial hash over bud
 * positions for the light look-up, and the hosts: oriented boxes (the
 * given ones, then the ground) with their exact obb queries, and the
 * triangle meshes of a host set (hosts/hosts.h). Shared by the ivy source
 * files only. */
#ifndef BANYAN_IVY_INTERNAL_H
#define BANYAN_IVY_INTERNAL_H

#include "banyan.h"
#include "base/frame.h"
#include "hosts/hosts.h"
#include "hosts/obb.h"
#include "base/progress.h"
#include "base/rng.h"
#include "base/vec.h"

/* Spatial hash cell edge, in units of leaf_max (the light look-up radius);
 * at least 1: a look-up reads at most 4 cells per axis (grid.c). */
#ifndef IVY_CELL_SCALE
#define IVY_CELL_SCALE 1.0
#endif

/* A random-walk candidate being scored (growth.c). */
typedef struct ivy_cand {
    v3 d;             /* direction */
    double fv, fgeo, fhelio, ftendril;
    double f_max;     /* the most its score can be */
    int32_t k;        /* the order it was drawn in */
} ivy_cand;

typedef struct ivy_bud {
    v3 P;             /* position */
    v3 V;             /* growth direction, unit */
    double N;         /* nourishment */
    int32_t state;    /* banyan_ivy_bud_state */
    int32_t L;        /* leaf side 0/1 */
    int32_t attached; /* F */
    int32_t sucker;   /* has a sucker (born A0 or A1) */
    int32_t run;      /* unattached buds from the last attached ancestor to here; 0 when attached */
    int32_t step_c;   /* step it was created */
    int32_t step_d;   /* step it became Z, -1 while alive */
    int32_t parent;   /* -1 for the first bud */
    int32_t child[2]; /* continuation, lateral; -1 when none */
    /* Light cache: 0 while awake; else the serial of the sleep that
     * found it too shaded to grow, which lasts until a bud its light test
     * counted moves (grid.c). */
    int32_t shaded;
    int32_t mark;     /* scratch of the sag correction */
    int32_t leader;   /* on a leading stem (a first bud's continuation line): it crosses rather than ends */
    int32_t follow;   /* internodes grown in a row alongside a stem it met (follow_length) */
    int32_t followed; /* while following: 1 + the bud of the followed stem it is beside; 0 otherwise */
    int32_t follow_sense; /* +1: the run goes the followed stem's way (to its continuation), -1 back to its root */
} ivy_bud;

/* One sleeper that counted a bud: valid while that sleeper's `shaded`
 * still holds `serial`. */
typedef struct ivy_dep {
    int32_t sleeper, serial, next;
} ivy_dep;

/* The spatial hash's copy of a bud, stored with the other buds of its
 * cell in one run of memory: a light look-up reads a few runs, not a
 * chain of buds scattered over the whole plant (grid.c). */
typedef struct ivy_gnode {
    v3 P;
    int32_t step_c;   /* the bud's, with IVY_GNODE_FOLLOW set on a bud grown alongside a stem */
    int32_t id;       /* bud index */
} ivy_gnode;
#define IVY_GNODE_FOLLOW (1 << 30)

/* A stem grown alongside another (follow_length) lies in that stem's
 * shade: it carries this share of the leaves a stem carries elsewhere,
 * and its leaves cast this share of the shade in the light model. */
#define IVY_FOLLOW_LEAF 0.7

/* A stem that an internode grown from one bud may cross (ivy_crosses_near):
 * its end bud's copy, that copy's cell, and the stem across the surface
 * (parent's u, w and the step to the end bud's), found once per bud. */
typedef struct ivy_xstem {
    v3 P;
    int32_t cell[3];
    double cx, cy, dx, dy;
} ivy_xstem;

/* A cell of the spatial hash: its coordinates and its buds' run in the
 * pool (n used of cap). Cells stay once made, empty or not. */
typedef struct ivy_cell {
    int32_t x, y, z;
    int32_t at, n, cap;
    int32_t id;       /* its number, in the order cells were made (its row of cnb) */
} ivy_cell;

struct banyan_ivy {
    banyan_ivy_params p;   /* start and ground_z moved into the frame below */
    v3 origin;             /* world position of the frame the plant grows in (base/frame.h) */
    obb *hosts;
    uint32_t n_hosts;      /* the given boxes, then the ground when params.ground: stems keep out of all */
    uint32_t n_grip;       /* the first n_grip are the ones suckers grip (the ground only as a host) */
    uint32_t n_given;      /* the given boxes */
    /* Mesh hosts (a host set's meshes; suckers grip them all). Mesh m is
     * host mesh0 + m in ivy_near.host and in the bounds below: mesh0 =
     * n_given + 1, after the ground's slot whether there is a ground or
     * not, so the numbers do not change when the ground is added. */
    const banyan_hosts *set; /* the host set grown on (banyan_ivy_create) */
    const host_mesh *meshes;
    uint32_t n_mesh, mesh0;
    v3 *box_lo, *box_hi;   /* world bounding boxes of the hosts (quick rejection) */
    v3 *clear_lo, *clear_hi; /* the same grown by clearance (one block with box_lo) */

    ivy_bud *buds;
    int32_t n, cap;
    int32_t active;        /* buds in A0, A1, A2 or D */
    int32_t roots;         /* the leading stems' first buds: buds 0 .. roots - 1 */
    int32_t *act, n_act;   /* those that are awake, in creation order (plus ones that ended or
                              fell asleep this step): a bud known too shaded sleeps until
                              the light cache forgets it */
    int32_t *wake, n_wake; /* buds woken since the last step, to merge into act */
    int32_t *merge;        /* scratch for the merge */
    /* Light cache (grid.c): each sleep leaves an edge at every bud its
     * test counted; a move of that bud walks its edges and wakes them. */
    ivy_dep *dep;          /* edge pool */
    int32_t n_dep, dep_cap;
    int32_t *dep_head;     /* per bud: first edge of the sleepers that counted it */
    int32_t *seen;         /* per bud: the last test that counted it */
    int32_t *counted, n_counted; /* buds the current test counted */
    int32_t test_id, sleep_serial;
    int32_t branch_points; /* p3 firings */
    int32_t step;          /* steps done */
    double step_seconds;

    /* Spatial hash: cells of IVY_CELL_SCALE * leaf_max in an open
     * addressing table; each cell's buds in a run of the pool. */
    int32_t (*bcell)[3];   /* per bud: its cell's coordinates */
    ivy_cell *cells;       /* the table (x = INT32_MIN: empty slot) */
    uint64_t *cbits;       /* a bit per slot: used (in cells' block) */
    uint32_t cmask;        /* slots - 1 */
    int32_t n_cells;
    /* Per cell (by id): the ids of the 27 cells around it, in z, y, x
     * order, -1 where there is none, and its slot in the table; room for
     * cnb_cap cells. A light test reads these instead of hashing the 27
     * cells (grid.c, shade). */
    int32_t (*cnb)[27];
    uint32_t *cslot;
    int32_t cnb_cap;
    ivy_gnode *pool;
    int64_t pool_n, pool_cap;
    /* The order a cell's buds are read in: newest link first, reset to
     * falling bud index whenever the plant passes 2 * vbuckets buds (the
     * chains of the bucket hash this replaced, kept so that the light
     * sums add up in the same order and results stay the same). */
    uint32_t vbuckets;
    int grid_oom;          /* the hash could not grow: the step fails */
    uint32_t grid_gen;     /* counts the copies linked and unlinked (the stems below go stale) */
    /* The stems near one bud for ivy_crosses_near, and what they were
     * gathered for: the bud's point, normal, self, layer, grid_gen; the
     * cells read (x0, x1, y0, y1, z0, z1); xs_ok = 0: not usable. */
    ivy_xstem *xs;
    int32_t n_xs, xs_cap;
    int xs_ok, xs_valid;
    v3 xs_a, xs_n, xs_u, xs_w;
    int32_t xs_self;
    double xs_layer;
    uint32_t xs_gen;
    int32_t xs_box[6];
    /* The cells the last light test of a bud's own point read (ivy_shade_watch
     * with vl): the same cells serve gather_stems at that point. */
    const ivy_cell *lc[64];
    int32_t n_lc, lc_box[6];
    v3 lc_p;
    uint32_t lc_gen;
    int lc_valid;
    double inv_cell;

    /* Scratch for the sag correction: cap entries each (tmp: 3 cap). */
    int32_t *chain, *moving, *stack, *sizes;
    v3 *tmp;
    int32_t scratch_cap;

    ivy_cand *cand;        /* params.candidates of them */
    int32_t *cand_ord;     /* their order of asking (growth.c) */

    /* Progress and budget: a one-shot generation's, else `own` (the
     * handle's budget, ivy_budget_start). Growth is counted in bud visits,
     * and the steps left are guessed at the current visits per step
     * (ivy_progress). */
    prog *prog;
    prog own;
    double rss0_mb;        /* resident MB when the handle was made */
    double work;           /* bud visits of the steps done */
    int32_t goal;          /* the step the generation ends at */
    double grow_share;     /* the part of the call that growth is */
    double mesh_from;      /* the fraction where the mesh starts (after the stats) */

    pcg32 rng;
};

/* Nearest surface that suckers grip (the given hosts, and the ground when
 * it is a host) of p: distance (< 0 inside a box or a closed mesh), the
 * closest surface point and the outward normal of the distance field
 * there, host index (boxes, the ground, then mesh0 + m) and face: for a
 * box 0..5 = -x, +x, -y, +y, -z, +z of that box; for a mesh the same
 * numbers as a cube map, the world axis along which the nearest
 * triangle's normal is largest, and its sign (the chart of the stats). */
typedef struct ivy_near {
    double dist;
    v3 normal;
    v3 point;
    int32_t host, face;
} ivy_near;
ivy_near ivy_nearest(const banyan_ivy *iv, v3 p);
/* The same over the first n boxes and every mesh; over all of them (the
 * ground too, whatever its kind): the surface a stem or leaf lies on. */
ivy_near ivy_nearest_of(const banyan_ivy *iv, v3 p, uint32_t n);
ivy_near ivy_nearest_any(const banyan_ivy *iv, v3 p);
/* ivy_nearest for a caller that only uses the answer when dist <= cap:
 * meshes are looked for within cap only (boxes as ivy_nearest). */
ivy_near ivy_nearest_within(const banyan_ivy *iv, v3 p, double cap);
/* Signed distance to the nearest gripped surface when it is at most
 * `cap`; HUGE_VAL or some value > cap otherwise (cheaper: no normal). */
double ivy_grip_distance(const banyan_ivy *iv, v3 p, double cap);
/* Fills box_lo / box_hi and clear_lo / clear_hi from the hosts. */
void ivy_host_boxes(banyan_ivy *iv);
/* Does the segment a-b meet a host or the ground, or end closer than
 * `clearance` to one? When it does not and grip != NULL, *grip is
 * ivy_grip_distance(iv, b, cap), found in the same pass over the hosts. */
int ivy_blocked(const banyan_ivy *iv, v3 a, v3 b, double cap, double *grip);
/* A hair past `clearance`, where a point is put off a surface: one put at
 * exactly clearance could read a little nearer (a float mesh, a run along
 * a wall far from the origin) and fall on the next clearance test's edge. */
static inline double ivy_clear_hair(const banyan_ivy *iv) { return iv->p.clearance * (1.0 + 1e-6) + 1e-7; }
/* Is p farther than `margin` outside host h's world bounding box? Then it
 * is farther than that from the host: the exact query can be skipped. */
static inline int ivy_far_from(const banyan_ivy *iv, uint32_t h, v3 p, double margin) {
    v3 lo = iv->box_lo[h], hi = iv->box_hi[h];
    return p.x < lo.x - margin || p.x > hi.x + margin || p.y < lo.y - margin || p.y > hi.y + margin ||
           p.z < lo.z - margin || p.z > hi.z + margin;
}
/* ivy_far_from(iv, h, p, clearance), on the boxes grown once. */
static inline int ivy_far_by_clearance(const banyan_ivy *iv, uint32_t h, v3 p) {
    v3 lo = iv->clear_lo[h], hi = iv->clear_hi[h];
    /* Above first: it settles the ground at once. */
    return p.z > hi.z || p.z < lo.z || p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y;
}
/* p pushed out of every host to `clearance` off the nearest surface. */
v3 ivy_push_out_near(const banyan_ivy *iv, v3 p);
/* The same; inline for the usual point, clear of every host's box (the
 * sag correction pushes each bud of every turn). */
static inline v3 ivy_push_out(const banyan_ivy *iv, v3 p) {
    for (uint32_t h = 0; h < iv->n_hosts; h++)
        if (!ivy_far_by_clearance(iv, h, p)) return ivy_push_out_near(iv, p);
    for (uint32_t m = 0; m < iv->n_mesh; m++)
        if (!ivy_far_by_clearance(iv, iv->mesh0 + m, p)) return ivy_push_out_near(iv, p);
    return p;
}
/* A bud moved from `from` to `to` (a turn of the sag): stopped
 * `clearance` before the first mesh surface in its way (a thin open mesh
 * has no inside for the push-out to find), then pushed out. Boxes: just
 * ivy_push_out(to). */
v3 ivy_stop_at_meshes(const banyan_ivy *iv, v3 from, v3 to);
/* Does segment a-b meet a mesh host's surface? */
int ivy_segment_meets_mesh(const banyan_ivy *iv, v3 a, v3 b);
static inline v3 ivy_move_out(const banyan_ivy *iv, v3 from, v3 to) {
    if (iv->n_mesh) to = ivy_stop_at_meshes(iv, from, to);
    return ivy_push_out(iv, to);
}

/* Spatial hash (grid.c). */
banyan_status ivy_grid_init(banyan_ivy *iv, uint32_t buckets);
void ivy_grid_insert(banyan_ivy *iv, int32_t i); /* after iv->n counts bud i; may rehash */
/* Moves buds set[k] to q[k] (k < n) and upkeeps the light cache. */
void ivy_grid_move_many(banyan_ivy *iv, const int32_t *set, const v3 *q, int32_t n);
/* Shade at p from every bud within leaf_max but `self`: returns H0, and
 * adds the light vector V_l to *vl when vl != NULL. Stops early once H0
 * passes `stop` (*vl is then left as it was: the bud will not grow). */
double ivy_shade(const banyan_ivy *iv, v3 p, int32_t self, double stop, v3 *vl);
/* The light test of the rules: ivy_test_begin, then one ivy_shade_watch
 * per point (the bud, then its H1 buds), which gathers the buds counted;
 * then ivy_sleep when the sum is over t0: bud i sleeps until one of them
 * moves (or it or an H1 bud moves: ivy_grid_move_many). */
void ivy_test_begin(banyan_ivy *iv);
double ivy_shade_watch(banyan_ivy *iv, v3 p, int32_t self, double stop, v3 *vl);
void ivy_sleep(banyan_ivy *iv, int32_t i);
/* Does internode a-b cross, seen along the unit normal n, an internode
 * whose end bud lies within `layer` of a across n and that does not share
 * bud `self`? (grid.c; f_cross of the random walk) */
int ivy_crosses(const banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer);
/* The end bud of the stem internode a-b crosses nearest a (of two at
 * one point, the lower bud), or -1. */
int32_t ivy_crossed_stem(const banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer);
/* The same answer, for the random walk's many internodes from one point a
 * (same n, self, layer): the stems near a are gathered once (until the
 * hash changes), then each query reads that short list. */
int ivy_crosses_near(banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer);
/* Diameter of bud i's leaf (and shadow) at the current step. */
double ivy_leaf_diameter(const banyan_ivy *iv, const ivy_bud *b);
/* Stem radius by age (the spec's rule, capped): the growth's (sag) and
 * the floor of the mesh's wood. */
double ivy_stem_radius(const banyan_ivy *iv, const ivy_bud *b);
/* The mesh's wood (wood.c): per bud its stem radius (age rule or pipe
 * model, the larger) in r and its tube centre in P (the bud, moved out of
 * the surface it lies on by as much as the stem is thicker than its gap).
 * r and P hold iv->n entries. BANYAN_E_NOMEM or OK. */
banyan_status ivy_wood(const banyan_ivy *iv, double *r, v3 *P);
/* Radius of curvature of a mesh host near `at` (a nearest answer), from
 * how far the surface's normal turns over steps of h along it (relief.c);
 * HUGE_VAL on boxes, the ground and flat parts. */
double ivy_relief_radius(const banyan_ivy *iv, ivy_near at, double h);
/* Distance from `at` (a nearest answer on a box) to the nearest edge of
 * its face, when below cap, and in *out_dir the way out across that edge
 * (in the face's plane): edges on the ground, where another host
 * carries the face on, or across a face narrower than 4 cap do not count. HUGE_VAL (out_dir untouched) on
 * meshes, the ground and farther from every edge. */
double ivy_edge_distance(const banyan_ivy *iv, ivy_near at, double cap, v3 *out_dir);
/* Per bud, the share of its leaf that old wood keeps (1: young wood, 0:
 * shed), from the buds' wood radii r (ivy_wood). */
void ivy_wood_leaf_shares(const banyan_ivy *iv, const double *r, double *share);

/* Sag correction of every dangling stem (sag.c). */
void ivy_sag(banyan_ivy *iv);

/* Fewest mesh vertices a plant of n buds can need: every bud is one ring
 * of its chain's tube, plus one leaf (blade and petiole) each (as banyan_ivy_mesh
 * counts). It only grows with n, so a one-shot generation can stop as
 * soon as it passes max_vertices instead of growing to the end (mesh.c). */
uint64_t ivy_mesh_vertex_floor(const banyan_ivy_params *p, int64_t n);

/* Starts the handle's own budget for a step or mesh call: its clock as if
 * it had run through every step call so far (step_seconds), memory from
 * banyan_ivy_create. A stopped handle stays stopped (a stop can fall in
 * the middle of a step). No-op for a one-shot generation's prog. Inline:
 * growth (growth.c) and meshing (mesh.c) both start it. */
static inline void ivy_budget_start(const banyan_ivy *iv) {
    prog *g = iv->prog;
    if (g != &iv->own || g->cancelled) return;
    prog_budget_resume(g, iv->p.max_seconds, iv->p.max_memory_mb, iv->step_seconds, iv->rss0_mb);
}

/* Grows n steps; stops with BANYAN_E_LIMIT as soon as the plant could no
 * longer be meshed within max_vertices when vertex_stop is set. */
banyan_status ivy_grow(banyan_ivy *iv, int32_t n, int vertex_stop, banyan_error *err);

/* Why the plant could not grow (banyan_ivy_growth), from its buds and
 * steps (stats.c). */
int32_t ivy_growth_check(const banyan_ivy *iv);

/* Checks params (table ranges and cross-field rules). */
banyan_status ivy_params_check(const banyan_ivy_params *p, banyan_error *err);

#endif
