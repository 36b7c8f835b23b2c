/* mesh_guard_obj.c — our own reader of a Wavefront OBJ file, run before
 * assimp sees it (sh__mesh_guard_obj, mesh_internal.h).
 *
 * Format (Wavefront, "Appendix B1: Object files (.obj)", Advanced
 * Visualizer manual; Paul Bourke's copy at paulbourke.net/dataformats/obj):
 * lines of statements, among them
 *     v x y z [w]        a position (w divides x, y, z), vertices numbered
 *                        from 1 in file order; assimp also reads v x y z r g b
 *     vt u v [w], vn i j k   texture coordinates, normals (own numbering)
 *     f v[/vt][/vn] ...  a face of 3 or more corners; l: a line, p: points
 *     # ...              a comment
 * An index n > 0 is the n-th element of its kind in the file, n < 0 counts
 * back from the last one defined before the statement.
 *
 * The lines are classified exactly as assimp 5.2's reader does
 * (code/AssetLib/Obj/ObjFileParser.cpp): by their first character, with no
 * leading blanks skipped ('v' then blank/'t'/'n'; 'f', 'l', 'p' whatever the
 * rest of the first word; a cstype section skipped up to "end"), and every
 * other line ignored.  Where assimp's reading is fragile the file is refused
 * rather than read another way:
 *  - a NUL, a form feed, or a carriage return not before a line feed (assimp
 *    ends a line at each); a line ending in a backslash (assimp joins the
 *    next line, copying its first character unexamined);
 *  - a position not of 3, 4 or 6 numbers (assimp silently skips it, and
 *    every later index then names another vertex), a normal not of 3, a
 *    texture coordinate not of 2 or 3; a number not as sh__mesh_number reads
 *    it, or starting with '.' (assimp's component count misses it);
 *  - a corner not of the forms v, v/t, v//n, v/t/n with indices of at most
 *    9 digits, no sign but '-', no leading zero (assimp steps through a
 *    corner by the digits of its value: "+3" or "03" would read 3 twice).
 * Checks: positions (x/w, y/w, z/w for four numbers) finite and within
 * SH_MESH_MAX_COORD, and normals too unless SH_MESH_COMPUTE_NORMALS — every
 * statement, used or not; at most SH_MESH_MAX_ELEMS positions and triangles;
 * every index names an element that exists (relative ones: before the
 * statement); a face has 3 to SH_MESH_MAX_FACE_INDICES corners, a line 2;
 * the faces' k² summed over those of k > 4 corners is within
 * SH_MESH_NGON_WORK (triangulation time); a face gives normals for all its
 * corners or none, and (unless
 * SH_MESH_COMPUTE_NORMALS) so do all faces, since assimp gives the corners of
 * a face without them a zero normal.  The importer then reads the file's own
 * bytes. */
#include "scene/mesh_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const unsigned char *d;
    size_t n;
    int flags, line;
    long long nv, nvt, nvn;        /* defined so far */
    long long maxv[3], maxline[3]; /* the largest positive index of each kind, and its line */
    long long corners, tris, ngon; /* ngon: sum of k² over faces of k > 4 corners */
    int with_n, without_n;         /* lines of a face with normals, one without (0: none yet) */
} obj_t;

enum { K_V, K_VT, K_VN };
static const char *const kind_name[] = {"vertex", "texture coordinate", "normal"};

/* a number of a v, vt or vn statement: sh__mesh_number's, and a digit or a
 * sign first (assimp's IsNumeric, by which it counts the components) */
static int obj_number(const char *t, size_t len, double *v)
{
    const int code = sh__mesh_number(t, len, 38, v);
    if (code != SH_NUM_NONFINITE && len && !(isdigit((unsigned char)t[0]) || t[0] == '+' || t[0] == '-'))
        return SH_NUM_SYNTAX;
    return code;
}

/* v, vt, vn: the numbers after the keyword (s[0..len)) */
static int numbers(obj_t *O, int kind, const char *s, size_t len)
{
    const char *tok[8];
    size_t tl[8];
    const int nt = sh__mesh_tokens(s, len, tok, tl, 7);
    const long long num = (kind == K_V ? O->nv : kind == K_VT ? O->nvt : O->nvn) + 1;
    const int check = kind == K_V || (kind == K_VN && !(O->flags & SH_MESH_COMPUTE_NORMALS));
    double x[7];
    for (int k = 0; k < nt && k < 7; k++) {
        const int code = obj_number(tok[k], tl[k], nt == 4 ? &x[k] : NULL); /* values needed only to divide by w */
        if (code == SH_NUM_SYNTAX || (code && check)) {
            char why[160];
            sh__mesh_number_why(code, kind == K_VN ? "component" : kind == K_VT ? "value" : "coordinate", tok[k],
                                tl[k], why, sizeof why);
            return sh_error(SH_EFORMAT, "OBJ %s %lld (line %d) has %s", kind_name[kind], num, O->line, why);
        }
    }
    const int ok = kind == K_V ? (nt == 3 || nt == 4 || nt == 6) : kind == K_VT ? (nt == 2 || nt == 3) : nt == 3;
    if (!ok)
        return sh_error(SH_EFORMAT, "OBJ %s %lld (line %d) has %d numbers (%s are read)", kind_name[kind], num, O->line,
                        nt, kind == K_V ? "3, 4 or 6" : kind == K_VT ? "2 or 3" : "3");
    if (kind == K_V && nt == 4) {
        if (x[3] == 0) return sh_error(SH_EFORMAT, "OBJ vertex %lld (line %d) has w = 0", num, O->line);
        for (int k = 0; k < 3; k++)
            if (!(fabs(x[k] / x[3]) <= SH_MESH_MAX_COORD))
                return sh_error(SH_EFORMAT, "OBJ vertex %lld (line %d) has a coordinate out of range: %g / %g (|x| <= %g)",
                                num, O->line, x[k], x[3], SH_MESH_MAX_COORD);
    }
    if (kind == K_V && ++O->nv > SH_MESH_MAX_ELEMS)
        return sh_error(SH_EFORMAT, "OBJ file has more than the %d vertices a mesh may have", SH_MESH_MAX_ELEMS);
    if (kind == K_VT) O->nvt++;
    if (kind == K_VN) O->nvn++;
    return SH_OK;
}

/* an index of at most 9 digits, '-' or no sign, no leading zero: its end */
static const char *index_at(const char *p, const char *e, long long *v)
{
    int neg = 0;
    if (p < e && *p == '-') neg = 1, p++;
    if (p == e || *p < '1' || *p > '9') return NULL;
    long long x = 0;
    int dig = 0;
    while (p < e && isdigit((unsigned char)*p)) {
        if (++dig > 9) return NULL;
        x = 10 * x + (*p++ - '0');
    }
    *v = neg ? -x : x;
    return p;
}

/* one index of kind k: a relative one resolved now, a positive one checked
 * against the final count at the end */
static int use_index(obj_t *O, int k, long long v)
{
    const long long have = k == K_V ? O->nv : k == K_VT ? O->nvt : O->nvn;
    if (v < 0 && have + v < 0)
        return sh_error(SH_EFORMAT, "OBJ line %d refers to %s %lld, but only %lld come before it", O->line, kind_name[k],
                        v, have);
    if (v > O->maxv[k]) {
        O->maxv[k] = v;
        O->maxline[k] = O->line;
    }
    return SH_OK;
}

/* f, l, p: the corners after the first word */
static int corners(obj_t *O, char type, const char *s, size_t len)
{
    size_t i = 0;
    while (i < len && s[i] != ' ' && s[i] != '\t') i++; /* the keyword, as assimp skips it */
    const char *p = s + i, *e = s + len;
    long long k = 0;
    int with = 0, without = 0;
    for (;;) {
        while (p < e && (*p == ' ' || *p == '\t')) p++;
        if (p == e) break;
        const char *t = p;
        while (p < e && *p != ' ' && *p != '\t') p++;
        const char *q;
        long long v, tv = 0, nv = 0;
        int has_t = 0, has_n = 0;
        if (!(q = index_at(t, p, &v))) goto bad;
        if (q < p && *q == '/') {
            q++;
            if (q < p && *q != '/') {
                if (!(q = index_at(q, p, &tv))) goto bad;
                has_t = 1;
            }
            if (q < p && *q == '/') {
                if (!(q = index_at(q + 1, p, &nv))) goto bad;
                has_n = 1;
            } else if (!has_t) goto bad;
        }
        if (q != p) goto bad;
        /* assimp: without texture coordinates so far but with normals, v/t's t is a normal */
        if (has_t && !has_n && O->nvt == 0 && O->nvn > 0) nv = tv, has_t = 0, has_n = 1;
        if (has_t && O->nvt == 0)
            return sh_error(SH_EFORMAT, "OBJ line %d refers to texture coordinate %lld, but none comes before it",
                            O->line, tv);
        int st = use_index(O, K_V, v);
        if (!st && has_t) st = use_index(O, K_VT, tv);
        if (!st && has_n) st = use_index(O, K_VN, nv);
        if (st) return st;
        if (has_n) with = 1;
        else without = 1;
        if (++k > SH_MESH_MAX_FACE_INDICES)
            return sh_error(SH_EFORMAT, "OBJ line %d has more than the %d corners read", O->line, SH_MESH_MAX_FACE_INDICES);
        continue;
    bad:
        return sh_error(SH_EFORMAT, "OBJ line %d: '%.*s' is not a corner (v, v/t, v//n or v/t/n)", O->line,
                        (int)(p - t > 30 ? 30 : p - t), t);
    }
    if (k == 0) return SH_OK; /* assimp ignores an empty statement */
    if (type == 'l' && k < 2) return sh_error(SH_EFORMAT, "OBJ line %d: a line of 1 vertex", O->line);
    if (type != 'f') return SH_OK;
    if (k < 3) return sh_error(SH_EFORMAT, "OBJ line %d: a face of %lld vertices (3 or more)", O->line, k);
    if (with && without)
        return sh_error(SH_EFORMAT, "OBJ line %d: a face with normals at some corners only", O->line);
    if (with && !O->with_n) O->with_n = O->line;
    if (without && !O->without_n) O->without_n = O->line;
    O->corners += k;
    O->tris += k - 2;
    if (k > 4) O->ngon += k * k;
    if (O->tris > SH_MESH_MAX_ELEMS)
        return sh_error(SH_EFORMAT, "OBJ faces make more than the %d triangles a mesh may have", SH_MESH_MAX_ELEMS);
    if (O->ngon > SH_MESH_NGON_WORK(O->n))
        return sh_error(SH_EFORMAT, "OBJ faces of many corners (up to line %d, %lld corners) would take the importer "
                                    "too long to triangulate: the sum of their corners squared exceeds %lld for a file "
                                    "of %zu bytes", O->line, k, SH_MESH_NGON_WORK(O->n), O->n);
    return SH_OK;
}

/* the first word of s[0..len) is w */
static int first_word(const char *s, size_t len, const char *w)
{
    size_t i = 0;
    while (i < len && s[i] != ' ' && s[i] != '\t') i++;
    return i == strlen(w) && !memcmp(s, w, i);
}

int sh__mesh_guard_obj(const unsigned char *data, size_t n, int flags, sh_mesh_guard *g)
{
    obj_t O;
    memset(&O, 0, sizeof O);
    O.d = data;
    O.n = n;
    O.flags = flags;
    int cstype = 0, st = SH_OK;
    for (size_t pos = 0; pos < n && !st;) {
        O.line++;
        const unsigned char *nl = memchr(data + pos, '\n', n - pos);
        size_t e = nl ? (size_t)(nl - data) : n;
        const size_t next = nl ? e + 1 : n;
        if (e > pos && data[e - 1] == '\r') e--;
        for (size_t i = pos; i < e; i++)
            if (data[i] == '\0' || data[i] == '\r' || data[i] == '\f')
                return sh_error(SH_EFORMAT, "OBJ line %d has a control character (0x%02x) that ends a line", O.line, data[i]);
        if (e > pos && data[e - 1] == '\\')
            return sh_error(SH_EFORMAT, "OBJ line %d ends in a backslash (continuation lines are not read)", O.line);
        const char *s = (const char *)data + pos;
        const size_t len = e - pos;
        pos = next;
        if (len == 0) continue;
        if (cstype) {
            if (s[0] == 'e' && first_word(s, len, "end")) cstype = 0;
            continue;
        }
        switch (s[0]) {
        case 'v':
            if (len < 2) break;
            if (s[1] == ' ' || s[1] == '\t') st = numbers(&O, K_V, s + 1, len - 1);
            else if (s[1] == 't') st = numbers(&O, K_VT, s + 2, len - 2);
            else if (s[1] == 'n') st = numbers(&O, K_VN, s + 2, len - 2);
            break;
        case 'f': case 'l': case 'p': st = corners(&O, s[0], s, len); break;
        case 'c': cstype = first_word(s, len, "cstype"); break;
        default: break;
        }
    }
    if (st) return st;
    const long long have[3] = {O.nv, O.nvt, O.nvn};
    for (int k = 0; k < 3; k++)
        if (O.maxv[k] > have[k])
            return sh_error(SH_EFORMAT, "OBJ line %lld refers to %s %lld of %lld", O.maxline[k], kind_name[k], O.maxv[k],
                            have[k]);
    if (O.with_n && O.without_n && !(flags & SH_MESH_COMPUTE_NORMALS))
        return sh_error(SH_EFORMAT, "OBJ faces on lines %d and %d: one gives normals, the other not (give them for "
                                    "every face or none, or compute them)", O.with_n < O.without_n ? O.with_n : O.without_n,
                        O.with_n < O.without_n ? O.without_n : O.with_n);
    g->max_vertices = O.corners;
    g->max_triangles = O.tris;
    return SH_OK;
}
