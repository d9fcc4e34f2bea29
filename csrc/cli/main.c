/* `banyan` command line tool:
 *   banyan <generator> [--preset FILE] [--seed N] [--set key=value ...]
 *                      [--host FILE.glb[@x,y,z] ...] [--threads N]
 *                      [-o out.glb|out.gltf|out.usda|out.usd] [--textures on|off] [--texture-size N] [--stats]
 *                      [--lod 0.5,0.15,billboard] [--engine-uvs] [--pivot-painter] [--fsync] [--compact]
 *   banyan <generator> --list      parameters with units, ranges, defaults
 * Presets and --set go through the library's parameter tables, so the CLI,
 * presets and the Blender add-on accept exactly the same keys. Hosts are
 * the preset's (boxes and meshes) plus every --host mesh; the command's
 * default boxes only when there are none. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "base/atomic_file.h"
#include "base/numparse.h"
#include "base/platform.h"

double cli_now_ms(void) { return plat_clock() * 1e3; }

/* The progress line: "\r<command>  42 %" on stderr (a terminal). */
static int32_t show_progress(void *user, double done) {
    fprintf(stderr, "\r%-8s %3d %%", (const char *)user, (int)(done * 100.0 + 1e-9));
    fflush(stderr);
    return 0;
}

static int usage(FILE *f) {
    fprintf(f, "usage: banyan <command> [--preset FILE] [--seed N] [--set key=value ...] [--threads N]\n"
               "                        [--host FILE.glb[@x,y,z] ...] [-o out.glb|out.gltf|out.usda] [--stats]\n"
               "                        [--textures on|off] [--texture-size N] [--texture-cache on|off|DIR]\n"
               "                        [--lod LIST] [--engine-uvs] [--pivot-painter] [--fsync] [--compact]\n"
               "       banyan <command> --list\n\n"
               "--host adds a glTF binary mesh as a host (roots, ivy; repeatable), moved by x,y,z metres\n"
               "when given; the preset's hosts stay, the default host is used only when there are none.\n"
               "--textures on (default) embeds the leaf and bark textures in the glTF file, drawn at\n"
               "--texture-size pixels (a power of two, 64 .. 8192; default 1024); off writes flat colours.\n"
               "--texture-cache on (default), off or DIR: keep the drawn textures' PNGs in DIR (default\n"
               "$XDG_CACHE_HOME/banyan/textures, else ~/.cache/banyan/textures; BANYAN_TEXTURE_CACHE=off\n"
               "or =DIR in the environment) and reuse them: the same file, written sooner.\n"
               "--lod 0.5,0.15,billboard adds coarser levels of detail to each mesh (MSFT_lod): falling\n"
               "shares of its triangles, optionally ending in billboard cards (3 vertical, 1 on top).\n"
               "--engine-uvs also writes the wind data as TEXCOORD_1..4 for engines that read only UV sets\n"
               "(docs/game-engines.md).\n"
               "--pivot-painter also writes Unreal's Pivot Painter 2 textures beside the glTF file,\n"
               "<out>_PivotPos_Index.exr and <out>_XVector_Extent.png (<out>: -o without its extension;\n"
               "<out>_<i>_... for each of several meshes), and the UV set that indexes them (TEXCOORD_1,\n"
               "or TEXCOORD_5 with --engine-uvs); the meshes need their wind attributes (docs/game-engines.md).\n"
               "--compact writes quantized, meshopt-compressed meshes (KHR_mesh_quantization,\n"
               "EXT_meshopt_compression, both required): smaller files that fewer importers read\n"
               "(three.js with its MeshoptDecoder; not Blender's; docs/gltf.md).\n"
               "--threads N: threads for avenue (one tree each), keyaki and ivy (meshing); 0: all cores\n"
               "(default); the output is the same on any count.\n"
               "--fsync syncs the glTF file to the disk before it replaces -o, so it survives a power cut\n"
               "(slower for large files; without it the file is still replaced whole: docs/formats.md).\n"
               "\ncommands:\n");
    for (int i = 0; cli_commands[i]; i++)
        fprintf(f, "  %-9s %s\n", cli_commands[i]->name, cli_commands[i]->summary);
    fprintf(f, "  %-9s %s\n", "textures", "leaf atlases and bark as PNG: banyan textures -o DIR [--size N] [--seed N]");
    return f == stdout ? 0 : 2;
}

/* The preset at path, malloc'd (*len bytes), or NULL with the reason in
 * msg. Reading stops past the library's limit, so a huge file is refused
 * without being read whole. */
static char *read_preset(const char *path, size_t *len, char *msg, size_t cap) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(msg, cap, "cannot read preset %s: %s", path, strerror(errno));
        return NULL;
    }
    size_t max = BANYAN_PRESET_MAX_BYTES, n = 0, r;
    char *buf = malloc(max + 1);
    errno = 0;
    while (buf && n <= max && (r = fread(buf + n, 1, max + 1 - n, f)) > 0) n += r;
    int failed = ferror(f), e = errno;
    fclose(f);
    if (!buf) snprintf(msg, cap, "cannot read preset %s: out of memory", path);
    else if (failed) snprintf(msg, cap, "cannot read preset %s: %s", path, e ? strerror(e) : "read error");
    else if (n > max)
        snprintf(msg, cap, "preset %s is larger than the %u-byte limit for presets (BANYAN_PRESET_MAX_BYTES)", path,
                 BANYAN_PRESET_MAX_BYTES);
    else {
        *len = n;
        return buf;
    }
    free(buf);
    return NULL;
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
        case BANYAN_PT_ENUM: { /* the choice's name: field k of "a|b|c" */
            const char *s = pi->choices;
            for (int32_t k = *(const int32_t *)f; k > 0 && s; k--) s = strchr(s, '|') ? strchr(s, '|') + 1 : NULL;
            snprintf(def, sizeof def, "%.*s", s ? (int)strcspn(s, "|") : 1, s ? s : "?");
            break;
        }
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
        /* A heading per panel group (the rows of a group are consecutive), then
         * key, the panel's label, range and unit, default, and the meaning. */
        if (i == 0 || strcmp(pi->group, banyan_param_get((banyan_generator)c->generator, i - 1)->group) != 0)
            printf("%s%s\n", i ? "\n" : "", pi->group);
        char range[64] = "";
        if (pi->type == BANYAN_PT_ENUM) snprintf(range, sizeof range, "%s", pi->choices);
        else if (pi->type != BANYAN_PT_SEED && pi->type != BANYAN_PT_BOOL && pi->type != BANYAN_PT_COLOR)
            snprintf(range, sizeof range, "[%g, %g]%s%s", pi->min, pi->max, pi->unit[0] ? " " : "", pi->unit);
        printf("  %-26s %-28s %-22s default %-12s %s\n", pi->name, pi->label, range, def, pi->description);
    }
    free(p);
}

/* "FILE.glb" or "FILE.glb@x,y,z": the file and the translation it asks
 * for (t unchanged when there is none). Returns 0 when the part after the
 * last '@' looks like a placement but is not three finite numbers. */
static int host_spec(const char *spec, char *path, size_t cap, double t[3]) {
    const char *at = strrchr(spec, '@');
    size_t n = strlen(spec);
    if (at && at[1] && strchr("+-.0123456789", at[1])) {
        const char *q = at + 1;
        for (int k = 0; k < 3; k++) {
            size_t len = num_scan_double(q, &t[k]);
            const char *end = q + len;
            if (!len || !(t[k] >= -1e6 && t[k] <= 1e6) || (k < 2 && *end != ',') || (k == 2 && *end)) return 0;
            q = end + 1;
        }
        n = (size_t)(at - spec);
    }
    if (n == 0 || n >= cap) return 0;
    memcpy(path, spec, n);
    path[n] = '\0';
    return 1;
}

/* Reads the --host meshes into read[] (caller frees) and extra[] (their
 * structs, for the host-set calls), within what is left of the command's
 * budget b. A file named
 * again is read once (its later entries share the first's arrays, moved),
 * and the set-wide triangle limit is kept as the files are read. */
static int read_host_args(const cli_command *cmd, const char **specs, int n, banyan_host_mesh **read,
                          banyan_host_mesh *extra, const cli_budget *b) {
    double(*ats)[3] = calloc((size_t)n + 1, sizeof *ats);
    char(*paths)[4096] = calloc((size_t)n + 1, sizeof *paths);
    uint64_t tris = 0;
    int ok = ats && paths;
    for (int i = 0; ok && i < n; i++) {
        double t[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        if (!host_spec(specs[i], paths[i], sizeof paths[i], ats[i])) {
            fprintf(stderr, "banyan %s: --host %s: expected FILE.glb or FILE.glb@x,y,z (metres, each within "
                    "[-1e6, 1e6])\n", cmd->name, specs[i]);
            ok = 0;
            break;
        }
        t[3] = ats[i][0], t[7] = ats[i][1], t[11] = ats[i][2];
        int j = 0;
        while (j < i && (!read[j] || strcmp(paths[j], paths[i]))) j++;
        if (j < i) {
            extra[i] = *read[j];
            for (int r = 0; r < 3; r++) extra[i].transform[4 * r + 3] += ats[i][r] - ats[j][r];
        } else {
            banyan_error err = {0, ""};
            banyan_budget left;
            if (cli_budget_left(b, "reading the hosts", &left, &err) ||
                banyan_glb_read_host_budget(paths[i], t, BANYAN_HOST_CLOSED_AUTO, &left, &read[i], &err)) {
                fprintf(stderr, "banyan %s: --host %s: %s: %s\n", cmd->name, specs[i],
                        banyan_status_name((banyan_status)err.code), err.message);
                ok = 0;
                break;
            }
            extra[i] = *read[i];
        }
        tris += extra[i].triangle_count;
        if (tris > BANYAN_HOSTS_MAX_TRIANGLES) {
            fprintf(stderr, "banyan %s: --host %s: with it the --host meshes hold %llu triangles; a host set takes at "
                    "most %u (decimate, or use fewer or box hosts)\n", cmd->name, specs[i],
                    (unsigned long long)tris, BANYAN_HOSTS_MAX_TRIANGLES);
            ok = 0;
        }
    }
    free(ats);
    free(paths);
    return ok;
}

/* -o names a .glb or .gltf file (the library's rule) that can be
 * written: its folder exists and is writable, it is not a folder. */
static int out_path_ok(const cli_command *cmd, const char *path) {
    size_t n = strlen(path);
    if ((n >= 5 && !strcasecmp(path + n - 5, ".usdc")) || (n >= 5 && !strcasecmp(path + n - 5, ".usdz"))) {
        fprintf(stderr, "banyan %s: -o %s: banyan writes USD text (.usda or .usd); convert it to a crate file with "
                        "OpenUSD's usdcat\n", cmd->name, path);
        return 0;
    }
    if (!((n >= 4 && !strcasecmp(path + n - 4, ".glb")) || (n >= 5 && !strcasecmp(path + n - 5, ".gltf")) ||
          cli_is_usd(path))) {
        fprintf(stderr, "banyan %s: -o %s: must end in .glb (binary glTF), .gltf (JSON glTF), .usda or .usd (USD text)\n",
                cmd->name, path);
        return 0;
    }
    char why[8400];
    if (atomic_check(path, why, sizeof why)) {
        fprintf(stderr, "banyan %s: -o %s: %s\n", cmd->name, path, why);
        return 0;
    }
    return 1;
}

/* The flags of a generator command. */
typedef struct cli_args {
    const char *out_path, *seed;
    int stats, list;
    cli_lod lod;
    banyan_gltf_options gltf_opt;
    const char **sets, **host_args; /* argc entries each */
    int n_sets, n_host_args;
    const char *threads_text; /* --threads as given: also the threads field of the ivy, keyaki and avenue params */
    int pivot_painter;        /* --pivot-painter: the textures beside -o (gltf_opt.pivot_painter writes the UV set) */
} cli_args;

/* The command line after the command: every flag into A and job. 0, or 1
 * on an unexpected argument, 2 on a bad flag's value (both reported). */
static int parse_args(int argc, char **argv, const cli_command *cmd, cli_job *job, cli_args *A) {
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        int has_val = i + 1 < argc;
        if (!strcmp(a, "--preset") && has_val) job->preset_path = argv[++i];
        else if (!strcmp(a, "--seed") && has_val) A->seed = argv[++i];
        else if (!strcmp(a, "--set") && has_val) A->sets[A->n_sets++] = argv[++i];
        else if (!strcmp(a, "--host") && has_val) A->host_args[A->n_host_args++] = argv[++i];
        else if ((!strcmp(a, "-o") || !strcmp(a, "--output")) && has_val) A->out_path = argv[++i];
        else if (!strcmp(a, "--threads") && has_val) {
            const char *v = argv[++i];
            long long t;
            if (!num_parse_int(v, 0, CLI_MAX_THREADS, &t)) {
                fprintf(stderr, "banyan %s: --threads '%s' must be a whole number in [0, %d] (0: all cores)\n",
                        cmd->name, v, CLI_MAX_THREADS);
                goto bad_flag;
            }
            job->threads = (int)t;
            A->threads_text = v;
        }
        else if (!strcmp(a, "--stats")) A->stats = 1;
        else if (!strcmp(a, "--textures") && has_val) {
            const char *v = argv[++i];
            if (strcmp(v, "on") && strcmp(v, "off")) {
                fprintf(stderr, "banyan %s: --textures '%s' must be on or off\n", cmd->name, v);
                goto bad_flag;
            }
            A->gltf_opt.textures = !strcmp(v, "on");
        } else if (!strcmp(a, "--texture-cache") && has_val) {
            const char *v = argv[++i]; /* on, off or a folder */
            if (!v[0]) {
                fprintf(stderr, "banyan %s: --texture-cache '' must be on, off or a folder\n", cmd->name);
                goto bad_flag;
            }
            A->gltf_opt.texture_cache = strcmp(v, "off") != 0;
            A->gltf_opt.texture_cache_dir = strcmp(v, "on") && strcmp(v, "off") ? v : NULL;
        } else if (!strcmp(a, "--texture-size") && has_val) {
            const char *v = argv[++i];
            long long n;
            if (!num_parse_int(v, 64, 8192, &n) || (n & (n - 1))) {
                fprintf(stderr, "banyan %s: --texture-size '%s' must be a power of two in [64, 8192]\n", cmd->name,
                        v);
                goto bad_flag;
            }
            A->gltf_opt.texture_size = (int32_t)n;
        }
        else if (!strcmp(a, "--lod") && has_val) {
            const char *v = argv[++i];
            if (!cli_lod_parse(v, &A->lod)) {
                fprintf(stderr,
                        "banyan %s: --lod '%s' must be up to %d falling ratios in [0.001, 1), comma-separated, "
                        "optionally ending in billboard (e.g. 0.5,0.15,billboard)\n",
                        cmd->name, v, CLI_MAX_LODS);
                goto bad_flag;
            }
        }
        else if (!strcmp(a, "--engine-uvs")) A->gltf_opt.engine_uvs = 1;
        else if (!strcmp(a, "--pivot-painter")) A->gltf_opt.pivot_painter = A->pivot_painter = 1;
        else if (!strcmp(a, "--fsync")) A->gltf_opt.sync = 1;
        else if (!strcmp(a, "--compact")) A->gltf_opt.compact = 1;
        else if (!strcmp(a, "--list")) A->list = 1;
        else {
            fprintf(stderr, "banyan %s: unexpected argument '%s'\n", cmd->name, a);
            return 1;
        }
    }
    return 0;
bad_flag:
    return 2;
}

/* The command's params: its defaults, the preset (*text keeps the file's
 * text for its hosts), --seed, --threads and the --set pairs. 0, or 1 on
 * an error (reported). */
static int load_params(const cli_command *cmd, cli_job *job, const cli_args *A, void *params, char **text,
                       banyan_error *err) {
    cmd->init(params);
    banyan_generator g = (banyan_generator)cmd->generator;
    if (job->preset_path) {
        char why[4200];
        *text = read_preset(job->preset_path, &job->preset_len, why, sizeof why);
        if (!*text) {
            fprintf(stderr, "banyan %s: %s\n", cmd->name, why);
            return 1;
        }
        job->preset_text = *text;
        if (cmd->generator < 0) {
            fprintf(stderr, "banyan %s: this command takes no preset\n", cmd->name);
            return 1;
        }
        if (banyan_preset_apply(g, params, *text, job->preset_len, job->preset_path, err)) {
            fprintf(stderr, "banyan %s: %s\n", cmd->name, err->message);
            return 1;
        }
    }
    if (A->seed && cmd->generator >= 0 && banyan_param_set_text(g, params, "seed", A->seed, err)) {
        fprintf(stderr, "banyan %s: --seed: %s\n", cmd->name, err->message);
        return 1;
    }
    /* Before the --set pairs, so that --set threads=N still wins. */
    if (A->threads_text &&
        (!strcmp(cmd->name, "ivy") || !strcmp(cmd->name, "keyaki") || !strcmp(cmd->name, "avenue")) &&
        banyan_param_set_text(g, params, "threads", A->threads_text, err)) {
        fprintf(stderr, "banyan %s: --threads: %s\n", cmd->name, err->message);
        return 1;
    }
    for (int i = 0; i < A->n_sets; i++) {
        char key[128];
        const char *eq = strchr(A->sets[i], '=');
        if (!eq || eq == A->sets[i] || (size_t)(eq - A->sets[i]) >= sizeof key) {
            fprintf(stderr, "banyan %s: --set '%s' must look like key=value\n", cmd->name, A->sets[i]);
            return 1;
        }
        memcpy(key, A->sets[i], (size_t)(eq - A->sets[i]));
        key[eq - A->sets[i]] = '\0';
        banyan_status s = cmd->generator >= 0 ? banyan_param_set_text(g, params, key, eq + 1, err)
                                              : cmd->set(params, key, eq + 1, err);
        if (s) {
            fprintf(stderr, "banyan %s: --set %s: %s\n", cmd->name, A->sets[i], err->message);
            return 1;
        }
    }
    return 0;
}

/* Reads the hosts: a preset's boxes through banyan_preset_hosts into
 * job->hosts; a mesh preset or any --host into a host set (*host_set),
 * the --host files read within the budget first (*hosts_read set). A
 * refusal is reported here. Returns 0, or CLI_EXIT_BAD_INPUT. */
static int load_hosts(const cli_command *cmd, cli_job *job, const char *text, const char **host_args, int n_host_args,
                      banyan_host_mesh **host_read, banyan_host_mesh *host_extra, const cli_budget *budget,
                      banyan_hosts **host_set, int *hosts_read, banyan_error *err) {
    if (job->preset_path) {
        /* Boxes only, no --host: the box calls, as always. A mesh preset
         * (refused by banyan_preset_hosts as UNSUPPORTED) or any --host
         * takes the host set. */
        banyan_status hs = BANYAN_E_UNSUPPORTED;
        if (!n_host_args)
            hs = banyan_preset_hosts(text, job->preset_len, job->preset_path, job->hosts, BANYAN_MAX_HOSTS,
                                     &job->n_hosts, err);
        if (hs == BANYAN_E_UNSUPPORTED && cmd->default_hosts) {
            *hosts_read = 1;
            if (!read_host_args(cmd, host_args, n_host_args, host_read, host_extra, budget)) return CLI_EXIT_BAD_INPUT;
            const char *slash = strrchr(job->preset_path, '/');
            char dir[4096] = ".";
            if (slash && (size_t)(slash - job->preset_path) < sizeof dir)
                snprintf(dir, sizeof dir, "%.*s", slash == job->preset_path ? 1 : (int)(slash - job->preset_path),
                         job->preset_path);
            banyan_budget left;
            hs = cli_budget_left(budget, "reading the hosts", &left, err);
            if (!hs)
                hs = banyan_preset_host_set_budget(text, job->preset_len, job->preset_path, dir, host_extra,
                                                   (uint32_t)n_host_args, &left, host_set, err);
        }
        if (hs) {
            fprintf(stderr, "banyan %s: %s\n", cmd->name, err->message);
            return CLI_EXIT_BAD_INPUT;
        }
    } else if (n_host_args) {
        *hosts_read = 1;
        if (!read_host_args(cmd, host_args, n_host_args, host_read, host_extra, budget)) return CLI_EXIT_BAD_INPUT;
        if (banyan_hosts_create(NULL, 0, host_extra, (uint32_t)n_host_args, host_set, err)) {
            fprintf(stderr, "banyan %s: --host: %s\n", cmd->name, err->message);
            return CLI_EXIT_BAD_INPUT;
        }
    }
    return 0;
}

banyan_status cli_job_hosts(const cli_job *job, const banyan_hosts **hosts, banyan_hosts **own, banyan_error *err) {
    *own = NULL;
    *hosts = job->host_set;
    if (job->host_set) return BANYAN_OK;
    banyan_status s = banyan_hosts_create(job->hosts, job->n_hosts, NULL, 0, own, err);
    *hosts = *own;
    return s;
}

/* Adds the host set's box, mesh and triangle counts and, when the first
 * mesh's zero is away from the world's origin, that origin to the stats. */
static void stat_hosts_origin(const banyan_hosts *host_set, banyan_mesh *const *meshes, uint32_t count, cli_stats *st) {
    if (host_set) {
        uint32_t nb = 0, nm = 0;
        uint64_t tris = 0;
        for (uint32_t i = 0; i < banyan_hosts_count(host_set); i++) {
            banyan_host_info info;
            if (banyan_hosts_info(host_set, i, &info, NULL)) continue;
            nb += info.kind == 0;
            nm += info.kind == 1;
            tris += info.triangle_count;
        }
        char buf[128];
        snprintf(buf, sizeof buf, "{\"boxes\": %u, \"meshes\": %u, \"triangles\": %" PRIu64 "}", nb, nm, tris);
        cli_stat_raw(st, "host_set", buf);
    }
    for (uint32_t i = 0; i < count && i < 1; i++) {
        const double *o = meshes[i]->origin;
        if (o[0] != 0 || o[1] != 0 || o[2] != 0) { /* far from the world's origin: where the mesh's zero is */
            char buf[128];
            snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", o[0], o[1], o[2]);
            cli_stat_raw(st, "origin", buf);
        }
    }
}

/* Writes the meshes to out_path: with --lod through cli_write_lods, else
 * one write (glTF or USD, cli_write_nodes) within what the budget has left. A failure is reported
 * here (with the budget's meaning when it ran out). Returns 0, or 1. */
static int write_output(const cli_command *cmd, const char *out_path, banyan_mesh **meshes, char **names,
                        uint32_t count, const cli_lod *lod, int threads, const banyan_gltf_options *gltf_opt,
                        const cli_budget *budget, cli_stats *st, banyan_error *err) {
    banyan_budget left;
    banyan_status ws = lod->count
                           ? cli_write_lods(out_path, meshes, names, count, lod, threads, gltf_opt, budget, st, err)
                           : cli_budget_left(budget, "writing", &left, err);
    if (!lod->count && !ws) { /* plain nodes: the bytes of banyan_gltf_write_ex for glTF */
        banyan_gltf_node *nodes = calloc(count, sizeof *nodes);
        for (uint32_t i = 0; nodes && i < count; i++) nodes[i].mesh = meshes[i], nodes[i].name = names ? names[i] : NULL;
        ws = nodes ? cli_write_nodes(out_path, nodes, count, gltf_opt, &left, err) : BANYAN_E_NOMEM;
        if (!nodes) snprintf(err->message, sizeof err->message, "out of memory for the nodes");
        free(nodes);
    }
    if (ws) {
        fprintf(stderr, "banyan %s: writing %s: %s: %s%s\n", cmd->name, out_path, banyan_status_name(ws),
                err->message,
                ws == BANYAN_E_LIMIT ? " (what generation left of the command's max_seconds and max_memory_mb "
                                       "is the budget of --lod, the textures and the write)"
                                     : "");
        return 1;
    }
    return 0;
}

/* --pivot-painter: each mesh's two textures beside out_path (its name
 * without the extension, then _<i> when there are several meshes), with
 * --stats' "pivot_painter" per mesh. Returns 0, or 1 (reported). */
static int write_pivot_painter(const cli_command *cmd, const char *out_path, banyan_mesh **meshes, uint32_t count,
                               int sync, cli_stats *st, banyan_error *err) {
    const char *dot = strrchr(out_path, '.');
    const size_t stem = dot ? (size_t)(dot - out_path) : strlen(out_path);
    char *prefix = malloc(stem + 16);
    if (!prefix) return 1;
    char json[4096];
    size_t used = 0;
    json[used++] = '[';
    for (uint32_t i = 0; i < count; i++) {
        memcpy(prefix, out_path, stem);
        if (count > 1) snprintf(prefix + stem, 16, "_%u", i);
        else prefix[stem] = '\0';
        banyan_pivot_painter_options o = {0.0, sync};
        banyan_pivot_painter_info info;
        banyan_status s = banyan_pivot_painter_write(prefix, meshes[i], &o, &info, err);
        if (s) {
            fprintf(stderr, "banyan %s: --pivot-painter %s: %s: %s\n", cmd->name, prefix, banyan_status_name(s),
                    err->message);
            free(prefix);
            return 1;
        }
        if (used < sizeof json - 200)
            used += (size_t)snprintf(json + used, sizeof json - used,
                                     "%s{\"elements\": %u, \"merged\": %u, \"width\": %u, \"height\": %u, "
                                     "\"depth\": %u}",
                                     i ? ", " : "", info.elements, info.merged, info.width, info.height, info.depth);
    }
    snprintf(json + used, sizeof json - used, "]");
    cli_stat_raw(st, "pivot_painter", json);
    free(prefix);
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 2) return usage(stderr);
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) return usage(stdout);
    if (!strcmp(argv[1], "--version")) {
        printf("banyan %s (ABI %d)\n", banyan_version_string(), banyan_abi_version());
        return 0;
    }
    if (!strcmp(argv[1], "textures")) return cli_textures_main(argc, argv);
    const cli_command *cmd = NULL;
    for (int i = 0; cli_commands[i]; i++)
        if (!strcmp(cli_commands[i]->name, argv[1])) cmd = cli_commands[i];
    if (!cmd) {
        fprintf(stderr, "banyan: unknown command '%s'\n", argv[1]);
        return usage(stderr);
    }

    static cli_job job; /* large (hosts); one per process */
    cli_args A = {NULL, NULL, 0, 0, {0, 0, {0}}, {0}, NULL, NULL, 0, 0, NULL, 0};
    banyan_gltf_options_init(&A.gltf_opt);
    A.sets = calloc((size_t)argc, sizeof *A.sets);
    A.host_args = calloc((size_t)argc, sizeof *A.host_args);
    if (!A.sets || !A.host_args) {
        free(A.sets);
        free(A.host_args);
        return 1;
    }
    int bad = parse_args(argc, argv, cmd, &job, &A);
    if (bad) {
        free(A.sets);
        free(A.host_args);
        return bad == 1 ? usage(stderr) : 2;
    }
    const char *out_path = A.out_path;
    int stats = A.stats, list = A.list;
    cli_lod lod = A.lod;
    banyan_gltf_options gltf_opt = A.gltf_opt;
    const char **sets = A.sets, **host_args = A.host_args;
    int n_host_args = A.n_host_args;
    if (list) {
        list_params(cmd);
        free(sets);
        free(host_args);
        return 0;
    }
    /* A bad -o is reported now, not after a long generation: a bad
     * command line (exit 2). */
    if (A.pivot_painter && (!out_path || cli_is_usd(out_path) || lod.count)) {
        fprintf(stderr, "banyan %s: --pivot-painter needs -o out.glb or out.gltf and no --lod (the textures go "
                        "beside the glTF file and index the finest mesh's vertices)\n", cmd->name);
        free(sets);
        free(host_args);
        return 2;
    }
    if (out_path && !out_path_ok(cmd, out_path)) {
        free(sets);
        free(host_args);
        return 2;
    }

    int rc = 1;
    char *text = NULL;
    banyan_mesh **meshes = NULL;
    char **names = NULL;
    uint32_t count = 0;
    banyan_error err = {0, ""};
    banyan_hosts *host_set = NULL;
    banyan_host_mesh **host_read = calloc((size_t)n_host_args + 1, sizeof *host_read);
    banyan_host_mesh *host_extra = calloc((size_t)n_host_args + 1, sizeof *host_extra);
    void *params = calloc(1, cmd->params_size);
    if (!params || !host_read || !host_extra) goto out;
    if (n_host_args && !cmd->default_hosts) {
        fprintf(stderr, "banyan %s: --host: this command takes no hosts (roots and ivy do)\n", cmd->name);
        goto out;
    }
    if (load_params(cmd, &job, &A, params, &text, &err)) goto out;
    banyan_generator g = (banyan_generator)cmd->generator;
    /* The command's budget, from here to the written file: the hosts'
     * reading, generation, --lod, the textures and the write. */
    cli_budget budget;
    cli_budget_start(&budget, cmd, params);
    int hosts_read = 0;
    rc = load_hosts(cmd, &job, text, host_args, n_host_args, host_read, host_extra, &budget, &host_set, &hosts_read,
                    &err);
    if (rc) goto out;
    rc = 1;
    /* The set holds its own copy of the meshes. */
    for (int i = 0; i < n_host_args; i++) {
        banyan_host_mesh_free(host_read[i]);
        host_read[i] = NULL;
    }
    job.host_set = host_set;
    /* The hosts' reading came out of the command's max_seconds: the
     * generator gets what is left. */
    banyan_budget gen_left;
    if (hosts_read && banyan_param_find(g, "max_seconds") && !cli_budget_left(&budget, "generating", &gen_left, NULL)) {
        char seconds[32];
        snprintf(seconds, sizeof seconds, "%.3f", gen_left.max_seconds);
        banyan_param_set_text(g, params, "max_seconds", seconds, NULL);
    }
    if (!host_set && job.n_hosts == 0 && cmd->default_hosts) cmd->default_hosts(&job);

    cli_stats st;
    st.len = 0;
    st.warning[0] = '\0';
    st.stats_ms = 0;
    job.stats = stats;
    banyan_progress progress = {show_progress, (void *)cmd->name};
    if (isatty(STDERR_FILENO)) job.progress = &progress;
    double t0 = cli_now_ms();
    banyan_status s = cmd->run(&job, params, &meshes, &names, &count, &st, &err);
    double t1 = cli_now_ms();
    if (job.progress) fprintf(stderr, "\r%-14s\r", ""); /* the line cleared */
    if (s) {
        fprintf(stderr, "banyan %s: %s: %s\n", cmd->name, banyan_status_name(s), err.message);
        goto out;
    }
    stat_hosts_origin(host_set, meshes, count, &st);
    double t2 = t1;
    if (out_path) {
        if (write_output(cmd, out_path, meshes, names, count, &lod, job.threads, &gltf_opt, &budget, &st, &err))
            goto out;
        if (A.pivot_painter && write_pivot_painter(cmd, out_path, meshes, count, gltf_opt.sync, &st, &err)) goto out;
        t2 = cli_now_ms();
    }
    if (stats) {
        uint64_t verts = 0, tris = 0;
        for (uint32_t i = 0; i < count; i++) {
            verts += meshes[i]->vertex_count;
            tris += meshes[i]->index_count / 3;
        }
        printf("{\"command\": \"%s\", \"meshes\": %u, \"vertices\": %" PRIu64 ", \"triangles\": %" PRIu64
               ", \"time_ms\": {\"generate\": %.3f, \"stats\": %.3f, \"write\": %.3f}%s%.*s}\n",
               cmd->name, count, verts, tris, t1 - t0 - st.stats_ms, st.stats_ms, t2 - t1, st.len ? ", " : "",
               (int)st.len, st.buf);
    }
    rc = 0;
    if (st.warning[0]) {
        fprintf(stderr, "banyan %s: warning: %s\n", cmd->name, st.warning);
        rc = CLI_EXIT_WARNING;
    }
out:
    for (uint32_t i = 0; meshes && i < count; i++) banyan_mesh_free(meshes[i]);
    for (uint32_t i = 0; names && i < count; i++) free(names[i]);
    free(meshes);
    free(names);
    for (int i = 0; host_read && i < n_host_args; i++) banyan_host_mesh_free(host_read[i]);
    free(host_read);
    free(host_extra);
    banyan_hosts_free(host_set);
    free(params);
    free(text);
    free(sets);
    free(host_args);
    return rc;
}
