/* cmd_rotate.c — `shlab rotate`: rotate coefficient vectors (one plan,
 * applied to every channel). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_rotate;

static const char help[] =
    "Usage: shlab rotate ROTATION (--coeffs C0,C1,... | --in FILE) [OPTIONS]\n"
    "\n"
    "Rotate SH coefficients: the output are the coefficients of g(s) = f(R⁻¹s).\n"
    "\n"
    "  --coeffs LIST        n² numbers, comma or space separated\n"
    "  --in FILE            JSON {\"coeffs\":[...]} or {\"channels\":{\"R\":[...],...}},\n"
    "                       or plain numbers\n"
    "  --order N            number of bands (default: from the number of coefficients,\n"
    "                       which must then be a perfect square; with --order exactly N²)\n"
    "  --method M           auto (default) | z | ivanic | zxzxz | choi | blanco | wigner |\n"
    "                       reference | halfpi (exact) or taylor1 | taylor1.5 | taylor2\n"
    "                       (Krivánek et al.'s approximations).  auto: zxzxz up to\n"
    "                       order 32, halfpi above — both stay rotations at every\n"
    "                       band; ivanic and choi drift from l ~ 50 (see shlab\n"
    "                       stability) and are used only when named\n"
    "  --threads N          halfpi: threads over bands and channels (default: all\n"
    "                       cores; the result is the same for any N)\n"
    "  --precision P        double (default) | float\n"
    "  --kernel K           auto (default) | scalar | unrolled | sse2 | avx2 | avx512:\n"
    "                       the code that runs (unrolled kernels: zxzxz and taylor*,\n"
    "                       order <= 10; the others always run the scalar loops)\n"
    "Rotation (exactly one): --euler A,B,G | --quat W,X,Y,Z | --matrix R00,...,R22 |\n"
    "  --axis X,Y,Z --angle T;  --inverse, --orthonormalize, --degrees\n"
    "  (see shlab rotmat --help; --euler reaches the plan as angles, the other\n"
    "  forms as the matrix, sh_rot_plan_set_matrix)\n"
    "  --convention cs|nocs Condon-Shortley phase (cs, default) or not\n"
    "  --quiet              no note and no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "From order 128 on, one line on stderr says the method, threads and memory of\n"
    "the rotation before it starts (after the rotation is checked against the\n"
    "method), and progress lines follow while it runs (ivanic, choi, blanco and\n"
    "zxzxz take O(order³) or more: minutes at order 1000); a plan that would not\n"
    "fit in the memory available is refused.  halfpi keeps O(order) scratch per thread (the\n"
    "coefficients and their JSON text are the bulk); with --inverse it applies\n"
    "the transpose, so a round trip adds no rounding of the angles.\n"
    "\n"
    "JSON: {\"order\",\"method\",\"convention\",\"precision\",\"coeffs\":[...]} (or \"channels\"),\n"
    "      with --kernel also \"kernel\" (the one used)\n";

/* From this order on a run says, before it starts, what it will take. */
#define ROTATE_NOTE_ORDER 128
/* Bytes per coefficient for its parsed JSON number and printed text, on top
 * of the double (measured: peak RSS of rotate --in at order 1001). */
#define ROTATE_JSON_BYTES 105

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,     CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_CONVENTION, CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPTS_ROTATION,  CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_PRECISION,  CLI_LONGOPT_KERNEL,
                                         {"coeffs", required_argument, 0, 'k'},
                                         {"in", required_argument, 0, 'i'},
                                         {"threads", required_argument, 0, 't'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    cli_rotation_args ra = {0};
    sh_rot_method method;
    sh_precision prec = SH_PREC_DOUBLE;
    const char *coeff_arg = NULL, *in = NULL;
    int threads = 0, quiet = 0;
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
        case 't':
            if (cli_int("--threads", optarg, &threads)) return CLI_EXIT_USAGE;
            if (threads < 1 || threads > 1024) return cli_fail("--threads: %d out of range 1..1024", threads);
            break;
        case 'q': quiet = 1; break;
        default: {
            const int e = cli_common_opt(&cmd_rotate, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    prec = com.prec;
    if (optind < argc) return cli_fail("rotate: unexpected argument '%s'", argv[optind]);
    if (!coeff_arg == !in) return cli_fail("rotate: give exactly one of --coeffs and --in");
    /* halfpi applies the inverse as the transpose (exactly negated angles):
     * it gets the rotation without --inverse and the flag */
    cli_rotation_args ra_fwd = ra;
    ra_fwd.inverse = 0;
    sh_rotation rot, rot_fwd;
    int r = cli_rotation_finish("rotate", &ra, com.degrees, 0, NULL, &rot);
    if (!r) r = cli_rotation_finish("rotate", &ra_fwd, com.degrees, 0, NULL, &rot_fwd);
    if (r) return r;
    double *c = NULL;
    int n = 0, nchan = 1;
    char names[SH_IMAGE_MAX_CHANNELS][8] = {"Y"};
    if (coeff_arg) {
        if (cli_doubles("--coeffs", coeff_arg, &c, &n)) return CLI_EXIT_USAGE;
    } else if (cli_read_coeffs_file(in, com.order, &c, &n, &nchan, names)) {
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
    method = com.have_method ? com.method : sh_rot_method_default(order, 0);
    const double vec_bytes = (double)n * nchan * (sizeof(double) + ROTATE_JSON_BYTES);
    const int euler_form = ra.form && !strcmp(ra.form, "euler");
    const int note = order >= ROTATE_NOTE_ORDER && !quiet;
    cli_progress pg;
    cli_progress_start(&pg, "rotate", quiet);
    int st;
    sh_rot_kernel used = SH_KERNEL_SCALAR;
    if (method == SH_ROT_HALFPI && prec == SH_PREC_DOUBLE) { /* streamed, threads */
        sh_rot_stream *s = NULL;
        st = sh_rot_stream_create(order, com.conv, threads, &s);
        if (!st && note) {
            const int t = sh_rot_stream_threads(s);
            const double sb = (double)sh_rot_stream_bytes(order, t);
            fprintf(stderr,
                    "shlab: rotate: order %d, %d channel%s, method halfpi on %d thread%s: %.1f MB of "
                    "scratch, about %.0f MB with the coefficients and their JSON\n",
                    order, nchan, nchan > 1 ? "s" : "", t, t > 1 ? "s" : "", sb / 1e6, (sb + vec_bytes) / 1e6);
        }
        if (!st) {
            sh_rot_stream_set_progress(s, cli_progress_step, &pg);
            st = sh_rot_stream_apply(s, 1, &rot_fwd, ra.inverse, nchan, c, c);
        }
        sh_rot_stream_free(s);
    } else {
        /* the rotation checked against the method on a 2-band plan first (z
         * refuses a tilted one), so that a refusal is the only line */
        sh_rot_plan *p = NULL;
        st = sh_rot_plan_check(order, method, prec);
        if (!st) st = sh_rot_plan_create(order < 2 ? order : 2, method, prec, com.conv, &p);
        if (!st) st = euler_form ? sh_rot_plan_set(p, &rot) : sh_rot_plan_set_matrix(p, rot.R);
        sh_rot_plan_free(p);
        p = NULL;
        if (!st && note) {
            const double pb = (double)sh_rot_plan_bytes(order, method, prec);
            fprintf(stderr,
                    "shlab: rotate: order %d, %d channel%s, method %s (%s, one thread): %.1f MB for the "
                    "plan, about %.0f MB with the coefficients and their JSON\n",
                    order, nchan, nchan > 1 ? "s" : "", sh_rot_method_name(method), sh_precision_name(prec),
                    pb / 1e6, (pb + vec_bytes) / 1e6);
        }
        if (!st) st = sh_rot_plan_create_progress(order, method, prec, com.conv, com.kernel, cli_progress_step, &pg, &p);
        /* angles as angles, any other form as its matrix (sh_rot_plan_set_matrix) */
        if (!st) st = euler_form ? sh_rot_plan_set(p, &rot) : sh_rot_plan_set_matrix(p, rot.R);
        for (int k = 0; !st && k < nchan; k++) st = sh_rot_plan_apply(p, c + (size_t)k * n, c + (size_t)k * n);
        if (p) used = sh_rot_plan_kernel(p);
        sh_rot_plan_free(p);
    }
    if (st) { free(c); return cli_fail_status(st); }
    cli_warn_approx_rotation("rotate", method, order, &rot, com.degrees);
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

const cli_command cmd_rotate = {"rotate", run, "rotate SH coefficients (one plan, many channels)", help, NULL};
