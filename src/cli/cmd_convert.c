/* cmd_convert.c — `shlab convert`: coefficient vectors between conventions
 * and normalisations (cs, nocs, 4pi, schmidt). */
#include "cli.h"
#include "cli_image_opts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    sh_norm from, to;
    int fmt;
    cli_coeffs_args c;
} convert_args;

static int parse_norm(const char *opt, const char *s, void *field)
{
    return sh_norm_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

static const cli_opt convert_opts[] = {
    CLI_CUSTOM(convert_args, from, "from", "NORM", parse_norm, NULL, "the input's normalisation: cs, nocs, 4pi or schmidt"),
    CLI_CUSTOM(convert_args, to, "to", "NORM", parse_norm, NULL, "the output's normalisation"),
    CLI_GROUP(convert_args, c, cli_coeffs_opts),
    CLI_FORMAT(convert_args, fmt),
    CLI_END,
};

static const cli_cmd convert_decl = {
    .name = "convert",
    .usage = "convert --from NORM --to NORM (--coeffs C0,C1,... | --in FILE) [OPTIONS]",
    .about = "Convert a coefficient vector (n² numbers, i = l(l+1)+m) between normalisations:\n"
             "  cs       orthonormal real SH with the Condon-Shortley phase (shlab's default)\n"
             "  nocs     orthonormal, without the phase (odd-m functions negated)\n"
             "  4pi      4π-normalised, without the phase (SHTOOLS' default 'real4pi')\n"
             "  schmidt  Schmidt semi-normalised, without the phase\n"
             "Coefficients transform inversely to the basis: the represented function is kept.\n",
    .opts = convert_opts,
    .notes = "JSON: {\"order\",\"convention\",\"from\",\"to\",\"coeffs\":[...]}\n"
             "(or \"channels\":{...} when the input had channels; \"convention\" is the output's)\n",
};

/* The result: one vector as "coeffs", channels by name. */
static json_t *build_result(const convert_args *a, int order, const double *c, int n, int nchan,
                            char names[SH_IMAGE_MAX_CHANNELS][8])
{
    /* the output's phase convention: cs for cs, nocs for every phase-free form */
    json_t *root = json_pack("{s:i,s:s,s:s,s:s}", "order", order, "convention", a->to == SH_NORM_CS ? "cs" : "nocs",
                             "from", sh_norm_name(a->from), "to", sh_norm_name(a->to));
    if (nchan == 1 && !strcmp(names[0], "Y")) return cli_put(root, "coeffs", cli_json_array(c, n));
    json_t *ch = json_object();
    for (int k = 0; k < nchan && ch; k++) ch = cli_put(ch, names[k], cli_json_array(c + (size_t)k * n, n));
    return cli_put(root, "channels", ch);
}

static int run(int argc, char **argv)
{
    convert_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&convert_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!cli_given(&seen, "from") || !cli_given(&seen, "to")) return cli_fail("convert: --from and --to are required");
    if ((rc = cli_coeffs_given("convert", &a.c))) return rc;
    double *c = NULL;
    int n = 0, nchan = 1;
    char names[SH_IMAGE_MAX_CHANNELS][8];
    if ((rc = cli_coeffs_read(&a.c, &c, &n, &nchan, names))) return rc;
    const int order = (int)lround(sqrt((double)n));
    if (order * order != n) { free(c); return cli_fail("convert: %d coefficients is not a perfect square n²", n); }
    if (sh_check_order(order)) { free(c); return cli_fail_status(SH_EINVAL); }
    for (int k = 0; k < nchan; k++) sh_convert(order, a.from, a.to, c + (size_t)k * n);
    json_t *root = build_result(&a, order, c, n, nchan, names);
    free(c);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_convert = {"convert", run, "convert coefficients between cs, nocs, 4pi and schmidt", &convert_decl};
