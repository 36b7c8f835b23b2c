/* test_study.c — the shading study's trusted decisions (scene.h,
 * "trustworthy decisions"; docs/CONVENTIONS.md "Trusted decisions"): the rule
 * on numbers built by hand, the refinement of the reference (pooling equals
 * drawing the replications at once; ref_l2 falls as 1/√replications), and the
 * decisions of a study: a reference too coarse for a tight budget is
 * undecided, a budget far above it is decided, and refinement decides only
 * where the rule then holds. */
#include "testutil.h"

#include <limits.h>

/* ------------------------------------------------------------ the rule */

START_TEST(test_decide_order_rule)
{
    /* errors at orders 1..4; budget 5 %: order 3 (4 %), so the reference must
     * be ≤ min(5 %, 4 %)/10 = 0.4 % */
    const double err[4] = {0.5, 0.08, 0.04, 0.01};
    sh_order_decision d;
    ck_assert_int_eq(sh_decide_order(4, err, 0.004, 0.05, &d), SH_OK);
    ck_assert(!d.undecided);
    ck_assert_int_eq(d.order, 3);
    ck_close(d.rel_l2, 0.04, TOL0, 1, "rel_l2 at the order");
    ck_close(d.ref_needed, 0.004, TOL1, 1, "needed");
    ck_assert_int_eq(sh_decide_order(4, err, 0.0041, 0.05, &d), SH_OK);
    ck_assert(d.undecided);
    ck_assert_int_eq(d.order, 0);
    /* budget 0.5 %: no order reaches it; every comparison fails, so the
     * reference must be ≤ 0.05 % */
    ck_assert_int_eq(sh_decide_order(4, err, 0.0004, 0.005, &d), SH_OK);
    ck_assert(!d.undecided);
    ck_assert_int_eq(d.order, 0);
    ck_close(d.rel_l2, 0.01, TOL0, 1, "rel_l2 at the largest order");
    ck_assert_int_eq(sh_decide_order(4, err, 0.0006, 0.005, &d), SH_OK);
    ck_assert(d.undecided);
    /* not monotone: order 2 (3 %) decides; the reference must be ≤ 0.3 % */
    const double bumpy[4] = {0.5, 0.03, 0.06, 0.001};
    ck_assert_int_eq(sh_decide_order(4, bumpy, 0.003, 0.05, &d), SH_OK);
    ck_assert(!d.undecided);
    ck_assert_int_eq(d.order, 2);
    ck_close(d.ref_needed, 0.003, TOL1, 1, "needed");
    ck_assert_int_eq(sh_decide_order(4, err, 0.001, 0, &d), SH_EINVAL);
}
END_TEST

START_TEST(test_decide_beta_rule)
{
    /* a walk within 5 % up to β_2 (4 %), failing at β_3 (6 %) */
    const double err[4] = {0.01, 0.02, 0.04, 0.06};
    double ref[4] = {0.0005, 0.0005, 0.0005, 0.0005};
    sh_beta_decision d;
    ck_assert_int_eq(sh_decide_beta(4, err, ref, 0.05, &d), SH_OK);
    ck_assert(!d.undecided);
    ck_assert_int_eq(d.last, 2);
    /* the tightest comparison: β_0, where 0.05 % meets min(5 %, 1 %)/10 = 0.1 % at half */
    ck_assert_int_eq(d.at, 0);
    ck_close(d.ref_needed, 0.001, TOL1, 1, "needed at β_0");
    /* β_0's reference above 0.1 %: undecided there, nothing known */
    ref[0] = 0.002;
    ck_assert_int_eq(sh_decide_beta(4, err, ref, 0.05, &d), SH_OK);
    ck_assert(d.undecided);
    ck_assert_int_eq(d.at, 0);
    ck_assert_int_eq(d.last, -1);
    /* the failing comparison's reference above 0.5 %: undecided at β_3, the
     * passes before it trusted */
    ref[0] = 0.0005;
    ref[3] = 0.01;
    ck_assert_int_eq(sh_decide_beta(4, err, ref, 0.05, &d), SH_OK);
    ck_assert(d.undecided);
    ck_assert_int_eq(d.at, 3);
    ck_assert_int_eq(d.last, 2);
    ck_close(d.ref_needed, 0.005, TOL1, 1, "needed at β_3");
    /* comparisons after the first failure decide nothing */
    const double err2[3] = {0.01, 0.06, 0.01};
    const double ref2[3] = {0.0005, 0.0005, 1};
    ck_assert_int_eq(sh_decide_beta(3, err2, ref2, 0.05, &d), SH_OK);
    ck_assert(!d.undecided);
    ck_assert_int_eq(d.last, 0);
}
END_TEST

START_TEST(test_replications_for)
{
    /* ref_l2 ∝ 1/√R: halving it takes 4× the replications */
    ck_assert_int_eq(sh_study_replications_for(0.02, 4, 0.01), 16);
    ck_assert_int_eq(sh_study_replications_for(0.02, 4, 0.03), 4);
    ck_assert_int_eq(sh_study_replications_for(0.03, 4, 0.01), 36);
    ck_assert_int_eq(sh_study_replications_for(1, 4, 1e-10), INT_MAX);
}
END_TEST

/* ------------------------------------------------------------ a study */

typedef struct {
    sh_proc_scene ps;
    sh_mesh m;
    sh_scene *s;
    sh_env *env;
} world;

/* box-open under Green's light: little sky is seen, visibility carries the
 * reference's variance */
static void world_make(world *w)
{
    ck_assert_int_eq(sh_proc_parse("box-open", &w->ps), SH_OK);
    w->ps.res = 4;
    ck_assert_int_eq(sh_mesh_procedural(&w->ps, &w->m), SH_OK);
    ck_assert_int_eq(sh_scene_create(&w->m, 0, &w->s), SH_OK);
    sh_light L;
    ck_assert_int_eq(sh_light_parse("green", 0, &L), SH_OK);
    ck_assert_int_eq(sh_env_from_light(&L, &w->env), SH_OK);
}

static void world_free(world *w)
{
    sh_env_free(w->env);
    sh_scene_free(w->s);
    sh_mesh_free(&w->m);
}

static sh_study *study_make(const world *w, int replications, int refine)
{
    sh_study_opts o = {0};
    o.max_order = 4;
    o.rays = 256;
    o.nverts = 60;
    o.seed = 3;
    o.ref.samples = 256;
    o.ref.replications = replications;
    o.refine = refine;
    sh_study *st;
    ck_assert_int_eq(sh_study_create(w->s, w->env, &o, &st), SH_OK);
    return st;
}

START_TEST(test_refine_pools)
{
    /* 4 replications refined to 64 is the reference of 64 replications
     * drawn at once, and its error is √(4/64) = 1/4 of the first */
    world w;
    world_make(&w);
    sh_study *a = study_make(&w, 4, 16), *b = study_make(&w, 64, 1);
    sh_study_info ia, ib;
    ck_assert_int_eq(sh_study_info_get(a, &ia), SH_OK);
    ck_assert_int_eq(ia.replications, 4);
    ck_assert_int_eq(ia.max_replications, 64);
    const double r4 = ia.ref_l2;
    ck_assert(r4 > 0);
    ck_assert_int_eq(sh_study_refine(a, 65), SH_EINVAL); /* beyond the cap */
    ck_assert_int_eq(sh_study_refine(a, 64), SH_OK);
    ck_assert_int_eq(sh_study_info_get(a, &ia), SH_OK);
    ck_assert_int_eq(sh_study_info_get(b, &ib), SH_OK);
    ck_assert_int_eq(ia.replications, 64);
    ck_close(ia.ref_l2, ib.ref_l2, 1e-10, 1e-300, "pooled against drawn at once");
    ck_assert_int_eq(ia.reference.rays_per_vertex, ib.reference.rays_per_vertex);
    for (int n = 1; n <= 4; n++) {
        sh_shade_err ea, eb;
        ck_assert_int_eq(sh_study_error(a, SH_ROT_IVANIC, n, &ea), SH_OK);
        ck_assert_int_eq(sh_study_error(b, SH_ROT_IVANIC, n, &eb), SH_OK);
        ck_close(ea.rel_l2, eb.rel_l2, 1e-10, 1e-300, "order %d", n);
    }
    /* 1/√R: the estimate's own spread at 4 replications (3 degrees of
     * freedom per vertex, 60 vertices) is about 10 %, hence ±30 % */
    const double ratio = r4 / ia.ref_l2;
    ck_assert_msg(ratio > 4 / 1.3 && ratio < 4 * 1.3, "ref_l2 fell by %.3g from 4 to 64 replications, not about 4", ratio);
    /* a new rotation starts again from the replications asked for */
    ck_assert_int_eq(sh_study_set_rotation(a, NULL), SH_OK);
    ck_assert_int_eq(sh_study_info_get(a, &ia), SH_OK);
    ck_assert_int_eq(ia.replications, 4);
    ck_close(ia.ref_l2, r4, TOL0, 1e-300, "the first reference again");
    sh_study_free(a);
    sh_study_free(b);
    world_free(&w);
}
END_TEST

/* the rule on the numbers of a study, recomputed here: the decision for
 * budget E from errors err[0..N) and the reference's error r */
static void check_rule(const double *err, int N, double r, double E, const sh_order_decision *d)
{
    int n = 0;
    for (int k = 0; k < N && !n; k++)
        if (err[k] <= E) n = k + 1;
    double need = E / 10;
    for (int k = 0; k < (n ? n : N); k++) need = fmin(need, err[k] / 10);
    ck_assert_msg(d->undecided == !(r <= need), "budget %g: undecided %d with ref_l2 %g against %g", E, d->undecided, r, need);
    if (!d->undecided) ck_assert_int_eq(d->order, n);
}

START_TEST(test_decide_orders)
{
    world w;
    world_make(&w);
    /* no refinement: a budget 5× the reference's error cannot be judged (the
     * rule asks 10×); one of 0.9 can */
    sh_study *st = study_make(&w, 4, 1);
    sh_study_info in;
    ck_assert_int_eq(sh_study_info_get(st, &in), SH_OK);
    const double r0 = in.ref_l2, budgets[2] = {5 * r0, 0.9};
    sh_order_decision d[2];
    sh_shade_err e[4];
    ck_assert_int_eq(sh_study_decide_orders(st, SH_ROT_IVANIC, 4, 2, budgets, d, e), SH_OK);
    double err[4];
    for (int k = 0; k < 4; k++) err[k] = e[k].rel_l2;
    ck_assert(d[0].undecided);
    ck_assert(!d[1].undecided);
    ck_assert_int_gt(d[1].order, 0);
    for (int b = 0; b < 2; b++) check_rule(err, 4, r0, budgets[b], &d[b]);
    ck_assert_int_eq(sh_study_info_get(st, &in), SH_OK);
    ck_assert_int_eq(in.replications, 4);
    sh_study_free(st);
    /* with refinement (up to 16×): the tight budget asks for ≥ 4× the
     * replications; whatever is decided obeys the rule on the final numbers */
    st = study_make(&w, 4, 16);
    ck_assert_int_eq(sh_study_decide_orders(st, SH_ROT_IVANIC, 4, 2, budgets, d, e), SH_OK);
    ck_assert_int_eq(sh_study_info_get(st, &in), SH_OK);
    ck_assert_int_ge(in.replications, 16);
    ck_assert_int_le(in.replications, 64);
    ck_assert(in.ref_l2 < r0);
    for (int k = 0; k < 4; k++) err[k] = e[k].rel_l2;
    for (int b = 0; b < 2; b++) check_rule(err, 4, in.ref_l2, budgets[b], &d[b]);
    sh_study_free(st);
    world_free(&w);
}
END_TEST

START_TEST(test_compare)
{
    /* a comparison judged at this rotation: refined until the rule holds */
    world w;
    world_make(&w);
    sh_study *st = study_make(&w, 4, 16);
    sh_study_info in;
    ck_assert_int_eq(sh_study_info_get(st, &in), SH_OK);
    const double r0 = in.ref_l2;
    const sh_rot_method m = SH_ROT_TAYLOR1;
    const int order = 4;
    const double budget = 0.9;
    double e;
    ck_assert_int_eq(sh_study_compare(st, 1, &m, &order, &budget, &e), SH_OK);
    ck_assert_int_eq(sh_study_info_get(st, &in), SH_OK);
    if (in.replications > 4) ck_assert(in.ref_l2 < r0);
    ck_assert_msg(in.ref_l2 <= fmin(budget, e) / 10 || sh_study_replications_for(in.ref_l2, in.replications, fmin(budget, e) / 10) > 64,
                  "ref_l2 %g, error %g: neither trusted nor out of the cap's reach", in.ref_l2, e);
    sh_study_free(st);
    world_free(&w);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("study");
    TCase *t = tcase_create("study");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, test_decide_order_rule);
    tcase_add_test(t, test_decide_beta_rule);
    tcase_add_test(t, test_replications_for);
    tcase_add_test(t, test_refine_pools);
    tcase_add_test(t, test_decide_orders);
    tcase_add_test(t, test_compare);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
