/* test_scale.c — SH scaling (Wang et al. 2006): τ families, matrices, scenes.
 *
 * Truths used (none copied from our own output):
 *  - ray geometry: the midrange τ against a ray-sphere intersection and the
 *    cone τ against a ray-cone intersection, both solved here in 3-D;
 *  - τ′ against central differences of τ;
 *  - k = 1 (midrange k = 0) gives the identity matrix;
 *  - a second, independent matrix computation (sh_scale_matrix_quad: 2-D
 *    product rule with sh_eval, numerical φ) in both conventions, and a slow
 *    obvious one here (GSL QAGS in θ per element, trapezoid in φ);
 *  - the change of variables u = τ(θ): M_plain(τ) = M_energy(τ⁻¹)ᵀ, with
 *    τ⁻¹ in closed form (linear 1/k, cone 1/k, midrange atan2(sinα, cosα−k));
 *  - preservation: plain keeps constants (column 0 = e_0), energy-preserving
 *    with τ onto [0,π] keeps ∫F (row 0 = e_0), linear k<1 energy M_00 =
 *    (1 − cos kπ)/2;
 *  - the group law of the cone family τ_a∘τ_b = τ_ab;
 *  - scenes: the cone family on the cone occluder and the midrange family on
 *    the midrange scene are exact geometry (err_geom ~ 0);
 *  - displacement in any direction d (rotate to the axis, scale, rotate
 *    back): the exact radiance against a ray-sphere intersection solved
 *    here (R ≠ 1); the result equals the +z result of the environment
 *    rotated by a Q' built here (rows e1, e2, d: a different twist than the
 *    library's), rotated back by a second method (wigner); an environment
 *    symmetric about d gives the +z zonal result placed on d by the
 *    addition theorem (sh_eval only, no rotation code); displacement k
 *    along −z = −k along +z; the rotation methods agree with each other. */
#include "testutil.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <string.h>

static double max_abs_diff(const double *a, const double *b, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

/* ---- τ against ray geometry ------------------------------------------- */

START_TEST(test_midrange_tau_vs_ray_sphere)
{
    /* environment sphere |x| = R at the origin, point p = (0,0,d); the ray
     * p + t s hits it at P; τ must be the polar angle of P. */
    const double R = 2.5, ks[] = {-0.9, -0.5, -0.1, 0.2, 0.6, 0.95};
    for (int a = 0; a < 6; a++) {
        const double d = ks[a] * R;
        sh_scaling s = {SH_SCALE_MIDRANGE, ks[a], 0, 0};
        for (int q = 0; q <= 40; q++) {
            const double th = M_PI * q / 40.0, ph = 0.3 + q;
            const double sd[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
            /* |p + t s|² = R²:  t² + 2 d s_z t + d² − R² = 0 */
            const double B = d * sd[2], C = d * d - R * R, t = -B + sqrt(B * B - C);
            const double P[3] = {t * sd[0], t * sd[1], d + t * sd[2]};
            const double alpha = atan2(hypot(P[0], P[1]), P[2]);
            double tau, dtau;
            ck_assert_int_eq(sh_scale_tau(&s, th, &tau, &dtau), SH_OK);
            ck_close(tau, alpha, TOL3, 1.0, "midrange tau k=%g theta=%g", ks[a], th);
        }
    }
}
END_TEST

START_TEST(test_cone_tau_vs_ray_cone)
{
    /* Occluder centre O = origin, sample point v_r = (0,0,−r): θ = 0 points
     * at O.  Cone surface: apex O, axis −z (toward the samples), half-angle
     * θ0: points X with −X_z = |X| cos θ0.  A ray from v_d = (0,0,−d) in
     * direction s(θ,φ) meets the surface at X; τ must be the angle at v_r
     * between +z and X − v_r. */
    const double r = 1.7, th0s[] = {M_PI / 6, M_PI / 4, M_PI / 3, 1.2}, ks[] = {0.3, 0.8, 1.0, 1.7, 4.0};
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 5; b++) {
            const double th0 = th0s[a], d = ks[b] * r, c2 = cos(th0) * cos(th0);
            sh_scaling s = {SH_SCALE_CONE, ks[b], th0, 0};
            for (int q = 1; q < 40; q++) {
                const double th = (M_PI - th0) * q / 40.0, ph = 1.1 * q;
                const double sd[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
                /* X = v_d + t s; (X_z)² = c2 |X|², X_z < 0:
                 * (s_z² − c2) t² + 2(−d s_z + c2 d s_z)… written out below */
                const double A = sd[2] * sd[2] - c2, B = 2.0 * (-d) * sd[2] * (1.0 - c2),
                             C = d * d * (1.0 - c2);
                double best = -1;
                if (fabs(A) < 1e-14) best = -C / B;
                else {
                    const double disc = B * B - 4 * A * C;
                    ck_assert(disc >= 0);
                    const double t1 = (-B - sqrt(disc)) / (2 * A), t2 = (-B + sqrt(disc)) / (2 * A);
                    const double ts[2] = {t1, t2};
                    for (int u = 0; u < 2; u++) {
                        const double z = -d + ts[u] * sd[2];
                        if (ts[u] > 0 && z < 0 && (best < 0 || ts[u] < best)) best = ts[u];
                    }
                }
                ck_assert_msg(best > 0, "ray th=%g misses the cone", th);
                const double X[3] = {best * sd[0], best * sd[1], -d + best * sd[2]};
                const double V[3] = {X[0], X[1], X[2] + r};
                const double alpha = atan2(hypot(V[0], V[1]), V[2]);
                double tau;
                ck_assert_int_eq(sh_scale_tau(&s, th, &tau, NULL), SH_OK);
                ck_close(tau, alpha, TOL4, 1.0, "cone tau th0=%g k=%g theta=%g", th0, ks[b], th);
            }
        }
}
END_TEST

START_TEST(test_dtau_finite_difference)
{
    const sh_scaling cs[] = {{SH_SCALE_LINEAR, 0.6, 0, 0}, {SH_SCALE_LINEAR, 2.3, 0, 0}, {SH_SCALE_CONE, 0.4, 0.7, 0},
                             {SH_SCALE_CONE, 3.0, 0, 0}, {SH_SCALE_MIDRANGE, 0.8, 0, 0}, {SH_SCALE_MIDRANGE, -0.6, 0, 0}};
    const double h = 1e-6;
    for (int c = 0; c < 6; c++)
        for (int q = 1; q < 50; q++) {
            const double th = M_PI * (q + 0.37) / 51.0;
            if (cs[c].family == SH_SCALE_LINEAR && fabs(th * cs[c].k - M_PI) < 1e-3) continue;
            double tp, tm, t, dt, dummy;
            sh_scale_tau(&cs[c], th + h, &tp, &dummy);
            sh_scale_tau(&cs[c], th - h, &tm, &dummy);
            sh_scale_tau(&cs[c], th, &t, &dt);
            ck_close(dt, (tp - tm) / (2 * h), 1e-7, 1.0, "dtau family %d k=%g theta=%g", cs[c].family, cs[c].k, th);
        }
}
END_TEST

START_TEST(test_cone_group_law)
{
    /* cot τ_k = (cot θ + (1−k) cot θ0)/k  ⇒  τ_a(τ_b(θ)) = τ_ab(θ) */
    const double ab[][2] = {{0.5, 3.0}, {1.7, 0.4}, {2.0, 2.0}};
    for (int c = 0; c < 3; c++)
        for (int q = 1; q < 30; q++) {
            const double th = M_PI * q / 30.0;
            sh_scaling A = {SH_SCALE_CONE, ab[c][0], 0.9, 0}, B = A, AB = A;
            B.k = ab[c][1];
            AB.k = ab[c][0] * ab[c][1];
            double tb, t2, tab;
            sh_scale_tau(&B, th, &tb, NULL);
            sh_scale_tau(&A, tb, &t2, NULL);
            sh_scale_tau(&AB, th, &tab, NULL);
            ck_close(t2, tab, TOL3, 1.0, "cone group law a=%g b=%g theta=%g", ab[c][0], ab[c][1], th);
        }
}
END_TEST

/* ---- matrices ------------------------------------------------------------ */

START_TEST(test_identity_at_k1)
{
    const sh_scaling cs[] = {{SH_SCALE_LINEAR, 1, 0, 0}, {SH_SCALE_CONE, 1, 0.4, 0}, {SH_SCALE_MIDRANGE, 0, 0, 0}};
    for (int c = 0; c < 3; c++)
        for (int e = 0; e < 2; e++)
            for (int N = 1; N <= 8; N++) {
                const int n = N * N;
                double *M = malloc(sizeof(double) * n * n);
                sh_scaling s = cs[c];
                s.energy = e;
                ck_assert_int_eq(sh_scale_matrix(N, &s, M, NULL), SH_OK);
                for (int i = 0; i < n; i++)
                    for (int j = 0; j < n; j++)
                        ck_close(M[i * n + j], i == j, 1e-13, 1.0, "identity %s e=%d N=%d (%d,%d)",
                                 sh_scale_family_name(s.family), e, N, i, j);
                free(M);
            }
}
END_TEST

static const sh_scaling cases[] = {
    {SH_SCALE_LINEAR, 0.6, 0, 0}, {SH_SCALE_LINEAR, 0.6, 0, 1}, {SH_SCALE_LINEAR, 2.5, 0, 0},
    {SH_SCALE_LINEAR, 2.5, 0, 1}, {SH_SCALE_CONE, 0.45, 0, 0},  {SH_SCALE_CONE, 2.2, 1.1, 1},
    {SH_SCALE_CONE, 0.05, 0.5, 1}, {SH_SCALE_MIDRANGE, 0.7, 0, 0}, {SH_SCALE_MIDRANGE, -0.9, 0, 1},
};
#define NCASES ((int)(sizeof cases / sizeof *cases))

START_TEST(test_vs_product_rule)
{
    const int N = 5, n = 25;
    double M[625], Q[625];
    const sh_scaling s = cases[_i];
    ck_assert_int_eq(sh_scale_matrix(N, &s, M, NULL), SH_OK);
    for (int c = 0; c < 2; c++) {
        /* 64 nodes: a size GSL tabulates exactly (other sizes are computed to ~1e-10) */
        ck_assert_int_eq(sh_scale_matrix_quad(N, c ? SH_NOCS : SH_CS, &s, 64, 16, Q), SH_OK);
        const double d = max_abs_diff(M, Q, (size_t)n * n);
        ck_assert_msg(d <= 1e-12, "%s k=%g energy=%d conv=%d: |M - quad| = %.3g",
                      sh_scale_family_name(s.family), s.k, s.energy, c, d);
    }
    /* entries with m_i != m_j are exact zeros */
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            int li, mi, lj, mj;
            sh_index_lm(i, &li, &mi);
            sh_index_lm(j, &lj, &mj);
            if (mi != mj) ck_assert(M[i * n + j] == 0.0);
        }
}
END_TEST

/* The slow obvious version: one element, QAGS in θ (GSL's Gauss-Kronrod),
 * φ by a 40-point trapezoid (exact for these trigonometric degrees). */
typedef struct { const sh_scaling *s; int i, j, N; } elem_ctx;
static double elem_integrand(double th, void *vctx)
{
    const elem_ctx *c = vctx;
    double t, dt, ya[64], yb[64], acc = 0.0;
    sh_scale_tau(c->s, th, &t, &dt);
    for (int q = 0; q < 40; q++) {
        const double ph = 2 * M_PI * q / 40.0;
        sh_eval(c->N, SH_CS, th, ph, ya);
        sh_eval(c->N, SH_CS, t, ph, yb);
        acc += ya[c->i] * yb[c->j];
    }
    return acc * (2 * M_PI / 40.0) * (c->s->energy ? sin(t) * dt : sin(th));
}

START_TEST(test_vs_qags_elements)
{
    const int N = 4, n = 16;
    double M[256];
    const sh_scaling s = cases[_i];
    ck_assert_int_eq(sh_scale_matrix(N, &s, M, NULL), SH_OK);
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(2000);
    gsl_error_handler_t *old = gsl_set_error_handler_off(); /* roundoff warnings near 1e-14 */
    const int picks[][2] = {{0, 0}, {2, 0}, {0, 2}, {6, 12}, {5, 11}, {15, 9}, {3, 3}, {13, 7}};
    for (int p = 0; p < 8; p++) {
        elem_ctx c = {&s, picks[p][0], picks[p][1], N};
        gsl_function F = {elem_integrand, &c};
        double br[SH_SCALE_MAX_BREAKS], pts[SH_SCALE_MAX_BREAKS + 2], v = 0, err, part;
        const int nb = sh_scale_breaks(&s, br);
        pts[0] = 0;
        for (int b = 0; b < nb; b++) pts[1 + b] = br[b];
        pts[nb + 1] = M_PI;
        for (int b = 0; b <= nb; b++) { /* QAGS on each piece */
            gsl_integration_qags(&F, pts[b], pts[b + 1], 1e-13, 1e-12, 2000, w, &part, &err);
            v += part;
        }
        ck_close(M[c.i * n + c.j], v, 1e-11, 1.0, "%s k=%g e=%d M[%d][%d] vs QAGS",
                 sh_scale_family_name(s.family), s.k, s.energy, c.i, c.j);
    }
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
}
END_TEST

/* τ⁻¹ of the midrange family: the direction of P − p for P at polar angle α
 * on the unit sphere and p = k ẑ: θ = atan2(sin α, cos α − k). */
static void midrange_inverse(double a, void *ctx, double *t, double *dt)
{
    const double k = *(const double *)ctx;
    *t = atan2(sin(a), cos(a) - k);
    *dt = (1.0 - k * cos(a)) / (1.0 - 2.0 * k * cos(a) + k * k);
}

START_TEST(test_transpose_inverse)
{
    /* u = τ(θ): M_plain(τ)_ij = ∫ y_i(τ⁻¹u) y_j(u) sin(τ⁻¹u) τ⁻¹′(u) du dφ = M_energy(τ⁻¹)_ji
     * for τ one-to-one (linear k <= 1: u = kθ covers [0, kπ], where
     * energy(1/k) has τ′ = 0 beyond; linear k > 1 plain is not one-to-one:
     * θ > π/k all map to u = π, so only that direction of the pair holds) */
    const int N = 6, n = 36;
    double *A = malloc(sizeof(double) * n * n), *B = malloc(sizeof(double) * n * n);
    const sh_scaling pairs[][2] = {{{SH_SCALE_LINEAR, 0.4, 0, 0}, {SH_SCALE_LINEAR, 2.5, 0, 1}},
                                   {{SH_SCALE_LINEAR, 1.0 / 3.0, 0, 0}, {SH_SCALE_LINEAR, 3.0, 0, 1}},
                                   {{SH_SCALE_CONE, 0.6, 0.8, 0}, {SH_SCALE_CONE, 1.0 / 0.6, 0.8, 1}},
                                   {{SH_SCALE_CONE, 2.0, 0.8, 1}, {SH_SCALE_CONE, 0.5, 0.8, 0}}};
    for (int p = 0; p < 4; p++) {
        ck_assert_int_eq(sh_scale_matrix(N, &pairs[p][0], A, NULL), SH_OK);
        ck_assert_int_eq(sh_scale_matrix(N, &pairs[p][1], B, NULL), SH_OK);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
                ck_close(A[i * n + j], B[j * n + i], 1e-12, 1.0, "transpose pair %d (%d,%d)", p, i, j);
    }
    const double ks[] = {0.75, -0.5};
    for (int q = 0; q < 2; q++)
        for (int e = 0; e < 2; e++) {
            sh_scaling s = {SH_SCALE_MIDRANGE, ks[q], 0, e};
            double k = ks[q];
            ck_assert_int_eq(sh_scale_matrix(N, &s, A, NULL), SH_OK);
            ck_assert_int_eq(sh_scale_matrix_tau(N, midrange_inverse, &k, !e, NULL, 0, B, NULL), SH_OK);
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++)
                    ck_close(A[i * n + j], B[j * n + i], 1e-12, 1.0, "midrange k=%g e=%d (%d,%d)", k, e, i, j);
        }
    free(A);
    free(B);
}
END_TEST

START_TEST(test_preservation)
{
    const int N = 6, n = 36;
    double M[1296];
    for (int c = 0; c < NCASES; c++) {
        const sh_scaling s = cases[c];
        ck_assert_int_eq(sh_scale_matrix(N, &s, M, NULL), SH_OK);
        if (!s.energy) { /* a constant stays the same constant: column 0 = e_0 */
            for (int i = 0; i < n; i++) ck_close(M[i * n], i == 0, 1e-14, 1.0, "plain case %d M[%d][0]", c, i);
        } else if (!(s.family == SH_SCALE_LINEAR && s.k < 1)) { /* τ onto [0,π]: ∫F kept, row 0 = e_0 */
            for (int j = 0; j < n; j++) ck_close(M[j], j == 0, 1e-14, 1.0, "energy case %d M[0][%d]", c, j);
        } else { /* M_00 = (1/4π) 2π ∫ sin(kθ) k dθ = (1 − cos kπ)/2 */
            ck_close(M[0], 0.5 * (1 - cos(s.k * M_PI)), 1e-14, 1.0, "linear energy M00 k=%g", s.k);
        }
    }
}
END_TEST

START_TEST(test_pattern_and_midrange_zeros)
{
    for (int N = 1; N <= 16; N++) {
        long cnt = 0;
        for (int i = 0; i < N * N; i++)
            for (int j = 0; j < N * N; j++) {
                int li, mi, lj, mj;
                sh_index_lm(i, &li, &mi);
                sh_index_lm(j, &lj, &mj);
                cnt += mi == mj;
            }
        ck_assert_int_eq(sh_scale_pattern_bound(N), cnt);
    }
    /* midrange: plain M_ij = 0 for even l_i > 2 l_j, energy for odd
     * l_i > 2 l_j + 1 (see scale_sparsity); the neighbours are not zero */
    const int N = 9, n = 81;
    double *M = malloc(sizeof(double) * n * n);
    for (int e = 0; e < 2; e++) {
        sh_scaling s = {SH_SCALE_MIDRANGE, 0.55, 0, e};
        ck_assert_int_eq(sh_scale_matrix(N, &s, M, NULL), SH_OK);
        for (int li = 0; li < N; li++)
            for (int lj = 0; lj < N; lj++)
                for (int m = -(li < lj ? li : lj); m <= (li < lj ? li : lj); m++) {
                    const double v = M[sh_index(li, m) * n + sh_index(lj, m)];
                    const int zero = e ? ((li & 1) && li > 2 * lj + 1) || (li == 0 && lj > 0)
                                       : (!(li & 1) && li > 2 * lj) || (lj == 0 && li > 0);
                    if (zero) ck_assert_msg(fabs(v) < 1e-14, "midrange e=%d (%d,%d,%d) = %g", e, li, lj, m, v);
                    else ck_assert_msg(fabs(v) > 1e-8, "midrange e=%d (%d,%d,%d) = %g small", e, li, lj, m, v);
                }
    }
    free(M);
}
END_TEST

START_TEST(test_errors)
{
    double M[16];
    sh_scaling bad[] = {{SH_SCALE_LINEAR, 0, 0, 0}, {SH_SCALE_LINEAR, -1, 0, 0}, {SH_SCALE_LINEAR, NAN, 0, 0},
                        {SH_SCALE_CONE, 2, M_PI, 0}, {SH_SCALE_MIDRANGE, 1.0, 0, 0}, {SH_SCALE_MIDRANGE, -1.5, 0, 0},
                        {SH_SCALE_LINEAR, 2, 0, 2}, {(sh_scale_family)7, 1, 0, 0}};
    for (int b = 0; b < 8; b++) ck_assert_int_eq(sh_scale_matrix(2, &bad[b], M, NULL), SH_EINVAL);
    sh_scaling ok = {SH_SCALE_LINEAR, 2, 0, 0};
    ck_assert_int_eq(sh_scale_matrix(0, &ok, M, NULL), SH_EINVAL);
    ck_assert_int_eq(sh_scale_matrix(SH_SCALE_MAX_ORDER + 1, &ok, M, NULL), SH_EINVAL);
    sh_scale_family f;
    ck_assert_int_eq(sh_scale_family_parse("lin", &f), SH_EINVAL);
    ck_assert_int_eq(sh_scale_family_parse("midrange", &f), SH_OK);
    ck_assert_int_eq(f, SH_SCALE_MIDRANGE);
}
END_TEST

/* ---- interpolation and scenes ------------------------------------------------ */

typedef struct { int calls, last, total, monotone; } prog_count;
static void count_progress(void *ctx, int done, int total, const char *what)
{
    prog_count *p = ctx;
    if (done != p->last + 1 || !what) p->monotone = 0;
    p->calls++;
    p->last = done;
    p->total = total;
}

START_TEST(test_interp)
{
    sh_scaling s = {SH_SCALE_CONE, 1, 0, 0};
    sh_scale_interp_result r10, r40, c40;
    ck_assert_int_eq(sh_scale_interp_error(4, &s, 10, SH_SPACING_GEOMETRIC, 0.5, 2, SH_INTERP_LINEAR, 101, &r10), SH_OK);
    ck_assert_int_eq(sh_scale_interp_error(4, &s, 40, SH_SPACING_GEOMETRIC, 0.5, 2, SH_INTERP_LINEAR, 101, &r40), SH_OK);
    ck_assert_int_eq(sh_scale_interp_error(4, &s, 40, SH_SPACING_GEOMETRIC, 0.5, 2, SH_INTERP_CUBIC, 101, &c40), SH_OK);
    /* linear interpolation error ~ h²: 4x the samples, ~16x smaller */
    ck_assert_msg(r40.max_error < r10.max_error / 8, "40 samples %g vs 10 samples %g", r40.max_error, r10.max_error);
    ck_assert_msg(c40.rms_error < r40.rms_error, "cubic %g vs linear %g", c40.rms_error, r40.rms_error);
    ck_assert(r40.rms_error <= r40.max_error);
    /* the progress variant: same numbers, one call per sampled and per dense k */
    sh_scale_interp_result p40;
    prog_count pc = {0, 0, 0, 1};
    ck_assert_int_eq(sh_scale_interp_error_progress(4, &s, 40, SH_SPACING_GEOMETRIC, 0.5, 2, SH_INTERP_LINEAR,
                                                    101, &p40, count_progress, &pc), SH_OK);
    ck_assert(p40.max_error == r40.max_error && p40.rms_error == r40.rms_error);
    ck_assert_int_eq(pc.calls, 40 + 101);
    ck_assert_int_eq(pc.total, 40 + 101);
    ck_assert_int_eq(pc.last, 40 + 101);
    ck_assert(pc.monotone);
    /* the dense grid contains the samples when it is the same grid: zero error */
    sh_scale_interp_result same;
    ck_assert_int_eq(sh_scale_interp_error(3, &s, 11, SH_SPACING_UNIFORM, 0.5, 1.5, SH_INTERP_LINEAR, 11, &same), SH_OK);
    ck_assert_msg(same.max_error < 1e-14, "interp at the samples %g", same.max_error);
    ck_assert_int_eq(sh_scale_interp_error(3, &s, 11, SH_SPACING_GEOMETRIC, -0.5, 1.5, SH_INTERP_LINEAR, 11, &same),
                     SH_EINVAL);
    ck_assert_int_eq(sh_scale_interp_error(3, &s, 2, SH_SPACING_UNIFORM, 0.5, 1.5, SH_INTERP_CUBIC, 11, &same),
                     SH_EINVAL);
}
END_TEST

START_TEST(test_scenes)
{
    const int N = 5;
    sh_scale_scene_err e;
    /* cone occluder, cone family with the occluder's θ0: exact geometry */
    sh_scale_scene cone = {SH_SCENE_CONE, 0.4, M_PI / 5, 0.3, NULL, NULL, NULL, 0, {0, 0, 0}, 0};
    const double ks[] = {0.7, 1.4, 2.5};
    for (int q = 0; q < 3; q++) {
        sh_scaling s = {SH_SCALE_CONE, ks[q], M_PI / 5, 0};
        ck_assert_int_eq(sh_scale_scene_errors(&cone, N, SH_CS, &s, ks[q], NULL, &e, NULL), SH_OK);
        ck_assert_msg(e.err_geom < 1e-12, "cone scene k=%g err_geom %g", ks[q], e.err_geom);
        /* and the linear family is not */
        s.family = SH_SCALE_LINEAR;
        ck_assert_int_eq(sh_scale_scene_errors(&cone, N, SH_CS, &s, ks[q], NULL, &e, NULL), SH_OK);
        ck_assert_msg(e.err_geom > 1e-3, "cone scene linear k=%g err_geom %g", ks[q], e.err_geom);
    }
    /* midrange plain: exact geometry; energy-preserving is not */
    sh_scale_scene mid = {SH_SCENE_MIDRANGE, 0, 0, 0, sh_scale_scene_lobes_fn, NULL, NULL, 120, {0, 0, 0}, 0};
    for (int e2 = 0; e2 < 2; e2++) {
        sh_scaling s = {SH_SCALE_MIDRANGE, -0.6, 0, e2};
        ck_assert_int_eq(sh_scale_scene_errors(&mid, N, SH_NOCS, &s, -0.6, NULL, &e, NULL), SH_OK);
        if (!e2) ck_assert_msg(e.err_geom < 1e-12, "midrange plain err_geom %g", e.err_geom);
        else ck_assert_msg(e.err_geom > 1e-2, "midrange energy err_geom %g", e.err_geom);
    }
    /* sphere: scaling to k = 1 is the identity, the exact cap comes back */
    sh_scale_scene sph = {SH_SCENE_SPHERE, 0.5, 0, 0, NULL, NULL, NULL, 0, {0, 0, 0}, 0};
    sh_scaling s1 = {SH_SCALE_LINEAR, 1.0, 0, 0};
    ck_assert_int_eq(sh_scale_scene_errors(&sph, N, SH_CS, &s1, 1.0, NULL, &e, NULL), SH_OK);
    ck_assert_msg(e.err_scaled < 1e-13 && e.err_geom < 1e-13, "sphere k=1: %g %g", e.err_scaled, e.err_geom);
    /* the region quadrature of the sphere's cap against the closed form */
    sh_scale_scene sphc = {SH_SCENE_CONE, 0.5, M_PI / 4, 0.0, NULL, NULL, NULL, 0, {0, 0, 0}, 0};
    double c1[25], z[5];
    ck_assert_int_eq(sh_scale_scene_exact(&sphc, N, SH_CS, 1.3, c1), SH_OK);
    const double beta = atan2(0.5 * tan(M_PI / 4), 1.3 - 0.5);
    ck_assert_int_eq(sh_cap_zonal(beta, N, z), SH_OK);
    for (int l = 0; l < N; l++)
        for (int m = -l; m <= l; m++)
            ck_close(c1[sh_index(l, m)], m ? 0.0 : z[l], 1e-13, 1.0, "flat-rim cone = cap (%d,%d)", l, m);
    /* scene errors */
    ck_assert_int_eq(sh_scale_scene_errors(&sph, N, SH_CS, &s1, 0.4, NULL, &e, NULL), SH_EINVAL);
    ck_assert_int_eq(sh_scale_scene_errors(&cone, N, SH_CS, &s1, 0.5, NULL, &e, NULL), SH_EINVAL);
}
END_TEST

/* ---- displacement in any direction --------------------------------------- */

static void unit3(double v[3])
{
    const double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= n, v[1] /= n, v[2] /= n;
}

/* A proper rotation with rows e1, e2, d (so Q d = ẑ), e1 ⟂ d from a fixed
 * helper vector: not the library's shortest rotation. */
static void frame_to_z(const double d[3], double Q[9])
{
    const double h[3] = {0.2, 0.9, -0.4};
    double e1[3] = {h[1] * d[2] - h[2] * d[1], h[2] * d[0] - h[0] * d[2], h[0] * d[1] - h[1] * d[0]};
    unit3(e1);
    const double e2[3] = {d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2], d[0] * e1[1] - d[1] * e1[0]};
    for (int j = 0; j < 3; j++) Q[j] = e1[j], Q[3 + j] = e2[j], Q[6 + j] = d[j];
}

/* The lobes environment rotated by Q: g(u) = f(Qᵀ u). */
static double rotated_lobes(const double u[3], double theta, double phi, void *ctx)
{
    const double *Q = ctx;
    double v[3], th, ph;
    for (int i = 0; i < 3; i++) v[i] = Q[i] * u[0] + Q[3 + i] * u[1] + Q[6 + i] * u[2];
    sh_angles_from_dir(v, &th, &ph);
    return sh_scale_scene_lobes_fn(v, th, ph, NULL);
}

/* A zonal environment about the axis in ctx: h(u·a) = exp(6(u·a − 1)) + 0.3 (u·a)³. */
static double zonal_about(const double u[3], double theta, double phi, void *ctx)
{
    const double *a = ctx, x = u[0] * a[0] + u[1] * a[1] + u[2] * a[2];
    return exp(6.0 * (x - 1.0)) + 0.3 * x * x * x;
}

START_TEST(test_axis_rotation)
{
    const double axes[][3] = {{0, 0, 1}, {0, 0, -2}, {1, 1, 1}, {1e-9, 0, 1}, {-3e-12, 2e-12, -1}, {0.3, -0.5, 0.8},
                              {1, 0, 0}, {0, -1e-200, 0}};
    for (int a = 0; a < 8; a++) {
        double u[3];
        sh_rotation Q;
        ck_assert_int_eq(sh_scale_axis_unit(axes[a], u), SH_OK);
        ck_assert_int_eq(sh_scale_axis_rotation(axes[a], &Q), SH_OK);
        for (int i = 0; i < 3; i++) {
            const double qa = Q.R[3 * i] * u[0] + Q.R[3 * i + 1] * u[1] + Q.R[3 * i + 2] * u[2];
            ck_close(qa, i == 2, TOL1, 1.0, "axis %d: (Q a)_%d", a, i);
        }
        const double det = Q.R[0] * (Q.R[4] * Q.R[8] - Q.R[5] * Q.R[7]) - Q.R[1] * (Q.R[3] * Q.R[8] - Q.R[5] * Q.R[6]) +
                           Q.R[2] * (Q.R[3] * Q.R[7] - Q.R[4] * Q.R[6]);
        ck_close(det, 1.0, TOL1, 1.0, "axis %d: det Q", a);
    }
    const double zero[3] = {0, 0, 0}, bad[3] = {NAN, 0, 1};
    sh_rotation Q;
    ck_assert_int_eq(sh_scale_axis_rotation(zero, &Q), SH_EINVAL);
    ck_assert_int_eq(sh_scale_axis_rotation(bad, &Q), SH_EINVAL);
}
END_TEST

START_TEST(test_midrange_dir_ray_geometry)
{
    /* environment on |x| = R, point p = k R d; the radiance from direction s
     * is the environment at the ray's hit P/|P| (solved here for R = 2.5) */
    const double R = 2.5, ks[] = {-0.85, 0.3, 0.9};
    double d[3] = {0.3, -0.5, 0.8};
    unit3(d);
    sh_scale_scene sc = {SH_SCENE_MIDRANGE, 0, 0, 0, sh_scale_scene_lobes_fn, NULL, NULL, 64, {d[0], d[1], d[2]}, 0};
    for (int a = 0; a < 3; a++)
        for (int q = 0; q < 60; q++) {
            const double th = M_PI * (q + 0.5) / 60.0, ph = 0.7 + 2.3 * q;
            const double s3[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
            const double p[3] = {ks[a] * R * d[0], ks[a] * R * d[1], ks[a] * R * d[2]};
            /* |p + t s|² = R²: t² + 2 (p·s) t + |p|² − R² = 0, the root t > 0 */
            const double B = p[0] * s3[0] + p[1] * s3[1] + p[2] * s3[2];
            const double C = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - R * R, t = -B + sqrt(B * B - C);
            const double P[3] = {(p[0] + t * s3[0]) / R, (p[1] + t * s3[1]) / R, (p[2] + t * s3[2]) / R};
            double pt, pp;
            sh_angles_from_dir(P, &pt, &pp);
            const double want = sh_scale_scene_lobes_fn(P, pt, pp, NULL);
            ck_close(sh_scale_scene_value(&sc, ks[a], th, ph), want, TOL3, 1e-3, "dir scene value k=%g th=%g",
                     ks[a], th);
        }
}
END_TEST

/* |a − b| / |b| over n entries */
static double rel_l2(const double *a, const double *b, int n)
{
    double s = 0, t = 0;
    for (int i = 0; i < n; i++) s += (a[i] - b[i]) * (a[i] - b[i]), t += b[i] * b[i];
    return sqrt(s / t);
}

START_TEST(test_midrange_dir_vs_rotated_env)
{
    /* scene along d with environment f  ==  R_sh(Q'ᵀ) · (scene along +z with
     * environment f(Q'ᵀ ·)), Q' d = ẑ built in frame_to_z; R_sh by the
     * wigner method (the library rotates with zxzxz / blanco) */
    const int N = 6, n = 36;
    double d[3] = {0.3, -0.5, 0.8}, Q[9], Qt[9];
    unit3(d);
    frame_to_z(d, Q);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Qt[3 * i + j] = Q[3 * j + i];
    sh_rotation back;
    ck_assert_int_eq(sh_rotation_from_matrix(Qt, 0, &back), SH_OK);
    sh_rot_plan *plan;
    ck_assert_int_eq(sh_rot_plan_create(N, SH_ROT_WIGNER, SH_PREC_DOUBLE, SH_CS, &plan), SH_OK);
    ck_assert_int_eq(sh_rot_plan_set(plan, &back), SH_OK);
    sh_scale_scene zs = {SH_SCENE_MIDRANGE, 0, 0, 0, rotated_lobes, Q, NULL, 160, {0, 0, 0}, 0};
    const sh_rot_method methods[2] = {SH_ROT_ZXZXZ, SH_ROT_BLANCO};
    const double ks[] = {-0.7, 0.5, 0.9};
    for (int q = 0; q < 3; q++)
        for (int e = 0; e < 2; e++) {
            sh_scaling s = {SH_SCALE_MIDRANGE, ks[q], 0, e};
            double Ez[36], Sz[36], Ed[36], Sd[36], Ezr[36], Szr[36];
            sh_scale_scene_err ez, ed;
            ck_assert_int_eq(sh_scale_scene_exact(&zs, N, SH_CS, ks[q], Ez), SH_OK);
            ck_assert_int_eq(sh_scale_scene_errors(&zs, N, SH_CS, &s, ks[q], NULL, &ez, Sz), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(plan, Ez, Ezr), SH_OK);
            ck_assert_int_eq(sh_rot_plan_apply(plan, Sz, Szr), SH_OK);
            for (int m = 0; m < 2; m++) {
                sh_scale_scene ds = {SH_SCENE_MIDRANGE, 0, 0, 0, sh_scale_scene_lobes_fn, NULL, NULL, 160,
                                     {3 * d[0], 3 * d[1], 3 * d[2]}, methods[m]};
                ck_assert_int_eq(sh_scale_scene_exact(&ds, N, SH_CS, ks[q], Ed), SH_OK);
                ck_assert_int_eq(sh_scale_scene_errors(&ds, N, SH_CS, &s, ks[q], NULL, &ed, Sd), SH_OK);
                const double dE = rel_l2(Ed, Ezr, n), dS = rel_l2(Sd, Szr, n);
                ck_assert_msg(dE < 1e-12 && dS < 1e-12, "k=%g e=%d method %s: exact %.3g scaled %.3g", ks[q], e,
                              sh_rot_method_name(methods[m]), dE, dS);
                /* and the three errors are the same numbers */
                ck_close(ed.err_scaled, ez.err_scaled, 1e-10, 1e-2, "err_scaled k=%g e=%d", ks[q], e);
                ck_close(ed.err_geom, ez.err_geom, 1e-10, 1e-2, "err_geom k=%g e=%d", ks[q], e);
                ck_close(ed.err_trunc, ez.err_trunc, 1e-10, 1e-2, "err_trunc k=%g e=%d", ks[q], e);
                if (!e) ck_assert_msg(ed.err_geom < 1e-12, "plain about d is exact geometry: %g", ed.err_geom);
            }
        }
    sh_rot_plan_free(plan);
}
END_TEST

START_TEST(test_midrange_dir_zonal_env)
{
    /* h(u·d) displaced along d: the +z result of h(u_z) is zonal (z_l), and
     * a function zonal about d with zonal coefficients z_l has coefficients
     * z_l √(4π/(2l+1)) y_lm(d) (addition theorem) — no rotation code used */
    const int N = 7, n = 49;
    double d[3] = {-0.6, 0.2, -0.5}, zax[3] = {0, 0, 1}, td, pd, yd[49];
    unit3(d);
    sh_angles_from_dir(d, &td, &pd);
    for (int c = 0; c < 2; c++) {
        const sh_convention conv = c ? SH_NOCS : SH_CS;
        ck_assert_int_eq(sh_eval(N, conv, td, pd, yd), SH_OK);
        sh_scale_scene zs = {SH_SCENE_MIDRANGE, 0, 0, 0, zonal_about, zax, NULL, 160, {0, 0, 0}, 0};
        sh_scale_scene ds = {SH_SCENE_MIDRANGE, 0, 0, 0, zonal_about, d, NULL, 160, {d[0], d[1], d[2]}, SH_ROT_IVANIC};
        const double ks[] = {-0.8, 0.6};
        for (int q = 0; q < 2; q++)
            for (int e = 0; e < 2; e++) {
                sh_scaling s = {SH_SCALE_MIDRANGE, ks[q], 0, e};
                double Sz[49], Sd[49], want[49], Ez[49], Ed[49], wantE[49];
                sh_scale_scene_err er;
                ck_assert_int_eq(sh_scale_scene_errors(&zs, N, conv, &s, ks[q], NULL, &er, Sz), SH_OK);
                ck_assert_int_eq(sh_scale_scene_errors(&ds, N, conv, &s, ks[q], NULL, &er, Sd), SH_OK);
                ck_assert_int_eq(sh_scale_scene_exact(&zs, N, conv, ks[q], Ez), SH_OK);
                ck_assert_int_eq(sh_scale_scene_exact(&ds, N, conv, ks[q], Ed), SH_OK);
                for (int l = 0; l < N; l++)
                    for (int m = -l; m <= l; m++) {
                        const double f = sqrt(4 * M_PI / (2 * l + 1)) * yd[sh_index(l, m)];
                        want[sh_index(l, m)] = Sz[sh_index(l, 0)] * f;
                        wantE[sh_index(l, m)] = Ez[sh_index(l, 0)] * f;
                        if (m) ck_assert_msg(fabs(Sz[sh_index(l, m)]) < 1e-14, "+z result not zonal (%d,%d)", l, m);
                    }
                const double dS = rel_l2(Sd, want, n), dE = rel_l2(Ed, wantE, n);
                ck_assert_msg(dS < 1e-12 && dE < 1e-12, "zonal about d, conv %d k=%g e=%d: scaled %.3g exact %.3g", c,
                              ks[q], e, dS, dE);
            }
    }
}
END_TEST

START_TEST(test_apply_axis)
{
    const int N = 6, n = 36;
    double M[1296], Mm[1296], in[36], a[36], b[36], c[36];
    for (int i = 0; i < n; i++) in[i] = sin(1.3 * i + 0.2) / (1 + i);
    for (int e = 0; e < 2; e++) {
        sh_scaling s = {SH_SCALE_MIDRANGE, 0.65, 0, e}, sm = s;
        sm.k = -0.65;
        ck_assert_int_eq(sh_scale_matrix(N, &s, M, NULL), SH_OK);
        ck_assert_int_eq(sh_scale_matrix(N, &sm, Mm, NULL), SH_OK);
        /* +z exactly: M alone, bit for bit */
        const double z[3] = {0, 0, 5}, mz[3] = {0, 0, -1}, t[3] = {0.4, 0.1, -0.9};
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, z, SH_ROT_ZXZXZ, in, a), SH_OK);
        for (int i = 0; i < n; i++) {
            double v = 0;
            for (int j = 0; j < n; j++) v += M[i * n + j] * in[j];
            ck_assert(a[i] == v);
        }
        /* k along −z = −k along +z */
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_NOCS, M, mz, SH_ROT_BLANCO, in, b), SH_OK);
        for (int i = 0; i < n; i++) {
            double v = 0;
            for (int j = 0; j < n; j++) v += Mm[i * n + j] * in[j];
            ck_close(b[i], v, 1e-13, 1.0, "e=%d -z vs -k (%d)", e, i);
        }
        /* the rotation methods agree; in place allowed */
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, t, SH_ROT_ZXZXZ, in, a), SH_OK);
        memcpy(c, in, sizeof c);
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, t, SH_ROT_IVANIC, c, c), SH_OK);
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, t, SH_ROT_REFERENCE, in, b), SH_OK);
        for (int i = 0; i < n; i++) {
            ck_close(a[i], b[i], 1e-13, 1.0, "zxzxz vs reference (%d)", i);
            ck_close(c[i], b[i], 1e-13, 1.0, "ivanic vs reference (%d)", i);
        }
        /* refusals */
        const double zero[3] = {0, 0, 0};
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, zero, SH_ROT_ZXZXZ, in, a), SH_EINVAL);
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, t, SH_ROT_Z, in, a), SH_EINVAL);
        ck_assert_int_eq(sh_scale_apply_axis(N, SH_CS, M, t, SH_ROT_TAYLOR15, in, a), SH_EINVAL);
    }
    /* a direction on an occluder scene is refused */
    sh_scale_scene cone = {SH_SCENE_CONE, 0.4, M_PI / 5, 0.3, NULL, NULL, NULL, 0, {1, 0, 0}, 0};
    ck_assert_int_eq(sh_scale_scene_check(&cone, 1.5), SH_EINVAL);
    sh_scale_scene mid = {SH_SCENE_MIDRANGE, 0, 0, 0, sh_scale_scene_lobes_fn, NULL, NULL, 64, {0, NAN, 1}, 0};
    ck_assert_int_eq(sh_scale_scene_check(&mid, 0.5), SH_EINVAL);
    mid.dir[1] = 0;
    mid.rotation = SH_ROT_TAYLOR1;
    ck_assert_int_eq(sh_scale_scene_check(&mid, 0.5), SH_EINVAL);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("scale");
    TCase *t = tcase_create("scale");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, test_midrange_tau_vs_ray_sphere);
    tcase_add_test(t, test_cone_tau_vs_ray_cone);
    tcase_add_test(t, test_dtau_finite_difference);
    tcase_add_test(t, test_cone_group_law);
    tcase_add_test(t, test_identity_at_k1);
    tcase_add_loop_test(t, test_vs_product_rule, 0, NCASES);
    tcase_add_loop_test(t, test_vs_qags_elements, 0, NCASES);
    tcase_add_test(t, test_transpose_inverse);
    tcase_add_test(t, test_preservation);
    tcase_add_test(t, test_pattern_and_midrange_zeros);
    tcase_add_test(t, test_errors);
    tcase_add_test(t, test_interp);
    tcase_add_test(t, test_scenes);
    tcase_add_test(t, test_axis_rotation);
    tcase_add_test(t, test_midrange_dir_ray_geometry);
    tcase_add_test(t, test_midrange_dir_vs_rotated_env);
    tcase_add_test(t, test_midrange_dir_zonal_env);
    tcase_add_test(t, test_apply_axis);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
