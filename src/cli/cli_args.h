/* cli_args.h — declared command-line options (not installed).
 *
 * Each command declares its options once, as a table of cli_opt: the name,
 * the kind of value and its range or choices, the default, the field of the
 * command's argument struct that receives it, and one help line.  One parser
 * (cli_args_parse) reads argv against the table: it applies the defaults,
 * refuses unknown options, repeats, missing values, values out of range and
 * options that need another one, each with one error line, and stops at the
 * first problem.  --help is printed from the same table (cli_args_help), so
 * the help text, the man page (tools/help2man.sh reads --help) and the parser
 * cannot disagree.
 *
 * Options that several commands share (the scene, the lighting, the rays,
 * the rotation input, the output format, sharding) are declared once as a
 * group — a table whose offsets are relative to a sub-struct — and a command
 * includes the group with CLI_GROUP(struct, field, table).
 *
 * The parser keeps no state outside its arguments: two parses in one process
 * (the tests, the fuzz harnesses) do not see each other.
 *
 * Syntax: `--name VALUE` or `--name=VALUE` (a value may begin with '-', as in
 * --euler -0.3,0,0), flags as `--name`; `-h` is --help; `--` ends the
 * options; names are matched exactly (no abbreviations, so adding an option
 * never makes an old command line ambiguous).  Positional arguments are
 * refused unless the command declares that it takes them (cli_cmd.positional).
 */
#ifndef SHLAB_CLI_ARGS_H
#define SHLAB_CLI_ARGS_H

#include <stddef.h>

typedef enum {
    CLI_T_END = 0, /* ends a table */
    CLI_T_FLAG,    /* int field set to 1 */
    CLI_T_INT,     /* int in [lo, hi] */
    CLI_T_LONG,    /* long in [lo, hi] */
    CLI_T_REAL,    /* double in [lo, hi] (either end open with CLI_LO_OPEN / CLI_HI_OPEN) */
    CLI_T_STRING,  /* const char *, pointing into argv (non-empty) */
    CLI_T_CHOICE,  /* int: the index of the value in choices[] */
    CLI_T_CUSTOM,  /* parse(): the value checked and stored by the command's own function */
    CLI_T_ORDER,   /* int order in 1..hi ("order N is outside 1..MAX (why)", cli_order_check) */
    CLI_T_GROUP,   /* a shared group: every option of `group`, offsets relative to off */
    CLI_T_HEADING, /* a heading line in --help ("Rotation:"), no option */
    CLI_T_DEFAULT, /* the command's own default of an option its groups declare (name, def) */
} cli_type;

enum {
    CLI_LO_OPEN = 1u << 0,   /* CLI_T_REAL: lo excluded */
    CLI_HI_OPEN = 1u << 1,   /* CLI_T_REAL: hi excluded */
    CLI_HIDDEN = 1u << 2,    /* parsed, not listed by --help */
    CLI_NO_DEFAULT = 1u << 3 /* --help prints no "(default ...)" even if def is set */
};

/* parse() of a CLI_T_CUSTOM option: store s into *field (the option's field)
 * or print one error line (cli_fail) and return its exit code.  opt is
 * "--name" for the messages. */
typedef int (*cli_parse_fn)(const char *opt, const char *s, void *field);

typedef struct cli_opt {
    cli_type type;
    const char *name;  /* without the dashes */
    const char *meta;  /* the value's name in --help ("N", "FILE"); NULL for flags */
    size_t off;        /* offsetof(struct, field) */
    double lo, hi;     /* numbers: the range (lo = hi = 0: any value) */
    unsigned flags;
    const char *def;   /* default, as text: parsed into the field before argv */
    const char *help;  /* one line; '\n' continues it, indented */
    const char *const *choices; /* CLI_T_CHOICE: NULL-terminated names */
    cli_parse_fn parse;         /* CLI_T_CUSTOM */
    const struct cli_opt *group; /* CLI_T_GROUP */
    const char *needs; /* another option this one applies to ("check"): refused without it */
    const char *why;   /* CLI_T_ORDER: the reason for the command's limit, or NULL */
} cli_opt;

/* Table entries.  S is the argument struct, F the field. */
#define CLI_FLAG(S, F, NAME, HELP) {.type = CLI_T_FLAG, .name = NAME, .off = offsetof(S, F), .help = HELP}
#define CLI_INT(S, F, NAME, META, LO, HI, DEF, HELP)                                               \
    {.type = CLI_T_INT, .name = NAME, .meta = META, .off = offsetof(S, F), .lo = LO, .hi = HI,      \
     .def = DEF, .help = HELP}
#define CLI_LONG(S, F, NAME, META, LO, HI, DEF, HELP)                                              \
    {.type = CLI_T_LONG, .name = NAME, .meta = META, .off = offsetof(S, F), .lo = LO, .hi = HI,     \
     .def = DEF, .help = HELP}
#define CLI_REAL(S, F, NAME, META, LO, HI, FLAGS, DEF, HELP)                                       \
    {.type = CLI_T_REAL, .name = NAME, .meta = META, .off = offsetof(S, F), .lo = LO, .hi = HI,     \
     .flags = FLAGS, .def = DEF, .help = HELP}
#define CLI_STRING(S, F, NAME, META, HELP)                                                         \
    {.type = CLI_T_STRING, .name = NAME, .meta = META, .off = offsetof(S, F), .help = HELP}
#define CLI_CHOICE(S, F, NAME, META, CHOICES, DEF, HELP)                                           \
    {.type = CLI_T_CHOICE, .name = NAME, .meta = META, .off = offsetof(S, F), .choices = CHOICES,   \
     .def = DEF, .help = HELP}
#define CLI_CUSTOM(S, F, NAME, META, FN, DEF, HELP)                                                \
    {.type = CLI_T_CUSTOM, .name = NAME, .meta = META, .off = offsetof(S, F), .parse = FN,          \
     .def = DEF, .help = HELP}
#define CLI_ORDER(S, F, MAX, WHY, HELP)                                                            \
    {.type = CLI_T_ORDER, .name = "order", .meta = "N", .off = offsetof(S, F), .lo = 1, .hi = MAX,    \
     .why = WHY, .help = HELP}
#define CLI_GROUP(S, F, TABLE) {.type = CLI_T_GROUP, .off = offsetof(S, F), .group = TABLE}
#define CLI_HEADING(TEXT) {.type = CLI_T_HEADING, .help = TEXT}
/* A shared group declares an option once, with the default most commands
 * want; a command whose default differs (shadow-field's 4096 rays) says so
 * in its own table: the parser applies it instead, --help prints it. */
#define CLI_DEFAULT(NAME, DEF) {.type = CLI_T_DEFAULT, .name = NAME, .def = DEF}
#define CLI_END {.type = CLI_T_END}

/* Options every command words the same way (cli_args.c). */
extern const char *const cli_format_names[];     /* table, csv, json: cli_format */
extern const char *const cli_convention_names[]; /* cs, nocs: sh_convention */
#define CLI_FORMAT(S, F)                                                                           \
    CLI_CHOICE(S, F, "format", "table|csv|json", cli_format_names, "table", "output format")
#define CLI_CONVENTION(S, F)                                                                       \
    CLI_CHOICE(S, F, "convention", "cs|nocs", cli_convention_names, "cs",                          \
               "Condon-Shortley phase (cs) or not")
#define CLI_DEGREES(S, F, HELP) CLI_FLAG(S, F, "degrees", HELP)

/* What a parse saw: which options were given (by the user, not defaults), and
 * where the positional arguments are. */
#define CLI_ARGS_MAX 96 /* options in one command, groups included */
typedef struct {
    const char *given[CLI_ARGS_MAX]; /* names given on the command line */
    int ngiven;
    int first_positional; /* argv index of the first positional argument (argc if none) */
} cli_parsed;

/* A command's declaration, beside its run(): the usage line(s) after
 * "Usage: shlab ", a description printed before the options, the table, and
 * notes printed after them (formulas, JSON fields).  positional: what the
 * command takes after its options ("FILE...") or NULL for nothing. */
typedef struct cli_cmd {
    const char *name;
    const char *usage;
    const char *about;
    const cli_opt *opts;
    const char *notes;
    const char *positional;
} cli_cmd;

/* Parse argv[1..argc-1] (argv[0] is the command's name) into args.  Returns
 * -1 to go on, 0 after printing --help (the command returns 0 at once), or
 * CLI_EXIT_USAGE after one error line. */
int cli_args_parse(const cli_cmd *cmd, int argc, char **argv, void *args, cli_parsed *seen);
/* 1 if option `name` (no dashes) was given on the command line. */
int cli_given(const cli_parsed *seen, const char *name);
/* The --help text of a command, on stdout; returns an exit code. */
int cli_args_help(const cli_cmd *cmd);

#endif
