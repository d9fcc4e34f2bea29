/* big_alloc.h - malloc for arrays of many megabytes that are written
 * whole right away (merged meshes): on Linux it asks for transparent huge
 * pages (arrays of 4 MiB and more), so the first writes take one page fault per 2 MiB instead of one
 * per 4 KiB. The memory is plain malloc memory: free() releases it. */
#ifndef BANYAN_BIG_ALLOC_H
#define BANYAN_BIG_ALLOC_H

#include <stddef.h>

void *big_malloc(size_t bytes);
/* realloc, with the same advice for the grown array. */
void *big_realloc(void *old, size_t bytes);

#endif
