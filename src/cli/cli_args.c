/* cli_args.c — the one parser of declared options, and --help from the same
 * tables (cli_args.h). */
#include "cli_args.h"
#include "cli.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The closing paragraph of every --help (where the conventions are written). */
const char cli_conventions_note[] =
    "\nConventions (basis, index, rotations, angles and units, output): docs/CONVENTIONS.md\n"
    "in the shlab source, installed as share/doc/shlab/CONVENTIONS.md.\n";

const char *const cli_format_names[] = {"table", "csv", "json", NULL};
const char *const cli_convention_names[] = {"cs", "nocs", NULL};

/* ---- the table, groups flattened ------------------------------------------ */

typedef struct {
    const cli_opt *o;
    size_t base; /* offset of the group's sub-struct in the command's struct */
} flat_opt;

typedef struct {
    flat_opt v[CLI_ARGS_MAX];
    int n;
} flat_table;

/* Append every option of t (groups expanded, headings skipped) to f. */
static int flatten(const cli_opt *t, size_t base, flat_table *f)
{
    for (; t && t->type != CLI_T_END; t++) {
        if (t->type == CLI_T_HEADING || t->type == CLI_T_DEFAULT) continue;
        if (t->type == CLI_T_GROUP) {
            if (flatten(t->group, base + t->off, f)) return -1;
            continue;
        }
        if (f->n == CLI_ARGS_MAX) return -1;
        f->v[f->n].o = t;
        f->v[f->n].base = base;
        f->n++;
    }
    return 0;
}

static const flat_opt *find(const flat_table *f, const char *name, size_t len)
{
    for (int k = 0; k < f->n; k++)
        if (strlen(f->v[k].o->name) == len && !strncmp(f->v[k].o->name, name, len)) return &f->v[k];
    return NULL;
}

/* ---- values ----------------------------------------------------------------- */

/* v as %g writes it when that reads back as v, else with the digits it
 * needs: 0.1 and 170, not 0.10000000000000001 or 1.7e+02 */
static void shortest(double v, char *buf, size_t n)
{
    for (int digits = 6; digits <= 17; digits++) {
        snprintf(buf, n, "%.*g", digits, v);
        if (strtod(buf, NULL) == v) return;
    }
}

/* "must be in (0, 1]", "must be > 0", "must be <= 10": the range of a real. */
static void real_range_text(const cli_opt *o, char *buf, size_t n)
{
    const int lo_open = (o->flags & CLI_LO_OPEN) != 0, hi_open = (o->flags & CLI_HI_OPEN) != 0;
    char lo[32], hi[32];
    shortest(o->lo, lo, sizeof lo);
    shortest(o->hi, hi, sizeof hi);
    if (isinf(o->hi))
        snprintf(buf, n, "%s %s", lo_open ? ">" : ">=", lo);
    else if (isinf(o->lo))
        snprintf(buf, n, "%s %s", hi_open ? "<" : "<=", hi);
    else
        snprintf(buf, n, "in %c%s, %s%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
}

static int has_range(const cli_opt *o) { return o->lo != 0 || o->hi != 0; }

/* "1..32", or ">= 0" when the upper end is the type's largest value (a seed,
 * a count with no limit of its own: 9223372036854775807 is no limit to print). */
static void int_range_text(const cli_opt *o, char *buf, size_t n)
{
    const double top = o->type == CLI_T_LONG ? (double)LONG_MAX : (double)INT_MAX;
    if (o->hi >= top) snprintf(buf, n, ">= %.0f", o->lo);
    else snprintf(buf, n, "%.0f..%.0f", o->lo, o->hi);
}

static int int_out_of_range(const char *opt, const cli_opt *o)
{
    char r[64];
    int_range_text(o, r, sizeof r);
    if (r[0] == '>') return cli_fail("%s: must be %s", opt, r);
    return cli_fail("%s: out of range %s", opt, r);
}

static int real_in_range(const cli_opt *o, double v)
{
    if (!has_range(o)) return 1;
    if ((o->flags & CLI_LO_OPEN) ? !(v > o->lo) : !(v >= o->lo)) return 0;
    if ((o->flags & CLI_HI_OPEN) ? !(v < o->hi) : !(v <= o->hi)) return 0;
    return 1;
}

/* Parse s into the option's field (base + off of args); one error line and
 * CLI_EXIT_USAGE if it is not a value of the option's kind and range. */
static int set_value(const flat_opt *fo, const char *s, void *args)
{
    const cli_opt *o = fo->o;
    void *field = (char *)args + fo->base + o->off;
    char opt[80];
    snprintf(opt, sizeof opt, "--%s", o->name);
    switch (o->type) {
    case CLI_T_FLAG: *(int *)field = 1; return 0;
    case CLI_T_INT: {
        int v;
        if (cli_int(opt, s, &v)) return CLI_EXIT_USAGE;
        if (has_range(o) && (v < o->lo || v > o->hi)) return int_out_of_range(opt, o);
        *(int *)field = v;
        return 0;
    }
    case CLI_T_LONG: {
        long v;
        if (cli_long(opt, s, &v)) return CLI_EXIT_USAGE;
        if (has_range(o) && ((double)v < o->lo || (double)v > o->hi)) return int_out_of_range(opt, o);
        *(long *)field = v;
        return 0;
    }
    case CLI_T_REAL: {
        double v;
        if (cli_double(opt, s, &v)) return CLI_EXIT_USAGE;
        if (!real_in_range(o, v)) {
            char r[96];
            real_range_text(o, r, sizeof r);
            return cli_fail("%s: must be %s", opt, r);
        }
        *(double *)field = v;
        return 0;
    }
    case CLI_T_STRING:
        if (!*s) return cli_fail("%s: empty value", opt);
        *(const char **)field = s;
        return 0;
    case CLI_T_CHOICE:
        for (int k = 0; o->choices[k]; k++)
            if (!strcmp(o->choices[k], s)) {
                *(int *)field = k;
                return 0;
            }
        {
            char list[256] = "";
            for (int k = 0; o->choices[k]; k++) {
                strncat(list, k ? ", " : "", sizeof list - strlen(list) - 1);
                strncat(list, o->choices[k], sizeof list - strlen(list) - 1);
            }
            return cli_fail("%s: unknown value '%s' (one of %s)", opt, s, list);
        }
    case CLI_T_ORDER: return cli_order_max(opt, s, (int)o->hi, o->why, (int *)field);
    case CLI_T_CUSTOM: return o->parse(opt, s, field);
    default: return cli_fail("%s: option of unknown kind", opt);
    }
}

/* ---- parsing ---------------------------------------------------------------- */

int cli_given(const cli_parsed *seen, const char *name)
{
    for (int k = 0; k < seen->ngiven; k++)
        if (!strcmp(seen->given[k], name)) return 1;
    return 0;
}

/* The command's own default of option `name` (a CLI_DEFAULT entry in its
 * table or its groups; the last one wins), or NULL. */
static const char *override_of(const cli_opt *t, const char *name)
{
    const char *def = NULL;
    for (; t && t->type != CLI_T_END; t++) {
        if (t->type == CLI_T_GROUP) {
            const char *d = override_of(t->group, name);
            if (d) def = d;
        } else if (t->type == CLI_T_DEFAULT && !strcmp(t->name, name)) {
            def = t->def;
        }
    }
    return def;
}

/* A CLI_DEFAULT must name an option of the command (else a bug). */
static int overrides_known(const cli_cmd *cmd, const cli_opt *t, const flat_table *f)
{
    for (; t && t->type != CLI_T_END; t++) {
        if (t->type == CLI_T_GROUP && overrides_known(cmd, t->group, f)) return -1;
        if (t->type == CLI_T_DEFAULT && !find(f, t->name, strlen(t->name)))
            return cli_fail("%s: a default for --%s, which it does not take (a bug)", cmd->name, t->name);
    }
    return 0;
}

static int apply_defaults(const cli_cmd *cmd, const flat_table *f, void *args)
{
    if (overrides_known(cmd, cmd->opts, f)) return -1;
    for (int k = 0; k < f->n; k++) {
        const char *own = override_of(cmd->opts, f->v[k].o->name);
        const char *def = own ? own : f->v[k].o->def;
        if (def && set_value(&f->v[k], def, args))
            return cli_fail("%s: the default of --%s is refused (a bug)", cmd->name, f->v[k].o->name);
    }
    return 0;
}

int cli_args_parse(const cli_cmd *cmd, int argc, char **argv, void *args, cli_parsed *seen)
{
    flat_table f = {.n = 0};
    memset(seen, 0, sizeof *seen);
    seen->first_positional = argc;
    if (flatten(cmd->opts, 0, &f)) return cli_fail("%s: too many options declared (a bug)", cmd->name);
    if (apply_defaults(cmd, &f, args)) return CLI_EXIT_USAGE;
    int i = 1, npos = 0;
    for (; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--")) { i++; break; }
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) return cli_args_help(cmd);
        if (a[0] != '-' || a[1] == '\0') { /* a positional argument ("-": standard input) */
            if (!cmd->positional) return cli_fail("%s: unexpected argument '%s'", cmd->name, a);
            if (!npos++) seen->first_positional = i;
            continue;
        }
        if (a[1] != '-') return cli_fail("%s: unknown option '%s' (see 'shlab %s --help')", cmd->name, a, cmd->name);
        if (npos) return cli_fail("%s: option '%s' after the arguments (options come first)", cmd->name, a);
        const char *name = a + 2, *eq = strchr(name, '=');
        const size_t len = eq ? (size_t)(eq - name) : strlen(name);
        const flat_opt *fo = find(&f, name, len);
        if (!fo) return cli_fail("%s: unknown option '%.*s' (see 'shlab %s --help')", cmd->name, (int)len + 2, a, cmd->name);
        if (cli_given(seen, fo->o->name))
            return cli_fail("%s: option --%s given twice (give each option once)", cmd->name, fo->o->name);
        const char *val = NULL;
        if (fo->o->type == CLI_T_FLAG) {
            if (eq) return cli_fail("%s: option --%s takes no value", cmd->name, fo->o->name);
        } else if (eq) {
            val = eq + 1;
        } else if (i + 1 < argc) {
            val = argv[++i];
        } else {
            return cli_fail("%s: option '%s' needs a value (see 'shlab %s --help')", cmd->name, a, cmd->name);
        }
        if (seen->ngiven == CLI_ARGS_MAX) return cli_fail("%s: too many options", cmd->name);
        seen->given[seen->ngiven++] = fo->o->name;
        const int rc = set_value(fo, val, args);
        if (rc) return rc;
    }
    /* after "--": everything is positional */
    for (; i < argc; i++) {
        if (!cmd->positional) return cli_fail("%s: unexpected argument '%s'", cmd->name, argv[i]);
        if (!npos++) seen->first_positional = i;
    }
    for (int k = 0; k < seen->ngiven; k++) {
        const flat_opt *fo = find(&f, seen->given[k], strlen(seen->given[k]));
        if (fo->o->needs && !cli_given(seen, fo->o->needs))
            return cli_fail("%s: --%s applies to --%s only", cmd->name, fo->o->name, fo->o->needs);
    }
    return -1;
}

/* ---- --help ----------------------------------------------------------------- */

#define HELP_COL 24 /* the column where the help lines of the options begin (1-based) */

/* "(default D; 1..32)": what the table knows beyond the help line, unless
 * the help line says it already. */
static void auto_text(const cli_opt *o, const char *def, char *buf, size_t n)
{
    char parts[2][128];
    int np = 0;
    const int says_default = o->help && strstr(o->help, "default") != NULL;
    if (def && !(o->flags & CLI_NO_DEFAULT) && !says_default) snprintf(parts[np++], sizeof parts[0], "default %s", def);
    if (has_range(o) && (o->type == CLI_T_INT || o->type == CLI_T_LONG || o->type == CLI_T_ORDER)) {
        char r[64];
        int_range_text(o, r, sizeof r);
        if (!o->help || !strstr(o->help, r)) snprintf(parts[np++], sizeof parts[0], "%s", r);
    } else if (has_range(o) && o->type == CLI_T_REAL) {
        real_range_text(o, parts[np], sizeof parts[0]);
        np++;
    }
    buf[0] = '\0';
    if (!np) return;
    snprintf(buf, n, "(%s%s%s)", parts[0], np > 1 ? "; " : "", np > 1 ? parts[1] : "");
}

static void help_option(FILE *out, const cli_opt *o, const char *def)
{
    char head[96], extra[300];
    snprintf(head, sizeof head, "  --%s%s%s", o->name, o->meta ? " " : "", o->meta ? o->meta : "");
    auto_text(o, def, extra, sizeof extra);
    if ((int)strlen(head) >= HELP_COL - 1) {
        fprintf(out, "%s\n%*s", head, HELP_COL - 1, "");
    } else {
        fprintf(out, "%-*s", HELP_COL - 1, head);
    }
    int col = HELP_COL - 1;
    for (const char *p = o->help ? o->help : ""; *p; p++) {
        if (*p == '\n') {
            fprintf(out, "\n%*s", HELP_COL - 1, "");
            col = HELP_COL - 1;
        } else {
            fputc(*p, out);
            col++;
        }
    }
    if (*extra) {
        if (col + 1 + (int)strlen(extra) > 80) fprintf(out, "\n%*s%s", HELP_COL - 1, "", extra);
        else fprintf(out, "%s%s", o->help && *o->help ? " " : "", extra);
    }
    fputc('\n', out);
}

/* root: the command's table, whose CLI_DEFAULT entries replace the defaults of t's options */
static void help_table(FILE *out, const cli_opt *t, const cli_opt *root)
{
    for (; t && t->type != CLI_T_END; t++) {
        if (t->flags & CLI_HIDDEN || t->type == CLI_T_DEFAULT) continue;
        if (t->type == CLI_T_GROUP) {
            help_table(out, t->group, root);
        } else if (t->type == CLI_T_HEADING) {
            fprintf(out, "%s\n", t->help);
        } else {
            const char *own = override_of(root, t->name);
            help_option(out, t, own ? own : t->def);
        }
    }
}

int cli_args_help(const cli_cmd *cmd)
{
    FILE *out = stdout;
    fprintf(out, "Usage: shlab %s\n", cmd->usage);
    if (cmd->about && *cmd->about) fprintf(out, "\n%s", cmd->about);
    fputs("\nOptions:\n", out);
    help_table(out, cmd->opts, cmd->opts);
    fputs("  --help               this text\n", out);
    if (cmd->notes && *cmd->notes) fprintf(out, "\n%s", cmd->notes);
    fputs(cli_conventions_note, out);
    if (fflush(out) != 0 || ferror(out)) return cli_fail("cannot write to standard output");
    return CLI_EXIT_OK;
}
