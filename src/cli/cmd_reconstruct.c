/* cmd_reconstruct.c — `shlab reconstruct`: (windowed) SH coefficients → a
 * lat-long float EXR, with the ringing of the first channel. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_reconstruct;

static const char help[] =
    "Usage: shlab reconstruct --order N (--coeffs C0,C1,... | --in FILE) --out F.exr\n"
    "                         [--width W] [--window KIND[:PARAM]] [OPTIONS]\n"
    "\n"
    "Reconstruct f = Σ σ_l c_i y_i on a W × W/2 lat-long grid (pixel centres,\n"
    "θ = π(j+½)/H, φ = 2π(i+½)/W) and write it as a float EXR (ZIP).  One\n"
    "coefficient vector gives a Y image; channel files give one EXR channel each.\n"
    "\n"
    "  --order N            bands 0..N-1 to use; may be less than the vector's\n"
    "                       order (the vector is truncated), not more\n"
    "  --coeffs LIST        n² numbers, comma or space separated\n"
    "  --in FILE            JSON {\"coeffs\":[...]} or {\"channels\":{\"R\":[...],...}}\n"
    "                       (1, 3 or 4 channels), or plain numbers\n"
    "  --out F.exr          output file (written to a temporary name, then renamed)\n"
    "  --width W            image width, 2..46340 (default 256); height is W/2\n"
    "  --window SPEC        none (default), gauss:S  σ_l = exp(-S·l(l+1)), S >= 0,\n"
    "                       hann[:W]  σ_l = ½(1+cos(πl/W)) for l < W else 0,\n"
    "                       lanczos[:W]  σ_l = sinc(l/W) for l < W else 0\n"
    "                       (W defaults to N)\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --threads N          threads (default 0: all cores); the image is the\n"
    "                       same for every N\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"convention\",\"window\",\"width\",\"height\",\"out\",\n"
    "       \"most_negative\",\"negative_energy_fraction\"}\n"
    "  (ringing of the first channel on the output grid, exact pixel solid\n"
    "  angles: the most negative value, 0 if none, and the fraction of ∫f²dΩ\n"
    "  where f < 0)\n";

/* the second transform (the ringing measure) in the progress lines */
static void ringing_step(void *ctx, int done, int total, const char *what)
{
    (void)what;
    cli_progress_step(ctx, done, total, "ring pairs of the ringing measure");
}

static int run(int argc, char **argv)
{
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"coeffs", required_argument, 0, 'k'},
        {"in", required_argument, 0, 'i'},
        {"out", required_argument, 0, 'o'},
        {"width", required_argument, 0, 'w'},
        {"window", required_argument, 0, 'W'},
        {"threads", required_argument, 0, 'T'},
        {"quiet", no_argument, 0, 'q'},
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    int width = 256, threads = 0, quiet = 0;
    cli_common com = CLI_COMMON_DEFAULTS;
    const char *coeff_arg = NULL, *in = NULL, *out = NULL, *win_arg = "none";
    sh_window win = {SH_WINDOW_NONE, 0.0};
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'k': coeff_arg = optarg; break;
        case 'i': in = optarg; break;
        case 'o': out = optarg; break;
        case 'w':
            if (cli_int("--width", optarg, &width)) return CLI_EXIT_USAGE;
            /* width × width/2 pixels must stay within SH_IMAGE_MAX_PIXELS */
            if (width < 2 || width > 46340)
                return cli_fail("--width: %d is out of range (2..46340)", width);
            break;
        case 'W':
            if (sh_window_parse(optarg, &win)) return cli_fail("--window: %s", sh_last_error());
            win_arg = optarg;
            break;
        case 'T':
            if (cli_int("--threads", optarg, &threads)) return CLI_EXIT_USAGE;
            if (threads < 0 || threads > 1024) return cli_fail("--threads must be in 0..1024, got %d", threads);
            break;
        case 'q': quiet = 1; break;
        default: {
            const int r = cli_common_opt(&cmd_reconstruct, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    int order = com.order;
    const sh_convention conv = com.conv;
    const cli_format fmt = com.fmt;
    if (optind < argc) return cli_fail("reconstruct: unexpected argument '%s'", argv[optind]);
    if (!order) return cli_fail("reconstruct: --order is required");
    if (!coeff_arg == !in) return cli_fail("reconstruct: give exactly one of --coeffs and --in");
    if (!out || !*out) return cli_fail("reconstruct: --out FILE is required");

    const char *tmp_out = NULL; /* written there, renamed onto `out` by cli_emit */
    if (cli_out_open("reconstruct", out, &tmp_out)) return CLI_EXIT_USAGE;

    double *v = NULL;
    int len = 0, nchan = 1;
    char names[SH_IMAGE_MAX_CHANNELS][8] = {"Y"};
    int have_names = 0;
    if (coeff_arg) {
        if (cli_doubles("--coeffs", coeff_arg, &v, &len)) return CLI_EXIT_USAGE;
    } else {
        /* the file may hold more bands than --order (truncated) */
        if (cli_read_coeffs_file(in, 0, &v, &len, &nchan, names)) return CLI_EXIT_USAGE;
        have_names = nchan > 1;
    }
    const int vorder = (int)lround(sqrt((double)len));
    if (vorder * vorder != len) {
        free(v);
        return cli_fail("reconstruct: %d coefficients per channel is not a square n²", len);
    }
    if (order > vorder) {
        free(v);
        return cli_fail("reconstruct: --order %d exceeds the order %d of the coefficients", order,
                        vorder);
    }
    if (nchan == 2) {
        free(v);
        return cli_fail("reconstruct: 2 channels are not supported (give 1, 3 or 4)");
    }
    /* truncate each channel to the first order² coefficients */
    const int nn = order * order;
    double *c = malloc(sizeof(double) * (size_t)nn * nchan);
    if (!c) { free(v); return cli_fail("out of memory"); }
    for (int ch = 0; ch < nchan; ch++) memcpy(c + (size_t)ch * nn, v + (size_t)ch * len, sizeof(double) * nn);
    free(v);

    /* the image, the plan of the transform (run twice: image, ringing) */
    const sh_grid g = {width / 2, width, NULL, NULL, 0.0};
    const double need = (double)width * (width / 2) * nchan * sizeof(float) +
                        (double)sh_sht_bytes(order, &g, nchan, threads);
    char what[96];
    snprintf(what, sizeof what, "a %d×%d reconstruction of order %d", width, width / 2, order);
    if (cli_mem_check("reconstruct", need, what)) { free(c); return CLI_EXIT_USAGE; }
    cli_progress prog;
    cli_progress_start(&prog, "reconstruct", quiet);
    const sh_run_opts iopts = {threads, cli_progress_step_est, &prog};
    sh_image img;
    int st = sh_reconstruct_latlong_ex(order, conv, c, nchan, &win, width, &iopts, &img);
    if (st) { free(c); return cli_fail_status(st); }
    if (have_names)
        for (int ch = 0; ch < nchan; ch++) memcpy(img.names[ch], names[ch], 8);
    double mn = 0.0, frac = 0.0;
    const sh_run_opts ropts = {threads, ringing_step, &prog};
    st = sh_ringing_ex(order, conv, c, &win, width, &ropts, &mn, &frac);
    free(c);
    if (st) { sh_image_free(&img); return cli_fail_status(st); }
    for (size_t p = 0; p < (size_t)img.width * img.height * img.nchan; p++)
        if (!isfinite(img.data[p])) {
            sh_image_free(&img);
            return cli_fail("reconstruct: the reconstruction is not finite in single precision");
        }

    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(conv)));
    root = cli_put(root, "window", json_string(win_arg));
    root = cli_put(root, "width", json_integer(img.width));
    root = cli_put(root, "height", json_integer(img.height));
    root = cli_put(root, "out", json_string(out));
    root = cli_put(root, "most_negative", json_real(mn));
    root = cli_put(root, "negative_energy_fraction", json_real(frac));
    if (!root || cli_json_bad(root)) {
        if (root) json_decref(root);
        sh_image_free(&img);
        return cli_fail("reconstruct: could not build the result");
    }
    /* write only once the result is known to be printable */
    st = sh_exr_write_progress(tmp_out, &img, cli_progress_step, &prog);
    sh_image_free(&img);
    if (st) { json_decref(root); return cli_fail("reconstruct: cannot write '%s' (%s)", out, sh_last_error()); }
    return cli_emit(root, fmt);
}

const cli_command cmd_reconstruct = {"reconstruct", run,
                                     "coefficients → lat-long EXR, with windowing and ringing", help, NULL};
