/* cmd_scale_interp.c — `shlab scale-interp`: the error of interpolating the
 * scaling matrix over k from sampled values (Wang et al. 2006, Sec. 2.2). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_scale_interp;

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
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"family\",\"energy\",\"convention\",[\"cone_angle\",\"unit\" (cone\n"
    "       family)],\"samples\",\"spacing\",\"interp\",\n"
    "       \"kmin\",\"kmax\",\"dense\",\"max_error\",\"rms_error\",\"worst_k\"}\n";

static int run(int argc, char **argv)
{
    enum { O_FAMILY = 0x201, O_SAMPLES, O_SPACING, O_KMIN, O_KMAX, O_INTERP, O_DENSE, O_ENERGY, O_CONE, O_QUIET };
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
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
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
    if (order > SH_SCALE_MAX_ORDER) return cli_fail("scale-interp: --order %d is above %d", order, SH_SCALE_MAX_ORDER);
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
        if (s.family != SH_SCALE_CONE) return cli_fail("scale-interp: --cone-angle applies to --family cone only");
        s.cone_angle = com.degrees ? cone * M_PI / 180.0 : cone;
        if (!(s.cone_angle > 0.0 && s.cone_angle < M_PI))
            return cli_fail("--cone-angle: %g is outside (0, %s)", cone, com.degrees ? "180" : "pi");
    }
    sh_scale_interp_result r;
    cli_progress prog;
    cli_progress_start(&prog, "scale-interp", quiet);
    const int st = sh_scale_interp_error_progress(order, &s, samples, sp, kmin, kmax, ik, dense, &r,
                                                  cli_progress_step, &prog);
    if (st) { /* the library's message may already name the command */
        const char *why = sh_last_error();
        if (!why || !*why) why = sh_strerror(st);
        return cli_fail(strncmp(why, "scale-interp: ", 14) ? "scale-interp: %s" : "%s", why);
    }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "family", json_string(sh_scale_family_name(s.family)));
    root = cli_put(root, "energy", json_boolean(s.energy));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    if (s.family == SH_SCALE_CONE) {
        root = cli_put(root, "cone_angle", json_real(cli_angle_out(s.cone_angle > 0 ? s.cone_angle : M_PI / 4.0, com.degrees)));
        root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
    }
    root = cli_put(root, "samples", json_integer(samples));
    root = cli_put(root, "spacing", json_string(sh_scale_spacing_name(sp)));
    root = cli_put(root, "interp", json_string(sh_scale_interp_name(ik)));
    root = cli_put(root, "kmin", json_real(kmin));
    root = cli_put(root, "kmax", json_real(kmax));
    root = cli_put(root, "dense", json_integer(dense));
    root = cli_put(root, "max_error", json_real(r.max_error));
    root = cli_put(root, "rms_error", json_real(r.rms_error));
    root = cli_put(root, "worst_k", json_real(r.worst_k));
    return cli_emit(root, com.fmt);
}

const cli_command cmd_scale_interp = {"scale-interp", run,
                                      "error of interpolating the scaling matrix over k (Wang Sec. 2.2)", help};
