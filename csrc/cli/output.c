/* output.c - the CLI's -o: the file's extension picks the format, glTF
 * (.glb, .gltf) or USD text (.usda, .usd); the nodes are the same. */
#include <string.h>
#include <strings.h>

#include "cli.h"

int cli_is_usd(const char *path) {
    size_t n = strlen(path);
    return (n >= 5 && !strcasecmp(path + n - 5, ".usda")) || (n >= 4 && !strcasecmp(path + n - 4, ".usd"));
}

banyan_status cli_write_nodes(const char *path, const banyan_gltf_node *nodes, uint32_t count,
                              const banyan_gltf_options *opt, const banyan_budget *budget, banyan_error *err) {
    if (cli_is_usd(path)) return banyan_usd_write_nodes_budget(path, nodes, count, opt, budget, err);
    return banyan_gltf_write_nodes_budget(path, nodes, count, opt, budget, err);
}
