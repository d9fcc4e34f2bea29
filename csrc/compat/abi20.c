/* abi20.c - ABI 20's names of the segment reference as thin wrappers
 * (banyan/compat.h). */
#include "banyan.h"
#include "banyan/compat.h"

banyan_status banyan_segment_generate(const banyan_segment_input *in, const banyan_segment_params *params,
                                      float *out_xyz, uint8_t *out_level, int32_t *out_count, banyan_error *err) {
    return banyan_segment_lines(in, params, out_xyz, out_level, out_count, err);
}

banyan_status banyan_segment_generate_many(const banyan_segment_input *ins, uint32_t count,
                                           const banyan_segment_params *params, float *out_xyz, uint8_t *out_level,
                                           int32_t *out_counts, banyan_error *err) {
    return banyan_segment_lines_many(ins, count, params, out_xyz, out_level, out_counts, err);
}
