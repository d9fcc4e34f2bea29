/* big_alloc.c - malloc for large output arrays (big_alloc.h). */
#define _DEFAULT_SOURCE
#define _POSIX_C_SOURCE 200809L
#include "big_alloc.h"

#include <stdint.h>
#include <stdlib.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#if defined(__linux__) && defined(MADV_HUGEPAGE)
#define HUGE_PAGE ((size_t)2 << 20)
#define BIG_MIN (2 * HUGE_PAGE)

/* Asks for huge pages on the whole 2 MiB pages inside [p, p + bytes). */
static void advise_huge(void *p, size_t bytes) {
    if (p && bytes >= BIG_MIN) {
        uintptr_t a = ((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
        uintptr_t b = ((uintptr_t)p + bytes) & ~(uintptr_t)(HUGE_PAGE - 1);
        if (b > a) (void)madvise((void *)a, b - a, MADV_HUGEPAGE);
    }
}
#endif

void *big_malloc(size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= BIG_MIN && bytes <= SIZE_MAX / 2) {
        /* Rounded up to whole huge pages when that adds at most a
         * quarter (the last page is written too, so all of it becomes
         * resident); otherwise the tail past the last whole huge page
         * stays 4 KiB pages (a 4.1 MiB array would cost 6 MiB). */
        size_t whole = (bytes + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
        if ((whole - bytes) * 4 <= bytes) bytes = whole;
        void *p = NULL;
        if (posix_memalign(&p, HUGE_PAGE, bytes)) return NULL;
        advise_huge(p, bytes);
        return p;
    }
#endif
    return malloc(bytes);
}

void *big_realloc(void *old, size_t bytes) {
    if (!old) return big_malloc(bytes);
    void *p = realloc(old, bytes);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    advise_huge(p, bytes);
#endif
    return p;
}
