/* rotation_bench.c — timing of the SH rotation methods (`shlab bench`, the
 * Table 1 and frontier experiments, `shlab plan`).
 *
 * References
 *  [1] J. Křivánek, J. Konttinen, S. Pattanaik, K. Bouatouch, J. Žára, "Fast
 *      Approximation to Spherical Harmonic Rotation", SCCG 2006 (tech. report
 *      2005), Sec. 3.1 (operation counts) and Table 1 (time per rotation in
 *      radiance caching: a 3×3 frame rotation per cache record and colour
 *      channel, then one vector rotated).
 *  [2] docs/CONVENTIONS.md, "Rotations".
 *
 * What is timed.  Per rotation (the radiance-caching use of [1]): for each of
 * `count` iterations, one seeded orthonormal matrix R_k (from a pool of
 * SH_BENCH_POOL) becomes an sh_rotation (R copied, ZYZ angles extracted by
 * sh_euler_from_matrix — no SVD: the user's frame is orthonormal by
 * construction), sh_rot_plan_set, and sh_rot_plan_apply to one vector of the
 * pool.  Batched: per iteration one set and `batch` applies; the time is
 * divided by batch (ns per rotated vector).  Vectors and matrices are drawn
 * once, before timing; outputs are summed into a checksum after each repeat
 * so that no work can be optimised away.  A warm-up repeat (untimed) goes
 * first; then `repeat` timed repeats, CLOCK_MONOTONIC around each; the
 * result is the median, min and max over repeats of ns per vector.
 *
 * Counted work: sh_rot_plan_mults after the last set/apply (the kernels
 * count their own multiplications in their loops), per rotated vector.
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define SH_BENCH_POOL 64

const char *sh_bench_mode_name(sh_bench_mode m)
{
    return m == SH_BENCH_BATCHED ? "batched" : m == SH_BENCH_KROT ? "k-rotations" : "per-rotation";
}

const char *sh_bench_input_name(sh_bench_input i)
{
    return i == SH_BENCH_INPUT_MATRIX ? "matrix" : "euler";
}

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

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

typedef struct {
    int order, nc, batch;
    sh_bench_mode mode;
    sh_rot_plan *p;
    double (*R)[9];  /* pool of matrices */
    double *vin, *vout;
    double sink;
    /* matrix input and k-rotations (bench_pool_matrix): the pool in float,
     * and `batch` matrices and vectors as structure of arrays */
    int input, fl;
    float (*Rf)[9];
    float *vinf, *voutf;
    void *Rs, *xs, *ys;
} bench_ctx;

static int bench_pool(bench_ctx *b, const sh_bench_opts *o, int zonly)
{
    uint64_t s = o->seed ? o->seed : 12345u;
    const double bmax = zonly ? 0.0 : o->max_beta;
    b->R = malloc(SH_BENCH_POOL * sizeof *b->R);
    b->vin = malloc((size_t)SH_BENCH_POOL * b->nc * sizeof *b->vin);
    b->vout = malloc((size_t)b->nc * sizeof *b->vout);
    if (!b->R || !b->vin || !b->vout) return sh_error(SH_ENOMEM, "bench: out of memory");
    for (int k = 0; k < SH_BENCH_POOL; k++) {
        sh_rotation r;
        const double a = M_PI * (2 * urand(&s) - 1), g = M_PI * (2 * urand(&s) - 1);
        const double be = bmax * urand(&s);
        sh_rotation_from_euler(a, be, g, &r);
        memcpy(b->R[k], r.R, sizeof r.R);
    }
    for (size_t i = 0; i < (size_t)SH_BENCH_POOL * b->nc; i++) b->vin[i] = 2 * urand(&s) - 1;
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
    for (int k = 0; k < SH_BENCH_POOL; k++)
        for (int j = 0; j < 9; j++) b->Rf[k][j] = (float)b->R[k][j];
    for (size_t i = 0; i < (size_t)SH_BENCH_POOL * nc; i++) b->vinf[i] = (float)b->vin[i];
    for (size_t k = 0; k < K; k++) {
        const size_t q = k & (SH_BENCH_POOL - 1);
        for (int j = 0; j < 9; j++) {
            if (b->fl) ((float *)b->Rs)[(size_t)j * K + k] = b->Rf[q][j];
            else ((double *)b->Rs)[(size_t)j * K + k] = b->R[q][j];
        }
        for (size_t i = 0; i < nc; i++) {
            if (b->fl) ((float *)b->xs)[i * K + k] = b->vinf[q * nc + i];
            else ((double *)b->xs)[i * K + k] = b->vin[q * nc + i];
        }
    }
    return SH_OK;
}

static void bench_free(bench_ctx *b)
{
    free(b->R), free(b->vin), free(b->vout);
    free(b->Rf), free(b->vinf), free(b->voutf), free(b->Rs), free(b->xs), free(b->ys);
}

/* Matrix input (set_matrix, vectors in the plan's precision; batched: one
 * apply_many) and k-rotations (one rotate_many of the batch); `count`
 * iterations. */
static int bench_run_matrix(bench_ctx *b, int count)
{
    int st = SH_OK;
    const size_t nc = (size_t)b->nc, K = (size_t)b->batch;
    for (int it = 0; it < count; it++) {
        const int k = it & (SH_BENCH_POOL - 1);
        if (b->mode == SH_BENCH_KROT) {
            if (b->fl) st |= sh_rot_plan_rotate_many_f(b->p, K, b->Rs, b->xs, b->ys);
            else st |= sh_rot_plan_rotate_many(b->p, K, b->Rs, b->xs, b->ys);
        } else if (b->fl) {
            st |= sh_rot_plan_set_matrix_f(b->p, b->Rf[k]);
            if (b->mode == SH_BENCH_BATCHED) st |= sh_rot_plan_apply_many_f(b->p, K, b->xs, b->ys);
            else st |= sh_rot_plan_apply_f(b->p, b->vinf + k * nc, b->voutf);
        } else {
            st |= sh_rot_plan_set_matrix(b->p, b->R[k]);
            if (b->mode == SH_BENCH_BATCHED) st |= sh_rot_plan_apply_many(b->p, K, b->xs, b->ys);
            else st |= sh_rot_plan_apply(b->p, b->vin + k * nc, b->vout);
        }
        const size_t i = (size_t)it % nc;
        if (b->mode == SH_BENCH_PER_ROTATION) b->sink += b->fl ? (double)b->voutf[i] : b->vout[i];
        else b->sink += b->fl ? (double)((float *)b->ys)[i * K] : ((double *)b->ys)[i * K];
    }
    return st;
}

/* The user's step: an orthonormal frame becomes an sh_rotation. */
static inline void rot_from_frame(const double R[9], sh_rotation *r)
{
    memcpy(r->R, R, sizeof r->R);
    sh_euler_from_matrix(R, &r->alpha, &r->beta, &r->gamma);
}

/* `count` iterations; returns elapsed ns (or < 0 on a library error). */
static double bench_run(bench_ctx *b, int count)
{
    sh_rotation r;
    int st = SH_OK;
    const size_t nc = (size_t)b->nc;
    const double t0 = now_ns();
    if (b->input == SH_BENCH_INPUT_MATRIX || b->mode == SH_BENCH_KROT) {
        st = bench_run_matrix(b, count);
    } else if (b->mode == SH_BENCH_PER_ROTATION) {
        for (int it = 0; it < count; it++) {
            const int k = it & (SH_BENCH_POOL - 1);
            rot_from_frame(b->R[k], &r);
            st |= sh_rot_plan_set(b->p, &r);
            st |= sh_rot_plan_apply(b->p, b->vin + k * nc, b->vout);
            b->sink += b->vout[it % nc];
        }
    } else {
        for (int it = 0; it < count; it++) {
            rot_from_frame(b->R[it & (SH_BENCH_POOL - 1)], &r);
            st |= sh_rot_plan_set(b->p, &r);
            for (int v = 0; v < b->batch; v++) {
                st |= sh_rot_plan_apply(b->p, b->vin + (size_t)(v & (SH_BENCH_POOL - 1)) * nc, b->vout);
                b->sink += b->vout[v % nc];
            }
        }
    }
    const double t1 = now_ns();
    return st ? -1.0 : t1 - t0;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int sh_rot_bench(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                 const sh_bench_opts *opts, sh_bench_result *res)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    const sh_bench_opts *o = opts ? opts : &def;
    if (o->repeat < 1 || o->count < 0 || o->batch < 1 || !(o->target_ms >= 0) || !(o->max_beta >= 0 && o->max_beta <= M_PI))
        return sh_error(SH_EINVAL, "bench: need repeat >= 1, count >= 0, batch >= 1, max beta in [0, pi]");
    if (mode != SH_BENCH_PER_ROTATION && mode != SH_BENCH_BATCHED && mode != SH_BENCH_KROT)
        return sh_error(SH_EINVAL, "bench: unknown mode");
    if (o->input != SH_BENCH_INPUT_EULER && o->input != SH_BENCH_INPUT_MATRIX)
        return sh_error(SH_EINVAL, "bench: unknown input");
    memset(res, 0, sizeof *res);
    bench_ctx b = {.order = order, .nc = order * order, .batch = mode == SH_BENCH_PER_ROTATION ? 1 : o->batch,
                   .mode = mode, .input = o->input, .fl = prec == SH_PREC_FLOAT};
    if (o->conv != SH_CS && o->conv != SH_NOCS) return sh_error(SH_EINVAL, "bench: unknown convention");
    int st = sh_rot_plan_create_kernel(order, method, prec, o->conv, o->kernel, &b.p);
    if (st) return st;
    double *t = malloc((size_t)o->repeat * sizeof *t);
    if (!t) st = sh_error(SH_ENOMEM, "bench: out of memory");
    if (!st) st = bench_pool(&b, o, method == SH_ROT_Z);
    if (!st && (b.input == SH_BENCH_INPUT_MATRIX || mode == SH_BENCH_KROT)) st = bench_pool_matrix(&b);
    int count = o->count;
    if (!st && count == 0) {
        /* calibrate: double the count until one run takes ≥ 1 ms (or the
         * target), then scale to the target */
        const double target = (o->target_ms > 0 ? o->target_ms : 5.0) * 1e6;
        count = 1;
        double e;
        for (;;) {
            e = bench_run(&b, count);
            if (e < 0) break;
            if (e >= 1e6 || e >= target || count >= (1 << 26)) break;
            count *= 2;
        }
        if (e < 0) st = sh_error(SH_EINVAL, "bench: %s failed", sh_rot_method_name(method));
        else {
            const double c = count * target / (e > 0 ? e : 1);
            count = c < 1 ? 1 : c > (double)(1 << 28) ? (1 << 28) : (int)c;
        }
    }
    if (!st && bench_run(&b, count) < 0) /* warm-up */
        st = sh_error(SH_EINVAL, "bench: %s failed", sh_rot_method_name(method));
    for (int r = 0; !st && r < o->repeat; r++) {
        const double e = bench_run(&b, count);
        if (e < 0) st = sh_error(SH_EINVAL, "bench: %s failed", sh_rot_method_name(method));
        t[r] = e / ((double)count * b.batch);
    }
    if (!st) {
        qsort(t, (size_t)o->repeat, sizeof *t, cmp_double);
        const int R = o->repeat;
        res->ns_median = R & 1 ? t[R / 2] : 0.5 * (t[R / 2 - 1] + t[R / 2]);
        res->ns_min = t[0];
        res->ns_max = t[R - 1];
        sh_rot_plan_mults(b.p, &res->set_mults, &res->apply_mults);
        /* batched: one set per batch; k-rotations: one per vector */
        res->mults = (double)res->set_mults / (mode == SH_BENCH_BATCHED ? b.batch : 1) + (double)res->apply_mults;
        res->mults_per_ns = res->ns_median > 0 ? res->mults / res->ns_median : 0;
        res->count = count;
        res->checksum = isfinite(b.sink) ? b.sink : 0;
    }
    free(t);
    bench_free(&b);
    sh_rot_plan_free(b.p);
    return st;
}

double sh_rot_bench_setup_ns(const sh_bench_opts *opts)
{
    const sh_bench_opts def = SH_BENCH_OPTS_DEFAULT;
    const sh_bench_opts *o = opts ? opts : &def;
    bench_ctx b = {.order = 1, .nc = 1, .batch = 1, .mode = SH_BENCH_PER_ROTATION};
    if (bench_pool(&b, o, 0)) {
        free(b.R); free(b.vin); free(b.vout);
        return 0;
    }
    const int count = 1 << 16, R = o->repeat > 0 ? o->repeat : 5;
    double best[64];
    const int nr = R < 64 ? R : 64;
    volatile double sink = 0;
    for (int r = -1; r < nr; r++) {
        sh_rotation rot;
        const double t0 = now_ns();
        for (int it = 0; it < count; it++) {
            rot_from_frame(b.R[it & (SH_BENCH_POOL - 1)], &rot);
            sink += rot.alpha + rot.beta + rot.gamma;
        }
        if (r >= 0) best[r] = (now_ns() - t0) / count;
    }
    (void)sink;
    qsort(best, (size_t)nr, sizeof *best, cmp_double);
    free(b.R); free(b.vin); free(b.vout);
    return nr & 1 ? best[nr / 2] : 0.5 * (best[nr / 2 - 1] + best[nr / 2]);
}
