/* shlab/measure.h — timing of the rotation methods (bench), the error engine and the
 * planner (plan).
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_MEASURE_H
#define SHLAB_MEASURE_H

#include "rotate.h"
#include "io.h"
#include "project.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Timing of the rotation methods (rotation_bench.c) and the choice of the
 * cheapest method for an error budget (rotation_choose.c).  Generic over the
 * methods table: every method built in (including the Taylor approximations
 * once registered) can be timed, measured and chosen. */
typedef enum {
    SH_BENCH_PER_ROTATION = 0, /* per vector: matrix → sh_rotation → plan_set → apply */
    SH_BENCH_BATCHED,          /* one set, then `batch` vectors applied; per vector */
    SH_BENCH_KROT              /* `batch` rotations applied to `batch` vectors in one
                                  sh_rot_plan_rotate_many call (structure of arrays);
                                  per vector */
} sh_bench_mode;
/* How the rotation reaches the plan:
 *   EULER   the user's 3×3 matrix → ZYZ angles (sh_euler_from_matrix) →
 *           sh_rot_plan_set; vectors as double (sh_rot_plan_apply) — the
 *           path every earlier version of shlab timed;
 *   MATRIX  sh_rot_plan_set_matrix (no angles), vectors in the plan's
 *           precision: float plans take float matrices and vectors
 *           (sh_rot_plan_set_matrix_f, sh_rot_plan_apply_f); batched mode
 *           applies the batch as one sh_rot_plan_apply_many call.
 * SH_BENCH_KROT always takes matrices (structure of arrays). */
typedef enum { SH_BENCH_INPUT_EULER = 0, SH_BENCH_INPUT_MATRIX } sh_bench_input;
const char *sh_bench_input_name(sh_bench_input i);
const char *sh_bench_mode_name(sh_bench_mode m);
typedef struct {
    int count;     /* timed iterations per repeat; 0 = calibrated to ~target_ms */
    int repeat;    /* timed repeats (median/min/max over them); ≥ 1 */
    int batch;     /* vectors per set in SH_BENCH_BATCHED; ≥ 1 */
    double target_ms; /* calibration target per repeat (count = 0); 0 = 5 ms */
    double max_beta;  /* the random rotations have β uniform in [0, max_beta] (the
                         z method is always timed at β = 0, its only domain) */
    uint64_t seed;    /* rotations and vectors (deterministic) */
    sh_convention conv; /* convention of the plans timed (default SH_CS) */
    sh_rot_kernel kernel; /* the plans' kernel (default SH_KERNEL_AUTO) */
    sh_bench_input input; /* default SH_BENCH_INPUT_EULER */
} sh_bench_opts;
#define SH_BENCH_OPTS_DEFAULT                                                                      \
    {0, 11, 16, 5.0, 3.14159265358979323846, 12345u, SH_CS, SH_KERNEL_AUTO, SH_BENCH_INPUT_EULER}
typedef struct {
    double ns_median, ns_min, ns_max; /* ns per rotated vector, over the repeats */
    double mults;        /* counted multiplications per rotated vector:
                            set + apply (per rotation), set/batch + apply (batched) */
    double mults_per_ns; /* mults / ns_median */
    uint64_t set_mults, apply_mults; /* as sh_rot_plan_mults reports them */
    int count;           /* iterations per repeat actually used */
    double checksum;     /* sum of outputs (keeps the work observable) */
    double ns_q1, ns_q3; /* quartiles over the repeats */
    double spread;       /* (ns_q3 − ns_q1) / ns_median */
    double sample_ms;    /* median duration of one timed repeat */
    int noisy;           /* the run breaks the noise criterion (sh_bench_noise) */
} sh_bench_result;
/* Time one (order, method, precision, mode).  A rotation is given to the
 * plan as a user holding an orthonormal 3×3 frame must: copy R, extract the
 * ZYZ angles (sh_euler_from_matrix), sh_rot_plan_set, sh_rot_plan_apply.
 * A warm-up repeat precedes the timed ones (CLOCK_MONOTONIC).  SH_EINVAL
 * for a method that is not built in or an order it refuses. */
int sh_rot_bench(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                 const sh_bench_opts *opts, sh_bench_result *res);
/* ns to build an sh_rotation from an orthonormal matrix as above (angles
 * only) — the part of every per-rotation time that no method can avoid. */
double sh_rot_bench_setup_ns(const sh_bench_opts *opts);

/* ---- The interleaved timing engine (rotation_bench.c) ---------------------
 * What to time is a table of entries, each a closure: run(ctx, count) does
 * `count` iterations of its work, `units` work units each (vectors rotated).
 * A new variant to compare is one more entry; one engine times them all.
 *
 * sh_bench_interleaved: each entry's count is calibrated so that one sample
 * lasts at least min_sample_ms; `warmup` untimed rounds follow (a warm-up
 * shorter than min_sample_ms raises the count again); then `samples` rounds,
 * and in every round each entry is timed once (CLOCK_MONOTONIC), round-robin,
 * the first entry shifted by one each round.  A slow drift of the machine's
 * load therefore reaches every entry alike, and two entries' samples of the
 * same round form a pair (sh_bench_paired_ratio).
 *
 * Noise criterion (sh_bench_noise; a run that breaks it is "noisy"):
 *   spread: some entry's (q3 − q1)/median over its samples > noise_spread
 *           (default 0.05);
 *   off-CPU: the timed samples spent more than noise_offcpu (default 0.02)
 *           of their wall time off this CPU (wall − CLOCK_THREAD_CPUTIME_ID:
 *           another process had the core);
 *   load:   other processes (and the hypervisor's steal) used more than
 *           noise_load CPUs (default 0.25) on average during the run
 *           (/proc/stat busy time minus this process's own, Linux only;
 *           runs shorter than 0.25 s are not judged by it).
 * Timings of a noisy run are still returned; callers must not turn them into
 * verdicts. */
typedef struct {
    const char *name;                  /* for messages */
    int (*run)(void *ctx, long count); /* SH_OK or an error status */
    void (*free)(void *ctx);           /* releases ctx (sh_bench_entry_free); may be NULL */
    void *ctx;
    double units; /* work units per iteration (0 counts as 1) */
    double mults; /* multiplications counted per unit (0: not counted) */
} sh_bench_entry;
typedef struct {
    double min_sample_ms; /* shortest sample (calibration target); 0 → 5 */
    int samples;          /* timed rounds; 0 → 15 */
    int warmup;           /* untimed rounds before them; < 0 → 0 */
    long count;           /* iterations per sample; 0 = calibrated */
    double noise_spread, noise_offcpu, noise_load; /* 0 → 0.05, 0.02, 0.25 */
    sh_progress_fn progress; /* optional: after each round */
    void *progress_ctx;
} sh_bench_cfg;
#define SH_BENCH_CFG_DEFAULT {5.0, 15, 1, 0, 0.05, 0.02, 0.25, NULL, NULL}
typedef struct {
    double ns_min, ns_q1, ns_median, ns_q3, ns_max; /* ns per unit over the samples */
    double spread;    /* (ns_q3 − ns_q1) / ns_median */
    double offcpu;    /* fraction of this entry's sample time spent off the CPU */
    double sample_ms; /* median duration of one sample */
    long count;       /* iterations per sample */
} sh_bench_stats;
typedef struct {
    int noisy;       /* the criterion above is broken */
    char why[200];   /* the parts broken, "" when quiet */
    double spread;   /* largest entry spread */
    double offcpu;   /* off-CPU fraction over all samples */
    double load;     /* CPUs used by other processes (−1: not known) */
    double seconds;  /* wall time of the whole run */
} sh_bench_noise;
/* samples: ne × cfg.samples ns per unit (entry-major, round r of entry i at
 * samples[i·S + r]); may be NULL.  st: ne results.  noise may be NULL. */
int sh_bench_interleaved(const sh_bench_entry *e, int ne, const sh_bench_cfg *cfg, double *samples,
                         sh_bench_stats *st, sh_bench_noise *noise);
/* The paired ratio a/b of two entries timed in the same rounds: median (and
 * quartiles) of the per-round ratios a[r]/b[r]; spread = (q3 − q1)/median;
 * noisy when spread > noise_spread (0 → 0.05). */
typedef struct { double median, q1, q3, spread; int noisy; } sh_bench_ratio;
int sh_bench_paired_ratio(const double *a, const double *b, int n, double noise_spread, sh_bench_ratio *r);
/* CPU seconds the whole machine has been busy (/proc/stat: all but idle and
 * iowait, steal included); < 0 where unknown.  Its increase over an interval,
 * minus the CPU time of one's own process (and children), divided by the
 * interval, is the load of other processes (the criterion's "load"). */
double sh_machine_busy_s(void);
/* An entry that times one rotation method as sh_rot_bench does (per rotation
 * or batched; units = vectors rotated per iteration; mults counted).  Free
 * it with sh_bench_entry_free. */
int sh_rot_bench_entry(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                       const sh_bench_opts *opts, sh_bench_entry *e);
/* Bytes sh_rot_bench_entry allocates for that entry (its plan and its pools
 * of rotations and vectors); the entries of one order live at once. */
double sh_rot_bench_entry_bytes(int order, sh_rot_method method, sh_precision prec, sh_bench_mode mode,
                                const sh_bench_opts *opts);
/* An entry for the matrix → ZYZ angles step alone (per rotation). */
int sh_rot_bench_setup_entry(const sh_bench_opts *opts, sh_bench_entry *e);
void sh_bench_entry_free(sh_bench_entry *e);
/* Instructions executed per unit, counted by valgrind's callgrind: each
 * entry runs n iterations untimed (warm-up), then n and 2n iterations each
 * between callgrind client requests, and ins[i] = (I(2n) − I(n)) / (n·units)
 * (the difference removes the calls' fixed cost).  The process must run as
 *   valgrind --tool=callgrind --instr-atstart=no --combine-dumps=yes
 *            --callgrind-out-file=FILE ...
 * and FILE is read back.  SH_ENOTSUP when not running under valgrind (or
 * built without valgrind's header). */
int sh_bench_instructions(const sh_bench_entry *e, int ne, long n, const char *callgrind_out,
                          double *ins);

/* Error of a method's rotation against the exact one (docs/CONVENTIONS.md,
 * "Taylor-approximated rotation"), computed generically: D = R_method −
 * R_exact for the rotation (α, β, γ) block by block, R_exact from the MPFR
 * reference plan (use_reference) or the zxzxz plan in double (accurate to
 * ~1e-15 for order ≤ 100; zxzxz then measures 0 against itself).  max = largest singular value of
 * D, mean = mean of all n² singular values (GSL one-sided Jacobi SVD per
 * band), lobe = ‖D c‖₂, c the unit coefficient vector of max(0, cosθ)^e
 * about +z (sh_lobe_zonal).  Since Z(α), Z(γ) are orthogonal and c is
 * zonal, these equal the measures of R_Y(β) − approx(R_Y(β)). */
typedef struct { double max, mean, lobe; } sh_rot_error;
typedef struct sh_rot_errws sh_rot_errws;
int sh_rot_errws_create(int order, double lobe_exp, int use_reference, sh_rot_errws **out);
/* The same with every plan (truth and methods) in convention conv (the
 * above: SH_CS).  The measures do not depend on it. */
int sh_rot_errws_create_conv(int order, double lobe_exp, int use_reference, sh_convention conv,
                             sh_rot_errws **out);
/* Set the rotation: computes the exact blocks once. */
int sh_rot_errws_set(sh_rot_errws *w, const sh_rotation *rot);
/* Error of a method (plans are created on first use and kept). */
int sh_rot_errws_eval(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err);
/* The same, also writing all order² singular values to sv (band l's, in
 * decreasing order, at sv[l²..l²+2l]) when sv is not NULL. */
int sh_rot_errws_eval_sv(sh_rot_errws *w, sh_rot_method method, sh_precision prec, sh_rot_error *err,
                         double *sv);
void sh_rot_errws_free(sh_rot_errws *w);

/* The cheapest method for an error budget (rotation_choose.c): every method
 * built in (reference excluded; z only if max_beta = 0) is measured (against
 * the MPFR reference up to order 32, zxzxz above) over the
 * β grid 0, h, 2h, …, max_beta (h ≤ beta_step) at seeded α, γ, and timed
 * (per rotation, all candidates interleaved in one sh_bench_interleaved run);
 * candidates whose largest error stays ≤ tolerance are ranked by ns_median. */
typedef enum { SH_MEASURE_LOBE = 0, SH_MEASURE_MAX } sh_error_measure;
const char *sh_error_measure_name(sh_error_measure m);
int sh_error_measure_parse(const char *s, sh_error_measure *out);
typedef struct {
    sh_rot_method method;
    int exact;
    double max_error;  /* largest error over the β grid (the chosen measure) */
    double worst_beta; /* where */
    double ns_per_rotation, mults;
    int ok;            /* max_error ≤ tolerance */
} sh_rot_candidate;
typedef struct {
    int order;
    double max_beta, tolerance, lobe_exp, beta_step;
    sh_error_measure measure;
    sh_precision prec;
    double target_ms; /* timing per repeat (0: 2 ms) */
    int repeat;       /* 0: 5 */
    sh_progress_fn progress; /* optional: after each β of the grid, then each method timed */
    void *progress_ctx;
    sh_convention conv;      /* convention of the plans measured and timed (0: SH_CS) */
    /* optional: the cost of a method instead of timing it (ns per rotation;
     * tests use it to be deterministic); mults are then not counted (0) */
    double (*cost)(void *ctx, sh_rot_method m, int order);
    void *cost_ctx;
    /* optional: the errors on the β grid, as sh_rot_choose_errors writes them
     * for every step (measured by shards of a sweep), instead of measuring */
    const double *grid_errors;
} sh_rot_choose_opts;
/* cand receives up to SH_ROT_NMETHODS candidates (sorted: admissible ones by
 * time first, then the others by error); *ncand their count; *choice and
 * *runner_up index cand (−1 when none). */
int sh_rot_choose(const sh_rot_choose_opts *o, sh_rot_candidate *cand, int *ncand, int *choice,
                  int *runner_up);
/* The β grid of sh_rot_choose as a sweep: the candidate methods (ms, *nm)
 * and the steps j = 0..nsteps−1 (β_j = max_beta·j/(nsteps−1); α, γ seeded by
 * j).  sh_rot_choose_errors writes err[j·nm + k], the error of ms[k] at step
 * j, for the steps shard owns (NULL: all; the others are left untouched);
 * progress counts those steps. */
int sh_rot_choose_grid(const sh_rot_choose_opts *o, sh_rot_method ms[SH_ROT_NMETHODS], int *nm, int *nsteps);
int sh_rot_choose_errors(const sh_rot_choose_opts *o, const sh_shard *shard, double *err);
/* The smallest order ≤ max_order whose projection of the image (luminance:
 * Y, or 0.2126R + 0.7152G + 0.0722B) has relative L2 residual ≤ tol on the
 * sphere, by Parseval: ε² = (‖f‖² − Σc²)/‖f‖², ‖f‖² by the same pixel
 * quadrature as the projection.  *order_out = −1 if none ≤ max_order; the
 * residuals per order 1..max_order into resid (may be NULL). */
int sh_order_for_image(const sh_image *img, sh_layout layout, double tol, int max_order,
                       int *order_out, double *resid);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_MEASURE_H */
