/* legendre_truth.h — the orthonormal associated Legendre function Q_l^m(x)
 * (Condon–Shortley phase, ∫ Q² dx·2π = 1, shlab's cs basis: y_l^0 = Q_l^0,
 * y_l^{±m} = √2 Q_l^m {cos, sin} mφ) computed independently of the library,
 * as the truth of the transform tests at high band.
 *
 * Two implementations, neither shared with src/:
 *   truth_qlm       long double, the standard (unscaled) column recurrence
 *                       Q_m^m = (−1)^m √((2m+1)!!/(4π (2m)!!)) s^m,
 *                       Q_l^m = a_l x Q_{l−1}^m − b_l Q_{l−2}^m,
 *                       a_l = √((4l²−1)/(l²−m²)),
 *                       b_l = √((2l+1)((l−1)²−m²) / ((2l−3)(l²−m²))),
 *                   with the exponent carried apart (frexpl) so that nothing
 *                   underflows however small s^m is; s = √((1−x)(1+x)) is
 *                   formed in long double, so the only rounding of the input
 *                   is that of x itself (the grid's node);
 *   truth_qlm_mpfr  the same recurrence in MPFR at `bits` bits of precision,
 *                   used by the tests to bound truth_qlm's own error.
 * GSL is not the truth here: gsl_sf_legendre_sphPlm underflows above l ≈ 800
 * (returns 0 where Q = −1.34 at l = 2047, m = 777, x = 0.924) and
 * gsl_sf_legendre_array errs by 2.7e-12 at l = 2047 near the pole (measured
 * against MPFR when this file was written). */
#ifndef SHLAB_TEST_LEGENDRE_TRUTH_H
#define SHLAB_TEST_LEGENDRE_TRUTH_H

#include <math.h>
#include <mpfr.h>
#include <stdlib.h>

static inline double truth_qlm(int l, int m, double xd)
{
    const long double x = xd, s = sqrtl((1.0L - x) * (1.0L + x));
    long double p = 1.0L / sqrtl(4.0L * 3.14159265358979323846264338327950288L);
    long e = 0; /* value = p · 2^e */
    int ex;
    for (int k = 1; k <= m; k++) {
        p *= -s * sqrtl((2.0L * k + 1.0L) / (2.0L * k));
        if (p == 0.0L) return 0.0; /* s = 0: the pole */
        frexpl(p, &ex);
        if (ex < -4000) p = ldexpl(p, -ex), e += ex;
    }
    long double q2 = 0.0L, q1 = p;
    for (int j = m + 1; j <= l; j++) {
        const long double L2 = (long double)j * j, M2 = (long double)m * m;
        const long double a = sqrtl((4.0L * L2 - 1.0L) / (L2 - M2));
        const long double b = sqrtl((2.0L * j + 1.0L) * ((j - 1.0L) * (j - 1.0L) - M2) /
                                    ((2.0L * j - 3.0L) * (L2 - M2)));
        const long double qn = a * x * q1 - b * q2;
        q2 = q1;
        q1 = qn;
        frexpl(q1, &ex);
        if (ex > 4000 || ex < -4000) q1 = ldexpl(q1, -ex), q2 = ldexpl(q2, -ex), e += ex;
    }
    return (double)ldexpl(q1, e > 100000 ? 100000 : e < -100000 ? -100000 : (int)e);
}

/* Q_l^m(x) for l = m..L into q[l − m] (the recursion of truth_qlm, kept
 * for every l); values below the double range come out as 0. */
static inline void truth_qlm_column(int L, int m, double xd, double *q)
{
    const long double x = xd, s = sqrtl((1.0L - x) * (1.0L + x));
    long double p = 1.0L / sqrtl(4.0L * 3.14159265358979323846264338327950288L);
    long e = 0;
    int ex;
    for (int k = 1; k <= m && p != 0.0L; k++) {
        p *= -s * sqrtl((2.0L * k + 1.0L) / (2.0L * k));
        frexpl(p, &ex);
        if (ex < -4000) p = ldexpl(p, -ex), e += ex;
    }
    long double q2 = 0.0L, q1 = p;
    const long double M2 = (long double)m * m;
    for (int j = m; j <= L; j++) {
        if (j > m) {
            const long double L2 = (long double)j * j;
            const long double a = sqrtl((4.0L * L2 - 1.0L) / (L2 - M2));
            const long double b = sqrtl((2.0L * j + 1.0L) * ((j - 1.0L) * (j - 1.0L) - M2) /
                                        ((2.0L * j - 3.0L) * (L2 - M2)));
            const long double qn = a * x * q1 - b * q2;
            q2 = q1;
            q1 = qn;
            frexpl(q1, &ex);
            if (ex > 4000 || ex < -4000) q1 = ldexpl(q1, -ex), q2 = ldexpl(q2, -ex), e += ex;
        }
        q[j - m] = e < -20000 ? 0.0 : (double)ldexpl(q1, (int)e);
    }
}

/* f(θ, φ) = Σ_{l ≤ L, |m| ≤ l} c_l^m y_l^m in shlab's cs basis (flat index
 * l(l+1)+m), from truth_qlm_column, summed in long double. */
static inline double truth_point(int L, const double *c, double x, double phi)
{
    double *q = malloc(sizeof(double) * (L + 1));
    long double f = 0.0L;
    for (int m = 0; m <= L; m++) {
        truth_qlm_column(L, m, x, q);
        long double a = 0.0L, b = 0.0L;
        for (int l = m; l <= L; l++) {
            a += (long double)c[l * (l + 1) + m] * q[l - m];
            if (m) b += (long double)c[l * (l + 1) - m] * q[l - m];
        }
        if (!m) f += a;
        else f += 1.41421356237309504880168872420969808L * (a * cosl((long double)m * phi) + b * sinl((long double)m * phi));
    }
    free(q);
    return (double)f;
}

static inline double truth_qlm_mpfr(int l, int m, double xd, mpfr_prec_t bits)
{
    mpfr_t x, s, p, a, b, q1, q2, t;
    mpfr_inits2(bits, x, s, p, a, b, q1, q2, t, (mpfr_ptr)0);
    mpfr_set_d(x, xd, MPFR_RNDN);
    mpfr_sqr(s, x, MPFR_RNDN);
    mpfr_ui_sub(s, 1, s, MPFR_RNDN);
    mpfr_sqrt(s, s, MPFR_RNDN);
    mpfr_const_pi(p, MPFR_RNDN);
    mpfr_mul_ui(p, p, 4, MPFR_RNDN);
    mpfr_rec_sqrt(p, p, MPFR_RNDN);
    for (int k = 1; k <= m; k++) {
        mpfr_set_ui(t, 2 * k + 1, MPFR_RNDN);
        mpfr_div_ui(t, t, 2 * k, MPFR_RNDN);
        mpfr_sqrt(t, t, MPFR_RNDN);
        mpfr_mul(p, p, t, MPFR_RNDN);
        mpfr_mul(p, p, s, MPFR_RNDN);
        mpfr_neg(p, p, MPFR_RNDN);
    }
    mpfr_set(q1, p, MPFR_RNDN);
    mpfr_set_ui(q2, 0, MPFR_RNDN);
    for (long j = m + 1; j <= l; j++) {
        const long M2 = (long)m * m;
        mpfr_set_si(a, 4 * j * j - 1, MPFR_RNDN);
        mpfr_div_si(a, a, j * j - M2, MPFR_RNDN);
        mpfr_sqrt(a, a, MPFR_RNDN);
        mpfr_set_si(b, (2 * j + 1) * ((j - 1) * (j - 1) - M2), MPFR_RNDN);
        mpfr_div_si(b, b, (2 * j - 3) * (j * j - M2), MPFR_RNDN);
        mpfr_sqrt(b, b, MPFR_RNDN);
        mpfr_mul(t, b, q2, MPFR_RNDN);
        mpfr_set(q2, q1, MPFR_RNDN);
        mpfr_mul(q1, q1, a, MPFR_RNDN);
        mpfr_mul(q1, q1, x, MPFR_RNDN);
        mpfr_sub(q1, q1, t, MPFR_RNDN);
    }
    const double r = mpfr_get_d(q1, MPFR_RNDN);
    mpfr_clears(x, s, p, a, b, q1, q2, t, (mpfr_ptr)0);
    return r;
}

#endif
