/* shade.c — environments, SH shading, the reference shading by direct
 * integration of the environment with ray-cast visibility, shading error.
 *
 * The reference integrates the rendering equation of shadowed diffuse
 * transfer (Green 2003, "Shadowed Diffuse Transfer"),
 *   B(x) = (ρ/π) ∫_H L(s) V(x,s) max(0, n·s) ds,
 * with the environment itself (not its SH projection).  An HDR probe's
 * energy sits in few pixels (a sun), and its pixel-scale detail makes
 * cosine-weighted sampling no better than plain Monte Carlo at the scale of
 * a stratum; so light × cosine is summed exactly over the pixels and only
 * visibility is sampled, one ray per block of pixels drawn in proportion to
 * the light it carries (scene.h).  Independent replications (different
 * jitter) give the standard error. */
#include "scene_internal.h"

#include <stdlib.h>
#include <string.h>

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
    if (!img || !out || !img->data) return sh_error(SH_EINVAL, "sh_env_from_image: bad arguments");
    if (img->width < 2 || img->height < 1)
        return sh_error(SH_EINVAL, "a %d×%d environment is too small: a lat-long environment needs at least 2×1 pixels",
                        img->width, img->height);
    if (img->nchan != 1 && img->nchan < 3)
        return sh_error(SH_EINVAL, "an environment needs 1 channel (luminance) or 3 or more (RGB), not %d", img->nchan);
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
            if (!isfinite(x)) { /* small negatives (lossy compression) are kept, as the projection keeps them */
                sh_env_free(e);
                return sh_error(SH_EFORMAT, "environment pixel %zu is not finite", k);
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
    /* channels Y, R, G, B as one 4-channel image, which must carry the order */
    const size_t np = (size_t)e->w * e->h;
    sh_image img = {.width = e->w, .height = e->h, .nchan = 4};
    if ((st = sh_image_check_order(&img, SH_LAYOUT_LATLONG, order))) return st;
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
    if (!(r2 > 0))
        return sh_error(SH_EINVAL,
                        "no light reaches the scene: the shading the errors are relative to is 0 at all %d vertices, "
                        "so a relative error is undefined",
                        n);
    e->rel_l2 = sqrt(d2 / r2);
    e->rel_max = dmax / sqrt(r2 / n);
    e->ref_l2 = sqrt(s2 / r2);
    return SH_OK;
}

/* ------------------------------------------------------------- reference */

typedef struct {
    const sh_scene *s;
    const sh_env *e;
    double R[9];              /* rotation of the environment (world = R·env) */
    const int *verts;
    const sh_reference_opts *o;
    int sq, reps;             /* analytic lights: s×s rays */
    int bs, bw, bh;           /* images: block side, blocks across and down */
    float *pdir;              /* images: pixel centre directions (3 per pixel) */
    double **wbuf;            /* images: per thread, a weight and a block sum per pixel */
    double rho, eps;
    double *B, *se;
    atomic_llong rays;
} rctx;

/* R·a (world from environment) and Rᵀ·a */
static void rot_apply(const double R[9], const double a[3], double o[3])
{
    for (int k = 0; k < 3; k++) o[k] = R[3 * k] * a[0] + R[3 * k + 1] * a[1] + R[3 * k + 2] * a[2];
}
static void rot_applyT(const double R[9], const double a[3], double o[3])
{
    for (int k = 0; k < 3; k++) o[k] = R[k] * a[0] + R[3 + k] * a[1] + R[6 + k] * a[2];
}

/* Per vertex, once: w[p] = L_p Ω_p max(0, n·centre_p) and, block by block
 * in scan order, cum[p] = Σ |w| of the block's pixels up to p. */
static void image_weights(const rctx *c, const double nenv[3], double *w, double *cum)
{
    const sh_env *e = c->e;
    const size_t np = (size_t)e->w * e->h;
    for (size_t p = 0; p < np; p++) {
        const float *cd = c->pdir + 3 * p;
        const double cp = nenv[0] * cd[0] + nenv[1] * cd[1] + nenv[2] * cd[2];
        w[p] = cp > 0 ? e->lum[p] * e->omega[p] * cp : 0.0;
    }
    sh__env_block_sums(e, c->bs, w, cum, NULL);
}

void sh__env_block_sums(const sh_env *e, int bs, const double *wt, double *cum, double *W)
{
    const int bw = (e->w + bs - 1) / bs, bh = (e->h + bs - 1) / bs;
    for (int by = 0; by < bh; by++)
        for (int bx = 0; bx < bw; bx++) {
            const int y0 = by * bs, x0 = bx * bs;
            const int y1 = y0 + bs < e->h ? y0 + bs : e->h, x1 = x0 + bs < e->w ? x0 + bs : e->w;
            double acc = 0;
            for (int y = y0; y < y1; y++)
                for (int x = x0; x < x1; x++) {
                    acc += fabs(wt[(size_t)y * e->w + x]);
                    cum[(size_t)y * e->w + x] = acc;
                }
            if (W) W[(size_t)by * bw + bx] = acc;
        }
}

size_t sh__env_block_pick(const sh_env *e, int bs, const double *cum, int bx, int by, double u, int *px, int *py)
{
    const int y0 = by * bs, x0 = bx * bs;
    const int y1 = y0 + bs < e->h ? y0 + bs : e->h, x1 = x0 + bs < e->w ? x0 + bs : e->w;
    const int bwid = x1 - x0, n = (y1 - y0) * bwid;
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (cum[(size_t)(y0 + mid / bwid) * e->w + x0 + mid % bwid] > u) hi = mid;
        else lo = mid + 1;
    }
    *py = y0 + lo / bwid;
    *px = x0 + lo % bwid;
    return (size_t)*py * e->w + *px;
}

void sh__env_pixel_sample(const sh_env *e, int px, int py, uint64_t *x, double d[3])
{
    const double dth = M_PI / e->h, dph = 2 * M_PI / e->w;
    const double z0 = cos(py * dth), z1 = cos((py + 1) * dth);
    const double z = z0 + (z1 - z0) * sh__uniform(x), ph = (px + sh__uniform(x)) * dph;
    const double st = sqrt(fmax(0.0, 1 - z * z));
    d[0] = st * cos(ph);
    d[1] = st * sin(ph);
    d[2] = z;
}

/* one replication of the image estimator at a vertex (see scene.h) */
static double image_replication(rctx *c, const double *w, const double *cum, const double nenv[3], const double org[3],
                                uint64_t *x, long long *rays)
{
    const sh_env *e = c->e;
    double sum = 0;
    for (int by = 0; by < c->bh; by++)
        for (int bx = 0; bx < c->bw; bx++) {
            const int y0 = by * c->bs, x0 = bx * c->bs;
            const int y1 = y0 + c->bs < e->h ? y0 + c->bs : e->h, x1 = x0 + c->bs < e->w ? x0 + c->bs : e->w;
            const double W = cum[(size_t)(y1 - 1) * e->w + x1 - 1]; /* the block's last running sum */
            if (!(W > 0)) continue;
            /* the pixel, with probability |w_p| / W: the first with cum > u */
            int px, py;
            const size_t p = sh__env_block_pick(e, c->bs, cum, bx, by, sh__uniform(x) * W, &px, &py);
            const float *cd = c->pdir + 3 * p;
            const double cp = nenv[0] * cd[0] + nenv[1] * cd[1] + nenv[2] * cd[2];
            if (!(cp > 0)) continue; /* cannot happen: w_p ≠ 0 */
            /* s uniform in the pixel's solid angle */
            double se_[3];
            sh__env_pixel_sample(e, px, py, x, se_);
            const double cs = nenv[0] * se_[0] + nenv[1] * se_[1] + nenv[2] * se_[2];
            if (cs <= 0) continue;
            double d[3];
            rot_apply(c->R, se_, d);
            (*rays)++;
            if (sh__occluded(c->s, org, d, INFINITY)) continue;
            sum += (w[p] > 0 ? W : -W) * cs / cp;
        }
    return c->rho / M_PI * sum;
}

static int ref_pass(void *vc, int thread, int begin, int end)
{
    rctx *c = vc;
    const sh_scene *s = c->s;
    const sh_mesh *m = &s->mesh;
    const sh_env *e = c->e;
    const int N = c->sq * c->sq;
    double *dir = e->is_image ? NULL : malloc(sizeof(double) * 3 * (size_t)N);
    if (!e->is_image && !dir) return sh_error(SH_ENOMEM, "out of memory");
    long long rays = 0;
    for (int iv = begin; iv < end; iv++) {
        const int v = c->verts ? c->verts[iv] : iv;
        const double *n = m->normal + 3 * v;
        double M[9], org[3], nenv[3];
        sh__tangent_frame(n, M);
        sh_scene_ray_origin(s, v, c->eps, org);
        rot_applyT(c->R, n, nenv); /* the normal in the environment's frame */
        double *w = e->is_image ? c->wbuf[thread] : NULL, *cum = w ? w + (size_t)e->w * e->h : NULL;
        if (w) image_weights(c, nenv, w, cum);
        double sum = 0, sum2 = 0;
        for (int r = c->o->first_replication; r < c->o->first_replication + c->reps; r++) {
            uint64_t seed = (uint64_t)c->o->seed * 1000003u + (uint64_t)v * 7919u + (uint64_t)r * 104729u + 1;
            double est = 0;
            if (w) {
                uint64_t h = seed ^ 0xA5A5A5A5DEADBEEFull, x = sh__splitmix(&h);
                est = image_replication(c, w, cum, nenv, org, &x, &rays);
            } else {
                /* cosine-weighted stratified rays, estimator (ρ/N) Σ V L(Rᵀd) */
                sh__cosine_samples(c->sq, seed, dir);
                for (int k = 0; k < N; k++) {
                    const double *dl = dir + 3 * k;
                    const double d[3] = {M[0] * dl[0] + M[1] * dl[1] + M[2] * dl[2], M[3] * dl[0] + M[4] * dl[1] + M[5] * dl[2],
                                         M[6] * dl[0] + M[7] * dl[1] + M[8] * dl[2]};
                    double q[3];
                    rot_applyT(c->R, d, q);
                    const double L = sh_env_eval(e, q, NULL);
                    if (L == 0) continue; /* no light: visibility does not matter */
                    rays++;
                    if (!sh__occluded(s, org, d, INFINITY)) est += L;
                }
                est *= c->rho / N;
            }
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
        o->first_replication < 0 || o->first_replication > 1000 || o->threads < 0 || o->threads > 256)
        return sh_error(SH_EINVAL,
                        "sh_shade_reference: samples, replications (>= 2), first_replication or threads out of range");
    const double rho = o->albedo > 0 ? o->albedo : 1.0;
    if (!(rho <= 1)) return sh_error(SH_EINVAL, "albedo %g not in (0, 1]", o->albedo);
    rctx c = {.s = s, .e = env, .verts = verts, .o = o, .rho = rho, .eps = o->ray_eps, .B = B, .se = se};
    atomic_init(&c.rays, 0);
    const long samples = o->samples > 0 ? o->samples : 8192;
    c.sq = (int)floor(sqrt((double)samples) + 0.5);
    if (c.sq < 1) c.sq = 1;
    c.reps = o->replications > 0 ? o->replications : 4;
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(c.R, rot ? rot->R : I, sizeof c.R);
    const int threads = o->threads > 0 ? o->threads : s->threads;
    int st = SH_OK;
    if (env->is_image) {
        /* blocks of bs×bs pixels, about `samples` of them on the sphere */
        const double per = (double)env->w * env->h / (double)samples;
        c.bs = (int)floor(sqrt(per) + 0.5);
        if (c.bs < 1) c.bs = 1;
        c.bw = (env->w + c.bs - 1) / c.bs;
        c.bh = (env->h + c.bs - 1) / c.bs;
        const size_t np = (size_t)env->w * env->h;
        c.pdir = malloc(sizeof(float) * 3 * np);
        c.wbuf = calloc((size_t)threads, sizeof *c.wbuf);
        if (!c.pdir || !c.wbuf) st = sh_error(SH_ENOMEM, "out of memory");
        for (int t = 0; !st && t < threads; t++)
            if (!(c.wbuf[t] = malloc(sizeof(double) * 2 * np))) st = sh_error(SH_ENOMEM, "out of memory");
        for (int y = 0; !st && y < env->h; y++)
            for (int x = 0; x < env->w; x++) {
                double d[3];
                sh_dir_from_angles(M_PI * (y + 0.5) / env->h, 2 * M_PI * (x + 0.5) / env->w, d);
                for (int k = 0; k < 3; k++) c.pdir[3 * ((size_t)y * env->w + x) + k] = (float)d[k];
            }
    }
    stats->threads = threads;
    const double t0 = sh__now();
    if (!st) st = sh__parallel_for(threads, nv, 2, ref_pass, &c, o->progress, o->progress_ctx, "reference vertices");
    stats->seconds = sh__now() - t0;
    stats->rays = atomic_load(&c.rays);
    stats->rays_per_s = stats->seconds > 0 ? stats->rays / stats->seconds : 0;
    stats->rays_per_vertex = env->is_image ? c.bw * c.bh * c.reps : c.sq * c.sq * c.reps;
    if (c.wbuf)
        for (int t = 0; t < threads; t++) free(c.wbuf[t]);
    free(c.wbuf);
    free(c.pdir);
    return st;
}
