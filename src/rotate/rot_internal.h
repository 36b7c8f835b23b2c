/* rot_internal.h — what the rotation kernels (src/rot_*.c, compiled once per
 * precision, see rot_real.h) share with the plan (rotation_plan.c).  Not
 * installed.
 *
 * Kernel contract.  A method provides, for each precision P ∈ {d, f} with
 * real type T (double, float):
 *   int  sh__rot_<m>_blocks_P(int order, const sh_rotation *rot, const void *tables,
 *                             T *blocks, void *work, uint64_t *mults);
 *        the block-diagonal SH rotation (layout of sh_rot_block_offset), in the
 *        CS convention, bands 0..order-1; adds the multiplications it executed
 *        to *mults.  No allocation: `work` has work_bytes(order) bytes.
 * and optionally tables (built once per order by the plan) and a sparse
 * set + apply that replaces blocks × vector (z, ZXZXZ, the Taylor kernels).
 */
#ifndef SHLAB_ROT_INTERNAL_H
#define SHLAB_ROT_INTERNAL_H

#include "core/shlab_internal.h"

typedef struct {
    const char *name;
    int max_order;
    int approximate; /* 1: a Taylor approximation (not held to the reference) */
    /* per-order tables: NULL if the method needs none */
    int (*tables_new_d)(int order, void **tables);
    int (*tables_new_f)(int order, void **tables);
    void (*tables_free)(void *tables);
    size_t (*work_bytes)(int order); /* for either precision (float needs no more) */
    int (*blocks_d)(int order, const sh_rotation *rot, const void *tables, double *blocks,
                    void *work, uint64_t *mults);
    int (*blocks_f)(int order, const sh_rotation *rot, const void *tables, float *blocks,
                    void *work, uint64_t *mults);
    /* sparse apply without a matrix (NULL: the plan multiplies by the blocks).
     * A sparse method has a per-rotation state: set_P fills `state`
     * (state_bytes(order) bytes, owned by the plan, enough for either
     * precision) once per sh_rot_plan_set — validating the rotation and
     * doing the work that does not depend on the vector, e.g. the multiple
     * angles — and adds its multiplications to *mults (the set's count);
     * apply_P reads it, for any number of vectors. */
    size_t (*state_bytes)(int order);
    int (*set_d)(int order, const sh_rotation *rot, const void *tables, void *state,
                 uint64_t *mults);
    int (*set_f)(int order, const sh_rotation *rot, const void *tables, void *state,
                 uint64_t *mults);
    void (*apply_d)(int order, const void *tables, const void *state, const double *in,
                    double *out, void *work, uint64_t *mults);
    void (*apply_f)(int order, const void *tables, const void *state, const float *in,
                    float *out, void *work, uint64_t *mults);
    /* a single band without the lower ones (NULL: compute 0..band) */
    int (*band_d)(int band, const sh_rotation *rot, double *block, void *work);
    size_t (*band_work_bytes)(int band);
    /* streaming (optional): bands l = 0, 1, 2, ... in order, each from the
     * method's own state of the previous band, in O(lmax²) memory; `state`
     * has stream_bytes(lmax) bytes, zeroed before band 0. */
    size_t (*stream_bytes)(int lmax);
    int (*stream_init)(int lmax, void *state); /* optional, after zeroing */
    int (*stream_d)(int l, const sh_rotation *rot, void *state, double *block);
    int (*stream_f)(int l, const sh_rotation *rot, void *state, float *block);
} sh__rot_ops;

/* ---- rot_blocks.c (generic): shared pieces ----------------------------- */
/* out = blocks · in, band by band; counts n(4n²−1)/3 multiplications. */
void sh__rot_blocks_apply_d(int order, const double *blocks, const double *in, double *out,
                            uint64_t *mults);
void sh__rot_blocks_apply_f(int order, const float *blocks, const float *in, float *out,
                            uint64_t *mults);
/* cs[2m], cs[2m+1] = cos(mθ), sin(mθ) for m = 0..mmax by the Chebyshev
 * recurrence cos(mθ) = 2cosθ cos((m−1)θ) − cos((m−2)θ) (and the same for sin),
 * seeded with libm's cosθ, sinθ and re-seeded from libm every
 * SH_ANGLE_RESEED steps (bounds the recurrence's m·ε error growth). */
#define SH_ANGLE_RESEED 16
void sh__rot_multiple_angles_d(double theta, int mmax, double *cs);
void sh__rot_multiple_angles_f(float theta, int mmax, float *cs);
/* Real Z rotation of one band's coefficients in place:
 *   c_m ← cos(mα) c_m − sin(mα) c_{−m},  c_{−m} ← sin(mα) c_m + cos(mα) c_{−m}
 * (f = a cos mφ + b sin mφ rotated by α about z).  cs from multiple_angles. */
void sh__rot_z_band_d(int l, const double *cs, double *c, uint64_t *mults);
void sh__rot_z_band_f(int l, const float *cs, float *c, uint64_t *mults);
/* The real block of Z(α)·R_Y(β)·Z(γ) for band l from the Wigner small-d
 * matrix d[(m'+l)(2l+1) + (m+l)] = d^l_{m'm}(β) (standard phase, D =
 * e^{−im'α} d e^{−imγ}), csa/csg = multiple angles of α, γ.  CS convention:
 *   R_Y[m',m]   = d_{m'm} + (−1)^m d_{m',−m}    (m, m' > 0)
 *   R_Y[−m',−m] = d_{m'm} − (−1)^m d_{m',−m}    (m, m' > 0)
 *   R_Y[0,m] = √2 d_{0m}, R_Y[m',0] = √2 d_{m'0}, R_Y[0,0] = d_00,
 *   cos/sin cross terms 0   (derivation in rot_blocks.c). */
void sh__rot_block_from_d_d(int l, const double *d, const double *csa, const double *csg,
                            double *block);
void sh__rot_block_from_d_f(int l, const float *d, const float *csa, const float *csg,
                            float *block);
/* Flip to/from the nocs convention: negate entries whose m and m' differ in
 * parity (= S·B·S, S = diag((−1)^m for odd m)). */
void sh__rot_blocks_nocs_d(int order, double *blocks);
/* The same for one band's (2l+1)² block. */
void sh__rot_band_nocs_d(int l, double *block);
void sh__rot_band_nocs_f(int l, float *block);
void sh__rot_blocks_nocs_f(int order, float *blocks);

/* Prototypes of a method's kernels in both precisions (each method file
 * states which it has; the ops table of the double compilation names both). */
#define SH__ROT_DECLARE_BLOCKS(m)                                                                  \
    int sh__rot_##m##_blocks_d(int, const sh_rotation *, const void *, double *, void *,          \
                               uint64_t *);                                                        \
    int sh__rot_##m##_blocks_f(int, const sh_rotation *, const void *, float *, void *, uint64_t *)
#define SH__ROT_DECLARE_APPLY(m)                                                                   \
    int sh__rot_##m##_set_d(int, const sh_rotation *, const void *, void *, uint64_t *);           \
    int sh__rot_##m##_set_f(int, const sh_rotation *, const void *, void *, uint64_t *);           \
    void sh__rot_##m##_apply_d(int, const void *, const void *, const double *, double *, void *, \
                               uint64_t *);                                                        \
    void sh__rot_##m##_apply_f(int, const void *, const void *, const float *, float *, void *,   \
                               uint64_t *)
#define SH__ROT_DECLARE_TABLES(m)                                                                  \
    int sh__rot_##m##_tables_new_d(int, void **);                                                  \
    int sh__rot_##m##_tables_new_f(int, void **)
#define SH__ROT_DECLARE_BAND(m)                                                                    \
    int sh__rot_##m##_band_d(int, const sh_rotation *, double *, void *);                          \
    int sh__rot_##m##_band_f(int, const sh_rotation *, float *, void *)

#define SH__ROT_DECLARE_STREAM(m)                                                                  \
    int sh__rot_##m##_stream_d(int, const sh_rotation *, void *, double *);                         \
    int sh__rot_##m##_stream_f(int, const sh_rotation *, void *, float *)

/* rotation_reference.c: the reference band computed at two MPFR precisions
 * (for `digits` and for digits + 30); the largest difference between them,
 * an estimate of the first one's error, in *maxdiff (may be < 1e-30). */
int sh__rot_reference_selfcheck(int band, const sh_rotation *rot, int digits, double *maxdiff);

/* ---- the methods: each method file defines its ops table once, in its
 * double compilation (inside #ifndef SH_REAL_FLOAT), naming both precisions. */
extern const sh__rot_ops sh__rot_z_ops, sh__rot_ivanic_ops, sh__rot_zxzxz_ops, sh__rot_choi_ops,
    sh__rot_blanco_ops, sh__rot_wigner_ops, sh__rot_reference_ops;
extern const sh__rot_ops sh__rot_taylor1_ops, sh__rot_taylor15_ops, sh__rot_taylor2_ops;

/* rotation_plan.c: non-zero if the band iterator computes each band alone
 * (a single-band routine with a per-band workspace): dropping it and asking
 * sh_rot_band for the next band costs nothing more and holds one workspace
 * instead of one per iterator. */
int sh__rot_bands_single(const sh_rot_bands *it);

#endif
