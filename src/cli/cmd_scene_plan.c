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
    int max_order, vertices, degrees, fmt;
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
             "  ref_l2  = √Σ se² / √Σ ref²  (the reference's own error; it should be\n"
             "            ≤ 1/10 of the errors it judges, reported as ref_ok)\n"
             "The order for a budget E is the smallest n ≤ --max-order with rel_l2 ≤ E.\n"
             "With --max-beta B > 0 the lighting is also rotated, R = Rz(α)Ry(β)Rz(γ)\n"
             "(α = 0.7, γ = −0.4 rad) for β on the grid 0, h, …, B (h = --beta-step),\n"
             "by the exact rotation and by the Taylor approximations (Křivánek et al.\n"
             "2005), the reference recomputed with rays for each β; for each budget and\n"
             "method, the largest grid β up to which rel_l2 at the chosen order stays\n"
             "≤ E (null if already the exact rotation fails it there).\n"
             "The errors are relative: the albedo ρ (--albedo) cancels.\n",
    .opts = plan_opts,
    .notes = "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"vertices_studied\",\n"
             "       \"rays_per_vertex\",\"reference\":{\"rays_per_vertex\",\"replications\",\n"
             "       \"ref_l2\",\"seconds\",\"rays_per_s\"},\"threads\",\n"
             "       \"orders\":[{\"order\",\"rel_l2\",\"rel_max\"}],\n"
             "       \"budgets\":[{\"budget\",\"order\" (null: none ≤ max-order),\"rel_l2\",\n"
             "                   \"ref_ok\",[\"max_beta\":{\"taylor1\",\"taylor15\",\"taylor2\"}]}],\n"
             "       [\"rotation\":{\"units\",\"alpha\",\"gamma\",\"rows\":[{\"beta\",\"method\",\"order\",\"rel_l2\",\"ref_l2\"}]}]}\n"
             "Angles (alpha, gamma, beta, max_beta) are in degrees with --degrees, else radians.\n"
             "Exit 0 when every budget has an order, 1 when some has none (the result is\n"
             "still printed).\n",
};

static const sh_rot_method taylor[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};
static const double alpha = 0.7, gamma_ = -0.4; /* the rotation study's α and γ (radians) */

/* The study and what it found. */
typedef struct {
    const plan_args *a;
    double deg, max_beta, beta_step; /* radians */
    cli_scene_session s;
    sh_study *st;
    sh_study_info info;
    sh_shade_err err[CLI_SCENE_MAX_ORDER + 1]; /* err[n]: order n against the reference */
    int chosen[PLAN_MAX_BUDGETS];              /* the order of each budget (-1: none) */
    double limit[PLAN_MAX_BUDGETS][3];         /* the largest β within the budget, per Taylor method (-1: none) */
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

/* The study at every order up to --max-order, and each budget's order. */
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
    so.threads = a->in.rays.threads;
    so.progress = cli_progress_step;
    so.progress_ctx = &w->s.prog;
    int e = sh_study_create(w->s.scene, w->s.env, &so, &w->st);
    for (int n = 1; !e && n <= a->max_order; n++) e = sh_study_error(w->st, SH_ROT_IVANIC, n, &w->err[n]);
    if (!e) e = sh_study_info_get(w->st, &w->info);
    for (int k = 0; k < a->budget.n; k++) {
        w->chosen[k] = -1;
        for (int n = 1; n <= a->max_order && !e; n++)
            if (w->err[n].rel_l2 <= a->budget.v[k]) { w->chosen[k] = n; break; }
    }
    return e;
}

/* One β of the rotation study: the reference recomputed, then the exact
 * rotation and each Taylor method at each budget's order (a row each);
 * the Taylor methods' limits follow while they stay within the budget. */
static int rotation_at(plan_work *w, double beta, int stop[][3])
{
    const plan_args *a = w->a;
    sh_rotation rot;
    int e;
    if ((e = sh_rotation_from_euler(alpha, beta, gamma_, &rot))) return e;
    if ((e = sh_study_set_rotation(w->st, &rot))) return e;
    for (int t = -1; t < 3; t++) {
        const sh_rot_method meth = t < 0 ? SH_ROT_IVANIC : taylor[t];
        for (int k = 0; k < a->budget.n; k++) {
            if (w->chosen[k] < 0) continue;
            sh_shade_err er;
            if ((e = sh_study_error(w->st, meth, w->chosen[k], &er))) return e;
            json_t *r = json_object();
            r = cli_put(r, "beta", json_real(beta / w->deg));
            r = cli_put(r, "method", json_string(t < 0 ? "exact" : sh_rot_method_name(meth)));
            r = cli_put(r, "order", json_integer(w->chosen[k]));
            r = cli_put(r, "rel_l2", json_real(er.rel_l2));
            r = cli_put(r, "ref_l2", json_real(er.ref_l2));
            if (!r || json_array_append_new(w->rows, r)) return sh_error(SH_ENOMEM, "out of memory");
            if (t >= 0 && !stop[k][t]) {
                if (er.rel_l2 <= a->budget.v[k]) w->limit[k][t] = beta;
                else stop[k][t] = 1;
            }
        }
    }
    return SH_OK;
}

/* The rotation study: β on the grid 0, h, ..., --max-beta. */
static int rotation_study(plan_work *w)
{
    int stop[PLAN_MAX_BUDGETS][3];
    memset(stop, 0, sizeof stop);
    for (int k = 0; k < PLAN_MAX_BUDGETS; k++)
        for (int t = 0; t < 3; t++) w->limit[k][t] = -1;
    if (!(w->max_beta > 0)) return SH_OK;
    if (!(w->rows = json_array())) return sh_error(SH_ENOMEM, "out of memory");
    const int nbeta = (int)floor(w->max_beta / w->beta_step + 1e-9);
    int e = SH_OK;
    for (int j = 0; j <= nbeta && !e; j++) {
        const double beta = j * w->beta_step;
        if (!w->a->in.rays.quiet) fprintf(stderr, "scene-plan: β = %.4g (%d of %d): reference\n", beta, j + 1, nbeta + 1);
        e = rotation_at(w, beta, stop);
    }
    return e;
}

static json_t *budgets_json(const plan_work *w)
{
    const plan_args *a = w->a;
    json_t *bj = json_array();
    for (int k = 0; k < a->budget.n && bj; k++) {
        const int n = w->chosen[k];
        json_t *r = json_object();
        r = cli_put(r, "budget", json_real(a->budget.v[k]));
        r = cli_put(r, "order", n > 0 ? json_integer(n) : json_null());
        r = cli_put(r, "rel_l2", json_real(w->err[n > 0 ? n : a->max_order].rel_l2));
        /* the reference must be 10× below what it judges: the budget */
        r = cli_put(r, "ref_ok", json_boolean(10 * w->info.ref_l2 <= a->budget.v[k]));
        if (w->max_beta > 0 && n > 0) {
            json_t *mb = json_object();
            for (int t = 0; t < 3; t++)
                mb = cli_put(mb, sh_rot_method_name(taylor[t]),
                             w->limit[k][t] >= 0 ? json_real(w->limit[k][t] / w->deg) : json_null());
            r = cli_put(r, "max_beta", mb);
        }
        if (!r || json_array_append_new(bj, r)) { json_decref(bj); bj = NULL; }
    }
    return bj;
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
    ref = cli_put(ref, "ref_l2", json_real(info->ref_l2));
    ref = cli_put(ref, "seconds", json_real(info->reference.seconds));
    ref = cli_put(ref, "rays_per_s", json_real(info->reference.rays_per_s));
    root = cli_put(root, "reference", ref);
    root = cli_put(root, "threads", json_integer(info->reference.threads));
    json_t *ords = json_array();
    for (int n = 1; n <= a->max_order && ords; n++) {
        json_t *r = json_object();
        r = cli_put(r, "order", json_integer(n));
        r = cli_put(r, "rel_l2", json_real(w->err[n].rel_l2));
        r = cli_put(r, "rel_max", json_real(w->err[n].rel_max));
        if (!r || json_array_append_new(ords, r)) { json_decref(ords); ords = NULL; }
    }
    root = cli_put(root, "orders", ords);
    root = cli_put(root, "budgets", budgets_json(w));
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

    const int N = a.max_order;
    int missing = 0;
    for (int k = 0; k < a.budget.n; k++)
        if (w.chosen[k] < 0) {
            fprintf(stderr, "scene-plan: no order <= %d meets the budget %g (at %d: %.3g)\n", N, a.budget.v[k], N,
                    w.err[N].rel_l2);
            missing = 1;
        }
    rc = cli_emit(root, (cli_format)a.fmt);
    return rc == CLI_EXIT_OK && missing ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_scene_plan = {"scene-plan", run, "smallest SH order for a shading error budget on a scene", &plan_decl};
