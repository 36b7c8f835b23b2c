/* sh_index.c — flat index helpers and the names of conventions.
 * Flat index i = l(l+1)+m (Green 2003, "y_i = y_l^m, i = l(l+1)+m"). */
#include "shlab.h"

#include <math.h>
#include <string.h>

void sh_index_lm(int i, int *l, int *m)
{
    int ll = (int)floor(sqrt((double)i));
    /* guard against rounding of sqrt near perfect squares */
    while (ll * ll > i) ll--;
    while ((ll + 1) * (ll + 1) <= i) ll++;
    *l = ll;
    *m = i - ll * (ll + 1);
}

int sh_check_order(int order)
{
    if (order < 1 || order > SHLAB_MAX_ORDER)
        return sh_error(SH_EINVAL, "order %d is outside 1..%d", order, SHLAB_MAX_ORDER);
    return SH_OK;
}

const char *sh_convention_name(sh_convention c) { return c == SH_NOCS ? "nocs" : "cs"; }

int sh_convention_parse(const char *s, sh_convention *out)
{
    if (s && strcmp(s, "cs") == 0) { *out = SH_CS; return SH_OK; }
    if (s && strcmp(s, "nocs") == 0) { *out = SH_NOCS; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown convention '%s' (expected cs or nocs)", s ? s : "");
}

static const char *const norm_names[] = {"cs", "nocs", "4pi", "schmidt"};

const char *sh_norm_name(sh_norm n)
{
    return (n >= SH_NORM_CS && n <= SH_NORM_SCHMIDT) ? norm_names[n] : "?";
}

int sh_norm_parse(const char *s, sh_norm *out)
{
    for (int k = 0; k < 4; k++)
        if (s && strcmp(s, norm_names[k]) == 0) { *out = (sh_norm)k; return SH_OK; }
    return sh_error(SH_EINVAL, "unknown normalisation '%s' (expected cs, nocs, 4pi or schmidt)",
                    s ? s : "");
}
