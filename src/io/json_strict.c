/* json_strict.c — JSON text parsed as shlab reads every input file
 * (json_strict.h). */
#include "io/json_strict.h"
#include "core/shlab_internal.h"

/* A JSON number that underflows is refused as on the command line
 * (sh__parse_double): jansson reads "1e-400" as 0.  The text is scanned for
 * number tokens outside strings. */
static int json_underflow(const char *buf, size_t n, const char *name)
{
    int in_str = 0, line = 1;
    for (size_t i = 0; i < n; i++) {
        const char c = buf[i];
        if (c == '\n') line++;
        if (in_str) {
            if (c == '\\') i++;
            else if (c == '"') in_str = 0;
            continue;
        }
        if (c == '"') { in_str = 1; continue; }
        if (c == '-' || (c >= '0' && c <= '9')) {
            char *end;
            double v;
            const int r = sh__parse_double(buf + i, &end, &v);
            if (r == SH__NUM_RANGE)
                return sh_error(SH_EFORMAT, "%s: line %d: the number '%.*s' is outside double's range", name, line,
                                (int)(end - (buf + i) < 40 ? end - (buf + i) : 40), buf + i);
            if (end > buf + i) i = (size_t)(end - buf) - 1;
        }
    }
    return SH_OK;
}

int sh__json_parse(const char *buf, size_t n, const char *name, json_t **root)
{
    json_error_t err;
    *root = json_loadb(buf, n, JSON_REJECT_DUPLICATES, &err);
    if (!*root) return sh_error(SH_EFORMAT, "%s: not valid JSON (line %d: %s)", name, err.line, err.text);
    const int st = json_underflow(buf, n, name);
    if (st) {
        json_decref(*root);
        *root = NULL;
    }
    return st;
}
