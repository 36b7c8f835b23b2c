/* rotation_plan.c — the rotation plan: one object per (order, method,
 * precision, convention) that owns the method's per-order tables, its scratch
 * space and the current rotation's blocks, and applies it to vectors.
 *
 * The methods register here (one ops table each, defined in the method's own
 * file, see rot_internal.h).  Every method computes in the CS convention; the
 * plan turns the result into nocs by the sign flip S·R·S (S = −1 on odd m).
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h" /* SH_PRAGMA */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const sh__rot_ops *const methods[SH_ROT_NMETHODS] = {
    [SH_ROT_Z] = &sh__rot_z_ops,
    [SH_ROT_IVANIC] = &sh__rot_ivanic_ops,
    [SH_ROT_ZXZXZ] = &sh__rot_zxzxz_ops,
    [SH_ROT_CHOI] = &sh__rot_choi_ops,
    [SH_ROT_BLANCO] = &sh__rot_blanco_ops,
    [SH_ROT_WIGNER] = &sh__rot_wigner_ops,
    [SH_ROT_REFERENCE] = &sh__rot_reference_ops,
    [SH_ROT_TAYLOR1] = &sh__rot_taylor1_ops, [SH_ROT_TAYLOR15] = &sh__rot_taylor15_ops, [SH_ROT_TAYLOR2] = &sh__rot_taylor2_ops,
    [SH_ROT_HALFPI] = &sh__rot_halfpi_ops,
};

static const char *const method_names[SH_ROT_NMETHODS] = {
    [SH_ROT_Z] = "z",           [SH_ROT_IVANIC] = "ivanic", [SH_ROT_ZXZXZ] = "zxzxz",
    [SH_ROT_CHOI] = "choi",     [SH_ROT_BLANCO] = "blanco", [SH_ROT_WIGNER] = "wigner",
    [SH_ROT_REFERENCE] = "reference", [SH_ROT_TAYLOR1] = "taylor1", [SH_ROT_TAYLOR15] = "taylor1.5",
    [SH_ROT_TAYLOR2] = "taylor2", [SH_ROT_HALFPI] = "halfpi",
};

const char *sh_rot_method_name(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS) ? method_names[m] : "?";
}

int sh_rot_method_parse(const char *s, sh_rot_method *out)
{
    for (int m = 0; m < SH_ROT_NMETHODS; m++)
        if (s && !strcmp(s, method_names[m])) {
            if (!methods[m]) return sh_error(SH_ENOTSUP, "method '%s' is not built in", s);
            *out = (sh_rot_method)m;
            return SH_OK;
        }
    return sh_error(SH_EINVAL,
                    "unknown method '%s' (z, ivanic, zxzxz, choi, blanco, wigner, reference, "
                    "halfpi, taylor1, taylor1.5, taylor2)",
                    s ? s : "");
}

sh_rot_method sh_rot_method_default(int order, int one_band)
{
    if (one_band) return SH_ROT_BLANCO;
    return order <= SH_ROT_DEFAULT_ZXZXZ_MAX ? SH_ROT_ZXZXZ : SH_ROT_HALFPI;
}

int sh_rot_method_is_exact(sh_rot_method m)
{
    return m >= 0 && m < SH_ROT_NMETHODS && methods[m] && !methods[m]->approximate;
}

const char *sh_precision_name(sh_precision p) { return p == SH_PREC_FLOAT ? "float" : "double"; }

int sh_precision_parse(const char *s, sh_precision *out)
{
    if (s && !strcmp(s, "double")) *out = SH_PREC_DOUBLE;
    else if (s && !strcmp(s, "float")) *out = SH_PREC_FLOAT;
    else return sh_error(SH_EINVAL, "unknown precision '%s' (float or double)", s ? s : "");
    return SH_OK;
}

int sh_rot_method_max_order(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS && methods[m]) ? methods[m]->max_order : 0;
}

/* ---------------------------------------------------------------- kernels
 * Which code runs a plan (sh_rot_kernel, rotate.h).  The unrolled kernels
 * (rot_fast.c, generated straight-line code for zxzxz and the Taylor methods
 * up to order SH_UNROLLED_MAX_ORDER) exist as one object per variant: the
 * plain one (default flags, one lane) and, on x86-64, one per ISA — `avx2`
 * and `avx512` (one lane, AVX2 + FMA, or AVX-512's 32 registers) and the
 * SIMD-lane objects `sse2v`, `avx2v`, `avx512v` used for batches
 * (rot_simd.h).  A variant is used only if it is
 * compiled in and the CPU runs it (CPUID, and XGETBV for the OS saving the
 * YMM/ZMM registers); the choice is made in plan create and kept in the
 * plan, so no global state is written after start-up. */
extern const sh__rot_fast_d sh__rot_fast_base_d;
extern const sh__rot_fast_f sh__rot_fast_base_f;
#if defined(__x86_64__)
#define SH_FAST_X86 1
#include <cpuid.h>
extern const sh__rot_fast_d sh__rot_fast_avx2_d, sh__rot_fast_avx512_d, sh__rot_fast_sse2v_d,
    sh__rot_fast_avx2v_d, sh__rot_fast_avx512v_d;
extern const sh__rot_fast_f sh__rot_fast_avx2_f, sh__rot_fast_avx512_f, sh__rot_fast_sse2v_f,
    sh__rot_fast_avx2v_f, sh__rot_fast_avx512v_f;

static unsigned long long xcr0(void)
{
    unsigned a, d;
    __asm__ volatile("xgetbv" : "=a"(a), "=d"(d) : "c"(0));
    return ((unsigned long long)d << 32) | a;
}
#endif

static const char *const kernel_names[SH_KERNEL_N] = {
    [SH_KERNEL_AUTO] = "auto",  [SH_KERNEL_SCALAR] = "scalar", [SH_KERNEL_UNROLLED] = "unrolled",
    [SH_KERNEL_SSE2] = "sse2",  [SH_KERNEL_AVX2] = "avx2",     [SH_KERNEL_AVX512] = "avx512",
};

const char *sh_rot_kernel_name(sh_rot_kernel k)
{
    return (k >= 0 && k < SH_KERNEL_N) ? kernel_names[k] : "?";
}

int sh_rot_kernel_parse(const char *s, sh_rot_kernel *out)
{
    for (int k = 0; k < SH_KERNEL_N; k++)
        if (s && !strcmp(s, kernel_names[k])) {
            *out = (sh_rot_kernel)k;
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown kernel '%s' (auto, scalar, unrolled, sse2, avx2, avx512)",
                    s ? s : "");
}

int sh_rot_kernel_available(sh_rot_kernel k)
{
    switch (k) {
    case SH_KERNEL_AUTO:
    case SH_KERNEL_SCALAR:
    case SH_KERNEL_UNROLLED: return 1;
#ifdef SH_FAST_X86
    case SH_KERNEL_SSE2: return 1; /* x86-64 baseline */
    case SH_KERNEL_AVX2:
    case SH_KERNEL_AVX512: {
        unsigned a, b, c, d;
        if (!__get_cpuid(1, &a, &b, &c, &d)) return 0;
        const int fma = (c & bit_FMA) != 0, osxsave = (c & bit_OSXSAVE) != 0, avx = (c & bit_AVX) != 0;
        if (!fma || !osxsave || !avx || __get_cpuid_max(0, NULL) < 7) return 0;
        const unsigned long long x = xcr0();
        __cpuid_count(7, 0, a, b, c, d);
        if (k == SH_KERNEL_AVX2) return (x & 6) == 6 && (b & bit_AVX2) != 0; /* XMM, YMM saved */
        return (x & 0xe6) == 0xe6 && (b & bit_AVX2) && (b & bit_AVX512F) && (b & bit_AVX512VL); /* + opmask, ZMM */
    }
#endif
    default: return 0;
    }
}

/* AUTO: the widest the CPU runs — AVX-512 (for one rotation its 32
 * registers, for batches 16 float lanes: both measured fastest, README
 * "Rotation speed"), else AVX2, else SSE2, else the plain unrolled code. */
static sh_rot_kernel kernel_auto(void)
{
    if (sh_rot_kernel_available(SH_KERNEL_AVX512)) return SH_KERNEL_AVX512;
    if (sh_rot_kernel_available(SH_KERNEL_AVX2)) return SH_KERNEL_AVX2;
    if (sh_rot_kernel_available(SH_KERNEL_SSE2)) return SH_KERNEL_SSE2;
    return SH_KERNEL_UNROLLED;
}

/* the unrolled tables of kernel k: one lane (single vectors) and SIMD lanes
 * (batches) */
static void kernel_tables(sh_rot_kernel k, const sh__rot_fast_d **d1, const sh__rot_fast_d **dv,
                          const sh__rot_fast_f **f1, const sh__rot_fast_f **fv)
{
    *d1 = *dv = &sh__rot_fast_base_d;
    *f1 = *fv = &sh__rot_fast_base_f;
#ifdef SH_FAST_X86
    switch (k) {
    case SH_KERNEL_SSE2: *dv = &sh__rot_fast_sse2v_d, *fv = &sh__rot_fast_sse2v_f; break;
    case SH_KERNEL_AVX2:
        *d1 = &sh__rot_fast_avx2_d, *f1 = &sh__rot_fast_avx2_f;
        *dv = &sh__rot_fast_avx2v_d, *fv = &sh__rot_fast_avx2v_f;
        break;
    case SH_KERNEL_AVX512:
        *d1 = &sh__rot_fast_avx512_d, *f1 = &sh__rot_fast_avx512_f;
        *dv = &sh__rot_fast_avx512v_d, *fv = &sh__rot_fast_avx512v_f;
        break;
    default: break;
    }
#else
    (void)k;
#endif
}

static int fast_method(sh_rot_method m)
{
    switch (m) {
    case SH_ROT_ZXZXZ: return SH__FAST_ZXZXZ;
    case SH_ROT_TAYLOR1: return SH__FAST_TAYLOR1;
    case SH_ROT_TAYLOR15: return SH__FAST_TAYLOR15;
    case SH_ROT_TAYLOR2: return SH__FAST_TAYLOR2;
    case SH_ROT_IVANIC: return SH__FAST_IVANIC;
    default: return -1;
    }
}

/* The kernel a plan of this order and method runs when `kernel` is asked
 * (AUTO: the widest available): the loop kernels (SCALAR) where the
 * method or the order has no unrolled kernel. */
static sh_rot_kernel kernel_for(int order, sh_rot_method method, sh_rot_kernel kernel)
{
    const sh_rot_kernel k = kernel == SH_KERNEL_AUTO ? kernel_auto() : kernel;
    const sh__rot_fast_d *d1, *dv;
    const sh__rot_fast_f *f1, *fv;
    kernel_tables(k, &d1, &dv, &f1, &fv);
    const int fm = fast_method(method);
    if (k == SH_KERNEL_SCALAR || fm < 0 || order > d1->max_order || !d1->fn[fm][order]) return SH_KERNEL_SCALAR;
    return k;
}

sh_rot_kernel sh_rot_plan_kernel_for(int order, sh_rot_method method, sh_rot_kernel kernel)
{
    if (kernel < 0 || kernel >= SH_KERNEL_N || order < 1 || method < 0 || method >= SH_ROT_NMETHODS)
        return SH_KERNEL_SCALAR;
    return kernel_for(order, method, kernel);
}

struct sh_rot_plan {
    int order;
    sh_rot_method method;
    sh_precision prec;
    sh_convention conv;
    const sh__rot_ops *ops;
    void *tables;
    void *work;
    void *state;      /* sparse methods: the per-rotation state set_P fills */
    void *blocks;     /* double or float, sh_rot_block_offset(order) */
    void *vin, *vout; /* vectors in the plan's precision (float plans: the converted ones) */
    double *vtmp;     /* a copy of the input vector */
    sh_rotation rot;
    int have_rot;
    int have_angles;  /* rot has the Euler angles (a plan set from a matrix may not) */
    uint64_t set_mults, apply_mults;
    sh_rot_kernel kernel; /* the kernel in use (never AUTO) */
    int fmeth;            /* the unrolled method, or −1: the loop kernels */
    const sh__rot_fast_d *fd1, *fdv; /* unrolled: one lane, SIMD lanes */
    const sh__rot_fast_f *ff1, *ffv;
    double par_d[SH__PAR_N]; /* unrolled: the rotation (nocs: β negated) */
    float par_f[SH__PAR_N];
    int blocks_ok;           /* unrolled ivanic: blocks holds the rotation's blocks */
    int nb;                  /* the method needs β itself (Taylor) */
    sh__fast_fn_d fn_d;      /* unrolled, one lane: the kernel of this order, or NULL */
    sh__fast_fn_f fn_f;
    uint64_t fn_mults;       /* its multiplications per call */
    sh_progress_fn progress; /* sh_rot_plan_create_progress: bands of the long steps */
    void *progress_ctx;
};

/* Progress of a plan's long steps, band by band (rot_internal.h): the plan
 * whose tables or rotation this thread is computing, while it has a
 * progress function; the methods' band loops call sh__rot_band_done. */
static _Thread_local const sh_rot_plan *progress_plan;
static _Thread_local const char *progress_what;
typedef struct { const sh_rot_plan *plan; const char *what; } progress_scope;
static progress_scope progress_enter(const sh_rot_plan *p, const char *what)
{
    const progress_scope outer = {progress_plan, progress_what};
    progress_plan = p->progress ? p : NULL;
    progress_what = what;
    return outer;
}
static void progress_leave(progress_scope outer)
{
    progress_plan = outer.plan;
    progress_what = outer.what;
}
void sh__rot_band_done(int done, int total)
{
    const sh_rot_plan *p = progress_plan;
    if (p) p->progress(p->progress_ctx, done, total, progress_what);
}

static int check_args(int order, sh_rot_method method, sh_precision prec, sh_convention conv)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (method < 0 || method >= SH_ROT_NMETHODS || !methods[method])
        return sh_error(SH_EINVAL, "rotation: unknown or unavailable method");
    if (order > methods[method]->max_order)
        return sh_error(SH_EINVAL, "method %s: order %d exceeds its limit %d",
                        method_names[method], order, methods[method]->max_order);
    if (prec != SH_PREC_DOUBLE && prec != SH_PREC_FLOAT)
        return sh_error(SH_EINVAL, "rotation: unknown precision");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "rotation: unknown convention");
    return SH_OK;
}

/* What a plan allocates: the blocks (methods without a sparse apply; the
 * sparse ones build blocks only when asked), the method's tables, scratch,
 * per-rotation state and the vector copies. */
static double plan_bytes(int order, const sh__rot_ops *ops, sh_precision prec)
{
    const double esz = prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    const double nb = (double)sh_rot_block_offset(order), nc = (double)order * order;
    double b = (ops->apply_d ? 0 : nb * esz) + nc * sizeof(double) + 2 * nc * esz; /* blocks, vtmp, vin, vout */
    if (ops->tables_bytes) b += (double)ops->tables_bytes(order) * (esz / sizeof(double));
    if (ops->work_bytes) b += (double)ops->work_bytes(order);
    if (ops->state_bytes) b += (double)ops->state_bytes(order);
    return b;
}

size_t sh_rot_plan_bytes(int order, sh_rot_method method, sh_precision prec)
{
    if (order < 1 || method < 0 || method >= SH_ROT_NMETHODS || !methods[method]) return 0;
    const double b = plan_bytes(order, methods[method], prec);
    return b >= (double)SIZE_MAX ? SIZE_MAX : (size_t)b;
}

int sh_rot_plan_check(int order, sh_rot_method method, sh_precision prec)
{
    int st = check_args(order, method, prec, SH_CS);
    if (st) return st;
    char what[96];
    snprintf(what, sizeof what, "rotation plan (method %s, %s, order %d)", method_names[method],
             sh_precision_name(prec), order);
    return sh__mem_check(plan_bytes(order, methods[method], prec), what);
}

int sh_rot_plan_create(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                       sh_rot_plan **out)
{
    return sh_rot_plan_create_kernel(order, method, prec, conv, SH_KERNEL_AUTO, out);
}

int sh_rot_plan_create_kernel(int order, sh_rot_method method, sh_precision prec,
                              sh_convention conv, sh_rot_kernel kernel, sh_rot_plan **out)
{
    return sh_rot_plan_create_progress(order, method, prec, conv, kernel, NULL, NULL, out);
}

int sh_rot_plan_create_progress(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                                sh_rot_kernel kernel, sh_progress_fn progress, void *ctx, sh_rot_plan **out)
{
    *out = NULL;
    int st = check_args(order, method, prec, conv);
    if (st) return st;
    if ((st = sh_rot_plan_check(order, method, prec))) return st;
    if (kernel < 0 || kernel >= SH_KERNEL_N) return sh_error(SH_EINVAL, "rotation: unknown kernel");
    if (!sh_rot_kernel_available(kernel))
        return sh_error(SH_ENOTSUP, "kernel %s is not available on this machine", kernel_names[kernel]);
    sh_rot_plan *p = calloc(1, sizeof *p);
    if (!p) return sh_error(SH_ENOMEM, "rotation plan: out of memory");
    p->order = order;
    p->method = method;
    p->prec = prec;
    p->conv = conv;
    p->ops = methods[method];
    p->kernel = kernel_for(order, method, kernel);
    p->progress = progress;
    p->progress_ctx = ctx;
    kernel_tables(p->kernel, &p->fd1, &p->fdv, &p->ff1, &p->ffv);
    p->fmeth = p->kernel == SH_KERNEL_SCALAR ? -1 : fast_method(method); /* -1: the loop kernels */
    p->nb = method == SH_ROT_TAYLOR1 || method == SH_ROT_TAYLOR15 || method == SH_ROT_TAYLOR2;
    if (p->fmeth >= 0) {
        if (prec == SH_PREC_FLOAT) p->fn_f = p->ff1->fn[p->fmeth][order];
        else p->fn_d = p->fd1->fn[p->fmeth][order];
        p->fn_mults = prec == SH_PREC_FLOAT ? p->ff1->mults[p->fmeth][order] : p->fd1->mults[p->fmeth][order];
    }
    const size_t esz = prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    const size_t nb = sh_rot_block_offset(order), nc = (size_t)order * order;
    if (!p->ops->apply_d) p->blocks = malloc(nb * esz); /* sparse methods: only on request */
    p->work = malloc((p->ops->work_bytes ? p->ops->work_bytes(order) : 0) + 64);
    p->vtmp = malloc(nc * sizeof(double));
    if (p->ops->state_bytes) p->state = malloc(p->ops->state_bytes(order) + 64);
    p->vin = malloc(nc * esz);
    p->vout = malloc(nc * esz);
    if ((!p->ops->apply_d && !p->blocks) || !p->work || !p->vtmp || (p->ops->state_bytes && !p->state) ||
        !p->vin || !p->vout) {
        sh_rot_plan_free(p);
        return sh_error(SH_ENOMEM, "rotation plan: out of memory (order %d)", order);
    }
    int (*tnew)(int, void **) = prec == SH_PREC_FLOAT ? p->ops->tables_new_f : p->ops->tables_new_d;
    /* tables for the loop kernels (and for unrolled ivanic's batches, which
     * build the blocks once per rotation) */
    if (p->fmeth < 0 || p->fmeth == SH__FAST_IVANIC) {
        const progress_scope outer = progress_enter(p, "bands of the plan's tables");
        if (tnew) st = tnew(order, &p->tables);
        progress_leave(outer);
    }
    if (st) {
        sh_rot_plan_free(p);
        return st;
    }
    *out = p;
    return SH_OK;
}

sh_rot_kernel sh_rot_plan_kernel(const sh_rot_plan *p) { return p->kernel; }

void sh_rot_plan_free(sh_rot_plan *p)
{
    if (!p) return;
    if (p->tables && p->ops->tables_free) p->ops->tables_free(p->tables);
    free(p->blocks);
    free(p->work);
    free(p->state);
    free(p->vin);
    free(p->vout);
    free(p->vtmp);
    free(p);
}

/* Blocks for the current rotation, in the plan's precision and convention,
 * into `blocks` (double or float as the plan). */
static int compute_blocks(sh_rot_plan *p, void *blocks, uint64_t *mults)
{
    int st;
    if (p->prec == SH_PREC_FLOAT) {
        st = p->ops->blocks_f(p->order, &p->rot, p->tables, blocks, p->work, mults);
        if (!st && p->conv == SH_NOCS) sh__rot_blocks_nocs_f(p->order, blocks);
    } else {
        st = p->ops->blocks_d(p->order, &p->rot, p->tables, blocks, p->work, mults);
        if (!st && p->conv == SH_NOCS) sh__rot_blocks_nocs_d(p->order, blocks);
    }
    return st;
}

/* The unrolled kernels: par in the plan's precision, nocs by β → −β
 * (rot_fast.c), counted multiplications of one vector. */
static void fast_par_done(sh_rot_plan *p, const double *pd)
{
    if (pd) for (int j = 0; j < SH__PAR_N; j++) p->par_d[j] = pd[j];
    if (p->prec == SH_PREC_FLOAT && pd)
        for (int j = 0; j < SH__PAR_N; j++) p->par_f[j] = (float)pd[j];
    if (p->conv == SH_NOCS && p->fmeth == SH__FAST_IVANIC) {
        /* Rz(π)·R·Rz(π) (rot_fast.c) */
        static const int neg[4] = {2, 5, 6, 7};
        for (int j = 0; j < 4; j++) p->par_d[neg[j]] = -p->par_d[neg[j]], p->par_f[neg[j]] = -p->par_f[neg[j]];
    } else if (p->conv == SH_NOCS) {
        p->par_d[3] = -p->par_d[3], p->par_d[6] = -p->par_d[6];
        p->par_f[3] = -p->par_f[3], p->par_f[6] = -p->par_f[6];
    }
    p->blocks_ok = 0;
    p->have_rot = 1;
}
static uint64_t fast_mults(const sh_rot_plan *p) { return p->fn_mults; }
static int need_beta(const sh_rot_plan *p) { return p->nb; }

static int set_angles(sh_rot_plan *p, const sh_rotation *rot)
{
    p->rot = *rot;
    p->have_rot = 0;
    p->have_angles = 1;
    p->set_mults = 0;
    int st = SH_OK;
    if (p->fmeth == SH__FAST_IVANIC) {
        fast_par_done(p, rot->R);
        return SH_OK;
    }
    if (p->fmeth >= 0) {
        if (p->prec == SH_PREC_FLOAT) sh__rot_par_euler_f(rot, p->par_f);
        else sh__rot_par_euler_d(rot, p->par_d);
        fast_par_done(p, NULL);
        return SH_OK;
    }
    if (p->ops->apply_d) {
        /* sparse methods: the per-rotation state (validates the rotation;
         * z refuses a tilted one here) */
        if (p->prec == SH_PREC_FLOAT)
            st = p->ops->set_f(p->order, rot, p->tables, p->state, &p->set_mults);
        else
            st = p->ops->set_d(p->order, rot, p->tables, p->state, &p->set_mults);
    } else {
        st = compute_blocks(p, p->blocks, &p->set_mults);
    }
    if (st == SH_OK) p->have_rot = 1;
    return st;
}

/* A rotation given as a matrix R (quat = 0) or a quaternion (quat = 1), in
 * double (rd) or float (rf, float plans only): the unrolled kernels and the
 * methods with set_par take par by algebra (rot_fast.c), ivanic reads R;
 * the others get the Euler angles extracted (sh_euler_from_matrix). */
/* 1 if every v[i] is finite: the largest |v[i]| as an integer (the bits of
 * a non-negative float order like its value) below that of +Inf; branch-
 * free, as this check runs once per rotation */
#define ALL_FINITE(NAME, T, U, ABS, INF)                                                           \
    static int NAME(const T *v, size_t n)                                                          \
    {                                                                                              \
        U m = 0;                                                                                   \
        SH_PRAGMA(omp simd reduction(max : m))                                                     \
        for (size_t i = 0; i < n; i++) {                                                           \
            U u;                                                                                   \
            memcpy(&u, v + i, sizeof u);                                                           \
            u &= ABS;                                                                              \
            m = u > m ? u : m;                                                                     \
        }                                                                                          \
        return m < INF;                                                                            \
    }
ALL_FINITE(all_finite_d, double, uint64_t, 0x7fffffffffffffffULL, 0x7ff0000000000000ULL)
ALL_FINITE(all_finite_f, float, uint32_t, 0x7fffffffu, 0x7f800000u)
#undef ALL_FINITE

int sh_rot_plan_set(sh_rot_plan *p, const sh_rotation *rot)
{
    const progress_scope outer = progress_enter(p, "bands of the rotation");
    const int st = set_angles(p, rot);
    progress_leave(outer);
    return st;
}

static int set_rot_in(sh_rot_plan *p, const double *rd, const float *rf, int quat);
static int set_rot(sh_rot_plan *p, const double *rd, const float *rf, int quat)
{
    const progress_scope outer = progress_enter(p, "bands of the rotation");
    const int st = set_rot_in(p, rd, rf, quat);
    progress_leave(outer);
    return st;
}

static int set_rot_in(sh_rot_plan *p, const double *rd, const float *rf, int quat)
{
    const int n = quat ? 4 : 9, nb = need_beta(p);
    if (!(rf ? all_finite_f(rf, (size_t)n) : all_finite_d(rd, (size_t)n)))
        return sh_error(SH_EINVAL, "rotation plan: %s entries must be finite", quat ? "quaternion" : "matrix");
    p->have_rot = 0;
    p->set_mults = (quat ? SH__PAR_MULTS_QUAT : SH__PAR_MULTS_MATRIX) + (nb && rf ? SH__PAR_MULTS_BETA_F : 0);
    if (p->fmeth == SH__FAST_IVANIC) { /* par = R */
        double R[9], q[4];
        if (quat) {
            for (int i = 0; i < 4; i++) q[i] = rf ? rf[i] : rd[i];
            sh__rot_quat_matrix(q, R);
        } else {
            for (int i = 0; i < 9; i++) R[i] = rf ? rf[i] : rd[i];
        }
        memcpy(p->rot.R, R, sizeof R);
        p->have_angles = 0;
        p->set_mults = quat ? SH__QUAT_MATRIX_MULTS : 0;
        fast_par_done(p, R);
        return SH_OK;
    }
    if (p->fmeth >= 0) { /* the unrolled kernels: par only */
        if (rf) {
            quat ? sh__rot_par_quat_f(rf, nb, p->par_f) : sh__rot_par_matrix_f(rf, nb, p->par_f);
        } else {
            double *pd = p->par_d;
            quat ? sh__rot_par_quat_d(rd, nb, pd) : sh__rot_par_matrix_d(rd, nb, pd);
            if (p->prec == SH_PREC_FLOAT)
                for (int j = 0; j < SH__PAR_N; j++) p->par_f[j] = (float)pd[j];
        }
        p->have_angles = 0;
        fast_par_done(p, NULL);
        return SH_OK;
    }
    double v[9];
    for (int i = 0; i < n; i++) v[i] = rd ? rd[i] : (double)rf[i];
    int st;
    if (p->ops->set_par_d || p->ops->blocks_par_d) {
        double pd[SH__PAR_N];
        if (rf) {
            /* float in: par in float arithmetic */
            quat ? sh__rot_par_quat_f(rf, nb, p->par_f) : sh__rot_par_matrix_f(rf, nb, p->par_f);
        } else {
            quat ? sh__rot_par_quat_d(rd, nb, pd) : sh__rot_par_matrix_d(rd, nb, pd);
            for (int j = 0; j < SH__PAR_N; j++) p->par_d[j] = pd[j], p->par_f[j] = (float)pd[j];
        }
        p->have_angles = 0;
        if (quat) {
            if ((st = sh_rotation_from_quat(v, 1, &p->rot))) return st;
            p->have_angles = 1;
        } else {
            memcpy(p->rot.R, v, sizeof p->rot.R);
        }
        if (p->ops->set_par_d) { /* sparse: the state */
            if (p->prec == SH_PREC_FLOAT)
                st = p->ops->set_par_f(p->order, p->par_f, p->tables, p->state, &p->set_mults);
            else
                st = p->ops->set_par_d(p->order, p->par_d, p->tables, p->state, &p->set_mults);
        } else if (p->prec == SH_PREC_FLOAT) { /* blocks */
            st = p->ops->blocks_par_f(p->order, p->par_f, p->tables, p->blocks, p->work, &p->set_mults);
            if (!st && p->conv == SH_NOCS) sh__rot_blocks_nocs_f(p->order, p->blocks);
        } else {
            st = p->ops->blocks_par_d(p->order, p->par_d, p->tables, p->blocks, p->work, &p->set_mults);
            if (!st && p->conv == SH_NOCS) sh__rot_blocks_nocs_d(p->order, p->blocks);
        }
        if (st == SH_OK) p->have_rot = 1;
        return st;
    }
    p->set_mults = 0;
    sh_rotation r;
    if (quat) {
        if ((st = sh_rotation_from_quat(v, 1, &r))) return st;
    } else {
        memcpy(r.R, v, sizeof r.R);
        if (p->ops->matrix_only) r.alpha = r.beta = r.gamma = 0; /* not read */
        else sh_euler_from_matrix(v, &r.alpha, &r.beta, &r.gamma);
    }
    st = set_angles(p, &r);
    p->have_angles = quat || !p->ops->matrix_only;
    return st;
}

int sh_rot_plan_set_matrix(sh_rot_plan *p, const double R[9]) { return set_rot(p, R, NULL, 0); }
int sh_rot_plan_set_quat(sh_rot_plan *p, const double q[4]) { return set_rot(p, q, NULL, 1); }
int sh_rot_plan_set_matrix_f(sh_rot_plan *p, const float R[9])
{
    if (p->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float matrix for a double plan");
    if (p->fmeth >= 0 && p->fmeth != SH__FAST_IVANIC) { /* set_rot's path, the hot case written out */
        if (!all_finite_f(R, 9)) return sh_error(SH_EINVAL, "rotation plan: matrix entries must be finite");
        p->ff1->par_matrix(R, p->nb, p->par_f);
        if (p->conv == SH_NOCS) p->par_f[3] = -p->par_f[3], p->par_f[6] = -p->par_f[6];
        p->set_mults = SH__PAR_MULTS_MATRIX + (p->nb ? SH__PAR_MULTS_BETA_F : 0);
        p->have_angles = 0;
        p->have_rot = 1;
        return SH_OK;
    }
    return set_rot(p, NULL, R, 0);
}
int sh_rot_plan_set_quat_f(sh_rot_plan *p, const float q[4])
{
    if (p->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float quaternion for a double plan");
    return set_rot(p, NULL, q, 1);
}

static void nocs_vec_d(int order, double *v)
{
    for (int l = 1; l < order; l++)
        for (int m = 1; m <= l; m += 2) {
            v[l * (l + 1) + m] = -v[l * (l + 1) + m];
            v[l * (l + 1) - m] = -v[l * (l + 1) - m];
        }
}
static void nocs_vec_f(int order, float *v)
{
    for (int l = 1; l < order; l++)
        for (int m = 1; m <= l; m += 2) {
            v[l * (l + 1) + m] = -v[l * (l + 1) + m];
            v[l * (l + 1) - m] = -v[l * (l + 1) - m];
        }
}

/* y = R_sh x in float (float plans); x and y may be the same array. */
static void apply_float(sh_rot_plan *p, const float *x, float *y, uint64_t *m)
{
    const size_t nc = (size_t)p->order * p->order;
    if (p->fn_f) {
        p->fn_f(p->par_f, 1, x, y, 1);
        *m += p->fn_mults;
    } else if (p->ops->apply_f) { /* sparse: the kernel works in CS, on distinct arrays */
        if (p->conv == SH_NOCS || x == y) {
            if (x != p->vin) memcpy(p->vin, x, nc * sizeof *x);
            x = p->vin;
            if (p->conv == SH_NOCS) nocs_vec_f(p->order, p->vin);
        }
        p->ops->apply_f(p->order, p->tables, p->state, x, y, p->work, m);
        if (p->conv == SH_NOCS) nocs_vec_f(p->order, y);
    } else {
        if (x == y) {
            if (x != p->vin) memcpy(p->vin, x, nc * sizeof *x);
            x = p->vin;
        }
        sh__rot_blocks_apply_f(p->order, p->blocks, x, y, m);
    }
}

int sh_rot_plan_apply(sh_rot_plan *p, const double *in, double *out)
{
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    const size_t nc = (size_t)p->order * p->order;
    uint64_t m = 0;
    if (p->prec == SH_PREC_FLOAT) {
        float *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = (float)in[i];
        apply_float(p, x, y, &m);
        for (size_t i = 0; i < nc; i++) out[i] = y[i];
    } else if (p->fn_d) {
        p->fn_d(p->par_d, 1, in, out, 1);
        m = p->fn_mults;
    } else {
        /* kernels need distinct input and output: copy when in == out (and
         * for a sparse kernel in nocs, whose input is sign-flipped first) */
        const double *x = in;
        const int sparse_nocs = p->ops->apply_d && p->conv == SH_NOCS;
        if (in == out || sparse_nocs) {
            memcpy(p->vtmp, in, nc * sizeof *p->vtmp);
            if (sparse_nocs) nocs_vec_d(p->order, p->vtmp);
            x = p->vtmp;
        }
        if (p->ops->apply_d) p->ops->apply_d(p->order, p->tables, p->state, x, out, p->work, &m);
        else sh__rot_blocks_apply_d(p->order, p->blocks, x, out, &m);
        if (sparse_nocs) nocs_vec_d(p->order, out);
    }
    p->apply_mults = m;
    return SH_OK;
}

int sh_rot_plan_apply_f(sh_rot_plan *p, const float *in, float *out)
{
    if (p->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float vectors for a double plan");
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    if (p->fn_f) {
        p->fn_f(p->par_f, 1, in, out, 1);
        p->apply_mults = p->fn_mults;
        return SH_OK;
    }
    uint64_t m = 0;
    apply_float(p, in, out, &m);
    p->apply_mults = m;
    return SH_OK;
}

/* ---- batches: structure of arrays, element i of vector k at [i·K + k] ---- */
static int check_batch(const sh_rot_plan *p, size_t K, int fl, int need_rot)
{
    if (fl && p->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float vectors for a double plan");
    if (!fl && p->prec != SH_PREC_DOUBLE) return sh_error(SH_EINVAL, "rotation plan: double vectors for a float plan (use the _f call)");
    if (need_rot && !p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    if (K == 0 || K > ((size_t)1 << 40)) return sh_error(SH_EINVAL, "rotation plan: batch of %zu vectors", K);
    return SH_OK;
}

/* the loop kernels, one vector at a time through the plan's buffers */
static void many_loop(sh_rot_plan *p, size_t K, const void *in, void *out, size_t k)
{
    const size_t nc = (size_t)p->order * p->order;
    uint64_t m = 0;
    if (p->prec == SH_PREC_FLOAT) {
        float *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = ((const float *)in)[i * K + k];
        apply_float(p, x, y, &m);
        for (size_t i = 0; i < nc; i++) ((float *)out)[i * K + k] = y[i];
    } else {
        double *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = ((const double *)in)[i * K + k];
        sh_rot_plan_apply(p, x, y);
        for (size_t i = 0; i < nc; i++) ((double *)out)[i * K + k] = y[i];
        m = p->apply_mults;
    }
    p->apply_mults = m;
}

/* out = blocks · in for K vectors (structure of arrays), band by band, a
 * chunk of vectors at a time (copied first: in == out allowed); each row
 * summed left to right as sh__rot_blocks_apply, vectorised across vectors. */
#define MANY_CHUNK 64
#define MANY_W (2 * SH__FAST_MAXO + 1)
#define BLOCKS_MANY(NAME, T)                                                                       \
    static void NAME(int order, const T *blocks, size_t K, const T *in, T *out)                    \
    {                                                                                              \
        T x[MANY_W * MANY_CHUNK];                                                                  \
        for (int l = 0; l < order; l++) {                                                          \
            const int w = 2 * l + 1;                                                               \
            const T *B = blocks + sh_rot_block_offset(l);                                          \
            for (size_t k0 = 0; k0 < K; k0 += MANY_CHUNK) {                                        \
                const size_t nk = K - k0 < MANY_CHUNK ? K - k0 : MANY_CHUNK;                       \
                for (int j = 0; j < w; j++)                                                        \
                    memcpy(x + (size_t)j * MANY_CHUNK, in + ((size_t)l * l + j) * K + k0, nk * sizeof *x); \
                for (int i = 0; i < w; i++) {                                                      \
                    T *o = out + ((size_t)l * l + i) * K + k0;                                     \
                    SH_PRAGMA(omp simd)                                                            \
                    for (size_t k = 0; k < nk; k++) {                                              \
                        T s = 0;                                                                   \
                        for (int j = 0; j < w; j++) s += B[(size_t)i * w + j] * x[(size_t)j * MANY_CHUNK + k]; \
                        o[k] = s;                                                                  \
                    }                                                                              \
                }                                                                                  \
            }                                                                                      \
        }                                                                                          \
    }
BLOCKS_MANY(blocks_many_d, double)
BLOCKS_MANY(blocks_many_f, float)
#undef BLOCKS_MANY

static int apply_many(sh_rot_plan *p, size_t K, const void *in, void *out, int fl)
{
    int st = check_batch(p, K, fl, 1);
    if (st) return st;
    if (p->fmeth == SH__FAST_IVANIC) {
        /* one rotation, many vectors: the blocks once (the loop kernel), then
         * blocks × vectors, rather than the fused kernel per vector */
        if (!p->blocks_ok) {
            uint64_t sm = 0;
            if ((st = compute_blocks(p, p->blocks, &sm))) return st;
            p->set_mults += sm;
            p->blocks_ok = 1;
        }
        if (fl) blocks_many_f(p->order, p->blocks, K, in, out);
        else blocks_many_d(p->order, p->blocks, K, in, out);
        p->apply_mults = (uint64_t)p->order * (4u * (uint64_t)p->order * p->order - 1) / 3;
        return SH_OK;
    }
    if (p->fmeth >= 0) {
        if (fl) p->ffv->many(p->fmeth, p->order, p->par_f, K, in, out);
        else p->fdv->many(p->fmeth, p->order, p->par_d, K, in, out);
        p->apply_mults = fast_mults(p);
        return SH_OK;
    }
    for (size_t k = 0; k < K; k++) many_loop(p, K, in, out, k);
    return SH_OK;
}
int sh_rot_plan_apply_many(sh_rot_plan *p, size_t K, const double *in, double *out)
{
    return apply_many(p, K, in, out, 0);
}
int sh_rot_plan_apply_many_f(sh_rot_plan *p, size_t K, const float *in, float *out)
{
    return apply_many(p, K, in, out, 1);
}

static int rotate_many(sh_rot_plan *p, size_t K, const void *rot, int quat, const void *in, void *out,
                       int fl)
{
    int st = check_batch(p, K, fl, 0);
    if (st) return st;
    const int nr = quat ? 4 : 9;
    if (p->fmeth >= 0) {
        /* unrolled, lanes of rotations; checked first: every entry finite */
        if (!(fl ? all_finite_f(rot, (size_t)nr * K) : all_finite_d(rot, (size_t)nr * K)))
            return sh_error(SH_EINVAL, "rotation plan: a rotation has an entry that is not finite");
        const int nocs = p->conv == SH_NOCS;
        if (fl) p->ffv->rotate(p->fmeth, p->order, nocs, K, rot, quat, in, out);
        else p->fdv->rotate(p->fmeth, p->order, nocs, K, rot, quat, in, out);
        if (p->fmeth == SH__FAST_IVANIC) p->set_mults = quat ? SH__QUAT_MATRIX_MULTS : 0;
        else p->set_mults = (quat ? SH__PAR_MULTS_QUAT : SH__PAR_MULTS_MATRIX) + (need_beta(p) && fl ? SH__PAR_MULTS_BETA_F : 0);
        p->apply_mults = fast_mults(p);
        p->have_rot = 0; /* the plan's own rotation is not one of them */
        return SH_OK;
    }
    for (size_t k = 0; k < K; k++) {
        double rd[9];
        float rf[9];
        for (int j = 0; j < nr; j++) {
            if (fl) rf[j] = ((const float *)rot)[(size_t)j * K + k];
            else rd[j] = ((const double *)rot)[(size_t)j * K + k];
        }
        if ((st = set_rot(p, fl ? NULL : rd, fl ? rf : NULL, quat))) return st;
        many_loop(p, K, in, out, k);
    }
    return SH_OK;
}
int sh_rot_plan_rotate_many(sh_rot_plan *p, size_t K, const double *R, const double *in, double *out)
{
    return rotate_many(p, K, R, 0, in, out, 0);
}
int sh_rot_plan_rotate_many_f(sh_rot_plan *p, size_t K, const float *R, const float *in, float *out)
{
    return rotate_many(p, K, R, 0, in, out, 1);
}
int sh_rot_plan_rotate_many_quat(sh_rot_plan *p, size_t K, const double *q, const double *in,
                                 double *out)
{
    return rotate_many(p, K, q, 1, in, out, 0);
}
int sh_rot_plan_rotate_many_quat_f(sh_rot_plan *p, size_t K, const float *q, const float *in,
                                   float *out)
{
    return rotate_many(p, K, q, 1, in, out, 1);
}

int sh_rot_plan_blocks(sh_rot_plan *p, double *blocks)
{
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    const size_t nb = sh_rot_block_offset(p->order), nc = (size_t)p->order * p->order;
    if (p->fmeth >= 0) {
        /* the unrolled kernel on each unit vector: column j of band l */
        double *e = malloc(2 * nc * sizeof *e), *col = e + nc;
        if (!e) return sh_error(SH_ENOMEM, "rotation plan: out of memory");
        for (int l = 0; l < p->order; l++) {
            const int w = 2 * l + 1;
            double *B = blocks + sh_rot_block_offset(l);
            for (int j = 0; j < w; j++) {
                memset(e, 0, nc * sizeof *e);
                e[l * l + j] = 1;
                sh_rot_plan_apply(p, e, col);
                for (int i = 0; i < w; i++) B[(size_t)i * w + j] = col[l * l + i];
            }
        }
        free(e);
        return SH_OK;
    }
    if (p->ops->apply_d) { /* sparse methods build their blocks on request */
        if (!p->have_angles) {
            sh_euler_from_matrix(p->rot.R, &p->rot.alpha, &p->rot.beta, &p->rot.gamma);
            p->have_angles = 1;
        }
        if (p->prec == SH_PREC_DOUBLE) return compute_blocks(p, blocks, NULL);
        float *fb = malloc(nb * sizeof *fb);
        if (!fb) return sh_error(SH_ENOMEM, "rotation plan: out of memory (blocks, order %d)", p->order);
        const int st = compute_blocks(p, fb, NULL);
        for (size_t i = 0; !st && i < nb; i++) blocks[i] = fb[i];
        free(fb);
        return st;
    }
    if (p->prec == SH_PREC_FLOAT)
        for (size_t i = 0; i < nb; i++) blocks[i] = ((float *)p->blocks)[i];
    else
        memcpy(blocks, p->blocks, nb * sizeof *blocks);
    return SH_OK;
}

void sh_rot_plan_mults(const sh_rot_plan *p, uint64_t *set_mults, uint64_t *apply_mults)
{
    if (set_mults) *set_mults = p->set_mults;
    if (apply_mults) *apply_mults = p->apply_mults;
}

int sh_rot_band(int band, sh_rot_method method, sh_precision prec, sh_convention conv,
                const sh_rotation *rot, double *block)
{
    /* the band iterator picks the cheapest path: the method's single-band
     * routine, its band-by-band stream, or (bounded in memory) a plan */
    sh_rot_bands *it;
    int st = sh_rot_bands_create(method, prec, conv, band, rot, &it);
    if (st) return st;
    st = sh_rot_bands_get(it, band, block);
    sh_rot_bands_free(it);
    return st;
}

void sh_rot_blocks_to_dense(int order, const double *blocks, double *dense)
{
    const size_t n = (size_t)order * order;
    memset(dense, 0, n * n * sizeof *dense);
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        const double *B = blocks + sh_rot_block_offset(l);
        for (int r = 0; r < w; r++)
            for (int c = 0; c < w; c++) dense[(size_t)(l * l + r) * n + (l * l + c)] = B[(size_t)r * w + c];
    }
}

/* ------------------------------------------------------- band iterator */
struct sh_rot_bands {
    sh_rot_method method;
    sh_precision prec;
    sh_convention conv;
    int lmax, next;
    sh_rotation rot;
    const sh__rot_ops *ops;
    enum { IT_STREAM, IT_BAND, IT_PLAN } kind;
    void *state;   /* stream state, band work, or the plan's blocks */
    float *fblock; /* float streams */
};

/* A method without a single-band or streaming path needs all blocks 0..L:
 * refused above 1 GiB (band ~ 400) rather than exhausting the machine. */
#define BANDS_PLAN_LIMIT ((size_t)1 << 30)

int sh_rot_bands_create(sh_rot_method method, sh_precision prec, sh_convention conv, int lmax,
                        const sh_rotation *rot, sh_rot_bands **out)
{
    *out = NULL;
    int st = check_args(lmax + 1, method, prec, conv);
    if (st) return st;
    sh_rot_bands *it = calloc(1, sizeof *it);
    if (!it) return sh_error(SH_ENOMEM, "rotation bands: out of memory");
    it->method = method;
    it->prec = prec;
    it->conv = conv;
    it->lmax = lmax;
    it->rot = *rot;
    it->ops = methods[method];
    const sh__rot_ops *ops = it->ops;
    const size_t w = 2 * (size_t)lmax + 1;
    if (ops->stream_bytes && (prec == SH_PREC_DOUBLE ? ops->stream_d != NULL : ops->stream_f != NULL)) {
        it->kind = IT_STREAM;
        it->state = calloc(1, ops->stream_bytes(lmax) + 64);
        if (prec == SH_PREC_FLOAT) it->fblock = malloc(w * w * sizeof(float));
        if (!it->state || (prec == SH_PREC_FLOAT && !it->fblock)) goto nomem;
        if (ops->stream_init && (st = ops->stream_init(lmax, it->state))) { sh_rot_bands_free(it); return st; }
    } else if (ops->band_d && prec == SH_PREC_DOUBLE) {
        it->kind = IT_BAND;
        it->state = malloc((ops->band_work_bytes ? ops->band_work_bytes(lmax) : 0) + 64);
        if (!it->state) goto nomem;
    } else {
        it->kind = IT_PLAN;
        const size_t bytes = sh_rot_block_offset(lmax + 1) * sizeof(double);
        if (bytes > BANDS_PLAN_LIMIT) {
            free(it);
            return sh_error(SH_ENOTSUP,
                            "method %s (%s) computes every band 0..%d to get the last one (%.1f GB of "
                            "blocks, limit 1.1 GB); for high bands use blanco or zxzxz (single band) "
                            "or ivanic (streams)",
                            method_names[method], sh_precision_name(prec), lmax, bytes / 1e9);
        }
        it->state = malloc(bytes);
        if (!it->state) goto nomem;
        sh_rot_plan *p;
        if ((st = sh_rot_plan_create(lmax + 1, method, prec, conv, &p))) { sh_rot_bands_free(it); return st; }
        if (!(st = sh_rot_plan_set(p, rot))) st = sh_rot_plan_blocks(p, it->state);
        sh_rot_plan_free(p);
        if (st) { sh_rot_bands_free(it); return st; }
    }
    *out = it;
    return SH_OK;
nomem:
    sh_rot_bands_free(it);
    return sh_error(SH_ENOMEM, "rotation bands: out of memory (lmax %d)", lmax);
}

int sh_rot_bands_next(sh_rot_bands *it, int *l_out, double *block)
{
    const int l = it->next;
    if (l > it->lmax) return sh_error(SH_EINVAL, "rotation bands: past lmax %d", it->lmax);
    const size_t w = 2 * (size_t)l + 1;
    int st = SH_OK;
    switch (it->kind) {
    case IT_STREAM:
        if (it->prec == SH_PREC_FLOAT) {
            st = it->ops->stream_f(l, &it->rot, it->state, it->fblock);
            for (size_t i = 0; !st && i < w * w; i++) block[i] = it->fblock[i];
        } else {
            st = it->ops->stream_d(l, &it->rot, it->state, block);
        }
        break;
    case IT_BAND: st = it->ops->band_d(l, &it->rot, block, it->state); break;
    case IT_PLAN:
        memcpy(block, (double *)it->state + sh_rot_block_offset(l), w * w * sizeof *block);
        break;
    }
    if (st) return st;
    if (it->conv == SH_NOCS && it->kind != IT_PLAN) sh__rot_band_nocs_d(l, block);
    *l_out = l;
    it->next++;
    return SH_OK;
}

int sh_rot_bands_get(sh_rot_bands *it, int l, double *block)
{
    if (l < it->next || l > it->lmax)
        return sh_error(SH_EINVAL, "rotation bands: band %d not reachable (next %d, lmax %d)", l,
                        it->next, it->lmax);
    if (it->kind != IT_STREAM) it->next = l; /* direct access */
    int got = -1, st;
    do {
        st = sh_rot_bands_next(it, &got, block);
    } while (!st && got < l);
    return st;
}

void sh_rot_bands_free(sh_rot_bands *it)
{
    if (!it) return;
    free(it->state);
    free(it->fblock);
    free(it);
}

int sh__rot_bands_single(const sh_rot_bands *it) { return it && it->kind == IT_BAND; }
