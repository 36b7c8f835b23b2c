/* number.c — the one rule for reading a decimal number from text, shared by
 * the library's spec parsers (lights, windows) and the CLI: strtod, and the
 * value must be finite and within double's range.  strtod reports ERANGE
 * for a value that overflows (±HUGE_VAL) and for one that underflows (0 or a
 * subnormal): "1e-400" would otherwise silently become 0.  Both are errors;
 * an exact zero ("0", "0e-400") is fine. */
#include "core/shlab_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>

int sh__parse_double(const char *s, char **end, double *out)
{
    char *e;
    errno = 0;
    const double v = strtod(s, &e);
    if (end) *end = e;
    if (e == s) return SH__NUM_NONE;
    if (errno == ERANGE || !isfinite(v)) return SH__NUM_RANGE;
    *out = v;
    return SH__NUM_OK;
}
