/* roots_internal.h - shared state of the roots generator (spec roots.md).
 * The net is built in stages: main roots (growth.c, spec 1), first branch
 * roots, main-root correction and second branch roots (branches.c, spec
 * 2-4), final polylines with segment repair (paths.c), and the tube mesh
 * with junction smoothing (mesh.c, spec 5). Tests reach the net through
 * roots_net_build to check its invariants. */
#ifndef BANYAN_ROOTS_INTERNAL_H
#define BANYAN_ROOTS_INTERNAL_H

#include "base/progress.h"
#include "banyan.h"
#include "hosts/hosts.h"
#include "mesh/mesh_builder.h"
#include "hosts/obb.h"
#include "base/rng.h"
#include "base/vec.h"

/* Kinds, also the skeleton tag and the `root_kind` attribute. Foot roots
 * (foot.c: drop roots, buttresses, surface roots) are held by the host and
 * the soil as the main roots' feet are: wind level 0 with the mains.
 * Aerial roots (aerial.c: thin hanging threads) sway as the thinnest
 * branch roots do: level 2. */
enum { ROOT_MAIN = 0, ROOT_FIRST = 1, ROOT_SECOND = 2, ROOT_FOOT = 3, ROOT_AERIAL = 4 };
static inline int roots_wind_level(int kind) {
    return kind == ROOT_FOOT ? 0 : kind == ROOT_AERIAL ? ROOT_SECOND : kind;
}

/* Collision world: hosts, ground, r. Clearance of a point = its distance
 * to the nearest host surface (signed, < 0 inside a box or a closed mesh)
 * or to the ground plane; a sphere centre is free when its clearance is
 * >= r. Every query loops over the boxes first, then over the meshes;
 * with no meshes it is the plain box query, bit for bit. Host numbers (`which`) follow the host set: boxes, then meshes. */
typedef struct roots_world {
    const obb *hosts;         /* the boxes */
    uint32_t n_hosts;         /* boxes */
    const host_mesh *meshes;  /* mesh hosts, numbered n_hosts + j */
    uint32_t n_meshes;
    const banyan_hosts *set;  /* the host set (world bounds per host) */
    uint32_t *hint;           /* per mesh: nearest triangle of the last point asked (UINT32_MAX: none),
                                 scratch of one net (see hint_cap in collide.c) */
    int ground;
    double ground_z;
    double r;
    double eps;  /* numerical slack of the free test, 1e-9 r */
} roots_world;

/* Nearest obstacle within `range` (> 0, HUGE_VAL for any): its clearance
 * and the outward unit normal of the distance field there; *which = host
 * index, or -1 for the ground (-2 when nothing was found). Exact below
 * range; at or above it the value is a lower bound (boxes and the ground
 * are always exact; a mesh is only searched within range, which keeps its
 * queries cheap). Without normal and which, a point deep inside a mesh
 * (deeper than max(range, 2 r)) may get an upper bound of its negative
 * clearance: enough for free tests and the turn's skipping. */
double world_clearance_in(const roots_world *w, v3 p, int with_ground, double range, v3 *normal, int *which);
static inline double world_clearance(const roots_world *w, v3 p, v3 *normal, int *which) {
    return world_clearance_in(w, p, 1, HUGE_VAL, normal, which);
}
static inline int world_free(const roots_world *w, v3 p) {
    return world_clearance_in(w, p, 1, w->r, NULL, NULL) >= w->r - w->eps;
}
/* Boxes and the ground only, exact (the fast path of world_clearance). */
double world_clearance_boxes(const roots_world *w, v3 p);
/* world_clearance_in without normal for a point known to lie outside
 * every closed mesh (within the free ball of a free point): meshes give
 * unsigned distances, which skips their inside tests. */
double world_clearance_outside(const roots_world *w, v3 p, double range);
/* q taken back along the segment c -> q to just before the first mesh
 * surface it crosses (a ray), q itself when it crosses none: with c free,
 * the result is outside every closed mesh and on c's side of open ones. */
v3 world_spoke(const roots_world *w, v3 c, v3 q);
/* First t in [0,1] at which the sphere moving p -> p + d would come closer
 * than r to an obstacle (1 when it never does); *normal gets the normal of
 * the obstacle hit. Exact up to bisection (the distance to a convex body,
 * a box or one triangle of a mesh, is convex along a line). */
double world_trace_ex(const roots_world *w, v3 p, v3 d, int meshes_free, v3 *normal, int *which);
static inline double world_trace(const roots_world *w, v3 p, v3 d, v3 *normal, int *which) {
    return world_trace_ex(w, p, d, 0, normal, which);
}
/* With meshes_free, the caller knows the whole move keeps clearance >= r
 * from every mesh (it lies in the free ball of its start): only the boxes
 * and the ground are traced. */
/* Clearance along the segment a-b (a free point), for comparing with
 * `stop`: a value below `stop` is a clearance the segment really has
 * there; a value at or above it is a lower bound of the least clearance
 * (convexity; for meshes the exact segment-to-triangles distance). */
double world_segment_clearance(const roots_world *w, v3 a, v3 b, double stop);
/* The obstacles (ground first, then hosts) closer to a free point p (so
 * outside every closed mesh: unsigned mesh distances) than `range`: their
 * clearance and distance-field normal, at most cap of them; returns how
 * many. A convex distance grows at least as fast as its tangent plane:
 * clearance(p + o) >= c + n.o, which lets callers skip far points. A mesh
 * is not convex: it comes with n = 0, and its bound is the Lipschitz one,
 * clearance(p + o) >= c - |o| (world_near_bound gives either). */
int world_near(const roots_world *w, v3 p, double range, double *c, v3 *n, int cap);
static inline double world_near_bound(double c, v3 n, v3 o) {
    return n.x == 0 && n.y == 0 && n.z == 0 ? c - v3_len(o) : c + v3_dot(n, o);
}
/* Least clearance along a-b and where it is (t in [0,1]): exact for
 * boxes, sampled and refined for meshes (a split point needs no more). */
double world_segment_deepest(const roots_world *w, v3 a, v3 b, double *t_min);
/* Moves p out of every obstacle to clearance r; returns 1 when it moved.
 * Along the distance-field normal; out of a box also through whichever
 * face costs least. */
int world_push_out(const roots_world *w, v3 *p);

/* One final polyline of the net (after correction and segment repair). */
typedef struct roots_poly {
    uint32_t off, n;   /* points pts[off .. off+n-1] */
    int32_t kind;      /* ROOT_* */
    int32_t id;        /* root_id, see docs/roots.md */
    int32_t a, k;      /* main root (0-based) and branch number along it */
    uint32_t ring_off; /* junction loops: index into net->loops, or UINT32_MAX */
    uint32_t soil_from; /* main roots that enter the soil: the first point of the underground end
                           (pts[off + soil_from ..] lie below the ground, soil_from - 1 is where the
                           root enters it); n when the root stays above ground. Foot roots: from
                           here on the points lie on or in the soil */
    uint32_t from;     /* foot and aerial roots: the net point (index into pts) they start on; else UINT32_MAX */
} roots_poly;

/* Points of a main root's underground end (soil_entry): it runs on
 * outwards and dips below the ground. */
#define ROOTS_SOIL_PTS 4

/* The world without the ground: the underground ends of soil-entering
 * roots keep clear of the hosts only. */
static inline roots_world roots_soil_world(const roots_world *w) {
    roots_world s = *w;
    s.ground = 0;
    return s;
}

typedef struct roots_net {
    /* Inputs, resolved. */
    roots_world w;
    const banyan_hosts *hosts; /* the host set grown on */
    banyan_hosts *own_hosts;   /* made from boxes by roots_net_build, freed with the net */
    v3 G;
    int N, B;          /* main roots, growth points per main root */
    int S1, S2;        /* samples per first / second branch root */
    int nb;            /* first-branch slots per main root */
    double r, u;

    /* Growth points (spec notation, 0-based). */
    v3 *M;             /* N * B: M[a*B + b] = M(a+1, b+1) after correction */
    v3 *M_grown;       /* N * B: as grown, before correction */
    v3 *K;             /* N * nb * S1 first branch points, slot [a*nb + k] */
    int32_t *K_valid;  /* N * nb: 1 when the slot holds a first branch root */
    int32_t *K_end;    /* N * nb: the slot of main root a+1 where slot (a, k)'s first branch root
                          ends: k, or k -+ 1 (branch_tilt) */
    uint8_t *K_ok;     /* N * nb * S1: the step into K[i] was checked free while placing it */
    v3 *Q;             /* N * nb * S2 second branch points, slot [a*nb + k] joins k and k+1 */
    int32_t *Q_valid;  /* N * nb */
    int32_t *ground_hit; /* N: main root a reached the ground */
    int32_t *soil_b;   /* N: growth index where main root a enters the soil (its later growth points
                          repeat that one), B when it does not */
    v3 *soil_pts;      /* N * ROOTS_SOIL_PTS: the underground end after M(a, soil_b) */

    /* Final polylines. */
    v3 *pts;
    double *rad;       /* per point radius (the pipe model, paths.c) */
    uint32_t n_pts, cap_pts;
    roots_poly *poly;
    uint32_t n_poly, cap_poly;
    /* Where growth point b of main root a sits in pts (after repair). */
    uint32_t *M_at;    /* N * B */
    uint32_t *K_mid_at; /* N * nb: where each first branch root's middle point K^mid sits */

    banyan_roots_stats stats;
    prog *prog;        /* progress and budget of a generation; NULL for the tests' nets */
} roots_net;

/* Inside a stage: keeps the budget and hears a cancel (the fraction stays
 * where the stage began); 1 once the run is stopped. The stages return
 * early then and the caller frees the net. */
static inline int roots_stop(const roots_net *net) { return prog_at(net->prog, 0.0); }

/* The progress fraction at the end of the main roots and at the start of
 * the mesh, which takes most of the time (bench_progress on the default
 * trunk; the stages between: generate.c). */
#define ROOTS_AT_MAINS 0.05
#define ROOTS_AT_MESH 0.13

/* Validates params and hosts and builds the net; on failure the net is
 * freed and err says why. The box form makes a box-only host set and goes
 * the same way; the set form only reads `hosts`, which must outlive the
 * net. */
banyan_status roots_net_build(const banyan_roots_params *p, const banyan_box *hosts, uint32_t n_hosts,
                              roots_net *net, banyan_error *err);
banyan_status roots_net_build_hosts(const banyan_roots_params *p, const banyan_hosts *hosts, roots_net *net,
                                    banyan_error *err);
void roots_net_free(roots_net *net);
/* Sweeps the net into a mesh (spec 5). */
banyan_status roots_net_mesh(const roots_net *net, const banyan_roots_params *p, banyan_mesh **out,
                             banyan_roots_stats *stats, banyan_error *err);

/* The fused surface (fused.c): one closed surface of the whole
 * net through an OpenVDB level set; roots_net_mesh calls it when
 * p->surface is BANYAN_ROOTS_FUSED. */
banyan_status roots_net_mesh_fused(const roots_net *net, const banyan_roots_params *p, banyan_mesh **out,
                                   banyan_roots_stats *stats, banyan_error *err);
/* Shared by both surfaces (mesh.c): the builder with the roots' attributes
 * (`root_kind`, `root_id`, the wind and birth slots: mesh/wind.h), colour and fig-bark material; the skeleton
 * (returns -1 when out of memory). */
struct wind_slots;
void roots_mesh_init(mesh_builder *mb, const banyan_roots_params *p, int *a_kind, int *a_id, struct wind_slots *ws);
int roots_mesh_skeleton(mesh_builder *mb, const roots_net *net, const banyan_roots_params *p);

/* Wind and birth values of a net (wind.c): per point of net->pts its
 * birth 0..1 and stiffness 0..1, per polyline its pivot (the skeleton
 * point it starts from on its parent, G for main roots) and phase; the
 * level is the polyline's kind. roots_wind_build returns -1 when out of
 * memory (rw then holds nothing). */
typedef struct roots_wind {
    double *birth, *stiff; /* n_pts each (one block) */
    v3 *pivot;             /* n_poly */
    double *phase;         /* n_poly */
} roots_wind;
int roots_wind_build(const roots_net *net, const banyan_roots_params *p, roots_wind *rw);
void roots_wind_free(roots_wind *rw);

/* Sweeps the aerial polylines as round tubes from their second point on,
 * into the fused surface's builder, whose first nt triangles are the
 * surface; each thread's first ring goes back towards its first point
 * onto the surface, so it leaves the bark with neither a gap nor a
 * crossing. Capped at both ends (closed shells); attributes a_kind, a_id,
 * the wind and birth of rw. roots_aerial_counts gives what one adds, for
 * mb_reserve (the sweep reads the builder's arrays, which must not
 * move). */
void roots_aerial_sweep_all(mesh_builder *mb, const roots_net *net, uint32_t nt, int a_kind, int a_id,
                            const struct wind_slots *ws, const roots_wind *rw);

/* The soil line (soil.c): rewrites the finished mesh's vertex colours as
 * a multiplier of the bark, white above a band about soil_line high
 * where the roots meet the ground, a darker, warmer soil tint towards it
 * (all white with the ground off or soil_line 0). m is in the net's frame
 * (before frame_set); the stain follows world x, y. */
void roots_soil_line(const roots_net *net, const banyan_roots_params *p, banyan_mesh *m);

/* Stages (each file's header comment names its spec section). */
void roots_grow_mains(roots_net *net, const banyan_roots_params *p);
void roots_grow_first(roots_net *net, const banyan_roots_params *p);
void roots_correct_mains(roots_net *net, const banyan_roots_params *p);
void roots_grow_second(roots_net *net, const banyan_roots_params *p);
void roots_press_first(roots_net *net, const banyan_roots_params *p);
/* Hugging: a point 1.5 r .. 4 hug_range r off a host goes back to about r
 * from it (when free there); returns 1 when it moved. */
int roots_press_point(const roots_world *w, const banyan_roots_params *p, v3 *q);
banyan_status roots_make_paths(roots_net *net, const banyan_roots_params *p);
/* The foot (foot.c): drop roots, plank buttresses and surface roots,
 * appended as ROOT_FOOT polylines once the radii are set. */
banyan_status roots_grow_foot(roots_net *net, const banyan_roots_params *p);
/* Aerial roots (aerial.c): thin threads hanging from the net, appended
 * as ROOT_AERIAL polylines after the foot. Their first point is the net
 * point they hang from (inside that root); the fused surface leaves them
 * out of its field and sweeps them with roots_aerial_sweep_all. */
banyan_status roots_grow_aerial(roots_net *net, const banyan_roots_params *p);
/* Sides of an aerial root's tube on the fused surface. */
#define ROOTS_AERIAL_SIDES 6
/* Vertices and indices the sweep adds for aerial polyline pl. */
void roots_aerial_counts(const roots_poly *pl, uint32_t *verts, uint32_t *indices);
/* The root_id after every polyline's so far (stages that append roots
 * number theirs on from it). */
static inline int roots_next_id(const roots_net *net) {
    int id = 0;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].id >= id) id = net->poly[t].id + 1;
    return id;
}
/* Room for `more` points (pts and rad); 0 when out of memory. */
int roots_reserve_pts(roots_net *net, uint32_t more);
/* Appends a polyline record (from = UINT32_MAX, soil_from = n); 0 when out of memory. */
int roots_add_poly(roots_net *net, uint32_t off, uint32_t n, int kind, int id, int a, int k);

/* First-branch slot k of a main root starts at growth index (0-based). */
static inline int roots_branch_b(const banyan_roots_params *p, int k) {
    return p->branch_start - 1 + k * p->branch_spacing;
}

/* Growth index on main root a+1 where the first branch root of slot
 * a * nb + k ends. */
static inline int roots_branch_end_b(const roots_net *net, const banyan_roots_params *p, int slot) {
    return roots_branch_b(p, net->K_end[slot]);
}

/* A first branch root grows in slot (a, k) only where both its ends lie
 * above the soil entry of their main roots (soil_entry). */
static inline int roots_slot_open(const roots_net *net, const banyan_roots_params *p, int a, int k) {
    int b = roots_branch_b(p, k);
    return b < net->soil_b[a] && b < net->soil_b[(a + 1) % net->N];
}

/* A segment between two free sphere centres may sag this far (times r)
 * into the r-offset of a host before it counts as cutting through: a chord
 * round a convex corner always dips a little, and a tube of n sides is
 * itself a polygon. Shared by the first-branch step test and segment
 * repair, so steps checked by one need not be checked by the other. */
#define ROOTS_SAG 0.2

/* Per-entity random streams (pcg32_seed's stream argument). */
enum { STREAM_SHARED = 1, STREAM_MAIN = 0x100, STREAM_FIRST = 0x10000, STREAM_SECOND = 0x20000000,
       STREAM_FOOT = 0x30000000, STREAM_AERIAL = 0x38000000, STREAM_TILT = 0x3c000000 };

/* The params checks of banyan_roots_generate: the table, then the rules
 * that tie fields together (generate.c). */
banyan_status roots_params_check(const banyan_roots_params *p, banyan_error *err);

#endif
