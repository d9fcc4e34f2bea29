#include "error.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

banyan_status banyan_fail(banyan_error *err, banyan_status code, const char *fmt, ...) {
    if (err) {
        err->code = (int32_t)code;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
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
    size_t cap = sizeof err->message - 1, p = strlen(prefix), m = strlen(err->message);
    if (p > cap) p = cap;
    if (p + m > cap) m = cap - p;
    memmove(err->message + p, err->message, m);
    memcpy(err->message, prefix, p);
    err->message[p + m] = '\0';
}
