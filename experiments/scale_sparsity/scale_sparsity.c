/* scale_sparsity — Wang et al. (2006) Sec. 2.2 and Appendix: "less than one
 * fifth of [M's] elements are non-zero ... the locations of these non-zero
 * elements are independent of the angular scaling function ... Regardless of
 * whether energy is being preserved, exactly N(2N²+1)/3 of the N⁴ elements in
 * M are non-zero".
 *
 * For N = 1..16 and every family and mode we
 *  (a) check the m_i = m_j pattern with the independent 2-D product rule
 *      (sh_scale_matrix_quad: sh_eval, numerical φ): the largest entry off the
 *      pattern relative to the largest entry;
 *  (b) check the analytic-φ matrices against that rule (N <= 8, ≤ 1e-10);
 *  (c) count the non-zeros (|M_ij| > 1e-12 max|M|) and compare them with the
 *      bound N(2N²+1)/3 and with the count predicted by the structural zeros
 *      derived in scale_sparsity/index.md (preservation of constants or of ∫F,
 *      parity, the mid-range polynomial/multipole structure). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

typedef struct {
    const char *label;
    sh_scaling s;
    int rule; /* 0 none known, 1 preservation only, 2 midrange, 3 symmetric τ (parity), 4 linear k = 2 */
} scase;

/* Structural zero predicted for (l_i, l_j) with m_i = m_j (|m| <= min). */
static int predicted_zero(const scase *c, int li, int lj)
{
    const sh_scaling *s = &c->s;
    const int surj = !(s->family == SH_SCALE_LINEAR && s->k < 1.0); /* τ([0,π]) = [0,π] */
    int z = 0;
    /* plain: a constant stays constant, M_i0 = δ_i0 */
    if (!s->energy && lj == 0 && li > 0) z = 1;
    /* energy-preserving, τ onto [0,π]: ∫F is kept, M_0j = δ_0j */
    if (s->energy && surj && li == 0 && lj > 0) z = 1;
    if (c->rule == 2) {
        /* plain: y_j(P/R) with P/R = k(ẑ − (s·ẑ)s) + W s, W = √(1 − k² sin²θ) even:
         * the part even under s → −s is a polynomial of degree <= 2 l_j */
        if (!s->energy && !(li & 1) && li > 2 * lj) z = 1;
        /* energy: y_i(τ⁻¹) = [h_i(s − kẑ)/D^{2l_i+1}]·D^{l_i+1}, D = |s − kẑ|: an
         * exterior multipole (bands >= l_i) times, for odd l_i, a polynomial of
         * degree (l_i+1)/2 in cos α */
        if (s->energy && (li & 1) && li > 2 * lj + 1) z = 1;
    }
    if (c->rule == 3 && ((li + lj) & 1)) z = 1; /* τ(π−θ) = π − τ(θ): parity */
    /* linear k = 2, plain: F = y_j∘τ is y_j(2θ, φ) — a polynomial P_j of degree
     * 2 l_j in s, even under s → −s — on the upper hemisphere and the pole
     * value c on the lower one, so its even part (F(s) + F(−s))/2 = (P_j + c)/2
     * is a polynomial of degree 2 l_j everywhere: M_ij = 0 for even l_i > 2 l_j */
    if (c->rule == 4 && !s->energy && !(li & 1) && li > 2 * lj) z = 1;
    return z;
}

static long predicted_count(const scase *c, int N)
{
    long cnt = 0;
    for (int li = 0; li < N; li++)
        for (int lj = 0; lj < N; lj++) {
            const int mm = li < lj ? li : lj;
            if (!predicted_zero(c, li, lj)) cnt += 2 * mm + 1;
        }
    return cnt;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const scase cases[] = {
        {"linear k=0.7 plain", {SH_SCALE_LINEAR, 0.7, 0, 0}, 1},
        {"linear k=0.7 energy", {SH_SCALE_LINEAR, 0.7, 0, 1}, 1},
        {"linear k=1.6 plain", {SH_SCALE_LINEAR, 1.6, 0, 0}, 1},
        {"linear k=1.6 energy", {SH_SCALE_LINEAR, 1.6, 0, 1}, 1},
        {"cone k=0.6 plain", {SH_SCALE_CONE, 0.6, M_PI / 4, 0}, 1},
        {"cone k=1.8 energy", {SH_SCALE_CONE, 1.8, M_PI / 4, 1}, 1},
        {"midrange k=0.5 plain", {SH_SCALE_MIDRANGE, 0.5, 0, 0}, 2},
        {"midrange k=-0.5 energy", {SH_SCALE_MIDRANGE, -0.5, 0, 1}, 2},
        {"cone θ0=90° k=0.6 plain", {SH_SCALE_CONE, 0.6, M_PI / 2, 0}, 3},
        {"linear k=0.5 plain", {SH_SCALE_LINEAR, 0.5, 0, 0}, 0},
        {"linear k=2 plain", {SH_SCALE_LINEAR, 2.0, 0, 0}, 4},
    };
    const int nc = (int)(sizeof cases / sizeof *cases), NMAX = 16;
    FILE *f = exp_data("sparsity.dat", "non-zero entries of the scaling matrix (|M_ij| > 1e-12 max|M|)",
                       "N bound then per case: measured predicted (case order in sparsity_cases.txt)");
    FILE *fc = exp_data("sparsity_cases.txt", "case labels in column order", "label");
    for (int c = 0; c < nc; c++) fprintf(fc, "%s\n", cases[c].label);
    fclose(fc);
    double worst_off = 0.0, worst_acc = 0.0;
    int mismatch = 0, generic_eq_bound = 0, generic_total = 0;
    char table[8192];
    int tl = snprintf(table, sizeof table,
                      "| case | N=2 | N=4 | N=8 | N=16 | predicted = measured for N=1..16 | largest zero | smallest non-zero |\n"
                      "|---|---|---|---|---|---|---|---|\n");
    double worst_gap_zero = 0.0, worst_gap_nz = INFINITY;
    long meas[16][17];
    /* structural, not threshold: the largest entry counted as zero and the
     * smallest counted as non-zero, relative to max|M|, over N = 1..16 */
    double big_zero[17], small_nz[17];
    for (int c = 0; c < 17; c++) big_zero[c] = 0.0, small_nz[c] = INFINITY;
    for (int N = 1; N <= NMAX; N++) {
        const int n = N * N;
        double *M = malloc(sizeof(double) * n * n), *Q = malloc(sizeof(double) * n * n);
        if (!M || !Q) { fprintf(stderr, "out of memory\n"); return 1; }
        exp_progress("N = %d", N);
        fprintf(f, "%d %ld", N, sh_scale_pattern_bound(N));
        for (int c = 0; c < nc; c++) {
            exp_check(sh_scale_matrix(N, &cases[c].s, M, NULL), "sh_scale_matrix");
            double mx = 0.0;
            for (int q = 0; q < n * n; q++) mx = fmax(mx, fabs(M[q]));
            /* (a) pattern from the independent rule: one family per mode, all N */
            if (c == 2 || c == 5 || c == 6 || c == 7) {
                const int nodes = N <= 8 ? 64 : 16, panels = N <= 8 ? 8 : 2;
                exp_check(sh_scale_matrix_quad(N, N & 1 ? SH_NOCS : SH_CS, &cases[c].s, nodes, panels, Q), "quad");
                for (int i = 0; i < n; i++)
                    for (int j = 0; j < n; j++) {
                        int li, mi, lj, mj;
                        sh_index_lm(i, &li, &mi);
                        sh_index_lm(j, &lj, &mj);
                        if (mi != mj) worst_off = fmax(worst_off, fabs(Q[i * n + j]) / mx);
                    }
                /* (b) accuracy against the independent rule */
                if (N <= 8)
                    for (int q = 0; q < n * n; q++) worst_acc = fmax(worst_acc, fabs(M[q] - Q[q]));
            }
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) {
                    int li, mi, lj, mj;
                    sh_index_lm(i, &li, &mi);
                    sh_index_lm(j, &lj, &mj);
                    if (mi != mj) continue;
                    const double v = fabs(M[i * n + j]) / mx;
                    if (v > 1e-12) small_nz[c] = fmin(small_nz[c], v);
                    else big_zero[c] = fmax(big_zero[c], v);
                }
            const long nz = sh_scale_nonzeros(N, M, 1e-12);
            const long pr = cases[c].rule ? predicted_count(&cases[c], N) : -1;
            if (pr >= 0 && pr != nz && cases[c].rule != 4) mismatch++; /* rule 4 is partial: reported below */
            if (cases[c].rule == 1 && N > 1) {
                generic_total++;
                generic_eq_bound += nz == sh_scale_pattern_bound(N);
            }
            meas[N - 1][c] = nz;
            fprintf(f, " %ld %ld", nz, pr);
        }
        fputc('\n', f);
        free(M);
        free(Q);
    }
    fclose(f);
    for (int c = 0; c < nc; c++) {
        int agree = 1;
        long extra = 0;
        if (cases[c].rule)
            for (int N = 1; N <= NMAX; N++) {
                agree &= predicted_count(&cases[c], N) == meas[N - 1][c];
                extra = predicted_count(&cases[c], N) - meas[N - 1][c];
            }
        char verdict[96];
        if (!cases[c].rule) snprintf(verdict, sizeof verdict, "no rule (measured only)");
        else if (agree) snprintf(verdict, sizeof verdict, "yes");
        else snprintf(verdict, sizeof verdict, "**no**: %ld more zeros than predicted at N=16", extra);
        worst_gap_zero = fmax(worst_gap_zero, big_zero[c]);
        if (big_zero[c] > 0) worst_gap_nz = fmin(worst_gap_nz, small_nz[c]);
        tl += snprintf(table + tl, sizeof table - tl, "| %s | %ld | %ld | %ld | %ld | %s | %.1e | %.1e |\n",
                       cases[c].label, meas[1][c], meas[3][c], meas[7][c], meas[15][c], verdict, big_zero[c],
                       small_nz[c]);
    }
    tl += snprintf(table + tl, sizeof table - tl, "| bound N(2N²+1)/3 | %ld | %ld | %ld | %ld | | | |\n",
                   sh_scale_pattern_bound(2), sh_scale_pattern_bound(4), sh_scale_pattern_bound(8),
                   sh_scale_pattern_bound(16));

    char me[1024];
    snprintf(me, sizeof me, "largest off-pattern entry / max|M| = %.1e (independent 2-D rule, N = 1..16, 4 cases)", worst_off);
    exp_claim_judged("wang-scaling-pattern", "Wang et al. 2006, Sec. 2.2",
                     "the non-zero entries of M lie at m_i = m_j, independently of τ and of energy preservation (Fig. 2, "
                     "Appendix)",
                     "Fig. 2 (pattern for N = 4)", me, "1e-13", worst_off <= 1e-13,
                     "scale_sparsity/sparsity.dat",
                     "an entry off m_i = m_j exceeds 1e-13 of max|M|.");
    snprintf(me, sizeof me, "max |M − independent 2-D product rule| = %.1e (N <= 8, 4 cases, both conventions)", worst_acc);
    exp_claim_judged("scale-matrix-accuracy", "shlab goal",
                     "scaling matrices by analytic φ + composite Gauss-Legendre θ agree with an independent computation",
                     "≤ 1e-10", me, "1e-10", worst_acc <= 1e-10,
                     "scale_sparsity/sparsity.dat",
                     "the two computations differ by more than 1e-10.");
    (void)mismatch; /* the rules and their cases: the report's table and list */
    snprintf(me, sizeof me,
             "N = 4: %ld (plain), %ld (energy, τ onto [0,π]), %ld/%ld (midrange), %ld (cone θ0=90°), %ld (linear "
             "k=1/2); the bound only for linear k<1 energy (%d of %d cases): index.md#scale_sparsity",
             meas[3][0], meas[3][3], meas[3][6], meas[3][7], meas[3][8], meas[3][9], generic_eq_bound, generic_total);
    const int count_exact = generic_eq_bound == generic_total;
    exp_claim_judged("wang-scaling-count", "Wang et al. 2006, Sec. 2.2",
                     "regardless of whether energy is preserved, exactly N(2N²+1)/3 of the N⁴ elements of M are non-zero",
                     "N(2N²+1)/3 (44 for N = 4)", me, "exact count", count_exact,
                     "scale_sparsity/sparsity.dat",
                     "structural zeros (constants or ∫F kept, parity) make N(2N²+1)/3 an upper bound that most cases stay below.");
    snprintf(me, sizeof me, "bound/N⁴ = %.3f (N=3), %.3f (N=4), %.3f (N=8); actual counts are lower",
             sh_scale_pattern_bound(3) / 81.0, sh_scale_pattern_bound(4) / 256.0, sh_scale_pattern_bound(8) / 4096.0);
    exp_claim("wang-one-fifth", "Wang et al. 2006, Sec. 2.2", "less than one fifth of the elements of M are non-zero",
              "< 1/5", me, "< 0.2", "reproduced", "scale_sparsity/sparsity.dat (holds for N >= 4; N <= 3 exceed 1/5)");

    exp_index("![non-zeros of M against N](scale_sparsity.png)\n\n"
              "Non-zero entries (|M_ij| > 1e-12 max|M|) of the scaling matrix for N = 1..16, against the pattern "
              "bound N(2N²+1)/3 = the number of (i, j) with m_i = m_j. The pattern itself is confirmed by an "
              "independent 2-D product rule (sh_eval at (θ,φ) and (τ(θ),φ), φ summed numerically): the largest "
              "entry off m_i = m_j is %.1e of max|M|, and the analytic-φ matrices agree with that rule to %.1e "
              "(N <= 8).\n\n%s\n"
              "**The paper's \"exactly N(2N²+1)/3 non-zero, regardless of energy preservation\" is only an upper "
              "bound.** The structural zeros (each verified by the count for N = 1..16, and the mid-range ones "
              "entry by entry in tests/scale/test_scale.c):\n\n"
              "* *Plain scaling keeps constants*: F_r = 1 gives F_d = F_r∘τ = 1, so column 0 is e_0 and the N−1 "
              "entries M_{(l,0),(0,0)}, l ≥ 1, vanish. *Energy-preserving scaling keeps ∫F dΩ* whenever τ maps "
              "[0,π] onto [0,π] (cone, midrange, linear k ≥ 1): row 0 is e_0ᵀ, again N−1 zeros. Linear k < 1 "
              "with energy preservation maps onto [0, kπ] only and reaches the bound. So the generic count is "
              "N(2N²+1)/3 − (N−1) (41 for N = 4, not 44).\n"
              "* *Mid-range*: P/R = k(ẑ − (s·ẑ)s) + W s with W = √(1 − k² sin²θ) even under s → −s, so y_j∘τ is a "
              "polynomial of degree ≤ 2l_j in its even part: plain M_ij = 0 for even l_i > 2l_j. For energy "
              "preservation M_ij = ⟨y_j, y_i∘τ⁻¹⟩ with y_i∘τ⁻¹ = [h_i(s−kẑ)/D^{2l_i+1}]·D^{l_i+1}, "
              "D = |s − kẑ|: an exterior multipole (bands ≥ l_i) times, for odd l_i, a polynomial of degree "
              "(l_i+1)/2 in cos α, so M_ij = 0 for odd l_i > 2l_j + 1.\n"
              "* *Symmetric τ* (cone with θ0 = 90°: τ(π−θ) = π − τ(θ)): entries with l_i + l_j odd vanish by parity.\n"
              "* *Linear k = 2* (plain): y_j(2θ, φ) is a polynomial P_j of degree 2l_j in s, even under s → −s, on "
              "the upper hemisphere and the pole value c on the lower one, so the even part of F = y_j∘τ is "
              "(P_j + c)/2 everywhere, a polynomial of degree 2l_j: M_ij = 0 for even l_i > 2l_j (the mid-range "
              "plain rule). This explains all but %ld of its zeros at N = 16 (the first extra pair is "
              "(l_i, l_j, m) = (6, 4, ±2), zero to 7e-17): not derived here.\n"
              "* *Linear k = 1/2* (plain): cos(θ/2) = √((1+cos θ)/2), so for m = 0 and even l_j, y_j∘τ is a "
              "polynomial of degree l_j/2 in cos θ (zero against l_i > l_j/2), and further zeros come from "
              "half-range parity; measured only, no closed count here.\n"
              "* None of these is a threshold effect: over all cases and N = 1..16 the largest entry counted as "
              "zero is %.1e of max|M| and the smallest counted as non-zero %.1e (the last two table columns), "
              "so any threshold between 1e-15 and the latter gives the same counts (the mid-range matrices have the smallest true entries, k^l-small).\n"
              "* Identity (k = 1): N² non-zeros.\n\n"
              "The paper's \"less than one fifth\" holds for the bound from N = 4 on (44/256 = 0.17; N = 3 gives 19/81 = 0.23).",
              worst_off, worst_acc, table, predicted_count(&cases[10], 16) - meas[15][10], worst_gap_zero,
              worst_gap_nz);
    return 0;
}
