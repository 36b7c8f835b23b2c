/* cap_closed_form — the cap light (1 for θ < t) has a closed-form projection
 * for every band: z_l = 2π K_l ∫_{cos t}^1 P_l(x) dx (sh_cap_zonal).  Compared
 * with (a) product quadrature of the discontinuous function (Gauss-Legendre in
 * cosθ split at the edge would be exact; the plain rule is what a user runs),
 * (b) Green's Maple-generated synth_light() constants for 4 bands (printed
 * with 10 digits in the paper). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exp.h"

/* Green 2003, "Creating Light Sources", synth_light(): Maple output, 4 bands */
static void green_synth_light(double cutoff, double sh[16])
{
    for (int i = 0; i < 16; i++) sh[i] = 0;
    const double t3 = (-cutoff + M_PI) > 0, t5 = cos(cutoff), t6 = t3 * t5, t9 = (-cutoff) > 0;
    const double t11 = t9 * t5, t14 = sin(cutoff), t15 = t14 * t14, t16 = t3 * t15, t18 = t9 * t15;
    const double t21 = t5 * t5, t22 = t21 * t5, t31 = t21 * t21;
    sh[0] = 3.544907702 - 1.772453851 * t3 - 1.772453851 * t6 - 1.772453851 * t9 + 1.772453851 * t11;
    sh[2] = 1.534990062 * t16 - 1.534990062 * t18;
    sh[6] = -1.98166365 * t3 * t22 + 1.98166365 * t6 + 1.98166365 * t9 * t22 - 1.98166365 * t11;
    sh[12] = 2.930920062 * t3 - 2.930920062 * t3 * t31 - 3.517104075 * t16 - 2.930920062 * t9 +
             2.930920062 * t9 * t31 + 3.517104075 * t18;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const int order = 65, n = order * order;
    const double ts_deg[] = {5, 30, 60, 90, 150};
    const int nts = 5;
    const long nodes[] = {64, 256, 1024, 4096};
    double *z = malloc(sizeof(double) * order), *q = malloc(sizeof(double) * n);
    FILE *f = exp_data("cap_quadrature.dat", "cap light: |closed form − product quadrature| per band",
                       "l t_deg nodes abs_err closed_form");
    double worst_green = 0;
    for (int k = 0; k < nts; k++) {
        const double t = ts_deg[k] * M_PI / 180.0;
        exp_check(sh_cap_zonal(t, order, z), "sh_cap_zonal");
        sh_light cap = {SH_LIGHT_CAP, {t, 0}};
        for (int j = 0; j < 4; j++) {
            exp_progress("t = %g deg, %ld theta nodes", ts_deg[k], nodes[j]);
            exp_check(sh_project(order, SH_CS, sh_light_fn, &cap, SH_RULE_QUAD, nodes[j], 0, q), "quad");
            for (int l = 0; l < order; l++)
                fprintf(f, "%d %g %ld %.3e %.17g\n", l, ts_deg[k], nodes[j], fabs(q[sh_index(l, 0)] - z[l]), z[l]);
            fprintf(f, "\n\n");
        }
        double g[16];
        green_synth_light(t, g);
        for (int l = 0; l < 4; l++) {
            const double e = fabs(g[sh_index(l, 0)] - z[l]);
            if (e > worst_green) worst_green = e;
        }
    }
    fclose(f);
    char meas[96];
    snprintf(meas, sizeof meas, "max |Maple − closed form| = %.2e over t in {5,30,60,90,150} deg", worst_green);
    exp_claim_judged("green-synth-light", "Green 2003, Creating Light Sources",
                     "synth_light's Maple-generated constants project the 4-band cap", "10-digit constants", meas, "1e-9",
                     worst_green <= 1e-9,
                     "cap_closed_form/cap_quadrature.dat",
                     "the constants differ from the closed form by more than their 10 printed digits allow.");
    exp_index("![cap closed form vs quadrature](cap_closed_form.png)\n\n"
              "The cap light (1 inside half-angle t) projected by its closed form z_l = 2πK_l ∫_{cos t}^1 P_l "
              "for every band to l = 64, against the product quadrature of the discontinuous function with "
              "64…4096 θ nodes (t = 5°, 30°, 60°, 90°, 150°). The quadrature error decays only like the "
              "node spacing (a step is not band-limited), so a closed form is worth having for every band, not "
              "only the four Green's Maple output gives. Green's synth_light constants agree with the closed "
              "form to %.1e (they are printed with 10 significant digits).",
              worst_green);
    free(z);
    free(q);
    return 0;
}
