/* shlab/rotate.h — rotations, rotation plans (every exact method), single bands, the MPFR
 * reference, stability.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_ROTATE_H
#define SHLAB_ROTATE_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Rotations (docs/CONVENTIONS.md): a proper rotation R acts on functions,
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
    SH_ROT_HALFPI,    /* d^l(π/2) generated band by band (O(l²) each), Z·Δ·Z(β)·Δ·Z; high bands */
    SH_ROT_DIRECT,    /* bands 0..2 straight from the matrix: a permutation, quadratic forms */
    SH_ROT_ZH,        /* zonal-harmonic factorisation: the basis at 2l+1 rotated directions (orders ≤ 6) */
    SH_ROT_NMETHODS
} sh_rot_method;
typedef enum { SH_PREC_DOUBLE = 0, SH_PREC_FLOAT = 1 } sh_precision;
const char *sh_rot_method_name(sh_rot_method m);
int sh_rot_method_parse(const char *s, sh_rot_method *out);
const char *sh_precision_name(sh_precision p);
int sh_precision_parse(const char *s, sh_precision *out);
/* Largest order a method accepts; 0 if the method is not built in.  Each is
 * the top at which a test or the report checks the method against an
 * independent truth (docs/ranges.md), and no higher:
 *   z, halfpi   SHLAB_MAX_ORDER (tests/core/test_ranges.c: the z rotation's closed
 *               form at order 4097, the pointwise identity at band 4096)
 *   blanco      l ≤ 4000: orthogonality and homomorphism to l = 4000 in the
 *               report (rotation_stability, long part); single bands
 *               against halfpi to l = 2000 in make check
 *   zxzxz       l ≤ 1400: the same long part (its single band is O(l³))
 *   ivanic,     l ≤ 200: the golden fixtures at band 200 against the MPFR
 *   choi        reference (tests/cli/test_fixtures.sh) and rotation_stability,
 *               which show them breaking down (orth > 1 after l ≈ 180):
 *               accepted to show that, accurate only to l ≈ 50
 *   wigner      l ≤ 60: rotation_stability (its terms grow like 4^l)
 *   reference   l ≤ 400: halfpi against it at band 400 (test_rot_halfpi)
 *   taylor*     SH_TAYLOR_MAX_ORDER (taylor.h; tests/core/test_ranges.c)
 *   direct      order 3 (bands 0..2): its closed forms exist for these bands
 *               only (rot_direct.c); tests/rotate/test_rot_direct.c against
 *               the MPFR reference
 *   zh          order 6 (bands 0..5): its directions and their condition
 *               numbers (≤ 4.5) are chosen for these bands (rot_zh.c);
 *               tests/rotate/test_rot_zh.c against the MPFR reference */
#define SH_ROT_BLANCO_MAX_ORDER 4001
#define SH_ROT_ZXZXZ_MAX_ORDER 1401
#define SH_ROT_IVANIC_MAX_ORDER 201
#define SH_ROT_CHOI_MAX_ORDER 201
#define SH_ROT_WIGNER_MAX_ORDER 61
#define SH_ROT_REFERENCE_MAX_ORDER 401
#define SH_ROT_DIRECT_MAX_ORDER 3
#define SH_ROT_ZH_MAX_ORDER 6
int sh_rot_method_max_order(sh_rot_method m);
/* 1 for the exact methods, 0 for the Taylor approximations. */
int sh_rot_method_is_exact(sh_rot_method m);
/* The method `rotate` and `rotmat` use when none is named: an exact method
 * that stays a rotation at every band.  All bands 0..order−1: zxzxz up to
 * order SH_ROT_DEFAULT_ZXZXZ_MAX (per-order tables of order³/3 values, the
 * fastest apply there), halfpi above (O(order) scratch, any order, threads).
 * One band alone (one_band ≠ 0): blanco (O(l²), no lower band).  ivanic and
 * choi, l-recursions from the 3×3 matrix, lose orthogonality geometrically
 * (1e-12 at l = 50, 4e-8 at 100, > 1 after 180) and are never the default. */
#define SH_ROT_DEFAULT_ZXZXZ_MAX 32
sh_rot_method sh_rot_method_default(int order, int one_band);

/* A rotation plan: the per-rotation state of one thread (rotation_plan.c).
 * sh_rotator_plan (below) makes one reading a rotator; any number of plans
 * of one rotator may run on different threads at once.
 * sh_rot_plan_create is the older door: a rotator and a plan in one
 * object (halfpi then stays a one-thread plan).
 * Create once for (order, method, precision, convention) —
 * per-order tables (X±90 blocks, recursion coefficients) are built here —
 * then set a rotation and apply it to many vectors.  A plan is used by one
 * thread at a time.  Float plans compute and apply in float arithmetic;
 * vectors cross this interface as double (sh_rot_plan_apply_f and the
 * batches below take float). */
typedef struct sh_rot_plan sh_rot_plan;
typedef struct sh_rotator sh_rotator;
int sh_rot_plan_create(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                       sh_rot_plan **out);
void sh_rot_plan_free(sh_rot_plan *p);
/* Bytes sh_rot_plan_create would allocate (blocks — none for the sparse
 * methods z, zxzxz, halfpi and the Taylor kernels until sh_rot_plan_blocks —,
 * tables, scratch, vectors); 0 for an unknown method.  sh_rot_plan_create
 * refuses (SH_ENOMEM, one line naming the size) a plan larger than the
 * memory available. */
size_t sh_rot_plan_bytes(int order, sh_rot_method method, sh_precision prec);
/* The checks sh_rot_plan_create makes before allocating (arguments, size
 * against the memory available), alone: SH_OK or its error. */
int sh_rot_plan_check(int order, sh_rot_method method, sh_precision prec);
/* Set the rotation (computes the block matrix, or for ZXZXZ the angles). */
int sh_rot_plan_set(sh_rot_plan *p, const sh_rotation *rot);
/* out = R_sh in (in-place allowed).  in and out have order² entries. */
int sh_rot_plan_apply(sh_rot_plan *p, const double *in, double *out);
/* The blocks of the current rotation (sh_rot_block_offset(order) doubles). */
int sh_rot_plan_blocks(sh_rot_plan *p, double *blocks);
/* Multiplications executed (counted by the kernels' loops, not by formula) by
 * the last sh_rot_plan_set and by one sh_rot_plan_apply. */
void sh_rot_plan_mults(const sh_rot_plan *p, uint64_t *set_mults, uint64_t *apply_mults);

/* Kernels.  zxzxz and the Taylor methods (up to order 10) and ivanic (up to
 * order 6) have unrolled kernels (generated straight-line code), built once
 * per instruction set; the plan picks one when it is created and keeps it:
 *   scalar    the loop kernels (every method and order; the reference path)
 *   unrolled  the unrolled kernels, built with the default flags
 *   sse2      unrolled; batches in SSE2 lanes (4 floats / 2 doubles)
 *   avx2      unrolled with AVX2 + FMA; batches in 8 / 4 lanes
 *   avx512    unrolled with AVX-512 registers; batches in 16 / 8 lanes
 *   auto      the best this CPU runs (avx512, else avx2, else sse2, else
 *             unrolled)
 * A plan whose method or order has no unrolled kernel uses the loop kernels
 * (sh_rot_plan_kernel then says scalar), except `direct`, whose batch of K
 * rotations (sh_rot_plan_rotate_many) is compiled for avx2 and avx512 too:
 * it keeps the kernel asked.  sh_rot_plan_create uses auto. */
typedef enum {
    SH_KERNEL_AUTO = 0,
    SH_KERNEL_SCALAR,
    SH_KERNEL_UNROLLED,
    SH_KERNEL_SSE2,
    SH_KERNEL_AVX2,
    SH_KERNEL_AVX512,
    SH_KERNEL_N
} sh_rot_kernel;
const char *sh_rot_kernel_name(sh_rot_kernel k);
int sh_rot_kernel_parse(const char *s, sh_rot_kernel *out);
/* 1 if kernel k is compiled in and this CPU (and OS) runs it. */
int sh_rot_kernel_available(sh_rot_kernel k);
/* sh_rot_plan_create with a kernel; SH_ENOTSUP if it is not available. */
int sh_rot_plan_create_kernel(int order, sh_rot_method method, sh_precision prec,
                              sh_convention conv, sh_rot_kernel kernel, sh_rot_plan **out);
/* sh_rot_plan_create_kernel with progress: fn(ctx, done, order,
 * what) as bands of the long steps finish — the per-order tables (zxzxz,
 * ivanic, choi, blanco) here, and the blocks of each rotation later
 * (ivanic, choi, blanco) in sh_rot_plan_set and the set_matrix/quat calls.
 * These are O(order³) or more: seconds from order ~300, minutes at 1000. */
int sh_rot_plan_create_progress(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                                sh_rot_kernel kernel, sh_progress_fn fn, void *ctx, sh_rot_plan **out);
sh_rot_kernel sh_rot_plan_kernel(const sh_rot_plan *p);
/* The kernel a plan (order, method, kernel asked) would run, without making
 * it: sh_rot_plan_kernel of the plan sh_rot_plan_create_kernel makes. */
sh_rot_kernel sh_rot_plan_kernel_for(int order, sh_rot_method method, sh_rot_kernel kernel);

/* ---- the rotator: the front door of rotation (rotator.c) ---------------------
 * One immutable object per (order, method, precision, kernel, convention,
 * threads): created once — arguments checked, `auto` resolved, per-order
 * tables built — then shared by any number of threads.  It chooses the path:
 * the unrolled kernels where they exist (zxzxz and Taylor to order 10, ivanic
 * to 6), the loop kernels otherwise, and for halfpi in double (what `auto`
 * picks above order SH_ROT_DEFAULT_ZXZXZ_MAX) the threaded all-band stream.
 *
 * Two ways to use one:
 *  - one call per rotation: sh_rotator_apply* (thread-safe; the unrolled
 *    kernels on one vector allocate nothing, the others make their per-call
 *    state inside the call);
 *  - a plan per thread (sh_rotator_plan, below): set a rotation once, apply
 *    it to many vectors, batches of K vectors or of K rotations.
 * Creating a rotator at order ≤ 10 costs a few small allocations: the CPU's
 * features are read once per process, and the memory available is consulted
 * only for requests of 64 MiB or more. */
#define SH_ROT_AUTO ((sh_rot_method)-1) /* zxzxz up to order 32, halfpi above */
typedef struct {
    int order;              /* bands 0..order−1 */
    sh_rot_method method;   /* a method, or SH_ROT_AUTO */
    sh_precision prec;      /* arithmetic (and the vectors of the _f calls) */
    sh_rot_kernel kernel;   /* SH_KERNEL_AUTO: the widest this CPU runs */
    sh_convention conv;
    int threads;            /* the stream's threads (≤ 0: every core); 1 elsewhere */
    sh_progress_fn progress; /* bands done in the long steps (the stream; the tables
                                and blocks of zxzxz, ivanic, choi, blanco), or NULL */
    void *progress_ctx;
} sh_rotator_opts;
/* Options start from this (method auto; every other zero field is a default:
 * double, kernel auto, cs, every core):
 *     sh_rotator_opts o = SH_ROTATOR_OPTS(6);  o.prec = SH_PREC_FLOAT;
 * (A zeroed method field is SH_ROT_Z, rotation about z only.) */
#define SH_ROTATOR_OPTS(n) ((sh_rotator_opts){.order = (n), .method = SH_ROT_AUTO})
int sh_rotator_create(const sh_rotator_opts *opts, sh_rotator **out);
void sh_rotator_free(sh_rotator *r);
/* What it chose. */
int sh_rotator_order(const sh_rotator *r);
sh_rot_method sh_rotator_method(const sh_rotator *r);
sh_precision sh_rotator_precision(const sh_rotator *r);
sh_rot_kernel sh_rotator_kernel(const sh_rotator *r);
int sh_rotator_threads(const sh_rotator *r);
int sh_rotator_streams(const sh_rotator *r); /* 1: the high-band stream */
/* Bytes the rotator holds (tables), and those of each plan or call (*per_plan). */
size_t sh_rotator_bytes(const sh_rotator *r, size_t *per_plan);
/* out + v·order² = R_sh · (in + v·order²) for v < nvec (in == out allowed),
 * with R_sh the rotation's (flags 0) or its inverse's (SH_ROTATE_INVERSE:
 * Rᵀ; for the stream the exactly negated angles −γ, −β, −α).  The rotation
 * as ZYZ angles (sh_rotation: its angles are used), as a row-major matrix
 * (by algebra where the kernels allow: no trigonometric call), or, for float
 * rotators, a float matrix and float vectors. */
#define SH_ROTATE_INVERSE 1u
int sh_rotator_apply(const sh_rotator *r, const sh_rotation *rot, unsigned flags, int nvec, const double *in,
                     double *out);
int sh_rotator_apply_matrix(const sh_rotator *r, const double R[9], unsigned flags, int nvec, const double *in,
                            double *out);
int sh_rotator_apply_matrix_f(const sh_rotator *r, const float R[9], const float *in, float *out);

/* A plan reading r (which must outlive it), for one thread (rotation_plan.c). */
int sh_rotator_plan(const sh_rotator *r, sh_rot_plan **out);
const sh_rotator *sh_rot_plan_rotator(const sh_rot_plan *p);


/* The rotation as a row-major 3×3 matrix or a quaternion (w, x, y, z; any
 * non-zero norm), without trigonometric calls for zxzxz and the Taylor
 * methods (cos, sin of α, β, γ by algebra from the well-conditioned
 * entries, exact at β = 0 and π; the Taylor methods take β by one atan2).
 * blanco takes the half angles by square roots.
 * The matrix must be a rotation (not checked beyond finite entries; use
 * sh_rotation_from_matrix to check or orthonormalise one).  The _f forms
 * take float input and compute in float (float plans only). */
int sh_rot_plan_set_matrix(sh_rot_plan *p, const double R[9]);
int sh_rot_plan_set_quat(sh_rot_plan *p, const double q[4]);
int sh_rot_plan_set_matrix_f(sh_rot_plan *p, const float R[9]);
int sh_rot_plan_set_quat_f(sh_rot_plan *p, const float q[4]);
/* out = R_sh in for a float plan, float vectors (in-place allowed). */
int sh_rot_plan_apply_f(sh_rot_plan *p, const float *in, float *out);
/* Batches, as structure of arrays (coefficient-major, vector-minor):
 * coefficient i of vector k at in[i·K + k], order²·K values; in == out
 * allowed.  apply_many: the plan's rotation applied to K vectors (colour
 * channels, many functions).  rotate_many: K rotations applied to K vectors,
 * rotation k given as R[j·K + k], j = 0..8 (row-major entries), or as a
 * quaternion q[j·K + k], j = 0..3; vectorised across rotations by the SIMD
 * kernels.  Double plans take the double forms, float plans the _f forms.
 * After rotate_many the plan has no rotation set. */
int sh_rot_plan_apply_many(sh_rot_plan *p, size_t K, const double *in, double *out);
int sh_rot_plan_apply_many_f(sh_rot_plan *p, size_t K, const float *in, float *out);
int sh_rot_plan_rotate_many(sh_rot_plan *p, size_t K, const double *R, const double *in,
                            double *out);
int sh_rot_plan_rotate_many_f(sh_rot_plan *p, size_t K, const float *R, const float *in,
                              float *out);
int sh_rot_plan_rotate_many_quat(sh_rot_plan *p, size_t K, const double *q, const double *in,
                                 double *out);
int sh_rot_plan_rotate_many_quat_f(sh_rot_plan *p, size_t K, const float *q, const float *in,
                                   float *out);

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
/* All bands at high order (rotation_stream.c): the halfpi method — d^l(π/2)
 * generated band by band, nothing kept between bands — run on threads across
 * bands and across batches of rotations, with O(order) scratch per thread
 * (sh_rot_stream_bytes: 0.7 MB per thread at order 1001, 3 MB at 4097) and
 * no memory beyond the caller's vectors.
 * Results are bit for bit the same for any number of threads.  Create once
 * for (order, convention, threads) and apply to any number of rotations and
 * vectors; the per-order scratch is all it keeps.  threads ≤ 0: all cores
 * (OpenMP's default, so OMP_NUM_THREADS counts); 1 when built without
 * OpenMP.  Refused (SH_ENOMEM, naming the size) if the scratch would not fit
 * in the memory available. */
typedef struct sh_rot_stream sh_rot_stream;
int sh_rot_stream_create(int order, sh_convention conv, int threads, sh_rot_stream **out);
void sh_rot_stream_free(sh_rot_stream *s);
/* Bytes sh_rot_stream_create allocates (each apply adds 48·order bytes per
 * rotation for its angles); the vectors are the caller's. */
size_t sh_rot_stream_bytes(int order, int threads);
int sh_rot_stream_threads(const sh_rot_stream *s);
/* Called (from one thread at a time) as bands finish: done of order. */
void sh_rot_stream_set_progress(sh_rot_stream *s, sh_progress_fn fn, void *ctx);
/* out + (r·nvec + v)·order² = R_sh(rots[r]) · (in + v·order²) for r < nrot,
 * v < nvec — or R_sh(rots[r])ᵀ, the inverse rotation, if inverse ≠ 0 (its
 * angles −γ, −β, −α are exact, so a round trip adds no rounding of angles).
 * in == out is allowed when nrot = 1. */
int sh_rot_stream_apply(sh_rot_stream *s, int nrot, const sh_rotation *rots, int inverse, int nvec,
                        const double *in, double *out);
/* One band alone, by the same kernel: band l of nvec vectors (in + v·(2l+1),
 * 2l+1 values each) into out (may be in); O(l²) time and memory per vector,
 * no lower band computed.  Allocates its own scratch: thread-safe. */
int sh_rot_band_apply(int l, sh_convention conv, const sh_rotation *rot, int inverse, int nvec,
                      const double *in, double *out);
/* The Wigner small-d matrix at π/2 of band l: d[m'(l+1) + m] = d^l_{m'm}(π/2)
 * for m', m = 0..l (standard phase, as rot_wigner.c); the negative indices
 * follow from d_{m',−m} = (−1)^{l+m'} d_{m'm} and d_{−m',m} = (−1)^{l+m} d_{m'm}.
 * O(l²), within ~1e-15 of the exact values up to l = 4000. */
int sh_wigner_d_halfpi(int l, double *d);
/* J = dR_Y/dβ at β = 0, the generator of rotations about y
 * (rotation_generator.c): band l as a (2l+1)² row-major block, closed form
 * from the angular-momentum ladder (the only non-zeros are m' = m ± 1, never
 * between m = 0 and m = −1); and its sub-diagonal in CS, s[j] = J[m][m−1] at
 * m = j − l for j = 1..2l, s[0] = 0 (the super-diagonal is −s). */
int sh_rot_deriv_J_band(int l, sh_convention conv, double *block);
void sh_rot_deriv_J_subdiag(int l, double *s);
/* Blocks of order n between the cs and nocs conventions (both ways):
 * entries whose m and m' differ in parity change sign (S·B·S). */
void sh_rot_blocks_flip_phase(int order, double *blocks);
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
 * Rotations a method refuses (z: β ≠ 0) are left out of its set.  halfpi
 * (double) forms no block for a band above exact_max and ref_max: orth and
 * hom then come from band applications to the probes (sh_rot_band_apply,
 * Rᵀ applied as the inverse rotation), O(l²) per band and rotation. */
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
