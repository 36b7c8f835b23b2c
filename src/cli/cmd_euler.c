/* cmd_euler.c — `shlab euler`: ZYZ Euler angles of a rotation (Green's
 * identities, stable at β = 0 and β = π; see rotation.c). */
#include "cli.h"

#include <getopt.h>
#include <math.h>

extern const cli_command cmd_euler;

static const char help[] =
    "Usage: shlab euler ROTATION [OPTIONS]\n"
    "\n"
    "ZYZ active Euler angles (α, β, γ) with R = Rz(α) Ry(β) Rz(γ), α, γ in (-π, π],\n"
    "β in [0, π].  At β = 0 only α+γ is defined (α = 0 is returned); at β = π only\n"
    "α-γ (α = 0).  Also prints how well the angles reproduce the matrix.\n"
    "\n"
    "Rotation (exactly one): --matrix R00,...,R22 | --quat W,X,Y,Z |\n"
    "  --axis X,Y,Z --angle T | --euler A,B,G   (see shlab rotmat --help);\n"
    "  --inverse, --orthonormalize\n"
    "  --degrees            angles in and out in degrees (the input forms --quat\n"
    "                       and --matrix have none; the printed angles are then in\n"
    "                       degrees)\n"
    "  --convention cs|nocs reported only (the angles do not depend on it)\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"alpha\",\"beta\",\"gamma\",\"unit\",\"residual\",\"convention\"}  (residual = max|R(α,β,γ) − R|)\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE, CLI_LONGOPT_DEGREES, CLI_LONGOPT_CONVENTION,
                                         CLI_LONGOPTS_ROTATION, {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    cli_rotation_args ra = {0};
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int r = cli_rotation_opt("euler", o, optarg, &ra);
        if (r > 0) return r;
        if (r == 0) continue;
        const int e = cli_common_opt(&cmd_euler, o, argv, &com);
        if (e >= 0) return e;
    }
    if (optind < argc) return cli_fail("euler: unexpected argument '%s'", argv[optind]);
    sh_rotation rot, back;
    int r = cli_rotation_finish("euler", &ra, com.degrees, 0, NULL, &rot);
    if (r) return r;
    double a, b, g;
    sh_euler_from_matrix(rot.R, &a, &b, &g);
    sh_rotation_from_euler(a, b, g, &back);
    double res = 0;
    for (int i = 0; i < 9; i++) res = fmax(res, fabs(back.R[i] - rot.R[i]));
    json_t *root = json_object();
    root = cli_put(root, "alpha", json_real(cli_angle_out(a, com.degrees)));
    root = cli_put(root, "beta", json_real(cli_angle_out(b, com.degrees)));
    root = cli_put(root, "gamma", json_real(cli_angle_out(g, com.degrees)));
    root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
    root = cli_put(root, "residual", json_real(res));
    /* last, so that the CSV columns of the angles keep their places */
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    return cli_emit(root, com.fmt);
}

const cli_command cmd_euler = {"euler", run, "ZYZ Euler angles of a rotation matrix", help, NULL};
