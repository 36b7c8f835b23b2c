/* shlab_internal.h — declarations shared between library files, not installed. */
#ifndef SHLAB_INTERNAL_H
#define SHLAB_INTERNAL_H

#include "shlab.h"

#include <signal.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* error.c: copy src into dst (cap bytes, always terminated) as one printable
 * line: control characters as \n, \r, \t or \xNN, bytes that are not UTF-8
 * (and the C1 controls) as \xNN; "..." marks a cut.  Used by sh_error and by
 * the CLI for every message that quotes input.  Returns dst. */
char *sh__escape_line(char *dst, size_t cap, const char *src);

/* number.c: read one number at s (strtod; *end after it).  SH__NUM_NONE: no
 * number there; SH__NUM_RANGE: infinite, NaN, or outside double's range
 * (overflow, or underflow of a non-zero value to 0 or a subnormal). */
enum { SH__NUM_OK = 0, SH__NUM_NONE, SH__NUM_RANGE };
int sh__parse_double(const char *s, char **end, double *out);

/* legendre.c: Q_l^m(x) for 0<=m<=l<=lmax, stored at l(l+1)/2+m (sh_layout=0)
 * or at the SH flat index l(l+1)+m (sh_layout=1). */
void sh__legendre_core(int lmax, double x, double *out, int sh_layout);

/* sh_basis.c: pieces of the separable (ring by ring) projections.
 * sh__trig_table fills t[(j·order + m)·2 + {0,1}] = {cos, sin}(m φ_j) with
 * φ_j = 2π(j + offset)/nphi.  sh__ring_accumulate adds one ring of latitude:
 * given Q_l^m(cosθ) (triangular layout, sh_legendre_idx) and the azimuthal
 * sums A_m = Σ_j f_j cos(mφ_j), B_m = Σ_j f_j sin(mφ_j), it adds
 * w·Q_l^0·A_0 to c_l^0 and w·√2·Q_l^m·{A_m, B_m} to c_l^{±m} (Green eq. 6;
 * odd m negated in nocs). */
void sh__trig_table(int order, int nphi, double offset, double *t);
void sh__ring_accumulate(int order, sh_convention conv, const double *Q, double w, const double *A,
                         const double *B, double *c);

/* gauss_legendre.c: S-point Gauss-Legendre nodes x[0..S) and weights w on
 * [−1,1] (GSL's glfixed table, every node polished by Newton steps on P_S:
 * GSL's computed nodes for sizes outside its tables are good to ~1e-10 only). */
int sh__gauss_legendre(long S, double *x, double *w);

/* io/tempfile.c: atomic output.  sh__make_temp_path creates an empty
 * temporary file next to `path` (mkstemp, name malloc'd into *tmp_out, and
 * registered for sh__temp_files_unlink); sh__commit_temp renames it onto
 * `path` (removing it on failure); sh__discard_temp removes it.  Neither
 * frees the name (the caller does).  Writers write the temp, then commit,
 * so a failure never leaves a partial output file. */
int sh__make_temp_path(const char *path, char **tmp_out);
int sh__commit_temp(const char *tmp, const char *path);
void sh__discard_temp(const char *tmp);
/* An existing temporary (made by sh__make_temp_path) opened for writing by
 * name, safely against a signal handler in another thread (tempfile.c). */
FILE *sh__temp_fopen(const char *tmp, const char *mode);
/* The window around a library call that opens a temporary by name itself
 * (OpenEXR's writers): signals blocked in this thread, and the signal
 * handler of another thread waits until sh__temp_leave (tempfile.c). */
void sh__temp_enter(sigset_t *old);
void sh__temp_leave(const sigset_t *old);

/* light_zonal.c: the zonal coefficients z[l] (of y_l^0, l < order) of
 * max(0, cosθ)^e about +z scaled to a unit vector (sh_lobe_zonal / its norm). */
int sh__lobe_zonal_unit(double e, int order, double *z);

/* memory.c: the memory the machine has available now (MemAvailable, else
 * free pages; the address-space limit, ulimit -v, when lower; SIZE_MAX if
 * unknown); a size as "1.2 GB", "34.5 MB", "12 kB";
 * SH_OK if `bytes` fit in 7/8 of it, else SH_ENOMEM with "<what> needs X of
 * memory; Y is available". */
size_t sh__mem_available(void);
const char *sh__bytes_str(double bytes, char *buf, size_t n);
#define SH__MEM_CHECK_FROM (64.0 * 1024 * 1024) /* smaller requests are not checked */
int sh__mem_check(double bytes, const char *what);

/* rotator.c: 1 if a rotator of this order, method, precision and kernel
 * (SH_KERNEL_AUTO: the one auto picks) applies one rotation to one vector
 * with the method's own one-vector kernel, else 0.  The cost model
 * (lab/cost_model.c) calibrates those rows apart from the method's others. */
int sh__rot_one_vector(int order, sh_rot_method method, sh_precision prec, sh_rot_kernel kernel);

#ifdef __cplusplus
}
#endif
#endif
