/*
 * fused_vdb.cpp - the one C++ file of the fused roots surface
 * (docs/roots.md "Fused surface"): OpenVDB 10 meshes a narrow-band level
 * set that fused.c has evaluated. The geometry (capsules, smooth union,
 * host difference) stays in C; this shim only copies fused.c's 8^3 blocks
 * into the leaves of a sparse openvdb::FloatGrid (same voxel order as a
 * LeafNode<float, 3>), meshes it as tools::volumeToMesh does at
 * adaptivity 0 and splits its quads. The meshing is volumeToMesh's own
 * stages (VolumeToMesh::operator() for a level set, no adaptivity, mask
 * or reference grid: the same points and quads in the same order), run
 * here one by one so the caller's stop (budget, cancel) is asked between
 * them and every kChunk leaves of the per-leaf ones: volumeToMesh itself
 * cannot be interrupted. It runs in a tbb::task_arena of one thread: the
 * roots generator has no threads parameter and uses one core, the output
 * order cannot depend on scheduling, and the per-leaf stages run in
 * pieces on the calling thread. No exception leaves this file.
 */
#include "roots/fused_vdb.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <thread>
#include <vector>

namespace {

namespace vtm = openvdb::tools::volume_to_mesh_internal;
using FloatTree = openvdb::FloatTree;
using BoolTree = FloatTree::ValueConverter<bool>::Type;
using Int16Tree = FloatTree::ValueConverter<openvdb::Int16>::Type;
using Index32Tree = FloatTree::ValueConverter<openvdb::Index32>::Type;

/* Leaves between two stop checks: a few milliseconds of work. */
constexpr size_t kChunk = 256;

struct Stopped {};

struct Stopper {
    const fused_vdb_in *in;
    std::thread::id caller; /* the stop is the generator's: asked on its thread only */
    void check() const {
        if (in->stop && std::this_thread::get_id() == caller && in->stop(in->stop_user)) throw Stopped();
    }
    /* op over leaves [0, n) in pieces, asking between them; one thread, so
     * the same as tbb::parallel_for over the whole range. */
    template <class Op> void each(size_t n, const Op &op) const {
        for (size_t a = 0; a < n; a += kChunk) {
            check();
            op(tbb::blocked_range<size_t>(a, a + kChunk < n ? a + kChunk : n));
        }
    }
};

/* VolumeToMesh::operator() and doVolumeToMesh for a level set at
 * isovalue 0, adaptivity 0: points, and each leaf's polygon pool. */
void mesh_uniform(const openvdb::FloatGrid &grid, const Stopper &stop, std::unique_ptr<openvdb::Vec3s[]> &points,
                  size_t &n_points, openvdb::tools::PolygonPoolList &pools, size_t &n_pools) {
    const FloatTree &input = grid.tree();
    const float iso = 0.0f;
    n_points = n_pools = 0;
    BoolTree intersection(false);
    vtm::identifySurfaceIntersectingVoxels(intersection, input, iso);
    if (intersection.empty()) return;
    stop.check();
    Int16Tree sign_flags(0);
    Index32Tree point_index(std::numeric_limits<openvdb::Index32>::max());
    vtm::computeAuxiliaryData(sign_flags, point_index, intersection, input, iso);
    intersection.clear();
    stop.check();
    std::vector<Index32Tree::LeafNodeType *> point_leaves;
    point_index.getNodes(point_leaves);
    std::vector<Int16Tree::LeafNodeType *> sign_leaves;
    sign_flags.getNodes(sign_leaves);
    const size_t n = sign_leaves.size();
    std::unique_ptr<openvdb::Index32[]> offsets(new openvdb::Index32[n]);
    stop.each(n, vtm::LeafNodePointCount<Int16Tree::LeafNodeType::LOG2DIM>(sign_leaves, offsets));
    openvdb::Index32 count = 0;
    for (size_t i = 0; i < n; ++i) {
        const openvdb::Index32 c = offsets[i];
        offsets[i] = count;
        count += c;
    }
    points.reset(new openvdb::Vec3s[count]);
    n_points = count;
    stop.each(n, vtm::ComputePoints<FloatTree>(points.get(), input, point_leaves, sign_leaves, offsets,
                                               grid.transform(), iso));
    pools.reset(new openvdb::tools::PolygonPool[n]);
    n_pools = n;
    /* A level set: the default orientation (invertSurfaceOrientation false). */
    stop.each(n, vtm::ComputePolygons<Int16Tree, vtm::UniformPrimBuilder>(sign_leaves, sign_flags, point_index,
                                                                         pools, false));
}

} // namespace

/* The whole life of the grid, run inside the one-thread arena: OpenVDB's
 * tree teardown is a parallel_for too, which outside it would start TBB's
 * worker threads. */
static int mesh_blocks(const fused_vdb_in *in, std::thread::id caller, fused_vdb_out *out) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(in->background);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    openvdb::FloatTree &tree = grid->tree();
    for (size_t b = 0; b < in->n_blocks; b++) {
        const int32_t *o = in->origin + 3 * b;
        const float *v = in->values + (size_t)512 * b;
        openvdb::FloatTree::LeafNodeType *leaf = tree.touchLeaf(openvdb::Coord(o[0], o[1], o[2]));
        /* Every voxel of a block holds its value (clamped to +-background
         * outside the band, inactive there): no flood fill to guess signs. */
        float *dst = leaf->buffer().data();
        openvdb::FloatTree::LeafNodeType::NodeMaskType mask;
        for (openvdb::Index i = 0; i < 512; i++) {
            bool on = v[i] > -in->background && v[i] < in->background;
            dst[i] = on ? v[i] : (v[i] < 0 ? -in->background : in->background);
            if (on) mask.setOn(i);
        }
        leaf->setValueMask(mask);
    }
    std::unique_ptr<openvdb::Vec3s[]> points;
    openvdb::tools::PolygonPoolList pools;
    size_t np = 0, npools = 0;
    mesh_uniform(*grid, Stopper{in, caller}, points, np, pools, npools);
    grid.reset();
    /* doVolumeToMesh's lists: every pool's triangles (none at adaptivity
     * 0), then every pool's quads, in pool order. */
    size_t ntri = 0, nquad = 0;
    for (size_t p = 0; p < npools; p++) ntri += pools[p].numTriangles(), nquad += pools[p].numQuads();
    size_t nt = ntri + 2 * nquad;
    if (np >= 0xffffffffu || nt >= 0x55555555u) return FUSED_VDB_TOO_BIG;
    out->pos = (float *)std::malloc(sizeof(float) * 3 * (np ? np : 1));
    out->tri = (uint32_t *)std::malloc(sizeof(uint32_t) * 3 * (nt ? nt : 1));
    if (!out->pos || !out->tri) {
        std::free(out->pos);
        std::free(out->tri);
        std::memset(out, 0, sizeof *out);
        return FUSED_VDB_NOMEM;
    }
    for (size_t i = 0; i < np; i++)
        for (int k = 0; k < 3; k++) out->pos[3 * i + k] = points[i][k];
    uint32_t *t = out->tri;
    for (size_t p = 0; p < npools; p++)
        for (size_t i = 0; i < pools[p].numTriangles(); i++) {
            const openvdb::Vec3I &f = pools[p].triangle(i);
            t[0] = f[0], t[1] = f[1], t[2] = f[2];
            t += 3;
        }
    for (size_t p = 0; p < npools; p++)
        for (size_t i = 0; i < pools[p].numQuads(); i++) {
            const openvdb::Vec4I &q = pools[p].quad(i);
            /* Split along the shorter diagonal: better-shaped triangles. */
            const openvdb::Vec3s &a = points[q[0]], &b = points[q[1]], &c = points[q[2]], &d = points[q[3]];
            if ((a - c).lengthSqr() <= (b - d).lengthSqr()) {
                t[0] = q[0], t[1] = q[1], t[2] = q[2];
                t[3] = q[0], t[4] = q[2], t[5] = q[3];
            } else {
                t[0] = q[0], t[1] = q[1], t[2] = q[3];
                t[3] = q[1], t[4] = q[2], t[5] = q[3];
            }
            t += 6;
        }
    out->n_pos = (uint32_t)np;
    out->n_tri = (uint32_t)nt;
    return FUSED_VDB_OK;
}

/* The module's one export (csrc/banyan_vdb.map). */
#ifdef _WIN32
#define FUSED_VDB_EXPORT __declspec(dllexport)
#else
#define FUSED_VDB_EXPORT __attribute__((visibility("default")))
#endif
extern "C" FUSED_VDB_EXPORT int fused_vdb_mesh(const fused_vdb_in *in, fused_vdb_out *out) {
    std::memset(out, 0, sizeof *out);
    try {
        int rc = FUSED_VDB_FAILED;
        tbb::task_arena arena(1);
        const std::thread::id caller = std::this_thread::get_id();
        arena.execute([&] { rc = mesh_blocks(in, caller, out); });
        return rc;
    } catch (const Stopped &) {
        std::free(out->pos);
        std::free(out->tri);
        std::memset(out, 0, sizeof *out);
        return FUSED_VDB_STOPPED;
    } catch (const std::bad_alloc &) {
        std::free(out->pos);
        std::free(out->tri);
        std::memset(out, 0, sizeof *out);
        return FUSED_VDB_NOMEM;
    } catch (...) {
        std::free(out->pos);
        std::free(out->tri);
        std::memset(out, 0, sizeof *out);
        return FUSED_VDB_FAILED;
    }
}
