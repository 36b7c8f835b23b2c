/* shlab/measure.h — the error of rotation methods (the error engine), the β
 * grid of the planner, and the order an environment image needs.  Timing
 * (the bench engine, the planner's timed choice) is the lab's: src/lab/lab.h.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_MEASURE_H
#define SHLAB_MEASURE_H

#include "rotate.h"
#include "io.h"
#include "project.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Error of a method's rotation against the exact one (docs/CONVENTIONS.md,
 * "Taylor-approximated rotation"), computed generically: D = R_method −
 * R_exact for the rotation (α, β, γ) block by block, R_exact from the MPFR
 * reference plan (use_reference) or the zxzxz plan in double (accurate to
 * ~1e-15 for order ≤ 100; zxzxz then measures 0 against itself).  max = largest singular value of
 * D, mean = mean of all n² singular values (GSL one-sided Jacobi SVD per
 * band), lobe = ‖D c‖₂, c the unit coefficient vector of max(0, cosθ)^e
 * about +z (sh_lobe_zonal).  Since Z(α), Z(γ) are orthogonal and c is
 * zonal, these equal the measures of R_Y(β) − approx(R_Y(β)). */
/* max: the largest singular value of R_method − R_exact, i.e. the largest
 * L2 error of the coefficients of a unit-norm input, which by Parseval is
 * also the largest relative L2 error of the rotated function on the sphere;
 * mean: the mean singular value; lobe: ‖(R_method − R_exact) c‖₂ for the
 * unit lobe c; coeff: the largest error of one coefficient for a unit-norm
 * input (the largest row norm of R_method − R_exact, ≤ max). */
typedef struct { double max, mean, lobe, coeff; } sh_rot_error;
typedef struct sh_rot_errws sh_rot_errws;
int sh_rot_errws_create(int order, double lobe_exp, int use_reference, sh_rot_errws **out);
/* The same with every plan (truth and methods) in convention conv (the
 * above: SH_CS).  The measures do not depend on it. */
int sh_rot_errws_create_conv(int order, double lobe_exp, int use_reference, sh_convention conv,
                             sh_rot_errws **out);
/* Set the rotation: computes the exact blocks once. */
int sh_rot_errws_set(sh_rot_errws *w, const sh_rotation *rot);
/* Error of a method (plans are created on first use and kept). */
int sh_rot_errws_eval(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err);
/* The same, also writing all order² singular values to sv (band l's, in
 * decreasing order, at sv[l²..l²+2l]) when sv is not NULL. */
int sh_rot_errws_eval_sv(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err,
                         double *sv);
void sh_rot_errws_free(sh_rot_errws *w);

/* The planner's question (rotation_choose.c): the cheapest method whose
 * error stays within a budget.  Every method built in (reference excluded; z
 * only if max_beta = 0) is measured (against the MPFR reference up to order
 * 32, zxzxz above) over the β grid 0, h, 2h, …, max_beta (h ≤ beta_step) at
 * seeded α, γ; the lab's sh_rot_choose (src/lab/lab.h) then times them and
 * ranks those whose largest error stays ≤ tolerance. */
typedef enum { SH_MEASURE_LOBE = 0, SH_MEASURE_MAX, SH_MEASURE_COEFF } sh_error_measure;
#define SH_NMEASURES 3
/* The measure m of an error. */
double sh_rot_error_in(const sh_rot_error *e, sh_error_measure m);
const char *sh_error_measure_name(sh_error_measure m);
int sh_error_measure_parse(const char *s, sh_error_measure *out);
typedef struct {
    int order;
    double max_beta, tolerance, lobe_exp, beta_step;
    sh_error_measure measure;
    sh_precision prec;
    double target_ms; /* timing per repeat (0: 2 ms) */
    int repeat;       /* 0: 5 */
    sh_progress_fn progress; /* optional: after each β of the grid, then each method timed */
    void *progress_ctx;
    sh_convention conv;      /* convention of the plans measured and timed (0: SH_CS) */
    /* optional: the cost of a method instead of timing it (ns per rotation;
     * tests use it to be deterministic); mults are then not counted (0) */
    double (*cost)(void *ctx, sh_rot_method m, int order);
    void *cost_ctx;
    /* optional: the errors on the β grid, as sh_rot_choose_errors writes them
     * for every step (measured by shards of a sweep), instead of measuring */
    const double *grid_errors;
} sh_rot_choose_opts;
/* For one method: its worst error over the β grid in every measure, and the
 * largest β up to which the chosen measure stays ≤ tolerance — the grid
 * continued past max_beta with the same step up to π (π when it never
 * fails; −1 when it fails within the grid already). */
int sh_rot_choose_extent(const sh_rot_choose_opts *o, sh_rot_method method, sh_rot_error *worst,
                         double *holds_to);
/* The same for n methods at once (each step's exact rotation computed once
 * for all of them): worst[k], holds_to[k] for methods[k]. */
int sh_rot_choose_extents(const sh_rot_choose_opts *o, const sh_rot_method *methods, int n, sh_rot_error *worst,
                          double *holds_to);
/* The β grid of sh_rot_choose as a sweep: the candidate methods (ms, *nm)
 * and the steps j = 0..nsteps−1 (β_j = max_beta·j/(nsteps−1); α, γ seeded by
 * j).  sh_rot_choose_errors writes err[j·nm + k], the error of ms[k] at step
 * j, for the steps in items (NULL: all; the others are left untouched);
 * progress counts those steps. */
int sh_rot_choose_grid(const sh_rot_choose_opts *o, sh_rot_method ms[SH_ROT_NMETHODS], int *nm, int *nsteps);
int sh_rot_choose_errors(const sh_rot_choose_opts *o, const sh_items *items, double *err);
/* The smallest order ≤ max_order whose projection of the image (luminance:
 * Y, or 0.2126R + 0.7152G + 0.0722B) has relative L2 residual ≤ tol on the
 * sphere, by Parseval: ε² = (‖f‖² − Σc²)/‖f‖², ‖f‖² by the same pixel
 * quadrature as the projection.  *order_out = −1 if none ≤ max_order; the
 * residuals per order 1..max_order into resid (may be NULL). */
int sh_order_for_image(const sh_image *img, sh_layout layout, double tol, int max_order,
                       int *order_out, double *resid);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_MEASURE_H */
