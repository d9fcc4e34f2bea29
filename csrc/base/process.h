/* process.h - this process's wall clock and resident memory, for the
 * library's budgets (progress.h) and the CLI's (cli/budget.c). */
#ifndef BANYAN_BASE_PROCESS_H
#define BANYAN_BASE_PROCESS_H

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds on the wall clock (UTC); 0 where it cannot be read. */
double process_now(void);
/* Resident memory of the process in MB, every thread's; 0 where it
 * cannot be read. */
double process_rss_mb(void);

#ifdef __cplusplus
}
#endif
#endif
