/* params_table.c - the parameter table of `banyan segments` (the tree
 * composer of spec segments.md, "Composing a tree") and its defaults: the
 * paper's angles and branch length, plus the choices banyan makes where
 * the spec is silent (unit, radii, sides, attachment tolerance). */
#include "../base/error.h"
#include "../params/params.h"
#include "segment_core.h"

#define S banyan_segments_params
const banyan_param_info segments_table_rows[] = {
    BP_DOUBLE(S, m, "Twig length", "Shape", "unit", 1e-6, 1e6, "length of every twig and fork branch, in paper units"),
    BP_DOUBLE(S, unit, "Scale", "Shape", "m", 1e-6, 1e3, "metres per paper unit"),
    BP_DOUBLE(S, alpha_deg, "Twig angle", "Shape", "deg", -360, 360, "twig angle about the vertical, +alpha for odd twigs, -alpha for even (alpha in the paper)"),
    BP_DOUBLE(S, beta_deg, "Fork turn", "Shape", "deg", -360, 360, "fork yaw about the vertical (beta in the paper)"),
    BP_DOUBLE(S, gamma_deg, "First child roll", "Shape", "deg", -360, 360, "roll of the first child about its parent's direction (gamma in the paper)"),
    BP_DOUBLE(S, omega_deg, "Second child roll", "Shape", "deg", -360, 360, "roll of the second child about its parent's direction (omega in the paper)"),
    BP_DOUBLE(S, radius, "Thickness", "Thickness", "m", 1e-6, 100, "base radius of a segment's axis; every tube tapers to half its base radius at its tip"),
    BP_DOUBLE(S, radius_ratio, "Thinning per level", "Thickness", "", 0.01, 1, "each level's base radius is this times the level above (a child also starts no thicker than its parent there)"),
    BP_DOUBLE(S, radius_min, "Minimum thickness", "Thickness", "m", 1e-6, 100, "no tube is thinner than this (the domes closing the tips aside)"),
    BP_DOUBLE(S, trunk_radius, "Trunk thickness", "Thickness", "m", 1e-6, 100, "base radius of the trunk line's tapering tube"),
    BP_INT(S, sides, "Sides", "Thickness", 3, 64, "sides of every tube"),
    BP_SEED(S, seed, "Seed", "Demo tree", "seed of the random demo tree (used only when no segment list is given)"),
    BP_INT(S, demo_segments, "Demo segments", "Demo tree", 1, 100000, "segments in the random demo tree"),
    BP_DOUBLE(S, demo_height, "Demo height", "Demo tree", "m", 0.01, 1000, "trunk height of the random demo tree"),
    BP_DOUBLE(S, attach_tolerance, "Attach tolerance", "Limits", "m", 0, 1e6, "how far a segment's start may lie from an earlier axis and still count as attached"),
    BP_INT(S, max_vertices, "Vertex limit", "Limits", 1, 1073741824, "refuse meshes with more vertices than this"),
    BP_BUDGET(S, "Limits"),
    BP_WIND(S, BP_F_SELF, "Limits"),
};
#undef S
const int32_t segments_table_row_count = (int32_t)(sizeof segments_table_rows / sizeof segments_table_rows[0]);
const size_t segments_table_params_size = sizeof(banyan_segments_params);

void banyan_segments_params_init(banyan_segments_params *p) {
    if (!p) return;
    p->seed = 1;
    p->max_vertices = 4000000;
    p->alpha_deg = 40.0;
    p->beta_deg = 30.0;
    p->gamma_deg = -30.0;
    p->omega_deg = 10.0;
    p->m = 10.0;
    p->unit = 0.05;
    p->radius = 0.02;
    p->radius_ratio = 0.6;
    p->radius_min = 0.002;
    p->trunk_radius = 0.06;
    p->sides = 6;
    p->attach_tolerance = 0.001;
    p->demo_segments = 24;
    p->demo_height = 4.0;
    p->max_seconds = PROG_MAX_SECONDS_DEFAULT;
    p->max_memory_mb = PROG_MAX_MEMORY_DEFAULT;
    p->wind = 1;
}

size_t banyan_sizeof_segments_params(void) { return sizeof(banyan_segments_params); }
size_t banyan_sizeof_segments_stats(void) { return sizeof(banyan_segments_stats); }

void seg_params_from_tree(const banyan_segments_params *tp, banyan_segment_params *sp) {
    sp->alpha_deg = tp->alpha_deg;
    sp->beta_deg = tp->beta_deg;
    sp->gamma_deg = tp->gamma_deg;
    sp->omega_deg = tp->omega_deg;
    sp->m = tp->m;
}
