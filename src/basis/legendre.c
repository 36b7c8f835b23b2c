/* legendre.c — fully normalised associated Legendre functions to high degree.
 *
 * References
 *  [1] S. A. Holmes, W. E. Featherstone, "A unified approach to the Clenshaw
 *      summation and the recursive computation of very high degree and order
 *      normalised associated Legendre functions", J. Geodesy 76 (2002) 279.
 *  [2] T. Fukushima, "Numerical computation of spherical harmonics of
 *      arbitrary degree and order by extending exponent of floating point
 *      numbers", J. Geodesy 86 (2012) 271 (the "X-number" idea used below).
 *
 * We compute Q_l^m(x) = K_l^m P_l^m(x), P with the Condon-Shortley phase and
 * K_l^m = sqrt((2l+1)(l-m)! / (4π (l+m)!)), so that y_l^0 = Q_l^0 and
 * y_l^{±m} = √2 Q_l^m {cos,sin}(mφ).  With s = sqrt(1-x²):
 *
 *   Q_0^0     = 1/sqrt(4π)
 *   Q_m^m     = -s · sqrt((2m+1)/(2m)) · Q_{m-1}^{m-1}           (sectoral)
 *   Q_{m+1}^m = sqrt(2m+3) · x · Q_m^m
 *   Q_l^m     = a_lm (x Q_{l-1}^m - b_lm Q_{l-2}^m),             ([1] eq. 11)
 *        a_lm = sqrt((4l²-1)/(l²-m²)),  b_lm = sqrt(((l-1)²-m²)/(4(l-1)²-1)).
 *
 * Near the poles s^m underflows long before the column it seeds becomes
 * representable again (at l=2000, θ=1°, m=200 the seed is ~1e-350 while
 * Q_2000^200 is ~1e-60).  The seed is therefore carried as mantissa·2^e with
 * an integer exponent e [2], and the column recurrence runs on mantissas
 * until the values are back in range.
 */
#include "core/shlab_internal.h"

#include <math.h>

size_t sh_legendre_n(int lmax) { return (size_t)(lmax + 1) * (lmax + 2) / 2; }

/* Rescaling threshold for mantissas: keep |mantissa| below 2^BIG. */
#define BIG 480
#define BIG_VAL 0x1p480

/* Store index of (l, m) in one of the two layouts. */
static inline size_t store_idx(int sh_layout, int l, int m)
{
    return sh_layout ? (size_t)l * (l + 1) + m : (size_t)l * (l + 1) / 2 + m;
}

/* Core: writes Q_l^m(x), 0<=m<=l<=lmax, at store_idx(layout, l, m). */
void sh__legendre_core(int lmax, double x, double *out, int sh_layout)
{
    const double s = sqrt((1.0 - x) * (1.0 + x));
    double seed = 1.0 / sqrt(4.0 * M_PI); /* sectoral Q_m^m = seed · 2^seed_exp */
    int seed_exp = 0;

    for (int m = 0; m <= lmax; m++) {
        if (m > 0) {
            seed *= -s * sqrt((2.0 * m + 1.0) / (2.0 * m));
            if (seed == 0.0) {
                /* s == 0 (the poles) or exhausted: every remaining column is 0 */
                for (int mm = m; mm <= lmax; mm++)
                    for (int l = mm; l <= lmax; l++) out[store_idx(sh_layout, l, mm)] = 0.0;
                return;
            }
            int e;
            seed = frexp(seed, &e); /* keep the mantissa in [0.5,1) */
            seed_exp += e;
        }
        /* column m: p2 = Q_{l-2}, p1 = Q_{l-1}, as mantissas at exponent ex */
        int ex = seed_exp;
        double p1 = seed, p2 = 0.0;
        out[store_idx(sh_layout, m, m)] = ldexp(p1, ex);
        if (m == lmax) break;
        double p = sqrt(2.0 * m + 3.0) * x * p1;
        out[store_idx(sh_layout, m + 1, m)] = ldexp(p, ex);
        p2 = p1;
        p1 = p;
        const double m2 = (double)m * m;
        int l = m + 2;
        /* scaled phase: mantissas with a non-zero exponent */
        for (; l <= lmax && ex != 0; l++) {
            const double ll = (double)l, lm1 = ll - 1.0;
            const double a = sqrt((4.0 * ll * ll - 1.0) / (ll * ll - m2));
            const double b = sqrt((lm1 * lm1 - m2) / (4.0 * lm1 * lm1 - 1.0));
            p = a * (x * p1 - b * p2);
            p2 = p1;
            p1 = p;
            if (fabs(p1) > BIG_VAL) {
                /* move magnitude from the mantissas into the exponent, never past 0 */
                const int k = -ex < BIG ? -ex : BIG;
                p1 = ldexp(p1, -k);
                p2 = ldexp(p2, -k);
                ex += k;
            }
            out[store_idx(sh_layout, l, m)] = ldexp(p1, ex);
        }
        /* plain phase */
        for (; l <= lmax; l++) {
            const double ll = (double)l, lm1 = ll - 1.0;
            const double a = sqrt((4.0 * ll * ll - 1.0) / (ll * ll - m2));
            const double b = sqrt((lm1 * lm1 - m2) / (4.0 * lm1 * lm1 - 1.0));
            p = a * (x * p1 - b * p2);
            p2 = p1;
            p1 = p;
            out[store_idx(sh_layout, l, m)] = p;
        }
    }
}

int sh_legendre_array(int lmax, double x, double *out)
{
    if (lmax < 0) return sh_error(SH_EINVAL, "lmax %d < 0", lmax);
    if (!(x >= -1.0 && x <= 1.0)) return sh_error(SH_EINVAL, "x = %g is outside [-1,1]", x);
    sh__legendre_core(lmax, x, out, 0);
    return SH_OK;
}
