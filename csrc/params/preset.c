/* preset.c - reading preset JSON (cJSON) into params and hosts. Every
 * refusal names the source, the line where it can be found, the key and
 * the reason. Format: see banyan.h "presets" and docs/presets.md. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "../core/error.h"
#include "../core/vec.h"
#include "params.h"

/* Presets are small; a larger text is a mistake, not a preset. */
#define PRESET_MAX_BYTES (4u << 20)
#define PRESET_MAX_DEPTH 16

int preset_line_at(const char *text, size_t len, size_t offset) {
    int line = 1;
    for (size_t i = 0; i < offset && i < len; i++) line += text[i] == '\n';
    return line;
}

/* Line of occurrence `nth` (0 = the first) of "key" (quoted), or 0.
 * cJSON keeps no positions, so keys are found again in the text. */
static int line_of_key(const char *text, size_t len, const char *key, int nth) {
    size_t k = strlen(key);
    for (size_t i = 0; i + k + 2 <= len; i++)
        if (text[i] == '"' && memcmp(text + i + 1, key, k) == 0 && text[i + k + 1] == '"' && nth-- == 0)
            return preset_line_at(text, len, i);
    return 0;
}

static void where_nth(char *buf, size_t n, const char *source, const char *text, size_t len, const char *key,
                      int nth) {
    int line = key ? line_of_key(text, len, key, nth) : 0;
    if (line) snprintf(buf, n, "%s:%d: ", source, line);
    else snprintf(buf, n, "%s: ", source);
}

static void where(char *buf, size_t n, const char *source, const char *text, size_t len, const char *key) {
    where_nth(buf, n, source, text, len, key, 0);
}

/* Length of the strict UTF-8 sequence at s[0..n-1] (RFC 3629: no overlong
 * forms, no surrogates, nothing past U+10FFFF, no NUL), or 0. */
static size_t utf8_sequence(const unsigned char *s, size_t n) {
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

/* One pass over the raw bytes before cJSON sees them: strict UTF-8, no
 * \u0000 escape (it would cut the C string cJSON makes short, so
 * "roots\u0000x" would read as "roots"), and brackets nested at most
 * PRESET_MAX_DEPTH deep, so cJSON never recurses far. */
static banyan_status prescan(const char *text, size_t len, const char *source, banyan_error *err) {
    const unsigned char *t = (const unsigned char *)text;
    int depth = 0, in_string = 0;
    for (size_t i = 0; i < len;) {
        size_t k = utf8_sequence(t + i, len - i);
        if (!k)
            return banyan_fail(err, BANYAN_E_PARSE, "%s:%d: byte %zu is not valid UTF-8 (0x%02x)", source,
                               preset_line_at(text, len, i), i, t[i]);
        unsigned char c = t[i];
        if (in_string) {
            if (c == '"') in_string = 0;
            else if (c == '\\' && i + 1 < len) {
                if (t[i + 1] == 'u' && i + 6 <= len && memcmp(t + i + 2, "0000", 4) == 0)
                    return banyan_fail(err, BANYAN_E_PARSE, "%s:%d: a \\u0000 escape is not allowed in a preset",
                                       source, preset_line_at(text, len, i));
                k = 2; /* skip the escaped character */
            }
        } else if (c == '"') {
            in_string = 1;
        } else if (c == '[' || c == '{') {
            if (++depth > PRESET_MAX_DEPTH)
                return banyan_fail(err, BANYAN_E_PARSE, "%s:%d: nesting deeper than %d levels", source,
                                   preset_line_at(text, len, i), PRESET_MAX_DEPTH);
        } else if (c == ']' || c == '}') {
            depth--;
        }
        i += k;
    }
    return BANYAN_OK;
}

/* c's key names an earlier member of its object too: a preset must not
 * say two things. Callers refuse unknown keys first, so the earlier
 * members are few and distinct and this stays cheap. */
static int given_before(const cJSON *obj, const cJSON *c) {
    int n = 0;
    for (const cJSON *d = obj->child; d && d != c; d = d->next) n += strcmp(d->string, c->string) == 0;
    return n; /* how many times: the line to name is that occurrence's */
}

/* cJSON 1.7 writes a file-level error position on every parse: serialise
 * parses so that concurrent calls on distinct texts stay race-free. */
static pthread_mutex_t json_lock = PTHREAD_MUTEX_INITIALIZER;

banyan_status preset_parse(const char *text, size_t len, const char *source, cJSON **root, banyan_error *err) {
    *root = NULL;
    if (!source) source = "<preset>";
    if (!text) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s: text is NULL", source);
    if (len == 0) return banyan_fail(err, BANYAN_E_PARSE, "%s: the file is empty; a preset is a JSON object", source);
    if (len > PRESET_MAX_BYTES)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: %zu bytes is over the %u-byte preset limit", source, len,
                           PRESET_MAX_BYTES);
    banyan_status s = prescan(text, len, source, err);
    if (s) return s;
    const char *end = NULL;
    pthread_mutex_lock(&json_lock);
    cJSON *j = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    pthread_mutex_unlock(&json_lock);
    size_t off = end && end >= text && end <= text + len ? (size_t)(end - text) : len;
    if (!j)
        return banyan_fail(err, BANYAN_E_PARSE, "%s:%d: malformed JSON (truncated file or syntax error)", source,
                           preset_line_at(text, len, off));
    while (off < len && (text[off] == ' ' || text[off] == '\t' || text[off] == '\n' || text[off] == '\r')) off++;
    if (off < len) {
        cJSON_Delete(j);
        return banyan_fail(err, BANYAN_E_PARSE, "%s:%d: text after the JSON object", source,
                           preset_line_at(text, len, off));
    }
    if (!cJSON_IsObject(j)) {
        cJSON_Delete(j);
        return banyan_fail(err, BANYAN_E_TYPE, "%s:1: a preset must be a JSON object", source);
    }
    static const char *const known[] = {"generator", "schema", "description", "params", "hosts", "name", "thumbnail", "segments", "trunk"};
    char w[300];
    for (cJSON *c = j->child; c; c = c->next) {
        int ok = 0;
        for (size_t k = 0; k < sizeof known / sizeof known[0]; k++) ok |= strcmp(c->string, known[k]) == 0;
        int twice = ok ? given_before(j, c) : 0;
        if (!ok || twice) {
            where_nth(w, sizeof w, source, text, len, c->string, twice);
            if (ok)
                s = banyan_fail(err, BANYAN_E_PARSE, "%stop-level key '%s' is given twice", w, c->string);
            else
                s = banyan_fail(err, BANYAN_E_UNKNOWN_KEY,
                                "%sunknown top-level key '%s' (expected generator, schema, description, params, "
                                "hosts, name, thumbnail, segments, trunk)", w, c->string);
            cJSON_Delete(j);
            return s;
        }
    }
    cJSON *schema = cJSON_GetObjectItemCaseSensitive(j, "schema");
    if (schema && (!cJSON_IsNumber(schema) || schema->valuedouble != BANYAN_PRESET_SCHEMA)) {
        where(w, sizeof w, source, text, len, "schema");
        cJSON_Delete(j);
        return banyan_fail(err, BANYAN_E_RANGE, "%sschema must be %d", w, BANYAN_PRESET_SCHEMA);
    }
    *root = j;
    return BANYAN_OK;
}

/* Numbers of a JSON number or array of numbers into out[0..cap-1]. */
static int numbers(const cJSON *v, double *out, int cap) {
    if (cJSON_IsNumber(v)) { out[0] = v->valuedouble; return 1; }
    if (!cJSON_IsArray(v)) return -1;
    int n = 0;
    for (const cJSON *c = v->child; c; c = c->next) {
        if (!cJSON_IsNumber(c) || n >= cap) return -1;
        out[n++] = c->valuedouble;
    }
    return n;
}

banyan_status banyan_preset_apply(banyan_generator g, void *params, const char *text, size_t length,
                                  const char *source, banyan_error *err) {
    if (!params) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    if (!banyan_generator_name(g)) return banyan_fail(err, BANYAN_E_INVALID_ARG, "generator %d is unknown", (int)g);
    if (!source) source = "<preset>";
    cJSON *j;
    banyan_status s = preset_parse(text, length, source, &j, err);
    if (s) return s;
    char w[300];
    const cJSON *gen = cJSON_GetObjectItemCaseSensitive(j, "generator");
    if (!cJSON_IsString(gen) || strcmp(gen->valuestring, banyan_generator_name(g)) != 0) {
        where(w, sizeof w, source, text, length, "generator");
        s = banyan_fail(err, gen ? BANYAN_E_TYPE : BANYAN_E_PARSE, "%sgenerator must be \"%s\"%s%s", w,
                        banyan_generator_name(g), cJSON_IsString(gen) ? ", not " : "",
                        cJSON_IsString(gen) ? gen->valuestring : "");
        goto done;
    }
    const cJSON *ps = cJSON_GetObjectItemCaseSensitive(j, "params");
    if (ps && !cJSON_IsObject(ps)) {
        where(w, sizeof w, source, text, length, "params");
        s = banyan_fail(err, BANYAN_E_TYPE, "%sparams must be an object", w);
        goto done;
    }
    /* "<source>:<line>: " of the key, looked up only on failure (it scans
     * the text). */
#define W() (where(w, sizeof w, source, text, length, c->string), w)
    for (const cJSON *c = ps ? ps->child : NULL; c; c = c->next) {
        const banyan_param_info *info = banyan_param_find(g, c->string);
        if (!info) {
            s = banyan_fail(err, BANYAN_E_UNKNOWN_KEY, "%sunknown %s parameter '%s'", W(), banyan_generator_name(g),
                            c->string);
            goto done;
        }
        int twice = given_before(ps, c);
        if (twice) {
            where_nth(w, sizeof w, source, text, length, c->string, twice);
            s = banyan_fail(err, BANYAN_E_PARSE, "%sparameter '%s' is given twice", w, c->string);
            goto done;
        }
        double vals[4];
        int n = -1;
        if (info->type == BANYAN_PT_BOOL) {
            if (cJSON_IsBool(c)) { vals[0] = cJSON_IsTrue(c) ? 1 : 0; n = 1; }
        } else if (info->type == BANYAN_PT_ENUM) {
            if (cJSON_IsString(c)) {
                int idx = param_enum_index(info->choices, c->valuestring, strlen(c->valuestring));
                if (idx < 0) {
                    s = banyan_fail(err, BANYAN_E_RANGE, "%s%s = \"%s\" must be one of %s", W(), c->string,
                                    c->valuestring, info->choices);
                    goto done;
                }
                vals[0] = idx;
                n = 1;
            }
        } else if (info->type == BANYAN_PT_SEED) {
            if (cJSON_IsNumber(c) && c->valuedouble >= 0 && c->valuedouble <= 9007199254740992.0) {
                vals[0] = c->valuedouble;
                n = 1;
            } else if (cJSON_IsString(c)) {
                s = banyan_param_set_text(g, params, c->string, c->valuestring, err);
                if (s) {
                    banyan_error_prefix(err, W());
                    goto done;
                }
                continue;
            }
        } else {
            n = numbers(c, vals, 4);
        }
        if (n < 0) {
            static const char *const tn[] = {"a number", "a whole number", "true or false", "a name", "[x, y, z]",
                                             "[r, g, b] or [r, g, b, a]", "a whole number >= 0"};
            s = banyan_fail(err, BANYAN_E_TYPE, "%s%s must be %s", W(), c->string, tn[info->type]);
            goto done;
        }
        s = param_assign(info, params, vals, n, "", err);
        if (s) {
            banyan_error_prefix(err, W());
            goto done;
        }
    }
#undef W
    banyan_error_clear(err);
done:
    cJSON_Delete(j);
    return s;
}

static banyan_status read_box(const cJSON *h, uint32_t i, const char *w, banyan_box *out, banyan_error *err) {
    if (!cJSON_IsObject(h)) return banyan_fail(err, BANYAN_E_TYPE, "%shosts[%u] must be an object", w, i);
    double c[3] = {0, 0, 0}, half[3], rot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    int have_half = 0, have_rot = 0;
    for (const cJSON *k = h->child; k; k = k->next) {
        if (given_before(h, k))
            return banyan_fail(err, BANYAN_E_PARSE, "%shosts[%u].%s is given twice", w, i, k->string);
        double v[9];
        int n = -1;
        if (cJSON_IsArray(k)) {
            n = 0;
            for (const cJSON *x = k->child; x && n >= 0; x = x->next) {
                if (!cJSON_IsNumber(x) || n >= 9) n = -1;
                else v[n++] = x->valuedouble;
            }
        }
        if (strcmp(k->string, "center") == 0 && n == 3) memcpy(c, v, sizeof c);
        else if (strcmp(k->string, "half") == 0 && n == 3) { memcpy(half, v, sizeof half); have_half = 1; }
        else if (strcmp(k->string, "rotation") == 0 && n == 9 && !have_rot) { memcpy(rot, v, sizeof rot); have_rot = 1; }
        else if (strcmp(k->string, "rotation_euler_deg") == 0 && n == 3 && !have_rot) {
            /* Blender's XYZ Euler: R = Rz * Ry * Rx. */
            m3 rx = m3_rotation(v3_make(1, 0, 0), deg2rad(v[0]));
            m3 ry = m3_rotation(v3_make(0, 1, 0), deg2rad(v[1]));
            m3 rz = m3_rotation(v3_make(0, 0, 1), deg2rad(v[2]));
            m3 a = m3_mul(&rz, &ry), r = m3_mul(&a, &rx);
            memcpy(rot, r.m, sizeof rot);
            have_rot = 1;
        } else if (strcmp(k->string, "name") == 0 && cJSON_IsString(k)) {
        } else
            return banyan_fail(err, BANYAN_E_TYPE,
                               "%shosts[%u].%s is unknown or malformed (keys: center [3], half [3], rotation [9] or "
                               "rotation_euler_deg [3], name)", w, i, k->string);
    }
    if (!have_half) return banyan_fail(err, BANYAN_E_TYPE, "%shosts[%u] needs \"half\": [hx, hy, hz]", w, i);
    memcpy(out->center, c, sizeof c);
    memcpy(out->half, half, sizeof half);
    memcpy(out->rotation, rot, sizeof rot);
    banyan_status s = banyan_box_validate(out, i, err);
    if (s) banyan_error_prefix(err, w);
    return s;
}

banyan_status banyan_preset_hosts(const char *text, size_t length, const char *source, banyan_box *out, uint32_t cap,
                                  uint32_t *count, banyan_error *err) {
    if (!count) return banyan_fail(err, BANYAN_E_INVALID_ARG, "count is NULL");
    *count = 0;
    if (!out && cap) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL but cap = %u", cap);
    if (!source) source = "<preset>";
    cJSON *j;
    banyan_status s = preset_parse(text, length, source, &j, err);
    if (s) return s;
    const cJSON *hosts = cJSON_GetObjectItemCaseSensitive(j, "hosts");
    char w[300];
    where(w, sizeof w, source, text, length, "hosts");
    if (hosts && !cJSON_IsArray(hosts)) {
        s = banyan_fail(err, BANYAN_E_TYPE, "%shosts must be an array of boxes", w);
    } else {
        uint32_t n = (uint32_t)cJSON_GetArraySize(hosts);
        if (n > cap) s = banyan_fail(err, BANYAN_E_RANGE, "%s%u hosts is more than the %u allowed", w, n, cap);
        uint32_t i = 0;
        for (const cJSON *h = hosts ? hosts->child : NULL; h && !s; h = h->next, i++) s = read_box(h, i, w, &out[i], err);
        if (!s) {
            *count = n;
            banyan_error_clear(err);
        }
    }
    cJSON_Delete(j);
    return s;
}
