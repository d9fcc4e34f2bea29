/* pool.h - the caller plus threads - 1 pthreads on one job (the avenue's
 * trees, an instanced avenue's variants): each thread runs work(job,
 * caller) and takes items from the job's own atomic counter. The caller,
 * once done with its share, keeps the budget (and the progress callback's
 * heartbeat) in sleeps of 50 us growing to 2 ms until the others finish, and sets *cancel when
 * prog_at says stop. A thread that cannot be started only means fewer
 * workers. g NULL: the caller joins at once (short jobs whose threads
 * poll the budget themselves), no heartbeat to wait out. */
#ifndef BANYAN_POOL_H
#define BANYAN_POOL_H

#include <stdatomic.h>

#include "progress.h"

void pool_run(int threads, void (*work)(void *job, int caller), void *job, prog *g, atomic_int *cancel);

/* The library's one "threads 0 = all cores" rule: `threads` when it is
 * not 0, else the online cores, at least 1 and at most `max`. */
int pool_threads(int threads, int max);

#endif
