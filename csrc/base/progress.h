/* progress.h - the progress / cancel callback of the long calls
 * (banyan_progress, docs/api.md "Progress and cancel") and the run's
 * budget: one place that keeps the fraction monotone, calls the
 * callback about 100 times for the fraction plus at most every
 * PROG_HEARTBEAT seconds while the fraction moves slower (so a cancel is
 * heard within that), remembers a cancel, and stops a run that passes its
 * max_seconds or max_memory_mb. The budget is checked at the same points
 * as the cancel, with or without a callback, so every loop that can cancel
 * also keeps the budget. Only the thread that called the generator calls
 * prog_*; workers watch their own stop flag. The callback never touches
 * the generator's state or its random numbers, so the output is the same
 * with or without one; a budget either lets a run finish with the same
 * bytes or stops it with BANYAN_E_LIMIT. */
#ifndef BANYAN_PROGRESS_H
#define BANYAN_PROGRESS_H

#include "banyan.h"
#include "process.h"

#ifdef __cplusplus
extern "C" { /* the glTF writer and the OpenVDB shim are C++ */
#endif

#define PROG_HEARTBEAT 0.1 /* seconds */
/* The budget parameters every generator's params carry, with one range. */
#define PROG_MAX_SECONDS_MIN 0.01
#define PROG_MAX_SECONDS_MAX 604800.0
#define PROG_MAX_SECONDS_DEFAULT 600.0
#define PROG_MAX_MEMORY_MIN 16.0
#define PROG_MAX_MEMORY_MAX 1048576.0
#define PROG_MAX_MEMORY_DEFAULT 8192.0 /* catches a runaway well before a 16 GB machine swaps */

enum { PROG_RUNNING = 0, PROG_CANCELLED = 1, PROG_OVER_TIME = 2, PROG_OVER_MEMORY = 3 };

typedef struct prog {
    banyan_progress_fn fn; /* NULL: no callback */
    void *user;
    double last;           /* the fraction last reported */
    double t_last;         /* when fn was last called */
    int32_t cancelled;     /* nonzero once stopped (sticky): a PROG_* reason */
    /* Budget (prog_budget); max_seconds 0 = none set. */
    double t_start, max_seconds, max_mb;
    double rss0_mb, t_mem; /* resident MB at the start; last memory read */
    double over_value;     /* seconds or MB when the budget stopped the run */
} prog;

/* Checks the caller's struct: NULL is fine (no progress); a struct without
 * fn is refused, naming `progress->fn`. */
banyan_status prog_check(const banyan_progress *p, banyan_error *err);
void prog_init(prog *g, const banyan_progress *p);
/* Starts the run's clock and memory baseline: past max_seconds of wall
 * time, or max_memory_mb of resident memory above what the process held at
 * this call, prog_at returns 1 and prog_fail reports BANYAN_E_LIMIT. */
void prog_budget(prog *g, double max_seconds, double max_memory_mb);
/* The same budget resumed across calls (the ivy's step API): `spent`
 * seconds already used by earlier calls, memory counted from rss0_mb. */
void prog_budget_resume(prog *g, double max_seconds, double max_memory_mb, double spent, double rss0_mb);
/* An estimate made before the work: 1 (and the run stopped as over its
 * memory) when `bytes` more would pass max_memory_mb. */
int prog_reserve(prog *g, double bytes);
/* `done` (clamped to [last, 0.999]) reached: keeps the budget, then calls
 * fn when the fraction moved by 1 % or the heartbeat is due. Returns 1 once
 * stopped. Cheap enough to call per unit of work (a clock read). */
int prog_at(prog *g, double done);
/* The final 1.0 on success; returns 1 when fn cancels even then. */
int prog_finish(prog *g);
static inline int prog_stopped(const prog *g) { return g && g->cancelled; }
/* Fills err for why the run stopped and returns its status:
 * BANYAN_E_CANCELLED for the callback, BANYAN_E_LIMIT naming max_seconds
 * or max_memory_mb for the budget. `what` names the run ("roots"). */
banyan_status prog_fail(const prog *g, banyan_error *err, const char *what);

/* The public banyan_budget of the calls whose params carry none (LOD,
 * textures, the glTF writer): NULL is the defaults; a bad field is refused
 * naming budget->max_seconds or budget->max_memory_mb and the range. On
 * success g's budget is started (prog_budget). */
banyan_status prog_budget_from(prog *g, const banyan_budget *b, banyan_error *err);

/* A wall-clock deadline that any thread may check without changing it
 * (the textures are drawn on the glTF writer's threads, which must not
 * call prog_at): t_end 0 = none. */
typedef struct prog_deadline {
    double t_end;
} prog_deadline;
/* The deadline of g's budget (0 when g has no max_seconds). */
prog_deadline prog_deadline_of(const prog *g);
static inline int prog_deadline_passed(const prog_deadline *d) { return d && d->t_end > 0.0 && process_now() > d->t_end; }

#ifdef __cplusplus
}
#endif
#endif
