/*
 * banyan/roots.h - strangler-fig roots around host boxes (spec roots.md,
 * after Honma 2011): six main roots grow from a germination point G by a
 * sphere walk down and around the hosts, first branch roots join
 * neighbouring main roots like belts, second branch roots cross-link the
 * belts, and the whole net is swept into tubes. See docs/roots.md.
 *
 * Lengths marked "unit" are multiples of `unit` (the paper's bare
 * numbers); lengths marked "m" are metres. Bools and counts are int32_t.
 */
#ifndef BANYAN_ROOTS_H
#define BANYAN_ROOTS_H
#include <stddef.h>
#include <stdint.h>

#include "../banyan.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct banyan_roots_params {
    uint64_t seed;                /* any value; same seed -> same bytes */
    double unit;                  /* m, 1e-4 .. 100: the paper's length unit u [0.05] */
    double radius;                /* unit, 0.001 .. 100: root radius r = radius * unit [0.8] */
    int32_t sides;                /* 4 .. 256 and even: tube sides n [8] */
    int32_t main_roots;           /* 1 .. 64: number of main roots [6] */
    int32_t growth_points;        /* 2 .. 10000: growth points per main root B [40] */
    int32_t moves;                /* 1 .. 100: sphere moves per growth point [5] */
    double forward_min;           /* unit, 0 .. 1000: forward draw I(min <= x <= max) [0] */
    double forward_max;           /* unit, 0 .. 1000, >= forward_min [4] */
    double lateral;               /* unit, 0 .. 1000: lateral draw I(-l <= x <= l) [4] */
    double start_radius;          /* unit, 0.01 .. 1000: circle around G holding M(a,1) [2] */
    double descent;               /* m, 0 .. 1000: length of U in V = S - Lambda - U [1] */
    int32_t branch_start;         /* 1 .. 10000: first-branch start index b (1-based) [4] */
    int32_t branch_spacing;       /* 1 .. 10000: first-branch spacing [5] */
    double branch_vertical;       /* unit, 0 .. 1000: Bezier vertical draw +-v [15] */
    double branch_tilt;           /* 0 .. 1: share of first branch roots that end one slot lower or higher
                                     on the next main root instead of level (a diamond lattice, not
                                     ladder rungs); 0: the paper's level branches [0.6] */
    int32_t branch_samples;       /* 3 .. 1001: growth points per first branch root [21] */
    double branch_jitter;         /* unit, 0 .. 1000: vertical jitter I(-j <= x <= j) per point [1.5] */
    double second_lateral;        /* unit, 0 .. 1000: second-branch lateral draw +-l [20] */
    int32_t second_samples;       /* 2 .. 1001: growth points per second branch root [6] */
    int32_t bezier_uniform;       /* bool: draw the Bezier offsets uniformly in [-v, v] instead of the
                                     spec's I(-v, v) pick of -v or +v [0] */
    double color[4];              /* linear RGBA 0..1: the material's base colour (the vertex colours are
                                     a multiplier of it and of the bark texture: soil_line) */
    int32_t first_branches;       /* bool: grow first branch roots [1] */
    int32_t second_branches;      /* bool: grow second branch roots [1] */
    int32_t correction;           /* bool: bend main roots at first branches (spec 3) [1] */
    int32_t smoothing;            /* bool: junction smoothing of first branch roots (spec 5) [1] */
    int32_t hugging;              /* bool: surface hugging; 0 = the paper's stop-on-contact [1] */
    double hug_range;             /* multiples of r, 1 .. 100: a face this near pulls the root [3] */
    double hug_pull;              /* 0 .. 100: weight of the down-the-face direction added to V [1] */
    double ground_step;           /* 0 .. 1: scale of a move's draws once a root crawls on the ground;
                                     1 = the paper, lower keeps the ground net near the host [0.3] */
    double junction_start_scale;  /* 0.1 .. 10: loop radius at a first branch's start, times r [1.15] */
    double junction_end_scale;    /* 0.1 .. 10: loop radius at a first branch's end, times r [1.08] */
    double junction_reach;        /* multiples of r, 1 .. 1e4: a junction loop reaches at most this far
                                     along the main root from the junction (0.8x at the far end) [2] */
    double junction_falloff;      /* 0.1 .. 10: exponent of the loop-to-round blend along the branch [3] */
    double germination[3];        /* m, each -1e6 .. 1e6: G when germination_auto is 0 */
    int32_t germination_auto;     /* bool: G = top centre of hosts[0] lifted by r [1] */
    int32_t ground;               /* bool: the ground half-space z < ground_z is solid [1] */
    double ground_z;              /* m, -1e6 .. 1e6 [0] */
    int32_t max_vertices;         /* 1 .. 2^30: refuse (BANYAN_E_LIMIT) beyond this [4000000] */
    /* The look of a real strangler fig (docs/roots.md). */
    int32_t surface;              /* banyan_roots_surface: one fused closed surface (OpenVDB) or the
                                     plain tubes [FUSED] */
    double voxel_size;            /* multiples of r, 0.1 .. 2: the fused surface's voxel [0.95] */
    double fuse_radius;           /* multiples of r, 0 .. 4: fillet where roots merge (smooth union) [2] */
    double maturity;              /* 0 .. 1: young separate cords (0) to an old fused sleeve (1): how
                                     much roots thicken with the flow and fuse [0.6] */
    double pipe_exponent;         /* 1.5 .. 4: pipe model r^e = sum of what feeds in (2 = da Vinci) [2.5] */
    double tip_radius;            /* 0.05 .. 1: radius at growing tips and branch ends, times r [0.6] */
    int32_t soil_entry;           /* bool: a root that reaches the ground enters the soil near the host
                                     with a buttress flare, instead of crawling outward [1] */
    double soil_reach;            /* multiples of r, 0 .. 100: how far past the host a root may run on
                                     the ground before it goes in [3] */
    double flare;                 /* 1 .. 10: radius where a root enters the soil, times its radius above [1.15] */
    double buttress;              /* 0 .. 4: how far plank buttresses and their surface roots run out
                                     past the host, times the host's smallest extent, at maturity 1
                                     (times maturity below); 0: none [1.2] */
    double foot_roots;            /* 0 .. 8: roots that drop from the lowest branch roots to the soil,
                                     per gap between main roots, at maturity 1 (times maturity) [3] */
    double aerial_roots;          /* 0 .. 200: thin roots hanging free from the net, at maturity 1
                                     (times maturity); some reach the soil [40] */
    double soil_line;             /* m, 0 .. 2: mean height of the darker, soil-stained band where the
                                     roots meet the ground (vertex colours); 0 = none [0.25] */
    int32_t smooth_paths;         /* bool: smooth curves through the growth points, no zigzag [1] */
    /* The run's budget (docs/api.md, "Budgets"): past either, BANYAN_E_LIMIT naming it. */
    double max_seconds;           /* s, 0.01 .. 604800: wall time of one call [600] */
    double max_memory_mb;         /* MB, 16 .. 1048576: resident memory above the process's at the call [8192] */
    int32_t wind;                 /* bool: the wind attributes (banyan.h, BANYAN_ATTR_WIND_*). Default 1 */
} banyan_roots_params;

/* banyan_roots_params.surface */
typedef enum banyan_roots_surface {
    BANYAN_ROOTS_FUSED = 0, /* one closed surface: touching roots merge with fillets */
    BANYAN_ROOTS_TUBES = 1  /* a tube per root (fast: distance, games) */
} banyan_roots_surface;

/* Measures of one generation (docs/roots.md, "Stats"). */
typedef struct banyan_roots_stats {
    uint32_t main_points;         /* growth points of main roots (B per root, G not counted) */
    uint32_t first_points;        /* growth points of first branch roots */
    uint32_t second_points;       /* growth points of second branch roots */
    uint32_t repair_points;       /* points inserted so no segment cuts a host (all kinds) */
    uint32_t first_roots;         /* first branch roots grown */
    uint32_t first_reached;       /* of those, how many end exactly on M(a+1,b) */
    uint32_t second_roots;        /* second branch roots grown */
    uint32_t reroute_events;      /* first-branch 1-degree re-routing events */
    uint32_t reroute_pushouts;    /* re-routes where a full turn found nothing: pushed out */
    uint32_t second_pushouts;     /* second-branch points pushed out of a host */
    uint32_t correction_pushouts; /* corrected main-root points pushed out of a host */
    uint32_t mains_on_ground;     /* main roots that reached the ground */
    double min_clearance;         /* m: least (distance to a host or the ground) over all skeleton points */
    double radius;                /* m: r, for comparing with min_clearance */
    uint32_t vertices;
    uint32_t triangles;
} banyan_roots_stats;

/* Defaults from the spec (roots.md, "Parameters"). */
BANYAN_API void banyan_roots_params_init(banyan_roots_params *p);
BANYAN_API size_t banyan_sizeof_roots_params(void);
BANYAN_API size_t banyan_sizeof_roots_stats(void);

/* Grows the net around the hosts of a host set (banyan/hosts.h: boxes and
 * triangle meshes, distances and contact taken on the real surface) and
 * sweeps it into one mesh with attributes `root_kind` (0 main, 1 first
 * branch, 2 second branch, 3 foot, 4 aerial) and `root_id`, vertex colour,
 * one material, and the skeleton (skel_tag = root kind). With
 * germination_auto, G is the highest surface point of host 0 on the
 * vertical line through the centre of its world bounds, lifted by r.
 * Refuses bad parameters (BANYAN_E_RANGE), a NULL host set
 * (BANYAN_E_NO_HOSTS), G inside a host or below the ground
 * (BANYAN_E_START_INSIDE), G so far from every host that no root could
 * reach one (BANYAN_E_START_FAR: farther than start_radius + (growth_points
 * - 1) * moves * hypot(forward_max, lateral) units + 4 r) and meshes beyond
 * max_vertices (BANYAN_E_LIMIT). `hosts` is only read. stats (NULL for
 * none) gets the net's measures, zeroed on failure; progress (NULL for
 * none): banyan.h, "progress". */
BANYAN_API banyan_status banyan_roots_generate(const banyan_roots_params *params, const banyan_hosts *hosts,
                                               banyan_mesh **out, banyan_roots_stats *stats,
                                               const banyan_progress *progress, banyan_error *err);

#ifdef __cplusplus
}
#endif

#endif
