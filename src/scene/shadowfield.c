/* shadowfield.c — shadow fields of a sphere occluder, sampled at one
 * distance and scaled to others (scene.h).
 *
 * References:
 *  [1] Wang, Lin, Guo, Shum 2006, "Spherical harmonics scaling", Sec. 2.2
 *      (M sampled at k, interpolated linearly in k) and Sec. 3.1 (object
 *      occlusion fields sampled at one radial distance and scaled to the
 *      others with the cone family).
 *  [2] Zhou, Hu, Lin, Guo, Shum 2005, "Precomputed shadow fields for
 *      dynamic scenes": the visibility of an occluder at a receiver is
 *      looked up in its field and combined with the lighting and the BRDF
 *      by SH products truncated to the working order.
 *  [3] The occlusion of a sphere of radius R seen from distance d is the
 *      cap of half-angle asin(R/d) about the direction to the centre; its
 *      zonal coefficients are sh_cap_zonal's, placed on any direction u by
 *      the addition theorem, O_lm = √(4π/(2l+1)) o_l y_lm(u). */
#include "scene_internal.h"

#include <stdlib.h>
#include <string.h>

const char *sh_sf_scaling_name(sh_sf_scaling s)
{
    switch (s) {
    case SH_SF_EXACT: return "exact";
    case SH_SF_CONE: return "cone";
    case SH_SF_SPHERE: return "sphere";
    }
    return "?";
}

int sh_sf_scaling_parse(const char *s, sh_sf_scaling *out)
{
    static const sh_sf_scaling all[] = {SH_SF_EXACT, SH_SF_CONE, SH_SF_SPHERE};
    for (int k = 0; k < 3; k++)
        if (s && !strcmp(s, sh_sf_scaling_name(all[k]))) {
            *out = all[k];
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown field scaling '%s' (exact, cone, sphere)", s ? s : "");
}

static int check_opts(const sh_sf_opts *o, double radius)
{
    if (!o) return sh_error(SH_EINVAL, "shadow field: no options");
    int st = sh_check_order(o->order);
    if (st) return st;
    if (o->order > SH_SF_MAX_ORDER) return sh_error(SH_EINVAL, "shadow field: order %d > %d", o->order, SH_SF_MAX_ORDER);
    if (o->scaling != SH_SF_EXACT && o->scaling != SH_SF_CONE && o->scaling != SH_SF_SPHERE)
        return sh_error(SH_EINVAL, "shadow field: unknown scaling");
    if (!(radius > 0) || !isfinite(radius)) return sh_error(SH_EINVAL, "shadow field: radius %g must be > 0", radius);
    if (!(o->d0 > radius) || !isfinite(o->d0))
        return sh_error(SH_EINVAL, "shadow field: the sampled distance %g must exceed the radius %g", o->d0, radius);
    if (!(o->cone_angle >= 0 && o->cone_angle < M_PI)) return sh_error(SH_EINVAL, "shadow field: cone angle must be in (0, π)");
    if (o->samples < 0 || o->samples == 1 || o->samples > 10000)
        return sh_error(SH_EINVAL, "shadow field: %d k samples (0, or 2..10000)", o->samples);
    if (o->samples && o->scaling == SH_SF_EXACT) return sh_error(SH_EINVAL, "shadow field: the exact field has no k table");
    if (!(o->kmin >= 0 && o->kmax >= 0) || (o->kmin > 0) != (o->kmax > 0) || (o->kmin > 0 && !(o->kmin < o->kmax)))
        return sh_error(SH_EINVAL, "shadow field: need 0 < kmin < kmax (or both 0)");
    if (!(o->albedo >= 0 && o->albedo <= 1)) return sh_error(SH_EINVAL, "albedo %g not in (0, 1]", o->albedo);
    return SH_OK;
}

/* The sphere's own τ: the cap at d (half-angle w_d) onto the cap at d0
 * (w0) and the rest of the sphere onto the rest, both linearly:
 *   τ(θ) = θ w0/w_d (θ ≤ w_d),  w0 + (θ − w_d)(π − w0)/(π − w_d) (beyond). */
typedef struct { double w0, wd; } sphere_tau;

static void sphere_tau_fn(double theta, void *ctx, double *tau, double *dtau)
{
    const sphere_tau *q = ctx;
    if (theta <= q->wd) {
        *dtau = q->w0 / q->wd;
        *tau = theta * *dtau;
    } else {
        *dtau = (M_PI - q->w0) / (M_PI - q->wd);
        *tau = q->w0 + (theta - q->wd) * *dtau;
    }
}

/* The m = 0 block of the scaling matrix at k = d/d0 (N×N, row-major in
 * (l, l')), M_ll' = 2π I_0(l, l') ([1] Eq. 6 with the φ integral done):
 * the cone family with k, or the sphere's τ above (plain ψ = sinθ: the
 * field is a visibility, F_d(θ) = F_r(τ(θ))). */
static int zonal_block(const sh_sf_opts *o, double radius, double k, double *I, double *work, double *B)
{
    const int N = o->order;
    int st;
    if (o->scaling == SH_SF_CONE) {
        sh_scaling s = {0};
        s.family = SH_SCALE_CONE;
        s.k = k;
        s.cone_angle = o->cone_angle;
        if ((st = sh_scaling_check(&s))) return st;
        double br[SH_SCALE_MAX_BREAKS];
        const int nb = sh_scale_breaks(&s, br);
        st = sh_scale_integrals_tau(N, sh_scale_family_tau, &s, 0, br, nb, I, work);
    } else {
        sphere_tau q = {asin(radius / o->d0), asin(fmin(1.0, radius / (k * o->d0)))};
        st = sh_scale_integrals_tau(N, sphere_tau_fn, &q, 0, &q.wd, 1, I, work);
    }
    if (st) return st;
    /* the m = 0 block comes first */
    for (int e = 0; e < N * N; e++) B[e] = 2 * M_PI * I[e];
    return SH_OK;
}

int sh_sf_field(const sh_sf_opts *o, double radius, double d, double *O)
{
    int st = check_opts(o, radius);
    if (st) return st;
    if (!O || !(d > radius) || !isfinite(d)) return sh_error(SH_EINVAL, "shadow field: distance %g must exceed the radius", d);
    const int N = o->order, n2 = N * N;
    double *z = malloc(sizeof(double) * N), *z0 = malloc(sizeof(double) * N), *B = malloc(sizeof(double) * N * N);
    double *Mf = malloc(sizeof(double) * sh_scale_integrals_n(N)), *work = malloc(sizeof(double) * sh_scale_work_n(N));
    if (!z || !z0 || !B || !Mf || !work) st = sh_error(SH_ENOMEM, "out of memory");
    if (!st && o->scaling == SH_SF_EXACT) st = sh_cap_zonal(asin(radius / d), N, z); /* [3] */
    else if (!st) {
        /* [1] the field sampled at d0, scaled: o = M(k) o_0 (m = 0 block) */
        if (!(st = sh_cap_zonal(asin(radius / o->d0), N, z0)) && !(st = zonal_block(o, radius, d / o->d0, Mf, work, B)))
            for (int l = 0; l < N; l++) {
                double a = 0;
                for (int lp = 0; lp < N; lp++) a += B[l * N + lp] * z0[lp];
                z[l] = a;
            }
    }
    if (!st) {
        memset(O, 0, sizeof(double) * n2);
        for (int l = 0; l < N; l++) O[l * (l + 1)] = z[l];
    }
    free(z); free(z0); free(B); free(Mf); free(work);
    return st;
}

/* The real Gaunt coefficients G(i, j, k) with i, j, k < n², as a list. */
typedef struct {
    int n;
    int *i, *j, *k;
    double *g;
} gaunt_list;

static void gaunt_free(gaunt_list *G)
{
    free(G->i); free(G->j); free(G->k); free(G->g);
}

static int gaunt_build(int order, gaunt_list *G)
{
    memset(G, 0, sizeof *G);
    const int n2 = order * order, lmax = order - 1;
    const size_t rown = sh_gaunt_real_row_n(lmax, lmax), workn = sh_gaunt_real_row_work_n(lmax, lmax);
    int *kk = malloc(sizeof(int) * rown);
    double *gg = malloc(sizeof(double) * rown), *work = malloc(sizeof(double) * workn);
    size_t cap = 4096;
    G->i = malloc(sizeof(int) * cap); G->j = malloc(sizeof(int) * cap); G->k = malloc(sizeof(int) * cap);
    G->g = malloc(sizeof(double) * cap);
    int st = (!kk || !gg || !work || !G->i || !G->j || !G->k || !G->g) ? sh_error(SH_ENOMEM, "out of memory") : SH_OK;
    for (int i = 0; i < n2 && !st; i++)
        for (int j = 0; j < n2 && !st; j++) {
            int cnt;
            if ((st = sh_gaunt_real_row(SH_CS, i, j, lmax, kk, gg, &cnt, work))) break;
            for (int q = 0; q < cnt; q++) {
                if (kk[q] >= n2 || gg[q] == 0) continue;
                if ((size_t)G->n == cap) {
                    cap *= 2;
                    int *a = realloc(G->i, sizeof(int) * cap), *b = realloc(G->j, sizeof(int) * cap),
                        *c = realloc(G->k, sizeof(int) * cap);
                    double *d = realloc(G->g, sizeof(double) * cap);
                    if (a) G->i = a;
                    if (b) G->j = b;
                    if (c) G->k = c;
                    if (d) G->g = d;
                    if (!a || !b || !c || !d) { st = sh_error(SH_ENOMEM, "out of memory"); break; }
                }
                G->i[G->n] = i;
                G->j[G->n] = j;
                G->k[G->n] = kk[q];
                G->g[G->n] = gg[q];
                G->n++;
            }
        }
    free(kk); free(gg); free(work);
    if (st) gaunt_free(G);
    return st;
}

int sh_shadow_field_transfer(const sh_sf_opts *o, const double centre[3], double radius, int n, const double *pos,
                             const double *normal, double *T, sh_sf_stats *stats)
{
    sh_sf_stats s0;
    if (!stats) stats = &s0;
    memset(stats, 0, sizeof *stats);
    int st = check_opts(o, radius);
    if (st) return st;
    if (!centre || !pos || !normal || !T || n < 0) return sh_error(SH_EINVAL, "shadow field: bad arguments");
    const int N = o->order, n2 = N * N;
    const double rho = o->albedo > 0 ? o->albedo : 1.0;
    double kmin = INFINITY, kmax = 0;
    for (int p = 0; p < n; p++) {
        const double *x = pos + 3 * p;
        const double d = sqrt((centre[0] - x[0]) * (centre[0] - x[0]) + (centre[1] - x[1]) * (centre[1] - x[1]) +
                              (centre[2] - x[2]) * (centre[2] - x[2]));
        if (!(d > radius) || !isfinite(d)) return sh_error(SH_EINVAL, "shadow field: receiver %d lies inside the occluder", p);
        kmin = fmin(kmin, d / o->d0);
        kmax = fmax(kmax, d / o->d0);
    }
    stats->kmin = kmin;
    stats->kmax = kmax;
    if (o->samples && o->kmin > 0) {
        kmin = o->kmin;
        kmax = o->kmax;
    }
    if (o->samples && !(kmax > kmin)) kmax = kmin * (1 + 1e-9) + 1e-12; /* one distance: a degenerate range */
    const double t0 = sh__now();
    double *z0 = malloc(sizeof(double) * N), *zl = malloc(sizeof(double) * N), *B = malloc(sizeof(double) * N * N);
    double *Mf = malloc(sizeof(double) * sh_scale_integrals_n(N)), *work = malloc(sizeof(double) * sh_scale_work_n(N));
    double *tab = o->samples ? malloc(sizeof(double) * (size_t)o->samples * N * N) : NULL, *ks = o->samples ? malloc(sizeof(double) * o->samples) : NULL;
    double *V = malloc(sizeof(double) * n2), *c = malloc(sizeof(double) * n2), *y = malloc(sizeof(double) * n2);
    gaunt_list G = {0};
    if (!z0 || !zl || !B || !Mf || !work || (o->samples && (!tab || !ks)) || !V || !c || !y) st = sh_error(SH_ENOMEM, "out of memory");
    if (!st) st = sh_cap_zonal(asin(radius / o->d0), N, z0);
    /* [1] Sec. 2.2: M tabulated at `samples` k, geometric from kmin to kmax */
    for (int q = 0; q < o->samples && !st; q++) {
        ks[q] = sh_scale_grid_point(SH_SPACING_GEOMETRIC, kmin, kmax, q, o->samples);
        st = zonal_block(o, radius, ks[q], Mf, work, tab + (size_t)q * N * N);
        stats->matrices++;
    }
    if (!st) st = gaunt_build(N, &G);
    for (int p = 0; p < n && !st; p++) {
        const double *x = pos + 3 * p, *nn = normal + 3 * p;
        const double cv[3] = {centre[0] - x[0], centre[1] - x[1], centre[2] - x[2]};
        const double d = sqrt(cv[0] * cv[0] + cv[1] * cv[1] + cv[2] * cv[2]), k = d / o->d0;
        /* the zonal field at d */
        if (o->scaling == SH_SF_EXACT) st = sh_cap_zonal(asin(radius / d), N, zl);
        else {
            if (!o->samples) {
                st = zonal_block(o, radius, k, Mf, work, B);
                stats->matrices++;
            } else {
                /* linear interpolation in k between the table's neighbours;
                 * outside the table, its end (clamped) */
                int q = 0;
                while (q + 2 < o->samples && ks[q + 1] < k) q++;
                double f = (k - ks[q]) / (ks[q + 1] - ks[q]);
                f = fmin(1.0, fmax(0.0, f));
                for (int e = 0; e < N * N; e++)
                    B[e] = (1 - f) * tab[(size_t)q * N * N + e] + f * tab[(size_t)(q + 1) * N * N + e];
            }
            for (int l = 0; l < N && !st; l++) {
                double a = 0;
                for (int lp = 0; lp < N; lp++) a += B[l * N + lp] * z0[lp];
                zl[l] = a;
            }
        }
        if (st) break;
        /* [3] placed on u, the direction to the centre; V = 1 − O */
        const double u[3] = {cv[0] / d, cv[1] / d, cv[2] / d};
        if ((st = sh_eval_dir(N, SH_CS, u, y))) break;
        for (int l = 0; l < N; l++)
            for (int m = -l; m <= l; m++) {
                const int i = sh_index(l, m);
                V[i] = -sqrt(4 * M_PI / (2 * l + 1)) * zl[l] * y[i];
            }
        V[0] += sqrt(4 * M_PI);
        /* [2] t = P_n(V · c⁺), c⁺ = (ρ/π) max(0, n·s): t_k = Σ G(i,j,k) V_i c_j */
        if ((st = sh_transfer_unshadowed(N, SH_CS, rho, nn, c))) break;
        double *t = T + (size_t)p * n2;
        memset(t, 0, sizeof(double) * n2);
        for (int q = 0; q < G.n; q++) t[G.k[q]] += G.g[q] * V[G.i[q]] * c[G.j[q]];
        if (o->progress && ((p & 255) == 255 || p == n - 1)) o->progress(o->progress_ctx, p + 1, n, "receivers");
    }
    stats->seconds = sh__now() - t0;
    gaunt_free(&G);
    free(z0); free(zl); free(B); free(Mf); free(work); free(tab); free(ks); free(V); free(c); free(y);
    return st;
}
