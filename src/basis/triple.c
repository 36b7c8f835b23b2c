/* triple.c — the triple-product transfer matrix of Green (2003), eq. 8:
 *
 *     M_ij = ∫ b(s) y_i(s) y_j(s) ds = Σ_k b_k G(i, j, k),
 *
 * for a light b given by coefficients (sh_triple_matrix) or as a function
 * (sh_triple_matrix_quad, a direct product quadrature used as the second,
 * independent method).  Applying M to the coefficients of a light a gives the
 * coefficients of the product a·b projected to `order` bands (Green eq. 9).
 *
 * References
 *  [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details" (2003), eqs. 8-9.
 *  [2] Gauss-Legendre nodes from sh__gauss_legendre (gauss_legendre.c: GSL's
 *      glfixed table polished by Newton steps to full double accuracy).
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int sh_triple_matrix(int order, sh_convention conv, const double *b, int border, double *M)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (border < 1 || border > SHLAB_MAX_ORDER)
        return sh_error(SH_EINVAL, "triple: light order %d out of range 1..%d", border,
                        SHLAB_MAX_ORDER);
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "triple: unknown convention");
    const int n = sh_ncoeff(order);
    /* bands of b that can contribute: l3 <= 2(order-1), and l3 < border */
    const int lmax3 = (border - 1 < 2 * (order - 1)) ? border - 1 : 2 * (order - 1);
    const int lmax = order - 1;
    const size_t rown = sh_gaunt_real_row_n(lmax, lmax);
    const size_t workn = sh_gaunt_real_row_work_n(lmax, lmax);
    int *kk = malloc(rown * sizeof *kk);
    double *gg = malloc(rown * sizeof *gg);
    double *work = malloc(workn * sizeof *work);
    if (!kk || !gg || !work) {
        free(kk); free(gg); free(work);
        return sh_error(SH_ENOMEM, "triple: out of memory");
    }
    /* [1] eq. 8 with the sparse real Gaunt row: only the O(order) non-zero
     * G(i, j, ·) are visited; M is symmetric, fill the upper triangle. */
    for (int i = 0; i < n; i++) {
        for (int j = i; j < n; j++) {
            int cnt;
            st = sh_gaunt_real_row(conv, i, j, lmax3, kk, gg, &cnt, work);
            if (st) goto done;
            double s = 0.0;
            for (int q = 0; q < cnt; q++) s += b[kk[q]] * gg[q];
            M[(size_t)i * n + j] = s;
            M[(size_t)j * n + i] = s;
        }
    }
    for (size_t q = 0; q < (size_t)n * n; q++)
        if (!isfinite(M[q])) {
            st = sh_error(SH_ENUM, "triple: non-finite matrix entry");
            break;
        }
done:
    free(kk);
    free(gg);
    free(work);
    return st;
}

int sh_triple_matrix_quad(int order, sh_convention conv, sh_sphere_fn f, void *ctx, int nodes,
                          double *M)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!f) return sh_error(SH_EINVAL, "triple: no function");
    if (nodes < 1 || nodes > 20000) return sh_error(SH_EINVAL, "triple: %d nodes out of range", nodes);
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "triple: unknown convention");
    const int n = sh_ncoeff(order);
    const int nphi = 2 * nodes;
    double *xw = malloc((size_t)nodes * 2 * sizeof *xw); /* GL nodes, then weights */
    double *y = malloc((size_t)n * sizeof *y);
    double *R = malloc((size_t)n * n * sizeof *R); /* one ring's partial sums */
    if (!xw || !y || !R) {
        free(xw);
        free(y);
        free(R);
        return sh_error(SH_ENOMEM, "triple: out of memory");
    }
    if ((st = sh__gauss_legendre(nodes, xw, xw + nodes))) {
        free(xw);
        free(y);
        free(R);
        return st;
    }
    memset(M, 0, sizeof(double) * (size_t)n * n);
    /* ∫ b y_i y_j dΩ ≈ Σ_a Σ_c w_a (2π/nphi) b y_i y_j at x_a = cosθ_a (GL)
     * and φ_c = 2π c/nphi: exact for band-limited integrands of total
     * band < min(2·nodes, nphi).  Each θ ring is summed separately, then
     * added with its weight (pairwise-style, to keep rounding ~1e-15). */
    const double dphi = 2.0 * M_PI / nphi;
    for (int a = 0; a < nodes && st == SH_OK; a++) {
        const double x = xw[a], w = xw[nodes + a];
        const double theta = acos(x);
        memset(R, 0, sizeof(double) * (size_t)n * n);
        for (int c = 0; c < nphi; c++) {
            const double phi = c * dphi;
            double dir[3];
            sh_dir_from_angles(theta, phi, dir);
            const double bv = f(dir, theta, phi, ctx);
            if (!isfinite(bv)) {
                st = sh_error(SH_ENUM, "triple: function is not finite at θ=%g φ=%g", theta, phi);
                break;
            }
            if ((st = sh_eval(order, conv, theta, phi, y))) break;
            for (int i = 0; i < n; i++) {
                const double si = bv * y[i];
                double *row = R + (size_t)i * n;
                for (int j = i; j < n; j++) row[j] += si * y[j];
            }
        }
        const double s = w * dphi;
        for (int i = 0; i < n; i++)
            for (int j = i; j < n; j++) M[(size_t)i * n + j] += s * R[(size_t)i * n + j];
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < i; j++) M[(size_t)i * n + j] = M[(size_t)j * n + i];
    free(xw);
    free(y);
    free(R);
    return st;
}
