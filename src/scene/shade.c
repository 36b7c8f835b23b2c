/* shade.c — environments, SH shading, the reference shading by direct
 * integration of the environment with ray-cast visibility, shading error.
 *
 * The reference integrates the rendering equation of shadowed diffuse
 * transfer (Green 2003, "Shadowed Diffuse Transfer"),
 *   B(x) = (ρ/π) ∫_H L(s) V(x,s) max(0, n·s) ds,
 * with the environment itself (not its SH projection).  An HDR probe's
 * energy sits in few pixels (a sun), which cosine-weighted sampling finds
 * rarely; so the brightest pixels are integrated one by one (their own
 * jittered rays, uniform in each pixel's solid angle) and only the rest by
 * cosine-weighted stratified rays — two unbiased estimators of disjoint
 * parts, summed.  Independent replications (different jitter) give the
 * standard error. */
#include "scene_internal.h"

#include <stdlib.h>
#include <string.h>

struct sh_env {
    int is_image;
    sh_light light;
    int w, h;
    float *lum, *rgb; /* w·h luminance; 3·w·h planar R, G, B */
    double *omega;    /* w·h pixel solid angles */
};

void sh_env_free(sh_env *e)
{
    if (!e) return;
    free(e->lum);
    free(e->rgb);
    free(e->omega);
    free(e);
}

int sh_env_from_light(const sh_light *L, sh_env **out)
{
    if (!L || !out) return sh_error(SH_EINVAL, "sh_env_from_light: bad arguments");
    *out = calloc(1, sizeof **out);
    if (!*out) return sh_error(SH_ENOMEM, "out of memory");
    (*out)->light = *L;
    return SH_OK;
}

int sh_env_from_image(const sh_image *img, sh_env **out)
{
    if (!img || !out || !img->data || img->width < 2 || img->height < 1 || (img->nchan != 1 && img->nchan < 3))
        return sh_error(SH_EINVAL, "sh_env_from_image: need a 1-channel or RGB image");
    if ((long long)img->width * img->height > SH_IMAGE_MAX_PIXELS) return sh_error(SH_EINVAL, "image too large");
    *out = NULL;
    sh_env *e = calloc(1, sizeof *e);
    if (!e) return sh_error(SH_ENOMEM, "out of memory");
    const size_t np = (size_t)img->width * img->height;
    e->is_image = 1;
    e->w = img->width;
    e->h = img->height;
    e->lum = malloc(sizeof(float) * np);
    e->rgb = malloc(sizeof(float) * 3 * np);
    e->omega = malloc(sizeof(double) * np);
    if (!e->lum || !e->rgb || !e->omega) { sh_env_free(e); return sh_error(SH_ENOMEM, "out of memory"); }
    int ci[3] = {0, 0, 0};
    if (img->nchan >= 3) {
        ci[1] = 1;
        ci[2] = 2;
        for (int c = 0; c < img->nchan; c++) {
            if (!strcmp(img->names[c], "R")) ci[0] = c;
            if (!strcmp(img->names[c], "G")) ci[1] = c;
            if (!strcmp(img->names[c], "B")) ci[2] = c;
        }
    }
    for (size_t k = 0; k < np; k++) {
        for (int c = 0; c < 3; c++) {
            const float x = img->data[(size_t)ci[c] * np + k];
            if (!isfinite(x) || x < 0) {
                sh_env_free(e);
                return sh_error(SH_EFORMAT, "environment pixel %zu is negative or not finite", k);
            }
            e->rgb[c * np + k] = x;
        }
        e->lum[k] = (float)(0.2126 * e->rgb[k] + 0.7152 * e->rgb[np + k] + 0.0722 * e->rgb[2 * np + k]);
    }
    int st = sh_pixel_solid_angles(SH_LAYOUT_LATLONG, e->w, e->h, e->omega);
    if (st) { sh_env_free(e); return st; }
    *out = e;
    return SH_OK;
}

/* lat-long pixel of a unit direction: θ = π(y+½)/h, φ = 2π(x+½)/w at centres */
static size_t env_pixel(const sh_env *e, const double d[3])
{
    const double th = acos(fmax(-1.0, fmin(1.0, d[2])));
    double ph = atan2(d[1], d[0]);
    if (ph < 0) ph += 2 * M_PI;
    int x = (int)(ph / (2 * M_PI) * e->w), y = (int)(th / M_PI * e->h);
    if (x >= e->w) x = e->w - 1;
    if (y >= e->h) y = e->h - 1;
    if (x < 0) x = 0;
    if (y < 0) y = 0;
    return (size_t)y * e->w + x;
}

double sh_env_eval(const sh_env *e, const double dir[3], double rgb[3])
{
    if (!e->is_image) {
        double th, ph;
        sh_angles_from_dir(dir, &th, &ph);
        const double v = sh_light_eval(&e->light, dir, th, ph);
        if (rgb) rgb[0] = rgb[1] = rgb[2] = v;
        return v;
    }
    const size_t k = env_pixel(e, dir), np = (size_t)e->w * e->h;
    if (rgb)
        for (int c = 0; c < 3; c++) rgb[c] = e->rgb[c * np + k];
    return e->lum[k];
}

int sh_env_project(const sh_env *e, int order, sh_convention conv, double *coeffs)
{
    if (!e || !coeffs) return sh_error(SH_EINVAL, "sh_env_project: bad arguments");
    int st = sh_check_order(order);
    if (st) return st;
    const int n2 = order * order;
    if (!e->is_image) {
        if (sh_light_has_closed_form(&e->light)) st = sh_light_closed_form(&e->light, order, conv, coeffs);
        else st = sh_project(order, conv, sh_light_fn, (void *)&e->light, SH_RULE_QUAD, 2 * order + 8, 0, coeffs);
        if (st) return st;
        for (int c = 1; c < 4; c++) memcpy(coeffs + (size_t)c * n2, coeffs, sizeof(double) * n2);
        return SH_OK;
    }
    /* channels Y, R, G, B as one 4-channel image */
    const size_t np = (size_t)e->w * e->h;
    sh_image img = {.width = e->w, .height = e->h, .nchan = 4};
    img.data = malloc(sizeof(float) * 4 * np);
    if (!img.data) return sh_error(SH_ENOMEM, "out of memory");
    memcpy(img.data, e->lum, sizeof(float) * np);
    memcpy(img.data + np, e->rgb, sizeof(float) * 3 * np);
    st = sh_project_image(&img, SH_LAYOUT_LATLONG, order, conv, coeffs);
    free(img.data);
    return st;
}

int sh_shade(int nvert, int tord, const double *T, int order, const double *L, double *B)
{
    if (nvert < 0 || !T || !L || !B || order < 1 || order > tord) return sh_error(SH_EINVAL, "sh_shade: bad arguments");
    const int n2 = order * order, t2 = tord * tord;
    /* Green: B(x) = Σ_i L_i t_i(x) (orthonormality turns ∫ L t into a dot product) */
    for (int v = 0; v < nvert; v++) {
        double b = 0;
        for (int i = 0; i < n2; i++) b += L[i] * T[(size_t)v * t2 + i];
        B[v] = b;
    }
    return SH_OK;
}

int sh_shade_error(int n, const double *B, const double *ref, const double *se, sh_shade_err *e)
{
    if (n < 1 || !B || !ref || !e) return sh_error(SH_EINVAL, "sh_shade_error: bad arguments");
    double d2 = 0, r2 = 0, s2 = 0, dmax = 0;
    for (int v = 0; v < n; v++) {
        const double d = B[v] - ref[v];
        d2 += d * d;
        r2 += ref[v] * ref[v];
        if (se) s2 += se[v] * se[v];
        dmax = fmax(dmax, fabs(d));
    }
    if (!(r2 > 0)) return sh_error(SH_EINVAL, "sh_shade_error: the reference is zero everywhere");
    e->rel_l2 = sqrt(d2 / r2);
    e->rel_max = dmax / sqrt(r2 / n);
    e->ref_l2 = sqrt(s2 / r2);
    return SH_OK;
}

/* ------------------------------------------------------------- reference */

typedef struct {
    const sh_scene *s;
    const sh_env *e;
    double R[9];             /* rotation of the environment (world = R·env) */
    const int *verts;
    const sh_reference_opts *o;
    int sq, reps, nbright, bright_rays;
    const int *bright;       /* pixel indices */
    unsigned char *is_bright; /* per pixel */
    double rho, eps;
    double *B, *se;
    atomic_llong rays;
} rctx;

static double rest_eval(const rctx *c, const double d[3])
{
    /* L(Rᵀ d), the bright pixels excluded */
    const double q[3] = {c->R[0] * d[0] + c->R[3] * d[1] + c->R[6] * d[2], c->R[1] * d[0] + c->R[4] * d[1] + c->R[7] * d[2],
                         c->R[2] * d[0] + c->R[5] * d[1] + c->R[8] * d[2]};
    if (!c->e->is_image) return sh_env_eval(c->e, q, NULL);
    const size_t k = env_pixel(c->e, q);
    return c->is_bright[k] ? 0.0 : c->e->lum[k];
}

static int ref_pass(void *vc, int thread, int begin, int end)
{
    rctx *c = vc;
    const sh_scene *s = c->s;
    const sh_mesh *m = &s->mesh;
    const int N = c->sq * c->sq;
    double *dir = malloc(sizeof(double) * 3 * (size_t)N);
    if (!dir) return sh_error(SH_ENOMEM, "out of memory");
    long long rays = 0;
    const double dth = M_PI / (c->e ? (c->e->h ? c->e->h : 1) : 1), dph = 2 * M_PI / (c->e->w ? c->e->w : 1);
    /* a pixel lies wholly below the horizon when its centre is more than
     * its angular half-diagonal below it */
    const double half_diag = 0.5 * sqrt(dth * dth + dph * dph);
    for (int iv = begin; iv < end; iv++) {
        const int v = c->verts ? c->verts[iv] : iv;
        const double *n = m->normal + 3 * v;
        double M[9], org[3];
        sh__tangent_frame(n, M);
        sh_scene_ray_origin(s, v, c->eps, org);
        double sum = 0, sum2 = 0;
        for (int r = 0; r < c->reps; r++) {
            uint64_t seed = (uint64_t)c->o->seed * 1000003u + (uint64_t)v * 7919u + (uint64_t)r * 104729u + 1;
            /* the rest of the environment: cosine-weighted stratified rays,
             * estimator (ρ/N) Σ V L (density cosθ/π) */
            sh__cosine_samples(c->sq, seed, dir);
            double est = 0;
            for (int k = 0; k < N; k++) {
                const double *dl = dir + 3 * k;
                const double d[3] = {M[0] * dl[0] + M[1] * dl[1] + M[2] * dl[2], M[3] * dl[0] + M[4] * dl[1] + M[5] * dl[2],
                                     M[6] * dl[0] + M[7] * dl[1] + M[8] * dl[2]};
                const double L = rest_eval(c, d);
                if (L == 0) continue; /* no light: visibility does not matter */
                rays++;
                if (!sh__occluded(s, org, d, INFINITY)) est += L;
            }
            est *= c->rho / N;
            /* bright pixels: (ρ/π) L_p Ω_p · mean over jittered rays in the
             * pixel (uniform in solid angle) of V max(0, n·s) */
            uint64_t x = seed ^ 0xA5A5A5A5DEADBEEFull;
            double eb = 0;
            for (int b = 0; b < c->nbright; b++) {
                const int p = c->bright[b], py = p / c->e->w, px = p % c->e->w;
                const double th0 = py * dth, ph0 = px * dph;
                double ce[3], cw[3];
                sh_dir_from_angles(th0 + 0.5 * dth, ph0 + 0.5 * dph, ce);
                for (int k = 0; k < 3; k++) cw[k] = c->R[3 * k] * ce[0] + c->R[3 * k + 1] * ce[1] + c->R[3 * k + 2] * ce[2];
                if (n[0] * cw[0] + n[1] * cw[1] + n[2] * cw[2] < -sin(half_diag)) continue;
                double acc = 0;
                for (int k = 0; k < c->bright_rays; k++) {
                    /* uniform in solid angle: cosθ uniform between the rows' edges */
                    const double z0 = cos(th0), z1 = cos(th0 + dth);
                    const double z = z0 + (z1 - z0) * sh__uniform(&x), ph = ph0 + dph * sh__uniform(&x);
                    const double st_ = sqrt(fmax(0.0, 1 - z * z));
                    const double de[3] = {st_ * cos(ph), st_ * sin(ph), z};
                    double d[3];
                    for (int q = 0; q < 3; q++) d[q] = c->R[3 * q] * de[0] + c->R[3 * q + 1] * de[1] + c->R[3 * q + 2] * de[2];
                    const double cs = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                    if (cs <= 0) continue;
                    rays++;
                    if (!sh__occluded(s, org, d, INFINITY)) acc += cs;
                }
                eb += c->e->lum[p] * c->e->omega[p] * acc / c->bright_rays;
            }
            est += c->rho / M_PI * eb;
            sum += est;
            sum2 += est * est;
        }
        const double mean = sum / c->reps;
        const double var = fmax(0.0, (sum2 - c->reps * mean * mean) / (c->reps - 1));
        c->B[iv] = mean;
        if (c->se) c->se[iv] = sqrt(var / c->reps);
    }
    free(dir);
    atomic_fetch_add(&c->rays, rays);
    return sh__embree_status(s, "casting reference rays");
}

static const float *g_key;
static int cmp_bright(const void *a, const void *b)
{
    const float x = g_key[*(const int *)a], y = g_key[*(const int *)b];
    return x > y ? -1 : x < y ? 1 : *(const int *)a - *(const int *)b;
}

int sh_shade_reference(const sh_scene *s, const sh_env *env, const sh_rotation *rot, const int *verts, int nv,
                       const sh_reference_opts *o, double *B, double *se, sh_transfer_stats *stats)
{
    sh_transfer_stats st0;
    if (!stats) stats = &st0;
    memset(stats, 0, sizeof *stats);
    if (!s || !env || !o || !B) return sh_error(SH_EINVAL, "sh_shade_reference: bad arguments");
    if (!verts) nv = s->mesh.nvert;
    if (nv < 0) return sh_error(SH_EINVAL, "sh_shade_reference: negative vertex count");
    for (int i = 0; verts && i < nv; i++)
        if (verts[i] < 0 || verts[i] >= s->mesh.nvert) return sh_error(SH_EINVAL, "sh_shade_reference: vertex %d out of range", verts[i]);
    if (o->samples < 0 || o->samples > 1L << 24 || o->replications == 1 || o->replications < 0 || o->replications > 1000 ||
        o->bright_rays < 0 || o->bright_rays > 1024 || o->threads < 0 || o->threads > 256)
        return sh_error(SH_EINVAL, "sh_shade_reference: samples, replications (>= 2), bright rays or threads out of range");
    const double rho = o->albedo > 0 ? o->albedo : 1.0;
    if (!(rho <= 1)) return sh_error(SH_EINVAL, "albedo %g not in (0, 1]", o->albedo);
    rctx c = {.s = s, .e = env, .verts = verts, .o = o, .rho = rho, .eps = o->ray_eps, .B = B, .se = se};
    atomic_init(&c.rays, 0);
    c.sq = (int)floor(sqrt((double)(o->samples > 0 ? o->samples : 4096)) + 0.5);
    if (c.sq < 1) c.sq = 1;
    c.reps = o->replications > 0 ? o->replications : 4;
    c.bright_rays = o->bright_rays > 0 ? o->bright_rays : 4;
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(c.R, rot ? rot->R : I, sizeof c.R);
    int *bright = NULL;
    if (env->is_image && o->bright >= 0) {
        const size_t np = (size_t)env->w * env->h;
        c.nbright = o->bright > 0 ? o->bright : 2048;
        if ((size_t)c.nbright > np) c.nbright = (int)np;
        int *idx = malloc(sizeof(int) * np);
        float *key = malloc(sizeof(float) * np);
        c.is_bright = calloc(np, 1);
        if (!idx || !key || !c.is_bright) {
            free(idx); free(key); free(c.is_bright);
            return sh_error(SH_ENOMEM, "out of memory");
        }
        for (size_t k = 0; k < np; k++) {
            idx[k] = (int)k;
            key[k] = (float)(env->lum[k] * env->omega[k]);
        }
        g_key = key;
        qsort(idx, np, sizeof(int), cmp_bright);
        free(key);
        bright = idx;
        for (int b = 0; b < c.nbright; b++) c.is_bright[bright[b]] = 1;
    } else if (env->is_image) {
        c.is_bright = calloc((size_t)env->w * env->h, 1);
        if (!c.is_bright) return sh_error(SH_ENOMEM, "out of memory");
    }
    c.bright = bright;
    const int threads = o->threads > 0 ? o->threads : s->threads;
    stats->threads = threads;
    const double t0 = sh__now();
    int st = sh__parallel_for(threads, nv, 4, ref_pass, &c, o->progress, o->progress_ctx, "reference vertices");
    stats->seconds = sh__now() - t0;
    stats->rays = atomic_load(&c.rays);
    stats->rays_per_s = stats->seconds > 0 ? stats->rays / stats->seconds : 0;
    stats->rays_per_vertex = c.sq * c.sq * c.reps;
    free(bright);
    free(c.is_bright);
    return st;
}
