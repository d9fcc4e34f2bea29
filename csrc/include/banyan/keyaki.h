/*
 * banyan/keyaki.h - keyaki (Zelkova serrata) trees and avenues of them.
 *
 * Method: Ishii, Chiba, Saito, "Simulation of natural scenes: procedure
 * modeling for trees" (spec/keyaki.md). A tree is a binary branching
 * process grown level by level under one of four models (simple fork,
 * strong/weak fork, twisted fork, branch-breaking "edaore" fork); the
 * skeleton gets pipe-model radii, tapered tubes and optional leaf cards.
 * An avenue places many trees along a line or polyline, generated in
 * parallel. See docs/keyaki.md for every rule and choice.
 *
 * Keyaki takes no hosts: a tree stands at `position` and grows up +Z.
 *
 * Lengths: every length field marked "unit" is multiplied by `unit`
 * (metres), so `unit` scales the whole tree and keeps its proportions.
 */
#ifndef BANYAN_KEYAKI_H
#define BANYAN_KEYAKI_H
#include <stddef.h>
#include <stdint.h>

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The four branching models of spec/keyaki.md, in the paper's order. */
typedef enum banyan_keyaki_model {
    BANYAN_KEYAKI_SIMPLE = 0,      /* model 1: rules 1-4 */
    BANYAN_KEYAKI_STRONG_WEAK = 1, /* model 2: rules 1-3, 5 */
    BANYAN_KEYAKI_TWISTED = 2,     /* model 3: rules 1, 3, 5, 6 */
    BANYAN_KEYAKI_EDAORE = 3       /* model 4: rules 1, 3, 4, 7-10 (default) */
} banyan_keyaki_model;

/* Rule 7: how the edaore split ratio is drawn from the ten values
 * 0.05:0.95, 0.15:0.85, ..., 0.95:0.05 (index k = 0..9).
 *   UNIFORM: k = rng_below(10).
 *   NORMAL:  k = floor(10 * (u1 + u2 + u3) / 3), u uniform in [0, 1):
 *            an Irwin-Hall bell centred between k = 4 and k = 5 (0.5:0.5). */
typedef enum banyan_keyaki_distribution {
    BANYAN_KEYAKI_UNIFORM = 0,
    BANYAN_KEYAKI_NORMAL = 1
} banyan_keyaki_distribution;

/* Branch lengths of models 2 and 3. EQUAL: every branch is segment_length
 * (rule 4). ENERGY: the children of a split e1:e2 get lengths in the ratio
 * 1/e1 : 1/e2 with mean segment_length (so 1:1 keeps segment_length),
 * the ratio capped at max_length_ratio. */
typedef enum banyan_keyaki_length_rule {
    BANYAN_KEYAKI_LENGTH_EQUAL = 0,
    BANYAN_KEYAKI_LENGTH_ENERGY = 1
} banyan_keyaki_length_rule;

/* Rule 2 (models 1 and 2): the fork plane of a tilted parent d.
 * STEEPEST: the plane in which d is the line of steepest slope, i.e. the
 *           plane through d and the horizontal perpendicular Z x d (the
 *           children spread sideways at equal height; rule 2 as stated).
 * VERTICAL: the vertical plane through d (the spec's "in other words"
 *           reading; every tree of models 1 and 2 is then a flat fan).
 * A vertical parent gets a random heading under both. */
typedef enum banyan_keyaki_fork_plane {
    BANYAN_KEYAKI_PLANE_STEEPEST = 0,
    BANYAN_KEYAKI_PLANE_VERTICAL = 1
} banyan_keyaki_fork_plane;

/* Models 3 and 4: which child of a fork is the strong one (the spec says
 * only that the twist turns "the way that raises the strong child").
 * UPPER:  the child that ends higher; the twist sense raises it most.
 *         Strong children stand up: a central leader, a narrow crown.
 * RANDOM: a side of the fork plane drawn 50:50 at each fork (also the
 *         survivor's side at a break); the twist sense raises that child.
 *         The crown opens like a wine glass. From tilt_mid on (leaning
 *         parents) the upper child is strong, so branches do not hang. */
typedef enum banyan_keyaki_strong_side {
    BANYAN_KEYAKI_SIDE_UPPER = 0,
    BANYAN_KEYAKI_SIDE_RANDOM = 1
} banyan_keyaki_strong_side;

/* Hard caps, documented so callers can plan. */
#define BANYAN_KEYAKI_MAX_LEVELS 30  /* levels 1 .. 30 */
#define BANYAN_KEYAKI_MAX_ORDER 32   /* Strahler orders never exceed levels + 1 */
#define BANYAN_AVENUE_MAX_TREES 10000
#define BANYAN_AVENUE_MAX_THREADS 64 /* threads of a tree or an avenue: 0 (all cores) .. 64 */

typedef struct banyan_keyaki_params {
    uint64_t seed;           /* any value; the tree's PCG32 streams derive from it */
    int32_t max_vertices;    /* 1 .. 2^30; refuse (BANYAN_E_LIMIT) beyond it. Default 4,000,000 */
    int32_t max_nodes;       /* 1 .. 2^24 skeleton branches; refuse (BANYAN_E_LIMIT) beyond. Default 1,000,000 */

    /* --- placement */
    double position[3];      /* m, each within +-1e6: trunk base. Default origin */
    double heading;          /* deg, -360 .. 360: turns the whole tree about its trunk. Default 0 */
    double unit;             /* m, 1e-3 .. 1e3: multiplies every "unit" length. Default 1 */
    double lean;             /* deg, 0 .. 30: the whole tree tilted about its foot (the trunk base) by this much, after
                                it has grown (its shape does not change). Default 0 */
    double lean_direction;   /* deg, -360 .. 360: the way it leans, counter-clockwise from +X, turned with heading.
                                Default 0 */

    /* --- growth (spec "Common terms", models 1-4) */
    int32_t model;           /* banyan_keyaki_model. Default EDAORE */
    int32_t levels;          /* L_max, 1 .. 30: forks from trunk to tip. Default 21 */
    double trunk_length;     /* unit, 0.01 .. 100: bole below the level-1 fork. Default 0.8 */
    double segment_length;   /* unit, 0.01 .. 100: length of one level (rule 4). Default 0.8 */
    double fork_angle;       /* deg, 0 .. 90: each child's angle from its parent at level 1 (rule 3). Default 15 */
    double fork_angle_step;  /* deg, -10 .. 10: added per level; the angle at level l is
                                fork_angle + step * (l - 1), which must stay within 0 .. 90. Default 1 */
    int32_t fork_plane;      /* banyan_keyaki_fork_plane, models 1-2 (rule 2). Default STEEPEST */
    /* models 2 and 3 (rule 5) */
    double strong_probability; /* 0 .. 1: p, the chance of a strong/weak split (7:3 and 3:7 share it). Default 0.5 */
    double strong_ratio;     /* 0.5 .. 0.95: the strong child's share at such a split (0.7 = 7:3). Default 0.7 */
    double stop_energy;      /* 0 .. 1: a branch with less energy stops forking. Default 0.01 */
    int32_t length_rule;     /* banyan_keyaki_length_rule. Default ENERGY */
    double max_length_ratio; /* 1 .. 10: cap of the weak:strong length ratio. Default 3 */
    /* models 3 and 4: twist of the fork plane about the parent (rules 6, 10) */
    double twist;            /* deg, 0 .. 90: tau; model 3 always, model 4 below tilt_mid. Default 35 */
    double twist_mid;        /* deg, 0 .. 90: model 4 twist for tilt_mid <= tilt < tilt_high. Default 15 */
    double twist_high;       /* deg, 0 .. 90: model 4 twist from tilt_high. Default 0 */
    double tilt_mid;         /* deg, 0 .. 180: parent tilt from vertical where twist_mid starts. Default 30 */
    double tilt_high;        /* deg, 0 .. 180, >= tilt_mid: where twist_high starts. Default 60 */
    int32_t strong_side;     /* banyan_keyaki_strong_side, models 3-4. Default RANDOM */
    /* model 4 (rules 7-9) */
    int32_t distribution;    /* banyan_keyaki_distribution. Default UNIFORM */
    double alpha;            /* 1.001 .. 10: break threshold T(l) = alpha^-l. Default 1.3 */
    double springback;       /* 0 .. 1: s; a survivor's angle is angle * (1 - s * (1 - l / L_max)). Default 1 */

    /* --- first branching (beyond the paper; docs/keyaki.md "First branching") */
    int32_t limbs;           /* 1 .. 12: limbs the trunk splits into, the first at trunk_length; each limb then
                                grows as the model's tree of `levels` levels. 1: the paper's single trunk. Default 1 */
    double limb_angle;       /* deg, 0 .. 80: a limb's lean from vertical where it leaves the trunk. Default 35 */
    double limb_zone;        /* unit, 0 .. 10: height over which the limbs leave, from trunk_length up. Default 0.8 */

    /* --- body (beyond the paper) */
    double tip_radius;       /* unit, 1e-4 .. 10: pipe-model radius of a tip branch. Default 0.045 */
    double pipe_exponent;    /* 1 .. 4: p in r_parent^p = sum r_child^p. Default 2.5 */
    double tip_taper;        /* 0.05 .. 1: end radius of a tip as a fraction of tip_radius. Default 0.5 */
    double flare;            /* 0 .. 3: extra trunk radius at the ground, a fraction of the trunk's radius
                                (root flare). Default 0.5 */
    double flare_height;     /* unit, 0.01 .. 10: height over which the flare fades into the trunk. Default 1 */
    int32_t flare_lobes;     /* 0 .. 16: root buttresses round the flare (0: a round flare). Default 5 */
    double bark_tile;        /* m, 0.01 .. 10: side of one bark texture tile on the surface (u wraps a whole
                                number of tiles round a tube). Default 0.4 */
    int32_t sides_max;       /* 3 .. 64: tube sides of the trunk. Default 14 */
    int32_t sides_min;       /* 3 .. 64, <= sides_max: tube sides of the thinnest branches. Default 4 */
    /* twigs and leaves (beyond the paper; docs/keyaki.md "Twigs and leaves"). Twig and leaf sizes are
       metres, not "unit": a keyaki's leaf is 3-7 cm on a young tree and an old one alike. */
    int32_t twig_levels;     /* 0 .. 3: orders of side twigs below the skeleton's outer branches (0: none, the
                                leaves sit on the skeleton). Default 2 */
    double twig_length;      /* m, 0.01 .. 5: length of a first-order twig; each finer order is twig_ratio of
                                its parent. Default 0.5 */
    double twig_ratio;       /* 0.05 .. 1: a twig's length as a fraction of its parent twig's. Default 0.3 */
    double twig_spacing;     /* m, 0.005 .. 5: distance between successive side twigs on a shoot. Default 0.2 */
    double twig_angle;       /* deg, 0 .. 90: a side twig's angle from its parent. Default 50 */
    double twig_radius;      /* m, 1e-4 .. 0.1: radius of a twig's tip (5 mm across by default). Default 0.0025 */
    int32_t light;           /* bool: light and crowding model: twig clusters shaded from the sky steer, stop or
                                drop (docs/keyaki.md "Light and crowding"). Default true */
    double shade_layers;     /* 0.1 .. 20: leaf clusters between a spot and the sky that shade it fully
                                (docs/keyaki.md "Light and crowding"). Default 2 */
    double light_steer;      /* deg, 0 .. 90: largest turn of a twig cluster towards its lit side. Default 35 */
    int32_t leaves;          /* bool: leaves. Default true */
    int32_t leaf_levels;     /* 0 .. 30: skeleton branches within this many levels of a tip carry twigs and
                                leaves; deeper ones (the limbs) carry spray-card shoots where they lie on the
                                crown's outer shell (docs/keyaki.md "Twigs and leaves"). Default 5 */
    double leaf_density;     /* leaves per metre of leafy twig (two ranks, one leaf a node), 0 .. 1000.
                                Default 24 */
    double leaf_size;        /* m, 0.005 .. 1: median blade length. Default 0.055 */
    double leaf_size_spread; /* 0 .. 1: blade lengths vary by up to this fraction either way. Default 0.3 */
    double bark_color[4];    /* linear RGBA. Default grey-brown */
    double leaf_color[4];    /* linear RGBA: the summer leaves' flat colour (textures off). Default green */
    int32_t season;          /* banyan_season: the leaf material (texture and flat colour); the geometry
                                is the same in every season. Default SUMMER */
    double bark_flake_radius; /* m, 0 .. 10: a tube whose first branch is at least this thick (the trunk, the old
                                 limbs) shows the bark's flakes; thinner ones and every twig the texture's smooth
                                 grey-brown lane (BANYAN_KEYAKI_BARK_SMOOTH_U0 .. _U1). Default 0.07 */

    /* --- twigs from segments (spec/segments.md, "Composing a tree"; docs/keyaki.md) */
    int32_t twigs_from_segments; /* bool: grow the skeleton to levels - segment_levels and make the finest
                                    levels as geometry-shader segments along its outer branches. Default false */
    int32_t segment_levels;  /* 1 .. 29, < levels when twigs_from_segments: finest levels the segments replace. Default 4 */
    double segment_twig_length; /* unit, 0.001 .. 100: m, the length of every twig and fork line. Default 0.8 */
    int32_t segment_twigs;   /* 0 .. 63: n, twigs per segment. Default 4 */
    int32_t segment_depth;   /* 0 .. 16: s, fork depth of the first twig (twig i forks to s + i - 1; the
                                128-vertex budget cuts the rest). Default 1 */

    /* --- the run's budget (docs/keyaki.md "Budget"): checked inside growth, crown and meshing; past
       either the call stops with BANYAN_E_LIMIT naming it. In an avenue's `tree` they are not used: the
       avenue's own budget covers every tree. */
    double max_seconds;      /* s, 0.01 .. 604800: wall time of the call. Default 600 */
    double max_memory_mb;    /* MB, 16 .. 1048576: resident memory the call may add. Default 8192 */
    int32_t wind;                 /* bool: the wind attributes (banyan.h, BANYAN_ATTR_WIND_*). Default 1 */
    int32_t threads;         /* 0 (all cores) .. BANYAN_AVENUE_MAX_THREADS: threads that mesh this one tree
                                (banyan_keyaki_generate; the mesh does not depend on it). An avenue's trees each
                                run on one thread: the avenue's own threads field spreads them. Default 0 */
} banyan_keyaki_params;

/* Fills the paper's defaults (edaore, 21 levels, alpha 1.3, ...). */
BANYAN_API void banyan_keyaki_params_init(banyan_keyaki_params *p);
BANYAN_API size_t banyan_sizeof_keyaki_params(void);

/* Topology of the final skeleton (after breaks). */
typedef struct banyan_keyaki_stats {
    int32_t node_count;       /* branches (straight segments), trunk included */
    int32_t tip_count;        /* branches without children */
    int32_t fork_count;       /* branches with two children */
    int32_t break_count;      /* forks where the weak child broke off (model 4) */
    int32_t max_level;        /* deepest level reached */
    int32_t max_order;        /* K: the trunk's Strahler order */
    int32_t stream_count[BANYAN_KEYAKI_MAX_ORDER];   /* [k-1] = N_k, k = 1 .. K; 0 beyond */
    double bifurcation_ratio[BANYAN_KEYAKI_MAX_ORDER]; /* [k-1] = N_k / N_{k+1}, k = 1 .. K-1; 0 beyond */
    double mean_bifurcation_ratio; /* mean of the K-1 ratios; 0 when K == 1 */
    double height;            /* m: highest branch end above position[2]. The skeleton's: the crown's twigs and
                                 leaves reach past the branch ends (the mesh's own is higher) */
    double crown_width;       /* m: twice the largest horizontal distance of a branch end from the trunk base
                                 (the skeleton's, as height) */
    double mean_run_length;   /* levels: mean length of a run of single branches between real forks */
} banyan_keyaki_stats;

BANYAN_API size_t banyan_sizeof_keyaki_stats(void);

/* Grows and meshes one tree. Refuses bad params (BANYAN_E_RANGE naming the
 * field), more than max_nodes branches or max_vertices vertices
 * (BANYAN_E_LIMIT, before the mesh is allocated).
 * stats: NULL, or the measures of the skeleton the mesh was built from
 * (the values banyan_keyaki_skeleton_stats gives for the same params);
 * zeroed on failure. progress: NULL, or called on the calling thread (docs/api.md
 * "Progress and cancel"); a cancel returns BANYAN_E_CANCELLED with *out NULL.
 * The mesh: part 0 bark (material 0, "keyaki_bark"), part 1 leaves
 * (material 1, "keyaki_leaf", double sided; absent without leaves); every
 * part has group 0. Attributes: tree_id (0), level (the branch's level,
 * 0 = trunk), order (its Strahler order). Skeleton: point 0 is the trunk
 * base, point i+1 the end of branch i; one edge per branch; skel_tag =
 * level | order << 8 | broken << 16 (broken: the branch's fork broke).
 * With twigs_from_segments, every tip of the (shorter) skeleton is the
 * axis of one segment; its twig and fork lines (not the axis, which is the
 * branch itself) are thin tubes appended to the bark part, with level =
 * the branch's level + the segment level code (twig = +1, fork depth d =
 * +1 + d) and order 0; they are not in the skeleton. */
BANYAN_API banyan_status banyan_keyaki_generate(const banyan_keyaki_params *p, banyan_mesh **out,
                                                banyan_keyaki_stats *stats, const banyan_progress *progress,
                                                banyan_error *err);

/* Grows the skeleton only (no mesh) and measures it: fast enough for
 * thousands of trees. max_vertices, threads and the body fields are not
 * used. out is zeroed on failure. */
BANYAN_API banyan_status banyan_keyaki_skeleton_stats(const banyan_keyaki_params *p, banyan_keyaki_stats *out,
                                                      banyan_error *err);

/* ------------------------------------------------------------- avenues */

typedef enum banyan_avenue_placement {
    BANYAN_AVENUE_SPACING = 0, /* trees every `spacing` metres, centred on the path */
    BANYAN_AVENUE_COUNT = 1    /* `count` trees per row, first and last at the path's ends */
} banyan_avenue_placement;

/* Most distinct trees of an instanced avenue (banyan_avenue_params.variants). */
#define BANYAN_AVENUE_MAX_VARIANTS 4096

typedef struct banyan_avenue_params {
    uint64_t seed;           /* base seed: tree i uses seed + i */
    int32_t max_vertices;    /* 1 .. 2^30, over the whole avenue (about 66 bytes each). Default 32,000,000 */
    double start[3];         /* m: the path's first point when no polyline is given. Default (0,0,0) */
    double end[3];           /* m: its last point. Default (60,0,0) */
    int32_t rows;            /* 1 .. 2. Default 2 */
    double row_offset;       /* m, 0 .. 1000: distance between the two rows (each at +-half from the path). Default 12 */
    int32_t stagger;         /* bool: shift row 2 by half a spacing. Default false */
    int32_t placement;       /* banyan_avenue_placement. Default SPACING */
    double spacing;          /* m, 0.1 .. 1e4. Default 8 */
    int32_t count;           /* trees per row, 1 .. 10000 (COUNT). Default 10 */
    double heading_jitter;   /* deg, 0 .. 180: heading uniform in +-this. Default 180 (any) */
    double height_jitter;    /* 0 .. 0.9: trunk_length scaled by 1 + uniform(+-this). Default 0.15 */
    double position_jitter;  /* m, 0 .. 100: offset uniform in a disc of this radius. Default 0.3 */
    int32_t levels_jitter;   /* 0 .. 29: levels lowered by a uniform whole number in [0, this] (never below 1),
                                so trees of mixed ages stand side by side. Default 0 */
    double scale_jitter;     /* 0 .. 0.5: tree.unit scaled by 1 + uniform(+-this): the whole tree's size (leaves
                                and twigs keep theirs). Default 0.12 */
    double lean_jitter;      /* deg, 0 .. 30: each tree leans (tree.lean) by uniform(0, this) in a uniform
                                direction (tree.lean_direction). Default 3 */
    banyan_keyaki_params tree; /* every tree; seed, max_vertices, position, heading, lean and lean_direction are
                                  set per tree */
    /* The avenue's budget, over every tree and thread (docs/keyaki.md "Budget"). */
    double max_seconds;      /* s, 0.01 .. 604800: wall time of the call. Default 600 */
    double max_memory_mb;    /* MB, 16 .. 1048576: resident memory the call may add, every thread's. Default 8192 */
    int32_t variants;        /* 0: every tree unique, merged into one mesh. 1 .. 4096: that many distinct
                                trees (variant k grown with seed + k), placed as instances (banyan_instance):
                                the same positions and headings as the unique avenue. Default 0 */
    int32_t threads;         /* 0 (all cores) .. BANYAN_AVENUE_MAX_THREADS: threads that grow the trees, one tree
                                each (fewer when the trees are few or large); the output does not depend on
                                it. Default 0 */
} banyan_avenue_params;

BANYAN_API void banyan_avenue_params_init(banyan_avenue_params *p);
BANYAN_API size_t banyan_sizeof_avenue_params(void);

/* The per-tree params of an avenue, in tree order (row 0 along the path,
 * then row 1). path_xyz: 3 * path_point_count metres (2 .. 1e6 points,
 * finite, consecutive points distinct), or NULL for the start-end line.
 * trees may be NULL (capacity 0) to count only; *tree_count gets the
 * count (at most BANYAN_AVENUE_MAX_TREES, else BANYAN_E_LIMIT). */
BANYAN_API banyan_status banyan_avenue_layout(const banyan_avenue_params *p, const double *path_xyz,
                                              uint32_t path_point_count, banyan_keyaki_params *trees,
                                              uint32_t capacity, uint32_t *tree_count, banyan_error *err);

/* Grows every tree of the avenue on p->threads threads (0 = all cores;
 * fewer are used when the trees are few or large, so scratch memory does
 * not multiply with them) and merges them into one mesh. The output does
 * not depend on the thread count. path_xyz and path_point_count as for
 * banyan_avenue_layout. Tree i's vertices are contiguous; its parts
 * (bark, material 0; leaves, material 1) have group = i; attribute
 * tree_id = i. The skeletons are merged the same way. progress: NULL, or
 * called on the calling thread; a cancel returns BANYAN_E_CANCELLED. */
BANYAN_API banyan_status banyan_avenue_generate(const banyan_avenue_params *p, const double *path_xyz,
                                                uint32_t path_point_count, banyan_mesh **out,
                                                const banyan_progress *progress, banyan_error *err);

#ifdef __cplusplus
}
#endif

#endif
