/* `banyan roots`: strangler-fig roots around hosts (spec roots.md): the
 * preset's boxes and meshes and any --host meshes. Without hosts it grows
 * round a trunk-like box. --stats adds the generator's own measures
 * (growth points per kind, branch roots that reached their end, re-routes
 * and push-outs, least clearance). */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"

static void init(void *p) { banyan_roots_params_init((banyan_roots_params *)p); }

/* A trunk 0.8 m wide and 8 m tall standing on the ground. */
static void default_hosts(cli_job *job) {
    job->hosts[0] = banyan_box_make(0, 0, 4, 0.4, 0.4, 4);
    job->n_hosts = 1;
}

static banyan_status run(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err) {
    (void)names;
    banyan_mesh **m = calloc(1, sizeof *m);
    if (!m) return BANYAN_E_NOMEM;
    banyan_roots_stats st;
    const banyan_roots_params *p = params;
    const banyan_hosts *hs;
    banyan_hosts *own;
    banyan_status s = cli_job_hosts(job, &hs, &own, err);
    if (!s) s = banyan_roots_generate(p, hs, &m[0], &st, job->progress, err);
    banyan_hosts_free(own);
    if (s) {
        free(m);
        return s;
    }
    *meshes = m;
    *count = 1;
    /* Generation time is the "time_ms" the CLI prints around run(). */
    char buf[256];
    snprintf(buf, sizeof buf, "{\"main\": %u, \"first\": %u, \"second\": %u}", st.main_points, st.first_points,
             st.second_points);
    cli_stat_raw(stats, "growth_points", buf);
    cli_stat_num(stats, "repair_points", st.repair_points);
    snprintf(buf, sizeof buf, "{\"grown\": %u, \"reached_end\": %u}", st.first_roots, st.first_reached);
    cli_stat_raw(stats, "first_branch_roots", buf);
    cli_stat_num(stats, "second_branch_roots", st.second_roots);
    snprintf(buf, sizeof buf, "{\"events\": %u, \"full_turn_pushouts\": %u}", st.reroute_events,
             st.reroute_pushouts);
    cli_stat_raw(stats, "reroutes", buf);
    snprintf(buf, sizeof buf, "{\"second_branch\": %u, \"correction\": %u}", st.second_pushouts,
             st.correction_pushouts);
    cli_stat_raw(stats, "pushouts", buf);
    cli_stat_num(stats, "main_roots_on_ground", st.mains_on_ground);
    cli_stat_num(stats, "min_clearance_m", st.min_clearance);
    cli_stat_num(stats, "radius_m", st.radius);
    snprintf(buf, sizeof buf, "{\"vertices\": %u, \"triangles\": %u}", st.vertices, st.triangles);
    cli_stat_raw(stats, "mesh", buf);
    return BANYAN_OK;
}

const cli_command cli_cmd_roots = {"roots", BANYAN_GEN_ROOTS, "strangler-fig roots around host boxes and meshes",
                                   sizeof(banyan_roots_params), init, default_hosts, run, NULL};
