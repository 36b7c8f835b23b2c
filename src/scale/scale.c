/* scale.c — spherical harmonics scaling (Wang, Lin, Guo, Shum 2006):
 * angular scaling functions τ and the scaling matrix
 *
 *     M_ij = ∫₀^{2π} ∫₀^π y_i(θ,φ) y_j(τ(θ),φ) ψ(θ) dθ dφ,
 *     ψ = sinθ (plain) or ψ = sin τ(θ) · τ′(θ) (energy-preserving),
 *
 * which maps the coefficients S_r of F_r to those of the scaled function
 * F_d(θ,φ) = F_r(τ(θ),φ) ψ(θ)/sinθ  ([1] eqs. 3-6; docs/CONVENTIONS.md "Scaling").
 * This operation is the subject of US patent 7,663,623; shlab implements it
 * to verify and measure it.
 *
 * References
 *  [1] J. Wang, S. Lin, B. Guo, H.-Y. Shum, "Spherical harmonics scaling",
 *      The Visual Computer 22 (2006), Sec. 2 (eqs. 1-6), Sec. 3.1 (cone
 *      approximation), Sec. 3.2 (mid-range lighting), Appendix (structure).
 *  [2] Gauss-Legendre nodes from sh__gauss_legendre (GSL glfixed, polished).
 *
 * The φ integral is analytic: with y_l^m = √2 Q_l^|m| trig(|m|φ) (m ≠ 0) and
 * y_l^0 = Q_l^0, ∫₀^{2π} trig_i trig_j dφ is 0 unless m_i = m_j, and then
 * 2π·(1/2)·2 = 2π (m ≠ 0) or 2π (m = 0), so
 *
 *     M_ij = 2π δ(m_i, m_j) ∫₀^π Q_{l_i}^{|m|}(cosθ) Q_{l_j}^{|m|}(cos τ(θ)) ψ(θ) dθ,   (A)
 *
 * the same for m and −m, and the same in both conventions (nocs negates y_i
 * and y_j together).  This is the m_i = m_j pattern of [1]'s Appendix.  The θ
 * integral (A) is done for every (m, l_i, l_j) at once by composite
 * Gauss-Legendre on the pieces between the kinks of τ, doubling the panels
 * until two successive estimates agree to 1e-14 (the last one is then good
 * to ~1e-16: the integrand is analytic on each piece), or until their change
 * stops halving below 1e-12 (the sums' own rounding, reached first at high
 * order: at order 64 and the ends of k the entries agree with adaptive
 * quadrature to 1.7e-12, tests/core/test_ranges.c).
 */
#include "core/shlab_internal.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Gauss-Legendre nodes per panel, the panel limit per piece, and the
 * agreement required of two successive panel doublings. */
#define SCALE_GL_NODES 24
#define SCALE_MAX_PANELS 8192
#define SCALE_TOL 1e-14
#define SCALE_FLOOR 1e-12

const char *sh_scale_family_name(sh_scale_family f)
{
    switch (f) {
    case SH_SCALE_LINEAR: return "linear";
    case SH_SCALE_CONE: return "cone";
    case SH_SCALE_MIDRANGE: return "midrange";
    }
    return "unknown";
}

int sh_scale_family_parse(const char *s, sh_scale_family *out)
{
    static const sh_scale_family all[] = {SH_SCALE_LINEAR, SH_SCALE_CONE, SH_SCALE_MIDRANGE};
    for (size_t i = 0; s && i < sizeof all / sizeof *all; i++)
        if (!strcmp(s, sh_scale_family_name(all[i]))) { *out = all[i]; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown scaling family '%s' (linear, cone, midrange)", s ? s : "");
}

static double cone_angle(const sh_scaling *s) { return s->cone_angle > 0.0 ? s->cone_angle : M_PI / 4.0; }

int sh_scaling_check(const sh_scaling *s)
{
    if (!s) return sh_error(SH_EINVAL, "no scaling given");
    const double k = s->k;
    switch (s->family) {
    case SH_SCALE_LINEAR:
    case SH_SCALE_CONE:
        if (!isfinite(k) || k < SH_SCALE_K_MIN || k > SH_SCALE_K_MAX)
            return sh_error(SH_EINVAL, "%s scaling: k = %g is outside [%g, %g] (k = d/r > 0)",
                            sh_scale_family_name(s->family), k, SH_SCALE_K_MIN, SH_SCALE_K_MAX);
        if (s->family == SH_SCALE_CONE) {
            const double t = s->cone_angle;
            if (!isfinite(t) || t < 0.0 || t >= M_PI)
                return sh_error(SH_EINVAL, "cone scaling: cone angle %g is outside (0, pi)", t);
        }
        break;
    case SH_SCALE_MIDRANGE:
        if (!isfinite(k) || fabs(k) > SH_SCALE_MIDRANGE_K_MAX)
            return sh_error(SH_EINVAL, "midrange scaling: k = %g is outside [-%g, %g] (k = d/R, |k| < 1)", k,
                            SH_SCALE_MIDRANGE_K_MAX, SH_SCALE_MIDRANGE_K_MAX);
        break;
    default: return sh_error(SH_EINVAL, "unknown scaling family %d", (int)s->family);
    }
    if (s->energy != 0 && s->energy != 1) return sh_error(SH_EINVAL, "scaling: energy must be 0 or 1");
    return SH_OK;
}

/* τ and τ′ of the three families (docs/CONVENTIONS.md "Scaling"):
 *  linear    τ = min(kθ, π),                     τ′ = k (kθ < π), 0 beyond;
 *  cone      τ = atan2(k sinθ, cosθ + (1−k) sinθ cotθ₀), i.e.
 *            cot τ = (cot θ + (1−k) cot θ₀)/k; with y = k sinθ,
 *            x = cosθ + (1−k) cotθ₀ sinθ:  x y′ − y x′ = k, so τ′ = k/(x²+y²);
 *  midrange  τ = θ − arcsin(k sinθ),  τ′ = 1 − k cosθ / √(1 − k² sin²θ).
 * The caller has checked s (sh_scaling_check). */
static void tau_eval(const sh_scaling *s, double theta, double *tau, double *dtau)
{
    const double k = s->k;
    switch (s->family) {
    case SH_SCALE_LINEAR:
        if (k * theta < M_PI) { *tau = k * theta; *dtau = k; }
        else { *tau = M_PI; *dtau = 0.0; }
        return;
    case SH_SCALE_CONE: {
        const double c = 1.0 / tan(cone_angle(s));
        const double st = sin(theta), ct = cos(theta);
        const double y = k * st, x = ct + (1.0 - k) * c * st;
        *tau = atan2(y, x);
        *dtau = k / (x * x + y * y);
        return;
    }
    case SH_SCALE_MIDRANGE: {
        const double st = sin(theta), ks = k * st;
        *tau = theta - asin(ks);
        *dtau = 1.0 - k * cos(theta) / sqrt((1.0 - ks) * (1.0 + ks));
        return;
    }
    }
    *tau = theta;
    *dtau = 1.0;
}

int sh_scale_tau(const sh_scaling *s, double theta, double *tau, double *dtau)
{
    int st = sh_scaling_check(s);
    if (st) return st;
    if (!isfinite(theta) || theta < 0.0 || theta > M_PI)
        return sh_error(SH_EINVAL, "scale tau: theta = %g is outside [0, pi]", theta);
    double t, d;
    tau_eval(s, theta, &t, &d);
    if (tau) *tau = t;
    if (dtau) *dtau = d;
    return SH_OK;
}

/* Points in (0, π) where τ has a kink (linear: θ = π/k) or changes fast
 * (midrange: θ = π/2, where τ′ has a near-singularity of width √(1−k²);
 * cone: τ = π/2, i.e. cot θ = −(1−k) cot θ₀, where τ turns over from ≈0 to
 * ≈π when k is far from 1). */
static int cmp_double(const void *a, const void *b);
int sh_scale_breaks(const sh_scaling *s, double *breaks)
{
    switch (s->family) {
    case SH_SCALE_LINEAR:
        if (s->k > 1.0) { breaks[0] = M_PI / s->k; return 1; }
        return 0;
    case SH_SCALE_CONE: {
        const double c = 1.0 / tan(cone_angle(s)), k = s->k;
        const double b = atan2(1.0, -(1.0 - k) * c);
        if (!(b > 0.0 && b < M_PI)) return 0;
        int n = 0;
        breaks[n++] = b;
        /* Near b, x ≈ x′(b)(θ − b) and τ′ = k/(x² + y²) is a Lorentzian of
         * half-width w = k sin b/|x′(b)|; for k ≫ 1 a second one sits at
         * θ = π (ε = π − θ: x² + y² ≈ 1 + 2(k−1)cε + ((k−1)²c² + k²)ε², width
         * 1/(k√(1 + c²))).  For k far from 1 uniform panels cannot resolve
         * them (cone k = 1e-3 and 1e3 had not converged at 8192 panels,
         * tests/core/test_ranges.c scale_top): graded breaks at b ± 4^j w and
         * π − 4^j w' (j = 0..4, up to the order of 1 rad) make each piece
         * smooth on its own length.  None is added when the turn is wide
         * (|ln k| small). */
        const double xp = -sin(b) + (1.0 - k) * c * cos(b), w = k * sin(b) / fabs(xp);
        if (w < 0.02)
            for (double d = w; d < 1.0 && n + 2 <= SH_SCALE_MAX_BREAKS - 5; d *= 4.0) {
                if (b - d > 0.0) breaks[n++] = b - d;
                if (b + d < M_PI) breaks[n++] = b + d;
            }
        const double wp = 1.0 / (k * sqrt(1.0 + c * c));
        if (k > 1.0 && wp < 0.02)
            for (double d = wp; d < 1.0 && n < SH_SCALE_MAX_BREAKS; d *= 4.0)
                if (M_PI - d > b) breaks[n++] = M_PI - d;
        qsort(breaks, (size_t)n, sizeof(double), cmp_double);
        return n;
    }
    case SH_SCALE_MIDRANGE: breaks[0] = M_PI / 2.0; return 1;
    }
    return 0;
}

void sh_scale_family_tau(double theta, void *ctx, double *tau, double *dtau)
{
    tau_eval((const sh_scaling *)ctx, theta, tau, dtau);
}

/* Layout of the θ integrals of (A): for m = 0..N−1 an (N−m)×(N−m) block,
 * (l_i − m, l_j − m) row-major, starting at off(m) = Σ_{m'<m} (N−m')². */
static size_t block_off(int N, int m)
{
    size_t o = 0;
    for (int q = 0; q < m; q++) o += (size_t)(N - q) * (N - q);
    return o;
}

size_t sh_scale_integrals_n(int order) { return block_off(order, order); }

size_t sh_scale_work_n(int order)
{
    if (order < 1) return 0;
    return 2 * sh_scale_integrals_n(order) + 2 * sh_legendre_n(order - 1) + 2 * SCALE_GL_NODES;
}

/* One composite Gauss-Legendre estimate of every integral of (A): `panels`
 * equal panels on each piece [e_p, e_{p+1}] of the edges e (n_edges points
 * from 0 to π).  I has sh_scale_integrals_n(N) entries. */
static int composite(int N, sh_scale_tau_fn tau, void *ctx, int energy, const double *edges, int n_edges,
                     long panels, const double *xg, const double *wg, double *Qa, double *Qb, double *I)
{
    const int lmax = N - 1;
    memset(I, 0, sizeof(double) * sh_scale_integrals_n(N));
    for (int p = 0; p + 1 < n_edges; p++) {
        const double a = edges[p], h = (edges[p + 1] - a) / (double)panels;
        for (long q = 0; q < panels; q++) {
            const double pa = a + h * (double)q;
            for (int g = 0; g < SCALE_GL_NODES; g++) {
                const double th = pa + 0.5 * h * (xg[g] + 1.0);
                double t, dt;
                tau(th, ctx, &t, &dt);
                /* ψ(θ) = sinθ (plain) or sin τ · τ′ (energy-preserving) [1] eq. 3 */
                const double psi = energy ? sin(t) * dt : sin(th);
                if (!isfinite(t) || !isfinite(psi))
                    return sh_error(SH_ENUM, "scale: tau is not finite at theta = %g", th);
                const double w = 0.5 * h * wg[g] * psi;
                if (w == 0.0) continue;
                sh__legendre_core(lmax, cos(th), Qa, 0);
                sh__legendre_core(lmax, cos(t), Qb, 0);
                /* (A): I_m(l_i, l_j) += w Q_{l_i}^m(cosθ) Q_{l_j}^m(cos τ) */
                double *Im = I;
                for (int m = 0; m < N; m++) {
                    const int nb = N - m;
                    for (int li = m; li < N; li++) {
                        const double a_i = w * Qa[sh_legendre_idx(li, m)];
                        double *row = Im + (size_t)(li - m) * nb - m;
                        for (int lj = m; lj < N; lj++) row[lj] += a_i * Qb[sh_legendre_idx(lj, m)];
                    }
                    Im += (size_t)nb * nb;
                }
            }
        }
    }
    return SH_OK;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int sh_scale_integrals_tau(int order, sh_scale_tau_fn tau, void *ctx, int energy, const double *breaks,
                           int nbreaks, double *I, double *work)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (order > SH_SCALE_MAX_ORDER)
        return sh_error(SH_EINVAL, "scale: order %d is above %d", order, SH_SCALE_MAX_ORDER);
    if (!tau || !I) return sh_error(SH_EINVAL, "scale: no tau function or output");
    if (nbreaks < 0 || nbreaks > SH_SCALE_MAX_BREAKS)
        return sh_error(SH_EINVAL, "scale: %d breakpoints (0..%d)", nbreaks, SH_SCALE_MAX_BREAKS);
    double edges[SH_SCALE_MAX_BREAKS + 2];
    int ne = 0;
    edges[ne++] = 0.0;
    for (int b = 0; b < nbreaks; b++) {
        if (!isfinite(breaks[b])) return sh_error(SH_EINVAL, "scale: breakpoint is not finite");
        if (breaks[b] > 0.0 && breaks[b] < M_PI) edges[ne++] = breaks[b];
    }
    qsort(edges + 1, (size_t)ne - 1, sizeof(double), cmp_double);
    edges[ne++] = M_PI;

    double *own = NULL;
    if (!work) {
        own = work = malloc(sizeof(double) * sh_scale_work_n(order));
        if (!own) return sh_error(SH_ENOMEM, "scale: out of memory (order %d)", order);
    }
    const size_t P = sh_scale_integrals_n(order), LN = sh_legendre_n(order - 1);
    double *I1 = work, *I2 = I1 + P, *Qa = I2 + P, *Qb = Qa + LN, *xg = Qb + LN, *wg = xg + SCALE_GL_NODES;
    st = sh__gauss_legendre(SCALE_GL_NODES, xg, wg);
    if (!st) st = composite(order, tau, ctx, energy, edges, ne, 1, xg, wg, Qa, Qb, I1);
    long panels = 1;
    double diff = INFINITY;
    while (!st) {
        panels *= 2;
        st = composite(order, tau, ctx, energy, edges, ne, panels, xg, wg, Qa, Qb, I2);
        if (st) break;
        double dmax = 0.0, vmax = 1.0;
        for (size_t q = 0; q < P; q++) {
            dmax = fmax(dmax, fabs(I2[q] - I1[q]));
            vmax = fmax(vmax, fabs(I2[q]));
        }
        const double prev = diff;
        diff = dmax / vmax;
        double *t = I1; I1 = I2; I2 = t; /* I1 = latest */
        if (diff <= SCALE_TOL) break;
        /* The sums' own rounding: at order 64 two estimates stop agreeing
         * better than ~1e-13 (the change no longer halves when the panels
         * double) before SCALE_TOL is met; that floor, below SCALE_FLOOR, is
         * accepted (tests/core/test_ranges.c, scale_top: 9 of the 12 cases at the
         * ends of k were refused after 8192 panels and 35-86 s). */
        if (diff <= SCALE_FLOOR && diff > 0.5 * prev) break;
        if (panels >= SCALE_MAX_PANELS) {
            st = sh_error(SH_ENUM, "scale: theta quadrature did not converge (%ld panels, change %.2e)",
                          panels, diff);
        }
    }
    if (!st) memcpy(I, I1, sizeof(double) * P);
    free(own);
    return st;
}

int sh_scale_matrix_tau(int order, sh_scale_tau_fn tau, void *ctx, int energy, const double *breaks,
                        int nbreaks, double *M, double *work)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (order > SH_SCALE_MAX_ORDER)
        return sh_error(SH_EINVAL, "scale: order %d is above %d", order, SH_SCALE_MAX_ORDER);
    if (!M) return sh_error(SH_EINVAL, "scale: no output matrix");
    double *own = NULL;
    if (!work) {
        own = work = malloc(sizeof(double) * (sh_scale_work_n(order) + sh_scale_integrals_n(order)));
        if (!own) return sh_error(SH_ENOMEM, "scale: out of memory (order %d)", order);
    }
    double *I = work + sh_scale_work_n(order);
    st = sh_scale_integrals_tau(order, tau, ctx, energy, breaks, nbreaks, I, work);
    if (!st) {
        const int N = order, n = sh_ncoeff(order);
        memset(M, 0, sizeof(double) * (size_t)n * n);
        /* (A): M_ij = 2π I_|m|(l_i, l_j) when m_i = m_j, else 0 */
        for (int m = -(N - 1); m < N; m++) {
            const int am = abs(m), nb = N - am;
            const double *Im = I + block_off(N, am);
            for (int li = am; li < N; li++)
                for (int lj = am; lj < N; lj++)
                    M[(size_t)sh_index(li, m) * n + sh_index(lj, m)] =
                        2.0 * M_PI * Im[(size_t)(li - am) * nb + (lj - am)];
        }
    }
    free(own);
    return st;
}

size_t sh_scale_matrix_work_n(int order) { return sh_scale_work_n(order) + sh_scale_integrals_n(order); }

int sh_scale_matrix(int order, const sh_scaling *s, double *M, double *work)
{
    int st = sh_scaling_check(s);
    if (st) return st;
    double br[SH_SCALE_MAX_BREAKS];
    const int nb = sh_scale_breaks(s, br);
    sh_scaling copy = *s;
    return sh_scale_matrix_tau(order, sh_scale_family_tau, &copy, s->energy, br, nb, M, work);
}

/* ---- second, independent computation ---------------------------------
 * M_ij by the 2-D product rule, without the analytic φ reduction and
 * without the Legendre arrays: every basis function comes from sh_eval (in
 * the given convention) at (θ, φ_q) and (τ(θ), φ_q); φ_q = 2πq/(2N+2) is
 * exact for the trigonometric polynomials of degree <= 2N−2 in φ; θ is
 * integrated by GSL's own fixed Gauss-Legendre table (gsl_integration_glfixed,
 * `nodes` points per panel) on `panels` equal panels per piece. */
int sh_scale_matrix_quad(int order, sh_convention conv, const sh_scaling *s, int nodes, int panels, double *M)
{
    int st = sh_scaling_check(s);
    if (st) return st;
    if ((st = sh_check_order(order))) return st;
    if (order > SH_SCALE_MAX_ORDER)
        return sh_error(SH_EINVAL, "scale: order %d is above %d", order, SH_SCALE_MAX_ORDER);
    if (nodes < 2 || nodes > 1000 || panels < 1 || panels > 100000)
        return sh_error(SH_EINVAL, "scale quad: %d nodes x %d panels out of range", nodes, panels);
    const int n = sh_ncoeff(order), nphi = 2 * order + 2;
    double br[SH_SCALE_MAX_BREAKS + 2];
    int ne = 0;
    br[ne++] = 0.0;
    ne += sh_scale_breaks(s, br + 1);
    br[ne++] = M_PI;
    qsort(br, (size_t)ne, sizeof(double), cmp_double);
    double *ya = malloc(sizeof(double) * (size_t)n * nphi), *yb = malloc(sizeof(double) * (size_t)n * nphi);
    gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)nodes);
    if (!ya || !yb || !tab) {
        free(ya), free(yb);
        if (tab) gsl_integration_glfixed_table_free(tab);
        return sh_error(SH_ENOMEM, "scale quad: out of memory");
    }
    memset(M, 0, sizeof(double) * (size_t)n * n);
    const double dphi = 2.0 * M_PI / nphi;
    for (int p = 0; p + 1 < ne && !st; p++) {
        const double h = (br[p + 1] - br[p]) / panels;
        for (int q = 0; q < panels && !st; q++) {
            const double a = br[p] + h * q;
            for (int g = 0; g < nodes; g++) {
                double th, w, t, dt;
                gsl_integration_glfixed_point(a, a + h, (size_t)g, &th, &w, tab);
                tau_eval(s, th, &t, &dt);
                const double psi = s->energy ? sin(t) * dt : sin(th);
                for (int k = 0; k < nphi; k++) {
                    const double ph = dphi * k;
                    st = sh_eval(order, conv, th, ph, ya + (size_t)k * n);
                    if (!st) st = sh_eval(order, conv, t, ph, yb + (size_t)k * n);
                    if (st) break;
                }
                if (st) break;
                const double ww = w * psi * dphi;
                for (int k = 0; k < nphi; k++) {
                    const double *A = ya + (size_t)k * n, *B = yb + (size_t)k * n;
                    for (int i = 0; i < n; i++) {
                        const double ai = ww * A[i];
                        double *row = M + (size_t)i * n;
                        for (int j = 0; j < n; j++) row[j] += ai * B[j];
                    }
                }
            }
        }
    }
    free(ya), free(yb);
    gsl_integration_glfixed_table_free(tab);
    return st;
}

/* ---- counting ---------------------------------------------------------- */
long sh_scale_pattern_bound(int order) { return (long)order * (2L * order * order + 1) / 3; }

long sh_scale_nonzeros(int order, const double *M, double rel)
{
    const size_t nn = (size_t)sh_ncoeff(order) * sh_ncoeff(order);
    double mx = 0.0;
    for (size_t q = 0; q < nn; q++) mx = fmax(mx, fabs(M[q]));
    long c = 0;
    for (size_t q = 0; q < nn; q++)
        if (fabs(M[q]) > rel * mx) c++;
    return c;
}
