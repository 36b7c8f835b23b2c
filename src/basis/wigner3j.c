/* wigner3j.c — Wigner 3j symbols for integer angular momenta.
 *
 * References
 *  [1] K. Schulten, R. G. Gordon, "Exact recursive evaluation of 3j- and
 *      6j-coefficients for quantum-mechanical coupling of angular momenta",
 *      J. Math. Phys. 16 (1975) 1961-1970, eqs. (3)-(6).
 *  [2] J. H. Luscombe, M. Luban, "Simplified recursive algorithm for Wigner 3j
 *      and 6j symbols", Phys. Rev. E 57 (1998) 7274-7277.
 *  [3] A. R. Edmonds, "Angular Momentum in Quantum Mechanics", eqs. (3.7.3),
 *      (3.7.17) (the symmetries and the sign at j1 = j2 + j3).
 *
 * For fixed j2, j3, m2, m3 (m1 = -m2-m3) the symbols f(j) = (j j2 j3; m1 m2 m3)
 * satisfy the three-term recursion in j [1, eq. (3)]
 *
 *     j A(j+1) f(j+1) + B(j) f(j) + (j+1) A(j) f(j-1) = 0,
 *     A(j) = √[(j² − (j2−j3)²) ((j2+j3+1)² − j²) (j² − m1²)],
 *     B(j) = −(2j+1) [ j2(j2+1) m1 − j3(j3+1) m1 − j(j+1)(m3 − m2) ],
 *
 * for jmin = max(|j2−j3|, |m1|) <= j <= jmax = j2+j3.  The recursion is run
 * forward from jmin (stable while the solution grows through the lower
 * classically forbidden region) and backward from jmax (stable likewise from
 * above); the two pieces are matched on an overlap inside the classically
 * allowed region, normalised by  Σ_j (2j+1) f(j)² = 1  [3, eq. (3.7.8)] and
 * the sign fixed by  sign f(jmax) = (−1)^(j2−j3−m1)  [3, eq. (3.7.17)].
 * Unlike the Racah sum (alternating, cancelling) or GSL's
 * gsl_sf_coupling_3j, the error stays at a few ulps for j in the thousands.
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>

/* Rescale threshold against overflow in the forbidden regions. */
#define W3J_BIG 1e150
#define W3J_SMALL 1e-150

static double w3j_A(double j, double j2, double j3, double m1)
{
    const double d = j2 - j3, s = j2 + j3 + 1.0;
    const double v = (j * j - d * d) * (s * s - j * j) * (j * j - m1 * m1);
    return v > 0.0 ? sqrt(v) : 0.0;
}

static double w3j_B(double j, double j2, double j3, double m1, double m2, double m3)
{
    return -(2.0 * j + 1.0) *
           (j2 * (j2 + 1.0) * m1 - j3 * (j3 + 1.0) * m1 - j * (j + 1.0) * (m3 - m2));
}

size_t sh_wigner3j_family_n(int j2, int j3) { return (size_t)(j2 + j3 + 1); }

/* ---- forward from jmin: f(jmin) = 1; next value from the two-term
 * relation (A(jmin) = 0), or, when jmin = 0 (j2 = j3, m1 = 0, where the
 * relation degenerates to 0 = 0), from the closed forms
 * (0 J J; 0 m −m) = (−1)^(J−m)/√(2J+1) and
 * (1 J J; 0 m −m) = (−1)^(J−m) m / √(J(J+1)(2J+1))  [3, Table 2].
 * Continues while the solution is still in the lower forbidden region:
 * there |f| grows monotonically; stops at the first j where it does not
 * (the lower turning point has been passed) or at a zero.  Returns the
 * last j reached: f is valid on [jmin, that j]. */
static int w3j_forward(int jmin, int jmax, int j2, int j3, int m2, int m3, double *f)
{
    const double J2 = j2, J3 = j3, M1 = -m2 - m3, M2 = m2, M3 = m3;
    f[0] = 1.0;
    if (jmin == 0)
        f[1] = M2 / sqrt(J2 * (J2 + 1.0));
    else
        f[1] = -w3j_B(jmin, J2, J3, M1, M2, M3) / (jmin * w3j_A(jmin + 1, J2, J3, M1));
    int jf = jmin + 1;
    while (jf < jmax && fabs(f[jf - jmin]) > fabs(f[jf - jmin - 1])) {
        const int j = jf;
        const double a = j * w3j_A(j + 1, J2, J3, M1);
        const double b = w3j_B(j, J2, J3, M1, M2, M3);
        const double c = (j + 1.0) * w3j_A(j, J2, J3, M1);
        f[j + 1 - jmin] = -(b * f[j - jmin] + c * f[j - 1 - jmin]) / a;
        jf++;
        if (fabs(f[jf - jmin]) > W3J_BIG)
            for (int q = 0; q <= jf - jmin; q++) f[q] *= W3J_SMALL;
    }
    return jf;
}

/* ---- backward from jmax through the upper forbidden region (where the
 * solution grows going down) and the classically allowed region (neutrally
 * stable), down to jm-1: a two-point overlap {jm-1, jm} with the forward
 * solution, which is valid on [jmin, jm] (jm < jmax).  The backward part is
 * matched to f there, scaled into f[jm..jmax], and *top_sign set to the
 * sign of the unnormalised f(jmax). */
static int w3j_backward_match(int jm, int jmin, int jmax, int j2, int j3, int m2, int m3, double *f,
                              double *top_sign)
{
    const double J2 = j2, J3 = j3, M1 = -m2 - m3, M2 = m2, M3 = m3;
    /* backward sweep into the scratch tail: g(jmax) = 1 */
    double *g = f; /* reuse: write g over [jm-1, jmax], keep f copies */
    const double f_jm = f[jm - jmin], f_jm1 = f[jm - 1 - jmin];
    g[jmax - jmin] = 1.0;
    {
        const int j = jmax;
        g[j - 1 - jmin] = -w3j_B(j, J2, J3, M1, M2, M3) / ((j + 1.0) * w3j_A(j, J2, J3, M1));
    }
    for (int j = jmax - 1; j - 1 >= jm - 1; j--) {
        const double a = j * w3j_A(j + 1, J2, J3, M1);
        const double b = w3j_B(j, J2, J3, M1, M2, M3);
        const double c = (j + 1.0) * w3j_A(j, J2, J3, M1);
        g[j - 1 - jmin] = -(b * g[j - jmin] + a * g[j + 1 - jmin]) / c;
        if (fabs(g[j - 1 - jmin]) > W3J_BIG)
            for (int q = j - 1 - jmin; q <= jmax - jmin; q++) g[q] *= W3J_SMALL;
    }
    /* least-squares match of g to f on {jm-1, jm}: scale = <f,g>/<g,g> */
    const double g_jm = g[jm - jmin], g_jm1 = g[jm - 1 - jmin];
    const double gg = g_jm * g_jm + g_jm1 * g_jm1;
    const double scale = (f_jm * g_jm + f_jm1 * g_jm1) / gg;
    /* restore f at jm-1, jm; scale the backward part */
    for (int q = jm - jmin; q <= jmax - jmin; q++) f[q] = g[q] * scale;
    f[jm - 1 - jmin] = f_jm1;
    f[jm - jmin] = f_jm;
    *top_sign = scale < 0.0 ? -1.0 : 1.0; /* g(jmax) = 1 times positive rescalings */
    /* f and g·scale agree on the overlap; keep f there.  If the
     * match is badly conditioned (gg tiny) the normalisation below
     * still fixes the overall scale, only the relative one is lost. */
    if (!(gg > 0.0) || !isfinite(scale) || scale == 0.0)
        return sh_error(SH_ENUM, "3j: recursion match failed (j2=%d j3=%d m2=%d m3=%d)",
                        j2, j3, m2, m3);
    return SH_OK;
}

/* normalise: Σ (2j+1) f² = 1, sign of f(jmax) = (−1)^(j2−j3−m1) */
static int w3j_normalise(int n, int jmin, int j2, int j3, int m1, double top_sign, double *f)
{
    double s = 0.0, big = 0.0;
    for (int q = 0; q < n; q++) big = fmax(big, fabs(f[q]));
    for (int q = 0; q < n; q++) {
        const double t = f[q] / big;
        s += (2.0 * (jmin + q) + 1.0) * t * t;
    }
    double norm = 1.0 / (big * sqrt(s));
    const int e = j2 - j3 - m1;
    const int want_neg = (e % 2 != 0);
    if ((top_sign < 0.0) != want_neg) norm = -norm;
    for (int q = 0; q < n; q++) f[q] *= norm;
    if (!isfinite(norm)) return sh_error(SH_ENUM, "3j: normalisation failed");
    return SH_OK;
}

int sh_wigner3j_family(int j2, int j3, int m2, int m3, int *jmin_out, int *jmax_out,
                       double *f)
{
    if (j2 < 0 || j3 < 0) return sh_error(SH_EINVAL, "3j: negative j (%d, %d)", j2, j3);
    if (j2 > 4 * SHLAB_MAX_ORDER || j3 > 4 * SHLAB_MAX_ORDER)
        return sh_error(SH_EINVAL, "3j: j too large (%d, %d)", j2, j3);
    const int m1 = -m2 - m3;
    const int jmax = j2 + j3;
    int jmin = abs(j2 - j3);
    if (abs(m1) > jmin) jmin = abs(m1);
    *jmin_out = jmin;
    *jmax_out = jmax;
    if (abs(m2) > j2 || abs(m3) > j3 || jmin > jmax) {
        /* every symbol of the family vanishes (empty family) */
        *jmin_out = jmax + 1;
        return SH_OK;
    }
    const int n = jmax - jmin + 1;
    /* sign of the unnormalised f(jmax), tracked separately: the stored
     * value may underflow to 0 deep in the upper forbidden region */
    double top_sign = 1.0;
    if (n == 1) {
        f[0] = 1.0 / sqrt(2.0 * jmin + 1.0);
    } else {
        const int jm = w3j_forward(jmin, jmax, j2, j3, m2, m3, f); /* f valid on [jmin, jm] */
        if (jm == jmax) top_sign = f[n - 1] < 0.0 ? -1.0 : 1.0;
        int st;
        if (jm < jmax && (st = w3j_backward_match(jm, jmin, jmax, j2, j3, m2, m3, f, &top_sign)))
            return st;
    }
    return w3j_normalise(n, jmin, j2, j3, m1, top_sign, f);
}

int sh_wigner3j_e(int j1, int j2, int j3, int m1, int m2, int m3, double *result)
{
    *result = 0.0;
    if (j1 < 0 || j2 < 0 || j3 < 0) return sh_error(SH_EINVAL, "3j: negative j");
    if (j1 > 4 * SHLAB_MAX_ORDER || j2 > 4 * SHLAB_MAX_ORDER || j3 > 4 * SHLAB_MAX_ORDER)
        return sh_error(SH_EINVAL, "3j: j too large");
    /* selection rules: m sum, |m| <= j, triangle */
    if (m1 + m2 + m3 != 0 || abs(m1) > j1 || abs(m2) > j2 || abs(m3) > j3) return SH_OK;
    if (j1 < abs(j2 - j3) || j1 > j2 + j3) return SH_OK;
    /* (j1 j2 j3; 0 0 0) = 0 for odd j1+j2+j3 (exactly, not by cancellation) */
    if (m1 == 0 && m2 == 0 && ((j1 + j2 + j3) & 1)) return SH_OK;
    double stackbuf[512];
    const size_t need = sh_wigner3j_family_n(j2, j3);
    double *buf = need <= 512 ? stackbuf : malloc(need * sizeof(double));
    if (!buf) return sh_error(SH_ENOMEM, "3j: out of memory");
    int jmin, jmax;
    int st = sh_wigner3j_family(j2, j3, m2, m3, &jmin, &jmax, buf);
    if (st == SH_OK && j1 >= jmin && j1 <= jmax) *result = buf[j1 - jmin];
    if (buf != stackbuf) free(buf);
    return st;
}

double sh_wigner3j(int j1, int j2, int j3, int m1, int m2, int m3)
{
    double r;
    if (sh_wigner3j_e(j1, j2, j3, m1, m2, m3, &r) != SH_OK) return NAN;
    return r;
}
