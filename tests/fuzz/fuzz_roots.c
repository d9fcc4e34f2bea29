/* fuzz_roots.c - libFuzzer harness: bytes -> roots params (through the
 * parameter table) and hosts -> a host set of them -> banyan_roots_generate
 * with stats -> free.
 * Generation is kept small - max_vertices at most 50,000, moves at most
 * 5, growth_points at most 200 - since time, not memory, is the fuzzer's
 * budget; the code paths are the same as for large nets. An input with an
 * FZ_REAL record keeps its sizes (a preset's real net) under the run
 * budget, max_vertices at most FZ_REAL_MAX_VERTICES. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    fz_input in;
    fz_read(BANYAN_GEN_ROOTS, &p, data, size, &in);
    p.max_vertices = fz_clamp_i32(p.max_vertices, in.real ? FZ_REAL_MAX_VERTICES : 50000);
    if (!in.real) {
        p.moves = fz_clamp_i32(p.moves, 5);
        p.growth_points = fz_clamp_i32(p.growth_points, 200);
    }
    fz_budget(BANYAN_GEN_ROOTS, &p);
    if (in.n_hosts == 0 && !(in.n_control && in.control[0] & 1)) {
        in.hosts[0] = banyan_box_make(0, 0, 1, 0.3, 0.3, 1); /* a trunk, unless the input wants none */
        in.n_hosts = 1;
    }
    banyan_mesh *m = (banyan_mesh *)&p; /* non-NULL: the call must clear it */
    banyan_roots_stats st;
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_hosts *H = (banyan_hosts *)&p; /* non-NULL: a refusal must clear it */
    banyan_status s = banyan_hosts_create(in.hosts, in.n_hosts, NULL, 0, &H, &e);
    if (s) {
        fz_check_failure(s, &e, H);
        return 0;
    }
    s = banyan_roots_generate(&p, H, &m, &st, NULL, &e);
    banyan_hosts_free(H);
    if (s == BANYAN_OK) {
        FZ_ASSERT(st.vertices == m->vertex_count, "stats %u vertices, mesh %u", st.vertices, m->vertex_count);
    } else {
        FZ_ASSERT(st.vertices == 0, "stats not zeroed on failure");
    }
    fz_check(s, &e, m, (uint32_t)(p.max_vertices > 0 ? p.max_vertices : 0));
    return 0;
}
