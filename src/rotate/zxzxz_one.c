/* zxzxz_one.c — zxzxz's kernel of ONE rotation applied to ONE vector, in
 * float, vectorised across the coefficients (AVX-512: 16 float lanes), for
 * orders n = 3..6 (bands 0..n−1; n = 3 runs the packed kernel of n = 4 with
 * band 3 zero: 1.72× `direct`'s time per rotation against the unrolled
 * scalar kernel's 2.00×, bench per-rotation, three alternated runs of each
 * build (14.7–15.0 against 17.3–18.0 ns), where a first split-layout
 * version had measured 20.7 against 19.0 ns; `direct` stays the faster at
 * n = 3).  Float
 * only (not a rot_*.c: compiled once).  The plan reaches it through
 * sh__rot_zxzxz_ops.one_f: rotator.c resolves it once (rotator one_mat),
 * and rotation_plan.c's sh_rot_plan_set_matrix_f only checks the matrix
 * and stores it in the state, which apply_f hands to the kernel, nothing in
 * between.  Everything that depends on the rotation — the Euler data, the
 * multiple angles — is computed here, in registers: the unrolled path's
 * par goes through memory, and a vector load of its scalar stores is not
 * forwarded (a first version of this kernel reading par that way took
 * 42 ns per rotation at n = 4, 24 with scalar loads, bench per-rotation).
 *
 * What it computes (rot_zxzxz.c's header, [1] there): for the rotation
 * R = Rz(α) Ry(β) Rz(γ),
 *   R_sh = Z(α) · X₋₉₀ · Z(β) · X₊₉₀ · Z(γ),   X₋₉₀ = S X₊₉₀ S,  S = Z(π) = diag((−1)^m)
 * (rot_zxzxz.c writes the same product as Z(α+π) X₊₉₀ Z(β+π) X₊₉₀ Z(γ); here
 * the two S are folded into a second constant matrix instead of the
 * angles).  The input is R itself (row-major, finiteness checked by the
 * plan; assumed orthogonal); cos, sin of α, β, γ by rot_fast.c's algebra
 * (zo_angles).  nocs: sin β negated, since S·R_cs(α, β, γ)·S =
 * R_cs(α, −β, γ): one function per (order, convention).
 *
 * Layout ("split"): coefficient (l, m) of the vector (index l² + l + m) is
 * kept in two registers, P for m ≥ 0 and N for m < 0, lane-aligned: lane
 * k of N holds (l, −m) where lane k of P holds (l, m) (N's m = 0 lanes are
 * zero).  Bands 0..4 (n(n+1)/2 ≤ 15 lanes): lane l(l+1)/2 + m.  Then
 *   Z(θ):  P' = c⊙P − s⊙N,  N' = s⊙P + c⊙N,   c, s = cos(mθ), sin(mθ) per lane
 * (rot_internal.h, sh__rot_z_band: c_m ← cos(mθ) c_m − sin(mθ) c_{−m},
 * c_{−m} ← sin(mθ) c_m + cos(mθ) c_{−m}; m = 0: c = 1, s = 0): element-wise,
 * no shuffle — 2 multiplications + 2 fused multiply-adds per register pair.
 *
 * X₊₉₀ and X₋₉₀.  Row m' of X₊₉₀ of band l has its non-zeros in one class
 * of columns (rot_zxzxz.c: A = 0, 2, 4…, B = −1, −3…, C = 1, 3…, D = −2,
 * −4…), at most ⌊l/2⌋ + 1 of them: ≤ 3 for l ≤ 5 (≤ 2 for l ≤ 3).  So
 * output lane i of a register is Σ_{j<J} W_j[i] · x[π_j(i)], where π_j(i) is
 * the lane (in P or N of the same band group) of the j-th non-zero column
 * of i's row and W_j[i] its entry of X (zero where the row has fewer than J):
 *   O = W₀ ⊙ perm₀(P, N) + W₁ ⊙ perm₁(P, N) + W₂ ⊙ perm₂(P, N),
 * one two-source permute (vpermt2ps) and one multiply or FMA per term and
 * output register; J = 2 for n ≤ 4, 3 for n = 5, 6.  W of X₋₉₀ = (−1)^{m'+m}
 * W of X₊₉₀; the permutes are the same.  The tables are built once (first
 * resolve) from rot_zxzxz.c's X₊₉₀ (d^l(π/2) in long double; its zero
 * pattern is checked exactly there and here: a row with more than 3
 * non-zeros leaves the kernel unresolved and the plan on the unrolled one).
 *
 * n = 4 ("packed"): the 16 coefficients fit one register, P lanes 0..9
 * (l(l+1)/2 + m) and N lanes 10..15 (10 + l(l−1)/2 + |m| − 1), so
 *   Z(θ):  v' = c⊙v + s'⊙swap(v),   s' = −sin(|m|θ) on P lanes, +sin on N lanes
 * (swap: the single-source permute exchanging (l, m) and (l, −m)), and each
 * X term is a single-source permute of v; the index vectors stay in
 * registers across the three Z and two X.  Measured 0.81× the split layout
 * at n = 4 (kernel alone).  n = 3 is the same kernel on 9 coefficients
 * (masked load and store): band 3's lanes hold zeros, which Z and X (block
 * diagonal by band) keep at zero, and v3 is not formed.  n = 5 keeps the split layout; n = 6 ("n = 6")
 * keeps it for bands 0..4 and packs band 5 (11 coefficients) into one
 * register the same way (P lanes 0..5, N lanes 6..10; its X with J = 3
 * single-source permutes instead of 2 × 3 two-source ones): 0.91× the split
 * band 5 (kernel alone).  (Bands 0..3 packed and band 4 apart at n = 5
 * would trade the two-source permutes for more c, s vectors: no fewer
 * instructions by count, not tried.)
 *
 * Multiple angles: 8-lane vectors v_m = (cos mα, cos mβ, cos mγ, 1,
 * sin mα, sin mβ, sin mγ, 0) by the Chebyshev recurrence
 *   v_m = 2cos(θ)·v_{m−1} − v_{m−2}   (cos and sin alike; lane 3: 2·1 − 1 = 1)
 * one FMA per m = 2..n−1 (v4 instead by the step-2 form
 * v4 = 2cos(2θ)·v2 − v0, 2cos 2θ = (2cos θ)² − 2: one FMA more, beside v3
 * rather than after it; measured 0.97× at n = 5, 6, kernel alone) — run
 * twice: once on the β and γ lanes, which the first two z rotations need
 * and which come first from R (zo_angles), once on the α lane, which comes
 * last and is needed last — then per angle the c, s lane vectors of Z by
 * one permute from (v₁|v₂, v₃|v₄) (lane 3 gives cos 0 = 1, lane 7
 * sin 0 = 0), plus one masked permute for m = 5 (band 5 at n = 6).  Load:
 * the n² inputs (masked loads, nothing read past the vector)
 * permuted into the layout; store: the inverse permutes, masked stores.
 * Everything is loaded before anything is stored: in == out is allowed.
 *
 * Multiplications (*mults, counted as executed: each multiply or FMA lane
 * that holds a coefficient or an angle, including the trivial ones —
 * cos 0 = 1 at m = 0, the zero weights of a row with fewer than J
 * non-zeros; the padding lanes are not counted): per Z 2 per live lane,
 * 2n² (three Z: 6n²); per X, J per live lane, J·n² (two X: 2Jn²);
 * Chebyshev 6(n−2) (per m, 4 live lanes in the β, γ run and 2 in the α
 * run; the step-2 factor 2cos 2θ adds 6 at n ≥ 5), and 24 for the angles
 * from R (zo_angles): n = 3, 4, 5, 6: 120, 196, 348, 486.  (The generated scalar kernel counts fewer, 120, 216, 344
 * at these orders plus 12 in the set, as it skips the zeros; it runs them
 * one instruction each.)
 */
#include "rotate/rot_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int sh__rot_zxzxz_xplus_band(int l, double *X); /* rot_zxzxz.c */
sh__rot_one_fn_f sh__rot_zxzxz_one_f(int order, int nocs, sh_rot_kernel kernel, uint64_t *mults);

#define ZO_MAXO 6
#define ZO_MINO 3 /* below: the unrolled kernel (header) */
#define ZO_J 3 /* terms per output lane, at most (header) */
#define ZO_ANGLE_MULTS 24u /* zo_angles */

/* The per-order tables of the split layout (n = 5, 6; bands 0..4): index
 * vectors of the permutes, weights, masks. */
typedef struct {
    _Alignas(64) int32_t in[2][16]; /* P, N from (in[0..15], in[16..31]); the type 64-aligned, so
                                       every element of an array of it is (the kernel's aligned loads) */
    int32_t xi[2][ZO_J][16];  /* term j of output P, N (from P|N) */
    float w[2][2][ZO_J][16];  /* its weights, X₊₉₀ and X₋₉₀ */
    int32_t cs[2][3][16];     /* cos, sin of angle a (0 α, 1 β, 2 γ): index into (v1|v2, v3|v4) */
    int32_t out[2][16];       /* out[0..15], out[16..24] from (P|N) */
    uint16_t kin[2];          /* live lanes of P, N */
    int J;                    /* terms per lane, all bands 0..n−1 (band 5: zoh) */
} zo_tab;

static _Alignas(64) zo_tab zo_tabs[ZO_MAXO + 1];
static int zo_ok[ZO_MAXO + 1];
static pthread_once_t zo_once = PTHREAD_ONCE_INIT;

/* lane of (l, |m|) in its register (header) */
static int zo_lane(int l, int am) { return l < 5 ? l * (l + 1) / 2 + am : am; }
/* index of (l, m) into the permute source pair (P|N) of its group */
static int zo_src(int l, int m) { return m >= 0 ? zo_lane(l, m) : 16 + zo_lane(l, -m); }

/* multiplications of one call (header) */
static uint64_t zo_mults(int n, int J)
{
    const uint64_t nn = (uint64_t)n * n;
    return ZO_ANGLE_MULTS + 6 * nn + 2 * (uint64_t)J * nn + 6 * (uint64_t)(n - 2) + (n > 4 ? 6 : 0);
}

static int zo_build(int n, zo_tab *t)
{
    double X[11 * 11];
    const int nl = n < 5 ? n : 5; /* the bands in P, N */
    memset(t, 0, sizeof *t);
    /* cos and sin index of m for angle a: v1|v2 = lanes 0..15, v3|v4 = 16..31;
     * in v_m cos at a, sin at 4 + a; lane 3 = 1, lane 7 = 0 */
    for (int l = 0; l < nl; l++)
        for (int m = 0; m <= l; m++)
            for (int cs = 0; cs < 2; cs++)
                for (int a = 0; a < 3; a++)
                    t->cs[cs][a][zo_lane(l, m)] = m == 0 ? (cs ? 7 : 3) : 8 * (m - 1) + 4 * cs + a;
    for (int cs = 0; cs < 2; cs++) /* the lanes past the bands: cos 0, sin 0 */
        for (int a = 0; a < 3; a++)
            for (int i = nl * (nl + 1) / 2; i < 16; i++) t->cs[cs][a][i] = cs ? 7 : 3;
    /* input: P lane (l, m) ← l² + l + m, N lane (l, m) ← l² + l − m */
    for (int l = 0; l < nl; l++)
        for (int m = 0; m <= l; m++) {
            t->in[0][zo_lane(l, m)] = l * l + l + m;
            t->kin[0] |= (uint16_t)(1u << zo_lane(l, m));
            if (m > 0) {
                t->in[1][zo_lane(l, m)] = l * l + l - m;
                t->kin[1] |= (uint16_t)(1u << zo_lane(l, m));
            }
        }
    /* X₊₉₀, X₋₉₀: output lane (l, m') takes its row's non-zero columns (J
     * over every band, band 5's written by zoh_build) */
    int J = 0;
    for (int l = 0; l < n; l++) {
        const int w = 2 * l + 1;
        if (sh__rot_zxzxz_xplus_band(l, X)) return 0;
        for (int mp = -l; mp <= l; mp++) {
            const int O = mp < 0, lane = zo_lane(l, mp < 0 ? -mp : mp);
            int j = 0;
            for (int m = -l; m <= l; m++) {
                const double x = X[(size_t)(mp + l) * w + (size_t)(m + l)];
                if (x == 0) continue;
                if (j == ZO_J) return 0;
                if (l < 5) {
                    t->xi[O][j][lane] = zo_src(l, m);
                    t->w[0][O][j][lane] = (float)x;
                    t->w[1][O][j][lane] = (float)((((mp + m) % 2) != 0) ? -x : x);
                }
                j++;
            }
            if (j > J) J = j;
        }
    }
    /* output: out[i], i = l² + l + m < 25 */
    for (int l = 0; l < nl; l++)
        for (int m = -l; m <= l; m++) {
            const int i = l * l + l + m;
            t->out[i >> 4][i & 15] = zo_src(l, m);
        }
    t->J = J;
    return J >= 1;
}

/* The non-zero entries of X₊₉₀'s band l, row by row, as terms of the output
 * lanes of a packed layout (lane[i]: the lane of m = i − l): term j of lane
 * (m') reads lane (m) with weight x for X₊₉₀ (wp) and (−1)^(m'+m) x for
 * X₋₉₀ = S X₊₉₀ S (wm).  0 if a row has more than maxj non-zeros. */
static int x_terms(int l, const int *lane, int maxj, int32_t (*xi)[16], float (*wp)[16], float (*wm)[16])
{
    double X[11 * 11];
    const int w = 2 * l + 1;
    if (sh__rot_zxzxz_xplus_band(l, X)) return 0;
    for (int mp = -l; mp <= l; mp++) {
        int j = 0;
        for (int m = -l; m <= l; m++) {
            const double x = X[(size_t)(mp + l) * w + (size_t)(m + l)];
            if (x == 0) continue;
            if (j == maxj) return 0;
            xi[j][lane[mp + l]] = lane[m + l];
            wp[j][lane[mp + l]] = (float)x;
            wm[j][lane[mp + l]] = (float)((((mp + m) % 2) != 0) ? -x : x);
            j++;
        }
    }
    return 1;
}

/* n = 4, packed (header "n = 4"): P lanes 0..9, N lanes 10..15 */
typedef struct {
    _Alignas(64) int32_t in[16];
    int32_t swap[16], xi[2][16], out[16];
    float w[2][2][16];       /* [X₊₉₀, X₋₉₀][term] */
    int32_t cs[2][3][16];    /* cos, sin of angle a: index into (v1|v2, v3|v4) */
    uint32_t sgn[16];        /* the sign bit on the P lanes: s' = −s there */
} zo4_tab;
static _Alignas(64) zo4_tab zo4;
static int zo4_ok;
static int zo4_lane(int l, int m) { return m >= 0 ? l * (l + 1) / 2 + m : 10 + l * (l - 1) / 2 - m - 1; }
static int zo4_build(zo4_tab *t)
{
    memset(t, 0, sizeof *t);
    for (int l = 0; l < 4; l++)
        for (int m = -l; m <= l; m++) {
            const int k = zo4_lane(l, m), am = m < 0 ? -m : m;
            t->in[k] = l * l + l + m;
            t->out[l * l + l + m] = k;
            t->swap[k] = zo4_lane(l, -m);
            t->sgn[k] = m >= 0 ? 0x80000000u : 0u;
            for (int cs = 0; cs < 2; cs++)
                for (int a = 0; a < 3; a++)
                    t->cs[cs][a][k] = am == 0 ? (cs ? 7 : 3) : 8 * (am - 1) + 4 * cs + a;
        }
    for (int l = 0; l < 4; l++) {
        int lane[7];
        for (int m = -l; m <= l; m++) lane[m + l] = zo4_lane(l, m);
        if (!x_terms(l, lane, 2, t->xi, t->w[0], t->w[1])) return 0;
    }
    return 1;
}

/* n = 6, band 5 packed in one register (header "n = 6"): P lanes 0..5,
 * N lanes 6..10 */
typedef struct {
    _Alignas(64) int32_t in[16];
    int32_t swap[16], xi[ZO_J][16], out1[16], out2[16];
    float w[2][ZO_J][16];
    int32_t cs[2][3][16], cs5[2][3][16];
    uint32_t sgn[16];
} zoh_tab;
static _Alignas(64) zoh_tab zoh;
static int zoh_ok;
static int zoh_lane(int m) { return m >= 0 ? m : 5 - m; }
static int zoh_build(zoh_tab *t)
{
    const int l = 5;
    memset(t, 0, sizeof *t);
    for (int m = -l; m <= l; m++) {
        const int k = zoh_lane(m), am = m < 0 ? -m : m;
        t->in[k] = l * l + l + m - 16; /* into (in[16..31], in[32..47]) */
        t->swap[k] = zoh_lane(-m);
        t->sgn[k] = m >= 0 ? 0x80000000u : 0u;
        for (int cs = 0; cs < 2; cs++)
            for (int a = 0; a < 3; a++) {
                t->cs[cs][a][k] = am == 0 || am == 5 ? (cs ? 7 : 3) : 8 * (am - 1) + 4 * cs + a;
                t->cs5[cs][a][k] = 4 * cs + a;
            }
        const int i = l * l + l + m; /* 25..35 */
        if (i < 32) t->out1[i - 16] = k;
        else t->out2[i - 32] = k;
    }
    int lane[11];
    for (int m = -l; m <= l; m++) lane[m + l] = zoh_lane(m);
    return x_terms(l, lane, ZO_J, t->xi, t->w[0], t->w[1]);
}

static void zo_init(void)
{
    zo4_ok = zo4_build(&zo4);
    for (int n = 5; n <= ZO_MAXO; n++) zo_ok[n] = zo_build(n, &zo_tabs[n]);
    zoh_ok = zoh_build(&zoh);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define ZO_HAVE_AVX512 1
#include <immintrin.h>

/* every function to the pop below is compiled for AVX-512 (GCC's pragma; clang,
 * which builds the fuzzers, has its own) */
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512vl,fma"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f,avx512vl,fma")
#endif

#define ZO_LDI(p) _mm512_load_si512((const void *)(p))
#define ZO_LDF(p) _mm512_load_ps((const void *)(p))

/* the c, s lane vectors of angle a (header "Multiple angles") */
static inline __attribute__((always_inline)) void zo_cs(const zo_tab *t, int a, __m512 v12, __m512 v34, __m512 *c,
                                                        __m512 *s)
{
    *c = _mm512_permutex2var_ps(v12, ZO_LDI(t->cs[0][a]), v34);
    *s = _mm512_permutex2var_ps(v12, ZO_LDI(t->cs[1][a]), v34);
}
/* Z(θ) of angle a on the packed band 5 (n = 6): v' = c⊙v + s'⊙swap(v) */
static inline __attribute__((always_inline)) __m512 zoh_z(int a, __m512 v12, __m512 v34, __m512 v5, __m512i sw,
                                                          __m512i sg, __m512 h)
{
    const zoh_tab *t = &zoh;
    const __mmask16 k5 = (1u << 5) | (1u << 10); /* |m| = 5: from v5 */
    const __m512 c = _mm512_mask_permutexvar_ps(_mm512_permutex2var_ps(v12, ZO_LDI(t->cs[0][a]), v34), k5,
                                                ZO_LDI(t->cs5[0][a]), v5);
    const __m512 s = _mm512_mask_permutexvar_ps(_mm512_permutex2var_ps(v12, ZO_LDI(t->cs[1][a]), v34), k5,
                                                ZO_LDI(t->cs5[1][a]), v5);
    const __m512 sp = _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(s), sg));
    return _mm512_fmadd_ps(sp, _mm512_permutexvar_ps(sw, h), _mm512_mul_ps(c, h));
}
/* X (x = 0: X₊₉₀, 1: X₋₉₀) on the packed band 5 */
static inline __attribute__((always_inline)) __m512 zoh_x(int x, const __m512i *xi, __m512 h)
{
    const zoh_tab *t = &zoh;
    __m512 o = _mm512_mul_ps(ZO_LDF(t->w[x][0]), _mm512_permutexvar_ps(xi[0], h));
    o = _mm512_fmadd_ps(ZO_LDF(t->w[x][1]), _mm512_permutexvar_ps(xi[1], h), o);
    return _mm512_fmadd_ps(ZO_LDF(t->w[x][2]), _mm512_permutexvar_ps(xi[2], h), o);
}

/* cos, sin of α, β, γ of R = Rz(α) Ry(β) Rz(γ) (nocs: sin β negated), by
 * the algebra of rot_fast.c (sh__rot_par_matrix, derivation there) with the
 * roles of α and γ exchanged — γ is needed first (Z(γ) starts the chain),
 * α last, so γ is taken straight from row 2 and α relative to it:
 *   cβ = r22,  sβ = |r20 + i r21|,  e^{iγ} = (−r20 + i r21)/sβ  (γ = 0 if sβ = 0),
 *   e^{i(α+σγ)} = (p + iq)/|p + iq|,  p + iq = (r11 + σ r00) + i(σ r10 − r01),
 *   e^{iα} = e^{i(α+σγ)} · (cγ − iσ sγ),
 * σ = +1 if r22 ≥ 0 ((b) of rot_fast.c, modulus 1 + cβ ≥ 1), −1 else ((c),
 * 1 − cβ > 1).  (From R = [[cαcβcγ − sαsγ, …, cαsβ], […, sαsβ],
 * [−sβcγ, sβsγ, cβ]].)  Near β = 0 or π e^{iγ} is ill-conditioned, but α
 * is taken relative to the same γ, so the error cancels in α ± γ, all that
 * R depends on there (rot_fast.c's argument, mirrored).  Each 1/√ by the
 * AVX-512 estimate (relative error < 2⁻¹⁴) and one Newton step
 * y ← y + (y/2)(1 − x y²) (error ≈ 1.5·2⁻²⁸ + rounding, about an ulp; not
 * the correctly rounded sqrt and division of rot_fast.c): 4 multiplications
 * instead of a square root and a division.  No branch (σ by the sign bit of
 * r22, the degenerate sβ = 0 by a mask; a mispredicted branch would cost
 * more than this function).  24 multiplications (ZO_ANGLE_MULTS, per line
 * below).  Out: g1 = (1, cβ, cγ, 1, 0, sβ, sγ, 0) and t = 2(1, cβ, cγ, 1)
 * twice (the Chebyshev factor), a1 = (cα, 1, 1, 1, sα, 0, 0, 0) and
 * ta = 2(cα, 1, 1, 1) twice (header "Multiple angles"). */
/* 1/√x, and 0 for x = 0 (the mask): in lane 0; *zero = 1 if x = 0, else 0 */
static inline __attribute__((always_inline)) __m128 zo_rsqrt(__m128 v, __m128 *zero)
{
    __m128 y = _mm_rsqrt14_ss(v, v);
    const __m128 e = _mm_fnmadd_ss(v, _mm_mul_ss(y, y), _mm_set_ss(1.0f)); /* 2: 1 − x y² */
    y = _mm_fmadd_ss(_mm_mul_ss(y, _mm_set_ss(0.5f)), e, y);               /* 2: y + (y/2) e */
    const __m128 pos = _mm_cmp_ss(v, _mm_setzero_ps(), _CMP_GT_OQ);
    *zero = _mm_andnot_ps(pos, _mm_set_ss(1.0f));
    return _mm_and_ps(y, pos);
}
/* a·b + c, fused (the target has FMA; -std=c11 does not contract) */
#define ZO_FMA(a, b, c) __builtin_fmaf((a), (b), (c))
/* insert lane 0 of b into lane k of a */
#define ZO_INS(a, b, k) _mm_insert_ps((a), (b), (k) << 4)
static inline __attribute__((always_inline)) void zo_angles(const float *R, int nocs, __m256 *g1, __m256 *tg,
                                                            __m256 *a1, __m256 *ta)
{
    const float r00 = R[0], r01 = R[1], r10 = R[3], r11 = R[4], r20 = R[6], r21 = R[7], r22 = R[8];
    /* β, γ */
    const float s2 = ZO_FMA(r20, r20, r21 * r21);                             /* 2 */
    __m128 g0;
    const float inv = _mm_cvtss_f32(zo_rsqrt(_mm_set_ss(s2), &g0));          /* 4 */
    const float cg = ZO_FMA(-r20, inv, _mm_cvtss_f32(g0)), sg = r21 * inv;    /* 2: cγ = 1 if sβ = 0 */
    const float sb = s2 * inv;                                                /* 1 */
    const __m128 glo = ZO_INS(ZO_INS(_mm_setr_ps(1, 0, 0, 1), _mm_set_ss(r22), 1), _mm_set_ss(cg), 2);
    const __m128 ghi = ZO_INS(ZO_INS(_mm_setzero_ps(), _mm_set_ss(nocs ? -sb : sb), 1), _mm_set_ss(sg), 2);
    const __m128 glo2 = _mm_add_ps(glo, glo);
    *g1 = _mm256_insertf128_ps(_mm256_castps128_ps256(glo), ghi, 1);
    *tg = _mm256_insertf128_ps(_mm256_castps128_ps256(glo2), glo2, 1);
    /* α */
    const float sgm = copysignf(1.0f, r22); /* σ: bit operations */
    const float p = ZO_FMA(sgm, r00, r11), q = ZO_FMA(sgm, r10, -r01);        /* 2 */
    const float n2 = ZO_FMA(p, p, q * q);                                     /* 2 */
    __m128 z0;
    const float nrm = _mm_cvtss_f32(zo_rsqrt(_mm_set_ss(n2), &z0));          /* 4 */
    const float cs = p * nrm, ss = q * nrm, ssg = sgm * sg;                   /* 3 */
    const float ca = ZO_FMA(cs, cg, ss * ssg), sa = ZO_FMA(ss, cg, -(cs * ssg)); /* 4 */
    const __m128 alo = _mm_move_ss(_mm_set1_ps(1.0f), _mm_set_ss(ca));
    const __m128 ahi = _mm_set_ss(sa);
    const __m128 alo2 = _mm_add_ps(alo, alo);
    *a1 = _mm256_insertf128_ps(_mm256_castps128_ps256(alo), ahi, 1);
    *ta = _mm256_insertf128_ps(_mm256_castps128_ps256(alo2), alo2, 1);
}
#undef ZO_INS
#undef ZO_FMA

/* v_1 … v_N−1 (header "Multiple angles") from v1 and t = 2cos θ per lane:
 * (v1|v2, v3|v4, v5) as the permutes of zo_cs read them */
static inline __attribute__((always_inline)) void zo_multiple(int N, __m256 v1, __m256 t, __m512 *v12, __m512 *v34,
                                                              __m512 *v5z)
{
    const __m256 v0 = _mm256_setr_ps(1, 1, 1, 1, 0, 0, 0, 0);
    const __m256 v2 = N > 2 ? _mm256_fmsub_ps(t, v1, v0) : v0;
    const __m256 v3 = N > 3 ? _mm256_fmsub_ps(t, v2, v1) : v0;
    /* v4 by the step-2 recurrence v4 = 2cos(2θ)·v2 − v0, 2cos 2θ = t² − 2:
     * beside v3 instead of after it (one FMA more, one less in the chain) */
    const __m256 t2 = N > 4 ? _mm256_fmsub_ps(t, t, _mm256_set1_ps(2.0f)) : v0;
    const __m256 v4 = N > 4 ? _mm256_fmsub_ps(t2, v2, v0) : v0;
    const __m256 v5 = N > 5 ? _mm256_fmsub_ps(t, v4, v3) : v0;
#define ZO_CAT(a, b) _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castps_pd(_mm512_castps256_ps512(a)), _mm256_castps_pd(b), 1))
    *v12 = ZO_CAT(v1, v2);
    *v34 = N > 3 ? ZO_CAT(v3, v4) : *v12;
    *v5z = _mm512_castps256_ps512(v5);
#undef ZO_CAT
}

/* Z(θ) on one register pair: P' = c⊙P − s⊙N, N' = s⊙P + c⊙N */
static inline __attribute__((always_inline)) void zo_z(__m512 c, __m512 s, __m512 *P, __m512 *N)
{
    const __m512 p = *P, q = *N;
    *P = _mm512_fnmadd_ps(s, q, _mm512_mul_ps(c, p));
    *N = _mm512_fmadd_ps(s, p, _mm512_mul_ps(c, q));
}

/* output register O of X (x = 0: X₊₉₀, 1: X₋₉₀) from the pair (P|N): Σ_j W_j ⊙ perm_j */
static inline __attribute__((always_inline)) __m512 zo_xo(const zo_tab *t, int J, int x, int O, __m512 P, __m512 N)
{
    __m512 o = _mm512_mul_ps(ZO_LDF(t->w[x][O][0]), _mm512_permutex2var_ps(P, ZO_LDI(t->xi[O][0]), N));
    for (int j = 1; j < J; j++)
        o = _mm512_fmadd_ps(ZO_LDF(t->w[x][O][j]), _mm512_permutex2var_ps(P, ZO_LDI(t->xi[O][j]), N), o);
    return o;
}

static inline __attribute__((always_inline)) void zo_kernel(int N, int J, int nocs, const float *R,
                                                            const float *in, float *out)
{
    const zo_tab *t = &zo_tabs[N];
    const int nc = N * N;
    /* the vector, in the split layout */
    const __m512 x0 = _mm512_maskz_loadu_ps((__mmask16)(nc >= 16 ? 0xffff : (1u << nc) - 1), in);
    const __m512 x1 = nc > 16 ? _mm512_maskz_loadu_ps((__mmask16)(nc >= 32 ? 0xffff : (1u << (nc - 16)) - 1), in + 16)
                              : x0;
    const __m512 x2 = nc > 32 ? _mm512_maskz_loadu_ps((__mmask16)((1u << (nc - 32)) - 1), in + 32) : x1;
    __m512 Pl = _mm512_maskz_permutex2var_ps(t->kin[0], x0, ZO_LDI(t->in[0]), x1);
    __m512 Nl = _mm512_maskz_permutex2var_ps(t->kin[1], x0, ZO_LDI(t->in[1]), x1);
    /* n = 6: band 5 packed (header "n = 6") */
    __m512 H = _mm512_setzero_ps();
    if (N == 6) H = _mm512_maskz_permutex2var_ps(0x7ff, x1, ZO_LDI(zoh.in), x2);
    /* the angles (zo_angles) and their multiples: γ and β first, α apart */
    __m256 g1, tg, a1, ta;
    zo_angles(R, nocs, &g1, &tg, &a1, &ta);
    __m512 g12, g34, g5, a12, a34, a5;
    zo_multiple(N, g1, tg, &g12, &g34, &g5);
    zo_multiple(N, a1, ta, &a12, &a34, &a5);
    __m512i hsw = _mm512_setzero_si512(), hsg = hsw, hxi[ZO_J] = {hsw, hsw, hsw};
    if (N == 6) {
        hsw = ZO_LDI(zoh.swap), hsg = ZO_LDI(zoh.sgn);
        for (int j = 0; j < ZO_J; j++) hxi[j] = ZO_LDI(zoh.xi[j]);
    }
    __m512 c, s;
    /* Z(γ) */
    zo_cs(t, 2, g12, g34, &c, &s);
    zo_z(c, s, &Pl, &Nl);
    if (N == 6) H = zoh_z(2, g12, g34, g5, hsw, hsg, H);
    /* X₊₉₀ */
    __m512 b0 = zo_xo(t, J, 0, 0, Pl, Nl), b1 = zo_xo(t, J, 0, 1, Pl, Nl);
    if (N == 6) H = zoh_x(0, hxi, H);
    /* Z(β) */
    zo_cs(t, 1, g12, g34, &c, &s);
    zo_z(c, s, &b0, &b1);
    if (N == 6) H = zoh_z(1, g12, g34, g5, hsw, hsg, H);
    /* X₋₉₀ */
    Pl = zo_xo(t, J, 1, 0, b0, b1), Nl = zo_xo(t, J, 1, 1, b0, b1);
    if (N == 6) H = zoh_x(1, hxi, H);
    /* Z(α) */
    zo_cs(t, 0, a12, a34, &c, &s);
    zo_z(c, s, &Pl, &Nl);
    if (N == 6) H = zoh_z(0, a12, a34, a5, hsw, hsg, H);
    /* back to l² + l + m */
    const __m512 y0 = _mm512_permutex2var_ps(Pl, ZO_LDI(t->out[0]), Nl);
    _mm512_mask_storeu_ps(out, (__mmask16)(nc >= 16 ? 0xffff : (1u << nc) - 1), y0);
    if (N == 5) _mm512_mask_storeu_ps(out + 16, 0x1ff, _mm512_permutex2var_ps(Pl, ZO_LDI(t->out[1]), Nl));
    if (N == 6) {
        const __m512 lo = _mm512_permutex2var_ps(Pl, ZO_LDI(t->out[1]), Nl);
        const __m512 hi = _mm512_permutexvar_ps(ZO_LDI(zoh.out1), H);
        _mm512_storeu_ps(out + 16, _mm512_mask_blend_ps(0xfe00, lo, hi));
        _mm512_mask_storeu_ps(out + 32, 0xf, _mm512_permutexvar_ps(ZO_LDI(zoh.out2), H));
    }
    (void)a5;
}

/* n = 4, packed: the 16 coefficients in one register (header "n = 4"); n = 3
 * the same with band 3 zero */
static inline __attribute__((always_inline)) void zo4_kernel(int N, int nocs, const float *R, const float *in,
                                                             float *out)
{
    const zo4_tab *t = &zo4;
    const __mmask16 live = N == 4 ? 0xffff : 0x1ff;
    __m512 v = _mm512_permutexvar_ps(ZO_LDI(t->in), _mm512_maskz_loadu_ps(live, in));
    __m256 g1, tg, a1, ta;
    zo_angles(R, nocs, &g1, &tg, &a1, &ta);
    __m512 g12, g34, g5, a12, a34, a5;
    zo_multiple(N, g1, tg, &g12, &g34, &g5);
    zo_multiple(N, a1, ta, &a12, &a34, &a5);
    const __m512i sw = ZO_LDI(t->swap), x0 = ZO_LDI(t->xi[0]), x1 = ZO_LDI(t->xi[1]);
    const __m512i sg = ZO_LDI(t->sgn); /* xor by integer ops: _mm512_xor_ps is AVX512DQ */
#define ZO4_Z(A12, A34, a)                                                                         \
    do {                                                                                           \
        const __m512 c = _mm512_permutex2var_ps(A12, ZO_LDI(t->cs[0][a]), A34);                    \
        const __m512 s = _mm512_castsi512_ps(                                                      \
            _mm512_xor_si512(_mm512_castps_si512(_mm512_permutex2var_ps(A12, ZO_LDI(t->cs[1][a]), A34)), sg)); \
        v = _mm512_fmadd_ps(s, _mm512_permutexvar_ps(sw, v), _mm512_mul_ps(c, v));                 \
    } while (0)
#define ZO4_X(x)                                                                                   \
    v = _mm512_fmadd_ps(ZO_LDF(t->w[x][1]), _mm512_permutexvar_ps(x1, v),                          \
                        _mm512_mul_ps(ZO_LDF(t->w[x][0]), _mm512_permutexvar_ps(x0, v)))
    ZO4_Z(g12, g34, 2); /* Z(γ) */
    ZO4_X(0);           /* X₊₉₀ */
    ZO4_Z(g12, g34, 1); /* Z(β) */
    ZO4_X(1);           /* X₋₉₀ */
    ZO4_Z(a12, a34, 0); /* Z(α) */
#undef ZO4_Z
#undef ZO4_X
    _mm512_mask_storeu_ps(out, live, _mm512_permutexvar_ps(ZO_LDI(t->out), v));
    (void)g5, (void)a5;
}
static void zo4_avx512_c(const float *R, const float *in, float *out) { zo4_kernel(4, 0, R, in, out); }
static void zo4_avx512_n(const float *R, const float *in, float *out) { zo4_kernel(4, 1, R, in, out); }
static void zo3_avx512_c(const float *R, const float *in, float *out) { zo4_kernel(3, 0, R, in, out); }
static void zo3_avx512_n(const float *R, const float *in, float *out) { zo4_kernel(3, 1, R, in, out); }

#define ZO_FN(o, J, nocs, sfx)                                                                     \
    static void zo_avx512_##o##sfx(const float *R, const float *in, float *out)                    \
    {                                                                                              \
        zo_kernel(o, J, nocs, R, in, out);                                                         \
    }
#define ZO_FNS(o, J) ZO_FN(o, J, 0, c) ZO_FN(o, J, 1, n)
ZO_FNS(5, 3)
ZO_FNS(6, 3)
#undef ZO_FN
#undef ZO_FNS
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

static const sh__rot_one_fn_f zo_avx512[2][ZO_MAXO + 1] = {
    {NULL, NULL, NULL, zo3_avx512_c, zo4_avx512_c, zo_avx512_5c, zo_avx512_6c},
    {NULL, NULL, NULL, zo3_avx512_n, zo4_avx512_n, zo_avx512_5n, zo_avx512_6n}};
static const int zo_J[ZO_MAXO + 1] = {0, 0, 1, 2, 2, 3, 3}; /* compiled: at most */
#endif

/* The kernel for (order, convention, the rotator's kernel), or NULL (the
 * plan keeps the unrolled scalar kernel): AVX-512, orders ZO_MINO..6. */
sh__rot_one_fn_f sh__rot_zxzxz_one_f(int order, int nocs, sh_rot_kernel kernel, uint64_t *mults)
{
    if (order < ZO_MINO || order > ZO_MAXO) return NULL;
#ifdef ZO_HAVE_AVX512
    if (kernel != SH_KERNEL_AVX512) return NULL;
    pthread_once(&zo_once, zo_init);
    const int ok = order <= 4 ? zo4_ok : zo_ok[order] && zo_tabs[order].J <= zo_J[order] && (order < 6 || zoh_ok);
    if (!ok) return NULL;
    *mults = zo_mults(order, zo_J[order]);
    return zo_avx512[nocs != 0][order];
#else
    (void)kernel;
    (void)zo_init;
    return NULL;
#endif
}
