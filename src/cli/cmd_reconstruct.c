/* cmd_reconstruct.c — `shlab reconstruct`: (windowed) SH coefficients → a
 * lat-long float EXR, with the ringing of the first channel. */
#include "cli.h"
#include "cli_image_opts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The widest image: W × W/2 within 2³⁰ pixels, the image limit before it
 * became SH_IMAGE_MAX_PIXELS (2²⁶).  The reconstruction refuses more than
 * 11585 itself, after the memory check (tests/cli/test_sht.sh asks a width of
 * 40000 for the memory's refusal). */
#define RECONSTRUCT_MAX_WIDTH 46340

typedef struct {
    sh_window win;
    const char *spec; /* as given, for the result */
} window_arg;

typedef struct {
    int order, width, conv, fmt;
    cli_coeffs_args c;
    const char *out;
    window_arg window;
    cli_run_args run;
} reconstruct_args;

static int parse_window(const char *opt, const char *s, void *field)
{
    window_arg *w = field;
    if (sh_window_parse(s, &w->win)) return cli_fail("%s: %s", opt, sh_last_error());
    w->spec = s;
    return 0;
}

static const cli_opt reconstruct_opts[] = {
    CLI_ORDER(reconstruct_args, order, SHLAB_MAX_ORDER, NULL,
              "bands 0..N-1 to use; may be less than the vector's\norder (the vector is truncated), not more"),
    CLI_GROUP(reconstruct_args, c, cli_coeffs_opts),
    CLI_STRING(reconstruct_args, out, "out", "F.exr", "output file (written to a temporary name, then renamed)"),
    CLI_INT(reconstruct_args, width, "width", "W", 2, RECONSTRUCT_MAX_WIDTH, "256", "image width; height is W/2"),
    CLI_CUSTOM(reconstruct_args, window, "window", "SPEC", parse_window, "none",
               "none (default), gauss:S  σ_l = exp(-S·l(l+1)), S >= 0,\n"
               "hann[:W]  σ_l = ½(1+cos(πl/W)) for l < W else 0,\n"
               "lanczos[:W]  σ_l = sinc(l/W) for l < W else 0\n"
               "(W defaults to N)"),
    CLI_CONVENTION(reconstruct_args, conv),
    CLI_GROUP(reconstruct_args, run, cli_run_opts),
    CLI_FORMAT(reconstruct_args, fmt),
    CLI_END,
};

static const cli_cmd reconstruct_decl = {
    .name = "reconstruct",
    .usage = "reconstruct --order N (--coeffs C0,C1,... | --in FILE) --out F.exr\n"
             "                         [--width W] [--window KIND[:PARAM]] [OPTIONS]",
    .about = "Reconstruct f = Σ σ_l c_i y_i on a W × W/2 lat-long grid (pixel centres,\n"
             "θ = π(j+½)/H, φ = 2π(i+½)/W) and write it as a float EXR (ZIP).  One\n"
             "coefficient vector gives a Y image; channel files give one EXR channel each\n"
             "(1, 3 or 4 channels).\n",
    .opts = reconstruct_opts,
    .notes = "JSON: {\"order\",\"convention\",\"window\",\"width\",\"height\",\"out\",\n"
             "       \"most_negative\",\"negative_energy_fraction\"}\n"
             "  (ringing of the first channel on the output grid, exact pixel solid\n"
             "  angles: the most negative value, 0 if none, and the fraction of ∫f²dΩ\n"
             "  where f < 0)\n",
};

/* the second transform (the ringing measure) in the progress lines */
static void ringing_step(void *ctx, int done, int total, const char *what)
{
    (void)what;
    cli_progress_step(ctx, done, total, "ring pairs of the ringing measure");
}

/* The coefficients (malloc'd): nchan channels of order² each, truncated
 * from the vector's order; the channel names when a file named them. */
static int read_coeffs(const reconstruct_args *a, double **out, int *nchan, char names[SH_IMAGE_MAX_CHANNELS][8],
                       int *have_names)
{
    double *v = NULL;
    int len = 0;
    if (cli_coeffs_read(&a->c, &v, &len, nchan, names)) return CLI_EXIT_USAGE;
    *have_names = *nchan > 1;
    const int vorder = (int)lround(sqrt((double)len));
    if (vorder * vorder != len) {
        free(v);
        return cli_fail("reconstruct: %d coefficients per channel is not a square n²", len);
    }
    if (a->order > vorder) {
        free(v);
        return cli_fail("reconstruct: --order %d exceeds the order %d of the coefficients", a->order, vorder);
    }
    if (*nchan == 2) {
        free(v);
        return cli_fail("reconstruct: 2 channels are not supported (give 1, 3 or 4)");
    }
    /* truncate each channel to the first order² coefficients */
    const int nn = a->order * a->order;
    double *c = malloc(sizeof(double) * (size_t)nn * *nchan);
    if (!c) { free(v); return cli_fail("out of memory"); }
    for (int ch = 0; ch < *nchan; ch++) memcpy(c + (size_t)ch * nn, v + (size_t)ch * len, sizeof(double) * nn);
    free(v);
    *out = c;
    return 0;
}

/* The image and the ringing of its first channel (mn, frac), after the
 * memory check; 0 or the exit code after the error line. */
static int reconstruct(const reconstruct_args *a, const double *c, int nchan, cli_progress *prog, sh_image *img,
                       double *mn, double *frac)
{
    const int order = a->order, width = a->width, threads = a->run.threads;
    /* the image, the plan of the transform (run twice: image, ringing) */
    const sh_grid g = {width / 2, width, NULL, NULL, 0.0};
    const double need = (double)width * (width / 2) * nchan * sizeof(float) +
                        (double)sh_sht_bytes(order, &g, nchan, threads);
    char what[96];
    snprintf(what, sizeof what, "a %d×%d reconstruction of order %d", width, width / 2, order);
    if (cli_mem_check("reconstruct", need, what)) return CLI_EXIT_USAGE;
    cli_progress_start(prog, "reconstruct", a->run.quiet);
    const sh_run_opts iopts = {threads, cli_progress_step_est, prog};
    int st = sh_reconstruct_latlong_ex(order, a->conv, c, nchan, &a->window.win, width, &iopts, img);
    if (st) return cli_fail_status(st);
    const sh_run_opts ropts = {threads, ringing_step, prog};
    st = sh_ringing_ex(order, a->conv, c, &a->window.win, width, &ropts, mn, frac);
    if (st) { sh_image_free(img); return cli_fail_status(st); }
    for (size_t p = 0; p < (size_t)img->width * img->height * img->nchan; p++)
        if (!isfinite(img->data[p])) {
            sh_image_free(img);
            return cli_fail("reconstruct: the reconstruction is not finite in single precision");
        }
    return 0;
}

static json_t *build_result(const reconstruct_args *a, const sh_image *img, double mn, double frac)
{
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(a->order));
    root = cli_put(root, "convention", json_string(sh_convention_name(a->conv)));
    root = cli_put(root, "window", json_string(a->window.spec));
    root = cli_put(root, "width", json_integer(img->width));
    root = cli_put(root, "height", json_integer(img->height));
    root = cli_put(root, "out", json_string(a->out));
    root = cli_put(root, "most_negative", json_real(mn));
    root = cli_put(root, "negative_energy_fraction", json_real(frac));
    if (root && cli_json_bad(root)) { json_decref(root); root = NULL; }
    return root;
}

static int run(int argc, char **argv)
{
    reconstruct_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&reconstruct_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!cli_given(&seen, "order")) return cli_fail("reconstruct: --order is required");
    if ((rc = cli_coeffs_given("reconstruct", &a.c))) return rc;
    if (!a.out) return cli_fail("reconstruct: --out FILE is required");
    const char *tmp_out = NULL; /* written there, renamed onto a.out by cli_emit */
    if (cli_out_open("reconstruct", a.out, &tmp_out)) return CLI_EXIT_USAGE;
    double *c = NULL;
    int nchan = 1, have_names = 0;
    char names[SH_IMAGE_MAX_CHANNELS][8];
    if ((rc = read_coeffs(&a, &c, &nchan, names, &have_names))) return rc;
    cli_progress prog;
    sh_image img;
    double mn = 0.0, frac = 0.0;
    rc = reconstruct(&a, c, nchan, &prog, &img, &mn, &frac);
    free(c);
    if (rc) return rc;
    if (have_names)
        for (int ch = 0; ch < nchan; ch++) memcpy(img.names[ch], names[ch], 8);
    json_t *root = build_result(&a, &img, mn, frac);
    if (!root) { sh_image_free(&img); return cli_fail("reconstruct: could not build the result"); }
    /* write only once the result is known to be printable */
    const int st = sh_exr_write_progress(tmp_out, &img, cli_progress_step, &prog);
    sh_image_free(&img);
    if (st) { json_decref(root); return cli_fail("reconstruct: cannot write '%s' (%s)", a.out, sh_last_error()); }
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_reconstruct = {"reconstruct", run, "coefficients → lat-long EXR, with windowing and ringing", &reconstruct_decl};
