/* scale_interp.c — scaling matrices tabulated at sampled k and interpolated
 * in between (Wang et al. 2006, Sec. 2.2: "we numerically compute M for
 * sampled values of k, and then linearly interpolate for intermediate
 * values ... sufficient to sample 40 values of k in an exponential
 * distribution"), with the interpolation error measured against the matrix
 * computed directly at every point of a dense k grid.
 *
 * References
 *  [1] J. Wang, S. Lin, B. Guo, H.-Y. Shum, "Spherical harmonics scaling",
 *      The Visual Computer 22 (2006), Sec. 2.2 and Fig. 3.
 *  [2] GSL manual, "Interpolation" (gsl_interp_linear, gsl_interp_cspline:
 *      natural cubic spline).
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *sh_scale_spacing_name(sh_scale_spacing s)
{
    return s == SH_SPACING_GEOMETRIC ? "geometric" : s == SH_SPACING_UNIFORM ? "uniform" : "unknown";
}

int sh_scale_spacing_parse(const char *s, sh_scale_spacing *out)
{
    if (s && !strcmp(s, "geometric")) { *out = SH_SPACING_GEOMETRIC; return SH_OK; }
    if (s && !strcmp(s, "uniform")) { *out = SH_SPACING_UNIFORM; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown spacing '%s' (geometric, uniform)", s ? s : "");
}

const char *sh_scale_interp_name(sh_scale_interp_kind k)
{
    return k == SH_INTERP_LINEAR ? "linear" : k == SH_INTERP_CUBIC ? "cubic" : "unknown";
}

int sh_scale_interp_parse(const char *s, sh_scale_interp_kind *out)
{
    if (s && !strcmp(s, "linear")) { *out = SH_INTERP_LINEAR; return SH_OK; }
    if (s && !strcmp(s, "cubic")) { *out = SH_INTERP_CUBIC; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown interpolation '%s' (linear, cubic)", s ? s : "");
}

/* The q-th of n points from a to b: geometric a·(b/a)^{q/(n−1)} or uniform. */
double sh_scale_grid_point(sh_scale_spacing sp, double a, double b, int q, int n)
{
    if (n < 2) return a;
    if (q == n - 1) return b;
    const double t = (double)q / (double)(n - 1);
    return sp == SH_SPACING_GEOMETRIC ? a * pow(b / a, t) : a + (b - a) * t;
}

int sh_scale_interp_error(int order, const sh_scaling *base, int samples, sh_scale_spacing spacing,
                          double kmin, double kmax, sh_scale_interp_kind interp, int dense,
                          sh_scale_interp_result *res)
{
    return sh_scale_interp_error_progress(order, base, samples, spacing, kmin, kmax, interp, dense, res,
                                          NULL, NULL);
}

int sh_scale_interp_error_progress(int order, const sh_scaling *base, int samples,
                                   sh_scale_spacing spacing, double kmin, double kmax,
                                   sh_scale_interp_kind interp, int dense,
                                   sh_scale_interp_result *res, sh_progress_fn fn, void *ctx)
{
    if (!res) return sh_error(SH_EINVAL, "scale-interp: missing argument");
    if (dense < 2 || dense > 100000) return sh_error(SH_EINVAL, "scale-interp: dense grid of %d points (2..100000)", dense);
    sh_scale_interp_point *pts = malloc(sizeof *pts * (size_t)dense);
    if (!pts) return sh_error(SH_ENOMEM, "scale-interp: out of memory");
    int st = sh_scale_interp_points(order, base, samples, spacing, kmin, kmax, interp, dense, NULL, pts, fn, ctx);
    if (!st) st = sh_scale_interp_reduce(pts, dense, res);
    free(pts);
    return st;
}

int sh_scale_interp_reduce(const sh_scale_interp_point *pts, int dense, sh_scale_interp_result *res)
{
    if (!pts || !res || dense < 1) return sh_error(SH_EINVAL, "scale-interp: missing argument");
    /* the first point with the largest error, and the sums in grid order
     * (so that shards joined by item reproduce the one-process result) */
    double emax = 0.0, esum = 0.0, wsum = 0.0, kworst = pts[0].k;
    for (int d = 0; d < dense; d++) {
        if (pts[d].max_error > emax) { emax = pts[d].max_error; kworst = pts[d].k; }
        esum += pts[d].sum_sq;
        wsum += pts[d].weight;
    }
    res->max_error = emax;
    res->rms_error = sqrt(esum / wsum);
    res->worst_k = kworst;
    if (!isfinite(res->max_error) || !isfinite(res->rms_error))
        return sh_error(SH_ENUM, "scale-interp: error is not finite");
    return SH_OK;
}

int sh_scale_interp_points(int order, const sh_scaling *base, int samples, sh_scale_spacing spacing,
                           double kmin, double kmax, sh_scale_interp_kind interp, int dense,
                           const sh_items *items, sh_scale_interp_point *pts, sh_progress_fn fn,
                           void *ctx)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (order > SH_SCALE_MAX_ORDER) return sh_error(SH_EINVAL, "scale-interp: order %d is above %d", order, SH_SCALE_MAX_ORDER);
    if (!base || !pts) return sh_error(SH_EINVAL, "scale-interp: missing argument");
    if (spacing != SH_SPACING_GEOMETRIC && spacing != SH_SPACING_UNIFORM)
        return sh_error(SH_EINVAL, "scale-interp: unknown spacing");
    if (interp != SH_INTERP_LINEAR && interp != SH_INTERP_CUBIC)
        return sh_error(SH_EINVAL, "scale-interp: unknown interpolation");
    const int smin = interp == SH_INTERP_CUBIC ? 3 : 2;
    if (samples < smin || samples > 10000)
        return sh_error(SH_EINVAL, "scale-interp: %d samples (%s needs %d..10000)", samples,
                        sh_scale_interp_name(interp), smin);
    if (dense < 2 || dense > 100000) return sh_error(SH_EINVAL, "scale-interp: dense grid of %d points (2..100000)", dense);
    if (!isfinite(kmin) || !isfinite(kmax) || !(kmin < kmax))
        return sh_error(SH_EINVAL, "scale-interp: need kmin < kmax (got %g, %g)", kmin, kmax);
    if (spacing == SH_SPACING_GEOMETRIC && !(kmin > 0.0))
        return sh_error(SH_EINVAL, "scale-interp: geometric spacing needs 0 < kmin (got %g)", kmin);
    sh_scaling s = *base;
    s.k = kmin;
    if ((st = sh_scaling_check(&s))) return st;
    s.k = kmax;
    if ((st = sh_scaling_check(&s))) return st;
    int mine = 0, done = 0;
    for (int d = 0; d < dense; d++) mine += sh_items_own(items, d) != 0;

    const size_t P = sh_scale_integrals_n(order);
    double *ks = malloc(sizeof(double) * (size_t)samples);
    double *tab = malloc(sizeof(double) * (size_t)samples * P); /* tab[q·S + s] */
    double *I = malloc(sizeof(double) * P);
    double *work = malloc(sizeof(double) * sh_scale_work_n(order));
    gsl_interp *gi = gsl_interp_alloc(interp == SH_INTERP_CUBIC ? gsl_interp_cspline : gsl_interp_linear,
                                      (size_t)samples);
    gsl_interp_accel *acc = gsl_interp_accel_alloc();
    if (!ks || !tab || !I || !work || !gi || !acc) {
        st = sh_error(SH_ENOMEM, "scale-interp: out of memory");
        goto done;
    }
    double br[SH_SCALE_MAX_BREAKS];
    /* table of the distinct θ integrals (M_ij = 2π I) at the sampled k
     * (every shard needs all of it) */
    for (int q = 0; q < samples && !st; q++) {
        s.k = ks[q] = sh_scale_grid_point(spacing, kmin, kmax, q, samples);
        const int nb = sh_scale_breaks(&s, br);
        st = sh_scale_integrals_tau(order, sh_scale_family_tau, &s, s.energy, br, nb, I, work);
        for (size_t p = 0; p < P; p++) tab[p * samples + q] = 2.0 * M_PI * I[p];
        if (fn && !st) fn(ctx, q + 1, samples + mine, "steps (tabulating the sampled k)");
    }
    if (st) goto done;
    /* error at each dense point: each integral of block m > 0 stands for the
     * two entries (m, −m), so it counts twice in the RMS. */
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    for (int d = 0; d < dense && !st; d++) {
        if (!sh_items_own(items, d)) continue;
        s.k = sh_scale_grid_point(spacing, kmin, kmax, d, dense);
        const int nb = sh_scale_breaks(&s, br);
        st = sh_scale_integrals_tau(order, sh_scale_family_tau, &s, s.energy, br, nb, I, work);
        sh_scale_interp_point pt = {s.k, 0.0, 0.0, 0.0};
        size_t p = 0;
        for (int m = 0; m < order && !st; m++) {
            const size_t nbm = (size_t)(order - m) * (order - m);
            const double wgt = m ? 2.0 : 1.0;
            for (size_t e = 0; e < nbm; e++, p++) {
                if (gsl_interp_init(gi, ks, tab + p * samples, (size_t)samples)) {
                    st = sh_error(SH_ENUM, "scale-interp: spline set-up failed");
                    break;
                }
                gsl_interp_accel_reset(acc);
                double v;
                if (gsl_interp_eval_e(gi, ks, tab + p * samples, s.k, acc, &v)) {
                    st = sh_error(SH_ENUM, "scale-interp: interpolation failed at k = %g", s.k);
                    break;
                }
                const double err = fabs(v - 2.0 * M_PI * I[p]);
                if (!(err <= pt.max_error)) pt.max_error = err; /* NaN propagates */
                pt.sum_sq += wgt * err * err;
                pt.weight += wgt;
            }
        }
        pts[d] = pt;
        if (fn && !st) fn(ctx, samples + ++done, samples + mine, "steps (checking the dense k grid)");
    }
    gsl_set_error_handler(old);
done:
    if (gi) gsl_interp_free(gi);
    if (acc) gsl_interp_accel_free(acc);
    free(ks), free(tab), free(I), free(work);
    return st;
}
