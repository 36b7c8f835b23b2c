/* mesh_sandbox.c — the mesh importer in a child process with limits
 * (sh__mesh_sandbox, mesh_internal.h).
 *
 * assimp can abort (ai_assert), loop forever or allocate without bound on a
 * file the guard let through; none of that may take the calling process
 * down.  So the import runs in the sandbox (src/core/sandbox.c: a child with
 * CPU, memory and wall-clock limits; the reasons are listed there), which
 * sends the mesh back as a frame (mesh_frame.c) that the parent checks
 * against the guard's bounds as it arrives. */
#include "scene/mesh_internal.h"
#include "core/sandbox.h"

#include <signal.h>
#include <string.h>

/* the child's exit status when its pipe broke */
enum { CHILD_WRITE_FAILED = SH_SANDBOX_CHILD_FIRST_FREE };

typedef struct {
    const sh_mesh_job *job;
    sh_mesh_frame_reader fr;
} mesh_run;

/* In the child: the import, its result as a frame on fd. */
static int import_child(void *arg, int fd)
{
    const sh_mesh_job *job = ((const mesh_run *)arg)->job;
    if (job->raw) {
        job->raw(job->arg, fd);
        return 0;
    }
    sh_mesh m;
    sh_mesh_report rep;
    memset(&m, 0, sizeof m);
    memset(&rep, 0, sizeof rep);
    const int st = job->run(job->arg, &m, &rep);
    return sh__mesh_frame_write(fd, st, &m, &rep) ? CHILD_WRITE_FAILED : 0;
}

/* In the parent: each chunk of the frame, checked as it arrives. */
static int import_feed(void *fctx, const unsigned char *bytes, size_t n)
{
    return sh__mesh_frame_feed(&((mesh_run *)fctx)->fr, bytes, n) != 0;
}

/* The import's outcome: the first failure that explains it, else the mesh
 * into out. */
static int import_result(const sh_mesh_job *job, mesh_run *mr, const sh_sandbox_result *r, sh_mesh *out,
                         sh_mesh_report *rep)
{
    const char *line = r->first_line;
    const sh_mesh_frame_reader *fr = &mr->fr;
    switch (r->outcome) {
    case SH_SANDBOX_MEMORY:
        return sh_error(SH_EFORMAT, "the importer went over its memory limit of %lld MB (stopped)", job->mem_bytes >> 20);
    case SH_SANDBOX_WALL:
        return sh_error(SH_EFORMAT, "the importer did not finish within %g s (stopped)", job->wall_seconds);
    case SH_SANDBOX_BROKEN: return sh_error(SH_EFORMAT, "the importer's answer broke the protocol: %s", fr->why);
    case SH_SANDBOX_CPU:
        return sh_error(SH_EFORMAT, "the importer used more than its %g s of CPU time (stopped)", r->cpu_limit);
    case SH_SANDBOX_SIGNAL:
        return sh_error(SH_EFORMAT, "the importer (assimp) was killed by signal %d (%s)%s%s", r->signal,
                        strsignal(r->signal), *line ? ": " : "", line);
    case SH_SANDBOX_DONE: break;
    }
    if (r->exit_status != 0)
        return sh_error(SH_EFORMAT, "the importer exited with status %d%s%s", r->exit_status, *line ? ": " : "", line);
    if (!sh__mesh_frame_complete(&mr->fr)) return sh_error(SH_EFORMAT, "the importer's answer broke the protocol: %s", fr->why);
    if (fr->hdr.kind == SH_FRAME_ERROR) {
        const int oom = strstr(fr->msg, "bad_alloc") != NULL;
        if (oom && job->mem_bytes > 0)
            return sh_error(fr->hdr.status, "%s (over the importer's memory limit of %lld MB)", fr->msg, job->mem_bytes >> 20);
        return sh_error(fr->hdr.status, "%s", fr->msg);
    }
    *out = mr->fr.mesh;
    memset(&mr->fr.mesh, 0, sizeof mr->fr.mesh);
    rep->submeshes = fr->hdr.submeshes;
    rep->skipped_primitives = fr->hdr.skipped;
    return SH_OK;
}

int sh__mesh_sandbox(const sh_mesh_job *job, sh_mesh *out, sh_mesh_report *rep)
{
    memset(out, 0, sizeof *out);
    mesh_run mr = {.job = job};
    sh__mesh_frame_begin(&mr.fr, job->max_vertices, job->max_triangles);
    const sh_sandbox_job sj = {.child = import_child, .feed = import_feed, .arg = &mr, .fctx = &mr,
                               .cpu_seconds = job->cpu_seconds, .wall_seconds = job->wall_seconds,
                               .mem_bytes = job->mem_bytes, .what = "the mesh importer"};
    sh_sandbox_result r;
    int st = sh__sandbox_run(&sj, &r);
    if (!st) st = import_result(job, &mr, &r, out, rep);
    sh__mesh_frame_end(&mr.fr);
    return st;
}
