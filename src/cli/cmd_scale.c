/* cmd_scale.c — `shlab scale`: the SH scaling matrix of Wang et al. (2006),
 * M_ij = ∫∫ y_i(θ,φ) y_j(τ(θ),φ) ψ(θ) dθ dφ, for one angular scaling family. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>

extern const cli_command cmd_scale;

/* The matrix has N⁴ entries; beyond this the output stops being useful. */
#define SCALE_PRINT_MAX_ORDER 32
/* --verify: the independent 2-D product rule (nodes × panels per piece) and
 * the agreement it must reach. */
#define SCALE_VERIFY_NODES 64
#define SCALE_VERIFY_PANELS 32
#define SCALE_VERIFY_MAX_ORDER 8
#define SCALE_VERIFY_TOL 1e-10

static const char help[] =
    "Usage: shlab scale --order N --family F --k K [OPTIONS]\n"
    "\n"
    "Spherical harmonics scaling matrix (Wang, Lin, Guo, Shum 2006, eq. 6)\n"
    "  M_ij = ∫∫ y_i(θ,φ) y_j(τ(θ),φ) ψ(θ) dθ dφ,   S_d = M S_r,\n"
    "with ψ = sinθ (plain: visibility) or ψ = sin τ(θ)·τ'(θ) (--energy:\n"
    "energy-preserving, ∫F dΩ kept).  Angular scaling families (docs/CONVENTIONS.md):\n"
    "  linear    τ = min(kθ, π),                              k = d/r in [0.001, 1000]\n"
    "  cone      cot τ = (cot θ + (1−k) cot θ0)/k  (cone occluder, half-angle θ0),\n"
    "                                                          k = d/r in [0.001, 1000]\n"
    "  midrange  τ = θ − arcsin(k sinθ)  (environment on a sphere of radius R,\n"
    "            point moved by d along +z),                  k = d/R in [−0.999, 0.999]\n"
    "The φ integral is analytic (only m_i = m_j survives: the matrix is the same\n"
    "in both conventions); the θ integral by composite Gauss-Legendre, panels\n"
    "doubled until two estimates agree to 1e-14.  This operation is the subject of\n"
    "US patent 7,663,623; shlab implements it to verify and measure it.\n"
    "\n"
    "  --order N            number of bands (1..32)\n"
    "  --family F           linear | cone | midrange\n"
    "  --k K                the family's parameter\n"
    "  --energy             energy-preserving ψ = sin τ·τ' (default plain ψ = sinθ)\n"
    "  --cone-angle T       cone family half-angle θ0 in (0, π) (default π/4)\n"
    "  --degrees            --cone-angle and the printed cone_angle in degrees\n"
    "  --verify             also compute M by an independent 2-D product rule\n"
    "                       (sh_eval, numerical φ; order <= 8) and exit 1 if any\n"
    "                       entry differs by more than 1e-10\n"
    "  --convention cs|nocs tag of the basis (M is the same in both)\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"family\",\"k\",\"energy\",\"convention\",\"matrix\":[[N² numbers] × N²],\n"
    "       \"nonzeros\" (|M_ij| > 1e-12·max|M|),\"pattern_bound\":N(2N²+1)/3,\n"
    "       \"cone_angle\",\"unit\" (cone family),\"method\"[,\"verify_max_diff\"]}\n";

static int run(int argc, char **argv)
{
    enum { O_FAMILY = 0x201, O_K, O_ENERGY, O_CONE, O_VERIFY };
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"family", required_argument, 0, O_FAMILY},
        {"k", required_argument, 0, O_K},
        {"energy", no_argument, 0, O_ENERGY},
        {"cone-angle", required_argument, 0, O_CONE},
        {"verify", no_argument, 0, O_VERIFY},
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = SCALE_PRINT_MAX_ORDER;
    com.max_order_why = "a printed N²×N² matrix";
    const char *family = NULL;
    int have_k = 0, have_cone = 0, verify = 0;
    sh_scaling s = {SH_SCALE_LINEAR, 0.0, 0.0, 0};
    double cone = 0.0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case O_FAMILY:
            if (family) return cli_fail("scale: --family given twice");
            family = optarg;
            break;
        case O_K:
            if (have_k) return cli_fail("scale: --k given twice");
            if (cli_double("--k", optarg, &s.k)) return CLI_EXIT_USAGE;
            have_k = 1;
            break;
        case O_ENERGY: s.energy = 1; break;
        case O_CONE:
            if (have_cone) return cli_fail("scale: --cone-angle given twice");
            if (cli_double("--cone-angle", optarg, &cone)) return CLI_EXIT_USAGE;
            have_cone = 1;
            break;
        case O_VERIFY: verify = 1; break;
        default: {
            const int r = cli_common_opt(&cmd_scale, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    if (optind < argc) return cli_fail("scale: unexpected argument '%s'", argv[optind]);
    const int order = com.order;
    if (!order) return cli_fail("scale: --order is required");
    if (!family) return cli_fail("scale: --family is required (linear, cone, midrange)");
    if (sh_scale_family_parse(family, &s.family)) return cli_fail("--family: %s", sh_last_error());
    if (!have_k) return cli_fail("scale: --k is required");
    if (have_cone) {
        if (cli_applies("scale", 1, "--cone-angle", s.family == SH_SCALE_CONE, "--family cone")) return CLI_EXIT_USAGE;
        s.cone_angle = com.degrees ? cone * M_PI / 180.0 : cone;
        if (!(s.cone_angle > 0.0 && s.cone_angle < M_PI))
            return cli_fail("--cone-angle: %g is outside (0, %s)", cone, com.degrees ? "180" : "pi");
    }
    if (sh_scaling_check(&s)) return cli_fail("scale: %s", sh_last_error());
    if (verify && cli_order_check("--order", order, SCALE_VERIFY_MAX_ORDER, "with --verify: O(N⁶) per node"))
        return CLI_EXIT_USAGE;

    const int n = sh_ncoeff(order);
    double *M = malloc(sizeof(double) * (size_t)n * n);
    if (!M) return cli_fail("out of memory");
    int st = sh_scale_matrix(order, &s, M, NULL);
    if (st) { free(M); return cli_fail_status(st); }
    double vdiff = 0.0;
    if (verify) {
        double *Q = malloc(sizeof(double) * (size_t)n * n);
        if (!Q) { free(M); return cli_fail("out of memory"); }
        st = sh_scale_matrix_quad(order, com.conv, &s, SCALE_VERIFY_NODES, SCALE_VERIFY_PANELS, Q);
        for (size_t q = 0; !st && q < (size_t)n * n; q++) vdiff = fmax(vdiff, fabs(M[q] - Q[q]));
        free(Q);
        if (st) { free(M); return cli_fail_status(st); }
    }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "family", json_string(sh_scale_family_name(s.family)));
    root = cli_put(root, "k", json_real(s.k));
    root = cli_put(root, "energy", json_boolean(s.energy));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    if (s.family == SH_SCALE_CONE) {
        root = cli_put(root, "cone_angle", json_real(cli_angle_out(s.cone_angle > 0 ? s.cone_angle : M_PI / 4.0, com.degrees)));
        root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
    }
    root = cli_put(root, "method", json_string("analytic-phi+gauss-legendre"));
    root = cli_put(root, "nonzeros", json_integer(sh_scale_nonzeros(order, M, 1e-12)));
    root = cli_put(root, "pattern_bound", json_integer(sh_scale_pattern_bound(order)));
    if (verify) root = cli_put(root, "verify_max_diff", json_real(vdiff));
    root = cli_put(root, "matrix", cli_json_matrix(M, (size_t)n, (size_t)n));
    free(M);
    const int rc = cli_emit(root, com.fmt);
    if (rc == CLI_EXIT_OK && verify && !(vdiff <= SCALE_VERIFY_TOL)) {
        fprintf(stderr, "shlab: scale: --verify: matrices differ by %.3g > %g\n", vdiff, SCALE_VERIFY_TOL);
        return CLI_EXIT_CHECK;
    }
    return rc;
}

const cli_command cmd_scale = {"scale", run, "SH scaling matrix of an angular scaling family (Wang 2006)", help, NULL};
