/* params.h - internal side of the parameter tables (see banyan.h,
 * "parameter tables"). Each generator defines one table of
 * banyan_param_info rows; registry.c maps generators to tables. */
#ifndef BANYAN_PARAMS_H
#define BANYAN_PARAMS_H

#include <stddef.h>

#include "banyan.h"
#include "base/progress.h"

typedef struct param_table {
    const banyan_param_info *rows;
    int32_t count;
    size_t params_size; /* sizeof the generator's params struct */
} param_table;

/* The table of g; count 0 when g has none (not built yet or out of range). */
param_table param_table_get(banyan_generator g);

/* Writes vals[0..n-1] into the field `info` describes after checking
 * count, finiteness and range. For ENUM/BOOL/INT vals must be integral.
 * `where` prefixes messages (e.g. "presets/x.json:12: "). */
banyan_status param_assign(const banyan_param_info *info, void *params, const double *vals, int n,
                           const char *where, banyan_error *err);
/* Enum choice index of name in "a|b|c", or -1. */
int param_enum_index(const char *choices, const char *name, size_t len);

/* The envelope every preset reader shares (preset.c): size, strict UTF-8,
 * nesting, JSON syntax, nothing after the object, a JSON object with known
 * top-level keys, each once, and the schema. *root (a cJSON object) is
 * the caller's to cJSON_Delete. Messages start "<source>:<line>: ". */
struct cJSON;
banyan_status preset_parse(const char *text, size_t len, const char *source, struct cJSON **root,
                           banyan_error *err);
/* 1-based line of byte `offset` in text. */
int preset_line_at(const char *text, size_t len, size_t offset);

/* Row constructors: the key is the field name, so one name is used in C,
 * presets, --set and the add-on; `label` and `group` are what a panel
 * shows (banyan.h). */
#define BP_ROW(S, field, label, group, type, unit, lo, hi, choices, desc) \
    { #field, unit, desc, type, lo, hi, choices, offsetof(S, field), label, group }
#define BP_DOUBLE(S, field, label, group, unit, lo, hi, desc) \
    BP_ROW(S, field, label, group, BANYAN_PT_DOUBLE, unit, lo, hi, NULL, desc)
#define BP_INT(S, field, label, group, lo, hi, desc) BP_ROW(S, field, label, group, BANYAN_PT_INT, "", lo, hi, NULL, desc)
#define BP_BOOL(S, field, label, group, desc) BP_ROW(S, field, label, group, BANYAN_PT_BOOL, "", 0, 1, NULL, desc)
#define BP_ENUM(S, field, label, group, choices, desc) \
    BP_ROW(S, field, label, group, BANYAN_PT_ENUM, "", 0, 0, choices, desc)
#define BP_VEC3(S, field, label, group, unit, lo, hi, desc) \
    BP_ROW(S, field, label, group, BANYAN_PT_VEC3, unit, lo, hi, NULL, desc)
#define BP_COLOR(S, field, label, group, desc) BP_ROW(S, field, label, group, BANYAN_PT_COLOR, "", 0, 1, NULL, desc)
#define BP_SEED(S, field, label, group, desc) \
    BP_ROW(S, field, label, group, BANYAN_PT_SEED, "", 0, 18446744073709551615.0, NULL, desc)
/* The run's budget (base/progress.h), the same two rows in every table:
 * max_seconds and max_memory_mb, ranges from the PROG_MAX_* constants. */
#define BP_BUDGET(S, group)                                                                                      \
    BP_DOUBLE(S, max_seconds, "Time limit", group, "s", PROG_MAX_SECONDS_MIN, PROG_MAX_SECONDS_MAX,             \
              "wall time a run may take; past it the run stops with BANYAN_E_LIMIT"),                             \
    BP_DOUBLE(S, max_memory_mb, "Memory limit", group, "MB", PROG_MAX_MEMORY_MIN, PROG_MAX_MEMORY_MAX,          \
              "resident memory a run may add to what the process held when it began; past it the run stops "   \
              "with BANYAN_E_LIMIT")

/* The wind attributes switch (banyan.h, BANYAN_ATTR_WIND_*), the same
 * row in every generator's table. F: the field wrapper (x or tree.x). */
#define BP_WIND(S, F, group)                                                                                     \
    BP_BOOL(S, F(wind), "Wind data", group,                                                                      \
            "per-vertex wind attributes: pivot, branch level, stiffness, phase and leaf flutter (game engines, "  \
            "Blender's wind setup)")
#define BP_F_SELF(x) x

#endif
