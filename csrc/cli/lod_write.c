/* lod_write.c - the CLI's --lod: each mesh's coarser levels
 * (banyan_mesh_lod) written with it as MSFT_lod (banyan_gltf_write_nodes).
 *   --lod 0.5,0.15,billboard   ratios of the triangles kept, falling, and
 *                              optionally a last level of cross billboards. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "base/numparse.h"

int cli_lod_parse(const char *spec, cli_lod *out) {
    memset(out, 0, sizeof *out);
    const char *p = spec;
    double last = 1.0;
    while (*p) {
        const char *e = strchr(p, ',');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        if (out->count >= CLI_MAX_LODS || out->billboard) return 0; /* billboard must come last */
        if (n == 9 && !strncmp(p, "billboard", 9)) {
            out->billboard = 1;
            out->ratio[out->count++] = 0;
        } else {
            char buf[64];
            double r;
            if (n == 0 || n >= sizeof buf) return 0;
            memcpy(buf, p, n);
            buf[n] = '\0';
            if (!num_parse_double(buf, &r) || !(r >= 0.001 && r < last)) return 0;
            out->ratio[out->count++] = r;
            last = r;
        }
        p += n;
        if (*p == ',') p++;
        if (e && !*p) return 0; /* a trailing comma */
    }
    return out->count > 0;
}

/* Levels of one mesh into lv[0 .. lod->count) (banyan_mesh_lods: the
 * ratios chained, the billboard beside them), under what is left of the
 * run's budget. */
static banyan_status levels_of(const banyan_mesh *mesh, const cli_lod *lod, int threads, const cli_budget *budget,
                               banyan_mesh **lv, banyan_error *err) {
    banyan_lod_params bb;
    banyan_lod_params_init(&bb);
    bb.billboard = 1;
    banyan_budget left;
    banyan_status s = cli_budget_left(budget, "the levels of detail", &left, err);
    if (!s)
        s = banyan_mesh_lods(mesh, lod->ratio, (uint32_t)(lod->count - (lod->billboard ? 1 : 0)),
                             lod->billboard ? &bb : NULL, threads, &left, lv, err);
    return s;
}

banyan_status cli_write_lods(const char *path, banyan_mesh *const *meshes, char *const *names, uint32_t count,
                             const cli_lod *lod, int threads, const banyan_gltf_options *opt,
                             const cli_budget *budget, cli_stats *st, banyan_error *err) {
    banyan_mesh **levels = calloc((size_t)count * CLI_MAX_LODS + 1, sizeof *levels);
    banyan_gltf_node *nodes = calloc((size_t)count + 1, sizeof *nodes);
    banyan_status s = levels && nodes ? BANYAN_OK : BANYAN_E_NOMEM;
    if (s && err) {
        err->code = s;
        snprintf(err->message, sizeof err->message, "out of memory for the levels of detail");
    }
    char tris[512];
    size_t tl = 0;
    tris[0] = '\0';
    for (uint32_t i = 0; !s && i < count; i++) {
        s = levels_of(meshes[i], lod, threads, budget, &levels[(size_t)i * CLI_MAX_LODS], err);
        for (int k = 0; !s && i == 0 && k < lod->count && tl + 32 < sizeof tris; k++)
            tl += (size_t)snprintf(tris + tl, sizeof tris - tl, "%s%u", k ? ", " : "", levels[k]->index_count / 3);
        nodes[i].mesh = meshes[i];
        nodes[i].name = names ? names[i] : NULL;
        nodes[i].lod_count = (uint32_t)lod->count;
        nodes[i].lods = (const banyan_mesh *const *)&levels[(size_t)i * CLI_MAX_LODS];
        nodes[i].lod_coverage = NULL;
    }
    if (!s) {
        char buf[600];
        snprintf(buf, sizeof buf, "[%s]", tris);
        cli_stat_raw(st, "lod_triangles", buf);
        banyan_budget left;
        s = cli_budget_left(budget, "writing", &left, err);
        if (!s) s = cli_write_nodes(path, nodes, count, opt, &left, err);
    }
    for (size_t k = 0; levels && k < (size_t)count * CLI_MAX_LODS; k++) banyan_mesh_free(levels[k]);
    free(levels);
    free(nodes);
    return s;
}
