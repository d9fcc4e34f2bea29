/* bench_png_filters: the PNG encoder's filter and level, chosen by this
 * (textures/png_write.c): the seven 1024-pixel textures (base colour and
 * normal map each) encoded with each fixed filter at a few libdeflate
 * levels, plus zlib level 1 with stb's per-row filter choice (the
 * library's earlier encoder, banyan_image_png's bytes at the time): total
 * bytes and the thread's CPU time, the least of `runs` runs. Thread CPU
 * time, not the wall clock: on a shared machine it does not count waiting.
 *   bench_png_filters [size] [runs]     (defaults 1024, 3) */
#include "bench.h"

#include "banyan.h"
#include "textures/png_write.h"

static double cpu_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

#define NT 7

int main(int argc, char **argv) {
    int size = argc > 1 ? atoi(argv[1]) : 1024, runs = argc > 2 ? atoi(argv[2]) : 3;
    if (runs < 1 || runs > 100) runs = 3;
    static const int set[NT][2] = {{BANYAN_TEX_KEYAKI_LEAF, 0}, {BANYAN_TEX_KEYAKI_LEAF, 1}, {BANYAN_TEX_IVY_LEAF, 0},
                                   {BANYAN_TEX_IVY_LEAF, 1},    {BANYAN_TEX_KEYAKI_BARK, 0}, {BANYAN_TEX_FIG_BARK, 0},
                                   {BANYAN_TEX_IVY_STEM, 0}};
    banyan_image *im[2 * NT];
    for (int t = 0; t < NT; t++) {
        banyan_texture_params p;
        banyan_texture_params_init(&p);
        p.kind = set[t][0];
        p.season = set[t][1];
        p.size = size;
        if (banyan_texture_generate(&p, &im[2 * t], &im[2 * t + 1], NULL)) return 1;
    }
    printf("| encoder | bytes | CPU ms (least of %d) |\n|---|---|---|\n", runs);
    static const char *fname[5] = {"None", "Sub", "Up", "Average", "Paeth"};
    static const int levels[] = {1, 2, 4, 6};
    for (int f = -1; f < 5; f++)
        for (size_t li = 0; li < (f < 0 ? 1 : sizeof levels / sizeof *levels); li++) {
            double best = 1e30;
            size_t bytes = 0;
            for (int r = 0; r < runs; r++) {
                bytes = 0;
                double t0 = cpu_now();
                for (int k = 0; k < 2 * NT; k++) {
                    uint8_t *png = NULL;
                    size_t len = 0;
                    if (f < 0) {
                        if (banyan_image_png(im[k], &png, &len, NULL)) return 1;
                    } else if (png_write(im[k]->pixels, (int)im[k]->width, (int)im[k]->height, (int)im[k]->channels, f,
                                         levels[li], NULL, &png, &len))
                        return 1;
                    bytes += len;
                    free(png);
                }
                double t = cpu_now() - t0;
                if (t < best) best = t;
            }
            if (f < 0) printf("| library (banyan_image_png) | %zu | %.1f |\n", bytes, best * 1e3);
            else printf("| %s, libdeflate %d | %zu | %.1f |\n", fname[f], levels[li], bytes, best * 1e3);
        }
    for (int k = 0; k < 2 * NT; k++) banyan_image_free(im[k]);
    return 0;
}
