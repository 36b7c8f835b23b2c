/* rot_choi.c — the `choi` method: the rotation matrices of the COMPLEX
 * spherical harmonics by recursion in l (band l from band l−1 and band 1),
 * in complex arithmetic (explicit re/im pairs), from the 3×3 matrix alone,
 * then converted to the real basis.  Independent of the real Ivanic recursion
 * and of the Euler angles.
 *
 * References
 *  [1] C. H. Choi, J. Ivanic, M. S. Gordon, K. Ruedenberg, "Rapid and stable
 *      determination of rotation matrices between spherical harmonics by
 *      direct recursion", J. Chem. Phys. 111 (1999) 8825, Sec. II–III: band 1
 *      from the Cartesian matrix, band l by coupling band 1 with band l−1
 *      through Clebsch-Gordan coefficients.  (The paper itself was not at
 *      hand; the formulas below are derived here from [2] and
 *      verified numerically in tests/rotate/test_rot_choi_blanco.c, so no equation
 *      number of [1] is quoted.)
 *  [2] Edmonds, Angular Momentum in Quantum Mechanics, eq. (4.3.1)/(4.6.5):
 *      D^{j1}_{m1'm1} D^{j2}_{m2'm2} = Σ_J C(j1 m1' j2 m2'|J M') C(j1 m1 j2 m2|J M) D^J_{M'M}.
 *  [3] docs/CONVENTIONS.md and rot_blocks.c: D^l_{m'm} = e^{−im'α} d^l_{m'm}(β) e^{−imγ},
 *      Y_l^m(R⁻¹s) = Σ_{m'} Y_l^{m'}(s) D^l_{m'm}(R), i.e. Y(R⁻¹s) = Dᵀ Y(s),
 *      and the real matrix R_sh = conj(U) D Uᵀ for y = U Y.
 *
 * Band 1 (derived, [3]).  Y_1(s) = √(3/4π) T s with rows (m = −1, 0, 1)
 *   T_{−1} = (1, −i, 0)/√2,  T_0 = (0, 0, 1),  T_1 = (−1, −i, 0)/√2   (CS phase),
 * T unitary.  Y_1(R⁻¹s) = T Rᵀ s·√(3/4π) = T Rᵀ T^H Y_1(s) = Dᵀ Y_1(s), hence
 *   D¹ = conj(T) R Tᵀ.                                                    (C1)
 *
 * Recursion (derived from [2] with j1 = 1, j2 = l−1, J = l): multiply [2] by
 * C(1 μ, l−1 M−μ | l M), sum over μ and use the orthogonality of the CG
 * coefficients at fixed M; only J = l survives:
 *   C(1 μ', l−1 M'−μ' | l M') D^l_{M'M}
 *        = Σ_{μ=−1}^{1} C(1 μ, l−1 M−μ | l M) D¹_{μ'μ} D^{l−1}_{M'−μ', M−μ}     (C2)
 * for any μ' with a non-zero left coefficient; we take μ' = 0 for |M'| < l,
 * μ' = ±1 for M' = ±l (left coefficient 1).  The stretched CG coefficients:
 *   C(1 +1, l−1 M−1 | l M) = √((l+M)(l+M−1) / (2l(2l−1)))
 *   C(1  0, l−1 M   | l M) = √((l−M)(l+M)   / (l(2l−1)))
 *   C(1 −1, l−1 M+1 | l M) = √((l−M)(l−M−1) / (2l(2l−1)))                  (C3)
 * (their squares sum to 1 — checked in the tables).  Entries of D^{l−1}
 * outside −(l−1)..l−1 are zero; so are the coefficients that multiply them.
 *
 * Real basis ([3], CS phase), m > 0:
 *   y^m = (Y^m + (−1)^m Y^{−m})/√2,  y^{−m} = (Y^m − (−1)^m Y^{−m})/(i√2),  y^0 = Y^0,
 *   R_sh[a][b] = Σ_{p,q} conj(U_{ap}) D_{pq} U_{bq}                        (C4)
 * whose imaginary part must vanish (the test checks it through
 * sh__rot_choi_blocks_imag_d).
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

SH__ROT_DECLARE_BLOCKS(choi);
SH__ROT_DECLARE_TABLES(choi);
/* the same as blocks, and also the largest |Im R_sh| of (C4) over all bands */
int sh__rot_choi_blocks_imag_d(int order, const sh_rotation *rot, const void *tables,
                               double *blocks, void *work, uint64_t *mults, double *imag_max);
int sh__rot_choi_blocks_imag_f(int order, const sh_rotation *rot, const void *tables,
                               float *blocks, void *work, uint64_t *mults, double *imag_max);

#include <stdlib.h>

/* Tables: for l = 1..order−1 at offset 4·l² (Σ_{k<l} 4(2k+1) = 4l²):
 * cg[0..2][M+l] = C(1 μ, l−1 M−μ | l M) for μ = −1, 0, 1, then inv[M'+l] =
 * 1 / (left coefficient of (C2)). */
static size_t choi_table_len(int order) { return 4 * (size_t)order * order; }

int SH_R(sh__rot_choi_tables_new)(int order, void **tables)
{
    sh_real *t = malloc(choi_table_len(order) * sizeof *t + 1);
    if (!t) return sh_error(SH_ENOMEM, "choi: out of memory (order %d)", order);
    for (int l = 1; l < order; l++) {
        const int w = 2 * l + 1;
        sh_real *cg = t + 4 * (size_t)l * l, *inv = cg + 3 * w;
        const double den = 2.0 * l * (2 * l - 1);
        for (int M = -l; M <= l; M++) {
            /* (C3) */
            cg[0 * w + M + l] = (sh_real)sqrt((double)(l - M) * (l - M - 1) / den);
            cg[1 * w + M + l] = (sh_real)sqrt(2.0 * (l - M) * (l + M) / den);
            cg[2 * w + M + l] = (sh_real)sqrt((double)(l + M) * (l + M - 1) / den);
            inv[M + l] = (M == -l || M == l) ? 1 : (sh_real)(1.0 / sqrt(2.0 * (l - M) * (l + M) / den));
        }
    }
    *tables = t;
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static void choi_tables_free(void *t) { free(t); }
#endif

/* work: cur and prev complex bands (re, im interleaved), stride W = 2L+1
 * with L = order−1, and the weights w[μ'][μ][M] (complex, 9·W). */
#ifndef SH_REAL_FLOAT
static size_t choi_work(int order)
{
    const size_t W = 2 * (size_t)order + 1;
    return (2 * 2 * W * W + 2 * 9 * W) * sizeof(double);
}
#endif

/* 1/√2 */
#define CHOI_H ((sh_real)0.70710678118654752440)
/* element (M', M) of a complex band at (re, im) = p[2k], p[2k+1] (stride W, offset L) */
#define IDX(mp, m) (2 * ((size_t)((mp) + L) * W + (size_t)((m) + L)))

/* (C1): D¹ = conj(T) R Tᵀ; T rows m = −1, 0, 1 as (re, im) of columns x, y, z.
 * Returns the multiplications. */
static inline uint64_t choi_band1(const sh_rotation *rot, sh_real D1[3][3][2])
{
    const sh_real h = CHOI_H;
    const sh_real Tre[3][3] = {{h, 0, 0}, {0, 0, 1}, {-h, 0, 0}};
    const sh_real Tim[3][3] = {{0, -h, 0}, {0, 0, 0}, {0, -h, 0}};
    uint64_t count = 0;
    sh_real Pre[3][3], Pim[3][3]; /* P = R Tᵀ: P[j][b] = Σ_k R[j][k] T[b][k] */
    for (int j = 0; j < 3; j++)
        for (int b = 0; b < 3; b++) {
            sh_real re = 0, im = 0;
            for (int k = 0; k < 3; k++) {
                re += (sh_real)rot->R[3 * j + k] * Tre[b][k];
                im += (sh_real)rot->R[3 * j + k] * Tim[b][k];
            }
            Pre[j][b] = re;
            Pim[j][b] = im;
        }
    count += 2 * 27;
    for (int a = 0; a < 3; a++) /* D[a][b] = Σ_j conj(T[a][j]) P[j][b] */
        for (int b = 0; b < 3; b++) {
            sh_real re = 0, im = 0;
            for (int j = 0; j < 3; j++) {
                re += Tre[a][j] * Pre[j][b] + Tim[a][j] * Pim[j][b];
                im += Tre[a][j] * Pim[j][b] - Tim[a][j] * Pre[j][b];
            }
            D1[a][b][0] = re;
            D1[a][b][1] = im;
        }
    count += 4 * 27;
    return count;
}

/* D¹ into the complex band buffer (rows and columns −1..1). */
static inline void choi_store_band1(sh_real D1[3][3][2], int L, int W, sh_real *band)
{
    for (int mp = -1; mp <= 1; mp++)
        for (int m = -1; m <= 1; m++) {
            band[IDX(mp, m)] = D1[mp + 1][m + 1][0];
            band[IDX(mp, m) + 1] = D1[mp + 1][m + 1][1];
        }
}

/* Band l ≥ 2 from band l−1 (prev) into cur, by (C2) with the weights of
 * (C3) (cg, inv: the band's tables).  Returns the multiplications.  Not
 * inlined: inlined, choi_blocks executes ~2 % more instructions (the
 * registers of its (C4) loop; callgrind, orders 8–64, double and float). */
#define CHOI_NOINLINE __attribute__((noinline))
static CHOI_NOINLINE uint64_t choi_band_recur(int l, int L, int W, const sh_real *cg, const sh_real *inv,
                                              sh_real D1[3][3][2], sh_real *wt, const sh_real *prev,
                                              sh_real *cur)
{
    const int w = 2 * l + 1;
    uint64_t count = 0;
    /* weights wt[μ'][μ][M] = C(1 μ, l−1 M−μ | l M) · D¹_{μ'μ}  (C2, C3) */
    for (int a = 0; a < 3; a++)
        for (int u = 0; u < 3; u++)
            for (int M = -l; M <= l; M++) {
                const sh_real c = cg[u * w + M + l];
                sh_real *o = wt + 2 * ((size_t)(3 * a + u) * W + (size_t)(M + l));
                o[0] = c * D1[a][u][0];
                o[1] = c * D1[a][u][1];
            }
    count += 2u * 9u * (uint64_t)w;
    /* (C2): D^l_{M'M} = inv(M') Σ_μ wt[μ'][μ][M] D^{l−1}_{M'−μ', M−μ} */
    for (int Mp = -l; Mp <= l; Mp++) {
        const int a = Mp == l ? 2 : Mp == -l ? 0 : 1, mup = a - 1;
        const int src = Mp - mup; /* row of D^{l−1}, always in −(l−1)..l−1 */
        for (int M = -l; M <= l; M++) {
            sh_real re = 0, im = 0;
            for (int u = 0; u < 3; u++) {
                const int mm = M - (u - 1);
                if (mm < -(l - 1) || mm > l - 1) continue;
                const sh_real *x = wt + 2 * ((size_t)(3 * a + u) * W + (size_t)(M + l));
                const sh_real *y = prev + IDX(src, mm);
                re += x[0] * y[0] - x[1] * y[1];
                im += x[0] * y[1] + x[1] * y[0];
                count += 4;
            }
            if (a == 1) {
                re *= inv[Mp + l];
                im *= inv[Mp + l];
                count += 2;
            }
            cur[IDX(Mp, M)] = re;
            cur[IDX(Mp, M) + 1] = im;
        }
    }
    return count;
}

/* Every band: band 1 from the matrix (C1), then band l from band l−1 (C2),
 * each turned into its real block (C4). */
static int choi_blocks(int order, const sh_rotation *rot, const void *tables, sh_real *blocks,
                       void *work, uint64_t *mults, double *imag_max)
{
    const int L = order - 1, W = 2 * L + 1;
    const sh_real *tab = tables;
    sh_real *buf0 = work, *buf1 = buf0 + 2 * (size_t)W * W, *wt = buf1 + 2 * (size_t)W * W;
    uint64_t count = 0;
    double imax = 0;
    blocks[0] = 1; /* band 0 */
    if (order < 2) return SH_OK;

    sh_real D1[3][3][2];
    count += choi_band1(rot, D1);
    sh_real *prev = buf0, *cur = buf1;
    choi_store_band1(D1, L, W, prev);
    for (int l = 1; l < order; l++) {
        sh__rot_band_done(l, order); /* bands 0..l−1 done */
        const sh_real *Dl = prev; /* band l, complex */
        if (l >= 2) {
            const sh_real *cg = tab + 4 * (size_t)l * l, *inv = cg + 3 * (2 * l + 1);
            count += choi_band_recur(l, L, W, cg, inv, D1, wt, prev, cur);
            Dl = cur;
        }
        /* (C4): real block.  Row a of U as up to two (column, coefficient)
         * pairs: a = 0: (0, 1); a = m > 0: (m, 1/√2), (−m, (−1)^m/√2);
         * a = −m: (m, −i/√2), (−m, i(−1)^m/√2). */
        const sh_real h = CHOI_H;
        const int w = 2 * l + 1;
        sh_real *B = blocks + sh_rot_block_offset(l);
        for (int ra = -l; ra <= l; ra++) {
            int pc[2], pn = 0;
            sh_real pr[2], pi[2];
            {
                const int m = ra < 0 ? -ra : ra;
                const sh_real sg = (m & 1) ? -1 : 1;
                if (m == 0) { pc[0] = 0; pr[0] = 1; pi[0] = 0; pn = 1; }
                else if (ra > 0) { pc[0] = m; pr[0] = h; pi[0] = 0; pc[1] = -m; pr[1] = sg * h; pi[1] = 0; pn = 2; }
                else { pc[0] = m; pr[0] = 0; pi[0] = -h; pc[1] = -m; pr[1] = 0; pi[1] = sg * h; pn = 2; }
            }
            for (int rb = -l; rb <= l; rb++) {
                int qc[2], qn = 0;
                sh_real qr[2], qi[2];
                {
                    const int m = rb < 0 ? -rb : rb;
                    const sh_real sg = (m & 1) ? -1 : 1;
                    if (m == 0) { qc[0] = 0; qr[0] = 1; qi[0] = 0; qn = 1; }
                    else if (rb > 0) { qc[0] = m; qr[0] = h; qi[0] = 0; qc[1] = -m; qr[1] = sg * h; qi[1] = 0; qn = 2; }
                    else { qc[0] = m; qr[0] = 0; qi[0] = -h; qc[1] = -m; qr[1] = 0; qi[1] = sg * h; qn = 2; }
                }
                sh_real re = 0, im = 0;
                for (int s = 0; s < pn; s++)
                    for (int t = 0; t < qn; t++) {
                        /* conj(U_ap) U_bq, then times D_pq */
                        const sh_real cr = pr[s] * qr[t] + pi[s] * qi[t];
                        const sh_real ci = pr[s] * qi[t] - pi[s] * qr[t];
                        const sh_real *d = Dl + IDX(pc[s], qc[t]);
                        re += cr * d[0] - ci * d[1];
                        im += cr * d[1] + ci * d[0];
                    }
                count += 8u * (uint64_t)(pn * qn);
                B[(size_t)(ra + l) * w + (size_t)(rb + l)] = re;
                if (imag_max && fabs((double)im) > imax) imax = fabs((double)im);
            }
        }
        if (l >= 2) { /* swap */
            sh_real *t = prev;
            prev = cur;
            cur = t;
        }
    }
    sh__rot_band_done(order, order);
    if (mults) *mults += count;
    if (imag_max) *imag_max = imax;
    return SH_OK;
}
#undef IDX
#undef CHOI_H
#undef CHOI_NOINLINE

int SH_R(sh__rot_choi_blocks_imag)(int order, const sh_rotation *rot, const void *tables,
                                   sh_real *blocks, void *work, uint64_t *mults, double *imag_max)
{
    return choi_blocks(order, rot, tables, blocks, work, mults, imag_max);
}

int SH_R(sh__rot_choi_blocks)(int order, const sh_rotation *rot, const void *tables,
                              sh_real *blocks, void *work, uint64_t *mults)
{
    return choi_blocks(order, rot, tables, blocks, work, mults, NULL);
}

#ifndef SH_REAL_FLOAT
static size_t choi_tables_bytes(int order) { return choi_table_len(order) * sizeof(double); }
const sh__rot_ops sh__rot_choi_ops = {
    .name = "choi",
    .tables_bytes = choi_tables_bytes,
    .max_order = SH_ROT_CHOI_MAX_ORDER,
    .tables_new_d = sh__rot_choi_tables_new_d,
    .tables_new_f = sh__rot_choi_tables_new_f,
    .tables_free = choi_tables_free,
    .work_bytes = choi_work,
    .blocks_d = sh__rot_choi_blocks_d,
    .blocks_f = sh__rot_choi_blocks_f,
};
#endif
