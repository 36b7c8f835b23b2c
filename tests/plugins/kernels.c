/* kernels.c — example plug-in kernels (shlab/kernel.h) for `shlab verify
 * --plugin` and `shlab bench --plugin`: a correct rotation kernel in every
 * ABI, one kernel with each mistake `verify --simulate` knows, and kernels
 * that misbehave (crash, hang, write out of bounds, decline orders).
 * Built by `make check` as build/tests/plugins/kernels.so; checked by
 * tests/cli/test_plugins.sh.
 *
 * Self-contained on purpose (no libshlab): the rotation is Ivanic and
 * Ruedenberg's recurrence for real SH rotation matrices (J. Phys. Chem.
 * 100, 6342 (1996), with the corrections of J. Phys. Chem. A 102, 9099
 * (1998)), written here from the paper, independently of shlab's own
 * rot_ivanic.c.  It works in the basis without the Condon-Shortley phase
 * (nocs: y_1^{-1}, y_1^0, y_1^1 ∝ y, z, x); the cs kernels negate odd m on
 * the way in and out. */
#include "shlab/kernel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAXO 64 /* largest order these kernels rotate */

/* R^l as a (2l+1)² block, index [(m+l)(2l+1) + (m'+l)]. */
typedef struct {
    double *b[MAXO];
} blocks;

static double at(const blocks *B, int l, int m, int mp) { return B->b[l][(m + l) * (2 * l + 1) + (mp + l)]; }

/* The paper's P function, built from R^1 and R^{l-1}. */
static double P(const blocks *B, int i, int l, int a, int b)
{
    const double r1 = at(B, 1, i, 1), rm1 = at(B, 1, i, -1), r0 = at(B, 1, i, 0);
    if (b == l) return r1 * at(B, l - 1, a, l - 1) - rm1 * at(B, l - 1, a, -l + 1);
    if (b == -l) return r1 * at(B, l - 1, a, -l + 1) + rm1 * at(B, l - 1, a, l - 1);
    return r0 * at(B, l - 1, a, b);
}

/* Blocks 0..order-1 of the rotation R (row-major), nocs basis. */
static int build(int order, const double R[9], blocks *B)
{
    memset(B, 0, sizeof *B);
    for (int l = 0; l < order; l++) {
        B->b[l] = malloc((size_t)(2 * l + 1) * (2 * l + 1) * sizeof(double));
        if (!B->b[l]) return -1;
    }
    B->b[0][0] = 1;
    if (order < 2) return 0;
    /* band 1: m = -1, 0, 1 ↔ y, z, x, so R^1 = P R Pᵀ with that permutation */
    static const int ax[3] = {1, 2, 0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) B->b[1][i * 3 + j] = R[ax[i] * 3 + ax[j]];
    for (int l = 2; l < order; l++)
        for (int m = -l; m <= l; m++)
            for (int mp = -l; mp <= l; mp++) {
                const int am = abs(m), d0 = m == 0;
                const double den = abs(mp) < l ? (double)(l + mp) * (l - mp) : (double)(2 * l) * (2 * l - 1);
                const double u = sqrt((double)(l + m) * (l - m) / den);
                const double v = 0.5 * sqrt((1.0 + d0) * (l + am - 1) * (l + am) / den) * (1 - 2 * d0);
                const double w = -0.5 * sqrt((double)(l - am - 1) * (l - am) / den) * (1 - d0);
                double U = am < l ? P(B, 0, l, m, mp) : 0, V, W = 0; /* u = 0 at |m| = l */
                if (m == 0) {
                    V = P(B, 1, l, 1, mp) + P(B, -1, l, -1, mp);
                } else if (m > 0) {
                    V = P(B, 1, l, m - 1, mp) * sqrt(1.0 + (m == 1)) - P(B, -1, l, -m + 1, mp) * (1 - (m == 1));
                    if (l - am - 1 >= 0 && am + 1 <= l - 1) W = P(B, 1, l, m + 1, mp) + P(B, -1, l, -m - 1, mp);
                } else {
                    V = P(B, 1, l, m + 1, mp) * (1 - (m == -1)) + P(B, -1, l, -m - 1, mp) * sqrt(1.0 + (m == -1));
                    if (am + 1 <= l - 1) W = P(B, 1, l, m - 1, mp) - P(B, -1, l, -m + 1, mp);
                }
                B->b[l][(m + l) * (2 * l + 1) + (mp + l)] = u * U + v * V + w * W;
            }
    return 0;
}

static void release(int order, blocks *B)
{
    for (int l = 0; l < order; l++) free(B->b[l]);
}

/* out = R_sh(R) in, in the convention cs (odd m negated around the nocs
 * rotation) or nocs. */
static int rotate(int order, const double R[9], int cs, const double *in, double *out)
{
    if (order < 1 || order > MAXO) return SHLAB_KERNEL_UNSUPPORTED;
    blocks B;
    if (build(order, R, &B)) return 2;
    for (int l = 0; l < order; l++)
        for (int m = -l; m <= l; m++) {
            double s = 0;
            for (int mp = -l; mp <= l; mp++) {
                const double x = in[l * l + l + mp] * (cs && (mp & 1) ? -1 : 1);
                s += at(&B, l, m, mp) * x;
            }
            out[l * l + l + m] = s * (cs && (m & 1) ? -1 : 1);
        }
    release(order, &B);
    return SHLAB_KERNEL_OK;
}

/* R = Rz(a) Ry(b) Rz(g), row-major. */
static void euler_matrix(double a, double b, double g, double R[9])
{
    const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cg = cos(g), sg = sin(g);
    const double M[9] = {ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb,
                         sa * cb * cg + ca * sg, -sa * cb * sg + ca * cg, sa * sb,
                         -sb * cg,               sb * sg,                 cb};
    memcpy(R, M, sizeof M);
}

/* The matrix of the unit quaternion (w, x, y, z). */
static void quat_matrix(const double q[4], double R[9])
{
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double M[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                         2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                         2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    memcpy(R, M, sizeof M);
}

/* ---- correct kernels, one per ABI ---------------------------------------- */

int rot_matrix_d(int order, const double R[9], const double *in, double *out) { return rotate(order, R, 1, in, out); }
int rot_matrix_d_nocs(int order, const double R[9], const double *in, double *out)
{
    return rotate(order, R, 0, in, out);
}

int rot_matrix_f(int order, const float Rf[9], const float *in, float *out)
{
    if (order < 1 || order > MAXO) return SHLAB_KERNEL_UNSUPPORTED;
    const int n = order * order;
    double R[9], *x = malloc(2 * (size_t)n * sizeof *x);
    if (!x) return 2;
    for (int i = 0; i < 9; i++) R[i] = Rf[i];
    for (int i = 0; i < n; i++) x[i] = in[i];
    const int rc = rotate(order, R, 1, x, x + n);
    for (int i = 0; i < n; i++) out[i] = (float)x[n + i];
    free(x);
    return rc;
}

int rot_quat_d(int order, const double q[4], const double *in, double *out)
{
    double R[9];
    quat_matrix(q, R);
    return rotate(order, R, 1, in, out);
}

int rot_euler_d(int order, double a, double b, double g, const double *in, double *out)
{
    double R[9];
    euler_matrix(a, b, g, R);
    return rotate(order, R, 1, in, out);
}

int rot_matrix_batch_d(int order, int count, const double *R, const double *in, double *out)
{
    const int n = order * order;
    for (int k = 0; k < count; k++) {
        const int rc = rotate(order, R + 9 * k, 1, in + (size_t)k * n, out + (size_t)k * n);
        if (rc) return rc;
    }
    return SHLAB_KERNEL_OK;
}

/* ---- one kernel per mistake `verify --simulate` knows -------------------- */

/* the inverse rotation: the transposed matrix (matrix-d) */
int mistake_inverse(int order, const double R[9], const double *in, double *out)
{
    const double T[9] = {R[0], R[3], R[6], R[1], R[4], R[7], R[2], R[5], R[8]};
    return rotate(order, T, 1, in, out);
}
/* the other phase convention: a nocs kernel given cs data (matrix-d) */
int mistake_convention(int order, const double R[9], const double *in, double *out)
{
    return rotate(order, R, 0, in, out);
}
/* α and γ swapped (euler-d) */
int mistake_swap(int order, double a, double b, double g, const double *in, double *out)
{
    return rot_euler_d(order, g, b, a, in, out);
}
/* β negated (euler-d): the same outputs as the other convention */
int mistake_beta(int order, double a, double b, double g, const double *in, double *out)
{
    return rot_euler_d(order, a, -b, g, in, out);
}
/* degrees taken as radians: the kernel converts radians it thinks are degrees (euler-d) */
int mistake_deg2rad(int order, double a, double b, double g, const double *in, double *out)
{
    const double k = M_PI / 180;
    return rot_euler_d(order, a * k, b * k, g * k, in, out);
}
/* radians taken as degrees (euler-d) */
int mistake_rad2deg(int order, double a, double b, double g, const double *in, double *out)
{
    const double k = 180 / M_PI;
    return rot_euler_d(order, a * k, b * k, g * k, in, out);
}

/* v with m reversed within each band */
static void reverse(int order, const double *v, double *r)
{
    for (int l = 0; l < order; l++)
        for (int m = -l; m <= l; m++) r[l * l + l + m] = v[l * l + l - m];
}
/* m descending within each band: input (which), output or both (matrix-d) */
static int mdesc(int order, const double R[9], const double *in, double *out, int in_rev, int out_rev)
{
    if (order < 1 || order > MAXO) return SHLAB_KERNEL_UNSUPPORTED;
    const int n = order * order;
    double *t = malloc(2 * (size_t)n * sizeof *t);
    if (!t) return 2;
    if (in_rev) reverse(order, in, t);
    else memcpy(t, in, (size_t)n * sizeof *t);
    const int rc = rotate(order, R, 1, t, t + n);
    if (out_rev) reverse(order, t + n, out);
    else memcpy(out, t + n, (size_t)n * sizeof *out);
    free(t);
    return rc;
}
int mistake_mdesc(int order, const double R[9], const double *in, double *out) { return mdesc(order, R, in, out, 1, 1); }
int mistake_mdesc_out(int order, const double R[9], const double *in, double *out)
{
    return mdesc(order, R, in, out, 0, 1);
}
int mistake_mdesc_in(int order, const double R[9], const double *in, double *out)
{
    return mdesc(order, R, in, out, 1, 0);
}
/* float precision only, behind a double interface (matrix-d) */
int mistake_float(int order, const double R[9], const double *in, double *out)
{
    const int rc = rotate(order, R, 1, in, out);
    for (int i = 0; i < order * order; i++) out[i] = (float)out[i];
    return rc;
}

/* ---- kernels that misbehave ------------------------------------------- */

/* orders 1..6 only, as DirectXMath's XMSHRotate */
int orders_1_6(int order, const double R[9], const double *in, double *out)
{
    return order > 6 ? SHLAB_KERNEL_UNSUPPORTED : rotate(order, R, 1, in, out);
}
/* a failure code at order 5 */
int fails_order_5(int order, const double R[9], const double *in, double *out)
{
    return order == 5 ? 7 : rotate(order, R, 1, in, out);
}
/* a null dereference at order 4 */
int crash_order_4(int order, const double R[9], const double *in, double *out)
{
    if (order == 4) {
        volatile double *p = NULL;
        *p = 1;
    }
    return rotate(order, R, 1, in, out);
}
/* never returns at order 3 */
int hang_order_3(int order, const double R[9], const double *in, double *out)
{
    volatile unsigned long spin = 0;
    while (order == 3) spin++;
    return rotate(order, R, 1, in, out);
}
/* writes one value past its output */
int writes_past_output(int order, const double R[9], const double *in, double *out)
{
    const int rc = rotate(order, R, 1, in, out);
    out[order * order] = 0;
    return rc;
}
/* writes one value before its output */
int writes_before_output(int order, const double R[9], const double *in, double *out)
{
    const int rc = rotate(order, R, 1, in, out);
    out[-1] = 0;
    return rc;
}
/* writes to its input (scratch in the caller's buffer) */
int writes_input(int order, const double R[9], const double *in, double *out)
{
    volatile double *scratch = (volatile double *)in;
    scratch[0] = in[0];
    return rotate(order, R, 1, in, out);
}
/* reads one value past its input */
int reads_past_input(int order, const double R[9], const double *in, double *out)
{
    volatile double x = in[order * order];
    (void)x;
    return rotate(order, R, 1, in, out);
}
/* leaves the last output unwritten */
int skips_last_output(int order, const double R[9], const double *in, double *out)
{
    const int n = order * order;
    double *t = malloc((size_t)n * sizeof *t);
    if (!t) return 2;
    const int rc = rotate(order, R, 1, in, t);
    memcpy(out, t, (size_t)(n - 1) * sizeof *out);
    free(t);
    return rc;
}
