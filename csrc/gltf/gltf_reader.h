/* gltf_reader.h - the .glb reader's calls inside the library (the public
 * ones are banyan_glb_read_host and banyan_glb_read_host_budget in banyan.h):
 * a look at a file's sizes from its header and JSON alone, and a read
 * inside a budget shared by several files (banyan_preset_host_set_budget). */
#ifndef BANYAN_GLTF_READER_H
#define BANYAN_GLTF_READER_H

#include <stdint.h>

#include "banyan.h"

#ifdef __cplusplus
extern "C" {
#endif
#include "base/progress.h"

/* The work of reading a .glb, counted from its header and JSON chunk
 * before its binary chunk is read: every node instance of every primitive
 * reached from the scene counted. */
typedef struct glb_sizes {
    uint64_t triangles;    /* triangles the host mesh would have */
    uint64_t vertex_reads; /* POSITION elements transformed and merged */
    double memory;         /* bytes the read may hold at once (an upper estimate) */
} glb_sizes;

/* Reads only the 12-byte header, the chunk headers and the JSON chunk of
 * path; refuses what banyan_glb_read_host would refuse from those (not a
 * .glb, sizes that disagree with the file, more than
 * BANYAN_HOSTS_MAX_TRIANGLES triangles or GLB_MAX_VERTEX_READS vertices to
 * read), or whose JSON would not fit the budget of g (NULL for none). */
banyan_status glb_scan(const char *path, prog *g, glb_sizes *out, banyan_error *err);

/* banyan_glb_read_host inside the budget of g (prog_budget; NULL for
 * none): refused up front when its estimate passes max_memory_mb, stopped
 * (BANYAN_E_LIMIT) when the time or memory runs out while it reads. */
banyan_status glb_read_host_prog(const char *path, const double transform[12], int32_t closed, prog *g,
                                 struct banyan_host_mesh **out, banyan_error *err);

/* cJSON parse under the library's one JSON lock (cJSON 1.7 keeps a global
 * error position): params/preset.c. */
struct cJSON;
struct cJSON *preset_json_parse(const char *text, size_t len, const char **end);

#ifdef __cplusplus
}
#endif

#define GLB_MAX_VERTEX_READS (3ull * BANYAN_HOSTS_MAX_TRIANGLES)

#endif
