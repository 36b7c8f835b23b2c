/* rotation_bands.c — one band, or the bands of a rotation one after the
 * other: through the method's single-band routine, its band-by-band stream
 * (O(lmax²) memory), or — bounded in memory — a plan's blocks. */
#include "rotate/rot_internal.h"

#include <stdlib.h>
#include <string.h>

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
    int st = sh__rot_check_args(lmax + 1, method, prec, conv);
    if (st) return st;
    sh_rot_bands *it = calloc(1, sizeof *it);
    if (!it) return sh_error(SH_ENOMEM, "rotation bands: out of memory");
    it->method = method;
    it->prec = prec;
    it->conv = conv;
    it->lmax = lmax;
    it->rot = *rot;
    it->ops = sh__rot_ops_of(method);
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
                            sh_rot_method_name(method), sh_precision_name(prec), lmax, bytes / 1e9);
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