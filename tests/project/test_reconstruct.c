/* test_reconstruct.c — windows, lat-long reconstruction, ringing.
 *
 * Truths: direct evaluation Σ c_i y_i with sh_eval at pixel centres; the
 * projection of the reconstructed image (a second, independent code path
 * in envmap.c); the Legendre identity ∫_a^1 P_l = (P_{l−1}(a) − P_{l+1}(a))/(2l+1)
 * with GSL's P_l for the coefficients of a cap; the window formulas.
 */
#include <stdio.h>

#include "testutil.h"

#include <gsl/gsl_sf_legendre.h>
#include <string.h>

START_TEST(window_parse_and_factors)
{
    sh_window w;
    ck_assert_int_eq(sh_window_parse("none", &w), SH_OK);
    ck_assert_int_eq(w.kind, SH_WINDOW_NONE);
    ck_assert_int_eq(sh_window_parse("gauss:0.01", &w), SH_OK);
    ck_assert_int_eq(w.kind, SH_WINDOW_GAUSS);
    ck_close(w.param, 0.01, 0, 1.0, "gauss S");
    ck_close(sh_window_factor(&w, 3, 8), exp(-0.12), TOL1, 1.0, "gauss l=3");
    ck_assert_int_eq(sh_window_parse("hann", &w), SH_OK);
    ck_assert_int_eq(w.kind, SH_WINDOW_HANN);
    ck_close(sh_window_factor(&w, 4, 8), 0.5, TOL1, 1.0, "hann l=W/2");
    ck_close(sh_window_factor(&w, 8, 8), 0.0, 0, 1.0, "hann l=W");
    ck_assert_int_eq(sh_window_parse("lanczos:4", &w), SH_OK);
    ck_close(sh_window_factor(&w, 2, 10), 2.0 / M_PI, TOL1, 1.0, "lanczos sinc(1/2)");
    ck_close(sh_window_factor(&w, 5, 10), 0.0, 0, 1.0, "lanczos beyond W");
    const char *bad[] = {"gauss", "gauss:-1", "gauss:nan", "hann:0", "lanczos:x", "none:3",
                         "box", "", "hann:3junk"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        ck_assert_msg(sh_window_parse(bad[k], &w) == SH_EINVAL, "'%s' accepted", bad[k]);
    /* every window is 1 at l = 0 and non-increasing in l */
    const char *specs[] = {"none", "gauss:0.003", "gauss:0", "hann", "hann:5.5", "lanczos",
                           "lanczos:7"};
    for (size_t k = 0; k < sizeof specs / sizeof specs[0]; k++) {
        ck_assert_int_eq(sh_window_parse(specs[k], &w), SH_OK);
        ck_close(sh_window_factor(&w, 0, 12), 1.0, 0, 1.0, "%s at l=0", specs[k]);
        for (int l = 1; l < 12; l++) {
            const double a = sh_window_factor(&w, l - 1, 12), b = sh_window_factor(&w, l, 12);
            ck_assert_msg(b <= a && b >= 0.0, "%s: σ_%d=%g > σ_%d=%g", specs[k], l, b, l - 1, a);
        }
    }
    ck_close(sh_window_factor(NULL, 5, 6), 1.0, 0, 1.0, "NULL window");
}
END_TEST

START_TEST(reconstruct_matches_direct_sum_and_round_trips)
{
    const int order = 5, nn = 25, W = 256, H = 128;
    double c[3 * 25];
    for (int i = 0; i < 3 * nn; i++) c[i] = sin(1.7 * i + 0.3) / (1 + i % nn);
    sh_window win;
    ck_assert_int_eq(sh_window_parse("hann:7", &win), SH_OK);
    sh_image img;
    ck_assert_int_eq(sh_reconstruct_latlong(order, SH_NOCS, c, 3, &win, W, &img), SH_OK);
    ck_assert_int_eq(img.width, W);
    ck_assert_int_eq(img.height, H);
    ck_assert_int_eq(img.nchan, 3);
    ck_assert_str_eq(img.names[0], "R");
    ck_assert_str_eq(img.names[2], "B");
    /* pointwise against Σ σ_l c_i y_i(centre) */
    double y[25];
    for (int k = 0; k < 50; k++) {
        const int i = (k * 97) % W, j = (k * 31) % H, ch = k % 3;
        ck_assert_int_eq(sh_eval(order, SH_NOCS, M_PI * (j + 0.5) / H, 2 * M_PI * (i + 0.5) / W, y), SH_OK);
        double f = 0.0;
        for (int q = 0; q < nn; q++) {
            int l, m;
            sh_index_lm(q, &l, &m);
            f += sh_window_factor(&win, l, order) * c[ch * nn + q] * y[q];
        }
        ck_close(img.data[ch * W * H + j * W + i], f, 2e-7, 1.0, "pixel (%d,%d,%d)", i, j, ch);
    }
    /* project back: recovers σ_l c up to the O(1/H²) θ sampling error */
    double back[3 * 25];
    ck_assert_int_eq(sh_project_image(&img, SH_LAYOUT_LATLONG, order, SH_NOCS, back), SH_OK);
    for (int q = 0; q < 3 * nn; q++) {
        int l, m;
        sh_index_lm(q % nn, &l, &m);
        ck_close(back[q], sh_window_factor(&win, l, order) * c[q], 2e-3, 1.0, "round trip c[%d]", q);
    }
    sh_image_free(&img);
    /* one channel is called Y; two channels and tiny widths are refused */
    ck_assert_int_eq(sh_reconstruct_latlong(order, SH_CS, c, 1, NULL, 8, &img), SH_OK);
    ck_assert_str_eq(img.names[0], "Y");
    ck_assert_int_eq(img.height, 4);
    sh_image_free(&img);
    ck_assert_int_eq(sh_reconstruct_latlong(order, SH_CS, c, 2, NULL, 8, &img), SH_EINVAL);
    ck_assert_int_eq(sh_reconstruct_latlong(order, SH_CS, c, 1, NULL, 1, &img), SH_EINVAL);
    c[3] = NAN;
    ck_assert_int_eq(sh_reconstruct_latlong(order, SH_CS, c, 1, NULL, 8, &img), SH_EINVAL);
}
END_TEST

/* coefficients of the cap {θ ≤ t}: z_l = 2π √((2l+1)/4π) ∫_{cos t}^1 P_l */
static void cap_coeffs(double t, int order, double *c)
{
    const double a = cos(t);
    memset(c, 0, sizeof(double) * order * order);
    for (int l = 0; l < order; l++) {
        const double I = l == 0 ? 1.0 - a
                                : (gsl_sf_legendre_Pl(l - 1, a) - gsl_sf_legendre_Pl(l + 1, a)) / (2.0 * l + 1.0);
        c[sh_index(l, 0)] = 2.0 * M_PI * sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) * I;
    }
}

START_TEST(gauss_window_reduces_ringing_of_a_cap)
{
    const int order = 16;
    double c[256];
    cap_coeffs(M_PI / 6, order, c);
    /* sanity of the truth: the band-0 term is the cap's mean */
    ck_close(c[0], 2 * M_PI * (1 - cos(M_PI / 6)) / sqrt(4 * M_PI), TOL1, 1.0, "cap c0");
    sh_window none = {SH_WINDOW_NONE, 0}, g1, g2, hann;
    ck_assert_int_eq(sh_window_parse("gauss:0.005", &g1), SH_OK);
    ck_assert_int_eq(sh_window_parse("gauss:0.02", &g2), SH_OK);
    ck_assert_int_eq(sh_window_parse("hann", &hann), SH_OK);
    double mn0, fr0, mn1, fr1, mn2, fr2, mnh, frh;
    ck_assert_int_eq(sh_ringing(order, SH_CS, c, &none, 256, &mn0, &fr0), SH_OK);
    ck_assert_int_eq(sh_ringing(order, SH_CS, c, &g1, 256, &mn1, &fr1), SH_OK);
    ck_assert_int_eq(sh_ringing(order, SH_CS, c, &g2, 256, &mn2, &fr2), SH_OK);
    ck_assert_int_eq(sh_ringing(order, SH_CS, c, &hann, 256, &mnh, &frh), SH_OK);
    ck_assert_msg(mn0 < -0.02 && fr0 > 1e-4, "unwindowed cap should ring: %g %g", mn0, fr0);
    ck_assert_msg(mn0 < mn1 && mn1 < mn2 && mn2 <= 0.0, "gauss: %g %g %g", mn0, mn1, mn2);
    ck_assert_msg(fr0 > fr1 && fr1 > fr2, "gauss energy: %g %g %g", fr0, fr1, fr2);
    ck_assert_msg(mnh > mn0 && frh < fr0, "hann: %g %g vs %g %g", mnh, frh, mn0, fr0);
    if (getenv("SHLAB_TEST_VERBOSE"))
        fprintf(stderr, "cap 30°, order 16: none %g/%g gauss:0.005 %g/%g gauss:0.02 %g/%g hann %g/%g\n",
                mn0, fr0, mn1, fr1, mn2, fr2, mnh, frh);
}
END_TEST

START_TEST(ringing_of_constants)
{
    double c[9] = {0};
    c[0] = 2.0 * sqrt(4 * M_PI); /* f ≡ 2 */
    double mn = 1, fr = 1;
    ck_assert_int_eq(sh_ringing(3, SH_CS, c, NULL, 64, &mn, &fr), SH_OK);
    ck_assert(mn == 0.0 && fr == 0.0);
    c[0] = -c[0]; /* f ≡ −2: all energy is negative */
    ck_assert_int_eq(sh_ringing(3, SH_CS, c, NULL, 64, &mn, &fr), SH_OK);
    ck_close(mn, -2.0, TOL2, 1.0, "most negative of -2");
    ck_close(fr, 1.0, TOL0, 1.0, "negative fraction of -2");
    memset(c, 0, sizeof c); /* f ≡ 0 */
    ck_assert_int_eq(sh_ringing(3, SH_CS, c, NULL, 64, &mn, &fr), SH_OK);
    ck_assert(mn == 0.0 && fr == 0.0);
    ck_assert_int_eq(sh_ringing(0, SH_CS, c, NULL, 64, &mn, &fr), SH_EINVAL);
}
END_TEST

static Suite *reconstruct_suite(void)
{
    Suite *s = suite_create("reconstruct");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, window_parse_and_factors);
    tcase_add_test(tc, reconstruct_matches_direct_sum_and_round_trips);
    tcase_add_test(tc, gauss_window_reduces_ringing_of_a_cap);
    tcase_add_test(tc, ringing_of_constants);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(reconstruct_suite)
