/* sht_kern.c — the Legendre stage of the spherical harmonic transforms (sht.c):
 * for one m and one chunk of ring pairs, the normalised associated Legendre
 * functions Q_l^m(x), l = m..lmax, by the recurrence of legendre.c, vectorised
 * across ring pairs (not along l), and
 *   analysis:  out_l,k += Σ_pairs Q_l^m(x) · (S_k if l−m even, D_k if odd),
 *   synthesis: north/south_k = E_k ± O_k,  E_k = Σ_{l−m even} Q_l^m(x) c_l,k,
 *                                           O_k = Σ_{l−m odd}  Q_l^m(x) c_l,k,
 * where S = F(north) + F(south), D = F(north) − F(south): a pair of rings at
 * ±x shares one recursion because Q_l^m(−x) = (−1)^(l−m) Q_l^m(x).
 *
 * This file is compiled once per instruction set (Makefile: baseline, AVX2+FMA,
 * AVX-512F) with GCC vector extensions; sht.c picks the widest set the CPU runs
 * (sh__sht_isa_usable) when a plan is created.  The FMA builds contract a·b+c
 * (-ffp-contract=fast), so results differ between sets by rounding only; for
 * one set they do not depend on the number of threads.
 *
 * Recurrence (Holmes & Featherstone 2002, eq. 11, as in legendre.c):
 *     Q_l^m = a_l x Q_{l−1}^m − c_l Q_{l−2}^m,   Q_{m−1}^m = 0,
 *     a_l = sqrt((4l²−1)/(l²−m²)),  c_l = a_l·sqrt(((l−1)²−m²)/(4(l−1)²−1)),
 * run in the scaled form Q_{m+i}^m = g_i T_i, g_0 = g_1 = 1, g_i = c_{m+i} g_{i−2}:
 *     T_i = α_i x T_{i−1} − T_{i−2},   α_i = a_{m+i} g_{i−1} / g_i,
 * one multiply and one fused multiply-subtract per step (the per-m tables α, g
 * are made by the plan in long double; g stays within a few powers of ten).
 * Analysis multiplies the lane sums of band l by g_i, synthesis the
 * coefficients.  The recursion is seeded by the sectoral T_0 = Q_m^m, which
 * sht.c carries as mant · 2^(800·k)
 * (Fukushima 2012's extended exponent, as legendre.c; k ≤ 0 per lane).  While
 * some lane of a block has k < 0 the "checked" loop runs: every few steps a
 * lane whose mantissa passed 2^400 is rescaled by 2^−800 and k += 1; only
 * lanes with k = 0 are accumulated (the others are < 2^−400).  Once every
 * lane has k = 0 the plain loop runs, two steps at a time so that the parity
 * of l − m is fixed per step.
 *
 *  [1] S. A. Holmes, W. E. Featherstone, J. Geodesy 76 (2002) 279.
 *  [2] T. Fukushima, J. Geodesy 86 (2012) 271.
 *  [3] M. Reinecke, D. S. Seljebotn, "Libsharp — spherical harmonic transforms
 *      revisited", A&A 554 (2013) A112 (ring pairs, vectorisation across rings).
 */
#include "project/sht_internal.h"

#include <string.h>
#if defined(SHT_KERN_AVX512) || defined(SHT_KERN_AVX2)
#include <immintrin.h>
#endif

/* VL doubles a vector; a block is NVA (analysis) or NVS (synthesis) vectors,
 * as many as the registers hold (measured with `shlab bench --peers --kernel`). */
#if defined(SHT_KERN_AVX512)
#define VL 8
#define NVA 4
#define NVS 4
#define KN(name) name##_avx512
#elif defined(SHT_KERN_AVX2)
#define VL 4
#define NVA 4
#define NVS 2
#define KN(name) name##_avx2
#else
#define VL 2
#define NVA 4
#define NVS 4
#define KN(name) name##_base
#endif
#define NVMAX 4
_Static_assert(NVA <= NVMAX && NVS <= NVMAX, "block too wide");
_Static_assert(SHT_LANES % (VL * NVA) == 0 && SHT_LANES % (VL * NVS) == 0,
               "a chunk must hold whole kernel blocks");
#define AI static inline __attribute__((always_inline))
_Static_assert(SHT_GRP % VL == 0, "a vector must lie in one group of lanes");

typedef double vd __attribute__((vector_size(VL * 8)));
typedef long long vm __attribute__((vector_size(VL * 8)));
typedef double vdu __attribute__((vector_size(VL * 8), aligned(8)));

static inline vd vload(const double *p) { return *(const vdu *)p; }
static inline void vstore(double *p, vd v) { *(vdu *)p = v; }
static inline vd bc(double s) { return (vd){0} + s; }
static inline vd sel(vm msk, vd a, vd b) { return (vd)(((vm)a & msk) | ((vm)b & ~msk)); }
static inline vd vabs(vd a) { return (vd)((vm)a & 0x7fffffffffffffffLL); }
/* Mask tests and the lane sum, with the instruction set's own reductions. */
#if defined(SHT_KERN_AVX512)
static inline unsigned msk_bits(vm m) { return _mm512_cmpneq_epi64_mask((__m512i)m, _mm512_setzero_si512()); }
static inline double hsum(vd v) { return _mm512_reduce_add_pd((__m512d)v); }
#elif defined(SHT_KERN_AVX2)
static inline unsigned msk_bits(vm m) { return (unsigned)_mm256_movemask_pd((__m256d)m); }
static inline double hsum(vd v)
{
    const __m128d h = _mm_add_pd(_mm256_castpd256_pd128((__m256d)v), _mm256_extractf128_pd((__m256d)v, 1));
    return _mm_cvtsd_f64(_mm_add_sd(h, _mm_unpackhi_pd(h, h)));
}
#else
static inline unsigned msk_bits(vm m)
{
    unsigned r = 0;
    for (int k = 0; k < VL; k++) r |= (m[k] != 0) << k;
    return r;
}
static inline double hsum(vd v)
{
    double s = 0.0;
    for (int k = 0; k < VL; k++) s += v[k];
    return s;
}
#endif

/* The lane sums of VL vectors at once, r[k] = Σ_lanes a[k]: a transpose by
 * pairwise sums (log₂ VL rounds of shuffles and adds, every add a full
 * vector), instead of VL separate reductions. */
#if defined(SHT_KERN_AVX512)
static inline vd hsum_vl(const vd *a)
{
    __m512d s[4], t[2];
    for (int k = 0; k < 4; k++) /* [a2k₀+a2k₁, a2k+1₀+a2k+1₁, a2k₂+a2k₃, …] */
        s[k] = _mm512_add_pd(_mm512_unpacklo_pd((__m512d)a[2 * k], (__m512d)a[2 * k + 1]),
                             _mm512_unpackhi_pd((__m512d)a[2 * k], (__m512d)a[2 * k + 1]));
    for (int k = 0; k < 2; k++) /* 128-bit lanes: [s0.0+s0.1, s0.2+s0.3, s1.0+s1.1, s1.2+s1.3] */
        t[k] = _mm512_add_pd(_mm512_shuffle_f64x2(s[2 * k], s[2 * k + 1], 0x88),
                             _mm512_shuffle_f64x2(s[2 * k], s[2 * k + 1], 0xdd));
    return (vd)_mm512_add_pd(_mm512_shuffle_f64x2(t[0], t[1], 0x88), _mm512_shuffle_f64x2(t[0], t[1], 0xdd));
}
#elif defined(SHT_KERN_AVX2)
static inline vd hsum_vl(const vd *a)
{
    const __m256d s0 = _mm256_add_pd(_mm256_unpacklo_pd((__m256d)a[0], (__m256d)a[1]),
                                     _mm256_unpackhi_pd((__m256d)a[0], (__m256d)a[1]));
    const __m256d s1 = _mm256_add_pd(_mm256_unpacklo_pd((__m256d)a[2], (__m256d)a[3]),
                                     _mm256_unpackhi_pd((__m256d)a[2], (__m256d)a[3]));
    return (vd)_mm256_add_pd(_mm256_permute2f128_pd(s0, s1, 0x20), _mm256_permute2f128_pd(s0, s1, 0x31));
}
#else
static inline vd hsum_vl(const vd *a)
{
    vd r;
    for (int k = 0; k < VL; k++) r[k] = hsum(a[k]);
    return r;
}
#endif
static inline int all_set(vm m) { return msk_bits(m) == (1u << VL) - 1; }
static inline int any_set(vm m) { return msk_bits(m) != 0; }

/* State of one block: nv ≤ NVMAX vectors of lanes; doff[v]: where vector v's
 * lanes start in the data rows of this m (group stride dstride, see
 * sht_lane_off). */
typedef struct {
    vd x[NVMAX], p1[NVMAX], p2[NVMAX], sc[NVMAX];
    size_t doff[NVMAX];
} blk_t;


/* The groups of lanes of block b (nv vectors): all flagged dead (sht_kjob.dead)?
 * And flagging them. */
AI int blk_dead(const sht_kjob *j, int b, const int nv)
{
    int all = 1;
    for (int g = b / SHT_GRP; g < (b + nv * VL) / SHT_GRP; g++) all &= j->dead[g];
    return all;
}
AI void blk_set_dead(const sht_kjob *j, int b, const int nv)
{
    for (int g = b / SHT_GRP; g < (b + nv * VL) / SHT_GRP; g++) j->dead[g] = 1;
}

/* Returns 0 if the block adds nothing: every seed is zero (padding, poles) or
 * every group is flagged dead; 1 if no lane lives yet, 2 if some do, 3 if all do. */
AI int blk_load(blk_t *B, const sht_kjob *j, int b, const int nv)
{
    vm nz = {0}, live = (vm){0} - 1, some = {0};
    for (int v = 0; v < nv; v++) B->doff[v] = sht_lane_off(b + v * VL, j->dstride);
    if (blk_dead(j, b, nv)) return 0;
    for (int v = 0; v < nv; v++) {
        const size_t so = sht_lane_off(b + v * VL, j->sstride);
        B->x[v] = vload(j->x + b + v * VL);
        B->p1[v] = vload(j->mant + so);
        B->sc[v] = vload(j->scl + so);
        B->p2[v] = bc(0.0);
        nz |= B->p1[v] != 0.0;
        live &= B->sc[v] == 0.0;
        some |= B->sc[v] == 0.0;
    }
    if (!any_set(nz)) return 0;
    return all_set(live) ? 3 : any_set(some) ? 2 : 1;
}

/* While some lane of a block is not live (k < 0) the block runs in groups of
 * up to RESCALE_EVERY steps: plain steps, then one check that rescales every
 * lane with k < 0 whose last two values passed 2^400 (both by 2^−800, exactly;
 * k += 1) and makes the mask of live lanes (k = 0) for the next group.  A
 * value grows by at most |α_i x| + 1 a step, and α_i ≤ √(2m) roughly (45 at
 * lmax 1023, 91 at 4096, the largest order): less than 2^6.6 a step, 2^106
 * in a group.  So values stay below 2^506, far from overflow, and a lane
 * whose value passes 2^−400 inside a group (its mantissa 2^400 with k = −1)
 * is accumulated from the next check on: what it would have added before is
 * below 2^(−400+99) = 2^−301 of an O(1) sum.  (A check costs about ten
 * operations a vector; every 16 steps instead of every 4 made the transforms
 * 5–9 % faster at lmax 511 and 1023.) */
#define RESCALE_EVERY 16

/* T_i = α_i x T_{i−1} − T_{i−2} for every lane (scaled or not). */
AI void step_plain(blk_t *B, double alpha, const int nv)
{
    for (int v = 0; v < nv; v++) {
        const vd pn = alpha * B->x[v] * B->p1[v] - B->p2[v];
        B->p2[v] = B->p1[v];
        B->p1[v] = pn;
    }
}

/* The check: rescale, and live[v] = all ones on the lanes with k = 0.
 * Returns the number of vectors whose lanes all live. */
AI int blk_rescale(blk_t *B, vm *live, const int nv)
{
    int all = 0;
    for (int v = 0; v < nv; v++) {
        const vm big = ((vabs(B->p1[v]) > 0x1p400) | (vabs(B->p2[v]) > 0x1p400)) & (B->sc[v] < 0.0);
        const vd f = sel(big, bc(0x1p-800), bc(1.0));
        B->p1[v] *= f;
        B->p2[v] *= f;
        B->sc[v] += sel(big, bc(1.0), bc(0.0));
        live[v] = B->sc[v] == 0.0;
        all += all_set(live[v]);
    }
    return all;
}

AI int blk_any_live(const vm *live, const int nv)
{
    vm m = {0};
    for (int v = 0; v < nv; v++) m |= live[v];
    return any_set(m);
}

/* Steps while no lane lives: nothing to accumulate.  Returns the first step
 * after the check that found a live lane, or nl, and then (nothing to add:
 * no step is left) flags the block's groups dead.  The checks fall on the
 * same steps whatever the block's width, and each lane's state is its own, so
 * the flag is a fact about each lane, which a block of another width (another
 * instruction set) may use. */
AI int run_dead(blk_t *B, const sht_kjob *j, int b, const double *al, int i, int nl, const int nv)
{
    vm live[NVMAX];
    while (i < nl) {
        const int e = i + RESCALE_EVERY < nl ? i + RESCALE_EVERY : nl;
        for (; i < e; i++) step_plain(B, al[i], nv);
        blk_rescale(B, live, nv);
        if (blk_any_live(live, nv)) break;
    }
    if (i >= nl) blk_set_dead(j, b, nv);
    return i;
}

/* The values of the live lanes, 0 on the others. */
AI void live_values(const blk_t *B, const vm *live, vd *q, const int nv)
{
    for (int v = 0; v < nv; v++) q[v] = (vd)((vm)B->p1[v] & live[v]);
}

/* ------------------------------------------------------------ analysis */

/* acc[2c + k] += Σ_v q[v] · in[doff[v] + (4c + 2·odd + k)·SHT_GRP] */
AI void acc_analysis(vd *acc, const vd *q, const double *in, const size_t *doff, int nc, int odd,
                     const int nv)
{
    for (int c = 0; c < nc; c++) {
        const double *dr = in + (size_t)(4 * c + 2 * odd) * SHT_GRP, *di = dr + SHT_GRP;
        vd sr = acc[2 * c], si = acc[2 * c + 1];
        for (int v = 0; v < nv; v++) {
            sr += q[v] * vload(dr + doff[v]);
            si += q[v] * vload(di + doff[v]);
        }
        acc[2 * c] = sr;
        acc[2 * c + 1] = si;
    }
}

/* The plain loop (every lane lives) from i (odd_first: parity of i) to nl − 1. */
AI void plain_analysis(blk_t *B, const double *al, int i, int nl, vd *acc, const double *in, int nc,
                       int odd_first, const int nv)
{
    const int s = 2 * nc;
    for (; i + 1 < nl; i += 2) {
        const double a0 = al[i], a1 = al[i + 1];
        for (int v = 0; v < nv; v++) B->p2[v] = a0 * B->x[v] * B->p1[v] - B->p2[v];
        acc_analysis(acc + (size_t)i * s, B->p2, in, B->doff, nc, odd_first, nv);
        for (int v = 0; v < nv; v++) B->p1[v] = a1 * B->x[v] * B->p2[v] - B->p1[v];
        acc_analysis(acc + (size_t)(i + 1) * s, B->p1, in, B->doff, nc, !odd_first, nv);
    }
    if (i < nl) {
        for (int v = 0; v < nv; v++) B->p2[v] = al[i] * B->x[v] * B->p1[v] - B->p2[v];
        acc_analysis(acc + (size_t)i * s, B->p2, in, B->doff, nc, odd_first, nv);
    }
}

AI void analysis_body(const sht_kjob *j, const int nc)
{
    const int nl = j->lmax - j->m + 1, np = j->npad, s = 2 * nc;
    const double *al = j->alpha, *in = j->in;
    vd *acc = (vd *)j->acc;
    int z = nl; /* acc of bands i ≥ z hold sums; below z nothing was added yet */
    for (int b = 0; b < np; b += VL * NVA) {
        blk_t B;
        const int kind = blk_load(&B, j, b, NVA);
        if (!kind) continue;
        vd q[NVMAX];
        int i = kind == 1 ? run_dead(&B, j, b, al, 1, nl, NVA) : 0; /* the first band this block adds to */
        if (i < z) { /* zero only the bands some block reaches (near a pole, high m start late) */
            memset(acc + (size_t)i * s, 0, sizeof(vd) * (size_t)(z - i) * s);
            z = i;
        }
        if (i == 0) {
            i = 1;
            for (int v = 0; v < NVA; v++) q[v] = sel(B.sc[v] == 0.0, B.p1[v], bc(0.0));
            acc_analysis(acc, q, in, B.doff, nc, 0, NVA); /* i = 0: l = m */
        }
        if (kind != 3) { /* some lanes still scaled: live lanes accumulated, a check every few steps */
            vm live[NVMAX];
            while (i < nl && blk_rescale(&B, live, NVA) < NVA) {
                const int e = i + RESCALE_EVERY < nl ? i + RESCALE_EVERY : nl;
                for (; i < e; i++) {
                    step_plain(&B, al[i], NVA);
                    live_values(&B, live, q, NVA);
                    acc_analysis(acc + (size_t)i * s, q, in, B.doff, nc, i & 1, NVA);
                }
            }
        }
        if (i & 1) plain_analysis(&B, al, i, nl, acc, in, nc, 1, NVA);
        else plain_analysis(&B, al, i, nl, acc, in, nc, 0, NVA);
    }
    /* out_i = g_i · Σ_lanes acc_i  (Q_l^m = g_i T_i), VL sums at a time; 0 below z */
    const int n = nl * s;
    memset(j->out, 0, sizeof(double) * (size_t)z * s);
    int t = z * s, i = z, k = 0; /* t = i·s + k */
    for (; t + VL <= n; t += VL) {
        const vd r = hsum_vl(acc + t);
        for (int q = 0; q < VL; q++) {
            j->out[t + q] = j->g[i] * r[q];
            if (++k == s) k = 0, i++;
        }
    }
    for (; t < n; t++) {
        j->out[t] = j->g[i] * hsum(acc[t]);
        if (++k == s) k = 0, i++;
    }
}

/* (A constant channel count, as in synthesis, was measured slower here.) */
void KN(sh__sht_analysis)(const sht_kjob *j) { analysis_body(j, j->nchan); }

/* ----------------------------------------------------------- synthesis */

/* e[2c + k] += q · cin[2c + k]  (e: E or O of every channel) */
AI void acc_synthesis(vd (*e)[NVMAX], const vd *q, const double *cin, int nc, const int nv)
{
    for (int ck = 0; ck < 2 * nc; ck++) {
        const double cv = cin[ck];
        for (int v = 0; v < nv; v++) e[ck][v] += q[v] * cv;
    }
}

AI void plain_synthesis(blk_t *B, const double *al, int i, int nl, vd (*E)[NVMAX], vd (*O)[NVMAX],
                        const double *cin, int nc, int odd_first, const int nv)
{
    const int s = 2 * nc;
    vd (*e0)[NVMAX] = odd_first ? O : E, (*e1)[NVMAX] = odd_first ? E : O;
    for (; i + 1 < nl; i += 2) {
        const double a0 = al[i], a1 = al[i + 1];
        for (int v = 0; v < nv; v++) B->p2[v] = a0 * B->x[v] * B->p1[v] - B->p2[v];
        acc_synthesis(e0, B->p2, cin + (size_t)i * s, nc, nv);
        for (int v = 0; v < nv; v++) B->p1[v] = a1 * B->x[v] * B->p2[v] - B->p1[v];
        acc_synthesis(e1, B->p1, cin + (size_t)(i + 1) * s, nc, nv);
    }
    if (i < nl) {
        for (int v = 0; v < nv; v++) B->p2[v] = al[i] * B->x[v] * B->p1[v] - B->p2[v];
        acc_synthesis(e0, B->p2, cin + (size_t)i * s, nc, nv);
    }
}

/* cin[i·2nc + 2c + k]: the coefficients of this m already multiplied by g_i. */
AI void synthesis_body(const sht_kjob *j, const int nc)
{
    const int nl = j->lmax - j->m + 1, np = j->npad, s = 2 * nc;
    const double *al = j->alpha, *cin = j->in;
    for (int b = 0; b < np; b += VL * NVS) {
        blk_t B;
        vd E[2 * SH_IMAGE_MAX_CHANNELS][NVMAX], O[2 * SH_IMAGE_MAX_CHANNELS][NVMAX];
        for (int ck = 0; ck < s; ck++)
            for (int v = 0; v < NVS; v++) E[ck][v] = O[ck][v] = bc(0.0);
        const int kind = blk_load(&B, j, b, NVS);
        if (kind) {
            vd q[NVMAX];
            int i = 1;
            if (kind == 1) i = run_dead(&B, j, b, al, 1, nl, NVS);
            else {
                for (int v = 0; v < NVS; v++) q[v] = sel(B.sc[v] == 0.0, B.p1[v], bc(0.0));
                acc_synthesis(E, q, cin, nc, NVS); /* l = m */
            }
            if (kind != 3) {
                vm live[NVMAX];
                while (i < nl && blk_rescale(&B, live, NVS) < NVS) {
                    const int e = i + RESCALE_EVERY < nl ? i + RESCALE_EVERY : nl;
                    for (; i < e; i++) {
                        step_plain(&B, al[i], NVS);
                        live_values(&B, live, q, NVS);
                        acc_synthesis((i & 1) ? O : E, q, cin + (size_t)i * s, nc, NVS);
                    }
                }
            }
            if (i & 1) plain_synthesis(&B, al, i, nl, E, O, cin, nc, 1, NVS);
            else plain_synthesis(&B, al, i, nl, E, O, cin, nc, 0, NVS);
        }
        /* north = E + O, south = E − O */
        for (int c = 0; c < nc; c++)
            for (int k = 0; k < 2; k++) {
                double *north = j->out + (size_t)(4 * c + k) * SHT_GRP;
                double *south = j->out + (size_t)(4 * c + 2 + k) * SHT_GRP;
                for (int v = 0; v < NVS; v++) {
                    vstore(north + B.doff[v], E[2 * c + k][v] + O[2 * c + k][v]);
                    vstore(south + B.doff[v], E[2 * c + k][v] - O[2 * c + k][v]);
                }
            }
    }
}

/* The channel count as a constant for the common cases (one map, RGB), so
 * that the channel loops unroll and the accumulators stay in registers. */
void KN(sh__sht_synthesis)(const sht_kjob *j)
{
    if (j->nchan == 1) synthesis_body(j, 1);
    else if (j->nchan == 3) synthesis_body(j, 3);
    else synthesis_body(j, j->nchan);
}

/* ---------------------------------------------------------- ring stages */

#if defined(SHT_KERN_AVX512)
/* r[j] (8 rows of 8) ← its transpose: three rounds of two-source shuffles. */
static inline void transpose8(__m512d r[8])
{
    __m512d u[8], v[8];
    for (int k = 0; k < 4; k++) { /* [r2k₀ r2k+1₀ r2k₂ r2k+1₂ …], [… ₁ … ₃ …] */
        u[2 * k] = _mm512_unpacklo_pd(r[2 * k], r[2 * k + 1]);
        u[2 * k + 1] = _mm512_unpackhi_pd(r[2 * k], r[2 * k + 1]);
    }
    const __m512i lo2 = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), hi2 = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    for (int h = 0; h < 2; h++) /* rows 4h..4h+3: v[4h + 0..3] hold columns {0,4}, {2,6}, {1,5}, {3,7} */
        for (int k = 0; k < 2; k++) {
            v[4 * h + 2 * k] = _mm512_permutex2var_pd(u[4 * h + k], lo2, u[4 * h + 2 + k]);
            v[4 * h + 2 * k + 1] = _mm512_permutex2var_pd(u[4 * h + k], hi2, u[4 * h + 2 + k]);
        }
    static const int col[4] = {0, 2, 1, 3}; /* v[q] holds columns col[q] and col[q] + 4 */
    for (int q = 0; q < 4; q++) {
        r[col[q]] = _mm512_shuffle_f64x2(v[q], v[4 + q], 0x44);
        r[col[q] + 4] = _mm512_shuffle_f64x2(v[q], v[4 + q], 0xee);
    }
}

/* (a, b) turned by the phase (c, s) = (cos mφ0, sin mφ0) as both ring stages
 * turn it: re = a·c + b·s, im = a·s − b·c. */
static inline void turn(__m512d a, __m512d b, __m512d c, __m512d s, __m512d *re, __m512d *im)
{
    *re = _mm512_fmadd_pd(a, c, _mm512_mul_pd(b, s));
    *im = _mm512_fmsub_pd(a, s, _mm512_mul_pd(b, c));
}

/* sht_internal.h: four m at a time, one 64-byte load per ring spectrum gives
 * (re, im) of the four; the weighted north ± south of the 8 lanes are turned
 * into rows (lanes across) by a transpose, then turned by e^{−imφ0} (turn). */
void sh__sht_scatter_avx512(const sht_sjob *j)
{
    const int nc = j->nchan;
    for (int c = 0; c < nc; c++) {
        const double *F[2 * SHT_GRP];
        __mmask8 live[2 * SHT_GRP];
        __m512d wv[2 * SHT_GRP];
        for (int s = 0; s < 2 * SHT_GRP; s++) {
            F[s] = j->X + ((size_t)s * nc + c) * j->M * 2;
            live[s] = j->w[s / 2][s % 2] != 0.0 ? 0xff : 0;
            wv[s] = _mm512_set1_pd(j->w[s / 2][s % 2]);
        }
        for (int m0 = 0; m0 < j->m1; m0 += 4) {
            __m512d S[SHT_GRP], D[SHT_GRP];
            for (int g = 0; g < SHT_GRP; g++) {
                const __m512d n = _mm512_mul_pd(wv[2 * g], _mm512_maskz_loadu_pd(live[2 * g], F[2 * g] + 2 * m0));
                const __m512d s = _mm512_maskz_loadu_pd(live[2 * g + 1], F[2 * g + 1] + 2 * m0);
                S[g] = _mm512_fmadd_pd(wv[2 * g + 1], s, n);
                D[g] = _mm512_fnmadd_pd(wv[2 * g + 1], s, n);
            }
            transpose8(S); /* S[2i], S[2i+1]: re, im of m0 + i, lanes across */
            transpose8(D);
            for (int i = 0; i < 4; i++) {
                const __m512d cp = _mm512_set1_pd(j->cph[m0 + i]), sp = _mm512_set1_pd(j->sph[m0 + i]);
                double *row = j->d + (size_t)(m0 + i) * j->mstride + (size_t)c * 4 * SHT_GRP;
                __m512d r[4];
                turn(S[2 * i], S[2 * i + 1], cp, sp, &r[0], &r[1]);
                turn(D[2 * i], D[2 * i + 1], cp, sp, &r[2], &r[3]);
                for (int k = 0; k < 4; k++) _mm512_storeu_pd(row + k * SHT_GRP, r[k]);
            }
        }
    }
}

/* The synthesis's way back (sht_internal.h): per m the four rows of the
 * group turned by e^{imφ0} — z = (a cos + b sin, a sin − b cos) for
 * (a, b) = (re, im) of the north and of the south row (turn) — then the 8 × 8 of
 * four m transposed, so that one 64-byte store writes (re, im) of the four m
 * of one ring's spectrum. */
void sh__sht_spectra_avx512(const sht_sjob *j)
{
    const int nc = j->nchan;
    for (int c = 0; c < nc; c++) {
        double *Z[2 * SHT_GRP];
        for (int s = 0; s < 2 * SHT_GRP; s++) Z[s] = j->X + ((size_t)s * nc + c) * j->M * 2;
        for (int m0 = 0; m0 < j->m1; m0 += 4) {
            __m512d Nr[SHT_GRP], Sr[SHT_GRP]; /* rows 2i, 2i+1: re, im of m0 + i, lanes across */
            for (int i = 0; i < 4; i++) {
                const __m512d cp = _mm512_set1_pd(j->cph[m0 + i]), sp = _mm512_set1_pd(j->sph[m0 + i]);
                const double *row = j->d + (size_t)(m0 + i) * j->mstride + (size_t)c * 4 * SHT_GRP;
                const __m512d an = _mm512_loadu_pd(row), bn = _mm512_loadu_pd(row + SHT_GRP);
                const __m512d as = _mm512_loadu_pd(row + 2 * SHT_GRP), bs = _mm512_loadu_pd(row + 3 * SHT_GRP);
                turn(an, bn, cp, sp, &Nr[2 * i], &Nr[2 * i + 1]);
                turn(as, bs, cp, sp, &Sr[2 * i], &Sr[2 * i + 1]);
            }
            transpose8(Nr); /* Nr[g]: (re, im) of m0..m0+3 of ring 2g */
            transpose8(Sr);
            for (int g = 0; g < SHT_GRP; g++) {
                _mm512_storeu_pd(Z[2 * g] + 2 * m0, Nr[g]);
                _mm512_storeu_pd(Z[2 * g + 1] + 2 * m0, Sr[g]);
            }
        }
    }
}
#endif
