/* cmd_reconstruct.c — placeholder until the command lands (being written now). */
#include "cli.h"
static int run(int argc, char **argv) { return cli_fail("reconstruct: not implemented yet"); }
const cli_command cmd_reconstruct = {"reconstruct", run, "(not implemented yet)", "not implemented yet\n"};
