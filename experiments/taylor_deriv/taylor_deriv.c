/* taylor_deriv — Křivánek et al. 2005: Figure 2 (J and J² of bands 1..3),
 * the sparsity claims of Sec. 3, Appendix A (the derivative recursion), the
 * multiplication counts of Sec. 3.1 and Appendix C, and the rotation
 * procedure of Sec. 3 (shRotYdiff15 between two z rotations) taken literally.
 *
 * Figure 2 is computed in the four combinations convention (cs, nocs) ×
 * direction (function rotation R_sh(R), frame rotation R_sh(R)ᵀ); the frame
 * rotation's derivative at 0 is Jᵀ = −J (and J² unchanged). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

#include "../../data/papers/krivanek2005_fig2.h"

#define NB(n) sh_rot_block_offset(n)

/* Paper's Appendix C z rotation, literally: v^{−m} = λ^{−m}cos − λ^m sin, v^m = λ^{−m} sin + λ^m cos. */
static void paper_z(int order, double a, double *x)
{
    for (int l = 1; l < order; l++)
        for (int m = 1; m <= l; m++) {
            const double c = cos(m * a), s = sin(m * a), lm = x[l * (l + 1) - m], lp = x[l * (l + 1) + m];
            x[l * (l + 1) - m] = lm * c - lp * s;
            x[l * (l + 1) + m] = lm * s + lp * c;
        }
}

/* Paper's shRotYdiff15, literally (flat index; the printed code's last line
 * uses the loop variable outside its scope: written here with i = n²−1). */
static void paper_ydiff15(int order, double *dest, const double *src, const double *dySubDiag,
                          const double *ddyDiag, double beta)
{
    const double bbeta = 0.5 * beta * beta;
    const int N = order * order;
    dest[0] = src[0];
    int i;
    for (i = 1; i < N - 1; i++)
        dest[i] = src[i] * (1.0 + bbeta * ddyDiag[i]) + beta * (dySubDiag[i] * src[i - 1] - dySubDiag[i + 1] * src[i + 1]);
    if (N > 1) dest[i] = src[i] * (1.0 + bbeta * ddyDiag[i]) + beta * dySubDiag[i] * src[i - 1];
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    char me[512];

    /* ---- Figure 2 in the four combinations ---------------------------- */
    const int order = 4;
    double *J[2], *J2[2];
    for (int c = 0; c < 2; c++) {
        J[c] = malloc(NB(order) * sizeof(double));
        J2[c] = malloc(NB(order) * sizeof(double));
        exp_check(sh_rot_deriv_recursion(order, 1, 0.0, c, J[c]), "deriv J");
        exp_check(sh_rot_deriv_recursion(order, 2, 0.0, c, J2[c]), "deriv J2");
    }
    const char *combo[4] = {"cs function", "cs frame", "nocs function", "nocs frame"};
    int matchJ[4] = {1, 1, 1, 1}, matchJ2[4] = {1, 1, 1, 1};
    FILE *f = exp_data("figure2.dat", "J = dR_Y/dbeta(0) and J^2 of bands 1..3, nocs function rotation (full precision)",
                       "l m_row m_col J J2 J_printed J2_printed");
    for (int l = 1; l <= 3; l++) {
        const int w = 2 * l + 1;
        for (int i = 0; i < w; i++)
            for (int j = 0; j < w; j++) {
                for (int k = 0; k < 4; k++) {
                    const int c = k / 2, frame = k & 1;
                    const double *B = J[c] + NB(l), *B2 = J2[c] + NB(l);
                    const double v = frame ? B[j * w + i] : B[i * w + j]; /* frame: Jᵀ */
                    const double v2 = frame ? B2[j * w + i] : B2[i * w + j];
                    if (fabs(sig3(v) - fig2_J[l - 1][i * w + j]) > 1e-9) matchJ[k] = 0;
                    if (fabs(sig3(v2) - fig2_J2[l - 1][i * w + j]) > 1e-9) matchJ2[k] = 0;
                }
                fprintf(f, "%d %d %d %.17g %.17g %g %g\n", l, i - l, j - l, J[1][NB(l) + i * w + j] + 0.0,
                        J2[1][NB(l) + i * w + j] + 0.0, fig2_J[l - 1][i * w + j], fig2_J2[l - 1][i * w + j]);
            }
    }
    fclose(f);
    /* markdown tables of the computed (nocs function) values, 3 significant digits */
    char tab[8192] = "";
    for (int l = 1; l <= 3; l++) {
        const int w = 2 * l + 1;
        char line[256];
        snprintf(line, sizeof line, "\nBand %d, J (left) and J² (right), rows/columns m = −%d..%d:\n\n```\n", l, l, l);
        strcat(tab, line);
        for (int i = 0; i < w; i++) {
            for (int j = 0; j < w; j++) {
                snprintf(line, sizeof line, "%6.3g", sig3(J[1][NB(l) + i * w + j]) + 0.0);
                strcat(tab, line);
            }
            strcat(tab, "   |");
            for (int j = 0; j < w; j++) {
                snprintf(line, sizeof line, "%6.3g", sig3(J2[1][NB(l) + i * w + j]) + 0.0);
                strcat(tab, line);
            }
            strcat(tab, "\n");
        }
        strcat(tab, "```\n");
    }
    /* which of the four (convention × function/frame) combinations give the
     * printed J and J², for the index's paragraph and one claim each */
    char verdicts[512] = "", jyes[128] = "", jno[128] = "", j2yes[128] = "", j2no[128] = "";
    int nj2 = 0;
    for (int k = 0; k < 4; k++) {
        char s[128];
        snprintf(s, sizeof s, "%s: J %s, J² %s; ", combo[k], matchJ[k] ? "matches" : "does not match (sign of every entry)",
                 matchJ2[k] ? "matches" : "does not match");
        strcat(verdicts, s);
        char *jl = matchJ[k] ? jyes : jno, *j2l = matchJ2[k] ? j2yes : j2no;
        if (*jl) strcat(jl, ", ");
        strcat(jl, combo[k]);
        if (*j2l) strcat(j2l, ", ");
        strcat(j2l, combo[k]);
        nj2 += matchJ2[k];
    }
    /* the paper's own convention: the nocs function rotation (Ivanic's basis,
     * App. A's band-1 table) = the cs frame rotation */
    const int j_ok = matchJ[2] && matchJ[1] && !matchJ[0] && !matchJ[3];
    snprintf(me, sizeof me, "J matches in %s; every entry has the opposite sign in %s", *jyes ? jyes : "none",
             *jno ? jno : "none");
    exp_claim("krivanek-fig2-J", "Křivánek et al. 2005, Fig. 2",
              "first derivative J of R_Y at 0 for bands 1-3, three significant digits", "Fig. 2 (left)", me,
              "3 significant digits", j_ok ? "reproduced" : "differs",
              j_ok ? "taylor_deriv/figure2.dat: the printed J is the nocs function (= cs frame) rotation's; shlab's "
                     "default, cs function rotation, gives −J"
                   : "taylor_deriv/figure2.dat; why: the printed J is not the nocs function (= cs frame) rotation's "
                     "to three digits.");
    if (nj2 == 4) snprintf(me, sizeof me, "J² matches in all four: %s", j2yes);
    else snprintf(me, sizeof me, "J² matches in %s; not in %s", *j2yes ? j2yes : "none", j2no);
    exp_claim_judged("krivanek-fig2-J2", "Křivánek et al. 2005, Fig. 2",
                     "second derivative J² of R_Y at 0 for bands 1-3, three significant digits", "Fig. 2 (right)", me,
                     "3 significant digits", nj2 == 4,
                     "taylor_deriv/figure2.dat",
                     "the printed J² differs from the computed one in a convention where it should not depend on the sign.");

    /* ---- sparsity and antisymmetry (Sec. 3), orders up to 16 ---------- */
    const int NO = 16, N = NO * NO;
    double *A = malloc(NB(NO) * sizeof *A), *A2 = malloc(NB(NO) * sizeof *A2), *G = malloc(NB(NO) * sizeof *G);
    double *D1 = malloc((size_t)N * N * sizeof *D1), *D2 = malloc((size_t)N * N * sizeof *D2);
    exp_check(sh_rot_deriv_recursion(NO, 1, 0.0, SH_CS, A), "J");
    exp_check(sh_rot_deriv_recursion(NO, 2, 0.0, SH_CS, A2), "J2");
    sh_rot_blocks_to_dense(NO, A, D1);
    sh_rot_blocks_to_dense(NO, A2, D2);
    double off1 = 0, off2 = 0, asym = 0, sym2 = 0;
    long nz1 = 0, nz2 = 0, slots1 = 0, slots2 = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            const double a = D1[i * N + j], b = D2[i * N + j];
            asym = fmax(asym, fabs(a + D1[j * N + i]));
            sym2 = fmax(sym2, fabs(b - D2[j * N + i]));
            if (abs(i - j) == 1) { slots1++; nz1 += fabs(a) > 1e-12; }
            else off1 = fmax(off1, fabs(a));
            if (i == j || abs(i - j) == 2) { slots2++; nz2 += fabs(b) > 1e-12; }
            else off2 = fmax(off2, fabs(b));
        }
    snprintf(me, sizeof me,
             "order 16: largest |J| off the flat sub/super-diagonals %.2g; largest |J²| off the main and ±2 diagonals %.2g; "
             "%ld of %ld J and %ld of %ld J² slots non-zero (zeros at band edges, between m = 0 and -1)",
             off1, off2, nz1, slots1, nz2, slots2);
    exp_claim_judged("krivanek-sec3-sparsity", "Křivánek et al. 2005, Sec. 3",
                     "J has non-zeros only on the super- and sub-diagonal; J² only on the main diagonal and the diagonals just beyond them",
                     "stated", me, "1e-12", off1 < 1e-12 && off2 < 1e-12,
                     "taylor_deriv (order 16, flat index)",
                     "an entry off the stated diagonals exceeds 1e-12.");
    snprintf(me, sizeof me, "max|J + Jᵀ| = %.2g, max|J² − (J²)ᵀ| = %.2g (order 16)", asym, sym2);
    exp_claim_judged("krivanek-sec3-antisymmetric", "Křivánek et al. 2005, Sec. 3",
                     "the first derivative matrix is antisymmetric (citing [Wei04]), so only its sub-diagonal is stored", "stated",
                     me, "1e-14", asym < 1e-14,
                     "taylor_deriv",
                     "J + Jᵀ departs from 0 by more than 1e-14.");

    /* ---- Appendix A recursion vs the generator, orders to 16, k to 6 -- */
    FILE *fa = exp_data("appendixA.dat", "Appendix A recursion vs generator R_Y(beta) J^k: max|diff| / max|entry|",
                        "order k beta rel_diff max_entry");
    double worst = 0;
    static const double betas[] = {0.0, 0.35, 1.2, 2.7};
    for (int n = 2; n <= NO; n += 2)
        for (int k = 0; k <= 6; k++)
            for (size_t b = 0; b < sizeof betas / sizeof *betas; b++) {
                exp_check(sh_rot_deriv_recursion(n, k, betas[b], SH_CS, A), "recursion");
                exp_check(sh_rot_deriv_generator(n, k, betas[b], SH_CS, G), "generator");
                double d = 0, mx = 0;
                for (size_t i = 0; i < NB(n); i++) {
                    d = fmax(d, fabs(A[i] - G[i]));
                    mx = fmax(mx, fabs(G[i]));
                }
                fprintf(fa, "%d %d %g %.3g %.6g\n", n, k, betas[b], d / fmax(mx, 1), mx);
                worst = fmax(worst, d / fmax(mx, 1));
            }
    fclose(fa);
    snprintf(me, sizeof me, "max |recursion − R_Y J^k| / max|entry| = %.2g over orders 2..16, k 0..6, β ∈ {0, 0.35, 1.2, 2.7}", worst);
    exp_claim_judged("krivanek-appA-recursion", "Křivánek et al. 2005, App. A",
                     "the k-th derivative of R_Y follows from the Ivanic-Ruedenberg recursion with the product rule (printed "
                     "formulas garbled; derived in rotation_deriv.c)",
                     "algorithm only", me, "1e-12", worst <= 1e-12,
                     "taylor_deriv/appendixA.dat",
                     "the recursion departs from R_Y J^k by more than 1e-12.");
    /* App. A band-1 table: R(1,0,1) = −sin β, R(1,1,0) = sin β: which convention? */
    double b1[3][9];
    exp_check(sh_rot_deriv_recursion(2, 0, 0.4, SH_NOCS, A), "band 1");
    memcpy(b1[0], A + 1, 9 * sizeof(double));
    snprintf(me, sizeof me, "nocs function rotation at β = 0.4: R(1,0,1) = %.6f (−sin = %.6f), R(1,1,0) = %.6f; in cs the signs flip",
             b1[0][5], -sin(0.4), b1[0][7]);
    const int band1_ok = fabs(b1[0][5] + sin(0.4)) < 1e-15 && fabs(b1[0][7] - sin(0.4)) < 1e-15;
    exp_claim("krivanek-appA-band1", "Křivánek et al. 2005, App. A",
              "band 1 of R_Y: R(1,0,1) = −sin β, R(1,1,0) = sin β, R(1,−1,−1) = 1", "as stated", me, "1e-15",
              band1_ok ? "reproduced" : "differs",
              band1_ok ? "holds in the nocs function rotation (Ivanic's basis) = the cs frame rotation"
                       : "taylor_deriv; why: the nocs function rotation's band 1 does not have the printed signs.");

    /* ---- multiplication counts (Sec. 3.1, Appendix C) ------------------ */
    /* The paper's count is that of its listing run literally: the loop
     * kernels (scalar), whose apply does the Z(α), Y and Z(γ) steps per
     * vector and whose set does the per-rotation extras the paper leaves out
     * (β²/2 and the multiple angles of α and γ).  The unrolled kernels (the
     * default to order 10) count everything in the apply and leave out the
     * products by the zeros of J's sub-diagonal. */
    FILE *fm = exp_data("mults.dat", "multiplications of one apply counted by the kernels' loops",
                        "n taylor1 taylor1.5 taylor2 z paper_9n2-4n paper_NZ=2n(n-1) taylor1.5_loops_set "
                        "taylor1.5_loops_apply (default kernels in the first four columns)");
    int ok15 = 1;
    uint64_t l_set[17] = {0}, l_app[17] = {0}, d_app[17] = {0}, z_set[17] = {0}, z_app[17] = {0};
    for (int n = 1; n <= 16; n++) {
        uint64_t cnt[5], setc[5];
        const sh_rot_method ms[5] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2, SH_ROT_Z, SH_ROT_TAYLOR15};
        sh_rotation r;
        for (int q = 0; q < 5; q++) {
            sh_rotation_from_euler(0.3, q == 3 ? 0.0 : 0.2, -0.7, &r);
            sh_rot_plan *p;
            exp_check(sh_rot_plan_create_kernel(n, ms[q], SH_PREC_DOUBLE, SH_CS, q == 4 ? SH_KERNEL_SCALAR : SH_KERNEL_AUTO,
                                                &p), "plan");
            exp_check(sh_rot_plan_set(p, &r), "set");
            double *v = calloc((size_t)n * n, sizeof *v), *o = calloc((size_t)n * n, sizeof *o);
            exp_check(sh_rot_plan_apply(p, v, o), "apply");
            sh_rot_plan_mults(p, &setc[q], &cnt[q]);
            sh_rot_plan_free(p);
            free(v), free(o);
        }
        const long paper = 9L * n * n - 4L * n, nz = 2L * n * (n - 1);
        /* loop kernels: apply = paper − 5 (band 0 copied, not multiplied by 1),
         * set = 2 (β²/2) + 4(n−2) (cos, sin of the multiple angles of α and γ) */
        if (n >= 3 && ((long)cnt[4] != paper - 5 || (long)setc[4] != 2 + 4 * (n - 2))) ok15 = 0;
        l_set[n] = setc[4], l_app[n] = cnt[4], d_app[n] = cnt[1] + setc[1], z_set[n] = setc[3], z_app[n] = cnt[3];
        fprintf(fm, "%d %llu %llu %llu %llu %ld %ld %llu %llu\n", n, (unsigned long long)cnt[0], (unsigned long long)cnt[1],
                (unsigned long long)cnt[2], (unsigned long long)cnt[3], paper, nz, (unsigned long long)setc[4],
                (unsigned long long)cnt[4]);
    }
    fclose(fm);
    for (int n = 6; n <= 10; n += 4) {
        const long paper = 9L * n * n - 4L * n;
        snprintf(me, sizeof me, "n = %d, loop kernels: apply %llu = %ld − 5 (band 0 copied), set %llu (β²/2, multiple "
                 "angles); unrolled kernels: %llu in all; Z alone %llu = 2n(n−1) (+ set %llu)",
                 n, (unsigned long long)l_app[n], paper, (unsigned long long)l_set[n], (unsigned long long)d_app[n],
                 (unsigned long long)z_app[n], (unsigned long long)z_set[n]);
        exp_claim_judged(n == 6 ? "krivanek-sec31-count-n6" : "krivanek-sec31-count-n10", "Křivánek et al. 2005, Sec. 3.1",
                         "the approximate rotation costs 2N_Z(n) + N_dY(n) = 9n² − 4n multiplications (N_dY = 5n², N_Z = 2n(n−1), "
                         "App. C)",
                         n == 6 ? "9n²−4n = 300" : "9n²−4n = 860", me, "loop apply = 9n²−4n − 5, set = 2 + 4(n−2), n = 3..16",
                         ok15,
                         "taylor_deriv/mults.dat",
                         "the loop kernels' counts depart from 9n²−4n beyond band 0's copy and the per-rotation extras.");
    }

    /* ---- the rotation procedure of Sec. 3, literally -------------------- */
    /* tables from Fig. 2's J (= the cs frame-rotation J: −J_cs) and diag(J²) */
    const int PO = 6, PN = PO * PO;
    double *sub = calloc((size_t)PN + 1, sizeof *sub), *dd = calloc((size_t)PN, sizeof *dd);
    exp_check(sh_rot_deriv_recursion(PO, 1, 0.0, SH_CS, A), "J");
    exp_check(sh_rot_deriv_recursion(PO, 2, 0.0, SH_CS, A2), "J2");
    sh_rot_blocks_to_dense(PO, A, D1);
    sh_rot_blocks_to_dense(PO, A2, D2);
    for (int i = 1; i < PN; i++) sub[i] = -D1[i * PN + i - 1]; /* printed J = −J_cs */
    for (int i = 0; i < PN; i++) dd[i] = D2[i * PN + i];
    double *lam = malloc(PN * sizeof *lam), *x = malloc(PN * sizeof *x), *y = malloc(PN * sizeof *y),
           *fun = malloc(PN * sizeof *fun), *frm = malloc(PN * sizeof *frm);
    for (int i = 0; i < PN; i++) lam[i] = sin(1.0 + 0.37 * i);
    const double al = 0.9, be = 1e-3, ga = -2.1;
    memcpy(x, lam, PN * sizeof *x);
    paper_z(PO, al, x);                        /* step 2: Z by α */
    paper_ydiff15(PO, y, x, sub, dd, be);      /* step 3: shRotYdiff15 */
    paper_z(PO, ga, y);                        /* step 4: Z by γ */
    sh_rotation r, ri;
    sh_rotation_from_euler(al, be, ga, &r);
    sh_rotation_inverse(&r, &ri);
    sh_rot_plan *p;
    exp_check(sh_rot_plan_create(PO, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_CS, &p), "plan");
    exp_check(sh_rot_plan_set(p, &r), "set");
    exp_check(sh_rot_plan_apply(p, lam, fun), "apply");
    exp_check(sh_rot_plan_set(p, &ri), "set");
    exp_check(sh_rot_plan_apply(p, lam, frm), "apply");
    sh_rot_plan_free(p);
    double efun = 0, efrm = 0, nl = 0;
    for (int i = 0; i < PN; i++) {
        efun += (y[i] - fun[i]) * (y[i] - fun[i]);
        efrm += (y[i] - frm[i]) * (y[i] - frm[i]);
        nl += lam[i] * lam[i];
    }
    efun = sqrt(efun / nl), efrm = sqrt(efrm / nl);
    snprintf(me, sizeof me,
             "order 6, (α,β,γ) = (0.9, 1e-3, −2.1), the literal steps (App. C, Fig. 2 tables): relative L2 distance "
             "%.2g to R_sh(R)Λ, %.2g to R_sh(R)ᵀΛ (Taylor error ~1e-6)",
             efun, efrm);
    const int frame = efrm < 1e-5 && efun > 1e-2;
    exp_claim("krivanek-sec3-procedure", "Křivánek et al. 2005, Sec. 3",
              "steps 1-4: rotate by Z(α), then shRotYdiff15 by β, then Z(γ) carries out R = R_Z(α)R_Y(β)R_Z(γ)", "as stated",
              me, "1e-5", frame || efun > 1e-5 ? "differs" : "reproduced",
              frame ? "taylor_deriv; why: App. C's z rotation, Fig. 2's J and the step order carry out the frame rotation "
                      "R_sh(R)ᵀ in the cs convention, not R."
              : efun > 1e-5 ? "taylor_deriv; why: the literal steps are off both R_sh(R)Λ and R_sh(R)ᵀΛ by more than 1e-5."
                            : "taylor_deriv");
    exp_claim("krivanek-sec3-code", "Křivánek et al. 2005, Sec. 3",
              "the listed C function shRotYdiff15 computes the 1.5th-order Y rotation", "C listing",
              "the last statement uses the loop variable i after the for loop that declares it; with i = n²−1 it works",
              "compiles as C99/C++", "differs",
              "taylor_deriv.c paper_ydiff15; why: as printed the function does not compile (i is out of scope in its "
              "last statement).");

    exp_index("Figure 2 of Křivánek et al. (J = dR_Y/dβ at 0 and J², bands 1–3), computed by the Appendix A recursion "
              "and rounded to three significant digits (nocs function rotation; data with full precision in "
              "[figure2.dat](figure2.dat)):\n%s\n"
              "**Which convention.** %s The printed J is the derivative of the function rotation in the nocs basis "
              "(Ivanic's, which Appendix A's band-1 table also uses) — equivalently of the *frame* rotation in the cs "
              "basis. In shlab's default (cs, function rotation) every entry of J has the opposite sign; J² is the same "
              "in all four combinations. The paper's whole pipeline (Appendix C's z rotation, whose sine has the "
              "opposite sign to the cs function rotation, the tables of Fig. 2, and the step order 'Z(α) first') is "
              "the cs frame rotation R_sh(R)ᵀ, measured in the claims ledger (krivanek-sec3-procedure).\n\n"
              "The Appendix A recursion (derived; the printed dV/dW/dP are garbled) agrees with the generator "
              "R_Y(β)J^k to %.2g relative to the largest entry for orders 2–16 and k ≤ 6 "
              "([appendixA.dat](appendixA.dat)); the kernels' counted multiplications are in [mults.dat](mults.dat).\n",
              tab, verdicts, worst);
    free(J[0]), free(J[1]), free(J2[0]), free(J2[1]), free(A), free(A2), free(G), free(D1), free(D2);
    free(sub), free(dd), free(lam), free(x), free(y), free(fun), free(frm);
    return 0;
}
