/* `banyan segments`: a tree composed of geometry-shader branch segments
 * (spec segments.md). The segment list comes from the preset's "segments"
 * (and optional "trunk"); without one, a random demo tree is grown from
 * --seed. Unattached segments are built but reported on stderr and in
 * --stats. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void init(void *p) { banyan_segments_params_init((banyan_segments_params *)p); }

static banyan_status run(const cli_job *job, const void *params, banyan_mesh ***meshes, char ***names,
                         uint32_t *count, cli_stats *stats, banyan_error *err) {
    (void)names;
    const banyan_segments_params *p = (const banyan_segments_params *)params;
    banyan_segment_input *segs = NULL;
    uint32_t n = 0, *unattached = NULL;
    double trunk[6];
    int32_t has_trunk = 0;
    const char *origin = "preset";
    banyan_status s = BANYAN_OK;
    if (job->preset_text) {
        s = banyan_segments_preset_read(job->preset_text, job->preset_len, job->preset_path, NULL, 0, &n, NULL, NULL,
                                        err);
        if (s) return s;
    }
    if (n) {
        segs = malloc(sizeof *segs * n);
        if (!segs) return BANYAN_E_NOMEM;
        s = banyan_segments_preset_read(job->preset_text, job->preset_len, job->preset_path, segs, n, &n, trunk,
                                        &has_trunk, err);
    } else {
        origin = "demo";
        segs = malloc(sizeof *segs * (size_t)p->demo_segments);
        if (!segs) return BANYAN_E_NOMEM;
        s = banyan_segments_demo(p, segs, (uint32_t)p->demo_segments, &n, trunk, err);
        has_trunk = 1;
    }
    banyan_mesh **m = NULL;
    banyan_segments_stats st;
    const double *tr = has_trunk ? trunk : NULL;
    if (!s) {
        m = calloc(1, sizeof *m);
        if (!m) s = BANYAN_E_NOMEM;
    }
    if (!s) s = banyan_segments_generate(p, segs, n, tr, &m[0], &st, job->progress, err);
    if (!s && st.unattached) { /* which ones, for the warning */
        unattached = malloc(sizeof *unattached * n);
        s = unattached ? banyan_segments_find_unattached(p, segs, n, tr, unattached, &st.unattached, err)
                       : BANYAN_E_NOMEM;
        if (s) banyan_mesh_free(m[0]);
    }
    if (s) {
        free(m);
        free(segs);
        free(unattached);
        return s;
    }
    char list[4096];
    size_t len = 0;
    list[len++] = '[';
    for (uint32_t i = 0; i < st.unattached && len + 16 < sizeof list; i++)
        len += (size_t)snprintf(list + len, sizeof list - len, "%s%u", i ? ", " : "", unattached[i]);
    list[len++] = ']';
    list[len] = '\0';
    if (st.unattached)
        fprintf(stderr, "banyan segments: warning: %u of %u segments are not attached to an earlier axis%s: %s\n",
                st.unattached, n, has_trunk ? " or the trunk" : "", list);
    char levels[256];
    len = 0;
    for (int i = 0; i < 8; i++)
        len += (size_t)snprintf(levels + len, sizeof levels - len, "%s%u", i ? ", " : "[", st.lines_per_level[i]);
    snprintf(levels + len, sizeof levels - len, "]");
    char quoted[16];
    snprintf(quoted, sizeof quoted, "\"%s\"", origin);
    cli_stat_raw(stats, "source", quoted);
    cli_stat_num(stats, "segments", st.segments);
    cli_stat_num(stats, "trunk", has_trunk);
    cli_stat_num(stats, "lines", st.lines);
    cli_stat_num(stats, "budget_hits", st.budget_hits);
    cli_stat_num(stats, "max_level", st.max_level);
    cli_stat_raw(stats, "lines_per_level", levels);
    cli_stat_num(stats, "unattached", st.unattached);
    cli_stat_raw(stats, "unattached_segments", list);
    free(segs);
    free(unattached);
    *meshes = m;
    *count = 1;
    return BANYAN_OK;
}

const cli_command cli_cmd_segments = {"segments", BANYAN_GEN_SEGMENTS,
                                      "a tree of geometry-shader branch segments (preset list or random demo)",
                                      sizeof(banyan_segments_params), init, NULL, run, NULL};
