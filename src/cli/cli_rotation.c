/* cli_rotation.c — the rotation options shared by rotmat, rotate, euler,
 * fixtures and verify: one rotation in one of four forms, optionally
 * inverted (the frame rotation) or orthonormalised. */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int take_form(const char *cmd, cli_rotation_args *r, const char *form, const char *opt,
                     const char *arg, int count)
{
    if (r->form)
        return cli_fail("%s: give one rotation (--%s and --%s both given)", cmd, r->form, opt);
    double *v = NULL;
    int n = 0;
    char name[16];
    snprintf(name, sizeof name, "--%s", opt);
    if (cli_doubles(name, arg, &v, &n)) return CLI_EXIT_USAGE;
    if (n != count) {
        free(v);
        return cli_fail("%s: --%s expects %d numbers, got %d", cmd, opt, count, n);
    }
    memcpy(r->v, v, (size_t)count * sizeof *v);
    free(v);
    r->form = form;
    return 0;
}

int cli_rotation_opt(const char *cmd, int o, const char *arg, cli_rotation_args *r)
{
    switch (o) {
    case CLI_OPT_EULER: return take_form(cmd, r, "euler", "euler", arg, 3);
    case CLI_OPT_QUAT: return take_form(cmd, r, "quat", "quat", arg, 4);
    case CLI_OPT_MATRIX: return take_form(cmd, r, "matrix", "matrix", arg, 9);
    case CLI_OPT_AXIS:
        if (r->have_axis) return cli_fail("%s: --axis given twice", cmd);
        if (cli_vec3("--axis", arg, r->axis)) return CLI_EXIT_USAGE;
        r->have_axis = 1;
        return 0;
    case CLI_OPT_ANGLE:
        if (r->have_angle) return cli_fail("%s: --angle given twice", cmd);
        if (cli_double("--angle", arg, &r->angle)) return CLI_EXIT_USAGE;
        r->have_angle = 1;
        return 0;
    case CLI_OPT_INVERSE: r->inverse = 1; return 0;
    case CLI_OPT_ORTHO: r->ortho = 1; return 0;
    default: return -1;
    }
}

int cli_rotation_finish(const char *cmd, const cli_rotation_args *r, int degrees, int optional,
                        int *given, sh_rotation *rot)
{
    /* --degrees: the angles given (--euler, --angle) and printed are in
     * degrees; a quaternion or a matrix has none, so it is simply not used */
    const double k = degrees ? M_PI / 180 : 1;
    int st;
    if (r->have_axis || r->have_angle) {
        if (r->form) return cli_fail("%s: give one rotation (--%s and --axis/--angle both given)",
                                     cmd, r->form);
        if (!r->have_axis || !r->have_angle)
            return cli_fail("%s: --axis and --angle go together", cmd);
        cli_warn_radians(cmd, "--angle", r->angle, degrees);
        st = sh_rotation_from_axis_angle(r->axis, r->angle * k, rot);
    } else if (!r->form) {
        if (given) *given = 0;
        if (optional) return 0;
        return cli_fail("%s: a rotation is required (--euler, --quat, --matrix or --axis/--angle)",
                        cmd);
    } else if (!strcmp(r->form, "euler")) {
        for (int i = 0; i < 3; i++) /* one warning for the three angles */
            if (!degrees && fabs(r->v[i]) > 2 * M_PI) { cli_warn_radians(cmd, "--euler angle", r->v[i], 0); break; }
        st = sh_rotation_from_euler(r->v[0] * k, r->v[1] * k, r->v[2] * k, rot);
    } else if (!strcmp(r->form, "quat")) {
        st = sh_rotation_from_quat(r->v, r->ortho, rot);
    } else {
        st = sh_rotation_from_matrix(r->v, r->ortho, rot);
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

int cli_precision(const char *s, sh_precision *out)
{
    if (sh_precision_parse(s, out)) return cli_fail("--precision: %s", sh_last_error());
    return 0;
}
