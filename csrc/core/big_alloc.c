/* big_alloc.c - malloc for large output arrays (big_alloc.h). */
#define _DEFAULT_SOURCE
#include "big_alloc.h"

#include <stdint.h>
#include <stdlib.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

/* Asks for huge pages on the whole 2 MiB pages inside [p, p + bytes). */
static void advise_huge(void *p, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (p && bytes >= 2 * huge) {
        uintptr_t a = ((uintptr_t)p + huge - 1) & ~(huge - 1), b = ((uintptr_t)p + bytes) & ~(huge - 1);
        if (b > a) (void)madvise((void *)a, b - a, MADV_HUGEPAGE);
    }
#else
    (void)p;
    (void)bytes;
#endif
}

void *big_malloc(size_t bytes) {
    void *p = malloc(bytes);
    advise_huge(p, bytes);
    return p;
}

void *big_realloc(void *old, size_t bytes) {
    void *p = realloc(old, bytes);
    advise_huge(p, bytes);
    return p;
}
