/* fused_vdb_module.c - fused_vdb_mesh for the shared library: OpenVDB
 * (with Boost, TBB, Imath and OpenVDB's codecs) costs a process about
 * 150 M instructions of symbol lookups when it loads, so libbanyan.so does
 * not link it. The shim (fused_vdb.cpp) is built as the module
 * libbanyan_vdb.so (banyan_vdb.dll on Windows), which this file loads
 * from the folder libbanyan.so was loaded from, the first time a fused
 * roots surface is meshed: the other runs never pay for it. The static library links the shim directly and
 * does not hold this file. */
#include <string.h>

#include "base/platform.h"
#include "roots/fused_vdb.h"

typedef int (*vdb_mesh_fn)(const fused_vdb_in *, fused_vdb_out *);

/* An address inside the library, to find its folder. */
static const char here = 0;

/* The module's entry, or NULL. Loading counts references: a second call
 * finds the module loaded and costs a name comparison, so nothing is
 * kept here (no global state); the module stays loaded for the process. */
static vdb_mesh_fn load_module(void) {
    void *h = plat_module_open_beside(&here, FUSED_VDB_MODULE);
    if (!h) return NULL;
    return (vdb_mesh_fn)plat_module_fn(h, "fused_vdb_mesh");
}

int fused_vdb_mesh(const fused_vdb_in *in, fused_vdb_out *out) {
    memset(out, 0, sizeof *out);
    vdb_mesh_fn fn = load_module();
    return fn ? fn(in, out) : FUSED_VDB_NO_MODULE;
}
