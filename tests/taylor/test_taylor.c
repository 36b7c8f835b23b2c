/* test_taylor.c — derivatives of R_Y (rotation_deriv.c), the Taylor kernels
 * (rot_taylor.c) and their error analysis (taylor_error.c).
 *
 * Truths: the two derivative computations against each other (Appendix A
 * recursion vs R_Y(β)·J^k); both against finite differences of an exact
 * method (blanco, which neither uses); J against the MPFR reference through
 * exp(βJ) = R_Y(β); J's structure (antisymmetric, m' = m ± 1 only, J² symmetric);
 * Krivánek's Figure 2 as printed (a paper value, not our output); the
 * kernels against dense I + βJ + ... built here from the recursion's J, J²
 * and the z method; error measures against GSL's symmetric eigensolver on
 * the dense DᵀD and the Frobenius identity Σσ² = ‖D‖_F². */
#include "rottest.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

#define NB(n) sh_rot_block_offset(n)

static double maxabs(const double *a, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
    return m;
}

/* R_Y(β) blocks by an exact method, conv */
static void exact_y(int order, sh_rot_method m, double beta, sh_convention conv, double *B)
{
    sh_rotation r;
    ck_assert_int_eq(sh_rotation_from_euler(0, beta, 0, &r), SH_OK);
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(order, m, SH_PREC_DOUBLE, conv, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
    ck_assert_int_eq(sh_rot_plan_blocks(p, B), SH_OK);
    sh_rot_plan_free(p);
}

START_TEST(test_deriv_two_ways)
{
    static const double betas[] = {0, 0.3, -1.1, 2.0, M_PI / 2, 3.0};
    double worst = 0;
    for (int order = 1; order <= 10; order++) {
        const size_t nb = NB(order);
        double *A = malloc(nb * sizeof *A), *G = malloc(nb * sizeof *G);
        for (int k = 0; k <= 5; k++)
            for (size_t b = 0; b < sizeof betas / sizeof *betas; b++)
                for (int conv = 0; conv < 2; conv++) {
                    ck_assert_int_eq(sh_rot_deriv_recursion(order, k, betas[b], conv, A), SH_OK);
                    ck_assert_int_eq(sh_rot_deriv_generator(order, k, betas[b], conv, G), SH_OK);
                    const double scale = fmax(1.0, maxabs(G, nb));
                    for (size_t i = 0; i < nb; i++) {
                        ck_close(A[i], G[i], 1e-12, scale, "deriv order %d k %d beta %g conv %d entry %zu",
                                 order, k, betas[b], conv, i);
                        worst = fmax(worst, fabs(A[i] - G[i]) / scale);
                    }
                }
        free(A);
        free(G);
    }
    fprintf(stderr, "deriv recursion vs generator, orders 1..10, k 0..5: max |diff|/max|entry| %.3g\n", worst);
}
END_TEST

/* 5-point central differences of blanco's R_Y: first and second derivative */
/* Large k and large β (deriv takes any k ≥ 0 and any β).  Truth for k = 40 at
 * order 3: J of bands 1, 2 has eigenvalues 0, ±i (, ±2i), so it satisfies
 * J⁵ = −5J³ − 4J (minimal polynomial x(x²+1)(x²+4)); J^40 is built here from
 * the closed-form J and its powers 2..4 (dense products) by that recurrence,
 * and R_Y(β) from blanco (which neither derivative uses). */
static void matmul(int w, const double *A, const double *B, double *C)
{
    for (int i = 0; i < w; i++)
        for (int j = 0; j < w; j++) {
            double a = 0;
            for (int q = 0; q < w; q++) a += A[i * w + q] * B[q * w + j];
            C[i * w + j] = a;
        }
}

START_TEST(test_deriv_large_k_beta)
{
    const int order = 3, K = 40;
    const double beta = 0.7;
    for (int cv = 0; cv < 2; cv++) {
        const sh_convention conv = cv ? SH_NOCS : SH_CS;
        double R[NB(3)], want[NB(3)], rec[NB(3)], gen[NB(3)];
        exact_y(order, SH_ROT_BLANCO, beta, conv, R);
        want[0] = 0; /* band 0: J = 0 */
        for (int l = 1; l < order; l++) {
            const int w = 2 * l + 1;
            double P[41][25];
            ck_assert_int_eq(sh_rot_deriv_J_band(l, conv, P[1]), SH_OK);
            for (int q = 2; q <= 4; q++) matmul(w, P[q - 1], P[1], P[q]);
            for (int q = 5; q <= K; q++)
                for (int i = 0; i < w * w; i++) P[q][i] = -5 * P[q - 2][i] - 4 * P[q - 4][i];
            matmul(w, R + NB(l), P[K], want + NB(l));
        }
        ck_assert_int_eq(sh_rot_deriv_recursion(order, K, beta, conv, rec), SH_OK);
        ck_assert_int_eq(sh_rot_deriv_generator(order, K, beta, conv, gen), SH_OK);
        const double scale = maxabs(want, NB(3)); /* ~ 2^40 */
        ck_assert_msg(scale > 1e11, "J^40 scale %g", scale);
        double er = 0, eg = 0;
        for (size_t i = 0; i < NB(3); i++) {
            er = fmax(er, fabs(rec[i] - want[i]));
            eg = fmax(eg, fabs(gen[i] - want[i]));
        }
        ck_assert_msg(er <= 1e-12 * scale && eg <= 1e-12 * scale, "k=40 %s: recursion %g, generator %g (scale %g)",
                      cv ? "nocs" : "cs", er / scale, eg / scale, scale);
    }
    /* β and β + 2π·1000 give the same derivative (R_Y is 2π-periodic); the
     * shift is known to ~1e-12 in double, so agreement to 1e-9 relative */
    {
        const int n = 5;
        double a[NB(5)], b[NB(5)];
        for (int way = 0; way < 2; way++)
            for (int k = 0; k <= 3; k++) {
                int (*f)(int, int, double, sh_convention, double *) = way ? sh_rot_deriv_generator : sh_rot_deriv_recursion;
                ck_assert_int_eq(f(n, k, 0.4, SH_CS, a), SH_OK);
                ck_assert_int_eq(f(n, k, 0.4 + 2 * M_PI * 1000, SH_CS, b), SH_OK);
                double d = 0;
                for (size_t i = 0; i < NB(5); i++) d = fmax(d, fabs(a[i] - b[i]));
                ck_assert_msg(d <= 1e-9 * fmax(1, maxabs(a, NB(5))), "way %d k %d: beta vs beta+2000pi differ by %g", way, k, d);
                /* and a huge β: finite, and still an orthogonal R_Y at k = 0 */
                ck_assert_int_eq(f(n, k, 1e300, SH_CS, b), SH_OK);
                for (size_t i = 0; i < NB(5); i++) ck_assert(isfinite(b[i]));
            }
    }
    /* order 2: J³ = −J exactly, so no k overflows: k = 4001 equals k = 1 */
    {
        double a[NB(2)], b[NB(2)];
        ck_assert_int_eq(sh_rot_deriv_generator(2, 1, 0.3, SH_CS, a), SH_OK);
        ck_assert_int_eq(sh_rot_deriv_recursion(2, 4001, 0.3, SH_CS, b), SH_OK);
        for (size_t i = 0; i < NB(2); i++) ck_assert_double_eq_tol(a[i], b[i], 1e-15);
    }
    /* overflow is refused, not returned as Inf: order 3 entries ≥ 2^k/5 */
    double big[NB(32)];
    ck_assert_int_eq(sh_rot_deriv_recursion(3, 2000, 0.1, SH_CS, big), SH_EINVAL);
    ck_assert_int_eq(sh_rot_deriv_generator(3, 2000, 0.1, SH_CS, big), SH_EINVAL);
    ck_assert_int_eq(sh_rot_deriv_generator(32, 400, 0.1, SH_CS, big), SH_EINVAL);
    ck_assert_int_eq(sh_rot_deriv_generator(3, -1, 0.1, SH_CS, big), SH_EINVAL);
}
END_TEST

START_TEST(test_deriv_finite_differences)
{
    const int order = 6;
    const size_t nb = NB(order);
    const double h = 1e-3, betas[] = {0.0, 0.4, 1.3, 2.5};
    double *F[5], *A = malloc(nb * sizeof *A);
    for (int q = 0; q < 5; q++) F[q] = malloc(nb * sizeof *F[q]);
    double worst1 = 0, worst2 = 0;
    for (size_t b = 0; b < sizeof betas / sizeof *betas; b++) {
        for (int q = 0; q < 5; q++) {
            /* blanco takes β ∈ [0, π]: at β < 0 use R_Y(−β) = Z(π) R_Y(β) Z(π), i.e. the rotation's own extraction */
            exact_y(order, SH_ROT_BLANCO, betas[b] + (q - 2) * h, SH_CS, F[q]);
        }
        for (int k = 1; k <= 2; k++) {
            ck_assert_int_eq(sh_rot_deriv_recursion(order, k, betas[b], SH_CS, A), SH_OK);
            for (size_t i = 0; i < nb; i++) {
                const double fd = k == 1 ? (F[0][i] - 8 * F[1][i] + 8 * F[3][i] - F[4][i]) / (12 * h)
                                         : (-F[0][i] + 16 * F[1][i] - 30 * F[2][i] + 16 * F[3][i] - F[4][i]) / (12 * h * h);
                const double tol = k == 1 ? 1e-8 : 1e-5;
                ck_close(A[i], fd, tol, 10.0, "finite difference k %d beta %g entry %zu", k, betas[b], i);
                if (k == 1) worst1 = fmax(worst1, fabs(A[i] - fd));
                else worst2 = fmax(worst2, fabs(A[i] - fd));
            }
        }
    }
    fprintf(stderr, "deriv vs 5-point differences of blanco (order 6, h 1e-3): k=1 %.3g, k=2 %.3g\n", worst1, worst2);
    for (int q = 0; q < 5; q++) free(F[q]);
    free(A);
}
END_TEST

/* J: closed form == recursion at β = 0; antisymmetric; only m' = m ± 1 and
 * never (0, −1); J² (recursion, k = 2) == J·J and symmetric. */
START_TEST(test_J_structure)
{
    const int order = 12;
    double *J1 = malloc(NB(order) * sizeof *J1), *J2 = malloc(NB(order) * sizeof *J2);
    double *Jc = malloc((size_t)(2 * order) * (2 * order) * sizeof *Jc);
    for (int conv = 0; conv < 2; conv++) {
        ck_assert_int_eq(sh_rot_deriv_recursion(order, 1, 0.0, conv, J1), SH_OK);
        ck_assert_int_eq(sh_rot_deriv_recursion(order, 2, 0.0, conv, J2), SH_OK);
        for (int l = 0; l < order; l++) {
            const int w = 2 * l + 1;
            const double *A = J1 + NB(l), *B = J2 + NB(l);
            ck_assert_int_eq(sh_rot_deriv_J_band(l, conv, Jc), SH_OK);
            for (int i = 0; i < w; i++)
                for (int j = 0; j < w; j++) {
                    const int mi = i - l, mj = j - l;
                    const double a = A[i * w + j];
                    ck_close(Jc[i * w + j], a, 1e-14, 1.0, "J closed vs recursion l %d (%d,%d)", l, mi, mj);
                    ck_assert_msg(a == -A[j * w + i] || fabs(a + A[j * w + i]) < 1e-14, "J antisymmetric l %d", l);
                    const int allowed = abs(mi - mj) == 1 && !((mi == 0 && mj == -1) || (mi == -1 && mj == 0));
                    if (!allowed) ck_assert_msg(fabs(a) < 1e-14, "J l %d (%d,%d) = %g outside the structure", l, mi, mj, a);
                    else ck_assert_msg(fabs(a) > 0.4, "J l %d (%d,%d) unexpectedly small", l, mi, mj);
                    double s = 0;
                    for (int q = 0; q < w; q++) s += A[i * w + q] * A[q * w + j];
                    ck_close(B[i * w + j], s, 1e-13, 1.0, "J2 == J*J l %d (%d,%d)", l, mi, mj);
                    ck_close(B[i * w + j], B[j * w + i], 1e-14, 1.0, "J2 symmetric l %d", l);
                    const int allowed2 = (mi == mj || abs(mi - mj) == 2) && ((mi < 0) == (mj < 0));
                    if (!allowed2) ck_assert_msg(fabs(B[i * w + j]) < 1e-13, "J2 l %d (%d,%d) outside the structure", l, mi, mj);
                }
        }
    }
    free(J1), free(J2), free(Jc);
}
END_TEST

/* exp(βJ) (long double, scaling and squaring) == the MPFR reference of R_Y(β). */
START_TEST(test_J_exponential)
{
    sh_rotation r;
    const double beta = 0.7;
    sh_rotation_from_euler(0, beta, 0, &r);
    for (int l = 0; l <= 8; l++) {
        const int w = 2 * l + 1;
        double *J = malloc((size_t)w * w * sizeof *J), *ref = malloc((size_t)w * w * sizeof *ref);
        long double *E = calloc((size_t)w * w, sizeof *E), *T = calloc((size_t)w * w, sizeof *T),
                    *U = calloc((size_t)w * w, sizeof *U);
        ck_assert_int_eq(sh_rot_deriv_J_band(l, SH_CS, J), SH_OK);
        ck_assert_int_eq(sh_rot_reference_band(l, SH_CS, &r, 32, ref, NULL), SH_OK);
        const int sq = 10; /* exp(A) = exp(A/2^10)^(2^10) */
        const long double a = (long double)beta / (1 << sq);
        for (int i = 0; i < w; i++) E[i * w + i] = T[i * w + i] = 1; /* E = Σ (aJ)^t / t!, T = term */
        for (int t = 1; t <= 20; t++) {
            for (int i = 0; i < w; i++)
                for (int j = 0; j < w; j++) {
                    long double s = 0;
                    for (int q = 0; q < w; q++) s += T[i * w + q] * J[q * w + j];
                    U[i * w + j] = s * a / t;
                }
            for (int i = 0; i < w * w; i++) { T[i] = U[i]; E[i] += U[i]; }
        }
        for (int s = 0; s < sq; s++) {
            for (int i = 0; i < w; i++)
                for (int j = 0; j < w; j++) {
                    long double v = 0;
                    for (int q = 0; q < w; q++) v += E[i * w + q] * E[q * w + j];
                    U[i * w + j] = v;
                }
            for (int i = 0; i < w * w; i++) E[i] = U[i];
        }
        for (int i = 0; i < w * w; i++) ck_close((double)E[i], ref[i], 1e-13, 1.0, "exp(beta J) vs MPFR R_Y l %d entry %d", l, i);
        free(J), free(ref), free(E), free(T), free(U);
    }
}
END_TEST

#include "../data/papers/krivanek2005_fig2.h"

START_TEST(test_figure2)
{
    const int order = 4;
    double *J = malloc(NB(order) * sizeof *J), *J2 = malloc(NB(order) * sizeof *J2);
    for (int conv = 0; conv < 2; conv++) {
        ck_assert_int_eq(sh_rot_deriv_recursion(order, 1, 0.0, conv, J), SH_OK);
        ck_assert_int_eq(sh_rot_deriv_recursion(order, 2, 0.0, conv, J2), SH_OK);
        for (int l = 1; l <= 3; l++) {
            const int w = 2 * l + 1;
            const double sg = conv == SH_NOCS ? 1.0 : -1.0; /* printed = nocs; cs is −J */
            for (int i = 0; i < w; i++)
                for (int j = 0; j < w; j++) {
                    ck_assert_msg(fabs(sig3(sg * J[NB(l) + i * w + j]) - fig2_J[l - 1][i * w + j]) < 1e-9,
                                  "Figure 2 J conv %d l %d (%d,%d): %.4f vs printed %.4f", conv, l, i - l, j - l,
                                  sg * J[NB(l) + i * w + j], fig2_J[l - 1][i * w + j]);
                    /* cs frame rotation: the transpose of the cs J */
                    if (conv == SH_CS)
                        ck_assert(fabs(sig3(J[NB(l) + j * w + i]) - fig2_J[l - 1][i * w + j]) < 1e-9);
                    ck_assert_msg(fabs(sig3(J2[NB(l) + i * w + j]) - fig2_J2[l - 1][i * w + j]) < 1e-9,
                                  "Figure 2 J2 conv %d l %d (%d,%d): %.4f vs printed %.4f", conv, l, i - l, j - l,
                                  J2[NB(l) + i * w + j], fig2_J2[l - 1][i * w + j]);
                }
        }
    }
    free(J), free(J2);
}
END_TEST

/* Dense reference of a Taylor method: Z(α)·T(β)·Z(γ) from the recursion's J,
 * J² and the z method's blocks, compared with the kernel's blocks. */
static void taylor_reference(int order, sh_rot_method m, const sh_rotation *r, sh_convention conv, double *out)
{
    const size_t nb = NB(order);
    double *J = malloc(nb * sizeof *J), *J2 = malloc(nb * sizeof *J2), *Za = malloc(nb * sizeof *Za),
           *Zg = malloc(nb * sizeof *Zg);
    ck_assert_int_eq(sh_rot_deriv_recursion(order, 1, 0.0, conv, J), SH_OK);
    ck_assert_int_eq(sh_rot_deriv_recursion(order, 2, 0.0, conv, J2), SH_OK);
    sh_rotation za, zg;
    sh_rotation_from_euler(r->alpha, 0, 0, &za);
    sh_rotation_from_euler(r->gamma, 0, 0, &zg);
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_Z, SH_PREC_DOUBLE, conv, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(p, &za), SH_OK);
    ck_assert_int_eq(sh_rot_plan_blocks(p, Za), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(p, &zg), SH_OK);
    ck_assert_int_eq(sh_rot_plan_blocks(p, Zg), SH_OK);
    sh_rot_plan_free(p);
    const double b = r->beta;
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        const size_t o = NB(l);
        double *T = malloc((size_t)w * w * sizeof *T), *U = malloc((size_t)w * w * sizeof *U);
        for (int i = 0; i < w; i++)
            for (int j = 0; j < w; j++) {
                double t = (i == j) + b * J[o + i * w + j];
                if (m == SH_ROT_TAYLOR2 || (m == SH_ROT_TAYLOR15 && i == j)) t += 0.5 * b * b * J2[o + i * w + j];
                T[i * w + j] = t;
            }
        for (int i = 0; i < w; i++)
            for (int j = 0; j < w; j++) {
                double s = 0;
                for (int q = 0; q < w; q++) s += T[i * w + q] * Zg[o + q * w + j];
                U[i * w + j] = s;
            }
        for (int i = 0; i < w; i++)
            for (int j = 0; j < w; j++) {
                double s = 0;
                for (int q = 0; q < w; q++) s += Za[o + i * w + q] * U[q * w + j];
                out[o + i * w + j] = s;
            }
        free(T), free(U);
    }
    free(J), free(J2), free(Za), free(Zg);
}

static const sh_rot_method TAYLORS[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};

START_TEST(test_taylor_blocks)
{
    static const double eul[][3] = {{0.3, 0.1, -0.5}, {-2.0, 0.4, 1.1}, {1.0, 0.0, 2.0}, {2.9, 1.2, -3.0}};
    for (int t = 0; t < 3; t++)
        for (int order = 1; order <= 8; order++) {
            const size_t nb = NB(order);
            double *B = malloc(nb * sizeof *B), *R = malloc(nb * sizeof *R);
            for (size_t e = 0; e < sizeof eul / sizeof *eul; e++)
                for (int conv = 0; conv < 2; conv++)
                    for (int prec = 0; prec < 2; prec++) {
                        sh_rotation r;
                        sh_rotation_from_euler(eul[e][0], eul[e][1], eul[e][2], &r);
                        sh_rot_plan *p;
                        ck_assert_int_eq(sh_rot_plan_create(order, TAYLORS[t], prec, conv, &p), SH_OK);
                        ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
                        ck_assert_int_eq(sh_rot_plan_blocks(p, B), SH_OK);
                        sh_rot_plan_free(p);
                        taylor_reference(order, TAYLORS[t], &r, conv, R);
                        for (size_t i = 0; i < nb; i++)
                            ck_close(B[i], R[i], prec ? 2e-6 : 1e-14, 1.0, "%s blocks order %d rot %zu conv %d prec %d entry %zu",
                                     sh_rot_method_name(TAYLORS[t]), order, e, conv, prec, i);
                    }
            free(B), free(R);
        }
}
END_TEST

START_TEST(test_taylor_apply)
{
    for (int t = 0; t < 3; t++) {
        ck_assert(!sh_rot_method_is_exact(TAYLORS[t]));
        rot_check_apply(TAYLORS[t], SH_PREC_DOUBLE, 1e-13);
        rot_check_apply(TAYLORS[t], SH_PREC_FLOAT, 1e-5);
    }
}
END_TEST

/* β = 0: exact (Z(α)Z(γ) == zxzxz); small β: error O(β²), O(β²), O(β³). */
START_TEST(test_taylor_accuracy)
{
    const int order = 6;
    const size_t nb = NB(order);
    double *B = malloc(nb * sizeof *B), *X = malloc(nb * sizeof *X);
    for (int t = 0; t < 3; t++) {
        sh_rotation r;
        sh_rotation_from_euler(0.7, 0.0, -2.2, &r);
        sh_rot_plan *p, *q;
        ck_assert_int_eq(sh_rot_plan_create(order, TAYLORS[t], SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &q), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(q, &r), SH_OK);
        ck_assert_int_eq(sh_rot_plan_blocks(p, B), SH_OK);
        ck_assert_int_eq(sh_rot_plan_blocks(q, X), SH_OK);
        for (size_t i = 0; i < nb; i++) ck_close(B[i], X[i], 1e-14, 1.0, "%s at beta 0 entry %zu", sh_rot_method_name(TAYLORS[t]), i);
        sh_rot_plan_free(p);
        sh_rot_plan_free(q);
        /* error ratio when β halves: 4 for O(β²), 8 for O(β³) */
        sh_taylor_err e1, e2;
        ck_assert_int_eq(sh_taylor_error(order, TAYLORS[t], 0.02, 7, &e1), SH_OK);
        ck_assert_int_eq(sh_taylor_error(order, TAYLORS[t], 0.01, 7, &e2), SH_OK);
        const double ratio = e1.max / e2.max, expect = TAYLORS[t] == SH_ROT_TAYLOR2 ? 8.0 : 4.0;
        ck_assert_msg(fabs(ratio - expect) < 0.1, "%s error ratio %g, expected %g", sh_rot_method_name(TAYLORS[t]), ratio, expect);
    }
    free(B), free(X);
}
END_TEST

/* multiplications counted by the loop kernels (SH_KERNEL_SCALAR): the set (once per rotation) 2 (β²/2)
 * + multiple angles 4(n−2); one apply, per band l ≥ 1: 8l + c(2l+1),
 * c = 3, 5, 8 (rot_taylor.c). */
START_TEST(test_taylor_mults)
{
    sh_rotation r;
    sh_rotation_from_euler(0.2, 0.3, 1.4, &r);
    static const uint64_t c[3] = {3, 5, 8};
    for (int t = 0; t < 3; t++)
        for (uint64_t n = 1; n <= ROT_MAXO; n++) {
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create_kernel((int)n, TAYLORS[t], SH_PREC_DOUBLE, SH_CS, SH_KERNEL_SCALAR, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            double v[ROT_MAXO * ROT_MAXO] = {0}, g[ROT_MAXO * ROT_MAXO];
            ck_assert_int_eq(sh_rot_plan_apply(p, v, g), SH_OK);
            uint64_t sm, am;
            sh_rot_plan_mults(p, &sm, &am);
            /* Σ_{l=1}^{n−1} 8l + c(2l+1) = 4n(n−1) + c(n²−1) */
            ck_assert_uint_eq(sm, 2 + (n > 2 ? 4 * (n - 2) : 0));
            ck_assert_uint_eq(am, 4 * n * (n - 1) + c[t] * (n * n - 1));
            if (t == 1 && n >= 3) /* the paper's 9n² − 4n less band 0's five */
                ck_assert_uint_eq(am, 9 * n * n - 4 * n - 5);
            sh_rot_plan_free(p);
        }
}
END_TEST

/* Singular values against the dense DᵀD eigenvalues (gsl_eigen_symm) and
 * Σσ² = ‖D‖_F², D = blanco − the taylor blocks; lobe two ways and directly. */
START_TEST(test_error_measures)
{
    const int order = 6, n = order * order;
    const size_t nb = NB(order);
    double *E = malloc(nb * sizeof *E), *A = malloc(nb * sizeof *A), *sv = malloc((size_t)n * sizeof *sv);
    double *D = malloc((size_t)n * n * sizeof *D), *Da = malloc((size_t)n * n * sizeof *Da);
    gsl_matrix *M = gsl_matrix_alloc(n, n);
    gsl_vector *ev = gsl_vector_alloc(n);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(n);
    double z[16];
    ck_assert_int_eq(sh_lobe_zonal(7, order, z), SH_OK);
    double zn = 0;
    for (int l = 0; l < order; l++) zn += z[l] * z[l];
    for (int t = 0; t < 3; t++)
        for (double beta = 0.05; beta < 1.6; beta += 0.5) {
            exact_y(order, SH_ROT_BLANCO, beta, SH_CS, E);
            exact_y(order, TAYLORS[t], beta, SH_CS, A);
            sh_rot_blocks_to_dense(order, E, D);
            sh_rot_blocks_to_dense(order, A, Da);
            double fro = 0;
            for (int i = 0; i < n * n; i++) {
                D[i] -= Da[i];
                fro += D[i] * D[i];
            }
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) {
                    double s = 0;
                    for (int q = 0; q < n; q++) s += D[q * n + i] * D[q * n + j];
                    gsl_matrix_set(M, i, j, s);
                }
            ck_assert_int_eq(gsl_eigen_symm(M, ev, ws), 0);
            double emax = 0, msum = 0;
            for (int i = 0; i < n; i++) {
                emax = fmax(emax, gsl_vector_get(ev, i));
                msum += sqrt(fmax(0, gsl_vector_get(ev, i)));
            }
            sh_taylor_err te;
            ck_assert_int_eq(sh_taylor_error(order, TAYLORS[t], beta, 7, &te), SH_OK);
            ck_assert_int_eq(sh_taylor_singular_values(order, TAYLORS[t], beta, sv), SH_OK);
            double s2 = 0;
            for (int i = 0; i < n; i++) s2 += sv[i] * sv[i];
            const char *nm = sh_rot_method_name(TAYLORS[t]);
            ck_close(s2, fro, 1e-12, 1e-300, "%s sum sigma^2 vs Frobenius beta %g", nm, beta);
            ck_close(te.max, sqrt(emax), 1e-12, 1e-300, "%s max sigma vs eig(DtD) beta %g", nm, beta);
            ck_close(te.mean, msum / n, 1e-7, 1e-300, "%s mean sigma vs eig(DtD) beta %g", nm, beta);
            /* lobe: ‖D c‖ directly, c = z/|z| on m = 0 */
            double lobe2 = 0;
            for (int i = 0; i < n; i++) {
                double y = 0;
                for (int l = 0; l < order; l++) y += D[i * n + l * (l + 1)] * z[l] / sqrt(zn);
                lobe2 += y * y;
            }
            double lb;
            ck_assert_int_eq(sh_taylor_lobe_error(order, TAYLORS[t], beta, 7, &lb), SH_OK);
            ck_close(te.lobe, sqrt(lobe2), 1e-12, 1e-15, "%s lobe (blocks) vs direct beta %g", nm, beta);
            ck_close(lb, sqrt(lobe2), 1e-12, 1e-15, "%s lobe (apply) vs direct beta %g", nm, beta);
        }
    /* the limit: error ≤ tol at it, > tol just above */
    double bl, e;
    ck_assert_int_eq(sh_taylor_lobe_limit(5, SH_ROT_TAYLOR15, 7, 1e-2, M_PI / 2, 0.01, &bl), SH_OK);
    ck_assert_int_eq(sh_taylor_lobe_error(5, SH_ROT_TAYLOR15, bl, 7, &e), SH_OK);
    ck_assert(e <= 1e-2);
    ck_assert_int_eq(sh_taylor_lobe_error(5, SH_ROT_TAYLOR15, bl + 1e-8, 7, &e), SH_OK);
    ck_assert(e > 1e-2);
    ck_assert_int_ne(sh_taylor_error(4, SH_ROT_ZXZXZ, 0.1, 7, &(sh_taylor_err){0}), SH_OK);
    ck_assert_int_ne(sh_taylor_error(4, SH_ROT_TAYLOR1, -0.1, 7, &(sh_taylor_err){0}), SH_OK);
    gsl_matrix_free(M);
    gsl_vector_free(ev);
    gsl_eigen_symm_free(ws);
    free(E), free(A), free(sv), free(D), free(Da);
}
END_TEST

static Suite *suite(void)
{
    (void)rot_check_pointwise, (void)rot_check_orth_homomorphism, (void)rot_check_reference_all;
    Suite *s = suite_create("taylor");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_deriv_two_ways);
    tcase_add_test(tc, test_deriv_finite_differences);
    tcase_add_test(tc, test_deriv_large_k_beta);
    tcase_add_test(tc, test_J_structure);
    tcase_add_test(tc, test_J_exponential);
    tcase_add_test(tc, test_figure2);
    tcase_add_test(tc, test_taylor_blocks);
    tcase_add_test(tc, test_taylor_apply);
    tcase_add_test(tc, test_taylor_accuracy);
    tcase_add_test(tc, test_taylor_mults);
    tcase_add_test(tc, test_error_measures);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
