/* test_locale.c - numbers read (and glTF bytes come out) the same under a
 * comma-decimal locale: a host application such as Blender may set the
 * process locale, and strtod follows LC_NUMERIC ("0.5" reads as 0 under
 * de_DE). Needs de_DE.UTF-8 (tools/setup.sh generates it); without it the
 * test says so and is skipped (exit 77). */
#define _POSIX_C_SOURCE 200809L
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"

#define LOCALE "de_DE.UTF-8"

/* Every way text becomes a number in the library, under the current
 * locale; `how` names the locale for the messages. */
static void read_numbers(const char *how) {
    banyan_error e;
    banyan_roots_params rp;
    banyan_roots_params_init(&rp);
    CHECK(banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", "0.5", &e) == BANYAN_OK && rp.radius == 0.5,
          "%s: --set radius=0.5: %s (radius %g)", how, e.message, rp.radius);
    CHECK(banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", "2.5e-1", &e) == BANYAN_OK && rp.radius == 0.25,
          "%s: --set radius=2.5e-1: %s", how, e.message);
    CHECK(banyan_param_set_text(BANYAN_GEN_ROOTS, &rp, "radius", "0,5", &e) == BANYAN_E_TYPE, "%s: 0,5 read", how);
    banyan_ivy_params ip;
    banyan_ivy_params_init(&ip);
    CHECK(banyan_param_set_text(BANYAN_GEN_IVY, &ip, "start", "0.5, 1.25,-2.75", &e) == BANYAN_OK &&
              ip.start[0] == 0.5 && ip.start[1] == 1.25 && ip.start[2] == -2.75,
          "%s: start=0.5,1.25,-2.75: %s", how, e.message);
    const char *preset = "{\"generator\": \"roots\", \"params\": {\"radius\": 0.375, \"forward_max\": 1.5e0},"
                         " \"hosts\": [{\"center\": [0.5, 0, 0.25], \"half\": [0.75, 0.5, 1.5]}]}";
    banyan_roots_params_init(&rp);
    CHECK(banyan_preset_apply(BANYAN_GEN_ROOTS, &rp, preset, strlen(preset), "l.json", &e) == BANYAN_OK &&
              rp.radius == 0.375 && rp.forward_max == 1.5,
          "%s: preset params: %s (radius %g)", how, e.message, rp.radius);
    banyan_box b[2];
    uint32_t n = 0;
    CHECK(banyan_preset_hosts(preset, strlen(preset), "l.json", b, 2, &n, &e) == BANYAN_OK && n == 1 &&
              b[0].center[0] == 0.5 && b[0].half[0] == 0.75 && b[0].half[2] == 1.5,
          "%s: preset hosts: %s", how, e.message);
    const char *segs = "{\"segments\": [{\"S\": [0, 0, 0.5], \"A\": [0.25, 0, 1], \"l\": 1.5, \"n\": 2, \"s\": 1}]}";
    banyan_segment_input in[1];
    CHECK(banyan_segments_preset_read(segs, strlen(segs), "s.json", in, 1, &n, NULL, NULL, &e) == BANYAN_OK &&
              n == 1 && in[0].l == 1.5 && in[0].S[2] == 0.5 && in[0].A[0] == 0.25,
          "%s: segment list: %s", how, e.message);
}

/* A tube's glTF file, whole, malloc'd (*len bytes). */
static unsigned char *tube_glb(const char *dir, const char *name, size_t *len) {
    double pts[9] = {0, 0, 0, 0.1, 0.2, 0.5, 0.3, 0.1, 1.25}, radii[3] = {0.05, 0.04, 0.025};
    banyan_mesh *m = NULL;
    banyan_error e;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (banyan_tube_generate(pts, radii, 3, 8, 1, &m, &e) || banyan_gltf_write(path, (const banyan_mesh *const *)&m,
                                                                                 NULL, 1, &e)) {
        banyan_mesh_free(m);
        CHECK(0, "tube %s: %s", name, e.message);
        return NULL;
    }
    banyan_mesh_free(m);
    FILE *f = fopen(path, "rb");
    unsigned char *buf = malloc(1 << 20);
    *len = f && buf ? fread(buf, 1, 1 << 20, f) : 0;
    if (f) fclose(f);
    return buf;
}

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : ".";
    read_numbers("C locale");
    size_t na = 0, nb = 0;
    unsigned char *a = tube_glb(dir, "locale_c.glb", &na);
    if (!setlocale(LC_ALL, LOCALE)) {
        printf("SKIP: the %s locale is not installed (tools/setup.sh generates it)\n", LOCALE);
        free(a);
        return 77;
    }
    /* The locale really bites: what the library must not rely on. */
    CHECK(strcmp(localeconv()->decimal_point, ",") == 0 && strtod("0.5", NULL) == 0.0,
          "%s: decimal point '%s'", LOCALE, localeconv()->decimal_point);
    read_numbers("setlocale(" LOCALE ")");
    CHECK(strcmp(localeconv()->decimal_point, ",") == 0, "the caller's locale changed");
    unsigned char *b = tube_glb(dir, "locale_de.glb", &nb);
    CHECK(a && b && na > 0 && na == nb && memcmp(a, b, na) == 0, "glTF bytes differ under %s (%zu, %zu bytes)",
          LOCALE, na, nb);
    free(a);
    free(b);
    /* A thread's own locale (uselocale), the process's back in C. */
    setlocale(LC_ALL, "C");
    locale_t de = newlocale(LC_ALL_MASK, LOCALE, (locale_t)0);
    CHECK(de != (locale_t)0, "newlocale(%s)", LOCALE);
    if (de) {
        locale_t old = uselocale(de);
        read_numbers("uselocale(" LOCALE ")");
        CHECK(uselocale((locale_t)0) == de, "the thread's locale changed");
        uselocale(old);
        freelocale(de);
    }
    return check_done("test_locale");
}
