/* budget.c - the command's one budget: the generator's max_seconds and
 * max_memory_mb (from --set or the preset) count from the start of the
 * hosts' reading to the end of the write, so each stage (the hosts,
 * generation, the levels of detail, the textures, the glTF writer) gets
 * what the ones before it left (banyan_budget), and a spent budget stops
 * the command with BANYAN_E_LIMIT. */
#include <stdio.h>
#include <string.h>

#include "base/process.h"
#include "cli.h"

static double param_double(const cli_command *cmd, const void *params, const char *key, double dflt) {
    if (cmd->generator < 0) return dflt;
    const banyan_param_info *pi = banyan_param_find((banyan_generator)cmd->generator, key);
    if (!pi || pi->type != BANYAN_PT_DOUBLE) return dflt;
    double v;
    memcpy(&v, (const char *)params + pi->offset, sizeof v);
    return v;
}

void cli_budget_start(cli_budget *b, const cli_command *cmd, const void *params) {
    banyan_budget d;
    banyan_budget_init(&d);
    b->max_seconds = param_double(cmd, params, "max_seconds", d.max_seconds);
    b->max_memory_mb = param_double(cmd, params, "max_memory_mb", d.max_memory_mb);
    b->t0 = process_now();
    b->rss0_mb = process_rss_mb();
}

banyan_status cli_budget_left(const cli_budget *b, const char *stage, banyan_budget *out, banyan_error *err) {
    banyan_budget_init(out);
    double spent = process_now() - b->t0, used = process_rss_mb() - b->rss0_mb;
    out->max_seconds = b->max_seconds - spent;
    out->max_memory_mb = b->max_memory_mb - (used > 0.0 ? used : 0.0);
    if (out->max_seconds < 0.01) {
        if (err) {
            err->code = BANYAN_E_LIMIT;
            snprintf(err->message, sizeof err->message,
                     "%s not started: %.2f s spent of max_seconds = %g; raise max_seconds or ask for less work", stage,
                     spent, b->max_seconds);
        }
        return BANYAN_E_LIMIT;
    }
    if (out->max_memory_mb < 16.0) {
        if (err) {
            err->code = BANYAN_E_LIMIT;
            snprintf(err->message, sizeof err->message,
                     "%s not started: %.0f MB held of max_memory_mb = %g; raise max_memory_mb or ask for less work",
                     stage, used, b->max_memory_mb);
        }
        return BANYAN_E_LIMIT;
    }
    return BANYAN_OK;
}
