/* test_files.h - reading a whole file (presets, shaders) in tests and
 * benchmarks, and walking the shipped presets of one generator. */
#ifndef BANYAN_TEST_FILES_H
#define BANYAN_TEST_FILES_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"

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

/* Calls fn(path, name, ctx) for every <dir>/<prefix>*.json in name order
 * (name: the file name without .json), so a new preset is tested as soon
 * as it is added. Returns how many it found, -1 if dir cannot be read. */
static inline int test_each_preset(const char *dir, const char *prefix,
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
    for (int i = 0; i < n; i++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s.json", dir, names[i]);
        fn(path, names[i], ctx);
        free(names[i]);
    }
    return n;
}

#endif
