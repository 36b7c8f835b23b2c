/* envmap.c — environment-map layouts, exact pixel solid angles, and the
 * projection of an environment image onto real SH.
 *
 * Layouts (docs/CONVENTIONS.md "Environment maps"):
 *  - lat-long W×H: pixel (i,j) centre u=(i+½)/W, v=(j+½)/H, θ=πv, φ=2πu;
 *    row j spans θ ∈ [πj/H, π(j+1)/H], so its pixels have the exact solid
 *    angle Ω_j = (2π/W)(cos θ_top − cos θ_bottom).
 *  - angle map ("probe", Green's hdr_lightsource [1]) size×size: pixel
 *    (x,y) centre u = 2(x+½)/size−1, v = 2(y+½)/size−1, ρ = √(u²+v²) ≤ 1,
 *    θ = πρ, direction (u/ρ·sinθ, v/ρ·sinθ, cosθ).  This inverts the
 *    forward map r = acos(dz)/(π√(dx²+dy²)), u = dx·r, v = dy·r: with
 *    √(dx²+dy²) = sinθ, r = ρ/sinθ and dx·r = u.
 *
 * Probe solid angles.  dΩ = sinθ dθ dψ with θ = πρ and du dv = ρ dρ dψ give
 *    dΩ = π sin(πρ)/ρ du dv   (ρ ≤ 1; 0 outside the disc).
 * Rather than a per-pixel cubature with clipping, the integral over a pixel
 * is written by inclusion-exclusion from the signed "quadrant" function
 *    G(a,b) = ∫∫_{0≤u≤a, 0≤v≤b, ρ≤1} dΩ,  Ω(pixel) = G(u1,v1)−G(u0,v1)−G(u1,v0)+G(u0,v0),
 * (G odd in a and in b), and G is integrated in polar form: the ray at
 * angle ψ leaves the region at ρ_max(ψ) = min(1, a/cosψ, b/sinψ), and
 * ∫₀^ρmax π sin(πρ) dρ = 1 − cos(πρ_max).  On the arc (ρ_max = 1) this is
 * 2 per radian; on the edge u = a, with v = a tanψ, dψ = a dv/(a²+v²):
 *    ∫ (1−cos(π√(a²+v²))) a/(a²+v²) dv = a ∫ h(a²+v²) dv,  h(s) = (1−cos π√s)/s,
 * and h is entire in s, so an n-point Gauss-Legendre rule (GSL glfixed)
 * converges geometrically.  For 0 < a,b ≤ 1:
 *    G(a,b) = a·I(a, min(b, √(1−a²))) + b·I(b, min(a, √(1−b²)))
 *             + 2·max(0, asin b − acos a),       I(c,L) = ∫₀^L h(c²+t²) dt.
 * The weights then sum to 4·G(1,1) = 4π by construction; the tests check
 * them pixel by pixel against a brute-force clipped tensor Gauss rule and
 * check ∫ y_i y_j ≈ δ_ij.
 *
 * Projection: c_i = Σ_pixels L · y_i(centre) · Ω_pixel.  For lat-long it is
 * separable: the rows are rings of latitude with the exact row solid angle
 * as weight, so the fast transform (sht.c) does it, O(H·W·log W + H·n²) for
 * all channels at once; the direct form it replaced (per row one Legendre
 * evaluation and the azimuthal sums A_m = Σ_i L cos(mφ_i), B_m = Σ_i L
 * sin(mφ_i) from a cos/sin table, O(H·W·n + H·n²) per channel) is kept as
 * sh__project_latlong_direct for the tests.  The angle map
 * is not separable, but its 8-fold grid symmetry lets one Legendre
 * evaluation serve up to 8 pixels (see project_probe).
 *
 * [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003.
 */
#include "project/sht_internal.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sh_layout_parse(const char *s, sh_layout *out)
{
    if (!s) return sh_error(SH_EINVAL, "layout is NULL");
    if (!strcmp(s, "latlong") || !strcmp(s, "equirect") || !strcmp(s, "latlon"))
        *out = SH_LAYOUT_LATLONG;
    else if (!strcmp(s, "probe") || !strcmp(s, "angular") || !strcmp(s, "anglemap"))
        *out = SH_LAYOUT_PROBE;
    else
        return sh_error(SH_EINVAL, "unknown layout '%s' (expected latlong or probe)", s);
    return SH_OK;
}

static int check_size(sh_layout layout, int width, int height)
{
    if (layout != SH_LAYOUT_LATLONG && layout != SH_LAYOUT_PROBE)
        return sh_error(SH_EINVAL, "unknown layout %d", (int)layout);
    if (width < 1 || height < 1 || (long long)width * height > SH_IMAGE_MAX_PIXELS)
        return sh_error(SH_EINVAL, "image size %d×%d is not usable", width, height);
    if (layout == SH_LAYOUT_PROBE && width != height)
        return sh_error(SH_EINVAL, "a probe (angle map) must be square, got %d×%d", width,
                        height);
    return SH_OK;
}

/* ------------------------------------------------------ pixel directions */

int sh_pixel_dir(sh_layout layout, int width, int height, double x, double y, double dir[3])
{
    int st = check_size(layout, width, height);
    if (st) return st;
    if (!isfinite(x) || !isfinite(y)) return sh_error(SH_EINVAL, "pixel position not finite");
    if (layout == SH_LAYOUT_LATLONG) {
        sh_dir_from_angles(M_PI * y / height, 2.0 * M_PI * x / width, dir);
        return SH_OK;
    }
    const double u = 2.0 * x / width - 1.0, v = 2.0 * y / height - 1.0;
    const double rho = hypot(u, v);
    if (rho > 1.0) return sh_error(SH_EINVAL, "pixel (%g,%g) lies outside the probe disc", x, y);
    if (rho == 0.0) {
        dir[0] = dir[1] = 0.0;
        dir[2] = 1.0;
        return SH_OK;
    }
    const double st_ = sin(M_PI * rho);
    dir[0] = u / rho * st_;
    dir[1] = v / rho * st_;
    dir[2] = cos(M_PI * rho);
    return SH_OK;
}

/* ------------------------------------------------- probe solid angles */

/* h(s) = (1 − cos π√s)/s = 2 sin²(π√s/2)/s, without cancellation. */
static inline double h_fn(double s)
{
    if (s <= 0.0) return 0.5 * M_PI * M_PI;
    const double q = sin(0.5 * M_PI * sqrt(s));
    return 2.0 * q * q / s;
}

/* I(c, L) = ∫₀^L h(c² + t²) dt by Gauss-Legendre. */
static double edge_integral(const gsl_integration_glfixed_table *gl, double c, double L)
{
    if (L <= 0.0) return 0.0;
    double sum = 0.0, xi, wi;
    for (size_t k = 0; k < gl->n; k++) {
        gsl_integration_glfixed_point(0.0, L, k, &xi, &wi, gl);
        sum += wi * h_fn(c * c + xi * xi);
    }
    return sum;
}

/* G(a,b) for a, b >= 0 (see the file comment). */
static double quadrant_omega(const gsl_integration_glfixed_table *gl, double a, double b)
{
    if (a > 1.0) a = 1.0;
    if (b > 1.0) b = 1.0;
    if (a <= 0.0 || b <= 0.0) return 0.0;
    const double ca = sqrt((1.0 - a) * (1.0 + a)), cb = sqrt((1.0 - b) * (1.0 + b));
    double g = a * edge_integral(gl, a, fmin(b, ca)) + b * edge_integral(gl, b, fmin(a, cb));
    const double arc = asin(b) - acos(a);
    if (arc > 0.0) g += 2.0 * arc;
    return g;
}

static int probe_solid_angles(int size, double *w)
{
    /* Grid lines u_k = 2k/size − 1 = (2k − size)/size, k = 0..size; |u_k|
     * takes the values i/size for i = |2k − size|, all of the parity of size. */
    const size_t n1 = (size_t)size + 1;
    double *G = malloc(n1 * n1 * sizeof *G);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(24);
    if (!G || !gl) {
        free(G);
        if (gl) gsl_integration_glfixed_table_free(gl);
        return sh_error(SH_ENOMEM, "probe solid angles: out of memory (size %d)", size);
    }
    for (int i = size % 2; i <= size; i += 2)
        for (int j = size % 2; j <= i; j += 2) {
            const double g = quadrant_omega(gl, (double)i / size, (double)j / size);
            G[(size_t)i * n1 + j] = g; /* G(a,b) = G(b,a): the region is symmetric */
            G[(size_t)j * n1 + i] = g;
        }
    gsl_integration_glfixed_table_free(gl);
#define GS(k, l) ((double)((2 * (k) > size) - (2 * (k) < size)) *                 \
                  (double)((2 * (l) > size) - (2 * (l) < size)) *                 \
                  G[(size_t)abs(2 * (k) - size) * n1 + (size_t)abs(2 * (l) - size)])
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            /* nearest point of the pixel to the centre: pixels wholly outside get 0 */
            const double u0 = (2.0 * x - size) / size, u1 = (2.0 * x + 2 - size) / size;
            const double v0 = (2.0 * y - size) / size, v1 = (2.0 * y + 2 - size) / size;
            const double nu = (u0 > 0) ? u0 : (u1 < 0 ? u1 : 0.0);
            const double nv = (v0 > 0) ? v0 : (v1 < 0 ? v1 : 0.0);
            double om = 0.0;
            if (nu * nu + nv * nv < 1.0) {
                om = GS(x + 1, y + 1) - GS(x, y + 1) - GS(x + 1, y) + GS(x, y);
                if (om < 0.0) om = 0.0; /* rounding in a sliver at the rim */
            }
            w[(size_t)y * size + x] = om;
        }
#undef GS
    free(G);
    return SH_OK;
}

int sh_pixel_solid_angles(sh_layout layout, int width, int height, double *w)
{
    int st = check_size(layout, width, height);
    if (st) return st;
    if (!w) return sh_error(SH_EINVAL, "sh_pixel_solid_angles: weights array is NULL");
    if (layout == SH_LAYOUT_PROBE) return probe_solid_angles(width, w);
    /* cos a − cos b = 2 sin((a+b)/2) sin((b−a)/2): no cancellation near the poles */
    const double half = 0.5 * M_PI / height;
    for (int j = 0; j < height; j++) {
        const double om = (2.0 * M_PI / width) * 2.0 * sin(M_PI * (j + 0.5) / height) * sin(half);
        for (int i = 0; i < width; i++) w[(size_t)j * width + i] = om;
    }
    return SH_OK;
}

/* Angles of the centre of probe pixel (x,y).  A pixel whose centre lies
 * outside the disc but which still overlaps it (a sliver at the rim, with
 * non-zero solid angle) is represented by the rim point ρ = 1 (θ = π) in the
 * centre's azimuth.  Returns 0 for pixels wholly outside the disc. */
static int probe_centre(int size, int x, int y, double *theta, double *phi)
{
    const double u0 = (2.0 * x - size) / size, u1 = (2.0 * x + 2 - size) / size;
    const double v0 = (2.0 * y - size) / size, v1 = (2.0 * y + 2 - size) / size;
    const double nu = (u0 > 0) ? u0 : (u1 < 0 ? u1 : 0.0);
    const double nv = (v0 > 0) ? v0 : (v1 < 0 ? v1 : 0.0);
    if (nu * nu + nv * nv >= 1.0) return 0;
    const double u = 0.5 * (u0 + u1), v = 0.5 * (v0 + v1);
    const double rho = fmin(hypot(u, v), 1.0);
    double p = atan2(v, u); /* azimuth of (u/ρ sinθ, v/ρ sinθ) */
    if (p < 0.0) p += 2.0 * M_PI;
    *theta = M_PI * rho;
    *phi = p;
    return 1;
}

/* ------------------------------------------------------- sampling a fn */

int sh_image_from_fn(sh_layout layout, int width, int height, sh_sphere_fn f, void *ctx,
                     sh_image *out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_image_from_fn: output is NULL");
    memset(out, 0, sizeof *out);
    int st = check_size(layout, width, height);
    if (st) return st;
    if (!f) return sh_error(SH_EINVAL, "sh_image_from_fn: function is NULL");
    out->data = malloc((size_t)width * height * sizeof(float));
    if (!out->data) return sh_error(SH_ENOMEM, "sh_image_from_fn: out of memory");
    out->width = width;
    out->height = height;
    out->nchan = 1;
    strcpy(out->names[0], "Y");
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            double d[3], th, ph, val = 0.0;
            int in = 1;
            if (layout == SH_LAYOUT_LATLONG) {
                th = M_PI * (y + 0.5) / height;
                ph = 2.0 * M_PI * (x + 0.5) / width;
            } else {
                in = probe_centre(width, x, y, &th, &ph);
            }
            if (in) {
                sh_dir_from_angles(th, ph, d);
                val = f(d, th, ph, ctx);
            }
            out->data[(size_t)y * width + x] = (float)val;
        }
    return SH_OK;
}

/* ---------------------------------------------------------- projection */

int sh__project_latlong_direct(const sh_image *img, int order, sh_convention conv, double *coeffs)
{
    const int W = img->width, H = img->height, n = order, nn = n * n;
    const size_t plane = (size_t)W * H;
    double *cs = malloc((size_t)W * n * 2 * sizeof *cs);    /* cos, sin(mφ_i) */
    double *Q = malloc(sh_legendre_n(n - 1) * sizeof *Q);
    double *AB = malloc((size_t)2 * n * sizeof *AB);
    if (!cs || !Q || !AB) {
        free(cs); free(Q); free(AB);
        return sh_error(SH_ENOMEM, "sh_project_image: out of memory");
    }
    sh__trig_table(n, W, 0.5, cs); /* pixel centres φ_i = 2π(i+½)/W */
    memset(coeffs, 0, (size_t)img->nchan * nn * sizeof *coeffs);
    const double half = 0.5 * M_PI / H;
    for (int j = 0; j < H; j++) {
        const double th = M_PI * (j + 0.5) / H;
        /* exact row solid angle per pixel: (2π/W)(cos θ_top − cos θ_bottom) */
        const double om = (2.0 * M_PI / W) * 2.0 * sin(th) * sin(half);
        sh__legendre_core(n - 1, cos(th), Q, 0);
        for (int c = 0; c < img->nchan; c++) {
            const float *row = img->data + c * plane + (size_t)j * W;
            double *A = AB, *B = AB + n;
            memset(AB, 0, (size_t)2 * n * sizeof *AB);
            for (int i = 0; i < W; i++) {
                const double L = row[i];
                const double *t = cs + (size_t)i * n * 2;
                for (int m = 0; m < n; m++) {
                    A[m] += L * t[2 * m];
                    B[m] += L * t[2 * m + 1];
                }
            }
            /* c_l^0 += Ω Q_l^0 A_0;  c_l^{±m} += Ω √2 Q_l^m {A_m, B_m} (Green eq. 6) */
            sh__ring_accumulate(n, conv, Q, om, A, B, coeffs + (size_t)c * nn);
        }
    }
    free(cs); free(Q); free(AB);
    return SH_OK;
}

/* Angle-map projection.  The pixel grid is symmetric under the 8 maps
 * (du,dv) → (±du,±dv), (±dv,±du) of centre offsets, which keep ρ (so θ,
 * Q_l^m and, by construction, the weight) and change only φ.  Pixels are
 * therefore processed by orbit: azimuthal sums A_m = Σ L Ω cos mφ,
 * B_m = Σ L Ω sin mφ over the orbit (Chebyshev recurrence in m), then one
 * Legendre evaluation per orbit, as in the lat-long case:
 * O(size²·n + size²·n²/8). */
static int project_probe(const sh_image *img, int order, sh_convention conv, double *coeffs)
{
    const int s = img->width, n = order, nn = n * n, nc = img->nchan;
    const size_t plane = (size_t)s * s;
    double *w = malloc(plane * sizeof *w);
    double *Q = malloc(sh_legendre_n(n - 1) * sizeof *Q);
    double *AB = malloc((size_t)2 * n * nc * sizeof *AB);
    if (!w || !Q || !AB) {
        free(w); free(Q); free(AB);
        return sh_error(SH_ENOMEM, "sh_project_image: out of memory");
    }
    int st = probe_solid_angles(s, w);
    if (st) { free(w); free(Q); free(AB); return st; }
    memset(coeffs, 0, (size_t)nc * nn * sizeof *coeffs);
    /* centre offsets d = 2x + 1 − s, in units of 1/s */
    for (int a = (s + 1) % 2; a < s; a += 2)
        for (int b = (s + 1) % 2; b <= a; b += 2) {
            const int x0 = (a + s - 1) / 2, y0 = (b + s - 1) / 2;
            double th, ph;
            if (!probe_centre(s, x0, y0, &th, &ph)) continue;
            /* the orbit of (a, b), without repeats */
            int orb[8][2], no = 0;
            const int cand[8][2] = {{a, b}, {-a, b}, {a, -b}, {-a, -b},
                                    {b, a}, {-b, a}, {b, -a}, {-b, -a}};
            for (int k = 0; k < 8; k++) {
                int dup = 0;
                for (int q = 0; q < no; q++)
                    if (orb[q][0] == cand[k][0] && orb[q][1] == cand[k][1]) dup = 1;
                if (!dup) { orb[no][0] = cand[k][0]; orb[no][1] = cand[k][1]; no++; }
            }
            memset(AB, 0, (size_t)2 * n * nc * sizeof *AB);
            for (int q = 0; q < no; q++) {
                const int px = (orb[q][0] + s - 1) / 2, py = (orb[q][1] + s - 1) / 2;
                const size_t pix = (size_t)py * s + px;
                const double om = w[pix];
                if (om == 0.0) continue;
                double phi = atan2((double)orb[q][1], (double)orb[q][0]);
                if (phi < 0.0) phi += 2.0 * M_PI;
                const double c1 = cos(phi), s1 = sin(phi);
                for (int c = 0; c < nc; c++) {
                    const double L = img->data[c * plane + pix] * om;
                    double *A = AB + (size_t)c * 2 * n, *B = A + n;
                    /* cos, sin((m+1)φ) = rotation of (cos mφ, sin mφ) by φ */
                    double cm = 1.0, sm = 0.0;
                    for (int m = 0; m < n; m++) {
                        A[m] += L * cm;
                        B[m] += L * sm;
                        const double t = cm * c1 - sm * s1;
                        sm = sm * c1 + cm * s1;
                        cm = t;
                    }
                }
            }
            sh__legendre_core(n - 1, cos(th), Q, 0);
            for (int c = 0; c < nc; c++) {
                const double *A = AB + (size_t)c * 2 * n, *B = A + n;
                /* c_l^0 += Q_l^0 A_0;  c_l^{±m} += √2 Q_l^m {A_m, B_m} (Green eq. 6) */
                sh__ring_accumulate(n, conv, Q, 1.0, A, B, coeffs + (size_t)c * nn);
            }
        }
    free(w); free(Q); free(AB);
    return SH_OK;
}

/* Row r of every channel of a lat-long image, as doubles. */
static int latlong_row(void *ctx, int r, double *buf)
{
    const sh_image *img = ctx;
    const size_t W = (size_t)img->width, plane = W * img->height;
    for (int c = 0; c < img->nchan; c++) {
        const float *row = img->data + c * plane + (size_t)r * W;
        for (size_t i = 0; i < W; i++) buf[c * W + i] = row[i];
    }
    return SH_OK;
}

static int project_latlong(const sh_image *img, int order, sh_convention conv,
                           const sh_run_opts *opts, double *coeffs)
{
    double *x = malloc(sizeof(double) * (size_t)img->height * 2);
    if (!x) return sh_error(SH_ENOMEM, "sh_project_image: out of memory");
    sh_grid g;
    sh_sht *p = NULL;
    int st = sh_grid_latlong(img->width, img->height, x, x + img->height, &g);
    if (!st) st = sh_sht_create(order, &g, img->nchan, opts->nthreads, &p);
    if (!st) {
        sh_sht_set_progress(p, opts->progress, opts->progress_ctx);
        st = sh__sht_analysis_cb(p, conv, latlong_row, (void *)img, coeffs);
    }
    sh_sht_destroy(p);
    free(x);
    return st;
}

/* The sampling bound of a band limit n: 2n − 1 samples in φ and n in θ
 * (lat-long), 2n − 1 across the disc of an angle map.  Fewer cannot carry
 * the bands (a 1×1 image projected to order 2 gave a dipole 6× its constant
 * term); the projection of such an image is only the discrete sum. */
int sh_image_max_order(const sh_image *img, sh_layout layout)
{
    if (!img || img->width < 1 || img->height < 1) return 0;
    int n = (img->width + 1) / 2;
    if (layout == SH_LAYOUT_LATLONG && img->height < n) n = img->height;
    if (layout == SH_LAYOUT_PROBE && (img->height + 1) / 2 < n) n = (img->height + 1) / 2;
    return n > SHLAB_MAX_ORDER ? SHLAB_MAX_ORDER : n;
}

int sh_image_check_order(const sh_image *img, sh_layout layout, int order)
{
    const int mx = sh_image_max_order(img, layout);
    if (order <= mx) return SH_OK;
    return sh_error(SH_EINVAL, "a %d×%d image carries orders up to %d (2n − 1 pixels across, n down), not %d",
                    img ? img->width : 0, img ? img->height : 0, mx, order);
}

int sh_project_image(const sh_image *img, sh_layout layout, int order, sh_convention conv,
                     double *coeffs)
{
    const sh_run_opts opts = SH_RUN_OPTS_DEFAULT;
    return sh_project_image_ex(img, layout, order, conv, &opts, coeffs);
}

int sh_project_image_ex(const sh_image *img, sh_layout layout, int order, sh_convention conv,
                        const sh_run_opts *opts, double *coeffs)
{
    const sh_run_opts defaults = SH_RUN_OPTS_DEFAULT;
    if (!opts) opts = &defaults;
    int st = sh_check_order(order);
    if (st) return st;
    if (!img || !img->data || img->nchan < 1 || img->nchan > SH_IMAGE_MAX_CHANNELS)
        return sh_error(SH_EINVAL, "sh_project_image: empty image");
    if (!coeffs) return sh_error(SH_EINVAL, "sh_project_image: coefficient array is NULL");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "unknown convention");
    if ((st = check_size(layout, img->width, img->height))) return st;
    st = layout == SH_LAYOUT_LATLONG ? project_latlong(img, order, conv, opts, coeffs)
                                     : project_probe(img, order, conv, coeffs);
    if (st) return st;
    const size_t total = (size_t)img->nchan * order * order;
    for (size_t i = 0; i < total; i++)
        if (!isfinite(coeffs[i]))
            return sh_error(SH_ENUM, "sh_project_image: coefficient %zu is not finite "
                                     "(the image has non-finite or huge pixels)", i);
    return SH_OK;
}
