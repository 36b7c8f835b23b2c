/* cli_fixture.c — reading golden rotation fixtures and applying a method to
 * one case (shared by `shlab verify` and `shlab fixtures`).  Format: see
 * data/fixtures/rotation/README.md. */
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

void fx_free(fx_set *set)
{
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
    if (!json_is_array(a) || (int)json_array_size(a) != n) return NULL;
    double *v = malloc((size_t)n * sizeof *v);
    if (!v) return NULL;
    for (int i = 0; i < n; i++) {
        const json_t *x = json_array_get(a, (size_t)i);
        if (!json_is_number(x)) { free(v); return NULL; }
        v[i] = json_number_value(x);
    }
    return v;
}

int fx_load(const char *path, fx_set *set)
{
    memset(set, 0, sizeof *set);
    json_error_t err;
    errno = 0;
    json_t *root = json_load_file(path, 0, &err);
    if (!root) return cli_fail_json("fixture", path, errno, &err);
    const json_t *cases = json_object_get(root, "cases");
    const char *fmt = json_string_value(json_object_get(root, "format"));
    if (!fmt || strcmp(fmt, "shlab-rotation-fixtures/1") || !json_is_array(cases)) {
        json_decref(root);
        return cli_fail("fixture '%s': not a shlab rotation fixture file (format "
                        "\"shlab-rotation-fixtures/1\" with \"cases\")", path);
    }
    set->ncases = (int)json_array_size(cases);
    set->cases = calloc((size_t)set->ncases + 1, sizeof *set->cases);
    if (!set->cases) { json_decref(root); return cli_fail("out of memory"); }
    for (int k = 0; k < set->ncases; k++) {
        const json_t *c = json_array_get(cases, (size_t)k);
        fx_case *x = &set->cases[k];
        const char *id = json_string_value(json_object_get(c, "id"));
        const json_t *order = json_object_get(c, "order"), *band = json_object_get(c, "band");
        const char *conv = json_string_value(json_object_get(c, "convention"));
        const json_t *eul = json_object_get(json_object_get(c, "rotation"), "euler");
        const json_t *tol = json_object_get(c, "tolerance");
        x->band = json_is_integer(band) ? (int)json_integer_value(band) : -1;
        x->order = json_is_integer(order) ? (int)json_integer_value(order) : 0;
        int ok = id && strlen(id) < sizeof x->id && x->order >= 1 && x->order <= 1001 && conv &&
                 !sh_convention_parse(conv, &x->conv) && x->band < x->order;
        double *e = ok ? numbers(eul, 3) : NULL;
        if (e) {
            snprintf(x->id, sizeof x->id, "%s", id);
            ok = !sh_rotation_from_euler(e[0], e[1], e[2], &x->rot);
            free(e);
        } else {
            ok = 0;
        }
        x->n = x->band >= 0 ? 2 * x->band + 1 : x->order * x->order;
        if (ok) {
            x->input = numbers(json_object_get(c, "input"), x->n);
            x->expected = numbers(json_object_get(c, "expected"), x->n);
            x->expected_f = numbers(json_object_get(c, "expected_float32"), x->n);
            x->tol_double = json_number_value(json_object_get(tol, "double"));
            x->tol_float = json_number_value(json_object_get(tol, "float32"));
            ok = x->input && x->expected && x->expected_f && x->tol_double > 0 && x->tol_float > 0;
        }
        if (!ok) {
            json_decref(root);
            fx_free(set);
            return cli_fail("fixture '%s': case %d is malformed (id, order, band, convention, "
                            "rotation.euler, input, expected, expected_float32, tolerance)", path, k);
        }
    }
    json_decref(root);
    return 0;
}

int fx_apply(sh_rot_method m, sh_precision prec, const fx_case *c, const sh_rotation *rot,
             sh_convention conv, const double *in, double *out)
{
    return fx_apply_kernel(m, prec, SH_KERNEL_AUTO, 0, c, rot, conv, in, out);
}

int fx_apply_kernel(sh_rot_method m, sh_precision prec, sh_rot_kernel kernel, int matrix,
                    const fx_case *c, const sh_rotation *rot, sh_convention conv, const double *in,
                    double *out)
{
    int st;
    if (c->band >= 0) {
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
    sh_rot_plan *p;
    if ((st = sh_rot_plan_create_kernel(c->order, m, prec, conv, kernel, &p))) return st;
    if (!matrix) {
        if (!(st = sh_rot_plan_set(p, rot))) st = sh_rot_plan_apply(p, in, out);
    } else if (prec == SH_PREC_DOUBLE) {
        if (!(st = sh_rot_plan_set_matrix(p, rot->R))) st = sh_rot_plan_apply(p, in, out);
    } else {
        const size_t n = (size_t)c->n;
        float R[9], *x = malloc(2 * n * sizeof *x);
        if (!x) st = sh_error(SH_ENOMEM, "out of memory");
        for (int i = 0; i < 9; i++) R[i] = (float)rot->R[i];
        for (size_t i = 0; !st && i < n; i++) x[i] = (float)in[i];
        if (!st) st = sh_rot_plan_set_matrix_f(p, R);
        if (!st) st = sh_rot_plan_apply_f(p, x, x + n);
        for (size_t i = 0; !st && i < n; i++) out[i] = x[n + i];
        free(x);
    }
    sh_rot_plan_free(p);
    return st;
}
