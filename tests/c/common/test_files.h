/* test_files.h - reading a whole file (presets, shaders) in tests and
 * benchmarks, and walking the shipped presets of one generator. */
#ifndef BANYAN_TEST_FILES_H
#define BANYAN_TEST_FILES_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"

/* dir/name in one of 4 rotating buffers, so one call can take a few. */
static inline const char *test_join(const char *dir, const char *name) {
    static char buf[4][1200];
    static int slot;
    char *p = buf[slot++ & 3];
    snprintf(p, sizeof buf[0], "%s/%s", dir, name);
    return p;
}

/* A NUL-terminated malloc'd copy of the file, or NULL. */
static inline char *test_read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    if (b) b[n] = 0;
    if (len) *len = b ? (size_t)n : 0;
    return b;
}

/* Applies argv[first..argc) as key=value to params (banyan_param_set_text),
 * as the CLI's --set: 0, or 1 after naming the bad one on stderr. */
static inline int test_param_overrides(banyan_generator g, void *params, int first, int argc, char **argv) {
    for (int i = first; i < argc; i++) {
        char key[256];
        const char *eq = strchr(argv[i], '=');
        if (!eq || eq - argv[i] >= (long)sizeof key) return fprintf(stderr, "bad override %s\n", argv[i]), 1;
        memcpy(key, argv[i], (size_t)(eq - argv[i]));
        key[eq - argv[i]] = 0;
        banyan_error err;
        if (banyan_param_set_text(g, params, key, eq + 1, &err)) {
            fprintf(stderr, "%s: %s\n", argv[i], err.message);
            return 1;
        }
    }
    return 0;
}

/* Reads the preset file at path and applies it to params (already
 * initialised), and, when hosts is not NULL, reads its hosts (at most cap)
 * into hosts and *n_hosts. Returns the status; err says why. */
static inline banyan_status test_load_preset(banyan_generator g, void *params, const char *path, banyan_box *hosts,
                                             uint32_t cap, uint32_t *n_hosts, banyan_error *err) {
    size_t len;
    char *text = test_read_file(path, &len);
    if (!text) {
        snprintf(err->message, sizeof err->message, "cannot read %.200s", path);
        return err->code = BANYAN_E_IO;
    }
    banyan_status s = banyan_preset_apply(g, params, text, len, path, err);
    if (!s && hosts) s = banyan_preset_hosts(text, len, path, hosts, cap, n_hosts, err);
    free(text);
    return s;
}

static inline int test_name_cmp(const void *a, const void *b) {
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* 1 when the preset file at path has a mesh host ("mesh" in "hosts"):
 * banyan_preset_hosts refuses it; read it with test_load_host_set. */
static inline int test_preset_has_mesh_hosts(const char *path) {
    size_t len;
    char *text = test_read_file(path, &len);
    if (!text) return 0;
    banyan_box box[1];
    uint32_t n = 0;
    int mesh = banyan_preset_hosts(text, len, path, box, 1, &n, NULL) == BANYAN_E_UNSUPPORTED;
    free(text);
    return mesh;
}

/* The host set of the preset file at path (boxes and meshes, mesh files
 * relative to the preset's folder), as banyan_preset_host_set builds it. */
static inline banyan_status test_load_host_set(const char *path, banyan_hosts **out, banyan_error *err) {
    *out = NULL;
    size_t len;
    char *text = test_read_file(path, &len);
    if (!text) {
        snprintf(err->message, sizeof err->message, "cannot read %.200s", path);
        return err->code = BANYAN_E_IO;
    }
    char dir[2048];
    const char *slash = strrchr(path, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    banyan_status s = banyan_preset_host_set(text, len, path, dir, NULL, 0, out, err);
    free(text);
    return s;
}

/* A roots preset's params and its hosts (boxes or meshes); *hosts NULL on
 * failure. */
static inline banyan_status test_load_roots(const char *path, banyan_roots_params *p, banyan_hosts **hosts,
                                            banyan_error *err) {
    banyan_roots_params_init(p);
    *hosts = NULL;
    banyan_status s = test_load_preset(BANYAN_GEN_ROOTS, p, path, NULL, 0, NULL, err);
    return s ? s : test_load_host_set(path, hosts, err);
}

static inline int test_walk_presets(const char *dir, const char *prefix, int meshes,
                                    void (*fn)(const char *path, const char *name, void *ctx), void *ctx);

/* Calls fn(path, name, ctx) for every <dir>/<prefix>*.json with box hosts
 * (or none) in name order (name: the file name without .json), so a new
 * preset is tested as soon as it is added. Returns how many it found, -1
 * if dir cannot be read. Presets with mesh hosts are walked by
 * test_each_mesh_preset. */
static inline int test_each_preset(const char *dir, const char *prefix,
                                   void (*fn)(const char *path, const char *name, void *ctx), void *ctx) {
    return test_walk_presets(dir, prefix, 0, fn, ctx);
}

/* The same for the presets with a mesh host (test_load_host_set). */
static inline int test_each_mesh_preset(const char *dir, const char *prefix,
                                        void (*fn)(const char *path, const char *name, void *ctx), void *ctx) {
    return test_walk_presets(dir, prefix, 1, fn, ctx);
}

static inline int test_walk_presets(const char *dir, const char *prefix, int meshes,
                                    void (*fn)(const char *path, const char *name, void *ctx), void *ctx) {
    DIR *d = opendir(dir);
    if (!d) return -1;
    char *names[256];
    int n = 0;
    size_t plen = strlen(prefix);
    for (struct dirent *e; (e = readdir(d)) != NULL && n < 256;) {
        size_t len = strlen(e->d_name);
        if (len > plen + 5 && !strncmp(e->d_name, prefix, plen) && !strcmp(e->d_name + len - 5, ".json")) {
            names[n] = malloc(len - 4);
            if (!names[n]) break;
            memcpy(names[n], e->d_name, len - 5);
            names[n++][len - 5] = 0;
        }
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], test_name_cmp);
    int walked = 0;
    for (int i = 0; i < n; i++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s.json", dir, names[i]);
        if (test_preset_has_mesh_hosts(path) == meshes) {
            fn(path, names[i], ctx);
            walked++;
        }
        free(names[i]);
    }
    return walked;
}

#endif
