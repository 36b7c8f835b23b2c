/* cmd_bench.c — `shlab bench`: time per rotation of the SH rotation methods
 * (per rotation from a 3×3 matrix or its angles, batched, K rotations of K
 * vectors, one-shot use of a rotator; every kernel variant), interleaved in
 * one process, with paired ratios, the noise criterion, the counted
 * multiplications, and instructions per rotation under valgrind
 * (--instructions).  The engine and the plan entries are in
 * src/lab/bench.c; this file lists what to time, and holds the one-shot
 * entry (a rotator made, applied once and freed per rotation). */
#include "cli.h"

#include <errno.h>
#include <gsl/gsl_rng.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern const cli_command cmd_bench;

#define BENCH_MAX_ORDERS 64   /* --order: orders in one run */
#define BENCH_MAX_BATCH 1000000 /* --batch */
#define BENCH_MAX_COUNT (1 << 28) /* --count */

/* The modes by index (a slot's md): the library's three plan modes, then
 * the one-shot rotator.  --mode's names give sets of them (bits). */
enum { MD_PER_ROTATION, MD_BATCHED, MD_KROT, MD_ONESHOT, MD_N };
static const char *const mode_name[MD_N] = {"per-rotation", "batched", "k-rotations", "oneshot"};
static const sh_bench_mode mode_of[MD_KROT + 1] = {SH_BENCH_PER_ROTATION, SH_BENCH_BATCHED, SH_BENCH_KROT};
static const char *const mode_sets[] = {"per-rotation", "batched", "both", "k-rotations", "all", "oneshot"};
static const int mode_bits[] = {1, 2, 3, 4, 7, 8}; /* "all": the three plan modes */

/* ---- the options ---------------------------------------------------------------- */

typedef struct { int n, v[BENCH_MAX_ORDERS]; } bench_orders;
typedef struct { int n; sh_rot_method v[SH_ROT_NMETHODS]; } bench_methods;
typedef struct { int n; sh_rot_kernel v[SH_KERNEL_N]; } bench_kernels;
/* --baseline METHOD[/KERNEL[/INPUT[/MODE]]]: -1 = the row's own */
typedef struct { sh_rot_method m; int kernel, input, mode; } baseline_spec;

typedef struct {
    bench_orders orders;
    bench_methods methods; /* n = 0: every method built in but reference */
    bench_kernels kernels;
    baseline_spec base;
    int modes, inputs; /* modes: bit md for mode md; inputs: bit 0 euler, bit 1 matrix */
    sh_precision prec;
    int count, repeat, batch;
    double target_ms, max_beta;
    long seed;
    int degrees, conv, instructions, quiet, fmt, peers;
    const char *plugin, *shader; /* declared for --help; handled by cmd_bench_plugin.c, cmd_bench_shader.c */
} bench_args;

static int parse_orders(const char *opt, const char *s, void *field)
{
    bench_orders *o = field;
    return cli_orders(opt, s, o->v, BENCH_MAX_ORDERS, &o->n);
}

static int parse_methods(const char *opt, const char *s, void *field)
{
    bench_methods *ms = field;
    ms->n = 0;
    if (!strcmp(s, "all")) {
        for (int m = 0; m < SH_ROT_NMETHODS; m++)
            if (sh_rot_method_max_order((sh_rot_method)m) > 0) ms->v[ms->n++] = (sh_rot_method)m;
        return 0;
    }
    char **t;
    int n, rc = 0;
    if (cli_split(opt, s, &t, &n)) return CLI_EXIT_USAGE;
    for (int i = 0; i < n && !rc; i++) {
        sh_rot_method m;
        if (sh_rot_method_parse(t[i], &m)) { rc = cli_fail("%s: %s", opt, sh_last_error()); break; }
        for (int k = 0; k < ms->n && !rc; k++)
            if (ms->v[k] == m) rc = cli_fail("%s: '%s' given twice", opt, t[i]);
        if (!rc) ms->v[ms->n++] = m; /* distinct methods: at most SH_ROT_NMETHODS */
    }
    free(t);
    return rc;
}

/* --kernel LIST: each available (an unavailable one is refused: the run
 * would otherwise quietly time another kernel) */
static int parse_kernels(const char *opt, const char *s, void *field)
{
    bench_kernels *ks = field;
    char **t;
    int n, rc = 0;
    if (cli_split(opt, s, &t, &n)) return CLI_EXIT_USAGE;
    ks->n = 0;
    for (int j = 0; j < n && !rc; j++) {
        sh_rot_kernel k;
        if ((rc = cli_parse_kernel(opt, t[j], &k))) break;
        for (int i = 0; !rc && i < ks->n; i++)
            if (ks->v[i] == k) rc = cli_fail("%s: '%s' given twice", opt, t[j]);
        if (!rc) ks->v[ks->n++] = k;
    }
    free(t);
    return rc;
}

/* A list of names, each one of names[0..n) standing for bits[i], into the
 * union of their bits; `expect` lists them for the error line. */
static int parse_bits(const char *opt, const char *s, const char *const *names, const int *bits, int n,
                      const char *expect, int *out)
{
    char **t;
    int k, rc = 0;
    if (cli_split(opt, s, &t, &k)) return CLI_EXIT_USAGE;
    *out = 0;
    for (int i = 0; i < k && !rc; i++) {
        int b = 0;
        for (int j = 0; j < n; j++)
            if (!strcmp(t[i], names[j])) b = bits[j];
        if (!b) rc = cli_fail("%s: '%s' (%s)", opt, t[i], expect);
        *out |= b;
    }
    free(t);
    return rc;
}

/* --mode LIST: the union of the sets named */
static int parse_modes(const char *opt, const char *s, void *field)
{
    return parse_bits(opt, s, mode_sets, mode_bits, (int)(sizeof mode_bits / sizeof *mode_bits),
                      "per-rotation, batched, both, k-rotations, all or oneshot", field);
}

/* --input LIST: bit 0 euler, bit 1 matrix */
static int parse_inputs(const char *opt, const char *s, void *field)
{
    static const char *const names[] = {"euler", "matrix", "quat"};
    static const int bits[] = {1, 2, 4};
    return parse_bits(opt, s, names, bits, 3, "euler, matrix or quat", field);
}

static int parse_baseline(const char *opt, const char *s, void *field)
{
    baseline_spec *b = field;
    char buf[128];
    if (strlen(s) >= sizeof buf) return cli_fail("%s: too long", opt);
    strcpy(buf, s);
    b->kernel = b->input = b->mode = -1;
    char *part[5] = {0};
    int np = 0;
    for (char *save = NULL, *t = strtok_r(buf, "/", &save); t; t = strtok_r(NULL, "/", &save)) {
        if (np == 4) return cli_fail("%s: METHOD[/KERNEL[/INPUT[/MODE]]], not '%s'", opt, s);
        part[np++] = t;
    }
    if (np == 0) return cli_fail("%s: empty", opt);
    if (sh_rot_method_parse(part[0], &b->m)) return cli_fail("%s: %s", opt, sh_last_error());
    if (np > 1) {
        sh_rot_kernel k;
        if (sh_rot_kernel_parse(part[1], &k)) return cli_fail("%s: %s", opt, sh_last_error());
        b->kernel = (int)k;
    }
    if (np > 2) {
        if (!strcmp(part[2], "euler")) b->input = 0;
        else if (!strcmp(part[2], "matrix")) b->input = 1;
        else if (!strcmp(part[2], "quat")) b->input = 2;
        else return cli_fail("%s: input '%s' (euler or matrix)", opt, part[2]);
    }
    for (int md = 0; np > 3 && md < MD_N; md++)
        if (!strcmp(part[3], mode_name[md])) b->mode = md;
    if (np > 3 && b->mode < 0)
        return cli_fail("%s: mode '%s' (per-rotation, batched, k-rotations or oneshot)", opt, part[3]);
    return 0;
}

static const cli_opt bench_opts[] = {
    CLI_CUSTOM(bench_args, orders, "order", "LIST", parse_orders, "2,4,6,8,10,16", "orders (comma separated)"),
    CLI_CUSTOM(bench_args, methods, "methods", "LIST", parse_methods, NULL,
               "z, ivanic, zxzxz, choi, blanco, wigner, reference, halfpi,\n"
               "direct (orders ≤ 3), zh (orders ≤ 6), taylor1, taylor1.5,\n"
               "taylor2, or\n"
               "'all' (default: every method built in except\n"
               "reference, which is MPFR, and those limited below the\n"
               "largest --order, e.g. direct beyond 3).  A method\n"
               "named here is timed at the orders it reaches"),
    CLI_CUSTOM(bench_args, modes, "mode", "LIST", parse_modes, "both",
               "per-rotation | batched | both | k-rotations | all (the\n"
               "three before) | oneshot; several: comma separated"),
    CLI_CUSTOM(bench_args, kernels, "kernel", "LIST", parse_kernels, "auto",
               "scalar, unrolled, sse2, avx2, avx512, auto (default auto;\n"
               "several: each is timed, so ratios come from one run).\n"
               "scalar = the loop kernels; the others use the unrolled\n"
               "kernels where the method has them (zxzxz, taylor*, n <= 10)"),
    CLI_CUSTOM(bench_args, inputs, "input", "LIST", parse_inputs, "euler",
               "euler (default): matrix -> ZYZ angles -> set, vectors as\n"
               "double; matrix: sh_rot_plan_set_matrix (no angles), and for\n"
               "float plans float matrices and vectors (the _f calls);\n"
               "batched mode then applies the batch in one apply_many;\n"
               "quat: sh_rot_plan_set_quat (w, x, y, z), otherwise as matrix.\n"
               "k-rotations takes matrices, or quaternions with quat\n"
               "(rotate_many_quat); oneshot takes euler or matrix."),
    CLI_CUSTOM(bench_args, base, "baseline", "SPEC", parse_baseline, NULL,
               "the entry the ratios divide by: METHOD[/KERNEL[/INPUT[/MODE]]];\n"
               "a part left out is the row's own (default: the first\n"
               "method, and the row's kernel, input and mode).  Example:\n"
               "zxzxz/scalar/euler/per-rotation divides every row by\n"
               "the loop kernel fed with angles, one rotation at a time"),
    CLI_CUSTOM(bench_args, prec, "precision", "P", cli_parse_precision, "double",
               "double (default) | float (float plans compute in float)"),
    CLI_INT(bench_args, count, "count", "C", 0, BENCH_MAX_COUNT, "0", "iterations per sample (0: calibrated)"),
    CLI_REAL(bench_args, target_ms, "target-ms", "T", 0, 10000, CLI_LO_OPEN, "5",
             "shortest sample when calibrated"),
    CLI_INT(bench_args, repeat, "repeat", "R", 1, 1000, "15", "timed rounds"),
    CLI_INT(bench_args, batch, "batch", "B", 1, BENCH_MAX_BATCH, "16",
            "vectors per rotation in batched mode, and rotations per\ncall in k-rotations mode"),
    CLI_REAL(bench_args, max_beta, "max-beta", "B", 0, 0, 0, NULL,
             "largest β of the random rotations (default π)"),
    CLI_DEGREES(bench_args, degrees, "--max-beta in degrees"),
    CLI_LONG(bench_args, seed, "seed", "S", 1, (double)LONG_MAX, "12345", "seed of rotations and vectors"),
    CLI_CONVENTION(bench_args, conv),
    CLI_FLAG(bench_args, instructions, "instructions", "count instructions under valgrind instead of timing"),
    CLI_FLAG(bench_args, quiet, "quiet", "no progress on stderr"),
    CLI_FORMAT(bench_args, fmt),
    CLI_FLAG(bench_args, peers, "peers",
             "instead: shlab's spherical harmonic transforms against\n"
             "libsharp's (see 'shlab bench --peers --help')"),
    {.type = CLI_T_STRING, .name = "plugin", .meta = "LIB.so:SYMBOL", .off = offsetof(bench_args, plugin),
     .help = "instead: your kernel (shlab/kernel.h) on the cost/error\n"
             "frontier beside shlab's choice at its error (see\n"
             "'shlab bench --plugin X --help')"},
    {.type = CLI_T_STRING, .name = "shader", .meta = "FILE", .off = offsetof(bench_args, shader),
     .help = "instead: a compute shader's rotations per second on the\n"
             "Vulkan device beside shlab's CPU kernel (see\n"
             "'shlab bench --shader X --help')"},
    CLI_END,
};

static const cli_cmd bench_decl = {
    .name = "bench",
    .usage = "bench [--order LIST] [--methods LIST] [OPTIONS]\n"
             "       shlab bench --peers [OPTIONS]   (see 'shlab bench --peers --help')\n"
             "       shlab bench --plugin LIB.so:SYMBOL --abi NAME [OPTIONS]   (see 'shlab bench --plugin X --help')\n"
             "       shlab bench --shader FILE --abi matrix|quat|euler [OPTIONS]   (see 'shlab bench --shader X --help')",
    .about =
        "Time the rotation of one coefficient vector by each method and order.\n"
        "  per-rotation  for every vector a new rotation, given as an orthonormal\n"
        "                3×3 matrix: copy it, extract the ZYZ angles, set the plan,\n"
        "                apply it (what radiance caching does per cache record);\n"
        "  batched       one rotation set, then --batch vectors applied; time per\n"
        "                vector (the set's cost shared among them);\n"
        "  k-rotations   --batch rotations (3×3 matrices) applied to --batch vectors\n"
        "                in one call, structure of arrays (sh_rot_plan_rotate_many:\n"
        "                SIMD lanes across rotations); time per vector;\n"
        "  oneshot       for every vector a rotator made, applied once and freed\n"
        "                (sh_rotator_create, sh_rotator_apply or, with --input\n"
        "                matrix, sh_rotator_apply_matrix(_f), sh_rotator_free):\n"
        "                the cost of one-shot use, creation included.\n"
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
        "same counts.\n",
    .opts = bench_opts,
    .notes =
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
        "       \"mults\",\"batch\"}]}\n",
};

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

/* ---- the one-shot entry ------------------------------------------------------------
 * Per iteration: sh_rotator_create, one rotation applied to one vector
 * (--input euler: the frame's ZYZ angles and sh_rotator_apply, vectors as
 * double; matrix: sh_rotator_apply_matrix, or for float rotators
 * sh_rotator_apply_matrix_f on float vectors), sh_rotator_free.  Rotations
 * and vectors come from a seeded pool drawn before timing, as in the plan
 * entries (rotation_bench.c). */
#define ONESHOT_POOL 64

typedef struct {
    sh_rotator_opts o;
    int nc, matrix;
    double (*R)[9], *vin, *vout;
    float (*Rf)[9], *vinf, *voutf; /* float rotators with --input matrix */
    double sink;
    char name[96];
} oneshot_ctx;

static void oneshot_free(void *v)
{
    oneshot_ctx *b = v;
    if (!b) return;
    free(b->R), free(b->vin), free(b->vout), free(b->Rf), free(b->vinf), free(b->voutf);
    free(b);
}

/* The frame R_k as an sh_rotation: R copied, its ZYZ angles extracted
 * (the user's step in the euler entries). */
static void frame_rotation(const double R[9], sh_rotation *rot)
{
    memcpy(rot->R, R, sizeof rot->R);
    sh_euler_from_matrix(R, &rot->alpha, &rot->beta, &rot->gamma);
}

/* One rotation of pool entry k by rotator r. */
static int oneshot_apply(oneshot_ctx *b, const sh_rotator *r, long k)
{
    const size_t nc = (size_t)b->nc;
    if (b->Rf) return sh_rotator_apply_matrix_f(r, b->Rf[k], b->vinf + k * nc, b->voutf);
    if (b->matrix) return sh_rotator_apply_matrix(r, b->R[k], 0, 1, b->vin + k * nc, b->vout);
    sh_rotation rot;
    frame_rotation(b->R[k], &rot);
    return sh_rotator_apply(r, &rot, 0, 1, b->vin + k * nc, b->vout);
}

static int oneshot_run(void *v, long count)
{
    oneshot_ctx *b = v;
    int st = SH_OK;
    for (long it = 0; it < count && !st; it++) {
        const long k = it & (ONESHOT_POOL - 1);
        sh_rotator *r;
        if ((st = sh_rotator_create(&b->o, &r))) break;
        st = oneshot_apply(b, r, k);
        sh_rotator_free(r);
        b->sink += b->Rf ? (double)b->voutf[it % b->nc] : b->vout[it % b->nc];
    }
    if (!isfinite(b->sink)) b->sink = 0;
    return st;
}

/* Multiplications per rotation: the set and apply of a plan of the same
 * rotator (the work the one-shot call does inside; creating counts none). */
static double oneshot_mults(oneshot_ctx *b)
{
    sh_rotator *r = NULL;
    sh_rot_plan *p = NULL;
    uint64_t sm = 0, am = 0;
    int st = sh_rotator_create(&b->o, &r);
    if (!st) st = sh_rotator_plan(r, &p);
    if (!st && b->Rf) {
        st = sh_rot_plan_set_matrix_f(p, b->Rf[0]);
        if (!st) st = sh_rot_plan_apply_f(p, b->vinf, b->voutf);
    } else if (!st) {
        sh_rotation rot;
        frame_rotation(b->R[0], &rot);
        st = b->matrix ? sh_rot_plan_set_matrix(p, b->R[0]) : sh_rot_plan_set(p, &rot);
        if (!st) st = sh_rot_plan_apply(p, b->vin, b->vout);
    }
    if (!st) sh_rot_plan_mults(p, &sm, &am);
    sh_rot_plan_free(p);
    sh_rotator_free(r);
    return (double)(sm + am);
}

/* The pool: seeded rotations (β uniform in [0, max_beta], 0 for z) and
 * vectors, in float too for float rotators with matrix input. */
static int oneshot_pool(oneshot_ctx *b, const sh_bench_opts *bo, int zonly)
{
    const size_t nc = (size_t)b->nc, np = ONESHOT_POOL;
    const int fl = b->matrix && b->o.prec == SH_PREC_FLOAT;
    b->R = malloc(np * sizeof *b->R);
    b->vin = malloc(np * nc * sizeof *b->vin);
    b->vout = malloc(nc * sizeof *b->vout);
    if (fl) {
        b->Rf = malloc(np * sizeof *b->Rf);
        b->vinf = malloc(np * nc * sizeof *b->vinf);
        b->voutf = malloc(nc * sizeof *b->voutf);
    }
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!g || !b->R || !b->vin || !b->vout || (fl && (!b->Rf || !b->vinf || !b->voutf))) {
        gsl_rng_free(g);
        return sh_error(SH_ENOMEM, "bench: out of memory");
    }
    gsl_rng_set(g, bo->seed);
    for (size_t k = 0; k < np; k++) {
        sh_rotation r;
        const double a = M_PI * (2 * gsl_rng_uniform(g) - 1), c = M_PI * (2 * gsl_rng_uniform(g) - 1);
        sh_rotation_from_euler(a, zonly ? 0 : bo->max_beta * gsl_rng_uniform(g), c, &r);
        memcpy(b->R[k], r.R, sizeof r.R);
        for (int j = 0; fl && j < 9; j++) b->Rf[k][j] = (float)r.R[j];
    }
    for (size_t i = 0; i < np * nc; i++) {
        b->vin[i] = 2 * gsl_rng_uniform(g) - 1;
        if (fl) b->vinf[i] = (float)b->vin[i];
    }
    gsl_rng_free(g);
    return SH_OK;
}

/* An engine entry for one-shot use at (order, method, precision) with bo's
 * kernel, convention and input; units: one rotated vector. */
static int oneshot_entry(int order, sh_rot_method method, sh_precision prec, const sh_bench_opts *bo,
                         sh_bench_entry *e)
{
    memset(e, 0, sizeof *e);
    oneshot_ctx *b = calloc(1, sizeof *b);
    if (!b) return sh_error(SH_ENOMEM, "bench: out of memory");
    b->o = SH_ROTATOR_OPTS(order);
    b->o.method = method;
    b->o.prec = prec;
    b->o.kernel = bo->kernel;
    b->o.conv = bo->conv;
    b->o.threads = 1;
    b->nc = order * order;
    b->matrix = bo->input == SH_BENCH_INPUT_MATRIX;
    snprintf(b->name, sizeof b->name, "%s order %d oneshot%s%s %s", sh_rot_method_name(method), order,
             b->matrix ? " from a matrix" : "", prec == SH_PREC_FLOAT ? " float" : "",
             sh_rot_kernel_name(sh_rot_plan_kernel_for(order, method, bo->kernel)));
    int st = oneshot_pool(b, bo, method == SH_ROT_Z);
    if (!st) st = oneshot_run(b, 1); /* the arguments, once, before timing */
    if (st) {
        oneshot_free(b);
        return st;
    }
    *e = (sh_bench_entry){b->name, oneshot_run, oneshot_free, b, 1, oneshot_mults(b)};
    return SH_OK;
}

/* Bytes of a one-shot entry: its pool, and the rotator with a plan that
 * one call may make. */
static double oneshot_bytes(int order, sh_rot_method method, sh_precision prec, const sh_bench_opts *bo)
{
    const double nc = (double)order * order;
    double b = sizeof(oneshot_ctx) + (double)sh_rot_plan_bytes(order, method, prec);
    b += ONESHOT_POOL * (9 + nc) * sizeof(double) + nc * sizeof(double);
    if (bo->input == SH_BENCH_INPUT_MATRIX && prec == SH_PREC_FLOAT)
        b += ONESHOT_POOL * (9 + nc) * sizeof(float) + nc * sizeof(float);
    return b;
}

/* ---- a run -------------------------------------------------------------------------- */

/* One timed entry: method, kernel, input and mode (indices), and the slot
 * of its baseline. */
typedef struct {
    int k, kk, in, md;
    int base;
} bench_slot;

/* What a run times and what it measured, entry i of order q at x = q·ne + i
 * (absent where the order is beyond the entry's method: no row). */
typedef struct {
    bench_args *a;
    sh_bench_opts bo;
    bench_slot *slot;
    int ne;
    sh_rot_kernel *used; /* the kernel entry x runs */
    sh_bench_stats *st;
    sh_bench_ratio *rat;
    double *ins, *mults;
    int *noisy_order, noisy;
    char why[320];
    double offcpu, load, setup;
    const char *cg_out; /* --instructions: the callgrind file, under valgrind */
} bench_run;

static int reaches(sh_rot_method m, int order) { return order <= sh_rot_method_max_order(m); }

/* Entry i exists at order q: its method reaches that order. */
static int present(const bench_run *R, int q, int i)
{
    return reaches(R->a->methods.v[R->slot[i].k], R->a->orders.v[q]);
}

static void run_free(bench_run *R)
{
    free(R->slot), free(R->used), free(R->st), free(R->rat), free(R->ins), free(R->mults), free(R->noisy_order);
}

/* The checks that involve several options, and the defaults that depend on
 * others: --max-beta in the unit of --degrees, the methods, each method's
 * limit at every order, the baseline's method. */
static int validate(bench_args *a, const cli_parsed *seen, sh_bench_opts *bo)
{
    if (cli_given(seen, "max-beta")) {
        const double b = a->degrees ? a->max_beta * M_PI / 180 : a->max_beta;
        if (!(b >= 0 && b <= M_PI + 1e-12)) return cli_fail("--max-beta: must be in [0, π]");
        bo->max_beta = fmin(b, M_PI);
    }
    bench_methods *ms = &a->methods;
    /* by default every method built in but the MPFR reference that reaches
     * the largest order asked for */
    const int by_default = ms->n == 0;
    int top = 0;
    for (int q = 0; q < a->orders.n; q++) top = a->orders.v[q] > top ? a->orders.v[q] : top;
    for (int m = 0; by_default && m < SH_ROT_NMETHODS; m++)
        if (m != SH_ROT_REFERENCE && reaches((sh_rot_method)m, top)) ms->v[ms->n++] = (sh_rot_method)m;
    if (!ms->n) return cli_fail("bench: no method reaches order %d", top);
    /* a method limited below some orders asked for is timed at the others (a
     * sweep of low-order methods beside general ones); none at all is an error */
    for (int k = 0; k < ms->n; k++) {
        const int lim = sh_rot_method_max_order(ms->v[k]);
        int reached = 0;
        for (int q = 0; q < a->orders.n; q++) reached += reaches(ms->v[k], a->orders.v[q]);
        if (!reached) return cli_fail("bench: method %s is limited to order %d", sh_rot_method_name(ms->v[k]), lim);
        const char *cg = getenv("SHLAB_CALLGRIND_OUT"); /* set: the run under callgrind, whose parent said it */
        if (reached < a->orders.n && !a->quiet && !(a->instructions && cg && *cg))
            fprintf(stderr, "bench: method %s is limited to order %d: not timed above it\n",
                    sh_rot_method_name(ms->v[k]), lim);
    }
    if (!cli_given(seen, "baseline")) a->base.m = ms->v[0];
    return 0;
}

/* "zxzxz/scalar/euler/per-rotation": an entry's name in ratio_to and messages. */
static void slot_name(const bench_run *R, const bench_slot *s, sh_rot_kernel kernel, char *buf, size_t n)
{
    snprintf(buf, n, "%s/%s/%s/%s", sh_rot_method_name(R->a->methods.v[s->k]), sh_rot_kernel_name(kernel),
             sh_bench_input_name((sh_bench_input)s->in), mode_name[s->md]);
}

/* The baseline of every slot: the spec's parts, the row's own elsewhere. */
static int find_baselines(bench_run *R)
{
    const baseline_spec *b = &R->a->base;
    for (int i = 0; i < R->ne; i++) {
        const bench_slot *s = &R->slot[i];
        for (int j = 0; j < R->ne && R->slot[i].base < 0; j++) {
            const bench_slot *t = &R->slot[j];
            if (R->a->methods.v[t->k] == b->m &&
                (b->kernel < 0 ? t->kk == s->kk : (int)R->a->kernels.v[t->kk] == b->kernel) &&
                (b->input < 0 ? t->in == s->in : t->in == b->input) && (b->mode < 0 ? t->md == s->md : t->md == b->mode))
                R->slot[i].base = j;
        }
        if (R->slot[i].base < 0)
            return cli_fail("--baseline: %s%s%s%s%s%s%s is not among the entries timed (--methods, --kernel, "
                            "--input, --mode)",
                            sh_rot_method_name(b->m), b->kernel >= 0 ? "/" : "",
                            b->kernel >= 0 ? sh_rot_kernel_name((sh_rot_kernel)b->kernel) : "",
                            b->input >= 0 ? "/" : "", b->input >= 0 ? sh_bench_input_name((sh_bench_input)b->input) : "",
                            b->mode >= 0 ? "/" : "", b->mode >= 0 ? mode_name[b->mode] : "");
    }
    return 0;
}

/* The slots: every (method, kernel, input, mode) in use; k-rotations takes
 * matrices and is timed once, under the first input listed. */
static int make_slots(bench_run *R)
{
    const bench_args *a = R->a;
    const int modes = a->modes, nm = a->methods.n, nk = a->kernels.n;
    R->slot = calloc((size_t)nm * nk * SH_BENCH_NINPUTS * MD_N, sizeof *R->slot);
    if (!R->slot) return cli_fail("out of memory");
    for (int k = 0; k < nm; k++)
        for (int kk = 0; kk < nk; kk++)
            for (int in = 0; in < SH_BENCH_NINPUTS; in++)
                for (int md = 0; md < MD_N; md++) {
                    if (!(modes & (1 << md)) || !(a->inputs & (1 << in))) continue;
                    if (md == MD_KROT && in == 1 && (a->inputs & 1)) continue;
                    if (md == MD_ONESHOT && in == SH_BENCH_INPUT_QUAT) continue; /* the rotator takes no quaternion */
                    R->slot[R->ne++] = (bench_slot){k, kk, md == MD_KROT && in == 0 ? 1 : in, md, -1};
                }
    return find_baselines(R);
}

static sh_bench_opts entry_opts(const bench_run *R, const bench_slot *s)
{
    sh_bench_opts eo = R->bo;
    eo.kernel = R->a->kernels.v[s->kk];
    eo.input = (sh_bench_input)s->in;
    return eo;
}

/* The entries of one order live at once: their memory together, at the
 * order that needs most, against what is available (one line naming
 * both), before any plan is made. */
static int check_memory(const bench_run *R)
{
    const bench_args *a = R->a;
    double most = 0;
    int most_q = 0;
    for (int q = 0; q < a->orders.n; q++) {
        double need = 0;
        for (int i = 0; i < R->ne; i++) {
            if (!present(R, q, i)) continue;
            const bench_slot *s = &R->slot[i];
            const sh_bench_opts eo = entry_opts(R, s);
            const int order = a->orders.v[q];
            const sh_rot_method m = a->methods.v[s->k];
            need += s->md == MD_ONESHOT ? oneshot_bytes(order, m, a->prec, &eo)
                                        : sh_rot_bench_entry_bytes(order, m, a->prec, mode_of[s->md], &eo);
        }
        if (need > most) most = need, most_q = q;
    }
    char what[96];
    snprintf(what, sizeof what, "timing order %d (%d entries at once)", a->orders.v[most_q], R->ne);
    return cli_mem_check("bench", most, what);
}

/* Every plan checked before the first progress line (arguments and its own
 * memory, sh_rot_plan_check, without building its tables): an order that
 * cannot be planned fails before any work is reported.  The kernel each
 * entry will run is kept for the rows. */
static int check_plans(bench_run *R)
{
    const bench_args *a = R->a;
    const int no = a->orders.n;
    for (int k = 0; k < a->methods.n; k++)
        for (int q = 0; q < no; q++)
            if (reaches(a->methods.v[k], a->orders.v[q]) && sh_rot_plan_check(a->orders.v[q], a->methods.v[k], a->prec))
                return cli_fail("bench: %s", sh_last_error());
    for (int q = 0; q < no; q++)
        for (int i = 0; i < R->ne; i++)
            if (present(R, q, i)) R->used[q * R->ne + i] = sh_rot_plan_kernel_for(a->orders.v[q], a->methods.v[R->slot[i].k],
                                                            a->kernels.v[R->slot[i].kk]);
    return 0;
}

/* progress over all orders: the engine reports rounds within one order */
typedef struct { cli_progress *p; int base, total; } round_progress;
static void on_round(void *ctx, int done, int total, const char *what)
{
    round_progress *r = ctx;
    (void)total;
    cli_progress_step(r->p, r->base + done, r->total, what);
}

/* The entries present at order q, made (progress per entry): ent[j] is slot
 * idx[j], *n of them. */
static int make_entries(bench_run *R, int q, sh_bench_entry *ent, int *idx, int *n, cli_progress *prog)
{
    const bench_args *a = R->a;
    int rc = SH_OK;
    char what[64];
    snprintf(what, sizeof what, "entries of order %d set up", a->orders.v[q]);
    *n = 0;
    for (int i = 0; i < R->ne && !rc; i++) {
        if (!present(R, q, i)) continue;
        idx[*n] = i;
        const bench_slot *s = &R->slot[i];
        const sh_bench_opts eo = entry_opts(R, s);
        const int order = a->orders.v[q];
        const sh_rot_method m = a->methods.v[s->k];
        sh_bench_entry *e = &ent[(*n)++];
        rc = s->md == MD_ONESHOT ? oneshot_entry(order, m, a->prec, &eo, e)
                                 : sh_rot_bench_entry(order, m, a->prec, mode_of[s->md], &eo, e);
        R->mults[q * R->ne + i] = e->mults;
        cli_progress_step(prog, i + 1, R->ne, what);
    }
    return rc;
}

/* Order q timed: its n entries (ent[j] is slot idx[j]) interleaved, each
 * paired with its baseline round by round where the baseline is present too,
 * and the noise of the order. */
static int time_order(bench_run *R, int q, const sh_bench_entry *ent, const int *idx, int n,
                      const sh_bench_cfg *cfg, double *smp, sh_bench_stats *st)
{
    const int S = cfg->samples, ne = R->ne;
    sh_bench_noise nz;
    int rc = sh_bench_interleaved(ent, n, cfg, smp, st, &nz);
    for (int j = 0; j < n && !rc; j++) {
        R->st[q * ne + idx[j]] = st[j];
        int b = -1; /* the baseline's place among the present entries */
        for (int k = 0; k < n; k++)
            if (idx[k] == R->slot[idx[j]].base) b = k;
        sh_bench_ratio *r = &R->rat[q * ne + idx[j]];
        if (b < 0) { /* the baseline's method does not reach this order: no ratio */
            r->median = NAN;
            continue;
        }
        rc = sh_bench_paired_ratio(smp + (size_t)j * S, smp + (size_t)b * S, S, cfg->noise_spread, r);
        if (!rc && r->noisy && !nz.noisy) {
            nz.noisy = 1;
            snprintf(nz.why, sizeof nz.why, "ratio %s / %s spread %.1f%% > %.1f%%", ent[j].name, ent[b].name,
                     100 * r->spread, 100 * cfg->noise_spread);
        }
    }
    if (rc) return rc;
    R->offcpu = fmax(R->offcpu, nz.offcpu);
    R->load = fmax(R->load, nz.load);
    R->noisy_order[q] = nz.noisy;
    if (nz.noisy && !R->noisy) snprintf(R->why, sizeof R->why, "order %d: %s", R->a->orders.v[q], nz.why);
    R->noisy |= nz.noisy;
    return 0;
}

/* Every order in turn: its entries made, timed (or their instructions
 * counted under callgrind) and freed.  A library status on failure. */
static int measure(bench_run *R)
{
    const bench_args *a = R->a;
    const int no = a->orders.n, ne = R->ne, S = R->bo.repeat;
    sh_bench_entry *ent = calloc((size_t)ne, sizeof *ent);
    double *smp = malloc((size_t)ne * S * sizeof *smp), *ins = malloc((size_t)ne * sizeof *ins);
    int *idx = malloc((size_t)ne * sizeof *idx);
    sh_bench_stats *st = malloc((size_t)ne * sizeof *st);
    if (!ent || !smp || !ins || !idx || !st) {
        free(ent), free(smp), free(ins), free(idx), free(st);
        return sh_error(SH_ENOMEM, "bench: out of memory");
    }
    cli_progress prog;
    cli_progress_start(&prog, "bench", a->quiet);
    round_progress rp = {&prog, 0, no * S};
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.samples = S;
    cfg.count = R->bo.count;
    cfg.min_sample_ms = R->bo.target_ms;
    cfg.progress = on_round;
    cfg.progress_ctx = &rp;
    int rc = SH_OK;
    for (int q = 0; q < no && !rc; q++) {
        int n = 0;
        rc = make_entries(R, q, ent, idx, &n, &prog);
        rp.base = q * S;
        if (!rc && a->instructions) {
            rc = sh_bench_instructions(ent, n, R->bo.count, R->cg_out, ins);
            for (int j = 0; j < n; j++) R->ins[(size_t)q * ne + idx[j]] = ins[j];
        } else if (!rc)
            rc = time_order(R, q, ent, idx, n, &cfg, smp, st);
        for (int i = 0; i < ne; i++) sh_bench_entry_free(&ent[i]);
        memset(ent, 0, (size_t)ne * sizeof *ent);
    }
    free(ent), free(smp), free(ins), free(idx), free(st);
    if (!rc && !a->instructions) R->setup = sh_rot_bench_setup_ns(&R->bo);
    return rc;
}

/* Row x (entry i of order q). */
static json_t *row_json(const bench_run *R, int q, int i)
{
    const bench_args *a = R->a;
    const bench_slot *s = &R->slot[i];
    const int x = q * R->ne + i, batch = s->md == MD_BATCHED || s->md == MD_KROT ? R->bo.batch : 1;
    json_t *row = json_object();
    row = cli_put(row, "method", json_string(sh_rot_method_name(a->methods.v[s->k])));
    row = cli_put(row, "order", json_integer(a->orders.v[q]));
    row = cli_put(row, "precision", json_string(sh_precision_name(a->prec)));
    row = cli_put(row, "mode", json_string(mode_name[s->md]));
    if (a->instructions) {
        row = cli_put(row, "kernel", json_string(sh_rot_kernel_name(R->used[x])));
        row = cli_put(row, "input", json_string(sh_bench_input_name((sh_bench_input)s->in)));
        row = cli_put(row, "instructions", json_real(R->ins[x]));
        row = cli_put(row, "mults", json_real(R->mults[x]));
        return cli_put(row, "batch", json_integer(batch));
    }
    const sh_bench_stats *t = &R->st[x];
    const int has_ratio = !isnan(R->rat[x].median); /* its baseline reaches this order */
    char rto[96];
    slot_name(R, &R->slot[s->base], R->used[q * R->ne + s->base], rto, sizeof rto);
    row = cli_put(row, "ns_per_rotation", json_real(t->ns_median));
    row = cli_put(row, "ns_median", json_real(t->ns_median));
    row = cli_put(row, "ns_min", json_real(t->ns_min));
    row = cli_put(row, "ns_max", json_real(t->ns_max));
    row = cli_put(row, "mults", json_real(R->mults[x]));
    row = cli_put(row, "mults_per_ns", json_real(t->ns_median > 0 ? R->mults[x] / t->ns_median : 0));
    row = cli_put(row, "count", json_integer(t->count));
    row = cli_put(row, "batch", json_integer(batch));
    row = cli_put(row, "kernel", json_string(sh_rot_kernel_name(R->used[x])));
    row = cli_put(row, "input", json_string(sh_bench_input_name((sh_bench_input)s->in)));
    row = cli_put(row, "ns_q1", json_real(t->ns_q1));
    row = cli_put(row, "ns_q3", json_real(t->ns_q3));
    row = cli_put(row, "spread", json_real(t->spread));
    row = cli_put(row, "sample_ms", json_real(t->sample_ms));
    row = cli_put(row, "ratio_to", has_ratio ? json_string(rto) : json_null());
    row = cli_put(row, "ratio", has_ratio ? json_real(R->rat[x].median) : json_null());
    row = cli_put(row, "ratio_q1", has_ratio ? json_real(R->rat[x].q1) : json_null());
    row = cli_put(row, "ratio_q3", has_ratio ? json_real(R->rat[x].q3) : json_null());
    return cli_put(row, "noisy_order", json_boolean(R->noisy_order[q]));
}

/* The result: the run's fields and the rows, method by method, order by
 * order, in slot order. */
static json_t *result(const bench_run *R)
{
    const bench_args *a = R->a;
    json_t *rows = json_array();
    for (int k = 0; k < a->methods.n && rows; k++)
        for (int q = 0; q < a->orders.n && rows; q++)
            for (int i = 0; i < R->ne && rows; i++) {
                if (R->slot[i].k != k || !present(R, q, i)) continue;
                json_t *row = row_json(R, q, i);
                if (!row || json_array_append_new(rows, row)) {
                    json_decref(rows);
                    rows = NULL;
                }
            }
    json_t *root = json_object();
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    if (a->instructions) {
        root = cli_put(root, "tool", json_string("callgrind"));
        root = cli_put(root, "n", json_integer(R->bo.count));
    } else {
        root = cli_put(root, "repeat", json_integer(R->bo.repeat));
        root = cli_put(root, "min_sample_ms", json_real(R->bo.target_ms));
        root = cli_put(root, "setup_ns", json_real(R->setup));
        root = cli_put(root, "noisy", json_boolean(R->noisy));
        root = cli_put(root, "noise", json_string(R->why));
        root = cli_put(root, "offcpu", json_real(R->offcpu));
        root = cli_put(root, "load", json_real(R->load));
    }
    return cli_put(root, "rows", rows);
}

/* The room for the results of every order. */
static int alloc_results(bench_run *R)
{
    const size_t n = (size_t)R->ne * R->a->orders.n;
    R->used = calloc(n, sizeof *R->used);
    R->st = calloc(n, sizeof *R->st);
    R->rat = calloc(n, sizeof *R->rat);
    R->ins = calloc(n, sizeof *R->ins);
    R->mults = calloc(n, sizeof *R->mults);
    R->noisy_order = calloc((size_t)R->a->orders.n, sizeof *R->noisy_order);
    if (!R->used || !R->st || !R->rat || !R->ins || !R->mults || !R->noisy_order) return cli_fail("out of memory");
    return 0;
}

/* --instructions: under valgrind (SHLAB_CALLGRIND_OUT names the file), or
 * this command line run again under it; 1 in *rerun when it was. */
static int instructions_setup(bench_run *R, int argc, char **argv, int *rerun)
{
    *rerun = 0;
    if (!R->a->instructions) return 0;
#if defined(__SANITIZE_ADDRESS__)
    /* valgrind cannot run a program built with AddressSanitizer */
    return cli_fail("bench --instructions: not available in a sanitizer build (valgrind cannot run it)");
#endif
    R->cg_out = getenv("SHLAB_CALLGRIND_OUT");
    if (!(R->cg_out && *R->cg_out)) {
        *rerun = 1;
        return rerun_under_callgrind(argc, argv);
    }
    if (R->bo.count == 0) R->bo.count = 64;
    return 0;
}

static int run(int argc, char **argv)
{
    for (int k = 1; k < argc; k++)
        if (!strcmp(argv[k], "--peers")) return cli_bench_peers(&cmd_bench, argc, argv);
    for (int k = 1; k < argc; k++)
        if (!strcmp(argv[k], "--plugin")) return cli_bench_plugin(&cmd_bench, argc, argv);
    for (int k = 1; k < argc; k++)
        if (!strcmp(argv[k], "--shader")) return cli_bench_shader(&cmd_bench, argc, argv);
    bench_args a = {.max_beta = M_PI, .base = {SH_ROT_Z, -1, -1, -1}};
    cli_parsed seen;
    int rc = cli_args_parse(&bench_decl, argc, argv, &a, &seen), rerun;
    if (rc >= 0) return rc;
    bench_run R = {.a = &a, .bo = SH_BENCH_OPTS_DEFAULT, .load = -1};
    R.bo.repeat = a.repeat;
    R.bo.count = a.count;
    R.bo.batch = a.batch;
    R.bo.target_ms = a.target_ms;
    R.bo.seed = (uint64_t)a.seed;
    R.bo.conv = (sh_convention)a.conv;
    if ((rc = validate(&a, &seen, &R.bo)) || (rc = make_slots(&R)) || (rc = instructions_setup(&R, argc, argv, &rerun)) ||
        rerun || (rc = check_memory(&R)) || (rc = alloc_results(&R)) || (rc = check_plans(&R))) {
        run_free(&R);
        return rc;
    }
    const int st = measure(&R);
    json_t *root = st ? NULL : result(&R);
    run_free(&R);
    if (st) return cli_fail_status(st);
    if (R.noisy && !a.instructions) cli_warn("bench: noisy run (%s); do not draw conclusions from it", R.why);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_bench = {"bench", run,
                               "time per rotation of the rotation methods and kernels (interleaved, "
                               "paired ratios, noise check), counted multiplications and instructions", &bench_decl};
