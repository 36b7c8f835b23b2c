/* cmd_project.c — `shlab project`: SH coefficients of an analytic light
 * (closed form or a projection rule) or of an EXR environment image. */
#include "cli.h"
#include "cli_image_opts.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
    int order, conv, fmt;
    cli_light_args light;
    sh_rule rule;
    cli_sampling_args s;
    const char *exr;
    sh_layout layout;
    cli_run_args run;
} project_args;

static int parse_layout(const char *opt, const char *s, void *field)
{
    return sh_layout_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

static const cli_opt project_opts[] = {
    CLI_ORDER(project_args, order, SHLAB_MAX_ORDER, NULL, "number of bands"),
    CLI_GROUP(project_args, light, cli_light_opts),
    CLI_CUSTOM(project_args, rule, "method", "M", cli_parse_rule, NULL,
               "the rule for --light; cap, const and lobe use their\n"
               "closed forms unless it is given, the others quad:\n"
               "quad   Gauss-Legendre in cosθ (S nodes) × 2S uniform φ\n"
               "mc     Green's stratified jittered Monte Carlo (S → round(√S)²)\n"
               "random plain uniform Monte Carlo\n"
               "qmc    Sobol points, shifted by a seeded random vector"),
    CLI_GROUP(project_args, s, cli_sampling_opts),
    CLI_STRING(project_args, exr, "exr", "FILE", "an OpenEXR environment image (R,G,B or Y channels)"),
    CLI_CUSTOM(project_args, layout, "layout", "L", parse_layout, "latlong",
               "latlong (default) or probe (Debevec angle map)"),
    CLI_CONVENTION(project_args, conv),
    CLI_GROUP(project_args, run, cli_run_opts),
    CLI_FORMAT(project_args, fmt),
    CLI_END,
};

static const cli_cmd project_decl = {
    .name = "project",
    .usage = "project --order N --light SPEC [--method quad|mc|random|qmc]\n"
             "                     [--samples S] [--seed K] [--degrees] [OPTIONS]\n"
             "       shlab project --order N --exr FILE [--layout latlong|probe] [OPTIONS]",
    .about = "Project a spherical function onto the n² real SH of bands 0..N-1,\n"
             "c_i = ∫ f y_i dΩ.\n",
    .opts = project_opts,
    .notes = "--samples: quad 1500 θ nodes by default (at most 20000), the others 10000\n"
             "samples (at most 1e8).  --threads: the threads of quad and --exr latlong.\n"
             "\n"
             "quad and latlong run the fast transform: an FFT in φ per ring of latitude\n"
             "and the Legendre recurrence across pairs of rings (docs/high-bands.md,\n"
             "\"High-band projection and synthesis\").  A long run prints its size before it starts,\n"
             "an estimate after the first chunk of rings, and progress once a second;\n"
             "a request whose memory (working memory and the printed result) exceeds\n"
             "what is available is refused before anything is allocated.\n"
             "\n"
             "JSON (light): {\"order\",\"convention\",\"light\",[\"unit\" of the angles in SPEC: cap,\n"
             "  cie-clear, cie-partly],\"method\",\"samples\",\"seed\",\"coeffs\":[n²]}\n"
             "  (\"method\" is \"closed-form\" when the closed form was used; \"samples\" is\n"
             "  the number actually used, 0 for closed forms)\n"
             "JSON (exr): {\"order\",\"convention\",\"layout\",\"width\",\"height\",\"fallback\",\n"
             "  \"channels\":{\"R\":[n²],\"G\":[n²],\"B\":[n²]}}\n",
};

/* Upper bounds that keep a request from running for hours. */
#define MAX_QUAD_NODES 20000L
#define MAX_SAMPLES 100000000L
/* Memory of one printed coefficient: the JSON tree and its rendered text. */
#define OUT_BYTES_PER_NUMBER 100.0

/* Working memory of a transform plan of `order` on nrings × nphi, plus the
 * coefficients and their printed form; refused (one line) if it cannot fit. */
static int check_memory(int order, int nrings, int nphi, int nchan, int threads, const char *what)
{
    const sh_grid g = {nrings, nphi, NULL, NULL, 0.0};
    const double n = (double)order * order * nchan;
    const double need = (double)sh_sht_bytes(order, &g, nchan, threads) + n * (8.0 + OUT_BYTES_PER_NUMBER);
    return cli_mem_check("project", need, what);
}

/* An analytic light: its closed form, or the rule of --method. */
static int run_light(const project_args *a, sh_light *L, int closed)
{
    const int order = a->order, n = sh_ncoeff(order);
    const long S = sh_rule_samples_used(a->rule, a->s.samples);
    if (!closed && a->rule == SH_RULE_QUAD) {
        char what[96];
        snprintf(what, sizeof what, "order %d on %ld × %ld Gauss nodes", order, S, 2 * S);
        const int rc = check_memory(order, (int)S, (int)(2 * S), 1, a->run.threads, what);
        if (rc) return rc;
        /* about 50 ns a function value and 1 ns a Legendre step: say what is coming */
        const double t = 1e-7 * S * S + 1e-9 * 0.25 * order * (double)order * S;
        if (!a->run.quiet && t > 2.0)
            fprintf(stderr, "project: %s, %.3g function values; an estimate follows the first chunk\n",
                    what, 2.0 * S * S);
    } else if (cli_mem_check("project", (double)n * (8.0 + OUT_BYTES_PER_NUMBER), "the result")) {
        return CLI_EXIT_USAGE;
    }
    double *c = malloc(sizeof(double) * (size_t)n);
    if (!c) return cli_fail("out of memory");
    int st;
    if (closed) {
        st = sh_light_closed_form(L, order, a->conv, c);
    } else {
        cli_progress prog;
        cli_progress_start(&prog, "project", a->run.quiet);
        const sh_run_opts opts = {a->run.threads, cli_progress_step_est, &prog};
        st = sh_project_ex(order, a->conv, sh_light_fn, L, a->rule, a->s.samples, (unsigned long)a->s.seed, &opts, c);
    }
    if (st) { free(c); return cli_fail_status(st); }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(a->conv)));
    root = cli_put(root, "light", json_string(a->light.spec));
    if (cli_light_has_angles(L)) root = cli_put(root, "unit", json_string(cli_angle_unit(a->light.degrees)));
    root = cli_put(root, "method", json_string(closed ? "closed-form" : sh_rule_name(a->rule)));
    root = cli_put(root, "samples", json_integer(closed ? 0 : S));
    root = cli_put(root, "seed", json_integer((json_int_t)a->s.seed));
    root = cli_put(root, "coeffs", cli_json_array(c, (size_t)n));
    free(c);
    return cli_emit(root, (cli_format)a->fmt);
}

/* An EXR environment: every channel of the image. */
static int run_exr(const project_args *a)
{
    const int order = a->order, threads = a->run.threads;
    sh_image img;
    int fallback = 0;
    if (cli_input("EXR image", a->exr)) return CLI_EXIT_USAGE;
    int st = sh_exr_read(a->exr, &img, &fallback);
    if (st) return cli_fail_status(st);
    if (sh_image_check_order(&img, a->layout, order)) {
        sh_image_free(&img);
        return cli_fail("project: %s", sh_last_error());
    }
    const int n = sh_ncoeff(order);
    char what[96];
    snprintf(what, sizeof what, "order %d of a %d×%d image", order, img.width, img.height);
    if (check_memory(order, img.height, img.width, img.nchan, threads, what)) {
        sh_image_free(&img);
        return CLI_EXIT_USAGE;
    }
    double *c = malloc(sizeof(double) * (size_t)n * img.nchan);
    if (!c) { sh_image_free(&img); return cli_fail("out of memory"); }
    cli_progress prog;
    cli_progress_start(&prog, "project", a->run.quiet);
    const sh_run_opts opts = {threads, cli_progress_step_est, &prog};
    st = sh_project_image_ex(&img, a->layout, order, a->conv, &opts, c);
    if (st) { free(c); sh_image_free(&img); return cli_fail_status(st); }
    json_t *ch = json_object();
    for (int k = 0; k < img.nchan && ch; k++)
        ch = cli_put(ch, img.names[k], cli_json_array(c + (size_t)k * n, (size_t)n));
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(a->conv)));
    root = cli_put(root, "layout", json_string(a->layout == SH_LAYOUT_LATLONG ? "latlong" : "probe"));
    root = cli_put(root, "width", json_integer(img.width));
    root = cli_put(root, "height", json_integer(img.height));
    root = cli_put(root, "fallback", json_boolean(fallback));
    root = cli_put(root, "channels", ch);
    free(c);
    sh_image_free(&img);
    return cli_emit(root, (cli_format)a->fmt);
}

/* --order, one input, and the options of the other input refused. */
static int validate(const project_args *a, const cli_parsed *seen)
{
    if (!cli_given(seen, "order")) return cli_fail("project: --order is required");
    if (a->light.spec && a->exr) return cli_fail("project: give --light or --exr, not both");
    if (!a->light.spec && !a->exr) return cli_fail("project: give --light SPEC or --exr FILE");
    if (a->exr) {
        if (cli_applies("project", cli_given(seen, "method"), "--method", 0, "--light") ||
            cli_applies("project", cli_given(seen, "samples"), "--samples", 0, "--light") ||
            cli_applies("project", cli_given(seen, "seed"), "--seed", 0, "--light") ||
            cli_applies("project", a->light.degrees, "--degrees", 0, "--light"))
            return CLI_EXIT_USAGE;
        return 0;
    }
    return cli_applies("project", cli_given(seen, "layout"), "--layout", 0, "--exr");
}

/* The light, whether its closed form is used (*closed), and the rule's sample
 * count within its cap. */
static int light_setup(const project_args *a, const cli_parsed *seen, sh_light *L, int *closed)
{
    const int have_method = cli_given(seen, "method");
    if (cli_light_read("project", &a->light, L)) return CLI_EXIT_USAGE;
    *closed = !have_method && sh_light_has_closed_form(L);
    if ((cli_given(seen, "samples") || cli_given(seen, "seed")) && *closed)
        return cli_fail("project: --samples/--seed need --method (light '%s' uses its closed form)", a->light.spec);
    const long cap = a->rule == SH_RULE_QUAD ? MAX_QUAD_NODES : MAX_SAMPLES;
    if (a->s.samples > cap)
        return cli_fail("--samples %ld is too large for %s (at most %ld)", a->s.samples, sh_rule_name(a->rule), cap);
    return 0;
}

static int run(int argc, char **argv)
{
    project_args a = {.rule = SH_RULE_QUAD};
    cli_parsed seen;
    int rc = cli_args_parse(&project_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    if (a.exr) return run_exr(&a);
    sh_light L;
    int closed = 0;
    if ((rc = light_setup(&a, &seen, &L, &closed))) return rc;
    return run_light(&a, &L, closed);
}

const cli_command cmd_project = {"project", run, "project a light or an EXR environment onto SH", &project_decl};
