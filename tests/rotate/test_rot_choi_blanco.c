/* test_rot_choi_blanco.c — the `choi` (complex recursion, Choi et al. 1999)
 * and `blanco` (d^l recurrences, Blanco et al. 1997) rotation methods, and
 * blanco's single-band m-recurrence path.
 *
 * Truths: sh_rot_reference_band (MPFR, ≥ 30 digits) at orders 1..10, both
 * conventions, seeded random rotations and the extremes β = 0, 1e-12, π/2,
 * π − 1e-9, π and gimbal cases; pointwise Σ g_i y_i(s) = Σ c_i y_i(R⁻¹s);
 * orthogonality; the homomorphism R(a)R(b) = R(ab); the imaginary part of
 * choi's conj(U) D Uᵀ vanishing.  Nothing here is a number copied from our
 * own output.  The largest errors seen are printed (for the closing note).
 *
 * Tolerances: double 1e-13 absolute (what every exact method must meet).  Float: 2e-5 absolute
 * (≈ 170 FLT_EPSILON): entries are ≤ 1 and the kernels take O(l) float
 * roundings per entry (l ≤ 9), plus the float rounding of the angles. */
#include "testutil.h"
#include "rotate/rot_internal.h"

#include <string.h>

int sh__rot_choi_blocks_imag_d(int order, const sh_rotation *rot, const void *tables,
                               double *blocks, void *work, uint64_t *mults, double *imag_max);

static unsigned long rng_state = 20240903;
static double urand(void)
{
    rng_state = rng_state * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

#define NROT 16
static sh_rotation rots[NROT];
static const char *rot_names[NROT];

static void make_rotations(void)
{
    static char names[NROT][48];
    const double b_ext[5] = {0.0, 1e-12, M_PI / 2, M_PI - 1e-9, M_PI};
    int k = 0;
    rng_state = 20240903;
    for (int i = 0; i < 5; i++, k++) { /* extremes in β with random α, γ */
        double a = (2 * urand() - 1) * M_PI, g = (2 * urand() - 1) * M_PI;
        sh_rotation_from_euler(a, b_ext[i], g, &rots[k]);
        snprintf(names[k], sizeof names[k], "beta=%.3g", b_ext[i]);
    }
    /* gimbal cases */
    const double gim[5][3] = {{0, 0, 0}, {0, M_PI, 0}, {0.7, 1e-12, -0.7}, {1.3, 0, -0.4}, {-2.0, M_PI, 1.1}};
    for (int i = 0; i < 5; i++, k++) {
        sh_rotation_from_euler(gim[i][0], gim[i][1], gim[i][2], &rots[k]);
        snprintf(names[k], sizeof names[k], "gimbal(%g,%g,%g)", gim[i][0], gim[i][1], gim[i][2]);
    }
    for (; k < NROT; k++) { /* seeded random rotations (uniform quaternions) */
        double q[4], n = 0;
        for (int j = 0; j < 4; j++) {
            q[j] = sqrt(-2 * log(urand() + 1e-300)) * cos(2 * M_PI * urand());
            n += q[j] * q[j];
        }
        for (int j = 0; j < 4; j++) q[j] /= sqrt(n);
        sh_rotation_from_quat(q, 0, &rots[k]);
        snprintf(names[k], sizeof names[k], "random #%d", k);
    }
    for (k = 0; k < NROT; k++) rot_names[k] = names[k];
}

/* reference blocks (order 10) per rotation and convention, computed once */
#define ORD 10
static double *refs[NROT][2];

static void setup(void)
{
    make_rotations();
    for (int r = 0; r < NROT; r++)
        for (int c = 0; c < 2; c++) {
            double *b = malloc(sh_rot_block_offset(ORD) * sizeof *b);
            for (int l = 0; l < ORD; l++)
                ck_assert_int_eq(sh_rot_reference_band(l, (sh_convention)c, &rots[r], 32,
                                                       b + sh_rot_block_offset(l), NULL),
                                 SH_OK);
            refs[r][c] = b;
        }
}
static void teardown(void)
{
    for (int r = 0; r < NROT; r++)
        for (int c = 0; c < 2; c++) free(refs[r][c]);
}

/* max |plan blocks − reference| over orders 1..10, all rotations, both conventions */
static double max_err_vs_reference(sh_rot_method m, sh_precision prec, double tol)
{
    double worst = 0;
    double *b = malloc(sh_rot_block_offset(ORD) * sizeof *b);
    for (int order = 1; order <= ORD; order++)
        for (int c = 0; c < 2; c++) {
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create(order, m, prec, (sh_convention)c, &p), SH_OK);
            for (int r = 0; r < NROT; r++) {
                ck_assert_int_eq(sh_rot_plan_set(p, &rots[r]), SH_OK);
                ck_assert_int_eq(sh_rot_plan_blocks(p, b), SH_OK);
                const size_t nb = sh_rot_block_offset(order);
                for (size_t i = 0; i < nb; i++) {
                    const double e = fabs(b[i] - refs[r][c][i]);
                    if (!(e <= tol))
                        ck_abort_msg("%s %s order %d %s %s: entry %zu err %.3g > %.3g",
                                     sh_rot_method_name(m), sh_precision_name(prec), order,
                                     sh_convention_name((sh_convention)c), rot_names[r], i, e, tol);
                    if (e > worst) worst = e;
                }
            }
            sh_rot_plan_free(p);
        }
    free(b);
    return worst;
}

static const sh_rot_method mine[2] = {SH_ROT_CHOI, SH_ROT_BLANCO};

START_TEST(test_reference_double)
{
    const double e = max_err_vs_reference(mine[_i], SH_PREC_DOUBLE, 1e-13);
    printf("%s double: max |R - reference| over orders 1..10, %d rotations, cs+nocs = %.3g\n",
           sh_rot_method_name(mine[_i]), NROT, e);
}
END_TEST

START_TEST(test_reference_float)
{
    const double e = max_err_vs_reference(mine[_i], SH_PREC_FLOAT, 2e-5);
    printf("%s float: max |R - reference| over orders 1..10, %d rotations, cs+nocs = %.3g\n",
           sh_rot_method_name(mine[_i]), NROT, e);
}
END_TEST

/* apply == blocks × vector (done here by hand), mults counted > 0 */
START_TEST(test_apply_and_mults)
{
    const sh_rot_method m = mine[_i];
    for (int order = 2; order <= ORD; order++)
        for (int c = 0; c < 2; c++) {
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create(order, m, SH_PREC_DOUBLE, (sh_convention)c, &p), SH_OK);
            const int n = order * order;
            double *b = malloc(sh_rot_block_offset(order) * sizeof *b), x[ORD * ORD], y[ORD * ORD];
            for (int r = 0; r < NROT; r += 3) {
                ck_assert_int_eq(sh_rot_plan_set(p, &rots[r]), SH_OK);
                ck_assert_int_eq(sh_rot_plan_blocks(p, b), SH_OK);
                for (int i = 0; i < n; i++) x[i] = 2 * urand() - 1;
                ck_assert_int_eq(sh_rot_plan_apply(p, x, y), SH_OK);
                for (int l = 0; l < order; l++) {
                    const int w = 2 * l + 1;
                    const double *B = b + sh_rot_block_offset(l);
                    for (int i = 0; i < w; i++) {
                        double s = 0;
                        for (int j = 0; j < w; j++) s += B[i * w + j] * x[l * l + j];
                        ck_close(y[l * l + i], s, 1e-15, 1.0, "%s apply order %d row %d",
                                 sh_rot_method_name(m), order, l * l + i);
                    }
                }
                uint64_t sm = 0, am = 0;
                sh_rot_plan_mults(p, &sm, &am);
                ck_assert_msg(sm > 0 && am > 0, "%s order %d: mults set %llu apply %llu",
                              sh_rot_method_name(m), order, (unsigned long long)sm,
                              (unsigned long long)am);
            }
            free(b);
            sh_rot_plan_free(p);
        }
}
END_TEST

/* g = R c evaluated at s equals f at R⁻¹ s, at random directions */
START_TEST(test_pointwise)
{
    const sh_rot_method m = mine[_i];
    const int order = 7, n = order * order;
    for (int c = 0; c < 2; c++) {
        sh_rot_plan *p;
        ck_assert_int_eq(sh_rot_plan_create(order, m, SH_PREC_DOUBLE, (sh_convention)c, &p), SH_OK);
        for (int r = 0; r < NROT; r++) {
            double coef[64], g[64], y[64], s[3], rs[3];
            for (int i = 0; i < n; i++) coef[i] = 2 * urand() - 1;
            ck_assert_int_eq(sh_rot_plan_set(p, &rots[r]), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(p, coef, g), SH_OK);
            for (int k = 0; k < 5; k++) {
                sh_dir_from_angles(acos(2 * urand() - 1), 2 * M_PI * urand(), s);
                for (int i = 0; i < 3; i++) /* R⁻¹ s = Rᵀ s */
                    rs[i] = rots[r].R[i] * s[0] + rots[r].R[3 + i] * s[1] + rots[r].R[6 + i] * s[2];
                double lhs = 0, rhs = 0;
                sh_eval_dir(order, (sh_convention)c, s, y);
                for (int i = 0; i < n; i++) lhs += g[i] * y[i];
                sh_eval_dir(order, (sh_convention)c, rs, y);
                for (int i = 0; i < n; i++) rhs += coef[i] * y[i];
                ck_close(lhs, rhs, 1e-13, 1.0, "%s pointwise %s %s", sh_rot_method_name(m),
                         sh_convention_name((sh_convention)c), rot_names[r]);
            }
        }
        sh_rot_plan_free(p);
    }
}
END_TEST

/* orthogonality max|R Rᵀ − I| and homomorphism R(a)R(b) = R(ab) at order 10 */
START_TEST(test_orthogonal_homomorphism)
{
    const sh_rot_method m = mine[_i];
    const size_t nb = sh_rot_block_offset(ORD);
    double *A = malloc(nb * sizeof *A), *B = malloc(nb * sizeof *B), *C = malloc(nb * sizeof *C);
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(ORD, m, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    for (int r = 0; r < NROT; r++) {
        const int r2 = (r * 7 + 3) % NROT;
        sh_rotation ab;
        sh_rotation_compose(&rots[r], &rots[r2], &ab);
        sh_rot_plan_set(p, &rots[r]);
        sh_rot_plan_blocks(p, A);
        sh_rot_plan_set(p, &rots[r2]);
        sh_rot_plan_blocks(p, B);
        sh_rot_plan_set(p, &ab);
        sh_rot_plan_blocks(p, C);
        for (int l = 0; l < ORD; l++) {
            const int w = 2 * l + 1;
            const size_t o = sh_rot_block_offset(l);
            for (int i = 0; i < w; i++)
                for (int j = 0; j < w; j++) {
                    double rr = 0, ab_ij = 0;
                    for (int k = 0; k < w; k++) {
                        rr += A[o + i * w + k] * A[o + j * w + k];
                        ab_ij += A[o + i * w + k] * B[o + k * w + j];
                    }
                    ck_close(rr, i == j, 1e-13, 1.0, "%s orthogonality l=%d %s", sh_rot_method_name(m), l,
                             rot_names[r]);
                    ck_close(ab_ij, C[o + i * w + j], 1e-13, 1.0, "%s homomorphism l=%d %s·%s",
                             sh_rot_method_name(m), l, rot_names[r], rot_names[r2]);
                }
        }
    }
    sh_rot_plan_free(p);
    free(A);
    free(B);
    free(C);
}
END_TEST

/* choi: Im(conj(U) D Uᵀ) vanishes (it is computed, not assumed) */
START_TEST(test_choi_imaginary_part)
{
    void *tables;
    ck_assert_int_eq(sh__rot_choi_ops.tables_new_d(ORD, &tables), SH_OK);
    void *work = malloc(sh__rot_choi_ops.work_bytes(ORD));
    double *b = malloc(sh_rot_block_offset(ORD) * sizeof *b), worst = 0;
    for (int r = 0; r < NROT; r++) {
        double im = -1;
        ck_assert_int_eq(sh__rot_choi_blocks_imag_d(ORD, &rots[r], tables, b, work, NULL, &im), SH_OK);
        ck_assert_msg(im >= 0 && im < 1e-14, "choi: max |Im| = %.3g at %s", im, rot_names[r]);
        if (im > worst) worst = im;
    }
    printf("choi: max |Im(conj(U) D U^T)| over %d rotations, order 10 = %.3g\n", NROT, worst);
    free(b);
    free(work);
    sh__rot_choi_ops.tables_free(tables);
}
END_TEST

/* blanco's single band (m-recurrence) against the reference, both conventions */
START_TEST(test_blanco_single_band)
{
    const int bands[] = {0, 1, 2, 7, 10, 33, 50};
    /* 1e-100 .. 1e-190: one step of the m-recurrence grows by ~4l/sinβ, more
     * than its 2^300 rescaling (the row overflowed to NaN; found by fuzzing) */
    const double betas[] = {0.0, 1e-12, 0.3, M_PI / 2, 2.4, M_PI - 1e-9, M_PI, 1e-100, 1e-150, 1e-190};
    double worst = 0;
    for (size_t ib = 0; ib < sizeof bands / sizeof *bands; ib++)
        for (size_t k = 0; k < sizeof betas / sizeof *betas; k++)
            for (int c = 0; c < 2; c++) {
                const int l = bands[ib], w = 2 * l + 1;
                sh_rotation rot;
                sh_rotation_from_euler(0.9 - k, betas[k], -1.7 + 0.5 * k, &rot);
                double *got = malloc((size_t)w * w * sizeof *got), *ref = malloc((size_t)w * w * sizeof *ref);
                ck_assert_int_eq(sh_rot_band(l, SH_ROT_BLANCO, SH_PREC_DOUBLE, (sh_convention)c, &rot, got),
                                 SH_OK);
                ck_assert_int_eq(sh_rot_reference_band(l, (sh_convention)c, &rot, 32, ref, NULL), SH_OK);
                for (int i = 0; i < w * w; i++) {
                    const double e = fabs(got[i] - ref[i]);
                    if (!(e <= 1e-13))
                        ck_abort_msg("blanco band %d beta %.17g %s entry %d: err %.3g", l, betas[k],
                                     sh_convention_name((sh_convention)c), i, e);
                    if (e > worst) worst = e;
                }
                free(got);
                free(ref);
            }
    printf("blanco single band: max |R - reference| at l <= 50, 10 betas, cs+nocs = %.3g\n", worst);
}
END_TEST


/* Regression (named after the bug): blanco's eq. 64 with cosβ rounded to −1
 * at β = π − 1e-9 disagreed with its exact-β edge columns and blew up
 * (error 2e-8 at l = 100, 99 at l = 200).  Band 100 vs the reference. */
START_TEST(test_blanco_cos_rounding_near_pi)
{
    const int order = 101, l = 100, w = 2 * l + 1;
    sh_rotation rot;
    sh_rotation_from_euler(0.4, M_PI - 1e-9, -2.2, &rot);
    double *all = malloc(sh_rot_block_offset(order) * sizeof *all), *ref = malloc((size_t)w * w * sizeof *ref);
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_BLANCO, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(p, &rot), SH_OK);
    ck_assert_int_eq(sh_rot_plan_blocks(p, all), SH_OK);
    ck_assert_int_eq(sh_rot_reference_band(l, SH_CS, &rot, 32, ref, NULL), SH_OK);
    for (int i = 0; i < w * w; i++)
        ck_close(all[sh_rot_block_offset(l) + i], ref[i], 1e-11, 1.0, "blanco l=100 beta=pi-1e-9 entry %d", i);
    sh_rot_plan_free(p);
    free(all);
    free(ref);
}
END_TEST

static Suite *rot_suite(void)
{
    Suite *s = suite_create("rot_choi_blanco");
    TCase *tc = tcase_create("methods");
    tcase_add_unchecked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 60);
    tcase_add_loop_test(tc, test_reference_double, 0, 2);
    tcase_add_loop_test(tc, test_reference_float, 0, 2);
    tcase_add_loop_test(tc, test_apply_and_mults, 0, 2);
    tcase_add_loop_test(tc, test_pointwise, 0, 2);
    tcase_add_loop_test(tc, test_orthogonal_homomorphism, 0, 2);
    tcase_add_test(tc, test_choi_imaginary_part);
    tcase_add_test(tc, test_blanco_single_band);
    tcase_add_test(tc, test_blanco_cos_rounding_near_pi);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(rot_suite)
