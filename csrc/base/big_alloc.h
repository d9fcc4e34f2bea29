/* big_alloc.h - malloc for arrays of many megabytes that are written
 * whole right away (merged meshes, sized builders): on Linux an array of
 * 4 MiB and more starts on a 2 MiB boundary and is advised to transparent
 * huge pages before anything touches it, so its first writes take one
 * page fault per 2 MiB instead of one per 4 KiB (malloc's own mmap starts
 * 16 bytes into a 4 KiB page: its first and last partial huge pages
 * faulted as 4 KiB pages, and the first of them before the advice).
 * The memory is plain malloc memory (posix_memalign): free() releases it,
 * as banyan_mesh_free does for every mesh array. */
#ifndef BANYAN_BIG_ALLOC_H
#define BANYAN_BIG_ALLOC_H

#include <stddef.h>

void *big_malloc(size_t bytes);
/* realloc: from NULL it is big_malloc; a grown array is advised again
 * (realloc may have moved it off the 2 MiB boundary); shrinking stays in
 * place. */
void *big_realloc(void *old, size_t bytes);

#endif
