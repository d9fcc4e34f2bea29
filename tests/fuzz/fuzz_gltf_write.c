/* fuzz_gltf_write.c - libFuzzer harness for the glTF writer: a small mesh
 * from bytes (fuzz_mesh.h, hostile when its flags say so) written as .glb
 * and read back with the library's reader (banyan_glb_read_host). After
 * the mesh, a flags byte: bit 0 textures on (64 pixels), bit 1 engine
 * uvs, bit 2 through banyan_gltf_write_nodes with a coarser level
 * (banyan_mesh_lod at half) as MSFT_lod, bit 3 a 0.01 s budget (else 5 s),
 * bit 4 a NULL name, bit 5 also the USD writer (textures off: no image
 * files). A refusal must be clean and leave the file that was
 * there; a written file must read back with the mesh's triangles, its
 * positions finite and within the mesh's bounds (Y up back to Z up); a
 * USD layer must start as one, name no NaN or infinity and hold at most
 * one Mesh a part. */
#define _POSIX_C_SOURCE 200809L
#include <unistd.h>

#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void bounds(const banyan_mesh *m, double lo[3], double hi[3]) {
    for (int j = 0; j < 3; j++) lo[j] = INFINITY, hi[j] = -INFINITY;
    for (uint32_t i = 0; i < m->index_count; i++)
        for (int j = 0; j < 3; j++) {
            double v = m->positions[3 * (size_t)m->indices[i] + j];
            lo[j] = v < lo[j] ? v : lo[j];
            hi[j] = v > hi[j] ? v : hi[j];
        }
}

/* The USD writer on the same mesh and options (its textures off). */
static void usd(const banyan_mesh *m, const char *name, const banyan_gltf_options *opt, const banyan_budget *b) {
    static char path[64];
    if (!path[0]) snprintf(path, sizeof path, "/tmp/banyan_fuzz_usd_write_%ld.usda", (long)getpid());
    unlink(path);
    banyan_gltf_options o = *opt;
    o.textures = 0;
    banyan_gltf_node node = {m, name, 0, NULL, NULL};
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_usd_write_nodes_budget(path, &node, 1, &o, b, &e);
    if (s) {
        fz_check_failure(s, &e, NULL);
        FZ_ASSERT(access(path, F_OK) != 0, "a refused USD write left %s (%s)", path, e.message);
        return;
    }
    FILE *f = fopen(path, "rb");
    FZ_ASSERT(f != NULL, "the USD layer %s is not there", path);
    static char buf[1 << 16];
    size_t n, meshes = 0, at = 0;
    int head = 1;
    while ((n = fread(buf, 1, sizeof buf - 1, f)) > 0) {
        buf[n] = '\0';
        if (head) FZ_ASSERT(!strncmp(buf, "#usda 1.0\n", 10), "the layer does not start with #usda 1.0");
        head = 0;
        static const char *const bad[] = {"nan,", "nan)", "nan]", "inf,", "inf)", "inf]"};
        for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
            FZ_ASSERT(!strstr(buf, bad[k]), "a NaN or infinity (%s) near byte %zu", bad[k], at);
        for (const char *q = strstr(buf, "def Mesh "); q; q = strstr(q + 1, "def Mesh ")) meshes++;
        at += n;
    }
    fclose(f);
    FZ_ASSERT(meshes <= m->part_count, "%zu meshes for %u parts", meshes, m->part_count);
    unlink(path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static char path[64];
    if (!path[0]) snprintf(path, sizeof path, "/tmp/banyan_fuzz_gltf_write_%ld.glb", (long)getpid());
    fz_reader r = {data, size, 0};
    fz_mesh fm;
    fz_mesh_read(&r, &fm);
    uint8_t flags = fz_u8(&r);
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.textures = flags & 1;
    o.texture_size = 64;
    o.engine_uvs = (flags >> 1) & 1;
    banyan_budget b;
    banyan_budget_init(&b);
    b.max_seconds = flags & 8 ? 0.01 : 5.0;
    b.max_memory_mb = 1024;
    const char *name = flags & 16 ? NULL : "fz";

    unlink(path);
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_status s;
    banyan_mesh *lod = NULL;
    if (flags & 4) {
        banyan_lod_params lp;
        banyan_lod_params_init(&lp);
        banyan_error le;
        if (banyan_mesh_lod(&fm.m, &lp, &lod, &le)) lod = NULL;
        const banyan_mesh *lods[1] = {lod};
        banyan_gltf_node node = {&fm.m, name, lod ? 1u : 0u, lod ? lods : NULL, NULL};
        s = banyan_gltf_write_nodes_budget(path, &node, 1, &o, &b, &e);
    } else {
        const banyan_mesh *ms[1] = {&fm.m};
        const char *names[1] = {name};
        s = banyan_gltf_write_ex_budget(path, ms, name ? names : NULL, 1, &o, &b, &e);
    }
    if (s) {
        fz_check_failure(s, &e, NULL);
        FZ_ASSERT(access(path, F_OK) != 0, "a refused write left %s (%s)", path, e.message);
    } else {
        static const double t[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        banyan_host_mesh *h = NULL;
        banyan_error re;
        banyan_status rs = banyan_glb_read_host(path, t, -1, &h, &re);
        FZ_ASSERT(rs == BANYAN_OK, "the written file does not read back: %s", re.message);
        FZ_ASSERT(h->triangle_count == fm.m.index_count / 3, "%u triangles read back, %u written", h->triangle_count,
                  fm.m.index_count / 3);
        FZ_ASSERT(fz_finite(h->positions, 3 * (size_t)h->vertex_count), "a position read back is not finite");
        double lo[3], hi[3];
        bounds(&fm.m, lo, hi);
        for (uint32_t i = 0; i < 3 * h->triangle_count; i++) {
            FZ_ASSERT(h->indices[i] < h->vertex_count, "index %u = %u of %u", i, h->indices[i], h->vertex_count);
            const float *P = h->positions + 3 * (size_t)h->indices[i];
            for (int j = 0; j < 3; j++) {
                double tol = 1e-5 * (fabs(lo[j]) + fabs(hi[j])) + 1e-6;
                FZ_ASSERT(P[j] >= lo[j] - tol && P[j] <= hi[j] + tol, "axis %d: %g outside [%g, %g]", j, P[j], lo[j],
                          hi[j]);
            }
        }
        banyan_host_mesh_free(h);
    }
    if (flags & 32) usd(&fm.m, name, &o, &b);
    banyan_mesh_free(lod);
    fz_mesh_free(&fm);
    unlink(path);
    return 0;
}
