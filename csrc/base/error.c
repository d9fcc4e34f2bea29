#include "error.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

size_t banyan_utf8_sequence(const unsigned char *s, size_t n) {
    unsigned char c = s[0];
    if (c == 0) return 0;
    if (c < 0x80) return 1;
    size_t len;
    unsigned char lo = 0x80, hi = 0xBF; /* range of the second byte */
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        len = 3;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        len = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
    } else
        return 0;
    if (len > n || s[1] < lo || s[1] > hi) return 0;
    for (size_t k = 2; k < len; k++)
        if ((s[k] & 0xC0) != 0x80) return 0;
    return len;
}

/* Length of the UTF-8 sequence at s (n bytes left) that a terminal shows
 * as text, or 0 for a byte to escape: C0 controls, DEL, the C1 controls
 * U+0080 .. U+009F (ESC and CSI start terminal commands) and anything
 * that is not strict UTF-8 (a path may hold any bytes). */
static size_t printable_sequence(const unsigned char *s, size_t n) {
    if (s[0] < 0x20 || s[0] == 0x7F) return 0;
    if (s[0] == 0xC2 && n > 1 && s[1] < 0xA0) return 0;
    return banyan_utf8_sequence(s, n);
}

/* Copies src (NUL-terminated) into dst[0 .. cap - 1] (cap > 0) with every
 * byte a terminal would act on written as \xNN, whole sequences and
 * escapes only, NUL-terminated. Returns the bytes written. Every message
 * goes through here, so a path or name from a file never reaches a
 * terminal raw. */
static size_t copy_escaped(char *dst, size_t cap, const char *src) {
    const unsigned char *s = (const unsigned char *)src;
    size_t n = strlen(src), o = 0;
    for (size_t i = 0; i < n;) {
        size_t k = printable_sequence(s + i, n - i);
        if (k) {
            if (o + k >= cap) break;
            memcpy(dst + o, s + i, k);
            o += k, i += k;
        } else {
            if (o + 4 >= cap) break;
            static const char hex[] = "0123456789abcdef";
            dst[o++] = '\\', dst[o++] = 'x', dst[o++] = hex[s[i] >> 4], dst[o++] = hex[s[i] & 15];
            i++;
        }
    }
    dst[o] = '\0';
    return o;
}

/* Fits the NUL-terminated s (n bytes) into dst[0 .. cap - 1]: whole when
 * it fits, else its first third, "...", and its end, cut between UTF-8
 * sequences. Messages put where first and the cause last, and a long path
 * in the middle gives up its own middle. */
static void fit_middle(char *dst, size_t cap, const char *s, size_t n) {
    if (n < cap) {
        memcpy(dst, s, n + 1);
        return;
    }
    size_t head = (cap - 4) / 3, tail = cap - 4 - head;
    while (head > 0 && ((unsigned char)s[head] & 0xC0) == 0x80) head--;
    while (tail > 0 && ((unsigned char)s[n - tail] & 0xC0) == 0x80) tail--;
    memcpy(dst, s, head);
    memcpy(dst + head, "...", 3);
    memcpy(dst + head + 3, s + n - tail, tail);
    dst[head + 3 + tail] = '\0';
}

banyan_status banyan_fail(banyan_error *err, banyan_status code, const char *fmt, ...) {
    if (err) {
        err->code = (int32_t)code;
        char raw[4608], esc[4608]; /* room for a PATH_MAX path and its cause */
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(raw, sizeof raw, fmt, ap);
        va_end(ap);
        size_t n = copy_escaped(esc, sizeof esc, raw);
        fit_middle(err->message, sizeof err->message, esc, n);
    }
    return code;
}

void banyan_error_clear(banyan_error *err) {
    if (err) {
        err->code = BANYAN_OK;
        err->message[0] = '\0';
    }
}

banyan_status banyan_check_range(banyan_error *err, const char *name, double v, double lo, double hi,
                                 const char *unit) {
    if (isfinite(v) && v >= lo && v <= hi) return BANYAN_OK;
    return banyan_fail(err, BANYAN_E_RANGE, "%s = %g must be within [%g, %g]%s%s", name, v, lo, hi,
                       unit && *unit ? " " : "", unit ? unit : "");
}

banyan_status banyan_check_int(banyan_error *err, const char *name, long long v, long long lo, long long hi) {
    if (v >= lo && v <= hi) return BANYAN_OK;
    return banyan_fail(err, BANYAN_E_RANGE, "%s = %lld must be within [%lld, %lld]", name, v, lo, hi);
}

const char *banyan_status_name(banyan_status s) {
    static const char *const names[] = {
        "BANYAN_OK",         "BANYAN_E_INVALID_ARG", "BANYAN_E_RANGE",       "BANYAN_E_NO_HOSTS",
        "BANYAN_E_BAD_HOST", "BANYAN_E_START_INSIDE", "BANYAN_E_START_FAR",  "BANYAN_E_LIMIT",
        "BANYAN_E_NOMEM",    "BANYAN_E_IO",          "BANYAN_E_PARSE",       "BANYAN_E_UNKNOWN_KEY",
        "BANYAN_E_TYPE",     "BANYAN_E_UNSUPPORTED", "BANYAN_E_INTERNAL",    "BANYAN_E_CANCELLED"};
    if ((unsigned)s < sizeof names / sizeof names[0]) return names[s];
    return "BANYAN_E_UNKNOWN_STATUS";
}

void banyan_error_prefix(banyan_error *err, const char *prefix) {
    if (!err || !prefix) return;
    enum { CAP = sizeof err->message, KEEP = 72 };
    char msg[CAP], pre[CAP];
    memcpy(msg, err->message, CAP);
    msg[CAP - 1] = '\0';
    size_t m = strlen(msg), p = copy_escaped(pre, CAP, prefix);
    /* The message (the cause) keeps its room: a long prefix (where it
     * happened) gives up its middle first, down to KEEP bytes. */
    if (p + m > CAP - 1 && p > KEEP) {
        size_t room = CAP - 1 > m + KEEP ? CAP - 1 - m : KEEP;
        if (room < p) {
            size_t tail = (room - 3) / 2, head = room - 3 - tail;
            while (head > 0 && ((unsigned char)pre[head] & 0xC0) == 0x80) head--; /* whole UTF-8 sequences */
            while (tail > 0 && ((unsigned char)pre[p - tail] & 0xC0) == 0x80) tail--;
            memmove(pre + head + 3, pre + p - tail, tail);
            memcpy(pre + head, "...", 3);
            p = head + 3 + tail;
            pre[p] = '\0';
        }
    }
    if (p + m > CAP - 1) {
        m = CAP - 1 - p;
        while (m > 0 && ((unsigned char)msg[m] & 0xC0) == 0x80) m--;
    }
    memcpy(err->message, pre, p);
    memcpy(err->message + p, msg, m);
    err->message[p + m] = '\0';
}
