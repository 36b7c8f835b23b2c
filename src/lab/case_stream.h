/* case_stream.h — a kernel under test answers from its sandboxed child one
 * record per fixture case (case_stream.c): the plug-in runner (plugin.c)
 * and the shader runner (shader.c) share the records, the parent's reader
 * and the one line that says how a child ended.  Not installed. */
#ifndef SHLAB_CASE_STREAM_H
#define SHLAB_CASE_STREAM_H

#include "core/sandbox.h"
#include "lab/lab.h"

#include <stdint.h>

/* A record: "u32 kind, i32 case, i32 rc, i32 n" then n doubles (native byte
 * order: the same machine):
 *   START  case k is about to run (a crash or a hang then names it);
 *   DONE   case k returned rc, its n outputs follow;
 *   OPEN   the kernel could not be loaded: n doubles of message text;
 *   INFO   n doubles of text: the device that runs it (shaders). */
enum { SH_REC_START = 1, SH_REC_DONE = 2, SH_REC_OPEN = 3, SH_REC_INFO = 4 };
typedef struct {
    uint32_t kind;
    int32_t k, rc, n;
} sh_rec_hdr;
#define SH_REC_MAX_TEXT 512
/* the child's exit statuses */
enum { SH_CASE_CHILD_WRITE = SH_SANDBOX_CHILD_FIRST_FREE, SH_CASE_CHILD_FAULT, SH_CASE_CHILD_CORRUPT };

int sh__rec_send(int fd, int kind, int k, int rc, const double *v, int n);
/* An OPEN or INFO record carrying text. */
int sh__rec_send_text(int fd, int kind, const char *text);

/* The parent's side: records checked against the fixture before a value is
 * stored; rc 0 (SHLAB_KERNEL_OK) ran, 1 (UNSUPPORTED) declined, other
 * values a failure (its outputs become NaN). */
typedef struct {
    const sh_fixture *fx;
    double **got;
    sh_plugin_report *rep;
    unsigned char *status;
    const char *who;   /* "the plug-in", "the shader": in messages */
    char info[SH_REC_MAX_TEXT]; /* the last INFO text */
    sh_rec_hdr h;
    size_t have;       /* bytes of the current header or body */
    int in_body;
    unsigned char buf[sizeof(sh_rec_hdr) + SH_REC_MAX_TEXT];
    double *body;      /* where the body goes */
    size_t body_bytes;
    const char *why;   /* the protocol broken */
} sh_case_reader;
int sh__case_reader_feed(void *fctx, const unsigned char *bytes, size_t n);
/* rep->failure: the one line for how the child ended (nothing if well). */
void sh__case_describe(double timeout_s, const sh_fixture *fx, const sh_sandbox_result *sr, const sh_case_reader *r,
                       sh_plugin_report *rep);

/* A child's whole answer kept as bytes (the timing runs: a few records),
 * refused once it outgrows cap. */
typedef struct {
    unsigned char *buf;
    size_t have, cap;
} sh_byte_sink;
int sh__byte_sink_feed(void *fctx, const unsigned char *bytes, size_t n);

#endif
