/* lights.c — analytic spherical light functions: parsing and evaluation.
 *
 * References
 *  [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *      Figure 7 (example light) and "Creating Light Sources" (CIE skies).
 *  [2] P. Moon, D. E. Spencer, "Illumination from a non-uniform sky",
 *      Illuminating Engineering 37 (1942) 707 (the CIE overcast sky).
 *  [3] CIE S 011/E:2003 (ISO 15469), spatial distribution of daylight; the
 *      clear sky of Kittler (1967) adopted by CIE in 1973 and the
 *      intermediate ("partly cloudy") sky in the simplified single-channel
 *      forms Green quotes.
 *
 * Green's Figure 7 light.  The OCR'd paper prints
 *     light(θ,φ) = max(0, 5cosθ − 4) + max(0, −4 sin(θ−π) cos(φ−2.5)) − 3     (A)
 * but with the −3 outside both max() the light is negative almost everywhere
 * and c_0 = −3·√(4π) + (small positive parts) ≈ −10.1, against Green's printed
 * c_0 = 0.39925.  Reading
 *     light(θ,φ) = max(0, 5cosθ − 4) + max(0, −4 sin(θ−π) cos(φ−2.5) − 3)    (B)
 * (note −4 sin(θ−π) = 4 sinθ) gives c_0 = 0.3995 (sh_green_reference, exact
 * to 1e-12), and the other 15 printed numbers agree within the spread of
 * Green's 10,000-sample stratified Monte Carlo.  Reading (B) is implemented.
 * The numbers are in tests/project/test_project.c and the report of this module.
 *
 * CIE skies (θ = zenith angle of the direction, γ = angle between direction
 * and sun, S = zenith angle of the sun, L_z = 1, and every sky is 0 below
 * the horizon, cosθ <= 0):
 *   overcast  (1 + 2cosθ)/3.  Green prints (1 + 2 sinβ)/3 with β "the angle
 *             between zenith and P", which would make the horizon the
 *             brightest part of the sky: the Moon & Spencer law [2] is in the
 *             elevation angle, sin(elevation) = cosθ.
 *   clear     (0.91 + 10e^{−3γ} + 0.45cos²γ)(1 − e^{−0.32/cosθ})
 *             / ((0.91 + 10e^{−3S} + 0.45cos²S)(1 − e^{−0.32}))  — as printed.
 *   partly    (0.526 + 5e^{−1.5γ})(1 − e^{−0.8/cosθ})
 *             / ((0.526 + 5e^{−1.5S})(1 − e^{−0.8})).  Green prints cosγ in
 *             the exponent of the gradation term; the gradation of luminance
 *             with height is a function of the zenith angle θ (as in the clear
 *             sky formula, and as L(zenith) = L_z requires).
 */
#include "core/shlab_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Parse exactly `n` comma-separated finite numbers from s. */
static int parse_numbers(const char *spec, const char *s, int n, double *v)
{
    const char *p = s;
    for (int k = 0; k < n; k++) {
        char *end;
        if (!*p || *p == ',' || *p == ' ')
            return sh_error(SH_EINVAL, "light '%s': expected %d number%s after ':'", spec, n,
                            n > 1 ? "s" : "");
        double x = 0;
        const int r = sh__parse_double(p, &end, &x);
        if (r == SH__NUM_NONE)
            return sh_error(SH_EINVAL, "light '%s': cannot read a number at '%.20s'", spec, p);
        if (r == SH__NUM_RANGE)
            return sh_error(SH_EINVAL, "light '%s': number %d is not finite or is outside double's "
                            "range (it overflows or underflows)", spec, k + 1);
        v[k] = x;
        p = end;
        if (k + 1 < n) {
            if (*p != ',')
                return sh_error(SH_EINVAL, "light '%s': expected %d comma-separated numbers", spec, n);
            p++;
        }
    }
    if (*p) return sh_error(SH_EINVAL, "light '%s': unexpected '%.20s' after the parameters", spec, p);
    return SH_OK;
}

int sh_light_parse(const char *spec, int degrees, sh_light *out)
{
    if (!spec || !out) return sh_error(SH_EINVAL, "light: no spec given");
    const double deg = degrees ? M_PI / 180.0 : 1.0;
    const char *colon = strchr(spec, ':');
    size_t nl = colon ? (size_t)(colon - spec) : strlen(spec);
    const char *arg = colon ? colon + 1 : NULL;
    sh_light L = {SH_LIGHT_GREEN, {0.0, 0.0}};
    int st;
#define NAME_IS(s) (nl == strlen(s) && strncmp(spec, s, nl) == 0)
    if (NAME_IS("green") || NAME_IS("cie-overcast")) {
        if (arg) return sh_error(SH_EINVAL, "light '%s': '%.*s' takes no parameters", spec, (int)nl, spec);
        L.kind = NAME_IS("green") ? SH_LIGHT_GREEN : SH_LIGHT_CIE_OVERCAST;
    } else if (NAME_IS("cap") || NAME_IS("const") || NAME_IS("lobe")) {
        if (!arg) return sh_error(SH_EINVAL, "light '%s': expected '%.*s:VALUE'", spec, (int)nl, spec);
        if ((st = parse_numbers(spec, arg, 1, L.p))) return st;
        if (NAME_IS("cap")) {
            L.kind = SH_LIGHT_CAP;
            L.p[0] *= deg;
            if (!(L.p[0] >= 0.0 && L.p[0] <= M_PI * (1.0 + 1e-15)))
                return sh_error(SH_EINVAL, "light '%s': cap half-angle must be in [0, pi] (%s)", spec,
                                degrees ? "[0, 180] degrees" : "radians; use --degrees for degrees");
            if (L.p[0] > M_PI) L.p[0] = M_PI;
        } else if (NAME_IS("const")) {
            L.kind = SH_LIGHT_CONST;
            /* shading, errors and pictures square and sum the radiance: keep
             * those finite (1e308 gave an exposure of 0 and infinite pixels) */
            if (!(fabs(L.p[0]) <= SH_LIGHT_MAX_VALUE))
                return sh_error(SH_EINVAL, "light '%s': the constant must be at most %g in magnitude", spec,
                                SH_LIGHT_MAX_VALUE);
        } else {
            L.kind = SH_LIGHT_LOBE;
            if (!(L.p[0] >= 0.0)) return sh_error(SH_EINVAL, "light '%s': lobe exponent must be >= 0", spec);
        }
    } else if (NAME_IS("cie-clear") || NAME_IS("cie-partly")) {
        if (!arg)
            return sh_error(SH_EINVAL, "light '%s': expected '%.*s:THETA,PHI' (sun position)", spec, (int)nl,
                            spec);
        if ((st = parse_numbers(spec, arg, 2, L.p))) return st;
        L.kind = NAME_IS("cie-clear") ? SH_LIGHT_CIE_CLEAR : SH_LIGHT_CIE_PARTLY;
        L.p[0] *= deg;
        L.p[1] *= deg;
        if (!(L.p[0] >= 0.0 && L.p[0] <= M_PI_2 * (1.0 + 1e-15)))
            return sh_error(SH_EINVAL, "light '%s': sun zenith angle must be in [0, pi/2] (%s)", spec,
                            degrees ? "[0, 90] degrees" : "radians; use --degrees for degrees");
        if (L.p[0] > M_PI_2) L.p[0] = M_PI_2;
    } else {
        return sh_error(SH_EINVAL,
                        "unknown light '%s' (expected green, cap:T, cie-overcast, cie-clear:THETA,PHI, "
                        "cie-partly:THETA,PHI, const:V or lobe:E)",
                        spec);
    }
#undef NAME_IS
    *out = L;
    return SH_OK;
}

/* Green's Figure 7 light, reading (B) (see the top of this file). */
static double green_light(double theta, double phi)
{
    const double c = cos(theta), s = sin(theta);
    const double a = 5.0 * c - 4.0;
    const double b = 4.0 * s * cos(phi - 2.5) - 3.0; /* −4 sin(θ−π) = 4 sinθ */
    return (a > 0.0 ? a : 0.0) + (b > 0.0 ? b : 0.0);
}

/* cos of the angle between unit direction d and the sun at (θs, φs). */
static double cos_to_sun(const double d[3], const double sun[2])
{
    double s[3];
    sh_dir_from_angles(sun[0], sun[1], s);
    double c = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
    return c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
}

double sh_light_eval(const sh_light *L, const double dir[3], double theta, double phi)
{
    const double cz = dir[2]; /* cosθ of the (unit) direction */
    switch (L->kind) {
    case SH_LIGHT_GREEN: return green_light(theta, phi);
    case SH_LIGHT_CAP: return theta < L->p[0] ? 1.0 : 0.0;
    case SH_LIGHT_CONST: return L->p[0];
    case SH_LIGHT_LOBE: return cz > 0.0 ? pow(cz, L->p[0]) : 0.0;
    case SH_LIGHT_CIE_OVERCAST: return cz > 0.0 ? (1.0 + 2.0 * cz) / 3.0 : 0.0;
    case SH_LIGHT_CIE_CLEAR: {
        if (!(cz > 0.0)) return 0.0;
        const double g = acos(cos_to_sun(dir, L->p)), S = L->p[0];
        const double cg = cos(g), cs = cos(S);
        const double num = (0.91 + 10.0 * exp(-3.0 * g) + 0.45 * cg * cg) * (-expm1(-0.32 / cz));
        const double den = (0.91 + 10.0 * exp(-3.0 * S) + 0.45 * cs * cs) * (-expm1(-0.32));
        return num / den;
    }
    case SH_LIGHT_CIE_PARTLY: {
        if (!(cz > 0.0)) return 0.0;
        const double g = acos(cos_to_sun(dir, L->p)), S = L->p[0];
        const double num = (0.526 + 5.0 * exp(-1.5 * g)) * (-expm1(-0.8 / cz));
        const double den = (0.526 + 5.0 * exp(-1.5 * S)) * (-expm1(-0.8));
        return num / den;
    }
    }
    return 0.0;
}

double sh_light_fn(const double dir[3], double theta, double phi, void *ctx)
{
    return sh_light_eval((const sh_light *)ctx, dir, theta, phi);
}

int sh_light_has_closed_form(const sh_light *L)
{
    return L->kind == SH_LIGHT_CAP || L->kind == SH_LIGHT_CONST || L->kind == SH_LIGHT_LOBE;
}
