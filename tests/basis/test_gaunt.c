/* test_gaunt.c — Wigner 3j symbols and real Gaunt coefficients.
 *
 * Truths used: GSL gsl_sf_coupling_3j_e (where its own error estimate says it
 * is accurate), the closed form of (j1 j2 j3; 0 0 0) via log-factorials, the
 * 3j symmetries, both orthogonality relations, and for the real Gaunt
 * coefficients a direct Gauss-Legendre × uniform-φ product quadrature of
 * sh_eval values (a method sharing nothing with the 3j route). */
#include "testutil.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_coupling.h>
#include <gsl/gsl_sf_gamma.h>
#include <stdio.h>
#include <string.h>

static unsigned long rng_state = 12345;
static unsigned rnd(unsigned n)
{
    rng_state = rng_state * 6364136223846793005UL + 1442695040888963407UL;
    return (unsigned)((rng_state >> 33) % n);
}

/* ------------------------------------------------------------------ 3j */

START_TEST(test_3j_vs_gsl)
{
    gsl_set_error_handler_off();
    long n = 0;
    for (int j1 = 0; j1 <= 14; j1++)
        for (int j2 = 0; j2 <= 14; j2++)
            for (int j3 = abs(j1 - j2); j3 <= j1 + j2; j3++)
                for (int m1 = -j1; m1 <= j1; m1++)
                    for (int m2 = -j2; m2 <= j2; m2++) {
                        const int m3 = -m1 - m2;
                        if (abs(m3) > j3) continue;
                        gsl_sf_result r;
                        if (gsl_sf_coupling_3j_e(2 * j1, 2 * j2, 2 * j3, 2 * m1, 2 * m2, 2 * m3, &r))
                            continue;
                        double v;
                        ck_assert_int_eq(sh_wigner3j_e(j1, j2, j3, m1, m2, m3, &v), SH_OK);
                        /* GSL's estimate plus a few hundred ulps of ours */
                        const double tol = 2.0 * r.err + TOL3 * fabs(r.val) + 1e-15;
                        if (!(fabs(v - r.val) <= tol))
                            ck_abort_msg("3j(%d %d %d; %d %d %d) = %.17g, GSL %.17g ± %.3g", j1, j2,
                                         j3, m1, m2, m3, v, r.val, r.err);
                        n++;
                    }
    ck_assert_int_gt(n, 100000);
}
END_TEST

/* (j1 j2 j3; 0 0 0) = (−1)^g √[(L−2j1)!(L−2j2)!(L−2j3)!/(L+1)!] g!/((g−j1)!(g−j2)!(g−j3)!),
 * L = j1+j2+j3 = 2g (Edmonds 3.7.17); 0 for odd L. */
static double w000_closed(int j1, int j2, int j3)
{
    const int L = j1 + j2 + j3;
    if (L & 1) return 0.0;
    const int g = L / 2;
    const double lg = 0.5 * (gsl_sf_lnfact(L - 2 * j1) + gsl_sf_lnfact(L - 2 * j2) +
                             gsl_sf_lnfact(L - 2 * j3) - gsl_sf_lnfact(L + 1)) +
                      gsl_sf_lnfact(g) - gsl_sf_lnfact(g - j1) - gsl_sf_lnfact(g - j2) -
                      gsl_sf_lnfact(g - j3);
    return ((g & 1) ? -1.0 : 1.0) * exp(lg);
}

/* stretched case j1 = j2 + j3 (Edmonds 3.7.17, after a cyclic permutation):
 * (j2+j3 j2 j3; m1 m2 m3) = (−1)^(j2−j3−m1) √[(2j2)!(2j3)!(J+m1)!(J−m1)! /
 *                            ((2J+1)!(j2+m2)!(j2−m2)!(j3+m3)!(j3−m3)!)] */
static double w_stretched(int j2, int j3, int m2, int m3)
{
    const int J = j2 + j3, m1 = -m2 - m3;
    const double lg = 0.5 * (gsl_sf_lnfact(2 * j2) + gsl_sf_lnfact(2 * j3) + gsl_sf_lnfact(J + m1) +
                             gsl_sf_lnfact(J - m1) - gsl_sf_lnfact(2 * J + 1) -
                             gsl_sf_lnfact(j2 + m2) - gsl_sf_lnfact(j2 - m2) -
                             gsl_sf_lnfact(j3 + m3) - gsl_sf_lnfact(j3 - m3));
    return (((j2 - j3 - m1) % 2) ? -1.0 : 1.0) * exp(lg);
}

START_TEST(test_3j_closed_forms)
{
    for (int j1 = 0; j1 <= 150; j1 += 7)
        for (int j2 = 0; j2 <= 150; j2 += 11)
            for (int j3 = abs(j1 - j2); j3 <= j1 + j2; j3++) {
                const double e = w000_closed(j1, j2, j3);
                ck_close(sh_wigner3j(j1, j2, j3, 0, 0, 0), e, 1e-11, 1e-300,
                         "3j(%d %d %d; 0 0 0)", j1, j2, j3);
            }
    for (int j2 = 1; j2 <= 300; j2 += 37)
        for (int j3 = 1; j3 <= 300; j3 += 41)
            for (int t = 0; t < 10; t++) {
                const int m2 = (int)rnd(2 * j2 + 1) - j2, m3 = (int)rnd(2 * j3 + 1) - j3;
                ck_close(sh_wigner3j(j2 + j3, j2, j3, -m2 - m3, m2, m3), w_stretched(j2, j3, m2, m3),
                         1e-10, 1e-300, "3j(%d %d %d; %d %d %d)", j2 + j3, j2, j3, -m2 - m3, m2, m3);
            }
}
END_TEST

START_TEST(test_3j_symmetries)
{
    for (int t = 0; t < 3000; t++) {
        const int j1 = (int)rnd(200), j2 = (int)rnd(200);
        const int j3 = abs(j1 - j2) + (int)rnd((unsigned)(j1 + j2 - abs(j1 - j2) + 1));
        const int m1 = (int)rnd(2 * j1 + 1) - j1;
        int lo = -j2, hi = j2;
        if (-m1 - j3 > lo) lo = -m1 - j3;
        if (-m1 + j3 < hi) hi = -m1 + j3;
        if (lo > hi) continue;
        const int m2 = lo + (int)rnd((unsigned)(hi - lo + 1)), m3 = -m1 - m2;
        const double s = ((j1 + j2 + j3) & 1) ? -1.0 : 1.0;
        const double w = sh_wigner3j(j1, j2, j3, m1, m2, m3);
        ck_assert(isfinite(w));
        const double tol = 1e-12, fl = 1e-4; /* errors ~1e-16 absolute: relative above 1e-4 */
        /* cyclic permutations: equal */
        ck_close(sh_wigner3j(j2, j3, j1, m2, m3, m1), w, tol, fl, "cyc(%d %d %d;%d %d %d)", j1, j2, j3, m1, m2, m3);
        ck_close(sh_wigner3j(j3, j1, j2, m3, m1, m2), w, tol, fl, "cyc2(%d %d %d;%d %d %d)", j1, j2, j3, m1, m2, m3);
        /* odd permutations and m → −m: factor (−1)^(j1+j2+j3) */
        ck_close(sh_wigner3j(j2, j1, j3, m2, m1, m3), s * w, tol, fl, "swap(%d %d %d;%d %d %d)", j1, j2, j3, m1, m2, m3);
        ck_close(sh_wigner3j(j1, j3, j2, m1, m3, m2), s * w, tol, fl, "swap23(%d %d %d;%d %d %d)", j1, j2, j3, m1, m2, m3);
        ck_close(sh_wigner3j(j1, j2, j3, -m1, -m2, -m3), s * w, tol, fl, "flip(%d %d %d;%d %d %d)", j1, j2, j3, m1, m2, m3);
    }
    /* selection rules give exact zeros */
    ck_assert(sh_wigner3j(3, 4, 5, 1, 1, 1) == 0.0);
    ck_assert(sh_wigner3j(1, 1, 3, 0, 0, 0) == 0.0);
    ck_assert(sh_wigner3j(2, 2, 2, 3, -3, 0) == 0.0);
    ck_assert(sh_wigner3j(1, 2, 2, 0, 0, 0) == 0.0); /* odd L, all m zero */
    double v;
    ck_assert_int_eq(sh_wigner3j_e(-1, 2, 2, 0, 0, 0, &v), SH_EINVAL);
    ck_assert(isnan(sh_wigner3j(-1, 2, 2, 0, 0, 0)));
}
END_TEST

/* Σ_{m1,m2} (2j3+1) (j1 j2 j3; m1 m2 m3)(j1 j2 j3'; m1 m2 m3) = δ_{j3 j3'}
 * (fixed m3), and Σ_{j3} (2j3+1) (..; m1 m2 m3)(..; m1' m2' m3) = δ_{m1 m1'}. */
START_TEST(test_3j_orthogonality)
{
    static const int pairs[][2] = {{5, 7}, {30, 30}, {47, 60}, {100, 100}, {100, 63}, {120, 7}};
    double worst = 0.0;
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
        const int j1 = pairs[p][0], j2 = pairs[p][1];
        const int jlo = abs(j1 - j2), jhi = j1 + j2;
        for (int t = 0; t < 6; t++) {
            const int j3 = jlo + (int)rnd((unsigned)(jhi - jlo + 1));
            const int j3b = (t & 1) ? j3 : jlo + (int)rnd((unsigned)(jhi - jlo + 1));
            const int lim = j3 < j3b ? j3 : j3b;
            const int m3 = (int)rnd(2 * lim + 1) - lim;
            double s = 0.0;
            for (int m1 = -j1; m1 <= j1; m1++) {
                const int m2 = -m1 - m3;
                if (abs(m2) > j2) continue;
                s += sh_wigner3j(j1, j2, j3, m1, m2, m3) * sh_wigner3j(j1, j2, j3b, m1, m2, m3);
            }
            s *= 2.0 * j3 + 1.0;
            const double e = (j3 == j3b) ? 1.0 : 0.0;
            ck_close(s, e, 1e-12, 1.0, "orth1 j=(%d %d %d/%d) m3=%d", j1, j2, j3, j3b, m3);
            worst = fmax(worst, fabs(s - e));
        }
        /* second relation: fixed m3, two different m1 */
        for (int t = 0; t < 4; t++) {
            const int m3 = (int)rnd(7) - 3;
            const int m1 = (int)rnd(2 * j1 + 1) - j1, m1b = (t & 1) ? m1 : (int)rnd(2 * j1 + 1) - j1;
            const int m2 = -m1 - m3, m2b = -m1b - m3;
            if (abs(m2) > j2 || abs(m2b) > j2) continue;
            double s = 0.0;
            for (int j3 = jlo; j3 <= jhi; j3++)
                s += (2.0 * j3 + 1.0) * sh_wigner3j(j1, j2, j3, m1, m2, m3) *
                     sh_wigner3j(j1, j2, j3, m1b, m2b, m3);
            ck_close(s, m1 == m1b ? 1.0 : 0.0, 1e-12, 1.0, "orth2 (%d %d) m1=%d/%d m3=%d", j1, j2, m1, m1b, m3);
        }
    }
    printf("3j orthogonality: worst |sum - delta| = %.3g (j up to 200)\n", worst);
}
END_TEST

/* The family routine agrees with single symbols and covers the range. */
START_TEST(test_3j_family)
{
    double f[401];
    int jmin, jmax;
    ck_assert_uint_eq(sh_wigner3j_family_n(150, 250), 401);
    ck_assert_int_eq(sh_wigner3j_family(150, 250, -17, 40, &jmin, &jmax, f), SH_OK);
    ck_assert_int_eq(jmin, 100);
    ck_assert_int_eq(jmax, 400);
    double s = 0.0;
    for (int j = jmin; j <= jmax; j++) s += (2.0 * j + 1.0) * f[j - jmin] * f[j - jmin];
    ck_close(s, 1.0, TOL2, 1.0, "family norm");
    ck_close(f[jmax - jmin], w_stretched(150, 250, -17, 40), 1e-10, 0, "family top");
    /* empty family */
    ck_assert_int_eq(sh_wigner3j_family(2, 3, 3, 0, &jmin, &jmax, f), SH_OK);
    ck_assert_int_gt(jmin, jmax);
}
END_TEST

/* Regression: when the top of a family underflows to 0 (deep in the upper
 * forbidden region), the sign must not be read from the stored f(jmax).
 * Reference values: exact rational evaluation (sympy.physics.wigner.wigner_3j). */
START_TEST(test_3j_underflowed_top_sign)
{
    ck_close(sh_wigner3j(1637, 1829, 1729, -19, 1717, -1698), -1.5766923941564767e-76, 1e-11, 0,
             "3j(1637 1829 1729; -19 1717 -1698)");
    ck_close(sh_wigner3j(500, 1829, 1729, -19, 1717, -1698), -6.795400372113466e-4, 1e-11, 0,
             "3j(500 1829 1729; -19 1717 -1698)");
    ck_close(sh_wigner3j(100, 1829, 1729, -19, 1717, -1698), 5.700672179602399e-44, 1e-11, 0,
             "3j(100 1829 1729; -19 1717 -1698)");
    /* beyond ~2900 the true values are below the double range */
    ck_assert(fabs(sh_wigner3j(3558, 1829, 1729, -19, 1717, -1698)) < 1e-300);
}
END_TEST

/* -------------------------------------------------------- real Gaunt */

/* Product quadrature table: y values at nth GL nodes × 2nth φ nodes. */
typedef struct {
    int order, nth, nph;
    double *w; /* per point weight */
    double *y; /* [point][n²] */
} quad_tab;

static quad_tab quad_make(int order, sh_convention conv, int nth)
{
    quad_tab q = {order, nth, 2 * nth, NULL, NULL};
    const int n = sh_ncoeff(order), np = q.nth * q.nph;
    q.w = malloc(sizeof(double) * np);
    q.y = malloc(sizeof(double) * (size_t)np * n);
    ck_assert(q.w && q.y);
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(nth);
    for (int a = 0; a < nth; a++) {
        double x, w;
        gsl_integration_glfixed_point(-1, 1, a, &x, &w, t);
        for (int c = 0; c < q.nph; c++) {
            const int p = a * q.nph + c;
            q.w[p] = w * 2 * M_PI / q.nph;
            ck_assert_int_eq(sh_eval(order, conv, acos(x), 2 * M_PI * c / q.nph, q.y + (size_t)p * n), SH_OK);
        }
    }
    gsl_integration_glfixed_table_free(t);
    return q;
}

static void quad_free(quad_tab *q) { free(q->w); free(q->y); }

static double quad_triple(const quad_tab *q, int i, int j, int k)
{
    const int n = sh_ncoeff(q->order);
    double s = 0.0;
    for (int p = 0; p < q->nth * q->nph; p++) {
        const double *y = q->y + (size_t)p * n;
        s += q->w[p] * y[i] * y[j] * y[k];
    }
    return s;
}

START_TEST(test_gaunt_vs_quadrature_l4)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    quad_tab q = quad_make(5, conv, 8); /* degree 12 < 2·8 */
    int nonzero = 0;
    double worst = 0.0;
    for (int i = 0; i < 25; i++)
        for (int j = 0; j < 25; j++)
            for (int k = 0; k < 25; k++) {
                const double e = quad_triple(&q, i, j, k), g = sh_gaunt_real(conv, i, j, k);
                ck_close(g, e, 1e-13, 1.0, "G_%s(%d,%d,%d)", sh_convention_name(conv), i, j, k);
                worst = fmax(worst, fabs(g - e));
                if (fabs(e) > 1e-12) nonzero++;
            }
    printf("gaunt l<=4 %s: worst |G - quad| = %.3g over 15625 triples, %d non-zero\n",
           sh_convention_name(conv), worst, nonzero);
    ck_assert_int_gt(nonzero, 500);
    quad_free(&q);
}
END_TEST

START_TEST(test_gaunt_vs_quadrature_l20)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    const int order = 23; /* bands to 22 */
    quad_tab q = quad_make(order, conv, 36); /* total degree <= 66 < 72 */
    int *kk = malloc(sizeof(int) * 64);
    double *gg = malloc(sizeof(double) * 64), *work = malloc(sizeof(double) * 200);
    double worst = 0.0;
    int nz = 0;
    for (int t = 0; t < 150; t++) {
        const int l1 = 17 + (int)rnd(6), l2 = 17 + (int)rnd(6);
        const int i = sh_index(l1, (int)rnd(2 * l1 + 1) - l1), j = sh_index(l2, (int)rnd(2 * l2 + 1) - l2);
        /* a random k (mostly zero by the rules) and every listed non-zero k */
        const int kr = (int)rnd((unsigned)sh_ncoeff(order));
        const double er = quad_triple(&q, i, j, kr);
        ck_close(sh_gaunt_real(conv, i, j, kr), er, 1e-12, 1.0, "G(%d,%d,%d)", i, j, kr);
        int cnt;
        ck_assert_int_eq(sh_gaunt_real_row(conv, i, j, order - 1, kk, gg, &cnt, work), SH_OK);
        for (int c = 0; c < cnt; c++) {
            const double e = quad_triple(&q, i, j, kk[c]);
            ck_close(gg[c], e, 1e-12, 1.0, "row G(%d,%d,%d)", i, j, kk[c]);
            ck_close(sh_gaunt_real(conv, i, j, kk[c]), e, 1e-12, 1.0, "G(%d,%d,%d)", i, j, kk[c]);
            worst = fmax(worst, fabs(gg[c] - e));
            if (fabs(e) > 1e-3) nz++;
        }
    }
    printf("gaunt l~20 %s: worst |G - quad| = %.3g, %d sizable entries checked\n",
           sh_convention_name(conv), worst, nz);
    ck_assert_int_gt(nz, 100);
    free(kk); free(gg); free(work);
    quad_free(&q);
}
END_TEST

/* y_0 = 1/√(4π):  G(0,j,k) = δ_jk/√(4π); every index permutation equal. */
START_TEST(test_gaunt_identities)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    const double c = 1.0 / sqrt(4.0 * M_PI);
    for (int j = 0; j < 100; j++)
        for (int k = 0; k < 100; k++)
            ck_close(sh_gaunt_real(conv, 0, j, k), j == k ? c : 0.0, TOL2, 1.0, "G(0,%d,%d)", j, k);
    for (int t = 0; t < 2000; t++) {
        const int i = (int)rnd(400), j = (int)rnd(400), k = (int)rnd(1600);
        const double g = sh_gaunt_real(conv, i, j, k);
        ck_close(sh_gaunt_real(conv, j, i, k), g, TOL2, 1.0, "G(%d,%d,%d) sym", j, i, k);
        ck_close(sh_gaunt_real(conv, k, j, i), g, TOL2, 1.0, "G(%d,%d,%d) sym", k, j, i);
        ck_close(sh_gaunt_real(conv, j, k, i), g, TOL2, 1.0, "G(%d,%d,%d) sym", j, k, i);
    }
    /* cs ↔ nocs: G changes sign by (−1)^(m_i+m_j+m_k) */
    for (int t = 0; t < 500; t++) {
        const int i = (int)rnd(200), j = (int)rnd(200), k = (int)rnd(400);
        int l, mi, mj, mk;
        sh_index_lm(i, &l, &mi);
        sh_index_lm(j, &l, &mj);
        sh_index_lm(k, &l, &mk);
        const double s = ((mi + mj + mk) & 1) ? -1.0 : 1.0;
        ck_close(sh_gaunt_real(SH_NOCS, i, j, k), s * sh_gaunt_real(SH_CS, i, j, k), TOL1, 1.0,
                 "cs/nocs G(%d,%d,%d)", i, j, k);
    }
    ck_assert(isnan(sh_gaunt_real(conv, -1, 0, 0)));
}
END_TEST

/* The sparse row lists every non-zero G(i,j,·): all others are exactly 0. */
START_TEST(test_gaunt_row_complete)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    int kk[32];
    double gg[32], work[64];
    for (int i = 0; i < 49; i++)
        for (int j = 0; j < 49; j++) {
            int l1, m1, l2, m2, cnt;
            sh_index_lm(i, &l1, &m1);
            sh_index_lm(j, &l2, &m2);
            ck_assert_uint_le(sh_gaunt_real_row_n(l1, l2), 32);
            ck_assert_uint_le(sh_gaunt_real_row_work_n(l1, l2), 64);
            ck_assert_int_eq(sh_gaunt_real_row(conv, i, j, 12, kk, gg, &cnt, work), SH_OK);
            ck_assert_int_le(cnt, (int)sh_gaunt_real_row_n(l1, l2));
            double full[169];
            memset(full, 0, sizeof full);
            for (int c = 0; c < cnt; c++) full[kk[c]] = gg[c];
            for (int k = 0; k < 169; k++)
                ck_close(full[k], sh_gaunt_real(conv, i, j, k), TOL1, 1.0, "row(%d,%d)[%d]", i, j, k);
        }
}
END_TEST

/* Complex Gaunt: ∫ Y_l^m Y_l^-m Y_0^0 = (−1)^m/√(4π). */
START_TEST(test_gaunt_complex)
{
    for (int l = 0; l < 30; l++)
        for (int m = -l; m <= l; m++) {
            double g;
            ck_assert_int_eq(sh_gaunt_complex_e(l, m, l, -m, 0, 0, &g), SH_OK);
            ck_close(g, ((m & 1) ? -1.0 : 1.0) / sqrt(4 * M_PI), TOL2, 1.0, "Gc(%d,%d)", l, m);
        }
}
END_TEST

static Suite *gaunt_suite(void)
{
    Suite *s = suite_create("gaunt");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_3j_vs_gsl);
    tcase_add_test(tc, test_3j_closed_forms);
    tcase_add_test(tc, test_3j_symmetries);
    tcase_add_test(tc, test_3j_orthogonality);
    tcase_add_test(tc, test_3j_family);
    tcase_add_test(tc, test_3j_underflowed_top_sign);
    tcase_add_loop_test(tc, test_gaunt_vs_quadrature_l4, 0, 2);
    tcase_add_loop_test(tc, test_gaunt_vs_quadrature_l20, 0, 2);
    tcase_add_loop_test(tc, test_gaunt_identities, 0, 2);
    tcase_add_loop_test(tc, test_gaunt_row_complete, 0, 2);
    tcase_add_test(tc, test_gaunt_complex);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(gaunt_suite)
