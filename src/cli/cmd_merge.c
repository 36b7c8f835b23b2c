/* cmd_merge.c — `shlab merge`: join the shard files of a sweep run with
 * --shard I/N into the output of the unsharded command (cli_sweep.c). */
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

extern const cli_sweep_kind sweep_stability, sweep_taylor_error, sweep_scale_interp, sweep_plan;

static const cli_sweep_kind *const kinds[] = {&sweep_stability, &sweep_taylor_error, &sweep_scale_interp,
                                              &sweep_plan};

typedef struct {
    cli_format fmt;
} merge_args;

static const cli_opt merge_opts[] = {
    CLI_CHOICE(merge_args, fmt, "format", "table|csv|json", cli_format_names, NULL,
               "output format (default: the sweep's --format)"),
    CLI_END,
};

static const cli_cmd merge_decl = {
    .name = "merge",
    .usage = "merge [--format F] FILE...",
    .about = "Join the shard files of one sweep into the output of the whole sweep, the same\n"
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
             "  FILE...              the N shard files, in any order\n",
    .opts = merge_opts,
    .notes = "Example (GNU parallel, two processes on one machine):\n"
             "  parallel shlab stability --method zxzxz --lmax 300 --shard {}/2 '>' part{}.jsonl ::: 0 1\n"
             "  shlab merge part0.jsonl part1.jsonl\n",
    .positional = "FILE...",
};

/* A shard file holds one line per item: the largest runs write a few MB. */
#define MERGE_MAX_BYTES (1LL << 30)

typedef struct {
    const char *name;  /* as given, for messages */
    const cli_sweep_kind *kind;
    json_t *head;      /* the shlab_shard object */
    json_t *params;
    json_t *rows;      /* the {"item","row"} lines */
    long *line;        /* each row's line number */
    int stopped;
} shard_file;

static const cli_sweep_kind *kind_of(const char *command)
{
    for (size_t k = 0; command && k < sizeof kinds / sizeof *kinds; k++)
        if (!strcmp(kinds[k]->command, command)) return kinds[k];
    return NULL;
}

static const cli_sweep_field head_fields[] = {
    {"command", CLI_FIELD_STRING, 0, 0, 0},           {"revision", CLI_FIELD_STRING, 0, 0, 0},
    {"shard", CLI_FIELD_INT, 0, 0, SH_SHARD_MAX - 1}, {"shards", CLI_FIELD_INT, 0, 1, SH_SHARD_MAX},
    {"items", CLI_FIELD_INT, 0, 0, 1LL << 31},        {"format", CLI_FIELD_STRING, 0, 0, 0},
    {NULL, 0, 0, 0, 0}};
static const cli_sweep_field end_fields[] = {{"rows", CLI_FIELD_INT, 0, 0, 1LL << 31},
                                             {"stopped", CLI_FIELD_BOOL, 0, 0, 0}, {NULL, 0, 0, 0, 0}};
static const cli_sweep_field line_fields[] = {{"item", CLI_FIELD_INT, 0, 0, 1LL << 31},
                                              {"row", CLI_FIELD_OBJECT, 0, 0, 0}, {NULL, 0, 0, 0, 0}};

/* Line 1: {"shlab_shard":{...},"params":{...}}, of a sweep merge knows. */
static int read_head(shard_file *f, json_t *v)
{
    char why[200];
    const json_t *h = json_object_get(v, "shlab_shard");
    if (!json_is_object(h) || json_object_size(v) != 2 || !json_is_object(json_object_get(v, "params")))
        return cli_fail("merge: %s: no shard header on line 1 (not written by --shard?)", f->name);
    if (cli_sweep_fields_ok(head_fields, h, why, sizeof why))
        return cli_fail("merge: %s line 1: the shard header's %s", f->name, why);
    const char *cmd = json_string_value(json_object_get(h, "command"));
    if (!(f->kind = kind_of(cmd))) return cli_fail("merge: %s: '%s' is not a sweep that merge knows", f->name, cmd);
    if (json_integer_value(json_object_get(h, "shard")) >= json_integer_value(json_object_get(h, "shards")))
        return cli_fail("merge: %s line 1: shard %lld of %lld", f->name,
                        (long long)json_integer_value(json_object_get(h, "shard")),
                        (long long)json_integer_value(json_object_get(h, "shards")));
    const char *format = json_string_value(json_object_get(h, "format"));
    if (strcmp(format, "table") && strcmp(format, "csv") && strcmp(format, "json"))
        return cli_fail("merge: %s line 1: format '%.20s' (table, csv or json)", f->name, format);
    f->head = json_incref((json_t *)h);
    f->params = json_incref(json_object_get(v, "params"));
    if (cli_sweep_fields_ok(f->kind->params_fields, f->params, why, sizeof why))
        return cli_fail("merge: %s line 1: the %s parameters: %s", f->name, cmd, why);
    return 0;
}

/* One shard file from a stream: header, item lines, end line, every line
 * checked before it is kept (one error line naming the file and the line). */
static int read_stream(FILE *in, shard_file *f)
{
    char *line = NULL, name[512], why[200];
    size_t cap = 0, cap_lines = 0;
    ssize_t n;
    long lineno = 0, nitems = 0;
    int rc = 0, ended = 0;
    f->rows = json_array();
    if (!f->rows) return cli_fail("out of memory");
    while (!rc && (n = getline(&line, &cap, in)) >= 0) {
        lineno++;
        if (ended) { rc = cli_fail("merge: %s: text after the end line (line %ld)", f->name, lineno); break; }
        if (memchr(line, '\0', (size_t)n)) {
            rc = cli_fail("merge: %s line %ld: a NUL byte (not a line of text)", f->name, lineno);
            break;
        }
        snprintf(name, sizeof name, "merge: %s line %ld", f->name, lineno);
        json_t *v = NULL;
        if (cli_json_parse(line, (size_t)n, name, &v)) { rc = CLI_EXIT_USAGE; break; }
        if (!json_is_object(v)) {
            json_decref(v);
            rc = cli_fail("%s: not a shard file line (not an object)", name);
            break;
        }
        if (lineno == 1) {
            rc = read_head(f, v);
            nitems = f->head ? (long)json_integer_value(json_object_get(f->head, "items")) : 0;
            json_decref(v);
        } else if (json_object_get(v, "end")) {
            const json_t *e = json_object_get(v, "end");
            if (json_object_size(v) != 1 || cli_sweep_fields_ok(end_fields, e, why, sizeof why))
                rc = cli_fail("%s: the end line: %s", name,
                              json_object_size(v) != 1 ? "fields besides \"end\"" : why);
            else if (json_integer_value(json_object_get(e, "rows")) != (json_int_t)json_array_size(f->rows))
                rc = cli_fail("merge: %s: the end line counts %lld rows, the file has %zu", f->name,
                              (long long)json_integer_value(json_object_get(e, "rows")), json_array_size(f->rows));
            f->stopped = json_is_true(json_object_get(e, "stopped"));
            ended = 1;
            json_decref(v);
        } else if (json_object_get(v, "item")) {
            if (cli_sweep_fields_ok(line_fields, v, why, sizeof why))
                rc = cli_fail("%s: an item line whose %s", name, why);
            else {
                const long j = (long)json_integer_value(json_object_get(v, "item"));
                if (j >= nitems)
                    rc = cli_fail("%s: item %ld of a sweep of %ld items", name, j, nitems);
                else if (cli_sweep_row_ok(f->kind, f->params, nitems, j, json_object_get(v, "row"), why, sizeof why))
                    rc = cli_fail("%s: the row of item %ld: %s", name, j, why);
            }
            const size_t k = json_array_size(f->rows);
            if (!rc && k == cap_lines) {
                cap_lines = cap_lines ? 2 * cap_lines : 64;
                long *nl = realloc(f->line, cap_lines * sizeof *nl);
                if (!nl) rc = cli_fail("out of memory");
                else f->line = nl;
            }
            if (!rc) {
                f->line[k] = lineno;
                if (json_array_append(f->rows, v)) rc = cli_fail("out of memory");
            }
            json_decref(v);
        } else {
            json_decref(v);
            rc = cli_fail("%s: neither an item nor the end line", name);
        }
    }
    free(line);
    if (!rc && ferror(in)) rc = cli_fail("merge: cannot read '%s'", f->name);
    if (!rc && lineno == 0) rc = cli_fail("merge: %s is empty", f->name);
    if (!rc && !ended) rc = cli_fail("merge: %s has no end line (cut short: did the shard finish?)", f->name);
    return rc;
}

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
    const int rc = read_stream(in, f);
    fclose(in);
    return rc;
}

static long head_int(const json_t *h, const char *k) { return (long)json_integer_value(json_object_get(h, k)); }

static void files_free(shard_file *f, int nf)
{
    for (int q = 0; f && q < nf; q++) {
        json_decref(f[q].head);
        json_decref(f[q].params);
        json_decref(f[q].rows);
        free(f[q].line);
    }
    free(f);
}

/* The files, read, joined: one sweep, every shard once, every item once, in
 * order.  0 with *result (the kind's finish) and *kind, or the exit code
 * after the error line. */
static int join(shard_file *f, int nf, int timed, const cli_sweep_kind **kind_out, cli_format *fmt, json_t **result)
{
    json_t **slot = NULL, *rows = NULL;
    int rc = 0;
    const json_t *h0 = f[0].head;
    const cli_sweep_kind *kind = f[0].kind;
    const long items = head_int(h0, "items"), N = head_int(h0, "shards");
    /* the files must be shards of one sweep */
    static const char *const same[] = {"command", "revision", "shards", "items", "format"};
    for (int q = 1; q < nf && !rc; q++) {
        for (size_t k = 0; k < sizeof same / sizeof *same && !rc; k++)
            if (!json_equal(json_object_get(f[q].head, same[k]), json_object_get(h0, same[k])))
                rc = cli_fail("merge: %s and %s are not shards of one sweep (%s differs)", f[0].name, f[q].name,
                              same[k]);
        if (!rc && !json_equal(f[q].params, f[0].params))
            rc = cli_fail("merge: %s and %s are not shards of one sweep (the parameters differ)", f[0].name,
                          f[q].name);
    }
    if (rc) return rc;
    int *seen = calloc((size_t)N, sizeof *seen);
    slot = calloc((size_t)items + 1, sizeof *slot);
    if (!seen || !slot) { free(seen); free(slot); return cli_fail("out of memory"); }
    for (int q = 0; q < nf && !rc; q++) {
        const sh_shard sh = {(int)head_int(f[q].head, "shard"), (int)N};
        if (seen[sh.index]++) rc = cli_fail("merge: shard %d/%ld given twice (%s)", sh.index, N, f[q].name);
        long last = -1, owned = 0;
        for (long j = 0; j < items; j++) owned += sh_shard_owns(&sh, j);
        size_t i;
        json_t *r;
        json_array_foreach(f[q].rows, i, r) {
            if (rc) break;
            const long j = (long)json_integer_value(json_object_get(r, "item"));
            if (!sh_shard_owns(&sh, j))
                rc = cli_fail("merge: %s line %ld: item %ld does not belong to shard %d/%ld", f[q].name, f[q].line[i],
                              j, sh.index, N);
            else if (j <= last)
                rc = cli_fail("merge: %s line %ld: item %ld out of order or repeated", f[q].name, f[q].line[i], j);
            else slot[j] = json_object_get(r, "row");
            last = j;
        }
        if (!rc && !f[q].stopped && (long)json_array_size(f[q].rows) != owned)
            rc = cli_fail("merge: %s: shard %d/%ld has %zu of its %ld items", f[q].name, sh.index, N,
                          json_array_size(f[q].rows), owned);
    }
    for (long s = 0; s < N && !rc; s++)
        if (!seen[s]) rc = cli_fail("merge: shard %ld/%ld is missing (%d file%s given)", s, N, nf, nf == 1 ? "" : "s");
    free(seen);
    /* rows in item order up to the first that stops the sweep */
    if (!rc && !(rows = json_array())) rc = cli_fail("out of memory");
    for (long j = 0; j < items && !rc; j++) {
        if (!slot[j]) {
            rc = cli_fail("merge: item %ld is missing (its shard stopped before it, but the sweep did not)", j);
            break;
        }
        if (json_array_append(rows, slot[j])) rc = cli_fail("out of memory");
        if (kind->stops && kind->stops(f[0].params, slot[j])) break;
    }
    free(slot);
    if (!rc && cli_format_parse(json_string_value(json_object_get(h0, "format")), fmt)) rc = CLI_EXIT_USAGE;
    if (rc) {
        json_decref(rows);
        return rc;
    }
    *kind_out = kind;
    if (kind->timed && !timed) {
        *result = json_pack("{s:O,s:o}", "params", f[0].params, "rows", rows);
        return *result ? 0 : cli_fail("out of memory");
    }
    *result = kind->finish(f[0].params, rows);
    if (!*result) return cli_fail("merge: %s", *sh_last_error() ? sh_last_error() : "out of memory");
    return 0;
}

int cli_merge_mem(int nf, const char *const *buf, const size_t *len, const char *const *name, int timed,
                  json_t **result, int *code)
{
    *result = NULL;
    *code = CLI_EXIT_USAGE;
    shard_file *f = calloc((size_t)(nf > 0 ? nf : 1), sizeof *f);
    int rc = f ? 0 : cli_fail("out of memory");
    if (!rc && nf < 1) rc = cli_fail("merge: no shard files given");
    for (int q = 0; q < nf && !rc; q++) {
        f[q].name = name[q];
        FILE *in = fmemopen((void *)buf[q], len[q], "r");
        if (!in && len[q] == 0) rc = cli_fail("merge: %s is empty", name[q]);
        else if (!in) rc = cli_fail("out of memory");
        else {
            rc = read_stream(in, &f[q]);
            fclose(in);
        }
    }
    const cli_sweep_kind *kind = NULL;
    cli_format fmt;
    if (!rc) rc = join(f, nf, timed, &kind, &fmt, result);
    if (!rc) *code = kind->exit_code && (timed || !kind->timed) ? kind->exit_code(*result) : CLI_EXIT_OK;
    files_free(f, nf);
    return rc;
}

static int run(int argc, char **argv)
{
    merge_args a = {CLI_TABLE};
    cli_parsed seen;
    int rc = cli_args_parse(&merge_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    const int nf = argc - seen.first_positional;
    if (nf < 1) return cli_fail("merge: no shard files given");
    shard_file *f = calloc((size_t)nf, sizeof *f);
    rc = f ? 0 : cli_fail("out of memory");
    for (int q = 0; q < nf && !rc; q++) {
        f[q].name = argv[seen.first_positional + q];
        rc = read_file(f[q].name, &f[q]);
    }
    const cli_sweep_kind *kind = NULL;
    cli_format fmt;
    json_t *result = NULL;
    if (!rc) rc = join(f, nf, 1, &kind, &fmt, &result);
    files_free(f, nf);
    if (rc) return rc;
    return cli_sweep_emit(kind, result, cli_given(&seen, "format") ? a.fmt : fmt);
}

const cli_command cmd_merge = {"merge", run, "join the shard files of a sweep run with --shard I/N", &merge_decl};
