/* shlab/taylor.h — rotation derivatives and the Taylor-approximated rotation (Krivanek et
 * al. 2005).
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_TAYLOR_H
#define SHLAB_TAYLOR_H

#include "rotate.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Derivatives of R_Y(β) = R_sh(Ry(β)) and Krivánek et al.'s (2005) Taylor
 * approximations (rotation_deriv.c, taylor_error.c; the Taylor rotations themselves are
 * rotation methods, src/rotate/rot_taylor.c).  Blocks use
 * the layout of sh_rot_block_offset; J = dR_Y/dβ at β = 0 (docs/CONVENTIONS.md). */
/* The recursion and the generator agree to 1.5e-14 of the largest entry at
 * order 32 (tests/core/test_ranges.c, deriv_top), but the Ivanic-Ruedenberg
 * recursion loses digits geometrically above: 3.5e-13 at 48, 1.1e-11 at 64
 * (the limit was 64 until that was measured). */
#define SH_DERIV_MAX_ORDER 32
/* Largest order of the Taylor rotation plans (taylor1, taylor1.5, taylor2):
 * the top of `taylor-error --order`, where tests/core/test_ranges.c checks them
 * (their blocks, and their error measures at β = π). */
#define SH_TAYLOR_MAX_ORDER 128
/* d^k R_Y/dβ^k at β, bands 0..order-1, by Krivánek's Appendix A: the Leibniz
 * rule carried through the Ivanic-Ruedenberg recursion (derivation in
 * rotation_deriv.c).  blocks: sh_rot_block_offset(order) doubles.  Any
 * k ≥ 0 and any finite β (reduced modulo 2π with remainder()); SH_EINVAL
 * when an entry would overflow (entries grow like (order−1)^k; for order
 * ≤ 2 they never do).  Cost and memory grow with k (the recursion carries
 * every derivative 0..k: O(k²) per entry). */
int sh_rot_deriv_recursion(int order, int k, double beta, sh_convention conv, double *blocks);
/* The same by the generator: R_Y(β)·J^k, R_Y(β) from the zxzxz method and J
 * from its closed form (sh_rot_deriv_J_band, rotate.h). */
int sh_rot_deriv_generator(int order, int k, double beta, sh_convention conv, double *blocks);
/* D(β) = R_Y(β) − approx(R_Y(β)) for taylor = SH_ROT_TAYLOR1/15/2: its
 * singular values (GSL one-sided Jacobi SVD, band by band: D is block
 * diagonal) give max (largest) and mean (mean of all order² values); lobe =
 * ‖D c‖₂, c the unit coefficient vector of max(0, cosθ)^lobe_exp about +z.
 * R_Y(β) exact from the zxzxz method, the approximation from the taylor plan
 * itself.  The same in both conventions (S D S has D's singular values, and
 * c is zonal). */
typedef struct { double beta, max, mean, lobe; } sh_taylor_err;
int sh_taylor_error(int order, sh_rot_method taylor, double beta, double lobe_exp, sh_taylor_err *out);
/* Only the lobe error (cheaper: no SVD). */
int sh_taylor_lobe_error(int order, sh_rot_method taylor, double beta, double lobe_exp, double *lobe);
/* The singular values of D(β), band by band concatenated (order² values). */
int sh_taylor_singular_values(int order, sh_rot_method taylor, double beta, double *sv);
/* The largest β in [0, beta_max] such that the lobe error stays <= tol for
 * every β' <= β (scan at step `step`, then bisection of the first crossing to
 * 1e-10 rad); beta_max if it never crosses. */
int sh_taylor_lobe_limit(int order, sh_rot_method taylor, double lobe_exp, double tol,
                         double beta_max, double step, double *beta_lim);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_TAYLOR_H */
