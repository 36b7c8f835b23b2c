/* fixture.c — golden rotation fixtures (shlab/verify.h): reading a fixture
 * and a candidate's outputs, and applying a method to one case.  Format:
 * data/fixtures/rotation/README.md.  Every input is untrusted: sizes and
 * integers are checked before anything is allocated or indexed. */
#include "core/shlab_internal.h"
#include "io/json_strict.h"

#include <stdlib.h>
#include <string.h>

void sh_fixture_free(sh_fixture *set)
{
    if (!set) return;
    for (int k = 0; k < set->ncases; k++) {
        free(set->cases[k].input);
        free(set->cases[k].expected);
        free(set->cases[k].expected_f);
    }
    free(set->cases);
    set->cases = NULL;
    set->ncases = 0;
}

static double *numbers(const json_t *a, int n)
{
    if (!json_is_array(a) || json_array_size(a) != (size_t)n) return NULL;
    double *v = malloc((size_t)n * sizeof *v);
    if (!v) return NULL;
    for (int i = 0; i < n; i++) {
        const json_t *x = json_array_get(a, (size_t)i);
        if (!json_is_number(x)) { free(v); return NULL; }
        v[i] = json_number_value(x);
    }
    return v;
}

/* A fixture or candidate file is at most this large (the golden fixtures are
 * about 1 MB). */
#define FX_MAX_BYTES ((long long)256 << 20)
/* room for "fixture '<path>'" in messages */
#define FX_NAME 4200

/* An integer member in [lo, hi], checked on the JSON value (a long long)
 * before it is narrowed: 4294967297 is not order 1. */
static int int_member(const json_t *c, const char *key, long long lo, long long hi, int dflt, int *out)
{
    const json_t *v = json_object_get(c, key);
    if (!v) { *out = dflt; return 1; }
    if (!json_is_integer(v)) return 0;
    const long long x = json_integer_value(v);
    if (x < lo || x > hi) return 0;
    *out = (int)x;
    return 1;
}

/* An id is printed in messages and written to candidate files: one line of
 * printable text. */
static int good_id(const char *id, size_t max)
{
    if (!id || !*id || strlen(id) >= max) return 0;
    char esc[256];
    sh__escape_line(esc, sizeof esc, id);
    return strcmp(esc, id) == 0;
}

int sh_fixture_load(const char *path, sh_fixture *set)
{
    if (!set) return sh_error(SH_EINVAL, "sh_fixture_load: no fixture");
    memset(set, 0, sizeof *set);
    char *buf;
    size_t n;
    if (sh_input_read_all("fixture", path, FX_MAX_BYTES, &buf, &n)) return SH_EIO;
    char name[FX_NAME];
    snprintf(name, sizeof name, "fixture '%s'", path);
    const int st = sh_fixture_load_mem(buf, n, name, set);
    free(buf);
    return st;
}

/* Case k of the JSON array into x; 0 if malformed. */
static int read_case(const json_t *c, const sh_fixture *set, int k, sh_fixture_case *x)
{
    const char *id = json_string_value(json_object_get(c, "id"));
    const char *conv = json_string_value(json_object_get(c, "convention"));
    const json_t *eul = json_object_get(json_object_get(c, "rotation"), "euler");
    const json_t *tol = json_object_get(c, "tolerance");
    /* orders up to 1001 (a band up to 1000): checked before any arithmetic */
    int ok = json_is_object(c) && good_id(id, sizeof x->id) && int_member(c, "order", 1, 1001, 0, &x->order) &&
             x->order >= 1 && int_member(c, "band", -1, 1000, -1, &x->band) && x->band < x->order && conv &&
             !sh_convention_parse(conv, &x->conv);
    for (int j = 0; ok && j < k; j++)
        if (!strcmp(set->cases[j].id, id)) ok = 0; /* ids name the cases of a candidate */
    double *e = ok ? numbers(eul, 3) : NULL;
    if (!e) return 0;
    snprintf(x->id, sizeof x->id, "%s", id);
    ok = !sh_rotation_from_euler(e[0], e[1], e[2], &x->rot);
    free(e);
    if (!ok) return 0;
    x->n = x->band >= 0 ? 2 * x->band + 1 : x->order * x->order;
    x->input = numbers(json_object_get(c, "input"), x->n);
    x->expected = numbers(json_object_get(c, "expected"), x->n);
    x->expected_f = numbers(json_object_get(c, "expected_float32"), x->n);
    x->tol_double = json_number_value(json_object_get(tol, "double"));
    x->tol_float = json_number_value(json_object_get(tol, "float32"));
    return x->input && x->expected && x->expected_f && x->tol_double > 0 && x->tol_float > 0;
}

int sh_fixture_load_mem(const char *buf, size_t len, const char *name, sh_fixture *set)
{
    if (!set || !buf || !name) return sh_error(SH_EINVAL, "sh_fixture_load_mem: no text, name or fixture");
    memset(set, 0, sizeof *set);
    json_t *root;
    int st = sh__json_parse(buf, len, name, &root);
    if (st) return st;
    const json_t *cases = json_object_get(root, "cases");
    const char *fmt = json_string_value(json_object_get(root, "format"));
    if (!fmt || strcmp(fmt, "shlab-rotation-fixtures/1") || !json_is_array(cases)) {
        json_decref(root);
        return sh_error(SH_EFORMAT, "%s: not a shlab rotation fixture file (format "
                                    "\"shlab-rotation-fixtures/1\" with \"cases\")", name);
    }
    const size_t nc = json_array_size(cases);
    if (nc == 0 || nc > 1000000) {
        json_decref(root);
        return sh_error(SH_EFORMAT, "%s: %s", name, nc ? "more than 10^6 cases" : "\"cases\" is empty");
    }
    set->cases = calloc(nc, sizeof *set->cases);
    if (!set->cases) { json_decref(root); return sh_error(SH_ENOMEM, "out of memory"); }
    set->ncases = (int)nc;
    for (int k = 0; k < set->ncases; k++) {
        if (read_case(json_array_get(cases, (size_t)k), set, k, &set->cases[k])) continue;
        json_decref(root);
        sh_fixture_free(set);
        return sh_error(SH_EFORMAT, "%s: case %d is malformed (id: unique printable text; order: 1..1001; "
                                    "band: -1..order-1; convention, rotation.euler, input, expected, "
                                    "expected_float32, tolerance)", name, k);
    }
    json_decref(root);
    return SH_OK;
}

int sh_fixture_load_candidate(const char *path, const sh_fixture *fx, const unsigned char *want, double **out,
                              unsigned char *present)
{
    char *buf;
    size_t n;
    if (sh_input_read_all("candidate", path, FX_MAX_BYTES, &buf, &n)) return SH_EIO;
    char name[FX_NAME];
    snprintf(name, sizeof name, "candidate '%s'", path);
    const int st = sh_fixture_load_candidate_mem(buf, n, name, fx, want, out, present);
    free(buf);
    return st;
}

int sh_fixture_load_candidate_mem(const char *buf, size_t len, const char *name, const sh_fixture *fx,
                                  const unsigned char *want, double **out, unsigned char *present)
{
    json_t *root;
    int st = sh__json_parse(buf, len, name, &root);
    if (st) return st;
    const json_t *res = json_object_get(root, "results");
    if (!json_is_object(res)) {
        json_decref(root);
        return sh_error(SH_EFORMAT, "%s: expected {\"results\": {\"<case id>\": [...]}}", name);
    }
    for (int k = 0; k < fx->ncases; k++) {
        const sh_fixture_case *c = &fx->cases[k];
        const json_t *a = json_object_get(res, c->id);
        if (present) present[k] = a != NULL;
        if (!a && want && !want[k]) continue;
        if (!json_is_array(a) || json_array_size(a) != (size_t)c->n) {
            json_decref(root);
            if (a) return sh_error(SH_EFORMAT, "%s: case '%s' is not an array of %d numbers", name, c->id, c->n);
            return sh_error(SH_EFORMAT, "%s: case '%s' missing (verify --orders or --cases runs fewer cases)", name,
                            c->id);
        }
        for (int i = 0; i < c->n; i++) {
            const json_t *x = json_array_get(a, (size_t)i);
            if (!json_is_number(x)) {
                json_decref(root);
                return sh_error(SH_EFORMAT, "%s: case '%s' entry %d is not a number", name, c->id, i);
            }
            out[k][i] = json_number_value(x);
        }
    }
    json_decref(root);
    return SH_OK;
}

int sh_fixture_apply(sh_rot_method m, sh_precision prec, sh_rot_kernel kernel, int matrix, const sh_fixture_case *c,
                     const sh_rotation *rot, sh_convention conv, const double *in, double *out)
{
    int st;
    if (c->band >= 0) {
        /* one band: its block B (2L+1)², applied in long double */
        const int w = 2 * c->band + 1;
        double *B = malloc((size_t)w * w * sizeof *B);
        if (!B) return sh_error(SH_ENOMEM, "out of memory");
        st = sh_rot_band(c->band, m, prec, conv, rot, B);
        for (int i = 0; !st && i < w; i++) {
            long double s = 0;
            for (int j = 0; j < w; j++) s += (long double)B[(size_t)i * w + j] * in[j];
            out[i] = (double)s;
        }
        free(B);
        return st;
    }
    /* a whole order: one rotation applied once, by the rotator (the library
     * picks the kernel and the path) */
    sh_rotator_opts o = SH_ROTATOR_OPTS(c->order);
    o.method = m;
    o.prec = prec;
    o.kernel = kernel;
    o.conv = conv;
    o.threads = 1;
    sh_rotator *r;
    if ((st = sh_rotator_create(&o, &r))) return st;
    if (!matrix) {
        st = sh_rotator_apply(r, rot, 0, 1, in, out);
    } else if (prec == SH_PREC_DOUBLE) {
        st = sh_rotator_apply_matrix(r, rot->R, 0, 1, in, out);
    } else {
        const size_t n = (size_t)c->n;
        float R[9], *x = malloc(2 * n * sizeof *x);
        if (!x) st = sh_error(SH_ENOMEM, "out of memory");
        for (int i = 0; i < 9; i++) R[i] = (float)rot->R[i];
        for (size_t i = 0; !st && i < n; i++) x[i] = (float)in[i];
        if (!st) st = sh_rotator_apply_matrix_f(r, R, x, x + n);
        for (size_t i = 0; !st && i < n; i++) out[i] = x[n + i];
        free(x);
    }
    sh_rotator_free(r);
    return st;
}
