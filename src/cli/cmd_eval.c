/* cmd_eval.c — `shlab eval`: all n² real SH at one direction. */
#include "cli.h"

#include <stdlib.h>

typedef struct {
    int order, degrees, conv, fmt;
    double dir[3], theta, phi;
} eval_args;

static int parse_dir(const char *opt, const char *s, void *field) { return cli_vec3(opt, s, field); }

static const cli_opt eval_opts[] = {
    CLI_ORDER(eval_args, order, SHLAB_MAX_ORDER, NULL, "number of bands"),
    CLI_CUSTOM(eval_args, dir, "dir", "X,Y,Z", parse_dir, NULL, "direction (normalised; must be finite and non-zero)"),
    CLI_REAL(eval_args, theta, "theta", "T", 0, 0, 0, NULL, "polar angle from +z (with --phi)"),
    CLI_REAL(eval_args, phi, "phi", "P", 0, 0, 0, NULL, "azimuth from +x (with --theta)"),
    CLI_DEGREES(eval_args, degrees, "--theta and --phi in degrees"),
    CLI_CONVENTION(eval_args, conv),
    CLI_FORMAT(eval_args, fmt),
    CLI_END,
};

static const cli_cmd eval_decl = {
    .name = "eval",
    .usage = "eval --order N (--dir X,Y,Z | --theta T --phi P) [OPTIONS]",
    .about = "Evaluate the n² real spherical harmonics y_i, i = l(l+1)+m, of bands 0..N-1\n"
             "at one direction.\n",
    .opts = eval_opts,
    .notes = "JSON: {\"order\",\"convention\",\"values\":[n² numbers]}\n",
};

/* --order, and the direction in one form; θ and φ in radians. */
static int validate(eval_args *a, const cli_parsed *seen)
{
    const int have_dir = cli_given(seen, "dir"), have_t = cli_given(seen, "theta"), have_p = cli_given(seen, "phi");
    if (!cli_given(seen, "order")) return cli_fail("eval: --order is required");
    if (have_dir && (have_t || have_p)) return cli_fail("eval: give --dir or --theta/--phi, not both");
    if (!have_dir && !(have_t && have_p)) return cli_fail("eval: give --dir X,Y,Z or both --theta and --phi");
    if (!have_dir) {
        a->theta = cli_angle_in("eval", "--theta", a->theta, a->degrees);
        a->phi = cli_angle_in("eval", "--phi", a->phi, a->degrees);
    }
    return 0;
}

static int run(int argc, char **argv)
{
    eval_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&eval_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    const int n = sh_ncoeff(a.order);
    double *y = malloc(sizeof(double) * n);
    if (!y) return cli_fail("out of memory");
    const int st = cli_given(&seen, "dir") ? sh_eval_dir(a.order, a.conv, a.dir, y)
                                           : sh_eval(a.order, a.conv, a.theta, a.phi, y);
    if (st) { free(y); return cli_fail_status(st); }
    json_t *root = json_pack("{s:i,s:s,s:o}", "order", a.order, "convention", sh_convention_name(a.conv), "values",
                             cli_json_array(y, (size_t)n));
    free(y);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_eval = {"eval", run, "evaluate the real SH basis at a direction", &eval_decl};
