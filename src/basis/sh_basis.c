/* sh_basis.c — evaluation of the real SH basis at a point, and coefficient
 * conversions between conventions and normalisations.
 *
 *  y_l^m  = √2 K_l^m cos(mφ) P_l^m(cosθ)      m > 0
 *  y_l^m  = √2 K_l^|m| sin(|m|φ) P_l^|m|(cosθ) m < 0       (Green 2003, eq. 6)
 *  y_l^0  = K_l^0 P_l^0(cosθ)
 * P carries the Condon-Shortley phase (convention cs); convention nocs
 * multiplies every odd-m function by -1 (Ivanic & Ruedenberg's real basis).
 */
#include "core/shlab_internal.h"

#include <math.h>


void sh_dir_from_angles(double theta, double phi, double dir[3])
{
    const double st = sin(theta);
    dir[0] = st * cos(phi);
    dir[1] = st * sin(phi);
    dir[2] = cos(theta);
}

int sh_angles_from_dir(const double dir[3], double *theta, double *phi)
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(dir[k])) return sh_error(SH_EINVAL, "direction has a non-finite component");
    /* scale by the largest component first: 1e-320 or 1e200 are valid directions */
    const double big = fmax(fabs(dir[0]), fmax(fabs(dir[1]), fabs(dir[2])));
    if (!(big > 0.0)) return sh_error(SH_EINVAL, "direction vector has zero length");
    const double x = dir[0] / big, y = dir[1] / big, z = dir[2] / big;
    /* atan2 of (|xy|, z) is accurate near the poles, unlike acos(z/r) */
    *theta = atan2(hypot(x, y), z);
    double p = atan2(y, x);
    if (p < 0.0) p += 2.0 * M_PI;
    if (p >= 2.0 * M_PI) p = 0.0;
    *phi = p;
    return SH_OK;
}

/* Evaluate with cosθ and sinθ-free inputs: x = cosθ, azimuth phi. */
static void eval_x_phi(int order, sh_convention conv, double x, double phi, double *y)
{
    const int lmax = order - 1;
    sh__legendre_core(lmax, x, y, 1); /* Q_l^m at l(l+1)+m, m >= 0 */
    for (int m = 1; m <= lmax; m++) {
        double c = M_SQRT2 * cos(m * phi), s = M_SQRT2 * sin(m * phi);
        if (conv == SH_NOCS && (m & 1)) { c = -c; s = -s; }
        for (int l = m; l <= lmax; l++) {
            const double q = y[sh_index(l, m)];
            y[sh_index(l, m)] = q * c;
            y[sh_index(l, -m)] = q * s;
        }
    }
}

int sh_eval(int order, sh_convention conv, double theta, double phi, double *y)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!isfinite(theta) || !isfinite(phi))
        return sh_error(SH_EINVAL, "angle is not finite");
    /* Any (θ, φ) names the direction (sinθ cosφ, sinθ sinφ, cosθ).  Reduce
     * both through libm's sin/cos (exact argument reduction, unlike fmod by a
     * rounded 2π): only cosθ enters the recurrence, which assumes sinθ >= 0, so
     * sinθ < 0 is turned into the same direction at −θ, φ + π; φ goes into
     * (−π, π] so that m·φ stays small. */
    const double st_ = sin(theta), ct = cos(theta);
    double sp = sin(phi), cp = cos(phi);
    if (st_ < 0.0) { sp = -sp; cp = -cp; }
    phi = atan2(sp, cp);
    eval_x_phi(order, conv, ct, phi, y);
    return SH_OK;
}

int sh_eval_dir(int order, sh_convention conv, const double dir[3], double *y)
{
    int st = sh_check_order(order);
    if (st) return st;
    double theta, phi;
    st = sh_angles_from_dir(dir, &theta, &phi);
    if (st) return st;
    eval_x_phi(order, conv, cos(theta), phi, y);
    return SH_OK;
}

void sh__trig_table(int order, int nphi, double offset, double *t)
{
    for (int j = 0; j < nphi; j++) {
        const double phi = 2.0 * M_PI * (j + offset) / nphi;
        for (int m = 0; m < order; m++) {
            t[((size_t)j * order + m) * 2] = cos(m * phi);
            t[((size_t)j * order + m) * 2 + 1] = sin(m * phi);
        }
    }
}

/* One ring of a separable projection (Green eq. 6 with the φ sums done):
 *   c_l^0 += w Q_l^0 A_0,   c_l^{±m} += w √2 Q_l^m {A_m, B_m},
 * odd m negated in nocs. */
void sh__ring_accumulate(int order, sh_convention conv, const double *Q, double w, const double *A,
                         const double *B, double *c)
{
    for (int m = 0; m < order; m++) {
        double f = m ? M_SQRT2 * w : w;
        if (conv == SH_NOCS && (m & 1)) f = -f;
        const double fa = f * A[m], fb = f * B[m];
        for (int l = m; l < order; l++) {
            const double q = Q[sh_legendre_idx(l, m)];
            c[sh_index(l, m)] += q * fa;
            if (m) c[sh_index(l, -m)] += q * fb;
        }
    }
}

void sh_convention_switch(int order, double *coeffs)
{
    for (int l = 1; l < order; l++)
        for (int m = 1; m <= l; m += 2) {
            coeffs[sh_index(l, m)] = -coeffs[sh_index(l, m)];
            coeffs[sh_index(l, -m)] = -coeffs[sh_index(l, -m)];
        }
}

/* Basis scale of normalisation `n` relative to orthonormal nocs for band l:
 * y_n = scale · y_nocs  (4π: √(4π); Schmidt: √(4π/(2l+1))). */
static double basis_scale(sh_norm n, int l)
{
    switch (n) {
    case SH_NORM_4PI: return sqrt(4.0 * M_PI);
    case SH_NORM_SCHMIDT: return sqrt(4.0 * M_PI / (2.0 * l + 1.0));
    default: return 1.0;
    }
}

int sh_convert(int order, sh_norm from, sh_norm to, double *coeffs)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (from < SH_NORM_CS || from > SH_NORM_SCHMIDT || to < SH_NORM_CS || to > SH_NORM_SCHMIDT)
        return sh_error(SH_EINVAL, "unknown normalisation");
    /* f = Σ c_from y_from = Σ c_from s_from y_nocs  ⇒  c_nocs = c_from · s_from,
     * then c_to = c_nocs / s_to.  The phase: cs → nocs flips odd m. */
    if (from == SH_NORM_CS) sh_convention_switch(order, coeffs);
    for (int l = 0; l < order; l++) {
        const double f = basis_scale(from, l) / basis_scale(to, l);
        if (f != 1.0)
            for (int m = -l; m <= l; m++) coeffs[sh_index(l, m)] *= f;
    }
    if (to == SH_NORM_CS) sh_convention_switch(order, coeffs);
    return SH_OK;
}
