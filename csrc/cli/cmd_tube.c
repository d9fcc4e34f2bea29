/* `banyan tube`: a demo tube along a helix through the shared sweeper.
 * Has no parameter table: it takes --set sides=N only. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "base/dmath.h"
#include "base/numparse.h"

typedef struct tube_demo_params {
    int32_t sides;
} tube_demo_params;

static void init(void *p) { ((tube_demo_params *)p)->sides = 16; }

static banyan_status run(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err) {
    (void)job;
    (void)names;
    enum { N = 64 };
    double pts[3 * N], radii[N];
    for (int i = 0; i < N; i++) {
        double t = i / (double)(N - 1);
        pts[3 * i] = 0.3 * dm_cos(6.0 * t);
        pts[3 * i + 1] = 0.3 * dm_sin(6.0 * t);
        pts[3 * i + 2] = 1.2 * t;
        radii[i] = 0.06 * (1.0 - 0.6 * t);
    }
    banyan_mesh **m = calloc(1, sizeof *m);
    if (!m) return BANYAN_E_NOMEM;
    banyan_status s = banyan_tube_generate(pts, radii, N, ((const tube_demo_params *)params)->sides, 1, &m[0], err);
    if (s) {
        free(m);
        return s;
    }
    *meshes = m;
    *count = 1;
    cli_stat_num(stats, "points", N);
    return BANYAN_OK;
}

static banyan_status set(void *params, const char *key, const char *value, banyan_error *err) {
    long long v;
    if (strcmp(key, "sides") != 0) {
        if (err) snprintf(err->message, sizeof err->message, "unknown tube parameter '%s' (only sides)", key);
        return BANYAN_E_UNKNOWN_KEY;
    }
    if (!num_parse_int(value, 3, 256, &v)) {
        if (err) snprintf(err->message, sizeof err->message, "sides = '%s' must be a whole number within [3, 256]", value);
        return BANYAN_E_RANGE;
    }
    ((tube_demo_params *)params)->sides = (int32_t)v;
    return BANYAN_OK;
}

const cli_command cli_cmd_tube = {"tube", -1, "a demo tube along a helix (shared sweeper)", sizeof(tube_demo_params),
                                  init, NULL, run, set};
