/* gen_zh_dirs.c — the directions of the `zh` rotation method
 * (src/rotate/rot_zh.c): one shared, nested set of 2L+1 unit directions,
 * band l using the first 2l+1, chosen from a Fibonacci spiral of N points
 * to keep the condition number of every Y_l[i][m] = y_lm(d_i) (nocs) small:
 *   greedy: band l adds the pair of candidates minimising cond(Y_l) with
 *           the first 2l−1 directions fixed;
 *   then coordinate descent: each direction in turn replaced by the
 *           candidate minimising max_l cond(Y_l) (the bands that use it),
 *           until a sweep changes nothing.
 * It also reports, for comparison, a separate set per band found the same
 * way (cond of Y_l alone).  Prints the condition numbers and the table as
 * C literals.  Deterministic.
 *   build/tools/gen_zh_dirs [L=5] [N=400]
 * Built by hand: cc -O2 -Isrc tools/gen_zh_dirs.c build/libshlab.a
 *   $(pkg-config --libs gsl) -lm ... (see the Makefile's LDLIBS) */
#include "shlab.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int L, N;
static double (*cand)[3];
static double *ycand; /* ycand[c * n² + i]: the nocs basis at candidate c */

static double cond_of(int l, const int *idx)
{
    const int w = 2 * l + 1;
    gsl_matrix *A = gsl_matrix_alloc(w, w), *V = gsl_matrix_alloc(w, w);
    gsl_vector *S = gsl_vector_alloc(w);
    const int nc = (L + 1) * (L + 1);
    for (int i = 0; i < w; i++)
        for (int m = 0; m < w; m++) gsl_matrix_set(A, i, m, ycand[(size_t)idx[i] * nc + l * l + m]);
    gsl_linalg_SV_decomp_jacobi(A, V, S);
    const double c = gsl_vector_get(S, 0) / gsl_vector_get(S, w - 1);
    gsl_matrix_free(A), gsl_matrix_free(V), gsl_vector_free(S);
    return isfinite(c) ? c : 1e300;
}

/* max over the bands l ≥ lo of cond(Y_l) for the shared set */
static double worst(const int *idx, int lo)
{
    double w = 0;
    for (int l = lo; l <= L; l++) w = fmax(w, cond_of(l, idx));
    return w;
}

int main(int argc, char **argv)
{
    L = argc > 1 ? atoi(argv[1]) : 5;
    N = argc > 2 ? atoi(argv[2]) : 400;
    const int nc = (L + 1) * (L + 1), nd = 2 * L + 1;
    cand = malloc((size_t)N * sizeof *cand);
    ycand = malloc((size_t)N * nc * sizeof *ycand);
    const double ga = M_PI * (3 - sqrt(5.0));
    for (int c = 0; c < N; c++) {
        const double z = 1 - (2.0 * c + 1) / N, r = sqrt(1 - z * z);
        cand[c][0] = r * cos(ga * c), cand[c][1] = r * sin(ga * c), cand[c][2] = z;
        const double n = sqrt(cand[c][0] * cand[c][0] + cand[c][1] * cand[c][1] + z * z);
        for (int k = 0; k < 3; k++) cand[c][k] /= n;
        sh_eval_dir(L + 1, SH_NOCS, cand[c], ycand + (size_t)c * nc);
    }
    /* shared, greedy */
    int idx[64];
    idx[0] = 0;
    for (int l = 1; l <= L; l++) {
        double best = INFINITY;
        int ba = 0, bb = 0;
        for (int a = 0; a < N; a++)
            for (int b = a + 1; b < N; b++) {
                idx[2 * l - 1] = a, idx[2 * l] = b;
                const double c = cond_of(l, idx);
                if (c < best) best = c, ba = a, bb = b;
            }
        idx[2 * l - 1] = ba, idx[2 * l] = bb;
    }
    printf("greedy shared:");
    for (int l = 0; l <= L; l++) printf(" %.4g", cond_of(l, idx));
    printf("\n");
    /* coordinate descent on the max over bands */
    for (int sweep = 0, changed = 1; changed && sweep < 50; sweep++) {
        changed = 0;
        for (int i = 0; i < nd; i++) {
            const int lo = i == 0 ? 0 : (i + 1) / 2; /* the first band using direction i */
            double best = worst(idx, lo);
            int bc = idx[i];
            for (int c = 0; c < N; c++) {
                int dup = 0;
                for (int j = 0; j < nd; j++) dup |= j != i && idx[j] == c;
                if (dup) continue;
                const int old = idx[i];
                idx[i] = c;
                const double w = worst(idx, lo);
                idx[i] = old;
                if (w < best * (1 - 1e-12)) best = w, bc = c;
            }
            if (bc != idx[i]) idx[i] = bc, changed = 1;
        }
    }
    printf("shared after descent:");
    for (int l = 0; l <= L; l++) printf(" %.4g", cond_of(l, idx));
    printf("\n");
    /* per band, for comparison: greedy pairs then descent on that band alone */
    printf("per band (own set):");
    for (int l = 1; l <= L; l++) {
        int jdx[64];
        const int w = 2 * l + 1;
        for (int i = 0; i < w; i++) jdx[i] = idx[i];
        for (int sweep = 0, changed = 1; changed && sweep < 50; sweep++) {
            changed = 0;
            for (int i = 0; i < w; i++) {
                double best = cond_of(l, jdx);
                int bc = jdx[i];
                for (int c = 0; c < N; c++) {
                    int dup = 0;
                    for (int j = 0; j < w; j++) dup |= j != i && jdx[j] == c;
                    if (dup) continue;
                    const int old = jdx[i];
                    jdx[i] = c;
                    const double cc = cond_of(l, jdx);
                    jdx[i] = old;
                    if (cc < best * (1 - 1e-12)) best = cc, bc = c;
                }
                if (bc != jdx[i]) jdx[i] = bc, changed = 1;
            }
        }
        printf(" %.4g", cond_of(l, jdx));
    }
    printf("\n/* the directions (candidate indices of a %d-point Fibonacci spiral) */\n", N);
    for (int i = 0; i < nd; i++)
        printf("    {%.17g, %.17g, %.17g}, /* %d */\n", cand[idx[i]][0], cand[idx[i]][1], cand[idx[i]][2], idx[i]);
    return 0;
}
