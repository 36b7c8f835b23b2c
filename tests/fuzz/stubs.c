/* stubs.c — the fuzz harnesses and the CLI's unit tests link the CLI's
 * shared code (libshlab_cli.a) without main.c; nothing of main.c is needed
 * any more, so this file is empty but for this note. */
#include "cli/cli.h"
