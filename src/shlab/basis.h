/* shlab/basis.h — associated Legendre functions, the real SH basis, normalisations,
 * Wigner 3j symbols, Gaunt coefficients and triple products.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_BASIS_H
#define SHLAB_BASIS_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --------------------------------------------------------------- Legendre
 * Normalised associated Legendre functions  Q_l^m(x) = K_l^m P_l^m(x)
 * (P with the Condon-Shortley phase, K as in docs/CONVENTIONS.md), for
 * 0 <= m <= l <= lmax, so that y_l^0 = Q_l^0 and y_l^{±m} = √2 Q_l^m trig(mφ).
 * Holmes & Featherstone (2002) recurrence with an extended exponent for the
 * sectoral seed, so that values are correct (not flushed to zero) until the
 * true value itself is below the double range; tested against GSL
 * gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SPHARM, csphase = -1). */
size_t sh_legendre_n(int lmax);                       /* (lmax+1)(lmax+2)/2 */
static inline size_t sh_legendre_idx(int l, int m) { return (size_t)l * (l + 1) / 2 + m; }
int sh_legendre_array(int lmax, double x, double *out);  /* out[sh_legendre_idx(l,m)] */

/* ------------------------------------------------------------------ basis
 * Evaluate all n² real SH at a point.  `y` has sh_ncoeff(order) entries.
 * sh_eval_dir normalises dir; a zero, NaN or infinite vector is SH_EINVAL. */
int sh_eval(int order, sh_convention conv, double theta, double phi, double *y);
int sh_eval_dir(int order, sh_convention conv, const double dir[3], double *y);
/* Direction <-> spherical angles (θ in [0,π], φ in [0,2π)). */
void sh_dir_from_angles(double theta, double phi, double dir[3]);
int sh_angles_from_dir(const double dir[3], double *theta, double *phi);

/* Convert a coefficient vector of `order` between normalisations, in place.
 * Coefficients transform inversely to the basis functions they multiply. */
int sh_convert(int order, sh_norm from, sh_norm to, double *coeffs);
/* Switch a coefficient vector between SH_CS and SH_NOCS in place. */
void sh_convention_switch(int order, double *coeffs);

/* ------------------------------------------------------- triple products */
/* Real Gaunt coefficient G = ∫ y_i y_j y_k dΩ (flat indices, given convention),
 * via complex Gaunt coefficients from Wigner 3j symbols. */
double sh_gaunt_real(sh_convention conv, int i, int j, int k);
/* Green eq. 8: M_ij = ∫ b y_i y_j for a light given by its coefficients b of
 * order border (bands >= 2·order-1 of b cannot contribute).  M is n²×n²,
 * row-major. */
int sh_triple_matrix(int order, sh_convention conv, const double *b, int border, double *M);

/* Wigner 3j symbols (integer j) by the Schulten-Gordon recursion in j
 * (wigner3j.c).  The family  (j j2 j3; -m2-m3 m2 m3)  for j = *jmin..*jmax
 * (jmin = max(|j2-j3|, |m2+m3|), jmax = j2+j3) is written to f[j - *jmin];
 * f needs sh_wigner3j_family_n(j2, j3) entries.  An empty family (|m| > j)
 * gives *jmin > *jmax.  Single symbols: 0 outside the selection rules; the
 * plain version returns NaN on error. */
size_t sh_wigner3j_family_n(int j2, int j3);
int sh_wigner3j_family(int j2, int j3, int m2, int m3, int *jmin, int *jmax, double *f);
int sh_wigner3j_e(int j1, int j2, int j3, int m1, int m2, int m3, double *result);
double sh_wigner3j(int j1, int j2, int j3, int m1, int m2, int m3);
/* Complex Gaunt coefficient ∫ Y_l1^m1 Y_l2^m2 Y_l3^m3 dΩ (CS phase, no
 * conjugates); sh_gaunt_real_e is sh_gaunt_real with a status (gaunt.c). */
int sh_gaunt_complex_e(int l1, int m1, int l2, int m2, int l3, int m3, double *result);
int sh_gaunt_real_e(sh_convention conv, int i, int j, int k, double *result);
/* Real-basis product expansion  y_i y_j = Σ_k G(i,j,k) y_k : the possibly
 * non-zero terms with band l3 <= lmax3 are written as (k[q], g[q]),
 * q < *count <= sh_gaunt_real_row_n(l_i, l_j); `work` holds
 * sh_gaunt_real_row_work_n(l_i, l_j) doubles. */
size_t sh_gaunt_real_row_n(int l1, int l2);
size_t sh_gaunt_real_row_work_n(int l1, int l2);
int sh_gaunt_real_row(sh_convention conv, int i, int j, int lmax3, int *k, double *g,
                      int *count, double *work);
/* Second, independent method for Green eq. 8: M_ij = ∫ f y_i y_j by the
 * product rule of `nodes` Gauss-Legendre nodes in cosθ × 2·nodes uniform φ
 * (exact when f·y_i·y_j has total band < 2·nodes). */
int sh_triple_matrix_quad(int order, sh_convention conv, sh_sphere_fn f, void *ctx, int nodes,
                          double *M);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_BASIS_H */
