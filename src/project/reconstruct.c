/* reconstruct.c — windowed SH reconstruction on a lat-long grid, and the
 * ringing (negative lobes) of a truncated expansion.
 *
 * Windows (the coefficient of band l is multiplied by a factor σ_l):
 *   none         σ_l = 1
 *   gauss:S      σ_l = exp(−S·l(l+1)), S ≥ 0.  This is the heat kernel on the
 *                sphere (y_l^m are eigenfunctions of the Laplacian with
 *                eigenvalue −l(l+1)), i.e. Gaussian pre-filtering of the
 *                data as Green recommends against ringing [1]; S = t is the
 *                diffusion time, angular width ≈ √(2S) rad.
 *   hann:W       σ_l = ½(1 + cos(πl/W)) for l < W, else 0
 *   lanczos:W    σ_l = sinc(l/W) = sin(πl/W)/(πl/W) for l < W, else 0
 * "hann" and "lanczos" without W use W = order (stored as param = 0).
 *
 * Reconstruction f(θ_j, φ_i) = Σ_l σ_l Σ_m c_l^m y_l^m at the lat-long pixel
 * centres (CONVENTIONS.md) is separable: per row one Legendre evaluation and
 *   a_m = Σ_l σ_l c_l^m Q_l^m,  b_m = Σ_l σ_l c_l^{−m} Q_l^m,
 *   f = a_0 + √2 Σ_{m>0} (a_m cos mφ + b_m sin mφ),
 * O(H·n² + H·W·n) per channel.
 *
 * [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *     section on ringing ("window your input data by pre-filtering it").
 */
#include "core/shlab_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sh_window_parse(const char *s, sh_window *out)
{
    if (!s || !out) return sh_error(SH_EINVAL, "window spec is NULL");
    const char *colon = strchr(s, ':');
    const size_t klen = colon ? (size_t)(colon - s) : strlen(s);
    sh_window w = {SH_WINDOW_NONE, 0.0};
    if (klen == 4 && !strncmp(s, "none", 4)) w.kind = SH_WINDOW_NONE;
    else if (klen == 5 && !strncmp(s, "gauss", 5)) w.kind = SH_WINDOW_GAUSS;
    else if (klen == 4 && !strncmp(s, "hann", 4)) w.kind = SH_WINDOW_HANN;
    else if (klen == 7 && !strncmp(s, "lanczos", 7)) w.kind = SH_WINDOW_LANCZOS;
    else
        return sh_error(SH_EINVAL, "unknown window '%s' (expected none, gauss:S, hann[:W] or "
                                   "lanczos[:W])", s);
    if (w.kind == SH_WINDOW_NONE) {
        if (colon) return sh_error(SH_EINVAL, "window 'none' takes no parameter");
    } else if (!colon) {
        if (w.kind == SH_WINDOW_GAUSS)
            return sh_error(SH_EINVAL, "window gauss needs its width: gauss:S with S >= 0");
        w.param = 0.0; /* W = order */
    } else {
        char *end;
        double p = 0;
        if (sh__parse_double(colon + 1, &end, &p) != SH__NUM_OK || *end != '\0')
            return sh_error(SH_EINVAL, "window '%s': parameter is not a finite number within "
                            "double's range", s);
        if (w.kind == SH_WINDOW_GAUSS && !(p >= 0.0))
            return sh_error(SH_EINVAL, "window '%s': S must be >= 0", s);
        if (w.kind != SH_WINDOW_GAUSS && !(p > 0.0))
            return sh_error(SH_EINVAL, "window '%s': W must be > 0", s);
        w.param = p;
    }
    *out = w;
    return SH_OK;
}

double sh_window_factor(const sh_window *w, int l, int order)
{
    if (!w || l < 0) return 1.0;
    const double W = w->param > 0.0 ? w->param : (double)order;
    switch (w->kind) {
    case SH_WINDOW_GAUSS: return exp(-w->param * l * (l + 1.0));
    case SH_WINDOW_HANN: return l < W ? 0.5 * (1.0 + cos(M_PI * l / W)) : 0.0;
    case SH_WINDOW_LANCZOS:
        if (l == 0) return 1.0;
        return l < W ? sin(M_PI * l / W) / (M_PI * l / W) : 0.0;
    default: return 1.0;
    }
}

/* Scratch for row synthesis, allocated once per call. */
typedef struct {
    int n, W;
    double *cs;  /* cos, sin(mφ_i) interleaved: [(i*n + m)*2 + {0,1}] */
    double *Q;   /* Q_l^m at sh_legendre_idx */
    double *ab;  /* a_m, b_m */
    double *sig; /* window factors per band */
} synth_t;

static void synth_free(synth_t *s)
{
    free(s->cs); free(s->Q); free(s->ab); free(s->sig);
}

static int synth_alloc(synth_t *s, int order, const sh_window *win, int W)
{
    memset(s, 0, sizeof *s);
    s->n = order;
    s->W = W;
    s->cs = malloc((size_t)W * order * 2 * sizeof *s->cs);
    s->Q = malloc(sh_legendre_n(order - 1) * sizeof *s->Q);
    s->ab = malloc((size_t)2 * order * sizeof *s->ab);
    s->sig = malloc((size_t)order * sizeof *s->sig);
    if (!s->cs || !s->Q || !s->ab || !s->sig) {
        synth_free(s);
        return sh_error(SH_ENOMEM, "reconstruction: out of memory");
    }
    sh__trig_table(order, W, 0.5, s->cs); /* pixel centres φ_i = 2π(i+½)/W */
    for (int l = 0; l < order; l++) s->sig[l] = sh_window_factor(win, l, order);
    return SH_OK;
}

/* Q for the row at polar angle theta (call once per row). */
static void synth_row_setup(synth_t *s, double theta) { sh__legendre_core(s->n - 1, cos(theta), s->Q, 0); }

/* One row of one channel into out[0..W-1]. */
static void synth_row(synth_t *s, sh_convention conv, const double *c, double *out)
{
    const int n = s->n;
    double *a = s->ab, *b = s->ab + n;
    for (int m = 0; m < n; m++) {
        double sa = 0.0, sb = 0.0;
        for (int l = m; l < n; l++) {
            const double q = s->sig[l] * s->Q[sh_legendre_idx(l, m)];
            sa += q * c[sh_index(l, m)];
            if (m) sb += q * c[sh_index(l, -m)];
        }
        double f = m ? M_SQRT2 : 1.0;
        if (conv == SH_NOCS && (m & 1)) f = -f;
        a[m] = f * sa;
        b[m] = f * sb;
    }
    for (int i = 0; i < s->W; i++) {
        const double *t = s->cs + (size_t)i * n * 2;
        double v = 0.0;
        for (int m = 0; m < n; m++) v += a[m] * t[2 * m] + b[m] * t[2 * m + 1];
        out[i] = v;
    }
}

static int check_args(int order, sh_convention conv, const double *coeffs, int width)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "unknown convention");
    if (!coeffs) return sh_error(SH_EINVAL, "coefficient array is NULL");
    if (width < 2 || width > (1 << 16))
        return sh_error(SH_EINVAL, "width %d out of range (2..65536)", width);
    for (int i = 0; i < order * order; i++)
        if (!isfinite(coeffs[i])) return sh_error(SH_EINVAL, "coefficient %d is not finite", i);
    return SH_OK;
}

int sh_reconstruct_latlong(int order, sh_convention conv, const double *coeffs, int nchan,
                           const sh_window *win, int width, sh_image *out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_reconstruct_latlong: output is NULL");
    memset(out, 0, sizeof *out);
    if (nchan < 1 || nchan > SH_IMAGE_MAX_CHANNELS || nchan == 2)
        return sh_error(SH_EINVAL, "sh_reconstruct_latlong: %d channels (1, 3 or 4)", nchan);
    int st = check_args(order, conv, coeffs, width);
    if (st) return st;
    for (int c = 1; c < nchan; c++)
        if ((st = check_args(order, conv, coeffs + (size_t)c * order * order, width))) return st;
    const int W = width, H = width / 2, nn = order * order;
    synth_t s;
    if ((st = synth_alloc(&s, order, win, W))) return st;
    double *row = malloc((size_t)W * sizeof *row);
    out->data = malloc((size_t)W * H * nchan * sizeof(float));
    if (!row || !out->data) {
        free(row);
        synth_free(&s);
        sh_image_free(out);
        return sh_error(SH_ENOMEM, "sh_reconstruct_latlong: out of memory");
    }
    out->width = W;
    out->height = H;
    out->nchan = nchan;
    static const char *const names[4] = {"R", "G", "B", "A"};
    if (nchan == 1) strcpy(out->names[0], "Y");
    else
        for (int c = 0; c < nchan; c++) strcpy(out->names[c], names[c]);
    const size_t plane = (size_t)W * H;
    for (int j = 0; j < H; j++) {
        synth_row_setup(&s, M_PI * (j + 0.5) / H);
        for (int c = 0; c < nchan; c++) {
            synth_row(&s, conv, coeffs + (size_t)c * nn, row);
            float *dst = out->data + c * plane + (size_t)j * W;
            for (int i = 0; i < W; i++) dst[i] = (float)row[i];
        }
    }
    free(row);
    synth_free(&s);
    return SH_OK;
}

int sh_ringing(int order, sh_convention conv, const double *coeffs, const sh_window *win,
               int width, double *most_negative, double *negative_energy_fraction)
{
    int st = check_args(order, conv, coeffs, width);
    if (st) return st;
    const int W = width, H = width / 2;
    synth_t s;
    if ((st = synth_alloc(&s, order, win, W))) return st;
    double *row = malloc((size_t)W * sizeof *row);
    if (!row) {
        synth_free(&s);
        return sh_error(SH_ENOMEM, "sh_ringing: out of memory");
    }
    double mn = 0.0, eneg = 0.0, etot = 0.0;
    const double half = 0.5 * M_PI / H;
    for (int j = 0; j < H; j++) {
        const double th = M_PI * (j + 0.5) / H;
        /* exact pixel solid angle (2π/W)(cos θ_top − cos θ_bottom) */
        const double om = (2.0 * M_PI / W) * 2.0 * sin(th) * sin(half);
        synth_row_setup(&s, th);
        synth_row(&s, conv, coeffs, row);
        for (int i = 0; i < W; i++) {
            const double f = row[i], e = f * f * om;
            etot += e;
            if (f < 0.0) {
                eneg += e;
                if (f < mn) mn = f;
            }
        }
    }
    free(row);
    synth_free(&s);
    if (!isfinite(mn) || !isfinite(etot)) return sh_error(SH_ENUM, "sh_ringing: overflow");
    if (most_negative) *most_negative = mn;
    if (negative_energy_fraction) *negative_energy_fraction = etot > 0.0 ? eneg / etot : 0.0;
    return SH_OK;
}
