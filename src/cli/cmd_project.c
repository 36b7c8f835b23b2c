/* cmd_project.c — placeholder until the command lands (being written now). */
#include "cli.h"
static int run(int argc, char **argv) { return cli_fail("project: not implemented yet"); }
const cli_command cmd_project = {"project", run, "(not implemented yet)", "not implemented yet\n"};
