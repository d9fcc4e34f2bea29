/* preset_read.c - the "segments" list and "trunk" line of a segments
 * preset (spec segments.md, "Composing a tree": a tree is a list of
 * segment inputs, for example from a preset). Read with cJSON; since cJSON
 * keeps no positions, a small scanner over the text finds the line of each
 * entry and field so that every refusal starts with "<source>:<line>:", as
 * the generic preset reader (csrc/params/preset.c) does. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "../base/error.h"
#include "../params/params.h"
#include "segment_core.h"

/* ---- positions in the JSON text (the text is known to be valid JSON) */

static size_t skip_ws(const char *t, size_t n, size_t i) {
    while (i < n && (t[i] == ' ' || t[i] == '\t' || t[i] == '\n' || t[i] == '\r')) i++;
    return i;
}

static size_t skip_string(const char *t, size_t n, size_t i) {
    for (i++; i < n && t[i] != '"'; i++)
        if (t[i] == '\\') i++;
    return i < n ? i + 1 : n;
}

static size_t skip_value(const char *t, size_t n, size_t i) {
    if (i >= n) return n;
    if (t[i] == '"') return skip_string(t, n, i);
    if (t[i] == '{' || t[i] == '[') {
        int depth = 0;
        while (i < n) {
            char c = t[i];
            if (c == '"') { i = skip_string(t, n, i); continue; }
            if (c == '{' || c == '[') depth++;
            if (c == '}' || c == ']') depth--;
            i++;
            if (depth == 0) return i;
        }
        return n;
    }
    while (i < n && t[i] != ',' && t[i] != '}' && t[i] != ']' && t[i] != ' ' && t[i] != '\n' && t[i] != '\t' &&
           t[i] != '\r')
        i++;
    return i;
}

/* Offset of the key `key` of the object starting at offset o, or n. */
static size_t key_offset(const char *t, size_t n, size_t o, const char *key) {
    size_t k = strlen(key), i = skip_ws(t, n, o);
    if (i >= n || t[i] != '{') return n;
    for (i++;;) {
        i = skip_ws(t, n, i);
        if (i >= n || t[i] != '"') return n;
        size_t ks = i, ke = skip_string(t, n, i);
        if (ke - ks == k + 2 && memcmp(t + ks + 1, key, k) == 0) return ks;
        i = skip_ws(t, n, ke);
        if (i < n && t[i] == ':') i++;
        i = skip_value(t, n, skip_ws(t, n, i));
        i = skip_ws(t, n, i);
        if (i < n && t[i] == ',') i++;
        else return n;
    }
}

/* Offset of the value after the key at offset k. */
static size_t value_after_key(const char *t, size_t n, size_t k) {
    size_t i = skip_ws(t, n, skip_string(t, n, k));
    if (i < n && t[i] == ':') i++;
    return skip_ws(t, n, i);
}

/* Offset of element `idx` of the array starting at offset a, or n. */
static size_t element_offset(const char *t, size_t n, size_t a, uint32_t idx) {
    size_t i = skip_ws(t, n, a);
    if (i >= n || t[i] != '[') return n;
    i++;
    for (uint32_t e = 0;; e++) {
        i = skip_ws(t, n, i);
        if (i >= n || t[i] == ']') return n;
        if (e == idx) return i;
        i = skip_ws(t, n, skip_value(t, n, i));
        if (i < n && t[i] == ',') i++;
        else return n;
    }
}

typedef struct reader {
    const char *t;
    size_t n;
    const char *source;
    size_t list;  /* offset of the segments array value, or n */
    size_t trunk; /* offset of the trunk value, or n */
} reader;

/* "<source>:<line>: " for entry i (field may be NULL), or the list's line. */
static void where_entry(const reader *r, uint32_t i, const char *field, char *buf, size_t cap) {
    size_t off = r->list < r->n ? element_offset(r->t, r->n, r->list, i) : r->n;
    if (off < r->n && field) {
        size_t f = key_offset(r->t, r->n, off, field);
        if (f < r->n) off = f;
    }
    if (off >= r->n) off = r->list;
    if (off < r->n) snprintf(buf, cap, "%s:%d: ", r->source, preset_line_at(r->t, r->n, off));
    else snprintf(buf, cap, "%s: ", r->source);
}

static int read_vec3(const cJSON *v, double out[3]) {
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3) return 0;
    int k = 0;
    for (const cJSON *c = v->child; c; c = c->next) {
        if (!cJSON_IsNumber(c)) return 0;
        out[k++] = c->valuedouble;
    }
    return 1;
}

static banyan_status read_entry(const reader *r, const cJSON *e, uint32_t i, banyan_segment_input *out,
                                banyan_error *err) {
    char w[300];
    if (!cJSON_IsObject(e)) {
        where_entry(r, i, NULL, w, sizeof w);
        return banyan_fail(err, BANYAN_E_TYPE,
                           "%ssegments[%u] must be an object {\"S\": [x,y,z], \"A\": [x,y,z], \"l\": .., \"n\": .., "
                           "\"s\": ..}", w, i);
    }
    static const char *const keys[5] = {"S", "A", "l", "n", "s"};
    /* The line is looked up only on failure: finding it scans the text. */
#define AT(field) (where_entry(r, i, (field), w, sizeof w), w)
    int seen[5] = {0, 0, 0, 0, 0};
    for (const cJSON *c = e->child; c; c = c->next) {
        int k = -1;
        for (int q = 0; q < 5; q++)
            if (strcmp(c->string, keys[q]) == 0) k = q;
        if (k < 0)
            return banyan_fail(err, BANYAN_E_UNKNOWN_KEY, "%ssegments[%u]: unknown key '%s' (keys: S, A, l, n, s)",
                               AT(c->string), i, c->string);
        if (seen[k]++)
            return banyan_fail(err, BANYAN_E_PARSE, "%ssegments[%u].%s is given twice", AT(c->string), i, keys[k]);
        if (k <= 1) {
            if (!read_vec3(c, k == 0 ? out->S : out->A))
                return banyan_fail(err, BANYAN_E_TYPE, "%ssegments[%u].%s must be [x, y, z] (3 numbers)",
                                   AT(c->string), i, keys[k]);
        } else if (!cJSON_IsNumber(c)) {
            return banyan_fail(err, BANYAN_E_TYPE, "%ssegments[%u].%s must be a %snumber", AT(c->string), i, keys[k],
                               k == 2 ? "" : "whole ");
        } else if (k == 2) {
            out->l = c->valuedouble;
        } else {
            double v = c->valuedouble;
            if (v != floor(v))
                return banyan_fail(err, BANYAN_E_TYPE, "%ssegments[%u].%s = %g must be a whole number",
                                   AT(c->string), i, keys[k], v);
            if (!(v >= -1e9 && v <= 1e9))
                return banyan_fail(err, BANYAN_E_RANGE, "%ssegments[%u].%s = %g must be within [0, %d]",
                                   AT(c->string), i, keys[k], v,
                                   k == 3 ? BANYAN_SEGMENT_MAX_TWIGS : BANYAN_SEGMENT_MAX_DEPTH);
            if (k == 3) out->n = (int32_t)v;
            else out->s = (int32_t)v;
        }
    }
#undef AT
    for (int q = 0; q < 5; q++)
        if (!seen[q]) {
            where_entry(r, i, NULL, w, sizeof w);
            return banyan_fail(err, BANYAN_E_PARSE, "%ssegments[%u] needs \"%s\" (every entry has S, A, l, n and s)", w,
                               i, keys[q]);
        }
    char prefix[40];
    snprintf(prefix, sizeof prefix, "segments[%u].", i);
    banyan_status s = seg_check_input(out, prefix, err);
    if (s) {
        /* Point at the field the message names: "segments[i].<field>". */
        char field[2] = {err ? err->message[strlen(prefix)] : 0, 0};
        where_entry(r, i, field[0] ? field : NULL, w, sizeof w);
        banyan_error_prefix(err, w);
    }
    return s;
}

static banyan_status read_trunk(const reader *r, const cJSON *tr, double trunk[6], banyan_error *err) {
    char w[300];
    if (r->trunk < r->n) snprintf(w, sizeof w, "%s:%d: ", r->source, preset_line_at(r->t, r->n, r->trunk));
    else snprintf(w, sizeof w, "%s: ", r->source);
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(tr, "start"), *b = cJSON_GetObjectItemCaseSensitive(tr, "end");
    double v[6];
    if (!cJSON_IsObject(tr) || cJSON_GetArraySize(tr) != 2 || !read_vec3(a, v) || !read_vec3(b, v + 3))
        return banyan_fail(err, BANYAN_E_TYPE, "%strunk must be {\"start\": [x, y, z], \"end\": [x, y, z]}", w);
    for (int c = 0; c < 6; c++)
        if (!isfinite(v[c]) || fabs(v[c]) > BANYAN_SEGMENT_MAX_COORD)
            return banyan_fail(err, BANYAN_E_RANGE, "%strunk.%s[%d] = %g must be within [-1e+12, 1e+12] m", w,
                               c < 3 ? "start" : "end", c % 3, v[c]);
    if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5])
        return banyan_fail(err, BANYAN_E_RANGE, "%strunk start and end must differ", w);
    if (trunk) memcpy(trunk, v, sizeof v);
    return BANYAN_OK;
}

banyan_status banyan_segments_preset_read(const char *text, size_t length, const char *source,
                                          banyan_segment_input *out, uint32_t cap, uint32_t *count, double trunk[6],
                                          int32_t *has_trunk, banyan_error *err) {
    if (count) *count = 0;
    if (has_trunk) *has_trunk = 0;
    if (!source) source = "<preset>";
    if (!text || !count) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s: text and count must not be NULL", source);
    if (!out && cap) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s: out is NULL but cap = %u", source, cap);
    cJSON *j;
    banyan_status s = preset_parse(text, length, source, &j, err);
    if (s) return s;
    reader r = {text, length, source, length, length};
    size_t k = key_offset(text, length, 0, "segments");
    if (k < length) r.list = value_after_key(text, length, k);
    k = key_offset(text, length, 0, "trunk");
    if (k < length) r.trunk = k;
    const cJSON *gen = cJSON_GetObjectItemCaseSensitive(j, "generator");
    if (gen && (!cJSON_IsString(gen) || strcmp(gen->valuestring, "segments") != 0)) {
        k = key_offset(text, length, 0, "generator");
        s = banyan_fail(err, BANYAN_E_TYPE, "%s:%d: generator must be \"segments\" for a segment list", source,
                        preset_line_at(text, length, k));
        goto done;
    }
    const cJSON *tr = cJSON_GetObjectItemCaseSensitive(j, "trunk");
    if (tr) {
        if ((s = read_trunk(&r, tr, trunk, err))) goto done;
        if (has_trunk) *has_trunk = 1;
    }
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(j, "segments");
    if (!list) goto done;
    if (!cJSON_IsArray(list)) {
        s = banyan_fail(err, BANYAN_E_TYPE, "%s:%d: segments must be an array of segment objects", source,
                        preset_line_at(text, length, r.list));
        goto done;
    }
    uint32_t n = (uint32_t)cJSON_GetArraySize(list);
    if (n == 0) { /* read as no list, it would grow the random demo tree */
        s = banyan_fail(err, BANYAN_E_RANGE, "%s:%d: segments is an empty list; give at least one segment or leave "
                        "the key out for the random tree of the params", source, preset_line_at(text, length, r.list));
        goto done;
    }
    if (n > BANYAN_SEGMENTS_MAX_COUNT) {
        s = banyan_fail(err, BANYAN_E_RANGE, "%s:%d: %u segments is more than the %u allowed", source,
                        preset_line_at(text, length, r.list), n, BANYAN_SEGMENTS_MAX_COUNT);
        goto done;
    }
    if (!out && cap == 0) {
        banyan_segment_input tmp;
        uint32_t i = 0;
        for (const cJSON *e = list->child; e && !s; e = e->next, i++) s = read_entry(&r, e, i, &tmp, err);
    } else {
        if (n > cap) {
            s = banyan_fail(err, BANYAN_E_RANGE, "%s:%d: %u segments is more than cap = %u", source,
                            preset_line_at(text, length, r.list), n, cap);
            goto done;
        }
        uint32_t i = 0;
        for (const cJSON *e = list->child; e && !s; e = e->next, i++) s = read_entry(&r, e, i, &out[i], err);
    }
    if (!s) *count = n;
done:
    cJSON_Delete(j);
    if (!s) banyan_error_clear(err);
    else if (has_trunk) *has_trunk = 0;
    return s;
}
