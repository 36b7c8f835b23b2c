/* shlab.h — the one public header of libshlab.
 *
 * shlab is a numerical verification and analysis workbench for real spherical
 * harmonics (SH).  Conventions (basis, phase, index, rotation direction, image
 * layouts) are pinned in CONVENTIONS.md and summarised in README.md:
 *   - direction s = (sinθ cosφ, sinθ sinφ, cosθ), z up;
 *   - real SH y_l^m, default convention SH_CS (Condon-Shortley phase inside P,
 *     as Green's P()/SH() code), alternative SH_NOCS (odd m negated);
 *   - flat index i = l(l+1)+m; "order n" = bands 0..n-1 = n² coefficients.
 *
 * Error handling follows GSL's style: every routine that can fail returns an
 * int status (SH_OK = 0); a one-line human-readable reason is kept in a
 * thread-local buffer (sh_last_error()).  No routine calls exit().
 * Numerical kernels never allocate; routines that need scratch space say so.
 */
#ifndef SHLAB_H
#define SHLAB_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SHLAB_VERSION "0.1.0"

/* Largest supported order (bands 0..SHLAB_MAX_ORDER-1).  The normalised
 * Legendre recurrence is tested against GSL up to l = 2000 and beyond. */
#define SHLAB_MAX_ORDER 2049

/* ---------------------------------------------------------------- status */
enum {
    SH_OK = 0,
    SH_EINVAL = 1,  /* bad argument (order out of range, NaN, zero vector, ...) */
    SH_ENOMEM = 2,  /* allocation failed */
    SH_EIO = 3,     /* file could not be opened / read / written */
    SH_EFORMAT = 4, /* file is corrupt, truncated or has no usable channels */
    SH_ENOTSUP = 5, /* valid request that this routine does not implement */
    SH_ENUM = 6     /* a numerical result was not finite / did not converge */
};

/* Record a formatted reason for a failure; returns status unchanged so that
 * code can write `return sh_error(SH_EINVAL, "order %d < 1", n);`. */
int sh_error(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The reason recorded by the last failing call on this thread ("" if none). */
const char *sh_last_error(void);
/* A generic name for a status code. */
const char *sh_strerror(int status);

/* ------------------------------------------------------------ conventions */
typedef enum { SH_CS = 0, SH_NOCS = 1 } sh_convention;

/* Coefficient normalisations accepted by sh_convert():
 *   SH_NORM_CS       orthonormal, Condon-Shortley phase (the default basis)
 *   SH_NORM_NOCS     orthonormal, no phase (odd m negated relative to CS)
 *   SH_NORM_4PI      4π-normalised (∫y² dΩ = 4π), no phase (SHTOOLS default)
 *   SH_NORM_SCHMIDT  Schmidt semi-normalised (∫y² dΩ = 4π/(2l+1)), no phase */
typedef enum { SH_NORM_CS = 0, SH_NORM_NOCS, SH_NORM_4PI, SH_NORM_SCHMIDT } sh_norm;

const char *sh_convention_name(sh_convention c);
int sh_convention_parse(const char *s, sh_convention *out);
const char *sh_norm_name(sh_norm n);
int sh_norm_parse(const char *s, sh_norm *out);

/* ------------------------------------------------------------------ index */
static inline int sh_index(int l, int m) { return l * (l + 1) + m; }
static inline int sh_ncoeff(int order) { return order * order; }
/* Inverse of sh_index: band l and order m of flat index i >= 0. */
void sh_index_lm(int i, int *l, int *m);
/* SH_OK if 1 <= order <= SHLAB_MAX_ORDER, else SH_EINVAL with a reason. */
int sh_check_order(int order);

/* --------------------------------------------------------------- Legendre
 * Normalised associated Legendre functions  Q_l^m(x) = K_l^m P_l^m(x)
 * (P with the Condon-Shortley phase, K as in CONVENTIONS.md), for
 * 0 <= m <= l <= lmax, so that y_l^0 = Q_l^0 and y_l^{±m} = √2 Q_l^m trig(mφ).
 * Holmes & Featherstone (2002) recurrence with an extended exponent for the
 * sectoral seed, so that values are correct (not flushed to zero) until the
 * true value itself is below the double range; tested against GSL
 * gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SPHARM, csphase = -1). */
size_t sh_legendre_n(int lmax);                       /* (lmax+1)(lmax+2)/2 */
static inline size_t sh_legendre_idx(int l, int m) { return (size_t)l * (l + 1) / 2 + m; }
int sh_legendre_array(int lmax, double x, double *out);  /* out[sh_legendre_idx(l,m)] */

/* ------------------------------------------------------------------ basis
 * Evaluate all n² real SH at a point.  `y` has sh_ncoeff(order) entries.
 * sh_eval_dir normalises dir; a zero, NaN or infinite vector is SH_EINVAL. */
int sh_eval(int order, sh_convention conv, double theta, double phi, double *y);
int sh_eval_dir(int order, sh_convention conv, const double dir[3], double *y);
/* Direction <-> spherical angles (θ in [0,π], φ in [0,2π)). */
void sh_dir_from_angles(double theta, double phi, double dir[3]);
int sh_angles_from_dir(const double dir[3], double *theta, double *phi);

/* Convert a coefficient vector of `order` between normalisations, in place.
 * Coefficients transform inversely to the basis functions they multiply. */
int sh_convert(int order, sh_norm from, sh_norm to, double *coeffs);
/* Switch a coefficient vector between SH_CS and SH_NOCS in place. */
void sh_convention_switch(int order, double *coeffs);

/* ------------------------------------------------------------- projection */
/* A scalar spherical function.  Both forms of the point are given so that a
 * function defined in angles (Green's example light) and one defined on
 * vectors are evaluated without a round trip. */
typedef double (*sh_sphere_fn)(const double dir[3], double theta, double phi, void *ctx);

typedef enum {
    SH_RULE_QUAD = 0, /* Gauss-Legendre in cosθ (GSL) × uniform φ: exact product rule */
    SH_RULE_MC,       /* Green's stratified (jittered) Monte Carlo */
    SH_RULE_RANDOM,   /* plain uniform Monte Carlo (for comparison) */
    SH_RULE_QMC       /* Sobol quasi-Monte Carlo (GSL qrng), Cranley-Patterson shifted by seed */
} sh_rule;
const char *sh_rule_name(sh_rule r);
int sh_rule_parse(const char *s, sh_rule *out);

/* Project f onto the first `order` bands.  `samples` is: for QUAD the number
 * of θ nodes (2·samples φ nodes); for MC the total count (rounded to a
 * square sqrt_n² as Green's sqrt_n_samples); for RANDOM/QMC the count.
 * samples <= 0 picks the rule's default.  Reproducible for a given seed. */
int sh_project(int order, sh_convention conv, sh_sphere_fn f, void *ctx, sh_rule rule,
               long samples, unsigned long seed, double *coeffs);
/* Default sample counts per rule. */
long sh_rule_default_samples(sh_rule r);

/* --------------------------------------------------------- analytic lights */
typedef enum {
    SH_LIGHT_GREEN = 0,   /* Green (2003) Figure 7 two-lobe example light */
    SH_LIGHT_CAP,         /* 1 inside a cap of half-angle t about +z */
    SH_LIGHT_CIE_OVERCAST,
    SH_LIGHT_CIE_CLEAR,   /* sun at (theta, phi) */
    SH_LIGHT_CIE_PARTLY,  /* sun at (theta, phi) */
    SH_LIGHT_CONST,       /* constant value */
    SH_LIGHT_LOBE         /* max(0, cosθ)^e */
} sh_light_kind;

typedef struct {
    sh_light_kind kind;
    double p[2];          /* cap: p[0] = t; const: p[0] = V; lobe: p[0] = e;
                             cie-clear/partly: p = sun (θ, φ) */
} sh_light;

/* Parse SPEC (green, cap:T, cie-overcast, cie-clear:TH,PH, cie-partly:TH,PH,
 * const:V, lobe:E); angles in degrees when `degrees` is non-zero. */
int sh_light_parse(const char *spec, int degrees, sh_light *out);
double sh_light_eval(const sh_light *L, const double dir[3], double theta, double phi);
/* sh_sphere_fn adaptor: ctx is a const sh_light *. */
double sh_light_fn(const double dir[3], double theta, double phi, void *ctx);
/* Non-zero if the light has a closed-form projection (cap, const, lobe). */
int sh_light_has_closed_form(const sh_light *L);
/* Closed-form coefficients; SH_ENOTSUP for lights without one. */
int sh_light_closed_form(const sh_light *L, int order, sh_convention conv, double *coeffs);
/* Zonal closed forms, band by band (z_l = coefficient of y_l^0). */
int sh_cap_zonal(double t, int order, double *z);
int sh_lobe_zonal(double e, int order, double *z);

/* ------------------------------------------------------- triple products */
/* Real Gaunt coefficient G = ∫ y_i y_j y_k dΩ (flat indices, given convention),
 * via complex Gaunt coefficients from Wigner 3j symbols. */
double sh_gaunt_real(sh_convention conv, int i, int j, int k);
/* Green eq. 8: M_ij = ∫ b y_i y_j for a light given by its coefficients b of
 * order border (bands >= 2·order-1 of b cannot contribute).  M is n²×n²,
 * row-major. */
int sh_triple_matrix(int order, sh_convention conv, const double *b, int border, double *M);

/* ----------------------------------------------------------------- images
 * Planar float image: data[c*width*height + y*width + x]. */
#define SH_IMAGE_MAX_CHANNELS 4
/* Largest image (width × height) any routine reads, writes or projects. */
#define SH_IMAGE_MAX_PIXELS (1LL << 30)
typedef struct {
    int width, height, nchan;
    char names[SH_IMAGE_MAX_CHANNELS][8]; /* "R","G","B","A" or "Y" */
    float *data;
} sh_image;

void sh_image_free(sh_image *img);
/* Read an OpenEXR file (scanline or tiled; half, float or uint channels; any
 * compression).  Channels R,G,B (or a single Y) are read by name; missing
 * file, corrupt file or no usable channel is an error.  OpenEXRCore is used
 * first; DWAA/DWAB data (not decodable by OpenEXRCore 3.1) falls back to the
 * ImfCRgbaFile C interface.  *used_fallback (may be NULL) reports which. */
int sh_exr_read(const char *path, sh_image *img, int *used_fallback);
/* Write a float EXR with OpenEXRCore; written to a temporary name and renamed,
 * so that a failure never leaves a partial file. */
int sh_exr_write(const char *path, const sh_image *img);

typedef enum { SH_LAYOUT_LATLONG = 0, SH_LAYOUT_PROBE } sh_layout;
int sh_layout_parse(const char *s, sh_layout *out);
/* Exact solid angle of every pixel (w*h weights, row-major). */
int sh_pixel_solid_angles(sh_layout layout, int width, int height, double *w);
/* Project each channel of an environment image: coeffs[c*n² + i]. */
int sh_project_image(const sh_image *img, sh_layout layout, int order, sh_convention conv,
                     double *coeffs);

/* Windowing against ringing: coefficient of band l scaled by sh_window_factor. */
typedef enum { SH_WINDOW_NONE = 0, SH_WINDOW_GAUSS, SH_WINDOW_HANN, SH_WINDOW_LANCZOS } sh_window_kind;
typedef struct { sh_window_kind kind; double param; } sh_window;
int sh_window_parse(const char *s, sh_window *out); /* "gauss:S", "hann:W", "lanczos:W", "none" */
double sh_window_factor(const sh_window *w, int l, int order);
/* Reconstruct nchan coefficient vectors to a width × width/2 lat-long image. */
int sh_reconstruct_latlong(int order, sh_convention conv, const double *coeffs, int nchan,
                           const sh_window *win, int width, sh_image *out);
/* Ringing of a reconstruction of one channel, on a lat-long grid of width w:
 * the most negative value (0 if none) and the fraction of ∫f² in f < 0. */
int sh_ringing(int order, sh_convention conv, const double *coeffs, const sh_window *win,
               int width, double *most_negative, double *negative_energy_fraction);

/* --------------------------------------------- more declarations by module
 * (each module appends its extra public declarations in its own section) */
/* [section: projection and lights] */
/* The number of samples sh_project really uses for `samples` (MC rounds to
 * a square N², samples <= 0 is the rule's default). */
long sh_rule_samples_used(sh_rule r, long samples);
/* Accurate projection of Green's Figure 7 light (the reading with the −3
 * inside the second max, see lights.c): analytic φ integrals, GSL QAGP in
 * cosθ with the kinks as breakpoints, to absolute/relative tolerance tol
 * (1e-12 is reachable).  order <= 64. */
int sh_green_reference(int order, sh_convention conv, double tol, double *coeffs);
/* The nodes of a rule as explicit lists (θ, φ, weight), malloc'd (caller
 * frees all three): QUAD gives S × 2S product nodes, the others the same
 * points sh_project uses for that seed, each of weight 4π/count. */
int sh_rule_nodes(sh_rule rule, long samples, unsigned long seed, double **theta, double **phi,
                  double **weight, long *count);
/* [end section: projection and lights] */
/* [section: images] */
/* Read an EXR through OpenEXR's ImfCRgbaFile C interface (the DWAA/DWAB
 * fallback of sh_exr_read; any compression the C++ library knows).  R,G,B
 * → 3 channels; a luminance-only (Y) file → 1 channel "Y"; half → float. */
int sh_exr_read_rgba(const char *path, sh_image *img);
/* Write img (1 channel → Y; 3 → RGB; 4 → RGBA) as a half-float DWAB file
 * through ImfCRgbaFile, via a temporary file renamed into place. */
int sh_exr_write_dwab_rgba(const char *path, const sh_image *img);
/* Fill a 1-channel "Y" image by point-sampling f at the pixel centres of
 * the layout.  Probe pixels wholly outside the unit disc get 0; rim pixels
 * whose centre lies outside but which overlap the disc are sampled at the
 * rim (θ = π), as sh_project_image treats them.  Allocates out->data; free
 * with sh_image_free. */
int sh_image_from_fn(sh_layout layout, int width, int height, sh_sphere_fn f, void *ctx,
                     sh_image *out);
/* Direction of the centre of pixel (x, y) (fractional pixel coordinates
 * allowed, e.g. x+0.5 is a centre).  Probe: SH_EINVAL outside the disc. */
int sh_pixel_dir(sh_layout layout, int width, int height, double x, double y, double dir[3]);
/* [end section: images] */
/* [section: triple] */
/* Wigner 3j symbols (integer j) by the Schulten-Gordon recursion in j
 * (wigner3j.c).  The family  (j j2 j3; -m2-m3 m2 m3)  for j = *jmin..*jmax
 * (jmin = max(|j2-j3|, |m2+m3|), jmax = j2+j3) is written to f[j - *jmin];
 * f needs sh_wigner3j_family_n(j2, j3) entries.  An empty family (|m| > j)
 * gives *jmin > *jmax.  Single symbols: 0 outside the selection rules; the
 * plain version returns NaN on error. */
size_t sh_wigner3j_family_n(int j2, int j3);
int sh_wigner3j_family(int j2, int j3, int m2, int m3, int *jmin, int *jmax, double *f);
int sh_wigner3j_e(int j1, int j2, int j3, int m1, int m2, int m3, double *result);
double sh_wigner3j(int j1, int j2, int j3, int m1, int m2, int m3);
/* Complex Gaunt coefficient ∫ Y_l1^m1 Y_l2^m2 Y_l3^m3 dΩ (CS phase, no
 * conjugates); sh_gaunt_real_e is sh_gaunt_real with a status (gaunt.c). */
int sh_gaunt_complex_e(int l1, int m1, int l2, int m2, int l3, int m3, double *result);
int sh_gaunt_real_e(sh_convention conv, int i, int j, int k, double *result);
/* Real-basis product expansion  y_i y_j = Σ_k G(i,j,k) y_k : the possibly
 * non-zero terms with band l3 <= lmax3 are written as (k[q], g[q]),
 * q < *count <= sh_gaunt_real_row_n(l_i, l_j); `work` holds
 * sh_gaunt_real_row_work_n(l_i, l_j) doubles. */
size_t sh_gaunt_real_row_n(int l1, int l2);
size_t sh_gaunt_real_row_work_n(int l1, int l2);
int sh_gaunt_real_row(sh_convention conv, int i, int j, int lmax3, int *k, double *g,
                      int *count, double *work);
/* Second, independent method for Green eq. 8: M_ij = ∫ f y_i y_j by the
 * product rule of `nodes` Gauss-Legendre nodes in cosθ × 2·nodes uniform φ
 * (exact when f·y_i·y_j has total band < 2·nodes). */
int sh_triple_matrix_quad(int order, sh_convention conv, sh_sphere_fn f, void *ctx, int nodes,
                          double *M);
/* [end section: triple] */
/* [section: rotation] */
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
 *         the set (b three places after a, cyclically),
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
/* [end section: rotation] */
/* [section: scaling] */
/* Spherical harmonics scaling (Wang, Lin, Guo, Shum 2006; scale.c).  The
 * subject of US patent 7,663,623; shlab implements it to verify and measure
 * it.  A monotone angular scaling function τ maps F_r to
 * F_d(θ,φ) = F_r(τ(θ),φ) ψ(θ)/sinθ and the coefficients by S_d = M S_r with
 *   M_ij = ∫∫ y_i(θ,φ) y_j(τ(θ),φ) ψ(θ) dθ dφ,
 * ψ = sinθ (plain) or sin τ·τ′ (energy-preserving).  M is n²×n² row-major,
 * zero unless m_i = m_j, and the same in both conventions. */
typedef enum { SH_SCALE_LINEAR = 0, SH_SCALE_CONE, SH_SCALE_MIDRANGE } sh_scale_family;
const char *sh_scale_family_name(sh_scale_family f);
int sh_scale_family_parse(const char *s, sh_scale_family *out);
/* Valid parameters: linear and cone k = d/r in [SH_SCALE_K_MIN, SH_SCALE_K_MAX]
 * (beyond, τ is ≈0 or ≈π almost everywhere); cone angle θ₀ in (0, π)
 * (0 means the default π/4); midrange k = d/R with |k| <= SH_SCALE_MIDRANGE_K_MAX
 * (τ′ becomes singular at θ = π/2 as |k| → 1). */
#define SH_SCALE_K_MIN 1e-3
#define SH_SCALE_K_MAX 1e3
#define SH_SCALE_MIDRANGE_K_MAX 0.999
#define SH_SCALE_MAX_ORDER 64
#define SH_SCALE_MAX_BREAKS 8
typedef struct {
    sh_scale_family family;
    double k;          /* linear, cone: d/r; midrange: signed d/R */
    double cone_angle; /* cone family θ₀ in radians; 0 = π/4 */
    int energy;        /* 0 plain (ψ = sinθ), 1 energy-preserving (ψ = sin τ·τ′) */
} sh_scaling;
/* SH_OK if the family and its parameters are valid, else SH_EINVAL. */
int sh_scaling_check(const sh_scaling *s);
/* τ(θ) and τ′(θ) of a family (CONVENTIONS.md "Scaling"); θ in [0, π]. */
int sh_scale_tau(const sh_scaling *s, double theta, double *tau, double *dtau);
/* Kinks / fast turns of τ in (0, π) (at most SH_SCALE_MAX_BREAKS); returns the count. */
int sh_scale_breaks(const sh_scaling *s, double *breaks);
/* Scratch sizes (doubles) for sh_scale_matrix / sh_scale_matrix_tau and for
 * sh_scale_integrals_tau; work may be NULL (then it is allocated). */
size_t sh_scale_matrix_work_n(int order);
size_t sh_scale_work_n(int order);
/* The scaling matrix of a family, θ integral to ~1e-15 (analytic φ). */
int sh_scale_matrix(int order, const sh_scaling *s, double *M, double *work);
/* The same for any monotone τ given as a function (τ and τ′ at θ), with up to
 * SH_SCALE_MAX_BREAKS points in (0, π) where τ is not smooth. */
typedef void (*sh_scale_tau_fn)(double theta, void *ctx, double *tau, double *dtau);
int sh_scale_matrix_tau(int order, sh_scale_tau_fn tau, void *ctx, int energy, const double *breaks,
                        int nbreaks, double *M, double *work);
/* The distinct θ integrals I_m(l_i, l_j) (M_ij = 2π I_|m|), m = 0..N−1 blocks of
 * (N−m)² entries, row-major in (l_i−m, l_j−m); sh_scale_integrals_n(N) of them. */
size_t sh_scale_integrals_n(int order);
int sh_scale_integrals_tau(int order, sh_scale_tau_fn tau, void *ctx, int energy, const double *breaks,
                           int nbreaks, double *I, double *work);
/* Second, independent computation: 2-D product rule with sh_eval in the given
 * convention (φ numerically), GSL glfixed `nodes` × `panels` per piece in θ. */
int sh_scale_matrix_quad(int order, sh_convention conv, const sh_scaling *s, int nodes, int panels,
                         double *M);
/* N(2N²+1)/3, the number of (i, j) with m_i = m_j; the entries of M with
 * |M_ij| > rel·max|M| (rel = 1e-12 in CONVENTIONS.md). */
long sh_scale_pattern_bound(int order);
long sh_scale_nonzeros(int order, const double *M, double rel);
/* τ of a family as an sh_scale_tau_fn (ctx: const sh_scaling *, checked). */
void sh_scale_family_tau(double theta, void *ctx, double *tau, double *dtau);
/* Interpolation over k (scale_interp.c, Wang Sec. 2.2): tabulate M at
 * `samples` k from kmin to kmax (geometric or uniform), interpolate each
 * entry in k (linear, or GSL natural cubic spline) and compare with M
 * computed directly at `dense` points (same spacing, ends included):
 * largest absolute entry error and RMS over all m_i = m_j entries. */
typedef enum { SH_SPACING_GEOMETRIC = 0, SH_SPACING_UNIFORM } sh_scale_spacing;
typedef enum { SH_INTERP_LINEAR = 0, SH_INTERP_CUBIC } sh_scale_interp_kind;
const char *sh_scale_spacing_name(sh_scale_spacing s);
int sh_scale_spacing_parse(const char *s, sh_scale_spacing *out);
const char *sh_scale_interp_name(sh_scale_interp_kind k);
int sh_scale_interp_parse(const char *s, sh_scale_interp_kind *out);
double sh_scale_grid_point(sh_scale_spacing sp, double a, double b, int q, int n);
typedef struct { double max_error, rms_error, worst_k; } sh_scale_interp_result;
int sh_scale_interp_error(int order, const sh_scaling *base, int samples, sh_scale_spacing spacing,
                          double kmin, double kmax, sh_scale_interp_kind interp, int dense,
                          sh_scale_interp_result *res);
/* Progress of a long computation: called after each of `total` steps
 * (`done` of them finished), `what` naming the phase.  Never required. */
typedef void (*sh_progress_fn)(void *ctx, int done, int total, const char *what);
/* sh_scale_interp_error with progress (samples + dense steps); fn may be NULL. */
int sh_scale_interp_error_progress(int order, const sh_scaling *base, int samples,
                                   sh_scale_spacing spacing, double kmin, double kmax,
                                   sh_scale_interp_kind interp, int dense,
                                   sh_scale_interp_result *res, sh_progress_fn fn, void *ctx);
/* Scaling about an arbitrary axis a (scale_axis.c, [Wang Sec. 3.2]): rotate
 * so that a becomes +z, scale, rotate back:
 *   S_d = R_sh(Q⁻¹) M R_sh(Q) S_r,   Q a = ẑ,
 * Q the shortest such rotation (about a × ẑ; π about x for a = −ẑ).  M is a
 * +z scaling matrix (sh_scale_matrix); the result does not depend on the
 * twist of Q about ẑ.  method: an exact general rotation method (not z, not
 * the Taylor approximations).  a need not be normalised; a = +ẑ exactly
 * applies M alone.  in and out have order² entries (in-place allowed). */
int sh_scale_axis_unit(const double axis[3], double unit[3]);
int sh_scale_axis_is_z(const double axis[3]);
int sh_scale_axis_rotation(const double axis[3], sh_rotation *to_z);
int sh_scale_apply_axis(int order, sh_convention conv, const double *M, const double axis[3], sh_rot_method method,
                        const double *in, double *out);
/* Scenes with ground truth for scaling (scale_scene.c): sphere occluder
 * (exact cap), cone occluder (non-zonal rim on a cone: the cone family is
 * exact geometry), mid-range environment on a sphere of radius R (ray-sphere
 * intersection).  k: d/r (occluders, reference sample at k = 1) or d/R
 * (midrange, reference at the centre k = 0).  Occluders lie along +z; the
 * midrange point moves to k·R·dir for any direction dir (all zero = +z),
 * and a direction other than +z is scaled by sh_scale_apply_axis with the
 * scene's rotation method. */
typedef enum { SH_SCENE_SPHERE = 0, SH_SCENE_CONE, SH_SCENE_MIDRANGE } sh_scale_scene_kind;
const char *sh_scale_scene_name(sh_scale_scene_kind k);
int sh_scale_scene_parse(const char *s, sh_scale_scene_kind *out);
typedef struct {
    sh_scale_scene_kind kind;
    double size;       /* sphere: ρ/r; cone: rim height h/r above the apex */
    double cone_angle; /* cone occluder half-angle θ0 in (0, π/2) */
    double wobble;     /* cone: rim at h(1 + wobble·cosφ), |wobble| < 1 */
    sh_sphere_fn light;        /* midrange: emitted radiance by direction from the centre */
    void *light_ctx;
    const sh_image *probe;     /* midrange: or a lat-long image (luminance, bilinear) */
    int nodes;                 /* midrange: θ nodes of the direct projections (QUAD rule) */
    double dir[3];             /* midrange: displacement direction (need not be unit); 0,0,0 = +z */
    sh_rot_method rotation;    /* midrange with dir ≠ +z: rotation method; SH_ROT_Z (0) = zxzxz */
} sh_scale_scene;
/* The scene's displacement direction as a unit vector (+z for 0,0,0). */
int sh_scale_scene_dir(const sh_scale_scene *sc, double unit[3]);
typedef struct { double err_scaled, err_geom, err_trunc; } sh_scale_scene_err;
int sh_scale_scene_check(const sh_scale_scene *sc, double k);
double sh_scale_scene_k_ref(const sh_scale_scene *sc);
/* The exact scene function at k (occlusion 1/0, or radiance). */
double sh_scale_scene_value(const sh_scale_scene *sc, double k, double theta, double phi);
/* Exact projection of the scene at k. */
int sh_scale_scene_exact(const sh_scale_scene *sc, int order, sh_convention conv, double k, double *c);
/* Projection of the scaled, untruncated reference function F_r(τ)ψ/sinθ. */
int sh_scale_scene_scaled_exact(const sh_scale_scene *sc, int order, sh_convention conv, const sh_scaling *s,
                                double *c);
/* Relative L2 errors (see scale_scene.c) of scaling S_r (NULL: the exact
 * projection at the reference k) to k with s; scaled_out (may be NULL)
 * receives M S_r. */
int sh_scale_scene_errors(const sh_scale_scene *sc, int order, sh_convention conv, const sh_scaling *s,
                          double k, const double *S_r, sh_scale_scene_err *e, double *scaled_out);
/* Built-in smooth two-lobe environment for the midrange scene. */
double sh_scale_scene_lobes_fn(const double d[3], double theta, double phi, void *ctx);
/* [end section: scaling] */

/* [section: taylor] */
/* Derivatives of R_Y(β) = R_sh(Ry(β)) and Krivánek et al.'s (2005) Taylor
 * approximations (rotation_deriv.c, taylor_error.c, rot_taylor.c).  Blocks use
 * the layout of sh_rot_block_offset; J = dR_Y/dβ at β = 0 (CONVENTIONS.md). */
#define SH_DERIV_MAX_ORDER 64 /* the Ivanic-Ruedenberg recursion loses digits above */
/* d^k R_Y/dβ^k at β, bands 0..order-1, by Krivánek's Appendix A: the Leibniz
 * rule carried through the Ivanic-Ruedenberg recursion (derivation in
 * rotation_deriv.c).  blocks: sh_rot_block_offset(order) doubles.  Any
 * k ≥ 0 and any finite β (reduced modulo 2π with remainder()); SH_EINVAL
 * when an entry would overflow (entries grow like (order−1)^k; for order
 * ≤ 2 they never do).  Cost and memory grow with k (the recursion carries
 * every derivative 0..k: O(k²) per entry). */
int sh_rot_deriv_recursion(int order, int k, double beta, sh_convention conv, double *blocks);
/* The same by the generator: R_Y(β)·J^k, R_Y(β) from the zxzxz method and J
 * from its closed form (sh_rot_deriv_J_band). */
int sh_rot_deriv_generator(int order, int k, double beta, sh_convention conv, double *blocks);
/* J of band l, (2l+1)² row-major, closed form from the angular-momentum
 * ladder (the only non-zeros are m' = m ± 1, never between m = 0 and m = −1). */
int sh_rot_deriv_J_band(int l, sh_convention conv, double *block);
/* J's sub-diagonal in band l, CS: s[j] = J[m][m−1] at m = j − l for j = 1..2l,
 * s[0] = 0 (the super-diagonal is −s by antisymmetry). */
void sh_rot_deriv_J_subdiag(int l, double *s);
/* D(β) = R_Y(β) − approx(R_Y(β)) for taylor = SH_ROT_TAYLOR1/15/2: its
 * singular values (GSL one-sided Jacobi SVD, band by band: D is block
 * diagonal) give max (largest) and mean (mean of all order² values); lobe =
 * ‖D c‖₂, c the unit coefficient vector of max(0, cosθ)^lobe_exp about +z.
 * R_Y(β) exact from the zxzxz method, the approximation from the taylor plan
 * itself.  The same in both conventions (S D S has D's singular values, and
 * c is zonal). */
typedef struct { double beta, max, mean, lobe; } sh_taylor_err;
int sh_taylor_error(int order, sh_rot_method taylor, double beta, double lobe_exp, sh_taylor_err *out);
/* Only the lobe error (cheaper: no SVD). */
int sh_taylor_lobe_error(int order, sh_rot_method taylor, double beta, double lobe_exp, double *lobe);
/* The singular values of D(β), band by band concatenated (order² values). */
int sh_taylor_singular_values(int order, sh_rot_method taylor, double beta, double *sv);
/* The largest β in [0, beta_max] such that the lobe error stays <= tol for
 * every β' <= β (scan at step `step`, then bisection of the first crossing to
 * 1e-10 rad); beta_max if it never crosses. */
int sh_taylor_lobe_limit(int order, sh_rot_method taylor, double lobe_exp, double tol,
                         double beta_max, double step, double *beta_lim);
/* [end section: taylor] */
/* [section: rotation speed] */
/* Timing of the rotation methods (rotation_bench.c) and the choice of the
 * cheapest method for an error budget (rotation_choose.c).  Generic over the
 * methods table: every method built in (including the Taylor approximations
 * once registered) can be timed, measured and chosen. */
typedef enum {
    SH_BENCH_PER_ROTATION = 0, /* per vector: matrix → sh_rotation → plan_set → apply */
    SH_BENCH_BATCHED           /* one set, then `batch` vectors applied; per vector */
} sh_bench_mode;
const char *sh_bench_mode_name(sh_bench_mode m);
typedef struct {
    int count;     /* timed iterations per repeat; 0 = calibrated to ~target_ms */
    int repeat;    /* timed repeats (median/min/max over them); ≥ 1 */
    int batch;     /* vectors per set in SH_BENCH_BATCHED; ≥ 1 */
    double target_ms; /* calibration target per repeat (count = 0); 0 = 5 ms */
    double max_beta;  /* the random rotations have β uniform in [0, max_beta] (the
                         z method is always timed at β = 0, its only domain) */
    uint64_t seed;    /* rotations and vectors (deterministic) */
    sh_convention conv; /* convention of the plans timed (default SH_CS) */
} sh_bench_opts;
#define SH_BENCH_OPTS_DEFAULT {0, 11, 16, 5.0, 3.14159265358979323846, 12345u, SH_CS}
typedef struct {
    double ns_median, ns_min, ns_max; /* ns per rotated vector, over the repeats */
    double mults;        /* counted multiplications per rotated vector:
                            set + apply (per rotation), set/batch + apply (batched) */
    double mults_per_ns; /* mults / ns_median */
    uint64_t set_mults, apply_mults; /* as sh_rot_plan_mults reports them */
    int count;           /* iterations per repeat actually used */
    double checksum;     /* sum of outputs (keeps the work observable) */
} sh_bench_result;
/* Time one (order, method, precision, mode).  A rotation is given to the
 * plan as a user holding an orthonormal 3×3 frame must: copy R, extract the
 * ZYZ angles (sh_euler_from_matrix), sh_rot_plan_set, sh_rot_plan_apply.
 * A warm-up repeat precedes the timed ones (CLOCK_MONOTONIC).  SH_EINVAL
 * for a method that is not built in or an order it refuses. */
int sh_rot_bench(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                 const sh_bench_opts *opts, sh_bench_result *res);
/* ns to build an sh_rotation from an orthonormal matrix as above (angles
 * only) — the part of every per-rotation time that no method can avoid. */
double sh_rot_bench_setup_ns(const sh_bench_opts *opts);

/* Error of a method's rotation against the exact one (CONVENTIONS.md,
 * "Taylor-approximated rotation"), computed generically: D = R_method −
 * R_exact for the rotation (α, β, γ) block by block, R_exact from the MPFR
 * reference plan (use_reference) or the zxzxz plan in double (accurate to
 * ~1e-15 for order ≤ 100; zxzxz then measures 0 against itself).  max = largest singular value of
 * D, mean = mean of all n² singular values (GSL one-sided Jacobi SVD per
 * band), lobe = ‖D c‖₂, c the unit coefficient vector of max(0, cosθ)^e
 * about +z (sh_lobe_zonal).  Since Z(α), Z(γ) are orthogonal and c is
 * zonal, these equal the measures of R_Y(β) − approx(R_Y(β)). */
typedef struct { double max, mean, lobe; } sh_rot_error;
typedef struct sh_rot_errws sh_rot_errws;
int sh_rot_errws_create(int order, double lobe_exp, int use_reference, sh_rot_errws **out);
/* The same with every plan (truth and methods) in convention conv (the
 * above: SH_CS).  The measures do not depend on it. */
int sh_rot_errws_create_conv(int order, double lobe_exp, int use_reference, sh_convention conv,
                             sh_rot_errws **out);
/* Set the rotation: computes the exact blocks once. */
int sh_rot_errws_set(sh_rot_errws *w, const sh_rotation *rot);
/* Error of a method (plans are created on first use and kept). */
int sh_rot_errws_eval(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err);
/* The same, also writing all order² singular values to sv (band l's, in
 * decreasing order, at sv[l²..l²+2l]) when sv is not NULL. */
int sh_rot_errws_eval_sv(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err,
                         double *sv);
void sh_rot_errws_free(sh_rot_errws *w);

/* The cheapest method for an error budget (rotation_choose.c): every method
 * built in (reference excluded; z only if max_beta = 0) is measured (against
 * the MPFR reference up to order 32, zxzxz above) over the
 * β grid 0, h, 2h, …, max_beta (h ≤ beta_step) at seeded α, γ, and timed
 * (sh_rot_bench per rotation, short); candidates whose largest error stays
 * ≤ tolerance are ranked by ns_median. */
typedef enum { SH_MEASURE_LOBE = 0, SH_MEASURE_MAX } sh_error_measure;
const char *sh_error_measure_name(sh_error_measure m);
int sh_error_measure_parse(const char *s, sh_error_measure *out);
typedef struct {
    sh_rot_method method;
    int exact;
    double max_error;  /* largest error over the β grid (the chosen measure) */
    double worst_beta; /* where */
    double ns_per_rotation, mults;
    int ok;            /* max_error ≤ tolerance */
} sh_rot_candidate;
typedef struct {
    int order;
    double max_beta, tolerance, lobe_exp, beta_step;
    sh_error_measure measure;
    sh_precision prec;
    double target_ms; /* timing per repeat (0: 2 ms) */
    int repeat;       /* 0: 5 */
    sh_progress_fn progress; /* optional: after each β of the grid, then each method timed */
    void *progress_ctx;
    sh_convention conv;      /* convention of the plans measured and timed (0: SH_CS) */
    /* optional: the cost of a method instead of timing it (ns per rotation;
     * tests use it to be deterministic); mults are then not counted (0) */
    double (*cost)(void *ctx, sh_rot_method m, int order);
    void *cost_ctx;
} sh_rot_choose_opts;
/* cand receives up to SH_ROT_NMETHODS candidates (sorted: admissible ones by
 * time first, then the others by error); *ncand their count; *choice and
 * *runner_up index cand (−1 when none). */
int sh_rot_choose(const sh_rot_choose_opts *o, sh_rot_candidate *cand, int *ncand, int *choice,
                  int *runner_up);
/* The smallest order ≤ max_order whose projection of the image (luminance:
 * Y, or 0.2126R + 0.7152G + 0.0722B) has relative L2 residual ≤ tol on the
 * sphere, by Parseval: ε² = (‖f‖² − Σc²)/‖f‖², ‖f‖² by the same pixel
 * quadrature as the projection.  *order_out = −1 if none ≤ max_order; the
 * residuals per order 1..max_order into resid (may be NULL). */
int sh_order_for_image(const sh_image *img, sh_layout layout, double tol, int max_order,
                       int *order_out, double *resid);
/* [end section: rotation speed] */

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_H */
