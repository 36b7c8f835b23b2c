/* taylor_error — Křivánek et al. 2005, Sec. 3.2 / Figure 3 (error of the 1st,
 * 1.5th and 2nd order Taylor rotation vs β: max and mean singular value of
 * D(β) and the error for the Phong lobe cos^7), extended to orders 2–16 and
 * β to 90°; Appendix B (β_lim = 1.25a) checked and replaced by a measured
 * table: the largest β at which the lobe error stays ≤ 1e-2 and ≤ 1e-3.
 * Also measured: whether "the average E(β) over all unit Λ is the average
 * singular value" (Monte Carlo over unit vectors). */
#include <gsl/gsl_rng.h>
#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

#define DEG (M_PI / 180.0)
static const sh_rot_method TY[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    char me[1024];

    /* ---- Figure 3: orders 5 and 8, β = 0..45° --------------------------- */
    static const int forders[2] = {5, 8};
    sh_taylor_err at25[2][3], at10[2][3];
    FILE *f = exp_data("figure3.dat", "Figure 3: error of the Taylor rotation about y (unit vectors; lobe cos^7)",
                       "beta_deg max_t1 mean_t1 lobe_t1 max_t15 mean_t15 lobe_t15 max_t2 mean_t2 lobe_t2 (blocks of orders 5, 8 separated by two blank lines)");
    for (int o = 0; o < 2; o++) {
        for (int s = 0; s <= 180; s++) {
            const double bd = 0.25 * s;
            fprintf(f, "%g", bd);
            for (int t = 0; t < 3; t++) {
                sh_taylor_err e;
                exp_check(sh_taylor_error(forders[o], TY[t], bd * DEG, 7, &e), "taylor error");
                fprintf(f, " %.6e %.6e %.6e", e.max, e.mean, e.lobe);
                if (s == 100) at25[o][t] = e;
                if (s == 40) at10[o][t] = e;
            }
            fprintf(f, "\n");
        }
        fprintf(f, "\n\n");
    }
    fclose(f);

    /* ---- extension: orders 2..16, β = 0..90° ---------------------------- */
    FILE *fx = exp_data("extended.dat", "error of the Taylor rotation, orders 2..16, beta 0..90 deg (lobe cos^7)",
                        "order beta_deg max_t1 mean_t1 lobe_t1 max_t15 mean_t15 lobe_t15 max_t2 mean_t2 lobe_t2 (one block per order)");
    double cross8 = -1; /* first β where taylor2's max error exceeds taylor1's, order 8 */
    for (int n = 2; n <= 16; n++) {
        exp_progress("taylor_error: order %d of 16", n);
        for (int s = 0; s <= 90; s++) {
            fprintf(fx, "%d %d", n, s);
            sh_taylor_err e[3];
            for (int t = 0; t < 3; t++) {
                exp_check(sh_taylor_error(n, TY[t], s * DEG, 7, &e[t]), "taylor error");
                fprintf(fx, " %.6e %.6e %.6e", e[t].max, e[t].mean, e[t].lobe);
            }
            if (n == 8 && cross8 < 0 && s > 0 && e[2].max > e[0].max) cross8 = s;
            fprintf(fx, "\n");
        }
        fprintf(fx, "\n\n");
    }
    fclose(fx);

    /* ---- measured alternative to Appendix B ----------------------------- */
    FILE *fl = exp_data("lobe_limits.dat", "largest beta (deg) with lobe error (cos^7, unit vector) <= tol for every beta' <= beta",
                        "order t1_1e-2 t15_1e-2 t2_1e-2 t1_1e-3 t15_1e-3 t2_1e-3");
    double lim[17][3][2];
    char table[4096] = "| order | T1 ≤1e-2 | T1.5 ≤1e-2 | T2 ≤1e-2 | T1 ≤1e-3 | T1.5 ≤1e-3 | T2 ≤1e-3 |\n|---|---|---|---|---|---|---|\n";
    for (int n = 2; n <= 16; n++) {
        fprintf(fl, "%d", n);
        for (int q = 0; q < 2; q++)
            for (int t = 0; t < 3; t++)
                exp_check(sh_taylor_lobe_limit(n, TY[t], 7, q ? 1e-3 : 1e-2, M_PI / 2, 0.25 * DEG, &lim[n][t][q]), "limit");
        char row[256];
        snprintf(row, sizeof row, "| %d | %.2f° | %.2f° | %.2f° | %.2f° | %.2f° | %.2f° |\n", n, lim[n][0][0] / DEG,
                 lim[n][1][0] / DEG, lim[n][2][0] / DEG, lim[n][0][1] / DEG, lim[n][1][1] / DEG, lim[n][2][1] / DEG);
        strcat(table, row);
        for (int q = 0; q < 2; q++)
            for (int t = 0; t < 3; t++) fprintf(fl, " %.4f", lim[n][t][q] / DEG);
        fprintf(fl, "\n");
    }
    fclose(fl);

    /* ---- Appendix B arithmetic ------------------------------------------ */
    const double rR = 0.1, k_lin = 1.0 / (1.0 / sqrt(2.0) + rR), k_deg = k_lin / DEG;
    FILE *fb = exp_data("appendixB.dat", "beta_lim for the radiance-cache error a: linearised a/(1/sqrt2 + r/R) vs exact 2 asin(a/(sqrt2 + 2r/R)), r/R = 0.1",
                        "a beta_lin_deg beta_exact_deg beta_paper_1.25a_deg");
    for (int q = 1; q <= 10; q++) {
        const double a = 0.1 * q, x = a / (sqrt(2.0) + 2 * rR);
        fprintf(fb, "%.1f %.4f %.4f %.4f\n", a, k_lin * a / DEG, x <= 1 ? 2 * asin(x) / DEG : 180.0, 1.25 * a / DEG);
    }
    fclose(fb);
    snprintf(me, sizeof me, "a·(1/√2 + 0.1)⁻¹ = %.4f·a", k_lin);
    char why[256];
    snprintf(why, sizeof why, "%.4f rounds to %.2f, not 1.25.", k_lin, k_lin);
    exp_claim_judged("krivanek-appB-125", "Křivánek et al. 2005, App. B", "with r/R_i = 0.1, β_lim = 1.25a", "1.25a", me,
                     "3 significant digits", fabs(k_lin - 1.25) < 0.005, "taylor_error/appendixB.dat", why);
    snprintf(me, sizeof me, "%.4f rad = %.2f° per unit a (1.25 rad = %.2f°)", k_lin, k_deg, 1.25 / DEG);
    snprintf(why, sizeof why, "neither %.4f rad (%.2f°) nor 1.25 rad (%.2f°) is 70.1°.", k_lin, k_deg, 1.25 / DEG);
    exp_claim_judged("krivanek-appB-deg", "Křivánek et al. 2005, App. B", "in degrees β_lim = 70.1a", "70.1a", me, "0.1°",
                     fabs(k_deg - 70.1) < 0.1, "taylor_error/appendixB.dat", why);
    /* the exact inverse against the linearised one at a = 0.1 and 1 */
    double lin_gap[2];
    for (int q = 0; q < 2; q++) {
        const double a = q ? 1.0 : 0.1;
        lin_gap[q] = 2 * asin(a / (sqrt(2.0) + 2 * rR)) / (k_lin * a) - 1;
    }
    snprintf(me, sizeof me, "f(β) = (2r/R_i + √2) sin(β/2), so β_lim = 2 asin(a/(2r/R_i + √2)); the linear β_lim is "
             "%.2f %% (a = 0.1) and %.1f %% (a = 1) below it", 100 * lin_gap[0], 100 * lin_gap[1]);
    exp_claim("krivanek-appB-inverse", "Křivánek et al. 2005, App. B",
              "the inverse of f(β) = (2r/R_i) sin(β/2) + √(1 − cos β) cannot be found analytically", "stated", me,
              "exact", "differs",
              "taylor_error/appendixB.dat; why: √(1 − cos β) = √2 sin(β/2), so f is a multiple of sin(β/2) and "
              "inverts in closed form.");
    snprintf(me, sizeof me,
             "lobe error ≤ 1e-2 to %.1f°/%.1f°/%.1f° (order 5, T1/T1.5/T2), %.1f°/%.1f°/%.1f° (order 10), for any a; "
             "β_lim = 1.25a is %.1f° at a = 0.1, %.1f° at a = 0.3",
             lim[5][0][0] / DEG, lim[5][1][0] / DEG, lim[5][2][0] / DEG, lim[10][0][0] / DEG, lim[10][1][0] / DEG,
             lim[10][2][0] / DEG, 1.25 * 0.1 / DEG, 1.25 * 0.3 / DEG);
    exp_claim("krivanek-appB-accuracy", "Křivánek et al. 2005, App. B",
              "β_lim = 1.25a (Sec. 4.2) lets the rotation error grow with the cache error a", "β_lim = 1.25a", me, "-",
              "not-applicable",
              "taylor_error/lobe_limits.dat; why: the paper states no accuracy bound for β_lim to compare with; the row "
              "records the measured limits.");

    /* ---- Sec. 3.2 claims -------------------------------------------------- */
    snprintf(me, sizeof me,
             "lobe error (unit cos^7 vector) at 25°, T1/T1.5/T2: order 5 %.3f/%.3f/%.3f, order 8 %.3f/%.3f/%.3f; T1.5 "
             "reaches 1e-2 at %.1f° (order 5), %.1f° (order 8)",
             at25[0][0].lobe, at25[0][1].lobe, at25[0][2].lobe, at25[1][0].lobe, at25[1][1].lobe, at25[1][2].lobe,
             lim[5][1][0] / DEG, lim[8][1][0] / DEG);
    snprintf(why, sizeof why, "at 25° the T1.5 lobe error is %.0f %% of the lobe's norm; 1e-2 holds only below %.1f°.",
             100 * at25[0][1].lobe, lim[5][1][0] / DEG);
    exp_claim_judged("krivanek-sec32-lobe25", "Křivánek et al. 2005, Sec. 3.2",
                     "the results for the Phong lobe cos^7 (Fig. 3) show good accuracy up to β = 25°",
                     "good accuracy up to 25° (Fig. 3 not legible in our copy)", me, "relative error ≤ 1e-2",
                     at25[0][1].lobe <= 1e-2, "taylor_error/figure3.dat", why);
    int order_ok = 1;
    for (int o = 0; o < 2; o++)
        if (!(at10[o][2].max < at10[o][1].max && at10[o][1].max < at10[o][0].max && at10[o][2].lobe < at10[o][1].lobe &&
              at10[o][1].lobe < at10[o][0].lobe))
            order_ok = 0;
    snprintf(me, sizeof me,
             "at 10°, order 5 max σ: T1 %.3f > T1.5 %.3f > T2 %.3f; order 8: %.3f > %.3f > %.3f; but for order 8 T2's max error exceeds T1's from β = %.0f° on",
             at10[0][0].max, at10[0][1].max, at10[0][2].max, at10[1][0].max, at10[1][1].max, at10[1][2].max, cross8);
    exp_claim_judged("krivanek-fig3-ordering", "Křivánek et al. 2005, Fig. 3",
                     "the 2nd-order expansion is more accurate than the 1.5th, which is more accurate than the 1st",
                     "curves", me, "ordering at small β", order_ok, "taylor_error/figure3.dat, extended.dat",
                     "at 10° the expansions' errors are not in the stated order.");

    /* "Average E(β) over all unit Λ is the average singular value" — Monte Carlo */
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 42);
    char mc[512] = "";
    int mc_diff = 0;
    for (int c = 0; c < 2; c++) {
        const int n = 5, N = n * n;
        const double beta = (c ? 20 : 10) * DEG;
        double *sv = malloc(N * sizeof *sv), *v = malloc(N * sizeof *v), *gv = malloc(N * sizeof *gv), *av = malloc(N * sizeof *av);
        exp_check(sh_taylor_singular_values(n, SH_ROT_TAYLOR15, beta, sv), "sv");
        double mean = 0, rms = 0;
        for (int i = 0; i < N; i++) mean += sv[i] / N, rms += sv[i] * sv[i] / N;
        rms = sqrt(rms);
        sh_rotation r;
        sh_rotation_from_euler(0, beta, 0, &r);
        sh_rot_plan *pe, *pa;
        exp_check(sh_rot_plan_create(n, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &pe), "plan");
        exp_check(sh_rot_plan_create(n, SH_ROT_TAYLOR15, SH_PREC_DOUBLE, SH_CS, &pa), "plan");
        exp_check(sh_rot_plan_set(pe, &r), "set");
        exp_check(sh_rot_plan_set(pa, &r), "set");
        double avg = 0;
        const int M = 20000;
        for (int s = 0; s < M; s++) {
            double nn = 0;
            for (int i = 0; i < N; i++) {
                v[i] = gsl_ran_gaussian(rng, 1.0);
                nn += v[i] * v[i];
            }
            for (int i = 0; i < N; i++) v[i] /= sqrt(nn);
            sh_rot_plan_apply(pe, v, gv);
            sh_rot_plan_apply(pa, v, av);
            double e = 0;
            for (int i = 0; i < N; i++) e += (gv[i] - av[i]) * (gv[i] - av[i]);
            avg += sqrt(e) / M;
        }
        sh_rot_plan_free(pe);
        sh_rot_plan_free(pa);
        char s[200];
        snprintf(s, sizeof s, "%sβ = %d°: mean σ %.4f, average E %.4f, RMS σ %.4f", c ? "; " : "order 5, T1.5, 20000 "
                 "random unit Λ: ", c ? 20 : 10, mean, avg, rms);
        strcat(mc, s);
        if (fabs(avg - mean) > 0.05 * mean) mc_diff = 1;
        free(sv), free(v), free(gv), free(av);
    }
    gsl_rng_free(rng);
    exp_claim("krivanek-sec32-mean", "Křivánek et al. 2005, Sec. 3.2",
              "the average of E(β) over all unit-length Λ is the average singular value of D(β)", "stated", mc,
              "5% (Monte Carlo error ~0.5%)", mc_diff ? "differs" : "reproduced",
              mc_diff ? "taylor_error; why: E‖DΛ‖ over the unit sphere is not the mean σ (diag(1,0): 2/π against 1/2); "
                        "E‖DΛ‖² is the mean σ²."
                      : "taylor_error ('mean' follows docs/CONVENTIONS.md: mean σ)");
    exp_claim("krivanek-sec32-max", "Křivánek et al. 2005, Sec. 3.2",
              "the maximum of E(β) over unit Λ is the largest singular value of D(β)", "stated",
              "the spectral norm's identity; GSL's Jacobi SVD σ₁ agrees with √λ_max(DᵀD) to 1e-12 (tests/taylor/test_taylor.c)",
              "1e-12", "reproduced", "tests/taylor/test_taylor.c test_error_measures");

    exp_index("![Figure 3 reproduced: max, mean and lobe error vs β for orders 5 and 8](taylor_error_fig3.png)\n\n"
              "Figure 3 of Křivánek et al. reproduced ([figure3.dat](figure3.dat)): rows max σ(D), mean σ(D), lobe error "
              "‖D c‖ for the unit-length cos⁷ lobe about +z; columns order 5 and 8; three expansions. The paper's plots "
              "are not legible in our copy, so only their shape and the text can be checked. At 25° the lobe error is "
              "%.2f (T1.5, order 5) and %.2f (order 8) of the lobe's norm — not what we would call good accuracy. "
              "For order 8, T2's max error exceeds T1's from β = %.0f° on: above a few tens of degrees the "
              "higher-order expansions are the worse ones.\n\n"
              "![Extension: orders 2–16, β to 90°](taylor_error_ext.png)\n\n"
              "Extension to orders 2–16 and β to 90° ([extended.dat](extended.dat)).\n\n"
              "**Appendix B.** With r/R_i = 0.1, a/(1/√2 + 0.1) = %.4f·a (printed 1.25a), i.e. %.2f°·a (printed 70.1a; "
              "1.25 rad would be 71.62°). The inverse of f is not impossible: f(β) = (2r/R_i + √2) sin(β/2), so "
              "β_lim = 2 asin(a/(2r/R_i + √2)) exactly ([appendixB.dat](appendixB.dat)). β_lim bounds nothing about "
              "the rotation error; the measured alternative is the largest β at which the lobe error (unit cos⁷ "
              "vector) stays below a tolerance ([lobe_limits.dat](lobe_limits.dat)):\n\n%s\n",
              at25[0][1].lobe, at25[1][1].lobe, cross8, k_lin, k_deg, table);
    return 0;
}
