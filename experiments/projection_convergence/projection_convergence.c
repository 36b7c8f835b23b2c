/* projection_convergence — error of the four projection rules against the
 * exact projection as the sample budget grows, for Green's Figure 7 light
 * (kinks: only first-order smooth) and the smooth lobe max(0,cosθ)^7 (exact
 * closed form).  Budget N = number of function evaluations: random and
 * stratified MC and QMC use N samples; the product rule uses S θ nodes × 2S φ
 * nodes with 2S² ≈ N.  Error = RMS over the 16 coefficients of order 4 of
 * (c − exact), and for the randomised rules the RMS over seeds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exp.h"

#define ORDER 4
#define NC (ORDER * ORDER)

static double rms_diff(const double *a, const double *b)
{
    double s = 0;
    for (int i = 0; i < NC; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s / NC);
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const char *specs[2] = {"green", "lobe:7"};
    const sh_rule rules[4] = {SH_RULE_RANDOM, SH_RULE_MC, SH_RULE_QMC, SH_RULE_QUAD};
    const char *rname[4] = {"random", "stratified", "qmc", "quad"};
    FILE *f = exp_data("projection_convergence.dat", "projection error vs function evaluations, order 4",
                       "light(0=green,1=lobe7) rule(0=random,1=stratified,2=qmc,3=quad) evaluations rms_error seeds");
    double slope[2][4];
    for (int s = 0; s < 2; s++) {
        sh_light L;
        exp_check(sh_light_parse(specs[s], 0, &L), "light");
        double exact[NC], c[NC];
        if (s == 0) exp_check(sh_green_reference(ORDER, SH_CS, 1e-12, exact), "green reference");
        else exp_check(sh_light_closed_form(&L, ORDER, SH_CS, exact), "closed form");
        for (int r = 0; r < 4; r++) {
            double lx[16], ly[16];
            int np = 0;
            for (int k = 3; k <= 10; k++) { /* N = 4^k: 64 … 1,048,576 */
                const long N = 1L << (2 * k);
                long samples = N;
                if (rules[r] == SH_RULE_QUAD) samples = lround(sqrt(N / 2.0));
                const long evals = rules[r] == SH_RULE_QUAD ? 2 * samples * samples : sh_rule_samples_used(rules[r], samples);
                const int seeds = rules[r] == SH_RULE_QUAD ? 1 : (N >= (1L << 18) ? 8 : 32);
                double acc = 0;
                for (int seed = 1; seed <= seeds; seed++) {
                    exp_check(sh_project(ORDER, SH_CS, sh_light_fn, &L, rules[r], samples, (unsigned long)seed, c),
                              "project");
                    const double e = rms_diff(c, exact);
                    acc += e * e;
                }
                const double err = sqrt(acc / seeds);
                fprintf(f, "%d %d %ld %.6e %d\n", s, r, evals, err, seeds);
                if (k >= 5 && err > 1e-12) /* above the rounding plateau */ { lx[np] = log((double)evals); ly[np] = log(err); np++; }
            }
            fprintf(f, "\n\n");
            /* least-squares slope of log error vs log N over the larger budgets */
            double mx = 0, my = 0, sxx = 0, sxy = 0;
            for (int i = 0; i < np; i++) { mx += lx[i] / np; my += ly[i] / np; }
            for (int i = 0; i < np; i++) { sxx += (lx[i] - mx) * (lx[i] - mx); sxy += (lx[i] - mx) * (ly[i] - my); }
            slope[s][r] = sxy / sxx;
            exp_progress("%s %s: slope %.2f", specs[s], rname[r], slope[s][r]);
        }
    }
    fclose(f);
    exp_index("![projection convergence](projection_convergence.png)\n\n"
              "RMS error of the 16 order-4 coefficients against the exact projection, versus the number of "
              "function evaluations (N = 64 … 1,048,576), for plain Monte Carlo, Green's stratified (jittered) "
              "Monte Carlo, shifted Sobol QMC and the Gauss-Legendre × uniform product rule. Fitted slopes "
              "(log error / log N, N ≥ 1024 and error above the 1e-12 rounding plateau): Green's light (kinked) random %.2f, stratified %.2f, QMC %.2f, "
              "product rule %.2f; smooth lobe cos⁷ random %.2f, stratified %.2f, QMC %.2f, product rule %.2f "
              "(reaching the rounding level near N = 6·10⁴). Plain Monte Carlo follows N^(−1/2); jittered "
              "stratification and QMC gain about a full power of N on these continuous integrands; the "
              "product rule is limited by the kinks of Green's light to about the same rate, and is "
              "spectrally fast only on the smooth lobe.",
              slope[0][0], slope[0][1], slope[0][2], slope[0][3], slope[1][0], slope[1][1], slope[1][2], slope[1][3]);
    char meas[200];
    snprintf(meas, sizeof meas, "error slope: random %.2f, stratified %.2f (Green's light)", slope[0][0], slope[0][1]);
    const int strat_ok = slope[0][1] < slope[0][0];
    exp_claim_judged("green-stratified-variance", "Green 2003, Monte Carlo Integration",
                     "jittered stratified sampling never has higher variance than plain random sampling, often much lower",
                     "-", meas, "stratified error falls faster than random (fitted slope)", strat_ok,
                     "projection_convergence/projection_convergence.dat",
                     "the stratified error does not fall faster than the random one on Green's light.");
    return 0;
}
