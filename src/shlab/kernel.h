/* shlab/kernel.h — the C ABI of a rotation kernel under test: a plug-in.
 *
 * A plug-in is a shared library that exports one function of a type below.
 * `shlab verify --plugin LIB.so:SYMBOL --abi NAME` runs every case of a
 * golden fixture through it, and `shlab bench --plugin LIB.so:SYMBOL --abi
 * NAME` times it beside shlab's methods (docs/check-your-kernel.md).  This
 * header is self-contained: a plug-in needs neither libshlab nor any other
 * shlab header, only `cc -shared -fPIC`.
 *
 * The function runs in a child process with a time limit; its output
 * buffer ends at a guard page and its input is read-only, so a kernel that
 * crashes, hangs or writes out of bounds is reported as such.
 *
 * Conventions (docs/CONVENTIONS.md):
 *  - coefficients: real orthonormal SH, flat index i = l(l+1)+m (m ascending
 *    within a band), order n = bands 0..n-1 = n² coefficients; the phase
 *    convention is the one given to shlab (--convention cs, the default:
 *    Condon-Shortley phase; nocs: odd-m functions negated);
 *  - the rotation acts on functions: g(s) = f(R⁻¹ s), and the kernel maps
 *    the coefficients of f (`in`) to those of g (`out`);
 *  - matrix: R row-major, R[3*i + j] = R_ij, a proper rotation;
 *  - quaternion: q = (w, x, y, z) of the same active rotation, unit, w ≥ 0;
 *  - Euler: ZYZ active, R = Rz(alpha) Ry(beta) Rz(gamma), radians.
 *  - in and out never overlap.
 *
 * Return SHLAB_KERNEL_OK, or SHLAB_KERNEL_UNSUPPORTED when the kernel does
 * not handle this order (the case is reported as not run: a kernel for
 * orders 1..6 is verified on those), or any other value for a failure (the
 * case fails).  The ABI names (--abi) are given beside each type. */
#ifndef SHLAB_KERNEL_H
#define SHLAB_KERNEL_H

#ifdef __cplusplus
extern "C" {
#endif

#define SHLAB_KERNEL_ABI_VERSION 1
#define SHLAB_KERNEL_OK 0
#define SHLAB_KERNEL_UNSUPPORTED 1

/* --abi matrix-d, matrix-f */
typedef int shlab_kernel_matrix_d(int order, const double R[9], const double *in, double *out);
typedef int shlab_kernel_matrix_f(int order, const float R[9], const float *in, float *out);
/* --abi quat-d, quat-f */
typedef int shlab_kernel_quat_d(int order, const double q[4], const double *in, double *out);
typedef int shlab_kernel_quat_f(int order, const float q[4], const float *in, float *out);
/* --abi euler-d, euler-f */
typedef int shlab_kernel_euler_d(int order, double alpha, double beta, double gamma, const double *in,
                                 double *out);
typedef int shlab_kernel_euler_f(int order, float alpha, float beta, float gamma, const float *in, float *out);
/* --abi matrix-batch-d, matrix-batch-f: count rotations at once; rotation k
 * is R + 9k, its input in + k·order², its output out + k·order². */
typedef int shlab_kernel_matrix_batch_d(int order, int count, const double *R, const double *in, double *out);
typedef int shlab_kernel_matrix_batch_f(int order, int count, const float *R, const float *in, float *out);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_KERNEL_H */
