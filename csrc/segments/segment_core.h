/* segment_core.h - internal side of the segment reference (reference.c),
 * shared by the composer, the preset reader and the demo tree. */
#ifndef BANYAN_SEGMENT_CORE_H
#define BANYAN_SEGMENT_CORE_H

#include "banyan.h"
#include "../mesh/mesh_builder.h"
#include "../base/vec.h"

/* The float constants one segment is generated with: exactly the shader's
 * uniforms (banyan_segment_uniforms). */
typedef struct seg_consts {
    float ca, sa, cb, sb, cg, sg, co, so; /* cos, sin of alpha, beta, gamma, omega */
    float m;                              /* twig / fork length */
} seg_consts;

/* Checks the four angles and m (m given in the caller's length unit,
 * scaled by m_scale before the check of the product) and fills k. */
banyan_status seg_consts_make(const banyan_segment_params *p, double m_scale, seg_consts *k, banyan_error *err);

/* Checks one input; messages start with `prefix` (e.g. "segs[3].") then
 * the field name. */
banyan_status seg_check_input(const banyan_segment_input *in, const char *prefix, banyan_error *err);

/* Generates one checked segment: xyz gets 3 floats per vertex, level (may
 * be NULL) one level code per vertex. Returns the vertex count (2..128).
 * Allocates nothing. */
int seg_run(const seg_consts *k, const banyan_segment_input *in, float *xyz, uint8_t *level);
/* seg_run that also gives each line's parent line (parent[j], one per
 * line, at most 64): the axis (line 0) is its own, a twig's is the axis,
 * a fork's the line it leaves (its start lies on that line). parent may
 * be NULL. */
int seg_run_tree(const seg_consts *k, const banyan_segment_input *in, float *xyz, uint8_t *level, uint8_t *parent);

/* Attachment (spec "Composing a tree"): writes the indices of segments
 * whose S is farther than tol from every earlier axis and from the trunk
 * line (6 doubles or NULL; without it segment 0 is the root) into out (may
 * be NULL) in increasing order and returns how many. A uniform grid finds
 * candidates; brute != 0 forces the O(count^2) scan (tests compare the
 * two). Inputs must be checked. *status gets BANYAN_E_NOMEM or OK, or
 * BANYAN_E_LIMIT when g (NULL: none) stops the run: the scan can take
 * count^2 / cells distance tests. */
struct prog;
uint32_t seg_find_unattached(const banyan_segment_input *segs, uint32_t count, const double *trunk, double tol,
                             int brute, uint32_t *out, banyan_status *status, struct prog *g);
/* seg_find_unattached that also gives every segment's parent (`parent`,
 * count entries): the nearest axis j < i within tol (a tie: the lower j),
 * -1 for the trunk (preferred on a tie), -2 for an unattached segment and,
 * without a trunk, for segment 0 (the root). */
uint32_t seg_attach_parents(const banyan_segment_input *segs, uint32_t count, const double *trunk, double tol,
                            int brute, int32_t *parent, uint32_t *out, banyan_status *status, struct prog *g);

/* Tube meshing of a segment's lines, shared by the composer (compose.c)
 * and the keyaki's twigs (keyaki/twigs.c). */

/* Radius of level code `level`: radius * ratio^level, never below
 * radius_min. */
double seg_level_radius(double radius, double ratio, double radius_min, int level);

/* One straight tube a -> b of `sides` (3..64) sides and radius r, closed
 * at b, through the shared sweeper: tube_counts(2, sides, 0, 1) vertices
 * and indices. The caller sets the attributes and part first. */
void seg_line_tube(mesh_builder *mb, v3 a, v3 b, double r, int sides);

/* The composer's tube shapes (shape.c): taper, flared junctions, domed
 * tips and the axes' zigzag, for the mesh only (the line set stays the
 * reference's). */
#define SEG_DOME_RINGS 2
#define SEG_TUBE_MAX_POINTS (3 + SEG_DOME_RINGS + BANYAN_SEGMENT_MAX_TWIGS)

/* One line's tube: ring centres c, radii r and distances s from the
 * line's start along it (for birth); rb, rt the line's base and tip
 * radius (the skeleton's); parent the line of the same segment it leaves
 * (-1: the axis of another segment or the trunk, -2: none). */
typedef struct seg_tube {
    v3 c[SEG_TUBE_MAX_POINTS];
    double r[SEG_TUBE_MAX_POINTS], s[SEG_TUBE_MAX_POINTS];
    int n;
    double rb, rt;
    int parent;
} seg_tube;

/* Per tree: each segment's move (the zigzag of the axes it hangs from)
 * and its axis's base and tip radius. */
typedef struct seg_shaper {
    const banyan_segments_params *p;
    const banyan_segment_input *segs;
    const double *trunk;
    const int32_t *parent; /* seg_attach_parents' */
    v3 *shift;
    double *rb, *rt;
    double trunk_rb, trunk_rt, ca, sa;
    double inner; /* cos(pi / sides): a polygonal ring's inner radius over its radius */
} seg_shaper;

/* Ring count of a line's tube: line -1 the trunk, 0 an axis with `twigs`
 * twigs, else a twig or fork. */
int seg_tube_points(int line, int twigs);
/* Returns nonzero when out of memory. parent: seg_attach_parents', kept. */
int seg_shaper_init(seg_shaper *sh, const banyan_segments_params *p, const banyan_segment_input *segs,
                    uint32_t count, const double *trunk, const int32_t *parent);
void seg_shaper_free(seg_shaper *sh);
void seg_shaper_trunk(const seg_shaper *sh, seg_tube *tb);
/* Line j of segment i (xyz, lev, par from seg_run_tree); tubes[0 .. j-1]
 * are the segment's earlier lines, already shaped. */
void seg_shaper_line(const seg_shaper *sh, uint32_t i, const float *xyz, const uint8_t *lev, const uint8_t *par,
                     const seg_tube *tubes, int j, seg_tube *tb);

/* The segment parameters inside the composer's params. */
void seg_params_from_tree(const banyan_segments_params *tp, banyan_segment_params *sp);

#endif
