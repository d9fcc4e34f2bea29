/* registry.c - which parameter table belongs to which generator. Each
 * generator's table lives beside its code (csrc/<generator>/params_table.c);
 * add one line per generator here when it lands. */
#include "params.h"

#define TABLE(name)                                   \
    extern const banyan_param_info name##_rows[];     \
    extern const int32_t name##_row_count;            \
    extern const size_t name##_params_size;

/* Declarations of generator tables go here, e.g. TABLE(roots_table) */

param_table param_table_get(banyan_generator g) {
    param_table t = {0, 0, 0};
    switch (g) {
    /* case BANYAN_GEN_ROOTS: t.rows = roots_table_rows; t.count = roots_table_row_count;
     *                        t.params_size = roots_table_params_size; break; */
    default: break;
    }
    return t;
}
