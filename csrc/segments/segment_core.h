/* segment_core.h - internal side of the segments generator, shared by the
 * composer, the preset reader and the demo tree; segment_ref.h holds the
 * reference itself. */
#ifndef BANYAN_SEGMENT_CORE_H
#define BANYAN_SEGMENT_CORE_H

#include "banyan.h"
#include "../mesh/mesh_builder.h"
#include "../base/vec.h"
#include "segment_ref.h"


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
