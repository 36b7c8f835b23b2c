/* cmd_deriv.c — `shlab deriv`: the k-th derivative of R_Y(β) = R_sh(Ry(β)),
 * by Krivánek's Appendix A recursion or by the generator R_Y(β)·J^k
 * (rotation_deriv.c). */
#include "cli.h"
#include "cli_image_opts.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>

#define DERIV_PRINT_MAX_ORDER 32

enum { WAY_RECURSION, WAY_GENERATOR };
static const char *const way_names[] = {"recursion", "generator", NULL};

typedef struct {
    int order, k, way, degrees, conv, fmt;
    double beta;
} deriv_args;

static const cli_opt deriv_opts[] = {
    CLI_ORDER(deriv_args, order, DERIV_PRINT_MAX_ORDER, CLI_WHY_PRINTED_MATRIX, "bands 0..N-1"),
    CLI_INT(deriv_args, k, "k", "K", 0, INT_MAX, NULL,
            "derivative order >= 0 (refused only when an entry\noverflows a double: about k > 709/ln(N-1))"),
    CLI_REAL(deriv_args, beta, "beta", "B", 0, 0, 0, "0",
             "angle (default 0; radians unless --degrees), any finite\nvalue: reduced modulo 2π (remainder), printed reduced"),
    CLI_CHOICE(deriv_args, way, "way", "recursion|generator", way_names, "recursion", "recursion (default) or generator (above)"),
    CLI_DEGREES(deriv_args, degrees, "B in and the printed beta in degrees (the derivative\nstays per radian)"),
    CLI_CONVENTION(deriv_args, conv),
    CLI_FORMAT(deriv_args, fmt),
    CLI_END,
};

static const cli_cmd deriv_decl = {
    .name = "deriv",
    .usage = "deriv --order N --k K [--beta B] [OPTIONS]",
    .about = "The k-th derivative d^k R_Y/dβ^k at β of the SH rotation about y,\n"
             "R_Y(β) = R_sh(Ry(β)) (function rotation, docs/CONVENTIONS.md), as the dense\n"
             "N²×N² matrix.  k = 1 at β = 0 is J, the generator; k = 2 at β = 0 is J².\n"
             "Computed by\n"
             "  recursion  Krivánek et al. 2005 Appendix A: the Leibniz rule carried\n"
             "             through the Ivanic-Ruedenberg recursion (default)\n"
             "  generator  R_Y(β)·J^k, R_Y from the zxzxz method, J in closed form\n"
             "The frame rotation's derivative is the transpose, times (-1)^k.\n",
    .opts = deriv_opts,
    .notes = "JSON: {\"order\",\"k\",\"beta\",\"unit\",\"convention\",\"way\",\"matrix\":[[...]]}\n"
             "(\"beta\" reduced to [-π, π], in \"unit\": radians, or degrees with --degrees.)\n",
};

/* The required options, and β in radians reduced to [-π, π]. */
static int validate(deriv_args *a, const cli_parsed *seen)
{
    if (!cli_given(seen, "order")) return cli_fail("deriv: --order is required");
    if (!cli_given(seen, "k")) return cli_fail("deriv: --k is required");
    a->beta = cli_angle_in("deriv", "--beta", a->beta, a->degrees);
    if (!isfinite(a->beta)) return cli_fail("deriv: --beta must be finite");
    a->beta = remainder(a->beta, 2.0 * M_PI); /* R_Y is 2π-periodic (exact reduction) */
    return 0;
}

/* The dense N²×N² derivative (malloc'd), or NULL after the error line. */
static double *derivative(const deriv_args *a)
{
    const int n = a->order;
    const size_t nn = (size_t)n * n;
    double *blocks = malloc(sh_rot_block_offset(n) * sizeof *blocks), *M = malloc(nn * nn * sizeof *M);
    if (!blocks || !M) {
        free(blocks);
        free(M);
        cli_fail("out of memory");
        return NULL;
    }
    const int st = a->way == WAY_GENERATOR ? sh_rot_deriv_generator(n, a->k, a->beta, a->conv, blocks)
                                           : sh_rot_deriv_recursion(n, a->k, a->beta, a->conv, blocks);
    if (st) {
        free(blocks);
        free(M);
        cli_fail_status(st);
        return NULL;
    }
    sh_rot_blocks_to_dense(n, blocks, M);
    free(blocks);
    for (size_t i = 0; i < nn * nn; i++) M[i] += 0.0; /* −0 → 0 */
    return M;
}

static int run(int argc, char **argv)
{
    deriv_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&deriv_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    double *M = derivative(&a);
    if (!M) return CLI_EXIT_USAGE;
    const size_t nn = (size_t)a.order * a.order;
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(a.order));
    root = cli_put(root, "k", json_integer(a.k));
    root = cli_put(root, "beta", json_real(cli_angle_out(a.beta, a.degrees)));
    root = cli_put(root, "unit", json_string(cli_angle_unit(a.degrees)));
    root = cli_put(root, "convention", json_string(sh_convention_name(a.conv)));
    root = cli_put(root, "way", json_string(way_names[a.way]));
    root = cli_put(root, "matrix", cli_json_matrix(M, nn, nn));
    free(M);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_deriv = {"deriv", run, "k-th derivative of the SH rotation about y (Appendix A)", &deriv_decl};
