/* progress.h - the progress / cancel callback of the long calls
 * (banyan_progress, docs/api.md "Progress and cancel"): one place that
 * keeps the fraction monotone, calls the callback about 100 times for the
 * fraction plus at most every PROG_HEARTBEAT seconds while the fraction
 * moves slower (so a cancel is heard within that), and remembers a cancel.
 * The callback never touches the generator's state or its random
 * numbers, so the output is the same with or without one. */
#ifndef BANYAN_PROGRESS_H
#define BANYAN_PROGRESS_H

#include "banyan.h"

#define PROG_HEARTBEAT 0.1 /* seconds */

typedef struct prog {
    banyan_progress_fn fn; /* NULL: no progress, every call is a no-op */
    void *user;
    double last;           /* the fraction last reported */
    double t_last;         /* when fn was last called */
    int32_t cancelled;     /* fn returned nonzero (sticky) */
} prog;

/* Checks the caller's struct: NULL is fine (no progress); a struct without
 * fn is refused, naming `progress->fn`. */
banyan_status prog_check(const banyan_progress *p, banyan_error *err);
void prog_init(prog *g, const banyan_progress *p);
/* `done` (clamped to [last, 0.999]) reached: calls fn when the fraction
 * moved by 1 % or the heartbeat is due. Returns 1 once cancelled. Cheap
 * enough to call per unit of work (a clock read). */
int prog_at(prog *g, double done);
/* The final 1.0 on success; returns 1 when fn cancels even then. */
int prog_finish(prog *g);
static inline int prog_stopped(const prog *g) { return g && g->cancelled; }
/* Fills err for BANYAN_E_CANCELLED and returns it. */
banyan_status prog_fail(banyan_error *err, const char *what);

#endif
