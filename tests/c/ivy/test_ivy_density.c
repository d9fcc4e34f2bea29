/* Ivy density and the light term, on the wall preset (spec/ivy.md,
 * "Density measure", "What a correct result shows").
 *   - A larger t0 gives denser ivy: the mean density over 10 seeds grows
 *     with t0 in {10, 15, 20, 25} (450 steps each, stepping API, no mesh).
 *   - The light term curbs crossings: over 10 seeds, plants grown to the
 *     same size (4000 buds) cross their stems visibly more often with
 *     w_helio = 0 than with the default weight. Plants are compared at the
 *     same size because the light term also makes them grow faster, and
 *     crossings rise with the square of the stem density. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "test_files.h"
#include "test_hosts.h"


int main(void) {
    banyan_ivy_params base;
    banyan_box hosts[4];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    banyan_ivy_params_init(&base);
    if (test_load_preset(BANYAN_GEN_IVY, &base, BANYAN_SOURCE_DIR "/presets/ivy_wall.json", hosts, 4, &nh, &err)) {
        CHECK(0, "preset: %s", err.message);
        return check_done("test_ivy_density");
    }
    banyan_hosts *H = TEST_HOSTS(hosts, nh);

    const double t0s[4] = {10, 15, 20, 25};
    double mean[4];
    for (int k = 0; k < 4; k++) {
        double sum = 0, buds = 0;
        for (uint64_t seed = 1; seed <= 10; seed++) {
            banyan_ivy_params p = base;
            p.seed = seed;
            p.t0 = t0s[k];
            banyan_ivy *iv = NULL;
            banyan_ivy_stats st;
            memset(&st, 0, sizeof st);
            if (banyan_ivy_create(&p, H, &iv, &err) == BANYAN_OK && banyan_ivy_step(iv, p.steps, &err) == BANYAN_OK)
                banyan_ivy_get_stats(iv, &st, &err);
            else
                CHECK(0, "t0 %g seed %llu: %s", t0s[k], (unsigned long long)seed, err.message);
            sum += st.density;
            buds += st.buds;
            banyan_ivy_free(iv);
        }
        mean[k] = sum / 10;
        printf("t0 = %g: mean density %.1f per m^2, mean buds %.0f\n", t0s[k], mean[k], buds / 10);
    }
    for (int k = 1; k < 4; k++)
        CHECK(mean[k] > mean[k - 1], "mean density %g at t0 = %g is not above %g at t0 = %g", mean[k], t0s[k],
              mean[k - 1], t0s[k - 1]);

    /* The light term. */
    const int32_t size = 4000;
    double cross[2] = {0, 0}, grown[2] = {0, 0};
    for (int w = 0; w < 2; w++)
        for (uint64_t seed = 1; seed <= 10; seed++) {
            banyan_ivy_params p = base;
            p.seed = seed;
            p.w_helio = w ? 0.0 : 1.0;
            banyan_ivy *iv = NULL;
            if (banyan_ivy_create(&p, H, &iv, &err) != BANYAN_OK) {
                CHECK(0, "create: %s", err.message);
                continue;
            }
            banyan_ivy_stats st = {0};
            for (int s = 0; s < p.steps && st.buds < size; s++)
                if (banyan_ivy_step(iv, 1, &err) || banyan_ivy_get_stats(iv, &st, &err)) break;
            CHECK(st.buds >= size, "w_helio %d seed %llu reached only %d buds", w, (unsigned long long)seed, st.buds);
            cross[w] += (double)st.crossings / st.buds;
            grown[w] += st.buds;
            banyan_ivy_free(iv);
        }
    printf("crossings per 1000 buds at %d buds: %.1f with the light term, %.1f without\n", size, 100.0 * cross[0],
           100.0 * cross[1]);
    CHECK(cross[1] > 1.1 * cross[0], "without the light term crossings per bud are %.4f, with it %.4f: not visibly more",
          cross[1] / 10, cross[0] / 10);
    banyan_hosts_free(H);
    return check_done("test_ivy_density");
}
