/* cmd_bench_plugin.c — `shlab bench --plugin LIB.so:SYMBOL --abi NAME`: a
 * user's kernel (shlab/kernel.h) placed on the cost/error frontier.  At
 * each order: its error on the golden fixture's cases, the method the model
 * would run for that error on the same path (sh_rot_choose), and the two
 * timed interleaved in a child process (sh_plugin_bench) with paired
 * ratios and the noise rule. */
#include "cli.h"
#include "lab/lab.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ORDERS 16

typedef struct {
    const char *plugin, *fixture, *methods_s, *abi_s;
    int conv, batch, repeat, quiet, fmt;
    double target_ms, timeout;
    struct { int n, v[MAX_ORDERS]; } orders;
} plug_args;

static int parse_orders(const char *opt, const char *s, void *field)
{
    plug_args *a = (plug_args *)((char *)field - offsetof(plug_args, orders));
    a->orders.n = 0;
    for (const char *p = s; *p;) {
        char *e;
        const long o = strtol(p, &e, 10);
        if (e == p || o < 1 || o > 64 || a->orders.n == MAX_ORDERS)
            return cli_fail("%s: expected up to %d orders in 1..64, comma separated, not '%s'", opt, MAX_ORDERS, s);
        a->orders.v[a->orders.n++] = (int)o;
        p = *e == ',' ? e + 1 : e;
        if (*e && *e != ',') return cli_fail("%s: expected orders like 2,4,6, not '%s'", opt, s);
    }
    return a->orders.n ? 0 : cli_fail("%s: empty", opt);
}


static const cli_opt plug_opts[] = {
    CLI_STRING(plug_args, plugin, "plugin", "LIB.so:SYMBOL", "the kernel (shlab/kernel.h)"),
    CLI_STRING(plug_args, abi_s, "abi", "NAME",
               "its type: matrix-d | matrix-f | quat-d | quat-f |\n"
               "euler-d | euler-f | matrix-batch-d | matrix-batch-f\n(required)"),
    CLI_CUSTOM(plug_args, orders, "order", "LIST", parse_orders, "2,4,6,8,10",
               "orders to time (each must have cases in the fixture)"),
    CLI_STRING(plug_args, fixture, "fixture", "F",
               "the golden cases that measure its error (default\n"
               "data/fixtures/rotation/orders_1_10.json)"),
    CLI_CONVENTION(plug_args, conv),
    CLI_STRING(plug_args, methods_s, "methods", "LIST",
               "shlab methods to time beside it, besides the model's\nchoice (comma separated, at most 3)"),
    CLI_INT(plug_args, batch, "batch", "B", 1, 4096, "16", "rotations per call of a batch ABI"),
    CLI_INT(plug_args, repeat, "repeat", "R", 3, 1000, "15", "timed rounds"),
    CLI_REAL(plug_args, target_ms, "target-ms", "T", 0, 10000, CLI_LO_OPEN, "5", "shortest sample"),
    CLI_REAL(plug_args, timeout, "timeout", "S", 0.1, 3600, 0, "60",
             "seconds the kernel may take per order (and over\nthe fixture), then it is stopped and reported"),
    CLI_FLAG(plug_args, quiet, "quiet", "no progress on stderr"),
    CLI_FORMAT(plug_args, fmt),
    CLI_END,
};

static const cli_cmd plug_decl = {
    .name = "bench --plugin",
    .usage = "bench --plugin LIB.so:SYMBOL --abi NAME [--order LIST] [OPTIONS]",
    .about =
        "Place a kernel of yours on the cost/error frontier.  At each order:\n"
        "  error    its worst error on the fixture's cases of that order, as\n"
        "           max |output_i − expected_i| / ‖input‖₂ (≤ the kernel's own\n"
        "           'coeff' error, the largest error of one coefficient for a\n"
        "           unit-norm input, which `shlab plan --error coeff` budgets);\n"
        "  budget   that error, or the fixture's tolerance of the ABI's precision\n"
        "           if larger (a kernel exact to rounding meets methods exact to it);\n"
        "  choice   the method `shlab plan` runs for the budget on the same path\n"
        "           (the ABI's input: matrix, quaternion or Euler angles, one\n"
        "           rotation per call, or --batch rotations per call for a batch\n"
        "           ABI) and precision, with its model cost and its own error;\n"
        "  timing   the kernel and the choice (and --methods) timed interleaved,\n"
        "           as `shlab bench` times (paired ratio per round, noise rule),\n"
        "           in a child process: a kernel that crashes or hangs is stopped\n"
        "           and reported.\n"
        "ratio = plug-in time / choice time (median over rounds, quartiles):\n"
        "below 1 the kernel is faster than what shlab would run at its accuracy.\n"
        "An Euler ABI gets the angles; shlab's Euler path starts from a matrix and\n"
        "extracts them (bench's setup_ns), as a user holding a frame must.\n",
    .opts = plug_opts,
    .notes = "JSON: {\"plugin\",\"abi\",\"fixture\",\"convention\",\"noisy\",\"noise\",\"rows\":[{\"order\",\n"
             "       \"plugin_error\",\"budget\",\"plugin_ns\",\"plugin_ns_q1\",\"plugin_ns_q3\",\"choice\",\n"
             "       \"choice_error\",\"choice_admissible\",\"choice_model_ns\",\"choice_ns\",\"ratio\",\n"
             "       \"ratio_q1\",\"ratio_q3\",\"verdict\",[\"others\":[{\"method\",\"ns\",\"ratio\"}]]}]}\n",
};

/* worst[o]: the largest max|out − exp| / ‖in‖₂ over the cases of order o
 * that ran (−1: none); tol[o]: the smallest tolerance of those cases in the
 * ABI's precision (what the fixture counts as exact). */
static int fixture_errors(const plug_args *a, const sh_plugin *p, double worst[65], double tol[65])
{
    sh_fixture fx;
    if (cli_input("fixture", a->fixture) || sh_fixture_load(a->fixture, &fx)) return cli_fail_status(SH_EFORMAT);
    double **got = calloc((size_t)fx.ncases, sizeof *got);
    unsigned char *skip = calloc((size_t)fx.ncases, 1), *status = calloc((size_t)fx.ncases, 1);
    int rc = got && skip && status ? 0 : cli_fail("out of memory");
    for (int k = 0; !rc && k < fx.ncases; k++) {
        skip[k] = (int)fx.cases[k].conv != a->conv || fx.cases[k].band >= 0 || fx.cases[k].order > 64;
        if (!(got[k] = malloc((size_t)fx.cases[k].n * sizeof **got))) rc = cli_fail("out of memory");
    }
    sh_plugin_report rep;
    if (!rc && sh_plugin_run_fixture(p, &fx, skip, got, status, &rep)) rc = cli_fail_status(SH_EIO);
    if (!rc && rep.open_failed) rc = cli_fail("bench: %s", rep.failure);
    if (!rc && rep.failed) {
        fprintf(stderr, "bench: %s\n", rep.failure);
        rc = CLI_EXIT_CHECK;
    }
    for (int o = 0; o <= 64; o++) worst[o] = -1, tol[o] = INFINITY;
    const int fl = sh_plugin_abi_precision(p->abi) == SH_PREC_FLOAT;
    for (int k = 0; !rc && k < fx.ncases; k++) {
        const sh_fixture_case *c = &fx.cases[k];
        if (status[k] != SH_PLUGIN_CASE_RAN && status[k] != SH_PLUGIN_CASE_ERROR) continue;
        double e = 0, nrm = 0;
        for (int i = 0; i < c->n; i++) {
            const double d = fabs(got[k][i] - c->expected[i]);
            if (isnan(d)) e = INFINITY; /* a NaN output is the worst */
            else if (d > e) e = d;
            nrm += c->input[i] * c->input[i];
        }
        e /= sqrt(nrm) > 0 ? sqrt(nrm) : 1;
        if (e > worst[c->order]) worst[c->order] = e;
        tol[c->order] = fmin(tol[c->order], fl ? c->tol_float : c->tol_double);
    }
    for (int k = 0; got && k < fx.ncases; k++) free(got[k]);
    free(got), free(skip), free(status);
    sh_fixture_free(&fx);
    return rc;
}

/* The method `shlab plan` runs for error ≤ e at the order on the ABI's path
 * (or, when none reaches e, the most accurate), its error and model cost. */
static int choose(const plug_args *a, sh_precision prec, int order, double e, const sh_rot_path *path,
                  sh_rot_candidate *out, int *admissible)
{
    sh_rot_choose_opts o = {.order = order, .max_beta = M_PI, .tolerance = fmax(e, 1e-300),
                            .measure = SH_MEASURE_COEFF, .lobe_exp = 7, .conv = (sh_convention)a->conv,
                            .beta_step = 0.25 * M_PI / 180, /* `shlab plan`'s defaults: the same answer */
                            .prec = prec};
    sh_rot_candidate cand[SH_ROT_NMETHODS];
    int nc, ch, ru;
    if (sh_rot_choose(&o, path, cand, &nc, &ch, &ru, NULL)) return cli_fail_status(SH_EINVAL);
    if (nc < 1) return cli_fail("bench: no shlab method rotates order %d on this path", order);
    *admissible = ch >= 0;
    *out = cand[ch >= 0 ? ch : 0]; /* the others come sorted by error */
    return 0;
}

static json_t *row_json(int order, double err, double budget, const sh_rot_candidate *ch, int admissible,
                        const sh_plugin_bench_result *r, const sh_rot_method *others, int nothers)
{
    const sh_bench_stats *ps = &r->stats[0], *cs = &r->stats[1];
    const sh_bench_ratio *q = &r->ratio[0];
    const char *verdict = r->noise.noisy           ? "noisy: no verdict"
                          : q->q3 < 1              ? "faster than shlab's choice at its error"
                          : q->q1 > 1              ? "slower than shlab's choice at its error"
                                                   : "as fast as shlab's choice (within the rounds' quartiles)";
    json_t *row = json_object();
    row = cli_put(row, "order", json_integer(order));
    row = cli_put(row, "plugin_error", json_real(err));
    row = cli_put(row, "budget", json_real(budget));
    row = cli_put(row, "plugin_ns", json_real(ps->ns_median));
    row = cli_put(row, "plugin_ns_q1", json_real(ps->ns_q1));
    row = cli_put(row, "plugin_ns_q3", json_real(ps->ns_q3));
    row = cli_put(row, "choice", json_string(sh_rot_method_name(ch->method)));
    row = cli_put(row, "choice_error", json_real(ch->max_error));
    row = cli_put(row, "choice_admissible", json_boolean(admissible));
    row = cli_put(row, "choice_model_ns", json_real(ch->ns_per_rotation));
    row = cli_put(row, "choice_ns", json_real(cs->ns_median));
    row = cli_put(row, "ratio", json_real(q->median));
    row = cli_put(row, "ratio_q1", json_real(q->q1));
    row = cli_put(row, "ratio_q3", json_real(q->q3));
    row = cli_put(row, "verdict", json_string(verdict));
    if (nothers) {
        json_t *arr = json_array();
        for (int i = 0; i < nothers && arr; i++) {
            json_t *x = json_pack("{s:s,s:f,s:f}", "method", sh_rot_method_name(others[i]), "ns",
                                  r->stats[2 + i].ns_median, "ratio", r->ratio[1 + i].median);
            if (!x || json_array_append_new(arr, x)) json_decref(arr), arr = NULL;
        }
        row = cli_put(row, "others", arr);
    }
    return row;
}

/* --methods: up to 3 names. */
static int parse_methods(const char *s, sh_rot_method *m, int *n)
{
    *n = 0;
    char buf[256];
    if (!s) return 0;
    if (strlen(s) >= sizeof buf) return cli_fail("--methods: too long");
    strcpy(buf, s);
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (*n == SH_PLUGIN_BENCH_MAX_METHODS - 1) return cli_fail("--methods: at most %d", SH_PLUGIN_BENCH_MAX_METHODS - 1);
        if (sh_rot_method_parse(t, &m[*n])) return cli_fail("--methods: %s", sh_last_error());
        (*n)++;
    }
    return 0;
}

int cli_bench_plugin(const cli_command *bench, int argc, char **argv)
{
    (void)bench; /* its own declaration: --help here is this comparison's */
    plug_args a = {.fixture = "data/fixtures/rotation/orders_1_10.json"};
    cli_parsed seen;
    int rc = cli_args_parse(&plug_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!a.abi_s) return cli_fail("bench: --plugin needs --abi NAME (the function's type, shlab/kernel.h)");
    sh_plugin_abi abi;
    if (sh_plugin_abi_parse(a.abi_s, &abi)) return cli_fail("bench: --abi: %s", sh_last_error());
    sh_rot_method others[SH_PLUGIN_BENCH_MAX_METHODS];
    int nothers;
    if ((rc = parse_methods(a.methods_s, others, &nothers))) return rc;
    sh_plugin p;
    if (sh_plugin_parse(a.plugin, abi, &p)) return cli_fail_status(SH_EINVAL);
    p.timeout_s = a.timeout;
    const int isbatch = p.abi == SH_PLUGIN_MATRIX_BATCH_D || p.abi == SH_PLUGIN_MATRIX_BATCH_F;
    const sh_rot_path path = {
        .input = p.abi == SH_PLUGIN_QUAT_D || p.abi == SH_PLUGIN_QUAT_F     ? SH_BENCH_INPUT_QUAT
                 : p.abi == SH_PLUGIN_EULER_D || p.abi == SH_PLUGIN_EULER_F ? SH_BENCH_INPUT_EULER
                                                                            : SH_BENCH_INPUT_MATRIX,
        .mode = isbatch ? SH_BENCH_KROT : SH_BENCH_PER_ROTATION,
        .batch = isbatch ? a.batch : 1};
    /* 1. its error at every order, from the fixture (in the child) */
    double worst[65], tol[65];
    if ((rc = fixture_errors(&a, &p, worst, tol))) return rc;
    for (int q = 0; q < a.orders.n; q++)
        if (worst[a.orders.v[q]] < 0)
            return cli_fail("bench: order %d: the kernel ran no case of that order in '%s' (its error is unknown)",
                            a.orders.v[q], a.fixture);
    cli_progress prog;
    cli_progress_start(&prog, "bench", a.quiet);
    json_t *rows = json_array();
    int noisy = 0;
    char why[240] = "";
    for (int q = 0; q < a.orders.n && rows && !rc; q++) {
        const int order = a.orders.v[q];
        /* 2. what shlab would run at that error: a kernel exact to the
         * fixture's tolerance is compared with the cheapest method that is too */
        const double budget = fmax(worst[order], tol[order]);
        sh_rot_candidate ch = {0};
        int adm = 0;
        if ((rc = choose(&a, sh_plugin_abi_precision(abi), order, budget, &path, &ch, &adm))) break;
        /* 3. the two (and --methods) timed interleaved in a child */
        sh_rot_method ms[SH_PLUGIN_BENCH_MAX_METHODS] = {ch.method};
        memcpy(ms + 1, others, (size_t)nothers * sizeof *ms);
        sh_plugin_bench_opts bo = {.order = order, .methods = ms, .nmethods = 1 + nothers, .input = path.input,
                                   .mode = path.mode, .batch = path.batch, .bench = SH_BENCH_OPTS_DEFAULT,
                                   .cfg = SH_BENCH_CFG_DEFAULT};
        bo.bench.conv = (sh_convention)a.conv;
        bo.cfg.samples = a.repeat;
        bo.cfg.min_sample_ms = a.target_ms;
        sh_plugin_bench_result r;
        if (sh_plugin_bench(&p, &bo, &r)) { rc = cli_fail("bench: %s", sh_last_error()); break; }
        if (r.failed) {
            fprintf(stderr, "bench: order %d: %s\n", order, r.failure);
            rc = CLI_EXIT_CHECK;
            break;
        }
        if (r.noise.noisy && !noisy) snprintf(why, sizeof why, "order %d: %.200s", order, r.noise.why);
        noisy |= r.noise.noisy;
        json_t *row = row_json(order, worst[order], budget, &ch, adm, &r, others, nothers);
        if (!row || json_array_append_new(rows, row)) json_decref(rows), rows = NULL;
        cli_progress_step(&prog, q + 1, a.orders.n, "orders timed");
    }
    if (rc) {
        json_decref(rows);
        return rc;
    }
    json_t *root = json_object();
    root = cli_put(root, "plugin", json_string(a.plugin));
    root = cli_put(root, "abi", json_string(sh_plugin_abi_name(abi)));
    root = cli_put(root, "fixture", json_string(a.fixture));
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a.conv)));
    root = cli_put(root, "noisy", json_boolean(noisy));
    root = cli_put(root, "noise", json_string(why));
    root = cli_put(root, "rows", rows);
    if (noisy) cli_warn("bench: noisy run (%s); do not draw conclusions from it", why);
    return cli_emit(root, (cli_format)a.fmt);
}
