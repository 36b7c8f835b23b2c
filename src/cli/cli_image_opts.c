/* cli_image_opts.c — the option groups of the function commands
 * (cli_image_opts.h): declared once, so that project and reconstruct, convert
 * and reconstruct, project and orthonormality, project and triple read and
 * document these options in the same words. */
#include "cli_image_opts.h"

#include <limits.h>
#include <string.h>

const cli_opt cli_run_opts[] = {
    CLI_INT(cli_run_args, threads, "threads", "N", 0, 1024, "0",
            "threads (default 0: all cores); the result is the same\nfor every N"),
    CLI_FLAG(cli_run_args, quiet, "quiet", "no progress or estimate on stderr"),
    CLI_END,
};

const cli_opt cli_coeffs_opts[] = {
    CLI_STRING(cli_coeffs_args, coeffs, "coeffs", "LIST", "n² numbers (i = l(l+1)+m), comma or space separated"),
    CLI_STRING(cli_coeffs_args, in, "in", "FILE",
               "JSON {\"coeffs\":[...]} or {\"channels\":{\"R\":[...],...}},\nor plain numbers"),
    CLI_END,
};

int cli_coeffs_given(const char *cmd, const cli_coeffs_args *a)
{
    if (!a->coeffs == !a->in) return cli_fail("%s: give exactly one of --coeffs and --in", cmd);
    return 0;
}

int cli_coeffs_read(const cli_coeffs_args *a, double **v, int *len, int *nchan,
                    char names[SH_IMAGE_MAX_CHANNELS][8])
{
    memset(names, 0, SH_IMAGE_MAX_CHANNELS * sizeof names[0]);
    strcpy(names[0], "Y");
    *nchan = 1;
    if (a->coeffs) return cli_doubles("--coeffs", a->coeffs, v, len);
    return cli_read_coeffs_file(a->in, 0, v, len, nchan, names);
}

const cli_opt cli_sampling_opts[] = {
    CLI_LONG(cli_sampling_args, samples, "samples", "S", 1, LONG_MAX, NULL,
             "S >= 1: quad's θ nodes (× 2S φ nodes), the others'\nsample count (mc rounds S to round(√S)²); defaults below"),
    CLI_LONG(cli_sampling_args, seed, "seed", "K", 0, LONG_MAX, "1",
             "seed >= 0 of mc, random and qmc (default 1; qmc: 0 = no\nshift)"),
    CLI_END,
};

int cli_parse_rule(const char *opt, const char *s, void *field)
{
    return sh_rule_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

const cli_opt cli_light_opts[] = {
    CLI_STRING(cli_light_args, spec, "light", "SPEC",
               "an analytic light:\n"
               "  green                Green (2003) Figure 7 two-lobe light\n"
               "  cap:T                1 for θ < T (T in [0,π])\n"
               "  cie-overcast         CIE overcast sky (1+2cosθ)/3\n"
               "  cie-clear:TH,PH      CIE clear sky, sun at (TH,PH), TH in [0,π/2]\n"
               "  cie-partly:TH,PH     CIE partly cloudy sky, sun at (TH,PH)\n"
               "  const:V              constant V\n"
               "  lobe:E               max(0,cosθ)^E, E >= 0"),
    CLI_DEGREES(cli_light_args, degrees, "angles in SPEC are in degrees"),
    CLI_END,
};

int cli_light_read(const char *cmd, const cli_light_args *a, sh_light *L)
{
    if (sh_light_parse(a->spec, a->degrees, L)) return cli_fail("--light: %s", sh_last_error());
    cli_light_warn(cmd, L, a->degrees);
    return 0;
}
