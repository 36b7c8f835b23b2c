/* mesh.c — triangle meshes: loading (the guard, then assimp in a sandbox),
 * validation, normals.
 *
 * sh_mesh_load reads the file's bytes once (sh_input_read_all: a regular
 * file, size checked first), and from then on works on those bytes only:
 * the guard checks them (mesh_guard*.c) and the importer, run in a child
 * process with limits (mesh_sandbox.c, mesh_import.c), reads them from
 * memory, so that what was checked is what is imported.  Only the mesh's
 * triangles come back (no assimp type leaves mesh_import.c); they are then
 * turned (SH_MESH_Y_UP) and validated here (sh_mesh_check).
 *
 * Cost of the guard and the sandbox (the parse, the canonical copy, fork,
 * the frame through the pipe), measured as one sh_mesh_load in a fresh
 * process, before and after, 11 interleaved runs each, medians, on the
 * shared 2-core test machine (busy: absolute times about twice an idle
 * machine's), wall / CPU of the process and its child:
 *     Wuson.ply (915 kB ASCII)     183 -> 228 ms    80 -> 100 ms
 *     WusonOBJ.obj (258 kB)        222 -> 234 ms   100 -> 120 ms
 *     spider.obj (106 kB)          206 -> 223 ms   100 -> 110 ms
 *     a 48-byte OBJ square         138 -> 156 ms    70 ->  80 ms
 *     a 287-byte binary PLY         22 ->  36 ms    10 ->  20 ms
 *     11 MB ASCII PLY grid        1840 -> 2490 ms  840 -> 1120 ms
 *     11 MB OBJ grid              2150 -> 2829 ms 1280 -> 1550 ms
 * i.e. some 10-45 ms a load, and a third more for 11 MB files (the guard
 * reads ASCII PLY at ~60 MB/s: 183 ms of the 650).  The procedural scenes
 * (sh_mesh_procedural) load no file and pay nothing. */
#include "scene/mesh_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sh_mesh_free(sh_mesh *m)
{
    if (!m) return;
    free(m->pos);
    free(m->normal);
    free(m->tri);
    memset(m, 0, sizeof *m);
}

int sh_mesh_copy(const sh_mesh *src, sh_mesh *dst)
{
    memset(dst, 0, sizeof *dst);
    if (!src || src->nvert < 0 || src->ntri < 0) return sh_error(SH_EINVAL, "sh_mesh_copy: bad mesh");
    const size_t nv = (size_t)src->nvert, nt = (size_t)src->ntri;
    dst->pos = malloc(sizeof(double) * 3 * (nv ? nv : 1));
    dst->normal = src->normal ? malloc(sizeof(double) * 3 * (nv ? nv : 1)) : NULL;
    dst->tri = malloc(sizeof(int) * 3 * (nt ? nt : 1));
    if (!dst->pos || !dst->tri || (src->normal && !dst->normal)) {
        sh_mesh_free(dst);
        return sh_error(SH_ENOMEM, "out of memory copying a mesh of %d vertices", src->nvert);
    }
    memcpy(dst->pos, src->pos, sizeof(double) * 3 * nv);
    if (src->normal) memcpy(dst->normal, src->normal, sizeof(double) * 3 * nv);
    memcpy(dst->tri, src->tri, sizeof(int) * 3 * nt);
    dst->nvert = src->nvert;
    dst->ntri = src->ntri;
    return SH_OK;
}

/* ------------------------------------------------------------- welding */

static const double *g_pos; /* qsort has no context argument */
static int cmp_pos(const void *a, const void *b)
{
    const double *p = g_pos + 3 * *(const int *)a, *q = g_pos + 3 * *(const int *)b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return *(const int *)a - *(const int *)b;
}

/* weld[v] = the smallest index of a vertex at exactly v's position.
 * Not thread-safe (qsort through a static); meshes are loaded serially. */
static int weld_positions(const sh_mesh *m, int *weld)
{
    int *ord = malloc(sizeof(int) * (size_t)(m->nvert ? m->nvert : 1));
    if (!ord) return sh_error(SH_ENOMEM, "out of memory welding %d vertices", m->nvert);
    for (int v = 0; v < m->nvert; v++) ord[v] = v;
    g_pos = m->pos;
    qsort(ord, (size_t)m->nvert, sizeof(int), cmp_pos);
    for (int k = 0; k < m->nvert;) {
        int j = k;
        while (j < m->nvert && !memcmp(m->pos + 3 * ord[j], m->pos + 3 * ord[k], 3 * sizeof(double))) j++;
        for (int q = k; q < j; q++) weld[ord[q]] = ord[k]; /* ord sorted by index within equal positions */
        k = j;
    }
    free(ord);
    return SH_OK;
}

static int cmp_edge(const void *a, const void *b)
{
    const long long x = *(const long long *)a, y = *(const long long *)b;
    return x < y ? -1 : x > y;
}

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void tri_normal(const sh_mesh *m, int t, double c[3])
{
    const double *a = m->pos + 3 * m->tri[3 * t], *b = m->pos + 3 * m->tri[3 * t + 1],
                 *d = m->pos + 3 * m->tri[3 * t + 2];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    cross(e1, e2, c); /* |c| = twice the area */
}

/* The arguments, the size limits, and every coordinate, normal and index:
 * Embree drops primitives with NaN/Inf corners silently, and holds
 * coordinates in single precision: both are refused here. */
static int check_elements(const sh_mesh *m, int flags)
{
    if (!m || m->nvert < 0 || m->ntri < 0 || (m->nvert > 0 && !m->pos) || (m->ntri > 0 && !m->tri))
        return sh_error(SH_EINVAL, "mesh: bad arguments");
    if (m->nvert > SH_MESH_MAX_ELEMS || m->ntri > SH_MESH_MAX_ELEMS)
        return sh_error(SH_EFORMAT, "mesh: %d vertices and %d triangles exceed the limit %d", m->nvert,
                        m->ntri, SH_MESH_MAX_ELEMS);
    if (m->ntri == 0 || m->nvert == 0) return sh_error(SH_EFORMAT, "mesh: no triangles");
    for (int v = 0; v < m->nvert; v++)
        for (int k = 0; k < 3; k++) {
            if (!isfinite(m->pos[3 * v + k]))
                return sh_error(SH_EFORMAT, "mesh: vertex %d has a non-finite coordinate", v);
            if (fabs(m->pos[3 * v + k]) > SH_MESH_MAX_COORD)
                return sh_error(SH_EFORMAT, "mesh: vertex %d has a coordinate out of range: %g (|x| <= %g)", v,
                                m->pos[3 * v + k], SH_MESH_MAX_COORD);
            if (m->normal && !(flags & SH_MESH_COMPUTE_NORMALS) && !isfinite(m->normal[3 * v + k]))
                return sh_error(SH_EFORMAT, "mesh: vertex %d has a non-finite normal", v);
        }
    for (long long i = 0; i < 3LL * m->ntri; i++)
        if (m->tri[i] < 0 || m->tri[i] >= m->nvert)
            return sh_error(SH_EFORMAT, "mesh: triangle %lld refers to vertex %d of %d", i / 3, m->tri[i],
                            m->nvert);
    return SH_OK;
}

static void bounding_box(const sh_mesh *m, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int v = 0; v < m->nvert; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->pos[3 * v + k]);
            hi[k] = fmax(hi[k], m->pos[3 * v + k]);
        }
}

/* degenerate triangles: a repeated corner or area ≤ 1e-14·diag², removed */
static int drop_degenerate(sh_mesh *m, double diag2, sh_mesh_report *rep)
{
    int nt = 0;
    for (int t = 0; t < m->ntri; t++) {
        const int *c = m->tri + 3 * t;
        double nrm[3];
        tri_normal(m, t, nrm);
        const double area = 0.5 * sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2] || !(area > 1e-14 * diag2)) {
            rep->degenerate_removed++;
            continue;
        }
        memmove(m->tri + 3 * nt, c, 3 * sizeof(int));
        nt++;
    }
    m->ntri = nt;
    if (nt == 0) return sh_error(SH_EFORMAT, "mesh: every triangle is degenerate (%d removed)", rep->degenerate_removed);
    return SH_OK;
}

/* unused vertices, removed (the triangles renumbered) */
static int drop_unused(sh_mesh *m, sh_mesh_report *rep)
{
    const int nt = m->ntri;
    int *map = malloc(sizeof(int) * (size_t)m->nvert);
    if (!map) return sh_error(SH_ENOMEM, "out of memory");
    for (int v = 0; v < m->nvert; v++) map[v] = -1;
    for (int i = 0; i < 3 * nt; i++) map[m->tri[i]] = 0;
    int nv = 0;
    for (int v = 0; v < m->nvert; v++) {
        if (map[v] < 0) { rep->unused_removed++; continue; }
        map[v] = nv;
        memmove(m->pos + 3 * nv, m->pos + 3 * v, 3 * sizeof(double));
        if (m->normal) memmove(m->normal + 3 * nv, m->normal + 3 * v, 3 * sizeof(double));
        nv++;
    }
    for (int i = 0; i < 3 * nt; i++) m->tri[i] = map[m->tri[i]];
    m->nvert = nv;
    free(map);
    return SH_OK;
}

/* normals: area-weighted face normals summed over welded positions */
static int compute_normals(sh_mesh *m, const int *weld, sh_mesh_report *rep)
{
    const int nv = m->nvert, nt = m->ntri;
    double *nrm = calloc(3 * (size_t)nv, sizeof(double));
    if (!nrm) return sh_error(SH_ENOMEM, "out of memory");
    for (int t = 0; t < nt; t++) {
        double c[3];
        tri_normal(m, t, c);
        for (int j = 0; j < 3; j++) {
            const int w = weld[m->tri[3 * t + j]];
            for (int k = 0; k < 3; k++) nrm[3 * w + k] += c[k];
        }
    }
    for (int v = 0; v < nv; v++)
        if (weld[v] != v) memcpy(nrm + 3 * v, nrm + 3 * weld[v], 3 * sizeof(double));
    free(m->normal);
    m->normal = nrm;
    rep->normals_computed = 1;
    return SH_OK;
}

/* every normal to unit length; a zero (or non-finite) one is refused */
static int unit_normals(sh_mesh *m, const sh_mesh_report *rep)
{
    for (int v = 0; v < m->nvert; v++) {
        double *n = m->normal + 3 * v;
        const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0) || !isfinite(len))
            return sh_error(SH_EFORMAT, "mesh: vertex %d has a zero normal%s", v,
                            rep->normals_computed ? " (its triangles cancel)" : "");
        for (int k = 0; k < 3; k++) n[k] /= len;
    }
    return SH_OK;
}

/* edges of the welded mesh, key (min, max) of welded indices, sorted:
 * those of one triangle are boundary edges, those of more than two
 * non-manifold (the first one's vertices kept).  edges: 3·ntri. */
static void count_edges(const sh_mesh *m, const int *weld, long long *edges, sh_mesh_report *rep)
{
    const int nv = m->nvert, nt = m->ntri;
    for (int t = 0; t < nt; t++)
        for (int j = 0; j < 3; j++) {
            long long a = weld[m->tri[3 * t + j]], b = weld[m->tri[3 * t + (j + 1) % 3]];
            if (a > b) { const long long x = a; a = b; b = x; }
            edges[3 * t + j] = a * (long long)nv + b;
        }
    qsort(edges, 3 * (size_t)nt, sizeof(long long), cmp_edge);
    for (size_t k = 0; k < 3 * (size_t)nt;) {
        size_t j = k;
        while (j < 3 * (size_t)nt && edges[j] == edges[k]) j++;
        if (j - k == 1) rep->boundary_edges++;
        if (j - k > 2) {
            if (rep->nonmanifold_edges == 0) {
                rep->nonmanifold_a = (int)(edges[k] / nv);
                rep->nonmanifold_b = (int)(edges[k] % nv);
            }
            rep->nonmanifold_edges++;
        }
        k = j;
    }
}

/* What needs the welded positions: the normals (computed when missing or
 * asked for, then made unit) and the edge counts. */
static int check_welded(sh_mesh *m, int flags, sh_mesh_report *rep)
{
    int *weld = malloc(sizeof(int) * (size_t)m->nvert);
    long long *edges = malloc(sizeof(long long) * 3 * (size_t)m->ntri);
    if (!weld || !edges) { free(weld); free(edges); return sh_error(SH_ENOMEM, "out of memory"); }
    int st = weld_positions(m, weld);
    if (!st && (!m->normal || (flags & SH_MESH_COMPUTE_NORMALS))) st = compute_normals(m, weld, rep);
    if (!st) st = unit_normals(m, rep);
    if (!st) count_edges(m, weld, edges, rep);
    free(weld);
    free(edges);
    return st;
}

int sh_mesh_check(sh_mesh *m, int flags, sh_mesh_report *rep)
{
    sh_mesh_report r0;
    if (!rep) rep = &r0;
    const int keep_sub = rep->submeshes, keep_skip = rep->skipped_primitives;
    memset(rep, 0, sizeof *rep);
    rep->submeshes = keep_sub;
    rep->skipped_primitives = keep_skip;
    int st = check_elements(m, flags);
    if (st) return st;
    double lo[3], hi[3];
    bounding_box(m, lo, hi);
    const double diag2 = (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (hi[2] - lo[2]) * (hi[2] - lo[2]);
    if ((st = drop_degenerate(m, diag2, rep))) return st;
    if ((st = drop_unused(m, rep))) return st;
    bounding_box(m, lo, hi);
    if ((st = check_welded(m, flags, rep))) return st;
    memcpy(rep->bbox_min, lo, sizeof lo);
    memcpy(rep->bbox_max, hi, sizeof hi);
    if (rep->nonmanifold_edges > 0 && !(flags & SH_MESH_ALLOW_NONMANIFOLD))
        return sh_error(SH_EFORMAT,
                        "mesh: %d non-manifold edge%s (shared by more than two triangles), the first "
                        "between vertices %d and %d",
                        rep->nonmanifold_edges, rep->nonmanifold_edges == 1 ? "" : "s", rep->nonmanifold_a,
                        rep->nonmanifold_b);
    return SH_OK;
}

/* ------------------------------------------------------------- loading */

typedef struct {
    const sh_mesh_guard *g;
    int side_files, flags;
} import_job;

/* In the child: assimp on the guard's bytes. */
static int run_import(void *arg, sh_mesh *m, sh_mesh_report *rep)
{
    const import_job *j = arg;
    return sh__mesh_import(j->g->bytes, j->g->size, j->g->name, j->side_files, j->flags, m, rep);
}

/* Guard, sandboxed import, turn, check: bytes named `name` (its extension
 * picks the format), shown as `shown` in messages; side_files as in
 * sh__mesh_import. */
static int load_bytes(const unsigned char *data, size_t n, const char *name, const char *shown, int side_files,
                      int flags, sh_mesh *out, sh_mesh_report *rep)
{
    sh_mesh_guard g;
    int st = sh__mesh_guard(data, n, name, flags, &g);
    if (st) {
        char why[600];
        snprintf(why, sizeof why, "%s", sh_last_error());
        return sh_error(st, "cannot read mesh '%s': %s", shown, why);
    }
    import_job j = {&g, side_files, flags};
    sh_mesh_job job;
    memset(&job, 0, sizeof job);
    job.run = run_import;
    job.arg = &j;
    job.cpu_seconds = g.cpu_seconds;
    job.wall_seconds = 2 * g.cpu_seconds + 5; /* the machine may be shared */
    job.mem_bytes = g.mem_budget;
    job.max_vertices = g.max_vertices;
    job.max_triangles = g.max_triangles;
    st = sh__mesh_sandbox(&job, out, rep);
    sh__mesh_guard_free(&g);
    if (st) {
        char why[600];
        snprintf(why, sizeof why, "%s", sh_last_error());
        return sh_error(st, "cannot read mesh '%s': %s", shown, why);
    }
    if (flags & SH_MESH_Y_UP)
        for (int v = 0; v < out->nvert; v++) {
            /* Rx(+90°): (x, y, z) → (x, −z, y), positions and normals */
            double *p = out->pos + 3 * (size_t)v, y = p[1];
            p[1] = -p[2];
            p[2] = y;
            if (out->normal) {
                double *q = out->normal + 3 * (size_t)v, ny = q[1];
                q[1] = -q[2];
                q[2] = ny;
            }
        }
    st = sh_mesh_check(out, flags, rep);
    if (st) {
        char why[600];
        snprintf(why, sizeof why, "%s", sh_last_error());
        sh_mesh_free(out);
        /* name the file: "mesh 'F': ..." */
        return sh_error(st, "mesh '%s'%s", shown, why + (strncmp(why, "mesh", 4) ? 0 : 4));
    }
    return SH_OK;
}

int sh_mesh_load(const char *path, int flags, sh_mesh *out, sh_mesh_report *rep)
{
    sh_mesh_report r0;
    if (!rep) rep = &r0;
    memset(rep, 0, sizeof *rep);
    if (!out || !path) return sh_error(SH_EINVAL, "sh_mesh_load: no output or no path");
    memset(out, 0, sizeof *out);
    /* the input policy (input_file.c): our messages, no blocking on a FIFO */
    char *buf;
    size_t n;
    int st = sh_input_read_all("mesh", path, SH_MESH_MAX_BYTES, &buf, &n);
    if (st) return st;
    st = load_bytes((const unsigned char *)buf, n, path, path, 1, flags, out, rep);
    free(buf);
    return st;
}

int sh_mesh_load_mem(const void *data, size_t size, const char *name, int flags, sh_mesh *out, sh_mesh_report *rep)
{
    sh_mesh_report r0;
    if (!rep) rep = &r0;
    memset(rep, 0, sizeof *rep);
    if (!out || !name || (!data && size)) return sh_error(SH_EINVAL, "sh_mesh_load_mem: no output, name or data");
    memset(out, 0, sizeof *out);
    if ((long long)size > SH_MESH_MAX_BYTES)
        return sh_error(SH_EFORMAT, "mesh '%s' has %zu bytes, more than the %lld a mesh may have", name, size,
                        SH_MESH_MAX_BYTES);
    return load_bytes(data, size, name, name, 0, flags, out, rep);
}
