/* test_param_ranges.c - every range a parameter table gives (printed by
 * --list, the docs and the add-on's sliders) is one the generator takes:
 * each number parameter of every table at its min and at its max, the
 * others at their defaults, passes the generator's own checks (the table
 * and the rules that tie fields together, as generation runs them), and
 * just outside it is refused. A rule that ties two fields may refuse an
 * extreme only when the other field's default is what it conflicts with;
 * those pairs are listed in `ties`, and the message must name both. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "ivy/ivy_internal.h"
#include "keyaki/keyaki_internal.h"
#include "roots/roots_internal.h"

/* Generation's checks of g's params, without generating. */
static banyan_status validate(banyan_generator g, const void *p, banyan_error *e) {
    switch (g) {
    case BANYAN_GEN_ROOTS: return roots_params_check(p, e);
    case BANYAN_GEN_KEYAKI: return keyaki_params_validate(p, e);
    case BANYAN_GEN_AVENUE: {
        /* The layout checks every tree as banyan_keyaki_generate would. */
        static banyan_keyaki_params trees[BANYAN_AVENUE_MAX_TREES];
        uint32_t n = 0;
        return banyan_avenue_layout(p, NULL, 0, trees, BANYAN_AVENUE_MAX_TREES, &n, e);
    }
    case BANYAN_GEN_IVY: return ivy_params_check(p, e);
    case BANYAN_GEN_SEGMENTS: {
        const banyan_segments_params *sp = p;
        banyan_segment_input *segs = malloc(sizeof *segs * (size_t)(sp->demo_segments > 0 ? sp->demo_segments : 1));
        uint32_t n = 0;
        double trunk[6];
        banyan_status s = segs ? banyan_segments_demo(sp, segs, (uint32_t)sp->demo_segments, &n, trunk, e)
                               : BANYAN_E_NOMEM;
        free(segs);
        return s;
    }
    default: return BANYAN_E_INTERNAL;
    }
}

static void init(banyan_generator g, void *p) {
    switch (g) {
    case BANYAN_GEN_ROOTS: banyan_roots_params_init(p); break;
    case BANYAN_GEN_KEYAKI: banyan_keyaki_params_init(p); break;
    case BANYAN_GEN_AVENUE: banyan_avenue_params_init(p); break;
    case BANYAN_GEN_IVY: banyan_ivy_params_init(p); break;
    case BANYAN_GEN_SEGMENTS: banyan_segments_params_init(p); break;
    default: break;
    }
}

/* Field `name` at v (every component of a vector). */
static void put(const banyan_param_info *pi, void *p, double v) {
    char *f = (char *)p + pi->offset;
    if (pi->type == BANYAN_PT_INT) {
        int32_t x = (int32_t)v;
        memcpy(f, &x, sizeof x);
    } else {
        int n = pi->type == BANYAN_PT_VEC3 ? 3 : pi->type == BANYAN_PT_COLOR ? 4 : 1;
        for (int k = 0; k < n; k++) memcpy(f + k * sizeof(double), &v, sizeof v);
    }
}

/* Fields tied by a rule: `field` at its min or max may be refused with the
 * other at its default, by a message that names both (`self` is how it
 * names the field). */
static const struct {
    const char *gen, *field, *other, *self;
} ties[] = {
    {"roots", "forward_min", "forward_max", NULL},
    {"keyaki", "fork_angle", "fork_angle_step", NULL}, {"keyaki", "fork_angle_step", "levels", NULL},
    {"keyaki", "tilt_mid", "tilt_high", NULL}, {"keyaki", "tilt_high", "tilt_mid", NULL},
    {"keyaki", "sides_min", "sides_max", NULL}, {"keyaki", "sides_max", "sides_min", NULL},
    /* A path of 2e6 m at the default spacing is more trees than allowed. */
    {"avenue", "start", "spacing", "path"}, {"avenue", "end", "spacing", "path"},
    {"avenue", "tree.fork_angle", "fork_angle_step", NULL}, {"avenue", "tree.fork_angle_step", "levels", NULL},
    {"avenue", "tree.tilt_mid", "tilt_high", NULL}, {"avenue", "tree.tilt_high", "tilt_mid", NULL},
    {"avenue", "tree.sides_min", "sides_max", NULL}, {"avenue", "tree.sides_max", "sides_min", NULL},
    {"ivy", "t1", "t2", NULL}, {"ivy", "t2", "t1", NULL},
    {"ivy", "stem_radius", "stem_radius_max", NULL}, {"ivy", "stem_radius_max", "stem_radius", NULL},
    {"ivy", "leaf_size_min", "leaf_size_max", NULL}, {"ivy", "leaf_size_max", "leaf_size_min", NULL},
};

static int tied(const char *gen, const char *field, const char *msg) {
    const char *dot = strrchr(field, '.'), *bare = dot ? dot + 1 : field; /* tree.x: messages say x too */
    for (size_t i = 0; i < sizeof ties / sizeof ties[0]; i++)
        if (!strcmp(ties[i].gen, gen) && !strcmp(ties[i].field, field) &&
            strstr(msg, ties[i].self ? ties[i].self : bare) && strstr(msg, ties[i].other))
            return 1;
    return 0;
}

int main(int argc, char **argv) {
    (void)argc;
    (void)argv;
    static unsigned char params[65536], saved[65536];
    int tried = 0;
    for (int g = 0; g < BANYAN_GEN_COUNT; g++) {
        const char *gen = banyan_generator_name((banyan_generator)g);
        memset(saved, 0, sizeof saved);
        init((banyan_generator)g, saved);
        banyan_error e;
        CHECK(validate((banyan_generator)g, saved, &e) == BANYAN_OK, "%s defaults: %s", gen, e.message);
        for (int32_t i = 0; i < banyan_param_count((banyan_generator)g); i++) {
            const banyan_param_info *pi = banyan_param_get((banyan_generator)g, i);
            if (pi->type != BANYAN_PT_DOUBLE && pi->type != BANYAN_PT_INT && pi->type != BANYAN_PT_VEC3 &&
                pi->type != BANYAN_PT_COLOR)
                continue;
            for (int end = 0; end < 2; end++) {
                double v = end ? pi->max : pi->min;
                memcpy(params, saved, sizeof params);
                put(pi, params, v);
                banyan_status s = validate((banyan_generator)g, params, &e);
                tried++;
                CHECK(s == BANYAN_OK || tied(gen, pi->name, e.message), "%s %s = %g (its %s) refused: %s: %s", gen,
                      pi->name, v, end ? "max" : "min", banyan_status_name(s), e.message);
                /* Just outside: the table check refuses it, naming the field. */
                double out = pi->type == BANYAN_PT_INT ? v + (end ? 1 : -1) : nextafter(v, end ? INFINITY : -INFINITY);
                if (pi->type == BANYAN_PT_INT && (out > INT32_MAX || out < INT32_MIN)) continue;
                memcpy(params, saved, sizeof params);
                put(pi, params, out);
                s = banyan_params_check((banyan_generator)g, params, &e);
                CHECK(s == BANYAN_E_RANGE && strstr(e.message, pi->name), "%s %s = %.17g (past its %s) : %s: %s", gen,
                      pi->name, out, end ? "max" : "min", banyan_status_name(s), e.message);
            }
        }
    }
    CHECK(tried > 100, "only %d extremes tried", tried);
    return check_done("test_param_ranges");
}
