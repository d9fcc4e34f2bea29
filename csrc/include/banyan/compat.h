/*
 * banyan/compat.h - the entry points of ABI 19 whose names the generators'
 * one entry shape (docs/api.md, "Params and hosts") no longer uses, kept
 * as thin wrappers for one ABI version: each calls the function named
 * beside it and will be removed with ABI 21. ABI 19's
 * banyan_roots_generate, banyan_ivy_generate, banyan_ivy_create,
 * banyan_keyaki_generate and banyan_avenue_generate kept their names with
 * the new arguments, and banyan_keyaki_stats names the stats struct, so
 * those cannot be kept (docs/api.md lists the calls that replace them).
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

#ifdef __cplusplus
}
#endif

#endif
