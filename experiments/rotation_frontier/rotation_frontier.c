/* rotation_frontier — the speed–accuracy frontier of the rotation methods:
 * error (lobe and max, docs/CONVENTIONS.md) against cost, for β = 5°, 15°, 25°
 * and orders 4..12, every exact and approximate method built in.
 *
 * References
 *  [1] J. Křivánek et al., "Fast Approximation to Spherical Harmonic
 *      Rotation" (2005), Sec. 3.2 (error measures) and Table 1 (speed).
 *  [2] docs/CONVENTIONS.md: max = σ_max(D), lobe = ‖D c‖₂, c the unit coefficient
 *      vector of max(0, cosθ)^7 about +z; D = R_method − R_exact.
 *
 * Errors by sh_rot_errws (rotation_choose.c): D block by block against the
 * MPFR reference at a rotation with the given β and seeded α, γ (the
 * measures do not depend on α, γ, see there).  Cost, deterministic: the
 * multiplications the kernels count per rotation (set + apply); machine-
 * dependent (timing part): ns per rotation from a 3×3 matrix, every method
 * of one order an entry of one interleaved run (sh_bench_interleaved), with
 * ratios to zxzxz paired by round.  Exact methods sit at rounding error; the
 * plots clip errors below 1e-17 to 1e-17.
 */
#include "exp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CLIP 1e-17
enum { NLO = 4, NHI = 12, NM = SH_ROT_NMETHODS };

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const double betas[3] = {5, 15, 25};
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    bo.max_beta = 25 * M_PI / 180;
    sh_rot_method ms[NM];
    int nm = 0;
    for (int m = 0; m < NM; m++)
        if (m != SH_ROT_REFERENCE && m != SH_ROT_Z && sh_rot_method_max_order((sh_rot_method)m) >= NHI)
            ms[nm++] = (sh_rot_method)m;
    static double mu[NM][NHI + 1], err[NM][3][NHI + 1][2];
    double worst_exact = 0;
    FILE *fm = exp_data("methods.txt", "methods in frontier.dat, in index order", "name");
    for (int k = 0; k < nm; k++) {
        fprintf(fm, "%s\n", sh_rot_method_name(ms[k]));
        exp_progress("rotation_frontier: errors of %s", sh_rot_method_name(ms[k]));
        for (int n = NLO; n <= NHI; n++) {
            sh_bench_entry e;
            exp_check(sh_rot_bench_entry(n, ms[k], SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &bo, &e), "entry");
            mu[ms[k]][n] = e.mults;
            sh_bench_entry_free(&e);
        }
        for (int b = 0; b < 3; b++)
            for (int n = NLO; n <= NHI; n++) {
                sh_rot_errws *w;
                sh_rotation rot;
                sh_rot_error e;
                exp_check(sh_rot_errws_create(n, 7, 1, &w), "errws");
                /* seeded α, γ (fixed per β and order) */
                const double a = sin(12.9898 * n + 78.233 * b) * M_PI, g = cos(4.1414 * n + 3.7 * b) * M_PI;
                exp_check(sh_rotation_from_euler(a, betas[b] * M_PI / 180, g, &rot), "rotation");
                exp_check(sh_rot_errws_set(w, &rot), "set");
                exp_check(sh_rot_errws_eval(w, ms[k], SH_PREC_DOUBLE, &e), "eval");
                sh_rot_errws_free(w);
                if (sh_rot_method_is_exact(ms[k])) worst_exact = fmax(worst_exact, e.max);
                err[ms[k]][b][n][0] = e.lobe;
                err[ms[k]][b][n][1] = e.max;
            }
    }
    fclose(fm);
    /* deterministic: error against counted multiplications */
    FILE *f = exp_data("frontier.dat", "error vs counted multiplications per rotation (index: method; blocks: beta 5, 15, 25 deg)",
                       "method beta_deg order mults lobe max lobe_clipped max_clipped");
    fprintf(f, "# errors clipped at %g for the log plots (columns 7, 8); exact methods sit at rounding error\n", CLIP);
    char best[3][256];
    double best_mu[3] = {INFINITY, INFINITY, INFINITY};
    for (int k = 0; k < nm; k++) {
        for (int b = 0; b < 3; b++) {
            for (int n = NLO; n <= NHI; n++) {
                const double lobe = err[ms[k]][b][n][0], mx = err[ms[k]][b][n][1];
                fprintf(f, "%s %g %d %.6g %.6g %.6g %.6g %.6g\n", sh_rot_method_name(ms[k]), betas[b], n, mu[ms[k]][n],
                        lobe, mx, fmax(lobe, CLIP), fmax(mx, CLIP));
                if (n == 8 && lobe <= 1e-3 && mu[ms[k]][n] < best_mu[b]) {
                    best_mu[b] = mu[ms[k]][n];
                    snprintf(best[b], sizeof best[b], "%s (%.0f multiplications, lobe %.2g)", sh_rot_method_name(ms[k]),
                             mu[ms[k]][n], lobe);
                }
            }
            fprintf(f, "\n");
        }
        fprintf(f, "\n");
    }
    fclose(f);
    const int taylor = sh_rot_method_max_order(SH_ROT_TAYLOR15) > 0;
    exp_index("Speed–accuracy frontier ([frontier.dat](frontier.dat)): for β = 5°, 15°, 25° and orders 4–12, "
              "the error of each method against the MPFR reference (lobe = ‖D c‖ with c the unit max(0,cosθ)^7 "
              "lobe, and max = σ_max(D), D = R_method − R_exact, one rotation with seeded α, γ per point) "
              "against its cost: here the multiplications its kernels count per rotation (set + apply, "
              "deterministic); against time per rotation in the timing report. Exact methods sit at rounding "
              "error (largest max error %.1e); the log plots clip errors below %g to %g. Fewest "
              "multiplications with lobe error ≤ 1e-3 at order 8: β = 5°: %s; 15°: %s; 25°: %s.%s\n\n"
              "![lobe error vs multiplications](rotation_frontier_lobe.png)\n\n"
              "![max error vs multiplications](rotation_frontier_max.png)\n",
              worst_exact, CLIP, CLIP, best[0], best[1], best[2],
              taylor ? "" : " The Taylor methods are not built in this tree yet; after their merge they appear "
                            "here without change.");
    char buf[2048];
    snprintf(buf, sizeof buf, "largest max error of an exact method over beta 5-25 deg, orders 4-12: %.2e", worst_exact);
    exp_claim_judged("frontier-exact-rounding", "shlab goal", "exact methods are at rounding error on the frontier (<= 1e-13)",
                     "-", buf, "1e-13", worst_exact <= 1e-13,
                     "rotation_frontier/frontier.dat",
                     "an exact method's max error exceeds 1e-13.");

    /* ---- timing part: every method of an order interleaved ----------------- */
    exp_part("timing");
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.samples = 11;
    cfg.min_sample_ms = 2;
    const int S = cfg.samples;
    static double smp[NM * 64];
    static sh_bench_stats st[NHI + 1][NM];
    static sh_bench_ratio rz[NHI + 1][NM];
    static sh_bench_noise nz[NHI + 1];
    int kz = -1;
    for (int k = 0; k < nm; k++)
        if (ms[k] == SH_ROT_ZXZXZ) kz = k;
    if (kz < 0) exp_check(SH_ENOTSUP, "zxzxz must be built in");
    for (int n = NLO; n <= NHI; n++) {
        exp_progress("rotation_frontier: timing order %d (%d methods interleaved)", n, nm);
        sh_bench_entry e[NM];
        for (int k = 0; k < nm; k++)
            exp_check(sh_rot_bench_entry(n, ms[k], SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &bo, &e[k]), "entry");
        exp_check(sh_bench_interleaved(e, nm, &cfg, smp, st[n], &nz[n]), "bench");
        for (int k = 0; k < nm; k++) {
            exp_check(sh_bench_paired_ratio(smp + (size_t)k * S, smp + (size_t)kz * S, S, cfg.noise_spread, &rz[n][k]), "ratio");
            sh_bench_entry_free(&e[k]);
        }
    }
    f = exp_data("frontier_time.dat", "error vs ns per rotation (index: method; blocks: beta 5, 15, 25 deg); times: "
                                      "medians of one interleaved run per order",
                 "method beta_deg order ns_median ns_q1 ns_q3 ratio_to_zxzxz ratio_q1 ratio_q3 lobe_clipped max_clipped run_noisy");
    for (int k = 0; k < nm; k++) {
        for (int b = 0; b < 3; b++) {
            for (int n = NLO; n <= NHI; n++)
                fprintf(f, "%s %g %d %.6g %.6g %.6g %.5g %.5g %.5g %.6g %.6g %d\n", sh_rot_method_name(ms[k]), betas[b], n,
                        st[n][k].ns_median, st[n][k].ns_q1, st[n][k].ns_q3, rz[n][k].median, rz[n][k].q1, rz[n][k].q3,
                        fmax(err[ms[k]][b][n][0], CLIP), fmax(err[ms[k]][b][n][1], CLIP), nz[n].noisy);
            fprintf(f, "\n");
        }
        fprintf(f, "\n");
    }
    fclose(f);
    /* the fastest exact method at every order: zxzxz, if every other exact
     * method's paired ratio to it stays above 1 (quartiles widened by 5 %) */
    int noisy = 0, straddle = 0, slower = 0;
    char why[512] = "", who[256] = "";
    double least = INFINITY;
    const char *least_m = "-";
    int least_n = 0;
    for (int n = NLO; n <= NHI; n++) {
        if (nz[n].offcpu > cfg.noise_offcpu || nz[n].load > cfg.noise_load) noisy = 1;
        for (int k = 0; k < nm; k++) {
            if (k == kz || !sh_rot_method_is_exact(ms[k])) continue;
            if (st[n][k].spread > cfg.noise_spread || st[n][kz].spread > cfg.noise_spread || rz[n][k].noisy) noisy = 1;
            const exp_side side = exp_ratio_side(&rz[n][k], 1, INFINITY);
            if (side == EXP_OUTSIDE) {
                slower = 1;
                snprintf(who + strlen(who), sizeof who - strlen(who), "%s%s at n=%d", *who ? ", " : "",
                         sh_rot_method_name(ms[k]), n);
            } else if (side == EXP_STRADDLES) straddle = 1;
            if (rz[n][k].median < least) {
                least = rz[n][k].median;
                least_m = sh_rot_method_name(ms[k]);
                least_n = n;
            }
        }
        if (nz[n].noisy && !*why) snprintf(why, sizeof why, "n=%d: %s", n, nz[n].why);
    }
    if (noisy && !*why) snprintf(why, sizeof why, "a time or ratio spread above %.0f %%", 100 * cfg.noise_spread);
    if (noisy && strlen(why) < 120) snprintf(buf, sizeof buf, "not measured (noisy run: %s)", why);
    else if (noisy) snprintf(buf, sizeof buf, "not measured (noisy run: frontier_time.dat)");
    else
        snprintf(buf, sizeof buf, "smallest paired ratio of another exact method to zxzxz over orders %d-%d: %s at n=%d, %.2f%s%s",
                 NLO, NHI, least_m, least_n, least, slower ? "; faster than zxzxz: " : "", who);
    const char *fv = noisy ? "not-measured" : slower ? "differs" : straddle ? "inconclusive" : "reproduced";
    char fev[256];
    exp_claim("frontier-fastest-exact", "shlab goal",
              "zxzxz is the fastest exact method per rotation from a 3x3 matrix at orders 4-12", "-", buf,
              "every other exact method's paired ratio to zxzxz > 1 (quartiles widened by 5%)", fv,
              exp_evidence(fev, sizeof fev, "rotation_frontier/timing/frontier_time.dat", fv,
                           slower ? "another exact method is faster than zxzxz at some order (measured cell)." : NULL));
    char fast[3][256];
    for (int b = 0; b < 3; b++) {
        double bns = INFINITY;
        snprintf(fast[b], sizeof fast[b], "none");
        for (int k = 0; k < nm; k++)
            if (err[ms[k]][b][8][0] <= 1e-3 && st[8][k].ns_median < bns) {
                bns = st[8][k].ns_median;
                snprintf(fast[b], sizeof fast[b], "%s (%.0f ns, lobe %.2g)", sh_rot_method_name(ms[k]), bns,
                         err[ms[k]][b][8][0]);
            }
    }
    char fastest[1024];
    if (nz[8].noisy)
        snprintf(fastest, sizeof fastest, "Not judged: the run at order 8 broke the noise criterion (%s)", nz[8].why);
    else
        snprintf(fastest, sizeof fastest, "Fastest method with lobe error ≤ 1e-3 at order 8: β = 5°: %s; 15°: %s; 25°: %s",
                 fast[0], fast[1], fast[2]);
    exp_index("The frontier against time per rotation from a 3×3 matrix ([frontier_time.dat](frontier_time.dat)): "
              "at each order all %d methods timed in one interleaved run (samples ≥ %.0f ms, %d rounds; points "
              "are medians). %s.\n\n"
              "![lobe error vs time](rotation_frontier_lobe_time.png)\n",
              nm, cfg.min_sample_ms, S, fastest);
    return 0;
}
