/* rot_zh.c — the `zh` method: SH rotation by zonal-harmonic factorisation
 * (Nowrouzezahrai, Simari & Fiume 2012), orders n ≤ 6 (bands 0..5), from
 * the 3×3 matrix R, no angle (precision-generic, see rot_real.h).
 *
 * Conventions (docs/CONVENTIONS.md, shlab/rotate.h): R is row-major and acts
 * on functions as g(s) = f(R⁻¹s) = f(Rᵀs); the block of band l maps f's
 * coefficients c_m to g's c'_m (index l(l+1) + m).  Derived below in the
 * `nocs` basis; `cs` as in rot_direct.c: B_cs(R) = S B_nocs(R) S with
 * S = diag((−1)^m) the SH rotation of Rz(π), so B_cs(R) = B_nocs(Rz(π) R Rz(π)),
 * and Rz(π) R Rz(π) is R with r02, r12, r20, r21 negated (no multiplication).
 *
 * Derivation.
 * (1) Addition theorem: Σ_m y_lm(d) y_lm(s) = (2l+1)/(4π) P_l(d·s).
 * (2) Take 2l+1 unit directions d_i with Y_l[i][m] = y_lm(d_i) invertible.
 *     The zonal lobes P_l(d_i·s) = (4π/(2l+1)) Σ_m Y_l[i][m] y_lm(s) then span
 *     band l, and f = Σ_m c_m y_lm = Σ_i w_i P_l(d_i·s) holds for
 *       c = (2l+1)/(4π) Y_lᵀ w,   i.e.   w = (4π/(2l+1)) Y_l⁻ᵀ c.
 * (3) Rotating a zonal lobe moves its axis only:
 *       g(s) = f(Rᵀs) = Σ_i w_i P_l(d_i·Rᵀs) = Σ_i w_i P_l((R d_i)·s),
 *     so by (1) again c'_m = (2l+1)/(4π) Σ_i w_i y_lm(R d_i), and with (2)
 *       c' = Y_l(Rd)ᵀ · (Y_l⁻ᵀ c)        (the constant cancels),
 *     Y_l(Rd)[i][m] = y_lm(R d_i).  A_l = Y_l⁻ᵀ is a fixed (2l+1)² matrix
 *     (computed once per process, below); the rotation enters only through
 *     the basis evaluated at the 2l+1 rotated directions R d_i (9
 *     multiplications each).  The block itself is B_l = Y_l(Rd)ᵀ A_l.
 * (4) Error.  With u = A_l c, c' = Y_l(Rd)ᵀ u; ‖Y_l(Rd)‖ = ‖Y_l(d)‖ (the
 *     columns of Y_l(Rd) are those of Y_l(d) times the orthogonal SH
 *     rotation), so rounding in u and in the evaluation is amplified by
 *     ‖Y_l‖‖Y_l⁻¹‖ = cond₂(Y_l): the error is about cond₂(Y_l) · (2l+1) · ε.
 *
 * Directions.  One shared nested set of 2n−1 = 11 directions: band l uses
 * the first 2l+1 (so the rotated directions and their basis values are
 * computed once for all bands).  Chosen by tools/gen_zh_dirs.c from a
 * 200-point Fibonacci spiral: greedy (band l adds the pair minimising
 * cond₂(Y_l) with the earlier directions fixed), then coordinate descent on
 * max over the bands using a direction.  cond₂(Y_l) (nocs; cs has the same
 * singular values), l = 0..5:
 *     1, 4.415, 3.251, 2.943, 4.309, 3.878
 * (test_rot_zh recomputes them with GSL's SVD and holds them ≤ 5).  A
 * separate set per band reaches 1.07, 1.80, 2.19, 3.10, 3.44 (same search),
 * i.e. at most 1.5× better, for n² rotated directions instead of 2n−1 and
 * a basis evaluation per band: not taken.  The greedy set alone (no
 * descent) had cond 19 at l = 2.  Measured against the MPFR reference
 * (test_rot_zh, 216 rotations, both conventions): blocks off by ≤ 8.6e-15
 * in double — about 4, 8, 18, 27, 39 ε at l = 1..5, as the estimate (4)
 * says (band 5: 3.88·11·ε = 9.5e-15) — and ≤ 1.5e-6 in float.  The limit
 * order 6 is the task's; the same search would give directions for higher
 * bands, whose conditioning was not measured here.
 *
 * The basis at a direction e = (x, y, z), a polynomial (no trigonometric
 * call).  nocs: y_l^{±m} = Q_l^m(z) · {C_m, S_m}(x, y), m ≥ 0, where
 *   C_m + i S_m = (x + i y)^m:  C_m = x C_{m−1} − y S_{m−1},
 *                               S_m = x S_{m−1} + y C_{m−1}   (C_1 = x, S_1 = y),
 *   Q_l^m = N_l^m P_l^m(z)/(1−z²)^{m/2},  N_l^m = √(2−δ_m0) K_l^m (CONVENTIONS.md),
 *   Q_m^m = √(1/4π) · [m > 0] √2 · Π_{k=1..m} √((2k+1)/(2k)),
 *   Q_{m+1}^m = √(2m+3) z Q_m^m,
 *   Q_l^m = a_lm z Q_{l−1}^m − b_lm Q_{l−2}^m,
 *     a_lm = √((4l²−1)/(l²−m²)),  b_lm = √((2l+1)((l−1)²−m²)/((2l−3)(l²−m²))).
 * Scaled monic: Q_l^m = g_lm Q̂_l^m with g_mm = Q_m^m, g_lm = a_lm g_{l−1,m}
 * (a_{m+1,m} = √(2m+3)), so Q̂_m = 1, Q̂_{m+1} = z and
 *   Q̂_l = z Q̂_{l−1} − β_lm Q̂_{l−2},   β_lm = b_lm / (a_lm a_{l−1,m})
 * (2 multiplications a step).  g_lm moves to the output:
 *   c'_{±m} = g_lm Σ_i (Q̂_l^m(e_i) u_i) {C_m, S_m}(e_i).
 *
 * Set (per rotation, no vector): e_i = r d_i (9), C_m, S_m for m = 2..L
 * (4 each), Q̂_l^m for l ≥ m + 2 (2 each), L = n − 1, for the 2L+1
 * directions:  (2L+1)(9 + 4(L−1) + L(L−1))  multiplications (L ≥ 1);
 * the state holds C, S and Q̂ at each direction.
 * Apply (per vector): u = A_l c (2l+1)², then per direction i < 2l+1:
 * t = Q̂_l^m u_i (m < l: 1; Q̂_l^l = 1: 0) and t·C_m, t·S_m (2), m = 0 one
 * product: 3l a direction; and the 2l+1 g_lm:
 *   Σ_{l=1..L} (2l+1)² + (2l+1)(3l+1) = Σ (2l+1)(5l+2).
 * Band 0: c'_0 = c_0.  Totals, set + apply (n = 2..6):
 *   n = 2: 27 + 21, 3: 75 + 81, 4: 161 + 200, 5: 297 + 398, 6: 495 + 695.
 * (The paper's setting keeps w of a fixed function and pays only the
 * evaluation and the second product per rotation; here every rotation gets
 * a new vector, so A_l c is paid each time.)
 *
 * rotate_many (K rotations of K vectors): the same set and apply per k in
 * one loop (`omp simd` over k), compiled for the default flags, AVX2 and
 * AVX-512 (target attributes) like rot_direct.c; no FMA contraction.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

#include <pthread.h>
#include <string.h>

SH__ROT_DECLARE_BLOCKS(zh);
SH__ROT_DECLARE_APPLY(zh);
int sh__rot_zh_set_mat_d(int, const double *, void *, uint64_t *);
int sh__rot_zh_set_mat_f(int, const float *, void *, uint64_t *);
void sh__rot_zh_state_blocks_d(int, const void *, double *);
void sh__rot_zh_state_blocks_f(int, const void *, double *);
int sh__rot_zh_rotate_many_d(int, int, sh_rot_kernel, size_t, const double *, const double *, double *,
                             uint64_t *, uint64_t *);
int sh__rot_zh_rotate_many_f(int, int, sh_rot_kernel, size_t, const float *, const float *, float *,
                             uint64_t *, uint64_t *);

#define ZH_L 5                           /* the largest band */
#define ZH_ND (2 * ZH_L + 1)             /* directions */
#define ZH_NQ ((ZH_L + 1) * (ZH_L + 2) / 2) /* (l, m ≥ 0) pairs */
#define ZH_NA 286                        /* Σ_{l ≤ 5} (2l+1)² */
#define ZH_QI(l, m) ((l) * ((l) + 1) / 2 + (m))

/* The tables, built once per process (double compilation, pthread_once):
 * directions, A_l = Y_l⁻ᵀ (nocs, row-major [i][m], band l at aoff(l) =
 * Σ_{k<l} (2k+1)²), g_lm and β_lm, in both precisions. */
typedef struct {
    double dir_d[ZH_ND][3];
    float dir_f[ZH_ND][3];
    double A_d[ZH_NA];
    float A_f[ZH_NA];
    double g_d[ZH_NQ], beta_d[ZH_NQ];
    float g_f[ZH_NQ], beta_f[ZH_NQ];
} sh__zh_tables;
const sh__zh_tables *sh__rot_zh_tables(void);
/* The nocs basis of bands 0..L at a unit direction, in long double by the
 * normalised recurrence (the tables' Y_l; test_rot_zh checks it against
 * sh_eval_dir) */
void sh__rot_zh_basis(int L, const double *e, long double *y);

#ifdef SH_REAL_FLOAT
#define ZH_TAB(x) x##_f
#else
#define ZH_TAB(x) x##_d
#endif

static inline int zh_aoff(int l) { return l * (4 * l * l - 1) / 3; } /* Σ_{k<l} (2k+1)² */

/* The per-rotation state: C_m, S_m (m = 1..L) and Q̂_l^m at each rotated
 * direction. */
typedef struct {
    sh_real C[ZH_ND][ZH_L + 1], S[ZH_ND][ZH_L + 1], Q[ZH_ND][ZH_NQ];
} SH_R(zh_state);

static int zh_check_order(int order)
{
    if (order < 1 || order > SH_ROT_ZH_MAX_ORDER)
        return sh_error(SH_EINVAL, "method zh: order %d outside 1..%d", order, SH_ROT_ZH_MAX_ORDER);
    return SH_OK;
}

static uint64_t zh_set_mults(int order)
{
    const int L = order - 1;
    return L < 1 ? 0 : (uint64_t)(2 * L + 1) * (uint64_t)(9 + 4 * (L - 1) + L * (L - 1));
}
static uint64_t zh_apply_mults(int order)
{
    uint64_t s = 0;
    for (int l = 1; l < order; l++) s += (uint64_t)(2 * l + 1) * (uint64_t)(5 * l + 2);
    return s;
}

/* r = R for nocs, Rz(π) R Rz(π) for cs (header) */
static inline __attribute__((always_inline)) void SH_R(zh_signs)(const sh_real *R, int nocs, sh_real *r)
{
#pragma GCC unroll 9
    for (int i = 0; i < 9; i++) r[i] = R[i];
    if (!nocs) r[2] = -r[2], r[5] = -r[5], r[6] = -r[6], r[7] = -r[7];
}

/* Set: the basis factors at the 2L+1 rotated directions (header). */
static inline __attribute__((always_inline)) void SH_R(zh_eval)(int order, const sh__zh_tables *T, const sh_real *r,
                                                                SH_R(zh_state) * st)
{
    const int L = order - 1;
    if (L < 1) return;
    const sh_real(*dir)[3] = (const sh_real(*)[3])T->ZH_TAB(dir);
    const sh_real *beta = T->ZH_TAB(beta);
    for (int i = 0; i < 2 * L + 1; i++) {
        const sh_real d0 = dir[i][0], d1 = dir[i][1], d2 = dir[i][2];
        const sh_real x = r[0] * d0 + r[1] * d1 + r[2] * d2;
        const sh_real y = r[3] * d0 + r[4] * d1 + r[5] * d2;
        const sh_real z = r[6] * d0 + r[7] * d1 + r[8] * d2;
        sh_real *C = st->C[i], *S = st->S[i], *Q = st->Q[i];
        C[1] = x, S[1] = y;
        for (int m = 2; m <= L; m++) {
            C[m] = x * C[m - 1] - y * S[m - 1];
            S[m] = x * S[m - 1] + y * C[m - 1];
        }
        for (int m = 0; m <= L; m++) {
            Q[ZH_QI(m, m)] = 1;
            if (m + 1 <= L) Q[ZH_QI(m + 1, m)] = z;
            for (int l = m + 2; l <= L; l++)
                Q[ZH_QI(l, m)] = z * Q[ZH_QI(l - 1, m)] - beta[ZH_QI(l, m)] * Q[ZH_QI(l - 2, m)];
        }
    }
}

/* Apply: y = R_sh x from the state (header). */
static inline __attribute__((always_inline)) void SH_R(zh_acc)(int order, const sh__zh_tables *T,
                                                               const SH_R(zh_state) * st, const sh_real *x,
                                                               sh_real *out)
{
    const sh_real *A = T->ZH_TAB(A), *g = T->ZH_TAB(g);
    out[0] = x[0];
    for (int l = 1; l < order; l++) {
        const int w = 2 * l + 1;
        const sh_real *c = x + l * l, *Al = A + zh_aoff(l);
        sh_real u[ZH_ND], acc[ZH_ND];
        for (int i = 0; i < w; i++) {
            sh_real s = 0;
            for (int m = 0; m < w; m++) s += Al[i * w + m] * c[m];
            u[i] = s;
        }
        for (int j = 0; j < w; j++) acc[j] = 0;
        for (int i = 0; i < w; i++) {
            const sh_real *C = st->C[i], *S = st->S[i], *Q = st->Q[i];
            acc[l] += Q[ZH_QI(l, 0)] * u[i];
            for (int m = 1; m < l; m++) {
                const sh_real t = Q[ZH_QI(l, m)] * u[i];
                acc[l + m] += t * C[m];
                acc[l - m] += t * S[m];
            }
            acc[l + l] += u[i] * C[l];
            acc[0] += u[i] * S[l];
        }
        sh_real *o = out + l * l;
        o[l] = g[ZH_QI(l, 0)] * acc[l];
        for (int m = 1; m <= l; m++) {
            o[l + m] = g[ZH_QI(l, m)] * acc[l + m];
            o[l - m] = g[ZH_QI(l, m)] * acc[l - m];
        }
    }
}

/* 0 if every R[i] is finite */
static inline __attribute__((always_inline)) int SH_R(zh_finite)(const sh_real *R)
{
    sh_real acc = 0;
#pragma GCC unroll 9
    for (int i = 0; i < 9; i++) acc += R[i] - R[i];
    return acc == 0;
}

int SH_R(sh__rot_zh_set_mat)(int order, const sh_real *R, void *state, uint64_t *mults)
{
    const int st = zh_check_order(order);
    if (st) return st;
    if (!SH_R(zh_finite)(R)) return sh_error(SH_EINVAL, "method zh: matrix entries must be finite");
    sh_real r[9];
    SH_R(zh_signs)(R, 0, r);
    const sh__zh_tables *T = sh__rot_zh_tables();
    switch (order) { /* each order a constant: the loops unroll */
    case 6: SH_R(zh_eval)(6, T, r, state); break;
    case 5: SH_R(zh_eval)(5, T, r, state); break;
    case 4: SH_R(zh_eval)(4, T, r, state); break;
    case 3: SH_R(zh_eval)(3, T, r, state); break;
    case 2: SH_R(zh_eval)(2, T, r, state); break;
    default: break;
    }
    if (mults) *mults += zh_set_mults(order);
    return SH_OK;
}

int SH_R(sh__rot_zh_set)(int order, const sh_rotation *rot, const void *tables, void *state, uint64_t *mults)
{
    sh_real R[9];
    for (int i = 0; i < 9; i++) R[i] = (sh_real)rot->R[i];
    return SH_R(sh__rot_zh_set_mat)(order, R, state, mults);
}

void SH_R(sh__rot_zh_apply)(int order, const void *tables, const void *state, const sh_real *in, sh_real *out,
                            void *work, uint64_t *mults)
{
    const sh__zh_tables *T = sh__rot_zh_tables();
    switch (order) { /* each order a constant: the loops unroll */
    case 6: SH_R(zh_acc)(6, T, state, in, out); break;
    case 5: SH_R(zh_acc)(5, T, state, in, out); break;
    case 4: SH_R(zh_acc)(4, T, state, in, out); break;
    case 3: SH_R(zh_acc)(3, T, state, in, out); break;
    case 2: SH_R(zh_acc)(2, T, state, in, out); break;
    default: out[0] = in[0]; break;
    }
    if (mults) *mults += zh_apply_mults(order);
}

/* The blocks (cs, layout of sh_rot_block_offset) of a state: column j of
 * band l is the apply of the unit vector e_j. */
static void SH_R(zh_state_blocks_r)(int order, const void *state, sh_real *blocks, uint64_t *mults)
{
    const sh__zh_tables *T = sh__rot_zh_tables();
    sh_real x[36], y[36];
    const int n = order * order;
    for (int i = 0; i < n; i++) x[i] = 0;
    blocks[0] = 1;
    for (int l = 1; l < order; l++) {
        const int w = 2 * l + 1;
        for (int j = 0; j < w; j++) {
            x[l * l + j] = 1;
            SH_R(zh_acc)(l + 1, T, state, x, y);
            x[l * l + j] = 0;
            for (int a = 0; a < w; a++) blocks[sh_rot_block_offset(l) + (size_t)a * w + j] = y[l * l + a];
        }
        if (mults) *mults += (uint64_t)w * zh_apply_mults(l + 1);
    }
}

void SH_R(sh__rot_zh_state_blocks)(int order, const void *state, double *blocks)
{
    sh_real b[286];
    SH_R(zh_state_blocks_r)(order, state, b, NULL);
    for (size_t i = 0; i < sh_rot_block_offset(order); i++) blocks[i] = b[i];
}

int SH_R(sh__rot_zh_blocks)(int order, const sh_rotation *rot, const void *tables, sh_real *blocks, void *work,
                            uint64_t *mults)
{
    const int st = zh_check_order(order);
    if (st) return st;
    SH_R(zh_state) s;
    sh_real R[9], r[9];
    for (int i = 0; i < 9; i++) R[i] = (sh_real)rot->R[i];
    if (!SH_R(zh_finite)(R)) return sh_error(SH_EINVAL, "method zh: matrix entries must be finite");
    SH_R(zh_signs)(R, 0, r);
    SH_R(zh_eval)(order, sh__rot_zh_tables(), r, &s);
    if (mults) *mults += zh_set_mults(order);
    SH_R(zh_state_blocks_r)(order, &s, blocks, mults);
    return SH_OK;
}

/* One rotation k of a structure-of-arrays batch (stride K). */
static inline __attribute__((always_inline)) void SH_R(zh_one)(int order, int nocs, const sh__zh_tables *T, size_t K,
                                                               size_t k, const sh_real *R, const sh_real *in,
                                                               sh_real *out)
{
    sh_real Rk[9], r[9], x[36], y[36];
    SH_R(zh_state) s;
#pragma GCC unroll 9
    for (int j = 0; j < 9; j++) Rk[j] = R[(size_t)j * K + k];
    for (int i = 0; i < order * order; i++) x[i] = in[(size_t)i * K + k];
    SH_R(zh_signs)(Rk, nocs, r);
    SH_R(zh_eval)(order, T, r, &s);
    SH_R(zh_acc)(order, T, &s, x, y);
    for (int i = 0; i < order * order; i++) out[(size_t)i * K + k] = y[i];
}

#define ZH_MANY(ORDER, NOCS, LANES)                                                                \
    do {                                                                                           \
        SH_PRAGMA(omp simd simdlen(LANES))                                                         \
        for (size_t k = 0; k < K; k++) SH_R(zh_one)(ORDER, NOCS, T, K, k, R, in, out);            \
    } while (0)
#define ZH_MANY_FN(NAME, TARGET, LANES)                                                            \
    TARGET static int NAME(int order, int nocs, size_t K, const sh_real *R, const sh_real *in,     \
                           sh_real *out)                                                           \
    {                                                                                              \
        const sh__zh_tables *T = sh__rot_zh_tables();                                              \
        sh_real acc = 0;                                                                           \
        SH_PRAGMA(omp simd simdlen(LANES) reduction(+ : acc))                                      \
        for (size_t i = 0; i < 9 * K; i++) acc += R[i] - R[i];                                     \
        if (acc != 0) return 0;                                                                    \
        switch (order * 2 + (nocs != 0)) {                                                         \
        case 2:                                                                                    \
        case 3:                                                                                    \
            for (size_t k = 0; k < K; k++) out[k] = in[k];                                         \
            break;                                                                                 \
        case 4: ZH_MANY(2, 0, LANES); break;                                                       \
        case 5: ZH_MANY(2, 1, LANES); break;                                                       \
        case 6: ZH_MANY(3, 0, LANES); break;                                                       \
        case 7: ZH_MANY(3, 1, LANES); break;                                                       \
        case 8: ZH_MANY(4, 0, LANES); break;                                                       \
        case 9: ZH_MANY(4, 1, LANES); break;                                                       \
        case 10: ZH_MANY(5, 0, LANES); break;                                                      \
        case 11: ZH_MANY(5, 1, LANES); break;                                                      \
        case 12: ZH_MANY(6, 0, LANES); break;                                                      \
        case 13: ZH_MANY(6, 1, LANES); break;                                                      \
        default: break; /* the rotator refuses other orders */                                     \
        }                                                                                          \
        return 1;                                                                                  \
    }
ZH_MANY_FN(SH_R(zh_many_base), , SH_SIMD_LANES16)
#if defined(__x86_64__) && defined(__GNUC__)
#define ZH_HAVE_WIDE 1
ZH_MANY_FN(SH_R(zh_many_avx2), __attribute__((target("avx2"))), 2 * SH_SIMD_LANES16)
ZH_MANY_FN(SH_R(zh_many_avx512), __attribute__((target("avx512f,avx512vl"))), 4 * SH_SIMD_LANES16)
#endif

int SH_R(sh__rot_zh_rotate_many)(int order, int nocs, sh_rot_kernel kernel, size_t K, const sh_real *R,
                                 const sh_real *in, sh_real *out, uint64_t *set_mults, uint64_t *apply_mults)
{
    int ok;
#ifdef ZH_HAVE_WIDE
    if (kernel == SH_KERNEL_AVX512) ok = SH_R(zh_many_avx512)(order, nocs, K, R, in, out);
    else if (kernel == SH_KERNEL_AVX2) ok = SH_R(zh_many_avx2)(order, nocs, K, R, in, out);
    else
#endif
        ok = SH_R(zh_many_base)(order, nocs, K, R, in, out);
    if (!ok) return sh_error(SH_EINVAL, "method zh: a rotation has an entry that is not finite");
    if (set_mults) *set_mults += zh_set_mults(order);
    if (apply_mults) *apply_mults += zh_apply_mults(order);
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
/* The directions (tools/gen_zh_dirs 5 200: points 157, 118, 107, 117, 33,
 * 164, 0, 65, 7, 28, 61 of a 200-point Fibonacci spiral z_c = 1 −
 * (2c+1)/200, φ_c = c·π(3 − √5)); band l uses the first 2l+1. */
static const double zh_dirs[ZH_ND][3] = {
    {0.80234622012382684, -0.16004856467025169, -0.57500000000000007},
    {0.88390899021840419, 0.42951123036665889, -0.18500000000000008},
    {0.68427620001191314, -0.72535583136641024, -0.074999999999999956},
    {-0.36230969958512588, -0.91548166643933182, -0.17500000000000007},
    {-0.59047166615180713, -0.45729444723493928, 0.66500000000000004},
    {-0.4780773643057219, -0.59616862860980369, -0.64500000000000013},
    {0.099874921777190678, 0, 0.995},
    {0.44071471799483997, -0.82870111460207951, 0.34500000000000003},
    {-0.1751295073195121, -0.33720120946702559, 0.92500000000000004},
    {-0.23662026456499977, -0.65786461403330498, 0.71500000000000008},
    {-0.28479254688081429, 0.8778771014448089, 0.38500000000000001},
};

static long double zh_a(int l, int m) { return sqrtl((4.0L * l * l - 1) / ((long double)l * l - (long double)m * m)); }
static long double zh_b(int l, int m)
{
    return sqrtl((2.0L * l + 1) * ((long double)(l - 1) * (l - 1) - (long double)m * m) /
                 ((2.0L * l - 3) * ((long double)l * l - (long double)m * m)));
}
static long double zh_qmm(int m)
{
    long double q = 1 / sqrtl(4 * 3.14159265358979323846264338327950288L);
    if (m > 0) q *= sqrtl(2.0L);
    for (int k = 1; k <= m; k++) q *= sqrtl((2.0L * k + 1) / (2.0L * k));
    return q;
}

void sh__rot_zh_basis(int L, const double *e, long double *y)
{
    const long double x = e[0], yy = e[1], z = e[2];
    long double C[ZH_L + 2], S[ZH_L + 2];
    C[0] = 1, S[0] = 0;
    for (int m = 1; m <= L; m++) C[m] = x * C[m - 1] - yy * S[m - 1], S[m] = x * S[m - 1] + yy * C[m - 1];
    for (int m = 0; m <= L; m++) {
        long double q2 = 0, q1 = zh_qmm(m);
        for (int l = m; l <= L; l++) {
            long double q;
            if (l == m) q = q1;
            else if (l == m + 1) q = sqrtl(2.0L * m + 3) * z * q1;
            else q = zh_a(l, m) * z * q1 - zh_b(l, m) * q2;
            if (l > m) q2 = q1, q1 = q;
            if (m == 0) y[l * (l + 1)] = q;
            else y[l * (l + 1) + m] = q * C[m], y[l * (l + 1) - m] = q * S[m];
        }
    }
}

/* Y⁻¹ of a w×w matrix by Gauss–Jordan with partial pivoting, long double */
static void zh_invert(int w, long double *Y, long double *Yi)
{
    for (int i = 0; i < w; i++)
        for (int j = 0; j < w; j++) Yi[i * w + j] = i == j;
    for (int c = 0; c < w; c++) {
        int p = c;
        for (int i = c + 1; i < w; i++)
            if (fabsl(Y[i * w + c]) > fabsl(Y[p * w + c])) p = i;
        for (int j = 0; j < w; j++) {
            long double t = Y[c * w + j];
            Y[c * w + j] = Y[p * w + j], Y[p * w + j] = t;
            t = Yi[c * w + j];
            Yi[c * w + j] = Yi[p * w + j], Yi[p * w + j] = t;
        }
        const long double d = Y[c * w + c];
        for (int j = 0; j < w; j++) Y[c * w + j] /= d, Yi[c * w + j] /= d;
        for (int i = 0; i < w; i++) {
            if (i == c) continue;
            const long double f = Y[i * w + c];
            for (int j = 0; j < w; j++) Y[i * w + j] -= f * Y[c * w + j], Yi[i * w + j] -= f * Yi[c * w + j];
        }
    }
}

static sh__zh_tables zh_tab;
static pthread_once_t zh_once = PTHREAD_ONCE_INIT;

static void zh_build(void)
{
    sh__zh_tables *T = &zh_tab;
    for (int i = 0; i < ZH_ND; i++)
        for (int k = 0; k < 3; k++) T->dir_d[i][k] = zh_dirs[i][k], T->dir_f[i][k] = (float)zh_dirs[i][k];
    for (int m = 0; m <= ZH_L; m++) {
        long double g = zh_qmm(m);
        for (int l = m; l <= ZH_L; l++) {
            long double beta = 0;
            if (l == m + 1) g *= sqrtl(2.0L * m + 3);
            if (l >= m + 2) {
                const long double al1 = l - 1 == m + 1 ? sqrtl(2.0L * m + 3) : zh_a(l - 1, m);
                beta = zh_b(l, m) / (zh_a(l, m) * al1);
                g *= zh_a(l, m);
            }
            T->g_d[ZH_QI(l, m)] = (double)g, T->g_f[ZH_QI(l, m)] = (float)g;
            T->beta_d[ZH_QI(l, m)] = (double)beta, T->beta_f[ZH_QI(l, m)] = (float)beta;
        }
    }
    long double yd[ZH_ND][(ZH_L + 1) * (ZH_L + 1)];
    for (int i = 0; i < ZH_ND; i++) sh__rot_zh_basis(ZH_L, zh_dirs[i], yd[i]);
    for (int l = 0; l <= ZH_L; l++) {
        const int w = 2 * l + 1;
        long double Y[ZH_ND * ZH_ND], Yi[ZH_ND * ZH_ND];
        for (int i = 0; i < w; i++)
            for (int m = 0; m < w; m++) Y[i * w + m] = yd[i][l * l + m];
        zh_invert(w, Y, Yi);
        for (int i = 0; i < w; i++)
            for (int m = 0; m < w; m++) { /* A[i][m] = (Y⁻ᵀ)[i][m] = (Y⁻¹)[m][i] */
                T->A_d[zh_aoff(l) + i * w + m] = (double)Yi[m * w + i];
                T->A_f[zh_aoff(l) + i * w + m] = (float)Yi[m * w + i];
            }
    }
}

const sh__zh_tables *sh__rot_zh_tables(void)
{
    pthread_once(&zh_once, zh_build);
    return &zh_tab;
}

/* the directions for the tests (test_rot_zh: condition numbers) */
const double (*sh__rot_zh_directions(void))[3] { return zh_dirs; }

static size_t zh_state_bytes(int order) { return sizeof(zh_state_d); }
static size_t zh_work(int order) { return 0; }
const sh__rot_ops sh__rot_zh_ops = {
    .name = "zh",
    .max_order = SH_ROT_ZH_MAX_ORDER,
    .work_bytes = zh_work,
    .state_bytes = zh_state_bytes,
    .set_d = sh__rot_zh_set_d,
    .set_f = sh__rot_zh_set_f,
    .blocks_d = sh__rot_zh_blocks_d,
    .blocks_f = sh__rot_zh_blocks_f,
    .apply_d = sh__rot_zh_apply_d,
    .apply_f = sh__rot_zh_apply_f,
    .matrix_only = 1,
    .set_mat_d = sh__rot_zh_set_mat_d,
    .set_mat_f = sh__rot_zh_set_mat_f,
    .rotate_many_d = sh__rot_zh_rotate_many_d,
    .rotate_many_f = sh__rot_zh_rotate_many_f,
    .state_blocks_d = sh__rot_zh_state_blocks_d,
    .state_blocks_f = sh__rot_zh_state_blocks_f,
};
#endif
