/* planner.c — the cheapest rotation method for an error budget (`shlab
 * plan`): the errors on the β grid from the library (sh_rot_choose_errors,
 * measure/rotation_choose.c), the methods timed by the lab's interleaved
 * engine (bench.c), the admissible ones ranked by time. */
#include "lab/lab.h"

#include "core/shlab_internal.h"

#include <stdlib.h>

static int cand_cmp(const void *a, const void *b)
{
    const sh_rot_candidate *x = a, *y = b;
    if (x->ok != y->ok) return y->ok - x->ok;
    if (x->ok) return (x->ns_per_rotation > y->ns_per_rotation) - (x->ns_per_rotation < y->ns_per_rotation);
    return (x->max_error > y->max_error) - (x->max_error < y->max_error);
}

int sh_rot_choose(const sh_rot_choose_opts *o, sh_rot_candidate *cand, int *ncand, int *choice,
                  int *runner_up)
{
    *ncand = 0;
    *choice = *runner_up = -1;
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm, nsteps;
    int st = sh_rot_choose_grid(o, ms, &nm, &nsteps);
    if (st) return st;
    const int nbeta = nsteps - 1;
    /* the errors on the β grid: given (measured by shards), or measured now */
    double *own = NULL;
    const double *err = o->grid_errors;
    if (!err) {
        if (!(own = malloc(sizeof *own * (size_t)nsteps * (nm ? nm : 1))))
            return sh_error(SH_ENOMEM, "plan: out of memory");
        if ((st = sh_rot_choose_errors(o, NULL, own))) { free(own); return st; }
        err = own;
    }
    for (int k = 0; k < nm; k++) {
        cand[k] = (sh_rot_candidate){ms[k], sh_rot_method_is_exact(ms[k]), 0, 0, 0, 0, 0};
        for (int j = 0; j < nsteps; j++) {
            const double v = err[(size_t)j * nm + k];
            if (j == 0 || v > cand[k].max_error) {
                cand[k].max_error = v;
                cand[k].worst_beta = nbeta ? o->max_beta * j / nbeta : 0;
            }
        }
    }
    free(own);
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    bo.max_beta = o->max_beta; /* rotations of the scene's range */
    bo.conv = o->conv;
    /* timing: every candidate one entry, interleaved in one run (measure.h) */
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.min_sample_ms = o->target_ms > 0 ? o->target_ms : 2.0;
    cfg.samples = o->repeat > 0 ? o->repeat : 5;
    sh_bench_entry ent[SH_ROT_NMETHODS];
    sh_bench_stats bs[SH_ROT_NMETHODS];
    double mults[SH_ROT_NMETHODS];
    for (int k = 0; k < nm && !o->cost && !st; k++)
        if ((st = sh_rot_bench_entry(o->order, ms[k], o->prec, SH_BENCH_PER_ROTATION, &bo, &ent[k])))
            for (int j = 0; j < k; j++) sh_bench_entry_free(&ent[j]);
    if (st) return st;
    if (!o->cost && nm > 0) {
        st = sh_bench_interleaved(ent, nm, &cfg, NULL, bs, NULL);
        for (int k = 0; k < nm; k++) {
            mults[k] = ent[k].mults;
            sh_bench_entry_free(&ent[k]);
        }
        if (st) return st;
    }
    for (int k = 0; k < nm; k++) {
        cand[k].ok = cand[k].max_error <= o->tolerance;
        if (o->cost) {
            cand[k].ns_per_rotation = o->cost(o->cost_ctx, ms[k], o->order);
            cand[k].mults = 0;
        } else {
            cand[k].ns_per_rotation = bs[k].ns_median;
            cand[k].mults = mults[k];
        }
        if (o->progress) o->progress(o->progress_ctx, nbeta + 2 + k, nbeta + 1 + nm, "steps (timing the methods)");
    }
    qsort(cand, (size_t)nm, sizeof *cand, cand_cmp);
    *ncand = nm;
    if (nm > 0 && cand[0].ok) *choice = 0;
    if (nm > 1 && cand[1].ok) *runner_up = 1;
    return SH_OK;
}

