/* shlab_internal.h — declarations shared between library files, not installed. */
#ifndef SHLAB_INTERNAL_H
#define SHLAB_INTERNAL_H

#include "shlab.h"

/* legendre.c: Q_l^m(x) for 0<=m<=l<=lmax, stored at l(l+1)/2+m (sh_layout=0)
 * or at the SH flat index l(l+1)+m (sh_layout=1). */
void sh__legendre_core(int lmax, double x, double *out, int sh_layout);

#endif
