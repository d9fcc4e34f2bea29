/* big_alloc and the builder's external arrays: large arrays start on a
 * 2 MiB boundary (Linux), keep their contents through realloc and are
 * released by free() (banyan_mesh_free frees every mesh array so; ASan
 * builds report any leak or mismatch). A builder writing into the
 * caller's skeleton refuses to pass the room it was given and never hands
 * the caller's arrays over as its own mesh. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "base/big_alloc.h"
#include "mesh/mesh_builder.h"

#define MIB ((size_t)1 << 20)

static int aligned_2m(const void *p) { return ((uintptr_t)p & (2 * MIB - 1)) == 0; }

/* Fills n bytes with a pattern of seed; 1 if p holds it. */
static void fill(unsigned char *p, size_t n, unsigned seed) {
    for (size_t i = 0; i < n; i++) p[i] = (unsigned char)(i * 31u + seed);
}
static int holds(const unsigned char *p, size_t n, unsigned seed) {
    for (size_t i = 0; i < n; i++)
        if (p[i] != (unsigned char)(i * 31u + seed)) return 0;
    return 1;
}

static void sizes(void) {
    /* Around the 4 MiB threshold and the round-up rule (at most a quarter). */
    const size_t n[] = {1, 4096, 4 * MIB - 1, 4 * MIB, 4 * MIB + 1, 7 * MIB + 12345, 64 * MIB + 3};
    for (size_t k = 0; k < sizeof n / sizeof *n; k++) {
        unsigned char *p = big_malloc(n[k]);
        CHECK(p != NULL, "big_malloc(%zu) failed", n[k]);
        if (!p) continue;
#if defined(__linux__)
        if (n[k] >= 4 * MIB) CHECK(aligned_2m(p), "big_malloc(%zu) = %p is not on a 2 MiB boundary", n[k], (void *)p);
#endif
        fill(p, n[k], (unsigned)k);
        CHECK(holds(p, n[k], (unsigned)k), "big_malloc(%zu) did not keep what was written", n[k]);
        free(p);
    }
}

static void reallocs(void) {
    unsigned char *p = big_realloc(NULL, 6 * MIB); /* from NULL: big_malloc */
    CHECK(p != NULL, "big_realloc(NULL, 6 MiB) failed");
    if (!p) return;
#if defined(__linux__)
    CHECK(aligned_2m(p), "big_realloc(NULL, 6 MiB) = %p is not on a 2 MiB boundary", (void *)p);
#endif
    fill(p, 6 * MIB, 7);
    unsigned char *q = big_realloc(p, 20 * MIB); /* grown: contents kept */
    CHECK(q != NULL, "big_realloc to 20 MiB failed");
    if (!q) {
        free(p);
        return;
    }
    CHECK(holds(q, 6 * MIB, 7), "growing lost the contents");
    fill(q, 20 * MIB, 9);
    unsigned char *r = big_realloc(q, 5 * MIB + 17); /* shrunk: contents kept */
    CHECK(r != NULL, "big_realloc to 5 MiB failed");
    if (!r) {
        free(q);
        return;
    }
    CHECK(holds(r, 5 * MIB + 17, 9), "shrinking lost the contents");
    free(r);
}

/* A sized builder's big arrays come from big_alloc; mb_finish hands them
 * over and banyan_mesh_free releases them. */
static void sized_builder(void) {
    mesh_builder mb;
    mb_init(&mb, MB_VERTEX_CEILING, 1);
    int slot = mb_add_attr(&mb, "a");
    uint32_t nv = 1200000; /* 4.8 MB per attribute, 14.4 MB of positions */
    CHECK(mb_reserve(&mb, nv, 3) == BANYAN_OK, "mb_reserve failed");
#if defined(__linux__)
    CHECK(aligned_2m(mb.pos) && aligned_2m(mb.nrm) && aligned_2m(mb.col) && aligned_2m(mb.attr[slot]),
          "the builder's big arrays are not on 2 MiB boundaries");
#endif
    mb_set_attr(&mb, slot, 0.5);
    uint32_t first = mb_vertices(&mb, nv);
    CHECK(first == 0, "mb_vertices returned %u", first);
    for (uint32_t i = 0; i < nv; i++) mb_put(&mb, i, v3_make(i, 0, 0), v3_make(0, 0, 1), 0, 0);
    mb_tri(&mb, 0, 1, 2);
    banyan_mesh *m = NULL;
    banyan_error err;
    CHECK(mb_finish(&mb, &m, &err) == BANYAN_OK && m, "mb_finish failed");
    if (m) {
        CHECK(m->vertex_count == nv && m->positions[3 * (nv - 1)] == (float)(nv - 1) &&
                  m->attributes[0].data[nv - 1] == 0.5f && m->colors[4 * (nv - 1) + 3] == 1.0f,
              "the finished mesh lost vertices");
    }
    banyan_mesh_free(m);
}

static void external_skeleton(void) {
    float pos[3 * 4], nrm[3 * 4], uv[2 * 4], spos[3 * 2], srad[2];
    int32_t stag[2];
    uint32_t idx[3], edges[2 * 1];
    mesh_builder mb;
    mb_init_external(&mb, 4, 3, pos, nrm, uv, NULL, idx, NULL, NULL, 0);
    mb_external_skeleton(&mb, spos, srad, stag, 2, edges, 1);
    CHECK(mb_skel_reserve(&mb, 2, 1) == BANYAN_OK, "reserving the room given failed");
    uint32_t a = mb_skel_point(&mb, v3_make(1, 2, 3), 0.5, 7), b = mb_skel_point(&mb, v3_make(4, 5, 6), 0.25, 8);
    mb_skel_edge(&mb, a, b);
    CHECK(mb.status == BANYAN_OK && a == 0 && b == 1, "points in the room given failed: status %d", (int)mb.status);
    CHECK(spos[3] == 4.0f && srad[1] == 0.25f && stag[1] == 8 && edges[0] == 0 && edges[1] == 1,
          "the skeleton was not written into the caller's arrays");
    mb_skel_point(&mb, v3_make(0, 0, 0), 1, 0); /* past the room given */
    CHECK(mb.status == BANYAN_E_INTERNAL, "a point past the room given: status %d, want BANYAN_E_INTERNAL",
          (int)mb.status);
    mb_free(&mb); /* must not free the caller's arrays (ASan: a bad free) */

    /* mb_finish never hands the caller's arrays over. */
    mb_init_external(&mb, 4, 3, pos, nrm, uv, NULL, idx, NULL, NULL, 0);
    mb_external_skeleton(&mb, spos, srad, stag, 2, edges, 1);
    for (int i = 0; i < 3; i++) mb_vertex(&mb, v3_make(i, i * i, 0), v3_make(0, 0, 1), 0, 0);
    mb_tri(&mb, 0, 1, 2);
    banyan_mesh *m = (banyan_mesh *)&mb; /* anything but NULL */
    banyan_error err;
    CHECK(mb_finish(&mb, &m, &err) == BANYAN_E_INTERNAL && m == NULL,
          "mb_finish on the caller's arrays must fail with *out NULL");

    /* Too late once points went into the builder's own arrays. */
    mb_init(&mb, 100, 0);
    mb_skel_point(&mb, v3_make(0, 0, 0), 1, 0);
    mb_external_skeleton(&mb, spos, srad, stag, 2, edges, 1);
    CHECK(mb.status == BANYAN_E_INTERNAL && mb.skel_pos != spos,
          "mb_external_skeleton after points were added must fail and keep the builder's arrays");
    mb_free(&mb);
}

int main(void) {
    sizes();
    reallocs();
    sized_builder();
    external_skeleton();
    return check_done("test_big_alloc");
}
