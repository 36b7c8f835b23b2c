/* orthonormality — how well each projection rule integrates the products of
 * basis functions: the Gram matrix G_ij = Σ_k w_k y_i(s_k) y_j(s_k) should be
 * the identity.  For a fixed budget of about 4096 nodes per rule (product
 * rule: 45 θ × 90 φ nodes; stratified MC 64²; random; Sobol), the error
 * max_{i,j < n²} |G_ij − δ_ij| is computed exactly for every order n ≤ 64
 * by sh_rule_gram_error (src/project/orthonormality.c): band by band,
 * e_k = max over rows i in band k and columns j in bands ≤ k (G is
 * symmetric), and error(n) = max_{k<n} e_k. */
#include <stdio.h>

#include "exp.h"

#define MAXO SH_GRAM_MAX_ORDER

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const sh_rule rules[4] = {SH_RULE_QUAD, SH_RULE_MC, SH_RULE_RANDOM, SH_RULE_QMC};
    const char *rname[4] = {"quad", "stratified", "random", "qmc"};
    const long samples[4] = {45, 4096, 4096, 4096};
    double err[4][MAXO];
    long counts[4];
    FILE *f = exp_data("orthonormality.dat", "Gram-matrix error of each rule vs order (about 4096 nodes each)",
                       "order quad stratified random qmc");
    /* the Gram matrix band by band: the library's routine (also `shlab orthonormality`) */
    for (int r = 0; r < 4; r++) {
        exp_check(sh_rule_gram_error(rules[r], samples[r], 1, MAXO, SH_CS, err[r], &counts[r], NULL, NULL),
                  "sh_rule_gram_error");
        exp_progress("%s: %ld nodes", rname[r], counts[r]);
    }
    for (int o = 0; o < MAXO; o++) fprintf(f, "%d %.3e %.3e %.3e %.3e\n", o + 1, err[0][o], err[1][o], err[2][o], err[3][o]);
    fclose(f);
    /* the top of the range (SH_GRAM_MAX_ORDER, `orthonormality --order`):
     * the product rule with S = 64 θ nodes is exact there, so its error at
     * order 64 is the routine's own rounding (docs/ranges.md; 13 s, too long
     * for make check) */
    double top[MAXO];
    long top_nodes = 0;
    exp_check(sh_rule_gram_error(SH_RULE_QUAD, MAXO, 1, MAXO, SH_CS, top, &top_nodes, NULL, NULL), "gram top");
    printf("orthonormality: product rule S = %d (%ld nodes) at order %d: max |G - I| = %.3g\n", MAXO, top_nodes, MAXO,
           top[MAXO - 1]);
    if (!(top[MAXO - 1] <= 1e-13)) {
        fprintf(stderr, "orthonormality: the exact rule is off by %.3g at order %d\n", top[MAXO - 1], MAXO);
        return 1;
    }
    int exact_to = 0;
    while (exact_to < MAXO && err[0][exact_to] < 1e-12) exact_to++;
    exp_index("![orthonormality](orthonormality.png)\n\n"
              "Largest deviation of the Gram matrix Σ w y_i y_j from the identity, over all basis pairs of "
              "order n, for each rule at a budget of about 4096 nodes (product rule %ld, stratified %ld, "
              "random %ld, Sobol %ld). The product rule with 45 Gauss-Legendre θ nodes is exact (≤ 1e-12: "
              "%.1e at n = %d) up to order %d, as it must be (products of degree ≤ 2·44 in cos θ), and "
              "fails abruptly beyond. The sampling rules are never orthonormal: at order 4 their error is "
              "%.2e (stratified), %.2e (random), %.2e (Sobol), and at order 64 %.2e, %.2e, %.2e. "
              "At the top of the range (order %d), the product rule with %d θ nodes (%ld nodes), exact there, "
              "gives %.1e: the computation's own rounding.",
              counts[0], counts[1], counts[2], counts[3], err[0][exact_to - 1], exact_to, exact_to,
              err[1][3], err[2][3], err[3][3], err[1][MAXO - 1], err[2][MAXO - 1], err[3][MAXO - 1], MAXO, MAXO,
              top_nodes, top[MAXO - 1]);
    return 0;
}
