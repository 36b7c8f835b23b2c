/* rotator.c — the front door of rotation: one immutable object per
 * (order, method, precision, kernel, convention, threads), created once,
 * shared by any number of threads.
 *
 * sh_rotator_create checks its arguments once (order within the library's
 * and the method's limits, the kernel available here, the memory of the
 * tables and of one plan), resolves `auto` (the method by order,
 * sh_rot_method_default; the widest kernel this CPU runs) and builds the
 * method's per-order tables.  After that nothing in the rotator is written:
 * the per-rotation state (the rotation, its blocks or multiple angles, the
 * scratch) lives in a plan (sh_rotator_plan, one per thread, rotation_plan.c)
 * or, for the one-shot calls below, on the caller's stack or in a plan made
 * and freed inside the call.
 *
 * Paths.  Orders and methods with unrolled kernels (zxzxz and the Taylor
 * methods to order 10, ivanic to 6) run the generated straight-line code
 * (rot_fast.c) chosen here; the other block and sparse methods run their loop
 * kernels; halfpi in double, the high-band method, runs as the threaded
 * stream (rotation_stream.c: all bands, O(order) scratch per thread).  The
 * caller no longer chooses between plan and stream.
 *
 * Cost of creating one: a few small allocations and no system call — the
 * kernel's CPU features are read once per process (rotation_kernels.c), and
 * memory is checked against the machine only for requests large enough to
 * matter (sh__mem_check).  The legacy sh_rot_plan_create is a rotator and
 * a plan in one object.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_finite.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int sh__rot_check_args(int order, sh_rot_method method, sh_precision prec, sh_convention conv)
{
    int st = sh_check_order(order);
    if (st) return st;
    const sh__rot_ops *ops = sh__rot_ops_of(method);
    if (!ops) return sh_error(SH_EINVAL, "rotation: unknown or unavailable method");
    if (order > ops->max_order)
        return sh_error(SH_EINVAL, "method %s: order %d exceeds its limit %d", sh_rot_method_name(method), order,
                        ops->max_order);
    if (prec != SH_PREC_DOUBLE && prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation: unknown precision");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "rotation: unknown convention");
    return SH_OK;
}

/* ---- sizes -------------------------------------------------------------------- */

double sh__rot_tables_bytes(int order, const sh__rot_ops *ops, sh_precision prec)
{
    const double esz = prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    return ops->tables_bytes ? (double)ops->tables_bytes(order) * (esz / sizeof(double)) : 0;
}

/* One plan: the blocks (methods without a sparse apply; the sparse ones build
 * blocks only when asked), scratch, per-rotation state and the vector copies. */
static double state_bytes(int order, const sh__rot_ops *ops, sh_precision prec)
{
    const double esz = prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    const double nb = (double)sh_rot_block_offset(order), nc = (double)order * order;
    double b = (ops->apply_d ? 0 : nb * esz) + nc * sizeof(double) + 2 * nc * esz; /* blocks, vtmp, vin, vout */
    if (ops->work_bytes) b += (double)ops->work_bytes(order);
    if (ops->state_bytes) b += (double)ops->state_bytes(order);
    return b;
}

double sh__rot_plan_state_bytes(const sh_rotator *r)
{
    double b = state_bytes(r->order, r->ops, r->prec);
    if (r->stream) b += (double)sh_rot_stream_bytes(r->order, r->threads);
    return b;
}

size_t sh_rot_plan_bytes(int order, sh_rot_method method, sh_precision prec)
{
    const sh__rot_ops *ops = sh__rot_ops_of(method);
    if (order < 1 || !ops) return 0;
    const double b = state_bytes(order, ops, prec) + sh__rot_tables_bytes(order, ops, prec);
    return b >= (double)SIZE_MAX ? SIZE_MAX : (size_t)b;
}

static int mem_check(int order, sh_rot_method method, sh_precision prec, double bytes)
{
    char what[96];
    snprintf(what, sizeof what, "rotation plan (method %s, %s, order %d)", sh_rot_method_name(method),
             sh_precision_name(prec), order);
    return sh__mem_check(bytes, what);
}

int sh_rot_plan_check(int order, sh_rot_method method, sh_precision prec)
{
    int st = sh__rot_check_args(order, method, prec, SH_CS);
    if (st) return st;
    return mem_check(order, method, prec, (double)sh_rot_plan_bytes(order, method, prec));
}

/* ---- progress of the long steps --------------------------------------------------
 * The methods' band loops (tables and blocks: O(order³) or more) call
 * sh__rot_band_done; it reports to the rotator whose tables or rotation this
 * thread is computing, if that rotator has a progress function. */
static _Thread_local const sh_rotator *progress_rotator;
static _Thread_local const char *progress_what;

sh__rot_progress_scope sh__rot_progress_enter(const sh_rotator *r, const char *what)
{
    const sh__rot_progress_scope outer = {progress_rotator, progress_what};
    progress_rotator = r->progress ? r : NULL;
    progress_what = what;
    return outer;
}

void sh__rot_progress_leave(sh__rot_progress_scope outer)
{
    progress_rotator = outer.r;
    progress_what = outer.what;
}

void sh__rot_band_done(int done, int total)
{
    const sh_rotator *r = progress_rotator;
    if (r) r->progress(r->progress_ctx, done, total, progress_what);
}

/* ---- create ------------------------------------------------------------------- */

/* The kernel: the unrolled code of (method, order) in the chosen variant, or
 * the loop kernels when there is none (then the kernel is `scalar`) — but a
 * method with its own batch kernel per instruction set (ops->rotate_many:
 * direct) keeps the kernel chosen, which its batches use. */
static void choose_kernel(sh_rotator *r, sh_rot_kernel kernel)
{
    r->kernel = kernel == SH_KERNEL_AUTO ? sh__rot_kernel_auto() : kernel;
    sh__rot_kernel_tables(r->kernel, &r->fd1, &r->fdv, &r->ff1, &r->ffv);
    r->fmeth = r->stream ? -1 : sh__rot_fast_method(r->method);
    const sh__rot_ops *ops = sh__rot_ops_of(r->method);
    const int own_batch = !r->stream && ops && ops->rotate_many_d;
    if (r->kernel == SH_KERNEL_SCALAR || r->fmeth < 0 || r->order > r->fd1->max_order ||
        !r->fd1->fn[r->fmeth][r->order]) {
        r->fmeth = -1;
        if (!own_batch) r->kernel = SH_KERNEL_SCALAR;
    }
    r->nb = r->method == SH_ROT_TAYLOR1 || r->method == SH_ROT_TAYLOR15 || r->method == SH_ROT_TAYLOR2;
    if (r->fmeth >= 0) {
        if (r->prec == SH_PREC_FLOAT) r->fn_f = r->ff1->fn[r->fmeth][r->order];
        else r->fn_d = r->fd1->fn[r->fmeth][r->order];
        r->fn_mults = r->prec == SH_PREC_FLOAT ? r->ff1->mults[r->fmeth][r->order] : r->fd1->mults[r->fmeth][r->order];
    }
}

/* The method's own one-vector kernel, if it has one for r's order, precision
 * and kernel (after choose_kernel). */
static void choose_one_vector(sh_rotator *r)
{
    if (!r->ops) return;
    if (!r->stream && r->fmeth < 0) {
        if (r->prec == SH_PREC_FLOAT && r->ops->one_f)
            r->one_f = r->ops->one_f(r->order, r->conv == SH_NOCS, r->kernel, &r->one_mults);
        else if (r->prec == SH_PREC_DOUBLE && r->ops->one_d)
            r->one_d = r->ops->one_d(r->order, r->conv == SH_NOCS, r->kernel, &r->one_mults);
    } else if (r->fmeth == SH__FAST_ZXZXZ && r->prec == SH_PREC_FLOAT && r->ops->one_f) {
        /* zxzxz's one-vector kernel (zxzxz_one.c), where it has one for this
         * order and kernel, in place of the unrolled one: it reads R */
        uint64_t m = 0;
        const sh__rot_one_fn_f f = r->ops->one_f(r->order, r->conv == SH_NOCS, r->kernel, &m);
        if (f) r->one_f = f, r->one_mults = m, r->one_mat = 1, r->fn_f = NULL;
    }
}

int sh__rot_one_vector(int order, sh_rot_method method, sh_precision prec, sh_rot_kernel kernel)
{
    if (kernel < 0 || kernel >= SH_KERNEL_N || order < 1 || method < 0 || method >= SH_ROT_NMETHODS ||
        order > sh_rot_method_max_order(method) || (prec != SH_PREC_FLOAT && prec != SH_PREC_DOUBLE))
        return 0;
    sh_rotator r = {.order = order, .method = method, .prec = prec, .conv = SH_CS, .ops = sh__rot_ops_of(method)};
    choose_kernel(&r, kernel);
    choose_one_vector(&r);
    return r.one_f || r.one_d;
}

sh_rot_kernel sh_rot_plan_kernel_for(int order, sh_rot_method method, sh_rot_kernel kernel)
{
    if (kernel < 0 || kernel >= SH_KERNEL_N || order < 1 || method < 0 || method >= SH_ROT_NMETHODS)
        return SH_KERNEL_SCALAR;
    sh_rotator r = {.order = order, .method = method};
    choose_kernel(&r, kernel);
    return r.kernel;
}

/* Both front doors: stream = 1 lets halfpi in double run as the stream. */
static int rotator_new(const sh_rotator_opts *o, int stream, sh_rotator **out)
{
    *out = NULL;
    const sh_rot_method method = o->method == SH_ROT_AUTO ? sh_rot_method_default(o->order, 0) : o->method;
    int st = sh__rot_check_args(o->order, method, o->prec, o->conv);
    if (st) return st;
    if (o->kernel < 0 || o->kernel >= SH_KERNEL_N) return sh_error(SH_EINVAL, "rotation: unknown kernel");
    if (!sh_rot_kernel_available(o->kernel))
        return sh_error(SH_ENOTSUP, "kernel %s is not available on this machine", sh_rot_kernel_name(o->kernel));
    if (o->threads < 0) return sh_error(SH_EINVAL, "rotation: %d threads", o->threads);
    sh_rotator *r = calloc(1, sizeof *r);
    if (!r) return sh_error(SH_ENOMEM, "rotation: out of memory");
    r->order = o->order;
    r->method = method;
    r->prec = o->prec;
    r->conv = o->conv;
    r->ops = sh__rot_ops_of(method);
    r->stream = stream && method == SH_ROT_HALFPI && o->prec == SH_PREC_DOUBLE;
    r->threads = 1;
    if (r->stream) r->threads = sh__rot_stream_resolve_threads(o->threads);
    r->progress = o->progress;
    r->progress_ctx = o->progress_ctx;
    choose_kernel(r, o->kernel);
    choose_one_vector(r);
    if ((st = mem_check(r->order, method, r->prec, sh__rot_plan_state_bytes(r) +
                                                         sh__rot_tables_bytes(r->order, r->ops, r->prec)))) {
        free(r);
        return st;
    }
    int (*tnew)(int, void **) = r->prec == SH_PREC_FLOAT ? r->ops->tables_new_f : r->ops->tables_new_d;
    /* tables for the loop kernels (and for unrolled ivanic's batches, which
     * build the blocks once per rotation) */
    if ((r->fmeth < 0 || r->fmeth == SH__FAST_IVANIC) && tnew) {
        const sh__rot_progress_scope outer = sh__rot_progress_enter(r, "bands of the tables");
        st = tnew(r->order, &r->tables);
        sh__rot_progress_leave(outer);
        if (st) {
            free(r);
            return st;
        }
    }
    *out = r;
    return SH_OK;
}

int sh_rotator_create(const sh_rotator_opts *o, sh_rotator **out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_rotator_create: no output");
    if (!o) return sh_error(SH_EINVAL, "sh_rotator_create: no options");
    return rotator_new(o, 1, out);
}

void sh_rotator_free(sh_rotator *r)
{
    if (!r) return;
    if (r->tables && r->ops->tables_free) r->ops->tables_free(r->tables);
    free(r);
}

int sh_rotator_order(const sh_rotator *r) { return r->order; }
sh_rot_method sh_rotator_method(const sh_rotator *r) { return r->method; }
sh_precision sh_rotator_precision(const sh_rotator *r) { return r->prec; }
sh_rot_kernel sh_rotator_kernel(const sh_rotator *r) { return r->kernel; }
int sh_rotator_threads(const sh_rotator *r) { return r->threads; }
int sh_rotator_streams(const sh_rotator *r) { return r->stream; }

size_t sh_rotator_bytes(const sh_rotator *r, size_t *per_plan)
{
    if (per_plan) *per_plan = (size_t)sh__rot_plan_state_bytes(r);
    return sizeof *r + (size_t)sh__rot_tables_bytes(r->order, r->ops, r->prec);
}

/* ---- the legacy door: a rotator and one plan in one object --------------------- */

int sh_rot_plan_create(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                       sh_rot_plan **out)
{
    return sh_rot_plan_create_kernel(order, method, prec, conv, SH_KERNEL_AUTO, out);
}

int sh_rot_plan_create_kernel(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                              sh_rot_kernel kernel, sh_rot_plan **out)
{
    return sh_rot_plan_create_progress(order, method, prec, conv, kernel, NULL, NULL, out);
}

int sh_rot_plan_create_progress(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                                sh_rot_kernel kernel, sh_progress_fn fn, void *ctx, sh_rot_plan **out)
{
    *out = NULL;
    if (method == SH_ROT_AUTO) return sh_error(SH_EINVAL, "rotation plan: name a method (or use sh_rotator_create)");
    const sh_rotator_opts o = {.order = order, .method = method, .prec = prec, .kernel = kernel, .conv = conv,
                               .progress = fn, .progress_ctx = ctx};
    sh_rotator *r;
    int st = rotator_new(&o, 0, &r); /* halfpi stays a plan: one thread, as it always was */
    if (st) return st;
    if ((st = sh__rot_plan_new(r, 1, out))) sh_rotator_free(r);
    return st;
}

/* ---- one rotation, one call ---------------------------------------------------- */

/* The rotation's input forms for the one-shot calls. */
typedef struct {
    const sh_rotation *rot; /* angles (and matrix) */
    const double *Rd;       /* or a double matrix */
    const float *Rf;        /* or a float matrix */
} rot_in;

static int set_in(sh_rot_plan *p, const rot_in *in, int inverse)
{
    if (in->rot) {
        if (!inverse) return sh_rot_plan_set(p, in->rot);
        sh_rotation inv;
        sh_rotation_inverse(in->rot, &inv);
        return sh_rot_plan_set(p, &inv);
    }
    if (in->Rd) {
        double T[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) T[3 * i + j] = inverse ? in->Rd[3 * j + i] : in->Rd[3 * i + j];
        return sh_rot_plan_set_matrix(p, T);
    }
    float T[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) T[3 * i + j] = inverse ? in->Rf[3 * j + i] : in->Rf[3 * i + j];
    return sh_rot_plan_set_matrix_f(p, T);
}

/* The stream: all nvec vectors in one call on the rotator's threads; the
 * inverse as the exactly negated angles (sh_rot_stream_apply). */
static int stream_apply(const sh_rotator *r, const rot_in *in, int inverse, int nvec, const double *x, double *y)
{
    sh_rotation rot;
    if (in->rot) {
        rot = *in->rot;
    } else {
        int st = sh_rotation_from_matrix(in->Rd, 1, &rot);
        if (st) return st;
    }
    sh_rot_stream *s;
    int st = sh_rot_stream_create(r->order, r->conv, r->threads, &s);
    if (st) return st;
    if (r->progress) sh_rot_stream_set_progress(s, r->progress, r->progress_ctx);
    if (x != y) memcpy(y, x, sizeof *y * (size_t)nvec * r->order * r->order);
    st = sh_rot_stream_apply(s, 1, &rot, inverse, nvec, y, y);
    sh_rot_stream_free(s);
    return st;
}

static int apply_in(const sh_rotator *r, const rot_in *in, unsigned flags, int nvec, const double *x, double *y)
{
    if (!r || !x || !y) return sh_error(SH_EINVAL, "sh_rotator_apply: NULL argument");
    if (flags & ~(unsigned)SH_ROTATE_INVERSE) return sh_error(SH_EINVAL, "sh_rotator_apply: unknown flags %#x", flags);
    if (nvec < 1) return sh_error(SH_EINVAL, "sh_rotator_apply: %d vectors", nvec);
    const int inverse = (flags & SH_ROTATE_INVERSE) != 0;
    if (r->stream) return stream_apply(r, in, inverse, nvec, x, y);
    const size_t nc = (size_t)r->order * r->order;
    if (r->fn_d && in->Rd && !inverse && nvec == 1) { /* unrolled, one vector: nothing to allocate */
        double par[SH__PAR_N];
        int st = sh__rot_plan_par_matrix_d(r, in->Rd, par);
        if (st) return st;
        r->fn_d(par, 1, x, y, 1);
        return SH_OK;
    }
    sh_rot_plan *p;
    int st = sh__rot_plan_new(r, 0, &p);
    if (!st) st = set_in(p, in, inverse);
    for (int v = 0; !st && v < nvec; v++) st = sh_rot_plan_apply(p, x + v * nc, y + v * nc);
    sh_rot_plan_free(p);
    return st;
}

int sh_rotator_apply(const sh_rotator *r, const sh_rotation *rot, unsigned flags, int nvec, const double *in,
                     double *out)
{
    if (!rot) return sh_error(SH_EINVAL, "sh_rotator_apply: no rotation");
    const rot_in ri = {.rot = rot};
    return apply_in(r, &ri, flags, nvec, in, out);
}

int sh_rotator_apply_matrix(const sh_rotator *r, const double R[9], unsigned flags, int nvec, const double *in,
                            double *out)
{
    if (!R) return sh_error(SH_EINVAL, "sh_rotator_apply_matrix: no matrix");
    const rot_in ri = {.Rd = R};
    return apply_in(r, &ri, flags, nvec, in, out);
}

int sh_rotator_apply_matrix_f(const sh_rotator *r, const float R[9], const float *in, float *out)
{
    if (!r || !R || !in || !out) return sh_error(SH_EINVAL, "sh_rotator_apply_matrix_f: NULL argument");
    if (r->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "sh_rotator_apply_matrix_f: a double rotator");
    if (r->one_mat) { /* the one-vector kernel reads R itself */
        if (!sh__finite9_f(R)) return sh_error(SH_EINVAL, "sh_rotator_apply_matrix_f: matrix entries must be finite");
        r->one_f(R, in, out);
        return SH_OK;
    }
    if (r->fn_f && r->fmeth != SH__FAST_IVANIC) { /* unrolled: nothing to allocate */
        float par[SH__PAR_N];
        int st = sh__rot_plan_par_matrix_f(r, R, par);
        if (st) return st;
        r->fn_f(par, 1, in, out, 1);
        return SH_OK;
    }
    sh_rot_plan *p;
    int st = sh__rot_plan_new(r, 0, &p);
    if (!st) st = sh_rot_plan_set_matrix_f(p, R);
    if (!st) st = sh_rot_plan_apply_f(p, in, out);
    sh_rot_plan_free(p);
    return st;
}
