/* rottest.h — shared checks for the SH rotation methods (tests/test_rot_*.c).
 *
 * Truths: the MPFR reference band (sh_rot_reference_band, ≥ 30 digits), the
 * pointwise identity Σ g_i y_i(s) = Σ c_i y_i(R⁻¹s) for g = R_sh c (evaluated
 * with sh_eval_dir, which shares no code with any rotation method),
 * orthogonality of each band block, and the homomorphism R(a)R(b) = R(ab).
 * Nothing here is a number copied from shlab's own output. */
#ifndef SHLAB_ROTTEST_H
#define SHLAB_ROTTEST_H

#include "testutil.h"

#include <stdint.h>
#include <string.h>

/* Double agreement required of every exact method; float: 32 float ulps of 1 (every
 * entry of a rotation block is ≤ 1 in magnitude, so absolute is right). */
#define ROT_TOL_D 1e-13
#define ROT_TOL_F (32.0 * 1.1920929e-07)
#define ROT_MAXO 10

static unsigned long rot_rng = 20240611UL;
static double rot_urand(void)
{
    rot_rng = rot_rng * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(rot_rng >> 11) / 9007199254740992.0;
}

/* The fixed test set: seeded random rotations, then the extremes of β and
 * the gimbal cases. */
#define ROT_NRAND 6
#define ROT_NCASES (ROT_NRAND + 10)
static void rot_case(int k, sh_rotation *r, char *name, size_t nn)
{
    double a, b, g;
    if (k < ROT_NRAND) {
        unsigned long save = rot_rng;
        rot_rng = 1000003UL * (unsigned long)(k + 1);
        a = (2 * rot_urand() - 1) * M_PI;
        b = rot_urand() * M_PI;
        g = (2 * rot_urand() - 1) * M_PI;
        rot_rng = save;
    } else {
        static const double ex[10][3] = {
            {0.3, 0.0, -1.2},      /* β = 0 */
            {2.1, 1e-12, 0.4},     /* β tiny */
            {-0.8, M_PI / 2, 2.9}, /* β = π/2 */
            {1.3, M_PI - 1e-9, -2.2},
            {-2.6, M_PI, 0.5},     /* β = π */
            {0.0, 0.0, 0.0},       /* identity: α = γ = 0, β = 0 */
            {0.0, M_PI, 0.0},      /* α = γ = 0, β = π */
            {0.9, 1e-12, -0.9},    /* α + γ = 0, tiny β */
            {-1.7, 1e-9, 1.7},     /* α + γ = 0, small β */
            {M_PI, M_PI - 1e-12, M_PI},
        };
        a = ex[k - ROT_NRAND][0];
        b = ex[k - ROT_NRAND][1];
        g = ex[k - ROT_NRAND][2];
    }
    sh_rotation_from_euler(a, b, g, r);
    snprintf(name, nn, "(α,β,γ)=(%.17g,%.17g,%.17g)", a, b, g);
}

/* Case k of a method test: the fixed set above, then random unit
 * quaternions (uniform in the ball, normalised by sh_rotation_from_quat),
 * seeded by `seed` and k. */
static inline void rot_case_quat(int k, unsigned long seed, sh_rotation *r, char *name, size_t nn)
{
    if (k < ROT_NCASES) {
        rot_case(k, r, name, nn);
        return;
    }
    unsigned long save = rot_rng;
    rot_rng = seed * (unsigned long)(k + 1);
    double q[4], n2;
    do {
        n2 = 0;
        for (int i = 0; i < 4; i++) q[i] = 2 * rot_urand() - 1, n2 += q[i] * q[i];
    } while (n2 < 0.01 || n2 > 1);
    rot_rng = save;
    ck_assert_int_eq(sh_rotation_from_quat(q, 1, r), SH_OK);
    snprintf(name, nn, "quaternion %d (β=%.3g)", k - ROT_NCASES, r->beta);
}

/* The MPFR reference blocks of bands 0..order−1 (32 digits; the layout of
 * sh_rot_block_offset). */
static inline void rot_reference_blocks(int order, sh_convention conv, const sh_rotation *r, double *B)
{
    for (int l = 0; l < order; l++)
        ck_assert_int_eq(sh_rot_reference_band(l, conv, r, 32, B + sh_rot_block_offset(l), NULL), SH_OK);
}

/* y = B x for bands 0..order−1 (the product done here, not by the plan). */
static inline void rot_blocks_mul(int order, const double *B, const double *x, double *y)
{
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        for (int a = 0; a < w; a++) {
            double s = 0;
            for (int b = 0; b < w; b++) s += B[sh_rot_block_offset(l) + (size_t)a * w + b] * x[l * l + b];
            y[l * l + a] = s;
        }
    }
}

/* max |a_i − b_i|; a non-finite a_i is INFINITY. */
static inline double rot_maxdiff(size_t n, const double *a, const double *b)
{
    double e = 0;
    for (size_t i = 0; i < n; i++) e = isfinite(a[i]) ? fmax(e, fabs(a[i] - b[i])) : INFINITY;
    return e;
}

/* The three ways to set a rotation: 0 angles (sh_rotation), 1 matrix, 2 quaternion. */
static inline int rot_set_how(sh_rot_plan *p, int how, const sh_rotation *r)
{
    double q[4];
    switch (how) {
    case 0: return sh_rot_plan_set(p, r);
    case 1: return sh_rot_plan_set_matrix(p, r->R);
    default: sh_rotation_to_quat(r, q); return sh_rot_plan_set_quat(p, q);
    }
}

/* Max |plan blocks − reference| over bands 0..order−1. */
static double rot_err_vs_reference(sh_rot_method method, sh_precision prec, sh_convention conv,
                                   int order, const sh_rotation *r)
{
    sh_rot_plan *p = NULL;
    ck_assert_int_eq(sh_rot_plan_create(order, method, prec, conv, &p), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(p, r), SH_OK);
    double *B = malloc(sh_rot_block_offset(order) * sizeof *B);
    double *ref = malloc((size_t)(2 * order) * (2 * order) * sizeof *ref);
    ck_assert_int_eq(sh_rot_plan_blocks(p, B), SH_OK);
    double e = 0;
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        ck_assert_int_eq(sh_rot_reference_band(l, conv, r, 32, ref, NULL), SH_OK);
        for (int i = 0; i < w * w; i++) e = fmax(e, fabs(B[sh_rot_block_offset(l) + i] - ref[i]));
        if (!isfinite(B[sh_rot_block_offset(l)])) e = INFINITY;
    }
    free(B);
    free(ref);
    sh_rot_plan_free(p);
    return e;
}

/* Every order 1..ROT_MAXO, every case, both conventions, both precisions. */
static inline void rot_check_reference_all(sh_rot_method method, double *maxd, double *maxf)
{
    *maxd = *maxf = 0;
    for (int k = 0; k < ROT_NCASES; k++) {
        sh_rotation r;
        char name[160];
        rot_case(k, &r, name, sizeof name);
        for (int conv = 0; conv < 2; conv++)
            for (int order = 1; order <= ROT_MAXO; order++) {
                const double ed = rot_err_vs_reference(method, SH_PREC_DOUBLE, conv, order, &r);
                const double ef = rot_err_vs_reference(method, SH_PREC_FLOAT, conv, order, &r);
                if (!(ed <= ROT_TOL_D))
                    ck_abort_msg("%s double %s order %d conv %d: err %.3g", sh_rot_method_name(method),
                                 name, order, conv, ed);
                if (!(ef <= ROT_TOL_F))
                    ck_abort_msg("%s float %s order %d conv %d: err %.3g", sh_rot_method_name(method),
                                 name, order, conv, ef);
                *maxd = fmax(*maxd, ed);
                *maxf = fmax(*maxf, ef);
            }
    }
}

/* apply == blocks × vector (the product done here), both conventions. */
static inline void rot_check_apply(sh_rot_method method, sh_precision prec, double tol)
{
    const int order = ROT_MAXO, n = order * order;
    double c[ROT_MAXO * ROT_MAXO], g[ROT_MAXO * ROT_MAXO], h[ROT_MAXO * ROT_MAXO];
    double *B = malloc(sh_rot_block_offset(order) * sizeof *B);
    for (int k = 0; k < ROT_NCASES; k++) {
        sh_rotation r;
        char name[160];
        rot_case(k, &r, name, sizeof name);
        for (int conv = 0; conv < 2; conv++) {
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create(order, method, prec, conv, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            ck_assert_int_eq(sh_rot_plan_blocks(p, B), SH_OK);
            for (int i = 0; i < n; i++) c[i] = 2 * rot_urand() - 1;
            ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
            rot_blocks_mul(order, B, c, h);
            for (int i = 0; i < n; i++)
                ck_close(g[i], h[i], tol, 1.0, "%s apply vs blocks %s conv %d i %d",
                         sh_rot_method_name(method), name, conv, i);
            /* in place gives the same */
            memcpy(h, c, sizeof h);
            ck_assert_int_eq(sh_rot_plan_apply(p, h, h), SH_OK);
            for (int i = 0; i < n; i++) ck_close(h[i], g[i], 0.0, 1.0, "in-place apply i %d", i);
            sh_rot_plan_free(p);
        }
    }
    free(B);
}

/* Pointwise: Σ g_i y_i(s) = Σ c_i y_i(R⁻¹ s). */
static inline void rot_check_pointwise(sh_rot_method method)
{
    const int order = ROT_MAXO, n = order * order;
    double c[ROT_MAXO * ROT_MAXO], g[ROT_MAXO * ROT_MAXO], y[ROT_MAXO * ROT_MAXO];
    for (int k = 0; k < ROT_NCASES; k++) {
        sh_rotation r;
        char name[160];
        rot_case(k, &r, name, sizeof name);
        for (int conv = 0; conv < 2; conv++) {
            sh_rot_plan *p;
            ck_assert_int_eq(sh_rot_plan_create(order, method, SH_PREC_DOUBLE, conv, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
            for (int i = 0; i < n; i++) c[i] = 2 * rot_urand() - 1;
            ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
            for (int t = 0; t < 8; t++) {
                double s[3] = {2 * rot_urand() - 1, 2 * rot_urand() - 1, 2 * rot_urand() - 1}, q[3];
                for (int i = 0; i < 3; i++) /* q = R⁻¹ s = Rᵀ s */
                    q[i] = r.R[0 * 3 + i] * s[0] + r.R[1 * 3 + i] * s[1] + r.R[2 * 3 + i] * s[2];
                double fg = 0, fc = 0;
                ck_assert_int_eq(sh_eval_dir(order, conv, s, y), SH_OK);
                for (int i = 0; i < n; i++) fg += g[i] * y[i];
                ck_assert_int_eq(sh_eval_dir(order, conv, q, y), SH_OK);
                for (int i = 0; i < n; i++) fc += c[i] * y[i];
                ck_close(fg, fc, 1e-12, 1.0, "%s pointwise %s conv %d", sh_rot_method_name(method), name, conv);
            }
            sh_rot_plan_free(p);
        }
    }
}

/* max |B Bᵀ − I| over the bands of one block set. */
static double rot_orth_err(int order, const double *B)
{
    double e = 0;
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        const double *M = B + sh_rot_block_offset(l);
        for (int a = 0; a < w; a++)
            for (int b = 0; b < w; b++) {
                double s = 0;
                for (int k = 0; k < w; k++) s += M[(size_t)a * w + k] * M[(size_t)b * w + k];
                e = fmax(e, fabs(s - (a == b)));
            }
    }
    return e;
}

/* Orthogonality at order 10 and the homomorphism R(a)R(b) = R(ab). */
static inline void rot_check_orth_homomorphism(sh_rot_method method)
{
    const int order = ROT_MAXO;
    const size_t nb = sh_rot_block_offset(order);
    double *A = malloc(nb * sizeof *A), *Bm = malloc(nb * sizeof *Bm), *C = malloc(nb * sizeof *C);
    for (int k = 0; k < ROT_NCASES; k++) {
        sh_rotation ra, rb, rc;
        char name[160], nb2[160];
        rot_case(k, &ra, name, sizeof name);
        rot_case((k + 3) % ROT_NCASES, &rb, nb2, sizeof nb2);
        sh_rotation_compose(&ra, &rb, &rc);
        sh_rot_plan *p;
        ck_assert_int_eq(sh_rot_plan_create(order, method, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &ra), SH_OK);
        ck_assert_int_eq(sh_rot_plan_blocks(p, A), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &rb), SH_OK);
        ck_assert_int_eq(sh_rot_plan_blocks(p, Bm), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &rc), SH_OK);
        ck_assert_int_eq(sh_rot_plan_blocks(p, C), SH_OK);
        const double eo = rot_orth_err(order, A);
        if (!(eo <= 1e-14)) ck_abort_msg("%s orthogonality %s: %.3g", sh_rot_method_name(method), name, eo);
        double eh = 0;
        for (int l = 0; l < order; l++) {
            const int w = 2 * l + 1;
            const size_t o = sh_rot_block_offset(l);
            for (int a = 0; a < w; a++)
                for (int b = 0; b < w; b++) {
                    double s = 0;
                    for (int t = 0; t < w; t++) s += A[o + (size_t)a * w + t] * Bm[o + (size_t)t * w + b];
                    eh = fmax(eh, fabs(s - C[o + (size_t)a * w + b]));
                }
        }
        if (!(eh <= 1e-13))
            ck_abort_msg("%s homomorphism %s · %s: %.3g", sh_rot_method_name(method), name, nb2, eh);
        sh_rot_plan_free(p);
    }
    free(A);
    free(Bm);
    free(C);
}

/* The method's single band L (sh_rot_band, the path `rotmat --band` uses)
 * against the MPFR reference, both conventions, at a fixed tilted rotation. */
static inline void rot_check_band(sh_rot_method method, int L)
{
    sh_rotation r;
    sh_rotation_from_euler(-1.9, 2.4, 0.6, &r);
    const int w = 2 * L + 1;
    double *b = malloc((size_t)w * w * sizeof *b), *ref = malloc((size_t)w * w * sizeof *ref);
    for (int conv = 0; conv < 2; conv++) {
        ck_assert_int_eq(sh_rot_band(L, method, SH_PREC_DOUBLE, conv, &r, b), SH_OK);
        ck_assert_int_eq(sh_rot_reference_band(L, conv, &r, 32, ref, NULL), SH_OK);
        for (int i = 0; i < w * w; i++)
            ck_close(b[i], ref[i], 1e-13, 1.0, "%s band %d conv %d i %d", sh_rot_method_name(method), L, conv, i);
    }
    free(b);
    free(ref);
}

#endif
