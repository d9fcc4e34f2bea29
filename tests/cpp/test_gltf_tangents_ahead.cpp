/*
 * test_gltf_tangents_ahead.cpp - the glTF writer's tangents computed ahead
 * on their own thread (csrc/gltf/gltf_write_tangents.cpp) are the bits the
 * stream computes itself, whichever side computes a range and in whatever
 * order the ranges are taken.
 *
 *   test_gltf_tangents_ahead OUTDIR
 *
 * Checks, on a small textured keyaki (two parts, each its own range) and
 * the same arrays as one primitive (the whole mesh's range):
 *   - every range's tangents from TangentAhead::take equal tangents_of's,
 *     bit for bit, taken in order, in reverse (the taker computes ranges
 *     the thread has not reached) and after the thread is done;
 *   - a node given twice and a node the thread must not read (an index
 *     out of range, after a good one) still give every good range exactly;
 *   - textured .glb files written twice are the same bytes.
 * Ends with "N passed, N failed"; exits 1 on any failure.
 */
#include "banyan.h"
#include "check.h"
#include "gltf/gltf_write.h"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

using gltfw::TangentAhead;
using gltfw::TangentKey;

namespace {

std::string read_file(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

bool same(const std::vector<float> &a, const std::vector<float> &b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

/* Every key of the nodes' meshes with its tangents computed inline. */
void references(const std::vector<const banyan_mesh *> &meshes, std::vector<TangentKey> &keys,
                std::vector<std::vector<float>> &want) {
    std::vector<double> scratch;
    for (const banyan_mesh *m : meshes) {
        size_t from = keys.size();
        gltfw::tangent_keys(m, keys);
        for (size_t k = from; k < keys.size(); ++k) want.push_back(gltfw::tangents_of(keys[k], scratch));
    }
}

/* order: 0 in order, 1 reversed, 2 in order after the thread had time to finish. */
void check_takes(const char *label, const std::vector<banyan_gltf_node> &nodes, const std::vector<TangentKey> &keys,
                 const std::vector<std::vector<float>> &want, int order) {
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    TangentAhead ahead(nodes.data(), static_cast<uint32_t>(nodes.size()), o);
    if (order == 2) std::this_thread::sleep_for(std::chrono::milliseconds(300));
    std::vector<double> scratch;
    int good = 0;
    for (size_t i = 0; i < keys.size(); ++i) {
        size_t k = order == 1 ? keys.size() - 1 - i : i;
        std::shared_ptr<const std::vector<float>> t = ahead.take(keys[k], scratch);
        good += t && same(*t, want[k]);
    }
    CHECK(good == static_cast<int>(keys.size()), "%s (order %d): %d of %zu ranges equal the inline tangents", label,
          order, good, keys.size());
}

} // namespace

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    p.levels = 8;
    p.seed = 11;
    banyan_mesh *m = nullptr;
    banyan_error err = {0, ""};
    CHECK(banyan_keyaki_generate(&p, &m, NULL, NULL, &err) == BANYAN_OK && m, "keyaki: %s", err.message);
    if (!m) return check_done("test_gltf_tangents_ahead");
    CHECK(m->part_count >= 2 && m->uvs && m->normals && m->material_count > 0 &&
              m->materials[0].texture != BANYAN_TEX_NONE,
          "the keyaki is not the textured, several-part mesh this test needs");

    banyan_mesh one = *m; /* the same arrays as one primitive: one whole-mesh range */
    one.part_count = 0;
    one.parts = nullptr;
    one.material_count = 1;

    std::vector<const banyan_mesh *> meshes = {m, &one};
    std::vector<TangentKey> keys;
    std::vector<std::vector<float>> want;
    references(meshes, keys, want);
    CHECK(keys.size() >= 3, "%zu ranges, expected the parts' and one whole", keys.size());
    bool whole = false;
    for (const TangentKey &k : keys) whole = whole || k.whole;
    CHECK(whole, "no whole-mesh range");

    std::vector<banyan_gltf_node> nodes = {banyan_gltf_node{m, "parts", 0, nullptr, nullptr},
                                           banyan_gltf_node{&one, "one", 0, nullptr, nullptr}};
    for (int order = 0; order < 3; ++order) check_takes("two nodes", nodes, keys, want, order);

    /* The same node twice: its ranges repeat; each take is still exact. */
    std::vector<banyan_gltf_node> twice = {nodes[0], nodes[0]};
    std::vector<TangentKey> k2;
    std::vector<std::vector<float>> w2;
    references({m, m}, k2, w2);
    for (int order = 0; order < 3; ++order) check_takes("a node twice", twice, k2, w2, order);

    /* A mesh the thread must not read after a good one: the thread stops
     * there; the good ranges are exact, taken from it or computed here. */
    std::vector<uint32_t> bad_ix(m->indices, m->indices + m->index_count);
    bad_ix[bad_ix.size() / 2] = m->vertex_count; /* out of range */
    banyan_mesh bad = *m;
    bad.indices = bad_ix.data();
    std::vector<banyan_gltf_node> with_bad = {nodes[0], banyan_gltf_node{&bad, "bad", 0, nullptr, nullptr}};
    std::vector<TangentKey> k3;
    std::vector<std::vector<float>> w3;
    references({m}, k3, w3);
    for (int order = 0; order < 3; ++order) check_takes("a good node, then a bad one", with_bad, k3, w3, order);

    /* The writer: the same bytes on every write. */
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_size = 64;
    o.texture_cache = 0;
    std::string a = std::string(argv[1]) + "/test_gltf_tangents_ahead_a.glb";
    std::string b = std::string(argv[1]) + "/test_gltf_tangents_ahead_b.glb";
    const banyan_mesh *const two[2] = {m, &one};
    CHECK(banyan_gltf_write_ex(a.c_str(), two, nullptr, 2, &o, &err) == BANYAN_OK, "write a: %s", err.message);
    CHECK(banyan_gltf_write_ex(b.c_str(), two, nullptr, 2, &o, &err) == BANYAN_OK, "write b: %s", err.message);
    const std::string da = read_file(a), db = read_file(b);
    CHECK(!da.empty() && da == db, "two writes of the same meshes differ (%zu, %zu bytes)", da.size(), db.size());

    banyan_mesh_free(m);
    return check_done("test_gltf_tangents_ahead");
}
