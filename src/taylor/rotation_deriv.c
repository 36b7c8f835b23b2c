/* rotation_deriv.c — derivatives d^k R_Y/dβ^k of the SH rotation about y,
 * computed two independent ways, and the closed form of J = dR_Y/dβ(0).
 *
 * References
 *  [1] J. Křivánek, J. Konttinen, S. Pattanaik, K. Bouatouch, "Fast
 *      Approximation to Spherical Harmonic Rotation", IRISA PI 1728 (2005),
 *      Appendix A (derivative recursion), Figure 2 (J and J² for l = 1..3).
 *  [2] J. Ivanic, K. Ruedenberg, J. Phys. Chem. 100 (1996) 6342, Table 1, and
 *      J. Phys. Chem. A 102 (1998) 9099 (corrected Table 2) — the recursion
 *      as transcribed, with its misprints removed, in rot_ivanic.c.
 *  [3] A. R. Edmonds, "Angular Momentum in Quantum Mechanics" (1957), 4.1:
 *      d^l_{m'm}(β) = <m'|exp(−iβJ_y)|m>, J_± = J_x ± iJ_y,
 *      J_±|m> = √((l∓m)(l±m+1)) |m±1>.
 *
 * (1) The recursion ([1] App. A, derived here; the printed dV, dW, dP are
 * garbled by the OCR and partly by the typesetting).  In the Ivanic basis
 * (our nocs) every entry of band l is, by [2],
 *   M^l_{mn} = u U + v V + w W,   U, V, W = sums of ±P(i, a, n),
 *   P(i, a, n) = R1(i, 0) M^{l−1}(a, n)                           |n| < l
 *              = R1(i, 1) M^{l−1}(a, l−1) − R1(i, −1) M^{l−1}(a, −l+1)   n = l
 *              = R1(i, 1) M^{l−1}(a, −l+1) + R1(i, −1) M^{l−1}(a, l−1)   n = −l
 * with constant u, v, w.  Each P is a sum of products f·g of a band-1 entry
 * and a band-(l−1) entry, so by the Leibniz rule (fg)^(k) = Σ_j C(k,j) f^(j) g^(k−j)
 *   P^(k)(i, a, n) = Σ_{j=0..k} C(k, j) [R1^(j)(i, ·) M^{l−1,(k−j)}(a, ·)]   ([1] "dT")
 * and M^{l,(k)} = u U^(k) + v V^(k) + w W^(k), U^(k) etc. the same signed sums
 * of P^(k) (the printed dV, dW with fractions are OCR debris of these sums).
 * Band 1 about y in the order (y, z, x) is
 *   R1(β) = [[1, 0, 0], [0, cosβ, −sinβ], [0, sinβ, cosβ]]   ([1] App. A),
 * whose derivatives are exact: cos^(k)β = cos(β + kπ/2), sin^(k)β =
 * sin(β + kπ/2), 1^(k) = δ_k0.  All orders 0..k are carried together, band
 * by band.  The u, v, w coefficients are recomputed here from [2] Table 1
 * (the same formulas as rot_ivanic.c; v has √(1+δ_{|m|1}) folded in).  The
 * nocs result is turned into CS by S·M·S (S = −1 on odd m).
 *
 * (2) The generator.  Ry(β + t) = Ry(β) Ry(t) and R_sh is a homomorphism, so
 *   d^k R_Y/dβ^k (β) = R_Y(β) J^k,  J = dR_Y/dβ(0),
 * with R_Y(β) from the zxzxz method (accurate to l = 1000) and J from its
 * closed form (rotate/rotation_generator.c) — no code shared with (1).
 *
 * The closed form of J is derived in rotate/rotation_generator.c.
 */
#include "core/shlab_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Checks the arguments and brings (k, β) to an equivalent pair:
 *  - β modulo 2π (R_Y is 2π-periodic, so are its derivatives): remainder()
 *    is exact, β' ∈ [−π, π] differs from β by a multiple of the double 2π;
 *  - for order ≤ 2 (bands 0, 1 only) J is 0 (band 0) and J³ = −J (band 1,
 *    eigenvalues 0, ±i), so J^k, k ≥ 1, repeats with period 4: k → (k−1) mod 4 + 1.
 * k is refused only when the result must overflow: J is normal with largest
 * eigenvalue modulus l = order − 1 in the top band, so ‖R_Y J^k‖₂ = l^k and
 * some entry is ≥ l^k / (2l+1) (‖A‖₂ ≤ w·max|a_ij| for a w×w matrix). */
static int deriv_check(int order, int *k, double *beta, sh_convention conv)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (order > SH_DERIV_MAX_ORDER)
        return sh_error(SH_EINVAL, "deriv: order %d exceeds %d", order, SH_DERIV_MAX_ORDER);
    if (*k < 0) return sh_error(SH_EINVAL, "deriv: k = %d must be >= 0", *k);
    if (!isfinite(*beta)) return sh_error(SH_EINVAL, "deriv: beta must be finite");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "deriv: unknown convention");
    *beta = remainder(*beta, 2.0 * M_PI);
    if (order <= 2) {
        if (*k > 4) *k = (*k - 1) % 4 + 1;
    } else {
        const int l = order - 1;
        if ((double)*k * log((double)l) - log(2.0 * l + 1) > log(DBL_MAX))
            return sh_error(SH_EINVAL,
                            "deriv: k = %d overflows a double at order %d (band %d has an entry >= %d^k/%d > "
                            "1.8e308; k <= %d at most)",
                            *k, order, l, 2 * l + 1, l, (int)floor((log(DBL_MAX) + log(2.0 * l + 1)) / log((double)l)));
    }
    return SH_OK;
}

/* An entry overflowed on the way (the bound above is only a lower one). */
static int deriv_finite(int order, int k, const double *blocks)
{
    const size_t nb = sh_rot_block_offset(order);
    for (size_t i = 0; i < nb; i++)
        if (!isfinite(blocks[i]))
            return sh_error(SH_EINVAL, "deriv: k = %d overflows at order %d (an entry is not finite in double)",
                            k, order);
    return SH_OK;
}

/* ------------------------------------------------ (1) the recursion */

/* u, v', w of [2] Table 1 (v' = v·√(1+δ_{|m|,1})) for band l, entry (m, n). */
static void uvw(int l, int m, int n, double *u, double *v, double *w)
{
    const int am = m < 0 ? -m : m;
    const double d = (n == l || n == -l) ? (2.0 * l) * (2.0 * l - 1) : (double)(l + n) * (l - n);
    *u = sqrt((double)(l + m) * (l - m) / d);
    *v = 0.5 * sqrt((m == 0 ? 2.0 : 1.0) * (l + am - 1) * (double)(l + am) / d) * (m == 0 ? -1.0 : 1.0);
    if (am == 1) *v *= sqrt(2.0);
    *w = m == 0 ? 0.0 : -0.5 * sqrt((double)(l - am - 1) * (l - am) / d);
}

typedef struct {
    int K;
    const double *R1;   /* (K+1) band-1 derivative blocks, 9 each, nocs (y, z, x) */
    const double *prev; /* (K+1) blocks of band l−1, (2l−1)² each */
    int l;
    const double *binom; /* C(k, j) at k·(K+1) + j */
} rec_ctx;

/* P^(k)(i, a, n) of band l (Leibniz over the products of P). */
static double dP(const rec_ctx *c, int k, int i, int a, int n)
{
    const int l = c->l, lp = l - 1, pw = 2 * l - 1;
    const size_t psz = (size_t)pw * pw;
    double acc = 0;
#define R1(j, r, q) c->R1[(size_t)(j) * 9 + (size_t)((r) + 1) * 3 + (size_t)((q) + 1)]
#define PM(j, x, y) c->prev[(size_t)(j) * psz + (size_t)((x) + lp) * pw + (size_t)((y) + lp)]
    for (int j = 0; j <= k; j++) {
        const int kj = k - j;
        double t;
        if (n > -l && n < l) t = R1(j, i, 0) * PM(kj, a, n);
        else if (n == l) t = R1(j, i, 1) * PM(kj, a, lp) - R1(j, i, -1) * PM(kj, a, -lp);
        else t = R1(j, i, 1) * PM(kj, a, -lp) + R1(j, i, -1) * PM(kj, a, lp);
        acc += c->binom[(size_t)k * (c->K + 1) + j] * t;
    }
#undef R1
#undef PM
    return acc;
}

int sh_rot_deriv_recursion(int order, int k, double beta, sh_convention conv, double *blocks)
{
    const int k_asked = k;
    int st = deriv_check(order, &k, &beta, conv);
    if (st) return st;
    const int K = k;
    const size_t nb = sh_rot_block_offset(order);
    double *all = malloc((size_t)(K + 1) * nb * sizeof *all);
    double *R1 = malloc((size_t)(K + 1) * 9 * sizeof *R1);
    double *binom = malloc((size_t)(K + 1) * (K + 1) * sizeof *binom);
    if (!all || !R1 || !binom) {
        free(all), free(R1), free(binom);
        return sh_error(SH_ENOMEM, "deriv: out of memory (order %d, k %d)", order, k);
    }
    for (int a = 0; a <= K; a++) {
        binom[(size_t)a * (K + 1)] = 1;
        for (int b = 1; b <= K; b++)
            binom[(size_t)a * (K + 1) + b] =
                b > a ? 0 : (a == b ? 1 : binom[(size_t)(a - 1) * (K + 1) + b - 1] + binom[(size_t)(a - 1) * (K + 1) + b]);
    }
    /* 1^(j), cos^(j), sin^(j) at β ([1] App. A, band 0 and band 1) */
    const double c = cos(beta), s = sin(beta);
    for (int j = 0; j <= K; j++) {
        static const int cq[4][2] = {{1, 0}, {0, -1}, {-1, 0}, {0, 1}}; /* cos^(j) = cq·(c, s) */
        const double cj = cq[j & 3][0] * c + cq[j & 3][1] * s;
        static const int sq[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}}; /* sin^(j) = sq·(c, s) */
        const double sj = sq[j & 3][0] * c + sq[j & 3][1] * s;
        double *M = R1 + (size_t)j * 9;
        memset(M, 0, 9 * sizeof *M);
        M[0] = j == 0 ? 1.0 : 0.0; /* (−1, −1): y is fixed */
        M[4] = cj;                 /* (0, 0)   */
        M[5] = -sj;                /* (0, 1) = −sin^(j) */
        M[7] = sj;                 /* (1, 0) = +sin^(j) */
        M[8] = cj;                 /* (1, 1)   */
        double *B0 = all + (size_t)j * nb;
        B0[0] = j == 0 ? 1.0 : 0.0;
        if (order > 1) memcpy(B0 + sh_rot_block_offset(1), M, 9 * sizeof *M);
    }
    /* M^{l,(q)}_{mn} = u U^(q) + v V^(q) + w W^(q)  ([1] App. A; [2] eq. 8.1) */
    for (int l = 2; l < order; l++) {
        const int w = 2 * l + 1, pw = 2 * l - 1;
        /* gather band l−1 of every derivative contiguously */
        double *prev = malloc((size_t)(K + 1) * pw * pw * sizeof *prev);
        if (!prev) {
            free(all), free(R1), free(binom);
            return sh_error(SH_ENOMEM, "deriv: out of memory");
        }
        for (int q = 0; q <= K; q++)
            memcpy(prev + (size_t)q * pw * pw, all + (size_t)q * nb + sh_rot_block_offset(l - 1),
                   (size_t)pw * pw * sizeof *prev);
        rec_ctx ctx = {K, R1, prev, l, binom};
        for (int q = 0; q <= K; q++) {
            double *B = all + (size_t)q * nb + sh_rot_block_offset(l);
            for (int m = -l; m <= l; m++) {
                const int am = m < 0 ? -m : m;
                for (int n = -l; n <= l; n++) {
                    double u, v, ww, acc = 0;
                    uvw(l, m, n, &u, &v, &ww);
                    if (am < l) acc += u * dP(&ctx, q, 0, m, n); /* U = _0P_{mn} */
                    if (m == 0) acc += v * (dP(&ctx, q, 1, 1, n) + dP(&ctx, q, -1, -1, n));
                    else if (m == 1) acc += v * dP(&ctx, q, 1, 0, n);
                    else if (m == -1) acc += v * dP(&ctx, q, -1, 0, n);
                    else if (m > 1) acc += v * (dP(&ctx, q, 1, m - 1, n) - dP(&ctx, q, -1, -m + 1, n));
                    else acc += v * (dP(&ctx, q, 1, m + 1, n) + dP(&ctx, q, -1, -m - 1, n));
                    if (m != 0 && am < l - 1) {
                        if (m > 0) acc += ww * (dP(&ctx, q, 1, m + 1, n) + dP(&ctx, q, -1, -m - 1, n));
                        else acc += ww * (dP(&ctx, q, 1, m - 1, n) - dP(&ctx, q, -1, -m + 1, n));
                    }
                    B[(size_t)(m + l) * w + (size_t)(n + l)] = acc;
                }
            }
        }
        free(prev);
    }
    memcpy(blocks, all + (size_t)K * nb, nb * sizeof *blocks);
    free(all), free(R1), free(binom);
    if (conv == SH_CS) sh_rot_blocks_flip_phase(order, blocks); /* S·M·S: the recursion works in nocs */
    return deriv_finite(order, k_asked, blocks);
}

/* ------------------------------------------------ (2) the generator */

int sh_rot_deriv_generator(int order, int k, double beta, sh_convention conv, double *blocks)
{
    const int k_asked = k;
    int st = deriv_check(order, &k, &beta, conv);
    if (st) return st;
    sh_rotation rot;
    if ((st = sh_rotation_from_euler(0, beta, 0, &rot))) return st;
    sh_rot_plan *p;
    if ((st = sh_rot_plan_create(order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &p))) return st;
    if (!(st = sh_rot_plan_set(p, &rot))) st = sh_rot_plan_blocks(p, blocks);
    sh_rot_plan_free(p);
    if (st) return st;
    const int W = 2 * order - 1;
    double *s = malloc((size_t)(W + 1) * sizeof *s), *row = malloc((size_t)W * sizeof *row);
    if (!s || !row) {
        free(s), free(row);
        return sh_error(SH_ENOMEM, "deriv: out of memory");
    }
    /* G ← G·J, k times, band by band: (G J)[r][m] = G[r][m−1] J[m−1][m] + G[r][m+1] J[m+1][m]
     * = −s_m G[r][m−1] + s_{m+1} G[r][m+1] */
    for (int l = 1; l < order; l++) {
        const int w = 2 * l + 1;
        double *G = blocks + sh_rot_block_offset(l);
        sh_rot_deriv_J_subdiag(l, s);
        s[w] = 0;
        for (int q = 0; q < k; q++)
            for (int r = 0; r < w; r++) {
                double *g = G + (size_t)r * w;
                for (int j = 0; j < w; j++)
                    row[j] = (j > 0 ? -s[j] * g[j - 1] : 0.0) + (j + 1 < w ? s[j + 1] * g[j + 1] : 0.0);
                memcpy(g, row, (size_t)w * sizeof *g);
            }
    }
    if (k > 0) blocks[0] = 0;
    free(s), free(row);
    if (conv == SH_NOCS) sh_rot_blocks_flip_phase(order, blocks); /* S·M·S */
    return deriv_finite(order, k_asked, blocks);
}
