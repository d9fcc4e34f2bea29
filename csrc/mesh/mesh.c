/* banyan_mesh ownership, lookup and hashing; ABI and layout queries. */
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/error.h"

void banyan_mesh_free(banyan_mesh *m) {
    if (!m) return;
    free(m->positions); free(m->normals); free(m->uvs); free(m->colors); free(m->indices);
    if (m->attributes)
        for (uint32_t i = 0; i < m->attribute_count; i++) free(m->attributes[i].data);
    free(m->attributes);
    free(m->materials); free(m->parts);
    free(m->skel_points); free(m->skel_radius); free(m->skel_tag); free(m->skel_edges);
    if (m->images)
        for (uint32_t i = 0; i < m->image_count; i++) free(m->images[i].pixels);
    free(m->images);
    free(m->instances);
    free(m);
}

const float *banyan_mesh_attribute(const banyan_mesh *m, const char *name) {
    if (!m || !name) return NULL;
    for (uint32_t i = 0; i < m->attribute_count; i++)
        if (strncmp(m->attributes[i].name, name, BANYAN_NAME_MAX) == 0) return m->attributes[i].data;
    return NULL;
}

banyan_status banyan_mesh_corner_uvs(const banyan_mesh *m, float *out, uint64_t out_count, banyan_error *err) {
    if (!m || !out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh and out must not be NULL");
    if (!m->uvs || !m->indices) return banyan_fail(err, BANYAN_E_INVALID_ARG, "the mesh has no uvs or indices");
    if (out_count < 2 * (uint64_t)m->index_count)
        return banyan_fail(err, BANYAN_E_RANGE, "out_count = %llu must be at least 2 * index_count = %llu",
                           (unsigned long long)out_count, 2ULL * m->index_count);
    for (uint32_t k = 0; k < m->index_count; k++) {
        uint32_t v = m->indices[k];
        if (v >= m->vertex_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "indices[%u] = %u is out of range [0, %u)", k, v,
                               m->vertex_count);
        out[2 * (size_t)k] = m->uvs[2 * (size_t)v];
        out[2 * (size_t)k + 1] = m->uvs[2 * (size_t)v + 1];
    }
    banyan_error_clear(err);
    return BANYAN_OK;
}

banyan_status banyan_group_localize(float *positions, uint32_t vertex_count, uint32_t *indices, uint64_t index_count,
                                    uint32_t first_vertex, double origin_out[3], banyan_error *err) {
    if (!origin_out || (!positions && vertex_count) || (!indices && index_count))
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "positions, indices and origin_out must not be NULL");
    if ((uint64_t)first_vertex + vertex_count > UINT32_MAX)
        return banyan_fail(err, BANYAN_E_RANGE, "first_vertex + vertex_count = %llu must be at most %u",
                           (unsigned long long)first_vertex + vertex_count, UINT32_MAX);
    for (uint64_t k = 0; k < index_count; k++)
        if (indices[k] - first_vertex >= vertex_count) /* unsigned: below first_vertex wraps high */
            return banyan_fail(err, BANYAN_E_RANGE, "indices[%llu] = %u is outside the group's vertices [%u, %u)",
                               (unsigned long long)k, indices[k], first_vertex, first_vertex + vertex_count);
    for (uint64_t k = 0; k < index_count; k++) indices[k] -= first_vertex;
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (uint32_t i = 0; i < vertex_count; i++)
        for (int c = 0; c < 3; c++) {
            float x = positions[3 * (size_t)i + c];
            if (i == 0 || x < lo[c]) lo[c] = x;
            if (i == 0 || x > hi[c]) hi[c] = x;
        }
    float o[3] = {0.5f * (lo[0] + hi[0]), 0.5f * (lo[1] + hi[1]), lo[2]};
    for (uint32_t i = 0; i < vertex_count; i++)
        for (int c = 0; c < 3; c++) positions[3 * (size_t)i + c] -= o[c];
    for (int c = 0; c < 3; c++) origin_out[c] = o[c];
    banyan_error_clear(err);
    return BANYAN_OK;
}

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= 1099511628211ULL;
    }
    return h;
}

uint64_t banyan_mesh_hash(const banyan_mesh *m) {
    uint64_t h = 14695981039346656037ULL;
    if (!m) return h;
    size_t nv = m->vertex_count;
    h = fnv(h, &m->vertex_count, sizeof m->vertex_count);
    h = fnv(h, &m->index_count, sizeof m->index_count);
    if (m->positions) h = fnv(h, m->positions, 3 * nv * sizeof(float));
    if (m->normals) h = fnv(h, m->normals, 3 * nv * sizeof(float));
    if (m->uvs) h = fnv(h, m->uvs, 2 * nv * sizeof(float));
    if (m->colors) h = fnv(h, m->colors, 4 * nv * sizeof(float));
    if (m->indices) h = fnv(h, m->indices, m->index_count * sizeof(uint32_t));
    for (uint32_t i = 0; m->attributes && i < m->attribute_count; i++) {
        h = fnv(h, m->attributes[i].name, BANYAN_NAME_MAX);
        if (m->attributes[i].data) h = fnv(h, m->attributes[i].data, nv * sizeof(float));
    }
    if (m->materials) h = fnv(h, m->materials, m->material_count * sizeof(banyan_material));
    if (m->parts) h = fnv(h, m->parts, m->part_count * sizeof(banyan_part));
    size_t ns = m->skel_point_count;
    if (m->skel_points) h = fnv(h, m->skel_points, 3 * ns * sizeof(float));
    if (m->skel_radius) h = fnv(h, m->skel_radius, ns * sizeof(float));
    if (m->skel_tag) h = fnv(h, m->skel_tag, ns * sizeof(int32_t));
    if (m->skel_edges) h = fnv(h, m->skel_edges, 2 * (size_t)m->skel_edge_count * sizeof(uint32_t));
    /* Only when set: meshes near the world origin keep the hashes they had. */
    if (m->origin[0] != 0 || m->origin[1] != 0 || m->origin[2] != 0) h = fnv(h, m->origin, sizeof m->origin);
    for (uint32_t i = 0; m->images && i < m->image_count; i++) {
        const banyan_image *im = &m->images[i];
        h = fnv(h, im, 3 * sizeof(uint32_t));
        if (im->pixels) h = fnv(h, im->pixels, (size_t)im->width * im->height * im->channels);
    }
    if (m->instances) h = fnv(h, m->instances, m->instance_count * sizeof(banyan_instance));
    return h;
}

int32_t banyan_abi_version(void) { return BANYAN_ABI_VERSION; }
const char *banyan_version_string(void) { return BANYAN_VERSION_STRING; }
size_t banyan_sizeof_error(void) { return sizeof(banyan_error); }
size_t banyan_sizeof_box(void) { return sizeof(banyan_box); }
size_t banyan_sizeof_attribute(void) { return sizeof(banyan_attribute); }
size_t banyan_sizeof_material(void) { return sizeof(banyan_material); }
size_t banyan_sizeof_part(void) { return sizeof(banyan_part); }
size_t banyan_sizeof_mesh(void) { return sizeof(banyan_mesh); }
size_t banyan_sizeof_param_info(void) { return sizeof(banyan_param_info); }
size_t banyan_sizeof_instance(void) { return sizeof(banyan_instance); }
