/* test_rot_direct.c — the `direct` method (src/rotate/rot_direct.c): bands
 * 0..2 written straight from the matrix.
 *
 * Truths: the MPFR reference band (sh_rot_reference_band, 32 digits,
 * computed from the Euler angles by the Wigner sum: no code shared with the
 * quadratic forms), the pointwise identity Σ g_i y_i(s) = Σ c_i y_i(Rᵀs)
 * with sh_eval_dir, and the method's own single-rotation path for the
 * batch.  Rotations: the fixed set of rottest.h (random, β = 0, tiny, π/2,
 * near π, π, the gimbal cases α + γ = 0) and random unit quaternions.
 * The multiplication counts are the ones derived in rot_direct.c's header
 * (set: none; apply: 9 for band 1, 48 for band 2), not read from a run. */
#include "rottest.h"

#define DR_NQ 200
#define DR_NCASES (ROT_NCASES + DR_NQ)
#define DR_N 9 /* coefficients of order 3 */
#define DR_NB 35 /* sh_rot_block_offset(3) */
#define DR_TOL_D 1e-14
#define DR_TOL_F 2e-6 /* float blocks: a few float ulps of 1 (entries are ≤ 1) */

START_TEST(test_blocks_vs_reference)
{
    double worst[2] = {0, 0};
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++)
            for (int order = 1; order <= 3; order++) {
                sh_rot_plan *p = NULL;
                ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_DIRECT, pr, conv, &p), SH_OK);
                for (int k = 0; k < DR_NCASES; k++) {
                    sh_rotation r;
                    char name[160];
                    double ref[DR_NB], B[DR_NB];
                    rot_case_quat(k, 7919UL, &r, name, sizeof name);
                    rot_reference_blocks(3, conv, &r, ref);
                    for (int how = 0; how < 3; how++) {
                        ck_assert_int_eq(rot_set_how(p, how, &r), SH_OK);
                        ck_assert_int_eq(sh_rot_plan_blocks(p, B), SH_OK);
                        const double e = rot_maxdiff(sh_rot_block_offset(order), B, ref);
                        if (!(e <= (pr ? DR_TOL_F : DR_TOL_D)))
                            ck_abort_msg("direct %s %s order %d set %d %s: max|B − ref| = %.3g", sh_precision_name(pr),
                                         sh_convention_name(conv), order, how, name, e);
                        worst[pr] = fmax(worst[pr], e);
                    }
                }
                sh_rot_plan_free(p);
            }
    fprintf(stderr, "direct vs reference, orders 1..3, %d rotations: double %.3g float %.3g\n", DR_NCASES, worst[0],
            worst[1]);
}
END_TEST

/* apply (double and float API, every way of setting) == reference blocks ×
 * vector; in place gives the same bits. */
START_TEST(test_apply_vs_reference)
{
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++) {
            sh_rot_plan *p = NULL;
            ck_assert_int_eq(sh_rot_plan_create(3, SH_ROT_DIRECT, pr, conv, &p), SH_OK);
            const double tol = pr ? ROT_TOL_F : 4 * DR_TOL_D;
            for (int k = 0; k < DR_NCASES; k++) {
                sh_rotation r;
                char name[160];
                double ref[DR_NB], c[DR_N], want[DR_N], g[DR_N], h[DR_N];
                rot_case_quat(k, 7919UL, &r, name, sizeof name);
                rot_reference_blocks(3, conv, &r, ref);
                for (int i = 0; i < DR_N; i++) c[i] = 2 * rot_urand() - 1;
                rot_blocks_mul(3, ref, c, want);
                for (int how = 0; how < 4; how++) {
                    if (how == 3) { /* float matrix and float vectors */
                        if (!pr) continue;
                        float Rf[9], cf[DR_N], gf[DR_N];
                        for (int i = 0; i < 9; i++) Rf[i] = (float)r.R[i];
                        for (int i = 0; i < DR_N; i++) cf[i] = (float)c[i];
                        ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, Rf), SH_OK);
                        ck_assert_int_eq(sh_rot_plan_apply_f(p, cf, gf), SH_OK);
                        for (int i = 0; i < DR_N; i++) g[i] = gf[i];
                    } else {
                        ck_assert_int_eq(rot_set_how(p, how, &r), SH_OK);
                        ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
                        memcpy(h, c, sizeof h);
                        ck_assert_int_eq(sh_rot_plan_apply(p, h, h), SH_OK);
                        ck_assert_msg(memcmp(g, h, sizeof g) == 0, "in-place apply differs (%s)", name);
                    }
                    const double e = rot_maxdiff(DR_N, g, want);
                    if (!(e <= tol))
                        ck_abort_msg("direct %s %s set %d %s: max|apply − ref·c| = %.3g", sh_precision_name(pr),
                                     sh_convention_name(conv), how, name, e);
                }
            }
            sh_rot_plan_free(p);
        }
}
END_TEST

/* The function is rotated: Σ g_i y_i(s) = Σ c_i y_i(Rᵀs) at random points. */
START_TEST(test_pointwise)
{
    for (int conv = 0; conv < 2; conv++) {
        sh_rot_plan *p = NULL;
        ck_assert_int_eq(sh_rot_plan_create(3, SH_ROT_DIRECT, SH_PREC_DOUBLE, conv, &p), SH_OK);
        for (int k = 0; k < DR_NCASES; k += 7) {
            sh_rotation r;
            char name[160];
            double c[DR_N], g[DR_N];
            rot_case_quat(k, 7919UL, &r, name, sizeof name);
            for (int i = 0; i < DR_N; i++) c[i] = 2 * rot_urand() - 1;
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
            for (int t = 0; t < 6; t++) {
                const double s[3] = {rot_urand() - 0.5, rot_urand() - 0.5, rot_urand() - 0.5};
                double ri[3], ys[DR_N], yr[DR_N], f = 0, gg = 0;
                for (int i = 0; i < 3; i++) ri[i] = r.R[i] * s[0] + r.R[3 + i] * s[1] + r.R[6 + i] * s[2];
                ck_assert_int_eq(sh_eval_dir(3, conv, s, ys), SH_OK);
                ck_assert_int_eq(sh_eval_dir(3, conv, ri, yr), SH_OK);
                for (int i = 0; i < DR_N; i++) f += c[i] * yr[i], gg += g[i] * ys[i];
                ck_close(gg, f, 64 * DBL_EPSILON, 1, "direct %s %s point %d", sh_convention_name(conv), name, t);
            }
        }
        sh_rot_plan_free(p);
    }
}
END_TEST

/* rotate_many (K rotations, structure of arrays) == K single rotations
 * (set_matrix + apply) and == the reference; in place; every order,
 * convention and kernel (the batch is compiled per instruction set), double
 * and float; rotate_many_quat too. */
static void dr_check_many(int order, sh_convention conv, sh_precision pr, sh_rot_kernel kern)
{
    const size_t K = DR_NCASES, n = (size_t)order * order;
    double *R = malloc(9 * K * sizeof *R), *q = malloc(4 * K * sizeof *q);
    double *x = malloc(n * K * sizeof *x), *y = malloc(n * K * sizeof *y), *yq = malloc(n * K * sizeof *yq);
    float *Rf = malloc(9 * K * sizeof *Rf), *xf = malloc(n * K * sizeof *xf), *yf = malloc(n * K * sizeof *yf);
    sh_rotation *rs = malloc(K * sizeof *rs);
    ck_assert(R && q && x && y && yq && Rf && xf && yf && rs);
    for (size_t k = 0; k < K; k++) {
        char name[160];
        double qk[4];
        rot_case_quat((int)k, 7919UL, &rs[k], name, sizeof name);
        sh_rotation_to_quat(&rs[k], qk);
        for (int j = 0; j < 9; j++) Rf[j * K + k] = (float)(R[j * K + k] = rs[k].R[j]);
        for (int j = 0; j < 4; j++) q[j * K + k] = qk[j];
        for (size_t i = 0; i < n; i++) xf[i * K + k] = (float)(x[i * K + k] = 2 * rot_urand() - 1);
    }
    sh_rot_plan *p = NULL, *one = NULL;
    ck_assert_int_eq(sh_rot_plan_create_kernel(order, SH_ROT_DIRECT, pr, conv, kern, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_kernel(p), kern); /* kept: the batch has a variant per kernel */
    /* the single rotations with the same kernel: each instruction set has its
     * own one-vector kernel too (fused multiply-adds in avx2 and avx512) */
    ck_assert_int_eq(sh_rot_plan_create_kernel(order, SH_ROT_DIRECT, pr, conv, kern, &one), SH_OK);
    if (pr) {
        ck_assert_int_eq(sh_rot_plan_rotate_many_f(p, K, Rf, xf, yf), SH_OK);
        for (size_t i = 0; i < n * K; i++) y[i] = yf[i];
        /* in place */
        ck_assert_int_eq(sh_rot_plan_rotate_many_f(p, K, Rf, xf, xf), SH_OK);
        ck_assert_msg(memcmp(xf, yf, n * K * sizeof *xf) == 0, "rotate_many_f in place differs");
        for (size_t i = 0; i < n * K; i++) xf[i] = (float)x[i];
    } else {
        ck_assert_int_eq(sh_rot_plan_rotate_many(p, K, R, x, y), SH_OK);
        double *z = malloc(n * K * sizeof *z);
        memcpy(z, x, n * K * sizeof *z);
        ck_assert_int_eq(sh_rot_plan_rotate_many(p, K, R, z, z), SH_OK);
        ck_assert_msg(memcmp(z, y, n * K * sizeof *z) == 0, "rotate_many in place differs");
        free(z);
        ck_assert_int_eq(sh_rot_plan_rotate_many_quat(p, K, q, x, yq), SH_OK);
    }
    uint64_t ms, ma;
    ck_assert_int_eq(pr ? sh_rot_plan_rotate_many_f(p, K, Rf, xf, yf) : sh_rot_plan_rotate_many(p, K, R, x, y), SH_OK);
    sh_rot_plan_mults(p, &ms, &ma);
    ck_assert_uint_eq(ms, 0u);
    ck_assert_uint_eq(ma, order == 3 ? 57u : order == 2 ? 9u : 0u);
    const double tol_one = pr ? 2e-6 : 4e-15, tol_ref = pr ? ROT_TOL_F : 4 * DR_TOL_D;
    for (size_t k = 0; k < K; k++) {
        double xk[DR_N], yk[DR_N], want[DR_N], ref[DR_NB];
        for (size_t i = 0; i < n; i++) xk[i] = x[i * K + k];
        if (pr) {
            float Rk[9], xk_f[DR_N], yk_f[DR_N];
            for (int j = 0; j < 9; j++) Rk[j] = Rf[j * K + k];
            for (size_t i = 0; i < n; i++) xk_f[i] = xf[i * K + k];
            ck_assert_int_eq(sh_rot_plan_set_matrix_f(one, Rk), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply_f(one, xk_f, yk_f), SH_OK);
            for (size_t i = 0; i < n; i++) yk[i] = yk_f[i];
            ck_assert_int_eq(sh_rot_plan_apply_f(one, xk_f, xk_f), SH_OK); /* in place: the same bits */
            ck_assert_msg(memcmp(xk_f, yk_f, n * sizeof *xk_f) == 0, "apply_f in place differs (%s)",
                          sh_rot_kernel_name(kern));
        } else {
            ck_assert_int_eq(sh_rot_plan_set_matrix(one, rs[k].R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(one, xk, yk), SH_OK);
            double xin[DR_N];
            memcpy(xin, xk, sizeof xin);
            ck_assert_int_eq(sh_rot_plan_apply(one, xin, xin), SH_OK); /* in place: the same bits */
            ck_assert_msg(memcmp(xin, yk, n * sizeof *xin) == 0, "apply in place differs (%s)", sh_rot_kernel_name(kern));
        }
        rot_reference_blocks(3, conv, &rs[k], ref);
        rot_blocks_mul(order, ref, xk, want);
        for (size_t i = 0; i < n; i++) {
            ck_close(y[i * K + k], yk[i], tol_one, 1, "rotate_many vs one, order %d %s %s %s k %zu i %zu", order,
                     sh_convention_name(conv), sh_precision_name(pr), sh_rot_kernel_name(kern), k, i);
            ck_close(y[i * K + k], want[i], tol_ref, 1, "rotate_many vs reference, order %d %s %s k %zu i %zu",
                     order, sh_convention_name(conv), sh_precision_name(pr), k, i);
            if (!pr)
                ck_close(yq[i * K + k], want[i], tol_ref, 1, "rotate_many_quat vs reference, order %d %s k %zu i %zu",
                         order, sh_convention_name(conv), k, i);
        }
    }
    sh_rot_plan_free(p);
    sh_rot_plan_free(one);
    free(R), free(q), free(x), free(y), free(yq), free(Rf), free(xf), free(yf), free(rs);
}

START_TEST(test_rotate_many)
{
    for (int kern = SH_KERNEL_SCALAR; kern < SH_KERNEL_N; kern++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)kern)) continue;
        for (int order = 1; order <= 3; order++)
            for (int conv = 0; conv < 2; conv++)
                for (int pr = 0; pr < 2; pr++) dr_check_many(order, conv, pr, (sh_rot_kernel)kern);
    }
}
END_TEST

/* apply_many (one rotation, K vectors, structure of arrays) == the
 * reference blocks × each vector, double and float, both conventions. */
START_TEST(test_apply_many)
{
    enum { K = 13 };
    sh_rotation r;
    char name[160];
    rot_case_quat(3, 7919UL, &r, name, sizeof name);
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++) {
            double ref[DR_NB], x[DR_N * K], y[DR_N * K], xk[DR_N], want[DR_N];
            float xf[DR_N * K], yf[DR_N * K];
            rot_reference_blocks(3, conv, &r, ref);
            for (int i = 0; i < DR_N * K; i++) xf[i] = (float)(x[i] = 2 * rot_urand() - 1);
            sh_rot_plan *p = NULL;
            ck_assert_int_eq(sh_rot_plan_create(3, SH_ROT_DIRECT, pr, conv, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            if (pr) {
                ck_assert_int_eq(sh_rot_plan_apply_many_f(p, K, xf, yf), SH_OK);
                for (int i = 0; i < DR_N * K; i++) y[i] = yf[i], x[i] = xf[i];
            } else {
                ck_assert_int_eq(sh_rot_plan_apply_many(p, K, x, y), SH_OK);
            }
            for (int k = 0; k < K; k++) {
                for (int i = 0; i < DR_N; i++) xk[i] = x[i * K + k];
                rot_blocks_mul(3, ref, xk, want);
                for (int i = 0; i < DR_N; i++)
                    ck_close(y[i * K + k], want[i], pr ? ROT_TOL_F : 4 * DR_TOL_D, 1, "apply_many %s %s k %d i %d",
                             sh_precision_name(pr), sh_convention_name(conv), k, i);
            }
            sh_rot_plan_free(p);
        }
}
END_TEST

/* Counts of one rotation (the header's derivation), the limits, and the
 * refusals. */
START_TEST(test_counts_limits)
{
    sh_rotation r;
    sh_rotation_from_euler(0.4, 1.1, -2.3, &r);
    const uint64_t want_set[4] = {0, 0, 0, 0}, want_apply[4] = {0, 0, 9, 57};
    for (int order = 1; order <= 3; order++) {
        sh_rot_plan *p = NULL;
        double c[DR_N] = {0}, g[DR_N];
        ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_DIRECT, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
        ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
        uint64_t ms, ma;
        sh_rot_plan_mults(p, &ms, &ma);
        ck_assert_uint_eq(ms, want_set[order]);
        ck_assert_uint_eq(ma, want_apply[order]);
        sh_rot_plan_free(p);
    }
    sh_rot_method m;
    ck_assert_int_eq(sh_rot_method_parse("direct", &m), SH_OK);
    ck_assert_int_eq(m, SH_ROT_DIRECT);
    ck_assert_str_eq(sh_rot_method_name(SH_ROT_DIRECT), "direct");
    ck_assert_int_eq(sh_rot_method_max_order(SH_ROT_DIRECT), 3);
    ck_assert(sh_rot_method_is_exact(SH_ROT_DIRECT));
    sh_rot_plan *p = NULL;
    ck_assert_int_ne(sh_rot_plan_create(4, SH_ROT_DIRECT, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    ck_assert_ptr_null(p);
    /* a matrix with a NaN is refused, singly and in a batch */
    ck_assert_int_eq(sh_rot_plan_create(3, SH_ROT_DIRECT, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    double bad[9];
    memcpy(bad, r.R, sizeof bad);
    bad[4] = NAN;
    ck_assert_int_ne(sh_rot_plan_set_matrix(p, bad), SH_OK);
    double x[DR_N] = {0}, y[DR_N];
    ck_assert_int_ne(sh_rot_plan_rotate_many(p, 1, bad, x, y), SH_OK);
    sh_rot_plan_free(p);
    /* float, every kernel: an infinite entry in the last of 3 rotations is
     * refused before anything is written (in place: the input survives) */
    for (int kern = SH_KERNEL_SCALAR; kern < SH_KERNEL_N; kern++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)kern)) continue;
        ck_assert_int_eq(sh_rot_plan_create_kernel(3, SH_ROT_DIRECT, SH_PREC_FLOAT, SH_CS, kern, &p), SH_OK);
        float Rf[27], v[27], v0[27], R1[9];
        for (int j = 0; j < 9; j++)
            for (int k = 0; k < 3; k++) Rf[j * 3 + k] = (float)r.R[j];
        Rf[4 * 3 + 2] = INFINITY;
        for (int i = 0; i < 27; i++) v[i] = v0[i] = (float)i;
        ck_assert_int_ne(sh_rot_plan_rotate_many_f(p, 3, Rf, v, v), SH_OK);
        ck_assert(memcmp(v, v0, sizeof v) == 0);
        for (int j = 0; j < 9; j++) R1[j] = (float)r.R[j];
        R1[8] = NAN;
        ck_assert_int_ne(sh_rot_plan_set_matrix_f(p, R1), SH_OK);
        sh_rot_plan_free(p);
    }
    /* the finiteness check of one matrix (rot_finite.h: vector lanes and the
     * last entry alone) sees ±∞ and NaN at every position, in both
     * precisions, for direct and for zxzxz's unrolled path */
    const sh_rot_method ms_[2] = {SH_ROT_DIRECT, SH_ROT_ZXZXZ};
    for (int mi = 0; mi < 2; mi++)
        for (int pr = 0; pr < 2; pr++) {
            ck_assert_int_eq(sh_rot_plan_create(3, ms_[mi], pr, SH_CS, &p), SH_OK);
            const double bads[3] = {INFINITY, -INFINITY, NAN};
            for (int j = 0; j < 9; j++)
                for (int b = 0; b < 3; b++) {
                    double Rd[9];
                    float Rf1[9];
                    memcpy(Rd, r.R, sizeof Rd);
                    Rd[j] = bads[b];
                    for (int i = 0; i < 9; i++) Rf1[i] = (float)Rd[i];
                    if (pr) {
                        ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, Rf1), SH_EINVAL);
                    } else {
                        ck_assert_int_eq(sh_rot_plan_set_matrix(p, Rd), SH_EINVAL);
                    }
                    /* a good matrix after a bad one is accepted */
                    for (int i = 0; i < 9; i++) Rf1[i] = (float)r.R[i];
                    ck_assert_int_eq(pr ? sh_rot_plan_set_matrix_f(p, Rf1) : sh_rot_plan_set_matrix(p, r.R), SH_OK);
                }
            sh_rot_plan_free(p);
        }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rot_direct");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_blocks_vs_reference);
    tcase_add_test(tc, test_apply_vs_reference);
    tcase_add_test(tc, test_pointwise);
    tcase_add_test(tc, test_rotate_many);
    tcase_add_test(tc, test_apply_many);
    tcase_add_test(tc, test_counts_limits);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
