/* error.c — status codes and the thread-local "last error" reason (GSL style:
 * routines return a status, the CLI turns it into one line on stderr). */
#include "shlab.h"

#include <stdarg.h>
#include <stdio.h>

static _Thread_local char last_error[512];

int sh_error(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
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
