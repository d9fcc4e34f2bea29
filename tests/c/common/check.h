/* check.h - the tests' tiny harness: CHECK records a failure with its
 * line and goes on; check_done prints "N passed, N failed" and gives the
 * exit code. */
#ifndef BANYAN_CHECK_H
#define BANYAN_CHECK_H

#include <stdio.h>

static int check_passed, check_failed;

#define CHECK(cond, ...)                                                        \
    do {                                                                        \
        if (cond) check_passed++;                                               \
        else {                                                                  \
            check_failed++;                                                     \
            fprintf(stderr, "%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                       \
            fputc('\n', stderr);                                                \
        }                                                                       \
    } while (0)

/* Sanitizer builds run the same work several times slower: a time bound
 * on how long a stop takes once a budget is spent (the work between two
 * polls) is this much looser there. The budget itself is not scaled. */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define CHECK_SLACK 4.0
#else
#define CHECK_SLACK 1.0
#endif

static inline int check_done(const char *name) {
    printf("%s: %d passed, %d failed\n", name, check_passed, check_failed);
    return check_failed ? 1 : 0;
}

#endif
