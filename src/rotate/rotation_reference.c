/* rotation_reference.c — the `reference` method: the direct Wigner small-d
 * sum (rot_wigner.c) and its composition into the real basis
 * (sh__rot_block_from_d) carried out in MPFR, with the precision raised with
 * the band so that the cancellation of the sum (its terms grow like 4^l) still
 * leaves `digits` correct significant digits:
 *     bits = ⌈digits·log2(10)⌉ + 2l + 64.
 * sh__rot_reference_selfcheck measures that claim by recomputing with 100
 * more bits.  Input angles are taken as exact binary numbers.
 *
 * Symmetries used to sum only the region m' ≥ |m| (Edmonds 4.2.6):
 *     d_{m'm} = (−1)^{m−m'} d_{mm'} = d_{−m,−m'}.
 */
#include "rotate/rot_internal.h"

#include <math.h>
#include <mpfr.h>
#include <stdlib.h>

/* The MPFR sum costs O(l³) operations at O(l) bits per band: band 200 takes
 * about 1.5 s, band 400 about 20 s; higher bands are refused. */
#define REF_MAX_ORDER SH_ROT_REFERENCE_MAX_ORDER
#define REF_DIGITS 32

typedef struct {
    int l;
    mpfr_prec_t bits;
    mpfr_t *d; /* (2l+1)² */
} ref_band;

static void dref_compute(int l, double beta, mpfr_prec_t bits, mpfr_t *d)
{
    const int w = 2 * l + 1;
    mpfr_t c, s, t, u, half, *fact, *sqf, *cp, *sp;
    fact = malloc(4 * (size_t)(2 * l + 1) * sizeof(mpfr_t));
    sqf = fact + (2 * l + 1);
    cp = sqf + (2 * l + 1);
    sp = cp + (2 * l + 1);
    mpfr_inits2(bits, c, s, t, u, half, (mpfr_ptr)0);
    mpfr_set_d(half, beta, MPFR_RNDN);
    mpfr_div_2ui(half, half, 1, MPFR_RNDN); /* β/2, exact */
    mpfr_sin_cos(s, c, half, MPFR_RNDN);
    for (int k = 0; k <= 2 * l; k++) {
        mpfr_init2(fact[k], bits); mpfr_init2(sqf[k], bits);
        mpfr_init2(cp[k], bits); mpfr_init2(sp[k], bits);
        mpfr_fac_ui(fact[k], (unsigned long)k, MPFR_RNDN);
        mpfr_sqrt(sqf[k], fact[k], MPFR_RNDN);
        if (k == 0) { mpfr_set_ui(cp[0], 1, MPFR_RNDN); mpfr_set_ui(sp[0], 1, MPFR_RNDN); }
        else { mpfr_mul(cp[k], cp[k - 1], c, MPFR_RNDN); mpfr_mul(sp[k], sp[k - 1], s, MPFR_RNDN); }
    }
#define DD(mp, m) d[(size_t)((mp) + l) * w + (size_t)((m) + l)]
    for (int mp = 0; mp <= l; mp++)
        for (int m = -mp; m <= mp; m++) {
            mpfr_t pre, sum;
            mpfr_inits2(bits, pre, sum, (mpfr_ptr)0);
            mpfr_mul(pre, sqf[l + mp], sqf[l - mp], MPFR_RNDN);
            mpfr_mul(pre, pre, sqf[l + m], MPFR_RNDN);
            mpfr_mul(pre, pre, sqf[l - m], MPFR_RNDN);
            mpfr_set_ui(sum, 0, MPFR_RNDN);
            const int s0 = (m - mp > 0) ? m - mp : 0, s1 = (l + m < l - mp) ? l + m : l - mp;
            for (int k = s0; k <= s1; k++) {
                mpfr_mul(u, fact[l + m - k], fact[k], MPFR_RNDN);
                mpfr_mul(u, u, fact[mp - m + k], MPFR_RNDN);
                mpfr_mul(u, u, fact[l - mp - k], MPFR_RNDN);
                mpfr_div(t, pre, u, MPFR_RNDN);
                mpfr_mul(t, t, cp[2 * l + m - mp - 2 * k], MPFR_RNDN);
                mpfr_mul(t, t, sp[mp - m + 2 * k], MPFR_RNDN);
                if ((mp - m + k) & 1) mpfr_sub(sum, sum, t, MPFR_RNDN);
                else mpfr_add(sum, sum, t, MPFR_RNDN);
            }
            mpfr_set(DD(mp, m), sum, MPFR_RNDN);
            mpfr_clears(pre, sum, (mpfr_ptr)0);
        }
    /* fill the rest by symmetry from the region m' ≥ |m| */
    for (int mp = -l; mp <= l; mp++)
        for (int m = -l; m <= l; m++) {
            if (mp >= abs(m)) continue;
            if (m >= abs(mp)) { /* d_{m'm} = (−1)^{m−m'} d_{mm'} */
                mpfr_set(DD(mp, m), DD(m, mp), MPFR_RNDN);
                if ((m - mp) & 1) mpfr_neg(DD(mp, m), DD(mp, m), MPFR_RNDN);
            } else if (-mp >= abs(m)) { /* d_{m'm} = (−1)^{m−m'} d_{−m',−m} */
                mpfr_set(DD(mp, m), DD(-mp, -m), MPFR_RNDN);
                if ((m - mp) & 1) mpfr_neg(DD(mp, m), DD(mp, m), MPFR_RNDN);
            } else { /* −m ≥ |m'|: d_{m'm} = d_{−m,−m'} */
                mpfr_set(DD(mp, m), DD(-m, -mp), MPFR_RNDN);
            }
        }
#undef DD
    for (int k = 0; k <= 2 * l; k++) mpfr_clears(fact[k], sqf[k], cp[k], sp[k], (mpfr_ptr)0);
    free(fact);
    mpfr_clears(c, s, t, u, half, (mpfr_ptr)0);
}

/* The real block (formulas of sh__rot_block_from_d) in MPFR; out[(2l+1)²]
 * initialised by the caller. */
static void block_compute(int l, const sh_rotation *rot, mpfr_prec_t bits, mpfr_t *B)
{
    const int w = 2 * l + 1;
    mpfr_t *d = malloc((size_t)w * w * sizeof(mpfr_t));
    for (size_t i = 0; i < (size_t)w * w; i++) mpfr_init2(d[i], bits);
    dref_compute(l, rot->beta, bits, d);
    mpfr_t r2, a, b, p, q, c, s, x;
    mpfr_inits2(bits, r2, a, b, p, q, c, s, x, (mpfr_ptr)0);
    mpfr_sqrt_ui(r2, 2, MPFR_RNDN);
#define D(mp, m) d[(size_t)((mp) + l) * w + (size_t)((m) + l)]
#define BB(mp, m) B[(size_t)((mp) + l) * w + (size_t)((m) + l)]
    mpfr_set(BB(0, 0), D(0, 0), MPFR_RNDN);
    for (int m = 1; m <= l; m++) {
        mpfr_mul(BB(0, m), r2, D(0, m), MPFR_RNDN);
        mpfr_set_ui(BB(0, -m), 0, MPFR_RNDN);
        mpfr_mul(BB(m, 0), r2, D(m, 0), MPFR_RNDN);
        mpfr_set_ui(BB(-m, 0), 0, MPFR_RNDN);
    }
    for (int mp = 1; mp <= l; mp++)
        for (int m = 1; m <= l; m++) {
            mpfr_set(a, D(mp, m), MPFR_RNDN);
            if (m & 1) mpfr_neg(b, D(mp, -m), MPFR_RNDN);
            else mpfr_set(b, D(mp, -m), MPFR_RNDN);
            mpfr_add(BB(mp, m), a, b, MPFR_RNDN);
            mpfr_sub(BB(-mp, -m), a, b, MPFR_RNDN);
            mpfr_set_ui(BB(mp, -m), 0, MPFR_RNDN);
            mpfr_set_ui(BB(-mp, m), 0, MPFR_RNDN);
        }
    /* Z(α) on the left, Z(γ) on the right, cos/sin(mθ) directly in MPFR */
    for (int mp = 1; mp <= l; mp++) {
        mpfr_set_d(x, rot->alpha, MPFR_RNDN);
        mpfr_mul_si(x, x, mp, MPFR_RNDN);
        mpfr_sin_cos(s, c, x, MPFR_RNDN);
        for (int m = -l; m <= l; m++) {
            mpfr_set(p, BB(mp, m), MPFR_RNDN);
            mpfr_set(q, BB(-mp, m), MPFR_RNDN);
            mpfr_mul(a, c, p, MPFR_RNDN); mpfr_mul(b, s, q, MPFR_RNDN);
            mpfr_sub(BB(mp, m), a, b, MPFR_RNDN);
            mpfr_mul(a, s, p, MPFR_RNDN); mpfr_mul(b, c, q, MPFR_RNDN);
            mpfr_add(BB(-mp, m), a, b, MPFR_RNDN);
        }
    }
    for (int m = 1; m <= l; m++) {
        mpfr_set_d(x, rot->gamma, MPFR_RNDN);
        mpfr_mul_si(x, x, m, MPFR_RNDN);
        mpfr_sin_cos(s, c, x, MPFR_RNDN);
        for (int mp = -l; mp <= l; mp++) {
            mpfr_set(p, BB(mp, m), MPFR_RNDN);
            mpfr_set(q, BB(mp, -m), MPFR_RNDN);
            mpfr_mul(a, c, p, MPFR_RNDN); mpfr_mul(b, s, q, MPFR_RNDN);
            mpfr_add(BB(mp, m), a, b, MPFR_RNDN);
            mpfr_mul(a, s, p, MPFR_RNDN); mpfr_mul(b, c, q, MPFR_RNDN);
            mpfr_sub(BB(mp, -m), b, a, MPFR_RNDN);
        }
    }
#undef D
#undef BB
    mpfr_clears(r2, a, b, p, q, c, s, x, (mpfr_ptr)0);
    for (size_t i = 0; i < (size_t)w * w; i++) mpfr_clear(d[i]);
    free(d);
}

static mpfr_prec_t bits_for(int l, int digits) { return (mpfr_prec_t)(digits * 3.33 + 2 * l + 64); }

static mpfr_t *band_alloc(int l, mpfr_prec_t bits)
{
    const size_t n = (size_t)(2 * l + 1) * (2 * l + 1);
    mpfr_t *B = malloc(n * sizeof(mpfr_t));
    if (B) for (size_t i = 0; i < n; i++) mpfr_init2(B[i], bits);
    return B;
}
static void band_free(int l, mpfr_t *B)
{
    const size_t n = (size_t)(2 * l + 1) * (2 * l + 1);
    for (size_t i = 0; i < n; i++) mpfr_clear(B[i]);
    free(B);
}

int sh_rot_reference_band(int band, sh_convention conv, const sh_rotation *rot, int digits,
                          double *block, long double *block_ld)
{
    if (band < 0 || band >= REF_MAX_ORDER)
        return sh_error(SH_EINVAL, "reference: band %d out of range 0..%d", band, REF_MAX_ORDER - 1);
    if (digits < 17 || digits > 1000)
        return sh_error(SH_EINVAL, "reference: digits %d out of range 17..1000", digits);
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "reference: unknown convention");
    const int l = band, w = 2 * l + 1;
    const mpfr_prec_t bits = bits_for(l, digits);
    mpfr_t *B = band_alloc(l, bits);
    if (!B) return sh_error(SH_ENOMEM, "reference: out of memory");
    block_compute(l, rot, bits, B);
    for (int mp = -l; mp <= l; mp++)
        for (int m = -l; m <= l; m++) {
            const size_t i = (size_t)(mp + l) * w + (m + l);
            const int flip = conv == SH_NOCS && ((mp ^ m) & 1);
            if (block) block[i] = (flip ? -1 : 1) * mpfr_get_d(B[i], MPFR_RNDN);
            if (block_ld) block_ld[i] = (flip ? -1 : 1) * mpfr_get_ld(B[i], MPFR_RNDN);
        }
    band_free(l, B);
    return SH_OK;
}

int sh__rot_reference_selfcheck(int band, const sh_rotation *rot, int digits, double *maxdiff)
{
    const int l = band, w = 2 * l + 1;
    const mpfr_prec_t b1 = bits_for(l, digits), b2 = b1 + 100;
    mpfr_t *B1 = band_alloc(l, b1), *B2 = band_alloc(l, b2);
    if (!B1 || !B2) {
        if (B1) band_free(l, B1);
        if (B2) band_free(l, B2);
        return sh_error(SH_ENOMEM, "reference: out of memory");
    }
    block_compute(l, rot, b1, B1);
    block_compute(l, rot, b2, B2);
    mpfr_t t;
    mpfr_init2(t, b2);
    double worst = 0;
    for (size_t i = 0; i < (size_t)w * w; i++) {
        mpfr_sub(t, B1[i], B2[i], MPFR_RNDN);
        double e = fabs(mpfr_get_d(t, MPFR_RNDN));
        if (e > worst) worst = e;
    }
    mpfr_clear(t);
    band_free(l, B1);
    band_free(l, B2);
    *maxdiff = worst;
    return SH_OK;
}

static int ref_blocks_d(int order, const sh_rotation *rot, const void *tables, double *blocks,
                        void *work, uint64_t *mults)
{
    for (int l = 0; l < order; l++) {
        int st = sh_rot_reference_band(l, SH_CS, rot, REF_DIGITS, blocks + sh_rot_block_offset(l), NULL);
        if (st) return st;
    }
    return SH_OK;
}

static int ref_blocks_f(int order, const sh_rotation *rot, const void *tables, float *blocks,
                        void *work, uint64_t *mults)
{
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        double *tmp = malloc((size_t)w * w * sizeof *tmp);
        if (!tmp) return sh_error(SH_ENOMEM, "reference: out of memory");
        int st = sh_rot_reference_band(l, SH_CS, rot, REF_DIGITS, tmp, NULL);
        for (size_t i = 0; !st && i < (size_t)w * w; i++) blocks[sh_rot_block_offset(l) + i] = (float)tmp[i];
        free(tmp);
        if (st) return st;
    }
    return SH_OK;
}

static int ref_band_d(int band, const sh_rotation *rot, double *block, void *work)
{
    return sh_rot_reference_band(band, SH_CS, rot, REF_DIGITS, block, NULL);
}

const sh__rot_ops sh__rot_reference_ops = {
    .name = "reference",
    .max_order = REF_MAX_ORDER,
    .blocks_d = ref_blocks_d,
    .blocks_f = ref_blocks_f,
    .band_d = ref_band_d,
};
