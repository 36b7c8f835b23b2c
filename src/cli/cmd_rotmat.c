/* cmd_rotmat.c — `shlab rotmat`: the SH rotation matrix of a rotation, by a
 * chosen method, whole (order N) or one band (--band L). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_rotmat;

/* The dense matrix has N⁴ entries; beyond this the output stops being useful. */
#define ROTMAT_MAX_ORDER 32

static const char help[] =
    "Usage: shlab rotmat --order N --method M ROTATION [OPTIONS]\n"
    "       shlab rotmat --band L --method M ROTATION [OPTIONS]\n"
    "\n"
    "The real SH rotation matrix R_sh(R): the coefficients of f map to those of\n"
    "g(s) = f(R⁻¹s) (docs/CONVENTIONS.md).  It is block diagonal; the whole N²×N²\n"
    "matrix is printed, or with --band L only the (2L+1)×(2L+1) block of band L\n"
    "(rows and columns m = -L..L).\n"
    "\n"
    "Rotation (exactly one):\n"
    "  --euler A,B,G        ZYZ active: R = Rz(A) Ry(B) Rz(G)\n"
    "  --quat W,X,Y,Z       unit quaternion, active\n"
    "  --matrix R00,...,R22 row-major 3×3 (refused unless proper orthogonal to 1e-6)\n"
    "  --axis X,Y,Z --angle T   right-handed rotation by T about the axis\n"
    "  --inverse            use R⁻¹ (the frame rotation, R_sh transposed)\n"
    "  --orthonormalize     accept a matrix/quaternion that is not orthonormal:\n"
    "                       use the nearest proper rotation\n"
    "  --degrees            angles in degrees (radians otherwise; a warning on\n"
    "                       stderr when an angle in radians exceeds 2π)\n"
    "\n"
    "  --order N            bands 0..N-1 (1..32 for the printed matrix)\n"
    "  --band L             one band only (0..1000; below --order if both are given);\n"
    "                       blanco, zxzxz, halfpi, wigner and reference compute it\n"
    "                       without the lower bands, ivanic streams through them, the\n"
    "                       others need all lower blocks in memory (refused above 1.1 GB)\n"
    "  --method M           auto (default) | z | ivanic | zxzxz | choi | blanco | wigner |\n"
    "                       reference | halfpi (exact) or taylor1 | taylor1.5 | taylor2\n"
    "                       (Krivánek et al.'s approximations).  auto: zxzxz for\n"
    "                       --order, blanco for --band (O(l²)) — exact at every band;\n"
    "                       ivanic and choi drift from l ~ 50 and are used only when named.\n"
    "                       The Taylor methods warn on stderr, with the estimated error,\n"
    "                       when β is beyond the angle where their lobe error reaches 1e-2\n"
    "  --precision P        double (default) | float (computed in float)\n"
    "  --kernel K           auto (default) | scalar | unrolled | sse2 | avx2 | avx512\n"
    "                       (whole orders; the unrolled kernels give the matrix by\n"
    "                       rotating each unit vector)\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"order\",\"method\",\"convention\",\"precision\",[\"band\"],[\"kernel\"],\n"
    "       \"orthogonality_error\",\"matrix\":[[...]]}  (kernel: with --kernel, the one used)\n"
    "A rotation given by --euler reaches the plan as angles, any other form as its\n"
    "matrix (sh_rot_plan_set_matrix, no trigonometric call for zxzxz and taylor*).\n"
    "orthogonality_error is max|R Rᵀ - I| (for --band: the two-probe estimate\n"
    "max|Rᵀ(R v) - v|); an exact method above 1e-8 (float: 1e-3) gets a warning\n"
    "on stderr: it has broken down at that band.\n";

/* An exact method whose result is far from orthogonal has broken down
 * (the l-recursions do past l ≈ 100): say so instead of printing it silently. */
static void warn_if_inaccurate(sh_rot_method m, sh_precision p, int band, double orth)
{
    const double limit = p == SH_PREC_FLOAT ? 1e-3 : 1e-8;
    if (sh_rot_method_is_exact(m) && !(orth <= limit))
        cli_warn("method %s is inaccurate here: orthogonality error %.2g at band %d "
                 "(see 'shlab stability --method %s'; blanco, zxzxz and halfpi stay accurate)",
                 sh_rot_method_name(m), orth, band, sh_rot_method_name(m));
}

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,     CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_CONVENTION, CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPTS_ROTATION,  CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_PRECISION,  CLI_LONGOPT_KERNEL,
                                         {"band", required_argument, 0, 'b'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    cli_rotation_args ra = {0};
    sh_rot_method method;
    sh_precision prec = SH_PREC_DOUBLE;
    int band = -1;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int r = cli_rotation_opt("rotmat", o, optarg, &ra);
        if (r > 0) return r;
        if (r == 0) continue;
        switch (o) {
        case 'b':
            if (cli_int("--band", optarg, &band)) return CLI_EXIT_USAGE;
            if (band < 0 || band > 1000) return cli_fail("--band: %d out of range 0..1000", band);
            break;
        default: {
            const int e = cli_common_opt(&cmd_rotmat, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    prec = com.prec;
    if (optind < argc) return cli_fail("rotmat: unexpected argument '%s'", argv[optind]);
    if (band >= 0 && com.order && band >= com.order)
        return cli_fail("rotmat: --band %d is not below --order %d", band, com.order);
    if (band < 0 && !com.order) return cli_fail("rotmat: --order (or --band) is required");
    if (band < 0 && cli_order_check("--order", com.order, ROTMAT_MAX_ORDER, "a printed N²×N² matrix; --band for one band"))
        return CLI_EXIT_USAGE;
    const int order = com.order ? com.order : band + 1;
    method = com.have_method ? com.method : sh_rot_method_default(order, band >= 0);
    if ((band >= 0 ? band + 1 : order) > sh_rot_method_max_order(method))
        return cli_fail("rotmat: method %s is limited to order %d", sh_rot_method_name(method),
                        sh_rot_method_max_order(method));
    sh_rotation rot;
    int r = cli_rotation_finish("rotmat", &ra, com.degrees, 0, NULL, &rot);
    if (r) return r;

    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "method", json_string(sh_rot_method_name(method)));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "precision", json_string(sh_precision_name(prec)));
    int st;
    if (band >= 0) {
        const size_t w = 2 * (size_t)band + 1;
        double *B = malloc(w * w * sizeof *B);
        if (!B) { json_decref(root); return cli_fail("out of memory"); }
        st = sh_rot_band(band, method, prec, com.conv, &rot, B);
        if (st) { free(B); json_decref(root); return cli_fail_status(st); }
        const double orth = sh_rot_block_orthogonality(B, (int)w, 0);
        root = cli_put(root, "band", json_integer(band));
        root = cli_put(root, "orthogonality_error", json_real(orth));
        root = cli_put(root, "matrix", cli_json_matrix(B, w, w));
        free(B);
        warn_if_inaccurate(method, prec, band, orth);
    } else {
        const size_t n = (size_t)order * order;
        double *blocks = malloc(sh_rot_block_offset(order) * sizeof *blocks);
        double *M = malloc(n * n * sizeof *M);
        sh_rot_plan *p = NULL;
        if (!blocks || !M) { free(blocks); free(M); json_decref(root); return cli_fail("out of memory"); }
        st = sh_rot_plan_create_kernel(order, method, prec, com.conv, com.kernel, &p);
        /* a rotation given as angles reaches the plan as angles, any other
         * form as its matrix (sh_rot_plan_set_matrix: no angles) */
        if (!st) st = ra.form && !strcmp(ra.form, "euler") ? sh_rot_plan_set(p, &rot) : sh_rot_plan_set_matrix(p, rot.R);
        if (!st) st = sh_rot_plan_blocks(p, blocks);
        if (p && com.have_kernel) root = cli_put(root, "kernel", json_string(sh_rot_kernel_name(sh_rot_plan_kernel(p))));
        sh_rot_plan_free(p);
        if (st) { free(blocks); free(M); json_decref(root); return cli_fail_status(st); }
        sh_rot_blocks_to_dense(order, blocks, M);
        double orth = 0;
        for (int l = 0; l < order; l++)
            orth = fmax(orth, sh_rot_block_orthogonality(blocks + sh_rot_block_offset(l), 2 * l + 1, 1));
        root = cli_put(root, "orthogonality_error", json_real(orth));
        root = cli_put(root, "matrix", cli_json_matrix(M, n, n));
        warn_if_inaccurate(method, prec, order - 1, orth);
        free(blocks);
        free(M);
    }
    cli_warn_approx_rotation("rotmat", method, band >= 0 ? band + 1 : order, &rot, com.degrees);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_rotmat = {"rotmat", run, "SH rotation matrix of a rotation (exact methods and Taylor approximations)", help, NULL};
