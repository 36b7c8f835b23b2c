/* mesh_guard_ply.c — our own reader of a PLY file, run before assimp sees it
 * (sh__mesh_guard_ply, mesh_internal.h).
 *
 * Format (Greg Turk, "The PLY Polygon File Format", 1994): a text header
 *     ply
 *     format ascii | binary_little_endian | binary_big_endian 1.0
 *     comment ... | obj_info ...
 *     element <name> <count>
 *     property <type> <name>
 *     property list <count type> <item type> <name>
 *     end_header
 * with types char/int8 uchar/uint8 short/int16 ushort/uint16 int/int32
 * uint/uint32 float/float32 double/float64 (1 1 2 2 4 4 4 8 bytes), then the
 * body: every instance of every element in header order, its properties in
 * order, a list as its count and then its items; ASCII one instance per line,
 * binary packed records in the declared byte order.
 *
 * Why the importer gets a copy, not the file.  assimp 5.2's reader
 * (code/AssetLib/Ply/PlyParser.cpp, PlyLoader.cpp, IOStreamBuffer.h) reads
 * header lines into a reused buffer, so a comment shorter than an earlier
 * line exposes that line's tail, which is then parsed as a header line; a
 * comment between properties ends the element's property list; after
 * "end_header\n" a binary body whose first byte is 0x0a loses that byte (it
 * is taken for the end of "\r\n": a correct file is then read one byte off
 * and aborted in TriangulateProcess); in ASCII one blank line is skipped, a
 * NUL or form feed ends a line, and a missing value reads as 0; counts are
 * read modulo 2^32; two vertex or face elements overflow the first one's
 * arrays; a face's texcoord list longer than two per index reads past the
 * indices; a material's opacity is read from the specular power's slot.
 * So the importer is given a canonical copy written here from what was
 * parsed and checked: a header with the vertex and face elements only
 * (comments, obj_info and every other element dropped — assimp makes no
 * geometry of them), ending "end_header\r\n" before a binary body (the
 * 0x0a rule then skips the '\n' only), and the body of those two elements:
 * binary, their records byte for byte; ASCII, one line per instance, each
 * value's text unchanged, one space apart.
 *
 * Checks (each refusal is one line; vertices and faces are numbered from 0,
 * as PLY's indices count them, with the file's line in ASCII):
 *  - the header ends within SH_MESH_PLY_MAX_HEADER bytes; its element and
 *    property lines are well formed, with known types (a line of no known
 *    keyword is skipped, as assimp does: Blender 2.4 wrote one); at most one vertex and one face element,
 *    the vertex element first; no tristrips element (assimp keeps only the
 *    last triangle of each strip); the face element has one integer
 *    vertex_indices (or vertex_index) list; list counts are integers;
 *  - each count is at most SH_MESH_MAX_ELEMS and the counts fit the body's
 *    length before anything else is read: binary, count × the smallest
 *    record (fixed properties, and per list its count); ASCII, 2 bytes per
 *    value (a character and a separator);
 *  - the body then walked: every value present and well formed (ASCII
 *    numbers as sh__mesh_number reads them), x, y, z (and nx, ny, nz unless
 *    SH_MESH_COMPUTE_NORMALS) finite and within SH_MESH_MAX_COORD, 1 to
 *    SH_MESH_MAX_FACE_INDICES indices per face, each a vertex that exists, at
 *    most two texture coordinates per index, faces of many corners within
 *    SH_MESH_NGON_WORK, and nothing after the last element but (ASCII)
 *    white space. */
#include "scene/mesh_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum { T_CHAR, T_UCHAR, T_SHORT, T_USHORT, T_INT, T_UINT, T_FLOAT, T_DOUBLE };
static const char *const type_canon[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
static const int type_size[] = {1, 1, 2, 2, 4, 4, 4, 8};
static const struct {
    const char *name;
    int type;
} type_names[] = {{"char", T_CHAR},     {"int8", T_CHAR},     {"uchar", T_UCHAR},   {"uint8", T_UCHAR},
                  {"short", T_SHORT},   {"int16", T_SHORT},   {"ushort", T_USHORT}, {"uint16", T_USHORT},
                  {"int", T_INT},       {"int32", T_INT},     {"uint", T_UINT},     {"uint32", T_UINT},
                  {"float", T_FLOAT},   {"float32", T_FLOAT}, {"double", T_DOUBLE}, {"float64", T_DOUBLE},
                  {"double64", T_DOUBLE}};
#define IS_FLOAT(t) ((t) == T_FLOAT || (t) == T_DOUBLE)
#define IS_SIGNED(t) ((t) == T_CHAR || (t) == T_SHORT || (t) == T_INT)

/* what a property means to the mesh */
enum { R_NONE, R_X, R_Y, R_Z, R_NX, R_NY, R_NZ, R_VIDX, R_TEXC };
enum { K_OTHER, K_VERTEX, K_FACE };
#define PLY_MAX_ELEMENTS 32
#define PLY_MAX_PROPS 64
#define PLY_MAX_NAME 64

typedef struct {
    char name[PLY_MAX_NAME];
    int list, ctype, type, role;
} prop_t;

typedef struct {
    char name[PLY_MAX_NAME];
    long long count;
    int kind, nprop;
    prop_t prop[PLY_MAX_PROPS];
} elem_t;

typedef struct {
    const unsigned char *d;
    size_t n, body;     /* the body starts at d + body */
    int fmt;            /* 0 ascii, 1 little endian, 2 big endian */
    int flags;
    int nelem, vertex, face; /* element indices (-1: none) */
    elem_t *el;
    long long corners, tris; /* face indices, and the triangles they make */
    long long ngon;          /* sum of k² over faces of k > 4 corners */
    unsigned char *out;      /* the canonical copy */
    size_t olen, ocap;
    int line;                /* ASCII: line number of the current position */
} ply_t;

/* ------------------------------------------------------------- helpers */

/* Append k bytes to the canonical copy (olen counts past ocap: checked at the end). */
static void put(ply_t *P, const void *s, size_t k)
{
    if (P->olen + k <= P->ocap) memcpy(P->out + P->olen, s, k);
    P->olen += k; /* an overflow is caught by the caller (olen > ocap) */
}
/* Append a string to the canonical copy. */
static void puts_(ply_t *P, const char *s) { put(P, s, strlen(s)); }

/* The token t[0..len) is the word w. */
static int tok_is(const char *t, size_t len, const char *w) { return len == strlen(w) && !memcmp(t, w, len); }

/* a decimal count of digits only, saturated above 10^17; -1 if not digits */
static long long parse_count(const char *t, size_t len)
{
    if (len == 0) return -1;
    long long v = 0;
    for (size_t i = 0; i < len; i++) {
        if (!isdigit((unsigned char)t[i])) return -1;
        if (v < 100000000000000000LL) v = 10 * v + (t[i] - '0');
    }
    return v;
}

/* An ASCII integer of the given type as assimp reads it (strtoul10 for the
 * unsigned types: digits only; strtol10 for the signed: an optional sign):
 * at most 20 characters.  0 and *v (saturated), or -1. */
static int ascii_int(const char *t, size_t len, int type, long long *v)
{
    size_t i = 0;
    int neg = 0;
    if (IS_SIGNED(type) && len > 0 && (t[0] == '+' || t[0] == '-')) neg = t[i++] == '-';
    if (i == len || len > 20) return -1;
    long long x = 0;
    for (; i < len; i++) {
        if (!isdigit((unsigned char)t[i])) return -1;
        if (x < 1000000000000LL) x = 10 * x + (t[i] - '0');
    }
    *v = neg ? -x : x;
    return 0;
}

/* size bytes at p as an unsigned number in the file's byte order. */
static uint64_t rd(const ply_t *P, const unsigned char *p, int size)
{
    uint64_t v = 0;
    for (int k = 0; k < size; k++) v |= (uint64_t)p[P->fmt == 2 ? size - 1 - k : k] << (8 * k);
    return v;
}

/* a binary integer of any integer type, sign-extended */
static long long bin_int(const ply_t *P, const unsigned char *p, int type)
{
    const uint64_t u = rd(P, p, type_size[type]);
    switch (type) {
    case T_CHAR: return (int8_t)u;
    case T_SHORT: return (int16_t)u;
    case T_INT: return (int32_t)u;
    default: return (long long)u;
    }
}

/* a binary value of any type as a double */
static double bin_value(const ply_t *P, const unsigned char *p, int type)
{
    const uint64_t u = rd(P, p, type_size[type]);
    if (type == T_FLOAT) {
        const uint32_t w = (uint32_t)u;
        float f;
        memcpy(&f, &w, 4);
        return f;
    }
    if (type == T_DOUBLE) {
        double d;
        memcpy(&d, &u, 8);
        return d;
    }
    return (double)bin_int(P, p, type);
}

/* the refusal of a coordinate (role) of vertex v, given as the text tok */
static int bad_coord(const ply_t *P, long long v, int role, int code, const char *tok, size_t len)
{
    char why[160];
    sh__mesh_number_why(code, role >= R_NX ? "normal" : "coordinate", tok, len, why, sizeof why);
    if (P->fmt == 0) return sh_error(SH_EFORMAT, "PLY vertex %lld (line %d) has %s", v, P->line, why);
    return sh_error(SH_EFORMAT, "PLY vertex %lld has %s", v, why);
}

/* ------------------------------------------------------------- header */

/* T_* of a type name (PLY's and assimp's spellings), or -1. */
static int find_type(const char *t, size_t len)
{
    for (size_t k = 0; k < sizeof type_names / sizeof *type_names; k++)
        if (tok_is(t, len, type_names[k].name)) return type_names[k].type;
    return -1;
}

/* One header line tokenized: element, property, end_header (*done = 1);
 * comments, obj_info and lines of no known keyword are skipped. */
static int header_line(ply_t *P, int line, const char **tok, size_t *tl, int nt, int *done)
{
    if (nt == 0 || tok_is(tok[0], tl[0], "comment") || tok_is(tok[0], tl[0], "obj_info")) return SH_OK;
    if (tok_is(tok[0], tl[0], "end_header")) {
        if (nt != 1) return sh_error(SH_EFORMAT, "PLY header line %d: text after end_header", line);
        *done = 1;
        return SH_OK;
    }
    if (tok_is(tok[0], tl[0], "element")) {
        if (nt != 3) return sh_error(SH_EFORMAT, "PLY header line %d: expected 'element <name> <count>'", line);
        if (P->nelem == PLY_MAX_ELEMENTS)
            return sh_error(SH_EFORMAT, "PLY header: more than %d elements", PLY_MAX_ELEMENTS);
        if (tl[1] >= PLY_MAX_NAME)
            return sh_error(SH_EFORMAT, "PLY header line %d: an element name longer than %d bytes", line, PLY_MAX_NAME - 1);
        elem_t *e = &P->el[P->nelem];
        memset(e, 0, sizeof *e);
        memcpy(e->name, tok[1], tl[1]);
        e->count = parse_count(tok[2], tl[2]);
        if (e->count < 0)
            return sh_error(SH_EFORMAT, "PLY header line %d: the count of element '%s' is not a number: '%.*s'", line,
                            e->name, (int)(tl[2] > 30 ? 30 : tl[2]), tok[2]);
        if (e->count > SH_MESH_MAX_ELEMS)
            return sh_error(SH_EFORMAT, "PLY element '%s' has %.*s%s instances, more than the %d a mesh may have",
                            e->name, (int)(tl[2] > 30 ? 30 : tl[2]), tok[2], tl[2] > 30 ? "..." : "",
                            SH_MESH_MAX_ELEMS);
        if (!strcmp(e->name, "vertex")) {
            if (P->vertex >= 0) return sh_error(SH_EFORMAT, "PLY header: two 'vertex' elements");
            e->kind = K_VERTEX;
            P->vertex = P->nelem;
        } else if (!strcmp(e->name, "face")) {
            if (P->face >= 0) return sh_error(SH_EFORMAT, "PLY header: two 'face' elements");
            if (P->vertex < 0) return sh_error(SH_EFORMAT, "PLY header: the face element comes before the vertex element");
            e->kind = K_FACE;
            P->face = P->nelem;
        } else if (!strcmp(e->name, "tristrips")) {
            return sh_error(SH_EFORMAT, "PLY element 'tristrips' (triangle strips) is not read (assimp 5.2 keeps one "
                                        "triangle of each strip)");
        }
        P->nelem++;
        return SH_OK;
    }
    if (tok_is(tok[0], tl[0], "property")) {
        if (P->nelem == 0) return sh_error(SH_EFORMAT, "PLY header line %d: a property before any element", line);
        elem_t *e = &P->el[P->nelem - 1];
        const int list = nt >= 2 && tok_is(tok[1], tl[1], "list");
        if (nt != (list ? 5 : 3))
            return sh_error(SH_EFORMAT, "PLY header line %d: expected 'property <type> <name>' or 'property list "
                                        "<count type> <type> <name>'", line);
        if (e->nprop == PLY_MAX_PROPS)
            return sh_error(SH_EFORMAT, "PLY element '%s' has more than %d properties", e->name, PLY_MAX_PROPS);
        prop_t *p = &e->prop[e->nprop];
        memset(p, 0, sizeof *p);
        p->list = list;
        const char *nm = tok[nt - 1];
        const size_t nl = tl[nt - 1];
        if (nl >= PLY_MAX_NAME)
            return sh_error(SH_EFORMAT, "PLY header line %d: a property name longer than %d bytes", line, PLY_MAX_NAME - 1);
        memcpy(p->name, nm, nl);
        for (int k = list ? 2 : 1; k < nt - 1; k++) {
            const int t = find_type(tok[k], tl[k]);
            if (t < 0)
                return sh_error(SH_EFORMAT, "PLY header line %d: unknown type '%.*s'", line, (int)(tl[k] > 30 ? 30 : tl[k]),
                                tok[k]);
            if (list && k == 2) p->ctype = t;
            else p->type = t;
        }
        if (list && IS_FLOAT(p->ctype))
            return sh_error(SH_EFORMAT, "PLY list '%s' has a count of floating-point type", p->name);
        for (int k = 0; k < e->nprop; k++)
            if (!strcmp(e->prop[k].name, p->name))
                return sh_error(SH_EFORMAT, "PLY element '%s' has two properties '%s'", e->name, p->name);
        if (e->kind == K_VERTEX && !list) {
            static const char *const names[] = {"x", "y", "z", "nx", "ny", "nz"};
            for (int k = 0; k < 6; k++)
                if (!strcmp(p->name, names[k])) p->role = R_X + k;
        } else if (e->kind == K_FACE && list) {
            if (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index")) {
                for (int k = 0; k < e->nprop; k++)
                    if (e->prop[k].role == R_VIDX)
                        return sh_error(SH_EFORMAT, "PLY face element has two vertex index lists");
                if (IS_FLOAT(p->type))
                    return sh_error(SH_EFORMAT, "PLY face list '%s' has indices of floating-point type", p->name);
                p->role = R_VIDX;
            } else if (!strcmp(p->name, "texcoord")) {
                p->role = R_TEXC;
            }
        }
        e->nprop++;
        return SH_OK;
    }
    return SH_OK; /* another line (Blender 2.4 wrote a bare "Created by ..."): ignored, as assimp does */
}

/* The header, line by line within SH_MESH_PLY_MAX_HEADER bytes: P->fmt,
 * the elements, P->body; then the element rules (a vertex element with
 * properties, a face element with its index list). */
static int parse_header(ply_t *P)
{
    const size_t lim = P->n < SH_MESH_PLY_MAX_HEADER ? P->n : SH_MESH_PLY_MAX_HEADER;
    size_t pos = 0;
    int done = 0;
    for (int line = 1; !done; line++) {
        const unsigned char *nl = memchr(P->d + pos, '\n', lim - pos);
        if (!nl) {
            if (P->n > SH_MESH_PLY_MAX_HEADER)
                return sh_error(SH_EFORMAT, "PLY header does not end within its first %d bytes (no end_header line)",
                                SH_MESH_PLY_MAX_HEADER);
            return sh_error(SH_EFORMAT, "PLY header does not end: the file stops in line %d, before end_header", line);
        }
        size_t e = (size_t)(nl - P->d);
        const size_t next = e + 1;
        if (e > pos && P->d[e - 1] == '\r') e--;
        for (size_t i = pos; i < e; i++)
            if ((P->d[i] < 0x20 && P->d[i] != '\t') || P->d[i] == 0x7f)
                return sh_error(SH_EFORMAT, "PLY header line %d has a control character (0x%02x)", line, P->d[i]);
        const char *tok[8];
        size_t tl[8];
        const int nt = sh__mesh_tokens((const char *)P->d + pos, e - pos, tok, tl, 7);
        if (line == 1) {
            if (nt != 1 || tl[0] != 3 || strncasecmp(tok[0], "ply", 3))
                return sh_error(SH_EFORMAT, "not a PLY file: the first line is not 'ply'");
        } else if (line == 2) {
            if (nt != 3 || !tok_is(tok[0], tl[0], "format"))
                return sh_error(SH_EFORMAT, "PLY header line 2 is not 'format <ascii|binary_little_endian|"
                                            "binary_big_endian> 1.0'");
            if (tok_is(tok[1], tl[1], "ascii")) P->fmt = 0;
            else if (tok_is(tok[1], tl[1], "binary_little_endian")) P->fmt = 1;
            else if (tok_is(tok[1], tl[1], "binary_big_endian")) P->fmt = 2;
            else
                return sh_error(SH_EFORMAT, "PLY format '%.*s' is none of ascii, binary_little_endian, binary_big_endian",
                                (int)(tl[1] > 30 ? 30 : tl[1]), tok[1]);
            if (!tok_is(tok[2], tl[2], "1.0"))
                return sh_error(SH_EFORMAT, "PLY format version '%.*s' (1.0 is read)", (int)(tl[2] > 30 ? 30 : tl[2]),
                                tok[2]);
        } else {
            int st = header_line(P, line, tok, tl, nt, &done);
            if (st) return st;
        }
        pos = next;
        P->line = line + 1;
    }
    P->body = pos;
    if (P->vertex < 0) return sh_error(SH_EFORMAT, "PLY header has no vertex element");
    if (P->el[P->vertex].nprop == 0) return sh_error(SH_EFORMAT, "PLY vertex element has no properties");
    if (P->face >= 0) {
        int has = 0;
        for (int k = 0; k < P->el[P->face].nprop; k++) has |= P->el[P->face].prop[k].role == R_VIDX;
        if (!has) return sh_error(SH_EFORMAT, "PLY face element has no vertex_indices list");
    }
    return SH_OK;
}

/* The canonical header: the vertex and face elements only. */
static void write_header(ply_t *P)
{
    static const char *const fmt[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    char buf[256];
    snprintf(buf, sizeof buf, "ply\nformat %s 1.0\n", fmt[P->fmt]);
    puts_(P, buf);
    for (int i = 0; i < P->nelem; i++) {
        const elem_t *e = &P->el[i];
        if (e->kind == K_OTHER) continue;
        snprintf(buf, sizeof buf, "element %s %lld\n", e->name, e->count);
        puts_(P, buf);
        for (int k = 0; k < e->nprop; k++) {
            const prop_t *p = &e->prop[k];
            if (p->list) snprintf(buf, sizeof buf, "property list %s %s %s\n", type_canon[p->ctype], type_canon[p->type], p->name);
            else snprintf(buf, sizeof buf, "property %s %s\n", type_canon[p->type], p->name);
            puts_(P, buf);
        }
    }
    puts_(P, P->fmt ? "end_header\r\n" : "end_header\n");
}

/* Do the counts fit the body?  min: the fewest bytes (binary) or values
 * (ASCII) an instance of e takes. */
static int fit_counts(ply_t *P)
{
    const long long avail = (long long)(P->n - P->body);
    long long need = 0;
    for (int i = 0; i < P->nelem; i++) {
        const elem_t *e = &P->el[i];
        long long min = 0;
        for (int k = 0; k < e->nprop; k++) {
            const prop_t *p = &e->prop[k];
            if (P->fmt) min += p->list ? type_size[p->ctype] : type_size[p->type];
            else min += 1;
        }
        /* ASCII: 2 bytes a value (the last one may lack its separator) */
        const long long per = P->fmt ? min : 2 * min;
        need += e->count * per;
        if (need > avail + (P->fmt ? 0 : 1))
            return sh_error(SH_EFORMAT, "PLY body has %lld bytes, fewer than its header's counts need: element '%s' alone "
                                        "(%lld instances of at least %lld bytes) does not fit after byte %lld",
                            avail, e->name, e->count, per, need - e->count * per);
    }
    return SH_OK;
}

/* ------------------------------------------------------------- body */

/* Face f read, with k indices and tc texture coordinates: its rules, and
 * the counts of corners, triangles and triangulation work. */
static int face_done(ply_t *P, long long f, long long k, long long tc)
{
    if (tc > 2 * k)
        return sh_error(SH_EFORMAT, "PLY face %lld has %lld texture coordinates for %lld vertices (2 each at most)", f, tc, k);
    P->corners += k;
    P->tris += k >= 3 ? k - 2 : 0;
    if (k > 4) P->ngon += k * k;
    if (P->tris > SH_MESH_MAX_ELEMS)
        return sh_error(SH_EFORMAT, "PLY faces make more than the %d triangles a mesh may have", SH_MESH_MAX_ELEMS);
    if (P->ngon > SH_MESH_NGON_WORK(P->n))
        return sh_error(SH_EFORMAT, "PLY faces of many corners (up to face %lld, %lld corners) would take the importer "
                                    "too long to triangulate: the sum of their corners squared exceeds %lld for a file "
                                    "of %zu bytes", f, k, SH_MESH_NGON_WORK(P->n), P->n);
    return SH_OK;
}

/* A face's index count: 1 to SH_MESH_MAX_FACE_INDICES. */
static int vidx_count(const ply_t *P, long long f, long long k)
{
    if (k < 1) return sh_error(SH_EFORMAT, "PLY face %lld has no vertex indices (a count of %lld)", f, k);
    if (k > SH_MESH_MAX_FACE_INDICES)
        return sh_error(SH_EFORMAT, "PLY face %lld has %lld vertex indices, more than the %d read", f, k,
                        SH_MESH_MAX_FACE_INDICES);
    return SH_OK;
}

/* A face's index: a vertex of the vertex element. */
static int vidx_value(const ply_t *P, long long f, long long v)
{
    const long long nv = P->el[P->vertex].count;
    if (v < 0 || v >= nv) {
        if (P->fmt == 0)
            return sh_error(SH_EFORMAT, "PLY face %lld (line %d) refers to vertex %lld of %lld", f, P->line, v, nv);
        return sh_error(SH_EFORMAT, "PLY face %lld refers to vertex %lld of %lld", f, v, nv);
    }
    return SH_OK;
}

/* The binary body, record by record (every value in the file, every
 * length checked before it is read); the vertex and face elements' bytes
 * copied to the canonical copy; nothing may follow the last element. */
static int walk_binary(ply_t *P)
{
    const unsigned char *p = P->d + P->body, *end = P->d + P->n;
    for (int i = 0; i < P->nelem; i++) {
        const elem_t *e = &P->el[i];
        const unsigned char *b0 = p;
        for (long long j = 0; j < e->count; j++) {
            long long k = 0, tc = 0;
            for (int q = 0; q < e->nprop; q++) {
                const prop_t *pr = &e->prop[q];
                const int cs = pr->list ? type_size[pr->ctype] : 0, is = type_size[pr->type];
                if ((size_t)(end - p) < (size_t)(pr->list ? cs : is))
                    goto truncated;
                if (!pr->list) {
                    if (pr->role >= R_X && pr->role <= R_NZ && IS_FLOAT(pr->type) &&
                        (pr->role <= R_Z || !(P->flags & SH_MESH_COMPUTE_NORMALS))) {
                        const double x = bin_value(P, p, pr->type);
                        if (!(fabs(x) <= SH_MESH_MAX_COORD)) {
                            char num[40];
                            snprintf(num, sizeof num, "%g", x);
                            return bad_coord(P, j, pr->role, isfinite(x) ? SH_NUM_RANGE : SH_NUM_NONFINITE, num,
                                             strlen(num));
                        }
                    }
                    p += is;
                    continue;
                }
                const long long c = bin_int(P, p, pr->ctype);
                p += cs;
                if (pr->role == R_VIDX) {
                    int st = vidx_count(P, j, c);
                    if (st) return st;
                    k = c;
                } else if (c < 0) {
                    return sh_error(SH_EFORMAT, "PLY element '%s' instance %lld: list '%s' has a negative count", e->name,
                                    j, pr->name);
                }
                if (pr->role == R_TEXC) tc = c;
                if ((unsigned long long)(end - p) / (unsigned)is < (unsigned long long)c) goto truncated;
                if (pr->role == R_VIDX)
                    for (long long a = 0; a < c; a++) {
                        int st = vidx_value(P, j, bin_int(P, p + a * is, pr->type));
                        if (st) return st;
                    }
                p += c * is;
            }
            if (e->kind == K_FACE) {
                int st = face_done(P, j, k, tc);
                if (st) return st;
            }
            continue;
        truncated:
            return sh_error(SH_EFORMAT, "PLY body ends inside element '%s' (instance %lld of %lld): the file is shorter "
                                        "than its header's counts say", e->name, j, e->count);
        }
        if (e->kind != K_OTHER) put(P, b0, (size_t)(p - b0));
    }
    if (p != end)
        return sh_error(SH_EFORMAT, "PLY body has %lld bytes after its last element (the header's counts do not match "
                                    "the body)", (long long)(end - p));
    return SH_OK;
}

/* The next non-blank line of the ASCII body from *pos: [*b, *e), with
 * *pos moved past it and P->line counted; 0 at the end of the file. */
static int next_line(ply_t *P, size_t *pos, size_t *b, size_t *e)
{
    while (*pos < P->n) {
        const unsigned char *nl = memchr(P->d + *pos, '\n', P->n - *pos);
        size_t s = *pos, t = nl ? (size_t)(nl - P->d) : P->n;
        *pos = nl ? t + 1 : P->n;
        if (t > s && P->d[t - 1] == '\r') t--;
        int blank = 1;
        for (size_t i = s; i < t; i++) {
            const unsigned char c = P->d[i];
            if ((c < 0x20 && c != '\t') || c == 0x7f)
                return sh_error(SH_EFORMAT, "PLY line %d has a control character (0x%02x)", P->line, c), -1;
            if (c != ' ' && c != '\t') blank = 0;
        }
        if (!blank) {
            *b = s;
            *e = t;
            return 1;
        }
        P->line++;
    }
    return 0;
}

/* one ASCII value of property type t; coordinates checked (role) */
static int ascii_value(ply_t *P, const elem_t *e, long long j, const prop_t *pr, int type, const char *t, size_t len)
{
    if (!IS_FLOAT(type)) {
        long long v;
        if (ascii_int(t, len, type, &v))
            return sh_error(SH_EFORMAT, "PLY line %d: '%.*s' is not a %s (element '%s', property '%s')", P->line,
                            (int)(len > 30 ? 30 : len), t, type_canon[type], e->name, pr->name);
        return SH_OK;
    }
    const int code = sh__mesh_number(t, len, type == T_FLOAT ? 38 : 308, NULL);
    const int coord = pr->role >= R_X && pr->role <= R_NZ && (pr->role <= R_Z || !(P->flags & SH_MESH_COMPUTE_NORMALS));
    if (code && coord) return bad_coord(P, j, pr->role, code, t, len);
    if (code == SH_NUM_SYNTAX)
        return sh_error(SH_EFORMAT, "PLY line %d: '%.*s' is not a number (element '%s', property '%s')", P->line,
                        (int)(len > 30 ? 30 : len), t, e->name, pr->name);
    return SH_OK;
}

/* The ASCII body, an instance a line (blank lines skipped), each line
 * holding exactly its element's values; the vertex and face lines copied
 * to the canonical copy, values one space apart; only white space may
 * follow the last element. */
static int walk_ascii(ply_t *P)
{
    size_t pos = P->body;
    enum { MAXTOK = 2 * PLY_MAX_PROPS + SH_MESH_MAX_FACE_INDICES + 8 };
    const char **tok = malloc(sizeof *tok * MAXTOK);
    size_t *tl = malloc(sizeof *tl * MAXTOK);
    if (!tok || !tl) {
        free(tok);
        free(tl);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    int st = SH_OK;
    for (int i = 0; i < P->nelem && !st; i++) {
        const elem_t *e = &P->el[i];
        for (long long j = 0; j < e->count && !st; j++) {
            size_t b, t;
            const int got = next_line(P, &pos, &b, &t);
            if (got < 0) { st = SH_EFORMAT; break; }
            if (!got) {
                st = sh_error(SH_EFORMAT, "PLY file ends in element '%s' after %lld of its %lld instances", e->name, j,
                              e->count);
                break;
            }
            const int nt = sh__mesh_tokens((const char *)P->d + b, t - b, tok, tl, MAXTOK);
            if (nt > MAXTOK) {
                st = sh_error(SH_EFORMAT, "PLY line %d has more than %d values", P->line, MAXTOK);
                break;
            }
            int q = 0, used = 0;
            long long k = 0, tc = 0;
            for (; q < e->nprop && !st; q++) {
                const prop_t *pr = &e->prop[q];
                if (used >= nt) break;
                if (!pr->list) {
                    st = ascii_value(P, e, j, pr, pr->type, tok[used], tl[used]);
                    used++;
                    continue;
                }
                long long c;
                if (ascii_int(tok[used], tl[used], pr->ctype, &c) || c < 0) {
                    st = sh_error(SH_EFORMAT, "PLY line %d: the count of list '%s' is not a count: '%.*s'", P->line,
                                  pr->name, (int)(tl[used] > 30 ? 30 : tl[used]), tok[used]);
                    break;
                }
                used++;
                if (pr->role == R_VIDX) {
                    if ((st = vidx_count(P, j, c))) break;
                    k = c;
                }
                if (pr->role == R_TEXC) tc = c;
                if (c > nt - used) break; /* too few values: below */
                for (long long a = 0; a < c && !st; a++, used++) {
                    if (pr->role == R_VIDX) {
                        long long v;
                        if (ascii_int(tok[used], tl[used], pr->type, &v))
                            st = sh_error(SH_EFORMAT, "PLY line %d: '%.*s' is not a vertex index", P->line,
                                          (int)(tl[used] > 30 ? 30 : tl[used]), tok[used]);
                        else st = vidx_value(P, j, v);
                    } else {
                        st = ascii_value(P, e, j, pr, pr->type, tok[used], tl[used]);
                    }
                }
            }
            if (st) break;
            if (q < e->nprop || used < nt) {
                st = sh_error(SH_EFORMAT, "PLY line %d has %s values than element '%s' declares (%d properties)", P->line,
                              used < nt ? "more" : "fewer", e->name, e->nprop);
                break;
            }
            if (e->kind == K_FACE && (st = face_done(P, j, k, tc))) break;
            if (e->kind != K_OTHER) {
                for (int a = 0; a < nt; a++) {
                    if (a) put(P, " ", 1);
                    put(P, tok[a], tl[a]);
                }
                put(P, "\n", 1);
            }
            P->line++;
        }
    }
    free(tok);
    free(tl);
    if (st) return st;
    for (size_t i = pos; i < P->n; i++)
        if (!isspace(P->d[i])) {
            int line = P->line;
            for (size_t a = pos; a < i; a++) line += P->d[a] == '\n';
            return sh_error(SH_EFORMAT, "PLY file has text after its last element (line %d)", line);
        }
    return SH_OK;
}

int sh__mesh_guard_ply(const unsigned char *data, size_t n, int flags, sh_mesh_guard *g)
{
    ply_t P;
    memset(&P, 0, sizeof P);
    P.d = data;
    P.n = n;
    P.flags = flags;
    P.vertex = P.face = -1;
    P.el = malloc(sizeof *P.el * PLY_MAX_ELEMENTS);
    if (!P.el) return sh_error(SH_ENOMEM, "out of memory");
    int st = parse_header(&P);
    if (!st) st = fit_counts(&P);
    if (!st) {
        /* the copy is never longer than the file: kept lines are not
         * lengthened, the header is rewritten (under 64 KB + names) */
        P.ocap = n + 2 * SH_MESH_PLY_MAX_HEADER;
        P.out = malloc(P.ocap);
        if (!P.out) st = sh_error(SH_ENOMEM, "out of memory copying a PLY file of %zu bytes", n);
    }
    if (!st) {
        write_header(&P);
        st = P.fmt ? walk_binary(&P) : walk_ascii(&P);
    }
    if (!st && P.olen > P.ocap) st = sh_error(SH_EFORMAT, "PLY copy overflow (%zu > %zu bytes)", P.olen, P.ocap);
    /* a correct import has at most the file's vertices, or one per face
     * corner (when a post-processing step splits the mesh), and a triangle
     * per face corner beyond two */
    const long long nv = P.vertex >= 0 ? P.el[P.vertex].count : 0;
    free(P.el);
    if (st) {
        free(P.out);
        return st;
    }
    g->canon = P.out;
    g->bytes = P.out;
    g->size = P.olen;
    g->max_vertices = nv + P.corners;
    g->max_triangles = P.tris;
    return SH_OK;
}
