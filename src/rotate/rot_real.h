/* rot_real.h — precision-generic rotation kernels.
 *
 * Every file named src/rot_*.c is a rotation kernel written once in terms of
 * `sh_real` and compiled twice by the Makefile: as double (rot_x.o, function
 * names suffixed _d) and with -DSH_REAL_FLOAT as float (rot_x_f.o, suffix _f).
 * A float kernel does its arithmetic in float, so the stability experiment
 * measures what a single-precision implementation (a shader) really gets.
 */
#ifndef SHLAB_ROT_REAL_H
#define SHLAB_ROT_REAL_H

#include <math.h>

/* SH_SIMD_SHORT: `#pragma omp simd` for the kernels' short loops (a few to
 * a few tens of iterations: one row of a band), 16 bytes of lanes
 * (simdlen; GCC takes it as the vectorisation factor): with -march=native
 * GCC otherwise vectorises them 32 or 64 bytes wide, and most iterations of
 * such short loops then run in the remainder — measured 1.1–1.2× slower
 * (docs/rotation.md "Rotation speed", the -O3 -march=native note).  The loops are
 * vectorised at -O2 too (-fopenmp-simd; no OpenMP runtime). */
#define SH_PRAGMA_(x) _Pragma(#x)
#define SH_PRAGMA(x) SH_PRAGMA_(x)
#define SH_SIMD_SHORT SH_PRAGMA(omp simd simdlen(SH_SIMD_LANES16))

#ifdef SH_REAL_FLOAT
#define SH_SIMD_LANES16 4
typedef float sh_real;
#define SH_R(name) name##_f
#define SH_SQRT sqrtf
#define SH_SIN sinf
#define SH_COS cosf
#define SH_FABS fabsf
#define SH_REAL_EPS 1.1920929e-07f
#else
#define SH_SIMD_LANES16 2
typedef double sh_real;
#define SH_R(name) name##_d
#define SH_SQRT sqrt
#define SH_SIN sin
#define SH_COS cos
#define SH_FABS fabs
#define SH_REAL_EPS 2.220446049250313e-16
#endif

#endif
