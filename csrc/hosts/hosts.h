/* hosts.h - the host set inside the library (public side: banyan/hosts.h).
 * Boxes keep the exact obb queries of obb.h; meshes are Embree scenes
 * queried here (hosts.c). Generators loop over the boxes as before (so a
 * box-only set gives the bytes it always gave) and ask the mesh queries
 * below for the meshes. */
#ifndef BANYAN_HOSTS_HOSTS_H
#define BANYAN_HOSTS_HOSTS_H

#include "banyan.h"
#include "obb.h"
#include "base/vec.h"

/* One mesh host, in world space relative to `origin` (kept in double, so
 * a mesh far from the world origin keeps float precision near itself). */
typedef struct host_mesh {
    v3 origin;              /* its vertices' zero, in the set's frame */
    uint32_t nv, nt;        /* vertices, triangles kept */
    float *pos;             /* 4 * nv (Embree reads 16-byte vertices): x, y, z, 0 relative to origin */
    uint32_t *tri;          /* 3 * nt */
    float *fnrm;            /* 3 * nt unit face normals (outward for a closed mesh) */
    uint32_t *twin;         /* 3 * nt: the side (3 t + k) across edge k (v0v1, v1v2, v2v0) of triangle t,
                               UINT32_MAX on a hole or a non-manifold edge; gives the edge pseudonormals */
    float *vnrm;            /* 3 * nv angle-weighted vertex pseudonormals, unit */
    int closed;             /* has an inside: signed distances */
    int sign_by_rays;       /* the pseudonormal sign is not to be trusted (holes, several shells,
                               inconsistent winding): inside is decided by rays */
    uint32_t dropped, boundary_edges, shells;
    v3 lo, hi;              /* bounds, in the set's frame */
    float bpad;             /* triangle boxes grow by this for Embree (1e-6 of the diagonal): its float
                               traversal then never drops a triangle the exact tests would keep */
    double slack;           /* 1e-12 of the diagonal: culls drop only what is farther by more than this */
    uint32_t ncap;          /* triangles closing its holes, for the inside test (host_caps.c); 0 unless
                               sign_by_rays == 1 with holes and no non-manifold edge */
    float *capv;            /* 9 * ncap: each cap triangle's corners */
    void *scene;            /* RTCScene */
} host_mesh;

struct banyan_hosts {
    /* World position of the set's frame (frame.h): everything below is
     * relative to it, and the generators run in it; the public queries
     * translate in double. 0 for scenes near the world origin. */
    v3 origin;
    uint32_t n_boxes, n_meshes;
    obb *boxes;             /* n_boxes */
    host_mesh *meshes;      /* n_meshes */
    v3 *lo, *hi;            /* bounds per host (boxes, then meshes) */
    void *device;           /* RTCDevice, NULL without meshes */
};

/* Vertex i of m (relative to m->origin) and a stored float triple. */
static inline v3 vtx(const host_mesh *m, uint32_t i) {
    const float *f = m->pos + 4 * (size_t)i;
    return v3_make(f[0], f[1], f[2]);
}
static inline v3 f3(const float *f) { return v3_make(f[0], f[1], f[2]); }

/* Nearest surface point of a mesh. */
typedef struct mesh_near {
    double dist;            /* signed for closed meshes (< 0 inside), else >= 0 */
    v3 point;               /* world */
    v3 normal;              /* unit: outward normal of the distance field at p (from the surface towards p
                               outside, away from p inside); the face's normal when p is on it */
    uint32_t prim;          /* triangle */
} mesh_near;

/* The nearest surface of m to p, looked for within `cap` metres (> 0,
 * HUGE_VAL for no limit). Returns 1 with *out filled when a surface lies
 * within cap. Returns 0 when none does: out->dist is then +cap outside (or
 * for an open mesh) and -cap inside a closed mesh (a bound: |distance| >=
 * cap), out->normal (0,0,1), out->point p. */
int hmesh_nearest(const host_mesh *m, v3 p, double cap, mesh_near *out);
/* Signed distance only, under the same rule (exact below cap, +-cap beyond). */
double hmesh_distance(const host_mesh *m, v3 p, double cap);
/* Unsigned distance under the same cap rule, with no inside test (which
 * costs rays on a miss, or on every query of a mesh signed by rays): for a
 * caller that knows which side p is on, e.g. a point within the free ball
 * of a point known to be outside. */
double hmesh_udistance(const host_mesh *m, v3 p, double cap, uint32_t *prim);
/* Distance from p to triangle prim of m. A caller asking many nearby
 * points keeps the last nearest triangle (prim of hmesh_nearest, or of
 * hmesh_udistance above when not NULL) and caps the next query at its
 * distance (times 1 + 1e-6: Embree's radius is a float): the nearest
 * surface is no farther, and a small query sphere visits few leaves. */
double hmesh_prim_distance(const host_mesh *m, uint32_t prim, v3 p);
/* The closest point of triangle prim of m to p, world. */
v3 hmesh_prim_closest(const host_mesh *m, uint32_t prim, v3 p);
/* Least unsigned distance from the segment a-b to m's surface, exact below
 * cap (> 0), cap beyond. Exact per triangle (no sphere tracing): a few
 * queries however near the segment runs to the surface. With `first`, the
 * least over the first piece (pieces of at most 2 cap, taken in order from
 * a) that comes nearer than cap instead (a real distance of the segment,
 * not always the least): for a caller that only asks whether the segment
 * comes within cap. */
double hmesh_segment_distance(const host_mesh *m, v3 a, v3 b, double cap, int first);
/* A sphere of radius r moved from p by d: the first t in [0, 1] at which,
 * getting nearer to a triangle, it would come within r - eps of it (t is
 * where it is at r: free); 1 when it never does. *normal (when t < 1): the
 * distance gradient of that triangle there. Exact up to root finding (the
 * distance to a triangle is convex along a line); unlike sphere tracing, a
 * sphere pressed against the surface and moving along it or away is not
 * stopped, so it can slide. (These four were added for the roots.) */
double hmesh_sweep(const host_mesh *m, v3 p, v3 d, double r, double eps, v3 *normal);
/* Makes geometry (an RTCGeometry of type USER) hold m's triangles: Embree
 * builds and walks the tree over their boxes; every answer comes from the
 * library's own tests in double (host_queries.c). */
void hmesh_user_geometry(void *geometry, host_mesh *m);

/* Fills m->capv and m->ncap from the holes of m (m->twin): 0 when out of
 * memory. */
int hmesh_build_caps(host_mesh *m);
/* The generalised winding number of m's caps at p (local): a sum of solid
 * angles over 4 pi. */
double hmesh_cap_winding(const host_mesh *m, v3 p);

/* p inside the closed mesh m (0 for open meshes). */
int hmesh_inside(const host_mesh *m, v3 p);
/* First surface hit along segment a -> b: returns 1 with t in [0, 1] and
 * the face normal (facing a), else 0. */
int hmesh_segment_hit(const host_mesh *m, v3 a, v3 b, double *t, v3 *normal);


/* Host h's world bounds (boxes then meshes). */
static inline int hosts_far_from(const banyan_hosts *H, uint32_t h, v3 p, double margin) {
    v3 lo = H->lo[h], hi = H->hi[h];
    return p.x < lo.x - margin || p.x > hi.x + margin || p.y < lo.y - margin || p.y > hi.y + margin ||
           p.z < lo.z - margin || p.z > hi.z + margin;
}

#endif
