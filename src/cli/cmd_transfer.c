/* cmd_transfer.c — `shlab transfer`: Green's transfer vectors of a mesh or a
 * procedural scene, timed (rays per second), optionally checked against the
 * procedural scenes' closed forms.  Logic in src/scene/transfer.c. */
#include "cli_scene.h"

#include <getopt.h>
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_transfer;

static const char help[] =
    "Usage: shlab transfer (--mesh FILE | --scene SPEC) [OPTIONS]\n"
    "\n"
    "Green's per-vertex transfer vectors t(x) (exit radiance B = Σ L_i t_i for a\n"
    "lighting with SH coefficients L):\n"
    "  unshadowed      t_i = (ρ/π) ∫ y_i max(0, n·s) ds   (rays, or --closed-form)\n"
    "  shadowed        t_i = (ρ/π) ∫ y_i V(x,s) max(0, n·s) ds, V by ray casting\n"
    "  interreflected  shadowed plus bounces of transfer interpolated at the\n"
    "                  hits, until a bounce adds ≤ --bounce-tol of the total\n"
    "Rays per vertex: a jittered s×s grid mapped to the hemisphere with density\n"
    "cosθ/π, the same set for every vertex in its tangent frame; origins offset\n"
    "along the normal by --ray-eps × the bounding-box diagonal.  The time is\n"
    "the wall time of the ray passes (with --repeat R the median of R runs).\n"
    "\n"
    CLI_SCENE_HELP
    "  --transfer K         unshadowed | shadowed (default) | interreflected\n"
    "  --order N            number of bands (default 4; 1..32)\n"
    "  --rays R             rays per vertex (default 1024; rounded to a square)\n"
    "  --albedo A           ρ in (0, 1] (default 1)\n"
    "  --bounces B          interreflected: at most B bounces (default 100)\n"
    "  --bounce-tol E       interreflected: stop when a bounce adds ≤ E (default 1e-6)\n"
    "  --closed-form        unshadowed: the closed form (clamped cosine rotated to n)\n"
    "  --seed K             jitter seed (default 1)\n"
    "  --ray-eps E          ray origin offset (default 1e-4)\n"
    "  --repeat R           run R times, report the median time (default 1)\n"
    "  --check              --scene only: compare with the closed forms (below);\n"
    "                       exit 1 if a vertex is outside its bound\n"
    "  --replications R     --check: independent runs (seeds K..K+R−1) giving\n"
    "                       the standard error (default 16)\n"
    "  --convention cs|nocs basis (default cs)\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "Closed forms (--check): shadowed/unshadowed — sphere-plane plane vertices\n"
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
    "       \"max_excess\" (error − allowed, ≤ 0 passes),\"k\",\"failures\",\"ok\"}]}\n";

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

static int run(int argc, char **argv)
{
    enum { O_KIND = 0x301, O_RAYS, O_ALBEDO, O_BOUNCES, O_BTOL, O_CF, O_SEED, O_EPS, O_REPEAT, O_CHECK, O_REPL, O_QUIET };
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPTS_SCENE,
                                         CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_CONVENTION,
                                         {"transfer", required_argument, 0, O_KIND},
                                         {"rays", required_argument, 0, O_RAYS},
                                         {"albedo", required_argument, 0, O_ALBEDO},
                                         {"bounces", required_argument, 0, O_BOUNCES},
                                         {"bounce-tol", required_argument, 0, O_BTOL},
                                         {"closed-form", no_argument, 0, O_CF},
                                         {"seed", required_argument, 0, O_SEED},
                                         {"ray-eps", required_argument, 0, O_EPS},
                                         {"repeat", required_argument, 0, O_REPEAT},
                                         {"check", no_argument, 0, O_CHECK},
                                         {"replications", required_argument, 0, O_REPL},
                                         {"quiet", no_argument, 0, O_QUIET},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = CLI_SCENE_MAX_ORDER;
    cli_scene_args sa = {0};
    sh_transfer_opts to = {0};
    to.kind = SH_TRANSFER_SHADOWED;
    to.seed = 1;
    int repeat = 1, check = 0, repl = 16, quiet = 0, have_repl = 0;
    long seed = 1;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        const int e = cli_scene_opt("transfer", o, optarg, &sa);
        if (e > 0) return e;
        if (e == 0) continue;
        switch (o) {
        case O_KIND:
            if (sh_transfer_kind_parse(optarg, &to.kind)) return cli_fail("--transfer: %s", sh_last_error());
            break;
        case O_RAYS:
            if (cli_long("--rays", optarg, &to.rays)) return CLI_EXIT_USAGE;
            if (to.rays < 1 || to.rays > 1L << 20) return cli_fail("--rays: out of range 1..1048576");
            break;
        case O_ALBEDO:
            if (cli_double("--albedo", optarg, &to.albedo)) return CLI_EXIT_USAGE;
            if (!(to.albedo > 0 && to.albedo <= 1)) return cli_fail("--albedo: must be in (0, 1]");
            break;
        case O_BOUNCES:
            if (cli_int("--bounces", optarg, &to.max_bounces)) return CLI_EXIT_USAGE;
            if (to.max_bounces < 1 || to.max_bounces > SH_TRANSFER_MAX_BOUNCES)
                return cli_fail("--bounces: out of range 1..%d", SH_TRANSFER_MAX_BOUNCES);
            break;
        case O_BTOL:
            if (cli_double("--bounce-tol", optarg, &to.bounce_tol)) return CLI_EXIT_USAGE;
            if (!(to.bounce_tol > 0 && to.bounce_tol < 1)) return cli_fail("--bounce-tol: must be in (0, 1)");
            break;
        case O_CF: to.closed_form = 1; break;
        case O_SEED:
            if (cli_long("--seed", optarg, &seed)) return CLI_EXIT_USAGE;
            if (seed < 0) return cli_fail("--seed: must be >= 0");
            to.seed = (unsigned long)seed;
            break;
        case O_EPS:
            if (cli_double("--ray-eps", optarg, &to.ray_eps)) return CLI_EXIT_USAGE;
            if (!(to.ray_eps > 0 && to.ray_eps < 0.1)) return cli_fail("--ray-eps: must be in (0, 0.1)");
            break;
        case O_REPEAT:
            if (cli_int("--repeat", optarg, &repeat)) return CLI_EXIT_USAGE;
            if (repeat < 1 || repeat > 100) return cli_fail("--repeat: out of range 1..100");
            break;
        case O_CHECK: check = 1; break;
        case O_REPL:
            if (cli_int("--replications", optarg, &repl)) return CLI_EXIT_USAGE;
            if (repl < 2 || repl > 1000) return cli_fail("--replications: out of range 2..1000");
            have_repl = 1;
            break;
        case O_QUIET: quiet = 1; break;
        default: {
            const int e2 = cli_common_opt(&cmd_transfer, o, argv, &com);
            if (e2 >= 0) return e2;
        }
        }
    }
    if (optind < argc) return cli_fail("transfer: unexpected argument '%s'", argv[optind]);
    to.order = com.order ? com.order : 4;
    to.conv = com.conv;
    if (cli_applies("transfer", to.closed_form, "--closed-form", to.kind == SH_TRANSFER_UNSHADOWED, "--transfer unshadowed"))
        return CLI_EXIT_USAGE;
    if (check && !sa.scene) return cli_fail("transfer: --check needs a procedural --scene");
    if (check && to.closed_form) return cli_fail("transfer: --check compares the ray estimator; drop --closed-form");
    if (cli_applies("transfer", have_repl, "--replications", check, "--check")) return CLI_EXIT_USAGE;
    if (check && repeat > 1) return cli_fail("transfer: --repeat and --check do not go together");
    to.threads = sa.threads;

    sh_mesh m;
    sh_proc_scene ps;
    int is_proc;
    sh_scene *s;
    json_t *desc;
    int rc = cli_scene_build("transfer", &sa, &m, &ps, &is_proc, &s, &desc);
    if (rc) return rc;
    const int n2 = to.order * to.order, nv = m.nvert;
    const double rho = to.albedo > 0 ? to.albedo : 1.0;
    double furnace = 0;
    if (check && to.kind == SH_TRANSFER_INTERREFLECTED && sh_proc_furnace(&ps, rho, &furnace)) {
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        return cli_fail("transfer: --check: %s", sh_last_error());
    }
    double *T = malloc(sizeof(double) * (size_t)nv * n2), *mean = NULL, *sq = NULL, *times = malloc(sizeof(double) * 100);
    /* --check of the shadowed transfer: the closed forms first (a scene
     * without one is refused before any ray is cast) */
    double *CF = NULL, *BD = NULL;
    int *KN = NULL, nknown = 0;
    const int cf_first = check && to.kind == SH_TRANSFER_SHADOWED;
    if (check) {
        mean = calloc((size_t)nv * n2, sizeof(double));
        sq = calloc((size_t)nv * n2, sizeof(double));
    }
    if (cf_first) {
        CF = malloc(sizeof(double) * (size_t)nv * n2);
        BD = malloc(sizeof(double) * (size_t)nv * n2);
        KN = malloc(sizeof(int) * (size_t)nv);
    }
    int st = SH_OK;
    if (!T || !times || (check && (!mean || !sq)) || (cf_first && (!CF || !BD || !KN)))
        st = sh_error(SH_ENOMEM, "out of memory");
    if (!st && cf_first) {
        st = sh_proc_closed_forms(&ps, &m, nv, NULL, to.order, to.conv, rho,
                                  (to.ray_eps > 0 ? to.ray_eps : 1e-4) * sh_scene_diag(s), CF, BD, KN);
        for (int v = 0; v < nv && !st; v++) nknown += KN[v] > 0;
        if (!st && !nknown)
            st = sh_error(SH_EINVAL, "transfer: --check: no vertex of %s at this --res has a closed form to check against",
                          sa.scene);
    }
    if (st) {
        free(T); free(times); free(mean); free(sq); free(CF); free(BD); free(KN);
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        return cli_fail_status(st);
    }
    cli_progress prog;
    cli_progress_start(&prog, "transfer", quiet);
    to.progress = cli_progress_step;
    to.progress_ctx = &prog;
    sh_transfer_stats stats;
    const int runs = check ? repl : repeat;
    for (int r = 0; r < runs && !st; r++) {
        if (check) to.seed = (unsigned long)seed + (unsigned long)r;
        st = sh_transfer(s, &to, T, &stats);
        times[r] = stats.seconds;
        if (check)
            for (size_t i = 0; i < (size_t)nv * n2; i++) {
                mean[i] += T[i];
                sq[i] += T[i] * T[i];
            }
    }
    if (st) {
        free(T); free(times); free(mean); free(sq); free(CF); free(BD); free(KN);
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        return cli_fail_status(st);
    }
    /* median time */
    for (int a = 1; a < runs; a++)
        for (int b = a; b > 0 && times[b - 1] > times[b]; b--) {
            const double x = times[b];
            times[b] = times[b - 1];
            times[b - 1] = x;
        }
    const double med = runs % 2 ? times[runs / 2] : 0.5 * (times[runs / 2 - 1] + times[runs / 2]);
    json_t *root = json_object();
    root = cli_put(root, is_proc ? "scene" : "mesh", desc);
    root = cli_put(root, "transfer", json_string(sh_transfer_kind_name(to.kind)));
    root = cli_put(root, "order", json_integer(to.order));
    root = cli_put(root, "convention", json_string(sh_convention_name(to.conv)));
    root = cli_put(root, "albedo", json_real(rho));
    root = cli_put(root, "closed_form", json_boolean(to.closed_form));
    root = cli_put(root, "rays_per_vertex", json_integer(stats.rays_per_vertex));
    root = cli_put(root, "rays", json_integer(stats.rays));
    root = cli_put(root, "seconds", json_real(med));
    root = cli_put(root, "runs", json_integer(runs));
    root = cli_put(root, "rays_per_s", json_real(med > 0 ? stats.rays / med : 0));
    root = cli_put(root, "threads", json_integer(stats.threads));
    const double first = (double)stats.rays_per_vertex * nv;
    root = cli_put(root, "escaped_fraction", json_real(first > 0 && !to.closed_form ? stats.escaped / first : 0));
    root = cli_put(root, "backface_fraction", json_real(first > 0 && !to.closed_form ? stats.backface / first : 0));
    if (to.kind == SH_TRANSFER_INTERREFLECTED) {
        root = cli_put(root, "bounces", json_integer(stats.bounces));
        root = cli_put(root, "converged", json_boolean(stats.converged));
        root = cli_put(root, "last_bounce_rel", json_real(stats.last_bounce_rel));
    }
    int failed = 0;
    if (check) {
        check_result cr = {0};
        /* k: P(|t_{R−1}| > k) = 1 % / (comparisons), the comparisons being at
         * most every coefficient of every vertex */
        const double ncmp = (double)nv * (to.kind == SH_TRANSFER_INTERREFLECTED ? 1 : n2);
        const double k = gsl_cdf_tdist_Qinv(0.01 / (2 * ncmp), repl - 1);
        double *cf = malloc(sizeof(double) * n2), *bd = malloc(sizeof(double) * n2);
        for (int v = 0; v < nv && cf && bd && !st; v++) {
            double *mu = mean + (size_t)v * n2, *s2 = sq + (size_t)v * n2;
            double se[1024];
            for (int i = 0; i < n2; i++) {
                mu[i] /= repl;
                se[i] = sqrt(fmax(0.0, (s2[i] - repl * mu[i] * mu[i]) / (repl - 1)) / repl);
            }
            int known = 0;
            if (to.kind == SH_TRANSFER_INTERREFLECTED) {
                if (ps.kind == SH_PROC_BOWL && !(m.pos[3 * v + 2] < -1e-9)) continue; /* the rim */
                cr.vertices++;
                /* constant radiance 1: B = √(4π) t_0; exact for ρ = 1, else within the
                 * sky fraction's Monte Carlo error (6 SE of t_0, scaled to B) */
                check_one(&cr, fabs(sqrt(4 * M_PI) * mu[0] - furnace),
                          (rho == 1 ? 1e-9 : 0) + k * sqrt(4 * M_PI) * se[0] + (rho == 1 ? 0 : 1e-3));
                continue;
            }
            if (to.kind == SH_TRANSFER_UNSHADOWED) {
                if ((st = sh_transfer_unshadowed(to.order, to.conv, rho, m.normal + 3 * v, cf))) break;
                for (int i = 0; i < n2; i++) bd[i] = 0;
                known = to.order;
            } else {
                memcpy(cf, CF + (size_t)v * n2, sizeof(double) * n2);
                memcpy(bd, BD + (size_t)v * n2, sizeof(double) * n2);
                known = KN[v];
            }
            if (!known) continue;
            cr.vertices++;
            for (int i = 0; i < known * known; i++) check_one(&cr, fabs(mu[i] - cf[i]), bd[i] + k * se[i] + 1e-12);
        }
        free(cf);
        free(bd);
        if (st) {
            json_decref(root);
            free(T); free(times); free(mean); free(sq); free(CF); free(BD); free(KN);
            sh_scene_free(s);
            sh_mesh_free(&m);
            return cli_fail_status(st);
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
        root = cli_put(root, "check", c);
        failed = cr.failures > 0 || cr.vertices == 0;
    }
    free(T); free(times); free(mean); free(sq); free(CF); free(BD); free(KN);
    sh_scene_free(s);
    sh_mesh_free(&m);
    rc = cli_emit(root, com.fmt);
    return rc == CLI_EXIT_OK && failed ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_transfer = {"transfer", run, "Green's transfer vectors of a mesh or procedural scene (rays/s)", help, NULL};
