/* rot_fast.c — the unrolled rotation kernels (zxzxz, taylor1, taylor1.5,
 * taylor2 for orders ≤ SH_UNROLLED_MAX_ORDER) and their drivers: one
 * rotation from a 3×3 matrix or a quaternion without trigonometric calls,
 * one rotation applied to K vectors, K rotations applied to K vectors.
 *
 * Compiled once per precision and per variant (rot_simd.h; the Makefile's
 * FAST_VARIANTS): the plain object has one lane (shk_t = sh_real), the SIMD
 * objects have 2 to 16 lanes, each lane a rotation and a vector, the arrays
 * laid out as structure of arrays (coefficient i of lane k at p[i·K + k]).
 * Each object exports one table, sh__rot_fast_<variant>_<d|f>
 * (rot_internal.h), which the plan picks when it is created
 * (rotation_plan.c: compiled in, and the CPU runs it).
 *
 * References
 *  [1] docs/CONVENTIONS.md: R = Rz(α) Ry(β) Rz(γ) (ZYZ, active),
 *        R = [[cαcβcγ − sαsγ, −cαcβsγ − sαcγ, cαsβ],
 *             [sαcβcγ + cαsγ, −sαcβsγ + cαcγ, sαsβ],
 *             [−sβcγ,          sβsγ,            cβ ]].
 *  [2] the quaternion of Rz(θ) is (cos θ/2, 0, 0, sin θ/2), of Ry(θ)
 *      (cos θ/2, 0, sin θ/2, 0); R = Rz(α)Ry(β)Rz(γ) ↔ q = qz(α) qy(β) qz(γ).
 *  [3] rotation.c (sh_euler_from_matrix): the same well-conditioned entries,
 *      there for atan2.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_simd.h"

#define SHK_FN_T SH_R(sh__fast_fn)
#include "rotate/rot_unrolled_gen.h"

#include <math.h>

#if SH_UNROLLED_MAX_ORDER > SH__FAST_MAXO
#error "rot_unrolled_gen.h has more orders than SH__FAST_MAXO"
#endif

/* ---- the rotation's par from a matrix, without trigonometric calls --------
 *
 * From [1]: cβ = R22 and
 *   sβ e^{iα} = R02 + i R12,                                              (a)
 *   (1 + cβ) e^{i(α+γ)} = (R00 + R11) + i (R10 − R01),                    (b)
 *   (1 − cβ) e^{i(α−γ)} = (R11 − R00) − i (R10 + R01).                    (c)
 * (b) and (c) follow from the sums and differences of the upper-left 2×2
 * block, e.g. R00 + R11 = cβ(cαcγ − sαsγ) + (cαcγ − sαsγ).  So
 *   sβ = |R02 + i R12|,  e^{iα} = (R02 + i R12)/sβ,
 * and γ from (b) when cβ ≥ 0 (its modulus 1 + cβ ≥ 1) or from (c) when
 * cβ < 0 (1 − cβ > 1): e^{iγ} = e^{i(α+γ)} e^{−iα} = e^{iα} e^{−i(α−γ)}.
 * Near β = 0 (or π) e^{iα} from (a) is ill-conditioned (relative error ε/sβ)
 * but R then depends on α+γ (α−γ) alone, which (b) ((c)) gives to ε, and
 * γ is taken relative to the same α, so its error cancels in the rotation
 * (the argument of rotation.c).  At sβ = 0 exactly — the gimbal cases
 * β = 0, π, where only α ± γ is defined — α = 0 and γ = α ± γ.  cos and sin
 * of the multiple angles then come from these by the Chebyshev recurrence
 * (the kernels).  Cost: 12 multiplications, 2 square roots, 2 divisions.
 * R must be a rotation (orthonormal, det +1); it is not checked here.
 * For the Taylor kernels computed in double also for float rotations
 * (shk_d): float arithmetic here puts 2–3 float ulps into cos γ, sin γ,
 * which they amplify near β = π past the golden fixtures' tolerance; the
 * exact kernels take it in float. */
#define SHK_PAR_MATRIX(NAME, T, M, LD, SPLAT, SQRT, SEL)                                          \
    static inline void NAME(const sh_real *R, size_t KR, T par[7])                                 \
    {                                                                                              \
        const T r00 = LD(R, 0, KR), r01 = LD(R, 1, KR), r02 = LD(R, 2, KR);                        \
        const T r10 = LD(R, 3, KR), r11 = LD(R, 4, KR), r12 = LD(R, 5, KR), r22 = LD(R, 8, KR);   \
        const T one = SPLAT(1), zero = SPLAT(0);                                                   \
        const T s2 = r02 * r02 + r12 * r12, sb = SQRT(s2);                                         \
        const M has = s2 > zero; /* sβ ≠ 0: α from (a), else α = 0 */                              \
        const T inv = SEL(has, one / SEL(has, sb, one), zero);                                     \
        const T ca = r02 * inv + SEL(has, zero, one), sa = r12 * inv;                              \
        const M up = r22 >= zero; /* (b), else (c) */                                              \
        const T p = SEL(up, r00 + r11, r11 - r00), q = SEL(up, r10 - r01, -(r10 + r01));           \
        const T nrm = one / SQRT(p * p + q * q);                                                   \
        const T cs = p * nrm, ss = q * nrm; /* e^{i(α+γ)}, or e^{i(α−γ)} */                        \
        const T t = ss * ca - cs * sa;                                                             \
        par[0] = ca, par[1] = sa, par[2] = r22, par[3] = sb;                                       \
        par[4] = cs * ca + ss * sa;                                                                \
        par[5] = SEL(up, t, -t);                                                                   \
        par[6] = zero;                                                                             \
    }
/* in double lanes (every variant), and in the kernel's own lanes (float:
 * enough for the exact methods, 1–2 float ulps in the angles) */
SHK_PAR_MATRIX(shk_par_matrix, shk_d, shk_dm, SHK_DLD, SHK_DSPLAT, SHK_DSQRT, SHK_DSEL)
#ifdef SH_REAL_FLOAT
SHK_PAR_MATRIX(shk_par_matrix_r, shk_t, shk_m, SHK_LD, SHK_SPLAT, SHK_SQRT, SHK_SEL)
#endif
#undef SHK_PAR_MATRIX

/* ---- the same from a quaternion q = (w, x, y, z), unit or not ------------
 *
 * From [2]: q = qz(α) qy(β) qz(γ) =
 *   (cos(β/2) cos((α+γ)/2), −sin(β/2) sin((α−γ)/2),
 *    sin(β/2) cos((α−γ)/2),  cos(β/2) sin((α+γ)/2)),
 * so with A = w + iz = cos(β/2) e^{i(α+γ)/2} and B = y − ix =
 * sin(β/2) e^{i(α−γ)/2} (both products of half angles):
 *   cβ = (|A|² − |B|²)/n,  sβ = 2|A||B|/n   (n = |q|² = |A|² + |B|²),
 *   e^{iα} = AB/(|A||B|) = ((wy + zx) + i(zy − wx))/(|A||B|),
 *   e^{iγ} = AB̄/(|A||B|) = ((wy − zx) + i(wx + zy))/(|A||B|).
 * A product and a modulus, never a difference of nearly equal numbers:
 * near β = 0 the direction of B is ill-defined, but α + γ = arg A², which is
 * all R depends on there.  |B| = 0 (β = 0): α = 0, e^{iγ} = A²/|A|²;
 * |A| = 0 (β = π): α = 0, e^{iγ} = B̄²/|B|².  q and −q give the same par.
 * Cost: 18 multiplications, 1 square root, 3 divisions. */
static inline void shk_par_quat(const sh_real *Q, size_t KQ, shk_d par[7])
{
    const shk_d w = SHK_DLD(Q, 0, KQ), x = SHK_DLD(Q, 1, KQ), y = SHK_DLD(Q, 2, KQ), z = SHK_DLD(Q, 3, KQ);
    const shk_d one = SHK_DSPLAT(1), zero = SHK_DSPLAT(0);
    const shk_d ww = w * w, zz = z * z, xx = x * x, yy = y * y;
    const shk_d a2 = ww + zz, b2 = xx + yy, in2 = one / (a2 + b2);
    const shk_d ab = SHK_DSQRT(a2 * b2);
    const shk_dm has = ab > zero;
    const shk_d iab = SHK_DSEL(has, one / SHK_DSEL(has, ab, one), zero);
    const shk_d wy = w * y, zx = z * x, zy = z * y, wx = w * x;
    /* the degenerate cases: A²/|A|² (|B| = 0) or B̄²/|B|² (|A| = 0) */
    const shk_dm up = a2 >= b2;
    const shk_d dn = one / SHK_DSEL(up, a2, b2);
    const shk_d dc = SHK_DSEL(up, ww - zz, yy - xx) * dn;
    const shk_d ds = SHK_DSEL(up, w, x) * SHK_DSEL(up, z, y) * (dn + dn);
    par[0] = (wy + zx) * iab + SHK_DSEL(has, zero, one);
    par[1] = (zy - wx) * iab;
    par[2] = (a2 - b2) * in2;
    par[3] = (ab + ab) * in2;
    par[4] = (wy - zx) * iab + SHK_DSEL(has, zero, dc);
    par[5] = (wx + zy) * iab + SHK_DSEL(has, zero, ds);
    par[6] = zero;
}

/* β = atan2(sin β, cos β) ∈ [0, π] (sin β ≥ 0): the Taylor kernels need the
 * angle itself.  In double, libm's atan2, lane by lane.  In float, by
 * Abramowitz & Stegun 4.4.49 (Hastings): atan x = x(1 + a₂x² + … + a₁₆x¹⁶)
 * + ε, |ε| ≤ 2·10⁻⁸ on [0, 1] (a quarter of a float ulp at 1), evaluated
 * in double on x = min(s, |c|)/max(s, |c|), then β = atan x, π/2 − atan x,
 * or π minus those for c < 0.  Cost: 10 multiplications, 1 division. */
#ifdef SH_REAL_FLOAT
static inline shk_d shk_beta(shk_d s, shk_d c)
{
    const shk_d zero = SHK_DSPLAT(0), one = SHK_DSPLAT(1);
    const shk_dm cpos = c >= zero;
    const shk_d ac = SHK_DSEL(cpos, c, -c);
    const shk_dm swap = s > ac;
    const shk_d num = SHK_DSEL(swap, ac, s), den = SHK_DSEL(swap, s, ac);
    const shk_d x = num / SHK_DSEL(den > zero, den, one), x2 = x * x;
    const shk_d a = ((((((((0.0028662257 * x2 - 0.0161657367) * x2 + 0.0429096138) * x2 - 0.0752896400) * x2 +
                          0.1065626393) * x2 - 0.1420889944) * x2 + 0.1999355085) * x2 - 0.3333314528) * x2 + 1) * x;
    const shk_d t = SHK_DSEL(swap, 1.5707963267948966 - a, a);
    return SHK_DSEL(cpos, t, 3.1415926535897931 - t);
}
#define SH__BETA_MULTS 10
#else
#define SH__BETA_MULTS 0
#endif

/* par as the kernels read it: rounded to sh_real, β if need_beta (lane by
 * lane in double), nocs = S·R_cs·S with S = diag((−1)^m) = Z(π), and
 * Rz(π)Ry(β)Rz(π) = Ry(−β): the cs kernel with sin β and β negated —
 * exact, no pass over the vectors. */
/* ivanic's par: the matrix itself (from a quaternion: its matrix,
 * normalised by |q|², 19 multiplications and 1 division); nocs = Rz(π)·R·Rz(π) (as above), which negates R02,
 * R12, R20, R21 */
static inline void shk_par_ivanic(const sh_real *rot, size_t KR, int quat, int nocs, sh_real *par, size_t KP)
{
    shk_d R[9];
    if (quat) {
        const shk_d w = SHK_DLD(rot, 0, KR), x = SHK_DLD(rot, 1, KR), y = SHK_DLD(rot, 2, KR), z = SHK_DLD(rot, 3, KR);
        const shk_d ww = w * w, xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z;
        const shk_d wx = w * x, wy = w * y, wz = w * z;
        const shk_d s = SHK_DSPLAT(2) / (ww + xx + yy + zz), one = SHK_DSPLAT(1);
        R[0] = one - s * (yy + zz), R[1] = s * (xy - wz), R[2] = s * (xz + wy);
        R[3] = s * (xy + wz), R[4] = one - s * (xx + zz), R[5] = s * (yz - wx);
        R[6] = s * (xz - wy), R[7] = s * (yz + wx), R[8] = one - s * (xx + yy);
    } else {
        for (int j = 0; j < 9; j++) R[j] = SHK_DLD(rot, j, KR);
    }
    if (nocs) R[2] = -R[2], R[5] = -R[5], R[6] = -R[6], R[7] = -R[7];
    for (int j = 0; j < 9; j++) SHK_DST(par, j, KP, R[j]);
}

static inline void shk_par(const sh_real *rot, size_t KR, int quat, int need_beta, int nocs,
                           sh_real *par, size_t KP)
{
#ifdef SH_REAL_FLOAT
    if (!quat && !need_beta) { /* zxzxz: float lanes (rot_simd.h) suffice */
        shk_t pr[7];
        shk_par_matrix_r(rot, KR, pr);
        if (nocs) pr[3] = -pr[3];
        for (int j = 0; j < 7; j++) SHK_ST(par, j, KP, pr[j]);
        return;
    }
#endif
    shk_d pd[7];
    if (quat) shk_par_quat(rot, KR, pd);
    else shk_par_matrix(rot, KR, pd);
#ifdef SH_REAL_FLOAT
    if (need_beta) pd[6] = shk_beta(pd[3], pd[2]);
    if (nocs) pd[3] = -pd[3], pd[6] = -pd[6];
    for (int j = 0; j < 7; j++) SHK_DST(par, j, KP, pd[j]);
#else
    for (int j = 0; j < 7; j++) SHK_DST(par, j, KP, pd[j]);
    if (need_beta)
        for (size_t i = 0; i < (size_t)SHK_LANES; i++) par[6 * KP + i] = atan2(par[3 * KP + i], par[2 * KP + i]);
    if (nocs)
        for (size_t i = 0; i < (size_t)SHK_LANES; i++) par[3 * KP + i] = -par[3 * KP + i], par[6 * KP + i] = -par[6 * KP + i];
#endif
}

/* K rotations of K vectors, SHK_LANES at a time; a last partial group is
 * copied into padded buffers (identity rotations, zero vectors). */
static void fast_rotate(int meth, int order, int nocs, size_t K, const sh_real *rot, int quat,
                        const sh_real *in, sh_real *out)
{
    const SHK_FN_T f = unrolled_table[meth][order];
    const int W = SHK_LANES, nr = quat ? 4 : 9, nc = order * order;
    sh_real par[SH__PAR_N * SHK_LANES];
    size_t k = 0;
#if SHK_LANES == 1
    /* one lane: each rotation and vector gathered into contiguous buffers */
    for (; k < K; k++) {
        sh_real rb[9], xb[SH__FAST_MAXO * SH__FAST_MAXO];
        for (int r = 0; r < nr; r++) rb[r] = rot[(size_t)r * K + k];
        for (int c = 0; c < nc; c++) xb[c] = in[(size_t)c * K + k];
        if (meth == SH__FAST_IVANIC) shk_par_ivanic(rb, 1, quat, nocs, par, 1);
        else shk_par(rb, 1, quat, meth != SH__FAST_ZXZXZ, nocs, par, 1);
        f(par, 1, xb, xb, 1);
        for (int c = 0; c < nc; c++) out[(size_t)c * K + k] = xb[c];
    }
#endif
    for (; k + (size_t)W <= K; k += (size_t)W) {
        if (meth == SH__FAST_IVANIC) shk_par_ivanic(rot + k, K, quat, nocs, par, (size_t)W);
        else shk_par(rot + k, K, quat, meth != SH__FAST_ZXZXZ, nocs, par, (size_t)W);
        f(par, (size_t)W, in + k, out + k, K);
    }
#if SHK_LANES > 1
    if (k < K) {
        const int nt = (int)(K - k);
        sh_real rb[9 * SHK_LANES], xb[SH__FAST_MAXO * SH__FAST_MAXO * SHK_LANES];
        static const sh_real id_m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, id_q[4] = {1, 0, 0, 0};
        for (int r = 0; r < nr; r++)
            for (int i = 0; i < W; i++) rb[r * W + i] = i < nt ? rot[(size_t)r * K + k + (size_t)i] : (quat ? id_q : id_m)[r];
        for (int c = 0; c < nc; c++)
            for (int i = 0; i < W; i++) xb[c * W + i] = i < nt ? in[(size_t)c * K + k + (size_t)i] : 0;
        if (meth == SH__FAST_IVANIC) shk_par_ivanic(rb, (size_t)W, quat, nocs, par, (size_t)W);
        else shk_par(rb, (size_t)W, quat, meth != SH__FAST_ZXZXZ, nocs, par, (size_t)W);
        f(par, (size_t)W, xb, xb, (size_t)W);
        for (int c = 0; c < nc; c++)
            for (int i = 0; i < nt; i++) out[(size_t)c * K + k + (size_t)i] = xb[c * W + i];
    }
#endif
}

/* one rotation (par) applied to K vectors: par spread over the lanes */
static void fast_many(int meth, int order, const sh_real *par1, size_t K, const sh_real *in,
                      sh_real *out)
{
    const SHK_FN_T f = unrolled_table[meth][order];
    const int W = SHK_LANES;
    sh_real par[SH__PAR_N * SHK_LANES];
    for (int j = 0; j < SH__PAR_N; j++)
        for (int i = 0; i < W; i++) par[j * W + i] = par1[j];
    size_t k = 0;
#if SHK_LANES == 1
    for (; k < K; k++) {
        sh_real xb[SH__FAST_MAXO * SH__FAST_MAXO];
        for (int c = 0; c < order * order; c++) xb[c] = in[(size_t)c * K + k];
        f(par, 1, xb, xb, 1);
        for (int c = 0; c < order * order; c++) out[(size_t)c * K + k] = xb[c];
    }
#endif
    for (; k + (size_t)W <= K; k += (size_t)W) f(par, (size_t)W, in + k, out + k, K);
#if SHK_LANES > 1
    if (k < K) {
        const int nt = (int)(K - k), nc = order * order;
        sh_real xb[SH__FAST_MAXO * SH__FAST_MAXO * SHK_LANES];
        for (int c = 0; c < nc; c++)
            for (int i = 0; i < W; i++) xb[c * W + i] = i < nt ? in[(size_t)c * K + k + (size_t)i] : 0;
        f(par, (size_t)W, xb, xb, (size_t)W);
        for (int c = 0; c < nc; c++)
            for (int i = 0; i < nt; i++) out[(size_t)c * K + k + (size_t)i] = xb[c * W + i];
    }
#endif
}

#if SHK_LANES == 1
/* one rotation from its matrix: zxzxz's and the Taylor kernels' par */
static void fast_par_matrix(const sh_real *R, int need_beta, sh_real *par)
{
#ifdef SH_REAL_FLOAT
    if (!need_beta) {
        shk_par_matrix_r(R, 1, par);
        return;
    }
#endif
    shk_d pd[7];
    shk_par_matrix(R, 1, pd);
#ifdef SH_REAL_FLOAT
    if (need_beta) pd[6] = shk_beta(pd[3], pd[2]);
#else
    if (need_beta) pd[6] = atan2(pd[3], pd[2]);
#endif
#pragma GCC unroll 7
    for (int j = 0; j < 7; j++) par[j] = (sh_real)pd[j];
}
#endif

#define SHK_STR_(x) #x
#define SHK_STR(x) SHK_STR_(x)
const SH_R(sh__rot_fast) SHK_SYM(sh__rot_fast) = {
    .name = SHK_STR(SHK_VARIANT),
    .lanes = SHK_LANES,
    .max_order = SH_UNROLLED_MAX_ORDER,
    .fn = unrolled_table,
    .mults = unrolled_mults,
    .rotate = fast_rotate,
    .many = fast_many,
#if SHK_LANES == 1
    .par_matrix = fast_par_matrix,
#endif
};

#ifdef SHK_IS_BASE
/* ---- one rotation, for the plan (the plain object only) ----------------- */
void SH_R(sh__rot_par_matrix)(const sh_real *R, int need_beta, sh_real *par)
{
    fast_par_matrix(R, need_beta, par);
}

void SH_R(sh__rot_par_quat)(const sh_real *q, int need_beta, sh_real *par)
{
    shk_par(q, 1, 1, need_beta, 0, par, 1);
}

/* From the Euler angles: libm's cos and sin of each (in the plan's precision,
 * as the loop kernels' sh__rot_multiple_angles seeds them). */
#ifndef SH_REAL_FLOAT
void sh__rot_quat_matrix(const double q[4], double R[9]) { shk_par_ivanic(q, 1, 1, 0, R, 1); }
#endif

void SH_R(sh__rot_par_euler)(const sh_rotation *rot, sh_real *par)
{
    const sh_real a = (sh_real)rot->alpha, b = (sh_real)rot->beta, g = (sh_real)rot->gamma;
    par[0] = SH_COS(a), par[1] = SH_SIN(a);
    par[2] = SH_COS(b), par[3] = SH_SIN(b);
    par[4] = SH_COS(g), par[5] = SH_SIN(g);
    par[6] = b;
}
#endif
