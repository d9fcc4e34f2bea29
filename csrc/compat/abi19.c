/* abi19.c - ABI 19's entry point names as thin wrappers (banyan/compat.h). */
#include "banyan.h"
#include "banyan/compat.h"

banyan_status banyan_roots_generate_hosts(const banyan_roots_params *params, const banyan_hosts *hosts,
                                          banyan_mesh **out, banyan_roots_stats *stats,
                                          const banyan_progress *progress, banyan_error *err) {
    return banyan_roots_generate(params, hosts, out, stats, progress, err);
}

banyan_status banyan_roots_generate_stats(const banyan_roots_params *params, const banyan_box *hosts,
                                          uint32_t n_hosts, banyan_mesh **out, banyan_roots_stats *stats,
                                          banyan_error *err) {
    banyan_hosts *set = NULL;
    if (out) *out = NULL;
    banyan_status s = banyan_hosts_create(hosts, n_hosts, NULL, 0, &set, err);
    if (!s) s = banyan_roots_generate(params, set, out, stats, NULL, err);
    banyan_hosts_free(set);
    return s;
}

banyan_status banyan_ivy_generate_hosts(const banyan_ivy_params *params, const banyan_hosts *hosts, banyan_mesh **out,
                                        const banyan_progress *progress, banyan_error *err) {
    return banyan_ivy_generate(params, hosts, out, NULL, progress, err);
}

banyan_status banyan_ivy_generate_hosts_stats(const banyan_ivy_params *params, const banyan_hosts *hosts,
                                              banyan_mesh **out, banyan_ivy_stats *stats,
                                              const banyan_progress *progress, banyan_error *err) {
    return banyan_ivy_generate(params, hosts, out, stats, progress, err);
}

banyan_status banyan_ivy_create_hosts(const banyan_ivy_params *params, const banyan_hosts *hosts, banyan_ivy **out,
                                      banyan_error *err) {
    return banyan_ivy_create(params, hosts, out, err);
}

size_t banyan_sizeof_keyaki_statistics(void) { return sizeof(banyan_keyaki_statistics); }
