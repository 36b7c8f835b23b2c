/* test_triple.c — Green (2003) eq. 8 transfer matrix M_ij = ∫ b y_i y_j.
 *
 * Truths: the direct product quadrature sh_triple_matrix_quad (shares no
 * code with the Gaunt route), the identity M(b = 1) = I, symmetry, and
 * Green's Fig. 10 claim (M a = projection of the pointwise product a·b),
 * where that projection is done here by an independent GL × uniform-φ loop. */
#include "testutil.h"

#include <gsl/gsl_integration.h>
#include <stdio.h>
#include <string.h>

static unsigned long rng_state = 777;
static double urand(void)
{
    rng_state = rng_state * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* A band-limited function Σ c_k y_k. */
typedef struct {
    int order;
    sh_convention conv;
    const double *c;
} sh_fn_ctx;

static double sh_fn(const double dir[3], double theta, double phi, void *vctx)
{
    const sh_fn_ctx *x = vctx;
    double y[400];
    sh_eval(x->order, x->conv, theta, phi, y);
    double s = 0.0;
    for (int k = 0; k < sh_ncoeff(x->order); k++) s += x->c[k] * y[k];
    return s;
}

/* A smooth, not band-limited function. */
static double smooth_fn(const double d[3], double theta, double phi, void *ctx)
{
    return exp(1.5 * d[0] - 0.7 * d[1] + 0.9 * d[2]) + 1.0 / (2.0 + d[2]);
}

/* Independent projection: c_i = ∫ f y_i by nth GL nodes × 2nth φ nodes. */
static void project(int order, sh_convention conv, sh_sphere_fn f, void *ctx, int nth, double *c)
{
    const int n = sh_ncoeff(order);
    double *y = malloc(sizeof(double) * n);
    memset(c, 0, sizeof(double) * n);
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(nth);
    for (int a = 0; a < nth; a++) {
        double x, w;
        gsl_integration_glfixed_point(-1, 1, a, &x, &w, t);
        for (int q = 0; q < 2 * nth; q++) {
            const double th = acos(x), ph = M_PI * q / nth;
            double d[3];
            sh_dir_from_angles(th, ph, d);
            const double v = f(d, th, ph, ctx) * w * M_PI / nth;
            sh_eval(order, conv, th, ph, y);
            for (int i = 0; i < n; i++) c[i] += v * y[i];
        }
    }
    gsl_integration_glfixed_table_free(t);
    free(y);
}

static double max_abs_diff(const double *a, const double *b, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

START_TEST(test_bandlimited_vs_quad)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    const int order = 6, border = 5, n = 36;
    double b[25];
    for (int k = 0; k < 25; k++) b[k] = 2.0 * urand() - 1.0;
    double *M = malloc(sizeof(double) * n * n), *Q = malloc(sizeof(double) * n * n);
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, border, M), SH_OK);
    sh_fn_ctx ctx = {border, conv, b};
    /* b·y_i·y_j has band <= 4 + 10 = 14: 8 nodes are exact */
    ck_assert_int_eq(sh_triple_matrix_quad(order, conv, sh_fn, &ctx, 8, Q), SH_OK);
    const double d = max_abs_diff(M, Q, (size_t)n * n);
    printf("triple %s order 6, b of order 5: max |M_gaunt - M_quad| = %.3g\n",
           sh_convention_name(conv), d);
    for (int i = 0; i < n * n; i++) ck_close(M[i], Q[i], 1e-13, 1.0, "M[%d]", i);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            ck_assert(M[i * n + j] == M[j * n + i]);
    free(M); free(Q);
}
END_TEST

/* b not band-limited: once b is projected to order 2N−1, the Gaunt matrix
 * equals the quadrature of the true b (bands >= 2N−1 are orthogonal to
 * every y_i y_j); a longer b vector changes nothing. */
START_TEST(test_smooth_vs_quad)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    const int order = 5, n = 25, bo = 2 * order - 1;
    double b[19 * 19 + 200], Q[625], M[625], M2[625];
    /* 64 nodes: a GSL-tabulated rule (its computed ones are ~1e-10 only) */
    project(bo + 4, conv, smooth_fn, NULL, 64, b);
    ck_assert_int_eq(sh_triple_matrix_quad(order, conv, smooth_fn, NULL, 64, Q), SH_OK);
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, bo, M), SH_OK);
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, bo + 4, M2), SH_OK);
    const double d = max_abs_diff(M, Q, n * n);
    printf("triple %s order 5, smooth b projected to order 9: max |M_gaunt - M_quad| = %.3g\n",
           sh_convention_name(conv), d);
    for (int i = 0; i < n * n; i++) {
        ck_close(M[i], Q[i], 1e-12, 1.0, "M[%d]", i);
        ck_assert(M2[i] == M[i]);
    }
    /* truncating b one band lower does change M (the band 2N−2 matters) */
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, bo - 1, M2), SH_OK);
    ck_assert(max_abs_diff(M, M2, n * n) > 1e-6);
}
END_TEST

START_TEST(test_identity)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    const int order = 8, n = 64;
    double b[9] = {0};
    double *M = malloc(sizeof(double) * n * n);
    /* b = √(4π) y_0 ≡ 1  ⇒  M = I;  b = c ⇒ M = c I */
    b[0] = sqrt(4.0 * M_PI);
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, 3, M), SH_OK);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            ck_close(M[i * n + j], i == j ? 1.0 : 0.0, TOL1, 1.0, "I[%d][%d]", i, j);
    b[0] = -2.5 * sqrt(4.0 * M_PI);
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, 1, M), SH_OK);
    for (int i = 0; i < n; i++) ck_close(M[i * n + i], -2.5, TOL1, 1.0, "cI[%d]", i);
    free(M);
}
END_TEST

/* Green Fig. 10: M a = projection of a·b to `order` bands, when a and b are
 * band-limited (order N each: a·b has band <= 2N−2). */
typedef struct { sh_fn_ctx a, b; } prod_ctx;
static double prod_fn(const double d[3], double th, double ph, void *vctx)
{
    prod_ctx *p = vctx;
    return sh_fn(d, th, ph, &p->a) * sh_fn(d, th, ph, &p->b);
}

START_TEST(test_apply_equals_product_projection)
{
    const sh_convention conv = _i ? SH_NOCS : SH_CS;
    const int order = 7, n = 49;
    double a[49], b[49], c[49], p[49], M[49 * 49];
    for (int k = 0; k < n; k++) { a[k] = urand() - 0.5; b[k] = urand() - 0.5; }
    ck_assert_int_eq(sh_triple_matrix(order, conv, b, order, M), SH_OK);
    for (int i = 0; i < n; i++) {
        c[i] = 0.0;
        for (int j = 0; j < n; j++) c[i] += M[i * n + j] * a[j];
    }
    prod_ctx pc = {{order, conv, a}, {order, conv, b}};
    project(order, conv, prod_fn, &pc, 12, p); /* degree 18 + 6 < 24 */
    double d = 0.0;
    for (int i = 0; i < n; i++) {
        ck_close(c[i], p[i], 1e-13, 1.0, "(Ma)[%d]", i);
        d = fmax(d, fabs(c[i] - p[i]));
    }
    printf("triple %s order 7: max |M a - proj(a b)| = %.3g\n", sh_convention_name(conv), d);
}
END_TEST

/* Green's example b = y_2^2: M couples only (l, m) pairs allowed by the
 * selection rules; check a handful of entries against the Gaunt values. */
START_TEST(test_green_example)
{
    const int order = 5, n = 25;
    double b[9] = {0}, M[625];
    b[sh_index(2, 2)] = 1.0;
    ck_assert_int_eq(sh_triple_matrix(order, SH_CS, b, 3, M), SH_OK);
    int nz = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            ck_close(M[i * n + j], sh_gaunt_real(SH_CS, i, j, sh_index(2, 2)), TOL1, 1.0, "M[%d][%d]", i, j);
            if (fabs(M[i * n + j]) > 1e-12) nz++;
        }
    /* M_00,22 = 1/√(4π) */
    ck_close(M[0 * n + sh_index(2, 2)], 1.0 / sqrt(4 * M_PI), TOL1, 1.0, "M[0][8]");
    ck_assert_int_gt(nz, 0);
    ck_assert_int_lt(nz, n * n / 4);
    printf("triple: Green's b = y_2^2 example, order 5: %d non-zero entries of 625\n", nz);
}
END_TEST

static double one_fn(const double d[3], double th, double ph, void *ctx) { return 1.0; }

/* The quadrature method with many (untabulated) nodes stays exact:
 * b = 1 gives the orthonormality matrix I.  Regression: GSL's computed
 * Gauss-Legendre nodes for such n are only ~1e-10 accurate. */
START_TEST(test_quad_many_nodes)
{
    static const int nodes[] = {60, 200, 1000};
    double M[25 * 25];
    for (int t = 0; t < 3; t++) {
        ck_assert_int_eq(sh_triple_matrix_quad(5, SH_CS, one_fn, NULL, nodes[t], M), SH_OK);
        for (int i = 0; i < 25; i++)
            for (int j = 0; j < 25; j++)
                ck_close(M[i * 25 + j], i == j ? 1.0 : 0.0, 1e-13, 1.0, "nodes %d: M[%d][%d]", nodes[t], i, j);
    }
}
END_TEST

START_TEST(test_errors)
{
    double b[4] = {1, 0, 0, 0}, M[16];
    ck_assert_int_eq(sh_triple_matrix(0, SH_CS, b, 1, M), SH_EINVAL);
    ck_assert_int_eq(sh_triple_matrix(2, SH_CS, b, 0, M), SH_EINVAL);
    ck_assert_int_eq(sh_triple_matrix(2, (sh_convention)7, b, 1, M), SH_EINVAL);
    ck_assert_int_eq(sh_triple_matrix_quad(2, SH_CS, NULL, NULL, 4, M), SH_EINVAL);
    ck_assert_int_eq(sh_triple_matrix_quad(2, SH_CS, smooth_fn, NULL, 0, M), SH_EINVAL);
    ck_assert_str_ne(sh_last_error(), "");
}
END_TEST

static Suite *triple_suite(void)
{
    Suite *s = suite_create("triple");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_bandlimited_vs_quad, 0, 2);
    tcase_add_loop_test(tc, test_smooth_vs_quad, 0, 2);
    tcase_add_loop_test(tc, test_identity, 0, 2);
    tcase_add_loop_test(tc, test_apply_equals_product_projection, 0, 2);
    tcase_add_test(tc, test_green_example);
    tcase_add_test(tc, test_quad_many_nodes);
    tcase_add_test(tc, test_errors);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(triple_suite)
