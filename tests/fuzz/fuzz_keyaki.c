/* fuzz_keyaki.c - libFuzzer harness for keyaki trees and avenues. The
 * first byte picks: even, one tree (banyan_keyaki_generate and
 * banyan_keyaki_stats); odd, an avenue (banyan_avenue_layout and
 * banyan_avenue_generate on 0 .. 4 threads, from a control record, which
 * must give the same mesh as 1 thread). The
 * rest are records (fuzz_common.h) for that generator's table. Kept small
 * (max_vertices at most 50,000, max_nodes at most 4,000, at most 16 trees)
 * unless the input has an FZ_REAL record: then the preset's own sizes,
 * max_vertices at most FZ_REAL_MAX_VERTICES, and the run budget. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void tree(const uint8_t *data, size_t size) {
    banyan_keyaki_params p;
    banyan_keyaki_params_init(&p);
    fz_input in;
    fz_read(BANYAN_GEN_KEYAKI, &p, data, size, &in);
    p.max_vertices = fz_clamp_i32(p.max_vertices, in.real ? FZ_REAL_MAX_VERTICES : 50000);
    if (!in.real) p.max_nodes = fz_clamp_i32(p.max_nodes, 4000);
    fz_budget(BANYAN_GEN_KEYAKI, &p);
    banyan_keyaki_stats st;
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_keyaki_skeleton_stats(&p, &st, &e);
    if (s) fz_check_failure(s, &e, NULL);
    else FZ_ASSERT(st.node_count >= 1 && st.node_count <= p.max_nodes, "node_count %d", st.node_count);
    int stopped = fz_budget_stop(s, &e);
    banyan_mesh *m = (banyan_mesh *)&p;
    memset(&e, 0, sizeof e);
    banyan_status s2 = banyan_keyaki_generate(&p, &m, NULL, NULL, &e);
    /* The mesh adds only the vertex limit to what the skeleton can refuse
     * (and a budget that stopped either call says nothing of the other). */
    FZ_ASSERT(s == BANYAN_OK || stopped ? s2 == BANYAN_OK || s2 == BANYAN_E_LIMIT : s2 == s || fz_budget_stop(s2, &e),
              "stats %s, generate %s", banyan_status_name(s), banyan_status_name(s2));
    fz_check(s2, &e, m, (uint32_t)(p.max_vertices > 0 ? p.max_vertices : 0));
}

static void avenue(const uint8_t *data, size_t size) {
    banyan_avenue_params p;
    banyan_avenue_params_init(&p);
    fz_input in;
    fz_read(BANYAN_GEN_AVENUE, &p, data, size, &in);
    p.max_vertices = fz_clamp_i32(p.max_vertices, in.real ? FZ_REAL_MAX_VERTICES : 50000);
    if (!in.real) p.tree.max_nodes = fz_clamp_i32(p.tree.max_nodes, 4000);
    fz_budget(BANYAN_GEN_AVENUE, &p);
    uint32_t n = 0;
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_status s = banyan_avenue_layout(&p, NULL, 0, NULL, 0, &n, &e);
    if (s) {
        fz_check_failure(s, &e, NULL);
        return;
    }
    if (n > 16 && !in.real) { /* keep the run short: a few trees per row */
        p.placement = BANYAN_AVENUE_COUNT;
        p.count = 1 + (int32_t)(n % 8);
    }
    uint32_t cap = n ? n : 1;
    banyan_keyaki_params *trees = malloc(sizeof *trees * cap);
    FZ_ASSERT(trees != NULL, "%u trees", cap);
    s = banyan_avenue_layout(&p, NULL, 0, trees, cap, &n, &e);
    free(trees);
    if (s) fz_check_failure(s, &e, NULL);
    int threads = in.n_control ? in.control[0] % 5 : 2; /* 0 = all cores */
    banyan_mesh *m = (banyan_mesh *)&p;
    memset(&e, 0, sizeof e);
    p.threads = threads;
    s = banyan_avenue_generate(&p, NULL, 0, &m, NULL, &e);
    /* The output does not depend on the thread count (banyan/keyaki.h). */
    uint64_t h = s == BANYAN_OK ? banyan_mesh_hash(m) : 0;
    fz_check(s, &e, m, (uint32_t)(p.max_vertices > 0 ? p.max_vertices : 0));
    int stopped = fz_budget_stop(s, &e);
    banyan_mesh *one = NULL;
    memset(&e, 0, sizeof e);
    p.threads = 1;
    banyan_status s1 = banyan_avenue_generate(&p, NULL, 0, &one, NULL, &e);
    if (stopped || fz_budget_stop(s1, &e)) { /* the budget, not the input, decided one of them */
        fz_check(s1, &e, one, (uint32_t)(p.max_vertices > 0 ? p.max_vertices : 0));
        return;
    }
    FZ_ASSERT(s1 == s, "%d threads: %s, 1 thread: %s", threads, banyan_status_name(s), banyan_status_name(s1));
    if (s1 == BANYAN_OK)
        FZ_ASSERT(banyan_mesh_hash(one) == h, "%d threads and 1 thread give different meshes", threads);
    banyan_mesh_free(one);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size == 0) return 0;
    if (data[0] & 1) avenue(data + 1, size - 1);
    else tree(data + 1, size - 1);
    return 0;
}
