/* process.c - this process's wall clock and resident memory (process.h). */
#include "process.h"

#include <stdio.h>
#include <time.h>

double process_now(void) {
    struct timespec t;
    if (timespec_get(&t, TIME_UTC) != TIME_UTC) return 0.0;
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

double process_rss_mb(void) {
#if defined(__linux__)
    /* statm's second field: resident pages. Counts every thread's memory,
     * which is what a budget for threads must see. */
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return 0.0;
    unsigned long long size = 0, res = 0;
    int n = fscanf(f, "%llu %llu", &size, &res);
    fclose(f);
    return n == 2 ? (double)res * 4096.0 / (1024.0 * 1024.0) : 0.0;
#else
    return 0.0;
#endif
}
