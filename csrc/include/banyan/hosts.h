/*
 * banyan/hosts.h - host sets: the surfaces plants grow on (spec README,
 * "Hosts"). A host set is built once from any mix of oriented boxes (the
 * exact fast path) and triangle meshes under world transforms, then
 * shared, read-only, by every generate call that needs it: redo in
 * Blender, the steps of an ivy, several threads at once. Meshes are held
 * in an Embree BVH; distances, closest points, rays and sphere sweeps are
 * taken on their real triangles. See docs/hosts.md.
 *
 * Host numbering: the boxes first (0 .. n_boxes - 1), then the meshes in
 * the order given. Included by banyan.h.
 */
#ifndef BANYAN_HOSTS_H
#define BANYAN_HOSTS_H

#include <stdint.h>

/* Declared ahead of banyan.h, whose generator headers name it. */
typedef struct banyan_hosts banyan_hosts;

#include "../banyan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest triangle count of one host set (all meshes together). */
#define BANYAN_HOSTS_MAX_TRIANGLES 33554432u /* 2^25 */

/* Whether a mesh has an inside. */
typedef enum banyan_host_closed {
    BANYAN_HOST_CLOSED_AUTO = -1, /* closed when every edge is shared by exactly two triangles */
    BANYAN_HOST_OPEN = 0,         /* a thin two-sided surface: distances are unsigned */
    BANYAN_HOST_CLOSED = 1        /* solid: distances are signed (< 0 inside), even with small holes */
} banyan_host_closed;

/* One triangle mesh host. The arrays are read during banyan_hosts_create
 * only (the set keeps its own copy).
 *   positions   3 * vertex_count floats, object space, finite.
 *   indices     3 * triangle_count vertex numbers, each < vertex_count.
 *   transform   row-major 3x4 affine object -> world matrix (metres):
 *               world = transform[0..2 | 4..6 | 8..10] * p + (t[3], t[7], t[11]).
 *               Scale, shear and mirroring are allowed; it must be
 *               invertible. World coordinates must lie within [-1e6, 1e6].
 * Triangles of zero area are dropped; a mesh left with none is refused. */
typedef struct banyan_host_mesh {
    const float *positions;
    const uint32_t *indices;
    uint32_t vertex_count;
    uint32_t triangle_count;
    double transform[12];
    int32_t closed;             /* banyan_host_closed */
    int32_t reserved;           /* 0 */
} banyan_host_mesh;

/* Builds a host set from boxes[0 .. n_boxes - 1] and meshes[0 .. n_meshes -
 * 1] (n_boxes + n_meshes within 1 .. BANYAN_MAX_HOSTS). Refuses, naming the
 * host and the fault: bad boxes (BANYAN_E_BAD_HOST as banyan_box_validate),
 * empty meshes, non-finite or out-of-range coordinates, indices out of
 * range, a singular transform, a mesh whose triangles all have zero area
 * (all BANYAN_E_BAD_HOST), more than BANYAN_HOSTS_MAX_TRIANGLES triangles
 * (BANYAN_E_LIMIT). Needs Embree for meshes (BANYAN_E_UNSUPPORTED in a
 * build without it); boxes alone never touch Embree. On failure *out ==
 * NULL. The set is immutable and may be used from many threads at once.
 * Far from the world origin it keeps its hosts relative to a whole-metre
 * point near them (docs/api.md, "Far from the origin"); every query below
 * still takes and returns world coordinates. */
BANYAN_API banyan_status banyan_hosts_create(const banyan_box *boxes, uint32_t n_boxes,
                                             const banyan_host_mesh *meshes, uint32_t n_meshes,
                                             banyan_hosts **out, banyan_error *err);
/* Frees the set; accepts NULL. Nothing that uses it may still run. */
BANYAN_API void banyan_hosts_free(banyan_hosts *hosts);

/* What one host is. */
typedef struct banyan_host_info {
    int32_t kind;               /* 0 box, 1 mesh */
    int32_t closed;             /* 1 when it has an inside (a box always) */
    uint32_t triangle_count;    /* triangles kept (0 for a box) */
    uint32_t dropped_triangles; /* zero-area triangles dropped */
    uint32_t boundary_edges;    /* edges used by one triangle only (holes) */
    uint32_t shells;            /* connected pieces */
    double lo[3], hi[3];        /* world bounding box, metres */
} banyan_host_info;

BANYAN_API uint32_t banyan_hosts_count(const banyan_hosts *hosts);
BANYAN_API banyan_status banyan_hosts_info(const banyan_hosts *hosts, uint32_t index, banyan_host_info *out,
                                           banyan_error *err);

/* A query's answer: the nearest surface point, or the first one hit. */
typedef struct banyan_host_hit {
    int32_t host;               /* host index, -1 when nothing was found */
    uint32_t primitive;         /* triangle (box: face 0..5 = -x, +x, -y, +y, -z, +z) */
    double distance;            /* closest: signed distance (< 0 inside a closed host); ray/sweep: t */
    double point[3];            /* the surface point */
    double normal[3];           /* outward unit normal there (towards the query point for open meshes) */
} banyan_host_hit;

/* The nearest host surface to p within max_distance (> 0; HUGE_VAL for
 * any). hit->host = -1 when no surface is that near. A point inside a
 * closed host gets a negative distance, however deep. */
BANYAN_API banyan_status banyan_hosts_closest(const banyan_hosts *hosts, const double p[3], double max_distance,
                                              banyan_host_hit *hit, banyan_error *err);
/* The first surface along origin + t dir, t in [0, max_t] (dir need not be
 * unit; t is in multiples of it). hit->distance = t. */
BANYAN_API banyan_status banyan_hosts_raycast(const banyan_hosts *hosts, const double origin[3], const double dir[3],
                                              double max_t, banyan_host_hit *hit, banyan_error *err);
/* A sphere of `radius` moved from `from` to `to`: the first t in [0, 1]
 * at which it touches a host (hit->distance = t, hit->point the surface
 * point touched); hit->host = -1 when it passes free. A sphere that
 * touches at `from` gives t = 0. */
BANYAN_API banyan_status banyan_hosts_sweep_sphere(const banyan_hosts *hosts, const double from[3],
                                                   const double to[3], double radius, banyan_host_hit *hit,
                                                   banyan_error *err);
/* 1 when p is inside a closed host, else 0 (open meshes have no inside). */
BANYAN_API int32_t banyan_hosts_inside(const banyan_hosts *hosts, const double p[3]);

BANYAN_API size_t banyan_sizeof_host_mesh(void);
BANYAN_API size_t banyan_sizeof_host_hit(void);
BANYAN_API size_t banyan_sizeof_host_info(void);

#ifdef __cplusplus
}
#endif

#endif
