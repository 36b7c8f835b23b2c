/* cmd_euler.c — `shlab euler`: ZYZ Euler angles of a rotation (Green's
 * identities, stable at β = 0 and β = π; see rotation.c). */
#include "cli.h"

#include <math.h>
#include <stddef.h>

typedef struct {
    cli_rotation_args rot;
    int degrees, conv, fmt;
} euler_args;

static const cli_opt euler_opts[] = {
    CLI_GROUP(euler_args, rot, cli_rotation_opts),
    CLI_DEGREES(euler_args, degrees, "angles in and out in degrees (the input forms --quat\n"
                                     "and --matrix have none; the printed angles are then in\n"
                                     "degrees)"),
    CLI_CHOICE(euler_args, conv, "convention", "cs|nocs", cli_convention_names, "cs",
               "reported only (the angles do not depend on it)"),
    CLI_FORMAT(euler_args, fmt),
    CLI_END,
};

static const cli_cmd euler_decl = {
    .name = "euler",
    .usage = "euler ROTATION [OPTIONS]",
    .about = "ZYZ active Euler angles (α, β, γ) with R = Rz(α) Ry(β) Rz(γ), α, γ in (-π, π],\n"
             "β in [0, π].  At β = 0 only α+γ is defined (α = 0 is returned); at β = π only\n"
             "α-γ (α = 0).  Also prints how well the angles reproduce the matrix.\n"
             "The rotation: exactly one form (see shlab rotmat --help).\n",
    .opts = euler_opts,
    .notes = "JSON: {\"alpha\",\"beta\",\"gamma\",\"unit\",\"residual\",\"convention\"}  (residual = max|R(α,β,γ) − R|)\n",
};

static int run(int argc, char **argv)
{
    euler_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&euler_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    sh_rotation rot, back;
    if ((rc = cli_rotation_finish("euler", &a.rot, a.degrees, 0, NULL, &rot))) return rc;
    double al, be, ga;
    sh_euler_from_matrix(rot.R, &al, &be, &ga);
    sh_rotation_from_euler(al, be, ga, &back);
    double res = 0; /* max|R(α,β,γ) − R| */
    for (int i = 0; i < 9; i++) res = fmax(res, fabs(back.R[i] - rot.R[i]));
    json_t *root = json_object();
    root = cli_put(root, "alpha", json_real(cli_angle_out(al, a.degrees)));
    root = cli_put(root, "beta", json_real(cli_angle_out(be, a.degrees)));
    root = cli_put(root, "gamma", json_real(cli_angle_out(ga, a.degrees)));
    root = cli_put(root, "unit", json_string(cli_angle_unit(a.degrees)));
    root = cli_put(root, "residual", json_real(res));
    /* last, so that the CSV columns of the angles keep their places */
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a.conv)));
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_euler = {"euler", run, "ZYZ Euler angles of a rotation matrix", &euler_decl};
