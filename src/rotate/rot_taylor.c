/* rot_taylor.c — the approximate methods `taylor1`, `taylor1.5`, `taylor2`:
 * R_sh ≈ Z(α) · T(β) · Z(γ) with T(β) a Taylor polynomial of R_Y(β) at β = 0,
 * applied sparsely like the paper's shRotYdiff15 (precision-generic, see
 * rot_real.h).
 *
 * References
 *  [1] J. Křivánek, J. Konttinen, S. Pattanaik, K. Bouatouch, "Fast
 *      Approximation to Spherical Harmonic Rotation", IRISA PI 1728 (2005),
 *      Sec. 3 (the expansion and shRotYdiff15), Sec. 3.1 (cost 9n² − 4n),
 *      Appendix C (z rotation).
 *  [2] docs/CONVENTIONS.md "Taylor-approximated rotation":
 *        taylor1:   T = I + βJ
 *        taylor1.5: T = I + βJ + (β²/2)·diag(J²)
 *        taylor2:   T = I + βJ + (β²/2)·J²
 *  [3] rotation_deriv.c: the closed form of J (sh_rot_deriv_J_subdiag); J is
 *      checked there against Appendix A's recursion and finite differences.
 *
 * Structure (band l, positions j = m + l).  J couples only m and m ± 1 and is
 * antisymmetric: with s_j = J[m][m−1] (s_0 = 0, and s at m = 0 is J[0][−1] =
 * 0), row j of J is (−s_{j+1} to the right, s_j to the left).  J² couples m
 * and m, m ± 2 and is symmetric: J²_jj = −s_j² − s_{j+1}², q_j = J²[j][j−2] =
 * s_j s_{j−1}.  Per band, with x the band's coefficients after Z(γ) and
 * bb = β²/2 ([1] shRotYdiff15, eq. in Sec. 3):
 *   y_j = x_j (1 + bb·J²_jj) + β (s_j x_{j−1} − s_{j+1} x_{j+1})             (1.5)
 *   y_j = x_j + β (s_j x_{j−1} − s_{j+1} x_{j+1})                            (1)
 *   y_j = (1.5) + bb (q_j x_{j−2} + q_{j+2} x_{j+2})                         (2)
 * The band is copied into a buffer with two zeros on each side and the
 * tables carry zeros at the band ends, so one branch-free loop covers every
 * position (the products with those zeros are executed, as in [1]'s loop).
 *
 * Tables (built once per order in tables_new from the closed form [3]):
 * band l stores w + 2 values (w = 2l + 1) of each of s, J²_jj, q from
 * tab_off(l) = (l+1)² − 1.  No matrix is built in apply.
 *
 * Cost of one apply, counted in the loops: per band l ≥ 1, two z rotations
 * (4l each) and c·(2l+1) for the y step, c = 3 (taylor1), 5 (taylor1.5),
 * 8 (taylor2); band 0 is copied.  Taylor 1.5: 5(n²−1) + 4n(n−1) = 9n² − 4n − 5,
 * [1]'s 9n² − 4n less the five products of band 0.  The multiple angles of
 * α and γ, 2·2(n−2) for n ≥ 3 ([1] omits them), and bb = ½β² (2) depend on
 * the rotation only: the plan's set computes them once per rotation (counted
 * in the set's multiplications), not once per vector.  Z(γ) is fused into
 * the copy of the band into the padded buffer.  (Taylor 2 could be done
 * as I + βJ(I + (β/2)J) with 6 per coefficient; the brief and [1] store the
 * band of J², so that is what is measured.)
 *
 * Accuracy (the approximation, not rounding): exact at β = 0; the error of
 * taylor1 and taylor1.5 is O(β²), of taylor2 O(β³) — measured by
 * `shlab taylor-error` and the taylor_error experiment.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

#include <stdlib.h>
#include <string.h>

SH__ROT_DECLARE_BLOCKS(taylor1);
SH__ROT_DECLARE_BLOCKS(taylor15);
SH__ROT_DECLARE_BLOCKS(taylor2);
SH__ROT_DECLARE_APPLY(taylor1);
SH__ROT_DECLARE_APPLY(taylor15);
SH__ROT_DECLARE_APPLY(taylor2);
SH__ROT_DECLARE_TABLES(taylor);
SH__ROT_DECLARE_SET_PAR(taylor1);
SH__ROT_DECLARE_SET_PAR(taylor15);
SH__ROT_DECLARE_SET_PAR(taylor2);

static inline size_t tab_off(int l) { return (size_t)(l + 1) * (size_t)(l + 1) - 1; }

typedef struct {
    int order;
    sh_real *s, *d, *q; /* J sub-diagonal, diag(J²), J²[j][j−2]; tab_off(order) each */
} taylor_tables;

int SH_R(sh__rot_taylor_tables_new)(int order, void **tables)
{
    *tables = NULL;
    taylor_tables *T = malloc(sizeof *T);
    const size_t nt = tab_off(order);
    double *sd = malloc((2 * (size_t)order + 2) * sizeof *sd);
    if (T) {
        T->order = order;
        T->s = calloc(3 * nt, sizeof *T->s);
    }
    if (!T || !T->s || !sd) {
        if (T) free(T->s);
        free(T), free(sd);
        return sh_error(SH_ENOMEM, "taylor: out of memory (tables, order %d)", order);
    }
    T->d = T->s + nt;
    T->q = T->d + nt;
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        sh_rot_deriv_J_subdiag(l, sd); /* s_0 .. s_{w−1} (CS), s_0 = 0 */
        sd[w] = 0;
        sh_real *s = T->s + tab_off(l), *d = T->d + tab_off(l), *q = T->q + tab_off(l);
        for (int j = 0; j <= w; j++) s[j] = (sh_real)sd[j];
        for (int j = 0; j < w; j++) d[j] = (sh_real)(-sd[j] * sd[j] - sd[j + 1] * sd[j + 1]);
        for (int j = 2; j < w; j++) q[j] = (sh_real)(sd[j] * sd[j - 1]);
    }
    free(sd);
    *tables = T;
    return SH_OK;
}

/* y = T(β) x for band l; x has two zeros before x[0] and after x[w−1]. */
static inline __attribute__((always_inline)) void SH_R(ty_band)(int kind, int l,
                                                                const taylor_tables *T,
                                                                sh_real beta, sh_real bb,
                                                                const sh_real *x, sh_real *y)
{
    const int w = 2 * l + 1;
    const sh_real *s = T->s + tab_off(l), *d = T->d + tab_off(l), *q = T->q + tab_off(l);
    if (kind == 1) {
#pragma GCC unroll 32
        for (int j = 0; j < w; j++) y[j] = x[j] + beta * (s[j] * x[j - 1] - s[j + 1] * x[j + 1]);
    } else if (kind == 15) {
#pragma GCC unroll 32
        for (int j = 0; j < w; j++)
            y[j] = x[j] * (1 + bb * d[j]) + beta * (s[j] * x[j - 1] - s[j + 1] * x[j + 1]);
    } else {
#pragma GCC unroll 32
        for (int j = 0; j < w; j++)
            y[j] = x[j] * (1 + bb * d[j]) + beta * (s[j] * x[j - 1] - s[j + 1] * x[j + 1]) +
                   bb * (q[j] * x[j - 2] + q[j + 2] * x[j + 2]);
    }
}

static uint64_t ty_band_mults(int kind, int l)
{
    const uint64_t c = kind == 1 ? 3 : kind == 15 ? 5 : 8;
    return l == 0 ? 0 : 8u * (uint64_t)l + c * (uint64_t)(2 * l + 1);
}

/* One band through Z(γ), T(β), Z(α): in (w values) → out; pad has w + 4.
 * Z(γ) is applied while copying into the padded buffer, Z(α) in place:
 *   x_{+m} = cos(mγ) c_m − sin(mγ) c_{−m},  x_{−m} = sin(mγ) c_m + cos(mγ) c_{−m}.
 * Written once for any kind and l; ty_pipeline_K below instantiates it for
 * each kind and each small l as constants (the same operations in the same
 * order, the short loops laid out straight — as for zxzxz). */
static inline __attribute__((always_inline)) void SH_R(ty_pipeline_l)(
    int kind, int l, const taylor_tables *T, const sh_real *csa, const sh_real *csg, sh_real beta,
    sh_real bb, const sh_real *in, sh_real *out, sh_real *pad)
{
    const int w = 2 * l + 1;
    if (l == 0) {
        out[0] = in[0];
        return;
    }
    sh_real *x = pad + 2;
    pad[0] = pad[1] = x[w] = x[w + 1] = 0;
    x[l] = in[l];
#pragma GCC unroll 16
    for (int m = 1; m <= l; m++) { /* Z(γ) */
        const sh_real cm = csg[2 * m], sm = csg[2 * m + 1], a = in[l + m], b = in[l - m];
        x[l + m] = cm * a - sm * b;
        x[l - m] = sm * a + cm * b;
    }
    SH_R(ty_band)(kind, l, T, beta, bb, x, out);
#pragma GCC unroll 16
    for (int m = 1; m <= l; m++) { /* Z(α) */
        const sh_real cm = csa[2 * m], sm = csa[2 * m + 1], a = out[l + m], b = out[l - m];
        out[l + m] = cm * a - sm * b;
        out[l - m] = sm * a + cm * b;
    }
}
#define TY_SPECIAL 12 /* bands 0..11 (orders ≤ 12) get their own instance */
#define TY_PIPELINE(K)                                                                             \
    static void SH_R(ty_pipeline_##K)(int l, const taylor_tables *T, const sh_real *csa,          \
                                      const sh_real *csg, sh_real beta, sh_real bb,                \
                                      const sh_real *in, sh_real *out, sh_real *pad)               \
    {                                                                                              \
        switch (l) {                                                                               \
        case 0: SH_R(ty_pipeline_l)(K, 0, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 1: SH_R(ty_pipeline_l)(K, 1, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 2: SH_R(ty_pipeline_l)(K, 2, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 3: SH_R(ty_pipeline_l)(K, 3, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 4: SH_R(ty_pipeline_l)(K, 4, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 5: SH_R(ty_pipeline_l)(K, 5, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 6: SH_R(ty_pipeline_l)(K, 6, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 7: SH_R(ty_pipeline_l)(K, 7, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 8: SH_R(ty_pipeline_l)(K, 8, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 9: SH_R(ty_pipeline_l)(K, 9, T, csa, csg, beta, bb, in, out, pad); return;           \
        case 10: SH_R(ty_pipeline_l)(K, 10, T, csa, csg, beta, bb, in, out, pad); return;         \
        case 11: SH_R(ty_pipeline_l)(K, 11, T, csa, csg, beta, bb, in, out, pad); return;         \
        default: SH_R(ty_pipeline_l)(K, l, T, csa, csg, beta, bb, in, out, pad);                  \
        }                                                                                          \
    }
TY_PIPELINE(1)
TY_PIPELINE(15)
TY_PIPELINE(2)
typedef void (*ty_pipe_fn)(int, const taylor_tables *, const sh_real *, const sh_real *, sh_real,
                           sh_real, const sh_real *, sh_real *, sh_real *);
static ty_pipe_fn SH_R(ty_pipe_of)(int kind)
{
    return kind == 1 ? SH_R(ty_pipeline_1) : kind == 15 ? SH_R(ty_pipeline_15) : SH_R(ty_pipeline_2);
}

/* The per-rotation state (set): β, bb = ½β², then the multiple angles of α
 * and γ (2·order values each). */
typedef struct {
    sh_real beta, bb;
} ty_state_head;
static size_t ty_head(void) { return 2 * sizeof(double); } /* keeps the angles aligned */
static void SH_R(ty_state)(int order, const sh_rotation *rot, void *state, uint64_t *count)
{
    ty_state_head *h = state;
    sh_real *csa = (sh_real *)((char *)state + ty_head()), *csg = csa + 2 * order;
    h->beta = (sh_real)rot->beta;
    h->bb = (sh_real)0.5 * h->beta * h->beta;
    SH_R(sh__rot_multiple_angles)((sh_real)rot->alpha, order - 1, csa);
    SH_R(sh__rot_multiple_angles)((sh_real)rot->gamma, order - 1, csg);
    *count += 2 + (order > 2 ? 2u * 2u * (uint64_t)(order - 2) : 0); /* bb = ½β², angles */
}
/* the same from par (rot_internal.h: cos, sin of α and γ, and β) */
static void SH_R(ty_state_par)(int order, const sh_real *par, void *state, uint64_t *count)
{
    ty_state_head *h = state;
    sh_real *csa = (sh_real *)((char *)state + ty_head()), *csg = csa + 2 * order;
    h->beta = par[6];
    h->bb = (sh_real)0.5 * h->beta * h->beta;
    SH_R(sh__rot_multiple_angles_cs)(par[0], par[1], order - 1, csa);
    SH_R(sh__rot_multiple_angles_cs)(par[4], par[5], order - 1, csg);
    *count += 2 + (order > 2 ? 2u * 2u * (uint64_t)(order - 2) : 0); /* bb = ½β², angles */
}

/* work: pad (2·order + 3) */
static void SH_R(ty_apply)(int kind, int order, const void *tables, const void *state,
                           const sh_real *in, sh_real *out, void *work, uint64_t *mults)
{
    const taylor_tables *T = tables;
    const ty_state_head *h = state;
    const sh_real *csa = (const sh_real *)((const char *)state + ty_head()), *csg = csa + 2 * order;
    sh_real *pad = work;
    const ty_pipe_fn pipe = SH_R(ty_pipe_of)(kind);
    uint64_t count = 0;
    for (int l = 0; l < order; l++) {
        pipe(l, T, csa, csg, h->beta, h->bb, in + (size_t)l * l, out + (size_t)l * l, pad);
        count += ty_band_mults(kind, l);
    }
    if (mults) *mults += count;
}

static int SH_R(ty_blocks)(int kind, int order, const sh_rotation *rot, const void *tables,
                           sh_real *blocks, void *work, uint64_t *mults)
{
    const taylor_tables *T = tables;
    if (!T || T->order < order) return sh_error(SH_EINVAL, "taylor: tables missing or too small");
    uint64_t count = 0;
    void *state = work;
    SH_R(ty_state)(order, rot, state, &count);
    const ty_state_head *h = state;
    const sh_real *csa = (const sh_real *)((const char *)state + ty_head()), *csg = csa + 2 * order;
    sh_real *pad = (sh_real *)csg + 2 * order, *e = pad + 2 * order + 3, *col = e + 2 * order;
    const ty_pipe_fn pipe = SH_R(ty_pipe_of)(kind);
    /* column j of band l's block = the band pipeline on the unit vector e_j */
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        sh_real *B = blocks + sh_rot_block_offset(l);
        for (int j = 0; j < w; j++) {
            for (int i = 0; i < w; i++) e[i] = 0;
            e[j] = 1;
            pipe(l, T, csa, csg, h->beta, h->bb, e, col, pad);
            for (int i = 0; i < w; i++) B[(size_t)i * w + j] = col[i];
            count += ty_band_mults(kind, l);
        }
    }
    if (mults) *mults += count;
    return SH_OK;
}

#define TY_KERNELS(name, kind)                                                                     \
    int SH_R(sh__rot_##name##_set)(int order, const sh_rotation *rot, const void *tables,          \
                                   void *state, uint64_t *mults)                                  \
    {                                                                                              \
        uint64_t count = 0;                                                                        \
        SH_R(ty_state)(order, rot, state, &count);                                                 \
        if (mults) *mults += count;                                                                \
        return SH_OK;                                                                              \
    }                                                                                              \
    int SH_R(sh__rot_##name##_set_par)(int order, const sh_real *par, const void *tables,          \
                                       void *state, uint64_t *mults)                              \
    {                                                                                              \
        uint64_t count = 0;                                                                        \
        SH_R(ty_state_par)(order, par, state, &count);                                             \
        if (mults) *mults += count;                                                                \
        return SH_OK;                                                                              \
    }                                                                                              \
    void SH_R(sh__rot_##name##_apply)(int order, const void *tables, const void *state,            \
                                      const sh_real *in, sh_real *out, void *work, uint64_t *mults) \
    {                                                                                              \
        SH_R(ty_apply)(kind, order, tables, state, in, out, work, mults);                          \
    }                                                                                              \
    int SH_R(sh__rot_##name##_blocks)(int order, const sh_rotation *rot, const void *tables,        \
                                      sh_real *blocks, void *work, uint64_t *mults)                \
    {                                                                                              \
        return SH_R(ty_blocks)(kind, order, rot, tables, blocks, work, mults);                     \
    }
TY_KERNELS(taylor1, 1)
TY_KERNELS(taylor15, 15)
TY_KERNELS(taylor2, 2)

#ifndef SH_REAL_FLOAT
static void ty_tables_free(void *tables)
{
    taylor_tables *T = tables;
    if (T) free(T->s);
    free(T);
}
static size_t ty_state_bytes(int order) { return 2 * sizeof(double) + 4 * (size_t)order * sizeof(double); }
static size_t ty_work(int order) /* blocks: state, pad, e, col; apply: pad */
{
    return ty_state_bytes(order) + (6 * (size_t)order + 3) * sizeof(double);
}
#define TY_OPS(var, label, kn)                                                                   \
    const sh__rot_ops var = {                                                                      \
        .name = label,                                                                             \
        .max_order = SH_TAYLOR_MAX_ORDER,                                                              \
        .approximate = 1,                                                                          \
        .tables_new_d = sh__rot_taylor_tables_new_d,                                               \
        .tables_new_f = sh__rot_taylor_tables_new_f,                                               \
        .tables_free = ty_tables_free,                                                             \
        .work_bytes = ty_work,                                                                     \
        .state_bytes = ty_state_bytes,                                                             \
        .set_d = sh__rot_##kn##_set_d,                                                           \
        .set_f = sh__rot_##kn##_set_f,                                                           \
        .set_par_d = sh__rot_##kn##_set_par_d,                                                   \
        .set_par_f = sh__rot_##kn##_set_par_f,                                                   \
        .blocks_d = sh__rot_##kn##_blocks_d,                                                     \
        .blocks_f = sh__rot_##kn##_blocks_f,                                                     \
        .apply_d = sh__rot_##kn##_apply_d,                                                       \
        .apply_f = sh__rot_##kn##_apply_f,                                                       \
    };
TY_OPS(sh__rot_taylor1_ops, "taylor1", taylor1)
TY_OPS(sh__rot_taylor15_ops, "taylor1.5", taylor15)
TY_OPS(sh__rot_taylor2_ops, "taylor2", taylor2)
#endif
