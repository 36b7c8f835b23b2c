/* sht.c — fast spherical harmonic transforms on grids of rings of latitude:
 * analysis (projection by a quadrature rule) and synthesis (evaluation), for
 * the product Gauss rule of sh_project, lat-long environment maps and
 * reconstruction.
 *
 * A ring r at x_r = cosθ_r holds nphi points φ_j = φ0 + 2πj/nphi.  With
 * F_m(r) = Σ_j f_rj e^{−2πijm/nphi} (one real FFT per ring, FFTW3 [1]) and the
 * real basis y_l^{±m} = √2 Q_l^m {cos, sin}(mφ) (legendre.c):
 *   A_m = Σ_j f cos mφ_j = Re(e^{−imφ0} F_m),  B_m = Σ_j f sin mφ_j = −Im(e^{−imφ0} F_m),
 *   c_l^0 = Σ_r w_r Q_l^0(x_r) A_0,   c_l^{±m} = √2 Σ_r w_r Q_l^m(x_r) {A_m, B_m}
 * (Green 2003 eq. 6 with the φ sums done by the FFT), odd m negated in nocs.
 * For m ≥ nphi the sums alias: F_m = F_{m mod nphi}, or its conjugate mirror,
 * exactly what the direct sum in φ gives.  Synthesis is the transpose:
 *   a_m(x) = √2 Σ_l Q_l^m(x) c_l^m,  b_m(x) = √2 Σ_l Q_l^m(x) c_l^{−m},
 *   f(φ_j) = Re Σ_m z_m e^{imφ_j},   z_m = a_m − i b_m,
 * folded into nphi bins and evaluated by one inverse real FFT per ring.
 *
 * The Legendre sums run per m over ring pairs (x, −x) in the kernels of
 * sht_kern.c (one recursion serves both rings, Q_l^m(−x) = (−1)^(l−m) Q_l^m(x)).
 * Rings are processed in chunks of pairs so that a transform needs
 * O(L·chunk) working memory beyond its plan and its input/output: the map of
 * sh_project is never held whole.  Per chunk: (1) ring by ring, in parallel,
 * fill, FFT and scatter the m-spectra; (2) m by m, in parallel (m from 0 up,
 * dynamic schedule: the work of m is ∝ lmax − m), the Legendre kernel.  Every
 * sum is done by one thread in a fixed order, so results do not depend on
 * the number of threads.  FFTW plans are made with FFTW_ESTIMATE (the same
 * plan on every run) in sh_sht_create, outside any parallel region; threads
 * share them through the new-array execute functions on fftw_malloc'd buffers.
 *
 *  [1] M. Frigo, S. G. Johnson, "The design and implementation of FFTW3",
 *      Proc. IEEE 93 (2005) 216; FFTW manual, "Thread safety", "New-array
 *      Execute Functions".
 *  [2] M. Reinecke, D. S. Seljebotn, "Libsharp — spherical harmonic transforms
 *      revisited", A&A 554 (2013) A112 (the same organisation; its library is
 *      our oracle in the tests, not our back end).
 */
#include "project/sht_internal.h"

#include <fftw3.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define GRP SHT_GRP
_Static_assert(SHT_LANES % GRP == 0, "groups must tile a chunk");

/* Working memory budget for the chunk buffers (the m-spectra of a chunk). */
#ifndef CHUNK_BYTES
#define CHUNK_BYTES (32u << 20)
#endif

struct sh_sht {
    int order, lmax, nrings, nphi, nchan, nthreads;
    int npairs, chunk, nchunks; /* chunk: pairs per chunk, a multiple of SHT_LANES */
    int chunk_alloc;            /* the chunk the buffers were sized for */
    int seeded;                 /* 1 + the chunk whose seeds cmant, cscl hold (0: none) */
    double phi0;
    int *pn, *ps;               /* pair → north ring, south ring (−1: single ring) */
    double *px, *psin;          /* pair → cosθ, sinθ of its north ring */
    double *w;                  /* ring weights, NULL for a synthesis-only grid */
    double *rc;                 /* per m: α[0..nl), g[0..nl) at rc + moff[m], nl = lmax−m+1 */
    size_t *moff;
    double *fm;                 /* sectoral factors: Q_m^m = fm[m]·s·Q_{m−1}^{m−1}, fm[0] = Q_0^0 */
    double *cph, *sph;          /* cos mφ0, sin mφ0 */
    sht_polar pol;              /* small m next to the poles in long double (sht_polar.c) */
    double *pal;                /* its β tables, m < pol.pm, at pal + poff[m] */
    size_t *poff;
    sht_isa isa;
    sht_kern_fn ana, syn;
    fftw_plan r2c, c2r;
    /* chunk buffers */
    double *cx, *cmant, *cscl;  /* cx[chunk]; cmant, cscl: [m][chunk_alloc lanes] (m-major: a
                                   kernel job reads one run; they are written once per chunk) */
    double *cdata;              /* [m][group][nchan·4][SHT_GRP] (sht_internal.h) */
    unsigned char *cdead;       /* [m][group]: 1 once a kernel found that no lane of the group
                                   lives at this m (sht_kjob.dead); cleared with the seeds */
    double *alm;                /* coefficients m-major: m at alm + moff[m]·nchan, then
                                   [(l−m)·nchan + c]·2 + {0, 1} for c_l^{m}, c_l^{−m} */
    /* per-thread scratch */
    double **ring;              /* nchan·nphi (fftw_malloc) */
    double **fbuf;              /* nphi (fftw_malloc): FFT input/output when a channel of ring is
                                   not aligned as FFTW planned (odd nphi) */
    fftw_complex **spec;        /* nphi/2+1 (fftw_malloc) */
    fftw_complex **fold;        /* nphi, when nphi ≤ 2·lmax (aliasing), else NULL */
    double **gsp;               /* the m-spectra of one group's rings: [(2g + side)·nchan + c][m][2],
                                   gslot bins (analysis) or lmax + 1 (synthesis) to a ring */
    int gslot;                  /* bins of a ring in gsp in the analysis (gsp_slot) */
    double **acc;               /* analysis lane accumulators, 64-byte aligned */
    double **mout;              /* analysis sums of one m and chunk: (lmax+1)·nchan·2 */
    sh_progress_fn progress;
    void *pctx;
};

/* ------------------------------------------------------- instruction sets */

const char *sh__sht_isa_name(sht_isa isa)
{
    switch (isa) {
    case SHT_ISA_BASE: return "baseline";
    case SHT_ISA_AVX2: return "avx2+fma";
    case SHT_ISA_AVX512: return "avx512f";
    default: return "auto";
    }
}

int sh__sht_isa_usable(sht_isa isa)
{
    switch (isa) {
    case SHT_ISA_BASE: return 1;
#if defined(SHLAB_SHT_X86)
    case SHT_ISA_AVX2:
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case SHT_ISA_AVX512:
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f");
#endif
    default: return 0;
    }
}

int sh__sht_set_isa(sh_sht *p, sht_isa isa)
{
    if (isa == SHT_ISA_AUTO)
        isa = sh__sht_isa_usable(SHT_ISA_AVX512) ? SHT_ISA_AVX512
              : sh__sht_isa_usable(SHT_ISA_AVX2) ? SHT_ISA_AVX2 : SHT_ISA_BASE;
    if (!sh__sht_isa_usable(isa))
        return sh_error(SH_ENOTSUP, "kernels for %s are not built in or not supported by this CPU",
                        sh__sht_isa_name(isa));
    p->isa = isa;
    p->seeded = 0; /* the dead flags (sht_kjob.dead) came from another set's rounding */
    switch (isa) {
#if defined(SHLAB_SHT_X86)
    case SHT_ISA_AVX512: p->ana = sh__sht_analysis_avx512; p->syn = sh__sht_synthesis_avx512; break;
    case SHT_ISA_AVX2: p->ana = sh__sht_analysis_avx2; p->syn = sh__sht_synthesis_avx2; break;
#endif
    default: p->ana = sh__sht_analysis_base; p->syn = sh__sht_synthesis_base; break;
    }
    return SH_OK;
}

const char *sh_sht_kernel_name(const sh_sht *p) { return p ? sh__sht_isa_name(p->isa) : ""; }

int sh__sht_set_chunk(sh_sht *p, int pairs)
{
    if (!p || pairs < SHT_LANES || pairs % SHT_LANES || pairs > p->chunk_alloc)
        return sh_error(SH_EINVAL, "chunk of %d pairs (a multiple of %d, at most %d)", pairs, SHT_LANES,
                        p ? p->chunk_alloc : 0);
    p->chunk = pairs;
    p->seeded = 0;
    p->nchunks = (p->npairs + pairs - 1) / pairs;
    return SH_OK;
}

int sh__sht_dead_groups(const sh_sht *p)
{
    int n = 0;
    for (size_t i = 0; p->seeded && i < (size_t)(p->lmax + 1) * (p->chunk_alloc / GRP); i++) n += p->cdead[i];
    return n;
}

/* ------------------------------------------------------------------ grids */

int sh_grid_gauss(int nrings, int nphi, double *cos_theta, double *weight, sh_grid *g)
{
    if (nrings < 1 || nphi < 1 || !cos_theta || !weight || !g)
        return sh_error(SH_EINVAL, "sh_grid_gauss: %d rings of %d points", nrings, nphi);
    double *xw = malloc(sizeof(double) * (size_t)nrings * 2);
    if (!xw) return sh_error(SH_ENOMEM, "out of memory (Gauss grid of %d rings)", nrings);
    const int st = sh__gauss_legendre(nrings, xw, xw + nrings);
    if (st) { free(xw); return st; }
    /* north (x > 0) to south; ±x exact negatives so that the rings pair */
    for (int k = 0; k < nrings; k++) {
        const int j = nrings - 1 - k; /* GSL's nodes ascend */
        const double x = k < nrings / 2 ? xw[j] : (2 * k + 1 == nrings ? 0.0 : -xw[k]);
        const double w = k < nrings / 2 ? xw[nrings + j] : xw[nrings + k];
        cos_theta[k] = x;
        weight[k] = w * 2.0 * M_PI / nphi;
    }
    free(xw);
    *g = (sh_grid){nrings, nphi, cos_theta, weight, 0.0};
    return SH_OK;
}

int sh_grid_latlong(int width, int height, double *cos_theta, double *weight, sh_grid *g)
{
    if (width < 1 || height < 1 || !cos_theta || !g)
        return sh_error(SH_EINVAL, "sh_grid_latlong: %d×%d", width, height);
    /* row j: θ = π(j+½)/H, exact pixel solid angle (2π/W)(cos θ_top − cos θ_bottom)
     * = (2π/W)·2 sin θ sin(π/2H) (no cancellation near the poles); rows j and
     * H−1−j get exactly opposite cosθ. */
    const double half = 0.5 * M_PI / height;
    for (int j = 0; j < height; j++) {
        const int k = j < height - 1 - j ? j : height - 1 - j;
        const double th = M_PI * (k + 0.5) / height;
        const double x = 2 * j + 1 == height ? 0.0 : cos(th);
        cos_theta[j] = j == k ? x : -x;
        if (weight) weight[j] = (2.0 * M_PI / width) * 2.0 * sin(th) * sin(half);
    }
    *g = (sh_grid){height, width, cos_theta, weight, M_PI / width};
    return SH_OK;
}

/* ------------------------------------------------------------------ sizes */

static int chunk_pairs(int lmax, int nchan, int npairs)
{
    const double per = (double)(lmax + 1) * (2 + 4 * nchan) * sizeof(double);
    long c = (long)(CHUNK_BYTES / per) / SHT_LANES * SHT_LANES;
    if (c < SHT_LANES) c = SHT_LANES;
    const long all = ((long)npairs + SHT_LANES - 1) / SHT_LANES * SHT_LANES;
    return (int)(c < all ? c : all);
}

/* The m that take the polar path (sht_internal.h), and the length of their tables. */
static int polar_m(int lmax) { return lmax < SHT_POLAR_LMIN ? 0 : SHT_POLAR_M < lmax + 1 ? SHT_POLAR_M : lmax + 1; }
static size_t polar_len(int lmax, int pm) { return (size_t)pm * (lmax + 1) - (size_t)pm * (pm - 1) / 2; }

static int count_pairs(const sh_grid *g)
{
    if (!g->cos_theta) return (g->nrings + 1) / 2; /* a symmetric grid */
    int n = 0;
    for (int k = 0, j = g->nrings - 1; k <= j; k++, j--) n += (k < j && g->cos_theta[k] == -g->cos_theta[j]) ? 1 : (k < j ? 2 : 1);
    return n;
}

static int nthreads_eff(int nthreads)
{
#ifdef _OPENMP
    if (nthreads <= 0) nthreads = omp_get_max_threads();
#endif
    return nthreads < 1 ? 1 : nthreads;
}

/* Bins of a ring in gsp (analysis): N/2 + 1 when that is at most 2·(lmax + 1),
 * so that the FFT writes there itself; otherwise lmax + 1 and a copy. */
static int gsp_slot(int lmax, int nphi)
{
    return nphi / 2 + 1 > lmax + 1 && nphi / 2 + 1 <= 2 * (lmax + 1) ? nphi / 2 + 1 : lmax + 1;
}

size_t sh_sht_bytes(int order, const sh_grid *g, int nchan, int nthreads)
{
    if (order < 1 || !g || g->nrings < 1 || g->nphi < 1 || nchan < 1) return 0;
    const double L1 = order, np = count_pairs(g), T = nthreads_eff(nthreads);
    const double ch = chunk_pairs(order - 1, nchan, (int)np);
    double b = np * (2 * sizeof(int) + 2 * sizeof(double)) + g->nrings * sizeof(double);
    b += L1 * (L1 + 1) * sizeof(double) + L1 * (sizeof(size_t) + 3 * sizeof(double));
    b += ch * sizeof(double) * (1 + L1 * (2 + 4 * nchan)) + ch / GRP * L1;
    b += T * sizeof(double) *
         ((double)(nchan + 1) * g->nphi + 2 * (g->nphi / 2 + 1) + (g->nphi <= 2 * (order - 1) ? 2.0 * g->nphi : 0) +
          L1 * nchan * 2 * 8 + L1 * nchan * 2 + 8 + 2.0 * 8 * nchan * gsp_slot(order - 1, g->nphi) * 2);
    b += L1 * (L1 + 1) * nchan * sizeof(double);
    b += (double)polar_len(order - 1, polar_m(order - 1)) * sizeof(double) + SHT_POLAR_M * sizeof(size_t);
    return b > (double)SIZE_MAX / 2 ? SIZE_MAX / 2 : (size_t)b;
}

/* ------------------------------------------------------- create, destroy */

static pthread_mutex_t fftw_lock = PTHREAD_MUTEX_INITIALIZER; /* FFTW's planner is not thread-safe */

void sh_sht_destroy(sh_sht *p)
{
    if (!p) return;
    pthread_mutex_lock(&fftw_lock);
    if (p->r2c) fftw_destroy_plan(p->r2c);
    if (p->c2r) fftw_destroy_plan(p->c2r);
    pthread_mutex_unlock(&fftw_lock);
    for (int t = 0; t < p->nthreads; t++) {
        if (p->ring) fftw_free(p->ring[t]);
        if (p->fbuf) fftw_free(p->fbuf[t]);
        if (p->spec) fftw_free(p->spec[t]);
        if (p->fold) fftw_free(p->fold[t]);
        if (p->gsp) free(p->gsp[t]);
        if (p->acc) free(p->acc[t]);
        if (p->mout) free(p->mout[t]);
    }
    free(p->ring), free(p->fbuf), free(p->spec), free(p->fold), free(p->gsp), free(p->acc), free(p->mout);
    free(p->pn), free(p->ps), free(p->px), free(p->psin), free(p->w), free(p->rc), free(p->moff);
    free(p->pal), free(p->poff);
    free(p->fm), free(p->cph), free(p->sph), free(p->cx), free(p->cmant), free(p->cscl), free(p->cdata), free(p->cdead), free(p->alm);
    free(p);
}

/* The arguments of sh_sht_create, checked (order, grid, channels). */
static int sht_check_args(int order, const sh_grid *g, int nchan)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!g || !g->cos_theta || g->nrings < 1 || g->nphi < 1)
        return sh_error(SH_EINVAL, "sh_sht_create: empty grid");
    if (nchan < 1 || nchan > SH_IMAGE_MAX_CHANNELS)
        return sh_error(SH_EINVAL, "sh_sht_create: %d channels (1..%d)", nchan, SH_IMAGE_MAX_CHANNELS);
    if (g->nrings > (1 << 24) || g->nphi > (1 << 24) || (double)g->nrings * g->nphi * nchan > 1e11)
        return sh_error(SH_EINVAL, "sh_sht_create: grid of %d × %d points is too large", g->nrings,
                        g->nphi);
    if (!isfinite(g->phi0)) return sh_error(SH_EINVAL, "sh_sht_create: phi0 is not finite");
    for (int r = 0; r < g->nrings; r++) {
        if (!(g->cos_theta[r] >= -1.0 && g->cos_theta[r] <= 1.0))
            return sh_error(SH_EINVAL, "sh_sht_create: cos θ of ring %d is %g, not in [-1,1]", r,
                            g->cos_theta[r]);
        if (g->weight && !isfinite(g->weight[r]))
            return sh_error(SH_EINVAL, "sh_sht_create: weight of ring %d is not finite", r);
    }
    return SH_OK;
}

/* Every array of the plan (p's sizes set; pm polar m): 0, or 1 if an
 * allocation failed (sh_sht_destroy frees what was allocated). */
static int sht_alloc(sh_sht *p, const sh_grid *g, int pm)
{
    const int L = p->lmax, N = p->nphi, T = p->nthreads, nchan = p->nchan;
    const size_t nl_all = (size_t)(L + 1) * (L + 2) / 2;
    p->pn = malloc(sizeof(int) * p->npairs);
    p->ps = malloc(sizeof(int) * p->npairs);
    p->px = malloc(sizeof(double) * p->npairs);
    p->psin = malloc(sizeof(double) * p->npairs);
    p->w = g->weight ? malloc(sizeof(double) * g->nrings) : NULL;
    p->rc = malloc(sizeof(double) * 2 * nl_all);
    p->moff = malloc(sizeof(size_t) * (L + 1));
    p->fm = malloc(sizeof(double) * (L + 1));
    p->pal = pm ? malloc(sizeof(double) * polar_len(L, pm)) : NULL;
    p->poff = pm ? malloc(sizeof(size_t) * pm) : NULL;
    p->cph = malloc(sizeof(double) * (L + 1));
    p->sph = malloc(sizeof(double) * (L + 1));
    p->cx = malloc(sizeof(double) * p->chunk);
    p->cmant = malloc(sizeof(double) * (size_t)(L + 1) * p->chunk);
    p->cscl = malloc(sizeof(double) * (size_t)(L + 1) * p->chunk);
    p->cdata = aligned_alloc(64, sizeof(double) * (size_t)(L + 1) * nchan * 4 * p->chunk);
    p->cdead = malloc((size_t)(L + 1) * (p->chunk / GRP));
    p->alm = malloc(sizeof(double) * 2 * nl_all * nchan);
    p->ring = calloc(T, sizeof *p->ring);
    p->fbuf = calloc(T, sizeof *p->fbuf);
    p->spec = calloc(T, sizeof *p->spec);
    p->fold = calloc(T, sizeof *p->fold);
    p->gsp = calloc(T, sizeof *p->gsp);
    p->acc = calloc(T, sizeof *p->acc);
    p->mout = calloc(T, sizeof *p->mout);
    int bad = !p->pn || !p->ps || !p->px || !p->psin || (g->weight && !p->w) || !p->rc || !p->moff ||
              !p->fm || (pm && (!p->pal || !p->poff)) || !p->cph || !p->sph || !p->cx || !p->cmant || !p->cscl || !p->cdata || !p->cdead ||
              !p->ring || !p->fbuf || !p->spec || !p->fold || !p->gsp || !p->acc || !p->mout || !p->alm;
    const size_t accn = (size_t)(L + 1) * nchan * 2 * 8;
    for (int t = 0; t < T && !bad; t++) {
        p->ring[t] = fftw_malloc(sizeof(double) * (size_t)nchan * N);
        p->fbuf[t] = fftw_malloc(sizeof(double) * (size_t)N);
        p->spec[t] = fftw_malloc(sizeof(fftw_complex) * (size_t)(N / 2 + 1));
        p->fold[t] = N <= 2 * L ? fftw_malloc(sizeof(fftw_complex) * (size_t)N) : NULL;
        p->acc[t] = aligned_alloc(64, sizeof(double) * accn);
        p->mout[t] = malloc(sizeof(double) * (size_t)(L + 1) * nchan * 2);
        p->gsp[t] = malloc(sizeof(double) * 2 * GRP * nchan * (size_t)p->gslot * 2);
        bad = !p->ring[t] || !p->fbuf[t] || !p->spec[t] || (N <= 2 * L && !p->fold[t]) || !p->acc[t] || !p->mout[t] || !p->gsp[t];
    }
    return bad;
}

/* ring pairs: k and nrings−1−k when their cosθ are exact negatives; the
 * pairs' cosθ and sinθ, and the ring weights */
static void sht_pair_rings(sh_sht *p, const sh_grid *g)
{
    int q = 0;
    for (int k = 0, j = g->nrings - 1; k <= j; k++, j--) {
        if (k < j && g->cos_theta[k] == -g->cos_theta[j]) {
            p->pn[q] = k, p->ps[q] = j, q++;
        } else {
            p->pn[q] = k, p->ps[q] = -1, q++;
            if (k < j) p->pn[q] = j, p->ps[q] = -1, q++;
        }
    }
    for (q = 0; q < p->npairs; q++) {
        const double x = g->cos_theta[p->pn[q]];
        p->px[q] = x;
        p->psin[q] = sqrt((1.0 - x) * (1.0 + x));
    }
    if (p->w) memcpy(p->w, g->weight, sizeof(double) * g->nrings);
}

/* recursion tables (sht_kern.c), in long double: a_l = sqrt((4l²−1)/(l²−m²)),
 * c_l = a_l·sqrt(((l−1)²−m²)/(4(l−1)²−1)), g_0 = g_1 = 1, g_i = c_{m+i} g_{i−2},
 * α_i = a_{m+i} g_{i−1} / g_i, for i = l − m; the polar path's α_i − 2 for
 * m < pm; the normalisation f_m and the phase cos, sin mφ0 */
static void sht_recursion_tables(sh_sht *p, int pm)
{
    const int L = p->lmax;
    size_t off = 0, poff = 0;
    p->pol = (sht_polar){pm, cos(SHT_POLAR_THETA), p->pal, p->poff};
    for (int m = 0; m <= L; m++) {
        const int nl = L - m + 1;
        p->moff[m] = off;
        double *al = p->rc + off, *gg = al + nl;
        const long double m2 = (long double)m * m;
        long double g2 = 1.0L, g1 = 1.0L; /* g_{i−2}, g_{i−1} */
        double *pal = m < pm ? p->pal + poff : NULL;
        if (pal) p->poff[m] = poff, poff += nl, pal[0] = -2.0;
        al[0] = 0.0;
        gg[0] = 1.0;
        for (int i = 1; i < nl; i++) {
            const long double ll = m + i, lm1 = ll - 1.0L;
            const long double a = sqrtl((4.0L * ll * ll - 1.0L) / (ll * ll - m2));
            const long double c = a * sqrtl((lm1 * lm1 - m2) / (4.0L * lm1 * lm1 - 1.0L));
            const long double gi = i == 1 ? 1.0L : c * g2;
            al[i] = (double)(a * g1 / gi);
            if (pal) pal[i] = (double)(a * g1 / gi - 2.0L);
            gg[i] = (double)gi;
            g2 = g1;
            g1 = gi;
        }
        off += 2 * (size_t)nl;
        p->fm[m] = m ? -sqrt((2.0 * m + 1.0) / (2.0 * m)) : 1.0 / sqrt(4.0 * M_PI);
        p->cph[m] = cos(m * p->phi0);
        p->sph[m] = sin(m * p->phi0);
    }
}

int sh_sht_create(int order, const sh_grid *g, int nchan, int nthreads, sh_sht **out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_sht_create: output is NULL");
    *out = NULL;
    int st = sht_check_args(order, g, nchan);
    if (st) return st;
    const size_t need = sh_sht_bytes(order, g, nchan, nthreads);
    sh_sht *p = calloc(1, sizeof *p);
    if (!p) return sh_error(SH_ENOMEM, "out of memory (transform plan)");
    const int L = order - 1, N = g->nphi, T = nthreads_eff(nthreads);
    p->order = order;
    p->lmax = L;
    p->nrings = g->nrings;
    p->nphi = N;
    p->nchan = nchan;
    p->nthreads = T;
    p->phi0 = g->phi0;
    p->npairs = count_pairs(g);
    p->chunk = chunk_pairs(L, nchan, p->npairs);
    p->nchunks = (p->npairs + p->chunk - 1) / p->chunk;
    p->chunk_alloc = p->chunk;
    p->gslot = gsp_slot(L, N);
    const int pm = polar_m(L);
    if (sht_alloc(p, g, pm)) {
        sh_sht_destroy(p);
        return sh_error(SH_ENOMEM, "out of memory: the transform (order %d, %d × %d grid, %d channels, "
                                   "%d threads) needs %.3g MB", order, g->nrings, N, nchan, T, need / 1e6);
    }
    sht_pair_rings(p, g);
    sht_recursion_tables(p, pm);
    pthread_mutex_lock(&fftw_lock);
    p->r2c = fftw_plan_dft_r2c_1d(N, p->ring[0], p->spec[0], FFTW_ESTIMATE);
    p->c2r = fftw_plan_dft_c2r_1d(N, p->spec[0], p->ring[0], FFTW_ESTIMATE);
    pthread_mutex_unlock(&fftw_lock);
    if (!p->r2c || !p->c2r) {
        sh_sht_destroy(p);
        return sh_error(SH_ENOMEM, "FFTW could not plan a transform of length %d", N);
    }
    if ((st = sh__sht_set_isa(p, SHT_ISA_AUTO))) {
        sh_sht_destroy(p);
        return st;
    }
    *out = p;
    return SH_OK;
}

void sh_sht_set_progress(sh_sht *p, sh_progress_fn fn, void *ctx)
{
    if (!p) return;
    p->progress = fn;
    p->pctx = ctx;
}

/* ------------------------------------------------------------- chunks */

static inline int thread_id(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}


/* Group stride (doubles) of the chunk's data (the seeds' groups are contiguous). */
static inline size_t data_stride(const sh_sht *p) { return (size_t)p->nchan * 4 * GRP; }

/* Sectoral seeds of lanes [i0, i0+GRP) (one group) of the chunk starting at
 * pair q0 (n pairs): Q_m^m(x) = mant·2^(800·k) by the product of legendre.c,
 * Q_m^m = −sqrt((2m+1)/(2m))·s·Q_{m−1}^{m−1}, renormalised whenever the
 * mantissa falls below 2^−400.  Padding lanes get 0.  The group's dead flags
 * (sht_kjob.dead) are cleared. */
static void seeds_group(sh_sht *p, int q0, int n, int i0)
{
    typedef double v8 __attribute__((vector_size(GRP * sizeof(double))));
    typedef long long m8 __attribute__((vector_size(GRP * sizeof(double))));
    const int L = p->lmax;
    const size_t ms = (size_t)p->chunk_alloc; /* m stride */
    double *mant = p->cmant + i0, *scl = p->cscl + i0;
    v8 s, P, k = {0};
    for (int g = 0; g < GRP; g++) {
        const int live = i0 + g < n;
        s[g] = live ? p->psin[q0 + i0 + g] : 0.0;
        P[g] = live ? p->fm[0] : 0.0;
        p->cx[i0 + g] = live ? p->px[q0 + i0 + g] : 0.0;
    }
    const v8 zero = {0}, one = zero + 1.0, big = zero + 0x1p800;
    for (int m = 0; m <= L; m++) {
        if (m) {
            P *= s * p->fm[m];
            const m8 low = (P < 0x1p-400) & (P > -0x1p-400) & (P != 0.0);
            P *= (v8)(((m8)big & low) | ((m8)one & ~low));
            k -= (v8)((m8)one & low);
        }
        memcpy(mant + m * ms, &P, sizeof P);
        memcpy(scl + m * ms, &k, sizeof k);
        p->cdead[(size_t)m * (ms / GRP) + i0 / GRP] = 0;
        if (m < p->pol.pm) /* the polar path does these lanes: the kernels see zero */
            for (int g = 0; g < GRP; g++)
                if (sht_polar_lane(&p->pol, p->cx[i0 + g])) mant[m * ms + g] = 0.0;
    }
}

static sht_kjob job_for(const sh_sht *p, int m, int npad)
{
    const int nl = p->lmax - m + 1;
    sht_kjob j = {m, p->lmax, p->nchan, npad, p->cx, p->cmant + (size_t)m * p->chunk_alloc,
                  p->cscl + (size_t)m * p->chunk_alloc,
                  GRP, data_stride(p), p->rc + p->moff[m], p->rc + p->moff[m] + nl,
                  p->cdead + (size_t)m * (p->chunk_alloc / GRP), NULL, NULL, NULL};
    return j;
}

/* Row r of lane i0 + g's m-data in the chunk buffer (the group of i0). */
static inline double *data_at(sh_sht *p, int i0, int m, int c, int k)
{
    return p->cdata + (size_t)m * p->chunk_alloc * p->nchan * 4 + (size_t)(i0 / GRP) * data_stride(p) + ((size_t)c * 4 + k) * GRP;
}

/* The first failure among rings, by ring index, so that the reported error
 * does not depend on the threads. */
typedef struct {
    int st, ring;
    char msg[256];
} first_err;

static void note_err(first_err *e, int st, int ring)
{
#pragma omp critical(sht_err)
    if (!e->st || ring < e->ring) {
        e->st = st;
        e->ring = ring;
        snprintf(e->msg, sizeof e->msg, "%s", sh_last_error());
    }
}

/* Between shlab's flat layout (l(l+1)+m per channel) and the m-major alm,
 * in blocks of LBLK bands, m by m: a block's bands of one m are one short run
 * of alm, and on the flat side the block writes 2·LBLK rows that each advance
 * by one value per m, so every cache line on either side is used whole while
 * it is in L1.  It stays latency-bound all the same: perf at lmax 1023 gave
 * this step 12 % of a synthesis with 64-band blocks and 10–11 % with these
 * and the prefetch. */
#define LBLK 8
#define LPF 8 /* m ahead whose runs are prefetched */

static inline double mfactor(sh_convention conv, int m)
{
    return m ? ((conv == SH_NOCS && (m & 1)) ? -M_SQRT2 : M_SQRT2) : 1.0;
}

/* to_flat: coeffs = the analysis sums in alm, times √2 (m > 0, odd m negated
 * in nocs).  Otherwise: alm = coeffs times the same factor, the window σ_l and
 * the recursion scale g (sht_kern.c), ready for the synthesis kernel. */
static inline __attribute__((always_inline)) void alm_convert(sh_sht *p, sh_convention conv, double *coeffs,
                                                               const double *sigma, const int to_flat)
{
    const int L = p->lmax, nc = p->nchan;
    const size_t nn = (size_t)p->order * p->order;
#pragma omp parallel for schedule(dynamic) num_threads(p->nthreads)
    for (int l0 = 0; l0 <= L; l0 += LBLK) {
        const int l1 = l0 + LBLK - 1 < L ? l0 + LBLK - 1 : L;
        for (int m = 0; m <= l1; m++) {
            const double f = mfactor(conv, m), *gg = p->rc + p->moff[m] + (L - m + 1);
            double *a = p->alm + p->moff[m] * nc;
            if (m + LPF <= l1) { /* the m-major runs of m + LPF: far apart, so fetched ahead */
                const int mp = m + LPF, lp = mp > l0 ? mp : l0;
                const double *ap = p->alm + (p->moff[mp] + (size_t)(lp - mp) * 2) * nc;
                __builtin_prefetch(ap);
                __builtin_prefetch(ap + (size_t)(l1 - lp) * 2 * nc + 2 * nc - 1);
                if (!to_flat) __builtin_prefetch(p->rc + p->moff[mp] + (L - mp + 1) + (lp - mp));
            }
            for (int l = m > l0 ? m : l0; l <= l1; l++) {
                const double s = to_flat ? f : f * gg[l - m] * (sigma ? sigma[l] : 1.0);
                for (int c = 0; c < nc; c++) {
                    double *cc = coeffs + c * nn, *am = a + ((size_t)(l - m) * nc + c) * 2;
                    if (to_flat) {
                        cc[sh_index(l, m)] = s * am[0];
                        if (m) cc[sh_index(l, -m)] = s * am[1];
                    } else {
                        am[0] = s * cc[sh_index(l, m)];
                        am[1] = m ? s * cc[sh_index(l, -m)] : 0.0;
                    }
                }
            }
        }
    }
}

/* ------------------------------------------------------------- analysis */

#define MRUN 8 /* m to a thread at a time in the analysis's Legendre stage */

/* The sums of one m (out, as the kernels write them) into coeffs:
 * c_l^{±m} = √2·Σ (m > 0), odd m negated in nocs. */
static void put_m(const sh_sht *p, sh_convention conv, int m, const double *out, double *coeffs)
{
    const int L = p->lmax, nc = p->nchan;
    const size_t nn = (size_t)p->order * p->order;
    const double f = mfactor(conv, m);
    for (int l = m; l <= L; l++)
        for (int c = 0; c < nc; c++) {
            const double *o = out + ((size_t)(l - m) * nc + c) * 2;
            double *cc = coeffs + c * nn;
            cc[sh_index(l, m)] = f * o[0];
            if (m) cc[sh_index(l, -m)] = f * o[1];
        }
}

/* One group's rings, spectra in gsp (first min(N/2, lmax) + 1 bins; have[g][side]
 * = 0 where there is no ring), scaled by the ring weights and the φ0 phase and
 * written m by m into the chunk as S = north + south and D = north − south,
 * eight lanes (one cache line) per row. */
static void scatter_group(sh_sht *p, int t, int i0, int n, const double (*w)[2])
{
    const int L = p->lmax, N = p->nphi, nc = p->nchan;
    const size_t M = (size_t)p->gslot;
    const double *X = p->gsp[t];
    int m1 = 0; /* m below m1 done by a SIMD kernel */
#if defined(SHLAB_SHT_X86)
    if (p->isa == SHT_ISA_AVX512 && N >= 2 * L) { /* no aliasing: bin m */
        const sht_sjob j = {(L + 1) / 4 * 4, nc, p->gsp[t], M, p->cph, p->sph, w, data_at(p, i0, 0, 0, 0),
                            (size_t)p->chunk_alloc * nc * 4};
        sh__sht_scatter_avx512(&j);
        m1 = j.m1;
    }
#endif
    for (int m = m1; m <= L; m++) {
        /* F_m = Σ_j f_j e^{−2πijm/N}: bin k, conjugated above N/2 (aliasing) */
        int k = m % N, cj = 0;
        if (2 * k > N) k = N - k, cj = 1;
        const double cp = p->cph[m], sp = p->sph[m];
        for (int c = 0; c < nc; c++) {
            double *d = data_at(p, i0, m, c, 0);
            for (int g = 0; g < GRP; g++) {
                double A[2] = {0.0, 0.0}, B[2] = {0.0, 0.0};
                for (int side = 0; side < 2 && i0 + g < n; side++) {
                    if (w[g][side] == 0.0) continue;
                    const double *F = X + (((size_t)(2 * g + side) * nc + c) * M + k) * 2;
                    const double fr = F[0], fi = cj ? -F[1] : F[1];
                    /* A = Re(e^{−imφ0} F), B = −Im(e^{−imφ0} F) */
                    A[side] = w[g][side] * (cp * fr + sp * fi);
                    B[side] = -w[g][side] * (cp * fi - sp * fr);
                }
                d[g] = A[0] + A[1];
                d[GRP + g] = B[0] + B[1];
                d[2 * GRP + g] = A[0] - A[1];
                d[3 * GRP + g] = B[0] - B[1];
            }
        }
    }
}

int sh__sht_analysis_cb(sh_sht *p, sh_convention conv, sht_get_fn get, void *ctx, double *coeffs)
{
    if (!p || !get || !coeffs) return sh_error(SH_EINVAL, "sh_sht_analysis: NULL argument");
    if (!p->w) return sh_error(SH_EINVAL, "sh_sht_analysis: the grid has no weights");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "unknown convention");
    const int L = p->lmax, nc = p->nchan, N = p->nphi;
    /* One chunk (every ring pair at once): the sums of each m go straight into
     * coeffs.  Several: they are added up m-major in alm, then converted. */
    const int direct = p->nchunks == 1;
    if (!direct) memset(p->alm, 0, sizeof(double) * p->moff[L] * nc + 2 * nc * sizeof(double));
    first_err err = {0, 0, ""};
    for (int ch = 0; ch < p->nchunks && !err.st; ch++) {
        const int q0 = ch * p->chunk, n = p->npairs - q0 < p->chunk ? p->npairs - q0 : p->chunk;
        const int npad = (n + SHT_LANES - 1) / SHT_LANES * SHT_LANES;
        const int seed = p->seeded != ch + 1; /* one chunk: the seeds of the last transform still hold */
        /* (1) rings, a group of lanes at a time: seeds; fill, FFT, scatter */
#pragma omp parallel for schedule(dynamic) num_threads(p->nthreads)
        for (int i0 = 0; i0 < npad; i0 += GRP) {
            const int t = thread_id();
            if (seed) seeds_group(p, q0, n, i0);
            const int kmax = N / 2 < L ? N / 2 : L;
            double w[GRP][2] = {{0}};
            for (int g = 0; g < GRP && i0 + g < n; g++)
                for (int side = 0; side < 2; side++) {
                    const int r = side ? p->ps[q0 + i0 + g] : p->pn[q0 + i0 + g];
                    if (r < 0) break;
                    const int st = get(ctx, r, p->ring[t]);
                    if (st) {
                        note_err(&err, st, r);
                        break;
                    }
                    for (int c = 0; c < nc; c++) {
                        /* FFTW's new-array execute needs the alignment it planned for */
                        double *in = p->ring[t] + (size_t)c * N;
                        if (fftw_alignment_of(in) != fftw_alignment_of(p->ring[t]))
                            in = memcpy(p->fbuf[t], in, sizeof(double) * N);
                        double *slot = p->gsp[t] + ((size_t)(2 * g + side) * nc + c) * p->gslot * 2;
                        if (p->gslot >= N / 2 + 1 && fftw_alignment_of(slot) == fftw_alignment_of((double *)p->spec[t])) {
                            fftw_execute_dft_r2c(p->r2c, in, (fftw_complex *)slot);
                        } else {
                            fftw_execute_dft_r2c(p->r2c, in, p->spec[t]);
                            memcpy(slot, p->spec[t], sizeof(fftw_complex) * (size_t)(kmax + 1));
                        }
                    }
                    w[g][side] = p->w[r]; /* 0: no ring (or a ring of weight 0, which adds nothing) */
                }
            scatter_group(p, t, i0, n, (const double (*)[2])w);
        }
        p->seeded = ch + 1;
        if (err.st) break;
        /* (2) Legendre sums, m by m, in runs of MRUN m to a thread: a cache line
         * of coeffs holds neighbouring m of one band, and put_m of one run
         * writes most of its lines from one thread */
#pragma omp parallel for schedule(dynamic, MRUN) num_threads(p->nthreads)
        for (int m = 0; m <= L; m++) {
            const int t = thread_id();
            sht_kjob j = job_for(p, m, npad);
            j.in = data_at(p, 0, m, 0, 0);
            j.out = p->mout[t];
            j.acc = p->acc[t];
            p->ana(&j);
            if (m < p->pol.pm) sh__sht_polar_analysis(&p->pol, &j, n);
            if (direct) put_m(p, conv, m, j.out, coeffs);
            else {
                double *a = p->alm + p->moff[m] * nc;
                for (size_t q = 0; q < (size_t)(L - m + 1) * nc * 2; q++) a[q] += j.out[q];
            }
        }
        if (p->progress) p->progress(p->pctx, ch + 1, p->nchunks, "ring chunks");
    }
    if (err.st) return sh_error(err.st, "%s", err.msg);
    if (!direct) alm_convert(p, conv, coeffs, NULL, 1); /* inlined: one loop per direction */
    return SH_OK;
}

/* ------------------------------------------------------------ synthesis */

/* z_m e^{imφ0} (z = a − ib) of every ring of a group, from the chunk's rows
 * (north, south re/im, eight lanes per line), into gsp. */
static void spectra_group(sh_sht *p, int t, int i0)
{
    const int L = p->lmax, nc = p->nchan;
    const size_t M = (size_t)L + 1;
    double *Z = p->gsp[t];
    int m1 = 0; /* m below m1 done by a SIMD kernel */
#if defined(SHLAB_SHT_X86)
    if (p->isa == SHT_ISA_AVX512) {
        const sht_sjob j = {(L + 1) / 4 * 4, nc, Z, M, p->cph, p->sph, NULL, data_at(p, i0, 0, 0, 0),
                            (size_t)p->chunk_alloc * nc * 4};
        sh__sht_spectra_avx512(&j);
        m1 = j.m1;
    }
#endif
    for (int m = m1; m <= L; m++) {
        const double cp = p->cph[m], sp = p->sph[m];
        for (int c = 0; c < nc; c++) {
            const double *d = data_at(p, i0, m, c, 0);
            for (int g = 0; g < GRP; g++)
                for (int side = 0; side < 2; side++) {
                    const double a = d[2 * side * GRP + g], b = d[(2 * side + 1) * GRP + g];
                    double *z = Z + (((size_t)(2 * g + side) * nc + c) * M + m) * 2;
                    z[0] = a * cp + b * sp;
                    z[1] = a * sp - b * cp;
                }
        }
    }
}

/* Ring values from z_m e^{imφ0} (m = 0..lmax) into out[0..N):
 * f_j = Re Σ_m z_m e^{imφ0} e^{2πijm/N}, folded into N bins, inverse real FFT. */
static void ring_from_spectrum(sh_sht *p, int t, const double *z, double *out)
{
    const int L = p->lmax, N = p->nphi;
    fftw_complex *H = p->spec[t];
    memset(H, 0, sizeof(fftw_complex) * (size_t)(N / 2 + 1));
    fftw_complex *Z = p->fold[t];
    if (Z) {
        memset(Z, 0, sizeof(fftw_complex) * (size_t)N);
        for (int m = 0; m <= L; m++) {
            Z[m % N][0] += z[2 * m];
            Z[m % N][1] += z[2 * m + 1];
        }
        for (int k = 0; 2 * k <= N; k++) { /* H_k = (Z_k + conj Z_{N−k}) / 2 */
            const int kk = (N - k) % N;
            H[k][0] = 0.5 * (Z[k][0] + Z[kk][0]);
            H[k][1] = 0.5 * (Z[k][1] - Z[kk][1]);
        }
    } else {
        H[0][0] = z[0];
        for (int m = 1; m <= L; m++) {
            H[m][0] = 0.5 * z[2 * m];
            H[m][1] = 0.5 * z[2 * m + 1];
        }
    }
    /* FFTW's new-array execute needs the alignment it planned for */
    if (fftw_alignment_of(out) == fftw_alignment_of(p->ring[t])) {
        fftw_execute_dft_c2r(p->c2r, H, out);
    } else {
        fftw_execute_dft_c2r(p->c2r, H, p->fbuf[t]);
        memcpy(out, p->fbuf[t], sizeof(double) * N);
    }
}

int sh__sht_synthesis_cb(sh_sht *p, sh_convention conv, const double *coeffs, const double *sigma,
                         sht_put_fn put, void *ctx)
{
    if (!p || !put || !coeffs) return sh_error(SH_EINVAL, "sh_sht_synthesis: NULL argument");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "unknown convention");
    const int L = p->lmax, nc = p->nchan, N = p->nphi;
    /* the coefficients m-major, times √2 (m > 0, odd m negated in nocs), the
     * window σ_l and the recursion scale g (sht_kern.c) */
    alm_convert(p, conv, (double *)coeffs, sigma, 0); /* reads coeffs only */
    first_err err = {0, 0, ""};
    int pairs_done = 0; /* progress: ring pairs handed out, counted by group */
    for (int ch = 0; ch < p->nchunks && !err.st; ch++) {
        const int q0 = ch * p->chunk, n = p->npairs - q0 < p->chunk ? p->npairs - q0 : p->chunk;
        const int npad = (n + SHT_LANES - 1) / SHT_LANES * SHT_LANES;
        if (p->seeded != ch + 1) { /* one chunk: the seeds of the last transform still hold */
#pragma omp parallel for schedule(static) num_threads(p->nthreads)
            for (int i0 = 0; i0 < npad; i0 += GRP) seeds_group(p, q0, n, i0);
            p->seeded = ch + 1;
        }
        /* (1) Legendre sums, m by m: a_m, b_m of every ring of the chunk */
#pragma omp parallel for schedule(dynamic) num_threads(p->nthreads)
        for (int m = 0; m <= L; m++) {
            sht_kjob j = job_for(p, m, npad);
            j.in = p->alm + p->moff[m] * nc;
            j.out = data_at(p, 0, m, 0, 0);
            p->syn(&j);
            if (m < p->pol.pm) sh__sht_polar_synthesis(&p->pol, &j, n);
        }
        /* (2) rings, a group of lanes at a time: fold, inverse FFT, hand out */
#pragma omp parallel for schedule(dynamic) num_threads(p->nthreads)
        for (int i0 = 0; i0 < n; i0 += GRP) {
            const int t = thread_id();
            spectra_group(p, t, i0);
            for (int g = 0; g < GRP && i0 + g < n; g++)
                for (int side = 0; side < 2; side++) {
                    const int r = side ? p->ps[q0 + i0 + g] : p->pn[q0 + i0 + g];
                    if (r < 0) break;
                    for (int c = 0; c < nc; c++)
                        ring_from_spectrum(p, t, p->gsp[t] + ((size_t)(2 * g + side) * nc + c) * (L + 1) * 2,
                                           p->ring[t] + (size_t)c * N);
                    const int st = put(ctx, r, p->ring[t]);
                    if (st) {
                        note_err(&err, st, r);
                        break;
                    }
                }
            if (p->progress) {
                /* by group, not by chunk: a low order makes one chunk of a
                 * large map; reported from thread 0 only (one at a time) */
                int d;
#pragma omp atomic capture
                d = pairs_done += (n - i0 < GRP ? n - i0 : GRP);
                if (t == 0 && d < p->npairs) p->progress(p->pctx, d, p->npairs, "ring pairs");
            }
        }
    }
    if (p->progress && !err.st) p->progress(p->pctx, p->npairs, p->npairs, "ring pairs");
    if (err.st) return sh_error(err.st, "%s", err.msg);
    return SH_OK;
}

/* --------------------------------------------------- maps in memory */

typedef struct {
    const sh_sht *p;
    const double *map;
    double *out;
} map_ctx;

static int get_map(void *ctx, int r, double *buf)
{
    const map_ctx *m = ctx;
    const size_t N = (size_t)m->p->nphi, R = (size_t)m->p->nrings;
    for (int c = 0; c < m->p->nchan; c++) memcpy(buf + c * N, m->map + (c * R + r) * N, N * sizeof(double));
    return SH_OK;
}

static int put_map(void *ctx, int r, const double *buf)
{
    const map_ctx *m = ctx;
    const size_t N = (size_t)m->p->nphi, R = (size_t)m->p->nrings;
    for (int c = 0; c < m->p->nchan; c++) memcpy(m->out + (c * R + r) * N, buf + c * N, N * sizeof(double));
    return SH_OK;
}

int sh_sht_analysis(sh_sht *p, sh_convention conv, const double *map, double *coeffs)
{
    if (!p || !map) return sh_error(SH_EINVAL, "sh_sht_analysis: NULL argument");
    map_ctx m = {p, map, NULL};
    return sh__sht_analysis_cb(p, conv, get_map, &m, coeffs);
}

int sh_sht_synthesis(sh_sht *p, sh_convention conv, const double *coeffs, double *map)
{
    if (!p || !map) return sh_error(SH_EINVAL, "sh_sht_synthesis: NULL argument");
    map_ctx m = {p, NULL, map};
    return sh__sht_synthesis_cb(p, conv, coeffs, NULL, put_map, &m);
}
