/* lod_plants.h - the plants the level-of-detail test and benchmark reduce
 * (tests/c/io/test_lod.c, tests/bench/bench_lod.c): shipped presets grown
 * as the CLI grows them. */
#ifndef BANYAN_LOD_PLANTS_H
#define BANYAN_LOD_PLANTS_H

#include <stdio.h>
#include <string.h>

#include "banyan.h"
#include "test_files.h"
#include "test_hosts.h"

/* name: keyaki_mature, keyaki_young, roots_tubes, roots_fused (the
 * roots_trunk preset as tubes / one fused surface), ivy_wall, segments
 * (the demo tree), avenue (the default, 60 m of two rows) or
 * avenue_small (2 x 2 trees; variants > 0 makes it instanced). NULL with
 * err filled on failure. */
static inline banyan_mesh *lod_plant(const char *name, int32_t variants, banyan_error *err) {
    char path[1024];
    banyan_mesh *m = NULL;
    banyan_status s = BANYAN_E_INVALID_ARG;
    if (!strncmp(name, "keyaki_", 7)) {
        banyan_keyaki_params p;
        banyan_keyaki_params_init(&p);
        snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
        if (!(s = test_load_preset(BANYAN_GEN_KEYAKI, &p, path, NULL, 0, NULL, err)))
            s = banyan_keyaki_generate(&p, &m, NULL, NULL, err);
    } else if (!strncmp(name, "roots_", 6)) {
        banyan_roots_params p;
        banyan_box hosts[8];
        uint32_t nh = 0;
        banyan_roots_params_init(&p);
        snprintf(path, sizeof path, "%s/presets/roots_trunk.json", BANYAN_SOURCE_DIR);
        if (!(s = test_load_preset(BANYAN_GEN_ROOTS, &p, path, hosts, 8, &nh, err))) {
            p.surface = strcmp(name, "roots_fused") ? BANYAN_ROOTS_TUBES : BANYAN_ROOTS_FUSED;
            s = test_roots_boxes(&p, hosts, nh, &m, err);
        }
    } else if (!strcmp(name, "ivy_wall")) {
        banyan_ivy_params p;
        banyan_box hosts[8];
        uint32_t nh = 0;
        banyan_ivy_params_init(&p);
        snprintf(path, sizeof path, "%s/presets/ivy_wall.json", BANYAN_SOURCE_DIR);
        if (!(s = test_load_preset(BANYAN_GEN_IVY, &p, path, hosts, 8, &nh, err)))
            s = test_ivy_boxes(&p, hosts, nh, &m, err);
    } else if (!strcmp(name, "segments")) {
        banyan_segments_params p;
        banyan_segments_params_init(&p);
        enum { CAP = 4096 };
        static banyan_segment_input segs[CAP];
        double trunk[6];
        uint32_t n = 0;
        if (!(s = banyan_segments_demo(&p, segs, CAP, &n, trunk, err)))
            s = banyan_segments_generate(&p, segs, n, trunk, &m, NULL, NULL, err);
    } else if (!strncmp(name, "avenue", 6)) {
        banyan_avenue_params p;
        banyan_avenue_params_init(&p);
        if (!strcmp(name, "avenue_small")) {
            p.placement = BANYAN_AVENUE_COUNT;
            p.count = 2;
            p.end[0] = 16;
        }
        p.variants = variants;
        p.threads = 2;
        s = banyan_avenue_generate(&p, NULL, 0, &m, NULL, err);
    }
    if (s) {
        banyan_mesh_free(m);
        return NULL;
    }
    return m;
}

#endif
