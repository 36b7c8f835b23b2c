/* study.c — shading error of SH lighting on a scene: transfer, lighting and
 * reference at a vertex subset; error per order and per rotation method. */
#include "scene_internal.h"

#include <stdlib.h>
#include <string.h>

struct sh_study {
    const sh_scene *s;
    const sh_env *env;
    sh_study_opts o;
    int nv, order;
    int *verts;
    double *T;        /* nv·order² shadowed transfer */
    double *L;        /* order² luminance coefficients (unrotated) */
    double *RL;       /* the same rotated by `rl_method` */
    int rl_method;    /* −1: none yet */
    sh_rotation rot;
    double *ref, *se; /* reference and standard error at the vertices */
    double *B;        /* scratch */
    sh_study_info info;
};

void sh_study_free(sh_study *st)
{
    if (!st) return;
    free(st->verts);
    free(st->T);
    free(st->L);
    free(st->RL);
    free(st->ref);
    free(st->se);
    free(st->B);
    free(st);
}

int sh_study_create(const sh_scene *s, const sh_env *env, const sh_study_opts *o, sh_study **out)
{
    if (!s || !env || !o || !out) return sh_error(SH_EINVAL, "sh_study_create: bad arguments");
    *out = NULL;
    const int order = o->max_order > 0 ? o->max_order : 12;
    if (order > 64) return sh_error(SH_EINVAL, "study: order %d > 64", order);
    if (o->nverts < 0) return sh_error(SH_EINVAL, "study: negative vertex count");
    sh_study *st = calloc(1, sizeof *st);
    if (!st) return sh_error(SH_ENOMEM, "out of memory");
    st->s = s;
    st->env = env;
    st->o = *o;
    st->order = order;
    st->rl_method = -1;
    const int nall = s->mesh.nvert;
    st->nv = o->nverts > 0 && o->nverts < nall ? o->nverts : nall;
    const int n2 = order * order;
    st->verts = malloc(sizeof(int) * (size_t)nall);
    st->T = malloc(sizeof(double) * (size_t)st->nv * n2);
    st->L = malloc(sizeof(double) * 4 * (size_t)n2);
    st->RL = malloc(sizeof(double) * (size_t)n2);
    st->ref = malloc(sizeof(double) * (size_t)st->nv);
    st->se = malloc(sizeof(double) * (size_t)st->nv);
    st->B = malloc(sizeof(double) * (size_t)st->nv);
    if (!st->verts || !st->T || !st->L || !st->RL || !st->ref || !st->se || !st->B) {
        sh_study_free(st);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    /* a seeded random subset (partial Fisher-Yates), then sorted */
    for (int v = 0; v < nall; v++) st->verts[v] = v;
    uint64_t x = (uint64_t)o->seed * 0x2545F4914F6CDD1Dull + 17;
    if (st->nv < nall) {
        for (int k = 0; k < st->nv; k++) {
            const int j = k + (int)(sh__uniform(&x) * (nall - k));
            const int t = st->verts[k];
            st->verts[k] = st->verts[j];
            st->verts[j] = t;
        }
        for (int k = 1; k < st->nv; k++) /* insertion sort of the chosen ones */
            for (int j = k; j > 0 && st->verts[j - 1] > st->verts[j]; j--) {
                const int t = st->verts[j];
                st->verts[j] = st->verts[j - 1];
                st->verts[j - 1] = t;
            }
    }
    sh_transfer_opts to = {0};
    to.kind = SH_TRANSFER_SHADOWED;
    to.order = order;
    to.rays = o->rays;
    to.seed = o->seed;
    to.albedo = o->albedo;
    to.ray_eps = o->ref.ray_eps;
    to.threads = o->threads;
    to.verts = st->nv < nall ? st->verts : NULL;
    to.nverts = st->nv;
    to.progress = o->progress;
    to.progress_ctx = o->progress_ctx;
    int e = sh_transfer(s, &to, st->T, &st->info.transfer);
    if (!e) e = sh_env_project(env, order, SH_CS, st->L);
    if (!e) e = sh_study_set_rotation(st, NULL);
    if (e) {
        sh_study_free(st);
        return e;
    }
    st->info.nverts = st->nv;
    st->info.max_order = order;
    *out = st;
    return SH_OK;
}

int sh_study_set_rotation(sh_study *st, const sh_rotation *rot)
{
    if (!st) return sh_error(SH_EINVAL, "sh_study_set_rotation: no study");
    int e;
    if (rot) st->rot = *rot;
    else if ((e = sh_rotation_from_euler(0, 0, 0, &st->rot))) return e;
    st->rl_method = -1;
    sh_reference_opts ro = st->o.ref;
    ro.albedo = st->o.albedo;
    ro.threads = st->o.threads;
    ro.progress = st->o.progress;
    ro.progress_ctx = st->o.progress_ctx;
    if (!ro.seed) ro.seed = st->o.seed + 1;
    e = sh_shade_reference(st->s, st->env, rot, st->nv < st->s->mesh.nvert ? st->verts : NULL, st->nv, &ro, st->ref,
                           st->se, &st->info.reference);
    if (e) return e;
    double s2 = 0, r2 = 0;
    for (int k = 0; k < st->nv; k++) {
        s2 += st->se[k] * st->se[k];
        r2 += st->ref[k] * st->ref[k];
    }
    st->info.ref_l2 = r2 > 0 ? sqrt(s2 / r2) : 0;
    return SH_OK;
}

int sh_study_error(sh_study *st, sh_rot_method method, int order, sh_shade_err *err)
{
    if (!st || !err || order < 1 || order > st->order) return sh_error(SH_EINVAL, "sh_study_error: order out of 1..%d", st ? st->order : 0);
    if (st->rl_method != (int)method) {
        /* the luminance channel (the first of Y, R, G, B), rotated */
        const int e = sh_scene_rotate_coeffs(st->order, SH_CS, method, &st->rot, 1, st->L, st->RL);
        if (e) return e;
        st->rl_method = (int)method;
    }
    int e = sh_shade(st->nv, st->order, st->T, order, st->RL, st->B);
    if (!e) e = sh_shade_error(st->nv, st->B, st->ref, st->se, err);
    return e;
}

int sh_study_info_get(const sh_study *st, sh_study_info *info)
{
    if (!st || !info) return sh_error(SH_EINVAL, "sh_study_info_get: bad arguments");
    *info = st->info;
    return SH_OK;
}

const int *sh_study_vertices(const sh_study *st, int *n)
{
    if (n) *n = st ? st->nv : 0;
    return st ? st->verts : NULL;
}
