/* fuzz_rotation.c — the rotation arguments of rotmat, rotate, euler, ...:
 * the input is a list of lines "<letter><value>", each one option
 *   e --euler  q --quat  m --matrix  a --axis  A --angle  i --inverse
 *   o --orthonormalize  d --degrees  O --order  M --method  P --precision
 *   C --convention  n a number list (cli_doubles)
 * parsed with the CLI's own functions; a rotation that is accepted is then
 * built and applied to one band (order <= 9) by the chosen method. */
#include "fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *s = fuzz_cstr(data, size);
    cli_rotation_args r;
    memset(&r, 0, sizeof r);
    int degrees = 0, order = 3, bad = 0;
    sh_rot_method method = SH_ROT_IVANIC;
    sh_precision prec = SH_PREC_DOUBLE;
    sh_convention conv = SH_CS;
    char *save = NULL;
    for (char *line = strtok_r(s, "\n", &save); line && !bad; line = strtok_r(NULL, "\n", &save)) {
        const char *v = line + 1;
        int rc = 0;
        switch (line[0]) {
        case 'e': rc = cli_rotation_opt("fuzz", CLI_OPT_EULER, v, &r); break;
        case 'q': rc = cli_rotation_opt("fuzz", CLI_OPT_QUAT, v, &r); break;
        case 'm': rc = cli_rotation_opt("fuzz", CLI_OPT_MATRIX, v, &r); break;
        case 'a': rc = cli_rotation_opt("fuzz", CLI_OPT_AXIS, v, &r); break;
        case 'A': rc = cli_rotation_opt("fuzz", CLI_OPT_ANGLE, v, &r); break;
        case 'i': rc = cli_rotation_opt("fuzz", CLI_OPT_INVERSE, v, &r); break;
        case 'o': rc = cli_rotation_opt("fuzz", CLI_OPT_ORTHO, v, &r); break;
        case 'd': degrees = 1; break;
        case 'O': rc = cli_order("--order", v, &order); break;
        case 'M': rc = cli_method(v, &method); break;
        case 'P': rc = cli_precision(v, &prec); break;
        case 'C': rc = cli_convention(v, &conv); break;
        case 'n': {
            double *x = NULL;
            int n = 0;
            rc = cli_doubles("--list", v, &x, &n);
            if (!rc) {
                FUZZ_CHECK(n >= 1 && n <= CLI_MAX_NUMBERS, "%d numbers", n);
                for (int k = 0; k < n; k++) FUZZ_CHECK(isfinite(x[k]), "number %d", k);
                free(x);
            }
            break;
        }
        default: break;
        }
        FUZZ_CHECK(rc == 0 || rc == CLI_EXIT_USAGE, "exit code %d", rc);
        bad = rc != 0;
    }
    sh_rotation rot;
    int given = 0;
    if (!bad && cli_rotation_finish("fuzz", &r, degrees, 1, &given, &rot) == 0 && given) {
        for (int k = 0; k < 9; k++) FUZZ_CHECK(isfinite(rot.R[k]), "matrix entry %d", k);
        const int band = (order - 1) % 9;
        double B[19 * 19];
        if (band <= sh_rot_method_max_order(method) - 1 &&
            (method != SH_ROT_Z || rot.beta == 0)) {
            if (sh_rot_band(band, method, prec, conv, &rot, B) == SH_OK) {
                for (int k = 0; k < (2 * band + 1) * (2 * band + 1); k++)
                    FUZZ_CHECK(isfinite(B[k]), "band %d entry %d not finite (%s)", band, k,
                               sh_rot_method_name(method));
            } else {
                fuzz_check_reason();
            }
        }
    }
    free(s);
    return 0;
}
