/* `banyan avenue`: keyaki trees along the straight path start..end, one
 * or two rows, grown on --threads N threads (0 = all cores; the params'
 * threads field, as --set threads=N). --stats adds
 * the tree count and, over the trees, the mean, min and max of tips (the
 * skeleton's) and of crown widths (the mesh's: twice the farthest vertex
 * of the tree from its trunk's axis, twigs and leaves included) and the
 * mean Strahler bifurcation ratio; with --set
 * variants=N (instanced trees) also the variant and instance counts. A polyline path
 * is available through the library call (banyan_avenue_generate). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void init(void *p) { banyan_avenue_params_init((banyan_avenue_params *)p); }

/* Over the trees shown, the figures --stats prints. */
typedef struct tree_figures {
    double tips, width, ratio, tmin, tmax, wmin, wmax;
} tree_figures;

/* The trees' figures: an instanced avenue's tree i is its instance's
 * variant, grown from tree `variant`'s params (heading aside) at the
 * mesh's origin and drawn at the instance's scale, its skeleton's
 * statistics grown once per variant; an avenue's tree i is the parts of
 * group i, standing at its position. */
static banyan_status tree_stats(const banyan_mesh *a, const banyan_keyaki_params *trees, uint32_t n, tree_figures *f,
                                banyan_error *err) {
    const int instanced = a->instance_count == n;
    banyan_keyaki_stats *by = calloc(n ? n : 1, sizeof *by);
    double *reach = calloc(n ? n : 1, sizeof *reach);
    unsigned char *have = calloc(n ? n : 1, 1);
    banyan_status s = by && reach && have ? BANYAN_OK : BANYAN_E_NOMEM;
    *f = (tree_figures){0, 0, 0, 1e300, 0, 1e300, 0};
    for (uint32_t i = 0; !s && i < n; i++) {
        uint32_t k = instanced ? a->instances[i].variant : i;
        if (!have[k]) {
            if ((s = banyan_keyaki_skeleton_stats(&trees[k], &by[k], err))) break;
            double h;
            cli_tree_reach(a, k, instanced ? a->origin : trees[i].position, &h, &reach[k]);
            have[k] = 1;
        }
        const banyan_keyaki_stats *st = &by[k];
        double w = instanced ? reach[k] * a->instances[i].scale : reach[k];
        f->tips += st->tip_count;
        f->width += w;
        f->ratio += st->mean_bifurcation_ratio;
        if (st->tip_count < f->tmin) f->tmin = st->tip_count;
        if (st->tip_count > f->tmax) f->tmax = st->tip_count;
        if (w < f->wmin) f->wmin = w;
        if (w > f->wmax) f->wmax = w;
    }
    free(by);
    free(reach);
    free(have);
    return s;
}

static banyan_status run(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err) {
    const banyan_avenue_params *p = params;
    uint32_t n = 0;
    banyan_status s = banyan_avenue_layout(p, NULL, 0, NULL, 0, &n, err);
    if (s) return s;
    banyan_mesh **m = calloc(1, sizeof *m);
    char **nm = calloc(1, sizeof *nm);
    banyan_keyaki_params *trees = malloc(sizeof *trees * (n ? n : 1));
    if (!m || !nm || !trees) {
        s = BANYAN_E_NOMEM;
        goto fail;
    }
    if ((s = banyan_avenue_generate(p, NULL, 0, &m[0], job->progress, err))) goto fail;
    const double t0 = cli_now_ms();
    tree_figures f = {0, 0, 0, 0, 0, 0, 0};
    if (job->stats && ((s = banyan_avenue_layout(p, NULL, 0, trees, n, &n, err)) ||
                       (s = tree_stats(m[0], trees, n, &f, err)))) {
        banyan_mesh_free(m[0]);
        goto fail;
    }
    stats->stats_ms = cli_now_ms() - t0;
    free(trees);
    nm[0] = malloc(16);
    if (nm[0]) strcpy(nm[0], "avenue");
    *meshes = m;
    *names = nm;
    *count = 1;
    const banyan_mesh *a = m[0];
    cli_stat_num(stats, "trees", n);
    cli_stat_num(stats, "parts", a->part_count);
    if (a->instance_count > 0) { /* variants: distinct trees, drawn instance_count times */
        uint32_t variants = 0;
        for (uint32_t q = 0; q < a->part_count; q++)
            if (a->parts[q].group + 1 > variants) variants = a->parts[q].group + 1;
        cli_stat_num(stats, "variants", variants);
        cli_stat_num(stats, "instances", a->instance_count);
    }
    if (job->stats) {
        cli_stat_num(stats, "tips_mean", f.tips / n);
        cli_stat_num(stats, "tips_min", f.tmin);
        cli_stat_num(stats, "tips_max", f.tmax);
        cli_stat_num(stats, "crown_width_mean_m", f.width / n);
        cli_stat_num(stats, "crown_width_min_m", f.wmin);
        cli_stat_num(stats, "crown_width_max_m", f.wmax);
        cli_stat_num(stats, "mean_bifurcation_ratio", f.ratio / n);
    }
    return BANYAN_OK;
fail:
    free(m);
    free(nm);
    free(trees);
    return s;
}

const cli_command cli_cmd_avenue = {"avenue", BANYAN_GEN_AVENUE, "an avenue of keyaki trees",
                                    sizeof(banyan_avenue_params), init, NULL, run, NULL};
