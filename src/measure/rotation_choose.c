/* rotation_choose.c — the error of any rotation method against the exact
 * rotation, the errors on the planner's β grid (`shlab plan`; the timed
 * choice is the lab's, src/lab/planner.c), and the smallest order that
 * represents an environment image.
 *
 * References
 *  [1] J. Křivánek et al., "Fast Approximation to Spherical Harmonic
 *      Rotation" (2005), Sec. 3.2 (error of the Taylor approximations as
 *      singular values of D(β) = R_Y(β) − R'_Y(β), and the lobe error).
 *  [2] docs/CONVENTIONS.md, "Taylor-approximated rotation" (max, mean, lobe).
 *  [3] GSL reference manual, "Singular Value Decomposition":
 *      gsl_linalg_SV_decomp_jacobi (one-sided Jacobi, accurate small
 *      singular values).
 *
 * Generic error.  For a rotation (α, β, γ) the method's blocks B_l and the
 * exact blocks E_l (the MPFR reference, or zxzxz in double for speed) give the band
 * differences D_l = B_l − E_l.  A block-diagonal matrix has the union of its
 * blocks' singular values, so
 *   max  = max_l σ_max(D_l),   mean = (Σ_l Σ σ(D_l)) / n²,
 *   lobe = ‖D c‖₂ = √(Σ_l c_l² Σ_r D_l[r, 0]²)   (c zonal: only column m = 0).
 * The full rotation is Z(α)·R_Y(β)·Z(γ) for the exact and the approximate
 * methods alike, so D = Z(α)·D_Y(β)·Z(γ) with orthogonal Z's: the singular
 * values are those of D_Y(β), and Z(γ) c = c for a zonal c, so the lobe
 * error is ‖D_Y(β) c‖ too — the measures of [2], for any α, γ.
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct sh_rot_errws {
    int order, use_reference;
    sh_convention conv;
    double *exact, *blocks; /* sh_rot_block_offset(order) each */
    double *c;              /* lobe zonal coefficients c_l (unit vector) */
    double *A, *V, *S;
    sh_rot_plan *plans[SH_ROT_NMETHODS][2];
    sh_rot_plan *truth;
    sh_rotation rot;
    int have_rot;
};

int sh_rot_errws_create(int order, double lobe_exp, int use_reference, sh_rot_errws **out)
{
    return sh_rot_errws_create_conv(order, lobe_exp, use_reference, SH_CS, out);
}

int sh_rot_errws_create_conv(int order, double lobe_exp, int use_reference, sh_convention conv,
                             sh_rot_errws **out)
{
    *out = NULL;
    int st = sh_check_order(order);
    if (st) return st;
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "rotation error: unknown convention");
    if (order > 200) return sh_error(SH_EINVAL, "rotation error: order %d > 200", order);
    sh_rot_errws *w = calloc(1, sizeof *w);
    if (!w) return sh_error(SH_ENOMEM, "rotation error: out of memory");
    w->order = order;
    w->use_reference = use_reference;
    w->conv = conv;
    const size_t nb = sh_rot_block_offset(order), W = 2 * (size_t)order - 1;
    w->exact = malloc(nb * sizeof *w->exact);
    w->blocks = malloc(nb * sizeof *w->blocks);
    w->c = malloc((size_t)order * sizeof *w->c);
    w->A = malloc(W * W * sizeof *w->A);
    w->V = malloc(W * W * sizeof *w->V);
    w->S = malloc(W * sizeof *w->S);
    if (!w->exact || !w->blocks || !w->c || !w->A || !w->V || !w->S) {
        sh_rot_errws_free(w);
        return sh_error(SH_ENOMEM, "rotation error: out of memory (order %d)", order);
    }
    if ((st = sh__lobe_zonal_unit(lobe_exp, order, w->c))) { sh_rot_errws_free(w); return st; }
    if ((st = sh_rot_plan_create(order, use_reference ? SH_ROT_REFERENCE : SH_ROT_ZXZXZ, SH_PREC_DOUBLE,
                                 conv, &w->truth))) {
        sh_rot_errws_free(w);
        return st;
    }
    *out = w;
    return SH_OK;
}

void sh_rot_errws_free(sh_rot_errws *w)
{
    if (!w) return;
    for (int m = 0; m < SH_ROT_NMETHODS; m++)
        for (int p = 0; p < 2; p++) sh_rot_plan_free(w->plans[m][p]);
    sh_rot_plan_free(w->truth);
    free(w->exact); free(w->blocks); free(w->c);
    free(w->A); free(w->V); free(w->S);
    free(w);
}

int sh_rot_errws_set(sh_rot_errws *w, const sh_rotation *rot)
{
    int st;
    w->have_rot = 0;
    if ((st = sh_rot_plan_set(w->truth, rot)) || (st = sh_rot_plan_blocks(w->truth, w->exact))) return st;
    w->rot = *rot;
    w->have_rot = 1;
    return SH_OK;
}

int sh_rot_errws_eval(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err)
{
    return sh_rot_errws_eval_sv(w, method, prec, err, NULL);
}

int sh_rot_errws_eval_sv(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err,
                         double *sv)
{
    if (!w->have_rot) return sh_error(SH_EINVAL, "rotation error: no rotation set");
    if (method < 0 || method >= SH_ROT_NMETHODS || (prec != SH_PREC_DOUBLE && prec != SH_PREC_FLOAT))
        return sh_error(SH_EINVAL, "rotation error: bad method or precision");
    sh_rot_plan **pp = &w->plans[method][prec == SH_PREC_FLOAT];
    int st;
    if (!*pp && (st = sh_rot_plan_create(w->order, method, prec, w->conv, pp))) return st;
    if ((st = sh_rot_plan_set(*pp, &w->rot)) || (st = sh_rot_plan_blocks(*pp, w->blocks))) return st;
    double smax = 0, ssum = 0, lobe2 = 0, row2 = 0;
    for (int l = 0; l < w->order; l++) {
        const int n = 2 * l + 1;
        const double *B = w->blocks + sh_rot_block_offset(l), *E = w->exact + sh_rot_block_offset(l);
        double col2 = 0;
        for (int i = 0; i < n * n; i++) {
            const double d = B[i] - E[i];
            if (!isfinite(d)) return sh_error(SH_EINVAL, "rotation error: %s gave a non-finite entry",
                                              sh_rot_method_name(method));
            w->A[i] = d;
        }
        for (int r = 0; r < n; r++) {
            col2 += w->A[(size_t)r * n + l] * w->A[(size_t)r * n + l];
            double rr = 0;
            for (int c = 0; c < n; c++) rr += w->A[(size_t)r * n + c] * w->A[(size_t)r * n + c];
            row2 = fmax(row2, rr);
        }
        lobe2 += w->c[l] * w->c[l] * col2;
        /* singular values of D_l (one-sided Jacobi, [3]) */
        gsl_matrix_view A = gsl_matrix_view_array(w->A, (size_t)n, (size_t)n);
        gsl_matrix_view V = gsl_matrix_view_array(w->V, (size_t)n, (size_t)n);
        gsl_vector_view S = gsl_vector_view_array(w->S, (size_t)n);
        gsl_error_handler_t *old = gsl_set_error_handler_off();
        const int gs = gsl_linalg_SV_decomp_jacobi(&A.matrix, &V.matrix, &S.vector);
        gsl_set_error_handler(old);
        if (gs) return sh_error(SH_EINVAL, "rotation error: SVD failed (band %d)", l);
        for (int k = 0; k < n; k++) {
            smax = fmax(smax, w->S[k]);
            ssum += w->S[k];
            if (sv) sv[(size_t)l * l + k] = w->S[k];
        }
    }
    err->max = smax;
    err->mean = ssum / ((double)w->order * w->order);
    err->lobe = sqrt(lobe2);
    err->coeff = sqrt(row2);
    return SH_OK;
}

/* ---------------------------------------------------------------- choose */
static const char *const measure_names[SH_NMEASURES] = {"lobe", "max", "coeff"};
const char *sh_error_measure_name(sh_error_measure m)
{
    return (int)m >= 0 && m < SH_NMEASURES ? measure_names[m] : "lobe";
}
int sh_error_measure_parse(const char *s, sh_error_measure *out)
{
    for (int k = 0; k < SH_NMEASURES; k++)
        if (s && !strcmp(s, measure_names[k])) {
            *out = (sh_error_measure)k;
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown error measure '%s' (lobe, max or coeff)", s ? s : "");
}
double sh_rot_error_in(const sh_rot_error *e, sh_error_measure m)
{
    return m == SH_MEASURE_MAX ? e->max : m == SH_MEASURE_COEFF ? e->coeff : e->lobe;
}

static uint64_t rng_next(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 0x2545F4914F6CDD1DULL;
}

static int choose_check(const sh_rot_choose_opts *o)
{
    int st = sh_check_order(o->order);
    if (st) return st;
    if (o->order > 64) return sh_error(SH_EINVAL, "plan: order %d > 64", o->order);
    if (!(o->max_beta >= 0 && o->max_beta <= M_PI))
        return sh_error(SH_EINVAL, "plan: max beta must be in [0, pi]");
    if (!(o->tolerance > 0) || !isfinite(o->tolerance)) return sh_error(SH_EINVAL, "plan: tolerance must be > 0");
    if (!(o->beta_step > 0)) return sh_error(SH_EINVAL, "plan: beta step must be > 0");
    return SH_OK;
}

int sh_rot_choose_grid(const sh_rot_choose_opts *o, sh_rot_method ms[SH_ROT_NMETHODS], int *nm, int *nsteps)
{
    *nm = *nsteps = 0;
    const int st = choose_check(o);
    if (st) return st;
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (m == SH_ROT_REFERENCE || sh_rot_method_max_order((sh_rot_method)m) < o->order) continue;
        if (m == SH_ROT_Z && o->max_beta > 0) continue; /* z only rotates about z */
        ms[(*nm)++] = (sh_rot_method)m;
    }
    *nsteps = 1 + (o->max_beta > 0 ? (int)ceil(o->max_beta / o->beta_step - 1e-9) : 0);
    return SH_OK;
}

/* The rotation of step j of the β grid: β_j = j·h with h = max_beta / nbeta
 * (the grid's step; steps past nbeta continue it), α and γ seeded by j, so
 * a step's errors do not depend on which other steps are measured. */
static int step_rotation(const sh_rot_choose_opts *o, int nbeta, int j, sh_rotation *rot, double *beta_out)
{
    uint64_t seed = 0x9E3779B97F4A7C15ULL * (uint64_t)(j + 1);
    const double h = nbeta ? o->max_beta / nbeta : o->beta_step;
    const double beta = j <= nbeta ? (nbeta ? o->max_beta * j / nbeta : 0) : fmin(M_PI, o->max_beta + (j - nbeta) * h);
    const double a = M_PI * ((double)(rng_next(&seed) >> 11) / 9007199254740992.0 * 2 - 1);
    const double g = M_PI * ((double)(rng_next(&seed) >> 11) / 9007199254740992.0 * 2 - 1);
    if (beta_out) *beta_out = beta;
    return sh_rotation_from_euler(a, beta, g, rot);
}

int sh_rot_choose_errors(const sh_rot_choose_opts *o, const sh_items *items, double *err)
{
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm, nsteps;
    int st = sh_rot_choose_grid(o, ms, &nm, &nsteps);
    if (st) return st;
    const int nbeta = nsteps - 1;
    int mine = 0, done = 0;
    for (int j = 0; j < nsteps; j++) mine += sh_items_own(items, j) != 0;
    /* truth: the MPFR reference (every exact method is then measured, not
     * taken as the truth) up to order 32, zxzxz above */
    sh_rot_errws *w;
    if ((st = sh_rot_errws_create_conv(o->order, o->lobe_exp, o->order <= 32, o->conv, &w))) return st;
    for (int j = 0; j < nsteps && !st; j++) {
        if (!sh_items_own(items, j)) continue;
        sh_rotation rot;
        if ((st = step_rotation(o, nbeta, j, &rot, NULL)) || (st = sh_rot_errws_set(w, &rot))) break;
        for (int k = 0; k < nm && !st; k++) {
            sh_rot_error e;
            if ((st = sh_rot_errws_eval(w, ms[k], o->prec, &e))) break;
            err[(size_t)j * nm + k] = sh_rot_error_in(&e, o->measure);
        }
        /* unsharded, the steps count on into sh_rot_choose's timing */
        if (o->progress && !st)
            o->progress(o->progress_ctx, ++done, items ? mine : nsteps + nm, "steps (measuring on the β grid)");
    }
    sh_rot_errws_free(w);
    return st;
}

int sh_rot_choose_extents(const sh_rot_choose_opts *o, const sh_rot_method *methods, int n, sh_rot_error *worst,
                          double *holds_to)
{
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm, nsteps;
    int st = sh_rot_choose_grid(o, ms, &nm, &nsteps);
    if (st) return st;
    if (n < 1 || n > SH_ROT_NMETHODS) return sh_error(SH_EINVAL, "plan: extents of %d methods", n);
    const int nbeta = nsteps - 1;
    const double h = nbeta ? o->max_beta / nbeta : o->beta_step;
    /* the grid, then its continuation to π */
    const int nall = nsteps + (o->max_beta < M_PI ? (int)ceil((M_PI - o->max_beta) / h - 1e-9) : 0);
    sh_rot_errws *w;
    if ((st = sh_rot_errws_create_conv(o->order, o->lobe_exp, o->order <= 32, o->conv, &w))) return st;
    /* per method: failed within the grid, or its continuation has ended */
    int failed[SH_ROT_NMETHODS] = {0}, ended[SH_ROT_NMETHODS] = {0};
    for (int k = 0; k < n; k++) worst[k] = (sh_rot_error){0, 0, 0, 0}, holds_to[k] = -1;
    for (int j = 0; j < nall && !st; j++) {
        int active = 0;
        for (int k = 0; k < n; k++) active += j < nsteps || !ended[k];
        if (!active) break; /* the truth of the steps beyond is needed by none */
        sh_rotation rot;
        double beta;
        if ((st = step_rotation(o, nbeta, j, &rot, &beta)) || (st = sh_rot_errws_set(w, &rot))) break;
        for (int k = 0; k < n && !st; k++) {
            if (j >= nsteps && ended[k]) continue;
            sh_rot_error e;
            if ((st = sh_rot_errws_eval(w, methods[k], o->prec, &e))) break;
            const int ok = sh_rot_error_in(&e, o->measure) <= o->tolerance;
            if (j < nsteps) {
                worst[k].max = fmax(worst[k].max, e.max);
                worst[k].mean = fmax(worst[k].mean, e.mean);
                worst[k].lobe = fmax(worst[k].lobe, e.lobe);
                worst[k].coeff = fmax(worst[k].coeff, e.coeff);
                if (!ok) failed[k] = ended[k] = 1, holds_to[k] = -1;
            } else if (!ok) {
                ended[k] = 1; /* the answer holds up to the previous step */
                continue;
            }
            if (!failed[k]) holds_to[k] = beta;
        }
    }
    sh_rot_errws_free(w);
    return st;
}

int sh_rot_choose_extent(const sh_rot_choose_opts *o, sh_rot_method method, sh_rot_error *worst,
                         double *holds_to)
{
    return sh_rot_choose_extents(o, &method, 1, worst, holds_to);
}

/* ------------------------------------------------------- order for image */
int sh_order_for_image(const sh_image *img, sh_layout layout, double tol, int max_order,
                       int *order_out, double *resid)
{
    *order_out = -1;
    int st = sh_check_order(max_order);
    if (st) return st;
    if (!(tol > 0) || !isfinite(tol)) return sh_error(SH_EINVAL, "order for image: tolerance must be > 0");
    if (!img || !img->data || img->width < 1 || img->height < 1 || img->nchan < 1)
        return sh_error(SH_EINVAL, "order for image: empty image");
    const size_t np = (size_t)img->width * img->height, nn = (size_t)max_order * max_order;
    double *w = malloc(np * sizeof *w), *c = malloc((size_t)img->nchan * nn * sizeof *c);
    if (!w || !c) { free(w); free(c); return sh_error(SH_ENOMEM, "order for image: out of memory"); }
    if ((st = sh_pixel_solid_angles(layout, img->width, img->height, w)) ||
        (st = sh_project_image(img, layout, max_order, SH_CS, c))) {
        free(w); free(c);
        return st;
    }
    /* colour channels only (an alpha channel is not radiance) */
    double f2 = 0, *c2 = calloc((size_t)max_order, sizeof *c2);
    if (!c2) { free(w); free(c); return sh_error(SH_ENOMEM, "order for image: out of memory"); }
    for (int ch = 0; ch < img->nchan; ch++) {
        if (!strcmp(img->names[ch], "A")) continue;
        const float *d = img->data + (size_t)ch * np;
        for (size_t p = 0; p < np; p++) f2 += (double)d[p] * d[p] * w[p];
        for (int l = 0; l < max_order; l++)
            for (int m = -l; m <= l; m++) {
                const double v = c[(size_t)ch * nn + (size_t)sh_index(l, m)];
                c2[l] += v * v;
            }
    }
    free(w); free(c);
    if (!(f2 > 0) || !isfinite(f2)) {
        free(c2);
        return sh_error(SH_EINVAL, "order for image: the image is zero (or not finite)");
    }
    double acc = 0;
    for (int n = 1; n <= max_order; n++) {
        acc += c2[n - 1];
        /* ε² = (‖f‖² − Σ c²)/‖f‖², clamped at 0 (quadrature rounding) */
        const double r = sqrt(fmax(0.0, (f2 - acc) / f2));
        if (resid) resid[n - 1] = r;
        if (*order_out < 0 && r <= tol) *order_out = n;
    }
    free(c2);
    return SH_OK;
}
