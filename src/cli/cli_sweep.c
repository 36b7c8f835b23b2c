/* cli_sweep.c — sweeps that can be split into shards (see cli.h): the
 * runner every sweep command uses, the options they all take (--quiet,
 * --shard, --format: cli_sweep_opts), and the shard file written with
 * --shard.  `shlab merge` (cmd_merge.c) reads the files back.
 *
 * The unsharded run and the merge build the result the same way — the
 * rows in item order through the kind's finish() — and a row survives the
 * shard file exactly (reals written with 17 significant digits and read
 * back by strtod), so the merge prints the unsharded output byte for byte. */
#include "cli.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#ifndef SHLAB_REVISION
#define SHLAB_REVISION "unknown"
#endif

static const char *const format_names[] = {"table", "csv", "json"};

static const char *type_name(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "an object";
    case JSON_ARRAY: return "an array";
    case JSON_STRING: return "a string";
    case JSON_INTEGER: return "an integer";
    case JSON_REAL: return "a real";
    case JSON_TRUE:
    case JSON_FALSE: return "a boolean";
    default: return "null";
    }
}

static const char *const want_name[] = {"an integer", "a real", "a real or null", "a boolean", "a string",
                                        "an array of reals", "null or an array of integers",
                                        "an array of strings", "an object"};

static int int_in(const json_t *v, const cli_sweep_field *f)
{
    if (!json_is_integer(v)) return 0;
    const long long x = json_integer_value(v);
    return (f->min == 0 && f->max == 0) || (x >= f->min && x <= f->max);
}

static int field_ok(const cli_sweep_field *f, const json_t *v)
{
    size_t i;
    json_t *e;
    switch (f->type) {
    case CLI_FIELD_INT: return int_in(v, f);
    case CLI_FIELD_REAL: return json_is_real(v);
    case CLI_FIELD_REAL_OR_NULL: return json_is_real(v) || json_is_null(v);
    case CLI_FIELD_BOOL: return json_is_boolean(v);
    case CLI_FIELD_STRING: return json_is_string(v);
    case CLI_FIELD_OBJECT: return json_is_object(v);
    case CLI_FIELD_REALS:
        if (!json_is_array(v)) return 0;
        json_array_foreach(v, i, e) if (!json_is_real(e)) return 0;
        return 1;
    case CLI_FIELD_STRINGS:
        if (!json_is_array(v)) return 0;
        json_array_foreach(v, i, e) if (!json_is_string(e)) return 0;
        return 1;
    case CLI_FIELD_INTS_OR_NULL:
        if (json_is_null(v)) return 1;
        if (!json_is_array(v)) return 0;
        json_array_foreach(v, i, e) if (!int_in(e, f)) return 0;
        return 1;
    }
    return 0;
}

int cli_sweep_fields_ok(const cli_sweep_field *fields, const json_t *obj, char *why, size_t n)
{
    if (!json_is_object(obj)) return snprintf(why, n, "not an object"), 1;
    size_t known = 0;
    for (const cli_sweep_field *f = fields; f && f->key; f++) {
        const json_t *v = json_object_get(obj, f->key);
        if (!v) {
            if (f->optional) continue;
            return snprintf(why, n, "field '%s' is missing", f->key), 1;
        }
        known++;
        if (!field_ok(f, v)) {
            if ((f->type == CLI_FIELD_INT && json_is_integer(v)) || f->type == CLI_FIELD_INTS_OR_NULL)
                return snprintf(why, n, "field '%s' is not %s in %lld..%lld", f->key, want_name[f->type], f->min,
                                f->max), 1;
            return snprintf(why, n, "field '%s' is %s, not %s", f->key, type_name(v), want_name[f->type]), 1;
        }
    }
    if (json_object_size(obj) != known) {
        const char *key;
        json_t *v;
        json_object_foreach((json_t *)obj, key, v) {
            int found = 0;
            for (const cli_sweep_field *f = fields; f && f->key && !found; f++) found = !strcmp(f->key, key);
            if (!found) return snprintf(why, n, "unexpected field '%.40s'", key), 1;
        }
    }
    return 0;
}

int cli_sweep_row_ok(const cli_sweep_kind *kind, const json_t *params, long nitems, long j, const json_t *row,
                     char *why, size_t n)
{
    if (cli_sweep_fields_ok(kind->row_fields, row, why, n)) return 1;
    return kind->check_row ? kind->check_row(params, nitems, j, row, why, n) : 0;
}

/* ---- the options every sweep takes ------------------------------------------ */

/* --shard I/N into cli_sweep_args.shard (the field), and sharded beside it:
 * 0/1 given is a shard file all the same. */
static int shard_value(const char *opt, const char *s, void *field)
{
    cli_sweep_args *a = (cli_sweep_args *)((char *)field - offsetof(cli_sweep_args, shard));
    if (sh_shard_parse(s, &a->shard)) return cli_fail("%s: %s", opt, sh_last_error());
    a->sharded = 1;
    return 0;
}

const cli_opt cli_sweep_opts[] = {
    CLI_FLAG(cli_sweep_args, quiet, "quiet", "no progress on stderr (else a line a second after 1 s)"),
    CLI_CUSTOM(cli_sweep_args, shard, "shard", "I/N", shard_value, NULL,
               "compute only shard I of N (I = 0..N-1) and print a shard\n"
               "file (JSON lines); `shlab merge` joins the N files into\n"
               "exactly this command's output"),
    CLI_FORMAT(cli_sweep_args, fmt),
    CLI_END,
};

/* ---- the sweep ---------------------------------------------------------------- */

void cli_sweep_begin(cli_sweep *s, const cli_sweep_kind *kind, json_t *params, long nitems,
                     const cli_sweep_args *opts, const char *what)
{
    memset(s, 0, sizeof *s);
    s->kind = kind;
    s->params = params;
    s->rows = json_array();
    s->nitems = nitems;
    s->shard = opts->sharded ? opts->shard : (sh_shard)SH_SHARD_ALL;
    s->items = sh_shard_items(&s->shard); /* points into *s: s is not copied after this */
    s->sharded = opts->sharded;
    s->fmt = opts->fmt;
    s->last = -1;
    s->what = what;
    for (long j = 0; j < nitems; j++) s->owned += sh_shard_owns(&s->shard, j);
    if (s->sharded)
        snprintf(s->label, sizeof s->label, "%s (shard %d/%d)", kind->command, s->shard.index, s->shard.count);
    else
        snprintf(s->label, sizeof s->label, "%s", kind->command);
    cli_progress_start(&s->prog, s->label, opts->quiet);
}

const sh_items *cli_sweep_items(const cli_sweep *s) { return s->sharded ? &s->items : NULL; }

int cli_sweep_owns(const cli_sweep *s, long j)
{
    return !s->stopped && j >= 0 && j < s->nitems && sh_shard_owns(&s->shard, j);
}

int cli_sweep_add(cli_sweep *s, long j, json_t *row)
{
    if (!row || !s->rows || !s->params) {
        json_decref(row);
        return cli_fail("%s: out of memory or a non-finite value in a row", s->kind->command);
    }
    char why[160];
    if (!cli_sweep_owns(s, j) || j <= s->last) { /* a bug in the command, not the user's */
        json_decref(row);
        return cli_fail("%s: internal error: item %ld out of turn", s->kind->command, j);
    }
    /* what merge will check, checked here first (a bug in the command too) */
    if ((j == 0 || s->done == 0) && cli_sweep_fields_ok(s->kind->params_fields, s->params, why, sizeof why)) {
        json_decref(row);
        return cli_fail("%s: internal error: the sweep's parameters: %s", s->kind->command, why);
    }
    if (cli_sweep_row_ok(s->kind, s->params, s->nitems, j, row, why, sizeof why)) {
        json_decref(row);
        return cli_fail("%s: internal error: the row of item %ld: %s", s->kind->command, j, why);
    }
    const int stop = s->kind->stops && s->kind->stops(s->params, row);
    json_t *rec = row;
    if (s->sharded) {
        rec = json_object();
        rec = cli_put(rec, "item", json_integer(j));
        rec = cli_put(rec, "row", row);
    }
    if (!rec || json_array_append_new(s->rows, rec)) return cli_fail("out of memory");
    s->last = j;
    s->done++;
    s->stopped = stop;
    cli_progress_step(&s->prog, stop ? s->owned : s->done, s->owned, s->what);
    return stop;
}

void cli_sweep_free(cli_sweep *s)
{
    json_decref(s->params);
    json_decref(s->rows);
    s->params = s->rows = NULL;
}

static int put_line(FILE *m, json_t *v)
{
    if (!v) return -1;
    char *t = json_dumps(v, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17));
    json_decref(v);
    if (!t) return -1;
    fputs(t, m);
    fputc('\n', m);
    free(t);
    return 0;
}

/* The shard file: header, one line per row, end line; written in one go. */
static int write_shard(cli_sweep *s)
{
    if (cli_json_bad(s->rows)) return cli_fail("%s: a row has a non-finite value; nothing printed", s->kind->command);
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m) return cli_fail("out of memory");
    json_t *h = json_object();
    h = cli_put(h, "command", json_string(s->kind->command));
    h = cli_put(h, "revision", json_string(SHLAB_REVISION));
    h = cli_put(h, "shard", json_integer(s->shard.index));
    h = cli_put(h, "shards", json_integer(s->shard.count));
    h = cli_put(h, "items", json_integer(s->nitems));
    h = cli_put(h, "format", json_string(format_names[s->fmt]));
    json_t *head = cli_put(json_object(), "shlab_shard", h);
    head = cli_put(head, "params", json_incref(s->params));
    int bad = put_line(m, head);
    size_t i;
    json_t *r;
    json_array_foreach(s->rows, i, r) if (!bad) bad = put_line(m, json_incref(r));
    json_t *end = json_object();
    end = cli_put(end, "rows", json_integer((json_int_t)json_array_size(s->rows)));
    end = cli_put(end, "stopped", json_boolean(s->stopped));
    if (!bad) bad = put_line(m, cli_put(json_object(), "end", end));
    else json_decref(end);
    fclose(m);
    if (bad || !buf) { free(buf); return cli_fail("out of memory"); }
    const size_t w = fwrite(buf, 1, len, stdout);
    free(buf);
    if (w != len || fflush(stdout) != 0) return cli_fail("cannot write to standard output");
    return CLI_EXIT_OK;
}

int cli_sweep_emit(const cli_sweep_kind *kind, json_t *result, cli_format fmt)
{
    const int code = result && kind->exit_code ? kind->exit_code(result) : CLI_EXIT_OK;
    const int rc = cli_emit(result, fmt);
    return rc == CLI_EXIT_OK ? code : rc;
}

int cli_sweep_end(cli_sweep *s)
{
    int rc;
    if (!s->rows || !s->params) rc = cli_fail("out of memory");
    else if (s->sharded) rc = write_shard(s);
    else {
        json_t *rows = s->rows;
        s->rows = NULL;
        rc = cli_sweep_emit(s->kind, s->kind->finish(s->params, rows), s->fmt);
    }
    cli_sweep_free(s);
    return rc;
}

int cli_sweep_close(cli_sweep *s, int rc)
{
    if (!rc) return cli_sweep_end(s);
    cli_sweep_free(s);
    return rc;
}
