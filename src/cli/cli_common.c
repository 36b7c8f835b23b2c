/* cli_common.c — argument parsing and error reporting shared by commands. */
#define _GNU_SOURCE
#include "cli.h"
#include "core/shlab_internal.h"

#include <ctype.h>
#include <getopt.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

void cli_progress_start(cli_progress *p, const char *cmd, int quiet)
{
    p->cmd = cmd;
    p->quiet = quiet;
    p->printed = 0;
    p->t0 = p->last = now_s();
}

void cli_progress_step(void *ctx, int done, int total, const char *what)
{
    cli_progress *p = ctx;
    if (!p || p->quiet) return;
    const double t = now_s();
    const int end = done >= total;
    if (t - p->t0 < 1.0 || (t - p->last < 1.0 && !(end && p->printed))) return;
    fprintf(stderr, "%s: %d of %d %s, %.1f s\n", p->cmd, done, total, what ? what : "steps", t - p->t0);
    p->last = t;
    p->printed = 1;
}

int cli_fail_status(int st)
{
    const char *why = sh_last_error();
    return cli_fail("%s", (why && *why) ? why : sh_strerror(st));
}

int cli_fail_getopt(const char *cmd, char **argv, int optind_now, int optopt_val)
{
    const char *arg = argv[optind_now - 1];
    if (!arg) arg = "?";
    if (optopt_val == 0 || (arg[0] == '-' && arg[1] != '-' && optopt_val != 'h'))
        return cli_fail("%s: unknown option '%s' (see 'shlab %s --help')", cmd, arg, cmd);
    return cli_fail("%s: option '%s' needs a value (see 'shlab %s --help')", cmd, arg, cmd);
}

int cli_common_opt(const cli_command *cmd, int o, char **argv, cli_common *c)
{
    switch (o) {
    case 'h': return cli_help(cmd);
    case CLI_OPT_FORMAT: return cli_format_parse(optarg, &c->fmt) ? CLI_EXIT_USAGE : -1;
    case CLI_OPT_ORDER: return cli_order("--order", optarg, &c->order) ? CLI_EXIT_USAGE : -1;
    case CLI_OPT_CONVENTION: return cli_convention(optarg, &c->conv) ? CLI_EXIT_USAGE : -1;
    case CLI_OPT_DEGREES: c->degrees = 1; return -1;
    case CLI_OPT_METHOD:
        if (cli_method(optarg, &c->method)) return CLI_EXIT_USAGE;
        c->have_method = 1;
        return -1;
    case CLI_OPT_PRECISION: return cli_precision(optarg, &c->prec) ? CLI_EXIT_USAGE : -1;
    default: return cli_fail_getopt(cmd->name, argv, optind, optopt);
    }
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

int cli_order(const char *opt, const char *s, int *out)
{
    if (cli_int(opt, s, out)) return CLI_EXIT_USAGE;
    if (sh_check_order(*out)) return cli_fail("%s: %s", opt, sh_last_error());
    return 0;
}

int cli_double(const char *opt, const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    while (end && isspace((unsigned char)*end)) end++;
    if (end == s || *end != '\0') return cli_fail("%s expects a number, got '%s'", opt, s);
    if (!isfinite(v)) return cli_fail("%s: '%s' is not a finite number", opt, s);
    *out = v;
    return 0;
}

int cli_doubles(const char *opt, const char *s, double **out, int *n)
{
    size_t cap = 16, k = 0;
    double *v = malloc(cap * sizeof *v);
    if (!v) return cli_fail("out of memory");
    const char *p = s;
    for (;;) {
        while (*p && (isspace((unsigned char)*p) || *p == ',' || *p == '[' || *p == ']')) p++;
        if (!*p) break;
        char *end;
        double x = strtod(p, &end);
        if (end == p) {
            free(v);
            return cli_fail("%s: cannot read a number at '%.20s'", opt, p);
        }
        if (!isfinite(x)) {
            free(v);
            return cli_fail("%s: value %zu is not a finite number", opt, k + 1);
        }
        if (k == cap) {
            double *nv = realloc(v, 2 * cap * sizeof *v);
            if (!nv) { free(v); return cli_fail("out of memory"); }
            v = nv;
            cap *= 2;
        }
        v[k++] = x;
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

int cli_read_coeffs_file(const char *path, double **out, int *len, int *nchan,
                         char names[SH_IMAGE_MAX_CHANNELS][8])
{
    FILE *f = fopen(path, "rb");
    if (!f) return cli_fail("cannot open '%s': %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    if (!buf) { fclose(f); return cli_fail("out of memory"); }
    size_t got;
    while ((got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            char *nb = realloc(buf, 2 * cap + 1);
            if (!nb) { free(buf); fclose(f); return cli_fail("out of memory"); }
            buf = nb;
            cap *= 2;
        }
    }
    int rerr = ferror(f);
    fclose(f);
    if (rerr) { free(buf); return cli_fail("cannot read '%s'", path); }
    buf[n] = '\0';
    if (memchr(buf, '\0', n)) {
        free(buf);
        return cli_fail("%s: contains a NUL byte (not a text or JSON coefficient file)", path);
    }
    const char *p = buf;
    while (*p && isspace((unsigned char)*p)) p++;
    int rc = 0;
    if (*p == '{') {
        json_error_t err;
        json_t *root = json_loads(buf, JSON_DECODE_ANY, &err);
        if (!root) {
            rc = cli_fail("%s: not valid JSON (line %d: %s)", path, err.line, err.text);
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
    free(buf);
    return rc;
}
