/* cmd_triple.c — `shlab triple`: the triple-product transfer matrix of Green
 * (2003) eq. 8, M_ij = ∫ b(s) y_i(s) y_j(s) ds = Σ_k b_k G(i,j,k), for an
 * analytic light b. */
#include "cli.h"
#include "cli_image_opts.h"

#include <stdlib.h>

/* The matrix has N⁴ entries; beyond this the output stops being useful. */
#define TRIPLE_MAX_ORDER 32
/* θ nodes (× 2·nodes φ) for lights without a closed-form projection. */
#define TRIPLE_LIGHT_NODES 1000L

typedef struct {
    int order, conv, fmt;
    cli_light_args light;
} triple_args;

static const cli_opt triple_opts[] = {
    CLI_ORDER(triple_args, order, TRIPLE_MAX_ORDER, CLI_WHY_PRINTED_MATRIX, "number of bands of M"),
    CLI_GROUP(triple_args, light, cli_light_opts),
    CLI_CONVENTION(triple_args, conv),
    CLI_FORMAT(triple_args, fmt),
    CLI_END,
};

static const cli_cmd triple_decl = {
    .name = "triple",
    .usage = "triple --order N --light SPEC [OPTIONS]",
    .about = "Triple-product transfer matrix (Green 2003, eq. 8)\n"
             "  M_ij = ∫ b(s) y_i(s) y_j(s) ds = Σ_k b_k G(i,j,k),  i, j < N²,\n"
             "where G are the real Gaunt coefficients (from Wigner 3j symbols) and b_k\n"
             "the light's coefficients up to band 2N-2 (higher bands cannot contribute).\n"
             "M maps the coefficients of a light a to those of the product a·b.\n"
             "b comes from the light's closed form (cap, const, lobe), otherwise from a\n"
             "Gauss-Legendre × uniform-φ projection with 1000 θ nodes.\n",
    .opts = triple_opts,
    .notes = "JSON: {\"order\",\"convention\",\"light\",[\"unit\" (SPEC with angles)],\"method\":\"gaunt\",\n"
             "       \"light_method\":\"closed-form\"|\"quad\",\"light_order\":2N-1,\n"
             "       \"matrix\":[[N² numbers] × N²]}\n",
};

/* M (malloc'd, N²×N²) from the light's coefficients b up to band 2N-2, and
 * how b was found; NULL after the error line. */
static double *triple_matrix(const triple_args *a, sh_light *L, const char **lmethod)
{
    const int border = 2 * a->order - 1, n = sh_ncoeff(a->order);
    double *b = malloc(sizeof(double) * (size_t)sh_ncoeff(border));
    double *M = malloc(sizeof(double) * (size_t)n * n);
    if (!b || !M) {
        free(b);
        free(M);
        cli_fail("out of memory");
        return NULL;
    }
    int st;
    if (sh_light_has_closed_form(L)) {
        st = sh_light_closed_form(L, border, a->conv, b);
        *lmethod = "closed-form";
    } else {
        st = sh_project(border, a->conv, sh_light_fn, L, SH_RULE_QUAD, TRIPLE_LIGHT_NODES, 0, b);
        *lmethod = sh_rule_name(SH_RULE_QUAD);
    }
    if (!st) st = sh_triple_matrix(a->order, a->conv, b, border, M);
    free(b);
    if (st) {
        free(M);
        cli_fail_status(st);
        return NULL;
    }
    return M;
}

static int run(int argc, char **argv)
{
    triple_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&triple_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!cli_given(&seen, "order")) return cli_fail("triple: --order is required");
    if (!a.light.spec) return cli_fail("triple: --light is required");
    sh_light L;
    if ((rc = cli_light_read("triple", &a.light, &L))) return rc;
    const char *lmethod = NULL;
    double *M = triple_matrix(&a, &L, &lmethod);
    if (!M) return CLI_EXIT_USAGE;
    const int n = sh_ncoeff(a.order);
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(a.order));
    root = cli_put(root, "convention", json_string(sh_convention_name(a.conv)));
    root = cli_put(root, "light", json_string(a.light.spec));
    if (cli_light_has_angles(&L)) root = cli_put(root, "unit", json_string(cli_angle_unit(a.light.degrees)));
    root = cli_put(root, "method", json_string("gaunt"));
    root = cli_put(root, "light_method", json_string(lmethod));
    root = cli_put(root, "light_order", json_integer(2 * a.order - 1));
    root = cli_put(root, "matrix", cli_json_matrix(M, (size_t)n, (size_t)n));
    free(M);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_triple = {"triple", run, "triple-product transfer matrix of a light (Green eq. 8)", &triple_decl};
