/* The subcommands of `banyan`, in --help order. A generator that has not
 * landed yet is listed with run == NULL and says which issue builds it. */
#include "cli.h"

extern const cli_command cli_cmd_tube;

extern const cli_command cli_cmd_roots;
extern const cli_command cli_cmd_keyaki;
extern const cli_command cli_cmd_avenue;
extern const cli_command cli_cmd_ivy;
extern const cli_command cli_cmd_segments;

const cli_command *const cli_commands[] = {&cli_cmd_roots, &cli_cmd_keyaki, &cli_cmd_avenue, &cli_cmd_ivy,
                                           &cli_cmd_segments, &cli_cmd_tube, NULL};
