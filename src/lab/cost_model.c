/* cost_model.c — what a rotation costs on the paths users run, the same on
 * every run: instructions counted under valgrind's callgrind, turned into
 * nanoseconds by a calibration measured once (`make report`, experiment
 * trade_atlas) and committed as data/cost_model.tsv.  `shlab plan`, the
 * scene planner and the trade atlas read their costs from here.
 *
 * The table.  One row per (order, method, precision, input, mode) that the
 * experiment measured, the kernel `auto` picked:
 *   instructions  per rotated vector (shlab bench --instructions: runs of N
 *                 and 2N iterations, the difference; load-independent, the
 *                 same binary gives the same counts);
 *   ns            per rotated vector, the interleaved bench's median in the
 *                 calibration run (machine- and load-dependent);
 *   spread        that run's (q3 − q1)/median.
 * The build turns the table into C (Makefile: $(BUILD)/gen/cost_table.inc),
 * so the model needs no file at run time.
 *
 * The model.  cost(row) = instructions(row) × c(group), where the group is
 * (method, precision, input, mode, kernel) and c(group) the median over
 * its rows (the orders the kernel serves) of ns / instructions — except a
 * per-rotation row at an order where the method runs its own one-vector
 * kernel (sh__rot_one_vector), which is its own group: valgrind counts the
 * AVX2 path, not the AVX-512 kernel timed, and zxzxz's kernel of orders
 * 3..6 grows more slowly with the order than those counts (ns / instruction
 * 0.098 at order 3, 0.044 at 6 in one calibration), so one c for the method's
 * rows was 2× off at order 6, and one for the four orders still 1.6×; there
 * the cost is the calibration's time of that order.  Otherwise: instructions
 * carry how the work grows with the order; c carries the kernel's speed per
 * instruction on that path (its IPC on the calibration machine; the input
 * forms differ: Euler angles cost trigonometric calls), taken over many
 * rows so that one noisy sample does not move it.  Orders between measured ones: log
 * instructions linear in log order between the two neighbours (the work is
 * a power of the order, piecewise), c from the kernel auto picks there
 * (or the upper neighbour's when that kernel was not measured).
 */
#include "lab/lab.h"

#include "core/shlab_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int order;
    const char *method, *prec, *input, *mode;
    int batch;
    const char *kernel;
    double instructions, mults, ns, spread;
} cost_row_src;

/* SH_COST_SOURCE and the rows (generated from data/cost_model.tsv) */
static const cost_row_src cost_rows[] = {
#include "cost_table.inc"
    {0, NULL, NULL, NULL, NULL, 0, NULL, 0, 0, 0, 0}};
#ifndef SH_COST_SOURCE
#define SH_COST_SOURCE ""
#endif

typedef struct {
    int order, batch;
    sh_rot_method method;
    sh_precision prec;
    sh_bench_input input;
    sh_bench_mode mode;
    sh_rot_kernel kernel;
    int one; /* the method's one-vector kernel (the model's header) */
    double instructions, mults, ns;
} cost_row;

static cost_row *rows;
static int nrows;
static pthread_once_t rows_once = PTHREAD_ONCE_INIT;

static int parse_mode(const char *s, sh_bench_mode *m)
{
    for (int k = 0; k <= SH_BENCH_KROT; k++)
        if (!strcmp(s, sh_bench_mode_name((sh_bench_mode)k))) return *m = (sh_bench_mode)k, 0;
    return -1;
}
static int parse_input(const char *s, sh_bench_input *in)
{
    for (int k = 0; k < SH_BENCH_NINPUTS; k++)
        if (!strcmp(s, sh_bench_input_name((sh_bench_input)k))) return *in = (sh_bench_input)k, 0;
    return -1;
}

/* A per-rotation path on the method's one-vector kernel (the batches and
 * k rotations run the others). */
static int one_vector(int order, sh_rot_method m, sh_precision p, sh_bench_mode md, sh_rot_kernel k)
{
    return md == SH_BENCH_PER_ROTATION && sh__rot_one_vector(order, m, p, k);
}

/* The table parsed once; rows this build does not know (a method or kernel
 * renamed since the calibration) are left out. */
static void rows_load(void)
{
    const int n = (int)(sizeof cost_rows / sizeof *cost_rows) - 1;
    rows = n > 0 ? calloc((size_t)n, sizeof *rows) : NULL;
    if (!rows) return;
    for (int i = 0; i < n; i++) {
        const cost_row_src *s = &cost_rows[i];
        cost_row r = {.order = s->order, .batch = s->batch, .instructions = s->instructions,
                      .mults = s->mults, .ns = s->ns};
        if (sh_rot_method_parse(s->method, &r.method) || sh_precision_parse(s->prec, &r.prec) ||
            parse_input(s->input, &r.input) || parse_mode(s->mode, &r.mode) ||
            sh_rot_kernel_parse(s->kernel, &r.kernel) || !(r.instructions > 0) || !(r.ns > 0))
            continue;
        r.one = one_vector(r.order, r.method, r.prec, r.mode, r.kernel);
        rows[nrows++] = r;
    }
}

static int same_path(const cost_row *r, sh_rot_method m, sh_precision p, sh_bench_input in, sh_bench_mode md)
{
    return r->method == m && r->prec == p && r->input == in && r->mode == md;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* c(group): the median of ns / instructions over the rows of (method,
 * precision, input, mode, kernel), or of the one row of that order on a
 * one-vector kernel (order > 0; header); 0 when the group has no row. */
static double calibration(sh_rot_method m, sh_precision p, sh_bench_input in, sh_bench_mode md, sh_rot_kernel k,
                          int one_order)
{
    double *q = malloc(sizeof *q * (size_t)(nrows ? nrows : 1));
    int n = 0;
    for (int i = 0; q && i < nrows; i++)
        if (same_path(&rows[i], m, p, in, md) && rows[i].kernel == k &&
            (one_order ? rows[i].one && rows[i].order == one_order : !rows[i].one))
            q[n++] = rows[i].ns / rows[i].instructions;
    double c = 0;
    if (n > 0) {
        qsort(q, (size_t)n, sizeof *q, cmp_double);
        c = n % 2 ? q[n / 2] : 0.5 * (q[n / 2 - 1] + q[n / 2]);
    }
    free(q);
    return c;
}

const char *sh_cost_model_source(void) { return SH_COST_SOURCE; }

int sh_cost_model_range(sh_rot_method m, sh_precision p, sh_bench_input in, sh_bench_mode md, int *lo, int *hi)
{
    pthread_once(&rows_once, rows_load);
    *lo = *hi = 0;
    for (int i = 0; i < nrows; i++)
        if (same_path(&rows[i], m, p, in, md)) {
            if (!*lo || rows[i].order < *lo) *lo = rows[i].order;
            if (rows[i].order > *hi) *hi = rows[i].order;
        }
    return *hi > 0;
}

int sh_cost_model(int order, sh_rot_method m, sh_precision p, sh_bench_input in, sh_bench_mode md, sh_cost *out)
{
    pthread_once(&rows_once, rows_load);
    memset(out, 0, sizeof *out);
    const cost_row *below = NULL, *above = NULL;
    for (int i = 0; i < nrows; i++) {
        const cost_row *r = &rows[i];
        if (!same_path(r, m, p, in, md)) continue;
        if (r->order <= order && (!below || r->order > below->order)) below = r;
        if (r->order >= order && (!above || r->order < above->order)) above = r;
    }
    if (!below || !above)
        return sh_error(SH_ENOTSUP, "cost model: no %s %s %s %s cost at order %d (measured orders: %s)",
                        sh_rot_method_name(m), sh_precision_name(p), sh_bench_input_name(in),
                        sh_bench_mode_name(md), order, nrows ? "see data/cost_model.tsv" : "none in this build");
    out->order = order;
    out->batch = above->batch;
    if (below == above) {
        out->kernel = below->kernel;
        out->instructions = below->instructions;
        out->mults = below->mults;
    } else {
        const double t = (log(order) - log(below->order)) / (log(above->order) - log(below->order));
        out->instructions = exp((1 - t) * log(below->instructions) + t * log(above->instructions));
        out->mults = below->mults > 0 && above->mults > 0
                         ? exp((1 - t) * log(below->mults) + t * log(above->mults)) : 0;
        out->kernel = sh_rot_plan_kernel_for(order, m, SH_KERNEL_AUTO);
        out->interpolated = 1;
    }
    double c = calibration(m, p, in, md, out->kernel, one_vector(order, m, p, md, out->kernel) ? order : 0);
    if (!(c > 0)) c = calibration(m, p, in, md, above->kernel, above->one ? above->order : 0);
    out->ns_per_instruction = c;
    out->ns = out->instructions * c;
    return SH_OK;
}
