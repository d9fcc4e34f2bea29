/* keyaki_internal.h - the keyaki skeleton shared by growth, Strahler
 * statistics, the body mesher and the avenue (spec/keyaki.md). Tests
 * include it to inspect skeletons and to run Strahler on hand-built ones. */
#ifndef BANYAN_KEYAKI_INTERNAL_H
#define BANYAN_KEYAKI_INTERNAL_H

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>

#include "banyan.h"
#include "mesh/mesh_builder.h"
#include "base/progress.h"
#include "mesh/wind.h"
#include "base/rng.h"
#include "base/vec.h"

/* Node flags. */
#define KN_BROKEN 1u  /* this branch's fork broke: its weak child was removed (rule 8) */
#define KN_SPRUNG 2u  /* this branch survived a break and its angle sprang back (rule 9) */
#define KN_STRONG 4u  /* this branch is the strong child of a strong/weak fork */
#define KN_STOPPED 8u /* this branch stopped forking: energy below stop_energy (models 2-3) */
#define KN_TRUNK 16u  /* a piece of the trunk below or between the limbs' departures (first split): the
                         model does not fork it; its children are set when the tree starts */

/* One branch: a straight segment from `start` along `dir` for `length`.
 * Nodes are stored parents first (child index > parent index), level by
 * level in growth order. child[0] is the strong (or first) child. */
typedef struct keyaki_node {
    v3 start;        /* m */
    v3 dir;          /* unit */
    v3 plane;        /* unit normal of the fork plane this branch was made in (trunk: a random vertical plane) */
    double length;   /* m */
    double energy;   /* share of the trunk's energy (trunk 1) */
    double share;    /* energy of the limb this branch grows on (1 with one limb): the model's rules read
                        energy / share, so every limb grows as the model's whole tree would */
    double angle;    /* deg between this branch and its parent (0 for the trunk) */
    double radius;   /* m, pipe model (keyaki_radii) */
    int32_t parent;  /* -1 for the trunk */
    int32_t child[2];/* -1 when absent; a single child is child[0] */
    int32_t level;   /* 0 = trunk; a child of a level-l branch has level l + 1 */
    int32_t order;   /* Strahler order (keyaki_strahler) */
    uint32_t flags;  /* KN_* */
} keyaki_node;

/* A run's budget as the tree's loops see it (budget.c, docs/keyaki.md
 * "Budget"). Alone, g is the call's prog. In an avenue the calling thread
 * holds g and every thread watches `stop`; `tally` sums the vertices every
 * tree has counted or is already sure to need, so a refused avenue stops
 * at the same total whatever the thread count. */
typedef struct keyaki_run {
    prog *g;               /* the caller's budget and callback; NULL in an avenue's other threads */
    atomic_int *stop;      /* avenue: set once any thread stops; NULL alone */
    atomic_ullong *tally;  /* avenue's count pass: vertices counted or promised by all trees; NULL alone */
    uint64_t max_vertices; /* what the tree (alone) or the tally may reach; UINT64_MAX: no estimate */
    uint64_t promised;     /* this tree's part of the tally so far */
    int threads;           /* threads that may mesh this one tree (0, 1: the caller alone; an avenue's trees
                              keep 1: no pools inside its pool) */
    int stages;            /* 1: the run is one tree's whole call, and g's fraction moves as its stages end
                              (KEYAKI_AT_*); 0 in an avenue, whose own loop moves it */
} keyaki_run;

/* The fraction of a tree's call done when each stage ends (keyaki_run.stages). */
#define KEYAKI_AT_GROWN 0.25
#define KEYAKI_AT_PLANNED 0.6
#define KEYAKI_AT_MESHED 0.95

/* Reports that a stage of a one-tree run ended (keyaki_run.stages; nothing
 * otherwise): 1 once the run must stop, as keyaki_stopped. */
int keyaki_stage(keyaki_run *r, double done);

/* 1 once the run must stop (budget spent, cancelled, or another thread
 * stopped); cheap: a clock read. Loops call it every few hundred items. */
int keyaki_stopped(keyaki_run *r);
/* Status of a loop that saw keyaki_stopped; the public call replaces it
 * with prog_fail's message. */
banyan_status keyaki_stop_status(banyan_error *err);
/* The tree is already sure to need `vertices` (a lower bound that only
 * grows): BANYAN_E_LIMIT, naming max_vertices and `lower` (the fields to
 * lower), once that passes max_vertices, alone or with the avenue's tally. */
banyan_status keyaki_promise(keyaki_run *r, uint64_t vertices, const char *what, const char *lower,
                             banyan_error *err);
/* An allocation of `bytes` about to be made: 1 (and the run stopped) when
 * it would pass max_memory_mb. Only where g is set; elsewhere the caller's
 * polls of the resident size keep the budget. */
int keyaki_reserve_bytes(keyaki_run *r, double bytes);
/* qsort that keeps the run: checks keyaki_stopped as it merges a large
 * array; 1 when stopped (the array is then left part sorted). cmp must be
 * a total order: the result is then qsort's. */
int keyaki_sort(void *base, size_t n, size_t size, int (*cmp)(const void *, const void *), keyaki_run *r);
/* Bytes of a mesh of v vertices and i indices (with colours, the three
 * attributes, birth and, with wind, the seven wind attributes), for
 * keyaki_reserve_bytes. */
static inline double keyaki_mesh_bytes(uint64_t v, uint64_t i, int wind) {
    return (64.0 + (wind ? 28.0 : 0.0)) * (double)v + 4.0 * (double)i;
}

/* A growable skeleton; reuse one across calls to avoid allocations.
 * run: the budget its growth and meshing keep (NULL: none). */
typedef struct keyaki_skeleton {
    keyaki_node *nodes;
    int32_t count, cap;
    keyaki_run *run;
} keyaki_skeleton;

void keyaki_skeleton_free(keyaki_skeleton *sk);

/* The levels the skeleton is grown to: levels, or levels - segment_levels
 * when the finest levels come from segments (twigs.c). */
static inline int keyaki_grown_levels(const banyan_keyaki_params *p) {
    return p->twigs_from_segments ? p->levels - p->segment_levels : p->levels;
}

/* Checks every field (table ranges, then the rules tying fields together). */
banyan_status keyaki_params_validate(const banyan_keyaki_params *p, banyan_error *err);

/* Grows the skeleton of p (validated) into sk, replacing its contents,
 * and sets the pipe-model radii (keyaki_radii). With twigs_from_segments
 * the full tree is grown, radii set, then cut to keyaki_grown_levels
 * (keyaki_truncate). BANYAN_E_LIMIT past max_nodes, or as soon as the
 * branches grown so far need more than sk->run's max_vertices (each is at
 * least one ring of sides_min + 1 vertices), BANYAN_E_NOMEM; stops when
 * sk->run does (keyaki_stop_status). */
banyan_status keyaki_grow(const banyan_keyaki_params *p, keyaki_skeleton *sk, banyan_error *err);

/* Strahler orders of every node (tips 1; equal orders meeting give k + 1,
 * different orders the higher; a single child passes its order up).
 * Needs child index > parent index; returns BANYAN_E_INTERNAL otherwise. */
banyan_status keyaki_strahler(keyaki_node *nodes, int32_t count);

/* Fills st from a skeleton whose orders are set. base: the trunk base. */
void keyaki_measure(const keyaki_node *nodes, int32_t count, v3 base, banyan_keyaki_stats *st);

/* Pipe-model radii, children first. */
void keyaki_radii(keyaki_node *nodes, int32_t count, double tip_radius, double exponent);

/* A side limb's first ring, set back inside its parent, has this fraction
 * of the child's radius; the second ring, at the fork point, has all of
 * it. The child so emerges from the parent as a widening tube, and the
 * seam where the two tubes cross stays short. */
#define KEYAKI_SIDE_START 0.75

/* Body: a limb is one continuous tube through a chain of branches, always
 * continuing into the thicker child (tie: child[0]). */
typedef struct keyaki_limb {
    int32_t first;        /* first node of the chain */
    int32_t points;       /* ring count: nodes in the chain + 1, + 1 more for a side limb */
    int32_t sides;
    v3 start;             /* centre of the first ring (inside the parent for a side limb) */
    double start_radius;  /* m: KEYAKI_SIDE_START x the child's radius for a side limb */
    uint32_t vertex_offset; /* first ring's first vertex in the mesh (tree-local) */
} keyaki_limb;

typedef struct keyaki_wind keyaki_wind; /* below, with the body */

/* The crown (crown.c, docs/keyaki.md "Twigs and leaves", "Light and
 * crowding"): twigs below the skeleton and the leaves on them, generated
 * into flat arrays (grown by doubling) before meshing so they are counted
 * exactly. */
typedef struct keyaki_twig {
    int32_t first, count; /* its polyline: points first .. first + count - 1 of pts / rad */
    int32_t parent;       /* parent twig; -1: sits on skeleton branch `node` */
    int32_t node;         /* the skeleton branch its cluster grows from */
    int32_t order;        /* 1 = first-order twig (on the skeleton) .. twig_levels */
    int32_t level;        /* level attribute: the branch's level + order */
    int32_t sides;        /* tube sides */
    int32_t children;     /* sub-twigs on it (0: a twig tip) */
    double path0;         /* m: path length from the trunk base to its first point (birth) */
} keyaki_twig;

typedef struct keyaki_leaf {
    v3 base;        /* on the twig's axis: a leaf's petiole end (its quad's v = 0 edge centre), a card's painted twig base */
    v3 axis;        /* unit, petiole towards the blade's tip */
    v3 width;       /* unit, across the quad; width x axis is the face normal (z >= 0) */
    double length;  /* m, quad length: petiole + blade (blade: length x (LEAF_KEYAKI_BLADE_V1 - V0)) */
    int32_t twig;   /* twig it grows on; -1: on skeleton branch `node` or a segment line there */
    int32_t node;
    int32_t side;   /* +1 / -1: its rank, alternating along the twig */
    int32_t level;
    float path;     /* m: path length from the trunk base to `base` along the wood (birth, stiffness) */
    int32_t card;   /* 0: a single leaf; 1: a spray card (leaf_look.h LEAF_KEYAKI_SPRAY_*): `length` along
                       its painted twig, LEAF_KEYAKI_SPRAY_ASPECT times its width, its twig's base on the wood */
} keyaki_leaf;

typedef struct keyaki_crown {
    keyaki_twig *twigs;
    v3 *pts;
    double *rad;
    keyaki_leaf *leaves;
    int32_t n_twigs, cap_twigs, n_pts, cap_pts, n_leaves, cap_leaves;
    int32_t tips;                               /* twigs without sub-twigs */
    int count_only;                             /* n_leaves counted, leaves[] not filled */
    int32_t clusters, grown, steered, stopped, dropped; /* the light model's tally */
    uint64_t vertices, indices;                 /* the twig tubes' mesh */
    keyaki_run *run;                            /* the budget its growth and meshing keep (NULL: none) */
} keyaki_crown;

/* Grows the crown of a grown skeleton (radii set) into c (zeroed first;
 * free with keyaki_crown_free). Own PCG32 streams ("twigs", "leaves")
 * keyed by (seed, cluster): never the growth stream. count_only: the
 * same twigs and counts, but the leaves only counted (sizing a tree).
 * BANYAN_E_NOMEM. */
banyan_status keyaki_crown_grow(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, int count_only,
                                keyaki_run *run, keyaki_crown *c, banyan_error *err);
void keyaki_crown_free(keyaki_crown *c);
/* Appends the twig tubes to the current part (c->vertices exactly), with
 * their wind and birth, and the twigs to the skeleton (w: NULL for none). */
/* Smooth bark: the uvs of vertices from .. mb->nv - 1 (one tube swept
 * with `tiles` bark tiles round, and its caps) moved into the keyaki bark
 * texture's smooth lane (BANYAN_KEYAKI_BARK_SMOOTH_U0 .. _U1), v scaled
 * alike so texels stay square (body.c). */
void keyaki_bark_smooth(mesh_builder *mb, uint32_t from, int tiles);
void keyaki_crown_mesh_twigs(const keyaki_crown *c, mesh_builder *mb, const int attr[3], const keyaki_wind *w);
/* Appends leaves k0 .. k1 - 1 (4 vertices, 6 indices each; every value
 * from k alone, so ranges may be meshed on several threads into disjoint
 * slices) to the current part, with their wind and birth (w: NULL for
 * none); run: the budget this thread may poll. */
void keyaki_crown_mesh_leaves(const banyan_keyaki_params *p, const keyaki_crown *c, mesh_builder *mb,
                              const int attr[3], const keyaki_wind *w, int32_t k0, int32_t k1, keyaki_run *run);
/* Skeleton points and edges the crown's twigs add. */
void keyaki_crown_skel_counts(const keyaki_crown *c, uint64_t *points, uint64_t *edges);

typedef struct keyaki_body {
    keyaki_limb *limbs;
    int32_t limb_count;
    keyaki_crown crown;
    uint32_t vertices, indices;         /* totals: bark + leaves */
    uint32_t bark_vertices, bark_indices;
    uint32_t skel_points, skel_edges;   /* the mesh's skeleton: branches, twigs and segment lines */
    keyaki_run *run;                    /* the budget meshing keeps (from keyaki_body_plan) */
    wind_slots ws;                      /* the wind and birth slots (none after keyaki_body_plan) */
} keyaki_body;

/* skel_tag bit of the points below the skeleton proper (crown twigs and
 * segment twig lines): their tag is level | KEYAKI_SKEL_TWIG, no order.
 * Readers of the branch skeleton skip them. */
#define KEYAKI_SKEL_TWIG (1 << 17)

/* Path lengths from the trunk base to each branch's start, m (parents
 * first). */
static inline void keyaki_node_paths(const keyaki_node *n, int32_t count, double *path) {
    for (int32_t i = 0; i < count; i++) path[i] = n[i].parent < 0 ? 0.0 : path[n[i].parent] + n[n[i].parent].length;
}

/* Wind while one tree is meshed (body.c; docs/keyaki.md "Wind and growth
 * attributes"). A wind branch is the run of skeleton branches one body
 * tube sweeps through, except that the trunk (branch 0 and the trunk
 * pieces) is one of its own: its pivot is its first branch's start,
 * its phase that branch's. Births are written as path lengths (m) and
 * scaled to 0..1 once the tree is meshed. */
struct keyaki_wind {
    const wind_slots *ws;
    const keyaki_node *n;
    int32_t *root;     /* per branch: the first branch of its wind branch */
    int32_t *level;    /* per branch: its wind branch's level (trunk 0, limbs 1, a side branch its parent's + 1) */
    double *path;      /* per branch: path length from the trunk base to its start, m */
    uint64_t seed;
    uint32_t skel0;    /* the tree's first skeleton point (point skel0 + i + 1 ends branch i) */
};

/* Wood stiffness s = (1 - p / P)^KEYAKI_STIFF_POWER, p the path length
 * from the trunk base (the birth's), P the tree's longest: 1 at the trunk
 * foot only, continuous across forks (a child's base has its parent's
 * path), falling toward every tip; a leaf takes its wood's. Written once
 * the tree is meshed, from the births (body.c), so the meshers pass 1. */
#define KEYAKI_STIFF_POWER 1.5

/* The skeleton point where branch i starts. */
static inline uint32_t keyaki_skel_start(const keyaki_wind *w, int32_t i) {
    return w->skel0 + (uint32_t)(w->n[i].parent < 0 ? 0 : w->n[i].parent + 1);
}

/* Phase ids: branches are their index; twigs, leaves and segment lines
 * get ids of their own kinds. */
#define KEYAKI_PHASE_TWIG (1ull << 40)
#define KEYAKI_PHASE_LEAF (2ull << 40)
#define KEYAKI_PHASE_LINE (3ull << 40)

void keyaki_body_free(keyaki_body *b);

/* Plans the body of a grown skeleton (radii, orders set): limbs, sides,
 * the crown (keyaki_crown_grow) and exact totals, so the caller can
 * refuse past max_vertices before meshing. count_only: leaves counted,
 * not placed (the body can then only be measured, not meshed). */
banyan_status keyaki_body_plan(const banyan_keyaki_params *p, const keyaki_node *nodes, int32_t count, int count_only,
                               keyaki_run *run, keyaki_body *body, banyan_error *err);

/* Meshes a planned body into mb: bark part (material bark_mat, group) then
 * leaf part (leaf_mat, group); sets the tree_id/level/order attributes in
 * slots attr[0..2]; adds the skeleton. */
void keyaki_body_mesh(const banyan_keyaki_params *p, const keyaki_node *nodes, int32_t count, keyaki_body *body,
                      mesh_builder *mb, const int attr[3], uint32_t bark_mat, uint32_t leaf_mat, uint32_t group,
                      double tree_id);

/* Twigs from segments (twigs.c). */
/* Keeps the branches of level <= max_level (a prefix: nodes are stored
 * breadth first); the new tips lose their children and KN_BROKEN. */
void keyaki_truncate(keyaki_skeleton *sk, int max_level);
/* The segment params of the twigs: the paper's angles, m = segment_twig_length * unit. */
void keyaki_twig_params(const banyan_keyaki_params *p, banyan_segment_params *sp);
/* The segment input of tip branch x. */
void keyaki_twig_input(const banyan_keyaki_params *p, const keyaki_node *x, banyan_segment_input *in);
/* Tube radius of a line of segment level code level_code >= 1 on the
 * segment whose axis is tip branch x, m. */
double keyaki_twig_radius(const banyan_keyaki_params *p, const keyaki_node *x, int level_code);
/* Exact vertex and index counts of the twig tubes, and the lines (each
 * 2 skeleton points and 2 edges) (0 without the flag). */
void keyaki_twigs_plan(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, uint64_t *vertices,
                       uint64_t *indices, uint64_t *lines);
/* The segment of tip branch x (line 0 its axis): xyz and level codes as
 * banyan_segment_lines gives them, parent[j] the line that line j
 * leaves, and path[j] the path length from the trunk base to line j's
 * start (path_x: to x's start), m. Returns the vertex count (2 a line),
 * 0 on failure. */
int32_t keyaki_twig_lines(const banyan_keyaki_params *p, const keyaki_node *x, double path_x, float *xyz,
                          uint8_t *level, uint8_t *parent, double *path);
/* Appends the twig tubes to the current part of mb (attr[1] level,
 * attr[2] order; tree_id as set), with their wind and birth, and their
 * lines to the skeleton (w: NULL for none). */
void keyaki_twigs_mesh(const banyan_keyaki_params *p, const keyaki_node *n, int32_t count, mesh_builder *mb,
                       const int attr[3], const keyaki_wind *w);

/* The whole pipeline for one tree into a fresh mesh (used by keyaki and
 * avenue). sk is a scratch skeleton (may be reused). */
banyan_status keyaki_build(const banyan_keyaki_params *p, double tree_id, uint32_t group, keyaki_skeleton *sk,
                           banyan_mesh **out, banyan_error *err);

/* The same into a builder the caller made (mb_init, or mb_init_external
 * on a slice of an avenue's merged mesh, sized by keyaki_count): grows,
 * plans, refuses past max_vertices, adds the materials, the attributes
 * tree_id, level, order and the body. A failure in the builder is left
 * in mb->status (BANYAN_E_INTERNAL when the plan was not exact). */
banyan_status keyaki_build_into(const banyan_keyaki_params *p, double tree_id, uint32_t group, keyaki_skeleton *sk,
                                mesh_builder *mb, banyan_error *err);

/* Grows + plans without meshing: the exact sizes of a tree's mesh. */
typedef struct keyaki_counts {
    uint32_t vertices, indices;
    uint32_t nodes; /* skeleton branches */
    uint32_t skel_points, skel_edges; /* the mesh's skeleton with twigs (edges = points - 1) */
    uint32_t parts; /* 1 (bark) or 2 (bark, leaves) */
} keyaki_counts;
banyan_status keyaki_count(const banyan_keyaki_params *p, keyaki_skeleton *sk, keyaki_counts *c, banyan_error *err);

/* banyan_avenue_generate with p->variants > 0 (variants.c): the layout's
 * first trees grown once each at the origin, shown as instances. */
/* The avenue's frame (base/frame.h) picked from the trees' feet into *O;
 * on_path: the trees stand on a polyline (named so in the error). */
banyan_status avenue_frame(const banyan_keyaki_params *trees, uint32_t n, int on_path, v3 *O, banyan_error *err);

/* Builds trees[0..n) (positions in the avenue's frame, whose origin is
 * `origin`; tree i is group i, tree_id i) into one mesh: a pass sizes
 * every tree exactly, then each is built straight into its slice of the
 * merged arrays, on `threads` threads (0: all cores), the same bytes on
 * any count. `what` names the trees and `lower` what lowers their size
 * in the max_vertices message. Progress and budget through g, finished
 * here. */
banyan_status avenue_build(const banyan_keyaki_params *trees, uint32_t n, int threads, int max_vertices, v3 origin,
                           prog *g, const char *what, const char *lower, banyan_mesh **out, banyan_error *err);

banyan_status avenue_variants_generate(const banyan_avenue_params *p, const double *path_xyz, uint32_t path_point_count,
                                       banyan_mesh **out, const banyan_progress *progress, banyan_error *err);

/* PCG32 stream numbers of one tree. */
#define KEYAKI_STREAM_GROWTH 0x6b6579616b69ull /* "keyaki" */
#define KEYAKI_STREAM_LEAVES 0x6c6561766573ull /* "leaves" */
#define KEYAKI_STREAM_TWIGS 0x7477696773ull    /* "twigs" */
#define AVENUE_STREAM_JITTER 0x6a6974746572ull /* "jitter" */
#define AVENUE_STREAM_SHAPE 0x7368617065ull     /* "shape": size and lean */

#endif
