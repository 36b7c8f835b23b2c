/* rotation_plan.c — the rotation plan: one object per (order, method,
 * precision, convention) that owns the method's per-order tables, its scratch
 * space and the current rotation's blocks, and applies it to vectors.
 *
 * The methods register here (one ops table each, defined in the method's own
 * file, see rot_internal.h).  Every method computes in the CS convention; the
 * plan turns the result into nocs by the sign flip S·R·S (S = −1 on odd m).
 */
#include "rotate/rot_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const sh__rot_ops *const methods[SH_ROT_NMETHODS] = {
    [SH_ROT_Z] = &sh__rot_z_ops,
    [SH_ROT_IVANIC] = &sh__rot_ivanic_ops,
    [SH_ROT_ZXZXZ] = &sh__rot_zxzxz_ops,
    [SH_ROT_CHOI] = &sh__rot_choi_ops,
    [SH_ROT_BLANCO] = &sh__rot_blanco_ops,
    [SH_ROT_WIGNER] = &sh__rot_wigner_ops,
    [SH_ROT_REFERENCE] = &sh__rot_reference_ops,
    [SH_ROT_TAYLOR1] = &sh__rot_taylor1_ops, [SH_ROT_TAYLOR15] = &sh__rot_taylor15_ops, [SH_ROT_TAYLOR2] = &sh__rot_taylor2_ops,
};

static const char *const method_names[SH_ROT_NMETHODS] = {
    [SH_ROT_Z] = "z",           [SH_ROT_IVANIC] = "ivanic", [SH_ROT_ZXZXZ] = "zxzxz",
    [SH_ROT_CHOI] = "choi",     [SH_ROT_BLANCO] = "blanco", [SH_ROT_WIGNER] = "wigner",
    [SH_ROT_REFERENCE] = "reference", [SH_ROT_TAYLOR1] = "taylor1", [SH_ROT_TAYLOR15] = "taylor1.5",
    [SH_ROT_TAYLOR2] = "taylor2",
};

const char *sh_rot_method_name(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS) ? method_names[m] : "?";
}

int sh_rot_method_parse(const char *s, sh_rot_method *out)
{
    for (int m = 0; m < SH_ROT_NMETHODS; m++)
        if (s && !strcmp(s, method_names[m])) {
            if (!methods[m]) return sh_error(SH_ENOTSUP, "method '%s' is not built in", s);
            *out = (sh_rot_method)m;
            return SH_OK;
        }
    return sh_error(SH_EINVAL,
                    "unknown method '%s' (z, ivanic, zxzxz, choi, blanco, wigner, reference, "
                    "taylor1, taylor1.5, taylor2)",
                    s ? s : "");
}

int sh_rot_method_is_exact(sh_rot_method m)
{
    return m >= 0 && m < SH_ROT_NMETHODS && methods[m] && !methods[m]->approximate;
}

const char *sh_precision_name(sh_precision p) { return p == SH_PREC_FLOAT ? "float" : "double"; }

int sh_precision_parse(const char *s, sh_precision *out)
{
    if (s && !strcmp(s, "double")) *out = SH_PREC_DOUBLE;
    else if (s && !strcmp(s, "float")) *out = SH_PREC_FLOAT;
    else return sh_error(SH_EINVAL, "unknown precision '%s' (float or double)", s ? s : "");
    return SH_OK;
}

int sh_rot_method_max_order(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS && methods[m]) ? methods[m]->max_order : 0;
}

struct sh_rot_plan {
    int order;
    sh_rot_method method;
    sh_precision prec;
    sh_convention conv;
    const sh__rot_ops *ops;
    void *tables;
    void *work;
    void *state;      /* sparse methods: the per-rotation state set_P fills */
    void *blocks;     /* double or float, sh_rot_block_offset(order) */
    void *vin, *vout; /* float plans: the vector in float */
    double *vtmp;     /* a copy of the input vector */
    sh_rotation rot;
    int have_rot;
    uint64_t set_mults, apply_mults;
};

static int check_args(int order, sh_rot_method method, sh_precision prec, sh_convention conv)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (method < 0 || method >= SH_ROT_NMETHODS || !methods[method])
        return sh_error(SH_EINVAL, "rotation: unknown or unavailable method");
    if (order > methods[method]->max_order)
        return sh_error(SH_EINVAL, "method %s: order %d exceeds its limit %d",
                        method_names[method], order, methods[method]->max_order);
    if (prec != SH_PREC_DOUBLE && prec != SH_PREC_FLOAT)
        return sh_error(SH_EINVAL, "rotation: unknown precision");
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "rotation: unknown convention");
    return SH_OK;
}

int sh_rot_plan_create(int order, sh_rot_method method, sh_precision prec, sh_convention conv,
                       sh_rot_plan **out)
{
    *out = NULL;
    int st = check_args(order, method, prec, conv);
    if (st) return st;
    sh_rot_plan *p = calloc(1, sizeof *p);
    if (!p) return sh_error(SH_ENOMEM, "rotation plan: out of memory");
    p->order = order;
    p->method = method;
    p->prec = prec;
    p->conv = conv;
    p->ops = methods[method];
    const size_t esz = prec == SH_PREC_FLOAT ? sizeof(float) : sizeof(double);
    const size_t nb = sh_rot_block_offset(order), nc = (size_t)order * order;
    p->blocks = malloc(nb * esz);
    p->work = malloc((p->ops->work_bytes ? p->ops->work_bytes(order) : 0) + 64);
    p->vtmp = malloc(nc * sizeof(double));
    if (p->ops->state_bytes) p->state = malloc(p->ops->state_bytes(order) + 64);
    if (prec == SH_PREC_FLOAT) {
        p->vin = malloc(nc * sizeof(float));
        p->vout = malloc(nc * sizeof(float));
    }
    if (!p->blocks || !p->work || !p->vtmp || (p->ops->state_bytes && !p->state) || (prec == SH_PREC_FLOAT && (!p->vin || !p->vout))) {
        sh_rot_plan_free(p);
        return sh_error(SH_ENOMEM, "rotation plan: out of memory (order %d)", order);
    }
    int (*tnew)(int, void **) = prec == SH_PREC_FLOAT ? p->ops->tables_new_f : p->ops->tables_new_d;
    if (tnew && (st = tnew(order, &p->tables)) != SH_OK) {
        sh_rot_plan_free(p);
        return st;
    }
    *out = p;
    return SH_OK;
}

void sh_rot_plan_free(sh_rot_plan *p)
{
    if (!p) return;
    if (p->tables && p->ops->tables_free) p->ops->tables_free(p->tables);
    free(p->blocks);
    free(p->work);
    free(p->state);
    free(p->vin);
    free(p->vout);
    free(p->vtmp);
    free(p);
}

/* Blocks for the current rotation, in the plan's precision and convention. */
static int compute_blocks(sh_rot_plan *p, uint64_t *mults)
{
    int st;
    if (p->prec == SH_PREC_FLOAT) {
        st = p->ops->blocks_f(p->order, &p->rot, p->tables, p->blocks, p->work, mults);
        if (!st && p->conv == SH_NOCS) sh__rot_blocks_nocs_f(p->order, p->blocks);
    } else {
        st = p->ops->blocks_d(p->order, &p->rot, p->tables, p->blocks, p->work, mults);
        if (!st && p->conv == SH_NOCS) sh__rot_blocks_nocs_d(p->order, p->blocks);
    }
    return st;
}

int sh_rot_plan_set(sh_rot_plan *p, const sh_rotation *rot)
{
    p->rot = *rot;
    p->have_rot = 0;
    p->set_mults = 0;
    int st = SH_OK;
    if (p->ops->apply_d) {
        /* sparse methods: the per-rotation state (validates the rotation;
         * z refuses a tilted one here) */
        if (p->prec == SH_PREC_FLOAT)
            st = p->ops->set_f(p->order, rot, p->tables, p->state, &p->set_mults);
        else
            st = p->ops->set_d(p->order, rot, p->tables, p->state, &p->set_mults);
    } else {
        st = compute_blocks(p, &p->set_mults);
    }
    if (st == SH_OK) p->have_rot = 1;
    return st;
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

int sh_rot_plan_apply(sh_rot_plan *p, const double *in, double *out)
{
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    const size_t nc = (size_t)p->order * p->order;
    uint64_t m = 0;
    if (p->prec == SH_PREC_FLOAT) {
        float *x = p->vin, *y = p->vout;
        for (size_t i = 0; i < nc; i++) x[i] = (float)in[i];
        if (p->ops->apply_f) { /* sparse: the kernel works in CS */
            if (p->conv == SH_NOCS) nocs_vec_f(p->order, x);
            p->ops->apply_f(p->order, p->tables, p->state, x, y, p->work, &m);
            if (p->conv == SH_NOCS) nocs_vec_f(p->order, y);
        } else {
            sh__rot_blocks_apply_f(p->order, p->blocks, x, y, &m);
        }
        for (size_t i = 0; i < nc; i++) out[i] = y[i];
    } else {
        /* kernels need distinct input and output: copy when in == out (and
         * for a sparse kernel in nocs, whose input is sign-flipped first) */
        const double *x = in;
        const int sparse_nocs = p->ops->apply_d && p->conv == SH_NOCS;
        if (in == out || sparse_nocs) {
            memcpy(p->vtmp, in, nc * sizeof *p->vtmp);
            if (sparse_nocs) nocs_vec_d(p->order, p->vtmp);
            x = p->vtmp;
        }
        if (p->ops->apply_d) p->ops->apply_d(p->order, p->tables, p->state, x, out, p->work, &m);
        else sh__rot_blocks_apply_d(p->order, p->blocks, x, out, &m);
        if (sparse_nocs) nocs_vec_d(p->order, out);
    }
    p->apply_mults = m;
    return SH_OK;
}

int sh_rot_plan_blocks(sh_rot_plan *p, double *blocks)
{
    if (!p->have_rot) return sh_error(SH_EINVAL, "rotation plan: no rotation set");
    const size_t nb = sh_rot_block_offset(p->order);
    if (p->ops->apply_d) { /* sparse methods build their blocks on request */
        int st = compute_blocks(p, NULL);
        if (st) return st;
    }
    if (p->prec == SH_PREC_FLOAT)
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

int sh_rot_band(int band, sh_rot_method method, sh_precision prec, sh_convention conv,
                const sh_rotation *rot, double *block)
{
    /* the band iterator picks the cheapest path: the method's single-band
     * routine, its band-by-band stream, or (bounded in memory) a plan */
    sh_rot_bands *it;
    int st = sh_rot_bands_create(method, prec, conv, band, rot, &it);
    if (st) return st;
    st = sh_rot_bands_get(it, band, block);
    sh_rot_bands_free(it);
    return st;
}

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

/* ------------------------------------------------------- band iterator */
struct sh_rot_bands {
    sh_rot_method method;
    sh_precision prec;
    sh_convention conv;
    int lmax, next;
    sh_rotation rot;
    const sh__rot_ops *ops;
    enum { IT_STREAM, IT_BAND, IT_PLAN } kind;
    void *state;   /* stream state, band work, or the plan's blocks */
    float *fblock; /* float streams */
};

/* A method without a single-band or streaming path needs all blocks 0..L:
 * refused above 1 GiB (band ~ 400) rather than exhausting the machine. */
#define BANDS_PLAN_LIMIT ((size_t)1 << 30)

int sh_rot_bands_create(sh_rot_method method, sh_precision prec, sh_convention conv, int lmax,
                        const sh_rotation *rot, sh_rot_bands **out)
{
    *out = NULL;
    int st = check_args(lmax + 1, method, prec, conv);
    if (st) return st;
    sh_rot_bands *it = calloc(1, sizeof *it);
    if (!it) return sh_error(SH_ENOMEM, "rotation bands: out of memory");
    it->method = method;
    it->prec = prec;
    it->conv = conv;
    it->lmax = lmax;
    it->rot = *rot;
    it->ops = methods[method];
    const sh__rot_ops *ops = it->ops;
    const size_t w = 2 * (size_t)lmax + 1;
    if (ops->stream_bytes && (prec == SH_PREC_DOUBLE ? ops->stream_d != NULL : ops->stream_f != NULL)) {
        it->kind = IT_STREAM;
        it->state = calloc(1, ops->stream_bytes(lmax) + 64);
        if (prec == SH_PREC_FLOAT) it->fblock = malloc(w * w * sizeof(float));
        if (!it->state || (prec == SH_PREC_FLOAT && !it->fblock)) goto nomem;
        if (ops->stream_init && (st = ops->stream_init(lmax, it->state))) { sh_rot_bands_free(it); return st; }
    } else if (ops->band_d && prec == SH_PREC_DOUBLE) {
        it->kind = IT_BAND;
        it->state = malloc((ops->band_work_bytes ? ops->band_work_bytes(lmax) : 0) + 64);
        if (!it->state) goto nomem;
    } else {
        it->kind = IT_PLAN;
        const size_t bytes = sh_rot_block_offset(lmax + 1) * sizeof(double);
        if (bytes > BANDS_PLAN_LIMIT) {
            free(it);
            return sh_error(SH_ENOTSUP,
                            "method %s (%s) computes every band 0..%d to get the last one (%.1f GB of "
                            "blocks, limit 1.1 GB); for high bands use blanco or zxzxz (single band) "
                            "or ivanic (streams)",
                            method_names[method], sh_precision_name(prec), lmax, bytes / 1e9);
        }
        it->state = malloc(bytes);
        if (!it->state) goto nomem;
        sh_rot_plan *p;
        if ((st = sh_rot_plan_create(lmax + 1, method, prec, conv, &p))) { sh_rot_bands_free(it); return st; }
        if (!(st = sh_rot_plan_set(p, rot))) st = sh_rot_plan_blocks(p, it->state);
        sh_rot_plan_free(p);
        if (st) { sh_rot_bands_free(it); return st; }
    }
    *out = it;
    return SH_OK;
nomem:
    sh_rot_bands_free(it);
    return sh_error(SH_ENOMEM, "rotation bands: out of memory (lmax %d)", lmax);
}

int sh_rot_bands_next(sh_rot_bands *it, int *l_out, double *block)
{
    const int l = it->next;
    if (l > it->lmax) return sh_error(SH_EINVAL, "rotation bands: past lmax %d", it->lmax);
    const size_t w = 2 * (size_t)l + 1;
    int st = SH_OK;
    switch (it->kind) {
    case IT_STREAM:
        if (it->prec == SH_PREC_FLOAT) {
            st = it->ops->stream_f(l, &it->rot, it->state, it->fblock);
            for (size_t i = 0; !st && i < w * w; i++) block[i] = it->fblock[i];
        } else {
            st = it->ops->stream_d(l, &it->rot, it->state, block);
        }
        break;
    case IT_BAND: st = it->ops->band_d(l, &it->rot, block, it->state); break;
    case IT_PLAN:
        memcpy(block, (double *)it->state + sh_rot_block_offset(l), w * w * sizeof *block);
        break;
    }
    if (st) return st;
    if (it->conv == SH_NOCS && it->kind != IT_PLAN) sh__rot_band_nocs_d(l, block);
    *l_out = l;
    it->next++;
    return SH_OK;
}

int sh_rot_bands_get(sh_rot_bands *it, int l, double *block)
{
    if (l < it->next || l > it->lmax)
        return sh_error(SH_EINVAL, "rotation bands: band %d not reachable (next %d, lmax %d)", l,
                        it->next, it->lmax);
    if (it->kind != IT_STREAM) it->next = l; /* direct access */
    int got = -1, st;
    do {
        st = sh_rot_bands_next(it, &got, block);
    } while (!st && got < l);
    return st;
}

void sh_rot_bands_free(sh_rot_bands *it)
{
    if (!it) return;
    free(it->state);
    free(it->fblock);
    free(it);
}

int sh__rot_bands_single(const sh_rot_bands *it) { return it && it->kind == IT_BAND; }
