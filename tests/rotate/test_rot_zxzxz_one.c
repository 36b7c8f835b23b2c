/* test_rot_zxzxz_one.c — zxzxz's one-vector kernel in float
 * (src/rotate/zxzxz_one.c: vectorised across the coefficients, orders 3..6,
 * the AVX-512 kernel; the plan uses it for float plans of those orders on
 * that kernel, and the unrolled scalar kernel otherwise).
 *
 * Truths: the MPFR reference band (sh_rot_reference_band, 32 digits, from
 * the Euler angles by the Wigner sum: no code shared with zxzxz), and, for
 * the batches (which still run the unrolled kernels), agreement with them.
 * Rotations: rottest.h's fixed set (random, β = 0, tiny, π/2, near π, π,
 * the gimbal cases), random unit quaternions, and near-gimbal matrices
 * (β = 10^−u, u uniform in [1, 7], and π minus that, α and γ random).
 * The multiplication count is the header's formula (24 for the angles,
 * 2n² per z rotation, J·n² per X product, 6(n−2) for the Chebyshev
 * recurrence and 6 more for its step-2 factor at n ≥ 5; J = 2 at n = 3, 4, 3
 * at n = 5, 6), not read from a run. */
#include "rottest.h"

#define ZO_NQ 300
#define ZO_NG 200 /* near-gimbal cases */
#define ZO_NCASES (ROT_NCASES + ZO_NQ + ZO_NG)
#define ZO_MAXN 36
/* one kernel against the other on vectors with entries in [−1, 1]: each is
 * within a few float ulps per block entry of the truth (test_vs_reference),
 * and a coefficient sums up to 11 such products */
#define ZO_TOL_BATCH 1e-5
/* Against the reference: rottest.h's ROT_TOL_F (32 float ulps of 1) for
 * all but the near-gimbal cases; for those (β within 10⁻¹ … 10⁻⁷ of 0 or
 * π, given as float matrices) 48 ulps: the unrolled kernel of the same
 * method, from the same float matrices, reaches 5.1e-6 (43 ulps) there
 * (printed by test_vs_reference), this kernel 3.9e-6 when written */
#define ZO_TOL_GIMBAL (48.0 * 1.1920929e-07)
#define ZO_MAXB 286 /* sh_rot_block_offset(6) */

static uint64_t zo_mults(int n)
{
    const uint64_t J = n <= 4 ? 2 : 3, nn = (uint64_t)n * n;
    return 24 + 3 * 2 * nn + 2 * J * nn + 6 * (uint64_t)(n - 2) + (n > 4 ? 6 : 0);
}

/* case k: rottest's set and quaternions, then near-gimbal rotations */
static void zo_case(int k, sh_rotation *r, char *name, size_t nn)
{
    if (k < ROT_NCASES + ZO_NQ) {
        rot_case_quat(k, 104729UL, r, name, nn);
        return;
    }
    const double a = (2 * rot_urand() - 1) * M_PI, g = (2 * rot_urand() - 1) * M_PI;
    double b = pow(10.0, -1 - 6 * rot_urand());
    if (k & 1) b = M_PI - b;
    sh_rotation_from_euler(a, b, g, r);
    snprintf(name, nn, "near gimbal (α,β,γ)=(%.17g,%.17g,%.17g)", a, b, g);
}

static int zo_have(void) { return sh_rot_kernel_available(SH_KERNEL_AVX512); }

/* A float zxzxz plan and rotator of order n on the AVX-512 kernel. */
static void zo_plan_rotator(int n, sh_convention conv, sh_rot_plan **p, sh_rotator **rr)
{
    ck_assert_int_eq(sh_rot_plan_create_kernel(n, SH_ROT_ZXZXZ, SH_PREC_FLOAT, conv, SH_KERNEL_AVX512, p), SH_OK);
    const sh_rotator_opts o = {.order = n, .method = SH_ROT_ZXZXZ, .prec = SH_PREC_FLOAT, .conv = conv,
                               .kernel = SH_KERNEL_AVX512};
    ck_assert_int_eq(sh_rotator_create(&o, rr), SH_OK);
}

/* The blocks of the float plan by its one-vector path (apply_f on each unit
 * vector), R given as a float matrix. */
static void zo_blocks_f(sh_rot_plan *p, int n, double *B)
{
    for (int l = 0; l < n; l++) {
        const int w = 2 * l + 1;
        for (int j = 0; j < w; j++) {
            float e[ZO_MAXN] = {0}, c[ZO_MAXN];
            e[l * l + j] = 1;
            ck_assert_int_eq(sh_rot_plan_apply_f(p, e, c), SH_OK);
            for (int i = 0; i < w; i++) B[sh_rot_block_offset(l) + (size_t)i * w + j] = c[l * l + i];
        }
    }
}

/* every order, convention, rotation and way of setting: the blocks against
 * the reference; the plan runs the one-vector kernel (its count) */
START_TEST(test_vs_reference)
{
    if (!zo_have()) return;
    double worst = 0, worst_g = 0, worst_3 = 0, worst_u = 0;
    for (int conv = 0; conv < 2; conv++)
        for (int n = 3; n <= 6; n++) {
            sh_rot_plan *p = NULL, *u = NULL;
            ck_assert_int_eq(sh_rot_plan_create_kernel(n, SH_ROT_ZXZXZ, SH_PREC_FLOAT, conv, SH_KERNEL_AVX512, &p),
                             SH_OK);
            /* the unrolled scalar kernel, for comparison only (printed) */
            ck_assert_int_eq(sh_rot_plan_create_kernel(n, SH_ROT_ZXZXZ, SH_PREC_FLOAT, conv, SH_KERNEL_AVX2, &u),
                             SH_OK);
            for (int k = 0; k < ZO_NCASES; k++) {
                sh_rotation r;
                char name[200];
                double ref[ZO_MAXB], B[ZO_MAXB];
                zo_case(k, &r, name, sizeof name);
                rot_reference_blocks(n, conv, &r, ref);
                float Rf[9];
                for (int i = 0; i < 9; i++) Rf[i] = (float)r.R[i];
                /* how: 0 angles, 1 double matrix, 2 quaternion (one_mat_from_par),
                 * 3 float matrix (the per-rotation path) */
                for (int how = 0; how < 4; how++) {
                    if (how < 3) ck_assert_int_eq(rot_set_how(p, how, &r), SH_OK);
                    else ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, Rf), SH_OK);
                    zo_blocks_f(p, n, B);
                    uint64_t ms, ma;
                    sh_rot_plan_mults(p, &ms, &ma);
                    ck_assert_uint_eq(ma, zo_mults(n));
                    if (how == 3) ck_assert_uint_eq(ms, 0u);
                    const double e = rot_maxdiff(sh_rot_block_offset(n), B, ref);
                    if (!(e <= (k >= ROT_NCASES + ZO_NQ ? ZO_TOL_GIMBAL : ROT_TOL_F)))
                        ck_abort_msg("zxzxz one %s n %d set %d %s: max|B − ref| = %.3g", sh_convention_name(conv), n,
                                     how, name, e);
                    if (k >= ROT_NCASES + ZO_NQ) worst_g = fmax(worst_g, e);
                    else worst = fmax(worst, e);
                    if (how == 3) {
                        double Bu[ZO_MAXB];
                        ck_assert_int_eq(sh_rot_plan_set_matrix_f(u, Rf), SH_OK);
                        zo_blocks_f(u, n, Bu);
                        worst_u = fmax(worst_u, rot_maxdiff(sh_rot_block_offset(n), Bu, ref));
                        worst_3 = fmax(worst_3, e);
                    }
                    /* sh_rot_plan_blocks (the plan's own unit vectors) agrees */
                    if (how == 3 && k < 20) {
                        double B2[ZO_MAXB];
                        ck_assert_int_eq(sh_rot_plan_blocks(p, B2), SH_OK);
                        ck_assert(rot_maxdiff(sh_rot_block_offset(n), B2, B) == 0);
                    }
                }
            }
            sh_rot_plan_free(p);
            sh_rot_plan_free(u);
        }
    fprintf(stderr,
            "zxzxz one-vector kernel vs reference, n 3..6, %d rotations: %.3g (near gimbal %.3g), tol %.3g (%.3g); "
            "from float matrices %.3g, the unrolled kernel from the same %.3g\n",
            ZO_NCASES, worst, worst_g, ROT_TOL_F, ZO_TOL_GIMBAL, worst_3, worst_u);
}
END_TEST

/* the one-vector kernel against the batches (the unrolled SIMD kernels):
 * apply_many_f (one rotation, K vectors: par made from the stored R) and
 * rotate_many_f (K rotations); in place gives the same bits; the rotator's
 * one-shot call gives the same bits as the plan */
START_TEST(test_vs_batches)
{
    if (!zo_have()) return;
    enum { K = 64 };
    double worst = 0;
    for (int conv = 0; conv < 2; conv++)
        for (int n = 3; n <= 6; n++) {
            const int nc = n * n;
            sh_rot_plan *p = NULL;
            sh_rotator *rr = NULL;
            zo_plan_rotator(n, conv, &p, &rr);
            static float Rs[9 * K], xs[ZO_MAXN * K], ys[ZO_MAXN * K], ym[ZO_MAXN * K];
            for (int k = 0; k < ZO_NCASES; k += K) {
                const int nk = ZO_NCASES - k < K ? ZO_NCASES - k : K;
                for (int j = 0; j < nk; j++) {
                    sh_rotation r;
                    char name[200];
                    zo_case(k + j, &r, name, sizeof name);
                    for (int i = 0; i < 9; i++) Rs[i * nk + j] = (float)r.R[i];
                    for (int i = 0; i < nc; i++) xs[i * nk + j] = (float)(2 * rot_urand() - 1);
                }
                ck_assert_int_eq(sh_rot_plan_rotate_many_f(p, (size_t)nk, Rs, xs, ym), SH_OK);
                for (int j = 0; j < nk; j++) {
                    float R[9], x[ZO_MAXN], y[ZO_MAXN], y2[ZO_MAXN], yb[ZO_MAXN * K];
                    for (int i = 0; i < 9; i++) R[i] = Rs[i * nk + j];
                    for (int i = 0; i < nc; i++) x[i] = xs[i * nk + j];
                    ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, R), SH_OK);
                    ck_assert_int_eq(sh_rot_plan_apply_f(p, x, y), SH_OK);
                    for (int i = 0; i < nc; i++) {
                        const double e = fabs((double)y[i] - ym[i * nk + j]);
                        worst = fmax(worst, e);
                        if (!(e <= ZO_TOL_BATCH))
                            ck_abort_msg("zxzxz one vs rotate_many_f %s n %d case %d i %d: %.3g",
                                         sh_convention_name(conv), n, k + j, i, e);
                    }
                    /* apply_many_f: this rotation on all nk vectors of the group */
                    ck_assert_int_eq(sh_rot_plan_apply_many_f(p, (size_t)nk, xs, yb), SH_OK);
                    for (int i = 0; i < nc; i++)
                        ck_assert_msg(fabs((double)y[i] - yb[i * nk + j]) <= ZO_TOL_BATCH,
                                      "zxzxz one vs apply_many_f %s n %d case %d i %d", sh_convention_name(conv), n,
                                      k + j, i);
                    /* the one-vector path once more after the batch: R kept */
                    ck_assert_int_eq(sh_rot_plan_apply_f(p, x, y2), SH_OK);
                    ck_assert(memcmp(y, y2, (size_t)nc * sizeof *y) == 0);
                    /* in place */
                    memcpy(y2, x, (size_t)nc * sizeof *y2);
                    ck_assert_int_eq(sh_rot_plan_apply_f(p, y2, y2), SH_OK);
                    ck_assert_msg(memcmp(y, y2, (size_t)nc * sizeof *y) == 0, "in place differs, n %d", n);
                    /* the rotator's one-shot path */
                    ck_assert_int_eq(sh_rotator_apply_matrix_f(rr, R, x, y2), SH_OK);
                    ck_assert_msg(memcmp(y, y2, (size_t)nc * sizeof *y) == 0, "one-shot differs, n %d", n);
                    (void)ys;
                }
            }
            sh_rotator_free(rr);
            sh_rot_plan_free(p);
        }
    fprintf(stderr, "zxzxz one-vector kernel vs the unrolled batches: max %.3g\n", worst);
}
END_TEST

/* non-finite matrix entries: SH_EINVAL, and nothing written (the plan keeps
 * the previous rotation; the one-shot call leaves out as it was) */
START_TEST(test_nonfinite)
{
    if (!zo_have()) return;
    sh_rotation r;
    sh_rotation_from_euler(0.3, 1.1, -2.0, &r);
    const float bads[3] = {INFINITY, -INFINITY, NAN};
    for (int n = 3; n <= 6; n++) {
        const int nc = n * n;
        sh_rot_plan *p = NULL;
        sh_rotator *rr = NULL;
        zo_plan_rotator(n, SH_CS, &p, &rr);
        float R[9], x[ZO_MAXN], y0[ZO_MAXN], y[ZO_MAXN];
        for (int i = 0; i < 9; i++) R[i] = (float)r.R[i];
        for (int i = 0; i < nc; i++) x[i] = (float)(i + 1) / nc;
        ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, R), SH_OK);
        ck_assert_int_eq(sh_rot_plan_apply_f(p, x, y0), SH_OK);
        for (int j = 0; j < 9; j++)
            for (int b = 0; b < 3; b++) {
                float Rb[9];
                memcpy(Rb, R, sizeof Rb);
                Rb[j] = bads[b];
                ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, Rb), SH_EINVAL);
                ck_assert_int_eq(sh_rot_plan_apply_f(p, x, y), SH_OK);
                ck_assert(memcmp(y, y0, (size_t)nc * sizeof *y) == 0);
                for (int i = 0; i < nc; i++) y[i] = -7;
                ck_assert_int_eq(sh_rotator_apply_matrix_f(rr, Rb, x, y), SH_EINVAL);
                for (int i = 0; i < nc; i++) ck_assert(y[i] == -7);
            }
        sh_rotator_free(rr);
        sh_rot_plan_free(p);
    }
}
END_TEST

/* the kernel is chosen only where it exists: other kernels keep the
 * unrolled count, double plans too */
START_TEST(test_where_used)
{
    sh_rotation r;
    sh_rotation_from_euler(0.3, 1.1, -2.0, &r);
    float R[9], x[64] = {1}, y[64]; /* orders to 8 */
    for (int i = 0; i < 9; i++) R[i] = (float)r.R[i];
    for (int kern = SH_KERNEL_SCALAR; kern < SH_KERNEL_N; kern++) {
        if (!sh_rot_kernel_available((sh_rot_kernel)kern)) continue;
        for (int n = 1; n <= 8; n++) {
            sh_rot_plan *p = NULL;
            ck_assert_int_eq(sh_rot_plan_create_kernel(n, SH_ROT_ZXZXZ, SH_PREC_FLOAT, SH_CS, kern, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set_matrix_f(p, R), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply_f(p, x, y), SH_OK);
            uint64_t ms, ma;
            sh_rot_plan_mults(p, &ms, &ma);
            const int one = sh_rot_plan_kernel(p) == SH_KERNEL_AVX512 && n >= 3 && n <= 6;
            if (one) ck_assert_uint_eq(ma, zo_mults(n));
            else ck_assert_uint_ne(ma, n >= 2 ? zo_mults(n) : 1u);
            sh_rot_plan_free(p);
        }
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rot_zxzxz_one");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_vs_reference);
    tcase_add_test(tc, test_vs_batches);
    tcase_add_test(tc, test_nonfinite);
    tcase_add_test(tc, test_where_used);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
