/* cmd_orthonormality.c — `shlab orthonormality`: check that a projection
 * rule's nodes integrate the products of the basis functions, i.e. that its
 * Gram matrix is the identity (sh_rule_gram_error, the routine
 * experiments/orthonormality uses too). */
#include "cli.h"

#include <getopt.h>
#include <stdlib.h>

extern const cli_command cmd_orthonormality;

/* Work is about order⁴/2 · nodes multiply-adds: keep a request to minutes. */
#define ORTHO_MAX_NODES 2000000L
#define ORTHO_DEFAULT_SAMPLES 10000L

static const char help[] =
    "Usage: shlab orthonormality --order N [--rule R] [--samples S] [OPTIONS]\n"
    "\n"
    "Check the orthonormality of the real SH basis under a projection rule: the\n"
    "Gram matrix G_ij = Σ_k w_k y_i(s_k) y_j(s_k) of the rule's nodes s_k and\n"
    "weights w_k should be the identity (∫ y_i y_j dΩ = δ_ij).  For each order\n"
    "n = 1..N the largest |G_ij − δ_ij| over the n² functions is printed; the\n"
    "check passes when it stays <= --tolerance at order N.  A rule that is not\n"
    "orthonormal mixes coefficients when it projects (shlab project --method).\n"
    "\n"
    "  --order N            bands 0..N-1 (1..64; the Gram matrix has N⁴/2 entries)\n"
    "  --rule R             quad (default) | mc | random | qmc, the rules of\n"
    "                       shlab project --method: quad = S Gauss-Legendre θ\n"
    "                       nodes × 2S uniform φ nodes (exact for S >= N),\n"
    "                       mc = Green's stratified Monte Carlo (S rounded to a\n"
    "                       square), random, qmc = shifted Sobol points\n"
    "  --samples S          quad: θ nodes (default N, the smallest exact rule);\n"
    "                       others: sample count (default 10000); at most 2e6 nodes\n"
    "  --seed K             seed of the sampling rules (default 1)\n"
    "  --tolerance E        largest |G − I| accepted at order N (default 1e-12)\n"
    "  --convention cs|nocs basis (the error is the same in both)\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"convention\",\"rule\",\"samples\",\"seed\",\"nodes\",\"tolerance\",\n"
    "       \"max_error\" (at order N),\"orthonormal\",\"exact_to_order\" (largest n whose\n"
    "       error is <= E, 0 if none),\"rows\":[{\"order\",\"max_error\"}]}\n"
    "Exit 0 when orthonormal to E at order N, 1 when not (the result printed).\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_CONVENTION,
                                         {"rule", required_argument, 0, 'r'},
                                         {"samples", required_argument, 0, 's'},
                                         {"seed", required_argument, 0, 'k'},
                                         {"tolerance", required_argument, 0, 'e'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = SH_GRAM_MAX_ORDER;
    com.max_order_why = "the Gram matrix has order⁴/2 entries";
    sh_rule rule = SH_RULE_QUAD;
    long samples = 0, seed = 1;
    double tol = 1e-12;
    int quiet = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'r':
            if (sh_rule_parse(optarg, &rule)) return cli_fail("--rule: %s", sh_last_error());
            break;
        case 's':
            if (cli_long("--samples", optarg, &samples)) return CLI_EXIT_USAGE;
            if (samples < 1) return cli_fail("--samples must be >= 1, got %ld", samples);
            break;
        case 'k':
            if (cli_long("--seed", optarg, &seed)) return CLI_EXIT_USAGE;
            if (seed < 0) return cli_fail("--seed must be >= 0, got %ld", seed);
            break;
        case 'e':
            if (cli_double("--tolerance", optarg, &tol)) return CLI_EXIT_USAGE;
            if (!(tol > 0)) return cli_fail("--tolerance: must be > 0");
            break;
        case 'q': quiet = 1; break;
        default: {
            const int e = cli_common_opt(&cmd_orthonormality, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    if (optind < argc) return cli_fail("orthonormality: unexpected argument '%s'", argv[optind]);
    const int order = com.order;
    if (!order) return cli_fail("orthonormality: --order is required");
    if (!samples) samples = rule == SH_RULE_QUAD ? order : ORTHO_DEFAULT_SAMPLES;
    const long used = sh_rule_samples_used(rule, samples);
    const double nodes_est = rule == SH_RULE_QUAD ? 2.0 * (double)used * (double)used : (double)used;
    if (nodes_est > ORTHO_MAX_NODES)
        return cli_fail("orthonormality: %.0f nodes is more than %ld (--samples %ld, rule %s)", nodes_est,
                        ORTHO_MAX_NODES, samples, sh_rule_name(rule));

    double *err = malloc((size_t)order * sizeof *err);
    if (!err) return cli_fail("out of memory");
    long nodes = 0;
    cli_progress prog;
    cli_progress_start(&prog, "orthonormality", quiet);
    int st = sh_rule_gram_error(rule, samples, (unsigned long)seed, order, com.conv, err, &nodes,
                                cli_progress_step, &prog);
    if (st) { free(err); return cli_fail_status(st); }
    int exact_to = 0;
    while (exact_to < order && err[exact_to] <= tol) exact_to++;
    const int ok = err[order - 1] <= tol;
    json_t *rows = json_array();
    for (int n = 0; n < order && rows; n++) {
        json_t *r = json_object();
        r = cli_put(r, "order", json_integer(n + 1));
        r = cli_put(r, "max_error", json_real(err[n]));
        if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; }
    }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "rule", json_string(sh_rule_name(rule)));
    root = cli_put(root, "samples", json_integer(used));
    root = cli_put(root, "seed", json_integer(seed));
    root = cli_put(root, "nodes", json_integer(nodes));
    root = cli_put(root, "tolerance", json_real(tol));
    root = cli_put(root, "max_error", json_real(err[order - 1]));
    root = cli_put(root, "orthonormal", json_boolean(ok));
    root = cli_put(root, "exact_to_order", json_integer(exact_to));
    root = cli_put(root, "rows", rows);
    free(err);
    const int rc = cli_emit(root, com.fmt);
    return rc == CLI_EXIT_OK && !ok ? CLI_EXIT_CHECK : rc;
}

const cli_command cmd_orthonormality = {"orthonormality", run,
                                        "check the basis' orthonormality under a projection rule (Gram matrix)",
                                        help, NULL};
