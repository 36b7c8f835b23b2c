/* scale_smoothness — Wang et al. (2006) Sec. 2.2, Fig. 3: "elements in
 * different scaling transformation matrices change smoothly with respect to
 * k, and we have empirically found it sufficient to sample 40 values of k in
 * an exponential distribution" (then linear interpolation).
 *
 * (1) Fig. 3: six seeded random non-zero entries of M(k), order 4, for
 *     scaling visibility (plain) with the cone and the linear family,
 *     k = 0.5..2 (the radii of the paper's Fig. 5).
 * (2) Interpolation error (sh_scale_interp_error: tabulate at S values of
 *     k, interpolate every entry, compare with M computed directly on a
 *     dense grid of 400 k) for S = 5..160, geometric vs uniform spacing,
 *     linear vs natural cubic spline, for three family/mode settings. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

static unsigned long rng = 20060406UL;
static unsigned urand(unsigned n)
{
    rng = rng * 6364136223846793005UL + 1442695040888963407UL;
    return (unsigned)((rng >> 33) % n);
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const int N = 4, n = 16, NK = 241;
    const double kmin = 0.5, kmax = 2.0;
    double M[256];

    /* (1) six random non-zero entries, chosen once (seeded) among entries
     * that are not identically 0 or 1 over the range */
    const sh_scale_family fams[2] = {SH_SCALE_CONE, SH_SCALE_LINEAR};
    int pick[6][2];
    {
        sh_scaling s = {SH_SCALE_CONE, 1.37, 0, 0};
        exp_check(sh_scale_matrix(N, &s, M, NULL), "matrix");
        int got = 0;
        while (got < 6) {
            const int i = (int)urand(n), j = (int)urand(n);
            int dup = 0;
            for (int q = 0; q < got; q++) dup |= pick[q][0] == i && pick[q][1] == j;
            if (dup || fabs(M[i * n + j]) <= 1e-12 || j == 0) continue;
            pick[got][0] = i, pick[got][1] = j;
            got++;
        }
    }
    FILE *f = exp_data("fig3_elements.dat", "six seeded random non-zero entries of M(k), order 4, plain",
                       "k then M[i][j] for the six picks (one block per family: cone θ0=45°, linear)");
    for (int fa = 0; fa < 2; fa++) {
        fprintf(f, "# family %s; picks", sh_scale_family_name(fams[fa]));
        for (int q = 0; q < 6; q++) fprintf(f, " M[%d][%d]", pick[q][0], pick[q][1]);
        fputc('\n', f);
        for (int t = 0; t < NK; t++) {
            sh_scaling s = {fams[fa], sh_scale_grid_point(SH_SPACING_GEOMETRIC, kmin, kmax, t, NK), 0, 0};
            exp_check(sh_scale_matrix(N, &s, M, NULL), "matrix");
            fprintf(f, "%.6f", s.k);
            for (int q = 0; q < 6; q++) fprintf(f, " %.10f", M[pick[q][0] * n + pick[q][1]]);
            fputc('\n', f);
        }
        fprintf(f, "\n\n");
    }
    fclose(f);
    FILE *fl = exp_data("fig3_labels.txt", "labels of the six picks", "label");
    for (int q = 0; q < 6; q++) {
        int li, mi, lj, mj;
        sh_index_lm(pick[q][0], &li, &mi);
        sh_index_lm(pick[q][1], &lj, &mj);
        fprintf(fl, "M(%d,%d;%d,%d)\n", li, mi, lj, mj);
    }
    fclose(fl);

    /* (2) interpolation error per sample budget */
    typedef struct { const char *label; sh_scaling s; double a, b; } setting;
    const setting sets[] = {
        {"cone plain, k=0.5..2", {SH_SCALE_CONE, 1, 0, 0}, 0.5, 2.0},
        {"linear plain, k=0.5..2", {SH_SCALE_LINEAR, 1, 0, 0}, 0.5, 2.0},
        {"midrange energy, k=0.05..0.9", {SH_SCALE_MIDRANGE, 0, 0, 1}, 0.05, 0.9},
    };
    const int budgets[] = {5, 10, 20, 40, 80, 160};
    FILE *fi = exp_data("interp.dat", "interpolation error of M(k) over k, order 4, 400 dense k",
                        "samples max_err(geom,linear) rms(geom,linear) max(geom,cubic) rms(geom,cubic) "
                        "max(unif,linear) rms(unif,linear) max(unif,cubic) rms(unif,cubic); one block per setting");
    char table[8192];
    int tl = snprintf(table, sizeof table,
                      "| setting | samples | geometric, linear | geometric, cubic | uniform, linear | uniform, cubic |\n"
                      "|---|---|---|---|---|---|\n");
    double paper_cone = 0, paper_lin = 0, cubic_cone40 = 0;
    static const char *const claim_ids[3] = {"scale-interp-budget-cone", "scale-interp-budget-linear",
                                             "scale-interp-budget-midrange"};
    for (int st = 0; st < 3; st++) {
        /* the interpolation table, one ledger row per setting ("the
         * interpolation table in the claims ledger") */
        char row[2048];
        int rl = 0;
        row[0] = '\0';
        exp_progress("interpolation: %s", sets[st].label);
        fprintf(fi, "# %s\n", sets[st].label);
        for (int b = 0; b < 6; b++) {
            double v[8];
            for (int sp = 0; sp < 2; sp++)
                for (int ip = 0; ip < 2; ip++) {
                    sh_scale_interp_result r;
                    exp_check(sh_scale_interp_error(N, &sets[st].s, budgets[b], sp ? SH_SPACING_UNIFORM : SH_SPACING_GEOMETRIC,
                                                    sets[st].a, sets[st].b, ip ? SH_INTERP_CUBIC : SH_INTERP_LINEAR, 400, &r),
                              "interp");
                    v[(sp * 2 + ip) * 2] = r.max_error;
                    v[(sp * 2 + ip) * 2 + 1] = r.rms_error;
                }
            fprintf(fi, "%d", budgets[b]);
            for (int q = 0; q < 8; q++) fprintf(fi, " %.3e", v[q]);
            fputc('\n', fi);
            tl += snprintf(table + tl, sizeof table - tl, "| %s | %d | %.1e (rms %.1e) | %.1e (rms %.1e) | %.1e (rms %.1e) | %.1e (rms %.1e) |\n",
                           sets[st].label, budgets[b], v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
            if (budgets[b] == 40 && st == 0) { paper_cone = v[0]; cubic_cone40 = v[2]; }
            if (budgets[b] == 40 && st == 1) paper_lin = v[0];
            if (budgets[b] == 40)
                rl += snprintf(row + rl, sizeof row - (size_t)rl,
                               "order 4, S = 40: geometric linear %.1e, cubic %.1e; uniform linear %.1e, cubic %.1e; "
                               "every S: index.md#scale_smoothness",
                               v[0], v[2], v[4], v[6]);
        }
        char stmt[256];
        snprintf(stmt, sizeof stmt,
                 "interpolation error of M(k), %s: the paper's 40 geometric samples, linear, against other budgets, "
                 "uniform spacing and cubic splines",
                 sets[st].label);
        exp_claim(claim_ids[st], "Wang et al. 2006, Sec. 2.2", stmt, "-", row, "-", "not-applicable",
                  "scale_smoothness/interp.dat; why: the paper prints no interpolation error to compare with; the row "
                  "records shlab's measurement.");
        fprintf(fi, "\n\n");
    }
    fclose(fi);

    /* the scale of what interpolation error competes with: the truncation
     * error of scaling at order 4 (sphere occluder, rho = r/2, cone family) */
    sh_scale_scene sph = {SH_SCENE_SPHERE, 0.5, 0, 0, NULL, NULL, NULL, 0, {0, 0, 0}, 0};
    sh_scaling sc = {SH_SCALE_CONE, 1.5, acos(0.5), 0};
    sh_scale_scene_err e;
    exp_check(sh_scale_scene_errors(&sph, N, SH_CS, &sc, 1.5, NULL, &e, NULL), "scene");

    char me[400];
    snprintf(me, sizeof me,
             "order 4, 40 geometric samples, linear: max entry error %.1e (cone), %.1e (linear family, kink at k = 1), "
             "cubic %.1e (cone); scaling's own error, sphere scene, k = 1.5: %.2f",
             paper_cone, paper_lin, cubic_cone40, e.err_scaled);
    const int enough = paper_cone < 0.01 * e.err_scaled;
    exp_claim_judged("wang-40-samples", "Wang et al. 2006, Sec. 2.2",
                     "M changes smoothly with k (Fig. 3); 40 exponentially spaced samples of k with linear interpolation suffice",
                     "40 samples, qualitative", me, "interpolation error < 1 % of the scaling error", enough,
                     "scale_smoothness/interp.dat",
                     "40 samples leave an interpolation error above 1 % of the scaling's own error.");

    exp_index("![six entries of M against k](scale_smoothness_fig3.png)\n\n"
              "Figure 3 of the paper reproduced in spirit: six entries of the order-4 scaling matrix, picked at random "
              "(seeded) among the non-zero ones, against k = d/r from 0.5 to 2 (plain scaling of visibility), for the "
              "cone family (θ0 = 45°) and the linear family. The entries are smooth in k except that the linear "
              "family's M(k) has a kink at k = 1, where τ = min(kθ, π) starts to saturate at π.\n\n"
              "![interpolation error against samples](scale_smoothness_interp.png)\n\n"
              "Interpolating M(k) from S tabulated values (largest absolute entry error over a dense grid of 400 k "
              "and all m_i = m_j entries; `shlab scale-interp`). Linear interpolation converges like S⁻²; the "
              "natural cubic spline is 4–10× better at the same budget but also only S⁻² (its natural end "
              "conditions, and the linear family's kink at k = 1). Geometric spacing beats uniform for the d/r "
              "families (features crowd at small k) but not for the mid-range family, whose entries change fastest "
              "as |k| → 1. The paper's choice (40 samples, "
              "geometric, linear) gives %.1e for the cone family, far below the truncation error of order-4 "
              "scaling itself (%.2f relative L2 in the sphere scene at k = 1.5), so the 40 samples are indeed "
              "enough; 10 samples would be too (see the table).\n\n%s",
              paper_cone, e.err_scaled, table);
    return 0;
}
