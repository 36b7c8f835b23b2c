/* cmd_verify.c — `shlab verify`: check a candidate kernel's outputs (or one of
 * shlab's own methods) against golden rotation fixtures, and with --diagnose
 * name the likely cause of a mismatch by testing known transformations. */
#include "cli.h"
#include "core/shlab_internal.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_verify;

static const char help[] =
    "Usage: shlab verify --fixture F (--candidate C | --method M) [OPTIONS]\n"
    "\n"
    "Compare rotated coefficients with a golden fixture file (shlab fixtures).\n"
    "A case passes if every |candidate_i - expected_i| <= the case's double\n"
    "tolerance (--precision float: its float32 tolerance).  Exit 0 if all cases\n"
    "pass, 1 if any fails (the worst case is printed), 2 on bad input.\n"
    "\n"
    "  --fixture F          a fixture file (data/fixtures/rotation/*.json)\n"
    "  --candidate C        JSON {\"results\": {\"<case id>\": [outputs...], ...}}\n"
    "                       from the kernel under test (every case id of F)\n"
    "  --method M           instead of a candidate, run shlab's method M\n"
    "  --precision P        double (default) | float: the tolerance (and, with\n"
    "                       --method, the arithmetic) to use\n"
    "  --kernel K           with --method: auto (default) | scalar | unrolled |\n"
    "                       sse2 | avx2 | avx512, the code that runs (the fixture's\n"
    "                       Euler angles reach the plan as angles; --matrix-input:\n"
    "                       as the case's matrix, sh_rot_plan_set_matrix)\n"
    "  --quiet              no progress on stderr\n"
    "  --matrix-input       with --method: give each case's rotation as its matrix\n"
    "  --diagnose           on failure, test what the candidate matches instead:\n"
    "                       the other CS-phase convention, the inverse (frame)\n"
    "                       rotation, α and γ swapped, β negated, degrees taken as\n"
    "                       radians (or the reverse), m-descending order within a\n"
    "                       band, or float precision only\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "  --emit-candidate F   with --method: also write the outputs as a candidate\n"
    "                       file (the format a kernel under test must produce)\n"
    "  --simulate MISTAKE   with --emit-candidate: write what a kernel with this\n"
    "                       mistake would output: convention | inverse | swap |\n"
    "                       beta | deg2rad | rad2deg | mdesc | mdesc-out | mdesc-in\n"
    "                       | float (to try --diagnose).  The verdict printed is\n"
    "                       that of the simulated kernel (it fails, as meant);\n"
    "                       the exit status is 0 once the file is written\n"
    "\n"
    "JSON: {\"fixture\",\"source\",\"tolerance_kind\",\"cases\",\"failed\",\"pass\",\n"
    "       \"worst_id\",\"worst_index\",\"worst_got\",\"worst_expected\",\"worst_error\",\n"
    "       \"worst_tolerance\",\"convention\" (cs, nocs, or cs+nocs when the fixture's\n"
    "       cases mix both),[\"method\" (with --method)],[\"kernel\"],[\"input\"],\n"
    "       [\"simulated\" (with --simulate)],\n"
    "       [\"diagnosis\",\"diagnosis_matches\",\"diagnosis_checked\",\"diagnosis_tolerance\"]}\n"
    "\"failed\" counts the cases beyond the tolerance of tolerance_kind (double: 1e-13).\n"
    "The diagnosis compares at each case's float32 tolerance (1e-6 and more), so its\n"
    "counts are not comparable with \"failed\": diagnosis_checked = the cases the\n"
    "mistake changes by more than their float32 tolerance (a mistake that changes a\n"
    "case less, at β ≈ 0 say, proves nothing there), diagnosis_matches = those of\n"
    "them the candidate equals within it; a diagnosis must explain all it checks.\n";

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

static const char *const t_short[T_COUNT] = {"convention", "inverse", "swap", "beta", "deg2rad",
                                             "rad2deg", "mdesc", "mdesc-out", "mdesc-in"};

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

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_PRECISION,
                                         CLI_LONGOPT_KERNEL,
                                         {"fixture", required_argument, 0, 'f'},
                                         {"candidate", required_argument, 0, 'c'},
                                         {"diagnose", no_argument, 0, 'd'},
                                         {"emit-candidate", required_argument, 0, 'E'},
                                         {"simulate", required_argument, 0, 'S'},
                                         {"matrix-input", no_argument, 0, 'X'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    const char *fixture = NULL, *cand = NULL;
    sh_rot_method method = SH_ROT_IVANIC;
    sh_precision prec = SH_PREC_DOUBLE;
    int have_method = 0, diagnose = 0, simulate = -1; /* -1 none, T_COUNT = float */
    const char *emit = NULL;
    int matrix_input = 0, quiet = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'f': fixture = optarg; break;
        case 'c': cand = optarg; break;
        case 'd': diagnose = 1; break;
        case 'E': emit = optarg; break;
        case 'X': matrix_input = 1; break;
        case 'q': quiet = 1; break;
        case 'S':
            simulate = -2;
            for (int t = 0; t < T_COUNT; t++)
                if (!strcmp(optarg, t_short[t])) simulate = t;
            if (!strcmp(optarg, "float")) simulate = T_COUNT;
            if (!strcmp(optarg, "none")) simulate = -1;
            if (simulate == -2)
                return cli_fail("--simulate: unknown mistake '%s' (convention, inverse, swap, beta, "
                                "deg2rad, rad2deg, mdesc, mdesc-out, mdesc-in, float, none)", optarg);
            break;
        default: {
            const int e = cli_common_opt(&cmd_verify, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    method = com.method;
    prec = com.prec;
    have_method = com.have_method;
    if (optind < argc) return cli_fail("verify: unexpected argument '%s'", argv[optind]);
    if (!fixture) return cli_fail("verify: --fixture F is required");
    if (!cand == !have_method) return cli_fail("verify: give exactly one of --candidate and --method");
    if (emit && !have_method) return cli_fail("verify: --emit-candidate needs --method");
    if (simulate != -1 && !emit) return cli_fail("verify: --simulate needs --emit-candidate");
    if ((com.have_kernel || matrix_input) && !have_method) return cli_fail("verify: --kernel and --matrix-input need --method");
    const char *emit_tmp = NULL;
    if (emit && cli_out_open("verify", emit, &emit_tmp)) return CLI_EXIT_USAGE;
    fx_set fx;
    if (fx_load(fixture, &fx)) return CLI_EXIT_USAGE;
    double **got = calloc((size_t)fx.ncases + 1, sizeof *got);
    int rc = 0, st = 0, maxn = 1;
    for (int k = 0; k < fx.ncases; k++) if (fx.cases[k].n > maxn) maxn = fx.cases[k].n;
    double *tmp = malloc(2 * (size_t)maxn * sizeof *tmp);
    for (int k = 0; got && k < fx.ncases; k++)
        if (!(got[k] = malloc((size_t)fx.cases[k].n * sizeof **got))) { free(got); got = NULL; }
    if (!got || !tmp) { rc = cli_fail("out of memory"); goto done; }
    cli_progress prog;
    cli_progress_start(&prog, "verify", quiet);
    if (cand) {
        if ((rc = fx_load_candidate(cand, &fx, got))) goto done;
    } else {
        for (int k = 0; k < fx.ncases && !st; k++) {
            const fx_case *c = &fx.cases[k];
            if (c->order > sh_rot_method_max_order(method)) {
                rc = cli_fail("verify: method %s is limited to order %d; case '%s' needs %d",
                              sh_rot_method_name(method), sh_rot_method_max_order(method), c->id, c->order);
                goto done;
            }
            if (method == SH_ROT_Z && c->rot.beta != 0) {
                rc = cli_fail("verify: method z rotates about z only; case '%s' has β = %.3g rad", c->id, c->rot.beta);
                goto done;
            }
            if (simulate >= 0 && simulate < T_COUNT)
                st = transformed((transform)simulate, c, got[k], tmp);
            else
                st = fx_apply_kernel(method, simulate == T_COUNT ? SH_PREC_FLOAT : prec, com.kernel,
                                     matrix_input, c, &c->rot, c->conv, c->input, got[k]);
            cli_progress_step(&prog, k + 1, fx.ncases, "cases rotated");
        }
        if (st) { rc = cli_fail("verify: %s", sh_last_error()); goto done; }
        if (emit && (rc = write_candidate(emit_tmp, emit, &fx, got))) goto done;
    }
    /* the verdict */
    int failed = 0, fail_double = 0, worst_k = 0, worst_i = 0, failed_near = 0;
    double worst_ratio = -1;
    for (int k = 0; k < fx.ncases; k++) {
        const fx_case *c = &fx.cases[k];
        const double tol = prec == SH_PREC_FLOAT ? c->tol_float : c->tol_double;
        int at;
        const double e = max_err(got[k], c->expected, c->n, &at);
        if (!(e <= tol)) failed++;
        if (!(e <= tol) && e <= c->tol_float) failed_near++;
        if (!(e <= c->tol_double)) fail_double++;
        if (!(e / tol <= worst_ratio)) { worst_ratio = e / tol; worst_k = k; worst_i = at; }
    }
    const fx_case *wc = &fx.cases[worst_k];
    json_t *root = json_object();
    root = cli_put(root, "fixture", json_string(fixture));
    root = cli_put(root, "source", json_string(cand ? cand : sh_rot_method_name(method)));
    root = cli_put(root, "tolerance_kind", json_string(prec == SH_PREC_FLOAT ? "float32" : "double"));
    root = cli_put(root, "cases", json_integer(fx.ncases));
    root = cli_put(root, "failed", json_integer(failed));
    root = cli_put(root, "pass", json_boolean(failed == 0));
    const double wg = got[worst_k][worst_i], we = fabs(wg - wc->expected[worst_i]);
    root = cli_put(root, "worst_id", json_string(wc->id));
    root = cli_put(root, "worst_index", json_integer(worst_i));
    root = cli_put(root, "worst_got", isfinite(wg) ? json_real(wg) : json_string("not finite"));
    root = cli_put(root, "worst_expected", json_real(wc->expected[worst_i]));
    root = cli_put(root, "worst_error", isfinite(we) ? json_real(we) : json_string("not finite"));
    root = cli_put(root, "worst_tolerance",
                   json_real(prec == SH_PREC_FLOAT ? wc->tol_float : wc->tol_double));
    /* after the fields above, so that their CSV columns keep their places */
    int have_cs = 0, have_nocs = 0;
    for (int k = 0; k < fx.ncases; k++) {
        have_cs |= fx.cases[k].conv == SH_CS;
        have_nocs |= fx.cases[k].conv == SH_NOCS;
    }
    root = cli_put(root, "convention",
                   json_string(have_cs && have_nocs ? "cs+nocs" : have_nocs ? "nocs" : "cs"));
    if (have_method) root = cli_put(root, "method", json_string(sh_rot_method_name(method)));
    if (simulate >= 0) root = cli_put(root, "simulated", json_string(simulate < T_COUNT ? t_short[simulate] : "float"));
    if (com.have_kernel) root = cli_put(root, "kernel", json_string(sh_rot_kernel_name(com.kernel)));
    if (matrix_input) root = cli_put(root, "input", json_string("matrix"));
    if (diagnose && failed) {
        /* float precision only: every case within its float32 tolerance */
        int float_ok = 0, best = -1, best_n = 0, best_seen = 0;
        for (int k = 0; k < fx.ncases; k++) {
            int at;
            if (max_err(got[k], fx.cases[k].expected, fx.cases[k].n, &at) <= fx.cases[k].tol_float) float_ok++;
        }
        const char *cause = NULL;
        if (prec == SH_PREC_DOUBLE && float_ok == fx.ncases) {
            cause = "float precision only: every case matches within its float32 tolerance";
            best_n = best_seen = float_ok;
        } else {
            double *y = malloc((size_t)maxn * sizeof *y);
            if (!y) { json_decref(root); rc = cli_fail("out of memory"); goto done; }
            for (int t = 0; t < T_COUNT; t++) {
                /* β negated is the convention flip itself: d(-β) = S d(β) S with
                 * S = (-1)^m, and S commutes with the z rotations (see README) */
                if (t == T_BETA) continue;
                int n_ok = 0, n_seen = 0;
                for (int k = 0; k < fx.ncases; k++) {
                    const fx_case *c = &fx.cases[k];
                    int at;
                    if (transformed((transform)t, c, y, tmp)) continue;
                    /* a transformation that changes nothing (β = 0, say) proves nothing */
                    if (max_err(y, c->expected, c->n, &at) <= c->tol_float) continue;
                    n_seen++;
                    if (max_err(got[k], y, c->n, &at) <= c->tol_float) n_ok++;
                    cli_progress_step(&prog, t * fx.ncases + k + 1, T_COUNT * fx.ncases,
                                      "cases tried under the known mistakes (--diagnose)");
                }
                /* the transformation must explain every case it changes */
                if (n_ok > best_n && n_ok == n_seen) { best_n = n_ok; best = t; best_seen = n_seen; }
            }
            free(y);
            if (best >= 0) cause = t_name[best];
        }
        root = cli_put(root, "diagnosis", json_string(cause ? cause : "no known transformation explains the mismatch"));
        root = cli_put(root, "diagnosis_matches", json_integer(best_n));
        root = cli_put(root, "diagnosis_checked", json_integer(best_seen));
        root = cli_put(root, "diagnosis_tolerance", json_string("float32"));
        /* "failed" counts cases beyond the tolerance_kind tolerance (double:
         * 1e-13); the diagnosis compares at the float32 tolerance, so the two
         * counts differ: say what each one counts */
        fprintf(stderr,
                "verify: failed counts the cases beyond their %s tolerance; the diagnosis compares at "
                "each case's float32 tolerance: diagnosis_checked = the %d cases the mistake changes "
                "by more than that, diagnosis_matches = the %d of them the candidate equals (%d of the "
                "%d failed cases are within their float32 tolerance: too close to tell)\n",
                prec == SH_PREC_FLOAT ? "float32" : "double", best_seen, best_n, failed_near, failed);
    }
    if (failed) fprintf(stderr, "verify: %d of %d cases exceed the %s tolerance; worst: case %s, index %d%s\n",
                        failed, fx.ncases, prec == SH_PREC_FLOAT ? "float32" : "double", wc->id, worst_i,
                        simulate >= 0 ? " (the simulated mistake, as asked)" : "");
    rc = cli_emit(root, com.fmt);
    /* --simulate asks for a wrong kernel's outputs: they are meant to fail,
     * and the command succeeded once the candidate file is written */
    if (rc == 0 && failed && simulate < 0) rc = CLI_EXIT_CHECK;
    (void)fail_double;
done:
    if (got)
        for (int k = 0; k < fx.ncases; k++) free(got[k]);
    free(got);
    free(tmp);
    fx_free(&fx);
    return rc;
}

const cli_command cmd_verify = {"verify", run,
                                "check a kernel's rotated coefficients against golden fixtures",
                                help, NULL};
