/* cmd_taylor_error.c — `shlab taylor-error`: error of the Taylor-approximated
 * rotation about y (Krivánek et al. 2005 Sec. 3.2, Figure 3), by the singular
 * values of D(β) = R_Y(β) − T(β) and for a Phong lobe (taylor_error.c). */
#include "cli.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

extern const cli_sweep_kind sweep_taylor_error;

#define TE_MAX_ORDER 128
#define TE_MAX_STEPS 100000

/* --taylor's values, and the methods they name */
static const char *const taylor_names[] = {"1", "1.5", "2", NULL};
static const sh_rot_method taylor_methods[] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};

typedef struct {
    int order, taylor, steps, conv, degrees;
    double beta, beta_max, lobe_exp;
    cli_sweep_args sweep;
} taylor_error_args;

static const cli_opt taylor_error_opts[] = {
    CLI_ORDER(taylor_error_args, order, TE_MAX_ORDER, NULL, "bands 0..N-1"),
    CLI_CHOICE(taylor_error_args, taylor, "taylor", "T", taylor_names, NULL, "1 | 1.5 | 2"),
    CLI_REAL(taylor_error_args, beta, "beta", "B", 0, 0, 0, NULL, "one angle in [0, π] (radians unless --degrees)"),
    CLI_REAL(taylor_error_args, beta_max, "beta-max", "B", 0, 0, 0, NULL,
             "with --steps S: the S+1 angles i·B/S, i = 0..S"),
    {.type = CLI_T_INT, .name = "steps", .meta = "S", .off = offsetof(taylor_error_args, steps), .lo = 1,
     .hi = TE_MAX_STEPS, .help = "steps of the --beta-max grid", .needs = "beta-max"},
    CLI_REAL(taylor_error_args, lobe_exp, "lobe-exp", "E", 0, 1e4, 0, "7", "lobe exponent"),
    CLI_DEGREES(taylor_error_args, degrees, "angles in degrees (in and out)"),
    CLI_CHOICE(taylor_error_args, conv, "convention", "cs|nocs", cli_convention_names, "cs",
               "only reported (the errors do not depend on it)"),
    CLI_GROUP(taylor_error_args, sweep, cli_sweep_opts),
    CLI_END,
};

static const cli_cmd taylor_error_decl = {
    .name = "taylor-error",
    .usage = "taylor-error --order N --taylor 1|1.5|2 (--beta B | --beta-max B --steps S)\n"
             "                          [--lobe-exp E] [OPTIONS]",
    .about = "Error of the Taylor-approximated rotation about y, D(β) = R_Y(β) - T(β)\n"
             "(docs/CONVENTIONS.md): T = I + βJ (1), + β²/2·diag(J²) (1.5), + β²/2·J² (2).\n"
             "R_Y(β) is exact (zxzxz); T(β) is the taylor method's own matrix.\n"
             "  max   largest singular value of D (worst unit coefficient vector)\n"
             "  mean  mean of the N² singular values (GSL one-sided Jacobi SVD)\n"
             "  lobe  ‖D c‖₂, c the unit coefficient vector of max(0,cosθ)^E about +z\n"
             "The numbers are the same in both conventions and for the frame rotation.\n",
    .opts = taylor_error_opts,
    .notes = "JSON: {\"order\",\"taylor\",\"method\",\"convention\",\"lobe_exp\",\"unit\",\n"
             "       \"rows\":[{\"beta\",\"max\",\"mean\",\"lobe\"}]}  (beta in \"unit\")\n",
};

/* the sweep: item i is the angle i·B/S (or the one --beta) */
static json_t *finish(const json_t *params, json_t *rows)
{
    json_t *root = json_object();
    static const char *const keys[] = {"order", "taylor", "method", "convention", "lobe_exp", "unit"};
    for (int k = 0; k < 6; k++) root = cli_put(root, keys[k], json_incref(json_object_get(params, keys[k])));
    return cli_put(root, "rows", rows);
}

/* item i is the angle i·B/S, or the one --beta (the same formula in run) */
static double angle_of(int have_beta, double beta, double beta_max, long steps, long i)
{
    return have_beta ? beta : beta_max * i / steps;
}

static const cli_sweep_field params_fields[] = {
    {"order", CLI_FIELD_INT, 0, 1, TE_MAX_ORDER}, {"taylor", CLI_FIELD_STRING, 0, 0, 0},
    {"method", CLI_FIELD_STRING, 0, 0, 0},        {"convention", CLI_FIELD_STRING, 0, 0, 0},
    {"lobe_exp", CLI_FIELD_REAL, 0, 0, 0},        {"unit", CLI_FIELD_STRING, 0, 0, 0},
    {"beta", CLI_FIELD_REAL, 1, 0, 0},            {"beta_max", CLI_FIELD_REAL, 1, 0, 0},
    {"steps", CLI_FIELD_INT, 1, 1, TE_MAX_STEPS}, {NULL, 0, 0, 0, 0}};
static const cli_sweep_field row_fields[] = {{"beta", CLI_FIELD_REAL, 0, 0, 0}, {"max", CLI_FIELD_REAL, 0, 0, 0},
                                             {"mean", CLI_FIELD_REAL, 0, 0, 0}, {"lobe", CLI_FIELD_REAL, 0, 0, 0},
                                             {NULL, 0, 0, 0, 0}};

static int check_row(const json_t *params, long nitems, long j, const json_t *row, char *why, size_t n)
{
    const json_t *b = json_object_get(params, "beta"), *bm = json_object_get(params, "beta_max"),
                 *st = json_object_get(params, "steps");
    if (!b == !bm || !bm != !st) return snprintf(why, n, "the parameters give neither one angle nor a grid"), 1;
    const long steps = st ? (long)json_integer_value(st) : 0;
    if (nitems != (b ? 1 : steps + 1)) return snprintf(why, n, "the sweep has %ld items, its grid %ld", nitems, b ? 1 : steps + 1), 1;
    const double want = angle_of(b != NULL, json_real_value(b), json_real_value(bm), steps, j);
    const double got = json_real_value(json_object_get(row, "beta"));
    if (got != want) return snprintf(why, n, "beta %.17g, but item %ld is the angle %.17g", got, j, want), 1;
    return 0;
}

const cli_sweep_kind sweep_taylor_error = {"taylor-error", finish, NULL, NULL, params_fields, row_fields, check_row, 0};

/* What involves several options: the order and the Taylor form required,
 * one angle or a grid, within [0, π]. */
static int validate(const taylor_error_args *a, const cli_parsed *seen)
{
    const int have_beta = cli_given(seen, "beta"), have_max = cli_given(seen, "beta-max");
    if (!cli_given(seen, "order")) return cli_fail("taylor-error: --order is required");
    if (!cli_given(seen, "taylor")) return cli_fail("taylor-error: --taylor is required (1, 1.5 or 2)");
    if (have_beta == have_max) return cli_fail("taylor-error: give --beta, or --beta-max with --steps");
    if (have_max && !cli_given(seen, "steps")) return cli_fail("taylor-error: --beta-max needs --steps");
    const double unit = a->degrees ? M_PI / 180.0 : 1.0;
    const double top = have_beta ? a->beta : a->beta_max;
    if (top < 0 || top * unit > M_PI * (1 + 1e-15))
        return cli_fail("taylor-error: %s %g outside [0, %s", have_beta ? "--beta" : "--beta-max", top,
                        a->degrees ? "180] degrees" : "pi] radians (--degrees for degrees)");
    return 0;
}

/* Everything the rows depend on: the whole sweep, whichever shard runs. */
static json_t *sweep_params(const taylor_error_args *a, int have_beta)
{
    json_t *params = json_object();
    params = cli_put(params, "order", json_integer(a->order));
    params = cli_put(params, "taylor", json_string(taylor_names[a->taylor]));
    params = cli_put(params, "method", json_string(sh_rot_method_name(taylor_methods[a->taylor])));
    params = cli_put(params, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    params = cli_put(params, "lobe_exp", json_real(a->lobe_exp));
    params = cli_put(params, "unit", json_string(a->degrees ? "degrees" : "radians"));
    params = cli_put(params, have_beta ? "beta" : "beta_max", json_real(have_beta ? a->beta : a->beta_max));
    if (!have_beta) params = cli_put(params, "steps", json_integer(a->steps));
    return params;
}

/* This shard's angles, a row each (the errors of sh_taylor_error).  0 or
 * the exit code. */
static int compute(const taylor_error_args *a, int have_beta, cli_sweep *sw)
{
    const double unit = a->degrees ? M_PI / 180.0 : 1.0;
    for (long i = 0; i < sw->nitems; i++) {
        if (!cli_sweep_owns(sw, i)) continue;
        const double b = angle_of(have_beta, a->beta, a->beta_max, a->steps, i);
        sh_taylor_err e;
        const int st = sh_taylor_error(a->order, taylor_methods[a->taylor], fmin(b * unit, M_PI), a->lobe_exp, &e);
        if (st) return cli_fail_status(st);
        json_t *r = json_object();
        r = cli_put(r, "beta", json_real(b));
        r = cli_put(r, "max", json_real(e.max));
        r = cli_put(r, "mean", json_real(e.mean));
        r = cli_put(r, "lobe", json_real(e.lobe));
        if (cli_sweep_add(sw, i, r) == CLI_EXIT_USAGE) return CLI_EXIT_USAGE;
    }
    return 0;
}

static int run(int argc, char **argv)
{
    taylor_error_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&taylor_error_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    const int have_beta = cli_given(&seen, "beta");
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_taylor_error, sweep_params(&a, have_beta), have_beta ? 1 : a.steps + 1, &a.sweep,
                    "angles");
    return cli_sweep_close(&sw, compute(&a, have_beta, &sw));
}

const cli_command cmd_taylor_error = {"taylor-error", run,
                                      "error of the Taylor-approximated rotation (singular values, lobe)", &taylor_error_decl};
