/* test_lights.c — analytic lights and their closed-form projections.
 *
 * Truths used: GSL adaptive quadrature of 2π K_l P_l (gsl_sf_legendre_Pl,
 * not our closed forms); Green's Maple-generated synth_light() for 4 bands;
 * the clamped-cosine coefficients √π/2, √(π/3), √(5π)/8; the CIE formulas
 * at the zenith and below the horizon. */
#include <stdio.h>

#include "testutil.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_legendre.h>
#include <string.h>

static double Kl(int l) { return sqrt((2.0 * l + 1.0) / (4.0 * M_PI)); }

struct qp { int l; double e; };

/* cap: integrand in θ, P_l(cosθ) sinθ, so the tiny-cap interval is exact */
static double cap_integrand(double th, void *p)
{
    const struct qp *q = p;
    return gsl_sf_legendre_Pl(q->l, cos(th)) * sin(th);
}

static double lobe_integrand(double x, void *p)
{
    const struct qp *q = p;
    return (q->e == 0.0 ? 1.0 : pow(x, q->e)) * gsl_sf_legendre_Pl(q->l, x);
}

/* 2π K_l ∫ by GSL QAG/QAGS to ~1e-15 absolute. */
static double quad_ref(double (*fn)(double, void *), struct qp *q, double a, double b, int singular)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(4000);
    gsl_function F = {fn, q};
    double val, err;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    if (singular) gsl_integration_qags(&F, a, b, 1e-16, 1e-14, 4000, w, &val, &err);
    else gsl_integration_qag(&F, a, b, 1e-16, 1e-14, 4000, GSL_INTEG_GAUSS61, w, &val, &err);
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    return 2.0 * M_PI * Kl(q->l) * val;
}

START_TEST(test_cap_vs_quadrature)
{
    const double ts[] = {1e-3, 0.1, 0.7, M_PI_2, 2.5, 3.1, M_PI};
    const int order = 65;
    double z[65];
    for (size_t k = 0; k < sizeof ts / sizeof *ts; k++) {
        ck_assert_int_eq(sh_cap_zonal(ts[k], order, z), SH_OK);
        for (int l = 0; l < order; l++) {
            struct qp q = {l, 0.0};
            const double ref = quad_ref(cap_integrand, &q, 0.0, ts[k], 0);
            /* relative 1e-12, absolute 1e-12·(2πK_l·1e-3) near zeros */
            ck_close(z[l], ref, 1e-12, 1e-3 * 2.0 * M_PI * Kl(l), "cap t=%g l=%d", ts[k], l);
        }
    }
}
END_TEST

START_TEST(test_cap_tiny_no_cancellation)
{
    /* t → 0: z_l → 2πK_l (1 − cos t) ≈ π K_l t² for every l (P_l(1) = 1) */
    const double t = 1e-6;
    double z[65];
    ck_assert_int_eq(sh_cap_zonal(t, 65, z), SH_OK);
    for (int l = 0; l < 65; l++) {
        /* exact: 2πK_l ∫_0^t P_l(cosθ) sinθ dθ, P_l(cosθ) = 1 − l(l+1)θ²/4 + O(θ⁴) */
        const double ref = 2.0 * M_PI * Kl(l) * (t * t / 2.0) * (1.0 - t * t / 12.0 - l * (l + 1.0) * t * t / 8.0);
        ck_close(z[l], ref, 1e-13, 0.0, "tiny cap l=%d", l);
    }
}
END_TEST

/* Green 2003, synth_light(): Maple output for 4 bands, t3 = [t < π], t9 = [t < 0]. */
static void green_synth_light(double cutoff, double sh[16])
{
    memset(sh, 0, 16 * sizeof(double));
    double t3 = (-cutoff + M_PI) > 0 ? 1.0 : 0.0;
    double t5 = cos(cutoff);
    double t6 = t3 * t5;
    double t9 = (-cutoff) > 0 ? 1.0 : 0.0;
    double t11 = t9 * t5;
    double t14 = sin(cutoff);
    double t15 = t14 * t14;
    double t16 = t3 * t15;
    double t18 = t9 * t15;
    double t21 = t5 * t5;
    double t22 = t21 * t5;
    double t31 = t21 * t21;
    sh[0] = 3.544907702 - 1.772453851 * t3 - 1.772453851 * t6 - 1.772453851 * t9 + 1.772453851 * t11;
    sh[2] = 1.534990062 * t16 - 1.534990062 * t18;
    sh[6] = -1.98166365 * t3 * t22 + 1.98166365 * t6 + 1.98166365 * t9 * t22 - 1.98166365 * t11;
    sh[12] = 2.930920062 * t3 - 2.930920062 * t3 * t31 - 3.517104075 * t16 - 2.930920062 * t9 +
             2.930920062 * t9 * t31 + 3.517104075 * t18;
}

START_TEST(test_cap_vs_green_synth_light)
{
    const double ts[] = {0.2, 0.5, 1.0, M_PI_2, 2.0, 3.0};
    for (size_t k = 0; k < sizeof ts / sizeof *ts; k++) {
        sh_light L = {SH_LIGHT_CAP, {ts[k], 0.0}};
        double c[16], g[16];
        ck_assert_int_eq(sh_light_closed_form(&L, 4, SH_CS, c), SH_OK);
        green_synth_light(ts[k], g);
        /* Maple printed 10 significant digits */
        for (int i = 0; i < 16; i++) ck_close(c[i], g[i], 2e-8, 0.05, "cap t=%g vs synth_light[%d]", ts[k], i);
    }
}
END_TEST

START_TEST(test_lobe_vs_quadrature)
{
    const double es[] = {0.0, 0.5, 1.0, 2.0, 3.7, 10.0, 50.0};
    const int order = 65;
    double z[65];
    for (size_t k = 0; k < sizeof es / sizeof *es; k++) {
        ck_assert_int_eq(sh_lobe_zonal(es[k], order, z), SH_OK);
        for (int l = 0; l < order; l++) {
            struct qp q = {l, es[k]};
            const double ref = quad_ref(lobe_integrand, &q, 0.0, 1.0, es[k] != floor(es[k]));
            ck_close(z[l], ref, 1e-12, 1e-3 * 2.0 * M_PI * Kl(l), "lobe e=%g l=%d", es[k], l);
        }
    }
}
END_TEST

START_TEST(test_lobe_high_order)
{
    /* order 300: finite everywhere, and l = 257 (odd, e = 3 odd, l > e) is a
     * true zero of the formula; l = 256 agrees with quadrature */
    double z[300];
    ck_assert_int_eq(sh_lobe_zonal(3.0, 300, z), SH_OK);
    for (int l = 0; l < 300; l++) ck_assert(isfinite(z[l]));
    ck_assert(z[257] == 0.0);
    struct qp q = {256, 3.0};
    /* the quadrature of x³P_256 cancels to 1e-10 of its scale: absolute check */
    ck_close(z[256], quad_ref(lobe_integrand, &q, 0.0, 1.0, 0), 1e-10, 1e-3 * 2.0 * M_PI * Kl(256),
             "lobe e=3 l=256");
    /* e = 1, even l >= 2: ∫_0^1 x P_l = (−1)^{l/2+1} (l−2)! / (2^l (l/2−1)! (l/2+1)!)
     * (checked by hand for l = 2: 1/8, l = 4: −1/48) */
    double w[2049];
    ck_assert_int_eq(sh_lobe_zonal(1.0, 2049, w), SH_OK);
    const int ls[] = {2, 4, 10, 64, 256, 1000, 2048};
    for (size_t k = 0; k < sizeof ls / sizeof *ls; k++) {
        const int l = ls[k];
        const double lg = lgamma(l - 1.0) - l * M_LN2 - lgamma(l / 2.0) - lgamma(l / 2.0 + 2.0);
        const double ref = ((l / 2) % 2 ? 1.0 : -1.0) * exp(lg) * 2.0 * M_PI * Kl(l);
        ck_close(w[l], ref, 1e-10, 0.0, "lobe e=1 l=%d vs double-factorial form", l);
    }
    double c[300];
    ck_assert_int_eq(sh_cap_zonal(0.3, 300, c), SH_OK);
    struct qp r = {299, 0.0};
    ck_close(c[299], quad_ref(cap_integrand, &r, 0.0, 0.3, 0), 1e-10, 1e-3, "cap t=0.3 l=299");
}
END_TEST

/* Large exponents (regression: the log-gamma form returned ~4e222 for
 * e = 1e17 and the e = 0 answer for e = 1e300).  Truths: z_0 = √π/(e+1)
 * exactly, and for e ≫ l², I_l/I_0 = Π (e−k+2)/(e+k+1) = 1 − O(l²/e), so
 * z_l ≈ √(2l+1) z_0. */
START_TEST(test_lobe_huge_exponent)
{
    const double es[] = {1e6, 1e12, 1e15, 1e17, 1e100, 1e300};
    double z[11];
    for (size_t k = 0; k < sizeof es / sizeof *es; k++) {
        ck_assert_int_eq(sh_lobe_zonal(es[k], 11, z), SH_OK);
        ck_close(z[0], sqrt(M_PI) / (es[k] + 1.0), 1e-15, 0.0, "lobe e=%g c0", es[k]);
        for (int l = 1; l < 11; l++)
            ck_close(z[l], sqrt(2.0 * l + 1.0) * z[0], 200.0 / es[k] + 1e-14, 0.0, "lobe e=%g l=%d", es[k], l);
    }
}
END_TEST

START_TEST(test_lobe_clamped_cosine)
{
    double z[12];
    ck_assert_int_eq(sh_lobe_zonal(1.0, 12, z), SH_OK);
    ck_close(z[0], sqrt(M_PI) / 2.0, TOL1, 0.0, "c0 = sqrt(pi)/2");
    ck_close(z[1], sqrt(M_PI / 3.0), TOL1, 0.0, "c1 = sqrt(pi/3)");
    ck_close(z[2], sqrt(5.0 * M_PI) / 8.0, TOL1, 0.0, "c2 = sqrt(5pi)/8");
    for (int l = 3; l < 12; l += 2) ck_assert_msg(z[l] == 0.0, "odd l=%d must vanish, got %g", l, z[l]);
    for (int l = 4; l < 12; l += 2) ck_assert_msg(z[l] != 0.0, "even l=%d is not zero", l);
    /* through sh_light_closed_form: only m = 0 entries, both conventions */
    sh_light L;
    ck_assert_int_eq(sh_light_parse("lobe:1", 0, &L), SH_OK);
    double c[16];
    for (int conv = 0; conv < 2; conv++) {
        ck_assert_int_eq(sh_light_closed_form(&L, 4, (sh_convention)conv, c), SH_OK);
        for (int i = 0; i < 16; i++) {
            int l, m;
            sh_index_lm(i, &l, &m);
            if (m) ck_assert(c[i] == 0.0);
            else ck_close(c[i], z[l], 0.0, 0.0, "closed form l=%d", l);
        }
    }
}
END_TEST

START_TEST(test_const_closed_form)
{
    sh_light L;
    ck_assert_int_eq(sh_light_parse("const:2.5", 0, &L), SH_OK);
    ck_assert(sh_light_has_closed_form(&L));
    double c[9];
    ck_assert_int_eq(sh_light_closed_form(&L, 3, SH_CS, c), SH_OK);
    /* ∫ V y_0 = V·4π·(1/√(4π)) */
    ck_close(c[0], 2.5 * 4.0 * M_PI * 0.5 / sqrt(M_PI), TOL1, 0.0, "const c0");
    for (int i = 1; i < 9; i++) ck_assert(c[i] == 0.0);
    ck_assert_int_eq(sh_light_parse("green", 0, &L), SH_OK);
    ck_assert(!sh_light_has_closed_form(&L));
    ck_assert_int_eq(sh_light_closed_form(&L, 3, SH_CS, c), SH_ENOTSUP);
    ck_assert_int_eq(sh_light_parse("cie-overcast", 0, &L), SH_OK);
    ck_assert(!sh_light_has_closed_form(&L));
}
END_TEST

static double eval_at(const sh_light *L, double th, double ph)
{
    double d[3];
    sh_dir_from_angles(th, ph, d);
    return sh_light_eval(L, d, th, ph);
}

START_TEST(test_cie_skies)
{
    const char *specs[] = {"cie-overcast", "cie-clear:0.6,1.0", "cie-partly:0.6,1.0", "cie-clear:0,0",
                           "cie-partly:90,45"};
    for (size_t k = 0; k < sizeof specs / sizeof *specs; k++) {
        sh_light L;
        ck_assert_int_eq(sh_light_parse(specs[k], k == 4, &L), SH_OK);
        /* below and on the horizon: 0 */
        const double hz[3] = {1.0, 0.0, 0.0};
        ck_assert(sh_light_eval(&L, hz, M_PI_2, 0.0) == 0.0); /* cosθ = 0 exactly */
        for (double th = M_PI_2 + 1e-9; th <= M_PI; th += 0.1)
            for (double ph = 0; ph < 2 * M_PI; ph += 0.7)
                ck_assert_msg(eval_at(&L, th, ph) == 0.0, "%s below horizon th=%g", specs[k], th);
        /* at the zenith: L_z = 1 (γ = S there) */
        ck_close(eval_at(&L, 0.0, 0.3), 1.0, TOL1, 0.0, "%s at zenith", specs[k]);
        /* positive above the horizon */
        ck_assert(eval_at(&L, 1.2, 2.0) > 0.0);
    }
    sh_light L;
    ck_assert_int_eq(sh_light_parse("cie-overcast", 0, &L), SH_OK);
    /* (1+2cosθ)/3: zenith three times brighter than the horizon */
    ck_close(eval_at(&L, M_PI / 3.0, 0.0), 2.0 / 3.0, TOL1, 0.0, "overcast at 60 deg");
    /* clear sky: brighter towards the sun than away from it at the same height */
    ck_assert_int_eq(sh_light_parse("cie-clear:1.0,0.0", 0, &L), SH_OK);
    ck_assert(eval_at(&L, 1.0, 0.0) > 3.0 * eval_at(&L, 1.0, M_PI));
    ck_assert_int_eq(sh_light_parse("cie-partly:1.0,0.0", 0, &L), SH_OK);
    ck_assert(eval_at(&L, 1.0, 0.0) > eval_at(&L, 1.0, M_PI));
}
END_TEST

START_TEST(test_green_light_values)
{
    sh_light L;
    ck_assert_int_eq(sh_light_parse("green", 0, &L), SH_OK);
    /* zenith: first lobe 5·1 − 4 = 1, second lobe 0 */
    ck_close(eval_at(&L, 0.0, 0.0), 1.0, TOL1, 0.0, "green at zenith");
    /* equator at φ = 2.5: second lobe 4 − 3 = 1 */
    ck_close(eval_at(&L, M_PI_2, 2.5), 1.0, TOL1, 0.0, "green at (pi/2, 2.5)");
    /* nadir and equator opposite: 0 */
    ck_assert(eval_at(&L, M_PI, 0.0) == 0.0);
    ck_assert(eval_at(&L, M_PI_2, 2.5 + M_PI) == 0.0);
    /* cap and lobe evaluate as defined */
    ck_assert_int_eq(sh_light_parse("cap:30", 1, &L), SH_OK);
    ck_close(L.p[0], M_PI / 6.0, TOL0, 0.0, "cap degrees");
    ck_assert(eval_at(&L, 0.5, 0.0) == 1.0 && eval_at(&L, 0.53, 0.0) == 0.0);
    ck_assert_int_eq(sh_light_parse("lobe:2", 0, &L), SH_OK);
    ck_close(eval_at(&L, M_PI / 3.0, 1.0), 0.25, TOL1, 0.0, "lobe:2 at 60 deg");
    ck_assert(eval_at(&L, 2.0, 1.0) == 0.0);
}
END_TEST

START_TEST(test_parse_errors)
{
    const char *bad[] = {"", "bogus", "cap", "cap:", "cap:4", "cap:-0.1", "cap:nan", "cap:1x", "cap:1,2",
                         "lobe:-1", "lobe:inf", "lobe:", "const:", "const:1e999", "cie-clear",
                         "cie-clear:1", "cie-clear:2,0", "cie-clear:-0.1,0", "cie-clear:1,2,3",
                         "cie-partly:1,", "cie-partly:,1", "green:1", "cie-overcast:0", "Green", "cap :1"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        sh_light L;
        sh_error(SH_OK, "%s", "");
        ck_assert_msg(sh_light_parse(bad[k], 0, &L) == SH_EINVAL, "'%s' should fail", bad[k]);
        ck_assert_msg(strlen(sh_last_error()) > 0 && !strchr(sh_last_error(), '\n'), "reason for '%s'", bad[k]);
    }
    sh_light L;
    ck_assert_int_eq(sh_light_parse("cap:181", 1, &L), SH_EINVAL);
    ck_assert_int_eq(sh_light_parse("cap:180", 1, &L), SH_OK);
    ck_assert_int_eq(sh_light_parse("cie-clear:91,0", 1, &L), SH_EINVAL);
    ck_assert_int_eq(sh_light_parse("cie-clear:90,270", 1, &L), SH_OK);
    ck_close(L.p[1], 1.5 * M_PI, TOL0, 0.0, "sun phi degrees");
    ck_assert_int_eq(sh_light_parse("const:-2", 1, &L), SH_OK); /* V is not an angle */
    ck_close(L.p[0], -2.0, 0.0, 0.0, "const not converted");
    ck_assert_int_eq(sh_light_parse("lobe:0", 0, &L), SH_OK);
    double z[4];
    ck_assert_int_eq(sh_cap_zonal(-0.1, 4, z), SH_EINVAL);
    ck_assert_int_eq(sh_cap_zonal(NAN, 4, z), SH_EINVAL);
    ck_assert_int_eq(sh_cap_zonal(1.0, 0, z), SH_EINVAL);
    ck_assert_int_eq(sh_lobe_zonal(-1.0, 4, z), SH_EINVAL);
    ck_assert_int_eq(sh_lobe_zonal(INFINITY, 4, z), SH_EINVAL);
}
END_TEST

static Suite *lights_suite(void)
{
    Suite *s = suite_create("lights");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_cap_vs_quadrature);
    tcase_add_test(tc, test_cap_tiny_no_cancellation);
    tcase_add_test(tc, test_cap_vs_green_synth_light);
    tcase_add_test(tc, test_lobe_vs_quadrature);
    tcase_add_test(tc, test_lobe_high_order);
    tcase_add_test(tc, test_lobe_clamped_cosine);
    tcase_add_test(tc, test_lobe_huge_exponent);
    tcase_add_test(tc, test_const_closed_form);
    tcase_add_test(tc, test_cie_skies);
    tcase_add_test(tc, test_green_light_values);
    tcase_add_test(tc, test_parse_errors);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(lights_suite)
