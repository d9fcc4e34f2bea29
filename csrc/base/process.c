/* process.c - this process's wall clock and resident memory (process.h). */
#include "process.h"

#include "platform.h"

double process_now(void) { return plat_wall(); }

double process_rss_mb(void) { return plat_rss_mb(); }
