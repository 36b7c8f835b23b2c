/* test_bench.c — the speed library (lab/bench.c) and the generic error
 * and choice (rotation_choose.c).  No timing is asserted (speed belongs to
 * `shlab bench`): the tests check the counted work against the paper's
 * formula, the bookkeeping of the result, clean refusal of methods that are
 * not built in, the error measures against an independent dense computation,
 * and the order-for-image residuals against Parseval's closed form. */
#include "testutil.h"

#include "lab/lab.h"

#include <gsl/gsl_linalg.h>
#include <string.h>
#include <unistd.h>

static sh_bench_opts quick(void)
{
    sh_bench_opts o = SH_BENCH_OPTS_DEFAULT;
    o.count = 20;
    o.repeat = 3;
    o.batch = 4;
    o.kernel = SH_KERNEL_SCALAR; /* the loop kernels, whose counts the paper gives */
    return o;
}

/* zxzxz apply counts the n(2n²+18n−14)/3 of Krivánek Sec. 3.1; its set
 * counts the Chebyshev multiple angles 3·2(n−2) (once per rotation). */
START_TEST(test_counts_zxzxz)
{
    sh_bench_opts o = quick();
    for (int n = 3; n <= 9; n += 3) {
        sh_bench_result r;
        ck_assert_int_eq(sh_rot_bench(n, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &o, &r), SH_OK);
        const double paper = n * (2.0 * n * n + 18 * n - 14) / 3;
        ck_close((double)r.apply_mults, paper, 0, 1, "zxzxz apply mults n=%d", n);
        ck_assert_uint_eq(r.set_mults, 6u * (uint64_t)(n - 2));
        ck_close(r.mults, paper + 6.0 * (n - 2), 0, 1, "zxzxz mults n=%d", n);
        ck_assert(r.ns_min <= r.ns_median && r.ns_median <= r.ns_max && r.ns_min > 0);
        ck_close(r.mults_per_ns, r.mults / r.ns_median, TOL0, 0, "mults/ns n=%d", n);
        ck_assert_int_eq(r.count, 20);
    }
}
END_TEST

/* A matrix method: apply = n(4n²−1)/3 (the block non-zeros), batched mults
 * = set/batch + apply, for every exact method built in (the sparse z and
 * zh: the sums only). */
START_TEST(test_counts_blocks)
{
    sh_bench_opts o = quick();
    const int n = 5;
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (m == SH_ROT_ZXZXZ || m == SH_ROT_HALFPI || m == SH_ROT_REFERENCE || !sh_rot_method_is_exact((sh_rot_method)m) ||
            sh_rot_method_max_order((sh_rot_method)m) < n)
            continue;
        sh_bench_result a, b;
        ck_assert_int_eq(sh_rot_bench(n, (sh_rot_method)m, SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &o, &a), SH_OK);
        ck_assert_int_eq(sh_rot_bench(n, (sh_rot_method)m, SH_PREC_DOUBLE, SH_BENCH_BATCHED, &o, &b), SH_OK);
        /* z and zh apply sparsely (zh: its own count, test_rot_zh) */
        if (m != SH_ROT_Z && m != SH_ROT_ZH)
            ck_close((double)a.apply_mults, n * (4.0 * n * n - 1) / 3, 0, 1, "%s apply", sh_rot_method_name(m));
        ck_close(a.mults, (double)a.set_mults + a.apply_mults, TOL0, 1, "%s per-rotation", sh_rot_method_name(m));
        ck_close(b.mults, (double)b.set_mults / 4 + b.apply_mults, TOL0, 1, "%s batched", sh_rot_method_name(m));
        ck_assert(isfinite(a.checksum) && isfinite(b.checksum));
    }
}
END_TEST

/* Every method name parses; the ones not built in (e.g. the Taylor kernels
 * before their merge) are refused cleanly by the plan and by the bench. */
START_TEST(test_unregistered)
{
    sh_bench_opts o = quick();
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (sh_rot_method_max_order((sh_rot_method)m) > 0) continue;
        sh_rot_plan *p = (sh_rot_plan *)&o;
        ck_assert_int_ne(sh_rot_plan_create(4, (sh_rot_method)m, SH_PREC_DOUBLE, SH_CS, &p), SH_OK);
        ck_assert_ptr_null(p);
        sh_bench_result r;
        ck_assert_int_ne(sh_rot_bench(4, (sh_rot_method)m, SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &o, &r), SH_OK);
    }
    sh_bench_result r;
    o.repeat = 0;
    ck_assert_int_eq(sh_rot_bench(4, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &o, &r), SH_EINVAL);
}
END_TEST

/* The measures of sh_rot_errws against a dense computation: the n²×n²
 * difference matrix, its SVD (all singular values at once, not per band),
 * and the lobe vector from sh_light_closed_form. */
START_TEST(test_error_dense)
{
    const int n = 5, nn = n * n;
    sh_rotation rot;
    sh_rotation_from_euler(0.7, 0.4, -1.9, &rot);
    sh_rot_errws *w;
    ck_assert_int_eq(sh_rot_errws_create(n, 7, 1, &w), SH_OK);
    ck_assert_int_eq(sh_rot_errws_set(w, &rot), SH_OK);
    sh_rot_error e;
    ck_assert_int_eq(sh_rot_errws_eval(w, SH_ROT_ZXZXZ, SH_PREC_FLOAT, &e), SH_OK);

    double *bm = malloc(sh_rot_block_offset(n) * sizeof *bm), *be = malloc(sh_rot_block_offset(n) * sizeof *be);
    double *Dm = malloc((size_t)nn * nn * sizeof *Dm), *De = malloc((size_t)nn * nn * sizeof *De);
    sh_rot_plan *pm, *pe;
    ck_assert_int_eq(sh_rot_plan_create(n, SH_ROT_ZXZXZ, SH_PREC_FLOAT, SH_CS, &pm), SH_OK);
    ck_assert_int_eq(sh_rot_plan_create(n, SH_ROT_REFERENCE, SH_PREC_DOUBLE, SH_CS, &pe), SH_OK);
    sh_rot_plan_set(pm, &rot);
    sh_rot_plan_set(pe, &rot);
    sh_rot_plan_blocks(pm, bm);
    sh_rot_plan_blocks(pe, be);
    sh_rot_blocks_to_dense(n, bm, Dm);
    sh_rot_blocks_to_dense(n, be, De);
    for (int i = 0; i < nn * nn; i++) Dm[i] -= De[i];
    /* lobe: ‖D c‖ with c the normalised closed-form lobe coefficients */
    sh_light L = {0};
    L.kind = SH_LIGHT_LOBE;
    L.p[0] = 7;
    double c[25], cn = 0, lobe = 0;
    ck_assert_int_eq(sh_light_closed_form(&L, n, SH_CS, c), SH_OK);
    for (int i = 0; i < nn; i++) cn += c[i] * c[i];
    for (int r = 0; r < nn; r++) {
        double s = 0;
        for (int k = 0; k < nn; k++) s += Dm[r * nn + k] * c[k];
        lobe += s * s;
    }
    lobe = sqrt(lobe / cn);
    gsl_matrix_view A = gsl_matrix_view_array(Dm, nn, nn);
    gsl_matrix *V = gsl_matrix_alloc(nn, nn);
    gsl_vector *S = gsl_vector_alloc(nn);
    gsl_linalg_SV_decomp_jacobi(&A.matrix, V, S);
    double smax = 0, ssum = 0;
    for (int k = 0; k < nn; k++) {
        smax = fmax(smax, gsl_vector_get(S, k));
        ssum += gsl_vector_get(S, k);
    }
    ck_close(e.max, smax, 1e-6, 0, "max singular value");
    ck_close(e.mean, ssum / nn, 1e-6, 0, "mean singular value");
    ck_close(e.lobe, lobe, 1e-6, 0, "lobe error");
    /* float rounding, not zero and not large; ‖Dc‖ ≤ σ_max ‖c‖; mean ≤ max */
    ck_assert(e.max > 1e-9 && e.max < 1e-5);
    ck_assert(e.lobe <= e.max * (1 + 1e-12) && e.mean <= e.max);
    /* an exact double method sits at rounding error */
    ck_assert_int_eq(sh_rot_errws_eval(w, SH_ROT_BLANCO, SH_PREC_DOUBLE, &e), SH_OK);
    ck_assert(e.max < 1e-13 && e.lobe < 1e-13);
    gsl_matrix_free(V);
    gsl_vector_free(S);
    sh_rot_plan_free(pm);
    sh_rot_plan_free(pe);
    free(bm); free(be); free(Dm); free(De);
    sh_rot_errws_free(w);
}
END_TEST

/* choose: every exact method qualifies at 1e-12; ranking by time; nothing
 * qualifies at 1e-30; z is a candidate only at max β = 0. */
/* Costs injected instead of timings, so the ranking is deterministic: the
 * choice must be the cheapest method whose error meets the budget, whatever
 * this machine's speed.  Exact methods meet 1e-12 (MPFR truth); the Taylor
 * approximations, at β up to 0.2, do not (error O(β²) or more). */
static double fake_cost(void *ctx, sh_rot_method m, int order)
{
    (void)order;
    const double *c = ctx;
    return c[m];
}

typedef struct { int calls, last, total; } prog_count;
static void count_progress(void *ctx, int done, int total, const char *what)
{
    prog_count *p = ctx;
    ck_assert_int_eq(done, p->last + 1);
    ck_assert(what != NULL);
    p->calls++;
    p->last = done;
    p->total = total;
}

START_TEST(test_choose)
{
    double cost[SH_ROT_NMETHODS];
    for (int m = 0; m < SH_ROT_NMETHODS; m++) cost[m] = 1000 + 10 * m;
    cost[SH_ROT_TAYLOR15] = 1;  /* cheapest, but not accurate enough */
    cost[SH_ROT_WIGNER] = 50;   /* cheapest exact one */
    cost[SH_ROT_BLANCO] = 60;   /* runner-up */
    sh_rot_choose_opts o = {0};
    o.order = 4;
    o.max_beta = 0.2;
    o.tolerance = 1e-12;
    o.lobe_exp = 7;
    o.beta_step = 0.05;
    o.measure = SH_MEASURE_MAX;
    o.cost = fake_cost;
    o.cost_ctx = cost;
    prog_count pc = {0, 0, 0};
    o.progress = count_progress;
    o.progress_ctx = &pc;
    sh_rot_candidate c[SH_ROT_NMETHODS];
    int nc, ch, ru;
    ck_assert_int_eq(sh_rot_choose(&o, NULL, c, &nc, &ch, &ru, NULL), SH_OK);
    ck_assert_int_eq(ch, 0);
    ck_assert_int_eq(ru, 1);
    ck_assert_int_eq(c[ch].method, SH_ROT_WIGNER);
    ck_assert_int_eq(c[ru].method, SH_ROT_BLANCO);
    ck_assert_int_eq(pc.total, 5 + nc); /* β grid 0, 0.05, ..., 0.2, then each method */
    ck_assert_int_eq(pc.last, pc.total);
    int have_t15 = 0;
    for (int k = 0; k < nc; k++) {
        ck_assert(c[k].method != SH_ROT_Z && c[k].method != SH_ROT_REFERENCE);
        ck_assert(c[k].ns_per_rotation == cost[c[k].method]);
        if (c[k].exact) ck_assert_msg(c[k].ok, "%s error %g", sh_rot_method_name(c[k].method), c[k].max_error);
        if (c[k].method == SH_ROT_TAYLOR15) {
            have_t15 = 1;
            ck_assert(!c[k].ok && c[k].max_error > 1e-6);
        }
        if (k && c[k].ok) ck_assert(c[k - 1].ok && c[k - 1].ns_per_rotation <= c[k].ns_per_rotation);
        if (k && !c[k].ok && !c[k - 1].ok) ck_assert(c[k - 1].max_error <= c[k].max_error);
    }
    ck_assert(have_t15);
    /* a loose budget admits the approximation, which is then the cheapest */
    o.tolerance = 0.5;
    o.progress = NULL;
    ck_assert_int_eq(sh_rot_choose(&o, NULL, c, &nc, &ch, &ru, NULL), SH_OK);
    ck_assert_int_eq(c[ch].method, SH_ROT_TAYLOR15);
    /* nothing meets 1e-30 */
    o.tolerance = 1e-30;
    ck_assert_int_eq(sh_rot_choose(&o, NULL, c, &nc, &ch, &ru, NULL), SH_OK);
    ck_assert_int_eq(ch, -1);
    ck_assert_int_eq(ru, -1);
    /* β = 0: the z method joins */
    o.max_beta = 0;
    o.tolerance = 1e-12;
    ck_assert_int_eq(sh_rot_choose(&o, NULL, c, &nc, &ch, &ru, NULL), SH_OK);
    int have_z = 0;
    for (int k = 0; k < nc; k++) have_z |= c[k].method == SH_ROT_Z;
    ck_assert(have_z);
}
END_TEST

/* f = y_0^0 + a·y_2^1 (R, B) and y_0^0 + b·y_3^{-2} (G): ‖f‖² and the
 * residuals after each order are known in closed form (orthonormality):
 *   order 1, 2: √((2a²+b²)/F), order 3: |b|/√F, order ≥ 4: 0; F = 3+2a²+b². */
typedef struct { double a, b; } two;
static double fn_y(const double d[3], double th, double ph, void *ctx)
{
    const two *t = ctx;
    double y[16];
    sh_eval(4, SH_CS, th, ph, y);
    (void)d;
    return y[0] + t->a * y[sh_index(2, 1)];
}
static double fn_g(const double d[3], double th, double ph, void *ctx)
{
    const two *t = ctx;
    double y[16];
    sh_eval(4, SH_CS, th, ph, y);
    (void)d;
    return y[0] + t->b * y[sh_index(3, -2)];
}

START_TEST(test_order_for_image)
{
    two t = {0.3, 0.1};
    sh_image a = {0}, b = {0};
    ck_assert_int_eq(sh_image_from_fn(SH_LAYOUT_LATLONG, 256, 128, fn_y, &t, &a), SH_OK);
    ck_assert_int_eq(sh_image_from_fn(SH_LAYOUT_LATLONG, 256, 128, fn_g, &t, &b), SH_OK);
    /* an RGB image R = B = f_a, G = f_b, written and read back as EXR */
    const size_t np = 256 * 128;
    sh_image img = {256, 128, 3, {"R", "G", "B"}, malloc(3 * np * sizeof(float))};
    memcpy(img.data, a.data, np * sizeof(float));
    memcpy(img.data + np, b.data, np * sizeof(float));
    memcpy(img.data + 2 * np, a.data, np * sizeof(float));
    char path[] = "/tmp/shlab_test_bench_XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
    ck_assert_int_eq(sh_exr_write(path, &img), SH_OK);
    sh_image in = {0};
    ck_assert_int_eq(sh_exr_read(path, &in, NULL), SH_OK);
    unlink(path);
    double r[8];
    int order;
    ck_assert_int_eq(sh_order_for_image(&in, SH_LAYOUT_LATLONG, 0.05, 8, &order, r), SH_OK);
    /* the three channels together: ‖f‖² = 3 + 2a² + b² */
    const double f2 = 3 + 2 * t.a * t.a + t.b * t.b;
    const double e12 = sqrt((2 * t.a * t.a + t.b * t.b) / f2), e3 = fabs(t.b) / sqrt(f2);
    ck_close(r[0], e12, 2e-3, 0, "residual order 1");
    ck_close(r[1], e12, 2e-3, 0, "residual order 2");
    ck_close(r[2], e3, 2e-3, 0, "residual order 3");
    ck_assert(r[3] < 2e-3 && r[7] <= r[3]);
    ck_assert_int_eq(order, 4); /* e3 = 0.055 > 0.05 */
    ck_assert_int_eq(sh_order_for_image(&in, SH_LAYOUT_LATLONG, 0.1, 8, &order, NULL), SH_OK);
    ck_assert_int_eq(order, 3);
    ck_assert_int_eq(sh_order_for_image(&in, SH_LAYOUT_LATLONG, 0.3, 8, &order, NULL), SH_OK);
    ck_assert_int_eq(order, 1);
    ck_assert_int_eq(sh_order_for_image(&in, SH_LAYOUT_LATLONG, 1e-9, 3, &order, NULL), SH_OK);
    ck_assert_int_eq(order, -1);
    sh_image_free(&a);
    sh_image_free(&b);
    sh_image_free(&img);
    sh_image_free(&in);
}
END_TEST


/* ---- the interleaved engine, with entries that only record their calls
 * (no timing asserted: the order of the calls, the counts, the layout of
 * the samples, errors, and the statistics as functions of the samples). */
enum { LOG_MAX = 4096 };
typedef struct { int id; int *log; int *nlog; long *counts; int fail_at; } rec_ctx;
static int rec_run(void *v, long count)
{
    rec_ctx *c = v;
    if (*c->nlog == c->fail_at) return sh_error(SH_ENUM, "recorded failure");
    if (*c->nlog < LOG_MAX) {
        c->counts[*c->nlog] = count;
        c->log[(*c->nlog)++] = c->id;
    }
    volatile double x = 0;
    for (long i = 0; i < count; i++) x += 1.0;
    return SH_OK;
}

START_TEST(test_engine_round_robin)
{
    int log[LOG_MAX], nlog = 0;
    long counts[LOG_MAX];
    enum { NE = 3, S = 5 };
    rec_ctx c[NE];
    sh_bench_entry e[NE];
    for (int i = 0; i < NE; i++) {
        c[i] = (rec_ctx){i, log, &nlog, counts, -1};
        e[i] = (sh_bench_entry){"rec", rec_run, NULL, &c[i], i + 1.0, 0};
    }
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.samples = S;
    cfg.warmup = 2;
    cfg.count = 1000;
    double smp[NE * S];
    sh_bench_stats st[NE];
    sh_bench_noise nz;
    ck_assert_int_eq(sh_bench_interleaved(e, NE, &cfg, smp, st, &nz), SH_OK);
    /* fixed count: no calibration; 2 warm-up rounds in entry order, then
     * S rounds, round r starting at entry r mod NE */
    ck_assert_int_eq(nlog, (2 + S) * NE);
    for (int k = 0; k < nlog; k++) ck_assert_int_eq(counts[k], 1000);
    for (int w = 0; w < 2; w++)
        for (int i = 0; i < NE; i++) ck_assert_int_eq(log[w * NE + i], i);
    for (int r = 0; r < S; r++)
        for (int k = 0; k < NE; k++) ck_assert_int_eq(log[(2 + r) * NE + k], (k + r) % NE);
    /* statistics are order statistics of the returned samples (ns per unit) */
    for (int i = 0; i < NE; i++) {
        double x[S];
        memcpy(x, smp + i * S, sizeof x);
        for (int a = 0; a < S; a++)
            for (int b = a + 1; b < S; b++)
                if (x[b] < x[a]) { const double t = x[a]; x[a] = x[b]; x[b] = t; }
        ck_assert(x[0] > 0);
        ck_assert(st[i].ns_min == x[0] && st[i].ns_max == x[S - 1] && st[i].ns_median == x[2]);
        ck_assert(st[i].ns_q1 == x[1] && st[i].ns_q3 == x[3]); /* type 7 at n = 5: exact order statistics */
        ck_close(st[i].spread, (x[3] - x[1]) / x[2], TOL1, 0, "spread");
        ck_assert_int_eq(st[i].count, 1000);
        ck_assert(st[i].sample_ms > 0 && st[i].offcpu >= 0 && st[i].offcpu <= 1);
    }
    ck_assert(nz.seconds > 0 && nz.offcpu >= 0 && nz.offcpu <= 1 && nz.spread >= 0);
    ck_assert(nz.noisy == (nz.why[0] != '\0'));
    /* a failing entry stops the run with its status and message */
    nlog = 0;
    c[1].fail_at = 4;
    ck_assert_int_eq(sh_bench_interleaved(e, NE, &cfg, smp, st, NULL), SH_ENUM);
    ck_assert_str_eq(sh_last_error(), "recorded failure");
    ck_assert_int_ne(sh_bench_interleaved(e, 0, &cfg, smp, st, NULL), SH_OK);
    /* calibrated (count 0): every entry gets one count >= 1, used by all its samples */
    nlog = 0;
    c[1].fail_at = -1;
    cfg.count = 0;
    cfg.min_sample_ms = 0.2;
    cfg.warmup = 1;
    ck_assert_int_eq(sh_bench_interleaved(e, NE, &cfg, smp, st, NULL), SH_OK);
    for (int i = 0; i < NE; i++) ck_assert(st[i].count >= 1);
    for (int k = nlog - S * NE; k < nlog; k++) ck_assert_int_eq(counts[k], st[log[k]].count);
}
END_TEST

/* Paired ratios: the median and quartiles of a[r]/b[r], computed by hand. */
START_TEST(test_paired_ratio)
{
    const double b[6] = {10, 20, 10, 40, 10, 10};
    const double a[6] = {20, 60, 40, 80, 25, 10}; /* ratios 2 3 4 2 2.5 1 */
    sh_bench_ratio r;
    ck_assert_int_eq(sh_bench_paired_ratio(a, b, 6, 0.05, &r), SH_OK);
    /* sorted 1 2 2 2.5 3 4: median (2+2.5)/2, q1 at 1.25 → 2, q3 at 3.75 → 2.5 + 0.75·0.5 */
    ck_close(r.median, 2.25, TOL0, 0, "median");
    ck_close(r.q1, 2.0, TOL0, 0, "q1");
    ck_close(r.q3, 2.875, TOL0, 0, "q3");
    ck_close(r.spread, 0.875 / 2.25, TOL1, 0, "spread");
    ck_assert(r.noisy);
    /* a constant ratio is quiet whatever the drift of the times themselves */
    const double drift_b[4] = {10, 13, 17, 30}, drift_a[4] = {30, 39, 51, 90};
    ck_assert_int_eq(sh_bench_paired_ratio(drift_a, drift_b, 4, 0.05, &r), SH_OK);
    ck_close(r.median, 3, TOL1, 0, "paired ratio under drift");
    ck_assert(!r.noisy && r.spread < 1e-12);
    const double bad[1] = {0};
    ck_assert_int_eq(sh_bench_paired_ratio(bad, b, 1, 0.05, &r), SH_EINVAL);
}
END_TEST

/* The rotation entries: units, counted work and the old API agree. */
START_TEST(test_rot_entries)
{
    sh_bench_opts o = quick();
    sh_bench_entry e;
    ck_assert_int_eq(sh_rot_bench_entry(6, SH_ROT_ZXZXZ, SH_PREC_FLOAT, SH_BENCH_BATCHED, &o, &e), SH_OK);
    ck_assert(e.units == 4 && e.run && e.free && e.name);
    const double paper = 6 * (2.0 * 36 + 18 * 6 - 14) / 3;
    ck_close(e.mults, paper + 6.0 * 4 / 4, 0, 1, "zxzxz batched mults per vector");
    ck_assert_int_eq(e.run(e.ctx, 3), SH_OK);
    sh_bench_entry_free(&e);
    ck_assert_ptr_null(e.ctx);
    ck_assert_int_eq(sh_rot_bench_setup_entry(&o, &e), SH_OK);
    ck_assert(e.units == 1 && e.mults == 0);
    ck_assert_int_eq(e.run(e.ctx, 100), SH_OK);
    sh_bench_entry_free(&e);
    /* instruction counting needs valgrind: refused cleanly outside it */
    ck_assert_int_eq(sh_rot_bench_entry(3, SH_ROT_IVANIC, SH_PREC_DOUBLE, SH_BENCH_PER_ROTATION, &o, &e), SH_OK);
    double ins;
    ck_assert_int_eq(sh_bench_instructions(&e, 1, 8, "/nonexistent", &ins), SH_ENOTSUP);
    sh_bench_entry_free(&e);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("bench");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_counts_zxzxz);
    tcase_add_test(tc, test_counts_blocks);
    tcase_add_test(tc, test_unregistered);
    tcase_add_test(tc, test_error_dense);
    tcase_add_test(tc, test_choose);
    tcase_add_test(tc, test_order_for_image);
    tcase_add_test(tc, test_engine_round_robin);
    tcase_add_test(tc, test_paired_ratio);
    tcase_add_test(tc, test_rot_entries);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
