/* mesh_internal.h — the parts of mesh loading shared by src/scene/mesh*.c
 * and the tests (not installed).  Loading a mesh file is four steps, one
 * file each:
 *
 *   mesh_guard.c, mesh_guard_ply.c, mesh_guard_obj.c — cheap checks of the
 *       bytes before any importer sees them (the format by name and content;
 *       PLY and OBJ parsed by our own small readers, counts bounded by the
 *       file's length, coordinates finite and in range, indices in range);
 *   mesh_import.c  — assimp on those bytes, in this process (no file is
 *       opened but the ones the guard allows), copied out to an sh_mesh;
 *   mesh_frame.c   — the framed, size-checked byte stream a child process
 *       sends that mesh through;
 *   mesh_sandbox.c — the importer run in a child process with CPU-time,
 *       memory and wall-clock limits, so that an abort, a hang or an
 *       allocation storm inside assimp costs one error line.
 *
 * mesh.c (sh_mesh_load, sh_mesh_load_mem) strings them together. */
#ifndef SHLAB_MESH_INTERNAL_H
#define SHLAB_MESH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "core/shlab_internal.h"

/* Built with AddressSanitizer: the sandbox limits memory another way there,
 * and the budget allows for the sanitizer's own use (core/sandbox.h). */
#include "core/sandbox.h"
#ifdef SH_SANDBOX_ASAN
#define SH_MESH_ASAN 1
#endif

/* ------------------------------------------------------------------ guard */

enum { SH_MESH_FMT_OTHER = 0, SH_MESH_FMT_PLY = 1, SH_MESH_FMT_OBJ = 2 };

/* A PLY header longer than this is refused (it must end, with its
 * end_header line, within this prefix of the file). */
#define SH_MESH_PLY_MAX_HEADER 65536
/* Most vertex indices in one PLY face or OBJ statement (assimp's
 * AI_MAX_FACE_INDICES). */
#define SH_MESH_MAX_FACE_INDICES 0x7fff
/* assimp triangulates a face of k > 4 corners in time ~ k² (measured: a
 * convex face of 8000 corners 0.9 s, 16000 3.2 s, 32767 16.5 s on the
 * test machine), so the sum of k² over such faces is bounded by this
 * budget for a file of n bytes: 2^28 (~3.5 s) plus 32 per byte (~0.4 s a
 * MB, within the CPU budget's 0.5 s a MB).  Faces of up to ~100 corners
 * never come near it (their k² is at most 50 times their bytes). */
#define SH_MESH_NGON_WORK(n) ((1LL << 28) + 32LL * (long long)(n))

/* What the guard found.  The importer is given `bytes` (the file's own bytes,
 * or for PLY a canonical copy: see mesh_guard_ply.c) under the name `name`,
 * whose extension makes assimp choose the reader the guard checked for.
 * max_vertices/max_triangles bound what a correct import of these bytes can
 * give (the parent refuses a child that claims more). */
typedef struct {
    int format;                   /* SH_MESH_FMT_* */
    const unsigned char *bytes;   /* what the importer reads: data or canon */
    size_t size;
    unsigned char *canon;         /* malloc'd canonical copy, or NULL */
    char *name;                   /* malloc'd name given to the importer */
    long long max_vertices, max_triangles;
    long long mem_budget;         /* bytes the importer may add to its address space */
    double cpu_seconds;           /* CPU time the importer may use */
} sh_mesh_guard;

/* Check the bytes of a mesh file named `name` (a path or a bare name: its
 * extension and the bytes choose the format, as assimp would) before any
 * importer sees them; flags: sh_mesh_load's (SH_MESH_COMPUTE_NORMALS: file
 * normals are not checked, they will be ignored).  SH_OK and *g filled (free
 * with sh__mesh_guard_free), or SH_EFORMAT / SH_ENOMEM with a one-line reason
 * that does not name the file (the caller does) and *g empty. */
int sh__mesh_guard(const unsigned char *data, size_t n, const char *name, int flags, sh_mesh_guard *g);
void sh__mesh_guard_free(sh_mesh_guard *g);

/* The format-specific halves (mesh_guard_ply.c, mesh_guard_obj.c): same
 * contract, g->format, ->bytes/->size and ->name already set by
 * sh__mesh_guard; they set the bounds and, for PLY, the canonical copy. */
int sh__mesh_guard_ply(const unsigned char *data, size_t n, int flags, sh_mesh_guard *g);
int sh__mesh_guard_obj(const unsigned char *data, size_t n, int flags, sh_mesh_guard *g);

/* Shared by the two readers (mesh_guard.c).  Split s[0..len) at spaces and
 * tabs (what assimp's SkipSpaces skips) into at most max tokens, tok[k] and
 * tl[k] their starts and lengths: the count, or max + 1 if there are more
 * (then only max are set). */
int sh__mesh_tokens(const char *s, size_t len, const char **tok, size_t *tl, int max);
/* A number as assimp's
 * fast_atof reads it, restricted to what it and strtod(3) read alike:
 * [+-]? (D+ (. D*)? | . D+) ([eE] [+-]? D+)?, at most 64 characters, a
 * decimal exponent at most max_exp (38 when assimp parses into a float,
 * whose 10^e would overflow above; 308 into a double).  s[0..len) is the
 * token.  Returns 0 and, if v is not NULL, *v (strtod's value; without v
 * the conversion is skipped when the digits alone bound |x| below 1e37),
 * or a negative code:
 * SH_NUM_SYNTAX, SH_NUM_NONFINITE (nan, inf, infinity in any case, signed),
 * SH_NUM_RANGE (exponent too large, or |v| > SH_MESH_MAX_COORD). */
enum { SH_NUM_SYNTAX = -1, SH_NUM_NONFINITE = -2, SH_NUM_RANGE = -3 };
int sh__mesh_number(const char *s, size_t len, int max_exp, double *v);
/* The phrase for a value that sh__mesh_number refused (code < 0), what
 * being "coordinate" or "normal": "a non-finite coordinate 'nan'", "a
 * coordinate out of range: '1e308' (|x| <= 1e+38)", "a coordinate that is
 * not a number: 'x'"; written to buf, which is returned. */
const char *sh__mesh_number_why(int code, const char *what, const char *tok, size_t len, char *buf, size_t cap);

/* ----------------------------------------------------------------- import */

/* Import bytes[0..size) as the file `name` with assimp in this process:
 * triangulated, node transforms applied, submeshes concatenated, raw
 * positions refused if not finite or beyond SH_MESH_MAX_COORD before any
 * post-processing step (which could merge them away).  side_files: 1 lets
 * the importer read other files (an OBJ's material library) named relative
 * to `name`, through sh_input_open's policy; 0 refuses every other file.
 * Fills *m (positions, normals if every kept submesh has them and not
 * SH_MESH_COMPUTE_NORMALS, triangles; no sh_mesh_check, no SH_MESH_Y_UP)
 * and rep->submeshes, ->skipped_primitives.  SH_EFORMAT / SH_ENOMEM with a
 * reason (no file name) and *m empty on failure. */
int sh__mesh_import(const unsigned char *bytes, size_t size, const char *name, int side_files, int flags,
                    sh_mesh *m, sh_mesh_report *rep);

/* ------------------------------------------------------------------ frame */

/* The child's answer on its pipe (native byte order: same machine):
 *   header  magic "SHMESH\1\n", u32 kind (1 mesh, 2 error), i32 status,
 *           i64 nvert, i64 ntri, i32 has_normals, i32 submeshes,
 *           i32 skipped, u32 message length
 *   body    mesh: 3·nvert doubles, 3·nvert doubles if has_normals,
 *           3·ntri int32; error: the message (< 1024 bytes, no NUL)
 *   trailer magic "SHMESH-E", u64 body bytes
 * and then the end of the stream. */
typedef struct {
    char magic[8];
    uint32_t kind;
    int32_t status;
    int64_t nvert, ntri;
    int32_t has_normals, submeshes, skipped;
    uint32_t msglen;
} sh_mesh_frame_hdr;
enum { SH_FRAME_MESH = 1, SH_FRAME_ERROR = 2 };
#define SH_FRAME_MAX_MSG 1023

/* Write the frame for a finished import (st == SH_OK: *m and rep; else the
 * reason sh_last_error()) to fd.  0, or -1 if a write failed. */
int sh__mesh_frame_write(int fd, int st, const sh_mesh *m, const sh_mesh_report *rep);

/* The reader: fed the stream in chunks of any size, it checks each part as
 * it completes (magic, kind, counts against the bounds before anything is
 * allocated, the message, the trailer) and copies the arrays straight into
 * their sh_mesh.  Never trusts a count: the bounds come from the guard. */
typedef struct {
    long long max_vertices, max_triangles; /* set before the first feed */
    sh_mesh_frame_hdr hdr;
    sh_mesh mesh;                           /* filled as the body arrives */
    char msg[SH_FRAME_MAX_MSG + 1];
    int stage;                              /* internal */
    size_t got, need;                       /* bytes of the current part */
    unsigned char *dst;
    unsigned char trailer[16];
    uint64_t body;
    char why[160];                          /* the first broken rule */
} sh_mesh_frame_reader;
/* Start a reader (bounds as above). */
void sh__mesh_frame_begin(sh_mesh_frame_reader *r, long long max_vertices, long long max_triangles);
/* Feed n bytes: 0, or -1 once the stream broke a rule (r->why says which;
 * later feeds keep failing). */
int sh__mesh_frame_feed(sh_mesh_frame_reader *r, const void *bytes, size_t n);
/* The stream ended: 1 if it held exactly one complete frame, else 0 with
 * r->why set.  Then r->hdr and, for a mesh frame, r->mesh (the caller takes
 * it) or r->msg are valid. */
int sh__mesh_frame_complete(sh_mesh_frame_reader *r);
/* Free what the reader holds (the mesh, unless taken). */
void sh__mesh_frame_end(sh_mesh_frame_reader *r);

/* ---------------------------------------------------------------- sandbox */

/* One job for a child process.  run(arg, m, rep) is called in the child and
 * its result sent back as a frame; raw(arg, fd), when set instead, writes
 * whatever it likes to the result pipe (tests of the reader).  Limits: CPU
 * seconds (RLIMIT_CPU), bytes the child may add to its address space
 * (RLIMIT_AS over its size at the fork; 0: no limit), wall seconds (then
 * SIGKILL).  Bounds for the reader as in sh_mesh_frame_reader. */
typedef struct {
    int (*run)(void *arg, sh_mesh *m, sh_mesh_report *rep);
    void (*raw)(void *arg, int fd);
    void *arg;
    double cpu_seconds, wall_seconds;
    long long mem_bytes;
    long long max_vertices, max_triangles;
} sh_mesh_job;

/* Run the job in a child (fork; the child resets every signal to its
 * default, reads nothing, writes only its pipes, and leaves by _exit) and
 * wait for it within the limits.  SH_OK and *out, rep->submeshes and
 * ->skipped_primitives from a complete, valid frame of a child that exited
 * with status 0; else SH_EFORMAT (the child's own status and reason if it
 * sent one, else what happened to it: killed by a signal, with the first line
 * it wrote to stderr; over its CPU time; past the wall-clock limit; a broken
 * frame), or SH_EIO if no child could be started, with *out empty. */
int sh__mesh_sandbox(const sh_mesh_job *job, sh_mesh *out, sh_mesh_report *rep);

#endif
