/* cmd_convert.c — `shlab convert`: coefficient vectors between conventions
 * and normalisations (cs, nocs, 4pi, schmidt). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_convert;

static const char help[] =
    "Usage: shlab convert --from NORM --to NORM (--coeffs C0,C1,... | --in FILE) [OPTIONS]\n"
    "\n"
    "Convert a coefficient vector (n² numbers, i = l(l+1)+m) between normalisations:\n"
    "  cs       orthonormal real SH with the Condon-Shortley phase (shlab's default)\n"
    "  nocs     orthonormal, without the phase (odd-m functions negated)\n"
    "  4pi      4π-normalised, without the phase (SHTOOLS' default 'real4pi')\n"
    "  schmidt  Schmidt semi-normalised, without the phase\n"
    "Coefficients transform inversely to the basis: the represented function is kept.\n"
    "\n"
    "  --from NORM, --to NORM\n"
    "  --coeffs LIST        comma-separated numbers (count must be a perfect square)\n"
    "  --in FILE            JSON with \"coeffs\" or \"channels\", or plain numbers\n"
    "  --format table|csv|json\n"
    "  --help\n"
    "\n"
    "JSON: {\"order\",\"convention\",\"from\",\"to\",\"coeffs\":[...]}\n"
    "(or \"channels\":{...} when the input had channels; \"convention\" is the output's)\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        {"from", required_argument, 0, 'f'},
        {"to", required_argument, 0, 't'},
        {"coeffs", required_argument, 0, 'c'},
        {"in", required_argument, 0, 'i'},
        {0, 0, 0, 0}};
    sh_norm from = SH_NORM_CS, to = SH_NORM_CS;
    int have_from = 0, have_to = 0, n = 0, nchan = 1;
    double *c = NULL;
    const char *in = NULL;
    char names[SH_IMAGE_MAX_CHANNELS][8] = {"Y"};
    cli_common com = CLI_COMMON_DEFAULTS;
    opterr = 0;
    optind = 1;
    int o, rc = 0;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'f': if (sh_norm_parse(optarg, &from)) rc = cli_fail("--from: %s", sh_last_error()); have_from = 1; break;
        case 't': if (sh_norm_parse(optarg, &to)) rc = cli_fail("--to: %s", sh_last_error()); have_to = 1; break;
        case 'c': free(c); c = NULL; rc = cli_doubles("--coeffs", optarg, &c, &n); break;
        case 'i': in = optarg; break;
        default: {
            const int r = cli_common_opt(&cmd_convert, o, argv, &com);
            if (r >= 0) { free(c); return r; }
        }
        }
        if (rc) { free(c); return rc; }
    }
    if (optind < argc) { free(c); return cli_fail("convert: unexpected argument '%s'", argv[optind]); }
    if (!have_from || !have_to) { free(c); return cli_fail("convert: --from and --to are required"); }
    if (c && in) { free(c); return cli_fail("convert: give --coeffs or --in, not both"); }
    if (!c && !in) return cli_fail("convert: give --coeffs or --in");
    if (in && cli_read_coeffs_file(in, 0, &c, &n, &nchan, names)) return CLI_EXIT_USAGE;
    int order = (int)lround(sqrt((double)n));
    if (order * order != n) { free(c); return cli_fail("convert: %d coefficients is not a perfect square n²", n); }
    if (sh_check_order(order)) { free(c); return cli_fail_status(SH_EINVAL); }
    for (int k = 0; k < nchan; k++) sh_convert(order, from, to, c + (size_t)k * n);

    /* the output's phase convention: cs for cs, nocs for every phase-free form */
    json_t *root = json_pack("{s:i,s:s,s:s,s:s}", "order", order, "convention",
                             to == SH_NORM_CS ? "cs" : "nocs", "from", sh_norm_name(from), "to",
                             sh_norm_name(to));
    if (nchan == 1 && !strcmp(names[0], "Y")) {
        root = cli_put(root, "coeffs", cli_json_array(c, n));
    } else {
        json_t *ch = json_object();
        for (int k = 0; k < nchan && ch; k++)
            ch = cli_put(ch, names[k], cli_json_array(c + (size_t)k * n, n));
        root = cli_put(root, "channels", ch);
    }
    free(c);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_convert = {"convert", run, "convert coefficients between cs, nocs, 4pi and schmidt", help, NULL};
