/* fuzz_glb.c - libFuzzer harness for the glTF binary reader
 * (banyan_glb_read_host): the bytes are a .glb file, written to a file of
 * this process's own (the reader takes a path), read back and removed. A refusal
 * must be clean (status, message, *out NULL); an accepted mesh must have
 * triangles, indices within its vertices, finite positions, and the
 * transform and closed mode it was given. Seeds: tests/fuzz/seeds/fuzz_glb
 * (small files from test_host_files). */
#define _POSIX_C_SOURCE 200809L
#include <unistd.h>

#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static char path[64];
    if (!path[0]) snprintf(path, sizeof path, "/tmp/banyan_fuzz_glb_%ld.glb", (long)getpid());
    FILE *f = fopen(path, "wb");
    FZ_ASSERT(f != NULL, "cannot write %s", path);
    if (size) fwrite(data, 1, size, f);
    fclose(f);
    double t[12] = {2, 0, 0, 1, 0, 2, 0, -1, 0, 0, 2, 0.5};
    int32_t closed = size ? (int32_t)(data[size - 1] % 3) - 1 : -1;
    banyan_host_mesh *m = NULL;
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_glb_read_host(path, t, closed, &m, &e);
    unlink(path); /* each input's file goes with it: none is left in /tmp */
    if (s) {
        fz_check_failure(s, &e, m);
    } else {
        FZ_ASSERT(m && m->triangle_count > 0 && m->vertex_count > 0, "accepted a mesh without triangles");
        FZ_ASSERT(m->triangle_count <= BANYAN_HOSTS_MAX_TRIANGLES, "%u triangles", m->triangle_count);
        for (uint64_t i = 0; i < 3 * (uint64_t)m->triangle_count; i++)
            FZ_ASSERT(m->indices[i] < m->vertex_count, "index %llu = %u of %u", (unsigned long long)i,
                      m->indices[i], m->vertex_count);
        FZ_ASSERT(fz_finite(m->positions, 3 * (size_t)m->vertex_count), "a position is not finite");
        FZ_ASSERT(memcmp(m->transform, t, sizeof t) == 0 && m->closed == closed && m->reserved == 0,
                  "transform or closed not passed through");
        banyan_host_mesh_free(m);
    }
    return 0;
}
