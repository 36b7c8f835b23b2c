/* cmd_convert.c — `shlab convert`: coefficient vectors between conventions:
 * the historical names cs, nocs, 4pi, schmidt (sh_convert, unchanged) and
 * any convention spec (sh_conv_convert, shlab/convention.h). */
#include "cli.h"
#include "cli_image_opts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A --from/--to value: the spec as given and its descriptor. */
typedef struct {
    const char *text;
    sh_conv conv;
    int legacy; /* one of cs, nocs, 4pi, schmidt: norm below */
    sh_norm norm;
} conv_arg;

typedef struct {
    conv_arg from, to;
    int fmt;
    cli_coeffs_args c;
} convert_args;

static int parse_conv(const char *opt, const char *s, void *field)
{
    conv_arg *c = field;
    c->text = s;
    c->legacy = sh_norm_parse(s, &c->norm) == SH_OK;
    return sh_conv_parse(s, &c->conv) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

static const cli_opt convert_opts[] = {
    CLI_CUSTOM(convert_args, from, "from", "SPEC", parse_conv, NULL, "the input's convention: cs, nocs, 4pi, schmidt or a spec"),
    CLI_CUSTOM(convert_args, to, "to", "SPEC", parse_conv, NULL, "the output's convention"),
    CLI_GROUP(convert_args, c, cli_coeffs_opts),
    CLI_FORMAT(convert_args, fmt),
    CLI_END,
};

static const cli_cmd convert_decl = {
    .name = "convert",
    .usage = "convert --from SPEC --to SPEC (--coeffs C0,C1,... | --in FILE) [OPTIONS]",
    .about = "Convert a coefficient vector (n² numbers, i = l(l+1)+m) between normalisations:\n"
             "  cs       orthonormal real SH with the Condon-Shortley phase (shlab's default)\n"
             "  nocs     orthonormal, without the phase (odd-m functions negated)\n"
             "  4pi      4π-normalised, without the phase (SHTOOLS' default 'real4pi')\n"
             "  schmidt  Schmidt semi-normalised, without the phase\n"
             "  or a spec: comma-separated tokens, each field at most once, the rest shlab's:\n"
             "  real|complex|complex-half, cs|nocs, ortho|4pi|schmidt|sn3d|n3d|fuma,\n"
             "  acn|mdesc|cossin|fuma-order, neg-sin|neg-cos, z-up|y-up|y-up-lh|+x+z-y...;\n"
             "  presets ambix, fuma, healpix (docs/CONVENTIONS.md \"Other conventions\").\n"
             "  Complex vectors are re,im pairs: 2n² numbers (complex), n(n+1) (complex-half).\n"
             "Coefficients transform inversely to the basis: the represented function is kept\n"
             "(of complex coefficients, its real part).  `shlab identify` names a convention.\n",
    .opts = convert_opts,
    .notes = "JSON: {\"order\",\"convention\",\"from\",\"to\",\"coeffs\":[...]}\n"
             "(or \"channels\":{...} when the input had channels; \"convention\" is the output's)\n",
};

/* The result: one vector as "coeffs", channels by name. */
static json_t *build_result(const convert_args *a, int order, const double *c, int n, int nchan,
                            char names[SH_IMAGE_MAX_CHANNELS][8])
{
    /* "convention" names the output's convention in full, as "to" does (it once
       gave only the phase, so a Schmidt output read "nocs") */
    char f[96], t[96];
    if (!a->from.legacy) sh_conv_format(&a->from.conv, f, sizeof f);
    if (!a->to.legacy) sh_conv_format(&a->to.conv, t, sizeof t);
    const char *to = a->to.legacy ? sh_norm_name(a->to.norm) : t;
    json_t *root = json_pack("{s:i,s:s,s:s,s:s}", "order", order, "convention", to,
                             "from", a->from.legacy ? sh_norm_name(a->from.norm) : f, "to", to);
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
    int order = 0;
    if (a.from.legacy) {
        order = (int)lround(sqrt((double)n));
        if (order * order != n) { free(c); return cli_fail("convert: %d coefficients is not a perfect square n²", n); }
    } else if (sh_conv_order_of(&a.from.conv, (size_t)n, &order)) {
        free(c);
        return cli_fail("convert: --from %s: %s", a.from.text, sh_last_error());
    }
    if (sh_conv_check(&a.from.conv, order) || sh_conv_check(&a.to.conv, order)) { free(c); return cli_fail("convert: %s", sh_last_error()); }
    const int nout = (int)sh_conv_ndoubles(&a.to.conv, order);
    double *out = malloc(sizeof(double) * ((size_t)nout * nchan + 1));
    if (!out) { free(c); return cli_fail("out of memory"); }
    int st = SH_OK;
    for (int k = 0; k < nchan && !st; k++) {
        if (a.from.legacy && a.to.legacy) {
            memcpy(out + (size_t)k * nout, c + (size_t)k * n, sizeof(double) * n);
            st = sh_convert(order, a.from.norm, a.to.norm, out + (size_t)k * nout);
        } else {
            st = sh_conv_convert(&a.from.conv, &a.to.conv, order, c + (size_t)k * n, out + (size_t)k * nout);
        }
    }
    free(c);
    if (st) { free(out); return cli_fail_status(st); }
    json_t *root = build_result(&a, order, out, nout, nchan, names);
    free(out);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_convert = {"convert", run, "convert coefficients between conventions (cs, nocs, 4pi, schmidt, any spec)", &convert_decl};
