/* preset.c - reading preset JSON (cJSON) into params and hosts: boxes
 * (banyan_preset_hosts) or a host set of boxes and .glb meshes
 * (banyan_preset_host_set; the files are read by gltf/gltf_reader.cpp).
 * Every refusal names the source, the line where it can be found, the key
 * and the reason. Format: see banyan.h "presets" and docs/formats.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "../base/error.h"
#include "../base/platform.h"
#include "../base/progress.h"
#include "../base/vec.h"
#include "../gltf/gltf_reader.h"
#include "params.h"

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

/* One pass over the raw bytes before cJSON sees them: strict UTF-8, no
 * \u0000 escape (it would cut the C string cJSON makes short, so
 * "roots\u0000x" would read as "roots"), and brackets nested at most
 * PRESET_MAX_DEPTH deep, so cJSON never recurses far. */
static banyan_status prescan(const char *text, size_t len, const char *source, banyan_error *err) {
    const unsigned char *t = (const unsigned char *)text;
    int depth = 0, in_string = 0;
    for (size_t i = 0; i < len;) {
        size_t k = banyan_utf8_sequence(t + i, len - i);
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
static plat_lock json_lock = PLAT_LOCK_INIT;

cJSON *preset_json_parse(const char *text, size_t len, const char **end) {
    const char *e = NULL;
    plat_lock_take(&json_lock);
    cJSON *j = cJSON_ParseWithLengthOpts(text, len, &e, 0);
    plat_lock_give(&json_lock);
    if (end) *end = e;
    return j;
}

banyan_status preset_parse(const char *text, size_t len, const char *source, cJSON **root, banyan_error *err) {
    *root = NULL;
    if (!source) source = "<preset>";
    if (!text) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s: text is NULL", source);
    if (len == 0) return banyan_fail(err, BANYAN_E_PARSE, "%s: the file is empty; a preset is a JSON object", source);
    if (len > BANYAN_PRESET_MAX_BYTES)
        return banyan_fail(err, BANYAN_E_PARSE, "%s: %zu bytes is over the %u-byte preset limit", source, len,
                           BANYAN_PRESET_MAX_BYTES);
    banyan_status s = prescan(text, len, source, err);
    if (s) return s;
    const char *end = NULL;
    cJSON *j = preset_json_parse(text, len, &end);
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

/* Numbers of a JSON array into v[0..cap-1]: how many, or -1 when k is not
 * an array of at most cap numbers. */
static int number_array(const cJSON *k, double *v, int cap) { return cJSON_IsArray(k) ? numbers(k, v, cap) : -1; }

/* Blender's XYZ Euler in degrees: R = Rz * Ry * Rx, row-major. */
static void euler_deg(const double *v, double rot[9]) {
    m3 rx = m3_rotation(v3_make(1, 0, 0), deg2rad(v[0]));
    m3 ry = m3_rotation(v3_make(0, 1, 0), deg2rad(v[1]));
    m3 rz = m3_rotation(v3_make(0, 0, 1), deg2rad(v[2]));
    m3 a = m3_mul(&rz, &ry), r = m3_mul(&a, &rx);
    memcpy(rot, r.m, sizeof r.m);
}

static banyan_status read_box(const cJSON *h, uint32_t i, banyan_box *out, banyan_error *err) {
    if (!cJSON_IsObject(h)) return banyan_fail(err, BANYAN_E_TYPE, "hosts[%u] must be an object", i);
    double c[3] = {0, 0, 0}, half[3], rot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    int have_half = 0, have_rot = 0;
    for (const cJSON *k = h->child; k; k = k->next) {
        if (given_before(h, k))
            return banyan_fail(err, BANYAN_E_PARSE, "hosts[%u].%s is given twice", i, k->string);
        double v[9];
        int n = number_array(k, v, 9);
        if (strcmp(k->string, "center") == 0 && n == 3) memcpy(c, v, sizeof c);
        else if (strcmp(k->string, "half") == 0 && n == 3) { memcpy(half, v, sizeof half); have_half = 1; }
        else if (strcmp(k->string, "rotation") == 0 && n == 9 && !have_rot) { memcpy(rot, v, sizeof rot); have_rot = 1; }
        else if (strcmp(k->string, "rotation_euler_deg") == 0 && n == 3 && !have_rot) {
            euler_deg(v, rot);
            have_rot = 1;
        } else if (strcmp(k->string, "name") == 0 && cJSON_IsString(k)) {
        } else
            return banyan_fail(err, BANYAN_E_TYPE,
                               "hosts[%u].%s is unknown or malformed (keys: center [3], half [3], rotation [9] or "
                               "rotation_euler_deg [3], name; or \"mesh\" for a mesh host)", i, k->string);
    }
    if (!have_half) return banyan_fail(err, BANYAN_E_TYPE, "hosts[%u] needs \"half\": [hx, hy, hz]", i);
    memcpy(out->center, c, sizeof c);
    memcpy(out->half, half, sizeof half);
    memcpy(out->rotation, rot, sizeof rot);
    banyan_status s = banyan_box_validate(out, i, err);
    return s;
}

/* The "mesh" member of host entry h, or NULL when it is a box. */
static const cJSON *mesh_member(const cJSON *h) {
    return cJSON_IsObject(h) ? cJSON_GetObjectItemCaseSensitive(h, "mesh") : NULL;
}

/* One mesh host entry: its file (joined to base_dir, malloc'd into *path),
 * object -> world transform and closed mode. Reads no file. */
static banyan_status read_mesh_entry(const cJSON *h, uint32_t i, const char *base_dir, char **path,
                                     double transform[12], int32_t *closed, banyan_error *err) {
    *path = NULL;
    double t[3] = {0, 0, 0}, sc[3] = {1, 1, 1}, rot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    int have_t = 0, have_rot = 0;
    const char *file = NULL;
    *closed = BANYAN_HOST_CLOSED_AUTO;
    for (const cJSON *k = h->child; k; k = k->next) {
        if (given_before(h, k))
            return banyan_fail(err, BANYAN_E_PARSE, "hosts[%u].%s is given twice", i, k->string);
        double v[9];
        int n = number_array(k, v, 9);
        const char *key = k->string;
        if (!strcmp(key, "mesh")) {
            if (!cJSON_IsString(k) || !k->valuestring[0])
                return banyan_fail(err, BANYAN_E_TYPE, "hosts[%u].mesh must name a .glb file", i);
            file = k->valuestring;
        } else if ((!strcmp(key, "translation") || !strcmp(key, "center")) && have_t) {
            return banyan_fail(err, BANYAN_E_PARSE, "hosts[%u]: give one of translation and center", i);
        } else if ((!strcmp(key, "rotation") || !strcmp(key, "rotation_euler_deg")) && have_rot) {
            return banyan_fail(err, BANYAN_E_PARSE, "hosts[%u]: give one of rotation and rotation_euler_deg", i);
        } else if ((!strcmp(key, "translation") || !strcmp(key, "center")) && n == 3) {
            memcpy(t, v, sizeof t);
            have_t = 1;
        } else if (!strcmp(key, "rotation") && n == 9 && !have_rot) {
            memcpy(rot, v, sizeof rot);
            have_rot = 1;
        } else if (!strcmp(key, "rotation_euler_deg") && n == 3 && !have_rot) {
            for (int a = 0; a < 3; a++)
                if (!isfinite(v[a]))
                    return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].rotation_euler_deg[%d] = %g must be "
                                       "finite", i, a, v[a]);
            euler_deg(v, rot);
            have_rot = 1;
        } else if (!strcmp(key, "scale") && (cJSON_IsNumber(k) || n == 3)) {
            if (cJSON_IsNumber(k)) sc[0] = sc[1] = sc[2] = k->valuedouble;
            else memcpy(sc, v, sizeof sc);
        } else if (!strcmp(key, "closed") && cJSON_IsString(k)) {
            const char *c = k->valuestring;
            if (!strcmp(c, "auto")) *closed = BANYAN_HOST_CLOSED_AUTO;
            else if (!strcmp(c, "open")) *closed = BANYAN_HOST_OPEN;
            else if (!strcmp(c, "closed")) *closed = BANYAN_HOST_CLOSED;
            else
                return banyan_fail(err, BANYAN_E_RANGE, "hosts[%u].closed = \"%.40s\" must be \"auto\", \"open\" or "
                                   "\"closed\"", i, c);
        } else if (!strcmp(key, "name") && cJSON_IsString(k)) {
        } else
            return banyan_fail(err, !strcmp(key, "half") ? BANYAN_E_UNKNOWN_KEY : BANYAN_E_TYPE,
                               "hosts[%u].%s is unknown or malformed for a mesh host (keys: mesh, translation or "
                               "center [3], rotation [9] or rotation_euler_deg [3], scale, closed, name)", i, key);
    }
    if (!file) return banyan_fail(err, BANYAN_E_TYPE, "hosts[%u].mesh must name a .glb file", i);
    for (int a = 0; a < 3; a++) {
        if (!isfinite(t[a]) || fabs(t[a]) > 1e6)
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].translation[%d] = %g must be finite, within "
                               "[-1e6, 1e6] m", i, a, t[a]);
        if (!isfinite(sc[a]) || fabs(sc[a]) < 1e-6 || fabs(sc[a]) > 1e6)
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].scale[%d] = %g must be within [1e-6, 1e6] in "
                               "size (a negative scale mirrors)", i, a, sc[a]);
    }
    /* A rotation, as a box's, but a mesh host has "scale" for scale and
     * mirroring, so the messages say so. */
    for (int a = 0; a < 9; a++)
        if (!isfinite(rot[a]))
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].rotation[%d] = %g must be finite", i, a, rot[a]);
    m3 rm = m3_load(rot);
    for (int c = 0; c < 3; c++)
        for (int d = c; d < 3; d++) {
            double dot = v3_dot(m3_col(&rm, c), m3_col(&rm, d)), want = c == d ? 1.0 : 0.0;
            if (fabs(dot - want) > 1e-3)
                return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].rotation is not a rotation (column %d . "
                                   "column %d = %g, want %g): give the scale in \"scale\" and a pure rotation",
                                   i, c, d, dot, want);
        }
    if (m3_det(&rm) < 0)
        return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].rotation has determinant %g: give a proper rotation "
                           "(det +1) and mirror with a negative \"scale\"", i, m3_det(&rm));
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) transform[4 * r + c] = rot[3 * r + c] * sc[c];
        transform[4 * r + 3] = t[r];
    }
    size_t fl = strlen(file), bl = base_dir ? strlen(base_dir) : 0;
    int absolute = file[0] == '/' || file[0] == '\\' || (fl > 1 && file[1] == ':');
    if (absolute || !bl) bl = 0;
    *path = malloc(bl + fl + 2);
    if (!*path) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    if (bl) {
        memcpy(*path, base_dir, bl);
        if (base_dir[bl - 1] != '/') (*path)[bl++] = '/';
    }
    memcpy(*path + bl, file, fl + 1);
    return BANYAN_OK;
}

/* An explicit "hosts": [] would otherwise read as no key at all and grow
 * on the generator's default hosts: refuse it (hosts may be NULL). */
static banyan_status not_empty(const cJSON *hosts, const char *w, banyan_error *err) {
    if (!hosts || hosts->child) return BANYAN_OK;
    return banyan_fail(err, BANYAN_E_NO_HOSTS, "%shosts is an empty list; give at least one host or leave the key out "
                       "for the default hosts", w);
}

/* The start of the preset readers that fill a caller's array of cap
 * entries: checks count and out, parses the preset (*j, for the caller to
 * delete) and finds its "hosts" (NULL when absent), w the place to name in
 * messages. */
static banyan_status open_hosts(const char *text, size_t length, const char *source, const void *out, uint32_t cap,
                                uint32_t *count, cJSON **j, const cJSON **hosts, char w[300], banyan_error *err) {
    if (!count) return banyan_fail(err, BANYAN_E_INVALID_ARG, "count is NULL");
    *count = 0;
    if (!out && cap) return banyan_fail(err, BANYAN_E_INVALID_ARG, "out is NULL but cap = %u", cap);
    if (!source) source = "<preset>";
    banyan_status s = preset_parse(text, length, source, j, err);
    if (s) return s;
    *hosts = cJSON_GetObjectItemCaseSensitive(*j, "hosts");
    where(w, 300, source, text, length, "hosts");
    return BANYAN_OK;
}

banyan_status banyan_preset_hosts(const char *text, size_t length, const char *source, banyan_box *out, uint32_t cap,
                                  uint32_t *count, banyan_error *err) {
    cJSON *j;
    const cJSON *hosts;
    char w[300];
    banyan_status s = open_hosts(text, length, source, out, cap, count, &j, &hosts, w, err);
    if (s) return s;
    if (hosts && !cJSON_IsArray(hosts)) {
        s = banyan_fail(err, BANYAN_E_TYPE, "%shosts must be an array of boxes", w);
    } else if ((s = not_empty(hosts, w, err))) {
    } else {
        uint32_t n = (uint32_t)cJSON_GetArraySize(hosts);
        uint32_t i = 0;
        for (const cJSON *h = hosts ? hosts->child : NULL; h && !s; h = h->next, i++)
            if (mesh_member(h))
                s = banyan_fail(err, BANYAN_E_UNSUPPORTED, "%shosts[%u] is a mesh host (\"mesh\"), and only boxes "
                                "are read here: mesh hosts are for the generators that grow on meshes (roots, ivy); "
                                "give this one as a box (center, half)", w, i);
        if (!s && n > cap) s = banyan_fail(err, BANYAN_E_RANGE, "%s%u hosts is more than the %u allowed", w, n, cap);
        i = 0;
        for (const cJSON *h = hosts ? hosts->child : NULL; h && !s; h = h->next, i++)
            if ((s = read_box(h, i, &out[i], err))) banyan_error_prefix(err, w);
        if (!s) {
            *count = n;
            banyan_error_clear(err);
        }
    }
    cJSON_Delete(j);
    return s;
}

size_t banyan_sizeof_preset_mesh(void) { return sizeof(banyan_preset_mesh); }

/* The name of mesh entry h: its "name", or the file's base name without
 * its extension. */
static void entry_name(const cJSON *h, const char *path, char *out, size_t cap) {
    const cJSON *nm = cJSON_GetObjectItemCaseSensitive(h, "name");
    if (cJSON_IsString(nm) && nm->valuestring[0]) {
        snprintf(out, cap, "%s", nm->valuestring);
        return;
    }
    const char *b = path;
    for (const char *c = path; *c; c++)
        if (*c == '/' || *c == '\\') b = c + 1;
    const char *dot = strrchr(b, '.');
    size_t n = dot && dot != b ? (size_t)(dot - b) : strlen(b);
    snprintf(out, cap, "%.*s", (int)n, b);
}

banyan_status banyan_preset_meshes(const char *text, size_t length, const char *source, const char *base_dir,
                                   banyan_preset_mesh *out, uint32_t cap, uint32_t *count, banyan_error *err) {
    cJSON *j;
    const cJSON *hosts;
    char w[300];
    banyan_status s = open_hosts(text, length, source, out, cap, count, &j, &hosts, w, err);
    if (s) return s;
    if (!source) source = "<preset>";
    if (hosts && !cJSON_IsArray(hosts)) s = banyan_fail(err, BANYAN_E_TYPE, "%shosts must be an array", w);
    else s = not_empty(hosts, w, err);
    uint32_t i = 0, n = 0;
    for (const cJSON *h = hosts ? hosts->child : NULL; h && !s; h = h->next, i++) {
        if (!mesh_member(h)) continue;
        char wm[300], *path = NULL;
        where_nth(wm, sizeof wm, source, text, length, "mesh", (int)n);
        double transform[12];
        int32_t closed;
        if ((s = read_mesh_entry(h, i, base_dir, &path, transform, &closed, err))) {
            banyan_error_prefix(err, wm);
            break;
        }
        if (n < cap) {
            banyan_preset_mesh *m = &out[n];
            memset(m, 0, sizeof *m);
            if (strlen(path) >= sizeof m->path) {
                s = banyan_fail(err, BANYAN_E_RANGE, "%shosts[%u].mesh: the path joined to base_dir is %zu bytes, "
                                "more than the %zu allowed", wm, i, strlen(path), sizeof m->path - 1);
                free(path);
                break;
            }
            m->index = i;
            m->closed = closed;
            memcpy(m->transform, transform, sizeof m->transform);
            memcpy(m->path, path, strlen(path) + 1);
            entry_name(h, path, m->name, sizeof m->name);
        }
        free(path);
        n++;
    }
    if (!s && n > cap) s = banyan_fail(err, BANYAN_E_RANGE, "%s%u mesh hosts is more than cap = %u", w, n, cap);
    if (!s) {
        *count = n;
        banyan_error_clear(err);
    }
    cJSON_Delete(j);
    return s;
}

/* How the set numbers host k of banyan_hosts_create's messages ("hosts[K]
 * (mesh M) ...") in the preset's terms: its message is rewritten to start
 * "hosts[i]" (the preset's entry) or "--host / extra mesh j", keeping the
 * cause whole. Other messages get a short "host set: " prefix. */
static void name_set_host(banyan_error *err, const char *source, const uint32_t *entry, uint32_t nm, uint32_t n_extra) {
    if (!err) return;
    unsigned k = 0, mi = 0;
    int used = 0;
    if (sscanf(err->message, "hosts[%u] (mesh %u)%n", &k, &mi, &used) == 2 && used > 0 && mi < nm + n_extra) {
        char head[80];
        if (mi < nm) snprintf(head, sizeof head, "hosts[%u]", entry[mi]);
        else snprintf(head, sizeof head, "extra mesh %u (after the preset's hosts)", mi - nm);
        size_t h = strlen(head), r = strlen(err->message + used), cap = sizeof err->message - 1;
        if (h + r > cap) r = cap - h;
        memmove(err->message + h, err->message + used, r);
        memcpy(err->message, head, h);
        err->message[h + r] = '\0';
    }
    char pre[300];
    snprintf(pre, sizeof pre, "%s: host set: ", source);
    banyan_error_prefix(err, pre);
}

banyan_status banyan_preset_host_set(const char *text, size_t length, const char *source, const char *base_dir,
                                     const banyan_host_mesh *extra, uint32_t n_extra, banyan_hosts **out,
                                     banyan_error *err) {
    return banyan_preset_host_set_budget(text, length, source, base_dir, extra, n_extra, NULL, out, err);
}

/* err's message prefixed with the mesh entry it is about: "<where>hosts[i]: ". */
static void prefix_entry(banyan_error *err, const char *wm, uint32_t i) {
    char pre[340];
    snprintf(pre, sizeof pre, "%shosts[%u]: ", wm, i);
    banyan_error_prefix(err, pre);
}

/* What banyan_hosts_create holds per triangle and per vertex of its meshes
 * (positions, normals, twins, caps, Embree's tree), for the memory
 * estimate made before it runs: an upper bound, about twice the 119 bytes
 * a triangle (vertices included) measured on a 560k-triangle mesh. */
#define HOST_SET_BYTES_PER_TRIANGLE 160.0
#define HOST_SET_BYTES_PER_VERTEX 48.0

banyan_status banyan_preset_host_set_budget(const char *text, size_t length, const char *source, const char *base_dir,
                                            const banyan_host_mesh *extra, uint32_t n_extra,
                                            const banyan_budget *budget, banyan_hosts **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    if (n_extra && !extra) return banyan_fail(err, BANYAN_E_INVALID_ARG, "extra is NULL but n_extra = %u", n_extra);
    prog g;
    banyan_status s = prog_budget_from(&g, budget, err);
    if (s) return s;
    if (!source) source = "<preset>";
    cJSON *j;
    s = preset_parse(text, length, source, &j, err);
    if (s) return s;
    const cJSON *hosts = cJSON_GetObjectItemCaseSensitive(j, "hosts");
    char w[300];
    where(w, sizeof w, source, text, length, "hosts");
    uint32_t n = hosts ? (uint32_t)cJSON_GetArraySize(hosts) : 0, nb = 0, nm = 0;
    banyan_box *boxes = NULL;
    banyan_host_mesh *meshes = NULL, **read = NULL;
    uint32_t *entry = NULL; /* preset index of each of the preset's meshes */
    if (hosts && !cJSON_IsArray(hosts)) {
        s = banyan_fail(err, BANYAN_E_TYPE, "%shosts must be an array of boxes and meshes", w);
        goto done;
    }
    if ((s = not_empty(hosts, w, err))) goto done;
    if ((uint64_t)n + n_extra > BANYAN_MAX_HOSTS) {
        s = banyan_fail(err, BANYAN_E_RANGE, "%s%u hosts (%u in the preset, %u more) is more than the %u allowed", w,
                        n + n_extra, n, n_extra, BANYAN_MAX_HOSTS);
        goto done;
    }
    if (n + n_extra == 0) {
        s = banyan_fail(err, BANYAN_E_NO_HOSTS, "%s: the preset names no hosts", source);
        goto done;
    }
    boxes = malloc(sizeof *boxes * (n ? n : 1));
    meshes = malloc(sizeof *meshes * (n + n_extra));
    read = calloc(n ? n : 1, sizeof *read);
    entry = malloc(sizeof *entry * (n ? n : 1));
    if (!boxes || !meshes || !read || !entry) {
        s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
        goto done;
    }
    /* First every entry checked and every mesh file's sizes read from its
     * header and JSON: the set-wide limits and the memory estimate hold
     * before any file is read whole (one file named by many entries counts
     * once per entry). */
    uint64_t set_tris = 0, set_verts = 0;
    double set_bytes = 0;
    for (uint32_t k = 0; k < n_extra; k++) set_tris += extra[k].triangle_count, set_verts += extra[k].vertex_count;
    uint32_t i = 0;
    for (const cJSON *h = hosts ? hosts->child : NULL; h; h = h->next, i++) {
        if (!mesh_member(h)) {
            if ((s = read_box(h, i, &boxes[nb++], err))) {
                banyan_error_prefix(err, w);
                goto done;
            }
            continue;
        }
        char wm[300], *path = NULL;
        where_nth(wm, sizeof wm, source, text, length, "mesh", (int)nm);
        double transform[12];
        int32_t closed;
        glb_sizes z;
        if ((s = read_mesh_entry(h, i, base_dir, &path, transform, &closed, err))) {
            banyan_error_prefix(err, wm);
            goto done;
        }
        s = glb_scan(path, &g, &z, err);
        free(path);
        if (s) {
            prefix_entry(err, wm, i);
            goto done;
        }
        set_tris += z.triangles, set_verts += z.vertex_reads;
        set_bytes += z.memory + HOST_SET_BYTES_PER_TRIANGLE * (double)z.triangles;
        if (set_tris > BANYAN_HOSTS_MAX_TRIANGLES) {
            s = banyan_fail(err, BANYAN_E_LIMIT, "%shosts[%u]: with it the mesh hosts hold %llu triangles (each entry "
                            "counted, also when entries name one file); a host set takes at most %u (decimate, or "
                            "use fewer or box hosts)", wm, i, (unsigned long long)set_tris, BANYAN_HOSTS_MAX_TRIANGLES);
            goto done;
        }
        if (prog_at(&g, 0.0)) {
            s = prog_fail(&g, err, "reading the preset's mesh hosts");
            goto done;
        }
        nm++;
    }
    set_bytes += HOST_SET_BYTES_PER_VERTEX * (double)set_verts;
    if (prog_reserve(&g, set_bytes)) {
        s = prog_fail(&g, err, "building the host set (estimated from the mesh files' headers)");
        banyan_error_prefix(err, w);
        goto done;
    }
    nm = 0, i = 0;
    for (const cJSON *h = hosts ? hosts->child : NULL; h; h = h->next, i++) {
        if (!mesh_member(h)) continue;
        char wm[300], *path = NULL;
        where_nth(wm, sizeof wm, source, text, length, "mesh", (int)nm);
        double transform[12];
        int32_t closed;
        if ((s = read_mesh_entry(h, i, base_dir, &path, transform, &closed, err))) {
            banyan_error_prefix(err, wm);
            goto done;
        }
        s = glb_read_host_prog(path, transform, closed, &g, &read[nm], err);
        free(path);
        if (s) {
            prefix_entry(err, wm, i);
            goto done;
        }
        /* Placed, every vertex must stay where the host set accepts it. */
        const banyan_host_mesh *m = read[nm];
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            const float *p = m->positions + 3 * (size_t)v;
            for (int r = 0; r < 3; r++) {
                double x = transform[4 * r] * p[0] + transform[4 * r + 1] * p[1] + transform[4 * r + 2] * p[2] +
                           transform[4 * r + 3];
                if (!(fabs(x) <= 1e6)) {
                    s = banyan_fail(err, BANYAN_E_BAD_HOST, "%shosts[%u]: vertex %u lands at %g on axis %d, outside "
                                    "[-1e6, 1e6] m", wm, i, v, x, r);
                    goto done;
                }
            }
        }
        meshes[nm] = *m;
        entry[nm++] = i;
    }
    if (n_extra) memcpy(meshes + nm, extra, sizeof *extra * n_extra);
    /* The build itself cannot be stopped half way: it starts only with time
     * left, and the estimate above covered its memory. */
    if (prog_at(&g, 0.5)) {
        s = prog_fail(&g, err, "reading the preset's mesh hosts");
        goto done;
    }
    s = banyan_hosts_create(boxes, nb, meshes, nm + n_extra, out, err);
    if (s) name_set_host(err, source, entry, nm, n_extra);
    else banyan_error_clear(err);
done:
    for (uint32_t k = 0; read && k < n; k++) banyan_host_mesh_free(read[k]);
    free(read);
    free(boxes);
    free(meshes);
    free(entry);
    cJSON_Delete(j);
    if (s) *out = NULL;
    return s;
}
