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
 * centres (docs/CONVENTIONS.md) is separable: per row one Legendre evaluation and
 *   a_m = Σ_l σ_l c_l^m Q_l^m,  b_m = Σ_l σ_l c_l^{−m} Q_l^m,
 *   f = a_0 + √2 Σ_{m>0} (a_m cos mφ + b_m sin mφ).
 * The rows are rings of latitude, so the fast synthesis of sht.c does it
 * (Legendre sums across row pairs, one inverse FFT per row), O(H·n² +
 * H·W·log W) for all channels at once; the direct form above, O(H·n² + H·W·n)
 * per channel, is kept as sh__reconstruct_latlong_direct for the tests.
 *
 * [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *     section on ringing ("window your input data by pre-filtering it").
 */
#include "project/sht_internal.h"

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
    if ((long long)width * (width / 2) > SH_IMAGE_MAX_PIXELS)
        return sh_error(SH_EINVAL, "a %d×%d image is larger than %lld pixels (the largest tested; docs/ranges.md)",
                        width, width / 2, (long long)SH_IMAGE_MAX_PIXELS);
    for (int i = 0; i < order * order; i++)
        if (!isfinite(coeffs[i])) return sh_error(SH_EINVAL, "coefficient %d is not finite", i);
    return SH_OK;
}

int sh__reconstruct_latlong_direct(int order, sh_convention conv, const double *coeffs,
                                   const sh_window *win, int width, double *out)
{
    int st = check_args(order, conv, coeffs, width);
    if (st) return st;
    const int W = width, H = width / 2;
    synth_t s;
    if ((st = synth_alloc(&s, order, win, W))) return st;
    for (int j = 0; j < H; j++) {
        synth_row_setup(&s, M_PI * (j + 0.5) / H);
        synth_row(&s, conv, coeffs, out + (size_t)j * W);
    }
    synth_free(&s);
    return SH_OK;
}

/* A plan for the lat-long grid of width W (height W/2) and the window
 * factors σ_l; the caller frees *x and destroys *p. */
static int latlong_plan(int order, const sh_window *win, int width, int nchan,
                        const sh_run_opts *opts, double **x, sh_sht **p)
{
    const int H = width / 2;
    *p = NULL;
    *x = malloc(sizeof(double) * ((size_t)H + order));
    if (!*x) return sh_error(SH_ENOMEM, "reconstruction: out of memory");
    double *sig = *x + H;
    for (int l = 0; l < order; l++) sig[l] = sh_window_factor(win, l, order);
    sh_grid g;
    int st = sh_grid_latlong(width, H, *x, NULL, &g);
    if (!st) st = sh_sht_create(order, &g, nchan, opts->nthreads, p);
    if (!st) sh_sht_set_progress(*p, opts->progress, opts->progress_ctx);
    return st;
}

typedef struct {
    sh_image *img;
} put_image_ctx;

static int put_image_row(void *ctx, int r, const double *buf)
{
    sh_image *img = ((put_image_ctx *)ctx)->img;
    const size_t W = (size_t)img->width, plane = W * img->height;
    for (int c = 0; c < img->nchan; c++) {
        float *dst = img->data + c * plane + (size_t)r * W;
        for (size_t i = 0; i < W; i++) dst[i] = (float)buf[c * W + i];
    }
    return SH_OK;
}

int sh_reconstruct_latlong(int order, sh_convention conv, const double *coeffs, int nchan,
                           const sh_window *win, int width, sh_image *out)
{
    const sh_run_opts opts = SH_RUN_OPTS_DEFAULT;
    return sh_reconstruct_latlong_ex(order, conv, coeffs, nchan, win, width, &opts, out);
}

int sh_reconstruct_latlong_ex(int order, sh_convention conv, const double *coeffs, int nchan,
                              const sh_window *win, int width, const sh_run_opts *opts,
                              sh_image *out)
{
    const sh_run_opts defaults = SH_RUN_OPTS_DEFAULT;
    if (!opts) opts = &defaults;
    if (!out) return sh_error(SH_EINVAL, "sh_reconstruct_latlong: output is NULL");
    memset(out, 0, sizeof *out);
    if (nchan < 1 || nchan > SH_IMAGE_MAX_CHANNELS || nchan == 2)
        return sh_error(SH_EINVAL, "sh_reconstruct_latlong: %d channels (1, 3 or 4)", nchan);
    int st = check_args(order, conv, coeffs, width);
    if (st) return st;
    for (int c = 1; c < nchan; c++)
        if ((st = check_args(order, conv, coeffs + (size_t)c * order * order, width))) return st;
    const int W = width, H = width / 2;
    out->data = malloc((size_t)W * H * nchan * sizeof(float));
    if (!out->data) return sh_error(SH_ENOMEM, "sh_reconstruct_latlong: out of memory");
    out->width = W;
    out->height = H;
    out->nchan = nchan;
    static const char *const names[4] = {"R", "G", "B", "A"};
    if (nchan == 1) strcpy(out->names[0], "Y");
    else
        for (int c = 0; c < nchan; c++) strcpy(out->names[c], names[c]);
    double *x;
    sh_sht *p;
    st = latlong_plan(order, win, W, nchan, opts, &x, &p);
    if (!st) {
        put_image_ctx pc = {out};
        st = sh__sht_synthesis_cb(p, conv, coeffs, x + H, put_image_row, &pc);
    }
    sh_sht_destroy(p);
    free(x);
    if (st) sh_image_free(out);
    return st;
}

/* Per-row pieces of the ringing measure, summed over the rows in order at
 * the end so that the result does not depend on the threads. */
typedef struct {
    double *mn, *eneg, *etot; /* [H] */
    int W, H;
} ring_ctx;

static int ringing_row(void *ctx, int r, const double *f)
{
    ring_ctx *q = ctx;
    /* exact pixel solid angle (2π/W)(cos θ_top − cos θ_bottom) */
    const double th = M_PI * (r + 0.5) / q->H;
    const double om = (2.0 * M_PI / q->W) * 2.0 * sin(th) * sin(0.5 * M_PI / q->H);
    double mn = 0.0, eneg = 0.0, etot = 0.0;
    for (int i = 0; i < q->W; i++) {
        const double e = f[i] * f[i] * om;
        etot += e;
        if (f[i] < 0.0) {
            eneg += e;
            if (f[i] < mn) mn = f[i];
        }
    }
    q->mn[r] = mn;
    q->eneg[r] = eneg;
    q->etot[r] = etot;
    return SH_OK;
}

int sh_ringing(int order, sh_convention conv, const double *coeffs, const sh_window *win,
               int width, double *most_negative, double *negative_energy_fraction)
{
    const sh_run_opts opts = SH_RUN_OPTS_DEFAULT;
    return sh_ringing_ex(order, conv, coeffs, win, width, &opts, most_negative,
                         negative_energy_fraction);
}

int sh_ringing_ex(int order, sh_convention conv, const double *coeffs, const sh_window *win,
                  int width, const sh_run_opts *opts, double *most_negative,
                  double *negative_energy_fraction)
{
    const sh_run_opts defaults = SH_RUN_OPTS_DEFAULT;
    if (!opts) opts = &defaults;
    int st = check_args(order, conv, coeffs, width);
    if (st) return st;
    const int W = width, H = width / 2;
    double *rows = malloc(sizeof(double) * 3 * (size_t)H);
    if (!rows) return sh_error(SH_ENOMEM, "sh_ringing: out of memory");
    double *x;
    sh_sht *p;
    st = latlong_plan(order, win, W, 1, opts, &x, &p);
    if (!st) {
        ring_ctx q = {rows, rows + H, rows + 2 * H, W, H};
        st = sh__sht_synthesis_cb(p, conv, coeffs, x + H, ringing_row, &q);
    }
    sh_sht_destroy(p);
    free(x);
    double mn = 0.0, eneg = 0.0, etot = 0.0;
    for (int j = 0; j < H && !st; j++) {
        if (rows[j] < mn) mn = rows[j];
        eneg += rows[H + j];
        etot += rows[2 * H + j];
    }
    free(rows);
    if (st) return st;
    if (!isfinite(mn) || !isfinite(etot)) return sh_error(SH_ENUM, "sh_ringing: overflow");
    if (most_negative) *most_negative = mn;
    if (negative_energy_fraction) *negative_energy_fraction = etot > 0.0 ? eneg / etot : 0.0;
    return SH_OK;
}
