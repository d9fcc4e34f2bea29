/*
 * banyan/ivy.h - climbing ivy (Boston ivy, Parthenocissus) by growth
 * simulation: Shindo and Sakamoto's parametric L-system with a directed
 * random walk, light competition and sag of unattached stems
 * (spec/ivy.md). Included by banyan.h.
 *
 * Two ways to use it:
 *   - one shot: banyan_ivy_generate(params, hosts, &mesh, &stats,
 *     &progress, &err) grows params->steps steps and meshes the result;
 *   - stepping: banyan_ivy_create, then banyan_ivy_step(n) as often as
 *     wanted, banyan_ivy_mesh / banyan_ivy_stats at any point, and
 *     banyan_ivy_free. Growing 100 steps then 50 more gives the same plant
 *     as growing 150 at once.
 *
 * Units: metres, steps, degrees where a field says "deg". The paper's
 * Table 3 is in millimetres (1 px = 1 mm); the defaults are those values
 * in metres.
 */
#ifndef BANYAN_IVY_H
#define BANYAN_IVY_H

#include <stdint.h>

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest `steps` (and largest n of one banyan_ivy_step call). */
#define BANYAN_IVY_MAX_STEPS 100000
/* Most threads of banyan_ivy_params.threads (as an avenue's). */
#define BANYAN_IVY_MAX_THREADS 64

/* Bud states (also the skeleton's skel_tag). A0, A1, A2 are the three
 * successive apical states; A2 has no sucker. D is dormant, Z ended. */
typedef enum banyan_ivy_bud_state {
    BANYAN_IVY_A0 = 0,
    BANYAN_IVY_A1 = 1,
    BANYAN_IVY_A2 = 2,
    BANYAN_IVY_D = 3,
    BANYAN_IVY_Z = 4
} banyan_ivy_bud_state;

typedef struct banyan_ivy_params {
    uint64_t seed;              /* any value; same seed, same bytes */
    int32_t max_vertices;       /* mesh vertex cap, 1 .. 1<<30; more -> BANYAN_E_LIMIT */
    int32_t steps;              /* growth steps of banyan_ivy_generate, 0 .. BANYAN_IVY_MAX_STEPS (paper: 450) */
    double wrap_angle;          /* deg, 0 .. 180: a stem bends over an edge or curve whose surface turns by at most this (0: never) */
    double years;               /* > 0: grow this many years instead of `steps` (banyan_ivy_steps), 0 .. 1000 */
    double shoot_growth;        /* a leading shoot's growth per year, m, 0.01 .. 10: years x this / internode steps */
    int32_t max_buds;           /* bud cap, 1 .. 50,000,000; a step that could pass it -> BANYAN_E_LIMIT */
    int32_t candidates;         /* K, random-walk candidates per new bud, 1 .. 1000 */
    int32_t h1_buds;            /* buds before a dormant bud whose H0 adds into H1, 0 .. 64 */
    int32_t leaf_growth_steps;  /* steps a leaf (and its shadow) takes to reach leaf_max, 1 .. 100000 */
    int32_t sucker_pull;        /* 0/1: a bud that attaches is drawn to `clearance` off the surface */
    int32_t leaves;             /* 0/1: emit leaves (a petiole and a blade per bud) in the mesh */
    int32_t stem_sides;         /* sides of a stem tube, 3 .. 64 */
    int32_t helio_in_plane;     /* 0/1: for a bud within sucker reach, V_l is taken along the surface (docs/ivy.md) */
    int32_t ground;             /* plane z = ground_z: 0 none, 1 obstacle (stems rest on it, suckers do
                                   not grip it), 2 host (ivy climbs it too) */

    double start[3];            /* growth start, m; placed on the nearest host side a stem can grow from */
    double start_snap_max;      /* farthest the start may be from every host, m, 0 .. 1e6 (the ground does not count) */
    double ground_z;            /* height of the ground plane, m, -1e6 .. 1e6 */
    double internode;           /* l, internode length, m, 0.001 .. 10 (paper 30 mm) */
    double sucker_length;       /* D, sucker reach, m, 0 .. 10 (paper 30 mm) */
    double clearance;           /* gap a stem keeps from host surfaces, m, 1e-5 .. 1 */
    double leaf_max;            /* d_max, largest leaf (shadow) diameter, m, 0.001 .. 10 (paper 60 mm) */

    double t0;                  /* light threshold on H0 / H1, 0 .. 1e6 (paper 15 or 20) */
    double t1;                  /* nourishment an apical bud needs to grow, 0 .. 1e6 (paper 0.2) */
    double t2;                  /* nourishment a dormant bud needs to sprout, >= t1, 0 .. 1e6 (paper 2.0) */
    double alpha;               /* apical dominance, 0.5 .. 1 (paper 0.8) */
    double beta;                /* nourishment gained per step, 0 .. 1e3 (paper 0.05) */
    double n_start;             /* nourishment of the first bud, 0 .. 1e6 */

    double theta_max;           /* largest turn per axis of a candidate, deg, 0 .. 180 */
    double branch_angle;        /* R(theta) of rule p3, lateral branch angle, deg, 0 .. 180 */
    double w_d;                 /* weight of f_d (stay within sucker reach), 0 .. 100 */
    double w_v;                 /* weight of f_v (gentle turns), 0 .. 100 */
    double w_geo;               /* weight of f_geo (grow up), 0 .. 100 */
    double w_grav;              /* weight of f_grav (long free stems fall), 0 .. 100 */
    double w_helio;             /* weight of f_helio (grow towards light), 0 .. 100 */
    double w_cross;             /* weight of f_cross (a new internode crosses no stem, seen along the surface), 0 .. 100 */
    int32_t start_stems;        /* leading stems from the start, 1 .. 64 (docs/ivy.md, "Stem architecture") */
    int32_t crossing_ends;      /* 0/1: a bud whose every candidate crosses a stem ends instead of crossing */
    double follow_length;       /* with crossing_ends, a tip meeting a stem turns and runs alongside it for up to this, m, 0 .. 100 (0: it ends) */
    int32_t ground_branching;   /* 0/1: dormant buds lying on an obstacle ground may sprout laterals */
    double w_tendril;           /* weight of f_tendril (a free bud near a surface turns towards it), 0 .. 100 */
    double surface_reach;       /* a bud within this of a surface: light along it, f_cross and f_tendril act, m, 0 .. 10 */
    double start_fan;           /* the leading stems spread over +-start_fan from up along the start surface, deg, 0 .. 180 */
    double free_length;         /* unattached length after which f_grav acts and the free tip turns up, m, 0 .. 100 */
    double bmax;                /* Bmax: an unattached run longer than this ends (p6), m, 0 .. 100 */

    double gravity;             /* g, m/s^2, 0 .. 1000 (paper 9.8) */
    double internode_mass;      /* mass of one internode with its leaf, kg, 0 .. 1000 */
    double moment_max;          /* moment a joint holds before the stem sags, N m, 0 .. 1e6 */
    double sag_step;            /* rotation increment of the sag correction, deg, 0.5 .. 90 */
    double tip_elevation;       /* a free tip turns up to at least this angle above horizontal, deg, -90 .. 90 */
    double sag_stiffening;      /* a joint holds moment_max * (r / stem_radius)^this (r: its stem radius by age), 0 .. 6 */
    double tip_hook_length;     /* the last this much of a free stem bends up into a hook (a J), m, 0 .. 10 */
    double tip_hook_angle;      /* elevation the hook's last internode reaches, deg, -90 .. 90 */

    double stem_radius;         /* r0, stem radius at birth, m, 1e-5 .. 1 */
    double stem_radius_growth;  /* k, radius added per step of age, m, 0 .. 1 */
    double stem_radius_max;     /* cap of the age rule, m, >= stem_radius, 1e-5 .. 1 */
    double stem_pipe;           /* pipe model: a stem is at least this x sqrt(buds it carries) thick, m, 0 .. 0.1 */
    double leaf_scale;          /* overall multiplier of the drawn blade sizes, 0 .. 10 */
    double leaf_size_min;       /* drawn blade size (across the side lobes) of a new leaf, m, 0.001 .. 1 */
    double leaf_size_max;       /* drawn blade size of a full-grown leaf, m, >= leaf_size_min, 0.001 .. 1 */
    double leaf_petiole;        /* petiole length over blade size, 0 .. 5 */
    double leaf_tilt;           /* mean turn of a blade off the surface towards the sky, deg, 0 .. 90 */
    double leaf_spread;         /* per-leaf random spread of that turn and of the blade's heading, deg, 0 .. 90 */
    double leaf_share;          /* share of the buds that carry a leaf where the cover is average, 0 .. 1 */
    double leaf_clump;          /* how far that share varies over clumps: 0 even, 1 from none to twice, 0 .. 1 */
    double clump_size;          /* size of those clumps, m, 0.01 .. 100 */
    double clump_relief;        /* dense clumps stand this much further out than the average, thin zones as much nearer, m, 0 .. 1 */
    double edge_fray;           /* width of the band along a box face's edges where leaves lean out past the edge, m, 0 .. 10 (0: none) */
    double leaf_relief;         /* on mesh hosts a blade is at most this x the surface's radius of curvature under it (0: off), 0 .. 10 */
    int32_t leaf_size_steps;    /* steps of age a drawn blade takes to reach leaf_size_max, 1 .. 100000 */
    double stem_color[4];       /* linear RGBA of material "ivy_stem" */
    double leaf_color[4];       /* linear RGBA of material "ivy_leaf" in summer (its flat colour, textures off) */
    int32_t season;             /* banyan_season: the leaf material (texture and flat colour), not the geometry */
    double stats_cell;          /* grid cell for the covered-area measure, m, 0.001 .. 100 */
    /* The run's budget (docs/api.md, "Budgets"): past either, BANYAN_E_LIMIT
     * naming it. For a handle, the time of all its banyan_ivy_step calls
     * together (step_seconds), and memory above what the process held at
     * banyan_ivy_create. */
    double max_seconds;         /* s, 0.01 .. 604800 [600] */
    double max_memory_mb;       /* MB of resident memory, 16 .. 1048576 [8192] */
    int32_t wind;                 /* bool: the wind attributes (banyan.h, BANYAN_ATTR_WIND_*). Default 1 */
    int32_t threads;            /* threads of banyan_ivy_mesh: 0 (all cores, the default) .. BANYAN_IVY_MAX_THREADS;
                                   the mesh does not depend on it; small plants use one */
} banyan_ivy_params;

/* Fewest internodes per leading stem (start_stems) a plant must have
 * after its steps (or one per step, when it has fewer than this many) to
 * count as grown. */
#define BANYAN_IVY_MIN_INTERNODES 5

/* Why a plant could not grow (banyan_ivy_stats.cannot_grow). */
typedef enum banyan_ivy_growth {
    BANYAN_IVY_GREW = 0,    /* at least min(steps, BANYAN_IVY_MIN_INTERNODES) internodes per leading stem */
    BANYAN_IVY_BLOCKED = 1, /* no first bud grew: every direction from the start is blocked */
    BANYAN_IVY_STUNTED = 2  /* it grew, but fewer internodes than that: boxed in right away */
} banyan_ivy_growth;

/* One English sentence for a banyan_ivy_growth value (what the CLI and
 * the add-on print); never NULL. */
BANYAN_API const char *banyan_ivy_growth_text(int32_t cannot_grow);

/* What banyan_ivy_get_stats reports. Crossings and covered area are seen
 * along the normal of each bud's nearest host face, the ground included
 * (docs/ivy.md). */
typedef struct banyan_ivy_stats {
    int32_t steps;              /* steps grown so far */
    int32_t buds;               /* all buds, one leaf each */
    int32_t by_state[5];        /* buds in A0, A1, A2, D, Z (banyan_ivy_bud_state order) */
    int32_t attached;           /* buds with F set (within sucker reach, with a sucker) */
    int32_t branch_points;      /* buds with a lateral branch (p3 firings) */
    int32_t crossings;          /* stem crossings seen along the host normal */
    int32_t cannot_grow;        /* banyan_ivy_growth: 0 when the plant grew, else why it could not */
    double attached_fraction;   /* attached / buds */
    double covered_area;        /* m^2: occupied stats_cell cells on host faces */
    double density;             /* (branch_points + crossings) / covered_area, per m^2 */
    double stem_length;         /* m, sum of internode lengths */
    double step_seconds;        /* wall time spent in banyan_ivy_step so far */
} banyan_ivy_stats;

typedef struct banyan_ivy banyan_ivy;

/* Defaults: the paper's Table 3 in metres (t0 = 20) and 450 steps; the
 * start at (0, 0, 0.05), the bottom centre of the CLI's default wall. */
BANYAN_API void banyan_ivy_params_init(banyan_ivy_params *params);
/* The steps a generate call grows: `steps`, or with years > 0 the
 * nearest whole number to years x shoot_growth / internode (a step grows
 * one internode on a growing tip). -1 for NULL or values the params check
 * refuses (non-finite, or over BANYAN_IVY_MAX_STEPS). */
BANYAN_API int32_t banyan_ivy_steps(const banyan_ivy_params *params);
BANYAN_API size_t banyan_sizeof_ivy_params(void);
BANYAN_API size_t banyan_sizeof_ivy_stats(void);

/* Checks params and hosts, places the start on a host side where a stem
 * can grow (docs/ivy.md, "Hosts and start") and plants the first bud.
 * `hosts` is a host set (banyan/hosts.h): suckers grip, and leaves face,
 * the real surface of its boxes and triangle meshes. Errors:
 * BANYAN_E_RANGE (a field, or t2 < t1), BANYAN_E_INVALID_ARG (a NULL host
 * set), BANYAN_E_START_FAR (start farther than start_snap_max from every
 * host). On failure *out == NULL. The params are copied; the handle keeps
 * a pointer to `hosts`, which must outlive it (banyan_ivy_free first). */
BANYAN_API banyan_status banyan_ivy_create(const banyan_ivy_params *params, const banyan_hosts *hosts,
                                           banyan_ivy **out, banyan_error *err);

/* Grows n more steps (0 .. BANYAN_IVY_MAX_STEPS). Refuses with
 * BANYAN_E_LIMIT, before a step that could pass max_buds; the steps done
 * before it are kept and the plant stays usable. */
BANYAN_API banyan_status banyan_ivy_step(banyan_ivy *ivy, int32_t n, banyan_error *err);

/* Meshes the plant as it is now: stem tubes, then one petiole per leaf
 * (part 0, material "ivy_stem") and leaf blades (part 1, material
 * "ivy_leaf", double-sided, in bud order); attributes
 * `birth_step` and `part` (0 stem, 1 leaf); skeleton of bud positions,
 * internode edges, stem radii, skel_tag = banyan_ivy_bud_state. */
BANYAN_API banyan_status banyan_ivy_mesh(const banyan_ivy *ivy, banyan_mesh **out, banyan_error *err);

/* Fills *out with the plant's measures now (named get_stats because
 * banyan_ivy_stats is the struct). Returns BANYAN_E_INVALID_ARG on
 * NULL, BANYAN_E_NOMEM when the crossing count cannot allocate. */
BANYAN_API banyan_status banyan_ivy_get_stats(const banyan_ivy *ivy, banyan_ivy_stats *out, banyan_error *err);

/* Frees the handle; accepts NULL. */
BANYAN_API void banyan_ivy_free(banyan_ivy *ivy);

/* create + step(params->steps) + mesh + free. stats (NULL for none) gets
 * the plant's measures after its steps, cannot_grow included, zeroed on
 * failure; progress (NULL for none): banyan.h, "progress". */
BANYAN_API banyan_status banyan_ivy_generate(const banyan_ivy_params *params, const banyan_hosts *hosts,
                                             banyan_mesh **out, banyan_ivy_stats *stats,
                                             const banyan_progress *progress, banyan_error *err);

#ifdef __cplusplus
}
#endif

#endif
