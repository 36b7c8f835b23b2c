/* test_cost_model.c — the cost model (lab/cost_model.c) and the planner's
 * ranking (lab/planner.c).  No timing is asserted: the model is checked
 * against the committed table read here by an independent parser (the
 * calibration is the median ns/instruction of its group, the cost
 * instructions × that), interpolation against its neighbours, the planner's
 * choice against a brute-force search over its candidates' grid errors and
 * model costs, its answer against itself on a second run (determinism), and
 * the extent of an answer in β against one step further. */
#include "testutil.h"

#include "core/shlab_internal.h"
#include "lab/lab.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    int order;
    char method[16], prec[8], input[8], mode[16], kernel[12];
    double ins, ns;
} trow;

/* data/cost_model.tsv, parsed here with sscanf (independent of the build's
 * awk → C path); NULL when the repository has no table. */
static trow *read_table(int *n)
{
    FILE *f = fopen("data/cost_model.tsv", "r");
    *n = 0;
    if (!f) return NULL;
    trow *t = calloc(8192, sizeof *t);
    char line[1024];
    while (t && *n < 8192 && fgets(line, sizeof line, f)) {
        if (line[0] == '#' || !strncmp(line, "order", 5)) continue;
        trow r;
        int batch;
        double mults;
        if (sscanf(line, "%d\t%15s\t%7s\t%7s\t%15s\t%d\t%11s\t%lf\t%lf\t%lf", &r.order, r.method, r.prec, r.input,
                   r.mode, &batch, r.kernel, &r.ins, &mults, &r.ns) == 10)
            t[(*n)++] = r;
    }
    fclose(f);
    return t;
}

static int cmpd(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* every row of the table: cost = instructions × median(ns/ins of its
 * group), the group being (method, precision, input, mode, kernel), but a
 * per-rotation row where the rotator runs the method's own one-vector kernel
 * (sh__rot_one_vector) alone: its cost is its own ns */
START_TEST(test_model_rows)
{
    int n;
    trow *t = read_table(&n);
    ck_assert_msg(t && n > 500, "data/cost_model.tsv has %d rows", n);
    ck_assert_msg(sh_cost_model_source()[0] != 0, "the build has no cost model");
    double *q = malloc(sizeof *q * (size_t)n);
    int *one = malloc(sizeof *one * (size_t)n), checked = 0, ones = 0;
    for (int j = 0; j < n; j++) {
        sh_rot_method m;
        sh_precision p;
        sh_rot_kernel k;
        one[j] = !strcmp(t[j].mode, "per-rotation") && !sh_rot_method_parse(t[j].method, &m) &&
                 !sh_precision_parse(t[j].prec, &p) && !sh_rot_kernel_parse(t[j].kernel, &k) &&
                 sh__rot_one_vector(t[j].order, m, p, k);
        ones += one[j];
    }
    for (int i = 0; i < n; i += 7) { /* a spread-out seventh of the rows */
        int g = 0;
        for (int j = 0; j < n; j++)
            if (!strcmp(t[j].method, t[i].method) && !strcmp(t[j].prec, t[i].prec) && !strcmp(t[j].mode, t[i].mode) &&
                !strcmp(t[j].input, t[i].input) && !strcmp(t[j].kernel, t[i].kernel) && one[j] == one[i] &&
                (!one[i] || t[j].order == t[i].order))
                q[g++] = t[j].ns / t[j].ins;
        qsort(q, (size_t)g, sizeof *q, cmpd);
        const double c = g % 2 ? q[g / 2] : 0.5 * (q[g / 2 - 1] + q[g / 2]);
        sh_rot_method m;
        sh_precision p;
        ck_assert_int_eq(sh_rot_method_parse(t[i].method, &m), SH_OK);
        ck_assert_int_eq(sh_precision_parse(t[i].prec, &p), SH_OK);
        const sh_bench_input in = !strcmp(t[i].input, "matrix") ? SH_BENCH_INPUT_MATRIX
                                  : !strcmp(t[i].input, "quat") ? SH_BENCH_INPUT_QUAT : SH_BENCH_INPUT_EULER;
        const sh_bench_mode md = !strcmp(t[i].mode, "per-rotation") ? SH_BENCH_PER_ROTATION
                                 : !strcmp(t[i].mode, "batched") ? SH_BENCH_BATCHED : SH_BENCH_KROT;
        sh_cost mc;
        ck_assert_int_eq(sh_cost_model(t[i].order, m, p, in, md, &mc), SH_OK);
        ck_assert(!mc.interpolated);
        ck_close(mc.instructions, t[i].ins, 1e-5, 0, "%s %d instructions", t[i].method, t[i].order);
        ck_close(mc.ns, t[i].ins * c, 1e-5, 0, "%s %d %s %s %s ns", t[i].method, t[i].order, t[i].prec, t[i].input,
                 t[i].mode);
        checked++;
    }
    ck_assert(checked > 50);
    /* zxzxz float per-rotation at orders 3..6 and direct's at n ≤ 3 on AVX-512:
     * each costs its own calibration time */
    ck_assert_msg(!sh_rot_kernel_available(SH_KERNEL_AVX512) || ones > 0, "no one-vector row");
    for (int j = 0; j < n; j++) {
        if (!one[j] || strcmp(t[j].input, "matrix")) continue;
        sh_rot_method m;
        sh_precision p;
        sh_cost mc;
        ck_assert_int_eq(sh_rot_method_parse(t[j].method, &m), SH_OK);
        ck_assert_int_eq(sh_precision_parse(t[j].prec, &p), SH_OK);
        ck_assert_int_eq(sh_cost_model(t[j].order, m, p, SH_BENCH_INPUT_MATRIX, SH_BENCH_PER_ROTATION, &mc), SH_OK);
        ck_close(mc.ns, t[j].ns, 1e-5, 0, "%s %d %s one-vector ns", t[j].method, t[j].order, t[j].prec);
    }
    free(q);
    free(one);
    free(t);
}
END_TEST

/* between two measured orders the instructions lie between theirs (the
 * model interpolates log instructions in log order); beyond the table: a
 * clean refusal */
START_TEST(test_model_interpolates)
{
    sh_cost a, b, c;
    const sh_bench_input in = SH_BENCH_INPUT_MATRIX;
    ck_assert_int_eq(sh_cost_model(16, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, in, SH_BENCH_PER_ROTATION, &a), SH_OK);
    ck_assert_int_eq(sh_cost_model(18, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, in, SH_BENCH_PER_ROTATION, &b), SH_OK);
    ck_assert_int_eq(sh_cost_model(20, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, in, SH_BENCH_PER_ROTATION, &c), SH_OK);
    ck_assert(b.interpolated && !a.interpolated && !c.interpolated);
    ck_assert(a.instructions < b.instructions && b.instructions < c.instructions);
    /* geometric mean in log order: 18 = 16^(1−t)·20^t */
    const double t = (log(18.0) - log(16.0)) / (log(20.0) - log(16.0));
    ck_close(b.instructions, pow(a.instructions, 1 - t) * pow(c.instructions, t), 1e-12, 0, "interpolated");
    int lo, hi;
    ck_assert(sh_cost_model_range(SH_ROT_ZXZXZ, SH_PREC_DOUBLE, in, SH_BENCH_PER_ROTATION, &lo, &hi));
    ck_assert_int_eq(sh_cost_model(hi + 1, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, in, SH_BENCH_PER_ROTATION, &a), SH_ENOTSUP);
    ck_assert(strstr(sh_last_error(), "cost model"));
}
END_TEST

/* Over a grid of (order, β, budget, precision, path) the choice is
 * admissible and no admissible candidate costs less by the model (brute
 * force over the candidates' grid errors), and a second run gives the same
 * answer bit for bit. */
START_TEST(test_choice_cheapest)
{
    static const int orders[] = {3, 6, 10};
    static const double betas[] = {5, 20, 90}, budgets[] = {1e-3, 1e-6, 1e-10};
    int decided = 0, none = 0;
    for (int io = 0; io < 3; io++)
        for (int ib = 0; ib < 3; ib++)
            for (int ie = 0; ie < 3; ie++)
                for (int p = 0; p < 2; p++)
                    for (int md = 0; md < 2; md++) {
                        sh_rot_choose_opts o = {0};
                        o.order = orders[io];
                        o.max_beta = betas[ib] * M_PI / 180;
                        o.beta_step = 5 * M_PI / 180;
                        o.tolerance = budgets[ie];
                        o.lobe_exp = 7;
                        o.measure = SH_MEASURE_MAX;
                        o.prec = p ? SH_PREC_DOUBLE : SH_PREC_FLOAT;
                        sh_rot_path path = SH_ROT_PATH_DEFAULT;
                        path.mode = md ? SH_BENCH_KROT : SH_BENCH_PER_ROTATION;
                        path.batch = 256;
                        sh_rot_candidate c[SH_ROT_NMETHODS], c2[SH_ROT_NMETHODS];
                        int nc, ch, ru, nc2, ch2, ru2;
                        ck_assert_int_eq(sh_rot_choose(&o, &path, c, &nc, &ch, &ru, NULL), SH_OK);
                        ck_assert_int_eq(sh_rot_choose(&o, &path, c2, &nc2, &ch2, &ru2, NULL), SH_OK);
                        ck_assert(nc == nc2 && ch == ch2 && ru == ru2);
                        for (int k = 0; k < nc; k++)
                            ck_assert(c[k].method == c2[k].method && c[k].ns_per_rotation == c2[k].ns_per_rotation &&
                                      c[k].max_error == c2[k].max_error && c[k].instructions == c2[k].instructions &&
                                      c[k].kernel == c2[k].kernel && c[k].ok == c2[k].ok);
                        int best = -1;
                        for (int k = 0; k < nc; k++) {
                            ck_assert(c[k].from_model && c[k].ns_per_rotation > 0);
                            if (c[k].max_error <= o.tolerance &&
                                (best < 0 || c[k].ns_per_rotation < c[best].ns_per_rotation))
                                best = k;
                        }
                        if (best < 0) {
                            ck_assert_int_eq(ch, -1);
                            none++;
                            continue;
                        }
                        ck_assert_int_ge(ch, 0);
                        ck_assert(c[ch].max_error <= o.tolerance);
                        ck_assert(c[ch].ns_per_rotation == c[best].ns_per_rotation);
                        if (ru >= 0) ck_assert(c[ru].ns_per_rotation >= c[ch].ns_per_rotation);
                        decided++;
                    }
    /* float cannot meet 1e-10 anywhere; double meets every budget */
    ck_assert_int_ge(none, 18);
    ck_assert_int_ge(decided, 54);
}
END_TEST

/* the extent: worst errors in every unit over the grid, max bounding the
 * others, and the β up to which the answer holds */
START_TEST(test_extent)
{
    sh_rot_choose_opts o = {0};
    o.order = 6;
    o.max_beta = 10 * M_PI / 180;
    o.beta_step = 1 * M_PI / 180;
    o.tolerance = 1e-3;
    o.lobe_exp = 7;
    o.measure = SH_MEASURE_MAX;
    o.prec = SH_PREC_DOUBLE;
    sh_rot_error w;
    double holds;
    /* exact: holds to π */
    ck_assert_int_eq(sh_rot_choose_extent(&o, SH_ROT_ZXZXZ, &w, &holds), SH_OK);
    ck_close(holds, M_PI, 1e-12, 0, "exact holds to pi");
    ck_assert(w.max < 1e-13 && w.coeff <= w.max * (1 + 1e-12) && w.lobe <= w.max * (1 + 1e-12));
    /* two methods on one pass (one exact rotation a step) give what each
     * gives alone */
    {
        const sh_rot_method two[2] = {SH_ROT_TAYLOR2, SH_ROT_ZXZXZ};
        sh_rot_error w2[2], w1;
        double h2[2], h1;
        o.tolerance = 1e-2;
        ck_assert_int_eq(sh_rot_choose_extents(&o, two, 2, w2, h2), SH_OK);
        for (int k = 0; k < 2; k++) {
            ck_assert_int_eq(sh_rot_choose_extent(&o, two[k], &w1, &h1), SH_OK);
            ck_assert(h1 == h2[k] && w1.max == w2[k].max && w1.lobe == w2[k].lobe && w1.coeff == w2[k].coeff);
        }
        o.tolerance = 1e-3;
    }
    /* taylor2 at order 6: the error grows with β (~β³), so it fails beyond
     * some β; the extent is where the grid continued first exceeds E */
    o.tolerance = 1e-2;
    ck_assert_int_eq(sh_rot_choose_extent(&o, SH_ROT_TAYLOR2, &w, &holds), SH_OK);
    if (w.max <= o.tolerance) {
        ck_assert(holds >= o.max_beta - 1e-12 && holds < M_PI);
        /* one step further fails: the error there exceeds E */
        sh_rot_choose_opts o2 = o;
        o2.max_beta = holds + o.beta_step;
        sh_rot_error w2;
        double h2;
        ck_assert_int_eq(sh_rot_choose_extent(&o2, SH_ROT_TAYLOR2, &w2, &h2), SH_OK);
        ck_assert(w2.max > o.tolerance && h2 < 0);
    } else {
        ck_assert(holds < 0);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("cost_model");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_model_rows);
    tcase_add_test(tc, test_model_interpolates);
    tcase_add_test(tc, test_choice_cheapest);
    tcase_add_test(tc, test_extent);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
