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
 *  [4] CONVENTIONS.md: g(s) = f(R⁻¹s); `nocs` = Ivanic's real basis.
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
 * MISPRINTS in [3] (Green's Appendix I), proved by tests/test_rot_ivanic.c
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
 * also keeps every M^{l−1} index inside band l−1.  Multiplications counted:
 * 1 per P with |n| < l, 2 per P with |n| = l, 1 per u·U, v·V, w·W.
 */
#include "rot_internal.h"
#include "rot_real.h"

SH__ROT_DECLARE_BLOCKS(ivanic);
SH__ROT_DECLARE_TABLES(ivanic);
SH__ROT_DECLARE_BAND(ivanic);
SH__ROT_DECLARE_STREAM(ivanic);

#include <math.h>
#include <stdlib.h>

/* Per-order coefficient tables: band l (l ≥ 2) holds (2l+1)² triples
 * (u, v', w) at 3·sh_rot_block_offset(l), row m, column n, where v' has the
 * √(1+δ_{|m|1}) of V folded in.  Computed in double, stored in sh_real. */
typedef struct {
    int order;
    sh_real *uvw;
} ivanic_tables;

/* The u, v', w coefficients of band l (Table 1 of [1]) into t[3(2l+1)²]. */
static void SH_R(ivanic_coeffs)(int l, sh_real *t)
{
    const int w = 2 * l + 1;
    for (int m = -l; m <= l; m++) {
        const int am = m < 0 ? -m : m;
        for (int n = -l; n <= l; n++) {
            const double d = (n == l || n == -l) ? (2.0 * l) * (2.0 * l - 1) : (double)(l + n) * (l - n);
            const double u = sqrt((double)(l + m) * (l - m) / d);
            double v = 0.5 * sqrt((m == 0 ? 2.0 : 1.0) * (l + am - 1) * (double)(l + am) / d) *
                       (m == 0 ? -1.0 : 1.0);
            const double ww = m == 0 ? 0.0 : -0.5 * sqrt((double)(l - am - 1) * (l - am) / d);
            if (am == 1) v *= sqrt(2.0); /* √(1+δ_{|m|,1}) of V, folded */
            sh_real *e = t + 3 * ((size_t)(m + l) * w + (size_t)(n + l));
            e[0] = (sh_real)u;
            e[1] = (sh_real)v;
            e[2] = (sh_real)ww;
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
    for (int l = 2; l < order; l++) SH_R(ivanic_coeffs)(l, T->uvw + 3 * sh_rot_block_offset(l));
    *tables = T;
    return SH_OK;
}

/* Band 1 in Ivanic's basis order (y, z, x): M1[(i+1)*3 + (j+1)] = R_{π(i)π(j)}. */
static void SH_R(ivanic_band1)(const sh_rotation *rot, sh_real *M1)
{
    static const int perm[3] = {1, 2, 0}; /* m = −1, 0, 1 → y, z, x */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M1[i * 3 + j] = (sh_real)rot->R[perm[i] * 3 + perm[j]];
}

/* One step of the recursion: cur = M^l (nocs) from prev = M^{l−1}, band 1 M1
 * and the band's coefficient triples t.  Returns the multiplications. */
static uint64_t SH_R(ivanic_step)(int l, const sh_real *M1, const sh_real *prev, const sh_real *t,
                                  sh_real *cur)
{
    const int w = 2 * l + 1, pw = 2 * l - 1, lp = l - 1;
    uint64_t count = 0;
#define R1(i, j) M1[((i) + 1) * 3 + ((j) + 1)]
#define PM(a, b) prev[(size_t)((a) + lp) * pw + (size_t)((b) + lp)]
    for (int m = -l; m <= l; m++) {
        const int am = m < 0 ? -m : m;
        const int has_u = am < l, has_w = m != 0 && am < l - 1;
        for (int n = -l; n <= l; n++) {
            const sh_real *c = t + 3 * ((size_t)(m + l) * w + (size_t)(n + l));
            /* P(i, a, b) of [1] Table 2: one multiplication for |b| < l, two at |b| = l */
#define P(i, a)                                                                                    \
    (n > -l && n < l ? R1(i, 0) * PM(a, n)                                                         \
     : n == l        ? R1(i, 1) * PM(a, lp) - R1(i, -1) * PM(a, -lp)                               \
                     : R1(i, 1) * PM(a, -lp) + R1(i, -1) * PM(a, lp))
            const int pc = (n > -l && n < l) ? 1 : 2;
            sh_real acc = 0;
            if (has_u) { /* u·U, U = _0P_{mn} */
                acc += c[0] * P(0, m);
                count += (uint64_t)pc + 1;
            }
            /* v·V ([2] Table 2; √(1+δ) folded into v, the (1−δ) term skipped) */
            if (m == 0) {
                acc += c[1] * (P(1, 1) + P(-1, -1));
                count += 2u * pc + 1;
            } else if (m == 1) {
                acc += c[1] * P(1, 0);
                count += (uint64_t)pc + 1;
            } else if (m == -1) {
                acc += c[1] * P(-1, 0);
                count += (uint64_t)pc + 1;
            } else if (m > 1) {
                acc += c[1] * (P(1, m - 1) - P(-1, -m + 1));
                count += 2u * pc + 1;
            } else {
                acc += c[1] * (P(1, m + 1) + P(-1, -m - 1));
                count += 2u * pc + 1;
            }
            if (has_w) { /* w·W */
                if (m > 0) acc += c[2] * (P(1, m + 1) + P(-1, -m - 1));
                else acc += c[2] * (P(1, m - 1) - P(-1, -m + 1));
                count += 2u * pc + 1;
            }
            cur[(size_t)(m + l) * w + (size_t)(n + l)] = acc;
#undef P
        }
    }
#undef R1
#undef PM
    return count;
}

/* nocs → CS: negate entries whose m and n differ in parity (S·M·S). */
static void SH_R(ivanic_to_cs)(int l, sh_real *B)
{
    const int w = 2 * l + 1;
    for (int m = -l; m <= l; m++)
        for (int n = -l; n <= l; n++)
            if ((m ^ n) & 1) B[(size_t)(m + l) * w + (size_t)(n + l)] = -B[(size_t)(m + l) * w + (size_t)(n + l)];
}

int SH_R(sh__rot_ivanic_blocks)(int order, const sh_rotation *rot, const void *tables,
                                sh_real *blocks, void *work, uint64_t *mults)
{
    const ivanic_tables *T = tables;
    if (!T || T->order < order) return sh_error(SH_EINVAL, "ivanic: tables missing or too small");
    uint64_t count = 0;
    blocks[0] = 1;
    if (order > 1) SH_R(ivanic_band1)(rot, blocks + sh_rot_block_offset(1));
    for (int l = 2; l < order; l++)
        count += SH_R(ivanic_step)(l, blocks + sh_rot_block_offset(1),
                                   blocks + sh_rot_block_offset(l - 1),
                                   T->uvw + 3 * sh_rot_block_offset(l), blocks + sh_rot_block_offset(l));
    /* only after the whole recursion: it reads band l−1 in nocs */
    for (int l = 1; l < order; l++) SH_R(ivanic_to_cs)(l, blocks + sh_rot_block_offset(l));
    if (mults) *mults += count;
    return SH_OK;
}

/* One band without storing the lower ones: two band buffers and the band's
 * coefficients in work (ivanic_band_work). */
int SH_R(sh__rot_ivanic_band)(int band, const sh_rotation *rot, sh_real *block, void *work)
{
    const size_t wmax = (size_t)(2 * band + 1) * (2 * band + 1);
    sh_real *M1 = work, *a = M1 + 9, *b = a + wmax, *t = b + wmax;
    SH_R(ivanic_band1)(rot, M1);
    if (band == 0) {
        block[0] = 1;
        return SH_OK;
    }
    sh_real *prev = a, *cur = b;
    for (int i = 0; i < 9; i++) prev[i] = M1[i];
    for (int l = 2; l <= band; l++) {
        SH_R(ivanic_coeffs)(l, t);
        SH_R(ivanic_step)(l, M1, prev, t, cur);
        sh_real *x = prev;
        prev = cur;
        cur = x;
    }
    for (size_t i = 0; i < (size_t)(2 * band + 1) * (2 * band + 1); i++) block[i] = prev[i];
    SH_R(ivanic_to_cs)(band, block);
    return SH_OK;
}

/* Streaming: band l from the state's band l−1 (state: band 1 in nocs, the
 * previous band in nocs, a buffer for the current one, the coefficients;
 * the same layout as ivanic_band_work(lmax)). */
int SH_R(sh__rot_ivanic_stream)(int l, const sh_rotation *rot, void *state, sh_real *block)
{
    /* the buffers are sized for the largest band: offsets from lmax are not
     * known here, so the state starts with lmax's wmax */
    size_t *hdr = state;
    const size_t wmax = hdr[0];
    sh_real *M1 = (sh_real *)(hdr + 1), *prev = M1 + 9, *cur = prev + wmax, *t = cur + wmax;
    if (l == 0) {
        block[0] = 1;
        return SH_OK;
    }
    if (l == 1) {
        SH_R(ivanic_band1)(rot, M1);
        for (int i = 0; i < 9; i++) prev[i] = M1[i];
    } else {
        SH_R(ivanic_coeffs)(l, t);
        SH_R(ivanic_step)(l, M1, prev, t, cur);
        for (size_t i = 0; i < (size_t)(2 * l + 1) * (2 * l + 1); i++) prev[i] = cur[i];
    }
    for (size_t i = 0; i < (size_t)(2 * l + 1) * (2 * l + 1); i++) block[i] = prev[i];
    SH_R(ivanic_to_cs)(l, block);
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static void ivanic_tables_free(void *tables)
{
    ivanic_tables *T = tables;
    if (T) free(T->uvw);
    free(T);
}
static size_t ivanic_band_work(int band)
{
    const size_t wmax = (size_t)(2 * band + 1) * (2 * band + 1);
    return (9 + 5 * wmax) * sizeof(double);
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
const sh__rot_ops sh__rot_ivanic_ops = {
    .name = "ivanic",
    .max_order = SHLAB_MAX_ORDER,
    .tables_new_d = sh__rot_ivanic_tables_new_d,
    .tables_new_f = sh__rot_ivanic_tables_new_f,
    .tables_free = ivanic_tables_free,
    .blocks_d = sh__rot_ivanic_blocks_d,
    .blocks_f = sh__rot_ivanic_blocks_f,
    .band_d = sh__rot_ivanic_band_d,
    .band_work_bytes = ivanic_band_work,
    .stream_bytes = ivanic_stream_bytes,
    .stream_init = ivanic_stream_init,
    .stream_d = sh__rot_ivanic_stream_d,
    .stream_f = sh__rot_ivanic_stream_f,
};
#endif
