/* rotation_stability.c — how a rotation method's accuracy degrades with the
 * band: orthogonality, homomorphism and distance to the MPFR reference, band
 * by band, over a fixed set of rotations that includes the extremes
 * (β = 0, 1e-12, π/2, π − 1e-9, π) and gimbal lock.  Uses the band iterator
 * (sh_rot_bands), so memory is O(lmax²) for methods that stream.
 */
#include "rotate/rot_internal.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sh_rot_stability_set(sh_rotation set[SH_ROT_STABILITY_NSET],
                         const char *names[SH_ROT_STABILITY_NSET])
{
    static const char *const label[SH_ROT_STABILITY_NSET] = {
        "beta=0", "beta=1e-12", "beta=pi/2", "beta=pi-1e-9", "beta=pi",
        "gimbal(a,0,-a)", "gimbal(pi/2,pi,pi/2)", "beta=1e-7,a+g=0", "random1", "random2"};
    const double e[8][3] = {{0.7, 0, -0.2},        {0.3, 1e-12, -1.1},  {0.4, M_PI / 2, -1.3},
                            {-2.0, M_PI - 1e-9, 0.5}, {1.0, M_PI, -0.4},  {0.9, 0, -0.9},
                            {M_PI / 2, M_PI, M_PI / 2}, {1.2, 1e-7, -1.2}};
    for (int k = 0; k < 8; k++) sh_rotation_from_euler(e[k][0], e[k][1], e[k][2], &set[k]);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!r) return sh_error(SH_ENOMEM, "stability: out of memory");
    gsl_rng_set(r, 20261122);
    for (int k = 8; k < SH_ROT_STABILITY_NSET; k++) {
        /* uniform on SO(3): α, γ uniform, cos β uniform */
        const double a = M_PI * (2 * gsl_rng_uniform(r) - 1), g = M_PI * (2 * gsl_rng_uniform(r) - 1);
        const double b = acos(2 * gsl_rng_uniform(r) - 1);
        sh_rotation_from_euler(a, b, g, &set[k]);
    }
    gsl_rng_free(r);
    if (names)
        for (int k = 0; k < SH_ROT_STABILITY_NSET; k++) names[k] = label[k];
    return SH_OK;
}

static void matvec(int w, const double *B, const double *x, double *y, int transpose)
{
    for (int i = 0; i < w; i++) {
        double s = 0;
        for (int j = 0; j < w; j++) s += (transpose ? B[(size_t)j * w + i] : B[(size_t)i * w + j]) * x[j];
        y[i] = s;
    }
}

/* The orthogonality probes: unit vectors from a fixed-seed LCG, the same
 * for the block estimate and the matrix-free one (below). */
#define ORTH_PROBE_SEED 0x9E3779B97F4A7C15ULL
static void orth_probe(int w, uint64_t *x, double *v)
{
    double nn = 0;
    for (int i = 0; i < w; i++) {
        *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
        v[i] = (double)(*x >> 11) / 9007199254740992.0 - 0.5;
        nn += v[i] * v[i];
    }
    nn = sqrt(nn);
    for (int i = 0; i < w; i++) v[i] /= nn;
}

static double max_diff(size_t n, const double *a, const double *b)
{
    double worst = 0;
    for (size_t i = 0; i < n; i++) {
        const double e = fabs(a[i] - b[i]);
        if (!(e <= worst)) worst = isnan(e) ? INFINITY : e;
    }
    return worst;
}

/* A row without blocks, for a method that applies one band to vectors in
 * O(l²) (halfpi, sh_rot_band_apply): the probe estimate of orth and hom from
 * band applications only, O(l²) per band and rotation instead of the O(l³)
 * of forming 2n blocks.  Rᵀ is applied as the inverse rotation through the
 * same factors (Z(θ)ᵀ = Z(−θ), the same generated d(π/2), rot_halfpi.c), so
 * max|Rᵀ(R v) − v| is the block estimate's quantity, over the same probes;
 * the hom probes are drawn from rng as in the block path.  x: 8·w doubles. */
static int row_matrix_free(int l, sh_convention conv, int n, const sh_rotation *set,
                           const sh_rotation *ab, gsl_rng *rng, double *x, sh_rot_stability_row *row)
{
    const size_t w = 2 * (size_t)l + 1;
    double *p = x, *y = x + 2 * w, *z = x + 4 * w, *u = x + 6 * w;
    uint64_t seed = ORTH_PROBE_SEED;
    orth_probe((int)w, &seed, p);
    orth_probe((int)w, &seed, p + w);
    int st = SH_OK;
    for (int k = 0; k < n && !st; k++) {
        /* orth: Rᵀ(R v) − v, the two probes in one call each */
        if ((st = sh_rot_band_apply(l, conv, &set[k], 0, 2, p, y))) break;
        if ((st = sh_rot_band_apply(l, conv, &set[k], 1, 2, y, z))) break;
        row->orth = fmax(row->orth, max_diff(2 * w, z, p));
        /* hom: R(a)(R(b) v) − R(ab) v, b = set[(k+3) mod n] */
        for (int probe = 0; probe < 2; probe++) {
            double nn = 0, *q = y + probe * w;
            for (size_t i = 0; i < w; i++) { q[i] = gsl_rng_uniform(rng) - 0.5; nn += q[i] * q[i]; }
            nn = sqrt(nn);
            for (size_t i = 0; i < w; i++) q[i] /= nn;
        }
        if ((st = sh_rot_band_apply(l, conv, &set[(k + 3) % n], 0, 2, y, z))) break;
        if ((st = sh_rot_band_apply(l, conv, &set[k], 0, 2, z, z))) break;
        if ((st = sh_rot_band_apply(l, conv, &ab[k], 0, 2, y, u))) break;
        row->hom = fmax(row->hom, max_diff(2 * w, z, u));
    }
    if (!st && (isinf(row->orth) || isinf(row->hom))) row->broken = 1;
    return st;
}

double sh_rot_block_orthogonality(const double *B, int w, int exact)
{
    double worst = 0;
    if (exact) {
        for (int i = 0; i < w; i++)
            for (int j = 0; j < w; j++) {
                double s = 0;
                for (int q = 0; q < w; q++) s += B[(size_t)i * w + q] * B[(size_t)j * w + q];
                const double e = fabs(s - (i == j));
                if (!(e <= worst)) worst = isnan(e) ? INFINITY : e;
            }
        return worst;
    }
    double *v = malloc(3 * (size_t)w * sizeof *v);
    if (!v) return INFINITY;
    double *y = v + w, *z = v + 2 * w;
    uint64_t x = ORTH_PROBE_SEED;
    for (int probe = 0; probe < 2; probe++) {
        orth_probe(w, &x, v);
        matvec(w, B, v, y, 0);
        matvec(w, B, y, z, 1);
        for (int i = 0; i < w; i++) {
            const double e = fabs(z[i] - v[i]);
            if (!(e <= worst)) worst = isnan(e) ? INFINITY : e;
        }
    }
    free(v);
    return worst;
}

/* Where the blocks of a band come from: the n rotations of the set and the
 * n products ab[k] = set[k]·set[(k+3) mod n], by 2n iterators, or for a
 * method that computes each band alone (single) by sh_rot_band. */
typedef struct {
    sh_rot_method method;
    sh_precision prec;
    sh_convention conv;
    int n;
    const sh_rotation *set, *ab;
    sh_rot_bands **it; /* 2n: the set, then the products */
    int single;
} stab_blocks;

/* The set (without β ≠ 0 for the z method) and its products. */
static int stab_rotations(sh_rot_method method, sh_rotation set[SH_ROT_STABILITY_NSET],
                          sh_rotation ab[SH_ROT_STABILITY_NSET], int *n)
{
    sh_rotation all[SH_ROT_STABILITY_NSET];
    int st = sh_rot_stability_set(all, NULL);
    if (st) return st;
    *n = 0;
    for (int k = 0; k < SH_ROT_STABILITY_NSET; k++)
        if (method != SH_ROT_Z || all[k].beta == 0) set[(*n)++] = all[k];
    for (int k = 0; k < *n; k++) sh_rotation_compose(&set[k], &set[(k + 3) % *n], &ab[k]);
    return SH_OK;
}

/* The largest band that needs blocks: lmax, except for a method that
 * applies a band to vectors (halfpi, in double), whose bands above
 * exact_max and ref_max need none (row_matrix_free). */
static int stab_block_lmax(sh_rot_method method, sh_precision prec, int lmax, const int *bands,
                           int nbands, int ref_max, int exact_max)
{
    const int mfree = method == SH_ROT_HALFPI && prec == SH_PREC_DOUBLE;
    int lblk = lmax;
    if (mfree) {
        lblk = 0;
        for (int q = 0; q < nbands; q++) {
            const int l = bands ? bands[q] : q;
            if (l <= exact_max || l <= ref_max) lblk = l;
        }
    }
    return lblk;
}

/* The 2n iterators up to band lblk.  A method that computes each band
 * alone gets each block from sh_rot_band instead (one workspace at a time:
 * 2n of them, each sized for lmax, would be 20 GB at band 4000 for
 * blanco); the others keep their iterators (streams, stored plans). */
static int stab_blocks_open(stab_blocks *b, int lblk)
{
    int st = SH_OK;
    for (int k = 0; k < 2 * b->n && !st; k++)
        st = sh_rot_bands_create(b->method, b->prec, b->conv, lblk, k < b->n ? &b->set[k] : &b->ab[k - b->n],
                                 &b->it[k]);
    b->single = !st && sh__rot_bands_single(b->it[0]);
    for (int k = 0; b->single && k < 2 * b->n; k++) {
        sh_rot_bands_free(b->it[k]);
        b->it[k] = NULL;
    }
    return st;
}

/* Block l of rotation k (k < n: set[k], else ab[k − n]). */
static int stab_block(const stab_blocks *b, int k, int l, double *out)
{
    return b->single ? sh_rot_band(l, b->method, b->prec, b->conv, k < b->n ? &b->set[k] : &b->ab[k - b->n], out)
                     : sh_rot_bands_get(b->it[k], l, out);
}

/* A row from the blocks of band l: the n blocks of the set (blk, stride
 * W² each) and, one at a time after them, each product's block; orth
 * (exact or probed), hom over two probes from rng, ref against the MPFR
 * reference (ref: W_ref² doubles), broken if a block is not finite.
 * v: 4·W doubles. */
static int row_from_blocks(const stab_blocks *b, int l, size_t W, double *blk, double *ref, double *v,
                           gsl_rng *rng, sh_rot_stability_row *row)
{
    const int n = b->n, w = 2 * l + 1;
    int st = SH_OK;
    for (int k = 0; k < n && !st; k++) st = stab_block(b, k, l, blk + (size_t)k * W * W);
    if (st) return st;
    double *x = v, *y = v + W, *z = v + 2 * W, *u = v + 3 * W;
    for (int k = 0; k < n; k++) {
        const double *A = blk + (size_t)k * W * W;
        const double *B = blk + (size_t)((k + 3) % n) * W * W;
        double *C = blk + (size_t)n * W * W;
        if ((st = stab_block(b, n + k, l, C))) break;
        for (int i = 0; i < w * w && !row->broken; i++)
            if (!isfinite(C[i])) row->broken = 1;
        row->orth = fmax(row->orth, sh_rot_block_orthogonality(A, w, row->orth_exact));
        /* hom: A(B x) − C x over two unit probes */
        for (int probe = 0; probe < 2; probe++) {
            double nn = 0;
            for (int i = 0; i < w; i++) { x[i] = gsl_rng_uniform(rng) - 0.5; nn += x[i] * x[i]; }
            nn = sqrt(nn);
            for (int i = 0; i < w; i++) x[i] /= nn;
            matvec(w, B, x, y, 0);
            matvec(w, A, y, z, 0);
            matvec(w, C, x, u, 0);
            for (int i = 0; i < w; i++) row->hom = fmax(row->hom, fabs(z[i] - u[i]));
        }
        if (row->have_ref) {
            if ((st = sh_rot_reference_band(l, b->conv, &b->set[k], 32, ref, NULL))) break;
            for (int i = 0; i < w * w; i++) row->ref = fmax(row->ref, fabs(A[i] - ref[i]));
        }
    }
    if (st) return st;
    /* fmax drops NaN, so look at the blocks themselves */
    for (size_t i = 0; i < (size_t)n * W * W && !row->broken; i += 1)
        if ((i % (W * W)) < (size_t)w * w && !isfinite(blk[i])) row->broken = 1;
    return SH_OK;
}

int sh_rot_stability(sh_rot_method method, sh_precision prec, sh_convention conv, int lmax,
                     const int *bands, int nbands, int ref_max, int exact_max, double stop_above,
                     sh_rot_stability_cb cb, void *ctx)
{
    sh_rotation set[SH_ROT_STABILITY_NSET], ab[SH_ROT_STABILITY_NSET];
    int n = 0;
    int st = stab_rotations(method, set, ab, &n);
    if (st) return st;
    if (lmax < 0) return sh_error(SH_EINVAL, "stability: lmax %d < 0", lmax);
    if (!bands) nbands = lmax + 1;
    for (int q = 0; bands && q < nbands; q++)
        if (bands[q] < 0 || bands[q] > lmax || (q && bands[q] <= bands[q - 1]))
            return sh_error(SH_EINVAL, "stability: bands must increase within 0..%d", lmax);

    const int lblk = stab_block_lmax(method, prec, lmax, bands, nbands, ref_max, exact_max);
    /* the n blocks of the set and one block of a product (n + 1 blocks of
     * W² doubles: 5.6 GB at band 4000) */
    const size_t W = 2 * (size_t)lblk + 1, WV = 2 * (size_t)lmax + 1;
    stab_blocks b = {.method = method, .prec = prec, .conv = conv, .n = n, .set = set, .ab = ab};
    b.it = calloc(2 * (size_t)n, sizeof *b.it);
    double *blk = malloc(((size_t)n + 1) * W * W * sizeof *blk);
    const size_t WR = 2 * (size_t)(ref_max < 0 ? 0 : ref_max < lmax ? ref_max : lmax) + 1; /* bands with ref */
    double *ref = malloc(WR * WR * sizeof *ref), *v = malloc(8 * WV * sizeof *v);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!b.it || !blk || !ref || !v || !rng) {
        st = sh_error(SH_ENOMEM, "stability: out of memory (lmax %d)", lmax);
        goto done;
    }
    if ((st = stab_blocks_open(&b, lblk))) goto done;
    for (int q = 0; q < nbands; q++) {
        const int l = bands ? bands[q] : q;
        sh_rot_stability_row row = {.band = l, .orth_exact = l <= exact_max, .have_ref = l <= ref_max};
        /* the probes are seeded by the band, so a band's row is the same
         * whichever other bands are computed (--bands, shards) */
        gsl_rng_set(rng, 7 + (unsigned long)l);
        if (l > lblk) st = row_matrix_free(l, conv, n, set, ab, rng, v, &row);
        else st = row_from_blocks(&b, l, W, blk, ref, v, rng, &row);
        if (st) break;
        if (cb && (st = cb(&row, ctx))) break;
        if (row.broken || (stop_above > 0 && row.orth > stop_above)) break;
    }
done:
    if (b.it)
        for (int k = 0; k < 2 * n; k++) sh_rot_bands_free(b.it[k]);
    free(b.it);
    free(blk);
    free(ref);
    free(v);
    gsl_rng_free(rng);
    return st;
}
