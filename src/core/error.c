/* error.c — status codes and the thread-local "last error" reason (GSL style:
 * routines return a status, the CLI turns it into one line on stderr).
 *
 * A reason often quotes input (a file name, a channel name, a JSON parser's
 * message, an argument), so it is made printable as one line of text here,
 * in one place: control characters become \n, \r, \t or \xNN, and bytes that
 * are not UTF-8 (or are the C1 controls U+0080..U+009F) become \xNN. */
#include "core/shlab_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static _Thread_local char last_error[1024];

/* Length of the valid UTF-8 sequence at s (2..4), or 0 if there is none. */
static int utf8_len(const unsigned char *s)
{
    const unsigned char c = s[0];
    int n;
    unsigned char lo = 0x80, hi = 0xbf; /* allowed range of the second byte */
    if (c >= 0xc2 && c <= 0xdf) n = 2;
    else if (c >= 0xe0 && c <= 0xef) {
        n = 3;
        if (c == 0xe0) lo = 0xa0;        /* no overlong forms */
        if (c == 0xed) hi = 0x9f;        /* no surrogates */
    } else if (c >= 0xf0 && c <= 0xf4) {
        n = 4;
        if (c == 0xf0) lo = 0x90;
        if (c == 0xf4) hi = 0x8f;        /* at most U+10FFFF */
    } else return 0;
    if (s[1] < lo || s[1] > hi) return 0;
    for (int k = 2; k < n; k++)
        if (s[k] < 0x80 || s[k] > 0xbf) return 0;
    if (n == 2 && c == 0xc2 && s[1] <= 0x9f) return 0; /* C1 control */
    return n;
}

char *sh__escape_line(char *dst, size_t cap, const char *src)
{
    if (!dst || cap == 0) return dst;
    const unsigned char *s = (const unsigned char *)(src ? src : "");
    size_t o = 0;
    while (*s) {
        char esc[8];
        const char *piece;
        size_t len;
        int u = *s >= 0x80 ? utf8_len(s) : 0;
        if (*s >= 0x20 && *s != 0x7f && *s < 0x80) { piece = (const char *)s; len = 1; }
        else if (u) { piece = (const char *)s; len = (size_t)u; }
        else {
            if (*s == '\n') piece = "\\n";
            else if (*s == '\r') piece = "\\r";
            else if (*s == '\t') piece = "\\t";
            else { snprintf(esc, sizeof esc, "\\x%02x", *s); piece = esc; }
            len = strlen(piece);
            u = 1;
        }
        if (o + len + 4 > cap) { /* keep room for "..." and the terminator */
            if (o + 4 <= cap) memcpy(dst + o, "...", 3), o += 3;
            break;
        }
        memcpy(dst + o, piece, len);
        o += len;
        s += u ? (size_t)u : len;
    }
    dst[o < cap ? o : cap - 1] = '\0';
    return dst;
}

int sh_error(int status, const char *fmt, ...)
{
    char raw[sizeof last_error];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    sh__escape_line(last_error, sizeof last_error, raw);
    return status;
}

const char *sh_last_error(void) { return last_error; }

const char *sh_strerror(int status)
{
    switch (status) {
    case SH_OK: return "success";
    case SH_EINVAL: return "invalid argument";
    case SH_ENOMEM: return "out of memory";
    case SH_EIO: return "input/output error";
    case SH_EFORMAT: return "bad file format";
    case SH_ENOTSUP: return "not supported";
    case SH_ENUM: return "numerical failure";
    default: return "unknown error";
    }
}
