/* PCG32: the stream is fixed for a fixed seed (checked against the
 * reference pcg32-demo output), draws stay in range, bounded draws are
 * unbiased enough to pass a chi-square test. */
#include <math.h>

#include "check.h"
#include "base/rng.h"

int main(void) {
    /* pcg32-demo: pcg32_srandom_r(&rng, 42u, 54u), first six outputs. */
    static const uint32_t ref[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    pcg32 r;
    pcg32_seed(&r, 42u, 54u);
    for (int i = 0; i < 6; i++) {
        uint32_t x = pcg32_next(&r);
        CHECK(x == ref[i], "output %d = 0x%08x, want 0x%08x", i, x, ref[i]);
    }

    /* Same seed, same stream; different seed or stream, different one. */
    pcg32 a, b, c, d;
    pcg32_seed(&a, 7, 1);
    pcg32_seed(&b, 7, 1);
    pcg32_seed(&c, 8, 1);
    pcg32_seed(&d, 7, 2);
    int same = 1, diff_seed = 0, diff_stream = 0;
    for (int i = 0; i < 1000; i++) {
        uint32_t x = pcg32_next(&a);
        same &= x == pcg32_next(&b);
        diff_seed += x != pcg32_next(&c);
        diff_stream += x != pcg32_next(&d);
    }
    CHECK(same, "same seed gave different streams");
    CHECK(diff_seed > 990, "seeds 7 and 8 agree on %d of 1000", 1000 - diff_seed);
    CHECK(diff_stream > 990, "streams 1 and 2 agree on %d of 1000", 1000 - diff_stream);

    /* uniform in [0,1), range in [a,b], mean near the middle. */
    pcg32_seed(&r, 123, 0);
    double lo = 1, hi = 0, sum = 0;
    int bad = 0;
    for (int i = 0; i < 100000; i++) {
        double u = rng_uniform(&r);
        if (!(u >= 0 && u < 1)) bad++;
        lo = fmin(lo, u);
        hi = fmax(hi, u);
        sum += u;
        double x = rng_range(&r, -4, 4);
        if (!(x >= -4 && x <= 4)) bad++;
    }
    CHECK(bad == 0, "%d draws out of range", bad);
    CHECK(lo < 1e-3 && hi > 1 - 1e-3, "uniform spans [%g, %g]", lo, hi);
    CHECK(fabs(sum / 100000 - 0.5) < 0.01, "uniform mean %g", sum / 100000);

    /* rng_below: chi-square over 10 bins (9 dof; 27.9 is p = 0.001). */
    int bins[10] = {0};
    for (int i = 0; i < 100000; i++) {
        uint32_t k = rng_below(&r, 10);
        if (k >= 10) bad++;
        else bins[k]++;
    }
    double chi = 0;
    for (int k = 0; k < 10; k++) chi += (bins[k] - 10000.0) * (bins[k] - 10000.0) / 10000.0;
    CHECK(bad == 0, "rng_below out of range");
    CHECK(chi < 27.9, "chi-square %g over 10 bins", chi);
    CHECK(rng_below(&r, 1) == 0 && rng_below(&r, 0) == 0, "rng_below(1) and (0) must be 0");

    /* normal: mean 0, variance 1. */
    double s1 = 0, s2 = 0;
    for (int i = 0; i < 100000; i++) {
        double z = rng_normal(&r);
        s1 += z;
        s2 += z * z;
    }
    CHECK(fabs(s1 / 1e5) < 0.02 && fabs(s2 / 1e5 - 1) < 0.03, "normal mean %g var %g", s1 / 1e5, s2 / 1e5);
    return check_done("test_rng");
}
