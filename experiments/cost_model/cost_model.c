/* cost_model — the calibration of the cost model (src/lab/cost_model.c):
 * for every method the planner may choose, on the paths users run, the
 * instructions per rotated vector counted under valgrind's callgrind and
 * the interleaved bench's time, written to data/cost_model.tsv (committed;
 * the build compiles it into the planner, so `make report` rebuilds after
 * this experiment).
 *
 * Paths (shlab bench's names), each precision:
 *   orders 1..16    per-rotation from a matrix, a quaternion, Euler angles;
 *                   k-rotations (256 rotations per call) from matrices and
 *                   quaternions; batched (one rotation, 256 vectors) — the
 *                   batched paths without choi and wigner (BATCH_METHODS);
 *   orders 20..64   per-rotation from a matrix (the O(n⁴) methods choi and
 *                   wigner up to 32, where they are already far off the
 *                   frontier; direct stops at order 3).
 * Instructions are counted with the widest kernel valgrind runs (AVX2;
 * it cannot run AVX-512), times taken with the kernel `auto` picks; the
 * model's calibration c = ns / instruction per (method, precision, mode,
 * kernel) absorbs the difference.  Needs valgrind; without it the table is
 * left as committed.
 */
#include "exp.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_ROWS 4096
#define NCOL 32

typedef struct {
    char method[16], prec[8], input[8], mode[16], kernel[12];
    int order, batch;
    double ins, mults, ns, spread;
} row;
static row R[MAX_ROWS];
static int NR;

/* The batched paths leave out the O(n⁴) methods choi and wigner: one
 * rotation costs them 10-1000× the frontier's at every order here, and 256
 * of them per call under callgrind would take most of the run. */
#define BATCH_METHODS "--methods z,ivanic,zxzxz,blanco,taylor1,taylor1.5,taylor2,halfpi"

/* One bench call's sets of arguments, per precision. */
static const struct {
    const char *args;
    int count; /* --count under callgrind */
} SETS[] = {
    {"--order 1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16 --input matrix,quat,euler --mode per-rotation", 16},
    /* direct (orders ≤ 3): every path; the default methods above leave it out */
    {"--order 1,2,3 --methods direct --input matrix,quat,euler --mode per-rotation", 16},
    {"--order 1,2,3 --methods direct --input matrix,quat --mode k-rotations --batch 256", 1},
    {"--order 1,2,3 --methods direct --input matrix --mode batched --batch 256", 1},
    /* zh (orders ≤ 6): the same paths */
    {"--order 1,2,3,4,5,6 --methods zh --input matrix,quat,euler --mode per-rotation", 16},
    {"--order 1,2,3,4,5,6 --methods zh --input matrix,quat --mode k-rotations --batch 256", 1},
    {"--order 1,2,3,4,5,6 --methods zh --input matrix --mode batched --batch 256", 1},
    {"--order 1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16 --input matrix,quat --mode k-rotations --batch 256 " BATCH_METHODS, 1},
    {"--order 1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16 --input matrix --mode batched --batch 256 " BATCH_METHODS, 1},
    {"--order 20,24,32 --input matrix --mode per-rotation "
     "--methods z,ivanic,zxzxz,choi,blanco,wigner,taylor1,taylor1.5,taylor2,halfpi", 4},
    {"--order 48,64 --input matrix --mode per-rotation "
     "--methods z,ivanic,zxzxz,blanco,taylor1,taylor1.5,taylor2,halfpi", 2},
};

/* Split a CSV line in place (bench's CSV quotes no field we read). */
static int split(char *line, char **c)
{
    int n = 0;
    for (char *s = line, *t; n < NCOL && (t = strsep(&s, ",\n"));) c[n++] = t;
    return n;
}
static int col(char **hdr, int nh, const char *name)
{
    for (int k = 0; k < nh; k++)
        if (!strcmp(hdr[k], name)) return k;
    fprintf(stderr, "cost_model: shlab bench printed no column '%s'\n", name);
    exit(1);
}

static row *find(const char *m, int order, const char *prec, const char *in, const char *mode)
{
    for (int i = 0; i < NR; i++)
        if (R[i].order == order && !strcmp(R[i].method, m) && !strcmp(R[i].prec, prec) &&
            !strcmp(R[i].input, in) && !strcmp(R[i].mode, mode))
            return &R[i];
    if (NR == MAX_ROWS) { fprintf(stderr, "cost_model: too many rows\n"); exit(1); }
    row *r = &R[NR++];
    memset(r, 0, sizeof *r);
    snprintf(r->method, sizeof r->method, "%s", m);
    snprintf(r->prec, sizeof r->prec, "%s", prec);
    snprintf(r->input, sizeof r->input, "%s", in);
    snprintf(r->mode, sizeof r->mode, "%s", mode);
    r->order = order;
    return r;
}

/* Run one bench command (instructions or timing) and fold its rows in. */
static int run_bench(const char *args, const char *prec, int instructions, int count)
{
    const char *shlab = getenv("SHLAB") ? getenv("SHLAB") : "build/shlab";
    char cmd[1024], line[4096];
    if (instructions)
        snprintf(cmd, sizeof cmd, "%s bench --instructions --count %d %s --precision %s --format csv --quiet",
                 shlab, count, args, prec);
    else
        snprintf(cmd, sizeof cmd, "%s bench --repeat 9 --target-ms 2 %s --precision %s --format csv --quiet", shlab,
                 args, prec);
    FILE *f = popen(cmd, "r");
    if (!f) return 0;
    char *hdr[NCOL], hline[4096] = "";
    int nh = 0, n = 0;
    while (fgets(line, sizeof line, f)) {
        if (!nh) {
            snprintf(hline, sizeof hline, "%s", line);
            nh = split(hline, hdr);
            continue;
        }
        char *c[NCOL];
        if (split(line, c) != nh) continue;
        row *r = find(c[col(hdr, nh, "method")], atoi(c[col(hdr, nh, "order")]), prec, c[col(hdr, nh, "input")],
                      c[col(hdr, nh, "mode")]);
        r->batch = atoi(c[col(hdr, nh, "batch")]);
        r->mults = strtod(c[col(hdr, nh, "mults")], NULL);
        if (instructions) {
            r->ins = strtod(c[col(hdr, nh, "instructions")], NULL);
        } else {
            r->ns = strtod(c[col(hdr, nh, "ns_median")], NULL);
            r->spread = strtod(c[col(hdr, nh, "spread")], NULL);
            snprintf(r->kernel, sizeof r->kernel, "%s", c[col(hdr, nh, "kernel")]);
        }
        n++;
    }
    const int rc = pclose(f);
    if (rc) fprintf(stderr, "cost_model: '%s' failed\n", cmd);
    return rc == 0 && n > 0;
}

static void cpu_name(char *buf, size_t n)
{
    snprintf(buf, n, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
            char *s = strchr(line, ':') + 2;
            s[strcspn(s, "\n")] = 0;
            snprintf(buf, n, "%s", s);
            break;
        }
    if (f) fclose(f);
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    if (system("command -v valgrind >/dev/null 2>&1") != 0) {
        exp_kept("model", "valgrind is not installed; data/cost_model.tsv left as committed");
        return 0;
    }
    static const char *const precs[] = {"float", "double"};
    const int nsets = (int)(sizeof SETS / sizeof *SETS);
    for (int p = 0; p < 2; p++)
        for (int s = 0; s < nsets; s++) {
            exp_progress("cost_model: %s, set %d of %d: instructions under callgrind", precs[p], s + 1, nsets);
            if (!run_bench(SETS[s].args, precs[p], 1, SETS[s].count)) return 1;
            exp_progress("cost_model: %s, set %d of %d: timing", precs[p], s + 1, nsets);
            if (!run_bench(SETS[s].args, precs[p], 0, 0)) return 1;
        }
    const char *out = getenv("COST_MODEL_OUT") ? getenv("COST_MODEL_OUT") : "data/cost_model.tsv";
    char tmp[1024], cpu[256], date[32];
    snprintf(tmp, sizeof tmp, "%s.tmp", out);
    cpu_name(cpu, sizeof cpu);
    const time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&now));
    FILE *f = fopen(tmp, "w");
    if (!f) { fprintf(stderr, "cost_model: cannot write %s\n", tmp); return 1; }
    /* one line, no commas (it is printed as one CSV field) */
    for (char *c = cpu; *c; c++)
        if (*c == ',') *c = ';';
    fprintf(f, "# source: calibrated at code revision %s on %s; %s; make report (experiment cost_model)\n",
            exp_revision(), date, cpu);
    fprintf(f, "# The cost model's table (src/lab/cost_model.c): instructions per rotated vector under callgrind "
               "(AVX2 at most), ns per rotated vector by the interleaved bench (kernel auto), its spread.\n");
    fprintf(f, "order\tmethod\tprecision\tinput\tmode\tbatch\tkernel\tinstructions\tmults\tns\tspread\n");
    int kept = 0;
    for (int i = 0; i < NR; i++) {
        const row *r = &R[i];
        if (!(r->ins > 0) || !(r->ns > 0)) continue;
        fprintf(f, "%d\t%s\t%s\t%s\t%s\t%d\t%s\t%.6g\t%.6g\t%.5g\t%.3f\n", r->order, r->method, r->prec, r->input,
                r->mode, r->batch, r->kernel, r->ins, r->mults, r->ns, r->spread);
        kept++;
    }
    if (fclose(f) || rename(tmp, out)) { fprintf(stderr, "cost_model: cannot write %s\n", out); return 1; }
    exp_part("model");
    exp_index("The cost model's calibration: %d rows (method × order × precision × input × mode) in "
              "`data/cost_model.tsv`, instructions counted under callgrind and times by the interleaved bench, "
              "computed at code revision `%s` on %s. The planner (`shlab plan`), the trade atlas and the scene "
              "planner cost methods as instructions × the median ns per instruction of the method's "
              "(precision, input, mode, kernel) rows (src/lab/cost_model.c).",
              kept, exp_revision(), cpu);
    return 0;
}
