/* cli_rotation.c — the rotation options shared by rotmat, rotate, euler,
 * fixtures and verify: one rotation in one of four forms, optionally
 * inverted (the frame rotation) or orthonormalised. */
#include "cli.h"
#include "cli_args.h"

#include <stddef.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the declared group ------------------------------------------------------ */

static int numbers_n(const char *opt, const char *s, void *field, int count)
{
    cli_numbers *x = field;
    double *v = NULL;
    int n = 0;
    if (cli_doubles(opt, s, &v, &n)) return CLI_EXIT_USAGE;
    if (n != count) {
        free(v);
        return cli_fail("%s expects %d numbers, got %d", opt, count, n);
    }
    memcpy(x->v, v, (size_t)count * sizeof *v);
    x->n = count;
    free(v);
    return 0;
}
static int numbers_3(const char *opt, const char *s, void *field) { return numbers_n(opt, s, field, 3); }
static int numbers_4(const char *opt, const char *s, void *field) { return numbers_n(opt, s, field, 4); }
static int numbers_9(const char *opt, const char *s, void *field) { return numbers_n(opt, s, field, 9); }
static int angle_value(const char *opt, const char *s, void *field)
{
    /* the field is angle; have_angle follows it in cli_rotation_args */
    cli_rotation_args *r = (cli_rotation_args *)((char *)field - offsetof(cli_rotation_args, angle));
    if (cli_double(opt, s, &r->angle)) return CLI_EXIT_USAGE;
    r->have_angle = 1;
    return 0;
}

const cli_opt cli_rotation_opts[] = {
    CLI_HEADING("The rotation (one form; angles in radians unless --degrees):"),
    CLI_CUSTOM(cli_rotation_args, euler, "euler", "A,B,G", numbers_3, NULL,
               "ZYZ Euler angles (function rotation Rz(A) Ry(B) Rz(G))"),
    CLI_CUSTOM(cli_rotation_args, quat, "quat", "W,X,Y,Z", numbers_4, NULL, "unit quaternion"),
    CLI_CUSTOM(cli_rotation_args, matrix, "matrix", "R00,...,R22", numbers_9, NULL,
               "3x3 rotation matrix, row-major"),
    CLI_CUSTOM(cli_rotation_args, axis, "axis", "X,Y,Z", numbers_3, NULL, "rotation axis (with --angle)"),
    CLI_CUSTOM(cli_rotation_args, angle, "angle", "T", angle_value, NULL, "angle about --axis"),
    CLI_FLAG(cli_rotation_args, inverse, "inverse", "the inverse rotation (the frame rotation)"),
    CLI_FLAG(cli_rotation_args, ortho, "orthonormalize",
             "accept a --quat or --matrix that is not unit/orthonormal: use the nearest"),
    CLI_END,
};

int cli_parse_method(const char *opt, const char *s, void *field)
{
    if (!strcmp(s, "auto")) {
        *(sh_rot_method *)field = SH_ROT_AUTO;
        return 0;
    }
    if (sh_rot_method_parse(s, field)) return cli_fail("%s: %s", opt, sh_last_error());
    return 0;
}

int cli_parse_precision(const char *opt, const char *s, void *field)
{
    if (sh_precision_parse(s, field)) return cli_fail("%s: %s", opt, sh_last_error());
    return 0;
}

int cli_parse_kernel(const char *opt, const char *s, void *field)
{
    sh_rot_kernel *k = field;
    if (sh_rot_kernel_parse(s, k)) return cli_fail("%s: %s", opt, sh_last_error());
    if (!sh_rot_kernel_available(*k)) return cli_fail("%s: %s is not available on this machine", opt, s);
    return 0;
}

const cli_opt cli_method_opts[] = {
    CLI_CUSTOM(cli_method_args, method, "method", "M", cli_parse_method, "auto",
               "auto (default) | z | ivanic | zxzxz | choi | blanco | wigner |\n"
               "reference | halfpi | direct (orders ≤ 3) | zh (orders ≤ 6;\n"
               "exact) or taylor1 | taylor1.5 | taylor2 (Krivánek et al.'s\n"
               "approximations)"),
    CLI_CUSTOM(cli_method_args, prec, "precision", "P", cli_parse_precision, "double",
               "double (default) | float (computed in float)"),
    CLI_CUSTOM(cli_method_args, kernel, "kernel", "K", cli_parse_kernel, "auto",
               "auto (default) | scalar | unrolled | sse2 | avx2 | avx512:\n"
               "the code that runs"),
    CLI_END,
};

/* ---- the rotation ----------------------------------------------------------------- */

/* The one form given (r->form), or an error line: two forms, or half of
 * --axis/--angle. */
static int one_form(const char *cmd, cli_rotation_args *r)
{
    const struct { const cli_numbers *x; const char *name; } forms[] = {
        {&r->euler, "euler"}, {&r->quat, "quat"}, {&r->matrix, "matrix"}};
    const char *first = NULL;
    r->form = NULL;
    for (int k = 0; k < 3; k++) {
        if (!forms[k].x->n) continue;
        if (first) return cli_fail("%s: give one rotation (--%s and --%s both given)", cmd, first, forms[k].name);
        first = forms[k].name;
    }
    if (r->axis.n || r->have_angle) {
        if (first) return cli_fail("%s: give one rotation (--%s and --axis/--angle both given)", cmd, first);
        if (!r->axis.n || !r->have_angle) return cli_fail("%s: --axis and --angle go together", cmd);
        first = "axis-angle";
    }
    r->form = first;
    return 0;
}

int cli_rotation_finish(const char *cmd, cli_rotation_args *r, int degrees, int optional, int *given,
                        sh_rotation *rot)
{
    /* --degrees: the angles given (--euler, --angle) and printed are in
     * degrees; a quaternion or a matrix has none, so it is simply not used */
    const double k = degrees ? M_PI / 180 : 1;
    int st;
    if (one_form(cmd, r)) return CLI_EXIT_USAGE;
    if (!r->form) {
        if (given) *given = 0;
        if (optional) return 0;
        return cli_fail("%s: a rotation is required (--euler, --quat, --matrix or --axis/--angle)", cmd);
    }
    if (!strcmp(r->form, "axis-angle")) {
        cli_warn_radians(cmd, "--angle", r->angle, degrees);
        st = sh_rotation_from_axis_angle(r->axis.v, r->angle * k, rot);
    } else if (!strcmp(r->form, "euler")) {
        const double *e = r->euler.v;
        for (int i = 0; i < 3; i++) /* one warning for the three angles */
            if (!degrees && fabs(e[i]) > 2 * M_PI) { cli_warn_radians(cmd, "--euler angle", e[i], 0); break; }
        st = sh_rotation_from_euler(e[0] * k, e[1] * k, e[2] * k, rot);
    } else if (!strcmp(r->form, "quat")) {
        st = sh_rotation_from_quat(r->quat.v, r->ortho, rot);
    } else {
        st = sh_rotation_from_matrix(r->matrix.v, r->ortho, rot);
    }
    if (st) return cli_fail("%s", sh_last_error());
    if (r->inverse) sh_rotation_inverse(rot, rot);
    if (given) *given = 1;
    return 0;
}

json_t *cli_rotation_json(const sh_rotation *rot)
{
    double q[4], axis[3], angle, e[3] = {rot->alpha, rot->beta, rot->gamma};
    sh_rotation_to_quat(rot, q);
    sh_rotation_to_axis_angle(rot, axis, &angle);
    json_t *o = json_object();
    o = cli_put(o, "euler", cli_json_array(e, 3));
    o = cli_put(o, "quat", cli_json_array(q, 4));
    o = cli_put(o, "matrix", cli_json_array(rot->R, 9));
    o = cli_put(o, "axis", cli_json_array(axis, 3));
    o = cli_put(o, "angle", json_real(angle));
    return o;
}

int cli_method(const char *s, sh_rot_method *out)
{
    if (sh_rot_method_parse(s, out)) return cli_fail("--method: %s", sh_last_error());
    return 0;
}

