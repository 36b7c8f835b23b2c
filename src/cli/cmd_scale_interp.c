/* cmd_scale_interp.c — `shlab scale-interp`: the error of interpolating the
 * scaling matrix over k from sampled values (Wang et al. 2006, Sec. 2.2). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_scale_interp;
extern const cli_sweep_kind sweep_scale_interp;

#define INTERP_DEFAULT_DENSE 400

static const char help[] =
    "Usage: shlab scale-interp --order N --family F --samples S --spacing SP --kmin A --kmax B [OPTIONS]\n"
    "\n"
    "Interpolation of the SH scaling matrix over k (Wang et al. 2006, Sec. 2.2: 40\n"
    "samples of k in an exponential distribution, linear interpolation).  M(k) is\n"
    "tabulated at S values of k from A to B, every entry is interpolated in k, and\n"
    "the result is compared with M computed directly on a dense grid of k (same\n"
    "spacing, ends included).  Errors are absolute, over all entries with m_i = m_j.\n"
    "\n"
    "  --order N            number of bands (1..64)\n"
    "  --family F           linear | cone | midrange (see shlab scale --help)\n"
    "  --samples S          sampled values of k (>= 2; >= 3 for cubic)\n"
    "  --spacing SP         geometric (needs 0 < A) | uniform\n"
    "  --kmin A --kmax B    the k range, A < B, inside the family's valid range\n"
    "  --interp linear|cubic  linear (default) or GSL natural cubic spline\n"
    "  --dense D            points of the dense check grid (default 400)\n"
    "  --energy             energy-preserving scaling\n"
    "  --cone-angle T       cone family half-angle (default π/4)\n"
    "  --degrees            --cone-angle and the printed cone_angle in degrees\n"
    "  --convention cs|nocs tag only (the matrix does not depend on it)\n"
    "  --quiet              no progress on stderr (else a line a second after 1 s)\n"
    CLI_SHARD_HELP
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"family\",\"energy\",\"convention\",[\"cone_angle\",\"unit\" (cone\n"
    "       family)],\"samples\",\"spacing\",\"interp\",\n"
    "       \"kmin\",\"kmax\",\"dense\",\"max_error\",\"rms_error\",\"worst_k\"}\n";

/* the sweep: item d is point d of the dense k grid */
static json_t *finish(const json_t *params, json_t *rows)
{
    const size_t n = json_array_size(rows);
    sh_scale_interp_point *pts = malloc(sizeof *pts * (n ? n : 1));
    sh_scale_interp_result r;
    size_t i;
    json_t *row;
    json_array_foreach(rows, i, row) if (pts) {
        pts[i].k = json_real_value(json_object_get(row, "k"));
        pts[i].max_error = json_real_value(json_object_get(row, "max_error"));
        pts[i].sum_sq = json_real_value(json_object_get(row, "sum_sq"));
        pts[i].weight = json_real_value(json_object_get(row, "weight"));
    }
    const int st = pts && n ? sh_scale_interp_reduce(pts, (int)n, &r) : SH_ENOMEM;
    free(pts);
    json_decref(rows);
    if (st) return NULL;
    json_t *root = json_deep_copy(params);
    root = cli_put(root, "max_error", json_real(r.max_error));
    root = cli_put(root, "rms_error", json_real(r.rms_error));
    return cli_put(root, "worst_k", json_real(r.worst_k));
}

static const cli_sweep_field params_fields[] = {
    {"order", CLI_FIELD_INT, 0, 1, SH_SCALE_MAX_ORDER}, {"family", CLI_FIELD_STRING, 0, 0, 0},
    {"energy", CLI_FIELD_BOOL, 0, 0, 0},                {"convention", CLI_FIELD_STRING, 0, 0, 0},
    {"cone_angle", CLI_FIELD_REAL, 1, 0, 0},            {"unit", CLI_FIELD_STRING, 1, 0, 0},
    {"samples", CLI_FIELD_INT, 0, 0, 1LL << 31},       {"spacing", CLI_FIELD_STRING, 0, 0, 0},
    {"interp", CLI_FIELD_STRING, 0, 0, 0},              {"kmin", CLI_FIELD_REAL, 0, 0, 0},
    {"kmax", CLI_FIELD_REAL, 0, 0, 0},                  {"dense", CLI_FIELD_INT, 0, 2, 100000},
    {NULL, 0, 0, 0, 0}};
static const cli_sweep_field row_fields[] = {{"k", CLI_FIELD_REAL, 0, 0, 0}, {"max_error", CLI_FIELD_REAL, 0, 0, 0},
                                             {"sum_sq", CLI_FIELD_REAL, 0, 0, 0}, {"weight", CLI_FIELD_REAL, 0, 0, 0},
                                             {NULL, 0, 0, 0, 0}};

/* item d is point d of the dense grid, the library's sh_scale_grid_point */
static int check_row(const json_t *params, long nitems, long d, const json_t *row, char *why, size_t n)
{
    sh_scale_spacing sp;
    const long dense = (long)json_integer_value(json_object_get(params, "dense"));
    if (sh_scale_spacing_parse(json_string_value(json_object_get(params, "spacing")), &sp))
        return snprintf(why, n, "the parameters' spacing: %s", sh_last_error()), 1;
    if (nitems != dense) return snprintf(why, n, "the sweep has %ld items, its dense grid %ld points", nitems, dense), 1;
    const double want = sh_scale_grid_point(sp, json_real_value(json_object_get(params, "kmin")),
                                            json_real_value(json_object_get(params, "kmax")), (int)d, (int)dense);
    const double got = json_real_value(json_object_get(row, "k"));
    if (got != want) return snprintf(why, n, "k %.17g, but item %ld is the point k = %.17g", got, d, want), 1;
    return 0;
}

const cli_sweep_kind sweep_scale_interp = {"scale-interp", finish, NULL, NULL, params_fields, row_fields, check_row, 0};

static int run(int argc, char **argv)
{
    enum { O_FAMILY = 0x201, O_SAMPLES, O_SPACING, O_KMIN, O_KMAX, O_INTERP, O_DENSE, O_ENERGY, O_CONE, O_QUIET };
    sh_shard shard = SH_SHARD_ALL;
    int have_shard = 0;
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"family", required_argument, 0, O_FAMILY},
        {"samples", required_argument, 0, O_SAMPLES},
        {"spacing", required_argument, 0, O_SPACING},
        {"kmin", required_argument, 0, O_KMIN},
        {"kmax", required_argument, 0, O_KMAX},
        {"interp", required_argument, 0, O_INTERP},
        {"dense", required_argument, 0, O_DENSE},
        {"energy", no_argument, 0, O_ENERGY},
        {"cone-angle", required_argument, 0, O_CONE},
        {"quiet", no_argument, 0, O_QUIET},
        CLI_LONGOPT_SHARD,
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = SH_SCALE_MAX_ORDER;
    const char *family = NULL, *spacing = NULL, *interp = "linear";
    int samples = 0, dense = INTERP_DEFAULT_DENSE, have_min = 0, have_max = 0, have_cone = 0, quiet = 0;
    double kmin = 0, kmax = 0, cone = 0;
    sh_scaling s = {SH_SCALE_LINEAR, 1.0, 0.0, 0};
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case O_FAMILY: family = optarg; break;
        case O_SAMPLES: if (cli_int("--samples", optarg, &samples)) return CLI_EXIT_USAGE; break;
        case O_SPACING: spacing = optarg; break;
        case O_KMIN: if (cli_double("--kmin", optarg, &kmin)) return CLI_EXIT_USAGE; have_min = 1; break;
        case O_KMAX: if (cli_double("--kmax", optarg, &kmax)) return CLI_EXIT_USAGE; have_max = 1; break;
        case O_INTERP: interp = optarg; break;
        case O_DENSE: if (cli_int("--dense", optarg, &dense)) return CLI_EXIT_USAGE; break;
        case O_ENERGY: s.energy = 1; break;
        case O_QUIET: quiet = 1; break;
        case CLI_OPT_SHARD:
            if (cli_shard("--shard", optarg, &shard)) return CLI_EXIT_USAGE;
            have_shard = 1;
            break;
        case O_CONE: if (cli_double("--cone-angle", optarg, &cone)) return CLI_EXIT_USAGE; have_cone = 1; break;
        default: {
            const int r = cli_common_opt(&cmd_scale_interp, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    if (optind < argc) return cli_fail("scale-interp: unexpected argument '%s'", argv[optind]);
    const int order = com.order;
    if (!order) return cli_fail("scale-interp: --order is required");
    if (!family) return cli_fail("scale-interp: --family is required (linear, cone, midrange)");
    if (sh_scale_family_parse(family, &s.family)) return cli_fail("--family: %s", sh_last_error());
    if (!samples) return cli_fail("scale-interp: --samples is required");
    if (!spacing) return cli_fail("scale-interp: --spacing is required (geometric, uniform)");
    sh_scale_spacing sp;
    if (sh_scale_spacing_parse(spacing, &sp)) return cli_fail("--spacing: %s", sh_last_error());
    sh_scale_interp_kind ik;
    if (sh_scale_interp_parse(interp, &ik)) return cli_fail("--interp: %s", sh_last_error());
    if (!have_min || !have_max) return cli_fail("scale-interp: --kmin and --kmax are required");
    if (have_cone) {
        if (cli_applies("scale-interp", 1, "--cone-angle", s.family == SH_SCALE_CONE, "--family cone"))
            return CLI_EXIT_USAGE;
        s.cone_angle = com.degrees ? cone * M_PI / 180.0 : cone;
        if (!(s.cone_angle > 0.0 && s.cone_angle < M_PI))
            return cli_fail("--cone-angle: %g is outside (0, %s)", cone, com.degrees ? "180" : "pi");
    }
    /* everything the result depends on: the whole sweep, whichever shard runs */
    json_t *params = json_object();
    params = cli_put(params, "order", json_integer(order));
    params = cli_put(params, "family", json_string(sh_scale_family_name(s.family)));
    params = cli_put(params, "energy", json_boolean(s.energy));
    params = cli_put(params, "convention", json_string(sh_convention_name(com.conv)));
    if (s.family == SH_SCALE_CONE) {
        params = cli_put(params, "cone_angle",
                         json_real(cli_angle_out(s.cone_angle > 0 ? s.cone_angle : M_PI / 4.0, com.degrees)));
        params = cli_put(params, "unit", json_string(cli_angle_unit(com.degrees)));
    }
    params = cli_put(params, "samples", json_integer(samples));
    params = cli_put(params, "spacing", json_string(sh_scale_spacing_name(sp)));
    params = cli_put(params, "interp", json_string(sh_scale_interp_name(ik)));
    params = cli_put(params, "kmin", json_real(kmin));
    params = cli_put(params, "kmax", json_real(kmax));
    params = cli_put(params, "dense", json_integer(dense));
    if (dense < 2 || dense > 100000) {
        json_decref(params);
        return cli_fail("scale-interp: dense grid of %d points (2..100000)", dense);
    }
    sh_scale_interp_point *pts = malloc(sizeof *pts * (size_t)dense);
    if (!pts) { json_decref(params); return cli_fail("out of memory"); }
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_scale_interp, params, dense, have_shard ? &shard : NULL, com.fmt, quiet,
                    "points");
    /* progress from the library: every shard also tabulates all the samples */
    cli_progress prog;
    cli_progress_start(&prog, sw.label, quiet);
    sw.prog.quiet = 1;
    const int st = sh_scale_interp_points(order, &s, samples, sp, kmin, kmax, ik, dense,
                                          have_shard ? &shard : NULL, pts, cli_progress_step, &prog);
    if (st) { /* the library's message may already name the command */
        free(pts);
        cli_sweep_free(&sw);
        const char *why = sh_last_error();
        if (!why || !*why) why = sh_strerror(st);
        return cli_fail(strncmp(why, "scale-interp: ", 14) ? "scale-interp: %s" : "%s", why);
    }
    for (int d = 0; d < dense; d++) {
        if (!cli_sweep_owns(&sw, d)) continue;
        json_t *r = json_object();
        r = cli_put(r, "k", json_real(pts[d].k));
        r = cli_put(r, "max_error", json_real(pts[d].max_error));
        r = cli_put(r, "sum_sq", json_real(pts[d].sum_sq));
        r = cli_put(r, "weight", json_real(pts[d].weight));
        if (cli_sweep_add(&sw, d, r) == CLI_EXIT_USAGE) { free(pts); cli_sweep_free(&sw); return CLI_EXIT_USAGE; }
    }
    free(pts);
    return cli_sweep_end(&sw);
}
const cli_command cmd_scale_interp = {"scale-interp", run,
                                      "error of interpolating the scaling matrix over k (Wang Sec. 2.2)", help, NULL};
