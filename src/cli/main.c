/* main.c — the shlab command-line tool: dispatch to one command per file. */
#include "cli.h"
#include "cli_args.h"

#include <string.h>

extern const cli_command cmd_eval, cmd_project, cmd_reconstruct, cmd_triple, cmd_convert, cmd_identify;
extern const cli_command cmd_rotmat, cmd_rotate, cmd_euler, cmd_stability, cmd_fixtures,
    cmd_verify;
extern const cli_command cmd_scale, cmd_scale_interp, cmd_scale_scene;
extern const cli_command cmd_deriv, cmd_taylor_error;
extern const cli_command cmd_bench, cmd_plan;
extern const cli_command cmd_merge;
extern const cli_command cmd_orthonormality;
extern const cli_command cmd_transfer, cmd_scene_plan, cmd_render;
extern const cli_command cmd_cache, cmd_shadow_field;

static const cli_command *const table[] = {
    &cmd_eval, &cmd_project, &cmd_reconstruct, &cmd_triple, &cmd_convert, &cmd_identify,
    &cmd_rotmat, &cmd_rotate, &cmd_euler, &cmd_stability, &cmd_fixtures,
    &cmd_verify, &cmd_scale, &cmd_scale_interp, &cmd_scale_scene,
    &cmd_deriv, &cmd_taylor_error,
    &cmd_bench, &cmd_plan,
    &cmd_merge,
    &cmd_orthonormality,
    &cmd_transfer, &cmd_scene_plan, &cmd_render,
    &cmd_cache, &cmd_shadow_field,
};

const cli_command *cli_find(const char *name)
{
    for (size_t i = 0; i < sizeof table / sizeof *table; i++)
        if (!strcmp(table[i]->name, name)) return table[i];
    return NULL;
}

/* Every help text ends by pointing at the conventions document. */


static void usage(FILE *o)
{
    fprintf(o,
            "shlab %s — numerical verification workbench for real spherical harmonics\n"
            "\n"
            "Usage: shlab COMMAND [OPTIONS]\n"
            "       shlab COMMAND --help     (options of one command)\n"
            "       shlab --version\n"
            "\n"
            "Commands:\n",
            SHLAB_VERSION);
    for (size_t i = 0; i < sizeof table / sizeof *table; i++)
        fprintf(o, "  %-12s %s\n", table[i]->name, table[i]->summary);
    fprintf(o,
            "\n"
            "Conventions: real SH with the Condon-Shortley phase ('cs', default) or without\n"
            "('nocs'); flat index i = l(l+1)+m; order n = bands 0..n-1 (n² coefficients);\n"
            "direction (sinθcosφ, sinθsinφ, cosθ); angles in radians unless --degrees\n"
            "(then angles in and out are in degrees).\n"
            "Every command takes --format table|csv|json (default table).\n"
            "Exit status: 0 success, 1 a check failed, 2 bad usage or input.\n");
    fputs(cli_conventions_note, o);
}

int main(int argc, char **argv)
{
    cli_signals_install();
    if (argc < 2) return cli_fail("no command given (try 'shlab --help')");
    const char *c = argv[1];
    if (!strcmp(c, "--help") || !strcmp(c, "-h") || !strcmp(c, "help")) {
        if (argc > 2 && strcmp(c, "help") == 0) {
            const cli_command *cmd = cli_find(argv[2]);
            if (!cmd) return cli_fail("unknown command '%s' (try 'shlab --help')", argv[2]);
            return cli_args_help(cmd->decl);
        }
        usage(stdout);
        if (fflush(stdout) != 0 || ferror(stdout)) return cli_fail("cannot write to standard output");
        return CLI_EXIT_OK;
    }
    if (!strcmp(c, "--version")) {
        printf("shlab %s\n", SHLAB_VERSION);
        if (fflush(stdout) != 0 || ferror(stdout)) return cli_fail("cannot write to standard output");
        return CLI_EXIT_OK;
    }
    const cli_command *cmd = cli_find(c);
    if (!cmd) return cli_fail("unknown command '%s' (try 'shlab --help')", c);
    const int rc = cmd->run(argc - 1, argv + 1);
    cli_warn_flush(rc);
    return rc;
}
