/* taylor_error.c — error of Krivánek et al.'s Taylor-approximated rotation
 * about y, D(β) = R_Y(β) − T(β), by singular values and for a Phong lobe.
 *
 * References
 *  [1] J. Křivánek et al. 2005 (IRISA PI 1728), Sec. 3.2 and Figure 3:
 *      E(β) = ‖D(β)Λ‖; max over unit Λ = largest singular value σ₁ of D;
 *      "average over unit Λ" taken by the paper (and CONVENTIONS.md) as the
 *      mean singular value; the actual error for the lobe cos^7.
 *  [2] GSL manual, "Singular Value Decomposition": gsl_linalg_SV_decomp_jacobi
 *      (one-sided Jacobi orthogonalization, singular values to high relative
 *      accuracy), returns A = U S Vᵀ with S ≥ 0 in decreasing order.
 *  [3] CONVENTIONS.md "Taylor-approximated rotation" (the three expansions
 *      and the error measures), lights: sh_lobe_zonal (closed-form
 *      coefficients of max(0, cosθ)^e about +z).
 *
 * D is block diagonal (bands do not mix), so its singular values are those
 * of the band blocks together; each (2l+1)² block is decomposed alone.
 * R_Y(β) comes from the zxzxz method (exact, accurate to l = 1000); T(β) from
 * the taylor plan's blocks (the kernel under test).  sh_taylor_lobe_error
 * takes the other path — the two plans applied to the lobe vector — so the
 * tests can compare the two.  Both conventions give the same numbers: nocs
 * is S·D·S with S = diag(±1) orthogonal, and the lobe vector is zonal (m = 0,
 * S c = c).
 */
#include "rot_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
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

/* blocks of method m for Ry(β), CS */
static int y_blocks(int order, sh_rot_method m, double beta, double *blocks)
{
    sh_rotation rot;
    int st = sh_rotation_from_euler(0, beta, 0, &rot);
    if (st) return st;
    sh_rot_plan *p;
    if ((st = sh_rot_plan_create(order, m, SH_PREC_DOUBLE, SH_CS, &p))) return st;
    if (!(st = sh_rot_plan_set(p, &rot))) st = sh_rot_plan_blocks(p, blocks);
    sh_rot_plan_free(p);
    return st;
}

/* D(β) blocks = exact − approximation */
static int d_blocks(int order, sh_rot_method taylor, double beta, double **out)
{
    const size_t nb = sh_rot_block_offset(order);
    double *D = malloc(nb * sizeof *D), *A = malloc(nb * sizeof *A);
    int st = (!D || !A) ? sh_error(SH_ENOMEM, "taylor error: out of memory (order %d)", order) : SH_OK;
    if (!st) st = y_blocks(order, SH_ROT_ZXZXZ, beta, D);
    if (!st) st = y_blocks(order, taylor, beta, A);
    if (!st)
        for (size_t i = 0; i < nb; i++) D[i] -= A[i];
    free(A);
    if (st) {
        free(D);
        return st;
    }
    *out = D;
    return SH_OK;
}

/* Singular values of each band block of D into sv (order² values). */
static int band_svd(int order, const double *D, double *sv)
{
    const int W = 2 * order - 1;
    gsl_matrix *A = gsl_matrix_alloc((size_t)W, (size_t)W), *V = gsl_matrix_alloc((size_t)W, (size_t)W);
    gsl_vector *S = gsl_vector_alloc((size_t)W);
    if (!A || !V || !S) {
        if (A) gsl_matrix_free(A);
        if (V) gsl_matrix_free(V);
        if (S) gsl_vector_free(S);
        return sh_error(SH_ENOMEM, "taylor error: out of memory (SVD)");
    }
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int st = SH_OK;
    for (int l = 0; l < order && !st; l++) {
        const size_t w = 2 * (size_t)l + 1;
        gsl_matrix_view a = gsl_matrix_submatrix(A, 0, 0, w, w), v = gsl_matrix_submatrix(V, 0, 0, w, w);
        gsl_vector_view s = gsl_vector_subvector(S, 0, w);
        for (size_t r = 0; r < w; r++)
            for (size_t c = 0; c < w; c++) gsl_matrix_set(&a.matrix, r, c, D[sh_rot_block_offset(l) + r * w + c]);
        if (gsl_linalg_SV_decomp_jacobi(&a.matrix, &v.matrix, &s.vector))
            st = sh_error(SH_ENUM, "taylor error: Jacobi SVD did not converge (band %d)", l);
        for (size_t i = 0; i < w; i++) sv[(size_t)l * l + i] = gsl_vector_get(&s.vector, i);
    }
    gsl_set_error_handler(old);
    gsl_matrix_free(A);
    gsl_matrix_free(V);
    gsl_vector_free(S);
    return st;
}

int sh_taylor_singular_values(int order, sh_rot_method taylor, double beta, double *sv)
{
    int st = ty_check(order, taylor, beta);
    if (st) return st;
    double *D;
    if ((st = d_blocks(order, taylor, beta, &D))) return st;
    st = band_svd(order, D, sv);
    free(D);
    return st;
}

/* unit lobe vector's zonal part z[l] (coefficient of y_l^0) */
static int lobe_zonal_unit(int order, double e, double *z)
{
    int st = sh_lobe_zonal(e, order, z);
    if (st) return st;
    double n2 = 0;
    for (int l = 0; l < order; l++) n2 += z[l] * z[l];
    const double n = sqrt(n2);
    if (!(n > 0)) return sh_error(SH_EINVAL, "taylor error: lobe vector is zero");
    for (int l = 0; l < order; l++) z[l] /= n;
    return SH_OK;
}

int sh_taylor_error(int order, sh_rot_method taylor, double beta, double lobe_exp, sh_taylor_err *out)
{
    int st = ty_check(order, taylor, beta);
    if (st) return st;
    const size_t n = (size_t)order * order;
    double *sv = malloc(n * sizeof *sv), *z = malloc((size_t)order * sizeof *z), *D = NULL;
    if (!sv || !z) st = sh_error(SH_ENOMEM, "taylor error: out of memory");
    if (!st) st = lobe_zonal_unit(order, lobe_exp, z);
    if (!st) st = d_blocks(order, taylor, beta, &D);
    if (!st) st = band_svd(order, D, sv);
    if (!st) {
        double mx = 0, sum = 0, lobe2 = 0;
        for (size_t i = 0; i < n; i++) {
            mx = fmax(mx, sv[i]);
            sum += sv[i];
        }
        /* D c: c has only m = 0 entries, so band l of D c is column m = 0 times z_l */
        for (int l = 0; l < order; l++) {
            const size_t w = 2 * (size_t)l + 1;
            const double *B = D + sh_rot_block_offset(l);
            for (size_t r = 0; r < w; r++) {
                const double y = B[r * w + (size_t)l] * z[l];
                lobe2 += y * y;
            }
        }
        out->beta = beta;
        out->max = mx;
        out->mean = sum / (double)n;
        out->lobe = sqrt(lobe2);
    }
    free(sv), free(z), free(D);
    return st;
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
    if (!st) st = lobe_zonal_unit(order, lobe_exp, z);
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
