/* fuzz_ivy.c - libFuzzer harness for ivy: bytes -> ivy params and hosts.
 * The hosts go into a host set (a refusal is checked like any other).
 * Without control records: banyan_ivy_generate. With them: the stepping
 * calls - create, then for each control byte c step c % 64 steps and, when
 * c >= 128, mesh in between - then the mesh must equal a one-shot
 * generation of as many steps - then free. Kept small: steps at most 80,
 * max_buds at most 5,000, candidates at most 16, max_vertices at most
 * 50,000; with an FZ_REAL record, the input's sizes under the run budget
 * (max_vertices at most FZ_REAL_MAX_VERTICES). */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    banyan_ivy_params p;
    banyan_ivy_params_init(&p);
    fz_input in;
    fz_read(BANYAN_GEN_IVY, &p, data, size, &in);
    if (!in.real) {
        p.steps = fz_clamp_i32(p.steps, 80);
        if (banyan_ivy_steps(&p) > 80) p.years = 0; /* years also decide the steps */
        p.max_buds = fz_clamp_i32(p.max_buds, 5000);
        p.candidates = fz_clamp_i32(p.candidates, 16);
    }
    p.max_vertices = fz_clamp_i32(p.max_vertices, in.real ? FZ_REAL_MAX_VERTICES : 50000);
    fz_budget(BANYAN_GEN_IVY, &p);
    if (in.n_hosts == 0) {
        in.hosts[0] = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5); /* the CLI's wall */
        in.n_hosts = 1;
    }
    uint32_t max_v = (uint32_t)(p.max_vertices > 0 ? p.max_vertices : 0);
    banyan_error e;
    memset(&e, 0, sizeof e);
    banyan_hosts *H = (banyan_hosts *)&p; /* non-NULL: a refusal must clear it */
    banyan_status s = banyan_hosts_create(in.hosts, in.n_hosts, NULL, 0, &H, &e);
    if (s) {
        fz_check_failure(s, &e, H);
        return 0;
    }
    if (in.n_control == 0) {
        banyan_mesh *m = (banyan_mesh *)&p;
        s = banyan_ivy_generate(&p, H, &m, NULL, NULL, &e);
        fz_check(s, &e, m, max_v);
        banyan_hosts_free(H);
        return 0;
    }
    banyan_ivy *iv = (banyan_ivy *)&p;
    s = banyan_ivy_create(&p, H, &iv, &e);
    if (s) {
        fz_check_failure(s, &e, iv);
        banyan_hosts_free(H);
        return 0;
    }
    int32_t grown = 0;
    int limited = 0;
    for (int k = 0; k < in.n_control; k++) {
        int32_t n = in.control[k] % 64;
        s = banyan_ivy_step(iv, n, &e);
        if (s) {
            FZ_ASSERT(s == BANYAN_E_LIMIT || s == BANYAN_E_NOMEM, "step: %s", e.message);
            fz_check_failure(s, &e, NULL);
            limited = 1;
            break;
        }
        grown += n;
        banyan_ivy_stats st;
        s = banyan_ivy_get_stats(iv, &st, &e);
        FZ_ASSERT(s == BANYAN_OK, "stats: %s", e.message);
        FZ_ASSERT(st.steps == grown && st.buds >= 1, "stats: %d steps of %d, %d buds", st.steps, grown, st.buds);
        if (in.control[k] >= 128) {
            banyan_mesh *m = (banyan_mesh *)&p;
            s = banyan_ivy_mesh(iv, &m, &e);
            FZ_ASSERT(s == BANYAN_OK || s == BANYAN_E_LIMIT, "mesh: %s", e.message);
            fz_check(s, &e, m, max_v);
            if (fz_budget_stop(s, &e)) limited = 1; /* the one shot below may end otherwise */
        }
    }
    /* Growing in pieces gives the plant grown at once (banyan/ivy.h). */
    if (!limited) {
        banyan_mesh *a = NULL, *b = NULL;
        banyan_error eb;
        banyan_status sa = banyan_ivy_mesh(iv, &a, &e);
        banyan_ivy_params once = p;
        once.steps = grown;
        once.years = 0; /* `steps`, not the age, decides the one shot */
        banyan_status sb = banyan_ivy_generate(&once, H, &b, NULL, NULL, &eb);
        FZ_ASSERT(sa == sb || fz_budget_stop(sa, &e) || fz_budget_stop(sb, &eb), "stepped mesh %s, one shot %s", banyan_status_name(sa), banyan_status_name(sb));
        if (sa == BANYAN_OK)
            FZ_ASSERT(banyan_mesh_hash(a) == banyan_mesh_hash(b), "%d steps in pieces differ from one shot", grown);
        banyan_mesh_free(a);
        banyan_mesh_free(b);
    }
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
    return 0;
}
