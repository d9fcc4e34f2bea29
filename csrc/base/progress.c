/* progress.c - the progress / cancel callback and the run's budget
 * (progress.h). */
#include "progress.h"

#include "error.h"

#define PROG_MEM_EVERY 0.02 /* seconds between reads of the resident size */

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
    g->t_last = g->fn ? process_now() : 0.0;
    g->cancelled = PROG_RUNNING;
    g->t_start = g->max_seconds = g->max_mb = 0.0;
    g->rss0_mb = g->t_mem = g->over_value = 0.0;
}

void prog_budget_resume(prog *g, double max_seconds, double max_memory_mb, double spent, double rss0_mb) {
    g->max_seconds = max_seconds;
    g->max_mb = max_memory_mb;
    g->t_mem = process_now();
    g->t_start = g->t_mem - spent;
    g->rss0_mb = rss0_mb;
}

void prog_budget(prog *g, double max_seconds, double max_memory_mb) {
    prog_budget_resume(g, max_seconds, max_memory_mb, 0.0, process_rss_mb());
}

int prog_reserve(prog *g, double bytes) {
    if (!g || g->max_mb <= 0.0) return 0;
    if (g->cancelled) return 1;
    double mb = process_rss_mb() - g->rss0_mb + bytes / (1024.0 * 1024.0);
    if (mb > g->max_mb) {
        g->cancelled = PROG_OVER_MEMORY;
        g->over_value = mb;
    }
    return g->cancelled != PROG_RUNNING;
}

/* 1 when the budget is spent; reads the clock every call and the resident
 * size every PROG_MEM_EVERY seconds. */
static int over_budget(prog *g, double t) {
    if (g->max_seconds > 0.0 && t - g->t_start > g->max_seconds) {
        g->cancelled = PROG_OVER_TIME;
        g->over_value = t - g->t_start;
        return 1;
    }
    if (g->max_mb > 0.0 && t - g->t_mem >= PROG_MEM_EVERY) {
        g->t_mem = t;
        double mb = process_rss_mb() - g->rss0_mb;
        if (mb > g->max_mb) {
            g->cancelled = PROG_OVER_MEMORY;
            g->over_value = mb;
            return 1;
        }
    }
    return 0;
}

int prog_at(prog *g, double done) {
    if (!g) return 0;
    if (g->cancelled) return 1;
    int budget = g->max_seconds > 0.0 || g->max_mb > 0.0;
    if (!g->fn && !budget) return 0;
    double t = process_now();
    if (budget && over_budget(g, t)) return 1;
    if (!g->fn) return 0;
    if (!(done >= g->last)) done = g->last; /* NaN too */
    if (done > 0.999) done = 0.999;          /* 1.0 only on success */
    if (done < g->last + 0.01 && t - g->t_last < PROG_HEARTBEAT) return 0;
    g->last = done;
    g->t_last = t;
    if (g->fn(g->user, done)) g->cancelled = PROG_CANCELLED;
    return g->cancelled != PROG_RUNNING;
}

int prog_finish(prog *g) {
    if (!g || !g->fn) return g && g->cancelled;
    if (g->cancelled) return 1;
    g->last = 1.0;
    if (g->fn(g->user, 1.0)) g->cancelled = PROG_CANCELLED;
    return g->cancelled != PROG_RUNNING;
}

banyan_status prog_fail(const prog *g, banyan_error *err, const char *what) {
    if (g && g->cancelled == PROG_OVER_TIME)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "%s stopped after %.2f s, past max_seconds = %g (%g .. %.0f); raise max_seconds "
                           "or ask for less work", what, g->over_value, g->max_seconds,
                           PROG_MAX_SECONDS_MIN, PROG_MAX_SECONDS_MAX);
    if (g && g->cancelled == PROG_OVER_MEMORY)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "%s needs %.0f MB, past max_memory_mb = %g (%.0f .. %.0f); raise max_memory_mb "
                           "or ask for less work", what, g->over_value, g->max_mb,
                           PROG_MAX_MEMORY_MIN, PROG_MAX_MEMORY_MAX);
    return banyan_fail(err, BANYAN_E_CANCELLED, "%s cancelled by the progress callback", what);
}


prog_deadline prog_deadline_of(const prog *g) {
    prog_deadline d = {0.0};
    if (g && g->max_seconds > 0.0) d.t_end = g->t_start + g->max_seconds;
    return d;
}

void banyan_budget_init(banyan_budget *b) {
    if (!b) return;
    b->max_seconds = PROG_MAX_SECONDS_DEFAULT;
    b->max_memory_mb = PROG_MAX_MEMORY_DEFAULT;
}

size_t banyan_sizeof_budget(void) { return sizeof(banyan_budget); }

banyan_status prog_budget_from(prog *g, const banyan_budget *b, banyan_error *err) {
    banyan_budget d;
    banyan_budget_init(&d);
    if (b) d = *b;
    if (!(d.max_seconds >= PROG_MAX_SECONDS_MIN && d.max_seconds <= PROG_MAX_SECONDS_MAX))
        return banyan_fail(err, BANYAN_E_RANGE, "budget->max_seconds = %g is outside [%g, %.0f] (seconds)",
                           d.max_seconds, PROG_MAX_SECONDS_MIN, PROG_MAX_SECONDS_MAX);
    if (!(d.max_memory_mb >= PROG_MAX_MEMORY_MIN && d.max_memory_mb <= PROG_MAX_MEMORY_MAX))
        return banyan_fail(err, BANYAN_E_RANGE, "budget->max_memory_mb = %g is outside [%.0f, %.0f] (MB)",
                           d.max_memory_mb, PROG_MAX_MEMORY_MIN, PROG_MAX_MEMORY_MAX);
    prog_init(g, NULL);
    prog_budget(g, d.max_seconds, d.max_memory_mb);
    return BANYAN_OK;
}
