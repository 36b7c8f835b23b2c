/* shlab/convention.h — other people's SH conventions: a descriptor, its spec
 * string, the user's basis at a direction, conversions to and from shlab's
 * coefficients, and the identification of a convention from data
 * (docs/CONVENTIONS.md "Other conventions" and "Identify a convention").
 * Part of the public API: include <shlab.h>, which includes every part.
 *
 * shlab's own basis is the reference: real, orthonormal, Condon-Shortley
 * phase, ACN index l(l+1)+m, sin(|m|φ) for m < 0, z up ("cs").  A descriptor
 * says how a user's basis U_k differs:
 *
 *   kind    real | complex (all m, entry l(l+1)+m) | complex-half (m >= 0,
 *           HEALPix order: entry m(2·lmax+1−m)/2 + l, lmax = order−1);
 *           complex numbers are interleaved doubles (re, im): a complex
 *           vector of N entries is 2N doubles.  The complex Y_l^m are the
 *           standard orthonormal ones, Y_l^m = K P_l^m(cosθ) e^{imφ} with
 *           Y_l^{−m} = (−1)^m conj(Y_l^m) (cs); nocs multiplies m > 0 odd by −1.
 *   phase   cs | nocs (nocs: the real functions of odd |m| negated)
 *   norm    ortho | 4pi | schmidt | sn3d (= schmidt) | n3d (= 4pi) | fuma
 *           (scale of band l relative to orthonormal: 1, √(4π), √(4π/(2l+1)),
 *           fuma = schmidt × Furse-Malham's weights: W 1/√2, band 1: 1,
 *           band 2: R 1, S T U V 2/√3, band 3: K 1, L M √(45/32), N O 3/√5,
 *           P Q √(8/5); bands 0..3 only).  Complex kinds are orthonormal only.
 *   index   acn (l(l+1)+m) | mdesc (m = l..−l within a band) | cossin
 *           (m = 0, +1, −1, +2, −2, ...: cos1 sin1 cos2 sin2) | fuma-order
 *           (W X Y Z R S T U V K L M N O P Q; bands 0..3 only)
 *   neg     neg-sin: sin(|m|φ) for m < 0 (shlab) | neg-cos: cos for m < 0
 *           and sin for m > 0
 *   axes    z-up | y-up (= +x+z-y) | y-up-lh (= +x+z+y, a mirror) | any of
 *           the 48 signed permutations written as three signed letters: the
 *           user's coordinates (u_x, u_y, u_z) in terms of the (x, y, z)
 *           that shlab's formulas take, e.g. +x+z-y: u = (x, z, −y).
 *
 * The user's basis function k at a direction whose coordinates the user's
 * code receives as d is  U_k(d) = w_k · y_{l,±m}(s),  s the coordinates with
 * u = d (the axes' inverse), w_k the norm and phase.  A conversion keeps the
 * represented function of those same coordinates:
 *     Σ_i c_shlab,i y_i(d) = Σ_k c_user,k U_k(d)   for every d,
 * so a vector projected by the user from a light written in coordinates
 * converts to shlab's projection of the same formula.  For complex kinds
 * the function kept is the real part (a real function's coefficients
 * convert exactly; from shlab they are always those of a real function).
 *
 * Spec strings: comma-separated tokens in any order, each field at most once,
 * missing fields take shlab's value (real, cs, ortho, acn, neg-sin, z-up).
 * Whole-spec presets: cs, nocs (orthonormal), 4pi and schmidt (no phase:
 * `shlab convert`'s historical names), ambix (real,nocs,sn3d,acn),
 * fuma (real,nocs,fuma,fuma-order), healpix (complex-half,cs). */
#ifndef SHLAB_CONVENTION_H
#define SHLAB_CONVENTION_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { SH_KIND_REAL = 0, SH_KIND_COMPLEX, SH_KIND_COMPLEX_HALF } sh_conv_kind;
typedef enum {
    SH_CNORM_ORTHO = 0,
    SH_CNORM_4PI,
    SH_CNORM_SCHMIDT,
    SH_CNORM_SN3D, /* the same functions as SH_CNORM_SCHMIDT */
    SH_CNORM_N3D,  /* the same functions as SH_CNORM_4PI */
    SH_CNORM_FUMA
} sh_conv_norm;
typedef enum { SH_CINDEX_ACN = 0, SH_CINDEX_MDESC, SH_CINDEX_COSSIN, SH_CINDEX_FUMA } sh_conv_index;
#define SH_CONV_NAXES 48
/* FuMa (norm or index) covers bands 0..3: orders up to 4. */
#define SH_CONV_FUMA_MAX_ORDER 4

typedef struct {
    sh_conv_kind kind;
    int cs;              /* 1: Condon-Shortley phase */
    sh_conv_norm norm;
    sh_conv_index index; /* real kinds only */
    int neg_cos;         /* 1: cos(|m|φ) for m < 0, sin for m > 0 (real kinds) */
    int axes;            /* 0..47, 0 = z-up: perm = axes/8 of {xyz,xzy,yxz,yzx,zxy,zyx},
                            bit i of axes%8: the user's coordinate i is negated */
} sh_conv;

/* shlab's own convention (real, cs, ortho, acn, neg-sin, z-up). */
sh_conv sh_conv_shlab(void);
/* Parse a spec (see above); SH_EINVAL with the reason, naming the token. */
int sh_conv_parse(const char *spec, sh_conv *out);
/* The full spec, every field written ("real,cs,ortho,acn,neg-sin,z-up");
 * buf of at least 64 bytes.  Returns buf. */
char *sh_conv_format(const sh_conv *c, char *buf, size_t n);
/* The preset name this descriptor equals field by field, or NULL. */
const char *sh_conv_preset(const sh_conv *c);
/* 1 if the axes are a mirror (improper: determinant −1). */
int sh_conv_axes_mirror(int axes);
/* The 3×3 matrix S (row-major) with s = S d: shlab's formula coordinates of
 * the user's coordinates d. */
void sh_conv_axes_matrix(int axes, double S[9]);
/* SH_OK if the descriptor is valid at this order (FuMa: order <= 4). */
int sh_conv_check(const sh_conv *c, int order);
/* Doubles in a user vector of this order: n² real, 2n² complex,
 * n(n+1) complex-half. */
size_t sh_conv_ndoubles(const sh_conv *c, int order);
/* The order whose vector has `ndoubles` doubles, or SH_EINVAL. */
int sh_conv_order_of(const sh_conv *c, size_t ndoubles, int *order);
/* Band l of double k of a user vector of this order. */
int sh_conv_band_of(const sh_conv *c, int order, size_t k);
/* The user's basis at user coordinates d (normalised; zero or non-finite:
 * SH_EINVAL): sh_conv_ndoubles values. */
int sh_conv_eval_dir(const sh_conv *c, int order, const double d[3], double *values);
/* user → shlab (order² doubles out) and shlab → user (ndoubles out), exact
 * inverses of each other (to rounding) on real functions.  in and out must
 * not overlap.  Axes other than z-up rotate each band (an SH rotation by
 * the signed permutation, times (−1)^l for a mirror). */
int sh_conv_to_shlab(const sh_conv *c, int order, const double *user, double *shlab);
int sh_conv_from_shlab(const sh_conv *c, int order, const double *shlab, double *user);
/* from → to through shlab's basis: in has ndoubles(from), out ndoubles(to). */
int sh_conv_convert(const sh_conv *from, const sh_conv *to, int order, const double *in,
                    double *out);

/* ------------------------------------------------------------- identify
 * The candidates: every real descriptor (phase × ortho/4pi/schmidt/fuma ×
 * acn/mdesc/cossin/fuma-order × neg-sin/neg-cos × 48 axes; FuMa only to
 * order 4) and every complex one (complex/complex-half × phase × 48 axes).
 * sn3d and n3d are the same functions as schmidt and 4pi: they appear as
 * aliases.  Candidates whose bases are the same functions (cs ≡ nocs turned
 * by π about z, neg-cos with acn ≡ mdesc, ...) form one class, named by its
 * plainest member; its other members are its aliases. */
#define SH_IDENTIFY_MAX_ORDER 16
#define SH_IDENTIFY_MAX_ALIASES 16
typedef enum { SH_ID_IDENTIFIED = 0, SH_ID_AMBIGUOUS, SH_ID_NONE } sh_id_verdict;
typedef struct {
    sh_conv conv;                   /* the class's plainest member */
    int naliases;                   /* other members (at most SH_IDENTIFY_MAX_ALIASES kept) */
    sh_conv aliases[SH_IDENTIFY_MAX_ALIASES];
    int order;                      /* the order the data was read at */
    double residual;                /* relative RMS residual at that order */
    double band_residual[SH_IDENTIFY_MAX_ORDER]; /* through bands 0..L: relative RMS */
    int fits;                       /* residual <= tol */
    int fits_through;               /* largest order L whose bands 0..L−1 fit (0: none) */
} sh_id_candidate;
typedef struct {
    sh_id_verdict verdict;
    int ncand;                      /* the fitting classes, or the nearest ones if none fits */
    sh_id_candidate *cand;          /* best first; free with sh_identify_free */
    int needs_order;                /* ambiguous: the order at which the classes differ (0: none below 9) */
    int needs_basis;                /* ambiguous from a projection: the bases differ at this order */
    double tol;
} sh_id_result;
/* From the user's basis at ndir directions (user coordinates, dirs[3j..]):
 * values[j·per_dir + k], per_dir = ndoubles of the convention at the order.
 * order 0: every kind whose vector length matches per_dir. */
int sh_identify_basis(int ndir, const double *dirs, size_t per_dir, const double *values,
                      int order, double tol, sh_id_result *res);
/* From the user's coefficients (n doubles) of a function whose shlab
 * coefficients `ref` are known to ref_order (>= the data's order). */
int sh_identify_projection(size_t n, const double *coeffs, const double *ref, int ref_order,
                           int order, double tol, sh_id_result *res);
void sh_identify_free(sh_id_result *res);
/* What `shlab identify` says of a result, for every front end: identified:
 * the convention's spec and the `shlab convert` commands to shlab's
 * coefficients (of `file`) and back; otherwise `needs`, the sentence on what
 * decides (ambiguous) or that nothing fits.  Fields that do not apply are "". */
typedef struct {
    char convention[96], to_shlab[512], from_shlab[512], needs[160];
} sh_id_text;
void sh_identify_text(const sh_id_result *res, const char *file, sh_id_text *out);

/* The fixture (data/fixtures/basis/, identify_fixture.c): the directions at
 * which a user evaluates their basis, d[3j..3j+2] (unit vectors), and
 * exact[j] = {a, b, c, n}: d = (a, b, c)/n exactly (exact may be NULL). */
#define SH_IDENTIFY_NDIRS 32
void sh_identify_directions(double *d, int exact[][4]);
/* The light the user projects: directional lights (unit d[3j..], weight
 * w[j], exact as above), f = Σ_j w_j δ(d_j). */
#define SH_IDENTIFY_NLIGHTS 3
void sh_identify_light(double *d, double *w, int exact[][4]);
/* Its projection on shlab's basis, c_i = Σ_j w_j y_i(d_j), order <= 16. */
int sh_identify_light_coeffs(int order, double *c);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_CONVENTION_H */
