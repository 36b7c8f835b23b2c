/* shard.c — splitting a sweep into N independent shards (lab.h).
 *
 * A sweep is a list of work items numbered 0..n−1 in the order of the
 * unsharded run.  The items are dealt to the shards like cards, forth and
 * back ("serpentine"): with r = j mod 2N, item j belongs to shard r when
 * r < N and to shard 2N−1−r otherwise (N = 2: 0 1 1 0 0 1 1 0 ...).  Every
 * shard gets every 2N-th item twice, so a sweep whose items grow in cost
 * with j (bands: l² or l³) is split evenly — plain j mod N would give the
 * last shard the dearer item of every round — and the owner depends on
 * nothing but (j, N).
 */
#include "lab/lab.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>

static int parse_int(const char *s, char **end, long *v)
{
    if (*s < '0' || *s > '9') return -1; /* no sign, no space */
    errno = 0;
    *v = strtol(s, end, 10);
    return errno ? -1 : 0;
}

int sh_shard_parse(const char *s, sh_shard *out)
{
    char *end;
    long i, n;
    if (!s || parse_int(s, &end, &i) || *end != '/' || parse_int(end + 1, &end, &n) || *end)
        return sh_error(SH_EINVAL, "shard '%s' is not I/N (I = 0..N-1)", s ? s : "");
    if (n < 1 || n > SH_SHARD_MAX)
        return sh_error(SH_EINVAL, "shard '%s': N = %ld out of range 1..%d", s, n, SH_SHARD_MAX);
    if (i >= n) return sh_error(SH_EINVAL, "shard '%s': I = %ld must be below N = %ld (I counts from 0)", s, i, n);
    out->index = (int)i;
    out->count = (int)n;
    return SH_OK;
}

int sh_shard_owns(const sh_shard *s, long item)
{
    if (!s || s->count <= 1) return 1;
    if (item < 0) return 0;
    const long r = item % (2L * s->count);
    return (r < s->count ? r : 2L * s->count - 1 - r) == s->index;
}

static int shard_owns(void *ctx, long item) { return sh_shard_owns(ctx, item); }

sh_items sh_shard_items(const sh_shard *s)
{
    return (sh_items){s ? shard_owns : NULL, (void *)s};
}
