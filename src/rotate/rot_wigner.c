/* rot_wigner.c — the `wigner` method: Wigner small-d by the direct sum, in
 * long double, composed with z rotations into the real basis.
 *
 *   d^l_{m'm}(β) = Σ_s (−1)^{m'−m+s} √((l+m')!(l−m')!(l+m)!(l−m)!)
 *                  / ((l+m−s)! s! (m'−m+s)! (l−m'−s)!)
 *                  · cos(β/2)^{2l+m−m'−2s} sin(β/2)^{m'−m+2s},
 *   s from max(0, m−m') to min(l+m, l−m')      (Wigner 1931; Edmonds 4.1.23).
 *
 * The terms alternate and grow like 4^l/√l while d stays ≤ 1, so the sum
 * cancels: in long double (64-bit mantissa) it is accurate to ~1e-16 only
 * for small l, and the stability experiment shows where it breaks.  Both
 * precisions sum in long double; the float variant rounds the result.
 * Factorials are tabulated in long double (exact to 25!, relative 1e-19
 * beyond); (2l)! must fit, which caps the order at 400.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

SH__ROT_DECLARE_BLOCKS(wigner);
SH__ROT_DECLARE_BAND(wigner);

#include <stdlib.h>

#define WIGNER_MAX_ORDER SH_ROT_WIGNER_MAX_ORDER

/* work: long double fact[2l+1], sqf[2l+1], cpow[2l+1], spow[2l+1], then
 * sh_real d[(2l+1)²], csa, csg[2(l+1)] */
static void wigner_d(int l, long double beta, long double *ws, sh_real *d)
{
    long double *fact = ws, *sqf = ws + 2 * l + 1, *cp = sqf + 2 * l + 1, *sp = cp + 2 * l + 1;
    const long double c = cosl(beta / 2), s = sinl(beta / 2);
    fact[0] = sqf[0] = cp[0] = sp[0] = 1;
    for (int k = 1; k <= 2 * l; k++) {
        fact[k] = fact[k - 1] * k;
        sqf[k] = sqrtl(fact[k]);
        cp[k] = cp[k - 1] * c;
        sp[k] = sp[k - 1] * s;
    }
    const int w = 2 * l + 1;
    for (int mp = -l; mp <= l; mp++)
        for (int m = -l; m <= l; m++) {
            const long double pre = sqf[l + mp] * sqf[l - mp] * sqf[l + m] * sqf[l - m];
            const int s0 = (m - mp > 0) ? m - mp : 0;
            const int s1 = (l + m < l - mp) ? l + m : l - mp;
            long double sum = 0;
            for (int k = s0; k <= s1; k++) {
                long double t = pre / (fact[l + m - k] * fact[k] * fact[mp - m + k] * fact[l - mp - k]);
                t *= cp[2 * l + m - mp - 2 * k] * sp[mp - m + 2 * k];
                sum += ((mp - m + k) & 1) ? -t : t;
            }
            d[(size_t)(mp + l) * w + (m + l)] = (sh_real)sum;
        }
}

#ifndef SH_REAL_FLOAT
static size_t wigner_band_work(int l)
{
    return 4 * (size_t)(2 * l + 1) * sizeof(long double) +
           ((size_t)(2 * l + 1) * (2 * l + 1) + 4 * (size_t)(l + 1)) * sizeof(double);
}
#endif

int SH_R(sh__rot_wigner_band)(int l, const sh_rotation *rot, sh_real *block, void *work)
{
    long double *ws = work;
    sh_real *d = (sh_real *)(ws + 4 * (2 * l + 1));
    sh_real *csa = d + (size_t)(2 * l + 1) * (2 * l + 1), *csg = csa + 2 * (l + 1);
    wigner_d(l, (long double)rot->beta, ws, d);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->alpha, l, csa);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->gamma, l, csg);
    SH_R(sh__rot_block_from_d)(l, d, csa, csg, block);
    return SH_OK;
}

int SH_R(sh__rot_wigner_blocks)(int order, const sh_rotation *rot, const void *tables,
                                sh_real *blocks, void *work, uint64_t *mults)
{
    for (int l = 0; l < order; l++) {
        SH_R(sh__rot_wigner_band)(l, rot, blocks + sh_rot_block_offset(l), work);
        /* per element: 4 (prefactor) + 6 per term (4 in the denominator, the
         * division counted as one, 2 powers); per band 2·(2l) for the tables */
        uint64_t terms = 0;
        for (int mp = -l; mp <= l; mp++)
            for (int m = -l; m <= l; m++) {
                const int s0 = (m - mp > 0) ? m - mp : 0, s1 = (l + m < l - mp) ? l + m : l - mp;
                terms += (uint64_t)(s1 - s0 + 1);
            }
        if (mults) *mults += 3u * (uint64_t)(2 * l + 1) * (2 * l + 1) + 6u * terms + 4u * (uint64_t)l;
    }
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static size_t wigner_work(int order) { return wigner_band_work(order); }
static int wigner_band_double(int band, const sh_rotation *rot, double *block, void *work)
{
    return sh__rot_wigner_band_d(band, rot, block, work);
}
const sh__rot_ops sh__rot_wigner_ops = {
    .name = "wigner",
    .max_order = WIGNER_MAX_ORDER,
    .work_bytes = wigner_work,
    .blocks_d = sh__rot_wigner_blocks_d,
    .blocks_f = sh__rot_wigner_blocks_f,
    .band_d = wigner_band_double,
    .band_work_bytes = wigner_band_work,
};
#endif
