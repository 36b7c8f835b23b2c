/* study.c — shading error of SH lighting on a scene: transfer, lighting and
 * reference at a vertex subset; error per order and per rotation method; the
 * reference refined by pooling more replications.  The decisions made from
 * these errors, and the rule that trusts them: study_decide.c. */
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
    double *B, *B2;   /* scratch */
    int identity;     /* the rotation is the identity (the reference was computed with rot NULL) */
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
    free(st->B2);
    free(st);
}

int sh_study_create(const sh_scene *s, const sh_env *env, const sh_study_opts *o, sh_study **out)
{
    if (!s || !env || !o || !out) return sh_error(SH_EINVAL, "sh_study_create: bad arguments");
    *out = NULL;
    const int order = o->max_order > 0 ? o->max_order : 12;
    if (order > 64) return sh_error(SH_EINVAL, "study: order %d > 64", order);
    if (o->nverts < 0) return sh_error(SH_EINVAL, "study: negative vertex count");
    if (o->refine < 0) return sh_error(SH_EINVAL, "study: negative refinement cap %d", o->refine);
    sh_study *st = calloc(1, sizeof *st);
    if (!st) return sh_error(SH_ENOMEM, "out of memory");
    st->s = s;
    st->env = env;
    st->o = *o;
    st->order = order;
    st->rl_method = -1;
    const int reps = o->ref.replications > 0 ? o->ref.replications : 4;
    const int refine = o->refine > 0 ? o->refine : 16;
    st->info.max_replications = refine > 1000 / reps ? 1000 : refine * reps;
    if (st->info.max_replications < reps) st->info.max_replications = reps;
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
    st->B2 = malloc(sizeof(double) * (size_t)st->nv);
    if (!st->verts || !st->T || !st->L || !st->RL || !st->ref || !st->se || !st->B || !st->B2) {
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

/* ref_l2 = √Σ se² / √Σ ref² over the vertices studied */
static void update_ref_l2(sh_study *st)
{
    double s2 = 0, r2 = 0;
    for (int k = 0; k < st->nv; k++) {
        s2 += st->se[k] * st->se[k];
        r2 += st->ref[k] * st->ref[k];
    }
    st->info.ref_l2 = r2 > 0 ? sqrt(s2 / r2) : 0;
}

/* The reference's options: the study's, its threads and progress, the
 * seed (0: the study's + 1), replications first..first + count − 1. */
static sh_reference_opts ref_opts(const sh_study *st, int first, int count)
{
    sh_reference_opts ro = st->o.ref;
    ro.albedo = st->o.albedo;
    ro.threads = st->o.threads;
    ro.progress = st->o.progress;
    ro.progress_ctx = st->o.progress_ctx;
    if (!ro.seed) ro.seed = st->o.seed + 1;
    ro.first_replication = first;
    ro.replications = count;
    return ro;
}

int sh_study_set_rotation(sh_study *st, const sh_rotation *rot)
{
    if (!st) return sh_error(SH_EINVAL, "sh_study_set_rotation: no study");
    int e;
    if (rot) st->rot = *rot;
    else if ((e = sh_rotation_from_euler(0, 0, 0, &st->rot))) return e;
    st->rl_method = -1;
    const sh_reference_opts ro = ref_opts(st, 0, st->o.ref.replications);
    st->identity = rot == NULL;
    e = sh_shade_reference(st->s, st->env, rot, st->nv < st->s->mesh.nvert ? st->verts : NULL, st->nv, &ro, st->ref,
                           st->se, &st->info.reference);
    if (e) return e;
    st->info.replications = ro.replications > 0 ? ro.replications : 4;
    update_ref_l2(st);
    return SH_OK;
}

/* Pooling two sets of replications of one vertex (Chan et al. 1979): with
 * n_a, n_b replications, means m_a, m_b and standard errors se_a, se_b
 * (se² = var/n), n = n_a + n_b, δ = m_b − m_a,
 *   m  = m_a + δ n_b/n,
 *   M2 = (n_a − 1) n_a se_a² + (n_b − 1) n_b se_b² + δ² n_a n_b / n,
 *   se = √(M2 / ((n − 1) n)),
 * the mean and standard error of the n replications together, without the
 * cancellation of Σx² − n m². */
static void pool(int na, double *m, double *se, int nb, double mb, double seb)
{
    const int n = na + nb;
    const double d = mb - *m;
    const double M2 = (na - 1.0) * na * *se * *se + (nb - 1.0) * nb * seb * seb + d * d * na * nb / n;
    *m += d * nb / n;
    *se = sqrt(fmax(0.0, M2) / ((n - 1.0) * n));
}

int sh_study_refine(sh_study *st, int replications)
{
    if (!st) return sh_error(SH_EINVAL, "sh_study_refine: no study");
    const int have = st->info.replications, cap = st->info.max_replications;
    if (replications <= have) return SH_OK;
    if (replications > cap)
        return sh_error(SH_EINVAL, "sh_study_refine: %d replications exceed the cap of %d", replications, cap);
    /* at least 2 more (a standard error needs two), within the cap */
    const int more = replications - have >= 2 ? replications - have : 2;
    if (have + more > cap)
        return sh_error(SH_EINVAL, "sh_study_refine: %d replications exceed the cap of %d", have + more, cap);
    const sh_reference_opts ro = ref_opts(st, have, more);
    sh_transfer_stats rs;
    int e = sh_shade_reference(st->s, st->env, st->identity ? NULL : &st->rot, st->nv < st->s->mesh.nvert ? st->verts : NULL,
                               st->nv, &ro, st->B, st->B2, &rs);
    if (e) return e;
    for (int k = 0; k < st->nv; k++) pool(have, &st->ref[k], &st->se[k], more, st->B[k], st->B2[k]);
    sh_transfer_stats *t = &st->info.reference;
    t->rays += rs.rays;
    t->seconds += rs.seconds;
    t->rays_per_s = t->seconds > 0 ? t->rays / t->seconds : 0;
    t->rays_per_vertex += rs.rays_per_vertex;
    st->info.replications = have + more;
    update_ref_l2(st);
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
