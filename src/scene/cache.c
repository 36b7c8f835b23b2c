/* cache.c — Křivánek et al.'s radiance cache (scene.h): the incident
 * radiance in SH at sparse records, each in its own tangent frame, reused
 * at nearby vertices after a rotation from the record's frame into the
 * vertex's.
 *
 * References:
 *  [1] Křivánek, Konttinen, Pattanaik, Bouatouch, Žára 2005, "Fast
 *      approximation to spherical harmonic rotation", Sec. 4.2 (Eq. 1, the
 *      weight w_i, no translation gradients), Table 1, Figure 7, App. B.
 *  [2] Ward, Rubinstein, Clear 1988, "A ray tracing solution for diffuse
 *      interreflection": the weight 1/w = ‖p − p_i‖/R_i + √(1 − n·n_i), R_i
 *      the harmonic mean distance of the hemisphere's rays, records made
 *      lazily where no record covers a point.
 *  [3] Green 2003 (projection, diffuse transfer); Ramamoorthi & Hanrahan
 *      2001 (the clamped cosine and the Phong lobe as zonal functions, the
 *      addition theorem y-rotated to any direction). */
#include "scene_internal.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#define HARM_SIDE 8          /* 8×8 rays for the harmonic mean distance */
#define BOUNCE_MAX_ORDER 8   /* order of the direct light handed on by the bounce */
#define DIRECT_CHUNK 2048    /* vertices per pass of sh_cache_shade_direct */

/* ------------------------------------------------------------ options */

static int check_opts(const sh_scene *s, const sh_env *env, const sh_cache_opts *o)
{
    if (!s || !env || !o) return sh_error(SH_EINVAL, "radiance cache: bad arguments");
    const int order = o->order > 0 ? o->order : 6;
    int st = sh_check_order(order);
    if (st) return st;
    if (order > 32) return sh_error(SH_EINVAL, "radiance cache: order %d > 32", order);
    if (o->env_samples < 0 || (o->env_samples > 0 && o->env_samples < 16) || o->env_samples > 1L << 22)
        return sh_error(SH_EINVAL, "radiance cache: environment samples %ld not in 16..2^22", o->env_samples);
    if (o->rays < 0 || o->rays > 1L << 20) return sh_error(SH_EINVAL, "radiance cache: rays %ld not in 1..2^20", o->rays);
    if (!(o->albedo >= 0 && o->albedo <= 1)) return sh_error(SH_EINVAL, "albedo %g not in (0, 1]", o->albedo);
    if (!(o->a >= 0 && o->a <= 10)) return sh_error(SH_EINVAL, "radiance cache: allowed error a = %g not in (0, 10]", o->a);
    const double rmin = o->rmin > 0 ? o->rmin : 0.01, rmax = o->rmax > 0 ? o->rmax : 0.25;
    if (!(o->rmin >= 0 && o->rmax >= 0 && rmin < rmax && rmax <= 100))
        return sh_error(SH_EINVAL, "radiance cache: need 0 < rmin < rmax <= 100 (got %g, %g)", rmin, rmax);
    if (!(o->ray_eps >= 0 && o->ray_eps < 0.1)) return sh_error(SH_EINVAL, "ray offset must be in [0, 0.1)");
    if (o->threads < 0 || o->threads > 256) return sh_error(SH_EINVAL, "threads %d not in 0..256", o->threads);
    if (o->brdf.phong) {
        if (!(o->brdf.exponent > 0 && o->brdf.exponent <= 10000))
            return sh_error(SH_EINVAL, "Phong exponent %g not in (0, 10000]", o->brdf.exponent);
        for (int k = 0; k < 3; k++)
            if (!isfinite(o->brdf.eye[k])) return sh_error(SH_EINVAL, "Phong: the eye position is not finite");
    }
    return SH_OK;
}

void sh_rgb_luminance(int n, const double *rgb, double *Y)
{
    for (int v = 0; v < n; v++) Y[v] = 0.2126 * rgb[3 * v] + 0.7152 * rgb[3 * v + 1] + 0.0722 * rgb[3 * v + 2];
}

/* ------------------------------------------------- environment sampling */

/* Images: blocks of bs×bs pixels; per pixel the weight Ω_p·(|R|+|G|+|B|)
 * and, block by block in scan order, its running sum. */
typedef struct {
    int bs, bw, bh;
    double *W;   /* per block: the sum of its weights */
    double *cum; /* per pixel */
    float *S;    /* per pixel: |R| + |G| + |B| */
} envtab;

static void envtab_free(envtab *t)
{
    free(t->W);
    free(t->cum);
    free(t->S);
}

static int envtab_build(const sh_env *e, long samples, envtab *t)
{
    memset(t, 0, sizeof *t);
    const size_t np = (size_t)e->w * e->h;
    const double per = (double)np / (double)samples;
    t->bs = (int)floor(sqrt(per) + 0.5);
    if (t->bs < 1) t->bs = 1;
    t->bw = (e->w + t->bs - 1) / t->bs;
    t->bh = (e->h + t->bs - 1) / t->bs;
    t->W = malloc(sizeof(double) * (size_t)t->bw * t->bh);
    t->cum = malloc(sizeof(double) * np);
    t->S = malloc(sizeof(float) * np);
    if (!t->W || !t->cum || !t->S) {
        envtab_free(t);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    for (size_t p = 0; p < np; p++) {
        t->S[p] = fabsf(e->rgb[p]) + fabsf(e->rgb[np + p]) + fabsf(e->rgb[2 * np + p]);
        t->cum[p] = e->omega[p] * t->S[p];
    }
    sh__env_block_sums(e, t->bs, t->cum, t->cum, t->W); /* in place */
    return SH_OK;
}

/* A stratified uniform direction on the hemisphere z > 0: cell (i, j) of an
 * s×s grid in (z, φ), jittered (density 1/2π). */
static void hemi_uniform(int i, int j, int s, uint64_t *x, double u[3])
{
    const double z = (i + sh__uniform(x)) / s, ph = 2 * M_PI * (j + sh__uniform(x)) / s;
    const double r = sqrt(fmax(0.0, 1 - z * z));
    u[0] = r * cos(ph);
    u[1] = r * sin(ph);
    u[2] = z;
}

static void to_world(const double M[9], const double u[3], double d[3])
{
    for (int k = 0; k < 3; k++) d[k] = M[3 * k] * u[0] + M[3 * k + 1] * u[1] + M[3 * k + 2] * u[2];
}

/* The random stream of vertex v for one purpose (salt): depends on (seed,
 * v, salt) only, so a vertex gets the same numbers in every pass. */
static uint64_t vertex_stream(unsigned long seed, int v, uint64_t salt)
{
    uint64_t h = (uint64_t)seed * 0x9E3779B97F4A7C15ull ^ ((uint64_t)v + 1) * 0xD1B54A32D192ED03ull ^ salt;
    return sh__splitmix(&h);
}

/* -------------------------------------------------- incident radiance */

typedef struct {
    const sh_scene *s;
    const sh_env *env;
    int order, n2, sq_env, sq_b;
    envtab et;
    double *Bd; /* bounce: 3·nvert direct exit radiance, or NULL */
    const int *verts;
    double *L;
    double eps;
    unsigned long seed;
    atomic_llong rays;
} ictx;

static void add_scaled(int n2, const double *y, const double k[3], double *out)
{
    for (int c = 0; c < 3; c++) {
        if (k[c] == 0) continue;
        double *o = out + (size_t)c * n2;
        for (int i = 0; i < n2; i++) o[i] += k[c] * y[i];
    }
}

/* Λ at vertex v (3·n2, zeroed here); y: n2 scratch. */
static int incident_one(ictx *c, int v, double *y, double *out, long long *rays)
{
    const sh_scene *s = c->s;
    const sh_env *e = c->env;
    const int n2 = c->n2;
    const double *n = s->mesh.normal + 3 * v;
    double M[9], org[3];
    sh__tangent_frame(n, M);
    sh_scene_ray_origin(s, v, c->eps, org);
    memset(out, 0, sizeof(double) * 3 * n2);
    uint64_t x = vertex_stream(c->seed, v, 0x1111);
    int st = SH_OK;
    if (e->is_image) {
        /* one sample per block: pixel ∝ Ω_p S_p, s uniform in the pixel;
         * estimate of Σ_p L_c,p ∫_p V y is W_block · L_c,p / S_p · V(s) y(s) */
        const size_t np = (size_t)e->w * e->h;
        for (int by = 0; by < c->et.bh && !st; by++)
            for (int bx = 0; bx < c->et.bw; bx++) {
                const double W = c->et.W[(size_t)by * c->et.bw + bx];
                if (!(W > 0)) continue;
                int px, py;
                const size_t p = sh__env_block_pick(e, c->et.bs, c->et.cum, bx, by, sh__uniform(&x) * W, &px, &py);
                double d[3];
                sh__env_pixel_sample(e, px, py, &x, d);
                if (d[0] * n[0] + d[1] * n[1] + d[2] * n[2] <= 0 || !(c->et.S[p] > 0)) continue;
                (*rays)++;
                if (sh__occluded(s, org, d, INFINITY)) continue;
                const double u[3] = {M[0] * d[0] + M[3] * d[1] + M[6] * d[2], M[1] * d[0] + M[4] * d[1] + M[7] * d[2],
                                     M[2] * d[0] + M[5] * d[1] + M[8] * d[2]};
                if ((st = sh_eval_dir(c->order, SH_CS, u, y))) break;
                const double f = W / c->et.S[p];
                const double k[3] = {f * e->rgb[p], f * e->rgb[np + p], f * e->rgb[2 * np + p]};
                add_scaled(n2, y, k, out);
            }
    } else {
        /* stratified uniform hemisphere: (2π/N) Σ L V y */
        const int sq = c->sq_env, N = sq * sq;
        for (int i = 0; i < sq && !st; i++)
            for (int j = 0; j < sq; j++) {
                double u[3], d[3];
                hemi_uniform(i, j, sq, &x, u);
                to_world(M, u, d);
                const double Lv = sh_env_eval(e, d, NULL);
                if (Lv == 0) continue;
                (*rays)++;
                if (sh__occluded(s, org, d, INFINITY)) continue;
                if ((st = sh_eval_dir(c->order, SH_CS, u, y))) break;
                const double f = 2 * M_PI / N * Lv, k[3] = {f, f, f};
                add_scaled(n2, y, k, out);
            }
    }
    if (c->Bd && !st) {
        /* one bounce: (2π/N) Σ over front hits of B_d(hit) y */
        uint64_t xb = vertex_stream(c->seed, v, 0x2222);
        const int sq = c->sq_b, N = sq * sq;
        const sh_mesh *m = &s->mesh;
        for (int i = 0; i < sq && !st; i++)
            for (int j = 0; j < sq; j++) {
                double u[3], d[3], t, hu, hv;
                int front;
                hemi_uniform(i, j, sq, &xb, u);
                to_world(M, u, d);
                (*rays)++;
                const int h = sh__intersect(s, org, d, INFINITY, &t, &hu, &hv, &front);
                if (!h || !front) continue;
                const int *tc = m->tri + 3 * (h - 1);
                const double w0 = 1 - hu - hv;
                double k[3];
                for (int ch = 0; ch < 3; ch++)
                    k[ch] = 2 * M_PI / N *
                            (w0 * c->Bd[3 * tc[0] + ch] + hu * c->Bd[3 * tc[1] + ch] + hv * c->Bd[3 * tc[2] + ch]);
                if (k[0] == 0 && k[1] == 0 && k[2] == 0) continue;
                if ((st = sh_eval_dir(c->order, SH_CS, u, y))) break;
                add_scaled(n2, y, k, out);
            }
    }
    return st;
}

static int incident_pass(void *vc, int thread, int begin, int end)
{
    ictx *c = vc;
    double *y = malloc(sizeof(double) * (size_t)c->n2);
    if (!y) return sh_error(SH_ENOMEM, "out of memory");
    long long rays = 0;
    int st = SH_OK;
    for (int k = begin; k < end && !st; k++)
        st = incident_one(c, c->verts ? c->verts[k] : k, y, c->L + (size_t)k * 3 * c->n2, &rays);
    free(y);
    atomic_fetch_add(&c->rays, rays);
    return st ? st : sh__embree_status(c->s, "casting incident radiance rays");
}

/* The direct exit radiance at every vertex (R, G, B), for the bounce. */
static int direct_exit(const sh_scene *s, const sh_env *env, const sh_cache_opts *o, int order, double *Bd)
{
    const int bo = order < BOUNCE_MAX_ORDER ? order : BOUNCE_MAX_ORDER, n2 = bo * bo, nv = s->mesh.nvert;
    double *T = malloc(sizeof(double) * (size_t)nv * n2), *Le = malloc(sizeof(double) * 4 * n2);
    if (!T || !Le) {
        free(T);
        free(Le);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    sh_transfer_opts to = {0};
    to.kind = SH_TRANSFER_SHADOWED;
    to.order = bo;
    to.rays = o->rays;
    to.seed = o->seed;
    to.albedo = o->albedo;
    to.ray_eps = o->ray_eps;
    to.threads = o->threads;
    int st = sh_transfer(s, &to, T, NULL);
    if (!st) st = sh_env_project(env, bo, SH_CS, Le);
    for (int v = 0; v < nv && !st; v++)
        for (int c = 0; c < 3; c++) {
            double b = 0;
            for (int i = 0; i < n2; i++) b += Le[(size_t)(c + 1) * n2 + i] * T[(size_t)v * n2 + i];
            Bd[3 * v + c] = fmax(0.0, b);
        }
    free(T);
    free(Le);
    return st;
}

static int ictx_init(ictx *c, const sh_scene *s, const sh_env *env, const sh_cache_opts *o)
{
    memset(c, 0, sizeof *c);
    c->s = s;
    c->env = env;
    c->order = o->order > 0 ? o->order : 6;
    c->n2 = c->order * c->order;
    c->eps = o->ray_eps;
    c->seed = o->seed;
    atomic_init(&c->rays, 0);
    const long es = o->env_samples > 0 ? o->env_samples : 4096;
    c->sq_env = (int)floor(sqrt((double)es) + 0.5);
    c->sq_b = (int)floor(sqrt((double)(o->rays > 0 ? o->rays : 1024)) + 0.5);
    if (c->sq_b < 1) c->sq_b = 1;
    int st = env->is_image ? envtab_build(env, es, &c->et) : SH_OK;
    if (!st && o->bounce) {
        if (!(c->Bd = malloc(sizeof(double) * 3 * (size_t)s->mesh.nvert))) st = sh_error(SH_ENOMEM, "out of memory");
        else st = direct_exit(s, env, o, c->order, c->Bd);
    }
    return st;
}

static void ictx_free(ictx *c)
{
    envtab_free(&c->et);
    free(c->Bd);
}

static int incident_run(ictx *c, const sh_cache_opts *o, const int *verts, int nv, double *L, const char *what)
{
    c->verts = verts;
    c->L = L;
    const int threads = o->threads > 0 ? o->threads : c->s->threads;
    return sh__parallel_for(threads, nv, 4, incident_pass, c, o->progress, o->progress_ctx, what);
}

int sh_incident_radiance(const sh_scene *s, const sh_env *env, const sh_cache_opts *o, const int *verts, int nv,
                         double *L, sh_transfer_stats *stats)
{
    sh_transfer_stats st0;
    if (!stats) stats = &st0;
    memset(stats, 0, sizeof *stats);
    int st = check_opts(s, env, o);
    if (st) return st;
    if (!L) return sh_error(SH_EINVAL, "sh_incident_radiance: no output");
    if (!verts) nv = s->mesh.nvert;
    if (nv < 0) return sh_error(SH_EINVAL, "sh_incident_radiance: negative vertex count");
    for (int k = 0; verts && k < nv; k++)
        if (verts[k] < 0 || verts[k] >= s->mesh.nvert)
            return sh_error(SH_EINVAL, "sh_incident_radiance: vertex %d out of range", verts[k]);
    ictx c;
    const double t0 = sh__now();
    st = ictx_init(&c, s, env, o);
    if (!st) st = incident_run(&c, o, verts, nv, L, "incident radiance");
    stats->seconds = sh__now() - t0;
    stats->rays = atomic_load(&c.rays);
    stats->rays_per_s = stats->seconds > 0 ? stats->rays / stats->seconds : 0;
    stats->threads = o->threads > 0 ? o->threads : s->threads;
    ictx_free(&c);
    return st;
}

/* --------------------------------------------------------------- cache */

struct sh_cache {
    const sh_scene *s;
    const sh_env *env;
    sh_cache_opts o;
    int order, n2, nv, nrec;
    int *rec_vertex;   /* nrec */
    double *harm;      /* nv: R(v), clamped */
    double *L;         /* nrec·3·n2: the records, each in its own frame */
    double *frames;    /* nv·9 */
    /* the records each vertex uses (CSR over vertices) */
    int *nb_start;     /* nv + 1 */
    int *nb_rec;
    double *nb_iw;     /* 1/w (0: the record sits at the vertex's position with its normal) */
    double *nb_R;      /* 9 per use: M_vᵀ M_i */
    double *nb_beta;
    /* shading: one vector for diffuse, nv for Phong */
    double *g;
    int g_per_vertex;
    sh_cache_info info;
};

void sh_cache_free(sh_cache *c)
{
    if (!c) return;
    free(c->rec_vertex);
    free(c->harm);
    free(c->L);
    free(c->frames);
    free(c->nb_start);
    free(c->nb_rec);
    free(c->nb_iw);
    free(c->nb_R);
    free(c->nb_beta);
    free(c->g);
    free(c);
}

typedef struct {
    const sh_scene *s;
    double *harm;
    double eps;
    unsigned long seed;
    atomic_llong rays;
} hctx;

/* [2] R(v) = N / Σ 1/t_k over N stratified uniform hemisphere rays */
static int harm_pass(void *vc, int thread, int begin, int end)
{
    hctx *c = vc;
    long long rays = 0;
    for (int v = begin; v < end; v++) {
        double M[9], org[3];
        sh__tangent_frame(c->s->mesh.normal + 3 * v, M);
        sh_scene_ray_origin(c->s, v, c->eps, org);
        uint64_t x = vertex_stream(c->seed, v, 0x3333);
        double inv = 0;
        for (int i = 0; i < HARM_SIDE; i++)
            for (int j = 0; j < HARM_SIDE; j++) {
                double u[3], d[3], t, hu, hv;
                int front;
                hemi_uniform(i, j, HARM_SIDE, &x, u);
                to_world(M, u, d);
                rays++;
                if (sh__intersect(c->s, org, d, INFINITY, &t, &hu, &hv, &front)) inv += 1 / fmax(t, 1e-300);
            }
        c->harm[v] = inv > 0 ? HARM_SIDE * HARM_SIDE / inv : INFINITY;
    }
    atomic_fetch_add(&c->rays, rays);
    return sh__embree_status(c->s, "casting harmonic-mean rays");
}

/* [2] 1/w_i(p) = ‖p − p_i‖/R_i + √(1 − n·n_i) */
static double inv_weight(const sh_mesh *m, const double *harm, int p, int i)
{
    const double *a = m->pos + 3 * p, *b = m->pos + 3 * i, *na = m->normal + 3 * p, *nb = m->normal + 3 * i;
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const double nn = na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2];
    /* the same point with the same normal: w = ∞ exactly (n·n may round below 1) */
    if (dx == 0 && dy == 0 && dz == 0 && na[0] == nb[0] && na[1] == nb[1] && na[2] == nb[2]) return 0;
    return sqrt(dx * dx + dy * dy + dz * dz) / harm[i] + sqrt(fmax(0.0, 1 - nn));
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int setup_brdf(sh_cache *c)
{
    const sh_mesh *m = &c->s->mesh;
    const int n2 = c->n2;
    const double rho = c->o.albedo > 0 ? c->o.albedo : 1.0;
    if (!c->o.brdf.phong) {
        /* [3] diffuse: t = (ρ/π) clamped cosine about the local ẑ */
        static const double zhat[3] = {0, 0, 1};
        if (!(c->g = malloc(sizeof(double) * n2))) return sh_error(SH_ENOMEM, "out of memory");
        return sh_transfer_unshadowed(c->order, SH_CS, rho, zhat, c->g);
    }
    c->g_per_vertex = 1;
    double *z = malloc(sizeof(double) * c->order);
    c->g = malloc(sizeof(double) * (size_t)c->nv * n2);
    if (!z || !c->g) {
        free(z);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    const double E = c->o.brdf.exponent;
    int st = sh_lobe_zonal(E, c->order, z);
    for (int v = 0; v < c->nv && !st; v++) {
        /* r: the mirror direction of the view direction, in v's frame */
        const double *p = m->pos + 3 * v, *M = c->frames + 9 * (size_t)v;
        double w[3] = {c->o.brdf.eye[0] - p[0], c->o.brdf.eye[1] - p[1], c->o.brdf.eye[2] - p[2]};
        const double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        double r[3] = {0, 0, 1};
        if (wl > 0) {
            const double u[3] = {(M[0] * w[0] + M[3] * w[1] + M[6] * w[2]) / wl, (M[1] * w[0] + M[4] * w[1] + M[7] * w[2]) / wl,
                                 (M[2] * w[0] + M[5] * w[1] + M[8] * w[2]) / wl};
            r[0] = -u[0];
            r[1] = -u[1];
            r[2] = u[2];
        }
        double *g = c->g + (size_t)v * n2;
        if ((st = sh_eval_dir(c->order, SH_CS, r, g))) break;
        /* ρ (E+1)/(2π) max(0, r·s)^E = Σ_lm ρ (E+1)/(2π) √(4π/(2l+1)) z_l y_lm(r) y_lm(s) */
        for (int l = 0; l < c->order; l++) {
            const double f = rho * (E + 1) / (2 * M_PI) * sqrt(4 * M_PI / (2 * l + 1)) * z[l];
            for (int mm = -l; mm <= l; mm++) g[sh_index(l, mm)] *= f;
        }
    }
    free(z);
    return st;
}

/* [2] R(v) at every vertex (harm_pass), clamped to [rmin, rmax]; the
 * clamped fractions and the rays cast into c->info. */
static int harmonic_radii(sh_cache *c, const sh_cache_opts *o, int threads, double rmin, double rmax)
{
    const int nv = c->nv;
    hctx hc = {.s = c->s, .harm = c->harm, .eps = o->ray_eps, .seed = o->seed};
    atomic_init(&hc.rays, 0);
    int st = sh__parallel_for(threads, nv, 64, harm_pass, &hc, o->progress, o->progress_ctx, "harmonic mean distances");
    long long lo = 0, hi = 0;
    for (int v = 0; v < nv && !st; v++) {
        if (c->harm[v] < rmin) { c->harm[v] = rmin; lo++; }
        else if (c->harm[v] > rmax) { c->harm[v] = rmax; hi++; }
    }
    c->info.harm_clamped_lo = (double)lo / nv;
    c->info.harm_clamped_hi = (double)hi / nv;
    c->info.rays = atomic_load(&hc.rays);
    return st;
}

/* [2] lazy placement: vertices in a seeded random order (Fisher-Yates);
 * one no record covers (1/w < a) becomes a record.  perm: nv ints. */
static void place_records(sh_cache *c, const sh_cache_opts *o, double a, int *perm)
{
    const sh_mesh *m = &c->s->mesh;
    const int nv = c->nv;
    for (int v = 0; v < nv; v++) perm[v] = v;
    uint64_t x = vertex_stream(o->seed, -1, 0x4444);
    for (int k = nv - 1; k > 0; k--) {
        const int j = (int)(sh__uniform(&x) * (k + 1));
        const int t = perm[k];
        perm[k] = perm[j];
        perm[j] = t;
    }
    for (int k = 0; k < nv; k++) {
        const int v = perm[k];
        int covered = 0;
        for (int r = c->nrec - 1; r >= 0 && !covered; r--) covered = inv_weight(m, c->harm, v, c->rec_vertex[r]) < a;
        if (!covered) c->rec_vertex[c->nrec++] = v;
    }
}

/* the records each vertex uses (1/w < a): two passes (count, fill), each
 * use with its 1/w, the rotation from the record's frame into the
 * vertex's and that rotation's β.  *total: the uses. */
static int record_uses(sh_cache *c, double a, long long *total)
{
    const sh_mesh *m = &c->s->mesh;
    const int nv = c->nv;
    int st = SH_OK;
    for (int v = 0; v < nv && !st; v++) {
        c->nb_start[v] = (int)*total;
        for (int r = 0; r < c->nrec; r++) *total += inv_weight(m, c->harm, v, c->rec_vertex[r]) < a;
        if (*total > INT32_MAX / 16) st = sh_error(SH_ENOMEM, "radiance cache: too many record uses (a = %g too large)", a);
    }
    if (st) return st;
    const long long n = *total;
    c->nb_start[nv] = (int)n;
    c->nb_rec = malloc(sizeof(int) * (size_t)(n ? n : 1));
    c->nb_iw = malloc(sizeof(double) * (size_t)(n ? n : 1));
    c->nb_R = malloc(sizeof(double) * 9 * (size_t)(n ? n : 1));
    c->nb_beta = malloc(sizeof(double) * (size_t)(n ? n : 1));
    if (!c->nb_rec || !c->nb_iw || !c->nb_R || !c->nb_beta) return sh_error(SH_ENOMEM, "out of memory");
    for (int v = 0; v < nv; v++) {
        int k = c->nb_start[v];
        const double *Mv = c->frames + 9 * (size_t)v;
        for (int r = 0; r < c->nrec; r++) {
            const int i = c->rec_vertex[r];
            const double iw = inv_weight(m, c->harm, v, i);
            if (!(iw < a)) continue;
            c->nb_rec[k] = r;
            c->nb_iw[k] = iw;
            /* the rotation from the record's frame into v's: M_vᵀ M_i */
            const double *Mi = c->frames + 9 * (size_t)i;
            double *R = c->nb_R + 9 * (size_t)k;
            for (int p = 0; p < 3; p++)
                for (int q = 0; q < 3; q++)
                    R[3 * p + q] = Mv[p] * Mi[q] + Mv[3 + p] * Mi[3 + q] + Mv[6 + p] * Mi[6 + q];
            c->nb_beta[k] = acos(fmax(-1.0, fmin(1.0, R[8])));
            k++;
        }
    }
    return SH_OK;
}

/* mean, max and percentiles of the uses' rotation angles β into c->info */
static int beta_statistics(sh_cache *c, long long total)
{
    double *b = malloc(sizeof(double) * (size_t)total);
    if (!b) return sh_error(SH_ENOMEM, "out of memory");
    memcpy(b, c->nb_beta, sizeof(double) * (size_t)total);
    qsort(b, (size_t)total, sizeof(double), cmp_double);
    double sum = 0;
    for (long long k = 0; k < total; k++) sum += b[k];
    c->info.beta_mean = sum / total;
    c->info.beta_max = b[total - 1];
    c->info.beta_p50 = b[(size_t)(0.50 * (total - 1))];
    c->info.beta_p90 = b[(size_t)(0.90 * (total - 1))];
    c->info.beta_p99 = b[(size_t)(0.99 * (total - 1))];
    free(b);
    return SH_OK;
}

/* the records themselves: the incident radiance (R, G, B) at each */
static int compute_records(sh_cache *c, const sh_env *env, const sh_cache_opts *o)
{
    if (!(c->L = malloc(sizeof(double) * 3 * (size_t)c->nrec * c->n2))) return sh_error(SH_ENOMEM, "out of memory");
    sh_transfer_stats rs;
    const int st = sh_incident_radiance(c->s, env, o, c->rec_vertex, c->nrec, c->L, &rs);
    c->info.seconds_records = rs.seconds;
    c->info.rays += rs.rays;
    return st;
}

int sh_cache_create(const sh_scene *s, const sh_env *env, const sh_cache_opts *o, sh_cache **out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_cache_create: no output");
    *out = NULL;
    int st = check_opts(s, env, o);
    if (st) return st;
    sh_cache *c = calloc(1, sizeof *c);
    if (!c) return sh_error(SH_ENOMEM, "out of memory");
    c->s = s;
    c->env = env;
    c->o = *o;
    c->order = o->order > 0 ? o->order : 6;
    c->n2 = c->order * c->order;
    const sh_mesh *m = &s->mesh;
    const int nv = c->nv = m->nvert;
    const double a = o->a > 0 ? o->a : 0.2;
    const double rmin = (o->rmin > 0 ? o->rmin : 0.01) * s->diag, rmax = (o->rmax > 0 ? o->rmax : 0.25) * s->diag;
    const int threads = o->threads > 0 ? o->threads : s->threads;
    c->info.threads = threads;
    c->info.nverts = nv;
    c->harm = malloc(sizeof(double) * nv);
    c->frames = malloc(sizeof(double) * 9 * (size_t)nv);
    c->rec_vertex = malloc(sizeof(int) * nv);
    int *perm = malloc(sizeof(int) * nv);
    c->nb_start = malloc(sizeof(int) * ((size_t)nv + 1));
    if (!c->harm || !c->frames || !c->rec_vertex || !perm || !c->nb_start) {
        free(perm);
        sh_cache_free(c);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    for (int v = 0; v < nv; v++) sh__tangent_frame(m->normal + 3 * v, c->frames + 9 * (size_t)v);
    const double t0 = sh__now();
    st = harmonic_radii(c, o, threads, rmin, rmax);
    if (!st) place_records(c, o, a, perm);
    free(perm);
    long long total = 0;
    if (!st) st = record_uses(c, a, &total);
    c->info.seconds_placement = sh__now() - t0;
    c->info.records = c->nrec;
    c->info.uses = total;
    c->info.mean_uses = (double)total / nv;
    if (!st && total > 0) st = beta_statistics(c, total);
    if (!st) st = compute_records(c, env, o);
    if (!st) st = setup_brdf(c);
    if (st) {
        sh_cache_free(c);
        return st;
    }
    *out = c;
    return SH_OK;
}

int sh_cache_info_get(const sh_cache *c, sh_cache_info *info)
{
    if (!c || !info) return sh_error(SH_EINVAL, "sh_cache_info_get: bad arguments");
    *info = c->info;
    return SH_OK;
}

const int *sh_cache_records(const sh_cache *c, int *n)
{
    if (n) *n = c ? c->nrec : 0;
    return c ? c->rec_vertex : NULL;
}

int sh_cache_uses(const sh_cache *c, int v, int max, int *rec_vertex, double *inv_weight)
{
    if (!c || v < 0 || v >= c->nv || max < 0 || (max > 0 && (!rec_vertex || !inv_weight))) return -1;
    const int b = c->nb_start[v], n = c->nb_start[v + 1] - b;
    for (int k = 0; k < n && k < max; k++) {
        rec_vertex[k] = c->rec_vertex[c->nb_rec[b + k]];
        inv_weight[k] = c->nb_iw[b + k];
    }
    return n;
}

double sh_cache_radius(const sh_cache *c, int v) { return c && v >= 0 && v < c->nv ? c->harm[v] : 0; }

/* ------------------------------------------------------------ rotation */

typedef struct {
    sh_rot_plan *plan, *fallback;
    double beta_lim;
    double *acc, *tmp; /* 3·n2 each */
} rotctx;

static void rotctx_free(rotctx *r)
{
    sh_rot_plan_free(r->plan);
    sh_rot_plan_free(r->fallback);
    free(r->acc);
    free(r->tmp);
    memset(r, 0, sizeof *r);
}

static int rotctx_init(rotctx *r, const sh_cache *c, const sh_cache_rot *rot)
{
    memset(r, 0, sizeof *r);
    r->acc = malloc(sizeof(double) * 3 * c->n2);
    r->tmp = malloc(sizeof(double) * 3 * c->n2);
    if (!r->acc || !r->tmp) {
        rotctx_free(r);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    if (rot->ignore) return SH_OK;
    int st = sh_rot_plan_create(c->order, rot->method, SH_PREC_DOUBLE, SH_CS, &r->plan);
    if (!st && !sh_rot_method_is_exact(rot->method) && rot->beta_lim > 0) {
        r->beta_lim = rot->beta_lim;
        st = sh_rot_plan_create(c->order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &r->fallback);
    }
    if (st) rotctx_free(r);
    return st;
}

/* The one place the cache rotates: a record's three channels from its
 * frame into the vertex's, out_c = R_sh(R) in_c, R = M_vᵀ M_i, through a
 * rotation plan — per record use: the matrix set into the plan
 * (sh_rot_plan_set_matrix), three applies.  Taylor methods hand rotations
 * with β > β_lim to zxzxz ([1]: "the approximated rotation for β < β_lim and
 * the more costly ZXZXZ decomposition otherwise").  The batch forms do not
 * pay here: apply_many over the three channels (with the transpositions to
 * its layout) measured 2-3x slower than three applies, and a vertex uses
 * about two records, too few rotations for rotate_many. */
static int cache_rotate(rotctx *r, int n2, const double R[9], double beta, const double *in, double *out, int *fellback)
{
    sh_rot_plan *p = r->plan;
    *fellback = 0;
    if (r->fallback && beta > r->beta_lim) {
        p = r->fallback;
        *fellback = 1;
    }
    int st = sh__rotate_frame(p, R, in, out);
    for (int ch = 1; ch < 3 && !st; ch++) st = sh_rot_plan_apply(p, in + (size_t)ch * n2, out + (size_t)ch * n2);
    return st;
}

/* [1] Eq. 1: Λ(v) = Σ_S w_i R_i Λ_i / Σ_S w_i into r->acc. */
static int interpolate(const sh_cache *c, const sh_cache_rot *rot, rotctx *r, int v, long long *nrot, long long *nfb)
{
    const int n2 = c->n2, b = c->nb_start[v], e = c->nb_start[v + 1];
    int exact = -1;
    for (int k = b; k < e; k++)
        if (c->nb_iw[k] == 0) exact = k; /* w = ∞: that record alone (the limit) */
    memset(r->acc, 0, sizeof(double) * 3 * n2);
    double wsum = 0;
    for (int k = exact >= 0 ? exact : b; k < (exact >= 0 ? exact + 1 : e); k++) {
        const int rec = c->nb_rec[k];
        const double *src = c->L + (size_t)rec * 3 * n2;
        if (!rot->ignore && c->rec_vertex[rec] != v) {
            int fb;
            const int st = cache_rotate(r, n2, c->nb_R + 9 * (size_t)k, c->nb_beta[k], src, r->tmp, &fb);
            if (st) return st;
            src = r->tmp;
            (*nrot)++;
            *nfb += fb;
        }
        const double w = exact >= 0 ? 1.0 : 1.0 / c->nb_iw[k];
        for (int i = 0; i < 3 * n2; i++) r->acc[i] += w * src[i];
        wsum += w;
    }
    if (!(wsum > 0)) return sh_error(SH_ENUM, "radiance cache: vertex %d has no record", v);
    for (int i = 0; i < 3 * n2; i++) r->acc[i] /= wsum;
    return SH_OK;
}

static int check_rot(const sh_cache *c, const sh_cache_rot *rot)
{
    if (!c || !rot) return sh_error(SH_EINVAL, "radiance cache: bad arguments");
    if (rot->ignore) return SH_OK;
    if ((int)rot->method < 0 || rot->method >= SH_ROT_NMETHODS || !sh_rot_method_max_order(rot->method))
        return sh_error(SH_EINVAL, "radiance cache: unknown rotation method");
    if (rot->method == SH_ROT_Z) return sh_error(SH_EINVAL, "radiance cache: the z method rotates about z only");
    if (c->order > sh_rot_method_max_order(rot->method))
        return sh_error(SH_EINVAL, "radiance cache: %s accepts orders up to %d", sh_rot_method_name(rot->method),
                        sh_rot_method_max_order(rot->method));
    if (!(rot->beta_lim <= M_PI * 2) || isnan(rot->beta_lim)) return sh_error(SH_EINVAL, "radiance cache: bad beta_lim");
    return SH_OK;
}

int sh_cache_incident(sh_cache *c, const sh_cache_rot *rot, int v, double *L)
{
    int st = check_rot(c, rot);
    if (st) return st;
    if (v < 0 || v >= c->nv || !L) return sh_error(SH_EINVAL, "sh_cache_incident: vertex %d out of range", v);
    rotctx r;
    if ((st = rotctx_init(&r, c, rot))) return st;
    long long nr = 0, nf = 0;
    st = interpolate(c, rot, &r, v, &nr, &nf);
    if (!st) memcpy(L, r.acc, sizeof(double) * 3 * c->n2);
    rotctx_free(&r);
    return st;
}

static void shade_point(const sh_cache *c, int v, const double *Lam, double *B)
{
    const int n2 = c->n2;
    const double *g = c->g + (c->g_per_vertex ? (size_t)v * n2 : 0);
    for (int ch = 0; ch < 3; ch++) {
        double b = 0;
        for (int i = 0; i < n2; i++) b += g[i] * Lam[(size_t)ch * n2 + i];
        B[ch] = b;
    }
}

typedef struct {
    const sh_cache *c;
    const sh_cache_rot *rot;
    rotctx *r; /* per thread */
    double *B;
    atomic_llong nrot, nfb;
} sctx;

static int shade_pass(void *vc, int thread, int begin, int end)
{
    sctx *x = vc;
    rotctx *r = &x->r[thread];
    long long nr = 0, nf = 0;
    for (int v = begin; v < end; v++) {
        const int st = interpolate(x->c, x->rot, r, v, &nr, &nf);
        if (st) return st;
        shade_point(x->c, v, r->acc, x->B + 3 * (size_t)v);
    }
    atomic_fetch_add(&x->nrot, nr);
    atomic_fetch_add(&x->nfb, nf);
    return SH_OK;
}

int sh_cache_shade(sh_cache *c, const sh_cache_rot *rot, int threads, double *B, sh_cache_timing *t)
{
    int st = check_rot(c, rot);
    if (st) return st;
    if (!B || threads < 0 || threads > 256) return sh_error(SH_EINVAL, "sh_cache_shade: bad arguments");
    if (threads == 0) threads = c->s->threads;
    sctx x = {.c = c, .rot = rot, .B = B};
    atomic_init(&x.nrot, 0);
    atomic_init(&x.nfb, 0);
    if (!(x.r = calloc((size_t)threads, sizeof *x.r))) return sh_error(SH_ENOMEM, "out of memory");
    for (int k = 0; k < threads && !st; k++) st = rotctx_init(&x.r[k], c, rot);
    double sec = 0, cpu = 0;
    if (!st) {
        struct timespec c0, c1;
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
        const double t0 = sh__now();
        st = sh__parallel_for(threads, c->nv, 64, shade_pass, &x, NULL, NULL, NULL);
        sec = sh__now() - t0;
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
        cpu = (double)(c1.tv_sec - c0.tv_sec) + 1e-9 * (double)(c1.tv_nsec - c0.tv_nsec);
    }
    for (int k = 0; k < threads; k++) rotctx_free(&x.r[k]);
    free(x.r);
    if (t) {
        t->seconds = sec;
        t->cpu_seconds = threads == 1 ? cpu : 0;
        t->rotations = atomic_load(&x.nrot);
        t->fallbacks = atomic_load(&x.nfb);
    }
    return st;
}

int sh_cache_bench(sh_cache *c, const sh_cache_rot *rots, int n, int rounds, double min_cpu_seconds, double *sec)
{
    if (!c || !rots || !sec || n < 1 || rounds < 1 || !(min_cpu_seconds >= 0 && min_cpu_seconds < 100))
        return sh_error(SH_EINVAL, "sh_cache_bench: bad arguments");
    double *B = malloc(sizeof(double) * 3 * (size_t)c->nv);
    if (!B) return sh_error(SH_ENOMEM, "out of memory");
    int st = SH_OK;
    for (int r = 0; r < rounds && !st; r++)
        for (int j = 0; j < n && !st; j++) {
            const int k = (j + r) % n;
            double cpu = 0;
            int loops = 0;
            do {
                sh_cache_timing t;
                st = sh_cache_shade(c, &rots[k], 1, B, &t);
                cpu += t.cpu_seconds;
                loops++;
            } while (!st && cpu < min_cpu_seconds && loops < 100000);
            sec[(size_t)r * n + k] = cpu / loops;
        }
    free(B);
    return st;
}

int sh_cache_shade_direct(sh_cache *c, unsigned long seed, int threads, double *B, sh_transfer_stats *stats)
{
    sh_transfer_stats st0;
    if (!stats) stats = &st0;
    memset(stats, 0, sizeof *stats);
    if (!c || !B || threads < 0 || threads > 256) return sh_error(SH_EINVAL, "sh_cache_shade_direct: bad arguments");
    sh_cache_opts o = c->o;
    if (threads) o.threads = threads;
    o.seed = seed;
    const int n2 = c->n2, chunk = c->nv < DIRECT_CHUNK ? c->nv : DIRECT_CHUNK;
    double *L = malloc(sizeof(double) * 3 * (size_t)chunk * n2);
    int *verts = malloc(sizeof(int) * (size_t)chunk);
    if (!L || !verts) {
        free(L);
        free(verts);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    /* the streams depend on (seed, vertex) only: chunks change nothing */
    ictx ic;
    const double t0 = sh__now();
    int st = ictx_init(&ic, c->s, c->env, &o);
    o.progress = NULL;
    for (int b = 0; b < c->nv && !st; b += chunk) {
        const int n = b + chunk <= c->nv ? chunk : c->nv - b;
        for (int k = 0; k < n; k++) verts[k] = b + k;
        st = incident_run(&ic, &o, verts, n, L, "incident radiance");
        for (int k = 0; k < n && !st; k++) shade_point(c, b + k, L + (size_t)k * 3 * n2, B + 3 * (size_t)(b + k));
        if (c->o.progress && !st) c->o.progress(c->o.progress_ctx, b + n, c->nv, "vertices computed directly");
    }
    stats->seconds = sh__now() - t0;
    stats->rays = atomic_load(&ic.rays);
    stats->rays_per_s = stats->seconds > 0 ? stats->rays / stats->seconds : 0;
    stats->threads = o.threads > 0 ? o.threads : c->s->threads;
    ictx_free(&ic);
    free(L);
    free(verts);
    return st;
}
