/* registry.c - which parameter table belongs to which generator. Each
 * generator's table lives beside its code (csrc/<generator>/params_table.c)
 * and defines <name>_rows, <name>_row_count and <name>_params_size. */
#include "params.h"

#define TABLE(name)                               \
    extern const banyan_param_info name##_rows[]; \
    extern const int32_t name##_row_count;        \
    extern const size_t name##_params_size;
TABLE(roots_table)
TABLE(keyaki_table)
TABLE(avenue_table)
TABLE(ivy_table)
TABLE(segments_table)
#undef TABLE

param_table param_table_get(banyan_generator g) {
    static const banyan_param_info *const rows[BANYAN_GEN_COUNT] = {
        roots_table_rows, keyaki_table_rows, avenue_table_rows, ivy_table_rows, segments_table_rows};
    /* Counts and sizes are not constant expressions in C, so read them here. */
    const int32_t counts[BANYAN_GEN_COUNT] = {roots_table_row_count, keyaki_table_row_count, avenue_table_row_count,
                                              ivy_table_row_count, segments_table_row_count};
    const size_t sizes[BANYAN_GEN_COUNT] = {roots_table_params_size, keyaki_table_params_size,
                                            avenue_table_params_size, ivy_table_params_size,
                                            segments_table_params_size};
    param_table t = {0, 0, 0};
    if ((unsigned)g < BANYAN_GEN_COUNT) {
        t.rows = rows[g];
        t.count = counts[g];
        t.params_size = sizes[g];
    }
    return t;
}
