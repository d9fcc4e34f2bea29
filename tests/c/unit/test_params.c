/* Parameter tables and presets: param_assign checks types and ranges,
 * --set text parsing through a test table, preset envelopes and hosts are
 * read or refused with source:line and the key. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "params/params.h"

typedef struct demo {
    double radius;
    int32_t sides;
    int32_t hugging;
    int32_t model;
    double offset[3];
    double colour[4];
    uint64_t seed;
} demo;

static const banyan_param_info rows[] = {
    BP_DOUBLE(demo, radius, "Radius", "Shape", "m", 0.001, 10, "tube radius"),
    BP_INT(demo, sides, "Sides", "Shape", 4, 64, "sides"),
    BP_BOOL(demo, hugging, "Hug", "Shape", "hug"),
    BP_ENUM(demo, model, "Model", "Shape", "simple|strong_weak|twisted|edaore", "model"),
    BP_VEC3(demo, offset, "Offset", "Shape", "m", -100, 100, "offset"),
    BP_COLOR(demo, colour, "Colour", "Shape", "colour"),
    BP_SEED(demo, seed, "Seed", "Shape", "seed"),
};

static banyan_status assign(int row, demo *d, const double *v, int n, banyan_error *e) {
    return param_assign(&rows[row], d, v, n, "x.json:3: ", e);
}

int main(void) {
    demo d;
    memset(&d, 0, sizeof d);
    banyan_error e;
    double v[4] = {0.5, 0, 0, 0};
    CHECK(assign(0, &d, v, 1, &e) == BANYAN_OK && d.radius == 0.5, "radius 0.5");
    v[0] = 11;
    CHECK(assign(0, &d, v, 1, &e) == BANYAN_E_RANGE && strstr(e.message, "x.json:3: radius = 11 must be within [0.001, 10] m"),
          "radius 11: %s", e.message);
    CHECK(d.radius == 0.5, "a refused value must leave the field unchanged");
    v[0] = NAN;
    CHECK(assign(0, &d, v, 1, &e) == BANYAN_E_RANGE && strstr(e.message, "finite"), "NaN: %s", e.message);
    v[0] = INFINITY;
    CHECK(assign(0, &d, v, 1, &e) == BANYAN_E_RANGE, "inf accepted");
    v[0] = 8.5;
    CHECK(assign(1, &d, v, 1, &e) == BANYAN_E_TYPE && strstr(e.message, "whole"), "sides 8.5: %s", e.message);
    v[0] = 2147483647;
    CHECK(assign(1, &d, v, 1, &e) == BANYAN_E_RANGE && strstr(e.message, "sides = 2147483647 must be within [4, 64]"),
          "whole numbers in full: %s", e.message);
    v[0] = 8;
    CHECK(assign(1, &d, v, 1, &e) == BANYAN_OK && d.sides == 8, "sides 8");
    v[0] = 4;
    CHECK(assign(3, &d, v, 1, &e) == BANYAN_E_RANGE && strstr(e.message, "simple|strong_weak"), "enum 4: %s", e.message);
    v[0] = 1; v[1] = 2; v[2] = 3;
    CHECK(assign(4, &d, v, 3, &e) == BANYAN_OK && d.offset[2] == 3, "vec3");
    CHECK(assign(4, &d, v, 2, &e) == BANYAN_E_TYPE, "vec3 with 2 numbers accepted");
    v[0] = 0.1; v[1] = 0.2; v[2] = 0.3;
    CHECK(assign(5, &d, v, 3, &e) == BANYAN_OK && d.colour[3] == 1.0, "rgb gets alpha 1");
    v[2] = 1.5;
    CHECK(assign(5, &d, v, 3, &e) == BANYAN_E_RANGE, "colour 1.5 accepted");
    CHECK(param_enum_index("simple|strong_weak|twisted|edaore", "twisted", 7) == 2, "enum index");
    CHECK(param_enum_index("simple|strong_weak", "strong", 6) == -1, "enum prefix must not match");

    /* Generator names round-trip. */
    for (int g = 0; g < BANYAN_GEN_COUNT; g++)
        CHECK(banyan_generator_from_name(banyan_generator_name((banyan_generator)g)) == g, "generator %d name", g);
    CHECK(banyan_generator_from_name("oak") == -1 && banyan_generator_name(BANYAN_GEN_COUNT) == NULL, "unknown generator");

    /* Preset hosts. */
    const char *ok = "{\n \"generator\": \"roots\",\n \"schema\": 1,\n \"hosts\": [\n"
                     "  {\"center\": [0, 0, 1], \"half\": [0.3, 0.3, 1]},\n"
                     "  {\"center\": [2, 0, 0.5], \"half\": [1, 0.5, 0.5], \"rotation_euler_deg\": [0, 0, 90]}\n ]\n}\n";
    banyan_box hosts[4];
    uint32_t n = 99;
    CHECK(banyan_preset_hosts(ok, strlen(ok), "ok.json", hosts, 4, &n, &e) == BANYAN_OK && n == 2, "hosts: %s", e.message);
    CHECK(n == 2 && fabs(hosts[1].rotation[0]) < 1e-12 && fabs(hosts[1].rotation[3] - 1) < 1e-12,
          "Euler Z 90 maps x to y");
    CHECK(banyan_preset_hosts(ok, strlen(ok), "ok.json", hosts, 1, &n, &e) == BANYAN_E_RANGE && n == 0, "cap 1: %s",
          e.message);

    struct { const char *text; banyan_status code; const char *needle; } bad[] = {
        {"", BANYAN_E_PARSE, "empty"},
        {"{\"generator\": \"roots\",\n \"hosts\": [", BANYAN_E_PARSE, "t.json:2: malformed"},
        {"[1, 2]", BANYAN_E_TYPE, "JSON object"},
        {"{\"generator\": \"roots\", \"colour\": 1}", BANYAN_E_UNKNOWN_KEY, "'colour'"},
        {"{\"generator\": \"roots\", \"schema\": 2}", BANYAN_E_RANGE, "schema"},
        {"{\"hosts\": [{\"center\": [0,0,0]}]}", BANYAN_E_TYPE, "needs \"half\""},
        {"{\"hosts\": [{\"center\": [0,0,0], \"half\": [1, 0, 1]}]}", BANYAN_E_BAD_HOST, "half[1]"},
        {"{\"hosts\": [{\"center\": [0,0], \"half\": [1,1,1]}]}", BANYAN_E_TYPE, "center"},
        {"{\"hosts\": [{\"half\": [1,1,1], \"size\": 2}]}", BANYAN_E_TYPE, "size"},
        {"{\"hosts\": {}}", BANYAN_E_TYPE, "array"},
        {"{\"hosts\": [{\"half\": [1e400, 1, 1]}]}", BANYAN_E_BAD_HOST, "half[0]"},
        {"{\"a\": [[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]}", BANYAN_E_PARSE, "nesting"},
        {"{\"description\": \"\xff\xfe\"}", BANYAN_E_PARSE, "UTF-8"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        banyan_status s = banyan_preset_hosts(bad[i].text, strlen(bad[i].text), "t.json", hosts, 4, &n, &e);
        CHECK(s == bad[i].code && strstr(e.message, bad[i].needle), "bad preset %zu: got %s '%s', want %s '%s'", i,
              banyan_status_name(s), e.message, banyan_status_name(bad[i].code), bad[i].needle);
    }
    /* The text need not be NUL-terminated: a prefix is parsed, not the rest. */
    const char *cut = "{\"hosts\": [{\"half\": [1, 1, 1]}]}garbage";
    CHECK(banyan_preset_hosts(cut, strlen(cut) - 7, "cut.json", hosts, 4, &n, &e) == BANYAN_OK && n == 1,
          "length-limited: %s", e.message);

    /* Applying a preset to the wrong generator is refused. */
    char params[64];
    const char *keyaki = "{\"generator\": \"keyaki\", \"params\": {}}";
    CHECK(banyan_preset_apply(BANYAN_GEN_ROOTS, params, keyaki, strlen(keyaki), "k.json", &e) == BANYAN_E_TYPE &&
              strstr(e.message, "must be \"roots\""), "wrong generator: %s", e.message);
    /* Every *_free accepts NULL (banyan.h, "Ownership"): these must not crash. */
    banyan_mesh_free(NULL);
    banyan_hosts_free(NULL);
    banyan_host_mesh_free(NULL);
    banyan_ivy_free(NULL);
    banyan_image_free(NULL);
    banyan_png_free(NULL);
    CHECK(1, "*_free(NULL)");
    return check_done("test_params");
}
