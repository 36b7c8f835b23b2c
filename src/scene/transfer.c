/* transfer.c — Green's diffuse transfer vectors per vertex: unshadowed
 * (closed form or rays), shadowed (ray-cast visibility) and interreflected
 * (bounces of interpolated transfer).
 *
 * References:
 *  [1] Green 2003, "Spherical Harmonic Lighting: The Gritty Details",
 *      "Diffuse Unshadowed Transfer", "Shadowed Diffuse Transfer",
 *      "Diffuse Interreflected Transfer" (steps a-d).
 *  [2] Malley's method: a uniform point of the unit disc lifted to the
 *      hemisphere has density cosθ/π (Pharr, Jakob & Humphreys, PBRT 13.6.3).
 *  [3] Ramamoorthi & Hanrahan 2001: the clamped cosine's SH coefficients
 *      (here from sh_lobe_zonal) and the addition theorem. */
#include "scene_internal.h"

#include <stdlib.h>
#include <string.h>

const char *sh_transfer_kind_name(sh_transfer_kind k)
{
    switch (k) {
    case SH_TRANSFER_UNSHADOWED: return "unshadowed";
    case SH_TRANSFER_SHADOWED: return "shadowed";
    case SH_TRANSFER_INTERREFLECTED: return "interreflected";
    }
    return "?";
}

int sh_transfer_kind_parse(const char *s, sh_transfer_kind *out)
{
    static const sh_transfer_kind k[] = {SH_TRANSFER_UNSHADOWED, SH_TRANSFER_SHADOWED, SH_TRANSFER_INTERREFLECTED};
    for (int i = 0; i < 3; i++)
        if (s && !strcmp(s, sh_transfer_kind_name(k[i]))) {
            *out = k[i];
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown transfer '%s' (expected unshadowed, shadowed or interreflected)", s ? s : "");
}

int sh_transfer_unshadowed(int order, sh_convention conv, double albedo, const double n[3], double *t)
{
    int st = sh_check_order(order);
    if (st) return st;
    double *z = malloc(sizeof(double) * (size_t)order);
    if (!z) return sh_error(SH_ENOMEM, "out of memory");
    /* [3]: max(0, n·s) = Σ_l z_l √(4π/(2l+1)) Σ_m y_lm(n) y_lm(s), so
     * t_lm = (ρ/π) √(4π/(2l+1)) z_l y_lm(n) */
    if ((st = sh_lobe_zonal(1.0, order, z)) || (st = sh_eval_dir(order, conv, n, t))) {
        free(z);
        return st;
    }
    for (int l = 0; l < order; l++) {
        const double f = albedo / M_PI * sqrt(4 * M_PI / (2 * l + 1)) * z[l];
        for (int m = -l; m <= l; m++) t[sh_index(l, m)] *= f;
    }
    free(z);
    return SH_OK;
}

/* --------------------------------------------------------------- passes */

typedef struct {
    int tri;
    float u, v;
} hitrec;

typedef struct {
    const sh_scene *s;
    const sh_transfer_opts *o;
    int n2, N;              /* coefficients, rays per vertex */
    const double *dir;      /* N local directions */
    const double *Y;        /* N·n2: y_i(local direction k) */
    double *T;              /* output */
    sh_rot_plan **plans;    /* one per thread */
    double **acc;           /* scratch per thread: 2·n2 */
    hitrec **hits;          /* interreflected: per vertex */
    int *nhits;
    atomic_llong escaped, backface;
    /* bounces */
    const double *prev;
    double *next;
    double rho, eps;
} tctx;

static int first_pass(void *vc, int thread, int begin, int end)
{
    tctx *c = vc;
    const sh_scene *s = c->s;
    const sh_mesh *m = &s->mesh;
    const int n2 = c->n2, N = c->N, kind = c->o->kind;
    double *acc = c->acc[thread], *loc = acc + n2;
    hitrec *buf = NULL;
    if (kind == SH_TRANSFER_INTERREFLECTED && !(buf = malloc(sizeof(hitrec) * (size_t)N)))
        return sh_error(SH_ENOMEM, "out of memory");
    long long esc = 0, back = 0;
    for (int iv = begin; iv < end; iv++) {
        const int v = c->o->verts ? c->o->verts[iv] : iv;
        const double *n = m->normal + 3 * v;
        double M[9], org[3];
        sh__tangent_frame(n, M);
        sh_scene_ray_origin(s, v, c->eps, org);
        memset(acc, 0, sizeof(double) * n2);
        int nh = 0;
        for (int k = 0; k < N; k++) {
            const double *dl = c->dir + 3 * k;
            const double d[3] = {M[0] * dl[0] + M[1] * dl[1] + M[2] * dl[2], M[3] * dl[0] + M[4] * dl[1] + M[5] * dl[2],
                                 M[6] * dl[0] + M[7] * dl[1] + M[8] * dl[2]};
            int visible;
            if (kind == SH_TRANSFER_UNSHADOWED) visible = 1;
            else if (kind == SH_TRANSFER_SHADOWED) visible = !sh__occluded(s, org, d, INFINITY);
            else {
                double t, u, w;
                int front;
                const int h = sh__intersect(s, org, d, INFINITY, &t, &u, &w, &front);
                visible = !h;
                if (h && front) buf[nh++] = (hitrec){h - 1, (float)u, (float)w};
                if (h && !front) back++;
            }
            if (!visible) continue;
            esc++;
            /* [1] shadowed transfer: Σ V(s_k) y_i(s_k); with the density
             * cosθ/π of [2] the cosine and π cancel: t = (ρ/N) Σ V y */
            const double *y = c->Y + (size_t)k * n2;
            for (int i = 0; i < n2; i++) acc[i] += y[i];
        }
        for (int i = 0; i < n2; i++) loc[i] = c->rho / N * acc[i];
        int st = sh__rotate_frame(c->plans[thread], M, loc, c->T + (size_t)iv * n2);
        if (st) { free(buf); return st; }
        if (buf) {
            c->nhits[v] = nh;
            if (nh) {
                c->hits[v] = malloc(sizeof(hitrec) * (size_t)nh);
                if (!c->hits[v]) { free(buf); return sh_error(SH_ENOMEM, "out of memory storing hits"); }
                memcpy(c->hits[v], buf, sizeof(hitrec) * (size_t)nh);
            }
        }
    }
    free(buf);
    atomic_fetch_add(&c->escaped, esc);
    atomic_fetch_add(&c->backface, back);
    return kind == SH_TRANSFER_UNSHADOWED ? SH_OK : sh__embree_status(s, "casting transfer rays");
}

/* [1] step (d): bounce k+1 at x = ρ/N · Σ over front hits of bounce k
 * interpolated barycentrically at the hit, (1−u−v) t_0 + u t_1 + v t_2 */
static int bounce_pass(void *vc, int thread, int begin, int end)
{
    tctx *c = vc;
    const sh_mesh *m = &c->s->mesh;
    const int n2 = c->n2;
    for (int v = begin; v < end; v++) {
        double *out = c->next + (size_t)v * n2;
        memset(out, 0, sizeof(double) * n2);
        for (int h = 0; h < c->nhits[v]; h++) {
            const hitrec *r = &c->hits[v][h];
            const int *tc = m->tri + 3 * r->tri;
            const double w0 = 1.0 - r->u - r->v, w1 = r->u, w2 = r->v;
            const double *a = c->prev + (size_t)tc[0] * n2, *b = c->prev + (size_t)tc[1] * n2,
                         *d = c->prev + (size_t)tc[2] * n2;
            for (int i = 0; i < n2; i++) out[i] += w0 * a[i] + w1 * b[i] + w2 * d[i];
        }
        for (int i = 0; i < n2; i++) out[i] *= c->rho / c->N;
    }
    return SH_OK;
}

static double sum_norms(const double *T, int nv, int n2)
{
    double s = 0;
    for (int v = 0; v < nv; v++) {
        double q = 0;
        for (int i = 0; i < n2; i++) q += T[(size_t)v * n2 + i] * T[(size_t)v * n2 + i];
        s += sqrt(q);
    }
    return s;
}

/* The options sh_transfer reads, checked (o->verts against the mesh). */
static int check_transfer_opts(const sh_scene *s, const sh_transfer_opts *o)
{
    int st = sh_check_order(o->order);
    if (st) return st;
    if (o->kind != SH_TRANSFER_UNSHADOWED && o->kind != SH_TRANSFER_SHADOWED && o->kind != SH_TRANSFER_INTERREFLECTED)
        return sh_error(SH_EINVAL, "sh_transfer: unknown kind %d", (int)o->kind);
    const double rho = o->albedo > 0 ? o->albedo : 1.0;
    if (!(rho <= 1) || !isfinite(o->albedo) || o->albedo < 0) return sh_error(SH_EINVAL, "albedo %g not in (0, 1]", o->albedo);
    if (o->rays < 0 || o->rays > 1L << 24) return sh_error(SH_EINVAL, "rays per vertex %ld not in 1..2^24", o->rays);
    if (o->max_bounces < 0 || o->max_bounces > SH_TRANSFER_MAX_BOUNCES)
        return sh_error(SH_EINVAL, "bounces %d not in 0..%d", o->max_bounces, SH_TRANSFER_MAX_BOUNCES);
    if (!(o->bounce_tol >= 0) || !(o->ray_eps >= 0 && o->ray_eps < 0.1))
        return sh_error(SH_EINVAL, "bounce tolerance must be >= 0 and ray offset in [0, 0.1)");
    if (o->threads < 0 || o->threads > 256) return sh_error(SH_EINVAL, "threads %d not in 0..256", o->threads);
    const sh_mesh *m = &s->mesh;
    if (o->verts && o->kind == SH_TRANSFER_INTERREFLECTED)
        return sh_error(SH_EINVAL, "sh_transfer: interreflection needs every vertex (no subset)");
    if (o->verts && (o->nverts < 0 || o->nverts > m->nvert)) return sh_error(SH_EINVAL, "sh_transfer: bad subset size");
    for (int k = 0; o->verts && k < o->nverts; k++)
        if (o->verts[k] < 0 || o->verts[k] >= m->nvert) return sh_error(SH_EINVAL, "sh_transfer: vertex %d out of range", o->verts[k]);
    return SH_OK;
}

/* What the passes share, made: the sq×sq cosine-distributed local
 * directions (dir) and their basis values (Y), a rotation plan and
 * scratch per thread, and for interreflection the per-vertex hit lists. */
static int prepare_rays(tctx *c, int sq, int threads, int nv, double *dir, double *Y)
{
    const sh_transfer_opts *o = c->o;
    const int N = c->N, n2 = c->n2;
    int st = SH_OK;
    sh__cosine_samples(sq, o->seed, dir);
    for (int k = 0; k < N && !st; k++) st = sh_eval_dir(o->order, o->conv, dir + 3 * k, Y + (size_t)k * n2);
    if (st) return st;
    c->dir = dir;
    c->Y = Y;
    for (int t = 0; t < threads && !st; t++) {
        if (!(c->acc[t] = malloc(sizeof(double) * 2 * n2))) st = sh_error(SH_ENOMEM, "out of memory");
        else st = sh_rot_plan_create(o->order, SH_ROT_IVANIC, SH_PREC_DOUBLE, o->conv, &c->plans[t]);
    }
    if (st) return st;
    if (o->kind == SH_TRANSFER_INTERREFLECTED) {
        c->hits = calloc((size_t)nv, sizeof *c->hits);
        c->nhits = calloc((size_t)nv, sizeof *c->nhits);
        if (!c->hits || !c->nhits) return sh_error(SH_ENOMEM, "out of memory");
    }
    return SH_OK;
}

/* [1] interreflected: bounces added to T (the first pass's result) until
 * one adds at most the tolerance of the total (or the bounce limit). */
static int interreflect(tctx *c, int nv, int threads, double *T, sh_transfer_stats *stats)
{
    const sh_transfer_opts *o = c->o;
    const int n2 = c->n2;
    const int maxb = o->max_bounces > 0 ? o->max_bounces : 100;
    const double tol = o->bounce_tol > 0 ? o->bounce_tol : 1e-6;
    double *prev = malloc(sizeof(double) * (size_t)nv * n2), *next = malloc(sizeof(double) * (size_t)nv * n2);
    if (!prev || !next) { free(prev); free(next); return sh_error(SH_ENOMEM, "out of memory"); }
    int st = SH_OK;
    memcpy(prev, T, sizeof(double) * (size_t)nv * n2);
    for (int b = 1; b <= maxb; b++) {
        c->prev = prev;
        c->next = next;
        if ((st = sh__parallel_for(threads, nv, 64, bounce_pass, c, NULL, NULL, NULL))) break;
        for (size_t i = 0; i < (size_t)nv * n2; i++) T[i] += next[i];
        const double tot = sum_norms(T, nv, n2), add = sum_norms(next, nv, n2);
        stats->bounces = b;
        stats->last_bounce_rel = tot > 0 ? add / tot : 0;
        if (o->progress) o->progress(o->progress_ctx, b, maxb, "bounces");
        if (stats->last_bounce_rel <= tol) { stats->converged = 1; break; }
        double *x = prev; prev = next; next = x;
    }
    free(prev);
    free(next);
    return st;
}

int sh_transfer(const sh_scene *s, const sh_transfer_opts *o, double *T, sh_transfer_stats *stats)
{
    sh_transfer_stats st0;
    if (!stats) stats = &st0;
    memset(stats, 0, sizeof *stats);
    if (!s || !o || !T) return sh_error(SH_EINVAL, "sh_transfer: bad arguments");
    int st = check_transfer_opts(s, o);
    if (st) return st;
    const double rho = o->albedo > 0 ? o->albedo : 1.0;
    const sh_mesh *m = &s->mesh;
    const int n2 = o->order * o->order, nv = o->verts ? o->nverts : m->nvert;
    const int threads = o->threads > 0 ? o->threads : s->threads;
    stats->threads = threads;
    if (o->kind == SH_TRANSFER_UNSHADOWED && o->closed_form) {
        for (int v = 0; v < nv; v++)
            if ((st = sh_transfer_unshadowed(o->order, o->conv, rho, m->normal + 3 * (o->verts ? o->verts[v] : v),
                                             T + (size_t)v * n2)))
                return st;
        return SH_OK;
    }
    int sq = (int)floor(sqrt((double)(o->rays > 0 ? o->rays : 1024)) + 0.5);
    if (sq < 1) sq = 1;
    const int N = sq * sq;
    stats->rays_per_vertex = N;
    tctx c = {.s = s, .o = o, .n2 = n2, .N = N, .T = T, .rho = rho, .eps = o->ray_eps};
    atomic_init(&c.escaped, 0);
    atomic_init(&c.backface, 0);
    double *dir = malloc(sizeof(double) * 3 * (size_t)N);
    double *Y = malloc(sizeof(double) * (size_t)N * n2);
    c.plans = calloc((size_t)threads, sizeof *c.plans);
    c.acc = calloc((size_t)threads, sizeof *c.acc);
    if (!dir || !Y || !c.plans || !c.acc) { st = sh_error(SH_ENOMEM, "out of memory"); goto done; }
    if ((st = prepare_rays(&c, sq, threads, nv, dir, Y))) goto done;
    /* [1] the direct transfer at every vertex (and the hits for the bounces) */
    double t0 = sh__now();
    st = sh__parallel_for(threads, nv, 16, first_pass, &c, o->progress, o->progress_ctx, "vertices");
    stats->seconds = sh__now() - t0;
    if (st) goto done;
    stats->escaped = atomic_load(&c.escaped);
    stats->backface = atomic_load(&c.backface);
    if (o->kind != SH_TRANSFER_UNSHADOWED) stats->rays = (long long)N * nv;
    stats->rays_per_s = stats->seconds > 0 ? (double)stats->rays / stats->seconds : 0;
    if (o->kind == SH_TRANSFER_INTERREFLECTED) st = interreflect(&c, nv, threads, T, stats);
    for (size_t i = 0; !st && i < (size_t)nv * n2; i++)
        if (!isfinite(T[i])) st = sh_error(SH_ENUM, "sh_transfer: vertex %zu has a non-finite coefficient", i / n2);
done:
    if (c.plans) for (int t = 0; t < threads; t++) sh_rot_plan_free(c.plans[t]);
    if (c.acc) for (int t = 0; t < threads; t++) free(c.acc[t]);
    if (c.hits) for (int v = 0; v < nv; v++) free(c.hits[v]);
    free(c.hits);
    free(c.nhits);
    free(c.plans);
    free(c.acc);
    free(dir);
    free(Y);
    return st;
}
