/* cli_common.c — argument parsing and error reporting shared by commands. */
#define _GNU_SOURCE
#include "cli.h"
#include "io/json_strict.h"
#include "core/shlab_internal.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* The one error line.  Messages quote arguments and file contents, so the
 * text is escaped (sh__escape_line: no control character, no invalid UTF-8)
 * and cut at 2000 bytes: whatever the input, exactly one line. */
int cli_fail(const char *fmt, ...)
{
    char raw[2048], line[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    sh__escape_line(line, sizeof line, raw);
    fprintf(stderr, "shlab: error: %s\n", line);
    fflush(stderr);
    return CLI_EXIT_USAGE;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* SHLAB_PROGRESS_INTERVAL (docs/CONVENTIONS.md "Output"): seconds before the
 * first line and between lines, 1 unless set to a number in 0..3600. */
static double progress_interval(void)
{
    const char *s = getenv("SHLAB_PROGRESS_INTERVAL");
    char *end;
    double v = 1;
    if (s && *s && sh__parse_double(s, &end, &v) == SH__NUM_OK && !*end && v >= 0 && v <= 3600) return v;
    return 1;
}

void cli_progress_start(cli_progress *p, const char *cmd, int quiet)
{
    p->cmd = cmd;
    p->quiet = quiet;
    p->interval = progress_interval();
    p->printed = 0;
    p->estimated = 0;
    p->t0 = p->last = now_s();
}

void cli_progress_step(void *ctx, int done, int total, const char *what)
{
    cli_progress *p = ctx;
    if (!p || p->quiet) return;
    const double t = now_s();
    const int end = done >= total;
    if (t - p->t0 < p->interval || (t - p->last < p->interval && !(end && p->printed))) return;
    fprintf(stderr, "%s: %d of %d %s, %.1f s\n", p->cmd, done, total, what ? what : "steps", t - p->t0);
    p->last = t;
    p->printed = 1;
}

int cli_applies(const char *cmd, int given, const char *opt, int applies, const char *what)
{
    if (!given || applies) return 0;
    return cli_fail("%s: %s applies only to %s", cmd, opt, what);
}

int cli_fail_status(int st)
{
    const char *why = sh_last_error();
    return cli_fail("%s", (why && *why) ? why : sh_strerror(st));
}

int cli_long(const char *opt, const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end != '\0')
        return cli_fail("%s expects an integer, got '%s'", opt, s);
    *out = v;
    return 0;
}

int cli_int(const char *opt, const char *s, int *out)
{
    long v;
    if (cli_long(opt, s, &v)) return CLI_EXIT_USAGE;
    if (v < INT_MIN || v > INT_MAX) return cli_fail("%s: %s is out of range", opt, s);
    *out = (int)v;
    return 0;
}

int cli_order_check(const char *opt, int order, int max, const char *why)
{
    if (max <= 0 || max > SHLAB_MAX_ORDER) max = SHLAB_MAX_ORDER;
    if (order >= 1 && order <= max) return 0;
    return cli_fail("%s: order %d is outside 1..%d%s%s%s", opt, order, max, why ? " (" : "", why ? why : "",
                    why ? ")" : "");
}

int cli_order_max(const char *opt, const char *s, int max, const char *why, int *out)
{
    int v;
    if (cli_int(opt, s, &v) || cli_order_check(opt, v, max, why)) return CLI_EXIT_USAGE;
    *out = v;
    return 0;
}

int cli_order(const char *opt, const char *s, int *out) { return cli_order_max(opt, s, 0, NULL, out); }

/* Numbers: sh__parse_double's rule everywhere (finite, no overflow, and no
 * underflow of a non-zero value to 0 or a subnormal). */
#define RANGE_MSG "is not a finite number within double's range (1e-307 to 1e308 in magnitude, or 0)"

int cli_double(const char *opt, const char *s, double *out)
{
    char *end;
    double v = 0;
    const int r = sh__parse_double(s, &end, &v);
    while (end && isspace((unsigned char)*end)) end++;
    if (r == SH__NUM_NONE || *end != '\0') return cli_fail("%s expects a number, got '%s'", opt, s);
    if (r == SH__NUM_RANGE) return cli_fail("%s: '%s' " RANGE_MSG, opt, s);
    *out = v;
    return 0;
}

/* Lists: elements separated by a comma (white space around it allowed) or
 * by white space alone.  An empty element — two commas in a row, a comma
 * first or last — is an error, not dropped ("0.1,,0.2" is not two numbers,
 * "taylor1," not one method). */
static int fail_empty(const char *opt, const char *s, size_t at)
{
    return cli_fail("%s: empty element at character %zu of '%.40s%s' (two commas in a row, or a comma first or "
                    "last)",
                    opt, at + 1, s, strlen(s) > 40 ? "..." : "");
}

int cli_doubles(const char *opt, const char *s, double **out, int *n)
{
    size_t cap = 16, k = 0;
    double *v = malloc(cap * sizeof *v);
    if (!v) return cli_fail("out of memory");
    const char *p = s;
    int after_value = 0; /* a value since the last comma (or the start) */
    for (;;) {
        while (*p && (isspace((unsigned char)*p) || *p == '[' || *p == ']')) p++;
        if (*p == ',' || (!*p && k > 0 && !after_value)) {
            if (!after_value) {
                free(v);
                return fail_empty(opt, s, (size_t)(p - s));
            }
            after_value = 0;
            p++;
            continue;
        }
        if (!*p) break;
        char *end;
        double x = 0;
        const int r = sh__parse_double(p, &end, &x);
        if (r == SH__NUM_NONE) {
            free(v);
            return cli_fail("%s: cannot read a number at '%.20s'", opt, p);
        }
        if (r == SH__NUM_RANGE) {
            free(v);
            return cli_fail("%s: value %zu ('%.*s') " RANGE_MSG, opt, k + 1,
                            (int)(end - p < 40 ? end - p : 40), p);
        }
        if (k == CLI_MAX_NUMBERS) {
            free(v);
            return cli_fail("%s: more than %d numbers", opt, CLI_MAX_NUMBERS);
        }
        if (k == cap) {
            double *nv = realloc(v, 2 * cap * sizeof *v);
            if (!nv) { free(v); return cli_fail("out of memory"); }
            v = nv;
            cap *= 2;
        }
        v[k++] = x;
        after_value = 1;
        p = end;
        if (*p && !(isspace((unsigned char)*p) || *p == ',' || *p == ']')) {
            free(v);
            return cli_fail("%s: unexpected '%c' after value %zu", opt, *p, k);
        }
    }
    if (k == 0) { free(v); return cli_fail("%s: no numbers given", opt); }
    *out = v;
    *n = (int)k;
    return 0;
}

int cli_split(const char *opt, const char *s, char ***items, int *n)
{
    /* one block: the pointers, then a copy of s cut into the elements */
    const size_t len = strlen(s), most = len / 2 + 2;
    char **t = malloc(most * sizeof *t + len + 1);
    if (!t) return cli_fail("out of memory");
    char *buf = (char *)(t + most);
    memcpy(buf, s, len + 1);
    int k = 0, after_value = 0;
    char *p = buf;
    for (;;) {
        while (isspace((unsigned char)*p)) p++;
        if (*p == ',' || (!*p && k > 0 && !after_value)) {
            if (!after_value) {
                const size_t at = (size_t)(p - buf);
                free(t);
                return fail_empty(opt, s, at);
            }
            after_value = 0;
            *p++ = '\0';
            continue;
        }
        if (!*p) break;
        t[k++] = p;
        after_value = 1;
        while (*p && *p != ',' && !isspace((unsigned char)*p)) p++;
        if (isspace((unsigned char)*p)) *p++ = '\0';
    }
    if (k == 0) {
        free(t);
        return cli_fail("%s: empty list", opt);
    }
    *items = t;
    *n = k;
    return 0;
}

int cli_vec3(const char *opt, const char *s, double v[3])
{
    double *a;
    int n;
    if (cli_doubles(opt, s, &a, &n)) return CLI_EXIT_USAGE;
    if (n != 3) { free(a); return cli_fail("%s expects three numbers X,Y,Z, got %d", opt, n); }
    memcpy(v, a, 3 * sizeof *v);
    free(a);
    return 0;
}

int cli_format_parse(const char *s, cli_format *out)
{
    if (!strcmp(s, "table")) *out = CLI_TABLE;
    else if (!strcmp(s, "csv")) *out = CLI_CSV;
    else if (!strcmp(s, "json")) *out = CLI_JSON;
    else return cli_fail("--format: unknown format '%s' (expected table, csv or json)", s);
    return 0;
}

int cli_convention(const char *s, sh_convention *out)
{
    if (sh_convention_parse(s, out)) return cli_fail("--convention: %s", sh_last_error());
    return 0;
}

/* ---- coefficient files ---------------------------------------------- */

static int json_to_doubles(const json_t *a, double **out, int *len, const char *path)
{
    if (!json_is_array(a) || json_array_size(a) == 0)
        return cli_fail("%s: coefficients must be a non-empty array of numbers", path);
    size_t n = json_array_size(a);
    if (n > CLI_MAX_NUMBERS) return cli_fail("%s: more than %d coefficients", path, CLI_MAX_NUMBERS);
    double *v = malloc(n * sizeof *v);
    if (!v) return cli_fail("out of memory");
    for (size_t i = 0; i < n; i++) {
        const json_t *x = json_array_get(a, i);
        if (!json_is_number(x)) { free(v); return cli_fail("%s: coefficient %zu is not a number", path, i); }
        v[i] = json_number_value(x);
    }
    *out = v;
    *len = (int)n;
    return 0;
}

/* ---- small statistics ---------------------------------------------------- */

int cli_cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

double cli_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cli_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* ---- input files -------------------------------------------------------- */

int cli_read_file(const char *what, const char *path, size_t max, char **buf, size_t *n)
{
    if (cli_input(what, path)) return CLI_EXIT_USAGE;
    /* the library's input policy: regular files only, size checked first */
    if (sh_input_read_all(what, path, (long long)max, buf, n)) return cli_fail_status(SH_EIO);
    return 0;
}

int cli_json_parse(const char *buf, size_t n, const char *name, json_t **root)
{
    return sh__json_parse(buf, n, name, root) ? cli_fail_status(SH_EFORMAT) : 0;
}

/* A coefficient file's size: four channels of the order in text, 40 bytes a
 * number, and room for the JSON around them.  Memory: the text while it is
 * read, then per number its double and, in JSON, the parsed value
 * (CLI_JSON_NUMBER_BYTES). */
#define COEFF_TEXT_BYTES 40
#define COEFF_JSON_SLACK 4096
#define CLI_JSON_NUMBER_BYTES 100
#define CLI_PATH_WHAT 1200

int cli_read_coeffs_file(const char *path, int max_order, double **out, int *len, int *nchan,
                         char names[SH_IMAGE_MAX_CHANNELS][8])
{
    const int mo = max_order > 0 && max_order < SHLAB_MAX_ORDER ? max_order : SHLAB_MAX_ORDER;
    const size_t max = (size_t)SH_IMAGE_MAX_CHANNELS * mo * mo * COEFF_TEXT_BYTES + COEFF_JSON_SLACK;
    /* the size against the order and the memory before a byte is read */
    sh_input in;
    if (cli_input("coefficient file", path)) return CLI_EXIT_USAGE;
    if (sh_input_open("coefficient file", path, -1, &in)) return cli_fail_status(SH_EIO);
    const double size = (double)in.size;
    sh_input_close(&in);
    if (size > (double)max) {
        char a[32], b[32];
        return cli_fail("coefficient file '%s' has %s, more than the %s four channels of order %d take in text",
                        path, sh__bytes_str(size, a, sizeof a), sh__bytes_str((double)max, b, sizeof b), mo);
    }
    char what[CLI_PATH_WHAT];
    snprintf(what, sizeof what, "reading '%s'", path);
    if (cli_mem_check("coefficient file", size, what)) return CLI_EXIT_USAGE;
    char *buf;
    size_t n;
    if (cli_read_file("coefficient file", path, max, &buf, &n)) return CLI_EXIT_USAGE;
    const int rc = cli_read_coeffs_mem(buf, n, path, out, len, nchan, names);
    free(buf);
    return rc;
}

/* The numbers in a text: digits that do not continue a number. */
static size_t count_numbers(const char *buf, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (isdigit((unsigned char)buf[i]) && (i == 0 || !strchr("0123456789.eE+-", buf[i - 1]) || !buf[i - 1])) k++;
    return k;
}

int cli_read_coeffs_mem(const char *buf, size_t n, const char *path, double **out, int *len,
                        int *nchan, char names[SH_IMAGE_MAX_CHANNELS][8])
{
    if (memchr(buf, '\0', n))
        return cli_fail("%s: contains a NUL byte (not a text or JSON coefficient file)", path);
    const char *p = buf;
    while (*p && isspace((unsigned char)*p)) p++;
    /* the parsed numbers' memory, before parsing */
    const size_t count = count_numbers(buf, n);
    char what[CLI_PATH_WHAT];
    snprintf(what, sizeof what, "parsing the %zu numbers of '%s'", count, path);
    if (cli_mem_check("coefficient file", (double)count * (*p == '{' ? CLI_JSON_NUMBER_BYTES : 8), what))
        return CLI_EXIT_USAGE;
    int rc = 0;
    if (*p == '{') {
        json_t *root = NULL;
        if (cli_json_parse(buf, n, path, &root)) {
            rc = CLI_EXIT_USAGE;
        } else if (json_object_get(root, "coeffs")) {
            rc = json_to_doubles(json_object_get(root, "coeffs"), out, len, path);
            *nchan = 1;
            if (!rc && names) strcpy(names[0], "Y");
        } else if (json_is_object(json_object_get(root, "channels"))) {
            json_t *ch = json_object_get(root, "channels");
            const char *key;
            json_t *val;
            int c = 0, L = -1;
            double *all = NULL;
            json_object_foreach(ch, key, val) {
                if (c == SH_IMAGE_MAX_CHANNELS) { rc = cli_fail("%s: more than %d channels", path, SH_IMAGE_MAX_CHANNELS); break; }
                if (strlen(key) == 0 || strlen(key) > 7) {
                    rc = cli_fail("%s: channel name '%.20s' must have 1 to 7 characters", path, key);
                    break;
                }
                double *v;
                int vl;
                if ((rc = json_to_doubles(val, &v, &vl, path))) break;
                if (L >= 0 && vl != L) { free(v); rc = cli_fail("%s: channels have different lengths", path); break; }
                L = vl;
                double *na = realloc(all, (size_t)(c + 1) * L * sizeof *na);
                if (!na) { free(v); rc = cli_fail("out of memory"); break; }
                all = na;
                memcpy(all + (size_t)c * L, v, L * sizeof *v);
                free(v);
                if (names) snprintf(names[c], 8, "%s", key);
                c++;
            }
            if (!rc && c == 0) rc = cli_fail("%s: \"channels\" is empty", path);
            if (rc) free(all);
            else { *out = all; *len = L; *nchan = c; }
        } else {
            rc = cli_fail("%s: JSON has neither \"coeffs\" nor \"channels\"", path);
        }
        json_decref(root);
    } else {
        rc = cli_doubles(path, buf, out, len);
        *nchan = 1;
        if (!rc && names) strcpy(names[0], "Y");
    }
    return rc;
}

int cli_orders(const char *opt, const char *s, int *out, int max, int *n)
{
    /* each element through cli_order, so that a list words its errors as a
     * single --order does */
    char **t;
    int k, rc = 0;
    if (cli_split(opt, s, &t, &k)) return CLI_EXIT_USAGE;
    if (k > max) rc = cli_fail("%s: at most %d orders", opt, max);
    for (int i = 0; i < k && !rc; i++) rc = cli_order(opt, t[i], &out[i]);
    free(t);
    if (!rc) *n = k;
    return rc;
}

int cli_fail_json(const char *what, const char *path, int err_no, const json_error_t *err)
{
    struct stat sb;
    if (json_error_code(err) == json_error_cannot_open_file)
        return cli_fail("cannot open %s '%s': %s", what, path, err_no ? strerror(err_no) : err->text);
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return cli_fail("cannot read %s '%s': it is a directory", what, path);
    if (err->line > 0)
        return cli_fail("%s '%s' is not valid JSON: %s (line %d, column %d)", what, path, err->text, err->line,
                        err->column);
    return cli_fail("%s '%s' is not valid JSON: %s", what, path, err->text);
}

void cli_progress_step_est(void *ctx, int done, int total, const char *what)
{
    cli_progress *p = ctx;
    if (p && !p->quiet && !p->estimated && done < total) {
        /* the first step carries the set-up: extrapolate from the second */
        const double t = now_s() - p->t0;
        if (done == 1) p->t1 = t;
        if (done == 2) {
            const double all = t + (t - p->t1) * (total - 2);
            if (all > 2.0)
                fprintf(stderr, "%s: about %.0f s in all (%d %s so far took %.1f s)\n", p->cmd, all, done,
                        what ? what : "steps", t);
            p->estimated = 1;
        }
    }
    /* a run that printed nothing on the way ends silently (the result follows) */
    if (p && done >= total && !p->printed) return;
    cli_progress_step(ctx, done, total, what);
}

int cli_mem_check(const char *cmd, double bytes, const char *what)
{
    /* the library's rule: what is available (sh__mem_available) */
    const size_t a = sh__mem_available();
    const double avail = a == SIZE_MAX ? 0.0 : (double)a;
    if (avail > 0.0 && bytes > avail)
        return cli_fail("%s: %s needs %.3g GB of memory, only %.3g GB is available", cmd, what, bytes / 1e9,
                        avail / 1e9);
    return 0;
}
