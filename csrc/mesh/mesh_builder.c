#include "mesh_builder.h"

#include <stdlib.h>
#include <string.h>

#include "base/big_alloc.h"
#include "base/error.h"

void mb_init(mesh_builder *mb, uint32_t max_vertices, int with_color) {
    memset(mb, 0, sizeof *mb);
    mb->max_vertices = max_vertices < 1 ? 1 : (max_vertices > MB_VERTEX_CEILING ? MB_VERTEX_CEILING : max_vertices);
    mb->with_color = with_color;
    for (int i = 0; i < 4; i++) mb->cur_color[i] = 1.0f;
}

void mb_init_external(mesh_builder *mb, uint32_t cap_v, uint32_t cap_i, float *pos, float *nrm, float *uv, float *col,
                      uint32_t *idx, float *const *attr, const char *const *attr_names, uint32_t n_attr) {
    mb_init(mb, cap_v, col != NULL);
    mb->external = 1;
    mb->pos = pos, mb->nrm = nrm, mb->uv = uv, mb->col = col, mb->idx = idx;
    mb->cap_v = cap_v, mb->cap_i = cap_i;
    if (n_attr > MB_MAX_ATTRS) {
        mb->status = BANYAN_E_INTERNAL;
        return;
    }
    for (uint32_t i = 0; i < n_attr; i++) {
        mb->attr[i] = attr[i];
        strncpy(mb->attr_name[i], attr_names[i], BANYAN_NAME_MAX - 1);
        mb->attr_name[i][BANYAN_NAME_MAX - 1] = '\0';
    }
    mb->n_attr = n_attr;
}

void mb_external_skeleton(mesh_builder *mb, float *pos, float *radius, int32_t *tag, uint32_t cap_points,
                          uint32_t *edges, uint32_t cap_edges) {
    if (mb->n_skel || mb->n_edge) { /* too late: points were added to the builder's own arrays */
        if (!mb->status) mb->status = BANYAN_E_INTERNAL;
        return;
    }
    if (!mb->external_skel) { /* an empty reservation of its own */
        free(mb->skel_pos); free(mb->skel_rad); free(mb->skel_tag); free(mb->skel_edge);
    }
    mb->external_skel = 1;
    mb->skel_pos = pos, mb->skel_rad = radius, mb->skel_tag = tag, mb->skel_edge = edges;
    mb->cap_skel = cap_points, mb->cap_edge = cap_edges;
}

void mb_free(mesh_builder *mb) {
    if (!mb->external) {
        free(mb->pos); free(mb->nrm); free(mb->uv); free(mb->col); free(mb->idx);
        for (uint32_t i = 0; i < mb->n_attr; i++) free(mb->attr[i]);
    }
    free(mb->mat); free(mb->part);
    if (!mb->external_skel) {
        free(mb->skel_pos); free(mb->skel_rad); free(mb->skel_tag); free(mb->skel_edge);
    }
    memset(mb, 0, sizeof *mb);
}

/* realloc that leaves *p untouched on failure; big arrays get huge pages. */
static int grow(void **p, size_t count, size_t elem) {
    void *q = big_realloc(*p, count * elem);
    if (!q) return 0;
    *p = q;
    return 1;
}

int mb_add_attr(mesh_builder *mb, const char *name) {
    if (mb->external) {
        for (uint32_t i = 0; i < mb->n_attr; i++)
            if (!strncmp(mb->attr_name[i], name, BANYAN_NAME_MAX)) return (int)i;
        if (!mb->status) mb->status = BANYAN_E_INTERNAL;
        return 0;
    }
    if (mb->n_attr >= MB_MAX_ATTRS || mb->nv > 0) {
        if (!mb->status) mb->status = BANYAN_E_INTERNAL;
        return 0;
    }
    int slot = (int)mb->n_attr++;
    strncpy(mb->attr_name[slot], name, BANYAN_NAME_MAX - 1);
    mb->attr_name[slot][BANYAN_NAME_MAX - 1] = '\0';
    mb->cur_attr[slot] = 0.0f;
    if (mb->cap_v && !grow((void **)&mb->attr[slot], mb->cap_v, sizeof(float))) mb->status = BANYAN_E_NOMEM;
    return slot;
}

void mb_set_color(mesh_builder *mb, const double rgba[4]) {
    for (int i = 0; i < 4; i++) mb->cur_color[i] = (float)rgba[i];
}

uint32_t mb_add_material(mesh_builder *mb, const char *name, const double rgba[4], double roughness,
                         int double_sided) {
    if (mb->status) return 0;
    if (!grow((void **)&mb->mat, mb->n_mat + 1, sizeof *mb->mat)) {
        mb->status = BANYAN_E_NOMEM;
        return 0;
    }
    banyan_material *m = &mb->mat[mb->n_mat];
    memset(m, 0, sizeof *m);
    strncpy(m->name, name, BANYAN_NAME_MAX - 1);
    for (int i = 0; i < 4; i++) m->base_color[i] = (float)rgba[i];
    m->roughness = (float)roughness;
    m->double_sided = double_sided ? 1 : 0;
    m->texture = BANYAN_TEX_NONE; /* generators set their texture after adding the material; image 0: none */
    return mb->n_mat++;
}

static void close_part(mesh_builder *mb) {
    if (!mb->n_part) return;
    banyan_part *p = &mb->part[mb->n_part - 1];
    p->vertex_count = mb->nv - p->vertex_offset;
    p->index_count = mb->ni - p->index_offset;
}

void mb_begin_part(mesh_builder *mb, uint32_t material, uint32_t group) {
    if (mb->status) return;
    close_part(mb);
    /* An empty previous part is reused rather than kept. */
    if (mb->n_part && mb->part[mb->n_part - 1].vertex_count == 0 && mb->part[mb->n_part - 1].index_count == 0)
        mb->n_part--;
    if (!grow((void **)&mb->part, mb->n_part + 1, sizeof *mb->part)) {
        mb->status = BANYAN_E_NOMEM;
        return;
    }
    banyan_part *p = &mb->part[mb->n_part++];
    memset(p, 0, sizeof *p);
    p->vertex_offset = mb->nv;
    p->index_offset = mb->ni;
    p->material = material;
    p->group = group;
}

/* Capacity for `need` when the builder must grow. The first reservation
 * is taken as exact (generators reserve their totals up front). Later
 * growth is fourfold, so a caller that cannot reserve its total copies
 * about a third of its output in reallocs instead of all of it (as with
 * doubling); the slack is never touched, so costs no pages, and
 * mb_finish trims it. */
static uint64_t grown(uint64_t cap, uint64_t need, uint64_t first, uint64_t limit) {
    if (!cap) cap = need > first ? need : first;
    while (cap < need) cap *= 4;
    return cap < limit ? cap : limit;
}

static int resize_vertices(mesh_builder *mb, size_t c) {
    if (!grow((void **)&mb->pos, c, 3 * sizeof(float)) || !grow((void **)&mb->nrm, c, 3 * sizeof(float)) ||
        !grow((void **)&mb->uv, c, 2 * sizeof(float)) ||
        (mb->with_color && !grow((void **)&mb->col, c, 4 * sizeof(float))))
        return 0;
    for (uint32_t i = 0; i < mb->n_attr; i++)
        if (!grow((void **)&mb->attr[i], c, sizeof(float))) return 0;
    mb->cap_v = (uint32_t)c;
    return 1;
}

/* On failure at the generous capacity, tries the exact need. */
static int grow_vertices(mesh_builder *mb, uint32_t need) {
    if (need <= mb->cap_v) return 1;
    if (mb->external) return 0;
    uint64_t cap = grown(mb->cap_v, need, 256, mb->max_vertices);
    return resize_vertices(mb, (size_t)cap) || (cap > need && resize_vertices(mb, need));
}

static int grow_indices(mesh_builder *mb, uint64_t need) {
    if (need <= mb->cap_i) return 1;
    if (mb->external) return 0;
    uint64_t cap = grown(mb->cap_i, need, 768, 0xFFFFFFF0u);
    if (!grow((void **)&mb->idx, (size_t)cap, sizeof(uint32_t)) &&
        (cap == need || !grow((void **)&mb->idx, (size_t)(cap = need), sizeof(uint32_t))))
        return 0;
    mb->cap_i = (uint32_t)cap;
    return 1;
}

banyan_status mb_reserve(mesh_builder *mb, uint32_t n_vertices, uint32_t n_indices) {
    if (mb->status) return mb->status;
    uint64_t need_v = (uint64_t)mb->nv + n_vertices, need_i = (uint64_t)mb->ni + n_indices;
    if (need_v > mb->max_vertices || need_i > 0xFFFFFFF0u) return mb->status = BANYAN_E_LIMIT;
    if (!grow_vertices(mb, (uint32_t)need_v) || !grow_indices(mb, need_i))
        return mb->status = mb->external ? BANYAN_E_INTERNAL : BANYAN_E_NOMEM;
    return BANYAN_OK;
}

uint32_t mb_vertex_grow(mesh_builder *mb, v3 p, v3 n, double u, double v) {
    if (mb->status || mb_reserve(mb, 1, 0)) return 0;
    return mb_vertex(mb, p, n, u, v);
}

void mb_tri_grow(mesh_builder *mb, uint32_t a, uint32_t b, uint32_t c) {
    if (mb->status || mb_reserve(mb, 0, 3)) return;
    mb_tri(mb, a, b, c);
}

uint32_t mb_vertices(mesh_builder *mb, uint32_t count) {
    if (mb->status || (mb->nv + (uint64_t)count > mb->cap_v && mb_reserve(mb, count, 0))) return UINT32_MAX;
    uint32_t first = mb->nv, end = first + count;
    if (mb->with_color) {
        float *C = mb->col + 4 * (size_t)first;
        for (uint32_t i = 0; i < count; i++, C += 4) memcpy(C, mb->cur_color, sizeof mb->cur_color);
    }
    for (uint32_t a = 0; a < mb->n_attr; a++) {
        float *A = mb->attr[a], v = mb->cur_attr[a];
        for (uint32_t i = first; i < end; i++) A[i] = v;
    }
    mb->nv = end;
    return first;
}

uint32_t *mb_indices(mesh_builder *mb, uint32_t count) {
    if (mb->status || (mb->ni + (uint64_t)count > mb->cap_i && mb_reserve(mb, 0, count))) return NULL;
    uint32_t *I = mb->idx + mb->ni;
    mb->ni += count;
    return I;
}

banyan_status mb_skel_reserve(mesh_builder *mb, uint32_t points, uint32_t edges) {
    if (mb->status) return mb->status;
    uint64_t need_p = (uint64_t)mb->n_skel + points, need_e = (uint64_t)mb->n_edge + edges;
    if (need_p > 0xFFFFFFF0u || need_e > 0xFFFFFFF0u) return mb->status = BANYAN_E_LIMIT;
    if ((need_p > mb->cap_skel || need_e > mb->cap_edge) && mb->external_skel) return mb->status = BANYAN_E_INTERNAL;
    if (need_p > mb->cap_skel) {
        size_t cap = (size_t)grown(mb->cap_skel, need_p, 256, 0xFFFFFFF0u);
        if (!grow((void **)&mb->skel_pos, cap, 3 * sizeof(float)) || !grow((void **)&mb->skel_rad, cap, sizeof(float)) ||
            !grow((void **)&mb->skel_tag, cap, sizeof(int32_t)))
            return mb->status = BANYAN_E_NOMEM;
        mb->cap_skel = (uint32_t)cap;
    }
    if (need_e > mb->cap_edge) {
        size_t cap = (size_t)grown(mb->cap_edge, need_e, 256, 0xFFFFFFF0u);
        if (!grow((void **)&mb->skel_edge, cap, 2 * sizeof(uint32_t))) return mb->status = BANYAN_E_NOMEM;
        mb->cap_edge = (uint32_t)cap;
    }
    return BANYAN_OK;
}

uint32_t mb_skel_point_grow(mesh_builder *mb, v3 p, double radius, int32_t tag) {
    if (mb->status || mb_skel_reserve(mb, 1, 0)) return 0;
    return mb_skel_point(mb, p, radius, tag);
}

void mb_skel_edge_grow(mesh_builder *mb, uint32_t a, uint32_t b) {
    if (mb->status || mb_skel_reserve(mb, 0, 1)) return;
    mb_skel_edge(mb, a, b);
}

void mb_close(mesh_builder *mb) {
    static const double white[4] = {0.8, 0.8, 0.8, 1.0};
    if (mb->n_mat == 0) mb_add_material(mb, "banyan", white, 0.8, 0);
    if (mb->n_part == 0) {
        /* One part over everything. */
        uint32_t nv = mb->nv, ni = mb->ni;
        mb->nv = mb->ni = 0;
        mb_begin_part(mb, 0, 0);
        mb->nv = nv;
        mb->ni = ni;
    }
    close_part(mb);
    if (mb->n_part > 1 && mb->part[mb->n_part - 1].vertex_count == 0) mb->n_part--;
}

banyan_status mb_fail(const mesh_builder *mb, banyan_error *err) {
    banyan_status s = mb->status;
    if (s == BANYAN_E_LIMIT)
        return banyan_fail(err, s, "max_vertices = %u would be exceeded; raise max_vertices or lower the detail",
                           mb->max_vertices);
    if (s == BANYAN_E_NOMEM) return banyan_fail(err, s, "out of memory while building the mesh");
    return banyan_fail(err, s, "internal error while building the mesh");
}

banyan_status mb_finish(mesh_builder *mb, banyan_mesh **out, banyan_error *err) {
    *out = NULL;
    if ((mb->external || mb->external_skel) && !mb->status) mb->status = BANYAN_E_INTERNAL; /* not ours to hand over */
    if (mb->status) {
        banyan_status s = mb_fail(mb, err);
        mb_free(mb);
        return s;
    }
    if (mb->nv == 0 || mb->ni == 0) {
        mb_free(mb);
        return banyan_fail(err, BANYAN_E_INTERNAL, "the generator produced an empty mesh");
    }
    mb_close(mb);
    /* Hand over no slack: shrinking in place costs no copy. */
    if (mb->cap_v > mb->nv) resize_vertices(mb, mb->nv);
    if (mb->cap_i > mb->ni && grow((void **)&mb->idx, mb->ni, sizeof(uint32_t))) mb->cap_i = mb->ni;
    banyan_mesh *m = calloc(1, sizeof *m);
    banyan_attribute *attrs = mb->n_attr ? calloc(mb->n_attr, sizeof *attrs) : NULL;
    if (!m || mb->status || (mb->n_attr && !attrs)) {
        free(m); free(attrs);
        mb_free(mb);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory while finishing the mesh");
    }
    m->vertex_count = mb->nv;
    m->index_count = mb->ni;
    m->positions = mb->pos; m->normals = mb->nrm; m->uvs = mb->uv; m->colors = mb->col; m->indices = mb->idx;
    m->attribute_count = mb->n_attr;
    m->attributes = attrs;
    for (uint32_t i = 0; i < mb->n_attr; i++) {
        memcpy(attrs[i].name, mb->attr_name[i], BANYAN_NAME_MAX);
        attrs[i].data = mb->attr[i];
    }
    m->material_count = mb->n_mat; m->materials = mb->mat;
    m->part_count = mb->n_part; m->parts = mb->part;
    m->skel_point_count = mb->n_skel;
    m->skel_points = mb->skel_pos; m->skel_radius = mb->skel_rad; m->skel_tag = mb->skel_tag;
    m->skel_edge_count = mb->n_edge; m->skel_edges = mb->skel_edge;
    memset(mb, 0, sizeof *mb); /* ownership moved */
    *out = m;
    banyan_error_clear(err);
    return BANYAN_OK;
}
