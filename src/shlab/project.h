/* shlab/project.h — projection rules, analytic lights, environment maps, windowing and
 * reconstruction.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_PROJECT_H
#define SHLAB_PROJECT_H

#include "core.h"
#include "io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------- projection */

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
 * const:V with |V| ≤ SH_LIGHT_MAX_VALUE, lobe:E); angles in degrees when
 * `degrees` is non-zero. */
#define SH_LIGHT_MAX_VALUE 1e100
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

/* The largest order an image can carry: the sampling bound of a band limit
 * n, 2n − 1 samples in φ and n in θ (lat-long; 2n − 1 across an angle map).
 * sh_project_image computes the discrete sums at any order; above this one
 * they are not a projection (the CLI refuses them). */
int sh_image_max_order(const sh_image *img, sh_layout layout);
/* SH_OK if the image carries `order` (order <= sh_image_max_order), else
 * SH_EINVAL with "a W×H image carries orders up to M (2n − 1 pixels across,
 * n down), not N". */
int sh_image_check_order(const sh_image *img, sh_layout layout, int order);
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
/* Orthonormality of a rule (orthonormality.c): the Gram matrix
 * G_ij = Σ_k w_k y_i(s_k) y_j(s_k) of its nodes (sh_rule_nodes with samples
 * and seed) for bands 0..order-1, and err[l] = max |G_ij − δ_ij| over i, j
 * in bands 0..l: err[n−1] is the error at order n (cumulative, so
 * non-decreasing).  The same in both conventions.  nodes (may be NULL): the
 * number of nodes used.  progress (may be NULL) is called per chunk of 256
 * nodes.  Memory ≈ order⁴/2 doubles; order <= SH_GRAM_MAX_ORDER. */
#define SH_GRAM_MAX_ORDER 64
int sh_rule_gram_error(sh_rule rule, long samples, unsigned long seed, int order, sh_convention conv,
                       double *err, long *nodes, sh_progress_fn progress, void *ctx);
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

/* ------------------------------------- fast transforms on rings (sht.c)
 * A grid of rings of latitude: ring r at cosθ_r = cos_theta[r] holds nphi
 * points φ_j = phi0 + 2πj/nphi.  A map of nchan channels is
 * map[(c·nrings + r)·nphi + j]; coefficients are coeffs[c·order² + i].
 *   analysis   c_i = Σ_r weight[r] Σ_j f(θ_r, φ_j) y_i(θ_r, φ_j)
 *              (the quadrature of ∫ f y_i dΩ; weight[r] is the weight of each
 *              point of ring r, Δφ included),
 *   synthesis  f(θ_r, φ_j) = Σ_i c_i y_i(θ_r, φ_j),
 * so analysis = synthesisᵀ · diag(weights).  An FFT in φ per ring (FFTW3) and
 * the Legendre recurrence run across pairs of rings at ±cosθ (paired when
 * their cos_theta are exact negatives): O(order²·nrings + nrings·nphi·log nphi)
 * instead of the O(order²·nrings·nphi) of a direct sum.  Any nphi (aliasing
 * of m ≥ nphi/2 as the direct sum has it).  nthreads: OpenMP threads used
 * across rings and across m (0: all cores); results are bitwise the same for
 * every count.  A plan is used by one call at a time. */
typedef struct {
    int nrings, nphi;
    const double *cos_theta; /* [nrings], each in [−1, 1] */
    const double *weight;    /* [nrings] or NULL (then only synthesis) */
    double phi0;             /* azimuth of the first point of every ring */
} sh_grid;
typedef struct sh_sht sh_sht;
/* Gauss-Legendre rings (north to south) × nphi uniform φ from 0, weights
 * w_GL·2π/nphi: exact for band-limited products of total band < 2·nrings
 * when nphi exceeds the total band.  Arrays of nrings entries. */
int sh_grid_gauss(int nrings, int nphi, double *cos_theta, double *weight, sh_grid *g);
/* The lat-long layout W×H (docs/CONVENTIONS.md): ring j at θ = π(j+½)/H, φ0 = π/W,
 * weight = the exact pixel solid angle (weight may be NULL). */
int sh_grid_latlong(int width, int height, double *cos_theta, double *weight, sh_grid *g);
/* Bytes a plan needs (its tables, chunk buffers and per-thread scratch; the
 * map and coefficients are the caller's); 0 for an invalid request.
 * cos_theta may be NULL: the rings are then taken to pair up (the size
 * before the rings are made). */
size_t sh_sht_bytes(int order, const sh_grid *g, int nchan, int nthreads);
int sh_sht_create(int order, const sh_grid *g, int nchan, int nthreads, sh_sht **out);
void sh_sht_destroy(sh_sht *p);
int sh_sht_analysis(sh_sht *p, sh_convention conv, const double *map, double *coeffs);
int sh_sht_synthesis(sh_sht *p, sh_convention conv, const double *coeffs, double *map);
/* Progress after each chunk of rings (called from the calling thread). */
void sh_sht_set_progress(sh_sht *p, sh_progress_fn fn, void *ctx);
/* The kernel instruction set chosen for this CPU: "avx512f", "avx2+fma", "baseline". */
const char *sh_sht_kernel_name(const sh_sht *p);

/* Options of the heavy projection and reconstruction calls (the plain calls
 * use one thread and no progress). */
typedef struct {
    int nthreads;               /* 0: all cores; results do not depend on it */
    sh_progress_fn progress;    /* may be NULL */
    void *progress_ctx;
} sh_run_opts;
#define SH_RUN_OPTS_DEFAULT {1, NULL, NULL}
/* sh_project with options.  With nthreads != 1 the function f is called from
 * several threads at once and must allow that. */
int sh_project_ex(int order, sh_convention conv, sh_sphere_fn f, void *ctx, sh_rule rule,
                  long samples, unsigned long seed, const sh_run_opts *opts, double *coeffs);
int sh_project_image_ex(const sh_image *img, sh_layout layout, int order, sh_convention conv,
                        const sh_run_opts *opts, double *coeffs);
int sh_reconstruct_latlong_ex(int order, sh_convention conv, const double *coeffs, int nchan,
                              const sh_window *win, int width, const sh_run_opts *opts,
                              sh_image *out);
int sh_ringing_ex(int order, sh_convention conv, const double *coeffs, const sh_window *win,
                  int width, const sh_run_opts *opts, double *most_negative,
                  double *negative_energy_fraction);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_PROJECT_H */
