/* cmd_rotmat.c — `shlab rotmat`: the SH rotation matrix of a rotation, by a
 * chosen method, whole (order N) or one band (--band L). */
#include "cli.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* The dense matrix has N⁴ entries; beyond this the output stops being useful. */
#define ROTMAT_MAX_ORDER 32
/* --band: one block of (2L+1)² entries, printed */
#define ROTMAT_MAX_BAND 1000

typedef struct {
    cli_rotation_args rot;
    cli_method_args m;
    int order, band, degrees, conv, fmt;
} rotmat_args;

static const cli_opt rotmat_opts[] = {
    CLI_GROUP(rotmat_args, rot, cli_rotation_opts),
    CLI_DEGREES(rotmat_args, degrees, "angles in degrees (radians otherwise; a warning on\n"
                                      "stderr when an angle in radians exceeds 2π)"),
    CLI_HEADING(""),
    CLI_ORDER(rotmat_args, order, SHLAB_MAX_ORDER, NULL, "bands 0..N-1: 1..32 for the printed matrix, 1..4097\nwith --band"),
    CLI_INT(rotmat_args, band, "band", "L", 0, ROTMAT_MAX_BAND, NULL,
            "one band only (below --order if both are given)"),
    CLI_GROUP(rotmat_args, m, cli_method_opts),
    CLI_CONVENTION(rotmat_args, conv),
    CLI_FORMAT(rotmat_args, fmt),
    CLI_END,
};

static const cli_cmd rotmat_decl = {
    .name = "rotmat",
    .usage = "rotmat --order N --method M ROTATION [OPTIONS]\n"
             "       shlab rotmat --band L --method M ROTATION [OPTIONS]",
    .about = "The real SH rotation matrix R_sh(R): the coefficients of f map to those of\n"
             "g(s) = f(R⁻¹s) (docs/CONVENTIONS.md).  It is block diagonal; the whole N²×N²\n"
             "matrix is printed, or with --band L only the (2L+1)×(2L+1) block of band L\n"
             "(rows and columns m = -L..L).\n"
             "\n"
             "The rotation is one of: --euler A,B,G (ZYZ active: R = Rz(A) Ry(B) Rz(G)),\n"
             "--quat W,X,Y,Z (unit quaternion, active), --matrix R00,...,R22 (row-major\n"
             "3×3, refused unless proper orthogonal to 1e-6), --axis X,Y,Z --angle T\n"
             "(right-handed rotation by T about the axis); --inverse uses R⁻¹ (the frame\n"
             "rotation, R_sh transposed).\n",
    .opts = rotmat_opts,
    .notes =
        "--band: blanco, zxzxz, halfpi, wigner and reference compute it without the\n"
        "lower bands, ivanic streams through them, the others need all lower blocks\n"
        "in memory (refused above 1.1 GB).  --method auto: zxzxz for --order, blanco\n"
        "for --band (O(l²)) — exact at every band; ivanic and choi drift from l ~ 50\n"
        "and are used only when named.  The Taylor methods warn on stderr, with the\n"
        "estimated error, when β is beyond the angle where their lobe error reaches\n"
        "1e-2.  --kernel: whole orders; the unrolled kernels give the matrix by\n"
        "rotating each unit vector.\n"
        "\n"
        "JSON: {\"order\",\"method\",\"convention\",\"precision\",[\"band\"],[\"kernel\"],\n"
        "       \"orthogonality_error\",\"matrix\":[[...]]}  (kernel: with --kernel, the one used)\n"
        "A rotation given by --euler reaches the plan as angles, any other form as its\n"
        "matrix (sh_rot_plan_set_matrix, no trigonometric call for zxzxz and taylor*).\n"
        "orthogonality_error is max|R Rᵀ - I| (for --band: the two-probe estimate\n"
        "max|Rᵀ(R v) - v|); an exact method above 1e-8 (float: 1e-3) gets a warning\n"
        "on stderr: it has broken down at that band.\n",
};

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

/* --order and --band together; the method by order (auto) within its limit. */
static int validate(rotmat_args *a)
{
    const int band = a->band;
    if (band >= 0 && a->order && band >= a->order)
        return cli_fail("rotmat: --band %d is not below --order %d", band, a->order);
    if (band < 0 && !a->order) return cli_fail("rotmat: --order (or --band) is required");
    if (band < 0 && cli_order_check("--order", a->order, ROTMAT_MAX_ORDER,
                                    "a printed N²×N² matrix; --band for one band"))
        return CLI_EXIT_USAGE;
    if (!a->order) a->order = band + 1;
    if (a->m.method == SH_ROT_AUTO) a->m.method = sh_rot_method_default(a->order, band >= 0);
    const int top = sh_rot_method_max_order(a->m.method);
    if ((band >= 0 ? band + 1 : a->order) > top)
        return cli_fail("rotmat: method %s is limited to order %d", sh_rot_method_name(a->m.method), top);
    return 0;
}

/* The block of band L alone into root. */
static int one_band(const rotmat_args *a, const sh_rotation *rot, json_t **root)
{
    const size_t w = 2 * (size_t)a->band + 1;
    double *B = malloc(w * w * sizeof *B);
    if (!B) return cli_fail("out of memory");
    const int st = sh_rot_band(a->band, a->m.method, a->m.prec, (sh_convention)a->conv, rot, B);
    if (st) {
        free(B);
        return cli_fail_status(st);
    }
    const double orth = sh_rot_block_orthogonality(B, (int)w, 0);
    *root = cli_put(*root, "band", json_integer(a->band));
    *root = cli_put(*root, "orthogonality_error", json_real(orth));
    *root = cli_put(*root, "matrix", cli_json_matrix(B, w, w));
    free(B);
    warn_if_inaccurate(a->m.method, a->m.prec, a->band, orth);
    return 0;
}

/* The blocks of the rotation, from a plan of the rotator (a rotation given
 * as angles reaches it as angles, any other form as its matrix,
 * sh_rot_plan_set_matrix: no angles); *kernel: the one it ran. */
static int blocks_of(const rotmat_args *a, const sh_rotation *rot, double *blocks, sh_rot_kernel *kernel)
{
    sh_rotator_opts o = SH_ROTATOR_OPTS(a->order);
    o.method = a->m.method;
    o.prec = a->m.prec;
    o.kernel = a->m.kernel;
    o.conv = (sh_convention)a->conv;
    o.threads = 1;
    sh_rotator *r = NULL;
    sh_rot_plan *p = NULL;
    int st = sh_rotator_create(&o, &r);
    if (!st) st = sh_rotator_plan(r, &p);
    if (!st) st = a->rot.form && !strcmp(a->rot.form, "euler") ? sh_rot_plan_set(p, rot) : sh_rot_plan_set_matrix(p, rot->R);
    if (!st) st = sh_rot_plan_blocks(p, blocks);
    if (r) *kernel = sh_rotator_kernel(r);
    sh_rot_plan_free(p);
    sh_rotator_free(r);
    return st;
}

/* The whole N²×N² matrix into root. */
static int whole(const rotmat_args *a, const cli_parsed *seen, const sh_rotation *rot, json_t **root)
{
    const int order = a->order;
    const size_t n = (size_t)order * order;
    double *blocks = malloc(sh_rot_block_offset(order) * sizeof *blocks), *M = malloc(n * n * sizeof *M);
    sh_rot_kernel kernel = SH_KERNEL_SCALAR;
    if (!blocks || !M) {
        free(blocks);
        free(M);
        return cli_fail("out of memory");
    }
    const int st = blocks_of(a, rot, blocks, &kernel);
    if (st) {
        free(blocks);
        free(M);
        return cli_fail_status(st);
    }
    if (cli_given(seen, "kernel")) *root = cli_put(*root, "kernel", json_string(sh_rot_kernel_name(kernel)));
    sh_rot_blocks_to_dense(order, blocks, M);
    double orth = 0;
    for (int l = 0; l < order; l++)
        orth = fmax(orth, sh_rot_block_orthogonality(blocks + sh_rot_block_offset(l), 2 * l + 1, 1));
    *root = cli_put(*root, "orthogonality_error", json_real(orth));
    *root = cli_put(*root, "matrix", cli_json_matrix(M, n, n));
    warn_if_inaccurate(a->m.method, a->m.prec, order - 1, orth);
    free(blocks);
    free(M);
    return 0;
}

static int run(int argc, char **argv)
{
    rotmat_args a = {.band = -1};
    cli_parsed seen;
    int rc = cli_args_parse(&rotmat_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a))) return rc;
    sh_rotation rot;
    if ((rc = cli_rotation_finish("rotmat", &a.rot, a.degrees, 0, NULL, &rot))) return rc;
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(a.order));
    root = cli_put(root, "method", json_string(sh_rot_method_name(a.m.method)));
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a.conv)));
    root = cli_put(root, "precision", json_string(sh_precision_name(a.m.prec)));
    if ((rc = a.band >= 0 ? one_band(&a, &rot, &root) : whole(&a, &seen, &rot, &root))) {
        json_decref(root);
        return rc;
    }
    cli_warn_approx_rotation("rotmat", a.m.method, a.band >= 0 ? a.band + 1 : a.order, &rot, a.degrees);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_rotmat = {"rotmat", run,
                                "SH rotation matrix of a rotation (exact methods and Taylor approximations)", &rotmat_decl};
