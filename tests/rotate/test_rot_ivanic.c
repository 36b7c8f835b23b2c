/* test_rot_ivanic.c — the `ivanic` method (src/rotate/rot_ivanic.c).
 *
 * Truths: the MPFR reference (orders 1..10, seeded random rotations and the
 * extremes, both conventions, double and float plans), the pointwise
 * identity, orthogonality, the homomorphism (rottest.h).  And the proof of
 * the two misprints of Green's Appendix I: a slow transcription of the
 * printed tables here (entries of M^{l−1} outside band l−1 read as 0),
 * switched between the corrected formulas and Green's printed ones — the
 * corrected ones are orthogonal and equal the reference, each printed one
 * breaks orthogonality by O(1). */
#include "rottest.h"

/* ---- slow transcription of [Ivanic & Ruedenberg 1996/1998] ------------- */
enum { VAR_OK = 0, VAR_GREEN_V = 1, VAR_GREEN_W = 2 };

static double g_M[12][25][25]; /* nocs bands, [l][m+l][n+l] */
static double g_R1[3][3];

static double Mget(int l, int a, int b)
{
    if (a < -l || a > l || b < -l || b > l) return 0.0;
    return g_M[l][a + l][b + l];
}
static double P(int i, int l, int a, int b)
{
    const double ri0 = g_R1[i + 1][1], ri1 = g_R1[i + 1][2], rim1 = g_R1[i + 1][0];
    if (b == l) return ri1 * Mget(l - 1, a, l - 1) - rim1 * Mget(l - 1, a, -l + 1);
    if (b == -l) return ri1 * Mget(l - 1, a, -l + 1) + rim1 * Mget(l - 1, a, l - 1);
    return ri0 * Mget(l - 1, a, b);
}
static void slow_bands(const sh_rotation *r, int lmax, int variant)
{
    static const int perm[3] = {1, 2, 0}; /* (y, z, x) */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) g_R1[i][j] = g_M[1][i][j] = r->R[perm[i] * 3 + perm[j]];
    g_M[0][0][0] = 1;
    for (int l = 2; l <= lmax; l++)
        for (int m = -l; m <= l; m++)
            for (int n = -l; n <= l; n++) {
                const int am = abs(m), d0 = m == 0, dp1 = m == 1, dm1 = m == -1;
                const double d = abs(n) < l ? (double)(l + n) * (l - n) : 2.0 * l * (2.0 * l - 1);
                const double u = sqrt((l + m) * (double)(l - m) / d);
                const double v = 0.5 * sqrt((1 + d0) * (l + am - 1.0) * (l + am) / d) * (1 - 2 * d0);
                double w = -0.5 * sqrt((l - am - 1.0) * (l - am) / d) * (1 - d0);
                if (variant == VAR_GREEN_W && abs(n) == l) /* Green: (l+|m|−1)(l+|m|) */
                    w = -0.5 * sqrt((l + am - 1.0) * (l + am) / d) * (1 - d0);
                const double U = P(0, l, m, n);
                double V, W = 0;
                if (m == 0) V = P(1, l, 1, n) + P(-1, l, -1, n);
                else if (m > 0) V = P(1, l, m - 1, n) * sqrt(1.0 + dp1) - P(-1, l, -m + 1, n) * (1 - dp1);
                else if (variant == VAR_GREEN_V) /* Green: (1+δ) and √(1−δ) */
                    V = P(1, l, m + 1, n) * (1 + dm1) + P(-1, l, -m - 1, n) * sqrt(1.0 - dm1);
                else V = P(1, l, m + 1, n) * (1 - dm1) + P(-1, l, -m - 1, n) * sqrt(1.0 + dm1);
                if (m > 0) W = P(1, l, m + 1, n) + P(-1, l, -m - 1, n);
                else if (m < 0) W = P(1, l, m - 1, n) - P(-1, l, -m + 1, n);
                g_M[l][m + l][n + l] = (u != 0 ? u * U : 0) + v * V + (w != 0 ? w * W : 0);
            }
}
static double slow_orth(int lmax)
{
    double e = 0;
    for (int l = 0; l <= lmax; l++)
        for (int a = -l; a <= l; a++)
            for (int b = -l; b <= l; b++) {
                double s = 0;
                for (int k = -l; k <= l; k++) s += Mget(l, a, k) * Mget(l, b, k);
                e = fmax(e, fabs(s - (a == b)));
            }
    return e;
}

START_TEST(test_green_misprints)
{
    /* a generic rotation */
    sh_rotation r;
    sh_rotation_from_euler(0.7, 1.1, -2.3, &r);
    const int lmax = 5;
    slow_bands(&r, lmax, VAR_OK);
    const double e_ok = slow_orth(lmax);
    ck_assert_msg(e_ok < 1e-14, "corrected tables: orthogonality %.3g", e_ok);
    /* the corrected transcription equals the MPFR reference (nocs) */
    double ref[121];
    for (int l = 0; l <= lmax; l++) {
        ck_assert_int_eq(sh_rot_reference_band(l, SH_NOCS, &r, 32, ref, NULL), SH_OK);
        for (int a = -l; a <= l; a++)
            for (int b = -l; b <= l; b++)
                ck_close(Mget(l, a, b), ref[(a + l) * (2 * l + 1) + b + l], 1e-14, 1.0,
                         "slow corrected l %d (%d,%d)", l, a, b);
    }
    slow_bands(&r, lmax, VAR_GREEN_V);
    const double e_v = slow_orth(lmax);
    ck_assert_msg(e_v > 1e-2, "Green's m<0 V should break orthogonality (got %.3g)", e_v);
    slow_bands(&r, lmax, VAR_GREEN_W);
    const double e_w = slow_orth(lmax);
    ck_assert_msg(e_w > 1e-2, "Green's |n|=l w should break orthogonality (got %.3g)", e_w);
    fprintf(stderr, "ivanic misprints: corrected orth %.2g, Green m<0 V orth %.2g, Green w(|n|=l) orth %.2g\n",
            e_ok, e_v, e_w);
}
END_TEST

START_TEST(test_reference)
{
    double ed, ef;
    rot_check_reference_all(SH_ROT_IVANIC, &ed, &ef);
    fprintf(stderr, "ivanic vs reference, orders 1..%d, %d rotations, both conventions: double %.3g, float %.3g\n",
            ROT_MAXO, ROT_NCASES, ed, ef);
}
END_TEST

START_TEST(test_apply) { rot_check_apply(SH_ROT_IVANIC, SH_PREC_DOUBLE, 1e-15); rot_check_apply(SH_ROT_IVANIC, SH_PREC_FLOAT, 1e-6); }
END_TEST

START_TEST(test_pointwise) { rot_check_pointwise(SH_ROT_IVANIC); }
END_TEST

START_TEST(test_orth_homomorphism) { rot_check_orth_homomorphism(SH_ROT_IVANIC); }
END_TEST

/* The single-band path (ivanic streams through the lower bands) equals the reference. */
START_TEST(test_band) { rot_check_band(SH_ROT_IVANIC, 24); }
END_TEST

/* Multiplications of the loop kernel (SH_KERNEL_SCALAR; the unrolled one's
 * count is checked in test_kernels.c): set counts the recursion (> 0 from order 3 on, at most
 * the 3 terms × (2 P's of 2 mults + 1) per entry), apply is the plain block
 * product Σ(2l+1)² = n(4n²−1)/3. */
START_TEST(test_mults)
{
    sh_rotation r;
    sh_rotation_from_euler(0.2, 0.9, 1.4, &r);
    for (int n = 1; n <= ROT_MAXO; n++) {
        sh_rot_plan *p;
        ck_assert_int_eq(sh_rot_plan_create_kernel(n, SH_ROT_IVANIC, SH_PREC_DOUBLE, SH_CS, SH_KERNEL_SCALAR, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
        double c[ROT_MAXO * ROT_MAXO] = {0}, g[ROT_MAXO * ROT_MAXO];
        ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
        uint64_t sm, am;
        sh_rot_plan_mults(p, &sm, &am);
        ck_assert_uint_eq(am, (uint64_t)n * (4u * n * n - 1) / 3);
        if (n >= 3) {
            ck_assert_uint_gt(sm, 0);
            ck_assert_uint_le(sm, 15u * (sh_rot_block_offset(n) - 10));
        }
        sh_rot_plan_free(p);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rot_ivanic");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_green_misprints);
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
