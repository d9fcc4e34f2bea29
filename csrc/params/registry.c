/* registry.c - which parameter table belongs to which generator. Each
 * generator's table lives beside its code (csrc/<generator>/params_table.c);
 * add one line per generator here when it lands. */
#include "params.h"

#define TABLE(name)                                   \
    extern const banyan_param_info name##_rows[];     \
    extern const int32_t name##_row_count;            \
    extern const size_t name##_params_size;

/* Declarations of generator tables go here, e.g. TABLE(roots_table) */
TABLE(roots_table)
TABLE(ivy_table)
TABLE(keyaki_table)
TABLE(avenue_table)
TABLE(segments_table)

param_table param_table_get(banyan_generator g) {
    param_table t = {0, 0, 0};
    switch (g) {
    /* case BANYAN_GEN_ROOTS: t.rows = roots_table_rows; t.count = roots_table_row_count;
     *                        t.params_size = roots_table_params_size; break; */
    case BANYAN_GEN_SEGMENTS: t.rows = segments_table_rows; t.count = segments_table_row_count;
                              t.params_size = segments_table_params_size; break;
    case BANYAN_GEN_KEYAKI: t.rows = keyaki_table_rows; t.count = keyaki_table_row_count;
                            t.params_size = keyaki_table_params_size; break;
    case BANYAN_GEN_AVENUE: t.rows = avenue_table_rows; t.count = avenue_table_row_count;
                            t.params_size = avenue_table_params_size; break;
    case BANYAN_GEN_IVY: t.rows = ivy_table_rows; t.count = ivy_table_row_count;
                         t.params_size = ivy_table_params_size; break;
    case BANYAN_GEN_ROOTS: t.rows = roots_table_rows; t.count = roots_table_row_count;
                           t.params_size = roots_table_params_size; break;
    default: break;
    }
    return t;
}
