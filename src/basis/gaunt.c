/* gaunt.c — Gaunt coefficients (integrals of three spherical harmonics) for
 * the complex basis and for shlab's real basis (docs/CONVENTIONS.md, cs or nocs).
 *
 * References
 *  [1] A. R. Edmonds, "Angular Momentum in Quantum Mechanics" (1957), eq. (4.6.3):
 *        ∫ Y_l1^m1 Y_l2^m2 Y_l3^m3 dΩ
 *          = √((2l1+1)(2l2+1)(2l3+1)/4π) (l1 l2 l3; 0 0 0) (l1 l2 l3; m1 m2 m3),
 *      for Y_l^m = K_l^m P_l^m(cosθ) e^{imφ}, P with the Condon-Shortley phase,
 *      Y_l^{-m} = (−1)^m conj(Y_l^m).
 *  [2] M. A. Blanco, M. Flórez, M. Bermejo, "Evaluation of the rotation
 *      matrices in the basis of real spherical harmonics", J. Mol. Struct.
 *      (Theochem) 419 (1997) 19-27, eq. (19) (real ↔ complex map).
 *  [3] R. Green, "Spherical Harmonic Lighting: The Gritty Details" (2003), eq. 8.
 *
 * Real ↔ complex map for shlab's cs basis (derived from docs/CONVENTIONS.md:
 * y_l^m = √2 K P_l^m cos mφ = √2 Re Y_l^m, y_l^{-m} = √2 Im Y_l^m, m > 0):
 *     y_l^m    = (Y_l^m + (−1)^m Y_l^{-m}) / √2                 (m > 0)
 *     y_l^{-m} = −i (Y_l^m − (−1)^m Y_l^{-m}) / √2              (m > 0)
 *     y_l^0    = Y_l^0
 * i.e. y_l^μ = Σ_m U_{μm} Y_l^m; nocs multiplies row μ by (−1)^μ.  Then
 *     G(i,j,k) = ∫ y_i y_j y_k = Σ_{m1,m2,m3} U1 U2 U3 ∫ Y Y Y   (no conjugates).
 * Selection rules used to skip work: |l1−l2| <= l3 <= l1+l2, l1+l2+l3 even,
 * |μ3| ∈ {|μ1|+|μ2|, ||μ1|−|μ2||}, and an even number of negative μ (the
 * φ integral of cos·cos·sin or sin·sin·sin vanishes).
 */
#include "core/shlab_internal.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>

/* U_{μ m}: coefficient of Y_l^m in y_l^μ (see above). */
static double complex real_u(sh_convention conv, int mu, int m)
{
    const int a = abs(mu);
    if (abs(m) != a) return 0.0;
    const double sgn_a = (a & 1) ? -1.0 : 1.0;
    double complex u;
    if (mu == 0)
        u = 1.0;
    else if (mu > 0)
        u = (m > 0 ? 1.0 : sgn_a) * M_SQRT1_2;
    else
        u = (m > 0 ? -I : I * sgn_a) * M_SQRT1_2;
    if (conv == SH_NOCS && (a & 1)) u = -u;
    return u;
}

/* Combine the complex 3j symbols into the real Gaunt coefficient.
 * wA = (l1 l2 l3; a, b, −a−b), wB = (l1 l2 l3; a, −b, b−a), a = |μ1|, b = |μ2|;
 * for even l1+l2+l3 the symbol with all m negated is equal, so these two
 * cover every (m1, m2) = (±a, ±b).  pre = √(...) (l1 l2 l3; 0 0 0). */
static double real_combine(sh_convention conv, int mu1, int mu2, int mu3, double pre,
                           double wA, double wB)
{
    const int a = abs(mu1), b = abs(mu2);
    double complex s = 0.0;
    for (int s1 = -1; s1 <= 1; s1 += 2) {
        if (a == 0 && s1 < 0) continue;
        for (int s2 = -1; s2 <= 1; s2 += 2) {
            if (b == 0 && s2 < 0) continue;
            const int m1 = s1 * a, m2 = s2 * b, m3 = -m1 - m2;
            if (abs(m3) != abs(mu3)) continue;
            const double w = (s1 == s2 || a == 0 || b == 0) ? wA : wB;
            s += real_u(conv, mu1, m1) * real_u(conv, mu2, m2) * real_u(conv, mu3, m3) * w;
        }
    }
    /* the imaginary part vanishes identically (it is ±0 or rounding) */
    return pre * creal(s);
}

/* Quick real-basis selection rules on (μ1, μ2, μ3). */
static int real_m_allowed(int mu1, int mu2, int mu3)
{
    const int a = abs(mu1), b = abs(mu2), c = abs(mu3);
    if (c != a + b && c != abs(a - b)) return 0;
    const int nneg = (mu1 < 0) + (mu2 < 0) + (mu3 < 0);
    return (nneg & 1) == 0;
}

int sh_gaunt_complex_e(int l1, int m1, int l2, int m2, int l3, int m3, double *result)
{
    *result = 0.0;
    if (l1 < 0 || l2 < 0 || l3 < 0) return sh_error(SH_EINVAL, "gaunt: negative l");
    if (((l1 + l2 + l3) & 1) || m1 + m2 + m3 != 0) return SH_OK;
    double w0, w;
    int st = sh_wigner3j_e(l1, l2, l3, 0, 0, 0, &w0);
    if (st || w0 == 0.0) return st;
    st = sh_wigner3j_e(l1, l2, l3, m1, m2, m3, &w);
    if (st) return st;
    /* [1] eq. (4.6.3) */
    *result = sqrt((2.0 * l1 + 1.0) * (2.0 * l2 + 1.0) * (2.0 * l3 + 1.0) / (4.0 * M_PI)) * w0 * w;
    return SH_OK;
}

int sh_gaunt_real_e(sh_convention conv, int i, int j, int k, double *result)
{
    *result = 0.0;
    if (i < 0 || j < 0 || k < 0) return sh_error(SH_EINVAL, "gaunt: negative index");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "gaunt: unknown convention");
    int l1, m1, l2, m2, l3, m3;
    sh_index_lm(i, &l1, &m1);
    sh_index_lm(j, &l2, &m2);
    sh_index_lm(k, &l3, &m3);
    if (((l1 + l2 + l3) & 1) || l3 < abs(l1 - l2) || l3 > l1 + l2) return SH_OK;
    if (!real_m_allowed(m1, m2, m3)) return SH_OK;
    const int a = abs(m1), b = abs(m2);
    double w0, wA = 0.0, wB = 0.0;
    int st = sh_wigner3j_e(l1, l2, l3, 0, 0, 0, &w0);
    if (st) return st;
    if (abs(m3) == a + b && (st = sh_wigner3j_e(l1, l2, l3, a, b, -a - b, &wA))) return st;
    if (abs(m3) == abs(a - b) && (st = sh_wigner3j_e(l1, l2, l3, a, -b, b - a, &wB))) return st;
    const double pre =
        sqrt((2.0 * l1 + 1.0) * (2.0 * l2 + 1.0) * (2.0 * l3 + 1.0) / (4.0 * M_PI)) * w0;
    *result = real_combine(conv, m1, m2, m3, pre, wA, wB);
    return SH_OK;
}

double sh_gaunt_real(sh_convention conv, int i, int j, int k)
{
    double r;
    if (sh_gaunt_real_e(conv, i, j, k, &r) != SH_OK) return NAN;
    return r;
}

size_t sh_gaunt_real_row_n(int l1, int l2) { return 2 * (size_t)((l1 < l2 ? l1 : l2) + 1); }
size_t sh_gaunt_real_row_work_n(int l1, int l2) { return 3 * (size_t)(l1 + l2 + 1); }

int sh_gaunt_real_row(sh_convention conv, int i, int j, int lmax3, int *k, double *g,
                      int *count, double *work)
{
    *count = 0;
    if (i < 0 || j < 0) return sh_error(SH_EINVAL, "gaunt: negative index");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "gaunt: unknown convention");
    int l1, mu1, l2, mu2;
    sh_index_lm(i, &l1, &mu1);
    sh_index_lm(j, &l2, &mu2);
    const int a = abs(mu1), b = abs(mu2);
    const size_t fam = (size_t)(l1 + l2 + 1);
    double *w0 = work, *wA = work + fam, *wB = work + 2 * fam;
    int j0min, j0max, jAmin, jAmax, jBmin, jBmax, st;
    /* families over l3 of (l1 l2 l3; m1 m2 m3) = (l3 l1 l2; m3 m1 m2) (cyclic) */
    if ((st = sh_wigner3j_family(l1, l2, 0, 0, &j0min, &j0max, w0))) return st;
    if ((st = sh_wigner3j_family(l1, l2, a, b, &jAmin, &jAmax, wA))) return st;
    if ((st = sh_wigner3j_family(l1, l2, a, -b, &jBmin, &jBmax, wB))) return st;
    /* sign of μ3 from the parity rule; candidates |μ3| = a+b and |a−b| */
    const int neg = (mu1 < 0) != (mu2 < 0);
    int cand[2] = {a + b, abs(a - b)};
    const int ncand = (cand[0] == cand[1]) ? 1 : 2;
    const int l3lo = abs(l1 - l2), l3hi = l1 + l2 < lmax3 ? l1 + l2 : lmax3;
    for (int l3 = l3lo; l3 <= l3hi; l3 += 2) { /* l1+l2+l3 even */
        if (l3 < j0min || l3 > j0max) continue;
        const double pre = sqrt((2.0 * l1 + 1.0) * (2.0 * l2 + 1.0) * (2.0 * l3 + 1.0) /
                                (4.0 * M_PI)) * w0[l3 - j0min];
        for (int c = 0; c < ncand; c++) {
            const int am3 = cand[c];
            if (am3 > l3) continue;
            const int mu3 = neg ? -am3 : am3;
            if (neg && am3 == 0) continue; /* sin·cos·1 integrates to zero */
            const double vA = (l3 >= jAmin && l3 <= jAmax) ? wA[l3 - jAmin] : 0.0;
            const double vB = (l3 >= jBmin && l3 <= jBmax) ? wB[l3 - jBmin] : 0.0;
            const double v = real_combine(conv, mu1, mu2, mu3, pre, am3 == a + b ? vA : 0.0,
                                          am3 == abs(a - b) ? vB : 0.0);
            k[*count] = sh_index(l3, mu3);
            g[*count] = v;
            (*count)++;
        }
    }
    return SH_OK;
}
