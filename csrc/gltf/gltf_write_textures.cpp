/*
 * gltf_write_textures.cpp - the library's textures the materials name
 * (gltf_write.h): planned, drawn on their own threads (through the texture
 * cache), and written as image files beside the asset with opt->image_dir.
 */
#include "gltf/gltf_write.h"
#include "textures/tex_cache.h"

#include <sys/stat.h>
#ifdef _WIN32
#include <direct.h>
#endif

#include <cstring>
#include <system_error>

namespace gltfw {

/* Indexed by banyan_texture_kind (NONE is never drawn). */
const char *const kKindNames[BANYAN_TEX_COUNT] = {"none", "keyaki_leaf", "ivy_leaf", "keyaki_bark", "fig_bark",
                                                  "ivy_stem"};
static_assert(BANYAN_TEX_NONE == 0 && BANYAN_TEX_KEYAKI_LEAF == 1 && BANYAN_TEX_IVY_STEM == 5 && BANYAN_TEX_COUNT == 6,
              "kKindNames follows banyan_texture_kind");

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

TextureDrawer::TextureDrawer(const banyan_gltf_options &o, const prog_deadline &stop, double seconds,
                             std::vector<TexturePngs> &t)
    : o_(o), stop_(stop), seconds_(seconds), t_(t), status_(t.size(), BANYAN_OK), err_(t.size()), thrown_(t.size()) {
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

banyan_status TextureDrawer::wait(banyan_error *err) {
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

void TextureDrawer::draw(size_t i) {
    if (t_[i].have) return;
    try {
        status_[i] = draw_texture(t_[i].kind, t_[i].season, o_, stop_, seconds_, t_[i], &err_[i]);
    } catch (...) {
        thrown_[i] = std::current_exception();
    }
}

void texture_uris(const TexturePngs &t, const banyan_gltf_options &o, const std::string &dir, std::string &base,
                  std::string &normal) {
    std::string name = kKindNames[t.kind];
    if (is_leaf_kind(t.kind)) name += t.season == BANYAN_SEASON_AUTUMN ? "_autumn" : "_summer";
    const std::string tail = "-" + std::to_string(o.texture_size) + "-s" + std::to_string(o.texture_seed) + ".png";
    base = dir + "/" + name + tail;
    normal = dir + "/" + name + "_normal" + tail;
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

/* The most bytes a texture's PNG at `size` pixels a side can take: 4
 * channels and a filter byte a row, stored uncompressed (deflate's worst
 * case: zlib's compressBound), and the PNG's chunks. */
uint64_t png_bound(int32_t size) {
    const uint64_t raw = static_cast<uint64_t>(size) * (4 * static_cast<uint64_t>(size) + 1);
    return raw + (raw >> 12) + (raw >> 14) + (raw >> 25) + 13 + 1024;
}

} // namespace gltfw
