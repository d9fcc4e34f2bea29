/*
 * gltf_write_check.cpp - the glTF writer's validation (gltf_write.h): every
 * mesh, node and option checked before anything is created on disk; each
 * error names the field, its value and its range.
 */
#include "gltf/gltf_write.h"
#include "base/error.h"
#include "base/finite.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace gltfw {

/* Strict UTF-8 check (no overlongs, no surrogates, <= U+10FFFF). The JSON
 * serialiser throws on invalid UTF-8, so names are checked up front. */
bool valid_utf8(const char *s, size_t n, size_t *bad_at) {
    const unsigned char *p = reinterpret_cast<const unsigned char *>(s);
    size_t i = 0;
    while (i < n) {
        unsigned c = p[i];
        size_t len;
        unsigned cp;
        if (c < 0x80) {
            ++i;
            continue;
        } else if (c >= 0xC2 && c <= 0xDF) {
            len = 2;
            cp = c & 0x1F;
        } else if (c >= 0xE0 && c <= 0xEF) {
            len = 3;
            cp = c & 0x0F;
        } else if (c >= 0xF0 && c <= 0xF4) {
            len = 4;
            cp = c & 0x07;
        } else {
            *bad_at = i;
            return false;
        }
        if (n - i < len) {
            *bad_at = i;
            return false;
        }
        for (size_t k = 1; k < len; ++k) {
            unsigned cc = p[i + k];
            if ((cc & 0xC0) != 0x80) {
                *bad_at = i;
                return false;
            }
            cp = (cp << 6) | (cc & 0x3F);
        }
        if ((len == 3 && (cp < 0x800 || (cp >= 0xD800 && cp <= 0xDFFF))) ||
            (len == 4 && (cp < 0x10000 || cp > 0x10FFFF))) {
            *bad_at = i;
            return false;
        }
        i += len;
    }
    return true;
}

/* Length of a fixed-size name field; cap when it has no NUL. */
size_t name_len(const char *s, size_t cap) {
    const void *z = std::memchr(s, '\0', cap);
    return z ? static_cast<size_t>(static_cast<const char *>(z) - s) : cap;
}

bool ends_with_ci(const char *s, const char *suffix) {
    size_t n = std::strlen(s), m = std::strlen(suffix);
    if (n < m) return false;
    for (size_t i = 0; i < m; ++i) {
        char a = s[n - m + i], b = suffix[i];
        if (a >= 'A' && a <= 'Z') a = static_cast<char>(a - 'A' + 'a');
        if (a != b) return false;
    }
    return true;
}

const char *component_name(uint32_t k) {
    static const char *const names[4] = {"x", "y", "z", "w"};
    return k < 4 ? names[k] : "?";
}

/* Checks that n * width floats are finite; names the first bad one. */
banyan_status check_finite(const float *a, uint32_t n, uint32_t width, const char *mesh,
                           const char *field, banyan_error *err) {
    const uint64_t total = static_cast<uint64_t>(n) * width;
    if (floats_finite(a, static_cast<size_t>(total))) return BANYAN_OK;
    for (uint64_t i = 0; i < total; ++i) {
        if (!std::isfinite(a[i])) {
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.%s[%llu] = %g is not finite (vertex %llu%s%s)", mesh,
                        field, static_cast<unsigned long long>(i),
                        static_cast<double>(a[i]),
                        static_cast<unsigned long long>(i / width),
                        width > 1 ? ", " : "",
                        width > 1 ? component_name(static_cast<uint32_t>(i % width)) : "");
        }
    }
    return BANYAN_OK;
}

/* The groups of a mesh's parts that have triangles, sorted: its variants
 * when it has instances. */
std::vector<uint32_t> drawn_groups(const banyan_mesh *m) {
    std::vector<uint32_t> g;
    for (uint32_t p = 0; p < m->part_count; ++p)
        if (m->parts[p].index_count > 0) g.push_back(m->parts[p].group);
    std::sort(g.begin(), g.end());
    g.erase(std::unique(g.begin(), g.end()), g.end());
    return g;
}

/* Custom attributes: "_" + upper-cased name must be a unique key. */
banyan_status check_attributes(const banyan_mesh *m, const char *mi, banyan_error *err) {
    const uint32_t vc = m->vertex_count;
    banyan_status s;
    if (m->attribute_count > 0 && m->attributes == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "%s.attributes is NULL but attribute_count = %u", mi,
                    m->attribute_count);
    for (uint32_t a = 0; a < m->attribute_count; ++a) {
        const banyan_attribute *at = &m->attributes[a];
        size_t n = name_len(at->name, BANYAN_NAME_MAX);
        if (n == BANYAN_NAME_MAX)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.attributes[%u].name is not NUL-terminated within %d bytes",
                        mi, a, BANYAN_NAME_MAX);
        if (n == 0)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.attributes[%u].name is empty",
                        mi, a);
        for (size_t k = 0; k < n; ++k) {
            char c = at->name[k];
            bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                      (c >= '0' && c <= '9') || c == '_';
            if (!ok)
                return banyan_fail(err, BANYAN_E_INVALID_ARG,
                            "%s.attributes[%u].name \"%.*s\" has a character "
                            "outside [A-Za-z0-9_] at byte %zu",
                            mi, a, static_cast<int>(n), at->name, k);
        }
        for (uint32_t b = 0; b < a; ++b) {
            const char *o = m->attributes[b].name;
            size_t k = 0;
            for (; k < n; ++k) {
                char x = at->name[k], y = o[k];
                if (x >= 'a' && x <= 'z') x = static_cast<char>(x - 'a' + 'A');
                if (y >= 'a' && y <= 'z') y = static_cast<char>(y - 'a' + 'A');
                if (x != y) break;
            }
            if (k == n && o[n] == '\0')
                return banyan_fail(err, BANYAN_E_INVALID_ARG,
                            "%s.attributes[%u].name \"%s\" repeats attributes[%u] "
                            "(glTF names are upper-cased)",
                            mi, a, at->name, b);
        }
        if (at->data == nullptr)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.attributes[%u] (\"%s\").data is NULL",
                        mi, a, at->name);
        std::string field = std::string("attributes[") + std::to_string(a) + "].data";
        if ((s = check_finite(at->data, vc, 1, mi, field.c_str(), err)) != BANYAN_OK) return s;
    }

    return BANYAN_OK;
}

banyan_status check_materials(const banyan_mesh *m, const char *mi, banyan_error *err) {
    if (m->material_count > 0 && m->materials == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "%s.materials is NULL but material_count = %u", mi,
                    m->material_count);
    for (uint32_t k = 0; k < m->material_count; ++k) {
        const banyan_material *mat = &m->materials[k];
        size_t n = name_len(mat->name, BANYAN_NAME_MAX);
        size_t bad = 0;
        if (n == BANYAN_NAME_MAX)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.materials[%u].name is not NUL-terminated within %d bytes",
                        mi, k, BANYAN_NAME_MAX);
        if (!valid_utf8(mat->name, n, &bad))
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.materials[%u].name is not valid UTF-8 (byte %zu)", mi, k,
                        bad);
        for (int c = 0; c < 4; ++c) {
            float v = mat->base_color[c];
            if (!(v >= 0.0f && v <= 1.0f))
                return banyan_fail(err, BANYAN_E_RANGE,
                            "%s.materials[%u].base_color[%d] = %g is outside [0, 1]",
                            mi, k, c, static_cast<double>(v));
        }
        if (!(mat->roughness >= 0.0f && mat->roughness <= 1.0f))
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.materials[%u].roughness = %g is outside [0, 1]", mi, k,
                        static_cast<double>(mat->roughness));
        if (mat->texture < BANYAN_TEX_NONE || mat->texture >= BANYAN_TEX_COUNT)
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.materials[%u].texture = %d is outside [%d, %d] (banyan_texture_kind)",
                        mi, k, mat->texture, BANYAN_TEX_NONE, BANYAN_TEX_COUNT - 1);
        if (mat->season != BANYAN_SEASON_SUMMER && mat->season != BANYAN_SEASON_AUTUMN)
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.materials[%u].season = %d is outside [0, 1] (summer, autumn)", mi, k,
                        mat->season);
        if (!(mat->alpha_cutoff >= 0.0f && mat->alpha_cutoff <= 1.0f))
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.materials[%u].alpha_cutoff = %g is outside [0, 1]", mi, k,
                        static_cast<double>(mat->alpha_cutoff));
        if (!(mat->translucency >= 0.0f && mat->translucency <= 1.0f))
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.materials[%u].translucency = %g is outside [0, 1]", mi, k,
                        static_cast<double>(mat->translucency));
        /* image k is images[k - 1]; 0 (a zeroed material) names none. */
        if (mat->image < 0 || mat->image > static_cast<int64_t>(m->image_count))
            return banyan_fail(err, BANYAN_E_RANGE, "%s.materials[%u].image = %d is outside [0, %u] (image_count = %u)",
                               mi, k, mat->image, m->image_count, m->image_count);
        if (mat->image > 0 && m->uvs == nullptr)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.materials[%u].image = %d needs uvs, and %s.uvs is NULL",
                               mi, k, mat->image, mi);
    }

    return BANYAN_OK;
}

/* Images (banyan_material.image): what banyan_image_png accepts; then the parts. */
banyan_status check_images_parts(const banyan_mesh *m, const char *mi, banyan_error *err) {
    const uint32_t vc = m->vertex_count;
    if (m->image_count > 0 && m->images == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.images is NULL but image_count = %u", mi, m->image_count);
    for (uint32_t k = 0; k < m->image_count; ++k) {
        const banyan_image *im = &m->images[k];
        if (im->pixels == nullptr)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.images[%u].pixels is NULL", mi, k);
        if (im->channels != 3 && im->channels != 4)
            return banyan_fail(err, BANYAN_E_RANGE, "%s.images[%u].channels = %u must be 3 (RGB) or 4 (RGBA)", mi, k,
                               im->channels);
        if (im->width < 1 || im->width > 16384 || im->height < 1 || im->height > 16384)
            return banyan_fail(err, BANYAN_E_RANGE, "%s.images[%u] is %u x %u pixels; each side must be within [1, 16384]",
                               mi, k, im->width, im->height);
    }

    /* Parts. */
    if (m->part_count > 0 && m->parts == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.parts is NULL but part_count = %u",
                    mi, m->part_count);
    bool any_triangles = m->part_count == 0;
    for (uint32_t p = 0; p < m->part_count; ++p) {
        const banyan_part *pt = &m->parts[p];
        if (static_cast<uint64_t>(pt->vertex_offset) + pt->vertex_count > vc)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.parts[%u] vertices [%u, +%u) pass vertex_count = %u", mi, p,
                        pt->vertex_offset, pt->vertex_count, vc);
        if (static_cast<uint64_t>(pt->index_offset) + pt->index_count > m->index_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.parts[%u] indices [%u, +%u) pass index_count = %u", mi, p,
                        pt->index_offset, pt->index_count, m->index_count);
        if (pt->index_count % 3 != 0)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.parts[%u].index_count = %u is not a multiple of 3", mi, p,
                        pt->index_count);
        if (m->material_count > 0 && pt->material >= m->material_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "%s.parts[%u].material = %u is out of range [0, %u]", mi, p,
                        pt->material, m->material_count - 1);
        if (pt->index_count > 0) any_triangles = true;
    }
    if (!any_triangles)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "%s has %u parts and none has a triangle", mi, m->part_count);

    return BANYAN_OK;
}

/* Instances: each names a group that has triangles (a variant). */
banyan_status check_instances(const banyan_mesh *m, const char *mi, banyan_error *err) {
    if (m->instance_count > 0 && m->instances == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.instances is NULL but instance_count = %u", mi,
                           m->instance_count);
    if (m->instance_count > 0 && m->part_count == 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                           "%s has %u instances but no parts: variants are the parts' groups", mi, m->instance_count);
    std::vector<uint32_t> drawn = drawn_groups(m);
    for (uint32_t k = 0; k < m->instance_count; ++k) {
        const banyan_instance *in = &m->instances[k];
        if (!std::binary_search(drawn.begin(), drawn.end(), in->variant))
            return banyan_fail(err, BANYAN_E_RANGE,
                               "%s.instances[%u].variant = %u names no group with triangles (groups 0 .. %u)", mi, k,
                               in->variant, drawn.empty() ? 0u : drawn.back());
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(in->translation[c]) || std::fabs(in->translation[c]) > 1e7f)
                return banyan_fail(err, BANYAN_E_RANGE,
                                   "%s.instances[%u].translation[%d] = %g must be finite, within [-1e7, 1e7] m", mi, k,
                                   c, static_cast<double>(in->translation[c]));
        if (!std::isfinite(in->rotation_z))
            return banyan_fail(err, BANYAN_E_RANGE, "%s.instances[%u].rotation_z = %g must be finite (radians)", mi, k,
                               static_cast<double>(in->rotation_z));
        if (!(in->scale > 0.0f) || !std::isfinite(in->scale))
            return banyan_fail(err, BANYAN_E_RANGE, "%s.instances[%u].scale = %g must be finite and > 0", mi, k,
                               static_cast<double>(in->scale));
    }
    return BANYAN_OK;
}

banyan_status check_mesh(const banyan_mesh *m, const char *mi, banyan_error *err) {
    if (m == nullptr) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s is NULL", mi);
    if (m->vertex_count == 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "%s.vertex_count is 0; a mesh needs at least one vertex", mi);
    if (m->index_count == 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "%s.index_count is 0; a mesh needs at least one triangle", mi);
    if (m->index_count % 3 != 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "%s.index_count = %u is not a multiple of 3", mi, m->index_count);
    if (m->positions == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.positions is NULL", mi);
    if (m->indices == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.indices is NULL", mi);

    const uint32_t vc = m->vertex_count;
    uint32_t top = 0; /* the largest index, a reduction the compiler vectorises */
    for (uint32_t i = 0; i < m->index_count; ++i) top = std::max(top, m->indices[i]);
    for (uint32_t i = 0; top >= vc && i < m->index_count; ++i) {
        if (m->indices[i] >= vc)
            return banyan_fail(err, BANYAN_E_RANGE,
                        "%s.indices[%u] = %u is out of range [0, %u]", mi, i,
                        m->indices[i], vc - 1);
    }

    banyan_status s;
    if ((s = check_finite(m->positions, vc, 3, mi, "positions", err)) != BANYAN_OK) return s;
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(m->origin[k]) || std::fabs(m->origin[k]) > 1e7)
            return banyan_fail(err, BANYAN_E_RANGE, "%s.origin[%d] = %g must be finite, within [-1e7, 1e7] m", mi,
                               k, m->origin[k]);
    if (m->normals && (s = check_finite(m->normals, vc, 3, mi, "normals", err)) != BANYAN_OK)
        return s;
    if (m->uvs && (s = check_finite(m->uvs, vc, 2, mi, "uvs", err)) != BANYAN_OK) return s;
    if (m->colors && (s = check_finite(m->colors, vc, 4, mi, "colors", err)) != BANYAN_OK)
        return s;

    if ((s = check_attributes(m, mi, err)) != BANYAN_OK) return s;
    if ((s = check_materials(m, mi, err)) != BANYAN_OK) return s;
    if ((s = check_images_parts(m, mi, err)) != BANYAN_OK) return s;
    return check_instances(m, mi, err);
}

bool image_dir_ok(const char *d);

banyan_status check_options(const banyan_gltf_options &o, banyan_error *err) {
    if (o.textures != 0 && o.textures != 1)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->textures = %d must be 0 (off) or 1 (on)", o.textures);
    const int32_t n = o.texture_size;
    if (n < 64 || n > 8192 || (n & (n - 1)) != 0)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "opt->texture_size = %d must be a power of two in [64, 8192]", n);
    if (o.engine_uvs != 0 && o.engine_uvs != 1)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->engine_uvs = %d must be 0 (off) or 1 (on)", o.engine_uvs);
    if (o.pivot_painter != 0 && o.pivot_painter != 1)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->pivot_painter = %d must be 0 (off) or 1 (on)", o.pivot_painter);
    if (o.texture_cache != 0 && o.texture_cache != 1)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->texture_cache = %d must be 0 (off) or 1 (on)", o.texture_cache);
    if (o.sync != 0 && o.sync != 1)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->sync = %d must be 0 (no fsync) or 1 (fsync before the rename)",
                           o.sync);
    if (o.compact != 0 && o.compact != 1)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->compact = %d must be 0 (plain) or 1 (compact)", o.compact);
    if (o.image_dir != nullptr && o.image_dir[0] != '\0' && !image_dir_ok(o.image_dir))
        return banyan_fail(err, BANYAN_E_RANGE,
                           "opt->image_dir = '%.200s' must be a relative folder of at most 1024 characters, "
                           "'/'-separated parts of letters, digits, '.', '_' and '-', none empty, '.' or '..'",
                           o.image_dir);
    return BANYAN_OK;
}

/* opt->image_dir's folder parts, each a name a URI carries as it is. */
bool image_dir_ok(const char *d) {
    const size_t n = std::strlen(d);
    if (n == 0 || n > 1024) return false;
    size_t part = 0;
    for (size_t i = 0; i <= n; ++i) {
        const char c = d[i];
        if (c == '/' || c == '\0') {
            if (part == 0) return false; /* empty: a leading '/', "//" or a trailing '/' */
            const char *p = d + i - part;
            if ((part == 1 && p[0] == '.') || (part == 2 && p[0] == '.' && p[1] == '.')) return false;
            part = 0;
            continue;
        }
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                        c == '_' || c == '-';
        if (!ok) return false;
        ++part;
    }
    return true;
}

banyan_status check_node(const banyan_gltf_node &n, uint32_t i, bool ex, banyan_error *err) {
    std::string label = ex ? "meshes[" + std::to_string(i) + "]" : "nodes[" + std::to_string(i) + "].mesh";
    banyan_status s = check_mesh(n.mesh, label.c_str(), err);
    if (s != BANYAN_OK) return s;
    if (n.name) {
        size_t bad = 0;
        if (!valid_utf8(n.name, std::strlen(n.name), &bad))
            return banyan_fail(err, BANYAN_E_INVALID_ARG, ex ? "names[%u] is not valid UTF-8 (byte %zu)"
                                                             : "nodes[%u].name is not valid UTF-8 (byte %zu)",
                               i, bad);
    }
    if (n.lod_count > kMaxLods)
        return banyan_fail(err, BANYAN_E_RANGE, "nodes[%u].lod_count = %u is outside [0, %u]", i, n.lod_count, kMaxLods);
    if (n.lod_count > 0 && n.lods == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "nodes[%u].lods is NULL but lod_count = %u", i, n.lod_count);
    for (uint32_t k = 0; k < n.lod_count; ++k) {
        label = "nodes[" + std::to_string(i) + "].lods[" + std::to_string(k) + "]";
        if ((s = check_mesh(n.lods[k], label.c_str(), err)) != BANYAN_OK) return s;
    }
    if (n.lod_coverage && n.lod_count > 0) {
        for (uint32_t k = 0; k <= n.lod_count; ++k) {
            double c = n.lod_coverage[k];
            if (!(c > 0.0 && c <= 1.0))
                return banyan_fail(err, BANYAN_E_RANGE, "nodes[%u].lod_coverage[%u] = %g is outside (0, 1]", i, k, c);
            if (k > 0 && !(c < n.lod_coverage[k - 1]))
                return banyan_fail(err, BANYAN_E_RANGE,
                                   "nodes[%u].lod_coverage[%u] = %g must be less than lod_coverage[%u] = %g (coarser "
                                   "levels show at smaller coverages)",
                                   i, k, c, k - 1, n.lod_coverage[k - 1]);
        }
    }
    return BANYAN_OK;
}

} // namespace gltfw
