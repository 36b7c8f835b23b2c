/* rot_blocks.c — pieces every SH rotation method shares (precision-generic,
 * see rot_real.h): block × vector, multiple angles, the z rotation of a band,
 * the real block from a Wigner small-d matrix, the nocs sign flip.
 *
 * References
 *  [1] docs/CONVENTIONS.md: g(s) = f(R⁻¹s), R = Rz(α)Ry(β)Rz(γ), real SH with CS phase.
 *  [2] D^l_{m'm}(α,β,γ) = e^{−im'α} d^l_{m'm}(β) e^{−imγ}, Y_l^m(R⁻¹s) =
 *      Σ_{m'} Y_l^{m'}(s) D^l_{m'm}(R)  (Edmonds / Wikipedia "Wigner D-matrix").
 *
 * Derivation of the real R_Y block (sh__rot_block_from_d).  With complex
 * Y^m (CS phase) and the real basis y = U·Y,
 *   y^m  = (Y^m + (−1)^m Y^{−m})/√2,  y^{−m} = (Y^m − (−1)^m Y^{−m})/(i√2)  (m>0),
 * the real matrix is R = conj(U) D Uᵀ.  For β alone D = d is real, and with
 * d_{m'm} = (−1)^{m−m'} d_{mm'} = d_{−m,−m'} the four terms of each entry
 * collapse to the formulas in rot_internal.h; entries that pair a cosine with
 * a sine function are purely imaginary in conj(U) d Uᵀ and hence zero.  The
 * test suite checks the result by evaluating the rotated functions pointwise.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

void SH_R(sh__rot_blocks_apply)(int order, const sh_real *blocks, const sh_real *in, sh_real *out,
                                uint64_t *mults)
{
    /* per band: out_l = B_l · in_l, (2l+1)² multiplications.  Each row is a
     * dot product vectorised 16 bytes wide (partial sums in 2 doubles / 4
     * floats, added at the end: not the left-to-right order of a scalar
     * loop, the same accuracy).  An earlier form, four rows at a time with
     * four scalar accumulators, was packed by -O3 -march=native into one
     * vector of the four rows' entries gathered column by column, and ran
     * slower than with -O2 (docs/rotation.md "Rotation speed"). */
    uint64_t count = 0;
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        const sh_real *B = blocks + sh_rot_block_offset(l);
        const sh_real *x = in + (size_t)l * l;
        sh_real *y = out + (size_t)l * l;
        for (int r = 0; r < w; r++) {
            const sh_real *row = B + (size_t)r * w;
            sh_real acc = 0;
            SH_PRAGMA(omp simd simdlen(SH_SIMD_LANES16) reduction(+ : acc))
            for (int c = 0; c < w; c++) acc += row[c] * x[c];
            y[r] = acc;
        }
        count += (uint64_t)w * w;
    }
    if (mults) *mults += count;
}

/* cos(mθ) = 2cosθ·cos((m−1)θ) − cos((m−2)θ); likewise sin, from c1, s1.
 * The recurrence's rounding error grows like m·ε (2e-14 at m = 200 in
 * double), so with reseed every SH_ANGLE_RESEED steps two consecutive pairs
 * are taken from libm and the recurrence restarts from it.  The argument
 * m·θ is split exactly, p + e with e = fma(m, θ, −p), and
 * cos(p + e) = cos p − e sin p (as sh__rot_halfpi_angles): libm of the
 * rounded product alone was off by ~m·θ·1e-16, 8e-12 on the coefficients of
 * the z rotation at order 4097 (tests/core/test_ranges.c, rot_z_top). */
static void SH_R(angles_rec)(sh_real c1, sh_real s1, int reseed, sh_real theta, int mmax, sh_real *cs)
{
    const sh_real two_c = 2 * c1;
    cs[0] = 1;
    cs[1] = 0;
    if (mmax < 1) return;
    cs[2] = c1;
    cs[3] = s1;
    for (int m = 2; m <= mmax; m++) {
        if (reseed && m % SH_ANGLE_RESEED <= 1 && m > 1) { /* two consecutive seeds restart it */
            const double p = (double)m * (double)theta, e = fma((double)m, (double)theta, -p);
            const double c = cos(p), s = sin(p);
            cs[2 * m] = (sh_real)(c - s * e);
            cs[2 * m + 1] = (sh_real)(s + c * e);
            continue;
        }
        cs[2 * m] = two_c * cs[2 * (m - 1)] - cs[2 * (m - 2)];
        cs[2 * m + 1] = two_c * cs[2 * (m - 1) + 1] - cs[2 * (m - 2) + 1];
    }
}

void SH_R(sh__rot_multiple_angles)(sh_real theta, int mmax, sh_real *cs)
{
    SH_R(angles_rec)(SH_COS(theta), SH_SIN(theta), 1, theta, mmax, cs);
}

void SH_R(sh__rot_multiple_angles_cs)(sh_real c1, sh_real s1, int mmax, sh_real *cs)
{
    /* the recurrence of sh__rot_multiple_angles from the seeds c1, s1 (a
     * rotation given as a matrix: no angle); past the reseeding distance the
     * angle is taken once, θ = atan2(s1, c1), and the reseeded routine used */
    if (mmax >= SH_ANGLE_RESEED) SH_R(sh__rot_multiple_angles)((sh_real)atan2(s1, c1), mmax, cs);
    else SH_R(angles_rec)(c1, s1, 0, 0, mmax, cs);
}

void SH_R(sh__rot_z_band)(int l, const sh_real *cs, sh_real *c, uint64_t *mults)
{
    /* c points at band l's first coefficient (m = −l); index m+l. */
    for (int m = 1; m <= l; m++) {
        const sh_real cm = cs[2 * m], sm = cs[2 * m + 1];
        const sh_real a = c[l + m], b = c[l - m];
        c[l + m] = cm * a - sm * b;
        c[l - m] = sm * a + cm * b;
    }
    if (mults) *mults += 4u * (uint64_t)l;
}

void SH_R(sh__rot_block_from_d)(int l, const sh_real *d, const sh_real *csa, const sh_real *csg,
                                sh_real *block)
{
    const int w = 2 * l + 1;
    const sh_real r2 = SH_SQRT((sh_real)2);
#define D(mp, m) d[(size_t)((mp) + l) * w + (size_t)((m) + l)]
#define B(mp, m) block[(size_t)((mp) + l) * w + (size_t)((m) + l)]
    /* R_Y(β) in the real basis (formulas in rot_internal.h) */
    B(0, 0) = D(0, 0);
    for (int m = 1; m <= l; m++) {
        B(0, m) = r2 * D(0, m);
        B(0, -m) = 0;
        B(m, 0) = r2 * D(m, 0);
        B(-m, 0) = 0;
    }
    for (int mp = 1; mp <= l; mp++)
        for (int m = 1; m <= l; m++) {
            const sh_real a = D(mp, m), b = (m & 1) ? -D(mp, -m) : D(mp, -m);
            B(mp, m) = a + b;
            B(-mp, -m) = a - b;
            B(mp, -m) = 0;
            B(-mp, m) = 0;
        }
    /* Z(α) from the left: rows (m', −m') mix; Z(γ) from the right: columns.
     * Left:  [c_{m'}; c_{−m'}] ← [[cos, −sin], [sin, cos]](m'α) [c_{m'}; c_{−m'}]
     * Right: B·Z(γ): column m ← cos(mγ) B[:,m] + sin(mγ) B[:,−m],
     *                column −m ← −sin(mγ) B[:,m] + cos(mγ) B[:,−m]. */
    for (int mp = 1; mp <= l; mp++) {
        const sh_real c = csa[2 * mp], s = csa[2 * mp + 1];
        for (int m = -l; m <= l; m++) {
            const sh_real p = B(mp, m), q = B(-mp, m);
            B(mp, m) = c * p - s * q;
            B(-mp, m) = s * p + c * q;
        }
    }
    for (int m = 1; m <= l; m++) {
        const sh_real c = csg[2 * m], s = csg[2 * m + 1];
        for (int mp = -l; mp <= l; mp++) {
            const sh_real p = B(mp, m), q = B(mp, -m);
            B(mp, m) = c * p + s * q;
            B(mp, -m) = -s * p + c * q;
        }
    }
#undef D
#undef B
}

void SH_R(sh__rot_band_nocs)(int l, sh_real *B)
{
    const int w = 2 * l + 1;
    for (int mp = -l; mp <= l; mp++)
        for (int m = -l; m <= l; m++)
            if ((mp ^ m) & 1) B[(size_t)(mp + l) * w + (size_t)(m + l)] = -B[(size_t)(mp + l) * w + (size_t)(m + l)];
}

void SH_R(sh__rot_blocks_nocs)(int order, sh_real *blocks)
{
    for (int l = 1; l < order; l++) SH_R(sh__rot_band_nocs)(l, blocks + sh_rot_block_offset(l));
}
