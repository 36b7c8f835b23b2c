/* case_stream.c — records of a kernel's sandboxed child, one per fixture
 * case, and the parent's reader (case_stream.h). */
#include "lab/case_stream.h"
#include "core/shlab_internal.h"
#include "shlab/kernel.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

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

int sh__rec_send(int fd, int kind, int k, int rc, const double *v, int n)
{
    const sh_rec_hdr h = {(uint32_t)kind, k, rc, n};
    return write_all(fd, &h, sizeof h) || (n && write_all(fd, v, (size_t)n * sizeof *v)) ? -1 : 0;
}

int sh__rec_send_text(int fd, int kind, const char *text)
{
    double buf[SH_REC_MAX_TEXT / sizeof(double)];
    memset(buf, 0, sizeof buf);
    snprintf((char *)buf, sizeof buf, "%s", text);
    const int nd = (int)((strlen((char *)buf) + sizeof(double)) / sizeof(double));
    return sh__rec_send(fd, kind, -1, 0, buf, nd);
}

static int rec_begin_body(sh_case_reader *r)
{
    const sh_rec_hdr *h = &r->h;
    if (h->kind == SH_REC_OPEN || h->kind == SH_REC_INFO) {
        if (h->n < 1 || (size_t)h->n * sizeof(double) > SH_REC_MAX_TEXT) return (r->why = "bad message length"), -1;
        r->body = (double *)(void *)r->buf;
        r->body_bytes = (size_t)h->n * sizeof(double);
        return 0;
    }
    if (h->k < 0 || h->k >= r->fx->ncases) return (r->why = "case index out of range"), -1;
    if (h->kind == SH_REC_START) {
        if (h->n) return (r->why = "START with a body"), -1;
        r->rep->current = h->k;
        return 0;
    }
    if (h->kind != SH_REC_DONE || h->n != r->fx->cases[h->k].n) return (r->why = "bad record"), -1;
    r->body = r->got[h->k];
    r->body_bytes = (size_t)h->n * sizeof(double);
    return 0;
}

static void rec_end(sh_case_reader *r)
{
    const sh_rec_hdr *h = &r->h;
    if (h->kind == SH_REC_OPEN) {
        char *m = (char *)r->buf;
        m[r->body_bytes - 1] = '\0';
        snprintf(r->rep->failure, sizeof r->rep->failure, "cannot load %s: %.280s", r->who, m);
        r->rep->open_failed = 1;
    } else if (h->kind == SH_REC_INFO) {
        char *m = (char *)r->buf;
        m[r->body_bytes - 1] = '\0';
        snprintf(r->info, sizeof r->info, "%.500s", m);
    } else if (h->kind == SH_REC_DONE) {
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

int sh__case_reader_feed(void *fctx, const unsigned char *bytes, size_t n)
{
    sh_case_reader *r = fctx;
    while (n || (r->in_body && r->have == r->body_bytes)) {
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
        if (take) memcpy((unsigned char *)r->body + r->have, bytes, take); /* a START has no body */
        r->have += take, bytes += take, n -= take;
        if (r->have < r->body_bytes) return 0;
        rec_end(r);
        r->have = 0;
        r->in_body = 0;
    }
    return 0;
}

/* The one line that says what happened to the child, into rep->failure. */
void sh__case_describe(double timeout_s, const sh_fixture *fx, const sh_sandbox_result *sr, const sh_case_reader *r,
                       sh_plugin_report *rep)
{
    if (rep->open_failed) return;
    char at[96] = "";
    if (rep->current >= 0) snprintf(at, sizeof at, " on case '%s'", fx->cases[rep->current].id);
    const char *line = sr->first_line;
    switch (sr->outcome) {
    case SH_SANDBOX_WALL:
        snprintf(rep->failure, sizeof rep->failure, "the kernel did not return within %g s%s (stopped)", timeout_s, at);
        break;
    case SH_SANDBOX_CPU:
        snprintf(rep->failure, sizeof rep->failure, "the kernel used more than %g s of CPU time%s (stopped)",
                 sr->cpu_limit, at);
        break;
    case SH_SANDBOX_MEMORY:
        snprintf(rep->failure, sizeof rep->failure, "the kernel went over its memory limit%s (stopped)", at);
        break;
    case SH_SANDBOX_BROKEN:
        snprintf(rep->failure, sizeof rep->failure, "%s's process broke its answer (%s)", r->who, r->why ? r->why : "?");
        break;
    case SH_SANDBOX_SIGNAL:
        if (*line) snprintf(rep->failure, sizeof rep->failure, "%s", line);
        else snprintf(rep->failure, sizeof rep->failure, "the kernel was killed by signal %d (%s)%s", sr->signal,
                      strsignal(sr->signal), at);
        break;
    case SH_SANDBOX_DONE:
        if (sr->exit_status == SH_CASE_CHILD_FAULT || sr->exit_status == SH_CASE_CHILD_CORRUPT)
            snprintf(rep->failure, sizeof rep->failure, "%s", *line ? line : "the kernel crashed");
        else if (sr->exit_status != 0)
            snprintf(rep->failure, sizeof rep->failure, "the kernel's process exited with status %d%.96s%s%.150s",
                     sr->exit_status, at, *line ? ": " : "", line);
        else if (r->in_body || r->have)
            snprintf(rep->failure, sizeof rep->failure, "%s's process ended in the middle of an answer", r->who);
        break;
    }
}


int sh__byte_sink_feed(void *fctx, const unsigned char *bytes, size_t n)
{
    sh_byte_sink *s = fctx;
    if (s->have + n > s->cap) return -1;
    memcpy(s->buf + s->have, bytes, n);
    s->have += n;
    return 0;
}
