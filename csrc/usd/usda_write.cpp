/*
 * usda_write.cpp - banyan_usd_write_nodes (banyan/usd.h): the nodes as one
 * USD text layer, streamed through a bounded buffer into the atomic file.
 * Numbers are written shortest-round-trip (std::to_chars: the same bytes
 * on every CPU and locale). The textures come from the glTF writer's
 * texture stage (gltf_write.h: the same cache, names and PNG files).
 */
#include "banyan/usd.h"

#include "base/atomic_file.h"
#include "base/dmath.h"
#include "base/error.h"
#include "base/process.h"
#include "base/progress.h"
#include "gltf/gltf_write.h"
#include "textures/png_write.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace usdw {
namespace {

/* ------------------------------------------------------------ output */

/* Text into the temporary file through one fixed block: small pieces and
 * numbers go straight into it (no allocation a value), a full block is
 * written out. */
class Out {
  public:
    explicit Out(atomic_file *af) : af_(af), buf_(kBlock) {}
    Out &operator<<(const char *s) { return put(s, std::strlen(s)); }
    Out &operator<<(const std::string &s) { return put(s.data(), s.size()); }
    Out &put(const char *s, size_t n) {
        if (n > kBlock - used_) {
            flush();
            if (n > kBlock) return write(s, n);
        }
        std::memcpy(buf_.data() + used_, s, n);
        used_ += n;
        return *this;
    }
    void num(double v) { put_chars(v); }
    void num(float v) { put_chars(v); }
    void num(uint64_t v) { put_chars(v); }
    void flush() {
        write(buf_.data(), used_);
        used_ = 0;
    }
    int error() const { return err_; }

  private:
    static const size_t kBlock = 1 << 20;
    static const size_t kNumber = 48; /* the longest number to_chars writes here, with room */
    Out &write(const char *s, size_t n) {
        if (!err_ && n && std::fwrite(s, 1, n, af_->f) != n) err_ = errno ? errno : EIO;
        return *this;
    }
    template <class T> void put_chars(T v) {
        if (kBlock - used_ < kNumber) flush();
        auto r = std::to_chars(buf_.data() + used_, buf_.data() + used_ + kNumber, v);
        used_ = static_cast<size_t>(r.ptr - buf_.data());
    }
    atomic_file *af_;
    std::vector<char> buf_;
    size_t used_ = 0;
    int err_ = 0;
};

/* A USD identifier from any name: [A-Za-z_][A-Za-z0-9_]*, unique among
 * the names in `used`. */
std::string prim_name(const char *name, std::map<std::string, int> &used) {
    std::string s;
    for (const char *p = name; p && *p; ++p) {
        const char c = *p;
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        s += ok ? c : '_';
    }
    if (s.empty() || (s[0] >= '0' && s[0] <= '9')) s = "_" + s;
    int &n = used[s];
    std::string out = n ? s + "_" + std::to_string(n) : s;
    ++n;
    return out;
}

/* ------------------------------------------------------------ writer */

struct Writer {
    const char *path;
    banyan_gltf_options o;
    prog *g;
    banyan_error *err;
    Out &out;
    std::string folder;                         /* the layer's folder, with its separator */
    std::string image_dir;                      /* relative to folder */
    std::string layer_stem;                     /* the layer's file stem: its images' names begin with it */
    std::vector<gltfw::TexturePngs> textures;   /* the library's, planned */
    int slot[2 * BANYAN_TEX_COUNT];
    std::vector<std::string> tex_uri;           /* 2 t: base colour, 2 t + 1: normal map */

    banyan_status node(const banyan_gltf_node &n, const std::string &name, uint32_t index);
    banyan_status geom(const banyan_mesh *m, const std::string &root, const std::string &stem, const char *indent);
    banyan_status materials(const banyan_mesh *m, const std::string &scope, const std::string &stem,
                            const std::string &ind, std::vector<std::string> &mat_path);
    void material(const banyan_mesh *m, uint32_t k, const std::string &mpath, const std::string &uri,
                  const std::string &normal_uri, const std::string &ind);
    void mesh_part(const banyan_mesh *m, const banyan_part &pt, const std::string &name, const std::string &mat,
                   const std::string &ind);
    void skeleton(const banyan_mesh *m, const std::string &ind);
    banyan_status write(const banyan_gltf_node *nodes, uint32_t count);
    void instancer(const banyan_mesh *m, const std::string &proto_root, const std::vector<uint32_t> &groups,
                   const std::string &ind);
    banyan_status draw_textures();
    /* The budget ran out where only the deadline saw it (an encoder). */
    banyan_status over() {
        if (g->cancelled == PROG_RUNNING) {
            g->cancelled = PROG_OVER_TIME;
            g->over_value = process_now() - g->t_start;
        }
        return prog_fail(g, err, "writing USD");
    }
    banyan_status io_fail(int e, const std::string &what) {
        return banyan_fail(err, BANYAN_E_IO, "cannot write '%.300s': %s", what.c_str(), std::strerror(e));
    }
};

void vec3(Out &out, const float *p) {
    out << "(";
    out.num(p[0]);
    out << ", ";
    out.num(p[1]);
    out << ", ";
    out.num(p[2]);
    out << ")";
}

/* [(x, y, z), ...]: `count` triples starting at p. */
void vec3_array(Out &out, const float *p, uint32_t count) {
    out << "[";
    for (uint32_t i = 0; i < count; ++i) {
        if (i) out << ", ";
        vec3(out, p + 3 * static_cast<size_t>(i));
    }
    out << "]";
}

/* The library textures the nodes' meshes name: their files under
 * image_dir, drawn (through the texture cache) where missing. */
banyan_status Writer::draw_textures() {
    for (gltfw::TexturePngs &t : textures) {
        std::string base, normal;
        gltfw::texture_uris(t, o, image_dir, base, normal);
        tex_uri.push_back(base);
        tex_uri.push_back(normal);
        if (gltfw::is_regular_file(folder + base) && gltfw::is_regular_file(folder + normal)) continue;
        prog_deadline stop = prog_deadline_of(g);
        banyan_status s = gltfw::draw_texture(t.kind, t.season, o, stop, g->max_seconds, t, err);
        if (s != BANYAN_OK) return s;
        if (int e = gltfw::write_png_file(folder + base, t.base, o.sync != 0)) return io_fail(e, folder + base);
        if (int e = gltfw::write_png_file(folder + normal, t.normal, o.sync != 0)) return io_fail(e, folder + normal);
        t.base.clear();
        t.normal.clear();
    }
    return BANYAN_OK;
}

/* One UsdUVTexture shader reading primvars:st (connections name absolute
 * paths: a relative one inside a variant would carry its selection). */
void texture_shader(Out &out, const std::string &ind, const std::string &mpath, const char *name, const std::string &uri,
                    bool normal) {
    out << ind << "def Shader \"" << name << "\"\n" << ind << "{\n";
    out << ind << "    uniform token info:id = \"UsdUVTexture\"\n";
    out << ind << "    asset inputs:file = @" << uri << "@\n";
    out << ind << "    float2 inputs:st.connect = <" << mpath << "/St.outputs:result>\n";
    out << ind << "    token inputs:wrapS = \"repeat\"\n" << ind << "    token inputs:wrapT = \"repeat\"\n";
    if (normal) {
        out << ind << "    token inputs:sourceColorSpace = \"raw\"\n";
        out << ind << "    float4 inputs:scale = (2, 2, 2, 1)\n" << ind << "    float4 inputs:bias = (-1, -1, -1, 0)\n";
    } else {
        out << ind << "    token inputs:sourceColorSpace = \"sRGB\"\n";
        out << ind << "    float outputs:a\n";
    }
    out << ind << "    float3 outputs:rgb\n" << ind << "}\n";
}

/* Material k of m at mpath: UsdPreviewSurface, textured from `uri` (a
 * library texture's base colour, whose normal map is uri's pair, or a
 * mesh image) or flat. */
void Writer::material(const banyan_mesh *m, uint32_t k, const std::string &mpath, const std::string &uri,
                      const std::string &normal_uri, const std::string &ind) {
    const banyan_material &bm = m->materials[k];
    const std::string in = ind + "    ";
    const bool tex = !uri.empty();
    const bool library = tex && !normal_uri.empty();
    out << ind << "def Material \"" << mpath.substr(mpath.rfind('/') + 1) << "\"\n" << ind << "{\n";
    out << in << "token outputs:surface.connect = <" << mpath << "/Surface.outputs:surface>\n";
    out << in << "def Shader \"Surface\"\n" << in << "{\n";
    out << in << "    uniform token info:id = \"UsdPreviewSurface\"\n";
    if (tex) {
        out << in << "    color3f inputs:diffuseColor.connect = <" << mpath << "/BaseColor.outputs:rgb>\n";
    } else {
        out << in << "    color3f inputs:diffuseColor = ";
        vec3(out, bm.base_color);
        out << "\n";
    }
    out << in << "    float inputs:metallic = 0\n" << in << "    float inputs:roughness = ";
    out.num(bm.roughness);
    out << "\n";
    if (bm.alpha_cutoff > 0 && tex) {
        out << in << "    float inputs:opacity.connect = <" << mpath << "/BaseColor.outputs:a>\n";
        out << in << "    float inputs:opacityThreshold = ";
        out.num(bm.alpha_cutoff);
        out << "\n";
    } else if (bm.base_color[3] < 1) {
        out << in << "    float inputs:opacity = ";
        out.num(bm.base_color[3]);
        out << "\n";
    }
    if (library) out << in << "    normal3f inputs:normal.connect = <" << mpath << "/Normal.outputs:rgb>\n";
    out << in << "    token outputs:surface\n" << in << "}\n";
    if (tex) {
        out << in << "def Shader \"St\"\n" << in << "{\n";
        out << in << "    uniform token info:id = \"UsdPrimvarReader_float2\"\n";
        out << in << "    string inputs:varname = \"st\"\n" << in << "    float2 outputs:result\n" << in << "}\n";
        texture_shader(out, in, mpath, "BaseColor", uri, false);
        if (library) texture_shader(out, in, mpath, "Normal", normal_uri, true);
    }
    out << ind << "}\n";
}

/* The materials of m in a Scope "Materials" under scope; the mesh's own
 * images (a billboard's picture) written as PNG files named after stem. */
banyan_status Writer::materials(const banyan_mesh *m, const std::string &scope, const std::string &stem,
                                const std::string &ind, std::vector<std::string> &mat_path) {
    std::map<std::string, int> used;
    std::vector<std::string> image_uri(m->image_count);
    out << ind << "def Scope \"Materials\"\n" << ind << "{\n";
    for (uint32_t k = 0; k < m->material_count; ++k) {
        const banyan_material &bm = m->materials[k];
        mat_path.push_back(scope + "/Materials/" + prim_name(bm.name, used));
        std::string uri, normal_uri;
        if (o.textures && bm.image > 0 && m->uvs) { /* image k is images[k - 1] */
            const uint32_t im = static_cast<uint32_t>(bm.image - 1);
            if (image_uri[im].empty()) {
                image_uri[im] = image_dir + "/" + stem + "_image" + std::to_string(im) + ".png";
                uint8_t *png = nullptr;
                size_t len = 0;
                prog_deadline stop = prog_deadline_of(g);
                const banyan_image &I = m->images[im];
                int r = png_write(I.pixels, static_cast<int>(I.width), static_cast<int>(I.height),
                                  static_cast<int>(I.channels), PNG_WRITE_FILTER, PNG_WRITE_LEVEL, &stop, &png, &len);
                if (r < 0) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory encoding image %u", im);
                if (r > 0) return over();
                std::vector<unsigned char> bytes(png, png + len);
                banyan_png_free(png);
                if (int e = gltfw::write_png_file(folder + image_uri[im], bytes, o.sync != 0))
                    return io_fail(e, folder + image_uri[im]);
            }
            uri = image_uri[im];
        } else if (o.textures) {
            const int key = gltfw::texture_key(m, &bm);
            if (key >= 0 && slot[key] >= 0) {
                uri = tex_uri[2 * static_cast<size_t>(slot[key])];
                normal_uri = tex_uri[2 * static_cast<size_t>(slot[key]) + 1];
            }
        }
        material(m, k, mat_path.back(), uri, normal_uri, ind + "    ");
    }
    out << ind << "}\n";
    return BANYAN_OK;
}

/* A float primvar (one value a vertex) from `count` values at p. */
void primvar(Out &out, const std::string &ind, const char *type, const char *name, const float *p, uint32_t count,
             int width) {
    out << ind << type << " primvars:" << name << " = [";
    for (uint32_t i = 0; i < count; ++i) {
        if (i) out << ", ";
        if (width == 1) {
            out.num(p[i]);
            continue;
        }
        out << "(";
        for (int c = 0; c < width; ++c) {
            if (c) out << ", ";
            out.num(p[static_cast<size_t>(width) * i + static_cast<size_t>(c)]);
        }
        out << ")";
    }
    out << "] (\n" << ind << "    interpolation = \"vertex\"\n" << ind << ")\n";
}

/* A custom attribute's primvar name: its own, made an identifier, or
 * banyan_<name> where it would meet a primvar the writer sets itself. */
std::string attribute_primvar(const char *name) {
    std::map<std::string, int> none;
    std::string s = prim_name(name, none);
    if (s == "st" || s == "displayColor" || s == "displayOpacity" || s == "wind_pivot" || s == "normals")
        s = "banyan_" + s;
    return s;
}

/* One part as a Mesh: its triangles (indices from its first vertex). */
void Writer::mesh_part(const banyan_mesh *m, const banyan_part &pt, const std::string &name, const std::string &mat,
                       const std::string &ind) {
    const std::string in = ind + "    ";
    const uint32_t v0 = pt.vertex_offset, nv = pt.vertex_count, nt = pt.index_count / 3;
    out << ind << "def Mesh \"" << name << "\" (\n" << in << "prepend apiSchemas = [\"MaterialBindingAPI\"]\n"
        << ind << ")\n" << ind << "{\n";
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (uint32_t v = 0; v < nv; ++v)
        for (int c = 0; c < 3; ++c) {
            const float x = m->positions[3 * (static_cast<size_t>(v0) + v) + c];
            lo[c] = v == 0 || x < lo[c] ? x : lo[c];
            hi[c] = v == 0 || x > hi[c] ? x : hi[c];
        }
    out << in << "float3[] extent = [";
    vec3(out, lo);
    out << ", ";
    vec3(out, hi);
    out << "]\n" << in << "int[] faceVertexCounts = [";
    for (uint32_t t = 0; t < nt; ++t) out << (t ? ", 3" : "3");
    out << "]\n" << in << "int[] faceVertexIndices = [";
    for (uint32_t k = 0; k < 3 * nt; ++k) {
        if (k) out << ", ";
        out.num(static_cast<uint64_t>(m->indices[pt.index_offset + k] - v0));
    }
    out << "]\n" << in << "rel material:binding = <" << mat << ">\n";
    if (m->materials[pt.material].double_sided) out << in << "uniform bool doubleSided = 1\n";
    if (m->normals) {
        out << in << "normal3f[] normals = ";
        vec3_array(out, m->normals + 3 * static_cast<size_t>(v0), nv);
        out << " (\n" << in << "    interpolation = \"vertex\"\n" << in << ")\n";
    }
    out << in << "point3f[] points = ";
    vec3_array(out, m->positions + 3 * static_cast<size_t>(v0), nv);
    out << "\n";
    if (m->uvs) primvar(out, in, "texCoord2f[]", "st", m->uvs + 2 * static_cast<size_t>(v0), nv, 2);
    if (m->colors) {
        std::vector<float> rgb(3 * static_cast<size_t>(nv));
        for (uint32_t v = 0; v < nv; ++v)
            for (int c = 0; c < 3; ++c) rgb[3 * static_cast<size_t>(v) + c] = m->colors[4 * (static_cast<size_t>(v0) + v) + c];
        primvar(out, in, "color3f[]", "displayColor", rgb.data(), nv, 3);
    }
    const float *px = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X);
    const float *py = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Y);
    const float *pz = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Z);
    if (px && py && pz) {
        std::vector<float> piv(3 * static_cast<size_t>(nv));
        for (uint32_t v = 0; v < nv; ++v) {
            piv[3 * static_cast<size_t>(v)] = px[v0 + v];
            piv[3 * static_cast<size_t>(v) + 1] = py[v0 + v];
            piv[3 * static_cast<size_t>(v) + 2] = pz[v0 + v];
        }
        primvar(out, in, "float3[]", "wind_pivot", piv.data(), nv, 3);
    }
    for (uint32_t a = 0; a < m->attribute_count; ++a) {
        const banyan_attribute &at = m->attributes[a];
        if (px && py && pz && std::strncmp(at.name, "wind_pivot_", 11) == 0) continue;
        primvar(out, in, "float[]", attribute_primvar(at.name).c_str(), at.data + v0, nv, 1);
    }
    out << in << "uniform token subdivisionScheme = \"none\"\n" << ind << "}\n";
}

/* The skeleton: one linear two-point curve an edge, widths = diameters. */
void Writer::skeleton(const banyan_mesh *m, const std::string &ind) {
    const std::string in = ind + "    ";
    const uint32_t ne = m->skel_edge_count;
    out << ind << "def BasisCurves \"Skeleton\"\n" << ind << "{\n";
    out << in << "uniform token type = \"linear\"\n" << in << "uniform token purpose = \"guide\"\n";
    out << in << "int[] curveVertexCounts = [";
    for (uint32_t e = 0; e < ne; ++e) out << (e ? ", 2" : "2");
    out << "]\n" << in << "point3f[] points = [";
    for (uint32_t k = 0; k < 2 * ne; ++k) {
        if (k) out << ", ";
        vec3(out, m->skel_points + 3 * static_cast<size_t>(m->skel_edges[k]));
    }
    out << "]\n" << in << "float[] widths = [";
    for (uint32_t k = 0; k < 2 * ne; ++k) {
        if (k) out << ", ";
        out.num(2 * m->skel_radius[m->skel_edges[k]]);
    }
    out << "] (\n" << in << "    interpolation = \"vertex\"\n" << in << ")\n";
    out << in << "int[] primvars:tag = [";
    for (uint32_t k = 0; k < 2 * ne; ++k) {
        if (k) out << ", ";
        out.num(static_cast<double>(m->skel_tag[m->skel_edges[k]]));
    }
    out << "] (\n" << in << "    interpolation = \"vertex\"\n" << in << ")\n" << ind << "}\n";
}

/* The instances: a PointInstancer over the variants under proto_root. */
void Writer::instancer(const banyan_mesh *m, const std::string &proto_root, const std::vector<uint32_t> &groups,
                       const std::string &ind) {
    const std::string in = ind + "    ";
    std::map<uint32_t, uint32_t> proto;
    out << in << "rel prototypes = [";
    for (size_t k = 0; k < groups.size(); ++k) {
        proto[groups[k]] = static_cast<uint32_t>(k);
        out << (k ? ", <" : "<") << proto_root << "/variant_" << std::to_string(groups[k]) << ">";
    }
    out << "]\n" << in << "int[] protoIndices = [";
    for (uint32_t i = 0; i < m->instance_count; ++i) {
        if (i) out << ", ";
        out.num(static_cast<uint64_t>(proto[m->instances[i].variant]));
    }
    out << "]\n" << in << "point3f[] positions = [";
    for (uint32_t i = 0; i < m->instance_count; ++i) {
        if (i) out << ", ";
        vec3(out, m->instances[i].translation);
    }
    out << "]\n" << in << "quath[] orientations = [";
    for (uint32_t i = 0; i < m->instance_count; ++i) {
        const double h = 0.5 * static_cast<double>(m->instances[i].rotation_z);
        /* dm_*: the same bytes on every CPU (glibc's libm dispatches by CPU) */
        const float q[3] = {static_cast<float>(dm_cos(h)), 0.0f, static_cast<float>(dm_sin(h))};
        out << (i ? ", (" : "(");
        out.num(q[0]);
        out << ", 0, 0, ";
        out.num(q[2]);
        out << ")";
    }
    out << "]\n" << in << "float3[] scales = [";
    for (uint32_t i = 0; i < m->instance_count; ++i) {
        const float s = m->instances[i].scale, sv[3] = {s, s, s};
        if (i) out << ", ";
        vec3(out, sv);
    }
    out << "]\n";
}

/* The part names of one group, unique within it. */
std::vector<std::string> part_names(const banyan_mesh *m, uint32_t group) {
    std::map<std::string, int> used;
    std::vector<std::string> names;
    for (uint32_t q = 0; q < m->part_count; ++q)
        names.push_back(m->parts[q].group == group ? prim_name(m->materials[m->parts[q].material].name, used)
                                                   : std::string());
    return names;
}

/* One mesh's prims (materials, parts, skeleton, instances) in a Scope
 * "Geom" at root (the node's path). */
banyan_status Writer::geom(const banyan_mesh *m, const std::string &root, const std::string &stem, const char *indent) {
    const std::string ind = indent, in = ind + "    ", scope = root + "/Geom";
    out << ind << "def Scope \"Geom\"\n" << ind << "{\n";
    std::vector<std::string> mat;
    if (banyan_status s = materials(m, scope, stem, in, mat)) return s;
    const std::vector<uint32_t> groups = gltfw::drawn_groups(m);
    const bool inst = m->instance_count > 0;
    std::string proto_root = scope + "/Instances/Prototypes";
    std::string gind = in;
    if (inst) {
        out << in << "def PointInstancer \"Instances\"\n" << in << "{\n";
        instancer(m, proto_root, groups, in);
        out << in << "    def Scope \"Prototypes\"\n" << in << "    {\n";
        gind = in + "        ";
    }
    for (uint32_t grp : groups) {
        const bool own = inst || groups.size() > 1;
        const std::vector<std::string> names = part_names(m, grp);
        std::string pind = gind;
        if (own) {
            out << gind << "def Xform \"" << (inst ? "variant_" : "group_") << std::to_string(grp) << "\"\n" << gind << "{\n";
            pind += "    ";
        }
        for (uint32_t q = 0; q < m->part_count; ++q) {
            const banyan_part &pt = m->parts[q];
            if (pt.group != grp || pt.index_count == 0) continue;
            mesh_part(m, pt, names[q], mat[pt.material], pind);
            if (out.error()) return io_fail(out.error(), path);
            if (prog_at(g, 0.0)) return over();
        }
        if (own) out << gind << "}\n";
    }
    if (inst) out << in << "    }\n" << in << "}\n";
    /* An instanced mesh's skeleton stands in its variants' frames: not
     * written (the variants' meshes carry the wind pivots). */
    if (!inst && m->skel_edge_count > 0 && m->skel_points && m->skel_radius && m->skel_tag) skeleton(m, in);
    out << ind << "}\n";
    return BANYAN_OK;
}

/* One node: an Xform at the mesh's origin holding its Geom, or a variant
 * set "LOD" of one Geom a level. */
banyan_status Writer::node(const banyan_gltf_node &n, const std::string &name, uint32_t index) {
    const std::string root = "/" + name;
    const std::string stem = layer_stem + "_" + std::to_string(index);
    out << "def Xform \"" << name << "\" (\n    kind = \"component\"\n";
    if (n.lod_count > 0) out << "    variants = {\n        string LOD = \"lod0\"\n    }\n    prepend variantSets = \"LOD\"\n";
    out << ")\n{\n    double3 xformOp:translate = (";
    for (int c = 0; c < 3; ++c) {
        if (c) out << ", ";
        out.num(n.mesh->origin[c]);
    }
    out << ")\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n";
    if (n.lod_count == 0) {
        if (banyan_status s = geom(n.mesh, root, stem, "    ")) return s;
    } else {
        out << "    variantSet \"LOD\" = {\n";
        for (uint32_t k = 0; k <= n.lod_count; ++k) {
            const banyan_mesh *m = k == 0 ? n.mesh : n.lods[k - 1];
            out << "        \"lod" << std::to_string(k) << "\" {\n";
            if (banyan_status s = geom(m, root, stem + "_lod" + std::to_string(k), "            ")) return s;
            out << "        }\n";
        }
        out << "    }\n";
    }
    out << "}\n\n";
    return BANYAN_OK;
}

banyan_status Writer::write(const banyan_gltf_node *nodes, uint32_t count) {
    std::map<std::string, int> used;
    std::vector<std::string> names;
    for (uint32_t i = 0; i < count; ++i) {
        const std::string given = nodes[i].name ? std::string(nodes[i].name) : "banyan_" + std::to_string(i);
        names.push_back(prim_name(given.c_str(), used));
    }
    out << "#usda 1.0\n(\n    defaultPrim = \"" << names[0] << "\"\n";
    out << "    doc = \"banyan " << banyan_version_string() << "\"\n";
    out << "    metersPerUnit = 1\n    upAxis = \"Z\"\n)\n\n";
    for (uint32_t i = 0; i < count; ++i)
        if (banyan_status s = node(nodes[i], names[i], i)) return s;
    out.flush();
    if (out.error()) return io_fail(out.error(), path);
    return BANYAN_OK;
}

/* The path's extension: 1 text USD, 0 a crate (refused), -1 other. */
int usd_kind(const char *path) {
    if (gltfw::ends_with_ci(path, ".usda") || gltfw::ends_with_ci(path, ".usd")) return 1;
    if (gltfw::ends_with_ci(path, ".usdc") || gltfw::ends_with_ci(path, ".usdz")) return 0;
    return -1;
}

banyan_status check_call(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                         const banyan_gltf_options &o, banyan_error *err) {
    if (path == nullptr) return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is NULL");
    if (path[0] == '\0') return banyan_fail(err, BANYAN_E_INVALID_ARG, "path is empty");
    const int kind = usd_kind(path);
    if (kind == 0)
        return banyan_fail(err, BANYAN_E_UNSUPPORTED,
                           "path '%.300s': banyan writes USD text (.usda or .usd); convert it to a crate file with "
                           "OpenUSD's usdcat",
                           path);
    if (kind < 0) return banyan_fail(err, BANYAN_E_INVALID_ARG, "path '%.300s' must end in .usda or .usd", path);
    if (banyan_status s = gltfw::check_options(o, err)) return s;
    if (o.engine_uvs)
        return banyan_fail(err, BANYAN_E_RANGE, "opt->engine_uvs = 1 is for glTF only; USD carries the wind as primvars");
    if (o.pivot_painter)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "opt->pivot_painter = 1 is for glTF only; USD carries the wind as primvars");
    if (o.compact) return banyan_fail(err, BANYAN_E_RANGE, "opt->compact = 1 is for glTF only");
    if (count == 0) return banyan_fail(err, BANYAN_E_INVALID_ARG, "count is 0; nothing to write");
    if (count > gltfw::kMaxNodes)
        return banyan_fail(err, BANYAN_E_RANGE, "count = %u is outside [1, %u]", count, gltfw::kMaxNodes);
    if (nodes == nullptr) return banyan_fail(err, BANYAN_E_INVALID_ARG, "nodes is NULL but count = %u", count);
    for (uint32_t i = 0; i < count; ++i)
        if (banyan_status s = gltfw::check_node(nodes[i], i, false, err)) return s;
    return BANYAN_OK;
}

/* The layer's file name without folder and extension, as a file-name part. */
std::string stem_of(const char *path) {
    std::string f = path + gltfw::folder_of(path).size();
    const size_t dot = f.rfind('.');
    if (dot != std::string::npos) f.resize(dot);
    std::string s;
    for (char c : f) s += ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-') ? c : '_';
    return s.empty() ? "layer" : s;
}

banyan_status write_impl(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                         const banyan_gltf_options *opt, const banyan_budget *budget, banyan_error *err) {
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    if (opt) o = *opt;
    if (banyan_status s = check_call(path, nodes, count, o, err)) return s;
    prog g;
    prog_init(&g, nullptr);
    if (banyan_status s = prog_budget_from(&g, budget, err)) return s;
    char why[512];
    if (atomic_check(path, why, sizeof why)) return banyan_fail(err, BANYAN_E_IO, "cannot write '%.300s': %s", path, why);
    atomic_file af;
    if (int e = atomic_open(&af, path)) return banyan_fail(err, BANYAN_E_IO, "cannot write '%.300s': %s", path, std::strerror(e));
    af.sync = o.sync;
    Out out(&af);
    Writer W{path, o, &g, err, out, gltfw::folder_of(path), (o.image_dir && o.image_dir[0]) ? o.image_dir : "textures",
             stem_of(path), {}, {}, {}};
    std::vector<const banyan_mesh *> all;
    for (uint32_t i = 0; i < count; ++i)
        for (uint32_t k = 0; k <= nodes[i].lod_count; ++k) all.push_back(k ? nodes[i].lods[k - 1] : nodes[i].mesh);
    gltfw::plan_textures(all.data(), static_cast<uint32_t>(all.size()), o, W.textures, W.slot);
    bool images = false;
    for (const banyan_mesh *m : all) images = images || (o.textures && m->image_count > 0);
    banyan_status s = BANYAN_OK;
    if ((!W.textures.empty() || images))
        if (int e = gltfw::make_folders(W.folder, W.image_dir)) s = W.io_fail(e, W.folder + W.image_dir);
    if (!s) s = W.draw_textures();
    if (!s) s = W.write(nodes, count);
    if (s) {
        atomic_abort(&af);
        return s;
    }
    if (int e = atomic_commit(&af)) return W.io_fail(e, path);
    return BANYAN_OK;
}

/* The C calls' wrapper: no exception leaves the library. */
banyan_status guarded(const char *path, const banyan_gltf_node *nodes, uint32_t count, const banyan_gltf_options *opt,
                      const banyan_budget *budget, banyan_error *err) {
    try {
        return write_impl(path, nodes, count, opt, budget, err);
    } catch (const std::bad_alloc &) {
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory while writing USD '%.300s'", path ? path : "(null)");
    } catch (const std::exception &e) {
        return banyan_fail(err, BANYAN_E_INTERNAL, "internal error while writing USD '%.300s': %s",
                           path ? path : "(null)", e.what());
    }
}

} // namespace
} // namespace usdw

extern "C" BANYAN_API banyan_status banyan_usd_write_nodes(const char *path, const banyan_gltf_node *nodes,
                                                           uint32_t count, const banyan_gltf_options *opt,
                                                           banyan_error *err) {
    return usdw::guarded(path, nodes, count, opt, nullptr, err);
}

extern "C" BANYAN_API banyan_status banyan_usd_write_nodes_budget(const char *path, const banyan_gltf_node *nodes,
                                                                  uint32_t count, const banyan_gltf_options *opt,
                                                                  const banyan_budget *budget, banyan_error *err) {
    return usdw::guarded(path, nodes, count, opt, budget, err);
}
