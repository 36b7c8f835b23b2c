/* cli.h — shared pieces of the shlab command-line tool (not installed).
 *
 * Contract of every command (docs/CONVENTIONS.md "Output"):
 *  - the result is built completely as a JSON value, then rendered once as
 *    table, csv or json on stdout (so a failure never prints half a result);
 *  - bad usage or input: one line "shlab: error: ..." on stderr, exit 2;
 *  - a failed check or verification: exit 1; success: exit 0.
 */
#ifndef SHLAB_CLI_H
#define SHLAB_CLI_H

#include <jansson.h>
#include <stdio.h>

#include "shlab.h"
#include "lab/lab.h"
#include "cli_args.h"

#define CLI_EXIT_OK 0
#define CLI_EXIT_CHECK 1
#define CLI_EXIT_USAGE 2

typedef enum { CLI_TABLE = 0, CLI_CSV, CLI_JSON } cli_format;

typedef struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
    const cli_cmd *decl; /* the declaration: options, and --help printed from them */
} cli_command;

/* Print "shlab: error: <msg>" on stderr; returns CLI_EXIT_USAGE. */
int cli_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Fail with the library's last error for status st. */
int cli_fail_status(int st);

/* Strict parsers: the whole string must be consumed; NaN/Inf refused.
 * Return 0 on success, else print the error and return CLI_EXIT_USAGE. */
int cli_int(const char *opt, const char *s, int *out);
int cli_long(const char *opt, const char *s, long *out);
int cli_double(const char *opt, const char *s, double *out);
/* Comma/space separated list; *out is malloc'd (caller frees).  At most
 * CLI_MAX_NUMBERS values (four channels of order SHLAB_MAX_ORDER).  An
 * empty element (",,", a comma first or last) is an error, in every list. */
#define CLI_MAX_NUMBERS (SH_IMAGE_MAX_CHANNELS * SHLAB_MAX_ORDER * SHLAB_MAX_ORDER)
int cli_doubles(const char *opt, const char *s, double **out, int *n);
/* A list of words (methods, kernels, orders, ...) split as cli_doubles
 * splits numbers: *items[0..*n) point into one malloc'd block (free(*items)
 * frees it all); at least one element, none empty. */
int cli_split(const char *opt, const char *s, char ***items, int *n);
int cli_vec3(const char *opt, const char *s, double v[3]);
int cli_format_parse(const char *s, cli_format *out);
int cli_convention(const char *s, sh_convention *out);
int cli_order(const char *opt, const char *s, int *out);
/* The one wording for an order out of a command's range: "OPT: order N is
 * outside 1..MAX" (and " (why)" when given); max 0 means SHLAB_MAX_ORDER.
 * cli_order_max parses s first (an integer). */
int cli_order_check(const char *opt, int order, int max, const char *why);
int cli_order_max(const char *opt, const char *s, int max, const char *why, int *out);
/* A comma-separated list of at most max orders, each checked as cli_order does. */
int cli_orders(const char *opt, const char *s, int *out, int max, int *n);

/* Read a coefficient file: JSON with "coeffs" (array) or "channels"
 * ({name: array}), or plain text numbers.  Returns nchan vectors of length
 * *len concatenated in *out (malloc'd), channel names in names (may be NULL).
 * Bounded before reading by max_order (0: SHLAB_MAX_ORDER): a file larger
 * than four channels of that order need is refused unread, and one whose
 * text, or whose numbers once parsed, would not fit in memory. */
int cli_read_coeffs_file(const char *path, int max_order, double **out, int *len, int *nchan,
                         char names[SH_IMAGE_MAX_CHANNELS][8]);
/* The same from memory (buf[n] must be '\0'; `path` names it in messages). */
int cli_read_coeffs_mem(const char *buf, size_t n, const char *path, double **out, int *len,
                        int *nchan, char names[SH_IMAGE_MAX_CHANNELS][8]);
/* qsort comparison of doubles (ascending), and the median of v[0..n-1]
 * (sorts v in place; n >= 1). */
int cli_cmp_double(const void *a, const void *b);
double cli_median(double *v, int n);
/* Read a whole file (at most `max` bytes, else an error naming the limit)
 * into a malloc'd, NUL-terminated buffer.  `what` names the kind of file in
 * the messages ("cannot open fixture 'F': ..."). */
int cli_read_file(const char *what, const char *path, size_t max, char **buf, size_t *n);
/* Parse JSON text: duplicate keys and numbers outside double's range
 * (jansson would read "1e-400" as 0) are errors, as on the command line. */
int cli_json_parse(const char *buf, size_t n, const char *name, json_t **root);

/* The one error line for a JSON file that json_load_file could not read
 * (err_no: errno right after the call): "cannot open WHAT 'PATH': reason" or
 * "WHAT 'PATH' is not valid JSON: ... (line L, column C)". */
int cli_fail_json(const char *what, const char *path, int err_no, const json_error_t *err);

/* JSON builders. */
json_t *cli_json_array(const double *v, size_t n);
json_t *cli_json_matrix(const double *M, size_t rows, size_t cols);
/* Set root[key] = val (stealing val).  If root or val is NULL (allocation
 * failed, or a NaN was refused by json_real), frees both and returns NULL,
 * which cli_emit() reports as an error: a result is complete or not printed. */
json_t *cli_put(json_t *root, const char *key, json_t *val);
/* Non-zero if any number in the tree is not finite (jansson refuses NaN:
 * json_real returns NULL, so builders report failure via NULL as well). */
int cli_json_bad(const json_t *v);

/* Progress on stderr for long runs: nothing during the first second, then
 * at most one line a second ("cmd: done of total what, T s"), and a last
 * line when the work ends if any line was printed.  quiet: never. */
typedef struct {
    const char *cmd;
    int quiet, printed;
    double t0, last;
    int estimated;
    double t1; /* time of the first step (cli_progress_step_est) */
    double interval; /* seconds before the first line and between lines (SHLAB_PROGRESS_INTERVAL) */
} cli_progress;
void cli_progress_start(cli_progress *p, const char *cmd, int quiet);
/* An sh_progress_fn (ctx: cli_progress *). */
void cli_progress_step(void *ctx, int done, int total, const char *what);
/* The same, and after the second step one line with the total time it
 * extrapolates from the second step, when that is over 2 s
 * ("cmd: about N s in all (...)"); no closing line for a run that printed
 * no progress on the way (a single step that took a second, say). */
void cli_progress_step_est(void *ctx, int done, int total, const char *what);

/* 0 if `bytes` fit in the memory this process could still get
 * (sh__mem_available: MemAvailable, or ulimit -v when lower); otherwise one line "cmd: WHAT needs X GB of memory, only
 * Y GB is available" and CLI_EXIT_USAGE.  Call before allocating. */
int cli_mem_check(const char *cmd, double bytes, const char *what);

/* `shlab bench --peers` (cli_peers.c): shlab's transforms against libsharp. */
int cli_bench_peers(const cli_command *bench, int argc, char **argv);
/* `shlab bench --plugin`: a user's kernel on the frontier (cmd_bench_plugin.c). */
int cli_bench_plugin(const cli_command *bench, int argc, char **argv);
/* `shlab bench --shader`: a compute shader beside the CPU kernels (cmd_bench_shader.c). */
int cli_bench_shader(const cli_command *bench, int argc, char **argv);

/* Render `root` in `fmt` on stdout and release it; then, if stdout took it
 * all, rename the output files (cli_out_open) onto their targets, else
 * remove them.  Returns an exit code. */
int cli_emit(json_t *root, cli_format fmt);

/* Output files.  A command that writes files opens each one with
 * cli_out_open before its work (so an unwritable target fails first) and
 * writes it under the temporary name *tmp, next to the target.  cli_emit
 * commits them after the result is printed; an error, a failed write to
 * stdout or a signal removes them instead.  So no error truncates or removes
 * an existing file, and nothing is left behind.  Returns 0 or the exit code
 * after the error line. */
int cli_out_open(const char *cmd, const char *path, const char **tmp);
/* Record an input file (`what`: "fixture", "probe", ...) before reading it:
 * an output that names the same file (path or link), opened before or after,
 * is refused in one line.  Returns 0 or the exit code after the error line. */
int cli_input(const char *what, const char *path);
int cli_out_commit(void);
void cli_out_discard(void);
/* main: remove temporary files on SIGINT/SIGTERM/SIGHUP/SIGPIPE and at exit. */
void cli_signals_install(void);
/* cli_emit, before the result's first byte: from here the run finishes (stop
 * signals are held), so a stopped run has printed nothing. */
void cli_signals_commit(void);

/* The closing paragraph of every --help (where the conventions are written). */
extern const char cli_conventions_note[];
/* An option given where it does not apply is refused, never ignored — one
 * rule for every command: "CMD: OPT applies only to WHAT".  Returns 0 when
 * the option was not given or applies, else the exit code after the line. */
int cli_applies(const char *cmd, int given, const char *opt, int applies, const char *what);

const cli_command *cli_find(const char *name);
extern const cli_command cli_commands[];
extern const int cli_ncommands;

/* Options are declared per command and read by one parser (cli_args.h):
 * a command's cli_cmd table, its groups (rotation, sweep, scene, image...),
 * no process-global state. */

/* ---- rotations (cli_rotation.c) ------------------------------------------
 * The rotation options every rotation command takes:
 *   --euler A,B,G | --quat W,X,Y,Z | --matrix R00,...,R22 | --axis X,Y,Z --angle T,
 *   --inverse, --orthonormalize   (angles in radians unless --degrees). */
/* A list of numbers of a fixed count, as a declared option reads it
 * (cli_rotation_opts: --euler 3, --quat 4, --matrix 9, --axis 3). */
typedef struct {
    int n; /* numbers read: 0 when the option was not given */
    double v[9];
} cli_numbers;
typedef struct {
    cli_numbers euler, quat, matrix, axis;
    double angle;
    int have_angle, inverse, ortho;
    const char *form; /* cli_rotation_finish: "euler", "quat", "matrix", "axis-angle" or NULL */
} cli_rotation_args;
/* The rotation options as a declared group (cli_args.h): a command's table
 * includes it with CLI_GROUP(its_args, field, cli_rotation_opts), then calls
 * cli_rotation_finish. */
extern const cli_opt cli_rotation_opts[];
/* Declared --method (sh_rot_method; "auto": SH_ROT_AUTO, the command's
 * choice by order), --precision (sh_precision) and --kernel (sh_rot_kernel,
 * refused if this machine cannot run it): parse functions for CLI_CUSTOM. */
int cli_parse_method(const char *opt, const char *s, void *field);
int cli_parse_precision(const char *opt, const char *s, void *field);
int cli_parse_kernel(const char *opt, const char *s, void *field);
/* --method (default auto), --precision (double) and --kernel (auto) as one
 * declared group, for the commands that make the rotation they print
 * (rotate, rotmat): CLI_GROUP(its_args, field, cli_method_opts). */
typedef struct {
    sh_rot_method method; /* SH_ROT_AUTO: the command's choice by order */
    sh_precision prec;
    sh_rot_kernel kernel;
} cli_method_args;
extern const cli_opt cli_method_opts[];
/* Build the rotation (exactly one form required unless `optional`; then
 * *given says whether one was).  Returns 0 or an exit code. */
int cli_rotation_finish(const char *cmd, cli_rotation_args *r, int degrees, int optional,
                        int *given, sh_rotation *rot);
/* The rotation in every input form: {"euler":[α,β,γ],"quat":[w,x,y,z],
 * "matrix":[9],"axis":[3],"angle":t} (radians). */
json_t *cli_rotation_json(const sh_rotation *rot);
int cli_method(const char *s, sh_rot_method *out);



/* ---- angles and units (cli_angles.c) -------------------------------------
 * --degrees means angles in and angles out in degrees, in every command
 * (docs/CONVENTIONS.md "Angles and units"); every printed angle goes with a
 * "unit" field.  Warnings are one line "shlab: warning: ..." each on stderr,
 * printed when the command has finished; the exit status is not changed. */
void cli_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Print the warnings kept so far (main() calls it when the command returns):
 * only when rc is not CLI_EXIT_USAGE, whose one error line stays alone. */
void cli_warn_flush(int rc);
const char *cli_angle_unit(int degrees);          /* "degrees" or "radians" */
double cli_angle_out(double radians, int degrees); /* radians → the output unit */
/* Warn when an angle given in radians (degrees == 0) exceeds 2π in magnitude:
 * degrees given without --degrees, most likely.  what: e.g. "--beta". */
void cli_warn_radians(const char *cmd, const char *what, double value, int degrees);
/* The angle in radians (with the warning above). */
double cli_angle_in(const char *cmd, const char *what, double value, int degrees);
/* For an approximate method (taylor1, taylor1.5, taylor2): warn when the
 * rotation's β lies beyond the angle where the method's lobe error reaches
 * 1e-2, and give the estimated lobe error at β (sh_taylor_lobe_limit,
 * sh_taylor_lobe_error).  Nothing for exact methods. */
void cli_warn_approx_rotation(const char *cmd, sh_rot_method m, int order, const sh_rotation *rot,
                              int degrees);

/* Lights (sh_light_parse): 1 if the spec holds angles (cap:T, cie-clear and
 * cie-partly's sun position), so that the output says their unit; and the
 * 2π warning for the one angle that is not range-checked (the sun azimuth). */
int cli_light_has_angles(const sh_light *L);
void cli_light_warn(const char *cmd, const sh_light *L, int degrees);

/* ---- sharded sweeps (cli_sweep.c) -----------------------------------------
 * A sweep computes work items 0..n-1 (bands, angles, ...) in a fixed order.
 * With --shard I/N a command computes only the items shard I owns
 * (sh_shard_owns) and prints, instead of its result, a shard file of JSON
 * lines: a header with the command, the revision, I, N, n, the --format and
 * every parameter of the whole sweep; one {"item":j,"row":{...}} per item;
 * an end line with the number of rows.  `shlab merge` checks that the files
 * belong together (same command, revision, N, n, parameters), that no shard
 * and no item is missing or duplicated, and prints what the unsharded
 * command prints, byte for byte: both go through the kind's finish().
 * A kind may stop the sweep at a row (stops()): the rows after the first
 * such row are dropped, and a shard stops after its own first one. */
/* The fields of a row or of the parameters: key, JSON type (a real is a
 * JSON real: 1.0, never 1), whether it may be absent, and for integers
 * their range.  A list ends with key NULL. */
typedef enum {
    CLI_FIELD_INT, CLI_FIELD_REAL, CLI_FIELD_REAL_OR_NULL, CLI_FIELD_BOOL, CLI_FIELD_STRING,
    CLI_FIELD_REALS,        /* an array of reals (its length: check_row) */
    CLI_FIELD_INTS_OR_NULL, /* null, or an array of integers in [min, max] */
    CLI_FIELD_STRINGS,      /* an array of strings */
    CLI_FIELD_OBJECT
} cli_field_type;
typedef struct {
    const char *key;
    cli_field_type type;
    int optional;
    long long min, max; /* CLI_FIELD_INT, CLI_FIELD_INTS_OR_NULL (both 0: any) */
} cli_sweep_field;

typedef struct {
    const char *command;
    /* The command's result from its parameters and its rows (in item order,
     * up to the first stopping row; stolen).  NULL on failure. */
    json_t *(*finish)(const json_t *params, json_t *rows);
    /* Non-zero if this row ends the sweep (NULL: no row does). */
    int (*stops)(const json_t *params, const json_t *row);
    /* The exit status of a result (NULL: 0), e.g. CLI_EXIT_CHECK when plan
     * finds no method. */
    int (*exit_code)(const json_t *result);
    /* What a shard file may hold, checked by merge on every line it reads
     * (and by the sweep on what it writes): the parameters' fields, a row's
     * fields (exactly these, of these types), and check_row: 0 if `row` is
     * item j's row of a sweep of nitems (the band, angle or point item j
     * stands for, its arrays' lengths), else non-zero with the reason in why
     * (NULL: the fields only). */
    const cli_sweep_field *params_fields, *row_fields;
    int (*check_row)(const json_t *params, long nitems, long j, const json_t *row, char *why, size_t n);
    int timed; /* finish times something (plan times the methods: a second or more) */
} cli_sweep_kind;
/* 0 if obj has exactly the fields (types, ranges), else non-zero with the
 * reason in why ("field 'orth' is a string, not a real", ...). */
int cli_sweep_fields_ok(const cli_sweep_field *fields, const json_t *obj, char *why, size_t n);
/* A row of kind for item j: its fields and check_row.  0 or non-zero (why). */
int cli_sweep_row_ok(const cli_sweep_kind *kind, const json_t *params, long nitems, long j, const json_t *row,
                     char *why, size_t n);
/* `shlab merge` of shard files in memory (its fuzz harness): buf[q] of
 * len[q] bytes, named name[q] in messages.  0 with *result the merged
 * result (not printed) and *code its exit status; else the exit code after
 * the one error line.  timed 0: a sweep whose finish times something
 * (kind->timed) gives {"params","rows"}, checked and joined, instead. */
int cli_merge_mem(int nf, const char *const *buf, const size_t *len, const char *const *name, int timed,
                  json_t **result, int *code);

/* The options every sweep takes, declared once (cli_sweep.c): --quiet,
 * --shard I/N and --format.  A sweep's table ends with
 * CLI_GROUP(its_args, field, cli_sweep_opts); cli_sweep_begin reads them. */
typedef struct {
    int quiet;      /* --quiet: no progress on stderr */
    sh_shard shard; /* --shard I/N */
    int sharded;    /* --shard was given (even 0/1): print a shard file */
    cli_format fmt; /* --format */
} cli_sweep_args;
extern const cli_opt cli_sweep_opts[];

typedef struct {
    const cli_sweep_kind *kind;
    json_t *params, *rows;
    long nitems, owned, done, last;
    sh_shard shard;
    sh_items items;       /* the shard's items, as the library's sweeps take them */
    int sharded, stopped; /* sharded: --shard was given (even 0/1) */
    cli_format fmt;
    cli_progress prog;
    const char *what;
    char label[64]; /* "command" or "command (shard I/N)" for progress lines */
} cli_sweep;
/* Start a sweep of nitems items; params (stolen) must hold everything the
 * result depends on.  Without --shard (opts->sharded 0): the whole sweep,
 * printed as the command's result; else a shard file, also for 0/1.  what
 * names the items in progress lines ("bands"). */
void cli_sweep_begin(cli_sweep *s, const cli_sweep_kind *kind, json_t *params, long nitems,
                     const cli_sweep_args *opts, const char *what);
/* The items this run computes (NULL without --shard), for a library call
 * that splits the work itself. */
const sh_items *cli_sweep_items(const cli_sweep *s);
/* Non-zero if this run computes item j (its shard owns it, the sweep has not stopped). */
int cli_sweep_owns(const cli_sweep *s, long j);
/* Record item j's row (stolen; items in increasing order).  Returns 0 to go
 * on, 1 if the sweep stops at this row, CLI_EXIT_USAGE after printing the
 * error (then call cli_sweep_free). */
int cli_sweep_add(cli_sweep *s, long j, json_t *row);
/* Print the result (or the shard file) and release s; returns the exit code. */
int cli_sweep_end(cli_sweep *s);
/* The end of a sweep whose rows were computed with status rc (0 or an exit
 * code after its error line): cli_sweep_end when rc is 0, else s released
 * and rc returned. */
int cli_sweep_close(cli_sweep *s, int rc);
/* Render a kind's result (from finish) in fmt; the exit code of the result. */
int cli_sweep_emit(const cli_sweep_kind *kind, json_t *result, cli_format fmt);
void cli_sweep_free(cli_sweep *s);

#endif
