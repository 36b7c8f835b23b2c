/* cmd_triple.c — `shlab triple`: the triple-product transfer matrix of Green
 * (2003) eq. 8, M_ij = ∫ b(s) y_i(s) y_j(s) ds = Σ_k b_k G(i,j,k), for an
 * analytic light b. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>

extern const cli_command cmd_triple;

/* The matrix has N⁴ entries; beyond this the output stops being useful. */
#define TRIPLE_MAX_ORDER 32
/* θ nodes (× 2·nodes φ) for lights without a closed-form projection. */
#define TRIPLE_LIGHT_NODES 1000L

static const char help[] =
    "Usage: shlab triple --order N --light SPEC [OPTIONS]\n"
    "\n"
    "Triple-product transfer matrix (Green 2003, eq. 8)\n"
    "  M_ij = ∫ b(s) y_i(s) y_j(s) ds = Σ_k b_k G(i,j,k),  i, j < N²,\n"
    "where G are the real Gaunt coefficients (from Wigner 3j symbols) and b_k\n"
    "the light's coefficients up to band 2N-2 (higher bands cannot contribute).\n"
    "M maps the coefficients of a light a to those of the product a·b.\n"
    "b comes from the light's closed form (cap, const, lobe), otherwise from a\n"
    "Gauss-Legendre × uniform-φ projection with 1000 θ nodes.\n"
    "\n"
    "  --order N            number of bands of M (1..32)\n"
    "  --light SPEC         green | cap:T | cie-overcast | cie-clear:TH,PH |\n"
    "                       cie-partly:TH,PH | const:V | lobe:E (see shlab project)\n"
    "  --degrees            angles in SPEC are in degrees\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"convention\",\"light\",[\"unit\" (SPEC with angles)],\"method\":\"gaunt\",\n"
    "       \"light_method\":\"closed-form\"|\"quad\",\"light_order\":2N-1,\n"
    "       \"matrix\":[[N² numbers] × N²]}\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"light", required_argument, 0, 'L'},
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    const char *spec = NULL;
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = TRIPLE_MAX_ORDER;
    com.max_order_why = "a printed N²×N² matrix";
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'L':
            if (spec) return cli_fail("triple: --light given twice");
            spec = optarg;
            break;
        default: {
            const int r = cli_common_opt(&cmd_triple, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    const int order = com.order, degrees = com.degrees;
    const sh_convention conv = com.conv;
    const cli_format fmt = com.fmt;
    if (optind < argc) return cli_fail("triple: unexpected argument '%s'", argv[optind]);
    if (!order) return cli_fail("triple: --order is required");
    if (!spec) return cli_fail("triple: --light is required");
    sh_light L;
    if (sh_light_parse(spec, degrees, &L)) return cli_fail("--light: %s", sh_last_error());
    cli_light_warn("triple", &L, degrees);

    const int border = 2 * order - 1, n = sh_ncoeff(order);
    double *b = malloc(sizeof(double) * (size_t)sh_ncoeff(border));
    double *M = malloc(sizeof(double) * (size_t)n * n);
    if (!b || !M) { free(b); free(M); return cli_fail("out of memory"); }
    int st;
    const char *lmethod;
    if (sh_light_has_closed_form(&L)) {
        st = sh_light_closed_form(&L, border, conv, b);
        lmethod = "closed-form";
    } else {
        st = sh_project(border, conv, sh_light_fn, &L, SH_RULE_QUAD, TRIPLE_LIGHT_NODES, 0, b);
        lmethod = sh_rule_name(SH_RULE_QUAD);
    }
    if (!st) st = sh_triple_matrix(order, conv, b, border, M);
    free(b);
    if (st) { free(M); return cli_fail_status(st); }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(conv)));
    root = cli_put(root, "light", json_string(spec));
    if (cli_light_has_angles(&L)) root = cli_put(root, "unit", json_string(cli_angle_unit(degrees)));
    root = cli_put(root, "method", json_string("gaunt"));
    root = cli_put(root, "light_method", json_string(lmethod));
    root = cli_put(root, "light_order", json_integer(border));
    root = cli_put(root, "matrix", cli_json_matrix(M, (size_t)n, (size_t)n));
    free(M);
    return cli_emit(root, fmt);
}

const cli_command cmd_triple = {"triple", run, "triple-product transfer matrix of a light (Green eq. 8)",
                                help, NULL};
