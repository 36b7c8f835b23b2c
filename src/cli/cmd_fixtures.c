/* cmd_fixtures.c — `shlab fixtures`: write the golden rotation fixtures
 * (data/fixtures/rotation/, format in its README.md).
 *
 * Every expected vector is R_reference · input with R from the MPFR
 * reference (≥ 30 digits) and the product summed in long double, so it is the
 * exact answer rounded to double.  The files are deterministic: the same
 * shlab writes the same bytes (a test regenerates and compares them). */
#include "cli.h"
#include "core/shlab_internal.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *dir;
    sh_rot_method method; /* SH_ROT_AUTO (the default): the MPFR reference */
    int quiet, fmt;
} fixtures_args;

static const cli_opt fixtures_opts[] = {
    CLI_STRING(fixtures_args, dir, "out", "DIR", "output directory (must exist)"),
    CLI_CUSTOM(fixtures_args, method, "method", "M", cli_parse_method, NULL,
               "expected outputs from shlab's method M in double instead\n"
               "of the MPFR reference, for a kernel that implements M\n"
               "(e.g. taylor1.5): writes orders_1_10_M.json only"),
    CLI_FLAG(fixtures_args, quiet, "quiet", "no progress on stderr"),
    CLI_CHOICE(fixtures_args, fmt, "format", "table|csv|json", cli_format_names, "table",
               "the summary's format"),
    CLI_END,
};

static const cli_cmd fixtures_decl = {
    .name = "fixtures",
    .usage = "fixtures --out DIR [OPTIONS]",
    .about = "Write the golden rotation fixtures into DIR:\n"
             "  orders_1_10.json   orders 1..10 at the 10 rotations of 'shlab stability'\n"
             "                     (β = 0, 1e-12, π/2, π-1e-9, π, gimbal lock, random), both\n"
             "                     conventions: 200 cases\n"
             "  bands_50_200.json  single bands l = 50 and 200 at three rotations, both\n"
             "                     conventions: 12 cases\n"
             "Each case gives the input vector (seeded, unit length), the rotation in every\n"
             "form (euler, quat, matrix, axis+angle), the expected output (MPFR reference,\n"
             "exact to double rounding), its float32 rounding, the convention and the\n"
             "tolerances.  DIR and the targets are checked before anything is computed;\n"
             "the files are written to temporary names and renamed only when all are\n"
             "complete (all or nothing).\n",
    .opts = fixtures_opts,
};

/* Tolerances, |candidate_i − expected_i| ≤ tol for a unit input.  Double:
 * 1e-13 everywhere (the stable methods stay below 5e-15 even at
 * l = 200).  Float32: about 4× the worst error of shlab's best float kernel
 * (zxzxz, float arithmetic throughout) on these cases, measured with
 * `shlab verify --method zxzxz --precision float`: 2.3e-7 (orders ≤ 10; the
 * worst of all methods), 7.2e-7 (l = 50), 1.65e-6 (l = 200).  See README.md. */
#define TOL_D_LOW 1e-13
#define TOL_F_LOW 1e-6
#define TOL_D_B50 1e-13
#define TOL_F_B50 3e-6
#define TOL_D_B200 1e-13
#define TOL_F_B200 7e-6

static json_t *case_json(sh_rot_method method, const char *id, int order, int band, sh_convention conv,
                         const char *rname, const sh_rotation *rot, const double *in, int n, double tol_d,
                         double tol_f, int *st)
{
    double *exp = malloc((size_t)n * sizeof *exp), *expf = malloc((size_t)n * sizeof *expf);
    long double *B = NULL;
    if (!exp || !expf) { *st = SH_ENOMEM; goto fail; }
    const int l0 = band >= 0 ? band : 0, l1 = band >= 0 ? band : order - 1;
    B = malloc((size_t)(2 * l1 + 1) * (2 * l1 + 1) * sizeof *B);
    if (!B) { *st = SH_ENOMEM; goto fail; }
    if (method != SH_ROT_REFERENCE) {
        /* expected = what method M computes (in double): fixtures for a kernel
         * that implements an approximation (taylor1.5) or a given method.
         * The scalar loop kernel: the same bytes on every CPU (the unrolled
         * and SIMD kernels fuse multiply-adds where the CPU has FMA). */
        sh_rotator_opts o = SH_ROTATOR_OPTS(order);
        o.method = method;
        o.kernel = SH_KERNEL_SCALAR;
        o.conv = conv;
        o.threads = 1;
        sh_rotator *r;
        if ((*st = sh_rotator_create(&o, &r))) goto fail;
        *st = sh_rotator_apply(r, rot, 0, 1, in, exp);
        sh_rotator_free(r);
        if (*st) goto fail;
        for (int i = 0; i < n; i++) expf[i] = (double)(float)exp[i];
    }
    for (int l = l0; method == SH_ROT_REFERENCE && l <= l1; l++) {
        const int w = 2 * l + 1, off = band >= 0 ? 0 : l * l;
        if ((*st = sh_rot_reference_band(l, conv, rot, 32, NULL, B))) goto fail;
        for (int i = 0; i < w; i++) {
            long double s = 0;
            for (int j = 0; j < w; j++) s += B[(size_t)i * w + j] * (long double)in[off + j];
            exp[off + i] = (double)s;
            expf[off + i] = (double)(float)s;
        }
    }
    free(B);
    json_t *c = json_object();
    c = cli_put(c, "id", json_string(id));
    c = cli_put(c, "order", json_integer(order));
    if (band >= 0) c = cli_put(c, "band", json_integer(band));
    c = cli_put(c, "convention", json_string(sh_convention_name(conv)));
    c = cli_put(c, "method", json_string(sh_rot_method_name(method)));
    c = cli_put(c, "rotation_name", json_string(rname));
    c = cli_put(c, "rotation", cli_rotation_json(rot));
    c = cli_put(c, "input", cli_json_array(in, (size_t)n));
    c = cli_put(c, "expected", cli_json_array(exp, (size_t)n));
    c = cli_put(c, "expected_float32", cli_json_array(expf, (size_t)n));
    /* an approximation (Taylor) is not orthogonal: its outputs can exceed the
     * unit input by orders of magnitude, and the tolerances scale with them */
    double big = 1;
    for (int i = 0; i < n; i++) big = fmax(big, fabs(exp[i]));
    c = cli_put(c, "tolerance", json_pack("{s:f,s:f}", "double", tol_d * big, "float32", tol_f * big));
    free(exp);
    free(expf);
    if (!c) *st = SH_ENOMEM;
    return c;
fail:
    free(exp);
    free(expf);
    free(B);
    return NULL;
}

static void unit_vector(gsl_rng *r, double *v, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) { v[i] = 2 * gsl_rng_uniform(r) - 1; s += v[i] * v[i]; }
    s = sqrt(s);
    for (int i = 0; i < n; i++) v[i] /= s;
}

/* Write {"format", "description", "cases": [one case per line]} into the
 * temporary file of an output (cli_out_open; cli_emit renames it onto path). */
static int write_file(const char *tmp, const char *path, const char *description, json_t *cases)
{
    FILE *f = sh__temp_fopen(tmp, "w");
    int bad = !f;
    if (f) {
        fprintf(f, "{\"format\":\"shlab-rotation-fixtures/1\",\n\"description\":");
        json_t *d = json_string(description);
        char *ds = json_dumps(d, JSON_ENCODE_ANY);
        fputs(ds ? ds : "\"\"", f);
        free(ds);
        json_decref(d);
        fputs(",\n\"cases\":[\n", f);
        for (size_t k = 0; k < json_array_size(cases); k++) {
            char *s = json_dumps(json_array_get(cases, k), JSON_COMPACT | JSON_REAL_PRECISION(17));
            if (!s) { bad = 1; break; }
            fprintf(f, "%s%s\n", s, k + 1 < json_array_size(cases) ? "," : "");
            free(s);
        }
        fputs("]}\n", f);
        bad |= ferror(f) != 0;
        bad |= fclose(f) != 0;
    }
    return bad ? cli_fail("fixtures: cannot write '%s'", path) : 0;
}

/* The files: orders_1_10[_M].json, and for the reference bands_50_200.json,
 * opened (cli_out_open) before the work so that an unwritable target fails
 * first. */
typedef struct {
    char path[2][4096];
    const char *tmp[2];
    int nfiles;
} fixture_files;

static int open_files(const char *dir, sh_rot_method method, fixture_files *f)
{
    const int ref = method == SH_ROT_REFERENCE;
    f->nfiles = ref ? 2 : 1;
    if ((size_t)snprintf(f->path[0], sizeof f->path[0], "%s/orders_1_10%s%s.json", dir, ref ? "" : "_",
                         ref ? "" : sh_rot_method_name(method)) >= sizeof f->path[0] ||
        (size_t)snprintf(f->path[1], sizeof f->path[1], "%s/bands_50_200.json", dir) >= sizeof f->path[1])
        return cli_fail("fixtures: --out: directory name too long");
    for (int k = 0; k < f->nfiles; k++)
        if (cli_out_open("fixtures", f->path[k], &f->tmp[k])) return CLI_EXIT_USAGE;
    return 0;
}

/* The cases: orders 1..10 at every rotation of the stability set, both
 * conventions (low); for the reference, bands 50 and 200 at three of them
 * (high).  The inputs are drawn in this order from one seeded generator,
 * so the files are the same bytes every time. */
static int make_cases(const fixtures_args *a, sh_rot_method method, json_t *low, json_t *high, int *ncase)
{
    sh_rotation set[SH_ROT_STABILITY_NSET];
    const char *names[SH_ROT_STABILITY_NSET];
    sh_rot_stability_set(set, names);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double *in = malloc(401 * sizeof *in);
    int st = rng && in ? SH_OK : SH_ENOMEM;
    if (rng) gsl_rng_set(rng, 1);
    char id[64];
    for (int k = 0; k < SH_ROT_STABILITY_NSET && !st; k++)
        for (int cv = 0; cv < 2 && !st; cv++)
            for (int order = 1; order <= 10 && !st; order++) {
                const int n = order * order;
                unit_vector(rng, in, n);
                snprintf(id, sizeof id, "o%d-%s-%s", order, names[k], sh_convention_name(cv));
                json_t *c = case_json(method, id, order, -1, cv, names[k], &set[k], in, n, TOL_D_LOW, TOL_F_LOW, &st);
                if (c) {
                    json_array_append_new(low, c);
                    ++*ncase;
                }
            }
    const int pick[3] = {2, 3, 8}; /* β = π/2, π − 1e-9, random1 */
    const int bands[2] = {50, 200};
    for (int b = 0; b < 2 && !st && method == SH_ROT_REFERENCE; b++)
        for (int q = 0; q < 3 && !st; q++)
            for (int cv = 0; cv < 2 && !st; cv++) {
                const int l = bands[b], n = 2 * l + 1;
                if (!a->quiet) fprintf(stderr, "fixtures: band %d, %s, %s\n", l, names[pick[q]], sh_convention_name(cv));
                unit_vector(rng, in, n);
                snprintf(id, sizeof id, "b%d-%s-%s", l, names[pick[q]], sh_convention_name(cv));
                json_t *c = case_json(method, id, l + 1, l, cv, names[pick[q]], &set[pick[q]], in, n,
                                      b ? TOL_D_B200 : TOL_D_B50, b ? TOL_F_B200 : TOL_F_B50, &st);
                if (c) {
                    json_array_append_new(high, c);
                    ++*ncase;
                }
            }
    gsl_rng_free(rng);
    free(in);
    return st ? cli_fail("fixtures: %s", sh_last_error()) : 0;
}

static int write_files(sh_rot_method method, const fixture_files *f, json_t *low, json_t *high)
{
    char desc[512];
    if (method == SH_ROT_REFERENCE)
        snprintf(desc, sizeof desc, "shlab golden SH rotation fixtures: orders 1-10, 10 rotations (extremes "
                                    "included), cs and nocs; expected = MPFR reference. See README.md.");
    else
        snprintf(desc, sizeof desc, "shlab SH rotation fixtures for kernels implementing method %s: orders "
                                    "1-10, 10 rotations, cs and nocs; expected = shlab's %s in double%s. "
                                    "See README.md.", sh_rot_method_name(method), sh_rot_method_name(method),
                 sh_rot_method_is_exact(method) ? "" : " (an approximation, not the exact rotation)");
    int rc = write_file(f->tmp[0], f->path[0], desc, low);
    if (!rc && f->nfiles > 1)
        rc = write_file(f->tmp[1], f->path[1], "shlab golden SH rotation fixtures: single bands 50 and 200, 3 "
                                               "rotations, cs and nocs; expected = MPFR reference. See README.md.", high);
    return rc;
}

static int run(int argc, char **argv)
{
    fixtures_args a = {.method = SH_ROT_AUTO};
    cli_parsed seen;
    int rc = cli_args_parse(&fixtures_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!a.dir) return cli_fail("fixtures: --out DIR is required");
    const sh_rot_method method = a.method == SH_ROT_AUTO ? SH_ROT_REFERENCE : a.method;
    if (method == SH_ROT_Z) return cli_fail("fixtures: method z rotates about z only");
    fixture_files f;
    if ((rc = open_files(a.dir, method, &f))) return rc;
    json_t *low = json_array(), *high = json_array(), *root = NULL;
    int ncase = 0;
    rc = low && high ? make_cases(&a, method, low, high, &ncase) : cli_fail("fixtures: out of memory");
    if (!rc) rc = write_files(method, &f, low, high);
    json_decref(low);
    json_decref(high);
    if (rc) return rc;
    root = json_object();
    root = cli_put(root, "out", json_string(a.dir));
    root = cli_put(root, "method", json_string(sh_rot_method_name(method)));
    root = cli_put(root, "convention", json_string("cs+nocs")); /* every case names its own */
    root = cli_put(root, "files", f.nfiles > 1 ? json_pack("[s,s]", f.path[0], f.path[1]) : json_pack("[s]", f.path[0]));
    root = cli_put(root, "cases", json_integer(ncase));
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_fixtures = {"fixtures", run, "write the golden rotation fixtures", &fixtures_decl};
