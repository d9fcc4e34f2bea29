/* test_bad_input.c - every public entry point against hostile input:
 * NaN and inf in every field of every params table, values below and
 * above their ranges, zero and negative sizes, counts past
 * their caps, degenerate hosts, no hosts, start points inside or far from
 * the hosts, NULL pointers, vertex limits and broken presets.
 *
 * Every case checks three things: the status, that the message names the
 * field (a needle), and that the out pointer - preset to a non-NULL
 * sentinel - comes back NULL. A case whose wanted status is BANYAN_OK is a
 * documented repair (docs/reliability.md) and must give an output instead.
 *
 *   test_bad_input OUTDIR     run, print "N passed, N failed"
 *   test_bad_input --table    also print one JSON object per case on
 *                             stdout (the summary goes to stderr); read by
 *                             tools/reliability_table.py. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "test_files.h"
#include "test_hosts.h"

/* ------------------------------------------------------------ reporting */

static int table_mode;
static int in_sweep; /* the case comes from the table sweep, not a hand-made list */
static char sentinel_byte;
#define SENTINEL ((void *)&sentinel_byte)

static void json_string(const char *s) {
    putchar('"');
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\') printf("\\%c", *p);
        else if (*p < 0x20 || *p >= 0x7f) printf("\\u%04x", *p); /* messages may quote hostile bytes */
        else putchar(*p);
    }
    putchar('"');
}

/* One case: gen / entry / input class and text, wanted status and needle,
 * what came back. out_ok: the out pointer is as it must be (NULL on
 * failure, a result on a wanted BANYAN_OK). */
static void report(const char *gen, const char *entry, const char *klass, const char *input, banyan_status want,
                   const char *needle, banyan_status got, const banyan_error *e, int out_ok) {
    const char *msg = e->message;
    int status_ok = got == want;
    int msg_ok = want == BANYAN_OK || !needle || strstr(msg, needle) != NULL;
    int code_ok = want == BANYAN_OK || e->code == (int32_t)got; /* the error struct agrees with the return */
    CHECK(status_ok, "%s %s [%s]: got %s, want %s: %s", gen, entry, input, banyan_status_name(got),
          banyan_status_name(want), msg);
    CHECK(msg_ok, "%s %s [%s]: message '%s' does not name '%s'", gen, entry, input, msg, needle);
    CHECK(code_ok, "%s %s [%s]: err.code %d differs from the status %d", gen, entry, input, e->code, got);
    CHECK(out_ok, "%s %s [%s]: out is %s", gen, entry, input, want == BANYAN_OK ? "NULL" : "not NULL");
    if (!table_mode) return;
    printf("{\"generator\": ");
    json_string(gen);
    printf(", \"entry\": ");
    json_string(entry);
    printf(", \"class\": ");
    json_string(klass);
    printf(", \"input\": ");
    json_string(input);
    printf(", \"want\": \"%s\", \"status\": \"%s\", \"message\": ", banyan_status_name(want), banyan_status_name(got));
    json_string(msg);
    printf(", \"sweep\": %s, \"pass\": %s}\n", in_sweep ? "true" : "false",
           status_ok && msg_ok && code_ok && out_ok ? "true" : "false");
}

/* ----------------------------------------------------- default inputs */

static banyan_box trunk_host(void) { return banyan_box_make(0, 0, 1, 0.3, 0.3, 1); }
static banyan_box wall_host(void) { return banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5); }

/* Mesh out-pointer helper: sentinel in, freed result out. */
static int mesh_out_ok(banyan_mesh *m, banyan_status s) {
    if (s == BANYAN_OK) {
        int ok = m && m != SENTINEL;
        if (ok) banyan_mesh_free(m);
        return ok;
    }
    return m == NULL;
}

/* A call of one entry point on a params struct of its generator. */
typedef struct entry_call {
    const char *name;
    banyan_status (*call)(const void *params, int *out_ok, banyan_error *e);
} entry_call;

static banyan_status call_roots(const void *p, int *out_ok, banyan_error *e) {
    banyan_box h = trunk_host();
    banyan_hosts *H = TEST_HOSTS(&h, 1);
    banyan_mesh *m = SENTINEL;
    banyan_roots_stats st;
    memset(&st, 0xff, sizeof st);
    banyan_status s = banyan_roots_generate(p, H, &m, &st, NULL, e);
    *out_ok = mesh_out_ok(m, s) && (s == BANYAN_OK || st.vertices == 0); /* stats zeroed on failure */
    banyan_hosts_free(H);
    return s;
}
static banyan_status call_keyaki(const void *p, int *out_ok, banyan_error *e) {
    banyan_mesh *m = SENTINEL;
    banyan_status s = banyan_keyaki_generate(p, &m, NULL, NULL, e);
    *out_ok = mesh_out_ok(m, s);
    return s;
}
static banyan_status call_keyaki_stats(const void *p, int *out_ok, banyan_error *e) {
    banyan_keyaki_stats st;
    memset(&st, 0xff, sizeof st);
    banyan_status s = banyan_keyaki_skeleton_stats(p, &st, e);
    *out_ok = s == BANYAN_OK || st.node_count == 0;
    return s;
}
static banyan_status call_avenue(const void *p, int *out_ok, banyan_error *e) {
    banyan_mesh *m = SENTINEL;
    banyan_status s = banyan_avenue_generate(p, NULL, 0, &m, NULL, e);
    *out_ok = mesh_out_ok(m, s);
    return s;
}
static banyan_status call_avenue_layout(const void *p, int *out_ok, banyan_error *e) {
    banyan_keyaki_params trees[64];
    uint32_t n = 12345;
    banyan_status s = banyan_avenue_layout(p, NULL, 0, trees, 64, &n, e);
    *out_ok = s == BANYAN_OK || n == 0 || s == BANYAN_E_INVALID_ARG || s == BANYAN_E_LIMIT;
    return s;
}
static banyan_status call_ivy(const void *p, int *out_ok, banyan_error *e) {
    banyan_box h = wall_host();
    banyan_hosts *H = TEST_HOSTS(&h, 1);
    banyan_mesh *m = SENTINEL;
    banyan_ivy_stats st;
    memset(&st, 0xff, sizeof st);
    banyan_status s = banyan_ivy_generate(p, H, &m, &st, NULL, e);
    *out_ok = mesh_out_ok(m, s) && (s == BANYAN_OK || st.buds == 0); /* stats zeroed on failure */
    banyan_hosts_free(H);
    return s;
}
static banyan_status call_ivy_create(const void *p, int *out_ok, banyan_error *e) {
    banyan_box h = wall_host();
    banyan_hosts *H = TEST_HOSTS(&h, 1);
    banyan_ivy *iv = SENTINEL;
    banyan_status s = banyan_ivy_create(p, H, &iv, e);
    *out_ok = s == BANYAN_OK ? iv && iv != SENTINEL : iv == NULL;
    if (s == BANYAN_OK && iv != SENTINEL) banyan_ivy_free(iv);
    banyan_hosts_free(H);
    return s;
}
static const banyan_segment_input demo_segs[2] = {{{0, 0, 0}, {0, 0, 1}, 2.0, 3, 1}, {{0, 0, 1}, {1, 0, 1}, 1.0, 2, 0}};
static banyan_status call_segments(const void *p, int *out_ok, banyan_error *e) {
    banyan_mesh *m = SENTINEL;
    banyan_status s = banyan_segments_generate(p, demo_segs, 2, NULL, &m, NULL, NULL, e);
    *out_ok = mesh_out_ok(m, s);
    return s;
}
static banyan_status call_segments_lines(const void *p, int *out_ok, banyan_error *e) {
    uint32_t n = 12345;
    banyan_status s = banyan_segments_lines(p, demo_segs, 2, NULL, NULL, NULL, 0, &n, e);
    *out_ok = s == BANYAN_OK || n == 0;
    return s;
}
static banyan_status call_segments_unattached(const void *p, int *out_ok, banyan_error *e) {
    uint32_t list[2], n = 12345;
    banyan_status s = banyan_segments_find_unattached(p, demo_segs, 2, NULL, list, &n, e);
    *out_ok = s == BANYAN_OK || n == 0;
    return s;
}
static banyan_status call_segments_demo(const void *p, int *out_ok, banyan_error *e) {
    banyan_segment_input segs[4096];
    double trunk[6];
    uint32_t n = 12345;
    banyan_status s = banyan_segments_demo(p, segs, 4096, &n, trunk, e);
    *out_ok = s == BANYAN_OK || n == 0;
    return s;
}

typedef struct gen_entries {
    banyan_generator g;
    void (*init)(void *);
    size_t size;
    entry_call calls[4];
} gen_entries;

static void init_roots(void *p) { banyan_roots_params_init(p); }
static void init_keyaki(void *p) { banyan_keyaki_params_init(p); }
static void init_avenue(void *p) { banyan_avenue_params_init(p); }
static void init_ivy(void *p) { banyan_ivy_params_init(p); }
static void init_segments(void *p) { banyan_segments_params_init(p); }

static const gen_entries generators[] = {
    {BANYAN_GEN_ROOTS, init_roots, sizeof(banyan_roots_params),
     {{"banyan_roots_generate", call_roots}}},
    {BANYAN_GEN_KEYAKI, init_keyaki, sizeof(banyan_keyaki_params),
     {{"banyan_keyaki_generate", call_keyaki}, {"banyan_keyaki_skeleton_stats", call_keyaki_stats}}},
    {BANYAN_GEN_AVENUE, init_avenue, sizeof(banyan_avenue_params),
     {{"banyan_avenue_generate", call_avenue}, {"banyan_avenue_layout", call_avenue_layout}}},
    {BANYAN_GEN_IVY, init_ivy, sizeof(banyan_ivy_params),
     {{"banyan_ivy_generate", call_ivy}, {"banyan_ivy_create", call_ivy_create}}},
    {BANYAN_GEN_SEGMENTS, init_segments, sizeof(banyan_segments_params),
     {{"banyan_segments_generate", call_segments},
      {"banyan_segments_lines", call_segments_lines},
      {"banyan_segments_find_unattached", call_segments_unattached},
      {"banyan_segments_demo", call_segments_demo}}},
};
#define N_GENERATORS (sizeof generators / sizeof generators[0])

/* ------------------------------------------- every field of every table */

/* Writes v into component c of the field, as the field's C type. */
static void set_field(const banyan_param_info *info, void *params, int c, double v) {
    char *f = (char *)params + info->offset;
    if (info->type == BANYAN_PT_INT || info->type == BANYAN_PT_BOOL || info->type == BANYAN_PT_ENUM) {
        int32_t x = v <= INT32_MIN ? INT32_MIN : v >= INT32_MAX ? INT32_MAX : (int32_t)v;
        memcpy(f, &x, sizeof x);
    } else {
        memcpy(f + sizeof(double) * (size_t)c, &v, sizeof v);
    }
}

static int enum_choices(const char *choices) {
    int n = 1;
    for (const char *p = choices; *p; p++) n += *p == '|';
    return n;
}

typedef struct bad_value {
    const char *klass; /* "NaN", "inf", "below range", ... */
    double v;
} bad_value;

/* The hostile values for one field; returns how many. */
static int bad_values(const banyan_param_info *info, bad_value *out) {
    int n = 0;
    double lo = info->min, hi = info->max;
    switch (info->type) {
    case BANYAN_PT_DOUBLE:
    case BANYAN_PT_VEC3:
    case BANYAN_PT_COLOR:
        out[n++] = (bad_value){"NaN", NAN};
        out[n++] = (bad_value){"inf", INFINITY};
        out[n++] = (bad_value){"-inf", -INFINITY};
        out[n++] = (bad_value){"below range", lo > 0 ? lo * 0.5 : lo - (lo < 0 ? -lo : 1.0)};
        out[n++] = (bad_value){"above range", hi > 0 ? hi * 2.0 : hi + 1.0};
        if (lo > 0) out[n++] = (bad_value){"zero", 0.0};
        if (lo > -1.0 && lo * 0.5 != -1.0) out[n++] = (bad_value){"negative", -1.0};
        out[n++] = (bad_value){"huge", DBL_MAX};
        break;
    case BANYAN_PT_INT:
        out[n++] = (bad_value){"below range", lo - 1};
        out[n++] = (bad_value){"above range", hi + 1};
        if (lo > 0) out[n++] = (bad_value){"zero", 0};
        if (lo > -1 && lo - 1 != -1) out[n++] = (bad_value){"negative", -1};
        out[n++] = (bad_value){"INT32_MIN", INT32_MIN};
        if (hi < INT32_MAX) out[n++] = (bad_value){"INT32_MAX", INT32_MAX};
        break;
    case BANYAN_PT_BOOL:
        out[n++] = (bad_value){"negative", -1};
        out[n++] = (bad_value){"above range", 2};
        break;
    case BANYAN_PT_ENUM:
        out[n++] = (bad_value){"negative", -1};
        out[n++] = (bad_value){"above range", enum_choices(info->choices)};
        out[n++] = (bad_value){"INT32_MAX", INT32_MAX};
        break;
    default: break; /* seeds: every value is valid */
    }
    return n;
}

static void field_sweep(void) {
    in_sweep = 1;
    unsigned char *params = malloc(4096), *pristine = malloc(4096);
    for (size_t gi = 0; gi < N_GENERATORS; gi++) {
        const gen_entries *G = &generators[gi];
        const char *gen = banyan_generator_name(G->g);
        CHECK(G->size <= 4096, "%s params fit the scratch", gen);
        G->init(pristine);
        for (int32_t r = 0; r < banyan_param_count(G->g); r++) {
            const banyan_param_info *info = banyan_param_get(G->g, r);
            bad_value bv[12];
            int nb = bad_values(info, bv);
            int comps = info->type == BANYAN_PT_VEC3 ? 3 : info->type == BANYAN_PT_COLOR ? 4 : 1;
            for (int b = 0; b < nb; b++) {
                /* NaN goes into every component; other values into the last. */
                for (int c = 0; c < comps; c++) {
                    if (strcmp(bv[b].klass, "NaN") != 0 && c != comps - 1) continue;
                    char input[160];
                    if (comps > 1)
                        snprintf(input, sizeof input, "%s[%d] = %g", info->name, c, bv[b].v);
                    else
                        snprintf(input, sizeof input, "%s = %g", info->name, bv[b].v);
                    for (int k = 0; k < 4 && G->calls[k].name; k++) {
                        memcpy(params, pristine, G->size);
                        set_field(info, params, c, bv[b].v);
                        banyan_error e;
                        memset(&e, 0, sizeof e);
                        int out_ok = 0;
                        banyan_status s = G->calls[k].call(params, &out_ok, &e);
                        report(gen, G->calls[k].name, bv[b].klass, input, BANYAN_E_RANGE, info->name, s, &e, out_ok);
                        CHECK(strchr(e.message, '[') || strstr(e.message, "one of"),
                              "%s [%s]: the message '%s' gives no valid range", G->calls[k].name, input, e.message);
                    }
                }
            }
        }
    }
    free(params);
    free(pristine);
    in_sweep = 0;
}

/* ------------------------------------------------------- hand-made cases */

/* One hand-made case for a mesh-returning call: the runner fills m. */
#define RUN_MESH(gen, entry, klass, input, want, needle, expr)                 \
    do {                                                                       \
        banyan_mesh *m = SENTINEL;                                             \
        banyan_error e;                                                        \
        memset(&e, 0, sizeof e);                                               \
        banyan_status s_ = (expr);                                             \
        report(gen, entry, klass, input, want, needle, s_, &e, mesh_out_ok(m, s_)); \
    } while (0)

/* banyan_hosts_create on boxes[0 .. n - 1]: the out pointer preset to the
 * sentinel must come back NULL on a refusal. */
#define RUN_SET(klass, input, want, needle, boxes, n)                           \
    do {                                                                       \
        banyan_hosts *H_ = SENTINEL;                                           \
        banyan_error e;                                                        \
        memset(&e, 0, sizeof e);                                               \
        banyan_status s_ = banyan_hosts_create((boxes), (n), NULL, 0, &H_, &e); \
        report("hosts", "banyan_hosts_create", klass, input, want, needle, s_, &e, \
               s_ == BANYAN_OK ? H_ && H_ != SENTINEL : H_ == NULL);           \
        if (s_ == BANYAN_OK && H_ != SENTINEL) banyan_hosts_free(H_);          \
    } while (0)

/* A case without an out pointer (or with one checked by `ok`). */
#define RUN(gen, entry, klass, input, want, needle, expr, ok)                  \
    do {                                                                       \
        banyan_error e;                                                        \
        memset(&e, 0, sizeof e);                                               \
        banyan_status s_ = (expr);                                             \
        report(gen, entry, klass, input, want, needle, s_, &e, (ok));          \
    } while (0)

typedef struct bad_box {
    const char *input;
    banyan_box box;
    const char *needle;
} bad_box;

/* Degenerate hosts. The policy is to refuse, never to repair: a scaled or
 * sheared rotation would silently change the box's size otherwise. */
static int bad_boxes(bad_box *out) {
    int n = 0;
    banyan_box b = banyan_box_make(2, 0, 1, 0.5, 0.5, 1);
    banyan_box x;
#define BB(text, field, expr)     \
    x = b;                        \
    expr;                         \
    out[n++] = (bad_box){text, x, field}
    BB("center[0] = NaN", "hosts[1].center[0]", x.center[0] = NAN);
    BB("center[2] = inf", "hosts[1].center[2]", x.center[2] = INFINITY);
    BB("center[1] = 1e7 (beyond 1e6 m)", "hosts[1].center[1]", x.center[1] = 1e7);
    BB("half[0] = 0 (zero extent)", "hosts[1].half[0]", x.half[0] = 0);
    BB("half[2] = 0 (a plane)", "hosts[1].half[2]", x.half[2] = 0);
    BB("half[1] = -1 (negative size)", "hosts[1].half[1]", x.half[1] = -1);
    BB("half[0] = NaN", "hosts[1].half[0]", x.half[0] = NAN);
    BB("half[1] = inf", "hosts[1].half[1]", x.half[1] = INFINITY);
    BB("half[2] = 1e7 (beyond 1e6 m)", "hosts[1].half[2]", x.half[2] = 1e7);
    BB("rotation[4] = NaN", "hosts[1].rotation[4]", x.rotation[4] = NAN);
    BB("rotation[0] = -inf", "hosts[1].rotation[0]", x.rotation[0] = -INFINITY);
    BB("rotation scaled by 2 (not orthonormal)", "hosts[1].rotation is not orthonormal",
       for (int i = 0; i < 9; i++) x.rotation[i] *= 2);
    BB("rotation with scale (1, 1, 3) on z", "hosts[1].rotation is not orthonormal", x.rotation[8] = 3);
    BB("rotation sheared (x . y = 0.5)", "hosts[1].rotation is not orthonormal", x.rotation[1] = 0.5);
    BB("rotation all zero", "hosts[1].rotation is not orthonormal", memset(x.rotation, 0, sizeof x.rotation));
    BB("rotation mirrored (det -1)", "hosts[1].rotation has determinant", x.rotation[8] = -1);
#undef BB
    return n;
}

static void host_cases(void) {
    bad_box bb[32];
    int nb = bad_boxes(bb);
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    ip.steps = 5;
    for (int i = 0; i < nb; i++) {
        banyan_box two[2] = {trunk_host(), bb[i].box};
        RUN_SET("bad host", bb[i].input, BANYAN_E_BAD_HOST, bb[i].needle, two, 2);
        RUN("common", "banyan_box_validate", "bad host", bb[i].input, BANYAN_E_BAD_HOST, bb[i].needle,
            banyan_box_validate(&bb[i].box, 1, &e), 1);
    }
    RUN("common", "banyan_box_validate", "NULL", "box = NULL", BANYAN_E_INVALID_ARG, "NULL",
        banyan_box_validate(NULL, 0, &e), 1);

    /* Host lists. */
    banyan_box h = trunk_host(), w = wall_host();
    banyan_box *many = malloc(sizeof(banyan_box) * (BANYAN_MAX_HOSTS + 1));
    for (int i = 0; i <= BANYAN_MAX_HOSTS; i++) many[i] = banyan_box_make(3.0 * i, 0, 1, 0.5, 0.5, 1);
    RUN_SET("no hosts", "n_boxes = 0", BANYAN_E_NO_HOSTS, "n_boxes + n_meshes = 0", &h, 0);
    RUN_SET("no hosts", "boxes = NULL, n_boxes = 0", BANYAN_E_NO_HOSTS, "n_boxes + n_meshes = 0", NULL, 0);
    RUN_SET("NULL", "boxes = NULL, n_boxes = 1", BANYAN_E_INVALID_ARG, "boxes is NULL", NULL, 1);
    RUN_SET("above cap", "n_boxes = 257", BANYAN_E_RANGE, "n_boxes + n_meshes", many, BANYAN_MAX_HOSTS + 1);
    RUN_SET("above cap", "n_boxes = UINT32_MAX", BANYAN_E_RANGE, "n_boxes + n_meshes", many, UINT32_MAX);
    free(many);
    RUN_MESH("roots", "banyan_roots_generate", "no hosts", "hosts = NULL", BANYAN_E_NO_HOSTS, "hosts is NULL",
             banyan_roots_generate(&rp, NULL, &m, NULL, NULL, &e));
    RUN_MESH("ivy", "banyan_ivy_generate", "NULL", "hosts = NULL", BANYAN_E_INVALID_ARG, "hosts is NULL",
             banyan_ivy_generate(&ip, NULL, &m, NULL, NULL, &e));
    banyan_ivy *iv_ = SENTINEL;
    RUN("ivy", "banyan_ivy_create", "NULL", "hosts = NULL", BANYAN_E_INVALID_ARG, "hosts is NULL",
        banyan_ivy_create(&ip, NULL, &iv_, &e), iv_ == NULL);

    /* Start points. */
    banyan_roots_params g = rp;
    g.germination_auto = 0;
    g.germination[0] = 0, g.germination[1] = 0, g.germination[2] = 1;
    RUN_MESH("roots", "banyan_roots_generate", "start inside", "germination at the host's centre",
             BANYAN_E_START_INSIDE, "inside hosts[0]", test_roots_boxes(&g, &h, 1, &m, &e));
    g.germination[0] = 0.3; /* on the face */
    RUN_MESH("roots", "banyan_roots_generate", "start inside", "germination on the host's face", BANYAN_E_START_INSIDE,
             "inside hosts[0]", test_roots_boxes(&g, &h, 1, &m, &e));
    g.germination[0] = 1, g.germination[2] = -0.5;
    RUN_MESH("roots", "banyan_roots_generate", "start inside", "germination below the ground", BANYAN_E_START_INSIDE,
             "below the ground", test_roots_boxes(&g, &h, 1, &m, &e));
    g.germination[0] = 5000, g.germination[2] = 3;
    RUN_MESH("roots", "banyan_roots_generate", "start far", "germination 5 km from the host", BANYAN_E_START_FAR,
             "germination", test_roots_boxes(&g, &h, 1, &m, &e));
    banyan_box below = banyan_box_make(0, 0, 1, 0.3, 0.3, 1), above = banyan_box_make(0, 0, 2.5, 1, 1, 0.5);
    banyan_box stack[2] = {below, above};
    RUN_MESH("roots", "banyan_roots_generate", "start inside", "auto germination under another host",
             BANYAN_E_START_INSIDE, "inside hosts[1]", test_roots_boxes(&rp, stack, 2, &m, &e));

    banyan_ivy_params is = ip;
    is.start[0] = 0, is.start[1] = 40, is.start[2] = 1;
    RUN_MESH("ivy", "banyan_ivy_generate", "start far", "start 40 m from the wall", BANYAN_E_START_FAR, "start",
             test_ivy_boxes(&is, &w, 1, &m, &e));
    is.start[1] = 0.1; /* the wall's centre */
    RUN_MESH("ivy", "banyan_ivy_generate", "start inside", "start inside the wall (repaired: snapped to its surface)",
             BANYAN_OK, NULL, test_ivy_boxes(&is, &w, 1, &m, &e));
}

/* Vertex and count limits: refused with BANYAN_E_LIMIT, nothing returned. */
static void limit_cases(void) {
    banyan_box h = trunk_host(), w = wall_host();
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    rp.max_vertices = 1;
    RUN_MESH("roots", "banyan_roots_generate", "limit", "max_vertices = 1", BANYAN_E_LIMIT, "max_vertices",
             test_roots_boxes(&rp, &h, 1, &m, &e));
    banyan_roots_params_init(&rp);
    rp.growth_points = 10000, rp.main_roots = 64, rp.sides = 256;
    RUN_MESH("roots", "banyan_roots_generate", "limit", "growth_points 10000 x main_roots 64 x sides 256 (default cap)",
             BANYAN_E_LIMIT, "max_vertices", test_roots_boxes(&rp, &h, 1, &m, &e));

    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    kp.max_vertices = 1;
    RUN_MESH("keyaki", "banyan_keyaki_generate", "limit", "max_vertices = 1", BANYAN_E_LIMIT, "max_vertices",
             banyan_keyaki_generate(&kp, &m, NULL, NULL, &e));
    banyan_keyaki_params_init(&kp);
    kp.max_nodes = 10;
    RUN_MESH("keyaki", "banyan_keyaki_generate", "limit", "max_nodes = 10", BANYAN_E_LIMIT, "max_nodes",
             banyan_keyaki_generate(&kp, &m, NULL, NULL, &e));
    banyan_keyaki_params_init(&kp);
    kp.model = BANYAN_KEYAKI_SIMPLE, kp.levels = 30;
    RUN_MESH("keyaki", "banyan_keyaki_generate", "limit", "model simple, levels 30 (2^31 branches)", BANYAN_E_LIMIT,
             "max_nodes", banyan_keyaki_generate(&kp, &m, NULL, NULL, &e));

    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    ap.placement = BANYAN_AVENUE_COUNT, ap.count = 5000, ap.max_vertices = 1000;
    RUN_MESH("avenue", "banyan_avenue_generate", "limit", "10000 trees, max_vertices = 1000", BANYAN_E_LIMIT,
             "max_vertices", banyan_avenue_generate(&ap, NULL, 0, &m, NULL, &e));
    banyan_avenue_params_init(&ap);
    ap.spacing = 0.1, ap.end[0] = 1000;
    RUN_MESH("avenue", "banyan_avenue_generate", "above cap", "spacing 0.1 m on 1 km (20002 trees)", BANYAN_E_LIMIT,
             "trees", banyan_avenue_generate(&ap, NULL, 0, &m, NULL, &e));

    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    ip.max_vertices = 1;
    RUN_MESH("ivy", "banyan_ivy_generate", "limit", "max_vertices = 1", BANYAN_E_LIMIT, "max_vertices",
             test_ivy_boxes(&ip, &w, 1, &m, &e));
    banyan_ivy_params_init(&ip);
    ip.steps = BANYAN_IVY_MAX_STEPS, ip.max_vertices = 20000, ip.t0 = 1e6;
    RUN_MESH("ivy", "banyan_ivy_generate", "limit", "steps = 100000, max_vertices = 20000", BANYAN_E_LIMIT,
             "max_vertices", test_ivy_boxes(&ip, &w, 1, &m, &e));
    banyan_ivy_params_init(&ip);
    ip.max_buds = 5;
    RUN_MESH("ivy", "banyan_ivy_generate", "limit", "max_buds = 5", BANYAN_E_LIMIT, "max_buds",
             test_ivy_boxes(&ip, &w, 1, &m, &e));

    banyan_segments_params sp;
    banyan_segments_params_init(&sp);
    sp.max_vertices = 1;
    RUN_MESH("segments", "banyan_segments_generate", "limit", "max_vertices = 1", BANYAN_E_LIMIT, "max_vertices",
             banyan_segments_generate(&sp, demo_segs, 2, NULL, &m, NULL, NULL, &e));
    banyan_segments_params_init(&sp);
    float xyz[3 * 8];
    uint32_t nv = 0;
    RUN("segments", "banyan_segments_lines", "limit", "cap = 8, too small", BANYAN_E_LIMIT, "cap",
        banyan_segments_lines(&sp, demo_segs, 2, NULL, xyz, NULL, 8, &nv, &e), nv > 8);

}

/* NULL pointers at every entry point that takes one. */
static void null_cases(void) {
    banyan_box h = trunk_host(), w = wall_host();
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    banyan_segments_params sp;
    banyan_segments_params_init(&sp);

    RUN_MESH("roots", "banyan_roots_generate", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
             test_roots_boxes(NULL, &h, 1, &m, &e));
    RUN("roots", "banyan_roots_generate", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        test_roots_boxes(&rp, &h, 1, NULL, &e), 1);
    RUN_MESH("keyaki", "banyan_keyaki_generate", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
             banyan_keyaki_generate(NULL, &m, NULL, NULL, &e));
    RUN("keyaki", "banyan_keyaki_generate", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_keyaki_generate(&kp, NULL, NULL, NULL, &e), 1);
    RUN("keyaki", "banyan_keyaki_skeleton_stats", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_keyaki_skeleton_stats(&kp, NULL, &e), 1);
    banyan_keyaki_stats kst;
    RUN("keyaki", "banyan_keyaki_skeleton_stats", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_keyaki_skeleton_stats(NULL, &kst, &e), 1);
    RUN_MESH("avenue", "banyan_avenue_generate", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
             banyan_avenue_generate(NULL, NULL, 0, &m, NULL, &e));
    RUN("avenue", "banyan_avenue_generate", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_avenue_generate(&ap, NULL, 0, NULL, NULL, &e), 1);
    uint32_t n = 0;
    RUN("avenue", "banyan_avenue_layout", "NULL", "tree_count = NULL", BANYAN_E_INVALID_ARG, "tree_count",
        banyan_avenue_layout(&ap, NULL, 0, NULL, 0, NULL, &e), 1);
    RUN("avenue", "banyan_avenue_layout", "NULL", "trees = NULL, capacity = 4", BANYAN_E_INVALID_ARG, "trees",
        banyan_avenue_layout(&ap, NULL, 0, NULL, 4, &n, &e), 1);
    banyan_keyaki_params few[2];
    RUN("avenue", "banyan_avenue_layout", "above cap", "capacity = 2 for 16 trees", BANYAN_E_INVALID_ARG, "capacity",
        banyan_avenue_layout(&ap, NULL, 0, few, 2, &n, &e), n == 16);
    RUN_MESH("ivy", "banyan_ivy_generate", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
             test_ivy_boxes(NULL, &w, 1, &m, &e));
    RUN("ivy", "banyan_ivy_generate", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        test_ivy_boxes(&ip, &w, 1, NULL, &e), 1);
    banyan_hosts *hs = TEST_HOSTS(&w, 1);
    RUN("ivy", "banyan_ivy_create", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_ivy_create(&ip, hs, NULL, &e), 1);
    RUN("ivy", "banyan_ivy_step", "NULL", "ivy = NULL", BANYAN_E_INVALID_ARG, "ivy", banyan_ivy_step(NULL, 1, &e), 1);
    RUN_MESH("ivy", "banyan_ivy_mesh", "NULL", "ivy = NULL", BANYAN_E_INVALID_ARG, "ivy", banyan_ivy_mesh(NULL, &m, &e));
    banyan_ivy_stats ist;
    RUN("ivy", "banyan_ivy_get_stats", "NULL", "ivy = NULL", BANYAN_E_INVALID_ARG, "ivy",
        banyan_ivy_get_stats(NULL, &ist, &e), 1);
    /* A progress struct without its callback. */
    banyan_progress no_fn = {NULL, NULL};
    RUN_MESH("roots", "banyan_roots_generate", "NULL", "progress->fn = NULL", BANYAN_E_INVALID_ARG,
             "progress->fn", banyan_roots_generate(&rp, hs, &m, NULL, &no_fn, &e));
    RUN_MESH("ivy", "banyan_ivy_generate", "NULL", "progress->fn = NULL", BANYAN_E_INVALID_ARG, "progress->fn",
             banyan_ivy_generate(&ip, hs, &m, &ist, &no_fn, &e));
    RUN_MESH("ivy", "banyan_ivy_generate", "NULL", "params = NULL, stats", BANYAN_E_INVALID_ARG, "params",
             banyan_ivy_generate(NULL, hs, &m, &ist, NULL, &e));
    RUN_MESH("avenue", "banyan_avenue_generate", "NULL", "progress->fn = NULL", BANYAN_E_INVALID_ARG, "progress->fn",
             banyan_avenue_generate(&ap, NULL, 0, &m, &no_fn, &e));
    banyan_hosts_free(hs);
    RUN_MESH("segments", "banyan_segments_generate", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
             banyan_segments_generate(NULL, demo_segs, 2, NULL, &m, NULL, NULL, &e));
    RUN_MESH("segments", "banyan_segments_generate", "NULL", "segs = NULL, count = 2", BANYAN_E_INVALID_ARG, "segs",
             banyan_segments_generate(&sp, NULL, 2, NULL, &m, NULL, NULL, &e));
    RUN("segments", "banyan_segments_generate", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_segments_generate(&sp, demo_segs, 2, NULL, NULL, NULL, NULL, &e), 1);
    RUN("segments", "banyan_segments_lines", "NULL", "n_vertices = NULL", BANYAN_E_INVALID_ARG, "n_vertices",
        banyan_segments_lines(&sp, demo_segs, 2, NULL, NULL, NULL, 0, NULL, &e), 1);
    RUN("segments", "banyan_segments_find_unattached", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_segments_find_unattached(NULL, demo_segs, 2, NULL, NULL, &n, &e), 1);
    RUN("segments", "banyan_segments_demo", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_segments_demo(&sp, NULL, 0, &n, NULL, &e), 1);
    float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
    int32_t cnt = 7;
    banyan_segment_params sgp;
    banyan_segment_params_init(&sgp);
    RUN("segments", "banyan_segment_lines", "NULL", "in = NULL", BANYAN_E_INVALID_ARG, "input",
        banyan_segment_lines(NULL, &sgp, xyz, NULL, &cnt, &e), cnt == 0);
    RUN("segments", "banyan_segment_lines", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_segment_lines(&demo_segs[0], NULL, xyz, NULL, &cnt, &e), 1);
    RUN("segments", "banyan_segment_lines", "NULL", "out_xyz = NULL", BANYAN_E_INVALID_ARG, "out_xyz",
        banyan_segment_lines(&demo_segs[0], &sgp, NULL, NULL, &cnt, &e), 1);
    RUN("segments", "banyan_segment_lines_many", "NULL", "ins = NULL, count = 3", BANYAN_E_INVALID_ARG, "ins",
        banyan_segment_lines_many(NULL, 3, &sgp, xyz, NULL, &cnt, &e), 1);
    RUN("segments", "banyan_segment_uniforms", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_segment_uniforms(&sgp, NULL, &e), 1);
    RUN("segments", "banyan_segment_check", "NULL", "in = NULL", BANYAN_E_INVALID_ARG, "input",
        banyan_segment_check(NULL, &sgp, &e), 1);

    /* Shared calls. */
    double pts[6] = {0, 0, 0, 0, 0, 1}, radii[2] = {0.1, 0.1};
    RUN_MESH("common", "banyan_tube_generate", "NULL", "points = NULL", BANYAN_E_INVALID_ARG, "points",
             banyan_tube_generate(NULL, radii, 2, 8, 1, &m, &e));
    RUN_MESH("common", "banyan_tube_generate", "NULL", "radii = NULL", BANYAN_E_INVALID_ARG, "radii",
             banyan_tube_generate(pts, NULL, 2, 8, 1, &m, &e));
    RUN("common", "banyan_tube_generate", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_tube_generate(pts, radii, 2, 8, 1, NULL, &e), 1);
    RUN("common", "banyan_params_check", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_params_check(BANYAN_GEN_ROOTS, NULL, &e), 1);
    RUN("common", "banyan_params_check", "above range", "generator = 99", BANYAN_E_INVALID_ARG, "generator",
        banyan_params_check((banyan_generator)99, &rp, &e), 1);
    RUN("common", "banyan_param_set_text", "NULL", "key = NULL", BANYAN_E_INVALID_ARG, "key",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, NULL, "1", &e), 1);
    RUN("common", "banyan_param_set_text", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_param_set_text(BANYAN_GEN_ROOTS, NULL, "sides", "8", &e), 1);
    RUN("common", "banyan_param_set_text", "above range", "generator = 99", BANYAN_E_INVALID_ARG, "generator",
        banyan_param_set_text((banyan_generator)99, &rp, "sides", "8", &e), 1);
    RUN("common", "banyan_param_set_text", "unknown key", "key = 'colour'", BANYAN_E_UNKNOWN_KEY, "colour",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "colour", "1", &e), 1);
    RUN("common", "banyan_param_set_text", "wrong type", "sides = 'eight'", BANYAN_E_TYPE, "sides",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "sides", "eight", &e), rp.sides == 8);
    RUN("common", "banyan_param_set_text", "NaN", "radius = 'nan'", BANYAN_E_RANGE, "radius",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", "nan", &e), rp.radius == 0.8);
    RUN("common", "banyan_param_set_text", "inf", "unit = '1e400'", BANYAN_E_RANGE, "unit",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "unit", "1e400", &e), 1);
    RUN("common", "banyan_param_set_text", "wrong type", "sides = '0x10' (hexadecimal)", BANYAN_E_TYPE, "sides",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "sides", "0x10", &e), rp.sides == 8);
    RUN("common", "banyan_param_set_text", "wrong type", "sides = '8.5'", BANYAN_E_TYPE, "sides",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "sides", "8.5", &e), 1);
    RUN("common", "banyan_param_set_text", "above range", "sides = '4294967304' (beyond int32)", BANYAN_E_RANGE,
        "sides", banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "sides", "4294967304", &e), rp.sides == 8);
    RUN("common", "banyan_param_set_text", "wrong type", "seed = '-1'", BANYAN_E_TYPE, "seed",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "seed", "-1", &e), 1);
    /* Whole tokens in the C locale's spelling, nothing around them. */
    RUN("common", "banyan_param_set_text", "wrong type", "seed = ' -1' (a space before)", BANYAN_E_TYPE, "seed",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "seed", " -1", &e), 1);
    RUN("common", "banyan_param_set_text", "wrong type", "seed = '+1'", BANYAN_E_TYPE, "seed",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "seed", "+1", &e), 1);
    RUN("common", "banyan_param_set_text", "wrong type", "radius = '0,5' (a decimal comma)", BANYAN_E_TYPE, "radius",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", "0,5", &e), rp.radius == 0.8);
    RUN("common", "banyan_param_set_text", "wrong type", "radius = ' 0.5' (a space before)", BANYAN_E_TYPE, "radius",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", " 0.5", &e), rp.radius == 0.8);
    RUN("common", "banyan_param_set_text", "wrong type", "radius = '0.5 ' (a space after)", BANYAN_E_TYPE, "radius",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", "0.5 ", &e), rp.radius == 0.8);
    RUN("common", "banyan_param_set_text", "wrong type", "seed = '18446744073709551616' (2^64)", BANYAN_E_TYPE, "seed",
        banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "seed", "18446744073709551616", &e), 1);
    RUN("common", "banyan_param_set_text", "wrong type", "germination = '1,2' (two of three)", BANYAN_E_TYPE,
        "germination", banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "germination", "1,2", &e), 1);
    RUN("common", "banyan_param_set_text", "above range", "model = 'oak'", BANYAN_E_RANGE, "model",
        banyan_param_set_text(BANYAN_GEN_KEYAKI, &kp, "model", "oak", &e), 1);
    RUN("common", "banyan_mesh_corner_uvs", "NULL", "mesh = NULL", BANYAN_E_INVALID_ARG, "mesh",
        banyan_mesh_corner_uvs(NULL, xyz, 6, &e), 1);
    RUN("common", "banyan_gltf_write", "NULL", "path = NULL", BANYAN_E_INVALID_ARG, "path",
        banyan_gltf_write(NULL, NULL, NULL, 1, &e), 1);
    RUN("common", "banyan_gltf_write", "NULL", "meshes = NULL", BANYAN_E_INVALID_ARG, "meshes",
        banyan_gltf_write("x.glb", NULL, NULL, 1, &e), 1);
    const banyan_mesh *none = NULL;
    RUN("common", "banyan_gltf_write", "NULL", "meshes[0] = NULL", BANYAN_E_INVALID_ARG, "meshes[0]",
        banyan_gltf_write("x.glb", &none, NULL, 1, &e), 1);
    RUN("common", "banyan_gltf_write", "zero", "count = 0", BANYAN_E_INVALID_ARG, "count",
        banyan_gltf_write("x.glb", &none, NULL, 0, &e), 1);

    /* Calls on a real mesh. */
    banyan_mesh *tube = NULL;
    banyan_error te;
    if (banyan_tube_generate(pts, radii, 2, 8, 1, &tube, &te) == BANYAN_OK) {
        float few[4];
        RUN("common", "banyan_mesh_corner_uvs", "below range", "out_count = 4, too small", BANYAN_E_RANGE, "out_count",
            banyan_mesh_corner_uvs(tube, few, 4, &e), 1);
        const banyan_mesh *one = tube;
        RUN("common", "banyan_gltf_write", "NULL", "a directory that does not exist", BANYAN_E_IO, "/no/such/dir",
            banyan_gltf_write("/no/such/dir/x.glb", &one, NULL, 1, &e), 1);
        RUN("common", "banyan_gltf_write", "wrong type", "path ending in .obj", BANYAN_E_INVALID_ARG, ".glb",
            banyan_gltf_write("x.obj", &one, NULL, 1, &e), 1);
        const char *bad_name = "\xff\xfe";
        RUN("common", "banyan_gltf_write", "non-UTF-8", "node name ff fe", BANYAN_E_INVALID_ARG, "names[0]",
            banyan_gltf_write("x.glb", &one, &bad_name, 1, &e), 1);
        uint32_t keep = tube->indices[0];
        tube->indices[0] = tube->vertex_count; /* a corrupted mesh from a caller */
        RUN("common", "banyan_gltf_write", "above range", "indices[0] = vertex_count", BANYAN_E_RANGE, "indices[0]",
            banyan_gltf_write("x.glb", &one, NULL, 1, &e), 1);
        tube->indices[0] = keep;
        float keep_p = tube->positions[4];
        tube->positions[4] = NAN;
        RUN("common", "banyan_gltf_write", "NaN", "positions[4] = NaN", BANYAN_E_RANGE, "positions",
            banyan_gltf_write("x.glb", &one, NULL, 1, &e), 1);
        tube->positions[4] = keep_p;
        /* Texture options and a material's texture fields. */
        banyan_gltf_options go;
        struct { const char *klass, *input, *needle; int32_t textures, size; } opt_rows[] = {
            {"zero", "opt->texture_size = 0", "texture_size", 1, 0},
            {"not a power of two", "opt->texture_size = 100", "texture_size", 1, 100},
            {"above range", "opt->texture_size = 16384", "texture_size", 1, 16384},
            {"below range", "opt->texture_size = 32", "texture_size", 1, 32},
            {"above range", "opt->textures = 2", "textures", 2, 1024},
        };
        for (size_t i = 0; i < sizeof opt_rows / sizeof opt_rows[0]; i++) {
            banyan_gltf_options_init(&go);
            go.textures = opt_rows[i].textures;
            go.texture_size = opt_rows[i].size;
            RUN("common", "banyan_gltf_write_ex", opt_rows[i].klass, opt_rows[i].input, BANYAN_E_RANGE,
                opt_rows[i].needle, banyan_gltf_write_ex("x.glb", &one, NULL, 1, &go, &e), 1);
        }
        banyan_gltf_options_init(&go);
        int32_t keep_t = tube->materials[0].texture;
        tube->materials[0].texture = BANYAN_TEX_COUNT;
        RUN("common", "banyan_gltf_write_ex", "above range", "materials[0].texture = 6", BANYAN_E_RANGE,
            "materials[0].texture", banyan_gltf_write_ex("x.glb", &one, NULL, 1, &go, &e), 1);
        tube->materials[0].texture = keep_t;
        tube->materials[0].season = 2;
        RUN("common", "banyan_gltf_write_ex", "above range", "materials[0].season = 2", BANYAN_E_RANGE,
            "materials[0].season", banyan_gltf_write_ex("x.glb", &one, NULL, 1, &go, &e), 1);
        tube->materials[0].season = 0;
        tube->materials[0].alpha_cutoff = NAN;
        RUN("common", "banyan_gltf_write_ex", "NaN", "materials[0].alpha_cutoff = NaN", BANYAN_E_RANGE,
            "alpha_cutoff", banyan_gltf_write_ex("x.glb", &one, NULL, 1, &go, &e), 1);
        tube->materials[0].alpha_cutoff = 0;
        banyan_mesh_free(tube);
    } else {
        CHECK(0, "tube: %s", te.message);
    }

    /* Functions without a status answer NULL or -1, and do not crash. */
    CHECK(banyan_generator_name((banyan_generator)-1) == NULL && banyan_generator_name(BANYAN_GEN_COUNT) == NULL,
          "generator names out of range");
    CHECK(banyan_generator_from_name(NULL) == -1 && banyan_generator_from_name("oak") == -1, "unknown names");
    CHECK(banyan_param_get(BANYAN_GEN_ROOTS, -1) == NULL && banyan_param_get(BANYAN_GEN_ROOTS, 100000) == NULL &&
              banyan_param_get((banyan_generator)77, 0) == NULL && banyan_param_count((banyan_generator)77) == 0,
          "param_get out of range");
    CHECK(banyan_param_find(BANYAN_GEN_ROOTS, NULL) == NULL && banyan_param_find(BANYAN_GEN_ROOTS, "") == NULL,
          "param_find NULL");
    CHECK(banyan_mesh_attribute(NULL, "x") == NULL, "mesh_attribute NULL");
    CHECK(banyan_segment_vertex_count(-1, 0) == -1 && banyan_segment_vertex_count(64, 0) == -1 &&
              banyan_segment_vertex_count(0, 65) == -1 && banyan_segment_vertex_count(0, -1) == -1,
          "segment_vertex_count out of range");
    CHECK(banyan_segment_shader_source(3) == NULL && banyan_segment_shader_source(-1) == NULL, "shader stage");
    CHECK(strcmp(banyan_status_name((banyan_status)99), "BANYAN_E_UNKNOWN_STATUS") == 0, "status name");
    banyan_mesh_free(NULL);
    banyan_ivy_free(NULL);
    banyan_roots_params_init(NULL);
    banyan_keyaki_params_init(NULL);
    /* A NULL err is allowed everywhere. */
    CHECK(test_roots_boxes(NULL, &h, 1, NULL, NULL) == BANYAN_E_INVALID_ARG, "NULL err");
    CHECK(banyan_ivy_generate(&ip, NULL, NULL, NULL, NULL, NULL) == BANYAN_E_INVALID_ARG, "NULL err, NULL out");
}

/* Inputs beyond the params tables: paths, segment inputs, tubes, steps. */
static void input_cases(void) {
    banyan_avenue_params ap;
    banyan_avenue_params_init(&ap);
    double path[9] = {0, 0, 0, 30, 0, 0, 60, 5, 0};
    double bad[9];
#define AV(klass, text, expr, count, want, needle)                                                   \
    memcpy(bad, path, sizeof bad);                                                                   \
    expr;                                                                                            \
    RUN_MESH("avenue", "banyan_avenue_generate", klass, text, want, needle,                          \
             banyan_avenue_generate(&ap, bad, count, &m, NULL, &e))
    AV("NaN", "path point 1 = (NaN, 0, 0)", bad[3] = NAN, 3, BANYAN_E_RANGE, "path point 1");
    AV("inf", "path point 2 z = inf", bad[8] = INFINITY, 3, BANYAN_E_RANGE, "path point 2");
    AV("above range", "path point 0 x = 1e7", bad[0] = 1e7, 3, BANYAN_E_RANGE, "path point 0");
    AV("below range", "path_point_count = 1", (void)0, 1, BANYAN_E_RANGE, "path_point_count");
    AV("above cap", "path_point_count = 1000001", (void)0, 1000001, BANYAN_E_RANGE, "path_point_count");
    AV("zero", "path point 1 repeats point 0", memcpy(bad + 3, bad, 3 * sizeof(double)), 3, BANYAN_E_RANGE,
       "repeats");
#undef AV
    banyan_avenue_params z = ap;
    memcpy(z.end, z.start, sizeof z.end);
    RUN_MESH("avenue", "banyan_avenue_generate", "zero", "start = end (no path)", BANYAN_E_RANGE, "start and end",
             banyan_avenue_generate(&z, NULL, 0, &m, NULL, &e));
    banyan_avenue_params th = ap;
    th.threads = -1;
    RUN_MESH("avenue", "banyan_avenue_generate", "negative", "threads = -1", BANYAN_E_RANGE, "threads",
             banyan_avenue_generate(&th, NULL, 0, &m, NULL, &e));
    th.threads = 65;
    RUN_MESH("avenue", "banyan_avenue_generate", "above cap", "threads = 65", BANYAN_E_RANGE, "threads",
             banyan_avenue_generate(&th, NULL, 0, &m, NULL, &e));
    banyan_avenue_params cross = ap;
    cross.tree.sides_min = 20, cross.tree.sides_max = 10;
    RUN_MESH("avenue", "banyan_avenue_generate", "inconsistent", "tree.sides_min 20 > tree.sides_max 10",
             BANYAN_E_RANGE, "sides_min", banyan_avenue_generate(&cross, NULL, 0, &m, NULL, &e));

    /* Cross-field rules. */
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    banyan_box h = trunk_host(), w = wall_host();
    rp.forward_min = 5, rp.forward_max = 1;
    RUN_MESH("roots", "banyan_roots_generate", "inconsistent", "forward_min 5 > forward_max 1", BANYAN_E_RANGE,
             "forward_min", test_roots_boxes(&rp, &h, 1, &m, &e));
    banyan_roots_params_init(&rp);
    rp.sides = 7;
    RUN_MESH("roots", "banyan_roots_generate", "inconsistent", "sides = 7 (odd)", BANYAN_E_RANGE, "sides",
             test_roots_boxes(&rp, &h, 1, &m, &e));
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    kp.fork_angle = 80, kp.fork_angle_step = 5;
    RUN_MESH("keyaki", "banyan_keyaki_generate", "inconsistent", "fork_angle 80 + 5 per level leaves [0, 90]",
             BANYAN_E_RANGE, "fork_angle", banyan_keyaki_generate(&kp, &m, NULL, NULL, &e));
    banyan_keyaki_params_init(&kp);
    kp.tilt_mid = 90, kp.tilt_high = 45;
    RUN_MESH("keyaki", "banyan_keyaki_generate", "inconsistent", "tilt_mid 90 > tilt_high 45", BANYAN_E_RANGE,
             "tilt_mid", banyan_keyaki_generate(&kp, &m, NULL, NULL, &e));
    banyan_keyaki_params_init(&kp);
    kp.twigs_from_segments = 1, kp.levels = 4, kp.segment_levels = 4;
    RUN_MESH("keyaki", "banyan_keyaki_generate", "inconsistent", "segment_levels 4 >= levels 4", BANYAN_E_RANGE,
             "segment_levels", banyan_keyaki_generate(&kp, &m, NULL, NULL, &e));
    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    ip.t1 = 3, ip.t2 = 1;
    RUN_MESH("ivy", "banyan_ivy_generate", "inconsistent", "t2 1 < t1 3", BANYAN_E_RANGE, "t2",
             test_ivy_boxes(&ip, &w, 1, &m, &e));
    banyan_ivy_params_init(&ip);
    ip.stem_radius = 0.01, ip.stem_radius_max = 0.005;
    RUN_MESH("ivy", "banyan_ivy_generate", "inconsistent", "stem_radius_max < stem_radius", BANYAN_E_RANGE,
             "stem_radius_max", test_ivy_boxes(&ip, &w, 1, &m, &e));

    /* The ivy's stepping calls. */
    banyan_ivy_params_init(&ip);
    banyan_ivy *iv = NULL;
    banyan_error e0;
    banyan_hosts *wall_set = TEST_HOSTS(&w, 1);
    if (banyan_ivy_create(&ip, wall_set, &iv, &e0) == BANYAN_OK) {
        RUN("ivy", "banyan_ivy_step", "negative", "n = -1", BANYAN_E_RANGE, "n (steps)", banyan_ivy_step(iv, -1, &e), 1);
        RUN("ivy", "banyan_ivy_step", "above cap", "n = 100001", BANYAN_E_RANGE, "n (steps)",
            banyan_ivy_step(iv, BANYAN_IVY_MAX_STEPS + 1, &e), 1);
        RUN("ivy", "banyan_ivy_step", "below range", "n = INT32_MIN", BANYAN_E_RANGE, "n (steps)",
            banyan_ivy_step(iv, INT32_MIN, &e), 1);
        RUN("ivy", "banyan_ivy_get_stats", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
            banyan_ivy_get_stats(iv, NULL, &e), 1);
        RUN("ivy", "banyan_ivy_mesh", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out", banyan_ivy_mesh(iv, NULL, &e), 1);
        banyan_ivy_free(iv);
    } else {
        CHECK(0, "ivy create: %s", e0.message);
    }
    banyan_hosts_free(wall_set);

    /* Segment inputs. */
    banyan_segment_params sgp;
    banyan_segment_params_init(&sgp);
    struct {
        const char *klass, *text, *needle;
        banyan_segment_input in;
    } seg[] = {
        {"NaN", "S[1] = NaN", "S[1]", {{0, NAN, 0}, {0, 0, 1}, 1, 2, 1}},
        {"inf", "S[0] = inf", "S[0]", {{INFINITY, 0, 0}, {0, 0, 1}, 1, 2, 1}},
        {"above range", "S[2] = 1e13", "S[2]", {{0, 0, 1e13}, {0, 0, 1}, 1, 2, 1}},
        {"zero", "A = (0, 0, 0)", "A =", {{0, 0, 0}, {0, 0, 0}, 1, 2, 1}},
        {"NaN", "A[2] = NaN", "A[2]", {{0, 0, 0}, {0, 0, NAN}, 1, 2, 1}},
        {"huge", "A = (1e200, 1e200, 0): length overflows", "A =", {{0, 0, 0}, {1e200, 1e200, 0}, 1, 2, 1}},
        {"below range", "A length 1e-13", "A =", {{0, 0, 0}, {0, 0, 1e-13}, 1, 2, 1}},
        {"negative", "l = -1", "l", {{0, 0, 0}, {0, 0, 1}, -1, 2, 1}},
        {"NaN", "l = NaN", "l", {{0, 0, 0}, {0, 0, 1}, NAN, 2, 1}},
        {"negative", "n = -1", "n", {{0, 0, 0}, {0, 0, 1}, 1, -1, 1}},
        {"above cap", "n = 64", "n", {{0, 0, 0}, {0, 0, 1}, 1, 64, 1}},
        {"negative", "s = -1", "s", {{0, 0, 0}, {0, 0, 1}, 1, 2, -1}},
        {"above cap", "s = 65", "s", {{0, 0, 0}, {0, 0, 1}, 1, 2, 65}},
    };
    banyan_segments_params sp;
    banyan_segments_params_init(&sp);
    for (size_t i = 0; i < sizeof seg / sizeof seg[0]; i++) {
        RUN("segments", "banyan_segment_check", seg[i].klass, seg[i].text, BANYAN_E_RANGE, seg[i].needle,
            banyan_segment_check(&seg[i].in, &sgp, &e), 1);
        float xyz[3 * BANYAN_SEGMENT_MAX_VERTICES];
        int32_t cnt = 7;
        RUN("segments", "banyan_segment_lines", seg[i].klass, seg[i].text, BANYAN_E_RANGE, seg[i].needle,
            banyan_segment_lines(&seg[i].in, &sgp, xyz, NULL, &cnt, &e), cnt == 0);
        banyan_segment_input two[2] = {demo_segs[0], seg[i].in};
        char needle[48];
        snprintf(needle, sizeof needle, "segs[1].%s", seg[i].needle);
        RUN_MESH("segments", "banyan_segments_generate", seg[i].klass, seg[i].text, BANYAN_E_RANGE, needle,
                 banyan_segments_generate(&sp, two, 2, NULL, &m, NULL, NULL, &e));
        snprintf(needle, sizeof needle, "ins[1]");
        float *many = malloc(sizeof(float) * 3 * BANYAN_SEGMENT_MAX_VERTICES * 2);
        int32_t counts[2] = {7, 7};
        RUN("segments", "banyan_segment_lines_many", seg[i].klass, seg[i].text, BANYAN_E_RANGE, needle,
            banyan_segment_lines_many(two, 2, &sgp, many, NULL, counts, &e), 1);
        free(many);
    }
    struct {
        const char *klass, *text, *needle;
        banyan_segment_params p;
    } sgbad[] = {
        {"NaN", "alpha_deg = NaN", "alpha_deg", {NAN, 30, -30, 10, 10}},
        {"above range", "beta_deg = 400", "beta_deg", {40, 400, -30, 10, 10}},
        {"inf", "gamma_deg = -inf", "gamma_deg", {40, 30, -INFINITY, 10, 10}},
        {"zero", "m = 0", "m", {40, 30, -30, 10, 0}},
        {"negative", "m = -10", "m", {40, 30, -30, 10, -10}},
        {"NaN", "omega_deg = NaN", "omega_deg", {40, 30, -30, NAN, 10}},
    };
    for (size_t i = 0; i < sizeof sgbad / sizeof sgbad[0]; i++) {
        float u[9];
        RUN("segments", "banyan_segment_uniforms", sgbad[i].klass, sgbad[i].text, BANYAN_E_RANGE, sgbad[i].needle,
            banyan_segment_uniforms(&sgbad[i].p, u, &e), 1);
        RUN("segments", "banyan_segment_check", sgbad[i].klass, sgbad[i].text, BANYAN_E_RANGE, sgbad[i].needle,
            banyan_segment_check(&demo_segs[0], &sgbad[i].p, &e), 1);
    }
    RUN_MESH("segments", "banyan_segments_generate", "zero", "count = 0", BANYAN_E_RANGE, "count",
             banyan_segments_generate(&sp, demo_segs, 0, NULL, &m, NULL, NULL, &e));
    RUN_MESH("segments", "banyan_segments_generate", "above cap", "count = 2^22 + 1", BANYAN_E_RANGE, "count",
             banyan_segments_generate(&sp, demo_segs, BANYAN_SEGMENTS_MAX_COUNT + 1, NULL, &m, NULL, NULL, &e));
    float many1[3 * BANYAN_SEGMENT_MAX_VERTICES];
    int32_t c1 = 0;
    RUN("segments", "banyan_segment_lines_many", "above cap", "count = 2^24 + 1", BANYAN_E_RANGE, "count",
        banyan_segment_lines_many(demo_segs, (1u << 24) + 1, &sgp, many1, NULL, &c1, &e), 1);
    double trunk_nan[6] = {0, 0, 0, 0, NAN, 1}, trunk_zero[6] = {1, 1, 1, 1, 1, 1};
    RUN_MESH("segments", "banyan_segments_generate", "NaN", "trunk[4] = NaN", BANYAN_E_RANGE, "trunk[4]",
             banyan_segments_generate(&sp, demo_segs, 2, trunk_nan, &m, NULL, NULL, &e));
    RUN_MESH("segments", "banyan_segments_generate", "zero", "trunk start = end", BANYAN_E_RANGE, "trunk",
             banyan_segments_generate(&sp, demo_segs, 2, trunk_zero, &m, NULL, NULL, &e));
    banyan_segment_input flat[1] = {{{0, 0, 0}, {0, 0, 1}, 0, 0, 0}};
    RUN_MESH("segments", "banyan_segments_generate", "zero", "one segment of length 0 and no twigs", BANYAN_E_RANGE,
             "shorter", banyan_segments_generate(&sp, flat, 1, NULL, &m, NULL, NULL, &e));
    banyan_segment_input far[2] = {demo_segs[0], {{100, 0, 0}, {0, 0, 1}, 1, 2, 1}};
    banyan_segments_stats st;
    {
        banyan_mesh *m = SENTINEL;
        banyan_error e;
        memset(&e, 0, sizeof e);
        banyan_status s = banyan_segments_generate(&sp, far, 2, NULL, &m, &st, NULL, &e);
        int ok = s == BANYAN_OK && st.unattached == 1;
        report("segments", "banyan_segments_generate", "start far",
               "segment 100 m from every axis (reported in stats.unattached)", BANYAN_OK, NULL, s, &e,
               mesh_out_ok(m, s) && ok);
    }
    banyan_segment_input segbuf[4];
    double tr[6];
    uint32_t nd = 0;
    RUN("segments", "banyan_segments_demo", "above cap", "cap = 4 < demo_segments = 24", BANYAN_E_RANGE, "cap",
        banyan_segments_demo(&sp, segbuf, 4, &nd, tr, &e), nd == 0);

    /* The tube. */
    double pts[9] = {0, 0, 0, 0, 0, 1, 0, 1, 1}, radii[3] = {0.1, 0.1, 0.1};
    double bp[9], br[3];
#define TB(klass, text, expr, count, sides, caps, needle)                                            \
    memcpy(bp, pts, sizeof bp);                                                                      \
    memcpy(br, radii, sizeof br);                                                                    \
    expr;                                                                                            \
    RUN_MESH("common", "banyan_tube_generate", klass, text, BANYAN_E_RANGE, needle,                 \
             banyan_tube_generate(bp, br, count, sides, caps, &m, &e))
    TB("below range", "point_count = 1", (void)0, 1, 8, 1, "point_count");
    TB("above cap", "point_count = 1000001", (void)0, 1000001, 8, 1, "point_count");
    {
        /* 1e6 points x 257: refused before the points are even read. */
        banyan_mesh *m = SENTINEL;
        banyan_error e;
        memset(&e, 0, sizeof e);
        banyan_status s = banyan_tube_generate(pts, radii, 1000000, 256, 1, &m, &e);
        report("common", "banyan_tube_generate", "limit", "point_count = 1e6, sides = 256 (257M vertices)",
               BANYAN_E_LIMIT, "point_count", s, &e, mesh_out_ok(m, s));
    }
    TB("below range", "sides = 2", (void)0, 3, 2, 1, "sides");
    TB("above cap", "sides = 257", (void)0, 3, 257, 1, "sides");
    TB("above range", "caps = 2", (void)0, 3, 8, 2, "caps");
    TB("NaN", "points[1] y = NaN", bp[4] = NAN, 3, 8, 1, "points[1]");
    TB("inf", "points[2] z = inf", bp[8] = INFINITY, 3, 8, 1, "points[2]");
    TB("huge", "points[1] x = 1e300", bp[3] = 1e300, 3, 8, 1, "points[1]");
    TB("zero", "radii[1] = 0", br[1] = 0, 3, 8, 1, "radii[1]");
    TB("negative", "radii[0] = -1", br[0] = -1, 3, 8, 1, "radii[0]");
    TB("NaN", "radii[2] = NaN", br[2] = NAN, 3, 8, 1, "radii[2]");
    TB("zero", "points[1] repeats points[0]", memcpy(bp + 3, bp, 3 * sizeof(double)), 3, 8, 1, "points[1]");
#undef TB
}

/* ------------------------------------------------------------- presets */

/* Which readers a broken preset is tried on: the envelope (every reader
 * shares it), the params (banyan_preset_apply), the hosts. */
enum { ENV, PARAMS, HOSTS };

typedef struct bad_preset {
    int scope;
    const char *klass, *input;
    const char *text; /* NULL: read tests/data/bad_presets/<file> */
    const char *file;
    size_t len;       /* 0: strlen(text) */
    banyan_status want;
    const char *needle; /* "t.json:<line>:" where the parser knows it, and the key */
} bad_preset;

static void preset_cases(void) {
    static const bad_preset P[] = {
        {ENV, "empty", "empty file", "", NULL, 0, BANYAN_E_PARSE, "empty"},
        {ENV, "empty", "only whitespace", " \n\n ", NULL, 0, BANYAN_E_PARSE, "t.json:3: malformed"},
        {ENV, "truncated", "cut inside params", "{\"generator\": \"roots\",\n\"params\": {\"radius\": 0.", NULL, 0,
         BANYAN_E_PARSE, "t.json:2: malformed"},
        {ENV, "truncated", "cut after a key", "{\"generator\": \"roots\",\n\"params\"", NULL, 0, BANYAN_E_PARSE,
         "t.json:2:"},
        {ENV, "truncated", "roots_trunk.json cut inside true (line 8)", NULL, "truncated.json", 0, BANYAN_E_PARSE,
         "t.json:8: malformed"},
        {ENV, "truncated", "length cuts a valid text", "{\"generator\": \"roots\"}", NULL, 10, BANYAN_E_PARSE,
         "t.json:1: malformed"},
        {ENV, "syntax", "trailing comma", "{\"generator\": \"roots\",\n\"params\": {\"sides\": 8,}}", NULL, 0,
         BANYAN_E_PARSE, "t.json:2:"},
        {ENV, "syntax", "text after the object", "{\"generator\": \"roots\"}\n}", NULL, 0, BANYAN_E_PARSE,
         "t.json:2: text after"},
        {ENV, "wrong type", "a preset that is an array", "[1, 2]", NULL, 0, BANYAN_E_TYPE, "JSON object"},
        {ENV, "wrong type", "a preset that is a number", "42", NULL, 0, BANYAN_E_TYPE, "JSON object"},
        {ENV, "wrong type", "schema is a string", "{\"generator\": \"roots\",\n\"schema\": \"1\"}", NULL, 0,
         BANYAN_E_RANGE, "t.json:2: schema"},
        {PARAMS, "wrong type", "generator is a number", "{\"generator\": 3}", NULL, 0, BANYAN_E_TYPE, "generator"},
        {PARAMS, "wrong type", "params is an array", "{\"generator\": \"roots\",\n\"params\": [1]}", NULL, 0,
         BANYAN_E_TYPE, "t.json:2: params"},
        {PARAMS, "wrong type", "radius is a string", "{\"generator\": \"roots\",\n\"params\": {\n\"radius\": \"big\"}}",
         NULL, 0, BANYAN_E_TYPE, "t.json:3: radius"},
        {PARAMS, "wrong type", "sides is 8.5", "{\"generator\": \"roots\", \"params\": {\"sides\": 8.5}}", NULL, 0,
         BANYAN_E_TYPE, "sides"},
        {PARAMS, "wrong type", "hugging is 1, not true", "{\"generator\": \"roots\", \"params\": {\"hugging\": 1}}",
         NULL, 0, BANYAN_E_TYPE, "hugging"},
        {PARAMS, "wrong type", "color has 2 numbers", "{\"generator\": \"roots\", \"params\": {\"color\": [1, 0]}}",
         NULL, 0, BANYAN_E_TYPE, "color"},
        {PARAMS, "wrong type", "germination holds a string",
         "{\"generator\": \"roots\", \"params\": {\"germination\": [0, \"a\", 0]}}", NULL, 0, BANYAN_E_TYPE,
         "germination"},
        {PARAMS, "wrong type", "seed is negative", "{\"generator\": \"roots\", \"params\": {\"seed\": -3}}", NULL, 0,
         BANYAN_E_TYPE, "seed"},
        {ENV, "unknown key", "top-level 'colour'", "{\"generator\": \"roots\",\n\"colour\": 1}", NULL, 0,
         BANYAN_E_UNKNOWN_KEY, "t.json:2: unknown top-level key 'colour'"},
        {PARAMS, "unknown key", "param 'radious'", "{\"generator\": \"roots\", \"params\": {\n\n\"radious\": 1}}", NULL,
         0, BANYAN_E_UNKNOWN_KEY, "t.json:3: unknown roots parameter 'radious'"},
        {PARAMS, "unknown key", "a param given twice",
         "{\"generator\": \"roots\", \"params\": {\"sides\": 8,\n\"sides\": 6}}", NULL, 0, BANYAN_E_PARSE,
         "t.json:2: parameter 'sides' is given twice"},
        {ENV, "unknown key", "a top-level key given twice", "{\"generator\": \"roots\",\n\"generator\": \"ivy\"}", NULL,
         0, BANYAN_E_PARSE, "t.json:2: top-level key 'generator' is given twice"},
        {HOSTS, "unknown key", "host centre given twice",
         "{\"hosts\": [{\"half\": [1,1,1], \"center\": [0,0,0],\n\"center\": [5,0,0]}]}", NULL, 0, BANYAN_E_PARSE,
         "hosts[0].center is given twice"},
        {HOSTS, "unknown key", "host key 'size'", "{\"hosts\": [{\"half\": [1,1,1],\n\"size\": 2}]}", NULL, 0,
         BANYAN_E_TYPE, "hosts[0].size"},
        {HOSTS, "wrong type", "hosts is an object", "{\"hosts\": {}}", NULL, 0, BANYAN_E_TYPE, "array"},
        /* An explicit empty list is not the default hosts. */
        {HOSTS, "empty list", "hosts is []", "{\"hosts\": []}", NULL, 0, BANYAN_E_NO_HOSTS,
         "t.json:1: hosts is an empty list"},
        {HOSTS, "wrong type", "host without half", "{\"hosts\": [{\"center\": [0,0,0]}]}", NULL, 0, BANYAN_E_TYPE,
         "needs \"half\""},
        {HOSTS, "zero", "host half[1] = 0", "{\"hosts\": [{\"half\": [1, 0, 1]}]}", NULL, 0, BANYAN_E_BAD_HOST,
         "hosts[0].half[1]"},
        {HOSTS, "bad host", "host rotation scaled", "{\"hosts\": [{\"half\": [1,1,1], \"rotation\": [2,0,0,0,2,0,0,0,2]}]}",
         NULL, 0, BANYAN_E_BAD_HOST, "not orthonormal"},
        {PARAMS, "huge", "radius = 1e400", "{\"generator\": \"roots\",\n\"params\": {\"radius\": 1e400}}", NULL, 0,
         BANYAN_E_RANGE, "t.json:2: radius"},
        {PARAMS, "huge", "unit = -1e400", "{\"generator\": \"roots\",\n\"params\": {\"unit\": -1e400}}", NULL, 0,
         BANYAN_E_RANGE, "t.json:2: unit"},
        {PARAMS, "huge", "sides = 4294967304 (beyond int32)",
         "{\"generator\": \"roots\",\n\"params\": {\"sides\": 4294967304}}", NULL, 0, BANYAN_E_RANGE, "t.json:2: sides"},
        {PARAMS, "huge", "main_roots = -2147483649 (beyond int32)",
         "{\"generator\": \"roots\", \"params\": {\"main_roots\": -2147483649}}", NULL, 0, BANYAN_E_RANGE, "main_roots"},
        {PARAMS, "huge", "seed = 1e30", "{\"generator\": \"roots\", \"params\": {\"seed\": 1e30}}", NULL, 0,
         BANYAN_E_TYPE, "seed"},
        {HOSTS, "huge", "host half[0] = 1e400", "{\"hosts\": [{\"half\": [1e400, 1, 1]}]}", NULL, 0, BANYAN_E_BAD_HOST,
         "half[0]"},
        {PARAMS, "huge", "radius written with 401 digits", NULL, "long_number.json", 0, BANYAN_E_RANGE,
         "t.json:3: radius"},
        {ENV, "deep", "nesting 20 deep", "{\"description\":\n[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]}", NULL, 0,
         BANYAN_E_PARSE, "t.json:2: nesting"},
        {ENV, "deep", "nesting 100000 deep", NULL, "deep.json", 0, BANYAN_E_PARSE, "t.json:1: nesting"},
        {ENV, "non-UTF-8", "bytes ff fe in a string", "{\"description\": \"\xff\xfe\"}", NULL, 0, BANYAN_E_PARSE,
         "t.json:1: byte 17 is not valid UTF-8"},
        {ENV, "non-UTF-8", "a Latin-1 file", NULL, "latin1.json", 0, BANYAN_E_PARSE, "t.json:3: byte"},
        {ENV, "non-UTF-8", "an overlong '/' (c0 af)", "{\"description\": \"\xc0\xaf\"}", NULL, 0, BANYAN_E_PARSE,
         "UTF-8"},
        {ENV, "non-UTF-8", "overlong 3 bytes (e0 80 af)", "{\"description\": \"\xe0\x80\xaf\"}", NULL, 0,
         BANYAN_E_PARSE, "UTF-8"},
        {ENV, "non-UTF-8", "an encoded surrogate (ed a0 80)", "{\"description\": \"\xed\xa0\x80\"}", NULL, 0,
         BANYAN_E_PARSE, "UTF-8"},
        {ENV, "non-UTF-8", "beyond U+10FFFF (f4 90 80 80)", "{\"description\": \"\xf4\x90\x80\x80\"}", NULL, 0,
         BANYAN_E_PARSE, "UTF-8"},
        {ENV, "non-UTF-8", "UTF-16 with a BOM", NULL, "utf16.json", 0, BANYAN_E_PARSE, "t.json:1: byte 0"},
        {ENV, "non-UTF-8", "a NUL byte", "{\"generator\": \"roots\"\0}", NULL, 23, BANYAN_E_PARSE, "byte 21"},
        {ENV, "non-UTF-8", "a \\u0000 escape", "{\"generator\":\n\"roots\\u0000x\"}", NULL, 0, BANYAN_E_PARSE,
         "t.json:2: a \\u0000 escape"},
    };
    char *path = malloc(4096);
    for (size_t i = 0; i < sizeof P / sizeof P[0]; i++) {
        const char *text = P[i].text;
        char *owned = NULL;
        size_t len = P[i].len ? P[i].len : text ? strlen(text) : 0;
        if (!text) {
            snprintf(path, 4096, "%s/tests/data/bad_presets/%s", BANYAN_SOURCE_DIR, P[i].file);
            owned = test_read_file(path, &len);
            CHECK(owned != NULL, "read %s", path);
            if (!owned) continue;
            text = owned;
        }
        /* A heap copy of exactly len bytes: ASan sees any read past it. */
        char *exact = malloc(len ? len : 1);
        memcpy(exact, text, len);
        if (P[i].scope != HOSTS) {
            banyan_roots_params rp;
            banyan_roots_params_init(&rp);
            RUN("presets", "banyan_preset_apply", P[i].klass, P[i].input, P[i].want, P[i].needle,
                banyan_preset_apply(BANYAN_GEN_ROOTS, &rp, exact, len, "t.json", &e), 1);
        }
        if (P[i].scope != PARAMS) {
            banyan_box hosts[4];
            uint32_t n = 99;
            RUN("presets", "banyan_preset_hosts", P[i].klass, P[i].input, P[i].want, P[i].needle,
                banyan_preset_hosts(exact, len, "t.json", hosts, 4, &n, &e), n == 0);
        }
        if (P[i].scope == ENV) {
            banyan_segment_input segs[4];
            uint32_t n = 99;
            int32_t has = 7;
            RUN("presets", "banyan_segments_preset_read", P[i].klass, P[i].input, P[i].want, P[i].needle,
                banyan_segments_preset_read(exact, len, "t.json", segs, 4, &n, NULL, &has, &e), n == 0 && has == 0);
        }
        free(exact);
        free(owned);
    }
    free(path);

    /* Segment lists. */
    static const struct {
        const char *klass, *input, *text;
        banyan_status want;
        const char *needle;
    } S[] = {
        {"wrong type", "segments is an object", "{\"segments\": {}}", BANYAN_E_TYPE, "segments must be an array"},
        {"unknown key", "segment key 'len'",
         "{\"segments\": [\n{\"S\": [0,0,0], \"A\": [0,0,1], \"l\": 1, \"n\": 2, \"s\": 1, \"len\": 3}]}",
         BANYAN_E_UNKNOWN_KEY, "t.json:2: segments[0]: unknown key 'len'"},
        {"wrong type", "n = 2.5", "{\"segments\": [{\"S\": [0,0,0], \"A\": [0,0,1], \"l\": 1, \"n\": 2.5, \"s\": 1}]}",
         BANYAN_E_TYPE, "segments[0].n"},
        {"huge", "l = 1e400", "{\"segments\": [{\"S\": [0,0,0], \"A\": [0,0,1], \"l\": 1e400, \"n\": 2, \"s\": 1}]}",
         BANYAN_E_RANGE, "segments[0].l"},
        {"huge", "n = 1e10", "{\"segments\": [{\"S\": [0,0,0], \"A\": [0,0,1], \"l\": 1, \"n\": 1e10, \"s\": 1}]}",
         BANYAN_E_RANGE, "segments[0].n"},
        {"zero", "A = [0, 0, 0]", "{\"segments\": [{\"S\": [0,0,0], \"A\": [0,0,0], \"l\": 1, \"n\": 2, \"s\": 1}]}",
         BANYAN_E_RANGE, "segments[0].A"},
        {"truncated", "missing s", "{\"segments\": [{\"S\": [0,0,0], \"A\": [0,0,1], \"l\": 1, \"n\": 2}]}",
         BANYAN_E_PARSE, "needs \"s\""},
        {"wrong type", "trunk without end", "{\"trunk\": {\"start\": [0,0,0]}}", BANYAN_E_TYPE, "trunk"},
        {"unknown key", "top-level 'segmnets'", "{\"segmnets\": []}", BANYAN_E_UNKNOWN_KEY, "segmnets"},
        /* An explicit empty list is not the random demo tree. */
        {"empty list", "segments is []", "{\"segments\":\n[]}", BANYAN_E_RANGE, "t.json:2: segments is an empty list"},
    };
    for (size_t i = 0; i < sizeof S / sizeof S[0]; i++) {
        size_t len = strlen(S[i].text);
        char *exact = malloc(len);
        memcpy(exact, S[i].text, len);
        banyan_segment_input segs[4];
        uint32_t n = 99;
        RUN("presets", "banyan_segments_preset_read", S[i].klass, S[i].input, S[i].want, S[i].needle,
            banyan_segments_preset_read(exact, len, "t.json", segs, 4, &n, NULL, NULL, &e), n == 0);
        free(exact);
    }
    RUN("presets", "banyan_preset_apply", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_preset_apply(BANYAN_GEN_ROOTS, NULL, "{}", 2, "t.json", &e), 1);
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    RUN("presets", "banyan_preset_apply", "NULL", "text = NULL", BANYAN_E_INVALID_ARG, "text",
        banyan_preset_apply(BANYAN_GEN_ROOTS, &rp, NULL, 10, "t.json", &e), 1);
    RUN("presets", "banyan_preset_apply", "above range", "generator = 99", BANYAN_E_INVALID_ARG, "generator",
        banyan_preset_apply((banyan_generator)99, &rp, "{}", 2, "t.json", &e), 1);
    uint32_t n = 0;
    RUN("presets", "banyan_preset_hosts", "NULL", "count = NULL", BANYAN_E_INVALID_ARG, "count",
        banyan_preset_hosts("{}", 2, "t.json", NULL, 0, NULL, &e), 1);
    RUN("presets", "banyan_preset_hosts", "NULL", "out = NULL, cap = 4", BANYAN_E_INVALID_ARG, "out",
        banyan_preset_hosts("{}", 2, "t.json", NULL, 4, &n, &e), 1);
    const char *five = "{\"hosts\": [{\"half\": [1,1,1]}, {\"half\": [1,1,1]}, {\"half\": [1,1,1]}]}";
    banyan_box hb[2];
    RUN("presets", "banyan_preset_hosts", "above cap", "3 hosts, cap = 2", BANYAN_E_RANGE, "3 hosts",
        banyan_preset_hosts(five, strlen(five), "t.json", hb, 2, &n, &e), n == 0);
    RUN("presets", "banyan_segments_preset_read", "NULL", "count = NULL", BANYAN_E_INVALID_ARG, "count",
        banyan_segments_preset_read("{}", 2, "t.json", NULL, 0, NULL, NULL, NULL, &e), 1);
}

/* The shipped presets still load: the refusals above must not catch them. */
static void good_presets(void) {
    static const char *const names[] = {"roots_trunk", "roots_paper", "keyaki_mature", "avenue_street", "ivy_wall",
                                        "segments_paper"};
    static const banyan_generator gens[] = {BANYAN_GEN_ROOTS, BANYAN_GEN_ROOTS, BANYAN_GEN_KEYAKI, BANYAN_GEN_AVENUE,
                                            BANYAN_GEN_IVY, BANYAN_GEN_SEGMENTS};
    unsigned char params[4096];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, names[i]);
        size_t len = 0;
        char *text = test_read_file(path, &len);
        CHECK(text != NULL, "read %s", path);
        if (!text) continue;
        for (size_t g = 0; g < N_GENERATORS; g++)
            if (generators[g].g == gens[i]) generators[g].init(params);
        banyan_error e;
        CHECK(banyan_preset_apply(gens[i], params, text, len, names[i], &e) == BANYAN_OK, "%s: %s", names[i], e.message);
        banyan_box hosts[BANYAN_MAX_HOSTS];
        uint32_t n = 0;
        CHECK(banyan_preset_hosts(text, len, names[i], hosts, BANYAN_MAX_HOSTS, &n, &e) == BANYAN_OK, "%s hosts: %s",
              names[i], e.message);
        if (gens[i] == BANYAN_GEN_SEGMENTS)
            CHECK(banyan_segments_preset_read(text, len, names[i], NULL, 0, &n, NULL, NULL, &e) == BANYAN_OK && n > 0,
                  "%s segments: %s", names[i], e.message);
        free(text);
    }
}

/* Textures: size, kind, season; the two image out pointers
 * come back NULL. */
static int images_null(banyan_image *a, banyan_image *b) { return a == NULL && b == NULL; }

static void texture_cases(void) {
    static const struct {
        const char *klass, *input;
        int32_t kind, season, size;
        const char *needle;
    } rows[] = {
        {"zero", "size = 0", BANYAN_TEX_KEYAKI_LEAF, 0, 0, "size"},
        {"not a power of two", "size = 1000", BANYAN_TEX_KEYAKI_LEAF, 0, 1000, "power of two"},
        {"below range", "size = 32", BANYAN_TEX_IVY_LEAF, 0, 32, "[64, 8192]"},
        {"above range", "size = 16384", BANYAN_TEX_KEYAKI_BARK, 0, 16384, "[64, 8192]"},
        {"negative", "size = -1024", BANYAN_TEX_FIG_BARK, 0, -1024, "size"},
        {"above range", "kind = 7", 7, 0, 1024, "kind"},
        {"zero", "kind = 0 (BANYAN_TEX_NONE)", BANYAN_TEX_NONE, 0, 1024, "kind"},
        {"negative", "kind = -1", -1, 0, 1024, "kind"},
        {"above range", "season = 3", BANYAN_TEX_KEYAKI_LEAF, 3, 1024, "season"},
        {"negative", "season = -1", BANYAN_TEX_IVY_STEM, -1, 1024, "season"},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        banyan_texture_params p;
        banyan_texture_params_init(&p);
        p.kind = rows[i].kind;
        p.season = rows[i].season;
        p.size = rows[i].size;
        banyan_image *bc = SENTINEL, *nm = SENTINEL;
        RUN("textures", "banyan_texture_generate", rows[i].klass, rows[i].input, BANYAN_E_RANGE, rows[i].needle,
            banyan_texture_generate(&p, &bc, &nm, &e), images_null(bc, nm));
    }
    banyan_image *bc = SENTINEL, *nm = SENTINEL;
    RUN("textures", "banyan_texture_generate", "NULL", "params = NULL", BANYAN_E_INVALID_ARG, "params",
        banyan_texture_generate(NULL, &bc, &nm, &e), images_null(bc, nm));
    banyan_atlas_layout layout;
    RUN("textures", "banyan_texture_layout", "above range", "kind = 6", BANYAN_E_RANGE, "kind",
        banyan_texture_layout(BANYAN_TEX_COUNT, &layout, &e), 1);
    RUN("textures", "banyan_texture_layout", "NULL", "out = NULL", BANYAN_E_INVALID_ARG, "out",
        banyan_texture_layout(BANYAN_TEX_KEYAKI_LEAF, NULL, &e), 1);
    uint8_t *png = SENTINEL;
    size_t len = 1;
    RUN("textures", "banyan_image_png", "NULL", "image = NULL", BANYAN_E_INVALID_ARG, "image",
        banyan_image_png(NULL, &png, &len, &e), png == NULL && len == 0);
    uint8_t px[4] = {0, 0, 0, 0};
    banyan_image empty = {0, 0, 4, px};
    png = SENTINEL;
    RUN("textures", "banyan_image_png", "zero", "width = height = 0", BANYAN_E_RANGE, "width",
        banyan_image_png(&empty, &png, &len, &e), png == NULL);
}

int main(int argc, char **argv) {
    table_mode = argc > 1 && strcmp(argv[1], "--table") == 0;
    if (table_mode) {
        /* The JSON lines own stdout; CHECK failures and the summary go to stderr. */
        fflush(stdout);
    }
    field_sweep();
    host_cases();
    limit_cases();
    null_cases();
    input_cases();
    preset_cases();
    good_presets();
    texture_cases();
    if (table_mode) {
        fprintf(stderr, "test_bad_input: %d passed, %d failed\n", check_passed, check_failed);
        return check_failed ? 1 : 0;
    }
    return check_done("test_bad_input");
}
