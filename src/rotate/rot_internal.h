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

/* A method's kernel of one vector (ops->one_P, below). */
typedef void (*sh__rot_one_fn_d)(const double *state, const double *in, double *out);
typedef void (*sh__rot_one_fn_f)(const float *state, const float *in, float *out);

typedef struct {
    const char *name;
    int max_order;
    int approximate; /* 1: a Taylor approximation (not held to the reference) */
    /* per-order tables: NULL if the method needs none */
    size_t (*tables_bytes)(int order); /* their size in double (NULL: small, O(order²)) */
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
    /* sparse methods from a matrix or quaternion (optional): the same as
     * set_P, with the rotation given as par (SH__PAR_N values, below) instead
     * of angles — no trigonometric call */
    int (*set_par_d)(int order, const double *par, const void *tables, void *state,
                     uint64_t *mults);
    int (*set_par_f)(int order, const float *par, const void *tables, void *state,
                     uint64_t *mults);
    /* 1: the kernels read rot->R only (not the angles): a plan set from a
     * matrix does not extract them */
    int matrix_only;
    /* block methods from a matrix or quaternion (optional): blocks_P with the
     * rotation given as par (below) — no trigonometric call */
    int (*blocks_par_d)(int order, const double *par, const void *tables, double *blocks,
                        void *work, uint64_t *mults);
    int (*blocks_par_f)(int order, const float *par, const void *tables, float *blocks,
                        void *work, uint64_t *mults);
    /* sparse methods straight from a row-major matrix R (optional; direct):
     * the same as set_P, with R in the plan's precision and no angle or par
     * computed.  Checks that R is finite (SH_EINVAL, nothing set), assumes
     * it orthogonal.  Such a method keeps no sh_rotation: state_blocks_P
     * gives the blocks (cs, double, layout of sh_rot_block_offset) of the
     * state set_P or set_mat_P (P: the plan's precision) wrote. */
    int (*set_mat_d)(int order, const double *R, void *state, uint64_t *mults);
    int (*set_mat_f)(int order, const float *R, void *state, uint64_t *mults);
    void (*state_blocks_d)(int order, const void *state, double *blocks);
    void (*state_blocks_f)(int order, const void *state, double *blocks);
    /* K rotations given as matrices (9 rows of K, structure of arrays, like
     * sh_rot_plan_rotate_many) applied to K vectors (order² rows of K),
     * in == out allowed, in the convention nocs (1) or cs (0); checks first
     * that every entry of R is finite (SH_EINVAL, nothing written); compiled for
     * the rotator's kernel (avx2, avx512: that instruction set; any other:
     * the default flags); adds the multiplications of one rotation's set to
     * *set_mults and of its apply to *apply_mults (optional; NULL: the plan
     * sets and applies each).  A method with this keeps the kernel asked
     * (rotator.c) though it has no unrolled tables. */
    int (*rotate_many_d)(int order, int nocs, sh_rot_kernel kernel, size_t K, const double *R,
                         const double *in, double *out, uint64_t *set_mults, uint64_t *apply_mults);
    int (*rotate_many_f)(int order, int nocs, sh_rot_kernel kernel, size_t K, const float *R,
                         const float *in, float *out, uint64_t *set_mults, uint64_t *apply_mults);
    /* One vector of the plan's rotation (optional; direct): the kernel for
     * (order, convention nocs 1 or cs 0, the rotator's kernel), which reads
     * the state set_P or set_mat_P wrote (P: the plan's precision) and
     * applies it in that convention, in == out allowed; *mults = its
     * multiplications.  The rotator resolves it once (sh_rotator.one_P);
     * the plan's apply then calls it with nothing in between.  A method
     * with unrolled kernels (zxzxz, zxzxz_one.c) may have one too, in
     * place of the unrolled one-lane kernel of its order (one_mat, below):
     * its state is then the rotation's matrix R itself (9 floats,
     * row-major, as given: the convention is the kernel's), which every
     * set of the plan writes; the par of the unrolled batches is then made
     * from it when a batch needs it. */
    sh__rot_one_fn_d (*one_d)(int order, int nocs, sh_rot_kernel kernel, uint64_t *mults);
    sh__rot_one_fn_f (*one_f)(int order, int nocs, sh_rot_kernel kernel, uint64_t *mults);
} sh__rot_ops;

/* Progress of the long steps (rotator.c): a method whose tables or blocks
 * cost O(order³) or more reports each band finished, done of total; nothing
 * happens unless the rotator has a progress function. */
void sh__rot_band_done(int done, int total);

/* ---- the rotation as the sparse kernels use it ----------------------------
 * par = (cos α, sin α, cos β, sin β, cos γ, sin γ, β) (ivanic's unrolled
 * kernel: the matrix R, row-major, 9 values), at most SH__PAR_N values,
 * from a matrix or quaternion by algebra (rot_fast.c: sh__rot_par_matrix_P,
 * sh__rot_par_quat_P; derivation there) or from the Euler angles by libm
 * (sh__rot_par_euler_P).  par[6] = β only when need_beta (the Taylor
 * kernels), else 0.  Computed in double for either precision. */
#define SH__PAR_N 9
#define SH__PAR_MULTS_MATRIX 12 /* multiplications of sh__rot_par_matrix (and 2 √, 2 ÷) */
#define SH__PAR_MULTS_QUAT 18   /* of sh__rot_par_quat (and 1 √, 3 ÷) */
#define SH__PAR_MULTS_BETA_F 10 /* β in float (polynomial; and 1 ÷); double: atan2 */
#define SH__QUAT_MATRIX_MULTS 19 /* sh__rot_quat_matrix (and 1 ÷) */
void sh__rot_par_matrix_d(const double *R, int need_beta, double *par);
void sh__rot_par_matrix_f(const float *R, int need_beta, float *par);
void sh__rot_par_quat_d(const double *q, int need_beta, double *par);
void sh__rot_par_quat_f(const float *q, int need_beta, float *par);
void sh__rot_par_euler_d(const sh_rotation *rot, double *par);
void sh__rot_par_euler_f(const sh_rotation *rot, float *par);
/* The matrix of a quaternion (any non-zero norm), in double. */
void sh__rot_quat_matrix(const double q[4], double R[9]);

/* ---- the unrolled kernels (rot_fast.c + the generated rot_unrolled_gen.h),
 * one table per precision and variant (ISA and lane count) ---------------- */
enum { SH__FAST_ZXZXZ = 0, SH__FAST_TAYLOR1, SH__FAST_TAYLOR15, SH__FAST_TAYLOR2, SH__FAST_IVANIC,
       SH__FAST_NMETH };
#define SH__FAST_MAXO 16 /* capacity of the tables (the generator's --max-order ≤ this) */
#define SH__FAST_DEFINE(T, P)                                                                      \
    /* one call: `lanes` rotations (par, lane stride KP) applied to `lanes` vectors (in, out:  \
     * order² values, lane stride K); in == out allowed */                                     \
    typedef void (*sh__fast_fn_##P)(const T *par, size_t KP, const T *in, T *out, size_t K);      \
    typedef struct {                                                                               \
        const char *name;                                                                          \
        int lanes, max_order;                                                                      \
        const sh__fast_fn_##P (*fn)[SH__FAST_MAXO + 1]; /* [method][order], NULL: none */          \
        const unsigned (*mults)[SH__FAST_MAXO + 1];     /* multiplications of one fn call */       \
        /* K rotations (matrices: 9 rows of K, or quaternions: 4 rows of K; nocs negates β)     \
         * applied to K vectors, structure of arrays */                                            \
        void (*rotate)(int meth, int order, int nocs, size_t K, const T *rot, int quat,            \
                       const T *in, T *out);                                                       \
        /* one rotation (par) applied to K vectors, structure of arrays */                         \
        void (*many)(int meth, int order, const T *par, size_t K, const T *in, T *out);           \
        /* par of one rotation from its matrix (as sh__rot_par_matrix_P, built with the            \
         * variant's flags; one-lane variants only, else NULL) */                                  \
        void (*par_matrix)(const T *R, int need_beta, T *par);                                     \
    } sh__rot_fast_##P;
SH__FAST_DEFINE(double, d)
SH__FAST_DEFINE(float, f)
#undef SH__FAST_DEFINE

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
/* The same from c = cosθ, s = sinθ: the recurrence from these seeds for
 * mmax < SH_ANGLE_RESEED (no trigonometric call), else from θ = atan2(s, c)
 * as above. */
void sh__rot_multiple_angles_cs_d(double c, double s, int mmax, double *cs);
void sh__rot_multiple_angles_cs_f(float c, float s, int mmax, float *cs);
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
#define SH__ROT_DECLARE_SET_PAR(m)                                                                 \
    int sh__rot_##m##_set_par_d(int, const double *, const void *, void *, uint64_t *);            \
    int sh__rot_##m##_set_par_f(int, const float *, const void *, void *, uint64_t *)
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
extern const sh__rot_ops sh__rot_halfpi_ops;
extern const sh__rot_ops sh__rot_direct_ops;
extern const sh__rot_ops sh__rot_zh_ops;

/* ---- rot_halfpi.c: the band kernel of `halfpi`, shared with the threaded
 * all-band rotation (rotation_stream.c).  Band l of nj vectors (job j: the
 * multiple-angle table cs[j] of sh__rot_halfpi_set_angles with M ≥ l, input
 * in[j], output out[j], 2l+1 values each, out may be in); nocs: the vectors
 * are in the nocs convention.  work: sh__rot_halfpi_work_bytes(≥ l, ≥ nj)
 * bytes.  Bands are independent: no state passes from one to the next. */
size_t sh__rot_halfpi_work_bytes(int L, int J);
void sh__rot_halfpi_band_d(int l, int nocs, int nj, const double *const *cs, int M,
                           const double *const *in, double *const *out, void *work,
                           uint64_t *mults);
void sh__rot_halfpi_band_f(int l, int nocs, int nj, const float *const *cs, int M,
                           const float *const *in, float *const *out, void *work, uint64_t *mults);
/* cos, sin of mθ, m = 0..M (to an ulp for any m), into cs[2m], cs[2m+1] */
void sh__rot_halfpi_angles(double theta, int M, double *cs);
/* A job's table: the multiple angles of α, β, γ at cs, cs + 2(M+1),
 * cs + 4(M+1) (6(M+1) values); inverse: those of Rᵀ, angles −γ, −β, −α. */
void sh__rot_halfpi_set_angles(const sh_rotation *rot, int inverse, int M, double *cs);
/* d^l_{m'm}(π/2), m', m = 0..l, into d[m'(l+1) + m]; work as for nj = 0. */
void sh__rot_halfpi_delta_d(int l, void *work, double *d);

/* ---- rotation_methods.c, rotation_kernels.c: the registry and the kernels */
/* The ops table of method m (NULL: unknown or not built in). */
const sh__rot_ops *sh__rot_ops_of(sh_rot_method m);
/* The widest kernel this CPU runs (never SH_KERNEL_AUTO). */
sh_rot_kernel sh__rot_kernel_auto(void);
/* The unrolled tables of kernel k: one lane (single vectors) and SIMD lanes
 * (batches). */
void sh__rot_kernel_tables(sh_rot_kernel k, const sh__rot_fast_d **d1, const sh__rot_fast_d **dv,
                           const sh__rot_fast_f **f1, const sh__rot_fast_f **fv);
/* The unrolled method of m (SH__FAST_*), or −1 if it has none. */
int sh__rot_fast_method(sh_rot_method m);

/* ---- rotator.c: the immutable part of a rotation (sh_rotator, rotate.h),
 * shared by the per-thread plans made from it (rotation_plan.c).  Nothing
 * here changes after sh_rotator_create. */
struct sh_rotator {
    int order;
    sh_rot_method method; /* resolved (never SH_ROT_AUTO) */
    sh_precision prec;
    sh_convention conv;
    const sh__rot_ops *ops;
    void *tables;         /* the method's per-order tables (read only), or NULL */
    sh_rot_kernel kernel; /* the kernel in use (never AUTO) */
    int fmeth;            /* the unrolled method, or −1: the loop kernels */
    const sh__rot_fast_d *fd1, *fdv; /* unrolled: one lane, SIMD lanes */
    const sh__rot_fast_f *ff1, *ffv;
    int nb;               /* the method needs β itself (Taylor) */
    sh__fast_fn_d fn_d;   /* unrolled, one lane: the kernel of this order, or NULL */
    sh__fast_fn_f fn_f;
    uint64_t fn_mults;    /* its multiplications per call */
    sh__rot_one_fn_d one_d; /* the method's one-vector kernel (ops->one_P), or NULL */
    sh__rot_one_fn_f one_f;
    uint64_t one_mults;   /* its multiplications per call */
    int one_mat;          /* 1: an unrolled method's one_P, whose state is R (above) */
    int stream;           /* halfpi in double: all bands by sh_rot_stream, on threads */
    int threads;          /* the stream's threads (1 for the plans) */
    sh_progress_fn progress;
    void *progress_ctx;
};
/* Progress of the long steps (rotator.c): between enter and leave, this
 * thread's sh__rot_band_done calls report to r's progress function. */
typedef struct { const sh_rotator *r; const char *what; } sh__rot_progress_scope;
sh__rot_progress_scope sh__rot_progress_enter(const sh_rotator *r, const char *what);
void sh__rot_progress_leave(sh__rot_progress_scope outer);
/* The checks every rotation front door makes once: order within the
 * library's and the method's limits, known method, precision, convention. */
int sh__rot_check_args(int order, sh_rot_method method, sh_precision prec, sh_convention conv);
/* What one plan of r allocates (per-rotation state, scratch, vector copies;
 * the blocks of block methods), and the rotator's tables. */
double sh__rot_plan_state_bytes(const sh_rotator *r);
double sh__rot_tables_bytes(int order, const sh__rot_ops *ops, sh_precision prec);

/* rotation_plan.c: a plan reading rotator r (owns: freed with the plan). */
int sh__rot_plan_new(const sh_rotator *r, int owns, sh_rot_plan **out);
/* The unrolled kernels' parameters of a matrix for r (r->fmeth ≥ 0; the
 * float form not for ivanic); SH_EINVAL if an entry is not finite. */
int sh__rot_plan_par_matrix_d(const sh_rotator *r, const double R[9], double *par);
int sh__rot_plan_par_matrix_f(const sh_rotator *r, const float R[9], float *par);
/* rotation_stream.c: the threads of a stream asked with `threads` (≤ 0:
 * every core; 1 without OpenMP). */
int sh__rot_stream_resolve_threads(int threads);

/* rotation_bands.c: non-zero if the band iterator computes each band alone
 * (a single-band routine with a per-band workspace): dropping it and asking
 * sh_rot_band for the next band costs nothing more and holds one workspace
 * instead of one per iterator. */
int sh__rot_bands_single(const sh_rot_bands *it);

#endif
