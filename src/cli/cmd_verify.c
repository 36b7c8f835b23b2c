/* cmd_verify.c — `shlab verify`: check a candidate kernel's outputs (or one of
 * shlab's own methods) against golden rotation fixtures, and with --diagnose
 * name the likely cause of a mismatch by testing known transformations. */
#include "cli.h"
#include "core/shlab_internal.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* A transformation of the expected answer that a wrong kernel would produce. */
typedef enum {
    T_CONV, T_INVERSE, T_SWAP, T_BETA, T_DEG2RAD, T_RAD2DEG, T_MDESC_BOTH, T_MDESC_OUT, T_MDESC_IN,
    T_COUNT
} transform;
static const char *const t_name[T_COUNT] = {
    "other CS-phase convention (cs vs nocs; the same as β negated: R(α,-β,γ) = S R S)",
    "inverse rotation (frame rotation / transposed matrix / conjugated quaternion)",
    "alpha and gamma swapped (Rz(γ)Ry(β)Rz(α))",
    "beta negated (Ry(-β): left-handed y rotation)",
    "degrees taken as radians (angles scaled by π/180)",
    "radians taken as degrees (angles scaled by 180/π)",
    "m-descending order within each band (input and output)",
    "m-descending order of the output within each band",
    "m-descending order of the input within each band",
};

/* --simulate's names: the mistakes (transform's order), then float
 * precision only (T_COUNT) and none. */
static const char *const t_short[] = {"convention", "inverse", "swap", "beta", "deg2rad", "rad2deg", "mdesc",
                                      "mdesc-out", "mdesc-in", "float", "none", NULL};
#define SIM_FLOAT T_COUNT
#define SIM_NONE (T_COUNT + 1)

static void reverse_bands(const fx_case *c, const double *in, double *out)
{
    const int l0 = c->band >= 0 ? c->band : 0, l1 = c->band >= 0 ? c->band : c->order - 1;
    for (int l = l0; l <= l1; l++) {
        const int off = c->band >= 0 ? 0 : l * l, w = 2 * l + 1;
        for (int i = 0; i < w; i++) out[off + i] = in[off + w - 1 - i];
    }
}

/* What a kernel with mistake t outputs for case c (exact method). */
static int transformed(transform t, const fx_case *c, double *out, double *tmp)
{
    sh_rotation r = c->rot;
    const double a = c->rot.alpha, b = c->rot.beta, g = c->rot.gamma;
    const sh_rot_method m = c->band > 20 ? SH_ROT_REFERENCE : SH_ROT_WIGNER;
    sh_convention conv = c->conv;
    const double *in = c->input;
    switch (t) {
    case T_CONV: conv = conv == SH_CS ? SH_NOCS : SH_CS; break;
    case T_INVERSE: sh_rotation_inverse(&c->rot, &r); break;
    case T_SWAP: sh_rotation_from_euler(g, b, a, &r); break;
    case T_BETA: sh_rotation_from_euler(a, -b, g, &r); break;
    case T_DEG2RAD: sh_rotation_from_euler(a * M_PI / 180, b * M_PI / 180, g * M_PI / 180, &r); break;
    case T_RAD2DEG: sh_rotation_from_euler(a * 180 / M_PI, b * 180 / M_PI, g * 180 / M_PI, &r); break;
    case T_MDESC_BOTH:
    case T_MDESC_IN: reverse_bands(c, c->input, tmp); in = tmp; break;
    default: break;
    }
    int st = fx_apply(m, SH_PREC_DOUBLE, c, &r, conv, in, out);
    if (st) return st;
    if (t == T_MDESC_BOTH || t == T_MDESC_OUT) {
        memcpy(tmp, out, (size_t)c->n * sizeof *tmp);
        reverse_bands(c, tmp, out);
    }
    return SH_OK;
}

static double max_err(const double *a, const double *b, int n, int *at)
{
    double w = 0;
    *at = 0;
    for (int i = 0; i < n; i++) {
        const double e = fabs(a[i] - b[i]);
        if (!(e <= w)) { w = e; *at = i; } /* NaN counts as worst */
        if (isnan(e)) { w = INFINITY; *at = i; break; }
    }
    return w;
}

/* {"results": {"<id>": [...], ...}}, one case per line, into the temporary
 * file of the output (cli_out_open; cli_emit renames it onto `path`). */
static int write_candidate(const char *tmp, const char *path, const fx_set *fx, double **got)
{
    FILE *f = sh__temp_fopen(tmp, "w");
    int bad = !f;
    if (f) {
        fputs("{\"results\":{\n", f);
        for (int k = 0; k < fx->ncases && !bad; k++) {
            json_t *id = json_string(fx->cases[k].id);
            json_t *a = cli_json_array(got[k], (size_t)fx->cases[k].n);
            char *si = id ? json_dumps(id, JSON_ENCODE_ANY) : NULL;
            char *s = a ? json_dumps(a, JSON_COMPACT | JSON_REAL_PRECISION(17)) : NULL;
            if (!s || !si) bad = 1;
            else fprintf(f, "%s:%s%s\n", si, s, k + 1 < fx->ncases ? "," : "");
            free(s);
            free(si);
            json_decref(a);
            json_decref(id);
        }
        fputs("}}\n", f);
        bad |= ferror(f) != 0;
        bad |= fclose(f) != 0;
    }
    return bad ? cli_fail("verify: cannot write candidate '%s'", path) : 0;
}


typedef struct {
    const char *fixture, *cand, *emit;
    sh_rot_method method; /* SH_ROT_AUTO: none (a --candidate is verified) */
    sh_precision prec;
    sh_rot_kernel kernel;
    int diagnose, simulate, matrix_input, quiet, fmt;
} verify_args;

/* {.needs}: an option that applies only with another one */
#define NEEDS_FLAG(F, NAME, NEEDS, HELP)                                                           \
    {.type = CLI_T_FLAG, .name = NAME, .off = offsetof(verify_args, F), .help = HELP, .needs = NEEDS}

static const cli_opt verify_opts[] = {
    CLI_STRING(verify_args, fixture, "fixture", "F", "a fixture file (data/fixtures/rotation/*.json)"),
    CLI_STRING(verify_args, cand, "candidate", "C",
               "JSON {\"results\": {\"<case id>\": [outputs...], ...}}\n"
               "from the kernel under test (every case id of F)"),
    CLI_CUSTOM(verify_args, method, "method", "M", cli_parse_method, NULL,
               "instead of a candidate, run shlab's method M"),
    CLI_CUSTOM(verify_args, prec, "precision", "P", cli_parse_precision, "double",
               "double (default) | float: the tolerance (and, with\n--method, the arithmetic) to use"),
    {.type = CLI_T_CUSTOM, .name = "kernel", .meta = "K", .off = offsetof(verify_args, kernel),
     .parse = cli_parse_kernel, .def = "auto", .needs = "method",
     .help = "with --method: auto (default) | scalar | unrolled |\n"
             "sse2 | avx2 | avx512, the code that runs (the fixture's\n"
             "Euler angles reach the plan as angles; --matrix-input:\n"
             "as the case's matrix, sh_rot_plan_set_matrix)"},
    CLI_FLAG(verify_args, quiet, "quiet", "no progress on stderr"),
    NEEDS_FLAG(matrix_input, "matrix-input", "method", "with --method: give each case's rotation as its matrix"),
    CLI_FLAG(verify_args, diagnose, "diagnose",
             "on failure, test what the candidate matches instead:\n"
             "the other CS-phase convention, the inverse (frame)\n"
             "rotation, α and γ swapped, β negated, degrees taken as\n"
             "radians (or the reverse), m-descending order within a\n"
             "band, or float precision only"),
    CLI_FORMAT(verify_args, fmt),
    CLI_HEADING(""),
    {.type = CLI_T_STRING, .name = "emit-candidate", .meta = "F", .off = offsetof(verify_args, emit),
     .needs = "method",
     .help = "with --method: also write the outputs as a candidate\n"
             "file (the format a kernel under test must produce)"},
    {.type = CLI_T_CHOICE, .name = "simulate", .meta = "MISTAKE", .off = offsetof(verify_args, simulate),
     .choices = t_short, .def = "none", .flags = CLI_NO_DEFAULT, .needs = "emit-candidate",
     .help = "with --emit-candidate: write what a kernel with this\n"
             "mistake would output: convention | inverse | swap |\n"
             "beta | deg2rad | rad2deg | mdesc | mdesc-out | mdesc-in\n"
             "| float (to try --diagnose).  The verdict printed is\n"
             "that of the simulated kernel (it fails, as meant);\n"
             "the exit status is 0 once the file is written"},
    CLI_END,
};

static const cli_cmd verify_decl = {
    .name = "verify",
    .usage = "verify --fixture F (--candidate C | --method M) [OPTIONS]",
    .about = "Compare rotated coefficients with a golden fixture file (shlab fixtures).\n"
             "A case passes if every |candidate_i - expected_i| <= the case's double\n"
             "tolerance (--precision float: its float32 tolerance).  Exit 0 if all cases\n"
             "pass, 1 if any fails (the worst case is printed), 2 on bad input.\n",
    .opts = verify_opts,
    .notes =
        "JSON: {\"fixture\",\"source\",\"tolerance_kind\",\"cases\",\"failed\",\"pass\",\n"
        "       \"worst_id\",\"worst_index\",\"worst_got\",\"worst_expected\",\"worst_error\",\n"
        "       \"worst_tolerance\",\"convention\" (cs, nocs, or cs+nocs when the fixture's\n"
        "       cases mix both),[\"method\" (with --method)],[\"kernel\"],[\"input\"],\n"
        "       [\"simulated\" (with --simulate)],[\"skipped\"],\n"
        "       [\"diagnosis\",\"diagnosis_matches\",\"diagnosis_checked\",\"diagnosis_tolerance\"]}\n"
        "\"failed\" counts the cases beyond the tolerance of tolerance_kind (double: 1e-13).\n"
        "\"skipped\" (--method, when non-zero): the cases above the method's largest order\n"
        "(direct: 3), neither rotated nor judged; \"cases\" counts them too.\n"
        "The diagnosis compares at each case's float32 tolerance (1e-6 and more), so its\n"
        "counts are not comparable with \"failed\": diagnosis_checked = the cases the\n"
        "mistake changes by more than their float32 tolerance (a mistake that changes a\n"
        "case less, at β ≈ 0 say, proves nothing there), diagnosis_matches = those of\n"
        "them the candidate equals within it; a diagnosis must explain all it checks.\n",
};

/* The fixture, the outputs under test (got[k]: case k's n values) and scratch
 * for the transformations (tmp: 2·maxn). */
typedef struct {
    fx_set fx;
    double **got, *tmp;
    int maxn;
    unsigned char *skip; /* case k above the method's largest order: not rotated, not judged */
    int nskip;
    cli_progress prog;
} verify_work;

static void work_free(verify_work *w)
{
    if (w->got)
        for (int k = 0; k < w->fx.ncases; k++) free(w->got[k]);
    free(w->got);
    free(w->tmp);
    free(w->skip);
    fx_free(&w->fx);
}

static int work_load(const verify_args *a, verify_work *w)
{
    *w = (verify_work){.maxn = 1};
    if (fx_load(a->fixture, &w->fx)) return CLI_EXIT_USAGE;
    for (int k = 0; k < w->fx.ncases; k++) w->maxn = w->fx.cases[k].n > w->maxn ? w->fx.cases[k].n : w->maxn;
    w->got = calloc((size_t)w->fx.ncases + 1, sizeof *w->got);
    w->tmp = malloc(2 * (size_t)w->maxn * sizeof *w->tmp);
    w->skip = calloc((size_t)w->fx.ncases + 1, 1);
    int ok = w->got && w->tmp && w->skip;
    for (int k = 0; ok && k < w->fx.ncases; k++) ok = (w->got[k] = malloc((size_t)w->fx.cases[k].n * sizeof **w->got)) != NULL;
    return ok ? 0 : cli_fail("out of memory");
}

/* Every case rotated by shlab's method (or as the simulated mistake does it).
 * Cases above the method's largest order (direct: 3) are skipped, and said
 * so (stderr and "skipped"); a fixture with none in reach is refused. */
static int run_method(const verify_args *a, verify_work *w)
{
    const sh_rot_method m = a->method;
    const int top = sh_rot_method_max_order(m);
    int st = 0;
    for (int k = 0; k < w->fx.ncases; k++) {
        w->skip[k] = w->fx.cases[k].order > top;
        w->nskip += w->skip[k];
    }
    if (w->nskip == w->fx.ncases)
        return cli_fail("verify: method %s is limited to order %d; every case of the fixture needs more",
                        sh_rot_method_name(m), top);
    if (w->nskip && a->emit)
        return cli_fail("verify: method %s is limited to order %d: %d cases would be missing from "
                        "--emit-candidate", sh_rot_method_name(m), top, w->nskip);
    if (w->nskip)
        fprintf(stderr, "verify: method %s is limited to order %d: %d of the %d cases skipped (higher orders)\n",
                sh_rot_method_name(m), top, w->nskip, w->fx.ncases);
    for (int k = 0; k < w->fx.ncases && !st; k++) {
        const fx_case *c = &w->fx.cases[k];
        if (w->skip[k]) continue;
        if (m == SH_ROT_Z && c->rot.beta != 0)
            return cli_fail("verify: method z rotates about z only; case '%s' has β = %.3g rad", c->id, c->rot.beta);
        if (a->simulate < T_COUNT)
            st = transformed((transform)a->simulate, c, w->got[k], w->tmp);
        else
            st = fx_apply_kernel(m, a->simulate == SIM_FLOAT ? SH_PREC_FLOAT : a->prec, a->kernel, a->matrix_input, c,
                                 &c->rot, c->conv, c->input, w->got[k]);
        cli_progress_step(&w->prog, k + 1, w->fx.ncases, "cases rotated");
    }
    return st ? cli_fail("verify: %s", sh_last_error()) : 0;
}

/* The verdict: cases beyond their tolerance, and the worst one (by error
 * over tolerance). */
typedef struct {
    int failed, failed_near, worst_k, worst_i;
} verdict;

static verdict judge(const verify_args *a, const verify_work *w)
{
    verdict v = {0};
    double worst_ratio = -1;
    v.worst_k = -1;
    for (int k = 0; k < w->fx.ncases; k++) {
        const fx_case *c = &w->fx.cases[k];
        if (w->skip[k]) continue;
        if (v.worst_k < 0) v.worst_k = k;
        const double tol = a->prec == SH_PREC_FLOAT ? c->tol_float : c->tol_double;
        int at;
        const double e = max_err(w->got[k], c->expected, c->n, &at);
        if (!(e <= tol)) v.failed++;
        if (!(e <= tol) && e <= c->tol_float) v.failed_near++;
        if (!(e / tol <= worst_ratio)) worst_ratio = e / tol, v.worst_k = k, v.worst_i = at;
    }
    return v;
}

static json_t *result(const verify_args *a, int have_kernel, const verify_work *w, const verdict *v)
{
    const fx_case *wc = &w->fx.cases[v->worst_k];
    const int have_method = a->method != SH_ROT_AUTO, fl = a->prec == SH_PREC_FLOAT;
    json_t *root = json_object();
    root = cli_put(root, "fixture", json_string(a->fixture));
    root = cli_put(root, "source", json_string(a->cand ? a->cand : sh_rot_method_name(a->method)));
    root = cli_put(root, "tolerance_kind", json_string(fl ? "float32" : "double"));
    root = cli_put(root, "cases", json_integer(w->fx.ncases));
    root = cli_put(root, "failed", json_integer(v->failed));
    root = cli_put(root, "pass", json_boolean(v->failed == 0));
    const double wg = w->got[v->worst_k][v->worst_i], we = fabs(wg - wc->expected[v->worst_i]);
    root = cli_put(root, "worst_id", json_string(wc->id));
    root = cli_put(root, "worst_index", json_integer(v->worst_i));
    root = cli_put(root, "worst_got", isfinite(wg) ? json_real(wg) : json_string("not finite"));
    root = cli_put(root, "worst_expected", json_real(wc->expected[v->worst_i]));
    root = cli_put(root, "worst_error", isfinite(we) ? json_real(we) : json_string("not finite"));
    root = cli_put(root, "worst_tolerance", json_real(fl ? wc->tol_float : wc->tol_double));
    /* after the fields above, so that their CSV columns keep their places */
    int have_cs = 0, have_nocs = 0;
    for (int k = 0; k < w->fx.ncases; k++) {
        have_cs |= w->fx.cases[k].conv == SH_CS;
        have_nocs |= w->fx.cases[k].conv == SH_NOCS;
    }
    root = cli_put(root, "convention", json_string(have_cs && have_nocs ? "cs+nocs" : have_nocs ? "nocs" : "cs"));
    if (have_method) root = cli_put(root, "method", json_string(sh_rot_method_name(a->method)));
    if (a->simulate != SIM_NONE) root = cli_put(root, "simulated", json_string(t_short[a->simulate]));
    if (have_kernel) root = cli_put(root, "kernel", json_string(sh_rot_kernel_name(a->kernel)));
    if (a->matrix_input) root = cli_put(root, "input", json_string("matrix"));
    if (w->nskip) root = cli_put(root, "skipped", json_integer(w->nskip));
    return root;
}

/* The mistake that explains every case it changes (at the float32
 * tolerance) and the most of them; -1 if none.  *n_ok, *n_seen: its counts. */
static int best_mistake(verify_work *w, int *n_ok, int *n_seen)
{
    double *y = malloc((size_t)w->maxn * sizeof *y);
    if (!y) return -2;
    int best = -1;
    *n_ok = *n_seen = 0;
    for (int t = 0; t < T_COUNT; t++) {
        /* β negated is the convention flip itself: d(-β) = S d(β) S with
         * S = (-1)^m, and S commutes with the z rotations (see README) */
        if (t == T_BETA) continue;
        int ok = 0, seen = 0;
        for (int k = 0; k < w->fx.ncases; k++) {
            const fx_case *c = &w->fx.cases[k];
            int at;
            if (w->skip[k]) continue;
            if (transformed((transform)t, c, y, w->tmp)) continue;
            /* a transformation that changes nothing (β = 0, say) proves nothing */
            if (max_err(y, c->expected, c->n, &at) <= c->tol_float) continue;
            seen++;
            if (max_err(w->got[k], y, c->n, &at) <= c->tol_float) ok++;
            cli_progress_step(&w->prog, t * w->fx.ncases + k + 1, T_COUNT * w->fx.ncases,
                              "cases tried under the known mistakes (--diagnose)");
        }
        /* the transformation must explain every case it changes */
        if (ok > *n_ok && ok == seen) *n_ok = ok, best = t, *n_seen = seen;
    }
    free(y);
    return best;
}

/* --diagnose on a failure: the likely cause, into root, and one line on
 * stderr saying what its counts count. */
static int diagnose(const verify_args *a, verify_work *w, const verdict *v, json_t **root)
{
    /* float precision only: every case within its float32 tolerance */
    int float_ok = 0, best = -1, best_n = 0, best_seen = 0;
    for (int k = 0; k < w->fx.ncases; k++) {
        int at;
        if (w->skip[k]) continue;
        if (max_err(w->got[k], w->fx.cases[k].expected, w->fx.cases[k].n, &at) <= w->fx.cases[k].tol_float) float_ok++;
    }
    const char *cause = NULL;
    if (a->prec == SH_PREC_DOUBLE && float_ok == w->fx.ncases - w->nskip) {
        cause = "float precision only: every case matches within its float32 tolerance";
        best_n = best_seen = float_ok;
    } else if ((best = best_mistake(w, &best_n, &best_seen)) == -2) {
        return cli_fail("out of memory");
    } else if (best >= 0) {
        cause = t_name[best];
    }
    *root = cli_put(*root, "diagnosis", json_string(cause ? cause : "no known transformation explains the mismatch"));
    *root = cli_put(*root, "diagnosis_matches", json_integer(best_n));
    *root = cli_put(*root, "diagnosis_checked", json_integer(best_seen));
    *root = cli_put(*root, "diagnosis_tolerance", json_string("float32"));
    /* "failed" counts cases beyond the tolerance_kind tolerance (double:
     * 1e-13); the diagnosis compares at the float32 tolerance, so the two
     * counts differ: say what each one counts */
    fprintf(stderr,
            "verify: failed counts the cases beyond their %s tolerance; the diagnosis compares at "
            "each case's float32 tolerance: diagnosis_checked = the %d cases the mistake changes "
            "by more than that, diagnosis_matches = the %d of them the candidate equals (%d of the "
            "%d failed cases are within their float32 tolerance: too close to tell)\n",
            a->prec == SH_PREC_FLOAT ? "float32" : "double", best_seen, best_n, v->failed_near, v->failed);
    return 0;
}

/* The outputs under test: the candidate's, or shlab's method's (and then
 * the candidate file it writes with --emit-candidate). */
static int outputs(const verify_args *a, const char *emit_tmp, verify_work *w)
{
    if (a->cand) return fx_load_candidate(a->cand, &w->fx, w->got);
    int rc = run_method(a, w);
    if (!rc && a->emit) rc = write_candidate(emit_tmp, a->emit, &w->fx, w->got);
    return rc;
}

static int run(int argc, char **argv)
{
    verify_args a = {.method = SH_ROT_AUTO};
    cli_parsed seen;
    int rc = cli_args_parse(&verify_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!a.fixture) return cli_fail("verify: --fixture F is required");
    /* --method auto is no method (the default) */
    if (!a.cand == (a.method == SH_ROT_AUTO)) return cli_fail("verify: give exactly one of --candidate and --method");
    const char *emit_tmp = NULL;
    if (a.emit && cli_out_open("verify", a.emit, &emit_tmp)) return CLI_EXIT_USAGE;
    verify_work w;
    rc = work_load(&a, &w);
    cli_progress_start(&w.prog, "verify", a.quiet);
    if (!rc) rc = outputs(&a, emit_tmp, &w);
    if (rc) {
        work_free(&w);
        return rc;
    }
    const verdict v = judge(&a, &w);
    json_t *root = result(&a, cli_given(&seen, "kernel"), &w, &v);
    if (a.diagnose && v.failed && (rc = diagnose(&a, &w, &v, &root))) {
        json_decref(root);
        work_free(&w);
        return rc;
    }
    const int simulated = a.simulate != SIM_NONE;
    if (v.failed)
        fprintf(stderr, "verify: %d of %d cases exceed the %s tolerance; worst: case %s, index %d%s\n", v.failed,
                w.fx.ncases - w.nskip, a.prec == SH_PREC_FLOAT ? "float32" : "double", w.fx.cases[v.worst_k].id, v.worst_i,
                simulated ? " (the simulated mistake, as asked)" : "");
    work_free(&w);
    rc = cli_emit(root, (cli_format)a.fmt);
    /* --simulate asks for a wrong kernel's outputs: they are meant to fail,
     * and the command succeeded once the candidate file is written */
    return rc == 0 && v.failed && !simulated ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_verify = {"verify", run, "check a kernel's rotated coefficients against golden fixtures", &verify_decl};
