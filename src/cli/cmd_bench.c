/* cmd_bench.c — `shlab bench`: time per rotation of the SH rotation methods
 * (per rotation from a 3×3 matrix or its angles, batched, K rotations of K
 * vectors; every kernel variant), interleaved in one process, with paired
 * ratios, the noise criterion, the counted multiplications, and instructions
 * per rotation under valgrind (--instructions).  The engine and the entries
 * are in src/lab/bench.c; this file only lists what to time. */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

extern const cli_command cmd_bench;

static const char help[] =
    "Usage: shlab bench [--order LIST] [--methods LIST] [OPTIONS]\n"
    "       shlab bench --peers [OPTIONS]   (see 'shlab bench --peers --help')\n"
    "\n"
    "Time the rotation of one coefficient vector by each method and order.\n"
    "  per-rotation  for every vector a new rotation, given as an orthonormal\n"
    "                3×3 matrix: copy it, extract the ZYZ angles, set the plan,\n"
    "                apply it (what radiance caching does per cache record);\n"
    "  batched       one rotation set, then --batch vectors applied; time per\n"
    "                vector (the set's cost shared among them);\n"
    "  k-rotations   --batch rotations (3×3 matrices) applied to --batch vectors\n"
    "                in one call, structure of arrays (sh_rot_plan_rotate_many:\n"
    "                SIMD lanes across rotations); time per vector.\n"
    "\n"
    "How it is timed.  At each order every (method, kernel, input, mode) is one\n"
    "entry; each entry's iteration count is calibrated so that one sample lasts\n"
    "at least --target-ms; after a warm-up round the entries are timed\n"
    "round-robin, one sample each per round, for --repeat rounds\n"
    "(CLOCK_MONOTONIC), so slow changes of the machine's load reach all of them\n"
    "alike.  ns_per_rotation = ns_median is the median over the samples; ns_min,\n"
    "ns_q1, ns_q3, ns_max and spread = (q3 − q1)/median describe them; sample_ms\n"
    "is the length of one sample.  ratio = the median over the rounds of this\n"
    "entry's time divided by the baseline entry's time in the same round\n"
    "(ratio_q1, ratio_q3: quartiles of those per-round ratios; ratio_to names\n"
    "the baseline entry).\n"
    "\n"
    "Noise.  A run is noisy when an entry's spread or a ratio's spread exceeds\n"
    "5 %, when the samples spent more than 2 % of their time off the CPU\n"
    "(wall clock minus thread CPU clock: another process had the core), or\n"
    "when other processes used more than 0.25 CPUs on average (/proc/stat).\n"
    "A noisy run is printed as measured, with \"noisy\": true and the reason in\n"
    "\"noise\" (and a warning on stderr): do not draw conclusions from it.\n"
    "\n"
    "mults = multiplications counted by the kernels' loops per rotated vector\n"
    "(set + apply, or set/batch + apply); mults_per_ns shows a kernel that is\n"
    "slow for its own arithmetic.  Rotations and vectors are seeded\n"
    "(deterministic); β uniform in [0, --max-beta] (the z method only rotates\n"
    "about z and is timed at β = 0).\n"
    "\n"
    "--instructions counts instead of timing: shlab runs itself under\n"
    "valgrind's callgrind (valgrind must be installed) and reports the\n"
    "instructions executed per rotated vector, from runs of N and 2N\n"
    "iterations (N = --count, default 64; the difference removes fixed\n"
    "costs).  Independent of the machine's load; the same binary gives the\n"
    "same counts.\n"
    "\n"
    "  --order LIST       orders (comma separated; default 2,4,6,8,10,16)\n"
    "  --methods LIST     z, ivanic, zxzxz, choi, blanco, wigner, reference,\n"
    "                     taylor1, taylor1.5, taylor2, or 'all' (default: every\n"
    "                     method built in except reference, which is MPFR)\n"
    "  --mode M           per-rotation | batched | both | k-rotations | all\n"
    "                     (default both)\n"
    "  --kernel LIST      scalar, unrolled, sse2, avx2, avx512, auto (default auto;\n"
    "                     several: each is timed, so ratios come from one run).\n"
    "                     scalar = the loop kernels; the others use the unrolled\n"
    "                     kernels where the method has them (zxzxz, taylor*, n <= 10)\n"
    "  --input LIST       euler (default): matrix -> ZYZ angles -> set, vectors as\n"
    "                     double; matrix: sh_rot_plan_set_matrix (no angles), and for\n"
    "                     float plans float matrices and vectors (the _f calls);\n"
    "                     batched mode then applies the batch in one apply_many.\n"
    "                     k-rotations always takes matrices.\n"
    "  --baseline SPEC    the entry the ratios divide by: METHOD[/KERNEL[/INPUT[/MODE]]];\n"
    "                     a part left out is the row's own (default: the first\n"
    "                     method, and the row's kernel, input and mode).  Example:\n"
    "                     zxzxz/scalar/euler/per-rotation divides every row by\n"
    "                     the loop kernel fed with angles, one rotation at a time\n"
    "  --precision P      double (default) | float (float plans compute in float)\n"
    "  --count C          iterations per sample (default 0: calibrated)\n"
    "  --target-ms T      shortest sample when calibrated (default 5)\n"
    "  --repeat R         timed rounds (default 15)\n"
    "  --batch B          vectors per rotation in batched mode, and rotations per\n"
    "                     call in k-rotations mode (default 16)\n"
    "  --max-beta B       largest β of the random rotations (default π)\n"
    "  --degrees          --max-beta in degrees\n"
    "  --seed S           seed of rotations and vectors (default 12345)\n"
    "  --convention C     cs (default) | nocs: convention of the plans timed\n"
    "  --instructions     count instructions under valgrind instead of timing\n"
    "  --quiet            no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help             this text\n"
    "  --peers            instead: shlab's spherical harmonic transforms against\n"
    "                     libsharp's (see 'shlab bench --peers --help')\n"
    "\n"
    "JSON: {\"convention\",\"repeat\",\"min_sample_ms\",\"setup_ns\",\"noisy\",\"noise\",\n"
    "       \"offcpu\",\"load\",\"rows\":[{\"method\",\"order\",\"precision\",\"mode\",\n"
    "       \"ns_per_rotation\",\"ns_median\",\"ns_min\",\"ns_max\",\"mults\",\"mults_per_ns\",\n"
    "       \"count\",\"batch\",\"kernel\",\"input\",\"ns_q1\",\"ns_q3\",\"spread\",\"sample_ms\",\n"
    "       \"ratio_to\",\"ratio\",\"ratio_q1\",\"ratio_q3\",\"noisy_order\"}]}\n"
    "       (setup_ns: the matrix-to-angles step alone; kernel: the one the plan\n"
    "       used, scalar where the method has no other; offcpu: fraction of the\n"
    "       sample time off the CPU; load: CPUs used by other processes, -1 if\n"
    "       unknown).  --instructions: {\"convention\",\"tool\",\"n\",\"rows\":\n"
    "       [{\"method\",\"order\",\"precision\",\"mode\",\"kernel\",\"input\",\"instructions\",\n"
    "       \"mults\",\"batch\"}]}\n";

static int parse_methods(const char *s, sh_rot_method *ms, int *nm)
{
    *nm = 0;
    if (!strcmp(s, "all")) {
        for (int m = 0; m < SH_ROT_NMETHODS; m++)
            if (sh_rot_method_max_order((sh_rot_method)m) > 0) ms[(*nm)++] = (sh_rot_method)m;
        return 0;
    }
    char **t;
    int n, rc = 0;
    if (cli_split("--methods", s, &t, &n)) return CLI_EXIT_USAGE;
    for (int i = 0; i < n && !rc; i++) {
        sh_rot_method m;
        if (sh_rot_method_parse(t[i], &m)) { rc = cli_fail("--methods: %s", sh_last_error()); break; }
        for (int k = 0; k < *nm && !rc; k++)
            if (ms[k] == m) rc = cli_fail("--methods: '%s' given twice", t[i]);
        if (!rc) ms[(*nm)++] = m; /* distinct methods: at most SH_ROT_NMETHODS */
    }
    free(t);
    return rc;
}

/* --kernel LIST: each available (an unavailable one is refused: the run
 * would otherwise quietly time another kernel) */
static int parse_kernels(const char *s, sh_rot_kernel *ks, int *nk)
{
    char **t;
    int n, rc = 0;
    if (cli_split("--kernel", s, &t, &n)) return CLI_EXIT_USAGE;
    *nk = 0;
    for (int j = 0; j < n && !rc; j++) {
        sh_rot_kernel k;
        if (sh_rot_kernel_parse(t[j], &k)) rc = cli_fail("--kernel: %s", sh_last_error());
        else if (!sh_rot_kernel_available(k)) rc = cli_fail("--kernel: %s is not available on this machine", t[j]);
        for (int i = 0; !rc && i < *nk; i++)
            if (ks[i] == k) rc = cli_fail("--kernel: '%s' given twice", t[j]);
        if (!rc) ks[(*nk)++] = k;
    }
    free(t);
    return rc;
}

static int parse_inputs(const char *s, int *bits)
{
    char **t;
    int n, rc = 0;
    if (cli_split("--input", s, &t, &n)) return CLI_EXIT_USAGE;
    *bits = 0;
    for (int i = 0; i < n && !rc; i++) {
        if (!strcmp(t[i], "euler")) *bits |= 1;
        else if (!strcmp(t[i], "matrix")) *bits |= 2;
        else rc = cli_fail("--input: '%s' (euler or matrix)", t[i]);
    }
    free(t);
    return rc;
}

/* SIGINT/SIGTERM while valgrind runs: passed on to it, so that the parent
 * still removes the temporary files once the child has ended. */
static volatile pid_t cg_child;
static volatile sig_atomic_t cg_signal;
static void cg_forward(int sig)
{
    cg_signal = sig;
    if (cg_child > 0) kill(cg_child, sig);
}

/* --instructions outside valgrind: run this same command line under
 * callgrind (the child finds the output file in SHLAB_CALLGRIND_OUT),
 * pass its output through, and remove the callgrind file. */
static int rerun_under_callgrind(int argc, char **argv)
{
    char exe[4096];
    const ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0) return cli_fail("bench --instructions: cannot find the shlab executable");
    exe[len] = '\0';
    /* in $TMPDIR (default /tmp) */
    const char *tmp = getenv("TMPDIR");
    char dir[4096];
    if (snprintf(dir, sizeof dir, "%s/shlab-callgrind-XXXXXX", tmp && *tmp ? tmp : "/tmp") >= (int)sizeof dir)
        return cli_fail("bench --instructions: TMPDIR is too long");
    if (!mkdtemp(dir)) return cli_fail("bench --instructions: cannot make a temporary directory: %s", strerror(errno));
    char out[sizeof dir + 16], outopt[sizeof out + 32];
    snprintf(out, sizeof out, "%s/cg.out", dir);
    snprintf(outopt, sizeof outopt, "--callgrind-out-file=%s", out);
    char **args = calloc((size_t)argc + 9, sizeof *args);
    if (!args) { rmdir(dir); return cli_fail("out of memory"); }
    int k = 0;
    args[k++] = "valgrind";
    args[k++] = "--tool=callgrind";
    args[k++] = "--instr-atstart=no";
    args[k++] = "--combine-dumps=yes";
    args[k++] = "-q";
    args[k++] = outopt;
    args[k++] = exe;
    for (int i = 0; i < argc; i++) args[k++] = argv[i];
    args[k] = NULL;
    fflush(stdout);
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = cg_forward;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    const pid_t pid = fork();
    if (pid == 0) {
        sigaction(SIGINT, &old_int, NULL);
        sigaction(SIGTERM, &old_term, NULL);
        setenv("SHLAB_CALLGRIND_OUT", out, 1);
        execvp("valgrind", args);
        _exit(127);
    }
    cg_child = pid;
    free(args);
    int status = 0, rc, w;
    while ((w = (int)waitpid(pid, &status, 0)) < 0 && errno == EINTR && pid > 0) {}
    cg_child = 0;
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    if (pid < 0) rc = cli_fail("bench --instructions: cannot start valgrind: %s", strerror(errno));
    else if (w < 0) rc = cli_fail("bench --instructions: waiting for valgrind: %s", strerror(errno));
    else if (cg_signal) rc = cli_fail("bench --instructions: interrupted (signal %d)", (int)cg_signal);
    else if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        rc = cli_fail("bench --instructions needs valgrind (Debian package valgrind)");
    else rc = WIFEXITED(status) ? WEXITSTATUS(status) : cli_fail("bench --instructions: valgrind was killed");
    remove(out);
    rmdir(dir);
    return rc;
}

/* progress over all orders: the engine reports rounds within one order */
typedef struct { cli_progress *p; int base, total; } round_progress;
static void on_round(void *ctx, int done, int total, const char *what)
{
    round_progress *r = ctx;
    (void)total;
    cli_progress_step(r->p, r->base + done, r->total, what);
}

/* One timed entry: what it is, and the index of its baseline. */
typedef struct {
    int k, kk, in, md; /* method, kernel, input, mode indices */
    sh_rot_kernel used;
    int base;
} bench_slot;

static const sh_bench_mode mode_of[3] = {SH_BENCH_PER_ROTATION, SH_BENCH_BATCHED, SH_BENCH_KROT};

/* --baseline METHOD[/KERNEL[/INPUT[/MODE]]]: -1 = the row's own */
typedef struct { sh_rot_method m; int kernel, input, mode; } baseline_spec;
static int parse_baseline(const char *s, baseline_spec *b)
{
    char buf[128];
    if (strlen(s) >= sizeof buf) return cli_fail("--baseline: too long");
    strcpy(buf, s);
    b->kernel = b->input = b->mode = -1;
    char *part[5] = {0};
    int np = 0;
    for (char *save = NULL, *t = strtok_r(buf, "/", &save); t; t = strtok_r(NULL, "/", &save)) {
        if (np == 4) return cli_fail("--baseline: METHOD[/KERNEL[/INPUT[/MODE]]], not '%s'", s);
        part[np++] = t;
    }
    if (np == 0) return cli_fail("--baseline: empty");
    if (sh_rot_method_parse(part[0], &b->m)) return cli_fail("--baseline: %s", sh_last_error());
    if (np > 1) {
        sh_rot_kernel k;
        if (sh_rot_kernel_parse(part[1], &k)) return cli_fail("--baseline: %s", sh_last_error());
        b->kernel = (int)k;
    }
    if (np > 2) {
        if (!strcmp(part[2], "euler")) b->input = 0;
        else if (!strcmp(part[2], "matrix")) b->input = 1;
        else return cli_fail("--baseline: input '%s' (euler or matrix)", part[2]);
    }
    if (np > 3) {
        b->mode = !strcmp(part[3], "per-rotation") ? 0 : !strcmp(part[3], "batched") ? 1
                  : !strcmp(part[3], "k-rotations") ? 2 : -1;
        if (b->mode < 0) return cli_fail("--baseline: mode '%s' (per-rotation, batched or k-rotations)", part[3]);
    }
    return 0;
}

static int run(int argc, char **argv)
{
    for (int k = 1; k < argc; k++)
        if (!strcmp(argv[k], "--peers")) return cli_bench_peers(&cmd_bench, argc, argv);
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_PRECISION,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPT_CONVENTION,
                                         {"order", required_argument, 0, 'o'},
                                         {"methods", required_argument, 0, 'm'},
                                         {"mode", required_argument, 0, 'M'},
                                         {"baseline", required_argument, 0, 'L'},
                                         {"count", required_argument, 0, 'c'},
                                         {"target-ms", required_argument, 0, 't'},
                                         {"repeat", required_argument, 0, 'r'},
                                         {"batch", required_argument, 0, 'b'},
                                         {"max-beta", required_argument, 0, 'B'},
                                         {"seed", required_argument, 0, 's'},
                                         {"instructions", no_argument, 0, 'N'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"kernel", required_argument, 0, 'K'},
                                         {"input", required_argument, 0, 'I'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    sh_precision prec = SH_PREC_DOUBLE;
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    bo.repeat = 15;
    sh_rot_method ms[SH_ROT_NMETHODS];
    baseline_spec base = {SH_ROT_Z, -1, -1, -1};
    int nm = 0, have_methods = 0, have_base = 0, quiet = 0, no = 0, instructions = 0, modes = 3;
    int orders[64];
    double max_beta = 0;
    int have_beta = 0;
    sh_rot_kernel kernels[SH_KERNEL_N] = {SH_KERNEL_AUTO};
    int nk = 1, inputs = 1; /* bit 0 euler, bit 1 matrix */
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'o':
            if (cli_orders("--order", optarg, orders, 64, &no)) return CLI_EXIT_USAGE;
            break;
        case 'm':
            if (parse_methods(optarg, ms, &nm)) return CLI_EXIT_USAGE;
            have_methods = 1;
            break;
        case 'M':
            if (!strcmp(optarg, "per-rotation")) modes = 1;
            else if (!strcmp(optarg, "batched")) modes = 2;
            else if (!strcmp(optarg, "both")) modes = 3;
            else if (!strcmp(optarg, "k-rotations")) modes = 4;
            else if (!strcmp(optarg, "all")) modes = 7;
            else return cli_fail("--mode: '%s' (per-rotation, batched, both, k-rotations or all)", optarg);
            break;
        case 'K':
            if (parse_kernels(optarg, kernels, &nk)) return CLI_EXIT_USAGE;
            break;
        case 'I':
            if (parse_inputs(optarg, &inputs)) return CLI_EXIT_USAGE;
            break;
        case 'L':
            if (parse_baseline(optarg, &base)) return CLI_EXIT_USAGE;
            have_base = 1;
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
        case 'N': instructions = 1; break;
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
    if (!have_base) base.m = ms[0];

    /* the slots: every (method, kernel, input, mode) in use; k-rotations
     * takes matrices and is timed once, under the first input listed */
    bench_slot *slot = calloc((size_t)nm * nk * 2 * 3, sizeof *slot);
    if (!slot) return cli_fail("out of memory");
    int ne = 0;
    for (int k = 0; k < nm; k++)
        for (int kk = 0; kk < nk; kk++)
            for (int in = 0; in < 2; in++)
                for (int md = 0; md < 3; md++) {
                    if (!(modes & (1 << md)) || !(inputs & (1 << in))) continue;
                    if (md == 2 && in == 1 && (inputs & 1)) continue;
                    slot[ne++] = (bench_slot){k, kk, md == 2 ? 1 : in, md, SH_KERNEL_SCALAR, -1};
                }
    /* each slot's baseline: the spec's parts, the row's own elsewhere */
    for (int i = 0; i < ne; i++) {
        const bench_slot *s = &slot[i];
        for (int j = 0; j < ne && slot[i].base < 0; j++) {
            const bench_slot *t = &slot[j];
            if (ms[t->k] == base.m && (base.kernel < 0 ? t->kk == s->kk : (int)kernels[t->kk] == base.kernel) &&
                (base.input < 0 ? t->in == s->in : t->in == base.input) &&
                (base.mode < 0 ? t->md == s->md : t->md == base.mode))
                slot[i].base = j;
        }
        if (slot[i].base < 0) {
            free(slot);
            return cli_fail("--baseline: %s%s%s%s%s%s%s is not among the entries timed (--methods, --kernel, "
                            "--input, --mode)",
                            sh_rot_method_name(base.m), base.kernel >= 0 ? "/" : "",
                            base.kernel >= 0 ? sh_rot_kernel_name((sh_rot_kernel)base.kernel) : "",
                            base.input >= 0 ? "/" : "", base.input >= 0 ? (base.input ? "matrix" : "euler") : "",
                            base.mode >= 0 ? "/" : "", base.mode >= 0 ? sh_bench_mode_name(mode_of[base.mode]) : "");
        }
    }
#if defined(__SANITIZE_ADDRESS__)
    if (instructions) { /* valgrind cannot run a program built with AddressSanitizer */
        free(slot);
        return cli_fail("bench --instructions: not available in a sanitizer build (valgrind cannot run it)");
    }
#endif
    const char *cg_out = getenv("SHLAB_CALLGRIND_OUT");
    if (instructions && !(cg_out && *cg_out)) {
        free(slot);
        return rerun_under_callgrind(argc, argv);
    }
    if (instructions && bo.count == 0) bo.count = 64;

    /* the entries of one order live at once: their memory together, at the
     * order that needs most, against what is available (one line naming
     * both), before any plan is made */
    double most = 0;
    int most_q = 0;
    for (int q = 0; q < no; q++) {
        double need = 0;
        for (int i = 0; i < ne; i++) {
            sh_bench_opts eo = bo;
            eo.input = slot[i].in ? SH_BENCH_INPUT_MATRIX : SH_BENCH_INPUT_EULER;
            need += sh_rot_bench_entry_bytes(orders[q], ms[slot[i].k], prec, mode_of[slot[i].md], &eo);
        }
        if (need > most) most = need, most_q = q;
    }
    char what[96];
    snprintf(what, sizeof what, "timing order %d (%d entries at once)", orders[most_q], ne);
    if (cli_mem_check("bench", most, what)) {
        free(slot);
        return CLI_EXIT_USAGE;
    }
    /* every plan checked before the first progress line (arguments and its
     * own memory, sh_rot_plan_check, without building its tables): an order
     * that cannot be planned fails before any work is reported; the kernel
     * each plan will use is kept for the rows */
    sh_rot_kernel *plan_kernel = malloc((size_t)nm * nk * no * sizeof *plan_kernel);
    if (!plan_kernel) { free(slot); return cli_fail("out of memory"); }
    for (int k = 0; k < nm; k++)
        for (int kk = 0; kk < nk; kk++)
            for (int q = 0; q < no; q++) {
                if (sh_rot_plan_check(orders[q], ms[k], prec)) {
                    free(slot);
                    free(plan_kernel);
                    return cli_fail("bench: %s", sh_last_error());
                }
                plan_kernel[((size_t)k * nk + kk) * no + q] = sh_rot_plan_kernel_for(orders[q], ms[k], kernels[kk]);
            }

    const int S = bo.repeat;
    sh_bench_entry *ent = calloc((size_t)ne, sizeof *ent);
    sh_bench_stats *st = calloc((size_t)ne * no, sizeof *st);
    double *smp = malloc((size_t)ne * S * sizeof *smp), *ins = calloc((size_t)ne * no, sizeof *ins);
    sh_bench_ratio *rat = calloc((size_t)ne * no, sizeof *rat);
    double *mults = calloc((size_t)ne * no, sizeof *mults);
    int *noisy_order = calloc((size_t)no, sizeof *noisy_order);
    sh_rot_kernel *used = calloc((size_t)ne * no, sizeof *used);
    if (!ent || !st || !smp || !ins || !rat || !mults || !noisy_order || !used) {
        free(ent); free(st); free(smp); free(ins); free(rat); free(mults); free(noisy_order); free(used); free(slot);
        free(plan_kernel);
        return cli_fail("out of memory");
    }
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.samples = S;
    cfg.count = bo.count;
    cfg.min_sample_ms = bo.target_ms;
    cli_progress prog;
    cli_progress_start(&prog, "bench", quiet);
    round_progress rp = {&prog, 0, no * S};
    cfg.progress = on_round;
    cfg.progress_ctx = &rp;
    int rc = SH_OK, noisy = 0;
    char why[320] = "";
    double offcpu = 0, load = -1;
    for (int q = 0; q < no && !rc; q++) {
        for (int i = 0; i < ne && !rc; i++) {
            const bench_slot *s = &slot[i];
            bo.kernel = kernels[s->kk];
            bo.input = s->in ? SH_BENCH_INPUT_MATRIX : SH_BENCH_INPUT_EULER;
            rc = sh_rot_bench_entry(orders[q], ms[s->k], prec, mode_of[s->md], &bo, &ent[i]);
            used[q * ne + i] = plan_kernel[((size_t)s->k * nk + s->kk) * no + q];
            char what[64];
            snprintf(what, sizeof what, "entries of order %d set up", orders[q]);
            cli_progress_step(&prog, i + 1, ne, what);
        }
        for (int i = 0; i < ne && !rc; i++) mults[q * ne + i] = ent[i].mults;
        if (!rc && instructions) rc = sh_bench_instructions(ent, ne, bo.count, cg_out, ins + (size_t)q * ne);
        else if (!rc) {
            sh_bench_noise nz;
            rp.base = q * S;
            rc = sh_bench_interleaved(ent, ne, &cfg, smp, st + (size_t)q * ne, &nz);
            for (int i = 0; i < ne && !rc; i++) {
                const int b = slot[i].base;
                rc = sh_bench_paired_ratio(smp + (size_t)i * S, smp + (size_t)b * S, S, cfg.noise_spread,
                                           &rat[q * ne + i]);
                if (!rc && rat[q * ne + i].noisy && !nz.noisy) {
                    nz.noisy = 1;
                    snprintf(nz.why, sizeof nz.why, "ratio %s / %s spread %.1f%% > %.1f%%", ent[i].name,
                             ent[b].name, 100 * rat[q * ne + i].spread, 100 * cfg.noise_spread);
                }
            }
            if (!rc) {
                offcpu = fmax(offcpu, nz.offcpu);
                load = fmax(load, nz.load);
                noisy_order[q] = nz.noisy;
                if (nz.noisy && !noisy) snprintf(why, sizeof why, "order %d: %s", orders[q], nz.why);
                noisy |= nz.noisy;
            }
        }
        for (int i = 0; i < ne; i++) sh_bench_entry_free(&ent[i]);
    }
    free(ent);
    free(smp);
    double setup = 0;
    if (!rc && !instructions) setup = sh_rot_bench_setup_ns(&bo);
    json_t *rows = rc ? NULL : json_array();
    for (int k = 0; k < nm && rows; k++)
        for (int q = 0; q < no && rows; q++)
            for (int i = 0; i < ne && rows; i++) {
                const bench_slot *s = &slot[i];
                if (s->k != k) continue;
                const int x = q * ne + i, batch = s->md ? bo.batch : 1;
                json_t *row = json_object();
                row = cli_put(row, "method", json_string(sh_rot_method_name(ms[k])));
                row = cli_put(row, "order", json_integer(orders[q]));
                row = cli_put(row, "precision", json_string(sh_precision_name(prec)));
                row = cli_put(row, "mode", json_string(sh_bench_mode_name(mode_of[s->md])));
                if (instructions) {
                    row = cli_put(row, "kernel", json_string(sh_rot_kernel_name(used[x])));
                    row = cli_put(row, "input", json_string(s->in ? "matrix" : "euler"));
                    row = cli_put(row, "instructions", json_real(ins[x]));
                    row = cli_put(row, "mults", json_real(mults[x]));
                    row = cli_put(row, "batch", json_integer(batch));
                } else {
                    const sh_bench_stats *t = &st[x];
                    const bench_slot *b = &slot[s->base];
                    char rto[96];
                    snprintf(rto, sizeof rto, "%s/%s/%s/%s", sh_rot_method_name(ms[b->k]),
                             sh_rot_kernel_name(used[q * ne + s->base]), b->in ? "matrix" : "euler",
                             sh_bench_mode_name(mode_of[b->md]));
                    row = cli_put(row, "ns_per_rotation", json_real(t->ns_median));
                    row = cli_put(row, "ns_median", json_real(t->ns_median));
                    row = cli_put(row, "ns_min", json_real(t->ns_min));
                    row = cli_put(row, "ns_max", json_real(t->ns_max));
                    row = cli_put(row, "mults", json_real(mults[x]));
                    row = cli_put(row, "mults_per_ns", json_real(t->ns_median > 0 ? mults[x] / t->ns_median : 0));
                    row = cli_put(row, "count", json_integer(t->count));
                    row = cli_put(row, "batch", json_integer(batch));
                    row = cli_put(row, "kernel", json_string(sh_rot_kernel_name(used[x])));
                    row = cli_put(row, "input", json_string(s->in ? "matrix" : "euler"));
                    row = cli_put(row, "ns_q1", json_real(t->ns_q1));
                    row = cli_put(row, "ns_q3", json_real(t->ns_q3));
                    row = cli_put(row, "spread", json_real(t->spread));
                    row = cli_put(row, "sample_ms", json_real(t->sample_ms));
                    row = cli_put(row, "ratio_to", json_string(rto));
                    row = cli_put(row, "ratio", json_real(rat[x].median));
                    row = cli_put(row, "ratio_q1", json_real(rat[x].q1));
                    row = cli_put(row, "ratio_q3", json_real(rat[x].q3));
                    row = cli_put(row, "noisy_order", json_boolean(noisy_order[q]));
                }
                if (!row || json_array_append_new(rows, row)) { json_decref(rows); rows = NULL; }
            }
    free(st); free(ins); free(rat); free(mults); free(noisy_order); free(used); free(slot); free(plan_kernel);
    if (rc) return cli_fail_status(rc);
    if (!rows) return cli_fail("out of memory");
    json_t *root = json_object();
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    if (instructions) {
        root = cli_put(root, "tool", json_string("callgrind"));
        root = cli_put(root, "n", json_integer(bo.count));
    } else {
        root = cli_put(root, "repeat", json_integer(bo.repeat));
        root = cli_put(root, "min_sample_ms", json_real(bo.target_ms));
        root = cli_put(root, "setup_ns", json_real(setup));
        root = cli_put(root, "noisy", json_boolean(noisy));
        root = cli_put(root, "noise", json_string(why));
        root = cli_put(root, "offcpu", json_real(offcpu));
        root = cli_put(root, "load", json_real(load));
        if (noisy) cli_warn("bench: noisy run (%s); do not draw conclusions from it", why);
    }
    root = cli_put(root, "rows", rows);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_bench = {"bench", run,
                               "time per rotation of the rotation methods and kernels (interleaved, "
                               "paired ratios, noise check), counted multiplications and instructions",
                               help, NULL};
