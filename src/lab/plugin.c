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

enum { REC_START = 1, REC_DONE = 2, REC_OPEN = 3 };
typedef struct {
    uint32_t kind;
    int32_t k, rc, n;
} rec_hdr;

/* child exit statuses */
enum { CHILD_WRITE = SH_SANDBOX_CHILD_FIRST_FREE, CHILD_FAULT, CHILD_CORRUPT };

static int write_all(int fd, const void *p, size_t n)
{
    const char *c = p;
    while (n) {
        const ssize_t w = write(fd, c, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return -1;
        c += w;
        n -= (size_t)w;
    }
    return 0;
}

static int send_rec(int fd, int kind, int k, int rc, const double *v, int n)
{
    const rec_hdr h = {(uint32_t)kind, k, rc, n};
    return write_all(fd, &h, sizeof h) || (n && write_all(fd, v, (size_t)n * sizeof *v)) ? -1 : 0;
}

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
        char text[512];
        memset(text, 0, sizeof text);
        snprintf(text, sizeof text, "%s", why);
        const int nd = (int)((strlen(text) + sizeof(double)) / sizeof(double));
        send_rec(fd, REC_OPEN, -1, 0, (const double *)(void *)text, nd);
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
        if (send_rec(fd, REC_START, k, 0, NULL, 0)) return CHILD_WRITE;
        const int st = run_case(j, fn, k, res, &rc);
        if (st == -2) return CHILD_CORRUPT;
        if (st) return CHILD_WRITE;
        if (send_rec(fd, REC_DONE, k, rc, res, j->fx->cases[k].n)) return CHILD_WRITE;
    }
    free(res);
    return 0;
}

/* ------------------------------------------------------------------ parent */

typedef struct {
    const sh_fixture *fx;
    double **got;
    sh_plugin_report *rep;
    unsigned char *status;
    rec_hdr h;
    size_t have;       /* bytes of the current header or body */
    int in_body;
    unsigned char buf[sizeof(rec_hdr) + 512];
    double *body;      /* where the body goes */
    size_t body_bytes;
    const char *why;   /* the protocol broken */
} reader;

static int rec_begin_body(reader *r)
{
    const rec_hdr *h = &r->h;
    if (h->kind == REC_OPEN) {
        if (h->n < 1 || (size_t)h->n * sizeof(double) > 512) return (r->why = "bad message length"), -1;
        r->body = (double *)(void *)r->buf;
        r->body_bytes = (size_t)h->n * sizeof(double);
        return 0;
    }
    if (h->k < 0 || h->k >= r->fx->ncases) return (r->why = "case index out of range"), -1;
    if (h->kind == REC_START) {
        if (h->n) return (r->why = "START with a body"), -1;
        r->rep->current = h->k;
        return 0;
    }
    if (h->kind != REC_DONE || h->n != r->fx->cases[h->k].n) return (r->why = "bad record"), -1;
    r->body = r->got[h->k];
    r->body_bytes = (size_t)h->n * sizeof(double);
    return 0;
}

static void rec_end(reader *r)
{
    const rec_hdr *h = &r->h;
    if (h->kind == REC_OPEN) {
        char *m = (char *)r->buf;
        m[r->body_bytes - 1] = '\0';
        snprintf(r->rep->failure, sizeof r->rep->failure, "cannot load the plug-in: %.280s", m);
        r->rep->open_failed = 1;
    } else if (h->kind == REC_DONE) {
        r->rep->current = -1;
        if (h->rc == SHLAB_KERNEL_OK) r->status[h->k] = SH_PLUGIN_CASE_RAN, r->rep->ran++;
        else if (h->rc == SHLAB_KERNEL_UNSUPPORTED) r->status[h->k] = SH_PLUGIN_CASE_DECLINED, r->rep->declined++;
        else {
            r->status[h->k] = SH_PLUGIN_CASE_ERROR;
            r->rep->errors++;
            for (int i = 0; i < h->n; i++) r->got[h->k][i] = NAN; /* a failure fails its case */
        }
    }
}

static int reader_feed(void *fctx, const unsigned char *bytes, size_t n)
{
    reader *r = fctx;
    while (n) {
        if (!r->in_body) {
            const size_t take = sizeof r->h - r->have < n ? sizeof r->h - r->have : n;
            memcpy((unsigned char *)&r->h + r->have, bytes, take);
            r->have += take, bytes += take, n -= take;
            if (r->have < sizeof r->h) return 0;
            r->have = 0;
            r->body_bytes = 0;
            if (rec_begin_body(r)) return -1;
            r->in_body = 1;
        }
        const size_t take = r->body_bytes - r->have < n ? r->body_bytes - r->have : n;
        memcpy((unsigned char *)r->body + r->have, bytes, take);
        r->have += take, bytes += take, n -= take;
        if (r->have < r->body_bytes) return 0;
        rec_end(r);
        r->have = 0;
        r->in_body = 0;
    }
    return 0;
}

/* The one line that says what happened to the child, into rep->failure. */
static void describe(const sh_plugin *p, const sh_fixture *fx, const sh_sandbox_result *sr, const reader *r,
                     sh_plugin_report *rep)
{
    if (rep->open_failed) return;
    char at[96] = "";
    if (rep->current >= 0) snprintf(at, sizeof at, " on case '%s'", fx->cases[rep->current].id);
    const char *line = sr->first_line;
    switch (sr->outcome) {
    case SH_SANDBOX_WALL:
        snprintf(rep->failure, sizeof rep->failure, "the kernel did not return within %g s%s (stopped)", p->timeout_s, at);
        break;
    case SH_SANDBOX_CPU:
        snprintf(rep->failure, sizeof rep->failure, "the kernel used more than %g s of CPU time%s (stopped)",
                 sr->cpu_limit, at);
        break;
    case SH_SANDBOX_MEMORY:
        snprintf(rep->failure, sizeof rep->failure, "the kernel went over its memory limit%s (stopped)", at);
        break;
    case SH_SANDBOX_BROKEN:
        snprintf(rep->failure, sizeof rep->failure, "the plug-in's process broke its answer (%s)", r->why ? r->why : "?");
        break;
    case SH_SANDBOX_SIGNAL:
        if (*line) snprintf(rep->failure, sizeof rep->failure, "%s", line);
        else snprintf(rep->failure, sizeof rep->failure, "the kernel was killed by signal %d (%s)%s", sr->signal,
                      strsignal(sr->signal), at);
        break;
    case SH_SANDBOX_DONE:
        if (sr->exit_status == CHILD_FAULT || sr->exit_status == CHILD_CORRUPT)
            snprintf(rep->failure, sizeof rep->failure, "%s", *line ? line : "the kernel crashed");
        else if (sr->exit_status != 0)
            snprintf(rep->failure, sizeof rep->failure, "the kernel's process exited with status %d%s%s%s",
                     sr->exit_status, at, *line ? ": " : "", line);
        else if (r->in_body || r->have)
            snprintf(rep->failure, sizeof rep->failure, "the plug-in's process ended in the middle of an answer");
        break;
    }
}

int sh_plugin_run_fixture(const sh_plugin *p, const sh_fixture *fx, const unsigned char *skip, double **got,
                          unsigned char *status, sh_plugin_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->current = -1;
    for (int k = 0; k < fx->ncases; k++) status[k] = SH_PLUGIN_CASE_NOT_RUN;
    const fixture_job j = {p, fx, skip};
    reader r = {.fx = fx, .got = got, .rep = rep, .status = status};
    const sh_sandbox_job sj = {.child = fixture_child, .feed = reader_feed, .arg = (void *)&j, .fctx = &r,
                               .cpu_seconds = p->timeout_s, .wall_seconds = p->timeout_s,
                               .mem_bytes = 1LL << 30, .what = "the plug-in"};
    sh_sandbox_result sr;
    int st = sh__sandbox_run(&sj, &sr);
    if (st) return st;
    describe(p, fx, &sr, &r, rep);
    rep->failed = rep->failure[0] != '\0';
    return SH_OK;
}
