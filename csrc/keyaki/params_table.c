/* params_table.c - parameter tables of `keyaki` and `avenue`, their
 * defaults (the paper's: spec/keyaki.md, models 1-4) and the checks that
 * tie fields together.
 *
 * The avenue table embeds the tree's rows under a "tree." prefix
 * (offsetof(banyan_avenue_params, tree.levels) is plain C), so an avenue
 * preset or `--set tree.levels=14` sets every tree at once. The tree's
 * seed, max_vertices, position, heading, lean and lean_direction are not
 * in the avenue table: the avenue sets them per tree; nor are its max_seconds and max_memory_mb:
 * the avenue's own budget covers the whole avenue; nor is its threads:
 * the avenue's own threads field spreads its trees, one thread each. */
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "base/progress.h"
#include "keyaki_internal.h"
#include "params/params.h"
#include "textures/leaf_look.h"

#define KEYAKI_MODELS "simple|strong_weak|twisted|edaore"

/* The tree's rows, shared by both tables, one macro per panel group so
 * the avenue can put its own groups first; F names the field. */
#define KEYAKI_TREE_MAIN_ROWS(S, F) \
    BP_ENUM(S, F(model), "Branching model", "Tree", KEYAKI_MODELS, "branching model (spec models 1-4); edaore is the paper's best"), \
    BP_INT(S, F(levels), "Fork levels", "Tree", 1, BANYAN_KEYAKI_MAX_LEVELS, "L_max: fork levels from trunk to tip"), \
    BP_DOUBLE(S, F(trunk_length), "Trunk height", "Tree", "unit", 0.01, 100, "bole length below the level-1 fork"), \
    BP_DOUBLE(S, F(segment_length), "Branch length", "Tree", "unit", 0.01, 100, "length of one level's branch (rule 4)"), \
    BP_DOUBLE(S, F(unit), "Scale", "Tree", "m", 1e-3, 1e3, "length of one paper unit: scales every length marked 'unit'"), \
    BP_INT(S, F(limbs), "Limbs", "Tree", 1, 12, "limbs the trunk splits into at trunk_length (1: the paper's single trunk)"), \
    BP_DOUBLE(S, F(limb_angle), "Limb lean", "Tree", "deg", 0, 80, "a limb's lean from vertical where it leaves the trunk"), \
    BP_DOUBLE(S, F(limb_zone), "Limb zone", "Tree", "unit", 0, 10, "height over which the limbs leave the trunk, from trunk_length up")

#define KEYAKI_BRANCHING_ROWS(S, F) \
    BP_DOUBLE(S, F(fork_angle), "Fork angle", "Branching", "deg", 0, 90, "angle of each child from its parent at level 1 (rule 3)"), \
    BP_DOUBLE(S, F(fork_angle_step), "Fork angle per level", "Branching", "deg", -10, 10, "fork angle added per level"), \
    BP_ENUM(S, F(fork_plane), "Fork plane", "Branching", "steepest|vertical", "rule 2 fork plane of models 1-2 (see docs/keyaki.md)"), \
    BP_DOUBLE(S, F(strong_probability), "Uneven split chance", "Branching", "", 0, 1, "p: chance of a strong/weak split (models 2-3, rule 5)"), \
    BP_DOUBLE(S, F(strong_ratio), "Strong branch share", "Branching", "", 0.5, 0.95, "strong child's energy share at such a split (0.7 = 7:3)"), \
    BP_ENUM(S, F(strong_side), "Strong branch side", "Branching", "upper|random", "strong child of models 3-4: the upper one, or a random side"), \
    BP_ENUM(S, F(distribution), "Split spread", "Branching", "uniform|normal", "edaore split-ratio distribution (rule 7)"), \
    BP_DOUBLE(S, F(stop_energy), "Weakest branch that forks", "Branching", "", 0, 1, "a branch with less energy stops forking (models 2-3)"), \
    BP_ENUM(S, F(length_rule), "Branch length rule", "Branching", "equal|energy", "branch lengths of models 2-3: equal, or 1/energy"), \
    BP_DOUBLE(S, F(max_length_ratio), "Longest weak branch", "Branching", "", 1, 10, "cap of the weak:strong length ratio (energy lengths)"), \
    BP_DOUBLE(S, F(alpha), "Branch shedding", "Branching", "", 1.001, 10, "break threshold T(l) = alpha^-l (rule 8)"), \
    BP_DOUBLE(S, F(springback), "Spring back", "Branching", "", 0, 1, "s: a survivor's angle becomes angle * (1 - s (1 - l / L_max)) (rule 9)")

#define KEYAKI_TWIST_ROWS(S, F) \
    BP_DOUBLE(S, F(twist), "Twist", "Twist", "deg", 0, 90, "tau: fork-plane twist (model 3; model 4 below tilt_mid)"), \
    BP_DOUBLE(S, F(twist_mid), "Twist when leaning", "Twist", "deg", 0, 90, "model 4 twist for tilt_mid <= parent tilt < tilt_high"), \
    BP_DOUBLE(S, F(twist_high), "Twist when level", "Twist", "deg", 0, 90, "model 4 twist from tilt_high"), \
    BP_DOUBLE(S, F(tilt_mid), "Leaning from", "Twist", "deg", 0, 180, "parent tilt from vertical where twist_mid takes over"), \
    BP_DOUBLE(S, F(tilt_high), "Level from", "Twist", "deg", 0, 180, "parent tilt from vertical where twist_high takes over")

#define KEYAKI_THICKNESS_ROWS(S, F) \
    BP_DOUBLE(S, F(tip_radius), "Twig thickness", "Thickness", "unit", 1e-4, 10, "pipe-model radius of a tip branch"), \
    BP_DOUBLE(S, F(pipe_exponent), "Thickening exponent", "Thickness", "", 1, 4, "p in r_parent^p = sum of r_child^p"), \
    BP_DOUBLE(S, F(tip_taper), "Tip taper", "Thickness", "", 0.05, 1, "end radius of a tip as a fraction of tip_radius"), \
    BP_DOUBLE(S, F(flare), "Root flare", "Thickness", "", 0, 3, "extra trunk radius at the ground, a fraction of the trunk's"), \
    BP_DOUBLE(S, F(flare_height), "Flare height", "Thickness", "unit", 0.01, 10, "height over which the flare fades into the trunk"), \
    BP_INT(S, F(flare_lobes), "Flare buttresses", "Thickness", 0, 16, "root buttresses round the flare (0: round)"), \
    BP_DOUBLE(S, F(bark_tile), "Bark tile", "Thickness", "m", 0.01, 10, "side of one bark texture tile on the bark"), \
    BP_DOUBLE(S, F(bark_flake_radius), "Flaking bark from", "Thickness", "m", 0, 10, "tubes at least this thick show flakes; thinner ones and twigs smooth bark"), \
    BP_INT(S, F(sides_max), "Trunk sides", "Thickness", 3, 64, "tube sides of the trunk"), \
    BP_INT(S, F(sides_min), "Twig sides", "Thickness", 3, 64, "tube sides of the thinnest branches"), \
    BP_COLOR(S, F(bark_color), "Bark color", "Thickness", "bark material colour (linear RGBA)")

#define KEYAKI_LEAVES_ROWS(S, F) \
    BP_INT(S, F(twig_levels), "Twig orders", "Twigs", 0, 3, "orders of side twigs below the skeleton's outer branches"), \
    BP_DOUBLE(S, F(twig_length), "Twig length", "Twigs", "m", 0.01, 5, "length of a first-order twig"), \
    BP_DOUBLE(S, F(twig_ratio), "Twig length ratio", "Twigs", "", 0.05, 1, "a twig's length as a fraction of its parent twig's"), \
    BP_DOUBLE(S, F(twig_spacing), "Twig spacing", "Twigs", "m", 0.005, 5, "distance between successive side twigs on a shoot"), \
    BP_DOUBLE(S, F(twig_angle), "Twig angle", "Twigs", "deg", 0, 90, "a side twig's angle from its parent"), \
    BP_DOUBLE(S, F(twig_radius), "Twig tip radius", "Twigs", "m", 1e-4, 0.1, "radius of a twig's tip"), \
    BP_BOOL(S, F(light), "Light and crowding", "Twigs", "twig clusters shaded from above steer, stop or drop"), \
    BP_DOUBLE(S, F(shade_layers), "Shade layers", "Twigs", "", 0.1, 20, "leaf clusters above a spot that shade it fully"), \
    BP_DOUBLE(S, F(light_steer), "Turn to light", "Twigs", "deg", 0, 90, "largest turn of a twig cluster towards its lit side"), \
    BP_BOOL(S, F(leaves), "Leaves", "Leaves", "leaves along the twigs"), \
    BP_INT(S, F(leaf_levels), "Leafy levels", "Leaves", 0, BANYAN_KEYAKI_MAX_LEVELS, "skeleton branches within this many levels of a tip carry twigs and leaves"), \
    BP_DOUBLE(S, F(leaf_density), "Leaf density", "Leaves", "1/m", 0, 1000, "leaves per metre of leafy twig (two ranks)"), \
    BP_DOUBLE(S, F(leaf_size), "Leaf size", "Leaves", "m", 0.005, 1, "median blade length"), \
    BP_DOUBLE(S, F(leaf_size_spread), "Leaf size spread", "Leaves", "", 0, 1, "blade lengths vary by up to this fraction either way"), \
    BP_COLOR(S, F(leaf_color), "Leaf color", "Leaves", "summer leaves' flat colour, without textures (linear RGBA)"), \
    BP_ENUM(S, F(season), "Season", "Leaves", "summer|autumn", "leaf material: summer green or autumn yellow to rust; the geometry stays")

#define KEYAKI_SEGMENT_TWIGS_ROWS(S, F) \
    BP_BOOL(S, F(twigs_from_segments), "Twigs from segments", "Segment twigs", "finest levels as geometry-shader segments along the outer branches"), \
    BP_INT(S, F(segment_levels), "Levels replaced", "Segment twigs", 1, BANYAN_KEYAKI_MAX_LEVELS - 1, "finest levels the segments replace (< levels)"), \
    BP_DOUBLE(S, F(segment_twig_length), "Segment twig length", "Segment twigs", "unit", 0.001, 100, "m: length of every segment twig and fork line"), \
    BP_INT(S, F(segment_twigs), "Twigs per segment", "Segment twigs", 0, BANYAN_SEGMENT_MAX_TWIGS, "n: twigs per segment"), \
    BP_INT(S, F(segment_depth), "Twig fork depth", "Segment twigs", 0, 16, "s: fork depth of a segment's first twig (twig i: s + i - 1)")

#define KEYAKI_LIMITS_ROWS(S, F) \
    BP_INT(S, F(max_nodes), "Branch limit", "Limits", 1, 16777216, "skeleton branches allowed before refusing (BANYAN_E_LIMIT)")

/* The run's budget: the tree's own, or the avenue's (never tree.*). */
#define KEYAKI_BUDGET_ROWS(S) \
    BP_DOUBLE(S, max_seconds, "Time limit", "Limits", "s", PROG_MAX_SECONDS_MIN, PROG_MAX_SECONDS_MAX, "stop (BANYAN_E_LIMIT) past this much wall time"), \
    BP_DOUBLE(S, max_memory_mb, "Memory limit", "Limits", "MB", PROG_MAX_MEMORY_MIN, PROG_MAX_MEMORY_MAX, "stop (BANYAN_E_LIMIT) past this much added resident memory")

#define KEYAKI_TREE_GROUPS(S, F) \
    KEYAKI_TREE_MAIN_ROWS(S, F), \
    KEYAKI_BRANCHING_ROWS(S, F), \
    KEYAKI_TWIST_ROWS(S, F), \
    KEYAKI_THICKNESS_ROWS(S, F), \
    KEYAKI_LEAVES_ROWS(S, F), \
    KEYAKI_SEGMENT_TWIGS_ROWS(S, F), \
    BP_WIND(S, F, "Limits")

#define KEYAKI_F(x) x
#define AVENUE_F(x) tree.x

#define K banyan_keyaki_params
const banyan_param_info keyaki_table_rows[] = {
    BP_SEED(K, seed, "Seed", "Tree", "random seed"),
    BP_VEC3(K, position, "Position", "Tree", "m", -1e6, 1e6, "trunk base"),
    BP_DOUBLE(K, heading, "Heading", "Tree", "deg", -360, 360, "turns the whole tree about its trunk"),
    BP_DOUBLE(K, lean, "Lean", "Tree", "deg", 0, 30, "the whole tree tilted about its foot by this much"),
    BP_DOUBLE(K, lean_direction, "Lean direction", "Tree", "deg", -360, 360,
              "the way it leans, counter-clockwise from +X, turned with heading"),
    KEYAKI_TREE_GROUPS(K, KEYAKI_F),
    BP_INT(K, max_vertices, "Vertex limit", "Limits", 1, 1073741824, "refuse (BANYAN_E_LIMIT) beyond this many vertices"),
    KEYAKI_LIMITS_ROWS(K, KEYAKI_F),
    KEYAKI_BUDGET_ROWS(K),
    BP_INT(K, threads, "Threads", "Limits", 0, BANYAN_AVENUE_MAX_THREADS, "threads meshing the tree (0: all cores); the mesh is the same on any"),
};
#undef K
const int32_t keyaki_table_row_count = (int32_t)(sizeof keyaki_table_rows / sizeof keyaki_table_rows[0]);
const size_t keyaki_table_params_size = sizeof(banyan_keyaki_params);

#define A banyan_avenue_params
const banyan_param_info avenue_table_rows[] = {
    BP_SEED(A, seed, "Seed", "Avenue", "base seed: tree i uses seed + i"),
    BP_VEC3(A, start, "Path start", "Avenue", "m", -1e6, 1e6, "first point of the straight path"),
    BP_VEC3(A, end, "Path end", "Avenue", "m", -1e6, 1e6, "last point of the straight path"),
    BP_INT(A, rows, "Rows", "Avenue", 1, 2, "one or two rows of trees"),
    BP_DOUBLE(A, row_offset, "Row spacing", "Avenue", "m", 0, 1000, "distance between the two rows"),
    BP_BOOL(A, stagger, "Stagger rows", "Avenue", "shift the second row by half a spacing"),
    BP_ENUM(A, placement, "Placement", "Avenue", "spacing|count", "place trees every `spacing` m, or `count` per row"),
    BP_DOUBLE(A, spacing, "Tree spacing", "Avenue", "m", 0.1, 1e4, "distance between trees along the path"),
    BP_INT(A, count, "Trees per row", "Avenue", 1, BANYAN_AVENUE_MAX_TREES, "trees per row (placement count)"),
    BP_DOUBLE(A, heading_jitter, "Random turn", "Variation", "deg", 0, 180, "each tree turned by uniform(+-this)"),
    BP_DOUBLE(A, height_jitter, "Random height", "Variation", "", 0, 0.9, "trunk length scaled by 1 + uniform(+-this)"),
    BP_DOUBLE(A, position_jitter, "Random offset", "Variation", "m", 0, 100,
              "trunk moved uniformly within a disc of this radius"),
    BP_INT(A, levels_jitter, "Random age", "Variation", 0, BANYAN_KEYAKI_MAX_LEVELS - 1,
           "tree.levels lowered by a uniform whole number in [0, this], never below 1: trees of mixed ages"),
    BP_DOUBLE(A, scale_jitter, "Random size", "Variation", "", 0, 0.5, "tree.unit scaled by 1 + uniform(+-this): the whole tree's size"),
    BP_DOUBLE(A, lean_jitter, "Random lean", "Variation", "deg", 0, 30, "each tree leans by uniform(0, this) in a random direction"),
    BP_INT(A, variants, "Variants", "Variation", 0, BANYAN_AVENUE_MAX_VARIANTS,
           "0: every tree unique; else this many distinct trees placed as instances"),
    KEYAKI_TREE_GROUPS(A, AVENUE_F),
    BP_INT(A, max_vertices, "Vertex limit", "Limits", 1, 1073741824, "refuse (BANYAN_E_LIMIT) beyond this many vertices"),
    KEYAKI_LIMITS_ROWS(A, AVENUE_F),
    KEYAKI_BUDGET_ROWS(A),
    BP_INT(A, threads, "Threads", "Limits", 0, BANYAN_AVENUE_MAX_THREADS,
           "threads growing the trees, one tree each (0: all cores); the mesh is the same on any"),
};
#undef A
const int32_t avenue_table_row_count = (int32_t)(sizeof avenue_table_rows / sizeof avenue_table_rows[0]);
const size_t avenue_table_params_size = sizeof(banyan_avenue_params);

void banyan_keyaki_params_init(banyan_keyaki_params *p) {
    if (!p) return;
    memset(p, 0, sizeof *p);
    p->seed = 1;
    p->max_vertices = 4000000;
    p->max_nodes = 1000000;
    p->heading = 0;
    p->unit = 1.0;
    p->model = BANYAN_KEYAKI_EDAORE;
    p->levels = 21;
    p->trunk_length = 0.8;
    p->segment_length = 0.8;
    p->fork_angle = 15.0;
    p->fork_angle_step = 1.0;
    p->fork_plane = BANYAN_KEYAKI_PLANE_STEEPEST;
    p->strong_probability = 0.5;
    p->strong_ratio = 0.7;
    p->stop_energy = 0.01;
    p->length_rule = BANYAN_KEYAKI_LENGTH_ENERGY;
    p->max_length_ratio = 3.0;
    p->twist = 35.0;
    p->twist_mid = 15.0;
    p->twist_high = 0.0;
    p->tilt_mid = 30.0;
    p->tilt_high = 60.0;
    p->strong_side = BANYAN_KEYAKI_SIDE_RANDOM;
    p->distribution = BANYAN_KEYAKI_UNIFORM;
    p->alpha = 1.3;
    p->springback = 1.0;
    p->limbs = 1;
    p->limb_angle = 35.0;
    p->limb_zone = 0.8;
    p->tip_radius = 0.045;
    p->pipe_exponent = 2.5;
    p->tip_taper = 0.5;
    p->flare = 0.5;
    p->flare_height = 1.0;
    p->flare_lobes = 5;
    p->bark_tile = 0.4;
    p->bark_flake_radius = 0.07;
    p->sides_max = 14;
    p->sides_min = 4;
    p->twig_levels = 2;
    p->twig_length = 0.5;
    p->twig_ratio = 0.3;
    p->twig_spacing = 0.2;
    p->twig_angle = 50.0;
    p->twig_radius = 0.0025;
    p->light = 1;
    p->shade_layers = 2.0;
    p->light_steer = 35.0;
    p->leaves = 1;
    p->leaf_levels = 5;
    p->leaf_density = 24.0;
    p->leaf_size = 0.055;
    p->leaf_size_spread = 0.3;
    static const double bark[4] = LEAF_KEYAKI_BARK_RGBA, leaf[4] = {0.06, 0.20, 0.035, 1.0};
    memcpy(p->bark_color, bark, sizeof bark);
    memcpy(p->leaf_color, leaf, sizeof leaf);
    p->twigs_from_segments = 0;
    p->segment_levels = 4;
    p->segment_twig_length = 0.8;
    p->segment_twigs = 4;
    p->segment_depth = 1;
    p->wind = 1;
    p->max_seconds = PROG_MAX_SECONDS_DEFAULT;
    p->max_memory_mb = PROG_MAX_MEMORY_DEFAULT;
}

size_t banyan_sizeof_keyaki_params(void) { return sizeof(banyan_keyaki_params); }

void banyan_avenue_params_init(banyan_avenue_params *p) {
    if (!p) return;
    memset(p, 0, sizeof *p);
    banyan_keyaki_params_init(&p->tree);
    p->seed = 1;
    p->max_vertices = 32000000; /* a tree with its crown is ~0.1-0.8 M vertices */
    p->end[0] = 60.0;
    p->rows = 2;
    p->row_offset = 12.0;
    p->stagger = 0;
    p->placement = BANYAN_AVENUE_SPACING;
    p->spacing = 8.0;
    p->count = 10;
    p->heading_jitter = 180.0;
    p->height_jitter = 0.15;
    p->position_jitter = 0.3;
    p->scale_jitter = 0.12;
    p->lean_jitter = 3.0;
    p->max_seconds = PROG_MAX_SECONDS_DEFAULT;
    p->max_memory_mb = PROG_MAX_MEMORY_DEFAULT;
}

size_t banyan_sizeof_avenue_params(void) { return sizeof(banyan_avenue_params); }

banyan_status keyaki_params_validate(const banyan_keyaki_params *p, banyan_error *err) {
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    banyan_status s = banyan_params_check(BANYAN_GEN_KEYAKI, p, err);
    if (s) return s;
    double last = p->fork_angle + p->fork_angle_step * (p->levels - 1);
    if (last < 0 || last > 90)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "fork_angle + fork_angle_step * (levels - 1) = %g + %g * %d = %g deg must stay within "
                           "[0, 90] deg",
                           p->fork_angle, p->fork_angle_step, p->levels - 1, last);
    if (p->sides_min > p->sides_max)
        return banyan_fail(err, BANYAN_E_RANGE, "sides_min = %d must be <= sides_max = %d", p->sides_min,
                           p->sides_max);
    if (p->tilt_mid > p->tilt_high)
        return banyan_fail(err, BANYAN_E_RANGE, "tilt_mid = %g deg must be <= tilt_high = %g deg", p->tilt_mid,
                           p->tilt_high);
    if (p->twigs_from_segments && p->segment_levels >= p->levels)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "segment_levels = %d must be < levels = %d with twigs_from_segments (the skeleton keeps "
                           "levels - segment_levels >= 1 levels)",
                           p->segment_levels, p->levels);
    if (p->model == BANYAN_KEYAKI_SIMPLE) {
        /* Model 1 never stops: 2^(levels+1) - 1 branches, known up front. */
        int grown = p->levels; /* twigs from segments too: the full tree is grown, then cut */
        double nodes = p->limbs * (ldexp(1.0, grown + 1) - 1) + (p->limbs > 1 ? p->limbs - 1 : 0);
        if (nodes > p->max_nodes)
            return banyan_fail(err, BANYAN_E_LIMIT,
                               "model simple with levels = %d makes %.0f branches, more than max_nodes = %d; lower "
                               "levels (6 in the paper) or raise max_nodes",
                               grown, nodes, p->max_nodes);
    }
    return BANYAN_OK;
}
