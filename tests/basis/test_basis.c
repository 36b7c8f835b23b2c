/* test_basis.c — Legendre recurrence and real SH basis against independent
 * truths: GSL's gsl_sf_legendre_array_e, the addition theorem, closed-form
 * Cartesian polynomials for l <= 2, and Green's naive P()/SH() code. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_legendre.h>
#include <gsl/gsl_sf_gamma.h>
#include <string.h>

#include "testutil.h"

/* GSL's fully normalised functions with the CS phase: the same Q_l^m. */
static double *gsl_q(int lmax, double x)
{
    double *r = malloc(sizeof(double) * gsl_sf_legendre_array_n(lmax));
    int st = gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SPHARM, lmax, x, -1.0, r);
    ck_assert_int_eq(st, GSL_SUCCESS);
    return r;
}

static void compare_with_gsl(int lmax, double x, double rtol, double *worst)
{
    double *mine = malloc(sizeof(double) * sh_legendre_n(lmax));
    ck_assert_int_eq(sh_legendre_array(lmax, x, mine), SH_OK);
    double *ref = gsl_q(lmax, x);
    for (int l = 0; l <= lmax; l++) {
        /* scale of band l: the addition theorem bounds |Q| by sqrt((2l+1)/4π) */
        const double band = sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
        for (int m = 0; m <= l; m++) {
            const double a = mine[sh_legendre_idx(l, m)];
            const double b = ref[gsl_sf_legendre_array_index(l, m)];
            const double err = fabs(a - b) / band;
            if (err > *worst) *worst = err;
            ck_close(a, b, rtol, rtol == 0 ? 0 : band, "Q(%d,%d,x=%.17g)", l, m, x);
        }
    }
    free(mine);
    free(ref);
}

START_TEST(legendre_vs_gsl_low)
{
    const double xs[] = {-1.0, -0.999, -0.5, 0.0, 1e-9, 0.3, 0.7071, 0.99999, 1.0};
    double worst = 0;
    for (size_t k = 0; k < sizeof xs / sizeof *xs; k++) compare_with_gsl(64, xs[k], TOL2, &worst);
}
END_TEST

/* l = 2000: error measured relative to the band's scale sqrt((2l+1)/4π). */
START_TEST(legendre_vs_gsl_l2000)
{
    const double thetas[] = {1e-3, 0.0174533, 0.3, 1.0, M_PI / 2, 2.5, M_PI - 1e-4};
    double worst = 0;
    for (size_t k = 0; k < sizeof thetas / sizeof *thetas; k++)
        compare_with_gsl(2000, cos(thetas[k]), 2e-11, &worst);
    printf("legendre l<=2000 vs GSL: worst error / band scale = %.3g\n", worst);
}
END_TEST

/* Values whose sectoral seed underflows double but which are themselves
 * representable must not be flushed to zero (extended exponent). */
START_TEST(legendre_extended_exponent)
{
    const int lmax = 2000;
    const double x = cos(1.0 * M_PI / 180.0); /* θ = 1° */
    double *mine = malloc(sizeof(double) * sh_legendre_n(lmax));
    ck_assert_int_eq(sh_legendre_array(lmax, x, mine), SH_OK);
    double *ref = gsl_q(lmax, x);
    /* sin(1°)^200 ≈ 1e-350: the seed Q_200^200 underflows */
    const double seed = mine[sh_legendre_idx(200, 200)];
    ck_assert(seed == 0.0 || fabs(seed) < 1e-300);
    const double v = mine[sh_legendre_idx(2000, 200)];
    const double g = ref[gsl_sf_legendre_array_index(2000, 200)];
    ck_assert_msg(v != 0.0, "Q(2000,200) at 1 degree was flushed to zero");
    ck_close(v, g, 1e-10, 0, "Q(2000,200,1deg)");
    free(mine);
    free(ref);
}
END_TEST

/* Addition theorem: Σ_m (2-δ_m0) Q_l^m(x)² = (2l+1)/4π for every x. */
START_TEST(legendre_addition_theorem)
{
    const int lmax = 2000;
    double *q = malloc(sizeof(double) * sh_legendre_n(lmax));
    const double xs[] = {-0.9999, -0.3, 0.1, 0.8, 0.999999};
    for (size_t k = 0; k < 5; k++) {
        ck_assert_int_eq(sh_legendre_array(lmax, xs[k], q), SH_OK);
        for (int l = 0; l <= lmax; l += 37) {
            double s = 0;
            for (int m = 0; m <= l; m++) s += (m ? 2.0 : 1.0) * q[sh_legendre_idx(l, m)] * q[sh_legendre_idx(l, m)];
            ck_close(s, (2.0 * l + 1.0) / (4.0 * M_PI), 5e-12, 0, "addition l=%d x=%g", l, xs[k]);
        }
    }
    free(q);
}
END_TEST

START_TEST(legendre_bad_input)
{
    double q[3];
    ck_assert_int_eq(sh_legendre_array(1, 1.5, q), SH_EINVAL);
    ck_assert_int_eq(sh_legendre_array(1, NAN, q), SH_EINVAL);
    ck_assert_int_eq(sh_legendre_array(-1, 0.5, q), SH_EINVAL);
}
END_TEST

/* Closed-form real SH for l <= 2 in Cartesian form (cs convention). */
static void closed_form_cs(const double s[3], double y[9])
{
    const double x = s[0], yy = s[1], z = s[2];
    const double c1 = sqrt(3.0 / (4 * M_PI)), c2 = 0.5 * sqrt(15.0 / M_PI);
    y[0] = 0.5 / sqrt(M_PI);
    y[1] = -c1 * yy;
    y[2] = c1 * z;
    y[3] = -c1 * x;
    y[4] = c2 * x * yy;
    y[5] = -c2 * yy * z;
    y[6] = 0.25 * sqrt(5.0 / M_PI) * (3 * z * z - 1);
    y[7] = -c2 * x * z;
    y[8] = 0.5 * c2 * (x * x - yy * yy);
}

START_TEST(basis_closed_form_l2)
{
    for (int k = 0; k < 50; k++) {
        const double theta = 0.1 + 0.06 * k, phi = 0.37 * k;
        double s[3], y[9], yn[9], ref[9], yd[9];
        sh_dir_from_angles(theta, phi, s);
        closed_form_cs(s, ref);
        ck_assert_int_eq(sh_eval(3, SH_CS, theta, phi, y), SH_OK);
        ck_assert_int_eq(sh_eval(3, SH_NOCS, theta, phi, yn), SH_OK);
        const double s2[3] = {3 * s[0], 3 * s[1], 3 * s[2]}; /* not unit: normalised */
        ck_assert_int_eq(sh_eval_dir(3, SH_CS, s2, yd), SH_OK);
        for (int i = 0; i < 9; i++) {
            int l, m;
            sh_index_lm(i, &l, &m);
            ck_close(y[i], ref[i], TOL2, 1.0, "y_%d cs (%g,%g)", i, theta, phi);
            ck_close(yd[i], ref[i], TOL2, 1.0, "y_%d cs dir (%g,%g)", i, theta, phi);
            ck_close(yn[i], (abs(m) & 1) ? -ref[i] : ref[i], TOL2, 1.0, "y_%d nocs", i);
        }
    }
}
END_TEST

/* Green's P() and SH() (2003, "Spherical Harmonics"), written out naively. */
static double green_P(int l, int m, double x)
{
    double pmm = 1.0;
    if (m > 0) {
        double somx2 = sqrt((1.0 - x) * (1.0 + x)), fact = 1.0;
        for (int i = 1; i <= m; i++) { pmm *= (-fact) * somx2; fact += 2.0; }
    }
    if (l == m) return pmm;
    double pmmp1 = x * (2.0 * m + 1.0) * pmm;
    if (l == m + 1) return pmmp1;
    double pll = 0.0;
    for (int ll = m + 2; ll <= l; ++ll) {
        pll = ((2.0 * ll - 1.0) * x * pmmp1 - (ll + m - 1.0) * pmm) / (ll - m);
        pmm = pmmp1;
        pmmp1 = pll;
    }
    return pll;
}
static double green_SH(int l, int m, double theta, double phi)
{
    const int am = abs(m);
    const double K = sqrt((2.0 * l + 1.0) * gsl_sf_fact(l - am) / (4.0 * M_PI * gsl_sf_fact(l + am)));
    if (m == 0) return K * green_P(l, 0, cos(theta));
    if (m > 0) return M_SQRT2 * K * cos(m * phi) * green_P(l, m, cos(theta));
    return M_SQRT2 * K * sin(-m * phi) * green_P(l, -m, cos(theta));
}

START_TEST(basis_vs_green_code)
{
    const int order = 11;
    double y[121];
    for (int k = 0; k < 40; k++) {
        const double theta = 0.05 + 0.077 * k, phi = 6.2 - 0.15 * k;
        ck_assert_int_eq(sh_eval(order, SH_CS, theta, phi, y), SH_OK);
        for (int l = 0; l < order; l++)
            for (int m = -l; m <= l; m++)
                ck_close(y[sh_index(l, m)], green_SH(l, m, theta, phi), 1e-12, 1.0, "y(%d,%d)", l, m);
    }
}
END_TEST

START_TEST(basis_bad_input)
{
    double y[4];
    const double zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 1}, inf3[3] = {0, INFINITY, 0};
    ck_assert_int_eq(sh_eval_dir(2, SH_CS, zero, y), SH_EINVAL);
    ck_assert_int_eq(sh_eval_dir(2, SH_CS, nan3, y), SH_EINVAL);
    ck_assert_int_eq(sh_eval_dir(2, SH_CS, inf3, y), SH_EINVAL);
    ck_assert_int_eq(sh_eval(0, SH_CS, 1, 1, y), SH_EINVAL);
    ck_assert_int_eq(sh_eval(SHLAB_MAX_ORDER + 1, SH_CS, 1, 1, y), SH_EINVAL);
    ck_assert_int_eq(sh_eval(2, SH_CS, NAN, 1, y), SH_EINVAL);
    ck_assert(strlen(sh_last_error()) > 0);
}
END_TEST

/* Any (θ, φ) names the direction (sinθcosφ, sinθsinφ, cosθ), and any finite
 * non-zero vector a direction (regressions from review: θ < 0 gave the
 * direction at φ+π; φ = 1e308 overflowed m·φ; 1e-320 was "zero length"). */
START_TEST(basis_any_angles_and_scales)
{
    const double thetas[] = {-0.5, 4.0, 7.0, -20.0, 1.0};
    const double phis[] = {0.0, 1e6, -3.0, 1e308, 2.0};
    double y[16], yd[16];
    for (int k = 0; k < 5; k++) {
        double d[3];
        sh_dir_from_angles(thetas[k], phis[k], d);
        ck_assert_int_eq(sh_eval(4, SH_CS, thetas[k], phis[k], y), SH_OK);
        ck_assert_int_eq(sh_eval_dir(4, SH_CS, d, yd), SH_OK);
        for (int i = 0; i < 16; i++) ck_close(y[i], yd[i], 1e-9, 1.0, "theta=%g phi=%g y_%d", thetas[k], phis[k], i);
    }
    const double tiny[3] = {1e-320, 0, 0}, huge[3] = {1e200, 0, 0}, unit[3] = {1, 0, 0};
    double yt[16];
    ck_assert_int_eq(sh_eval_dir(4, SH_CS, unit, y), SH_OK);
    ck_assert_int_eq(sh_eval_dir(4, SH_CS, tiny, yt), SH_OK);
    ck_assert_int_eq(sh_eval_dir(4, SH_CS, huge, yd), SH_OK);
    for (int i = 0; i < 16; i++) {
        ck_close(yt[i], y[i], TOL1, 1.0, "tiny dir y_%d", i);
        ck_close(yd[i], y[i], TOL1, 1.0, "huge dir y_%d", i);
    }
}
END_TEST

START_TEST(index_round_trip)
{
    for (int l = 0; l < 300; l++)
        for (int m = -l; m <= l; m++) {
            int ll, mm;
            sh_index_lm(sh_index(l, m), &ll, &mm);
            ck_assert_int_eq(ll, l);
            ck_assert_int_eq(mm, m);
        }
}
END_TEST

/* Conversions: the represented function must be unchanged.  The Schmidt and
 * 4π bases are built independently from GSL's SCHMIDT normalisation (no
 * phase): S_l^m = sqrt(2(l-m)!/(l+m)!) P_l^m, 4π = sqrt(2l+1)·S. */
static double basis_value(sh_norm n, int l, int m, double theta, double phi, const double *schmidt)
{
    const int am = abs(m);
    const double trig = m > 0 ? cos(am * phi) : m < 0 ? sin(am * phi) : 1.0;
    double s = schmidt[gsl_sf_legendre_array_index(l, am)] * trig;
    if (n == SH_NORM_4PI) s *= sqrt(2.0 * l + 1.0);
    if (n == SH_NORM_NOCS || n == SH_NORM_CS) {
        s *= sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
        if (n == SH_NORM_CS && (am & 1)) s = -s;
    }
    return s;
}

START_TEST(convert_preserves_function)
{
    const int order = 9, n = order * order;
    double c[81], d[81];
    for (int i = 0; i < n; i++) c[i] = sin(1.7 * i + 0.3);
    double *schm = malloc(sizeof(double) * gsl_sf_legendre_array_n(order - 1));
    for (int from = 0; from < 4; from++)
        for (int to = 0; to < 4; to++) {
            memcpy(d, c, sizeof c);
            ck_assert_int_eq(sh_convert(order, (sh_norm)from, (sh_norm)to, d), SH_OK);
            for (int k = 0; k < 7; k++) {
                const double theta = 0.2 + 0.4 * k, phi = 0.9 * k;
                gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SCHMIDT, order - 1, cos(theta), 1.0, schm);
                double f = 0, g = 0;
                for (int l = 0; l < order; l++)
                    for (int m = -l; m <= l; m++) {
                        f += c[sh_index(l, m)] * basis_value((sh_norm)from, l, m, theta, phi, schm);
                        g += d[sh_index(l, m)] * basis_value((sh_norm)to, l, m, theta, phi, schm);
                    }
                ck_close(g, f, 1e-13, 1.0, "convert %d->%d at (%g,%g)", from, to, theta, phi);
            }
        }
    free(schm);
}
END_TEST

/* The cs basis built from GSL must equal sh_eval (checks basis_value too). */
START_TEST(convert_basis_matches_eval)
{
    const int order = 6;
    double y[36];
    double *schm = malloc(sizeof(double) * gsl_sf_legendre_array_n(order - 1));
    gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SCHMIDT, order - 1, cos(0.7), 1.0, schm);
    sh_eval(order, SH_CS, 0.7, 2.1, y);
    for (int l = 0; l < order; l++)
        for (int m = -l; m <= l; m++)
            ck_close(basis_value(SH_NORM_CS, l, m, 0.7, 2.1, schm), y[sh_index(l, m)], 1e-13, 1.0,
                     "cs basis (%d,%d)", l, m);
    free(schm);
}
END_TEST

static Suite *basis_suite(void)
{
    Suite *s = suite_create("basis");
    TCase *t = tcase_create("legendre");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, legendre_vs_gsl_low);
    tcase_add_test(t, legendre_vs_gsl_l2000);
    tcase_add_test(t, legendre_extended_exponent);
    tcase_add_test(t, legendre_addition_theorem);
    tcase_add_test(t, legendre_bad_input);
    suite_add_tcase(s, t);
    TCase *b = tcase_create("real-sh");
    tcase_add_test(b, basis_closed_form_l2);
    tcase_add_test(b, basis_vs_green_code);
    tcase_add_test(b, basis_bad_input);
    tcase_add_test(b, index_round_trip);
    tcase_add_test(b, basis_any_angles_and_scales);
    tcase_add_test(b, convert_preserves_function);
    tcase_add_test(b, convert_basis_matches_eval);
    suite_add_tcase(s, b);
    return s;
}

SHLAB_TEST_MAIN(basis_suite)
