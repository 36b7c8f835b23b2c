/* cmd_merge.c — `shlab merge`: join the shard files of a sweep run with
 * --shard I/N into the output of the unsharded command (cli_sweep.c). */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_merge;
extern const cli_sweep_kind sweep_stability, sweep_taylor_error, sweep_scale_interp, sweep_plan;

static const cli_sweep_kind *const kinds[] = {&sweep_stability, &sweep_taylor_error, &sweep_scale_interp,
                                              &sweep_plan};

static const char help[] =
    "Usage: shlab merge [--format F] FILE...\n"
    "\n"
    "Join the shard files of one sweep into the output of the whole sweep, the same\n"
    "bytes the command prints when run without --shard.  A sweep command run with\n"
    "--shard I/N (I = 0..N-1) computes only its share of the work items (item j goes\n"
    "to shard r if r < N, else to 2N-1-r, with r = j mod 2N) and prints a shard file\n"
    "(JSON lines: a header with the command, the shlab revision, I, N, the number of\n"
    "items, the --format and every parameter; one line per item with its index; an\n"
    "end line).  merge refuses files of different sweeps (command, revision,\n"
    "parameters, N or --format differ), a shard given twice or missing, a file cut\n"
    "short (no end line), and an item missing, foreign or repeated.  Where a sweep\n"
    "stops at a row (stability --stop-above, a broken band), the rows after the first\n"
    "such row are dropped, as the unsharded run never computes them.\n"
    "\n"
    "Sweeps that take --shard: stability (bands), taylor-error (angles), scale-interp\n"
    "(points of the dense k grid), plan (steps of the β grid; the methods are timed\n"
    "by the merge, so its timings are those of the merging machine).\n"
    "\n"
    "  FILE...              the N shard files, in any order\n"
    "  --format table|csv|json  output format (default: the sweep's --format)\n"
    "  --help               this text\n"
    "\n"
    "Example (GNU parallel, two processes on one machine):\n"
    "  parallel shlab stability --method zxzxz --lmax 300 --shard {}/2 '>' part{}.jsonl ::: 0 1\n"
    "  shlab merge part0.jsonl part1.jsonl\n";

/* A shard file holds one line per item: the largest runs write a few MB. */
#define MERGE_MAX_BYTES (1LL << 30)

typedef struct {
    json_t *head;  /* the shlab_shard object */
    json_t *params;
    json_t *rows;  /* the {"item","row"} lines */
    int stopped;
} shard_file;

/* Read one shard file: header, item lines, end line. */
static int read_file(const char *path, shard_file *f)
{
    sh_input inp;
    if (cli_input("shard file", path)) return CLI_EXIT_USAGE;
    if (sh_input_open("shard file", path, MERGE_MAX_BYTES, &inp)) return cli_fail_status(SH_EIO);
    FILE *in = fdopen(inp.fd, "r");
    if (!in) {
        sh_input_close(&inp);
        return cli_fail("merge: cannot read '%s': %s", path, strerror(errno));
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t n;
    long lineno = 0;
    int rc = 0, ended = 0;
    f->rows = json_array();
    while (!rc && (n = getline(&line, &cap, in)) >= 0) {
        lineno++;
        if (ended) { rc = cli_fail("merge: %s: text after the end line (line %ld)", path, lineno); break; }
        json_error_t err;
        json_t *v = json_loadb(line, (size_t)n, 0, &err);
        if (!v || !json_is_object(v)) {
            json_decref(v);
            rc = cli_fail("merge: %s line %ld: not a shard file line (%s)", path, lineno,
                          v ? "not an object" : err.text);
            break;
        }
        if (lineno == 1) {
            f->head = json_incref(json_object_get(v, "shlab_shard"));
            f->params = json_incref(json_object_get(v, "params"));
            json_decref(v);
            if (!json_is_object(f->head) || !json_is_object(f->params) ||
                !json_is_string(json_object_get(f->head, "command")) ||
                !json_is_integer(json_object_get(f->head, "shard")) ||
                !json_is_integer(json_object_get(f->head, "shards")) ||
                !json_is_integer(json_object_get(f->head, "items")) ||
                !json_is_string(json_object_get(f->head, "format")))
                rc = cli_fail("merge: %s: no shard header on line 1 (not written by --shard?)", path);
        } else if (json_object_get(v, "end")) {
            const json_t *e = json_object_get(v, "end");
            const json_t *k = json_object_get(e, "rows");
            if (!json_is_integer(k) || json_integer_value(k) != (json_int_t)json_array_size(f->rows))
                rc = cli_fail("merge: %s: the end line counts %lld rows, the file has %zu", path,
                              json_is_integer(k) ? (long long)json_integer_value(k) : -1LL,
                              json_array_size(f->rows));
            f->stopped = json_is_true(json_object_get(e, "stopped"));
            ended = 1;
            json_decref(v);
        } else if (json_is_integer(json_object_get(v, "item")) && json_is_object(json_object_get(v, "row"))) {
            if (json_array_append_new(f->rows, v)) rc = cli_fail("out of memory");
        } else {
            json_decref(v);
            rc = cli_fail("merge: %s line %ld: neither an item nor the end line", path, lineno);
        }
    }
    free(line);
    const int rerr = ferror(in);
    fclose(in);
    if (!rc && rerr) rc = cli_fail("merge: cannot read '%s'", path);
    if (!rc && lineno == 0) rc = cli_fail("merge: %s is empty", path);
    if (!rc && !ended) rc = cli_fail("merge: %s has no end line (cut short: did the shard finish?)", path);
    return rc;
}

static long head_int(const json_t *h, const char *k) { return (long)json_integer_value(json_object_get(h, k)); }

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE, {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    int have_fmt = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        if (o == CLI_OPT_FORMAT) have_fmt = 1;
        const int e = cli_common_opt(&cmd_merge, o, argv, &com);
        if (e >= 0) return e;
    }
    const int nf = argc - optind;
    if (nf < 1) return cli_fail("merge: no shard files given");
    shard_file *f = calloc((size_t)nf, sizeof *f);
    json_t **slot = NULL, *rows = NULL;
    const cli_sweep_kind *kind = NULL;
    long items = 0, N = 0;
    int rc = f ? 0 : cli_fail("out of memory");
    for (int q = 0; q < nf && !rc; q++) rc = read_file(argv[optind + q], &f[q]);
    if (rc) goto done;
    const json_t *h0 = f[0].head;
    const char *cmd = json_string_value(json_object_get(h0, "command"));
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++)
        if (!strcmp(kinds[k]->command, cmd)) kind = kinds[k];
    if (!kind) { rc = cli_fail("merge: %s: '%s' is not a sweep that merge knows", argv[optind], cmd); goto done; }
    items = head_int(h0, "items");
    N = head_int(h0, "shards");
    if (items < 0 || N < 1 || N > SH_SHARD_MAX) { rc = cli_fail("merge: %s: bad header", argv[optind]); goto done; }
    /* the files must be shards of one sweep */
    static const char *const same[] = {"command", "revision", "shards", "items", "format"};
    for (int q = 1; q < nf && !rc; q++) {
        for (size_t k = 0; k < sizeof same / sizeof *same && !rc; k++)
            if (!json_equal(json_object_get(f[q].head, same[k]), json_object_get(h0, same[k])))
                rc = cli_fail("merge: %s and %s are not shards of one sweep (%s differs)", argv[optind],
                              argv[optind + q], same[k]);
        if (!rc && !json_equal(f[q].params, f[0].params))
            rc = cli_fail("merge: %s and %s are not shards of one sweep (the parameters differ)",
                          argv[optind], argv[optind + q]);
    }
    if (rc) goto done;
    int *seen = calloc((size_t)N, sizeof *seen);
    slot = calloc((size_t)items + 1, sizeof *slot);
    if (!seen || !slot) { free(seen); rc = cli_fail("out of memory"); goto done; }
    for (int q = 0; q < nf && !rc; q++) {
        const sh_shard sh = {(int)head_int(f[q].head, "shard"), (int)N};
        if (sh.index < 0 || sh.index >= N) rc = cli_fail("merge: %s: shard %d of %ld out of range", argv[optind + q], sh.index, N);
        else if (seen[sh.index]++) rc = cli_fail("merge: shard %d/%ld given twice (%s)", sh.index, N, argv[optind + q]);
        long last = -1, owned = 0;
        for (long j = 0; j < items; j++) owned += sh_shard_owns(&sh, j);
        size_t i;
        json_t *r;
        json_array_foreach(f[q].rows, i, r) {
            if (rc) break;
            const long j = (long)json_integer_value(json_object_get(r, "item"));
            if (j < 0 || j >= items || !sh_shard_owns(&sh, j))
                rc = cli_fail("merge: %s: item %ld does not belong to shard %d/%ld", argv[optind + q], j, sh.index, N);
            else if (j <= last)
                rc = cli_fail("merge: %s: item %ld out of order or repeated", argv[optind + q], j);
            else slot[j] = json_object_get(r, "row");
            last = j;
        }
        if (!rc && !f[q].stopped && (long)json_array_size(f[q].rows) != owned)
            rc = cli_fail("merge: %s: shard %d/%ld has %zu of its %ld items", argv[optind + q], sh.index, N,
                          json_array_size(f[q].rows), owned);
    }
    for (long s = 0; s < N && !rc; s++)
        if (!seen[s]) rc = cli_fail("merge: shard %ld/%ld is missing (%d file%s given)", s, N, nf, nf == 1 ? "" : "s");
    free(seen);
    if (rc) goto done;
    /* rows in item order up to the first that stops the sweep */
    rows = json_array();
    for (long j = 0; j < items && !rc; j++) {
        if (!slot[j]) {
            rc = cli_fail("merge: item %ld is missing (its shard stopped before it, but the sweep did not)", j);
            break;
        }
        if (json_array_append(rows, slot[j])) rc = cli_fail("out of memory");
        if (kind->stops && kind->stops(f[0].params, slot[j])) break;
    }
    if (rc) goto done;
    cli_format fmt = com.fmt;
    if (!have_fmt && cli_format_parse(json_string_value(json_object_get(h0, "format")), &fmt)) {
        rc = CLI_EXIT_USAGE;
        goto done;
    }
    rc = cli_sweep_emit(kind, kind->finish(f[0].params, rows), fmt);
    rows = NULL;
done:
    json_decref(rows);
    free(slot);
    for (int q = 0; f && q < nf; q++) {
        json_decref(f[q].head);
        json_decref(f[q].params);
        json_decref(f[q].rows);
    }
    free(f);
    return rc;
}

const cli_command cmd_merge = {"merge", run, "join the shard files of a sweep run with --shard I/N", help};
