/* keyaki.c - the public keyaki calls: one tree, meshed
 * (banyan_keyaki_generate) or measured only (banyan_keyaki_stats), per
 * spec/keyaki.md. Growth is in growth.c, Strahler in strahler.c, the body
 * in body.c. The tree takes no hosts: it stands at `position`, up +Z. */
#include <string.h>

#include "base/error.h"
#include "base/frame.h"
#include "base/pool.h"
#include "keyaki_internal.h"

banyan_status banyan_keyaki_generate(const banyan_keyaki_params *p, banyan_mesh **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    banyan_status s = keyaki_params_validate(p, err);
    if (s) return s;
    /* Grown in a frame at its position (base/frame.h), which the mesh keeps. */
    banyan_keyaki_params q = *p;
    v3 at = v3_load(p->position), O = frame_pick(at, at);
    for (int k = 0; k < 3; k++) q.position[k] -= (&O.x)[k];
    /* The budget: time and memory inside every loop, max_vertices while
     * the skeleton and the crown grow (docs/keyaki.md "Budget"). */
    prog g;
    prog_init(&g, NULL);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    int threads = pool_threads(p->threads, BANYAN_AVENUE_MAX_THREADS);
    keyaki_run run = {&g, NULL, NULL, (uint64_t)p->max_vertices, 0, threads};
    keyaki_skeleton sk = {NULL, 0, 0, &run};
    s = keyaki_build(&q, 0.0, 0, &sk, out, err);
    keyaki_skeleton_free(&sk);
    if (s && prog_stopped(&g)) s = prog_fail(&g, err, "keyaki");
    if (!s) frame_set(*out, O);
    return s;
}

size_t banyan_sizeof_keyaki_statistics(void) { return sizeof(banyan_keyaki_statistics); }

banyan_status banyan_keyaki_stats(const banyan_keyaki_params *p, banyan_keyaki_statistics *out, banyan_error *err) {
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    memset(out, 0, sizeof *out);
    banyan_status s = keyaki_params_validate(p, err);
    if (s) return s;
    prog g; /* the budget; no vertex estimate: nothing is meshed */
    prog_init(&g, NULL);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    keyaki_run run = {&g, NULL, NULL, UINT64_MAX, 0, 1};
    keyaki_skeleton sk = {NULL, 0, 0, &run};
    s = keyaki_grow(p, &sk, err);
    if (s && prog_stopped(&g)) s = prog_fail(&g, err, "keyaki statistics");
    if (!s && keyaki_strahler(sk.nodes, sk.count))
        s = banyan_fail(err, BANYAN_E_INTERNAL, "skeleton children out of order");
    if (!s) {
        keyaki_measure(sk.nodes, sk.count, v3_load(p->position), out);
        banyan_error_clear(err);
    }
    keyaki_skeleton_free(&sk);
    return s;
}
