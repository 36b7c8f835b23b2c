/* rot_zxzxz.c — the `zxzxz` method: R_sh = Z(α) · X₋₉₀ · Z(β) · X₊₉₀ · Z(γ),
 * applied sparsely (precision-generic, see rot_real.h).
 *
 * References
 *  [1] J. Kautz, P.-P. Sloan, J. Snyder, "Fast, Arbitrary BRDF Shading for
 *      Low-Frequency Lighting Using Spherical Harmonics", EGWR 2002, Sec. 3
 *      and appendix (the ZXZXZ decomposition).
 *  [2] J. Krivánek et al. 2005, Sec. 3.1 (cost n(2n²+18n−14)/3 quoted for [1]).
 *  [3] Wigner d: d^l_{m'm}(β) as in rot_wigner.c (Edmonds 4.1.23).
 *  [4] Trapani & Navaza 2006 (d(π/2) by recursion); the recursion used here is
 *      the three-term one in m' below, run in the stable direction.
 *
 * Decomposition (our conventions, CONVENTIONS.md).  Ry(β) = Rx(−90°) Rz(β)
 * Rx(+90°) (the conjugated z axis Rx(−90°)ẑ is ŷ), and R_sh is a
 * homomorphism, so R_Y(β) = X₋₉₀ Z(β) X₊₉₀ with X_θ = R_sh(Rx(θ)), and
 *   R_sh(Rz(α)Ry(β)Rz(γ)) = Z(α) X₋₉₀ Z(β) X₊₉₀ Z(γ).
 * X₊₉₀ is generated, per band, from Rx(θ) = Rz(−90°) Ry(θ) Rz(+90°) (Rz(−90°)ŷ
 * = x̂): X₊₉₀ = Z(−90°) R_Y(π/2) Z(+90°), i.e. sh__rot_block_from_d with
 * d^l(π/2) and the exact multiple angles cos, sin(±m·90°) ∈ {0, ±1}.
 * X₋₉₀ = X₊₉₀⁻¹ = X₊₉₀ᵀ, applied as the transpose of the same table.
 *
 * d^l(π/2) (in long double, then rounded):
 *   d_{l,m} = (−1)^{l−m} √(C(2l, l+m)) / 2^l          ([3] with m' = l, one term)
 *     computed as e_0 = √(Π_{k=1..l} (2k−1)/(2k)), e_{±m} = e_{m−1} √((l−m+1)/(l+m));
 *   √((l−m')(l+m'+1)) d_{m'+1,m} + √((l+m')(l−m'+1)) d_{m'−1,m} = 2m d_{m'm}
 *     (the J± recurrence at β = π/2, where cosβ = 0; checked numerically
 *     against the direct sum), run downward from m' = l to m' = |m|: this
 *     goes from the classically forbidden region (m² + m'² > l², where d grows
 *     as m' decreases) into the allowed one — the stable direction.
 *   The rest from d_{m'm} = (−1)^{m'−m} d_{mm'} = d_{−m,−m'}.
 *
 * Structural zeros of X₊₉₀ (proved in tests/test_rot_zxzxz.c against the
 * MPFR reference of Rx(90°), and re-checked exactly by tables_new).  Call m
 * "cos type" if its real function after Z(90°) is a cosine: m ≥ 0 even or
 * m < 0 odd; otherwise "sin type".  R_Y(β) never mixes cos with sin (the
 * cross terms of sh__rot_block_from_d), and at β = π/2,
 * d_{m',−m} = (−1)^{l+m'} d_{m'm} makes the cos-cos entries vanish for
 * l+|m|+|m'| odd and the sin-sin entries for l+|m|+|m'| even.  Hence row m'
 * of X₊₉₀ has non-zeros only in the columns m = s·(q + 2k), k = 0, 1, …:
 *   cos type, l+|m'| even: q = 0, s = +   (m = 0, 2, 4, …)
 *   cos type, l+|m'| odd:  q = 1, s = −   (m = −1, −3, …)
 *   sin type, l+|m'| even: q = 1, s = +   (m = 1, 3, …)
 *   sin type, l+|m'| odd:  q = 2, s = −   (m = −2, −4, …)
 * which is l² + l + 1 of the (2l+1)² entries (about a quarter), stored row
 * by row with no index arrays.
 *
 * Cost of one apply (counted in the loops): per band l, three z rotations
 * (4l each) and two X products (l² + l + 1 each) = the n(2n²+18n−14)/3 of
 * [2] summed over l < n, plus the multiple angles of α, β, γ by the
 * Chebyshev recurrence, 3·2(n−2) for n ≥ 3, which the paper's count omits.
 * blocks (for rotmat) runs the band pipeline on each unit vector: O(l³) per
 * band, counted the same way.
 *
 * Memory.  A plan's tables hold Σ_{l<n} (l²+l+1) = n(n²+2)/3 values (X₋₉₀
 * shares them), ≈ 360 MB in double at order 512.  The single-band path
 * (sh_rot_band) builds X₊₉₀ of that band only, O(l²) memory, so band 1000
 * takes ~3 s; hence max_order is SHLAB_MAX_ORDER and a large plan simply
 * fails with SH_ENOMEM if the tables do not fit.
 */
#include "rot_internal.h"
#include "rot_real.h"

SH__ROT_DECLARE_BLOCKS(zxzxz);
SH__ROT_DECLARE_APPLY(zxzxz);
SH__ROT_DECLARE_TABLES(zxzxz);

#include <stdlib.h>
#include <string.h>

#define ZX_MAX_ORDER SHLAB_MAX_ORDER

/* Compact X₊₉₀ storage: band l's l²+l+1 non-zeros start at zx_off(l). */
static inline size_t zx_off(int l) { return (size_t)l * ((size_t)l * l + 2) / 3; }

/* The non-zero columns of row mp of band l: m = s·(q + 2k), k < cnt. */
static inline int zx_row(int l, int mp, int *q, int *s)
{
    const int amp = mp < 0 ? -mp : mp;
    const int cos_type = mp >= 0 ? !(amp & 1) : (amp & 1);
    const int odd = (l + amp) & 1;
    if (cos_type) {
        *q = odd ? 1 : 0;
        *s = odd ? -1 : 1;
    } else {
        *q = odd ? 2 : 1;
        *s = odd ? -1 : 1;
    }
    return *q <= l ? (l - *q) / 2 + 1 : 0;
}

typedef struct {
    int order;
    sh_real *x; /* X₊₉₀ non-zeros, zx_off(order) values */
} zx_tables;

#ifndef SH_REAL_FLOAT
/* d^l(π/2) into d[(m'+l)(2l+1) + (m+l)] (long double work ld[(2l+1)² + 2l+1]). */
static void zx_dpi2(int l, long double *ld, double *d)
{
    const int w = 2 * l + 1;
    long double *D = ld, *e = ld + (size_t)w * w;
#define DD(mp, m) D[(size_t)((mp) + l) * w + (size_t)((m) + l)]
    /* e_m = √(C(2l, l+m)) / 2^l */
    long double e0sq = 1;
    for (int k = 1; k <= l; k++) e0sq *= (long double)(2 * k - 1) / (2 * k);
    e[l] = sqrtl(e0sq);
    for (int m = 1; m <= l; m++) e[l + m] = e[l - m] = e[l + m - 1] * sqrtl((long double)(l - m + 1) / (l + m));
    for (int m = -l; m <= l; m++) {
        const int am = m < 0 ? -m : m;
        DD(l, m) = ((l - m) & 1) ? -e[l + m] : e[l + m];
        /* d_{m'−1,m} = (2m d_{m'm} − √((l−m')(l+m'+1)) d_{m'+1,m}) / √((l+m')(l−m'+1)) */
        for (int mp = l; mp > am; mp--) {
            long double v = 2.0L * m * DD(mp, m);
            if (mp < l) v -= sqrtl((long double)(l - mp) * (l + mp + 1)) * DD(mp + 1, m);
            DD(mp - 1, m) = v / sqrtl((long double)(l + mp) * (l - mp + 1));
        }
    }
    for (int mp = -l; mp <= l; mp++)
        for (int m = -l; m <= l; m++) {
            const int amp = mp < 0 ? -mp : mp, am = m < 0 ? -m : m;
            if (mp >= am) continue; /* computed above */
            if (m > amp) DD(mp, m) = ((mp - m) & 1) ? -DD(m, mp) : DD(m, mp); /* (−1)^{m'−m} d_{mm'} */
            else DD(mp, m) = DD(-m, -mp);                                     /* m < 0, −m > |m'| */
            (void)am;
        }
    for (size_t i = 0; i < (size_t)w * w; i++) d[i] = (double)D[i];
#undef DD
}

/* The dense X₊₉₀ block of band l (double) into X; ws has zx_gen_work(l). */
static size_t zx_gen_work(int l)
{
    const size_t w = 2 * (size_t)l + 1;
    return (w * w + w) * sizeof(long double) + (w * w + 4 * (size_t)(l + 1)) * sizeof(double);
}
static void zx_xplus_dense(int l, void *ws, double *X)
{
    const size_t w = 2 * (size_t)l + 1;
    long double *ld = ws;
    double *d = (double *)(ld + w * w + w), *csa = d + w * w, *csg = csa + 2 * (l + 1);
    zx_dpi2(l, ld, d);
    /* exact cos, sin of m·(−90°) (α) and m·(+90°) (γ) */
    static const double c4[4] = {1, 0, -1, 0}, s4[4] = {0, 1, 0, -1};
    for (int m = 0; m <= l; m++) {
        csa[2 * m] = c4[m & 3];
        csa[2 * m + 1] = -s4[m & 3];
        csg[2 * m] = c4[m & 3];
        csg[2 * m + 1] = s4[m & 3];
    }
    sh__rot_block_from_d_d(l, d, csa, csg, X);
}

/* Build the compact tables; checks that every entry outside the structural
 * pattern is exactly zero (else SH_EINVAL: the pattern derivation is wrong). */
static int zx_tables_build(int order, double *xd, float *xf)
{
    const int L = order - 1;
    void *ws = malloc(zx_gen_work(L));
    double *X = malloc((size_t)(2 * L + 1) * (2 * L + 1) * sizeof *X);
    unsigned char *in = malloc((size_t)(2 * L + 1));
    int st = SH_OK;
    if (!ws || !X || !in) st = sh_error(SH_ENOMEM, "zxzxz: out of memory (tables, order %d)", order);
    for (int l = 0; l < order && st == SH_OK; l++) {
        const int w = 2 * l + 1;
        zx_xplus_dense(l, ws, X);
        size_t k = zx_off(l);
        for (int mp = -l; mp <= l; mp++) {
            int q, s;
            const int cnt = zx_row(l, mp, &q, &s);
            memset(in, 0, (size_t)w);
            for (int j = 0; j < cnt; j++) {
                const int m = s * (q + 2 * j);
                in[m + l] = 1;
                const double v = X[(size_t)(mp + l) * w + (size_t)(m + l)];
                if (xd) xd[k] = v;
                if (xf) xf[k] = (float)v;
                k++;
            }
            for (int m = -l; m <= l; m++)
                if (!in[m + l] && X[(size_t)(mp + l) * w + (size_t)(m + l)] != 0)
                    st = sh_error(SH_EINVAL, "zxzxz: X+90 band %d entry (%d,%d) outside the zero pattern",
                                  l, mp, m);
        }
        if (st == SH_OK && k != zx_off(l + 1))
            st = sh_error(SH_EINVAL, "zxzxz: band %d has %zu non-zeros, expected %d", l,
                          k - zx_off(l), l * l + l + 1);
    }
    free(ws);
    free(X);
    free(in);
    return st;
}

static int zx_tables_new(int order, int single, void **tables)
{
    *tables = NULL;
    zx_tables *T = malloc(sizeof *T);
    if (!T) return sh_error(SH_ENOMEM, "zxzxz: out of memory (tables)");
    T->order = order;
    T->x = malloc(zx_off(order) * (single ? sizeof(float) : sizeof(double)));
    if (!T->x) {
        free(T);
        return sh_error(SH_ENOMEM, "zxzxz: out of memory (tables, order %d)", order);
    }
    int st = zx_tables_build(order, single ? NULL : (double *)T->x, single ? (float *)T->x : NULL);
    if (st) {
        free(T->x);
        free(T);
        return st;
    }
    *tables = T;
    return SH_OK;
}
int sh__rot_zxzxz_tables_new_d(int order, void **tables) { return zx_tables_new(order, 0, tables); }
int sh__rot_zxzxz_tables_new_f(int order, void **tables) { return zx_tables_new(order, 1, tables); }

/* The dense X₊₉₀ block of band l as generated (for the tests). */
int sh__rot_zxzxz_xplus_band(int l, double *X);
int sh__rot_zxzxz_xplus_band(int l, double *X)
{
    void *ws = malloc(zx_gen_work(l));
    if (!ws) return sh_error(SH_ENOMEM, "zxzxz: out of memory");
    zx_xplus_dense(l, ws, X);
    free(ws);
    return SH_OK;
}
#endif

/* y = X₊₉₀ x for band l (gather along each row's non-zeros). */
static void SH_R(zx_xplus)(int l, const sh_real *X, const sh_real *x, sh_real *y)
{
    for (int mp = -l; mp <= l; mp++) {
        int q, s;
        const int cnt = zx_row(l, mp, &q, &s);
        sh_real acc = 0;
        /* row m': Σ_k X[m', s(q+2k)] x[s(q+2k)] */
        if (s > 0)
            for (int k = 0; k < cnt; k++) acc += X[k] * x[l + q + 2 * k];
        else
            for (int k = 0; k < cnt; k++) acc += X[k] * x[l - q - 2 * k];
        X += cnt;
        y[mp + l] = acc;
    }
}

/* y = X₋₉₀ x = X₊₉₀ᵀ x for band l (scatter along each row's non-zeros). */
static void SH_R(zx_xminus)(int l, const sh_real *X, const sh_real *x, sh_real *y)
{
    for (int m = 0; m < 2 * l + 1; m++) y[m] = 0;
    for (int mp = -l; mp <= l; mp++) {
        int q, s;
        const int cnt = zx_row(l, mp, &q, &s);
        const sh_real xv = x[mp + l];
        if (s > 0)
            for (int k = 0; k < cnt; k++) y[l + q + 2 * k] += X[k] * xv;
        else
            for (int k = 0; k < cnt; k++) y[l - q - 2 * k] += X[k] * xv;
        X += cnt;
    }
}

/* One band: c (2l+1 values, in place) ← Z(α) X₋ Z(β) X₊ Z(γ) c; tmp has 2l+1. */
static void SH_R(zx_band)(int l, const sh_real *X, const sh_real *csa, const sh_real *csb,
                          const sh_real *csg, sh_real *c, sh_real *tmp)
{
    SH_R(sh__rot_z_band)(l, csg, c, NULL);   /* Z(γ) */
    SH_R(zx_xplus)(l, X, c, tmp);            /* X₊₉₀ */
    SH_R(sh__rot_z_band)(l, csb, tmp, NULL); /* Z(β) */
    SH_R(zx_xminus)(l, X, tmp, c);           /* X₋₉₀ = X₊₉₀ᵀ */
    SH_R(sh__rot_z_band)(l, csa, c, NULL);   /* Z(α) */
}

/* multiplications of zx_band: 3 z rotations (4l) + 2 X products (l²+l+1) */
static uint64_t zx_band_mults(int l) { return 12u * (uint64_t)l + 2u * ((uint64_t)l * l + l + 1); }

/* work: csa, csb, csg (2(order+1) each), c, tmp (2·order−1 each) */
static void SH_R(zx_angles)(int order, const sh_rotation *rot, sh_real *ws, uint64_t *count)
{
    sh_real *csa = ws, *csb = csa + 2 * (order + 1), *csg = csb + 2 * (order + 1);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->alpha, order - 1, csa);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->beta, order - 1, csb);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->gamma, order - 1, csg);
    if (order > 2) *count += 3u * 2u * (uint64_t)(order - 2); /* recurrence, m ≥ 2 */
}

void SH_R(sh__rot_zxzxz_apply)(int order, const sh_rotation *rot, const void *tables,
                               const sh_real *in, sh_real *out, void *work, uint64_t *mults)
{
    const zx_tables *T = tables;
    sh_real *ws = work;
    const size_t na = 2 * (size_t)(order + 1);
    sh_real *csa = ws, *csb = csa + na, *csg = csb + na, *tmp = csg + na;
    uint64_t count = 0;
    SH_R(zx_angles)(order, rot, ws, &count);
    if (out != in) memcpy(out, in, (size_t)order * order * sizeof *out);
    for (int l = 0; l < order; l++) {
        SH_R(zx_band)(l, T->x + zx_off(l), csa, csb, csg, out + (size_t)l * l, tmp);
        count += zx_band_mults(l);
    }
    if (mults) *mults += count;
}

#ifndef SH_REAL_FLOAT
/* One band without the lower ones (double): X₊₉₀ of band l alone (no
 * per-order tables), then the block column by column.  O(l²) memory. */
static size_t zx_band_work(int l)
{
    const size_t w = 2 * (size_t)l + 1, nnz = (size_t)l * l + l + 1;
    return zx_gen_work(l) + (w * w + nnz + 6 * (size_t)(l + 1) + 2 * w) * sizeof(double);
}
static int zx_band_double(int l, const sh_rotation *rot, double *block, void *work)
{
    const int w = 2 * l + 1;
    double *X = (double *)((char *)work + zx_gen_work(l)), *xc = X + (size_t)w * w;
    double *csa = xc + ((size_t)l * l + l + 1), *csb = csa + 2 * (l + 1), *csg = csb + 2 * (l + 1);
    double *col = csg + 2 * (l + 1), *tmp = col + w;
    zx_xplus_dense(l, work, X);
    size_t k = 0;
    for (int mp = -l; mp <= l; mp++) {
        int q, s;
        const int cnt = zx_row(l, mp, &q, &s);
        for (int j = 0; j < cnt; j++) xc[k++] = X[(size_t)(mp + l) * w + (size_t)(l + s * (q + 2 * j))];
    }
    sh__rot_multiple_angles_d(rot->alpha, l, csa);
    sh__rot_multiple_angles_d(rot->beta, l, csb);
    sh__rot_multiple_angles_d(rot->gamma, l, csg);
    for (int j = 0; j < w; j++) {
        for (int i = 0; i < w; i++) col[i] = 0;
        col[j] = 1;
        zx_band_d(l, xc, csa, csb, csg, col, tmp);
        for (int i = 0; i < w; i++) block[(size_t)i * w + j] = col[i];
    }
    return SH_OK;
}
#endif

int SH_R(sh__rot_zxzxz_blocks)(int order, const sh_rotation *rot, const void *tables,
                               sh_real *blocks, void *work, uint64_t *mults)
{
    const zx_tables *T = tables;
    if (!T || T->order < order) return sh_error(SH_EINVAL, "zxzxz: tables missing or too small");
    sh_real *ws = work;
    const size_t na = 2 * (size_t)(order + 1);
    sh_real *csa = ws, *csb = csa + na, *csg = csb + na, *tmp = csg + na, *col = tmp + 2 * order;
    uint64_t count = 0;
    SH_R(zx_angles)(order, rot, ws, &count);
    /* column j of band l's block = the band rotation of the unit vector e_j */
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        sh_real *B = blocks + sh_rot_block_offset(l);
        for (int j = 0; j < w; j++) {
            for (int i = 0; i < w; i++) col[i] = 0;
            col[j] = 1;
            SH_R(zx_band)(l, T->x + zx_off(l), csa, csb, csg, col, tmp);
            for (int i = 0; i < w; i++) B[(size_t)i * w + j] = col[i];
            count += zx_band_mults(l);
        }
    }
    if (mults) *mults += count;
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static void zx_tables_free(void *tables)
{
    zx_tables *T = tables;
    if (T) free(T->x);
    free(T);
}
static size_t zx_work(int order)
{
    return (6 * (size_t)(order + 1) + 4 * (size_t)order) * sizeof(double);
}
const sh__rot_ops sh__rot_zxzxz_ops = {
    .name = "zxzxz",
    .max_order = ZX_MAX_ORDER,
    .tables_new_d = sh__rot_zxzxz_tables_new_d,
    .tables_new_f = sh__rot_zxzxz_tables_new_f,
    .tables_free = zx_tables_free,
    .work_bytes = zx_work,
    .blocks_d = sh__rot_zxzxz_blocks_d,
    .blocks_f = sh__rot_zxzxz_blocks_f,
    .apply_d = sh__rot_zxzxz_apply_d,
    .apply_f = sh__rot_zxzxz_apply_f,
    .band_d = zx_band_double,
    .band_work_bytes = zx_band_work,
};
#endif
