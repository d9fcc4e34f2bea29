/*
 * gltf_writer.cpp - banyan_gltf_write(): banyan meshes to one glTF 2.0 asset.
 *
 * Built on Debian's shared tinygltf 2.7 (include <tiny_gltf.h> without
 * TINYGLTF_IMPLEMENTATION); exposes nothing but the extern "C" functions
 * declared in banyan.h; compiled with -fvisibility=hidden and C++14 or
 * later (tinygltf's class layout depends on TINYGLTF_USE_CPP14, which the
 * Debian library was built with). This file holds the calls and the write's
 * stages in order; gltf_write.h lists the files that hold the rest.
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
 * converted on a second thread into a few small blocks while the
 * caller writes. The bytes are those tinygltf wrote when it held the
 * buffer, whatever the threads do.
 *
 * Nothing is created on disk until every input has been checked. The file
 * is written through base/atomic_file.h: a write that fails part-way
 * leaves the old file as it was; fsync only with opt->sync. No exception leaves this file.
 */
#include "base/error.h"
#include "gltf/gltf_compact.h"
#include "gltf/gltf_write.h"
#include "pp2/pp2.h"
#include "textures/tex_budget.h"
#include "textures/tex_cache.h"

#include <algorithm>
#include <cstring>
#include <new>
#include <sstream>

namespace gltfw {
namespace {

/* One call's state, stage by stage: check, plan, build the model, write. */
struct Write {
    Write(const char *path_, const banyan_gltf_node *nodes_, uint32_t count_, const banyan_budget *budget_, bool ex_,
          banyan_error *err_)
        : path(path_), nodes(nodes_), count(count_), budget(budget_), ex(ex_), err(err_) {}
    const char *path;
    const banyan_gltf_node *nodes;
    uint32_t count;
    const banyan_budget *budget;
    bool ex;
    banyan_error *err;
    banyan_gltf_options o;
    bool binary = false;

    prog g{};
    prog_deadline deadline{};

    std::vector<Job> jobs;
    std::vector<TexturePngs> textures;
    int slot[2 * BANYAN_TEX_COUNT];
    bool external = false;                         /* opt->image_dir: the textures as files */
    std::string image_folder;
    std::vector<std::string> image_uri;            /* per texture image (2 t, 2 t + 1) */
    size_t tex_views = 0;                          /* the textures' images in the buffer */
    std::vector<std::vector<unsigned char>> pictures; /* the meshes' own images, as PNG */
    int picture_base = 0;
    uint64_t total = 0;                            /* the buffer's planned bytes */

    Builder b;
    std::unique_ptr<TangentAhead> ahead; /* the textured meshes' tangents, computed beside the checks */

    banyan_status over() {
        if (g.cancelled == PROG_RUNNING) { /* the streaming thread saw the deadline first */
            g.cancelled = PROG_OVER_TIME;
            g.over_value = process_now() - g.t_start;
        }
        return prog_fail(&g, err, "writing glTF");
    }
    banyan_status too_big() {
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the glTF buffer would hold %llu bytes; the limit is %llu (4 GiB less the "
                           "JSON)",
                           static_cast<unsigned long long>(total), static_cast<unsigned long long>(kMaxBufferBytes));
    }

    banyan_status check_call();
    banyan_status check_nodes();
    void plan_jobs();
    banyan_status plan_pivot_painter();
    banyan_status plan_images();
    banyan_status plan_buffer();
    banyan_status build_model();
    banyan_status write_file(TextureDrawer &drawer);
};

/* The path, the options and the node array, before anything else. */
banyan_status Write::check_call() {
    if (path == nullptr) return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is NULL");
    if (path[0] == '\0') return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is empty");
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
    return BANYAN_OK;
}

/* Every node and its levels. */
banyan_status Write::check_nodes() {
    for (uint32_t i = 0; i < count; ++i) {
        banyan_status s = check_node(nodes[i], i, ex, err);
        if (s != BANYAN_OK) return s;
    }
    return BANYAN_OK;
}

/* Every mesh to write, in order (each node's own, then its levels), and
 * the library textures their materials name. */
void Write::plan_jobs() {
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
    plan_textures(all.data(), static_cast<uint32_t>(all.size()), o, textures, slot);
    /* opt->image_dir: the textures as files beside the asset, drawn only
     * where a file is missing; their images carry a URI, not a view. */
    external = o.image_dir != nullptr && o.image_dir[0] != '\0';
    image_folder = external ? folder_of(path) : std::string();
    if (external) {
        for (TexturePngs &t : textures) {
            std::string base, normal;
            texture_uris(t, o, o.image_dir, base, normal);
            image_uri.push_back(base);
            image_uri.push_back(normal);
            t.have = is_regular_file(image_folder + image_uri[image_uri.size() - 2]) &&
                     is_regular_file(image_folder + image_uri.back());
        }
    }
    tex_views = external ? 0 : 2 * textures.size();
}

/* opt->pivot_painter: each node's mesh gets its Pivot Painter 2 texel
 * centres (pp2.h), the UV set the textures of banyan_pivot_painter_write
 * are read through. Levels of detail are refused: their vertices are not
 * the mesh's, and their elements would not match its textures. */
banyan_status Write::plan_pivot_painter() {
    if (!o.pivot_painter) return BANYAN_OK;
    size_t j = 0;
    for (uint32_t i = 0; i < count; ++i) {
        std::string what = ex ? "meshes[" + std::to_string(i) + "]" : "nodes[" + std::to_string(i) + "].mesh";
        if (nodes[i].lod_count > 0)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                               "nodes[%u].lod_count = %u: opt->pivot_painter = 1 takes no levels of detail", i,
                               nodes[i].lod_count);
        Job &J = jobs[j];
        j += 1 + nodes[i].lod_count;
        pp2_table t;
        if (banyan_status s = pp2_build(J.m, what.c_str(), &t, err)) return s;
        try {
            J.pp2_uv.resize(2 * static_cast<size_t>(t.vertex_count));
        } catch (const std::bad_alloc &) {
            pp2_free(&t);
            return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the Pivot Painter UV set");
        }
        for (uint32_t v = 0; v < t.vertex_count; ++v) pp2_texel_uv(&t, t.texel[v], &J.pp2_uv[2 * static_cast<size_t>(v)]);
        pp2_free(&t);
        J.L.pp2 = J.pp2_uv.data();
    }
    return BANYAN_OK;
}

/* The meshes' own images (a billboard's picture), one PNG each that a
 * material names; with textures off, materials are drawn flat. */
banyan_status Write::plan_images() {
    picture_base = 2 * static_cast<int>(textures.size());
    for (Job &J : jobs) {
        J.image_texture.assign(J.m->image_count, -1);
        for (uint32_t k = 0; o.textures && J.m->image_count > 0 && k < J.m->material_count; ++k) {
            int32_t im = J.m->materials[k].image - 1; /* image k is images[k - 1] */
            if (im < 0 || J.image_texture[static_cast<size_t>(im)] >= 0) continue;
            ImageGuard ig;
            size_t size = 0;
            banyan_status s = tex_png(&J.m->images[im], &deadline, g.max_seconds, &ig.png, &size, err);
            if (s != BANYAN_OK) return s;
            pictures.emplace_back(ig.png, ig.png + size);
            J.image_texture[static_cast<size_t>(im)] = picture_base + static_cast<int>(pictures.size() - 1);
        }
    }
    return BANYAN_OK;
}

/* Each mesh's primitives and bytes, so the buffer's size is checked before
 * the textures are drawn, and their memory reserved. */
banyan_status Write::plan_buffer() {
    /* A mesh with a library-textured material gets tangents for its normal map. */
    for (Job &J : jobs)
        for (uint32_t k = 0; k < J.m->material_count; ++k) {
            const banyan_material *bm = &J.m->materials[k];
            if (bm->image > 0) continue;
            int key = texture_key(J.m, bm);
            if (key >= 0 && slot[key] >= 0) J.tangents = true;
        }
    int material_base = 0;
    for (Job &J : jobs) {
        J.material_base = material_base;
        total += plan_mesh(J.m, J.L, material_base, J.tangents, J.prims, J.local);
        J.tangent_ranges = J.tangents && tangent_ranges_exact(J.m, J.prims, J.local);
        total += instance_bytes(J.m);
        material_base += static_cast<int>(J.m->material_count);
    }
    for (const auto &p : pictures) total += pad4(p.size());
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
    return BANYAN_OK;
}

/* The model: images, samplers and textures first (their bytes go at the
 * end of the buffer), then each node's materials, meshes and levels. */
banyan_status Write::build_model() {
    tinygltf::Model &model = b.model;
    model.asset.version = "2.0";
    model.asset.generator = "banyan";

    /* Sampler 0 repeats (bark), sampler 1 clamps (atlases, pictures). */
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
    return BANYAN_OK;
}

/* The file: the JSON with the buffer's size, then the buffer's bytes
 * streamed from the meshes, then the images'. */
banyan_status Write::write_file(TextureDrawer &drawer) {
    tinygltf::Model &model = b.model;
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
    auto stream = [&](size_t from) { stream_segments(bin, out, b.segs, from, deadline, late, ahead.get()); };
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

banyan_status write_nodes_impl(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                               const banyan_gltf_options *opt, const banyan_budget *budget, bool ex,
                               banyan_error *err) {
    Write W(path, nodes, count, budget, ex, err);
    banyan_gltf_options_init(&W.o);
    if (opt) W.o = *opt;
    if (banyan_status s = W.check_call()) return s;
    /* The tangents start before the nodes are checked (the check is most of
     * the time before the first byte); the compact write's inner call starts
     * its own. The budget's clock starts after the check. */
    if (W.o.textures && !W.o.compact)
        W.ahead.reset(new TangentAhead(nodes, count, W.o));
    if (banyan_status s = W.check_nodes()) return s;
    if (W.o.compact) { /* the plain .glb, rewritten compact (gltf_compact.cpp) */
        banyan_gltf_options plain = W.o;
        plain.compact = 0;
        plain.sync = 0;
        return gltf_compact_write(path, W.binary, W.o.sync != 0, W.o.engine_uvs != 0, [&](const char *tmp) {
            return write_nodes_impl(tmp, nodes, count, &plain, budget, ex, err);
        }, err);
    }
    /* The budget: the textures' memory refused up front from their size,
     * time checked between meshes, while streaming and inside the texture
     * painters and PNG encoders (on the drawing threads, by deadline). */
    if (banyan_status sb = prog_budget_from(&W.g, budget, err)) return sb;
    W.deadline = prog_deadline_of(&W.g);
    W.plan_jobs();
    if (banyan_status s = W.plan_pivot_painter()) return s;
    if (banyan_status s = W.plan_images()) return s;
    if (banyan_status s = W.plan_buffer()) return s;
    if (prog_at(&W.g, 0.0)) return W.over();
    TextureDrawer drawer(W.o, W.deadline, W.g.max_seconds, W.textures);
    if (banyan_status s = W.build_model()) return s;
    return W.write_file(drawer);
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
} // namespace gltfw

using gltfw::guarded;
using gltfw::write_nodes_impl;

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
