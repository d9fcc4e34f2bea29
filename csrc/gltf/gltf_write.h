/*
 * gltf_write.h - what the pieces of the glTF writer share (internal; C++).
 *
 * The writer (banyan_gltf_write* in banyan.h) is split by stage:
 *   gltf_writer.cpp          the calls, the stages in order, the file's head and tail;
 *   gltf_write_check.cpp     validation of the meshes, nodes and options;
 *   gltf_write_plan.cpp      the buffer's layout: primitives, vertex accessors, segments;
 *   gltf_write_tangents.cpp  per-vertex tangents, computed ahead on their own thread;
 *   gltf_write_stream.cpp    the BIN chunk's bytes converted and written on two threads;
 *   gltf_write_textures.cpp  the library's textures drawn, the image files;
 *   gltf_write_nodes.cpp     materials, meshes, instanced variants and nodes.
 * Everything here is in namespace gltfw, hidden like the rest of the library.
 */
#ifndef BANYAN_GLTF_WRITE_H
#define BANYAN_GLTF_WRITE_H

#include "banyan.h"
#include "base/atomic_file.h"
#include "base/progress.h"

#include <tiny_gltf.h>

#include <cerrno>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && \
    __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "the glTF writer copies floats as they are in memory: glTF is little-endian"
#endif

namespace gltfw {

/* glTF buffers are addressed with 32-bit lengths in GLB; keep some room for
 * the JSON chunk as well. */
const uint64_t kMaxBufferBytes = UINT64_C(0xFFFFFFFF) - (UINT64_C(64) << 20);

inline uint64_t pad4(uint64_t n) { return (n + 3) & ~UINT64_C(3); }

const uint32_t kMaxNodes = 65536;
const uint32_t kMaxLods = 7;

inline bool is_leaf_kind(int32_t kind) { return kind == BANYAN_TEX_KEYAKI_LEAF || kind == BANYAN_TEX_IVY_LEAF; }

/* ------------------------------------------------------------ validation (gltf_write_check.cpp) */

size_t name_len(const char *s, size_t cap);
bool ends_with_ci(const char *s, const char *suffix);
/* The groups of a mesh's parts that have triangles, sorted: its variants
 * when it has instances. */
std::vector<uint32_t> drawn_groups(const banyan_mesh *m);
banyan_status check_options(const banyan_gltf_options &o, banyan_error *err);
/* A node's meshes and levels; ex: named as banyan_gltf_write_ex's meshes[i]. */
banyan_status check_node(const banyan_gltf_node &n, uint32_t i, bool ex, banyan_error *err);

/* ------------------------------------------------------------ building */

/* One piece of the BIN chunk, in buffer order: the views are planned
 * first (the JSON needs their offsets) and their bytes streamed to the file
 * afterwards, straight from the mesh arrays or converted through a fixed
 * scratch block, so no copy of the buffer is ever held in memory. */
enum SegKind { kRaw, kZero, kPosition, kNormal, kUv, kTangent, kColor, kWindPivot, kEngineUv, kPivotPainterUv, kIndices };

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
    const float *pp2 = nullptr; /* opt->pivot_painter: each vertex's texel centre (u, v), the last TEXCOORD_n */
};


/* One primitive to write: indices [ioff, ioff + icount) drawn over vertices
 * [vbase, vbase + vcount). */
struct Prim {
    uint32_t ioff, icount, vbase, vcount;
    int material;   /* index into model.materials or -1 */
    uint32_t group; /* its part's group: the variant of an instanced mesh */
};

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
    std::vector<float> pp2_uv;      /* opt->pivot_painter: L.pp2's floats */
};


/* ------------------------------------------------------------ planning (gltf_write_plan.cpp) */

/* The double with the fewest decimal digits that rounds to f. */
double short_double(float f);
bool colors_repeat_material(const banyan_mesh *m);
Layout layout_of(const banyan_mesh *m, bool engine_uvs);
std::map<std::string, int> add_vertex_range(Builder &b, const banyan_mesh *m, const Layout &L, uint32_t base,
                                            uint32_t count, bool with_colors, const Segment *tangent);
void plan_prims(const banyan_mesh *m, int material_base, std::vector<Prim> &prims, bool &local);
uint64_t plan_mesh(const banyan_mesh *m, const Layout &L, int material_base, bool tangents, std::vector<Prim> &prims,
                   bool &local);
bool tangent_ranges_exact(const banyan_mesh *m, const std::vector<Prim> &prims, bool local);
/* Bytes of the instancing accessors: TRANSLATION, ROTATION, SCALE. */
inline uint64_t instance_bytes(const banyan_mesh *m) { return (3 + 4 + 3) * 4ull * m->instance_count; }

/* ------------------------------------------------------------ tangents (gltf_write_tangents.cpp) */

std::vector<float> vertex_tangents(const banyan_mesh *m, uint32_t vbase, uint32_t vcount, uint32_t ioff,
                                   uint32_t icount, std::vector<double> &acc);

/* The range a kTangent segment's tangents come from: the whole mesh's
 * triangles, or vertices [base, +count) from indices [ioff, +icount). */
struct TangentKey {
    const banyan_mesh *m = nullptr;
    bool whole = false;
    uint32_t base = 0, count = 0, ioff = 0, icount = 0;
    bool operator==(const TangentKey &k) const;
};
TangentKey tangent_key(const Segment &s);
/* scratch: the sums' memory, kept by the caller for the next range. */
std::vector<float> tangents_of(const TangentKey &k, std::vector<double> &scratch);
void tangent_keys(const banyan_mesh *m, std::vector<TangentKey> &out);

/* The tangents of every textured mesh of nodes, computed on a thread of
 * their own from before the meshes are checked (it reads only meshes whose
 * fields it can trust), in the order the stream takes them, at most
 * kAheadBytes held ahead. take() hands over a range's tangents, computing
 * them itself (in scratch) when the thread has not reached them: the same
 * bits either way. The destructor stops the thread and waits for it. */
class TangentAhead {
  public:
    static constexpr size_t kAheadBytes = size_t(64) << 20;

    TangentAhead(const banyan_gltf_node *nodes, uint32_t count, const banyan_gltf_options &o);
    ~TangentAhead();
    TangentAhead(const TangentAhead &) = delete;
    TangentAhead &operator=(const TangentAhead &) = delete;
    std::shared_ptr<const std::vector<float>> take(const TangentKey &key, std::vector<double> &scratch);

  private:
    enum State { kComputing, kDone, kTaken };
    struct Entry {
        TangentKey key;
        State state;
        std::shared_ptr<const std::vector<float>> data;
    };
    void run();
    bool compute(const TangentKey &key);

    const banyan_gltf_node *nodes_;
    uint32_t count_;
    const banyan_gltf_options o_;
    std::mutex mu_;
    std::condition_variable cv_;
    std::vector<Entry> entries_;
    std::vector<double> scratch_; /* the worker's sums, reused from range to range */
    size_t held_ = 0;
    bool stop_ = false;
    std::thread th_;
};

/* ------------------------------------------------------------ textures (gltf_write_textures.cpp) */

extern const char *const kKindNames[BANYAN_TEX_COUNT];

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


/* The slot key of a material's texture, or -1 when it is drawn flat. */
int texture_key(const banyan_mesh *m, const banyan_material *bm);
void plan_textures(const banyan_mesh *const *meshes, uint32_t count, const banyan_gltf_options &o,
                   std::vector<TexturePngs> &out, int slot[2 * BANYAN_TEX_COUNT]);
/* One library texture's two PNGs into t (through the texture cache). */
banyan_status draw_texture(int32_t kind, int32_t season, const banyan_gltf_options &o, const prog_deadline &stop,
                           double seconds, TexturePngs &t, banyan_error *err);
/* Texture t's two files under `dir` (relative, '/'-separated) as the
 * writers name them: <image>-<size>-s<seed>.png and <image>_normal-....
 * (opt->image_dir for glTF, the layer's image folder for USD). */
void texture_uris(const TexturePngs &t, const banyan_gltf_options &o, const std::string &dir, std::string &base,
                  std::string &normal);
std::string folder_of(const char *path);
bool is_regular_file(const std::string &p);
int make_folders(const std::string &base, const std::string &rel);
int write_png_file(const std::string &path, const std::vector<unsigned char> &bytes, bool sync);
uint64_t png_bound(int32_t size);

/* The textures drawn on their own threads (up to kThreads, texture k on
 * thread k % kThreads) while the meshes are planned: the PNGs' sizes are
 * needed only for the views at the buffer's end. A texture whose thread
 * could not be started is drawn in wait(). The destructor waits. */
class TextureDrawer {
  public:
    static constexpr size_t kThreads = 2;

    TextureDrawer(const banyan_gltf_options &o, const prog_deadline &stop, double seconds, std::vector<TexturePngs> &t);
    ~TextureDrawer() { join(); }
    /* The first failed texture's status, its message in *err; rethrows its exception. */
    banyan_status wait(banyan_error *err);

  private:
    void draw(size_t i);
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

/* ------------------------------------------------------------ nodes (gltf_write_nodes.cpp) */

double lod_coverage(const banyan_gltf_node &n, uint32_t k);
int emit_job(Builder &b, const Job &J, const int slot[2 * BANYAN_TEX_COUNT], bool &instanced);

/* ------------------------------------------------------------ streaming (gltf_write_stream.cpp) */

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
    Sink(std::FILE *f, bool base64);
    int error() const { return error_; }
    uint64_t count() const { return count_; }
    /* Writes to f from now on (a Sink made before its file was opened). */
    void reset(std::FILE *f) { f_ = f; }
    void put(const void *data, size_t n);
    /* The last 1 or 2 bytes of a base64 stream, '='-padded. */
    void finish();

    static constexpr size_t kBlock = size_t(4) << 20;

  private:
    void raw(const unsigned char *p, size_t n);
    static void encode(const unsigned char *in, int n, char *o);

    std::FILE *f_;
    bool base64_;
    int error_ = 0;
    uint64_t count_ = 0;
    unsigned char hold_[3] = {0, 0, 0};
    int held_ = 0;
    std::vector<char> out_;
};

/* Streams segs[from ..] into bin, converted on a second thread while the
 * caller writes; late is set when the deadline passed first. */
void stream_segments(Sink &bin, OutFile &out, const std::vector<Segment> &segs, size_t from,
                     const prog_deadline &deadline, bool &late, TangentAhead *ahead);
bool split_document(const std::string &doc, bool binary, uint64_t total, std::string &head, std::string &tail,
                    size_t json_chunk = 0);

} // namespace gltfw

#endif
