/* The ivy's look (issue #19, docs/ivy.md "How the look is measured") on
 * the wall and pillar presets over 5 seeds at their 450 steps:
 *   - stems fan out: of the attached stem length on the wall's front face
 *     (and on the faces facing the same way on the pillar preset), at
 *     most 35 % within 15 deg of vertical and 55 % within 30 deg;
 *   - the ground is crossed, not carpeted: at most 3 % of the leaf area
 *     lies on the ground (blades nearer the ground than any host), on
 *     the wall preset;
 *   - density (branch points + crossings per m^2 of covered face) in
 *     [70, 110] at the default t0 on the wall (the real wall: about 88).
 * Printed: every figure, per seed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "ivy_look.h"
#include "test_files.h"

typedef struct preset {
    const char *name;
    banyan_ivy_params p;
    banyan_box hosts[8];
    uint32_t nh;
} preset;

static int load(const char *name, preset *out) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    size_t len;
    char *text = test_read_file(path, &len);
    CHECK(text != NULL, "cannot read %s", path);
    if (!text) return 0;
    banyan_error err = {0, ""};
    out->name = name;
    banyan_ivy_params_init(&out->p);
    int ok = banyan_preset_apply(BANYAN_GEN_IVY, &out->p, text, len, path, &err) == BANYAN_OK &&
             banyan_preset_hosts(text, len, path, out->hosts, 8, &out->nh, &err) == BANYAN_OK;
    CHECK(ok, "%s: %s", name, err.message);
    free(text);
    return ok;
}

int main(void) {
    const char *names[2] = {"ivy_wall", "ivy_pillar"};
    const v3 front = v3_make(0, -1, 0);
    for (int pi = 0; pi < 2; pi++) {
        preset pr;
        if (!load(names[pi], &pr)) continue;
        double len = 0, w15 = 0, w30 = 0, dens = 0, ground = 0;
        for (uint64_t seed = 1; seed <= 5; seed++) {
            banyan_ivy_params p = pr.p;
            p.seed = seed;
            banyan_error err = {0, ""};
            banyan_ivy *iv = NULL;
            banyan_mesh *m = NULL;
            banyan_ivy_stats st;
            memset(&st, 0, sizeof st);
            if (banyan_ivy_create(&p, pr.hosts, pr.nh, &iv, &err) != BANYAN_OK ||
                banyan_ivy_step(iv, p.steps, &err) != BANYAN_OK || banyan_ivy_get_stats(iv, &st, &err) != BANYAN_OK ||
                banyan_ivy_mesh(iv, &m, &err) != BANYAN_OK) {
                CHECK(0, "%s seed %llu: %s", pr.name, (unsigned long long)seed, err.message);
                banyan_ivy_free(iv);
                continue;
            }
            ivy_stem_angles a = ivy_look_stem_angles(iv, front);
            double g = ivy_look_ground_leaf_share(iv, m);
            printf("%s seed %llu: %d buds, front stem %.1f m, within 15 deg %.1f %%, within 30 deg %.1f %%, "
                   "leaf area on the ground %.2f %%, density %.1f /m^2 (%d branch points, %d crossings, %.1f m^2)\n",
                   pr.name, (unsigned long long)seed, st.buds, a.length, 100 * a.within15 / a.length,
                   100 * a.within30 / a.length, 100 * g, st.density, st.branch_points, st.crossings, st.covered_area);
            len += a.length;
            w15 += a.within15;
            w30 += a.within30;
            dens += st.density / 5;
            ground += g / 5;
            banyan_mesh_free(m);
            banyan_ivy_free(iv);
        }
        printf("%s: within 15 deg %.1f %%, within 30 deg %.1f %%, leaf area on the ground %.2f %%, mean density %.1f\n",
               pr.name, 100 * w15 / len, 100 * w30 / len, 100 * ground, dens);
        CHECK(len > 1.0, "%s: only %.2f m of attached stem on the front faces", pr.name, len);
        CHECK(w15 <= 0.35 * len, "%s: %.1f %% of the front stem length within 15 deg of vertical (<= 35 %%)", pr.name,
              100 * w15 / len);
        CHECK(w30 <= 0.55 * len, "%s: %.1f %% of the front stem length within 30 deg of vertical (<= 55 %%)", pr.name,
              100 * w30 / len);
        if (pi == 0) {
            CHECK(ground <= 0.03, "%s: %.2f %% of the leaf area on the ground (<= 3 %%)", pr.name, 100 * ground);
            CHECK(dens >= 70 && dens <= 110, "%s: mean density %.1f per m^2 not within [70, 110]", pr.name, dens);
        }
    }
    return check_done("test_ivy_look");
}
