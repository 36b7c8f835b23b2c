/* sht_internal.h — pieces of the fast spherical harmonic transforms shared by
 * the driver (sht.c), the Legendre kernels (sht_kern.c, compiled once per
 * instruction set) and the tests.  Not installed. */
#ifndef SHLAB_SHT_INTERNAL_H
#define SHLAB_SHT_INTERNAL_H

#include "core/shlab_internal.h"

#include <math.h>

/* Ring pairs are handed to the kernels in chunks padded to a multiple of
 * SHT_LANES, which every kernel's block (lanes × vectors) divides. */
#define SHT_LANES 32

/* Extended exponent of the sectoral seeds (legendre.c, [2] there): a value is
 * mant · 2^(SHT_SCALE·k) with k ≤ 0 an integer per lane.  A lane "lives" (its
 * values are accumulated) once k = 0; values with k < 0 are below
 * 2^(SHT_RESCALE − SHT_SCALE) = 2^−400 and are dropped, far below rounding of
 * the O(1) values they would be added to. */
#define SHT_SCALE 800
#define SHT_RESCALE 400

/* Lanes (ring pairs) are stored in groups of SHT_GRP, one cache line of
 * doubles: the chunk buffers are m-major, [m][group][row][SHT_GRP], so that
 * the Legendre stage reads (analysis) or writes (synthesis) the rows of one m
 * as one run, and the ring stage a line per group, row and m.  (Group-major,
 * [group][m][row][SHT_GRP], which the ring stage would write contiguously,
 * measured 2–6 % slower at lmax 1023: the kernels' side, touched once per m
 * and block, is the one that must not stride.) */
#define SHT_GRP 8

/* One job of the Legendre stage: one m, every ring pair of one chunk.  Lane
 * i of a per-m array A lives at A[(i / SHT_GRP)·stride + i % SHT_GRP]. */
typedef struct {
    int m, lmax, nchan, npad;   /* npad: lanes, a multiple of SHT_LANES */
    const double *x;            /* [npad] cosθ of the pair's north ring (0 for padding) */
    const double *mant, *scl;   /* Q_m^m(x) = mant · 2^(SHT_SCALE·scl), group stride sstride */
    size_t sstride, dstride;    /* group strides of the seeds and of in/out */
    const double *alpha, *g;    /* scaled recursion of this m (sht_kern.c), indexed by l − m */
    unsigned char *dead;        /* per group of lanes: 1 = no lane of the group lives at any
                                   check of the recursion up to lmax (so the group adds nothing
                                   and, in the synthesis, writes zeros).  A kernel sets it for
                                   the groups of a block it found so, and skips blocks whose
                                   groups all have it: the flags hold while the seeds do
                                   (sht.c clears them with the seeds), so a plan that keeps its
                                   seeds does this part of the recursion once. */
    /* analysis: in  = rows (4c + k)·SHT_GRP, k = S_re, S_im, D_re, D_im (north ± south),
     *           out[(l−m)·nchan·2 + 2c + k] = g_{l−m} Σ_lanes Q_l^m · (S or D)_k, k = re, im
     *           (the polar path then adds its lanes' sums);
     *           acc: scratch of (lmax−m+1)·nchan·2·8 doubles, 64-byte aligned.
     * synthesis: in = [(l−m)·nchan·2 + 2c + k] coefficients of this m (times g),
     *           out = rows (4c + k)·SHT_GRP, k = north re, north im, south re, south im. */
    const double *in;
    double *out, *acc;
} sht_kjob;

typedef void (*sht_kern_fn)(const sht_kjob *);

/* The ring stages of one group of SHT_GRP lanes (sht.c), between the ring
 * spectra and the chunk's rows of m = 0..m1−1, turned by e^{∓imφ0}:
 * analysis (scatter_group): the spectra, weighted, into the rows as
 *   S = north + south, D = north − south (k = S_re, S_im, D_re, D_im), no
 *   aliasing (bin k = m), w[g][side] = 0 where there is no ring (its spectrum
 *   is not read);
 * synthesis (spectra_group): the rows (k = north re, north im, south re,
 *   south im, as the kernel wrote them) into the spectra (w unused).
 * Spectrum s = 2g + side (side 1: south) of channel c is X + ((s·nchan + c)·M
 * + m)·2 (re, im); the rows of m are d + m·mstride + (4c + k)·SHT_GRP. */
typedef struct {
    int m1, nchan;
    double *X;
    size_t M;
    const double *cph, *sph;    /* cos mφ0, sin mφ0 */
    const double (*w)[2];
    double *d;
    size_t mstride;
} sht_sjob;

/* Offset of lane i in an array of groups with group stride `stride`. */
static inline size_t sht_lane_off(int i, size_t stride) { return (size_t)(i / SHT_GRP) * stride + i % SHT_GRP; }

/* The polar path (sht_polar.c).  Next to a pole the recursion of the kernels
 * loses accuracy for small m: its two characteristic roots e^{±iθ} nearly
 * coincide, α x T_{i−1} − T_{i−2} cancels, and a rounding error made at one
 * step reaches band l amplified by up to min(l − k, 1/sin θ) (measured at
 * lmax 2047: 4e-12 of max|Q| for m ≤ 2 at θ < 0.2, against ≤ 2.4e-13 for
 * m ≥ 16).  For m < SHT_POLAR_M on rings with θ < SHT_POLAR_THETA (or
 * π − θ), when lmax ≥ SHT_POLAR_LMIN, the polar path runs Reinsch's form of
 * the same recursion instead (sht_polar.c), and the SIMD kernels see a zero
 * seed on those lanes (they add nothing, and write zeros that the polar path
 * replaces).  The constants were chosen by measurement against the truth of
 * tests/legendre_truth.h (experiments/sht_accuracy). */
#ifndef SHT_POLAR_M /* (overridable at build time for the measurements) */
#define SHT_POLAR_M 16
#endif
#ifndef SHT_POLAR_THETA
#define SHT_POLAR_THETA 0.1
#endif
#ifndef SHT_POLAR_LMIN
#define SHT_POLAR_LMIN 512
#endif

typedef struct {
    int pm;                 /* m < pm take the polar path (0: none) */
    double xmin;            /* a lane is polar when |x| > xmin = cos SHT_POLAR_THETA */
    const double *beta;     /* β_i = α_i − 2 of m < pm at beta + off[m] (rounded from long double) */
    const size_t *off;
} sht_polar;

/* For job j (m < pol->pm) and the first n lanes of its chunk: add the polar
 * lanes' sums to j->out (analysis) or write their ring values (synthesis). */
void sh__sht_polar_analysis(const sht_polar *pol, const sht_kjob *j, int n);
void sh__sht_polar_synthesis(const sht_polar *pol, const sht_kjob *j, int n);
static inline int sht_polar_lane(const sht_polar *pol, double x) { return pol->pm && fabs(x) > pol->xmin; }

/* Instruction sets with a compiled kernel (sht_kern.c built once per set). */
typedef enum { SHT_ISA_AUTO = 0, SHT_ISA_BASE, SHT_ISA_AVX2, SHT_ISA_AVX512 } sht_isa;
const char *sh__sht_isa_name(sht_isa isa);
/* Non-zero if the kernels of `isa` are compiled in and this CPU runs them. */
int sh__sht_isa_usable(sht_isa isa);
/* Force the kernels of a plan (tests compare every usable set with BASE). */
int sh__sht_set_isa(sh_sht *p, sht_isa isa);
/* Use chunks of `pairs` ring pairs (a multiple of SHT_LANES, at most what the
 * plan was sized for): tests run several chunks on small grids. */
int sh__sht_set_chunk(sh_sht *p, int pairs);
/* Groups of lanes flagged dead (sht_kjob.dead) in the chunk the plan holds. */
int sh__sht_dead_groups(const sh_sht *p);

void sh__sht_analysis_base(const sht_kjob *j);
void sh__sht_synthesis_base(const sht_kjob *j);
#if defined(SHLAB_SHT_X86)
void sh__sht_analysis_avx2(const sht_kjob *j);
void sh__sht_synthesis_avx2(const sht_kjob *j);
void sh__sht_analysis_avx512(const sht_kjob *j);
void sh__sht_synthesis_avx512(const sht_kjob *j);
/* The ring stages above, m1 a multiple of 4 (4 m to a block of 8×8 transposes). */
void sh__sht_scatter_avx512(const sht_sjob *j);
void sh__sht_spectra_avx512(const sht_sjob *j);
#endif

/* Transforms with the map streamed ring by ring (sht.c): get fills buf with
 * ring r (nchan × nphi values, channel-major), put receives it.  Both are
 * called from the plan's threads at once (for different rings) when the plan
 * has more than one; a non-zero status stops the transform and is returned
 * (the failure of the lowest ring index, whatever the threads).  sigma: a
 * factor per band applied to the coefficients (window), or NULL. */
typedef int (*sht_get_fn)(void *ctx, int ring, double *buf);
typedef int (*sht_put_fn)(void *ctx, int ring, const double *buf);
int sh__sht_analysis_cb(sh_sht *p, sh_convention conv, sht_get_fn get, void *ctx, double *coeffs);
int sh__sht_synthesis_cb(sh_sht *p, sh_convention conv, const double *coeffs, const double *sigma,
                         sht_put_fn put, void *ctx);

/* The slow direct paths the transforms replaced, kept as independent
 * references for the tests: a direct sum in φ ring by ring with one
 * sh__legendre_core call per ring (project.c, envmap.c), and a direct
 * synthesis row by row (reconstruct.c, out = W × W/2 doubles per channel). */
int sh__project_quad_direct(int order, sh_convention conv, sh_sphere_fn f, void *ctx, long S,
                            double *c);
int sh__project_latlong_direct(const sh_image *img, int order, sh_convention conv,
                               double *coeffs);
int sh__reconstruct_latlong_direct(int order, sh_convention conv, const double *coeffs,
                                   const sh_window *win, int width, double *out);

#endif
