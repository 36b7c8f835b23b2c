/* light_zonal.c — closed-form SH projections of zonal lights (cap, clamped
 * cosine lobe) and of the constant light.
 *
 * References
 *  [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *      synth_light() (Maple output of the cap for 4 bands).
 *  [2] I. S. Gradshteyn, I. M. Ryzhik, Table of Integrals, 7.126.2;
 *      DLMF 14.17 / 18.17 (Legendre integrals).
 *
 * A zonal light f(cosθ) has only m = 0 terms,
 *     z_l = ∫ f y_l^0 dΩ = 2π K_l ∫_{-1}^{1} f(x) P_l(x) dx,  K_l = √((2l+1)/4π).
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_sf_legendre.h>
#include <math.h>
#include <stdlib.h>

static double K0(int l) { return sqrt((2.0 * l + 1.0) / (4.0 * M_PI)); }

/* Cap of half-angle t about +z (f = 1 for θ < t).  With x0 = cos t:
 *   ∫_{x0}^1 P_l = (P_{l-1}(x0) − P_{l+1}(x0)) / (2l+1)          (l >= 1)
 * from (2l+1)P_l = P'_{l+1} − P'_{l-1} and P_{l±1}(1) = 1.  The difference
 * cancels as t → 0; with (1−x²)P'_l = l(l+1)/(2l+1) (P_{l-1} − P_{l+1}) it is
 *   ∫_{x0}^1 P_l = sin²t · P'_l(cos t) / (l(l+1)),
 * which has no cancellation: sin²t is exact and P'_l is summed by
 *   P'_{l+1} = P'_{l-1} + (2l+1) P_l   (P'_0 = 0, P'_1 = 1),
 * whose terms are all positive near x = 1.  c_0 = 2π K_0 (1 − cos t)
 * = 4π K_0 sin²(t/2).  Green's Maple output [1] gives for t in (0, π):
 * sh[0] = √π (1 − cos t), sh[2] = π K_1 sin²t, the same expressions. */
int sh_cap_zonal(double t, int order, double *z)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!isfinite(t) || t < 0.0 || t > M_PI * (1.0 + 1e-15))
        return sh_error(SH_EINVAL, "cap half-angle %g is not in [0, pi]", t);
    if (t > M_PI) t = M_PI;
    const int lmax = order - 1;
    double *P = malloc(sizeof(double) * (size_t)(lmax + 2));
    if (!P) return sh_error(SH_ENOMEM, "out of memory");
    const double x0 = cos(t), s = sin(t), s2 = s * s, h = sin(0.5 * t);
    gsl_sf_legendre_Pl_array(lmax + 1, x0, P);
    z[0] = 4.0 * M_PI * K0(0) * h * h;
    double dprev = 0.0, dcur = 1.0; /* P'_{l-1}, P'_l at l = 1 */
    for (int l = 1; l <= lmax; l++) {
        z[l] = 2.0 * M_PI * K0(l) * s2 * dcur / ((double)l * (l + 1));
        const double dnext = dprev + (2.0 * l + 1.0) * P[l];
        dprev = dcur;
        dcur = dnext;
    }
    free(P);
    return SH_OK;
}

/* Clamped cosine lobe max(0, cosθ)^e, e >= 0 (e = 0: the upper hemisphere).
 * I_l = ∫_0^1 x^e P_l(x) dx equals √π 2^{−e−1} Γ(1+e) / (Γ(1+(e−l)/2) Γ(3/2+(e+l)/2))
 * ([2] GR 7.126.2).  Evaluated by the two-step ratio that formula implies,
 *     I_0 = 1/(e+1),  I_1 = 1/(e+2),  I_l = (e − l + 2)/(e + l + 1) · I_{l−2},
 * a product of ratios of magnitude < 1: no cancellation, no gamma functions,
 * accurate for any e (the log-gamma form lost all accuracy near e ~ 1e15),
 * and exactly zero for l = e + 2, e + 4, … when e is an integer (P_l is
 * orthogonal to x^e, and the parity makes the half-range integral vanish). */
int sh_lobe_zonal(double e, int order, double *z)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!isfinite(e) || e < 0.0) return sh_error(SH_EINVAL, "lobe exponent %g must be finite and >= 0", e);
    double I[2] = {1.0 / (e + 1.0), 1.0 / (e + 2.0)}; /* I_{l} for even and odd l */
    for (int l = 0; l < order; l++) {
        if (l >= 2) I[l & 1] *= (e - l + 2.0) / (e + l + 1.0);
        z[l] = 2.0 * M_PI * K0(l) * I[l & 1];
    }
    return SH_OK;
}

int sh_light_closed_form(const sh_light *L, int order, sh_convention conv, double *coeffs)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!L) return sh_error(SH_EINVAL, "no light given");
    if (!sh_light_has_closed_form(L))
        return sh_error(SH_ENOTSUP, "this light has no closed-form projection (use a quadrature rule)");
    const int n = sh_ncoeff(order);
    for (int i = 0; i < n; i++) coeffs[i] = 0.0;
    if (L->kind == SH_LIGHT_CONST) {
        /* ∫ V y_0 = V · 4π / √(4π) */
        coeffs[0] = L->p[0] * sqrt(4.0 * M_PI);
        return SH_OK;
    }
    double *z = malloc(sizeof(double) * (size_t)order);
    if (!z) return sh_error(SH_ENOMEM, "out of memory");
    st = L->kind == SH_LIGHT_CAP ? sh_cap_zonal(L->p[0], order, z) : sh_lobe_zonal(L->p[0], order, z);
    if (!st)
        for (int l = 0; l < order; l++) coeffs[sh_index(l, 0)] = z[l]; /* m = 0: same in cs and nocs */
    free(z);
    return st;
}

int sh__lobe_zonal_unit(double e, int order, double *z)
{
    int st = sh_lobe_zonal(e, order, z);
    if (st) return st;
    double n2 = 0;
    for (int l = 0; l < order; l++) n2 += z[l] * z[l];
    const double n = sqrt(n2);
    if (!(n > 0)) return sh_error(SH_EINVAL, "lobe vector of exponent %g is zero", e);
    for (int l = 0; l < order; l++) z[l] /= n;
    return SH_OK;
}
