/* cmd_bench.c — `shlab bench`: time per rotation of the SH rotation methods
 * (per rotation from a 3×3 matrix, and batched), with the counted
 * multiplications and multiplications per nanosecond.  Timing logic in
 * rotation_bench.c. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_bench;

static const char help[] =
    "Usage: shlab bench [--order LIST] [--methods LIST] [OPTIONS]\n"
    "\n"
    "Time the rotation of one coefficient vector by each method and order.\n"
    "  per-rotation  for every vector a new rotation, given as an orthonormal\n"
    "                3×3 matrix: copy it, extract the ZYZ angles, set the plan,\n"
    "                apply it (what radiance caching does per cache record);\n"
    "  batched       one rotation set, then --batch vectors applied; time per\n"
    "                vector (the set's cost shared among them).\n"
    "A warm-up run, then --repeat timed runs of --count iterations each\n"
    "(CLOCK_MONOTONIC); ns_per_rotation is the median over the runs, ns_min and\n"
    "ns_max the spread.  mults = multiplications counted by the kernels' loops\n"
    "per rotated vector (set + apply, or set/batch + apply); mults_per_ns shows\n"
    "a kernel that is slow for its own arithmetic.  Rotations and vectors are\n"
    "seeded (deterministic); β uniform in [0, --max-beta] (the z method only\n"
    "rotates about z and is timed at β = 0).\n"
    "\n"
    "  --order LIST       orders (comma separated; default 2,4,6,8,10,16)\n"
    "  --methods LIST     z, ivanic, zxzxz, choi, blanco, wigner, reference,\n"
    "                     taylor1, taylor1.5, taylor2, or 'all' (default: every\n"
    "                     method built in except reference, which is MPFR)\n"
    "  --mode M           per-rotation | batched | both (default both)\n"
    "  --precision P      double (default) | float (float plans compute in float;\n"
    "                     vectors cross the API as double)\n"
    "  --count C          iterations per timed run (default 0: calibrated to\n"
    "                     about --target-ms each)\n"
    "  --target-ms T      calibration target per run (default 5)\n"
    "  --repeat R         timed runs (default 11)\n"
    "  --batch B          vectors per rotation in batched mode (default 16)\n"
    "  --max-beta B       largest β of the random rotations (default π)\n"
    "  --degrees          --max-beta in degrees\n"
    "  --seed S           seed of rotations and vectors (default 12345)\n"
    "  --convention C     cs (default) | nocs: convention of the plans timed\n"
    "  --quiet            no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help             this text\n"
    "\n"
    "JSON: {\"convention\",\"repeat\",\"setup_ns\",\"rows\":[{\"method\",\"order\",\"precision\",\"mode\",\n"
    "       \"ns_per_rotation\",\"ns_median\",\"ns_min\",\"ns_max\",\"mults\",\"mults_per_ns\",\n"
    "       \"count\",\"batch\"}]}   (setup_ns: the matrix-to-angles step alone)\n";

static int parse_methods(const char *s, sh_rot_method *ms, int *nm)
{
    *nm = 0;
    if (!strcmp(s, "all")) {
        for (int m = 0; m < SH_ROT_NMETHODS; m++)
            if (sh_rot_method_max_order((sh_rot_method)m) > 0) ms[(*nm)++] = (sh_rot_method)m;
        return 0;
    }
    char *dup = strdup(s);
    if (!dup) return cli_fail("out of memory");
    int rc = 0;
    for (char *save = NULL, *t = strtok_r(dup, ", ", &save); t; t = strtok_r(NULL, ", ", &save)) {
        sh_rot_method m;
        if (sh_rot_method_parse(t, &m)) { rc = cli_fail("--methods: %s", sh_last_error()); break; }
        for (int k = 0; k < *nm; k++)
            if (ms[k] == m) { rc = cli_fail("--methods: '%s' given twice", t); break; }
        if (rc) break;
        if (*nm >= SH_ROT_NMETHODS) { rc = cli_fail("--methods: too many"); break; }
        ms[(*nm)++] = m;
    }
    free(dup);
    if (!rc && *nm == 0) rc = cli_fail("--methods: empty list");
    return rc;
}

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_PRECISION,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPT_CONVENTION,
                                         {"order", required_argument, 0, 'o'},
                                         {"methods", required_argument, 0, 'm'},
                                         {"mode", required_argument, 0, 'M'},
                                         {"count", required_argument, 0, 'c'},
                                         {"target-ms", required_argument, 0, 't'},
                                         {"repeat", required_argument, 0, 'r'},
                                         {"batch", required_argument, 0, 'b'},
                                         {"max-beta", required_argument, 0, 'B'},
                                         {"seed", required_argument, 0, 's'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    sh_precision prec = SH_PREC_DOUBLE;
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm = 0, have_methods = 0, quiet = 0, no = 0, modes = 3;
    int orders[64];
    double max_beta = 0;
    int have_beta = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'o': {
            double *v = NULL;
            int n = 0;
            if (cli_doubles("--order", optarg, &v, &n)) return CLI_EXIT_USAGE;
            if (n < 1 || n > 64) { free(v); return cli_fail("--order: give 1 to 64 orders"); }
            for (int k = 0; k < n; k++) {
                if (v[k] != floor(v[k]) || v[k] < 1 || v[k] > SHLAB_MAX_ORDER) {
                    free(v);
                    return cli_fail("--order: need integers in 1..%d", SHLAB_MAX_ORDER);
                }
                orders[k] = (int)v[k];
            }
            no = n;
            free(v);
            break;
        }
        case 'm':
            if (parse_methods(optarg, ms, &nm)) return CLI_EXIT_USAGE;
            have_methods = 1;
            break;
        case 'M':
            if (!strcmp(optarg, "per-rotation")) modes = 1;
            else if (!strcmp(optarg, "batched")) modes = 2;
            else if (!strcmp(optarg, "both")) modes = 3;
            else return cli_fail("--mode: '%s' (per-rotation, batched or both)", optarg);
            break;
        case 'c':
            if (cli_int("--count", optarg, &bo.count)) return CLI_EXIT_USAGE;
            if (bo.count < 0 || bo.count > (1 << 28)) return cli_fail("--count: out of range 0..2^28");
            break;
        case 't':
            if (cli_double("--target-ms", optarg, &bo.target_ms)) return CLI_EXIT_USAGE;
            if (!(bo.target_ms > 0 && bo.target_ms <= 10000)) return cli_fail("--target-ms: must be in (0, 10000]");
            break;
        case 'r':
            if (cli_int("--repeat", optarg, &bo.repeat)) return CLI_EXIT_USAGE;
            if (bo.repeat < 1 || bo.repeat > 1000) return cli_fail("--repeat: out of range 1..1000");
            break;
        case 'b':
            if (cli_int("--batch", optarg, &bo.batch)) return CLI_EXIT_USAGE;
            if (bo.batch < 1 || bo.batch > 1000000) return cli_fail("--batch: out of range 1..1000000");
            break;
        case 'B':
            if (cli_double("--max-beta", optarg, &max_beta)) return CLI_EXIT_USAGE;
            have_beta = 1;
            break;
        case 's': {
            long s;
            if (cli_long("--seed", optarg, &s)) return CLI_EXIT_USAGE;
            if (s < 1) return cli_fail("--seed: must be >= 1");
            bo.seed = (uint64_t)s;
            break;
        }
        case 'q': quiet = 1; break;
        default: {
            const int e = cli_common_opt(&cmd_bench, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    prec = com.prec;
    bo.conv = com.conv;
    if (optind < argc) return cli_fail("bench: unexpected argument '%s'", argv[optind]);
    if (have_beta) {
        const double b = com.degrees ? max_beta * M_PI / 180 : max_beta;
        if (!(b >= 0 && b <= M_PI + 1e-12)) return cli_fail("--max-beta: must be in [0, π]");
        bo.max_beta = fmin(b, M_PI);
    }
    if (!no) {
        static const int def[] = {2, 4, 6, 8, 10, 16};
        no = 6;
        memcpy(orders, def, sizeof def);
    }
    if (!have_methods) {
        for (int m = 0; m < SH_ROT_NMETHODS; m++)
            if (m != SH_ROT_REFERENCE && sh_rot_method_max_order((sh_rot_method)m) > 0)
                ms[nm++] = (sh_rot_method)m;
    }
    for (int k = 0; k < nm; k++)
        for (int q = 0; q < no; q++)
            if (orders[q] > sh_rot_method_max_order(ms[k]))
                return cli_fail("bench: method %s is limited to order %d", sh_rot_method_name(ms[k]),
                                sh_rot_method_max_order(ms[k]));
    /* every plan once before the first progress line: an order that cannot
     * be planned (memory) fails before any work is reported */
    for (int k = 0; k < nm; k++)
        for (int q = 0; q < no; q++) {
            sh_rot_plan *p;
            const int st = sh_rot_plan_create(orders[q], ms[k], prec, com.conv, &p);
            if (st) return cli_fail("bench: %s", sh_last_error());
            sh_rot_plan_free(p);
        }
    json_t *rows = json_array();
    const int total = nm * no * ((modes & 1) + (modes >> 1));
    int done = 0;
    for (int k = 0; k < nm && rows; k++)
        for (int q = 0; q < no && rows; q++)
            for (int md = 0; md < 2 && rows; md++) {
                if (!(modes & (1 << md))) continue;
                const sh_bench_mode mode = md ? SH_BENCH_BATCHED : SH_BENCH_PER_ROTATION;
                if (!quiet)
                    fprintf(stderr, "bench: %d/%d %s order %d %s\n", ++done, total,
                            sh_rot_method_name(ms[k]), orders[q], sh_bench_mode_name(mode));
                sh_bench_result r;
                const int st = sh_rot_bench(orders[q], ms[k], prec, mode, &bo, &r);
                if (st) { json_decref(rows); return cli_fail_status(st); }
                json_t *row = json_object();
                row = cli_put(row, "method", json_string(sh_rot_method_name(ms[k])));
                row = cli_put(row, "order", json_integer(orders[q]));
                row = cli_put(row, "precision", json_string(sh_precision_name(prec)));
                row = cli_put(row, "mode", json_string(sh_bench_mode_name(mode)));
                row = cli_put(row, "ns_per_rotation", json_real(r.ns_median));
                row = cli_put(row, "ns_median", json_real(r.ns_median));
                row = cli_put(row, "ns_min", json_real(r.ns_min));
                row = cli_put(row, "ns_max", json_real(r.ns_max));
                row = cli_put(row, "mults", json_real(r.mults));
                row = cli_put(row, "mults_per_ns", json_real(r.mults_per_ns));
                row = cli_put(row, "count", json_integer(r.count));
                row = cli_put(row, "batch", json_integer(md ? bo.batch : 1));
                if (!row || json_array_append_new(rows, row)) { json_decref(rows); rows = NULL; }
            }
    json_t *root = json_object();
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "repeat", json_integer(bo.repeat));
    root = cli_put(root, "setup_ns", json_real(sh_rot_bench_setup_ns(&bo)));
    root = cli_put(root, "rows", rows);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_bench = {"bench", run,
                               "time per rotation of the rotation methods (per rotation and "
                               "batched), counted multiplications",
                               help};
