/* rot_simd.h — the small value layer under the unrolled rotation kernels
 * (rot_fast.c and the generated rot_unrolled_gen.h).
 *
 * The kernels are written once for a value type shk_t.  rot_fast.c is
 * compiled once per precision (rot_real.h: SH_REAL_FLOAT) and once per
 * variant (the Makefile's FAST_VARIANTS, FFTW's per-ISA objects):
 *   SHK_VBYTES unset   shk_t = sh_real: one rotation, one vector per call,
 *                      contiguous (the lane strides are ignored);
 *   SHK_VBYTES = 16, 32, 64   shk_t = a GCC vector of SHK_VBYTES bytes (SSE2,
 *                      AVX2, AVX-512): each lane an independent rotation and
 *                      vector, the arrays laid out as structure of arrays
 *                      (element i of lane k at p[i·K + k]).
 * The ISA comes from the compiler flags of that object (-mavx2 -mfma ...);
 * SHK_VARIANT names the object's exported symbols (SHK_SYM).
 *
 * Operations: + − * / and unary − on shk_t and with a real scalar (GCC
 * broadcasts it), SHK_C(x) a literal, SHK_SPLAT(x) a value from a real,
 * SHK_LD/SHK_ST a lane-strided load/store, SHK_SQRT, comparisons giving a
 * mask (shk_m) and SHK_SEL(mask, a, b) = mask ? a : b lane by lane.
 *
 * shk_d is the same lanes in double (= shk_t in a double build), for the
 * few operations per rotation that a float kernel does in double (the
 * rotation's cos/sin from its matrix, rot_fast.c): SHK_DLD loads sh_real
 * lanes as double, SHK_DST stores double lanes rounded to sh_real, with
 * SHK_DSPLAT, SHK_DSQRT, SHK_DSEL (mask shk_dm).
 */
#ifndef SHLAB_ROT_SIMD_H
#define SHLAB_ROT_SIMD_H

#include "rotate/rot_real.h"

#include <stddef.h>
#include <string.h>

#ifndef SHK_VARIANT
#define SHK_VARIANT base /* the plain compilation of rot_fast.c (one lane, default flags) */
#define SHK_IS_BASE 1
#endif
#define SHK_CAT3_(a, b, c) a##_##b##_##c
#define SHK_CAT3(a, b, c) SHK_CAT3_(a, b, c)
#ifdef SH_REAL_FLOAT
#define SHK_SYM(name) SHK_CAT3(name, SHK_VARIANT, f) /* exported: name_<variant>_f */
#else
#define SHK_SYM(name) SHK_CAT3(name, SHK_VARIANT, d)
#endif
#define SHK_C(x) ((sh_real)(x))

#ifndef SHK_VBYTES
/* ---- one lane: plain reals ---------------------------------------------- */
#define SHK_LANES 1
typedef sh_real shk_t;
typedef int shk_m;
/* one lane: the arrays are contiguous (the drivers gather a strided lane) */
#define SHK_LD(p, i, K) ((p)[i])
#define SHK_ST(p, i, K, v) ((p)[i] = (v))
#define SHK_SPLAT(x) ((sh_real)(x))
#define SHK_SQRT(x) SH_SQRT(x)
#define SHK_SEL(m, a, b) ((m) ? (a) : (b))
typedef double shk_d;
typedef int shk_dm;
#define SHK_DLD(p, i, K) ((double)(p)[i])
#define SHK_DST(p, i, K, v) ((p)[i] = (sh_real)(v))
#define SHK_DSPLAT(x) ((double)(x))
#define SHK_DSQRT(x) sqrt(x)
#define SHK_DSEL(m, a, b) ((m) ? (a) : (b))
#else
/* ---- SHK_VBYTES bytes of lanes ------------------------------------------ */
#include <immintrin.h>
#ifdef SH_REAL_FLOAT
#define SHK_LANES (SHK_VBYTES / 4)
#else
#define SHK_LANES (SHK_VBYTES / 8)
#endif
typedef sh_real shk_t __attribute__((vector_size(SHK_VBYTES)));
#ifdef SH_REAL_FLOAT
typedef int shk_m __attribute__((vector_size(SHK_VBYTES)));
#else
typedef long long shk_m __attribute__((vector_size(SHK_VBYTES)));
#endif
static inline shk_t shk_ld(const sh_real *p)
{
    shk_t v;
    memcpy(&v, p, sizeof v); /* unaligned load */
    return v;
}
static inline void shk_st(sh_real *p, shk_t v) { memcpy(p, &v, sizeof v); }
#define SHK_LD(p, i, K) shk_ld((p) + (size_t)(i) * (K))
#define SHK_ST(p, i, K, v) shk_st((p) + (size_t)(i) * (K), (v))
#define SHK_SPLAT(x) ((shk_t){0} + (sh_real)(x))
static inline shk_t shk_sqrt(shk_t x)
{
#if SHK_VBYTES == 16 && defined(SH_REAL_FLOAT)
    return (shk_t)_mm_sqrt_ps((__m128)x);
#elif SHK_VBYTES == 16
    return (shk_t)_mm_sqrt_pd((__m128d)x);
#elif SHK_VBYTES == 32 && defined(SH_REAL_FLOAT)
    return (shk_t)_mm256_sqrt_ps((__m256)x);
#elif SHK_VBYTES == 32
    return (shk_t)_mm256_sqrt_pd((__m256d)x);
#elif SHK_VBYTES == 64 && defined(SH_REAL_FLOAT)
    return (shk_t)_mm512_sqrt_ps((__m512)x);
#elif SHK_VBYTES == 64
    return (shk_t)_mm512_sqrt_pd((__m512d)x);
#else
#error "SHK_VBYTES must be 16, 32 or 64"
#endif
}
#define SHK_SQRT(x) shk_sqrt(x)
static inline shk_t shk_sel(shk_m m, shk_t a, shk_t b)
{
    return (shk_t)((m & (shk_m)a) | (~m & (shk_m)b));
}
#define SHK_SEL(m, a, b) shk_sel((m), (a), (b))

/* the lanes in double: in a float build twice the bytes, split in two native
 * double vectors for the square root */
typedef double shk_dn __attribute__((vector_size(SHK_VBYTES))); /* native */
typedef long long shk_dnm __attribute__((vector_size(SHK_VBYTES)));
static inline shk_dn shk_sqrt_dn(shk_dn x)
{
#if SHK_VBYTES == 16
    return (shk_dn)_mm_sqrt_pd((__m128d)x);
#elif SHK_VBYTES == 32
    return (shk_dn)_mm256_sqrt_pd((__m256d)x);
#else
    return (shk_dn)_mm512_sqrt_pd((__m512d)x);
#endif
}
#ifdef SH_REAL_FLOAT
typedef double shk_d __attribute__((vector_size(2 * SHK_VBYTES)));
typedef long long shk_dm __attribute__((vector_size(2 * SHK_VBYTES)));
static inline shk_d shk_dsqrt(shk_d x)
{
    shk_dn h[2];
    memcpy(h, &x, sizeof x);
    h[0] = shk_sqrt_dn(h[0]);
    h[1] = shk_sqrt_dn(h[1]);
    memcpy(&x, h, sizeof x);
    return x;
}
#define SHK_DLD(p, i, K) __builtin_convertvector(SHK_LD(p, i, K), shk_d)
#define SHK_DST(p, i, K, v) SHK_ST(p, i, K, __builtin_convertvector((v), shk_t))
#else
typedef shk_dn shk_d;
typedef shk_dnm shk_dm;
#define shk_dsqrt shk_sqrt_dn
#define SHK_DLD(p, i, K) SHK_LD(p, i, K)
#define SHK_DST(p, i, K, v) SHK_ST(p, i, K, v)
#endif
#define SHK_DSPLAT(x) ((shk_d){0} + (double)(x))
#define SHK_DSQRT(x) shk_dsqrt(x)
static inline shk_d shk_dsel(shk_dm m, shk_d a, shk_d b)
{
    return (shk_d)((m & (shk_dm)a) | (~m & (shk_dm)b));
}
#define SHK_DSEL(m, a, b) shk_dsel((m), (a), (b))
#endif

#endif
