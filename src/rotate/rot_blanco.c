/* rot_blanco.c — the `blanco` method: the Wigner small-d matrices d^l(β) by
 * the recurrences of Blanco, Flórez & Bermejo, composed with the z rotations
 * into the real basis (sh__rot_block_from_d); and a single-band path (an
 * m-recurrence at fixed l, O(l²)) for `rotmat --band L`.
 *
 * References
 *  [1] M. A. Blanco, M. Flórez, M. Bermejo, "Evaluation of the rotation
 *      matrices in the basis of real spherical harmonics", J. Mol. Struct.
 *      (Theochem) 419 (1997) 19.  Equation numbers below are the paper's as
 *      cited by F. J. Simons' MATLAB port (blanco.m, slepian_alpha); the paper
 *      itself was not at hand.  Eq. 64: three-term recurrence in l;
 *      eqs. 65, 66: the diagonal corner elements; eqs. 67, 68: the edge rows
 *      by a ratio recurrence in m'; eq. 38: the symmetries.
 *  [2] T. Dachsel, J. Chem. Phys. 124 (2006) 144115: the three-term recurrence
 *      in m at fixed l, run in its stable direction (single-band path).
 *  [3] Edmonds (4.1.23), as in rot_wigner.c: d^l_{m'm}(β) = Σ_s (−1)^{m'−m+s} … ;
 *      from it (one or two terms of the sum), with c = cos(β/2), s = sin(β/2):
 *        d^l_{m',l}   = √C(2l, l+m') c^{l+m'} s^{l−m'}                          (E1)
 *        d^l_{m',l−1} = √(C(2l, l+m')/(2l)) (l cosβ − m') c^{l−1+m'} s^{l−1−m'}   (E2)
 *      (E2 for |m'| ≤ l−1).
 *
 * Index convention: d[m'][m] = d^l_{m'm} as in rot_wigner.c (row m').  [1]
 * writes d with the indices in the other order; its formulas are transposed
 * here by d_{m'm} = (−1)^{m−m'} d_{mm'}, which removes their minus signs.
 *
 * What is computed.  Only the region m ≥ |m'| (the column index dominates);
 * the rest by the symmetries (eq. 38)
 *   d_{m'm} = (−1)^{m−m'} d_{mm'} = d_{−m,−m'}.                               (S)
 *
 * Departures from [1] (each verified against `reference` by the tests):
 *  - eq. 67 (edge column m = l: d_{m'−1,l} = √((l+m')/(l−m'+1)) tan(β/2) d_{m',l},
 *    from eq. 65's d_{ll} = cos²(β/2) d^{l−1}_{l−1,l−1}) multiplies by tan(β/2),
 *    which is huge near β = π while d_{ll} = cos^{2l}(β/2) underflows: for
 *    β > π/2 we start from the other corner, d_{−l,l} = sin²(β/2) d^{l−1}_{−(l−1),l−1},
 *    and run the ratio upward with cot(β/2).
 *  - eq. 68 (column l−1) is a ratio recurrence whose factor
 *    (l cosβ − m')/(l cosβ − m' − 1) is 0/0 when l cosβ = m'+1; the product
 *    telescopes to (E2), so we compute f_{m'} = d_{m',l−1}/(l cosβ − m') by the
 *    same ratio as column l (seeded by eq. 66's corner, f_{l−1} = d^{l−1}_{l−1,l−1},
 *    or f_{−(l−1)} = d^{l−1}_{−(l−1),l−1}) and multiply by (l cosβ − m').
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

SH__ROT_DECLARE_BLOCKS(blanco);
int sh__rot_blanco_blocks_par_d(int, const double *, const void *, double *, void *, uint64_t *);
int sh__rot_blanco_blocks_par_f(int, const float *, const void *, float *, void *, uint64_t *);
SH__ROT_DECLARE_TABLES(blanco);
int sh__rot_blanco_band_d(int band, const sh_rotation *rot, double *block, void *work);

#include <stdlib.h>
#include <string.h>

/* Tables per l ≥ 2 at offset 3·l² (Σ_{k<l} 3(2k+1)), three vectors over
 * m = −l..l:  ia[m] = 1/√(l²−m²) (|m| < l), b[m] = √((l−1)²−m²) (|m| ≤ l−1),
 * r[m'] = √((l+m')/(l−m'+1)) (the edge ratio, m' = −l+1..l; r[−l] unused). */
static size_t blanco_table_len(int order) { return 3 * (size_t)order * order; }

int SH_R(sh__rot_blanco_tables_new)(int order, void **tables)
{
    sh_real *t = malloc(blanco_table_len(order) * sizeof *t + 1);
    if (!t) return sh_error(SH_ENOMEM, "blanco: out of memory (order %d)", order);
    for (int l = 2; l < order; l++) {
        const int w = 2 * l + 1;
        sh_real *ia = t + 3 * (size_t)l * l, *b = ia + w, *r = b + w;
        for (int m = -l; m <= l; m++) {
            const double l2 = (double)l * l, k2 = (double)(l - 1) * (l - 1), m2 = (double)m * m;
            ia[m + l] = (m2 < l2) ? (sh_real)(1.0 / sqrt(l2 - m2)) : 0;
            b[m + l] = (m2 <= k2) ? (sh_real)sqrt(k2 - m2) : 0;
            r[m + l] = (m > -l) ? (sh_real)sqrt((double)(l + m) / (l - m + 1)) : 0;
        }
    }
    *tables = t;
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static void blanco_tables_free(void *t) { free(t); }
/* three region buffers of stride W = 2L+1, the full band d, csa, csg */
static size_t blanco_work(int order)
{
    const size_t W = 2 * (size_t)order + 1;
    return (4 * W * W + 4 * W) * sizeof(double);
}
#endif

/* The real block of band l straight from the region m ≥ |m'| of d (g,
 * stride W, offset L), without the full d matrix or the R_Y(β) block: with
 * P = d_{m'm} + (−1)^m d_{m',−m}, Q = d_{m'm} − (−1)^m d_{m',−m} (the R_Y
 * entries of rot_internal.h) and c' s' = cos, sin m'α, c s = cos, sin mγ,
 * the products Z(α)·R_Y·Z(γ) are, for m', m > 0,
 *   B(m', m) = c'c P − s's Q,    B(m', −m) = −c's P − s'c Q,
 *   B(−m', m) = s'c P + c's Q,   B(−m', −m) = −s's P + c'c Q,
 * and B(0, ±m) = √2 d_{0m} (c, −s), B(±m', 0) = √2 d_{m'0} (c', s'), B(0,0) = d_00
 * (the same derivation as sh__rot_block_from_d, whose two z passes also
 * multiply the zeros: 12 products per (m', m) here against 16).  The d
 * entries outside the region by (S): for m', m > 0,
 *   d_{m'm}  = g(m', m)                      (m ≥ m'),  (−1)^{m−m'} g(m, m')   (m < m'),
 *   d_{m',−m} = (−1)^{m+m'} g(−m, m')          (m ≤ m'),  (−1)^{m+m'} g(−m', m)  (m > m'),
 *   d_{m'0} = (−1)^{m'} g(0, m').
 * tmp: 2(l+1) values.  Returns the multiplications. */
static uint64_t SH_R(blanco_block)(int l, const sh_real *g, int L, int W, const sh_real *csa,
                                   const sh_real *csg, sh_real *B, sh_real *tmp)
{
    const int w = 2 * l + 1;
    const sh_real r2 = SH_SQRT((sh_real)2);
    sh_real *av = tmp, *dv = tmp + (l + 1); /* d_{m'm}, (−1)^{m+m'} d_{m',−m} of a row m' */
#define G(a, b) g[(size_t)((a) + L) * W + (size_t)((b) + L)]
#define BB(a, b) B[(size_t)((a) + l) * w + (size_t)((b) + l)]
    BB(0, 0) = G(0, 0);
    for (int m = 1; m <= l; m++) {
        const sh_real c = csg[2 * m], s = csg[2 * m + 1], e = r2 * G(0, m);
        BB(0, m) = c * e;
        BB(0, -m) = -s * e;
        const sh_real ca = csa[2 * m], sa = csa[2 * m + 1], f = r2 * ((m & 1) ? -G(0, m) : G(0, m));
        BB(m, 0) = ca * f;
        BB(-m, 0) = sa * f;
    }
    for (int mp = 1; mp <= l; mp++) {
        const sh_real ca = csa[2 * mp], sa = csa[2 * mp + 1];
        /* the row's d entries from the region: av = d_{m'm}, dv = (−1)^m d_{m',−m}
         * = (−1)^{m'} g(...) (S), so that P = a + dv, Q = a − dv below */
        const sh_real sg = (mp & 1) ? -1 : 1;
        for (int m = 1; m < mp; m++) {
            av[m] = ((mp - m) & 1) ? -G(m, mp) : G(m, mp);
            dv[m] = sg * G(-m, mp);
        }
        for (int m = mp; m <= l; m++) {
            av[m] = G(mp, m);
            dv[m] = sg * G(-mp, m);
        }
        sh_real *Bp = &BB(mp, 0), *Bn = &BB(-mp, 0);
        for (int m = 1; m <= l; m++) {
            const sh_real P = av[m] + dv[m], Q = av[m] - dv[m];
            const sh_real c = csg[2 * m], s = csg[2 * m + 1];
            const sh_real cc = ca * c, ss = sa * s, cs = ca * s, sc = sa * c;
            Bp[m] = cc * P - ss * Q;
            Bp[-m] = -(cs * P) - sc * Q;
            Bn[m] = sc * P + cs * Q;
            Bn[-m] = cc * Q - ss * P;
        }
    }
#undef G
#undef BB
    return 6u * (uint64_t)l + 12u * (uint64_t)l * l;
}

#define IX(a, b) ((size_t)((a) + L) * W + (size_t)((b) + L))

/* Band l ≥ 2, region |m'| ≤ m ≤ l−2, from bands l−1 (dm1) and l−2 (dm2) by
 * eq. 64 (ia, bb: the band's tables; c2 = cos²(β/2), s2 = sin²(β/2)).
 * Returns the multiplications. */
static inline uint64_t SH_R(blanco_interior)(int l, int L, int W, const sh_real *ia, const sh_real *bb,
                                             sh_real c2, sh_real s2, int lower, const sh_real *dm1,
                                             const sh_real *dm2, sh_real *cur)
{
    uint64_t count = 0;
    /* eq. 64, |m'| ≤ m ≤ l−2:
     *   d^l_{m'm} = l(2l−1)/√((l²−m²)(l²−m'²)) · [ (cosβ − m m'/(l(l−1))) d^{l−1}_{m'm}
     *              − √(((l−1)²−m²)((l−1)²−m'²))/((l−1)(2l−1)) · d^{l−2}_{m'm} ] */
    const sh_real k1 = (sh_real)l * (2 * l - 1), k3 = (sh_real)1 / ((sh_real)(l - 1) * (2 * l - 1));
    const sh_real kg = (sh_real)1 / ((sh_real)l * (l - 1));
    /* cosβ as 1 − 2sin²(β/2) or 2cos²(β/2) − 1: cosβ itself rounds to ±1
     * within 1e-8 of 0 or π, and the recurrence then amplifies the
     * mismatch with the edge columns (which carry the exact β) — measured
     * at β = π − 1e-9: error 99 at l = 200 with cosβ, ~1e-12 with this */
    const sh_real tws2 = 2 * s2, tcs2 = 2 * c2;
    for (int mp = -(l - 2); mp <= l - 2; mp++) {
        const sh_real A = k1 * ia[mp + l], B = k3 * bb[mp + l], G = (sh_real)mp * kg;
        const int m0 = mp < 0 ? -mp : mp;
        for (int m = m0; m <= l - 2; m++) {
            const sh_real fac1 = A * ia[m + l], fac3 = B * bb[m + l];
            const sh_real fac2 = lower ? (1 - (sh_real)m * G) - tws2 : tcs2 - (1 + (sh_real)m * G);
            cur[IX(mp, m)] = fac1 * (fac2 * dm1[IX(mp, m)] - fac3 * dm2[IX(mp, m)]);
        }
        count += 3 + 6u * (uint64_t)(l - 1 - m0);
    }
    return count;
}

/* The edge columns m = l (eqs. 65, 67) and m = l−1 (eqs. 66, 68 via (E2))
 * of band l for β ≤ π/2: from the corner d_{ll} down in m' (t = tan(β/2),
 * rr: the band's edge ratios).  Returns the multiplications. */
static inline uint64_t SH_R(blanco_edges_lower)(int l, int L, int W, const sh_real *rr, sh_real t,
                                                sh_real cb, sh_real c2, const sh_real *dm1, sh_real *cur)
{
    uint64_t count = 0;
    /* eq. 65: d_{ll} = cos²(β/2) d^{l−1}_{l−1,l−1}; eq. 66 corner f_{l−1} = d^{l−1}_{l−1,l−1} */
    sh_real e = c2 * dm1[IX(l - 1, l - 1)], f = dm1[IX(l - 1, l - 1)];
    cur[IX(l, l)] = e;
    cur[IX(l - 1, l)] = e = rr[l + l] * t * e;
    cur[IX(l - 1, l - 1)] = ((sh_real)l * cb - (sh_real)(l - 1)) * f;
    count += 1 + 2 + 2;
    /* eq. 67: d_{m'−1,l} = r(m') tan(β/2) d_{m',l}; the same ratio for f */
    for (int mp = l - 1; mp > -l; mp--) {
        const sh_real q = rr[mp + l] * t;
        e = q * e;
        cur[IX(mp - 1, l)] = e;
        if (mp - 1 >= -(l - 1)) {
            f = q * f;
            cur[IX(mp - 1, l - 1)] = ((sh_real)l * cb - (sh_real)(mp - 1)) * f;
            count += 2;
        }
        count += 2;
    }
    return count;
}

/* The same edge columns for β > π/2, from the other corner upward
 * (t = cot(β/2)). */
static inline uint64_t SH_R(blanco_edges_upper)(int l, int L, int W, const sh_real *rr, sh_real t,
                                                sh_real cb, sh_real s2, const sh_real *dm1, sh_real *cur)
{
    uint64_t count = 0;
    /* the other corner: d_{−l,l} = sin²(β/2) d^{l−1}_{−(l−1),l−1} and
     * f_{−(l−1)} = d^{l−1}_{−(l−1),l−1}; upward: d_{m'+1} = d_{m'} cot(β/2) / r(m'+1) */
    sh_real e = s2 * dm1[IX(-(l - 1), l - 1)], f = dm1[IX(-(l - 1), l - 1)];
    cur[IX(-l, l)] = e;
    cur[IX(-(l - 1), l - 1)] = ((sh_real)l * cb + (sh_real)(l - 1)) * f;
    count += 1 + 2;
    for (int mp = -l; mp < l; mp++) {
        const sh_real q = t / rr[mp + 1 + l];
        e = q * e;
        cur[IX(mp + 1, l)] = e;
        if (mp + 1 <= l - 1 && mp + 1 > -(l - 1)) {
            f = q * f;
            cur[IX(mp + 1, l - 1)] = ((sh_real)l * cb - (sh_real)(mp + 1)) * f;
            count += 2;
        }
        count += 2;
    }
    return count;
}

/* The blocks from cos β, sin β, c = cos(β/2), s = sin(β/2), lower = (β ≤ π/2)
 * and the multiple angles of α, γ already in work (csa, csg; blanco_work):
 * bands 0 and 1 directly, then band l from bands l−1 and l−2, its region
 * m ≥ |m'| by eq. 64 and its edge columns by eqs. 65–68, each turned into
 * its real block. */
static int SH_R(blanco_blocks_trig)(int order, sh_real cb, sh_real sb, sh_real c, sh_real s,
                                    int lower, const void *tables, sh_real *blocks, void *work,
                                    uint64_t *mults)
{
    const int L = order - 1, W = 2 * L + 1;
    const sh_real *tab = tables;
    sh_real *g0 = work, *g1 = g0 + (size_t)W * W, *g2 = g1 + (size_t)W * W;
    sh_real *d = g2 + (size_t)W * W, *csa = d + (size_t)W * W, *csg = csa + 2 * (size_t)(L + 1);
    uint64_t count = 0;
    const sh_real c2 = c * c, s2 = s * s;
    const sh_real t = lower ? s / c : c / s;  /* tan(β/2) or cot(β/2), ≤ 1 */
    count += 2;

    /* bands 0 and 1 (eqs. 48–52, in our index order): region m ≥ |m'| */
    sh_real *dm2 = g0, *dm1 = g1, *cur = g2; /* d^{l−2}, d^{l−1}, d^l */
    dm2[IX(0, 0)] = 1;
    blocks[0] = 1;
    if (order < 2) goto done;
    const sh_real r2 = SH_SQRT((sh_real)2);
    dm1[IX(0, 0)] = cb;
    dm1[IX(0, 1)] = sb / r2;
    dm1[IX(1, 1)] = c2;
    dm1[IX(-1, 1)] = s2;
    count += 1;
    count += SH_R(blanco_block)(1, dm1, L, W, csa, csg, blocks + sh_rot_block_offset(1), d);

    for (int l = 2; l < order; l++) {
        sh__rot_band_done(l, order); /* bands 0..l−1 done */
        const int w = 2 * l + 1;
        const sh_real *ia = tab + 3 * (size_t)l * l, *bb = ia + w, *rr = bb + w;
        count += SH_R(blanco_interior)(l, L, W, ia, bb, c2, s2, lower, dm1, dm2, cur);
        if (lower) count += SH_R(blanco_edges_lower)(l, L, W, rr, t, cb, c2, dm1, cur);
        else count += SH_R(blanco_edges_upper)(l, L, W, rr, t, cb, s2, dm1, cur);
        count += SH_R(blanco_block)(l, cur, L, W, csa, csg, blocks + sh_rot_block_offset(l), d);
        sh_real *tmp = dm2;
        dm2 = dm1;
        dm1 = cur;
        cur = tmp;
    }
done:
    sh__rot_band_done(order, order);
    if (mults) *mults += count;
    return SH_OK;
}
#undef IX

/* work layout of blanco_blocks_trig: three regions, d, then csa, csg */
static sh_real *SH_R(blanco_csa)(int order, void *work)
{
    const size_t W = 2 * (size_t)order - 1;
    return (sh_real *)work + 4 * W * W;
}

int SH_R(sh__rot_blanco_blocks)(int order, const sh_rotation *rot, const void *tables,
                                sh_real *blocks, void *work, uint64_t *mults)
{
    const int L = order - 1;
    sh_real *csa = SH_R(blanco_csa)(order, work), *csg = csa + 2 * (size_t)(L + 1);
    const sh_real beta = (sh_real)rot->beta;
    SH_R(sh__rot_multiple_angles)((sh_real)rot->alpha, L, csa);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->gamma, L, csg);
    if (mults && L >= 2) *mults += 2 * (2 * (uint64_t)(L - 1) + 1); /* 2cosθ, then 2 per step m ≥ 2 */
    if (mults) *mults += 2;
    return SH_R(blanco_blocks_trig)(order, SH_COS(beta), SH_SIN(beta), SH_COS(beta / 2), SH_SIN(beta / 2),
                                    rot->beta <= M_PI / 2, tables, blocks, work, mults);
}

/* From par (rot_internal.h; a matrix or quaternion, no angle): the half
 * angles by c = √((1 + cos β)/2), s = sin β/(2c) for cos β ≥ 0 and
 * s = √((1 − cos β)/2), c = sin β/(2s) otherwise (no cancellation in either),
 * the multiple angles by the recurrence from (cos, sin). */
int SH_R(sh__rot_blanco_blocks_par)(int order, const sh_real *par, const void *tables,
                                    sh_real *blocks, void *work, uint64_t *mults)
{
    const int L = order - 1;
    sh_real *csa = SH_R(blanco_csa)(order, work), *csg = csa + 2 * (size_t)(L + 1);
    SH_R(sh__rot_multiple_angles_cs)(par[0], par[1], L, csa);
    SH_R(sh__rot_multiple_angles_cs)(par[4], par[5], L, csg);
    if (mults && L >= 2) *mults += 2 * (2 * (uint64_t)(L - 1) + 1);
    const sh_real cb = par[2], sb = par[3];
    const int lower = cb >= 0;
    sh_real c, s;
    if (lower) {
        c = SH_SQRT((1 + cb) / 2);
        s = sb / (2 * c);
    } else {
        s = SH_SQRT((1 - cb) / 2);
        c = sb / (2 * s);
    }
    return SH_R(blanco_blocks_trig)(order, cb, sb, c, s, lower, tables, blocks, work, mults);
}

#ifndef SH_REAL_FLOAT
/* ---- single band, O(l²): the m-recurrence at fixed l ([2]) -------------
 *
 * From J_± acting on the column index (derived; verified in the tests):
 *   √((l−m)(l+m+1)) d_{m',m+1} + √((l+m)(l−m+1)) d_{m',m−1}
 *        = 2 (m cosβ − m') / sinβ · d_{m'm}.                                 (M1)
 * For each row m' it runs downward, m = l, l−1, …, |m'|, seeded by (E1) at
 * m = l (and d_{m',l+1} = 0).  In m ≥ |m'| the wanted solution never decays
 * in the direction of the recurrence: the turning points of d_{m'·} are
 * m± = m' cosβ ± sinβ √((l+½)² − m'²) and m− ≤ |m'| for every β, so the run
 * crosses (at most) the evanescent zone above m+, where it is the dominant
 * solution, and then the oscillatory zone.  The rest follows from (S).
 * Scaling: the row is computed with the seed set to 1 and rescaled by
 * 2^−300 (as often as needed) whenever it exceeds 2^300; the seed itself is kept as a mantissa
 * and a power of two (a ratio recurrence along m', started at the larger
 * corner c^{2l} or s^{2l}) so that nothing underflows before the end.
 * β > π/2 is reflected to π − β (not needed for stability — see above —
 * and measured to make no difference: max error vs reference at l = 200,
 * β = π − 1e-9 is 7.3e-14 with and without it; kept so that the recurrence
 * always runs with cosβ ≥ 0).  The error near the diagonal grows like
 * l·ε (the seed product and the run both take O(l) roundings).  sinβ = 0 (to within 2l·1e−200, where the recurrence factor would
 * overflow) is exact: d = identity at β = 0 (hence the antidiagonal
 * (−1)^{l−m} δ_{m',−m} at β = π through the reflection).  */
size_t sh__rot_blanco_band_work(int l)
{
    const size_t w = 2 * (size_t)l + 1;
    return (2 * w * w + 4 * w + 4 * (size_t)(l + 1)) * sizeof(double) + w * sizeof(int);
}

int sh__rot_blanco_band_d(int l, const sh_rotation *rot, double *block, void *work)
{
    const int w = 2 * l + 1;
    double *g = work, *d = g + (size_t)w * w, *A = d + (size_t)w * w, *sm = A + w + 1,
           *csa = sm + w + 1, *csg = csa + 2 * (size_t)(l + 1);
    int *se = (int *)(csg + 2 * (size_t)(l + 1));
    /* β > π/2: d_{m'm}(β) = (−1)^{l+m'} d_{m',−m}(π−β) (derived from [3]; checked
     * against the reference); π − β with π in two doubles, so that β = π − 1e-9
     * keeps its digits. */
    const int reflect = rot->beta > M_PI / 2;
    const double beta = reflect ? (M_PI - rot->beta) + 1.2246467991473532e-16 : rot->beta;
    const double cb = cos(beta), sb = sin(beta);
    sh__rot_multiple_angles_d(rot->alpha, l, csa);
    sh__rot_multiple_angles_d(rot->gamma, l, csg);
#define GG(a, b) g[(size_t)((a) + l) * w + (size_t)((b) + l)]
    if (!(sb > 2.0 * l * 1e-200)) {
        memset(d, 0, (size_t)w * w * sizeof *d); /* β ≤ π/2 here, so β = 0: identity */
        for (int m = -l; m <= l; m++) d[(size_t)(m + l) * w + (m + l)] = 1;
    } else {
        /* seeds (E1) as sm[m'] · 2^se[m']: ratio d_{m'−1,l}/d_{m',l} = √((l+m')/(l−m'+1)) tan(β/2) */
        const double c = cos(beta / 2), s = sin(beta / 2);
        int e;
        if (c >= s) {
            double x = 1;
            int ex = 0;
            for (int k = 0; k < 2 * l; k++) { x = frexp(x * c, &e) , ex += e; }
            const double t = s / c;
            sm[2 * l] = x, se[2 * l] = ex;
            for (int mp = l; mp > -l; mp--) {
                x = frexp(x * sqrt((double)(l + mp) / (l - mp + 1)) * t, &e);
                ex += e;
                sm[mp - 1 + l] = x, se[mp - 1 + l] = ex;
            }
        } else {
            double x = 1;
            int ex = 0;
            for (int k = 0; k < 2 * l; k++) { x = frexp(x * s, &e), ex += e; }
            const double t = c / s;
            sm[0] = x, se[0] = ex;
            for (int mp = -l; mp < l; mp++) {
                x = frexp(x * sqrt((double)(l - mp) / (l + mp + 1)) * t, &e);
                ex += e;
                sm[mp + 1 + l] = x, se[mp + 1 + l] = ex;
            }
        }
        /* A[m+l] = √((l+m)(l−m+1)), m = −l..l+1 (A at m = l+1 is 0, at −l is 0) */
        for (int m = -l; m <= l + 1; m++) A[m + l] = sqrt((double)(l + m) * (l - m + 1));
        const double two_c = 2 * cb / sb, two_i = 2 / sb;
        const double BIG = 0x1p300, IBIG = 0x1p-300;
        for (int mp = -l; mp <= l; mp++) {
            const int m0 = mp < 0 ? -mp : mp;
            int k = 0;
            double f = ldexp(sm[mp + l], se[mp + l]);
            double xp = 0, x = 1; /* x_{m+1}, x_m (scaled) */
            GG(mp, l) = f;
            /* (M1) downward: x_{m−1} = ((2(m cosβ − m')/sinβ) x_m − A_{m+1} x_{m+1}) / A_m */
            for (int m = l; m > m0; m--) {
                double xn = (((double)m * two_c - (double)mp * two_i) * x - A[m + 1 + l] * xp) / A[m + l];
                xp = x;
                x = xn;
                /* a loop, not one step: near β = 0 one step can grow x by more
                 * than 2^300 (about 4l/sinβ: 1e150 at β = 1e-150), and x must be
                 * back under 2^300 before the next step or it overflows */
                if (fabs(x) > BIG) {
                    do x *= IBIG, xp *= IBIG, k++;
                    while (fabs(x) > BIG);
                    f = ldexp(sm[mp + l], se[mp + l] + 300 * k);
                }
                GG(mp, m - 1) = x * f;
            }
        }
        /* (S) */
        for (int a = -l; a <= l; a++)
            for (int b = -l; b <= l; b++) {
                const int aa = a < 0 ? -a : a, ab = b < 0 ? -b : b;
                const double sg = ((b - a) & 1) ? -1 : 1;
                double v;
                if (b >= aa) v = GG(a, b);
                else if (a >= ab) v = sg * GG(b, a);
                else if (a <= -ab) v = GG(-b, -a);
                else v = sg * GG(-a, -b);
                d[(size_t)(a + l) * w + (size_t)(b + l)] = v;
            }
    }
#undef GG
    if (reflect) {
        for (int a = -l; a <= l; a++)
            for (int b = -l; b <= l; b++)
                g[(size_t)(a + l) * w + (size_t)(b + l)] =
                    (((l + a) & 1) ? -1 : 1) * d[(size_t)(a + l) * w + (size_t)(-b + l)];
        d = g;
    }
    sh__rot_block_from_d_d(l, d, csa, csg, block);
    return SH_OK;
}

static size_t blanco_band_work(int band) { return sh__rot_blanco_band_work(band); }

static size_t blanco_tables_bytes(int order) { return blanco_table_len(order) * sizeof(double); }
const sh__rot_ops sh__rot_blanco_ops = {
    .name = "blanco",
    .tables_bytes = blanco_tables_bytes,
    .max_order = SH_ROT_BLANCO_MAX_ORDER,
    .tables_new_d = sh__rot_blanco_tables_new_d,
    .tables_new_f = sh__rot_blanco_tables_new_f,
    .tables_free = blanco_tables_free,
    .work_bytes = blanco_work,
    .blocks_d = sh__rot_blanco_blocks_d,
    .blocks_f = sh__rot_blanco_blocks_f,
    .band_d = sh__rot_blanco_band_d,
    .band_work_bytes = blanco_band_work,
    .blocks_par_d = sh__rot_blanco_blocks_par_d,
    .blocks_par_f = sh__rot_blanco_blocks_par_f,
};
#endif
