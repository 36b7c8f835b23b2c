/* mesh_frame.c — the byte stream a mesh comes back on from the importer's
 * child process (mesh_internal.h: the layout, sh_mesh_frame_reader).
 *
 * Writer and reader of one frame: a fixed header, a body whose size the
 * header's counts fix, a trailer repeating the body's size, then the end of
 * the stream.  The reader takes the stream in chunks of any size (as read(2)
 * returns them, or as a fuzzer cuts them), checks every part as soon as it is
 * complete and before acting on it — counts within the bounds the parent
 * computed from the file (the guard's), never what the child claims alone —
 * and copies the arrays straight into the mesh it returns. */
#include "scene/mesh_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

_Static_assert(sizeof(int) == sizeof(int32_t), "triangle indices travel as int32");
_Static_assert(sizeof(sh_mesh_frame_hdr) == 48, "the frame header has no padding");

static const char MAGIC[8] = {'S', 'H', 'M', 'E', 'S', 'H', 1, '\n'};
static const char MAGIC_END[8] = {'S', 'H', 'M', 'E', 'S', 'H', '-', 'E'};

enum { S_HDR, S_MSG, S_POS, S_NRM, S_TRI, S_TRAILER, S_DONE, S_BROKEN };
static const char *const stage_name[] = {"header", "message", "positions", "normals", "triangles", "trailer"};

/* ------------------------------------------------------------- writer */

/* Write n bytes (EINTR and short writes retried): 0, or -1. */
static int write_all(int fd, const void *p, size_t n)
{
    const char *b = p;
    while (n > 0) {
        const ssize_t w = write(fd, b, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return -1;
        b += w;
        n -= (size_t)w;
    }
    return 0;
}

int sh__mesh_frame_write(int fd, int st, const sh_mesh *m, const sh_mesh_report *rep)
{
    sh_mesh_frame_hdr h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, MAGIC, 8);
    const char *msg = NULL;
    uint64_t body = 0;
    if (st == SH_OK) {
        h.kind = SH_FRAME_MESH;
        h.nvert = m->nvert;
        h.ntri = m->ntri;
        h.has_normals = m->normal != NULL;
        h.submeshes = rep->submeshes;
        h.skipped = rep->skipped_primitives;
        body = (uint64_t)h.nvert * 3 * sizeof(double) * (h.has_normals ? 2 : 1) + (uint64_t)h.ntri * 3 * sizeof(int32_t);
    } else {
        h.kind = SH_FRAME_ERROR;
        h.status = st;
        msg = sh_last_error();
        if (!msg || !*msg) msg = "the importer failed";
        h.msglen = (uint32_t)(strlen(msg) > SH_FRAME_MAX_MSG ? SH_FRAME_MAX_MSG : strlen(msg));
        body = h.msglen;
    }
    if (write_all(fd, &h, sizeof h)) return -1;
    if (msg && write_all(fd, msg, h.msglen)) return -1;
    if (st == SH_OK) {
        if (write_all(fd, m->pos, (size_t)h.nvert * 3 * sizeof(double))) return -1;
        if (h.has_normals && write_all(fd, m->normal, (size_t)h.nvert * 3 * sizeof(double))) return -1;
        if (write_all(fd, m->tri, (size_t)h.ntri * 3 * sizeof(int32_t))) return -1;
    }
    unsigned char tr[16];
    memcpy(tr, MAGIC_END, 8);
    memcpy(tr + 8, &body, 8);
    return write_all(fd, tr, sizeof tr);
}

/* ------------------------------------------------------------- reader */

/* The stream broke a rule: remember which, refuse all further bytes; -1. */
static int broken(sh_mesh_frame_reader *r, const char *why)
{
    snprintf(r->why, sizeof r->why, "%s", why);
    r->stage = S_BROKEN;
    return -1;
}

/* The next part: need bytes into dst. */
static void expect(sh_mesh_frame_reader *r, int stage, void *dst, size_t need)
{
    r->stage = stage;
    r->dst = dst;
    r->need = need;
    r->got = 0;
}

void sh__mesh_frame_begin(sh_mesh_frame_reader *r, long long max_vertices, long long max_triangles)
{
    memset(r, 0, sizeof *r);
    r->max_vertices = max_vertices < SH_MESH_MAX_ELEMS ? max_vertices : SH_MESH_MAX_ELEMS;
    r->max_triangles = max_triangles < SH_MESH_MAX_ELEMS ? max_triangles : SH_MESH_MAX_ELEMS;
    expect(r, S_HDR, &r->hdr, sizeof r->hdr);
}

/* The header is complete: check it, then allocate what it announces. */
static int header_done(sh_mesh_frame_reader *r)
{
    const sh_mesh_frame_hdr *h = &r->hdr;
    char why[160];
    if (memcmp(h->magic, MAGIC, 8)) return broken(r, "no frame header (wrong magic)");
    if (h->kind == SH_FRAME_ERROR) {
        if (h->status <= SH_OK || h->status > SH_ENUM) return broken(r, "an error frame without an error status");
        if (h->msglen == 0 || h->msglen > SH_FRAME_MAX_MSG) return broken(r, "an error frame's message length is out of range");
        if (h->nvert || h->ntri || h->has_normals) return broken(r, "an error frame with mesh counts");
        expect(r, S_MSG, r->msg, h->msglen);
        return 0;
    }
    if (h->kind != SH_FRAME_MESH) return broken(r, "unknown frame kind");
    if (h->status != SH_OK || h->msglen) return broken(r, "a mesh frame with an error status or message");
    if (h->nvert < 1 || h->nvert > r->max_vertices || h->ntri < 1 || h->ntri > r->max_triangles) {
        snprintf(why, sizeof why, "%lld vertices and %lld triangles, outside 1..%lld and 1..%lld (what the file can hold)",
                 (long long)h->nvert, (long long)h->ntri, r->max_vertices, r->max_triangles);
        return broken(r, why);
    }
    if ((h->has_normals != 0 && h->has_normals != 1) || h->submeshes < 1 || h->skipped < 0)
        return broken(r, "a mesh frame with bad submesh counts or normal flag");
    const size_t nv = (size_t)h->nvert, nt = (size_t)h->ntri;
    r->mesh.pos = malloc(3 * nv * sizeof(double));
    r->mesh.normal = h->has_normals ? malloc(3 * nv * sizeof(double)) : NULL;
    r->mesh.tri = malloc(3 * nt * sizeof(int));
    if (!r->mesh.pos || !r->mesh.tri || (h->has_normals && !r->mesh.normal)) {
        sh_mesh_free(&r->mesh);
        return broken(r, "out of memory for the mesh");
    }
    expect(r, S_POS, r->mesh.pos, 3 * nv * sizeof(double));
    return 0;
}

/* A part is complete: check it and expect the next one. */
static int part_done(sh_mesh_frame_reader *r)
{
    switch (r->stage) {
    case S_HDR: return header_done(r);
    case S_MSG:
        r->msg[r->hdr.msglen] = '\0';
        if (strlen(r->msg) != r->hdr.msglen) return broken(r, "a NUL in the error message");
        expect(r, S_TRAILER, r->trailer, sizeof r->trailer);
        return 0;
    case S_POS:
        if (r->hdr.has_normals) expect(r, S_NRM, r->mesh.normal, 3 * (size_t)r->hdr.nvert * sizeof(double));
        else expect(r, S_TRI, r->mesh.tri, 3 * (size_t)r->hdr.ntri * sizeof(int));
        return 0;
    case S_NRM: expect(r, S_TRI, r->mesh.tri, 3 * (size_t)r->hdr.ntri * sizeof(int)); return 0;
    case S_TRI:
        r->mesh.nvert = (int)r->hdr.nvert;
        r->mesh.ntri = (int)r->hdr.ntri;
        expect(r, S_TRAILER, r->trailer, sizeof r->trailer);
        return 0;
    case S_TRAILER: {
        uint64_t b;
        memcpy(&b, r->trailer + 8, 8);
        if (memcmp(r->trailer, MAGIC_END, 8)) return broken(r, "no frame trailer (wrong magic)");
        if (b != r->body) return broken(r, "the trailer's body size differs from the body received");
        r->stage = S_DONE;
        return 0;
    }
    default: return broken(r, "internal: bad stage");
    }
}

int sh__mesh_frame_feed(sh_mesh_frame_reader *r, const void *bytes, size_t n)
{
    const unsigned char *b = bytes;
    while (n > 0) {
        if (r->stage == S_BROKEN) return -1;
        if (r->stage == S_DONE) return broken(r, "data after the end of the frame");
        size_t take = r->need - r->got;
        if (take > n) take = n;
        memcpy(r->dst + r->got, b, take);
        r->got += take;
        if (r->stage != S_HDR && r->stage != S_TRAILER) r->body += take;
        b += take;
        n -= take;
        if (r->got == r->need && part_done(r)) return -1;
    }
    /* a zero-length part (no normals, ...) completes without bytes */
    return r->stage == S_BROKEN ? -1 : 0;
}

int sh__mesh_frame_complete(sh_mesh_frame_reader *r)
{
    if (r->stage == S_DONE) return 1;
    if (r->stage != S_BROKEN) {
        char why[160];
        snprintf(why, sizeof why, "the stream ended in the frame's %s (%zu of %zu bytes)", stage_name[r->stage], r->got,
                 r->need);
        broken(r, why);
    }
    return 0;
}

void sh__mesh_frame_end(sh_mesh_frame_reader *r) { sh_mesh_free(&r->mesh); }
