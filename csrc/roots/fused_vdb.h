/* fused_vdb.h - the C side of the OpenVDB shim (fused_vdb.cpp): meshes a
 * narrow-band level set given as 8^3 blocks aligned to multiples of 8, in
 * index space (voxel (i,j,k) sits at (i,j,k); the caller scales). */
#ifndef BANYAN_FUSED_VDB_H
#define BANYAN_FUSED_VDB_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fused_vdb_in {
    const int32_t *origin; /* 3 per block: the block's first voxel, multiples of 8 */
    const float *values;   /* 512 per block, voxel (x,y,z) at x*64 + y*8 + z (OpenVDB's leaf order) */
    size_t n_blocks;
    float background;      /* band half-width: |v| >= background is outside the band */
    /* Asked between the meshing's stages and every few hundred leaves of
     * its per-leaf stages, on the calling thread; nonzero stops the meshing
     * with FUSED_VDB_STOPPED (the budget, the cancel). NULL: never. */
    int (*stop)(void *user);
    void *stop_user;
} fused_vdb_in;

typedef struct fused_vdb_out {
    float *pos;    /* 3 per vertex, index space; malloc'd, the caller frees */
    uint32_t *tri; /* 3 per triangle; malloc'd */
    uint32_t n_pos, n_tri;
} fused_vdb_out;

/* The module's and the library's file names, as CMake names them. */
#ifdef _WIN32
#define FUSED_VDB_MODULE "banyan_vdb.dll"
#define FUSED_VDB_LIBRARY "banyan.dll"
#else
#define FUSED_VDB_MODULE "libbanyan_vdb.so"
#define FUSED_VDB_LIBRARY "libbanyan.so"
#endif

enum {
    FUSED_VDB_OK = 0,
    FUSED_VDB_NOMEM = 1,
    FUSED_VDB_TOO_BIG = 2,
    FUSED_VDB_FAILED = 3,
    FUSED_VDB_STOPPED = 4,
    FUSED_VDB_NO_MODULE = 5 /* libbanyan_vdb.so is not beside libbanyan.so (fused_vdb_module.c) */
};

/* Returns FUSED_VDB_*; on failure out is zeroed and nothing is held.
 * Defined by the shim (fused_vdb.cpp: the static library, and the module
 * libbanyan_vdb.so) and, in libbanyan.so, by fused_vdb_module.c, which
 * loads the module and calls its definition. */
int fused_vdb_mesh(const fused_vdb_in *in, fused_vdb_out *out);

#ifdef __cplusplus
}
#endif

#endif
