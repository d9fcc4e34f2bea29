/* keyaki.c - the public keyaki calls: one tree, meshed
 * (banyan_keyaki_generate) or its skeleton measured only
 * (banyan_keyaki_skeleton_stats), per spec/keyaki.md. Growth is in
 * growth.c, Strahler in strahler.c, the body in body.c. The tree takes no
 * hosts: it stands at `position`, up +Z. */
#include <string.h>

#include "base/error.h"
#include "base/frame.h"
#include "base/pool.h"
#include "keyaki_internal.h"

/* Both calls grow the tree in a frame at its position (base/frame.h): q is
 * p moved into it; returns the frame's origin, which the mesh keeps. The
 * same frame gives both calls the same skeleton. */
static v3 tree_frame(const banyan_keyaki_params *p, banyan_keyaki_params *q) {
    *q = *p;
    v3 at = v3_load(p->position), O = frame_pick(at, at);
    for (int k = 0; k < 3; k++) q->position[k] -= (&O.x)[k];
    return O;
}

banyan_status banyan_keyaki_generate(const banyan_keyaki_params *p, banyan_mesh **out, banyan_keyaki_stats *stats,
                                     const banyan_progress *progress, banyan_error *err) {
    if (stats) memset(stats, 0, sizeof *stats);
    BANYAN_CHECK_OUT(out, err);
    banyan_status s = keyaki_params_validate(p, err);
    if (s) return s;
    if ((s = prog_check(progress, err))) return s;
    banyan_keyaki_params q;
    v3 O = tree_frame(p, &q);
    /* The budget: time and memory inside every loop, max_vertices while
     * the skeleton and the crown grow (docs/keyaki.md "Budget"). */
    prog g;
    prog_init(&g, progress);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    int threads = pool_threads(p->threads, BANYAN_AVENUE_MAX_THREADS);
    keyaki_run run = {&g, NULL, NULL, (uint64_t)p->max_vertices, 0, threads, 1};
    keyaki_skeleton sk = {NULL, 0, 0, &run};
    s = keyaki_build(&q, 0.0, 0, &sk, out, err);
    if (!s && prog_finish(&g)) {
        banyan_mesh_free(*out);
        *out = NULL;
        s = BANYAN_E_CANCELLED;
    }
    if (s && prog_stopped(&g)) s = prog_fail(&g, err, "keyaki");
    if (!s) {
        frame_set(*out, O);
        if (stats) keyaki_measure(sk.nodes, sk.count, v3_load(q.position), stats);
    }
    keyaki_skeleton_free(&sk);
    return s;
}

size_t banyan_sizeof_keyaki_stats(void) { return sizeof(banyan_keyaki_stats); }

banyan_status banyan_keyaki_skeleton_stats(const banyan_keyaki_params *p, banyan_keyaki_stats *out,
                                           banyan_error *err) {
    if (!out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL");
    memset(out, 0, sizeof *out);
    banyan_status s = keyaki_params_validate(p, err);
    if (s) return s;
    banyan_keyaki_params q;
    tree_frame(p, &q);
    prog g; /* the budget; no vertex estimate: nothing is meshed */
    prog_init(&g, NULL);
    prog_budget(&g, p->max_seconds, p->max_memory_mb);
    keyaki_run run = {&g, NULL, NULL, UINT64_MAX, 0, 1, 0};
    keyaki_skeleton sk = {NULL, 0, 0, &run};
    s = keyaki_grow(&q, &sk, err);
    if (s && prog_stopped(&g)) s = prog_fail(&g, err, "keyaki statistics");
    if (!s && keyaki_strahler(sk.nodes, sk.count))
        s = banyan_fail(err, BANYAN_E_INTERNAL, "skeleton children out of order");
    if (!s) {
        keyaki_measure(sk.nodes, sk.count, v3_load(q.position), out);
        banyan_error_clear(err);
    }
    keyaki_skeleton_free(&sk);
    return s;
}
