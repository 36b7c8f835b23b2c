/* rotation_plan.c — a plan: the per-rotation state of one thread's work
 * with a rotator (rotator.c).  It holds the rotation that was set, what the
 * method derives from it once (blocks, multiple angles, the unrolled
 * kernels' parameters), scratch and vector copies, and applies it to one
 * vector, K vectors, or K rotations of K vectors.  The rotator it reads is
 * never written, so plans of one rotator run on different threads at once.
 *
 * Every method computes in the CS convention; the plan turns the result into
 * nocs by the sign flip S·R·S (S = −1 on odd m).
 */
#include "rotate/rot_finite.h"
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h" /* SH_PRAGMA */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct sh_rot_plan {
    const sh_rotator *r;
    sh_rotator *owned;  /* the rotator of sh_rot_plan_create, freed with the plan */
    void *work;
    void *state;        /* sparse methods: the per-rotation state set_P fills */
    void *blocks;       /* double or float, sh_rot_block_offset(order) */
    void *vin, *vout;   /* vectors in the plan's precision (float plans: the converted ones) */
    double *vtmp;       /* a copy of the input vector */
    sh_rot_stream *stream; /* halfpi in double through the front door */
    sh_rotation rot;
    int have_rot;
    int have_angles;    /* rot has the Euler angles (a plan set from a matrix may not) */
    uint64_t set_mults, apply_mults;
    double par_d[SH__PAR_N]; /* unrolled: the rotation (nocs: β negated) */
    float par_f[SH__PAR_N];
    int blocks_ok;      /* unrolled ivanic: blocks holds the rotation's blocks */
    int par_stale;      /* one_mat: par not yet made from the state's R (apply_many makes it) */
};

int sh__rot_plan_new(const sh_rotator *r, int owns, sh_rot_plan **out)
{
    *out = NULL;
    sh_rot_plan *p = calloc(1, sizeof *p);
    if (!p) return sh_error(SH_ENOMEM, "rotation plan: out of memory");
    p->r = r;
    if (owns) p->owned = (sh_rotator *)r;
    const int order = r->order;
    const size_t esz = r->prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    const size_t nb = sh_rot_block_offset(order), nc = (size_t)order * order;
    const sh__rot_ops *ops = r->ops;
    if (!ops->apply_d) p->blocks = malloc(nb * esz); /* sparse methods: only on request */
    p->work = malloc((ops->work_bytes ? ops->work_bytes(order) : 0) + 64);
    p->vtmp = malloc(nc * sizeof(double));
    if (ops->state_bytes) p->state = malloc(ops->state_bytes(order) + 64);
    p->vin = malloc(nc * esz);
    p->vout = malloc(nc * esz);
    if ((!ops->apply_d && !p->blocks) || !p->work || !p->vtmp || (ops->state_bytes && !p->state) || !p->vin ||
        !p->vout) {
        p->owned = NULL;
        sh_rot_plan_free(p);
        return sh_error(SH_ENOMEM, "rotation plan: out of memory (order %d)", order);
    }
    if (r->stream) {
        int st = sh_rot_stream_create(order, r->conv, r->threads, &p->stream);
        if (st) {
            p->owned = NULL;
            sh_rot_plan_free(p);
            return st;
        }
        if (r->progress) sh_rot_stream_set_progress(p->stream, r->progress, r->progress_ctx);
    }
    *out = p;
    return SH_OK;
}

int sh_rotator_plan(const sh_rotator *r, sh_rot_plan **out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_rotator_plan: no output");
    *out = NULL;
    if (!r) return sh_error(SH_EINVAL, "sh_rotator_plan: no rotator");
    return sh__rot_plan_new(r, 0, out);
}

sh_rot_kernel sh_rot_plan_kernel(const sh_rot_plan *p) { return p->r->kernel; }
const sh_rotator *sh_rot_plan_rotator(const sh_rot_plan *p) { return p->r; }

void sh_rot_plan_free(sh_rot_plan *p)
{
    if (!p) return;
    free(p->blocks);
    free(p->work);
    free(p->state);
    free(p->vin);
    free(p->vout);
    free(p->vtmp);
    sh_rot_stream_free(p->stream);
    sh_rotator_free(p->owned);
    free(p);
}

/* Blocks for the current rotation, in the plan's precision and convention,
 * into `blocks` (double or float as the plan). */
static int compute_blocks(sh_rot_plan *p, void *blocks, uint64_t *mults)
{
    int st;
    if (p->r->prec == SH_PREC_FLOAT) {
        st = p->r->ops->blocks_f(p->r->order, &p->rot, p->r->tables, blocks, p->work, mults);
        if (!st && p->r->conv == SH_NOCS) sh__rot_blocks_nocs_f(p->r->order, blocks);
    } else {
        st = p->r->ops->blocks_d(p->r->order, &p->rot, p->r->tables, blocks, p->work, mults);
        if (!st && p->r->conv == SH_NOCS) sh__rot_blocks_nocs_d(p->r->order, blocks);
    }
    return st;
}

/* A one-vector kernel that reads R (rotator one_mat: zxzxz_one.c, float
 * plans): the state is the rotation's matrix in float, as given (the
 * kernel applies the convention).  The sets other than
 * sh_rot_plan_set_matrix_f come here with R in double, or R in float
 * (rf), or a quaternion (its matrix, rotation.c). */
static void one_mat_state(sh_rot_plan *p, const double *rd, const float *rf, int quat)
{
    float *st = p->state;
    double R[9], q[4];
    if (quat) {
        for (int i = 0; i < 4; i++) q[i] = rf ? rf[i] : rd[i];
        sh__rot_quat_matrix(q, R);
        rd = R, rf = NULL;
    }
    for (int i = 0; i < 9; i++) st[i] = rf ? rf[i] : (float)rd[i];
    p->par_stale = 0;
}

/* The unrolled kernels: par in the plan's precision, nocs by β → −β
 * (rot_fast.c), counted multiplications of one vector. */
static void fast_par_done(sh_rot_plan *p, const double *pd)
{
    if (pd) for (int j = 0; j < SH__PAR_N; j++) p->par_d[j] = pd[j];
    if (p->r->prec == SH_PREC_FLOAT && pd)
        for (int j = 0; j < SH__PAR_N; j++) p->par_f[j] = (float)pd[j];
    if (p->r->conv == SH_NOCS && p->r->fmeth == SH__FAST_IVANIC) {
        /* Rz(π)·R·Rz(π) (rot_fast.c) */
        static const int neg[4] = {2, 5, 6, 7};
        for (int j = 0; j < 4; j++) p->par_d[neg[j]] = -p->par_d[neg[j]], p->par_f[neg[j]] = -p->par_f[neg[j]];
    } else if (p->r->conv == SH_NOCS) {
        p->par_d[3] = -p->par_d[3], p->par_d[6] = -p->par_d[6];
        p->par_f[3] = -p->par_f[3], p->par_f[6] = -p->par_f[6];
    }
    p->blocks_ok = 0;
    p->have_rot = 1;
}
static uint64_t fast_mults(const sh_rot_plan *p) { return p->r->fn_mults; }
static int need_beta(const sh_rot_plan *p) { return p->r->nb; }

int sh_rot_plan_set(sh_rot_plan *p, const sh_rotation *rot)
{
    p->rot = *rot;
    p->have_rot = 0;
    p->have_angles = 1;
    p->set_mults = 0;
    int st = SH_OK;
    if (p->stream) { /* the stream reads the angles at apply */
        p->have_rot = 1;
        return SH_OK;
    }
    if (p->r->fmeth == SH__FAST_IVANIC) {
        fast_par_done(p, rot->R);
        return SH_OK;
    }
    if (p->r->fmeth >= 0) {
        if (p->r->prec == SH_PREC_FLOAT) sh__rot_par_euler_f(rot, p->par_f);
        else sh__rot_par_euler_d(rot, p->par_d);
        fast_par_done(p, NULL);
        if (p->r->one_mat) one_mat_state(p, rot->R, NULL, 0);
        return SH_OK;
    }
    const sh__rot_progress_scope outer = sh__rot_progress_enter(p->r, "bands of the rotation");
    if (p->r->ops->apply_d) {
        /* sparse methods: the per-rotation state (validates the rotation;
         * z refuses a tilted one here) */
        if (p->r->prec == SH_PREC_FLOAT)
            st = p->r->ops->set_f(p->r->order, rot, p->r->tables, p->state, &p->set_mults);
        else
            st = p->r->ops->set_d(p->r->order, rot, p->r->tables, p->state, &p->set_mults);
    } else {
        st = compute_blocks(p, p->blocks, &p->set_mults);
    }
    sh__rot_progress_leave(outer);
    if (st == SH_OK) p->have_rot = 1;
    return st;
}

/* A rotation given as a matrix R (quat = 0) or a quaternion (quat = 1), in
 * double (rd) or float (rf, float plans only): the unrolled kernels and the
 * methods with set_par take par by algebra (rot_fast.c), ivanic reads R;
 * the others get the Euler angles extracted (sh_euler_from_matrix). */
/* 1 if every v[i] is finite: the largest |v[i]| as an integer (the bits of
 * a non-negative float order like its value) below that of +Inf; branch-
 * free, as this check runs once per rotation */
#define ALL_FINITE(NAME, T, U, ABS, INF)                                                           \
    static int NAME(const T *v, size_t n)                                                          \
    {                                                                                              \
        U m = 0;                                                                                   \
        SH_PRAGMA(omp simd reduction(max : m))                                                     \
        for (size_t i = 0; i < n; i++) {                                                           \
            U u;                                                                                   \
            memcpy(&u, v + i, sizeof u);                                                           \
            u &= ABS;                                                                              \
            m = u > m ? u : m;                                                                     \
        }                                                                                          \
        return m < INF;                                                                            \
    }
ALL_FINITE(all_finite_d, double, uint64_t, 0x7fffffffffffffffULL, 0x7ff0000000000000ULL)
ALL_FINITE(all_finite_f, float, uint32_t, 0x7fffffffu, 0x7f800000u)
#undef ALL_FINITE

/* The unrolled kernels' parameters of a rotation given as a matrix, for
 * rotator r (rot_fast.c: by algebra, no trigonometric call): ivanic reads R
 * itself (nocs: Rz(π)·R·Rz(π), entries 2, 5, 6, 7 negated), the others
 * (cos, sin of α, β, γ[, β]) with β negated for nocs. */
static const int nocs_ivanic[4] = {2, 5, 6, 7};
int sh__rot_plan_par_matrix_d(const sh_rotator *r, const double R[9], double *par)
{
    if (!sh__finite9_d(R)) return sh_error(SH_EINVAL, "rotation plan: matrix entries must be finite");
    if (r->fmeth == SH__FAST_IVANIC) {
        memcpy(par, R, 9 * sizeof *par);
        if (r->conv == SH_NOCS)
            for (int j = 0; j < 4; j++) par[nocs_ivanic[j]] = -par[nocs_ivanic[j]];
        return SH_OK;
    }
    sh__rot_par_matrix_d(R, r->nb, par);
    if (r->conv == SH_NOCS) par[3] = -par[3], par[6] = -par[6];
    return SH_OK;
}

static inline __attribute__((always_inline)) int par_matrix_f(const sh_rotator *r, const float R[9], float *par)
{
    if (!sh__finite9_f(R)) return sh_error(SH_EINVAL, "rotation plan: matrix entries must be finite");
    r->ff1->par_matrix(R, r->nb, par);
    if (r->conv == SH_NOCS) par[3] = -par[3], par[6] = -par[6];
    return SH_OK;
}
int sh__rot_plan_par_matrix_f(const sh_rotator *r, const float R[9], float *par) { return par_matrix_f(r, R, par); }

/* A sparse method set straight from the matrix (ops->set_mat_P: direct),
 * in the plan's precision: no angle, no par; sh_rot_plan_blocks reads its
 * state (ops->state_blocks_P), so the matrix is not kept. */
static int set_mat(sh_rot_plan *p, const double *rd, const float *rf)
{
    p->have_angles = 0;
    p->set_mults = 0;
    int st;
    if (p->r->prec == SH_PREC_FLOAT) {
        float R[9];
        for (int i = 0; i < 9; i++) R[i] = rf ? rf[i] : (float)rd[i];
        st = p->r->ops->set_mat_f(p->r->order, R, p->state, &p->set_mults);
    } else {
        st = p->r->ops->set_mat_d(p->r->order, rd, p->state, &p->set_mults);
    }
    if (st == SH_OK) p->have_rot = 1;
    return st;
}

static int set_rot(sh_rot_plan *p, const double *rd, const float *rf, int quat)
{
    const int n = quat ? 4 : 9, nb = need_beta(p);
    if (!(quat ? (rf ? all_finite_f(rf, 4) : all_finite_d(rd, 4)) : (rf ? sh__finite9_f(rf) : sh__finite9_d(rd))))
        return sh_error(SH_EINVAL, "rotation plan: %s entries must be finite", quat ? "quaternion" : "matrix");
    p->have_rot = 0;
    p->set_mults = (quat ? SH__PAR_MULTS_QUAT : SH__PAR_MULTS_MATRIX) + (nb && rf ? SH__PAR_MULTS_BETA_F : 0);
    if (p->r->fmeth == SH__FAST_IVANIC) { /* par = R */
        double R[9], q[4];
        if (quat) {
            for (int i = 0; i < 4; i++) q[i] = rf ? rf[i] : rd[i];
            sh__rot_quat_matrix(q, R);
        } else {
            for (int i = 0; i < 9; i++) R[i] = rf ? rf[i] : rd[i];
        }
        memcpy(p->rot.R, R, sizeof R);
        p->have_angles = 0;
        p->set_mults = quat ? SH__QUAT_MATRIX_MULTS : 0;
        fast_par_done(p, R);
        return SH_OK;
    }
    if (p->r->fmeth >= 0) { /* the unrolled kernels: par only */
        if (rf) {
            quat ? sh__rot_par_quat_f(rf, nb, p->par_f) : sh__rot_par_matrix_f(rf, nb, p->par_f);
        } else {
            double *pd = p->par_d;
            quat ? sh__rot_par_quat_d(rd, nb, pd) : sh__rot_par_matrix_d(rd, nb, pd);
            if (p->r->prec == SH_PREC_FLOAT)
                for (int j = 0; j < SH__PAR_N; j++) p->par_f[j] = (float)pd[j];
        }
        p->have_angles = 0;
        fast_par_done(p, NULL);
        if (p->r->one_mat) one_mat_state(p, rd, rf, quat);
        return SH_OK;
    }
    if (!quat && p->r->ops->set_mat_d) return set_mat(p, rd, rf);
    double v[9];
    for (int i = 0; i < n; i++) v[i] = rd ? rd[i] : (double)rf[i];
    int st;
    if (p->r->ops->set_par_d || p->r->ops->blocks_par_d) {
        double pd[SH__PAR_N];
        if (rf) {
            /* float in: par in float arithmetic */
            quat ? sh__rot_par_quat_f(rf, nb, p->par_f) : sh__rot_par_matrix_f(rf, nb, p->par_f);
        } else {
            quat ? sh__rot_par_quat_d(rd, nb, pd) : sh__rot_par_matrix_d(rd, nb, pd);
            for (int j = 0; j < SH__PAR_N; j++) p->par_d[j] = pd[j], p->par_f[j] = (float)pd[j];
        }
        p->have_angles = 0;
        if (quat) {
            if ((st = sh_rotation_from_quat(v, 1, &p->rot))) return st;
            p->have_angles = 1;
        } else {
            memcpy(p->rot.R, v, sizeof p->rot.R);
        }
        if (p->r->ops->set_par_d) { /* sparse: the state */
            if (p->r->prec == SH_PREC_FLOAT)
                st = p->r->ops->set_par_f(p->r->order, p->par_f, p->r->tables, p->state, &p->set_mults);
            else
                st = p->r->ops->set_par_d(p->r->order, p->par_d, p->r->tables, p->state, &p->set_mults);
        } else if (p->r->prec == SH_PREC_FLOAT) { /* blocks */
            st = p->r->ops->blocks_par_f(p->r->order, p->par_f, p->r->tables, p->blocks, p->work, &p->set_mults);
            if (!st && p->r->conv == SH_NOCS) sh__rot_blocks_nocs_f(p->r->order, p->blocks);
        } else {
            st = p->r->ops->blocks_par_d(p->r->order, p->par_d, p->r->tables, p->blocks, p->work, &p->set_mults);
            if (!st && p->r->conv == SH_NOCS) sh__rot_blocks_nocs_d(p->r->order, p->blocks);
        }
        if (st == SH_OK) p->have_rot = 1;
        return st;
    }
    p->set_mults = 0;
    sh_rotation r;
    if (quat) {
        if ((st = sh_rotation_from_quat(v, 1, &r))) return st;
    } else {
        memcpy(r.R, v, sizeof r.R);
        if (p->r->ops->matrix_only) r.alpha = r.beta = r.gamma = 0; /* not read */
        else sh_euler_from_matrix(v, &r.alpha, &r.beta, &r.gamma);
    }
    st = sh_rot_plan_set(p, &r);
    p->have_angles = quat || !p->r->ops->matrix_only;
    return st;
}

int sh_rot_plan_set_matrix(sh_rot_plan *p, const double R[9]) { return set_rot(p, R, NULL, 0); }
int sh_rot_plan_set_quat(sh_rot_plan *p, const double q[4]) { return set_rot(p, q, NULL, 1); }
/* set_rot's two hot cases written out, each its own function so that the
 * dispatch below needs no stack frame (every path a tail call): the
 * unrolled kernels' par, and a method's own state from the matrix (direct;
 * set_mat checks R) */
static __attribute__((noinline)) int set_matrix_fast_f(sh_rot_plan *p, const float R[9])
{
    const int st = par_matrix_f(p->r, R, p->par_f);
    if (st) return st;
    p->set_mults = SH__PAR_MULTS_MATRIX + (p->r->nb ? SH__PAR_MULTS_BETA_F : 0);
    p->have_angles = 0;
    p->have_rot = 1;
    return SH_OK;
}
/* one_mat (zxzxz_one.c): R checked finite (rot_finite.h) and copied into
 * the state, the first eight entries as two 16-byte vectors (the kernel's
 * loads of them are then forwarded from these stores); par is made only if
 * a batch asks (apply_many) */
static __attribute__((noinline)) int set_matrix_one_f(sh_rot_plan *p, const float R[9])
{
    if (!sh__finite9_f(R)) return sh_error(SH_EINVAL, "rotation plan: matrix entries must be finite");
    typedef float v4 __attribute__((vector_size(16)));
    v4 a, b;
    float *st = p->state;
    memcpy(&a, R, 16);
    memcpy(&b, R + 4, 16);
    memcpy(st, &a, 16);
    memcpy(st + 4, &b, 16);
    st[8] = R[8];
    p->set_mults = 0;
    p->par_stale = 1;
    p->have_angles = 0;
    p->have_rot = 1;
    return SH_OK;
}
static __attribute__((noinline)) int set_matrix_own_f(sh_rot_plan *p, const float R[9])
{
    p->have_rot = p->have_angles = 0;
    p->set_mults = 0;
    const int st = p->r->ops->set_mat_f(p->r->order, R, p->state, &p->set_mults);
    p->have_rot = st == SH_OK;
    return st;
}
int sh_rot_plan_set_matrix_f(sh_rot_plan *p, const float R[9])
{
    if (p->r->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float matrix for a double plan");
    if (p->r->fmeth >= 0 && p->r->fmeth != SH__FAST_IVANIC)
        return p->r->one_mat ? set_matrix_one_f(p, R) : set_matrix_fast_f(p, R);
    if (p->r->ops->set_mat_f) return set_matrix_own_f(p, R);
    return set_rot(p, NULL, R, 0);
}
int sh_rot_plan_set_quat_f(sh_rot_plan *p, const float q[4])
{
    if (p->r->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float quaternion for a double plan");
    return set_rot(p, NULL, q, 1);
}

static void nocs_vec_d(int order, double *v)
{
    for (int l = 1; l < order; l++)
        for (int m = 1; m <= l; m += 2) {
            v[l * (l + 1) + m] = -v[l * (l + 1) + m];
            v[l * (l + 1) - m] = -v[l * (l + 1) - m];
        }
}
static void nocs_vec_f(int order, float *v)
{
    for (int l = 1; l < order; l++)
        for (int m = 1; m <= l; m += 2) {
            v[l * (l + 1) + m] = -v[l * (l + 1) + m];
            v[l * (l + 1) - m] = -v[l * (l + 1) - m];
        }
}

/* y = R_sh x in float (float plans); x and y may be the same array. */
static void apply_float(sh_rot_plan *p, const float *x, float *y, uint64_t *m)
{
    const size_t nc = (size_t)p->r->order * p->r->order;
    if (p->r->fn_f) {
        p->r->fn_f(p->par_f, 1, x, y, 1);
        *m += p->r->fn_mults;
    } else if (p->r->one_f) { /* the method's one-vector kernel: convention and in == out its own */
        p->r->one_f(p->state, x, y);
        *m += p->r->one_mults;
    } else if (p->r->ops->apply_f) { /* sparse: the kernel works in CS, on distinct arrays */
        if (p->r->conv == SH_NOCS || x == y) {
            if (x != p->vin) memcpy(p->vin, x, nc * sizeof *x);
            x = p->vin;
            if (p->r->conv == SH_NOCS) nocs_vec_f(p->r->order, p->vin);
        }
        p->r->ops->apply_f(p->r->order, p->r->tables, p->state, x, y, p->work, m);
        if (p->r->conv == SH_NOCS) nocs_vec_f(p->r->order, y);
    } else {
        if (x == y) {
            if (x != p->vin) memcpy(p->vin, x, nc * sizeof *x);
            x = p->vin;
        }
        sh__rot_blocks_apply_f(p->r->order, p->blocks, x, y, m);
    }
}

int sh_rot_plan_apply(sh_rot_plan *p, const double *in, double *out)
{
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    const size_t nc = (size_t)p->r->order * p->r->order;
    uint64_t m = 0;
    if (p->stream) {
        p->apply_mults = 0; /* not counted by the stream */
        return sh_rot_stream_apply(p->stream, 1, &p->rot, 0, 1, in, out);
    }
    if (p->r->prec == SH_PREC_FLOAT) {
        float *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = (float)in[i];
        apply_float(p, x, y, &m);
        for (size_t i = 0; i < nc; i++) out[i] = y[i];
    } else if (p->r->fn_d) {
        p->r->fn_d(p->par_d, 1, in, out, 1);
        m = p->r->fn_mults;
    } else if (p->r->one_d) {
        p->r->one_d(p->state, in, out);
        m = p->r->one_mults;
    } else {
        /* kernels need distinct input and output: copy when in == out (and
         * for a sparse kernel in nocs, whose input is sign-flipped first) */
        const double *x = in;
        const int sparse_nocs = p->r->ops->apply_d && p->r->conv == SH_NOCS;
        if (in == out || sparse_nocs) {
            memcpy(p->vtmp, in, nc * sizeof *p->vtmp);
            if (sparse_nocs) nocs_vec_d(p->r->order, p->vtmp);
            x = p->vtmp;
        }
        if (p->r->ops->apply_d) p->r->ops->apply_d(p->r->order, p->r->tables, p->state, x, out, p->work, &m);
        else sh__rot_blocks_apply_d(p->r->order, p->blocks, x, out, &m);
        if (sparse_nocs) nocs_vec_d(p->r->order, out);
    }
    p->apply_mults = m;
    return SH_OK;
}

int sh_rot_plan_apply_f(sh_rot_plan *p, const float *in, float *out)
{
    if (p->r->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float vectors for a double plan");
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    /* the count first: nothing is read back after the kernel */
    if (p->r->fn_f) {
        p->apply_mults = p->r->fn_mults;
        p->r->fn_f(p->par_f, 1, in, out, 1);
        return SH_OK;
    }
    if (p->r->one_f) {
        p->apply_mults = p->r->one_mults;
        p->r->one_f(p->state, in, out);
        return SH_OK;
    }
    uint64_t m = 0;
    apply_float(p, in, out, &m);
    p->apply_mults = m;
    return SH_OK;
}

/* ---- batches: structure of arrays, element i of vector k at [i·K + k] ---- */
static int check_batch(const sh_rot_plan *p, size_t K, int fl, int need_rot)
{
    if (fl && p->r->prec != SH_PREC_FLOAT) return sh_error(SH_EINVAL, "rotation plan: float vectors for a double plan");
    if (!fl && p->r->prec != SH_PREC_DOUBLE) return sh_error(SH_EINVAL, "rotation plan: double vectors for a float plan (use the _f call)");
    if (need_rot && !p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    if (K == 0 || K > ((size_t)1 << 40)) return sh_error(SH_EINVAL, "rotation plan: batch of %zu vectors", K);
    return SH_OK;
}

/* the loop kernels, one vector at a time through the plan's buffers */
static void many_loop(sh_rot_plan *p, size_t K, const void *in, void *out, size_t k)
{
    const size_t nc = (size_t)p->r->order * p->r->order;
    uint64_t m = 0;
    if (p->r->prec == SH_PREC_FLOAT) {
        float *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = ((const float *)in)[i * K + k];
        apply_float(p, x, y, &m);
        for (size_t i = 0; i < nc; i++) ((float *)out)[i * K + k] = y[i];
    } else {
        double *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = ((const double *)in)[i * K + k];
        sh_rot_plan_apply(p, x, y);
        for (size_t i = 0; i < nc; i++) ((double *)out)[i * K + k] = y[i];
        m = p->apply_mults;
    }
    p->apply_mults = m;
}

/* out = blocks · in for K vectors (structure of arrays), band by band, a
 * chunk of vectors at a time (copied first: in == out allowed); each row
 * summed left to right as sh__rot_blocks_apply, vectorised across vectors. */
#define MANY_CHUNK 64
#define MANY_W (2 * SH__FAST_MAXO + 1)
#define BLOCKS_MANY(NAME, T)                                                                       \
    static void NAME(int order, const T *blocks, size_t K, const T *in, T *out)                    \
    {                                                                                              \
        T x[MANY_W * MANY_CHUNK];                                                                  \
        for (int l = 0; l < order; l++) {                                                          \
            const int w = 2 * l + 1;                                                               \
            const T *B = blocks + sh_rot_block_offset(l);                                          \
            for (size_t k0 = 0; k0 < K; k0 += MANY_CHUNK) {                                        \
                const size_t nk = K - k0 < MANY_CHUNK ? K - k0 : MANY_CHUNK;                       \
                for (int j = 0; j < w; j++)                                                        \
                    memcpy(x + (size_t)j * MANY_CHUNK, in + ((size_t)l * l + j) * K + k0, nk * sizeof *x); \
                for (int i = 0; i < w; i++) {                                                      \
                    T *o = out + ((size_t)l * l + i) * K + k0;                                     \
                    SH_PRAGMA(omp simd)                                                            \
                    for (size_t k = 0; k < nk; k++) {                                              \
                        T s = 0;                                                                   \
                        for (int j = 0; j < w; j++) s += B[(size_t)i * w + j] * x[(size_t)j * MANY_CHUNK + k]; \
                        o[k] = s;                                                                  \
                    }                                                                              \
                }                                                                                  \
            }                                                                                      \
        }                                                                                          \
    }
BLOCKS_MANY(blocks_many_d, double)
BLOCKS_MANY(blocks_many_f, float)
#undef BLOCKS_MANY

static int apply_many(sh_rot_plan *p, size_t K, const void *in, void *out, int fl)
{
    int st = check_batch(p, K, fl, 1);
    if (st) return st;
    if (p->r->fmeth == SH__FAST_IVANIC) {
        /* one rotation, many vectors: the blocks once (the loop kernel), then
         * blocks × vectors, rather than the fused kernel per vector */
        if (!p->blocks_ok) {
            uint64_t sm = 0;
            if ((st = compute_blocks(p, p->blocks, &sm))) return st;
            p->set_mults += sm;
            p->blocks_ok = 1;
        }
        if (fl) blocks_many_f(p->r->order, p->blocks, K, in, out);
        else blocks_many_d(p->r->order, p->blocks, K, in, out);
        p->apply_mults = (uint64_t)p->r->order * (4u * (uint64_t)p->r->order * p->r->order - 1) / 3;
        return SH_OK;
    }
    if (p->r->fmeth >= 0) {
        if (p->par_stale) { /* set by sh_rot_plan_set_matrix_f for the one-vector kernel: R in the state */
            par_matrix_f(p->r, p->state, p->par_f);
            p->par_stale = 0;
        }
        if (fl) p->r->ffv->many(p->r->fmeth, p->r->order, p->par_f, K, in, out);
        else p->r->fdv->many(p->r->fmeth, p->r->order, p->par_d, K, in, out);
        p->apply_mults = fast_mults(p);
        return SH_OK;
    }
    for (size_t k = 0; k < K; k++) many_loop(p, K, in, out, k);
    return SH_OK;
}
int sh_rot_plan_apply_many(sh_rot_plan *p, size_t K, const double *in, double *out)
{
    return apply_many(p, K, in, out, 0);
}
int sh_rot_plan_apply_many_f(sh_rot_plan *p, size_t K, const float *in, float *out)
{
    return apply_many(p, K, in, out, 1);
}

static int rotate_many(sh_rot_plan *p, size_t K, const void *rot, int quat, const void *in, void *out,
                       int fl)
{
    int st = check_batch(p, K, fl, 0);
    if (st) return st;
    const int nr = quat ? 4 : 9;
    if (!quat && (fl ? p->r->ops->rotate_many_f != NULL : p->r->ops->rotate_many_d != NULL)) {
        /* the method's own batch of matrices (direct; it checks them finite) */
        const int nocs = p->r->conv == SH_NOCS;
        p->set_mults = p->apply_mults = 0;
        p->have_rot = 0; /* the plan's own rotation is not one of them */
        if (fl) return p->r->ops->rotate_many_f(p->r->order, nocs, p->r->kernel, K, rot, in, out, &p->set_mults, &p->apply_mults);
        return p->r->ops->rotate_many_d(p->r->order, nocs, p->r->kernel, K, rot, in, out, &p->set_mults, &p->apply_mults);
    }
    if (p->r->fmeth >= 0) {
        /* unrolled, lanes of rotations; checked first: every entry finite */
        if (!(fl ? all_finite_f(rot, (size_t)nr * K) : all_finite_d(rot, (size_t)nr * K)))
            return sh_error(SH_EINVAL, "rotation plan: a rotation has an entry that is not finite");
        const int nocs = p->r->conv == SH_NOCS;
        if (fl) p->r->ffv->rotate(p->r->fmeth, p->r->order, nocs, K, rot, quat, in, out);
        else p->r->fdv->rotate(p->r->fmeth, p->r->order, nocs, K, rot, quat, in, out);
        if (p->r->fmeth == SH__FAST_IVANIC) p->set_mults = quat ? SH__QUAT_MATRIX_MULTS : 0;
        else p->set_mults = (quat ? SH__PAR_MULTS_QUAT : SH__PAR_MULTS_MATRIX) + (need_beta(p) && fl ? SH__PAR_MULTS_BETA_F : 0);
        p->apply_mults = fast_mults(p);
        p->have_rot = 0; /* the plan's own rotation is not one of them */
        return SH_OK;
    }
    for (size_t k = 0; k < K; k++) {
        double rd[9];
        float rf[9];
        for (int j = 0; j < nr; j++) {
            if (fl) rf[j] = ((const float *)rot)[(size_t)j * K + k];
            else rd[j] = ((const double *)rot)[(size_t)j * K + k];
        }
        if ((st = set_rot(p, fl ? NULL : rd, fl ? rf : NULL, quat))) return st;
        many_loop(p, K, in, out, k);
    }
    return SH_OK;
}
int sh_rot_plan_rotate_many(sh_rot_plan *p, size_t K, const double *R, const double *in, double *out)
{
    return rotate_many(p, K, R, 0, in, out, 0);
}
int sh_rot_plan_rotate_many_f(sh_rot_plan *p, size_t K, const float *R, const float *in, float *out)
{
    return rotate_many(p, K, R, 0, in, out, 1);
}
int sh_rot_plan_rotate_many_quat(sh_rot_plan *p, size_t K, const double *q, const double *in,
                                 double *out)
{
    return rotate_many(p, K, q, 1, in, out, 0);
}
int sh_rot_plan_rotate_many_quat_f(sh_rot_plan *p, size_t K, const float *q, const float *in,
                                   float *out)
{
    return rotate_many(p, K, q, 1, in, out, 1);
}

int sh_rot_plan_blocks(sh_rot_plan *p, double *blocks)
{
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    const size_t nb = sh_rot_block_offset(p->r->order), nc = (size_t)p->r->order * p->r->order;
    if (p->r->fmeth >= 0) {
        /* the unrolled kernel on each unit vector: column j of band l */
        double *e = malloc(2 * nc * sizeof *e), *col = e + nc;
        if (!e) return sh_error(SH_ENOMEM, "rotation plan: out of memory");
        for (int l = 0; l < p->r->order; l++) {
            const int w = 2 * l + 1;
            double *B = blocks + sh_rot_block_offset(l);
            for (int j = 0; j < w; j++) {
                memset(e, 0, nc * sizeof *e);
                e[l * l + j] = 1;
                sh_rot_plan_apply(p, e, col);
                for (int i = 0; i < w; i++) B[(size_t)i * w + j] = col[l * l + i];
            }
        }
        free(e);
        return SH_OK;
    }
    if (p->r->ops->state_blocks_d) { /* direct: the blocks of its state */
        if (p->r->prec == SH_PREC_FLOAT) p->r->ops->state_blocks_f(p->r->order, p->state, blocks);
        else p->r->ops->state_blocks_d(p->r->order, p->state, blocks);
        if (p->r->conv == SH_NOCS) sh__rot_blocks_nocs_d(p->r->order, blocks);
        return SH_OK;
    }
    if (p->r->ops->apply_d) { /* sparse methods build their blocks on request */
        if (!p->have_angles) {
            sh_euler_from_matrix(p->rot.R, &p->rot.alpha, &p->rot.beta, &p->rot.gamma);
            p->have_angles = 1;
        }
        if (p->r->prec == SH_PREC_DOUBLE) return compute_blocks(p, blocks, NULL);
        float *fb = malloc(nb * sizeof *fb);
        if (!fb) return sh_error(SH_ENOMEM, "rotation plan: out of memory (blocks, order %d)", p->r->order);
        const int st = compute_blocks(p, fb, NULL);
        for (size_t i = 0; !st && i < nb; i++) blocks[i] = fb[i];
        free(fb);
        return st;
    }
    if (p->r->prec == SH_PREC_FLOAT)
        for (size_t i = 0; i < nb; i++) blocks[i] = ((float *)p->blocks)[i];
    else
        memcpy(blocks, p->blocks, nb * sizeof *blocks);
    return SH_OK;
}

void sh_rot_plan_mults(const sh_rot_plan *p, uint64_t *set_mults, uint64_t *apply_mults)
{
    if (set_mults) *set_mults = p->set_mults;
    if (apply_mults) *apply_mults = p->apply_mults;
}

void sh_rot_blocks_flip_phase(int order, double *blocks) { sh__rot_blocks_nocs_d(order, blocks); }

void sh_rot_blocks_to_dense(int order, const double *blocks, double *dense)
{
    const size_t n = (size_t)order * order;
    memset(dense, 0, n * n * sizeof *dense);
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        const double *B = blocks + sh_rot_block_offset(l);
        for (int r = 0; r < w; r++)
            for (int c = 0; c < w; c++) dense[(size_t)(l * l + r) * n + (l * l + c)] = B[(size_t)r * w + c];
    }
}
