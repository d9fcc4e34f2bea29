/* Ivy parameters: defaults (the paper's Table 3, spec/ivy.md "Defaults",
 * converted from millimetres to metres), the parameter table that presets,
 * --set and the add-on use, and the checks that tie fields together. */
#include <string.h>

#include "base/error.h"
#include "ivy_internal.h"
#include "params/params.h"

#define S banyan_ivy_params

const banyan_param_info ivy_table_rows[] = {
    BP_SEED(S, seed, "Seed", "Growth", "random seed; the same seed gives the same bytes"),
    BP_INT(S, steps, "Growth steps", "Growth", 0, BANYAN_IVY_MAX_STEPS, "growth steps (paper: 450); unused when years > 0"),
    BP_DOUBLE(S, years, "Years of growth", "Growth", "", 0, 1000, "the plant's age: > 0 grows years x Growth per year / Leaf spacing steps instead of Growth steps (0: use Growth steps)"),
    BP_DOUBLE(S, shoot_growth, "Growth per year", "Growth", "m", 0.01, 10, "how far a leading shoot grows in a year (Boston ivy: 1-2 m); turns years into steps"),
    BP_DOUBLE(S, internode, "Leaf spacing", "Growth", "m", 0.001, 10, "l, internode length (paper 30 mm)"),
    BP_DOUBLE(S, branch_angle, "Branch angle", "Growth", "deg", 0, 180, "R(theta) of rule p3: angle of a lateral branch off its stem"),
    BP_DOUBLE(S, theta_max, "Wander angle", "Growth", "deg", 0, 180, "largest turn about each axis of a random-walk candidate"),
    BP_BOOL(S, leaves, "Leaves", "Leaves", "emit leaves: a petiole and a blade per bud"),
    BP_DOUBLE(S, leaf_max, "Leaf shadow size", "Leaves", "m", 0.001, 10, "d_max, largest leaf shadow diameter of the light model; light look-up radius (paper 60 mm); drawn blades have their own sizes"),
    BP_INT(S, leaf_growth_steps, "Leaf shadow growing time", "Leaves", 1, 100000, "steps a leaf's shadow takes to reach leaf_max"),
    BP_DOUBLE(S, leaf_size_min, "Young leaf size", "Leaves", "m", 0.001, 1, "drawn blade size (across the side lobes) of a new leaf near a growing tip (real 5 cm)"),
    BP_DOUBLE(S, leaf_size_max, "Old leaf size", "Leaves", "m", 0.001, 1, "drawn blade size of a full-grown leaf (real up to 20 cm); at least leaf_size_min"),
    BP_INT(S, leaf_size_steps, "Leaf size age", "Leaves", 1, 100000, "steps of age a drawn blade takes to grow from leaf_size_min to leaf_size_max"),
    BP_DOUBLE(S, leaf_scale, "Leaf size scale", "Leaves", "", 0, 10, "multiplier of every drawn blade size (not of the light model's leaf_max)"),
    BP_DOUBLE(S, leaf_petiole, "Leaf stalk length", "Leaves", "", 0, 5, "petiole length over blade size (about the blade's length at 0.7): how far blades stand off the stem"),
    BP_DOUBLE(S, leaf_tilt, "Leaf tilt", "Leaves", "deg", 0, 90, "mean turn of a blade off its surface towards the sky"),
    BP_DOUBLE(S, leaf_spread, "Leaf spread", "Leaves", "deg", 0, 90, "per-leaf random spread of the tilt and of the blade's heading"),
    BP_DOUBLE(S, leaf_share, "Leaf share", "Leaves", "", 0, 1, "share of the buds that carry a leaf where the cover is average (young tips half of it)"),
    BP_DOUBLE(S, leaf_clump, "Leaf clumping", "Leaves", "", 0, 1, "how far that share varies over clumps (0: even; 1: from none to twice)"),
    BP_DOUBLE(S, clump_size, "Clump size", "Leaves", "m", 0.01, 100, "size of the clumps of denser and thinner leaves"),
    BP_DOUBLE(S, clump_relief, "Clump relief", "Leaves", "m", 0, 1, "dense clumps stand this much further out than the average, thin zones as much nearer, their flanks' blades facing along them (0: one even layer)"),
    BP_DOUBLE(S, edge_fray, "Frayed edges", "Leaves", "m", 0, 10, "width of the band along a host box's edges where leaves lean out past the edge, raggedly (0: none)"),
    BP_DOUBLE(S, leaf_relief, "Fit to relief", "Leaves", "", 0, 10, "on mesh hosts a blade is at most this x the radius of curvature of the surface under it, so a statue's nose and eyes still read (0: off)"),
    BP_COLOR(S, leaf_color, "Leaf color", "Leaves", "summer flat colour of material ivy_leaf, without textures (linear RGBA)"),
    BP_ENUM(S, season, "Season", "Leaves", "summer|autumn", "leaf material: summer green or autumn crimson; the geometry stays"),
    BP_DOUBLE(S, stem_radius, "Stem thickness", "Stems", "m", 1e-5, 1, "r0, stem radius at birth"),
    BP_DOUBLE(S, stem_radius_growth, "Thickening per step", "Stems", "m", 0, 1, "k, stem radius added per step of age"),
    BP_DOUBLE(S, stem_radius_max, "Maximum thickening by age", "Stems", "m", 1e-5, 1, "largest stem radius by age; at least stem_radius (old wood at the foot, past 1.5 times it, sheds its leaves)"),
    BP_DOUBLE(S, stem_pipe, "Trunk thickening", "Stems", "m", 0, 0.1, "pipe model: a stem is at least this x sqrt(buds it carries) thick, so leading stems become trunks (0: age rule only)"),
    BP_INT(S, stem_sides, "Stem sides", "Stems", 3, 64, "sides of a stem tube"),
    BP_COLOR(S, stem_color, "Stem color", "Stems", "base colour of material ivy_stem (linear RGBA)"),
    BP_DOUBLE(S, sucker_length, "Aerial root reach", "Climbing", "m", 0, 10, "D, sucker reach: a bud within it of a surface attaches (paper 30 mm)"),
    BP_DOUBLE(S, clearance, "Gap to the surface", "Climbing", "m", 1e-5, 1, "gap a stem keeps from host surfaces (> 0: a stem on a face must not count as inside it)"),
    BP_BOOL(S, sucker_pull, "Aerial roots pull the stem", "Climbing", "a bud that attaches is drawn to clearance off the surface by its sucker"),
    BP_DOUBLE(S, wrap_angle, "Wrap over edges up to", "Climbing", "deg", 0, 180, "a stem whose surface falls away under it bends over onto it when the surface turns by at most this within an internode (rounded forms, gentle edges); over a sharper edge it grows on free and may hang (0: never)"),
    BP_DOUBLE(S, w_d, "Cling to surfaces", "Climbing", "", 0, 100, "weight of f_d, staying within sucker reach of a surface (w_d in the paper)"),
    BP_DOUBLE(S, w_v, "Straightness", "Climbing", "", 0, 100, "weight of f_v, gentle turns (w_v in the paper)"),
    BP_DOUBLE(S, w_geo, "Climb upwards", "Climbing", "", 0, 100, "weight of f_geo, growing against gravity (w_geo in the paper)"),
    BP_DOUBLE(S, w_grav, "Droop", "Climbing", "", 0, 100, "weight of f_grav, long unattached stems falling (w_grav in the paper)"),
    BP_DOUBLE(S, w_helio, "Seek light", "Climbing", "", 0, 100, "weight of f_helio, growing towards light, curbing crossings (w_helio in the paper)"),
    BP_DOUBLE(S, w_cross, "Avoid crossing stems", "Climbing", "", 0, 100, "weight of f_cross: a new internode that crosses no stem, seen along the surface, scores it (stems run side by side instead of crossing)"),
    BP_BOOL(S, crossing_ends, "Stems stop at stems", "Climbing", "a bud whose every way on would cross a stem ends instead (stems meet side by side rather than crossing)"),
    BP_DOUBLE(S, follow_length, "Run alongside stems", "Climbing", "m", 0, 100, "with crossing_ends, a tip that meets a stem turns and runs alongside it, a little apart, for up to this before it ends (0: it ends where it meets the stem)"),
    BP_DOUBLE(S, w_tendril, "Reach for surfaces", "Climbing", "", 0, 100, "weight of f_tendril: a free bud with a sucker within surface_reach of a surface turns towards it (tendrils grow away from light, into the wall)"),
    BP_DOUBLE(S, surface_reach, "Surface reach", "Climbing", "m", 0, 10, "within this of a surface a bud takes light along it, avoids crossing stems on it, and its tendrils reach for it"),
    BP_BOOL(S, helio_in_plane, "Light along the surface", "Climbing", "for a bud within surface_reach of a surface, the light vector is taken along it"),
    BP_DOUBLE(S, t0, "Shade tolerance", "Climbing", "", 0, 1e6, "light threshold on H0 and H1: larger lets buds grow in more shade (t0 in the paper, which uses 15 or 20)"),
    BP_DOUBLE(S, alpha, "Apical dominance", "Branching", "", 0.5, 1, "apical dominance: share of nourishment the apex keeps at p2 (alpha in the paper, which uses 0.8)"),
    BP_DOUBLE(S, t1, "Tip growth threshold", "Branching", "", 0, 1e6, "nourishment an apical bud needs to grow (t1 in the paper, which uses 0.2)"),
    BP_DOUBLE(S, t2, "Side bud threshold", "Branching", "", 0, 1e6, "nourishment a dormant bud needs to sprout; at least t1 (t2 in the paper, which uses 2.0)"),
    BP_DOUBLE(S, beta, "Nourishment per step", "Branching", "", 0, 1000, "nourishment a waiting bud gains per step (beta in the paper, which uses 0.05)"),
    BP_DOUBLE(S, n_start, "Starting nourishment", "Branching", "", 0, 1e6, "nourishment of the first bud"),
    BP_INT(S, h1_buds, "Shade look-back", "Branching", 0, 64, "buds before a dormant bud on its stem whose H0 adds into H1 (H1 in the paper)"),
    BP_INT(S, candidates, "Directions tried", "Branching", 1, 1000, "K, random-walk candidates tried for each new bud"),
    BP_DOUBLE(S, free_length, "Free length before drooping", "Hanging stems", "m", 0, 100, "unattached length after which f_grav acts and the free tip turns up"),
    BP_DOUBLE(S, bmax, "Longest free run", "Hanging stems", "m", 0, 100, "Bmax: a longer unattached run ends (rule p6)"),
    BP_DOUBLE(S, tip_elevation, "Tip lift angle", "Hanging stems", "deg", -90, 90, "a free stem tip turns up to at least this angle above horizontal"),
    BP_DOUBLE(S, sag_stiffening, "Stiffening with age", "Hanging stems", "", 0, 6, "a joint holds Joint strength x (stem radius / radius at birth)^this: old stems arch, young tips droop"),
    BP_DOUBLE(S, tip_hook_length, "Tip hook length", "Hanging stems", "m", 0, 10, "the last this much of a free stem bends up (a J, not an L)"),
    BP_DOUBLE(S, tip_hook_angle, "Tip hook angle", "Hanging stems", "deg", -90, 90, "elevation the last internode of the hook reaches"),
    BP_DOUBLE(S, gravity, "Gravity", "Hanging stems", "m/s^2", 0, 1000, "g (paper 9.8)"),
    BP_DOUBLE(S, internode_mass, "Mass per leaf", "Hanging stems", "kg", 0, 1000, "mass of one internode with its leaf"),
    BP_DOUBLE(S, moment_max, "Joint strength", "Hanging stems", "N m", 0, 1e6, "moment a joint holds before an unattached stem sags"),
    BP_DOUBLE(S, sag_step, "Sag step", "Hanging stems", "deg", 0.5, 90, "rotation increment of the sag correction"),
    BP_VEC3(S, start, "Start point", "Start and ground", "m", -1e6, 1e6, "growth start; placed on the nearest host side a stem can grow from (not facing down, above the ground)"),
    BP_INT(S, start_stems, "Leading stems", "Start and ground", 1, 64, "stems growing from the start point, fanned out along the surface"),
    BP_DOUBLE(S, start_fan, "Leading stem spread", "Start and ground", "deg", 0, 180, "the leading stems spread over this angle either side of up"),
    BP_DOUBLE(S, start_snap_max, "Start snap distance", "Start and ground", "m", 0, 1e6, "farthest the start may be from every host (the ground does not count)"),
    BP_ENUM(S, ground, "Ground", "Start and ground", "none|obstacle|host",
            "the plane z = ground_z: absent, an obstacle stems rest on, or a host suckers grip as well"),
    BP_DOUBLE(S, ground_z, "Ground height", "Start and ground", "m", -1e6, 1e6, "height of the ground plane"),
    BP_BOOL(S, ground_branching, "Branch on the ground", "Start and ground", "dormant buds lying on the ground (when it is an obstacle) may sprout laterals"),
    BP_INT(S, max_vertices, "Vertex limit", "Limits", 1, 1073741824, "mesh vertex cap; a larger mesh is refused with BANYAN_E_LIMIT"),
    BP_INT(S, max_buds, "Bud limit", "Limits", 1, 50000000, "bud cap; a step that could pass it is refused with BANYAN_E_LIMIT"),
    BP_BUDGET(S, "Limits"),
    BP_WIND(S, BP_F_SELF, "Limits"),
    BP_INT(S, threads, "Threads", "Limits", 0, BANYAN_IVY_MAX_THREADS, "threads that build the mesh (0: all cores); the mesh is the same on any count"),
    BP_DOUBLE(S, stats_cell, "Coverage cell size", "Limits", "m", 0.001, 100, "grid cell of the covered-area measure"),
};
const int32_t ivy_table_row_count = (int32_t)(sizeof ivy_table_rows / sizeof ivy_table_rows[0]);
const size_t ivy_table_params_size = sizeof(banyan_ivy_params);

void banyan_ivy_params_init(banyan_ivy_params *p) {
    if (!p) return;
    memset(p, 0, sizeof *p);
    p->seed = 1;
    p->max_vertices = 4000000;
    p->steps = 450;
    p->years = 0;
    p->shoot_growth = 1.5;
    p->max_buds = 2000000;
    p->max_seconds = PROG_MAX_SECONDS_DEFAULT;
    p->max_memory_mb = PROG_MAX_MEMORY_DEFAULT;
    p->wind = 1;
    p->candidates = 10;
    p->h1_buds = 2;
    p->leaf_growth_steps = 20;
    p->sucker_pull = 1;
    p->wrap_angle = 60;
    p->leaves = 1;
    p->stem_sides = 6;
    p->helio_in_plane = 1;
    p->ground = 1;
    p->ground_z = 0.0;
    p->start[0] = 0.0;
    p->start[1] = 0.0;
    p->start[2] = 0.05;
    p->start_snap_max = 0.5;
    p->internode = 0.03;
    p->sucker_length = 0.03;
    p->clearance = 0.004;
    p->leaf_max = 0.06;
    p->t0 = 20.0;
    p->t1 = 0.2;
    p->t2 = 2.0;
    p->alpha = 0.8;
    p->beta = 0.05;
    p->n_start = 2.0;
    p->theta_max = 20.0;
    p->branch_angle = 45.0;
    p->w_d = 1.0;
    p->w_v = 2.0;
    p->w_geo = 0.25;
    p->w_grav = 1.0;
    p->w_helio = 1.0;
    p->w_cross = 1.0;
    p->start_stems = 5;
    p->start_fan = 60.0;
    p->w_tendril = 2.0;
    p->crossing_ends = 1;
    p->follow_length = 0.6;
    p->surface_reach = 0.15;
    p->ground_branching = 0;
    p->free_length = 0.1;
    p->bmax = 0.45;
    p->gravity = 9.8;
    p->internode_mass = 0.001;
    p->moment_max = 0.003;
    p->sag_step = 4.0;
    p->tip_elevation = 20.0;
    p->sag_stiffening = 3.0;
    p->tip_hook_length = 0.15;
    p->tip_hook_angle = 70.0;
    p->stem_radius = 0.0015;
    p->stem_radius_growth = 0.00002;
    p->stem_radius_max = 0.003;
    p->stem_pipe = 0.00025;
    p->leaf_scale = 1.0;
    p->leaf_size_min = 0.05;
    p->leaf_size_max = 0.14;
    p->leaf_size_steps = 300;
    p->leaf_petiole = 0.7;
    p->leaf_tilt = 16.0;
    p->leaf_spread = 10.0;
    p->leaf_share = 0.55;
    p->leaf_clump = 0.25;
    p->clump_size = 0.7;
    p->clump_relief = 0.06;
    p->leaf_relief = 0.3;
    p->edge_fray = 0.12;
    const double stem[4] = {0.20, 0.12, 0.07, 1.0}, leaf[4] = {0.10, 0.30, 0.05, 1.0};
    memcpy(p->stem_color, stem, sizeof stem);
    memcpy(p->leaf_color, leaf, sizeof leaf);
    p->stats_cell = 0.1;
}

size_t banyan_sizeof_ivy_params(void) { return sizeof(banyan_ivy_params); }
size_t banyan_sizeof_ivy_stats(void) { return sizeof(banyan_ivy_stats); }

int32_t banyan_ivy_steps(const banyan_ivy_params *p) {
    if (!p) return -1;
    if (!(p->years > 0)) return p->steps;
    double n = p->years * p->shoot_growth / p->internode;
    if (!(n >= 0 && n <= BANYAN_IVY_MAX_STEPS)) return -1; /* NaN, and a negative rate or internode, too */
    return (int32_t)(n + 0.5);
}

banyan_status ivy_params_check(const banyan_ivy_params *p, banyan_error *err) {
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    banyan_status s = banyan_params_check(BANYAN_GEN_IVY, p, err);
    if (s) return s;
    if (p->t2 < p->t1)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "t2 = %g must be >= t1 = %g (dormant buds need more nourishment than apical buds)", p->t2,
                           p->t1);
    if (p->stem_radius_max < p->stem_radius)
        return banyan_fail(err, BANYAN_E_RANGE, "stem_radius_max = %g must be >= stem_radius = %g m",
                           p->stem_radius_max, p->stem_radius);
    if (banyan_ivy_steps(p) < 0)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "years = %g gives %.0f steps (years x shoot_growth / internode), over %d; lower years",
                           p->years, p->years * p->shoot_growth / p->internode, BANYAN_IVY_MAX_STEPS);
    if (p->leaf_size_max < p->leaf_size_min)
        return banyan_fail(err, BANYAN_E_RANGE, "leaf_size_max = %g must be >= leaf_size_min = %g m",
                           p->leaf_size_max, p->leaf_size_min);
    return BANYAN_OK;
}
