/* test_peer_healpix.cc — HEALPix C++ as an oracle for shlab's all-band
 * rotation (sh_rot_stream, the halfpi method).
 *
 * Truths: HEALPix's own synthesis (alm2map) at the pixel centres, against
 * shlab's basis evaluated there (sh_eval, no rotation code) — this pins the
 * basis map of peer_healpix.h; HEALPix's rotate_alm, synthesised, against the
 * unrotated function evaluated at R⁻¹s — this pins the angle map without
 * using any shlab rotation (and a swapped map must fail it); then shlab's
 * rotation of every band to lmax 300 against rotate_alm.  Built only when
 * pkg-config finds healpix_cxx (the Makefile says so otherwise). */
#include "peer_healpix.h"

#include <alm_healpix_tools.h>
#include <healpix_map.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "testutil.h"

/* max over the pixel centres of a HEALPix map (Nside 2^k) of |synthesis of
 * a − f_ref(s)|, where f_ref is the real-SH function c evaluated at M·s */
static double synth_vs_eval(int lmax, const peer_alm &a, const double *c, const double M[9], int k)
{
    Healpix_Map<double> map(k, RING);
    alm2map(a, map);
    const int order = lmax + 1;
    std::vector<double> y((size_t)order * order);
    double worst = 0;
    for (int p = 0; p < map.Npix(); p++) {
        const pointing pt = map.pix2ang(p);
        const double s[3] = {std::sin(pt.theta) * std::cos(pt.phi), std::sin(pt.theta) * std::sin(pt.phi),
                             std::cos(pt.theta)};
        double d[3];
        for (int i = 0; i < 3; i++) d[i] = M[3 * i] * s[0] + M[3 * i + 1] * s[1] + M[3 * i + 2] * s[2];
        ck_assert_int_eq(sh_eval_dir(order, SH_CS, d, y.data()), SH_OK);
        double f = 0;
        for (size_t i = 0; i < y.size(); i++) f += c[i] * y[i];
        worst = std::fmax(worst, std::fabs(map[p] - f));
    }
    return worst;
}

START_TEST(test_basis_map)
{
    const int lmax = 12, n = (lmax + 1) * (lmax + 1);
    std::vector<double> c(n);
    peer_gauss(11, n, c.data());
    peer_alm a(lmax, lmax);
    peer_to_alm(lmax, c.data(), a);
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double e = synth_vs_eval(lmax, a, c.data(), I, 4);
    fprintf(stderr, "healpix alm2map vs shlab basis (lmax %d, Nside 16): %.3g\n", lmax, e);
    ck_assert_msg(e < 1e-12, "basis map: %.3g", e);
    /* the round trip of the map itself */
    std::vector<double> back(n);
    peer_from_alm(lmax, a, back.data());
    for (int i = 0; i < n; i++) ck_assert(back[i] == c[i] || std::fabs(back[i] - c[i]) < 1e-15);
}
END_TEST

START_TEST(test_angle_map)
{
    /* rotate_alm with (ψ, θ, φ) = (γ, β, α) synthesises g(s) = f(R⁻¹s) */
    const int lmax = 10, n = (lmax + 1) * (lmax + 1);
    std::vector<double> c(n);
    peer_gauss(12, n, c.data());
    sh_rotation r;
    ck_assert_int_eq(sh_rotation_from_euler(0.7, 1.1, -2.3, &r), SH_OK);
    double Rt[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Rt[3 * i + j] = r.R[3 * j + i];
    peer_alm a(lmax, lmax);
    peer_to_alm(lmax, c.data(), a);
    peer_rotate(a, r);
    const double e = synth_vs_eval(lmax, a, c.data(), Rt, 4);
    fprintf(stderr, "healpix rotate_alm(gamma, beta, alpha) vs f(R^-1 s): %.3g\n", e);
    ck_assert_msg(e < 1e-12, "angle map: %.3g", e);
    /* the other order of the angles is a different rotation: the check sees it */
    peer_to_alm(lmax, c.data(), a);
    rotate_alm(a, r.alpha, r.beta, r.gamma);
    const double e2 = synth_vs_eval(lmax, a, c.data(), Rt, 4);
    ck_assert_msg(e2 > 1e-3, "swapped angles pass too (%.3g): the check is blind", e2);
}
END_TEST

/* shlab's all-band rotation against rotate_alm, lmax 300, several rotations,
 * both directions; coefficients N(0, 1) */
START_TEST(test_agreement_lmax300)
{
    const int lmax = 300, order = lmax + 1, n = order * order;
    std::vector<double> c(n), y(n), h(n);
    peer_gauss(13, n, c.data());
    const double e3[5][3] = {{0.3, 1.1, -0.7}, {-2.9, 2.8, 1.9}, {1.0, 0.0, -0.4}, {0.6, M_PI, 2.0},
                             {M_PI / 2, M_PI / 2, -M_PI / 2}};
    sh_rot_stream *s;
    ck_assert_int_eq(sh_rot_stream_create(order, SH_CS, 1, &s), SH_OK);
    peer_alm a(lmax, lmax);
    double worst = 0;
    for (int k = 0; k < 5; k++)
        for (int inv = 0; inv < 2; inv++) {
            sh_rotation r;
            ck_assert_int_eq(sh_rotation_from_euler(e3[k][0], e3[k][1], e3[k][2], &r), SH_OK);
            ck_assert_int_eq(sh_rot_stream_apply(s, 1, &r, inv, 1, c.data(), y.data()), SH_OK);
            peer_to_alm(lmax, c.data(), a);
            peer_rotate(a, r, inv != 0);
            peer_from_alm(lmax, a, h.data());
            double e = 0;
            for (int i = 0; i < n; i++) e = std::fmax(e, std::fabs(y[i] - h[i]));
            ck_assert_msg(e <= 1e-12, "rotation %d%s: max |shlab - healpix| = %.3g", k, inv ? " (inverse)" : "", e);
            worst = std::fmax(worst, e);
        }
    sh_rot_stream_free(s);
    fprintf(stderr, "shlab halfpi vs healpix rotate_alm, lmax %d, 10 rotations: max abs diff %.3g\n", lmax, worst);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("peer_healpix");
    TCase *tc = tcase_create("healpix");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_basis_map);
    tcase_add_test(tc, test_angle_map);
    tcase_add_test(tc, test_agreement_lmax300);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
