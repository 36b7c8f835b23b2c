/* planner.c — the cheapest rotation method for an error budget (`shlab
 * plan`): the errors on the β grid from the library (sh_rot_choose_errors,
 * measure/rotation_choose.c), the costs from the cost model on the path the
 * user runs (cost_model.c: instructions × a committed calibration, so the
 * same question gets the same answer on every run), the admissible methods
 * ranked by cost.  With path->live the candidates are also timed now by the
 * interleaved engine (bench.c), and a live figure more than 1.5× away from
 * the model's is flagged. */
#include "lab/lab.h"

#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* how far a live time may stray from the model before it is flagged */
#define PLAN_LIVE_FACTOR 1.5

static int cand_cmp(const void *a, const void *b)
{
    const sh_rot_candidate *x = a, *y = b;
    if (x->ok != y->ok) return y->ok - x->ok;
    if (x->ok) return (x->ns_per_rotation > y->ns_per_rotation) - (x->ns_per_rotation < y->ns_per_rotation);
    return (x->max_error > y->max_error) - (x->max_error < y->max_error);
}

/* Each candidate's largest error over the β grid and where it occurs. */
static int grid_worst(const sh_rot_choose_opts *o, const sh_rot_method *ms, int nm, int nsteps,
                      sh_rot_candidate *cand)
{
    const int nbeta = nsteps - 1;
    double *own = NULL;
    const double *err = o->grid_errors;
    if (!err) {
        if (!(own = malloc(sizeof *own * (size_t)nsteps * (nm ? nm : 1))))
            return sh_error(SH_ENOMEM, "plan: out of memory");
        const int st = sh_rot_choose_errors(o, NULL, own);
        if (st) { free(own); return st; }
        err = own;
    }
    for (int k = 0; k < nm; k++) {
        cand[k] = (sh_rot_candidate){.method = ms[k], .exact = sh_rot_method_is_exact(ms[k])};
        for (int j = 0; j < nsteps; j++) {
            const double v = err[(size_t)j * nm + k];
            if (j == 0 || v > cand[k].max_error) {
                cand[k].max_error = v;
                cand[k].worst_beta = nbeta ? o->max_beta * j / nbeta : 0;
            }
        }
    }
    free(own);
    return SH_OK;
}

/* The bench options of the path: rotations of the scene's β range. */
static sh_bench_opts path_bench_opts(const sh_rot_choose_opts *o, const sh_rot_path *p)
{
    sh_bench_opts bo = SH_BENCH_OPTS_DEFAULT;
    bo.max_beta = o->max_beta;
    bo.conv = o->conv;
    bo.input = p->input;
    bo.batch = p->mode == SH_BENCH_PER_ROTATION ? 1 : p->batch;
    return bo;
}

/* Live: every candidate in `which` one entry, timed interleaved in one run. */
static int time_live(const sh_rot_choose_opts *o, const sh_rot_path *p, sh_rot_candidate *cand, int nm,
                     const int *which, sh_bench_noise *noise)
{
    sh_bench_entry ent[SH_ROT_NMETHODS];
    sh_bench_stats bs[SH_ROT_NMETHODS];
    int idx[SH_ROT_NMETHODS], ne = 0, st = SH_OK;
    const sh_bench_opts bo = path_bench_opts(o, p);
    for (int k = 0; k < nm && !st; k++)
        if (which[k] && !(st = sh_rot_bench_entry(o->order, cand[k].method, o->prec, p->mode, &bo, &ent[ne])))
            idx[ne++] = k;
    sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
    cfg.min_sample_ms = o->target_ms > 0 ? o->target_ms : 2.0;
    cfg.samples = o->repeat > 0 ? o->repeat : 11;
    if (!st && ne > 0) st = sh_bench_interleaved(ent, ne, &cfg, NULL, bs, noise);
    for (int i = 0; i < ne; i++) {
        sh_rot_candidate *c = &cand[idx[i]];
        if (!st) {
            c->live_ns = bs[i].ns_median;
            c->live_q1 = bs[i].ns_q1;
            c->live_q3 = bs[i].ns_q3;
            if (!c->mults) c->mults = ent[i].mults;
        }
        sh_bench_entry_free(&ent[i]);
    }
    return st;
}

/* Each candidate's cost: the test's function, else the model's, else (no
 * model for it) timed live; with path->live every one timed live too. */
static int costs(const sh_rot_choose_opts *o, const sh_rot_path *p, sh_rot_candidate *cand, int nm, int nsteps,
                 sh_bench_noise *noise)
{
    int need_live[SH_ROT_NMETHODS], any = 0;
    for (int k = 0; k < nm; k++) {
        sh_rot_candidate *c = &cand[k];
        sh_cost mc;
        c->kernel = sh_rot_plan_kernel_for(o->order, c->method, SH_KERNEL_AUTO);
        need_live[k] = p->live;
        if (o->cost) {
            c->ns_per_rotation = o->cost(o->cost_ctx, c->method, o->order);
            c->from_model = 1;
        } else if (sh_cost_model(o->order, c->method, o->prec, p->input, p->mode, &mc) == SH_OK ||
                   /* a path the calibration left out for this method (the O(n⁴)
                    * methods are not batched there): its one-at-a-time cost,
                    * an upper bound of what batching can cost per vector */
                   (sh_cost_model(o->order, c->method, o->prec, SH_BENCH_INPUT_MATRIX, SH_BENCH_PER_ROTATION, &mc) ==
                        SH_OK && (c->from_model = 2))) {
            c->ns_per_rotation = mc.ns;
            c->instructions = mc.instructions;
            c->mults = mc.mults;
            c->kernel = mc.kernel;
            if (!c->from_model) c->from_model = 1;
        } else {
            need_live[k] = 1;
        }
        any |= need_live[k];
    }
    if (any) {
        const int st = time_live(o, p, cand, nm, need_live, noise);
        if (st) return st;
    }
    for (int k = 0; k < nm; k++) {
        sh_rot_candidate *c = &cand[k];
        if (!c->from_model) c->ns_per_rotation = c->live_ns;
        else if (c->live_ns > 0 && c->from_model == 1)
            c->live_disagrees = c->live_ns > PLAN_LIVE_FACTOR * c->ns_per_rotation ||
                                c->live_ns * PLAN_LIVE_FACTOR < c->ns_per_rotation;
        /* the steps after the β grid's (sh_rot_choose_errors counts those) */
        if (o->progress) o->progress(o->progress_ctx, nsteps + 1 + k, nsteps + nm, "steps (costing the methods)");
    }
    return SH_OK;
}

int sh_rot_choose(const sh_rot_choose_opts *o, const sh_rot_path *path, sh_rot_candidate *cand, int *ncand,
                  int *choice, int *runner_up, sh_bench_noise *noise)
{
    *ncand = 0;
    *choice = *runner_up = -1;
    if (noise) memset(noise, 0, sizeof *noise);
    const sh_rot_path def = SH_ROT_PATH_DEFAULT;
    const sh_rot_path *p = path ? path : &def;
    if (p->batch < 1 || (int)p->input < 0 || p->input >= SH_BENCH_NINPUTS || (int)p->mode < 0 ||
        p->mode > SH_BENCH_KROT)
        return sh_error(SH_EINVAL, "plan: bad rotation path");
    sh_rot_method ms[SH_ROT_NMETHODS];
    int nm, nsteps;
    int st = sh_rot_choose_grid(o, ms, &nm, &nsteps);
    if (st || (st = grid_worst(o, ms, nm, nsteps, cand)) || (st = costs(o, p, cand, nm, nsteps, noise))) return st;
    for (int k = 0; k < nm; k++) cand[k].ok = cand[k].max_error <= o->tolerance;
    qsort(cand, (size_t)nm, sizeof *cand, cand_cmp);
    *ncand = nm;
    if (nm > 0 && cand[0].ok) *choice = 0;
    if (nm > 1 && cand[1].ok) *runner_up = 1;
    return SH_OK;
}
