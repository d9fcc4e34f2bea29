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
 *     (u, 1 - v), COLOR_0 (UNSIGNED_BYTE normalized VEC4, when colors !=
 *     NULL and they do more than repeat the materials' base colours),
 *     "_NAME" float scalars for custom attributes, UNSIGNED_INT indices;
 *   - Z-up to Y-up: (x, y, z) -> (x, z, -y) for positions, normals and
 *     the wind pivot (_WIND_PIVOT_X/_Y/_Z);
 *   - one metallic-roughness material per banyan_material;
 *   - with textures on, the library's textures that the materials name
 *     (banyan/textures.h), drawn at the options' size and seed, as PNG
 *     images in bufferViews at the end of the buffer: one image per
 *     (kind, season, map), shared by every material that uses it;
 *     baseColorTexture (factor white, as the texture carries the colour)
 *     and normalTexture; bark samplers REPEAT, atlas samplers
 *     CLAMP_TO_EDGE; alpha_cutoff > 0 gives alphaMode MASK. With
 *     opt->image_dir those images are PNG files in that folder instead
 *     (relative URIs; a file already there is kept, not drawn again).
 * The skeleton is not exported.
 *
 * The buffer is never held in memory: its views are planned (offsets,
 * POSITION min/max), tinygltf writes the JSON for an empty buffer whose
 * byteLength is then set, and the bytes are streamed after it (the .glb's
 * BIN chunk, or base64 in the .gltf's data URI) from the mesh arrays,
 * converted on a second thread into a few 4 MiB blocks (Pipe) while the
 * caller writes. The bytes are those tinygltf wrote when it held the
 * buffer, whatever the threads do.
 *
 * Nothing is created on disk until every input has been checked. The file
 * is written through base/atomic_file.h: a write that fails part-way
 * leaves the old file as it was; fsync only with opt->sync. No exception leaves this file.
 */
#include "banyan.h"
#include "base/atomic_file.h"
#include "base/dmath.h"
#include "base/error.h"
#include "base/progress.h"
#include "gltf/gltf_compact.h"
#include "textures/tex_budget.h"
#include "textures/tex_cache.h"

#include <tiny_gltf.h>

#include <sys/stat.h>
#ifdef _WIN32
#include <direct.h>
#endif

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <ostream>
#include <sstream>
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

uint64_t pad4(uint64_t n) { return (n + 3) & ~UINT64_C(3); }

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

bool is_leaf_kind(int32_t kind) { return kind == BANYAN_TEX_KEYAKI_LEAF || kind == BANYAN_TEX_IVY_LEAF; }

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
    for (uint32_t i = 0; i < m->index_count; ++i) {
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

    /* Custom attributes: "_" + upper-cased name must be a unique key. */
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

    /* Materials. */
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
        /* A mesh without images names none: ABI 10 callers' zero-filled
         * materials (image 0) still write as before. */
        if (m->image_count > 0 && (mat->image < -1 || mat->image >= static_cast<int64_t>(m->image_count)))
            return banyan_fail(err, BANYAN_E_RANGE, "%s.materials[%u].image = %d is outside [-1, %u] (image_count = %u)",
                               mi, k, mat->image, m->image_count - 1, m->image_count);
        if (m->image_count > 0 && mat->image >= 0 && m->uvs == nullptr)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s.materials[%u].image = %d needs uvs, and %s.uvs is NULL",
                               mi, k, mat->image, mi);
    }

    /* Images (banyan_material.image): what banyan_image_png accepts. */
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

    /* Instances: each names a group that has triangles (a variant). */
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

/* ------------------------------------------------------------ building */

/* One piece of the BIN chunk, in buffer order: the views are planned
 * first (the JSON needs their offsets) and their bytes streamed to the file
 * afterwards, straight from the mesh arrays or converted through a fixed
 * scratch block, so no copy of the buffer is ever held in memory. */
enum SegKind { kRaw, kZero, kPosition, kNormal, kUv, kTangent, kColor, kWindPivot, kEngineUv, kIndices };

struct Layout;

struct Segment {
    SegKind kind;
    uint64_t bytes = 0;
    const void *src = nullptr;          /* kRaw */
    const banyan_mesh *m = nullptr;
    const Layout *L = nullptr;          /* wind kinds */
    uint32_t base = 0, count = 0;       /* vertices [base, +count); kIndices: indices [base, +count) */
    uint32_t aux = 0;                   /* kWindPivot: the glTF axis (0 .. 2); kEngineUv: the set (1 .. 4);
                                           kIndices: the vertex base subtracted */
    uint32_t ioff = 0, icount = 0;      /* kTangent: the triangles the range's tangents come from */
    bool whole = false;                 /* kTangent: from the whole mesh's triangles */
};

struct Builder {
    tinygltf::Model model;
    std::vector<Segment> segs;
    uint64_t size = 0;                       /* the buffer's bytes so far */
    std::vector<std::vector<float>> keep;    /* small arrays built here (instances) */

    /* An image's bytes as a new bufferView (no target), then zeros to pad
     * the buffer to 4 bytes for the views that follow. */
    int add_image_view(const std::vector<unsigned char> &bytes) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = static_cast<size_t>(size);
        v.byteLength = bytes.size();
        push_image(bytes);
        model.bufferViews.push_back(v);
        return static_cast<int>(model.bufferViews.size() - 1);
    }
    /* An image's bytes, then zeros to 4 bytes. */
    void push_image(const std::vector<unsigned char> &bytes) {
        Segment sg{kRaw};
        sg.src = bytes.data();
        sg.bytes = bytes.size();
        segs.push_back(sg);
        size += bytes.size();
        if (pad4(size) != size) {
            Segment z{kZero};
            z.bytes = pad4(size) - size;
            segs.push_back(z);
            size = pad4(size);
        }
    }

    /* An image's bufferView whose bytes come later (fill_image_view), at
     * offset `at` and `len` bytes for now: the widest they can be. */
    int add_image_placeholder(uint64_t at, uint64_t len) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = static_cast<size_t>(at);
        v.byteLength = static_cast<size_t>(len);
        model.bufferViews.push_back(v);
        return static_cast<int>(model.bufferViews.size() - 1);
    }
    /* The placeholder `view` made the image's own, as add_image_view would. */
    int fill_image_view(int view, const std::vector<unsigned char> &bytes) {
        tinygltf::BufferView &v = model.bufferViews[static_cast<size_t>(view)];
        v.byteOffset = static_cast<size_t>(size);
        v.byteLength = bytes.size();
        push_image(bytes);
        return view;
    }

    /* sg.bytes bytes (a multiple of 4) as a new bufferView. */
    int add_view(const Segment &sg, int target) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = static_cast<size_t>(size);
        v.byteLength = static_cast<size_t>(sg.bytes);
        v.target = target;
        segs.push_back(sg);
        size += sg.bytes;
        model.bufferViews.push_back(v);
        return static_cast<int>(model.bufferViews.size() - 1);
    }

    /* A small array kept until the buffer is written. */
    int add_floats(std::vector<float> &&a, int target) {
        keep.push_back(std::move(a));
        Segment sg{kRaw};
        sg.src = keep.back().data();
        sg.bytes = keep.back().size() * sizeof(float);
        return add_view(sg, target);
    }

    /* normalized: integer components read as 0..1 (COLOR_0's bytes). */
    int add_accessor(int view, int component, int type, size_t count,
                     const std::vector<double> *mn = nullptr,
                     const std::vector<double> *mx = nullptr, bool normalized = false) {
        tinygltf::Accessor a;
        a.bufferView = view;
        a.byteOffset = 0;
        a.normalized = normalized;
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

/* Per-vertex tangents (x, y, z, w) in the mesh's own Z-up frame, for
 * normal maps: xyz the direction of increasing u, made perpendicular to
 * the normal; w = +1 when (normal x tangent) points up the image
 * (increasing banyan v, glTF's bitangent), -1 where the uvs are mirrored.
 * Triangles add their uv gradients to their corners (Lengyel's method);
 * a vertex without a usable gradient gets any unit vector perpendicular
 * to its normal. Needs normals and uvs. Computed for vertices
 * [vbase, vbase + vc) from the triangles of indices [ioff, ioff + icount),
 * which must reference only those vertices; out[4 (v - vbase) ..]. When no
 * other triangle touches the range, this is the whole mesh's result, bit
 * for bit: each vertex sums the same terms in the same order. */
std::vector<float> vertex_tangents(const banyan_mesh *m, uint32_t vbase, uint32_t vcount, uint32_t ioff,
                                   uint32_t icount) {
    const size_t vc = vcount;
    std::vector<double> acc(6 * vc, 0.0); /* t then b, per vertex */
    for (uint32_t k = ioff; k + 2 < ioff + icount; k += 3) {
        const uint32_t i[3] = {m->indices[k], m->indices[k + 1], m->indices[k + 2]};
        const uint32_t rel[3] = {i[0] - vbase, i[1] - vbase, i[2] - vbase};
        const float *p0 = m->positions + 3 * static_cast<size_t>(i[0]);
        const float *p1 = m->positions + 3 * static_cast<size_t>(i[1]);
        const float *p2 = m->positions + 3 * static_cast<size_t>(i[2]);
        const float *t0 = m->uvs + 2 * static_cast<size_t>(i[0]);
        const float *t1 = m->uvs + 2 * static_cast<size_t>(i[1]);
        const float *t2 = m->uvs + 2 * static_cast<size_t>(i[2]);
        double e1[3], e2[3];
        for (int c = 0; c < 3; ++c) {
            e1[c] = static_cast<double>(p1[c]) - p0[c];
            e2[c] = static_cast<double>(p2[c]) - p0[c];
        }
        double du1 = static_cast<double>(t1[0]) - t0[0], dv1 = static_cast<double>(t1[1]) - t0[1];
        double du2 = static_cast<double>(t2[0]) - t0[0], dv2 = static_cast<double>(t2[1]) - t0[1];
        double det = du1 * dv2 - du2 * dv1;
        if (!(std::fabs(det) > 1e-20)) continue;
        double r = 1.0 / det, sd[3], td[3];
        for (int c = 0; c < 3; ++c) {
            sd[c] = (e1[c] * dv2 - e2[c] * dv1) * r;
            td[c] = (e2[c] * du1 - e1[c] * du2) * r;
        }
        for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) {
                acc[6 * static_cast<size_t>(rel[j]) + c] += sd[c];
                acc[6 * static_cast<size_t>(rel[j]) + 3 + c] += td[c];
            }
    }
    std::vector<float> out(4 * vc);
    for (size_t v = 0; v < vc; ++v) {
        const float *nv = m->normals + 3 * (vbase + v);
        double n[3] = {nv[0], nv[1], nv[2]};
        double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (nl > 0.0) {
            for (double &c : n) c /= nl;
        } else { /* the writer's zero normal becomes +Y up, i.e. +Z here */
            n[0] = n[1] = 0.0;
            n[2] = 1.0;
        }
        const double *t = &acc[6 * v], *bt = &acc[6 * v + 3];
        double d = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        double q[3] = {t[0] - d * n[0], t[1] - d * n[1], t[2] - d * n[2]};
        double ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if (!(ql > 1e-12 * (1.0 + std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2])))) {
            /* any perpendicular: n x (the axis least along n) */
            double a[3] = {0.0, 0.0, 0.0};
            int least = std::fabs(n[0]) <= std::fabs(n[1]) ? (std::fabs(n[0]) <= std::fabs(n[2]) ? 0 : 2)
                                                            : (std::fabs(n[1]) <= std::fabs(n[2]) ? 1 : 2);
            a[least] = 1.0;
            q[0] = n[1] * a[2] - n[2] * a[1];
            q[1] = n[2] * a[0] - n[0] * a[2];
            q[2] = n[0] * a[1] - n[1] * a[0];
            ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        }
        for (double &c : q) c /= ql;
        double cx[3] = {n[1] * q[2] - n[2] * q[1], n[2] * q[0] - n[0] * q[2], n[0] * q[1] - n[1] * q[0]};
        double w = cx[0] * bt[0] + cx[1] * bt[1] + cx[2] * bt[2] < 0.0 ? -1.0 : 1.0;
        for (int c = 0; c < 3; ++c) out[4 * v + c] = static_cast<float>(q[c]);
        out[4 * v + 3] = static_cast<float>(w);
    }
    return out;
}

/* How a mesh's custom attributes go out (docs/gltf.md "Wind"). Every one
 * is a float SCALAR: Blender's glTF importer before 5.2 fails on a mesh
 * whose custom attributes differ in element count. With all three pivot
 * components, _WIND_PIVOT_X/_Y/_Z are the pivot in glTF's axes like
 * POSITION ((x, y, z) -> (x, z, -y)); the other wind scalars go out as
 * they are. With all seven and engine_uvs they are also written as
 * TEXCOORD_1 .. 4 for importers that keep only UV sets. */
const char *const kWindNames[7] = {BANYAN_ATTR_WIND_PIVOT_X, BANYAN_ATTR_WIND_PIVOT_Y, BANYAN_ATTR_WIND_PIVOT_Z,
                                   BANYAN_ATTR_WIND_LEVEL,   BANYAN_ATTR_WIND_STIFFNESS, BANYAN_ATTR_WIND_PHASE,
                                   BANYAN_ATTR_WIND_FLUTTER};

struct Layout {
    const float *wind[7] = {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
    const float *birth = nullptr;
    bool pivot = false;      /* the three pivot components present */
    bool engine_uvs = false; /* all seven present and the option on: TEXCOORD_1 .. 4 */
};

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
    } else if (L.engine_uvs) { /* TEXCOORD_n must count up from 0 */
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
    return attrs;
}

/* The temporary output file (base/atomic_file.h), removed unless
 * commit() succeeded. */
class OutFile {
  public:
    OutFile() : af_{nullptr, nullptr, nullptr, 0} {}
    ~OutFile() { atomic_abort(&af_); }
    int open(const char *path, bool sync) {
        int e = atomic_open(&af_, path);
        af_.sync = sync ? 1 : 0;
        return e;
    }
    std::FILE *get() { return af_.f; }
    /* With sync: the disk starts on what is written so far. */
    void start_writeback() {
        if (af_.sync) atomic_start_writeback(&af_);
    }
    /* Flushes, syncs (if asked) and renames over the target; 0 or an errno value. */
    int commit() { return atomic_commit(&af_); }
    /* A temporary regular file, which can be written again at its start
     * (not a FIFO or device written in place). */
    bool seekable() const { return af_.temp != nullptr; }
    /* n bytes over the file's first n; 0 or an errno value. Leaves the
     * position at the end. */
    int rewrite_start(const void *p, size_t n) {
        errno = 0;
        if (std::fseek(af_.f, 0, SEEK_SET) != 0) return errno ? errno : EIO;
        if (std::fwrite(p, 1, n, af_.f) != n) return errno ? errno : EIO;
        if (std::fseek(af_.f, 0, SEEK_END) != 0) return errno ? errno : EIO;
        return 0;
    }

  private:
    atomic_file af_;
};

/* Where the BIN chunk's bytes go: the file as they are, or (a .gltf)
 * base64 inside the JSON's data URI. Remembers the first errno. */
class Sink {
  public:
    Sink(std::FILE *f, bool base64) : f_(f), base64_(base64) {
        if (base64_) out_.resize(4 * (kBlock / 3) + 8);
    }
    int error() const { return error_; }
    uint64_t count() const { return count_; }
    /* Writes to f from now on (a Sink made before its file was opened). */
    void reset(std::FILE *f) { f_ = f; }

    void put(const void *data, size_t n) {
        const unsigned char *p = static_cast<const unsigned char *>(data);
        count_ += n;
        if (!base64_) {
            raw(p, n);
            return;
        }
        while (n > 0) {
            if (held_ > 0 || n < 3) { /* finish the held triple first */
                while (held_ < 3 && n > 0) {
                    hold_[held_++] = *p++;
                    --n;
                }
                if (held_ == 3) {
                    encode(hold_, 3, &out_[0]);
                    raw(reinterpret_cast<const unsigned char *>(&out_[0]), 4);
                    held_ = 0;
                }
                continue;
            }
            size_t take = std::min(n - n % 3, static_cast<size_t>(kBlock / 3 * 3));
            char *o = &out_[0];
            for (size_t i = 0; i < take; i += 3, o += 4) encode(p + i, 3, o);
            raw(reinterpret_cast<const unsigned char *>(&out_[0]), static_cast<size_t>(o - &out_[0]));
            p += take;
            n -= take;
        }
    }

    /* The last 1 or 2 bytes of a base64 stream, '='-padded. */
    void finish() {
        if (base64_ && held_ > 0) {
            encode(hold_, held_, &out_[0]);
            raw(reinterpret_cast<const unsigned char *>(&out_[0]), 4);
            held_ = 0;
        }
    }

    static constexpr size_t kBlock = size_t(4) << 20;

  private:
    void raw(const unsigned char *p, size_t n) {
        if (error_ != 0 || n == 0) return;
        errno = 0;
        if (std::fwrite(p, 1, n, f_) != n) error_ = errno ? errno : EIO;
    }
    static void encode(const unsigned char *in, int n, char *o) {
        static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        uint32_t v = static_cast<uint32_t>(in[0]) << 16 | (n > 1 ? static_cast<uint32_t>(in[1]) << 8 : 0u) |
                     (n > 2 ? static_cast<uint32_t>(in[2]) : 0u);
        o[0] = kAlphabet[v >> 18 & 63];
        o[1] = kAlphabet[v >> 12 & 63];
        o[2] = n > 1 ? kAlphabet[v >> 6 & 63] : '=';
        o[3] = n > 2 ? kAlphabet[v & 63] : '=';
    }

    std::FILE *f_;
    bool base64_;
    int error_ = 0;
    uint64_t count_ = 0;
    unsigned char hold_[3] = {0, 0, 0};
    int held_ = 0;
    std::vector<char> out_;
};

/* The BIN chunk's bytes on their way from the converting thread to the
 * writing one (the caller), in order: converted or small pieces gathered in
 * a few small fixed blocks (kBlockBytes each, reused), large raw arrays
 * handed over as they are in the mesh. Converting block k + 1 while block k
 * is written overlaps the CPU work with write(); the bytes do not depend on
 * the split. Without a thread (none could be started) each piece is
 * written as soon as it is ready. */
class Pipe {
  public:
    /* Small blocks, so the one just converted is still in the cache when
     * write() copies it: 4 MiB blocks made write() 2.5x slower here. */
    static constexpr int kBlocks = 8;
    static constexpr size_t kBlockBytes = size_t(512) << 10;
    static constexpr size_t kByReference = size_t(256) << 10; /* raw pieces at least this long are not copied */
    static constexpr uint64_t kWriteback = uint64_t(64) << 20; /* with sync: start the disk every this many bytes */

    Pipe(Sink &sink, OutFile &file) : sink_(sink), file_(file) {
        for (int k = 0; k < kBlocks; ++k) {
            blocks_[k].resize(kBlockBytes);
            if (k > 0) free_.push_back(k);
        }
    }

    /* Producer side. Room for at least min bytes (4-aligned) in the current block. */
    unsigned char *space(size_t min, size_t &cap) {
        if (kBlockBytes - fill_ < min || fill_ % 4 != 0) hand_block();
        cap = kBlockBytes - fill_;
        return blocks_[cur_].data() + fill_;
    }
    void used(size_t n) { fill_ += n; }
    void put(const void *data, size_t n) {
        if (n >= kByReference) {
            hand_block();
            push(Piece{data, n, -1});
            return;
        }
        const unsigned char *p = static_cast<const unsigned char *>(data);
        while (n > 0) {
            if (fill_ == kBlockBytes) hand_block();
            size_t take = std::min(n, kBlockBytes - fill_);
            std::memcpy(blocks_[cur_].data() + fill_, p, take);
            fill_ += take;
            p += take;
            n -= take;
        }
    }
    void zeros(uint64_t n) {
        while (n > 0) {
            if (fill_ == kBlockBytes) hand_block();
            size_t take = static_cast<size_t>(std::min<uint64_t>(n, kBlockBytes - fill_));
            std::memset(blocks_[cur_].data() + fill_, 0, take);
            fill_ += take;
            n -= take;
        }
    }
    /* Whether the writing side failed: the producer may stop early. */
    bool failed() {
        std::lock_guard<std::mutex> lk(mu_);
        return stop_;
    }
    /* The last block, then the end mark. */
    void finish() {
        hand_block();
        push(Piece{nullptr, 0, -2});
    }

    /* Runs produce(*this) on a new thread while the caller writes; inline
     * when no thread can be started. Rethrows the producer's exception. */
    template <class F> void run(F produce) {
        auto body = [this, &produce] {
            try {
                produce(*this);
            } catch (...) {
                std::lock_guard<std::mutex> lk(mu_);
                thrown_ = std::current_exception();
            }
            finish();
        };
        std::thread t;
        threaded_ = true; /* before the thread starts: it reads it */
        try {
            t = std::thread(body);
        } catch (const std::system_error &) {
            threaded_ = false;
        }
        if (!threaded_) {
            body();
        } else {
            for (;;) {
                Piece pc;
                {
                    std::unique_lock<std::mutex> lk(mu_);
                    cv_.wait(lk, [this] { return !queue_.empty(); });
                    pc = queue_.front();
                    queue_.pop_front();
                }
                if (pc.block == -2) break;
                write(pc);
                std::lock_guard<std::mutex> lk(mu_);
                if (pc.block >= 0) free_.push_back(pc.block);
                if (sink_.error()) stop_ = true;
                cv_.notify_all();
            }
            t.join();
        }
        if (thrown_) std::rethrow_exception(thrown_);
    }

  private:
    struct Piece {
        const void *p;
        size_t n;
        int block; /* -1: mesh memory; -2: the end */
    };

    void write(const Piece &pc) {
        sink_.put(pc.p, pc.n);
        written_ += pc.n;
        if (written_ - synced_ >= kWriteback) {
            file_.start_writeback();
            synced_ = written_;
        }
    }
    void push(const Piece &pc) {
        if (!threaded_) {
            if (pc.block != -2) write(pc);
            if (sink_.error()) stop_ = true;
            return;
        }
        std::lock_guard<std::mutex> lk(mu_);
        queue_.push_back(pc);
        cv_.notify_all();
    }
    /* The current block to the writer (when it holds anything), then a free one. */
    void hand_block() {
        if (fill_ == 0) return;
        if (!threaded_) {
            write(Piece{blocks_[cur_].data(), fill_, cur_});
            if (sink_.error()) stop_ = true;
            fill_ = 0;
            return;
        }
        std::unique_lock<std::mutex> lk(mu_);
        queue_.push_back(Piece{blocks_[cur_].data(), fill_, cur_});
        cv_.notify_all();
        cv_.wait(lk, [this] { return !free_.empty(); });
        cur_ = free_.front();
        free_.pop_front();
        fill_ = 0;
    }

    Sink &sink_;
    OutFile &file_;
    std::vector<unsigned char> blocks_[kBlocks];
    int cur_ = 0;
    size_t fill_ = 0;
    bool threaded_ = false;
    std::mutex mu_;
    std::condition_variable cv_;
    std::deque<Piece> queue_;
    std::deque<int> free_;
    bool stop_ = false;
    std::exception_ptr thrown_;
    uint64_t written_ = 0, synced_ = 0;
};

/* Streams the planned segments into a Pipe, converting straight into its
 * blocks. */
class BinWriter {
  public:
    explicit BinWriter(Pipe &out) : out_(out) {}

    void write(const Segment &s) {
        switch (s.kind) {
        case kRaw:
            out_.put(s.src, static_cast<size_t>(s.bytes));
            return;
        case kZero:
            out_.zeros(s.bytes);
            return;
        case kIndices:
            if (s.aux == 0) { /* already right: straight from the mesh */
                out_.put(s.m->indices + s.base, static_cast<size_t>(s.count) * sizeof(uint32_t));
                return;
            }
            break;
        case kTangent:
            tangents_for(s);
            break;
        default:
            break;
        }
        /* 4-byte words per element (kColor: its four bytes are one) */
        const uint32_t width = s.kind == kIndices ? 1 : static_cast<uint32_t>(s.bytes / 4 / (s.count ? s.count : 1));
        const size_t elem = static_cast<size_t>(width) * sizeof(float);
        for (uint32_t i0 = 0; i0 < s.count;) {
            size_t cap = 0;
            float *o = reinterpret_cast<float *>(out_.space(elem, cap));
            uint32_t n = static_cast<uint32_t>(std::min<uint64_t>(cap / elem, s.count - i0));
            fill(s, i0, n, o);
            out_.used(n * elem);
            i0 += n;
        }
    }

  private:
    /* Elements [i0, i0 + n) of segment s into o. */
    void fill(const Segment &s, uint32_t i0, uint32_t n, float *o) {
        const banyan_mesh *m = s.m;
        const size_t b = static_cast<size_t>(s.base) + i0;
        switch (s.kind) {
        case kPosition: /* (x, y, z) -> (x, z, -y) */
            for (uint32_t i = 0; i < n; ++i, o += 3) {
                const float *p = m->positions + 3 * (b + i);
                o[0] = p[0];
                o[1] = p[2];
                o[2] = -p[1];
            }
            break;
        case kNormal: /* converted, renormalised in double; a zero normal becomes +Y */
            for (uint32_t i = 0; i < n; ++i, o += 3) {
                const float *nv = m->normals + 3 * (b + i);
                double q[3] = {nv[0], nv[2], -static_cast<double>(nv[1])};
                double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
                if (len > 0.0) {
                    for (int k = 0; k < 3; ++k) o[k] = static_cast<float>(q[k] / len);
                } else {
                    o[0] = 0.0f;
                    o[1] = 1.0f;
                    o[2] = 0.0f;
                }
            }
            break;
        case kUv: /* glTF's v runs down the image, banyan's (like Blender's) up */
            for (uint32_t i = 0; i < n; ++i, o += 2) {
                const float *t = m->uvs + 2 * (b + i);
                o[0] = t[0];
                o[1] = 1.0f - t[1];
            }
            break;
        case kTangent: { /* converted like the normals (a rotation: w keeps its sign) */
            const float *t = tan_.data() + 4 * (b - tan_base_);
            for (uint32_t i = 0; i < n; ++i, o += 4, t += 4) {
                o[0] = t[0];
                o[1] = t[2];
                o[2] = -t[1];
                o[3] = t[3];
            }
            break;
        }
        case kWindPivot: { /* one axis of a point like POSITION: x, z, -y */
            const Layout &L = *s.L;
            const float *src = L.wind[s.aux == 0 ? 0 : s.aux == 1 ? 2 : 1];
            const float sign = s.aux == 2 ? -1.0f : 1.0f;
            for (uint32_t i = 0; i < n; ++i) o[i] = sign * src[b + i];
            break;
        }
        case kEngineUv: {
            /* TEXCOORD_1 pivot (x, y), 2 (pivot z, level), 3 (stiffness,
             * phase), 4 (flutter, birth); the pivot Y up as in _WIND_PIVOT_*. */
            const Layout &L = *s.L;
            for (uint32_t i = 0; i < n; ++i, o += 2) {
                size_t j = b + i;
                float a = 0.0f, c = 0.0f;
                switch (s.aux) {
                case 1: a = L.wind[0][j]; c = L.wind[2][j]; break;
                case 2: a = -L.wind[1][j]; c = L.wind[3][j]; break;
                case 3: a = L.wind[4][j]; c = L.wind[5][j]; break;
                default: a = L.wind[6][j]; c = L.birth ? L.birth[j] : 0.0f; break;
                }
                o[0] = a;
                o[1] = c;
            }
            break;
        }
        case kColor: { /* clamped to [0, 1], rounded to the nearest of 0..255 */
            uint8_t *u = reinterpret_cast<uint8_t *>(o);
            const float *c = m->colors + 4 * b;
            for (uint32_t i = 0; i < 4 * n; ++i) {
                float x = c[i];
                x = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
                u[i] = static_cast<uint8_t>(x * 255.0f + 0.5f);
            }
            break;
        }
        case kIndices: { /* rebased to the primitive's first vertex */
            uint32_t *u = reinterpret_cast<uint32_t *>(o);
            for (uint32_t i = 0; i < n; ++i) u[i] = m->indices[b + i] - s.aux;
            break;
        }
        default:
            break;
        }
    }

    /* The tangents a kTangent segment reads: its own range's, or the whole
     * mesh's, kept while the same mesh's ranges follow. */
    void tangents_for(const Segment &s) {
        if (s.whole) {
            if (tan_mesh_ != s.m || !tan_whole_) {
                tan_ = vertex_tangents(s.m, 0, s.m->vertex_count, 0, s.m->index_count);
                tan_mesh_ = s.m;
                tan_whole_ = true;
                tan_base_ = 0;
            }
            return;
        }
        tan_ = vertex_tangents(s.m, s.base, s.count, s.ioff, s.icount);
        tan_mesh_ = s.m;
        tan_whole_ = false;
        tan_base_ = s.base;
    }

    Pipe &out_;
    std::vector<float> tan_;
    const banyan_mesh *tan_mesh_ = nullptr;
    bool tan_whole_ = false;
    size_t tan_base_ = 0;
};

uint64_t vertex_range_bytes(const banyan_mesh *m, const Layout &L, uint64_t count, bool with_colors, bool tangents) {
    /* in 4-byte words: a colour is 4 bytes */
    uint64_t floats = 3 + (m->normals ? 3 : 0) + (m->uvs || L.engine_uvs ? 2 : 0) +
                      (m->colors && with_colors ? 1 : 0) + (tangents ? 4 : 0) + m->attribute_count +
                      (L.engine_uvs ? 8 : 0);
    return floats * 4 * count;
}

/* One primitive to write: indices [ioff, ioff + icount) drawn over vertices
 * [vbase, vbase + vcount). */
struct Prim {
    uint32_t ioff, icount, vbase, vcount;
    int material;   /* index into model.materials or -1 */
    uint32_t group; /* its part's group: the variant of an instanced mesh */
};

/* Plans a mesh's primitives; `local` tells whether each part keeps to its
 * own vertices. Returns the bytes the mesh adds to the buffer. */
uint64_t plan_mesh(const banyan_mesh *m, const Layout &L, int material_base, bool tangents, std::vector<Prim> &prims,
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
    bool colors = !colors_repeat_material(m);
    for (const Prim &pr : prims) {
        bytes += 4ull * pr.icount;
        if (local) bytes += vertex_range_bytes(m, L, pr.vcount, colors, tangents);
    }
    if (!local) bytes += vertex_range_bytes(m, L, m->vertex_count, colors, tangents);
    return bytes;
}

/* ------------------------------------------------------------ textures */

const char *const kKindNames[BANYAN_TEX_COUNT] = {"keyaki_leaf", "ivy_leaf", "keyaki_bark", "fig_bark",
                                                  "ivy_stem"};

/* One texture the asset embeds: PNG bytes of its base colour (RGBA) and
 * normal map (RGB); image 2 i and 2 i + 1, texture 2 i and 2 i + 1 for the
 * i-th texture drawn. */
struct TexturePngs {
    int32_t kind, season;
    std::vector<unsigned char> base, normal;
    bool have = false; /* opt->image_dir: both files are there already, nothing to draw */
};

/* Frees the library's images and PNG buffers on every path out. */
struct ImageGuard {
    banyan_image *base = nullptr, *normal = nullptr;
    uint8_t *png = nullptr;
    ~ImageGuard() {
        banyan_image_free(base);
        banyan_image_free(normal);
        banyan_png_free(png);
    }
};

banyan_status draw_texture(int32_t kind, int32_t season, const banyan_gltf_options &o, const prog_deadline &stop,
                           double seconds, TexturePngs &t, banyan_error *err) {
    banyan_texture_params tp;
    banyan_texture_params_init(&tp);
    tp.kind = kind;
    tp.season = season;
    tp.size = o.texture_size;
    tp.seed = o.texture_seed;
    char dir[4096];
    const bool cached = tex_cache_dir(o.texture_cache, o.texture_cache_dir, dir, sizeof dir) != 0;
    uint8_t *png[2] = {nullptr, nullptr};
    size_t len[2] = {0, 0};
    banyan_status s = tex_cached_pngs(&tp, cached ? dir : nullptr, &stop, seconds, &png[0], &len[0], &png[1], &len[1], err);
    /* t.kind and t.season were set by plan_textures: the caller reads them meanwhile */
    try {
        if (s == BANYAN_OK) t.base.assign(png[0], png[0] + len[0]), t.normal.assign(png[1], png[1] + len[1]);
    } catch (...) {
        banyan_png_free(png[0]);
        banyan_png_free(png[1]);
        throw;
    }
    banyan_png_free(png[0]);
    banyan_png_free(png[1]);
    return s;
}

/* The slot key of a material's texture, or -1 when it is drawn flat:
 * no texture, or a mesh without the uvs and normals a texture needs. */
int texture_key(const banyan_mesh *m, const banyan_material *bm) {
    if (bm->texture == BANYAN_TEX_NONE || m->uvs == nullptr || m->normals == nullptr) return -1;
    return bm->texture * 2 + (is_leaf_kind(bm->texture) ? bm->season : 0); /* bark has no seasons */
}

/* Draws every texture the meshes' materials name, in order of first use;
 * slot[kind * 2 + season] gets its index into `out` (-1: unused). */
/* The library textures the materials name, in first-use order: kind and
 * season into out, its index into slot; drawn later (draw_planned). */
void plan_textures(const banyan_mesh *const *meshes, uint32_t count, const banyan_gltf_options &o,
                   std::vector<TexturePngs> &out, int slot[2 * BANYAN_TEX_COUNT]) {
    for (int i = 0; i < 2 * BANYAN_TEX_COUNT; ++i) slot[i] = -1;
    if (!o.textures) return;
    for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < meshes[i]->material_count; ++k) {
            const banyan_material *bm = &meshes[i]->materials[k];
            int key = texture_key(meshes[i], bm);
            if (key < 0 || slot[key] >= 0) continue;
            out.emplace_back();
            out.back().kind = bm->texture;
            out.back().season = key % 2;
            slot[key] = static_cast<int>(out.size() - 1);
        }
    }
}

/* The textures drawn on their own threads (up to kThreads, texture k on
 * thread k % kThreads) while the meshes are planned: the PNGs' sizes are
 * needed only for the views at the buffer's end. A texture whose thread
 * could not be started is drawn in wait(). The destructor waits. */
class TextureDrawer {
  public:
    static constexpr size_t kThreads = 2;

    TextureDrawer(const banyan_gltf_options &o, const prog_deadline &stop, double seconds, std::vector<TexturePngs> &t)
        : o_(o), stop_(stop), seconds_(seconds), t_(t), status_(t.size(), BANYAN_OK), err_(t.size()),
          thrown_(t.size()) {
        th_.reserve(kThreads);
        for (size_t k = 0; k < kThreads && k < t_.size(); ++k) {
            try {
                th_.emplace_back([this, k] {
                    for (size_t i = k; i < t_.size(); i += kThreads) draw(i);
                });
            } catch (const std::system_error &) {
                break;
            }
        }
        started_ = th_.size();
    }
    ~TextureDrawer() { join(); }
    /* The first failed texture's status, its message in *err; rethrows its exception. */
    banyan_status wait(banyan_error *err) {
        join();
        for (size_t k = started_; k < kThreads && k < t_.size(); ++k) /* threads never started */
            for (size_t i = k; i < t_.size(); i += kThreads) draw(i);
        started_ = kThreads;
        for (size_t i = 0; i < t_.size(); ++i) {
            if (thrown_[i]) std::rethrow_exception(thrown_[i]);
            if (status_[i] != BANYAN_OK) {
                if (err) *err = err_[i];
                return status_[i];
            }
        }
        return BANYAN_OK;
    }

  private:
    void draw(size_t i) {
        if (t_[i].have) return;
        try {
            status_[i] = draw_texture(t_[i].kind, t_[i].season, o_, stop_, seconds_, t_[i], &err_[i]);
        } catch (...) {
            thrown_[i] = std::current_exception();
        }
    }
    void join() {
        for (std::thread &t : th_)
            if (t.joinable()) t.join();
    }
    const banyan_gltf_options &o_;
    const prog_deadline stop_; /* the call's max_seconds, checked by the painters and the PNG encoder */
    const double seconds_;
    std::vector<TexturePngs> &t_;
    std::vector<banyan_status> status_;
    std::vector<banyan_error> err_;
    std::vector<std::exception_ptr> thrown_;
    std::vector<std::thread> th_;
    size_t started_ = 0; /* threads started; the rest are drawn in wait() */
};

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

/* The folder of path with its trailing separator ("" for the current one). */
std::string folder_of(const char *path) {
    const char *s = std::strrchr(path, '/');
#ifdef _WIN32
    const char *b = std::strrchr(path, '\\');
    if (b != nullptr && (s == nullptr || b > s)) s = b;
#endif
    return s ? std::string(path, static_cast<size_t>(s - path + 1)) : std::string();
}

bool is_regular_file(const std::string &p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0 && (st.st_mode & S_IFMT) == S_IFREG && st.st_size > 0;
}

/* base + rel and every folder between, created where missing; 0 or errno. */
int make_folders(const std::string &base, const std::string &rel) {
    for (size_t i = 0; i <= rel.size(); ++i) {
        if (i < rel.size() && rel[i] != '/') continue;
        const std::string d = base + rel.substr(0, i);
        struct stat st;
        if (stat(d.c_str(), &st) == 0 && (st.st_mode & S_IFMT) == S_IFDIR) continue;
#ifdef _WIN32
        int r = _mkdir(d.c_str());
#else
        int r = mkdir(d.c_str(), 0777);
#endif
        if (r != 0 && errno != EEXIST) return errno;
    }
    return 0;
}

/* bytes as the whole file path, by rename; synced with opt->sync. */
int write_png_file(const std::string &path, const std::vector<unsigned char> &bytes, bool sync) {
    atomic_file af;
    int e = atomic_open(&af, path.c_str());
    if (e) return e;
    af.sync = sync ? 1 : 0;
    errno = 0;
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), af.f) != bytes.size()) {
        e = errno ? errno : EIO;
        atomic_abort(&af);
        return e;
    }
    return atomic_commit(&af);
}


/* One banyan mesh to write: a node's own mesh or one of its levels of
 * detail, with its plan. */
struct Job {
    const banyan_mesh *m;
    std::string name;
    Layout L;
    std::vector<Prim> prims;
    bool local = false;
    bool tangents = false;
    bool tangent_ranges = false; /* each primitive's tangents from its own triangles (tangent_ranges_exact) */
    int material_base = 0;
    std::vector<int> image_texture; /* per m->images: the glTF texture of its PNG, -1 unused */
};

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

/* Bytes of the instancing accessors: TRANSLATION, ROTATION, SCALE. */
uint64_t instance_bytes(const banyan_mesh *m) { return (3 + 4 + 3) * 4ull * m->instance_count; }

const uint32_t kMaxNodes = 65536;
const uint32_t kMaxLods = 7;

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

/* The screen coverage below which level k + 1 replaces level k (MSFT_lod's
 * "MSFT_screencoverage", one value per level, the primary first). */
double lod_coverage(const banyan_gltf_node &n, uint32_t k) {
    return n.lod_coverage ? n.lod_coverage[k] : 0.5 / std::ldexp(1.0, static_cast<int>(k));
}

/* Writes a job's materials, mesh(es) and node(s); returns the node that
 * stands for it (the one the scene or MSFT_lod lists). Without instances:
 * one mesh on one node. With instances: one mesh per variant that has
 * instances, each on a child node carrying EXT_mesh_gpu_instancing, under
 * a node that holds the mesh's origin. */
int emit_job(Builder &b, const Job &J, const int slot[2 * BANYAN_TEX_COUNT], bool &instanced) {
    tinygltf::Model &model = b.model;
    const banyan_mesh *m = J.m;
    for (uint32_t k = 0; k < m->material_count; ++k) {
        const banyan_material *bm = &m->materials[k];
        tinygltf::Material mat;
        mat.name.assign(bm->name, name_len(bm->name, BANYAN_NAME_MAX));
        int image_tex = m->image_count > 0 && bm->image >= 0 ? J.image_texture[static_cast<size_t>(bm->image)] : -1;
        int key = image_tex < 0 && !(m->image_count > 0 && bm->image >= 0) ? texture_key(m, bm) : -1;
        int tex = key >= 0 ? slot[key] : -1;
        if (image_tex >= 0) { /* the image carries the colour; it has no normal map */
            mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, short_double(bm->base_color[3])};
            mat.pbrMetallicRoughness.baseColorTexture.index = image_tex;
        } else if (tex >= 0) { /* the texture carries the colour */
            mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, short_double(bm->base_color[3])};
            mat.pbrMetallicRoughness.baseColorTexture.index = 2 * tex;
            mat.normalTexture.index = 2 * tex + 1;
        } else {
            mat.pbrMetallicRoughness.baseColorFactor = {
                short_double(bm->base_color[0]), short_double(bm->base_color[1]),
                short_double(bm->base_color[2]), short_double(bm->base_color[3])};
        }
        mat.pbrMetallicRoughness.metallicFactor = 0.0;
        mat.pbrMetallicRoughness.roughnessFactor = short_double(bm->roughness);
        mat.doubleSided = bm->double_sided != 0;
        if (bm->alpha_cutoff > 0.0f) {
            mat.alphaMode = "MASK"; /* alpha-tested: no sorting, unlike BLEND */
            mat.alphaCutoff = short_double(bm->alpha_cutoff);
        } else if (bm->base_color[3] < 1.0f) {
            mat.alphaMode = "BLEND";
        }
        model.materials.push_back(mat);
    }

    std::map<std::string, int> shared;
    bool colors = !colors_repeat_material(m);
    Segment tan{kTangent};
    tan.whole = !J.tangent_ranges;
    const Segment *tp = J.tangents ? &tan : nullptr;
    if (!J.local) shared = add_vertex_range(b, m, J.L, 0, m->vertex_count, colors, tp);
    auto add_prim = [&](const Prim &pr, tinygltf::Mesh &gm) {
        tinygltf::Primitive prim;
        tan.ioff = pr.ioff;
        tan.icount = pr.icount;
        prim.attributes = J.local ? add_vertex_range(b, m, J.L, pr.vbase, pr.vcount, colors, tp) : shared;
        Segment ix{kIndices};
        ix.m = m;
        ix.base = pr.ioff;
        ix.count = pr.icount;
        ix.aux = pr.vbase;
        ix.bytes = 4ull * pr.icount;
        int v = b.add_view(ix, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        prim.indices = b.add_accessor(v, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, pr.icount);
        prim.material = pr.material;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        gm.primitives.push_back(prim);
    };

    tinygltf::Node node;
    node.name = J.name;
    if (m->origin[0] != 0 || m->origin[1] != 0 || m->origin[2] != 0) /* the local origin, Y up, in double */
        node.translation = {m->origin[0], m->origin[2], -m->origin[1]};
    if (m->instance_count == 0) {
        tinygltf::Mesh gm;
        gm.name = J.name;
        for (const Prim &pr : J.prims) add_prim(pr, gm);
        model.meshes.push_back(gm);
        node.mesh = static_cast<int>(model.meshes.size() - 1);
        model.nodes.push_back(node);
        return static_cast<int>(model.nodes.size() - 1);
    }

    /* Instanced: the parent first, its variant children after it. */
    instanced = true;
    model.nodes.push_back(node);
    const int parent = static_cast<int>(model.nodes.size() - 1);
    std::vector<uint32_t> variants = drawn_groups(m);
    std::vector<int> children;
    for (uint32_t g : variants) {
        std::vector<float> T, R, S;
        for (uint32_t k = 0; k < m->instance_count; ++k) {
            const banyan_instance *in = &m->instances[k];
            if (in->variant != g) continue;
            /* Z up -> Y up turns +Z into +Y: a turn about +Z stays a turn
             * of the same angle about +Y. */
            double h = 0.5 * static_cast<double>(in->rotation_z);
            T.insert(T.end(), {in->translation[0], in->translation[2], -in->translation[1]});
            R.insert(R.end(), {0.0f, static_cast<float>(dm_sin(h)), 0.0f, static_cast<float>(dm_cos(h))});
            S.insert(S.end(), {in->scale, in->scale, in->scale});
        }
        if (T.empty()) continue; /* a variant no instance shows */
        tinygltf::Mesh gm;
        gm.name = J.name + "_variant_" + std::to_string(g);
        for (const Prim &pr : J.prims)
            if (pr.group == g) add_prim(pr, gm);
        model.meshes.push_back(gm);
        const size_t n = T.size() / 3;
        tinygltf::Value::Object attrs;
        int v = b.add_floats(std::move(T), 0);
        attrs["TRANSLATION"] = tinygltf::Value(b.add_accessor(v, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n));
        v = b.add_floats(std::move(R), 0);
        attrs["ROTATION"] = tinygltf::Value(b.add_accessor(v, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, n));
        v = b.add_floats(std::move(S), 0);
        attrs["SCALE"] = tinygltf::Value(b.add_accessor(v, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n));
        tinygltf::Value::Object ext;
        ext["attributes"] = tinygltf::Value(attrs);
        tinygltf::Node child;
        child.name = gm.name;
        child.mesh = static_cast<int>(model.meshes.size() - 1);
        child.extensions["EXT_mesh_gpu_instancing"] = tinygltf::Value(ext);
        model.nodes.push_back(child);
        children.push_back(static_cast<int>(model.nodes.size() - 1));
    }
    model.nodes[static_cast<size_t>(parent)].children = children;
    return parent;
}

void put_u32(std::string &s, uint32_t v) {
    for (int k = 0; k < 4; ++k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
}

uint32_t get_u32(const std::string &s, size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(s[at + static_cast<size_t>(k)]);
    return v;
}

/* Sets buffer 0's "byteLength": 0 after `key` to n; false if not found
 * where expected. `at` gets where the digit was. */
bool patch_byte_length(std::string &json, const std::string &key, const std::string &field, uint64_t n,
                       size_t &at) {
    size_t k = json.find(key);
    if (k == std::string::npos || json.find(key, k + 1) != std::string::npos) return false;
    size_t f = json.find(field, k + key.size());
    if (f == std::string::npos || f != json.find_first_of('"', k + key.size())) return false;
    at = f + field.size();
    if (json.compare(at, 1, "0") != 0 || (at + 1 < json.size() && json[at + 1] >= '0' && json[at + 1] <= '9'))
        return false;
    json.replace(at, 1, std::to_string(n));
    return true;
}

/* tinygltf's document for an empty buffer 0 into what goes before and after
 * the buffer's `total` bytes: a .glb's header, JSON chunk and BIN chunk
 * header, then the BIN padding; a .gltf's JSON up to the base64 of the data
 * URI, then the rest. The same bytes tinygltf writes with the buffer held,
 * but for json_chunk (a .glb): the JSON chunk padded with spaces to that
 * length, the head's size fixed before the JSON is known. */
bool split_document(const std::string &doc, bool binary, uint64_t total, std::string &head, std::string &tail,
                    size_t json_chunk = 0) {
    if (binary) {
        if (doc.size() < 20 || doc.compare(0, 4, "glTF") != 0 || get_u32(doc, 16) != 0x4E4F534Au) return false;
        uint32_t chunk = get_u32(doc, 12);
        if (20 + static_cast<uint64_t>(chunk) != doc.size()) return false; /* no BIN chunk: the buffer was empty */
        std::string json = doc.substr(20, chunk);
        while (!json.empty() && json.back() == ' ') json.pop_back(); /* tinygltf's padding */
        size_t at = 0;
        if (!patch_byte_length(json, "\"buffers\":[{", "\"byteLength\":", total, at)) return false;
        if (json_chunk) { /* a JSON chunk of this many bytes (a multiple of 4): spaces after the JSON */
            if (json.size() > json_chunk || json_chunk % 4) return false;
            json.append(json_chunk - json.size(), ' ');
        }
        const uint64_t jpad = (4 - json.size() % 4) % 4, bpad = (4 - total % 4) % 4;
        const uint64_t length = 12 + 8 + json.size() + jpad + 8 + total + bpad;
        if (length > 0xFFFFFFFFu) return false;
        head.assign("glTF");
        put_u32(head, 2);
        put_u32(head, static_cast<uint32_t>(length));
        put_u32(head, static_cast<uint32_t>(json.size() + jpad));
        put_u32(head, 0x4E4F534Au); /* JSON */
        head += json;
        head.append(static_cast<size_t>(jpad), ' ');
        put_u32(head, static_cast<uint32_t>(total + bpad));
        put_u32(head, 0x004E4942u); /* BIN */
        tail.assign(static_cast<size_t>(bpad), '\0');
        return true;
    }
    std::string json = doc;
    size_t at = 0;
    if (!patch_byte_length(json, "\"buffers\": [", "\"byteLength\": ", total, at)) return false;
    const std::string uri = "\"uri\": \"data:application/octet-stream;base64,\"";
    size_t u = json.find(uri, at);
    if (u == std::string::npos || json.find_first_of("{}", at) < u) return false;
    size_t split = u + uri.size() - 1; /* before the closing quote */
    head = json.substr(0, split);
    tail = json.substr(split);
    return true;
}

/* The most bytes a texture's PNG at `size` pixels a side can take: 4
 * channels and a filter byte a row, stored uncompressed (deflate's worst
 * case: zlib's compressBound), and the PNG's chunks. */
uint64_t png_bound(int32_t size) {
    const uint64_t raw = static_cast<uint64_t>(size) * (4 * static_cast<uint64_t>(size) + 1);
    return raw + (raw >> 12) + (raw >> 14) + (raw >> 25) + 13 + 1024;
}

banyan_status write_nodes_impl(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                               const banyan_gltf_options *opt, const banyan_budget *budget, bool ex,
                               banyan_error *err) {
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    if (opt) o = *opt;
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
    banyan_status checked = check_options(o, err);
    if (checked != BANYAN_OK) return checked;
    if (count == 0) return banyan_fail(err, BANYAN_E_INVALID_ARG, "count is 0; nothing to write");
    if (!ex && count > kMaxNodes)
        return banyan_fail(err, BANYAN_E_RANGE, "count = %u is outside [1, %u]", count, kMaxNodes);
    if (nodes == nullptr)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, ex ? "meshes is NULL but count = %u" : "nodes is NULL but count = %u",
                           count);
    for (uint32_t i = 0; i < count; ++i) {
        banyan_status s = check_node(nodes[i], i, ex, err);
        if (s != BANYAN_OK) return s;
    }
    if (o.compact) { /* the plain .glb, rewritten compact (gltf_compact.cpp) */
        banyan_gltf_options plain = o;
        plain.compact = 0;
        plain.sync = 0;
        return gltf_compact_write(path, binary, o.sync != 0, o.engine_uvs != 0, [&](const char *tmp) {
            return write_nodes_impl(tmp, nodes, count, &plain, budget, ex, err);
        }, err);
    }
    /* The budget: the textures' memory refused up front from their size,
     * time checked between meshes, while streaming and inside the texture
     * painters and PNG encoders (on the drawing threads, by deadline). */
    prog g;
    if (banyan_status sb = prog_budget_from(&g, budget, err)) return sb;
    const prog_deadline deadline = prog_deadline_of(&g);
    auto over = [&] {
        if (g.cancelled == PROG_RUNNING) { /* the streaming thread saw the deadline first */
            g.cancelled = PROG_OVER_TIME;
            g.over_value = prog_now() - g.t_start;
        }
        return prog_fail(&g, err, "writing glTF");
    };

    /* Every mesh to write, in order: each node's own, then its levels. */
    std::vector<Job> jobs;
    std::vector<const banyan_mesh *> all;
    for (uint32_t i = 0; i < count; ++i) {
        std::string name = nodes[i].name ? std::string(nodes[i].name) : "banyan_" + std::to_string(i);
        for (uint32_t k = 0; k <= nodes[i].lod_count; ++k) {
            Job J;
            J.m = k == 0 ? nodes[i].mesh : nodes[i].lods[k - 1];
            J.name = k == 0 ? name : name + "_lod" + std::to_string(k);
            J.L = layout_of(J.m, o.engine_uvs != 0);
            jobs.push_back(std::move(J));
            all.push_back(jobs.back().m);
        }
    }

    std::vector<TexturePngs> textures;
    int slot[2 * BANYAN_TEX_COUNT];
    plan_textures(all.data(), static_cast<uint32_t>(all.size()), o, textures, slot);
    /* opt->image_dir: the textures as files beside the asset, drawn only
     * where a file is missing; their images carry a URI, not a view. */
    const bool external = o.image_dir != nullptr && o.image_dir[0] != '\0';
    const std::string image_folder = external ? folder_of(path) : std::string();
    std::vector<std::string> image_uri; /* per texture image (2 t, 2 t + 1) */
    if (external) {
        for (TexturePngs &t : textures) {
            std::string name = kKindNames[t.kind];
            if (is_leaf_kind(t.kind)) name += t.season == BANYAN_SEASON_AUTUMN ? "_autumn" : "_summer";
            const std::string tail = "-" + std::to_string(o.texture_size) + "-s" + std::to_string(o.texture_seed) + ".png";
            image_uri.push_back(std::string(o.image_dir) + "/" + name + tail);
            image_uri.push_back(std::string(o.image_dir) + "/" + name + "_normal" + tail);
            t.have = is_regular_file(image_folder + image_uri[image_uri.size() - 2]) &&
                     is_regular_file(image_folder + image_uri.back());
        }
    }
    const size_t tex_views = external ? 0 : 2 * textures.size(); /* the textures' images in the buffer */
    /* The meshes' own images (a billboard's picture), one PNG each that a
     * material names; with textures off, materials are drawn flat. */
    std::vector<std::vector<unsigned char>> pictures;
    const int picture_base = 2 * static_cast<int>(textures.size());
    for (Job &J : jobs) {
        J.image_texture.assign(J.m->image_count, -1);
        for (uint32_t k = 0; o.textures && J.m->image_count > 0 && k < J.m->material_count; ++k) {
            int32_t im = J.m->materials[k].image;
            if (im < 0 || J.image_texture[static_cast<size_t>(im)] >= 0) continue;
            ImageGuard ig;
            size_t size = 0;
            banyan_status s = tex_png(&J.m->images[im], &deadline, g.max_seconds, &ig.png, &size, err);
            if (s != BANYAN_OK) return s;
            pictures.emplace_back(ig.png, ig.png + size);
            J.image_texture[static_cast<size_t>(im)] = picture_base + static_cast<int>(pictures.size() - 1);
        }
    }
    /* A mesh with a library-textured material gets tangents for its normal map. */
    for (Job &J : jobs)
        for (uint32_t k = 0; k < J.m->material_count; ++k) {
            const banyan_material *bm = &J.m->materials[k];
            if (J.m->image_count > 0 && bm->image >= 0) continue;
            int key = texture_key(J.m, bm);
            if (key >= 0 && slot[key] >= 0) J.tangents = true;
        }

    /* Plan, so the buffer is allocated once and its size checked first. */
    uint64_t total = 0;
    int material_base = 0;
    for (Job &J : jobs) {
        J.material_base = material_base;
        total += plan_mesh(J.m, J.L, material_base, J.tangents, J.prims, J.local);
        J.tangent_ranges = J.tangents && tangent_ranges_exact(J.m, J.prims, J.local);
        total += instance_bytes(J.m);
        material_base += static_cast<int>(J.m->material_count);
    }
    for (const auto &p : pictures) total += pad4(p.size());
    auto too_big = [&] {
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the glTF buffer would hold %llu bytes; the limit is %llu (4 GiB less the "
                           "JSON)",
                           static_cast<unsigned long long>(total), static_cast<unsigned long long>(kMaxBufferBytes));
    };
    if (total > kMaxBufferBytes) return too_big(); /* before the textures are drawn */
    size_t to_draw = 0;
    for (const TexturePngs &t : textures) to_draw += !t.have;
    if (to_draw > 0) {
        const size_t at_once = std::min(to_draw, TextureDrawer::kThreads);
        if (prog_reserve(&g, static_cast<double>(at_once) * static_cast<double>(tex_peak_bytes(o.texture_size, 1))))
            return banyan_fail(err, BANYAN_E_LIMIT,
                               "drawing %u texture%s of %d pixels (%u at once) needs %.0f MB, past max_memory_mb = "
                               "%g (%.0f .. %.0f); lower the texture size (a power of two, 64 .. 8192), turn the "
                               "textures off or raise max_memory_mb",
                               static_cast<unsigned>(to_draw), to_draw == 1 ? "" : "s",
                               static_cast<int>(o.texture_size), static_cast<unsigned>(at_once), g.over_value,
                               g.max_mb, PROG_MAX_MEMORY_MIN, PROG_MAX_MEMORY_MAX);
    }
    if (prog_at(&g, 0.0)) return over();
    TextureDrawer drawer(o, deadline, g.max_seconds, textures);

    Builder b;
    tinygltf::Model &model = b.model;
    model.asset.version = "2.0";
    model.asset.generator = "banyan";

    /* Images, samplers and textures first (their bytes go at the end of
     * the buffer): sampler 0 repeats (bark), sampler 1 clamps (atlases,
     * pictures). */
    int sampler[2] = {-1, -1};
    auto sampler_for = [&](bool clamp) {
        if (sampler[clamp] < 0) {
            tinygltf::Sampler sm;
            sm.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
            sm.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
            sm.wrapS = sm.wrapT = clamp ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE : TINYGLTF_TEXTURE_WRAP_REPEAT;
            model.samplers.push_back(sm);
            sampler[clamp] = static_cast<int>(model.samplers.size() - 1);
        }
        return sampler[clamp];
    };
    auto add_texture = [&](const std::string &name, int smp) {
        tinygltf::Image im;
        im.name = name;
        im.mimeType = "image/png";
        model.images.push_back(im); /* bufferView set below */
        tinygltf::Texture tx;
        tx.name = im.name;
        tx.sampler = smp;
        tx.source = static_cast<int>(model.images.size() - 1);
        model.textures.push_back(tx);
    };
    for (size_t t = 0; t < textures.size(); ++t) {
        const TexturePngs &tp = textures[t];
        bool atlas = is_leaf_kind(tp.kind);
        int smp = sampler_for(atlas);
        std::string name = kKindNames[tp.kind];
        if (atlas) name += tp.season == BANYAN_SEASON_AUTUMN ? "_autumn" : "_summer";
        add_texture(name, smp);
        add_texture(name + "_normal", smp);
        if (external) {
            model.images[model.images.size() - 2].uri = image_uri[2 * t];
            model.images.back().uri = image_uri[2 * t + 1];
        }
    }
    for (const Job &J : jobs)
        for (size_t k = 0; k < J.image_texture.size(); ++k)
            if (J.image_texture[k] >= 0) add_texture(J.name + "_image_" + std::to_string(k), sampler_for(true));

    tinygltf::Scene scene;
    bool any_lod = false, any_instanced = false;
    size_t j = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const banyan_gltf_node &n = nodes[i];
        if (prog_at(&g, 0.5 * i / count)) return over();
        int primary = emit_job(b, jobs[j++], slot, any_instanced);
        if (n.lod_count > 0) {
            /* MSFT_lod: the coarser levels are nodes outside the scene's
             * roots, listed finest first on the primary node. */
            tinygltf::Value::Array ids, coverage;
            for (uint32_t k = 0; k < n.lod_count; ++k) ids.push_back(tinygltf::Value(emit_job(b, jobs[j++], slot, any_instanced)));
            for (uint32_t k = 0; k <= n.lod_count; ++k) coverage.push_back(tinygltf::Value(lod_coverage(n, k)));
            tinygltf::Value::Object ext, extras;
            ext["ids"] = tinygltf::Value(ids);
            extras["MSFT_screencoverage"] = tinygltf::Value(coverage);
            tinygltf::Node &pn = model.nodes[static_cast<size_t>(primary)];
            pn.extensions["MSFT_lod"] = tinygltf::Value(ext);
            pn.extras = tinygltf::Value(extras);
            any_lod = true;
        }
        scene.nodes.push_back(primary);
    }
    /* Used, not required: a viewer without them shows the finest level,
     * and each variant once at the node's origin (docs/gltf.md). */
    if (any_instanced) model.extensionsUsed.push_back("EXT_mesh_gpu_instancing");
    if (any_lod) model.extensionsUsed.push_back("MSFT_lod");
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    /* A .glb with textures need not wait for them: its JSON (before the
     * BIN chunk) is written first for PNGs of the largest size they can
     * have, which fixes the head's size, the meshes' bytes are streamed
     * while the textures are drawn, and at the end the real JSON, padded
     * with spaces to the same size, is written over the start. Not for a
     * .gltf (its data URI sits inside the JSON) or a target written in
     * place (a FIFO cannot be rewound). */
    const size_t image_views = tex_views + pictures.size();
    const uint64_t bound = png_bound(o.texture_size);
    uint64_t widest = b.size + tex_views * pad4(bound);
    for (const auto &p : pictures) widest += pad4(p.size());
    const bool defer = binary && tex_views > 0 && widest <= kMaxBufferBytes;
    OutFile out;
    if (defer) {
        if (int oe = out.open(path, o.sync != 0))
            return banyan_fail(err, BANYAN_E_IO, "cannot open '%s' for writing: %s", path, std::strerror(oe));
    }
    std::string head, tail; /* what goes before and after the buffer's bytes */
    size_t json_chunk = 0;   /* deferred: the JSON chunk's bytes, fixed by the widest JSON */
    /* The JSON with an empty buffer, then its byteLength set to the
     * planned size: tinygltf writes everything but the bytes. */
    auto serialize = [&](uint64_t bytes) -> banyan_status {
        model.buffers.assign(1, tinygltf::Buffer());
        std::ostringstream js;
        tinygltf::TinyGLTF writer;
        writer.SetImageWriter(nullptr, nullptr); /* an image's uri is written as it is */
        if (!writer.WriteGltfSceneToStream(&model, js, /*prettyPrint=*/true, binary))
            return banyan_fail(err, BANYAN_E_INTERNAL, "the glTF serialiser failed for '%s'", path);
        if (!split_document(js.str(), binary, bytes, head, tail, json_chunk))
            return banyan_fail(err, BANYAN_E_INTERNAL,
                               "unexpected glTF JSON from tinygltf for '%s'; please report this", path);
        return BANYAN_OK;
    };
    std::vector<int> views; /* the images' bufferViews, in image order */
    auto image_of = [&](size_t k) { /* textures' images first, then the pictures' */
        return k < tex_views ? k : static_cast<size_t>(picture_base) + (k - tex_views);
    };
    if (defer) {
        uint64_t at = b.size;
        for (size_t k = 0; k < image_views; ++k) {
            uint64_t len = k < tex_views ? bound : pictures[k - tex_views].size();
            views.push_back(b.add_image_placeholder(at, len));
            model.images[image_of(k)].bufferView = views.back();
            at = pad4(at + len);
        }
        if (banyan_status sj = serialize(widest)) return sj;
        json_chunk = head.size() - 28; /* the glb header, the JSON chunk's header, the BIN chunk's */
    }
    const size_t mesh_segs = b.segs.size();
    Sink raw(defer ? out.get() : nullptr, false);
    Sink bin(defer ? out.get() : nullptr, !binary);
    bool late = false; /* the producer passed the deadline (one thread writes it, read after its join) */
    auto stream = [&](size_t from) {
        Pipe pipe(bin, out);
        pipe.run([&b, from, &deadline, &late](Pipe &p) {
            BinWriter bw(p);
            for (size_t k = from, n = b.segs.size(); k < n; ++k) {
                if (p.failed()) break;
                if (prog_deadline_passed(&deadline)) {
                    late = true;
                    break;
                }
                bw.write(b.segs[k]);
            }
        });
    };
    if (defer) {
        raw.put(head.data(), head.size()); /* for now: rewritten at the end */
        stream(0);
    }

    banyan_status drawn = drawer.wait(err);
    if (drawn != BANYAN_OK) return drawn;
    if (prog_at(&g, 0.75) || late) return over();
    if (external) {
        /* The missing files, before the asset that names them. */
        if (int fe = make_folders(image_folder, o.image_dir))
            return banyan_fail(err, BANYAN_E_IO, "cannot create the image folder '%s%s': %s", image_folder.c_str(),
                               o.image_dir, std::strerror(fe));
        for (size_t t = 0; t < textures.size(); ++t) {
            if (textures[t].have) continue;
            for (size_t m = 0; m < 2; ++m) {
                const std::string f = image_folder + image_uri[2 * t + m];
                if (int fe = write_png_file(f, m ? textures[t].normal : textures[t].base, o.sync != 0))
                    return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", f.c_str(), std::strerror(fe));
            }
        }
    } else {
        for (const TexturePngs &t : textures) total += pad4(t.base.size()) + pad4(t.normal.size());
    }
    if (total > kMaxBufferBytes) return too_big();
    for (size_t k = 0; k < image_views; ++k) {
        const std::vector<unsigned char> &bytes = k < tex_views
                                                      ? (k % 2 ? textures[k / 2].normal : textures[k / 2].base)
                                                      : pictures[k - tex_views];
        if (defer && bytes.size() > bound && k < tex_views)
            return banyan_fail(err, BANYAN_E_INTERNAL, "a %llu-byte PNG is over its bound %llu; please report this",
                               static_cast<unsigned long long>(bytes.size()),
                               static_cast<unsigned long long>(bound));
        model.images[image_of(k)].bufferView = defer ? b.fill_image_view(views[k], bytes) : b.add_image_view(bytes);
    }

    if (b.size != total)
        return banyan_fail(err, BANYAN_E_INTERNAL,
                    "glTF buffer holds %llu bytes, planned %llu; please report this",
                    static_cast<unsigned long long>(b.size), static_cast<unsigned long long>(total));
    const size_t widest_head = head.size();
    if (banyan_status sj = serialize(total)) return sj;
    if (defer && head.size() != widest_head)
        return banyan_fail(err, BANYAN_E_INTERNAL, "the glTF head grew from %llu to %llu bytes; please report this",
                           static_cast<unsigned long long>(widest_head), static_cast<unsigned long long>(head.size()));
    if (!defer) {
        if (int oe = out.open(path, o.sync != 0))
            return banyan_fail(err, BANYAN_E_IO, "cannot open '%s' for writing: %s", path, std::strerror(oe));
        raw.reset(out.get());
        bin.reset(out.get());
        raw.put(head.data(), head.size());
    }
    stream(defer ? mesh_segs : 0);
    if (prog_at(&g, 0.99) || late) return over();
    bin.finish();
    if (!bin.error() && bin.count() != total)
        return banyan_fail(err, BANYAN_E_INTERNAL, "wrote %llu buffer bytes, planned %llu; please report this",
                           static_cast<unsigned long long>(bin.count()), static_cast<unsigned long long>(total));
    raw.put(tail.data(), tail.size());
    int e = raw.error() ? raw.error() : bin.error();
    if (e == 0 && defer) e = out.rewrite_start(head.data(), head.size());
    if (e != 0) return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", path, std::strerror(e));
    e = out.commit();
    if (e != 0) return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", path, std::strerror(e));
    return BANYAN_OK;
}

/* The C calls' wrapper: no exception leaves the library. */
template <class F> banyan_status guarded(const char *path, banyan_error *err, F f) {
    try {
        return f();
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

} // namespace

extern "C" BANYAN_API void banyan_gltf_options_init(banyan_gltf_options *opt) {
    if (opt == nullptr) return;
    std::memset(opt, 0, sizeof *opt);
    opt->textures = 1;
    opt->texture_size = 1024;
    opt->texture_seed = 1;
    opt->engine_uvs = 0;
    opt->sync = 0;
    opt->image_dir = nullptr;
    opt->compact = 0;
    opt->texture_cache = 1;
    opt->texture_cache_dir = nullptr;
}

extern "C" BANYAN_API size_t banyan_sizeof_gltf_options(void) { return sizeof(banyan_gltf_options); }

extern "C" BANYAN_API size_t banyan_sizeof_gltf_node(void) { return sizeof(banyan_gltf_node); }

extern "C" BANYAN_API banyan_status banyan_gltf_write_nodes(const char *path, const banyan_gltf_node *nodes,
                                                            uint32_t count, const banyan_gltf_options *opt,
                                                            banyan_error *err) {
    return banyan_gltf_write_nodes_budget(path, nodes, count, opt, nullptr, err);
}

extern "C" BANYAN_API banyan_status banyan_gltf_write_nodes_budget(const char *path, const banyan_gltf_node *nodes,
                                                                   uint32_t count, const banyan_gltf_options *opt,
                                                                   const banyan_budget *budget, banyan_error *err) {
    return guarded(path, err, [&] { return write_nodes_impl(path, nodes, count, opt, budget, false, err); });
}

extern "C" BANYAN_API banyan_status banyan_gltf_write(const char *path,
                                                      const banyan_mesh *const *meshes,
                                                      const char *const *names, uint32_t count,
                                                      banyan_error *err) {
    return banyan_gltf_write_ex(path, meshes, names, count, nullptr, err);
}

/* One node per mesh, no levels of detail: banyan_gltf_write_nodes. */
extern "C" BANYAN_API banyan_status banyan_gltf_write_ex(const char *path,
                                                         const banyan_mesh *const *meshes,
                                                         const char *const *names, uint32_t count,
                                                         const banyan_gltf_options *opt, banyan_error *err) {
    return banyan_gltf_write_ex_budget(path, meshes, names, count, opt, nullptr, err);
}

extern "C" BANYAN_API banyan_status banyan_gltf_write_ex_budget(const char *path, const banyan_mesh *const *meshes,
                                                                const char *const *names, uint32_t count,
                                                                const banyan_gltf_options *opt,
                                                                const banyan_budget *budget, banyan_error *err) {
    return guarded(path, err, [&] {
        std::vector<banyan_gltf_node> nodes;
        if (meshes != nullptr) {
            nodes.resize(count);
            for (uint32_t i = 0; i < count; ++i)
                nodes[i] = banyan_gltf_node{meshes[i], names ? names[i] : nullptr, 0, nullptr, nullptr};
        }
        return write_nodes_impl(path, meshes ? nodes.data() : nullptr, count, opt, budget, true, err);
    });
}
