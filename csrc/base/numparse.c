/* Locale-free number parsing; see numparse.h. The grammar is checked
 * here; the conversion (correct rounding is hard) is strtod's, run in the
 * C locale for the call with uselocale, which changes the calling
 * thread's locale only, so other threads are not disturbed. */
#if !defined(_WIN32)
#  define _POSIX_C_SOURCE 200809L
#endif
#include "numparse.h"

#include <limits.h>
#include <locale.h>
#include <stdlib.h>
#include <string.h>
#if defined(__APPLE__)
#  include <xlocale.h>
#endif

static int digit(char c) { return c >= '0' && c <= '9'; }

/* Length of the number at s by the grammar of numparse.h, or 0. */
static size_t scan(const char *s) {
    size_t i = 0, whole = 0, frac = 0;
    if (s[i] == '+' || s[i] == '-') i++;
    while (digit(s[i])) i++, whole++;
    if (s[i] == '.') {
        i++;
        while (digit(s[i])) i++, frac++;
    }
    if (!whole && !frac) return 0;
    if (s[i] == 'e' || s[i] == 'E') {
        size_t e = i + 1, ed = 0;
        if (s[e] == '+' || s[e] == '-') e++;
        while (digit(s[e])) e++, ed++;
        if (ed) i = e; /* "1e" is the number 1 followed by "e" */
    }
    return i;
}

/* strtod of the n bytes at s (a number by scan()) in the C locale into
 * *out; 0 when there is no memory for it. */
static int convert(const char *s, size_t n, double *out) {
    char small[128], *buf = n < sizeof small ? small : malloc(n + 1);
    if (!buf) return 0;
    memcpy(buf, s, n);
    buf[n] = '\0';
#if defined(_WIN32)
    _locale_t c = _create_locale(LC_NUMERIC, "C");
    if (c) {
        *out = _strtod_l(buf, NULL, c);
        _free_locale(c);
    }
#else
    /* glibc hands out its static C locale for "C": nothing allocated. */
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c) {
        locale_t old = uselocale(c);
        *out = strtod(buf, NULL);
        uselocale(old);
        freelocale(c);
    }
#endif
    if (buf != small) free(buf);
    return c != NULL; /* no C locale (no memory): no number rather than a wrong one */
}

size_t num_scan_double(const char *s, double *out) {
    size_t n = s ? scan(s) : 0;
    return n && convert(s, n, out) ? n : 0;
}

int num_parse_double(const char *s, double *out) {
    double v;
    size_t n = num_scan_double(s, &v);
    if (!n || s[n]) return 0;
    *out = v;
    return 1;
}

/* Digits only, value within [0, limit]: 1 and *out, else 0. */
static int parse_digits(const char *s, uint64_t limit, uint64_t *out) {
    uint64_t v = 0;
    if (!digit(*s)) return 0;
    for (; *s; s++) {
        if (!digit(*s)) return 0;
        uint64_t d = (uint64_t)(*s - '0');
        if (v > (limit - d) / 10) return 0;
        v = v * 10 + d;
    }
    *out = v;
    return 1;
}

int num_parse_u64(const char *s, uint64_t *out) { return s && parse_digits(s, UINT64_MAX, out); }

int num_parse_int(const char *s, long long lo, long long hi, long long *out) {
    if (!s || lo > hi) return 0;
    int neg = s[0] == '-';
    if (neg && lo >= 0) return 0;
    uint64_t mag, limit = neg ? (uint64_t)0 - (uint64_t)lo : (hi < 0 ? 0 : (uint64_t)hi);
    if (!parse_digits(s + neg, limit, &mag)) return 0;
    long long v = neg ? (mag == (uint64_t)LLONG_MAX + 1 ? LLONG_MIN : -(long long)mag) : (long long)mag;
    if (v < lo || v > hi) return 0;
    *out = v;
    return 1;
}
