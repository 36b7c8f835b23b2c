/* test_ranges.c — every range the documentation promises, at its upper end,
 * on full-size inputs, against a truth that shares no code with what it
 * judges (docs/ranges.md is the audit; each test prints the error it
 * measured as a line "test_ranges: ..." that the audit quotes).
 *
 * Truths used here: the orthonormal Legendre functions of
 * tests/legendre_truth.h (long double, extended exponent; bounded against
 * MPFR at 256 bits at the top band below), Gauss-Legendre quadrature that is
 * exact for the polynomial integrands of the closed forms, the definitions of
 * the bases and of a rotation about z, the pointwise identity
 * Σ g_i y_i(s) = Σ c_i y_i(R⁻¹s) of a rotation, closed forms and
 * orthogonality relations of the Wigner 3j symbols, GSL's adaptive QAG
 * quadrature of the scaling integrals, two independent derivative methods,
 * the Taylor rotations rebuilt from their definition with J checked against
 * an exact rotation, a symmetric eigensolver in place of the one-sided
 * Jacobi SVD, and bitwise equality where a result must not depend on the
 * number of threads or on the batch size. */
#include "testutil.h"

#include "exr_writer.h"
#include "legendre_truth.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <string.h>
#include <unistd.h>

#define LTOP (SHLAB_MAX_ORDER - 1) /* the top band */

static unsigned long long rng_state = 88172645463325252ULL;
static double urand(void) /* [0, 1) */
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}
static double nrand(void)
{
    const double u1 = urand() + 1e-300, u2 = urand();
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

/* ------------------------------------------------ Legendre and the basis */

/* sh_legendre_array at l = 4096 (SHLAB_MAX_ORDER − 1), every (l, m) with
 * l ≤ 4096, against truth_qlm_column; the truth itself against MPFR at the
 * top band; and the addition theorem Σ_m (2 − δ_m0) Q_l^m(x)² = (2l+1)/4π at
 * l = 4096.  Errors relative to the band's scale √((2l+1)/4π), the bound of
 * |Q_l^m| (addition theorem), as in test_basis.c. */
START_TEST(legendre_top)
{
    const int L = LTOP;
    const double xs[] = {0.9999694, 0.05, -0.7};
    double *q = malloc(sizeof(double) * sh_legendre_n(L)), *col = malloc(sizeof(double) * (L + 1));
    ck_assert(q && col);
    double worst = 0.0, worst_add = 0.0, worst_mpfr = 0.0;
    for (size_t k = 0; k < sizeof xs / sizeof *xs; k++) {
        ck_assert_int_eq(sh_legendre_array(L, xs[k], q), SH_OK);
        for (int m = 0; m <= L; m++) {
            truth_qlm_column(L, m, xs[k], col);
            for (int l = m; l <= L; l++) {
                const double band = sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
                const double e = fabs(q[sh_legendre_idx(l, m)] - col[l - m]) / band;
                if (!(e <= worst)) worst = e; /* NaN propagates */
            }
        }
        long double s = 0.0L;
        for (int m = 0; m <= L; m++) s += (m ? 2.0L : 1.0L) * (long double)q[sh_legendre_idx(L, m)] * q[sh_legendre_idx(L, m)];
        worst_add = fmax(worst_add, fabs((double)s / ((2.0 * L + 1.0) / (4.0 * M_PI)) - 1.0));
        const int ms[] = {0, 1, 100, 1500, 3000, 4000, 4096};
        for (size_t i = 0; i < sizeof ms / sizeof *ms; i++) {
            const double t = truth_qlm(L, ms[i], xs[k]), r = truth_qlm_mpfr(L, ms[i], xs[k], 256);
            worst_mpfr = fmax(worst_mpfr, fabs(t - r) / sqrt((2.0 * L + 1.0) / (4.0 * M_PI)));
        }
    }
    printf("test_ranges: Legendre l <= %d (3 x, every l, m) vs long-double truth: max error %.3g of the band scale;"
           " addition theorem at l = %d: %.3g relative; truth vs MPFR 256 bits at l = %d: %.3g\n",
           L, worst, L, worst_add, L, worst_mpfr);
    ck_assert_msg(worst_mpfr <= 1e-15, "truth vs MPFR %.3g", worst_mpfr);
    ck_assert_msg(worst <= 1e-12, "Legendre at l <= %d: %.3g", L, worst);
    ck_assert_msg(worst_add <= 1e-12, "addition theorem at l = %d: %.3g", L, worst_add);
    free(q);
    free(col);
}
END_TEST

/* The real basis at order 4097 (sh_eval, both conventions) against its
 * definition built from the truth Legendre functions and cosl/sinl of mφ:
 * y_l^0 = Q_l^0, y_l^{±m} = √2 Q_l^m {cos, sin}(mφ), nocs = odd m negated.
 * Errors relative to √2 × the band's scale. */
START_TEST(basis_top)
{
    const int order = SHLAB_MAX_ORDER, L = order - 1;
    const double pts[][2] = {{0.83, 2.1}, {3.1, -0.7}};
    double *y = malloc(sizeof(double) * (size_t)order * order), *col = malloc(sizeof(double) * (L + 1));
    ck_assert(y && col);
    double worst = 0.0;
    for (int conv = 0; conv < 2; conv++) {
        const size_t p = (size_t)conv; /* one direction per convention */
        {
            const double th = pts[p][0], ph = pts[p][1];
            ck_assert_int_eq(sh_eval(order, (sh_convention)conv, th, ph, y), SH_OK);
            for (int m = 0; m <= L; m++) {
                truth_qlm_column(L, m, cos(th), col);
                const double sg = (conv == SH_NOCS && (m & 1)) ? -1.0 : 1.0;
                const double cm = (double)cosl((long double)m * ph), sm = (double)sinl((long double)m * ph);
                for (int l = m; l <= L; l++) {
                    const double s = M_SQRT2 * sqrt((2.0 * l + 1.0) / (4.0 * M_PI));
                    double e;
                    if (!m) e = fabs(y[sh_index(l, 0)] - col[0 + l]) / s;
                    else {
                        const double q = sg * M_SQRT2 * col[l - m];
                        e = fmax(fabs(y[sh_index(l, m)] - q * cm), fabs(y[sh_index(l, -m)] - q * sm)) / s;
                    }
                    if (!(e <= worst)) worst = e;
                }
            }
        }
    }
    printf("test_ranges: basis order %d (cs, nocs; a direction each, all %d functions) vs definition: max error %.3g of"
           " sqrt(2) x band scale\n",
           order, order * order, worst);
    ck_assert_msg(worst <= 1e-12, "basis at order %d: %.3g", order, worst);
    free(y);
    free(col);
}
END_TEST

/* sh_convert at order 4097 keeps the function: Σ c'_i y'_i(s) = Σ c_i y_i(s)
 * with y' the target basis built from its definition (docs/CONVENTIONS.md):
 * 4pi = √(4π)·y_nocs, schmidt = √(4π/(2l+1))·y_nocs, nocs = odd m negated;
 * the functions evaluated with the truth Legendre functions.  Relative to
 * Σ |c_i y_i(s)|. */
START_TEST(convert_top)
{
    const int order = SHLAB_MAX_ORDER, L = order - 1;
    const size_t n = (size_t)order * order;
    double *c = malloc(sizeof(double) * n), *col = malloc(sizeof(double) * (L + 1));
    ck_assert(c && col);
    for (size_t i = 0; i < n; i++) c[i] = nrand();
    const sh_norm to[] = {SH_NORM_NOCS, SH_NORM_4PI, SH_NORM_SCHMIDT};
    double *d[3];
    for (int t = 0; t < 3; t++) {
        d[t] = malloc(sizeof(double) * n);
        ck_assert_ptr_nonnull(d[t]);
        memcpy(d[t], c, sizeof(double) * n);
        ck_assert_int_eq(sh_convert(order, SH_NORM_CS, to[t], d[t]), SH_OK);
    }
    const double th = 1.234, ph = -2.2, x = cos(th);
    long double f = 0.0L, g[3] = {0.0L, 0.0L, 0.0L}, scale = 0.0L;
    for (int m = 0; m <= L; m++) {
        truth_qlm_column(L, m, x, col);
        const long double cm = cosl((long double)m * ph), sm = sinl((long double)m * ph);
        const double sg = (m & 1) ? -1.0 : 1.0; /* y_nocs = sg · y_cs */
        for (int l = m; l <= L; l++) {
            /* the target bases: nocs, 4pi = √(4π) nocs, schmidt = √(4π/(2l+1)) nocs */
            const long double norm[3] = {1.0L, sqrtl(4.0L * M_PI), sqrtl(4.0L * M_PI / (2.0L * l + 1.0L))};
            const long double q = (long double)col[l - m] * (m ? M_SQRT2 : 1.0);
            const long double yc = q * (m ? cm : 1.0L), ys = q * sm;
            f += c[sh_index(l, m)] * yc;
            scale += fabsl(c[sh_index(l, m)] * yc);
            for (int t = 0; t < 3; t++) g[t] += d[t][sh_index(l, m)] * norm[t] * sg * yc;
            if (m) {
                f += c[sh_index(l, -m)] * ys;
                scale += fabsl(c[sh_index(l, -m)] * ys);
                for (int t = 0; t < 3; t++) g[t] += d[t][sh_index(l, -m)] * norm[t] * sg * ys;
            }
        }
    }
    double worst = 0.0;
    for (int t = 0; t < 3; t++) worst = fmax(worst, (double)(fabsl(f - g[t]) / scale)), free(d[t]);
    printf("test_ranges: convert cs -> nocs, 4pi, schmidt at order %d: function kept to %.3g of sum |c y|\n", order,
           worst);
    ck_assert_msg(worst <= 1e-14, "convert at order %d: %.3g", order, worst);
    free(c);
    free(col);
}
END_TEST

/* ------------------------------------ conversions between convention specs */

/* A user's real basis at direction u, by the spec's definitions written out
 * here (docs/CONVENTIONS.md, "Other conventions"): the coordinates the
 * shlab formulas see are s with s[axis_i] = sign_i·u_i (the axes string
 * "+x+z-y" lists, for the user's x, y, z, the sign and the shlab axis);
 * nocs = orthonormal real functions without the phase; 4pi ×√(4π), schmidt
 * ×√(4π/(2l+1)); m < 0 ↔ sin (neg-sin) or cos (neg-cos); index acn
 * l(l+1)+m, mdesc l(l+1)−m, cossin l² + (0, cos1, sin1, cos2, ...).  The
 * function f(u) = Σ c_k y_k(u), summed in long double from truth Legendre. */
typedef struct {
    const char *spec, *axes;
    int cs, norm, neg_cos, index; /* norm 0 ortho 1 4pi 2 schmidt; index 0 acn 1 mdesc 2 cossin */
} user_real;

static long double user_real_point(const user_real *ur, int L, const double *c, const double u[3])
{
    double s[3];
    for (int i = 0; i < 3; i++) {
        const int ax = ur->axes[2 * i + 1] - 'x';
        s[ax] = (ur->axes[2 * i] == '-' ? -1.0 : 1.0) * u[i];
    }
    const double x = s[2], ph = atan2(s[1], s[0]);
    double *q = malloc(sizeof(double) * (L + 1));
    ck_assert_ptr_nonnull(q);
    long double f = 0.0L;
    for (int m = 0; m <= L; m++) {
        truth_qlm_column(L, m, x, q); /* orthonormal, Condon-Shortley phase inside */
        const long double cm = cosl((long double)m * ph), sm = sinl((long double)m * ph);
        const long double ph_sign = !ur->cs && (m & 1) ? -1.0L : 1.0L;
        for (int l = m; l <= L; l++) {
            const long double nl = ur->norm == 1 ? sqrtl(4.0L * M_PI) : ur->norm == 2 ? sqrtl(4.0L * M_PI / (2 * l + 1)) : 1.0L;
            const long double qq = (long double)q[l - m] * (m ? M_SQRT2 : 1.0) * ph_sign * nl;
            /* the functions of m and −m: cos(mφ) and sin(mφ) */
            const long double fc = qq * (m ? cm : 1.0L), fs = qq * sm;
            int kc, ks; /* where the cos and the sin function sit */
            if (ur->index == 2) kc = l * l + (m ? 2 * m - 1 : 0), ks = l * l + 2 * m;
            else {
                const int mc = m == 0 ? 0 : ur->neg_cos ? -m : m, msn = -mc; /* the m each function carries */
                kc = ur->index == 1 ? l * (l + 1) - mc : l * (l + 1) + mc;
                ks = ur->index == 1 ? l * (l + 1) - msn : l * (l + 1) + msn;
            }
            f += c[kc] * fc;
            if (m) f += c[ks] * fs;
        }
    }
    free(q);
    return f;
}

/* The HEALPix-style complex layout (complex-half): a_lm for m ≥ 0 at
 * m(2L+1−m)/2 + l, interleaved re, im, of a real function
 * f = Σ_l [a_l0 Y_l0 + Σ_{m>0} 2 Re(a_lm Y_lm)], Y_lm = Q_l^m e^{imφ} with
 * the Condon-Shortley phase in Q (cs) or not (nocs: (−1)^m Q). */
static long double user_half_point(int cs, int L, const double *a, const double u[3])
{
    const double x = u[2], ph = atan2(u[1], u[0]);
    double *q = malloc(sizeof(double) * (L + 1));
    ck_assert_ptr_nonnull(q);
    long double f = 0.0L;
    for (int m = 0; m <= L; m++) {
        truth_qlm_column(L, m, x, q);
        const long double cm = cosl((long double)m * ph), sm = sinl((long double)m * ph);
        const long double sg = !cs && (m & 1) ? -1.0L : 1.0L;
        for (int l = m; l <= L; l++) {
            const size_t e = (size_t)m * (2 * L + 1 - m) / 2 + l;
            const long double re = a[2 * e], im = a[2 * e + 1], qq = sg * q[l - m];
            f += m ? 2.0L * qq * (re * cm - im * sm) : qq * re;
        }
    }
    free(q);
    return f;
}

/* convert --from SPEC for the real kinds at the top order: shlab's
 * coefficients converted to the user's convention (axes through an SH
 * rotation, the layout, the norm, the phase) represent the same function at
 * the same coordinates, against the definitions above. */
START_TEST(convert_specs_top)
{
    const int order = SHLAB_MAX_ORDER, L = order - 1;
    const size_t n = (size_t)order * order;
    static const user_real U[] = {
        {"real,nocs,4pi,mdesc,neg-cos,y-up", "+x+z-y", 0, 1, 1, 1},
        {"real,cs,schmidt,cossin", "+x+y+z", 1, 2, 0, 2}, /* no rotation: the layout and norm alone */
        {"real,cs,ortho,acn,y-up-lh", "+x+z+y", 1, 0, 0, 0},
    };
    double *c = malloc(sizeof(double) * n), *d = malloc(sizeof(double) * n);
    ck_assert(c && d);
    for (size_t i = 0; i < n; i++) c[i] = nrand();
    static const double dirs[2][3] = {{0.31, -0.52, 0.79}, {-0.66, 0.24, -0.71}};
    double worst = 0.0;
    for (size_t t = 0; t < sizeof U / sizeof *U; t++) {
        sh_conv cv;
        ck_assert_int_eq(sh_conv_parse(U[t].spec, &cv), SH_OK);
        ck_assert_int_eq(sh_conv_from_shlab(&cv, order, c, d), SH_OK);
        for (int j = 0; j < 2; j++) {
            const double nn = sqrt(dirs[j][0] * dirs[j][0] + dirs[j][1] * dirs[j][1] + dirs[j][2] * dirs[j][2]);
            const double u[3] = {dirs[j][0] / nn, dirs[j][1] / nn, dirs[j][2] / nn};
            /* shlab's function at the same coordinates, the user's in their basis */
            const long double f = truth_point(L, c, u[2], atan2(u[1], u[0]));
            const long double g = user_real_point(&U[t], L, d, u);
            /* scale: Σ|c y| ≈ √n·max|y| for unit random c; |y| ≤ √((2L+1)/4π) */
            const double scale = sqrt((double)n) * sqrt((2.0 * L + 1) / (4 * M_PI));
            worst = fmax(worst, (double)fabsl(f - g) / scale);
        }
    }
    /* the complex half layout, both phases (healpix = complex-half,cs) */
    double *a = malloc(sizeof(double) * (size_t)order * (order + 1));
    ck_assert_ptr_nonnull(a);
    for (int cs = 0; cs <= 1; cs++) {
        sh_conv cv;
        ck_assert_int_eq(sh_conv_parse(cs ? "healpix" : "complex-half,nocs", &cv), SH_OK);
        ck_assert_int_eq(sh_conv_from_shlab(&cv, order, c, a), SH_OK);
        for (int j = 0; j < 2; j++) {
            const double nn = sqrt(dirs[j][0] * dirs[j][0] + dirs[j][1] * dirs[j][1] + dirs[j][2] * dirs[j][2]);
            const double u[3] = {dirs[j][0] / nn, dirs[j][1] / nn, dirs[j][2] / nn};
            const long double f = truth_point(L, c, u[2], atan2(u[1], u[0])), g = user_half_point(cs, L, a, u);
            const double scale = sqrt((double)n) * sqrt((2.0 * L + 1) / (4 * M_PI));
            worst = fmax(worst, (double)fabsl(f - g) / scale);
        }
    }
    free(a);
    printf("test_ranges: convert shlab -> real specs (axes, layouts, norms, phase) and complex-half at order %d: "
           "function kept to %.3g of sqrt(n) max|y|\n", order, worst);
    ck_assert_msg(worst <= 1e-12, "convert specs at order %d: %.3g", order, worst);
    free(c);
    free(d);
}
END_TEST

/* identify at its largest order (SH_IDENTIFY_MAX_ORDER): a user's basis
 * built from the definitions above at the fixture's 32 directions is named,
 * for a convention that only the top bands' values pin down no better than
 * the others (ambix-like y-up with m-descending order and neg-cos). */
START_TEST(identify_top)
{
    const int order = SH_IDENTIFY_MAX_ORDER, L = order - 1, n = order * order;
    static const user_real U[] = {
        {"real,nocs,4pi,mdesc,neg-cos,y-up", "+x+z-y", 0, 1, 1, 1},
        {"real,cs,schmidt,cossin,+y+x-z", "+y+x-z", 1, 2, 0, 2},
    };
    double d[3 * SH_IDENTIFY_NDIRS], *v = malloc(sizeof(double) * SH_IDENTIFY_NDIRS * n), *e = calloc((size_t)n, sizeof(double));
    ck_assert(v && e);
    sh_identify_directions(d, NULL);
    for (size_t t = 0; t < sizeof U / sizeof *U; t++) {
        for (int j = 0; j < SH_IDENTIFY_NDIRS; j++)
            for (int k = 0; k < n; k++) {
                e[k] = 1.0;
                v[(size_t)j * n + k] = (double)user_real_point(&U[t], L, e, d + 3 * j);
                e[k] = 0.0;
            }
        sh_id_result r;
        ck_assert_int_eq(sh_identify_basis(SH_IDENTIFY_NDIRS, d, (size_t)n, v, order, 1e-4, &r), SH_OK);
        sh_conv want;
        ck_assert_int_eq(sh_conv_parse(U[t].spec, &want), SH_OK);
        int named = r.verdict == SH_ID_IDENTIFIED && !memcmp(&r.cand[0].conv, &want, sizeof want);
        for (int a = 0; r.verdict == SH_ID_IDENTIFIED && a < r.cand[0].naliases; a++)
            named |= !memcmp(&r.cand[0].aliases[a], &want, sizeof want);
        char got[96];
        printf("test_ranges: identify at order %d: '%s' named '%s' (residual %.3g)\n", order, U[t].spec,
               r.ncand ? sh_conv_format(&r.cand[0].conv, got, sizeof got) : "none", r.ncand ? r.cand[0].residual : -1.0);
        ck_assert_msg(named, "identify at order %d did not name %s", order, U[t].spec);
        sh_identify_free(&r);
    }
    free(v);
    free(e);
}
END_TEST

/* ------------------------------------------- closed forms of the lights */

/* Gauss-Legendre nodes and weights on [−1, 1] in long double: Newton on
 * P_n from the asymptotic guesses (GSL's glfixed tables are good to only
 * ~1e-10 at n in the thousands, too coarse for a truth here). */
static void gl_rule(int n, long double *x, long double *w)
{
    for (int k = 0; k < n; k++) {
        long double t = cosl(M_PI * (k + 0.75L) / (n + 0.5L)), dp = 0.0L;
        for (int it = 0, small = 0; it < 30 && small < 2; it++) {
            long double p0 = 1.0L, p1 = t;
            for (int j = 1; j < n; j++) {
                const long double p2 = ((2.0L * j + 1.0L) * t * p1 - j * p0) / (j + 1.0L);
                p0 = p1, p1 = p2;
            }
            dp = n * (t * p1 - p0) / (t * t - 1.0L);
            const long double dt = p1 / dp;
            t -= dt;
            if (fabsl(dt) < 1e-16L) small++; /* quadratic convergence: one more step is at rounding */
        }
        x[k] = t;
        w[k] = 2.0L / ((1.0L - t * t) * dp * dp);
    }
}

/* Gauss-Legendre (the rule x, w of n nodes) on [b − len, b] of f(x)·P_l(x)
 * for every l ≤ L at once (P_l by the unnormalised three-term recurrence in
 * long double, |P_l| ≤ 1): exact when f·P_l is a polynomial of degree < 2n.
 * The length is given apart so that a short interval is not rounded. */
static void gl_legendre_moments(const long double *x, const long double *w, int n, long double len, long double b,
                                double (*f)(double, void *), void *ctx, int L, long double *S)
{
    for (int l = 0; l <= L; l++) S[l] = 0.0L;
    const long double h = len / 2.0L, c = b - h;
    for (int k = 0; k < n; k++) {
        const long double xk = c + h * x[k];
        const long double wf = h * w[k] * f((double)xk, ctx);
        long double p0 = 1.0L, p1 = xk;
        S[0] += wf;
        if (L >= 1) S[1] += wf * p1;
        for (int l = 1; l < L; l++) {
            const long double p2 = ((2.0L * l + 1.0L) * xk * p1 - l * p0) / (l + 1.0L);
            p0 = p1, p1 = p2;
            S[l + 1] += wf * p2;
        }
    }
}

static double f_one(double x, void *ctx) { (void)x, (void)ctx; return 1.0; }
static double f_pow(double x, void *ctx) { return pow(x, *(const double *)ctx); }
static double f_lin(double x, void *ctx) { const double *ab = ctx; return ab[0] * x + ab[1]; }

/* ∫_0^1 x^e P_l(x) dx = √π Γ(1+e) / (2^{e+1} Γ(1+(e−l)/2) Γ((e+l+3)/2))
 * (Gradshteyn-Ryzhik 7.126.2) in long double log-gamma form with signs;
 * the library uses a ratio recursion instead. */
static long double lobe_gamma_form(double e, int l)
{
    int s1, s2, s3;
    const long double a = lgammal_r(1.0L + e, &s1), b = lgammal_r(1.0L + (e - l) / 2.0L, &s2),
                      c = lgammal_r((e + l + 3.0L) / 2.0L, &s3);
    return (long double)(s1 * s2 * s3) * sqrtl(M_PI) * expl(a - b - c - (e + 1.0L) * logl(2.0L));
}

/* The closed forms of cap:T, lobe:E and const:V at order 4097 (every band)
 * against Gauss-Legendre quadrature exact for their polynomial integrands
 * (cap: ∫_{cos T}^1 P_l; lobe with integer E: ∫_0^1 x^E P_l; 2200 nodes), and
 * for non-integer E against the gamma-function closed form.  Error relative
 * to the coefficient's bound 2πK_l·∫|f| (cap: 2πK_l(1 − cos T); lobe:
 * 2πK_l/(E+1)). */
START_TEST(closed_forms_top)
{
    const int order = SHLAB_MAX_ORDER, L = order - 1, NGL = 2200;
    double *z = malloc(sizeof(double) * order);
    long double *S = malloc(sizeof(long double) * order);
    long double *gx = malloc(sizeof(long double) * 2 * NGL), *gw = gx + NGL;
    ck_assert(z && S && gx);
    gl_rule(NGL, gx, gw);
    double wc = 0.0, wl = 0.0, wg = 0.0, wct = 0.0, wp = 0.0;
    int wcl = 0, wpl = 0;
    const double ts[] = {1e-3, 0.3, 1.0, 2.5, M_PI}; /* 1e-3 first: next to the pole */
    for (size_t k = 0; k < sizeof ts / sizeof *ts; k++) {
        ck_assert_int_eq(sh_cap_zonal(ts[k], order, z), SH_OK);
        const long double h = sinl(ts[k] / 2.0L);
        gl_legendre_moments(gx, gw, NGL, 2.0L * h * h, 1.0L, f_one, NULL, L, S); /* [cos T, 1] */
        for (int l = 0; l <= L; l++) {
            const double K = sqrt((2.0 * l + 1.0) / (4.0 * M_PI)), bound = 4.0 * M_PI * K * sin(ts[k] / 2) * sin(ts[k] / 2);
            const double e = fabs(z[l] - (double)(2.0L * M_PI * K * S[l])) / bound;
            if (ts[k] < 0.01) {
                if (!(e <= wp)) wp = e, wpl = l;
            } else if (!(e <= wc)) wc = e, wct = ts[k], wcl = l;
        }
    }
    const double es[] = {0.0, 1.0, 2.0, 7.0, 50.0};
    for (size_t k = 0; k < sizeof es / sizeof *es; k++) {
        ck_assert_int_eq(sh_lobe_zonal(es[k], order, z), SH_OK);
        gl_legendre_moments(gx, gw, NGL, 1.0L, 1.0L, f_pow, (void *)&es[k], L, S);
        for (int l = 0; l <= L; l++) {
            const double K = sqrt((2.0 * l + 1.0) / (4.0 * M_PI)), bound = 2.0 * M_PI * K / (es[k] + 1.0);
            const double e = fabs(z[l] - (double)(2.0L * M_PI * K * S[l])) / bound;
            if (!(e <= wl)) wl = e;
        }
    }
    /* non-integer exponents: the gamma form, relative to the value itself */
    const double eg[] = {0.5, 3.7, 1234.5};
    for (size_t k = 0; k < sizeof eg / sizeof *eg; k++) {
        ck_assert_int_eq(sh_lobe_zonal(eg[k], order, z), SH_OK);
        for (int l = 0; l <= L; l++) {
            const long double K = sqrtl((2.0L * l + 1.0L) / (4.0L * M_PI)), tr = 2.0L * M_PI * K * lobe_gamma_form(eg[k], l);
            /* values below double's normal range (E = 1234.5, l ~ 1190) may flush to 0 */
            const double e = fabsl(tr) < 1e-290L ? (fabs(z[l]) < 1e-290 ? 0.0 : 1.0) : (double)(fabsl(z[l] - tr) / fabsl(tr));
            if (!(e <= wg)) wg = e;
        }
    }
    /* const:V: c_0 = V√(4π), every other coefficient exactly 0 */
    sh_light cl = {SH_LIGHT_CONST, {2.5, 0.0}};
    double *c = malloc(sizeof(double) * (size_t)order * order);
    ck_assert_ptr_nonnull(c);
    ck_assert_int_eq(sh_light_closed_form(&cl, order, SH_CS, c), SH_OK);
    ck_close(c[0], 2.5 * sqrt(4.0 * M_PI), TOL1, 0.0, "const c0");
    size_t nonzero = 0;
    for (size_t i = 1; i < (size_t)order * order; i++) nonzero += c[i] != 0.0;
    ck_assert_msg(nonzero == 0, "const: %zu coefficients beyond c0 are not 0", nonzero);
    printf("test_ranges: closed forms at order %d: cap vs exact Gauss-Legendre: T = 0.3..pi %.3g (T = %g, l = %d), T = 1e-3 %.3g (l = %d), lobe (E = 0..50)"
           " %.3g of the bound 2 pi K_l int|f|; lobe E = 0.5, 3.7, 1234.5 vs gamma form %.3g relative; const exact\n",
           order, wc, wct, wcl, wp, wpl, wl, wg);
    /* the library evaluates P'_l at cos T rounded to double: next to the pole
     * (T = 1e-3, 1 − cos T = 5e-7) that rounding, 2e-10 of 1 − cos T, is
     * amplified through P'_l at high l; elsewhere the closed form is exact
     * to rounding */
    ck_assert_msg(wc <= 1e-13, "cap %.3g at T = %g, l = %d", wc, wct, wcl);
    ck_assert_msg(wp <= 2e-11, "cap %.3g at T = 1e-3, l = %d", wp, wpl);
    ck_assert_msg(wl <= 1e-13, "lobe %.3g", wl);
    ck_assert_msg(wg <= 1e-11, "lobe gamma form %.3g", wg);
    free(c);
    free(z);
    free(S);
    free(gx);
}
END_TEST

/* ------------------------------------------------ rotations at the top */

/* The z method at order 4097: about z by α, c'_m = c_m cos mα − c_{−m} sin mα,
 * c'_{−m} = c_m sin mα + c_{−m} cos mα (from y(φ − α)), mα in long double.
 * Max abs error on N(0, 1) coefficients. */
START_TEST(rot_z_top)
{
    const int order = SHLAB_MAX_ORDER;
    const size_t n = (size_t)order * order;
    double *c = malloc(sizeof(double) * n), *g = malloc(sizeof(double) * n);
    ck_assert(c && g);
    for (size_t i = 0; i < n; i++) c[i] = 2.0 * urand() - 1.0;
    const double alphas[] = {2.5, M_PI - 1e-9};
    double worst = 0.0;
    for (size_t a = 0; a < 2; a++) {
        sh_rot_plan *p;
        sh_rotation r;
        ck_assert_int_eq(sh_rotation_from_euler(alphas[a], 0.0, 0.0, &r), SH_OK);
        ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_Z, SH_PREC_DOUBLE, a ? SH_NOCS : SH_CS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &r), SH_OK);
        ck_assert_int_eq(sh_rot_plan_apply(p, c, g), SH_OK);
        sh_rot_plan_free(p);
        for (int l = 0; l < order; l++) {
            worst = fmax(worst, fabs(g[sh_index(l, 0)] - c[sh_index(l, 0)]));
            for (int m = 1; m <= l; m++) {
                const long double cm = cosl((long double)m * alphas[a]), sm = sinl((long double)m * alphas[a]);
                const double cp = c[sh_index(l, m)], cn = c[sh_index(l, -m)];
                const double e1 = fabs(g[sh_index(l, m)] - (double)(cp * cm - cn * sm));
                const double e2 = fabs(g[sh_index(l, -m)] - (double)(cp * sm + cn * cm));
                const double e = fmax(e1, e2);
                if (!(e <= worst)) worst = e;
            }
        }
    }
    printf("test_ranges: z rotation at order %d (alpha = 2.5, pi - 1e-9; all %zu coefficients, uniform in [-1,1]) vs cos/sin of"
           " m alpha: max abs error %.3g\n",
           order, n, worst);
    ck_assert_msg(worst <= 1e-13, "z at order %d: %.3g", order, worst);
    free(c);
    free(g);
}
END_TEST

/* Y_L^m(s) for m = −L..L (cs), from the truth Legendre functions. */
static void band_values(int L, double th, double ph, long double *Y)
{
    const double x = cos(th);
    Y[L] = truth_qlm(L, 0, x);
    for (int m = 1; m <= L; m++) {
        const long double q = M_SQRT2 * (long double)truth_qlm(L, m, x);
        Y[L + m] = q * cosl((long double)m * ph);
        Y[L - m] = q * sinl((long double)m * ph);
    }
}

/* The top band alone, l = 4096, rotated by halfpi (sh_rot_band_apply, the
 * kernel of every high-band rotation): the pointwise identity
 * Σ_m g_m Y_m(s) = Σ_m c_m Y_m(R⁻¹s) at three directions, both sides with the
 * truth Legendre functions (no code shared with the rotation), forward and
 * inverse (then g = R⁻¹c and the right side is at R s).  Relative to
 * Σ_m |c_m Y_m|.  Also d^l(π/2) (sh_wigner_d_halfpi) at l = 4096, whose
 * column m = 0 is d^l_{m'0}(π/2) = √(4π/(2l+1)) Q_l^{m'}(0) and row 0
 * d_{0m} = (−1)^m d_{m0}: max abs error. */
START_TEST(halfpi_top_band)
{
    const int L = LTOP, w = 2 * L + 1;
    double *c = malloc(sizeof(double) * w), *g = malloc(sizeof(double) * w);
    long double *Y = malloc(sizeof(long double) * w);
    ck_assert(c && g && Y);
    for (int i = 0; i < w; i++) c[i] = nrand();
    sh_rotation r;
    ck_assert_int_eq(sh_rotation_from_euler(-0.9, 0.8, 2.6, &r), SH_OK);
    const double dirs[][2] = {{0.4, 0.3}, {M_PI / 2, 1.0}, {2.2, 2.9}};
    double worst = 0.0;
    for (int inv = 0; inv < 2; inv++) {
        ck_assert_int_eq(sh_rot_band_apply(L, SH_CS, &r, inv, 1, c, g), SH_OK);
        for (size_t k = 0; k < sizeof dirs / sizeof *dirs; k++) {
            double s[3], u[3], tu, pu;
            sh_dir_from_angles(dirs[k][0], dirs[k][1], s);
            for (int i = 0; i < 3; i++) /* u = R⁻¹ s = Rᵀ s (inverse: u = R s) */
                u[i] = inv ? r.R[3 * i] * s[0] + r.R[3 * i + 1] * s[1] + r.R[3 * i + 2] * s[2]
                           : r.R[i] * s[0] + r.R[3 + i] * s[1] + r.R[6 + i] * s[2];
            ck_assert_int_eq(sh_angles_from_dir(u, &tu, &pu), SH_OK);
            long double lhs = 0.0L, rhs = 0.0L, scale = 0.0L;
            band_values(L, dirs[k][0], dirs[k][1], Y);
            for (int i = 0; i < w; i++) lhs += g[i] * Y[i];
            band_values(L, tu, pu, Y);
            for (int i = 0; i < w; i++) rhs += c[i] * Y[i], scale += fabsl(c[i] * Y[i]);
            worst = fmax(worst, (double)(fabsl(lhs - rhs) / scale));
        }
    }
    /* d^L(π/2), column 0 and row 0 */
    double *d = malloc(sizeof(double) * (size_t)(L + 1) * (L + 1));
    ck_assert_ptr_nonnull(d);
    ck_assert_int_eq(sh_wigner_d_halfpi(L, d), SH_OK);
    double wd = 0.0;
    const double f = sqrt(4.0 * M_PI / (2.0 * L + 1.0));
    for (int mp = 0; mp <= L; mp++) {
        const double t = f * truth_qlm(L, mp, 0.0);
        const double e = fmax(fabs(d[(size_t)mp * (L + 1)] - t), fabs(d[mp] - ((mp & 1) ? -t : t)));
        if (!(e <= wd)) wd = e;
    }
    printf("test_ranges: halfpi band %d (forward and inverse, 3 directions) vs pointwise identity with truth"
           " Legendre: %.3g of sum |c Y|; d^%d(pi/2) column and row 0 vs sqrt(4pi/(2l+1)) Q_l^m(0): max abs %.3g\n",
           L, worst, L, wd);
    ck_assert_msg(worst <= 1e-12, "halfpi band %d pointwise %.3g", L, worst);
    ck_assert_msg(wd <= 1e-14, "d^%d(pi/2) column 0: %.3g", L, wd);
    free(d);
    free(c);
    free(g);
    free(Y);
}
END_TEST

/* ------------------------------------------------- threads and batches */

/* --threads accepts up to 1024 (project, reconstruct, rotate) and 256 (the
 * scene commands), and the documentation promises the same result for every
 * count.  At the top counts against one thread, bit for bit: the fast
 * transforms (synthesis and analysis on a Gauss grid, three channels; the
 * lat-long reconstruction the CLI runs), the all-band rotation stream, and
 * the interreflected transfer of a procedural scene (Embree, 256 threads). */
START_TEST(threads_top)
{
    const int order = 300, nr = order + 1, np = 2 * order + 2, nchan = 3;
    const size_t n = (size_t)order * order, nm = (size_t)nr * np;
    double *x = malloc(sizeof(double) * nr), *w = malloc(sizeof(double) * nr);
    double *c = malloc(sizeof(double) * n * nchan), *map[2], *back[2];
    ck_assert(x && w && c);
    for (size_t i = 0; i < n * nchan; i++) c[i] = 2.0 * urand() - 1.0;
    sh_grid g;
    ck_assert_int_eq(sh_grid_gauss(nr, np, x, w, &g), SH_OK);
    const int counts[2] = {1, 1024};
    for (int t = 0; t < 2; t++) {
        map[t] = malloc(sizeof(double) * nm * nchan), back[t] = malloc(sizeof(double) * n * nchan);
        ck_assert(map[t] && back[t]);
        sh_sht *p;
        ck_assert_int_eq(sh_sht_create(order, &g, nchan, counts[t], &p), SH_OK);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, c, map[t]), SH_OK);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, map[t], back[t]), SH_OK);
        sh_sht_destroy(p);
    }
    ck_assert_msg(!memcmp(map[0], map[1], sizeof(double) * nm * nchan), "synthesis: 1024 threads differ from 1");
    ck_assert_msg(!memcmp(back[0], back[1], sizeof(double) * n * nchan), "analysis: 1024 threads differ from 1");
    double rt = 0.0; /* and the transform pair is right: the Gauss rule is exact at this size */
    for (size_t i = 0; i < n * nchan; i++) rt = fmax(rt, fabs(back[0][i] - c[i]));
    ck_assert_msg(rt <= 1e-12, "Gauss round trip %.3g", rt);
    /* reconstruction on a lat-long image (what `reconstruct --threads` runs) */
    sh_image im[2];
    const sh_window win = {SH_WINDOW_NONE, 0.0};
    for (int t = 0; t < 2; t++) {
        const sh_run_opts o = {counts[t], NULL, NULL};
        ck_assert_int_eq(sh_reconstruct_latlong_ex(order, SH_CS, c, nchan, &win, 1024, &o, &im[t]), SH_OK);
    }
    ck_assert(im[0].width == im[1].width && im[0].height == im[1].height);
    ck_assert_msg(!memcmp(im[0].data, im[1].data, sizeof(float) * (size_t)im[0].width * im[0].height * nchan),
                  "reconstruction: 1024 threads differ from 1");
    sh_image_free(&im[0]), sh_image_free(&im[1]);
    /* the all-band rotation */
    const int rorder = 401;
    const size_t rn = (size_t)rorder * rorder;
    double *v = malloc(sizeof(double) * rn * 2), *out[2];
    ck_assert_ptr_nonnull(v);
    for (size_t i = 0; i < 2 * rn; i++) v[i] = 2.0 * urand() - 1.0;
    sh_rotation rots[2];
    sh_rotation_from_euler(0.3, 1.1, -0.7, &rots[0]);
    sh_rotation_from_euler(-2.0, 2.9, 0.4, &rots[1]);
    for (int t = 0; t < 2; t++) {
        out[t] = malloc(sizeof(double) * rn * 4);
        ck_assert_ptr_nonnull(out[t]);
        sh_rot_stream *st;
        ck_assert_int_eq(sh_rot_stream_create(rorder, SH_CS, counts[t], &st), SH_OK);
        ck_assert_int_eq(sh_rot_stream_threads(st), counts[t]);
        ck_assert_int_eq(sh_rot_stream_apply(st, 2, rots, 0, 2, v, out[t]), SH_OK);
        sh_rot_stream_free(st);
    }
    ck_assert_msg(!memcmp(out[0], out[1], sizeof(double) * rn * 4), "rotation stream: 1024 threads differ from 1");
    /* a scene: interreflected transfer, 1 and 256 threads (the scene commands' top) */
    sh_proc_scene ps;
    sh_mesh m;
    ck_assert_int_eq(sh_proc_parse("box-open", &ps), SH_OK);
    ps.res = 3;
    ck_assert_int_eq(sh_mesh_procedural(&ps, &m), SH_OK);
    const int sorder = 3, sn = m.nvert * sorder * sorder;
    double *T[2];
    for (int t = 0; t < 2; t++) {
        sh_scene *sc;
        ck_assert_int_eq(sh_scene_create(&m, t ? 256 : 1, &sc), SH_OK);
        sh_transfer_opts o = {0};
        o.kind = SH_TRANSFER_INTERREFLECTED;
        o.order = sorder;
        o.rays = 64;
        o.albedo = 0.7;
        o.threads = t ? 256 : 1;
        T[t] = malloc(sizeof(double) * sn);
        ck_assert_ptr_nonnull(T[t]);
        sh_transfer_stats stt;
        ck_assert_int_eq(sh_transfer(sc, &o, T[t], &stt), SH_OK);
        ck_assert_int_eq(stt.threads, o.threads);
        sh_scene_free(sc);
    }
    ck_assert_msg(!memcmp(T[0], T[1], sizeof(double) * sn), "transfer: 256 threads differ from 1");
    printf("test_ranges: threads: SHT order %d (3 channels), lat-long reconstruction 1024 x 512, rotation stream"
           " order %d and interreflected transfer (%d vertices): 1024 (scene: 256) threads bitwise equal to 1;"
           " Gauss round trip %.3g\n",
           order, rorder, m.nvert, rt);
    sh_mesh_free(&m);
    for (int t = 0; t < 2; t++) free(map[t]), free(back[t]), free(out[t]), free(T[t]);
    free(x), free(w), free(c), free(v);
}
END_TEST

/* K rotations of K vectors in one call (sh_rot_plan_rotate_many, SIMD lanes
 * across rotations) and one rotation on K vectors (apply_many) at the top
 * of `bench --batch` (K = 1,000,000), order 3, double and float, zxzxz
 * and taylor1.5 with the auto kernel: every vector against the same
 * rotation applied alone by the loop kernels (sh_rot_plan_set_matrix,
 * sh_rot_plan_apply on a scalar plan: a second implementation). */
START_TEST(batch_top)
{
    const size_t K = 1000000;
    const int order = 3, nc = 9;
    double *R = malloc(sizeof(double) * 9 * K), *xin = malloc(sizeof(double) * nc * K), *y = malloc(sizeof(double) * nc * K);
    float *Rf = malloc(sizeof(float) * 9 * K), *xf = malloc(sizeof(float) * nc * K), *yf = malloc(sizeof(float) * nc * K);
    ck_assert(R && xin && y && Rf && xf && yf);
    for (size_t k = 0; k < K; k++) {
        sh_rotation r;
        sh_rotation_from_euler((2 * urand() - 1) * M_PI, urand() * M_PI, (2 * urand() - 1) * M_PI, &r);
        for (int j = 0; j < 9; j++) R[j * K + k] = r.R[j], Rf[j * K + k] = (float)r.R[j];
        for (int i = 0; i < nc; i++) xf[i * K + k] = (float)(xin[i * K + k] = 2 * urand() - 1);
    }
    const sh_rot_method ms[2] = {SH_ROT_ZXZXZ, SH_ROT_TAYLOR15};
    double wd = 0.0, wf = 0.0, wa = 0.0;
    int bad = 0; /* statuses, checked once (ck_assert in a loop of 10⁶ costs a write each) */
    for (int mi = 0; mi < 2; mi++)
        for (int prec = 0; prec < 2; prec++) {
            sh_rot_plan *p, *s;
            ck_assert_int_eq(sh_rot_plan_create_kernel(order, ms[mi], prec, SH_CS, SH_KERNEL_AUTO, &p), SH_OK);
            ck_assert_int_eq(sh_rot_plan_create_kernel(order, ms[mi], SH_PREC_DOUBLE, SH_CS, SH_KERNEL_SCALAR, &s), SH_OK);
            if (prec == SH_PREC_DOUBLE) ck_assert_int_eq(sh_rot_plan_rotate_many(p, K, R, xin, y), SH_OK);
            else ck_assert_int_eq(sh_rot_plan_rotate_many_f(p, K, Rf, xf, yf), SH_OK);
            double e = 0.0;
            for (size_t k = 0; k < K; k++) {
                double Rk[9], xk[9], yk[9], sc = 1.0;
                for (int j = 0; j < 9; j++) Rk[j] = prec ? (double)Rf[j * K + k] : R[j * K + k];
                for (int i = 0; i < nc; i++) xk[i] = prec ? (double)xf[i * K + k] : xin[i * K + k];
                bad |= sh_rot_plan_set_matrix(s, Rk) | sh_rot_plan_apply(s, xk, yk);
                for (int i = 0; i < nc; i++) sc = fmax(sc, fabs(yk[i])); /* Taylor outputs exceed 1 at large β */
                for (int i = 0; i < nc; i++) {
                    const double d = fabs((prec ? (double)yf[i * K + k] : y[i * K + k]) - yk[i]) / sc;
                    if (!(d <= e)) e = d;
                }
            }
            if (prec) wf = fmax(wf, e);
            else wd = fmax(wd, e);
            /* one rotation (the first) on all K vectors */
            if (prec == SH_PREC_DOUBLE) {
                double R0[9];
                for (int j = 0; j < 9; j++) R0[j] = R[j * K];
                ck_assert_int_eq(sh_rot_plan_set_matrix(p, R0), SH_OK);
                ck_assert_int_eq(sh_rot_plan_apply_many(p, K, xin, y), SH_OK);
                ck_assert_int_eq(sh_rot_plan_set_matrix(s, R0), SH_OK);
                for (size_t k = 0; k < K; k++) {
                    double xk[9], yk[9], sc = 1.0;
                    for (int i = 0; i < nc; i++) xk[i] = xin[i * K + k];
                    bad |= sh_rot_plan_apply(s, xk, yk);
                    for (int i = 0; i < nc; i++) sc = fmax(sc, fabs(yk[i]));
                    for (int i = 0; i < nc; i++) {
                        const double d = fabs(y[i * K + k] - yk[i]) / sc;
                        if (!(d <= wa)) wa = d;
                    }
                }
            }
            sh_rot_plan_free(p);
            sh_rot_plan_free(s);
        }
    ck_assert_int_eq(bad, SH_OK);
    printf("test_ranges: batches K = %zu (order %d, zxzxz and taylor1.5, auto kernel) vs the loop kernels one at a"
           " time: rotate_many double %.3g, float %.3g; apply_many double %.3g (max abs, of max(1, |y|))\n",
           K, order, wd, wf, wa);
    ck_assert_msg(wd <= 1e-14 && wa <= 1e-14, "double batches %.3g %.3g", wd, wa); /* FMA against none: a few ulps */
    ck_assert_msg(wf <= 2e-6, "float batch %.3g", wf);
    free(R), free(xin), free(y), free(Rf), free(xf), free(yf);
}
END_TEST

/* ------------------------------------------------------------- Wigner 3j */

/* log|(j j2 j3; 0 0 0)| closed form (Edmonds 3.7.17), long double lgamma. */
static long double w000_log(int j1, int j2, int j3, int *sign)
{
    const int L = j1 + j2 + j3, g = L / 2;
    *sign = (g & 1) ? -1 : 1;
    return 0.5L * (lgammal(L - 2 * j1 + 1.0L) + lgammal(L - 2 * j2 + 1.0L) + lgammal(L - 2 * j3 + 1.0L) -
                   lgammal(L + 2.0L)) +
           lgammal(g + 1.0L) - lgammal(g - j1 + 1.0L) - lgammal(g - j2 + 1.0L) - lgammal(g - j3 + 1.0L);
}

/* 3j symbols at the largest j the code accepts (j2, j3 ≤ 4·SHLAB_MAX_ORDER,
 * so families reach j = 2·16388): the family (j J J; 0 0 0) against its
 * closed form at every j; the orthogonality of two different families with
 * the same m1, Σ_j (2j+1) f(j) f'(j) = 0 (each family is normalised on its
 * own, so this checks their shapes); and at j = 4000 (the README's promise)
 * the orthogonality in m, Σ_{m1} (2j3+1) (j1 j2 j3; m1 m2 m3)² = 1 over
 * 6001 symbols of 6001 families. */
START_TEST(wigner3j_top)
{
    const int J = 4 * SHLAB_MAX_ORDER, nf = 2 * J + 1;
    double *f = malloc(sizeof(double) * nf), *h = malloc(sizeof(double) * nf);
    ck_assert(f && h);
    int jmin, jmax;
    ck_assert_int_eq(sh_wigner3j_family(J, J, 0, 0, &jmin, &jmax, f), SH_OK);
    ck_assert_int_eq(jmin, 0);
    ck_assert_int_eq(jmax, 2 * J);
    double w0 = 0.0;
    for (int j = 0; j <= 2 * J; j++) {
        double e;
        if (j & 1) e = fabs(f[j]); /* odd j + 2J: zero by parity */
        else {
            int sg;
            const long double lv = w000_log(j, J, J, &sg), t = sg * expl(lv);
            e = (double)(fabsl(f[j] - t) / fabsl(t));
        }
        if (!(e <= w0)) w0 = e;
    }
    /* cross-family orthogonality at the top */
    const int pairs[][4] = {{0, 0, 1, -1}, {17, -3, 5000, -4986}, {16000, -15612, 16388, -16000}};
    double wx = 0.0;
    for (size_t k = 0; k < sizeof pairs / sizeof *pairs; k++) {
        int a0, a1, b0, b1;
        ck_assert_int_eq(sh_wigner3j_family(J, J, pairs[k][0], pairs[k][1], &a0, &a1, f), SH_OK);
        ck_assert_int_eq(sh_wigner3j_family(J, J, pairs[k][2], pairs[k][3], &b0, &b1, h), SH_OK);
        ck_assert_int_eq(a1, b1);
        long double sum = 0.0L, sa = 0.0L;
        for (int j = (a0 > b0 ? a0 : b0); j <= a1; j++) {
            sum += (2.0L * j + 1.0L) * f[j - a0] * h[j - b0];
            sa += (2.0L * j + 1.0L) * f[j - a0] * f[j - a0];
        }
        ck_assert_msg(fabsl(sum) <= 1e-11L && fabsl(sa - 1.0L) <= 1e-11L, "families %zu: cross %.3Lg, norm - 1 %.3Lg", k,
                      fabsl(sum), fabsl(sa - 1.0L));
        wx = fmax(wx, (double)fabsl(sum));
        wx = fmax(wx, (double)fabsl(sa - 1.0L));
    }
    /* orthogonality in m at j = 4000 */
    const int j1 = 3000, j2 = 3000, j3 = 4000, m3 = 17;
    long double sm = 0.0L;
    for (int m1 = -j1; m1 <= j1; m1++) {
        const int m2 = -m1 - m3;
        if (abs(m2) > j2) continue;
        double v;
        ck_assert_int_eq(sh_wigner3j_e(j1, j2, j3, m1, m2, m3, &v), SH_OK);
        sm += (long double)v * v;
    }
    const double wm = (double)fabsl((2.0L * j3 + 1.0L) * sm - 1.0L);
    printf("test_ranges: 3j at j2 = j3 = %d (families to j = %d): (j J J; 0 0 0) vs closed form %.3g relative;"
           " cross-family orthogonality and norms %.3g; m-orthogonality at j = 4000: %.3g\n",
           J, 2 * J, w0, wx, wm);
    ck_assert_msg(w0 <= 1e-11, "(j J J; 0 0 0) %.3g", w0);
    ck_assert_msg(wx <= 1e-11, "cross-family orthogonality %.3g", wx);
    ck_assert_msg(wm <= 1e-11, "m-orthogonality %.3g", wm);
    /* beyond the limit: refused */
    ck_assert_int_eq(sh_wigner3j_family(J + 1, J, 0, 0, &jmin, &jmax, f), SH_EINVAL);
    free(f), free(h);
}
END_TEST

/* ----------------------------------------------------- stability bands */

/* `stability` takes bands up to 4000; halfpi, the method that reaches
 * them cheaply, at band 4000: a rotation is orthogonal and a homomorphism,
 * so both measures must be at rounding level over the whole set of 10
 * rotations (every row of the 8001-wide band probed). */
START_TEST(stability_top)
{
    typedef struct { sh_rot_stability_row r; int n; } one;
    one got = {{0}, 0};
    int keep(const sh_rot_stability_row *r, void *ctx);
    const int bands[1] = {4000};
    ck_assert_int_eq(sh_rot_stability(SH_ROT_HALFPI, SH_PREC_DOUBLE, SH_CS, 4000, bands, 1, -1, 128, 0, keep, &got),
                     SH_OK);
    ck_assert_int_eq(got.n, 1);
    printf("test_ranges: stability halfpi band 4000: orth (probe) %.3g, hom %.3g\n", got.r.orth, got.r.hom);
    ck_assert(got.r.band == 4000 && !got.r.broken);
    ck_assert_msg(got.r.orth <= 1e-13 && got.r.hom <= 1e-13, "band 4000: orth %.3g hom %.3g", got.r.orth, got.r.hom);
}
END_TEST
int keep(const sh_rot_stability_row *r, void *ctx)
{
    struct { sh_rot_stability_row r; int n; } *o = ctx;
    o->r = *r, o->n++;
    return 0;
}

/* -------------------------------------------------------------- scaling */

static int cmp_d(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* τ and τ′ of the families from docs/CONVENTIONS.md, written here again:
 * linear min(kθ, π); cone atan2(k sinθ, cosθ + (1−k) sinθ cotθ0) with
 * τ′ = k/(x² + y²) (x, y the atan2 arguments); midrange θ − asin(k sinθ). */
typedef struct {
    int family, energy, li, lj, m;
    double k, th0;
} scale_q;
static void my_tau(const scale_q *q, double th, double *tau, double *dtau)
{
    if (q->family == SH_SCALE_LINEAR) {
        const int in = q->k * th < M_PI;
        *tau = in ? q->k * th : M_PI, *dtau = in ? q->k : 0.0;
    } else if (q->family == SH_SCALE_CONE) {
        const double y = q->k * sin(th), x = cos(th) + (1.0 - q->k) * sin(th) / tan(q->th0);
        *tau = atan2(y, x), *dtau = q->k / (x * x + y * y);
    } else {
        const double s = q->k * sin(th);
        *tau = th - asin(s), *dtau = 1.0 - q->k * cos(th) / sqrt(1.0 - s * s);
    }
}
/* QAG's pieces: 0, π, the breaks the library reports (kinks and fast
 * turns of τ; they only split the domain) and 15 uniform points between,
 * so that no piece holds more than a few oscillations of Q_63. */
static size_t scale_points(const sh_scaling *sc, double *pts)
{
    size_t n = 0;
    pts[n++] = 0.0, pts[n++] = M_PI;
    n += (size_t)sh_scale_breaks(sc, pts + n);
    for (int j = 1; j < 16; j++) pts[n++] = M_PI * j / 16.0;
    qsort(pts, n, sizeof(double), cmp_d);
    size_t u = 1; /* drop repeats */
    for (size_t i = 1; i < n; i++)
        if (pts[i] > pts[u - 1]) pts[u++] = pts[i];
    return u;
}

static double scale_integrand(double th, void *ctx)
{
    const scale_q *q = ctx;
    double tau, dtau;
    my_tau(q, th, &tau, &dtau);
    const double psi = q->energy ? sin(tau) * dtau : sin(th);
    return truth_qlm(q->li, q->m, cos(th)) * truth_qlm(q->lj, q->m, cos(tau)) * psi;
}
/* ∫ F over [pts[0], pts[np−1]]: GSL's adaptive QAG (61-point Gauss-Kronrod)
 * on every piece between the points, summed; *err the sum of its error
 * estimates. */
static double qag_pieces(gsl_function *F, const double *pts, size_t np, gsl_integration_workspace *ws, double *err)
{
    double sum = 0.0;
    *err = 0.0;
    for (size_t i = 0; i + 1 < np; i++) {
        double v, e;
        const int st = gsl_integration_qag(F, pts[i], pts[i + 1], 1e-16, 1e-13, 1000, GSL_INTEG_GAUSS61, ws, &v, &e);
        ck_assert_msg(st == GSL_SUCCESS || st == GSL_EROUND, "QAG: %s", gsl_strerror(st));
        sum += v, *err += e;
    }
    return sum;
}
/* M_ij/(2π) by qag_pieces */
static double scale_truth(scale_q *q, const double *pts, size_t np, gsl_integration_workspace *ws, double *err)
{
    gsl_function F = {scale_integrand, q};
    return qag_pieces(&F, pts, np, ws, err);
}

/* The scaling matrices at the top of every range they accept: order 64
 * (SH_SCALE_MAX_ORDER, bands to 63), k at both ends of linear and cone
 * ([1e-3, 1e3]) and of midrange (±0.999), plain and energy-preserving.
 * Entries M_ij = 2π ∫ Q_li^m(cosθ) Q_lj^m(cos τ) ψ dθ (analytic φ) against
 * GSL's adaptive QAG on pieces split at the kinks of τ, Legendre from the
 * truth, τ written independently; and the full 4096 × 4096 matrix of one
 * case (pattern m_i = m_j, entries at their flat indices).  Error relative
 * to max(1, |M_ij|). */
START_TEST(scale_top)
{
    const int N = SH_SCALE_MAX_ORDER;
    const struct { int family; double k; } cases[] = {{SH_SCALE_LINEAR, SH_SCALE_K_MIN}, {SH_SCALE_LINEAR, SH_SCALE_K_MAX},
                                                      {SH_SCALE_CONE, SH_SCALE_K_MIN},   {SH_SCALE_CONE, SH_SCALE_K_MAX},
                                                      {SH_SCALE_MIDRANGE, -SH_SCALE_MIDRANGE_K_MAX},
                                                      {SH_SCALE_MIDRANGE, SH_SCALE_MIDRANGE_K_MAX}};
    const int ent[][3] = {{63, 63, 0}, {63, 0, 0}, {0, 63, 0}, {63, 61, 1}, {62, 63, 30}, {63, 63, 63}, {40, 63, 17}, {1, 1, 1}};
    double *I = malloc(sizeof(double) * sh_scale_integrals_n(N));
    ck_assert_ptr_nonnull(I);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    double worst = 0.0, worst_est = 0.0;
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++)
        for (int energy = 0; energy < 2; energy++) {
            /* both weights at the cone's ends (the hard ones), one each elsewhere */
            if (cases[c].family != SH_SCALE_CONE && energy != (int)(c & 1)) continue;
            sh_scaling sc = {(sh_scale_family)cases[c].family, cases[c].k, 0.0, energy};
            double br[SH_SCALE_MAX_BREAKS], pts[SH_SCALE_MAX_BREAKS + 18];
            const int nb = sh_scale_breaks(&sc, br);
            ck_assert_int_eq(sh_scale_integrals_tau(N, sh_scale_family_tau, &sc, energy, br, nb, I, NULL), SH_OK);
            const size_t np = scale_points(&sc, pts);
            for (size_t e = 0; e < sizeof ent / sizeof *ent; e++) {
                scale_q q = {cases[c].family, energy, ent[e][0], ent[e][1], ent[e][2], cases[c].k, M_PI / 4};
                double err;
                const double val = scale_truth(&q, pts, np, ws, &err);
                size_t off = 0;
                for (int mm = 0; mm < q.m; mm++) off += (size_t)(N - mm) * (N - mm);
                const double lib = 2.0 * M_PI * I[off + (size_t)(q.li - q.m) * (N - q.m) + (q.lj - q.m)];
                const double tr = 2.0 * M_PI * val, d = fabs(lib - tr) / fmax(1.0, fabs(tr));
                ck_assert_msg(d <= 1e-11 + 2.0 * M_PI * err, "%s k=%g energy %d (%d,%d,%d): %.17g vs QAG %.17g ± %.2g",
                              sh_scale_family_name(sc.family), sc.k, energy, q.li, q.lj, q.m, lib, tr, 2 * M_PI * err);
                worst = fmax(worst, d), worst_est = fmax(worst_est, 2.0 * M_PI * err);
            }
        }
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(ws);
    /* the whole matrix of one case: its pattern and its entries at the flat indices */
    const int n = N * N;
    double *M = malloc(sizeof(double) * (size_t)n * n);
    ck_assert_ptr_nonnull(M);
    sh_scaling sc = {SH_SCALE_CONE, SH_SCALE_K_MAX, 0.0, 1};
    ck_assert_int_eq(sh_scale_matrix(N, &sc, M, NULL), SH_OK);
    size_t off_pattern = 0;
    for (int i = 0; i < n; i++) {
        int li, mi;
        sh_index_lm(i, &li, &mi);
        for (int j = 0; j < n; j++) {
            int lj, mj;
            sh_index_lm(j, &lj, &mj);
            off_pattern += mi != mj && M[(size_t)i * n + j] != 0.0;
        }
    }
    ck_assert_msg(off_pattern == 0, "%zu entries off the m_i = m_j pattern", off_pattern);
    double wm = 0.0;
    for (size_t e = 0; e < sizeof ent / sizeof *ent; e += 2) /* every other entry, both signs of m */
        for (int sg = -1; sg <= 1; sg += 2) {
            scale_q q = {SH_SCALE_CONE, 1, ent[e][0], ent[e][1], ent[e][2], SH_SCALE_K_MAX, M_PI / 4};
            if (sg < 0 && !q.m) continue;
            double val = 0.0, err = 0.0, pts[SH_SCALE_MAX_BREAKS + 18];
            const size_t np = scale_points(&sc, pts);
            gsl_integration_workspace *w2 = gsl_integration_workspace_alloc(1000);
            gsl_error_handler_t *o2 = gsl_set_error_handler_off();
            val = scale_truth(&q, pts, np, w2, &err);
            gsl_set_error_handler(o2);
            gsl_integration_workspace_free(w2);
            const double lib = M[(size_t)sh_index(q.li, sg * q.m) * n + sh_index(q.lj, sg * q.m)];
            wm = fmax(wm, fabs(lib - 2.0 * M_PI * val) / fmax(1.0, fabs(2.0 * M_PI * val)));
        }
    printf("test_ranges: scaling order %d, linear and cone k = %g and %g, midrange k = +-%g, plain and energy (cone: both at each end): entries"
           " (bands to 63) vs QAG %.3g (QAG's own estimate up to %.2g); full matrix (cone k = %g, energy): pattern"
           " exact, entries %.3g\n",
           N, SH_SCALE_K_MIN, SH_SCALE_K_MAX, SH_SCALE_MIDRANGE_K_MAX, worst, worst_est, SH_SCALE_K_MAX, wm);
    ck_assert_msg(wm <= 1e-11, "full matrix entries %.3g", wm);
    free(M), free(I);
}
END_TEST

/* ------------------------------------------- derivatives and Taylor */

/* sh_rot_deriv_recursion at its largest order (SH_DERIV_MAX_ORDER = 32,
 * `deriv`'s top; it was 64, where the two agree only to 1.1e-11):
 * Křivánek's Appendix A recursion against the
 * generator R_Y(β)·J^k (zxzxz and the closed-form J), two methods that
 * share no code, for k = 1, 2, 3 at β = 0.7 and π, both conventions.
 * Error relative to the largest entry. */
START_TEST(deriv_top)
{
    const int N = SH_DERIV_MAX_ORDER;
    const size_t nb = sh_rot_block_offset(N);
    double *a = malloc(sizeof(double) * nb), *b = malloc(sizeof(double) * nb);
    ck_assert(a && b);
    double worst = 0.0;
    const double betas[] = {0.7, M_PI};
    for (int conv = 0; conv < 2; conv++)
        for (int k = 1; k <= 3; k++)
            for (int q = 0; q < 2; q++) {
                ck_assert_int_eq(sh_rot_deriv_recursion(N, k, betas[q], (sh_convention)conv, a), SH_OK);
                ck_assert_int_eq(sh_rot_deriv_generator(N, k, betas[q], (sh_convention)conv, b), SH_OK);
                double mx = 0.0, d = 0.0;
                for (size_t i = 0; i < nb; i++) mx = fmax(mx, fabs(b[i]));
                for (size_t i = 0; i < nb; i++) {
                    const double e = fabs(a[i] - b[i]);
                    if (!(e <= d)) d = e;
                }
                worst = fmax(worst, d / mx);
            }
    printf("test_ranges: rotation derivatives at order %d (k = 1..3, beta = 0.7, pi, cs and nocs): recursion vs"
           " generator %.3g of the largest entry\n",
           N, worst);
    ck_assert_msg(worst <= 1e-13, "derivatives at order %d: %.3g", N, worst);
    free(a), free(b);
}
END_TEST

/* The Taylor rotations at the largest order they accept (128, the top of
 * `taylor-error --order`) and β = π (the top of its β range):
 *  - J (sh_rot_deriv_J_band) against an exact rotation: blanco's single
 *    bands, (R_Y(h) − R_Y(−h))/2h = J + h²J³/6 + O(h⁴), at bands 1, 64, 127;
 *  - the plans' blocks against I + βJ (+ β²/2 diag(J²), + β²/2 J²) built
 *    here from that J, every band;
 *  - sh_taylor_error's max and mean singular value and lobe error (taylor1.5:
 *    at order 128 the call itself takes 10 s) against
 *    D = R_Y(β) − T(β) (R_Y from blanco, not the zxzxz the library uses),
 *    its singular values from the eigenvalues of DᵀD (GSL's symmetric
 *    eigensolver, not the one-sided Jacobi SVD);
 *  - the planner's error engine (`plan`, order ≤ 64, zxzxz as its truth
 *    above 32) at order 64 against the same construction. */
static void dense_mul(int w, const double *A, const double *B, double *C)
{
    memset(C, 0, sizeof(double) * (size_t)w * w);
    for (int i = 0; i < w; i++)
        for (int q = 0; q < w; q++) {
            const double a = A[(size_t)i * w + q];
            for (int j = 0; j < w; j++) C[(size_t)i * w + j] += a * B[(size_t)q * w + j];
        }
}
static void taylor_block(sh_rot_method t, int w, double beta, const double *J, const double *J2, double *T)
{
    for (int i = 0; i < w; i++)
        for (int j = 0; j < w; j++) {
            const size_t q = (size_t)i * w + j;
            T[q] = (i == j) + beta * J[q];
            if (t == SH_ROT_TAYLOR2 || (t == SH_ROT_TAYLOR15 && i == j)) T[q] += 0.5 * beta * beta * J2[q];
        }
}
/* The singular values of a w×w block D: square roots of the eigenvalues of
 * DᵀD (GSL's symmetric eigensolver) into sv. */
static void block_sv(int w, const double *D, gsl_matrix *M, gsl_vector *ev, double *sv)
{
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc((size_t)w);
    gsl_matrix_view Mv = gsl_matrix_submatrix(M, 0, 0, (size_t)w, (size_t)w);
    gsl_vector_view ew = gsl_vector_subvector(ev, 0, (size_t)w);
    gsl_matrix_set_zero(&Mv.matrix);
    for (int q = 0; q < w; q++)
        for (int i = 0; i < w; i++) {
            const double a = D[(size_t)q * w + i];
            double *row = gsl_matrix_ptr(&Mv.matrix, (size_t)i, 0);
            for (int j = 0; j < w; j++) row[j] += a * D[(size_t)q * w + j];
        }
    ck_assert_int_eq(gsl_eigen_symm(&Mv.matrix, &ew.vector, ws), 0);
    gsl_eigen_symm_free(ws);
    for (int i = 0; i < w; i++) sv[i] = sqrt(fmax(0.0, gsl_vector_get(&ew.vector, (size_t)i)));
}
START_TEST(taylor_top)
{
    const int N = 128, W = 2 * N - 1;
    const double beta = M_PI;
    const sh_rot_method T3[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};
    ck_assert_int_eq(sh_rot_method_max_order(SH_ROT_TAYLOR1), N);
    double *J = malloc(sizeof(double) * W * W * 6), *J2 = J + W * W, *R = J2 + W * W, *T = R + W * W, *A = T + W * W,
           *B = A + W * W;
    const size_t nb = sh_rot_block_offset(N);
    double *blk[3];
    for (int t = 0; t < 3; t++) blk[t] = malloc(sizeof(double) * nb);
    ck_assert(J && blk[0] && blk[1] && blk[2]);
    /* J against the exact rotation */
    double wj = 0.0;
    const int jb[3] = {1, 64, 127};
    for (int k = 0; k < 3; k++) {
        const int l = jb[k], w = 2 * l + 1;
        const double h = 1e-5;
        sh_rotation rp, rm;
        sh_rotation_from_euler(0, h, 0, &rp);
        sh_rotation_from_euler(0, -h, 0, &rm); /* β < 0: the same rotation as (π, h, π) */
        ck_assert_int_eq(sh_rot_deriv_J_band(l, SH_CS, J), SH_OK);
        dense_mul(w, J, J, J2);
        dense_mul(w, J2, J, A); /* J³ */
        ck_assert_int_eq(sh_rot_band(l, SH_ROT_BLANCO, SH_PREC_DOUBLE, SH_CS, &rp, R), SH_OK);
        ck_assert_int_eq(sh_rot_band(l, SH_ROT_BLANCO, SH_PREC_DOUBLE, SH_CS, &rm, B), SH_OK);
        for (int i = 0; i < w * w; i++) wj = fmax(wj, fabs((R[i] - B[i]) / (2 * h) - J[i] - h * h / 6 * A[i]) / l);
    }
    /* the plans' blocks, and the error measures */
    sh_rotation rot;
    sh_rotation_from_euler(0, beta, 0, &rot);
    for (int t = 0; t < 3; t++) {
        sh_rot_plan *p;
        ck_assert_int_eq(sh_rot_plan_create(N, T3[t], SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &rot), SH_OK);
        ck_assert_int_eq(sh_rot_plan_blocks(p, blk[t]), SH_OK);
        sh_rot_plan_free(p);
    }
    double z[128];
    ck_assert_int_eq(sh_lobe_zonal(7, N, z), SH_OK);
    double zn = 0.0;
    for (int l = 0; l < N; l++) zn += z[l] * z[l];
    gsl_matrix *M = gsl_matrix_alloc(W, W);
    gsl_vector *ev = gsl_vector_alloc(W);
    double wb = 0.0, wm[3] = {0}, wmean[3] = {0}, wl[3] = {0}, smax[3] = {0}, ssum[3] = {0}, lobe2[3] = {0};
    double smax64[3] = {0}, ssum64[3] = {0}, lobe64[3] = {0}, z64[64], zn64 = 0.0, sv[2 * 128];
    ck_assert_int_eq(sh_lobe_zonal(7, 64, z64), SH_OK);
    for (int l = 0; l < 64; l++) zn64 += z64[l] * z64[l];
    for (int l = 0; l < N; l++) {
        const int w = 2 * l + 1;
        ck_assert_int_eq(sh_rot_deriv_J_band(l, SH_CS, J), SH_OK);
        dense_mul(w, J, J, J2);
        ck_assert_int_eq(sh_rot_band(l, SH_ROT_BLANCO, SH_PREC_DOUBLE, SH_CS, &rot, R), SH_OK);
        for (int t = 0; t < 3; t++) {
            taylor_block(T3[t], w, beta, J, J2, T);
            const double *P = blk[t] + sh_rot_block_offset(l);
            double sc = 1.0;
            for (int i = 0; i < w * w; i++) sc = fmax(sc, fabs(T[i]));
            for (int i = 0; i < w * w; i++) wb = fmax(wb, fabs(P[i] - T[i]) / sc);
            if (l >= 64 && T3[t] != SH_ROT_TAYLOR15) continue; /* sh_taylor_error at 128: taylor1.5 alone (10 s each) */
            for (int i = 0; i < w * w; i++) A[i] = R[i] - T[i];
            block_sv(w, A, M, ev, sv);
            double lc = 0.0; /* ‖D c‖² of the band: c has only m = 0 (column l) */
            for (int i = 0; i < w; i++) lc += A[(size_t)i * w + l] * A[(size_t)i * w + l];
            for (int i = 0; i < w; i++) {
                smax[t] = fmax(smax[t], sv[i]), ssum[t] += sv[i];
                if (l < 64) smax64[t] = fmax(smax64[t], sv[i]), ssum64[t] += sv[i];
            }
            lobe2[t] += lc * z[l] * z[l] / zn;
            if (l < 64) lobe64[t] += lc * z64[l] * z64[l] / zn64;
        }
    }
    double we = 0.0, wemean = 0.0;
    sh_rot_errws *ew;
    ck_assert_int_eq(sh_rot_errws_create(64, 7, 0, &ew), SH_OK);
    ck_assert_int_eq(sh_rot_errws_set(ew, &rot), SH_OK);
    for (int t = 0; t < 3; t++) {
        if (T3[t] == SH_ROT_TAYLOR15) {
            sh_taylor_err te;
            ck_assert_int_eq(sh_taylor_error(N, T3[t], beta, 7, &te), SH_OK);
            wm[t] = fabs(te.max - smax[t]) / smax[t];
            wmean[t] = fabs(te.mean - ssum[t] / (N * N)) / (ssum[t] / (N * N));
            wl[t] = fabs(te.lobe - sqrt(lobe2[t])) / sqrt(lobe2[t]);
        }
        /* the planner's engine at its top order (zxzxz truth above 32) */
        sh_rot_error re;
        ck_assert_int_eq(sh_rot_errws_eval(ew, T3[t], SH_PREC_DOUBLE, &re), SH_OK);
        we = fmax(we, fabs(re.max - smax64[t]) / smax64[t]);
        we = fmax(we, fabs(re.lobe - sqrt(lobe64[t])) / sqrt(lobe64[t]));
        wemean = fmax(wemean, fabs(re.mean - ssum64[t] / (64 * 64)) / (ssum64[t] / (64 * 64)));
    }
    sh_rot_errws_free(ew);
    printf("test_ranges: Taylor at order %d, beta = pi: J vs exact rotation (central difference) %.3g of l;"
           " plan blocks (taylor1, 1.5, 2) vs I + bJ (+ b^2/2 diag J^2, J^2) %.3g; taylor_error (taylor1.5) vs"
           " eig(D^T D) with blanco: max %.3g, mean %.3g, lobe %.3g (relative); plan's error engine at order 64"
           " (3 methods): max and lobe %.3g, mean %.3g\n",
           N, wj, wb, wm[1], wmean[1], wl[1], we, wemean);
    ck_assert_msg(wj <= 1e-9, "J vs exact rotation %.3g", wj);
    ck_assert_msg(wb <= 1e-13, "plan blocks %.3g", wb);
    /* the mean: an eigenvalue of DᵀD fixes a small σ only to √ε·σ_max (as
     * test_taylor.c's test_error_measures allows) */
    for (int t = 0; t < 3; t++)
        ck_assert_msg(wm[t] <= 1e-12 && wmean[t] <= 1e-7 && wl[t] <= 1e-12, "%s: max %.3g mean %.3g lobe %.3g",
                      sh_rot_method_name(T3[t]), wm[t], wmean[t], wl[t]);
    ck_assert_msg(we <= 1e-12 && wemean <= 1e-7, "plan engine at order 64: %.3g, mean %.3g", we, wemean);
    gsl_matrix_free(M), gsl_vector_free(ev);
    for (int t = 0; t < 3; t++) free(blk[t]);
    free(J);
}
END_TEST

/* ------------------------------------------------------ triple products */

/* Green's transfer matrix at `triple`'s top order (32; the light to band
 * 62): M (Gaunt coefficients, Wigner 3j) against the exact quadrature of
 * ∫ b y_i y_j on a Gauss grid of 64 rings × 128 points (exact for total
 * band < 128: here ≤ 124), every column j as the analysis of b·y_j by the
 * fast transform.  Relative to max|M|. */
START_TEST(triple_top)
{
    const int N = 32, BO = 2 * N - 1, n = N * N, nr = 64, np = 128;
    double *b = malloc(sizeof(double) * BO * BO), *M = malloc(sizeof(double) * (size_t)n * n);
    double *x = malloc(sizeof(double) * nr), *w = malloc(sizeof(double) * nr);
    double *fb = malloc(sizeof(double) * nr * np), *map = malloc(sizeof(double) * nr * np), *col = malloc(sizeof(double) * n);
    double *e = calloc((size_t)n, sizeof(double));
    ck_assert(b && M && x && w && fb && map && col && e);
    for (int i = 0; i < BO * BO; i++) b[i] = (2.0 * urand() - 1.0) / (1.0 + sqrt((double)i));
    double worst = 0.0;
    for (int conv = 0; conv < 2; conv++) {
        ck_assert_int_eq(sh_triple_matrix(N, (sh_convention)conv, b, BO, M), SH_OK);
        sh_grid g;
        ck_assert_int_eq(sh_grid_gauss(nr, np, x, w, &g), SH_OK);
        sh_sht *pb, *p;
        ck_assert_int_eq(sh_sht_create(BO, &g, 1, 1, &pb), SH_OK);
        ck_assert_int_eq(sh_sht_synthesis(pb, (sh_convention)conv, b, fb), SH_OK);
        sh_sht_destroy(pb);
        ck_assert_int_eq(sh_sht_create(N, &g, 1, 1, &p), SH_OK);
        double mx = 0.0, d = 0.0;
        for (int i = 0; i < n * n; i++) mx = fmax(mx, fabs(M[i]));
        for (int j = 0; j < n; j++) {
            e[j] = 1.0;
            ck_assert_int_eq(sh_sht_synthesis(p, (sh_convention)conv, e, map), SH_OK);
            e[j] = 0.0;
            for (int q = 0; q < nr * np; q++) map[q] *= fb[q];
            ck_assert_int_eq(sh_sht_analysis(p, (sh_convention)conv, map, col), SH_OK);
            for (int i = 0; i < n; i++) {
                const double t = fabs(M[(size_t)i * n + j] - col[i]);
                if (!(t <= d)) d = t;
            }
        }
        sh_sht_destroy(p);
        worst = fmax(worst, d / mx);
    }
    printf("test_ranges: triple product order %d (light to band %d, cs and nocs): Gaunt matrix vs exact quadrature"
           " %.3g of max|M|\n",
           N, BO - 1, worst);
    ck_assert_msg(worst <= 1e-13, "triple order %d: %.3g", N, worst);
    free(b), free(M), free(x), free(w), free(fb), free(map), free(col), free(e);
}
END_TEST

/* ------------------------------------------------------ scene closed forms */

/* ∫ over the cap of half-angle a about u of y_i(s)·(n·s) dΩ, every i < N²,
 * added to acc with weight sg: Gauss-Legendre (long double rule) in cos θ'
 * on [cos a, 1] and uniform φ' about u, exact for the polynomial integrand
 * of degree ≤ N (40 × 80 nodes for N ≤ 32). */
static void cap_moments(int N, const double u[3], double a, const double n[3], double sg, long double *gx,
                        long double *gw, int ng, double *y, long double *acc)
{
    double e1[3], e2[3];
    const double t[3] = {fabs(u[0]) < 0.9 ? 1.0 : 0.0, fabs(u[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    e1[0] = t[1] * u[2] - t[2] * u[1], e1[1] = t[2] * u[0] - t[0] * u[2], e1[2] = t[0] * u[1] - t[1] * u[0];
    const double ne = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int i = 0; i < 3; i++) e1[i] /= ne;
    e2[0] = u[1] * e1[2] - u[2] * e1[1], e2[1] = u[2] * e1[0] - u[0] * e1[2], e2[2] = u[0] * e1[1] - u[1] * e1[0];
    const long double h = (1.0L - cosl(a)) / 2.0L, c = 1.0L - h;
    const int nphi = 80;
    for (int k = 0; k < ng; k++) {
        const long double xc = c + h * gx[k], sn = sqrtl(1.0L - xc * xc);
        for (int q = 0; q < nphi; q++) {
            const double ph = 2.0 * M_PI * q / nphi, cp = cos(ph), sp = sin(ph);
            double s[3];
            for (int i = 0; i < 3; i++) s[i] = (double)(xc * u[i] + sn * (cp * e1[i] + sp * e2[i]));
            ck_assert_int_eq(sh_eval_dir(N, SH_CS, s, y), SH_OK);
            const long double wgt = sg * h * gw[k] * (2.0L * M_PI / nphi) * (n[0] * s[0] + n[1] * s[1] + n[2] * s[2]);
            for (int i = 0; i < N * N; i++) acc[i] += wgt * y[i];
        }
    }
}

/* The scene commands' top order (32: transfer, render, cache, scene-plan):
 * the closed forms the scenes are checked against, against quadrature —
 * sh_transfer_unshadowed for tilted normals ((ρ/π) ∫_{n·s>0} y_i n·s) and
 * sh_proc_closed_form at the sphere-plane's plane vertices (the hemisphere
 * minus the sphere's cap of half-angle asin(R/d) about the direction to the
 * centre, every coefficient).  Max abs error. */
START_TEST(scene_top)
{
    const int N = 32, n2 = N * N, NG = 40;
    long double *gx = malloc(sizeof(long double) * 2 * NG), *gw = gx + NG;
    long double *acc = malloc(sizeof(long double) * n2);
    double *y = malloc(sizeof(double) * n2), *t = malloc(sizeof(double) * n2);
    ck_assert(gx && acc && y && t);
    gl_rule(NG, gx, gw);
    const double rho = 0.8;
    double wu = 0.0, wc = 0.0;
    const double normals[][3] = {{0, 0, 1}, {0.3, -0.5, 0.81}, {-0.9, 0.1, -0.2}};
    for (int k = 0; k < 3; k++) {
        double nn[3], len = sqrt(normals[k][0] * normals[k][0] + normals[k][1] * normals[k][1] + normals[k][2] * normals[k][2]);
        for (int i = 0; i < 3; i++) nn[i] = normals[k][i] / len;
        ck_assert_int_eq(sh_transfer_unshadowed(N, SH_CS, rho, nn, t), SH_OK);
        for (int i = 0; i < n2; i++) acc[i] = 0.0L;
        cap_moments(N, nn, M_PI / 2, nn, 1.0, gx, gw, NG, y, acc);
        for (int i = 0; i < n2; i++) wu = fmax(wu, fabs(t[i] - (double)(rho / M_PI * acc[i])));
    }
    sh_proc_scene ps;
    sh_mesh m;
    ck_assert_int_eq(sh_proc_parse("sphere-plane", &ps), SH_OK);
    ck_assert_int_eq(sh_mesh_procedural(&ps, &m), SH_OK);
    const double up[3] = {0, 0, 1}, R = ps.p[0], H = ps.p[1];
    int tested = 0;
    for (int v = 0; v < m.nvert && tested < 24; v += 37) {
        int known = 0;
        ck_assert_int_eq(sh_proc_closed_form(&ps, &m, v, N, SH_CS, rho, 0.0, t, NULL, &known), SH_OK);
        if (known != N) continue;
        const double *p = m.pos + 3 * v;
        double u[3] = {-p[0], -p[1], H - p[2]};
        const double d = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int i = 0; i < 3; i++) u[i] /= d;
        for (int i = 0; i < n2; i++) acc[i] = 0.0L;
        cap_moments(N, up, M_PI / 2, up, 1.0, gx, gw, NG, y, acc);
        cap_moments(N, u, asin(R / d), up, -1.0, gx, gw, NG, y, acc);
        for (int i = 0; i < n2; i++) wc = fmax(wc, fabs(t[i] - (double)(rho / M_PI * acc[i])));
        tested++;
    }
    sh_mesh_free(&m);
    printf("test_ranges: scene closed forms at order %d: unshadowed transfer (3 normals) vs quadrature %.3g,"
           " sphere-plane shadowed transfer (%d plane vertices) %.3g (max abs)\n",
           N, wu, tested, wc);
    ck_assert_int_ge(tested, 10);
    ck_assert_msg(wu <= 1e-13 && wc <= 1e-13, "scene closed forms: %.3g %.3g", wu, wc);
    free(gx), free(acc), free(y), free(t);
}
END_TEST

/* --------------------------------------------------- Green's light */

/* sh_green_reference at its largest order (64): Green's light is the sum
 * of two clamped linear lobes, max(0, 5 s·ẑ − 4) + max(0, 4 s·d − 3) with
 * d = (cos 2.5, sin 2.5, 0) (−4 sin(θ − π) cos(φ − 2.5) = 4 s·d), each
 * zonal about its axis, so by Funk-Hecke c_lm = 2π Σ_lobes y_lm(axis)
 * ∫_{b/a}^1 (a x − b) P_l(x) dx, the integral exact by Gauss-Legendre of a
 * polynomial (the library integrates in θ by QAGP with analytic φ sums).
 * Max abs error. */
START_TEST(green_top)
{
    const int N = 64, n = N * N, NG = 40;
    double *ref = malloc(sizeof(double) * n), *y1 = malloc(sizeof(double) * n), *y2 = malloc(sizeof(double) * n);
    long double *gx = malloc(sizeof(long double) * 2 * NG), *gw = gx + NG, *S1 = malloc(sizeof(long double) * 2 * N),
                *S2 = S1 + N;
    ck_assert(ref && y1 && y2 && gx && S1);
    gl_rule(NG, gx, gw);
    const double z[3] = {0, 0, 1}, d[3] = {cos(2.5), sin(2.5), 0.0};
    double lin[2][2] = {{5.0, -4.0}, {4.0, -3.0}};
    gl_legendre_moments(gx, gw, NG, 1.0L - 4.0L / 5.0L, 1.0L, f_lin, lin[0], N - 1, S1);
    gl_legendre_moments(gx, gw, NG, 1.0L - 3.0L / 4.0L, 1.0L, f_lin, lin[1], N - 1, S2);
    double worst = 0.0;
    for (int conv = 0; conv < 2; conv++) {
        ck_assert_int_eq(sh_green_reference(N, (sh_convention)conv, 1e-12, ref), SH_OK);
        ck_assert_int_eq(sh_eval_dir(N, (sh_convention)conv, z, y1), SH_OK);
        ck_assert_int_eq(sh_eval_dir(N, (sh_convention)conv, d, y2), SH_OK);
        for (int i = 0; i < n; i++) {
            int l, m;
            sh_index_lm(i, &l, &m);
            const double t = (double)(2.0L * M_PI * (S1[l] * y1[i] + S2[l] * y2[i]));
            worst = fmax(worst, fabs(ref[i] - t));
        }
    }
    printf("test_ranges: Green's light, reference projection at order %d (cs, nocs) vs Funk-Hecke of its two lobes:"
           " max abs error %.3g\n",
           N, worst);
    ck_assert_msg(worst <= 1e-12, "green reference %.3g", worst);
    free(ref), free(y1), free(y2), free(gx), free(S1);
}
END_TEST

/* ---------------------------------------------------------------- images */

/* The largest image (SH_IMAGE_MAX_PIXELS = 2²⁶ pixels) as a lat-long
 * environment, 11584 × 5792 (the largest width whose W × W/2 fits):
 *  - reconstruction of a few bands, m = 0, 17, 63 (sh_reconstruct_latlong_ex,
 *    the transform `reconstruct` runs) against the function evaluated at
 *    every pixel centre with the truth Legendre functions;
 *  - projection of that image (sh_project_image_ex, `project --exr`)
 *    against its definition Σ_pixels L y(centre) Ω for those coefficients,
 *    summed here pixel by pixel with exact solid angles (2π/W)(cos θ_top −
 *    cos θ_bottom);
 *  - reading it from an uncompressed EXR file written by OpenEXR's C++
 *    library: every pixel bitwise;
 *  - one pixel more is refused, by the reconstruction and the writer. */
START_TEST(image_top)
{
    const int W = 11584, H = W / 2, order = 64;
    ck_assert((long long)W * H <= SH_IMAGE_MAX_PIXELS && (long long)(W + 2) * (H + 1) > SH_IMAGE_MAX_PIXELS);
    const int sel[][2] = {{0, 0}, {63, 0}, {63, -63}, {40, 17}, {63, 62}};
    const double val[] = {2.0, 1.0, 0.5, -0.7, 0.3};
    const int ns = 5;
    double *c = calloc((size_t)order * order, sizeof(double)), *cc = malloc(sizeof(double) * order * order);
    ck_assert(c && cc);
    for (int k = 0; k < ns; k++) c[sh_index(sel[k][0], sel[k][1])] = val[k];
    sh_image im;
    const sh_window win = {SH_WINDOW_NONE, 0.0};
    const sh_run_opts o = {0, NULL, NULL};
    ck_assert_int_eq(sh_reconstruct_latlong_ex(order, SH_CS, c, 1, &win, W, &o, &im), SH_OK);
    ck_assert(im.width == W && im.height == H && im.nchan == 1);
    /* every pixel against the truth; and the projection's definition */
    long double proj[5] = {0};
    double wpix = 0.0;
    double *trig = malloc(sizeof(double) * W * ns); /* the φ factor of each selected function, by column */
    ck_assert_ptr_nonnull(trig);
    for (int k = 0; k < ns; k++)
        for (int i = 0; i < W; i++) {
            const int m = sel[k][1];
            const double ph = 2.0 * M_PI * (i + 0.5) / W;
            trig[(size_t)k * W + i] = m > 0 ? cos(m * ph) : m < 0 ? sin(-m * ph) : 1.0;
        }
    for (int j = 0; j < H; j++) {
        const double th = M_PI * (j + 0.5) / H, x = cos(th);
        const double omega = 2.0 * M_PI / W * (cos(M_PI * j / H) - cos(M_PI * (j + 1.0) / H));
        double q[5];
        long double row[5] = {0};
        for (int k = 0; k < ns; k++) q[k] = (sel[k][1] ? M_SQRT2 : 1.0) * truth_qlm(sel[k][0], abs(sel[k][1]), x);
        for (int i = 0; i < W; i++) {
            double f = 0.0;
            for (int k = 0; k < ns; k++) f += val[k] * q[k] * trig[(size_t)k * W + i];
            const float L = im.data[(size_t)j * W + i];
            const double e = fabs((double)L - f);
            if (!(e <= wpix)) wpix = e;
            for (int k = 0; k < ns; k++) row[k] += (double)L * trig[(size_t)k * W + i];
        }
        for (int k = 0; k < ns; k++) proj[k] += row[k] * q[k] * omega;
    }
    free(trig);
    ck_assert_int_eq(sh_project_image_ex(&im, SH_LAYOUT_LATLONG, order, SH_CS, &o, cc), SH_OK);
    double wproj = 0.0;
    for (int k = 0; k < ns; k++)
        wproj = fmax(wproj, fabs(cc[sh_index(sel[k][0], sel[k][1])] - (double)proj[k]) / fabs((double)proj[k]));
    /* the file: written by OpenEXR's C++ library (no compression), read by shlab */
    char path[] = "/tmp/shlab_ranges_XXXXXX";
    const int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
    tw_spec spec = {W, H, 0, 0, 0, TW_SCANLINE, 0, 0, 1, {"Y"}, {TW_FLOAT}, {0}, {0}};
    const void *planes[1] = {im.data};
    ck_assert_msg(tw_write(path, &spec, planes) == 0, "%s", tw_error());
    sh_image rd;
    int fb = -1;
    ck_assert_int_eq(sh_exr_read(path, &rd, &fb), SH_OK);
    unlink(path);
    ck_assert(rd.width == W && rd.height == H && rd.nchan == 1);
    ck_assert_msg(!memcmp(rd.data, im.data, sizeof(float) * (size_t)W * H), "EXR read differs");
    sh_image_free(&rd);
    /* one pixel more: refused */
    sh_image big;
    ck_assert_int_eq(sh_reconstruct_latlong_ex(order, SH_CS, c, 1, &win, W + 2, &o, &big), SH_EINVAL);
    sh_image over = im;
    over.width = W + 2, over.height = H + 1; /* the data are not read: refused first */
    ck_assert_int_eq(sh_exr_write(path, &over), SH_EINVAL);
    printf("test_ranges: image %d x %d (%lld pixels, the limit %lld): reconstruction vs truth at every pixel %.3g"
           " (float), projection vs its pixel sum %.3g relative, EXR read bitwise\n",
           W, H, (long long)W * H, (long long)SH_IMAGE_MAX_PIXELS, wpix, wproj);
    ck_assert_msg(wpix <= 1e-6, "reconstruction %.3g", wpix); /* float pixels of values up to ~6 */
    ck_assert_msg(wproj <= 1e-12, "projection %.3g", wproj);
    sh_image_free(&im);
    free(c), free(cc);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("ranges");
    const struct {
        const char *name;
        const TTest *test;
    } T[] = {
        {"legendre", legendre_top},   {"basis", basis_top},   {"convert", convert_top},
        {"closed_forms", closed_forms_top}, {"rot_z", rot_z_top}, {"halfpi", halfpi_top_band},
        {"threads", threads_top}, {"batch", batch_top}, {"wigner3j", wigner3j_top}, {"stability", stability_top},
        {"scale", scale_top},         {"deriv", deriv_top},   {"taylor", taylor_top},
        {"triple", triple_top},       {"scene", scene_top},   {"image", image_top},
        {"green", green_top},         {"convert_specs", convert_specs_top},
        {"identify", identify_top},
    };
    for (size_t k = 0; k < sizeof T / sizeof *T; k++) {
        TCase *tc = tcase_create(T[k].name);
        tcase_set_timeout(tc, 600);
        tcase_add_test(tc, T[k].test);
        suite_add_tcase(s, tc);
    }
    return s;
}

SHLAB_TEST_MAIN(suite)
