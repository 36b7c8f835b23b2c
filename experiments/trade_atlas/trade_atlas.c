/* trade_atlas — the speed–accuracy trade of rotation, as a user meets it:
 * for orders 1..16, float and double, one rotation at a time and 256 at
 * once (from 3×3 matrices), and the β ranges 5°, 20°, 45°, 90° and any
 * (180°): every method's worst error on the β range against its cost, the
 * Pareto frontier per order, and "budget E, β ≤ B → use X" tables — the
 * answers `shlab plan` gives.
 *
 * Error: the "max" unit (docs/CONVENTIONS.md): the largest singular value of
 * R_method − R_exact, the worst relative L2 error of a rotated function on
 * the sphere, and a bound for the other units; the worst over the β grid
 * 0, 1°, …, B at seeded α, γ (sh_rot_choose_errors, against the MPFR
 * reference).  Cost: the cost model (src/lab/cost_model.c, calibrated by the
 * cost_model experiment): deterministic.  The choice in the tables is
 * sh_rot_choose's, the planner's own.
 *
 * Timing part (machine-dependent): the model against a live interleaved
 * run, and the planner's choices against the measured frontier — for a grid
 * of (order, β, budget, precision, path) no admissible method is faster than
 * the choice by more than the noise (paired ratio whose upper quartile,
 * widened by the run-to-run spread, is below 1).
 */
#include "exp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NB 5
#define NO 16
#define NBUD 11 /* 1e-2 .. 1e-12 */
static const double BETAS[NB] = {5, 20, 45, 90, 180};
static const char *const PREC[2] = {"float", "double"};
static const sh_bench_mode PATHS[2] = {SH_BENCH_PER_ROTATION, SH_BENCH_KROT};
static const int TABLE_ORDERS[] = {3, 6, 10, 16};
#define NTAB ((int)(sizeof TABLE_ORDERS / sizeof *TABLE_ORDERS))

/* errors[p][n][j·nm + k]: method k at step j (1° steps 0..180°) */
static double *ERR[2][NO + 1];
/* the methods of each order's β grid (sh_rot_choose_grid: a method limited
 * below the order is not in it, so the lists differ: direct to 3, zh to 6),
 * and ERR[p][n] laid out by that order's list */
static sh_rot_method MS[NO + 1][SH_ROT_NMETHODS];
static int NM[NO + 1], NSTEPS;

static sh_rot_choose_opts opts_for(int n, int p, double beta_deg, double budget)
{
    sh_rot_choose_opts o = {0};
    o.order = n;
    o.max_beta = beta_deg * M_PI / 180;
    o.beta_step = M_PI / 180;
    o.tolerance = budget;
    o.lobe_exp = 7;
    o.measure = SH_MEASURE_MAX;
    o.prec = p ? SH_PREC_DOUBLE : SH_PREC_FLOAT;
    return o;
}

static void measure_errors(void)
{
    for (int p = 0; p < 2; p++)
        for (int n = 1; n <= NO; n++) {
            exp_progress("trade_atlas: errors, %s, order %d", PREC[p], n);
            sh_rot_choose_opts o = opts_for(n, p, 180, 1);
            exp_check(sh_rot_choose_grid(&o, MS[n], &NM[n], &NSTEPS), "grid");
            ERR[p][n] = malloc(sizeof(double) * (size_t)NSTEPS * NM[n]);
            if (!ERR[p][n]) exp_check(SH_ENOMEM, "errors");
            exp_check(sh_rot_choose_errors(&o, NULL, ERR[p][n]), "errors");
        }
}

/* The worst error of method k over the steps up to beta_deg. */
static double worst(int p, int n, int k, double beta_deg)
{
    double w = 0;
    for (int j = 0; j <= (int)lround(beta_deg); j++) w = fmax(w, ERR[p][n][(size_t)j * NM[n] + k]);
    return w;
}

/* The planner's choice (sh_rot_choose on the atlas's errors): index into
 * MS, or −1; *ns its model cost. */
static int choose(int n, int p, int path, double beta_deg, double budget, double *ns)
{
    sh_rot_choose_opts o = opts_for(n, p, beta_deg, budget);
    o.grid_errors = ERR[p][n];
    sh_rot_path rp = SH_ROT_PATH_DEFAULT;
    rp.mode = PATHS[path];
    rp.batch = 256;
    sh_rot_candidate c[SH_ROT_NMETHODS];
    int nc, ch, ru;
    exp_check(sh_rot_choose(&o, &rp, c, &nc, &ch, &ru, NULL), "choose");
    if (ch < 0) return -1;
    *ns = c[ch].ns_per_rotation;
    for (int k = 0; k < NM[n]; k++)
        if (MS[n][k] == c[ch].method) return k;
    return -1;
}

static double model_ns(int n, int p, int path, int k)
{
    sh_cost c;
    if (sh_cost_model(n, MS[n][k], p ? SH_PREC_DOUBLE : SH_PREC_FLOAT, SH_BENCH_INPUT_MATRIX, PATHS[path], &c)) return NAN;
    return c.ns;
}

/* atlas_<prec>_<path>.dat: index b (β range), a block per order of its
 * Pareto frontier sorted by error; labels_... the order at its cheapest. */
static void write_atlas(int p, int path)
{
    char name[64], lname[64], title[200];
    snprintf(name, sizeof name, "atlas_%s_%s.dat", PREC[p], sh_bench_mode_name(PATHS[path]));
    snprintf(lname, sizeof lname, "labels_%s_%s.dat", PREC[p], sh_bench_mode_name(PATHS[path]));
    snprintf(title, sizeof title, "Pareto frontier per order of model cost against worst max error, %s, %s from "
             "matrices (index: beta range 5, 20, 45, 90, 180 deg)", PREC[p], sh_bench_mode_name(PATHS[path]));
    FILE *f = exp_data(name, title, "beta_deg order method max_error ns instructions_per_ns_model");
    FILE *fl = exp_data(lname, "order labels at each frontier's cheapest point", "beta_deg order max_error ns");
    for (int b = 0; b < NB; b++) {
        for (int n = 2; n <= NO; n++) {
            double e[SH_ROT_NMETHODS], c[SH_ROT_NMETHODS];
            int on[SH_ROT_NMETHODS], nf = 0, cheapest = -1;
            for (int k = 0; k < NM[n]; k++) {
                e[k] = fmax(worst(p, n, k, BETAS[b]), 1e-16);
                c[k] = model_ns(n, p, path, k);
            }
            for (int k = 0; k < NM[n]; k++) {
                on[k] = isfinite(c[k]) && e[k] < 1; /* an error ≥ 1 (100 %) is no answer */
                for (int q = 0; q < NM[n] && on[k]; q++)
                    if (q != k && isfinite(c[q]) && c[q] <= c[k] && e[q] <= e[k] && (c[q] < c[k] || e[q] < e[k]))
                        on[k] = 0;
            }
            /* the frontier by increasing error */
            for (int done = 0; done < NM[n]; done++) {
                int best = -1;
                for (int k = 0; k < NM[n]; k++)
                    if (on[k] == 1 && (best < 0 || e[k] < e[best])) best = k;
                if (best < 0) break;
                on[best] = 2;
                fprintf(f, "%g %d %s %.4g %.4g\n", BETAS[b], n, sh_rot_method_name(MS[n][best]), e[best], c[best]);
                if (cheapest < 0 || c[best] < c[cheapest]) cheapest = best;
                nf++;
            }
            if (nf) fprintf(f, "\n");
            if (cheapest >= 0)
                fprintf(fl, "%g %d %.4g %.4g\n", BETAS[b], n, e[cheapest], c[cheapest]);
        }
        fprintf(f, "\n");
        fprintf(fl, "\n\n");
    }
    fclose(f);
    fclose(fl);
}

/* "budget E, β ≤ B → use X (ns)" for one order, precision and path. */
static void table(int n, int p, int path, char *out, size_t cap)
{
    size_t l = strlen(out);
    l += (size_t)snprintf(out + l, cap - l, "\n**Order %d, %s, %s** (model ns per rotated vector)\n\n| budget (max) |", n,
                          PREC[p], path ? "256 rotations per call (k-rotations)" : "one rotation at a time");
    for (int b = 0; b < NB; b++) l += (size_t)snprintf(out + l, cap - l, b < NB - 1 ? " β ≤ %g° |" : " any β |", BETAS[b]);
    l += (size_t)snprintf(out + l, cap - l, "\n|---|---|---|---|---|---|\n");
    for (int e = 0; e < NBUD; e++) {
        const double E = pow(10, -2 - e);
        if (p == 0 && E < 1e-7) break; /* float: nothing below its rounding */
        l += (size_t)snprintf(out + l, cap - l, "| 1e-%d |", 2 + e);
        for (int b = 0; b < NB; b++) {
            double ns = 0;
            const int k = choose(n, p, path, BETAS[b], E, &ns);
            l += k < 0 ? (size_t)snprintf(out + l, cap - l, " – |")
                       : (size_t)snprintf(out + l, cap - l, " %s (%.3g) |", sh_rot_method_name(MS[n][k]), ns);
        }
        l += (size_t)snprintf(out + l, cap - l, "\n");
    }
}

/* ---- timing part ---------------------------------------------------------- */
typedef struct {
    int checked, beyond, noisy_runs, runs;
    /* zxzxz float order 6 from a matrix: live / model, one at a time and 256
     * per call, and whether those runs were noisy */
    double fid[2];
    int fid_noisy[2];
    double worst_ratio; /* the smallest paired ratio other/choice among violations */
    char worst_what[200];
} frontier_check;

/* Time every method at (order, precision, path) interleaved; then, for each
 * β range and budget, the choice against every admissible method. */
static void check_frontier(int n, int p, int path, FILE *f, frontier_check *fc)
{
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    bo.input = SH_BENCH_INPUT_MATRIX;
    bo.batch = path ? 256 : 1;
    sh_bench_entry ent[SH_ROT_NMETHODS];
    int idx[SH_ROT_NMETHODS], ne = 0;
    for (int k = 0; k < NM[n]; k++)
        if (sh_rot_bench_entry(n, MS[n][k], p ? SH_PREC_DOUBLE : SH_PREC_FLOAT, PATHS[path], &bo, &ent[ne]) == SH_OK)
            idx[ne++] = k;
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.samples = 11;
    cfg.min_sample_ms = 2;
    sh_bench_stats st[SH_ROT_NMETHODS];
    sh_bench_noise nz;
    double *smp = malloc(sizeof *smp * (size_t)ne * cfg.samples);
    exp_check(smp ? sh_bench_interleaved(ent, ne, &cfg, smp, st, &nz) : SH_ENOMEM, "timing");
    fc->runs++;
    fc->noisy_runs += nz.noisy;
    for (int i = 0; i < ne; i++) {
        const double model = model_ns(n, p, path, idx[i]);
        fprintf(f, "%d %s %s %s %.4g %.4g %.3f %d\n", n, PREC[p], sh_bench_mode_name(PATHS[path]),
                sh_rot_method_name(MS[n][idx[i]]), st[i].ns_median, model, st[i].ns_median / model, nz.noisy);
        if (n == 6 && p == 0 && MS[n][idx[i]] == SH_ROT_ZXZXZ) {
            fc->fid[path] = st[i].ns_median / model;
            fc->fid_noisy[path] = nz.noisy;
        }
    }
    for (int b = 0; b < NB; b++)
        for (int e = 0; e < NBUD; e += 2) {
            const double E = pow(10, -2 - e);
            double ns;
            const int ch = choose(n, p, path, BETAS[b], E, &ns);
            int ci = -1;
            for (int i = 0; i < ne; i++)
                if (idx[i] == ch) ci = i;
            if (ci < 0) continue;
            for (int i = 0; i < ne; i++) {
                if (i == ci || !(worst(p, n, idx[i], BETAS[b]) <= E)) continue;
                sh_bench_ratio r;
                exp_check(sh_bench_paired_ratio(smp + (size_t)i * cfg.samples, smp + (size_t)ci * cfg.samples,
                                                cfg.samples, 0, &r), "ratio");
                fc->checked++;
                if (r.q3 * (1 + EXP_RUN_TO_RUN) < 1) {
                    fc->beyond++;
                    if (!fc->worst_ratio || r.median < fc->worst_ratio) {
                        fc->worst_ratio = r.median;
                        snprintf(fc->worst_what, sizeof fc->worst_what, "order %d %s %s, β ≤ %g°, budget %g: %s "
                                 "%.2f× the time of the choice %s", n, PREC[p], sh_bench_mode_name(PATHS[path]),
                                 BETAS[b], E, sh_rot_method_name(MS[n][idx[i]]), r.median, sh_rot_method_name(MS[n][ch]));
                    }
                }
            }
        }
    for (int i = 0; i < ne; i++) sh_bench_entry_free(&ent[i]);
    free(smp);
}

/* The ledger rows of the timing part: the model's fidelity where the issue
 * of the trade set its bar, and the choices on the measured frontier. */
static void claims(const frontier_check *fc)
{
    char meas[200], ev[400];
    const int noisy = fc->fid_noisy[0] || fc->fid_noisy[1];
    const int in = fc->fid[0] >= 1 / 1.5 && fc->fid[0] <= 1.5 && fc->fid[1] >= 1 / 1.5 && fc->fid[1] <= 1.5;
    const char *v = noisy ? "not-measured" : in ? "reproduced" : "differs";
    snprintf(meas, sizeof meas, "live/model %.2f one at a time, %.2f 256 per call", fc->fid[0], fc->fid[1]);
    exp_claim("plan-model-within-1.5x", "shlab goal",
              "the cost model's ns per rotation for zxzxz, float, order 6, from a matrix, is within 1.5x of a live "
              "interleaved bench of the same path, one at a time and 256 rotations per call",
              "within 1.5x", meas, "[1/1.5, 1.5]", v,
              exp_evidence(ev, sizeof ev, "trade_atlas/timing/live.dat", v,
                           "the live time is outside 1.5x of the model's (the calibration's machine or load differ)"));
    snprintf(meas, sizeof meas, "%d of %d pairs faster than the choice beyond the noise", fc->beyond, fc->checked);
    const char *v2 = fc->noisy_runs > fc->runs / 2 ? "not-measured" : fc->beyond == 0 ? "reproduced" : "differs";
    exp_claim("plan-on-measured-frontier", "shlab goal",
              "over a grid of order, beta range, budget, precision and path, no method within the budget is faster "
              "than the planner's choice beyond the noise of a live interleaved run",
              "0 faster", meas, "paired ratio q3 x 1.05 < 1 counts", v2,
              exp_evidence(ev, sizeof ev, "trade_atlas/timing/live.dat", v2,
                           "some admissible method ran faster than the model's choice (trade_atlas timing section)"));
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    if (!sh_cost_model_source()[0]) {
        fprintf(stderr, "trade_atlas: this build has no cost model (data/cost_model.tsv; experiment cost_model)\n");
        return 1;
    }
    measure_errors();
    FILE *fm = exp_data("methods.txt", "methods in the atlas", "name");
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        int in = 0; /* every method of any order's grid, in the table's order */
        for (int n = 1; n <= NO; n++)
            for (int k = 0; k < NM[n]; k++) in |= MS[n][k] == (sh_rot_method)m;
        if (in) fprintf(fm, "%s\n", sh_rot_method_name((sh_rot_method)m));
    }
    fclose(fm);
    for (int p = 0; p < 2; p++)
        for (int path = 0; path < 2; path++) write_atlas(p, path);
    static char tabs[1 << 17];
    tabs[0] = 0;
    for (int t = 0; t < NTAB; t++)
        for (int p = 0; p < 2; p++)
            for (int path = 0; path < 2; path++) table(TABLE_ORDERS[t], p, path, tabs, sizeof tabs);
    exp_index("**The trade atlas.** What each rotation method costs and how wrong it is, for orders 1..16, float and "
              "double, one rotation at a time and 256 rotations per call (`rotate_many`), from 3×3 matrices. Error: "
              "the worst, over β = 0, 1°, …, B (seeded α, γ), of the largest singular value of R_method − R_exact "
              "(the \"max\" unit: the worst relative L2 error of a rotated function, and a bound for the coefficient "
              "and lobe units; docs/CONVENTIONS.md), against the MPFR reference. Cost: the cost model's ns per "
              "rotated vector (instructions under callgrind × the calibration in `data/cost_model.tsv`; %s). Each "
              "panel is one β range; each line one order's Pareto frontier (no method both cheaper and more "
              "accurate; errors of 1 or more left out), drawn for orders 2, 3, 4, 6, 8, 12, 16 and labelled n = order "
              "at its cheapest point; dashed verticals are budgets 1e-2 … 1e-12. Errors below 1e-16 are drawn at "
              "1e-16. Data (every order 2..16): atlas_*.dat. In double the budget lines fall in the gap between the "
              "exact methods' rounding and the approximations' errors, except at the smallest β and loosest budgets: "
              "there the answer is an exact method, chosen by cost.\n\n"
              "![float, one rotation at a time](trade_atlas_float_per-rotation.png)\n\n"
              "![float, 256 rotations per call](trade_atlas_float_k-rotations.png)\n\n"
              "![double, one rotation at a time](trade_atlas_double_per-rotation.png)\n\n"
              "![double, 256 rotations per call](trade_atlas_double_k-rotations.png)\n\n"
              "**Budget E, β ≤ B → use X.** The planner's choice (`shlab plan --order N --max-beta B --tolerance E "
              "--error max --precision P [--mode k-rotations]`, on the same 1° grid), and its model cost in ns per "
              "rotated vector; – : no method meets the budget (float stops at 1e-7, its rounding).\n%s",
              sh_cost_model_source(), tabs);

    /* ---- timing: the model and the choices against live runs ---- */
    exp_part("timing");
    FILE *f = exp_data("live.dat", "live interleaved time against the cost model, per method",
                       "order precision mode method live_ns model_ns live_over_model noisy");
    frontier_check fc = {0};
    for (int t = 0; t < NTAB; t++)
        for (int p = 0; p < 2; p++)
            for (int path = 0; path < 2; path++) {
                exp_progress("trade_atlas: live timing, order %d %s %s", TABLE_ORDERS[t], PREC[p],
                             sh_bench_mode_name(PATHS[path]));
                check_frontier(TABLE_ORDERS[t], p, path, f, &fc);
            }
    fclose(f);
    exp_index("**The model against live runs, and the choices against the measured frontier** (orders 3, 6, 10, 16; "
              "float and double; one at a time and 256 per call; every method one entry of one interleaved run per "
              "(order, precision, path), 11 rounds). live.dat has each method's live median beside the model "
              "(live_over_model). Over β ranges 5°, 20°, 45°, 90°, any and budgets 1e-2, 1e-4, …, 1e-12, %d "
              "(choice, admissible other method) pairs were compared by their paired time ratio; %d had the other "
              "method faster beyond the noise (upper quartile of the ratio × 1.05 < 1)%s%s. %d of %d runs broke the "
              "noise rule.",
              fc.checked, fc.beyond, fc.beyond ? "; the largest gap: " : "", fc.beyond ? fc.worst_what : "",
              fc.noisy_runs, fc.runs);
    claims(&fc);
    return 0;
}
