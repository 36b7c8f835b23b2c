/* krivanek2005_fig2.h — Křivánek et al. 2005, Figure 2, transcribed as
 * printed (three significant digits): bands 1..3 of dR_Y/dβ(0) (J) and
 * d²R_Y/dβ²(0) (J²), each band row-major with rows and columns m = −l..l.
 * Shared by tests/taylor/test_taylor.c and experiments/taylor_deriv (data, not
 * code: the paper's numbers, to be compared with shlab's). */
#ifndef SHLAB_KRIVANEK2005_FIG2_H
#define SHLAB_KRIVANEK2005_FIG2_H

#include <math.h>

/* Krivánek Figure 2 as printed (three significant digits): bands 1..3 of
 * dR_Y/dβ(0) and d²R_Y/dβ²(0).  The printed J is the nocs function rotation
 * (equivalently the cs frame rotation, Jᵀ); in cs it is −J.  J² holds in all. */
static const double fig2_J[3][49] = {
    {0, 0, 0, 0, 0, -1, 0, 1, 0},
    {0, 1, 0, 0, 0, -1, 0, 0, 0, 0, 0, 0, 0, -1.73, 0, 0, 0, 1.73, 0, -1, 0, 0, 0, 1, 0},
    {0, 1.22, 0, 0, 0, 0, 0, -1.22, 0, 1.58, 0, 0, 0, 0, 0, -1.58, 0, 0, 0, 0, 0, 0, 0, 0, 0, -2.45, 0, 0,
     0, 0, 0, 2.45, 0, -1.58, 0, 0, 0, 0, 0, 1.58, 0, -1.22, 0, 0, 0, 0, 0, 1.22, 0}};
static const double fig2_J2[3][49] = {
    {0, 0, 0, 0, -1, 0, 0, 0, -1},
    {-1, 0, 0, 0, 0, 0, -1, 0, 0, 0, 0, 0, -3, 0, 1.73, 0, 0, 0, -4, 0, 0, 0, 1.73, 0, -1},
    {-1.5, 0, 1.94, 0, 0, 0, 0, 0, -4, 0, 0, 0, 0, 0, 1.94, 0, -2.5, 0, 0, 0, 0, 0, 0, 0, -6, 0, 3.87, 0,
     0, 0, 0, 0, -8.5, 0, 1.94, 0, 0, 0, 3.87, 0, -4, 0, 0, 0, 0, 0, 1.94, 0, -1.5}};

/* x rounded to three significant digits, as the figure prints it */
static inline double sig3(double x)
{
    if (fabs(x) < 1e-12) return 0;
    const double e = floor(log10(fabs(x))) - 2, p = pow(10, e);
    return round(x / p) * p;
}

#endif
