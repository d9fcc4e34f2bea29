/* bench_lod: banyan_mesh_lod's levels (ratio 0.5, 0.15 and the crossed
 * billboard) on the keyaki_mature preset and the default avenue (unique
 * trees): milliseconds per level (median of 5 runs, one thread) and the
 * triangles kept. Prints figures; asserts nothing. */
#include "bench.h"

#include "banyan.h"
#include "lod_plants.h"

static void bench_plant(const char *name) {
    banyan_error err = {0, ""};
    double t0 = bench_now();
    banyan_mesh *m = lod_plant(name, 0, &err);
    double gen = bench_now() - t0;
    if (!m) {
        printf("%s: cannot grow: %s\n", name, err.message);
        return;
    }
    printf("%s: %u vertices, %u triangles, %u parts (grown in %.0f ms)\n", name, m->vertex_count, m->index_count / 3,
           m->part_count, 1e3 * gen);
    const char *labels[3] = {"ratio 0.50", "ratio 0.15", "billboard"};
    for (int level = 0; level < 3; level++) {
        banyan_lod_params p;
        banyan_lod_params_init(&p);
        p.ratio = level == 1 ? 0.15 : 0.5;
        p.billboard = level == 2;
        double ms[5];
        uint32_t tris = 0;
        int ok = 1;
        for (int r = 0; r < 5 && ok; r++) {
            banyan_mesh *o = NULL;
            double a = bench_now();
            ok = banyan_mesh_lod(m, &p, &o, &err) == BANYAN_OK;
            ms[r] = 1e3 * (bench_now() - a);
            if (o) tris = o->index_count / 3;
            banyan_mesh_free(o);
        }
        if (!ok) {
            printf("  %-10s failed: %s\n", labels[level], err.message);
            continue;
        }
        printf("  %-10s %8.1f ms  %9u triangles (%.3f of the original)\n", labels[level], bench_median(ms, 5), tris,
               (double)tris / (m->index_count / 3));
    }
    banyan_mesh_free(m);
}

int main(void) {
    bench_plant("keyaki_mature");
    bench_plant("avenue");
    return 0;
}
