/* `banyan ivy`: ivy climbing hosts (spec/ivy.md): the preset's boxes and
 * meshes and any --host meshes. Without hosts it grows on a 3 m x 3 m
 * wall whose face is the plane y = 0 (x in [-1.5, 1.5], z in [0, 3]), the
 * paper's setting. --stats prints the generator's measures: bud counts
 * by state, attached fraction, branch points, crossings, covered area and
 * density. */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"

static void init(void *p) { banyan_ivy_params_init((banyan_ivy_params *)p); }

static void default_hosts(cli_job *job) {
    job->hosts[0] = banyan_box_make(0.0, 0.1, 1.5, 1.5, 0.1, 1.5);
    job->n_hosts = 1;
}

static banyan_status run(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err) {
    const banyan_ivy_params *p = params;
    banyan_ivy *iv = NULL;
    const banyan_hosts *hs;
    banyan_hosts *own;
    banyan_status s = cli_job_hosts(job, &hs, &own, err);
    if (!s) s = banyan_ivy_create(p, hs, &iv, err);
    if (s) {
        banyan_hosts_free(own);
        return s;
    }
    banyan_ivy_stats st;
    banyan_mesh **m = calloc(1, sizeof *m);
    char **nm = calloc(1, sizeof *nm);
    if (!m || !nm) {
        s = BANYAN_E_NOMEM;
        if (err) {
            err->code = s;
            snprintf(err->message, sizeof err->message, "out of memory");
        }
    }
    /* In up to 100 parts when showing progress (the same plant as all the
     * steps at once), the fraction of steps done. */
    const int32_t steps = banyan_ivy_steps(p); /* the params are checked: >= 0 */
    int32_t parts = job->progress ? (steps < 100 ? steps : 100) : 1;
    for (int32_t k = 0, done = 0; !s && k < parts; k++) {
        int32_t to = (int32_t)((int64_t)steps * (k + 1) / (parts ? parts : 1));
        s = banyan_ivy_step(iv, to - done, err);
        done = to;
        if (job->progress) job->progress->fn(job->progress->user, (double)done / steps);
    }
    if (!s && parts == 0) s = banyan_ivy_step(iv, 0, err);
    if (!s) s = banyan_ivy_get_stats(iv, &st, err);
    if (!s) s = banyan_ivy_mesh(iv, &m[0], err);
    banyan_ivy_free(iv);
    banyan_hosts_free(own);
    if (!s) {
        nm[0] = malloc(4);
        if (nm[0]) snprintf(nm[0], 4, "ivy");
    }
    if (s) {
        free(m);
        free(nm);
        return s;
    }
    *meshes = m;
    *names = nm;
    *count = 1;
    char buf[256];
    snprintf(buf, sizeof buf, "{\"A0\": %d, \"A1\": %d, \"A2\": %d, \"D\": %d, \"Z\": %d}", st.by_state[0],
             st.by_state[1], st.by_state[2], st.by_state[3], st.by_state[4]);
    cli_stat_num(stats, "steps", st.steps);
    cli_stat_num(stats, "buds", st.buds);
    cli_stat_raw(stats, "buds_by_state", buf);
    cli_stat_num(stats, "attached", st.attached);
    cli_stat_num(stats, "attached_fraction", st.attached_fraction);
    cli_stat_num(stats, "branch_points", st.branch_points);
    cli_stat_num(stats, "crossings", st.crossings);
    cli_stat_num(stats, "covered_area_m2", st.covered_area);
    cli_stat_num(stats, "density_per_m2", st.density);
    cli_stat_num(stats, "stem_length_m", st.stem_length);
    cli_stat_num(stats, "step_seconds", st.step_seconds);
    cli_stat_num(stats, "cannot_grow", st.cannot_grow);
    if (st.cannot_grow)
        snprintf(stats->warning, sizeof stats->warning, "%s (%d buds after %d steps)",
                 banyan_ivy_growth_text(st.cannot_grow), st.buds, st.steps);
    return BANYAN_OK;
}

const cli_command cli_cmd_ivy = {"ivy", BANYAN_GEN_IVY, "ivy climbing host boxes and meshes", sizeof(banyan_ivy_params),
                                 init, default_hosts, run, NULL};
