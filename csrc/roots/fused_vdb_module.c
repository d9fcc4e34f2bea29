/* fused_vdb_module.c - fused_vdb_mesh for the shared library: OpenVDB
 * (with Boost, TBB, Imath and OpenVDB's codecs) costs a process about
 * 150 M instructions of symbol lookups when it loads, so libbanyan.so does
 * not link it. The shim (fused_vdb.cpp) is built as the module
 * libbanyan_vdb.so, which this file loads from the folder libbanyan.so was
 * loaded from, the first time a fused roots surface is meshed: the other
 * runs never pay for it. The static library links the shim directly and
 * does not hold this file. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "roots/fused_vdb.h"

#define VDB_MODULE "libbanyan_vdb.so"

typedef int (*vdb_mesh_fn)(const fused_vdb_in *, fused_vdb_out *);

/* An address inside libbanyan.so, for dladdr. */
static const char here = 0;

/* The module's entry, or NULL. dlopen counts references: a second call
 * finds the module loaded and costs a name comparison, so nothing is
 * kept here (no global state); the module stays loaded for the process. */
static vdb_mesh_fn load_module(void) {
    Dl_info self;
    if (!dladdr(&here, &self) || !self.dli_fname) return NULL;
    const char *slash = strrchr(self.dli_fname, '/');
    size_t dir = slash ? (size_t)(slash - self.dli_fname + 1) : 0;
    char path[4096];
    if (dir + sizeof VDB_MODULE > sizeof path) return NULL;
    memcpy(path, self.dli_fname, dir);
    memcpy(path + dir, VDB_MODULE, sizeof VDB_MODULE);
    void *h = dlopen(slash ? path : VDB_MODULE, RTLD_NOW | RTLD_LOCAL);
    if (!h) return NULL;
    vdb_mesh_fn fn;
    void *sym = dlsym(h, "fused_vdb_mesh");
    memcpy(&fn, &sym, sizeof fn); /* ISO C has no object-to-function pointer cast */
    return fn;
}

int fused_vdb_mesh(const fused_vdb_in *in, fused_vdb_out *out) {
    memset(out, 0, sizeof *out);
    vdb_mesh_fn fn = load_module();
    return fn ? fn(in, out) : FUSED_VDB_NO_MODULE;
}
