/* test_cli_args.c — the declared-option parser (src/cli/cli_args.c): values
 * of every kind land in their fields, defaults apply, and each misuse is
 * refused with exit 2 — unknown, repeated, valueless, out of range, a
 * choice not listed, an option without the one it needs, a positional
 * argument where none is declared; the order's wording is the one every
 * command uses; two parses share no state; --help lists what the table
 * declares, defaults and ranges included.  Truth: the table itself and the
 * wording of cli_order_check. */
#include "testutil.h"

#include "cli/cli.h"
#include "cli/cli_args.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

typedef struct {
    int seed;
} sub_args;

typedef struct {
    int order, rays, quiet, check, fmt, conv, degrees;
    long count;
    double beta, albedo;
    const char *out;
    sub_args sub;
} args;

static const cli_opt sub_opts[] = {
    CLI_INT(sub_args, seed, "seed", "S", 0, 1000, "7", "random seed"),
    CLI_END,
};

static const cli_opt opts[] = {
    CLI_HEADING("Test:"),
    CLI_ORDER(args, order, 32, "a printed matrix", "bands 0..N-1"),
    CLI_INT(args, rays, "rays", "N", 1, 1048576, "256", "rays per vertex"),
    CLI_LONG(args, count, "count", "K", 1, 1e12, "10", "repetitions"),
    CLI_REAL(args, beta, "beta", "B", 0, 0, 0, "0", "any finite angle"),
    CLI_REAL(args, albedo, "albedo", "A", 0, 1, CLI_HI_OPEN, "0.5", "reflectance"),
    CLI_STRING(args, out, "out", "FILE", "output file"),
    CLI_FLAG(args, quiet, "quiet", "no progress"),
    CLI_FLAG(args, check, "check", "check"),
    CLI_FORMAT(args, fmt),
    CLI_CONVENTION(args, conv),
    CLI_DEGREES(args, degrees, "angles in degrees"),
    CLI_GROUP(args, sub, sub_opts),
    CLI_END,
};

static const cli_cmd cmd = {.name = "t", .usage = "t [OPTIONS]", .about = "A test.\n", .opts = opts};

/* Parse a NULL-terminated command line into *a; the return of cli_args_parse. */
static int parse(args *a, cli_parsed *seen, const char *const *line)
{
    char *argv[32];
    int argc = 0;
    argv[argc++] = (char *)"t";
    for (; *line; line++) argv[argc++] = (char *)*line;
    memset(a, 0xab, sizeof *a); /* defaults must overwrite this */
    a->out = NULL;
    a->quiet = a->check = a->degrees = 0;
    return cli_args_parse(&cmd, argc, argv, a, seen);
}

#define PARSE(...) parse(&a, &seen, (const char *const[]){__VA_ARGS__, NULL})

START_TEST(test_defaults_and_values)
{
    args a;
    cli_parsed seen;
    ck_assert_int_eq(parse(&a, &seen, (const char *const[]){NULL}), -1);
    ck_assert_int_eq(a.rays, 256);
    ck_assert_int_eq(a.count, 10);
    ck_assert(a.beta == 0 && a.albedo == 0.5);
    ck_assert_int_eq(a.fmt, CLI_TABLE);
    ck_assert_int_eq(a.conv, SH_CS);
    ck_assert_int_eq(a.sub.seed, 7);
    ck_assert_ptr_null(a.out);
    ck_assert_int_eq(seen.ngiven, 0);

    ck_assert_int_eq(PARSE("--order", "5", "--rays=1024", "--beta", "-0.25", "--albedo", "0", "--out", "x.json",
                           "--quiet", "--format", "json", "--convention", "nocs", "--seed", "1000", "--count",
                           "1000000000000"),
                     -1);
    ck_assert_int_eq(a.order, 5);
    ck_assert_int_eq(a.rays, 1024);
    ck_assert(a.beta == -0.25 && a.albedo == 0);
    ck_assert_str_eq(a.out, "x.json");
    ck_assert_int_eq(a.quiet, 1);
    ck_assert_int_eq(a.check, 0);
    ck_assert_int_eq(a.fmt, CLI_JSON);
    ck_assert_int_eq(a.conv, SH_NOCS);
    ck_assert_int_eq(a.sub.seed, 1000);
    ck_assert_int_eq(a.count, 1000000000000L);
    ck_assert(cli_given(&seen, "rays") && cli_given(&seen, "seed") && !cli_given(&seen, "check"));
    /* a second parse sees nothing of the first */
    ck_assert_int_eq(PARSE("--check"), -1);
    ck_assert_int_eq(a.rays, 256);
    ck_assert(!cli_given(&seen, "rays") && cli_given(&seen, "check"));
}
END_TEST

START_TEST(test_refusals)
{
    args a;
    cli_parsed seen;
    const int U = CLI_EXIT_USAGE;
    ck_assert_int_eq(PARSE("--nope"), U);
    ck_assert_int_eq(PARSE("-x"), U);
    ck_assert_int_eq(PARSE("--ord", "5"), U); /* no abbreviations */
    ck_assert_int_eq(PARSE("--rays", "4", "--rays", "4"), U);
    ck_assert_int_eq(PARSE("--quiet", "--quiet"), U);
    ck_assert_int_eq(PARSE("--quiet=1"), U);
    ck_assert_int_eq(PARSE("--rays"), U);
    ck_assert_int_eq(PARSE("--rays", "0"), U);
    ck_assert_int_eq(PARSE("--rays", "1048577"), U);
    ck_assert_int_eq(PARSE("--rays", "0x10"), U);
    ck_assert_int_eq(PARSE("--rays", "4.5"), U);
    ck_assert_int_eq(PARSE("--count", "0"), U);
    ck_assert_int_eq(PARSE("--albedo", "1"), U); /* [0, 1) */
    ck_assert_int_eq(PARSE("--albedo", "-1e-300"), U);
    ck_assert_int_eq(PARSE("--beta", "nan"), U);
    ck_assert_int_eq(PARSE("--beta", "1e309"), U);
    ck_assert_int_eq(PARSE("--out", ""), U);
    ck_assert_int_eq(PARSE("--format", "xml"), U);
    ck_assert_int_eq(PARSE("--order", "0"), U);
    ck_assert_int_eq(PARSE("--order", "33"), U);
    ck_assert_int_eq(PARSE("file.txt"), U); /* no positional declared */
    ck_assert_int_eq(PARSE("--", "--rays"), U);
}
END_TEST

/* Run f with stdout or stderr (fd) redirected to a temporary file; its text. */
static char *capture(int fd, int (*f)(void *), void *ctx, int *rc)
{
    static char text[16384];
    FILE *tmp = tmpfile();
    ck_assert_ptr_nonnull(tmp);
    fflush(NULL);
    const int saved = dup(fd);
    dup2(fileno(tmp), fd);
    *rc = f(ctx);
    fflush(NULL);
    dup2(saved, fd);
    close(saved);
    rewind(tmp);
    const size_t n = fread(text, 1, sizeof text - 1, tmp);
    text[n] = '\0';
    fclose(tmp);
    return text;
}

static int parse_order_0(void *ctx)
{
    args a;
    cli_parsed seen;
    (void)ctx;
    return PARSE("--order", "0");
}

static int help(void *ctx)
{
    (void)ctx;
    return cli_args_help(&cmd);
}

START_TEST(test_wording_and_help)
{
    int rc;
    /* the order's message is cli_order_check's, with the command's limit and reason */
    const char *e = capture(2, parse_order_0, NULL, &rc);
    ck_assert_int_eq(rc, CLI_EXIT_USAGE);
    ck_assert_str_eq(e, "shlab: error: --order: order 0 is outside 1..32 (a printed matrix)\n");
    const char *h = capture(1, help, NULL, &rc);
    ck_assert_int_eq(rc, 0);
    ck_assert(strstr(h, "Usage: shlab t [OPTIONS]\n") == h);
    ck_assert_ptr_nonnull(strstr(h, "\nTest:\n"));
    ck_assert_ptr_nonnull(strstr(h, "  --order N"));
    ck_assert_ptr_nonnull(strstr(h, "1..32"));
    ck_assert_ptr_nonnull(strstr(h, "  --rays N             rays per vertex (default 256; 1..1048576)\n"));
    ck_assert_ptr_nonnull(strstr(h, "reflectance (default 0.5; in [0, 1))"));
    ck_assert_ptr_nonnull(strstr(h, "  --seed S"));
    ck_assert_ptr_nonnull(strstr(h, "  --help               this text\n"));
}
END_TEST

/* A command whose default of a group's option differs: CLI_DEFAULT. */
static const cli_opt own_opts[] = {
    CLI_REAL(args, beta, "beta", "B", 0.1, 170, CLI_LO_OPEN | CLI_HI_OPEN, NULL, "step"),
    CLI_GROUP(args, sub, sub_opts),
    CLI_DEFAULT("seed", "9"),
    CLI_END,
};
static const cli_cmd own_cmd = {.name = "u", .usage = "u [OPTIONS]", .opts = own_opts};

static int own_help(void *ctx)
{
    (void)ctx;
    return cli_args_help(&own_cmd);
}

START_TEST(test_command_default)
{
    args a;
    cli_parsed seen;
    char *argv[] = {(char *)"u", NULL};
    a.sub.seed = -1;
    ck_assert_int_eq(cli_args_parse(&own_cmd, 1, argv, &a, &seen), -1);
    ck_assert_int_eq(a.sub.seed, 9);
    /* the group's own default still holds where no command says otherwise */
    ck_assert_int_eq(PARSE("--quiet"), -1);
    ck_assert_int_eq(a.sub.seed, 7);
    int rc;
    const char *h = capture(1, own_help, NULL, &rc);
    ck_assert_int_eq(rc, 0);
    ck_assert_ptr_nonnull(strstr(h, "  --seed S             random seed (default 9; 0..1000)\n"));
    /* a limit is written as it was declared (not 0.10000000000000001 or 1.7e+02) */
    ck_assert_ptr_nonnull(strstr(h, "  --beta B             step (in (0.1, 170))\n"));
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("cli_args");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_defaults_and_values);
    tcase_add_test(tc, test_refusals);
    tcase_add_test(tc, test_wording_and_help);
    tcase_add_test(tc, test_command_default);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
