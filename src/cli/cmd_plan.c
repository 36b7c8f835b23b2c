/* cmd_plan.c — `shlab plan`: the cheapest rotation method (measured now)
 * whose measured error stays within a tolerance for every β up to a
 * maximum, and the runner-up; with --order auto, first the smallest order
 * that represents an environment image.  Logic in rotation_choose.c. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_plan;
extern const cli_sweep_kind sweep_plan;

/* plan times every method at the order: up to 64 */
#define PLAN_MAX_ORDER 64

static const char help[] =
    "Usage: shlab plan --order N --max-beta B --tolerance E [OPTIONS]\n"
    "       shlab plan --order auto --exr FILE --tolerance E --max-beta B [OPTIONS]\n"
    "\n"
    "Choose the cheapest rotation method for a scene: every method built in\n"
    "(exact ones and the Taylor approximations once available; not the MPFR\n"
    "reference; z only when B = 0) is measured against the exact rotation on a\n"
    "β grid 0..B (step <= --beta-step, seeded α, γ) and timed now (per rotation\n"
    "from a 3×3 matrix, as `shlab bench`).  The choice is the fastest method whose\n"
    "largest error over the grid is <= E; the runner-up the next fastest.\n"
    "Errors (docs/CONVENTIONS.md): lobe = ‖(R_method − R_exact) c‖₂ with c the unit\n"
    "coefficient vector of max(0,cosθ)^e about +z; max = the largest singular\n"
    "value of R_method − R_exact.\n"
    "With --order auto the order is first chosen as the smallest n <= --max-order\n"
    "whose projection of the image has relative L2 residual <= E on the sphere\n"
    "(Parseval: ε² = (‖f‖² − Σc²)/‖f‖², colour channels together, ‖f‖² by the\n"
    "same pixel quadrature as the projection); the same E is then the rotation\n"
    "tolerance (override with --rot-tolerance).\n"
    "\n"
    "  --order N|auto       order (1..64) or auto (needs --exr)\n"
    "  --max-beta B         largest rotation about y the scene needs (<= π)\n"
    "  --tolerance E        error budget (> 0)\n"
    "  --rot-tolerance E2   rotation budget when it should differ from E (auto)\n"
    "  --measure lobe|max   error measure (default lobe)\n"
    "  --lobe-exp E2        exponent of the lobe (default 7)\n"
    "  --beta-step S        largest grid step (default 0.25°)\n"
    "  --degrees            angles in degrees: --max-beta and --beta-step, and the\n"
    "                       printed max_beta and worst_beta (\"unit\" says which)\n"
    "  --precision P        double (default) | float\n"
    "  --convention C       cs (default) | nocs: convention of the plans measured and timed\n"
    "  --exr FILE           environment image (with --order auto)\n"
    "  --layout L           latlong (default) | probe\n"
    "  --max-order M        largest order tried by auto (default 32)\n"
    "  --quiet              no progress on stderr (else a line a second after 1 s)\n"
    CLI_SHARD_HELP
    "                       (the β grid; the merge times the methods)\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"convention\",\"max_beta\",\"unit\" (of max_beta and worst_beta),\n"
    "       \"tolerance\",\"measure\",\"lobe_exp\",\"precision\",\n"
    "       \"choice\":{\"method\",\"ns_per_rotation\",\"max_error\"} (null if none qualifies),\n"
    "       \"runner_up\":{...} (or null),\n"
    "       \"candidates\":[{\"method\",\"exact\",\"ok\",\"max_error\",\"worst_beta\",\n"
    "                      \"ns_per_rotation\",\"mults\"}],\n"
    "       with --order auto also \"order_residual\" (relative L2 at the chosen order)\n"
    "       and \"image\":{\"path\",\"width\",\"height\",\"layout\"}}.  Exit 0 if a method\n"
    "       qualifies, 1 if none does (the candidates still printed), also 1 with\n"
    "       --order auto when no order <= --max-order represents the image to E:\n"
    "       then \"order\":null, \"max_order\", \"order_residual\" at --max-order,\n"
    "       choice and runner_up null, no candidates (one line on stderr says so).\n";

static json_t *cand_json(const sh_rot_candidate *c, int full, int degrees)
{
    json_t *o = json_object();
    o = cli_put(o, "method", json_string(sh_rot_method_name(c->method)));
    if (full) {
        o = cli_put(o, "exact", json_boolean(c->exact));
        o = cli_put(o, "ok", json_boolean(c->ok));
    }
    o = cli_put(o, "ns_per_rotation", json_real(c->ns_per_rotation));
    o = cli_put(o, "max_error", json_real(c->max_error));
    if (full) {
        o = cli_put(o, "worst_beta", json_real(cli_angle_out(c->worst_beta, degrees)));
        o = cli_put(o, "mults", json_real(c->mults));
    }
    return o;
}

/* The choice from the errors on the β grid (rows in step order); the
 * methods are timed here, by the process that prints the result. */
static json_t *finish(const json_t *params, json_t *rows)
{
    sh_rot_choose_opts co = {0};
    const json_t *mj = json_object_get(params, "methods");
    const int degrees = json_is_true(json_object_get(params, "degrees"));
    co.order = (int)json_integer_value(json_object_get(params, "order"));
    co.max_beta = json_real_value(json_object_get(params, "max_beta"));
    co.tolerance = json_real_value(json_object_get(params, "tolerance"));
    co.lobe_exp = json_real_value(json_object_get(params, "lobe_exp"));
    co.beta_step = json_real_value(json_object_get(params, "beta_step"));
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm = 0, nsteps = 0, bad = 0;
    bad |= sh_error_measure_parse(json_string_value(json_object_get(params, "measure")), &co.measure) != SH_OK;
    bad |= sh_precision_parse(json_string_value(json_object_get(params, "precision")), &co.prec) != SH_OK;
    bad |= sh_convention_parse(json_string_value(json_object_get(params, "convention")), &co.conv) != SH_OK;
    bad |= sh_rot_choose_grid(&co, ms, &nm, &nsteps) != SH_OK;
    bad |= (size_t)nm != json_array_size(mj) || (size_t)nsteps != json_array_size(rows);
    for (int k = 0; !bad && k < nm; k++)
        bad |= strcmp(json_string_value(json_array_get(mj, (size_t)k)), sh_rot_method_name(ms[k])) != 0;
    double *err = bad ? NULL : malloc(sizeof *err * (size_t)nsteps * (nm ? nm : 1));
    size_t j;
    json_t *row;
    json_array_foreach(rows, j, row) for (int k = 0; err && k < nm; k++)
        err[j * nm + k] = json_real_value(json_array_get(json_object_get(row, "errors"), (size_t)k));
    json_decref(rows);
    if (!err) { sh_error(SH_EINVAL, "plan: the shards' methods or steps do not match this build"); return NULL; }
    co.grid_errors = err;
    sh_rot_candidate cand[SH_ROT_NMETHODS];
    int nc = 0, choice = -1, runner = -1;
    const int st = sh_rot_choose(&co, cand, &nc, &choice, &runner);
    free(err);
    if (st) return NULL;
    json_t *cj = json_array();
    for (int k = 0; k < nc && cj; k++)
        if (json_array_append_new(cj, cand_json(&cand[k], 1, degrees))) { json_decref(cj); cj = NULL; }
    json_t *root = json_object();
    static const char *const keys[] = {"order", "convention", "max_beta", "tolerance", "measure", "lobe_exp",
                                       "precision", "image_tolerance", "order_residual", "image"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++) {
        const char *from = strcmp(keys[k], "max_beta") ? keys[k] : "max_beta_shown";
        if (json_object_get(params, from)) root = cli_put(root, keys[k], json_deep_copy(json_object_get(params, from)));
        if (!strcmp(keys[k], "max_beta")) root = cli_put(root, "unit", json_string(cli_angle_unit(degrees)));
    }
    root = cli_put(root, "choice", choice >= 0 ? cand_json(&cand[choice], 0, degrees) : json_null());
    root = cli_put(root, "runner_up", runner >= 0 ? cand_json(&cand[runner], 0, degrees) : json_null());
    return cli_put(root, "candidates", cj);
}

/* no method qualifies: a failed check */
static int exit_code(const json_t *result)
{
    return json_is_null(json_object_get(result, "choice")) ? CLI_EXIT_CHECK : CLI_EXIT_OK;
}

/* item j is step j of the β grid (the same formula in run) */
static double beta_of(double max_beta, long nsteps, long j) { return nsteps > 1 ? max_beta * j / (nsteps - 1) : 0; }

static const cli_sweep_field params_fields[] = {
    {"order", CLI_FIELD_INT, 0, 1, PLAN_MAX_ORDER}, {"convention", CLI_FIELD_STRING, 0, 0, 0},
    {"max_beta", CLI_FIELD_REAL, 0, 0, 0},          {"degrees", CLI_FIELD_BOOL, 0, 0, 0},
    {"max_beta_shown", CLI_FIELD_REAL, 0, 0, 0},    {"tolerance", CLI_FIELD_REAL, 0, 0, 0},
    {"measure", CLI_FIELD_STRING, 0, 0, 0},         {"lobe_exp", CLI_FIELD_REAL, 0, 0, 0},
    {"precision", CLI_FIELD_STRING, 0, 0, 0},       {"image_tolerance", CLI_FIELD_REAL, 1, 0, 0},
    {"order_residual", CLI_FIELD_REAL, 1, 0, 0},    {"image", CLI_FIELD_OBJECT, 1, 0, 0},
    {"beta_step", CLI_FIELD_REAL, 0, 0, 0},         {"methods", CLI_FIELD_STRINGS, 0, 0, 0},
    {NULL, 0, 0, 0, 0}};
static const cli_sweep_field row_fields[] = {{"beta", CLI_FIELD_REAL, 0, 0, 0}, {"errors", CLI_FIELD_REALS, 0, 0, 0},
                                             {NULL, 0, 0, 0, 0}};

static int check_row(const json_t *params, long nitems, long j, const json_t *row, char *why, size_t n)
{
    const double want = beta_of(json_real_value(json_object_get(params, "max_beta")), nitems, j);
    const double got = json_real_value(json_object_get(row, "beta"));
    if (got != want) return snprintf(why, n, "beta %.17g, but item %ld is the step β = %.17g", got, j, want), 1;
    const size_t ne = json_array_size(json_object_get(row, "errors")),
                 nm = json_array_size(json_object_get(params, "methods"));
    if (ne != nm) return snprintf(why, n, "%zu errors for %zu methods", ne, nm), 1;
    return 0;
}

const cli_sweep_kind sweep_plan = {"plan", finish, NULL, exit_code, params_fields, row_fields, check_row, 1};

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_PRECISION,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPT_CONVENTION,
                                         {"order", required_argument, 0, 'o'},
                                         {"max-beta", required_argument, 0, 'B'},
                                         {"tolerance", required_argument, 0, 'e'},
                                         {"rot-tolerance", required_argument, 0, 'E'},
                                         {"measure", required_argument, 0, 'm'},
                                         {"lobe-exp", required_argument, 0, 'l'},
                                         {"beta-step", required_argument, 0, 's'},
                                         {"exr", required_argument, 0, 'x'},
                                         {"layout", required_argument, 0, 'y'},
                                         {"max-order", required_argument, 0, 'M'},
                                         {"quiet", no_argument, 0, 'q'},
                                         CLI_LONGOPT_SHARD,
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    sh_rot_choose_opts co = {0};
    co.lobe_exp = 7;
    co.measure = SH_MEASURE_LOBE;
    co.prec = SH_PREC_DOUBLE;
    double max_beta = 0, beta_step = -1, rot_tol = -1;
    int have_beta = 0, have_tol = 0, order_auto = 0, quiet = 0, max_order = 32, have_layout = 0;
    int have_max_order = 0;
    const char *exr = NULL;
    sh_shard shard = SH_SHARD_ALL;
    int have_shard = 0;
    sh_layout layout = SH_LAYOUT_LATLONG;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case CLI_OPT_PRECISION:
            if (cli_precision(optarg, &co.prec)) return CLI_EXIT_USAGE;
            break;
        case 'o':
            if (!strcmp(optarg, "auto")) order_auto = 1;
            else {
                if (cli_order_max("--order", optarg, PLAN_MAX_ORDER, NULL, &co.order)) return CLI_EXIT_USAGE;
                order_auto = 0;
            }
            break;
        case 'B':
            if (cli_double("--max-beta", optarg, &max_beta)) return CLI_EXIT_USAGE;
            have_beta = 1;
            break;
        case 'e':
            if (cli_double("--tolerance", optarg, &co.tolerance)) return CLI_EXIT_USAGE;
            if (!(co.tolerance > 0)) return cli_fail("--tolerance: must be > 0");
            have_tol = 1;
            break;
        case 'E':
            if (cli_double("--rot-tolerance", optarg, &rot_tol)) return CLI_EXIT_USAGE;
            if (!(rot_tol > 0)) return cli_fail("--rot-tolerance: must be > 0");
            break;
        case 'm':
            if (sh_error_measure_parse(optarg, &co.measure)) return cli_fail("--measure: %s", sh_last_error());
            break;
        case 'l':
            if (cli_double("--lobe-exp", optarg, &co.lobe_exp)) return CLI_EXIT_USAGE;
            if (!(co.lobe_exp >= 0 && co.lobe_exp <= 1e6)) return cli_fail("--lobe-exp: must be in [0, 1e6]");
            break;
        case 's':
            if (cli_double("--beta-step", optarg, &beta_step)) return CLI_EXIT_USAGE;
            if (!(beta_step > 0)) return cli_fail("--beta-step: must be > 0");
            break;
        case 'x':
            if (exr) return cli_fail("plan: --exr given twice");
            exr = optarg;
            break;
        case 'y':
            if (sh_layout_parse(optarg, &layout)) return cli_fail("--layout: %s", sh_last_error());
            have_layout = 1;
            break;
        case 'M':
            if (cli_order_max("--max-order", optarg, PLAN_MAX_ORDER, NULL, &max_order)) return CLI_EXIT_USAGE;
            have_max_order = 1;
            break;
        case 'q': quiet = 1; break;
        case CLI_OPT_SHARD:
            if (cli_shard("--shard", optarg, &shard)) return CLI_EXIT_USAGE;
            have_shard = 1;
            break;
        default: {
            const int e = cli_common_opt(&cmd_plan, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    if (optind < argc) return cli_fail("plan: unexpected argument '%s'", argv[optind]);
    if (!order_auto && co.order == 0) return cli_fail("plan: --order N (or auto) is required");
    if (!have_beta) return cli_fail("plan: --max-beta is required");
    if (!have_tol) return cli_fail("plan: --tolerance is required");
    if (order_auto && !exr) return cli_fail("plan: --order auto needs --exr FILE");
    if (cli_applies("plan", exr != NULL, "--exr", order_auto, "--order auto") ||
        cli_applies("plan", have_layout, "--layout", order_auto, "--order auto") ||
        cli_applies("plan", have_max_order, "--max-order", order_auto, "--order auto") ||
        cli_applies("plan", rot_tol > 0, "--rot-tolerance", order_auto, "--order auto"))
        return CLI_EXIT_USAGE;
    co.conv = com.conv;
    const double deg = com.degrees ? M_PI / 180 : 1.0;
    co.max_beta = max_beta * deg;
    if (!(co.max_beta >= 0 && co.max_beta <= M_PI * (1 + 1e-12)))
        return cli_fail("--max-beta: %g is outside [0, %s", max_beta,
                        com.degrees ? "180] degrees" : "π] radians (--degrees for degrees)");
    co.max_beta = fmin(co.max_beta, M_PI);
    co.beta_step = beta_step > 0 ? beta_step * deg : 0.25 * M_PI / 180;
    if (co.beta_step < 1e-5) return cli_fail("--beta-step: too small (< 1e-5 rad)");

    json_t *img_json = NULL;
    double order_resid = 0;
    const double img_tol = co.tolerance;
    if (order_auto) {
        sh_image img = {0};
        if (cli_input("EXR image", exr)) return CLI_EXIT_USAGE;
        int st = sh_exr_read(exr, &img, NULL);
        if (st) return cli_fail_status(st);
        double resid[64];
        int order = -1;
        /* no order beyond what the image can carry (sh_image_max_order) */
        if (max_order > sh_image_max_order(&img, layout)) max_order = sh_image_max_order(&img, layout);
        if (!quiet) fprintf(stderr, "plan: projecting %s (%dx%d) to order %d\n", exr, img.width, img.height, max_order);
        st = sh_order_for_image(&img, layout, img_tol, max_order, &order, resid);
        const int w = img.width, h = img.height;
        sh_image_free(&img);
        if (st) return cli_fail_status(st);
        img_json = json_object();
        img_json = cli_put(img_json, "path", json_string(exr));
        img_json = cli_put(img_json, "width", json_integer(w));
        img_json = cli_put(img_json, "height", json_integer(h));
        img_json = cli_put(img_json, "layout", json_string(layout == SH_LAYOUT_LATLONG ? "latlong" : "probe"));
        if (order < 0) {
            /* a valid request whose answer is "no order qualifies": a failed
             * check (exit 1), the result still printed, without candidates */
            fprintf(stderr, "plan: no order <= %d represents %s to relative L2 %g (at order %d: %.3g)\n",
                    max_order, exr, img_tol, max_order, resid[max_order - 1]);
            json_t *root = json_object();
            root = cli_put(root, "order", json_null());
            root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
            root = cli_put(root, "max_beta", json_real(com.degrees ? fmin(max_beta, 180.0) : co.max_beta));
            root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
            root = cli_put(root, "tolerance", json_real(rot_tol > 0 ? rot_tol : co.tolerance));
            root = cli_put(root, "measure", json_string(sh_error_measure_name(co.measure)));
            root = cli_put(root, "lobe_exp", json_real(co.lobe_exp));
            root = cli_put(root, "precision", json_string(sh_precision_name(co.prec)));
            root = cli_put(root, "image_tolerance", json_real(img_tol));
            root = cli_put(root, "max_order", json_integer(max_order));
            root = cli_put(root, "order_residual", json_real(resid[max_order - 1]));
            root = cli_put(root, "image", img_json);
            root = cli_put(root, "choice", json_null());
            root = cli_put(root, "runner_up", json_null());
            root = cli_put(root, "candidates", json_array());
            const int rc = cli_emit(root, com.fmt);
            return rc == CLI_EXIT_OK ? CLI_EXIT_CHECK : rc;
        }
        co.order = order;
        order_resid = resid[order - 1];
        if (rot_tol > 0) co.tolerance = rot_tol;
    }
    /* the sweep: step j of the β grid; everything the result depends on */
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm = 0, nsteps = 0;
    int st = sh_rot_choose_grid(&co, ms, &nm, &nsteps);
    if (st) { json_decref(img_json); return cli_fail_status(st); }
    json_t *params = json_object(), *mj = json_array();
    for (int k = 0; k < nm && mj; k++)
        if (json_array_append_new(mj, json_string(sh_rot_method_name(ms[k])))) { json_decref(mj); mj = NULL; }
    params = cli_put(params, "order", json_integer(co.order));
    params = cli_put(params, "convention", json_string(sh_convention_name(com.conv)));
    params = cli_put(params, "max_beta", json_real(co.max_beta));
    params = cli_put(params, "degrees", json_boolean(com.degrees));
    params = cli_put(params, "max_beta_shown", json_real(com.degrees ? fmin(max_beta, 180.0) : co.max_beta));
    params = cli_put(params, "tolerance", json_real(co.tolerance));
    params = cli_put(params, "measure", json_string(sh_error_measure_name(co.measure)));
    params = cli_put(params, "lobe_exp", json_real(co.lobe_exp));
    params = cli_put(params, "precision", json_string(sh_precision_name(co.prec)));
    if (order_auto) {
        params = cli_put(params, "image_tolerance", json_real(img_tol));
        params = cli_put(params, "order_residual", json_real(order_resid));
        params = cli_put(params, "image", img_json);
    }
    params = cli_put(params, "beta_step", json_real(co.beta_step));
    params = cli_put(params, "methods", mj);
    double *err = malloc(sizeof *err * (size_t)nsteps * (nm ? nm : 1));
    if (!err) { json_decref(params); return cli_fail("out of memory"); }
    if (!quiet) fprintf(stderr, "plan: measuring and timing the methods at order %d\n", co.order);
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_plan, params, nsteps, have_shard ? &shard : NULL, com.fmt, quiet, "steps");
    co.progress = cli_progress_step;
    co.progress_ctx = &sw.prog;
    st = sh_rot_choose_errors(&co, have_shard ? &shard : NULL, err);
    sw.prog.quiet = 1; /* the library counted the steps */
    if (st) { free(err); cli_sweep_free(&sw); return cli_fail_status(st); }
    for (int j = 0; j < nsteps; j++) {
        if (!cli_sweep_owns(&sw, j)) continue;
        json_t *r = json_object();
        r = cli_put(r, "beta", json_real(beta_of(co.max_beta, nsteps, j)));
        r = cli_put(r, "errors", cli_json_array(err + (size_t)j * nm, (size_t)nm));
        if (cli_sweep_add(&sw, j, r) == CLI_EXIT_USAGE) { free(err); cli_sweep_free(&sw); return CLI_EXIT_USAGE; }
    }
    free(err);
    return cli_sweep_end(&sw);
}

const cli_command cmd_plan = {"plan", run,
                              "the cheapest rotation method for an error budget up to a β "
                              "(measured now); --order auto from an EXR",
                              help, NULL};
