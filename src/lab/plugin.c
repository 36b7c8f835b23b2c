/* plugin.c — a user's rotation kernel (a plug-in, shlab/kernel.h) run on the
 * cases of a golden fixture, or timed, in the sandbox (core/sandbox.c).
 *
 * The library is opened (dlopen) in the child, so that even its
 * constructors cannot take shlab down.  For every case the child builds
 * guarded buffers: the input is copied to pages it then makes read-only
 * (mprotect), and input and output each end exactly at a PROT_NONE page, so
 * a kernel that writes to its input, reads past its input's end or writes
 * past its output's end faults at once; a SIGSEGV/SIGBUS handler (on its own
 * stack) names which of these the faulting address was and leaves.  The
 * bytes before the output (from its page's start) hold a pattern, checked
 * after the call: a write before the output's start.  The output starts as
 * NaN, so a value the kernel never wrote fails its case.
 *
 * The child's answer is a stream of records (native byte order: same
 * machine), each "u32 kind, i32 case, i32 rc, i32 n" then n doubles:
 *   START  the case is about to run (so a crash or a hang names it);
 *   DONE   the kernel returned rc, and n = the case's outputs follow;
 *   OPEN   the library or the symbol could not be opened; n bytes of the
 *          message follow (padded to whole doubles).
 * The parent checks every record against the fixture before it stores a
 * value. */
#define _GNU_SOURCE
#include "lab/lab.h"
#include "core/sandbox.h"
#include "core/shlab_internal.h"
#include "shlab/kernel.h"
#include "lab/case_stream.h"

#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const abi_names[SH_PLUGIN_ABI_COUNT] = {
    "matrix-d", "matrix-f", "quat-d", "quat-f", "euler-d", "euler-f", "matrix-batch-d", "matrix-batch-f",
};

const char *sh_plugin_abi_name(sh_plugin_abi a) { return (unsigned)a < SH_PLUGIN_ABI_COUNT ? abi_names[a] : "?"; }

int sh_plugin_abi_parse(const char *s, sh_plugin_abi *out)
{
    for (int a = 0; s && a < SH_PLUGIN_ABI_COUNT; a++)
        if (!strcmp(s, abi_names[a])) {
            *out = (sh_plugin_abi)a;
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown kernel ABI '%s' (matrix-d, matrix-f, quat-d, quat-f, euler-d, euler-f, "
                               "matrix-batch-d, matrix-batch-f: shlab/kernel.h)", s ? s : "");
}

sh_precision sh_plugin_abi_precision(sh_plugin_abi a)
{
    return a == SH_PLUGIN_MATRIX_F || a == SH_PLUGIN_QUAT_F || a == SH_PLUGIN_EULER_F || a == SH_PLUGIN_MATRIX_BATCH_F
               ? SH_PREC_FLOAT
               : SH_PREC_DOUBLE;
}

int sh_plugin_parse(const char *spec, sh_plugin_abi abi, sh_plugin *out)
{
    memset(out, 0, sizeof *out);
    const char *colon = spec ? strrchr(spec, ':') : NULL;
    if (!colon || colon == spec || !colon[1])
        return sh_error(SH_EINVAL, "plug-in '%s': expected LIB.so:SYMBOL", spec ? spec : "");
    const size_t n = (size_t)(colon - spec);
    if (n >= sizeof out->lib || strlen(colon + 1) >= sizeof out->symbol)
        return sh_error(SH_EINVAL, "plug-in '%s': path or symbol too long", spec);
    memcpy(out->lib, spec, n);
    out->lib[n] = '\0';
    snprintf(out->symbol, sizeof out->symbol, "%s", colon + 1);
    /* a path (dlopen would search the library path for a bare name) */
    if (!strchr(out->lib, '/')) {
        if (n + 2 >= sizeof out->lib) return sh_error(SH_EINVAL, "plug-in '%s': path too long", spec);
        memmove(out->lib + 2, out->lib, n + 1);
        memcpy(out->lib, "./", 2);
    }
    struct stat sb;
    if (stat(out->lib, &sb)) return sh_error(SH_EIO, "plug-in '%s': cannot open '%s': %s", spec, out->lib, strerror(errno));
    if (!S_ISREG(sb.st_mode)) return sh_error(SH_EIO, "plug-in '%s': '%s' is not a regular file", spec, out->lib);
    out->abi = abi;
    out->timeout_s = 10;
    return SH_OK;
}

/* ------------------------------------------------------------------ child */

/* child exit statuses */
enum { CHILD_WRITE = SH_CASE_CHILD_WRITE, CHILD_FAULT = SH_CASE_CHILD_FAULT, CHILD_CORRUPT = SH_CASE_CHILD_CORRUPT };

/* A buffer of `bytes` whose end touches a PROT_NONE page. */
typedef struct {
    unsigned char *map; /* the mapping: data pages, then the guard page */
    size_t map_len;
    unsigned char *p;    /* the buffer: ends at the guard */
    unsigned char *page; /* the first data page (the pattern runs from here to p) */
} guarded;

static long page_size(void) { return sysconf(_SC_PAGESIZE); }

static int guarded_alloc(size_t bytes, guarded *g)
{
    const size_t ps = (size_t)page_size(), data = (bytes + ps - 1) / ps * ps;
    g->map_len = data + ps;
    g->map = mmap(NULL, g->map_len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (g->map == MAP_FAILED) return -1;
    if (mprotect(g->map + data, ps, PROT_NONE)) return -1;
    g->page = g->map;
    g->p = g->map + data - bytes;
    memset(g->page, 0xA5, (size_t)(g->p - g->page));
    return 0;
}

static int guarded_pattern_ok(const guarded *g)
{
    for (const unsigned char *c = g->page; c < g->p; c++)
        if (*c != 0xA5) return 0;
    return 1;
}

static void guarded_free(guarded *g)
{
    if (g->map && g->map != MAP_FAILED) munmap(g->map, g->map_len);
    memset(g, 0, sizeof *g);
}

/* The regions the fault handler names (child only; one run at a time). */
static struct {
    const unsigned char *in_lo, *in_hi, *out_lo, *out_hi; /* data [lo, hi) then the guard page */
    char case_id[64];
} fault;

static void fault_say(const char *what)
{
    char msg[256];
    const int n = snprintf(msg, sizeof msg, "the kernel %s on case '%s'\n", what, fault.case_id);
    if (n > 0 && write(2, msg, (size_t)n) < 0) {}
}

static void on_fault(int sig, siginfo_t *si, void *uc)
{
    const unsigned char *a = si->si_addr;
    const size_t ps = (size_t)page_size();
    if (a >= fault.out_hi && a < fault.out_hi + ps) fault_say("wrote past the end of its output (guard page)");
    else if (a >= fault.in_hi && a < fault.in_hi + ps) fault_say("read past the end of its input (guard page)");
    else if (a >= fault.in_lo && a < fault.in_hi) fault_say("wrote to its input (read-only)");
    else {
        char what[96];
        snprintf(what, sizeof what, "crashed (%s at address %p)", sig == SIGBUS ? "SIGBUS" : "SIGSEGV", (void *)a);
        fault_say(what);
    }
    _exit(CHILD_FAULT);
}

static void catch_faults(void)
{
    static char stack[1 << 16];
    stack_t ss = {.ss_sp = stack, .ss_size = sizeof stack, .ss_flags = 0};
    sigaltstack(&ss, NULL);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = on_fault;
    sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigaction(SIGSEGV, &sa, NULL);
    sigaction(SIGBUS, &sa, NULL);
}

/* dlopen + dlsym in the child; on failure an OPEN record with the message. */
static void *open_kernel(const sh_plugin *p, int fd)
{
    void *h = dlopen(p->lib, RTLD_NOW | RTLD_LOCAL);
    const char *why = h ? NULL : dlerror();
    void *fn = h ? dlsym(h, p->symbol) : NULL;
    char msg[512];
    if (h && !fn) {
        snprintf(msg, sizeof msg, "no symbol '%.200s' in '%.250s'", p->symbol, p->lib);
        why = msg;
    }
    if (why) {
        sh__rec_send_text(fd, SH_REC_OPEN, why);
        return NULL;
    }
    return fn;
}

/* One call of the kernel: count rotations of one order, in and out
 * (count·n values each, already in the ABI's precision in guarded buffers). */
static int call_kernel(const sh_plugin *p, void *fn, int order, int count, const sh_rotation *rot, const void *in,
                       void *out)
{
    double q[4];
    float qf[4], Rf[9];
    switch (p->abi) {
    case SH_PLUGIN_MATRIX_D: return ((shlab_kernel_matrix_d *)fn)(order, rot->R, in, out);
    case SH_PLUGIN_MATRIX_F:
        for (int i = 0; i < 9; i++) Rf[i] = (float)rot->R[i];
        return ((shlab_kernel_matrix_f *)fn)(order, Rf, in, out);
    case SH_PLUGIN_QUAT_D: sh_rotation_to_quat(rot, q); return ((shlab_kernel_quat_d *)fn)(order, q, in, out);
    case SH_PLUGIN_QUAT_F:
        sh_rotation_to_quat(rot, q);
        for (int i = 0; i < 4; i++) qf[i] = (float)q[i];
        return ((shlab_kernel_quat_f *)fn)(order, qf, in, out);
    case SH_PLUGIN_EULER_D: return ((shlab_kernel_euler_d *)fn)(order, rot->alpha, rot->beta, rot->gamma, in, out);
    case SH_PLUGIN_EULER_F:
        return ((shlab_kernel_euler_f *)fn)(order, (float)rot->alpha, (float)rot->beta, (float)rot->gamma, in, out);
    case SH_PLUGIN_MATRIX_BATCH_D:
    case SH_PLUGIN_MATRIX_BATCH_F: {
        /* count rotations: matrices in a plain buffer (read-only is not needed) */
        const int fl = p->abi == SH_PLUGIN_MATRIX_BATCH_F;
        void *R = malloc((size_t)count * 9 * (fl ? sizeof(float) : sizeof(double)));
        if (!R) return -1;
        for (int k = 0; k < count; k++)
            for (int i = 0; i < 9; i++) {
                if (fl) ((float *)R)[9 * k + i] = (float)rot[k].R[i];
                else ((double *)R)[9 * k + i] = rot[k].R[i];
            }
        const int rc = fl ? ((shlab_kernel_matrix_batch_f *)fn)(order, count, R, in, out)
                          : ((shlab_kernel_matrix_batch_d *)fn)(order, count, R, in, out);
        free(R);
        return rc;
    }
    default: return -1;
    }
}

typedef struct {
    const sh_plugin *p;
    const sh_fixture *fx;
    const unsigned char *skip;
} fixture_job;

/* The coefficients a case gives the kernel: the whole order, or for a band
 * case the order band+1 with zeros outside the band. */
static int case_order(const sh_fixture_case *c) { return c->band >= 0 ? c->band + 1 : c->order; }

/* Case k through the kernel: rc, and its c->n outputs into res. */
static int run_case(const fixture_job *j, void *fn, int k, double *res, int *rc)
{
    const sh_fixture_case *c = &j->fx->cases[k];
    const int fl = sh_plugin_abi_precision(j->p->abi) == SH_PREC_FLOAT, order = case_order(c);
    const size_t n = (size_t)order * order, es = fl ? sizeof(float) : sizeof(double);
    const int off = c->band >= 0 ? c->band * c->band : 0;
    guarded gi = {0}, go = {0};
    if (guarded_alloc(n * es, &gi) || guarded_alloc(n * es, &go)) return -1;
    for (size_t i = 0; i < n; i++) {
        const double x = (int)i >= off && (int)i < off + c->n ? c->input[i - off] : 0.0;
        if (fl) ((float *)(void *)gi.p)[i] = (float)x;
        else ((double *)(void *)gi.p)[i] = x;
        if (fl) ((float *)(void *)go.p)[i] = NAN;
        else ((double *)(void *)go.p)[i] = NAN;
    }
    mprotect(gi.map, gi.map_len - (size_t)page_size(), PROT_READ);
    fault.in_lo = gi.p;
    fault.in_hi = gi.p + n * es;
    fault.out_lo = go.p;
    fault.out_hi = go.p + n * es;
    snprintf(fault.case_id, sizeof fault.case_id, "%s", c->id);
    *rc = call_kernel(j->p, fn, order, 1, &c->rot, gi.p, go.p);
    const int corrupt = !guarded_pattern_ok(&go);
    for (int i = 0; i < c->n; i++)
        res[i] = fl ? (double)((float *)(void *)go.p)[off + i] : ((double *)(void *)go.p)[off + i];
    guarded_free(&gi);
    guarded_free(&go);
    if (corrupt) {
        fault_say("wrote before the start of its output");
        return -2;
    }
    return 0;
}

static int fixture_child(void *arg, int fd)
{
    const fixture_job *j = arg;
    catch_faults();
    void *fn = open_kernel(j->p, fd);
    if (!fn) return 0;
    int maxn = 1;
    for (int k = 0; k < j->fx->ncases; k++) maxn = j->fx->cases[k].n > maxn ? j->fx->cases[k].n : maxn;
    double *res = malloc((size_t)maxn * sizeof *res);
    if (!res) return CHILD_WRITE;
    for (int k = 0; k < j->fx->ncases; k++) {
        if (j->skip && j->skip[k]) continue;
        int rc = 0;
        if (sh__rec_send(fd, SH_REC_START, k, 0, NULL, 0)) return CHILD_WRITE;
        const int st = run_case(j, fn, k, res, &rc);
        if (st == -2) return CHILD_CORRUPT;
        if (st) return CHILD_WRITE;
        if (sh__rec_send(fd, SH_REC_DONE, k, rc, res, j->fx->cases[k].n)) return CHILD_WRITE;
    }
    free(res);
    return 0;
}

/* ------------------------------------------------------------------ parent */

/* The time limit is the wall clock's (--timeout); the CPU limit is a
 * backstop one second later, so that a kernel that spins is stopped, and
 * reported, by the same rule whether or not the machine is busy. */
#define PLUGIN_CPU_SECONDS(p) ((p)->timeout_s + 1)

int sh_plugin_run_fixture(const sh_plugin *p, const sh_fixture *fx, const unsigned char *skip, double **got,
                          unsigned char *status, sh_plugin_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->current = -1;
    for (int k = 0; k < fx->ncases; k++) status[k] = SH_PLUGIN_CASE_NOT_RUN;
    const fixture_job j = {p, fx, skip};
    sh_case_reader r = {.fx = fx, .got = got, .rep = rep, .status = status, .who = "the plug-in"};
    const sh_sandbox_job sj = {.child = fixture_child, .feed = sh__case_reader_feed, .arg = (void *)&j, .fctx = &r,
                               .cpu_seconds = PLUGIN_CPU_SECONDS(p), .wall_seconds = p->timeout_s,
                               .mem_bytes = 1LL << 30, .what = "the plug-in"};
    sh_sandbox_result sr;
    int st = sh__sandbox_run(&sj, &sr);
    if (st) return st;
    sh__case_describe(p->timeout_s, fx, &sr, &r, rep);
    rep->failed = rep->failure[0] != '\0';
    return SH_OK;
}

/* ------------------------------------------------------------------ timing */

/* The plug-in as a bench entry: per iteration one call on rotation k of the
 * pool (held in the ABI's own form, as its user holds it) and vector k; the
 * batch ABIs take `batch` rotations and vectors per call (units = batch). */
typedef struct {
    const sh_plugin *p;
    void *fn;
    int order, nc, batch, fl;
    void *R;           /* pool: 9 (matrix), 4 (quat) or 3 (euler) per rotation, or per batch 9·batch */
    void *vin, *vout;  /* pool vectors (batch ABIs: batch·nc per call), one output (batch·nc) */
    int per;           /* numbers per rotation in R */
} plugin_entry;

static int plugin_entry_run(void *v, long count)
{
    plugin_entry *e = v;
    const size_t es = e->fl ? sizeof(float) : sizeof(double);
    int bad = 0;
    for (long it = 0; it < count; it++) {
        const long k = it & (SH_BENCH_POOL - 1);
        const char *R = (const char *)e->R + (size_t)k * e->per * es;
        const char *in = (const char *)e->vin + (size_t)k * e->nc * es;
        int rc;
        switch (e->p->abi) {
        case SH_PLUGIN_MATRIX_D: rc = ((shlab_kernel_matrix_d *)e->fn)(e->order, (const double *)R, (const double *)in, e->vout); break;
        case SH_PLUGIN_MATRIX_F: rc = ((shlab_kernel_matrix_f *)e->fn)(e->order, (const float *)R, (const float *)in, e->vout); break;
        case SH_PLUGIN_QUAT_D: rc = ((shlab_kernel_quat_d *)e->fn)(e->order, (const double *)R, (const double *)in, e->vout); break;
        case SH_PLUGIN_QUAT_F: rc = ((shlab_kernel_quat_f *)e->fn)(e->order, (const float *)R, (const float *)in, e->vout); break;
        case SH_PLUGIN_EULER_D: {
            const double *a = (const double *)R;
            rc = ((shlab_kernel_euler_d *)e->fn)(e->order, a[0], a[1], a[2], (const double *)in, e->vout);
            break;
        }
        case SH_PLUGIN_EULER_F: {
            const float *a = (const float *)R;
            rc = ((shlab_kernel_euler_f *)e->fn)(e->order, a[0], a[1], a[2], (const float *)in, e->vout);
            break;
        }
        case SH_PLUGIN_MATRIX_BATCH_D:
            rc = ((shlab_kernel_matrix_batch_d *)e->fn)(e->order, e->batch, (const double *)R, (const double *)in, e->vout);
            break;
        case SH_PLUGIN_MATRIX_BATCH_F:
            rc = ((shlab_kernel_matrix_batch_f *)e->fn)(e->order, e->batch, (const float *)R, (const float *)in, e->vout);
            break;
        default: rc = -1;
        }
        bad |= rc != SHLAB_KERNEL_OK;
    }
    return bad ? sh_error(SH_EINVAL, "the kernel returned a failure code while timed") : SH_OK;
}

static void plugin_entry_free(void *v)
{
    plugin_entry *e = v;
    if (!e) return;
    free(e->R), free(e->vin), free(e->vout), free(e);
}

/* The pool of sh_bench_pool (the rotation entries' own seed and β range) in
 * the ABI's form; batch ABIs: per call `batch` consecutive pool entries. */
static int plugin_entry_make(const sh_plugin *p, void *fn, int order, int batch, const sh_bench_opts *o,
                             sh_bench_entry *out)
{
    plugin_entry *e = calloc(1, sizeof *e);
    if (!e) return sh_error(SH_ENOMEM, "out of memory");
    const int isbatch = p->abi == SH_PLUGIN_MATRIX_BATCH_D || p->abi == SH_PLUGIN_MATRIX_BATCH_F;
    e->p = p, e->fn = fn, e->order = order, e->nc = order * order, e->batch = isbatch ? batch : 1;
    e->fl = sh_plugin_abi_precision(p->abi) == SH_PREC_FLOAT;
    const int per1 = p->abi == SH_PLUGIN_QUAT_D || p->abi == SH_PLUGIN_QUAT_F ? 4
                     : p->abi == SH_PLUGIN_EULER_D || p->abi == SH_PLUGIN_EULER_F ? 3 : 9;
    e->per = per1 * e->batch;
    const size_t es = e->fl ? sizeof(float) : sizeof(double), nb = (size_t)e->batch * e->nc;
    double(*R)[9] = malloc(SH_BENCH_POOL * sizeof *R), *v = malloc((size_t)SH_BENCH_POOL * e->nc * sizeof *v);
    e->R = malloc((size_t)SH_BENCH_POOL * e->per * es);
    e->vin = malloc((size_t)SH_BENCH_POOL * nb * es);
    e->vout = malloc(nb * es);
    if (!R || !v || !e->R || !e->vin || !e->vout) {
        free(R), free(v), plugin_entry_free(e);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    sh_bench_pool(o->seed, o->max_beta, e->nc, R, v);
    for (int k = 0; k < SH_BENCH_POOL; k++)
        for (int b = 0; b < e->batch; b++) {
            const int q = (k + b) & (SH_BENCH_POOL - 1);
            sh_rotation r;
            memcpy(r.R, R[q], sizeof r.R);
            double x[9];
            if (per1 == 9) memcpy(x, r.R, sizeof r.R);
            else if (per1 == 4) sh_rotation_to_quat(&r, x);
            else sh_euler_from_matrix(r.R, &x[0], &x[1], &x[2]);
            for (int j = 0; j < per1; j++) {
                const size_t at = (size_t)k * e->per + (size_t)b * per1 + j;
                if (e->fl) ((float *)e->R)[at] = (float)x[j];
                else ((double *)e->R)[at] = x[j];
            }
            for (int i = 0; i < e->nc; i++) {
                const size_t at = (size_t)k * nb + (size_t)b * e->nc + i;
                if (e->fl) ((float *)e->vin)[at] = (float)v[(size_t)q * e->nc + i];
                else ((double *)e->vin)[at] = v[(size_t)q * e->nc + i];
            }
        }
    free(R), free(v);
    *out = (sh_bench_entry){.name = "plug-in", .run = plugin_entry_run, .free = plugin_entry_free, .ctx = e,
                            .units = e->batch};
    return SH_OK;
}

/* What the timing child sends back: entry 0 the plug-in, then the methods. */
typedef struct {
    int status;
    char why[256];
    sh_bench_stats st[1 + SH_PLUGIN_BENCH_MAX_METHODS];
    sh_bench_ratio ratio[SH_PLUGIN_BENCH_MAX_METHODS]; /* plug-in / method i, paired by round */
    sh_bench_noise noise;
} bench_answer;

typedef struct {
    const sh_plugin *p;
    const sh_plugin_bench_opts *o;
} bench_job;

static int bench_child(void *arg, int fd)
{
    const bench_job *j = arg;
    const sh_plugin_bench_opts *o = j->o;
    bench_answer *ans = calloc(1, sizeof *ans);
    sh_bench_entry ent[1 + SH_PLUGIN_BENCH_MAX_METHODS];
    memset(ent, 0, sizeof ent);
    int ne = 0, st = ans ? SH_OK : SH_ENOMEM;
    void *fn = st ? NULL : open_kernel(j->p, fd);
    if (!fn) return 0; /* the OPEN record says why (or no memory: the parent sees no answer) */
    sh_bench_opts bo = o->bench;
    bo.input = o->input;
    bo.batch = o->batch;
    st = plugin_entry_make(j->p, fn, o->order, o->batch, &bo, &ent[ne++]);
    for (int i = 0; !st && i < o->nmethods; i++)
        st = sh_rot_bench_entry(o->order, o->methods[i], sh_plugin_abi_precision(j->p->abi), o->mode, &bo, &ent[ne++]);
    const int S = o->cfg.samples > 0 ? o->cfg.samples : 15;
    double *smp = st ? NULL : malloc((size_t)ne * S * sizeof *smp);
    if (!st && !smp) st = SH_ENOMEM;
    if (!st) st = sh_bench_interleaved(ent, ne, &o->cfg, smp, ans->st, &ans->noise);
    for (int i = 1; !st && i < ne; i++)
        st = sh_bench_paired_ratio(smp, smp + (size_t)i * S, S, o->cfg.noise_spread, &ans->ratio[i - 1]);
    ans->status = st;
    if (st) snprintf(ans->why, sizeof ans->why, "%s", sh_last_error());
    for (int i = 0; i < ne; i++) sh_bench_entry_free(&ent[i]);
    free(smp);
    /* one DONE record: the answer's bytes as doubles */
    const int nd = (int)((sizeof *ans + sizeof(double) - 1) / sizeof(double));
    double *buf = calloc((size_t)nd, sizeof *buf);
    if (!buf) return CHILD_WRITE;
    memcpy(buf, ans, sizeof *ans);
    const int w = sh__rec_send(fd, SH_REC_DONE, 0, 0, buf, nd);
    free(buf);
    free(ans);
    return w ? CHILD_WRITE : 0;
}


int sh_plugin_bench(const sh_plugin *p, const sh_plugin_bench_opts *o, sh_plugin_bench_result *res)
{
    memset(res, 0, sizeof *res);
    if (o->nmethods < 0 || o->nmethods > SH_PLUGIN_BENCH_MAX_METHODS)
        return sh_error(SH_EINVAL, "plug-in bench: at most %d methods beside the plug-in", SH_PLUGIN_BENCH_MAX_METHODS);
    const int nd = (int)((sizeof(bench_answer) + sizeof(double) - 1) / sizeof(double));
    sh_byte_sink sink = {.cap = sizeof(sh_rec_hdr) + SH_REC_MAX_TEXT + (size_t)nd * sizeof(double)};
    if (!(sink.buf = malloc(sink.cap))) return sh_error(SH_ENOMEM, "out of memory");
    const bench_job j = {p, o};
    const sh_sandbox_job sj = {.child = bench_child, .feed = sh__byte_sink_feed, .arg = (void *)&j, .fctx = &sink,
                               .cpu_seconds = PLUGIN_CPU_SECONDS(p), .wall_seconds = p->timeout_s, .mem_bytes = 1LL << 30,
                               .what = "the plug-in"};
    sh_sandbox_result sr;
    int st = sh__sandbox_run(&sj, &sr);
    const sh_rec_hdr *h = (const sh_rec_hdr *)(void *)sink.buf;
    if (!st && sink.have >= sizeof *h && h->kind == SH_REC_OPEN) {
        char *m = (char *)(sink.buf + sizeof *h);
        sink.buf[sink.cap - 1] = '\0';
        st = sh_error(SH_EINVAL, "cannot load the plug-in: %.280s", m);
    } else if (!st && sr.outcome == SH_SANDBOX_DONE && sr.exit_status == 0 &&
               sink.have == sizeof *h + (size_t)nd * sizeof(double) && h->kind == SH_REC_DONE && h->n == nd) {
        bench_answer ans;
        memcpy(&ans, sink.buf + sizeof *h, sizeof ans);
        if (ans.status) st = sh_error(ans.status, "%s", ans.why);
        memcpy(res->stats, ans.st, sizeof ans.st);
        memcpy(res->ratio, ans.ratio, sizeof ans.ratio);
        res->noise = ans.noise;
    } else if (!st) {
        /* the kernel ended the child: say how, as the fixture run does */
        sh_plugin_report rep = {.current = -1};
        sh_case_reader r = {.who = "the plug-in"};
        sh__case_describe(p->timeout_s, NULL, &sr, &r, &rep);
        if (!rep.failure[0]) snprintf(rep.failure, sizeof rep.failure, "the plug-in's process sent no answer");
        res->failed = 1;
        snprintf(res->failure, sizeof res->failure, "%s", rep.failure);
    }
    free(sink.buf);
    return st;
}
