/* shlab/scale.h — SH scaling (Wang et al. 2006): matrices, interpolation over k, scenes.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_SCALE_H
#define SHLAB_SCALE_H

#include "core.h"
#include "project.h"
#include "rotate.h"

#ifdef __cplusplus
extern "C" {
#endif

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
#define SH_SCALE_MAX_BREAKS 16
typedef struct {
    sh_scale_family family;
    double k;          /* linear, cone: d/r; midrange: signed d/R */
    double cone_angle; /* cone family θ₀ in radians; 0 = π/4 */
    int energy;        /* 0 plain (ψ = sinθ), 1 energy-preserving (ψ = sin τ·τ′) */
} sh_scaling;
/* SH_OK if the family and its parameters are valid, else SH_EINVAL. */
int sh_scaling_check(const sh_scaling *s);
/* τ(θ) and τ′(θ) of a family (docs/CONVENTIONS.md "Scaling"); θ in [0, π]. */
int sh_scale_tau(const sh_scaling *s, double theta, double *tau, double *dtau);
/* Kinks / fast turns of τ in (0, π), in increasing order (at most
 * SH_SCALE_MAX_BREAKS: the cone family far from k = 1 adds graded points
 * around its turn); returns the count. */
int sh_scale_breaks(const sh_scaling *s, double *breaks);
/* Scratch sizes (doubles) for sh_scale_matrix / sh_scale_matrix_tau and for
 * sh_scale_integrals_tau; work may be NULL (then it is allocated). */
size_t sh_scale_matrix_work_n(int order);
size_t sh_scale_work_n(int order);
/* The scaling matrix of a family, θ integral to ~1e-15 (analytic φ; 1.7e-12
 * at order 64 and the ends of the k ranges, docs/ranges.md). */
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
 * |M_ij| > rel·max|M| (rel = 1e-12 in docs/CONVENTIONS.md). */
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
/* sh_scale_interp_error with progress (samples + dense steps); fn may be NULL. */
int sh_scale_interp_error_progress(int order, const sh_scaling *base, int samples,
                                   sh_scale_spacing spacing, double kmin, double kmax,
                                   sh_scale_interp_kind interp, int dense,
                                   sh_scale_interp_result *res, sh_progress_fn fn, void *ctx);
/* The same in two steps, for a sweep split into shards: the error at each
 * point d of the dense grid in items (NULL: every point; the
 * sampled table is computed in full either way) — the point's k, its
 * largest entry error, Σ w·err² and Σ w over its entries (w = 2 for m ≠ 0) —
 * then the result from all points in grid order (the first point with the
 * largest error gives worst_k). */
typedef struct { double k, max_error, sum_sq, weight; } sh_scale_interp_point;
int sh_scale_interp_points(int order, const sh_scaling *base, int samples, sh_scale_spacing spacing,
                           double kmin, double kmax, sh_scale_interp_kind interp, int dense,
                           const sh_items *items, sh_scale_interp_point *pts, sh_progress_fn fn,
                           void *ctx);
int sh_scale_interp_reduce(const sh_scale_interp_point *pts, int dense, sh_scale_interp_result *res);
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

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_SCALE_H */
