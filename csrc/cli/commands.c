/* The subcommands of `banyan`, in --help order. A generator that has not
 * landed yet is listed with run == NULL and says which issue builds it. */
#include "cli.h"

extern const cli_command cli_cmd_tube;

static const cli_command missing_roots = {"roots", BANYAN_GEN_ROOTS, "strangler-fig roots around host boxes", 0,
                                          NULL, NULL, NULL, NULL, "issue #3"};
static const cli_command missing_keyaki = {"keyaki", BANYAN_GEN_KEYAKI, "one keyaki (Zelkova) tree", 0,
                                           NULL, NULL, NULL, NULL, "issue #4"};
static const cli_command missing_avenue = {"avenue", BANYAN_GEN_AVENUE, "an avenue of keyaki trees", 0,
                                           NULL, NULL, NULL, NULL, "issue #4"};
static const cli_command missing_ivy = {"ivy", BANYAN_GEN_IVY, "ivy climbing host boxes", 0, NULL, NULL, NULL, NULL,
                                        "issue #5"};
static const cli_command missing_segments = {"segments", BANYAN_GEN_SEGMENTS,
                                             "geometry-shader branch segments", 0, NULL, NULL, NULL, NULL, "issue #6"};

const cli_command *const cli_commands[] = {&missing_roots, &missing_keyaki, &missing_avenue, &missing_ivy,
                                           &missing_segments, &cli_cmd_tube, NULL};
