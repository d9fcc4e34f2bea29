/*
 * gltf_writer.cpp - banyan_gltf_write(): banyan meshes to one glTF 2.0 asset.
 *
 * The only C++ file of libbanyan. It is built on Debian's shared tinygltf
 * 2.7 (include <tiny_gltf.h> without TINYGLTF_IMPLEMENTATION) and exposes
 * nothing but the extern "C" function declared in banyan.h; compile it with
 * -fvisibility=hidden and C++14 or later (tinygltf's class layout depends on
 * TINYGLTF_USE_CPP14, which the Debian library was built with).
 *
 * What is written (see docs/gltf.md):
 *   - one buffer; one node + one mesh per input mesh, all in scene 0;
 *   - one primitive per non-empty banyan_part. When every part's indices
 *     stay inside the part's own vertex range (the normal case: parts never
 *     share vertices), each primitive gets its own vertex accessors over
 *     that range and indices rebased to it. Otherwise the mesh's primitives
 *     share accessors over all its vertices and keep absolute indices;
 *   - POSITION (min/max), NORMAL (renormalised; zero -> +Y), TEXCOORD_0
 *     (u, 1 - v), COLOR_0 (float VEC4, when colors != NULL), "_NAME" float
 *     scalars for custom attributes, UNSIGNED_INT indices;
 *   - Z-up to Y-up: (x, y, z) -> (x, z, -y) for positions and normals;
 *   - one metallic-roughness material per banyan_material.
 * The skeleton is not exported.
 *
 * Nothing is created on disk until every input has been checked. A write
 * that fails part-way removes the file. No exception leaves this file.
 */
#include "banyan.h"
#include "core/error.h"

#include <tiny_gltf.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && \
    __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "gltf_writer.cpp copies floats as they are in memory: glTF is little-endian"
#endif

namespace {

/* glTF buffers are addressed with 32-bit lengths in GLB; keep some room for
 * the JSON chunk as well. */
const uint64_t kMaxBufferBytes = UINT64_C(0xFFFFFFFF) - (UINT64_C(64) << 20);

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
banyan_status check_finite(const float *a, uint32_t n, uint32_t width, uint32_t mesh,
                           const char *field, banyan_error *err) {
    const uint64_t total = static_cast<uint64_t>(n) * width;
    for (uint64_t i = 0; i < total; ++i) {
        if (!std::isfinite(a[i])) {
            return banyan_fail(err, BANYAN_E_RANGE,
                        "meshes[%u].%s[%llu] = %g is not finite (vertex %llu%s%s)", mesh,
                        field, static_cast<unsigned long long>(i),
                        static_cast<double>(a[i]),
                        static_cast<unsigned long long>(i / width),
                        width > 1 ? ", " : "",
                        width > 1 ? component_name(static_cast<uint32_t>(i % width)) : "");
        }
    }
    return BANYAN_OK;
}

banyan_status check_mesh(const banyan_mesh *m, uint32_t mi, banyan_error *err) {
    if (m == nullptr) return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes[%u] is NULL", mi);
    if (m->vertex_count == 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "meshes[%u].vertex_count is 0; a mesh needs at least one vertex", mi);
    if (m->index_count == 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "meshes[%u].index_count is 0; a mesh needs at least one triangle", mi);
    if (m->index_count % 3 != 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "meshes[%u].index_count = %u is not a multiple of 3", mi, m->index_count);
    if (m->positions == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes[%u].positions is NULL", mi);
    if (m->indices == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes[%u].indices is NULL", mi);

    const uint32_t vc = m->vertex_count;
    for (uint32_t i = 0; i < m->index_count; ++i) {
        if (m->indices[i] >= vc)
            return banyan_fail(err, BANYAN_E_RANGE,
                        "meshes[%u].indices[%u] = %u is out of range [0, %u]", mi, i,
                        m->indices[i], vc - 1);
    }

    banyan_status s;
    if ((s = check_finite(m->positions, vc, 3, mi, "positions", err)) != BANYAN_OK) return s;
    if (m->normals && (s = check_finite(m->normals, vc, 3, mi, "normals", err)) != BANYAN_OK)
        return s;
    if (m->uvs && (s = check_finite(m->uvs, vc, 2, mi, "uvs", err)) != BANYAN_OK) return s;
    if (m->colors && (s = check_finite(m->colors, vc, 4, mi, "colors", err)) != BANYAN_OK)
        return s;

    /* Custom attributes: "_" + upper-cased name must be a unique key. */
    if (m->attribute_count > 0 && m->attributes == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "meshes[%u].attributes is NULL but attribute_count = %u", mi,
                    m->attribute_count);
    for (uint32_t a = 0; a < m->attribute_count; ++a) {
        const banyan_attribute *at = &m->attributes[a];
        size_t n = name_len(at->name, BANYAN_NAME_MAX);
        if (n == BANYAN_NAME_MAX)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].attributes[%u].name is not NUL-terminated within %d bytes",
                        mi, a, BANYAN_NAME_MAX);
        if (n == 0)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes[%u].attributes[%u].name is empty",
                        mi, a);
        for (size_t k = 0; k < n; ++k) {
            char c = at->name[k];
            bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                      (c >= '0' && c <= '9') || c == '_';
            if (!ok)
                return banyan_fail(err, BANYAN_E_INVALID_ARG,
                            "meshes[%u].attributes[%u].name \"%.*s\" has a character "
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
                            "meshes[%u].attributes[%u].name \"%s\" repeats attributes[%u] "
                            "(glTF names are upper-cased)",
                            mi, a, at->name, b);
        }
        if (at->data == nullptr)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes[%u].attributes[%u] (\"%s\").data is NULL",
                        mi, a, at->name);
        std::string field = std::string("attributes[") + std::to_string(a) + "].data";
        if ((s = check_finite(at->data, vc, 1, mi, field.c_str(), err)) != BANYAN_OK) return s;
    }

    /* Materials. */
    if (m->material_count > 0 && m->materials == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "meshes[%u].materials is NULL but material_count = %u", mi,
                    m->material_count);
    for (uint32_t k = 0; k < m->material_count; ++k) {
        const banyan_material *mat = &m->materials[k];
        size_t n = name_len(mat->name, BANYAN_NAME_MAX);
        size_t bad = 0;
        if (n == BANYAN_NAME_MAX)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].materials[%u].name is not NUL-terminated within %d bytes",
                        mi, k, BANYAN_NAME_MAX);
        if (!valid_utf8(mat->name, n, &bad))
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].materials[%u].name is not valid UTF-8 (byte %zu)", mi, k,
                        bad);
        for (int c = 0; c < 4; ++c) {
            float v = mat->base_color[c];
            if (!(v >= 0.0f && v <= 1.0f))
                return banyan_fail(err, BANYAN_E_RANGE,
                            "meshes[%u].materials[%u].base_color[%d] = %g is outside [0, 1]",
                            mi, k, c, static_cast<double>(v));
        }
        if (!(mat->roughness >= 0.0f && mat->roughness <= 1.0f))
            return banyan_fail(err, BANYAN_E_RANGE,
                        "meshes[%u].materials[%u].roughness = %g is outside [0, 1]", mi, k,
                        static_cast<double>(mat->roughness));
    }

    /* Parts. */
    if (m->part_count > 0 && m->parts == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes[%u].parts is NULL but part_count = %u",
                    mi, m->part_count);
    bool any_triangles = m->part_count == 0;
    for (uint32_t p = 0; p < m->part_count; ++p) {
        const banyan_part *pt = &m->parts[p];
        if (static_cast<uint64_t>(pt->vertex_offset) + pt->vertex_count > vc)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].parts[%u] vertices [%u, +%u) pass vertex_count = %u", mi, p,
                        pt->vertex_offset, pt->vertex_count, vc);
        if (static_cast<uint64_t>(pt->index_offset) + pt->index_count > m->index_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].parts[%u] indices [%u, +%u) pass index_count = %u", mi, p,
                        pt->index_offset, pt->index_count, m->index_count);
        if (pt->index_count % 3 != 0)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].parts[%u].index_count = %u is not a multiple of 3", mi, p,
                        pt->index_count);
        if (m->material_count > 0 && pt->material >= m->material_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                        "meshes[%u].parts[%u].material = %u is out of range [0, %u]", mi, p,
                        pt->material, m->material_count - 1);
        if (pt->index_count > 0) any_triangles = true;
    }
    if (!any_triangles)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "meshes[%u] has %u parts and none has a triangle", mi, m->part_count);
    return BANYAN_OK;
}

/* ------------------------------------------------------------ building */

struct Builder {
    tinygltf::Model model;
    std::vector<unsigned char> &bin;

    explicit Builder(std::vector<unsigned char> &b) : bin(b) {}

    /* Appends `bytes` bytes (a multiple of 4) as a new bufferView. */
    int add_view(const void *data, size_t bytes, int target) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = bin.size();
        v.byteLength = bytes;
        v.target = target;
        const unsigned char *p = static_cast<const unsigned char *>(data);
        bin.insert(bin.end(), p, p + bytes);
        model.bufferViews.push_back(v);
        return static_cast<int>(model.bufferViews.size() - 1);
    }

    int add_accessor(int view, int component, int type, size_t count,
                     const std::vector<double> *mn = nullptr,
                     const std::vector<double> *mx = nullptr) {
        tinygltf::Accessor a;
        a.bufferView = view;
        a.byteOffset = 0;
        a.normalized = false;
        a.componentType = component;
        a.type = type;
        a.count = count;
        if (mn) a.minValues = *mn;
        if (mx) a.maxValues = *mx;
        model.accessors.push_back(a);
        return static_cast<int>(model.accessors.size() - 1);
    }
};

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
 * square the colour; such colours are left out (the roots carry their one
 * colour both ways). */
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

/* The vertex accessors for vertices [base, base + count) of mesh m. */
std::map<std::string, int> add_vertex_range(Builder &b, const banyan_mesh *m, uint32_t base,
                                            uint32_t count, bool with_colors) {
    std::map<std::string, int> attrs;
    const int AB = TINYGLTF_TARGET_ARRAY_BUFFER;
    const int F = TINYGLTF_COMPONENT_TYPE_FLOAT;
    std::vector<float> tmp;

    /* POSITION: (x, y, z) -> (x, z, -y), with min / max of what is stored. */
    tmp.resize(static_cast<size_t>(count) * 3);
    std::vector<double> mn(3, 0.0), mx(3, 0.0);
    for (uint32_t i = 0; i < count; ++i) {
        const float *p = m->positions + 3 * static_cast<size_t>(base + i);
        float q[3] = {p[0], p[2], -p[1]};
        for (int k = 0; k < 3; ++k) {
            tmp[3 * static_cast<size_t>(i) + k] = q[k];
            double d = static_cast<double>(q[k]);
            if (i == 0 || d < mn[k]) mn[k] = d;
            if (i == 0 || d > mx[k]) mx[k] = d;
        }
    }
    int v = b.add_view(tmp.data(), tmp.size() * sizeof(float), AB);
    attrs["POSITION"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC3, count, &mn, &mx);

    /* NORMAL: converted, renormalised in double; a zero normal becomes +Y. */
    if (m->normals) {
        for (uint32_t i = 0; i < count; ++i) {
            const float *n = m->normals + 3 * static_cast<size_t>(base + i);
            double q[3] = {n[0], n[2], -static_cast<double>(n[1])};
            double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            float *o = &tmp[3 * static_cast<size_t>(i)];
            if (len > 0.0) {
                for (int k = 0; k < 3; ++k) o[k] = static_cast<float>(q[k] / len);
            } else {
                o[0] = 0.0f;
                o[1] = 1.0f;
                o[2] = 0.0f;
            }
        }
        v = b.add_view(tmp.data(), tmp.size() * sizeof(float), AB);
        attrs["NORMAL"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC3, count);
    }

    /* TEXCOORD_0: glTF's v runs down the image, banyan's (like Blender's) up. */
    if (m->uvs) {
        tmp.resize(static_cast<size_t>(count) * 2);
        for (uint32_t i = 0; i < count; ++i) {
            const float *t = m->uvs + 2 * static_cast<size_t>(base + i);
            tmp[2 * static_cast<size_t>(i)] = t[0];
            tmp[2 * static_cast<size_t>(i) + 1] = 1.0f - t[1];
        }
        v = b.add_view(tmp.data(), tmp.size() * sizeof(float), AB);
        attrs["TEXCOORD_0"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC2, count);
    }

    if (m->colors && with_colors) {
        v = b.add_view(m->colors + 4 * static_cast<size_t>(base),
                       static_cast<size_t>(count) * 4 * sizeof(float), AB);
        attrs["COLOR_0"] = b.add_accessor(v, F, TINYGLTF_TYPE_VEC4, count);
    }

    for (uint32_t a = 0; a < m->attribute_count; ++a) {
        const banyan_attribute *at = &m->attributes[a];
        v = b.add_view(at->data + base, static_cast<size_t>(count) * sizeof(float), AB);
        attrs[upper_attribute_key(at->name)] =
            b.add_accessor(v, F, TINYGLTF_TYPE_SCALAR, count);
    }
    return attrs;
}

uint64_t vertex_range_bytes(const banyan_mesh *m, uint64_t count, bool with_colors) {
    uint64_t floats = 3 + (m->normals ? 3 : 0) + (m->uvs ? 2 : 0) + (m->colors && with_colors ? 4 : 0) +
                      m->attribute_count;
    return floats * 4 * count;
}

/* One primitive to write: indices [ioff, ioff + icount) drawn over vertices
 * [vbase, vbase + vcount). */
struct Prim {
    uint32_t ioff, icount, vbase, vcount;
    int material; /* index into model.materials or -1 */
};

/* Plans a mesh's primitives; `local` tells whether each part keeps to its
 * own vertices. Returns the bytes the mesh adds to the buffer. */
uint64_t plan_mesh(const banyan_mesh *m, int material_base, std::vector<Prim> &prims,
                   bool &local) {
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
    uint64_t bytes = 0;
    if (m->part_count == 0) {
        prims.push_back(Prim{0, m->index_count, 0, m->vertex_count,
                             m->material_count > 0 ? material_base : -1});
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
        prims.push_back(pr);
    }
    bool colors = !colors_repeat_material(m);
    for (const Prim &pr : prims) {
        bytes += 4ull * pr.icount;
        if (local) bytes += vertex_range_bytes(m, pr.vcount, colors);
    }
    if (!local) bytes += vertex_range_bytes(m, m->vertex_count, colors);
    return bytes;
}

/* A std::streambuf that writes to a FILE* and remembers the first errno. */
class FileBuf : public std::streambuf {
  public:
    explicit FileBuf(std::FILE *f) : f_(f) {}
    int error() const { return error_; }

  protected:
    std::streamsize xsputn(const char *s, std::streamsize n) override {
        if (n <= 0) return 0;
        errno = 0;
        size_t w = std::fwrite(s, 1, static_cast<size_t>(n), f_);
        if (w != static_cast<size_t>(n) && error_ == 0) error_ = errno ? errno : EIO;
        return static_cast<std::streamsize>(w);
    }
    int_type overflow(int_type c) override {
        if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
        char ch = traits_type::to_char_type(c);
        return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
    }

  private:
    std::FILE *f_;
    int error_ = 0;
};

/* Closes and removes the output file unless commit() was called. */
class OutFile {
  public:
    explicit OutFile(const char *path) : path_(path) {}
    ~OutFile() {
        if (f_) {
            std::fclose(f_);
            std::remove(path_);
        }
    }
    bool open() {
        errno = 0;
        f_ = std::fopen(path_, "wb");
        return f_ != nullptr;
    }
    std::FILE *get() { return f_; }
    /* Flushes and closes; returns 0 or an errno value. The file is removed
     * on failure. */
    int close() {
        int e = 0;
        errno = 0;
        if (std::fflush(f_) != 0 || std::ferror(f_)) e = errno ? errno : EIO;
        errno = 0;
        if (std::fclose(f_) != 0 && e == 0) e = errno ? errno : EIO;
        f_ = nullptr;
        if (e != 0) std::remove(path_);
        return e;
    }

  private:
    const char *path_;
    std::FILE *f_ = nullptr;
};

banyan_status write_impl(const char *path, const banyan_mesh *const *meshes,
                         const char *const *names, uint32_t count, banyan_error *err) {
    if (path == nullptr) return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is NULL");
    if (path[0] == '\0') return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is empty");
    bool binary;
    if (ends_with_ci(path, ".glb")) {
        binary = true;
    } else if (ends_with_ci(path, ".gltf")) {
        binary = false;
    } else {
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                    "path '%s' must end in .glb (binary) or .gltf (JSON)", path);
    }
    if (count == 0) return banyan_fail(err, BANYAN_E_INVALID_ARG, "count is 0; nothing to write");
    if (meshes == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes is NULL but count = %u", count);

    for (uint32_t i = 0; i < count; ++i) {
        banyan_status s = check_mesh(meshes[i], i, err);
        if (s != BANYAN_OK) return s;
        if (names && names[i]) {
            size_t bad = 0;
            if (!valid_utf8(names[i], std::strlen(names[i]), &bad))
                return banyan_fail(err, BANYAN_E_INVALID_ARG, "names[%u] is not valid UTF-8 (byte %zu)",
                            i, bad);
        }
    }

    /* Plan, so the buffer is allocated once and its size checked first. */
    std::vector<std::vector<Prim>> plans(count);
    std::vector<char> local(count, 0);
    uint64_t total = 0;
    int material_base = 0;
    for (uint32_t i = 0; i < count; ++i) {
        bool l = false;
        total += plan_mesh(meshes[i], material_base, plans[i], l);
        local[i] = l ? 1 : 0;
        material_base += static_cast<int>(meshes[i]->material_count);
    }
    if (total > kMaxBufferBytes)
        return banyan_fail(err, BANYAN_E_LIMIT,
                    "the glTF buffer would hold %llu bytes; the limit is %llu (4 GiB less the "
                    "JSON)",
                    static_cast<unsigned long long>(total),
                    static_cast<unsigned long long>(kMaxBufferBytes));

    std::vector<unsigned char> bin;
    bin.reserve(static_cast<size_t>(total));
    Builder b(bin);
    tinygltf::Model &model = b.model;
    model.asset.version = "2.0";
    model.asset.generator = "banyan";

    tinygltf::Scene scene;
    std::vector<uint32_t> rebased;
    for (uint32_t i = 0; i < count; ++i) {
        const banyan_mesh *m = meshes[i];
        for (uint32_t k = 0; k < m->material_count; ++k) {
            const banyan_material *bm = &m->materials[k];
            tinygltf::Material mat;
            mat.name.assign(bm->name, name_len(bm->name, BANYAN_NAME_MAX));
            mat.pbrMetallicRoughness.baseColorFactor = {
                short_double(bm->base_color[0]), short_double(bm->base_color[1]),
                short_double(bm->base_color[2]), short_double(bm->base_color[3])};
            mat.pbrMetallicRoughness.metallicFactor = 0.0;
            mat.pbrMetallicRoughness.roughnessFactor = short_double(bm->roughness);
            mat.doubleSided = bm->double_sided != 0;
            if (bm->base_color[3] < 1.0f) mat.alphaMode = "BLEND";
            model.materials.push_back(mat);
        }

        std::string name = (names && names[i]) ? std::string(names[i])
                                               : "banyan_" + std::to_string(i);
        tinygltf::Mesh gm;
        gm.name = name;
        std::map<std::string, int> shared;
        bool colors = !colors_repeat_material(m);
        if (!local[i]) shared = add_vertex_range(b, m, 0, m->vertex_count, colors);
        for (const Prim &pr : plans[i]) {
            tinygltf::Primitive prim;
            prim.attributes = local[i] ? add_vertex_range(b, m, pr.vbase, pr.vcount, colors) : shared;
            rebased.resize(pr.icount);
            for (uint32_t k = 0; k < pr.icount; ++k)
                rebased[k] = m->indices[pr.ioff + k] - pr.vbase;
            int v = b.add_view(rebased.data(), rebased.size() * sizeof(uint32_t),
                               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
            prim.indices = b.add_accessor(v, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                          TINYGLTF_TYPE_SCALAR, pr.icount);
            prim.material = pr.material;
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            gm.primitives.push_back(prim);
        }
        model.meshes.push_back(gm);

        tinygltf::Node node;
        node.name = name;
        node.mesh = static_cast<int>(model.meshes.size() - 1);
        model.nodes.push_back(node);
        scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
    }
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    if (bin.size() != total)
        return banyan_fail(err, BANYAN_E_INTERNAL,
                    "glTF buffer holds %zu bytes, planned %llu; please report this",
                    bin.size(), static_cast<unsigned long long>(total));
    tinygltf::Buffer buffer;
    buffer.data.swap(bin);
    model.buffers.push_back(std::move(buffer));

    OutFile out(path);
    if (!out.open())
        return banyan_fail(err, BANYAN_E_IO, "cannot open '%s' for writing: %s", path,
                    std::strerror(errno));
    FileBuf fb(out.get());
    std::ostream os(&fb);
    tinygltf::TinyGLTF writer;
    bool ok = writer.WriteGltfSceneToStream(&model, os, /*prettyPrint=*/true, binary);
    os.flush();
    if (fb.error() != 0)
        return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", path, std::strerror(fb.error()));
    if (!ok || !os)
        return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': the glTF serialiser failed", path);
    int e = out.close();
    if (e != 0) return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", path, std::strerror(e));
    return BANYAN_OK;
}

} // namespace

extern "C" BANYAN_API banyan_status banyan_gltf_write(const char *path,
                                                      const banyan_mesh *const *meshes,
                                                      const char *const *names, uint32_t count,
                                                      banyan_error *err) {
    try {
        return write_impl(path, meshes, names, count, err);
    } catch (const std::bad_alloc &) {
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory while writing glTF '%s'",
                    path ? path : "(null)");
    } catch (const std::exception &e) {
        return banyan_fail(err, BANYAN_E_INTERNAL, "internal error while writing glTF '%s': %s",
                    path ? path : "(null)", e.what());
    } catch (...) {
        return banyan_fail(err, BANYAN_E_INTERNAL, "unknown internal error while writing glTF '%s'",
                    path ? path : "(null)");
    }
}
