/* Parameter table and defaults of the roots generator. The defaults are the
 * spec's (roots.md, "Parameters"); the few that the spec leaves open are
 * explained in docs/roots.md. */
#include "banyan.h"
#include "params/params.h"

#define S banyan_roots_params

const banyan_param_info roots_table_rows[] = {
    BP_SEED(S, seed, "Seed", "Roots", "random seed; the same seed gives the same mesh"),
    BP_INT(S, main_roots, "Main roots", "Roots", 1, 64, "number of main roots"),
    BP_INT(S, growth_points, "Root length", "Roots", 2, 10000, "growth points per main root B"),
    BP_DOUBLE(S, radius, "Thickness", "Roots", "unit", 0.001, 100, "root radius r, in units"),
    BP_DOUBLE(S, unit, "Scale", "Roots", "m", 1e-4, 100, "the paper's length unit u; every paper constant is multiplied by it"),
    BP_ENUM(S, surface, "Surface", "Roots", "fused|tubes", "one fused closed surface (roots merge where they touch) or plain tubes (fast)"),
    BP_DOUBLE(S, maturity, "Age", "Roots", "", 0, 1, "young separate cords (0) to an old fused sleeve (1)"),
    BP_DOUBLE(S, tip_radius, "Tip thickness", "Roots", "r", 0.05, 1, "radius at growing tips and branch ends"),
    BP_DOUBLE(S, pipe_exponent, "Thickening exponent", "Roots", "", 1.5, 4, "pipe model: r^e of a root = sum over what feeds into it"),
    BP_INT(S, sides, "Sides", "Roots", 4, 256, "tube sides n (even)"),
    BP_COLOR(S, color, "Color", "Roots", "root colour (vertex colour and material base colour)"),
    BP_INT(S, moves, "Moves per point", "Growth", 1, 100, "sphere moves per growth point"),
    BP_DOUBLE(S, forward_min, "Forward pull (min)", "Growth", "unit", 0, 1000, "forward draw, lower end"),
    BP_DOUBLE(S, forward_max, "Forward pull (max)", "Growth", "unit", 0, 1000, "forward draw, upper end"),
    BP_DOUBLE(S, lateral, "Sideways wander", "Growth", "unit", 0, 1000, "lateral draw: I(-lateral <= x <= lateral)"),
    BP_DOUBLE(S, start_radius, "Spread at the top", "Growth", "unit", 0.01, 1000, "radius of the circle around G holding the first growth points"),
    BP_DOUBLE(S, descent, "Downward pull", "Growth", "m", 0, 1000, "length of U in V = S - Lambda - U while growing down (the spec's U is 1 m)"),
    BP_DOUBLE(S, ground_step, "Crawl on the ground", "Growth", "", 0, 1, "scale of the moves once a root crawls on the ground (1 = the paper)"),
    BP_BOOL(S, hugging, "Hug the surface", "Hugging", "surface hugging (off: the paper's stop-on-contact)"),
    BP_DOUBLE(S, hug_range, "Hug distance", "Hugging", "r", 1, 100, "a host face nearer than this pulls a hugging root"),
    BP_DOUBLE(S, hug_pull, "Hug strength", "Hugging", "", 0, 100, "weight of the down-the-face direction added to V"),
    BP_BOOL(S, first_branches, "Side roots", "Branches", "grow first branch roots"),
    BP_INT(S, branch_start, "First side root at", "Branches", 1, 10000, "first-branch start index b (1-based)"),
    BP_INT(S, branch_spacing, "Side root spacing", "Branches", 1, 10000, "first-branch spacing along a main root"),
    BP_DOUBLE(S, branch_vertical, "Side root drop", "Branches", "unit", 0, 1000, "first-branch Bezier vertical draw"),
    BP_INT(S, branch_samples, "Side root length", "Branches", 3, 1001, "growth points per first branch root"),
    BP_DOUBLE(S, branch_jitter, "Side root wobble", "Branches", "unit", 0, 1000, "first-branch vertical jitter per point"),
    BP_BOOL(S, second_branches, "Rootlets", "Branches", "grow second branch roots"),
    BP_DOUBLE(S, second_lateral, "Rootlet spread", "Branches", "unit", 0, 1000, "second-branch lateral Bezier draw"),
    BP_INT(S, second_samples, "Rootlet length", "Branches", 2, 1001, "growth points per second branch root"),
    BP_BOOL(S, correction, "Bend at side roots", "Branches", "bend main roots where first branch roots leave them"),
    BP_BOOL(S, smoothing, "Smooth junctions", "Junctions", "junction smoothing at both ends of first branch roots"),
    BP_DOUBLE(S, junction_start_scale, "Junction size at start", "Junctions", "r", 0.1, 10, "radius of the junction loop at a first branch's start"),
    BP_DOUBLE(S, junction_end_scale, "Junction size at end", "Junctions", "r", 0.1, 10, "radius of the junction loop at a first branch's end"),
    BP_DOUBLE(S, junction_reach, "Junction reach", "Junctions", "r", 1, 1e4, "how far a junction loop reaches along the main root (0.8x at the far end)"),
    BP_DOUBLE(S, junction_falloff, "Junction blend", "Junctions", "", 0.1, 10, "exponent of the loop-to-round blend towards the branch middle"),
    BP_DOUBLE(S, fuse_radius, "Fusing", "Surface", "r", 0, 4, "fillet radius where roots merge (fused surface)"),
    BP_DOUBLE(S, voxel_size, "Surface detail", "Surface", "r", 0.1, 2, "voxel size of the fused surface (smaller: finer, slower)"),
    BP_BOOL(S, smooth_paths, "Smooth paths", "Surface", "smooth curves through the growth points"),
    BP_BOOL(S, soil_entry, "Enter the soil", "Start and ground", "roots reaching the ground go into the soil near the host"),
    BP_DOUBLE(S, soil_reach, "Soil reach", "Start and ground", "r", 0, 100, "how far past the host a root runs on the ground before going in"),
    BP_DOUBLE(S, flare, "Buttress flare", "Start and ground", "", 1, 10, "radius where a root enters the soil, times its radius above"),
    BP_DOUBLE(S, buttress, "Buttress reach", "Start and ground", "", 0, 4, "how far plank buttresses and surface roots run out past the host, times its width, at age 1 (0: none)"),
    BP_DOUBLE(S, foot_roots, "Roots to the soil", "Start and ground", "", 0, 8, "roots dropping from the lowest side roots to the soil, per gap between main roots, at age 1"),
    BP_BOOL(S, germination_auto, "Start above the host", "Start and ground", "G = top centre of hosts[0] lifted by r"),
    BP_VEC3(S, germination, "Start point", "Start and ground", "m", -1e6, 1e6, "germination point G (when germination_auto is off)"),
    BP_BOOL(S, ground, "Ground", "Start and ground", "the ground half-space below ground_z is solid"),
    BP_DOUBLE(S, ground_z, "Ground height", "Start and ground", "m", -1e6, 1e6, "height of the ground plane"),
    BP_BOOL(S, bezier_uniform, "Even curve offsets", "Advanced", "draw Bezier offsets uniformly in [-v, v] instead of picking -v or +v"),
    BP_INT(S, max_vertices, "Vertex limit", "Advanced", 1, 1073741824, "refuse meshes with more vertices"),
    BP_BUDGET(S, "Advanced"),
    BP_WIND(S, BP_F_SELF, "Advanced"),
};

const int32_t roots_table_row_count = (int32_t)(sizeof roots_table_rows / sizeof roots_table_rows[0]);
const size_t roots_table_params_size = sizeof(S);

void banyan_roots_params_init(banyan_roots_params *p) {
    if (!p) return;
    static const banyan_roots_params d = {
        .seed = 1,
        .unit = 0.05,
        .radius = 0.8,
        .sides = 8,
        .main_roots = 6,
        .growth_points = 40,
        .moves = 5,
        .forward_min = 0,
        .forward_max = 4,
        .lateral = 4,
        .start_radius = 2,
        .descent = 1,
        .branch_start = 4,
        .branch_spacing = 5,
        .branch_vertical = 15,
        .branch_samples = 21,
        .branch_jitter = 0, /* #18: smooth paths, no zigzag (the paper: 1.5) */
        .second_lateral = 20,
        .second_samples = 6,
        .bezier_uniform = 0,
        .color = {0.20, 0.15, 0.10, 1.0},
        .first_branches = 1,
        .second_branches = 1,
        .correction = 1,
        .smoothing = 1,
        .hugging = 1,
        .hug_range = 3,
        .hug_pull = 1,
        .ground_step = 0.3,
        .junction_start_scale = 1.15,
        .junction_end_scale = 1.08,
        .junction_reach = 2, /* #18: was 8; thick main roots (pipe model) make the junction, long loops folded the tubes */
        .junction_falloff = 3,
        .surface = 0,
        .voxel_size = 0.9,
        .fuse_radius = 2,
        .maturity = 0.6,
        .pipe_exponent = 2.5,
        .tip_radius = 0.6,
        .soil_entry = 1,
        .soil_reach = 3,
        .flare = 1.15,
        .buttress = 1.2,
        .foot_roots = 3,
        .smooth_paths = 1,
        .germination = {0, 0, 0},
        .germination_auto = 1,
        .ground = 1,
        .ground_z = 0,
        .max_vertices = 4000000,
        .max_seconds = PROG_MAX_SECONDS_DEFAULT,
        .max_memory_mb = PROG_MAX_MEMORY_DEFAULT,
        .wind = 1,
    };
    *p = d;
}

size_t banyan_sizeof_roots_params(void) { return sizeof(banyan_roots_params); }
size_t banyan_sizeof_roots_stats(void) { return sizeof(banyan_roots_stats); }
