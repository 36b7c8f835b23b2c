/* rotation_kernels — the speed of the rotation kernels at low orders, as
 * ratios measured interleaved in one process: the loop kernels as every
 * earlier shlab ran them (a 3×3 matrix → ZYZ angles → set → apply, vectors
 * as double) against the unrolled and SIMD kernels (rot_fast.c) from the
 * matrix (sh_rot_plan_set_matrix, no trigonometric call), one rotation at a
 * time, one rotation applied to K vectors (apply_many) and K rotations of K
 * vectors (rotate_many), in float and double.
 *
 * Method.  Every variant is a loop of `count` iterations over a pool of 64
 * seeded rotations and vectors, count calibrated once to ≈ 1 ms.  Then
 * ROUNDS rounds; in each round every variant runs once (the order reversed
 * every other round), so all variants of a round share the machine's load
 * of that moment.  Reported: the median and minimum over rounds of ns per
 * rotated vector, and for each variant the median over rounds of the ratio
 * t(old) / t(variant) within a round, with its 10th–90th percentile range.
 * A run whose old-path times spread by more than 1.5× (max/min over the
 * rounds) is marked noisy in the data header and the index.  The machine
 * this runs on may be shared: only the ratios are meant to be compared.
 *
 * Usage: rotation_kernels OUTDIR [ROUNDS]   (default 15)
 */
#include "exp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { POOL = 64, KBATCH = 256 };
enum { V_OLD, V_MATRIX, V_MANY, V_KROT }; /* how a variant feeds the plan */

typedef struct {
    char label[48];
    sh_rot_method method;
    sh_rot_kernel kernel;
    int how, K;
    sh_rot_plan *p;
    int count;
    double *t, *ratio; /* per round: ns per vector, t_old / t */
} variant;

typedef struct {
    int n, nc, fl, mask; /* mask: an index below nc without a division */
    double R[POOL][9];
    float Rf[POOL][9];
    double *vd, *od;
    float *vf, *of;
    void *Rs, *xs, *ys; /* KBATCH rotations and vectors, structure of arrays */
    double sink;
} pool;

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static int cmpd(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* q-quantile of v[0..n) (sorted copy) */
static double quantile(const double *v, int n, double q)
{
    double *s = malloc((size_t)n * sizeof *s);
    memcpy(s, v, (size_t)n * sizeof *s);
    qsort(s, (size_t)n, sizeof *s, cmpd);
    const double x = q * (n - 1);
    const int i = (int)floor(x);
    const double r = i + 1 < n ? s[i] + (x - i) * (s[i + 1] - s[i]) : s[n - 1];
    free(s);
    return r;
}

static void pool_init(pool *P, int n, int fl)
{
    memset(P, 0, sizeof *P);
    P->n = n, P->nc = n * n, P->fl = fl;
    P->mask = 0;
    while (2 * (P->mask + 1) <= P->nc) P->mask = 2 * P->mask + 1;
    unsigned long long s = 12345;
    for (int k = 0; k < POOL; k++) {
        sh_rotation r;
        double u[3];
        for (int j = 0; j < 3; j++) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            u[j] = (double)(s >> 11) / 9007199254740992.0;
        }
        sh_rotation_from_euler(M_PI * (2 * u[0] - 1), M_PI * u[1], M_PI * (2 * u[2] - 1), &r);
        for (int j = 0; j < 9; j++) P->R[k][j] = r.R[j], P->Rf[k][j] = (float)r.R[j];
    }
    const size_t nv = (size_t)POOL * P->nc, ns = (size_t)KBATCH * P->nc;
    P->vd = malloc(nv * sizeof *P->vd), P->od = malloc(ns * sizeof *P->od);
    P->vf = malloc(nv * sizeof *P->vf), P->of = malloc(ns * sizeof *P->of);
    const size_t es = fl ? sizeof(float) : sizeof(double);
    P->Rs = malloc(9 * KBATCH * es), P->xs = malloc(ns * es), P->ys = malloc(ns * es);
    if (!P->vd || !P->od || !P->vf || !P->of || !P->Rs || !P->xs || !P->ys) exp_check(SH_ENOMEM, "pool");
    for (size_t i = 0; i < nv; i++) P->vd[i] = sin(0.7 * (double)i + 0.3), P->vf[i] = (float)P->vd[i];
    for (size_t k = 0; k < KBATCH; k++)
        for (int j = 0; j < 9 + P->nc; j++) {
            const size_t q = k % POOL;
            const double v = j < 9 ? P->R[q][j] : P->vd[q * P->nc + (size_t)(j - 9)];
            const size_t at = (j < 9 ? (size_t)j : (size_t)(j - 9)) * KBATCH + k;
            void *dst = j < 9 ? P->Rs : P->xs;
            if (fl) ((float *)dst)[at] = (float)v;
            else ((double *)dst)[at] = v;
        }
}

static void pool_free(pool *P)
{
    free(P->vd), free(P->od), free(P->vf), free(P->of), free(P->Rs), free(P->xs), free(P->ys);
}

/* count iterations of variant v; returns ns per rotated vector */
static double run(variant *v, pool *P, int count)
{
    const size_t nc = (size_t)P->nc;
    int st = SH_OK;
    const double t0 = now_ns();
    for (int it = 0; it < count; it++) {
        const int k = it & (POOL - 1);
        switch (v->how) {
        case V_OLD: { /* the earlier path: angles, set, apply with double vectors */
            sh_rotation r;
            memcpy(r.R, P->R[k], sizeof r.R);
            sh_euler_from_matrix(r.R, &r.alpha, &r.beta, &r.gamma);
            st |= sh_rot_plan_set(v->p, &r);
            st |= sh_rot_plan_apply(v->p, P->vd + k * nc, P->od);
            P->sink += P->od[it & P->mask];
            break;
        }
        case V_MATRIX:
            if (P->fl) {
                st |= sh_rot_plan_set_matrix_f(v->p, P->Rf[k]);
                st |= sh_rot_plan_apply_f(v->p, P->vf + k * nc, P->of);
                P->sink += P->of[it & P->mask];
            } else {
                st |= sh_rot_plan_set_matrix(v->p, P->R[k]);
                st |= sh_rot_plan_apply(v->p, P->vd + k * nc, P->od);
                P->sink += P->od[it & P->mask];
            }
            break;
        case V_MANY:
            if (P->fl) {
                st |= sh_rot_plan_set_matrix_f(v->p, P->Rf[k]);
                st |= sh_rot_plan_apply_many_f(v->p, (size_t)v->K, P->xs, P->ys);
                P->sink += ((float *)P->ys)[0];
            } else {
                st |= sh_rot_plan_set_matrix(v->p, P->R[k]);
                st |= sh_rot_plan_apply_many(v->p, (size_t)v->K, P->xs, P->ys);
                P->sink += ((double *)P->ys)[0];
            }
            break;
        case V_KROT:
            if (P->fl) st |= sh_rot_plan_rotate_many_f(v->p, (size_t)v->K, P->Rs, P->xs, P->ys);
            else st |= sh_rot_plan_rotate_many(v->p, (size_t)v->K, P->Rs, P->xs, P->ys);
            P->sink += P->fl ? (double)((float *)P->ys)[it & (KBATCH - 1)] : ((double *)P->ys)[it & (KBATCH - 1)];
            break;
        }
    }
    const double t = now_ns() - t0;
    exp_check(st, v->label);
    return t / ((double)count * (v->how == V_MANY || v->how == V_KROT ? v->K : 1));
}

static int add(variant *vs, int nv, int n, sh_precision prec, const char *label, sh_rot_method m,
               sh_rot_kernel k, int how, int K)
{
    if (!sh_rot_kernel_available(k)) return nv;
    variant *v = &vs[nv];
    memset(v, 0, sizeof *v);
    snprintf(v->label, sizeof v->label, "%s", label);
    v->method = m, v->kernel = k, v->how = how, v->K = K;
    exp_check(sh_rot_plan_create_kernel(n, m, prec, SH_CS, k, &v->p), label);
    return nv + 1;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const int rounds = argc > 2 ? atoi(argv[2]) : 15;
    if (rounds < 3 || rounds > 1000) exp_check(SH_EINVAL, "rounds must be in 3..1000");
    FILE *f = exp_data("kernels.dat",
                       "ns per rotated vector of the rotation kernels, interleaved rounds, and the ratio "
                       "old/variant within a round (old: scalar loop kernels, matrix -> angles -> set -> "
                       "apply with double vectors)",
                       "precision order method input kernel ns_median ns_min ratio_median ratio_p10 "
                       "ratio_p90 mults");
    fprintf(f, "# %d rounds.  input: old = matrix -> ZYZ angles -> sh_rot_plan_set -> sh_rot_plan_apply, "
               "double vectors; one = sh_rot_plan_set_matrix(_f) + apply(_f), vectors in the precision; "
               "many = one rotation on %d vectors (apply_many); krot = %d rotations of %d vectors "
               "(rotate_many, structure of arrays).  ratio = t(old of the method) / t, per round.\n",
            rounds, KBATCH, KBATCH, KBATCH);
    static const int orders[] = {3, 4, 5, 6, 8, 10};
    int noisy = 0;
    double worst_spread = 1;
    for (int fl = 1; fl >= 0; fl--)
        for (size_t oi = 0; oi < sizeof orders / sizeof *orders; oi++) {
            const int n = orders[oi];
            const sh_precision prec = fl ? SH_PREC_FLOAT : SH_PREC_DOUBLE;
            variant vs[24];
            int nv = 0;
            nv = add(vs, nv, n, prec, "old", SH_ROT_ZXZXZ, SH_KERNEL_SCALAR, V_OLD, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_ZXZXZ, SH_KERNEL_SCALAR, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_ZXZXZ, SH_KERNEL_UNROLLED, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_ZXZXZ, SH_KERNEL_AVX2, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_ZXZXZ, SH_KERNEL_AVX512, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "many", SH_ROT_ZXZXZ, SH_KERNEL_AVX2, V_MANY, KBATCH);
            nv = add(vs, nv, n, prec, "many", SH_ROT_ZXZXZ, SH_KERNEL_AVX512, V_MANY, KBATCH);
            nv = add(vs, nv, n, prec, "krot", SH_ROT_ZXZXZ, SH_KERNEL_SSE2, V_KROT, KBATCH);
            nv = add(vs, nv, n, prec, "krot", SH_ROT_ZXZXZ, SH_KERNEL_AVX2, V_KROT, KBATCH);
            nv = add(vs, nv, n, prec, "krot", SH_ROT_ZXZXZ, SH_KERNEL_AVX512, V_KROT, KBATCH);
            nv = add(vs, nv, n, prec, "old", SH_ROT_TAYLOR15, SH_KERNEL_SCALAR, V_OLD, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_TAYLOR15, SH_KERNEL_AVX2, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_TAYLOR15, SH_KERNEL_AVX512, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "krot", SH_ROT_TAYLOR15, SH_KERNEL_AVX2, V_KROT, KBATCH);
            nv = add(vs, nv, n, prec, "old", SH_ROT_IVANIC, SH_KERNEL_SCALAR, V_OLD, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_IVANIC, SH_KERNEL_AUTO, V_MATRIX, 1);
            nv = add(vs, nv, n, prec, "old", SH_ROT_BLANCO, SH_KERNEL_SCALAR, V_OLD, 1);
            nv = add(vs, nv, n, prec, "one", SH_ROT_BLANCO, SH_KERNEL_AUTO, V_MATRIX, 1);
            pool P;
            pool_init(&P, n, fl);
            exp_progress("rotation_kernels: %s order %d, %d variants", fl ? "float" : "double", n, nv);
            for (int i = 0; i < nv; i++) {
                variant *v = &vs[i];
                v->t = calloc((size_t)rounds, sizeof *v->t);
                v->ratio = calloc((size_t)rounds, sizeof *v->ratio);
                if (!v->t || !v->ratio) exp_check(SH_ENOMEM, "rounds");
                int c = 1;
                for (;;) { /* calibrate to ≈ 1 ms */
                    const double e = run(v, &P, c) * c * (v->how >= V_MANY ? v->K : 1);
                    if (e >= 1e6 || c >= (1 << 24)) break;
                    c = e < 1e5 ? c * 10 : (int)(c * 1.2e6 / e) + 1;
                }
                v->count = c;
            }
            for (int r = 0; r < rounds; r++)
                for (int j = 0; j < nv; j++) {
                    const int i = (r & 1) ? nv - 1 - j : j;
                    vs[i].t[r] = run(&vs[i], &P, vs[i].count);
                }
            /* ratios against the old path of the same method (zxzxz's for the
             * zxzxz variants), within each round */
            for (int i = 0; i < nv; i++) {
                int ref = 0;
                for (int j = 0; j < nv; j++)
                    if (vs[j].how == V_OLD && vs[j].method == vs[i].method) ref = j;
                for (int r = 0; r < rounds; r++) vs[i].ratio[r] = vs[ref].t[r] / vs[i].t[r];
            }
            const double spread = quantile(vs[0].t, rounds, 1) / quantile(vs[0].t, rounds, 0);
            if (spread > worst_spread) worst_spread = spread;
            if (spread > 1.5) noisy = 1;
            for (int i = 0; i < nv; i++) {
                variant *v = &vs[i];
                uint64_t sm = 0, am = 0;
                sh_rot_plan_mults(v->p, &sm, &am);
                const double mults = (double)sm / (v->how == V_MANY ? v->K : 1) + (double)am;
                fprintf(f, "%s %d %s %s %s %.2f %.2f %.3f %.3f %.3f %.1f\n", fl ? "float" : "double", n,
                        sh_rot_method_name(v->method), v->label, sh_rot_kernel_name(sh_rot_plan_kernel(v->p)),
                        quantile(v->t, rounds, 0.5), quantile(v->t, rounds, 0), quantile(v->ratio, rounds, 0.5),
                        quantile(v->ratio, rounds, 0.1), quantile(v->ratio, rounds, 0.9), mults);
                sh_rot_plan_free(v->p);
                free(v->t);
                free(v->ratio);
            }
            fflush(f);
            pool_free(&P);
            if (!isfinite(P.sink)) exp_check(SH_EINVAL, "checksum");
        }
    fprintf(f, "# old-path spread max/min over rounds, worst case: %.2f%s\n", worst_spread,
            noisy ? " (NOISY: > 1.5, the machine was loaded; ratios are less certain)" : "");
    fclose(f);
    exp_index("**Kernel speed** (`kernels.dat`): ns per rotated vector of the loop kernels as earlier "
              "versions ran them (matrix → ZYZ angles → set → apply, double vectors) against the "
              "unrolled and SIMD kernels fed a matrix (no trigonometric call), one rotation at a time, "
              "one rotation on %d vectors, and %d rotations of %d vectors, in float and double; ratios "
              "are medians over %d interleaved rounds of old/variant within a round.%s",
              KBATCH, KBATCH, KBATCH, rounds,
              noisy ? " This run was NOISY (old-path times spread > 1.5× over the rounds)." : "");
    return 0;
}
