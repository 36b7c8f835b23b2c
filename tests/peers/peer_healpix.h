/* peer_healpix.h — HEALPix C++ (Debian libhealpix-cxx-dev) as a peer of
 * shlab's all-band rotation: the convention map between the two, shared by
 * the oracle test (test_peer_healpix.cc) and the benchmark
 * (peer_healpix_bench.cc).  C++ only at this edge; the library stays C11.
 *
 * Conventions (each checked numerically by test_peer_healpix.cc, not assumed):
 *  - basis: HEALPix's a_lm (m ≥ 0, complex; f = Σ a_lm Y_lm over m = −l..l
 *    with a_{l,−m} = (−1)^m conj(a_lm), Y_lm with the Condon-Shortley phase)
 *    and shlab's real CS coefficients c_l^m:
 *        a_l0 = c_l^0,   a_lm = (c_l^m − i c_l^{−m}) / √2   (m > 0),
 *    and back c_l^m = √2 Re a_lm, c_l^{−m} = −√2 Im a_lm.  (From
 *    y^m = √2 Re Y^m, y^{−m} = √2 Im Y^m.)
 *  - rotation: rotate_alm(alm, ψ, θ, φ) is the active rotation
 *    Rz(φ) Ry(θ) Rz(ψ) of the function, so shlab's R = Rz(α) Ry(β) Rz(γ)
 *    (g(s) = f(R⁻¹ s)) is (ψ, θ, φ) = (γ, β, α), and its inverse
 *    Rz(−γ) Ry(−β) Rz(−α) is (−α, −β, −γ).
 */
#ifndef SHLAB_PEER_HEALPIX_H
#define SHLAB_PEER_HEALPIX_H

#include <alm.h>
#include <alm_powspec_tools.h>
#include <xcomplex.h>

#include <cmath>

extern "C" {
#include "shlab.h"
}

typedef Alm<xcomplex<double> > peer_alm;

static inline void peer_to_alm(int lmax, const double *c, peer_alm &a)
{
    const double s = 1 / std::sqrt(2.0);
    for (int l = 0; l <= lmax; l++) {
        const double *b = c + (size_t)l * (l + 1);
        a(l, 0) = xcomplex<double>(b[0], 0);
        for (int m = 1; m <= l; m++) a(l, m) = xcomplex<double>(s * b[m], -s * b[-m]);
    }
}

static inline void peer_from_alm(int lmax, const peer_alm &a, double *c)
{
    const double s = std::sqrt(2.0);
    for (int l = 0; l <= lmax; l++) {
        double *b = c + (size_t)l * (l + 1);
        b[0] = a(l, 0).real();
        for (int m = 1; m <= l; m++) {
            b[m] = s * a(l, m).real();
            b[-m] = -s * a(l, m).imag();
        }
    }
}

/* shlab's rotation (α, β, γ) done by HEALPix (inverse: Rᵀ) */
static inline void peer_rotate(peer_alm &a, const sh_rotation &r, bool inverse = false)
{
    if (inverse) rotate_alm(a, -r.alpha, -r.beta, -r.gamma);
    else rotate_alm(a, r.gamma, r.beta, r.alpha);
}

/* seeded N(0, 1) coefficients */
static inline void peer_gauss(unsigned long long seed, size_t n, double *x)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u1 = ((seed >> 11) + 0.5) / 9007199254740992.0;
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u2 = ((seed >> 11) + 0.5) / 9007199254740992.0;
        x[i] = std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
    }
}

#endif
