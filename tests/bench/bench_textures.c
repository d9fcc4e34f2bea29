/* bench_textures: time to draw every texture the library makes:
 * the keyaki and Boston ivy leaf atlases in both seasons and the
 * three barks, base colour and normal map each, one thread (the painters
 * are single-threaded). Median of `runs` runs with min and max, per
 * texture and for the whole set (the sum of each run's times); then the
 * PNG encoding of the set once, for scale (the glTF writer and the add-on
 * pay it too). Target: the set at 1024 under 150 ms. Besides
 * the wall clock it prints the thread's CPU time for the set: on this
 * shared 2-core machine the wall clock also counts time spent waiting for
 * a core.
 *   bench_textures [size] [runs]     (defaults 1024, 7) */
#include "bench.h"

#include "banyan.h"

#define NT 7

static double bench_cpu_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

int main(int argc, char **argv) {
    int size = argc > 1 ? atoi(argv[1]) : 1024, runs = argc > 2 ? atoi(argv[2]) : 7;
    if (runs < 1 || runs > 100) runs = 7;
    static const struct { int kind, season; const char *name; } set[NT] = {
        {BANYAN_TEX_KEYAKI_LEAF, 0, "keyaki_leaf summer"}, {BANYAN_TEX_KEYAKI_LEAF, 1, "keyaki_leaf autumn"},
        {BANYAN_TEX_IVY_LEAF, 0, "ivy_leaf summer"},       {BANYAN_TEX_IVY_LEAF, 1, "ivy_leaf autumn"},
        {BANYAN_TEX_KEYAKI_BARK, 0, "keyaki_bark"},        {BANYAN_TEX_FIG_BARK, 0, "fig_bark"},
        {BANYAN_TEX_IVY_STEM, 0, "ivy_stem"}};
    double t[NT][100], total[100], cpu[100];
    double png_s = 0, png_cpu = 0;
    size_t png_bytes = 0;
    for (int r = 0; r < runs; r++) {
        total[r] = 0;
        double c0 = bench_cpu_now();
        for (int i = 0; i < NT; i++) {
            banyan_texture_params p;
            banyan_texture_params_init(&p);
            p.kind = set[i].kind;
            p.season = set[i].season;
            p.size = size;
            banyan_image *bc = NULL, *nm = NULL;
            banyan_error e;
            double t0 = bench_now();
            if (banyan_texture_generate(&p, &bc, &nm, &e) != BANYAN_OK) {
                fprintf(stderr, "bench_textures: %s\n", e.message);
                return 1;
            }
            t[i][r] = bench_now() - t0;
            total[r] += t[i][r];
            if (r == 0) {
                for (int k = 0; k < 2; k++) {
                    uint8_t *png = NULL;
                    size_t len = 0;
                    double p0 = bench_now(), q0 = bench_cpu_now();
                    if (banyan_image_png(k ? nm : bc, &png, &len, &e) == BANYAN_OK) png_bytes += len;
                    png_s += bench_now() - p0;
                    png_cpu += bench_cpu_now() - q0;
                    banyan_png_free(png);
                }
            }
            banyan_image_free(bc);
            banyan_image_free(nm);
        }
        cpu[r] = bench_cpu_now() - c0 - png_cpu;
        png_cpu = 0;
    }
    printf("bench_textures: size %d, base colour + normal map each, one thread, median [min .. max] of %d runs\n",
           size, runs);
    for (int i = 0; i < NT; i++) {
        double mn = t[i][0], mx = t[i][0];
        for (int r = 0; r < runs; r++) mn = t[i][r] < mn ? t[i][r] : mn, mx = t[i][r] > mx ? t[i][r] : mx;
        double med = bench_median(t[i], runs);
        printf("  %-20s %7.1f ms [%.1f .. %.1f]\n", set[i].name, med * 1e3, mn * 1e3, mx * 1e3);
    }
    double mn = total[0], mx = total[0];
    for (int r = 0; r < runs; r++) mn = total[r] < mn ? total[r] : mn, mx = total[r] > mx ? total[r] : mx;
    double med = bench_median(total, runs);
    printf("  %-20s %7.1f ms [%.1f .. %.1f] (target < 150 ms at 1024)\n", "all 7 textures", med * 1e3, mn * 1e3,
           mx * 1e3);
    printf("  %-20s %7.1f ms CPU time of the thread (median)\n", "all 7 textures", bench_median(cpu, runs) * 1e3);
    printf("  PNG of the 14 images (once): %.1f ms, %.1f MB\n", png_s * 1e3, png_bytes / 1e6);
    printf("JSON {\"bench\": \"textures\", \"size\": %d, \"total_ms\": %.2f}\n", size, med * 1e3);
    return 0;
}
