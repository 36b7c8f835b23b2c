/* mesh_guard.c — the guard in front of the mesh importer: which reader the
 * bytes go to, and the checks every reader shares (mesh_internal.h).
 *
 * The format is chosen as assimp chooses its reader (Importer::ReadFile,
 * assimp 5.2): by the name's extension, and when no reader claims the
 * extension, by the content.  We make the choice ourselves and hand the
 * importer a name whose extension forces it:
 *   .ply, or no known extension and a first line "ply" (PLYImporter's magic)
 *        -> PLY, checked by mesh_guard_ply.c;
 *   .obj, or no known extension and an OBJ keyword at the start of a line
 *        in the first 200 bytes (ObjFileImporter::CanRead's tokens)
 *        -> OBJ, checked by mesh_guard_obj.c;
 *   anything else -> the importer's own choice, unchecked here: such files
 *        rely on the sandbox alone (mesh_sandbox.c).
 *
 * Limits handed to the sandbox, from the file's size n.  Measured growth of
 * the importer's resident memory (getrusage around sh__mesh_import on 11 MB
 * PLY and OBJ grids and the test models): 11 (PLY) to 17 (OBJ)
 * bytes per input byte, at least 20 MB for any OBJ (assimp's 16 MB line
 * buffer); under AddressSanitizer 25 to 37 bytes per byte.  Speed: 10-30 MB/s
 * on a loaded machine.  So:
 *   memory   256 MB + 64 n, formats not checked here 1 GB + 64 n, plus under
 *            AddressSanitizer 256 MB (its quarantine keeps up to 256 MB of
 *            freed memory); never above the machine's physical memory;
 *   CPU      10 s + 1 s per 2 MB. */
#include "scene/mesh_internal.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

int sh__mesh_import_knows_ext(const char *ext); /* mesh_import.c */

void sh__mesh_guard_free(sh_mesh_guard *g)
{
    if (!g) return;
    free(g->canon);
    free(g->name);
    memset(g, 0, sizeof *g);
}

/* The extension of name's last component (after its last '.'), or NULL. */
static const char *ext_of(const char *name)
{
    const char *base = strrchr(name, '/');
    base = base ? base + 1 : name;
    const char *dot = strrchr(base, '.');
    return dot && dot[1] ? dot + 1 : NULL;
}

/* PLYImporter's magic: the first line begins with "ply", in any case. */
static int looks_ply(const unsigned char *d, size_t n)
{
    return n >= 3 && tolower(d[0]) == 'p' && tolower(d[1]) == 'l' && tolower(d[2]) == 'y';
}

/* ObjFileImporter::CanRead: one of its tokens at the start of a line within
 * the first 200 bytes, in any case. */
static int looks_obj(const unsigned char *d, size_t n)
{
    static const char *tok[] = {"mtllib", "usemtl", "v ", "vt ", "vn ", "o ", "g ", "s ", "f "};
    const size_t lim = n < 200 ? n : 200;
    for (size_t i = 0; i < lim; i++) {
        if (i > 0 && d[i - 1] != '\n' && d[i - 1] != '\r') continue;
        for (size_t k = 0; k < sizeof tok / sizeof *tok; k++) {
            const size_t L = strlen(tok[k]);
            if (i + L <= lim && !strncasecmp((const char *)d + i, tok[k], L)) return 1;
        }
    }
    return 0;
}

int sh__mesh_guard(const unsigned char *data, size_t n, const char *name, int flags, sh_mesh_guard *g)
{
    if (!g) return sh_error(SH_EINVAL, "sh__mesh_guard: no output");
    memset(g, 0, sizeof *g);
    if (!name || (!data && n)) return sh_error(SH_EINVAL, "sh__mesh_guard: bad arguments");
    if (n == 0) return sh_error(SH_EFORMAT, "the file is empty");
    const char *ext = ext_of(name);
    int fmt = SH_MESH_FMT_OTHER;
    if (ext && !strcasecmp(ext, "ply")) fmt = SH_MESH_FMT_PLY;
    else if (ext && !strcasecmp(ext, "obj")) fmt = SH_MESH_FMT_OBJ;
    else if (!ext || !sh__mesh_import_knows_ext(ext)) fmt = looks_ply(data, n) ? SH_MESH_FMT_PLY
                                                            : looks_obj(data, n) ? SH_MESH_FMT_OBJ
                                                                                 : SH_MESH_FMT_OTHER;
    /* the importer's name: ours, with the extension that forces the reader */
    const char *force = fmt == SH_MESH_FMT_PLY ? ".ply" : fmt == SH_MESH_FMT_OBJ ? ".obj" : "";
    if (ext && *force && !strcasecmp(ext, force + 1)) force = "";
    g->name = malloc(strlen(name) + strlen(force) + 1);
    if (!g->name) return sh_error(SH_ENOMEM, "out of memory");
    strcpy(g->name, name);
    strcat(g->name, force);
    g->format = fmt;
    g->bytes = data;
    g->size = n;
    g->max_vertices = g->max_triangles = SH_MESH_MAX_ELEMS;
    g->mem_budget = (fmt == SH_MESH_FMT_OTHER ? 1LL << 30 : 256LL << 20) + 64 * (long long)n;
#ifdef SH_MESH_ASAN
    g->mem_budget += 256LL << 20;
#endif
    const long long phys = (long long)sysconf(_SC_PHYS_PAGES) * (long long)sysconf(_SC_PAGESIZE);
    if (phys > 0 && g->mem_budget > phys) g->mem_budget = phys;
    g->cpu_seconds = 10.0 + (double)n / (2 << 20);
    int st = SH_OK;
    if (fmt == SH_MESH_FMT_PLY) st = sh__mesh_guard_ply(data, n, flags, g);
    else if (fmt == SH_MESH_FMT_OBJ) st = sh__mesh_guard_obj(data, n, flags, g);
    if (st) sh__mesh_guard_free(g);
    return st;
}

/* ------------------------------------------------------------- tokens */

int sh__mesh_tokens(const char *s, size_t len, const char **tok, size_t *tl, int max)
{
    int k = 0;
    size_t i = 0;
    while (i < len) {
        while (i < len && (s[i] == ' ' || s[i] == '\t')) i++;
        if (i == len) break;
        const size_t b = i;
        while (i < len && s[i] != ' ' && s[i] != '\t') i++;
        if (k == max) return max + 1;
        tok[k] = s + b;
        tl[k] = i - b;
        k++;
    }
    return k;
}

/* ------------------------------------------------------------- numbers */

int sh__mesh_number(const char *s, size_t len, int max_exp, double *v)
{
    if (v) *v = 0;
    if (len == 0) return SH_NUM_SYNTAX;
    size_t i = 0;
    if (s[i] == '+' || s[i] == '-') i++;
    /* nan, inf, infinity (fast_atof reads them, in any case) */
    if (i < len && isalpha((unsigned char)s[i])) {
        if (len - i == 3 && (!strncasecmp(s + i, "nan", 3) || !strncasecmp(s + i, "inf", 3))) return SH_NUM_NONFINITE;
        if (len - i == 8 && !strncasecmp(s + i, "infinity", 8)) return SH_NUM_NONFINITE;
        return SH_NUM_SYNTAX;
    }
    if (len > 64) return SH_NUM_SYNTAX;
    /* mag: the power of ten of the first non-zero digit, before the exponent */
    long mag = LONG_MIN;
    size_t d0 = i;
    while (i < len && isdigit((unsigned char)s[i])) {
        if (mag == LONG_MIN && s[i] != '0') mag = 0;
        else if (mag != LONG_MIN) mag++;
        i++;
    }
    const size_t idig = i - d0;
    size_t fdig = 0;
    if (i < len && s[i] == '.') {
        i++;
        const size_t f0 = i;
        while (i < len && isdigit((unsigned char)s[i])) {
            if (mag == LONG_MIN && s[i] != '0') mag = -(long)(i - f0) - 1;
            i++;
        }
        fdig = i - f0;
    }
    if (idig == 0 && fdig == 0) return SH_NUM_SYNTAX;
    long e = 0;
    if (i < len && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        int neg = 0;
        if (i < len && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
        if (i == len || !isdigit((unsigned char)s[i])) return SH_NUM_SYNTAX;
        while (i < len && isdigit((unsigned char)s[i])) {
            if (e < 100000) e = 10 * e + (s[i] - '0');
            i++;
        }
        if (!neg && e > max_exp) return SH_NUM_RANGE;
        if (neg) e = -e;
    }
    if (i != len) return SH_NUM_SYNTAX;
    /* |value| < 10^(mag + e + 1): below 1e37 needs no conversion to decide */
    if (!v && (mag == LONG_MIN || mag + e <= 36)) return 0;
    char tmp[72];
    memcpy(tmp, s, len);
    tmp[len] = '\0';
    const double x = strtod(tmp, NULL);
    if (v) *v = x;
    if (!(fabs(x) <= SH_MESH_MAX_COORD)) return SH_NUM_RANGE;
    return 0;
}

const char *sh__mesh_number_why(int code, const char *what, const char *tok, size_t len, char *buf, size_t cap)
{
    const int L = len > 40 ? 40 : (int)len;
    const char *more = len > 40 ? "..." : "";
    if (code == SH_NUM_NONFINITE) snprintf(buf, cap, "a non-finite %s '%.*s'", what, L, tok);
    else if (code == SH_NUM_RANGE)
        snprintf(buf, cap, "a %s out of range: '%.*s%s' (|x| <= %g)", what, L, tok, more, SH_MESH_MAX_COORD);
    else snprintf(buf, cap, "a %s that is not a number: '%.*s%s'", what, L, tok, more);
    return buf;
}
