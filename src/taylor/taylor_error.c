/* taylor_error.c — error of Krivánek et al.'s Taylor-approximated rotation
 * about y, D(β) = R_Y(β) − T(β), by singular values and for a Phong lobe.
 *
 * References
 *  [1] J. Křivánek et al. 2005 (IRISA PI 1728), Sec. 3.2 and Figure 3:
 *      E(β) = ‖D(β)Λ‖; max over unit Λ = largest singular value σ₁ of D;
 *      "average over unit Λ" taken by the paper (and docs/CONVENTIONS.md) as the
 *      mean singular value; the actual error for the lobe cos^7.
 *  [2] GSL manual, "Singular Value Decomposition": gsl_linalg_SV_decomp_jacobi
 *      (one-sided Jacobi orthogonalization, singular values to high relative
 *      accuracy), returns A = U S Vᵀ with S ≥ 0 in decreasing order.
 *  [3] docs/CONVENTIONS.md "Taylor-approximated rotation" (the three expansions
 *      and the error measures), lights: sh_lobe_zonal (closed-form
 *      coefficients of max(0, cosθ)^e about +z).
 *
 * D is block diagonal (bands do not mix), so its singular values are those
 * of the band blocks together; each (2l+1)² block is decomposed alone, by
 * the generic error engine of rotation_choose.c (sh_rot_errws) that `plan`
 * and the frontier use for every method.  R_Y(β) comes from the zxzxz method
 * (exact, accurate to l = 1000); T(β) from the taylor plan's blocks (the
 * kernel under test).  sh_taylor_lobe_error
 * takes the other path — the two plans applied to the lobe vector — so the
 * tests can compare the two.  Both conventions give the same numbers: nocs
 * is S·D·S with S = diag(±1) orthogonal, and the lobe vector is zonal (m = 0,
 * S c = c).
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int ty_check(int order, sh_rot_method taylor, double beta)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (taylor != SH_ROT_TAYLOR1 && taylor != SH_ROT_TAYLOR15 && taylor != SH_ROT_TAYLOR2)
        return sh_error(SH_EINVAL, "taylor error: method must be taylor1, taylor1.5 or taylor2");
    if (!isfinite(beta) || beta < 0 || beta > M_PI)
        return sh_error(SH_EINVAL, "taylor error: beta %g outside [0, pi]", beta);
    return SH_OK;
}

/* The measures of D(β) through the generic error engine (rotation_choose.c:
 * band blocks of zxzxz minus the taylor plan's, GSL's Jacobi SVD per band,
 * lobe error from the m = 0 columns). */
static int ty_eval(int order, sh_rot_method taylor, double beta, double lobe_exp, sh_rot_error *e,
                   double *sv)
{
    int st = ty_check(order, taylor, beta);
    if (st) return st;
    sh_rotation rot;
    sh_rot_errws *w;
    if ((st = sh_rotation_from_euler(0, beta, 0, &rot))) return st;
    if ((st = sh_rot_errws_create(order, lobe_exp, 0, &w))) return st;
    if (!(st = sh_rot_errws_set(w, &rot))) st = sh_rot_errws_eval_sv(w, taylor, SH_PREC_DOUBLE, e, sv);
    sh_rot_errws_free(w);
    return st;
}

int sh_taylor_singular_values(int order, sh_rot_method taylor, double beta, double *sv)
{
    sh_rot_error e;
    return ty_eval(order, taylor, beta, 7, &e, sv);
}

int sh_taylor_error(int order, sh_rot_method taylor, double beta, double lobe_exp, sh_taylor_err *out)
{
    sh_rot_error e;
    int st = ty_eval(order, taylor, beta, lobe_exp, &e, NULL);
    if (st) return st;
    out->beta = beta;
    out->max = e.max;
    out->mean = e.mean;
    out->lobe = e.lobe;
    return SH_OK;
}

int sh_taylor_lobe_error(int order, sh_rot_method taylor, double beta, double lobe_exp, double *lobe)
{
    int st = ty_check(order, taylor, beta);
    if (st) return st;
    const size_t n = (size_t)order * order;
    double *c = calloc(3 * n, sizeof *c), *z = malloc((size_t)order * sizeof *z);
    double *ye = c + n, *ya = ye + n;
    sh_rot_plan *pe = NULL, *pa = NULL;
    sh_rotation rot;
    if (!c || !z) st = sh_error(SH_ENOMEM, "taylor error: out of memory");
    if (!st) st = sh__lobe_zonal_unit(lobe_exp, order, z);
    if (!st) st = sh_rotation_from_euler(0, beta, 0, &rot);
    if (!st) st = sh_rot_plan_create(order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &pe);
    if (!st) st = sh_rot_plan_create(order, taylor, SH_PREC_DOUBLE, SH_CS, &pa);
    if (!st) st = sh_rot_plan_set(pe, &rot);
    if (!st) st = sh_rot_plan_set(pa, &rot);
    if (!st) {
        for (int l = 0; l < order; l++) c[l * (l + 1)] = z[l];
        st = sh_rot_plan_apply(pe, c, ye);
    }
    if (!st) st = sh_rot_plan_apply(pa, c, ya);
    if (!st) {
        double s2 = 0;
        for (size_t i = 0; i < n; i++) s2 += (ye[i] - ya[i]) * (ye[i] - ya[i]);
        *lobe = sqrt(s2);
    }
    sh_rot_plan_free(pe);
    sh_rot_plan_free(pa);
    free(c), free(z);
    return st;
}

int sh_taylor_lobe_limit(int order, sh_rot_method taylor, double lobe_exp, double tol, double beta_max,
                         double step, double *beta_lim)
{
    int st = ty_check(order, taylor, beta_max);
    if (st) return st;
    if (!(tol > 0) || !(step > 0) || !isfinite(tol))
        return sh_error(SH_EINVAL, "taylor lobe limit: tol and step must be > 0");
    double lo = 0, hi = -1, e;
    for (double b = step; ; b += step) {
        if (b > beta_max) b = beta_max;
        if ((st = sh_taylor_lobe_error(order, taylor, b, lobe_exp, &e))) return st;
        if (e > tol) { hi = b; break; }
        lo = b;
        if (b >= beta_max) break;
    }
    if (hi < 0) {
        *beta_lim = beta_max;
        return SH_OK;
    }
    while (hi - lo > 1e-10) {
        const double mid = 0.5 * (lo + hi);
        if ((st = sh_taylor_lobe_error(order, taylor, mid, lobe_exp, &e))) return st;
        if (e > tol) hi = mid;
        else lo = mid;
    }
    *beta_lim = lo;
    return SH_OK;
}
