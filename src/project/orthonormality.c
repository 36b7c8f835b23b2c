/* orthonormality.c — how well a projection rule integrates the products of
 * basis functions.  The rule's nodes s_k and weights w_k (sh_rule_nodes)
 * give the Gram matrix
 *     G_ij = Σ_k w_k y_i(s_k) y_j(s_k),
 * which is the identity for a rule that integrates every product of bands
 * < n exactly (∫ y_i y_j dΩ = δ_ij, docs/CONVENTIONS.md "Basis").  The error
 * is reported band by band and cumulatively: e_l = max |G_ij − δ_ij| over
 * rows i in band l and columns j in bands ≤ l (G is symmetric, so this is
 * the lower triangle), err[l] = max_{l' ≤ l} e_l', the error at order l+1.
 *
 * G is accumulated over chunks of CHUNK nodes: per chunk the n² basis values
 * of every node (one sh_eval each) are stored row by row, and each entry
 * adds the dot product of two rows.  The sum per entry runs over the chunks
 * in node order and, within a chunk, with four partial sums; the result does
 * not depend on the machine's load or on anything but the rule and order.
 * Memory: the lower triangle of G (n²(n²+1)/2 doubles, 67 MB at n = 64) and
 * two chunks of n²·CHUNK values.
 *
 * [1] R. Green, "Spherical Harmonic Lighting: The Gritty Details", GDC 2003,
 *     "Projection" (the SH functions are orthonormal, so projection is one
 *     integral per coefficient; a rule that is not orthonormal mixes them). */
#include "shlab.h"
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>

#define CHUNK 256

__attribute__((optimize("O3", "unroll-loops"))) static double dot(const double *restrict a,
                                                                   const double *restrict b, long n)
{
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    long k = 0;
    for (; k + 4 <= n; k += 4) {
        s0 += a[k] * b[k];
        s1 += a[k + 1] * b[k + 1];
        s2 += a[k + 2] * b[k + 2];
        s3 += a[k + 3] * b[k + 3];
    }
    for (; k < n; k++) s0 += a[k] * b[k];
    return (s0 + s1) + (s2 + s3);
}

int sh_rule_gram_error(sh_rule rule, long samples, unsigned long seed, int order, sh_convention conv,
                       double *err, long *nodes, sh_progress_fn progress, void *ctx)
{
    if (order < 1 || order > SH_GRAM_MAX_ORDER)
        return sh_error(SH_EINVAL, "orthonormality: order %d is outside 1..%d (the Gram matrix has order⁴/2 "
                                   "entries)", order, SH_GRAM_MAX_ORDER);
    if (!err) return sh_error(SH_EINVAL, "orthonormality: no output array");
    double *t = NULL, *p = NULL, *w = NULL;
    long cnt = 0;
    int st = sh_rule_nodes(rule, samples, seed, &t, &p, &w, &cnt);
    if (st) return st;
    const size_t nb = (size_t)order * order;
    double *G = calloc(nb * (nb + 1) / 2, sizeof *G); /* row i at i(i+1)/2, columns 0..i */
    double *Y = malloc(nb * CHUNK * sizeof *Y), *YW = malloc(nb * CHUNK * sizeof *YW);
    double *y = malloc(nb * sizeof *y);
    if (!G || !Y || !YW || !y) st = sh_error(SH_ENOMEM, "orthonormality: out of memory (%zu MB for order %d)",
                                             (nb * (nb + 1) / 2 + 2 * nb * CHUNK) * sizeof(double) >> 20, order);
    const int nchunks = (int)((cnt + CHUNK - 1) / CHUNK);
    for (long c0 = 0; !st && c0 < cnt; c0 += CHUNK) {
        const long len = c0 + CHUNK <= cnt ? CHUNK : cnt - c0;
        for (long k = 0; k < len && !st; k++) {
            st = sh_eval(order, conv, t[c0 + k], p[c0 + k], y);
            for (size_t i = 0; i < nb; i++) {
                Y[i * len + k] = y[i];
                YW[i * len + k] = y[i] * w[c0 + k];
            }
        }
        /* G_ij += Σ_k w_k y_i(s_k) y_j(s_k) over this chunk, j ≤ i */
        for (size_t i = 0; !st && i < nb; i++) {
            double *Gi = G + i * (i + 1) / 2;
            for (size_t j = 0; j <= i; j++) Gi[j] += dot(YW + i * len, Y + j * len, len);
        }
        if (progress) progress(ctx, (int)(c0 / CHUNK) + 1, nchunks, "chunks of nodes");
    }
    for (int l = 0; !st && l < order; l++) {
        double e = l ? err[l - 1] : 0;
        for (size_t i = (size_t)l * l; i < (size_t)(l + 1) * (l + 1); i++) {
            const double *Gi = G + i * (i + 1) / 2;
            for (size_t j = 0; j <= i; j++) {
                const double g = fabs(Gi[j] - (j == i));
                if (!(g <= e)) e = g; /* NaN counts as worst */
            }
        }
        err[l] = e;
    }
    if (!st && nodes) *nodes = cnt;
    free(G), free(Y), free(YW), free(y), free(t), free(p), free(w);
    return st;
}
