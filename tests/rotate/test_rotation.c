/* test_rotation.c — rotation input forms, ZYZ extraction, and every exact
 * rotation method registered in the plan.
 *
 * Truths (none from our own output):
 *  - pointwise: g = R_sh c satisfies Σ g_i y_i(s) = Σ c_i y_i(R⁻¹s) (sh_eval_dir,
 *    the basis evaluation, tested against GSL), in both conventions;
 *  - the MPFR reference, itself checked by recomputation with 100 more bits;
 *  - identities: R Rᵀ = I, R(A)R(B) = R(AB), R(R⁻¹) = R(R)ᵀ;
 *  - matrices built from angles by hand (Rz, Ry written out), quaternion and
 *    axis-angle formulas against each other.
 */
#include "testutil.h"

#include <string.h>

#include "rotate/rot_internal.h"

static unsigned long rng_state = 4242;
static double urand(void)
{
    rng_state = rng_state * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* The rotation set: seeded random ones plus the extremes. */
#define NROT 14
static void rotation_set(sh_rotation *r)
{
    const double e[][3] = {
        {0, 0, 0},         {0.7, 0, -0.2},      {0.3, 1e-12, -0.3},  {1.1, 1e-12, 2.0},
        {0.4, M_PI / 2, -1.3}, {-2.0, M_PI - 1e-9, 0.5}, {0, M_PI, 0}, {1.0, M_PI, -0.4},
        {M_PI, M_PI / 2, M_PI}, {0.5, 1e-7, -0.5},
    };
    int k = 0;
    for (; k < 10; k++) sh_rotation_from_euler(e[k][0], e[k][1], e[k][2], &r[k]);
    rng_state = 4242;
    for (; k < NROT; k++)
        sh_rotation_from_euler(2 * M_PI * urand() - M_PI, M_PI * urand(), 2 * M_PI * urand() - M_PI,
                               &r[k]);
}

static void mat3_mul(const double *A, const double *B, double *C)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += A[3 * i + k] * B[3 * k + j];
            C[3 * i + j] = s;
        }
}

/* ---------------------------------------------------------------- input */
START_TEST(test_euler_matrix_by_hand)
{
    /* R = Rz(α) Ry(β) Rz(γ) multiplied out here from docs/CONVENTIONS.md */
    const double a = 0.3, b = 1.2, g = -2.1;
    const double Rza[9] = {cos(a), -sin(a), 0, sin(a), cos(a), 0, 0, 0, 1};
    const double Ryb[9] = {cos(b), 0, sin(b), 0, 1, 0, -sin(b), 0, cos(b)};
    const double Rzg[9] = {cos(g), -sin(g), 0, sin(g), cos(g), 0, 0, 0, 1};
    double T[9], R[9];
    mat3_mul(Rza, Ryb, T);
    mat3_mul(T, Rzg, R);
    sh_rotation r;
    ck_assert_int_eq(sh_rotation_from_euler(a, b, g, &r), SH_OK);
    for (int i = 0; i < 9; i++) ck_close(r.R[i], R[i], TOL1, 1, "R[%d]", i);
}
END_TEST

START_TEST(test_euler_extraction_roundtrip)
{
    sh_rotation set[NROT];
    rotation_set(set);
    double worst = 0;
    for (int k = 0; k < NROT; k++) {
        double a, b, g;
        sh_euler_from_matrix(set[k].R, &a, &b, &g);
        ck_assert(b >= 0 && b <= M_PI && a > -M_PI && a <= M_PI && g > -M_PI && g <= M_PI);
        sh_rotation back;
        sh_rotation_from_euler(a, b, g, &back);
        for (int i = 0; i < 9; i++) worst = fmax(worst, fabs(back.R[i] - set[k].R[i]));
    }
    /* near-degenerate cases (β = 1e-12, π − 1e-9) included */
    ck_close(worst, 0, 4 * DBL_EPSILON, 1, "max |R(euler(R)) − R|");
    /* the degenerate cases return α = 0 and put the whole angle in γ */
    double a, b, g;
    sh_rotation r;
    sh_rotation_from_euler(0.4, 0, 0.5, &r);
    sh_euler_from_matrix(r.R, &a, &b, &g);
    ck_assert(a == 0 && b == 0);
    ck_close(g, 0.9, TOL1, 1, "β = 0: γ = α+γ");
    /* at β = π only α−γ is defined (sin π ≠ 0 in double, so α is arbitrary) */
    sh_rotation_from_euler(0.4, M_PI, 0.1, &r);
    sh_euler_from_matrix(r.R, &a, &b, &g);
    ck_close(b, M_PI, TOL0, 1, "β = π");
    ck_close(remainder(a - g, 2 * M_PI), 0.3, TOL1, 1, "β = π: α−γ");
}
END_TEST

START_TEST(test_quat_axis_forms)
{
    /* rotation by t about z three ways */
    const double t = 0.8, q[4] = {cos(t / 2), 0, 0, sin(t / 2)}, z[3] = {0, 0, 2};
    sh_rotation a, b, c;
    ck_assert_int_eq(sh_rotation_from_quat(q, 0, &a), SH_OK);
    ck_assert_int_eq(sh_rotation_from_axis_angle(z, t, &b), SH_OK);
    sh_rotation_from_euler(t, 0, 0, &c);
    for (int i = 0; i < 9; i++) {
        ck_close(a.R[i], c.R[i], TOL1, 1, "quat R[%d]", i);
        ck_close(b.R[i], c.R[i], TOL1, 1, "axis R[%d]", i);
    }
    /* rotation by 90° about x maps y to z (right-hand rule) */
    const double x[3] = {1, 0, 0};
    sh_rotation_from_axis_angle(x, M_PI / 2, &a);
    ck_close(a.R[7], 1, TOL1, 1, "Rx(90) y -> z: R21");
    /* to_quat / to_axis_angle invert the constructors on the random set */
    sh_rotation set[NROT];
    rotation_set(set);
    for (int k = 0; k < NROT; k++) {
        double qq[4], ax[3], ang;
        sh_rotation_to_quat(&set[k], qq);
        sh_rotation_to_axis_angle(&set[k], ax, &ang);
        sh_rotation_from_quat(qq, 0, &a);
        sh_rotation_from_axis_angle(ax, ang, &b);
        for (int i = 0; i < 9; i++) {
            ck_close(a.R[i], set[k].R[i], TOL2, 1, "quat round trip %d R[%d]", k, i);
            ck_close(b.R[i], set[k].R[i], TOL2, 1, "axis round trip %d R[%d]", k, i);
        }
    }
}
END_TEST

START_TEST(test_matrix_checks)
{
    const double refl[9] = {1, 0, 0, 0, 1, 0, 0, 0, -1};
    const double skew[9] = {1, 0.01, 0, 0, 1, 0, 0, 0, 1};
    sh_rotation r;
    ck_assert_int_eq(sh_rotation_from_matrix(refl, 0, &r), SH_EINVAL);
    ck_assert(strstr(sh_last_error(), "determinant") != NULL);
    ck_assert_int_eq(sh_rotation_from_matrix(skew, 0, &r), SH_EINVAL);
    ck_assert(strstr(sh_last_error(), "orthogonal") != NULL);
    /* --orthonormalize: the polar factor of a perturbed rotation is the
     * rotation to first order in the (symmetric) perturbation */
    sh_rotation set[NROT], back;
    rotation_set(set);
    double M[9];
    for (int i = 0; i < 9; i++) M[i] = set[13].R[i] * 1.001;
    ck_assert_int_eq(sh_rotation_from_matrix(M, 0, &r), SH_EINVAL);
    ck_assert_int_eq(sh_rotation_from_matrix(M, 1, &r), SH_OK);
    for (int i = 0; i < 9; i++) ck_close(r.R[i], set[13].R[i], TOL2, 1, "polar R[%d]", i);
    /* a reflection cannot be made a rotation by scaling: det fixed to +1 */
    ck_assert_int_eq(sh_rotation_from_matrix(refl, 1, &back), SH_OK);
    const double *R = back.R;
    const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                       R[2] * (R[3] * R[7] - R[4] * R[6]);
    ck_close(det, 1, TOL1, 1, "det after orthonormalize");
    const double nan_m[9] = {NAN, 0, 0, 0, 1, 0, 0, 0, 1};
    ck_assert_int_eq(sh_rotation_from_matrix(nan_m, 1, &r), SH_EINVAL);
    const double q0[4] = {0, 0, 0, 0};
    ck_assert_int_eq(sh_rotation_from_quat(q0, 1, &r), SH_EINVAL);
}
END_TEST

START_TEST(test_inverse_compose)
{
    sh_rotation set[NROT], inv, prod;
    rotation_set(set);
    for (int k = 0; k < NROT; k++) {
        sh_rotation_inverse(&set[k], &inv);
        sh_rotation fromangles;
        sh_rotation_from_euler(inv.alpha, inv.beta, inv.gamma, &fromangles);
        sh_rotation_compose(&set[k], &inv, &prod);
        for (int i = 0; i < 9; i++) {
            ck_close(prod.R[i], (i % 4 == 0), TOL1, 1, "R R⁻¹ %d [%d]", k, i);
            ck_close(fromangles.R[i], inv.R[i], TOL1, 1, "angles of inverse %d [%d]", k, i);
        }
    }
}
END_TEST

/* --------------------------------------------------------------- methods */
/* the exact methods that are built in */
/* an exact method that reaches `order` (direct stops at 3) */
static int method_ok(int m, int order)
{
    return sh_rot_method_is_exact((sh_rot_method)m) && sh_rot_method_max_order((sh_rot_method)m) >= order;
}

/* Dense rotation matrix of `order` from a plan (NULL on failure). */
static double *plan_blocks(int order, int m, sh_precision prec, sh_convention conv,
                           const sh_rotation *rot)
{
    sh_rot_plan *p;
    if (sh_rot_plan_create(order, (sh_rot_method)m, prec, conv, &p)) return NULL;
    double *b = malloc(sh_rot_block_offset(order) * sizeof *b);
    if (sh_rot_plan_set(p, rot) || sh_rot_plan_blocks(p, b)) {
        free(b);
        b = NULL;
    }
    sh_rot_plan_free(p);
    return b;
}

/* z handles only β = 0 */
static int method_accepts(int m, const sh_rotation *r) { return m != SH_ROT_Z || r->beta == 0; }

START_TEST(test_pointwise_truth)
{
    /* for every method, order 6, both conventions: rotating the coefficients
     * rotates the function */
    const int order = 6, n = 36;
    sh_rotation set[NROT];
    rotation_set(set);
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (!method_ok(m, order)) continue;
        for (int cv = 0; cv < 2; cv++)
            for (int k = 0; k < NROT; k++) {
                if (!method_accepts(m, &set[k])) continue;
                sh_rot_plan *p;
                ck_assert_int_eq(sh_rot_plan_create(order, (sh_rot_method)m, SH_PREC_DOUBLE, cv, &p), SH_OK);
                ck_assert_int_eq(sh_rot_plan_set(p, &set[k]), SH_OK);
                double c[36], g[36];
                for (int i = 0; i < n; i++) c[i] = urand() - 0.5;
                ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
                sh_rot_plan_free(p);
                for (int t = 0; t < 8; t++) {
                    double s[3] = {urand() - 0.5, urand() - 0.5, urand() - 0.5}, ri[3];
                    for (int i = 0; i < 3; i++)
                        ri[i] = set[k].R[i] * s[0] + set[k].R[3 + i] * s[1] + set[k].R[6 + i] * s[2];
                    double ys[36], yr[36], f = 0, gg = 0;
                    sh_eval_dir(order, cv, s, ys);
                    sh_eval_dir(order, cv, ri, yr);
                    for (int i = 0; i < n; i++) { f += c[i] * yr[i]; gg += g[i] * ys[i]; }
                    ck_close(gg, f, 64 * DBL_EPSILON, 1, "%s %s rot %d point %d",
                             sh_rot_method_name(m), sh_convention_name(cv), k, t);
                }
            }
    }
}
END_TEST

START_TEST(test_methods_vs_reference)
{
    /* the accuracy shlab requires: every method within 1e-13 of the reference at orders
     * ≤ 10 over the rotation set, both conventions; float within 2e-6 */
    const int order = 10;
    sh_rotation set[NROT];
    rotation_set(set);
    const size_t nb = sh_rot_block_offset(order);
    for (int k = 0; k < NROT; k++)
        for (int cv = 0; cv < 2; cv++) {
            double *ref = malloc(nb * sizeof *ref);
            for (int l = 0; l < order; l++)
                ck_assert_int_eq(sh_rot_reference_band(l, cv, &set[k], 32, ref + sh_rot_block_offset(l), NULL), SH_OK);
            for (int m = 0; m < SH_ROT_NMETHODS; m++) {
                if (!method_ok(m, order) || m == SH_ROT_REFERENCE || !method_accepts(m, &set[k])) continue;
                for (int pr = 0; pr < 2; pr++) {
                    double *b = plan_blocks(order, m, pr, cv, &set[k]);
                    ck_assert_msg(b != NULL, "%s: %s", sh_rot_method_name(m), sh_last_error());
                    double worst = 0;
                    for (size_t i = 0; i < nb; i++) worst = fmax(worst, fabs(b[i] - ref[i]));
                    free(b);
                    ck_close(worst, 0, pr ? 2e-6 : 1e-13, 1, "%s %s %s rot %d (β=%.3g): max|R − ref|",
                             sh_rot_method_name(m), sh_precision_name(pr), sh_convention_name(cv), k,
                             set[k].beta);
                }
            }
            free(ref);
        }
}
END_TEST

START_TEST(test_identities)
{
    /* orthogonality, homomorphism and inverse = transpose at order 12 */
    const int order = 12;
    sh_rotation set[NROT], ab, inv;
    rotation_set(set);
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (!method_ok(m, order) || m == SH_ROT_Z || m == SH_ROT_REFERENCE) continue;
        for (int k = 0; k + 1 < NROT; k += 3) {
            sh_rotation_compose(&set[k], &set[k + 1], &ab);
            sh_rotation_inverse(&set[k], &inv);
            double *A = plan_blocks(order, m, 0, SH_CS, &set[k]);
            double *B = plan_blocks(order, m, 0, SH_CS, &set[k + 1]);
            double *C = plan_blocks(order, m, 0, SH_CS, &ab);
            double *I = plan_blocks(order, m, 0, SH_CS, &inv);
            ck_assert(A && B && C && I);
            double orth = 0, hom = 0, tr = 0;
            for (int l = 0; l < order; l++) {
                const int w = 2 * l + 1;
                const size_t o = sh_rot_block_offset(l);
                for (int i = 0; i < w; i++)
                    for (int j = 0; j < w; j++) {
                        double s = 0, h = 0;
                        for (int q = 0; q < w; q++) {
                            s += A[o + i * w + q] * A[o + j * w + q];
                            h += A[o + i * w + q] * B[o + q * w + j];
                        }
                        orth = fmax(orth, fabs(s - (i == j)));
                        hom = fmax(hom, fabs(h - C[o + i * w + j]));
                        tr = fmax(tr, fabs(I[o + i * w + j] - A[o + j * w + i]));
                    }
            }
            free(A); free(B); free(C); free(I);
            ck_close(orth, 0, 1e-13, 1, "%s rot %d: max|RRᵀ − I|", sh_rot_method_name(m), k);
            ck_close(hom, 0, 1e-13, 1, "%s rot %d: max|R(a)R(b) − R(ab)|", sh_rot_method_name(m), k);
            ck_close(tr, 0, 1e-13, 1, "%s rot %d: max|R(R⁻¹) − R(R)ᵀ|", sh_rot_method_name(m), k);
        }
    }
}
END_TEST

START_TEST(test_apply_band_consistency)
{
    /* apply == blocks × vector (also in place), sh_rot_band == the plan's
     * last block, and counted multiplications are positive */
    const int order = 9;
    sh_rotation set[NROT];
    rotation_set(set);
    const sh_rotation *r = &set[12];
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (!method_ok(m, order) || m == SH_ROT_Z) continue;
        for (int cv = 0; cv < 2; cv++) {
            double *b = plan_blocks(order, m, 0, cv, r), *D = malloc(81 * 81 * sizeof *D);
            sh_rot_blocks_to_dense(order, b, D);
            double c[81], g[81], h[81];
            for (int i = 0; i < 81; i++) c[i] = urand() - 0.5;
            sh_rot_plan *p;
            sh_rot_plan_create(order, (sh_rot_method)m, SH_PREC_DOUBLE, cv, &p);
            sh_rot_plan_set(p, r);
            sh_rot_plan_apply(p, c, g);
            uint64_t ms, ma;
            sh_rot_plan_mults(p, &ms, &ma);
            ck_assert_msg(ma > 0, "%s counts apply multiplications", sh_rot_method_name(m));
            memcpy(h, c, sizeof h);
            sh_rot_plan_apply(p, h, h);
            sh_rot_plan_free(p);
            for (int i = 0; i < 81; i++) {
                double s = 0;
                for (int j = 0; j < 81; j++) s += D[i * 81 + j] * c[j];
                ck_close(g[i], s, 1e-14, 1, "%s %s apply[%d]", sh_rot_method_name(m), sh_convention_name(cv), i);
                ck_close(h[i], g[i], 0, 1, "%s in place [%d]", sh_rot_method_name(m), i);
            }
            double band[17 * 17];
            ck_assert_int_eq(sh_rot_band(8, (sh_rot_method)m, SH_PREC_DOUBLE, cv, r, band), SH_OK);
            for (int i = 0; i < 17 * 17; i++)
                ck_close(band[i], b[sh_rot_block_offset(8) + i], 1e-14, 1, "%s band 8 [%d]",
                         sh_rot_method_name(m), i);
            free(b);
            free(D);
        }
    }
}
END_TEST

START_TEST(test_z_method)
{
    sh_rotation r;
    sh_rotation_from_euler(0.3, 0.2, 0, &r);
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(4, SH_ROT_Z, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_EINVAL); /* tilted: refused */
    sh_rot_plan_free(p);
}
END_TEST

START_TEST(test_reference_digits)
{
    /* the reference's claim of ≥ 30 digits, measured against 100 more bits */
    sh_rotation set[NROT];
    rotation_set(set);
    const int bands[] = {1, 5, 20, 60};
    for (int k = 4; k < NROT; k += 3)
        for (int b = 0; b < 4; b++) {
            double d;
            ck_assert_int_eq(sh__rot_reference_selfcheck(bands[b], &set[k], 30, &d), SH_OK);
            ck_assert_msg(d < 1e-30, "reference band %d rot %d: %.3g", bands[b], k, d);
        }
}
END_TEST

START_TEST(test_bad_arguments)
{
    sh_rot_plan *p;
    ck_assert_int_eq(sh_rot_plan_create(0, SH_ROT_WIGNER, SH_PREC_DOUBLE, SH_CS, &p), SH_EINVAL);
    ck_assert_int_eq(sh_rot_plan_create(401, SH_ROT_WIGNER, SH_PREC_DOUBLE, SH_CS, &p), SH_EINVAL);
    ck_assert_int_eq(sh_rot_plan_create(3, (sh_rot_method)99, SH_PREC_DOUBLE, SH_CS, &p), SH_EINVAL);
    sh_rot_method m;
    ck_assert_int_eq(sh_rot_method_parse("nope", &m), SH_EINVAL);
    ck_assert_int_eq(sh_rot_plan_create(3, SH_ROT_WIGNER, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    double v[9] = {0};
    ck_assert_int_eq(sh_rot_plan_apply(p, v, v), SH_EINVAL); /* no rotation set */
    sh_rot_plan_free(p);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rotation");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, test_euler_matrix_by_hand);
    tcase_add_test(t, test_euler_extraction_roundtrip);
    tcase_add_test(t, test_quat_axis_forms);
    tcase_add_test(t, test_matrix_checks);
    tcase_add_test(t, test_inverse_compose);
    tcase_add_test(t, test_pointwise_truth);
    tcase_add_test(t, test_methods_vs_reference);
    tcase_add_test(t, test_identities);
    tcase_add_test(t, test_apply_band_consistency);
    tcase_add_test(t, test_z_method);
    tcase_add_test(t, test_reference_digits);
    tcase_add_test(t, test_bad_arguments);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
