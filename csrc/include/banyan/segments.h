/*
 * banyan/segments.h - geometry-shader branch segments (spec: segments.md,
 * after Yamamoto 2019).
 *
 * A segment is one axis branch with n twigs and a forking hierarchy, sized
 * so that one geometry-shader invocation can emit it: at most 128 vertices
 * (64 lines). Banyan ships it twice: a CPU reference in C (the source of
 * truth, banyan_segment_lines) and a GLSL geometry shader
 * (banyan_segment_shader_source) that emits the same vertices in the same
 * order. A tree is a list of segments (banyan_segments_generate), each
 * attached to the axis of an earlier one or to a trunk line.
 *
 * Names. banyan_segment_* (singular) is the shader twin: calls and types
 * about one segment input (banyan_segment_input, banyan_segment_params),
 * each input on its own, also when many are passed at once
 * (banyan_segment_lines_many, like one draw call). banyan_segments_*
 * (plural) is the generator, a tree composed of a list of segments:
 * banyan_segments_generate has the entry shape of every generator
 * (docs/api.md, "Params"), and _lines, _find_unattached, _demo and
 * _preset_read work on the same list.
 *
 * Levels. Every output vertex carries a level code:
 *   0 = the axis, 1 = a twig (the spec's hierarchy level 0),
 *   1 + d = a branch of the spec's hierarchy level d (d >= 1).
 * So the level code is the spec's level plus one, which frees 0 for the
 * axis; thickness and colour fall with it.
 *
 * Precision. Inputs are given in double and rounded to float first; the
 * reference then computes in float (IEEE single, no fused multiply-add),
 * with the operations in the same order as the shader, so that shader and
 * reference agree to the last bit wherever the GPU compiler keeps that
 * order. Angles reach both as float cos/sin pairs computed once in double
 * (banyan_segment_uniforms), so the shader needs no trigonometry.
 */
#ifndef BANYAN_SEGMENTS_H
#define BANYAN_SEGMENTS_H
#include <stddef.h>
#include <stdint.h>

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The vertex budget of one segment (the shader's max_vertices). */
#define BANYAN_SEGMENT_MAX_VERTICES 128
/* Largest twig count n (the spec's n < 64). */
#define BANYAN_SEGMENT_MAX_TWIGS 63
/* Largest first-twig depth s accepted. */
#define BANYAN_SEGMENT_MAX_DEPTH 64
/* Level codes (see above). */
#define BANYAN_SEGMENT_LEVEL_AXIS 0
#define BANYAN_SEGMENT_LEVEL_TWIG 1
/* Bound on |S| components, l, and |A| (see banyan_segment_input). */
#define BANYAN_SEGMENT_MAX_COORD 1e12
#define BANYAN_SEGMENT_MIN_DIR 1e-12

/* The five inputs of one segment (spec "Inputs of one segment").
 *   S  start of the axis branch, metres; each component finite, |x| <= 1e12.
 *   A  direction of the axis; any length within [1e-12, 1e12] (it is
 *      normalised, in float, by the reference and the shader alike).
 *      A = 0, NaN or inf is refused.
 *   l  length of the axis, metres, 0 .. 1e12 (0 is allowed: the axis
 *      collapses to S and every twig starts there).
 *   n  twigs on the axis, 0 .. 63.
 *   s  hierarchy depth of the twig nearest the root, 0 .. 64; twig i
 *      (1-based) forks down to depth s + i - 1. */
typedef struct banyan_segment_input {
    double S[3];
    double A[3];
    double l;
    int32_t n;
    int32_t s;
} banyan_segment_input;

/* Global parameters of the method, with the paper's values as defaults
 * (banyan_segment_params_init).
 *   alpha_deg  twig angle: twig i is the axis direction turned about the
 *              vertical by +alpha (odd i) or -alpha (even i). 40; -360..360.
 *   beta_deg   fork yaw about the vertical. 30; -360..360.
 *   gamma_deg  roll of child 1 about its parent's direction. -30; -360..360.
 *   omega_deg  roll of child 2. 10; -360..360.
 *   m          length of every twig and fork branch, in the same unit as S
 *              and l (the paper's 10). 1e-6 .. 1e6. */
typedef struct banyan_segment_params {
    double alpha_deg;
    double beta_deg;
    double gamma_deg;
    double omega_deg;
    double m;
} banyan_segment_params;

BANYAN_API void banyan_segment_params_init(banyan_segment_params *params);
BANYAN_API size_t banyan_sizeof_segment_params(void);
BANYAN_API size_t banyan_sizeof_segment_input(void);

/* Checks one input and the params; BANYAN_E_RANGE names the field, its
 * value and its range ("S[1] = nan must be finite"). */
BANYAN_API banyan_status banyan_segment_check(const banyan_segment_input *in, const banyan_segment_params *params,
                                              banyan_error *err);

/* The CPU reference: generates one segment into caller arrays. It
 * allocates nothing. Vertices come as line pairs (vertex 2k -> 2k+1) in
 * generation order: the axis, the n twigs in order, then the forks level
 * by level (breadth-first), within a level in twig order, then parent
 * order; each fork adds its two child lines G1->H1, G2->H2. Before every
 * fork the 128-vertex budget is checked; the first fork that does not fit
 * ends the segment.
 *   out_xyz    room for 128 * 3 floats (x, y, z per vertex).
 *   out_level  room for 128 level codes, or NULL.
 *   out_count  gets the vertex count (even, 2 .. 128); 0 on failure. */
BANYAN_API banyan_status banyan_segment_lines(const banyan_segment_input *in, const banyan_segment_params *params,
                                                 float out_xyz[BANYAN_SEGMENT_MAX_VERTICES * 3],
                                                 uint8_t out_level[BANYAN_SEGMENT_MAX_VERTICES],
                                                 int32_t *out_count, banyan_error *err);

/* Many segments at once, as one shader draw call would make them: segment
 * i writes 128 vertex slots from out_xyz + 384 * i and out_level + 128 * i
 * (unused slots are left untouched) and its count to out_counts[i].
 * out_level may be NULL. Every input is checked first; on failure nothing
 * is written and the message names ins[i]. count 0 .. 1<<24. */
BANYAN_API banyan_status banyan_segment_lines_many(const banyan_segment_input *ins, uint32_t count,
                                                      const banyan_segment_params *params, float *out_xyz,
                                                      uint8_t *out_level, int32_t *out_counts, banyan_error *err);

/* Vertex count of a segment with n twigs and first depth s, budget
 * included (it depends on nothing else): 2 + 2n + 4 * min(F, (126 - 2n) / 4)
 * with F = sum over i of (2^(s+i-1) - 1) forks. -1 when n or s is out of
 * range. Use it to size transform-feedback buffers. */
BANYAN_API int32_t banyan_segment_vertex_count(int32_t n, int32_t s);

/* The shader's uniforms for these params, exactly as the reference uses
 * them: out[0..7] = cos, sin of alpha, beta, gamma, omega (float, rounded
 * from double), out[8] = m. Refuses params out of range. */
BANYAN_API banyan_status banyan_segment_uniforms(const banyan_segment_params *params, float out[9], banyan_error *err);

/* GLSL 3.30 core source of the shader twin, NUL-terminated, static:
 * stage 0 vertex, 1 geometry, 2 fragment; NULL for any other stage.
 * Interface (see docs/segments.md):
 *   vertex inputs   location 0 vec3 a_S, 1 vec3 a_A, 2 float a_l,
 *                   3 int a_n, 4 int a_s (glVertexAttribIPointer);
 *   uniforms        vec2 u_alpha, u_beta, u_gamma, u_omega (cos, sin),
 *                   float u_m, mat4 u_mvp;
 *   geometry        points in, line_strip out, max_vertices = 128; each
 *                   line is one EndPrimitive'd 2-vertex strip;
 *   output varying  vec4 g_seg = (x, y, z, level code), capturable with
 *                   transform feedback; gl_Position = u_mvp * (x, y, z, 1). */
BANYAN_API const char *banyan_segment_shader_source(int32_t stage);

/* ------------------------------------------------------- tree composer */

#define BANYAN_SEGMENTS_MAX_COUNT (1u << 22)

/* Parameters of `banyan segments` (generator BANYAN_GEN_SEGMENTS); keys
 * as in presets and --set. Defaults from banyan_segments_params_init.
 *   seed              used only by banyan_segments_demo (random tree).
 *   max_vertices      mesh vertex cap, 1 .. 1<<30 (default 4,000,000).
 *   alpha_deg .. omega_deg   as in banyan_segment_params (40, 30, -30, 10).
 *   m                 twig and fork length in paper units (10); metres =
 *                     m * unit.
 *   unit              metres per paper unit, 1e-6 .. 1e3 (0.05: twigs of
 *                     0.5 m).
 *   radius            base radius of an axis line (level 0), m (0.02); every
 *                     tube tapers to half its base radius at its tip.
 *   radius_ratio      base radius of level k = radius * radius_ratio^k, no
 *                     more than the parent's where a line leaves it (0.6).
 *   radius_min        radii never go below this (tip domes aside), m (0.002).
 *   trunk_radius      base radius of the trunk line's tube, m (0.06).
 *   sides             sides of every tube, 3 .. 64 (6).
 *   attach_tolerance  how far S may lie from an earlier axis (or the
 *                     trunk) and still count as attached, m (0.001).
 *   demo_segments     segments in banyan_segments_demo's random tree (24).
 *   demo_height       trunk height of the demo tree, m (4).
 *   max_seconds, max_memory_mb   the run's budget of banyan_segments_generate:
 *                     past either, BANYAN_E_LIMIT naming it. */
typedef struct banyan_segments_params {
    uint64_t seed;
    int32_t max_vertices;
    double alpha_deg;
    double beta_deg;
    double gamma_deg;
    double omega_deg;
    double m;
    double unit;
    double radius;
    double radius_ratio;
    double radius_min;
    double trunk_radius;
    int32_t sides;
    double attach_tolerance;
    int32_t demo_segments;
    double demo_height;
    double max_seconds;   /* budget (docs/api.md, "Budgets"): s, 0.01 .. 604800 (600) */
    double max_memory_mb; /* MB of resident memory above the process's at the call, 16 .. 1048576 (8192) */
    int32_t wind;                 /* bool: the wind attributes (banyan.h, BANYAN_ATTR_WIND_*). Default 1 */
} banyan_segments_params;

BANYAN_API void banyan_segments_params_init(banyan_segments_params *params);
BANYAN_API size_t banyan_sizeof_segments_params(void);

/* Measures of one composed tree. */
typedef struct banyan_segments_stats {
    uint32_t segments;      /* inputs */
    uint32_t lines;         /* lines in the line set, trunk included */
    uint32_t budget_hits;   /* segments the 128-vertex budget cut short */
    uint32_t unattached;    /* segments not on an earlier axis or the trunk */
    uint32_t max_level;     /* highest level code present */
    uint32_t lines_per_level[8]; /* lines of level code 0..6; [7] = 7 and deeper */
} banyan_segments_stats;
BANYAN_API size_t banyan_sizeof_segments_stats(void);

/* Which segments are not attached. Segment i is attached when its S lies
 * within attach_tolerance of the axis line S_j + A_j/|A_j| t, t in
 * [0, l_j], of an earlier segment j < i, or of the trunk line. trunk is 6
 * doubles (start x, y, z, end x, y, z) or NULL; without a trunk, segment 0
 * is the root and counts as attached. unattached (NULL, or room for
 * `count` indices) gets the unattached indices in increasing order and
 * *n_unattached their number. Inputs are checked as by
 * banyan_segment_check. */
BANYAN_API banyan_status banyan_segments_find_unattached(const banyan_segments_params *params,
                                                         const banyan_segment_input *segs, uint32_t count,
                                                         const double *trunk, uint32_t *unattached,
                                                         uint32_t *n_unattached, banyan_error *err);

/* The tree's line set into caller arrays: every line of every segment (in
 * segment order, each in reference order), metres, the trunk line first
 * when given (level code -1). Call with xyz == NULL to get *n_vertices
 * only. Otherwise xyz holds 3 * cap floats and level (or NULL) cap
 * entries; BANYAN_E_LIMIT when cap is too small (nothing is written;
 * *n_vertices still gets the count needed). */
BANYAN_API banyan_status banyan_segments_lines(const banyan_segments_params *params,
                                               const banyan_segment_input *segs, uint32_t count,
                                               const double *trunk, float *xyz, int8_t *level, uint32_t cap,
                                               uint32_t *n_vertices, banyan_error *err);

/* The composed tree as a thin tube mesh. Each line becomes a tube of
 * `sides` sides through the shared sweeper, radius by level, closed at its
 * tip; lines shorter than 1e-9 m get no tube. The skeleton is the line set:
 * two points per line and one edge, skel_tag = level code (-1 trunk),
 * skel_radius = the tube radius. Per-vertex attributes: "level" (level
 * code, -1 trunk) and "segment" (input index, -1 trunk); vertex colours
 * fade from bark to twig green with the level. The input geometry is
 * segs[0 .. count) (count 1 .. 1<<22) and trunk (6 doubles, or NULL), as
 * in banyan_segments_find_unattached. Unattached segments are still
 * built; stats->unattached counts them and banyan_segments_find_unattached
 * on the same inputs lists them. stats: NULL, or filled (zeroed on
 * failure). progress: NULL, or called on the calling thread (docs/api.md
 * "Progress and cancel"); the mesh does not depend on it.
 * BANYAN_E_LIMIT when the mesh would pass max_vertices. */
BANYAN_API banyan_status banyan_segments_generate(const banyan_segments_params *params,
                                                  const banyan_segment_input *segs, uint32_t count,
                                                  const double *trunk, banyan_mesh **out,
                                                  banyan_segments_stats *stats, const banyan_progress *progress,
                                                  banyan_error *err);

/* A random tree of params->demo_segments attached segments from
 * params->seed: a vertical trunk of demo_height metres, segments on the
 * trunk, then segments on earlier segments' axes. out has room for cap
 * inputs; trunk gets 6 doubles. Used by `banyan segments` without a
 * preset, the tests and the benchmark. */
BANYAN_API banyan_status banyan_segments_demo(const banyan_segments_params *params, banyan_segment_input *out,
                                              uint32_t cap, uint32_t *count, double trunk[6], banyan_error *err);

/* Reads a preset's segment list:
 *   "segments": [ {"S": [x,y,z], "A": [x,y,z], "l": 1.5, "n": 4, "s": 1}, ...]
 *   "trunk": {"start": [x,y,z], "end": [x,y,z]}           (optional)
 * All five keys of an entry are required; others are refused. Messages
 * start with "<source>:<line>: segments[i]". With out == NULL and cap == 0
 * only *count is set; otherwise more than cap entries is refused. Without
 * "segments" *count is 0; an empty list is refused (BANYAN_E_RANGE). trunk
 * (6 doubles) and *has_trunk (0 or 1) may be NULL. */
BANYAN_API banyan_status banyan_segments_preset_read(const char *text, size_t length, const char *source,
                                                     banyan_segment_input *out, uint32_t cap, uint32_t *count,
                                                     double trunk[6], int32_t *has_trunk, banyan_error *err);

#ifdef __cplusplus
}
#endif

#endif
