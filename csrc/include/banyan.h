/*
 * banyan.h - public C API of libbanyan.
 *
 * libbanyan grows plants procedurally around host boxes: strangler-fig
 * roots, keyaki trees and avenues, ivy, and geometry-shader branch
 * segments. This header holds the shared types (status, error, box, mesh),
 * the parameter tables, presets and glTF export. Each generator's own
 * params and calls live in banyan/<generator>.h, included at the end.
 *
 * Conventions (see docs/api.md):
 *   - Z up, metres, radians only where a field says so (most angles are
 *     degrees, as in the papers, and say so).
 *   - Every call validates its input. A failed call returns a non-zero
 *     banyan_status, fills *err when err != NULL, leaves *out == NULL and
 *     leaks nothing.
 *   - Ownership: a banyan_mesh returned through `banyan_mesh **out` belongs
 *     to the caller, who frees it with banyan_mesh_free(). Nothing else the
 *     library returns needs freeing unless its doc says so. Every *_free
 *     accepts NULL (and does nothing); freeing a handle twice, or using it
 *     after it is freed, is undefined behaviour, as with free().
 *   - No global state: every call is reentrant and thread-safe on distinct
 *     arguments. The same params and seed give byte-identical output.
 */
#ifndef BANYAN_H
#define BANYAN_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(BANYAN_STATIC)
#  define BANYAN_API
#elif defined(_WIN32)
#  if defined(BANYAN_BUILD)
#    define BANYAN_API __declspec(dllexport)
#  else
#    define BANYAN_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define BANYAN_API __attribute__((visibility("default")))
#else
#  define BANYAN_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever a public struct's layout or a call's meaning changes.
 * The Blender add-on refuses to load a library with another version. */
#define BANYAN_ABI_VERSION 22

/* ---------------------------------------------------------------- status */

typedef enum banyan_status {
    BANYAN_OK = 0,
    BANYAN_E_INVALID_ARG = 1,  /* a NULL pointer or a malformed argument */
    BANYAN_E_RANGE = 2,        /* a number is NaN, inf or outside its range */
    BANYAN_E_NO_HOSTS = 3,     /* hosts are required but none were given */
    BANYAN_E_BAD_HOST = 4,     /* a host box is degenerate (zero extent, bad rotation) */
    BANYAN_E_START_INSIDE = 5, /* the start / germination point is inside a host */
    BANYAN_E_START_FAR = 6,    /* the start point is far from every host */
    BANYAN_E_LIMIT = 7,        /* the output would pass max_vertices; nothing allocated */
    BANYAN_E_NOMEM = 8,        /* an allocation failed */
    BANYAN_E_IO = 9,           /* a file could not be read or written */
    BANYAN_E_PARSE = 10,       /* a preset or JSON text is malformed */
    BANYAN_E_UNKNOWN_KEY = 11, /* a preset or --set names a key that does not exist */
    BANYAN_E_TYPE = 12,        /* a preset value has the wrong type */
    BANYAN_E_UNSUPPORTED = 13, /* a feature is not available in this build */
    BANYAN_E_INTERNAL = 14,    /* a broken invariant; please report it */
    BANYAN_E_CANCELLED = 15    /* the progress callback asked to stop; nothing returned */
} banyan_status;

/* Filled on failure when the caller passes a non-NULL pointer. The message
 * names the parameter, its value and its valid range. */
typedef struct banyan_error {
    int32_t code;       /* a banyan_status */
    char message[256];  /* NUL-terminated, UTF-8 */
} banyan_error;

/* A short fixed English name for a status ("BANYAN_E_RANGE"); never NULL. */
BANYAN_API const char *banyan_status_name(banyan_status s);

/* ------------------------------------------------------------- progress */

/* Progress and cancel for the long calls (banyan_roots_generate,
 * banyan_ivy_generate, banyan_avenue_generate), passed as a pointer
 * just before `err`; NULL = no progress. `done` is the fraction of the
 * call's work done, 0 .. 1, never decreasing; fn runs on the calling
 * thread, about 100 times for the fraction plus at most one every 0.1 s
 * while it moves slower (so a cancel is heard within about 0.1 s), and
 * once with exactly 1.0 just before a successful return. A nonzero return
 * cancels: the call stops soon after and returns BANYAN_E_CANCELLED with
 * *out == NULL and nothing leaked. fn must not call back into the same
 * generation. The output does not depend on the callback (docs/api.md). */
typedef int32_t (*banyan_progress_fn)(void *user, double done);
typedef struct banyan_progress {
    banyan_progress_fn fn; /* required when the struct is passed */
    void *user;            /* handed back to fn as is */
} banyan_progress;

/* --------------------------------------------------------------- budget */

/* The budget of a call whose params carry none (banyan_mesh_lod_budget,
 * banyan_texture_generate_budget, banyan_gltf_write_ex_budget,
 * banyan_gltf_write_nodes_budget, banyan_glb_read_host_budget,
 * banyan_preset_host_set_budget), with the generators' meaning and ranges
 * (docs/api.md "Budgets"): past max_seconds of wall time, or max_memory_mb
 * of resident memory above the process's at the call, the call stops (or
 * refuses up front, when its size says so) with BANYAN_E_LIMIT naming the
 * field, *out == NULL and nothing leaked. NULL: the defaults, which the
 * same calls without _budget use. Init with banyan_budget_init. */
typedef struct banyan_budget {
    double max_seconds;   /* s, 0.01 .. 604800. Default 600 */
    double max_memory_mb; /* MB, 16 .. 1048576. Default 8192 */
} banyan_budget;

BANYAN_API void banyan_budget_init(banyan_budget *b);
BANYAN_API size_t banyan_sizeof_budget(void);

/* ----------------------------------------------------------------- hosts */

/* An oriented box: a host object's bounding box under its world matrix.
 * A world point p is inside when |dot(p - center, axis_k)| <= half[k] for
 * k = 0,1,2, where axis_k is column k of `rotation`.
 *   center    metres, finite.
 *   half      half-extents in metres, each finite and > 0 (1e-6 .. 1e6).
 *   rotation  3x3, row-major: rotation[3*r + c]. Its columns are the box's
 *             local x, y, z axes in world space. Must be orthonormal with
 *             determinant +1 within 1e-3; a scaled matrix is refused
 *             (fold the scale into `half`). */
typedef struct banyan_box {
    double center[3];
    double half[3];
    double rotation[9];
} banyan_box;

/* Axis-aligned box helper: rotation = identity. */
BANYAN_API banyan_box banyan_box_make(double cx, double cy, double cz,
                                      double hx, double hy, double hz);

/* Checks one box; BANYAN_E_BAD_HOST names `hosts[index]` and the fault. */
BANYAN_API banyan_status banyan_box_validate(const banyan_box *box, uint32_t index,
                                             banyan_error *err);

/* ------------------------------------------------------------------ mesh */

#define BANYAN_NAME_MAX 32

/* One float per vertex, e.g. "root_kind", "tree_id", "birth_step". */
typedef struct banyan_attribute {
    char name[BANYAN_NAME_MAX]; /* NUL-terminated, [A-Za-z0-9_] */
    float *data;                /* vertex_count floats */
} banyan_attribute;

/* Wind and growth attributes (docs/game-engines.md). Every
 * generator's mesh carries them when its params' `wind` is 1 (the
 * default); `birth` is always there.
 *   wind_pivot_x/y/z  the point the vertex sways about, in the mesh's
 *                     frame (like positions): the base of its branch, of
 *                     its twig, or a leaf's petiole base; on the plant's own
 *                     skeleton.
 *   wind_level        branch order: 0 trunk (ivy: main stem; roots: the
 *                     root), 1 its branches, ...; a leaf is its twig's + 1.
 *   wind_stiffness    0..1: 1 does not move (trunk base, a stem stuck to
 *                     a wall, a root gripping its host), falling toward
 *                     the free tips; where a root or stem holds on again
 *                     further out, it is 1 there again.
 *   wind_phase        0..1, one value per branch (all of its vertices),
 *                     random from the branch: branches do not sway in step.
 *   wind_flutter      0..1: leaf flutter weight (1 on a leaf blade, 0 on
 *                     wood).
 *   birth             0..1: when the vertex appears as the plant grows (0
 *                     the first wood, 1 the last); growth animation shows
 *                     the vertices with birth <= t. */
#define BANYAN_ATTR_WIND_PIVOT_X "wind_pivot_x"
#define BANYAN_ATTR_WIND_PIVOT_Y "wind_pivot_y"
#define BANYAN_ATTR_WIND_PIVOT_Z "wind_pivot_z"
#define BANYAN_ATTR_WIND_LEVEL "wind_level"
#define BANYAN_ATTR_WIND_STIFFNESS "wind_stiffness"
#define BANYAN_ATTR_WIND_PHASE "wind_phase"
#define BANYAN_ATTR_WIND_FLUTTER "wind_flutter"
#define BANYAN_ATTR_BIRTH "birth"

/* An 8-bit image, rows top to bottom. channels 4 (RGBA, sRGB colour,
 * straight alpha) for base colour, 3 (RGB, tangent-space normal, glTF's
 * convention: +X right, +Y up in uv space) for normal maps. */
typedef struct banyan_image {
    uint32_t width, height, channels;
    uint8_t *pixels;         /* width * height * channels bytes */
} banyan_image;

/* A material: glTF metallic-roughness; a base colour factor and,
 * optionally, one of the library's textures (banyan/textures.h), which
 * the glTF writer embeds and the add-on packs. */
typedef struct banyan_material {
    char name[BANYAN_NAME_MAX];
    float base_color[4];        /* linear RGBA, each 0..1: the flat colour (textures off). With a
                                   texture the texture's colour replaces it: the glTF writer's
                                   baseColorFactor is then (1, 1, 1, base_color[3]) */
    float roughness;            /* 0..1 */
    int32_t double_sided;       /* 0 or 1; leaf cards are double sided */
    int32_t texture;            /* banyan_texture_kind; BANYAN_TEX_NONE (0): no texture */
    int32_t season;             /* banyan_season of a leaf texture; 0 otherwise */
    float alpha_cutoff;         /* > 0: alpha-tested (glTF MASK) at this cutoff, leaves 0.5; 0: opaque */
    float translucency;         /* 0..1: light through a back-lit leaf (Blender's material; glTF ignores it) */
    int32_t image;              /* which of the mesh's images is its base colour (RGBA), e.g. a billboard's
                                   picture, counted from 1: k is images[k - 1]; 0 (a zeroed material): no
                                   image. When > 0 it replaces `texture` */
} banyan_material;

/* One placed copy of a variant (instancing): the parts whose
 * group is `variant`, turned by rotation_z about +Z, scaled by scale,
 * then moved by translation (metres, in the mesh's frame). */
typedef struct banyan_instance {
    uint32_t variant;
    float translation[3];
    float rotation_z;           /* radians, counter-clockwise seen from above */
    float scale;                /* uniform, > 0 */
} banyan_instance;

/* A part is a contiguous run of vertices and of indices drawn with one
 * material. Parts never share vertices. Ivy has a stem part and a leaf
 * part; an avenue has parts grouped by tree (group = tree index). */
typedef struct banyan_part {
    uint32_t vertex_offset, vertex_count;
    uint32_t index_offset, index_count; /* indices are absolute vertex numbers */
    uint32_t material;                  /* index into materials */
    uint32_t group;                     /* generator-defined, e.g. tree index; else 0 */
} banyan_part;

/* A flat triangle mesh (par_shapes style) plus an optional skeleton.
 * Positions in metres, Z up. Triangles wind counter-clockwise seen from
 * outside. Every array below has the length its comment gives; optional
 * arrays are NULL when absent. */
typedef struct banyan_mesh {
    uint32_t vertex_count;
    uint32_t index_count;       /* 3 * triangle count */
    float *positions;           /* 3 * vertex_count */
    float *normals;             /* 3 * vertex_count, unit length */
    float *uvs;                 /* 2 * vertex_count; u around a tube 0..1, v along it in metres over the local
                                   circumference (square texels on a taper); leaf cards: an atlas cell */
    float *colors;              /* 4 * vertex_count linear RGBA, or NULL */
    uint32_t *indices;          /* index_count */

    uint32_t attribute_count;
    banyan_attribute *attributes;

    uint32_t material_count;    /* >= 1 */
    banyan_material *materials;
    uint32_t part_count;        /* >= 1; parts cover all vertices and indices in order */
    banyan_part *parts;

    /* Skeleton: the growth graph the mesh was swept from. */
    uint32_t skel_point_count;
    float *skel_points;         /* 3 * skel_point_count, metres */
    float *skel_radius;         /* skel_point_count, metres */
    int32_t *skel_tag;          /* skel_point_count; generator-defined (root kind, level...) */
    uint32_t skel_edge_count;
    uint32_t *skel_edges;       /* 2 * skel_edge_count point indices */

    /* The mesh's local origin in world metres (Z up). positions and
     * skel_points are relative to it: world = origin + position, added in
     * double. It is (0, 0, 0) for scenes near the world origin and a whole
     * number of metres near the hosts otherwise, so float positions keep
     * millimetres far away (docs/api.md "Far from the origin"). The
     * glTF writer puts it in the node's translation; the add-on in the
     * object's location. */
    double origin[3];

    /* Images the materials name (banyan_material.image: material image k
     * is images[k - 1]), owned by the mesh; 0 / NULL for none. */
    uint32_t image_count;
    banyan_image *images;

    /* Instancing. 0 / NULL: the mesh is drawn as it is. Otherwise the
     * parts of group g are variant g, standing at the frame's origin (its
     * foot), and each instance draws one variant where it stands. */
    uint32_t instance_count;
    banyan_instance *instances;
} banyan_mesh;

/* Frees a mesh and every array it owns. Accepts NULL. */
BANYAN_API void banyan_mesh_free(banyan_mesh *mesh);

/* The attribute array called `name`, or NULL. */
BANYAN_API const float *banyan_mesh_attribute(const banyan_mesh *mesh, const char *name);

/* Per-corner UVs, as Blender's UV layers and other per-loop consumers
 * want them: out[2k], out[2k+1] = uv of vertex indices[k], for every k <
 * index_count. `out_count` is the number of floats `out` can take and must
 * be at least 2 * index_count. */
BANYAN_API banyan_status banyan_mesh_corner_uvs(const banyan_mesh *mesh, float *out, uint64_t out_count,
                                                banyan_error *err);

/* Makes one group of a mesh (e.g. one tree of an avenue) a mesh of its
 * own, in buffers the caller copied out: `indices` (index_count of them)
 * refer to vertices first_vertex .. first_vertex + vertex_count - 1 and
 * become 0-based; `positions` (3 * vertex_count floats) move so that the
 * bottom centre of their bounds is the origin, and that point, in the
 * mesh's frame, is written to origin_out (the object's location, a pivot
 * at the foot). An index outside the group is refused and nothing is
 * changed. */
BANYAN_API banyan_status banyan_group_localize(float *positions, uint32_t vertex_count, uint32_t *indices,
                                               uint64_t index_count, uint32_t first_vertex, double origin_out[3],
                                               banyan_error *err);

/* The edges of a triangle list, for hosts that keep meshes as polygons,
 * corners and edges (Blender's polygons, loops and edges) and would
 * otherwise derive them: each unordered vertex pair that some triangle's
 * side joins is one edge. indices (index_count, a multiple of 3) refer to
 * vertices 0 .. vertex_count - 1. Writes corner_edges[k] (index_count of
 * them) = the edge from corner k to the next corner of its triangle (k + 1,
 * or k - 2 after its third); edges[2e], edges[2e + 1] = edge e's vertices,
 * the lower first, edges numbered by the first corner that uses them;
 * *edge_count = their number, at most edge_capacity (index_count always
 * suffices). face_starts, when not NULL, gets index_count / 3 entries 0,
 * 3, 6, ... (each triangle's first corner). Memory grows with
 * index_count, not vertex_count (unused vertices cost nothing). On
 * failure the outputs' contents are unspecified and *edge_count is 0. */
BANYAN_API banyan_status banyan_triangle_edges(const uint32_t *indices, uint64_t index_count, uint32_t vertex_count,
                                               uint32_t *corner_edges, uint32_t *edges, uint64_t edge_capacity,
                                               uint64_t *edge_count, uint32_t *face_starts, banyan_error *err);

/* FNV-1a 64 hash over every byte of every array of the mesh; used by tests
 * and tools to compare outputs. */
BANYAN_API uint64_t banyan_mesh_hash(const banyan_mesh *mesh);

/* ---------------------------------------------------------- ABI checking */

BANYAN_API int32_t banyan_abi_version(void);
BANYAN_API const char *banyan_version_string(void);
BANYAN_API size_t banyan_sizeof_error(void);
BANYAN_API size_t banyan_sizeof_box(void);
BANYAN_API size_t banyan_sizeof_attribute(void);
BANYAN_API size_t banyan_sizeof_material(void);
BANYAN_API size_t banyan_sizeof_part(void);
BANYAN_API size_t banyan_sizeof_mesh(void);
BANYAN_API size_t banyan_sizeof_param_info(void);
BANYAN_API size_t banyan_sizeof_instance(void);

/* ------------------------------------------------------ parameter tables */

/* Every generator describes its params struct with a table, so the CLI,
 * presets and the Blender add-on set, check and document parameters in
 * one place. */
typedef enum banyan_generator {
    BANYAN_GEN_ROOTS = 0,
    BANYAN_GEN_KEYAKI = 1,
    BANYAN_GEN_AVENUE = 2,
    BANYAN_GEN_IVY = 3,
    BANYAN_GEN_SEGMENTS = 4,
    BANYAN_GEN_COUNT = 5
} banyan_generator;

typedef enum banyan_param_type {
    BANYAN_PT_DOUBLE = 0, /* double */
    BANYAN_PT_INT = 1,    /* int32_t */
    BANYAN_PT_BOOL = 2,   /* int32_t, 0 or 1 */
    BANYAN_PT_ENUM = 3,   /* int32_t index into the '|'-separated `choices` */
    BANYAN_PT_VEC3 = 4,   /* double[3] */
    BANYAN_PT_COLOR = 5,  /* double[4] linear RGBA, each 0..1 */
    BANYAN_PT_SEED = 6    /* uint64_t */
} banyan_param_type;

typedef struct banyan_param_info {
    const char *name;        /* key in presets, --set and the add-on */
    const char *unit;        /* "m", "deg", "unit", "" ... */
    const char *description; /* one sentence, used as tooltip */
    int32_t type;            /* banyan_param_type */
    double min, max;         /* inclusive range for numbers (each component) */
    const char *choices;     /* for ENUM: "simple|strong_weak|..." else NULL */
    size_t offset;           /* byte offset in the params struct */
    const char *label;       /* what a panel shows: words an artist knows, "Branch angle";
                                unique within the generator's table */
    const char *group;       /* panel section, "Growth", "Leaves", "Limits"...: a group's rows
                                are consecutive, and groups come in the order to show them,
                                the most used first */
} banyan_param_info;

/* Name of a generator ("roots", "keyaki", "avenue", "ivy", "segments"), or
 * NULL when out of range; and the reverse, returning -1 when unknown. */
BANYAN_API const char *banyan_generator_name(banyan_generator g);
BANYAN_API int32_t banyan_generator_from_name(const char *name);

/* Number of parameters of a generator, and the i-th description (NULL when
 * out of range). 0 when the generator is not built yet. */
BANYAN_API int32_t banyan_param_count(banyan_generator g);
BANYAN_API const banyan_param_info *banyan_param_get(banyan_generator g, int32_t i);
BANYAN_API const banyan_param_info *banyan_param_find(banyan_generator g, const char *name);

/* Sets a parameter from text, as given to --set key=value: numbers, true /
 * false, enum names, "x,y,z" vectors, "r,g,b[,a]" colours. Refuses unknown
 * keys (BANYAN_E_UNKNOWN_KEY), malformed text (BANYAN_E_TYPE) and values
 * outside [min, max] (BANYAN_E_RANGE). `params` points to the generator's
 * params struct. On failure the struct is unchanged. */
BANYAN_API banyan_status banyan_param_set_text(banyan_generator g, void *params,
                                               const char *key, const char *value,
                                               banyan_error *err);

/* Checks every field of a params struct against its table: finite, within
 * [min, max], enum in range. Generators call it first, then check the
 * rules that tie fields together. */
BANYAN_API banyan_status banyan_params_check(banyan_generator g, const void *params,
                                             banyan_error *err);

/* --------------------------------------------------------------- presets */

/* A preset is a JSON object:
 *   { "generator": "roots", "schema": 1, "description": "...",
 *     "params": { "<key>": value, ... },
 *     "hosts": [ { "center": [x,y,z], "half": [hx,hy,hz],
 *                  "rotation": [9 numbers, row-major]  (optional)
 *                  | "rotation_euler_deg": [rx,ry,rz]    (optional, XYZ) }
 *                | { "mesh": "file.glb", ... } (banyan_preset_host_set) ] }
 * Unknown keys at any level, wrong types and values out of range are
 * refused; messages start with "<source>:<line>:" where known. A list key
 * ("hosts", "segments") that is given must not be empty: leave the key
 * out for the generator's default. A text longer than
 * BANYAN_PRESET_MAX_BYTES is refused. Numbers are read the same whatever
 * the process locale. */
#define BANYAN_PRESET_SCHEMA 1
#define BANYAN_PRESET_MAX_BYTES (4u << 20)
#define BANYAN_MAX_HOSTS 256

/* Applies a preset's "params" to `params` (which should hold defaults from
 * the generator's params_init). `generator` must match the preset's. The
 * text need not be NUL-terminated. On failure `params` may be partly set. */
BANYAN_API banyan_status banyan_preset_apply(banyan_generator g, void *params,
                                             const char *text, size_t length,
                                             const char *source, banyan_error *err);

/* Reads a preset's "hosts" into out[0..cap-1]; *count gets how many there
 * are (0 when the preset has none). Refuses more than `cap`, and a preset
 * with a mesh host (BANYAN_E_UNSUPPORTED: read those with
 * banyan_preset_host_set). */
BANYAN_API banyan_status banyan_preset_hosts(const char *text, size_t length,
                                             const char *source, banyan_box *out,
                                             uint32_t cap, uint32_t *count,
                                             banyan_error *err);

/* ------------------------------------------------- mesh hosts from files */

/* banyan_host_mesh and banyan_hosts are defined in banyan/hosts.h; the
 * tags are declared here so these calls can name them. */
struct banyan_host_mesh;
struct banyan_hosts;

/* Reads a self-contained glTF 2.0 binary file (.glb; no other file is
 * opened, images are not decoded) as one host mesh: every triangle
 * (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN; points and lines are
 * skipped) of every mesh primitive reached from the default scene (scene
 * 0 when none is named; every root node when there are no scenes), under
 * its node transforms, in the rest pose (skins and morph targets are not
 * applied). Positions are converted from glTF's Y up to banyan's Z up,
 * (x, y, z) -> (x, -z, y), and vertices at exactly the same position are
 * merged, so a watertight mesh exported with split UV seams or hard
 * edges reads as closed. A mirroring node transform reverses the
 * triangles' winding, keeping them counter-clockwise from outside.
 *   transform  the 3x4 object -> world matrix to put in the mesh (as
 *              banyan_host_mesh.transform), or NULL for identity; finite.
 *   closed     banyan_host_closed: -1 auto, 0 open, 1 closed.
 * *out is one allocation (the struct and its arrays) that the caller
 * frees with banyan_host_mesh_free. Refuses, with the path and, where it
 * applies, the mesh and primitive: a file that cannot be read
 * (BANYAN_E_IO), that is not a glTF binary or is malformed (buffers or
 * accessors out of bounds, a node graph that is not a tree, compressed or
 * quantized positions, a required extension it cannot read:
 * BANYAN_E_PARSE), that has no triangles or a non-finite position or an
 * index out of range (BANYAN_E_BAD_HOST), or more than
 * BANYAN_HOSTS_MAX_TRIANGLES triangles (BANYAN_E_LIMIT). On failure
 * *out == NULL. */
BANYAN_API banyan_status banyan_glb_read_host(const char *path, const double transform[12], int32_t closed,
                                              struct banyan_host_mesh **out, banyan_error *err);
/* banyan_glb_read_host inside a budget (banyan_budget; NULL: the
 * defaults, which banyan_glb_read_host uses). The sizes are read from the file's header and JSON before
 * its binary chunk: a file whose triangles (every node's instance
 * counted), vertices to read (at most 3 * BANYAN_HOSTS_MAX_TRIANGLES) or
 * memory estimate pass the limits is refused before the read
 * (BANYAN_E_LIMIT naming the limit); a read that runs out of time or
 * memory stops with BANYAN_E_LIMIT naming max_seconds or max_memory_mb. */
BANYAN_API banyan_status banyan_glb_read_host_budget(const char *path, const double transform[12], int32_t closed,
                                                     const banyan_budget *budget, struct banyan_host_mesh **out,
                                                     banyan_error *err);
/* Frees a mesh from banyan_glb_read_host; accepts NULL. */
BANYAN_API void banyan_host_mesh_free(struct banyan_host_mesh *mesh);

/* Builds the host set of a preset (banyan/hosts.h) whose "hosts" may mix
 * boxes and meshes. A mesh host is
 *   { "mesh": "hosts/rock.glb",           (required; relative to base_dir)
 *     "translation": [x, y, z]            (or "center"; default origin)
 *     "rotation": [9] | "rotation_euler_deg": [3]   (as for boxes)
 *     "scale": s | [sx, sy, sz]           (each 1e-6 .. 1e6 in size; < 0 mirrors)
 *     "closed": "auto" | "open" | "closed"  (default "auto")
 *     "name": "..." }
 * read with banyan_glb_read_host; world = translation + rotation * (scale
 * * p). A relative mesh path is joined to base_dir (the preset's folder;
 * NULL for the current directory). The meshes extra[0 .. n_extra - 1]
 * (e.g. the CLI's --host files) are added after the preset's own hosts;
 * their arrays are only read during the call. Host numbering as in
 * banyan_hosts_create: the boxes, then the meshes in order (the preset's,
 * then the extra ones). Refuses, naming `hosts[i]` (the preset's
 * numbering) and the problem, before anything is built: a mesh file that
 * is missing, not glTF or without triangles, a non-finite or singular
 * transform, unknown keys, box keys on a mesh or mesh keys on a box.
 * BANYAN_E_NO_HOSTS when the preset names no hosts and n_extra is 0
 * (callers then use their own defaults). On failure *out == NULL. */
BANYAN_API banyan_status banyan_preset_host_set(const char *text, size_t length, const char *source,
                                                const char *base_dir, const struct banyan_host_mesh *extra,
                                                uint32_t n_extra, struct banyan_hosts **out, banyan_error *err);
/* One mesh host entry of a preset as banyan_preset_host_set reads it
 * (the file itself is not read). */
typedef struct banyan_preset_mesh {
    uint32_t index;        /* its place in the preset's "hosts" */
    int32_t closed;        /* banyan_host_closed: -1 auto, 0 open, 1 closed */
    double transform[12];  /* object -> world, row-major 3x4: translation + rotation * (scale * p) */
    char path[4096];       /* the file, a relative one joined to base_dir */
    char name[256];        /* its "name", or the file's base name without the extension */
} banyan_preset_mesh;
BANYAN_API size_t banyan_sizeof_preset_mesh(void);
/* The mesh host entries of a preset, in order, into out[0 .. cap - 1];
 * *count gets how many there are (0: only boxes, or no "hosts"). Checks
 * each entry as banyan_preset_host_set does (naming hosts[i]) and refuses
 * more than cap (BANYAN_E_RANGE) or a joined path of 4096 bytes or more.
 * Reads no mesh file: what a caller that places the meshes itself (the
 * add-on's objects) needs, composed once, here. */
BANYAN_API banyan_status banyan_preset_meshes(const char *text, size_t length, const char *source,
                                              const char *base_dir, banyan_preset_mesh *out, uint32_t cap,
                                              uint32_t *count, banyan_error *err);
/* banyan_preset_host_set inside one budget for the whole call
 * (banyan_budget; NULL: the defaults, which banyan_preset_host_set uses):
 * every mesh file's sizes are read from its header first, and the set-wide
 * limits (BANYAN_HOSTS_MAX_TRIANGLES over all meshes, however many entries
 * name one file) and the memory estimate are checked before any file is
 * read whole. */
BANYAN_API banyan_status banyan_preset_host_set_budget(const char *text, size_t length, const char *source,
                                                       const char *base_dir, const struct banyan_host_mesh *extra,
                                                       uint32_t n_extra, const banyan_budget *budget,
                                                       struct banyan_hosts **out, banyan_error *err);

/* ----------------------------------------------------------- glTF export */

/* How banyan_gltf_write_ex writes. Init with banyan_gltf_options_init. */
typedef struct banyan_gltf_options {
    int32_t textures;        /* 0/1: embed the textures the materials name (banyan/textures.h). Default 1 */
    int32_t texture_size;    /* pixels per side: a power of two, 64 .. 8192. Default 1024 */
    uint64_t texture_seed;   /* seed of the drawn textures. Default 1 */
    int32_t engine_uvs;      /* 0/1: also write the wind data as TEXCOORD_1 .. 4 for importers that read only UV
                                sets (docs/gltf.md "Wind"). Default 0 */
    int32_t sync;            /* 0/1: fsync the file before renaming it over the target, so it survives a power
                                cut (docs/formats.md "Writing files"). Default 0, as cp and Blender's save */
    const char *image_dir;   /* NULL or "" (default): the textures are embedded. Else the library's textures
                                (not a mesh's own images) are PNG files in this folder, relative to the glTF
                                file's folder ('/'-separated; letters, digits, '.', '_', '-'; no "." or ".."
                                part), named <image>-<texture_size>-s<texture_seed>.png and referenced by that
                                relative URI. The folder is created; a file already there is kept, not drawn
                                again (each is written whole by rename, so one that exists is complete) */
    int32_t compact;         /* 0/1: quantized (KHR_mesh_quantization) and meshopt-compressed
                                (EXT_meshopt_compression) meshes, both required: a fraction of the size, read
                                by fewer importers (docs/gltf.md "Compact files"). Default 0 */
    int32_t texture_cache;   /* 0/1: keep the drawn textures' PNGs in an on-disk cache and read them from it
                                (docs/gltf.md "Texture cache"; the same bytes either way). Default 1. The
                                environment's BANYAN_TEXTURE_CACHE=off turns it off too */
    const char *texture_cache_dir; /* NULL or "" (default): BANYAN_TEXTURE_CACHE when it names a folder, else
                                      $XDG_CACHE_HOME/banyan/textures, else ~/.cache/banyan/textures */
    int32_t pivot_painter;   /* 0/1: also write each vertex's Pivot Painter 2 texel centre (banyan/pivot_painter.h)
                                as one more UV set, TEXCOORD_1, or TEXCOORD_5 with engine_uvs; a mesh without the
                                wind attributes is refused, and so are levels of detail (docs/gltf.md "Pivot
                                Painter 2"). Default 0 */
} banyan_gltf_options;

BANYAN_API void banyan_gltf_options_init(banyan_gltf_options *opt);
BANYAN_API size_t banyan_sizeof_gltf_options(void);

/* Writes meshes as one glTF 2.0 asset: one node and one mesh per input,
 * one primitive per part, one material per banyan_material, vertex colours
 * as COLOR_0, custom attributes as "_NAME" accessors (upper-cased name).
 * Positions convert Z-up to Y-up: (x, y, z) -> (x, z, -y). The format
 * follows the path: ".glb" binary, ".gltf" JSON with embedded buffer.
 * names may be NULL (nodes are then "banyan_0", ...).
 * Textures (opt->textures): a material whose texture is not
 * BANYAN_TEX_NONE gets baseColorTexture and normalTexture, PNG images in
 * the buffer, one per (kind, season, map) and shared by every material
 * that uses it; its baseColorFactor is then white (the texture carries
 * the colour; base_color is the flat colour for textures off). Materials
 * with alpha_cutoff > 0 are alphaMode MASK at that cutoff. opt NULL: the
 * defaults. Refuses a bad option naming it and its range.
 * The file is replaced whole or not at all: the bytes go to a temporary
 * ".<name>.XXXXXX.tmp" in the same folder, renamed over path once
 * written (and synced first with opt->sync); a failed write leaves the
 * old file (docs/formats.md, "Writing files"). A symlink stays; its
 * target is replaced. */
BANYAN_API banyan_status banyan_gltf_write_ex(const char *path,
                                              const banyan_mesh *const *meshes,
                                              const char *const *names, uint32_t count,
                                              const banyan_gltf_options *opt, banyan_error *err);

/* One node of banyan_gltf_write_nodes: a mesh, its coarser levels of
 * detail and how it is placed.
 *   lods, lod_count    coarser meshes (banyan_mesh_lod), finest first,
 *                      0 .. 7: written as MSFT_lod on the node, with
 *                      "MSFT_screencoverage" in the node's extras.
 *   lod_coverage       lod_count + 1 falling screen coverages in (0, 1], or
 *                      NULL for 0.5, 0.25, 0.125, ... (halving).
 * A mesh with instances (banyan_mesh.instance_count > 0) becomes one
 * mesh per variant, each on a node with EXT_mesh_gpu_instancing
 * (TRANSLATION, ROTATION, SCALE accessors, Y up). */
typedef struct banyan_gltf_node {
    const banyan_mesh *mesh;
    const char *name;                  /* NULL: "banyan_<i>" */
    uint32_t lod_count;
    const banyan_mesh *const *lods;
    const double *lod_coverage;
} banyan_gltf_node;

BANYAN_API size_t banyan_sizeof_gltf_node(void);

/* Writes nodes (count 1 .. 65536) as one glTF asset, as banyan_gltf_write_ex
 * does for plain meshes (same options, same atomic write). Every custom
 * attribute is a "_NAME" float scalar; the wind pivot's three
 * (_WIND_PIVOT_X/_Y/_Z) are in glTF's axes (Y up, the node's frame) like
 * POSITION; docs/game-engines.md. */
BANYAN_API banyan_status banyan_gltf_write_nodes(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                                                 const banyan_gltf_options *opt, banyan_error *err);

/* banyan_gltf_write_ex and banyan_gltf_write_nodes under a budget
 * (banyan_budget; NULL: the defaults, which the calls without _budget
 * use): the textures' memory (about 15 bytes a pixel for each of the two
 * drawn at once) is refused up front with BANYAN_E_LIMIT, naming
 * max_memory_mb and the texture size; past max_seconds the write stops
 * (between meshes, while streaming, inside the texture painters and the
 * PNG encoder) with BANYAN_E_LIMIT and the old file is left as it was. */
BANYAN_API banyan_status banyan_gltf_write_ex_budget(const char *path, const banyan_mesh *const *meshes,
                                                     const char *const *names, uint32_t count,
                                                     const banyan_gltf_options *opt, const banyan_budget *budget,
                                                     banyan_error *err);
BANYAN_API banyan_status banyan_gltf_write_nodes_budget(const char *path, const banyan_gltf_node *nodes,
                                                        uint32_t count, const banyan_gltf_options *opt,
                                                        const banyan_budget *budget, banyan_error *err);

/* banyan_gltf_write_ex with the default options (textures at 1024). */
BANYAN_API banyan_status banyan_gltf_write(const char *path,
                                           const banyan_mesh *const *meshes,
                                           const char *const *names, uint32_t count,
                                           banyan_error *err);

/* --------------------------------------------------------- demo: a tube */

/* A swept tube along a polyline, through the shared sweeper: the smallest
 * thing the library makes, used by the CLI's `tube` demo and tests.
 *   points  3 * point_count metres, each coordinate within [-1e6, 1e6],
 *           point_count 2 .. 1e6, consecutive points distinct.
 *   radii   point_count radii in metres, each within [1e-9, 1e6].
 *   sides   3 .. 256.  caps: 0 or 1.
 * The tube has no max_vertices of its own: point_count * (sides + 1) (plus
 * the caps) past BANYAN_TUBE_MAX_VERTICES is refused with BANYAN_E_LIMIT
 * before anything is allocated. Points reaching more than 8192 m from
 * their bounds' centre are refused with BANYAN_E_RANGE (one mesh keeps 1
 * mm only that far from its origin: split the tube). The mesh always
 * carries the wind attributes and birth: pivot points[0], level 0,
 * stiffness sqrt(radius / the largest), birth by arc length 0 .. 1. */
#define BANYAN_TUBE_MAX_VERTICES 16000000u
BANYAN_API banyan_status banyan_tube_generate(const double *points, const double *radii,
                                              uint32_t point_count, int32_t sides,
                                              int32_t caps, banyan_mesh **out,
                                              banyan_error *err);

#ifdef __cplusplus
}
#endif

/* Generators. Each header declares its params struct, params_init,
 * generate and sizeof calls. */
#include "banyan/generators.h"
/* USD export of the same nodes the glTF writer takes. */
#include "banyan/usd.h"
/* Unreal's Pivot Painter 2 textures. */
#include "banyan/pivot_painter.h"

#endif /* BANYAN_H */
