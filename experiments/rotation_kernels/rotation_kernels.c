/* rotation_kernels — the rotation kernels at low orders (n = 3, 4, 5, 6, 10),
 * float and double: the path every earlier shlab ran (the loop kernels fed
 * a 3×3 matrix through ZYZ angles, vectors as double) against the matrix
 * input (sh_rot_plan_set_matrix(_f), no trigonometric call) with the loop,
 * unrolled, SSE2, AVX2 and AVX-512 kernels one rotation at a time, one
 * rotation on K vectors (apply_many) and K rotations of K vectors
 * (rotate_many, structure of arrays), K = 256.
 *
 * It is a separate experiment from rotation_speed because it answers other
 * questions (how fast the kernels are, and the speed goals set for them)
 * with other entries (kernels, inputs, precisions, K = 256, low orders);
 * rotation_speed is the paper's Table 1 and every method's cost at orders
 * 2–16 in double.  Both time with the library's one engine.
 *
 * Time (timing part): every variant is an entry of sh_rot_bench_entry
 * (sh_bench_opts.kernel / .input, SH_BENCH_BATCHED, SH_BENCH_KROT); the
 * entries of one (precision, order) are timed in one interleaved run
 * (sh_bench_interleaved), and speed-ups are paired ratios
 * (sh_bench_paired_ratio: median and quartiles over the rounds of
 * t(old) / t(variant) in the same round).  A speed claim is judged only when
 * its runs meet the noise criterion of measure.h on the entries it uses, and
 * only where the ratio's uncertainty (exp_ratio_side) lies wholly on one side
 * of the goal; otherwise "not-measured" or "inconclusive".
 *
 * Instructions (kept part "instructions", deterministic for one binary):
 * `shlab bench --instructions` (valgrind's callgrind) for every variant
 * except AVX-512, which valgrind cannot run (its CPUID hides it, so `auto`
 * is AVX2 there).
 *
 * Goals judged (speed goals set for the kernels):
 *  G1  float, from a matrix, one rotation at a time: the fastest exact method
 *      ≥ 4× faster than the old zxzxz float path, n = 3..6;
 *  G2  float taylor1.5 (fastest kernel) ≤ 0.5× the time of that exact one;
 *  G3  K rotations of K vectors, float, n = 6: ≤ 0.25× the fastest exact
 *      method's one-at-a-time time, per rotation;
 *  G4  double, n = 6 and 10: every exact method reworked (zxzxz, ivanic,
 *      blanco) ≥ 2× faster from a matrix than its own old path.
 */
#include "exp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { K = 256, NO = 5, NPREC = 2 };
static const int ORDERS[NO] = {3, 4, 5, 6, 10};

#define ZX SH_ROT_ZXZXZ
#define T15 SH_ROT_TAYLOR15
#define IV SH_ROT_IVANIC
#define BL SH_ROT_BLANCO
#define EU SH_BENCH_INPUT_EULER
#define MX SH_BENCH_INPUT_MATRIX
#define PR SH_BENCH_PER_ROTATION
#define BA SH_BENCH_BATCHED
#define KR SH_BENCH_KROT

/* The variants, in the order of the data files' rows.  id: a token for the
 * data files and the plots; the first is the old zxzxz path, the baseline
 * of every speed-up, and each method's euler variant is its old path. */
typedef struct {
    const char *id;
    sh_rot_method m;
    sh_rot_kernel k;
    sh_bench_input in;
    sh_bench_mode md;
} variant;
static const variant V[] = {
    {"old-zxzxz", ZX, SH_KERNEL_SCALAR, EU, PR},
    {"zxzxz-scalar", ZX, SH_KERNEL_SCALAR, MX, PR},
    {"zxzxz-unrolled", ZX, SH_KERNEL_UNROLLED, MX, PR},
    {"zxzxz-sse2", ZX, SH_KERNEL_SSE2, MX, PR},
    {"zxzxz-avx2", ZX, SH_KERNEL_AVX2, MX, PR},
    {"zxzxz-avx512", ZX, SH_KERNEL_AVX512, MX, PR},
    {"zxzxz-many", ZX, SH_KERNEL_AUTO, MX, BA},
    {"zxzxz-krot-scalar", ZX, SH_KERNEL_SCALAR, MX, KR},
    {"zxzxz-krot-sse2", ZX, SH_KERNEL_SSE2, MX, KR},
    {"zxzxz-krot-avx2", ZX, SH_KERNEL_AVX2, MX, KR},
    {"zxzxz-krot-avx512", ZX, SH_KERNEL_AVX512, MX, KR},
    {"old-taylor1.5", T15, SH_KERNEL_SCALAR, EU, PR},
    {"taylor1.5-unrolled", T15, SH_KERNEL_UNROLLED, MX, PR},
    {"taylor1.5-avx2", T15, SH_KERNEL_AVX2, MX, PR},
    {"taylor1.5-avx512", T15, SH_KERNEL_AVX512, MX, PR},
    {"taylor1.5-krot", T15, SH_KERNEL_AUTO, MX, KR},
    {"old-ivanic", IV, SH_KERNEL_SCALAR, EU, PR},
    {"ivanic-auto", IV, SH_KERNEL_AUTO, MX, PR},
    {"old-blanco", BL, SH_KERNEL_SCALAR, EU, PR},
    {"blanco-auto", BL, SH_KERNEL_AUTO, MX, PR},
};
enum { NV = sizeof V / sizeof *V };

static int is_exact(sh_rot_method m) { return m == ZX || m == IV || m == BL; }
static int old_of(int v) /* the old variant of v's method */
{
    for (int j = 0; j < NV; j++)
        if (V[j].m == V[v].m && V[j].in == EU) return j;
    return 0;
}
/* one rotation at a time from a matrix (the G1/G2 candidates) */
static int one_matrix(int v) { return V[v].in == MX && V[v].md == PR; }

/* ---- results ----------------------------------------------------------- */
typedef struct {
    int have;                 /* timed (kernel available) */
    sh_rot_kernel used;       /* the kernel the plan ran */
    sh_bench_stats st;        /* ns per rotated vector */
    sh_bench_ratio sp, own;   /* paired t(old zxzxz)/t, t(old of its method)/t */
    double mults;             /* counted multiplications per rotated vector */
    double ins;               /* instructions per rotated vector (0: not counted) */
    sh_rot_kernel ins_used;   /* the kernel under valgrind */
} result;
static result RES[NPREC][NO][NV];
static sh_bench_noise NZ[NPREC][NO];
static double SMP[NPREC][NO][NV][64];
static const char *prec_name(int p) { return p ? "double" : "float"; }

/* ---- instructions: `shlab bench --instructions` per variant ------------- */
static int count_variant(int p, int v)
{
    const char *shlab = getenv("SHLAB") ? getenv("SHLAB") : "build/shlab";
    char cmd[1024], ord[64] = "";
    for (int q = 0; q < NO; q++) snprintf(ord + strlen(ord), sizeof ord - strlen(ord), "%s%d", q ? "," : "", ORDERS[q]);
    snprintf(cmd, sizeof cmd,
             "%s bench --instructions --order %s --methods %s --precision %s --kernel %s --input %s --mode %s "
             "--batch %d --format csv --quiet",
             shlab, ord, sh_rot_method_name(V[v].m), prec_name(p), sh_rot_kernel_name(V[v].k),
             sh_bench_input_name(V[v].in), sh_bench_mode_name(V[v].md), K);
    FILE *f = popen(cmd, "r");
    if (!f) return 0;
    char line[1024];
    int rows = 0;
    while (fgets(line, sizeof line, f)) {
        char *c[16];
        int nc = 0;
        for (char *s = line, *t; nc < 16 && (t = strsep(&s, ",\n"));) c[nc++] = t;
        /* convention,tool,n,method,order,precision,mode,kernel,input,instructions,mults,batch */
        if (nc < 11 || !strcmp(c[3], "method")) continue;
        const int n = atoi(c[4]);
        for (int q = 0; q < NO; q++)
            if (ORDERS[q] == n) {
                RES[p][q][v].ins = strtod(c[9], NULL);
                if (sh_rot_kernel_parse(c[7], &RES[p][q][v].ins_used)) RES[p][q][v].ins_used = SH_KERNEL_SCALAR;
                rows++;
            }
    }
    return pclose(f) == 0 && rows == NO;
}
static int count_instructions(void)
{
    if (system("command -v valgrind >/dev/null 2>&1") != 0) return 0;
    for (int p = 0; p < NPREC; p++)
        for (int v = 0; v < NV; v++) {
            if (V[v].k == SH_KERNEL_AVX512) continue; /* valgrind cannot run it */
            exp_progress("rotation_kernels: instructions, %s %s", prec_name(p), V[v].id);
            if (!count_variant(p, v)) {
                fprintf(stderr, "rotation_kernels: counting %s %s failed\n", prec_name(p), V[v].id);
                return 0;
            }
        }
    return 1;
}

/* ---- verdicts ------------------------------------------------------------ */
/* the noise criterion on the entries a claim uses (as rotation_speed) */
static int claim_noisy(int p, int q, const int *vs, int nvs, const sh_bench_ratio *r, const sh_bench_cfg *cfg,
                       char *why, size_t wn)
{
    const sh_bench_noise *nz = &NZ[p][q];
    double spread = 0;
    for (int k = 0; k < nvs; k++) spread = fmax(spread, RES[p][q][vs[k]].st.spread);
    const int noisy = nz->offcpu > cfg->noise_offcpu || nz->load > cfg->noise_load || spread > cfg->noise_spread ||
                      r->spread > cfg->noise_spread;
    if (noisy)
        snprintf(why + strlen(why), wn - strlen(why), "%s%s n=%d: off-CPU %.1f%%, other load %.2f CPUs, time spread %.1f%%, ratio spread %.1f%%",
                 *why ? "; " : "", prec_name(p), ORDERS[q], 100 * nz->offcpu, nz->load, 100 * spread, 100 * r->spread);
    return noisy;
}
/* why the goals below are out of reach (the same for time and instructions) */
#define TAYLOR_HALF_WHY                                                                                     \
    "taylor1.5's unrolled kernel has 292 products at n = 6 against zxzxz's 344 (the z rotations are the "   \
    "same in both), so no kernel can reach 0.5×."
/* the measured cell of a speed claim from a noisy run (the medians and the
 * noise: kernels.dat, noise.dat and the timing report) */
#define NOISY_MEAS "not measured: a noisy run (noise.dat); medians in kernels.dat and timing.md#rotation_kernels"
#define KROT_WHY "256 rotations at once cost more than 0.25× the fastest exact method's one-at-a-time rotation."
/* the fastest (by median time, or by instructions) of the variants accepted
 * (and of method m, unless m < 0) */
static int fastest(int p, int q, int (*ok)(int), int m, int by_ins)
{
    int best = -1;
    for (int v = 0; v < NV; v++) {
        const result *r = &RES[p][q][v];
        if (!ok(v) || (m >= 0 && (int)V[v].m != m) || !(by_ins ? r->ins > 0 : r->have)) continue;
        const double x = by_ins ? r->ins : r->st.ns_median;
        if (best < 0 || x < (by_ins ? RES[p][q][best].ins : RES[p][q][best].st.ns_median)) best = v;
    }
    return best;
}
static int exact_one(int v) { return one_matrix(v) && is_exact(V[v].m); }
static int taylor_one(int v) { return one_matrix(v) && V[v].m == T15; }
static int exact_krot(int v) { return V[v].md == KR && is_exact(V[v].m); }
/* ns with 3 significant digits, without an exponent */
static const char *fmt_ns(char *b, double x)
{
    snprintf(b, 32, x >= 100 ? "%.0f" : x >= 10 ? "%.1f" : "%.2f", x);
    return b;
}
static double *smp(int p, int q, int v) { return SMP[p][q][v]; }
static int qof(int n)
{
    for (int q = 0; q < NO; q++)
        if (ORDERS[q] == n) return q;
    return 0;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    bo.batch = K;
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.samples = 21;
    cfg.min_sample_ms = 3;
    const int S = cfg.samples;
    char buf[4096];

    /* ---- deterministic part: what is compared ---------------------------- */
    exp_index("The rotation kernels at orders 3, 4, 5, 6, 10 in float and double. **old** is the path "
              "every earlier shlab ran: a seeded orthonormal 3×3 matrix → ZYZ angles → `sh_rot_plan_set` → "
              "`sh_rot_plan_apply` with the loop kernels (`--kernel scalar --input euler`), vectors as "
              "double also for float plans. The variants hand the plan the matrix "
              "(`sh_rot_plan_set_matrix(_f)`, no trigonometric call; float plans take float matrices and "
              "vectors) and run the loop kernels (scalar), the generated straight-line kernels (unrolled), "
              "and those compiled for SSE2, AVX2 and AVX-512 (one rotation at a time: SSE2 runs the plain "
              "unrolled code, its lanes serve batches), one rotation applied to %d vectors (`apply_many`, the "
              "widest kernel) and %d rotations of %d vectors in one `rotate_many` call (structure of arrays, "
              "SIMD lanes across rotations); ivanic and blanco from the matrix with their best kernel "
              "(`auto`). Every variant is an entry of `sh_rot_bench_entry`; the entries of one precision and "
              "order are timed in one interleaved run (timing part), and their instructions are counted under "
              "valgrind (next paragraph). Goals judged: float, from a matrix, one at a time, the fastest exact "
              "method ≥ 4× the old zxzxz float path (n = 3..6) and taylor1.5 ≤ 0.5× that exact time; "
              "%d rotations of %d vectors, float, n = 6, ≤ 0.25× the fastest exact one-at-a-time time per "
              "rotation; double, n = 6 and 10, zxzxz, ivanic and blanco each ≥ 2× its old path (choi and "
              "wigner were not reworked). The old path runs today's loop kernels, and those of ivanic and blanco "
              "were reworked along with the fast kernels (blanco: the real block straight from d; ivanic: rows "
              "written once), so their ratio to the old path understates the gain over earlier versions, which "
              "one binary cannot measure.",
              K, K, K, K, K);

    /* ---- kept part: instructions under valgrind --------------------------- */
    exp_progress("rotation_kernels: instructions under callgrind");
    const int have_ins = count_instructions();
    if (have_ins) {
        exp_part("instructions");
        FILE *f = exp_data("instructions.dat",
                           "instructions per rotated vector under valgrind's callgrind (shlab bench --instructions; "
                           "AVX-512 variants are not counted: valgrind cannot run them, and auto is avx2 there)",
                           "precision order variant method kernel input mode instructions ratio_old_zxzxz "
                           "ratio_old_of_method");
        for (int p = 0; p < NPREC; p++)
            for (int q = 0; q < NO; q++)
                for (int v = 0; v < NV; v++) {
                    const result *r = &RES[p][q][v];
                    if (!(r->ins > 0)) continue;
                    fprintf(f, "%s %d %s %s %s %s %s %.8g %.4f %.4f\n", prec_name(p), ORDERS[q], V[v].id,
                            sh_rot_method_name(V[v].m), sh_rot_kernel_name(r->ins_used), sh_bench_input_name(V[v].in),
                            sh_bench_mode_name(V[v].md), r->ins, RES[p][q][0].ins / r->ins,
                            RES[p][q][old_of(v)].ins / r->ins);
                }
        fclose(f);
        /* table: instructions per rotated vector, old → fastest */
        char tab[8192];
        size_t tl = (size_t)snprintf(tab, sizeof tab, "| precision | variant | kernel |");
        for (int q = 0; q < NO; q++) tl += (size_t)snprintf(tab + tl, sizeof tab - tl, " n = %d |", ORDERS[q]);
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "\n|---|---|---|");
        for (int q = 0; q < NO; q++) tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "---|");
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "\n");
        for (int p = 0; p < NPREC; p++)
            for (int v = 0; v < NV; v++) {
                if (!(RES[p][NO - 1][v].ins > 0)) continue;
                tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "| %s | %s | %s |", prec_name(p), V[v].id,
                                       sh_rot_kernel_name(RES[p][NO - 2][v].ins_used));
                for (int q = 0; q < NO; q++) {
                    const result *r = &RES[p][q][v];
                    tl += (size_t)snprintf(tab + tl, sizeof tab - tl, v ? " %.0f (%.1f×) |" : " %.0f |", r->ins,
                                           RES[p][q][0].ins / r->ins);
                }
                tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "\n");
            }
        exp_index("Instructions executed per rotated vector (computed at code revision `%s` under valgrind's "
                  "callgrind by `shlab bench --instructions --batch %d`, one call per variant: each entry runs "
                  "64 and 128 iterations between client requests and the difference is divided by 64, so fixed "
                  "costs drop out; [instructions.dat](instructions.dat)). Load-independent, and the same binary "
                  "gives the same counts (gcc -O2). AVX-512 code does not run under valgrind, so AVX2 is the "
                  "widest counted, and `auto` counts AVX2. In brackets: old zxzxz / variant (of the same "
                  "precision); the kernel column is the one the plan ran at n = 6 (ivanic's unrolled kernels "
                  "stop at n = 6: at n = 10 it runs its loops).\n\n"
                  "![instructions per rotated vector](rotation_kernels_instructions.png)\n\n%s",
                  exp_revision(), K, tab);

        /* the goals, by instructions */
        exp_side s1[4], s2[4];
        size_t bl = 0, b2 = 0;
        char m2[1024] = "", ev[256], why[200], low[96] = "";
        int fe6 = 0, ft6 = 0;
        bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "old zxzxz / fastest exact:");
        b2 += (size_t)snprintf(m2 + b2, sizeof m2 - b2, "fastest taylor1.5 / fastest exact:");
        for (int n = 3; n <= 6; n++) {
            const int q = qof(n), fe = fastest(0, q, exact_one, -1, 1), ft = fastest(0, q, taylor_one, -1, 1);
            const double r1 = RES[0][q][0].ins / RES[0][q][fe].ins, r2 = RES[0][q][ft].ins / RES[0][q][fe].ins;
            s1[n - 3] = r1 >= 4 ? EXP_INSIDE : EXP_OUTSIDE;
            s2[n - 3] = r2 <= 0.5 ? EXP_INSIDE : EXP_OUTSIDE;
            if (r1 < 4) snprintf(low + strlen(low), sizeof low - strlen(low), "%sn = %d", *low ? ", " : "", n);
            bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "%s n=%d %.2f", n > 3 ? "," : "", n, r1);
            b2 += (size_t)snprintf(m2 + b2, sizeof m2 - b2, "%s n=%d %.2f", n > 3 ? "," : "", n, r2);
            fe6 = fe, ft6 = ft;
        }
        snprintf(buf + bl, sizeof buf - bl, " (%s at n=6; instructions per rotated vector)", V[fe6].id);
        snprintf(m2 + b2, sizeof m2 - b2, " (%s / %s at n=6)", V[ft6].id, V[fe6].id);
        const char *v1 = exp_sides_verdict(s1, 4), *v2 = exp_sides_verdict(s2, 4);
        snprintf(why, sizeof why, "the fastest exact method executes fewer than 4× fewer instructions than the old "
                 "path at %s.", low);
        exp_claim("kernels-float-matrix-4x-instructions", "shlab goal",
                  "float, from a 3x3 matrix, one rotation at a time: the fastest exact method executes >= 4x fewer "
                  "instructions than the old scalar zxzxz float path (angles, loop kernels), n = 3..6",
                  ">= 4", buf, ">= 4 at every n (exact counts)", v1,
                  exp_evidence(ev, sizeof ev, "rotation_kernels/instructions/instructions.dat (callgrind; AVX2 the "
                               "widest counted)", v1, why));
        exp_claim("kernels-float-taylor-half-instructions", "shlab goal",
                  "float taylor1.5 from a matrix executes <= 0.5x the instructions of the fastest exact method, n = 3..6",
                  "<= 0.5", m2, "<= 0.5 at every n (exact counts)", v2,
                  exp_evidence(ev, sizeof ev, "rotation_kernels/instructions/instructions.dat", v2, TAYLOR_HALF_WHY));
        {
            const int q = qof(6), fe = fastest(0, q, exact_one, -1, 1), fk = fastest(0, q, exact_krot, -1, 1);
            const double r = RES[0][q][fk].ins / RES[0][q][fe].ins;
            snprintf(buf, sizeof buf, "n=6: %.0f / %.0f = %.3f (%s / %s)", RES[0][q][fk].ins, RES[0][q][fe].ins, r,
                     V[fk].id, V[fe].id);
            exp_claim_judged("kernels-krot-quarter-instructions", "shlab goal",
                             "float, n = 6: K = 256 rotations of 256 vectors execute <= 0.25x the instructions per "
                             "rotation of the fastest exact method one rotation at a time",
                             "<= 0.25", buf, "<= 0.25 (exact counts)", r <= 0.25,
                             "rotation_kernels/instructions/instructions.dat (AVX2 lanes, 8 floats)", KROT_WHY);
        }
        {
            exp_side s[6];
            bl = (size_t)snprintf(buf, sizeof buf, "old / from a matrix (n = 6, 10):");
            int k = 0;
            char low[128] = "", ev[256], why[256];
            for (int v = 0; v < NV; v++) {
                if (V[v].in != EU || !is_exact(V[v].m)) continue;
                bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "%s %s", k ? ";" : "", sh_rot_method_name(V[v].m));
                for (int n = 6; n <= 10; n += 4) {
                    const int q = qof(n);
                    const int best = fastest(1, q, one_matrix, (int)V[v].m, 1);
                    const double r = RES[1][q][v].ins / RES[1][q][best].ins;
                    s[k++] = r >= 2 ? EXP_INSIDE : EXP_OUTSIDE;
                    if (r < 2)
                        snprintf(low + strlen(low), sizeof low - strlen(low), "%s%s n=%d", *low ? ", " : "",
                                 sh_rot_method_name(V[v].m), n);
                    bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "%s %.2f (%s)", n == 6 ? "" : ",", r,
                                           sh_rot_kernel_name(RES[1][q][best].ins_used));
                }
            }
            const char *v4 = exp_sides_verdict(s, k);
            snprintf(why, sizeof why, "below 2 for %s: the old path runs today's (reworked) loop "
                     "kernels (index.md#rotation_kernels).", low);
            exp_claim("kernels-double-2x-instructions", "shlab goal",
                      "double, n = 6 and 10: zxzxz, ivanic and blanco from a matrix each execute >= 2x fewer "
                      "instructions than their old path (angles, loop kernels)",
                      ">= 2", buf, ">= 2 for every method and n (exact counts)", v4,
                      exp_evidence(ev, sizeof ev, "rotation_kernels/instructions/instructions.dat", v4, why));
        }
        FILE *fv = exp_data("variants.txt", "variants in instructions.dat, in row order", "id");
        for (int v = 0; v < NV; v++)
            if (RES[0][0][v].ins > 0) fprintf(fv, "%s\n", V[v].id);
        fclose(fv);
    } else {
        fprintf(stderr, "rotation_kernels: no valgrind: instruction counts kept as they are\n");
    }
    exp_part(NULL);

    /* ---- timing part ---------------------------------------------------- */
    exp_part("timing");
    for (int p = 0; p < NPREC; p++)
        for (int q = 0; q < NO; q++) {
            const int n = ORDERS[q];
            const sh_precision prec = p ? SH_PREC_DOUBLE : SH_PREC_FLOAT;
            sh_bench_entry e[NV];
            int idx[NV], ne = 0;
            for (int v = 0; v < NV; v++) {
                if (!sh_rot_kernel_available(V[v].k)) continue;
                bo.kernel = V[v].k;
                bo.input = V[v].in;
                exp_check(sh_rot_bench_entry(n, V[v].m, prec, V[v].md, &bo, &e[ne]), V[v].id);
                sh_rot_plan *kp;
                exp_check(sh_rot_plan_create_kernel(n, V[v].m, prec, SH_CS, V[v].k, &kp), V[v].id);
                RES[p][q][v].used = sh_rot_plan_kernel(kp);
                sh_rot_plan_free(kp);
                RES[p][q][v].mults = e[ne].mults;
                RES[p][q][v].have = 1;
                idx[ne++] = v;
            }
            exp_progress("rotation_kernels: timing %s n = %d (%d entries interleaved)", prec_name(p), n, ne);
            double *sm = malloc((size_t)ne * S * sizeof *sm);
            sh_bench_stats st[NV];
            if (!sm) exp_check(SH_ENOMEM, "samples");
            exp_check(sh_bench_interleaved(e, ne, &cfg, sm, st, &NZ[p][q]), "bench");
            for (int i = 0; i < ne; i++) {
                RES[p][q][idx[i]].st = st[i];
                memcpy(SMP[p][q][idx[i]], sm + (size_t)i * S, (size_t)S * sizeof *sm);
                sh_bench_entry_free(&e[i]);
            }
            free(sm);
            for (int i = 0; i < ne; i++) {
                const int v = idx[i];
                result *r = &RES[p][q][v];
                exp_check(sh_bench_paired_ratio(smp(p, q, 0), smp(p, q, v), S, cfg.noise_spread, &r->sp), "ratio");
                exp_check(sh_bench_paired_ratio(smp(p, q, old_of(v)), smp(p, q, v), S, cfg.noise_spread, &r->own),
                          "ratio");
            }
        }
    FILE *f = exp_data("kernels.dat",
                       "ns per rotated vector of each variant, all variants of one precision and order timed "
                       "interleaved in one run; speed-ups paired by round",
                       "precision order variant method kernel input mode ns_min ns_q1 ns_median ns_q3 ns_max "
                       "spread speedup_vs_old_zxzxz q1 q3 speedup_vs_old_of_method q1 q3 mults count sample_ms "
                       "run_noisy");
    fprintf(f, "# %d rounds of samples >= %.0f ms; K = %d (apply_many: one rotation on K vectors; k-rotations: K "
               "rotations of K vectors); speed-up = median over rounds of t(old)/t(variant) in the same round\n",
            S, cfg.min_sample_ms, K);
    for (int p = 0; p < NPREC; p++)
        for (int q = 0; q < NO; q++)
            for (int v = 0; v < NV; v++) {
                const result *r = &RES[p][q][v];
                if (!r->have) continue;
                fprintf(f, "%s %d %s %s %s %s %s %.5g %.5g %.5g %.5g %.5g %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.6g %ld %.3g %d\n",
                        prec_name(p), ORDERS[q], V[v].id, sh_rot_method_name(V[v].m), sh_rot_kernel_name(r->used),
                        sh_bench_input_name(V[v].in), sh_bench_mode_name(V[v].md), r->st.ns_min, r->st.ns_q1,
                        r->st.ns_median, r->st.ns_q3, r->st.ns_max, r->st.spread, r->sp.median, r->sp.q1, r->sp.q3,
                        r->own.median, r->own.q1, r->own.q3, r->mults, r->st.count, r->st.sample_ms, NZ[p][q].noisy);
            }
    fclose(f);
    f = exp_data("noise.dat", "noise of each interleaved run (criterion: measure.h)",
                 "precision order noisy max_spread offcpu load_cpus seconds why");
    int nnoisy = 0;
    for (int p = 0; p < NPREC; p++)
        for (int q = 0; q < NO; q++) {
            const sh_bench_noise *z = &NZ[p][q];
            nnoisy += z->noisy;
            fprintf(f, "%s %d %d %.4f %.4f %.3f %.2f %s\n", prec_name(p), ORDERS[q], z->noisy, z->spread, z->offcpu,
                    z->load, z->seconds, z->noisy ? z->why : "-");
        }
    fclose(f);

    /* ---- timing claims ---------------------------------------------------- */
    char why[2048] = "";
    const char *notm = "not-measured";
    {   /* G1, G2 */
        exp_side s1[4], s2[4];
        int noisy1 = 0, noisy2 = 0;
        char why2[2048] = "", m2[2048] = "", low[96] = "";
        size_t bl = 0, b2 = 0;
        int fe6 = 0, ft6 = 0;
        for (int n = 3; n <= 6; n++) {
            const int q = qof(n), fe = fastest(0, q, exact_one, -1, 0), ft = fastest(0, q, taylor_one, -1, 0);
            sh_bench_ratio r1 = RES[0][q][fe].sp, r2;
            exp_check(sh_bench_paired_ratio(smp(0, q, ft), smp(0, q, fe), S, cfg.noise_spread, &r2), "ratio");
            const int u1[2] = {0, fe}, u2[2] = {ft, fe};
            noisy1 |= claim_noisy(0, q, u1, 2, &r1, &cfg, why, sizeof why);
            noisy2 |= claim_noisy(0, q, u2, 2, &r2, &cfg, why2, sizeof why2);
            s1[n - 3] = exp_ratio_side(&r1, 4, INFINITY);
            s2[n - 3] = exp_ratio_side(&r2, 0, 0.5);
            if (s1[n - 3] == EXP_OUTSIDE)
                snprintf(low + strlen(low), sizeof low - strlen(low), "%sn = %d", *low ? ", " : "", n);
            bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "%sn=%d %.2f [%.2f-%.2f]", n > 3 ? ", " : "", n, r1.median,
                                   r1.q1, r1.q3);
            b2 += (size_t)snprintf(m2 + b2, sizeof m2 - b2, "%sn=%d %.2f [%.2f-%.2f]", n > 3 ? ", " : "", n, r2.median,
                                   r2.q1, r2.q3);
            fe6 = fe, ft6 = ft;
        }
        snprintf(buf + bl, sizeof buf - bl, " (paired t(old)/t(fastest exact); %s at n=6)", V[fe6].id);
        snprintf(m2 + b2, sizeof m2 - b2, " (%s / %s at n=6)", V[ft6].id, V[fe6].id);
        (void)why2;
        const char *v1 = noisy1 ? notm : exp_sides_verdict(s1, 4), *v2 = noisy2 ? notm : exp_sides_verdict(s2, 4);
        char ev[256], wy[160];
        snprintf(wy, sizeof wy, "the fastest exact method is less than 4× as fast as the old path at %s.", low);
        exp_claim("kernels-float-matrix-4x", "shlab goal",
                  "float, from a 3x3 matrix, one rotation at a time: the fastest exact method >= 4x faster than the "
                  "old scalar zxzxz float path (angles, loop kernels) in the same run, n = 3..6",
                  ">= 4", noisy1 ? NOISY_MEAS : buf, ">= 4 at every n (paired ratio's quartiles widened by 5%)", v1,
                  exp_evidence(ev, sizeof ev, "rotation_kernels/timing/kernels.dat", v1, wy));
        exp_claim("kernels-float-taylor-half", "shlab goal",
                  "float taylor1.5 from a matrix (fastest kernel) takes <= 0.5x the time of the fastest exact method, "
                  "n = 3..6", "<= 0.5", noisy2 ? NOISY_MEAS : m2, "<= 0.5 at every n (paired ratio's quartiles widened by 5%)",
                  v2, exp_evidence(ev, sizeof ev, "rotation_kernels/timing/kernels.dat", v2, TAYLOR_HALF_WHY));
    }
    {   /* G3 */
        const int q = qof(6), fe = fastest(0, q, exact_one, -1, 0), fk = fastest(0, q, exact_krot, -1, 0);
        sh_bench_ratio r;
        exp_check(sh_bench_paired_ratio(smp(0, q, fk), smp(0, q, fe), S, cfg.noise_spread, &r), "ratio");
        const int u[2] = {fk, fe};
        char w[1024] = "", ev[256];
        const int noisy = claim_noisy(0, q, u, 2, &r, &cfg, w, sizeof w);
        snprintf(buf, sizeof buf, "n=6: %.3f [%.3f-%.3f] (%.1f / %.1f ns per rotation, %s / %s)", r.median, r.q1, r.q3,
                 RES[0][q][fk].st.ns_median, RES[0][q][fe].st.ns_median, V[fk].id, V[fe].id);
        const exp_side s = exp_ratio_side(&r, 0, 0.25);
        const char *v3 = noisy ? notm : exp_sides_verdict(&s, 1);
        exp_claim("kernels-krot-quarter", "shlab goal",
                  "float, n = 6: K = 256 rotations of 256 vectors take <= 0.25x the time per rotation of the fastest "
                  "exact method one rotation at a time", "<= 0.25", noisy ? NOISY_MEAS : buf,
                  "<= 0.25 (paired ratio's quartiles widened by 5%)", v3,
                  exp_evidence(ev, sizeof ev, "rotation_kernels/timing/kernels.dat", v3, KROT_WHY));
    }
    {   /* G4 */
        exp_side s[6];
        int k = 0, noisy = 0;
        size_t bl = 0;
        char w[2048] = "", low[128] = "", ev[256], wy[256];
        bl = (size_t)snprintf(buf, sizeof buf, "old / from a matrix, paired (n = 6, 10):");
        for (int v = 0; v < NV; v++) {
            if (V[v].in != EU || !is_exact(V[v].m)) continue;
            bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "%s %s", k ? ";" : "", sh_rot_method_name(V[v].m));
            for (int n = 6; n <= 10; n += 4) {
                const int q = qof(n);
                const int best = fastest(1, q, one_matrix, (int)V[v].m, 0);
                const sh_bench_ratio *r = &RES[1][q][best].own;
                const int u[2] = {v, best};
                noisy |= claim_noisy(1, q, u, 2, r, &cfg, w, sizeof w);
                s[k++] = exp_ratio_side(r, 2, INFINITY);
                if (s[k - 1] == EXP_OUTSIDE)
                    snprintf(low + strlen(low), sizeof low - strlen(low), "%s%s n=%d", *low ? ", " : "",
                             sh_rot_method_name(V[v].m), n);
                bl += (size_t)snprintf(buf + bl, sizeof buf - bl, "%s %.2f [%.2f-%.2f]", n == 6 ? "" : ",", r->median,
                                       r->q1, r->q3);
            }
        }
        const char *v4 = noisy ? notm : exp_sides_verdict(s, k);
        snprintf(wy, sizeof wy, "below 2 for %s: the old path runs today's (reworked) loop "
                 "kernels (index.md#rotation_kernels).", low);
        exp_claim("kernels-double-2x", "shlab goal",
                  "double, n = 6 and 10: zxzxz, ivanic and blanco from a matrix each >= 2x faster than their old path "
                  "(angles, loop kernels) in the same run", ">= 2", noisy ? NOISY_MEAS : buf,
                  ">= 2 for every method and n (paired ratio's quartiles widened by 5%)", v4,
                  exp_evidence(ev, sizeof ev, "rotation_kernels/timing/kernels.dat", v4, wy));
    }

    /* ---- timing index ------------------------------------------------------ */
    char tab[16384];
    size_t tl = 0;
    for (int p = 0; p < NPREC; p++) {
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "%s%s — ns per rotated vector: median (min, spread), "
                               "and the paired speed-up over old zxzxz:\n\n| variant | kernel |",
                               p ? "\n" : "", p ? "Double" : "Float");
        for (int q = 0; q < NO; q++)
            tl += (size_t)snprintf(tab + tl, sizeof tab - tl, " n = %d%s |", ORDERS[q], NZ[p][q].noisy ? " (noisy)" : "");
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "\n|---|---|");
        for (int q = 0; q < NO; q++) tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "---|");
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "\n");
        for (int v = 0; v < NV; v++) {
            if (!RES[p][0][v].have) continue;
            tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "| %s | %s |", V[v].id,
                                   sh_rot_kernel_name(RES[p][qof(6)][v].used));
            for (int q = 0; q < NO; q++) {
                const result *r = &RES[p][q][v];
                char a[32], b[32];
                tl += (size_t)snprintf(tab + tl, sizeof tab - tl, " %s (%s, %.0f%%)", fmt_ns(a, r->st.ns_median),
                                       fmt_ns(b, r->st.ns_min), 100 * r->st.spread);
                tl += (size_t)snprintf(tab + tl, sizeof tab - tl, v ? " %.2f× |" : " |", r->sp.median);
            }
            tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "\n");
        }
    }
    exp_index("Time per rotated vector ([kernels.dat](kernels.dat): min, quartiles, max, spread = (q3 − q1)/median, "
              "paired speed-ups with their quartiles, counted multiplications; machine in timing.md). Each "
              "precision and order is one interleaved run of every variant the CPU runs: calibrated samples of at "
              "least %.0f ms, a warm-up round, %d rounds. Speed-up = median over the rounds of t(old zxzxz) / "
              "t(variant) in the same round. Noise ([noise.dat](noise.dat)): %d of %d runs broke the noise "
              "criterion%s.\n\n"
              "![time per rotated vector](rotation_kernels.png)\n\n%s",
              cfg.min_sample_ms, S, nnoisy, NPREC * NO,
              nnoisy ? " (marked below; their speed claims are recorded as not measured and their times are not "
                       "to be compared)"
                     : "",
              tab);
    return 0;
}
