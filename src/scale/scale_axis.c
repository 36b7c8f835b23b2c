/* scale_axis.c — SH scaling about an arbitrary axis (Wang et al. 2006,
 * Sec. 3.2: "rotate to the axis, scale, rotate back").
 *
 * The families of scale.c scale about +z.  For a unit axis a, let Q be a
 * rotation with Q a = ẑ.  If g(s) = f(Q⁻¹ s) (coefficients R_sh(Q) c_f, the
 * function rotation of docs/CONVENTIONS.md), then a displacement of f along a is
 * a displacement of g along ẑ, so
 *
 *     S_d = R_sh(Q⁻¹) · M · R_sh(Q) · S_r,      R_sh(Q⁻¹) = R_sh(Q)ᵀ.
 *
 * Q is not unique (any Rz(γ)·Q also takes a to ẑ); M couples only equal m
 * with equal values for ±m, so it commutes with every R_sh(Rz(γ)) and the
 * result does not depend on the choice.  We take the shortest rotation:
 * about a × ẑ by the angle between a and ẑ (atan2(|a × ẑ|, a_z)); for
 * a = −ẑ, π about x; for a = +ẑ the identity (no rotation is applied).
 *
 * References
 *  [1] J. Wang, S. Lin, B. Guo, H.-Y. Shum, "Spherical harmonics scaling",
 *      The Visual Computer 22 (2006), Sec. 3.2.
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int sh_scale_axis_unit(const double axis[3], double unit[3])
{
    if (!axis) return sh_error(SH_EINVAL, "scaling axis: none given");
    if (!isfinite(axis[0]) || !isfinite(axis[1]) || !isfinite(axis[2]))
        return sh_error(SH_EINVAL, "scaling axis: components must be finite");
    /* scale before squaring: no overflow or underflow for any finite axis */
    const double big = fmax(fabs(axis[0]), fmax(fabs(axis[1]), fabs(axis[2])));
    if (!(big > 0.0)) return sh_error(SH_EINVAL, "scaling axis: direction vector has zero length");
    const double x = axis[0] / big, y = axis[1] / big, z = axis[2] / big, n = sqrt(x * x + y * y + z * z);
    unit[0] = x / n, unit[1] = y / n, unit[2] = z / n;
    return SH_OK;
}

int sh_scale_axis_is_z(const double axis[3])
{
    return axis && axis[0] == 0.0 && axis[1] == 0.0 && axis[2] > 0.0;
}

int sh_scale_axis_rotation(const double axis[3], sh_rotation *to_z)
{
    double a[3];
    int st = sh_scale_axis_unit(axis, a);
    if (st) return st;
    const double s = hypot(a[0], a[1]);
    if (s == 0.0) {
        if (a[2] > 0.0) return sh_rotation_from_euler(0.0, 0.0, 0.0, to_z);
        const double x[3] = {1.0, 0.0, 0.0};
        return sh_rotation_from_axis_angle(x, M_PI, to_z);
    }
    /* Rodrigues: R a = a cosθ + (â × a) sinθ with â = a × ẑ/|a × ẑ|,
     * (a × ẑ) × a = ẑ − a cosθ, |a × ẑ| = sinθ  ⇒  R a = ẑ. */
    const double ax[3] = {a[1] / s, -a[0] / s, 0.0};
    return sh_rotation_from_axis_angle(ax, atan2(s, a[2]), to_z);
}

int sh_scale_apply_axis(int order, sh_convention conv, const double *M, const double axis[3], sh_rot_method method,
                        const double *in, double *out)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!M || !in || !out) return sh_error(SH_EINVAL, "scale about an axis: NULL argument");
    double a[3];
    if ((st = sh_scale_axis_unit(axis, a))) return st;
    if (!sh_rot_method_is_exact(method) || method == SH_ROT_Z)
        return sh_error(SH_EINVAL, "scale about an axis: rotation method %s is not an exact general rotation",
                        sh_rot_method_name(method));
    const int n = sh_ncoeff(order);
    double *buf = malloc(sizeof(double) * 2 * (size_t)n);
    if (!buf) return sh_error(SH_ENOMEM, "scale about an axis: out of memory");
    double *u = buf, *v = buf + n;
    sh_rot_plan *plan = NULL;
    sh_rotation Q, Qi;
    const int rotate = !sh_scale_axis_is_z(a);
    if (rotate) {
        st = sh_scale_axis_rotation(a, &Q);
        if (!st) sh_rotation_inverse(&Q, &Qi);
        if (!st) st = sh_rot_plan_create(order, method, SH_PREC_DOUBLE, conv, &plan);
        if (!st) st = sh_rot_plan_set(plan, &Q);
        if (!st) st = sh_rot_plan_apply(plan, in, u); /* to the axis: u = R_sh(Q) S_r */
    } else {
        memcpy(u, in, sizeof(double) * (size_t)n);
    }
    if (!st) { /* scale about +z: v = M u  ([1] eq. 5) */
        for (int i = 0; i < n; i++) {
            double acc = 0.0;
            for (int j = 0; j < n; j++) acc += M[(size_t)i * n + j] * u[j];
            v[i] = acc;
        }
    }
    if (!st && rotate) st = sh_rot_plan_set(plan, &Qi);
    if (!st) { /* and back: out = R_sh(Q⁻¹) v */
        if (rotate) st = sh_rot_plan_apply(plan, v, out);
        else memcpy(out, v, sizeof(double) * (size_t)n);
    }
    sh_rot_plan_free(plan);
    free(buf);
    return st;
}
