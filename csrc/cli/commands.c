/* The subcommands of `banyan`, in --help order: one per generator, plus
 * the sweeper's tube demo. */
#include "cli.h"

extern const cli_command cli_cmd_roots, cli_cmd_keyaki, cli_cmd_avenue, cli_cmd_ivy, cli_cmd_segments, cli_cmd_tube;

const cli_command *const cli_commands[] = {&cli_cmd_roots, &cli_cmd_keyaki, &cli_cmd_avenue, &cli_cmd_ivy,
                                           &cli_cmd_segments, &cli_cmd_tube, NULL};
