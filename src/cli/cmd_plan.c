/* cmd_plan.c — `shlab plan`: the cheapest rotation method (measured now)
 * whose measured error stays within a tolerance for every β up to a
 * maximum, and the runner-up; with --order auto, first the smallest order
 * that represents an environment image.  Logic in rotation_choose.c. */
#include "cli.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

extern const cli_sweep_kind sweep_plan;

/* plan times every method at the order: up to 64 */
#define PLAN_MAX_ORDER 64

/* --order auto (the order chosen from --exr) */
#define PLAN_ORDER_AUTO (-1)

typedef struct {
    int order; /* 1..PLAN_MAX_ORDER or PLAN_ORDER_AUTO */
    double max_beta, tolerance, rot_tol, lobe_exp, beta_step;
    sh_error_measure measure;
    sh_precision prec;
    int conv, degrees, max_order;
    int input, mode, batch, live, brief;
    const char *exr;
    sh_layout layout;
    cli_sweep_args sweep;
} plan_args;

static int order_value(const char *opt, const char *s, void *field)
{
    if (!strcmp(s, "auto")) {
        *(int *)field = PLAN_ORDER_AUTO;
        return 0;
    }
    return cli_order_max(opt, s, PLAN_MAX_ORDER, NULL, field);
}
static int measure_value(const char *opt, const char *s, void *field)
{
    return sh_error_measure_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}
/* the paths users run (lab.h: sh_bench_input, sh_bench_mode) */
static const char *const input_names[] = {"euler", "matrix", "quat", NULL};
static const char *const mode_names[] = {"per-rotation", "batched", "k-rotations", NULL};

static int layout_value(const char *opt, const char *s, void *field)
{
    return sh_layout_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

static const cli_opt plan_opts[] = {
    CLI_CUSTOM(plan_args, order, "order", "N|auto", order_value, NULL, "order (1..64) or auto (needs --exr)"),
    CLI_REAL(plan_args, max_beta, "max-beta", "B", 0, 0, 0, NULL, "largest rotation about y the scene needs (<= π)"),
    CLI_REAL(plan_args, tolerance, "tolerance", "E", 0, INFINITY, CLI_LO_OPEN, NULL, "error budget"),
    CLI_REAL(plan_args, rot_tol, "rot-tolerance", "E2", 0, INFINITY, CLI_LO_OPEN, NULL,
             "rotation budget when it should differ from E (auto)"),
    CLI_CUSTOM(plan_args, measure, "error", "lobe|max|coeff", measure_value, "lobe",
               "the unit of E (below: Units)"),
    CLI_REAL(plan_args, lobe_exp, "lobe-exp", "E2", 0, 1e6, 0, "7", "exponent of the lobe"),
    CLI_REAL(plan_args, beta_step, "beta-step", "S", 0, INFINITY, CLI_LO_OPEN, NULL,
             "largest grid step (default 0.25°)"),
    CLI_DEGREES(plan_args, degrees, "angles in degrees: --max-beta and --beta-step, and the\n"
                                    "printed max_beta and worst_beta (\"unit\" says which)"),
    CLI_CUSTOM(plan_args, prec, "precision", "P", cli_parse_precision, "double", "double | float"),
    CLI_CHOICE(plan_args, input, "input", "I", input_names, "matrix",
               "how the rotation arrives: matrix | quat | euler (ZYZ angles\n"
               "taken from a matrix)"),
    CLI_CHOICE(plan_args, mode, "mode", "M", mode_names, "per-rotation",
               "per-rotation (one vector per rotation) | batched (one\n"
               "rotation, --batch vectors) | k-rotations (--batch rotations\n"
               "in one call)"),
    CLI_INT(plan_args, batch, "batch", "K", 1, 1 << 20, "256", "vectors per call with --mode batched or k-rotations"),
    CLI_FLAG(plan_args, live, "measure",
             "also time the candidates now (interleaved, noise rule) and say\n"
             "where the live time is more than 1.5x from the model's"),
    CLI_FLAG(plan_args, brief, "brief", "print the answer only (choice and runner-up), not every candidate"),
    CLI_CHOICE(plan_args, conv, "convention", "C", cli_convention_names, "cs",
               "cs | nocs: convention of the plans measured and timed"),
    CLI_STRING(plan_args, exr, "exr", "FILE", "environment image (with --order auto)"),
    CLI_CUSTOM(plan_args, layout, "layout", "L", layout_value, "latlong", "latlong | probe"),
    {.type = CLI_T_ORDER, .name = "max-order", .meta = "M", .off = offsetof(plan_args, max_order), .lo = 1,
     .hi = PLAN_MAX_ORDER, .def = "32", .help = "largest order tried by auto"},
    CLI_GROUP(plan_args, sweep, cli_sweep_opts),
    CLI_END,
};

static const cli_cmd plan_decl = {
    .name = "plan",
    .usage = "plan --order N --max-beta B --tolerance E [OPTIONS]\n"
             "       shlab plan --order auto --exr FILE --tolerance E --max-beta B [OPTIONS]",
    .about = "Choose the cheapest rotation method for a budget: every method built in\n"
             "(the exact ones and the Taylor approximations; not the MPFR reference; z\n"
             "only when B = 0) is measured against the exact rotation on a β grid 0..B\n"
             "(step <= --beta-step, seeded α, γ) and costed on the path you run (--input,\n"
             "--mode, --batch) by the cost model: instructions counted under callgrind\n"
             "times a committed calibration (data/cost_model.tsv, written by `make\n"
             "report`), so the same question gets the same answer on every run; a path\n"
             "or order the model lacks is timed now.  The choice is the cheapest method\n"
             "whose largest error over the grid is <= E; the runner-up the next.  For\n"
             "both it prints the worst error in every unit and holds_to_beta, the largest\n"
             "β (the grid continued to π) up to which it stays within E.\n"
             "Units (docs/CONVENTIONS.md), D = R_method − R_exact, c a coefficient vector:\n"
             "  max    the largest singular value of D = the worst ‖D c‖₂ for ‖c‖₂ = 1 =\n"
             "         the worst relative L2 error of the rotated function on the sphere\n"
             "         (Parseval); a bound for every other unit;\n"
             "  coeff  the worst error of one coefficient, max |(D c)_i| for ‖c‖₂ = 1 (the\n"
             "         largest row norm of D; <= max);\n"
             "  lobe   ‖D c‖₂ for c the unit-norm coefficients of max(0,cosθ)^e about +z\n"
             "         (--lobe-exp e), the measure of Křivánek et al.\n"
             "With --order auto the order is first chosen as the smallest n <= --max-order\n"
             "whose projection of the image has relative L2 residual <= E on the sphere\n"
             "(Parseval: ε² = (‖f‖² − Σc²)/‖f‖², colour channels together, ‖f‖² by the\n"
             "same pixel quadrature as the projection); the same E is then the rotation\n"
             "tolerance (override with --rot-tolerance).\n"
             "With --shard the shards measure the β grid; the merge times the methods.\n",
    .opts = plan_opts,
    .notes = "JSON: {\"order\",\"convention\",\"max_beta\",\"unit\" (of max_beta and worst_beta),\n"
             "       \"tolerance\",\"measure\" (the unit of tolerance),\"lobe_exp\",\"precision\",\n"
             "       \"input\",\"mode\",\"batch\",\"cost_model\" (where its calibration comes from),\n"
             "       \"choice\":{\"method\",\"kernel\",\"ns_per_rotation\",\"instructions\",\"cost_source\" (model, or\n"
             "                 model-per-rotation: the method's one-at-a-time cost where the\n"
             "                 calibration did not batch it, or live),\n"
             "                 \"max_error\",\"error_lobe\",\"error_max\",\"error_coeff\",\"holds_to_beta\",\n"
             "                 with --measure \"live_ns\",\"live_q1\",\"live_q3\",\"live_disagrees\"}\n"
             "       (null if none qualifies), \"runner_up\":{...} (or null),\n"
             "       \"candidates\":[{\"method\",\"exact\",\"ok\",\"max_error\",\"worst_beta\",\n"
             "                      \"ns_per_rotation\",\"mults\",\"kernel\",\"instructions\",\n"
             "                      \"cost_source\"[,\"live_ns\",...]}], with --measure \"noisy\",\"noise\".\n"
             "       with --order auto also \"order_residual\" (relative L2 at the chosen order)\n"
             "       and \"image\":{\"path\",\"width\",\"height\",\"layout\"}}.  Exit 0 if a method\n"
             "       qualifies, 1 if none does (the candidates still printed), also 1 with\n"
             "       --order auto when no order <= --max-order represents the image to E:\n"
             "       then \"order\":null, \"max_order\", \"order_residual\" at --max-order,\n"
             "       choice and runner_up null, no candidates (one line on stderr says so).\n",
};

static json_t *cand_json(const sh_rot_candidate *c, int full, int degrees)
{
    json_t *o = json_object();
    o = cli_put(o, "method", json_string(sh_rot_method_name(c->method)));
    if (full) {
        o = cli_put(o, "exact", json_boolean(c->exact));
        o = cli_put(o, "ok", json_boolean(c->ok));
    }
    o = cli_put(o, "kernel", json_string(sh_rot_kernel_name(c->kernel)));
    o = cli_put(o, "ns_per_rotation", json_real(c->ns_per_rotation));
    o = cli_put(o, "instructions", c->instructions > 0 ? json_real(c->instructions) : json_null());
    o = cli_put(o, "cost_source", json_string(c->from_model == 2 ? "model-per-rotation" : c->from_model ? "model" : "live"));
    o = cli_put(o, "max_error", json_real(c->max_error));
    if (full) {
        o = cli_put(o, "worst_beta", json_real(cli_angle_out(c->worst_beta, degrees)));
        o = cli_put(o, "mults", json_real(c->mults));
    }
    if (c->live_ns > 0) {
        o = cli_put(o, "live_ns", json_real(c->live_ns));
        o = cli_put(o, "live_q1", json_real(c->live_q1));
        o = cli_put(o, "live_q3", json_real(c->live_q3));
        if (c->from_model) o = cli_put(o, "live_disagrees", json_boolean(c->live_disagrees));
    }
    return o;
}

/* The choice or the runner-up as the answer (its path: the result's
 * precision, input, mode, batch): the candidate, its worst error in every
 * unit and how far in β it holds. */
static json_t *answer_json(const sh_rot_candidate *c, const sh_rot_error *w, double holds, int degrees)
{
    json_t *o = cand_json(c, 0, degrees);
    for (int m = 0; m < SH_NMEASURES; m++) {
        char key[32];
        snprintf(key, sizeof key, "error_%s", sh_error_measure_name((sh_error_measure)m));
        o = cli_put(o, key, json_real(sh_rot_error_in(w, (sh_error_measure)m)));
    }
    return cli_put(o, "holds_to_beta", json_real(cli_angle_out(holds, degrees)));
}

/* The rotation path of the parameters (input, mode, batch, live). */
static int path_of(const json_t *params, sh_rot_path *p)
{
    const char *in = json_string_value(json_object_get(params, "input"));
    const char *md = json_string_value(json_object_get(params, "mode"));
    *p = (sh_rot_path)SH_ROT_PATH_DEFAULT;
    int ok_in = 0, ok_md = 0;
    for (int k = 0; in && input_names[k]; k++)
        if (!strcmp(in, input_names[k])) p->input = (sh_bench_input)k, ok_in = 1;
    for (int k = 0; md && mode_names[k]; k++)
        if (!strcmp(md, mode_names[k])) p->mode = (sh_bench_mode)k, ok_md = 1;
    p->batch = (int)json_integer_value(json_object_get(params, "batch"));
    p->live = json_is_true(json_object_get(params, "live"));
    return ok_in && ok_md && p->batch >= 1 ? 0 : -1;
}

/* The choice from the errors on the β grid (rows in step order); the
 * methods are costed here, by the process that prints the result. */
static json_t *finish(const json_t *params, json_t *rows)
{
    sh_rot_choose_opts co = {0};
    sh_rot_path path;
    const json_t *mj = json_object_get(params, "methods");
    const int degrees = json_is_true(json_object_get(params, "degrees"));
    co.order = (int)json_integer_value(json_object_get(params, "order"));
    co.max_beta = json_real_value(json_object_get(params, "max_beta"));
    co.tolerance = json_real_value(json_object_get(params, "tolerance"));
    co.lobe_exp = json_real_value(json_object_get(params, "lobe_exp"));
    co.beta_step = json_real_value(json_object_get(params, "beta_step"));
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm = 0, nsteps = 0, bad = path_of(params, &path) != 0;
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
    sh_bench_noise noise;
    const int st = sh_rot_choose(&co, &path, cand, &nc, &choice, &runner, &noise);
    free(err);
    if (st) return NULL;
    json_t *cj = json_array();
    for (int k = 0; k < nc && cj; k++)
        if (json_array_append_new(cj, cand_json(&cand[k], 1, degrees))) { json_decref(cj); cj = NULL; }
    json_t *root = json_object();
    static const char *const keys[] = {"order", "convention", "max_beta", "tolerance", "measure", "lobe_exp",
                                       "precision", "input", "mode", "batch", "image_tolerance",
                                       "order_residual", "image"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++) {
        const char *from = strcmp(keys[k], "max_beta") ? keys[k] : "max_beta_shown";
        if (json_object_get(params, from)) root = cli_put(root, keys[k], json_deep_copy(json_object_get(params, from)));
        if (!strcmp(keys[k], "max_beta")) root = cli_put(root, "unit", json_string(cli_angle_unit(degrees)));
    }
    root = cli_put(root, "cost_model", json_string(sh_cost_model_source()[0] ? sh_cost_model_source() : "none"));
    if (path.live) {
        root = cli_put(root, "noisy", json_boolean(noise.noisy));
        root = cli_put(root, "noise", json_string(noise.why));
        if (noise.noisy) cli_warn("plan: noisy live timing (%s); the choice uses the model", noise.why);
    }
    /* the answer's extent: choice and runner-up on one pass over the β grid */
    sh_rot_method am[2];
    sh_rot_error aw[2];
    double ah[2];
    int na = 0;
    if (choice >= 0) am[na++] = cand[choice].method;
    if (runner >= 0) am[na++] = cand[runner].method;
    if (na && sh_rot_choose_extents(&co, am, na, aw, ah)) { json_decref(root); json_decref(cj); return NULL; }
    json_t *cjs = choice >= 0 ? answer_json(&cand[choice], &aw[0], ah[0], degrees) : json_null();
    json_t *rjs = runner >= 0 ? answer_json(&cand[runner], &aw[na - 1], ah[na - 1], degrees) : json_null();
    if (!cjs || !rjs) { json_decref(cjs); json_decref(rjs); json_decref(root); json_decref(cj); return NULL; }
    root = cli_put(root, "choice", cjs);
    root = cli_put(root, "runner_up", rjs);
    if (json_is_true(json_object_get(params, "brief"))) {
        json_decref(cj);
        return root;
    }
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
    {"input", CLI_FIELD_STRING, 0, 0, 0},           {"mode", CLI_FIELD_STRING, 0, 0, 0},
    {"batch", CLI_FIELD_INT, 0, 1, 1 << 20},        {"live", CLI_FIELD_BOOL, 0, 0, 0},
    {"brief", CLI_FIELD_BOOL, 1, 0, 0},
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

/* What involves several options: the order, --max-beta and --tolerance
 * required; --exr, --layout, --max-order and --rot-tolerance with --order
 * auto only; the angles in radians within [0, π].  The choice's inputs
 * into *co (its order 0 with auto). */
static int validate(const plan_args *a, const cli_parsed *seen, sh_rot_choose_opts *co)
{
    const int order_auto = a->order == PLAN_ORDER_AUTO;
    if (!cli_given(seen, "order")) return cli_fail("plan: --order N (or auto) is required");
    if (!cli_given(seen, "max-beta")) return cli_fail("plan: --max-beta is required");
    if (!cli_given(seen, "tolerance")) return cli_fail("plan: --tolerance is required");
    if (order_auto && !a->exr) return cli_fail("plan: --order auto needs --exr FILE");
    if (cli_applies("plan", a->exr != NULL, "--exr", order_auto, "--order auto") ||
        cli_applies("plan", cli_given(seen, "layout"), "--layout", order_auto, "--order auto") ||
        cli_applies("plan", cli_given(seen, "max-order"), "--max-order", order_auto, "--order auto") ||
        cli_applies("plan", cli_given(seen, "rot-tolerance"), "--rot-tolerance", order_auto, "--order auto") ||
        cli_applies("plan", cli_given(seen, "batch"), "--batch", a->mode != SH_BENCH_PER_ROTATION,
                    "--mode batched or k-rotations"))
        return CLI_EXIT_USAGE;
    *co = (sh_rot_choose_opts){.order = order_auto ? 0 : a->order, .tolerance = a->tolerance,
                               .lobe_exp = a->lobe_exp, .measure = a->measure, .prec = a->prec,
                               .conv = (sh_convention)a->conv};
    const double deg = a->degrees ? M_PI / 180 : 1.0;
    co->max_beta = a->max_beta * deg;
    if (!(co->max_beta >= 0 && co->max_beta <= M_PI * (1 + 1e-12)))
        return cli_fail("--max-beta: %g is outside [0, %s", a->max_beta,
                        a->degrees ? "180] degrees" : "π] radians (--degrees for degrees)");
    co->max_beta = fmin(co->max_beta, M_PI);
    co->beta_step = a->beta_step > 0 ? a->beta_step * deg : 0.25 * M_PI / 180;
    if (co->beta_step < 1e-5) return cli_fail("--beta-step: too small (< 1e-5 rad)");
    return 0;
}

/* max_beta as printed: in the unit asked for */
static double max_beta_shown(const plan_args *a, const sh_rot_choose_opts *co)
{
    return a->degrees ? fmin(a->max_beta, 180.0) : co->max_beta;
}

/* --order auto when no order <= --max-order represents the image: a valid
 * request whose answer is "no order qualifies", a failed check (exit 1),
 * the result still printed, without candidates. */
static int no_order(const plan_args *a, const sh_rot_choose_opts *co, int max_order, double resid, json_t *image)
{
    fprintf(stderr, "plan: no order <= %d represents %s to relative L2 %g (at order %d: %.3g)\n", max_order,
            a->exr, a->tolerance, max_order, resid);
    json_t *root = json_object();
    root = cli_put(root, "order", json_null());
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    root = cli_put(root, "max_beta", json_real(max_beta_shown(a, co)));
    root = cli_put(root, "unit", json_string(cli_angle_unit(a->degrees)));
    root = cli_put(root, "tolerance", json_real(a->rot_tol > 0 ? a->rot_tol : co->tolerance));
    root = cli_put(root, "measure", json_string(sh_error_measure_name(co->measure)));
    root = cli_put(root, "lobe_exp", json_real(co->lobe_exp));
    root = cli_put(root, "precision", json_string(sh_precision_name(co->prec)));
    root = cli_put(root, "image_tolerance", json_real(a->tolerance));
    root = cli_put(root, "max_order", json_integer(max_order));
    root = cli_put(root, "order_residual", json_real(resid));
    root = cli_put(root, "image", image);
    root = cli_put(root, "choice", json_null());
    root = cli_put(root, "runner_up", json_null());
    root = cli_put(root, "candidates", json_array());
    const int rc = cli_emit(root, a->sweep.fmt);
    return rc == CLI_EXIT_OK ? CLI_EXIT_CHECK : rc;
}

/* --order auto: the smallest order whose projection of the image has
 * relative L2 residual <= --tolerance (then --rot-tolerance, if given, is
 * the rotation's budget).  -1 to go on with co->order, *image and *resid
 * set; else the exit code (the result printed when no order qualifies). */
static int auto_order(const plan_args *a, sh_rot_choose_opts *co, json_t **image, double *resid_out)
{
    sh_image img = {0};
    if (cli_input("EXR image", a->exr)) return CLI_EXIT_USAGE;
    int st = sh_exr_read(a->exr, &img, NULL);
    if (st) return cli_fail_status(st);
    double resid[64];
    int order = -1, max_order = a->max_order;
    /* no order beyond what the image can carry (sh_image_max_order) */
    if (max_order > sh_image_max_order(&img, a->layout)) max_order = sh_image_max_order(&img, a->layout);
    if (!a->sweep.quiet)
        fprintf(stderr, "plan: projecting %s (%dx%d) to order %d\n", a->exr, img.width, img.height, max_order);
    st = sh_order_for_image(&img, a->layout, a->tolerance, max_order, &order, resid);
    const int w = img.width, h = img.height;
    sh_image_free(&img);
    if (st) return cli_fail_status(st);
    json_t *img_json = json_object();
    img_json = cli_put(img_json, "path", json_string(a->exr));
    img_json = cli_put(img_json, "width", json_integer(w));
    img_json = cli_put(img_json, "height", json_integer(h));
    img_json = cli_put(img_json, "layout", json_string(a->layout == SH_LAYOUT_LATLONG ? "latlong" : "probe"));
    if (order < 0) return no_order(a, co, max_order, resid[max_order - 1], img_json);
    co->order = order;
    *resid_out = resid[order - 1];
    *image = img_json;
    if (a->rot_tol > 0) co->tolerance = a->rot_tol;
    return -1;
}

/* Everything the result depends on (the sweep: step j of the β grid),
 * whichever shard runs; image (stolen) and resid with --order auto. */
static json_t *sweep_params(const plan_args *a, const sh_rot_choose_opts *co, const sh_rot_method *ms, int nm,
                            json_t *image, double resid)
{
    json_t *params = json_object(), *mj = json_array();
    for (int k = 0; k < nm && mj; k++)
        if (json_array_append_new(mj, json_string(sh_rot_method_name(ms[k])))) { json_decref(mj); mj = NULL; }
    params = cli_put(params, "order", json_integer(co->order));
    params = cli_put(params, "convention", json_string(sh_convention_name(co->conv)));
    params = cli_put(params, "max_beta", json_real(co->max_beta));
    params = cli_put(params, "degrees", json_boolean(a->degrees));
    params = cli_put(params, "max_beta_shown", json_real(max_beta_shown(a, co)));
    params = cli_put(params, "tolerance", json_real(co->tolerance));
    params = cli_put(params, "measure", json_string(sh_error_measure_name(co->measure)));
    params = cli_put(params, "lobe_exp", json_real(co->lobe_exp));
    params = cli_put(params, "precision", json_string(sh_precision_name(co->prec)));
    params = cli_put(params, "input", json_string(input_names[a->input]));
    params = cli_put(params, "mode", json_string(mode_names[a->mode]));
    params = cli_put(params, "batch", json_integer(a->mode == SH_BENCH_PER_ROTATION ? 1 : a->batch));
    params = cli_put(params, "live", json_boolean(a->live));
    if (a->brief) params = cli_put(params, "brief", json_true());
    if (a->order == PLAN_ORDER_AUTO) {
        params = cli_put(params, "image_tolerance", json_real(a->tolerance));
        params = cli_put(params, "order_residual", json_real(resid));
        params = cli_put(params, "image", image);
    }
    params = cli_put(params, "beta_step", json_real(co->beta_step));
    return cli_put(params, "methods", mj);
}

/* The errors of the nm methods on this shard's steps of the β grid, a row
 * each.  0 or the exit code. */
static int measure(sh_rot_choose_opts *co, int nm, int nsteps, cli_sweep *sw)
{
    double *err = malloc(sizeof *err * (size_t)nsteps * (nm ? nm : 1));
    if (!err) return cli_fail("out of memory");
    co->progress = cli_progress_step;
    co->progress_ctx = &sw->prog;
    const int st = sh_rot_choose_errors(co, cli_sweep_items(sw), err);
    sw->prog.quiet = 1; /* the library counted the steps */
    if (st) { free(err); return cli_fail_status(st); }
    for (int j = 0; j < nsteps; j++) {
        if (!cli_sweep_owns(sw, j)) continue;
        json_t *r = json_object();
        r = cli_put(r, "beta", json_real(beta_of(co->max_beta, nsteps, j)));
        r = cli_put(r, "errors", cli_json_array(err + (size_t)j * nm, (size_t)nm));
        if (cli_sweep_add(sw, j, r) == CLI_EXIT_USAGE) { free(err); return CLI_EXIT_USAGE; }
    }
    free(err);
    return 0;
}

static int run(int argc, char **argv)
{
    plan_args a = {0};
    cli_parsed seen;
    sh_rot_choose_opts co;
    int rc = cli_args_parse(&plan_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen, &co))) return rc;
    json_t *image = NULL;
    double resid = 0;
    if (a.order == PLAN_ORDER_AUTO && (rc = auto_order(&a, &co, &image, &resid)) >= 0) return rc;
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm = 0, nsteps = 0;
    const int st = sh_rot_choose_grid(&co, ms, &nm, &nsteps);
    if (st) { json_decref(image); return cli_fail_status(st); }
    if (!a.sweep.quiet) fprintf(stderr, "plan: measuring and costing the methods at order %d\n", co.order);
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_plan, sweep_params(&a, &co, ms, nm, image, resid), nsteps, &a.sweep, "steps");
    return cli_sweep_close(&sw, measure(&co, nm, nsteps, &sw));
}

const cli_command cmd_plan = {"plan", run,
                              "the cheapest rotation method for an error budget up to a β "
                              "(measured now); --order auto from an EXR",
                              &plan_decl};
