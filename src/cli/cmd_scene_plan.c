/* cmd_scene_plan.c — `shlab scene-plan`: the smallest SH order whose
 * shading of a scene under an environment stays within an error budget,
 * measured against a reference by direct integration; and how far each
 * Taylor rotation may turn the lighting within the budget.  Logic in
 * src/scene/study.c. */
#include "cli_scene.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_scene_plan;

#define PLAN_MAX_BUDGETS 8
#define PLAN_MAX_BETAS 400

static const char help[] =
    "Usage: shlab scene-plan (--mesh FILE | --scene SPEC) (--probe FILE | --light SPEC)\n"
    "                        --budget E[,E2,...] [OPTIONS]\n"
    "\n"
    "Measure the shading error of SH lighting on a scene and choose the order.\n"
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
    "\n"
    CLI_SCENE_HELP
    CLI_ENV_HELP
    "  --budget LIST        relative L2 shading error budgets (each in (0, 1))\n"
    "  --max-order M        largest order tried (default 12; ≤ 32)\n"
    "  --rays R             transfer rays per vertex (default 1024)\n"
    "  --vertices K         vertices studied, a seeded random subset (default 500;\n"
    "                       0 = all)\n"
    "  --ref-samples S      reference blocks (rays) per replication (default 16384)\n"
    "  --replications R     reference replications (default 4)\n"
    "  --albedo A           ρ (default 1; the error is relative, ρ cancels)\n"
    "  --seed K             seed of the subset, the jitter (default 1)\n"
    "  --max-beta B         rotation study up to β = B (default 0: none)\n"
    "  --beta-step H        its grid step (default 5°)\n"
    "  --degrees            --max-beta, --beta-step (and --light angles) in degrees\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"vertices_studied\",\n"
    "       \"rays_per_vertex\",\"reference\":{\"rays_per_vertex\",\"replications\",\n"
    "       \"ref_l2\",\"seconds\",\"rays_per_s\"},\"threads\",\n"
    "       \"orders\":[{\"order\",\"rel_l2\",\"rel_max\"}],\n"
    "       \"budgets\":[{\"budget\",\"order\" (null: none ≤ max-order),\"rel_l2\",\n"
    "                   \"ref_ok\",[\"max_beta\":{\"taylor1\",\"taylor15\",\"taylor2\"}]}],\n"
    "       [\"rotation\":{\"units\",\"alpha\",\"gamma\",\"rows\":[{\"beta\",\"method\",\"order\",\"rel_l2\",\"ref_l2\"}]}]}\n"
    "Angles (alpha, gamma, beta, max_beta) are in degrees with --degrees, else radians.\n"
    "Exit 0 when every budget has an order, 1 when some has none (the result is\n"
    "still printed).\n";

static const sh_rot_method taylor[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};

static int run(int argc, char **argv)
{
    enum { O_BUDGET = 0x301, O_MAXORD, O_RAYS, O_VERTS, O_REFS, O_REPL, O_ALBEDO, O_SEED, O_MAXB, O_BSTEP, O_QUIET };
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPTS_SCENE,
                                         CLI_LONGOPTS_ENV,
                                         CLI_LONGOPT_DEGREES,
                                         {"budget", required_argument, 0, O_BUDGET},
                                         {"max-order", required_argument, 0, O_MAXORD},
                                         {"rays", required_argument, 0, O_RAYS},
                                         {"vertices", required_argument, 0, O_VERTS},
                                         {"ref-samples", required_argument, 0, O_REFS},
                                         {"replications", required_argument, 0, O_REPL},
                                         {"albedo", required_argument, 0, O_ALBEDO},
                                         {"seed", required_argument, 0, O_SEED},
                                         {"max-beta", required_argument, 0, O_MAXB},
                                         {"beta-step", required_argument, 0, O_BSTEP},
                                         {"quiet", no_argument, 0, O_QUIET},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    cli_scene_args sa = {0};
    sh_study_opts so = {0};
    so.max_order = 12;
    so.rays = 1024;
    so.nverts = 500;
    so.seed = 1;
    so.ref.samples = 16384;
    so.ref.replications = 4;
    double *budgets = NULL, max_beta = 0, beta_step = -1;
    int nb = 0, quiet = 0;
    long seed = 1;
    opterr = 0;
    optind = 1;
    int o;
#define FAIL(...) do { free(budgets); return cli_fail(__VA_ARGS__); } while (0)
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        const int e = cli_scene_opt("scene-plan", o, optarg, &sa);
        if (e > 0) { free(budgets); return e; }
        if (e == 0) continue;
        switch (o) {
        case O_BUDGET:
            free(budgets);
            budgets = NULL;
            if (cli_doubles("--budget", optarg, &budgets, &nb)) return CLI_EXIT_USAGE;
            if (nb < 1 || nb > PLAN_MAX_BUDGETS) FAIL("--budget: give 1..%d values", PLAN_MAX_BUDGETS);
            for (int k = 0; k < nb; k++)
                if (!(budgets[k] > 0 && budgets[k] < 1)) FAIL("--budget: each value must be in (0, 1)");
            break;
        case O_MAXORD:
            if (cli_order_max("--max-order", optarg, CLI_SCENE_MAX_ORDER, NULL, &so.max_order)) {
                free(budgets);
                return CLI_EXIT_USAGE;
            }
            break;
        case O_RAYS:
            if (cli_long("--rays", optarg, &so.rays)) { free(budgets); return CLI_EXIT_USAGE; }
            if (so.rays < 1 || so.rays > 1L << 20) FAIL("--rays: out of range 1..1048576");
            break;
        case O_VERTS:
            if (cli_int("--vertices", optarg, &so.nverts)) { free(budgets); return CLI_EXIT_USAGE; }
            if (so.nverts < 0) FAIL("--vertices: must be >= 0");
            break;
        case O_REFS:
            if (cli_long("--ref-samples", optarg, &so.ref.samples)) { free(budgets); return CLI_EXIT_USAGE; }
            if (so.ref.samples < 16 || so.ref.samples > 1L << 22) FAIL("--ref-samples: out of range 16..4194304");
            break;
        case O_REPL:
            if (cli_int("--replications", optarg, &so.ref.replications)) { free(budgets); return CLI_EXIT_USAGE; }
            if (so.ref.replications < 2 || so.ref.replications > 1000) FAIL("--replications: out of range 2..1000");
            break;
        case O_ALBEDO:
            if (cli_double("--albedo", optarg, &so.albedo)) { free(budgets); return CLI_EXIT_USAGE; }
            if (!(so.albedo > 0 && so.albedo <= 1)) FAIL("--albedo: must be in (0, 1]");
            break;
        case O_SEED:
            if (cli_long("--seed", optarg, &seed)) { free(budgets); return CLI_EXIT_USAGE; }
            if (seed < 0) FAIL("--seed: must be >= 0");
            so.seed = (unsigned long)seed;
            break;
        case O_MAXB:
            if (cli_double("--max-beta", optarg, &max_beta)) { free(budgets); return CLI_EXIT_USAGE; }
            break;
        case O_BSTEP:
            if (cli_double("--beta-step", optarg, &beta_step)) { free(budgets); return CLI_EXIT_USAGE; }
            if (!(beta_step > 0)) FAIL("--beta-step: must be > 0");
            break;
        case O_QUIET: quiet = 1; break;
        default: {
            const int e2 = cli_common_opt(&cmd_scene_plan, o, argv, &com);
            if (e2 >= 0) { free(budgets); return e2; }
        }
        }
    }
    if (optind < argc) FAIL("scene-plan: unexpected argument '%s'", argv[optind]);
    if (!nb) FAIL("scene-plan: --budget is required");
    const double deg = com.degrees ? M_PI / 180 : 1.0;
    max_beta *= deg;
    beta_step = beta_step > 0 ? beta_step * deg : 5 * M_PI / 180;
    if (!(max_beta >= 0 && max_beta <= M_PI * (1 + 1e-12))) FAIL("--max-beta: must be in [0, π]");
    if (max_beta > 0 && max_beta / beta_step > PLAN_MAX_BETAS) FAIL("--beta-step: more than %d grid points", PLAN_MAX_BETAS);
    so.threads = sa.threads;

    sh_mesh m;
    sh_proc_scene ps;
    int is_proc;
    sh_scene *s;
    json_t *desc, *edesc;
    int rc = cli_scene_build("scene-plan", &sa, &m, &ps, &is_proc, &s, &desc);
    if (rc) { free(budgets); return rc; }
    sh_env *env;
    if ((rc = cli_env_build("scene-plan", &sa, com.degrees, 0, &env, &edesc))) {
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        free(budgets);
        return rc;
    }
    cli_progress prog;
    cli_progress_start(&prog, "scene-plan", quiet);
    so.progress = cli_progress_step;
    so.progress_ctx = &prog;
    sh_study *st = NULL;
    int e = sh_study_create(s, env, &so, &st);
    const int N = so.max_order;
    sh_shade_err err[33];
    sh_study_info info;
    for (int n = 1; !e && n <= N; n++) e = sh_study_error(st, SH_ROT_IVANIC, n, &err[n]);
    if (!e) e = sh_study_info_get(st, &info);
    json_t *root = NULL;
    int missing = 0;
    if (!e) {
        root = json_object();
        root = cli_put(root, is_proc ? "scene" : "mesh", desc);
        desc = NULL;
        root = cli_put(root, "environment", edesc);
        edesc = NULL;
        root = cli_put(root, "vertices_studied", json_integer(info.nverts));
        root = cli_put(root, "rays_per_vertex", json_integer(info.transfer.rays_per_vertex));
        json_t *ref = json_object();
        ref = cli_put(ref, "rays_per_vertex", json_integer(info.reference.rays_per_vertex));
        ref = cli_put(ref, "replications", json_integer(so.ref.replications));
        ref = cli_put(ref, "ref_l2", json_real(info.ref_l2));
        ref = cli_put(ref, "seconds", json_real(info.reference.seconds));
        ref = cli_put(ref, "rays_per_s", json_real(info.reference.rays_per_s));
        root = cli_put(root, "reference", ref);
        root = cli_put(root, "threads", json_integer(info.reference.threads));
        json_t *ords = json_array();
        for (int n = 1; n <= N && ords; n++) {
            json_t *r = json_object();
            r = cli_put(r, "order", json_integer(n));
            r = cli_put(r, "rel_l2", json_real(err[n].rel_l2));
            r = cli_put(r, "rel_max", json_real(err[n].rel_max));
            if (!r || json_array_append_new(ords, r)) { json_decref(ords); ords = NULL; }
        }
        root = cli_put(root, "orders", ords);
    }
    int chosen[PLAN_MAX_BUDGETS];
    for (int k = 0; k < nb; k++) {
        chosen[k] = -1;
        for (int n = 1; n <= N && !e; n++)
            if (err[n].rel_l2 <= budgets[k]) { chosen[k] = n; break; }
        if (chosen[k] < 0) missing = 1;
    }
    /* rotation study: β grid, the reference recomputed per β */
    double limit[PLAN_MAX_BUDGETS][3];
    int stop[PLAN_MAX_BUDGETS][3];
    memset(stop, 0, sizeof stop);
    for (int k = 0; k < nb; k++)
        for (int t = 0; t < 3; t++) limit[k][t] = -1;
    json_t *rows = NULL;
    const double alpha = 0.7, gamma = -0.4;
    if (!e && max_beta > 0) {
        rows = json_array();
        const int nbeta = (int)floor(max_beta / beta_step + 1e-9);
        for (int j = 0; j <= nbeta && !e; j++) {
            const double beta = j * beta_step;
            sh_rotation rot;
            if ((e = sh_rotation_from_euler(alpha, beta, gamma, &rot))) break;
            if (!quiet) fprintf(stderr, "scene-plan: β = %.4g (%d of %d): reference\n", beta, j + 1, nbeta + 1);
            if ((e = sh_study_set_rotation(st, &rot))) break;
            for (int t = -1; t < 3 && !e; t++) {
                const sh_rot_method meth = t < 0 ? SH_ROT_IVANIC : taylor[t];
                for (int k = 0; k < nb && !e; k++) {
                    if (chosen[k] < 0) continue;
                    sh_shade_err er;
                    if ((e = sh_study_error(st, meth, chosen[k], &er))) break;
                    json_t *r = json_object();
                    r = cli_put(r, "beta", json_real(beta / deg));
                    r = cli_put(r, "method", json_string(t < 0 ? "exact" : sh_rot_method_name(meth)));
                    r = cli_put(r, "order", json_integer(chosen[k]));
                    r = cli_put(r, "rel_l2", json_real(er.rel_l2));
                    r = cli_put(r, "ref_l2", json_real(er.ref_l2));
                    if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; e = SH_ENOMEM; }
                    if (t >= 0 && !stop[k][t]) {
                        if (er.rel_l2 <= budgets[k]) limit[k][t] = beta;
                        else stop[k][t] = 1;
                    }
                }
            }
        }
        if (e == SH_ENOMEM && !rows) sh_error(SH_ENOMEM, "out of memory");
    }
    if (!e) {
        json_t *bj = json_array();
        for (int k = 0; k < nb && bj; k++) {
            json_t *r = json_object();
            r = cli_put(r, "budget", json_real(budgets[k]));
            r = cli_put(r, "order", chosen[k] > 0 ? json_integer(chosen[k]) : json_null());
            r = cli_put(r, "rel_l2", json_real(err[chosen[k] > 0 ? chosen[k] : N].rel_l2));
            /* the reference must be 10× below what it judges: the budget */
            r = cli_put(r, "ref_ok", json_boolean(10 * info.ref_l2 <= budgets[k]));
            if (max_beta > 0 && chosen[k] > 0) {
                json_t *mb = json_object();
                for (int t = 0; t < 3; t++)
                    mb = cli_put(mb, sh_rot_method_name(taylor[t]), limit[k][t] >= 0 ? json_real(limit[k][t] / deg) : json_null());
                r = cli_put(r, "max_beta", mb);
            }
            if (!r || json_array_append_new(bj, r)) { json_decref(bj); bj = NULL; }
        }
        root = cli_put(root, "budgets", bj);
        if (max_beta > 0) {
            json_t *rj = json_object();
            rj = cli_put(rj, "units", json_string(com.degrees ? "degrees" : "radians"));
            rj = cli_put(rj, "alpha", json_real(alpha / deg));
            rj = cli_put(rj, "gamma", json_real(gamma / deg));
            rj = cli_put(rj, "rows", rows);
            rows = NULL;
            root = cli_put(root, "rotation", rj);
        }
    }
    json_decref(rows);
    json_decref(desc);
    json_decref(edesc);
    sh_study_free(st);
    sh_env_free(env);
    sh_scene_free(s);
    sh_mesh_free(&m);
    if (e) {
        json_decref(root);
        free(budgets);
        return cli_fail_status(e);
    }
    for (int k = 0; k < nb; k++)
        if (chosen[k] < 0)
            fprintf(stderr, "scene-plan: no order <= %d meets the budget %g (at %d: %.3g)\n", N, budgets[k], N, err[N].rel_l2);
    free(budgets);
#undef FAIL
    rc = cli_emit(root, com.fmt);
    return rc == CLI_EXIT_OK && missing ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_scene_plan = {"scene-plan", run, "smallest SH order for a shading error budget on a scene",
                                    help, NULL};
