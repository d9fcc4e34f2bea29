/* fuzz_mesh.h - a small banyan_mesh from bytes, for the harnesses that
 * take a mesh in (fuzz_lod: banyan_mesh_lod, fuzz_gltf_write: the glTF
 * writer). Well formed by default, with bytes that make it hostile:
 *   flags   bit 0 normals, 1 uvs, 2 colours, 3 a wind_flutter attribute
 *           (its parts count as leaves), 4 a birth attribute, 5 positions
 *           as raw float bits (NaN, inf, huge), 6 indices as raw bytes
 *           (outside their part or the mesh), 7 an RGBA image that the
 *           first material names.
 *   nv      3 + b % 125 vertices;  parts 1 + b % 4;  triangles 1 + b % 96
 *   materials  1 + b % 3, each: texture b % 7 - 1 (-1 none .. 4, 5 bad),
 *           season b & 1, alpha cutoff b / 255
 *   per vertex  position (3 x int16 / 64 m, or 3 raw floats), then when
 *           present a normal (3 x int8), uv (2 x int8 / 32), colour
 *           (4 x u8), attribute values (u8 / 255)
 *   per triangle  3 index bytes (mod the part's vertices unless raw)
 *   per part  material byte, group byte (% 4)
 * Missing bytes read as 0. fz_mesh_free frees what fz_mesh_read made. */
#ifndef BANYAN_FUZZ_MESH_H
#define BANYAN_FUZZ_MESH_H

#include "fuzz_common.h"

typedef struct fz_mesh {
    banyan_mesh m;
    banyan_part parts[4];
    banyan_material mats[3];
    banyan_attribute attrs[2];
    banyan_image image;
} fz_mesh;

static inline float fz_f32(fz_reader *r) {
    float f;
    uint8_t b[4];
    fz_bytes(r, b, 4);
    memcpy(&f, b, 4);
    return f;
}

static inline void fz_mesh_read(fz_reader *r, fz_mesh *fm) {
    memset(fm, 0, sizeof *fm);
    banyan_mesh *m = &fm->m;
    uint8_t flags = fz_u8(r);
    uint32_t nv = 3 + fz_u8(r) % 125, np = 1 + fz_u8(r) % 4, nt = 1 + fz_u8(r) % 96, nm = 1 + fz_u8(r) % 3;
    if (np > nv) np = nv;
    m->vertex_count = nv;
    m->index_count = 3 * nt;
    m->positions = calloc(3 * (size_t)nv, sizeof(float));
    m->normals = flags & 1 ? calloc(3 * (size_t)nv, sizeof(float)) : NULL;
    m->uvs = flags & 2 ? calloc(2 * (size_t)nv, sizeof(float)) : NULL;
    m->colors = flags & 4 ? calloc(4 * (size_t)nv, sizeof(float)) : NULL;
    m->indices = calloc(3 * (size_t)nt, sizeof(uint32_t));
    static const char *const names[2] = {BANYAN_ATTR_WIND_FLUTTER, BANYAN_ATTR_BIRTH};
    for (int a = 0; a < 2; a++)
        if (flags & (8 << a)) {
            banyan_attribute *at = &fm->attrs[m->attribute_count++];
            snprintf(at->name, sizeof at->name, "%s", names[a]);
            at->data = calloc(nv, sizeof(float));
        }
    m->attributes = m->attribute_count ? fm->attrs : NULL;
    for (uint32_t k = 0; k < nm; k++) {
        banyan_material *mt = &fm->mats[k];
        snprintf(mt->name, sizeof mt->name, "fz_%u", k);
        mt->base_color[0] = 0.3f, mt->base_color[1] = 0.5f, mt->base_color[2] = 0.2f, mt->base_color[3] = 1.0f;
        mt->roughness = 0.8f;
        mt->texture = (int32_t)(fz_u8(r) % 7) - 1;
        mt->season = fz_u8(r) & 1;
        mt->alpha_cutoff = fz_u8(r) / 255.0f;
        mt->image = 0;
    }
    m->material_count = nm;
    m->materials = fm->mats;
    if (flags & 128) {
        fm->image.width = 1 + fz_u8(r) % 16;
        fm->image.height = 1 + fz_u8(r) % 16;
        fm->image.channels = 4;
        fm->image.pixels = calloc((size_t)fm->image.width * fm->image.height, 4);
        for (size_t i = 0; i < (size_t)fm->image.width * fm->image.height * 4; i += 7) fm->image.pixels[i] = fz_u8(r);
        m->image_count = 1;
        m->images = &fm->image;
        fm->mats[0].image = 1; /* images[0] */
    }
    for (uint32_t v = 0; v < nv; v++) {
        for (int j = 0; j < 3; j++)
            m->positions[3 * v + j] = flags & 32 ? fz_f32(r) : fz_i16(r) / 64.0f;
        if (m->normals) {
            float n[3] = {(int8_t)fz_u8(r), (int8_t)fz_u8(r), (int8_t)fz_u8(r)};
            float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int j = 0; j < 3; j++) m->normals[3 * v + j] = l > 0 ? n[j] / l : (j == 2);
        }
        if (m->uvs)
            for (int j = 0; j < 2; j++) m->uvs[2 * v + j] = (int8_t)fz_u8(r) / 32.0f;
        if (m->colors)
            for (int j = 0; j < 4; j++) m->colors[4 * v + j] = fz_u8(r) / 255.0f;
        for (uint32_t a = 0; a < m->attribute_count; a++) fm->attrs[a].data[v] = fz_u8(r) / 255.0f;
    }
    /* Parts: vertices and triangles split evenly, in order. */
    for (uint32_t p = 0; p < np; p++) {
        banyan_part *pt = &fm->parts[p];
        pt->vertex_offset = nv * p / np;
        pt->vertex_count = nv * (p + 1) / np - pt->vertex_offset;
        pt->index_offset = 3 * (nt * p / np);
        pt->index_count = 3 * (nt * (p + 1) / np) - pt->index_offset;
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k++) {
            uint8_t b = fz_u8(r);
            m->indices[k] = flags & 64 ? b : pt->vertex_offset + b % pt->vertex_count;
        }
    }
    for (uint32_t p = 0; p < np; p++) {
        fm->parts[p].material = fz_u8(r) % nm;
        fm->parts[p].group = fz_u8(r) % 4;
    }
    m->part_count = np;
    m->parts = fm->parts;
}

static inline void fz_mesh_free(fz_mesh *fm) {
    free(fm->m.positions);
    free(fm->m.normals);
    free(fm->m.uvs);
    free(fm->m.colors);
    free(fm->m.indices);
    for (int a = 0; a < 2; a++) free(fm->attrs[a].data);
    free(fm->image.pixels);
}

#endif
