/* Ivy mesh benchmark: the wall preset (presets/ivy_wall.json)
 * grown once, then banyan_ivy_mesh timed alone over several runs, with
 * the growth and the stats beside it. Prints medians of wall and CPU
 * time, metres of stem (the skeleton's internode edges) per second of
 * growth + mesh, and a 64-bit FNV-1a hash of every output array, so two
 * builds can be compared for byte-identical meshes as well as speed.
 * Each run meshes the plant twice, alternating: on one thread and on
 * the preset's `threads` (0: all cores); the hashes must agree.
 * Usage: bench_ivy_mesh [runs] [preset] [mesh-only repeats]; the last
 * grows once and then only meshes (for a profiler), on the preset's
 * threads. */
#include "bench.h"

#include <math.h>

#include "banyan.h"
#include "ivy/ivy_internal.h"
#include "test_files.h"
#include "test_hosts.h"

static double cpu_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

/* FNV-1a over 32-bit words (every array here is whole words): quick enough for 50 MB. */
static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const unsigned char *b = p;
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        uint32_t w;
        memcpy(&w, b + i, 4);
        h = (h ^ w) * 0x100000001b3ULL;
    }
    for (; i < n; i++) h = (h ^ b[i]) * 0x100000001b3ULL;
    return h;
}

static uint64_t mesh_hash(const banyan_mesh *m) {
    uint64_t h = 0xcbf29ce484222325ULL;
    size_t nv = m->vertex_count;
    h = fnv(h, m->positions, nv * 3 * sizeof(float));
    h = fnv(h, m->normals, nv * 3 * sizeof(float));
    if (m->uvs) h = fnv(h, m->uvs, nv * 2 * sizeof(float));
    if (m->colors) h = fnv(h, m->colors, nv * 4 * sizeof(float));
    h = fnv(h, m->indices, m->index_count * sizeof(uint32_t));
    for (uint32_t a = 0; a < m->attribute_count; a++) {
        h = fnv(h, m->attributes[a].name, strlen(m->attributes[a].name));
        h = fnv(h, m->attributes[a].data, nv * sizeof(float));
    }
    h = fnv(h, m->parts, m->part_count * sizeof *m->parts);
    h = fnv(h, m->skel_points, (size_t)m->skel_point_count * 3 * sizeof(float));
    h = fnv(h, m->skel_radius, (size_t)m->skel_point_count * sizeof(float));
    h = fnv(h, m->skel_tag, (size_t)m->skel_point_count * sizeof(int32_t));
    h = fnv(h, m->skel_edges, (size_t)m->skel_edge_count * 2 * sizeof(uint32_t));
    return h;
}

static double stem_length(const banyan_mesh *m) {
    double s = 0;
    for (uint32_t e = 0; e < m->skel_edge_count; e++) {
        const float *a = m->skel_points + 3 * (size_t)m->skel_edges[2 * e], *b = m->skel_points + 3 * (size_t)m->skel_edges[2 * e + 1];
        s += sqrt((double)(a[0] - b[0]) * (a[0] - b[0]) + (double)(a[1] - b[1]) * (a[1] - b[1]) +
                  (double)(a[2] - b[2]) * (a[2] - b[2]));
    }
    return s;
}

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 9;
    if (runs < 1) runs = 1;
    char path[1024];
    if (argc > 2) snprintf(path, sizeof path, "%s", argv[2]);
    else snprintf(path, sizeof path, "%s/presets/ivy_wall.json", BANYAN_SOURCE_DIR);
    size_t len;
    char *text = test_read_file(path, &len);
    banyan_ivy_params p;
    banyan_box hosts[16];
    uint32_t nh = 0;
    banyan_error err = {0, ""};
    banyan_ivy_params_init(&p);
    if (!text || banyan_preset_apply(BANYAN_GEN_IVY, &p, text, len, path, &err) ||
        banyan_preset_hosts(text, len, path, hosts, 16, &nh, &err)) {
        fprintf(stderr, "bench_ivy_mesh: cannot load %s: %s\n", path, err.message);
        return 1;
    }
    free(text);
    banyan_hosts *H = TEST_HOSTS(hosts, nh);

    if (argc > 3) {
        banyan_ivy *iv = NULL;
        if (banyan_ivy_create(&p, H, &iv, &err) || banyan_ivy_step(iv, p.steps, &err)) return 1;
        double t0 = cpu_now();
        for (int r = 0; r < atoi(argv[3]); r++) {
            banyan_mesh *m = NULL;
            if (banyan_ivy_mesh(iv, &m, &err)) return 1;
            banyan_mesh_free(m);
        }
        printf("mesh only: %.1f ms CPU each\n", (cpu_now() - t0) / atoi(argv[3]) * 1e3);
        banyan_ivy_free(iv);
        banyan_hosts_free(H);
        return 0;
    }
    double *tw = malloc(sizeof(double) * (size_t)runs * 6), *tc = tw + runs, *gw = tw + 2 * runs, *gc = tw + 3 * runs,
           *t1w = tw + 4 * runs, *t1c = tw + 5 * runs;
    const int32_t threads = p.threads;
    banyan_ivy *iv = NULL;
    uint64_t hash = 0;
    banyan_mesh *m = NULL, *keep[2] = {NULL, NULL};
    for (int r = 0; r < runs; r++) {
        /* Growth each run too (its own figure, and the mesh then reads
         * cold buds as in one shot). The last run's meshes are freed
         * before it, so both meshes of a run write fresh memory. */
        banyan_mesh_free(keep[0]);
        banyan_mesh_free(keep[1]);
        keep[0] = keep[1] = NULL;
        banyan_ivy_free(iv);
        iv = NULL;
        double a = bench_now(), ca = cpu_now();
        if (banyan_ivy_create(&p, H, &iv, &err) || banyan_ivy_step(iv, p.steps, &err)) {
            fprintf(stderr, "bench_ivy_mesh: %s\n", err.message);
            return 1;
        }
        double b = bench_now(), cb = cpu_now();
        gw[r] = b - a, gc[r] = cb - ca;
        /* One thread and the preset's, first one then the other by turns. */
        for (int k = 0; k < 2; k++) {
            int one = (k + r) % 2 == 0;
            iv->p.threads = one ? 1 : threads;
            double s0 = bench_now(), c0 = cpu_now();
            if (banyan_ivy_mesh(iv, &keep[k], &err)) {
                fprintf(stderr, "bench_ivy_mesh: %s\n", err.message);
                return 1;
            }
            double s1 = bench_now(), c1 = cpu_now();
            *(one ? &t1w[r] : &tw[r]) = s1 - s0;
            *(one ? &t1c[r] : &tc[r]) = c1 - c0;
            uint64_t h = mesh_hash(keep[k]);
            if ((r || k) && h != hash) fprintf(stderr, "bench_ivy_mesh: run %d (%s) hashes differently\n", r, one ? "1 thread" : "threads");
            hash = h;
        }
    }
    m = keep[0];
    double len_m = stem_length(m);
    printf("%s: %u vertices, %u triangles, %.1f m of stem, hash %016llx\n", path, m->vertex_count,
           m->index_count / 3, len_m, (unsigned long long)hash);
    double mw = bench_median(tw, runs), mc = bench_median(tc, runs), g = bench_median(gw, runs),
           gcpu = bench_median(gc, runs), m1w = bench_median(t1w, runs), m1c = bench_median(t1c, runs);
    printf("  growth: median %.1f ms wall, %.1f ms CPU\n", g * 1e3, gcpu * 1e3);
    printf("  mesh, 1 thread: median %.1f ms wall, %.1f ms CPU (%d runs)\n", m1w * 1e3, m1c * 1e3, runs);
    printf("  mesh, threads = %d: median %.1f ms wall, %.1f ms CPU (all threads); %.2fx the 1-thread wall\n", threads,
           mw * 1e3, mc * 1e3, m1w / mw);
    printf("  growth + mesh: %.0f m/s of stem (CPU, 1 thread); %.0f m/s (wall, mesh on threads = %d)\n",
           len_m / (gcpu + m1c), len_m / (g + mw), threads);
    banyan_mesh_free(keep[0]);
    banyan_mesh_free(keep[1]);
    banyan_ivy_free(iv);
    banyan_hosts_free(H);
    free(tw);
    return 0;
}
