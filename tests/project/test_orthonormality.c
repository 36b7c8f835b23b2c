/* test_orthonormality.c — sh_rule_gram_error, the Gram matrix of a rule's
 * nodes.  Truths: Gauss-Legendre with S θ nodes integrates polynomials of
 * degree ≤ 2S−1 in cos θ exactly (and 2S uniform φ nodes the trigonometric
 * products), so the product rule is orthonormal to rounding up to order S
 * and not at order S+1 (y_S^0² has degree 2S); a naive triple loop over
 * sh_eval at the same nodes (a second implementation of the definition);
 * the error is the same in both conventions (the sign flips cancel in
 * |G_ij − δ_ij|). */
#include "testutil.h"

START_TEST(test_quad_exact_up_to_S)
{
    const int S = 7;
    double err[10];
    long nodes = 0;
    ck_assert_int_eq(sh_rule_gram_error(SH_RULE_QUAD, S, 1, 10, SH_CS, err, &nodes, NULL, NULL), SH_OK);
    ck_assert_int_eq(nodes, 2L * S * S);
    for (int n = 1; n <= S; n++) ck_assert_msg(err[n - 1] <= 1e-13, "order %d: %.3g", n, err[n - 1]);
    /* y_S^0 squared has degree 2S > 2S − 1: not integrated exactly */
    ck_assert_msg(err[S] > 1e-3, "order %d: %.3g", S + 1, err[S]);
    for (int n = 1; n < 10; n++) ck_assert_msg(err[n] >= err[n - 1], "not cumulative at %d", n);
}
END_TEST

START_TEST(test_naive_gram)
{
    const int order = 5, nb = 25;
    const sh_rule rules[] = {SH_RULE_MC, SH_RULE_RANDOM, SH_RULE_QMC, SH_RULE_QUAD};
    const long samples[] = {600, 700, 513, 4};
    for (int r = 0; r < 4; r++) {
        double err[5], *t, *p, *w, y[25], G[25][25] = {{0}};
        long cnt, nodes;
        ck_assert_int_eq(sh_rule_gram_error(rules[r], samples[r], 3, order, SH_NOCS, err, &nodes, NULL, NULL), SH_OK);
        ck_assert_int_eq(sh_rule_nodes(rules[r], samples[r], 3, &t, &p, &w, &cnt), SH_OK);
        ck_assert_int_eq(nodes, cnt);
        for (long k = 0; k < cnt; k++) {
            ck_assert_int_eq(sh_eval(order, SH_NOCS, t[k], p[k], y), SH_OK);
            for (int i = 0; i < nb; i++)
                for (int j = 0; j < nb; j++) G[i][j] += w[k] * y[i] * y[j];
        }
        for (int n = 1; n <= order; n++) {
            double e = 0;
            for (int i = 0; i < n * n; i++)
                for (int j = 0; j < n * n; j++) e = fmax(e, fabs(G[i][j] - (i == j)));
            /* both sums carry rounding of about (nodes)·ε: 1e-12 absolute below 1e-2 */
            ck_close(err[n - 1], e, 1e-10, 1e-2, "%s order %d", sh_rule_name(rules[r]), n);
        }
        free(t), free(p), free(w);
    }
}
END_TEST

START_TEST(test_conventions_and_limits)
{
    double a[8], b[8];
    ck_assert_int_eq(sh_rule_gram_error(SH_RULE_RANDOM, 300, 9, 8, SH_CS, a, NULL, NULL, NULL), SH_OK);
    ck_assert_int_eq(sh_rule_gram_error(SH_RULE_RANDOM, 300, 9, 8, SH_NOCS, b, NULL, NULL, NULL), SH_OK);
    for (int n = 0; n < 8; n++) ck_close(a[n], b[n], 1e-13, 1e-3, "cs vs nocs, order %d", n + 1);
    ck_assert_int_ne(sh_rule_gram_error(SH_RULE_QUAD, 4, 1, 0, SH_CS, a, NULL, NULL, NULL), SH_OK);
    ck_assert_int_ne(sh_rule_gram_error(SH_RULE_QUAD, 4, 1, SH_GRAM_MAX_ORDER + 1, SH_CS, a, NULL, NULL, NULL), SH_OK);
    ck_assert_msg(sh_last_error()[0] != '\0', "no reason given");
}
END_TEST

static Suite *orthonormality_suite(void)
{
    Suite *s = suite_create("orthonormality");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_quad_exact_up_to_S);
    tcase_add_test(tc, test_naive_gram);
    tcase_add_test(tc, test_conventions_and_limits);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(orthonormality_suite)
