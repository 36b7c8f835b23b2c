/* cmd_identify.c — `shlab identify`: name a user's SH convention from their
 * basis at the fixture's directions or their projection of the fixture's
 * light (data/fixtures/basis/README.md; sh_identify_basis/_projection). */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *basis, *projection, *print, *rotated, *fixture;
    int order;
    double tol;
    int fmt;
} identify_args;

static const cli_opt identify_opts[] = {
    CLI_STRING(identify_args, basis, "basis", "FILE",
               "your basis at the 32 fixture directions: JSON {\"values\": [[...],...]}\n"
               "(one row per direction, in the fixture's order) or plain numbers, row\n"
               "after row; a row is your vector of basis values (complex: re,im)"),
    CLI_STRING(identify_args, projection, "projection", "FILE",
               "your coefficients of the fixture's light: JSON {\"coeffs\": [...]} or\n"
               "plain numbers"),
    CLI_STRING(identify_args, rotated, "rotated", "FILE",
               "your kernel's rotation of the golden cases of --fixture: a\n"
               "candidate file {\"results\": {\"<case id>\": [...]}} (cases\n"
               "missing from it are not used)"),
    CLI_STRING(identify_args, fixture, "fixture", "F",
               "with --rotated: the golden rotation fixture\n"
               "(default data/fixtures/rotation/orders_1_10.json)"),
    CLI_INT(identify_args, order, "order", "N", 1, SH_IDENTIFY_MAX_ORDER, NULL,
            "the order of your data (default: from the count of numbers)"),
    CLI_REAL(identify_args, tol, "tol", "T", 0, 1, CLI_LO_OPEN | CLI_HI_OPEN, "1e-4",
             "relative RMS residual a fit may have (default 1e-4)"),
    CLI_STRING(identify_args, print, "print", "WHAT",
               "print the fixture instead: directions, or light (with shlab's\n"
               "coefficients to --order, default 8)"),
    CLI_FORMAT(identify_args, fmt),
    CLI_END,
};

static const cli_cmd identify_decl = {
    .name = "identify",
    .usage = "identify (--basis FILE | --projection FILE) [--order N] [--tol T] [OPTIONS]\n"
             "       shlab identify --rotated FILE [--fixture F] [OPTIONS]\n"
             "       shlab identify --print directions|light [--order N] [--format json]",
    .about = "Name the spherical-harmonic convention of your data: real or complex, phase,\n"
             "normalisation (ortho, 4pi, schmidt = sn3d, n3d, fuma), index order (acn, mdesc,\n"
             "cossin, fuma-order), the function of m < 0 (neg-sin, neg-cos) and axes (z-up,\n"
             "y-up, any of the 48 signed permutations).  Give either your basis evaluated at\n"
             "the fixture's directions (`shlab identify --print directions`) or your\n"
             "coefficients of the fixture's light (`--print light`): three directional\n"
             "lights, whose coefficients in an orthonormal basis are Σ w·U(d); in a basis\n"
             "with ∫U² = g they are Σ w·U(d)/g (4pi: g = 4π; schmidt: 4π/(2l+1)); complex:\n"
             "Σ w·conj(Y(d)).  Prints the convention, the residual of every fitting class\n"
             "band by band, and the `shlab convert` commands to shlab's coefficients and\n"
             "back.  Conventions that are the same functions (cs ≡ nocs turned by π about\n"
             "z, ...) are one class, named by its plainest member, the rest as aliases.\n"
             "--rotated reads a kernel's outputs on the golden rotation cases instead and\n"
             "names what its rotation convention does differently from shlab's (the\n"
             "diagnosis of `shlab verify --diagnose`): the phase, m-descending order,\n"
             "the inverse (frame) rotation, Euler angle order or units, float precision.\n",
    .opts = identify_opts,
    .notes = "JSON: {\"input\",\"order\",\"tolerance\",\"verdict\":\"identified|ambiguous|none\",\n"
             "\"convention\",\"to_shlab\",\"from_shlab\",\"needs\",\"candidates\":[{\"convention\",\n"
             "\"aliases\",\"residual\",\"fits\",\"fits_through_order\",\"band_residuals\"}]}\n"
             "--rotated: {\"input\":\"rotated\",\"fixture\",\"cases\",\"verdict\",\"convention\",\n"
             "\"rotation\",[\"to_shlab\",\"from_shlab\"],\"diagnosis\",\"diagnosis_matches\",\n"
             "\"diagnosis_checked\"}\n"
             "Exit status: 0 identified; 1 ambiguous or no fit (the result still printed:\n"
             "\"needs\" says what decides, or the nearest conventions are listed); 2 bad input.\n",
};

/* --basis: {"values": [[row], ...]} or the numbers row after row. */
static int read_basis(const char *path, double **v, int *n)
{
    char *buf = NULL;
    size_t len = 0;
    int rc = cli_read_file("basis file", path, (size_t)1 << 26, &buf, &len);
    if (rc) return rc;
    const char *p = buf;
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
    json_t *root = NULL, *vals = NULL;
    if (*p == '{' && !(rc = cli_json_parse(buf, len, path, &root)) &&
        json_is_array(vals = json_object_get(root, "values"))) {
        size_t i, k = 0, per = 0;
        json_t *row, *x;
        *v = malloc(sizeof(double) * (len / 2 + 1));
        json_array_foreach(vals, i, row) {
            if (!json_is_array(row) || (i && json_array_size(row) != per)) {
                rc = cli_fail("identify: '%s': row %zu of \"values\" is not an array of %zu numbers", path, i + 1, per);
                break;
            }
            per = json_array_size(row);
            size_t j;
            json_array_foreach(row, j, x) {
                if (!json_is_number(x) || !isfinite(json_number_value(x))) {
                    rc = cli_fail("identify: '%s': row %zu, value %zu is not a finite number", path, i + 1, j + 1);
                    break;
                }
                (*v)[k++] = json_number_value(x);
            }
            if (rc) break;
        }
        *n = (int)k;
    } else if (!rc) {
        json_decref(root);
        root = NULL;
        int nchan = 1, len2 = 0;
        rc = cli_read_coeffs_mem(buf, len, path, v, &len2, &nchan, NULL);
        if (!rc && nchan != 1) rc = cli_fail("identify: '%s': one vector expected, not channels", path);
        *n = len2;
    }
    json_decref(root);
    free(buf);
    if (rc) { free(*v); *v = NULL; }
    return rc;
}

static json_t *spec_json(const sh_conv *c)
{
    char b[96];
    return json_string(sh_conv_format(c, b, sizeof b));
}

static json_t *candidate_json(const sh_id_candidate *k)
{
    char al[SH_IDENTIFY_MAX_ALIASES * 64] = "", br[SH_IDENTIFY_MAX_ORDER * 16] = "", b[96];
    for (int i = 0; i < k->naliases; i++) {
        if (i) strcat(al, " ");
        strcat(al, sh_conv_format(&k->aliases[i], b, sizeof b));
    }
    for (int l = 0; l < k->order; l++) snprintf(br + strlen(br), sizeof br - strlen(br), "%s%.3g", l ? " " : "", k->band_residual[l]);
    const char *pre = sh_conv_preset(&k->conv);
    json_t *o = json_pack("{s:o,s:s,s:s,s:b,s:i,s:s}", "convention", spec_json(&k->conv), "preset", pre ? pre : "",
                          "aliases", al, "fits", k->fits, "fits_through_order", k->fits_through, "band_residuals", br);
    return cli_put(o, "residual", json_real(k->residual));
}

static json_t *result_json(const identify_args *a, const sh_id_result *r, const char *file)
{
    static const char *const verdicts[] = {"identified", "ambiguous", "none"};
    json_t *root = json_pack("{s:s,s:i,s:f,s:s}", "input", a->basis ? "basis" : "projection", "order",
                             r->ncand ? r->cand[0].order : 0, "tolerance", r->tol, "verdict", verdicts[r->verdict]);
    sh_id_text t;
    sh_identify_text(r, file, &t);
    if (r->verdict == SH_ID_IDENTIFIED) {
        root = cli_put(root, "convention", json_string(t.convention));
        root = cli_put(root, "to_shlab", json_string(t.to_shlab));
        root = cli_put(root, "from_shlab", json_string(t.from_shlab));
    }
    if (*t.needs) root = cli_put(root, "needs", json_string(t.needs));
    json_t *arr = json_array();
    for (int i = 0; i < r->ncand && arr; i++)
        if (json_array_append_new(arr, candidate_json(&r->cand[i]))) { json_decref(arr); arr = NULL; }
    return cli_put(root, "candidates", arr);
}

/* --print directions | light: the fixture, as committed in data/fixtures/basis/. */
static int print_fixture(const identify_args *a, const cli_parsed *seen)
{
    const int isdir = !strcmp(a->print, "directions");
    if (!isdir && strcmp(a->print, "light")) return cli_fail("identify: --print takes directions or light, not '%s'", a->print);
    if (isdir && cli_given(seen, "order")) return cli_fail("identify: --order applies only to --print light");
    double d[3 * SH_IDENTIFY_NDIRS], w[SH_IDENTIFY_NLIGHTS];
    int ex[SH_IDENTIFY_NDIRS][4];
    const int n = isdir ? SH_IDENTIFY_NDIRS : SH_IDENTIFY_NLIGHTS;
    if (isdir) sh_identify_directions(d, ex);
    else sh_identify_light(d, w, ex);
    json_t *rows = json_array();
    for (int j = 0; j < n && rows; j++) {
        json_t *r = json_pack("{s:i,s:i,s:i,s:i}", "a", ex[j][0], "b", ex[j][1], "c", ex[j][2], "n", ex[j][3]);
        r = cli_put(r, "x", json_real(d[3 * j]));
        r = cli_put(r, "y", json_real(d[3 * j + 1]));
        r = cli_put(r, "z", json_real(d[3 * j + 2]));
        if (!isdir) r = cli_put(r, "weight", json_real(w[j]));
        if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; }
    }
    json_t *root = json_pack("{s:s}", "fixture", isdir ? "directions" : "light");
    root = cli_put(root, isdir ? "directions" : "lights", rows);
    if (!isdir) {
        const int order = a->order ? a->order : 8;
        double c[SH_IDENTIFY_MAX_ORDER * SH_IDENTIFY_MAX_ORDER];
        if (sh_identify_light_coeffs(order, c)) { json_decref(root); return cli_fail_status(SH_EINVAL); }
        root = cli_put(root, "order", json_integer(order));
        root = cli_put(root, "convention", json_string("cs"));
        root = cli_put(root, "coeffs", cli_json_array(c, (size_t)order * order));
    }
    return cli_emit(root, (cli_format)a->fmt);
}

/* What a diagnosed mistake says about the user's conventions: the basis
 * (a spec convert takes, or NULL) and the rotation. */
static void rotated_meaning(const sh_diagnosis *d, const char *conv, const char **basis, const char **rotation)
{
    static char other[16], mdesc[32];
    const int nocs = !strcmp(conv, "nocs");
    *basis = conv;
    *rotation = "shlab's: g(s) = f(R⁻¹s), ZYZ active, radians";
    if (!d->found) { *basis = NULL; *rotation = NULL; return; }
    if (d->float_only) { *rotation = "shlab's, computed in float precision"; return; }
    switch (d->mistake) {
    case SH_MISTAKE_CONVENTION:
    case SH_MISTAKE_BETA:
        snprintf(other, sizeof other, "%s", nocs ? "cs" : "nocs");
        *basis = other;
        break;
    case SH_MISTAKE_MDESC:
        snprintf(mdesc, sizeof mdesc, "%s,mdesc", conv);
        *basis = mdesc;
        break;
    case SH_MISTAKE_MDESC_IN:
    case SH_MISTAKE_MDESC_OUT:
        *basis = NULL;
        *rotation = d->mistake == SH_MISTAKE_MDESC_IN ? "reads its input m-descending and writes ascending"
                                                     : "reads its input m-ascending and writes descending";
        break;
    case SH_MISTAKE_INVERSE: *rotation = "the inverse: g(s) = f(R s) (a frame rotation; transposed matrix, conjugated quaternion)"; break;
    case SH_MISTAKE_SWAP: *rotation = "Euler angles applied in the other order: Rz(γ)Ry(β)Rz(α)"; break;
    case SH_MISTAKE_DEG2RAD: *rotation = "takes the angles in degrees"; break;
    case SH_MISTAKE_RAD2DEG: *rotation = "takes radians where degrees are meant (angles scaled by 180/π)"; break;
    default: break;
    }
}

/* --rotated: the user's rotated coefficients against the golden cases, the
 * diagnosis read as conventions. */
static int identify_rotated(const identify_args *a)
{
    const char *fxp = a->fixture ? a->fixture : "data/fixtures/rotation/orders_1_10.json";
    sh_fixture fx;
    if (cli_input("fixture", fxp) || cli_input("rotated file", a->rotated)) return CLI_EXIT_USAGE;
    if (sh_fixture_load(fxp, &fx)) return cli_fail_status(SH_EFORMAT);
    const size_t nc = (size_t)fx.ncases;
    double **got = calloc(nc, sizeof *got);
    unsigned char *want = calloc(nc, 1), *present = calloc(nc, 1), *skip = calloc(nc, 1);
    int rc = got && want && present && skip ? 0 : cli_fail("out of memory");
    for (size_t k = 0; !rc && k < nc; k++)
        if (!(got[k] = malloc((size_t)fx.cases[k].n * sizeof **got))) rc = cli_fail("out of memory");
    if (!rc && sh_fixture_load_candidate(a->rotated, &fx, want, got, present)) rc = cli_fail_status(SH_EFORMAT);
    int run = 0, have_cs = 0, have_nocs = 0;
    for (size_t k = 0; !rc && k < nc; k++) {
        skip[k] = !present[k];
        run += present[k];
        if (present[k]) have_cs |= fx.cases[k].conv == SH_CS, have_nocs |= fx.cases[k].conv == SH_NOCS;
    }
    if (!rc && !run) rc = cli_fail("identify: '%s' holds none of the cases of fixture '%s'", a->rotated, fxp);
    if (!rc && have_cs && have_nocs)
        rc = cli_fail("identify: '%s' holds cases of both conventions; a kernel has one (keep the cs or the nocs cases)",
                      a->rotated);
    sh_verdict v;
    sh_diagnosis d = {0};
    if (!rc && (sh_verify_judge(&fx, skip, got, SH_PREC_DOUBLE, &v) ||
                (v.failed && sh_verify_diagnose(&fx, skip, got, SH_PREC_DOUBLE, NULL, NULL, &d))))
        rc = cli_fail_status(SH_ENOMEM);
    json_t *root = NULL;
    int verdict_ok = 0;
    if (!rc) {
        const char *conv = have_nocs ? "nocs" : "cs", *basis = conv, *rotation = "shlab's: g(s) = f(R⁻¹s), ZYZ active, radians";
        if (v.failed) rotated_meaning(&d, conv, &basis, &rotation);
        verdict_ok = !v.failed || d.found;
        root = json_pack("{s:s,s:s,s:i,s:s}", "input", "rotated", "fixture", fxp, "cases", run, "verdict",
                         verdict_ok ? "identified" : "none");
        root = cli_put(root, "convention", basis ? json_string(basis) : json_null());
        root = cli_put(root, "rotation", rotation ? json_string(rotation) : json_null());
        if (basis && strcmp(basis, "cs")) {
            char cmd[256];
            snprintf(cmd, sizeof cmd, "shlab convert --from %s --to cs --in FILE", basis);
            root = cli_put(root, "to_shlab", json_string(cmd));
            snprintf(cmd, sizeof cmd, "shlab convert --from cs --to %s --in FILE", basis);
            root = cli_put(root, "from_shlab", json_string(cmd));
        }
        root = cli_put(root, "diagnosis", json_string(v.failed ? d.cause : "none: every case matches shlab's rotation"));
        root = cli_put(root, "diagnosis_matches", json_integer(v.failed ? d.matches : run));
        root = cli_put(root, "diagnosis_checked", json_integer(v.failed ? d.checked : run));
    }
    for (size_t k = 0; got && k < nc; k++) free(got[k]);
    free(got), free(want), free(present), free(skip);
    sh_fixture_free(&fx);
    if (rc) return rc;
    rc = cli_emit(root, (cli_format)a->fmt);
    return rc ? rc : verdict_ok ? CLI_EXIT_OK : CLI_EXIT_CHECK;
}

static int run(int argc, char **argv)
{
    identify_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&identify_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    const int nin = !!a.basis + !!a.projection + !!a.print + !!a.rotated;
    if (nin != 1) return cli_fail("identify: give exactly one of --basis, --projection, --rotated and --print");
    if (a.fixture && !a.rotated) return cli_fail("identify: --fixture applies only to --rotated");
    if (a.print) return print_fixture(&a, &seen);
    if (a.rotated) return identify_rotated(&a);
    const char *file = a.basis ? a.basis : a.projection;
    if ((rc = cli_input(a.basis ? "basis file" : "projection file", file))) return rc;
    double *v = NULL;
    int n = 0;
    sh_id_result r;
    int st;
    if (a.basis) {
        if ((rc = read_basis(file, &v, &n))) return rc;
        if (n == 0 || n % SH_IDENTIFY_NDIRS) {
            free(v);
            return cli_fail("identify: '%s' has %d numbers, not a whole row for each of the %d directions", file, n,
                            SH_IDENTIFY_NDIRS);
        }
        double d[3 * SH_IDENTIFY_NDIRS];
        sh_identify_directions(d, NULL);
        st = sh_identify_basis(SH_IDENTIFY_NDIRS, d, (size_t)n / SH_IDENTIFY_NDIRS, v, a.order, a.tol, &r);
    } else {
        int nchan = 1;
        if ((rc = cli_read_coeffs_file(file, SH_IDENTIFY_MAX_ORDER, &v, &n, &nchan, NULL))) return rc;
        if (nchan != 1) { free(v); return cli_fail("identify: '%s': one vector expected, not channels", file); }
        double ref[SH_IDENTIFY_MAX_ORDER * SH_IDENTIFY_MAX_ORDER];
        sh_identify_light_coeffs(SH_IDENTIFY_MAX_ORDER, ref);
        st = sh_identify_projection((size_t)n, v, ref, SH_IDENTIFY_MAX_ORDER, a.order, a.tol, &r);
    }
    free(v);
    if (st) return cli_fail("identify: '%s': %s", file, sh_last_error());
    json_t *root = result_json(&a, &r, file);
    const int verdict = r.verdict;
    sh_identify_free(&r);
    rc = cli_emit(root, (cli_format)a.fmt);
    return rc ? rc : verdict == SH_ID_IDENTIFIED ? CLI_EXIT_OK : CLI_EXIT_CHECK;
}

const cli_command cmd_identify = {"identify", run, "name the SH convention of your basis or coefficients", &identify_decl};
