/* Benchmark of roots on a mesh host: the default net (6 main
 * roots x 40 growth points, all branch kinds, hugging, n = 16 sides) round
 * a closed cylinder trunk the size of the CLI's default trunk (0.4 m
 * radius, 8 m tall) tessellated into about 50,000 triangles, against the
 * same net round its bounding box given as a box. Single-threaded, seeds
 * 1..20 in turn; prints the median time per net of each (whole call and
 * the net alone, without the tube mesh), their ratio (target: the mesh
 * within 5x of the box) and the host set's build time. The same for
 * Suzanne's stand-in (tests/c/common/host_meshes.h: three shells that cut
 * each other, 1,408 triangles, inside decided by rays) against its
 * bounding box.
 *   bench_roots_hosts [runs]   (default 40) */
#include "bench.h"

#include "banyan.h"
#include "roots/roots_internal.h"
#include "host_meshes.h"
#include "test_hosts.h"

typedef struct figures {
    double call, net;
    uint32_t triangles;
} figures;

static figures measure(const banyan_hosts *H, const banyan_box *box, int runs) {
    banyan_roots_params p;
    banyan_roots_params_init(&p);
    p.surface = BANYAN_ROOTS_TUBES; /* the tube mesh on a mesh host against a box (bench_roots has the fused surface) */
    p.sides = 16;
    double *t = malloc(sizeof(double) * (size_t)runs), *tn = malloc(sizeof(double) * (size_t)runs);
    figures f = {0, 0, 0};
    for (int i = 0; i < runs + 2; i++) {
        p.seed = 1 + (uint64_t)(i % 20);
        banyan_mesh *m = NULL;
        banyan_error err;
        double t0 = bench_now();
        banyan_status s = H ? banyan_roots_generate(&p, H, &m, NULL, NULL, &err)
                            : test_roots_boxes(&p, box, 1, &m, &err);
        double t1 = bench_now();
        roots_net net;
        banyan_status sn = H ? roots_net_build_hosts(&p, H, &net, &err) : roots_net_build(&p, box, 1, &net, &err);
        double t2 = bench_now();
        if (s || sn) {
            fprintf(stderr, "bench_roots_hosts: %s\n", err.message);
            exit(1);
        }
        roots_net_free(&net);
        if (i >= 2) { /* the first two warm up */
            t[i - 2] = t1 - t0;
            tn[i - 2] = t2 - t1;
        }
        if (i == 2) f.triangles = m->index_count / 3;
        banyan_mesh_free(m);
    }
    f.call = bench_median(t, runs);
    f.net = bench_median(tn, runs);
    free(t);
    free(tn);
    return f;
}

int main(int argc, char **argv) {
    int runs = argc > 1 ? atoi(argv[1]) : 40;
    if (runs < 3) runs = 3;
    /* 128 sides x 195 rows: 49,920 side triangles and 256 in the caps. */
    tm_mesh trunk = {0};
    tm_cylinder(&trunk, 0, 0, 0, 0.4, 8.0, 128, 195);
    banyan_host_mesh hm = tm_host(&trunk, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    banyan_box box = banyan_box_make(0, 0, 4, 0.4, 0.4, 4); /* its bounding box: the CLI's default trunk */
    banyan_hosts *H = NULL;
    banyan_error err;
    double t0 = bench_now();
    if (banyan_hosts_create(NULL, 0, &hm, 1, &H, &err)) {
        fprintf(stderr, "bench_roots_hosts: %s\n", err.message);
        return 1;
    }
    double build = bench_now() - t0;

    figures fb = measure(NULL, &box, runs);
    figures fm = measure(H, NULL, runs);
    printf("bench_roots_hosts: default net, n = 16, %d runs per figure, 1 thread\n", runs);
    printf("  host: closed cylinder r 0.4 m, 8 m, %u triangles (host set built in %.1f ms)\n", trunk.nt, build * 1e3);
    printf("  bounding box:  %8.3f ms per call, %8.3f ms of it the net  (%u triangles out)\n", fb.call * 1e3,
           fb.net * 1e3, fb.triangles);
    printf("  mesh host:     %8.3f ms per call, %8.3f ms of it the net  (%u triangles out)\n", fm.call * 1e3,
           fm.net * 1e3, fm.triangles);
    printf("  mesh / box:    %.2fx per call (target <= 5x), %.2fx the net\n", fm.call / fb.call, fm.net / fb.net);
    banyan_hosts_free(H);
    tm_free(&trunk);

    tm_mesh head = {0};
    tm_two_shell_head(&head, 0.7);
    banyan_host_mesh hh = tm_host(&head, 0, 0, 0, BANYAN_HOST_CLOSED_AUTO);
    if (banyan_hosts_create(NULL, 0, &hh, 1, &H, &err)) {
        fprintf(stderr, "bench_roots_hosts: %s\n", err.message);
        return 1;
    }
    banyan_host_info info;
    banyan_hosts_info(H, 0, &info, &err);
    banyan_box hbox = banyan_box_make(0.5 * (info.lo[0] + info.hi[0]), 0.5 * (info.lo[1] + info.hi[1]),
                                      0.5 * (info.lo[2] + info.hi[2]), 0.5 * (info.hi[0] - info.lo[0]),
                                      0.5 * (info.hi[1] - info.lo[1]), 0.5 * (info.hi[2] - info.lo[2]));
    fb = measure(NULL, &hbox, runs);
    fm = measure(H, NULL, runs);
    printf("  host: Suzanne's stand-in, %u triangles in three shells\n", info.triangle_count);
    printf("  bounding box:  %8.3f ms per call, %8.3f ms of it the net\n", fb.call * 1e3, fb.net * 1e3);
    printf("  mesh host:     %8.3f ms per call, %8.3f ms of it the net\n", fm.call * 1e3, fm.net * 1e3);
    printf("  mesh / box:    %.2fx per call, %.2fx the net\n", fm.call / fb.call, fm.net / fb.net);
    banyan_hosts_free(H);
    tm_free(&head);
    return 0;
}
