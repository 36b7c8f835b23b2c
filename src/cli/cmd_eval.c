/* cmd_eval.c — `shlab eval`: all n² real SH at one direction. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>

extern const cli_command cmd_eval;

static const char help[] =
    "Usage: shlab eval --order N (--dir X,Y,Z | --theta T --phi P) [OPTIONS]\n"
    "\n"
    "Evaluate the n² real spherical harmonics y_i, i = l(l+1)+m, of bands 0..N-1\n"
    "at one direction.\n"
    "\n"
    "  --order N            number of bands (1..2049)\n"
    "  --dir X,Y,Z          direction (normalised; must be finite and non-zero)\n"
    "  --theta T --phi P    polar angle from +z and azimuth from +x\n"
    "  --degrees            --theta and --phi in degrees\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"convention\",\"values\":[n² numbers]}\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"dir", required_argument, 0, 'd'},
        {"theta", required_argument, 0, 't'},
        {"phi", required_argument, 0, 'p'},
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    int have_dir = 0, have_t = 0, have_p = 0;
    double dir[3], theta = 0, phi = 0;
    cli_common com = CLI_COMMON_DEFAULTS;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'd': if (cli_vec3("--dir", optarg, dir)) return CLI_EXIT_USAGE; have_dir = 1; break;
        case 't': if (cli_double("--theta", optarg, &theta)) return CLI_EXIT_USAGE; have_t = 1; break;
        case 'p': if (cli_double("--phi", optarg, &phi)) return CLI_EXIT_USAGE; have_p = 1; break;
        default: {
            const int r = cli_common_opt(&cmd_eval, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    const int order = com.order;
    const sh_convention conv = com.conv;
    if (optind < argc) return cli_fail("eval: unexpected argument '%s'", argv[optind]);
    if (!order) return cli_fail("eval: --order is required");
    if (have_dir && (have_t || have_p)) return cli_fail("eval: give --dir or --theta/--phi, not both");
    if (!have_dir && !(have_t && have_p)) return cli_fail("eval: give --dir X,Y,Z or both --theta and --phi");
    if (!have_dir) {
        theta = cli_angle_in("eval", "--theta", theta, com.degrees);
        phi = cli_angle_in("eval", "--phi", phi, com.degrees);
    }

    double *y = malloc(sizeof(double) * sh_ncoeff(order));
    if (!y) return cli_fail("out of memory");
    int st = have_dir ? sh_eval_dir(order, conv, dir, y) : sh_eval(order, conv, theta, phi, y);
    if (st) { free(y); return cli_fail_status(st); }
    json_t *root = json_pack("{s:i,s:s,s:o}", "order", order, "convention",
                             sh_convention_name(conv), "values",
                             cli_json_array(y, (size_t)sh_ncoeff(order)));
    free(y);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_eval = {"eval", run, "evaluate the real SH basis at a direction", help, NULL};
