/* test_rot_zxzxz.c — the `zxzxz` method (src/rotate/rot_zxzxz.c).
 *
 * Truths: the MPFR reference (orders 1..10, seeded random rotations and the
 * extremes, both conventions, double and float plans; the sparse apply is
 * compared with the blocks and with the pointwise identity), and for the
 * fixed X₊₉₀ blocks the MPFR reference band of Rx(+90°) itself: the
 * structural zero pattern the sparse loops rely on is proved on it, and the
 * generated blocks (d(π/2) recurrence) are compared with it to l = 100. */
#include "rottest.h"

/* src/rotate/rot_zxzxz.c: the dense X₊₉₀ block of band l as the tables are built */
int sh__rot_zxzxz_xplus_band(int l, double *X);

/* The pattern, stated from its derivation (rot_zxzxz.c header): m is of cos
 * type if m ≥ 0 is even or m < 0 is odd; X₊₉₀[m', m] can be non-zero only if
 * m, m' have the same type and l+|m|+|m'| is even (cos) resp. odd (sin). */
static int cos_type(int m) { return m >= 0 ? !(m & 1) : (-m) & 1; }
static int allowed(int l, int mp, int m)
{
    if (cos_type(mp) != cos_type(m)) return 0;
    const int par = (l + abs(m) + abs(mp)) & 1;
    return cos_type(m) ? par == 0 : par == 1;
}

START_TEST(test_xplus_pattern_and_values)
{
    sh_rotation rx;
    const double xaxis[3] = {1, 0, 0};
    ck_assert_int_eq(sh_rotation_from_axis_angle(xaxis, M_PI / 2, &rx), SH_OK);
    const int L = 100, W = 2 * L + 1;
    double *ref = malloc((size_t)W * W * sizeof *ref), *X = malloc((size_t)W * W * sizeof *X);
    double emax = 0;
    for (int l = 0; l <= L; l += (l < 40 ? 1 : 30)) {
        const int w = 2 * l + 1;
        ck_assert_int_eq(sh_rot_reference_band(l, SH_CS, &rx, 32, ref, NULL), SH_OK);
        ck_assert_int_eq(sh__rot_zxzxz_xplus_band(l, X), SH_OK);
        int nallowed = 0;
        for (int mp = -l; mp <= l; mp++)
            for (int m = -l; m <= l; m++) {
                const size_t i = (size_t)(mp + l) * w + (size_t)(m + l);
                if (allowed(l, mp, m)) nallowed++;
                else {
                    /* outside the pattern: zero in the truth up to the rounding of
                     * the rotation itself (π/2 and cos(π/2) ≈ 6e-17 are not exact
                     * in double, so the reference is of a rotation ~1e-16 away
                     * from Rx(90°)), exactly zero as generated */
                    ck_assert_msg(fabs(ref[i]) < 1e-14, "X+90 l %d (%d,%d) reference %.3g", l, mp, m, ref[i]);
                    ck_assert_msg(X[i] == 0.0, "X+90 l %d (%d,%d) generated %.3g", l, mp, m, X[i]);
                }
                ck_close(X[i], ref[i], 1e-14, 1.0, "X+90 generated vs reference l %d (%d,%d)", l, mp, m);
                emax = fmax(emax, fabs(X[i] - ref[i]));
            }
        ck_assert_int_eq(nallowed, l * l + l + 1);
    }
    fprintf(stderr, "zxzxz X+90 generated vs MPFR Rx(90deg), l <= %d: %.3g\n", L, emax);
    free(ref);
    free(X);
}
END_TEST

START_TEST(test_reference)
{
    double ed, ef;
    rot_check_reference_all(SH_ROT_ZXZXZ, &ed, &ef);
    fprintf(stderr, "zxzxz vs reference, orders 1..%d, %d rotations, both conventions: double %.3g, float %.3g\n",
            ROT_MAXO, ROT_NCASES, ed, ef);
}
END_TEST

START_TEST(test_apply) { rot_check_apply(SH_ROT_ZXZXZ, SH_PREC_DOUBLE, 1e-15); rot_check_apply(SH_ROT_ZXZXZ, SH_PREC_FLOAT, 1e-6); }
END_TEST

START_TEST(test_pointwise) { rot_check_pointwise(SH_ROT_ZXZXZ); }
END_TEST

START_TEST(test_orth_homomorphism) { rot_check_orth_homomorphism(SH_ROT_ZXZXZ); }
END_TEST

/* The single-band path (X₊₉₀ of that band only) equals the reference. */
START_TEST(test_band) { rot_check_band(SH_ROT_ZXZXZ, 60); }
END_TEST

/* The loop kernel's sparse apply executes, per band l, three z rotations (4l) and two
 * X products over the l²+l+1 non-zeros: Σ_{l<n} = n(2n²+18n−14)/3, the
 * paper's count; the set computes the Chebyshev multiple angles of α, β, γ
 * (2 per m = 2..n−1 each), which the paper leaves out, once per rotation. */
START_TEST(test_mults)
{
    sh_rotation r;
    sh_rotation_from_euler(0.2, 0.9, 1.4, &r);
    for (uint64_t n = 1; n <= ROT_MAXO; n++) {
        sh_rot_plan *p;
        ck_assert_int_eq(sh_rot_plan_create_kernel((int)n, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, SH_KERNEL_SCALAR, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
        double c[ROT_MAXO * ROT_MAXO] = {0}, g[ROT_MAXO * ROT_MAXO];
        ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
        uint64_t sm, am;
        sh_rot_plan_mults(p, &sm, &am);
        const uint64_t paper = n * (2 * n * n + 18 * n - 14) / 3, angles = n > 2 ? 6 * (n - 2) : 0;
        ck_assert_uint_eq(am, paper);
        ck_assert_uint_eq(sm, angles);
        ck_assert_uint_gt(am, 0);
        sh_rot_plan_free(p);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rot_zxzxz");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_xplus_pattern_and_values);
    tcase_add_test(tc, test_reference);
    tcase_add_test(tc, test_apply);
    tcase_add_test(tc, test_pointwise);
    tcase_add_test(tc, test_orth_homomorphism);
    tcase_add_test(tc, test_band);
    tcase_add_test(tc, test_mults);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
