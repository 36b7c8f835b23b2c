/* cmd_verify.c — `shlab verify`: check a kernel against golden rotation
 * fixtures — its outputs in a candidate file, the kernel itself as a plug-in
 * (shlab/kernel.h, run in a child process), or one of shlab's own methods —
 * and with --diagnose name the likely cause of a mismatch.  The verdict and
 * the diagnosis are the library's (shlab/verify.h). */
#include "cli.h"
#include "core/shlab_internal.h"
#include "lab/lab.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* --simulate's names: the known mistakes (sh_mistake's order), then float
 * precision only and none. */
static const char *const t_short[] = {"convention", "inverse", "swap", "beta", "deg2rad", "rad2deg", "mdesc",
                                      "mdesc-out", "mdesc-in", "float", "none", NULL};
#define SIM_FLOAT SH_MISTAKE_COUNT
#define SIM_NONE (SH_MISTAKE_COUNT + 1)

/* {"results": {"<id>": [...], ...}}, one case per line, into the temporary
 * file of the output (cli_out_open; cli_emit renames it onto `path`). */
static int write_candidate(const char *tmp, const char *path, const sh_fixture *fx, double **got,
                           const unsigned char *not_run)
{
    FILE *f = sh__temp_fopen(tmp, "w");
    int bad = !f, first = 1;
    if (f) {
        fputs("{\"results\":{\n", f);
        for (int k = 0; k < fx->ncases && !bad; k++) {
            if (not_run[k]) continue;
            json_t *id = json_string(fx->cases[k].id);
            json_t *a = cli_json_array(got[k], (size_t)fx->cases[k].n);
            char *si = id ? json_dumps(id, JSON_ENCODE_ANY) : NULL;
            char *s = a ? json_dumps(a, JSON_COMPACT | JSON_REAL_PRECISION(17)) : NULL;
            if (!s || !si) bad = 1;
            else fprintf(f, "%s%s:%s", first ? "" : ",\n", si, s);
            first = 0;
            free(s);
            free(si);
            json_decref(a);
            json_decref(id);
        }
        fputs("\n}}\n", f);
        bad |= ferror(f) != 0;
        bad |= fclose(f) != 0;
    }
    return bad ? cli_fail("verify: cannot write candidate '%s'", path) : 0;
}


typedef struct {
    const char *fixture, *cand, *emit, *plugin, *shader, *entry, *defines, *abi_s, *orders, *cases;
    sh_rot_method method; /* SH_ROT_AUTO: none (a --candidate or --plugin is verified) */
    sh_precision prec;
    sh_rot_kernel kernel;
    int abi, conv, device, device_given;
    double timeout;
    int diagnose, simulate, matrix_input, quiet, fmt;
} verify_args;

/* {.needs}: an option that applies only with another one */
#define NEEDS_FLAG(F, NAME, NEEDS, HELP)                                                           \
    {.type = CLI_T_FLAG, .name = NAME, .off = offsetof(verify_args, F), .help = HELP, .needs = NEEDS}


static const cli_opt verify_opts[] = {
    CLI_STRING(verify_args, fixture, "fixture", "F", "a fixture file (data/fixtures/rotation/*.json)"),
    CLI_STRING(verify_args, cand, "candidate", "C",
               "JSON {\"results\": {\"<case id>\": [outputs...], ...}}\n"
               "from the kernel under test (every case id of F that\n"
               "is run: see --orders, --cases)"),
    CLI_STRING(verify_args, plugin, "plugin", "LIB.so:SYMBOL",
               "the kernel itself: a function in a shared library\n"
               "(shlab/kernel.h), run on every case in a child\n"
               "process with a time limit and guarded buffers"),
    CLI_STRING(verify_args, shader, "shader", "FILE",
               "a compute shader (.glsl, .comp, .hlsl or .spv) under\n"
               "the convention of docs/check-your-kernel.md, run on\n"
               "a Vulkan device (lavapipe without a GPU), float32"),
    CLI_CUSTOM(verify_args, method, "method", "M", cli_parse_method, NULL,
               "instead of a candidate, run shlab's method M"),
    CLI_CUSTOM(verify_args, prec, "precision", "P", cli_parse_precision, "double",
               "double (default; with a -f plug-in ABI: float) |\n"
               "float: the tolerance (and, with --method, the\narithmetic) to use"),
    CLI_STRING(verify_args, orders, "orders", "LIST",
               "run only the cases of these orders, e.g. 1-6 or 1,2,4\n"
               "(the rest are reported as not run)"),
    CLI_STRING(verify_args, cases, "cases", "IDS", "run only these case ids, comma-separated"),
    {.type = CLI_T_CHOICE, .name = "convention", .meta = "cs|nocs", .off = offsetof(verify_args, conv),
     .choices = cli_convention_names, .def = "cs", .flags = CLI_NO_DEFAULT,
     .help = "run only the cases in this phase convention (the\n"
             "kernel's); default: every case, and with --plugin cs"},
    CLI_FLAG(verify_args, quiet, "quiet", "no progress on stderr"),
    CLI_FLAG(verify_args, diagnose, "diagnose",
             "on failure, test what the kernel matches instead:\n"
             "the other CS-phase convention, the inverse (frame)\n"
             "rotation, α and γ swapped, β negated, degrees taken as\n"
             "radians (or the reverse), m-descending order within a\n"
             "band, or float precision only"),
    CLI_FORMAT(verify_args, fmt),
    CLI_HEADING("Plug-in (--plugin) and shader (--shader):"),
    {.type = CLI_T_STRING, .name = "abi", .meta = "NAME", .off = offsetof(verify_args, abi_s),
     .help = "the kernel's type (required): a plug-in's function\n"
             "(shlab/kernel.h) matrix-d | matrix-f | quat-d | quat-f\n"
             "| euler-d | euler-f | matrix-batch-d | matrix-batch-f;\n"
             "a shader's rotation input matrix | quat | euler"},
    CLI_STRING(verify_args, entry, "entry", "NAME", "a shader's entry point (default main)"),
    CLI_STRING(verify_args, defines, "define", "NAME[=V],...", "a shader's preprocessor macros"),
    CLI_INT(verify_args, device, "device", "N", 0, 64, NULL,
            "the Vulkan device for a shader (default: the first\nGPU, else the first device)"),
    {.type = CLI_T_REAL, .name = "timeout", .meta = "S", .off = offsetof(verify_args, timeout), .lo = 0.1,
     .hi = 3600, .def = "10",
     .help = "seconds a plug-in may take over all cases, or a\n"
             "shader over one dispatch (then it is stopped and\nreported)"},
    CLI_HEADING("Method (--method):"),
    {.type = CLI_T_CUSTOM, .name = "kernel", .meta = "K", .off = offsetof(verify_args, kernel),
     .parse = cli_parse_kernel, .def = "auto", .needs = "method",
     .help = "with --method: auto (default) | scalar | unrolled |\n"
             "sse2 | avx2 | avx512, the code that runs (the fixture's\n"
             "Euler angles reach the plan as angles; --matrix-input:\n"
             "as the case's matrix, sh_rot_plan_set_matrix)"},
    NEEDS_FLAG(matrix_input, "matrix-input", "method", "with --method: give each case's rotation as its matrix"),
    {.type = CLI_T_STRING, .name = "emit-candidate", .meta = "F", .off = offsetof(verify_args, emit),
     .help = "with --method or --plugin: also write the outputs of\n"
             "the cases run as a candidate file (the format a\n"
             "kernel under test must produce)"},
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
    .usage = "verify --fixture F (--candidate C | --plugin LIB.so:SYMBOL --abi NAME |\n"
             "       --shader FILE --abi matrix|quat|euler | --method M) [OPTIONS]",
    .about = "Compare rotated coefficients with a golden fixture file (shlab fixtures).\n"
             "A case passes if every |output_i - expected_i| <= the case's double\n"
             "tolerance (--precision float: its float32 tolerance).  Exit 0 if all cases\n"
             "run pass, 1 if any fails or the plug-in or shader crashed, hung or wrote\n"
             "out of bounds (the reason is printed), 2 on bad input (a shader that does\n"
             "not compile, no Vulkan device).\n",
    .opts = verify_opts,
    .notes =
        "JSON: {\"fixture\",\"source\",\"tolerance_kind\",\"cases\",\"failed\",\"pass\",\n"
        "       \"worst_id\",\"worst_index\",\"worst_got\",\"worst_expected\",\"worst_error\",\n"
        "       \"worst_tolerance\",\"convention\" (cs, nocs, or cs+nocs when the cases run\n"
        "       mix both),[\"method\" (with --method)],[\"kernel\"],[\"input\"],\n"
        "       [\"simulated\" (with --simulate)],[\"skipped\",\"skipped_why\"],\n"
        "       [\"abi\",\"kernel_failure\",\"kernel_errors\" (with --plugin, --shader)],\n"
        "       [\"device\",\"driver\" (with --shader)],\n"
        "       [\"diagnosis\",\"diagnosis_matches\",\"diagnosis_checked\",\"diagnosis_tolerance\"]}\n"
        "\"failed\" counts the cases beyond the tolerance of tolerance_kind (double: 1e-13).\n"
        "\"skipped\" (when non-zero): the cases not run, neither rotated nor judged, and\n"
        "\"skipped_why\" the reasons: not asked for (--orders, --cases), above the\n"
        "method's largest order (direct: 3), in the other convention than the plug-in's,\n"
        "declined by the plug-in (it returned SHLAB_KERNEL_UNSUPPORTED), or not reached\n"
        "(the plug-in stopped before them: kernel_failure says why); \"cases\" counts them too.\n"
        "The diagnosis compares at each case's float32 tolerance (1e-6 and more), so its\n"
        "counts are not comparable with \"failed\": diagnosis_checked = the cases the\n"
        "mistake changes by more than their float32 tolerance (a mistake that changes a\n"
        "case less, at β ≈ 0 say, proves nothing there), diagnosis_matches = those of\n"
        "them the candidate equals within it; a diagnosis must explain all it checks.\n",
};

/* Why a case was not run (the bits of verify_work.skip). */
enum { SKIP_ASKED = 1, SKIP_ORDER = 2, SKIP_CONV = 4, SKIP_DECLINED = 8, SKIP_UNREACHED = 16 };
static const char *const skip_why[] = {"not asked for", "above the method's order", "other convention",
                                       "declined by the kernel", "not reached"};

/* The fixture, the outputs under test (got[k]: case k's n values), which
 * cases were not run (skip[k]: SKIP_* bits; run[k]: skip[k] == 0 as the
 * library takes it) and the plug-in's report. */
typedef struct {
    sh_fixture fx;
    double **got;
    unsigned char *skip, *not_run;
    int nskip;
    sh_plugin_report prep;
    char device[256], driver[256]; /* --shader: where it ran */
    cli_progress prog;
} verify_work;

static void work_free(verify_work *w)
{
    if (w->got)
        for (int k = 0; k < w->fx.ncases; k++) free(w->got[k]);
    free(w->got);
    free(w->skip);
    free(w->not_run);
    sh_fixture_free(&w->fx);
}

/* "1-6", "1,2,4", "2-3,7": order o in the list? */
static int parse_orders(const char *s, unsigned char *want /* [1002] */)
{
    memset(want, 0, 1002);
    const char *p = s;
    while (*p) {
        char *e;
        long lo = strtol(p, &e, 10), hi = lo;
        if (e == p || lo < 1 || lo > 1001) return cli_fail("verify: --orders '%s': expected orders 1..1001 like 1-6 or 1,2,4", s);
        p = e;
        if (*p == '-') {
            hi = strtol(p + 1, &e, 10);
            if (e == p + 1 || hi < lo || hi > 1001) return cli_fail("verify: --orders '%s': expected orders 1..1001 like 1-6 or 1,2,4", s);
            p = e;
        }
        for (long o = lo; o <= hi; o++) want[o] = 1;
        if (*p == ',') p++;
        else if (*p) return cli_fail("verify: --orders '%s': expected orders 1..1001 like 1-6 or 1,2,4", s);
    }
    return 0;
}

/* Is id one of the comma-separated ids? */
static int in_list(const char *list, const char *id)
{
    const size_t n = strlen(id);
    for (const char *p = list; p && *p;) {
        const char *e = strchr(p, ',');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && !strncmp(p, id, n)) return 1;
        p = e ? e + 1 : NULL;
    }
    return 0;
}

/* The cases asked for (--orders, --cases): the others get SKIP_ASKED; every
 * id of --cases must exist. */
static int select_cases(const verify_args *a, verify_work *w)
{
    unsigned char want[1002];
    if (a->orders && parse_orders(a->orders, want)) return CLI_EXIT_USAGE;
    for (const char *p = a->cases; p && *p;) {
        const char *e = strchr(p, ',');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        int found = 0;
        for (int k = 0; k < w->fx.ncases && !found; k++)
            found = strlen(w->fx.cases[k].id) == len && !strncmp(w->fx.cases[k].id, p, len);
        if (!found) return cli_fail("verify: --cases: no case '%.*s' in fixture '%s'", (int)len, p, a->fixture);
        p = e ? e + 1 : NULL;
    }
    for (int k = 0; k < w->fx.ncases; k++) {
        const sh_fixture_case *c = &w->fx.cases[k];
        if ((a->orders && !want[c->order]) || (a->cases && !in_list(a->cases, c->id))) w->skip[k] |= SKIP_ASKED;
        else if (a->conv >= 0 && (int)c->conv != a->conv) w->skip[k] |= SKIP_CONV;
    }
    return 0;
}

static int work_load(const verify_args *a, verify_work *w)
{
    memset(w, 0, sizeof *w);
    /* inputs are registered: no output may overwrite them */
    if (cli_input("fixture", a->fixture) || (a->cand && cli_input("candidate", a->cand))) return CLI_EXIT_USAGE;
    if (sh_fixture_load(a->fixture, &w->fx)) return cli_fail_status(SH_EFORMAT);
    const size_t nc = (size_t)w->fx.ncases;
    w->got = calloc(nc + 1, sizeof *w->got);
    w->skip = calloc(nc + 1, 1);
    w->not_run = calloc(nc + 1, 1);
    int ok = w->got && w->skip && w->not_run;
    for (size_t k = 0; ok && k < nc; k++) ok = (w->got[k] = malloc((size_t)w->fx.cases[k].n * sizeof **w->got)) != NULL;
    if (!ok) return cli_fail("out of memory");
    return select_cases(a, w);
}

/* Count the cases not run, refuse a run with none left, and fill not_run
 * (the library's skip). */
static int count_skipped(const verify_args *a, verify_work *w, const char *what)
{
    w->nskip = 0;
    for (int k = 0; k < w->fx.ncases; k++) {
        w->not_run[k] = w->skip[k] != 0;
        w->nskip += w->not_run[k];
    }
    if (w->nskip == w->fx.ncases && !w->prep.failed)
        return cli_fail("verify: no case of fixture '%s' is run (%s)", a->fixture, what);
    return 0;
}

/* Every case rotated by shlab's method (or as the simulated mistake does it).
 * Cases above the method's largest order (direct: 3) are skipped, and said
 * so (stderr and "skipped"). */
static int run_method(const verify_args *a, verify_work *w)
{
    const sh_rot_method m = a->method;
    const int top = sh_rot_method_max_order(m);
    int above = 0, st = 0;
    for (int k = 0; k < w->fx.ncases; k++)
        if (w->fx.cases[k].order > top && !w->skip[k]) w->skip[k] |= SKIP_ORDER, above++;
    if (above && a->emit)
        return cli_fail("verify: method %s is limited to order %d: %d cases would be missing from "
                        "--emit-candidate", sh_rot_method_name(m), top, above);
    char why[96];
    snprintf(why, sizeof why, "method %s is limited to order %d", sh_rot_method_name(m), top);
    if (count_skipped(a, w, above ? why : "--orders, --cases")) return CLI_EXIT_USAGE;
    if (above)
        fprintf(stderr, "verify: method %s is limited to order %d: %d of the %d cases skipped (higher orders)\n",
                sh_rot_method_name(m), top, above, w->fx.ncases);
    for (int k = 0; k < w->fx.ncases && !st; k++) {
        const sh_fixture_case *c = &w->fx.cases[k];
        if (w->skip[k]) continue;
        if (m == SH_ROT_Z && c->rot.beta != 0)
            return cli_fail("verify: method z rotates about z only; case '%s' has β = %.3g rad", c->id, c->rot.beta);
        if (a->simulate < SH_MISTAKE_COUNT)
            st = sh_fixture_simulate((sh_mistake)a->simulate, c, w->got[k]);
        else
            st = sh_fixture_apply(m, a->simulate == SIM_FLOAT ? SH_PREC_FLOAT : a->prec, a->kernel, a->matrix_input, c,
                                  &c->rot, c->conv, c->input, w->got[k]);
        cli_progress_step(&w->prog, k + 1, w->fx.ncases, "cases rotated");
    }
    return st ? cli_fail("verify: %s", sh_last_error()) : 0;
}

/* Every case asked for, in the plug-in's convention, through the user's
 * kernel in a child process; what it declined or never reached is not run. */
static int run_plugin(const verify_args *a, verify_work *w)
{
    sh_plugin p;
    if (sh_plugin_parse(a->plugin, (sh_plugin_abi)a->abi, &p)) return cli_fail_status(SH_EINVAL);
    p.timeout_s = a->timeout;
    if (count_skipped(a, w, "--convention, --orders, --cases")) return CLI_EXIT_USAGE;
    unsigned char *status = calloc((size_t)w->fx.ncases + 1, 1);
    if (!status) return cli_fail("out of memory");
    int st = sh_plugin_run_fixture(&p, &w->fx, w->not_run, w->got, status, &w->prep);
    for (int k = 0; !st && k < w->fx.ncases; k++) {
        if (w->skip[k]) continue;
        if (status[k] == SH_PLUGIN_CASE_DECLINED) w->skip[k] |= SKIP_DECLINED;
        if (status[k] == SH_PLUGIN_CASE_NOT_RUN) w->skip[k] |= SKIP_UNREACHED;
    }
    free(status);
    if (st) return cli_fail_status(st);
    if (w->prep.open_failed) return cli_fail("verify: %s", w->prep.failure);
    for (int k = 0; k < w->fx.ncases; k++) w->not_run[k] = w->skip[k] != 0;
    w->nskip = 0;
    for (int k = 0; k < w->fx.ncases; k++) w->nskip += w->not_run[k];
    if (w->nskip == w->fx.ncases && !w->prep.failed)
        return cli_fail("verify: the kernel declined every case it was given (SHLAB_KERNEL_UNSUPPORTED)");
    return 0;
}

/* Every case asked for, in the shader's convention, one dispatch per order
 * on the Vulkan device, in a child process. */
static int run_shader(const verify_args *a, verify_work *w)
{
    sh_shader s;
    if (cli_input("shader", a->shader)) return CLI_EXIT_USAGE;
    sh_shader_form form;
    if (sh_shader_form_parse(a->abi_s, &form)) return cli_fail("verify: --abi: %s", sh_last_error());
    if (sh_shader_load(a->shader, a->entry, a->defines, &s)) return cli_fail_status(SH_EFORMAT);
    s.form = form;
    s.device = a->device_given ? a->device : -1;
    s.timeout_s = a->timeout;
    int rc = count_skipped(a, w, "--convention, --orders, --cases");
    unsigned char *status = rc ? NULL : calloc((size_t)w->fx.ncases + 1, 1);
    if (!rc && !status) rc = cli_fail("out of memory");
    sh_shader_report rep;
    if (!rc && sh_shader_run_fixture(&s, &w->fx, w->not_run, w->got, status, &rep)) rc = cli_fail_status(SH_EIO);
    sh_shader_free(&s);
    if (!rc) {
        w->prep = rep.cases;
        snprintf(w->device, sizeof w->device, "%s", rep.device);
        snprintf(w->driver, sizeof w->driver, "%s", rep.driver);
        for (int k = 0; k < w->fx.ncases; k++) {
            if (w->skip[k]) continue;
            if (status[k] == SH_PLUGIN_CASE_DECLINED) w->skip[k] |= SKIP_DECLINED;
            if (status[k] == SH_PLUGIN_CASE_NOT_RUN) w->skip[k] |= SKIP_UNREACHED;
        }
        w->nskip = 0;
        for (int k = 0; k < w->fx.ncases; k++) w->nskip += (w->not_run[k] = w->skip[k] != 0);
        /* no device, a pipeline the driver refuses: bad input, as a plug-in that does not load */
        if (w->prep.open_failed) rc = cli_fail("verify: %s", w->prep.failure);
        else if (w->nskip == w->fx.ncases && !w->prep.failed)
            rc = cli_fail("verify: the shader declined every case it was given (status 1)");
    }
    free(status);
    return rc;
}

static void put_skipped(const verify_work *w, json_t **root)
{
    if (!w->nskip) return;
    char why[200] = "";
    for (int b = 0; b < 5; b++) {
        int n = 0;
        for (int k = 0; k < w->fx.ncases; k++) n += (w->skip[k] & (1 << b)) != 0;
        if (n)
            snprintf(why + strlen(why), sizeof why - strlen(why), "%s%d %s", *why ? ", " : "", n, skip_why[b]);
    }
    *root = cli_put(*root, "skipped", json_integer(w->nskip));
    *root = cli_put(*root, "skipped_why", json_string(why));
}

static json_t *result(const verify_args *a, int have_kernel, const verify_work *w, const sh_verdict *v)
{
    const int have_method = a->method != SH_ROT_AUTO, fl = a->prec == SH_PREC_FLOAT;
    json_t *root = json_object();
    root = cli_put(root, "fixture", json_string(a->fixture));
    root = cli_put(root, "source", json_string(a->cand     ? a->cand
                                               : a->plugin ? a->plugin
                                               : a->shader ? a->shader
                                                           : sh_rot_method_name(a->method)));
    root = cli_put(root, "tolerance_kind", json_string(fl ? "float32" : "double"));
    root = cli_put(root, "cases", json_integer(w->fx.ncases));
    root = cli_put(root, "failed", json_integer(v->failed));
    root = cli_put(root, "pass", json_boolean(v->failed == 0 && !w->prep.failed));
    if (v->worst_case >= 0) {
        const sh_fixture_case *wc = &w->fx.cases[v->worst_case];
        const double wg = w->got[v->worst_case][v->worst_index];
        root = cli_put(root, "worst_id", json_string(wc->id));
        root = cli_put(root, "worst_index", json_integer(v->worst_index));
        root = cli_put(root, "worst_got", isfinite(wg) ? json_real(wg) : json_string("not finite"));
        root = cli_put(root, "worst_expected", json_real(wc->expected[v->worst_index]));
        root = cli_put(root, "worst_error", isfinite(v->worst_error) ? json_real(v->worst_error) : json_string("not finite"));
        root = cli_put(root, "worst_tolerance", json_real(v->worst_tolerance));
    }
    /* after the fields above, so that their CSV columns keep their places */
    int have_cs = 0, have_nocs = 0;
    for (int k = 0; k < w->fx.ncases; k++) {
        if (w->not_run[k]) continue;
        have_cs |= w->fx.cases[k].conv == SH_CS;
        have_nocs |= w->fx.cases[k].conv == SH_NOCS;
    }
    root = cli_put(root, "convention", json_string(have_cs && have_nocs ? "cs+nocs" : have_nocs ? "nocs" : "cs"));
    if (have_method) root = cli_put(root, "method", json_string(sh_rot_method_name(a->method)));
    if (a->simulate != SIM_NONE) root = cli_put(root, "simulated", json_string(t_short[a->simulate]));
    if (have_kernel) root = cli_put(root, "kernel", json_string(sh_rot_kernel_name(a->kernel)));
    if (a->matrix_input) root = cli_put(root, "input", json_string("matrix"));
    put_skipped(w, &root);
    if (a->plugin || a->shader) {
        root = cli_put(root, "abi", json_string(a->abi_s));
        root = cli_put(root, "kernel_failure", w->prep.failed ? json_string(w->prep.failure) : json_null());
        root = cli_put(root, "kernel_errors", json_integer(w->prep.errors));
    }
    if (a->shader) {
        root = cli_put(root, "device", json_string(w->device));
        root = cli_put(root, "driver", json_string(w->driver));
    }
    return root;
}

static void diag_progress(void *ctx, long done, long total)
{
    cli_progress_step(ctx, (int)done, (int)total, "cases tried under the known mistakes (--diagnose)");
}

/* --diagnose on a failure: the likely cause, into root, and one line on
 * stderr saying what its counts count. */
static int diagnose(const verify_args *a, verify_work *w, const sh_verdict *v, json_t **root)
{
    sh_diagnosis d;
    if (sh_verify_diagnose(&w->fx, w->not_run, w->got, a->prec, diag_progress, &w->prog, &d))
        return cli_fail_status(SH_ENOMEM);
    *root = cli_put(*root, "diagnosis", json_string(d.cause));
    *root = cli_put(*root, "diagnosis_matches", json_integer(d.matches));
    *root = cli_put(*root, "diagnosis_checked", json_integer(d.checked));
    *root = cli_put(*root, "diagnosis_tolerance", json_string("float32"));
    /* "failed" counts cases beyond the tolerance_kind tolerance (double:
     * 1e-13); the diagnosis compares at the float32 tolerance, so the two
     * counts differ: say what each one counts */
    fprintf(stderr,
            "verify: failed counts the cases beyond their %s tolerance; the diagnosis compares at "
            "each case's float32 tolerance: diagnosis_checked = the %d cases the mistake changes "
            "by more than that, diagnosis_matches = the %d of them the outputs equal (%d of the "
            "%d failed cases are within their float32 tolerance: too close to tell)\n",
            a->prec == SH_PREC_FLOAT ? "float32" : "double", d.checked, d.matches, v->failed_near, v->failed);
    return 0;
}

/* The outputs under test: the candidate's, the plug-in's, or shlab's
 * method's (and then the candidate file it writes with --emit-candidate). */
static int outputs(const verify_args *a, const char *emit_tmp, verify_work *w)
{
    if (a->plugin || a->shader) {
        int rc = a->plugin ? run_plugin(a, w) : run_shader(a, w);
        /* a candidate file holds numbers: refuse what JSON cannot carry */
        for (int k = 0; !rc && a->emit && k < w->fx.ncases; k++)
            for (int i = 0; !rc && !w->not_run[k] && i < w->fx.cases[k].n; i++)
                if (!isfinite(w->got[k][i]))
                    rc = cli_fail("verify: case '%s' has non-finite outputs (the kernel failed there): not "
                                  "written to --emit-candidate, which holds numbers only", w->fx.cases[k].id);
        return !rc && a->emit ? write_candidate(emit_tmp, a->emit, &w->fx, w->got, w->not_run) : rc;
    }
    if (a->cand) {
        if (count_skipped(a, w, "--orders, --cases")) return CLI_EXIT_USAGE;
        /* the cases asked for must be there; the others may be */
        unsigned char *want = malloc((size_t)w->fx.ncases + 1);
        if (!want) return cli_fail("out of memory");
        for (int k = 0; k < w->fx.ncases; k++) want[k] = !w->not_run[k];
        const int st = sh_fixture_load_candidate(a->cand, &w->fx, want, w->got, NULL);
        free(want);
        return st ? cli_fail_status(SH_EFORMAT) : 0;
    }
    int rc = run_method(a, w);
    if (!rc && a->emit) rc = write_candidate(emit_tmp, a->emit, &w->fx, w->got, w->not_run);
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
    if ((a.cand != NULL) + (a.plugin != NULL) + (a.shader != NULL) + (a.method != SH_ROT_AUTO) != 1)
        return cli_fail("verify: give exactly one of --candidate, --plugin, --shader and --method");
    if ((a.plugin || a.shader) && !a.abi_s)
        return cli_fail("verify: %s needs --abi NAME (the kernel's type: docs/check-your-kernel.md)",
                        a.plugin ? "--plugin" : "--shader");
    if (a.abi_s && !a.plugin && !a.shader) return cli_fail("verify: --abi applies to --plugin and --shader");
    if (!a.shader && (a.entry || a.defines || cli_given(&seen, "device")))
        return cli_fail("verify: --entry, --define and --device apply to --shader");
    if (!a.plugin && !a.shader && cli_given(&seen, "timeout"))
        return cli_fail("verify: --timeout applies to --plugin and --shader");
    a.device_given = cli_given(&seen, "device");
    if (a.plugin) {
        sh_plugin_abi abi;
        if (sh_plugin_abi_parse(a.abi_s, &abi)) return cli_fail("verify: --abi: %s", sh_last_error());
        a.abi = (int)abi;
        if (!cli_given(&seen, "precision")) a.prec = sh_plugin_abi_precision(abi);
    }
    if (a.shader && !cli_given(&seen, "precision")) a.prec = SH_PREC_FLOAT; /* shaders compute in float32 */
    /* not given: every case, but a plug-in has one convention (cs) */
    if (!cli_given(&seen, "convention")) a.conv = a.plugin || a.shader ? SH_CS : -1;
    if (a.emit && !a.plugin && !a.shader && a.method == SH_ROT_AUTO)
        return cli_fail("verify: --emit-candidate needs --method, --plugin or --shader");
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
    sh_verdict v;
    sh_verify_judge(&w.fx, w.not_run, w.got, a.prec, &v);
    json_t *root = result(&a, cli_given(&seen, "kernel"), &w, &v);
    if (a.diagnose && v.failed && (rc = diagnose(&a, &w, &v, &root))) {
        json_decref(root);
        work_free(&w);
        return rc;
    }
    const int simulated = a.simulate != SIM_NONE;
    if (w.prep.failed) fprintf(stderr, "verify: %s\n", w.prep.failure);
    if (w.prep.errors)
        fprintf(stderr, "verify: the kernel returned a failure code (not SHLAB_KERNEL_OK or _UNSUPPORTED; a "
                        "shader's status other than 0 or 1) on %d cases: they fail\n", w.prep.errors);
    if (v.failed)
        fprintf(stderr, "verify: %d of %d cases exceed the %s tolerance; worst: case %s, index %d%s\n", v.failed, v.run,
                a.prec == SH_PREC_FLOAT ? "float32" : "double", w.fx.cases[v.worst_case].id, v.worst_index,
                simulated ? " (the simulated mistake, as asked)" : "");
    if (w.nskip && !a.quiet && (a.cand || a.plugin || a.shader))
        fprintf(stderr, "verify: %d of the %d cases not run\n", w.nskip, w.fx.ncases);
    work_free(&w);
    rc = cli_emit(root, (cli_format)a.fmt);
    /* --simulate asks for a wrong kernel's outputs: they are meant to fail,
     * and the command succeeded once the candidate file is written */
    return rc == 0 && (v.failed || w.prep.failed) && !simulated ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_verify = {"verify", run, "check a kernel's rotated coefficients against golden fixtures", &verify_decl};
