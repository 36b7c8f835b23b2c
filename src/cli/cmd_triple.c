/* cmd_triple.c — placeholder until the command lands (being written now). */
#include "cli.h"
static int run(int argc, char **argv) { return cli_fail("triple: not implemented yet"); }
const cli_command cmd_triple = {"triple", run, "(not implemented yet)", "not implemented yet\n"};
