/* fuzz_rotation.c — the rotation arguments of rotmat, rotate, euler, ...:
 * the input is a list of lines "<letter><value>", each one option
 *   e --euler  q --quat  m --matrix  a --axis  A --angle  i --inverse
 *   o --orthonormalize  d --degrees  O --order  M --method  P --precision
 *   C --convention  n a number list (cli_doubles)
 * read by the CLI's declared-option parser (cli_args_parse with the rotation
 * group and the options around it); a rotation that is accepted is then
 * built and applied to one band (order <= 9) by the chosen method. */
#include "fuzz.h"

#include <math.h>
#include <stddef.h>

/* The options, declared as the rotation commands declare them (cli_args.h):
 * the lines become a command line that the CLI's one parser reads. */
typedef struct {
    cli_rotation_args rot;
    int degrees, order;
    sh_rot_method method;
    sh_precision prec;
    sh_convention conv;
} fuzz_args;

static const cli_opt fuzz_opts[] = {
    CLI_GROUP(fuzz_args, rot, cli_rotation_opts),
    CLI_DEGREES(fuzz_args, degrees, "angles in degrees"),
    CLI_ORDER(fuzz_args, order, SHLAB_MAX_ORDER, NULL, "bands"),
    CLI_CUSTOM(fuzz_args, method, "method", "M", cli_parse_method, "ivanic", "method"),
    CLI_CUSTOM(fuzz_args, prec, "precision", "P", cli_parse_precision, "double", "precision"),
    CLI_CONVENTION(fuzz_args, conv),
    CLI_END,
};
static const cli_cmd fuzz_decl = {.name = "fuzz", .usage = "fuzz", .opts = fuzz_opts};

/* The option a line's letter names ('n' and unknown letters: none). */
static const char *option_of(char c)
{
    switch (c) {
    case 'e': return "--euler";
    case 'q': return "--quat";
    case 'm': return "--matrix";
    case 'a': return "--axis";
    case 'A': return "--angle";
    case 'i': return "--inverse";
    case 'o': return "--orthonormalize";
    case 'd': return "--degrees";
    case 'O': return "--order";
    case 'M': return "--method";
    case 'P': return "--precision";
    case 'C': return "--convention";
    default: return NULL;
    }
}

/* A number list line: cli_doubles' contract. */
static void number_list(const char *v)
{
    double *x = NULL;
    int n = 0;
    const int rc = cli_doubles("--list", v, &x, &n);
    FUZZ_CHECK(rc == 0 || rc == CLI_EXIT_USAGE, "exit code %d", rc);
    if (rc) return;
    FUZZ_CHECK(n >= 1 && n <= CLI_MAX_NUMBERS, "%d numbers", n);
    for (int k = 0; k < n; k++) FUZZ_CHECK(isfinite(x[k]), "number %d", k);
    free(x);
}

/* Build and check the rotation the parsed options give, then one band of it
 * (order <= 9) by the chosen method. */
static void rotate_band(fuzz_args *a)
{
    sh_rotation rot;
    int given = 0;
    if (cli_rotation_finish("fuzz", &a->rot, a->degrees, 1, &given, &rot) || !given) return;
    for (int k = 0; k < 9; k++) FUZZ_CHECK(isfinite(rot.R[k]), "matrix entry %d", k);
    const sh_rot_method method = a->method == SH_ROT_AUTO ? SH_ROT_IVANIC : a->method;
    const int band = (a->order - 1) % 9;
    double B[19 * 19];
    if (band > sh_rot_method_max_order(method) - 1 || (method == SH_ROT_Z && rot.beta != 0)) return;
    if (sh_rot_band(band, method, a->prec, a->conv, &rot, B) == SH_OK) {
        for (int k = 0; k < (2 * band + 1) * (2 * band + 1); k++)
            FUZZ_CHECK(isfinite(B[k]), "band %d entry %d not finite (%s)", band, k, sh_rot_method_name(method));
    } else {
        fuzz_check_reason();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *s = fuzz_cstr(data, size);
    char *argv[2 * CLI_ARGS_MAX + 1];
    int argc = 0;
    argv[argc++] = (char *)"fuzz";
    char *save = NULL;
    for (char *line = strtok_r(s, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        if (line[0] == 'n') {
            number_list(line + 1);
            continue;
        }
        const char *opt = option_of(line[0]);
        if (!opt || argc + 2 > (int)(sizeof argv / sizeof *argv)) continue;
        argv[argc++] = (char *)opt;
        if (line[0] != 'i' && line[0] != 'o' && line[0] != 'd') argv[argc++] = line + 1;
    }
    fuzz_args a;
    memset(&a, 0, sizeof a);
    a.order = 3; /* --order is optional here */
    cli_parsed seen;
    const int rc = cli_args_parse(&fuzz_decl, argc, argv, &a, &seen);
    FUZZ_CHECK(rc == -1 || rc == CLI_EXIT_USAGE, "parser exit code %d", rc);
    if (rc == -1) rotate_band(&a);
    free(s);
    return 0;
}
