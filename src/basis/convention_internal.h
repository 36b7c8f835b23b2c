/* convention_internal.h — shared by convention.c and identify.c (not installed). */
#ifndef SHLAB_CONVENTION_INTERNAL_H
#define SHLAB_CONVENTION_INTERNAL_H

#include "shlab.h"

/* Real kinds: the user's entry k is U_k = w · y_i, y_i shlab's cs function
 * at the formula coordinates (the axes not applied). */
void sh__conv_real_entry(const sh_conv *c, int k, int *i, double *w);

#endif
