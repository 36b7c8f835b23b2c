/* cmd_rotate.c — `shlab rotate`: rotate coefficient vectors (one rotator,
 * applied to every channel). */
#include "cli.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* From this order on a run says, before it starts, what it will take. */
#define ROTATE_NOTE_ORDER 128
/* Bytes per coefficient for its parsed JSON number and printed text, on top
 * of the double (measured: peak RSS of rotate --in at order 1001). */
#define ROTATE_JSON_BYTES 105
/* --threads: the high-band stream's threads (none given: every core) */
#define ROTATE_MAX_THREADS 1024

typedef struct {
    cli_rotation_args rot;
    cli_method_args m;
    const char *coeffs, *in;
    int order, threads, quiet, degrees, conv, fmt;
} rotate_args;

static const cli_opt rotate_opts[] = {
    CLI_STRING(rotate_args, coeffs, "coeffs", "LIST", "n² numbers, comma or space separated"),
    CLI_STRING(rotate_args, in, "in", "FILE",
               "JSON {\"coeffs\":[...]} or {\"channels\":{\"R\":[...],...}},\nor plain numbers"),
    CLI_ORDER(rotate_args, order, SHLAB_MAX_ORDER, NULL,
              "number of bands (default: from the number of coefficients,\n"
              "which must then be a perfect square; with --order exactly N²)"),
    CLI_GROUP(rotate_args, m, cli_method_opts),
    CLI_INT(rotate_args, threads, "threads", "N", 1, ROTATE_MAX_THREADS, NULL,
            "halfpi: threads over bands and channels (default: all\n"
            "cores; the result is the same for any N)"),
    CLI_CONVENTION(rotate_args, conv),
    CLI_FLAG(rotate_args, quiet, "quiet", "no note and no progress on stderr"),
    CLI_FORMAT(rotate_args, fmt),
    CLI_GROUP(rotate_args, rot, cli_rotation_opts),
    CLI_DEGREES(rotate_args, degrees, "angles in degrees (radians otherwise)"),
    CLI_END,
};

static const cli_cmd rotate_decl = {
    .name = "rotate",
    .usage = "rotate ROTATION (--coeffs C0,C1,... | --in FILE) [OPTIONS]",
    .about = "Rotate SH coefficients: the output are the coefficients of g(s) = f(R⁻¹s).\n",
    .opts = rotate_opts,
    .notes =
        "--method auto: zxzxz up to order 32, halfpi above — both stay rotations at\n"
        "every band; ivanic and choi drift from l ~ 50 (see shlab stability) and are\n"
        "used only when named.  --kernel: the unrolled kernels serve zxzxz and taylor*\n"
        "up to order 10; the others always run the scalar loops.  The rotation needs\n"
        "exactly one form (see shlab rotmat --help); --euler reaches the rotator as\n"
        "angles, the other forms as the matrix (sh_rotator_apply_matrix).\n"
        "\n"
        "From order 128 on, one line on stderr says the method, threads and memory of\n"
        "the rotation before it runs (after the rotation is checked against the\n"
        "method), and progress lines follow while it runs (ivanic, choi, blanco and\n"
        "zxzxz take O(order³) or more: minutes at order 1000); a rotation that would\n"
        "not fit in the memory available is refused.  halfpi keeps O(order) scratch\n"
        "per thread (the coefficients and their JSON text are the bulk); with\n"
        "--inverse it applies the transpose, so a round trip adds no rounding of the\n"
        "angles.\n"
        "\n"
        "JSON: {\"order\",\"method\",\"convention\",\"precision\",\"coeffs\":[...]} (or \"channels\"),\n"
        "      with --kernel also \"kernel\" (the one used)\n",
};

/* The coefficients read: nchan channels of n = order² values each. */
typedef struct {
    double *c;
    int n, nchan, order;
    char names[SH_IMAGE_MAX_CHANNELS][8];
} rotate_input;

/* --coeffs or --in, and the order they make (--order, or √n). */
static int read_input(const rotate_args *a, rotate_input *x)
{
    *x = (rotate_input){.nchan = 1, .names = {"Y"}};
    if (a->coeffs ? cli_doubles("--coeffs", a->coeffs, &x->c, &x->n)
                  : cli_read_coeffs_file(a->in, a->order, &x->c, &x->n, &x->nchan, x->names))
        return CLI_EXIT_USAGE;
    x->order = a->order;
    if (x->order && x->n != x->order * x->order) {
        free(x->c);
        return cli_fail("rotate: --order %d needs %d coefficients per channel, got %d", x->order,
                        x->order * x->order, x->n);
    }
    if (!x->order) x->order = (int)lround(sqrt((double)x->n));
    if (x->order * x->order != x->n || x->order < 1) {
        free(x->c);
        return cli_fail("rotate: %d coefficients is not a perfect square n²", x->n);
    }
    return 0;
}

/* The rotation as the rotator takes it: --euler as angles, any other form
 * as its matrix (no trigonometric call).  The stream (halfpi in double)
 * reads angles whatever the form, so it gets the ones the input made
 * rather than angles re-extracted from the matrix. */
static int apply(const sh_rotator *r, const sh_rotation *rot, int angles, unsigned flags, int nvec, double *c)
{
    if (angles || sh_rotator_streams(r)) return sh_rotator_apply(r, rot, flags, nvec, c, c);
    return sh_rotator_apply_matrix(r, rot->R, flags, nvec, c, c);
}

/* What rotate says on stderr: progress, and from order ROTATE_NOTE_ORDER
 * one note first — said at the first progress report (the library reports
 * only once the rotation's arguments and memory are checked) or, when the
 * rotator is built without one, just before the rotation runs.  A refusal
 * therefore stays the only line. */
typedef struct {
    cli_progress pg;
    char note[512];
} rotate_say;

static void say_note(rotate_say *s)
{
    if (s->note[0]) fputs(s->note, stderr);
    s->note[0] = '\0';
}

static void on_progress(void *ctx, int done, int total, const char *what)
{
    rotate_say *s = ctx;
    say_note(s);
    cli_progress_step(&s->pg, done, total, what);
}

/* A rotator of at most two bands with the options of the full one: it
 * checks the rotation against the method (z refuses a tilted one) before
 * anything large is built, and tells the path (the high-band stream or a
 * plan) and the threads the full rotator will take, for the note. */
static int probe(const sh_rotator_opts *o, const sh_rotation *rot, int angles, unsigned flags, int *streams,
                 int *threads)
{
    sh_rotator_opts small = *o;
    small.order = o->order < 2 ? o->order : 2;
    small.progress = NULL;
    double v[4] = {0};
    sh_rotator *r;
    int st = sh_rotator_create(&small, &r);
    if (!st) st = apply(r, rot, angles, flags, 1, v);
    if (!st) *streams = sh_rotator_streams(r), *threads = sh_rotator_threads(r);
    sh_rotator_free(r);
    return st;
}

/* The note: method, threads and memory (the stream's scratch, or the plan's
 * tables and state). */
static void write_note(char *buf, size_t size, const sh_rotator_opts *o, int streams, int t, const rotate_input *x)
{
    const double vec = (double)x->n * x->nchan * (sizeof(double) + ROTATE_JSON_BYTES);
    const char *chs = x->nchan > 1 ? "s" : "";
    if (streams) {
        const double sb = (double)sh_rot_stream_bytes(x->order, t);
        snprintf(buf, size,
                 "shlab: rotate: order %d, %d channel%s, method halfpi on %d thread%s: %.1f MB of scratch, "
                 "about %.0f MB with the coefficients and their JSON\n",
                 x->order, x->nchan, chs, t, t > 1 ? "s" : "", sb / 1e6, (sb + vec) / 1e6);
    } else {
        const double pb = (double)sh_rot_plan_bytes(x->order, o->method, o->prec);
        snprintf(buf, size,
                 "shlab: rotate: order %d, %d channel%s, method %s (%s, one thread): %.1f MB for the plan, "
                 "about %.0f MB with the coefficients and their JSON\n",
                 x->order, x->nchan, chs, sh_rot_method_name(o->method), sh_precision_name(o->prec), pb / 1e6,
                 (pb + vec) / 1e6);
    }
}

/* Rotate every channel in place by one rotator (it picks plan or stream);
 * *kernel: the one it ran. */
static int rotate(const rotate_args *a, sh_rot_method method, const sh_rotation *fwd, int inverse, rotate_input *x,
                  sh_rot_kernel *kernel)
{
    rotate_say say = {.note = ""};
    cli_progress_start(&say.pg, "rotate", a->quiet);
    sh_rotator_opts o = SH_ROTATOR_OPTS(x->order);
    o.method = method;
    o.prec = a->m.prec;
    o.kernel = a->m.kernel;
    o.conv = (sh_convention)a->conv;
    o.threads = a->threads;
    o.progress = on_progress;
    o.progress_ctx = &say;
    const int angles = a->rot.form && !strcmp(a->rot.form, "euler");
    const unsigned flags = inverse ? SH_ROTATE_INVERSE : 0;
    int streams = 0, threads = 1;
    sh_rotator *r = NULL;
    int st = probe(&o, fwd, angles, flags, &streams, &threads);
    if (!st && x->order >= ROTATE_NOTE_ORDER && !a->quiet) write_note(say.note, sizeof say.note, &o, streams, threads, x);
    if (!st) st = sh_rotator_create(&o, &r);
    if (!st) say_note(&say);
    if (!st) st = apply(r, fwd, angles, flags, x->nchan, x->c);
    if (r) *kernel = sh_rotator_kernel(r);
    sh_rotator_free(r);
    return st ? cli_fail_status(st) : 0;
}

static json_t *result(const rotate_args *a, const cli_parsed *seen, const rotate_input *x, sh_rot_method method,
                      sh_rot_kernel kernel)
{
    json_t *root = json_object();
    root = cli_put(root, "order", json_integer(x->order));
    root = cli_put(root, "method", json_string(sh_rot_method_name(method)));
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    root = cli_put(root, "precision", json_string(sh_precision_name(a->m.prec)));
    if (cli_given(seen, "kernel")) root = cli_put(root, "kernel", json_string(sh_rot_kernel_name(kernel)));
    if (x->nchan == 1 && !strcmp(x->names[0], "Y"))
        return cli_put(root, "coeffs", cli_json_array(x->c, (size_t)x->n));
    json_t *ch = json_object();
    for (int k = 0; k < x->nchan && ch; k++)
        ch = cli_put(ch, x->names[k], cli_json_array(x->c + (size_t)k * x->n, (size_t)x->n));
    return cli_put(root, "channels", ch);
}

static int run(int argc, char **argv)
{
    rotate_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&rotate_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!a.coeffs == !a.in) return cli_fail("rotate: give exactly one of --coeffs and --in");
    /* --inverse goes to the rotator as a flag: halfpi then applies the
     * transpose (the exactly negated angles), the others Rᵀ */
    const int inverse = a.rot.inverse;
    a.rot.inverse = 0;
    sh_rotation fwd, rot;
    if ((rc = cli_rotation_finish("rotate", &a.rot, a.degrees, 0, NULL, &fwd))) return rc;
    rot = fwd;
    if (inverse) sh_rotation_inverse(&fwd, &rot);
    rotate_input x;
    if ((rc = read_input(&a, &x))) return rc;
    /* auto by order (sh_rot_method_default: the rotator's own rule), named
     * here so that the note can say it before the rotator is built */
    const sh_rot_method method = a.m.method == SH_ROT_AUTO ? sh_rot_method_default(x.order, 0) : a.m.method;
    sh_rot_kernel kernel = SH_KERNEL_SCALAR;
    if ((rc = rotate(&a, method, &fwd, inverse, &x, &kernel))) {
        free(x.c);
        return rc;
    }
    cli_warn_approx_rotation("rotate", method, x.order, &rot, a.degrees);
    json_t *root = result(&a, &seen, &x, method, kernel);
    free(x.c);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_rotate = {"rotate", run, "rotate SH coefficients (one plan, many channels)", &rotate_decl};
