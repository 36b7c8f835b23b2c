/* cli_image_opts.h — option groups that the function commands share
 * (cli_args.h groups: CLI_GROUP(struct, field, table)):
 *   cli_run_opts       --threads, --quiet                 project, reconstruct
 *   cli_coeffs_opts    --coeffs LIST | --in FILE          convert, reconstruct
 *   cli_sampling_opts  --samples, --seed of a rule        project, orthonormality
 *   cli_light_opts     --light SPEC, --degrees            project, triple
 * and cli_parse_rule, the projection rule (sh_rule) for a CLI_CUSTOM option
 * (project --method, orthonormality --rule). */
#ifndef SHLAB_CLI_IMAGE_OPTS_H
#define SHLAB_CLI_IMAGE_OPTS_H

#include "cli.h"

/* The reason of the commands that print a dense N²×N² matrix for their
 * limit of --order (deriv, triple, scale). */
#define CLI_WHY_PRINTED_MATRIX "a printed N²×N² matrix"

typedef struct {
    int threads; /* 0: all cores */
    int quiet;
} cli_run_args;
extern const cli_opt cli_run_opts[];

typedef struct {
    const char *coeffs, *in; /* the option's text: read by cli_coeffs_read */
} cli_coeffs_args;
extern const cli_opt cli_coeffs_opts[];
/* Exactly one of --coeffs and --in was given, else "CMD: give exactly one
 * of --coeffs and --in" and CLI_EXIT_USAGE. */
int cli_coeffs_given(const char *cmd, const cli_coeffs_args *a);
/* Read them (cli_doubles or cli_read_coeffs_file, no bound below
 * SHLAB_MAX_ORDER): nchan vectors of *len numbers in *v (malloc'd), the
 * channel names in names ("Y" for one vector).  0 or the exit code. */
int cli_coeffs_read(const cli_coeffs_args *a, double **v, int *len, int *nchan,
                    char names[SH_IMAGE_MAX_CHANNELS][8]);

typedef struct {
    long samples; /* 0: the command's default (sh_rule_samples_used) */
    long seed;
} cli_sampling_args;
extern const cli_opt cli_sampling_opts[];
/* parse() of a declared sh_rule option: quad, mc, random or qmc. */
int cli_parse_rule(const char *opt, const char *s, void *field);

typedef struct {
    const char *spec; /* NULL: not given */
    int degrees;
} cli_light_args;
extern const cli_opt cli_light_opts[];
/* The light of --light (one error line "--light: ..." if its spec is bad),
 * with the warning for an angle that looks like degrees. */
int cli_light_read(const char *cmd, const cli_light_args *a, sh_light *L);

#endif
