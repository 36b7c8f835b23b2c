/* bench.c — timing of the SH rotation methods (`shlab bench`, the
 * Table 1 and frontier experiments, `shlab plan`): an interleaved timing
 * engine over a table of entries, the rotation entries, and instruction
 * counts under valgrind.
 *
 * References
 *  [1] J. Křivánek, J. Konttinen, S. Pattanaik, K. Bouatouch, J. Žára, "Fast
 *      Approximation to Spherical Harmonic Rotation", SCCG 2006 (tech. report
 *      2005), Sec. 3.1 (operation counts) and Table 1 (time per rotation in
 *      radiance caching: a 3×3 frame rotation per cache record and colour
 *      channel, then one vector rotated).
 *  [2] docs/CONVENTIONS.md, "Rotations".
 *
 * What is timed.  Per rotation (the radiance-caching use of [1]): for each
 * iteration, one seeded orthonormal matrix R_k (from a pool of
 * SH_BENCH_POOL) becomes an sh_rotation (R copied, ZYZ angles extracted by
 * sh_euler_from_matrix — no SVD: the user's frame is orthonormal by
 * construction), sh_rot_plan_set, and sh_rot_plan_apply to one vector of the
 * pool.  Batched: per iteration one set and `batch` applies (units = batch:
 * times are per rotated vector).  Matrix input (sh_bench_opts.input): the
 * frame goes straight to sh_rot_plan_set_matrix(_f) (no angles), vectors in
 * the plan's precision, a batch through one apply_many.  K rotations
 * (SH_BENCH_KROT): per iteration one sh_rot_plan_rotate_many(_f) of `batch`
 * matrices and vectors laid out as structure of arrays (units = batch).  Vectors and matrices are drawn once,
 * before timing; outputs are summed into a sink so that no work can be
 * optimised away.
 *
 * How it is timed (sh_bench_interleaved, measure.h): every entry compared is
 * calibrated to samples of at least min_sample_ms, warmed up, and then timed
 * once per round, round-robin, for `samples` rounds; results are the
 * min/quartiles/max over the samples, ratios are medians of per-round
 * ratios, and the run is judged against the noise criterion of measure.h.
 *
 * Counted work: sh_rot_plan_mults after the last set/apply (the kernels
 * count their own multiplications in their loops), per rotated vector.
 */
#include "lab/lab.h"

#include "core/shlab_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SH_HAVE_CALLGRIND 1
#endif
#endif


const char *sh_bench_mode_name(sh_bench_mode m)
{
    return m == SH_BENCH_BATCHED ? "batched" : m == SH_BENCH_KROT ? "k-rotations" : "per-rotation";
}

const char *sh_bench_input_name(sh_bench_input i)
{
    return i == SH_BENCH_INPUT_MATRIX ? "matrix" : i == SH_BENCH_INPUT_QUAT ? "quat" : "euler";
}

static double clock_ns(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}
static double now_ns(void) { return clock_ns(CLOCK_MONOTONIC); }

/* xorshift64* — deterministic, independent of libc's rand */
static double urand(uint64_t *s)
{
    uint64_t x = *s;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *s = x;
    return (double)((x * 0x2545F4914F6CDD1DULL) >> 11) * (1.0 / 9007199254740992.0);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Quantile q of sorted x[0..n) by linear interpolation between order
 * statistics at position q(n − 1) (Hyndman & Fan type 7, R's default). */
static double quantile(const double *x, int n, double q)
{
    if (n == 1) return x[0];
    const double p = q * (n - 1);
    const int i = (int)floor(p);
    if (i >= n - 1) return x[n - 1];
    return x[i] + (p - i) * (x[i + 1] - x[i]);
}

/* ---------------------------------------------------- the timing engine */

/* CPU time used by the whole machine (busy jiffies of /proc/stat's "cpu"
 * line, steal included) and by this process, in seconds; < 0 if unknown. */
double sh_machine_busy_s(void)
{
    FILE *f = fopen("/proc/stat", "r");
    if (!f) return -1;
    unsigned long long v[8] = {0};
    const int n = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4],
                         &v[5], &v[6], &v[7]);
    fclose(f);
    if (n < 4) return -1;
    const long hz = sysconf(_SC_CLK_TCK);
    /* user nice system idle iowait irq softirq steal: all but idle, iowait */
    const unsigned long long busy = v[0] + v[1] + v[2] + v[5] + v[6] + v[7];
    return hz > 0 ? (double)busy / (double)hz : -1;
}
static double self_cpu_s(void)
{
    struct rusage u;
    if (getrusage(RUSAGE_SELF, &u)) return -1;
    return (double)u.ru_utime.tv_sec + (double)u.ru_stime.tv_sec + 1e-6 * ((double)u.ru_utime.tv_usec + (double)u.ru_stime.tv_usec);
}

/* One timed run of an entry: wall and thread-CPU ns (the CPU clock is read
 * outside the wall interval, so cpu ≥ wall when nothing else ran). */
static int time_entry(const sh_bench_entry *e, long count, double *wall, double *cpu)
{
    const double c0 = clock_ns(CLOCK_THREAD_CPUTIME_ID), t0 = now_ns();
    const int st = e->run(e->ctx, count);
    const double t1 = now_ns(), c1 = clock_ns(CLOCK_THREAD_CPUTIME_ID);
    *wall = t1 - t0;
    if (cpu) *cpu = c1 - c0;
    return st;
}

/* Count so that one run lasts ≥ target ns: double it until a run takes a
 * quarter of the target, then scale (10 % margin). */
static int calibrate(const sh_bench_entry *e, double target, long *count)
{
    long c = 1;
    double el = 0;
    for (;;) {
        int st = time_entry(e, c, &el, NULL);
        if (st) return st;
        if (el >= 0.25 * target || c >= (1L << 40)) break;
        c *= el < 1e-3 * target ? 16 : 2;
    }
    const double want = ceil((double)c * 1.1 * target / (el > 0 ? el : 1));
    *count = want < 1 ? 1 : want > (double)(1L << 40) ? (1L << 40) : (long)want;
    return SH_OK;
}

static int add_why(sh_bench_noise *nz, const char *fmt, double a, double b)
{
    const size_t k = strlen(nz->why);
    snprintf(nz->why + k, sizeof nz->why - k, "%s", k ? "; " : "");
    const size_t k2 = strlen(nz->why);
    snprintf(nz->why + k2, sizeof nz->why - k2, fmt, a, b);
    return 1;
}

/* The configuration with every unset field at its default, or an error. */
static int bench_config(const sh_bench_cfg *cfg_in, sh_bench_cfg *out)
{
    const sh_bench_cfg def = SH_BENCH_CFG_DEFAULT;
    sh_bench_cfg c = cfg_in ? *cfg_in : def;
    if (!(c.min_sample_ms > 0)) c.min_sample_ms = def.min_sample_ms;
    if (c.samples <= 0) c.samples = def.samples;
    if (c.warmup < 0) c.warmup = 0;
    if (!(c.noise_spread > 0)) c.noise_spread = def.noise_spread;
    if (!(c.noise_offcpu > 0)) c.noise_offcpu = def.noise_offcpu;
    if (!(c.noise_load > 0)) c.noise_load = def.noise_load;
    if (c.count < 0 || !isfinite(c.min_sample_ms) || c.min_sample_ms > 1e5 || c.samples > 100000)
        return sh_error(SH_EINVAL, "bench: need count >= 0, min sample time <= 1e5 ms, samples <= 100000");
    *out = c;
    return SH_OK;
}

/* Iterations per sample of each entry: the fixed count, or calibrated and
 * then warmed up (a calibrated count whose warm-up ran short is raised). */
static int bench_counts(const sh_bench_entry *e, int ne, const sh_bench_cfg *c, long *count)
{
    const double target = c->min_sample_ms * 1e6;
    int rc = SH_OK;
    for (int i = 0; i < ne && !rc; i++) {
        if (c->count > 0) count[i] = c->count;
        else rc = calibrate(&e[i], target, &count[i]);
    }
    for (int w = 0; w < c->warmup && !rc; w++)
        for (int i = 0; i < ne && !rc; i++) {
            double el;
            rc = time_entry(&e[i], count[i], &el, NULL);
            if (!rc && c->count == 0 && el < target) {
                const double want = ceil((double)count[i] * 1.1 * target / (el > 0 ? el : 1));
                count[i] = want > (double)(1L << 40) ? (1L << 40) : (long)want;
            }
        }
    return rc;
}

/* The timed rounds: each round times every entry once, starting one entry
 * later than the round before (so no entry always follows the same one). */
static int bench_rounds(const sh_bench_entry *e, int ne, const sh_bench_cfg *c, const long *count, double *ns,
                        double *wall, double *cpu)
{
    const int S = c->samples;
    int rc = SH_OK;
    for (int r = 0; r < S && !rc; r++) {
        for (int k = 0; k < ne && !rc; k++) {
            const int i = (k + r) % ne;
            const size_t at = (size_t)i * S + r;
            rc = time_entry(&e[i], count[i], &wall[at], &cpu[at]);
            const double units = e[i].units > 0 ? e[i].units : 1;
            ns[at] = wall[at] / ((double)count[i] * units);
        }
        if (!rc && c->progress) c->progress(c->progress_ctx, r + 1, S, "rounds");
    }
    if (rc && sh_last_error()[0] == '\0') sh_error(rc, "bench: %s failed", e[0].name ? e[0].name : "entry");
    return rc;
}

/* Entry i's statistics over its S samples (tmp: S doubles of scratch); its
 * wall and off-CPU totals added to *wall_all, *off_all. */
static void bench_entry_stats(int i, int S, long count, const double *ns, const double *wall, const double *cpu,
                              double *tmp, sh_bench_stats *st, double *wall_all, double *off_all)
{
    double w = 0, off = 0;
    for (int r = 0; r < S; r++) {
        const size_t at = (size_t)i * S + r;
        w += wall[at];
        off += fmax(0.0, wall[at] - cpu[at]);
        tmp[r] = wall[at];
    }
    qsort(tmp, (size_t)S, sizeof *tmp, cmp_double);
    st->sample_ms = quantile(tmp, S, 0.5) * 1e-6;
    memcpy(tmp, ns + (size_t)i * S, (size_t)S * sizeof *tmp);
    qsort(tmp, (size_t)S, sizeof *tmp, cmp_double);
    st->ns_min = tmp[0];
    st->ns_q1 = quantile(tmp, S, 0.25);
    st->ns_median = quantile(tmp, S, 0.5);
    st->ns_q3 = quantile(tmp, S, 0.75);
    st->ns_max = tmp[S - 1];
    st->spread = st->ns_median > 0 ? (st->ns_q3 - st->ns_q1) / st->ns_median : 0;
    st->offcpu = w > 0 ? off / w : 0;
    st->count = count;
    *off_all += off;
    *wall_all += w;
}

/* The noise rule: the largest spread, the share of time off the CPU, and
 * the load of other processes over the run (busy CPU seconds of the machine
 * less this process's), each against its threshold. */
typedef struct {
    double worst, off_all, wall_all, seconds, busy0, busy1, self0, self1;
    int worst_i;
} bench_tally;
static void bench_noise(const sh_bench_entry *e, const sh_bench_cfg *c, const bench_tally *b, sh_bench_noise *noise)
{
    memset(noise, 0, sizeof *noise);
    noise->spread = b->worst;
    noise->offcpu = b->wall_all > 0 ? b->off_all / b->wall_all : 0;
    noise->seconds = b->seconds;
    noise->load = -1;
    if (b->busy0 >= 0 && b->busy1 >= 0 && b->self0 >= 0 && b->self1 >= 0 && b->seconds >= 0.25)
        noise->load = fmax(0.0, ((b->busy1 - b->busy0) - (b->self1 - b->self0)) / b->seconds);
    if (b->worst > c->noise_spread) {
        const size_t k = strlen(noise->why);
        snprintf(noise->why + k, sizeof noise->why - k, "spread %.1f%% > %.1f%% (%s)", 100 * b->worst,
                 100 * c->noise_spread, e[b->worst_i].name ? e[b->worst_i].name : "entry");
        noise->noisy = 1;
    }
    if (noise->offcpu > c->noise_offcpu)
        noise->noisy = add_why(noise, "off-CPU %.1f%% > %.1f%% of the sample time", 100 * noise->offcpu,
                               100 * c->noise_offcpu);
    if (noise->load > c->noise_load)
        noise->noisy = add_why(noise, "other processes used %.2f CPUs > %.2f", noise->load, c->noise_load);
}

int sh_bench_interleaved(const sh_bench_entry *e, int ne, const sh_bench_cfg *cfg_in, double *samples,
                         sh_bench_stats *st, sh_bench_noise *noise)
{
    sh_bench_cfg c = SH_BENCH_CFG_DEFAULT;
    int rc = bench_config(cfg_in, &c);
    if (rc) return rc;
    if (!e || ne < 1 || !st) return sh_error(SH_EINVAL, "bench: no entries to time");
    for (int i = 0; i < ne; i++)
        if (!e[i].run) return sh_error(SH_EINVAL, "bench: entry %d has nothing to run", i);
    const int S = c.samples;
    const size_t tot = (size_t)ne * (size_t)S;
    double *ns = samples ? samples : malloc(tot * sizeof *ns);
    double *wall = malloc(tot * sizeof *wall), *cpu = malloc(tot * sizeof *cpu);
    double *tmp = malloc((size_t)S * sizeof *tmp);
    long *count = malloc((size_t)ne * sizeof *count);
    if (!ns || !wall || !cpu || !tmp || !count) {
        rc = sh_error(SH_ENOMEM, "bench: out of memory");
        goto done;
    }
    bench_tally b = {.busy0 = sh_machine_busy_s(), .self0 = self_cpu_s()};
    const double t_start = now_ns();
    if ((rc = bench_counts(e, ne, &c, count)) || (rc = bench_rounds(e, ne, &c, count, ns, wall, cpu))) {
        if (rc && sh_last_error()[0] == '\0') sh_error(rc, "bench: %s failed", e[0].name ? e[0].name : "entry");
        goto done;
    }
    b.seconds = (now_ns() - t_start) * 1e-9;
    b.busy1 = sh_machine_busy_s();
    b.self1 = self_cpu_s();
    for (int i = 0; i < ne; i++) {
        bench_entry_stats(i, S, count[i], ns, wall, cpu, tmp, &st[i], &b.wall_all, &b.off_all);
        if (st[i].spread > b.worst) { b.worst = st[i].spread; b.worst_i = i; }
    }
    if (noise) bench_noise(e, &c, &b, noise);
done:
    if (ns != samples) free(ns);
    free(wall);
    free(cpu);
    free(tmp);
    free(count);
    return rc;
}

int sh_bench_paired_ratio(const double *a, const double *b, int n, double noise_spread, sh_bench_ratio *r)
{
    if (!a || !b || !r || n < 1) return sh_error(SH_EINVAL, "bench: paired ratio of no samples");
    double *q = malloc((size_t)n * sizeof *q);
    if (!q) return sh_error(SH_ENOMEM, "bench: out of memory");
    for (int k = 0; k < n; k++) {
        if (!(a[k] > 0 && b[k] > 0) || !isfinite(a[k]) || !isfinite(b[k])) {
            free(q);
            return sh_error(SH_EINVAL, "bench: paired ratio of a non-positive time");
        }
        q[k] = a[k] / b[k];
    }
    qsort(q, (size_t)n, sizeof *q, cmp_double);
    r->median = quantile(q, n, 0.5);
    r->q1 = quantile(q, n, 0.25);
    r->q3 = quantile(q, n, 0.75);
    r->spread = (r->q3 - r->q1) / r->median;
    r->noisy = r->spread > (noise_spread > 0 ? noise_spread : 0.05);
    free(q);
    return SH_OK;
}

void sh_bench_entry_free(sh_bench_entry *e)
{
    if (!e) return;
    if (e->free && e->ctx) e->free(e->ctx);
    memset(e, 0, sizeof *e);
}

/* ------------------------------------------------- the rotation entries */

typedef struct {
    int order, nc, batch;
    sh_bench_mode mode; /* or -1: matrix → angles only */
    sh_rot_plan *p;
    double (*R)[9];  /* pool of matrices */
    double *vin, *vout;
    double sink;
    char name[96];
    /* matrix input and k-rotations (bench_pool_matrix): the pool in float,
     * and `batch` matrices and vectors as structure of arrays */
    int input, fl;
    float (*Rf)[9];
    float *vinf, *voutf;
    void *Rs, *xs, *ys;
    /* quaternion input: the pool's rotations as (w, x, y, z), double and
     * float, and the batch's as structure of arrays (q[j·K + k]) in Rs */
    double (*Q)[4];
    float (*Qf)[4];
} bench_ctx;

static void bench_ctx_free(void *v)
{
    bench_ctx *b = v;
    if (!b) return;
    sh_rot_plan_free(b->p);
    free(b->R);
    free(b->vin);
    free(b->vout);
    free(b->Rf), free(b->vinf), free(b->voutf), free(b->Rs), free(b->xs), free(b->ys);
    free(b->Q), free(b->Qf);
    free(b);
}

void sh_bench_pool(uint64_t seed, double max_beta, int nc, double (*R)[9], double *vin)
{
    uint64_t s = seed ? seed : 12345u;
    for (int k = 0; k < SH_BENCH_POOL; k++) {
        sh_rotation r;
        const double a = M_PI * (2 * urand(&s) - 1), g = M_PI * (2 * urand(&s) - 1);
        const double be = max_beta * urand(&s);
        sh_rotation_from_euler(a, be, g, &r);
        memcpy(R[k], r.R, sizeof r.R);
    }
    for (size_t i = 0; i < (size_t)SH_BENCH_POOL * nc; i++) vin[i] = 2 * urand(&s) - 1;
}

static int bench_pool(bench_ctx *b, const sh_bench_opts *o, int zonly)
{
    b->R = malloc(SH_BENCH_POOL * sizeof *b->R);
    b->vin = malloc((size_t)SH_BENCH_POOL * b->nc * sizeof *b->vin);
    b->vout = malloc((size_t)b->nc * sizeof *b->vout);
    if (!b->R || !b->vin || !b->vout) return sh_error(SH_ENOMEM, "bench: out of memory");
    sh_bench_pool(o->seed, zonly ? 0.0 : o->max_beta, b->nc, b->R, b->vin);
    return SH_OK;
}

/* The pool for matrix input and k-rotations: float copies, and the batch
 * as structure of arrays (R[j·K + k], x[i·K + k]) in the plan's precision. */
static int bench_pool_matrix(bench_ctx *b)
{
    const size_t K = (size_t)b->batch, nc = (size_t)b->nc, es = b->fl ? sizeof(float) : sizeof(double);
    b->Rf = malloc(SH_BENCH_POOL * sizeof *b->Rf);
    b->vinf = malloc((size_t)SH_BENCH_POOL * nc * sizeof *b->vinf);
    b->voutf = malloc(nc * sizeof *b->voutf);
    b->Rs = malloc(9 * K * es);
    b->xs = malloc(nc * K * es);
    b->ys = malloc(nc * K * es);
    if (!b->Rf || !b->vinf || !b->voutf || !b->Rs || !b->xs || !b->ys) return sh_error(SH_ENOMEM, "bench: out of memory");
    const int quat = b->input == SH_BENCH_INPUT_QUAT;
    if (quat && (!(b->Q = malloc(SH_BENCH_POOL * sizeof *b->Q)) || !(b->Qf = malloc(SH_BENCH_POOL * sizeof *b->Qf))))
        return sh_error(SH_ENOMEM, "bench: out of memory");
    for (int k = 0; k < SH_BENCH_POOL; k++) {
        for (int j = 0; j < 9; j++) b->Rf[k][j] = (float)b->R[k][j];
        if (!quat) continue;
        sh_rotation r;
        memcpy(r.R, b->R[k], sizeof r.R);
        sh_rotation_to_quat(&r, b->Q[k]);
        for (int j = 0; j < 4; j++) b->Qf[k][j] = (float)b->Q[k][j];
    }
    for (size_t i = 0; i < (size_t)SH_BENCH_POOL * nc; i++) b->vinf[i] = (float)b->vin[i];
    for (size_t k = 0; k < K; k++) {
        const size_t q = k & (SH_BENCH_POOL - 1);
        for (int j = 0; j < (quat ? 4 : 9); j++) {
            if (b->fl) ((float *)b->Rs)[(size_t)j * K + k] = quat ? b->Qf[q][j] : b->Rf[q][j];
            else ((double *)b->Rs)[(size_t)j * K + k] = quat ? b->Q[q][j] : b->R[q][j];
        }
        for (size_t i = 0; i < nc; i++) {
            if (b->fl) ((float *)b->xs)[i * K + k] = b->vinf[q * nc + i];
            else ((double *)b->xs)[i * K + k] = b->vin[q * nc + i];
        }
    }
    return SH_OK;
}

/* Matrix input (set_matrix, vectors in the plan's precision; batched: one
 * apply_many) and k-rotations (one rotate_many of the batch); `count`
 * iterations.  The loop is the measured thing's only companion: the choice
 * of calls is made once, outside it, and each iteration does the calls, the
 * pool index and one output read into a local sink (index i cycling
 * through the coefficients without a division) — the same few instructions
 * for every method. */
#define BENCH_LOOP(CALLS, OUT)                                                                     \
    do {                                                                                           \
        size_t i = 0;                                                                              \
        for (long it = 0; it < count; it++) {                                                      \
            const long k = it & (SH_BENCH_POOL - 1);                                               \
            (void)k;                                                                               \
            CALLS;                                                                                 \
            sink += (double)(OUT);                                                                 \
            i = i + 1 == nc ? 0 : i + 1;                                                           \
        }                                                                                          \
    } while (0)
static int bench_run_matrix(bench_ctx *b, long count)
{
    int st = SH_OK;
    const size_t nc = (size_t)b->nc, K = (size_t)b->batch;
    sh_rot_plan *const p = b->p;
    const int quat = b->input == SH_BENCH_INPUT_QUAT;
    double sink = b->sink;
    float *const ysf = b->ys, *const voutf = b->voutf, *const vinf = b->vinf;
    double *const ysd = b->ys, *const vout = b->vout, *const vin = b->vin;
    if (b->mode == SH_BENCH_KROT) {
        if (b->fl && quat) BENCH_LOOP(st |= sh_rot_plan_rotate_many_quat_f(p, K, b->Rs, b->xs, b->ys), ysf[i * K]);
        else if (b->fl) BENCH_LOOP(st |= sh_rot_plan_rotate_many_f(p, K, b->Rs, b->xs, b->ys), ysf[i * K]);
        else if (quat) BENCH_LOOP(st |= sh_rot_plan_rotate_many_quat(p, K, b->Rs, b->xs, b->ys), ysd[i * K]);
        else BENCH_LOOP(st |= sh_rot_plan_rotate_many(p, K, b->Rs, b->xs, b->ys), ysd[i * K]);
    } else if (b->mode == SH_BENCH_BATCHED) {
        if (b->fl && quat)
            BENCH_LOOP((st |= sh_rot_plan_set_quat_f(p, b->Qf[k]), st |= sh_rot_plan_apply_many_f(p, K, b->xs, b->ys)), ysf[i * K]);
        else if (b->fl)
            BENCH_LOOP((st |= sh_rot_plan_set_matrix_f(p, b->Rf[k]), st |= sh_rot_plan_apply_many_f(p, K, b->xs, b->ys)), ysf[i * K]);
        else if (quat)
            BENCH_LOOP((st |= sh_rot_plan_set_quat(p, b->Q[k]), st |= sh_rot_plan_apply_many(p, K, b->xs, b->ys)), ysd[i * K]);
        else
            BENCH_LOOP((st |= sh_rot_plan_set_matrix(p, b->R[k]), st |= sh_rot_plan_apply_many(p, K, b->xs, b->ys)), ysd[i * K]);
    } else { /* per rotation */
        const float(*const Rf)[9] = (const float(*)[9])b->Rf;
        const float(*const Qf)[4] = (const float(*)[4])b->Qf;
        if (b->fl && quat)
            BENCH_LOOP((st |= sh_rot_plan_set_quat_f(p, Qf[k]), st |= sh_rot_plan_apply_f(p, vinf + k * nc, voutf)), voutf[i]);
        else if (b->fl)
            BENCH_LOOP((st |= sh_rot_plan_set_matrix_f(p, Rf[k]), st |= sh_rot_plan_apply_f(p, vinf + k * nc, voutf)), voutf[i]);
        else if (quat)
            BENCH_LOOP((st |= sh_rot_plan_set_quat(p, b->Q[k]), st |= sh_rot_plan_apply(p, vin + k * nc, vout)), vout[i]);
        else
            BENCH_LOOP((st |= sh_rot_plan_set_matrix(p, b->R[k]), st |= sh_rot_plan_apply(p, vin + k * nc, vout)), vout[i]);
    }
    b->sink = sink;
    return st;
}
#undef BENCH_LOOP

/* The user's step: an orthonormal frame becomes an sh_rotation. */
static inline void rot_from_frame(const double R[9], sh_rotation *r)
{
    memcpy(r->R, R, sizeof r->R);
    sh_euler_from_matrix(R, &r->alpha, &r->beta, &r->gamma);
}

/* `count` iterations (the entry's run). */
static int bench_run(void *v, long count)
{
    bench_ctx *b = v;
    sh_rotation r;
    int st = SH_OK;
    const size_t nc = (size_t)b->nc;
    if ((int)b->mode >= 0 && (b->input != SH_BENCH_INPUT_EULER || b->mode == SH_BENCH_KROT)) {
        st = bench_run_matrix(b, count);
    } else if ((int)b->mode < 0) {
        for (long it = 0; it < count; it++) {
            rot_from_frame(b->R[it & (SH_BENCH_POOL - 1)], &r);
            b->sink += r.alpha + r.beta + r.gamma;
        }
    } else if (b->mode == SH_BENCH_PER_ROTATION) {
        for (long it = 0; it < count; it++) {
            const long k = it & (SH_BENCH_POOL - 1);
            rot_from_frame(b->R[k], &r);
            st |= sh_rot_plan_set(b->p, &r);
            st |= sh_rot_plan_apply(b->p, b->vin + k * nc, b->vout);
            b->sink += b->vout[it % nc];
        }
    } else {
        for (long it = 0; it < count; it++) {
            rot_from_frame(b->R[it & (SH_BENCH_POOL - 1)], &r);
            st |= sh_rot_plan_set(b->p, &r);
            for (int v = 0; v < b->batch; v++) {
                st |= sh_rot_plan_apply(b->p, b->vin + (size_t)(v & (SH_BENCH_POOL - 1)) * nc, b->vout);
                b->sink += b->vout[v % nc];
            }
        }
    }
    if (!isfinite(b->sink)) b->sink = 0;
    return st ? sh_error(SH_EINVAL, "bench: %s failed", b->name) : SH_OK;
}

static int check_opts(const sh_bench_opts *o)
{
    if (o->repeat < 1 || o->count < 0 || o->batch < 1 || !(o->target_ms >= 0) ||
        !(o->max_beta >= 0 && o->max_beta <= M_PI))
        return sh_error(SH_EINVAL, "bench: need repeat >= 1, count >= 0, batch >= 1, max beta in [0, pi]");
    if (o->conv != SH_CS && o->conv != SH_NOCS) return sh_error(SH_EINVAL, "bench: unknown convention");
    return SH_OK;
}

int sh_rot_bench_entry(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                       const sh_bench_opts *opts, sh_bench_entry *e)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    const sh_bench_opts *o = opts ? opts : &def;
    memset(e, 0, sizeof *e);
    int st = check_opts(o);
    if (st) return st;
    if (mode != SH_BENCH_PER_ROTATION && mode != SH_BENCH_BATCHED && mode != SH_BENCH_KROT)
        return sh_error(SH_EINVAL, "bench: unknown mode");
    if (o->input != SH_BENCH_INPUT_EULER && o->input != SH_BENCH_INPUT_MATRIX && o->input != SH_BENCH_INPUT_QUAT)
        return sh_error(SH_EINVAL, "bench: unknown input");
    bench_ctx *b = calloc(1, sizeof *b);
    if (!b) return sh_error(SH_ENOMEM, "bench: out of memory");
    b->order = order;
    b->nc = order * order;
    b->batch = mode == SH_BENCH_PER_ROTATION ? 1 : o->batch;
    b->mode = mode;
    b->input = o->input;
    b->fl = prec == SH_PREC_FLOAT;
    if (!(st = sh_rot_plan_create_kernel(order, method, prec, o->conv, o->kernel, &b->p)))
        snprintf(b->name, sizeof b->name, "%s order %d %s%s%s %s", sh_rot_method_name(method), order,
                 sh_bench_mode_name(mode), o->input == SH_BENCH_INPUT_MATRIX ? " from a matrix"
                                          : o->input == SH_BENCH_INPUT_QUAT ? " from a quaternion" : "",
                 prec == SH_PREC_FLOAT ? " float" : "", sh_rot_kernel_name(sh_rot_plan_kernel(b->p)));
    if (st || (st = bench_pool(b, o, method == SH_ROT_Z)) ||
        ((b->input != SH_BENCH_INPUT_EULER || mode == SH_BENCH_KROT) && (st = bench_pool_matrix(b))) ||
        (st = bench_run(b, 1))) {
        bench_ctx_free(b);
        return st;
    }
    uint64_t sm, am;
    sh_rot_plan_mults(b->p, &sm, &am);
    /* batched: one set per batch; k-rotations: one set per vector */
    const double set_per_unit = mode == SH_BENCH_BATCHED ? (double)sm / b->batch : (double)sm;
    *e = (sh_bench_entry){b->name, bench_run, bench_ctx_free, b, b->batch, set_per_unit + (double)am};
    return SH_OK;
}

double sh_rot_bench_entry_bytes(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                                const sh_bench_opts *opts)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    const sh_bench_opts *o = opts ? opts : &def;
    const double nc = (double)order * order, es = prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    const double K = mode == SH_BENCH_PER_ROTATION ? 1 : o->batch;
    /* bench_ctx_new's pieces: the plan, bench_pool, bench_pool_matrix */
    double b = sizeof(bench_ctx) + (double)sh_rot_plan_bytes(order, method, prec);
    b += SH_BENCH_POOL * (9 + nc) * sizeof(double) + nc * sizeof(double);
    if (o->input != SH_BENCH_INPUT_EULER || mode == SH_BENCH_KROT)
        b += SH_BENCH_POOL * (9 + nc) * sizeof(float) + nc * sizeof(float) + K * (9 + 2 * nc) * es;
    if (o->input == SH_BENCH_INPUT_QUAT) b += SH_BENCH_POOL * 4 * (sizeof(double) + sizeof(float));
    return b;
}

int sh_rot_bench_setup_entry(const sh_bench_opts *opts, sh_bench_entry *e)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    const sh_bench_opts *o = opts ? opts : &def;
    memset(e, 0, sizeof *e);
    bench_ctx *b = calloc(1, sizeof *b);
    if (!b) return sh_error(SH_ENOMEM, "bench: out of memory");
    b->order = b->nc = b->batch = 1;
    b->mode = (sh_bench_mode)-1;
    snprintf(b->name, sizeof b->name, "matrix to angles");
    const int st = bench_pool(b, o, 0);
    if (st) {
        bench_ctx_free(b);
        return st;
    }
    *e = (sh_bench_entry){b->name, bench_run, bench_ctx_free, b, 1, 0};
    return SH_OK;
}

/* One entry through the engine, with sh_bench_opts' meaning of the fields
 * (repeat = samples, target_ms = shortest sample, count fixed if > 0). */
static int bench_one(sh_bench_entry *e, const sh_bench_opts *o, sh_bench_stats *s, sh_bench_noise *nz)
{
    sh_bench_cfg c = SH_BENCH_CFG_DEFAULT;
    c.samples = o->repeat;
    c.count = o->count;
    c.min_sample_ms = o->target_ms > 0 ? o->target_ms : 5.0;
    return sh_bench_interleaved(e, 1, &c, NULL, s, nz);
}

int sh_rot_bench(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                 const sh_bench_opts *opts, sh_bench_result *res)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    const sh_bench_opts *o = opts ? opts : &def;
    memset(res, 0, sizeof *res);
    sh_bench_entry e;
    int st = sh_rot_bench_entry(order, method, prec, mode, o, &e);
    if (st) return st;
    sh_bench_stats s;
    sh_bench_noise nz;
    if (!(st = bench_one(&e, o, &s, &nz))) {
        const bench_ctx *b = e.ctx;
        res->ns_median = s.ns_median;
        res->ns_min = s.ns_min;
        res->ns_max = s.ns_max;
        res->ns_q1 = s.ns_q1;
        res->ns_q3 = s.ns_q3;
        res->spread = s.spread;
        res->sample_ms = s.sample_ms;
        res->noisy = nz.noisy;
        sh_rot_plan_mults(b->p, &res->set_mults, &res->apply_mults);
        res->mults = e.mults;
        res->mults_per_ns = res->ns_median > 0 ? res->mults / res->ns_median : 0;
        res->count = s.count > (1L << 30) ? (1 << 30) : (int)s.count;
        res->checksum = b->sink;
    }
    sh_bench_entry_free(&e);
    return st;
}

double sh_rot_bench_setup_ns(const sh_bench_opts *opts)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    sh_bench_opts o = opts ? *opts : def;
    sh_bench_entry e;
    if (sh_rot_bench_setup_entry(&o, &e)) return 0;
    if (o.repeat < 1) o.repeat = 5;
    sh_bench_stats s;
    const int st = bench_one(&e, &o, &s, NULL);
    sh_bench_entry_free(&e);
    return st ? 0 : s.ns_median;
}

/* ------------------------------------------- instructions under callgrind */

#ifdef SH_HAVE_CALLGRIND
/* Read back the "summary:" of the dump whose trigger is `label`. */
static int read_dump(FILE *f, const char *label, double *out)
{
    char line[512], want[128];
    snprintf(want, sizeof want, "desc: Trigger: Client Request: %s", label);
    int found = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!found) found = !strcmp(line, want);
        else if (!strncmp(line, "summary:", 8) || !strncmp(line, "totals:", 7)) {
            *out = strtod(strchr(line, ':') + 1, NULL);
            return SH_OK;
        }
    }
    return sh_error(SH_EFORMAT, "bench: no callgrind dump '%s' in the callgrind output", label);
}
#endif

int sh_bench_instructions(const sh_bench_entry *e, int ne, long n, const char *callgrind_out, double *ins)
{
    if (!e || ne < 1 || n < 1 || !callgrind_out || !ins) return sh_error(SH_EINVAL, "bench: instructions: bad arguments");
#ifndef SH_HAVE_CALLGRIND
    return sh_error(SH_ENOTSUP, "bench: instructions: built without valgrind's callgrind.h");
#else
    if (!RUNNING_ON_VALGRIND) return sh_error(SH_ENOTSUP, "bench: instructions: not running under valgrind");
    static int calls; /* dump labels are unique within the process */
    const int call = ++calls;
    char label[64];
    int st = SH_OK;
    CALLGRIND_START_INSTRUMENTATION;
    for (int i = 0; i < ne && !st; i++) {
        st = e[i].run(e[i].ctx, n); /* warm-up: lazy binding, first touches */
        CALLGRIND_ZERO_STATS;
        if (!st) st = e[i].run(e[i].ctx, n);
        snprintf(label, sizeof label, "shlab-bench %d.%d n", call, i);
        CALLGRIND_DUMP_STATS_AT(label);
        if (!st) st = e[i].run(e[i].ctx, 2 * n);
        snprintf(label, sizeof label, "shlab-bench %d.%d 2n", call, i);
        CALLGRIND_DUMP_STATS_AT(label);
    }
    CALLGRIND_STOP_INSTRUMENTATION;
    if (st) return st;
    FILE *f = fopen(callgrind_out, "r");
    if (!f) return sh_error(SH_EIO, "bench: cannot read the callgrind output '%s'", callgrind_out);
    for (int i = 0; i < ne && !st; i++) {
        double a = 0, b = 0;
        snprintf(label, sizeof label, "shlab-bench %d.%d n", call, i);
        if (!(st = read_dump(f, label, &a))) {
            snprintf(label, sizeof label, "shlab-bench %d.%d 2n", call, i);
            st = read_dump(f, label, &b);
        }
        ins[i] = (b - a) / ((double)n * (e[i].units > 0 ? e[i].units : 1));
    }
    fclose(f);
    return st;
#endif
}
