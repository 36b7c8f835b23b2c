/* shlab_internal.h — declarations shared between library files, not installed. */
#ifndef SHLAB_INTERNAL_H
#define SHLAB_INTERNAL_H

#include "shlab.h"

/* legendre.c: Q_l^m(x) for 0<=m<=l<=lmax, stored at l(l+1)/2+m (sh_layout=0)
 * or at the SH flat index l(l+1)+m (sh_layout=1). */
void sh__legendre_core(int lmax, double x, double *out, int sh_layout);

/* gauss_legendre.c: S-point Gauss-Legendre nodes x[0..S) and weights w on
 * [−1,1] (GSL's glfixed table, every node polished by Newton steps on P_S:
 * GSL's computed nodes for sizes outside its tables are good to ~1e-10 only). */
int sh__gauss_legendre(long S, double *x, double *w);

/* exr_io.c: atomic output.  sh__make_temp_path creates an empty temporary
 * file next to `path` (mkstemp, name malloc'd into *tmp_out); sh__commit_temp
 * renames it onto `path` (removing it on failure).  Writers write the temp,
 * then commit, so a failure never leaves a partial output file. */
int sh__make_temp_path(const char *path, char **tmp_out);
int sh__commit_temp(const char *tmp, const char *path);

#endif
