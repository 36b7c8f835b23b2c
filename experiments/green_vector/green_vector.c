/* green_vector — Green (2003), "Spherical Harmonic Lighting: The Gritty
 * Details", section "SH Projection": the 16-coefficient vector printed for his
 * Figure 7 light projected with 10,000 jittered samples.  Every printed number
 * is compared with the exact projection (sh_green_reference, adaptive
 * quadrature with the kinks as breakpoints) and with the spread of the very
 * estimator he used (stratified Monte Carlo, 10,000 samples) over many seeds.
 *
 * Verdict per coefficient: reproduced when |printed − exact| ≤ 3σ_MC + 5e-6
 * (σ_MC = standard deviation over seeds; 5e-6 = half a unit of the printed
 * 5th decimal), otherwise differs.  The light's formula as OCR'd (the −3
 * outside the second max) is tested against c_0 as well. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

static const double printed[15] = {0.39925,  -0.21075, 0.28687,  0.28277, -0.31530,
                                   -0.00040, 0.13159,  0.00098,  -0.09359, -0.00072,
                                   0.12290,  0.30458,  -0.16427, -0.00062, -0.09126};
/* Green prints 15 numbers for 16 coefficients.  Which one is missing is not
 * assumed: every choice of the omitted index is tried and the alignment under
 * which most printed numbers are reproduced is used (and reported). */
#define NPRINTED 15

/* The light as the OCR'd text prints it: −3 outside the second max. */
static double light_as_printed(const double d[3], double theta, double phi, void *ctx)
{
    (void)d; (void)ctx;
    return fmax(0.0, 5.0 * cos(theta) - 4.0) + fmax(0.0, -4.0 * sin(theta - M_PI) * cos(phi - 2.5)) - 3.0;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const int order = 4, n = 16, seeds = 400;
    double exact[16], c[16], mean[16] = {0}, m2[16] = {0};
    exp_check(sh_green_reference(order, SH_CS, 1e-12, exact), "sh_green_reference");

    sh_light green;
    exp_check(sh_light_parse("green", 0, &green), "sh_light_parse");
    exp_progress("%d seeds of 10,000 stratified samples", seeds);
    for (int s = 1; s <= seeds; s++) {
        exp_check(sh_project(order, SH_CS, sh_light_fn, &green, SH_RULE_MC, 10000, (unsigned long)s, c),
                  "sh_project mc");
        for (int i = 0; i < n; i++) { /* Welford */
            const double d = c[i] - mean[i];
            mean[i] += d / s;
            m2[i] += d * (c[i] - mean[i]);
        }
    }
    /* the formula exactly as OCR'd: c_0 only decides it */
    double alt[16];
    exp_check(sh_project(order, SH_CS, light_as_printed, NULL, SH_RULE_QUAD, 2000, 0, alt), "quad");

    /* alignment: printed[j] ↔ coefficient j (j < skip) or j+1 (j >= skip) */
    double sd[16];
    for (int i = 0; i < n; i++) sd[i] = sqrt(m2[i] / (seeds - 1));
    /* score: a match counts 1, a match up to sign 1/2 */
    int skip = 15;
    double best = -1;
    for (int k = 0; k < n; k++) {
        double good = 0;
        for (int j = 0; j < NPRINTED; j++) {
            const int i = j < k ? j : j + 1;
            const double tol = 3.0 * sd[i] + 5e-6;
            good += fabs(printed[j] - exact[i]) <= tol ? 1.0 : fabs(printed[j] + exact[i]) <= tol ? 0.5 : 0.0;
        }
        if (good > best) { best = good; skip = k; }
    }
    int sl, sm;
    sh_index_lm(skip, &sl, &sm);

    FILE *f = exp_data("green_vector.dat", "Green 2003 Fig. 7 light, 4 bands: printed vs exact vs MC",
                       "i l m printed exact mc_mean mc_std z=(printed-exact)/mc_std verdict");
    int nrep = 0, nsign = 0;
    double worst_z = 0;
    char signs[256] = "";
    for (int i = 0; i < n; i++) {
        int l, m;
        sh_index_lm(i, &l, &m);
        char id[48];
        snprintf(id, sizeof id, "green-fig7-c%d", i);
        if (i == skip) {
            fprintf(f, "%d %d %d nan %.10f %.10f %.3e nan missing\n", i, l, m, exact[i], mean[i], sd[i]);
            char meas[96];
            snprintf(meas, sizeof meas, "exact %.5f", exact[i]);
            exp_claim(id, "Green 2003, SH Projection",
                      "the 4-band vector of the Figure 7 light has 16 coefficients; the paper prints 15 "
                      "(this one is the one missing: best alignment of the printed list)",
                      "(not printed)", meas, "-", "differs",
                      "green_vector/green_vector.dat; why: the paper prints 15 numbers for 16 coefficients "
                      "and this is the one the printed list leaves out.");
            continue;
        }
        const double pv = printed[i < skip ? i : i - 1];
        const double err = fabs(pv - exact[i]);
        const double z = (pv - exact[i]) / sd[i];
        const int ok = err <= 3.0 * sd[i] + 5e-6;
        const int flipped = !ok && fabs(pv + exact[i]) <= 3.0 * sd[i] + 5e-6;
        nrep += ok;
        nsign += flipped;
        if (ok && fabs(z) > worst_z) worst_z = fabs(z);
        if (flipped) {
            char b[64];
            snprintf(b, sizeof b, "%sy_%d^%d", *signs ? ", " : "", l, m);
            strncat(signs, b, sizeof signs - strlen(signs) - 1);
        }
        fprintf(f, "%d %d %d %.5f %.10f %.10f %.3e %.2f %s\n", i, l, m, pv, exact[i], mean[i], sd[i], z,
                ok ? "reproduced" : flipped ? "differs(sign)" : "differs");
        char pr[32], meas[160], tol[64], st[128];
        snprintf(pr, sizeof pr, "%.5f", pv);
        snprintf(meas, sizeof meas, "exact %.6f; MC(10k) mean %.6f sd %.2e; z %.2f%s", exact[i], mean[i], sd[i], z,
                 flipped ? "; matches with the opposite sign" : "");
        snprintf(tol, sizeof tol, "3 sd + 5e-6 = %.2e", 3.0 * sd[i] + 5e-6);
        snprintf(st, sizeof st, "coefficient y_%d^%d of the Figure 7 light, 10,000 jittered samples", l, m);
        exp_claim_judged(id, "Green 2003, SH Projection", st, pr, meas, tol, ok, "green_vector/green_vector.dat",
                         flipped ? "the printed value is the exact one with the opposite sign (within the tolerance "
                                   "once negated)."
                                 : "the printed value lies outside 3 sd of Green's estimator around the exact "
                                   "coefficient.");
    }
    fclose(f);

    char meas[160];
    snprintf(meas, sizeof meas, "c_0 = %.5f with the -3 inside the second max; %.5f as OCR'd (-3 outside)",
             exact[0], alt[0]);
    const int formula_ok = fabs(alt[0] - printed[0]) < 0.01;
    exp_claim_judged("green-fig7-formula", "Green 2003, SH Projection",
                     "Figure 7's light = max(0,5cos t-4) + max(0,-4 sin(t-pi) cos(p-2.5)) - 3 (as OCR'd)", "0.39925 (c_0)",
                     meas, "|c_0 − printed| < 0.01", formula_ok,
                     "green_vector/green_vector.dat",
                     "with the −3 outside the second max c_0 is far from the printed value; only the −3 inside the max reproduces it.");

    /* Green, "Orthogonal Basis Functions": "a triangular grid of functions
     * per band, giving us a total of n(n+1) coefficients for an n band
     * approximation".  Count the grid P_l^m, 0 <= m <= l < n. */
    {
        const int nb = 4;
        int count = 0;
        for (int l = 0; l < nb; l++)
            for (int m = 0; m <= l; m++) count++;
        char pr[64], me[96];
        snprintf(pr, sizeof pr, "n(n+1) = %d for n = %d", nb * (nb + 1), nb);
        snprintf(me, sizeof me, "%d = n(n+1)/2 (counted: 0 <= m <= l < n)", count);
        exp_claim_judged("green-legendre-count", "Green 2003, Orthogonal Basis Functions",
                         "the triangular grid of associated Legendre functions of an n-band approximation has n(n+1) entries",
                         pr, me, "exact", count == nb * (nb + 1),
                         "green_vector/green_vector.c",
                         "band l holds l + 1 functions P_l^m (0 ≤ m ≤ l), so n bands hold n(n+1)/2, half the printed count.");
    }
    exp_index("![Green's example vector](green_vector.png)\n\n"
              "Green's Figure 7 light projected onto 4 bands: the 15 numbers the paper prints, the exact "
              "projection (adaptive quadrature with the kinks as breakpoints, 1e-12) and the mean ± 2σ of "
              "the estimator he used (stratified Monte Carlo, 10,000 samples) over %d seeds. The paper "
              "prints 15 numbers for 16 coefficients; the printed list lines up with the exact vector when "
              "y_%d^%d (exact %.5f) is taken as the missing one. Under that alignment %d of the 15 printed "
              "numbers lie within 3σ (+ half a printed unit) of the exact value (largest deviation among "
              "them %.2fσ)%s%s. The light formula as OCR'd (−3 outside the second max) gives c₀ = %.4f instead "
              "of the printed 0.39925: the −3 belongs inside the max.",
              seeds, sl, sm, exact[skip], nrep, worst_z, nsign ? "; printed with the opposite sign: " : "",
              signs, alt[0]);
    return 0;
}
