/* test_kernels.c — the kernels of a plan (sh_rot_kernel): every kernel this
 * machine runs, stepped through one by one, against the loop kernels
 * (scalar) and the MPFR reference; the rotation from a matrix or a
 * quaternion (no angles) against the Euler path and the reference, at the
 * gimbal cases; the float API and the batches (apply_many, rotate_many,
 * structure of arrays) against single applies; the counted multiplications
 * of the generated kernels against their source text.
 *
 * Truths: the MPFR reference band (rotation_reference.c, ≥ 30 digits), the
 * loop kernels (rot_zxzxz.c, rot_taylor.c; tested against the reference in
 * test_rot_zxzxz.c and test_taylor.c), and the text of
 * src/rotate/rot_unrolled_gen.h.  No timing. */
#include "rottest.h"

#include <ctype.h>

static const sh_rot_method FAST[5] = {SH_ROT_ZXZXZ, SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2, SH_ROT_IVANIC};
#define MAXO 12 /* 11 and 12 have no unrolled kernel: the plan falls back */

/* The rotations: the stability set (β = 0, 1e-12, π/2, π−1e-9, π, gimbal
 * pairs, tiny β with α+γ = 0, two seeded random ones) and rottest's cases. */
#define NROT (SH_ROT_STABILITY_NSET + ROT_NCASES)
static void rotation(int k, sh_rotation *r, char *name, size_t nn)
{
    if (k < SH_ROT_STABILITY_NSET) {
        sh_rotation set[SH_ROT_STABILITY_NSET];
        const char *names[SH_ROT_STABILITY_NSET];
        ck_assert_int_eq(sh_rot_stability_set(set, names), SH_OK);
        *r = set[k];
        snprintf(name, nn, "stability set %s", names[k]);
    } else {
        rot_case(k - SH_ROT_STABILITY_NSET, r, name, nn);
    }
}

static double max_abs(const double *v, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
    return m;
}

/* y = plan(kernel) applied to x, rotation by angles (matrix = 0), matrix
 * (1) or quaternion (2) */
static void run1(int order, sh_rot_method m, sh_precision prec, sh_convention conv, sh_rot_kernel k,
                 int input, const sh_rotation *r, const double *x, double *y)
{
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create_kernel(order, m, prec, conv, k, &p), SH_OK);
    if (input == 0) ck_assert_int_eq(sh_rot_plan_set(p, r), SH_OK);
    else if (input == 1) ck_assert_int_eq(sh_rot_plan_set_matrix(p, r->R), SH_OK);
    else {
        double q[4];
        sh_rotation_to_quat(r, q);
        ck_assert_int_eq(sh_rot_plan_set_quat(p, q), SH_OK);
    }
    ck_assert_int_eq(sh_rot_plan_apply(p, x, y), SH_OK);
    sh_rot_plan_free(p);
}

/* Every available kernel against the loop kernels, Euler input: the
 * unrolled code without FMA (unrolled, sse2: same operations in the same
 * order) is equal bit for bit in cs for zxzxz and Taylor; ivanic (whose loop
 * kernel sums the block × vector in vector lanes), with FMA (avx2, avx512),
 * and in nocs
 * (β negated, or for ivanic R conjugated by Rz(π), instead of the vectors
 * or blocks flipped) to a few ulps of the largest output. */
START_TEST(test_kernels_vs_scalar)
{
    double x[MAXO * MAXO], a[MAXO * MAXO], b[MAXO * MAXO];
    int nk = 0;
    for (int k = SH_KERNEL_SCALAR; k < SH_KERNEL_N; k++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)k)) continue;
        nk++;
        const int nofma = k == SH_KERNEL_SCALAR || k == SH_KERNEL_UNROLLED || k == SH_KERNEL_SSE2;
        for (int mi = 0; mi < 5; mi++)
            for (int prec = 0; prec < 2; prec++)
                for (int conv = 0; conv < 2; conv++)
                    for (int order = 1; order <= MAXO; order++)
                        for (int c = 0; c < NROT; c += 3) {
                            sh_rotation r;
                            char name[160];
                            rotation(c, &r, name, sizeof name);
                            const int n = order * order;
                            for (int i = 0; i < n; i++) x[i] = 2 * rot_urand() - 1;
                            run1(order, FAST[mi], prec, conv, SH_KERNEL_SCALAR, 0, &r, x, a);
                            run1(order, FAST[mi], prec, conv, (sh_rot_kernel)k, 0, &r, x, b);
                            const double eps = prec == SH_PREC_FLOAT ? 1.1920929e-07 : 2.220446049250313e-16;
                            /* bit for bit: zxzxz and Taylor without FMA in cs (ivanic's loop
                             * kernel sums its block × vector in vector lanes) */
                            const int exact = nofma && conv == SH_CS && FAST[mi] != SH_ROT_IVANIC;
                            const double tol = exact ? 0 : 64 * eps * fmax(1, max_abs(a, n));
                            for (int i = 0; i < n; i++)
                                if (!(fabs(a[i] - b[i]) <= tol))
                                    ck_abort_msg("%s kernel %s %s %s order %d %s: i %d scalar %.17g got %.17g",
                                                 sh_rot_method_name(FAST[mi]), sh_rot_kernel_name(k),
                                                 sh_precision_name(prec), sh_convention_name(conv), order,
                                                 name, i, a[i], b[i]);
                        }
    }
    ck_assert_int_ge(nk, 2); /* scalar and unrolled everywhere */
}
END_TEST

/* The rotation from its matrix and from its quaternion (no angles): the
 * exact methods that use it (zxzxz, ivanic, blanco) against the MPFR
 * reference, the Taylor methods against their Euler path, every kernel,
 * both conventions and precisions. */
START_TEST(test_matrix_input)
{
    double x[MAXO * MAXO], y[MAXO * MAXO], ref[2 * MAXO * MAXO];
    double *B = malloc((size_t)(2 * MAXO) * (2 * MAXO) * sizeof *B);
    for (int k = SH_KERNEL_SCALAR; k < SH_KERNEL_N; k++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)k)) continue;
        for (int c = 0; c < NROT; c++) {
            sh_rotation r;
            char name[160];
            rotation(c, &r, name, sizeof name);
            for (int conv = 0; conv < 2; conv++)
                for (int order = 1; order <= 10; order += (order < 6 ? 1 : 4)) {
                    const int n = order * order;
                    for (int i = 0; i < n; i++) x[i] = 2 * rot_urand() - 1;
                    /* reference: band by band, summed in long double */
                    for (int l = 0; l < order; l++) {
                        const int w = 2 * l + 1;
                        ck_assert_int_eq(sh_rot_reference_band(l, conv, &r, 32, B, NULL), SH_OK);
                        for (int i = 0; i < w; i++) {
                            long double s = 0;
                            for (int j = 0; j < w; j++) s += (long double)B[i * w + j] * x[l * l + j];
                            ref[l * l + i] = (double)s;
                        }
                    }
                    for (int prec = 0; prec < 2; prec++)
                        for (int input = 1; input <= 2; input++) {
                            const double tol = prec == SH_PREC_FLOAT ? ROT_TOL_F * 4 : ROT_TOL_D;
                            static const sh_rot_method exact[3] = {SH_ROT_ZXZXZ, SH_ROT_IVANIC, SH_ROT_BLANCO};
                            for (int e = 0; e < 3; e++) {
                                run1(order, exact[e], prec, conv, (sh_rot_kernel)k, input, &r, x, y);
                                for (int i = 0; i < n; i++)
                                    if (!(fabs(y[i] - ref[i]) <= tol))
                                        ck_abort_msg("%s %s %s %s order %d %s from %s: i %d ref %.17g got %.17g",
                                                     sh_rot_method_name(exact[e]), sh_rot_kernel_name(k),
                                                     sh_precision_name(prec), sh_convention_name(conv), order,
                                                     name, input == 1 ? "matrix" : "quaternion", i, ref[i], y[i]);
                            }
                            /* Taylor: the same approximation as from the angles (its
                             * outputs grow like β²l² at large β: relative tolerance) */
                            run1(order, SH_ROT_TAYLOR15, prec, conv, (sh_rot_kernel)k, 0, &r, x, ref + n);
                            run1(order, SH_ROT_TAYLOR15, prec, conv, (sh_rot_kernel)k, input, &r, x, y);
                            const double tt = (prec == SH_PREC_FLOAT ? 1e-5 : 1e-12) * fmax(1, max_abs(ref + n, n));
                            for (int i = 0; i < n; i++)
                                if (!(fabs(y[i] - ref[n + i]) <= tt))
                                    ck_abort_msg("taylor1.5 %s %s order %d %s from %s: i %d angles %.17g got %.17g",
                                                 sh_rot_kernel_name(k), sh_precision_name(prec), order, name,
                                                 input == 1 ? "matrix" : "quaternion", i, ref[n + i], y[i]);
                        }
                }
        }
    }
    free(B);
}
END_TEST

/* At the gimbal cases β = 0 and β = π only α ± γ is defined: a matrix built
 * from (α, 0, γ) and from (α+γ, 0, 0) is the same rotation, and so must the
 * result be; the same for (α, π, γ) and (α−γ, π, 0).  Against the reference,
 * with the matrix entries that are exactly 0 there. */
START_TEST(test_gimbal)
{
    static const double ag[4][2] = {{0.9, -0.9}, {2.5, 1.0}, {-3.0, 3.1}, {M_PI, M_PI}};
    double x[36], y[36], z[36];
    for (int i = 0; i < 36; i++) x[i] = sin(1.0 + i);
    for (int c = 0; c < 4; c++)
        for (int pi = 0; pi < 2; pi++) {
            const double b = pi ? M_PI : 0, a = ag[c][0], g = ag[c][1];
            sh_rotation r1, r2;
            ck_assert_int_eq(sh_rotation_from_euler(a, b, g, &r1), SH_OK);
            ck_assert_int_eq(sh_rotation_from_euler(pi ? a - g : a + g, b, 0, &r2), SH_OK);
            for (int prec = 0; prec < 2; prec++) {
                run1(6, SH_ROT_ZXZXZ, prec, SH_CS, SH_KERNEL_AUTO, 1, &r1, x, y);
                run1(6, SH_ROT_ZXZXZ, prec, SH_CS, SH_KERNEL_AUTO, 1, &r2, x, z);
                const double tol = prec == SH_PREC_FLOAT ? ROT_TOL_F : ROT_TOL_D;
                for (int i = 0; i < 36; i++)
                    ck_close(y[i], z[i], tol, 1.0, "gimbal (%g,%g,%g) %s i %d", a, b, g, sh_precision_name(prec), i);
            }
        }
}
END_TEST

/* The float API (float matrix, float vectors) against the double interface
 * of the same float plan, and refusals. */
START_TEST(test_float_api)
{
    sh_rotation r;
    sh_rotation_from_euler(0.4, 1.2, -2.2, &r);
    float R[9], xf[36], yf[36];
    double x[36], y[36];
    for (int i = 0; i < 9; i++) R[i] = (float)r.R[i];
    for (int i = 0; i < 36; i++) xf[i] = (float)(x[i] = sin(0.3 * i));
    for (int k = SH_KERNEL_SCALAR; k < SH_KERNEL_N; k++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)k)) continue;
        for (int m = 0; m < SH_ROT_NMETHODS; m++) {
            if (m == SH_ROT_Z || m == SH_ROT_REFERENCE || sh_rot_method_max_order((sh_rot_method)m) < 6) continue;
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create_kernel(6, (sh_rot_method)m, SH_PREC_FLOAT, SH_CS, (sh_rot_kernel)k, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply_f(p, xf, yf), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(p, x, y), SH_OK);
            for (int i = 0; i < 36; i++)
                ck_close(yf[i], y[i], 8 * ROT_TOL_F, 1.0, "%s kernel %s float API i %d", sh_rot_method_name(m),
                         sh_rot_kernel_name(k), i);
            /* in place */
            float zf[36];
            memcpy(zf, xf, sizeof zf);
            ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply_f(p, zf, zf), SH_OK);
            for (int i = 0; i < 36; i++) ck_assert_float_eq(zf[i], yf[i]);
            sh_rot_plan_free(p);
        }
    }
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(4, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, R), SH_EINVAL);
    ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
    ck_assert_int_eq(sh_rot_plan_apply_f(p, xf, yf), SH_EINVAL);
    double bad[9];
    memcpy(bad, r.R, sizeof bad);
    bad[4] = NAN;
    ck_assert_int_eq(sh_rot_plan_set_matrix(p, bad), SH_EINVAL);
    bad[4] = INFINITY;
    ck_assert_int_eq(sh_rot_plan_set_matrix(p, bad), SH_EINVAL);
    ck_assert_int_eq(sh_rot_plan_apply_many(p, 0, x, y), SH_EINVAL);
    sh_rot_plan_free(p);
    for (int k = SH_KERNEL_SCALAR; k < SH_KERNEL_N; k++)
        if (!sh_rot_kernel_available((sh_rot_kernel)k))
            ck_assert_int_eq(sh_rot_plan_create_kernel(4, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, (sh_rot_kernel)k, &p),
                             SH_ENOTSUP);
    sh_rot_kernel kk;
    ck_assert_int_eq(sh_rot_kernel_parse("avx3", &kk), SH_EINVAL);
    ck_assert_int_eq(sh_rot_kernel_parse("avx2", &kk), SH_OK);
    ck_assert_int_eq(kk, SH_KERNEL_AVX2);
}
END_TEST

/* Batches (structure of arrays) against one apply per vector: K = 1, 3, 17,
 * 64 (partial SIMD groups), every kernel, the fast methods and two loop
 * methods, both precisions, both conventions, matrices and quaternions, in
 * place too. */
START_TEST(test_batches)
{
    static const int Ks[4] = {1, 3, 17, 64};
    static const sh_rot_method ms[6] = {SH_ROT_ZXZXZ, SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2, SH_ROT_IVANIC,
                                        SH_ROT_BLANCO};
    const int order = 5, nc = 25, Kmax = 64;
    double *R = malloc(9 * Kmax * sizeof *R), *Q = malloc(4 * Kmax * sizeof *Q);
    double *x = malloc((size_t)nc * Kmax * sizeof *x), *y = malloc((size_t)nc * Kmax * sizeof *y);
    float *Rf = malloc(9 * Kmax * sizeof *Rf), *Qf = malloc(4 * Kmax * sizeof *Qf);
    float *xf = malloc((size_t)nc * Kmax * sizeof *xf), *yf = malloc((size_t)nc * Kmax * sizeof *yf);
    sh_rotation rs[64];
    for (int k = 0; k < Kmax; k++) {
        char name[160];
        rotation(k % NROT, &rs[k], name, sizeof name);
        double q[4];
        sh_rotation_to_quat(&rs[k], q);
        for (int j = 0; j < 9; j++) R[j * Kmax + k] = rs[k].R[j], Rf[j * Kmax + k] = (float)rs[k].R[j];
        for (int j = 0; j < 4; j++) Q[j * Kmax + k] = q[j], Qf[j * Kmax + k] = (float)q[j];
        for (int i = 0; i < nc; i++) xf[i * Kmax + k] = (float)(x[i * Kmax + k] = 2 * rot_urand() - 1);
    }
    for (int kn = SH_KERNEL_SCALAR; kn < SH_KERNEL_N; kn++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)kn)) continue;
        for (int mi = 0; mi < 6; mi++)
            for (int prec = 0; prec < 2; prec++)
                for (int conv = 0; conv < 2; conv++)
                    for (int ki = 0; ki < 4; ki++)
                        for (int quat = 0; quat < 2; quat++) {
                            const int K = Ks[ki];
                            sh_rot_plan *p, *s;
                            ck_assert_int_eq(sh_rot_plan_create_kernel(order, ms[mi], prec, conv, (sh_rot_kernel)kn, &p), SH_OK);
                            ck_assert_int_eq(sh_rot_plan_create_kernel(order, ms[mi], prec, conv, (sh_rot_kernel)kn, &s), SH_OK);
                            /* the arrays have stride Kmax: repack to stride K */
                            double *Rk = malloc(9 * (size_t)K * sizeof *Rk), *xk = malloc((size_t)nc * K * sizeof *xk);
                            double *yk = malloc((size_t)nc * K * sizeof *yk);
                            float *Rkf = malloc(9 * (size_t)K * sizeof *Rkf), *xkf = malloc((size_t)nc * K * sizeof *xkf);
                            float *ykf = malloc((size_t)nc * K * sizeof *ykf);
                            const int nr = quat ? 4 : 9;
                            for (int k = 0; k < K; k++) {
                                for (int j = 0; j < nr; j++) {
                                    Rk[j * K + k] = quat ? Q[j * Kmax + k] : R[j * Kmax + k];
                                    Rkf[j * K + k] = quat ? Qf[j * Kmax + k] : Rf[j * Kmax + k];
                                }
                                for (int i = 0; i < nc; i++) xk[i * K + k] = x[i * Kmax + k], xkf[i * K + k] = xf[i * Kmax + k];
                            }
                            if (prec == SH_PREC_DOUBLE) {
                                ck_assert_int_eq(quat ? sh_rot_plan_rotate_many_quat(p, (size_t)K, Rk, xk, yk)
                                                      : sh_rot_plan_rotate_many(p, (size_t)K, Rk, xk, yk), SH_OK);
                            } else {
                                ck_assert_int_eq(quat ? sh_rot_plan_rotate_many_quat_f(p, (size_t)K, Rkf, xkf, ykf)
                                                      : sh_rot_plan_rotate_many_f(p, (size_t)K, Rkf, xkf, ykf), SH_OK);
                            }
                            for (int k = 0; k < K; k++) {
                                double v[25], w[25];
                                float vf[25], wf[25];
                                for (int i = 0; i < nc; i++) v[i] = xk[i * K + k], vf[i] = xkf[i * K + k];
                                if (prec == SH_PREC_DOUBLE) {
                                    double rr[9];
                                    for (int j = 0; j < nr; j++) rr[j] = Rk[j * K + k];
                                    ck_assert_int_eq(quat ? sh_rot_plan_set_quat(s, rr) : sh_rot_plan_set_matrix(s, rr), SH_OK);
                                    ck_assert_int_eq(sh_rot_plan_apply(s, v, w), SH_OK);
                                } else {
                                    float rr[9];
                                    for (int j = 0; j < nr; j++) rr[j] = Rkf[j * K + k];
                                    ck_assert_int_eq(quat ? sh_rot_plan_set_quat_f(s, rr) : sh_rot_plan_set_matrix_f(s, rr), SH_OK);
                                    ck_assert_int_eq(sh_rot_plan_apply_f(s, vf, wf), SH_OK);
                                    for (int i = 0; i < nc; i++) w[i] = wf[i];
                                }
                                const double tol = (prec == SH_PREC_FLOAT ? 4 * ROT_TOL_F : 64 * 2.2e-16) * fmax(1, max_abs(w, nc));
                                for (int i = 0; i < nc; i++) {
                                    const double got = prec == SH_PREC_DOUBLE ? yk[i * K + k] : ykf[i * K + k];
                                    if (!(fabs(got - w[i]) <= tol))
                                        ck_abort_msg("%s kernel %s %s %s K %d %s lane %d i %d: single %.17g batch %.17g",
                                                     sh_rot_method_name(ms[mi]), sh_rot_kernel_name(kn),
                                                     sh_precision_name(prec), sh_convention_name(conv), K,
                                                     quat ? "quat" : "matrix", k, i, w[i], got);
                                }
                            }
                            /* one rotation on K vectors, in place */
                            if (prec == SH_PREC_DOUBLE) {
                                ck_assert_int_eq(sh_rot_plan_set_matrix(p, rs[0].R), SH_OK);
                                memcpy(yk, xk, (size_t)nc * K * sizeof *yk);
                                ck_assert_int_eq(sh_rot_plan_apply_many(p, (size_t)K, yk, yk), SH_OK);
                            } else {
                                float r0[9];
                                for (int j = 0; j < 9; j++) r0[j] = (float)rs[0].R[j];
                                ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, r0), SH_OK);
                                memcpy(ykf, xkf, (size_t)nc * K * sizeof *ykf);
                                ck_assert_int_eq(sh_rot_plan_apply_many_f(p, (size_t)K, ykf, ykf), SH_OK);
                            }
                            for (int k = 0; k < K; k++) {
                                double v[25], w[25];
                                for (int i = 0; i < nc; i++) v[i] = prec == SH_PREC_DOUBLE ? xk[i * K + k] : xkf[i * K + k];
                                ck_assert_int_eq(sh_rot_plan_apply(p, v, w), SH_OK);
                                const double tol = (prec == SH_PREC_FLOAT ? 4 * ROT_TOL_F : 64 * 2.2e-16) * fmax(1, max_abs(w, nc));
                                for (int i = 0; i < nc; i++) {
                                    const double got = prec == SH_PREC_DOUBLE ? yk[i * K + k] : ykf[i * K + k];
                                    if (!(fabs(got - w[i]) <= tol))
                                        ck_abort_msg("apply_many %s kernel %s %s K %d lane %d i %d: %.17g vs %.17g",
                                                     sh_rot_method_name(ms[mi]), sh_rot_kernel_name(kn),
                                                     sh_precision_name(prec), K, k, i, w[i], got);
                                }
                            }
                            free(Rk), free(xk), free(yk), free(Rkf), free(xkf), free(ykf);
                            sh_rot_plan_free(p);
                            sh_rot_plan_free(s);
                        }
    }
    free(R), free(Q), free(x), free(y), free(Rf), free(Qf), free(xf), free(yf);
}
END_TEST

/* The generated file: its banner's count per method and order equals the
 * number of multiplications (" * ") in that function's text and what a
 * plan with the unrolled kernel reports for one apply. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) { free(s); s = NULL; }
    if (s) s[n] = 0;
    fclose(f);
    return s;
}

START_TEST(test_generated_counts)
{
    char *src = slurp("src/rotate/rot_unrolled_gen.h");
    ck_assert_msg(src != NULL, "cannot read src/rotate/rot_unrolled_gen.h (run from the repository root)");
    static const char *const label[5] = {"zxzxz", "taylor1", "taylor1.5", "taylor2", "ivanic"};
    static const char *const fname[5] = {"zxzxz", "taylor1", "taylor15", "taylor2", "ivanic"};
    int checked = 0;
    for (int mi = 0; mi < 5; mi++) {
        /* banner line " *   <label> 1:a 2:b ..." */
        char key[32];
        snprintf(key, sizeof key, " *   %s ", label[mi]);
        const char *line = strstr(src, key);
        ck_assert_msg(line != NULL, "banner has no line for %s", label[mi]);
        const char *q = line + strlen(key);
        for (;;) {
            while (*q == ' ') q++;
            if (!isdigit((unsigned char)*q)) break;
            int order = 0;
            unsigned long count = 0;
            ck_assert_int_eq(sscanf(q, "%d:%lu", &order, &count), 2);
            while (*q && *q != ' ' && *q != '\n') q++;
            /* the function's text */
            char head[64];
            snprintf(head, sizeof head, "static void %s_%d(", fname[mi], order);
            const char *b = strstr(src, head), *e = b ? strstr(b, "\n}\n") : NULL;
            ck_assert_msg(b && e, "no function %s_%d", fname[mi], order);
            unsigned long stars = 0;
            for (const char *t = b; (t = strstr(t, " * ")) && t < e; t += 3) stars++;
            ck_assert_msg(stars == count, "%s order %d: banner %lu, source %lu", label[mi], order, count, stars);
            /* the plan */
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create_kernel(order, FAST[mi], SH_PREC_DOUBLE, SH_CS, SH_KERNEL_UNROLLED, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_kernel(p), SH_KERNEL_UNROLLED);
            sh_rotation r;
            sh_rotation_from_euler(0.3, 0.2, 0.1, &r);
            double v[256] = {0}, w[256];
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(p, v, w), SH_OK);
            uint64_t sm, am;
            sh_rot_plan_mults(p, &sm, &am);
            ck_assert_uint_eq(am, count);
            ck_assert_uint_eq(sm, 0); /* from angles: libm only */
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
            sh_rot_plan_mults(p, &sm, NULL);
            ck_assert_uint_eq(sm, mi == 4 ? 0 : 12); /* ivanic reads the matrix as it is */
            sh_rot_plan_free(p);
            /* the loop kernel does at least as many (the unrolled code skips
             * the products with ±1) */
            ck_assert_int_eq(sh_rot_plan_create_kernel(order, FAST[mi], SH_PREC_DOUBLE, SH_CS, SH_KERNEL_SCALAR, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(p, v, w), SH_OK);
            sh_rot_plan_mults(p, &sm, &am);
            ck_assert_uint_le(count, sm + am);
            sh_rot_plan_free(p);
            checked++;
        }
    }
    ck_assert_int_ge(checked, 5 * 6); /* orders up to at least 6 */
    free(src);
}
END_TEST

/* sh_rot_plan_blocks of an unrolled plan (each unit vector through the
 * kernel) against the loop kernel's blocks, and orthogonality. */
START_TEST(test_blocks)
{
    for (int k = SH_KERNEL_UNROLLED; k < SH_KERNEL_N; k++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)k)) continue;
        for (int c = 0; c < NROT; c += 2) {
            sh_rotation r;
            char name[160];
            rotation(c, &r, name, sizeof name);
            const int order = 8;
            const size_t nb = sh_rot_block_offset(order);
            double *A = malloc(nb * sizeof *A), *B = malloc(nb * sizeof *B);
            for (int conv = 0; conv < 2; conv++) {
                sh_rot_plan *p, *q;
                ck_assert_int_eq(sh_rot_plan_create_kernel(order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, conv, (sh_rot_kernel)k, &p), SH_OK);
                ck_assert_int_eq(sh_rot_plan_create_kernel(order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, conv, SH_KERNEL_SCALAR, &q), SH_OK);
                ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
                ck_assert_int_eq(sh_rot_plan_set(q, &r), SH_OK);
                ck_assert_int_eq(sh_rot_plan_blocks(p, A), SH_OK);
                ck_assert_int_eq(sh_rot_plan_blocks(q, B), SH_OK);
                for (size_t i = 0; i < nb; i++)
                    ck_close(A[i], B[i], ROT_TOL_D, 1.0, "blocks %s %s conv %d entry %zu", sh_rot_kernel_name(k), name, conv, i);
                ck_assert(rot_orth_err(order, A) <= 1e-14);
                sh_rot_plan_free(p);
                sh_rot_plan_free(q);
            }
            free(A);
            free(B);
        }
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("kernels");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, test_kernels_vs_scalar);
    tcase_add_test(tc, test_matrix_input);
    tcase_add_test(tc, test_gimbal);
    tcase_add_test(tc, test_float_api);
    tcase_add_test(tc, test_batches);
    tcase_add_test(tc, test_generated_counts);
    tcase_add_test(tc, test_blocks);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
