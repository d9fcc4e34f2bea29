/* `banyan keyaki`: one keyaki tree (spec/keyaki.md). Takes no hosts.
 * --stats adds the tree's own measures: Strahler stream counts N_k, the
 * bifurcation ratios N_k / N_{k+1} and their mean, tips, forks, breaks
 * and the skeleton's height and crown width (banyan_keyaki_generate's
 * stats, of the skeleton the mesh was built from), then the height and
 * crown width of the mesh written:
 * the crown's twigs and leaves reach past the skeleton's branch ends. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void init(void *p) { banyan_keyaki_params_init((banyan_keyaki_params *)p); }

/* Appends the measures of one skeleton as stats members. */
static void cli_keyaki_stats_json(cli_stats *stats, const banyan_keyaki_stats *st) {
    char buf[2048];
    size_t n = 0;
    n += (size_t)snprintf(buf + n, sizeof buf - n, "[");
    for (int k = 0; k < st->max_order && n < sizeof buf; k++)
        n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%d", k ? ", " : "", st->stream_count[k]);
    if (n < sizeof buf) snprintf(buf + n, sizeof buf - n, "]");
    cli_stat_raw(stats, "stream_counts", buf);
    n = 0;
    n += (size_t)snprintf(buf + n, sizeof buf - n, "[");
    for (int k = 0; k + 1 < st->max_order && n < sizeof buf; k++)
        n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%.17g", k ? ", " : "", st->bifurcation_ratio[k]);
    if (n < sizeof buf) snprintf(buf + n, sizeof buf - n, "]");
    cli_stat_raw(stats, "bifurcation_ratios", buf);
    cli_stat_num(stats, "mean_bifurcation_ratio", st->mean_bifurcation_ratio);
    cli_stat_num(stats, "max_order", st->max_order);
    cli_stat_num(stats, "branches", st->node_count);
    cli_stat_num(stats, "tips", st->tip_count);
    cli_stat_num(stats, "forks", st->fork_count);
    cli_stat_num(stats, "breaks", st->break_count);
    cli_stat_num(stats, "max_level", st->max_level);
    cli_stat_num(stats, "mean_run_length", st->mean_run_length);
    cli_stat_num(stats, "skeleton_height_m", st->height);
    cli_stat_num(stats, "skeleton_crown_width_m", st->crown_width);
}

void cli_tree_reach(const banyan_mesh *m, int64_t group, const double base[3], double *height, double *width) {
    double o[3], top = -HUGE_VAL, r2 = 0;
    for (int k = 0; k < 3; k++) o[k] = m->origin[k] - base[k];
    for (uint32_t p = 0; p < m->part_count; p++) {
        const banyan_part *pt = &m->parts[p];
        if (group >= 0 && pt->group != (uint32_t)group) continue;
        for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count; v++) {
            const float *q = m->positions + 3 * (size_t)v;
            double dx = o[0] + q[0], dy = o[1] + q[1], z = o[2] + q[2];
            if (z > top) top = z;
            if (dx * dx + dy * dy > r2) r2 = dx * dx + dy * dy;
        }
    }
    *height = top > -HUGE_VAL ? top : 0.0;
    *width = 2.0 * sqrt(r2);
}

static banyan_status run(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err) {
    const banyan_keyaki_params *p = params;
    banyan_keyaki_stats st;
    banyan_mesh **m = calloc(1, sizeof *m);
    char **nm = calloc(1, sizeof *nm);
    if (!m || !nm) {
        free(m);
        free(nm);
        return BANYAN_E_NOMEM;
    }
    banyan_status s = banyan_keyaki_generate(p, &m[0], &st, job->progress, err);
    if (s) {
        free(m);
        free(nm);
        return s;
    }
    nm[0] = malloc(16);
    if (nm[0]) strcpy(nm[0], "keyaki");
    *meshes = m;
    *names = nm;
    *count = 1;
    cli_keyaki_stats_json(stats, &st);
    if (job->stats) { /* the mesh's reach: a pass over its vertices, timed apart */
        const double t0 = cli_now_ms();
        double height, width;
        cli_tree_reach(m[0], -1, p->position, &height, &width);
        cli_stat_num(stats, "height_m", height);
        cli_stat_num(stats, "crown_width_m", width);
        stats->stats_ms = cli_now_ms() - t0;
    }
    return BANYAN_OK;
}

const cli_command cli_cmd_keyaki = {"keyaki", BANYAN_GEN_KEYAKI, "one keyaki (Zelkova) tree",
                                    sizeof(banyan_keyaki_params), init, NULL, run, NULL};
