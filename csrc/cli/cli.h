/* cli.h - the `banyan` command line tool: shared job description and the
 * per-generator command table. Each generator has one cmd_<name>.c with a
 * cli_command, listed in commands.c. */
#ifndef BANYAN_CLI_H
#define BANYAN_CLI_H

#include <stdio.h>

#include "banyan.h"

/* What the command line asked for, after the preset was read. */
typedef struct cli_job {
    const char *preset_path;     /* NULL when none */
    const char *preset_text;     /* file contents, NULL when none */
    size_t preset_len;
    banyan_box hosts[BANYAN_MAX_HOSTS];
    uint32_t n_hosts;            /* from the preset; 0 when it has none */
    /* Set when any host is a mesh (a preset "mesh" or --host): the command
     * grows on it instead of `hosts`. With boxes only it stays NULL and
     * the command grows on a set of `hosts` (cli_job_hosts). */
    const banyan_hosts *host_set;
    int threads;                 /* --threads N, 0 = all cores, at most CLI_MAX_THREADS */
    /* A "\r<command> 42 %" line on stderr when it is a terminal, else
     * NULL; run() hands it to the library call (or calls it itself). */
    const banyan_progress *progress;
    /* --stats: run() adds the generator's statistics (cli_stat_*); without
     * it, run() leaves out the ones that cost time of their own. */
    int stats;
} cli_job;

/* The host set a command grows on: job->host_set, or a set of the job's
 * boxes made into *own, which the caller frees (banyan_hosts_free). */
banyan_status cli_job_hosts(const cli_job *job, const banyan_hosts **hosts, banyan_hosts **own, banyan_error *err);

/* Generator-specific JSON written by --stats: run() appends
 * `"key": value` members with cli_stat_*; main wraps them in one object. */
typedef struct cli_stats {
    char buf[16384];
    size_t len;
    /* Set by run() when the output is written but not what was asked for
     * (an ivy that could not grow): main prints it and exits with
     * CLI_EXIT_WARNING. */
    char warning[512];
    /* Milliseconds run() spent on statistics after the library call
     * (timed apart from the generation: "time_ms"."stats"). */
    double stats_ms;
} cli_stats;

/* Milliseconds on the process's clock (statistics timed apart). */
double cli_now_ms(void);

/* --threads range: the avenue's threads field (banyan_avenue_params),
 * which the library checks again. */
#define CLI_MAX_THREADS BANYAN_AVENUE_MAX_THREADS

/* --lod: falling ratios of triangles kept, the last may be a billboard
 * (ratio 0, billboard 1). */
#define CLI_MAX_LODS BANYAN_LOD_MAX_LEVELS
typedef struct cli_lod {
    int count;
    int billboard;
    double ratio[CLI_MAX_LODS];
} cli_lod;
/* 1 when spec ("0.5,0.15,billboard") is well formed. */
int cli_lod_parse(const char *spec, cli_lod *out);
struct cli_command;
/* The command's budget, started once the params are final (budget.c):
 * the generator's max_seconds and max_memory_mb (the defaults for
 * commands without them) cover reading the hosts, generation, --lod,
 * the textures and the write. */
typedef struct cli_budget {
    double max_seconds, max_memory_mb;
    double t0, rss0_mb; /* when the budget started, and the resident MB then */
} cli_budget;
void cli_budget_start(cli_budget *b, const struct cli_command *cmd, const void *params);
/* What is left for `stage` ("the levels of detail"), as a banyan_budget;
 * BANYAN_E_LIMIT (err naming the field) when less than the library's
 * least (0.01 s, 16 MB) is left. */
banyan_status cli_budget_left(const cli_budget *b, const char *stage, banyan_budget *out, banyan_error *err);

/* Writes meshes with their levels of detail as MSFT_lod, each level and
 * the write within what is left of the budget; threads (--threads) 1 makes
 * the levels one after another, else the billboard beside the others. */
banyan_status cli_write_lods(const char *path, banyan_mesh *const *meshes, char *const *names, uint32_t count,
                             const cli_lod *lod, int threads, const banyan_gltf_options *opt,
                             const cli_budget *budget, cli_stats *st, banyan_error *err);

/* -o's format: 1 when path names USD text (.usda, .usd), else glTF. */
int cli_is_usd(const char *path);
/* The nodes written to path in the format its extension names
 * (banyan_usd_write_nodes_budget or banyan_gltf_write_nodes_budget). */
banyan_status cli_write_nodes(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                              const banyan_gltf_options *opt, const banyan_budget *budget, banyan_error *err);

/* Exit codes: 0 done, 1 refused or failed, 2 bad command line or hosts
 * refused before any work (a --host file, a preset's hosts: the same
 * input gives the same refusal), 3 written with a warning (docs/ivy.md,
 * "Hosts and start"). */
#define CLI_EXIT_BAD_INPUT 2
#define CLI_EXIT_WARNING 3
void cli_stat_num(cli_stats *s, const char *key, double v);
void cli_stat_raw(cli_stats *s, const char *key, const char *json);

typedef struct cli_command {
    const char *name;            /* subcommand */
    int generator;               /* banyan_generator, or -1 when it has no param table */
    const char *summary;         /* one line for --help */
    size_t params_size;
    void (*init)(void *params);  /* defaults */
    /* Fills default hosts when the preset and --host gave none (may leave
     * 0). NULL for commands that take no hosts (they refuse --host). */
    void (*default_hosts)(cli_job *job);
    /* Generates one or more meshes. *names may stay NULL. */
    banyan_status (*run)(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err);
    /* --set for commands without a param table (generator == -1). */
    banyan_status (*set)(void *params, const char *key, const char *value, banyan_error *err);
} cli_command;

extern const cli_command *const cli_commands[];

/* A tree as meshed (bark, twigs, leaves; the parts of `group`, or all for
 * -1): its highest vertex above `base` (world metres) and twice the
 * largest horizontal distance of a vertex from the vertical through
 * base, in double (cmd_keyaki.c; --stats of keyaki and avenue). */
void cli_tree_reach(const banyan_mesh *m, int64_t group, const double base[3], double *height, double *width);

/* `banyan textures -o DIR`: not a mesh command (cmd_textures.c). */
int cli_textures_main(int argc, char **argv);

#endif
