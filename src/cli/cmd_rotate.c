/* cmd_rotate.c — `shlab rotate`: rotate coefficient vectors (one plan,
 * applied to every channel). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_rotate;

static const char help[] =
    "Usage: shlab rotate --method M ROTATION (--coeffs C0,C1,... | --in FILE) [OPTIONS]\n"
    "\n"
    "Rotate SH coefficients: the output are the coefficients of g(s) = f(R⁻¹s).\n"
    "\n"
    "  --coeffs LIST        n² numbers, comma or space separated\n"
    "  --in FILE            JSON {\"coeffs\":[...]} or {\"channels\":{\"R\":[...],...}},\n"
    "                       or plain numbers\n"
    "  --order N            number of bands (default: from the number of coefficients,\n"
    "                       which must then be a perfect square; with --order exactly N²)\n"
    "  --method M           z | ivanic | zxzxz | choi | blanco | wigner | reference\n"
    "                       (exact; default ivanic) or taylor1 | taylor1.5 |\n"
    "                       taylor2 (Krivánek et al.'s approximations)\n"
    "  --precision P        double (default) | float\n"
    "  --kernel K           auto (default) | scalar | unrolled | sse2 | avx2 | avx512:\n"
    "                       the code that runs (unrolled kernels: zxzxz and taylor*,\n"
    "                       order <= 10; the others always run the scalar loops)\n"
    "Rotation (exactly one): --euler A,B,G | --quat W,X,Y,Z | --matrix R00,...,R22 |\n"
    "  --axis X,Y,Z --angle T;  --inverse, --orthonormalize, --degrees\n"
    "  (see shlab rotmat --help; --euler reaches the plan as angles, the other\n"
    "  forms as the matrix, sh_rot_plan_set_matrix)\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"method\",\"convention\",\"precision\",\"coeffs\":[...]} (or \"channels\"),\n"
    "      with --kernel also \"kernel\" (the one used)\n";

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,     CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_CONVENTION, CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPTS_ROTATION,  CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_PRECISION,  CLI_LONGOPT_KERNEL,
                                         {"coeffs", required_argument, 0, 'k'},
                                         {"in", required_argument, 0, 'i'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    cli_rotation_args ra = {0};
    sh_rot_method method = SH_ROT_IVANIC;
    sh_precision prec = SH_PREC_DOUBLE;
    const char *coeff_arg = NULL, *in = NULL;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int r = cli_rotation_opt("rotate", o, optarg, &ra);
        if (r > 0) return r;
        if (r == 0) continue;
        switch (o) {
        case 'k':
            if (coeff_arg) return cli_fail("rotate: --coeffs given twice");
            coeff_arg = optarg;
            break;
        case 'i':
            if (in) return cli_fail("rotate: --in given twice");
            in = optarg;
            break;
        default: {
            const int e = cli_common_opt(&cmd_rotate, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    method = com.method;
    prec = com.prec;
    if (optind < argc) return cli_fail("rotate: unexpected argument '%s'", argv[optind]);
    if (!coeff_arg == !in) return cli_fail("rotate: give exactly one of --coeffs and --in");
    sh_rotation rot;
    int r = cli_rotation_finish("rotate", &ra, com.degrees, 0, NULL, &rot);
    if (r) return r;
    double *c = NULL;
    int n = 0, nchan = 1;
    char names[SH_IMAGE_MAX_CHANNELS][8] = {"Y"};
    if (coeff_arg) {
        if (cli_doubles("--coeffs", coeff_arg, &c, &n)) return CLI_EXIT_USAGE;
    } else if (cli_read_coeffs_file(in, &c, &n, &nchan, names)) {
        return CLI_EXIT_USAGE;
    }
    int order = com.order;
    if (order) {
        if (n != order * order) {
            free(c);
            return cli_fail("rotate: --order %d needs %d coefficients per channel, got %d", order,
                            order * order, n);
        }
    } else {
        order = (int)lround(sqrt((double)n));
        if (order * order != n || order < 1) {
            free(c);
            return cli_fail("rotate: %d coefficients is not a perfect square n²", n);
        }
    }
    sh_rot_plan *p = NULL;
    int st = sh_rot_plan_create_kernel(order, method, prec, com.conv, com.kernel, &p);
    /* angles as angles, any other form as its matrix (sh_rot_plan_set_matrix) */
    if (!st) st = ra.form && !strcmp(ra.form, "euler") ? sh_rot_plan_set(p, &rot) : sh_rot_plan_set_matrix(p, rot.R);
    for (int k = 0; !st && k < nchan; k++) st = sh_rot_plan_apply(p, c + (size_t)k * n, c + (size_t)k * n);
    const sh_rot_kernel used = p ? sh_rot_plan_kernel(p) : SH_KERNEL_SCALAR;
    sh_rot_plan_free(p);
    if (st) { free(c); return cli_fail_status(st); }
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "method", json_string(sh_rot_method_name(method)));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "precision", json_string(sh_precision_name(prec)));
    if (com.have_kernel) root = cli_put(root, "kernel", json_string(sh_rot_kernel_name(used)));
    if (nchan == 1 && !strcmp(names[0], "Y")) {
        root = cli_put(root, "coeffs", cli_json_array(c, (size_t)n));
    } else {
        json_t *ch = json_object();
        for (int k = 0; k < nchan && ch; k++)
            ch = cli_put(ch, names[k], cli_json_array(c + (size_t)k * n, (size_t)n));
        root = cli_put(root, "channels", ch);
    }
    free(c);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_rotate = {"rotate", run, "rotate SH coefficients (one plan, many channels)", help};
