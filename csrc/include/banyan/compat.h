/*
 * banyan/compat.h - entry points whose names the public API no longer
 * uses, kept as thin wrappers: each calls the function named beside it.
 * ABI 19's names (of the calls that took the generators' one entry
 * shape, docs/api.md "Params") and ABI 20's names of the segment
 * reference (banyan_segment_lines) are removed with ABI 23.
 *
 * A call that kept its name with new arguments cannot be kept beside it:
 *   ABI 20: banyan_roots_generate, banyan_ivy_generate, banyan_ivy_create,
 *           banyan_keyaki_generate and banyan_avenue_generate took the one
 *           entry shape, and banyan_keyaki_stats names the stats struct
 *           (ABI 19's call of that name is banyan_keyaki_skeleton_stats);
 *   ABI 21: banyan_segments_generate lost its `unattached` argument (the
 *           list is banyan_segments_find_unattached's; the count stays in
 *           stats->unattached) and takes a progress callback before err;
 *           banyan_material.image counts from 1 (0 = no image, k = the
 *           mesh's images[k - 1]; ABI 20: -1 = none, k = images[k]).
 * docs/api.md, "ABI checks", lists them too.
 */
#ifndef BANYAN_COMPAT_H
#define BANYAN_COMPAT_H

#include <stddef.h>
#include <stdint.h>

#include "../banyan.h"

/* The generator types by their struct tags: this header is reached from
 * each generator header through banyan.h, before that header's own types
 * are complete. */

#ifdef __cplusplus
extern "C" {
#endif

struct banyan_roots_params;
struct banyan_roots_stats;
struct banyan_ivy_params;
struct banyan_ivy_stats;
struct banyan_ivy;
struct banyan_hosts;
struct banyan_keyaki_stats;

/* banyan_roots_generate on a host set. */
BANYAN_API banyan_status banyan_roots_generate_hosts(const struct banyan_roots_params *params, const struct banyan_hosts *hosts,
                                                     banyan_mesh **out, struct banyan_roots_stats *stats,
                                                     const banyan_progress *progress, banyan_error *err);
/* banyan_roots_generate on the host set of boxes[0 .. n_hosts). */
BANYAN_API banyan_status banyan_roots_generate_stats(const struct banyan_roots_params *params, const banyan_box *hosts,
                                                     uint32_t n_hosts, banyan_mesh **out, struct banyan_roots_stats *stats,
                                                     banyan_error *err);
/* banyan_ivy_generate without stats. */
BANYAN_API banyan_status banyan_ivy_generate_hosts(const struct banyan_ivy_params *params, const struct banyan_hosts *hosts,
                                                   banyan_mesh **out, const banyan_progress *progress,
                                                   banyan_error *err);
/* banyan_ivy_generate. */
BANYAN_API banyan_status banyan_ivy_generate_hosts_stats(const struct banyan_ivy_params *params, const struct banyan_hosts *hosts,
                                                         banyan_mesh **out, struct banyan_ivy_stats *stats,
                                                         const banyan_progress *progress, banyan_error *err);
/* banyan_ivy_create. */
BANYAN_API banyan_status banyan_ivy_create_hosts(const struct banyan_ivy_params *params, const struct banyan_hosts *hosts,
                                                 struct banyan_ivy **out, banyan_error *err);
/* The keyaki's stats struct and its size. */
typedef struct banyan_keyaki_stats banyan_keyaki_statistics;
BANYAN_API size_t banyan_sizeof_keyaki_statistics(void);

/* ABI 20's names of the segment reference. */
struct banyan_segment_input;
struct banyan_segment_params;
/* banyan_segment_lines. */
BANYAN_API banyan_status banyan_segment_generate(const struct banyan_segment_input *in,
                                                 const struct banyan_segment_params *params, float *out_xyz,
                                                 uint8_t *out_level, int32_t *out_count, banyan_error *err);
/* banyan_segment_lines_many. */
BANYAN_API banyan_status banyan_segment_generate_many(const struct banyan_segment_input *ins, uint32_t count,
                                                      const struct banyan_segment_params *params, float *out_xyz,
                                                      uint8_t *out_level, int32_t *out_counts, banyan_error *err);

#ifdef __cplusplus
}
#endif

#endif
