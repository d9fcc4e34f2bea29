/*
 * gltf_write_nodes.cpp - a mesh's materials, glTF meshes and nodes
 * (gltf_write.h): one node, or a parent holding one EXT_mesh_gpu_instancing
 * child per variant; MSFT_lod's coverages.
 */
#include "gltf/gltf_write.h"
#include "base/dmath.h"

#include <cmath>

namespace gltfw {

/* The screen coverage below which level k + 1 replaces level k (MSFT_lod's
 * "MSFT_screencoverage", one value per level, the primary first). */
double lod_coverage(const banyan_gltf_node &n, uint32_t k) {
    return n.lod_coverage ? n.lod_coverage[k] : 0.5 / std::ldexp(1.0, static_cast<int>(k));
}

/* One glTF material per banyan_material of the job's mesh: a library
 * texture or the mesh's own image carries the colour, else the factors. */
void emit_materials(tinygltf::Model &model, const Job &J, const int slot[2 * BANYAN_TEX_COUNT]) {
    const banyan_mesh *m = J.m;
    for (uint32_t k = 0; k < m->material_count; ++k) {
        const banyan_material *bm = &m->materials[k];
        tinygltf::Material mat;
        mat.name.assign(bm->name, name_len(bm->name, BANYAN_NAME_MAX));
        int image_tex = bm->image > 0 ? J.image_texture[static_cast<size_t>(bm->image - 1)] : -1;
        int key = image_tex < 0 && bm->image == 0 ? texture_key(m, bm) : -1;
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
}

/* Writes a job's materials, mesh(es) and node(s); returns the node that
 * stands for it (the one the scene or MSFT_lod lists). Without instances:
 * one mesh on one node. With instances: one mesh per variant that has
 * instances, each on a child node carrying EXT_mesh_gpu_instancing, under
 * a node that holds the mesh's origin. */
int emit_job(Builder &b, const Job &J, const int slot[2 * BANYAN_TEX_COUNT], bool &instanced) {
    tinygltf::Model &model = b.model;
    const banyan_mesh *m = J.m;
    emit_materials(model, J, slot);

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

} // namespace gltfw
