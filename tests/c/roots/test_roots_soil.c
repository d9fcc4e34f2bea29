/* The soil line (csrc/roots/soil.c, docs/roots.md "Soil line") on the
 * default params (the CLI's trunk: a 0.8 m x 0.8 m x 8 m box) and
 * roots_mature_fig, both surfaces on the default:
 *   - every vertex higher than 2 soil_line above the ground is white
 *     (1, 1, 1, 1); every colour lies in [0, 1];
 *   - the vertices within 3 cm of the ground are darkened: their mean
 *     luminance multiplier is at most 0.7;
 *   - the same seed gives the same colours;
 *   - soil_line 0, or the ground off: every colour exactly white;
 *   - soil_line -1, 3 or NaN: BANYAN_E_RANGE naming soil_line. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "test_files.h"

static double luminance(const float *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static int all_white(const banyan_mesh *m) {
    for (uint32_t i = 0; i < 4 * m->vertex_count; i++)
        if (m->colors[i] != 1.0f) return 0;
    return 1;
}

static banyan_mesh *grow(const char *name, const banyan_roots_params *p, const banyan_hosts *H) {
    banyan_mesh *m = NULL;
    banyan_error err;
    if (banyan_roots_generate(p, H, &m, NULL, NULL, &err) != BANYAN_OK) {
        CHECK(0, "%s: %s", name, err.message);
        return NULL;
    }
    CHECK(m->colors != NULL, "%s: no vertex colours", name);
    if (!m->colors) {
        banyan_mesh_free(m);
        return NULL;
    }
    return m;
}

static void check_band(const char *name, const banyan_roots_params *p, const banyan_hosts *H) {
    banyan_mesh *m = grow(name, p, H), *again = grow(name, p, H);
    if (!m || !again) goto done;
    const double ground = p->ground_z - m->origin[2];
    uint32_t high = 0, high_stained = 0, low = 0, outside = 0;
    double low_sum = 0, darkest = 1;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *c = m->colors + 4 * (size_t)v;
        double h = (double)m->positions[3 * (size_t)v + 2] - ground;
        for (int k = 0; k < 4; k++) outside += !(c[k] >= 0.0f && c[k] <= 1.0f);
        if (h > 2 * p->soil_line) {
            high++;
            high_stained += c[0] != 1.0f || c[1] != 1.0f || c[2] != 1.0f || c[3] != 1.0f;
        } else if (h <= 0.03) {
            low++;
            low_sum += luminance(c);
        }
        if (luminance(c) < darkest) darkest = luminance(c);
    }
    double low_mean = low ? low_sum / low : 1;
    printf("%-28s %u vertices: %u above 2 soil_line (%u not white), %u within 3 cm of the ground (mean luminance "
           "x%.3f), darkest x%.3f\n",
           name, m->vertex_count, high, high_stained, low, low_mean, darkest);
    CHECK(high > 0 && high_stained == 0, "%s: %u of %u vertices above 2 soil_line are not white", name, high_stained,
          high);
    CHECK(outside == 0, "%s: %u colour components outside [0, 1]", name, outside);
    CHECK(low > 0 && low_mean <= 0.7, "%s: %u vertices within 3 cm of the ground, mean luminance multiplier %.3f > 0.7",
          name, low, low_mean);
    CHECK(m->vertex_count == again->vertex_count &&
              !memcmp(m->colors, again->colors, sizeof(float) * 4 * (size_t)m->vertex_count),
          "%s: two runs give different colours", name);
done:
    banyan_mesh_free(m);
    banyan_mesh_free(again);
}

static void check_white(const char *name, const banyan_roots_params *p, const banyan_hosts *H) {
    banyan_mesh *m = grow(name, p, H);
    if (!m) return;
    CHECK(all_white(m), "%s: colours not all white", name);
    banyan_mesh_free(m);
}

static void check_refused(const banyan_hosts *H, double value) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.soil_line = value;
    banyan_mesh *m = NULL;
    banyan_error err;
    memset(&err, 0, sizeof err);
    banyan_status s = banyan_roots_generate(&p, H, &m, NULL, NULL, &err);
    CHECK(s == BANYAN_E_RANGE && m == NULL, "soil_line = %g: status %d, want BANYAN_E_RANGE", value, (int)s);
    CHECK(strstr(err.message, "soil_line") && strstr(err.message, "[0, 2]"), "soil_line = %g: message \"%s\"", value,
          err.message);
    banyan_mesh_free(m);
}

int main(void) {
    banyan_box trunk = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    banyan_hosts *H = NULL;
    banyan_error err;
    CHECK(banyan_hosts_create(&trunk, 1, NULL, 0, &H, &err) == BANYAN_OK, "trunk: %s", err.message);
    if (H) {
        banyan_roots_params p;
        banyan_roots_params_init(&p);
        CHECK(p.soil_line == 0.25, "default soil_line = %g, want 0.25", p.soil_line);
        check_band("default", &p, H);
        p.surface = BANYAN_ROOTS_TUBES;
        check_band("default, tubes", &p, H);
        p.surface = BANYAN_ROOTS_FUSED;
        p.soil_line = 0;
        check_white("default, soil_line 0", &p, H);
        p.soil_line = 0.25;
        p.ground = 0;
        check_white("default, no ground", &p, H);
        check_refused(H, -1);
        check_refused(H, 3);
        check_refused(H, NAN);
        banyan_hosts_free(H);
    }

    banyan_roots_params p;
    char path[512];
    snprintf(path, sizeof path, "%s/presets/roots_mature_fig.json", BANYAN_SOURCE_DIR);
    if (test_load_roots(path, &p, &H, &err) != BANYAN_OK) {
        CHECK(0, "roots_mature_fig: %s", err.message);
    } else {
        check_band("roots_mature_fig", &p, H);
        banyan_hosts_free(H);
    }
    return check_done("test_roots_soil");
}
