/* gltf_compact.cpp - the compact form of a glTF asset banyan wrote
 * (banyan_gltf_options.compact, docs/gltf.md "Compact files").
 *
 * The writer makes the plain .glb first (a temporary file); this file reads
 * it back and rewrites every mesh accessor:
 *   - POSITION: UNSIGNED_SHORT in a per-node frame (KHR_mesh_quantization),
 *     the node's translation and uniform scale turning it back into metres;
 *   - the wind pivots (_WIND_PIVOT_X/_Y/_Z, and the pivot parts of the
 *     engine uv sets) in that same frame, so position - pivot stays the
 *     arm, in the node's units;
 *   - NORMAL and TANGENT: 8-bit octahedral (the OCTAHEDRAL filter);
 *   - TEXCOORD_0: floats with 14 mantissa bits;
 *   - everything else (the other `_` attributes, colours, instances): as it is;
 * then compresses each accessor's data with meshoptimizer's vertex or index
 * codec (EXT_meshopt_compression). Images stay as they are. Both
 * extensions are required: the fallback buffer holds no bytes.
 *
 * A node group (a scene node and its MSFT_lod levels) gets a frame only
 * when none of its nodes is instanced (EXT_mesh_gpu_instancing applies the
 * node's transform after the instance's), rotated, scaled or a parent, and
 * each of their meshes is used by that node alone; the others keep float
 * positions and pivots (compressed all the same). */
#include "gltf/gltf_compact.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <cjson/cJSON.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

const int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;
const int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
const int kUvMantissa = 14; /* TEXCOORD_0: 2^-14 relative, a 16th of a texel at u = 4 on a 1024 image */

uint64_t pad4(uint64_t n) { return (n + 3) & ~UINT64_C(3); }

struct JsonDoc {
    cJSON *p = nullptr;
    ~JsonDoc() { cJSON_Delete(p); }
};

cJSON *item(const cJSON *o, const char *k) { return o ? cJSON_GetObjectItemCaseSensitive(o, k) : nullptr; }
double num(const cJSON *o, const char *k, double def) {
    const cJSON *v = item(o, k);
    return cJSON_IsNumber(v) ? v->valuedouble : def;
}
int inum(const cJSON *o, const char *k, int def) { return static_cast<int>(num(o, k, def)); }
void set_num(cJSON *o, const char *k, double v) {
    cJSON_DeleteItemFromObjectCaseSensitive(o, k);
    cJSON_AddNumberToObject(o, k, v);
}

uint32_t component_bytes(int ct) {
    switch (ct) {
    case kByte:
    case kUByte: return 1;
    case kShort:
    case kUShort: return 2;
    case kUInt:
    case kFloat: return 4;
    default: return 0;
    }
}
uint32_t type_width(const char *t) {
    if (!t) return 0;
    if (!std::strcmp(t, "SCALAR")) return 1;
    if (!std::strcmp(t, "VEC2")) return 2;
    if (!std::strcmp(t, "VEC3")) return 3;
    if (!std::strcmp(t, "VEC4")) return 4;
    if (!std::strcmp(t, "MAT4")) return 16;
    return 0;
}

/* One accessor's data in the plain file's BIN chunk. */
struct Acc {
    const unsigned char *base = nullptr;
    uint32_t count = 0, width = 0, ct = 0, elem = 0, stride = 0;
    float f(uint32_t i, uint32_t c) const {
        float v;
        std::memcpy(&v, base + static_cast<size_t>(i) * stride + 4u * c, 4);
        return v;
    }
    uint32_t u(uint32_t i) const {
        const unsigned char *p = base + static_cast<size_t>(i) * stride;
        if (ct == kUInt) {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        if (ct == kUShort) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        return *p;
    }
};

/* Each converted accessor's role. */
enum Role { kOther, kPosition, kNormal, kTangent, kUv0, kEngineUvXY, kEngineUvZ, kPivotX, kPivotY, kPivotZ, kIndices };

struct Frame {
    bool on = false;
    double lo[3] = {0, 0, 0};
    double s = 1; /* metres per step */
    double q(double v, int axis) const { return (v - lo[axis]) / s; }
};

/* A bufferView of the output: meshopt-compressed (`fallback` bytes once
 * decoded) or raw (an image). */
struct View {
    std::vector<unsigned char> bytes;
    bool compressed = false;
    uint32_t stride = 0, count = 0;
    const char *mode = "ATTRIBUTES", *filter = nullptr;
    int target = 0;
    cJSON *plain = nullptr; /* a raw view: the old view's JSON (copied) */
};

View encode_vertices(const std::vector<unsigned char> &data, uint32_t count, uint32_t stride, const char *filter) {
    View v;
    v.compressed = true;
    v.stride = stride;
    v.count = count;
    v.filter = filter;
    v.target = kArrayBuffer;
    v.bytes.resize(meshopt_encodeVertexBufferBound(count, stride));
    v.bytes.resize(meshopt_encodeVertexBuffer(v.bytes.data(), v.bytes.size(), data.data(), count, stride));
    return v;
}

void put16(std::vector<unsigned char> &d, size_t at, uint16_t v) { std::memcpy(&d[at], &v, 2); }

uint16_t quant16(double q) {
    double r = std::floor(q + 0.5);
    return static_cast<uint16_t>(r < 0 ? 0 : r > 65535 ? 65535 : r);
}

bool read_file(const char *path, std::vector<unsigned char> &out, int &e) {
    std::FILE *f = std::fopen(path, "rb");
    if (!f) {
        e = errno;
        return false;
    }
    unsigned char buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.insert(out.end(), buf, buf + n);
    e = std::ferror(f) ? EIO : 0;
    std::fclose(f);
    return e == 0;
}

std::string base64(const unsigned char *p, size_t n) {
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string s;
    s.reserve((n + 2) / 3 * 4);
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = static_cast<uint32_t>(p[i]) << 16;
        if (i + 1 < n) v |= static_cast<uint32_t>(p[i + 1]) << 8;
        if (i + 2 < n) v |= p[i + 2];
        s += t[(v >> 18) & 63];
        s += t[(v >> 12) & 63];
        s += i + 1 < n ? t[(v >> 6) & 63] : '=';
        s += i + 2 < n ? t[v & 63] : '=';
    }
    return s;
}

void add_required(cJSON *root, const char *list, const char *name) {
    cJSON *a = item(root, list);
    if (!cJSON_IsArray(a)) {
        cJSON_DeleteItemFromObjectCaseSensitive(root, list);
        a = cJSON_AddArrayToObject(root, list);
    }
    const cJSON *e;
    cJSON_ArrayForEach(e, a) if (cJSON_IsString(e) && !std::strcmp(e->valuestring, name)) return;
    cJSON_AddItemToArray(a, cJSON_CreateString(name));
}

class Compactor {
  public:
    Compactor(cJSON *root, const unsigned char *bin, uint64_t bin_len, bool engine_uvs)
        : root_(root), bin_(bin), bin_len_(bin_len), engine_uvs_(engine_uvs) {}

    /* false: the plain file is not what banyan's writer makes (why_ says what). */
    bool run() {
        accessors_ = item(root_, "accessors");
        views_ = item(root_, "bufferViews");
        const int n_acc = cJSON_GetArraySize(accessors_);
        role_.assign(static_cast<size_t>(n_acc), kOther);
        mesh_of_.assign(static_cast<size_t>(n_acc), -1);
        if (!assign_roles() || !make_frames()) return false;
        std::vector<int> new_view(static_cast<size_t>(n_acc), -1);
        for (int a = 0; a < n_acc; ++a)
            if (!convert(a)) return false;
        /* Images keep their bytes, in views of their own. */
        cJSON *img;
        cJSON_ArrayForEach(img, item(root_, "images")) {
            const cJSON *bv = item(img, "bufferView");
            if (!cJSON_IsNumber(bv)) continue;
            cJSON *old = cJSON_GetArrayItem(views_, bv->valueint);
            const uint64_t off = static_cast<uint64_t>(num(old, "byteOffset", 0)), len = static_cast<uint64_t>(num(old, "byteLength", 0));
            if (!old || off + len > bin_len_) return fail("an image's bufferView is outside the buffer");
            View v;
            v.bytes.assign(bin_ + off, bin_ + off + len);
            v.plain = cJSON_Duplicate(old, true);
            out_.push_back(std::move(v));
            set_num(img, "bufferView", static_cast<double>(out_.size() - 1));
        }
        for (size_t k = 0; k < frames_.size(); ++k) place_nodes(k);
        return true;
    }

    /* The JSON and the buffer of the compact asset. */
    void finish(std::vector<unsigned char> &buffer) {
        cJSON *views = cJSON_CreateArray();
        uint64_t fallback = 0;
        for (View &v : out_) {
            const uint64_t at = buffer.size();
            buffer.insert(buffer.end(), v.bytes.begin(), v.bytes.end());
            buffer.resize(pad4(buffer.size()), 0);
            cJSON *j;
            if (v.compressed) {
                j = cJSON_CreateObject();
                const uint64_t len = static_cast<uint64_t>(v.count) * v.stride;
                cJSON_AddNumberToObject(j, "buffer", 1);
                cJSON_AddNumberToObject(j, "byteOffset", static_cast<double>(fallback));
                cJSON_AddNumberToObject(j, "byteLength", static_cast<double>(len));
                if (v.target != kElementArrayBuffer) cJSON_AddNumberToObject(j, "byteStride", v.stride);
                if (v.target > 0) cJSON_AddNumberToObject(j, "target", v.target);
                cJSON *ext = cJSON_AddObjectToObject(cJSON_AddObjectToObject(j, "extensions"), "EXT_meshopt_compression");
                cJSON_AddNumberToObject(ext, "buffer", 0);
                cJSON_AddNumberToObject(ext, "byteOffset", static_cast<double>(at));
                cJSON_AddNumberToObject(ext, "byteLength", static_cast<double>(v.bytes.size()));
                cJSON_AddNumberToObject(ext, "byteStride", v.stride);
                cJSON_AddNumberToObject(ext, "count", v.count);
                cJSON_AddStringToObject(ext, "mode", v.mode);
                if (v.filter) cJSON_AddStringToObject(ext, "filter", v.filter);
                fallback += pad4(len);
            } else {
                j = v.plain;
                v.plain = nullptr;
                set_num(j, "buffer", 0);
                set_num(j, "byteOffset", static_cast<double>(at));
                set_num(j, "byteLength", static_cast<double>(v.bytes.size()));
            }
            cJSON_AddItemToArray(views, j);
            std::vector<unsigned char>().swap(v.bytes);
        }
        cJSON_ReplaceItemInObjectCaseSensitive(root_, "bufferViews", views);
        cJSON *buffers = cJSON_CreateArray();
        cJSON *b0 = cJSON_CreateObject();
        cJSON_AddNumberToObject(b0, "byteLength", static_cast<double>(buffer.size()));
        cJSON_AddItemToArray(buffers, b0);
        cJSON *b1 = cJSON_CreateObject();
        cJSON_AddNumberToObject(b1, "byteLength", static_cast<double>(fallback ? fallback : 4));
        cJSON_AddBoolToObject(cJSON_AddObjectToObject(cJSON_AddObjectToObject(b1, "extensions"),
                                                      "EXT_meshopt_compression"),
                              "fallback", 1);
        cJSON_AddItemToArray(buffers, b1);
        cJSON_ReplaceItemInObjectCaseSensitive(root_, "buffers", buffers);
        for (const char *list : {"extensionsUsed", "extensionsRequired"}) {
            add_required(root_, list, "EXT_meshopt_compression");
            add_required(root_, list, "KHR_mesh_quantization");
        }
    }

    ~Compactor() {
        for (View &v : out_) cJSON_Delete(v.plain);
    }

    const std::string &why() const { return why_; }

  private:
    bool fail(const char *what) {
        why_ = what;
        return false;
    }

    bool read_acc(int a, Acc &r) {
        const cJSON *j = cJSON_GetArrayItem(accessors_, a);
        if (item(j, "sparse")) return fail("a sparse accessor");
        const cJSON *bv = item(j, "bufferView");
        if (!cJSON_IsNumber(bv)) return fail("an accessor without a bufferView");
        const cJSON *v = cJSON_GetArrayItem(views_, bv->valueint);
        if (!v || inum(v, "buffer", 0) != 0) return fail("an accessor's bufferView is missing");
        r.ct = static_cast<uint32_t>(inum(j, "componentType", 0));
        r.width = type_width(cJSON_GetStringValue(item(j, "type")));
        r.count = static_cast<uint32_t>(num(j, "count", 0));
        r.elem = component_bytes(static_cast<int>(r.ct)) * r.width;
        r.stride = static_cast<uint32_t>(num(v, "byteStride", r.elem));
        const uint64_t off = static_cast<uint64_t>(num(v, "byteOffset", 0)) + static_cast<uint64_t>(num(j, "byteOffset", 0));
        const uint64_t len = static_cast<uint64_t>(num(v, "byteLength", 0));
        if (r.elem == 0 || r.count == 0 || r.stride < r.elem) return fail("an accessor of an unknown type");
        if (static_cast<uint64_t>(r.count - 1) * r.stride + r.elem > len || off + len > bin_len_ ||
            static_cast<uint64_t>(num(v, "byteOffset", 0)) + len > bin_len_)
            return fail("an accessor outside its bufferView");
        r.base = bin_ + off;
        return true;
    }

    bool assign_roles() {
        int m = 0;
        cJSON *mesh;
        cJSON_ArrayForEach(mesh, item(root_, "meshes")) {
            cJSON *prim;
            cJSON_ArrayForEach(prim, item(mesh, "primitives")) {
                const int mode = inum(prim, "mode", 4);
                cJSON *at;
                cJSON_ArrayForEach(at, item(prim, "attributes")) {
                    const char *k = at->string;
                    Role r = kOther;
                    if (!std::strcmp(k, "POSITION")) r = kPosition;
                    else if (!std::strcmp(k, "NORMAL")) r = kNormal;
                    else if (!std::strcmp(k, "TANGENT")) r = kTangent;
                    else if (!std::strcmp(k, "TEXCOORD_0")) r = kUv0;
                    else if (engine_uvs_ && !std::strcmp(k, "TEXCOORD_1")) r = kEngineUvXY;
                    else if (engine_uvs_ && !std::strcmp(k, "TEXCOORD_2")) r = kEngineUvZ;
                    else if (!std::strcmp(k, "_WIND_PIVOT_X")) r = kPivotX;
                    else if (!std::strcmp(k, "_WIND_PIVOT_Y")) r = kPivotY;
                    else if (!std::strcmp(k, "_WIND_PIVOT_Z")) r = kPivotZ;
                    if (!claim(at->valueint, r, m)) return false;
                }
                const cJSON *ix = item(prim, "indices");
                if (cJSON_IsNumber(ix)) {
                    if (!claim(ix->valueint, kIndices, m)) return false;
                    if (mode != 4) triangles_[ix->valueint] = false;
                }
            }
            ++m;
        }
        return true;
    }

    bool claim(int a, Role r, int mesh) {
        if (a < 0 || a >= static_cast<int>(role_.size())) return fail("a primitive names a missing accessor");
        if (mesh_of_[a] >= 0 && (mesh_of_[a] != mesh || role_[a] != r)) return fail("an accessor shared by two roles or meshes");
        role_[a] = r;
        mesh_of_[a] = mesh;
        return true;
    }

    /* One frame per node group that can take one (see the top). */
    bool make_frames() {
        cJSON *nodes = item(root_, "nodes");
        const int n_nodes = cJSON_GetArraySize(nodes), n_mesh = cJSON_GetArraySize(item(root_, "meshes"));
        std::vector<int> users(static_cast<size_t>(n_mesh), 0);
        cJSON *node;
        cJSON_ArrayForEach(node, nodes) {
            int mi = inum(node, "mesh", -1);
            if (mi >= 0 && mi < n_mesh) ++users[mi];
        }
        frame_of_mesh_.assign(static_cast<size_t>(n_mesh), -1);
        std::vector<char> seen(static_cast<size_t>(n_nodes), 0);
        cJSON *scene;
        cJSON_ArrayForEach(scene, item(root_, "scenes")) {
            cJSON *sn;
            cJSON_ArrayForEach(sn, item(scene, "nodes")) {
                std::vector<int> group{sn->valueint};
                cJSON *id;
                cJSON_ArrayForEach(id, item(item(item(cJSON_GetArrayItem(nodes, sn->valueint), "extensions"), "MSFT_lod"), "ids"))
                    group.push_back(id->valueint);
                bool ok = true;
                for (int g : group) {
                    const cJSON *n = cJSON_GetArrayItem(nodes, g);
                    const int mi = inum(n, "mesh", -1);
                    if (!n || g < 0 || g >= n_nodes || seen[g] || mi < 0 || mi >= n_mesh || users[mi] != 1 ||
                        item(n, "rotation") || item(n, "scale") || item(n, "matrix") || item(n, "children") ||
                        item(item(n, "extensions"), "EXT_mesh_gpu_instancing"))
                        ok = false;
                }
                for (int g : group)
                    if (g >= 0 && g < n_nodes) seen[g] = 1;
                if (!ok) continue;
                Frame f;
                double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
                for (int g : group) {
                    const int mi = inum(cJSON_GetArrayItem(nodes, g), "mesh", -1);
                    for (int a = 0; a < static_cast<int>(role_.size()); ++a) {
                        if (mesh_of_[a] != mi) continue;
                        const Role r = role_[a];
                        if (r != kPosition && r != kPivotX && r != kPivotY && r != kPivotZ)
                            continue; /* the engine UVs' arms are differences: they scale, the box holds points */
                        Acc c;
                        if (!read_acc(a, c)) return false;
                        if (c.ct != kFloat) return fail("a position or pivot that is not float");
                        for (uint32_t i = 0; i < c.count; ++i) {
                            if (r == kPosition) {
                                for (int k = 0; k < 3; ++k) {
                                    lo[k] = std::min(lo[k], static_cast<double>(c.f(i, k)));
                                    hi[k] = std::max(hi[k], static_cast<double>(c.f(i, k)));
                                }
                            } else {
                                const int axis = r == kPivotX ? 0 : r == kPivotY ? 1 : 2;
                                lo[axis] = std::min(lo[axis], static_cast<double>(c.f(i, 0)));
                                hi[axis] = std::max(hi[axis], static_cast<double>(c.f(i, 0)));
                            }
                        }
                    }
                }
                if (!(lo[0] <= hi[0])) continue; /* no positions */
                double ext = 0;
                for (int k = 0; k < 3; ++k) {
                    f.lo[k] = lo[k];
                    ext = std::max(ext, hi[k] - lo[k]);
                }
                f.s = ext > 0 ? ext / 65535.0 : 1.0;
                f.on = true;
                frames_.push_back(f);
                frame_nodes_.push_back(group);
                for (int g : group) frame_of_mesh_[inum(cJSON_GetArrayItem(nodes, g), "mesh", -1)] = static_cast<int>(frames_.size() - 1);
            }
        }
        return true;
    }

    /* The group's nodes: translation + lo, uniform scale s. */
    void place_nodes(size_t k) {
        const Frame &f = frames_[k];
        for (int g : frame_nodes_[k]) {
            cJSON *n = cJSON_GetArrayItem(item(root_, "nodes"), g);
            double t[3] = {0, 0, 0};
            const cJSON *old = item(n, "translation");
            for (int i = 0; i < 3; ++i) {
                const cJSON *e = cJSON_GetArrayItem(old, i);
                if (cJSON_IsNumber(e)) t[i] = e->valuedouble;
                t[i] += f.lo[i];
            }
            const double s[3] = {f.s, f.s, f.s};
            cJSON_DeleteItemFromObjectCaseSensitive(n, "translation");
            cJSON_AddItemToObject(n, "translation", cJSON_CreateDoubleArray(t, 3));
            cJSON_AddItemToObject(n, "scale", cJSON_CreateDoubleArray(s, 3));
        }
    }

    /* Accessor a: its new data, compressed into a view of its own. */
    bool convert(int a) {
        cJSON *j = cJSON_GetArrayItem(accessors_, a);
        Acc c;
        if (!read_acc(a, c)) return false;
        const Role r = role_[a];
        const Frame *f = nullptr;
        if (mesh_of_[a] >= 0 && frame_of_mesh_[mesh_of_[a]] >= 0) f = &frames_[frame_of_mesh_[mesh_of_[a]]];
        std::vector<unsigned char> d;
        View v;
        auto retype = [&](int ct, bool normalized) {
            set_num(j, "componentType", ct);
            cJSON_DeleteItemFromObjectCaseSensitive(j, "normalized");
            if (normalized) cJSON_AddBoolToObject(j, "normalized", 1);
        };
        const bool is_float = c.ct == kFloat;
        if (r == kIndices && (c.ct == kUInt || c.ct == kUShort || c.ct == kUByte)) {
            std::vector<uint32_t> ix(c.count);
            uint32_t top = 0;
            for (uint32_t i = 0; i < c.count; ++i) top = std::max(top, ix[i] = c.u(i));
            const bool tri = c.count % 3 == 0 && triangles_.find(a) == triangles_.end();
            const uint32_t size = top < 65535 ? 2 : 4;
            v.compressed = true;
            v.count = c.count;
            v.stride = size;
            v.target = kElementArrayBuffer;
            if (tri) {
                v.mode = "TRIANGLES";
                v.bytes.resize(meshopt_encodeIndexBufferBound(c.count, top + 1));
                v.bytes.resize(meshopt_encodeIndexBuffer(v.bytes.data(), v.bytes.size(), ix.data(), c.count));
            } else {
                v.mode = "INDICES";
                v.bytes.resize(meshopt_encodeIndexSequenceBound(c.count, top + 1));
                v.bytes.resize(meshopt_encodeIndexSequence(v.bytes.data(), v.bytes.size(), ix.data(), c.count));
            }
            retype(size == 2 ? kUShort : kUInt, false);
        } else if (r == kPosition && f && is_float && c.width == 3) {
            d.assign(static_cast<size_t>(c.count) * 8, 0);
            uint16_t lo[3] = {65535, 65535, 65535}, hi[3] = {0, 0, 0};
            for (uint32_t i = 0; i < c.count; ++i)
                for (int k = 0; k < 3; ++k) {
                    const uint16_t q = quant16(f->q(c.f(i, k), k));
                    put16(d, static_cast<size_t>(i) * 8 + 2 * k, q);
                    lo[k] = std::min(lo[k], q);
                    hi[k] = std::max(hi[k], q);
                }
            v = encode_vertices(d, c.count, 8, nullptr);
            retype(kUShort, false);
            const double mn[3] = {double(lo[0]), double(lo[1]), double(lo[2])}, mx[3] = {double(hi[0]), double(hi[1]), double(hi[2])};
            cJSON_ReplaceItemInObjectCaseSensitive(j, "min", cJSON_CreateDoubleArray(mn, 3));
            cJSON_ReplaceItemInObjectCaseSensitive(j, "max", cJSON_CreateDoubleArray(mx, 3));
        } else if ((r == kPivotX || r == kPivotY || r == kPivotZ) && f && is_float && c.width == 1) {
            const int axis = r - kPivotX;
            d.assign(static_cast<size_t>(c.count) * 4, 0);
            for (uint32_t i = 0; i < c.count; ++i) put16(d, static_cast<size_t>(i) * 4, quant16(f->q(c.f(i, 0), axis)));
            v = encode_vertices(d, c.count, 4, nullptr);
            retype(kUShort, false);
            drop_bounds(j);
        } else if ((r == kNormal || r == kTangent) && is_float && c.width == (r == kNormal ? 3u : 4u)) {
            std::vector<float> in(static_cast<size_t>(c.count) * 4, 0.f);
            for (uint32_t i = 0; i < c.count; ++i)
                for (uint32_t k = 0; k < c.width; ++k) in[4 * i + k] = c.f(i, k);
            d.assign(static_cast<size_t>(c.count) * 4, 0);
            meshopt_encodeFilterOct(d.data(), c.count, 4, 8, in.data());
            v = encode_vertices(d, c.count, 4, "OCTAHEDRAL");
            retype(kByte, true);
            drop_bounds(j);
        } else if ((r == kUv0 || r == kEngineUvXY || r == kEngineUvZ) && is_float) {
            d.assign(static_cast<size_t>(c.count) * c.elem, 0);
            for (uint32_t i = 0; i < c.count; ++i)
                for (uint32_t k = 0; k < c.width; ++k) {
                    float x = c.f(i, k);
                    if (r == kUv0) x = meshopt_quantizeFloat(x, kUvMantissa);
                    else if (f && (r == kEngineUvXY || k == 0)) x = static_cast<float>(x / f->s); /* an arm: scaled only */
                    std::memcpy(&d[(static_cast<size_t>(i) * c.width + k) * 4], &x, 4);
                }
            v = encode_vertices(d, c.count, c.elem, nullptr);
            drop_bounds(j);
        } else {
            /* As it is, each element padded to 4 bytes. */
            const uint32_t stride = static_cast<uint32_t>(pad4(c.elem));
            if (stride > 256) return fail("an accessor element over 256 bytes");
            d.assign(static_cast<size_t>(c.count) * stride, 0);
            for (uint32_t i = 0; i < c.count; ++i)
                std::memcpy(&d[static_cast<size_t>(i) * stride], c.base + static_cast<size_t>(i) * c.stride, c.elem);
            v = encode_vertices(d, c.count, stride, nullptr);
        }
        /* Indices and vertex data keep their view's target; instances' had none. */
        const cJSON *oldv = cJSON_GetArrayItem(views_, inum(j, "bufferView", 0));
        if (r != kIndices && r != kOther) v.target = kArrayBuffer;
        else if (r == kOther) v.target = inum(oldv, "target", 0);
        cJSON_DeleteItemFromObjectCaseSensitive(j, "byteOffset");
        out_.push_back(std::move(v));
        set_num(j, "bufferView", static_cast<double>(out_.size() - 1));
        return true;
    }

    /* Bounds of a converted attribute (not POSITION: set above) would no longer be exact. */
    static void drop_bounds(cJSON *j) {
        cJSON_DeleteItemFromObjectCaseSensitive(j, "min");
        cJSON_DeleteItemFromObjectCaseSensitive(j, "max");
    }

    cJSON *root_, *accessors_ = nullptr, *views_ = nullptr;
    const unsigned char *bin_;
    uint64_t bin_len_;
    bool engine_uvs_;
    std::vector<Role> role_;
    std::vector<int> mesh_of_, frame_of_mesh_;
    std::map<int, bool> triangles_; /* index accessors of non-triangle-list primitives */
    std::vector<Frame> frames_;
    std::vector<std::vector<int>> frame_nodes_;
    std::vector<View> out_;
    std::string why_;
};

uint32_t le32(const unsigned char *p) {
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 | static_cast<uint32_t>(p[2]) << 16 |
           static_cast<uint32_t>(p[3]) << 24;
}
void put32(std::string &s, uint32_t v) {
    for (int i = 0; i < 4; ++i) s += static_cast<char>((v >> (8 * i)) & 0xFF);
}

} // namespace

banyan_status gltf_compact_write(const char *path, bool binary, bool sync, bool engine_uvs,
                                 const std::function<banyan_status(const char *plain_glb)> &write_plain,
                                 banyan_error *err) {
    atomic_file af;
    if (int oe = atomic_open(&af, path))
        return banyan_fail(err, BANYAN_E_IO, "cannot open '%s' for writing: %s", path, std::strerror(oe));
    af.sync = sync ? 1 : 0;
    struct Guard {
        atomic_file *af;
        std::string plain;
        ~Guard() {
            atomic_abort(af);
            if (!plain.empty()) std::remove(plain.c_str());
        }
    } guard{&af, std::string(af.temp ? af.temp : path) + ".plain.glb"};
    if (!af.temp) guard.plain = std::string(path) + ".plain.glb"; /* a FIFO written in place */

    if (banyan_status s = write_plain(guard.plain.c_str())) return s;
    std::vector<unsigned char> glb;
    int re;
    if (!read_file(guard.plain.c_str(), glb, re))
        return banyan_fail(err, BANYAN_E_IO, "cannot read back '%s': %s", guard.plain.c_str(), std::strerror(re));
    std::remove(guard.plain.c_str());
    guard.plain.clear();
    auto odd = [&](const char *why) {
        return banyan_fail(err, BANYAN_E_INTERNAL, "the compact writer cannot read its own .glb (%s); please report this", why);
    };
    if (glb.size() < 20 || std::memcmp(glb.data(), "glTF", 4) != 0) return odd("no glb header");
    const uint64_t json_len = le32(&glb[12]);
    if (20 + json_len > glb.size() || le32(&glb[16]) != 0x4E4F534A) return odd("no JSON chunk");
    const unsigned char *bin = nullptr;
    uint64_t bin_len = 0;
    if (20 + json_len + 8 <= glb.size()) {
        bin_len = le32(&glb[20 + json_len]);
        bin = &glb[28 + json_len];
        if (28 + json_len + bin_len > glb.size()) return odd("a cut BIN chunk");
    }
    JsonDoc doc;
    doc.p = cJSON_ParseWithLength(reinterpret_cast<const char *>(&glb[20]), json_len);
    if (!doc.p) return odd("bad JSON");
    std::vector<unsigned char> buffer;
    {
        Compactor c(doc.p, bin, bin_len, engine_uvs);
        if (!c.run()) return odd(c.why().c_str());
        c.finish(buffer);
    }
    std::vector<unsigned char>().swap(glb);

    std::string head;
    if (!binary) {
        cJSON *b0 = cJSON_GetArrayItem(item(doc.p, "buffers"), 0);
        cJSON_AddStringToObject(b0, "uri",
                                ("data:application/octet-stream;base64," + base64(buffer.data(), buffer.size())).c_str());
        std::vector<unsigned char>().swap(buffer);
    }
    char *js = cJSON_PrintUnformatted(doc.p);
    if (!js) throw std::bad_alloc();
    std::string json(js);
    cJSON_free(js);
    if (binary) {
        json.resize(pad4(json.size()), ' ');
        const uint64_t total = 12 + 8 + json.size() + 8 + buffer.size();
        if (total > UINT32_MAX) return banyan_fail(err, BANYAN_E_RANGE, "the compact '%s' would be over 4 GiB", path);
        head = "glTF";
        put32(head, 2);
        put32(head, static_cast<uint32_t>(total));
        put32(head, static_cast<uint32_t>(json.size()));
        put32(head, 0x4E4F534A);
        head += json;
        put32(head, static_cast<uint32_t>(buffer.size()));
        put32(head, 0x004E4942);
    } else {
        head = json;
    }
    errno = 0;
    if (std::fwrite(head.data(), 1, head.size(), af.f) != head.size() ||
        (!buffer.empty() && std::fwrite(buffer.data(), 1, buffer.size(), af.f) != buffer.size()))
        return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", path, std::strerror(errno ? errno : EIO));
    if (int e = atomic_commit(&af)) return banyan_fail(err, BANYAN_E_IO, "cannot write '%s': %s", path, std::strerror(e));
    return BANYAN_OK;
}
