/* mesh_builder.h - a growable banyan_mesh under construction.
 *
 * Generators set the "current" colour and attribute values, then add
 * vertices and triangles; every vertex takes the current values. Errors
 * are sticky: after the first failure (out of memory, or the vertex limit)
 * further calls do nothing and mb_finish reports it, so generator code
 * need not check every call. */
#ifndef BANYAN_MESH_BUILDER_H
#define BANYAN_MESH_BUILDER_H

#include "banyan.h"
#include "base/vec.h"

#define MB_MAX_ATTRS 16
/* Hard ceiling on vertices in one mesh, whatever max_vertices asks. */
#define MB_VERTEX_CEILING 0x40000000u

typedef struct mesh_builder {
    float *pos, *nrm, *uv, *col;
    uint32_t *idx;
    uint32_t nv, cap_v, ni, cap_i;
    uint32_t max_vertices;
    int with_color;
    float cur_color[4];

    uint32_t n_attr;
    char attr_name[MB_MAX_ATTRS][BANYAN_NAME_MAX];
    float *attr[MB_MAX_ATTRS];
    float cur_attr[MB_MAX_ATTRS];

    banyan_material *mat;
    uint32_t n_mat;
    banyan_part *part;
    uint32_t n_part;

    float *skel_pos, *skel_rad;
    int32_t *skel_tag;
    uint32_t n_skel, cap_skel;
    uint32_t *skel_edge;
    uint32_t n_edge, cap_edge;

    banyan_status status; /* first failure, sticky */
    /* The big arrays (pos, nrm, uv, col, idx, attr) belong to the caller
     * and hold exactly cap_v vertices and cap_i indices (mb_init_external):
     * never grown, trimmed nor freed here. */
    int external;
    /* The skeleton arrays belong to the caller too (mb_external_skeleton). */
    int external_skel;

    /* tube_sweep's ring angles (cosines, sines) and u per ring vertex for
     * ring_sides sides, kept across the tubes of one mesh; 0 = none yet. */
    int ring_sides;
    double ring_cs[256], ring_sn[256];
    float ring_u[257];
} mesh_builder;

/* max_vertices: the generator's limit (1 .. MB_VERTEX_CEILING). */
void mb_init(mesh_builder *mb, uint32_t max_vertices, int with_color);
void mb_free(mesh_builder *mb);

/* A builder writing straight into the caller's arrays, sized exactly
 * (cap_v vertices, cap_i indices; col NULL: no colours), e.g. one tree's
 * slice of an avenue's merged mesh, so nothing is copied and no page is
 * touched twice. attr[k] is the array of the attribute attr_names[k];
 * mb_add_attr then returns the slot of the name it is given. Needing more
 * room than given fails with BANYAN_E_INTERNAL (the caller's plan was
 * wrong). Finish with mb_close, not mb_finish; mb_free frees only the
 * builder's own small arrays (parts, materials, skeleton). */
void mb_init_external(mesh_builder *mb, uint32_t cap_v, uint32_t cap_i, float *pos, float *nrm, float *uv, float *col,
                      uint32_t *idx, float *const *attr, const char *const *attr_names, uint32_t n_attr);
/* Skeleton points and edges written straight into the caller's arrays
 * too (room for cap_points points and cap_edges edges), e.g. one tree's
 * slice of an avenue's merged skeleton. Edges hold the builder's own point
 * numbers (from 0): the caller offsets them. Needing more room fails with
 * BANYAN_E_INTERNAL, as mb_init_external's arrays do; mb_free leaves them. */
void mb_external_skeleton(mesh_builder *mb, float *pos, float *radius, int32_t *tag, uint32_t cap_points,
                          uint32_t *edges, uint32_t cap_edges);
/* Closes the current part and drops a trailing empty one (mb_finish does
 * this too). */
void mb_close(mesh_builder *mb);
/* Reports the builder's sticky failure (mb->status, nonzero) in err, as
 * mb_finish does, and returns it. */
banyan_status mb_fail(const mesh_builder *mb, banyan_error *err);

/* Declares a per-vertex float attribute; returns its slot. Declare all
 * attributes before adding vertices. */
int mb_add_attr(mesh_builder *mb, const char *name);
static inline void mb_set_attr(mesh_builder *mb, int slot, double v) { mb->cur_attr[slot] = (float)v; }
void mb_set_color(mesh_builder *mb, const double rgba[4]);

/* Adds a material; returns its index. */
uint32_t mb_add_material(mesh_builder *mb, const char *name, const double rgba[4], double roughness,
                         int double_sided);
/* Starts a new part drawn with `material`; vertices and triangles added
 * from now on belong to it. Without any call, one part with material 0
 * covers everything. */
void mb_begin_part(mesh_builder *mb, uint32_t material, uint32_t group);

/* Makes room for n more vertices and m more indices; fails with
 * BANYAN_E_LIMIT when the vertex limit would be passed. */
banyan_status mb_reserve(mesh_builder *mb, uint32_t n_vertices, uint32_t n_indices);
/* Slow paths of mb_vertex / mb_tri: grow, then add. */
uint32_t mb_vertex_grow(mesh_builder *mb, v3 p, v3 n, double u, double v);
void mb_tri_grow(mesh_builder *mb, uint32_t a, uint32_t b, uint32_t c);

/* Adds a vertex and returns its index. Inline because the sweeper calls it
 * for every vertex; call mb_reserve first so it never has to grow. */
/* Writes vertex i's position, normal and uv (as floats). */
static inline void mb_put(mesh_builder *mb, uint32_t i, v3 p, v3 n, double u, double v) {
    float *P = mb->pos + 3 * (size_t)i, *N = mb->nrm + 3 * (size_t)i, *T = mb->uv + 2 * (size_t)i;
    P[0] = (float)p.x; P[1] = (float)p.y; P[2] = (float)p.z;
    N[0] = (float)n.x; N[1] = (float)n.y; N[2] = (float)n.z;
    T[0] = (float)u; T[1] = (float)v;
}

static inline uint32_t mb_vertex(mesh_builder *mb, v3 p, v3 n, double u, double v) {
    if (mb->nv >= mb->cap_v || mb->status) return mb_vertex_grow(mb, p, n, u, v);
    uint32_t i = mb->nv++;
    mb_put(mb, i, p, n, u, v);
    if (mb->with_color) {
        float *C = mb->col + 4 * (size_t)i;
        C[0] = mb->cur_color[0]; C[1] = mb->cur_color[1]; C[2] = mb->cur_color[2]; C[3] = mb->cur_color[3];
    }
    for (uint32_t a = 0; a < mb->n_attr; a++) mb->attr[a][i] = mb->cur_attr[a];
    return i;
}

static inline void mb_tri(mesh_builder *mb, uint32_t a, uint32_t b, uint32_t c) {
    if (mb->ni + 3 > mb->cap_i || mb->status) {
        mb_tri_grow(mb, a, b, c);
        return;
    }
    uint32_t *I = mb->idx + mb->ni;
    I[0] = a; I[1] = b; I[2] = c;
    mb->ni += 3;
}

/* Bulk paths for sweepers: mb_vertices appends `count` vertices carrying
 * the current colour and attributes and returns the first one's index; the
 * caller writes their positions, normals and uvs (mb_put, or straight into
 * mb->pos/nrm/uv).
 * mb_indices appends `count` indices and returns where to write them.
 * Both return UINT32_MAX / NULL once the builder has failed. */
uint32_t mb_vertices(mesh_builder *mb, uint32_t count);
uint32_t *mb_indices(mesh_builder *mb, uint32_t count);

/* Skeleton: mb_skel_reserve makes room for more points and edges (like
 * mb_reserve); the adds are inline, growing on their slow paths. */
banyan_status mb_skel_reserve(mesh_builder *mb, uint32_t points, uint32_t edges);
uint32_t mb_skel_point_grow(mesh_builder *mb, v3 p, double radius, int32_t tag);
void mb_skel_edge_grow(mesh_builder *mb, uint32_t a, uint32_t b);

static inline uint32_t mb_skel_point(mesh_builder *mb, v3 p, double radius, int32_t tag) {
    if (mb->n_skel >= mb->cap_skel || mb->status) return mb_skel_point_grow(mb, p, radius, tag);
    uint32_t i = mb->n_skel++;
    float *P = mb->skel_pos + 3 * (size_t)i;
    P[0] = (float)p.x; P[1] = (float)p.y; P[2] = (float)p.z;
    mb->skel_rad[i] = (float)radius;
    mb->skel_tag[i] = tag;
    return i;
}

static inline void mb_skel_edge(mesh_builder *mb, uint32_t a, uint32_t b) {
    if (mb->n_edge >= mb->cap_edge || mb->status) {
        mb_skel_edge_grow(mb, a, b);
        return;
    }
    uint32_t *E = mb->skel_edge + 2 * (size_t)mb->n_edge++;
    E[0] = a; E[1] = b;
}

/* Hands the arrays over as a banyan_mesh; the builder is emptied either
 * way. On failure *out stays NULL and err says why. */
banyan_status mb_finish(mesh_builder *mb, banyan_mesh **out, banyan_error *err);

#endif
