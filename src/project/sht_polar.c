/* sht_polar.c — the Legendre stage of the transforms for small m
 * (m < SHT_POLAR_M) on ring pairs close to a pole, where the recursion of
 * the kernels cancels (sht_internal.h gives the error model and the rule).
 *
 * The kernels' scaled recursion (sht_kern.c), Q_{m+i}^m = g_i T_i,
 *     T_0 = Q_m^m(x),  T_i = α_i x T_{i−1} − T_{i−2},
 * in Reinsch's form [1]: with u = 1 − x (exact for x ≥ ½, Sterbenz) and
 * D_i = T_i − T_{i−1},
 *     D_i = ((α_i − 2) − α_i u) T_{i−1} + D_{i−1},   T_i = T_{i−1} + D_i,
 *     D_0 = T_0 (T_{−1} = 0),
 * algebraically the same recursion, but the small factor α_i x − 2 is formed
 * from small terms (β_i = α_i − 2 from long double tables, α_i u) instead of
 * as the difference of two numbers near 2, so the rounding errors no longer
 * grow like 1/θ.  Measured at lmax 2047 for θ < 0.2 (scalar, against
 * tests/legendre_truth.h): 6e-13 of max|Q| at m = 0 against 4e-12 for the
 * plain form; beyond θ ≈ 0.6 the plain form is the more accurate one.  In
 * the transform (errors of single bands on the Gauss grids of lmax 1023 and
 * 2047 relative to the band's maximum on the sphere) θ < 0.1, 0.2 and 0.5
 * all give the same worst case, 3.4e-13 and 3.9e-13 (set by m ≥ 16, which the
 * kernels do), against 3.6e-12 without this path, so SHT_POLAR_THETA = 0.1,
 * the cheapest.  A ring with x < 0 runs the recursion at |x|:
 * T_i(x) = (−1)^i T_i(|x|).
 *
 * PW lanes at a time in vectors (the lanes of a pass are independent).
 * Analysis:  out[i·2nc + 2c + k] += g_i Σ_polar lanes T_i · (S or D)_{c,k}
 * Synthesis: north/south_{c,k} = E ± O, E, O the sums over even / odd i of
 *            T_i · in[i·2nc + 2c + k] (in already holds g_i c_l)
 * with the row layouts of sht_kjob (sht_internal.h).  The kernels saw a zero
 * seed on these lanes, so they added nothing to out and wrote zeros to their
 * rows, which the synthesis here overwrites.  A lane is done by the thread
 * that does its m, in a fixed order: results do not depend on threads.
 *
 *  [1] C. Reinsch, as presented in J. Stoer, R. Bulirsch, "Introduction to
 *      Numerical Analysis", §2.3.2 (the modification of Goertzel's
 *      recurrence for x near ±1); the same device, applied here to the
 *      normalised Legendre recursion. */
#include "project/sht_internal.h"

#define PW 8 /* lanes per pass */
typedef double vp __attribute__((vector_size(PW * sizeof(double))));

/* Q_m^m(x) = (−1)^m √((2m+1)!!/(4π (2m)!!)) s^m, s = √((1−x)(1+x)), in
 * long double (m < SHT_POLAR_M: no range problem). */
static double seed(int m, double x)
{
    const long double s = sqrtl((1.0L - x) * (1.0L + x));
    long double q = 0.28209479177387814347403972578038630L; /* 1/√(4π) */
    for (int k = 1; k <= m; k++) q *= -s * sqrtl((2.0L * k + 1.0L) / (2.0L * k));
    return (double)q;
}

/* Up to PW polar lanes from lane *from on; unused lanes carry T = 0. */
typedef struct {
    int n, lane[PW];
    vp u, a, t, d, odd; /* odd: the factor of T_i for odd i (−1 where x < 0) */
} pass;

static int next_pass(const sht_polar *pol, const sht_kjob *j, int n, int *from, pass *P)
{
    P->n = 0;
    for (int q = 0; q < PW; q++) P->u[q] = P->t[q] = P->d[q] = 0.0, P->odd[q] = 1.0, P->lane[q] = -1;
    for (; *from < n && P->n < PW; (*from)++) {
        const double x = j->x[*from];
        if (!sht_polar_lane(pol, x)) continue;
        const int q = P->n++;
        P->lane[q] = *from;
        P->u[q] = 1.0 - fabs(x);
        P->t[q] = P->d[q] = seed(j->m, fabs(x));
        P->odd[q] = x < 0.0 ? -1.0 : 1.0;
    }
    return P->n;
}

/* T_i from T_{i−1}, D_{i−1}: α_i = β_i + 2. */
static inline void step(pass *P, double beta)
{
    const double alpha = beta + 2.0;
    P->d += (beta - alpha * P->u) * P->t;
    P->t += P->d;
}

void sh__sht_polar_analysis(const sht_polar *pol, const sht_kjob *j, int n)
{
    const int m = j->m, nl = j->lmax - m + 1, nc = j->nchan, s = 2 * nc;
    const double *beta = pol->beta + pol->off[m];
    double *sum = j->acc; /* the kernels' scratch (nl·s·8 doubles), free again */
    for (int i = 0; i < nl * s; i++) sum[i] = 0.0;
    pass P;
    for (int from = 0; next_pass(pol, j, n, &from, &P) > 0;) {
        size_t o[PW];
        for (int q = 0; q < P.n; q++) o[q] = sht_lane_off(P.lane[q], j->dstride);
        for (int i = 0; i < nl; i++) {
            if (i) step(&P, beta[i]);
            const vp t = (i & 1) ? P.t * P.odd : P.t;
            const double *row = j->in + (size_t)(2 * (i & 1)) * SHT_GRP;
            for (int ck = 0; ck < s; ck++) {
                const double *r = row + (size_t)(4 * (ck >> 1) + (ck & 1)) * SHT_GRP;
                double acc = 0.0;
                for (int q = 0; q < P.n; q++) acc += t[q] * r[o[q]];
                sum[i * s + ck] += acc;
            }
        }
    }
    for (int i = 0; i < nl; i++)
        for (int k = 0; k < s; k++) j->out[(size_t)i * s + k] += j->g[i] * sum[i * s + k];
}

void sh__sht_polar_synthesis(const sht_polar *pol, const sht_kjob *j, int n)
{
    const int m = j->m, nl = j->lmax - m + 1, nc = j->nchan, s = 2 * nc;
    const double *beta = pol->beta + pol->off[m];
    pass P;
    for (int from = 0; next_pass(pol, j, n, &from, &P) > 0;) {
        vp eo[2][2 * SH_IMAGE_MAX_CHANNELS] = {{{0}}};
        for (int i = 0; i < nl; i++) {
            if (i) step(&P, beta[i]);
            for (int ck = 0; ck < s; ck++) eo[i & 1][ck] += P.t * j->in[(size_t)i * s + ck];
        }
        for (int q = 0; q < P.n; q++) {
            const size_t o = sht_lane_off(P.lane[q], j->dstride);
            for (int c = 0; c < nc; c++)
                for (int h = 0; h < 2; h++) {
                    const double e = eo[0][2 * c + h][q], d = eo[1][2 * c + h][q] * P.odd[q];
                    j->out[o + (size_t)(4 * c + h) * SHT_GRP] = e + d;
                    j->out[o + (size_t)(4 * c + 2 + h) * SHT_GRP] = e - d;
                }
        }
    }
}
