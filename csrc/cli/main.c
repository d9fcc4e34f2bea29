/* `banyan` command line tool:
 *   banyan <generator> [--preset FILE] [--seed N] [--set key=value ...]
 *                      [--threads N] [-o out.glb|out.gltf] [--stats]
 *   banyan <generator> --list      parameters with units, ranges, defaults
 * Presets and --set go through the library's parameter tables, so the CLI,
 * presets and the Blender add-on accept exactly the same keys. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static void append(cli_stats *s, const char *key, const char *val) {
    if (s->len >= sizeof s->buf) return;
    int n = snprintf(s->buf + s->len, sizeof s->buf - s->len, "%s\"%s\": %s", s->len ? ", " : "", key, val);
    if (n > 0) s->len += (size_t)n;
    if (s->len > sizeof s->buf) s->len = sizeof s->buf;
}

void cli_stat_num(cli_stats *s, const char *key, double v) {
    char b[64];
    snprintf(b, sizeof b, "%.17g", v);
    append(s, key, b);
}

void cli_stat_raw(cli_stats *s, const char *key, const char *json) { append(s, key, json); }

static int usage(FILE *f) {
    fprintf(f, "usage: banyan <command> [--preset FILE] [--seed N] [--set key=value ...] [--threads N]\n"
               "                        [-o out.glb|out.gltf] [--stats]\n"
               "       banyan <command> --list\n\ncommands:\n");
    for (int i = 0; cli_commands[i]; i++)
        fprintf(f, "  %-9s %s\n", cli_commands[i]->name, cli_commands[i]->summary);
    return f == stdout ? 0 : 2;
}

static char *read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    for (size_t r; buf && (r = fread(buf + n, 1, cap - n, f)) > 0;) {
        n += r;
        if (n == cap) {
            char *b = cap < (64u << 20) ? realloc(buf, cap *= 2) : NULL;
            if (!b) { free(buf); buf = NULL; }
            else buf = b;
        }
    }
    fclose(f);
    *len = n;
    return buf;
}

static void list_params(const cli_command *c) {
    if (c->generator < 0) {
        printf("%s has no parameter table; it takes --set sides=N (3..256)\n", c->name);
        return;
    }
    void *p = calloc(1, c->params_size ? c->params_size : 1);
    if (p && c->init) c->init(p);
    int32_t n = banyan_param_count((banyan_generator)c->generator);
    for (int32_t i = 0; i < n; i++) {
        const banyan_param_info *pi = banyan_param_get((banyan_generator)c->generator, i);
        const char *f = (const char *)p + pi->offset;
        char def[96] = "";
        switch (pi->type) {
        case BANYAN_PT_DOUBLE: snprintf(def, sizeof def, "%g", *(const double *)f); break;
        case BANYAN_PT_INT: snprintf(def, sizeof def, "%d", *(const int32_t *)f); break;
        case BANYAN_PT_BOOL: snprintf(def, sizeof def, "%s", *(const int32_t *)f ? "true" : "false"); break;
        case BANYAN_PT_ENUM: snprintf(def, sizeof def, "#%d", *(const int32_t *)f); break;
        case BANYAN_PT_SEED: snprintf(def, sizeof def, "%" PRIu64, *(const uint64_t *)f); break;
        case BANYAN_PT_VEC3: {
            const double *v = (const double *)f;
            snprintf(def, sizeof def, "%g,%g,%g", v[0], v[1], v[2]);
            break;
        }
        case BANYAN_PT_COLOR: {
            const double *v = (const double *)f;
            snprintf(def, sizeof def, "%g,%g,%g,%g", v[0], v[1], v[2], v[3]);
            break;
        }
        }
        if (pi->type == BANYAN_PT_ENUM)
            printf("%-28s %-14s default %-10s %s (%s)\n", pi->name, "", def, pi->description, pi->choices);
        else if (pi->type == BANYAN_PT_SEED)
            printf("%-28s %-14s default %-10s %s\n", pi->name, "", def, pi->description);
        else
            printf("%-28s [%g, %g] %-4s default %-10s %s\n", pi->name, pi->min, pi->max, pi->unit, def, pi->description);
    }
    free(p);
}

int main(int argc, char **argv) {
    if (argc < 2) return usage(stderr);
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) return usage(stdout);
    if (!strcmp(argv[1], "--version")) {
        printf("banyan %s (ABI %d)\n", banyan_version_string(), banyan_abi_version());
        return 0;
    }
    const cli_command *cmd = NULL;
    for (int i = 0; cli_commands[i]; i++)
        if (!strcmp(cli_commands[i]->name, argv[1])) cmd = cli_commands[i];
    if (!cmd) {
        fprintf(stderr, "banyan: unknown command '%s'\n", argv[1]);
        return usage(stderr);
    }

    static cli_job job; /* large (hosts); one per process */
    const char *out_path = NULL, *seed = NULL;
    int stats = 0, list = 0;
    const char **sets = calloc((size_t)argc, sizeof *sets);
    int n_sets = 0;
    if (!sets) return 1;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        int has_val = i + 1 < argc;
        if (!strcmp(a, "--preset") && has_val) job.preset_path = argv[++i];
        else if (!strcmp(a, "--seed") && has_val) seed = argv[++i];
        else if (!strcmp(a, "--set") && has_val) sets[n_sets++] = argv[++i];
        else if ((!strcmp(a, "-o") || !strcmp(a, "--output")) && has_val) out_path = argv[++i];
        else if (!strcmp(a, "--threads") && has_val) job.threads = atoi(argv[++i]);
        else if (!strcmp(a, "--stats")) stats = 1;
        else if (!strcmp(a, "--list")) list = 1;
        else {
            fprintf(stderr, "banyan %s: unexpected argument '%s'\n", cmd->name, a);
            free(sets);
            return usage(stderr);
        }
    }
    if (list) {
        list_params(cmd);
        free(sets);
        return 0;
    }

    int rc = 1;
    char *text = NULL;
    banyan_mesh **meshes = NULL;
    char **names = NULL;
    uint32_t count = 0;
    banyan_error err = {0, ""};
    void *params = calloc(1, cmd->params_size);
    if (!params) goto out;
    cmd->init(params);
    banyan_generator g = (banyan_generator)cmd->generator;
    if (job.preset_path) {
        text = read_file(job.preset_path, &job.preset_len);
        if (!text) {
            fprintf(stderr, "banyan %s: cannot read preset %s: %s\n", cmd->name, job.preset_path, strerror(errno));
            goto out;
        }
        job.preset_text = text;
        if (cmd->generator < 0) {
            fprintf(stderr, "banyan %s: this command takes no preset\n", cmd->name);
            goto out;
        }
        if (banyan_preset_apply(g, params, text, job.preset_len, job.preset_path, &err) ||
            banyan_preset_hosts(text, job.preset_len, job.preset_path, job.hosts, BANYAN_MAX_HOSTS, &job.n_hosts, &err)) {
            fprintf(stderr, "banyan %s: %s\n", cmd->name, err.message);
            goto out;
        }
    }
    if (seed && cmd->generator >= 0 && banyan_param_set_text(g, params, "seed", seed, &err)) {
        fprintf(stderr, "banyan %s: --seed: %s\n", cmd->name, err.message);
        goto out;
    }
    for (int i = 0; i < n_sets; i++) {
        char key[128];
        const char *eq = strchr(sets[i], '=');
        if (!eq || eq == sets[i] || (size_t)(eq - sets[i]) >= sizeof key) {
            fprintf(stderr, "banyan %s: --set '%s' must look like key=value\n", cmd->name, sets[i]);
            goto out;
        }
        memcpy(key, sets[i], (size_t)(eq - sets[i]));
        key[eq - sets[i]] = '\0';
        banyan_status s = cmd->generator >= 0 ? banyan_param_set_text(g, params, key, eq + 1, &err)
                                              : cmd->set(params, key, eq + 1, &err);
        if (s) {
            fprintf(stderr, "banyan %s: --set %s: %s\n", cmd->name, sets[i], err.message);
            goto out;
        }
    }
    if (job.n_hosts == 0 && cmd->default_hosts) cmd->default_hosts(&job);

    cli_stats st;
    st.len = 0;
    double t0 = now_ms();
    banyan_status s = cmd->run(&job, params, &meshes, &names, &count, &st, &err);
    double t1 = now_ms();
    if (s) {
        fprintf(stderr, "banyan %s: %s: %s\n", cmd->name, banyan_status_name(s), err.message);
        goto out;
    }
    double t2 = t1;
    if (out_path) {
        if (banyan_gltf_write(out_path, (const banyan_mesh *const *)meshes, (const char *const *)names, count, &err)) {
            fprintf(stderr, "banyan %s: writing %s: %s\n", cmd->name, out_path, err.message);
            goto out;
        }
        t2 = now_ms();
    }
    if (stats) {
        uint64_t verts = 0, tris = 0;
        for (uint32_t i = 0; i < count; i++) {
            verts += meshes[i]->vertex_count;
            tris += meshes[i]->index_count / 3;
        }
        printf("{\"command\": \"%s\", \"meshes\": %u, \"vertices\": %" PRIu64 ", \"triangles\": %" PRIu64
               ", \"time_ms\": {\"generate\": %.3f, \"write\": %.3f}%s%.*s}\n",
               cmd->name, count, verts, tris, t1 - t0, t2 - t1, st.len ? ", " : "", (int)st.len, st.buf);
    }
    rc = 0;
out:
    for (uint32_t i = 0; meshes && i < count; i++) banyan_mesh_free(meshes[i]);
    for (uint32_t i = 0; names && i < count; i++) free(names[i]);
    free(meshes);
    free(names);
    free(params);
    free(text);
    free(sets);
    return rc;
}
