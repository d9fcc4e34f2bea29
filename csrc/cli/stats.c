/* The --stats JSON object a command fills (cli.h: cli_stats), for main.c
 * and the level-of-detail writer (lod_write.c). */
#include <stdio.h>

#include "cli.h"

static void append(cli_stats *s, const char *key, const char *val) {
    if (s->len >= sizeof s->buf) return;
    int n = snprintf(s->buf + s->len, sizeof s->buf - s->len, "%s\"%s\": %s", s->len ? ", " : "", key, val);
    if (n > 0) s->len += (size_t)n;
    if (s->len > sizeof s->buf) s->len = sizeof s->buf;
}

void cli_stat_num(cli_stats *s, const char *key, double v) {
    char b[64];
    snprintf(b, sizeof b, "%.17g", v);
    append(s, key, b);
}

void cli_stat_raw(cli_stats *s, const char *key, const char *json) { append(s, key, json); }
