/* cmd_project.c — `shlab project`: SH coefficients of an analytic light
 * (closed form or a projection rule) or of an EXR environment image. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>

extern const cli_command cmd_project;

static const char help[] =
    "Usage: shlab project --order N --light SPEC [--method quad|mc|random|qmc]\n"
    "                     [--samples S] [--seed K] [--degrees] [OPTIONS]\n"
    "       shlab project --order N --exr FILE [--layout latlong|probe] [OPTIONS]\n"
    "\n"
    "Project a spherical function onto the n² real SH of bands 0..N-1,\n"
    "c_i = ∫ f y_i dΩ.\n"
    "\n"
    "  --order N            number of bands (1..2049)\n"
    "  --light SPEC         an analytic light:\n"
    "                         green                Green (2003) Figure 7 two-lobe light\n"
    "                         cap:T                1 for θ < T (T in [0,π])\n"
    "                         cie-overcast         CIE overcast sky (1+2cosθ)/3\n"
    "                         cie-clear:TH,PH      CIE clear sky, sun at (TH,PH), TH in [0,π/2]\n"
    "                         cie-partly:TH,PH     CIE partly cloudy sky, sun at (TH,PH)\n"
    "                         const:V              constant V\n"
    "                         lobe:E               max(0,cosθ)^E, E >= 0\n"
    "                       cap, const and lobe use their closed forms unless\n"
    "                       --method is given; the others default to quad.\n"
    "  --method M           quad   Gauss-Legendre in cosθ (S nodes) × 2S uniform φ\n"
    "                       mc     Green's stratified jittered Monte Carlo (S → round(√S)²)\n"
    "                       random plain uniform Monte Carlo\n"
    "                       qmc    Sobol points, shifted by a seeded random vector\n"
    "  --samples S          quad: θ nodes (default 1500); others: sample count\n"
    "                       (default 10000)\n"
    "  --seed K             random seed (integer >= 0, default 1; qmc: 0 = no shift)\n"
    "  --degrees            angles in SPEC are in degrees\n"
    "  --exr FILE           an OpenEXR environment image (R,G,B or Y channels)\n"
    "  --layout L           latlong (default) or probe (Debevec angle map)\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --threads N          threads for quad and --exr latlong (default 0: all\n"
    "                       cores); the result is the same for every N\n"
    "  --quiet              no progress or estimate on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "quad and latlong run the fast transform: an FFT in φ per ring of latitude\n"
    "and the Legendre recurrence across pairs of rings (README \"High-band\n"
    "projection and synthesis\").  A long run prints its size before it starts,\n"
    "an estimate after the first chunk of rings, and progress once a second;\n"
    "a request whose memory (working memory and the printed result) exceeds\n"
    "what is available is refused before anything is allocated.\n"
    "\n"
    "JSON (light): {\"order\",\"convention\",\"light\",[\"unit\" of the angles in SPEC: cap,\n"
    "  cie-clear, cie-partly],\"method\",\"samples\",\"seed\",\"coeffs\":[n²]}\n"
    "  (\"method\" is \"closed-form\" when the closed form was used; \"samples\" is\n"
    "  the number actually used, 0 for closed forms)\n"
    "JSON (exr): {\"order\",\"convention\",\"layout\",\"width\",\"height\",\"fallback\",\n"
    "  \"channels\":{\"R\":[n²],\"G\":[n²],\"B\":[n²]}}\n";

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

static int run_light(int order, sh_convention conv, const char *spec, int degrees, int have_method,
                     sh_rule rule, long samples, unsigned long seed, int threads, int quiet,
                     cli_format fmt)
{
    sh_light L;
    if (sh_light_parse(spec, degrees, &L)) return cli_fail("--light: %s", sh_last_error());
    cli_light_warn("project", &L, degrees);
    const int n = sh_ncoeff(order);
    const int closed = !have_method && sh_light_has_closed_form(&L);
    const long S = sh_rule_samples_used(rule, samples);
    if (!closed && rule == SH_RULE_QUAD) {
        char what[96];
        snprintf(what, sizeof what, "order %d on %ld × %ld Gauss nodes", order, S, 2 * S);
        const int rc = check_memory(order, (int)S, (int)(2 * S), 1, threads, what);
        if (rc) return rc;
        /* about 50 ns a function value and 1 ns a Legendre step: say what is coming */
        const double t = 1e-7 * S * S + 1e-9 * 0.25 * order * (double)order * S;
        if (!quiet && t > 2.0)
            fprintf(stderr, "project: %s, %.3g function values; an estimate follows the first chunk\n",
                    what, 2.0 * S * S);
    } else if (cli_mem_check("project", (double)n * (8.0 + OUT_BYTES_PER_NUMBER), "the result")) {
        return CLI_EXIT_USAGE;
    }
    double *c = malloc(sizeof(double) * (size_t)n);
    if (!c) return cli_fail("out of memory");
    int st;
    const char *method;
    long used;
    if (closed) {
        st = sh_light_closed_form(&L, order, conv, c);
        method = "closed-form";
        used = 0;
    } else {
        cli_progress prog;
        cli_progress_start(&prog, "project", quiet);
        const sh_run_opts opts = {threads, cli_progress_step_est, &prog};
        st = sh_project_ex(order, conv, sh_light_fn, &L, rule, samples, seed, &opts, c);
        method = sh_rule_name(rule);
        used = S;
    }
    if (st) { free(c); return cli_fail_status(st); }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(conv)));
    root = cli_put(root, "light", json_string(spec));
    if (cli_light_has_angles(&L)) root = cli_put(root, "unit", json_string(cli_angle_unit(degrees)));
    root = cli_put(root, "method", json_string(method));
    root = cli_put(root, "samples", json_integer(used));
    root = cli_put(root, "seed", json_integer((json_int_t)seed));
    root = cli_put(root, "coeffs", cli_json_array(c, (size_t)n));
    free(c);
    return cli_emit(root, fmt);
}

static int run_exr(int order, sh_convention conv, const char *path, sh_layout layout, int threads,
                   int quiet, cli_format fmt)
{
    sh_image img;
    int fallback = 0;
    if (cli_input("EXR image", path)) return CLI_EXIT_USAGE;
    int st = sh_exr_read(path, &img, &fallback);
    if (st) return cli_fail_status(st);
    if (sh_image_check_order(&img, layout, order)) {
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
    cli_progress_start(&prog, "project", quiet);
    const sh_run_opts opts = {threads, cli_progress_step_est, &prog};
    st = sh_project_image_ex(&img, layout, order, conv, &opts, c);
    if (st) { free(c); sh_image_free(&img); return cli_fail_status(st); }
    json_t *ch = json_object();
    for (int k = 0; k < img.nchan && ch; k++)
        ch = cli_put(ch, img.names[k], cli_json_array(c + (size_t)k * n, (size_t)n));
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(conv)));
    root = cli_put(root, "layout", json_string(layout == SH_LAYOUT_LATLONG ? "latlong" : "probe"));
    root = cli_put(root, "width", json_integer(img.width));
    root = cli_put(root, "height", json_integer(img.height));
    root = cli_put(root, "fallback", json_boolean(fallback));
    root = cli_put(root, "channels", ch);
    free(c);
    sh_image_free(&img);
    return cli_emit(root, fmt);
}

static int run(int argc, char **argv)
{
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"light", required_argument, 0, 'L'},
        {"exr", required_argument, 0, 'x'},
        {"layout", required_argument, 0, 'y'},
        {"method", required_argument, 0, 'm'},
        {"samples", required_argument, 0, 's'},
        {"seed", required_argument, 0, 'k'},
        {"threads", required_argument, 0, 'T'},
        {"quiet", no_argument, 0, 'q'},
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    int have_method = 0, have_samples = 0, have_seed = 0, have_layout = 0;
    cli_common com = CLI_COMMON_DEFAULTS;
    const char *spec = NULL, *exr = NULL;
    sh_rule rule = SH_RULE_QUAD;
    sh_layout layout = SH_LAYOUT_LATLONG;
    long samples = 0, seed = 1;
    int threads = 0, quiet = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'L':
            if (spec) return cli_fail("project: --light given twice");
            spec = optarg;
            break;
        case 'x':
            if (exr) return cli_fail("project: --exr given twice");
            exr = optarg;
            break;
        case 'y':
            if (sh_layout_parse(optarg, &layout)) return cli_fail("--layout: %s", sh_last_error());
            have_layout = 1;
            break;
        case 'm':
            if (sh_rule_parse(optarg, &rule)) return cli_fail("--method: %s", sh_last_error());
            have_method = 1;
            break;
        case 's':
            if (cli_long("--samples", optarg, &samples)) return CLI_EXIT_USAGE;
            if (samples < 1) return cli_fail("--samples must be >= 1, got %ld", samples);
            have_samples = 1;
            break;
        case 'k':
            if (cli_long("--seed", optarg, &seed)) return CLI_EXIT_USAGE;
            if (seed < 0) return cli_fail("--seed must be >= 0, got %ld", seed);
            have_seed = 1;
            break;
        case 'T':
            if (cli_int("--threads", optarg, &threads)) return CLI_EXIT_USAGE;
            if (threads < 0 || threads > 1024) return cli_fail("--threads must be in 0..1024, got %d", threads);
            break;
        case 'q': quiet = 1; break;
        default: {
            const int r = cli_common_opt(&cmd_project, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    const int order = com.order, degrees = com.degrees;
    const sh_convention conv = com.conv;
    const cli_format fmt = com.fmt;
    if (optind < argc) return cli_fail("project: unexpected argument '%s'", argv[optind]);
    if (!order) return cli_fail("project: --order is required");
    if (spec && exr) return cli_fail("project: give --light or --exr, not both");
    if (!spec && !exr) return cli_fail("project: give --light SPEC or --exr FILE");
    if (exr) {
        if (cli_applies("project", have_method, "--method", 0, "--light") ||
            cli_applies("project", have_samples, "--samples", 0, "--light") ||
            cli_applies("project", have_seed, "--seed", 0, "--light") ||
            cli_applies("project", degrees, "--degrees", 0, "--light"))
            return CLI_EXIT_USAGE;
        return run_exr(order, conv, exr, layout, threads, quiet, fmt);
    }
    if (cli_applies("project", have_layout, "--layout", 0, "--exr")) return CLI_EXIT_USAGE;
    if ((have_samples || have_seed) && !have_method) {
        sh_light L;
        if (sh_light_parse(spec, degrees, &L)) return cli_fail("--light: %s", sh_last_error());
        if (sh_light_has_closed_form(&L))
            return cli_fail("project: --samples/--seed need --method (light '%s' uses its closed form)", spec);
    }
    const long cap = rule == SH_RULE_QUAD ? MAX_QUAD_NODES : MAX_SAMPLES;
    if (samples > cap) return cli_fail("--samples %ld is too large for %s (at most %ld)", samples,
                                       sh_rule_name(rule), cap);
    return run_light(order, conv, spec, degrees, have_method, rule, samples, (unsigned long)seed, threads,
                     quiet, fmt);
}

const cli_command cmd_project = {"project", run, "project a light or an EXR environment onto SH", help, NULL};
