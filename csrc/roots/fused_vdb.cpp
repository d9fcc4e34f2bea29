/*
 * fused_vdb.cpp - the one C++ file of the fused roots surface (issue #18,
 * docs/roots.md "Fused surface"): OpenVDB 10 meshes a narrow-band level
 * set that fused.c has evaluated. The geometry (capsules, smooth union,
 * host difference) stays in C; this shim only copies fused.c's 8^3 blocks
 * into the leaves of a sparse openvdb::FloatGrid (same voxel order as a
 * LeafNode<float, 3>), runs tools::volumeToMesh and splits its quads.
 * volumeToMesh runs in a tbb::task_arena of one thread: the roots
 * generator has no threads parameter and uses one core, and the output
 * order cannot depend on scheduling. No exception leaves this file.
 */
#include "roots/fused_vdb.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <cstring>
#include <new>

/* The whole life of the grid, run inside the one-thread arena: OpenVDB's
 * tree teardown is a parallel_for too, which outside it would start TBB's
 * worker threads. */
static int mesh_blocks(const fused_vdb_in *in, fused_vdb_out *out) {
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
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0, in->adaptivity);
    grid.reset();
    size_t nt = tris.size() + 2 * quads.size();
    if (points.size() >= 0xffffffffu || nt >= 0x55555555u) return FUSED_VDB_TOO_BIG;
    out->pos = (float *)std::malloc(sizeof(float) * 3 * (points.size() ? points.size() : 1));
    out->tri = (uint32_t *)std::malloc(sizeof(uint32_t) * 3 * (nt ? nt : 1));
    if (!out->pos || !out->tri) {
        std::free(out->pos);
        std::free(out->tri);
        std::memset(out, 0, sizeof *out);
        return FUSED_VDB_NOMEM;
    }
    for (size_t i = 0; i < points.size(); i++)
        for (int k = 0; k < 3; k++) out->pos[3 * i + k] = points[i][k];
    uint32_t *t = out->tri;
    for (const openvdb::Vec3I &f : tris) {
        t[0] = f[0], t[1] = f[1], t[2] = f[2];
        t += 3;
    }
    for (const openvdb::Vec4I &q : quads) {
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
    out->n_pos = (uint32_t)points.size();
    out->n_tri = (uint32_t)nt;
    return FUSED_VDB_OK;
}

extern "C" int fused_vdb_mesh(const fused_vdb_in *in, fused_vdb_out *out) {
    std::memset(out, 0, sizeof *out);
    try {
        int rc = FUSED_VDB_FAILED;
        tbb::task_arena arena(1);
        arena.execute([&] { rc = mesh_blocks(in, out); });
        return rc;
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
