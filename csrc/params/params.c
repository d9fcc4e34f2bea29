/* Generic set/check over parameter tables; see banyan.h. */
#include "params.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/error.h"
#include "../base/numparse.h"

static const char *const generator_names[BANYAN_GEN_COUNT] = {"roots", "keyaki", "avenue", "ivy", "segments"};

const char *banyan_generator_name(banyan_generator g) {
    return (unsigned)g < BANYAN_GEN_COUNT ? generator_names[g] : NULL;
}

int32_t banyan_generator_from_name(const char *name) {
    if (!name) return -1;
    for (int i = 0; i < BANYAN_GEN_COUNT; i++)
        if (strcmp(name, generator_names[i]) == 0) return i;
    return -1;
}

int32_t banyan_param_count(banyan_generator g) { return param_table_get(g).count; }

const banyan_param_info *banyan_param_get(banyan_generator g, int32_t i) {
    param_table t = param_table_get(g);
    return i >= 0 && i < t.count ? &t.rows[i] : NULL;
}

const banyan_param_info *banyan_param_find(banyan_generator g, const char *name) {
    if (!name) return NULL;
    param_table t = param_table_get(g);
    for (int32_t i = 0; i < t.count; i++)
        if (strcmp(t.rows[i].name, name) == 0) return &t.rows[i];
    return NULL;
}

int param_enum_index(const char *choices, const char *name, size_t len) {
    int idx = 0;
    const char *p = choices;
    while (p && *p) {
        const char *bar = strchr(p, '|');
        size_t n = bar ? (size_t)(bar - p) : strlen(p);
        if (n == len && strncmp(p, name, len) == 0) return idx;
        idx++;
        p = bar ? bar + 1 : NULL;
    }
    return -1;
}

static int enum_count(const char *choices) {
    int n = 1;
    for (const char *p = choices; p && *p; p++) n += *p == '|';
    return choices ? n : 0;
}

static int components(int type) {
    switch (type) {
    case BANYAN_PT_VEC3: return 3;
    case BANYAN_PT_COLOR: return 4;
    default: return 1;
    }
}

banyan_status param_assign(const banyan_param_info *info, void *params, const double *vals, int n,
                           const char *where, banyan_error *err) {
    char *field = (char *)params + info->offset;
    int want = components(info->type);
    if (info->type == BANYAN_PT_COLOR && n == 3) {
        /* r,g,b: alpha 1. */
    } else if (n != want) {
        return banyan_fail(err, BANYAN_E_TYPE, "%s%s needs %d number%s, got %d", where, info->name, want,
                           want > 1 ? "s" : "", n);
    }
    for (int i = 0; i < n; i++) {
        double v = vals[i];
        int integral = info->type == BANYAN_PT_INT || info->type == BANYAN_PT_BOOL || info->type == BANYAN_PT_ENUM ||
                       info->type == BANYAN_PT_SEED;
        if (!isfinite(v))
            return banyan_fail(err, BANYAN_E_RANGE, "%s%s = %g must be finite, within [%g, %g]%s%s", where,
                               info->name, v, info->min, info->max, *info->unit ? " " : "", info->unit);
        if (integral && v != floor(v))
            return banyan_fail(err, BANYAN_E_TYPE, "%s%s = %g must be a whole number", where, info->name, v);
        double lo = info->min, hi = info->max;
        if (info->type == BANYAN_PT_ENUM) {
            lo = 0;
            hi = enum_count(info->choices) - 1;
        }
        if (v < lo || v > hi) {
            /* Whole numbers in full: 2147483647, not 2.14748e+09. */
            char vt[40];
            snprintf(vt, sizeof vt, integral && fabs(v) < 1e18 ? "%.0f" : "%g", v);
            if (info->type == BANYAN_PT_ENUM)
                return banyan_fail(err, BANYAN_E_RANGE, "%s%s = %s must be one of %s", where, info->name, vt,
                                   info->choices);
            return banyan_fail(err, BANYAN_E_RANGE, "%s%s = %s must be within [%g, %g]%s%s", where, info->name, vt,
                               lo, hi, *info->unit ? " " : "", info->unit);
        }
    }
    switch (info->type) {
    case BANYAN_PT_DOUBLE: memcpy(field, &vals[0], sizeof(double)); break;
    case BANYAN_PT_INT:
    case BANYAN_PT_BOOL:
    case BANYAN_PT_ENUM: {
        int32_t x = (int32_t)vals[0];
        memcpy(field, &x, sizeof x);
        break;
    }
    case BANYAN_PT_SEED: {
        uint64_t x = (uint64_t)vals[0];
        memcpy(field, &x, sizeof x);
        break;
    }
    case BANYAN_PT_VEC3: memcpy(field, vals, 3 * sizeof(double)); break;
    case BANYAN_PT_COLOR: {
        double c[4] = {vals[0], vals[1], vals[2], n == 4 ? vals[3] : 1.0};
        memcpy(field, c, sizeof c);
        break;
    }
    default: return banyan_fail(err, BANYAN_E_INTERNAL, "%s has unknown type %d", info->name, info->type);
    }
    return BANYAN_OK;
}

/* [+-]nan, [+-]inf or [+-]infinity (any case) at s: its length and value,
 * else 0. */
static size_t nonfinite_word(const char *s, double *out) {
    size_t i = s[0] == '+' || s[0] == '-';
    static const char *const words[] = {"infinity", "inf", "nan"};
    for (int w = 0; w < 3; w++) {
        size_t n = strlen(words[w]), k = 0;
        while (k < n && tolower((unsigned char)s[i + k]) == words[w][k]) k++;
        if (k < n) continue;
        *out = w < 2 ? (s[0] == '-' ? -INFINITY : INFINITY) : NAN;
        return i + n;
    }
    return 0;
}

static banyan_status unknown_key(banyan_generator g, const char *key, banyan_error *err) {
    return banyan_fail(err, BANYAN_E_UNKNOWN_KEY, "unknown %s parameter '%s' (see `banyan %s --list`)",
                       banyan_generator_name(g) ? banyan_generator_name(g) : "?", key,
                       banyan_generator_name(g) ? banyan_generator_name(g) : "?");
}

banyan_status banyan_param_set_text(banyan_generator g, void *params, const char *key, const char *value,
                                    banyan_error *err) {
    if (!params || !key || !value) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params, key and value must not be NULL");
    if (!banyan_generator_name(g)) return banyan_fail(err, BANYAN_E_INVALID_ARG, "generator %d is unknown", (int)g);
    const banyan_param_info *info = banyan_param_find(g, key);
    if (!info) return unknown_key(g, key, err);
    double vals[4];
    int n = 0;
    if (info->type == BANYAN_PT_BOOL) {
        static const char *const t[] = {"true", "1", "on", "yes"}, *const f[] = {"false", "0", "off", "no"};
        for (int i = 0; i < 4; i++) {
            if (strcmp(value, t[i]) == 0) { vals[0] = 1; n = 1; }
            if (strcmp(value, f[i]) == 0) { vals[0] = 0; n = 1; }
        }
        if (!n) return banyan_fail(err, BANYAN_E_TYPE, "%s = '%s' must be true or false", key, value);
    } else if (info->type == BANYAN_PT_ENUM && !isdigit((unsigned char)value[0])) {
        int idx = param_enum_index(info->choices, value, strlen(value));
        if (idx < 0) return banyan_fail(err, BANYAN_E_RANGE, "%s = '%s' must be one of %s", key, value, info->choices);
        vals[0] = idx;
        n = 1;
    } else if (info->type == BANYAN_PT_SEED) {
        uint64_t seed;
        if (!num_parse_u64(value, &seed))
            return banyan_fail(err, BANYAN_E_TYPE, "%s = '%s' must be a whole number in [0, 2^64-1] (digits only)",
                               key, value);
        memcpy((char *)params + info->offset, &seed, sizeof seed);
        return BANYAN_OK;
    } else {
        /* Decimal numbers in the C locale's spelling, comma separated
         * (spaces allowed after a comma); "nan" and "inf" are read so that
         * the range check can say the value must be finite. */
        const char *p = value;
        for (;;) {
            if (n >= 4) return banyan_fail(err, BANYAN_E_TYPE, "%s = '%s' has too many numbers", key, value);
            size_t len = num_scan_double(p, &vals[n]);
            if (!len) len = nonfinite_word(p, &vals[n]);
            if (!len)
                return banyan_fail(err, BANYAN_E_TYPE, "%s = '%s' is not a decimal number%s", key, value,
                                   components(info->type) > 1 ? " list like 1,2,3" : " like 0.5");
            n++;
            const char *end = p + len;
            if (*end == ',') {
                for (p = end + 1; *p == ' '; p++) {}
                continue;
            }
            if (*end) return banyan_fail(err, BANYAN_E_TYPE, "%s = '%s' has trailing text '%s'", key, value, end);
            break;
        }
    }
    return param_assign(info, params, vals, n, "", err);
}

banyan_status banyan_params_check(banyan_generator g, const void *params, banyan_error *err) {
    if (!params) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    if (!banyan_generator_name(g)) return banyan_fail(err, BANYAN_E_INVALID_ARG, "generator %d is unknown", (int)g);
    param_table t = param_table_get(g);
    for (int32_t i = 0; i < t.count; i++) {
        const banyan_param_info *info = &t.rows[i];
        const char *field = (const char *)params + info->offset;
        double vals[4];
        int n = components(info->type);
        switch (info->type) {
        case BANYAN_PT_DOUBLE: memcpy(vals, field, sizeof(double)); break;
        case BANYAN_PT_INT:
        case BANYAN_PT_BOOL:
        case BANYAN_PT_ENUM: {
            int32_t x;
            memcpy(&x, field, sizeof x);
            vals[0] = x;
            break;
        }
        case BANYAN_PT_SEED: continue; /* every value is valid */
        case BANYAN_PT_VEC3: memcpy(vals, field, 3 * sizeof(double)); break;
        case BANYAN_PT_COLOR: memcpy(vals, field, 4 * sizeof(double)); break;
        default: return banyan_fail(err, BANYAN_E_INTERNAL, "%s has unknown type %d", info->name, info->type);
        }
        /* Assign into a scratch copy: the same checks, nothing written. */
        unsigned char scratch[64];
        banyan_param_info shifted = *info;
        shifted.offset = 0;
        banyan_status s = param_assign(&shifted, scratch, vals, n, "", err);
        if (s) return s;
    }
    return BANYAN_OK;
}
