/* rot_zxzxz.c — the `zxzxz` method: R_sh = Z(α) · X₋₉₀ · Z(β) · X₊₉₀ · Z(γ),
 * applied sparsely (precision-generic, see rot_real.h).
 *
 * References
 *  [1] J. Kautz, P.-P. Sloan, J. Snyder, "Fast, Arbitrary BRDF Shading for
 *      Low-Frequency Lighting Using Spherical Harmonics", EGWR 2002, Sec. 3
 *      and appendix (the ZXZXZ decomposition).
 *  [2] J. Krivánek et al. 2005, Sec. 3.1 (cost n(2n²+18n−14)/3 quoted for [1]).
 *  [3] Wigner d: d^l_{m'm}(β) as in rot_wigner.c (Edmonds 4.1.23).
 *  [4] Trapani & Navaza 2006 (d(π/2) by recursion); the recursion used here is
 *      the three-term one in m' below, run in the stable direction.
 *
 * Decomposition (our conventions, docs/CONVENTIONS.md).  Ry(β) = Rx(−90°) Rz(β)
 * Rx(+90°) (the conjugated z axis Rx(−90°)ẑ is ŷ), and R_sh is a
 * homomorphism, so R_Y(β) = X₋₉₀ Z(β) X₊₉₀ with X_θ = R_sh(Rx(θ)), and
 *   R_sh(Rz(α)Ry(β)Rz(γ)) = Z(α) X₋₉₀ Z(β) X₊₉₀ Z(γ).
 * X₊₉₀ is generated, per band, from Rx(θ) = Rz(−90°) Ry(θ) Rz(+90°) (Rz(−90°)ŷ
 * = x̂): X₊₉₀ = Z(−90°) R_Y(π/2) Z(+90°), i.e. sh__rot_block_from_d with
 * d^l(π/2) and the exact multiple angles cos, sin(±m·90°) ∈ {0, ±1}.
 * X₋₉₀ = X₊₉₀⁻¹ = X₊₉₀ᵀ, but it is not applied as a transpose: since
 * Rz(π) Rx(θ) Rz(π) = Rx(−θ) (Rz(π) = diag(−1, −1, 1) negates the x-y
 * mixing entries), X₋₉₀ = Z(π) X₊₉₀ Z(π), and Z(π) = diag((−1)^m) commutes
 * with every Z(θ), so
 *   R_sh = Z(α) Z(π) X₊₉₀ Z(π) Z(β) X₊₉₀ Z(γ) = Z(α+π) X₊₉₀ Z(β+π) X₊₉₀ Z(γ),
 * with cos, sin(m(θ+π)) = (−1)^m cos, sin(mθ) — sign flips of the multiple
 * angles, made once per rotation.  Both X products then read the one table
 * row by row (a gather), and no second table is stored.
 *
 * d^l(π/2) (in long double, then rounded):
 *   d_{l,m} = (−1)^{l−m} √(C(2l, l+m)) / 2^l          ([3] with m' = l, one term)
 *     computed as e_0 = √(Π_{k=1..l} (2k−1)/(2k)), e_{±m} = e_{m−1} √((l−m+1)/(l+m));
 *   √((l−m')(l+m'+1)) d_{m'+1,m} + √((l+m')(l−m'+1)) d_{m'−1,m} = 2m d_{m'm}
 *     (the J± recurrence at β = π/2, where cosβ = 0; checked numerically
 *     against the direct sum), run downward from m' = l to m' = |m|: this
 *     goes from the classically forbidden region (m² + m'² > l², where d grows
 *     as m' decreases) into the allowed one — the stable direction.
 *   The rest from d_{m'm} = (−1)^{m'−m} d_{mm'} = d_{−m,−m'}.
 *
 * Structural zeros of X₊₉₀ (proved in tests/rotate/test_rot_zxzxz.c against the
 * MPFR reference of Rx(90°), and re-checked exactly by tables_new).  Call m
 * "cos type" if its real function after Z(90°) is a cosine: m ≥ 0 even or
 * m < 0 odd; otherwise "sin type".  R_Y(β) never mixes cos with sin (the
 * cross terms of sh__rot_block_from_d), and at β = π/2,
 * d_{m',−m} = (−1)^{l+m'} d_{m'm} makes the cos-cos entries vanish for
 * l+|m|+|m'| odd and the sin-sin entries for l+|m|+|m'| even.  Hence row m'
 * of X₊₉₀ has non-zeros only in the columns m = s·(q + 2k), k = 0, 1, …:
 *   cos type, l+|m'| even: q = 0, s = +   (m = 0, 2, 4, …)
 *   cos type, l+|m'| odd:  q = 1, s = −   (m = −1, −3, …)
 *   sin type, l+|m'| even: q = 1, s = +   (m = 1, 3, …)
 *   sin type, l+|m'| odd:  q = 2, s = −   (m = −2, −4, …)
 * which is l² + l + 1 of the (2l+1)² entries (about a quarter).  The
 * pattern is a permutation of four dense blocks: name the classes of m
 *   A: m = 0, 2, 4, …   B: m = −1, −3, …   C: m = 1, 3, …   D: m = −2, −4, …
 * (sizes ⌊l/2⌋+1, ⌊(l+1)/2⌋, ⌊(l+1)/2⌋, ⌊l/2⌋); every row of one class
 * reads the columns of one class: for l even A←A, B←B, C←D, D←C, for l odd
 * A←B, B←A, C←C, D←D (from the table above: the parity of l+|m'| is the
 * same for a whole class).  The band's vector is therefore kept split by
 * class (A|B|C|D, each in ascending |m|) between the z rotations, and X₊₉₀
 * is stored as the four dense blocks, row-major, rows and columns in
 * ascending |m| — the same left-to-right sums as the row-by-row gather.
 * The z rotations pair m with −m: A_k with D_{k−1} (m = 2k), C_k with B_k
 * (m = 2k+1); Z(γ) is fused into the split of the input, Z(α+π) into its
 * merge into the output.
 *
 * Cost of one apply (counted in the loops): per band l, three z rotations
 * (4l each) and two X products (l² + l + 1 each) = the n(2n²+18n−14)/3 of
 * [2] summed over l < n.  The multiple angles of α, β, γ by the Chebyshev
 * recurrence, 3·2(n−2) for n ≥ 3, which the paper's count omits, are done
 * once per rotation by the plan's set (counted there, in the set's
 * multiplications), not once per vector.
 * blocks (for rotmat) runs the band pipeline on each unit vector: O(l³) per
 * band, counted the same way.
 *
 * Memory.  A plan's tables hold Σ_{l<n} (l²+l+1) = n(n²+2)/3 values (X₋₉₀
 * uses them too), ≈ 360 MB in double at order 512.  The single-band path
 * (sh_rot_band) builds X₊₉₀ of that band only, O(l²) memory, so band 1000
 * takes ~3 s; a large plan simply fails with SH_ENOMEM if the tables do not
 * fit.  max_order is the largest band the report checks (l = 1400,
 * SH_ROT_ZXZXZ_MAX_ORDER).
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

SH__ROT_DECLARE_BLOCKS(zxzxz);
SH__ROT_DECLARE_APPLY(zxzxz);
SH__ROT_DECLARE_TABLES(zxzxz);
SH__ROT_DECLARE_SET_PAR(zxzxz);
sh__rot_one_fn_f sh__rot_zxzxz_one_f(int, int, sh_rot_kernel, uint64_t *); /* zxzxz_one.c */

#include <stdlib.h>
#include <string.h>

#define ZX_MAX_ORDER SH_ROT_ZXZXZ_MAX_ORDER

/* Compact X₊₉₀ storage: band l's l²+l+1 non-zeros start at zx_off(l). */
static inline size_t zx_off(int l) { return (size_t)l * ((size_t)l * l + 2) / 3; }

/* The classes of m (header): K = 0..3 for A, B, C, D; the k-th member
 * (ascending |m|), the class sizes, and the column class read by row class K. */
static inline int zx_cls_m(int K, int k)
{
    return K == 0 ? 2 * k : K == 1 ? -(2 * k + 1) : K == 2 ? 2 * k + 1 : -(2 * k + 2);
}
static inline void zx_cls_n(int l, int n[4])
{
    n[0] = l / 2 + 1;
    n[1] = n[2] = (l + 1) / 2;
    n[3] = l / 2;
}
static inline int zx_col(int l, int K)
{
    static const int even[4] = {0, 1, 3, 2}, odd[4] = {1, 0, 2, 3};
    return (l & 1) ? odd[K] : even[K];
}

typedef struct {
    int order;
    sh_real *x; /* X₊₉₀ non-zeros, zx_off(order) values */
} zx_tables;

#ifndef SH_REAL_FLOAT
/* d^l(π/2) into d[(m'+l)(2l+1) + (m+l)] (long double work ld[(2l+1)² + 2l+1]). */
static void zx_dpi2(int l, long double *ld, double *d)
{
    const int w = 2 * l + 1;
    long double *D = ld, *e = ld + (size_t)w * w;
#define DD(mp, m) D[(size_t)((mp) + l) * w + (size_t)((m) + l)]
    /* e_m = √(C(2l, l+m)) / 2^l */
    long double e0sq = 1;
    for (int k = 1; k <= l; k++) e0sq *= (long double)(2 * k - 1) / (2 * k);
    e[l] = sqrtl(e0sq);
    for (int m = 1; m <= l; m++) e[l + m] = e[l - m] = e[l + m - 1] * sqrtl((long double)(l - m + 1) / (l + m));
    for (int m = -l; m <= l; m++) {
        const int am = m < 0 ? -m : m;
        DD(l, m) = ((l - m) & 1) ? -e[l + m] : e[l + m];
        /* d_{m'−1,m} = (2m d_{m'm} − √((l−m')(l+m'+1)) d_{m'+1,m}) / √((l+m')(l−m'+1)) */
        for (int mp = l; mp > am; mp--) {
            long double v = 2.0L * m * DD(mp, m);
            if (mp < l) v -= sqrtl((long double)(l - mp) * (l + mp + 1)) * DD(mp + 1, m);
            DD(mp - 1, m) = v / sqrtl((long double)(l + mp) * (l - mp + 1));
        }
    }
    for (int mp = -l; mp <= l; mp++)
        for (int m = -l; m <= l; m++) {
            const int amp = mp < 0 ? -mp : mp, am = m < 0 ? -m : m;
            if (mp >= am) continue; /* computed above */
            if (m > amp) DD(mp, m) = ((mp - m) & 1) ? -DD(m, mp) : DD(m, mp); /* (−1)^{m'−m} d_{mm'} */
            else DD(mp, m) = DD(-m, -mp);                                     /* m < 0, −m > |m'| */
            (void)am;
        }
    for (size_t i = 0; i < (size_t)w * w; i++) d[i] = (double)D[i];
#undef DD
}

/* The dense X₊₉₀ block of band l (double) into X; ws has zx_gen_work(l). */
static size_t zx_gen_work(int l)
{
    const size_t w = 2 * (size_t)l + 1;
    return (w * w + w) * sizeof(long double) + (w * w + 4 * (size_t)(l + 1)) * sizeof(double);
}
static void zx_xplus_dense(int l, void *ws, double *X)
{
    const size_t w = 2 * (size_t)l + 1;
    long double *ld = ws;
    double *d = (double *)(ld + w * w + w), *csa = d + w * w, *csg = csa + 2 * (l + 1);
    zx_dpi2(l, ld, d);
    /* exact cos, sin of m·(−90°) (α) and m·(+90°) (γ) */
    static const double c4[4] = {1, 0, -1, 0}, s4[4] = {0, 1, 0, -1};
    for (int m = 0; m <= l; m++) {
        csa[2 * m] = c4[m & 3];
        csa[2 * m + 1] = -s4[m & 3];
        csg[2 * m] = c4[m & 3];
        csg[2 * m + 1] = s4[m & 3];
    }
    sh__rot_block_from_d_d(l, d, csa, csg, X);
}

/* Band l's compact X₊₉₀ (the four class blocks, header) from the dense X;
 * checks that every entry outside the pattern is exactly zero (else
 * SH_EINVAL: the pattern derivation is wrong).  `in` has (2l+1)² bytes. */
static int zx_compact(int l, const double *X, unsigned char *in, double *xd, float *xf)
{
    const size_t w = 2 * (size_t)l + 1;
    int n[4];
    zx_cls_n(l, n);
    memset(in, 0, w * w);
    size_t k = 0;
    for (int K = 0; K < 4; K++) {
        const int C = zx_col(l, K);
        for (int r = 0; r < n[K]; r++)
            for (int c = 0; c < n[C]; c++) {
                const size_t i = (size_t)(zx_cls_m(K, r) + l) * w + (size_t)(zx_cls_m(C, c) + l);
                in[i] = 1;
                if (xd) xd[k] = X[i];
                if (xf) xf[k] = (float)X[i];
                k++;
            }
    }
    if (k != (size_t)l * l + l + 1)
        return sh_error(SH_EINVAL, "zxzxz: band %d has %zu non-zeros, expected %d", l, k, l * l + l + 1);
    for (size_t i = 0; i < w * w; i++)
        if (!in[i] && X[i] != 0)
            return sh_error(SH_EINVAL, "zxzxz: X+90 band %d entry (%d,%d) outside the zero pattern", l,
                            (int)(i / w) - l, (int)(i % w) - l);
    return SH_OK;
}

/* Build the compact tables of bands 0..order−1. */
static int zx_tables_build(int order, double *xd, float *xf)
{
    const int L = order - 1;
    const size_t W = 2 * (size_t)L + 1;
    void *ws = malloc(zx_gen_work(L));
    double *X = malloc(W * W * sizeof *X);
    unsigned char *in = malloc(W * W);
    int st = SH_OK;
    if (!ws || !X || !in) st = sh_error(SH_ENOMEM, "zxzxz: out of memory (tables, order %d)", order);
    for (int l = 0; l < order && st == SH_OK; l++) {
        zx_xplus_dense(l, ws, X);
        st = zx_compact(l, X, in, xd ? xd + zx_off(l) : NULL, xf ? xf + zx_off(l) : NULL);
        sh__rot_band_done(l + 1, order);
    }
    free(ws);
    free(X);
    free(in);
    return st;
}

static int zx_tables_new(int order, int single, void **tables)
{
    *tables = NULL;
    zx_tables *T = malloc(sizeof *T);
    if (!T) return sh_error(SH_ENOMEM, "zxzxz: out of memory (tables)");
    T->order = order;
    T->x = malloc(zx_off(order) * (single ? sizeof(float) : sizeof(double)));
    if (!T->x) {
        free(T);
        return sh_error(SH_ENOMEM, "zxzxz: out of memory (tables, order %d)", order);
    }
    int st = zx_tables_build(order, single ? NULL : (double *)T->x, single ? (float *)T->x : NULL);
    if (st) {
        free(T->x);
        free(T);
        return st;
    }
    *tables = T;
    return SH_OK;
}
int sh__rot_zxzxz_tables_new_d(int order, void **tables) { return zx_tables_new(order, 0, tables); }
int sh__rot_zxzxz_tables_new_f(int order, void **tables) { return zx_tables_new(order, 1, tables); }

/* The dense X₊₉₀ block of band l as generated (for the tests). */
int sh__rot_zxzxz_xplus_band(int l, double *X);
int sh__rot_zxzxz_xplus_band(int l, double *X)
{
    void *ws = malloc(zx_gen_work(l));
    if (!ws) return sh_error(SH_ENOMEM, "zxzxz: out of memory");
    zx_xplus_dense(l, ws, X);
    free(ws);
    return SH_OK;
}
#endif

/* y = M x, M dense nr × nc row-major: two rows at a time (two independent
 * accumulator chains; each row still summed left to right). */
static inline __attribute__((always_inline)) void SH_R(zx_mv)(int nr, int nc, const sh_real *M, const sh_real *x, sh_real *y)
{
    int r = 0;
#pragma GCC unroll 8
    for (; r + 2 <= nr; r += 2, M += 2 * nc) {
        const sh_real *M1 = M + nc;
        sh_real a0 = M[0] * x[0], a1 = M1[0] * x[0];
#pragma GCC unroll 16
        for (int c = 1; c < nc; c++) {
            a0 += M[c] * x[c];
            a1 += M1[c] * x[c];
        }
        y[r] = a0;
        y[r + 1] = a1;
    }
    if (r < nr) {
        sh_real a0 = M[0] * x[0];
#pragma GCC unroll 16
        for (int c = 1; c < nc; c++) a0 += M[c] * x[c];
        y[r] = a0;
    }
}

/* t = X₊₉₀ u for band l, u and t split by class (A|B|C|D): four dense blocks. */
static inline __attribute__((always_inline)) void SH_R(zx_xmul)(int l, const sh_real *X, const sh_real *u, sh_real *t)
{
    int n[4], o[4];
    zx_cls_n(l, n);
    o[0] = 0, o[1] = n[0], o[2] = n[0] + n[1], o[3] = o[2] + n[2];
#pragma GCC unroll 4
    for (int K = 0; K < 4; K++) {
        const int C = zx_col(l, K);
        if (n[K] && n[C]) SH_R(zx_mv)(n[K], n[C], X, u + o[C], t + o[K]);
        X += (size_t)n[K] * n[C];
    }
}

/* Z(θ) on a class-split band in place:
 *   c_m ← cos(mθ) c_m − sin(mθ) c_{−m},  c_{−m} ← sin(mθ) c_m + cos(mθ) c_{−m}
 * for m = 2k (A_k, D_{k−1}) and m = 2k+1 (C_k, B_k). */
static inline __attribute__((always_inline)) void SH_R(zx_zsplit)(int l, const sh_real *cs, sh_real *u)
{
    const int nA = l / 2 + 1, nB = (l + 1) / 2;
    sh_real *A = u, *B = u + nA, *C = B + nB, *D = C + nB;
#pragma GCC unroll 16
    for (int k = 1; 2 * k <= l; k++) {
        const sh_real c = cs[4 * k], s = cs[4 * k + 1], a = A[k], b = D[k - 1];
        A[k] = c * a - s * b;
        D[k - 1] = s * a + c * b;
    }
#pragma GCC unroll 16
    for (int k = 0; 2 * k + 1 <= l; k++) {
        const sh_real c = cs[4 * k + 2], s = cs[4 * k + 3], a = C[k], b = B[k];
        C[k] = c * a - s * b;
        B[k] = s * a + c * b;
    }
}

/* One band: out = Z(α+π) X₊₉₀ Z(β+π) X₊₉₀ Z(γ) in (2l+1 values each, header);
 * u, t have 2l+1.  csa, csb carry the +π (set).  Written once for any l;
 * zx_band below instantiates it for each small l as a constant, so that the
 * compiler lays the tiny loops out straight (the same operations in the same
 * order, without the loop control that dominates at these sizes). */
static inline __attribute__((always_inline)) void SH_R(zx_band_l)(int l, const sh_real *X, const sh_real *csa, const sh_real *csb,
                          const sh_real *csg, const sh_real *in, sh_real *out, sh_real *u,
                          sh_real *t)
{
    const int nA = l / 2 + 1, nB = (l + 1) / 2;
    const sh_real *x = in + l; /* x[m], m = −l..l */
    sh_real *y = out + l;
    /* split + Z(γ): A_k = m 2k, D_{k−1} = m −2k, C_k = m 2k+1, B_k = m −(2k+1) */
    {
        sh_real *A = u, *B = u + nA, *C = B + nB, *D = C + nB;
        A[0] = x[0];
#pragma GCC unroll 16
        for (int k = 1; 2 * k <= l; k++) {
            const sh_real c = csg[4 * k], s = csg[4 * k + 1], a = x[2 * k], b = x[-2 * k];
            A[k] = c * a - s * b;
            D[k - 1] = s * a + c * b;
        }
#pragma GCC unroll 16
        for (int k = 0; 2 * k + 1 <= l; k++) {
            const sh_real c = csg[4 * k + 2], s = csg[4 * k + 3], a = x[2 * k + 1], b = x[-2 * k - 1];
            C[k] = c * a - s * b;
            B[k] = s * a + c * b;
        }
    }
    SH_R(zx_xmul)(l, X, u, t);       /* X₊₉₀ */
    SH_R(zx_zsplit)(l, csb, t);      /* Z(β+π) */
    SH_R(zx_xmul)(l, X, t, u);       /* X₊₉₀ (with the Z(π)s: X₋₉₀) */
    /* Z(α+π) + merge */
    {
        const sh_real *A = u, *B = u + nA, *C = B + nB, *D = C + nB;
        y[0] = A[0];
#pragma GCC unroll 16
        for (int k = 1; 2 * k <= l; k++) {
            const sh_real c = csa[4 * k], s = csa[4 * k + 1], a = A[k], b = D[k - 1];
            y[2 * k] = c * a - s * b;
            y[-2 * k] = s * a + c * b;
        }
#pragma GCC unroll 16
        for (int k = 0; 2 * k + 1 <= l; k++) {
            const sh_real c = csa[4 * k + 2], s = csa[4 * k + 3], a = C[k], b = B[k];
            y[2 * k + 1] = c * a - s * b;
            y[-2 * k - 1] = s * a + c * b;
        }
    }
}

#define ZX_SPECIAL 12 /* bands 0..11 (orders ≤ 12) get their own instance */
static void SH_R(zx_band)(int l, const sh_real *X, const sh_real *csa, const sh_real *csb,
                          const sh_real *csg, const sh_real *in, sh_real *out, sh_real *u,
                          sh_real *t)
{
    switch (l) {
#define ZX_CASE(L)                                                                                 \
    case L: SH_R(zx_band_l)(L, X, csa, csb, csg, in, out, u, t); return;
        ZX_CASE(0) ZX_CASE(1) ZX_CASE(2) ZX_CASE(3) ZX_CASE(4) ZX_CASE(5)
        ZX_CASE(6) ZX_CASE(7) ZX_CASE(8) ZX_CASE(9) ZX_CASE(10) ZX_CASE(11)
#undef ZX_CASE
    default: SH_R(zx_band_l)(l, X, csa, csb, csg, in, out, u, t);
    }
}

/* multiplications of zx_band: 3 z rotations (4l) + 2 X products (l²+l+1) */
static uint64_t zx_band_mults(int l) { return 12u * (uint64_t)l + 2u * ((uint64_t)l * l + l + 1); }

/* The per-rotation state: multiple angles of α+π, β+π, γ (2·order values
 * each; the +π is the sign (−1)^m, exact). */
static size_t zx_na(int order) { return 2 * (size_t)order; }
static void SH_R(zx_flip)(int order, sh_real *st, uint64_t *count);
static void SH_R(zx_angles)(int order, const sh_rotation *rot, sh_real *st, uint64_t *count)
{
    const size_t na = zx_na(order);
    sh_real *csa = st, *csb = csa + na, *csg = csb + na;
    SH_R(sh__rot_multiple_angles)((sh_real)rot->alpha, order - 1, csa);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->beta, order - 1, csb);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->gamma, order - 1, csg);
    SH_R(zx_flip)(order, st, count);
}
/* the same from par (cos, sin of α, β, γ; rot_internal.h): no angle */
static void SH_R(zx_angles_par)(int order, const sh_real *par, sh_real *st, uint64_t *count)
{
    const size_t na = zx_na(order);
    sh_real *csa = st, *csb = csa + na, *csg = csb + na;
    SH_R(sh__rot_multiple_angles_cs)(par[0], par[1], order - 1, csa);
    SH_R(sh__rot_multiple_angles_cs)(par[2], par[3], order - 1, csb);
    SH_R(sh__rot_multiple_angles_cs)(par[4], par[5], order - 1, csg);
    SH_R(zx_flip)(order, st, count);
}
/* the +π of α and β: (−1)^m */
static void SH_R(zx_flip)(int order, sh_real *st, uint64_t *count)
{
    const size_t na = zx_na(order);
    sh_real *csa = st, *csb = csa + na;
    for (int m = 1; m < order; m += 2) {
        csa[2 * m] = -csa[2 * m], csa[2 * m + 1] = -csa[2 * m + 1];
        csb[2 * m] = -csb[2 * m], csb[2 * m + 1] = -csb[2 * m + 1];
    }
    if (order > 2) *count += 3u * 2u * (uint64_t)(order - 2); /* recurrence, m ≥ 2 */
}

int SH_R(sh__rot_zxzxz_set)(int order, const sh_rotation *rot, const void *tables, void *state,
                            uint64_t *mults)
{
    uint64_t count = 0;
    SH_R(zx_angles)(order, rot, state, &count);
    if (mults) *mults += count;
    return SH_OK;
}

int SH_R(sh__rot_zxzxz_set_par)(int order, const sh_real *par, const void *tables, void *state,
                                uint64_t *mults)
{
    uint64_t count = 0;
    SH_R(zx_angles_par)(order, par, state, &count);
    if (mults) *mults += count;
    return SH_OK;
}

void SH_R(sh__rot_zxzxz_apply)(int order, const void *tables, const void *state,
                               const sh_real *in, sh_real *out, void *work, uint64_t *mults)
{
    const zx_tables *T = tables;
    const size_t na = zx_na(order);
    const sh_real *csa = state, *csb = csa + na, *csg = csb + na;
    sh_real *u = work, *t = u + 2 * order;
    uint64_t count = 0;
    for (int l = 0; l < order; l++) {
        const size_t o = (size_t)l * l;
        SH_R(zx_band)(l, T->x + zx_off(l), csa, csb, csg, in + o, out + o, u, t);
        count += zx_band_mults(l);
    }
    if (mults) *mults += count;
}

#ifndef SH_REAL_FLOAT
/* One band without the lower ones (double): X₊₉₀ of band l alone (no
 * per-order tables), then the block column by column.  O(l²) memory. */
static size_t zx_band_work(int l)
{
    const size_t w = 2 * (size_t)l + 1, nnz = (size_t)l * l + l + 1;
    return zx_gen_work(l) + (w * w + nnz + 6 * (size_t)(l + 1) + 4 * w) * sizeof(double) + w * w;
}
static int zx_band_double(int l, const sh_rotation *rot, double *block, void *work)
{
    const int w = 2 * l + 1;
    double *X = (double *)((char *)work + zx_gen_work(l)), *xc = X + (size_t)w * w;
    double *ang = xc + ((size_t)l * l + l + 1), *e = ang + 6 * (size_t)(l + 1);
    double *col = e + w, *u = col + w, *t = u + w;
    unsigned char *in = (unsigned char *)(t + w);
    zx_xplus_dense(l, work, X);
    int st = zx_compact(l, X, in, xc, NULL);
    if (st) return st;
    uint64_t count = 0;
    zx_angles_d(l + 1, rot, ang, &count);
    const size_t na = zx_na(l + 1);
    for (int j = 0; j < w; j++) {
        for (int i = 0; i < w; i++) e[i] = 0;
        e[j] = 1;
        zx_band_d(l, xc, ang, ang + na, ang + 2 * na, e, col, u, t);
        for (int i = 0; i < w; i++) block[(size_t)i * w + j] = col[i];
    }
    return SH_OK;
}
#endif

int SH_R(sh__rot_zxzxz_blocks)(int order, const sh_rotation *rot, const void *tables,
                               sh_real *blocks, void *work, uint64_t *mults)
{
    const zx_tables *T = tables;
    if (!T || T->order < order) return sh_error(SH_EINVAL, "zxzxz: tables missing or too small");
    const size_t na = zx_na(order);
    sh_real *csa = work, *csb = csa + na, *csg = csb + na, *e = csg + na, *col = e + 2 * order;
    sh_real *u = col + 2 * order, *t = u + 2 * order;
    uint64_t count = 0;
    SH_R(zx_angles)(order, rot, csa, &count);
    /* column j of band l's block = the band rotation of the unit vector e_j */
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        sh_real *B = blocks + sh_rot_block_offset(l);
        for (int j = 0; j < w; j++) {
            for (int i = 0; i < w; i++) e[i] = 0;
            e[j] = 1;
            SH_R(zx_band)(l, T->x + zx_off(l), csa, csb, csg, e, col, u, t);
            for (int i = 0; i < w; i++) B[(size_t)i * w + j] = col[i];
            count += zx_band_mults(l);
        }
    }
    if (mults) *mults += count;
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static void zx_tables_free(void *tables)
{
    zx_tables *T = tables;
    if (T) free(T->x);
    free(T);
}
static size_t zx_work(int order) /* blocks: angles, e, col, u, t; apply: u, t */
{
    return (3 * zx_na(order) + 8 * (size_t)order) * sizeof(double);
}
static size_t zx_state(int order) { return 3 * zx_na(order) * sizeof(double); }
static size_t zx_tables_bytes(int order) { return zx_off(order) * sizeof(double); }
const sh__rot_ops sh__rot_zxzxz_ops = {
    .name = "zxzxz",
    .max_order = ZX_MAX_ORDER,
    .tables_bytes = zx_tables_bytes,
    .tables_new_d = sh__rot_zxzxz_tables_new_d,
    .tables_new_f = sh__rot_zxzxz_tables_new_f,
    .tables_free = zx_tables_free,
    .work_bytes = zx_work,
    .state_bytes = zx_state,
    .set_d = sh__rot_zxzxz_set_d,
    .set_f = sh__rot_zxzxz_set_f,
    .set_par_d = sh__rot_zxzxz_set_par_d,
    .set_par_f = sh__rot_zxzxz_set_par_f,
    .blocks_d = sh__rot_zxzxz_blocks_d,
    .blocks_f = sh__rot_zxzxz_blocks_f,
    .apply_d = sh__rot_zxzxz_apply_d,
    .apply_f = sh__rot_zxzxz_apply_f,
    .band_d = zx_band_double,
    .band_work_bytes = zx_band_work,
    .one_f = sh__rot_zxzxz_one_f,
};
#endif
