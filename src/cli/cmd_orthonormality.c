/* cmd_orthonormality.c — `shlab orthonormality`: check that a projection
 * rule's nodes integrate the products of the basis functions, i.e. that its
 * Gram matrix is the identity (sh_rule_gram_error, the routine
 * experiments/orthonormality uses too). */
#include "cli.h"
#include "cli_image_opts.h"

#include <math.h>
#include <stdlib.h>

/* Work is about order⁴/2 · nodes multiply-adds: keep a request to minutes. */
#define ORTHO_MAX_NODES 2000000L
#define ORTHO_DEFAULT_SAMPLES 10000L

typedef struct {
    int order, conv, quiet, fmt;
    sh_rule rule;
    double tol;
    cli_sampling_args s;
} ortho_args;

static const cli_opt ortho_opts[] = {
    CLI_ORDER(ortho_args, order, SH_GRAM_MAX_ORDER, "the Gram matrix has order⁴/2 entries", "bands 0..N-1"),
    CLI_CUSTOM(ortho_args, rule, "rule", "R", cli_parse_rule, "quad",
               "quad (default) | mc | random | qmc, the rules of\n"
               "shlab project --method: quad = S Gauss-Legendre θ\n"
               "nodes × 2S uniform φ nodes (exact for S >= N),\n"
               "mc = Green's stratified Monte Carlo (S rounded to a\n"
               "square), random, qmc = shifted Sobol points"),
    CLI_GROUP(ortho_args, s, cli_sampling_opts),
    CLI_REAL(ortho_args, tol, "tolerance", "E", 0, INFINITY, CLI_LO_OPEN, "1e-12",
             "largest |G − I| accepted at order N (default 1e-12)"),
    CLI_CONVENTION(ortho_args, conv),
    CLI_FLAG(ortho_args, quiet, "quiet", "no progress on stderr"),
    CLI_FORMAT(ortho_args, fmt),
    CLI_END,
};

static const cli_cmd ortho_decl = {
    .name = "orthonormality",
    .usage = "orthonormality --order N [--rule R] [--samples S] [OPTIONS]",
    .about = "Check the orthonormality of the real SH basis under a projection rule: the\n"
             "Gram matrix G_ij = Σ_k w_k y_i(s_k) y_j(s_k) of the rule's nodes s_k and\n"
             "weights w_k should be the identity (∫ y_i y_j dΩ = δ_ij).  For each order\n"
             "n = 1..N the largest |G_ij − δ_ij| over the n² functions is printed; the\n"
             "check passes when it stays <= --tolerance at order N.  A rule that is not\n"
             "orthonormal mixes coefficients when it projects (shlab project --method).\n",
    .opts = ortho_opts,
    .notes = "--samples: quad N θ nodes by default (the smallest exact rule), the others\n"
             "10000 samples; at most 2e6 nodes.  The error is the same in both conventions.\n"
             "\n"
             "JSON: {\"order\",\"convention\",\"rule\",\"samples\",\"seed\",\"nodes\",\"tolerance\",\n"
             "       \"max_error\" (at order N),\"orthonormal\",\"exact_to_order\" (largest n whose\n"
             "       error is <= E, 0 if none),\"rows\":[{\"order\",\"max_error\"}]}\n"
             "Exit 0 when orthonormal to E at order N, 1 when not (the result printed).\n",
};

/* --order, the default sample count, and the rule's size against ORTHO_MAX_NODES. */
static int validate(ortho_args *a, const cli_parsed *seen)
{
    if (!cli_given(seen, "order")) return cli_fail("orthonormality: --order is required");
    if (!a->s.samples) a->s.samples = a->rule == SH_RULE_QUAD ? a->order : ORTHO_DEFAULT_SAMPLES;
    const long used = sh_rule_samples_used(a->rule, a->s.samples);
    const double nodes_est = a->rule == SH_RULE_QUAD ? 2.0 * (double)used * (double)used : (double)used;
    if (nodes_est > ORTHO_MAX_NODES)
        return cli_fail("orthonormality: %.0f nodes is more than %ld (--samples %ld, rule %s)", nodes_est,
                        ORTHO_MAX_NODES, a->s.samples, sh_rule_name(a->rule));
    return 0;
}

/* The result from the errors err[n-1] at each order n = 1..N. */
static json_t *build_result(const ortho_args *a, const double *err, long nodes)
{
    const int order = a->order;
    int exact_to = 0;
    while (exact_to < order && err[exact_to] <= a->tol) exact_to++;
    json_t *rows = json_array();
    for (int n = 0; n < order && rows; n++) {
        json_t *r = json_object();
        r = cli_put(r, "order", json_integer(n + 1));
        r = cli_put(r, "max_error", json_real(err[n]));
        if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; }
    }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(a->conv)));
    root = cli_put(root, "rule", json_string(sh_rule_name(a->rule)));
    root = cli_put(root, "samples", json_integer(sh_rule_samples_used(a->rule, a->s.samples)));
    root = cli_put(root, "seed", json_integer(a->s.seed));
    root = cli_put(root, "nodes", json_integer(nodes));
    root = cli_put(root, "tolerance", json_real(a->tol));
    root = cli_put(root, "max_error", json_real(err[order - 1]));
    root = cli_put(root, "orthonormal", json_boolean(err[order - 1] <= a->tol));
    root = cli_put(root, "exact_to_order", json_integer(exact_to));
    return cli_put(root, "rows", rows);
}

static int run(int argc, char **argv)
{
    ortho_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&ortho_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    double *err = malloc((size_t)a.order * sizeof *err);
    if (!err) return cli_fail("out of memory");
    long nodes = 0;
    cli_progress prog;
    cli_progress_start(&prog, "orthonormality", a.quiet);
    const int st = sh_rule_gram_error(a.rule, a.s.samples, (unsigned long)a.s.seed, a.order, a.conv, err, &nodes,
                                      cli_progress_step, &prog);
    if (st) { free(err); return cli_fail_status(st); }
    const int ok = err[a.order - 1] <= a.tol;
    json_t *root = build_result(&a, err, nodes);
    free(err);
    rc = cli_emit(root, (cli_format)a.fmt);
    return rc == CLI_EXIT_OK && !ok ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_orthonormality = {"orthonormality", run,
                                        "check the basis' orthonormality under a projection rule (Gram matrix)", &ortho_decl};
