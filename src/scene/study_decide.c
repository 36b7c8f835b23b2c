/* study_decide.c — the decisions of the shading study and the rule that
 * trusts them (scene.h, "trustworthy decisions"): the order for a budget,
 * the largest β within a budget, and the refinement of the reference that
 * an untrusted decision asks for.
 *
 * The rule: a comparison "e ≤ E" is trusted when ref_l2 ≤ min(E, e)/10.
 * Why: the reference's own error r adds to a measured error in quadrature
 * (e_measured² ≈ e² + r²), so with r ≤ E/10 no comparison near the budget
 * flips by the reference's noise (it moves e by ≤ E/200 there), and with
 * r ≤ e/10 the error printed at the decision is the SH error, not the
 * reference's noise.  A decision is trusted when all the comparisons it
 * rests on are. */
#include "scene_internal.h"

#include <limits.h>
#include <stdlib.h>

double sh_study_ref_needed(double budget, double err) { return fmin(budget, err) / SH_STUDY_MARGIN; }

int sh_study_replications_for(double ref_l2, int replications, double needed)
{
    if (ref_l2 <= needed) return replications;
    if (!(needed > 0)) return INT_MAX;
    /* the standard error of a mean of R independent replications ∝ 1/√R */
    const double q = ref_l2 / needed, r = ceil(replications * q * q);
    return r < (double)INT_MAX ? (int)r : INT_MAX;
}

int sh_decide_order(int max_order, const double *err, double ref_l2, double budget, sh_order_decision *d)
{
    if (max_order < 1 || !err || !d || !(budget > 0) || !(ref_l2 >= 0))
        return sh_error(SH_EINVAL, "sh_decide_order: bad arguments");
    int n = 0;
    for (int k = 1; k <= max_order && !n; k++)
        if (err[k - 1] <= budget) n = k;
    /* it rests on the comparisons at orders 1..n (all of them when none
     * passes): the failing ones ask ref_l2 ≤ E/10, the passing one
     * ref_l2 ≤ err(n)/10 */
    const int last = n ? n : max_order;
    double needed = INFINITY;
    for (int k = 1; k <= last; k++) needed = fmin(needed, sh_study_ref_needed(budget, err[k - 1]));
    d->undecided = !(ref_l2 <= needed);
    d->order = d->undecided ? 0 : n;
    d->rel_l2 = d->undecided ? 0 : err[last - 1];
    d->ref_l2 = ref_l2;
    d->ref_needed = needed;
    return SH_OK;
}

int sh_decide_beta(int nbeta, const double *err, const double *ref_l2, double budget, sh_beta_decision *d)
{
    if (nbeta < 1 || !err || !ref_l2 || !d || !(budget > 0)) return sh_error(SH_EINVAL, "sh_decide_beta: bad arguments");
    /* the walk: passes from β_0 on, up to the first failure (end) */
    int last = -1, end = nbeta - 1;
    for (int j = 0; j < nbeta; j++) {
        if (!(err[j] <= budget)) {
            end = j;
            break;
        }
        last = j;
    }
    d->undecided = 0;
    d->at = 0;
    double worst = -1;
    for (int j = 0; j <= end; j++) {
        const double need = sh_study_ref_needed(budget, err[j]);
        const int ok = ref_l2[j] <= need;
        const double ratio = ref_l2[j] > 0 ? ref_l2[j] / need : 0;
        if (ok && ratio <= worst) continue;
        worst = ratio;
        d->at = j;
        d->ref_l2 = ref_l2[j];
        d->ref_needed = need;
        if (!ok) {
            d->undecided = 1;
            break;
        }
    }
    /* undecided: the comparisons before `at` are trusted passes, a lower bound */
    d->last = d->undecided ? d->at - 1 : last;
    return SH_OK;
}

/* The replications to refine to: for each comparison k whose reference
 * breaks the rule (ref_l2 > needed[k]), the count the 1/√R law asks for,
 * times 1.25 (a margin for the estimated ref_l2), at least 2 more; the
 * largest of those within the cap.  0: none fits (or none is needed). */
static int refine_target(const sh_study_info *in, int n, const double *needed)
{
    const int have = in->replications, cap = in->max_replications;
    int best = 0;
    for (int k = 0; k < n; k++) {
        if (in->ref_l2 <= needed[k]) continue;
        const int want = sh_study_replications_for(in->ref_l2, have, needed[k]);
        if (want > cap) continue;
        int target = (int)fmin((double)cap, ceil(1.25 * want));
        if (target < have + 2) target = have + 2;
        if (target <= cap && target > best) best = target;
    }
    return best;
}

/* measure(st, ctx, needed): the n comparisons at the study's reference, and
 * what the rule asks of it for each (needed[k]) */
typedef int (*measure_fn)(sh_study *st, void *ctx, double *needed);

/* Measure, refine the reference for the untrusted, measure again: at most
 * SH_STUDY_ROUNDS refinements, and none that the cap cannot afford. */
static int settle(sh_study *st, int n, measure_fn measure, void *ctx)
{
    double *needed = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (!needed) return sh_error(SH_ENOMEM, "out of memory");
    int e = SH_OK;
    for (int round = 0; !e; round++) {
        if ((e = measure(st, ctx, needed)) || round == SH_STUDY_ROUNDS) break;
        sh_study_info in;
        if ((e = sh_study_info_get(st, &in))) break;
        const int target = refine_target(&in, n, needed);
        if (!target) break;
        e = sh_study_refine(st, target);
    }
    free(needed);
    return e;
}

typedef struct {
    sh_rot_method method;
    int max_order, nb;
    const double *budgets;
    sh_order_decision *d;
    sh_shade_err *err;
} orders_ctx;

static int measure_orders(sh_study *st, void *vc, double *needed)
{
    orders_ctx *c = vc;
    double e[64];
    sh_study_info in;
    int st_ = sh_study_info_get(st, &in);
    for (int n = 1; !st_ && n <= c->max_order; n++) {
        sh_shade_err er;
        st_ = sh_study_error(st, c->method, n, &er);
        e[n - 1] = er.rel_l2;
        if (c->err) c->err[n - 1] = er;
    }
    for (int k = 0; !st_ && k < c->nb; k++) {
        st_ = sh_decide_order(c->max_order, e, in.ref_l2, c->budgets[k], &c->d[k]);
        needed[k] = c->d[k].ref_needed;
    }
    return st_;
}

int sh_study_decide_orders(sh_study *st, sh_rot_method method, int max_order, int nb, const double *budgets,
                           sh_order_decision *d, sh_shade_err *err)
{
    if (!st || nb < 0 || (nb && (!budgets || !d)) || max_order < 1 || max_order > 64)
        return sh_error(SH_EINVAL, "sh_study_decide_orders: bad arguments");
    orders_ctx c = {method, max_order, nb, budgets, d, err};
    return settle(st, nb, measure_orders, &c);
}

typedef struct {
    const sh_rot_method *method;
    const int *order;
    const double *budget;
    double *err;
    int n;
} compare_ctx;

static int measure_compare(sh_study *st, void *vc, double *needed)
{
    compare_ctx *c = vc;
    for (int k = 0; k < c->n; k++) {
        sh_shade_err er;
        const int e = sh_study_error(st, c->method[k], c->order[k], &er);
        if (e) return e;
        c->err[k] = er.rel_l2;
        needed[k] = sh_study_ref_needed(c->budget[k], er.rel_l2);
    }
    return SH_OK;
}

int sh_study_compare(sh_study *st, int n, const sh_rot_method *method, const int *order, const double *budget,
                     double *err)
{
    if (!st || n < 0 || (n && (!method || !order || !budget || !err)))
        return sh_error(SH_EINVAL, "sh_study_compare: bad arguments");
    for (int k = 0; k < n; k++)
        if (!(budget[k] > 0)) return sh_error(SH_EINVAL, "sh_study_compare: budget %g is not positive", budget[k]);
    compare_ctx c = {method, order, budget, err, n};
    return settle(st, n, measure_compare, &c);
}
