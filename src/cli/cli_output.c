/* cli_output.c — one result value, three renderings (table, csv, json).
 *
 * Commands build a complete jansson object; it is checked for non-finite
 * numbers (never printed as a result), rendered into memory and written to
 * stdout in one go.  JSON reals are printed with 17 significant digits
 * (exact round trip).  Table and CSV layouts are derived from the shape:
 *   scalars                       → context ("key: value" / leading columns)
 *   array of numbers              → one column (with i,l,m when SH-indexed)
 *   array of arrays (a matrix)    → one row per row
 *   array of objects (rows)       → one row per object, header from keys
 *   object of arrays (channels)   → one column per channel, with i,l,m
 *   object of scalars             → context under dotted keys ("choice.method")
 */
#define _GNU_SOURCE
#include "cli.h"
#include "core/shlab_internal.h"

#include <signal.h>
#include <sys/stat.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

json_t *cli_json_array(const double *v, size_t n)
{
    json_t *a = json_array();
    if (!a) return NULL;
    for (size_t i = 0; i < n; i++) {
        json_t *x = json_real(v[i] + 0.0); /* −0 → 0; NULL for NaN/Inf */
        if (!x || json_array_append_new(a, x)) { json_decref(a); return NULL; }
    }
    return a;
}

json_t *cli_json_matrix(const double *M, size_t rows, size_t cols)
{
    json_t *a = json_array();
    if (!a) return NULL;
    for (size_t r = 0; r < rows; r++) {
        json_t *row = cli_json_array(M + r * cols, cols);
        if (!row || json_array_append_new(a, row)) { json_decref(a); return NULL; }
    }
    return a;
}

json_t *cli_put(json_t *root, const char *key, json_t *val)
{
    if (!root || !val || json_object_set_new(root, key, val)) {
        if (root) json_decref(root);
        else if (val) json_decref(val);
        return NULL;
    }
    return root;
}

int cli_json_bad(const json_t *v)
{
    if (!v) return 1;
    if (json_is_real(v)) return !isfinite(json_real_value(v));
    if (json_is_array(v)) {
        size_t i;
        json_t *x;
        json_array_foreach(v, i, x) if (cli_json_bad(x)) return 1;
    } else if (json_is_object(v)) {
        const char *k;
        json_t *x;
        json_object_foreach((json_t *)v, k, x) if (cli_json_bad(x)) return 1;
    }
    return 0;
}

/* ---- text rendering ---------------------------------------------------- */

static int is_scalar(const json_t *v) { return !json_is_array(v) && !json_is_object(v); }

static void put_scalar(FILE *o, const json_t *v, int table)
{
    if (json_is_real(v)) fprintf(o, table ? "%.10g" : "%.17g", json_real_value(v));
    else if (json_is_integer(v)) fprintf(o, "%lld", (long long)json_integer_value(v));
    else if (json_is_string(v)) {
        const char *str = json_string_value(v);
        if (!table && strpbrk(str, ",\"\n\r")) { /* RFC 4180 quoting */
            fputc('"', o);
            for (; *str; str++) {
                if (*str == '"') fputc('"', o);
                fputc(*str, o);
            }
            fputc('"', o);
        } else {
            fputs(str, o);
        }
    }
    else if (json_is_true(v)) fputs("true", o);
    else if (json_is_false(v)) fputs("false", o);
    else if (json_is_null(v)) fputs(table ? "-" : "", o); /* a table shows "no value" */
    else {
        char *s = json_dumps(v, JSON_COMPACT | JSON_REAL_PRECISION(17) | JSON_ENCODE_ANY);
        if (s) { fputs(s, o); free(s); }
    }
}

static int is_square(size_t n)
{
    size_t r = (size_t)llround(sqrt((double)n));
    return r * r == n;
}

/* Column headers and cell access for one tabular member. */
typedef struct {
    const char *key;
    const json_t *v;
    int kind; /* 1 vector, 2 matrix, 3 rows, 4 channels */
    size_t nrows;
    int sh;   /* rows are SH-indexed (print i,l,m) */
} table_t;

static int classify(const char *key, const json_t *v, table_t *t)
{
    t->key = key;
    t->v = v;
    t->sh = 0;
    if (json_is_array(v)) {
        t->nrows = json_array_size(v);
        const json_t *first = json_array_get(v, 0);
        if (!first || is_scalar(first)) {
            t->kind = 1;
            t->sh = (!strcmp(key, "values") || !strcmp(key, "coeffs")) && is_square(t->nrows);
        } else if (json_is_array(first)) t->kind = 2;
        else t->kind = 3;
        return 1;
    }
    if (json_is_object(v)) {
        const char *k;
        json_t *x;
        size_t n = (size_t)-1;
        json_object_foreach((json_t *)v, k, x) {
            if (!json_is_array(x)) return 0;
            if (n == (size_t)-1) n = json_array_size(x);
            else if (json_array_size(x) != n) return 0;
        }
        if (n == (size_t)-1) return 0;
        t->kind = 4;
        t->nrows = n;
        t->sh = is_square(n);
        return 1;
    }
    return 0;
}

static void put_header(FILE *o, const table_t *t, const char *sep)
{
    int first = 1;
#define H(s) do { if (!first) fputs(sep, o); fputs(s, o); first = 0; } while (0)
    if (t->sh) { H("i"); H("l"); H("m"); }
    switch (t->kind) {
    case 1: H(t->key); break;
    case 2: {
        H("row");
        size_t nc = json_array_size(json_array_get(t->v, 0));
        for (size_t c = 0; c < nc; c++) { char b[32]; snprintf(b, sizeof b, "c%zu", c); H(b); }
        break;
    }
    case 3: {
        const char *k;
        json_t *x;
        json_object_foreach(json_array_get(t->v, 0), k, x) H(k);
        break;
    }
    case 4: {
        const char *k;
        json_t *x;
        json_object_foreach((json_t *)t->v, k, x) H(k);
        break;
    }
    }
#undef H
}

static void put_row(FILE *o, const table_t *t, size_t r, const char *sep, int table)
{
    int first = 1;
#define S() do { if (!first) fputs(sep, o); first = 0; } while (0)
    if (t->sh) {
        int l, m;
        sh_index_lm((int)r, &l, &m);
        S(); fprintf(o, "%zu", r);
        S(); fprintf(o, "%d", l);
        S(); fprintf(o, "%d", m);
    }
    switch (t->kind) {
    case 1: S(); put_scalar(o, json_array_get(t->v, r), table); break;
    case 2: {
        const json_t *row = json_array_get(t->v, r);
        S(); fprintf(o, "%zu", r);
        size_t i;
        json_t *x;
        json_array_foreach(row, i, x) { S(); put_scalar(o, x, table); }
        break;
    }
    case 3: {
        const char *k;
        json_t *x;
        json_object_foreach(json_array_get(t->v, r), k, x) { S(); put_scalar(o, x, table); }
        break;
    }
    case 4: {
        const char *k;
        json_t *x;
        json_object_foreach((json_t *)t->v, k, x) { S(); put_scalar(o, json_array_get(x, r), table); }
        break;
    }
    }
#undef S
}

/* An object whose members are all scalars (e.g. plan's "choice") is shown
 * as context with dotted keys: "choice.method: zxzxz" / column "choice.method". */
static int is_flat_object(const json_t *v)
{
    if (!json_is_object(v) || json_object_size(v) == 0) return 0;
    const char *k;
    json_t *x;
    json_object_foreach((json_t *)v, k, x) if (!is_scalar(x)) return 0;
    return 1;
}

/* Call f for every context value of root, in order: its scalars, and the
 * members of its flat objects under "key.member". */
typedef void (*ctx_fn)(FILE *o, const char *prefix, const char *key, const json_t *v, int *first,
                       int table);
static void each_context(FILE *o, json_t *root, ctx_fn f, int *first, int table)
{
    const char *k;
    json_t *v;
    json_object_foreach(root, k, v) {
        if (is_scalar(v)) f(o, NULL, k, v, first, table);
        else if (is_flat_object(v)) {
            const char *k2;
            json_t *x;
            json_object_foreach(v, k2, x) f(o, k, k2, x, first, table);
        }
    }
}

static void ctx_table(FILE *o, const char *prefix, const char *key, const json_t *v, int *first,
                      int table)
{
    (void)first;
    if (prefix) fprintf(o, "%s.", prefix);
    fprintf(o, "%s: ", key);
    put_scalar(o, v, table);
    fputc('\n', o);
}

static void ctx_csv_head(FILE *o, const char *prefix, const char *key, const json_t *v, int *first,
                         int table)
{
    (void)v;
    (void)table;
    if (!*first) fputc(',', o);
    if (prefix) fprintf(o, "%s.", prefix);
    fputs(key, o);
    *first = 0;
}

static void ctx_csv_value(FILE *o, const char *prefix, const char *key, const json_t *v, int *first,
                          int table)
{
    (void)prefix;
    (void)key;
    if (!*first) fputc(',', o);
    put_scalar(o, v, table);
    *first = 0;
}

static void render_text(FILE *o, json_t *root, cli_format fmt)
{
    const char *k;
    json_t *v;
    table_t tabs[16];
    int nt = 0;
    json_object_foreach(root, k, v) {
        if (!is_scalar(v) && !is_flat_object(v) && nt < 16 && classify(k, v, &tabs[nt])) nt++;
    }
    if (fmt == CLI_TABLE) {
        int first = 1;
        each_context(o, root, ctx_table, &first, 1);
        for (int t = 0; t < nt; t++) {
            fprintf(o, "\n%s:\n", tabs[t].key);
            put_header(o, &tabs[t], "\t");
            fputc('\n', o);
            for (size_t r = 0; r < tabs[t].nrows; r++) { put_row(o, &tabs[t], r, "\t", 1); fputc('\n', o); }
        }
        return;
    }
    /* CSV: context values become leading columns repeated on every row */
    for (int t = 0; t < (nt ? nt : 1); t++) {
        if (t) fputc('\n', o);
        int first = 1;
        each_context(o, root, ctx_csv_head, &first, 0);
        if (nt) { if (!first) fputc(',', o); put_header(o, &tabs[t], ","); }
        fputc('\n', o);
        size_t nrows = nt ? tabs[t].nrows : 1;
        for (size_t r = 0; r < nrows; r++) {
            first = 1;
            each_context(o, root, ctx_csv_value, &first, 0);
            if (nt) { if (!first) fputc(',', o); put_row(o, &tabs[t], r, ",", 0); }
            fputc('\n', o);
        }
    }
}

int cli_emit(json_t *root, cli_format fmt)
{
    if (!root) return cli_fail("out of memory or a non-finite value while building the result");
    if (cli_json_bad(root)) {
        json_decref(root);
        return cli_fail("the result contains a non-finite value; nothing printed");
    }
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m) { json_decref(root); return cli_fail("out of memory"); }
    if (fmt == CLI_JSON) {
        char *s = json_dumps(root, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17));
        if (s) { fputs(s, m); fputc('\n', m); free(s); }
    } else {
        render_text(m, root, fmt);
    }
    fclose(m);
    json_decref(root);
    if (!buf || len == 0) { free(buf); return cli_fail("could not render the result"); }
    cli_signals_commit();
    size_t w = fwrite(buf, 1, len, stdout);
    free(buf);
    if (w != len || fflush(stdout) != 0) {
        cli_out_discard();
        return cli_fail("cannot write to standard output");
    }
    return cli_out_commit();
}

/* ---- output files --------------------------------------------------------
 * Each output is a temporary file next to its target (sh__make_temp_path,
 * registered for the signal handler); cli_emit renames them all onto their
 * targets once the result is on stdout.  Anything not committed is removed:
 * by cli_out_discard, at exit (main registers sh__temp_files_unlink), or by
 * the signal handler. */
#define CLI_MAX_OUT 8
static struct {
    char *tmp, *path;
    int exists;                   /* the target existed when it was opened */
    unsigned long long dev, ino;  /* its file then (stat, through links) */
} outs[CLI_MAX_OUT];
static int nouts;

/* Inputs read so far (cli_input): an output may not name one of them, by the
 * same path or through a link (same device and inode), in either order. */
#define CLI_MAX_IN 64
static struct {
    unsigned long long dev, ino;
    char what[32];
} ins[CLI_MAX_IN];
static int nins;

int cli_input(const char *what, const char *path)
{
    struct stat sb;
    if (!path || stat(path, &sb) != 0) return 0; /* the reader reports a missing file */
    for (int k = 0; k < nouts; k++)
        if (outs[k].exists && outs[k].dev == (unsigned long long)sb.st_dev && outs[k].ino == (unsigned long long)sb.st_ino)
            return cli_fail("the output '%s' is also the input %s '%s': refusing to overwrite it", outs[k].path, what,
                            path);
    if (nins < CLI_MAX_IN) {
        ins[nins].dev = (unsigned long long)sb.st_dev;
        ins[nins].ino = (unsigned long long)sb.st_ino;
        snprintf(ins[nins].what, sizeof ins[nins].what, "%s", what);
        nins++;
    }
    return 0;
}

int cli_out_open(const char *cmd, const char *path, const char **tmp)
{
    *tmp = NULL;
    if (!path || !*path) return cli_fail("%s: empty output file name", cmd);
    for (int k = 0; k < nouts; k++)
        if (!strcmp(outs[k].path, path)) return cli_fail("%s: '%s' is written twice", cmd, path);
    if (nouts == CLI_MAX_OUT) return cli_fail("%s: too many output files", cmd);
    struct stat sb;
    const int exists = stat(path, &sb) == 0;
    for (int k = 0; exists && k < nins; k++)
        if (ins[k].dev == (unsigned long long)sb.st_dev && ins[k].ino == (unsigned long long)sb.st_ino)
            return cli_fail("%s: the output '%s' is also an input (the %s): refusing to overwrite it", cmd, path,
                            ins[k].what);
    char *t = NULL, *p = strdup(path);
    if (!p) return cli_fail("out of memory");
    if (sh__make_temp_path(path, &t)) {
        free(p);
        return cli_fail("%s: %s", cmd, sh_last_error());
    }
    outs[nouts].tmp = t;
    outs[nouts].path = p;
    outs[nouts].exists = exists;
    outs[nouts].dev = exists ? (unsigned long long)sb.st_dev : 0;
    outs[nouts].ino = exists ? (unsigned long long)sb.st_ino : 0;
    nouts++;
    *tmp = t;
    return 0;
}

int cli_out_commit(void)
{
    int rc = CLI_EXIT_OK;
    for (int k = 0; k < nouts; k++) {
        if (rc == CLI_EXIT_OK) {
            if (sh__commit_temp(outs[k].tmp, outs[k].path)) rc = cli_fail("%s", sh_last_error());
        } else {
            sh__discard_temp(outs[k].tmp);
        }
        free(outs[k].tmp);
        free(outs[k].path);
    }
    nouts = 0;
    return rc;
}

void cli_out_discard(void)
{
    for (int k = 0; k < nouts; k++) {
        sh__discard_temp(outs[k].tmp);
        free(outs[k].tmp);
        free(outs[k].path);
    }
    nouts = 0;
}

/* ---- signals -------------------------------------------------------------
 * On SIGINT, SIGTERM, SIGHUP, SIGPIPE (the user or a supervisor stops us)
 * and SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL (a library aborts or faults):
 * remove every temporary file (the library's registry holds them all, the
 * CLI's and the library writers'), then die by the same signal.
 *
 * The handler runs with every signal blocked (sa_mask full) and without
 * SA_RESETHAND: with SA_RESETHAND (which on Linux implies SA_NODEFER) a second
 * signal arriving during the handler — `timeout` sends one to the child and
 * one to its process group, a user presses Ctrl-C twice — met the default
 * action before the files were removed.  Now a second signal waits until the
 * removal is done; only then is the default action restored and the signal
 * raised again (it is delivered when the handler returns).  A signal that
 * reaches another thread runs this handler there, which also removes every
 * file before it restores the default.  Everything called here is
 * async-signal-safe (unlink, sigaction, raise). */
static volatile sig_atomic_t committing;

static void on_signal(int sig)
{
    /* the result is being written: a stop request now would leave a complete
     * stdout with a signal's exit status, or outputs half renamed */
    if (committing && (sig == SIGINT || sig == SIGTERM || sig == SIGHUP)) return;
    sh__temp_files_unlink();
    struct sigaction dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, NULL);
    raise(sig);
}

/* From the first byte of the result on: the run finishes.  SIGINT, SIGTERM
 * and SIGHUP are blocked in this thread and ignored by the handler in any
 * other, so a run either stops before it prints anything, or prints its whole
 * result, renames its outputs and exits 0.  Called by cli_emit only; what
 * follows it (writing a few kilobytes, renames, freeing) takes milliseconds. */
void cli_signals_commit(void)
{
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGHUP);
    committing = 1;
    sigprocmask(SIG_BLOCK, &stop, NULL);
}

void cli_signals_install(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL};
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = 0;
    sigfillset(&sa.sa_mask);
    for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++) {
        struct sigaction old;
        /* a signal ignored by whoever started us stays ignored */
        if (sigaction(sigs[k], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        sigaction(sigs[k], &sa, NULL);
    }
    atexit(sh__temp_files_unlink);
}
