/*
 * gltf_write_plan.cpp - the glTF buffer's layout (gltf_write.h): each mesh's
 * primitives, its vertex accessors and the segments their bytes are
 * streamed from later.
 */
#include "gltf/gltf_write.h"

#include <algorithm>
#include <cstring>

namespace gltfw {

/* The double with the fewest decimal digits that rounds to f, so material
 * factors read 0.35 in the JSON rather than 0.3499999940395355. */
double short_double(float f) {
    char buf[32];
    for (int prec = 6; prec <= 9; ++prec) {
        std::snprintf(buf, sizeof buf, "%.*g", prec, static_cast<double>(f));
        double d = std::strtod(buf, nullptr);
        if (static_cast<float>(d) == f) return d;
    }
    return static_cast<double>(f);
}

std::string upper_attribute_key(const char *name) {
    std::string key = "_";
    for (const char *c = name; *c; ++c) {
        char x = *c;
        if (x >= 'a' && x <= 'z') x = static_cast<char>(x - 'a' + 'A');
        key += x;
    }
    return key;
}

/* True when every vertex colour equals the base colour of the material
 * drawing it. glTF shows baseColorFactor x COLOR_0, so writing both would
 * square the colour; such colours are left out. (The roots' vertex colours
 * are a multiplier, the soil line, white above it: they are written.) */
bool colors_repeat_material(const banyan_mesh *m) {
    if (!m->colors || m->material_count == 0) return false;
    auto same = [&](uint32_t v, uint32_t mat) {
        if (mat >= m->material_count || v >= m->vertex_count) return false;
        return std::memcmp(m->colors + 4 * static_cast<size_t>(v), m->materials[mat].base_color,
                           4 * sizeof(float)) == 0;
    };
    if (m->part_count == 0) {
        for (uint32_t v = 0; v < m->vertex_count; ++v)
            if (!same(v, 0)) return false;
        return true;
    }
    for (uint32_t p = 0; p < m->part_count; ++p) {
        const banyan_part *pt = &m->parts[p];
        for (uint32_t i = 0; i < pt->index_count; ++i)
            if (!same(m->indices[pt->index_offset + i], pt->material)) return false;
    }
    return true;
}

Layout layout_of(const banyan_mesh *m, bool engine_uvs) {
    Layout L;
    int found = 0;
    for (int k = 0; k < 7; ++k)
        if ((L.wind[k] = banyan_mesh_attribute(m, kWindNames[k])) != nullptr) found++;
    L.birth = banyan_mesh_attribute(m, BANYAN_ATTR_BIRTH);
    L.pivot = L.wind[0] && L.wind[1] && L.wind[2];
    L.engine_uvs = found == 7 && engine_uvs;
    return L;
}

bool is_wind_attribute(const Layout &L, const banyan_attribute *at) {
    if (!L.pivot) return false;
    for (int k = 0; k < 3; ++k)
        if (at->data == L.wind[k] && std::strcmp(at->name, kWindNames[k]) == 0) return true;
    return false;
}

/* The vertex accessors for vertices [base, base + count) of mesh m, as
 * planned views; tangent (or NULL) is the kTangent segment of the range
 * (its vertex range is filled in here). */
std::map<std::string, int> add_vertex_range(Builder &b, const banyan_mesh *m, const Layout &L, uint32_t base,
                                            uint32_t count, bool with_colors, const Segment *tangent) {
    std::map<std::string, int> attrs;
    const int AB = TINYGLTF_TARGET_ARRAY_BUFFER;
    const int F = TINYGLTF_COMPONENT_TYPE_FLOAT;
    auto seg = [&](SegKind kind, uint32_t floats_per_vertex) {
        Segment sg{kind};
        sg.m = m;
        sg.L = &L;
        sg.base = base;
        sg.count = count;
        sg.bytes = static_cast<uint64_t>(count) * floats_per_vertex * sizeof(float);
        return sg;
    };

    /* POSITION: (x, y, z) -> (x, z, -y), with min / max of what is stored
     * (the bytes are written later; the JSON needs these first). */
    std::vector<double> mn(3, 0.0), mx(3, 0.0);
    for (uint32_t i = 0; i < count; ++i) {
        const float *p = m->positions + 3 * static_cast<size_t>(base + i);
        float q[3] = {p[0], p[2], -p[1]};
        for (int k = 0; k < 3; ++k) {
            double d = static_cast<double>(q[k]);
            if (i == 0 || d < mn[k]) mn[k] = d;
            if (i == 0 || d > mx[k]) mx[k] = d;
        }
    }
    int v = b.add_view(seg(kPosition, 3), AB);
    attrs["POSITION"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC3, count, &mn, &mx);

    if (m->normals) {
        v = b.add_view(seg(kNormal, 3), AB);
        attrs["NORMAL"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC3, count);
    }

    if (m->uvs) {
        v = b.add_view(seg(kUv, 2), AB);
        attrs["TEXCOORD_0"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC2, count);
    } else if (L.engine_uvs || L.pp2) { /* TEXCOORD_n must count up from 0 */
        v = b.add_view(seg(kZero, 2), AB);
        attrs["TEXCOORD_0"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC2, count);
    }

    if (tangent) {
        Segment sg = *tangent;
        sg.m = m;
        sg.base = base;
        sg.count = count;
        sg.bytes = static_cast<uint64_t>(count) * 4 * sizeof(float);
        v = b.add_view(sg, AB);
        attrs["TANGENT"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC4, count);
    }

    if (m->colors && with_colors) { /* 4 bytes a vertex: r, g, b, a as 0..255 */
        Segment sg = seg(kColor, 1);
        v = b.add_view(sg, AB);
        attrs["COLOR_0"] = b.add_accessor(v, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, count,
                                          nullptr, nullptr, true);
    }

    for (uint32_t a = 0; a < m->attribute_count; ++a) {
        const banyan_attribute *at = &m->attributes[a];
        if (is_wind_attribute(L, at)) continue;
        Segment sg = seg(kRaw, 1);
        sg.src = at->data + base;
        v = b.add_view(sg, AB);
        attrs[upper_attribute_key(at->name)] =
            b.add_accessor(v, F, TINYGLTF_TYPE_SCALAR, count);
    }

    if (L.pivot) {
        for (uint32_t axis = 0; axis < 3; ++axis) {
            Segment sg = seg(kWindPivot, 1);
            sg.aux = axis;
            v = b.add_view(sg, AB);
            attrs[upper_attribute_key(kWindNames[axis])] = b.add_accessor(v, F, TINYGLTF_TYPE_SCALAR, count);
        }
    }

    if (L.engine_uvs) {
        for (uint32_t set = 1; set <= 4; ++set) {
            Segment sg = seg(kEngineUv, 2);
            sg.aux = set;
            v = b.add_view(sg, AB);
            attrs["TEXCOORD_" + std::to_string(set)] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC2, count);
        }
    }

    if (L.pp2) { /* Pivot Painter 2: the vertex's texel centre, after every other set */
        v = b.add_view(seg(kPivotPainterUv, 2), AB);
        attrs["TEXCOORD_" + std::to_string(L.engine_uvs ? 5 : 1)] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC2, count);
    }
    return attrs;
}

uint64_t vertex_range_bytes(const banyan_mesh *m, const Layout &L, uint64_t count, bool with_colors, bool tangents) {
    /* in 4-byte words: a colour is 4 bytes */
    uint64_t floats = 3 + (m->normals ? 3 : 0) + (m->uvs || L.engine_uvs || L.pp2 ? 2 : 0) +
                      (m->colors && with_colors ? 1 : 0) + (tangents ? 4 : 0) + m->attribute_count +
                      (L.engine_uvs ? 8 : 0) + (L.pp2 ? 2 : 0);
    return floats * 4 * count;
}

/* A mesh's primitives; `local` tells whether each part keeps to its own
 * vertices. */
void plan_prims(const banyan_mesh *m, int material_base, std::vector<Prim> &prims, bool &local) {
    prims.clear();
    local = m->part_count > 0;
    for (uint32_t p = 0; p < m->part_count && local; ++p) {
        const banyan_part *pt = &m->parts[p];
        for (uint32_t i = 0; i < pt->index_count; ++i) {
            uint32_t ix = m->indices[pt->index_offset + i];
            if (ix < pt->vertex_offset || ix - pt->vertex_offset >= pt->vertex_count) {
                local = false;
                break;
            }
        }
    }
    if (m->part_count == 0) {
        prims.push_back(Prim{0, m->index_count, 0, m->vertex_count,
                             m->material_count > 0 ? material_base : -1, 0});
    }
    for (uint32_t p = 0; p < m->part_count; ++p) {
        const banyan_part *pt = &m->parts[p];
        if (pt->index_count == 0) continue;
        Prim pr;
        pr.ioff = pt->index_offset;
        pr.icount = pt->index_count;
        pr.vbase = local ? pt->vertex_offset : 0;
        pr.vcount = local ? pt->vertex_count : m->vertex_count;
        pr.material = m->material_count > 0 ? material_base + static_cast<int>(pt->material) : -1;
        pr.group = pt->group;
        prims.push_back(pr);
    }
}

/* Plans a mesh's primitives (plan_prims). Returns the bytes the mesh adds
 * to the buffer. */
uint64_t plan_mesh(const banyan_mesh *m, const Layout &L, int material_base, bool tangents, std::vector<Prim> &prims,
                   bool &local) {
    plan_prims(m, material_base, prims, local);
    uint64_t bytes = 0;
    bool colors = !colors_repeat_material(m);
    for (const Prim &pr : prims) {
        bytes += 4ull * pr.icount;
        if (local) bytes += vertex_range_bytes(m, L, pr.vcount, colors, tangents);
    }
    if (!local) bytes += vertex_range_bytes(m, L, m->vertex_count, colors, tangents);
    return bytes;
}

/* Whether each primitive's tangents, computed from its own triangles
 * alone, are the whole mesh's: parts keep to their vertices, no two
 * primitives share a vertex or a triangle, and every triangle is in one.
 * Then only one part's tangents are held at a time. */
bool tangent_ranges_exact(const banyan_mesh *m, const std::vector<Prim> &prims, bool local) {
    if (!local) return false;
    std::vector<std::pair<uint32_t, uint32_t>> v, ix;
    uint64_t covered = 0;
    for (const Prim &pr : prims) {
        v.emplace_back(pr.vbase, pr.vcount);
        ix.emplace_back(pr.ioff, pr.icount);
        covered += pr.icount;
    }
    if (covered != m->index_count) return false;
    for (auto *r : {&v, &ix}) {
        std::sort(r->begin(), r->end());
        for (size_t k = 1; k < r->size(); ++k)
            if (static_cast<uint64_t>((*r)[k - 1].first) + (*r)[k - 1].second > (*r)[k].first) return false;
    }
    return true;
}

} // namespace gltfw
