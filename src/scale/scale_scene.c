/* scale_scene.c — scenes where SH scaling can be checked against ground
 * truth (Wang et al. 2006, Sec. 3): the function at the sampled point is
 * projected, scaled with a family's matrix, and compared with the exact
 * projection of the function at the new point.
 *
 *  sphere    occluder = sphere of radius ρ, centre O in direction +z (θ = 0)
 *            from the sample point at distance d = k r.  The occlusion is
 *            exactly the cap θ < arcsin(ρ/d)  (k > ρ/r).
 *  cone      occluder = solid cone with apex O, axis toward the sample point,
 *            half-angle θ0, cut by a rim at axial distance a(φ) = h(1 + ε cosφ)
 *            from the apex (ε ≠ 0: not zonal).  Every part of the body is seen
 *            inside the rim (the angle to a body point grows toward the rim),
 *            so the occlusion is exactly θ < β(φ) with
 *            β(φ) = atan2(a(φ) tanθ0, d − a(φ)) (d > a).  The rim lies on the
 *            cone surface: the cone family with the occluder's θ0 is exact
 *            geometry here ([1] Sec. 3.1, Fig. 4).
 *  midrange  an environment L(ω) emitted (with direction-independent
 *            radiance) from a sphere of radius R, seen from p = d a, d = kR,
 *            a the unit displacement direction (default ẑ): the radiance
 *            arriving from direction s is L(P/R) with P = p + t s the
 *            ray-sphere hit, t = −d (s·a) + √(R² − d² (1 − (s·a)²))
 *            ([1] Sec. 3.2).  For a ≠ ẑ the capture is scaled about a by
 *            sh_scale_apply_axis (rotate to the axis, scale, rotate back);
 *            the untruncated reference F_r∘τ is evaluated about a directly
 *            (3×3 matrix Q with Q a = ẑ), without SH rotations.
 *
 * Three errors, relative L2 over the coefficient vectors (Parseval: relative
 * L2 of the band-limited functions), against the exact projection E(k):
 *   err_scaled = |M S_r − E(k)| / |E(k)|          what a user of scaling gets;
 *   err_geom   = |P_N(F_r∘τ · ψ/sinθ) − E(k)|/|E|  the family's geometry alone
 *                (scaling of the exact, not truncated, function);
 *   err_trunc  = |M S_r − P_N(F_r∘τ ψ/sinθ)|/|E|   what truncating S_r costs.
 *
 * References
 *  [1] J. Wang, S. Lin, B. Guo, H.-Y. Shum, "Spherical harmonics scaling",
 *      The Visual Computer 22 (2006), Sec. 3.1-3.2, Figs. 4-7.
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Region projections: trapezoid in φ (spectral for a smooth periodic
 * boundary), Gauss-Legendre on [0, b(φ)] in θ (the integrand y_i·ψ is
 * smooth there, the step sits exactly at the end). */
#define REGION_NPHI 256
#define REGION_NTHETA 64

const char *sh_scale_scene_name(sh_scale_scene_kind k)
{
    switch (k) {
    case SH_SCENE_SPHERE: return "sphere";
    case SH_SCENE_CONE: return "cone";
    case SH_SCENE_MIDRANGE: return "midrange";
    }
    return "unknown";
}

int sh_scale_scene_parse(const char *s, sh_scale_scene_kind *out)
{
    static const sh_scale_scene_kind all[] = {SH_SCENE_SPHERE, SH_SCENE_CONE, SH_SCENE_MIDRANGE};
    for (size_t i = 0; s && i < sizeof all / sizeof *all; i++)
        if (!strcmp(s, sh_scale_scene_name(all[i]))) { *out = all[i]; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown scene '%s' (sphere, cone, midrange)", s ? s : "");
}

double sh_scale_scene_k_ref(const sh_scale_scene *sc) { return sc->kind == SH_SCENE_MIDRANGE ? 0.0 : 1.0; }

static int dir_unset(const double d[3]) { return d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0; }

int sh_scale_scene_dir(const sh_scale_scene *sc, double unit[3])
{
    if (!sc) return sh_error(SH_EINVAL, "no scene given");
    if (dir_unset(sc->dir)) {
        unit[0] = unit[1] = 0.0, unit[2] = 1.0;
        return SH_OK;
    }
    return sh_scale_axis_unit(sc->dir, unit);
}

/* The rotation method of a scene (SH_ROT_Z, the zero default, = zxzxz). */
static sh_rot_method scene_rotation(const sh_scale_scene *sc)
{
    return sc->rotation == SH_ROT_Z ? SH_ROT_ZXZXZ : sc->rotation;
}

static double rim(const sh_scale_scene *sc, double phi) { return sc->size * (1.0 + sc->wobble * cos(phi)); }

int sh_scale_scene_check(const sh_scale_scene *sc, double k)
{
    if (!sc) return sh_error(SH_EINVAL, "no scene given");
    switch (sc->kind) {
    case SH_SCENE_SPHERE:
    case SH_SCENE_CONE:
        if (!dir_unset(sc->dir) && !(sc->dir[0] == 0.0 && sc->dir[1] == 0.0 && sc->dir[2] > 0.0))
            return sh_error(SH_EINVAL, "%s scene: the occluder lies along +z; a displacement direction applies "
                                       "to the midrange scene only", sh_scale_scene_name(sc->kind));
        break;
    case SH_SCENE_MIDRANGE: {
        double a[3];
        if (sh_scale_scene_dir(sc, a)) return sh_error(SH_EINVAL, "midrange scene: %s", sh_last_error());
        const sh_rot_method m = scene_rotation(sc);
        if ((int)m < 0 || m >= SH_ROT_NMETHODS || !sh_rot_method_is_exact(m) || !sh_rot_method_max_order(m))
            return sh_error(SH_EINVAL, "midrange scene: rotation method %s is not an exact method built in",
                            (int)m >= 0 && m < SH_ROT_NMETHODS ? sh_rot_method_name(m) : "?");
        break;
    }
    }
    switch (sc->kind) {
    case SH_SCENE_SPHERE:
        if (!(sc->size > 0.0 && sc->size < 1.0))
            return sh_error(SH_EINVAL, "sphere scene: radius rho/r = %g must be in (0, 1)", sc->size);
        if (!isfinite(k) || !(k > sc->size) || k > SH_SCALE_K_MAX)
            return sh_error(SH_EINVAL, "sphere scene: k = d/r = %g must be > rho/r = %g (outside the sphere)", k,
                            sc->size);
        return SH_OK;
    case SH_SCENE_CONE: {
        const double amax = sc->size * (1.0 + fabs(sc->wobble));
        if (!(sc->cone_angle > 0.0 && sc->cone_angle < M_PI / 2.0))
            return sh_error(SH_EINVAL, "cone scene: occluder half-angle %g must be in (0, pi/2)", sc->cone_angle);
        if (!(fabs(sc->wobble) < 1.0))
            return sh_error(SH_EINVAL, "cone scene: rim wobble %g must be in (-1, 1)", sc->wobble);
        if (!(sc->size > 0.0 && amax < 1.0))
            return sh_error(SH_EINVAL, "cone scene: rim height h(1+|wobble|) = %g must be in (0, 1)", amax);
        if (!isfinite(k) || !(k > amax) || k > SH_SCALE_K_MAX)
            return sh_error(SH_EINVAL, "cone scene: k = d/r = %g must be > %g (beyond the rim)", k, amax);
        return SH_OK;
    }
    case SH_SCENE_MIDRANGE:
        if (!sc->light && !sc->probe) return sh_error(SH_EINVAL, "midrange scene: no light or probe");
        if (sc->probe && (sc->probe->nchan < 1 || !sc->probe->data))
            return sh_error(SH_EINVAL, "midrange scene: empty probe image");
        if (!isfinite(k) || fabs(k) > SH_SCALE_MIDRANGE_K_MAX)
            return sh_error(SH_EINVAL, "midrange scene: k = d/R = %g must be in [-%g, %g]", k,
                            SH_SCALE_MIDRANGE_K_MAX, SH_SCALE_MIDRANGE_K_MAX);
        if (sc->nodes < 8 || sc->nodes > 4096)
            return sh_error(SH_EINVAL, "midrange scene: %d quadrature nodes (8..4096)", sc->nodes);
        return SH_OK;
    }
    return sh_error(SH_EINVAL, "unknown scene %d", (int)sc->kind);
}

/* Occlusion boundary at k: occluded iff θ < beta(φ). */
static double occ_beta(const sh_scale_scene *sc, double k, double phi)
{
    if (sc->kind == SH_SCENE_SPHERE) return asin(sc->size / k);
    const double a = rim(sc, phi);
    return atan2(a * tan(sc->cone_angle), k - a);
}

/* ---- environment for the midrange scene ---------------------------------- */

/* Bilinear lookup of channel-averaged luminance in a lat-long image
 * (docs/CONVENTIONS.md: pixel centre θ = π(j+½)/H, φ = 2π(i+½)/W; φ wraps). */
static double probe_lookup(const sh_image *img, const double d[3])
{
    double th, ph;
    sh_angles_from_dir(d, &th, &ph);
    const int W = img->width, H = img->height;
    double x = ph / (2.0 * M_PI) * W - 0.5, y = th / M_PI * H - 0.5;
    if (y < 0) y = 0;
    if (y > H - 1) y = H - 1;
    const double fx = floor(x), fy = floor(y);
    const double ax = x - fx, ay = y - fy;
    int x0 = ((int)fx % W + W) % W, x1 = (x0 + 1) % W, y0 = (int)fy, y1 = y0 + 1 < H ? y0 + 1 : H - 1;
    static const double lum3[3] = {0.2126, 0.7152, 0.0722};
    double v = 0.0;
    const size_t plane = (size_t)W * H;
    for (int c = 0; c < (img->nchan >= 3 ? 3 : 1); c++) {
        const float *p = img->data + c * plane;
        const double wc = img->nchan >= 3 ? lum3[c] : 1.0;
        const double v00 = p[(size_t)y0 * W + x0], v01 = p[(size_t)y0 * W + x1];
        const double v10 = p[(size_t)y1 * W + x0], v11 = p[(size_t)y1 * W + x1];
        v += wc * ((1 - ay) * ((1 - ax) * v00 + ax * v01) + ay * ((1 - ax) * v10 + ax * v11));
    }
    return v;
}

static double env(const sh_scale_scene *sc, const double d[3])
{
    if (sc->probe) return probe_lookup(sc->probe, d);
    double th, ph;
    sh_angles_from_dir(d, &th, &ph);
    return sc->light(d, th, ph, sc->light_ctx);
}

/* Radiance arriving at p = k a (R = 1, |a| = 1) from direction s: the ray
 * p + t s meets |x| = 1 where t² + 2k (s·a) t + k² − 1 = 0, t > 0. */
static void ray_hit(double k, const double a[3], const double s[3], double P[3])
{
    const double b = k * (s[0] * a[0] + s[1] * a[1] + s[2] * a[2]), c = k * k - 1.0;
    const double t = -b + sqrt(b * b - c);
    for (int i = 0; i < 3; i++) P[i] = k * a[i] + t * s[i];
    const double n = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
    P[0] /= n, P[1] /= n, P[2] /= n;
}

/* a: the unit displacement direction; Q (row-major, proper) takes a to ẑ. */
typedef struct {
    const sh_scale_scene *sc;
    double k;
    const sh_scaling *s;
    double a[3], Q[9];
    int tilted;
} mid_ctx;

static int mid_ctx_init(mid_ctx *c, const sh_scale_scene *sc, double k, const sh_scaling *s)
{
    c->sc = sc, c->k = k, c->s = s;
    int st = sh_scale_scene_dir(sc, c->a);
    if (st) return st;
    c->tilted = !sh_scale_axis_is_z(c->a);
    sh_rotation q;
    if ((st = sh_scale_axis_rotation(c->a, &q))) return st;
    memcpy(c->Q, q.R, sizeof c->Q);
    return SH_OK;
}

static double mid_exact_fn(const double dir[3], double theta, double phi, void *vctx)
{
    const mid_ctx *c = vctx;
    double P[3];
    ray_hit(c->k, c->a, dir, P);
    return env(c->sc, P);
}

/* F_r(τ(θ),φ) ψ(θ)/sinθ, F_r = the environment seen from the centre; θ, φ
 * about the displacement axis: (θ, φ) of Q s, and the source direction
 * Qᵀ u(τ(θ), φ). */
static double mid_scaled_fn(const double dir[3], double theta, double phi, void *vctx)
{
    const mid_ctx *c = vctx;
    double t, dt, d[3];
    if (c->tilted) {
        double qs[3];
        for (int i = 0; i < 3; i++) qs[i] = c->Q[3 * i] * dir[0] + c->Q[3 * i + 1] * dir[1] + c->Q[3 * i + 2] * dir[2];
        sh_angles_from_dir(qs, &theta, &phi);
    }
    sh_scale_tau(c->s, theta, &t, &dt);
    sh_dir_from_angles(t, phi, d);
    if (c->tilted) {
        double u[3];
        for (int i = 0; i < 3; i++) u[i] = c->Q[i] * d[0] + c->Q[3 + i] * d[1] + c->Q[6 + i] * d[2];
        memcpy(d, u, sizeof d);
    }
    double f = env(c->sc, d);
    if (c->s->energy) {
        const double st = sin(theta);
        /* sinτ·τ′/sinθ → τ′² at the poles (τ(0) = 0, τ(π) = π) */
        f *= st > 1e-12 ? sin(t) * dt / st : dt * dt;
    }
    return f;
}

double sh_scale_scene_value(const sh_scale_scene *sc, double k, double theta, double phi)
{
    if (sc->kind != SH_SCENE_MIDRANGE) return theta < occ_beta(sc, k, phi) ? 1.0 : 0.0;
    mid_ctx c;
    if (mid_ctx_init(&c, sc, k, NULL)) return NAN;
    double d[3];
    sh_dir_from_angles(theta, phi, d);
    return mid_exact_fn(d, theta, phi, &c);
}

/* ---- region projections (occluder scenes) ------------------------------- */

/* c_i = ∫₀^{2π} ∫₀^{b(φ)} y_i(θ,φ) ψ(θ) dθ dφ with ψ = sinθ (s == NULL) or
 * the scaling's ψ; b(φ) = the exact boundary at k (s == NULL) or
 * τ⁻¹(β_r(φ)) (F_r∘τ occluded iff τ(θ) < β_r(φ), τ non-decreasing). */
static int region_project(const sh_scale_scene *sc, int order, sh_convention conv, double k,
                          const sh_scaling *s, double *c)
{
    const int n = sh_ncoeff(order);
    double *y = malloc(sizeof(double) * (size_t)n), xg[REGION_NTHETA], wg[REGION_NTHETA];
    if (!y) return sh_error(SH_ENOMEM, "scene: out of memory");
    int st = sh__gauss_legendre(REGION_NTHETA, xg, wg);
    memset(c, 0, sizeof(double) * (size_t)n);
    const double dphi = 2.0 * M_PI / REGION_NPHI;
    for (int q = 0; q < REGION_NPHI && !st; q++) {
        const double phi = dphi * q;
        double b;
        if (!s) {
            b = occ_beta(sc, k, phi);
        } else {
            /* bisection for τ(b) = β_r: 60 halvings of [0, π] reach 3e-18 */
            const double br = occ_beta(sc, sh_scale_scene_k_ref(sc), phi);
            double lo = 0.0, hi = M_PI;
            for (int it = 0; it < 64; it++) {
                const double mid = 0.5 * (lo + hi);
                double t, dt;
                sh_scale_tau(s, mid, &t, &dt);
                if (t < br) lo = mid; else hi = mid;
            }
            b = 0.5 * (lo + hi);
        }
        for (int g = 0; g < REGION_NTHETA && !st; g++) {
            const double th = 0.5 * b * (xg[g] + 1.0);
            double psi = sin(th);
            if (s && s->energy) {
                double t, dt;
                sh_scale_tau(s, th, &t, &dt);
                psi = sin(t) * dt;
            }
            st = sh_eval(order, conv, th, phi, y);
            const double w = 0.5 * b * wg[g] * psi * dphi;
            for (int i = 0; i < n; i++) c[i] += w * y[i];
        }
    }
    free(y);
    return st;
}

int sh_scale_scene_exact(const sh_scale_scene *sc, int order, sh_convention conv, double k, double *c)
{
    int st = sh_check_order(order);
    if (st) return st;
    if ((st = sh_scale_scene_check(sc, k))) return st;
    if (sc->kind == SH_SCENE_SPHERE) {
        /* zonal: the cap closed form (light_zonal.c) */
        double *z = malloc(sizeof(double) * (size_t)order);
        if (!z) return sh_error(SH_ENOMEM, "scene: out of memory");
        st = sh_cap_zonal(asin(sc->size / k), order, z);
        if (!st) {
            memset(c, 0, sizeof(double) * (size_t)sh_ncoeff(order));
            for (int l = 0; l < order; l++) c[sh_index(l, 0)] = z[l];
        }
        free(z);
        return st;
    }
    if (sc->kind == SH_SCENE_CONE) return region_project(sc, order, conv, k, NULL, c);
    mid_ctx mc;
    if ((st = mid_ctx_init(&mc, sc, k, NULL))) return st;
    return sh_project(order, conv, mid_exact_fn, &mc, SH_RULE_QUAD, sc->nodes, 0, c);
}

int sh_scale_scene_scaled_exact(const sh_scale_scene *sc, int order, sh_convention conv, const sh_scaling *s,
                                double *c)
{
    int st = sh_check_order(order);
    if (st) return st;
    if ((st = sh_scale_scene_check(sc, sh_scale_scene_k_ref(sc)))) return st;
    if ((st = sh_scaling_check(s))) return st;
    if (sc->kind != SH_SCENE_MIDRANGE) return region_project(sc, order, conv, 0.0, s, c);
    mid_ctx mc;
    if ((st = mid_ctx_init(&mc, sc, 0.0, s))) return st;
    return sh_project(order, conv, mid_scaled_fn, &mc, SH_RULE_QUAD, sc->nodes, 0, c);
}

static double l2(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) {
        const double d = a[i] - (b ? b[i] : 0.0);
        s += d * d;
    }
    return sqrt(s);
}

int sh_scale_scene_errors(const sh_scale_scene *sc, int order, sh_convention conv, const sh_scaling *s,
                          double k, const double *S_r, sh_scale_scene_err *e, double *scaled_out)
{
    int st = sh_check_order(order);
    if (st) return st;
    if ((st = sh_scale_scene_check(sc, k))) return st;
    if ((st = sh_scaling_check(s))) return st;
    const int n = sh_ncoeff(order);
    double *M = malloc(sizeof(double) * (size_t)n * n), *buf = malloc(sizeof(double) * 4 * (size_t)n);
    if (!M || !buf) { free(M); free(buf); return sh_error(SH_ENOMEM, "scene: out of memory"); }
    double *Sr = buf, *E = buf + n, *Sd = buf + 2 * n, *G = buf + 3 * n;
    if (S_r) memcpy(Sr, S_r, sizeof(double) * (size_t)n);
    else st = sh_scale_scene_exact(sc, order, conv, sh_scale_scene_k_ref(sc), Sr);
    if (!st) st = sh_scale_scene_exact(sc, order, conv, k, E);
    if (!st) st = sh_scale_matrix(order, s, M, NULL);
    if (!st) st = sh_scale_scene_scaled_exact(sc, order, conv, s, G);
    if (!st && sc->kind == SH_SCENE_MIDRANGE) {
        /* S_d = R_sh(Q⁻¹) M R_sh(Q) S_r about the displacement axis (M alone for +z) */
        double a[3];
        st = sh_scale_scene_dir(sc, a);
        if (!st) st = sh_scale_apply_axis(order, conv, M, a, scene_rotation(sc), Sr, Sd);
    } else if (!st) {
        /* S_d = M S_r  ([1] eq. 5) */
        for (int i = 0; i < n; i++) {
            double v = 0.0;
            for (int j = 0; j < n; j++) v += M[(size_t)i * n + j] * Sr[j];
            Sd[i] = v;
        }
    }
    if (!st) {
        const double ne = l2(E, NULL, n);
        if (!(ne > 0.0)) st = sh_error(SH_ENUM, "scene: the exact projection is zero");
        else {
            e->err_scaled = l2(Sd, E, n) / ne;
            e->err_geom = l2(G, E, n) / ne;
            e->err_trunc = l2(Sd, G, n) / ne;
            if (scaled_out) memcpy(scaled_out, Sd, sizeof(double) * (size_t)n);
        }
    }
    free(M);
    free(buf);
    return st;
}

/* Two smooth, non-zonal von Mises-Fisher lobes (a "red and a green source",
 * [1] Fig. 11 in spirit): exp(κ(ω·a − 1)) + 0.6 exp(κ(ω·b − 1)), κ = 8,
 * a at (θ, φ) = (50°, 30°), b at (110°, 200°). */
double sh_scale_scene_lobes_fn(const double d[3], double theta, double phi, void *ctx)
{
    static const double ta = 50.0 * M_PI / 180, pa = 30.0 * M_PI / 180;
    static const double tb = 110.0 * M_PI / 180, pb = 200.0 * M_PI / 180;
    const double a[3] = {sin(ta) * cos(pa), sin(ta) * sin(pa), cos(ta)};
    const double b[3] = {sin(tb) * cos(pb), sin(tb) * sin(pb), cos(tb)};
    const double ka = 8.0;
    const double da = d[0] * a[0] + d[1] * a[1] + d[2] * a[2], db = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
    return exp(ka * (da - 1.0)) + 0.6 * exp(ka * (db - 1.0));
}
