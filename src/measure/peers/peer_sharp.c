/* peer_sharp.c — libsharp as a peer (see peer_sharp.h for the conventions).
 *
 * [1] M. Reinecke, D. S. Seljebotn, "Libsharp — spherical harmonic transforms
 *     revisited", A&A 554 (2013) A112; libsharp 1.0 sharp.h,
 *     sharp_geomhelpers.h, sharp_almhelpers.h. */
#include "measure/peers/peer_sharp.h"

#include <math.h>
#include <stdlib.h>

void sh_peer_agreement(const double *a, const double *b, size_t n, double *rel_l2, double *max_rel)
{
    double d = 0.0, nb = 0.0, dm = 0.0, bm = 0.0;
    for (size_t i = 0; i < n; i++) {
        d += (a[i] - b[i]) * (a[i] - b[i]);
        nb += b[i] * b[i];
        dm = fmax(dm, fabs(a[i] - b[i]));
        bm = fmax(bm, fabs(b[i]));
    }
    *rel_l2 = nb > 0.0 ? sqrt(d / nb) : sqrt(d);
    *max_rel = bm > 0.0 ? dm / bm : dm;
}

#if defined(SHLAB_HAVE_SHARP)
#include <libsharp/sharp.h>
#include <libsharp/sharp_almhelpers.h>
#include <libsharp/sharp_geomhelpers.h>
#ifdef _OPENMP
#include <omp.h>
#endif

struct sh_peer_sharp {
    int lmax, nrings, nphi;
    sharp_geom_info *geom;
    sharp_alm_info *alm_info;
    double *alm; /* complex a_lm, interleaved re, im */
};

int sh_peer_sharp_available(void) { return 1; }

void sh_peer_sharp_threads(int nthreads)
{
#ifdef _OPENMP
    omp_set_num_threads(nthreads > 0 ? nthreads : omp_get_num_procs());
#else
    (void)nthreads;
#endif
}

static int finish(int lmax, int nrings, int nphi, sharp_geom_info *geom, sh_peer_sharp **out)
{
    sh_peer_sharp *s = calloc(1, sizeof *s);
    if (!s) {
        sharp_destroy_geom_info(geom);
        return sh_error(SH_ENOMEM, "out of memory (libsharp peer)");
    }
    s->lmax = lmax;
    s->nrings = nrings;
    s->nphi = nphi;
    s->geom = geom;
    sharp_make_triangular_alm_info(lmax, lmax, 1, &s->alm_info);
    s->alm = calloc(2 * (size_t)sharp_alm_count(s->alm_info), sizeof(double));
    if (!s->alm) {
        sh_peer_sharp_destroy(s);
        return sh_error(SH_ENOMEM, "out of memory (libsharp a_lm)");
    }
    *out = s;
    return SH_OK;
}

int sh_peer_sharp_gauss(int lmax, sh_peer_sharp **out)
{
    if (lmax < 0 || lmax > 100000) return sh_error(SH_EINVAL, "libsharp peer: lmax %d", lmax);
    const int nr = lmax + 1, np = 2 * lmax + 2;
    sharp_geom_info *geom;
    sharp_make_gauss_geom_info(nr, np, 0.0, 1, np, &geom);
    return finish(lmax, nr, np, geom, out);
}

int sh_peer_sharp_grid(int lmax, const sh_grid *g, sh_peer_sharp **out)
{
    if (lmax < 0 || !g || g->nrings < 1 || g->nphi < 1 || !g->cos_theta)
        return sh_error(SH_EINVAL, "libsharp peer: bad grid");
    const int nr = g->nrings;
    int *nph = malloc(sizeof(int) * nr), *stride = malloc(sizeof(int) * nr);
    ptrdiff_t *ofs = malloc(sizeof(ptrdiff_t) * nr);
    double *phi0 = malloc(sizeof(double) * nr), *theta = malloc(sizeof(double) * nr);
    if (!nph || !stride || !ofs || !phi0 || !theta) {
        free(nph), free(stride), free(ofs), free(phi0), free(theta);
        return sh_error(SH_ENOMEM, "out of memory (libsharp geometry)");
    }
    for (int r = 0; r < nr; r++) {
        nph[r] = g->nphi;
        stride[r] = 1;
        ofs[r] = (ptrdiff_t)r * g->nphi;
        phi0[r] = g->phi0;
        theta[r] = acos(g->cos_theta[r]);
    }
    sharp_geom_info *geom;
    sharp_make_geom_info(nr, nph, ofs, stride, phi0, theta, g->weight, &geom);
    free(nph), free(stride), free(ofs), free(phi0), free(theta);
    return finish(lmax, nr, g->nphi, geom, out);
}

int sh_peer_sharp_rings(const sh_peer_sharp *s, int *nrings, int *nphi, double *cos_theta,
                        double *weight, double *phi0)
{
    if (!s) return sh_error(SH_EINVAL, "libsharp peer is NULL");
    *nrings = s->nrings;
    *nphi = s->nphi;
    for (int i = 0; i < s->geom->npairs; i++)
        for (int k = 0; k < 2; k++) {
            const sharp_ringinfo *r1 = &s->geom->pair[i].r1, *r = k ? &s->geom->pair[i].r2 : r1;
            if (r->nph <= 0) continue;
            const int ring = (int)(r->ofs / s->nphi);
            /* libsharp runs one Legendre recursion per ring pair, at the
             * first ring's cosθ, and takes the second ring's values from it
             * by parity ([1], Sec. 3): the second ring it computes with is
             * at −cosθ₁, not at its own cth, which can differ by an ulp. */
            if (cos_theta) cos_theta[ring] = k ? -r1->cth : r->cth;
            if (weight) weight[ring] = r->weight;
            if (phi0) *phi0 = r->phi0;
        }
    return SH_OK;
}

int sh_peer_sharp_map2alm(sh_peer_sharp *s, const double *map)
{
    void *a = s->alm, *m = (void *)map;
    sharp_execute(SHARP_MAP2ALM, 0, &a, &m, s->geom, s->alm_info, SHARP_DP, NULL, NULL);
    return SH_OK;
}

int sh_peer_sharp_alm2map(sh_peer_sharp *s, double *map)
{
    void *a = s->alm, *m = map;
    sharp_execute(SHARP_ALM2MAP, 0, &a, &m, s->geom, s->alm_info, SHARP_DP, NULL, NULL);
    return SH_OK;
}

void sh_peer_sharp_get_cs(const sh_peer_sharp *s, double *c)
{
    for (int l = 0; l <= s->lmax; l++)
        for (int m = 0; m <= l; m++) {
            const double *a = s->alm + 2 * sharp_alm_index(s->alm_info, l, m);
            if (!m) {
                c[sh_index(l, 0)] = a[0];
            } else { /* c_l^m = √2 Re a, c_l^{−m} = −√2 Im a */
                c[sh_index(l, m)] = M_SQRT2 * a[0];
                c[sh_index(l, -m)] = -M_SQRT2 * a[1];
            }
        }
}

void sh_peer_sharp_set_cs(sh_peer_sharp *s, const double *c)
{
    for (int l = 0; l <= s->lmax; l++)
        for (int m = 0; m <= l; m++) {
            double *a = s->alm + 2 * sharp_alm_index(s->alm_info, l, m);
            if (!m) { /* a_lm = (c_l^m − i c_l^{−m}) / √2 */
                a[0] = c[sh_index(l, 0)];
                a[1] = 0.0;
            } else {
                a[0] = c[sh_index(l, m)] / M_SQRT2;
                a[1] = -c[sh_index(l, -m)] / M_SQRT2;
            }
        }
}

void sh_peer_sharp_destroy(sh_peer_sharp *s)
{
    if (!s) return;
    if (s->geom) sharp_destroy_geom_info(s->geom);
    if (s->alm_info) sharp_destroy_alm_info(s->alm_info);
    free(s->alm);
    free(s);
}

#else /* no libsharp */

#define ABSENT sh_error(SH_ENOTSUP, "libsharp was not found when shlab was built (Debian: libsharp-dev)")
struct sh_peer_sharp {
    int unused;
};
int sh_peer_sharp_available(void) { return 0; }
void sh_peer_sharp_threads(int nthreads) { (void)nthreads; }
int sh_peer_sharp_gauss(int lmax, sh_peer_sharp **out) { (void)lmax, (void)out; return ABSENT; }
int sh_peer_sharp_grid(int lmax, const sh_grid *g, sh_peer_sharp **out)
{
    (void)lmax, (void)g, (void)out;
    return ABSENT;
}
int sh_peer_sharp_rings(const sh_peer_sharp *s, int *nrings, int *nphi, double *cos_theta,
                        double *weight, double *phi0)
{
    (void)s, (void)nrings, (void)nphi, (void)cos_theta, (void)weight, (void)phi0;
    return ABSENT;
}
int sh_peer_sharp_map2alm(sh_peer_sharp *s, const double *map) { (void)s, (void)map; return ABSENT; }
int sh_peer_sharp_alm2map(sh_peer_sharp *s, double *map) { (void)s, (void)map; return ABSENT; }
void sh_peer_sharp_get_cs(const sh_peer_sharp *s, double *c) { (void)s, (void)c; }
void sh_peer_sharp_set_cs(sh_peer_sharp *s, const double *c) { (void)s, (void)c; }
void sh_peer_sharp_destroy(sh_peer_sharp *s) { (void)s; }

#endif
