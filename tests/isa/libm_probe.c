/* Test only (isa_sweep.py): a hash of glibc libm results on inputs where
 * its FMA and non-FMA builds round differently. isa_sweep.py runs it with
 * and without GLIBC_TUNABLES to prove the tunable really switches libm's
 * kernels on this machine. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

int main(void) {
    uint64_t h = 1469598103934665603ull;
    double x = 0.1234567;
    for (int i = 0; i < 4000000; i++) {
        x = x * 1.0000013 + 0.37;
        if (x > 1e4) x -= 1e4;
        double r[6] = {sin(x), cos(x), exp(x * 1e-3), log(x + 1), atan2(x, 3.0), pow(x, 0.37)};
        for (int k = 0; k < 6; k++) {
            uint64_t b;
            memcpy(&b, &r[k], sizeof b);
            h = (h ^ b) * 1099511628211ull;
        }
    }
    printf("%016llx\n", (unsigned long long)h);
    return 0;
}
