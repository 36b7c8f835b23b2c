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
#include "project/sht_internal.h"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_qrng.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* QUAD default, measured against sh_green_reference (order 4, tol 1e-13)
 * for every S from 900 to 2500: the kinks of Green's light (cosθ = 0.8 and
 * the curve 4 sinθ cos(φ−2.5) = 3) make the error erratic, ~O(S⁻²), so the
 * criterion must hold for all S past the default, not just at it:
 *   max_i |c_i − exact| ≤ 1e-5·c_0          for every S >= 922 (fails at 921),
 *   |c_i − exact| ≤ 1e-5·|c_i| on all ≠0 c_i for every S >= 1376 (fails at 1375;
 *                                            worst above: 8.6e-6 at S = 1541).
 * S = 1500 gives 5 correct significant digits on every coefficient.
 * MC: Green's example, 100 × 100 samples. */
#define QUAD_DEFAULT 1500
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
 * trigonometric polynomial of degree <= 2S−1 in φ.
 *
 * sh_project computes it by the fast transform (sht.c: one FFT per ring, the
 * Legendre sums across ring pairs), project_quad_fast below.  This is the
 * direct sum it replaced, O(S²·order + S·order²) per ring pass with Q
 * evaluated once per row and the trig factors once per column, kept as the
 * tests' independent reference. */
int sh__project_quad_direct(int order, sh_convention conv, sh_sphere_fn f, void *ctx, long S,
                            double *c)
{
    if (S > 100000000L / 2) return sh_error(SH_EINVAL, "quad: %ld nodes is too many", S);
    const int n = sh_ncoeff(order), nphi = (int)(2 * S);
    double *xs = malloc(sizeof(double) * (size_t)S * 2); /* nodes, then weights */
    double *trig = malloc(sizeof(double) * (size_t)nphi * order * 2); /* cos, sin of mφ_j */
    double *fr = malloc(sizeof(double) * (size_t)nphi);               /* f on one row */
    double *AB = malloc(sizeof(double) * (size_t)order * 2);          /* Σ_j f {cos, sin} */
    double *Q = malloc(sizeof(double) * sh_legendre_n(order - 1));
    if (!xs || !trig || !fr || !AB || !Q) {
        free(xs), free(trig), free(fr), free(AB), free(Q);
        return sh_error(SH_ENOMEM, "out of memory (quad with %ld nodes)", S);
    }
    int st = sh__gauss_legendre(S, xs, xs + S);
    if (st) {
        free(xs), free(trig), free(fr), free(AB), free(Q);
        return st;
    }
    sh__trig_table(order, nphi, 0.0, trig);
    memset(c, 0, sizeof(double) * (size_t)n);
    const double dphi = 2.0 * M_PI / nphi;
    for (long k = 0; k < S && !st; k++) {
        const double x = xs[k], w = xs[S + k];
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
        /* A_m, B_m = Σ_j f_j {cos, sin}(mφ_j): j outer so that the trig
         * table is read contiguously */
        double *A = AB, *B = AB + order;
        memset(AB, 0, sizeof(double) * (size_t)order * 2);
        for (int j = 0; j < nphi; j++) {
            const double fj = fr[j];
            const double *tj = trig + (size_t)j * order * 2;
            for (int m = 0; m < order; m++) {
                A[m] += fj * tj[2 * m];
                B[m] += fj * tj[2 * m + 1];
            }
        }
        sh_legendre_array(order - 1, x, Q);
        sh__ring_accumulate(order, conv, Q, dphi * w, A, B, c);
    }
    free(xs), free(trig), free(fr), free(AB), free(Q);
    return st;
}

/* ---- equal-weight sample sequences (MC, RANDOM, QMC) --------------------
 * One generator serves sh_project (streaming, any count) and sh_rule_nodes
 * (explicit node lists), so both see exactly the same points for a seed. */
typedef struct {
    sh_rule rule;
    long N, k, used; /* MC: N×N strata; k = next sample; used = total */
    gsl_rng *r;
    gsl_qrng *q;
    double shift[2];
} sampler;

static void sampler_free(sampler *s)
{
    if (s->r) gsl_rng_free(s->r);
    if (s->q) gsl_qrng_free(s->q);
    s->r = NULL;
    s->q = NULL;
}

static int sampler_init(sampler *s, sh_rule rule, long samples, unsigned long seed)
{
    s->rule = rule;
    s->k = 0;
    s->r = gsl_rng_alloc(gsl_rng_mt19937);
    s->q = rule == SH_RULE_QMC ? gsl_qrng_alloc(gsl_qrng_sobol, 2) : NULL;
    if (!s->r || (rule == SH_RULE_QMC && !s->q)) {
        sampler_free(s);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    gsl_rng_set(s->r, seed);
    s->N = lround(sqrt((double)samples));
    if (s->N < 1) s->N = 1;
    s->used = rule == SH_RULE_MC ? s->N * s->N : samples;
    s->shift[0] = s->shift[1] = 0.0;
    if (rule == SH_RULE_QMC && seed != 0) {
        s->shift[0] = gsl_rng_uniform(s->r);
        s->shift[1] = gsl_rng_uniform(s->r);
    }
    return SH_OK;
}

/* Next point (θ, φ); returns 0 when the sequence is exhausted. */
static int sampler_next(sampler *s, double *theta, double *phi)
{
    if (s->k >= s->used) return 0;
    if (s->rule == SH_RULE_MC) {
        /* Green's SH_setup_spherical_samples [1]: N×N strata of the unit
         * square, one jittered point in each, x = (a+ξ)/N, y = (b+ξ)/N,
         * θ = 2 acos(√(1−x)) (so cosθ = 1−2x, uniform), φ = 2πy; w = 4π/N². */
        const long a = s->k / s->N, b = s->k % s->N;
        const double inv = 1.0 / (double)s->N;
        const double x = (a + gsl_rng_uniform(s->r)) * inv;
        const double y = (b + gsl_rng_uniform(s->r)) * inv;
        *theta = 2.0 * acos(sqrt(1.0 - x));
        *phi = 2.0 * M_PI * y;
    } else {
        /* Uniform on the sphere: z = 1 − 2u uniform in [−1,1], φ = 2πv.
         * RANDOM: (u,v) pseudo-random.  QMC: (u,v) the 2-D Sobol sequence
         * shifted modulo 1 by a seeded random vector [3] (seed 0: no shift). */
        double u[2];
        if (s->rule == SH_RULE_QMC) {
            gsl_qrng_get(s->q, u);
            for (int d = 0; d < 2; d++) {
                u[d] += s->shift[d];
                if (u[d] >= 1.0) u[d] -= 1.0;
            }
        } else {
            u[0] = gsl_rng_uniform(s->r);
            u[1] = gsl_rng_uniform(s->r);
        }
        *theta = acos(1.0 - 2.0 * u[0]);
        *phi = 2.0 * M_PI * u[1];
    }
    s->k++;
    return 1;
}

/* The ring callback of the fast path: f at the 2S points of ring r (the
 * same points, evaluated the same way, as the direct sum). */
typedef struct {
    sh_sphere_fn f;
    void *ctx;
    const double *x;
    int nphi;
} quad_ctx;

static int quad_ring(void *vctx, int r, double *buf)
{
    const quad_ctx *q = vctx;
    const double x = q->x[r], theta = acos(x), s = sqrt((1.0 - x) * (1.0 + x));
    for (int j = 0; j < q->nphi; j++) {
        const double phi = 2.0 * M_PI * j / q->nphi;
        const double d[3] = {s * cos(phi), s * sin(phi), x};
        buf[j] = q->f(d, theta, phi, q->ctx);
        if (!isfinite(buf[j]))
            return sh_error(SH_ENUM, "function is not finite at theta=%g phi=%g", theta, phi);
    }
    return SH_OK;
}

static int project_quad_fast(int order, sh_convention conv, sh_sphere_fn f, void *ctx, long S,
                             const sh_run_opts *opts, double *c)
{
    if (S > 100000000L / 2) return sh_error(SH_EINVAL, "quad: %ld nodes is too many", S);
    if (S > (1 << 24)) return sh_error(SH_EINVAL, "quad: %ld nodes is too many", S);
    double *xw = malloc(sizeof(double) * (size_t)S * 2);
    if (!xw) return sh_error(SH_ENOMEM, "out of memory (quad with %ld nodes)", S);
    sh_grid g;
    sh_sht *p = NULL;
    int st = sh_grid_gauss((int)S, (int)(2 * S), xw, xw + S, &g);
    if (!st) st = sh_sht_create(order, &g, 1, opts->nthreads, &p);
    if (!st) {
        sh_sht_set_progress(p, opts->progress, opts->progress_ctx);
        quad_ctx q = {f, ctx, xw, (int)(2 * S)};
        st = sh__sht_analysis_cb(p, conv, quad_ring, &q, c);
    }
    sh_sht_destroy(p);
    free(xw);
    return st;
}

int sh_project(int order, sh_convention conv, sh_sphere_fn f, void *ctx, sh_rule rule, long samples,
               unsigned long seed, double *coeffs)
{
    const sh_run_opts opts = SH_RUN_OPTS_DEFAULT;
    return sh_project_ex(order, conv, f, ctx, rule, samples, seed, &opts, coeffs);
}

int sh_project_ex(int order, sh_convention conv, sh_sphere_fn f, void *ctx, sh_rule rule,
                  long samples, unsigned long seed, const sh_run_opts *opts, double *coeffs)
{
    const sh_run_opts defaults = SH_RUN_OPTS_DEFAULT;
    if (!opts) opts = &defaults;
    int st = sh_check_order(order);
    if (st) return st;
    if (!f || !coeffs) return sh_error(SH_EINVAL, "sh_project: no function or output");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "unknown convention");
    if (rule < SH_RULE_QUAD || rule > SH_RULE_QMC) return sh_error(SH_EINVAL, "unknown projection rule");
    if (samples <= 0) samples = sh_rule_default_samples(rule);
    if (rule == SH_RULE_QUAD) return project_quad_fast(order, conv, f, ctx, samples, opts, coeffs);

    if (samples > 1000000000L) return sh_error(SH_EINVAL, "%ld samples is too many", samples);
    const int n = sh_ncoeff(order);
    double *y = malloc(sizeof(double) * (size_t)n);
    sampler sm;
    if (!y) return sh_error(SH_ENOMEM, "out of memory");
    if ((st = sampler_init(&sm, rule, samples, seed))) {
        free(y);
        return st;
    }
    memset(coeffs, 0, sizeof(double) * (size_t)n);
    double theta, phi;
    while (!st && sampler_next(&sm, &theta, &phi)) {
        double d[3];
        sh_dir_from_angles(theta, phi, d);
        const double v = f(d, theta, phi, ctx);
        if (!isfinite(v)) {
            st = sh_error(SH_ENUM, "function is not finite at theta=%g phi=%g", theta, phi);
            break;
        }
        sh_eval(order, conv, theta, phi, y);
        for (int i = 0; i < n; i++) coeffs[i] += v * y[i];
    }
    const double wgt = 4.0 * M_PI / (double)sm.used;
    for (int i = 0; i < n; i++) coeffs[i] *= wgt;
    free(y);
    sampler_free(&sm);
    return st;
}

int sh_rule_nodes(sh_rule rule, long samples, unsigned long seed, double **theta, double **phi,
                  double **weight, long *count)
{
    if (rule < SH_RULE_QUAD || rule > SH_RULE_QMC) return sh_error(SH_EINVAL, "unknown projection rule");
    if (samples <= 0) samples = sh_rule_default_samples(rule);
    const long S = samples;
    const long total = rule == SH_RULE_QUAD ? 2 * S * S : sh_rule_samples_used(rule, samples);
    if (total > 100000000L) return sh_error(SH_EINVAL, "%ld nodes is too many", total);
    double *t = malloc(sizeof(double) * (size_t)total), *p = malloc(sizeof(double) * (size_t)total);
    double *w = malloc(sizeof(double) * (size_t)total);
    if (!t || !p || !w) {
        free(t), free(p), free(w);
        return sh_error(SH_ENOMEM, "out of memory (%ld nodes)", total);
    }
    int st = SH_OK;
    if (rule == SH_RULE_QUAD) {
        double *xw = malloc(sizeof(double) * (size_t)S * 2);
        if (!xw || (st = sh__gauss_legendre(S, xw, xw + S))) {
            free(xw), free(t), free(p), free(w);
            return st ? st : sh_error(SH_ENOMEM, "out of memory");
        }
        for (long k = 0; k < S; k++)
            for (long j = 0; j < 2 * S; j++) {
                const long i = k * 2 * S + j;
                t[i] = acos(xw[k]);
                p[i] = M_PI * (double)j / (double)S;
                w[i] = xw[S + k] * M_PI / (double)S;
            }
        free(xw);
    } else {
        sampler sm;
        if ((st = sampler_init(&sm, rule, samples, seed))) {
            free(t), free(p), free(w);
            return st;
        }
        for (long i = 0; sampler_next(&sm, &t[i], &p[i]); i++) w[i] = 4.0 * M_PI / (double)total;
        sampler_free(&sm);
    }
    *theta = t;
    *phi = p;
    *weight = w;
    *count = total;
    return SH_OK;
}
