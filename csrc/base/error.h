/* error.h - filling banyan_error and small input checks shared by every
 * entry point, so messages read the same everywhere. */
#ifndef BANYAN_ERROR_H
#define BANYAN_ERROR_H

#include "banyan.h"

#if defined(__MINGW32__) /* mingw's C99 printf (__USE_MINGW_ANSI_STDIO), not msvcrt's */
#  define BANYAN_PRINTF(a, b) __attribute__((format(gnu_printf, a, b)))
#elif defined(__GNUC__)
#  define BANYAN_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#  define BANYAN_PRINTF(a, b)
#endif

#ifdef __cplusplus
extern "C" { /* the C++ shims (csrc/gltf) report through these too */
#endif

/* Fills err (when non-NULL) and returns code. */
/* Length of the strict UTF-8 sequence at s[0 .. n-1] (RFC 3629: no
 * overlong forms, no surrogates, nothing past U+10FFFF, no NUL), or 0. */
size_t banyan_utf8_sequence(const unsigned char *s, size_t n);

banyan_status banyan_fail(banyan_error *err, banyan_status code, const char *fmt, ...) BANYAN_PRINTF(3, 4);
/* Puts `prefix` (e.g. "file.json:3: ") before err's message, truncating. */
void banyan_error_prefix(banyan_error *err, const char *prefix);
/* Clears err to BANYAN_OK / "". */
void banyan_error_clear(banyan_error *err);

/* "name = value must be within [lo, hi] unit": finite and in range. */
banyan_status banyan_check_range(banyan_error *err, const char *name, double v, double lo, double hi,
                                 const char *unit);
banyan_status banyan_check_int(banyan_error *err, const char *name, long long v, long long lo, long long hi);

#ifdef __cplusplus
}
#endif

/* Guard for out-parameters: checks out != NULL and sets *out = NULL. */
#define BANYAN_CHECK_OUT(out, err)                                                              \
    do {                                                                                        \
        if (!(out)) return banyan_fail((err), BANYAN_E_INVALID_ARG, "out is NULL");           \
        *(out) = NULL;                                                                          \
    } while (0)

#endif
