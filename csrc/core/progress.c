/* progress.c - the progress / cancel callback helper (progress.h). */
#include "progress.h"

#include <time.h>

#include "error.h"

static double now_seconds(void) {
    struct timespec t;
    if (timespec_get(&t, TIME_UTC) != TIME_UTC) return 0.0;
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

banyan_status prog_check(const banyan_progress *p, banyan_error *err) {
    if (p && !p->fn)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                           "progress->fn is NULL; pass progress = NULL for no progress, or set a callback");
    return BANYAN_OK;
}

void prog_init(prog *g, const banyan_progress *p) {
    g->fn = p ? p->fn : NULL;
    g->user = p ? p->user : NULL;
    g->last = 0.0;
    g->t_last = g->fn ? now_seconds() : 0.0;
    g->cancelled = 0;
}

int prog_at(prog *g, double done) {
    if (!g || !g->fn) return 0;
    if (g->cancelled) return 1;
    if (!(done >= g->last)) done = g->last; /* NaN too */
    if (done > 0.999) done = 0.999;          /* 1.0 only on success */
    double t = now_seconds();
    if (done < g->last + 0.01 && t - g->t_last < PROG_HEARTBEAT) return 0;
    g->last = done;
    g->t_last = t;
    if (g->fn(g->user, done)) g->cancelled = 1;
    return g->cancelled;
}

int prog_finish(prog *g) {
    if (!g || !g->fn) return 0;
    if (g->cancelled) return 1;
    g->last = 1.0;
    if (g->fn(g->user, 1.0)) g->cancelled = 1;
    return g->cancelled;
}

banyan_status prog_fail(banyan_error *err, const char *what) {
    return banyan_fail(err, BANYAN_E_CANCELLED, "%s cancelled by the progress callback", what);
}
