/* pool.c - see pool.h. */
#include "pool.h"

#include "banyan.h"
#include "platform.h"

typedef struct pool {
    void (*work)(void *job, int caller);
    void *job;
    atomic_int running; /* threads other than the caller still working */
} pool;

static void *worker(void *arg) {
    pool *P = arg;
    P->work(P->job, 0);
    atomic_fetch_sub(&P->running, 1);
    return NULL;
}

void pool_run(int threads, void (*work)(void *job, int caller), void *job, prog *g, atomic_int *cancel) {
    plat_thread tid[BANYAN_AVENUE_MAX_THREADS];
    pool P = {work, job, 0};
    int started = 0;
    if (threads > BANYAN_AVENUE_MAX_THREADS) threads = BANYAN_AVENUE_MAX_THREADS;
    atomic_store(&P.running, threads - 1);
    for (int t = 1; t < threads; t++)
        if (plat_thread_start(&tid[started], worker, &P) == 0) started++;
    atomic_fetch_sub(&P.running, threads - 1 - started);
    work(job, 1);
    /* Sleeps from 50 us doubling to 2 ms: short jobs (an ivy's mesh items)
     * are joined soon after they end, long ones wake the caller rarely. */
    long pause = 50;
    while (g && atomic_load(&P.running) > 0) { /* no prog to keep: just join */
        if (prog_at(g, g->last)) atomic_store(cancel, 1);
        plat_sleep_us(pause);
        pause = pause * 2 < 2000 ? pause * 2 : 2000;
    }
    for (int t = 0; t < started; t++) plat_thread_join(&tid[t]);
}

int pool_threads(int threads, int max) {
    if (threads != 0) return threads;
    int c = plat_cpus();
    return c > max ? max : c;
}
