/* cmd_transfer.c — `shlab transfer`: Green's transfer vectors of a mesh or a
 * procedural scene, timed (rays per second), optionally checked against the
 * procedural scenes' closed forms.  Logic in src/scene/transfer.c. */
#include "cli_scene.h"

#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_transfer;

typedef struct {
    cli_scene_input in;
    sh_transfer_kind kind;
    int order, conv, fmt;
    int bounces;
    double bounce_tol, ray_eps;
    int closed_form, repeat, check, replications;
} transfer_args;

static const cli_opt transfer_opts[] = {
    CLI_CUSTOM(transfer_args, kind, "transfer", "K", cli_parse_transfer_kind, "shadowed",
               "unshadowed | shadowed | interreflected"),
    CLI_SCENE_ORDER(transfer_args, order, CLI_SCENE_MAX_ORDER, "4", "number of bands"),
    CLI_INT(transfer_args, bounces, "bounces", "B", 1, SH_TRANSFER_MAX_BOUNCES, "100",
            "interreflected: at most B bounces"),
    CLI_REAL(transfer_args, bounce_tol, "bounce-tol", "E", 0, 1, CLI_LO_OPEN | CLI_HI_OPEN, "1e-6",
             "interreflected: stop when a bounce adds ≤ E"),
    CLI_FLAG(transfer_args, closed_form, "closed-form", "unshadowed: the closed form (clamped cosine rotated to n)"),
    CLI_REAL(transfer_args, ray_eps, "ray-eps", "E", 0, 0.1, CLI_LO_OPEN | CLI_HI_OPEN, "1e-4", "ray origin offset"),
    CLI_INT(transfer_args, repeat, "repeat", "R", 1, 100, "1", "run R times, report the median time"),
    CLI_FLAG(transfer_args, check, "check",
             "--scene only: compare with the closed forms (below);\nexit 1 if a vertex is outside its bound"),
    CLI_INT(transfer_args, replications, "replications", "R", 2, 1000, "16",
            "--check: independent runs (seeds K..K+R−1) giving\nthe standard error"),
    CLI_CONVENTION(transfer_args, conv),
    CLI_FORMAT(transfer_args, fmt),
    CLI_GROUP(transfer_args, in.scene, cli_scene_opts),
    CLI_GROUP(transfer_args, in.rays, cli_rays_opts),
    CLI_DEFAULT("albedo", "1"),
    CLI_END,
};

static const cli_cmd transfer_decl = {
    .name = "transfer",
    .usage = "transfer (--mesh FILE | --scene SPEC) [OPTIONS]",
    .about = "Green's per-vertex transfer vectors t(x) (exit radiance B = Σ L_i t_i for a\n"
             "lighting with SH coefficients L):\n"
             "  unshadowed      t_i = (ρ/π) ∫ y_i max(0, n·s) ds   (rays, or --closed-form)\n"
             "  shadowed        t_i = (ρ/π) ∫ y_i V(x,s) max(0, n·s) ds, V by ray casting\n"
             "  interreflected  shadowed plus bounces of transfer interpolated at the\n"
             "                  hits, until a bounce adds ≤ --bounce-tol of the total\n"
             "Rays per vertex: a jittered s×s grid mapped to the hemisphere with density\n"
             "cosθ/π, the same set for every vertex in its tangent frame (--rays rounded\n"
             "to a square); origins offset along the normal by --ray-eps × the\n"
             "bounding-box diagonal.  The time is the wall time of the ray passes (with\n"
             "--repeat R the median of R runs).\n",
    .opts = transfer_opts,
    .notes = "Closed forms (--check): shadowed/unshadowed — sphere-plane plane vertices\n"
             "(every coefficient, the sphere's cap by Gaunt coefficients), bowl (t_0 of\n"
             "sky fraction ½), box floor (t_0 of the hole's view factor); checked as\n"
             "|mean − closed form| ≤ tessellation bound + k·SE, k the two-sided quantile\n"
             "of Student's t (R−1 degrees of freedom) at which all the comparisons\n"
             "together fail by chance with probability 1 %; unshadowed against the\n"
             "closed form everywhere.  Interreflected with ρ = 1 (and the bowl with any\n"
             "ρ): the furnace — constant radiance 1 gives B = 1 (bowl: ρ/(2−ρ)).\n"
             "\n"
             "JSON: {\"mesh\"|\"scene\":{...vertices, triangles, validation},\"transfer\",\"order\",\n"
             "       \"albedo\",\"rays_per_vertex\",\"rays\",\"seconds\",\"rays_per_s\",\"threads\",\n"
             "       \"escaped_fraction\",\"backface_fraction\",[\"bounces\",\"converged\",\n"
             "       \"last_bounce_rel\"],[\"check\":{\"vertices\",\"coefficients\",\"max_error\",\n"
             "       \"max_excess\" (error − allowed, ≤ 0 passes),\"k\",\"failures\",\"ok\"}]}\n",
};

/* The run: the options for sh_transfer, the scene, and what the runs made. */
typedef struct {
    const transfer_args *a;
    sh_transfer_opts to;
    cli_scene_session s;
    int nv, n2, runs;
    double furnace;             /* --check, interreflected: the furnace's answer */
    double *T, *times;          /* the last run's transfer; each run's seconds */
    double *mean, *sq;          /* --check: Σ T and Σ T² over the replications */
    double *CF, *BD;            /* --check, shadowed: closed forms and their bounds */
    int *KN;                    /* --check, shadowed: the bands known at each vertex */
    sh_transfer_stats stats;
} transfer_work;

typedef struct {
    int vertices, coeffs, failures;
    double max_error, max_excess;
} check_result;

static void check_one(check_result *r, double err, double allowed)
{
    r->coeffs++;
    r->max_error = fmax(r->max_error, err);
    const double ex = err - allowed;
    if (r->coeffs == 1 || ex > r->max_excess) r->max_excess = ex;
    if (ex > 0) r->failures++;
}

/* The options that go together (one option's range is the table's). */
static int validate(const transfer_args *a, const cli_parsed *seen)
{
    if (cli_applies("transfer", a->closed_form, "--closed-form", a->kind == SH_TRANSFER_UNSHADOWED,
                    "--transfer unshadowed"))
        return CLI_EXIT_USAGE;
    if (a->check && !a->in.scene.scene) return cli_fail("transfer: --check needs a procedural --scene");
    if (a->check && a->closed_form) return cli_fail("transfer: --check compares the ray estimator; drop --closed-form");
    if (cli_scene_applies("transfer", seen, "replications", a->check, "--check")) return CLI_EXIT_USAGE;
    if (a->check && a->repeat > 1) return cli_fail("transfer: --repeat and --check do not go together");
    return 0;
}

static void transfer_options(const transfer_args *a, transfer_work *w)
{
    sh_transfer_opts *to = &w->to;
    *to = cli_scene_transfer_opts(&w->s, &a->in.rays, a->kind, a->order);
    to->conv = (sh_convention)a->conv;
    to->max_bounces = a->bounces;
    to->bounce_tol = a->bounce_tol;
    to->ray_eps = a->ray_eps;
    to->closed_form = a->closed_form;
}

/* The arrays, and for --check what the runs are checked against: the
 * furnace's answer, the shadowed closed forms (a scene without one is
 * refused before any ray is cast). */
static int prepare(transfer_work *w)
{
    const transfer_args *a = w->a;
    const size_t nt = (size_t)w->nv * w->n2;
    const int cf_first = a->check && a->kind == SH_TRANSFER_SHADOWED;
    if (a->check && a->kind == SH_TRANSFER_INTERREFLECTED && sh_proc_furnace(&w->s.proc, w->to.albedo, &w->furnace))
        return cli_fail("transfer: --check: %s", sh_last_error());
    w->T = malloc(sizeof(double) * nt);
    w->times = malloc(sizeof(double) * 100);
    if (a->check) {
        w->mean = calloc(nt, sizeof(double));
        w->sq = calloc(nt, sizeof(double));
    }
    if (cf_first) {
        w->CF = malloc(sizeof(double) * nt);
        w->BD = malloc(sizeof(double) * nt);
        w->KN = malloc(sizeof(int) * (size_t)w->nv);
    }
    if (!w->T || !w->times || (a->check && (!w->mean || !w->sq)) || (cf_first && (!w->CF || !w->BD || !w->KN)))
        return cli_fail_status(sh_error(SH_ENOMEM, "out of memory"));
    if (!cf_first) return 0;
    int st = sh_proc_closed_forms(&w->s.proc, &w->s.mesh, w->nv, NULL, a->order, w->to.conv, w->to.albedo,
                                  a->ray_eps * sh_scene_diag(w->s.scene), w->CF, w->BD, w->KN);
    int nknown = 0;
    for (int v = 0; v < w->nv && !st; v++) nknown += w->KN[v] > 0;
    if (!st && !nknown)
        st = sh_error(SH_EINVAL, "transfer: --check: no vertex of %s at this --res has a closed form to check against",
                      a->in.scene.scene);
    return st ? cli_fail_status(st) : 0;
}

/* --repeat runs (their median time), or --check's replications (seeds K,
 * K+1, ...; Σ T and Σ T² kept). */
static int run_transfers(transfer_work *w)
{
    const transfer_args *a = w->a;
    const unsigned long seed = w->to.seed;
    w->runs = a->check ? a->replications : a->repeat;
    for (int r = 0; r < w->runs; r++) {
        if (a->check) w->to.seed = seed + (unsigned long)r;
        const int st = sh_transfer(w->s.scene, &w->to, w->T, &w->stats);
        if (st) return cli_fail_status(st);
        w->times[r] = w->stats.seconds;
        if (a->check)
            for (size_t i = 0; i < (size_t)w->nv * w->n2; i++) {
                w->mean[i] += w->T[i];
                w->sq[i] += w->T[i] * w->T[i];
            }
    }
    return 0;
}

/* The closed forms against the replications' means: a json object, *failed
 * set when a vertex is outside its bound (or none was checked). */
static int check_result_json(transfer_work *w, json_t **out, int *failed)
{
    const transfer_args *a = w->a;
    const int n2 = w->n2, repl = a->replications;
    const double rho = w->to.albedo;
    check_result cr = {0};
    /* k: P(|t_{R−1}| > k) = 1 % / (comparisons), the comparisons being at
     * most every coefficient of every vertex */
    const double ncmp = (double)w->nv * (a->kind == SH_TRANSFER_INTERREFLECTED ? 1 : n2);
    const double k = gsl_cdf_tdist_Qinv(0.01 / (2 * ncmp), repl - 1);
    double cf[1024], bd[1024], se[1024];
    for (int v = 0; v < w->nv; v++) {
        double *mu = w->mean + (size_t)v * n2, *s2 = w->sq + (size_t)v * n2;
        for (int i = 0; i < n2; i++) {
            mu[i] /= repl;
            se[i] = sqrt(fmax(0.0, (s2[i] - repl * mu[i] * mu[i]) / (repl - 1)) / repl);
        }
        if (a->kind == SH_TRANSFER_INTERREFLECTED) {
            if (w->s.proc.kind == SH_PROC_BOWL && !(w->s.mesh.pos[3 * v + 2] < -1e-9)) continue; /* the rim */
            cr.vertices++;
            /* constant radiance 1: B = √(4π) t_0; exact for ρ = 1, else within the
             * sky fraction's Monte Carlo error (6 SE of t_0, scaled to B) */
            check_one(&cr, fabs(sqrt(4 * M_PI) * mu[0] - w->furnace),
                      (rho == 1 ? 1e-9 : 0) + k * sqrt(4 * M_PI) * se[0] + (rho == 1 ? 0 : 1e-3));
            continue;
        }
        int known;
        if (a->kind == SH_TRANSFER_UNSHADOWED) {
            const int st = sh_transfer_unshadowed(a->order, w->to.conv, rho, w->s.mesh.normal + 3 * v, cf);
            if (st) return cli_fail_status(st);
            for (int i = 0; i < n2; i++) bd[i] = 0;
            known = a->order;
        } else {
            memcpy(cf, w->CF + (size_t)v * n2, sizeof(double) * n2);
            memcpy(bd, w->BD + (size_t)v * n2, sizeof(double) * n2);
            known = w->KN[v];
        }
        if (!known) continue;
        cr.vertices++;
        for (int i = 0; i < known * known; i++) check_one(&cr, fabs(mu[i] - cf[i]), bd[i] + k * se[i] + 1e-12);
    }
    json_t *c = json_object();
    c = cli_put(c, "replications", json_integer(repl));
    c = cli_put(c, "vertices", json_integer(cr.vertices));
    c = cli_put(c, "coefficients", json_integer(cr.coeffs));
    c = cli_put(c, "max_error", json_real(cr.max_error));
    c = cli_put(c, "max_excess", json_real(cr.max_excess));
    c = cli_put(c, "k", json_real(k));
    c = cli_put(c, "failures", json_integer(cr.failures));
    c = cli_put(c, "ok", json_boolean(cr.failures == 0 && cr.vertices > 0));
    *out = c;
    *failed = cr.failures > 0 || cr.vertices == 0;
    return 0;
}

/* The result: the scene, the transfer's parameters, the median time. */
static json_t *build_result(transfer_work *w)
{
    const sh_transfer_opts *to = &w->to;
    const sh_transfer_stats *st = &w->stats;
    const double med = cli_median(w->times, w->runs);
    json_t *root = cli_scene_session_result(&w->s);
    root = cli_put(root, "transfer", json_string(sh_transfer_kind_name(to->kind)));
    root = cli_put(root, "order", json_integer(to->order));
    root = cli_put(root, "convention", json_string(sh_convention_name(to->conv)));
    root = cli_put(root, "albedo", json_real(to->albedo));
    root = cli_put(root, "closed_form", json_boolean(to->closed_form));
    root = cli_put(root, "rays_per_vertex", json_integer(st->rays_per_vertex));
    root = cli_put(root, "rays", json_integer(st->rays));
    root = cli_put(root, "seconds", json_real(med));
    root = cli_put(root, "runs", json_integer(w->runs));
    root = cli_put(root, "rays_per_s", json_real(med > 0 ? st->rays / med : 0));
    root = cli_put(root, "threads", json_integer(st->threads));
    const double first = (double)st->rays_per_vertex * w->nv;
    root = cli_put(root, "escaped_fraction", json_real(first > 0 && !to->closed_form ? st->escaped / first : 0));
    root = cli_put(root, "backface_fraction", json_real(first > 0 && !to->closed_form ? st->backface / first : 0));
    if (to->kind == SH_TRANSFER_INTERREFLECTED) {
        root = cli_put(root, "bounces", json_integer(st->bounces));
        root = cli_put(root, "converged", json_boolean(st->converged));
        root = cli_put(root, "last_bounce_rel", json_real(st->last_bounce_rel));
    }
    return root;
}

static void work_free(transfer_work *w)
{
    free(w->T); free(w->times); free(w->mean); free(w->sq); free(w->CF); free(w->BD); free(w->KN);
    cli_scene_session_close(&w->s);
}

static int run(int argc, char **argv)
{
    transfer_args a;
    memset(&a, 0, sizeof a);
    cli_parsed seen;
    int rc = cli_args_parse(&transfer_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;

    transfer_work w = {.a = &a, .n2 = a.order * a.order};
    if ((rc = cli_scene_session_open("transfer", &a.in, 0, 0, NULL, 0, &w.s))) return rc;
    w.nv = w.s.mesh.nvert;
    transfer_options(&a, &w);
    rc = prepare(&w);
    if (!rc) rc = run_transfers(&w);
    json_t *root = NULL, *check = NULL;
    int failed = 0;
    if (!rc && a.check) rc = check_result_json(&w, &check, &failed);
    if (!rc) {
        root = build_result(&w);
        if (check) root = cli_put(root, "check", check);
    }
    work_free(&w);
    if (rc) return rc;
    rc = cli_emit(root, (cli_format)a.fmt);
    return rc == CLI_EXIT_OK && failed ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_transfer = {"transfer", run, "Green's transfer vectors of a mesh or procedural scene (rays/s)", &transfer_decl};
