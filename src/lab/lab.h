/* lab/lab.h — the workbench around the numerical library (not installed):
 * the interleaved timing engine and machine-load probes (bench.c), sweeps
 * split into shards (shard.c), the planner's timed choice (planner.c), and
 * the removal of temporary files on a signal (io/tempfile.c).  Used by the
 * command-line tool, the experiments and the tests; built as
 * libshlab_lab.a, on top of libshlab.  Nothing in libshlab depends on it.
 */
#ifndef SHLAB_LAB_H
#define SHLAB_LAB_H

#include "shlab.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- shards (shard.c) ------------------------------------------------------
 * A long sweep (work items 0..n−1 in the order of the unsharded run) split
 * into N independent processes.  Items are dealt forth and back: with
 * r = j mod 2N, item j belongs to shard r if r < N, else to 2N−1−r
 * (N = 2: 0 1 1 0 0 1 1 0 ...), so costs that grow with j are shared evenly.
 * A work item's result must not depend on which shard computed it (seeds
 * come from the item, not from a running generator). */
#define SH_SHARD_MAX 100000
typedef struct {
    int index, count; /* I and N; count 1 = the whole sweep */
} sh_shard;
#define SH_SHARD_ALL {0, 1}
/* Parse "I/N" (decimal, 0 <= I < N <= SH_SHARD_MAX). */
int sh_shard_parse(const char *s, sh_shard *out);
/* Non-zero if shard s owns item j (always when s is NULL or count is 1). */
int sh_shard_owns(const sh_shard *s, long item);
/* The items of a sweep that shard s owns, as the library's sweeps take them
 * (s NULL or count 1: every item).  items must not outlive s. */
sh_items sh_shard_items(const sh_shard *s);

/* ---- timing (bench.c) -------------------------------------------------------- */
/* Timing of the rotation methods (lab/bench.c) and the choice of the
 * cheapest method for an error budget (rotation_choose.c).  Generic over the
 * methods table: every method built in (including the Taylor approximations
 * once registered) can be timed, measured and chosen. */
typedef enum {
    SH_BENCH_PER_ROTATION = 0, /* per vector: matrix → sh_rotation → plan_set → apply */
    SH_BENCH_BATCHED,          /* one set, then `batch` vectors applied; per vector */
    SH_BENCH_KROT              /* `batch` rotations applied to `batch` vectors in one
                                  sh_rot_plan_rotate_many(_quat) call (structure of
                                  arrays); per vector */
} sh_bench_mode;
/* How the rotation reaches the plan:
 *   EULER   the user's 3×3 matrix → ZYZ angles (sh_euler_from_matrix) →
 *           sh_rot_plan_set; vectors as double (sh_rot_plan_apply) — the
 *           path every earlier version of shlab timed;
 *   MATRIX  sh_rot_plan_set_matrix (no angles), vectors in the plan's
 *           precision: float plans take float matrices and vectors
 *           (sh_rot_plan_set_matrix_f, sh_rot_plan_apply_f); batched mode
 *           applies the batch as one sh_rot_plan_apply_many call.
 *   QUAT    sh_rot_plan_set_quat(_f) (w, x, y, z) in the plan's precision,
 *           like MATRIX otherwise; k-rotations then take quaternions
 *           (sh_rot_plan_rotate_many_quat(_f)).
 * SH_BENCH_KROT with EULER takes matrices. */
typedef enum { SH_BENCH_INPUT_EULER = 0, SH_BENCH_INPUT_MATRIX, SH_BENCH_INPUT_QUAT } sh_bench_input;
#define SH_BENCH_NINPUTS 3
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

/* ---- The interleaved timing engine (lab/bench.c) ---------------------
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
/* The pool every rotation entry cycles through: SH_BENCH_POOL rotations
 * (α, γ uniform in (−π, π], β uniform in [0, max_beta], from seed) into R and
 * SH_BENCH_POOL vectors of nc coefficients uniform in [−1, 1) into vin. */
#define SH_BENCH_POOL 64
void sh_bench_pool(uint64_t seed, double max_beta, int nc, double (*R)[9], double *vin);
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


/* ---- plug-in kernels (plugin.c) ---------------------------------------------
 * A user's rotation kernel in a shared library (shlab/kernel.h), run in a
 * child process with a time limit and guarded buffers (plugin.c says how):
 * a crash, a hang or an out-of-bounds write is reported, never suffered. */
typedef enum {
    SH_PLUGIN_MATRIX_D, SH_PLUGIN_MATRIX_F, SH_PLUGIN_QUAT_D, SH_PLUGIN_QUAT_F, SH_PLUGIN_EULER_D,
    SH_PLUGIN_EULER_F, SH_PLUGIN_MATRIX_BATCH_D, SH_PLUGIN_MATRIX_BATCH_F, SH_PLUGIN_ABI_COUNT
} sh_plugin_abi;
const char *sh_plugin_abi_name(sh_plugin_abi a);
int sh_plugin_abi_parse(const char *s, sh_plugin_abi *out);
/* The arithmetic the ABI's type implies (…-f: float). */
sh_precision sh_plugin_abi_precision(sh_plugin_abi a);
typedef struct {
    char lib[1024], symbol[256];
    sh_plugin_abi abi;
    double timeout_s; /* wall and CPU seconds for the whole run (default 10) */
} sh_plugin;
/* "LIB.so:SYMBOL" (a bare file name is taken in the current directory);
 * the file must be a regular file.  Nothing is loaded here. */
int sh_plugin_parse(const char *spec, sh_plugin_abi abi, sh_plugin *out);
/* What happened to each case of a fixture run. */
enum { SH_PLUGIN_CASE_NOT_RUN = 0, SH_PLUGIN_CASE_RAN, SH_PLUGIN_CASE_DECLINED, SH_PLUGIN_CASE_ERROR };
typedef struct {
    int ran, declined, errors; /* cases: returned OK, SHLAB_KERNEL_UNSUPPORTED, another code */
    int failed;                /* the run ended early: failure says why */
    int open_failed;           /* ... because the library or symbol did not load */
    int current;               /* the case running when it ended (−1: none) */
    char failure[320];
} sh_plugin_report;
/* Every case not skipped through the kernel: got[k] (outputs; NaN where it
 * returned a failure code), status[k] (SH_PLUGIN_CASE_*).  SH_OK whatever
 * the kernel did (rep says); SH_EIO if no child process could be started. */
int sh_plugin_run_fixture(const sh_plugin *p, const sh_fixture *fx, const unsigned char *skip, double **got,
                          unsigned char *status, sh_plugin_report *rep);

/* The plug-in timed beside shlab's methods at one order, interleaved (the
 * engine above, paired ratios and its noise rule), in a child process: the
 * kernel on the pool of sh_bench_pool in the ABI's form (a batch ABI takes
 * `batch` rotations per call), each method on the path (input, mode, batch)
 * in the ABI's precision. */
#define SH_PLUGIN_BENCH_MAX_METHODS 4
typedef struct {
    int order;
    const sh_rot_method *methods;
    int nmethods;
    sh_bench_input input;
    sh_bench_mode mode;
    int batch;
    sh_bench_opts bench; /* seed, β range, convention of the methods' plans */
    sh_bench_cfg cfg;
} sh_plugin_bench_opts;
typedef struct {
    sh_bench_stats stats[1 + SH_PLUGIN_BENCH_MAX_METHODS]; /* 0: the plug-in, then the methods */
    sh_bench_ratio ratio[SH_PLUGIN_BENCH_MAX_METHODS];     /* plug-in / method i, paired by round */
    sh_bench_noise noise;
    int failed;          /* the kernel crashed, hung, ...: failure says how */
    char failure[320];
} sh_plugin_bench_result;
int sh_plugin_bench(const sh_plugin *p, const sh_plugin_bench_opts *o, sh_plugin_bench_result *res);

/* ---- shader kernels (shader.c) ------------------------------------------------
 * A user's compute shader (GLSL, HLSL or SPIR-V) under the convention of
 * docs/check-your-kernel.md ("Shaders"), compiled by shaderc's library and
 * run on a Vulkan device (lavapipe, a CPU device, where there is no GPU) in
 * the sandbox.  Built without Vulkan, the calls are SH_ENOTSUP. */
typedef enum { SH_SHADER_MATRIX = 0, SH_SHADER_QUAT, SH_SHADER_EULER } sh_shader_form;
#define SH_SHADER_NFORMS 3
const char *sh_shader_form_name(sh_shader_form f);
int sh_shader_form_parse(const char *s, sh_shader_form *out);
typedef struct {
    char path[1024], entry[128];
    uint32_t *spirv;
    size_t nwords;
    sh_shader_form form; /* how the rotations reach it */
    int device;          /* Vulkan device index, −1: the first GPU, else the first device */
    double timeout_s;    /* per dispatch (default 10) */
} sh_shader;
/* Read and compile (by the name: .glsl/.comp GLSL, .hlsl HLSL, .spv
 * SPIR-V as is); entry: the entry point (NULL: "main"); defines: the
 * preprocessor's macros, "NAME[=VALUE],..." (NULL: none).  A source that
 * does not compile is SH_EFORMAT with the compiler's message on one line. */
int sh_shader_load(const char *path, const char *entry, const char *defines, sh_shader *out);
void sh_shader_free(sh_shader *s);
typedef struct {
    sh_plugin_report cases; /* as a plug-in's: ran, declined, errors, failure */
    char device[256], driver[256];
    int is_cpu;
} sh_shader_report;
/* Every case not skipped, one dispatch per order; status[k] as a plug-in's
 * (a shader's status 1 declines an order, other non-zero values fail). */
int sh_shader_run_fixture(const sh_shader *s, const sh_fixture *fx, const unsigned char *skip, double **got,
                          unsigned char *status, sh_shader_report *rep);
/* Dispatches of K rotations (each k of k[]) timed interleaved with shlab's
 * CPU kernel cpu_method rotating K rotations at once in float
 * (sh_rot_plan_rotate_many_f, at most 4096 per call). */
#define SH_SHADER_BENCH_MAX_K 24
typedef struct {
    int order;
    int nk, k[SH_SHADER_BENCH_MAX_K];
    sh_rot_method cpu_method;
    sh_bench_opts bench; /* seed, β range, convention */
    sh_bench_cfg cfg;
} sh_shader_bench_opts;
typedef struct {
    sh_bench_stats shader[SH_SHADER_BENCH_MAX_K], cpu[SH_SHADER_BENCH_MAX_K]; /* ns per rotation */
    sh_bench_ratio ratio[SH_SHADER_BENCH_MAX_K]; /* shader / cpu, paired by round */
    sh_bench_noise noise[SH_SHADER_BENCH_MAX_K];
    double max_error[SH_SHADER_BENCH_MAX_K]; /* the first dispatch's outputs against zxzxz in double */
    sh_shader_report report;
} sh_shader_bench_result;
int sh_shader_bench(const sh_shader *s, const sh_shader_bench_opts *o, sh_shader_bench_result *res);

/* ---- the planner's choice (planner.c) ----------------------------------------
 * The path a user runs: how the rotation arrives (matrix, quaternion or
 * Euler angles) and how many vectors one call rotates. */
typedef struct {
    sh_bench_input input; /* default SH_BENCH_INPUT_MATRIX */
    sh_bench_mode mode;   /* per-rotation, batched (one rotation, `batch`
                             vectors) or k-rotations (`batch` rotations) */
    int batch;            /* vectors per call beyond per-rotation (≥ 1) */
    int live;             /* also time the candidates now (interleaved) */
} sh_rot_path;
#define SH_ROT_PATH_DEFAULT {SH_BENCH_INPUT_MATRIX, SH_BENCH_PER_ROTATION, 1, 0}
typedef struct {
    sh_rot_method method;
    int exact;
    double max_error;  /* largest error over the β grid (the chosen measure) */
    double worst_beta; /* where */
    double ns_per_rotation; /* the ranking cost: the model's (sh_cost_model),
                               or the live time where the model has none */
    double mults;
    int ok;            /* max_error ≤ tolerance */
    int from_model;    /* ns_per_rotation is the model's: 1 on the path asked
                          for, 2 its one-at-a-time cost from a matrix (the
                          calibration has no row of the method on that path);
                          0: timed live */
    sh_rot_kernel kernel;  /* the kernel auto picks */
    double instructions;   /* per rotated vector (model; 0 if none) */
    /* path.live: the interleaved timing now (ns per rotated vector) */
    double live_ns, live_q1, live_q3;
    int live_disagrees; /* the live median is outside [model/1.5, model·1.5] */
} sh_rot_candidate;
/* cand receives up to SH_ROT_NMETHODS candidates (sorted: admissible ones by
 * cost first, then the others by error); *ncand their count; *choice and
 * *runner_up index cand (−1 when none).  path NULL: the default path.  The
 * cost is the model's unless o->cost is given (tests); a method the model
 * does not cover at the order is timed live.  *noisy (may be NULL) is set
 * when a live timing broke the noise rule. */
int sh_rot_choose(const sh_rot_choose_opts *o, const sh_rot_path *path, sh_rot_candidate *cand, int *ncand,
                  int *choice, int *runner_up, sh_bench_noise *noise);

/* ---- the cost model (cost_model.c) -------------------------------------------
 * The cost of a rotation on a path users run, from instructions counted
 * under callgrind and a committed calibration (data/cost_model.tsv, written
 * by `make report`): deterministic, the same on every run. */
typedef struct {
    int order, batch;     /* batch: vectors per call in the calibration run */
    sh_rot_kernel kernel; /* the kernel auto picks for it */
    double instructions;  /* per rotated vector */
    double mults;         /* counted multiplications per rotated vector */
    double ns_per_instruction; /* the calibration used */
    double ns;            /* the model's ns per rotated vector */
    int interpolated;     /* the order lies between two measured ones */
} sh_cost;
/* The cost of (order, method, precision, input, mode).  SH_ENOTSUP outside
 * the orders the table covers for that path (sh_cost_model_range). */
int sh_cost_model(int order, sh_rot_method m, sh_precision p, sh_bench_input in, sh_bench_mode md,
                  sh_cost *out);
/* The smallest and largest order measured for the path; 0 if none. */
int sh_cost_model_range(sh_rot_method m, sh_precision p, sh_bench_input in, sh_bench_mode md, int *lo,
                        int *hi);
/* Where the calibration comes from (revision, date, machine), "" if the
 * build has no table. */
const char *sh_cost_model_source(void);

/* ---- temporary files (io/tempfile.c) ------------------------------------------- */
/* Remove every temporary file that a writer of this library (sh_exr_write,
 * ...) has created and not yet renamed into place.  Async-signal-safe: meant
 * for SIGINT/SIGTERM handlers and atexit. */
void sh__temp_files_unlink(void);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_LAB_H */
