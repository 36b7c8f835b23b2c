/* test_mesh_guard.c — the guard in front of the mesh importer and the
 * importer's sandbox (src/scene/mesh_internal.h): the child process's limits
 * and the parent's checks of what it sends, each guard rule on a file built
 * here byte by byte, and the real test models loaded through the guard
 * against an independent reading of their text (tests/cli/test_meshes.sh
 * runs the hostile files of tests/fuzz/mesh_files.pl through the CLI). */
#include "testutil.h"

#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "scene/mesh_internal.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* the reason is one printable line */
static void one_line(void)
{
    const char *w = sh_last_error();
    ck_assert(w && *w);
    for (const char *p = w; *p; p++) ck_assert_msg((unsigned char)*p >= 0x20, "control character in '%s'", w);
}

/* ------------------------------------------------------------- sandbox */

/* a unit right triangle (0,0,0) (1,0,0) (0,1,0) */
static int run_triangle(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    static const double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const int tri[3] = {0, 1, 2};
    m->nvert = 3;
    m->ntri = 1;
    m->pos = malloc(sizeof pos);
    m->tri = malloc(sizeof tri);
    memcpy(m->pos, pos, sizeof pos);
    memcpy(m->tri, tri, sizeof tri);
    rep->submeshes = 1;
    rep->skipped_primitives = 7;
    return SH_OK;
}
static int run_abort(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    static const char msg[] = "ai_assert failure in ./code/PostProcessing/TriangulateProcess.cpp(238): numOut != x\n";
    if (write(2, msg, sizeof msg - 1) < 0) {}
    abort();
}
static int run_sleep(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    for (;;) pause();
    return 0;
}
static int run_spin(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    volatile unsigned long x = 0;
    for (;;) x++;
    return 0;
}
/* allocate and touch 1 MB blocks until one fails (at most 4 GB) */
static int run_grow(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    for (int k = 0; k < 4096; k++) {
        char *p = malloc(1 << 20);
        if (!p) return sh_error(SH_ENOMEM, "out of memory after %d MB", k);
        memset(p, 1, 1 << 20);
    }
    return sh_error(SH_EFORMAT, "4 GB allocated: no limit");
}
/* what an importer leaks stays in the child: it leaves by _exit, so
 * LeakSanitizer (under SANITIZE=1) makes no report there, which would end
 * it with status 23, and the parent never held the memory */
static void *volatile leaked;
static int run_leak(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    for (int k = 0; k < 16; k++) {
        leaked = malloc(1 << 20);
        memset(leaked, 7, 1 << 20);
    }
    leaked = NULL;
    return run_triangle(arg, m, rep);
}
static int run_refuse(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    return sh_error(SH_EFORMAT, "Invalid .ply file: the importer's own words");
}

static sh_mesh_job job_of(int (*run)(void *, sh_mesh *, sh_mesh_report *))
{
    sh_mesh_job j;
    memset(&j, 0, sizeof j);
    j.run = run;
    j.cpu_seconds = 5;
    j.wall_seconds = 5;
    j.mem_bytes = 256LL << 20;
    j.max_vertices = j.max_triangles = 100;
    return j;
}

START_TEST(test_sandbox_result)
{
    sh_mesh_job j = job_of(run_triangle);
    sh_mesh m;
    sh_mesh_report rep;
    memset(&rep, 0, sizeof rep);
    ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_OK);
    ck_assert_int_eq(m.nvert, 3);
    ck_assert_int_eq(m.ntri, 1);
    ck_assert_ptr_null(m.normal);
    ck_assert(m.pos[3] == 1 && m.pos[7] == 1 && m.tri[2] == 2);
    ck_assert_int_eq(rep.submeshes, 1);
    ck_assert_int_eq(rep.skipped_primitives, 7);
    sh_mesh_free(&m);
    j = job_of(run_leak);
    ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_OK);
    ck_assert_int_eq(m.ntri, 1);
    sh_mesh_free(&m);
    /* the child's own refusal comes back word for word, with its status */
    j = job_of(run_refuse);
    ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_EFORMAT);
    ck_assert_str_eq(sh_last_error(), "Invalid .ply file: the importer's own words");
    ck_assert_ptr_null(m.pos);
}
END_TEST

/* the parent's SIGABRT handler must not run in the child */
static char marker[256];
static void on_abrt(int sig)
{
    const int fd = open(marker, O_WRONLY | O_CREAT, 0600);
    if (fd >= 0) close(fd);
}

START_TEST(test_sandbox_abort)
{
    snprintf(marker, sizeof marker, "/tmp/shlab-test-mesh-guard-%d", (int)getpid());
    unlink(marker);
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_abrt;
    sigaction(SIGABRT, &sa, &old);
    sh_mesh_job j = job_of(run_abort);
    sh_mesh m;
    sh_mesh_report rep;
    const double t0 = now_s();
    ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_EFORMAT);
    ck_assert(now_s() - t0 < 2);
    sigaction(SIGABRT, &old, NULL);
    one_line();
    ck_assert_msg(strstr(sh_last_error(), "signal 6") && strstr(sh_last_error(), "ai_assert failure in"), "%s",
                  sh_last_error());
    ck_assert_msg(access(marker, F_OK) != 0, "the parent's SIGABRT handler ran in the child");
    ck_assert_ptr_null(m.pos);
}
END_TEST

START_TEST(test_sandbox_wall_limit)
{
    sh_mesh_job j = job_of(run_sleep);
    j.wall_seconds = 1;
    sh_mesh m;
    sh_mesh_report rep;
    const double t0 = now_s();
    ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_EFORMAT);
    const double dt = now_s() - t0;
    ck_assert_msg(dt >= 1 && dt < 2.5, "stopped after %.2f s", dt);
    ck_assert_msg(strstr(sh_last_error(), "did not finish within 1 s"), "%s", sh_last_error());
}
END_TEST

START_TEST(test_sandbox_cpu_limit)
{
    sh_mesh_job j = job_of(run_spin);
    j.cpu_seconds = 1;
    j.wall_seconds = 20; /* a loaded machine gives the child less than a core */
    sh_mesh m;
    sh_mesh_report rep;
    ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "more than its 1 s of CPU time"), "%s", sh_last_error());
}
END_TEST

START_TEST(test_sandbox_memory_limit)
{
    /* 64 MB over the child's address space at the fork: malloc fails there
     * (under AddressSanitizer the child's malloc hook stops it instead) */
    sh_mesh_job j = job_of(run_grow);
    j.mem_bytes = 64LL << 20;
    sh_mesh m;
    sh_mesh_report rep;
    const double t0 = now_s();
    const int st = sh__mesh_sandbox(&j, &m, &rep);
    ck_assert(now_s() - t0 < 5);
    one_line();
    ck_assert_msg(st == SH_ENOMEM || st == SH_EFORMAT, "status %d", st);
    ck_assert_msg(!strstr(sh_last_error(), "no limit"), "%s", sh_last_error());
    int mb = -1;
    const char *p = strstr(sh_last_error(), "out of memory after ");
    if (p) sscanf(p, "out of memory after %d MB", &mb);
    if (st == SH_ENOMEM) ck_assert_msg(mb >= 0 && mb <= 64, "%s", sh_last_error());
    else ck_assert_msg(strstr(sh_last_error(), "went over its memory limit of 64 MB"), "%s", sh_last_error());
}
END_TEST

/* ------------------------------------------------------------- frames */

static void put_hdr(int fd, uint32_t kind, int32_t status, int64_t nv, int64_t nt, uint32_t msglen)
{
    sh_mesh_frame_hdr h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, "SHMESH\1\n", 8);
    h.kind = kind;
    h.status = status;
    h.nvert = nv;
    h.ntri = nt;
    h.submeshes = 1;
    h.msglen = msglen;
    if (write(fd, &h, sizeof h) < 0) {}
}
static void put_bytes(int fd, size_t n, int c)
{
    char buf[256];
    memset(buf, c, sizeof buf);
    while (n > 0) {
        const size_t k = n < sizeof buf ? n : sizeof buf;
        if (write(fd, buf, k) < 0) return;
        n -= k;
    }
}
static void put_trailer(int fd, uint64_t body)
{
    if (write(fd, "SHMESH-E", 8) < 0 || write(fd, &body, 8) < 0) {}
}
/* lies a child could tell, by number */
static void raw_lie(void *arg, int fd)
{
    const int which = *(int *)arg;
    const size_t body = 3 * 3 * 8 + 3 * 4;
    switch (which) {
    case 0: put_hdr(fd, 1, 0, 1 << 26, 1, 0); break;        /* claims 2^26 vertices, sends nothing */
    case 1: put_hdr(fd, 1, 0, 3, 1, 0); put_bytes(fd, 20, 0); break;   /* a short body */
    case 2: put_hdr(fd, 1, 0, 3, 1, 0); put_bytes(fd, body, 0); put_trailer(fd, body); put_bytes(fd, 1, 0); break;
    case 3: put_hdr(fd, 1, 0, 3, 1, 0); put_bytes(fd, body, 0); put_trailer(fd, body + 1); break;
    case 4: put_bytes(fd, 100, 'x'); break;                 /* no frame at all */
    case 5: put_hdr(fd, 2, SH_EFORMAT, 0, 0, 5); if (write(fd, "ab\0cd", 5) < 0) {} put_trailer(fd, 5); break;
    case 6: break;                                          /* nothing */
    case 7: put_hdr(fd, 1, 0, -1, 1, 0); break;             /* a negative count */
    case 8: put_hdr(fd, 2, 0, 0, 0, 3); break;              /* an error frame without an error */
    }
}

START_TEST(test_frame_lies)
{
    static const char *const expect[] = {
        "outside 1..100",          "ended in the frame's positions", "data after the end",
        "trailer's body size",     "wrong magic",                    "a NUL in the error message",
        "frame's header (0 of 48", "outside 1..100",                 "without an error status"};
    for (int which = 0; which < 9; which++) {
        sh_mesh_job j = job_of(NULL);
        j.raw = raw_lie;
        j.arg = &which;
        sh_mesh m;
        sh_mesh_report rep;
        ck_assert_int_eq(sh__mesh_sandbox(&j, &m, &rep), SH_EFORMAT);
        ck_assert_ptr_null(m.pos);
        ck_assert_msg(strstr(sh_last_error(), "broke the protocol") && strstr(sh_last_error(), expect[which]),
                      "lie %d: %s", which, sh_last_error());
        one_line();
    }
}
END_TEST

/* a frame written to a pipe and read back in chunks of 1, 7 and all bytes */
START_TEST(test_frame_roundtrip)
{
    sh_mesh m = {0}, back;
    sh_mesh_report rep = {0};
    ck_assert_int_eq(run_triangle(NULL, &m, &rep), SH_OK);
    m.normal = calloc(9, sizeof(double));
    m.normal[2] = m.normal[5] = m.normal[8] = 1;
    int p[2];
    ck_assert_int_eq(pipe(p), 0);
    ck_assert_int_eq(sh__mesh_frame_write(p[1], SH_OK, &m, &rep), 0);
    close(p[1]);
    unsigned char buf[4096];
    const ssize_t n = read(p[0], buf, sizeof buf);
    close(p[0]);
    ck_assert_int_eq(n, 48 + 9 * 8 * 2 + 3 * 4 + 16);
    const size_t chunks[3] = {1, 7, (size_t)n};
    for (int c = 0; c < 3; c++) {
        sh_mesh_frame_reader r;
        sh__mesh_frame_begin(&r, 3, 1);
        for (size_t i = 0; i < (size_t)n; i += chunks[c])
            ck_assert_int_eq(sh__mesh_frame_feed(&r, buf + i, (size_t)n - i < chunks[c] ? (size_t)n - i : chunks[c]), 0);
        ck_assert_int_eq(sh__mesh_frame_complete(&r), 1);
        back = r.mesh;
        ck_assert_int_eq(back.nvert, 3);
        ck_assert(!memcmp(back.pos, m.pos, 9 * sizeof(double)) && !memcmp(back.normal, m.normal, 9 * sizeof(double)));
        ck_assert(!memcmp(back.tri, m.tri, 3 * sizeof(int)));
        sh__mesh_frame_end(&r);
    }
    /* bounds below the mesh: refused at the header, before any allocation */
    sh_mesh_frame_reader r;
    sh__mesh_frame_begin(&r, 2, 1);
    ck_assert_int_eq(sh__mesh_frame_feed(&r, buf, (size_t)n), -1);
    ck_assert_ptr_null(r.mesh.pos);
    sh__mesh_frame_end(&r);
    sh_mesh_free(&m);
}
END_TEST

/* ------------------------------------------------------------- guard */

/* load bytes through the whole path (guard, sandbox, check) */
static int load(const void *d, size_t n, const char *name, int flags, sh_mesh *m)
{
    sh_mesh_report rep;
    const int st = sh_mesh_load_mem(d, n, name, flags | SH_MESH_ALLOW_NONMANIFOLD, m, &rep);
    if (st) {
        one_line();
        ck_assert_ptr_null(m->pos);
    }
    return st;
}
static int loads(const char *text, const char *name, int flags, sh_mesh *m)
{
    return load(text, strlen(text), name, flags, m);
}
/* refused with a reason containing `why` */
#define REFUSED(text, name, why)                                                                         \
    do {                                                                                                 \
        sh_mesh m_;                                                                                      \
        ck_assert_int_eq(loads(text, name, 0, &m_), SH_EFORMAT);                                         \
        ck_assert_msg(strstr(sh_last_error(), why), "%s: expected '%s' in: %s", name, why, sh_last_error()); \
    } while (0)

static double mesh_area(const sh_mesh *m)
{
    double a = 0;
    for (int t = 0; t < m->ntri; t++) {
        const double *p = m->pos + 3 * m->tri[3 * t], *q = m->pos + 3 * m->tri[3 * t + 1],
                     *r = m->pos + 3 * m->tri[3 * t + 2];
        const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        a += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return a;
}

#define PLY_HEAD(fmt) "ply\nformat " fmt " 1.0\n"
#define SQ_VERTS "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
#define SQ_FACES "element face 2\nproperty list uchar int vertex_indices\n"
#define SQ_BODY "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"

START_TEST(test_guard_ply_ascii)
{
    sh_mesh m;
    /* the unit square, with a comment, obj_info, a Blender 2.4 bare line,
     * CRLF, blank lines and an element assimp makes nothing of */
    const char *ok = "ply\r\nformat ascii 1.0\r\ncomment hi\r\nobj_info x\r\nCreated by Blender3D 247\r\n" SQ_VERTS
                     "element edge 1\nproperty int vertex1\nproperty int vertex2\n" SQ_FACES "end_header\r\n"
                     "0 0 0\r\n\r\n1 0 0\n1 1 0\n0 1 0\n0 1\n3 0 1 2\n3 0 2 3\n\n";
    ck_assert_int_eq(loads(ok, "sq.ply", 0, &m), SH_OK);
    ck_assert_int_eq(m.ntri, 2);
    ck_close(mesh_area(&m), 1.0, TOL1, 1, "area");
    sh_mesh_free(&m);
    /* assimp's reused line buffer: after "comment b" it parsed the tail of
     * the longer comment before it, " element face 5", as an element (the
     * importer now sees our copy, without comments) */
    const char *smuggle = PLY_HEAD("ascii") "comment x  element face 5\ncomment b\n" SQ_VERTS SQ_FACES
                          "end_header\n" SQ_BODY;
    ck_assert_int_eq(loads(smuggle, "sm.ply", 0, &m), SH_OK);
    ck_assert_int_eq(m.ntri, 2);
    sh_mesh_free(&m);
    REFUSED(PLY_HEAD("ascii") "element vertex 99999999999999999999\nproperty float x\n" SQ_FACES "end_header\n0\n",
            "c.ply", "99999999999999999999 instances, more than the 67108864");
    REFUSED(PLY_HEAD("ascii") "element vertex 4000000000\nproperty float x\nend_header\n0\n", "c.ply",
            "4000000000 instances");
    REFUSED(PLY_HEAD("ascii") "element vertex 1000\nproperty float x\nproperty float y\nend_header\n0 0\n", "c.ply",
            "fewer than its header's counts need");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n", "c.ply",
            "ends in element 'face' after 1 of its 2");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "c.ply",
            "line 11 has fewer values");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0 7\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
            "c.ply", "line 10 has more values");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n" SQ_BODY "3 0 1 2\n", "c.ply", "text after its last");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 nan\n3 0 1 2\n3 0 2 3\n",
            "c.ply", "PLY vertex 3 (line 13) has a non-finite coordinate 'nan'");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 1e39\n3 0 1 2\n3 0 2 3\n",
            "c.ply", "out of range: '1e39'");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 4\n3 0 2 3\n", "c.ply",
            "face 0 (line 14) refers to vertex 4 of 4");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0\n3 0 2 3\n", "c.ply",
            "face 0 has no vertex indices");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 -2\n3 0 2 3\n", "c.ply",
            "face 0 (line 14) refers to vertex -2 of 4");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0\f0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "c.ply",
            "control character (0x0c)");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0x1\n3 0 1 2\n3 0 2 3\n",
            "c.ply", "not a number: '0x1'");
    /* the header */
    REFUSED("ply\nformat ascii 1.0\nelement vertex 4\nprope", "c.ply", "stops in line 4, before end_header");
    REFUSED("plx\n", "c.ply", "the first line is not 'ply'");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS SQ_VERTS "end_header\n", "c.ply", "two 'vertex' elements");
    REFUSED(PLY_HEAD("ascii") SQ_FACES SQ_VERTS "end_header\n", "c.ply", "face element comes before the vertex");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS "element tristrips 1\nproperty list int int vertex_indices\nend_header\n",
            "c.ply", "tristrips");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS "element face 1\nproperty list float int vertex_indices\nend_header\n", "c.ply",
            "count of floating-point type");
    REFUSED(PLY_HEAD("ascii") SQ_VERTS "element face 1\nproperty list uchar int flags\nend_header\n", "c.ply",
            "no vertex_indices list");
    REFUSED(PLY_HEAD("ascii") "element vertex 1\nproperty quad x\nend_header\n0\n", "c.ply", "unknown type 'quad'");
    REFUSED(PLY_HEAD("ascii") "property float x\n", "c.ply", "a property before any element");
    /* a header that never ends: refused after 64 KB, not read to the end */
    const size_t big = 4 << 20;
    char *h = malloc(big);
    memcpy(h, "ply\nformat ascii 1.0\n", 21);
    for (size_t i = 21; i < big; i++) h[i] = (i % 64 == 63) ? '\n' : 'c';
    ck_assert_int_eq(load(h, big, "big.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "within its first 65536 bytes"), "%s", sh_last_error());
    free(h);
}
END_TEST

/* little-endian bytes */
static size_t le(unsigned char *p, uint64_t v, int n)
{
    for (int k = 0; k < n; k++) p[k] = (unsigned char)(v >> (8 * k));
    return (size_t)n;
}
static size_t lef(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return le(p, u, 4);
}
/* a binary little-endian PLY: the square's header with the given counts,
 * nv vertices from xyz, faces as (count, indices) with count bytes cnt */
static size_t bin_square(unsigned char *out, const char *counts, int nv, const float *xyz, int nf, const int *cnt,
                         const int *idx)
{
    size_t n = (size_t)sprintf((char *)out, PLY_HEAD("binary_little_endian") "%s" "end_header\n", counts);
    for (int v = 0; v < 3 * nv; v++) n += lef(out + n, xyz[v]);
    for (int f = 0, i = 0; f < nf; f++) {
        n += le(out + n, (uint64_t)cnt[f], 1);
        for (int k = 0; k < cnt[f]; k++) n += le(out + n, (uint64_t)(uint32_t)idx[i++], 4);
    }
    return n;
}

START_TEST(test_guard_ply_binary)
{
    static const float xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const int cnt[2] = {3, 3}, idx[6] = {0, 1, 2, 0, 2, 3}, zero[2] = {0, 0};
    unsigned char buf[1024];
    sh_mesh m;
    const char *counts = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 2\nproperty list uchar int vertex_indices\n";
    size_t n = bin_square(buf, counts, 4, xyz, 2, cnt, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_OK);
    ck_close(mesh_area(&m), 1.0, TOL1, 1, "area");
    sh_mesh_free(&m);
    /* the header says 2 vertices, the body holds 4 and the faces (assimp
     * read faces from vertex bytes and aborted) */
    const char *short2 = "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 2\nproperty list uchar int vertex_indices\n";
    n = bin_square(buf, short2, 4, xyz, 2, cnt, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    /* face lists of count 0 in an otherwise correct file (assimp aborted) */
    n = bin_square(buf, counts, 4, xyz, 2, zero, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "face 0 has no vertex indices"), "%s", sh_last_error());
    /* more bytes than the counts say */
    n = bin_square(buf, counts, 4, xyz, 2, cnt, idx);
    buf[n++] = 0;
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "1 bytes after its last element"), "%s", sh_last_error());
    /* a negative index, an index past the vertices */
    static const int neg[6] = {0, 1, -1, 0, 2, 3}, past[6] = {0, 1, 2, 0, 2, 4};
    n = bin_square(buf, counts, 4, xyz, 2, cnt, neg);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "face 0 refers to vertex -1 of 4"), "%s", sh_last_error());
    n = bin_square(buf, counts, 4, xyz, 2, cnt, past);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "face 1 refers to vertex 4 of 4"), "%s", sh_last_error());
    /* counts no body could hold: refused before reading (2e9 > the limit; 1e6 > the bytes) */
    n = bin_square(buf, "element vertex 1000000\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 2\nproperty list uchar int vertex_indices\n", 4, xyz, 2, cnt, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "element 'vertex' alone (1000000 instances of at least 12 bytes)"), "%s",
                  sh_last_error());
    n = bin_square(buf, "element vertex 2000000000\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 2000000000\nproperty list uchar int vertex_indices\n", 4, xyz, 2, cnt, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    /* NaN and 1e300 (double) coordinates */
    const float nan_xyz[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, NAN};
    n = bin_square(buf, counts, 4, nan_xyz, 2, cnt, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "PLY vertex 3 has a non-finite coordinate"), "%s", sh_last_error());
    /* first body byte 0x0a: x of vertex 0 is the float of bits 0x0000000a.
     * assimp 5.2 skips a 0x0a after "end_header\n" (as if the line ended
     * "\r\n") and read the whole body one byte off: it aborted on this
     * correct file */
    float tiny;
    const uint32_t bits = 10;
    memcpy(&tiny, &bits, 4);
    const float xyz0a[12] = {tiny, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    n = bin_square(buf, counts, 4, xyz0a, 2, cnt, idx);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_OK);
    ck_assert(m.pos[0] == (double)tiny || m.pos[3] == (double)tiny || m.pos[6] == (double)tiny || m.pos[9] == (double)tiny);
    ck_close(mesh_area(&m), 1.0, 1e-6, 1, "area");
    sh_mesh_free(&m);
    /* big-endian: the same square */
    n = (size_t)sprintf((char *)buf, PLY_HEAD("binary_big_endian") "%send_header\n", counts);
    for (int v = 0; v < 12; v++) {
        uint32_t u;
        memcpy(&u, &xyz[v], 4);
        for (int k = 3; k >= 0; k--) buf[n++] = (unsigned char)(u >> (8 * k));
    }
    for (int f = 0; f < 2; f++) {
        buf[n++] = 3;
        for (int k = 0; k < 3; k++) buf[n++] = 0, buf[n++] = 0, buf[n++] = 0, buf[n++] = (unsigned char)idx[3 * f + k];
    }
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_OK);
    ck_close(mesh_area(&m), 1.0, TOL1, 1, "big-endian area");
    sh_mesh_free(&m);
    /* a face texcoord list longer than two per index (assimp read past the
     * indices), and a material with an opacity but no specular power
     * (assimp read the opacity from an absent slot: dropped from the copy) */
    const char *tc = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n";
    n = bin_square(buf, tc, 4, xyz, 1, cnt, idx); /* vertices, face 0's indices */
    n += le(buf + n, 7, 1);                        /* face 0's texcoord list: 7 values */
    for (int k = 0; k < 7; k++) n += lef(buf + n, 0.5f);
    n += le(buf + n, 3, 1);                        /* face 1: 0 2 3, no texcoords */
    for (int k = 0; k < 3; k++) n += le(buf + n, (uint64_t)idx[3 + k], 4);
    n += le(buf + n, 0, 1);
    ck_assert_int_eq(load(buf, n, "b.ply", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "face 0 has 7 texture coordinates for 3 vertices"), "%s", sh_last_error());
    const char *mat = PLY_HEAD("ascii") SQ_VERTS SQ_FACES "element material 1\nproperty float opacity\nend_header\n"
                      SQ_BODY "0.5\n";
    ck_assert_int_eq(loads(mat, "mat.ply", 0, &m), SH_OK);
    ck_assert_int_eq(m.ntri, 2);
    sh_mesh_free(&m);
}
END_TEST

START_TEST(test_guard_obj)
{
    sh_mesh m;
    /* relative indices, CRLF, v/t/n corners, a cstype section skipped */
    const char *ok = "# square\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nvt 0 0\nvn 0 0 1\n"
                     "cstype bezier\nv 9 9 9\nend\nf 1/1/1 2/1/1 3/1/1\nf -4/-1/-1 -2/1/1 -1/1/1\n";
    ck_assert_int_eq(loads(ok, "sq.obj", 0, &m), SH_OK);
    ck_assert_int_eq(m.ntri, 2);
    ck_close(mesh_area(&m), 1.0, TOL1, 1, "area");
    ck_assert(m.normal && m.normal[2] == 1);
    sh_mesh_free(&m);
    /* assimp: with normals but no texture coordinates, v/x's x is a normal */
    ck_assert_int_eq(loads("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1/1 2/1 3/1\n", "n.obj", 0, &m), SH_OK);
    ck_assert(m.normal && m.normal[2] == 1);
    sh_mesh_free(&m);
    /* homogeneous w */
    ck_assert_int_eq(loads("v 0 0 0 2\nv 2 0 0 2\nv 0 2 0 2\nf 1 2 3\n", "w.obj", 0, &m), SH_OK);
    ck_close(mesh_area(&m), 0.5, TOL1, 1, "w divides");
    sh_mesh_free(&m);
    /* non-finite or out of range wherever it is, the vertex named */
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 nan\nf 1 2 3\nf 2 4 3\n", "a.obj",
            "OBJ vertex 4 (line 4) has a non-finite coordinate 'nan'");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nv -inf 0 0\nf 1 2 3\n", "a.obj", "vertex 4 (line 4) has a non-finite");
    REFUSED("v 1e308 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "a.obj", "coordinate out of range: '1e308' (|x| <= 1e+38)");
    REFUSED("v 1 0 0 1e-39\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "a.obj", "out of range: 1 / 1e-39");
    REFUSED("v 1 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "a.obj", "w = 0");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 nan 1\nf 1//1 2//1 3//1\n", "a.obj", "OBJ normal 1 (line 4)");
    ck_assert_int_eq(loads("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 nan 1\nf 1//1 2//1 3//1\n", "a.obj",
                           SH_MESH_COMPUTE_NORMALS, &m), SH_OK);
    sh_mesh_free(&m);
    REFUSED("v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "a.obj", "vertex 1 (line 1) has 2 numbers");
    REFUSED("v .5 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "a.obj", "not a number: '.5'");
    /* corners */
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "a.obj", "line 4 refers to vertex 4 of 3");
    REFUSED("v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", "a.obj", "refers to vertex -3, but only 2 come before it");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 +3\n", "a.obj", "'+3' is not a corner");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 03\n", "a.obj", "'03' is not a corner");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # c\n", "a.obj", "'#' is not a corner");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "a.obj", "a face of 2 vertices");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3//1\n", "a.obj", "normals at some corners only");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n", "a.obj",
            "faces on lines 6 and 7");
    REFUSED("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", "a.obj", "texture coordinate 1, but none comes before it");
    REFUSED("v 0 0 0\nv 1 0 0 \\\nv 0 1 0\nf 1 2 3\n", "a.obj", "line 2 ends in a backslash");
    REFUSED("v 0 0 0\nv 1 0\r0\nv 0 1 0\nf 1 2 3\n", "a.obj", "line 2 has a control character (0x0d)");
    /* one face of 20000 corners: assimp would triangulate it for ~5 s */
    const int K = 20000;
    char *poly = malloc(64 * (size_t)K), *p = poly;
    for (int i = 0; i < K; i++)
        p += sprintf(p, "v %.6f %.6f 0\n", cos(2 * M_PI * i / K), sin(2 * M_PI * i / K));
    p += sprintf(p, "f");
    for (int i = 1; i <= K; i++) p += sprintf(p, " %d", i);
    *p++ = '\n';
    const double t0 = now_s();
    ck_assert_int_eq(load(poly, (size_t)(p - poly), "poly.obj", 0, &m), SH_EFORMAT);
    ck_assert(now_s() - t0 < 1);
    ck_assert_msg(strstr(sh_last_error(), "too long to triangulate"), "%s", sh_last_error());
    free(poly);
    char nul[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n#\0x\n";
    ck_assert_int_eq(load(nul, sizeof nul - 1, "a.obj", 0, &m), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "line 5 has a control character (0x00)"), "%s", sh_last_error());
}
END_TEST

START_TEST(test_guard_format_choice)
{
    sh_mesh_guard g;
    const char *ply = PLY_HEAD("ascii") SQ_VERTS SQ_FACES "end_header\n" SQ_BODY;
    /* no extension assimp knows: the content decides, and the importer's
     * name then forces that reader */
    ck_assert_int_eq(sh__mesh_guard((const unsigned char *)ply, strlen(ply), "dir/scan.dat", 0, &g), SH_OK);
    ck_assert_int_eq(g.format, SH_MESH_FMT_PLY);
    ck_assert_str_eq(g.name, "dir/scan.dat.ply");
    ck_assert_ptr_nonnull(g.canon);
    sh__mesh_guard_free(&g);
    const char *obj = "# x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    ck_assert_int_eq(sh__mesh_guard((const unsigned char *)obj, strlen(obj), "noext", 0, &g), SH_OK);
    ck_assert_int_eq(g.format, SH_MESH_FMT_OBJ);
    ck_assert_str_eq(g.name, "noext.obj");
    ck_assert_int_eq(g.max_triangles, 1);
    sh__mesh_guard_free(&g);
    /* the extension decides over the content; upper case too */
    ck_assert_int_eq(sh__mesh_guard((const unsigned char *)obj, strlen(obj), "X.PLY", 0, &g), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "first line is not 'ply'"), "%s", sh_last_error());
    ck_assert_int_eq(sh__mesh_guard((const unsigned char *)ply, strlen(ply), "x.stl", 0, &g), SH_OK);
    ck_assert_int_eq(g.format, SH_MESH_FMT_OTHER);
    ck_assert_str_eq(g.name, "x.stl");
    sh__mesh_guard_free(&g);
    ck_assert_int_eq(sh__mesh_guard((const unsigned char *)"", 0, "x.obj", 0, &g), SH_EFORMAT);
}
END_TEST

START_TEST(test_guard_numbers)
{
    static const struct {
        const char *s;
        int code;
        double v;
    } c[] = {{"0", 0, 0},          {"-1.5", 0, -1.5},     {"+.5", 0, 0.5},      {"5.", 0, 5},
             {"1.e3", 0, 1e3},     {"1e38", 0, 1e38},     {"2e38", SH_NUM_RANGE, 0}, {"1e39", SH_NUM_RANGE, 0},
             {"0e50", SH_NUM_RANGE, 0}, {"1e-400", 0, 0},  {"nan", SH_NUM_NONFINITE, 0}, {"-INF", SH_NUM_NONFINITE, 0},
             {"Infinity", SH_NUM_NONFINITE, 0}, {"", SH_NUM_SYNTAX, 0}, {".", SH_NUM_SYNTAX, 0}, {"1e", SH_NUM_SYNTAX, 0},
             {"0x10", SH_NUM_SYNTAX, 0}, {"1,5", SH_NUM_SYNTAX, 0}, {"--1", SH_NUM_SYNTAX, 0}, {"nanx", SH_NUM_SYNTAX, 0}};
    for (size_t k = 0; k < sizeof c / sizeof *c; k++) {
        double v = -7;
        const int code = sh__mesh_number(c[k].s, strlen(c[k].s), 38, &v);
        ck_assert_msg(code == c[k].code, "'%s': code %d, expected %d", c[k].s, code, c[k].code);
        if (code == 0) ck_assert_msg(v == c[k].v, "'%s': %g", c[k].s, v);
    }
    /* an exponent of 39..308 is fine where assimp reads a double */
    double v;
    ck_assert_int_eq(sh__mesh_number("0.001e40", 8, 308, &v), 0);
    ck_assert_int_eq(sh__mesh_number("0.001e40", 8, 38, &v), SH_NUM_RANGE);
}
END_TEST

START_TEST(test_mesh_check_range)
{
    /* in memory: the same one rule for every vertex */
    double pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    int tri[6] = {0, 1, 2, 1, 3, 2};
    for (int c = 0; c < 2; c++) {
        sh_mesh m = {4, 2, malloc(sizeof pos), NULL, malloc(sizeof tri)};
        memcpy(m.pos, pos, sizeof pos);
        memcpy(m.tri, tri, sizeof tri);
        m.pos[11] = c ? 1e308 : NAN;
        ck_assert_int_eq(sh_mesh_check(&m, 0, NULL), SH_EFORMAT);
        ck_assert_str_eq(sh_last_error(), c ? "mesh: vertex 3 has a coordinate out of range: 1e+308 (|x| <= 1e+38)"
                                            : "mesh: vertex 3 has a non-finite coordinate");
        sh_mesh_free(&m);
    }
}
END_TEST

/* ------------------------------------------------------------- models */

/* Triangles read from the model's text here (sscanf: independent of the
 * guard and of assimp): count, area, coordinate sum over corners, with the
 * degenerate ones sh_mesh_check drops left out (area <= 1e-14 diag²). */
typedef struct {
    int ntri;
    double area, sum;
} tri_stats;

static void stats_add(tri_stats *s, const float *a, const float *b, const float *c, double diag2)
{
    const double u[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
    const double v[3] = {(double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2]};
    const double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double area = 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(area > 1e-14 * diag2)) return;
    s->ntri++;
    s->area += area;
    for (int k = 0; k < 3; k++) s->sum += (double)a[k] + b[k] + c[k];
}

static double diag2_of(const float *p, int n)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], p[3 * i + k]), hi[k] = fmax(hi[k], p[3 * i + k]);
    for (int k = 0; k < 3; k++) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return d;
}

/* an ASCII PLY of x y z first in each vertex line, triangles "3 a b c" */
static int ply_stats(const char *path, tri_stats *s)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[1024];
    int nv = 0, nf = 0;
    while (fgets(line, sizeof line, f) && strncmp(line, "end_header", 10)) {
        sscanf(line, "element vertex %d", &nv);
        sscanf(line, "element face %d", &nf);
    }
    float *p = malloc(sizeof(float) * 3 * (size_t)nv);
    for (int i = 0; i < nv; i++) ck_assert(fgets(line, sizeof line, f) && sscanf(line, "%f %f %f", p + 3 * i, p + 3 * i + 1, p + 3 * i + 2) == 3);
    const double d2 = diag2_of(p, nv);
    memset(s, 0, sizeof *s);
    for (int i = 0; i < nf; i++) {
        int k, a, b, c;
        ck_assert(fgets(line, sizeof line, f) && sscanf(line, "%d %d %d %d", &k, &a, &b, &c) == 4 && k == 3);
        stats_add(s, p + 3 * a, p + 3 * b, p + 3 * c, d2);
    }
    free(p);
    fclose(f);
    return 0;
}

/* an OBJ of "v x y z" and triangles "f a[/..] b[/..] c[/..]" */
static int obj_stats(const char *path, tri_stats *s)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char line[1024];
    float *p = NULL;
    int nv = 0, cap = 0, nf = 0, fcap = 0, *fi = NULL;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            if (nv == cap) p = realloc(p, sizeof(float) * 3 * (size_t)(cap = cap ? 2 * cap : 1024));
            ck_assert(sscanf(line + 2, "%f %f %f", p + 3 * nv, p + 3 * nv + 1, p + 3 * nv + 2) == 3);
            nv++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            if (nf == fcap) fi = realloc(fi, sizeof(int) * 3 * (size_t)(fcap = fcap ? 2 * fcap : 1024));
            ck_assert(sscanf(line + 2, "%d%*s %d%*s %d", fi + 3 * nf, fi + 3 * nf + 1, fi + 3 * nf + 2) == 3);
            nf++;
        }
    }
    fclose(f);
    /* the bounding box of the vertices the faces use (the importer keeps no other) */
    float *used = malloc(sizeof(float) * 9 * (size_t)nf);
    for (int i = 0; i < 3 * nf; i++) memcpy(used + 3 * i, p + 3 * (fi[i] - 1), 3 * sizeof(float));
    const double d2 = diag2_of(used, 3 * nf);
    memset(s, 0, sizeof *s);
    for (int i = 0; i < nf; i++) stats_add(s, used + 9 * i, used + 9 * i + 3, used + 9 * i + 6, d2);
    free(used);
    free(p);
    free(fi);
    return 0;
}

START_TEST(test_models_independent)
{
    static const char *const models[] = {"data/models/Wuson.ply", "data/models/WusonOBJ.obj", "data/models/spider.obj"};
    for (int k = 0; k < 3; k++) {
        tri_stats s;
        const int is_ply = strstr(models[k], ".ply") != NULL;
        if ((is_ply ? ply_stats : obj_stats)(models[k], &s)) {
            fprintf(stderr, "test_models_independent: SKIPPED %s (run `make models`)\n", models[k]);
            continue;
        }
        sh_mesh m;
        sh_mesh_report rep;
        ck_assert_int_eq(sh_mesh_load(models[k], SH_MESH_ALLOW_NONMANIFOLD, &m, &rep), SH_OK);
        ck_assert_msg(m.ntri == s.ntri, "%s: %d triangles, the text has %d", models[k], m.ntri, s.ntri);
        double sum = 0;
        for (int t = 0; t < 3 * m.ntri; t++)
            for (int c = 0; c < 3; c++) sum += m.pos[3 * m.tri[t] + c];
        /* (the text read by strtof here, by assimp's fast_atof there: an ulp apart at times) */
        ck_close(mesh_area(&m), s.area, 1e-6, 1e-9, "%s: area", models[k]);
        ck_close(sum, s.sum, 1e-6, 1, "%s: sum of corner coordinates", models[k]);
        sh_mesh_free(&m);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("mesh_guard");
    TCase *t = tcase_create("mesh_guard");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, test_sandbox_result);
    tcase_add_test(t, test_sandbox_abort);
    tcase_add_test(t, test_sandbox_wall_limit);
    tcase_add_test(t, test_sandbox_cpu_limit);
    tcase_add_test(t, test_sandbox_memory_limit);
    tcase_add_test(t, test_frame_lies);
    tcase_add_test(t, test_frame_roundtrip);
    tcase_add_test(t, test_guard_ply_ascii);
    tcase_add_test(t, test_guard_ply_binary);
    tcase_add_test(t, test_guard_obj);
    tcase_add_test(t, test_guard_format_choice);
    tcase_add_test(t, test_guard_numbers);
    tcase_add_test(t, test_mesh_check_range);
    tcase_add_test(t, test_models_independent);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
