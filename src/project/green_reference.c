/* green_reference.c — accurate SH projection of Green's Figure 7 light, the
 * ground truth against which projection rules are measured.
 *
 * References
 *  [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *      Figure 7; the reading with the −3 inside the second max (lights.c):
 *        light = max(0, 5x − 4) + max(0, 4 s cos(φ − 2.5) − 3),
 *      x = cosθ, s = sinθ = √(1−x²).
 *  [2] GSL manual, QAGP adaptive integration with known singular points.
 *
 * With ψ = φ − 2.5, a = 4s and (for a > 3) α = acos(3/a), the second lobe is
 * a cosψ − 3 on |ψ| < α, even in ψ, so its φ integrals are analytic:
 *   ∫ lobe2 cos(mφ) dφ = cos(2.5m) C_m,   ∫ lobe2 sin(mφ) dφ = sin(2.5m) C_m,
 *   C_m = ∫_{−α}^{α} (a cosψ − 3) cos(mψ) dψ:
 *   C_0 = 2(a sinα − 3α),   C_1 = a(α + sinα cosα) − 6 sinα,
 *   C_m = a [sin((m−1)α)/(m−1) + sin((m+1)α)/(m+1)] − 6 sin(mα)/m   (m >= 2).
 * The first lobe is zonal: 2π max(0, 5x − 4) for m = 0 only.  Then
 *   c_l^0 = ∫ Q_l^0(x) [2π lobe1(x) + C_0(x)] dx,
 *   c_l^{±m} = ±-phase · √2 ∫ Q_l^m(x) {cos, sin}(2.5m) C_m(x) dx,
 * with Q_l^m = gsl_sf_legendre_sphPlm (Condon-Shortley phase, independent of
 * our own recurrence).  The x integral is done by QAGP with breakpoints at
 * the kinks x = 0.8 (first lobe) and x = ±√7/4 (s = 3/4, where the second
 * lobe appears, with a (a−3)^{3/2} singularity).
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_legendre.h>
#include <math.h>

struct gref {
    int l, m; /* m >= 0 */
};

static double lobe2_Cm(int m, double x)
{
    const double s = sqrt((1.0 - x) * (1.0 + x)), a = 4.0 * s;
    if (!(a > 3.0)) return 0.0;
    const double al = acos(3.0 / a), sa = sin(al);
    if (m == 0) return 2.0 * (a * sa - 3.0 * al);
    if (m == 1) return a * (al + sa * cos(al)) - 6.0 * sa;
    return a * (sin((m - 1) * al) / (m - 1) + sin((m + 1) * al) / (m + 1)) - 6.0 * sin(m * al) / m;
}

static double integrand(double x, void *p)
{
    const struct gref *g = p;
    double phi_part = lobe2_Cm(g->m, x);
    if (g->m == 0 && 5.0 * x - 4.0 > 0.0) phi_part += 2.0 * M_PI * (5.0 * x - 4.0);
    if (phi_part == 0.0) return 0.0;
    return gsl_sf_legendre_sphPlm(g->l, g->m, x) * phi_part;
}

int sh_green_reference(int order, sh_convention conv, double tol, double *coeffs)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (order > 64) return sh_error(SH_EINVAL, "green reference: order %d > 64 is not supported", order);
    if (!(tol > 0.0) || !isfinite(tol)) return sh_error(SH_EINVAL, "green reference: tolerance must be > 0");
    if (tol < 1e-14) tol = 1e-14;
    const size_t limit = 2000;
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(limit);
    if (!ws) return sh_error(SH_ENOMEM, "out of memory");
    const double r7 = sqrt(7.0) / 4.0;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    for (int l = 0; l < order && !st; l++)
        for (int m = 0; m <= l && !st; m++) {
            double pts[5] = {-1.0, -r7, r7, 0.8, 1.0};
            struct gref g = {l, m};
            gsl_function F = {integrand, &g};
            double val, err;
            int gst = gsl_integration_qagp(&F, pts, 5, tol, tol, limit, ws, &val, &err);
            if (gst && err > 100.0 * tol) {
                st = sh_error(SH_ENUM, "green reference: l=%d m=%d did not converge (%s, err %g)", l, m,
                              gsl_strerror(gst), err);
                break;
            }
            if (m == 0) {
                coeffs[sh_index(l, 0)] = val;
            } else {
                const double sgn = (conv == SH_NOCS && (m & 1)) ? -1.0 : 1.0;
                coeffs[sh_index(l, m)] = sgn * M_SQRT2 * cos(2.5 * m) * val;
                coeffs[sh_index(l, -m)] = sgn * M_SQRT2 * sin(2.5 * m) * val;
            }
        }
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(ws);
    return st;
}
