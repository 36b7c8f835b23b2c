/* cmd_taylor_error.c — `shlab taylor-error`: error of the Taylor-approximated
 * rotation about y (Krivánek et al. 2005 Sec. 3.2, Figure 3), by the singular
 * values of D(β) = R_Y(β) − T(β) and for a Phong lobe (taylor_error.c). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_taylor_error;
extern const cli_sweep_kind sweep_taylor_error;

#define TE_MAX_ORDER 128
#define TE_MAX_STEPS 100000

static const char help[] =
    "Usage: shlab taylor-error --order N --taylor 1|1.5|2 (--beta B | --beta-max B --steps S)\n"
    "                          [--lobe-exp E] [OPTIONS]\n"
    "\n"
    "Error of the Taylor-approximated rotation about y, D(β) = R_Y(β) - T(β)\n"
    "(docs/CONVENTIONS.md): T = I + βJ (1), + β²/2·diag(J²) (1.5), + β²/2·J² (2).\n"
    "R_Y(β) is exact (zxzxz); T(β) is the taylor method's own matrix.\n"
    "  max   largest singular value of D (worst unit coefficient vector)\n"
    "  mean  mean of the N² singular values (GSL one-sided Jacobi SVD)\n"
    "  lobe  ‖D c‖₂, c the unit coefficient vector of max(0,cosθ)^E about +z\n"
    "The numbers are the same in both conventions and for the frame rotation.\n"
    "\n"
    "  --order N            bands 0..N-1 (1..128)\n"
    "  --taylor T           1 | 1.5 | 2\n"
    "  --beta B             one angle in [0, π] (radians unless --degrees)\n"
    "  --beta-max B --steps S   the S+1 angles i·B/S, i = 0..S (S <= 100000)\n"
    "  --lobe-exp E         lobe exponent (default 7, >= 0)\n"
    "  --degrees            angles in degrees (in and out)\n"
    "  --convention cs|nocs only reported (the errors do not depend on it)\n"
    "  --quiet              no progress on stderr (else a line a second after 1 s)\n"
    CLI_SHARD_HELP
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"taylor\",\"method\",\"convention\",\"lobe_exp\",\"unit\",\n"
    "       \"rows\":[{\"beta\",\"max\",\"mean\",\"lobe\"}]}  (beta in \"unit\")\n";

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

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_CONVENTION,
                                         CLI_LONGOPT_DEGREES,
                                         {"taylor", required_argument, 0, 't'},
                                         {"beta", required_argument, 0, 'b'},
                                         {"beta-max", required_argument, 0, 'B'},
                                         {"steps", required_argument, 0, 's'},
                                         {"lobe-exp", required_argument, 0, 'e'},
                                         {"quiet", no_argument, 0, 'q'},
                                         CLI_LONGOPT_SHARD,
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = TE_MAX_ORDER;
    sh_rot_method m = SH_ROT_NMETHODS;
    const char *tname = NULL;
    double beta = -1, beta_max = -1, lobe_exp = 7;
    int steps = -1, have_beta = 0, have_max = 0, quiet = 0;
    sh_shard shard = SH_SHARD_ALL;
    int have_shard = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 't':
            if (!strcmp(optarg, "1")) m = SH_ROT_TAYLOR1;
            else if (!strcmp(optarg, "1.5")) m = SH_ROT_TAYLOR15;
            else if (!strcmp(optarg, "2")) m = SH_ROT_TAYLOR2;
            else return cli_fail("--taylor: '%s' is not 1, 1.5 or 2", optarg);
            tname = optarg;
            break;
        case 'b':
            if (cli_double("--beta", optarg, &beta)) return CLI_EXIT_USAGE;
            have_beta = 1;
            break;
        case 'B':
            if (cli_double("--beta-max", optarg, &beta_max)) return CLI_EXIT_USAGE;
            have_max = 1;
            break;
        case 's':
            if (cli_int("--steps", optarg, &steps)) return CLI_EXIT_USAGE;
            if (steps < 1 || steps > TE_MAX_STEPS) return cli_fail("--steps: %d out of range 1..%d", steps, TE_MAX_STEPS);
            break;
        case 'e':
            if (cli_double("--lobe-exp", optarg, &lobe_exp)) return CLI_EXIT_USAGE;
            if (lobe_exp < 0 || lobe_exp > 1e4) return cli_fail("--lobe-exp: %g out of range 0..1e4", lobe_exp);
            break;
        case 'q': quiet = 1; break;
        case CLI_OPT_SHARD:
            if (cli_shard("--shard", optarg, &shard)) return CLI_EXIT_USAGE;
            have_shard = 1;
            break;
        default: {
            const int e = cli_common_opt(&cmd_taylor_error, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    if (optind < argc) return cli_fail("taylor-error: unexpected argument '%s'", argv[optind]);
    if (!com.order) return cli_fail("taylor-error: --order is required");
    if (!tname) return cli_fail("taylor-error: --taylor is required (1, 1.5 or 2)");
    if (have_beta == have_max) return cli_fail("taylor-error: give --beta, or --beta-max with --steps");
    if (have_max && steps < 0) return cli_fail("taylor-error: --beta-max needs --steps");
    if (!have_max && steps >= 0) return cli_fail("taylor-error: --steps needs --beta-max");
    const double unit = com.degrees ? M_PI / 180.0 : 1.0;
    const double top = have_beta ? beta : beta_max;
    if (top < 0 || top * unit > M_PI * (1 + 1e-15))
        return cli_fail("taylor-error: %s %g outside [0, %s", have_beta ? "--beta" : "--beta-max", top,
                        com.degrees ? "180] degrees" : "pi] radians (--degrees for degrees)");
    const int nrow = have_beta ? 1 : steps + 1;
    /* everything the rows depend on: the whole sweep, whichever shard runs */
    json_t *params = json_object();
    params = cli_put(params, "order", json_integer(com.order));
    params = cli_put(params, "taylor", json_string(tname));
    params = cli_put(params, "method", json_string(sh_rot_method_name(m)));
    params = cli_put(params, "convention", json_string(sh_convention_name(com.conv)));
    params = cli_put(params, "lobe_exp", json_real(lobe_exp));
    params = cli_put(params, "unit", json_string(com.degrees ? "degrees" : "radians"));
    params = cli_put(params, have_beta ? "beta" : "beta_max", json_real(top));
    if (!have_beta) params = cli_put(params, "steps", json_integer(steps));
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_taylor_error, params, nrow, have_shard ? &shard : NULL, com.fmt, quiet, "angles");
    for (int i = 0; i < nrow; i++) {
        if (!cli_sweep_owns(&sw, i)) continue;
        const double b = angle_of(have_beta, beta, beta_max, steps, i);
        sh_taylor_err e;
        int st = sh_taylor_error(com.order, m, fmin(b * unit, M_PI), lobe_exp, &e);
        if (st) { cli_sweep_free(&sw); return cli_fail_status(st); }
        json_t *r = json_object();
        r = cli_put(r, "beta", json_real(b));
        r = cli_put(r, "max", json_real(e.max));
        r = cli_put(r, "mean", json_real(e.mean));
        r = cli_put(r, "lobe", json_real(e.lobe));
        if (cli_sweep_add(&sw, i, r) == CLI_EXIT_USAGE) { cli_sweep_free(&sw); return CLI_EXIT_USAGE; }
    }
    return cli_sweep_end(&sw);
}

const cli_command cmd_taylor_error = {"taylor-error", run,
                                      "error of the Taylor-approximated rotation (singular values, lobe)",
                                      help, NULL};
