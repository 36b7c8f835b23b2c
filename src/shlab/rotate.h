/* shlab/rotate.h — rotations, rotation plans (every exact method), single bands, the MPFR
 * reference, stability.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_ROTATE_H
#define SHLAB_ROTATE_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Rotations (CONVENTIONS.md): a proper rotation R acts on functions,
 * g(s) = f(R⁻¹ s); the SH rotation matrix R_sh(R) maps the coefficients of f
 * to those of g, so R_sh(AB) = R_sh(A) R_sh(B).  Euler angles are ZYZ active:
 * R = Rz(α) Ry(β) Rz(γ).  An sh_rotation carries both the 3×3 matrix (row
 * major) and ZYZ angles that reproduce it; methods use whichever they need. */
typedef struct {
    double R[9];                /* row-major proper orthogonal matrix */
    double alpha, beta, gamma;  /* ZYZ angles, α,γ ∈ (−π, π], β ∈ [0, π] */
} sh_rotation;
int sh_rotation_from_euler(double alpha, double beta, double gamma, sh_rotation *out);
/* Unit quaternion (w,x,y,z), active.  |q| must be within 1e-6 of 1 (it is then
 * normalised) unless orthonormalize != 0 (any non-zero q is normalised). */
int sh_rotation_from_quat(const double q[4], int orthonormalize, sh_rotation *out);
/* Rotation by angle t about axis a (right-hand rule; a normalised, non-zero). */
int sh_rotation_from_axis_angle(const double axis[3], double angle, sh_rotation *out);
/* A row-major 3×3 matrix.  Refused (SH_EINVAL) when max|RᵀR − I| > 1e-6 or
 * det R < 0, unless orthonormalize != 0: then the nearest proper rotation
 * (polar factor by GSL's SVD, det fixed to +1) is used.  An accepted matrix is
 * always replaced by its polar factor (a change of ≤ 1e-6). */
int sh_rotation_from_matrix(const double M[9], int orthonormalize, sh_rotation *out);
/* The inverse rotation R → Rᵀ (the frame rotation); the angles become
 * (π−γ, β, −π−α) wrapped to (−π, π], i.e. Rz(−γ)Ry(−β)Rz(−α). */
void sh_rotation_inverse(const sh_rotation *in, sh_rotation *out);
/* ZYZ angles of a rotation matrix (Green's identities, stable at and near the
 * degenerate β = 0 and β = π: α+γ, resp. α−γ, is taken from the well-conditioned
 * entries).  The matrix is not checked. */
void sh_euler_from_matrix(const double R[9], double *alpha, double *beta, double *gamma);
/* Product C = A·B of two rotations (matrices multiplied, angles re-extracted). */
void sh_rotation_compose(const sh_rotation *A, const sh_rotation *B, sh_rotation *C);
/* The rotation as a unit quaternion (w ≥ 0; Shepperd's method) and as axis
 * and angle ∈ [0, π] (axis (0,0,1) for the identity). */
void sh_rotation_to_quat(const sh_rotation *rot, double q[4]);
void sh_rotation_to_axis_angle(const sh_rotation *rot, double axis[3], double *angle);

/* Block-diagonal storage of an SH rotation of order n: band l is a
 * (2l+1)×(2l+1) row-major block (rows and columns m = −l..l) starting at
 * sh_rot_block_offset(l); sh_rot_block_offset(n) values in all
 * (= n(4n²−1)/3, the non-zeros of the matrix). */
static inline size_t sh_rot_block_offset(int l)
{
    return (size_t)l * (size_t)(2 * l - 1) * (size_t)(2 * l + 1) / 3;
}

typedef enum {
    SH_ROT_Z = 0,     /* rotation about z only: O(n²), Chebyshev multiple angles */
    SH_ROT_IVANIC,    /* Ivanic-Ruedenberg recursion (1996, corrections 1998) */
    SH_ROT_ZXZXZ,     /* Kautz et al.: Z(α) X₋₉₀ Z(β) X₊₉₀ Z(γ), applied sparsely */
    SH_ROT_CHOI,      /* Choi et al. 1999 complex recursion, converted to real */
    SH_ROT_BLANCO,    /* Blanco, Flórez & Bermejo 1997 recursion for d^l(β) */
    SH_ROT_WIGNER,    /* direct Wigner small-d sum in long double */
    SH_ROT_REFERENCE, /* the same sum in MPFR, ≥ 30 correct digits */
    SH_ROT_TAYLOR1,   /* approximate: Z(α)·(I + βJ)·Z(γ)  (Krivánek et al. 2005) */
    SH_ROT_TAYLOR15,  /* approximate: Z(α)·(I + βJ + β²/2·diag(J²))·Z(γ) */
    SH_ROT_TAYLOR2,   /* approximate: Z(α)·(I + βJ + β²/2·J²)·Z(γ) */
    SH_ROT_NMETHODS
} sh_rot_method;
typedef enum { SH_PREC_DOUBLE = 0, SH_PREC_FLOAT = 1 } sh_precision;
const char *sh_rot_method_name(sh_rot_method m);
int sh_rot_method_parse(const char *s, sh_rot_method *out);
const char *sh_precision_name(sh_precision p);
int sh_precision_parse(const char *s, sh_precision *out);
/* Largest order a method accepts (the direct sums use factorial tables);
 * 0 if the method is not built in. */
int sh_rot_method_max_order(sh_rot_method m);
/* 1 for the exact methods, 0 for the Taylor approximations. */
int sh_rot_method_is_exact(sh_rot_method m);

/* A rotation plan: create once for (order, method, precision, convention) —
 * per-order tables (X±90 blocks, recursion coefficients) are built here —
 * then set a rotation and apply it to many vectors.  Not thread-safe; one
 * plan per thread.  Float plans compute and apply in float arithmetic;
 * vectors cross the interface as double. */
typedef struct sh_rot_plan sh_rot_plan;
int sh_rot_plan_create(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                       sh_rot_plan **out);
void sh_rot_plan_free(sh_rot_plan *p);
/* Set the rotation (computes the block matrix, or for ZXZXZ the angles). */
int sh_rot_plan_set(sh_rot_plan *p, const sh_rotation *rot);
/* out = R_sh in (in-place allowed).  in and out have order² entries. */
int sh_rot_plan_apply(sh_rot_plan *p, const double *in, double *out);
/* The blocks of the current rotation (sh_rot_block_offset(order) doubles). */
int sh_rot_plan_blocks(sh_rot_plan *p, double *blocks);
/* Multiplications executed (counted by the kernels' loops, not by formula) by
 * the last sh_rot_plan_set and by one sh_rot_plan_apply. */
void sh_rot_plan_mults(const sh_rot_plan *p, uint64_t *set_mults, uint64_t *apply_mults);

/* One band only (l = band), as a (2l+1)² row-major block, for methods that
 * can compute a band without the lower ones (blanco, wigner, reference; the
 * others compute bands 0..l and keep the last). */
int sh_rot_band(int band, sh_rot_method method, sh_precision prec, sh_convention conv,
                const sh_rotation *rot, double *block);
/* Band by band, l = 0..lmax, in O(lmax²) memory where the method allows it
 * (a streaming recursion, or a single-band routine); otherwise through a
 * plan of order lmax+1, refused (SH_ENOTSUP) if its blocks would exceed
 * 2 GiB.  Each call of next writes band *l (0, 1, 2, ...) into block. */
typedef struct sh_rot_bands sh_rot_bands;
int sh_rot_bands_create(sh_rot_method method, sh_precision prec, sh_convention conv, int lmax,
                        const sh_rotation *rot, sh_rot_bands **out);
int sh_rot_bands_next(sh_rot_bands *it, int *l, double *block);
/* Band l (≥ every band asked before): single-band methods compute only it,
 * streaming ones pass through the bands in between. */
int sh_rot_bands_get(sh_rot_bands *it, int l, double *block);
void sh_rot_bands_free(sh_rot_bands *it);
/* Dense order²×order² matrix (row-major) from blocks. */
void sh_rot_blocks_to_dense(int order, const double *blocks, double *dense);
/* Reference band block: MPFR with precision chosen for `digits` (≥ 30)
 * correct significant digits after the cancellation of the direct sum;
 * rounded to double and to long double. */
int sh_rot_reference_band(int band, sh_convention conv, const sh_rotation *rot, int digits,
                          double *block, long double *block_ld);
/* Stability of a method, band by band (rotation_stability.c), over the
 * fixed rotation set of sh_rot_stability_set: for each band the maximum over
 * the set of
 *   orth  max|R Rᵀ − I| (exactly for l ≤ exact_max; above, the probe
 *         estimate max|Rᵀ(R v) − v| over two seeded unit vectors v),
 *   hom   max|R(a)(R(b) v) − R(ab) v| over two unit probes, pairs (a, b) of
 *         the set (b three places after a, cyclically); the probes are
 *         seeded by the band, so a row does not depend on the other bands,
 *   ref   max|R − R_reference| (MPFR) for l ≤ ref_max, else not computed.
 * Rotations a method refuses (z: β ≠ 0) are left out of its set. */
typedef struct {
    int band;
    double orth, hom, ref;
    int orth_exact, have_ref;
    int broken; /* some entry was not finite (overflow): the numbers are void */
} sh_rot_stability_row;
#define SH_ROT_STABILITY_NSET 10
/* The set: β = 0, 1e-12, π/2, π−1e-9, π, gimbal-lock pairs (α, 0, −α) and
 * (π/2, π, π/2), tiny β with α+γ = 0, and two seeded random rotations; names
 * (may be NULL) get a short label for each. */
int sh_rot_stability_set(sh_rotation set[SH_ROT_STABILITY_NSET], const char *names[SH_ROT_STABILITY_NSET]);
/* Orthogonality error of one w×w block B: max|B Bᵀ − I| exactly (exact ≠ 0,
 * O(w³)), or the two-probe estimate max|Bᵀ(B v) − v| over two fixed seeded
 * unit vectors v (O(w²); a lower bound of the exact value's order).  A
 * non-finite entry gives +Inf. */
double sh_rot_block_orthogonality(const double *B, int w, int exact);
typedef int (*sh_rot_stability_cb)(const sh_rot_stability_row *row, void *ctx);
/* Rows for the bands listed (increasing; NULL: every band 0..lmax).  The
 * sweep stops after the first row whose orth exceeds stop_above (> 0), or
 * that is broken; a callback returning non-zero also stops it. */
int sh_rot_stability(sh_rot_method method, sh_precision prec, sh_convention conv, int lmax,
                     const int *bands, int nbands, int ref_max, int exact_max, double stop_above,
                     sh_rot_stability_cb cb, void *ctx);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_ROTATE_H */
