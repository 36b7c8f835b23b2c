/* rotation_stability — the stability map: how each exact rotation
 * method's error grows with the band, in double up to l = 1000 and in float
 * up to l = 64, over the fixed rotation set of `shlab stability` (β = 0,
 * 1e-12, π/2, π−1e-9, π, gimbal lock, random), and where each one breaks.
 *
 * Per band and method (maximum over the set): orth = max|RRᵀ − I| (exact to
 * l = 128, probe estimate above), hom = homomorphism error on unit probes,
 * ref = max|R − R_MPFR| (l ≤ 40).  A sweep stops after the first band whose
 * orth exceeds 1 (the method has failed).
 *
 * Memory: ivanic streams band by band; zxzxz and blanco compute single bands;
 * halfpi forms blocks only up to l = 128 (above, its rows come from band
 * applications to the probes, sh_rot_stability); choi and wigner hold a plan
 * (choi is run to l = 200, wigner to 60: both have failed long before).
 *
 * The long part (`rotation_stability OUTDIR --part long`, into OUTDIR/long,
 * kept by `make report`, which runs only the part above): the stable
 * methods to l = 4000 (halfpi, blanco; zxzxz to 1400, its single band costs
 * O(l³)), double, exact orthogonality to l = 500 and the probe estimate
 * above, on a sparse ladder of bands; meant to be run as shards (docs/sweeps.md,
 * "Sweeps in shards"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

typedef struct {
    FILE *f;
    int last_band;
    double last_orth;
    double t1, t2;            /* thresholds: 1e3·ε and 1e6·ε of the precision */
    int first_t1, first_t2;   /* first band with orth above them (-1: never) */
    int first_ref;            /* first band with ref > t1 */
    double orth_at[4];        /* at l = 50, 100, 200, 1000 (or -1) */
} acc;

static int on_row(const sh_rot_stability_row *r, void *vctx)
{
    acc *a = vctx;
    if (r->broken) {
        fprintf(a->f, "# band %d: non-finite entries (overflow); sweep stopped\n", r->band);
        a->last_band = r->band;
        a->last_orth = INFINITY;
        if (a->first_t1 < 0) a->first_t1 = r->band;
        if (a->first_t2 < 0) a->first_t2 = r->band;
        return 0;
    }
    fprintf(a->f, "%d %.6e %.6e %.6e %d\n", r->band, r->orth, r->hom, r->have_ref ? r->ref : -1.0,
            r->orth_exact);
    a->last_band = r->band;
    a->last_orth = r->orth;
    if (a->first_t1 < 0 && r->orth > a->t1) a->first_t1 = r->band;
    if (a->first_t2 < 0 && r->orth > a->t2) a->first_t2 = r->band;
    if (a->first_ref < 0 && r->have_ref && r->ref > a->t1) a->first_ref = r->band;
    const int marks[4] = {50, 100, 200, 1000};
    for (int q = 0; q < 4; q++)
        if (r->band == marks[q]) a->orth_at[q] = r->orth;
    if (r->band % 100 == 0) exp_progress("band %d orth %.2e", r->band, r->orth);
    return 0;
}

/* the rows a (possibly sharded) run computes, by position in the ladder */
typedef struct {
    int pos[128], band[128], n, got;
    sh_rot_stability_row rows[128];
} got;

static int keep_row(const sh_rot_stability_row *r, void *vctx)
{
    got *g = vctx;
    g->rows[g->got++] = *r;
    return 0;
}

/* bands 0..20, then a roughly geometric ladder to lmax */
static int ladder(int lmax, int dense_to, int *b)
{
    static const int steps[] = {25, 30, 35, 40, 50, 60, 70, 80, 90, 100, 120, 140, 160, 180, 200,
                                250, 300, 400, 500, 600, 700, 800, 900, 1000};
    int n = 0;
    for (int l = 0; l <= dense_to && l <= lmax; l++) b[n++] = l;
    for (size_t k = 0; k < sizeof steps / sizeof *steps; k++)
        if (steps[k] > dense_to && steps[k] <= lmax) b[n++] = steps[k];
    return n;
}

/* the long part's ladder: 0..20, then about 12 bands a decade to lmax */
static int ladder_long(int lmax, int *b)
{
    static const int steps[] = {25,  30,  35,  40,  50,  60,  70,  80,   90,   100,  120,  140,  160,
                                180, 200, 250, 300, 350, 400, 500, 600,  700,  800,  900,  1000, 1200,
                                1400, 1700, 2000, 2400, 2800, 3400, 4000};
    int n = 0;
    for (int l = 0; l <= 20 && l <= lmax; l++) b[n++] = l;
    for (size_t k = 0; k < sizeof steps / sizeof *steps; k++)
        if (steps[k] <= lmax) b[n++] = steps[k];
    return n;
}

static void fmt_band(char *s, size_t n, int b, int last, int lmax)
{
    if (b >= 0) snprintf(s, n, "%d", b);
    else if (last >= lmax) snprintf(s, n, "> %d", lmax);
    else snprintf(s, n, "—");
}

static void fmt_orth(char *s, size_t n, double v)
{
    if (v < 0) snprintf(s, n, "—");
    else snprintf(s, n, "%.1e", v);
}

/* One method's sweep over bands[0..nb) as items base + q of this run (a
 * shard computes its own, the merge takes them from the files): the rows,
 * in band order, to on_row, up to the first with orth > 1. */
static void sweep(sh_rot_method m, sh_precision prec, const int *bands, int nb, int exact_max, long base, acc *a)
{
    got g;
    memset(&g, 0, sizeof g);
    for (int q = 0; q < nb; q++)
        if (exp_computes(base + q)) g.pos[g.n++] = q, g.band[g.n - 1] = bands[q];
    if (g.n)
        exp_check(sh_rot_stability(m, prec, SH_CS, g.band[g.n - 1], g.band, g.n, 40, exact_max, 1.0, keep_row, &g),
                  "stability");
    for (int q = 0, i = 0; q < nb; q++) {
        double v[6] = {0};
        if (i < g.got && g.pos[i] == q) {
            const sh_rot_stability_row *r = &g.rows[i++];
            v[0] = r->orth, v[1] = r->hom, v[2] = r->ref;
            v[3] = r->orth_exact, v[4] = r->have_ref, v[5] = r->broken;
        } else if (exp_computes(base + q)) {
            break; /* after this shard's stop (orth > 1) */
        }
        if (!exp_item(base + q, 6, v)) continue;
        const sh_rot_stability_row r = {bands[q], v[0], v[1], v[2], (int)v[3], (int)v[4], (int)v[5]};
        on_row(&r, a);
        if (r.broken || r.orth > 1.0) break; /* the sweep stops after orth > 1 */
    }
}

#define LONG_EXACT_MAX 500

static int run_long(void)
{
    static const struct {
        sh_rot_method m;
        int lmax;
    } M[] = {{SH_ROT_HALFPI, 4000}, {SH_ROT_BLANCO, 4000}, {SH_ROT_ZXZXZ, 1400}};
    const int nm = sizeof M / sizeof *M;
    exp_part("long");
    char table[4096];
    size_t tl = 0;
    tl += (size_t)snprintf(table + tl, sizeof table - tl,
                           "| method | bands run | largest exact orth (l ≤ %d) | largest estimate (l > %d) | "
                           "orth at l = 1000* | 2000* | 4000* | largest hom |\n|---|---|---|---|---|---|---|---|\n",
                           LONG_EXACT_MAX, LONG_EXACT_MAX);
    int bands[128];
    for (int k = 0; k < nm; k++) {
        const int nb = ladder_long(M[k].lmax, bands);
        char name[64], title[160];
        snprintf(name, sizeof name, "%s_double.dat", sh_rot_method_name(M[k].m));
        snprintf(title, sizeof title, "stability of %s in double to l = %d over the extreme rotation set",
                 sh_rot_method_name(M[k].m), M[k].lmax);
        acc a = {exp_data(name, title, "band orth hom ref(-1: not computed) orth_exact"), -1, 0,
                 1e3 * 2.220446049250313e-16, 1e6 * 2.220446049250313e-16, -1, -1, -1, {-1, -1, -1, -1}};
        exp_progress("%s double to l = %d (long part)", sh_rot_method_name(M[k].m), M[k].lmax);
        sweep(M[k].m, SH_PREC_DOUBLE, bands, nb, LONG_EXACT_MAX, 1000L * k, &a);
        fclose(a.f);
        /* the summary from the file just written (the rows in band order) */
        char p[4200];
        snprintf(p, sizeof p, "%s/%s", exp_outdir(), name);
        FILE *f = fopen(p, "r");
        double ex = 0, est = 0, hom = 0, at[3] = {-1, -1, -1};
        char line[512];
        while (f && fgets(line, sizeof line, f)) {
            int b, exact;
            double o, h, r;
            if (line[0] == '#' || sscanf(line, "%d %lf %lf %lf %d", &b, &o, &h, &r, &exact) != 5) continue;
            if (exact) ex = fmax(ex, o);
            else est = fmax(est, o);
            hom = fmax(hom, h);
            if (b == 1000) at[0] = o;
            if (b == 2000) at[1] = o;
            if (b == 4000) at[2] = o;
        }
        if (f) fclose(f);
        char o[3][32];
        for (int q = 0; q < 3; q++) fmt_orth(o[q], sizeof o[q], at[q]);
        tl += (size_t)snprintf(table + tl, sizeof table - tl, "| %s | 0–%d%s | %.1e | %.1e | %s | %s | %s | %.1e |\n",
                               sh_rot_method_name(M[k].m), a.last_band,
                               a.last_band < M[k].lmax ? " (stopped: orth > 1)" : "", ex, est, o[0], o[1], o[2], hom);
    }
    exp_index("**To l = 4000** (the long part, computed on request as shards and kept by `make report`, "
              "which runs only the sweeps above; docs/sweeps.md): the stable methods in "
              "double on bands 0–20 and about 12 a decade above, halfpi and blanco to l = 4000, zxzxz to "
              "1400 (a single zxzxz band costs O(l³): 4.5 s at l = 500, minutes above 1000). *orth* is exact "
              "(max|RRᵀ − I|, O(l³) a block) up to l = %d and the two-probe estimate max|Rᵀ(R v) − v| "
              "above (O(l²)); the estimate is the largest entry of a residual *vector* and runs about "
              "10× (7–16× here) below the exact maximum entry at the same band, so the step down at l = %d in the "
              "plot (dotted line, open markers) is the change of measure, not an improvement. "
              "halfpi forms no block above l = %d: its estimate and hom come from band applications to "
              "the probes, Rᵀ applied as the inverse rotation through the same generated d(π/2). "
              "Commands: `build/experiments/rotation_stability OUTDIR --part long [--shard I/N | "
              "--merge FILE...]`; one method alone: `shlab stability --method M --bands B1,B2,... "
              "--exact-max %d`.\n\n"
              "![orthogonality error to l = 4000, double](stability_long.png)\n\n"
              "%s\n"
              "* the estimate (l > %d). Computed by the code at revision `%s`.\n",
              LONG_EXACT_MAX, LONG_EXACT_MAX, LONG_EXACT_MAX, LONG_EXACT_MAX, table, LONG_EXACT_MAX,
              exp_revision());
    return 0;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const char *part = exp_requested_part();
    if (part && strcmp(part, "long")) {
        fprintf(stderr, "rotation_stability: error: no part '%s' (the only part run on request is long)\n", part);
        return 2;
    }
    if (part) return run_long();
    static const struct {
        sh_rot_method m;
        int lmax_d, lmax_f, dense;
    } M[] = {{SH_ROT_ZXZXZ, 1000, 64, 20}, {SH_ROT_BLANCO, 1000, 64, 20}, {SH_ROT_HALFPI, 1000, 64, 20},
             {SH_ROT_IVANIC, 1000, 64, 40}, {SH_ROT_CHOI, 200, 64, 40},    {SH_ROT_WIGNER, 60, 64, 60}};
    /* zxzxz computes a single band in O(l³) (X₋₉₀·Z(β)·X₊₉₀), 20 of them per
     * band (the set and the products for the homomorphism): its ladder above
     * l = 200 is thinned to 300, 500, 1000. */
    const int nm = sizeof M / sizeof *M;
    char table[8192];
    size_t tl = 0;
    tl += (size_t)snprintf(table + tl, sizeof table - tl,
                           "| method | precision | bands run | first band with orth > 1e3·ε | > 1e6·ε | "
                           "first band off the reference by > 1e3·ε (l ≤ 40) | orth at l = 50 | 100 | 200* | 1000* |\n"
                           "|---|---|---|---|---|---|---|---|---|---|\n");
    int bands[128];
    char summary_ivanic[256] = "";
    int ivanic_t2 = -1; /* ivanic in double: the first band with orth > 1e6·ε */
    for (int pr = 0; pr < 2; pr++)
        for (int k = 0; k < nm; k++) {
            /* no band above the method's largest order (ivanic: 201, where the
               golden fixtures show it failing; its sweep stops near l = 180) */
            const int want = pr ? M[k].lmax_f : M[k].lmax_d, top = sh_rot_method_max_order(M[k].m) - 1;
            const int lmax = want < top ? want : top;
            int nb = pr ? ladder(lmax, lmax, bands) : ladder(lmax, M[k].dense, bands);
            if (!pr && M[k].m == SH_ROT_ZXZXZ) { /* thin the expensive top */
                int n2 = 0;
                for (int q = 0; q < nb; q++)
                    if (bands[q] <= 200 || bands[q] == 300 || bands[q] == 500 || bands[q] == 1000) bands[n2++] = bands[q];
                nb = n2;
            }
            char name[64], title[160];
            snprintf(name, sizeof name, "%s_%s.dat", sh_rot_method_name(M[k].m), pr ? "float" : "double");
            snprintf(title, sizeof title, "stability of %s in %s over the extreme rotation set",
                     sh_rot_method_name(M[k].m), pr ? "float" : "double");
            const double eps = pr ? 1.1920929e-07 : 2.220446049250313e-16;
            acc a = {exp_data(name, title, "band orth hom ref(-1: not computed) orth_exact"), -1, 0,
                     1e3 * eps, 1e6 * eps, -1, -1, -1, {-1, -1, -1, -1}};
            exp_progress("%s %s to l = %d", sh_rot_method_name(M[k].m), pr ? "float" : "double", lmax);
            /* items: band q of sweep (pr, k); this run computes its own (exp.h) */
            sweep(M[k].m, pr ? SH_PREC_FLOAT : SH_PREC_DOUBLE, bands, nb, 128, 1000L * (pr * nm + k), &a);
            fclose(a.f);
            char b1[32], b2[32], b3[32], o[4][32];
            fmt_band(b1, sizeof b1, a.first_t1, a.last_band, lmax);
            fmt_band(b2, sizeof b2, a.first_t2, a.last_band, lmax);
            fmt_band(b3, sizeof b3, a.first_ref, a.last_band < 40 ? a.last_band : 40, 40);
            for (int q = 0; q < 4; q++) fmt_orth(o[q], sizeof o[q], a.orth_at[q]);
            tl += (size_t)snprintf(table + tl, sizeof table - tl, "| %s | %s | 0–%d%s | %s | %s | %s | %s | %s | %s | %s |\n",
                                   sh_rot_method_name(M[k].m), pr ? "float" : "double", a.last_band,
                                   a.last_band < lmax ? " (stopped: orth > 1)" : "", b1, b2, b3, o[0], o[1], o[2], o[3]);
            if (!pr && M[k].m == SH_ROT_IVANIC) ivanic_t2 = a.first_t2;
            if (!pr && M[k].m == SH_ROT_IVANIC)
                snprintf(summary_ivanic, sizeof summary_ivanic, "orth %s at l = 50, %s at l = 100, first > 2.2e-10 at l = %s, fails (> 1) after l = %d",
                         o[0], o[1], b2, a.last_band);
        }
    exp_index("The stability map: the error of each exact rotation method against the band, "
              "as the maximum over the 10 rotations of `shlab stability` (β = 0, 1e-12, π/2, "
              "π−1e-9, π, the gimbal-lock cases, two random). *orth* = max|RRᵀ − I| (exact to l = "
              "128, two-probe estimate above), *hom* = |R(a)R(b)v − R(ab)v| on unit probes, *ref* = "
              "distance to the MPFR reference (l ≤ 40). A sweep stops once orth exceeds 1. "
              "Command: `shlab stability --method M --lmax L [--precision float]` gives the same rows.\n\n"
              "![orthogonality error vs band, double](stability_double.png)\n\n"
              "![orthogonality error vs band, float](stability_float.png)\n\n"
              "%s\n"
              "ε = 2.2e-16 (double) or 1.2e-7 (float); * above l = 128 orth is the two-probe estimate, "
              "the largest entry of the residual vector Rᵀ(R v) − v, which runs 5–10× below the exact "
              "maximum entry of RRᵀ − I at the same band: the step down at l = 128 in the plot (dotted "
              "line, open markers) is the change of measure, not an improvement. "
              "The recursions in l that start from the 3×3 matrix (Ivanic-Ruedenberg, Choi's complex "
              "recursion) amplify rounding error geometrically with the band; the single-band methods "
              "(zxzxz with generated X±90 blocks, blanco's m-recurrence for d^l(β), halfpi through the "
              "generated d(π/2)) stay near l·ε to l = 1000 (and to 4000, below); the direct Wigner sum cancels catastrophically (its terms grow like 4^l).\n",
              table);
    const int lost = ivanic_t2 > 0 && ivanic_t2 <= 200;
    exp_claim_judged("high-degree-recursions", "Gumerov & Duraiswami 2015",
                     "recursions in l exact to rounding at low degree can lose all accuracy by l ~ 100-200 (also "
                     "Lessig, de Witt & Fiume 2012)",
                     "qualitative", summary_ivanic, "orth > 2.2e-10 by l = 200", lost,
                     "rotation_stability/ivanic_double.dat (Ivanic-Ruedenberg); Choi's recursion alike (choi_double.dat)",
                     "the Ivanic-Ruedenberg recursion keeps orth below 2.2e-10 to l = 200.");
    return 0;
}
