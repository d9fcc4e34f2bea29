/* segment_ref.h - the segment reference (reference.c) and the straight
 * tubes of its lines (compose.c): the part of the segments generator
 * other generators use. The keyaki's twigs (keyaki/twigs.c) grow from it;
 * the dependency is one-way: nothing in csrc/segments uses the keyaki. */
#ifndef BANYAN_SEGMENT_REF_H
#define BANYAN_SEGMENT_REF_H

#include "banyan.h"
#include "../base/vec.h"
#include "../mesh/mesh_builder.h"

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

/* Tube meshing of a segment's lines, shared by the composer (compose.c)
 * and the keyaki's twigs (keyaki/twigs.c). */

/* Radius of level code `level`: radius * ratio^level, never below
 * radius_min. */
double seg_level_radius(double radius, double ratio, double radius_min, int level);

/* One straight tube a -> b of `sides` (3..64) sides and radius r, closed
 * at b, through the shared sweeper: tube_counts(2, sides, 0, 1) vertices
 * and indices. The caller sets the attributes and part first. */
void seg_line_tube(mesh_builder *mb, v3 a, v3 b, double r, int sides);

#endif
