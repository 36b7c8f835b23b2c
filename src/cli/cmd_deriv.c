/* cmd_deriv.c — `shlab deriv`: the k-th derivative of R_Y(β) = R_sh(Ry(β)),
 * by Krivánek's Appendix A recursion or by the generator R_Y(β)·J^k
 * (rotation_deriv.c). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_deriv;

#define DERIV_PRINT_MAX_ORDER 32

static const char help[] =
    "Usage: shlab deriv --order N --k K [--beta B] [OPTIONS]\n"
    "\n"
    "The k-th derivative d^k R_Y/dβ^k at β of the SH rotation about y,\n"
    "R_Y(β) = R_sh(Ry(β)) (function rotation, docs/CONVENTIONS.md), as the dense\n"
    "N²×N² matrix.  k = 1 at β = 0 is J, the generator; k = 2 at β = 0 is J².\n"
    "Computed by\n"
    "  recursion  Krivánek et al. 2005 Appendix A: the Leibniz rule carried\n"
    "             through the Ivanic-Ruedenberg recursion (default)\n"
    "  generator  R_Y(β)·J^k, R_Y from the zxzxz method, J in closed form\n"
    "The frame rotation's derivative is the transpose, times (-1)^k.\n"
    "\n"
    "  --order N            bands 0..N-1 (1..32)\n"
    "  --k K                derivative order >= 0 (refused only when an entry\n"
    "                       overflows a double: about k > 709/ln(N-1))\n"
    "  --beta B             angle (default 0; radians unless --degrees), any finite\n"
    "                       value: reduced modulo 2π (remainder), printed reduced\n"
    "  --way recursion|generator\n"
    "  --degrees            B in and the printed beta in degrees (the derivative\n"
    "                       stays per radian)\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"k\",\"beta\",\"unit\",\"convention\",\"way\",\"matrix\":[[...]]}\n"
    "(\"beta\" reduced to [-π, π], in \"unit\": radians, or degrees with --degrees.)\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,     CLI_LONGOPT_ORDER, CLI_LONGOPT_CONVENTION,
                                         CLI_LONGOPT_DEGREES,   {"k", required_argument, 0, 'k'},
                                         {"beta", required_argument, 0, 'b'},
                                         {"way", required_argument, 0, 'w'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = DERIV_PRINT_MAX_ORDER;
    com.max_order_why = "a printed N²×N² matrix";
    int k = -1, generator = 0;
    double beta = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'k':
            if (cli_int("--k", optarg, &k)) return CLI_EXIT_USAGE;
            if (k < 0) return cli_fail("--k: %d must be >= 0", k);
            break;
        case 'b':
            if (cli_double("--beta", optarg, &beta)) return CLI_EXIT_USAGE;
            break;
        case 'w':
            if (!strcmp(optarg, "recursion")) generator = 0;
            else if (!strcmp(optarg, "generator")) generator = 1;
            else return cli_fail("--way: '%s' is not recursion or generator", optarg);
            break;
        default: {
            const int e = cli_common_opt(&cmd_deriv, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    if (optind < argc) return cli_fail("deriv: unexpected argument '%s'", argv[optind]);
    if (!com.order) return cli_fail("deriv: --order is required");
    if (k < 0) return cli_fail("deriv: --k is required");
    beta = cli_angle_in("deriv", "--beta", beta, com.degrees);
    if (!isfinite(beta)) return cli_fail("deriv: --beta must be finite");
    beta = remainder(beta, 2.0 * M_PI); /* R_Y is 2π-periodic (exact reduction) */
    const int n = com.order;
    const size_t nn = (size_t)n * n;
    double *blocks = malloc(sh_rot_block_offset(n) * sizeof *blocks), *M = malloc(nn * nn * sizeof *M);
    if (!blocks || !M) { free(blocks); free(M); return cli_fail("out of memory"); }
    int st = generator ? sh_rot_deriv_generator(n, k, beta, com.conv, blocks)
                       : sh_rot_deriv_recursion(n, k, beta, com.conv, blocks);
    if (st) { free(blocks); free(M); return cli_fail_status(st); }
    sh_rot_blocks_to_dense(n, blocks, M);
    for (size_t i = 0; i < nn * nn; i++) M[i] += 0.0; /* −0 → 0 */
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(n));
    root = cli_put(root, "k", json_integer(k));
    root = cli_put(root, "beta", json_real(cli_angle_out(beta, com.degrees)));
    root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "way", json_string(generator ? "generator" : "recursion"));
    root = cli_put(root, "matrix", cli_json_matrix(M, nn, nn));
    free(blocks);
    free(M);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_deriv = {"deriv", run, "k-th derivative of the SH rotation about y (Appendix A)", help, NULL};
