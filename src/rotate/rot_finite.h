/* rot_finite.h — is a 3×3 matrix (9 values) finite?  The check every
 * rotation given as a matrix passes once, on the per-rotation path.
 *
 * x − x is +0 for every finite x (round to nearest: an exact zero is +0)
 * and NaN for ±∞ and NaN; a sum of +0s is +0, and a NaN stays NaN.  So
 *   Σ (R[i] − R[i]) has all bits zero  ⇔  every R[i] is finite.
 * The first eight entries are summed in 16-byte vectors (GCC/Clang vector
 * extension; SSE2 on x86-64: two or four subtractions, one or three
 * additions), R[8] − R[8] added to the first lane, the bits read as two
 * 64-bit words: branch-free, no reduction loop (the omp-simd max loop it replaces ran
 * ~30 instructions for nine values).  -ffast-math would fold x − x to 0:
 * the library is not built with it (the Makefile's -std=c11 -O2).
 */
#ifndef SHLAB_ROT_FINITE_H
#define SHLAB_ROT_FINITE_H

#include <stdint.h>
#include <string.h>

#define SH__FINITE9(NAME, T)                                                                       \
    static inline __attribute__((always_inline)) int NAME(const T *R)                              \
    {                                                                                              \
        typedef T v_t __attribute__((vector_size(16)));                                            \
        typedef uint64_t u_t __attribute__((vector_size(16)));                                     \
        enum { N = 16 / sizeof(T) }; /* lanes: 4 floats, 2 doubles */                              \
        v_t acc, a;                                                                                \
        memcpy(&acc, R, 16);                                                                       \
        acc -= acc;                                                                                \
        for (int i = N; i < 8; i += N) {                                                           \
            memcpy(&a, R + i, 16);                                                                 \
            acc += a - a;                                                                          \
        }                                                                                          \
        acc[0] += R[8] - R[8];                                                                     \
        const u_t z = (u_t)acc;                                                                    \
        return (z[0] | z[1]) == 0;                                                                 \
    }
SH__FINITE9(sh__finite9_d, double)
SH__FINITE9(sh__finite9_f, float)
#undef SH__FINITE9

#endif
