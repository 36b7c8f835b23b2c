/* cmd_scene_plan.c — `shlab scene-plan`: the smallest SH order whose
 * shading of a scene under an environment stays within an error budget,
 * measured against a reference by direct integration; and how far each
 * Taylor rotation may turn the lighting within the budget.  Logic in
 * src/scene/study.c. */
#include "cli_scene.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_scene_plan;

#define PLAN_MAX_BUDGETS 8
#define PLAN_MAX_BETAS 400

typedef struct {
    double v[PLAN_MAX_BUDGETS];
    int n;
} budget_list;

typedef struct {
    cli_scene_input in;
    cli_reference_args ref;
    budget_list budget;
    int max_order, vertices, degrees, fmt, refine;
    double max_beta, beta_step; /* in the unit of --degrees; beta_step 0: 5° */
} plan_args;

static int parse_budget(const char *opt, const char *s, void *field)
{
    budget_list *b = field;
    double *v = NULL;
    int n = 0;
    if (cli_doubles(opt, s, &v, &n)) return CLI_EXIT_USAGE;
    int rc = 0;
    if (n < 1 || n > PLAN_MAX_BUDGETS) rc = cli_fail("%s: give 1..%d values", opt, PLAN_MAX_BUDGETS);
    for (int k = 0; k < n && !rc; k++)
        if (!(v[k] > 0 && v[k] < 1)) rc = cli_fail("%s: each value must be in (0, 1)", opt);
    if (!rc) {
        memcpy(b->v, v, sizeof(double) * (size_t)n);
        b->n = n;
    }
    free(v);
    return rc;
}

static const cli_opt plan_opts[] = {
    CLI_CUSTOM(plan_args, budget, "budget", "LIST", parse_budget, NULL,
               "relative L2 shading error budgets (each in (0, 1); required)"),
    {.type = CLI_T_ORDER, .name = "max-order", .meta = "M", .off = offsetof(plan_args, max_order), .lo = 1,
     .hi = CLI_SCENE_MAX_ORDER, .def = "12", .help = "largest order tried"},
    CLI_INT(plan_args, vertices, "vertices", "K", 0, INT_MAX, "500",
            "vertices studied, a seeded random subset (0 = all)"),
    CLI_REAL(plan_args, max_beta, "max-beta", "B", 0, 0, 0, "0", "rotation study up to β = B (0: none)"),
    CLI_REAL(plan_args, beta_step, "beta-step", "H", 0, INFINITY, CLI_LO_OPEN, NULL, "its grid step (default 5°)"),
    CLI_DEGREES(plan_args, degrees, "--max-beta, --beta-step (and --light angles) in degrees"),
    CLI_FORMAT(plan_args, fmt),
    CLI_GROUP(plan_args, in.scene, cli_scene_opts),
    CLI_GROUP(plan_args, in.env, cli_env_opts),
    CLI_GROUP(plan_args, in.rays, cli_rays_opts),
    CLI_DEFAULT("albedo", "1"),
    CLI_GROUP(plan_args, ref, cli_reference_opts),
    CLI_INT(plan_args, refine, "refine", "F", 1, 500, "16",
            "refine the reference up to F × --replications where the rule fails (1: never)"),
    CLI_END,
};

static const cli_cmd plan_decl = {
    .name = "scene-plan",
    .usage = "scene-plan (--mesh FILE | --scene SPEC) (--probe FILE | --light SPEC)\n"
             "                        --budget E[,E2,...] [OPTIONS]",
    .about = "Measure the shading error of SH lighting on a scene and choose the order.\n"
             "At a seeded subset of the vertices: shadowed transfer (Green) of order\n"
             "--max-order with --rays rays per vertex; the environment's luminance\n"
             "projected to the same order; a reference exit radiance by direct\n"
             "integration of the environment itself with ray-cast visibility (light ×\n"
             "cosine summed exactly over the pixels, visibility sampled; --replications\n"
             "independent runs give its standard error).  For each order n the SH\n"
             "shading B_n = Σ_{i<n²} L_i t_i is compared with the reference:\n"
             "  rel_l2  = √Σ(B_n − ref)² / √Σ ref²          (over the vertices)\n"
             "  rel_max = max|B_n − ref| / RMS(ref)\n"
             "  ref_l2  = √Σ se² / √Σ ref²  (the reference's own error)\n"
             "The order for a budget E is the smallest n ≤ --max-order with rel_l2 ≤ E.\n"
             "With --max-beta B > 0 the lighting is also rotated, R = Rz(α)Ry(β)Rz(γ)\n"
             "(α = 0.7, γ = −0.4 rad) for β on the grid 0, h, …, B (h = --beta-step),\n"
             "by the exact rotation and by the Taylor approximations (Křivánek et al.\n"
             "2005), the reference recomputed with rays for each β; for each budget and\n"
             "method, the largest grid β up to which rel_l2 at the budget's order stays\n"
             "≤ E (null if it fails already at β = 0).\n"
             "Trusted or undecided.  A comparison \"rel_l2 ≤ E\" is trusted only when\n"
             "  ref_l2 ≤ min(E, rel_l2) / 10,\n"
             "the reference ten times below both numbers compared: its error adds to\n"
             "rel_l2 in quadrature, so it then moves rel_l2 by at most 0.5 % of E near\n"
             "the budget and of rel_l2 at the order decided.  An order rests on the\n"
             "comparisons at orders 1..n (ref_l2 ≤ E/10 and ≤ rel_l2(n)/10); a largest β\n"
             "on those at each β up to the first that fails, each with that β's\n"
             "reference.  Where the rule fails, the reference is refined: more\n"
             "replications pooled with those drawn (deterministic given --seed), as many\n"
             "as ref_l2 ∝ 1/√replications says it needs (× 1.25), at most 3 times and\n"
             "never beyond --refine × --replications (nor 1000) — the cap on its work.\n"
             "If the rule still fails, the decision is \"undecided\": no order or β is\n"
             "given, only the reference's error and what it would need.\n"
             "The errors are relative: the albedo ρ (--albedo) cancels.\n",
    .opts = plan_opts,
    .notes = "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"vertices_studied\",\n"
             "       \"rays_per_vertex\",\"reference\":{\"rays_per_vertex\",\"replications\" (asked),\n"
             "       \"replications_used\",\"max_replications\",\"ref_l2\",\"seconds\",\"rays_per_s\"},\n"
             "       \"threads\",\"orders\":[{\"order\",\"rel_l2\",\"rel_max\"}],\n"
             "       \"budgets\":[{\"budget\",\"decision\" (\"decided\"|\"undecided\"),\n"
             "                   \"order\" (null: none ≤ max-order, or undecided),\n"
             "                   \"rel_l2\" (at the order, at max-order when none; null if undecided),\n"
             "                   \"ref_l2\",\"ref_needed\" (what the rule asks of it),\n"
             "                   \"replications\",\"replications_needed\" (undecided: by 1/√R, null\n"
             "                   beyond 2³¹ − 2; decided: null),\n"
             "                   [\"max_beta\":{\"taylor1\"|\"taylor1.5\"|\"taylor2\":{\"decision\",\n"
             "                      \"max_beta\" (null: fails at β = 0, or undecided),\"at_beta\" (the β\n"
             "                      judged: undecided, where the rule fails; else the nearest to\n"
             "                      failing it),\"ref_l2\",\"ref_needed\",\"replications\",\n"
             "                      \"replications_needed\",\"model_ns_per_rotation\"}} (null without a\n"
             "                      decided order), \"exact_method\",\"exact_model_ns_per_rotation\"\n"
             "                      (the cost model's cheapest exact method at the order; costs of one\n"
             "                      rotation from a matrix in double, as `shlab plan` costs it)]}],\n"
             "       [\"rotation\":{\"units\",\"alpha\",\"gamma\",\"rows\":[{\"beta\",\"method\",\"order\",\"rel_l2\",\n"
             "                    \"ref_l2\",\"replications\"}]}]}\n"
             "Angles (alpha, gamma, beta, max_beta, at_beta) are in degrees with --degrees,\n"
             "else radians.\n"
             "Exit 0 when every budget has an order and every decision is trusted, 1 when\n"
             "some budget has none or some decision is undecided (the result is still\n"
             "printed, with one line on stderr each), as `plan` when no method qualifies.\n",
};

static const sh_rot_method taylor[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};
static const double alpha = 0.7, gamma_ = -0.4; /* the rotation study's α and γ (radians) */

/* One walk of the rotation study: a budget's order under a Taylor method,
 * β by β until the first comparison that fails (or breaks the rule). */
typedef struct {
    int open;                          /* still walking */
    int n;                             /* the β measured */
    double err[PLAN_MAX_BETAS + 1];    /* rel_l2 at each β */
    double ref[PLAN_MAX_BETAS + 1];    /* that β's reference's ref_l2 */
    int reps[PLAN_MAX_BETAS + 1];      /* and its replications */
    sh_beta_decision d;
} walk;

/* The study and what it found. */
typedef struct {
    const plan_args *a;
    double deg, max_beta, beta_step; /* radians */
    cli_scene_session s;
    sh_study *st;
    sh_study_info info;
    sh_shade_err err[CLI_SCENE_MAX_ORDER];     /* err[n − 1]: order n against the final reference */
    sh_order_decision dec[PLAN_MAX_BUDGETS];   /* each budget's order */
    walk w[PLAN_MAX_BUDGETS][3];               /* per budget and Taylor method */
    json_t *rows;                              /* the rotation study's rows */
} plan_work;

/* The rotation study's grid, in radians. */
static int validate(const plan_args *a, const cli_parsed *seen, plan_work *w)
{
    if (!cli_given(seen, "budget")) return cli_fail("scene-plan: --budget is required");
    w->deg = a->degrees ? M_PI / 180 : 1.0;
    w->max_beta = a->max_beta * w->deg;
    w->beta_step = a->beta_step > 0 ? a->beta_step * w->deg : 5 * M_PI / 180;
    if (!(w->max_beta >= 0 && w->max_beta <= M_PI * (1 + 1e-12))) return cli_fail("--max-beta: must be in [0, π]");
    if (w->max_beta > 0 && w->max_beta / w->beta_step > PLAN_MAX_BETAS)
        return cli_fail("--beta-step: more than %d grid points", PLAN_MAX_BETAS);
    return 0;
}

/* The study at every order up to --max-order, and each budget's order
 * (sh_study_decide_orders: the rule, the reference refined). */
static int study_orders(plan_work *w)
{
    const plan_args *a = w->a;
    sh_study_opts so = {0};
    so.max_order = a->max_order;
    so.rays = a->in.rays.rays;
    so.nverts = a->vertices;
    so.seed = (unsigned long)a->in.rays.seed;
    so.albedo = a->in.rays.albedo;
    so.ref.samples = a->ref.samples;
    so.ref.replications = a->ref.replications;
    so.refine = a->refine;
    so.threads = a->in.rays.threads;
    so.progress = cli_progress_step;
    so.progress_ctx = &w->s.prog;
    int e = sh_study_create(w->s.scene, w->s.env, &so, &w->st);
    if (!e) e = sh_study_decide_orders(w->st, SH_ROT_IVANIC, a->max_order, a->budget.n, a->budget.v, w->dec, w->err);
    if (!e) e = sh_study_info_get(w->st, &w->info);
    return e;
}

static int has_order(const plan_work *w, int k) { return !w->dec[k].undecided && w->dec[k].order > 0; }

/* Step j of the β grid in the unit printed: j times the step as the user
 * gave it (15, not 14.999999999999998, for the third step of 5°). */
static double grid_beta_shown(const plan_work *w, long j)
{
    const double step = w->a->beta_step > 0 ? w->a->beta_step : (w->a->degrees ? 5.0 : 5 * M_PI / 180);
    return (double)j * step;
}

/* The open walks' comparisons at this β (refining the reference until they
 * are trusted or the cap stops it), then each walk's verdict so far. */
static int walks_at(plan_work *w)
{
    const plan_args *a = w->a;
    sh_rot_method meth[3 * PLAN_MAX_BUDGETS];
    int ord[3 * PLAN_MAX_BUDGETS], m = 0;
    double bud[3 * PLAN_MAX_BUDGETS], er[3 * PLAN_MAX_BUDGETS];
    for (int k = 0; k < a->budget.n; k++)
        for (int t = 0; t < 3; t++)
            if (w->w[k][t].open) {
                meth[m] = taylor[t];
                ord[m] = w->dec[k].order;
                bud[m++] = a->budget.v[k];
            }
    int e = sh_study_compare(w->st, m, meth, ord, bud, er);
    sh_study_info in;
    if (!e) e = sh_study_info_get(w->st, &in);
    m = 0;
    for (int k = 0; k < a->budget.n && !e; k++)
        for (int t = 0; t < 3 && !e; t++) {
            walk *wk = &w->w[k][t];
            if (!wk->open) continue;
            wk->err[wk->n] = er[m++];
            wk->ref[wk->n] = in.ref_l2;
            wk->reps[wk->n] = in.replications;
            wk->n++;
            /* the walk stops at its first failure or at a comparison the rule cannot trust */
            e = sh_decide_beta(wk->n, wk->err, wk->ref, a->budget.v[k], &wk->d);
            if (!e && (wk->d.undecided || wk->d.last < wk->n - 1)) wk->open = 0;
        }
    return e;
}

/* One β of the rotation study: the reference recomputed, the walks, then
 * the exact rotation and each Taylor method at each budget's order (a row
 * each) against the reference as refined. */
static int rotation_at(plan_work *w, double beta)
{
    const plan_args *a = w->a;
    sh_rotation rot;
    int e;
    if ((e = sh_rotation_from_euler(alpha, beta, gamma_, &rot))) return e;
    if ((e = sh_study_set_rotation(w->st, &rot))) return e;
    if ((e = walks_at(w))) return e;
    sh_study_info in;
    if ((e = sh_study_info_get(w->st, &in))) return e;
    for (int t = -1; t < 3; t++) {
        const sh_rot_method meth = t < 0 ? SH_ROT_IVANIC : taylor[t];
        for (int k = 0; k < a->budget.n; k++) {
            if (!has_order(w, k)) continue;
            sh_shade_err er;
            if ((e = sh_study_error(w->st, meth, w->dec[k].order, &er))) return e;
            json_t *r = json_object();
            r = cli_put(r, "beta", json_real(grid_beta_shown(w, lround(beta / w->beta_step))));
            r = cli_put(r, "method", json_string(t < 0 ? "exact" : sh_rot_method_name(meth)));
            r = cli_put(r, "order", json_integer(w->dec[k].order));
            r = cli_put(r, "rel_l2", json_real(er.rel_l2));
            r = cli_put(r, "ref_l2", json_real(er.ref_l2));
            r = cli_put(r, "replications", json_integer(in.replications));
            if (!r || json_array_append_new(w->rows, r)) return sh_error(SH_ENOMEM, "out of memory");
        }
    }
    return SH_OK;
}

/* The rotation study: β on the grid 0, h, ..., --max-beta. */
static int rotation_study(plan_work *w)
{
    if (!(w->max_beta > 0)) return SH_OK;
    for (int k = 0; k < w->a->budget.n; k++)
        for (int t = 0; t < 3; t++) w->w[k][t].open = has_order(w, k);
    if (!(w->rows = json_array())) return sh_error(SH_ENOMEM, "out of memory");
    const int nbeta = (int)floor(w->max_beta / w->beta_step + 1e-9);
    int e = SH_OK;
    for (int j = 0; j <= nbeta && !e; j++) {
        const double beta = j * w->beta_step;
        if (!w->a->in.rays.quiet) fprintf(stderr, "scene-plan: β = %.4g (%d of %d): reference\n", beta, j + 1, nbeta + 1);
        e = rotation_at(w, beta);
    }
    return e;
}

/* What an undecided decision would need: the replications by the 1/√R law,
 * as JSON (null beyond INT_MAX − 1) and as words. */
static json_t *reps_json(double ref_l2, int reps, double needed)
{
    const int r = sh_study_replications_for(ref_l2, reps, needed);
    return r < INT_MAX ? json_integer(r) : json_null();
}
static const char *reps_words(double ref_l2, int reps, double needed, char *buf, size_t n)
{
    const int r = sh_study_replications_for(ref_l2, reps, needed);
    if (r < INT_MAX) snprintf(buf, n, "about %d replications", r);
    else snprintf(buf, n, "more than %d replications", INT_MAX - 1);
    return buf;
}

/* The cost model's ns for one rotation by m at the order (from a matrix,
 * double: set + apply), as `shlab plan` costs it; null outside the model. */
static json_t *model_ns(int order, sh_rot_method m)
{
    sh_cost c;
    return sh_cost_model(order, m, SH_PREC_DOUBLE, SH_BENCH_INPUT_MATRIX, SH_BENCH_PER_ROTATION, &c) == SH_OK
               ? json_real(c.ns) : json_null();
}

/* The exact method the cost model finds cheapest at the order, and its ns. */
static void cheapest_exact(int order, json_t **name, json_t **ns)
{
    double best = INFINITY;
    int bm = -1;
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        sh_cost c;
        if (m == SH_ROT_REFERENCE || m == SH_ROT_Z || !sh_rot_method_is_exact((sh_rot_method)m) ||
            sh_cost_model(order, (sh_rot_method)m, SH_PREC_DOUBLE, SH_BENCH_INPUT_MATRIX, SH_BENCH_PER_ROTATION, &c))
            continue;
        if (c.ns < best) best = c.ns, bm = m;
    }
    *name = bm >= 0 ? json_string(sh_rot_method_name((sh_rot_method)bm)) : json_null();
    *ns = bm >= 0 ? json_real(best) : json_null();
}

/* A walk's decision: {"decision","max_beta","at_beta","ref_l2","ref_needed",
 * "replications","replications_needed","model_ns_per_rotation"}. */
static json_t *walk_json(const plan_work *w, const walk *wk, int order, sh_rot_method m)
{
    const sh_beta_decision *d = &wk->d;
    const int undecided = d->undecided, reps = wk->reps[d->at];
    json_t *o = json_object();
    o = cli_put(o, "decision", json_string(undecided ? "undecided" : "decided"));
    o = cli_put(o, "max_beta", !undecided && d->last >= 0 ? json_real(grid_beta_shown(w, d->last)) : json_null());
    o = cli_put(o, "at_beta", json_real(grid_beta_shown(w, d->at)));
    o = cli_put(o, "ref_l2", json_real(d->ref_l2));
    o = cli_put(o, "ref_needed", json_real(d->ref_needed));
    o = cli_put(o, "replications", json_integer(reps));
    o = cli_put(o, "replications_needed", undecided ? reps_json(d->ref_l2, reps, d->ref_needed) : json_null());
    return cli_put(o, "model_ns_per_rotation", model_ns(order, m));
}

static json_t *budget_json(const plan_work *w, int k)
{
    const plan_args *a = w->a;
    const sh_order_decision *d = &w->dec[k];
    const int reps = w->info.replications;
    json_t *r = json_object();
    r = cli_put(r, "budget", json_real(a->budget.v[k]));
    r = cli_put(r, "decision", json_string(d->undecided ? "undecided" : "decided"));
    r = cli_put(r, "order", has_order(w, k) ? json_integer(d->order) : json_null());
    r = cli_put(r, "rel_l2", d->undecided ? json_null() : json_real(d->rel_l2));
    r = cli_put(r, "ref_l2", json_real(d->ref_l2));
    r = cli_put(r, "ref_needed", json_real(d->ref_needed));
    r = cli_put(r, "replications", json_integer(reps));
    r = cli_put(r, "replications_needed", d->undecided ? reps_json(d->ref_l2, reps, d->ref_needed) : json_null());
    if (w->max_beta > 0) {
        json_t *mb = has_order(w, k) ? json_object() : json_null();
        for (int t = 0; t < 3 && has_order(w, k); t++)
            mb = cli_put(mb, sh_rot_method_name(taylor[t]), walk_json(w, &w->w[k][t], d->order, taylor[t]));
        r = cli_put(r, "max_beta", mb);
        json_t *en = json_null(), *ens = json_null();
        if (has_order(w, k)) cheapest_exact(d->order, &en, &ens);
        r = cli_put(r, "exact_method", en);
        r = cli_put(r, "exact_model_ns_per_rotation", ens);
    }
    return r;
}

static json_t *build_result(plan_work *w)
{
    const plan_args *a = w->a;
    const sh_study_info *info = &w->info;
    json_t *root = cli_scene_session_result(&w->s);
    root = cli_put(root, "vertices_studied", json_integer(info->nverts));
    root = cli_put(root, "rays_per_vertex", json_integer(info->transfer.rays_per_vertex));
    json_t *ref = json_object();
    ref = cli_put(ref, "rays_per_vertex", json_integer(info->reference.rays_per_vertex));
    ref = cli_put(ref, "replications", json_integer(a->ref.replications));
    ref = cli_put(ref, "replications_used", json_integer(info->replications));
    ref = cli_put(ref, "max_replications", json_integer(info->max_replications));
    ref = cli_put(ref, "ref_l2", json_real(info->ref_l2));
    ref = cli_put(ref, "seconds", json_real(info->reference.seconds));
    ref = cli_put(ref, "rays_per_s", json_real(info->reference.rays_per_s));
    root = cli_put(root, "reference", ref);
    root = cli_put(root, "threads", json_integer(info->reference.threads));
    json_t *ords = json_array();
    for (int n = 1; n <= a->max_order && ords; n++) {
        json_t *r = json_object();
        r = cli_put(r, "order", json_integer(n));
        r = cli_put(r, "rel_l2", json_real(w->err[n - 1].rel_l2));
        r = cli_put(r, "rel_max", json_real(w->err[n - 1].rel_max));
        if (!r || json_array_append_new(ords, r)) { json_decref(ords); ords = NULL; }
    }
    root = cli_put(root, "orders", ords);
    json_t *bj = json_array();
    for (int k = 0; k < a->budget.n && bj; k++) {
        json_t *r = budget_json(w, k);
        if (!r || json_array_append_new(bj, r)) { json_decref(bj); bj = NULL; }
    }
    root = cli_put(root, "budgets", bj);
    if (w->max_beta > 0) {
        json_t *rj = json_object();
        rj = cli_put(rj, "units", json_string(a->degrees ? "degrees" : "radians"));
        rj = cli_put(rj, "alpha", json_real(alpha / w->deg));
        rj = cli_put(rj, "gamma", json_real(gamma_ / w->deg));
        rj = cli_put(rj, "rows", w->rows);
        w->rows = NULL;
        root = cli_put(root, "rotation", rj);
    }
    return root;
}

/* One line on stderr for each budget without an order or with a decision
 * the rule leaves undecided; 1 if there was any. */
static int report_gaps(const plan_work *w)
{
    const plan_args *a = w->a;
    const int N = a->max_order;
    int gaps = 0;
    char words[64];
    for (int k = 0; k < a->budget.n; k++) {
        const sh_order_decision *d = &w->dec[k];
        if (d->undecided) {
            fprintf(stderr,
                    "scene-plan: budget %g: order undecided: the reference's error %.3g is above the %.3g the rule "
                    "needs (%s; the cap is %d)\n",
                    a->budget.v[k], d->ref_l2, d->ref_needed,
                    reps_words(d->ref_l2, w->info.replications, d->ref_needed, words, sizeof words),
                    w->info.max_replications);
            gaps = 1;
        } else if (!d->order) {
            fprintf(stderr, "scene-plan: no order <= %d meets the budget %g (at %d: %.3g)\n", N, a->budget.v[k], N,
                    d->rel_l2);
            gaps = 1;
        }
        for (int t = 0; t < 3 && w->max_beta > 0 && has_order(w, k); t++) {
            const walk *wk = &w->w[k][t];
            if (!wk->d.undecided) continue;
            fprintf(stderr,
                    "scene-plan: budget %g, %s: largest β undecided at β = %g: the reference's error %.3g is above the "
                    "%.3g the rule needs (%s; the cap is %d)\n",
                    a->budget.v[k], sh_rot_method_name(taylor[t]), grid_beta_shown(w, wk->d.at), wk->d.ref_l2,
                    wk->d.ref_needed, reps_words(wk->d.ref_l2, wk->reps[wk->d.at], wk->d.ref_needed, words, sizeof words),
                    w->info.max_replications);
            gaps = 1;
        }
    }
    return gaps;
}

static int run(int argc, char **argv)
{
    plan_args a;
    memset(&a, 0, sizeof a);
    cli_parsed seen;
    int rc = cli_args_parse(&plan_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    plan_work w = {.a = &a};
    if ((rc = validate(&a, &seen, &w))) return rc;

    if ((rc = cli_scene_session_open("scene-plan", &a.in, a.degrees, CLI_SCENE_NEEDS_ENV, NULL, 0, &w.s))) return rc;
    int e = study_orders(&w);
    if (!e) e = rotation_study(&w);
    json_t *root = e ? NULL : build_result(&w);
    json_decref(w.rows);
    sh_study_free(w.st);
    cli_scene_session_close(&w.s);
    if (e) return cli_fail_status(e);
    const int gaps = report_gaps(&w);
    rc = cli_emit(root, (cli_format)a.fmt);
    return rc == CLI_EXIT_OK && gaps ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_scene_plan = {"scene-plan", run, "smallest SH order for a shading error budget on a scene", &plan_decl};
