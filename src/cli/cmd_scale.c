/* cmd_scale.c — `shlab scale`: the SH scaling matrix of Wang et al. (2006),
 * M_ij = ∫∫ y_i(θ,φ) y_j(τ(θ),φ) ψ(θ) dθ dφ, for one angular scaling family. */
#include "cli.h"
#include "cli_image_opts.h"

#include <math.h>
#include <stdlib.h>

/* The matrix has N⁴ entries; beyond this the output stops being useful. */
#define SCALE_PRINT_MAX_ORDER 32
/* --verify: the independent 2-D product rule (nodes × panels per piece) and
 * the agreement it must reach. */
#define SCALE_VERIFY_NODES 64
#define SCALE_VERIFY_PANELS 32
#define SCALE_VERIFY_MAX_ORDER 8
#define SCALE_VERIFY_TOL 1e-10

typedef struct {
    int order, verify, degrees, conv, fmt;
    double cone; /* --cone-angle as given (degrees with --degrees) */
    sh_scaling s;
} scale_args;

static int parse_family(const char *opt, const char *s, void *field)
{
    return sh_scale_family_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

static const cli_opt scale_opts[] = {
    CLI_ORDER(scale_args, order, SCALE_PRINT_MAX_ORDER, CLI_WHY_PRINTED_MATRIX, "number of bands"),
    CLI_CUSTOM(scale_args, s.family, "family", "F", parse_family, NULL, "linear | cone | midrange"),
    CLI_REAL(scale_args, s.k, "k", "K", 0, 0, 0, NULL, "the family's parameter"),
    CLI_FLAG(scale_args, s.energy, "energy", "energy-preserving ψ = sin τ·τ' (default plain ψ = sinθ)"),
    CLI_REAL(scale_args, cone, "cone-angle", "T", 0, 0, 0, NULL, "cone family half-angle θ0 in (0, π) (default π/4)"),
    CLI_DEGREES(scale_args, degrees, "--cone-angle and the printed cone_angle in degrees"),
    CLI_FLAG(scale_args, verify, "verify",
             "also compute M by an independent 2-D product rule\n"
             "(sh_eval, numerical φ; order <= 8) and exit 1 if any\n"
             "entry differs by more than 1e-10"),
    CLI_CONVENTION(scale_args, conv),
    CLI_FORMAT(scale_args, fmt),
    CLI_END,
};

static const cli_cmd scale_decl = {
    .name = "scale",
    .usage = "scale --order N --family F --k K [OPTIONS]",
    .about = "Spherical harmonics scaling matrix (Wang, Lin, Guo, Shum 2006, eq. 6)\n"
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
             "US patent 7,663,623; shlab implements it to verify and measure it.\n",
    .opts = scale_opts,
    .notes = "JSON: {\"order\",\"family\",\"k\",\"energy\",\"convention\",\"matrix\":[[N² numbers] × N²],\n"
             "       \"nonzeros\" (|M_ij| > 1e-12·max|M|),\"pattern_bound\":N(2N²+1)/3,\n"
             "       \"cone_angle\",\"unit\" (cone family),\"method\"[,\"verify_max_diff\"]}\n",
};

/* The required options, the cone angle in radians, the family's parameters,
 * and --verify's smaller limit of the order. */
static int validate(scale_args *a, const cli_parsed *seen)
{
    if (!cli_given(seen, "order")) return cli_fail("scale: --order is required");
    if (!cli_given(seen, "family")) return cli_fail("scale: --family is required (linear, cone, midrange)");
    if (!cli_given(seen, "k")) return cli_fail("scale: --k is required");
    if (cli_given(seen, "cone-angle")) {
        if (cli_applies("scale", 1, "--cone-angle", a->s.family == SH_SCALE_CONE, "--family cone"))
            return CLI_EXIT_USAGE;
        a->s.cone_angle = a->degrees ? a->cone * M_PI / 180.0 : a->cone;
        if (!(a->s.cone_angle > 0.0 && a->s.cone_angle < M_PI))
            return cli_fail("--cone-angle: %g is outside (0, %s)", a->cone, a->degrees ? "180" : "pi");
    }
    if (sh_scaling_check(&a->s)) return cli_fail("scale: %s", sh_last_error());
    if (a->verify && cli_order_check("--order", a->order, SCALE_VERIFY_MAX_ORDER, "with --verify: O(N⁶) per node"))
        return CLI_EXIT_USAGE;
    return 0;
}

/* --verify: the largest |M − Q| against the 2-D product rule Q (*vdiff);
 * 0 or the exit code after the error line. */
static int verify_matrix(const scale_args *a, const double *M, double *vdiff)
{
    const size_t nn = (size_t)sh_ncoeff(a->order) * sh_ncoeff(a->order);
    double *Q = malloc(sizeof(double) * nn);
    if (!Q) return cli_fail("out of memory");
    const int st = sh_scale_matrix_quad(a->order, a->conv, &a->s, SCALE_VERIFY_NODES, SCALE_VERIFY_PANELS, Q);
    *vdiff = 0.0;
    for (size_t q = 0; !st && q < nn; q++) *vdiff = fmax(*vdiff, fabs(M[q] - Q[q]));
    free(Q);
    return st ? cli_fail_status(st) : 0;
}

static json_t *build_result(const scale_args *a, const double *M, double vdiff)
{
    const int n = sh_ncoeff(a->order);
    const sh_scaling *s = &a->s;
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(a->order));
    root = cli_put(root, "family", json_string(sh_scale_family_name(s->family)));
    root = cli_put(root, "k", json_real(s->k));
    root = cli_put(root, "energy", json_boolean(s->energy));
    root = cli_put(root, "convention", json_string(sh_convention_name(a->conv)));
    if (s->family == SH_SCALE_CONE) {
        root = cli_put(root, "cone_angle",
                       json_real(cli_angle_out(s->cone_angle > 0 ? s->cone_angle : M_PI / 4.0, a->degrees)));
        root = cli_put(root, "unit", json_string(cli_angle_unit(a->degrees)));
    }
    root = cli_put(root, "method", json_string("analytic-phi+gauss-legendre"));
    root = cli_put(root, "nonzeros", json_integer(sh_scale_nonzeros(a->order, M, 1e-12)));
    root = cli_put(root, "pattern_bound", json_integer(sh_scale_pattern_bound(a->order)));
    if (a->verify) root = cli_put(root, "verify_max_diff", json_real(vdiff));
    return cli_put(root, "matrix", cli_json_matrix(M, (size_t)n, (size_t)n));
}

static int run(int argc, char **argv)
{
    scale_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&scale_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    const int n = sh_ncoeff(a.order);
    double *M = malloc(sizeof(double) * (size_t)n * n);
    if (!M) return cli_fail("out of memory");
    const int st = sh_scale_matrix(a.order, &a.s, M, NULL);
    if (st) { free(M); return cli_fail_status(st); }
    double vdiff = 0.0;
    if (a.verify && (rc = verify_matrix(&a, M, &vdiff))) { free(M); return rc; }
    json_t *root = build_result(&a, M, vdiff);
    free(M);
    rc = cli_emit(root, (cli_format)a.fmt);
    if (rc == CLI_EXIT_OK && a.verify && !(vdiff <= SCALE_VERIFY_TOL)) {
        fprintf(stderr, "shlab: scale: --verify: matrices differ by %.3g > %g\n", vdiff, SCALE_VERIFY_TOL);
        return CLI_EXIT_CHECK;
    }
    return rc;
}

const cli_command cmd_scale = {"scale", run, "SH scaling matrix of an angular scaling family (Wang 2006)", &scale_decl};
