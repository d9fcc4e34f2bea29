/* bench_instancing: the 10,000-tree avenue (placement count, 5,000
 * trees a row, 2 rows, 3 m apart along 15 km, default keyaki trees):
 *   - as 16 variants placed as instances: generate time, .glb write time
 *     and size (target < 1 GB), peak resident set;
 *   - as unique trees: what happens (the vertex count it would need, the
 *     refusal and how long it takes), and the largest unique avenue that
 *     fits the default max_vertices, with its time, peak and .glb.
 * Each case runs once in a forked child whose peak resident set
 * (wait4's ru_maxrss) is its own. Nothing is asserted.
 *
 *   bench_instancing [OUTDIR]   (default /tmp; the .glb files are removed) */
#define _DEFAULT_SOURCE /* wait4 */
#include "bench.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "banyan.h"

typedef struct result {
    int status;
    char message[256];
    double gen_s, write_s;
    uint64_t vertices, triangles, instances, file_bytes;
    uint32_t variants;
} result;

static void avenue(banyan_avenue_params *p, int32_t per_row, int32_t variants) {
    banyan_avenue_params_init(p);
    p->threads = 2;
    p->placement = BANYAN_AVENUE_COUNT;
    p->count = per_row;
    p->rows = 2;
    p->end[0] = 3.0 * (per_row - 1); /* 3 m apart: 15 km for 5,000, within one frame (8192 m each way) */
    p->variants = variants;
}

/* Generates (and writes, when path is set) in a child; *mb its peak. */
static int run(const banyan_avenue_params *p, const char *path, result *out, double *mb) {
    int fd[2];
    if (pipe(fd)) return perror("pipe"), 1;
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0) return perror("fork"), 1;
    if (pid == 0) {
        result r;
        memset(&r, 0, sizeof r);
        banyan_error err;
        banyan_mesh *m = NULL;
        double t0 = bench_now();
        r.status = banyan_avenue_generate(p, NULL, 0, &m, NULL, &err);
        r.gen_s = bench_now() - t0;
        if (r.status) snprintf(r.message, sizeof r.message, "%s", err.message);
        if (m) {
            r.vertices = m->vertex_count;
            r.triangles = m->index_count / 3;
            r.instances = m->instance_count;
            for (uint32_t q = 0; q < m->part_count; q++)
                if (m->parts[q].group + 1 > r.variants) r.variants = m->parts[q].group + 1;
            if (path) {
                t0 = bench_now();
                r.status = banyan_gltf_write(path, (const banyan_mesh *const *)&m, NULL, 1, &err);
                r.write_s = bench_now() - t0;
                if (r.status) snprintf(r.message, sizeof r.message, "write: %.240s", err.message);
                struct stat st;
                if (stat(path, &st) == 0) r.file_bytes = (uint64_t)st.st_size;
                unlink(path);
            }
            banyan_mesh_free(m);
        }
        ssize_t n = write(fd[1], &r, sizeof r);
        _exit(n == (ssize_t)sizeof r ? 0 : 1);
    }
    close(fd[1]);
    ssize_t n = read(fd[0], out, sizeof *out);
    close(fd[0]);
    int status = 0;
    struct rusage u;
    if (wait4(pid, &status, 0, &u) < 0) return perror("wait4"), 1;
    *mb = u.ru_maxrss / 1024.0; /* kilobytes on Linux */
    if (n != (ssize_t)sizeof *out || !WIFEXITED(status) || WEXITSTATUS(status)) {
        fprintf(stderr, "the child failed (status %d)\n", status);
        return 1;
    }
    return 0;
}

static void show(const char *what, const result *r, double mb) {
    printf("%s: %s\n", what, r->status ? banyan_status_name((banyan_status)r->status) : "ok");
    if (r->status) printf("  refused after %.2f s: %s\n", r->gen_s, r->message);
    if (r->vertices)
        printf("  generate %.2f s, %llu vertices, %llu triangles, %u distinct trees, %llu instances\n", r->gen_s,
               (unsigned long long)r->vertices, (unsigned long long)r->triangles, r->variants,
               (unsigned long long)r->instances);
    if (r->file_bytes)
        printf("  .glb write %.2f s, %.1f MB (%llu bytes)\n", r->write_s, r->file_bytes / 1e6,
               (unsigned long long)r->file_bytes);
    printf("  peak resident %.0f MB\n", mb);
}

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : "/tmp";
    char path[1024];
    banyan_avenue_params p;
    result r;
    double mb;

    avenue(&p, 5000, 16);
    snprintf(path, sizeof path, "%s/bench_instancing_variants.glb", dir);
    if (run(&p, path, &r, &mb)) return 1;
    show("10,000 trees as 16 variants (2 threads, textures 1024)", &r, mb);
    double per_tree = r.variants ? (double)r.vertices / r.variants : 0;
    printf("  %.0f vertices a tree on average\n", per_tree);

    avenue(&p, 5000, 0);
    if (run(&p, NULL, &r, &mb)) return 1;
    show("10,000 unique trees, default max_vertices (32,000,000)", &r, mb);
    printf("  it would need about %.2e vertices (%.0f a tree): %.0f GB as a banyan_mesh at 66 bytes a vertex\n",
           per_tree * 10000, per_tree, per_tree * 10000 * 66 / 1e9);
    p.max_vertices = 1 << 30;
    if (run(&p, NULL, &r, &mb)) return 1;
    show("10,000 unique trees, max_vertices 2^30 (its largest)", &r, mb);

    /* The largest unique avenue under the default max_vertices, with 5 %
     * room for the trees' spread. */
    int32_t per_row = per_tree > 0 ? (int32_t)(0.95 * 32000000.0 / per_tree / 2) : 50;
    avenue(&p, per_row, 0);
    snprintf(path, sizeof path, "%s/bench_instancing_unique.glb", dir);
    if (run(&p, path, &r, &mb)) return 1;
    char what[128];
    snprintf(what, sizeof what, "largest unique avenue under max_vertices: %d trees (2 threads, textures 1024)",
             2 * per_row);
    show(what, &r, mb);
    return 0;
}
