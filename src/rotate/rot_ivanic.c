/* rot_ivanic.c — the `ivanic` method: the Ivanic-Ruedenberg recursion for
 * real SH rotation matrices, band l from band l−1 and band 1, starting from
 * the 3×3 matrix rot->R (precision-generic, see rot_real.h).
 *
 * References
 *  [1] J. Ivanic, K. Ruedenberg, "Rotation Matrices for Real Spherical
 *      Harmonics. Direct Determination by Recursion", J. Phys. Chem. 100
 *      (1996) 6342–6347, Tables 1 and 2 (eqs. 8.1–8.5).
 *  [2] J. Ivanic, K. Ruedenberg, "Additions and Corrections", J. Phys.
 *      Chem. A 102 (1998) 9099–9100 (the corrected Table 2).
 *  [3] R. Green, "Spherical Harmonic Lighting: The Gritty Details" (2003),
 *      Appendix I — a transcription of [1]+[2] with two misprints (below).
 *  [4] docs/CONVENTIONS.md: g(s) = f(R⁻¹s); `nocs` = Ivanic's real basis.
 *
 * Basis.  [1] uses real SH without the Condon-Shortley phase (our `nocs`):
 * band 1 is ∝ (y, z, x) for m = −1, 0, 1.  A linear function c·s rotated as
 * g(s) = c·(R⁻¹s) = (Rc)·s, so the band-1 block is R itself with rows and
 * columns permuted to (y, z, x):  M¹_{mn} = R_{π(m) π(n)}, π(−1, 0, 1) =
 * (y, z, x) ([3]'s R_{mn} table).  The recursion then yields the nocs
 * blocks; the CS blocks are S·M·S, S = diag((−1)^m), i.e. entries whose m and
 * n differ in parity are negated at the end (a sign flip, no multiplication).
 *
 * The recursion ([1] eq. 8.1, Table 1 for u, v, w; [2] Table 2 for U, V, W):
 *   M^l_{mn} = u^l_{mn} U^l_{mn} + v^l_{mn} V^l_{mn} + w^l_{mn} W^l_{mn}
 * with d = (l+n)(l−n) for |n| < l and d = (2l)(2l−1) for |n| = l,
 *   u = √((l+m)(l−m)/d)
 *   v = ½ √((1+δ_{m0})(l+|m|−1)(l+|m|)/d) (1−2δ_{m0})
 *   w = −½ √((l−|m|−1)(l−|m|)/d) (1−δ_{m0})
 * and the P function
 *   _iP^l_{ab} = R_{i0} M^{l−1}_{ab}                                  |b| < l
 *             = R_{i1} M^{l−1}_{a,l−1} − R_{i,−1} M^{l−1}_{a,−l+1}     b = l
 *             = R_{i1} M^{l−1}_{a,−l+1} + R_{i,−1} M^{l−1}_{a,l−1}     b = −l
 *   U = _0P_{mn}
 *   V = _1P_{1n} + _{−1}P_{−1,n}                                       m = 0
 *     = _1P_{m−1,n} √(1+δ_{m1}) − _{−1}P_{−m+1,n} (1−δ_{m1})           m > 0
 *     = _1P_{m+1,n} (1−δ_{m,−1}) + _{−1}P_{−m−1,n} √(1+δ_{m,−1})       m < 0
 *   W = _1P_{m+1,n} + _{−1}P_{−m−1,n}                                  m > 0
 *     = _1P_{m−1,n} − _{−1}P_{−m+1,n}                                  m < 0
 *
 * MISPRINTS in [3] (Green's Appendix I), proved by tests/rotate/test_rot_ivanic.c
 * (each variant breaks orthogonality of band 2 or 3 by O(1) while the table
 * above agrees with the MPFR reference to 1e-15):
 *   (a) V for m < 0 is printed  _1P_{m+1,n}(1+δ_{m,−1}) + _{−1}P_{−m−1,n}√(1−δ_{m,−1});
 *       the factors must be (1−δ_{m,−1}) and √(1+δ_{m,−1}) (as in [2]):
 *       for m = −1 the term is √2 · _{−1}P_{0n}, not 2 · _1P_{0n}.
 *   (b) w for |n| = l is printed with (l+|m|−1)(l+|m|); it must be
 *       (l−|m|−1)(l−|m|), the same numerator as for |n| < l.
 * (V for m = 0 and m > 0, W, u, v and P are printed correctly there, as
 * read in our copy papers/green-2003-sh-lighting-gritty-details.md.)
 *
 * High bands (measured, β = 1.1): the recursion amplifies rounding
 * exponentially, about ×8 per 10 bands — error vs the MPFR reference
 * 5.6e-16 (l = 10), 2e-15 (20), 7.6e-13 (50), 4e-8 (100), 91 (200).  Float
 * and double errors are the same multiple of their ε at every band, so
 * this is the recursion's own error growth, not a wrong coefficient.
 *
 * Implementation.  The δ factors are folded into the tables: for |m| = 1 the
 * term with (1−δ) vanishes and √2 is multiplied into v.  Coefficients that
 * are zero (u for |m| = l; w for m = 0 or |m| ≥ l−1) skip their term, which
 * also keeps every M^{l−1} index inside band l−1.  The tables are planar
 * (a u, a v and a w matrix per band), so every row is a few branch-free
 * passes over n.
 *
 * Shared products.  _{±1}P^l_{an} depends on (a, n) only, and V of row a±1
 * and W of row a∓1 both use it: the two (2l−1) × (2l+1) matrices _1P and
 * _{−1}P are computed once per band (1 multiplication per entry, 2 in the
 * columns |n| = l) and read by the rows; _0P_{mn} is used by U of row m
 * alone and is formed in that row's pass.  Every product is the one the
 * formula above evaluates, so the result is the same bit for bit as
 * evaluating P afresh per (m, n); only repeats are not re-executed.
 * Multiplications counted (executed): 2(2l−1)(2l+3) for the two P matrices,
 * per row with |m| < l the (2l−1) + 4 of _0P, and 1 per entry for each of
 * u·U, v·V, w·W present.
 *
 * Computed in the CS convention directly.  With S = diag((−1)^m), the CS
 * blocks are M_cs = S M S: M_cs[m][n] = (−1)^{m+n} M[m][n], and band 1's is
 * R_{π(i)π(j)} (−1)^{i+j}.  Every term of M^l_{mn} is a coefficient times
 * R¹_{ij} M^{l−1}_{an'} with j = 0, n' = n (|n| < l) or j = ±1, n' = ±(l−1)
 * (|n| = l), and a = m (U, i = 0) or a = m ± 1 (V, W, i = ±1); the sign
 * (−1)^{m+n}·(−1)^{i+j}·(−1)^{a+n'} is then (−1)^{m+a+i} = +1 in every
 * case.  So the recursion run on the CS band 1 and the CS band l−1 yields
 * the CS band l exactly (sign changes only, bit for bit S M S); no
 * conversion pass is needed.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

SH__ROT_DECLARE_BLOCKS(ivanic);
SH__ROT_DECLARE_TABLES(ivanic);
SH__ROT_DECLARE_BAND(ivanic);
SH__ROT_DECLARE_STREAM(ivanic);

#include <math.h>
#include <stdlib.h>

/* Per-order coefficient tables: band l (l ≥ 2) holds at
 * 3·sh_rot_block_offset(l) three (2l+1)² matrices u, v', w (row m, column
 * n), where v' has the √(1+δ_{|m|1}) of V folded in.  Computed in double,
 * stored in sh_real. */
typedef struct {
    int order;
    sh_real *uvw;
} ivanic_tables;

/* The u, v', w coefficients of band l (Table 1 of [1]) into t[3(2l+1)²]. */
static void SH_R(ivanic_coeffs)(int l, sh_real *t)
{
    const int w = 2 * l + 1;
    const size_t ww = (size_t)w * w;
    for (int m = -l; m <= l; m++) {
        const int am = m < 0 ? -m : m;
        for (int n = -l; n <= l; n++) {
            const double d = (n == l || n == -l) ? (2.0 * l) * (2.0 * l - 1) : (double)(l + n) * (l - n);
            const double u = sqrt((double)(l + m) * (l - m) / d);
            double v = 0.5 * sqrt((m == 0 ? 2.0 : 1.0) * (l + am - 1) * (double)(l + am) / d) *
                       (m == 0 ? -1.0 : 1.0);
            const double wc = m == 0 ? 0.0 : -0.5 * sqrt((double)(l - am - 1) * (l - am) / d);
            if (am == 1) v *= sqrt(2.0); /* √(1+δ_{|m|,1}) of V, folded */
            const size_t i = (size_t)(m + l) * w + (size_t)(n + l);
            t[i] = (sh_real)u;
            t[ww + i] = (sh_real)v;
            t[2 * ww + i] = (sh_real)wc;
        }
    }
}

int SH_R(sh__rot_ivanic_tables_new)(int order, void **tables)
{
    *tables = NULL;
    ivanic_tables *T = malloc(sizeof *T);
    if (!T) return sh_error(SH_ENOMEM, "ivanic: out of memory (tables)");
    T->order = order;
    T->uvw = malloc((3 * sh_rot_block_offset(order) + 1) * sizeof *T->uvw);
    if (!T->uvw) {
        free(T);
        return sh_error(SH_ENOMEM, "ivanic: out of memory (tables, order %d)", order);
    }
    for (int l = 2; l < order; l++) {
        SH_R(ivanic_coeffs)(l, T->uvw + 3 * sh_rot_block_offset(l));
        sh__rot_band_done(l + 1, order);
    }
    *tables = T;
    return SH_OK;
}

/* Band 1 in Ivanic's basis order (y, z, x), CS signs:
 * M1[(i+1)*3 + (j+1)] = (−1)^{i+j} R_{π(i)π(j)}. */
static void SH_R(ivanic_band1)(const sh_rotation *rot, sh_real *M1)
{
    static const int perm[3] = {1, 2, 0}; /* m = −1, 0, 1 → y, z, x */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const sh_real r = (sh_real)rot->R[perm[i] * 3 + perm[j]];
            M1[i * 3 + j] = ((i + j) & 1) ? -r : r; /* i+j ≡ (i−1)+(j−1) */
        }
}

/* One row of band l in one pass, each entry written once:
 *   row_k = (u_k·U_k + v_k·V_k) + w_k·W_k   (u·U left out when !hu, w·W when wk = 0)
 * with U_k = r00·pa_{k−1} inside and ue0, uew at the two edge columns,
 * V = A, A + B or A − B (vk = 0, 1, 2), W = C + D or C − D (wk = 1, 2).  The
 * sums are those of the formula in the header, in the same order.  Called
 * with constant flags, so each combination is its own branch-free loop
 * (GCC inlines it).  Earlier the row was written by a u·U pass and then
 * read back and updated by a v·V and a w·W pass: once -O3 vectorises those
 * passes, a vector load of the row just stored element by element waits
 * for store-to-load forwarding (the −O3 slowdown of docs/rotation.md "Rotation
 * speed"); written once, the row has no such dependence. */
static inline __attribute__((always_inline)) void SH_R(iv_row)(
    int w, sh_real *restrict row, int hu, sh_real r00, sh_real ue0, sh_real uew,
    const sh_real *restrict pa, const sh_real *restrict u, int vk, const sh_real *restrict v,
    const sh_real *restrict A, const sh_real *restrict B, int wk, const sh_real *restrict wc,
    const sh_real *restrict C, const sh_real *restrict D)
{
#define IV_V(k) (vk == 0 ? A[k] : vk == 1 ? A[k] + B[k] : A[k] - B[k])
#define IV_W(k) (wk == 1 ? C[k] + D[k] : C[k] - D[k])
#define IV_ENTRY(k, U)                                                                             \
    do {                                                                                           \
        sh_real x_ = hu ? u[k] * (U) + v[k] * IV_V(k) : v[k] * IV_V(k);                            \
        if (wk) x_ += wc[k] * IV_W(k);                                                             \
        row[k] = x_;                                                                               \
    } while (0)
    IV_ENTRY(0, ue0);
SH_SIMD_SHORT
    for (int k = 1; k < w - 1; k++) IV_ENTRY(k, r00 * pa[k - 1]);
    IV_ENTRY(w - 1, uew);
#undef IV_ENTRY
#undef IV_V
#undef IV_W
}

/* iv_row with the flags as constants: one instance per combination used */
static inline __attribute__((always_inline)) void SH_R(iv_row_any)(
    int w, sh_real *row, int hu, sh_real r00, sh_real ue0, sh_real uew, const sh_real *pa,
    const sh_real *u, int vk, const sh_real *v, const sh_real *A, const sh_real *B, int wk,
    const sh_real *wc, const sh_real *C, const sh_real *D)
{
#define IV_CASE(HU, VK, WK)                                                                        \
    if (hu == HU && vk == VK && wk == WK) {                                                        \
        SH_R(iv_row)(w, row, HU, r00, ue0, uew, pa, u, VK, v, A, B, WK, wc, C, D);                 \
        return;                                                                                    \
    }
    IV_CASE(1, 1, 0) IV_CASE(1, 0, 0) IV_CASE(1, 0, 1) IV_CASE(1, 0, 2) IV_CASE(1, 1, 2)
    IV_CASE(1, 2, 1) IV_CASE(1, 2, 0) IV_CASE(0, 1, 0) IV_CASE(0, 2, 0) IV_CASE(0, 1, 2)
    IV_CASE(0, 2, 1) IV_CASE(0, 0, 0) IV_CASE(0, 0, 1) IV_CASE(0, 0, 2)
#undef IV_CASE
}

/* One step of the recursion: cur = M^l (CS) from prev = M^{l−1}, band 1 M1
 * (CS, see the header), the band's coefficient planes t; P has room for
 * 2(2l−1)(2l+1) values.  Returns the multiplications. */
static uint64_t SH_R(ivanic_step)(int l, const sh_real *M1, const sh_real *prev, const sh_real *t,
                                  sh_real *cur, sh_real *P)
{
    const int w = 2 * l + 1, pw = 2 * l - 1, lp = l - 1;
    const size_t ww = (size_t)w * w;
    const sh_real *tu = t, *tv = t + ww, *tw = t + 2 * ww;
    uint64_t count = 0;
#define R1(i, j) M1[((i) + 1) * 3 + ((j) + 1)]
    /* _iP_{an} for i = ±1 ([1] Table 2), row a + lp, column n + l:
     *   |n| < l: R_{i0} M^{l−1}_{an}
     *   n = l:   R_{i1} M^{l−1}_{a,l−1} − R_{i,−1} M^{l−1}_{a,−l+1}
     *   n = −l:  R_{i1} M^{l−1}_{a,−l+1} + R_{i,−1} M^{l−1}_{a,l−1} */
    sh_real *Pp = P, *Pm = P + (size_t)pw * w;
    for (int s = 0; s < 2; s++) {
        const int i = s ? -1 : 1;
        const sh_real r0 = R1(i, 0), r1 = R1(i, 1), rm = R1(i, -1);
        sh_real *Pi = s ? Pm : Pp;
        for (int a = 0; a < pw; a++) {
            const sh_real *pa = prev + (size_t)a * pw;
            sh_real *row = Pi + (size_t)a * w;
            row[0] = r1 * pa[0] + rm * pa[pw - 1];
SH_SIMD_SHORT
            for (int k = 0; k < pw; k++) row[k + 1] = r0 * pa[k];
            row[w - 1] = r1 * pa[pw - 1] - rm * pa[0];
        }
    }
    count += 2u * (uint64_t)pw * (uint64_t)(pw + 4);
#define PP(a) (Pp + (size_t)((a) + lp) * w) /* _1P row a */
#define PN(a) (Pm + (size_t)((a) + lp) * w) /* _{−1}P row a */
    const sh_real r00 = R1(0, 0), r01 = R1(0, 1), r0m = R1(0, -1);
    for (int m = -l; m <= l; m++) {
        const int am = m < 0 ? -m : m;
        const size_t o = (size_t)(m + l) * w;
        /* u·U (|m| < l), U = _0P_{mn}: edges by the b = ±l formulas */
        const int hu = am < l;
        const sh_real *pa = hu ? prev + (size_t)(m + lp) * pw : NULL;
        const sh_real ue0 = hu ? r01 * pa[0] + r0m * pa[pw - 1] : 0;
        const sh_real uew = hu ? r01 * pa[pw - 1] - r0m * pa[0] : 0;
        /* v·V ([2] Table 2; √(1+δ) folded into v, the (1−δ) term skipped) */
        int vk;
        const sh_real *A, *B;
        if (m == 0) vk = 1, A = PP(1), B = PN(-1);
        else if (m == 1 || m == -1) vk = 0, A = m == 1 ? PP(0) : PN(0), B = NULL;
        else if (m > 1) vk = 2, A = PP(m - 1), B = PN(-m + 1);
        else vk = 1, A = PP(m + 1), B = PN(-m - 1);
        /* w·W (m ≠ 0, |m| < l−1) */
        int wk = 0;
        const sh_real *C = NULL, *D = NULL;
        if (m != 0 && am < l - 1) {
            if (m > 0) wk = 1, C = PP(m + 1), D = PN(-m - 1);
            else wk = 2, C = PP(m - 1), D = PN(-m + 1);
        }
        SH_R(iv_row_any)(w, cur + o, hu, r00, ue0, uew, pa, tu + o, vk, tv + o, A, B, wk, tw + o, C, D);
        count += (hu ? (uint64_t)pw + 4 + (uint64_t)w : 0) + (uint64_t)w + (wk ? (uint64_t)w : 0);
    }
#undef PP
#undef PN
#undef R1
    return count;
}

int SH_R(sh__rot_ivanic_blocks)(int order, const sh_rotation *rot, const void *tables,
                                sh_real *blocks, void *work, uint64_t *mults)
{
    const ivanic_tables *T = tables;
    if (!T || T->order < order) return sh_error(SH_EINVAL, "ivanic: tables missing or too small");
    uint64_t count = 0;
    blocks[0] = 1;
    if (order > 1) SH_R(ivanic_band1)(rot, blocks + sh_rot_block_offset(1));
    for (int l = 2; l < order; l++) {
        count += SH_R(ivanic_step)(l, blocks + sh_rot_block_offset(1),
                                   blocks + sh_rot_block_offset(l - 1),
                                   T->uvw + 3 * sh_rot_block_offset(l), blocks + sh_rot_block_offset(l),
                                   work);
        sh__rot_band_done(l + 1, order);
    }
    if (mults) *mults += count;
    return SH_OK;
}

/* One band without storing the lower ones: band 1, two band buffers, the
 * band's coefficients and the P matrices in work (ivanic_band_work). */
int SH_R(sh__rot_ivanic_band)(int band, const sh_rotation *rot, sh_real *block, void *work)
{
    const size_t wmax = (size_t)(2 * band + 1) * (2 * band + 1);
    sh_real *M1 = work, *a = M1 + 9, *b = a + wmax, *t = b + wmax, *P = t + 3 * wmax;
    SH_R(ivanic_band1)(rot, M1);
    if (band == 0) {
        block[0] = 1;
        return SH_OK;
    }
    sh_real *prev = a, *cur = b;
    for (int i = 0; i < 9; i++) prev[i] = M1[i];
    for (int l = 2; l <= band; l++) {
        SH_R(ivanic_coeffs)(l, t);
        SH_R(ivanic_step)(l, M1, prev, t, cur, P);
        sh_real *x = prev;
        prev = cur;
        cur = x;
    }
    for (size_t i = 0; i < (size_t)(2 * band + 1) * (2 * band + 1); i++) block[i] = prev[i];
    return SH_OK;
}

/* Streaming: band l from the state's band l−1 (state: band 1, the previous
 * band, a buffer for the current one, the coefficients, the P matrices; the
 * same layout as ivanic_band_work(lmax)). */
int SH_R(sh__rot_ivanic_stream)(int l, const sh_rotation *rot, void *state, sh_real *block)
{
    /* the buffers are sized for the largest band: offsets from lmax are not
     * known here, so the state starts with lmax's wmax */
    size_t *hdr = state;
    const size_t wmax = hdr[0];
    sh_real *M1 = (sh_real *)(hdr + 1), *prev = M1 + 9, *cur = prev + wmax, *t = cur + wmax;
    sh_real *P = t + 3 * wmax;
    if (l == 0) {
        block[0] = 1;
        return SH_OK;
    }
    if (l == 1) {
        SH_R(ivanic_band1)(rot, M1);
        for (int i = 0; i < 9; i++) prev[i] = M1[i];
    } else {
        SH_R(ivanic_coeffs)(l, t);
        SH_R(ivanic_step)(l, M1, prev, t, cur, P);
        for (size_t i = 0; i < (size_t)(2 * l + 1) * (2 * l + 1); i++) prev[i] = cur[i];
    }
    for (size_t i = 0; i < (size_t)(2 * l + 1) * (2 * l + 1); i++) block[i] = prev[i];
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
/* The coefficient tables of band l in double (for tools/gen_rot_unrolled.c). */
void sh__rot_ivanic_coeffs(int l, double *t);
void sh__rot_ivanic_coeffs(int l, double *t) { ivanic_coeffs_d(l, t); }

static void ivanic_tables_free(void *tables)
{
    ivanic_tables *T = tables;
    if (T) free(T->uvw);
    free(T);
}
static size_t ivanic_band_work(int band)
{
    const size_t wmax = (size_t)(2 * band + 1) * (2 * band + 1);
    return (9 + 7 * wmax) * sizeof(double);
}
static size_t ivanic_work(int order) /* the P matrices of the largest band */
{
    return 2 * (size_t)(2 * order + 1) * (2 * order + 1) * sizeof(double);
}
static size_t ivanic_stream_bytes(int lmax)
{
    return sizeof(size_t) + ivanic_band_work(lmax);
}
static int ivanic_stream_init(int lmax, void *state)
{
    *(size_t *)state = (size_t)(2 * lmax + 1) * (2 * lmax + 1);
    return SH_OK;
}
static size_t ivanic_tables_bytes(int order) { return 3 * sh_rot_block_offset(order) * sizeof(double); }
const sh__rot_ops sh__rot_ivanic_ops = {
    .name = "ivanic",
    .tables_bytes = ivanic_tables_bytes,
    .max_order = SH_ROT_IVANIC_MAX_ORDER,
    .tables_new_d = sh__rot_ivanic_tables_new_d,
    .tables_new_f = sh__rot_ivanic_tables_new_f,
    .tables_free = ivanic_tables_free,
    .work_bytes = ivanic_work,
    .blocks_d = sh__rot_ivanic_blocks_d,
    .blocks_f = sh__rot_ivanic_blocks_f,
    .band_d = sh__rot_ivanic_band_d,
    .band_work_bytes = ivanic_band_work,
    .stream_bytes = ivanic_stream_bytes,
    .stream_init = ivanic_stream_init,
    .stream_d = sh__rot_ivanic_stream_d,
    .stream_f = sh__rot_ivanic_stream_f,
    .matrix_only = 1,
};
#endif
