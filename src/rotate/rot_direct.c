/* rot_direct.c — the `direct` method: the SH rotation of bands 0..2 (orders
 * n ≤ 3) written straight from the 3×3 matrix R, no angle, no recursion
 * (precision-generic, see rot_real.h).
 *
 * Conventions (docs/CONVENTIONS.md, shlab/rotate.h): R is row-major, r_ij =
 * R[3i + j], and acts on functions as g(s) = f(R⁻¹s) = f(Rᵀs); the block B of
 * band l maps f's coefficients c to g's, c'_m = Σ_m' B[m][m'] c_m' (rows and
 * columns m = −l..l, index i = l(l+1) + m).  Everything below is derived in
 * the `nocs` basis (no Condon–Shortley phase), whose band-1 and band-2
 * functions are, up to one positive constant per band,
 *   band 1:  y_1^{−1} ∝ y,  y_1^0 ∝ z,  y_1^1 ∝ x
 *   band 2:  y_2^{−2} ∝ xy, y_2^{−1} ∝ yz, y_2^0 ∝ (3z²−1)/(2√3), y_2^1 ∝ xz,
 *            y_2^2 ∝ (x²−y²)/2
 * (the textbook real harmonics; on the unit sphere 3z²−1 = 2z²−x²−y²).
 *
 * The `cs` basis.  cs = nocs with odd m negated: B_cs = S B_nocs S, S =
 * diag((−1)^m).  S is itself the SH rotation of Rz(π) = diag(−1, −1, 1) (a z
 * rotation turns the (m, −m) pair by mπ), and the SH rotation is a
 * homomorphism, so
 *   B_cs(R) = B_nocs(Rz(π) R Rz(π)),
 * and Rz(π) R Rz(π) is R with r02, r12, r20, r21 negated.  The kernels
 * evaluate the nocs formulas below on that sign-flipped R for cs (no
 * multiplication), on R itself for nocs.
 *
 * Band 1.  f(s) = Σ_m c_m y_1^m(s) = k a·s with a = (c_1, c_{−1}, c_0) (the
 * x, y, z components).  g(s) = k a·(Rᵀs) = k (Ra)·s, so a' = R a: with the
 * permutation π(−1) = 1 (y), π(0) = 2 (z), π(1) = 0 (x),
 *   B1[m][m'] = r_{π(m) π(m')}   = | r11 r12 r10 |
 *                                  | r21 r22 r20 |
 *                                  | r01 r02 r00 |     (0 multiplications).
 *
 * Band 2.  On the sphere every band-2 function is a traceless symmetric
 * quadratic form sᵀA s.  The forms of the five harmonics, scaled to unit
 * Frobenius norm (⟨X, Y⟩ = tr(XᵀY); the five have equal norms before
 * scaling, so one constant per band covers them),
 *   E_{−2} = (e0e1ᵀ + e1e0ᵀ)/√2,  E_{−1} = (e1e2ᵀ + e2e1ᵀ)/√2,
 *   E_1 = (e0e2ᵀ + e2e0ᵀ)/√2,     E_2 = diag(1, −1, 0)/√2,
 *   E_0 = diag(−1, −1, 2)/√6,
 * are an orthonormal basis of the traceless symmetric matrices.
 * f(s) = sᵀ(k Σ c_m' E_m') s, g(s) = f(Rᵀs) = sᵀ R A Rᵀ s, so
 *   B2[m][m'] = ⟨E_m, R E_m' Rᵀ⟩.
 * With r_a the a-th column of R, R E_m' Rᵀ is (r_a r_bᵀ + r_b r_aᵀ)/√2 for an
 * off-diagonal m' ↔ (a, b) ∈ {−2: (0,1), −1: (1,2), 1: (0,2)},
 * (r0r0ᵀ − r1r1ᵀ)/√2 for m' = 2, and (3 r2r2ᵀ − I)/√6 for m' = 0 (using
 * r0r0ᵀ + r1r1ᵀ + r2r2ᵀ = RRᵀ = I).  The inner products with E_m for an
 * off-diagonal m ↔ (i, j), m = 2 and m = 0 give (orthogonality of the
 * columns, Σ_k r_ka r_kb = δ_ab, folds the m = 0 rows into one product):
 *   B2[(i,j)][(a,b)] = r_ia r_jb + r_ib r_ja                 9 × 2 mults
 *   B2[(i,j)][2]     = r_i0 r_j0 − r_i1 r_j1                 3 × 2
 *   B2[(i,j)][0]     = √3 r_i2 r_j2                          3 × 1 (+2: √3 r02, √3 r12)
 *   B2[2][(a,b)]     = r_0a r_0b − r_1a r_1b                 3 × 2
 *   B2[0][(a,b)]     = √3 r_2a r_2b                          3 × 1 (+2: √3 r20, √3 r21)
 *   B2[2][2]         = ½[(r00−r01)(r00+r01) − (r10−r11)(r10+r11)]   3
 *   B2[0][2]         = (√3/2)(r20−r21)(r20+r21)              2
 *   B2[2][0]         = (√3/2)(r02−r12)(r02+r12)              2
 *   B2[0][0]         = (3 r22² − 1)/2                        2
 * (e.g. B2[0][2] = (−X00 − X11 + 2X22)/√6 with X = (r0r0ᵀ − r1r1ᵀ)/√2:
 * −(r00² − r01²) − (r10² − r11²) = r20² − r21² by the column norms, so the
 * sum is 3(r20² − r21²)/√12.)  In all 49 multiplications for the band-2
 * block (sh_rot_plan_blocks, rotmat); band 1 costs none.  The
 * identities hold for an orthogonal R: the result is the SH rotation of R
 * only if R is one (R is checked finite, as by the other methods given a
 * matrix; here by Σ (r − r) = 0, which is vectorised in the batch and runs
 * before anything is written).
 *
 * Apply.  One vector per rotation (the goal: a new rotation for every
 * vector) does not need the block: the same identity read the other way,
 * with Ã = √2 Σ c_m E_m (symmetric, traceless),
 *   Ã = | c_2 − q   c_{−2}     c_1   |    q = c_0/√3         1 mult
 *       | c_{−2}   −c_2 − q   c_{−1} |
 *       | c_1       c_{−1}     2q    |
 *   Ã' = r Ã rᵀ:  M = Ã rᵀ (27), Ã'_ij = Σ_k r_ik M_kj for the six
 *        entries 00, 11, 22, 01, 12, 02 (18)
 *   c'_{−2} = Ã'01,  c'_{−1} = Ã'12,  c'_1 = Ã'02,
 *   c'_2 = ½(Ã'00 − Ã'11),  c'_0 = (√3/2) Ã'22                 2 mults
 * (c'_m = ⟨E_m, A'⟩: √2 A'_ij for the off-diagonal m, (A'00 − A'11)/√2,
 * and (2A'22 − A'00 − A'11)/√6 = 3A'22/√6 as A' is traceless), i.e. 48
 * multiplications for band 2, and 9 for band 1 (B1 x, a permuted R x):
 * 57 at n = 3 per rotation and vector, against 49 + 34 through the blocks
 * (57 is also the count quoted for Hable's order-3 rotation; this
 * derivation is our own and was not checked against his).
 * out_0 = in_0.  So the per-rotation state is r alone (9 values, the cs
 * signs applied: no multiplication at set), and every apply costs 57; a
 * rotation applied to many vectors pays 57 a vector where blocks would pay
 * 34 (apply_many is not this method's case).  rotate_many (K rotations,
 * structure of arrays) runs the same per-vector code in one loop over k
 * that the compiler vectorises across rotations (`omp simd`),
 * compiled three times: default flags (SSE2 on x86-64), AVX2 and AVX-512
 * (target attributes), chosen by the rotator's kernel.  No contraction to
 * FMA there (-std=c11 turns it off): the batch variants give the same bits.
 * The single rotation (the plan's apply through ops->one_P, one function per
 * order, convention and instruction set) is the same code with each sum of
 * three products fused into two FMAs in its avx2 and avx512 variants (the
 * multiplications counted are the same 57): it differs from the batch by
 * rounding only (test_rot_direct holds them to 4e-15 of each other in
 * double, 2e-6 in float, per kernel, and each to the MPFR reference).
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_finite.h"
#include "rotate/rot_real.h"

#include <string.h>

SH__ROT_DECLARE_BLOCKS(direct);
SH__ROT_DECLARE_APPLY(direct);
int sh__rot_direct_set_mat_d(int, const double *, void *, uint64_t *);
int sh__rot_direct_set_mat_f(int, const float *, void *, uint64_t *);
void sh__rot_direct_state_blocks_d(int, const void *, double *);
void sh__rot_direct_state_blocks_f(int, const void *, double *);
int sh__rot_direct_rotate_many_d(int, int, sh_rot_kernel, size_t, const double *, const double *,
                                 double *, uint64_t *, uint64_t *);
int sh__rot_direct_rotate_many_f(int, int, sh_rot_kernel, size_t, const float *, const float *,
                                 float *, uint64_t *, uint64_t *);
sh__rot_one_fn_d sh__rot_direct_one_d(int, int, sh_rot_kernel, uint64_t *);
sh__rot_one_fn_f sh__rot_direct_one_f(int, int, sh_rot_kernel, uint64_t *);

#define DR_SQRT3 ((sh_real)1.7320508075688772935)
#define DR_HSQRT3 ((sh_real)0.86602540378443864676)
#define DR_RSQRT3 ((sh_real)0.57735026918962576451)
#define DR_BLOCK_MULTS 49u /* band 2's block (header) */
#define DR_APPLY_MULTS 57u /* band 1 (9) and band 2 (48) of one vector from r (header) */

/* r = R for nocs, Rz(π) R Rz(π) for cs (header: r02, r12, r20, r21 negated) */
static inline __attribute__((always_inline)) void SH_R(dr_signs)(const sh_real *R, int nocs, sh_real *r)
{
#pragma GCC unroll 9
    for (int i = 0; i < 9; i++) r[i] = R[i];
    if (!nocs) r[2] = -r[2], r[5] = -r[5], r[6] = -r[6], r[7] = -r[7];
}

/* B1 (row-major 3×3) from r: a permutation (header) */
static inline __attribute__((always_inline)) void SH_R(dr_band1)(const sh_real *r, sh_real *b)
{
    b[0] = r[4], b[1] = r[5], b[2] = r[3];
    b[3] = r[7], b[4] = r[8], b[5] = r[6];
    b[6] = r[1], b[7] = r[2], b[8] = r[0];
}

/* B2 (row-major 5×5, rows and columns m = −2..2) from r: the quadratic
 * forms of the header, 49 multiplications */
static inline __attribute__((always_inline)) void SH_R(dr_band2)(const sh_real *r, sh_real *b)
{
    const sh_real r00 = r[0], r01 = r[1], r02 = r[2], r10 = r[3], r11 = r[4], r12 = r[5];
    const sh_real r20 = r[6], r21 = r[7], r22 = r[8];
    const sh_real s0 = DR_SQRT3 * r02, s1 = DR_SQRT3 * r12; /* √3 r_i2 */
    const sh_real t0 = DR_SQRT3 * r20, t1 = DR_SQRT3 * r21; /* √3 r_2a */
    /* row m = −2, (i, j) = (0, 1) */
    b[0] = r00 * r11 + r01 * r10;
    b[1] = r01 * r12 + r02 * r11;
    b[2] = s0 * r12;
    b[3] = r00 * r12 + r02 * r10;
    b[4] = r00 * r10 - r01 * r11;
    /* row m = −1, (i, j) = (1, 2) */
    b[5] = r10 * r21 + r11 * r20;
    b[6] = r11 * r22 + r12 * r21;
    b[7] = s1 * r22;
    b[8] = r10 * r22 + r12 * r20;
    b[9] = r10 * r20 - r11 * r21;
    /* row m = 0: √3 r_2a r_2b, and the two diagonal corners */
    b[10] = t0 * r21;
    b[11] = t1 * r22;
    b[12] = (sh_real)1.5 * (r22 * r22) - (sh_real)0.5;
    b[13] = t0 * r22;
    b[14] = DR_HSQRT3 * ((r20 - r21) * (r20 + r21));
    /* row m = 1, (i, j) = (0, 2) */
    b[15] = r00 * r21 + r01 * r20;
    b[16] = r01 * r22 + r02 * r21;
    b[17] = s0 * r22;
    b[18] = r00 * r22 + r02 * r20;
    b[19] = r00 * r20 - r01 * r21;
    /* row m = 2: r_0a r_0b − r_1a r_1b */
    b[20] = r00 * r01 - r10 * r11;
    b[21] = r01 * r02 - r11 * r12;
    b[22] = DR_HSQRT3 * ((r02 - r12) * (r02 + r12));
    b[23] = r00 * r02 - r10 * r12;
    b[24] = (sh_real)0.5 * ((r00 - r01) * (r00 + r01) - (r10 - r11) * (r10 + r11));
}

static int dr_check_order(int order)
{
    if (order < 1 || order > SH_ROT_DIRECT_MAX_ORDER)
        return sh_error(SH_EINVAL, "method direct: order %d outside 1..%d (bands 0..2 only)", order,
                        SH_ROT_DIRECT_MAX_ORDER);
    return SH_OK;
}

/* The blocks of bands 0..order−1 (layout of sh_rot_block_offset) from r
 * (R sign-flipped for cs already: the blocks are cs). */
static void SH_R(dr_blocks_r)(int order, const sh_real *r, sh_real *blocks, uint64_t *mults)
{
    blocks[0] = 1;
    if (order > 1) SH_R(dr_band1)(r, blocks + 1);
    if (order > 2) {
        SH_R(dr_band2)(r, blocks + 10);
        if (mults) *mults += DR_BLOCK_MULTS;
    }
}

/* The state from R: dr_signs(R, 0, r) (entries 2, 5, 6, 7 negated, the cs
 * case), written for the per-rotation set: the first eight as 16-byte
 * vectors times a ±1 table (exact: x·(−1) = −x), R[8] copied — the entry by
 * entry copy and flips cost ~26 instructions there. */
static inline __attribute__((always_inline)) void SH_R(dr_state_from)(const sh_real *R, sh_real *r)
{
    typedef sh_real v_t __attribute__((vector_size(16)));
    static const sh_real sgn[8] = {1, 1, -1, 1, 1, -1, -1, -1};
    enum { N = 16 / sizeof(sh_real) };
    for (int i = 0; i < 8; i += N) {
        v_t a, s;
        memcpy(&a, R + i, 16);
        memcpy(&s, sgn + i, 16);
        a *= s;
        memcpy(r + i, &a, 16);
    }
    r[8] = R[8];
}

/* The per-rotation state is r: R with the cs signs (header), 9 values, the
 * same for every order (which the rotator checked); no multiplication.  R
 * is checked finite first (rot_finite.h). */
int SH_R(sh__rot_direct_set_mat)(int order, const sh_real *R, void *state, uint64_t *mults)
{
#ifdef SH_REAL_FLOAT
    if (!sh__finite9_f(R)) return sh_error(SH_EINVAL, "method direct: matrix entries must be finite");
#else
    if (!sh__finite9_d(R)) return sh_error(SH_EINVAL, "method direct: matrix entries must be finite");
#endif
    SH_R(dr_state_from)(R, state);
    return SH_OK;
}

int SH_R(sh__rot_direct_set)(int order, const sh_rotation *rot, const void *tables, void *state,
                             uint64_t *mults)
{
    sh_real R[9];
    for (int i = 0; i < 9; i++) R[i] = (sh_real)rot->R[i];
    return SH_R(sh__rot_direct_set_mat)(order, R, state, mults);
}

int SH_R(sh__rot_direct_blocks)(int order, const sh_rotation *rot, const void *tables,
                                sh_real *blocks, void *work, uint64_t *mults)
{
    const int st = dr_check_order(order);
    if (st) return st;
    sh_real R[9], r[9];
    for (int i = 0; i < 9; i++) R[i] = (sh_real)rot->R[i];
    SH_R(dr_signs)(R, 0, r);
    SH_R(dr_blocks_r)(order, r, blocks, mults);
    return SH_OK;
}

/* The blocks of the state (sh_rot_plan_blocks), in double. */
void SH_R(sh__rot_direct_state_blocks)(int order, const void *state, double *blocks)
{
    sh_real b[35];
    SH_R(dr_blocks_r)(order, state, b, NULL);
    for (size_t i = 0; i < sh_rot_block_offset(order); i++) blocks[i] = b[i];
}

/* a·b + c: one fused multiply-add when FUSED (the one-vector kernels built
 * for FMA, below; the sum then rounds once instead of twice), else the
 * product and the sum (every other caller: FUSED is a constant 0 there, so
 * no fma call is ever made without the instruction) */
#ifdef SH_REAL_FLOAT
#define DR_FMA_FN __builtin_fmaf
#else
#define DR_FMA_FN __builtin_fma
#endif
#define DR_MA(a, b, c) (fused ? DR_FMA_FN((a), (b), (c)) : (a) * (b) + (c))

/* y = R_sh x for bands 0..order−1 from r (header, "Apply"): band 1 by the
 * permutation B1, band 2 as Ã' = r Ã rᵀ; 9 + 48 multiplications.  Each sum
 * of three products is taken left to right, a·b + c·d + e·f =
 * (a·b + c·d) + e·f, fused as fma(e, f, fma(c, d, a·b)). */
static inline __attribute__((always_inline)) void SH_R(dr_apply_r)(int order, int fused, const sh_real *r,
                                                                   const sh_real *x, sh_real *y)
{
#define DR_SUM3(a, b, c, d, e, f) DR_MA(e, f, DR_MA(c, d, (a) * (b)))
    y[0] = x[0];
    if (order > 1) {
        y[1] = DR_SUM3(r[4], x[1], r[5], x[2], r[3], x[3]);
        y[2] = DR_SUM3(r[7], x[1], r[8], x[2], r[6], x[3]);
        y[3] = DR_SUM3(r[1], x[1], r[2], x[2], r[0], x[3]);
    }
    if (order > 2) {
        /* Ã (symmetric, six values); v_j = Ã (row j of r)ᵀ = column j of
         * M = Ã rᵀ; Ã'_ij = (row i of r)·v_j, v_2 first, so that few values
         * are alive at once */
        const sh_real q = DR_RSQRT3 * x[6];
        const sh_real a00 = x[8] - q, a11 = -x[8] - q, a22 = q + q, a01 = x[4], a12 = x[5], a02 = x[7];
#define DR_V(j, v0, v1, v2)                                                                        \
    const sh_real v0 = DR_SUM3(a00, r[3 * (j)], a01, r[3 * (j) + 1], a02, r[3 * (j) + 2]);         \
    const sh_real v1 = DR_SUM3(a01, r[3 * (j)], a11, r[3 * (j) + 1], a12, r[3 * (j) + 2]);         \
    const sh_real v2 = DR_SUM3(a02, r[3 * (j)], a12, r[3 * (j) + 1], a22, r[3 * (j) + 2])
#define DR_DOT(i, v0, v1, v2) DR_SUM3(r[3 * (i)], v0, r[3 * (i) + 1], v1, r[3 * (i) + 2], v2)
        DR_V(2, w0, w1, w2);
        y[6] = DR_HSQRT3 * DR_DOT(2, w0, w1, w2); /* c'_0 = (√3/2) Ã'22 */
        y[5] = DR_DOT(1, w0, w1, w2);             /* c'_{−1} = Ã'12 */
        y[7] = DR_DOT(0, w0, w1, w2);             /* c'_1 = Ã'02 */
        DR_V(1, u0, u1, u2);
        y[4] = DR_DOT(0, u0, u1, u2); /* c'_{−2} = Ã'01 */
        const sh_real t11 = DR_DOT(1, u0, u1, u2);
        DR_V(0, s0, s1, s2);
        y[8] = (sh_real)0.5 * (DR_DOT(0, s0, s1, s2) - t11); /* c'_2 = ½(Ã'00 − Ã'11) */
#undef DR_V
#undef DR_DOT
    }
#undef DR_SUM3
}
static uint64_t dr_apply_mults(int order) { return order > 2 ? DR_APPLY_MULTS : order > 1 ? 9u : 0u; }

/* out = R_sh in (in ≠ out: the plan copies for in place) */
void SH_R(sh__rot_direct_apply)(int order, const void *tables, const void *state, const sh_real *in,
                                sh_real *out, void *work, uint64_t *mults)
{
    switch (order) { /* each order a constant: the tests on it fold away */
    case 3: SH_R(dr_apply_r)(3, 0, state, in, out); break;
    case 2: SH_R(dr_apply_r)(2, 0, state, in, out); break;
    default: SH_R(dr_apply_r)(1, 0, state, in, out); break;
    }
    if (mults) *mults += dr_apply_mults(order);
}

/* One vector of one rotation, the plan's per-rotation path
 * (ops->one_P): r from the state (cs; a nocs plan flips entries 2, 5, 6, 7
 * back, which gives the nocs block, header "The cs basis"), the vector
 * loaded first (in == out allowed), then dr_apply_r — fused into FMA in
 * the variants built for it (avx2, avx512: the rotator's kernel), so these
 * differ from apply_P and the batch by float rounding only.  One function
 * per (order, convention, instruction set): the tests on them fold away. */
static inline __attribute__((always_inline)) void SH_R(dr_one_vec)(int order, int nocs, int fused,
                                                                   const sh_real *state, const sh_real *in,
                                                                   sh_real *out)
{
    sh_real r[9], x[9];
    SH_R(dr_signs)(state, !nocs, r);
#pragma GCC unroll 9
    for (int i = 0; i < order * order; i++) x[i] = in[i];
    SH_R(dr_apply_r)(order, fused, r, x, out);
}
#define DR_ONE_FN(NAME, TARGET, ORDER, NOCS, FUSED)                                                \
    TARGET static void NAME(const sh_real *state, const sh_real *in, sh_real *out)                 \
    {                                                                                              \
        SH_R(dr_one_vec)(ORDER, NOCS, FUSED, state, in, out);                                      \
    }
#define DR_ONE_SET(PFX, TARGET, FUSED)                                                             \
    DR_ONE_FN(SH_R(PFX##_1c), TARGET, 1, 0, FUSED)                                                       \
    DR_ONE_FN(SH_R(PFX##_2c), TARGET, 2, 0, FUSED)                                                       \
    DR_ONE_FN(SH_R(PFX##_3c), TARGET, 3, 0, FUSED)                                                       \
    DR_ONE_FN(SH_R(PFX##_1n), TARGET, 1, 1, FUSED)                                                       \
    DR_ONE_FN(SH_R(PFX##_2n), TARGET, 2, 1, FUSED)                                                       \
    DR_ONE_FN(SH_R(PFX##_3n), TARGET, 3, 1, FUSED)
#define DR_ONE_ROW(PFX)                                                                            \
    {{SH_R(PFX##_1c), SH_R(PFX##_2c), SH_R(PFX##_3c)}, {SH_R(PFX##_1n), SH_R(PFX##_2n), SH_R(PFX##_3n)}}
typedef void (*SH_R(dr_one_t))(const sh_real *, const sh_real *, sh_real *);
/* GCC's straight-line (SLP) vectoriser would gather the nine results into
 * one vector store (a dozen shuffles, the stack realigned, spills): off for
 * these functions, the results are stored as they come */
#if defined(__GNUC__) && !defined(__clang__)
#define DR_NO_SLP __attribute__((optimize("no-tree-slp-vectorize")))
#else
#define DR_NO_SLP
#endif
DR_ONE_SET(dr_one_base, DR_NO_SLP, 0)
#if defined(__x86_64__) && defined(__GNUC__)
DR_ONE_SET(dr_one_avx2, DR_NO_SLP __attribute__((target("avx2,fma"))), 1)
DR_ONE_SET(dr_one_avx512, DR_NO_SLP __attribute__((target("avx512f,avx512vl,fma"))), 1)
static const SH_R(dr_one_t) SH_R(dr_one_tab)[3][2][3] = {
    DR_ONE_ROW(dr_one_base), DR_ONE_ROW(dr_one_avx2), DR_ONE_ROW(dr_one_avx512)};
#else
static const SH_R(dr_one_t) SH_R(dr_one_tab)[1][2][3] = {DR_ONE_ROW(dr_one_base)};
#endif
#undef DR_ONE_FN
#undef DR_ONE_SET
#undef DR_ONE_ROW

/* The kernel of one vector for (order, convention, the rotator's kernel),
 * and its multiplications (fused or not, the same products). */
SH_R(dr_one_t) SH_R(sh__rot_direct_one)(int order, int nocs, sh_rot_kernel kernel, uint64_t *mults)
{
    if (order < 1 || order > SH_ROT_DIRECT_MAX_ORDER) return NULL;
    int isa = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    isa = kernel == SH_KERNEL_AVX512 ? 2 : kernel == SH_KERNEL_AVX2 ? 1 : 0;
#endif
    *mults = dr_apply_mults(order);
    return SH_R(dr_one_tab)[isa][nocs != 0][order - 1];
}

/* One rotation k of a structure-of-arrays batch (stride K): r and the
 * vector in registers, then dr_apply_r.  ORDER and NOCS are constants at
 * each call. */
static inline __attribute__((always_inline)) void SH_R(dr_one)(int order, int nocs, size_t K, size_t k,
                                                               const sh_real *R, const sh_real *in,
                                                               sh_real *out)
{
    sh_real Rk[9], r[9], x[9], y[9];
#pragma GCC unroll 9
    for (int j = 0; j < 9; j++) Rk[j] = R[(size_t)j * K + k];
#pragma GCC unroll 9
    for (int i = 0; i < order * order; i++) x[i] = in[(size_t)i * K + k];
    SH_R(dr_signs)(Rk, nocs, r);
    SH_R(dr_apply_r)(order, 0, r, x, y);
#pragma GCC unroll 9
    for (int i = 0; i < order * order; i++) out[(size_t)i * K + k] = y[i];
}

/* The batch loop, one instance per instruction set: LANES = the vector's
 * bytes / sizeof(sh_real) (simdlen), ORDER and NOCS constants. */
#define DR_MANY(ORDER, NOCS, LANES)                                                                \
    do {                                                                                           \
        SH_PRAGMA(omp simd simdlen(LANES))                                                         \
        for (size_t k = 0; k < K; k++) SH_R(dr_one)(ORDER, NOCS, K, k, R, in, out);               \
    } while (0)
#define DR_MANY_FN(NAME, TARGET, LANES)                                                            \
    TARGET static int NAME(int order, int nocs, size_t K, const sh_real *R, const sh_real *in,     \
                           sh_real *out)                                                           \
    {                                                                                              \
        sh_real acc = 0; /* 0 if every entry is finite (rot_finite.h) */                           \
        SH_PRAGMA(omp simd simdlen(LANES) reduction(+ : acc))                                      \
        for (size_t i = 0; i < 9 * K; i++) acc += R[i] - R[i];                                     \
        if (acc != 0) return 0;                                                                    \
        switch (order * 2 + (nocs != 0)) {                                                         \
        case 2: DR_MANY(1, 0, LANES); break;                                                       \
        case 3: DR_MANY(1, 1, LANES); break;                                                       \
        case 4: DR_MANY(2, 0, LANES); break;                                                       \
        case 5: DR_MANY(2, 1, LANES); break;                                                       \
        case 6: DR_MANY(3, 0, LANES); break;                                                       \
        case 7: DR_MANY(3, 1, LANES); break;                                                       \
        default: break; /* the rotator refuses other orders */                                     \
        }                                                                                          \
        return 1;                                                                                  \
    }
/* the default flags (SSE2 on x86-64), and on x86-64 AVX2 and AVX-512 (the
 * same arithmetic: no contraction to FMA, -std=c11, so every variant gives
 * the same bits) */
DR_MANY_FN(SH_R(dr_many_base), , SH_SIMD_LANES16)
#if defined(__x86_64__) && defined(__GNUC__)
#define DR_HAVE_WIDE 1
DR_MANY_FN(SH_R(dr_many_avx2), __attribute__((target("avx2"))), 2 * SH_SIMD_LANES16)
DR_MANY_FN(SH_R(dr_many_avx512), __attribute__((target("avx512f,avx512vl"))), 4 * SH_SIMD_LANES16)
#endif

int SH_R(sh__rot_direct_rotate_many)(int order, int nocs, sh_rot_kernel kernel, size_t K,
                                     const sh_real *R, const sh_real *in, sh_real *out,
                                     uint64_t *set_mults, uint64_t *apply_mults)
{
    int ok;
#ifdef DR_HAVE_WIDE
    if (kernel == SH_KERNEL_AVX512) ok = SH_R(dr_many_avx512)(order, nocs, K, R, in, out);
    else if (kernel == SH_KERNEL_AVX2) ok = SH_R(dr_many_avx2)(order, nocs, K, R, in, out);
    else
#endif
        ok = SH_R(dr_many_base)(order, nocs, K, R, in, out);
    if (!ok) return sh_error(SH_EINVAL, "method direct: a rotation has an entry that is not finite");
    if (apply_mults) *apply_mults += dr_apply_mults(order); /* set: none */
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static size_t dr_state(int order) { return 9 * sizeof(double); }
static size_t dr_work(int order) { return 0; }
const sh__rot_ops sh__rot_direct_ops = {
    .name = "direct",
    .max_order = SH_ROT_DIRECT_MAX_ORDER,
    .work_bytes = dr_work,
    .state_bytes = dr_state,
    .set_d = sh__rot_direct_set_d,
    .set_f = sh__rot_direct_set_f,
    .blocks_d = sh__rot_direct_blocks_d,
    .blocks_f = sh__rot_direct_blocks_f,
    .apply_d = sh__rot_direct_apply_d,
    .apply_f = sh__rot_direct_apply_f,
    .matrix_only = 1,
    .set_mat_d = sh__rot_direct_set_mat_d,
    .set_mat_f = sh__rot_direct_set_mat_f,
    .rotate_many_d = sh__rot_direct_rotate_many_d,
    .rotate_many_f = sh__rot_direct_rotate_many_f,
    .one_d = sh__rot_direct_one_d,
    .one_f = sh__rot_direct_one_f,
    .state_blocks_d = sh__rot_direct_state_blocks_d,
    .state_blocks_f = sh__rot_direct_state_blocks_f,
};
#endif
