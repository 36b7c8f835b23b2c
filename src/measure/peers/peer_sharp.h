/* peer_sharp.h — libsharp (Debian libsharp-dev, C API) as a peer of shlab's
 * spherical harmonic transforms: an independent oracle for the tests and a
 * yardstick for `shlab bench --peers`.  Linked into the CLI and the tests that
 * use it, never into libshlab.  Built without libsharp, every call returns
 * SH_ENOTSUP ("libsharp was not found when shlab was built").
 *
 * Conventions, derived and checked numerically (tests/project/test_sht_sharp.c):
 * libsharp's map2alm/alm2map use complex a_lm, m ≥ 0, with
 *   f = Σ_l [a_l0 Y_l0 + Σ_{m>0} 2 Re(a_lm Y_lm)],  Y_lm = Q_l^m(cosθ) e^{imφ}
 * (Q the orthonormal Legendre functions with the Condon-Shortley phase, as in
 * shlab's cs basis), hence for m > 0
 *   a_lm = (c_l^m − i c_l^{−m}) / √2,   c_l^m = √2 Re a_lm,  c_l^{−m} = −√2 Im a_lm,
 * and a_l0 = c_l^0; map2alm sums w_ring·f·conj(Y_lm) with the ring weight as
 * given (the Gauss geometry's weights include 2π/nphi). */
#ifndef SHLAB_PEER_SHARP_H
#define SHLAB_PEER_SHARP_H

#include "shlab.h"

typedef struct sh_peer_sharp sh_peer_sharp;

/* Non-zero if libsharp is built in. */
int sh_peer_sharp_available(void);
/* libsharp's own Gauss-Legendre geometry: lmax+1 rings (north to south) of
 * 2·lmax+2 points from φ = 0, triangular a_lm to lmax.  The map layout is
 * shlab's: map[ring·nphi + j]. */
int sh_peer_sharp_gauss(int lmax, sh_peer_sharp **out);
/* The rings of a shlab grid (θ = acos(cos_theta) is what libsharp takes;
 * libsharp recomputes cosθ from it, so its rings differ from shlab's by
 * rounding near the poles). */
int sh_peer_sharp_grid(int lmax, const sh_grid *g, sh_peer_sharp **out);
/* libsharp's rings as libsharp computes with them (cosθ, weight): build an
 * sh_grid on exactly these rings to compare the transforms alone.  The
 * second ring of each of libsharp's pairs is given at exactly −cosθ of the
 * first, where libsharp evaluates it (its own cth of that ring can differ by
 * an ulp); the pairs are then pairs for shlab too. */
int sh_peer_sharp_rings(const sh_peer_sharp *s, int *nrings, int *nphi, double *cos_theta,
                        double *weight, double *phi0);
/* One thread count for libsharp's OpenMP regions (process-wide: it calls
 * omp_set_num_threads; shlab's own regions name their thread count). */
void sh_peer_sharp_threads(int nthreads);
/* The timed calls: map2alm (analysis) and alm2map (synthesis) with libsharp's
 * complex a_lm kept inside the peer object. */
int sh_peer_sharp_map2alm(sh_peer_sharp *s, const double *map);
int sh_peer_sharp_alm2map(sh_peer_sharp *s, double *map);
/* Conversion between the held a_lm and shlab's real cs coefficients
 * (order lmax+1, flat index l(l+1)+m). */
void sh_peer_sharp_get_cs(const sh_peer_sharp *s, double *coeffs);
void sh_peer_sharp_set_cs(sh_peer_sharp *s, const double *coeffs);
void sh_peer_sharp_destroy(sh_peer_sharp *s);

/* How far a result is from a peer's: *rel_l2 = ‖a − b‖₂ / ‖b‖₂ (normwise),
 * *max_rel = max|a − b| / max|b|.  Available without libsharp too. */
void sh_peer_agreement(const double *a, const double *b, size_t n, double *rel_l2, double *max_rel);

#endif
