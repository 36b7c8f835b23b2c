/* test_rot_zh.c — the `zh` method (src/rotate/rot_zh.c): zonal-harmonic
 * factorisation, orders 1..6.
 *
 * Truths: the MPFR reference band (sh_rot_reference_band, 32 digits, from
 * the Euler angles by the Wigner sum: no code shared with zh), the
 * pointwise identity Σ g_i y_i(s) = Σ c_i y_i(Rᵀs) with sh_eval_dir (libm
 * trigonometry, not zh's Cartesian recurrences), the homomorphism
 * R_sh(AB) = R_sh(A)R_sh(B), and the method's single-rotation path for the
 * batch.  Rotations: rottest.h's set (random, β = 0, tiny, π/2, near π, π,
 * the gimbal cases α + γ = 0) and 200 random unit quaternions.
 * Condition numbers of Y_l[i][m] = y_lm(d_i) at zh's directions: GSL's
 * SVD of the matrix built with sh_eval_dir.
 * Tolerances: double 2e-14 on the blocks.  The error estimate of
 * rot_zh.c's header is cond₂(Y_l)·(2l+1)·ε: at band 5, 3.88·11·2.2e-16 =
 * 9.5e-15, and the worst measured here is 8.6e-15 (band 5; per band about
 * 4, 8, 18, 27, 39 ε for l = 1..5, growing as the estimate does), so 1e-14
 * would sit at the estimate itself: 2e-14 is twice it.  Paths that round
 * differently (matrix or quaternion against angles, rotate_many in nocs
 * against the plan's cs kernel with flipped vectors) differ by up to the
 * same amount.  Float 2e-6 (entries ≤ 1: ≈ 17 float ulps, below rottest.h's
 * ROT_TOL_F = 32 ulps; measured 1.5e-6).  The multiplication counts are
 * those derived in the header. */
#include "rottest.h"

#include <gsl/gsl_linalg.h>

#define ZH_NQ_ 200
#define ZH_NCASES (ROT_NCASES + ZH_NQ_)
#define ZH_MAXO 6
#define ZH_N 36   /* coefficients of order 6 */
#define ZH_NB 286 /* sh_rot_block_offset(6) */
#define ZH_TOL_D 2e-14
#define ZH_TOL_F 2e-6
#define ZH_COND_MAX 5.0 /* rot_zh.c: 1, 4.415, 3.251, 2.943, 4.309, 3.878 */

const double (*sh__rot_zh_directions(void))[3];
void sh__rot_zh_basis(int L, const double *e, long double *y);

/* The condition numbers of Y_l at zh's directions (sh_eval_dir, GSL SVD,
 * nocs and cs: the same), and zh's own long-double basis against
 * sh_eval_dir. */
START_TEST(test_condition)
{
    const double(*d)[3] = sh__rot_zh_directions();
    double y[11][ZH_N];
    for (int i = 0; i < 11; i++) {
        const double n = sqrt(d[i][0] * d[i][0] + d[i][1] * d[i][1] + d[i][2] * d[i][2]);
        ck_assert_msg(fabs(n - 1) < 4e-16, "direction %d: norm − 1 = %.3g", i, n - 1);
        long double yl[ZH_N];
        sh__rot_zh_basis(5, d[i], yl);
        for (int conv = 0; conv < 2; conv++) {
            ck_assert_int_eq(sh_eval_dir(ZH_MAXO, conv, d[i], y[i]), SH_OK);
            for (int j = 0; j < ZH_N; j++) {
                int m = j - (int)floor(sqrt(j)) * ((int)floor(sqrt(j)) + 1);
                const double want = conv == SH_NOCS || !(abs(m) & 1) ? (double)yl[j] : -(double)yl[j];
                ck_close(y[i][j], want, 4e-15, 1, "zh basis vs sh_eval_dir, direction %d index %d", i, j);
            }
        }
    }
    fprintf(stderr, "zh: cond2(Y_l), l = 0..5:");
    for (int l = 0; l < ZH_MAXO; l++) {
        const int w = 2 * l + 1;
        gsl_matrix *A = gsl_matrix_alloc(w, w), *V = gsl_matrix_alloc(w, w);
        gsl_vector *S = gsl_vector_alloc(w);
        for (int i = 0; i < w; i++)
            for (int m = 0; m < w; m++) gsl_matrix_set(A, i, m, y[i][l * l + m]);
        gsl_linalg_SV_decomp_jacobi(A, V, S);
        const double c = gsl_vector_get(S, 0) / gsl_vector_get(S, w - 1);
        fprintf(stderr, " %.4g", c);
        ck_assert_msg(c >= 1 && c <= ZH_COND_MAX, "band %d: cond %.4g > %.1f", l, c, ZH_COND_MAX);
        gsl_matrix_free(A), gsl_matrix_free(V), gsl_vector_free(S);
    }
    fprintf(stderr, "\n");
}
END_TEST

/* Blocks, orders 1..6, both conventions and precisions, every rotation,
 * set from angles, matrix and quaternion: against the reference, and the
 * three ways against each other. */
START_TEST(test_blocks_vs_reference)
{
    double worst[2] = {0, 0}, ways[2] = {0, 0};
    sh_rot_plan *p[2][2][ZH_MAXO + 1];
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++)
            for (int order = 1; order <= ZH_MAXO; order++)
                ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_ZH, pr, conv, &p[conv][pr][order]), SH_OK);
    for (int conv = 0; conv < 2; conv++)
        for (int k = 0; k < ZH_NCASES; k++) {
            sh_rotation r;
            char name[160];
            double ref[ZH_NB], B[3][ZH_NB];
            rot_case_quat(k, 104729UL, &r, name, sizeof name);
            rot_reference_blocks(ZH_MAXO, conv, &r, ref);
            for (int pr = 0; pr < 2; pr++)
                for (int order = 1; order <= ZH_MAXO; order++) {
                    const size_t nb = sh_rot_block_offset(order);
                    for (int how = 0; how < 3; how++) {
                        ck_assert_int_eq(rot_set_how(p[conv][pr][order], how, &r), SH_OK);
                        ck_assert_int_eq(sh_rot_plan_blocks(p[conv][pr][order], B[how]), SH_OK);
                        const double e = rot_maxdiff(nb, B[how], ref);
                        if (!(e <= (pr ? ZH_TOL_F : ZH_TOL_D)))
                            ck_abort_msg("zh %s %s order %d set %d %s: max|B − ref| = %.3g", sh_precision_name(pr),
                                         sh_convention_name(conv), order, how, name, e);
                        worst[pr] = fmax(worst[pr], e);
                        if (how) ways[pr] = fmax(ways[pr], rot_maxdiff(nb, B[how], B[0]));
                    }
                }
        }
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++)
            for (int order = 1; order <= ZH_MAXO; order++) sh_rot_plan_free(p[conv][pr][order]);
    fprintf(stderr,
            "zh vs reference, orders 1..6, %d rotations x 3 ways, cs+nocs: double %.3g float %.3g; "
            "matrix/quaternion vs angles: double %.3g float %.3g\n",
            ZH_NCASES, worst[0], worst[1], ways[0], ways[1]);
    ck_assert(ways[0] <= ZH_TOL_D && ways[1] <= ZH_TOL_F);
}
END_TEST

/* R_sh(AB) = R_sh(A) R_sh(B), band by band, double, both conventions. */
START_TEST(test_homomorphism)
{
    double worst = 0;
    for (int conv = 0; conv < 2; conv++) {
        sh_rot_plan *p = NULL;
        ck_assert_int_eq(sh_rot_plan_create(ZH_MAXO, SH_ROT_ZH, SH_PREC_DOUBLE, conv, &p), SH_OK);
        for (int k = 0; k + 1 < ZH_NCASES; k += 2) {
            sh_rotation a, b, ab;
            char name[160];
            double A[ZH_NB], Bb[ZH_NB], C[ZH_NB];
            rot_case_quat(k, 104729UL, &a, name, sizeof name);
            rot_case_quat(k + 1, 104729UL, &b, name, sizeof name);
            sh_rotation_compose(&a, &b, &ab);
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, a.R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_blocks(p, A), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, b.R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_blocks(p, Bb), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, ab.R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_blocks(p, C), SH_OK);
            for (int l = 0; l < ZH_MAXO; l++) {
                const int w = 2 * l + 1;
                const size_t o = sh_rot_block_offset(l);
                for (int i = 0; i < w; i++)
                    for (int j = 0; j < w; j++) {
                        double s = 0;
                        for (int t = 0; t < w; t++) s += A[o + (size_t)i * w + t] * Bb[o + (size_t)t * w + j];
                        worst = fmax(worst, fabs(s - C[o + (size_t)i * w + j]));
                    }
            }
        }
        sh_rot_plan_free(p);
    }
    fprintf(stderr, "zh: max|R(AB) − R(A)R(B)| = %.3g (orders ≤ 6, %d pairs, cs+nocs)\n", worst, ZH_NCASES / 2);
    ck_assert(worst <= 2 * ZH_TOL_D);
}
END_TEST

/* apply (double and float API, every way of setting) == reference × c;
 * in place gives the same bits. */
START_TEST(test_apply_vs_reference)
{
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++)
            for (int order = 1; order <= ZH_MAXO; order++) {
                const int n = order * order;
                sh_rot_plan *p = NULL;
                ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_ZH, pr, conv, &p), SH_OK);
                const double tol = pr ? ROT_TOL_F : 4 * ZH_TOL_D;
                for (int k = 0; k < ZH_NCASES; k += 5) {
                    sh_rotation r;
                    char name[160];
                    double ref[ZH_NB], c[ZH_N], want[ZH_N], g[ZH_N], h[ZH_N];
                    rot_case_quat(k, 104729UL, &r, name, sizeof name);
                    rot_reference_blocks(ZH_MAXO, conv, &r, ref);
                    for (int i = 0; i < n; i++) c[i] = 2 * rot_urand() - 1;
                    rot_blocks_mul(order, ref, c, want);
                    for (int how = 0; how < 4; how++) {
                        if (how == 3) {
                            if (!pr) continue;
                            float Rf[9], cf[ZH_N], gf[ZH_N];
                            for (int i = 0; i < 9; i++) Rf[i] = (float)r.R[i];
                            for (int i = 0; i < n; i++) cf[i] = (float)c[i];
                            ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, Rf), SH_OK);
                            ck_assert_int_eq(sh_rot_plan_apply_f(p, cf, gf), SH_OK);
                            for (int i = 0; i < n; i++) g[i] = gf[i];
                        } else {
                            ck_assert_int_eq(rot_set_how(p, how, &r), SH_OK);
                            ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
                            memcpy(h, c, sizeof h);
                            ck_assert_int_eq(sh_rot_plan_apply(p, h, h), SH_OK);
                            ck_assert_msg(memcmp(g, h, (size_t)n * sizeof *g) == 0, "in-place apply differs (%s)", name);
                        }
                        const double e = rot_maxdiff((size_t)n, g, want);
                        if (!(e <= tol))
                            ck_abort_msg("zh %s %s order %d set %d %s: max|apply − ref·c| = %.3g", sh_precision_name(pr),
                                         sh_convention_name(conv), order, how, name, e);
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
        ck_assert_int_eq(sh_rot_plan_create(ZH_MAXO, SH_ROT_ZH, SH_PREC_DOUBLE, conv, &p), SH_OK);
        for (int k = 0; k < ZH_NCASES; k += 7) {
            sh_rotation r;
            char name[160];
            double c[ZH_N], g[ZH_N];
            rot_case_quat(k, 104729UL, &r, name, sizeof name);
            for (int i = 0; i < ZH_N; i++) c[i] = 2 * rot_urand() - 1;
            ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
            for (int t = 0; t < 6; t++) {
                const double s[3] = {rot_urand() - 0.5, rot_urand() - 0.5, rot_urand() - 0.5};
                double ri[3], ys[ZH_N], yr[ZH_N], f = 0, gg = 0;
                for (int i = 0; i < 3; i++) ri[i] = r.R[i] * s[0] + r.R[3 + i] * s[1] + r.R[6 + i] * s[2];
                ck_assert_int_eq(sh_eval_dir(ZH_MAXO, conv, s, ys), SH_OK);
                ck_assert_int_eq(sh_eval_dir(ZH_MAXO, conv, ri, yr), SH_OK);
                for (int i = 0; i < ZH_N; i++) f += c[i] * yr[i], gg += g[i] * ys[i];
                ck_close(gg, f, 256 * DBL_EPSILON, 1, "zh %s %s point %d", sh_convention_name(conv), name, t);
            }
        }
        sh_rot_plan_free(p);
    }
}
END_TEST

/* rotate_many (K rotations of K vectors) == K single rotations and == the
 * reference; in place; every order, convention, precision and kernel;
 * rotate_many_quat in double. */
static void zh_check_many(int order, sh_convention conv, sh_precision pr, sh_rot_kernel kern, const double *refs)
{
    const size_t K = ZH_NCASES, n = (size_t)order * order;
    double *R = malloc(9 * K * sizeof *R), *q = malloc(4 * K * sizeof *q);
    double *x = malloc(n * K * sizeof *x), *y = malloc(n * K * sizeof *y), *yq = malloc(n * K * sizeof *yq);
    float *Rf = malloc(9 * K * sizeof *Rf), *xf = malloc(n * K * sizeof *xf), *yf = malloc(n * K * sizeof *yf);
    sh_rotation *rs = malloc(K * sizeof *rs);
    ck_assert(R && q && x && y && yq && Rf && xf && yf && rs);
    for (size_t k = 0; k < K; k++) {
        char name[160];
        double qk[4];
        rot_case_quat((int)k, 104729UL, &rs[k], name, sizeof name);
        sh_rotation_to_quat(&rs[k], qk);
        for (int j = 0; j < 9; j++) Rf[j * K + k] = (float)(R[j * K + k] = rs[k].R[j]);
        for (int j = 0; j < 4; j++) q[j * K + k] = qk[j];
        for (size_t i = 0; i < n; i++) xf[i * K + k] = (float)(x[i * K + k] = 2 * rot_urand() - 1);
    }
    sh_rot_plan *p = NULL, *one = NULL;
    ck_assert_int_eq(sh_rot_plan_create_kernel(order, SH_ROT_ZH, pr, conv, kern, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_kernel(p), kern);
    ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_ZH, pr, conv, &one), SH_OK);
    if (pr) {
        ck_assert_int_eq(sh_rot_plan_rotate_many_f(p, K, Rf, xf, yf), SH_OK);
        for (size_t i = 0; i < n * K; i++) y[i] = yf[i];
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
    static const uint64_t want_set[7] = {0, 0, 27, 75, 161, 297, 495}, want_apply[7] = {0, 0, 21, 81, 200, 398, 695};
    uint64_t ms, ma;
    ck_assert_int_eq(pr ? sh_rot_plan_rotate_many_f(p, K, Rf, xf, yf) : sh_rot_plan_rotate_many(p, K, R, x, y), SH_OK);
    sh_rot_plan_mults(p, &ms, &ma);
    ck_assert_uint_eq(ms, want_set[order]);
    ck_assert_uint_eq(ma, want_apply[order]);
    const double tol_one = pr ? 2 * ROT_TOL_F : ZH_TOL_D, /* two paths, each within tol_ref */ tol_ref = pr ? ROT_TOL_F : 4 * ZH_TOL_D;
    for (size_t k = 0; k < K; k++) {
        double xk[ZH_N], yk[ZH_N], want[ZH_N];
        for (size_t i = 0; i < n; i++) xk[i] = x[i * K + k];
        if (pr) {
            float Rk[9], xk_f[ZH_N], yk_f[ZH_N];
            for (int j = 0; j < 9; j++) Rk[j] = Rf[j * K + k];
            for (size_t i = 0; i < n; i++) xk_f[i] = xf[i * K + k];
            ck_assert_int_eq(sh_rot_plan_set_matrix_f(one, Rk), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply_f(one, xk_f, yk_f), SH_OK);
            for (size_t i = 0; i < n; i++) yk[i] = yk_f[i];
        } else {
            ck_assert_int_eq(sh_rot_plan_set_matrix(one, rs[k].R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(one, xk, yk), SH_OK);
        }
        rot_blocks_mul(order, refs + k * ZH_NB, xk, want);
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
    double *refs = malloc((size_t)2 * ZH_NCASES * ZH_NB * sizeof *refs);
    ck_assert(refs);
    for (int conv = 0; conv < 2; conv++)
        for (int k = 0; k < ZH_NCASES; k++) {
            sh_rotation r;
            char name[160];
            rot_case_quat(k, 104729UL, &r, name, sizeof name);
            rot_reference_blocks(ZH_MAXO, conv, &r, refs + ((size_t)conv * ZH_NCASES + k) * ZH_NB);
        }
    for (int kern = SH_KERNEL_SCALAR; kern < SH_KERNEL_N; kern++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)kern)) continue;
        for (int order = 1; order <= ZH_MAXO; order++)
            for (int conv = 0; conv < 2; conv++)
                for (int pr = 0; pr < 2; pr++)
                    zh_check_many(order, conv, pr, (sh_rot_kernel)kern, refs + (size_t)conv * ZH_NCASES * ZH_NB);
    }
    free(refs);
}
END_TEST

/* apply_many (one rotation, K vectors) == reference × each vector. */
START_TEST(test_apply_many)
{
    enum { K = 13 };
    sh_rotation r;
    char name[160];
    rot_case_quat(3, 104729UL, &r, name, sizeof name);
    for (int conv = 0; conv < 2; conv++)
        for (int pr = 0; pr < 2; pr++) {
            double ref[ZH_NB], x[ZH_N * K], y[ZH_N * K], xk[ZH_N], want[ZH_N];
            float xf[ZH_N * K], yf[ZH_N * K];
            rot_reference_blocks(ZH_MAXO, conv, &r, ref);
            for (int i = 0; i < ZH_N * K; i++) xf[i] = (float)(x[i] = 2 * rot_urand() - 1);
            sh_rot_plan *p = NULL;
            ck_assert_int_eq(sh_rot_plan_create(ZH_MAXO, SH_ROT_ZH, pr, conv, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            if (pr) {
                ck_assert_int_eq(sh_rot_plan_apply_many_f(p, K, xf, yf), SH_OK);
                for (int i = 0; i < ZH_N * K; i++) y[i] = yf[i], x[i] = xf[i];
            } else {
                ck_assert_int_eq(sh_rot_plan_apply_many(p, K, x, y), SH_OK);
            }
            for (int k = 0; k < K; k++) {
                for (int i = 0; i < ZH_N; i++) xk[i] = x[i * K + k];
                rot_blocks_mul(ZH_MAXO, ref, xk, want);
                for (int i = 0; i < ZH_N; i++)
                    ck_close(y[i * K + k], want[i], pr ? ROT_TOL_F : 4 * ZH_TOL_D, 1, "apply_many %s %s k %d i %d",
                             sh_precision_name(pr), sh_convention_name(conv), k, i);
            }
            sh_rot_plan_free(p);
        }
}
END_TEST

/* Counts of one rotation (the header's derivation), the limits, refusals. */
START_TEST(test_counts_limits)
{
    sh_rotation r;
    sh_rotation_from_euler(0.4, 1.1, -2.3, &r);
    static const uint64_t want_set[7] = {0, 0, 27, 75, 161, 297, 495}, want_apply[7] = {0, 0, 21, 81, 200, 398, 695};
    for (int order = 1; order <= ZH_MAXO; order++) {
        sh_rot_plan *p = NULL;
        double c[ZH_N] = {0}, g[ZH_N];
        ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_ZH, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set_matrix(p, r.R), SH_OK);
        ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
        uint64_t ms, ma;
        sh_rot_plan_mults(p, &ms, &ma);
        ck_assert_uint_eq(ms, want_set[order]);
        ck_assert_uint_eq(ma, want_apply[order]);
        sh_rot_plan_free(p);
    }
    sh_rot_method m;
    ck_assert_int_eq(sh_rot_method_parse("zh", &m), SH_OK);
    ck_assert_int_eq(m, SH_ROT_ZH);
    ck_assert_str_eq(sh_rot_method_name(SH_ROT_ZH), "zh");
    ck_assert_int_eq(sh_rot_method_max_order(SH_ROT_ZH), 6);
    ck_assert(sh_rot_method_is_exact(SH_ROT_ZH));
    sh_rot_plan *p = NULL;
    ck_assert_int_ne(sh_rot_plan_create(7, SH_ROT_ZH, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    ck_assert_ptr_null(p);
    ck_assert_int_eq(sh_rot_plan_create(6, SH_ROT_ZH, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
    double bad[9];
    memcpy(bad, r.R, sizeof bad);
    bad[4] = NAN;
    ck_assert_int_ne(sh_rot_plan_set_matrix(p, bad), SH_OK);
    double x[ZH_N] = {0}, y[ZH_N];
    ck_assert_int_ne(sh_rot_plan_rotate_many(p, 1, bad, x, y), SH_OK);
    sh_rot_plan_free(p);
    for (int kern = SH_KERNEL_SCALAR; kern < SH_KERNEL_N; kern++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)kern)) continue;
        ck_assert_int_eq(sh_rot_plan_create_kernel(6, SH_ROT_ZH, SH_PREC_FLOAT, SH_CS, kern, &p), SH_OK);
        float Rf[27], v[3 * ZH_N], v0[3 * ZH_N], R1[9];
        for (int j = 0; j < 9; j++)
            for (int k = 0; k < 3; k++) Rf[j * 3 + k] = (float)r.R[j];
        Rf[4 * 3 + 2] = INFINITY;
        for (int i = 0; i < 3 * ZH_N; i++) v[i] = v0[i] = (float)i;
        ck_assert_int_ne(sh_rot_plan_rotate_many_f(p, 3, Rf, v, v), SH_OK);
        ck_assert(memcmp(v, v0, sizeof v) == 0);
        for (int j = 0; j < 9; j++) R1[j] = (float)r.R[j];
        R1[8] = NAN;
        ck_assert_int_ne(sh_rot_plan_set_matrix_f(p, R1), SH_OK);
        sh_rot_plan_free(p);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rot_zh");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_condition);
    tcase_add_test(tc, test_blocks_vs_reference);
    tcase_add_test(tc, test_homomorphism);
    tcase_add_test(tc, test_apply_vs_reference);
    tcase_add_test(tc, test_pointwise);
    tcase_add_test(tc, test_rotate_many);
    tcase_add_test(tc, test_apply_many);
    tcase_add_test(tc, test_counts_limits);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
