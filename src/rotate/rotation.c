/* rotation.c — rotations as input: Euler angles (ZYZ, active), quaternions,
 * axis-angle, matrices (checked, optionally orthonormalised), the inverse,
 * and ZYZ extraction from a matrix, stable at and near β = 0 and β = π.
 *
 * References
 *  [1] docs/CONVENTIONS.md: R = Rz(α) Ry(β) Rz(γ),
 *        R = [[cαcβcγ − sαsγ, −cαcβsγ − sαcγ, cαsβ],
 *             [sαcβcγ + cαsγ, −sαcβsγ + cαcγ, sαsβ],
 *             [−sβcγ,          sβsγ,            cβ ]].
 *  [2] R. Green, "Spherical Harmonic Lighting: The Gritty Details" (2003),
 *      "Rotating Spherical Harmonics": β = acos R22, α = atan2(R12, R02),
 *      γ = atan2(R21, −R20), with the sinβ = 0 cases treated apart.
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>

static double wrap_pi(double a)
{
    /* to (−π, π] */
    a = remainder(a, 2 * M_PI);
    if (a <= -M_PI) a += 2 * M_PI;
    return a;
}

static void matrix_from_euler(double a, double b, double g, double *R)
{
    const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cg = cos(g), sg = sin(g);
    R[0] = ca * cb * cg - sa * sg;
    R[1] = -ca * cb * sg - sa * cg;
    R[2] = ca * sb;
    R[3] = sa * cb * cg + ca * sg;
    R[4] = -sa * cb * sg + ca * cg;
    R[5] = sa * sb;
    R[6] = -sb * cg;
    R[7] = sb * sg;
    R[8] = cb;
}

void sh_euler_from_matrix(const double R[9], double *alpha, double *beta, double *gamma)
{
    /* β from both the third column and the third row (each gives sinβ). */
    const double sb = 0.5 * (hypot(R[2], R[5]) + hypot(R[6], R[7]));
    const double b = atan2(sb, R[8]);
    /* α from the third column (Green).  Near β = 0 it is ill-conditioned on
     * its own, but only α+γ matters there and that comes from the upper-left
     * 2×2 block, which is well-conditioned:
     *   R10 − R01 = (1 + cβ) sin(α+γ),   R00 + R11 = (1 + cβ) cos(α+γ);
     * near β = π only α−γ matters:
     *   R10 + R01 = (cβ − 1) sin(α−γ),   R00 − R11 = (cβ − 1) cos(α−γ).
     * At sinβ = 0 exactly, atan2(0, 0) = 0 sets α = 0. */
    const double a = atan2(R[5], R[2]);
    double g;
    if (R[8] >= 0) {
        const double sum = atan2(R[3] - R[1], R[0] + R[4]);
        g = sum - a;
    } else {
        const double diff = atan2(-(R[3] + R[1]), -(R[0] - R[4]));
        g = a - diff;
    }
    *alpha = wrap_pi(a);
    *beta = b;
    *gamma = wrap_pi(g);
}

int sh_rotation_from_euler(double alpha, double beta, double gamma, sh_rotation *out)
{
    if (!isfinite(alpha) || !isfinite(beta) || !isfinite(gamma))
        return sh_error(SH_EINVAL, "rotation: Euler angles must be finite");
    matrix_from_euler(alpha, beta, gamma, out->R);
    /* Keep the angles as given when they are already canonical, so that a
     * fixture's angles reach every method bit for bit; otherwise re-extract. */
    if (beta >= 0 && beta <= M_PI && alpha > -M_PI && alpha <= M_PI && gamma > -M_PI &&
        gamma <= M_PI) {
        out->alpha = alpha;
        out->beta = beta;
        out->gamma = gamma;
    } else {
        sh_euler_from_matrix(out->R, &out->alpha, &out->beta, &out->gamma);
    }
    return SH_OK;
}

static int finish_from_matrix(const double *R, sh_rotation *out)
{
    memcpy(out->R, R, sizeof out->R);
    sh_euler_from_matrix(R, &out->alpha, &out->beta, &out->gamma);
    return SH_OK;
}

int sh_rotation_from_quat(const double q[4], int orthonormalize, sh_rotation *out)
{
    for (int i = 0; i < 4; i++)
        if (!isfinite(q[i])) return sh_error(SH_EINVAL, "rotation: quaternion must be finite");
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n == 0) return sh_error(SH_EINVAL, "rotation: quaternion is zero");
    if (!orthonormalize && fabs(n - 1) > 1e-6)
        return sh_error(SH_EINVAL,
                        "rotation: quaternion has norm %.17g, not 1 (use --orthonormalize to "
                        "normalise it)",
                        n);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                         2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                         2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    return finish_from_matrix(R, out);
}

int sh_rotation_from_axis_angle(const double axis[3], double angle, sh_rotation *out)
{
    if (!isfinite(axis[0]) || !isfinite(axis[1]) || !isfinite(axis[2]) || !isfinite(angle))
        return sh_error(SH_EINVAL, "rotation: axis and angle must be finite");
    const double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(n > 0) || !isfinite(n)) return sh_error(SH_EINVAL, "rotation: axis is zero");
    /* quaternion (cos t/2, sin t/2 · a) */
    const double h = 0.5 * angle, s = sin(h) / n;
    const double q[4] = {cos(h), axis[0] * s, axis[1] * s, axis[2] * s};
    return sh_rotation_from_quat(q, 1, out);
}

int sh_rotation_from_matrix(const double M[9], int orthonormalize, sh_rotation *out)
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(M[i])) return sh_error(SH_EINVAL, "rotation: matrix entries must be finite");
    double dev = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += M[3 * k + i] * M[3 * k + j];
            dev = fmax(dev, fabs(s - (i == j)));
        }
    const double det = M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
                       M[2] * (M[3] * M[7] - M[4] * M[6]);
    if (!orthonormalize && (dev > 1e-6 || det < 0))
        return sh_error(SH_EINVAL,
                        det < 0 ? "rotation: matrix has determinant %.6g < 0 (a reflection, not a "
                                  "rotation)"
                                : "rotation: matrix is not orthogonal (max|RᵀR − I| = %.3g > "
                                  "1e-6; use --orthonormalize)",
                        det < 0 ? det : dev);
    /* Polar factor by SVD: M = U Σ Vᵀ → R = U diag(1, 1, det(U Vᵀ)) Vᵀ, the
     * nearest proper rotation in the Frobenius norm. */
    gsl_matrix *U = gsl_matrix_alloc(3, 3), *V = gsl_matrix_alloc(3, 3);
    gsl_vector *S = gsl_vector_alloc(3), *work = gsl_vector_alloc(3);
    if (!U || !V || !S || !work) {
        gsl_matrix_free(U); gsl_matrix_free(V); gsl_vector_free(S); gsl_vector_free(work);
        return sh_error(SH_ENOMEM, "rotation: out of memory");
    }
    for (int i = 0; i < 9; i++) gsl_matrix_set(U, i / 3, i % 3, M[i]);
    gsl_linalg_SV_decomp_jacobi(U, V, S);
    (void)work;
    double R[9], d = 0;
    if (gsl_vector_get(S, 2) <= 1e-300) {
        gsl_matrix_free(U); gsl_matrix_free(V); gsl_vector_free(S); gsl_vector_free(work);
        return sh_error(SH_EINVAL, "rotation: matrix is singular; no rotation is near it");
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double s = 0;
                for (int k = 0; k < 3; k++) {
                    double f = (pass == 1 && k == 2 && d < 0) ? -1 : 1;
                    s += f * gsl_matrix_get(U, i, k) * gsl_matrix_get(V, j, k);
                }
                R[3 * i + j] = s;
            }
        d = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
            R[2] * (R[3] * R[7] - R[4] * R[6]);
        if (d > 0) break;
    }
    gsl_matrix_free(U); gsl_matrix_free(V); gsl_vector_free(S); gsl_vector_free(work);
    return finish_from_matrix(R, out);
}

void sh_rotation_inverse(const sh_rotation *in, sh_rotation *out)
{
    sh_rotation t;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) t.R[3 * i + j] = in->R[3 * j + i];
    /* (Rz(α)Ry(β)Rz(γ))⁻¹ = Rz(−γ)Ry(−β)Rz(−α) = Rz(π−γ)Ry(β)Rz(−π−α) */
    if (in->beta == 0) {
        t.alpha = wrap_pi(-(in->alpha + in->gamma));
        t.beta = 0;
        t.gamma = 0;
    } else {
        t.alpha = wrap_pi(M_PI - in->gamma);
        t.beta = in->beta;
        t.gamma = wrap_pi(-M_PI - in->alpha);
    }
    *out = t;
}

void sh_rotation_compose(const sh_rotation *A, const sh_rotation *B, sh_rotation *C)
{
    double R[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += A->R[3 * i + k] * B->R[3 * k + j];
            R[3 * i + j] = s;
        }
    finish_from_matrix(R, C);
}

void sh_rotation_to_quat(const sh_rotation *rot, double q[4])
{
    /* Shepperd (1978): take the largest of 4w², 4x², 4y², 4z² (from the
     * trace and the diagonal) as the pivot, so no square root of a small
     * difference is taken. */
    const double *R = rot->R;
    const double t = R[0] + R[4] + R[8];
    double w, x, y, z;
    if (t >= R[0] && t >= R[4] && t >= R[8]) {
        const double s = 2 * sqrt(1 + t);
        w = s / 4; x = (R[7] - R[5]) / s; y = (R[2] - R[6]) / s; z = (R[3] - R[1]) / s;
    } else if (R[0] >= R[4] && R[0] >= R[8]) {
        const double s = 2 * sqrt(1 + R[0] - R[4] - R[8]);
        w = (R[7] - R[5]) / s; x = s / 4; y = (R[1] + R[3]) / s; z = (R[2] + R[6]) / s;
    } else if (R[4] >= R[8]) {
        const double s = 2 * sqrt(1 - R[0] + R[4] - R[8]);
        w = (R[2] - R[6]) / s; x = (R[1] + R[3]) / s; y = s / 4; z = (R[5] + R[7]) / s;
    } else {
        const double s = 2 * sqrt(1 - R[0] - R[4] + R[8]);
        w = (R[3] - R[1]) / s; x = (R[2] + R[6]) / s; y = (R[5] + R[7]) / s; z = s / 4;
    }
    const double sg = w < 0 ? -1 : 1, n = sqrt(w * w + x * x + y * y + z * z);
    q[0] = sg * w / n; q[1] = sg * x / n; q[2] = sg * y / n; q[3] = sg * z / n;
}

void sh_rotation_to_axis_angle(const sh_rotation *rot, double axis[3], double *angle)
{
    double q[4];
    sh_rotation_to_quat(rot, q);
    const double s = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    *angle = 2 * atan2(s, q[0]);
    if (s == 0) {
        axis[0] = 0; axis[1] = 0; axis[2] = 1;
    } else {
        axis[0] = q[1] / s; axis[1] = q[2] / s; axis[2] = q[3] / s;
    }
}
