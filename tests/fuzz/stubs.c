/* stubs.c — the one symbol of the CLI's shared code that lives in main.c
 * (the command table's help printer), for the fuzz harnesses, which link the
 * shared CLI code without main.c.  Never called by the harnesses. */
#include "cli/cli.h"

int cli_help(const cli_command *cmd)
{
    (void)cmd;
    return CLI_EXIT_OK;
}

const char cli_conventions_note[] = "";
