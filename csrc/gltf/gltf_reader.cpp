/*
 * gltf_reader.cpp - banyan_glb_read_host(): a glTF 2.0 binary (.glb) file
 * as one host mesh (banyan/hosts.h), for presets' "mesh" hosts and the
 * CLI's --host. The only place that reads glTF.
 *
 * Built, like gltf_writer.cpp, on Debian's shared tinygltf 2.7 (the header
 * without TINYGLTF_IMPLEMENTATION); exposes nothing but the extern "C"
 * calls declared in banyan.h. tinygltf parses the container and JSON;
 * everything it does not check (accessor and view bounds, index ranges,
 * the node tree, finiteness) is checked here, since a host file is input
 * from anywhere. Images are never decoded and no other file is opened
 * (external buffers are refused).
 *
 * What is read: the triangles of every primitive reached from the scene
 * (modes 4, 5, 6), POSITION as float VEC3 and indices as unsigned
 * byte / short / int, under the node transforms (matrix or TRS), in glTF's
 * Y up converted to banyan's Z up: (x, y, z) -> (x, -z, y), the inverse of
 * the writer's. Equal positions are merged (exporters split vertices at
 * UV seams and hard edges, which would open a closed mesh). No exception
 * leaves this file.
 */
#include "gltf/gltf_reader.h"

#include "banyan.h"
#include "base/error.h"

#include <cjson/cJSON.h>

#include <tiny_gltf.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unordered_map>
#include <vector>

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "gltf_reader.cpp reads floats and indices as they are in memory: glTF is little-endian"
#endif

namespace {

/* tinygltf takes the file's length as unsigned int. */
const uint64_t kMaxFileBytes = UINT64_C(0x7FFFFFFF);

/* Images are not needed for a host: accept them undecoded. */
bool skip_image(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *, int,
                void *) {
    return true;
}

/* No file is opened on the glb's behalf: a buffer or image "uri" naming
 * a file (another .bin, /dev/zero, anything) is refused; only the BIN
 * chunk and data: URIs are read. */
bool any_file(const std::string &, void *) { return true; } /* so that no_read says why */
std::string same_path(const std::string &p, void *) { return p; }
bool no_read(std::vector<unsigned char> *, std::string *why, const std::string &, void *) {
    if (why) *why = "an external file (banyan reads self-contained .glb files only)";
    return false;
}
bool no_write(std::string *, const std::string &, const std::vector<unsigned char> &, void *) { return false; }

/* Column-major 4x4, as glTF stores node matrices. */
struct mat4 {
    double m[16];
};

mat4 mat_identity() {
    mat4 a{};
    a.m[0] = a.m[5] = a.m[10] = a.m[15] = 1;
    return a;
}

mat4 mat_mul(const mat4 &a, const mat4 &b) {
    mat4 c{};
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[4 * k + row] * b.m[4 * col + k];
            c.m[4 * col + row] = s;
        }
    return c;
}

/* The node's local matrix: `matrix`, else T * R * S. */
mat4 node_matrix(const tinygltf::Node &n) {
    if (n.matrix.size() == 16) {
        mat4 a;
        for (int i = 0; i < 16; ++i) a.m[i] = n.matrix[i];
        return a;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (n.translation.size() == 3)
        for (int i = 0; i < 3; ++i) t[i] = n.translation[i];
    if (n.rotation.size() == 4)
        for (int i = 0; i < 4; ++i) q[i] = n.rotation[i];
    if (n.scale.size() == 3)
        for (int i = 0; i < 3; ++i) s[i] = n.scale[i];
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                   2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                   2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)}; /* row-major */
    mat4 a{};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) a.m[4 * col + row] = r[3 * row + col] * s[col];
    for (int row = 0; row < 3; ++row) a.m[12 + row] = t[row];
    a.m[15] = 1;
    return a;
}

double det3(const mat4 &a) {
    const double *m = a.m;
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

/* " (\"name\")" of a named mesh, for messages; "" when unnamed. */
std::string label(const tinygltf::Mesh &m) {
    return m.name.empty() ? std::string() : " (\"" + m.name.substr(0, 40) + "\")";
}

/* A vertex key: the float bits of a position (-0 made +0 first). */
struct vkey {
    uint32_t b[3];
    bool operator==(const vkey &o) const { return b[0] == o.b[0] && b[1] == o.b[1] && b[2] == o.b[2]; }
};
struct vkey_hash {
    size_t operator()(const vkey &k) const {
        uint64_t h = UINT64_C(1469598103934665603);
        for (uint32_t v : k.b) h = (h ^ v) * UINT64_C(1099511628211);
        return static_cast<size_t>(h ^ (h >> 29));
    }
};

struct reader {
    const char *path;
    const tinygltf::Model &model;
    banyan_error *err;
    prog *g;                      /* the budget, or NULL */
    const char *what;             /* "reading <path>", for prog_fail */
    std::vector<float> pos;       /* 3 per vertex, Z up */
    std::vector<uint32_t> tri;    /* 3 per triangle */
    std::unordered_map<vkey, uint32_t, vkey_hash> weld;
    /* pos is relative to off (Z up, whole metres): 0 unless the first mesh
     * node stands farther than 4096 m out (base/frame.h's FRAME_NEAR), so a
     * far mesh keeps its float precision; read_host folds off into the
     * transform, in double. */
    double off[3] = {0, 0, 0};
    bool have_off = false;
    uint64_t primitives = 0, skipped = 0; /* primitives seen; of those, not triangles */

    reader(const char *p, const tinygltf::Model &m, banyan_error *e, prog *gp, const char *w)
        : path(p), model(m), err(e), g(gp), what(w) {}

    /* Every 64k elements: 1 (err filled) once the budget is spent. */
    bool stopped(size_t k) { return (k & 0xFFFF) == 0xFFFF && g && prog_at(g, g->last); }

    /* The bytes of accessor `a`: element k starts at base + k * stride and
     * has `elem` bytes. Checks the accessor, view and buffer bounds. */
    banyan_status span(int a, int mesh, size_t prim, const char *what, size_t elem, const unsigned char **base,
                       size_t *stride, size_t *count) {
        const auto &acc = model.accessors[static_cast<size_t>(a)];
        if (acc.sparse.isSparse)
            return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: %s is a sparse accessor (not read)", path,
                        mesh, prim, what);
        if (acc.bufferView < 0 || static_cast<size_t>(acc.bufferView) >= model.bufferViews.size())
            return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: %s has no buffer view (compressed?)", path,
                        mesh, prim, what);
        const auto &view = model.bufferViews[static_cast<size_t>(acc.bufferView)];
        if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size())
            return banyan_fail(err, BANYAN_E_PARSE, "%s: buffer view %d names buffer %d, which does not exist", path,
                        acc.bufferView, view.buffer);
        const auto &buf = model.buffers[static_cast<size_t>(view.buffer)].data;
        size_t st = view.byteStride ? view.byteStride : elem;
        /* Every sum and product checked: offsets near 2^64 from a crafted
         * file must not wrap the end back into the buffer. */
        uint64_t need = 0;
        bool wraps = false;
        if (acc.count) {
            uint64_t last = 0;
            wraps = __builtin_mul_overflow(static_cast<uint64_t>(st), static_cast<uint64_t>(acc.count - 1), &last) ||
                    __builtin_add_overflow(last, static_cast<uint64_t>(elem), &last) ||
                    __builtin_add_overflow(last, static_cast<uint64_t>(acc.byteOffset), &need);
        } else if (acc.byteOffset > view.byteLength) {
            wraps = true;
        }
        if (st < elem || wraps || view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset ||
            need > view.byteLength)
            return banyan_fail(err, BANYAN_E_PARSE,
                        "%s: mesh %d primitive %zu: %s (%zu elements from byte %zu, stride %zu) reaches past its "
                        "buffer view (%zu bytes from byte %zu) or buffer (%zu bytes)", path, mesh, prim, what,
                        acc.count, acc.byteOffset, st, view.byteLength, view.byteOffset, buf.size());
        *base = buf.data() + view.byteOffset + acc.byteOffset;
        *stride = st;
        *count = acc.count;
        return BANYAN_OK;
    }

    banyan_status primitive(const mat4 &world, bool mirrored, int mesh, size_t pi) {
        const auto &gm = model.meshes[static_cast<size_t>(mesh)];
        const tinygltf::Primitive &p = gm.primitives[pi];
        ++primitives;
        /* -1: no "mode" given, glTF's default (triangles). */
        if (p.mode < -1 || p.mode > TINYGLTF_MODE_TRIANGLE_FAN)
            return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: mode = %d is not a glTF primitive mode "
                        "(0 .. 6): banyan reads triangles (4, the default), strips (5) and fans (6), and skips points "
                        "and lines (0 .. 3)", path, mesh, pi, p.mode);
        int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            ++skipped;
            return BANYAN_OK;
        }
        auto it = p.attributes.find("POSITION");
        if (it == p.attributes.end()) {
            ++skipped;
            return BANYAN_OK;
        }
        if (it->second < 0 || static_cast<size_t>(it->second) >= model.accessors.size())
            return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: POSITION names accessor %d, which does "
                        "not exist", path, mesh, pi, it->second);
        const auto &pacc = model.accessors[static_cast<size_t>(it->second)];
        if (pacc.type != TINYGLTF_TYPE_VEC3 || pacc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: POSITION is not float VEC3 (quantized "
                        "positions are not read)", path, mesh, pi);
        const unsigned char *pb = nullptr;
        size_t pstride = 0, nv = 0;
        banyan_status s = span(it->second, mesh, pi, "POSITION", 12, &pb, &pstride, &nv);
        if (s) return s;
        if (nv > UINT32_MAX)
            return banyan_fail(err, BANYAN_E_LIMIT, "%s: mesh %d primitive %zu: %zu vertices", path, mesh, pi, nv);

        if (!have_off) {
            const double t[3] = {world.m[12], -world.m[14], world.m[13]};
            if (std::fabs(t[0]) > 4096 || std::fabs(t[1]) > 4096 || std::fabs(t[2]) > 4096)
                for (int r = 0; r < 3; ++r) off[r] = std::round(t[r]);
            have_off = true;
        }
        /* This primitive's vertices, transformed and merged. */
        std::vector<uint32_t> local(nv);
        for (size_t k = 0; k < nv; ++k) {
            if (stopped(k)) return prog_fail(g, err, what);
            float f[3];
            std::memcpy(f, pb + k * pstride, sizeof f);
            double w[3];
            for (int r = 0; r < 3; ++r)
                w[r] = world.m[r] * f[0] + world.m[4 + r] * f[1] + world.m[8 + r] * f[2] + world.m[12 + r];
            float z[3] = {static_cast<float>(w[0] - off[0]), static_cast<float>(-w[2] - off[1]),
                          static_cast<float>(w[1] - off[2])};
            vkey key;
            for (int r = 0; r < 3; ++r) {
                if (!std::isfinite(z[r]))
                    return banyan_fail(err, BANYAN_E_BAD_HOST, "%s: mesh %d%s primitive %zu: vertex %zu is not finite "
                                "(%g, %g, %g) after its node transforms", path, mesh, label(gm).c_str(), pi, k,
                                static_cast<double>(f[0]), static_cast<double>(f[1]), static_cast<double>(f[2]));
                if (z[r] == 0.0f) z[r] = 0.0f; /* -0 -> +0 */
                std::memcpy(&key.b[r], &z[r], 4);
            }
            auto ins = weld.emplace(key, static_cast<uint32_t>(pos.size() / 3));
            if (ins.second) {
                if (pos.size() / 3 >= UINT32_MAX)
                    return banyan_fail(err, BANYAN_E_LIMIT, "%s: more than %u vertices", path, UINT32_MAX);
                pos.insert(pos.end(), z, z + 3);
            }
            local[k] = ins.first->second;
        }

        /* Indices, or 0 .. nv - 1. */
        std::vector<uint32_t> idx;
        if (p.indices >= 0) {
            if (static_cast<size_t>(p.indices) >= model.accessors.size())
                return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: indices name accessor %d, which does "
                            "not exist", path, mesh, pi, p.indices);
            const auto &iacc = model.accessors[static_cast<size_t>(p.indices)];
            size_t es = iacc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                        : iacc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                        : iacc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                       : 0;
            if (iacc.type != TINYGLTF_TYPE_SCALAR || es == 0)
                return banyan_fail(err, BANYAN_E_PARSE, "%s: mesh %d primitive %zu: indices must be unsigned byte, short "
                            "or int scalars", path, mesh, pi);
            const unsigned char *ib = nullptr;
            size_t istride = 0, ni = 0;
            if ((s = span(p.indices, mesh, pi, "indices", es, &ib, &istride, &ni))) return s;
            idx.resize(ni);
            for (size_t k = 0; k < ni; ++k) {
                if (stopped(k)) return prog_fail(g, err, what);
                const unsigned char *e = ib + k * istride;
                uint32_t v = es == 1 ? e[0] : es == 2 ? static_cast<uint32_t>(e[0] | e[1] << 8) : 0;
                if (es == 4) std::memcpy(&v, e, 4);
                if (v >= nv)
                    return banyan_fail(err, BANYAN_E_BAD_HOST, "%s: mesh %d%s primitive %zu: index %zu = %u is out of "
                                "range (%zu vertices)", path, mesh, label(gm).c_str(), pi, k, v, nv);
                idx[k] = v;
            }
        } else {
            idx.resize(nv);
            for (size_t k = 0; k < nv; ++k) idx[k] = static_cast<uint32_t>(k);
        }

        size_t n = idx.size();
        size_t nt = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : n >= 3 ? n - 2 : 0;
        if (static_cast<uint64_t>(tri.size() / 3) + nt > BANYAN_HOSTS_MAX_TRIANGLES)
            return banyan_fail(err, BANYAN_E_LIMIT, "%s: more than %u triangles (BANYAN_HOSTS_MAX_TRIANGLES)", path,
                        BANYAN_HOSTS_MAX_TRIANGLES);
        tri.reserve(tri.size() + 3 * nt);
        for (size_t t = 0; t < nt; ++t) {
            if (stopped(t)) return prog_fail(g, err, what);
            uint32_t a, b, c;
            if (mode == TINYGLTF_MODE_TRIANGLES) {
                a = idx[3 * t], b = idx[3 * t + 1], c = idx[3 * t + 2];
            } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                /* Odd triangles swap their first two corners to keep the winding. */
                a = idx[t + (t & 1)], b = idx[t + 1 - (t & 1)], c = idx[t + 2];
            } else {
                a = idx[0], b = idx[t + 1], c = idx[t + 2];
            }
            if (mirrored) std::swap(b, c);
            tri.push_back(local[a]);
            tri.push_back(local[b]);
            tri.push_back(local[c]);
        }
        return BANYAN_OK;
    }

    /* Walks the node tree from `roots`; each node at most once. */
    banyan_status walk(const std::vector<int> &roots) {
        std::vector<char> seen(model.nodes.size(), 0);
        struct item {
            int node;
            mat4 parent;
        };
        std::vector<item> stack;
        for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, mat_identity()});
        while (!stack.empty()) {
            item it = stack.back();
            stack.pop_back();
            if (it.node < 0 || static_cast<size_t>(it.node) >= model.nodes.size())
                return banyan_fail(err, BANYAN_E_PARSE, "%s: node %d does not exist", path, it.node);
            if (seen[static_cast<size_t>(it.node)]++)
                return banyan_fail(err, BANYAN_E_PARSE, "%s: node %d is reached twice (the node graph must be a tree)", path,
                            it.node);
            const tinygltf::Node &n = model.nodes[static_cast<size_t>(it.node)];
            mat4 world = mat_mul(it.parent, node_matrix(n));
            for (double v : world.m)
                if (!std::isfinite(v))
                    return banyan_fail(err, BANYAN_E_BAD_HOST, "%s: node %d (\"%.40s\") has a non-finite transform (with "
                                "its parents')", path, it.node, n.name.c_str());
            if (n.mesh >= 0) {
                if (static_cast<size_t>(n.mesh) >= model.meshes.size())
                    return banyan_fail(err, BANYAN_E_PARSE, "%s: node %d names mesh %d, which does not exist", path, it.node,
                                n.mesh);
                bool mirrored = det3(world) < 0;
                const auto &gm = model.meshes[static_cast<size_t>(n.mesh)];
                for (size_t pi = 0; pi < gm.primitives.size(); ++pi) {
                    banyan_status s = primitive(world, mirrored, n.mesh, pi);
                    if (s) return s;
                }
            }
            for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world});
        }
        return BANYAN_OK;
    }
};

/* Extensions a host can be read without: they change looks, not shape. */
bool ignorable_extension(const std::string &e) {
    return e.rfind("KHR_materials_", 0) == 0 || e.rfind("KHR_texture_", 0) == 0 || e == "KHR_lights_punctual" ||
           e == "EXT_texture_webp";
}

/* cJSON's number k of o when it is >= 0 (whole, at most 2^53), else dflt. */
double count_of(const cJSON *o, const char *k, double dflt) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);
    if (!cJSON_IsNumber(v) || !(v->valuedouble >= 0)) return dflt;
    return std::floor(std::min(v->valuedouble, 9007199254740992.0)); /* a count past 2^53 is refused later */
}

/* What the JSON chunk asks of the reader, before the binary chunk is read:
 * the triangles and POSITION reads of every node instance of every
 * primitive reached from the scene (the walk's rules: default scene, or
 * every root node), and the bytes of the binary chunk that the buffers
 * use (bin_need) and copy (bin_copy). References that do not exist are
 * left for the full read to refuse. Returns 0 when the text is not JSON. */
struct json_sizes {
    double triangles = 0, vertex_reads = 0, bin_need = 0, bin_copy = 0;
};

bool scan_json(const char *text, size_t len, json_sizes *z) {
    cJSON *j = preset_json_parse(text, len, nullptr);
    if (!j) return false;
    const cJSON *accs = cJSON_GetObjectItemCaseSensitive(j, "accessors");
    const cJSON *meshes = cJSON_GetObjectItemCaseSensitive(j, "meshes");
    const cJSON *nodes = cJSON_GetObjectItemCaseSensitive(j, "nodes");
    const cJSON *scenes = cJSON_GetObjectItemCaseSensitive(j, "scenes");
    const cJSON *bufs = cJSON_GetObjectItemCaseSensitive(j, "buffers");
    std::vector<double> acount;
    for (const cJSON *a = cJSON_IsArray(accs) ? accs->child : nullptr; a; a = a->next)
        acount.push_back(count_of(a, "count", 0));
    auto count_at = [&](const cJSON *o, const char *k) -> double {
        double i = count_of(o, k, -1);
        return i >= 0 && i < static_cast<double>(acount.size()) ? acount[static_cast<size_t>(i)] : -1;
    };
    std::vector<double> mtri, mreads; /* per mesh, one instance */
    for (const cJSON *m = cJSON_IsArray(meshes) ? meshes->child : nullptr; m; m = m->next) {
        double t = 0, r = 0;
        const cJSON *prims = cJSON_GetObjectItemCaseSensitive(m, "primitives");
        for (const cJSON *p = cJSON_IsArray(prims) ? prims->child : nullptr; p; p = p->next) {
            double mode = count_of(p, "mode", TINYGLTF_MODE_TRIANGLES);
            const cJSON *attrs = cJSON_GetObjectItemCaseSensitive(p, "attributes");
            double nv = cJSON_IsObject(attrs) ? count_at(attrs, "POSITION") : -1;
            if (nv < 0 || mode < TINYGLTF_MODE_TRIANGLES || mode > TINYGLTF_MODE_TRIANGLE_FAN) continue;
            double ni = cJSON_GetObjectItemCaseSensitive(p, "indices") ? count_at(p, "indices") : nv;
            if (ni < 0) ni = 0;
            r += nv;
            t += mode == TINYGLTF_MODE_TRIANGLES ? std::floor(ni / 3) : ni >= 3 ? ni - 2 : 0;
        }
        mtri.push_back(t);
        mreads.push_back(r);
    }
    std::vector<const cJSON *> node;
    for (const cJSON *n = cJSON_IsArray(nodes) ? nodes->child : nullptr; n; n = n->next) node.push_back(n);
    std::vector<size_t> stack;
    auto push_all = [&](const cJSON *list) {
        for (const cJSON *c = cJSON_IsArray(list) ? list->child : nullptr; c; c = c->next)
            if (cJSON_IsNumber(c) && c->valuedouble >= 0 && c->valuedouble < static_cast<double>(node.size()))
                stack.push_back(static_cast<size_t>(c->valuedouble));
    };
    if (cJSON_IsArray(scenes) && scenes->child) {
        double sc = count_of(j, "scene", 0);
        const cJSON *scene = sc < cJSON_GetArraySize(scenes) ? cJSON_GetArrayItem(scenes, static_cast<int>(sc)) : nullptr;
        if (scene) push_all(cJSON_GetObjectItemCaseSensitive(scene, "nodes"));
    } else {
        std::vector<char> child(node.size(), 0);
        for (const cJSON *n : node) {
            const cJSON *ch = cJSON_GetObjectItemCaseSensitive(n, "children");
            for (const cJSON *c = cJSON_IsArray(ch) ? ch->child : nullptr; c; c = c->next)
                if (cJSON_IsNumber(c) && c->valuedouble >= 0 && c->valuedouble < static_cast<double>(node.size()))
                    child[static_cast<size_t>(c->valuedouble)] = 1;
        }
        for (size_t i = 0; i < node.size(); ++i)
            if (!child[i]) stack.push_back(i);
    }
    std::vector<char> seen(node.size(), 0);
    while (!stack.empty()) {
        size_t n = stack.back();
        stack.pop_back();
        if (seen[n]++) continue; /* the walk refuses it */
        double m = count_of(node[n], "mesh", -1);
        if (m >= 0 && m < static_cast<double>(mtri.size())) {
            z->triangles += mtri[static_cast<size_t>(m)];
            z->vertex_reads += mreads[static_cast<size_t>(m)];
        }
        push_all(cJSON_GetObjectItemCaseSensitive(node[n], "children"));
    }
    for (const cJSON *b = cJSON_IsArray(bufs) ? bufs->child : nullptr; b; b = b->next)
        if (!cJSON_GetObjectItemCaseSensitive(b, "uri")) {
            double l = count_of(b, "byteLength", 0);
            z->bin_need = std::max(z->bin_need, l);
            z->bin_copy += l;
        }
    cJSON_Delete(j);
    return true;
}

/* An open .glb whose header, chunk headers and JSON chunk are read and
 * checked; the binary chunk is left in the file. */
struct front {
    FILE *f = nullptr;
    uint64_t size = 0;
    std::vector<unsigned char> bytes; /* the 20-byte header, then the JSON chunk */
    uint32_t json_len = 0, bin_len = 0;
    bool has_bin = false;
    json_sizes z;
    ~front() {
        if (f) std::fclose(f);
    }
};

/* The JSON chunk may not pass this: a host's JSON is small (the big
 * arrays live in the binary chunk), and its parse costs memory. */
const uint32_t kMaxJsonBytes = UINT32_C(64) << 20;
const double kJsonTreeBytes = 48.0; /* a parsed JSON tree's bytes per byte of text, at most */

bool read_all(FILE *f, void *buf, size_t n) { return n == 0 || std::fread(buf, 1, n, f) == n; }

/* Opens path and reads its sizes from the header before anything else:
 * a file that is not a .glb, or whose header and chunk lengths disagree
 * with the file's size or pass the limits, is refused having read at most
 * 28 bytes; then the JSON chunk alone is read and scanned. */
banyan_status read_front(const char *path, front *fr, prog *g, banyan_error *err) {
    /* A FIFO or a device would block or never end: regular files only. */
    struct stat sb;
    if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
        return banyan_fail(err, BANYAN_E_IO, "%s: not a regular file", path);
    fr->f = std::fopen(path, "rb");
    if (!fr->f) return banyan_fail(err, BANYAN_E_IO, "%s: cannot open: %s", path, std::strerror(errno));
    if (fstat(fileno(fr->f), &sb) != 0 || !S_ISREG(sb.st_mode))
        return banyan_fail(err, BANYAN_E_IO, "%s: cannot read (not a regular file?)", path);
    fr->size = static_cast<uint64_t>(sb.st_size);
    unsigned char h[20] = {0};
    size_t got = std::fread(h, 1, fr->size < 20 ? static_cast<size_t>(fr->size) : 20, fr->f);
    if (got < 12 || std::memcmp(h, "glTF", 4) != 0)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a glTF binary (.glb) file: it does not start with \"glTF\"%s", path,
                    got && h[0] == '{' ? " (a .gltf JSON file? export it as .glb)" : "");
    uint32_t hdr[5];
    std::memcpy(hdr, h, 20);
    if (hdr[1] != 2)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: glTF binary version %u (banyan reads version 2)", path, hdr[1]);
    if (fr->size > kMaxFileBytes)
        return banyan_fail(err, BANYAN_E_LIMIT, "%s: %llu bytes is more than the %llu a .glb may have here", path,
                    static_cast<unsigned long long>(fr->size), static_cast<unsigned long long>(kMaxFileBytes));
    if (hdr[2] != fr->size)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: the header says %u bytes but the file has %llu (truncated?)", path,
                    hdr[2], static_cast<unsigned long long>(fr->size));
    /* tinygltf 2.7 lets a BIN chunk run up to its 8-byte header past the
     * end of the data: every length is checked here. */
    if (got < 20 || hdr[4] != 0x4E4F534Au || hdr[3] == 0 || hdr[3] > fr->size - 20)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: the JSON chunk is missing or truncated", path);
    if (hdr[3] > kMaxJsonBytes)
        return banyan_fail(err, BANYAN_E_LIMIT, "%s: its JSON chunk has %u bytes; banyan reads at most %u (a host's "
                    "geometry belongs in the binary chunk)", path, hdr[3], kMaxJsonBytes);
    fr->json_len = hdr[3];
    uint64_t next = 20 + static_cast<uint64_t>(hdr[3]);
    if (next < fr->size) {
        uint32_t bin[2] = {0, 0};
        if (fr->size - next < 8 || std::fseek(fr->f, static_cast<long>(next), SEEK_SET) != 0 || !read_all(fr->f, bin, 8) ||
            bin[0] > fr->size - next - 8)
            return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: the chunk after the JSON runs past the end "
                        "of the file", path);
        if (bin[1] != 0x004E4942u || bin[0] < 4 || bin[0] % 4)
            return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: the chunk after the JSON is not a BIN "
                        "chunk of a whole number of 4-byte words", path);
        fr->bin_len = bin[0];
        fr->has_bin = true;
    }
    /* Parsing JSON holds a tree of many times its size (cJSON: about 40
     * bytes a value, down to 2 bytes a value of text). */
    if (g && prog_reserve(g, kJsonTreeBytes * fr->json_len)) {
        char what[300];
        std::snprintf(what, sizeof what, "reading the JSON of %s", path);
        return prog_fail(g, err, what);
    }
    fr->bytes.resize(20 + static_cast<size_t>(fr->json_len));
    std::memcpy(fr->bytes.data(), h, 20);
    if (std::fseek(fr->f, 20, SEEK_SET) != 0 || !read_all(fr->f, fr->bytes.data() + 20, fr->json_len))
        return banyan_fail(err, BANYAN_E_IO, "%s: cannot read its JSON chunk: %s", path, std::strerror(errno));
    if (!scan_json(reinterpret_cast<const char *>(fr->bytes.data() + 20), fr->json_len, &fr->z))
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: its JSON chunk is not valid JSON", path);
    if (fr->z.triangles > BANYAN_HOSTS_MAX_TRIANGLES)
        return banyan_fail(err, BANYAN_E_LIMIT, "%s: %.0f triangles (each node's instance counted); a host takes at most "
                    "%u (BANYAN_HOSTS_MAX_TRIANGLES): decimate, or instance fewer", path,
                    fr->z.triangles, BANYAN_HOSTS_MAX_TRIANGLES);
    if (fr->z.vertex_reads > static_cast<double>(GLB_MAX_VERTEX_READS))
        return banyan_fail(err, BANYAN_E_LIMIT, "%s: %.0f vertices to read (each node's instance of each primitive's "
                    "POSITION); at most %llu: decimate, or instance fewer", path, fr->z.vertex_reads,
                    static_cast<unsigned long long>(GLB_MAX_VERTEX_READS));
    if (fr->z.bin_need > fr->bin_len)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: a buffer of %.0f bytes is longer than the "
                    "%u-byte BIN chunk", path, fr->z.bin_need, fr->bin_len);
    return BANYAN_OK;
}

/* The most the read holds at once, in bytes (an upper estimate): the
 * chunks read, tinygltf's copies of the buffers and its JSON tree, and per
 * vertex read and per triangle the merge table, positions and indices. */
double front_memory(const front &fr) {
    return 20.0 + fr.json_len + 8 + fr.z.bin_need + fr.z.bin_copy + kJsonTreeBytes * fr.json_len + 56.0 * fr.z.vertex_reads +
           24.0 * fr.z.triangles;
}

banyan_status read_host(const char *path, const double *transform, int32_t closed, prog *g, banyan_host_mesh **out,
                        banyan_error *err) {
    front fr;
    banyan_status st = read_front(path, &fr, g, err);
    if (st) return st;
    char what[300];
    std::snprintf(what, sizeof what, "reading %s", path);
    if (g && prog_reserve(g, front_memory(fr))) return prog_fail(g, err, what);
    /* The binary chunk: only the bytes the buffers use, read in pieces
     * the budget can stop between. tinygltf gets the header, the JSON and
     * a BIN chunk of that length. */
    size_t need = static_cast<size_t>(fr.z.bin_need + 3) & ~static_cast<size_t>(3);
    std::vector<unsigned char> bytes;
    bytes.swap(fr.bytes);
    if (fr.has_bin && need) {
        size_t at = bytes.size();
        bytes.resize(at + 8 + need);
        uint32_t bin[2] = {static_cast<uint32_t>(need), 0x004E4942u};
        std::memcpy(bytes.data() + at, bin, 8);
        at += 8;
        if (std::fseek(fr.f, static_cast<long>(28 + fr.json_len), SEEK_SET) != 0)
            return banyan_fail(err, BANYAN_E_IO, "%s: cannot read: %s", path, std::strerror(errno));
        for (size_t done = 0; done < need;) {
            size_t piece = std::min(need - done, static_cast<size_t>(8) << 20);
            if (!read_all(fr.f, bytes.data() + at + done, piece))
                return banyan_fail(err, BANYAN_E_IO, "%s: read %zu of %zu bytes of its BIN chunk", path, done, need);
            done += piece;
            if (g && prog_at(g, g->last)) return prog_fail(g, err, what);
        }
    }
    std::fclose(fr.f);
    fr.f = nullptr;
    uint32_t glb_length = static_cast<uint32_t>(bytes.size());
    std::memcpy(bytes.data() + 8, &glb_length, 4);

    std::string dir(path);
    size_t slash = dir.find_last_of('/');
    dir = slash == std::string::npos ? std::string(".") : dir.substr(0, slash ? slash : 1);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    tinygltf::FsCallbacks fs = {any_file, same_path, no_read, no_write, nullptr};
    loader.SetFsCallbacks(fs);
    std::string e, w;
    if (!loader.LoadBinaryFromMemory(&model, &e, &w, bytes.data(), static_cast<unsigned int>(bytes.size()), dir)) {
        size_t nl = e.find('\n');
        if (nl != std::string::npos) e.resize(nl);
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: %.160s", path,
                    e.empty() ? "tinygltf gave no reason" : e.c_str());
    }
    bytes.clear();
    bytes.shrink_to_fit();
    for (const auto &x : model.extensionsRequired)
        if (!ignorable_extension(x))
            return banyan_fail(err, BANYAN_E_PARSE, "%s: requires the extension %.60s, which banyan does not read "
                        "(export without compression or quantization)", path, x.c_str());

    /* The scene's root nodes; without scenes, every node no one holds. */
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int sc = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (static_cast<size_t>(sc) >= model.scenes.size())
            return banyan_fail(err, BANYAN_E_PARSE, "%s: the default scene %d does not exist", path, sc);
        roots = model.scenes[static_cast<size_t>(sc)].nodes;
    } else {
        std::vector<char> child(model.nodes.size(), 0);
        for (const auto &n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && static_cast<size_t>(c) < child.size()) child[static_cast<size_t>(c)] = 1;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!child[i]) roots.push_back(static_cast<int>(i));
    }
    reader r(path, model, err, g, what);
    banyan_status s = r.walk(roots);
    if (s) return s;
    size_t nt = r.tri.size() / 3, nv = r.pos.size() / 3;
    if (nt == 0)
        return banyan_fail(err, BANYAN_E_BAD_HOST, "%s: has no triangles (%zu meshes, %llu primitives reached, %llu of them "
                    "points, lines or without POSITION)", path, model.meshes.size(),
                    static_cast<unsigned long long>(r.primitives), static_cast<unsigned long long>(r.skipped));

    /* One block: the struct, then positions, then indices. */
    size_t head = (sizeof(banyan_host_mesh) + 15) & ~static_cast<size_t>(15);
    size_t total = head + sizeof(float) * r.pos.size() + sizeof(uint32_t) * r.tri.size();
    unsigned char *block = static_cast<unsigned char *>(std::malloc(total));
    if (!block) return banyan_fail(err, BANYAN_E_NOMEM, "%s: out of memory for %zu vertices", path, nv);
    banyan_host_mesh *m = reinterpret_cast<banyan_host_mesh *>(block);
    std::memset(m, 0, sizeof *m);
    float *pos = reinterpret_cast<float *>(block + head);
    uint32_t *idx = reinterpret_cast<uint32_t *>(block + head + sizeof(float) * r.pos.size());
    std::memcpy(pos, r.pos.data(), sizeof(float) * r.pos.size());
    std::memcpy(idx, r.tri.data(), sizeof(uint32_t) * r.tri.size());
    m->positions = pos;
    m->indices = idx;
    m->vertex_count = static_cast<uint32_t>(nv);
    m->triangle_count = static_cast<uint32_t>(nt);
    static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    std::memcpy(m->transform, transform ? transform : identity, sizeof m->transform);
    for (int row = 0; row < 3 && (r.off[0] != 0 || r.off[1] != 0 || r.off[2] != 0); ++row) /* pos is relative to off */
        m->transform[4 * row + 3] += m->transform[4 * row] * r.off[0] + m->transform[4 * row + 1] * r.off[1] +
                                     m->transform[4 * row + 2] * r.off[2];
    m->closed = closed;
    m->reserved = 0;
    *out = m;
    return BANYAN_OK;
}


/* The public calls' checks, then read_host; no exception leaves. */
banyan_status read_checked(const char *path, const double transform[12], int32_t closed, prog *g, banyan_host_mesh **out,
                           banyan_error *err) {
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    *out = nullptr;
    if (!path || !*path) return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is NULL or empty");
    if (closed < -1 || closed > 1)
        return banyan_fail(err, BANYAN_E_RANGE, "closed = %d must be -1 (auto), 0 (open) or 1 (closed)", closed);
    for (int i = 0; transform && i < 12; ++i)
        if (!std::isfinite(transform[i]))
            return banyan_fail(err, BANYAN_E_RANGE, "transform[%d] = %g must be finite", i, transform[i]);
    try {
        return read_host(path, transform, closed, g, out, err);
    } catch (const std::bad_alloc &) {
        return banyan_fail(err, BANYAN_E_NOMEM, "%s: out of memory", path);
    } catch (const std::length_error &) {
        return banyan_fail(err, BANYAN_E_LIMIT, "%s: a size in the file is larger than this machine can hold", path);
    } catch (...) {
        /* Library internals (std::exception::what) mean nothing to a user. */
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: a value in it stopped the reader", path);
    }
}

} // namespace

banyan_status glb_read_host_prog(const char *path, const double transform[12], int32_t closed, prog *g,
                                 banyan_host_mesh **out, banyan_error *err) {
    return read_checked(path, transform, closed, g, out, err);
}

banyan_status glb_scan(const char *path, prog *g, glb_sizes *out, banyan_error *err) {
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    *out = glb_sizes{0, 0, 0};
    if (!path || !*path) return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is NULL or empty");
    try {
        front fr;
        banyan_status s = read_front(path, &fr, g, err);
        if (s) return s;
        out->triangles = static_cast<uint64_t>(fr.z.triangles);
        out->vertex_reads = static_cast<uint64_t>(fr.z.vertex_reads);
        out->memory = front_memory(fr);
        return BANYAN_OK;
    } catch (const std::bad_alloc &) {
        return banyan_fail(err, BANYAN_E_NOMEM, "%s: out of memory", path);
    } catch (...) {
        return banyan_fail(err, BANYAN_E_PARSE, "%s: not a valid glTF binary: a value in it stopped the reader", path);
    }
}

extern "C" BANYAN_API banyan_status banyan_glb_read_host(const char *path, const double transform[12], int32_t closed,
                                                         banyan_host_mesh **out, banyan_error *err) {
    return banyan_glb_read_host_budget(path, transform, closed, nullptr, out, err);
}

extern "C" BANYAN_API banyan_status banyan_glb_read_host_budget(const char *path, const double transform[12],
                                                                int32_t closed, const banyan_budget *budget,
                                                                banyan_host_mesh **out, banyan_error *err) {
    if (out) *out = nullptr;
    prog g;
    banyan_status s = prog_budget_from(&g, budget, err);
    if (s != BANYAN_OK) return s;
    return read_checked(path, transform, closed, &g, out, err);
}

extern "C" BANYAN_API void banyan_host_mesh_free(banyan_host_mesh *mesh) { std::free(mesh); }
