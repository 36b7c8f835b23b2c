/* project.c — projection of a spherical function onto the real SH basis,
 *     c_i = ∫ f(s) y_i(s) dΩ,
 * by four rules: a product Gauss rule, Green's stratified Monte Carlo, plain
 * Monte Carlo and shifted Sobol quasi-Monte Carlo.
 *
 * References
 *  [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *      SH_setup_spherical_samples() and SH_project_polar_function().
 *  [2] GSL manual: fixed-order Gauss-Legendre integration, gsl_rng_mt19937,
 *      gsl_qrng_sobol.
 *  [3] R. Cranley, T. N. L. Patterson, "Randomization of number theoretic
 *      methods for multiple integration", SIAM J. Numer. Anal. 13 (1976) 904.
 */
#include "shlab_internal.h"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_qrng.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* QUAD default: Green's light (kinks along cosθ = 0.8 and along the curve
 * 4 sinθ cos(φ−2.5) = 3) needs S = 200 to reach |c_i − exact| ≤ 1e-5·c_0 on
 * all 16 coefficients of order 4 (measured against sh_green_reference; see
 * tests/test_project.c).  MC: Green's example, 100 × 100 samples. */
#define QUAD_DEFAULT 200
#define MC_DEFAULT 10000

const char *sh_rule_name(sh_rule r)
{
    switch (r) {
    case SH_RULE_QUAD: return "quad";
    case SH_RULE_MC: return "mc";
    case SH_RULE_RANDOM: return "random";
    case SH_RULE_QMC: return "qmc";
    }
    return "unknown";
}

int sh_rule_parse(const char *s, sh_rule *out)
{
    static const sh_rule all[] = {SH_RULE_QUAD, SH_RULE_MC, SH_RULE_RANDOM, SH_RULE_QMC};
    if (s)
        for (size_t k = 0; k < sizeof all / sizeof *all; k++)
            if (!strcmp(s, sh_rule_name(all[k]))) { *out = all[k]; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown projection method '%s' (expected quad, mc, random or qmc)",
                    s ? s : "(null)");
}

long sh_rule_default_samples(sh_rule r) { return r == SH_RULE_QUAD ? QUAD_DEFAULT : MC_DEFAULT; }

long sh_rule_samples_used(sh_rule r, long samples)
{
    if (samples <= 0) samples = sh_rule_default_samples(r);
    if (r == SH_RULE_MC) {
        long N = lround(sqrt((double)samples));
        return N < 1 ? 1 : N * N;
    }
    return samples;
}

/* Gauss-Legendre in x = cosθ with S nodes x_k, weights w_k, times 2S
 * uniform φ_j = 2πj/(2S):  c_lm = Σ_k w_k Q_l^|m|(x_k) · (2π/2S) Σ_j f_kj √2 trig(mφ_j).
 * Exact when f·y_i is a polynomial of degree <= 2S−1 in x and a
 * trigonometric polynomial of degree <= 2S−1 in φ.  Q is evaluated once per
 * row, the trig factors once per column. */
static int project_quad(int order, sh_convention conv, sh_sphere_fn f, void *ctx, long S, double *c)
{
    if (S > 100000000L / 2) return sh_error(SH_EINVAL, "quad: %ld nodes is too many", S);
    const int n = sh_ncoeff(order), nphi = (int)(2 * S);
    gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)S);
    double *trig = malloc(sizeof(double) * (size_t)nphi * order * 2); /* cos, sin of mφ_j */
    double *fr = malloc(sizeof(double) * (size_t)nphi);               /* f on one row */
    double *Fm = malloc(sizeof(double) * (size_t)order * 2);          /* Σ_j f trig */
    double *Q = malloc(sizeof(double) * sh_legendre_n(order - 1));
    if (!tab || !trig || !fr || !Fm || !Q) {
        if (tab) gsl_integration_glfixed_table_free(tab);
        free(trig), free(fr), free(Fm), free(Q);
        return sh_error(SH_ENOMEM, "out of memory (quad with %ld nodes)", S);
    }
    for (int j = 0; j < nphi; j++) {
        const double phi = 2.0 * M_PI * j / nphi;
        for (int m = 0; m < order; m++) {
            trig[((size_t)j * order + m) * 2] = cos(m * phi);
            trig[((size_t)j * order + m) * 2 + 1] = sin(m * phi);
        }
    }
    memset(c, 0, sizeof(double) * (size_t)n);
    const double dphi = 2.0 * M_PI / nphi;
    int st = SH_OK;
    for (long k = 0; k < S && !st; k++) {
        double x, w;
        gsl_integration_glfixed_point(-1.0, 1.0, (size_t)k, &x, &w, tab);
        const double theta = acos(x), s = sqrt((1.0 - x) * (1.0 + x));
        for (int j = 0; j < nphi; j++) {
            const double phi = 2.0 * M_PI * j / nphi;
            const double d[3] = {s * cos(phi), s * sin(phi), x};
            fr[j] = f(d, theta, phi, ctx);
            if (!isfinite(fr[j])) {
                st = sh_error(SH_ENUM, "function is not finite at theta=%g phi=%g", theta, phi);
                break;
            }
        }
        if (st) break;
        for (int m = 0; m < order; m++) {
            double sc = 0.0, ss = 0.0;
            for (int j = 0; j < nphi; j++) {
                sc += fr[j] * trig[((size_t)j * order + m) * 2];
                ss += fr[j] * trig[((size_t)j * order + m) * 2 + 1];
            }
            Fm[2 * m] = sc * dphi * w;
            Fm[2 * m + 1] = ss * dphi * w;
        }
        sh_legendre_array(order - 1, x, Q);
        for (int l = 0; l < order; l++) {
            c[sh_index(l, 0)] += Q[sh_legendre_idx(l, 0)] * Fm[0];
            for (int m = 1; m <= l; m++) {
                double q = M_SQRT2 * Q[sh_legendre_idx(l, m)];
                if (conv == SH_NOCS && (m & 1)) q = -q;
                c[sh_index(l, m)] += q * Fm[2 * m];
                c[sh_index(l, -m)] += q * Fm[2 * m + 1];
            }
        }
    }
    gsl_integration_glfixed_table_free(tab);
    free(trig), free(fr), free(Fm), free(Q);
    return st;
}

/* Accumulate one equal-weight sample at (cosθ = z, φ) (θ given as well). */
static int add_sample(int order, sh_convention conv, sh_sphere_fn f, void *ctx, double theta, double phi,
                      double *y, double *c)
{
    double d[3];
    sh_dir_from_angles(theta, phi, d);
    const double v = f(d, theta, phi, ctx);
    if (!isfinite(v)) return sh_error(SH_ENUM, "function is not finite at theta=%g phi=%g", theta, phi);
    sh_eval(order, conv, theta, phi, y);
    const int n = sh_ncoeff(order);
    for (int i = 0; i < n; i++) c[i] += v * y[i];
    return SH_OK;
}

int sh_project(int order, sh_convention conv, sh_sphere_fn f, void *ctx, sh_rule rule, long samples,
               unsigned long seed, double *coeffs)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!f || !coeffs) return sh_error(SH_EINVAL, "sh_project: no function or output");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "unknown convention");
    if (rule < SH_RULE_QUAD || rule > SH_RULE_QMC) return sh_error(SH_EINVAL, "unknown projection rule");
    if (samples <= 0) samples = sh_rule_default_samples(rule);
    if (rule == SH_RULE_QUAD) return project_quad(order, conv, f, ctx, samples, coeffs);

    if (samples > 1000000000L) return sh_error(SH_EINVAL, "%ld samples is too many", samples);
    const int n = sh_ncoeff(order);
    double *y = malloc(sizeof(double) * (size_t)n);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_qrng *q = rule == SH_RULE_QMC ? gsl_qrng_alloc(gsl_qrng_sobol, 2) : NULL;
    if (!y || !r || (rule == SH_RULE_QMC && !q)) {
        free(y);
        if (r) gsl_rng_free(r);
        if (q) gsl_qrng_free(q);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    gsl_rng_set(r, seed);
    memset(coeffs, 0, sizeof(double) * (size_t)n);
    long used = samples;
    if (rule == SH_RULE_MC) {
        /* Green's SH_setup_spherical_samples [1]: N×N strata of the unit
         * square, one jittered point in each, x = (a+ξ)/N, y = (b+ξ)/N,
         * θ = 2 acos(√(1−x)) (so cosθ = 1−2x, uniform), φ = 2πy; w = 4π/N². */
        long N = lround(sqrt((double)samples));
        if (N < 1) N = 1;
        used = N * N;
        const double inv = 1.0 / (double)N;
        for (long a = 0; a < N && !st; a++)
            for (long b = 0; b < N && !st; b++) {
                const double x = (a + gsl_rng_uniform(r)) * inv;
                const double yy = (b + gsl_rng_uniform(r)) * inv;
                st = add_sample(order, conv, f, ctx, 2.0 * acos(sqrt(1.0 - x)), 2.0 * M_PI * yy, y, coeffs);
            }
    } else {
        /* Uniform on the sphere: z = 1 − 2u uniform in [−1,1], φ = 2πv.
         * RANDOM: (u,v) pseudo-random.  QMC: (u,v) the 2-D Sobol sequence
         * shifted modulo 1 by a seeded random vector [3] (seed 0: no shift). */
        double shift[2] = {0.0, 0.0};
        if (rule == SH_RULE_QMC && seed != 0) {
            shift[0] = gsl_rng_uniform(r);
            shift[1] = gsl_rng_uniform(r);
        }
        for (long k = 0; k < samples && !st; k++) {
            double u[2];
            if (rule == SH_RULE_QMC) {
                gsl_qrng_get(q, u);
                for (int d = 0; d < 2; d++) {
                    u[d] += shift[d];
                    if (u[d] >= 1.0) u[d] -= 1.0;
                }
            } else {
                u[0] = gsl_rng_uniform(r);
                u[1] = gsl_rng_uniform(r);
            }
            const double z = 1.0 - 2.0 * u[0];
            st = add_sample(order, conv, f, ctx, acos(z), 2.0 * M_PI * u[1], y, coeffs);
        }
    }
    const double wgt = 4.0 * M_PI / (double)used;
    for (int i = 0; i < n; i++) coeffs[i] *= wgt;
    free(y);
    gsl_rng_free(r);
    if (q) gsl_qrng_free(q);
    return st;
}
