/* gauss_legendre.c — S-point Gauss-Legendre rule on [−1,1] to full double
 * accuracy, shared by the product projection rule (project.c) and the
 * quadrature transfer matrix (triple.c).
 *
 * References
 *  [1] GSL manual, "Fixed order Gauss-Legendre integration"
 *      (gsl_integration_glfixed_table_alloc / _point).
 *  [2] M. Abramowitz, I. A. Stegun, Handbook of Mathematical Functions,
 *      25.4.29 (Gauss-Legendre weights).
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_integration.h>
#include <math.h>

/* P_n(x) and P'_n(x) by the three-term recurrence (stable upwards):
 *   k P_k = (2k−1) x P_{k−1} − (k−1) P_{k−2},   (x²−1) P'_n = n (x P_n − P_{n−1}). */
static void legendre_pd(long n, double x, double *p, double *dp)
{
    double p0 = 1.0, p1 = x;
    for (long k = 2; k <= n; k++) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / (double)k;
        p0 = p1;
        p1 = p2;
    }
    *p = p1;
    *dp = (double)n * (x * p1 - p0) / (x * x - 1.0);
}

/* Gauss-Legendre nodes and weights on [−1,1].  GSL's glfixed tables are
 * exact for its precomputed sizes, but for other n its nodes are only good
 * to ~1e-10 (measured: Σw − 2 = 1.7e-10 at n = 200, 4e-10 at n = 1000), so
 * every node is polished by Newton steps on P_n and the weight recomputed,
 * w = 2 / ((1−x²) P'_n(x)²)  (Abramowitz & Stegun 25.4.29). */
int sh__gauss_legendre(long S, double *x, double *w)
{
    gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)S);
    if (!tab) return sh_error(SH_ENOMEM, "out of memory (Gauss-Legendre table of %ld nodes)", S);
    for (long k = 0; k < S; k++) gsl_integration_glfixed_point(-1.0, 1.0, (size_t)k, &x[k], &w[k], tab);
    gsl_integration_glfixed_table_free(tab);
    if (S == 1) { x[0] = 0.0; w[0] = 2.0; return SH_OK; }
    for (long k = 0; k < S; k++) {
        double xi = x[k], p, dp;
        for (int it = 0; it < 4; it++) {
            legendre_pd(S, xi, &p, &dp);
            const double dx = p / dp;
            xi -= dx;
            if (fabs(dx) <= 1e-17) break;
        }
        legendre_pd(S, xi, &p, &dp);
        x[k] = xi;
        w[k] = 2.0 / ((1.0 - xi) * (1.0 + xi) * dp * dp);
    }
    return SH_OK;
}

