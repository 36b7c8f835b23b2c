/* number.c — the one rule for reading a decimal number from text, shared by
 * the library's spec parsers (lights, windows, scenes) and the CLI: strtod
 * on decimal text only, and the value must be finite and within double's
 * range.
 *
 * Decimal only: strtod also reads hexadecimal ("0x10" is 16, "0x1p-3" is
 * 0.125), "inf", "infinity" and "nan"; none of them is a number here, so
 * "--samples 0x10" is refused instead of read as 16.  The text must start
 * (after white space and a sign) with a digit, or with '.' and a digit.
 *
 * Range: strtod reports ERANGE for a value that overflows (±HUGE_VAL) and
 * for one that underflows (0 or a subnormal): "1e-400" would otherwise
 * silently become 0.  Both are errors; an exact zero ("0", "0e-400") is
 * fine. */
#include "core/shlab_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>

/* Non-zero if s begins a decimal number: [space][sign](digit | . digit), not 0x. */
static int decimal_start(const char *s)
{
    while (isspace((unsigned char)*s)) s++;
    if (*s == '+' || *s == '-') s++;
    if (s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) return 0;
    if (*s == '.') s++;
    return isdigit((unsigned char)*s);
}

int sh__parse_double(const char *s, char **end, double *out)
{
    if (end) *end = (char *)s;
    if (!decimal_start(s)) return SH__NUM_NONE;
    char *e;
    errno = 0;
    const double v = strtod(s, &e);
    if (end) *end = e;
    if (e == s) return SH__NUM_NONE;
    if (errno == ERANGE || !isfinite(v)) return SH__NUM_RANGE;
    *out = v;
    return SH__NUM_OK;
}
