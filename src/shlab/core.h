/* shlab/core.h — status codes, error messages, conventions, the flat index,
 * spherical functions, progress.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_CORE_H
#define SHLAB_CORE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest supported order (bands 0..SHLAB_MAX_ORDER-1).  The normalised
 * Legendre recurrence is tested against GSL up to l = 2000 and beyond; the
 * halfpi rotation is tested to l = 4000. */
#define SHLAB_MAX_ORDER 4097

/* ---------------------------------------------------------------- status */
enum {
    SH_OK = 0,
    SH_EINVAL = 1,  /* bad argument (order out of range, NaN, zero vector, ...) */
    SH_ENOMEM = 2,  /* allocation failed */
    SH_EIO = 3,     /* file could not be opened / read / written */
    SH_EFORMAT = 4, /* file is corrupt, truncated or has no usable channels */
    SH_ENOTSUP = 5, /* valid request that this routine does not implement */
    SH_ENUM = 6     /* a numerical result was not finite / did not converge */
};

/* Record a formatted reason for a failure; returns status unchanged so that
 * code can write `return sh_error(SH_EINVAL, "order %d < 1", n);`. */
int sh_error(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The reason recorded by the last failing call on this thread ("" if none). */
const char *sh_last_error(void);
/* A generic name for a status code. */
const char *sh_strerror(int status);

/* ------------------------------------------------------------ conventions */
typedef enum { SH_CS = 0, SH_NOCS = 1 } sh_convention;

/* Coefficient normalisations accepted by sh_convert():
 *   SH_NORM_CS       orthonormal, Condon-Shortley phase (the default basis)
 *   SH_NORM_NOCS     orthonormal, no phase (odd m negated relative to CS)
 *   SH_NORM_4PI      4π-normalised (∫y² dΩ = 4π), no phase (SHTOOLS default)
 *   SH_NORM_SCHMIDT  Schmidt semi-normalised (∫y² dΩ = 4π/(2l+1)), no phase */
typedef enum { SH_NORM_CS = 0, SH_NORM_NOCS, SH_NORM_4PI, SH_NORM_SCHMIDT } sh_norm;

const char *sh_convention_name(sh_convention c);
int sh_convention_parse(const char *s, sh_convention *out);
const char *sh_norm_name(sh_norm n);
int sh_norm_parse(const char *s, sh_norm *out);

/* ------------------------------------------------------------------ index */
static inline int sh_index(int l, int m) { return l * (l + 1) + m; }
static inline int sh_ncoeff(int order) { return order * order; }
/* Inverse of sh_index: band l and order m of flat index i >= 0. */
void sh_index_lm(int i, int *l, int *m);
/* SH_OK if 1 <= order <= SHLAB_MAX_ORDER, else SH_EINVAL with a reason. */
int sh_check_order(int order);

/* A scalar spherical function.  Both forms of the point are given so that a
 * function defined in angles (Green's example light) and one defined on
 * vectors are evaluated without a round trip. */
typedef double (*sh_sphere_fn)(const double dir[3], double theta, double phi, void *ctx);

/* Progress of a long computation: called after each of `total` steps
 * (`done` of them finished), `what` naming the phase.  Never required. */
typedef void (*sh_progress_fn)(void *ctx, int done, int total, const char *what);

/* ------------------------------------------------------------ sweep items
 * Which work items of a sweep a call computes (items 0..n−1 in the order of
 * the unsharded run): owns(ctx, j) != 0.  A NULL sh_items means every item.
 * A work item's result must not depend on which others are computed (seeds
 * come from the item, not from a running generator), so a sweep can be split
 * across processes (the lab's shards) and joined. */
typedef struct {
    int (*owns)(void *ctx, long item);
    void *ctx;
} sh_items;
/* Non-zero if items (NULL: all) include item j. */
static inline int sh_items_own(const sh_items *items, long item)
{
    return !items || !items->owns || items->owns(items->ctx, item);
}

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_CORE_H */
