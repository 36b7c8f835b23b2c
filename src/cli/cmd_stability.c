/* cmd_stability.c — `shlab stability`: a method's accuracy band by band
 * (orthogonality, homomorphism, distance to the MPFR reference) over the fixed
 * rotation set with the extremes. */
#include "cli.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>

extern const cli_sweep_kind sweep_stability;

/* Largest band: memory is 11 blocks of (2L+1)² doubles (1.4 GB at 2000,
 * 5.6 GB at 4000; halfpi needs none above --exact-max and --ref-max), time
 * depends on the method (and no method may go beyond its own largest order). */
#define STABILITY_MAX_BAND 4000

/* --bands L1,L2,...: increasing bands in 0..STABILITY_MAX_BAND */
typedef struct {
    int n;
    int v[STABILITY_MAX_BAND + 1];
} band_list;

typedef struct {
    sh_rot_method method;
    sh_precision prec;
    int lmax, ref_max, exact_max;
    band_list bands;
    double stop_above; /* 0: not given */
    int conv, degrees;
    cli_sweep_args sweep;
} stability_args;

static int bands_value(const char *opt, const char *s, void *field)
{
    band_list *b = field;
    double *v = NULL;
    int n = 0;
    if (cli_doubles(opt, s, &v, &n)) return CLI_EXIT_USAGE;
    for (int q = 0; q < n; q++) {
        if (q > STABILITY_MAX_BAND || v[q] != floor(v[q]) || v[q] < 0 || v[q] > STABILITY_MAX_BAND ||
            (q && v[q] <= v[q - 1])) {
            free(v);
            return cli_fail("%s: need increasing integers in 0..%d", opt, STABILITY_MAX_BAND);
        }
        b->v[q] = (int)v[q];
    }
    b->n = n;
    free(v);
    return 0;
}

static const cli_opt stability_opts[] = {
    CLI_CUSTOM(stability_args, method, "method", "M", cli_parse_method, NULL,
               "z | ivanic | zxzxz | choi | blanco | wigner | halfpi\n"
               "| direct (bands ≤ 2) | zh (bands ≤ 5) | reference | taylor1\n"
               "| taylor1.5\n"
               "| taylor2 (halfpi forms\n"
               "no block above --exact-max and --ref-max: O(l²) a band)"),
    CLI_INT(stability_args, lmax, "lmax", "L", 0, STABILITY_MAX_BAND, NULL,
            "every band 0..L, below the method's limit"),
    CLI_CUSTOM(stability_args, bands, "bands", "L1,L2,...", bands_value, NULL,
               "only these bands (increasing, <= 4000); single-band\n"
               "methods then compute nothing else"),
    CLI_REAL(stability_args, stop_above, "stop-above", "X", 0, INFINITY, CLI_LO_OPEN, NULL,
             "stop after the first band whose orth exceeds X"),
    CLI_CUSTOM(stability_args, prec, "precision", "P", cli_parse_precision, "double", "double | float"),
    CLI_INT(stability_args, ref_max, "ref-max", "R", -1, 300, "40", "compare with the reference up to band R"),
    CLI_INT(stability_args, exact_max, "exact-max", "E", -1, INT_MAX, "128",
            "exact orthogonality up to band E (-1: none)"),
    CLI_CONVENTION(stability_args, conv),
    CLI_DEGREES(stability_args, degrees, "print the rotations' Euler angles in degrees"),
    CLI_GROUP(stability_args, sweep, cli_sweep_opts),
    CLI_END,
};

static const cli_cmd stability_decl = {
    .name = "stability",
    .usage = "stability --method M --lmax L [OPTIONS]",
    .about = "Accuracy of a rotation method band by band, l = 0..L, as the maximum over a\n"
             "fixed set of 10 rotations: β = 0, 1e-12, π/2, π-1e-9, π, the gimbal-lock\n"
             "cases (0.9, 0, -0.9) and (π/2, π, π/2), β = 1e-7 with α+γ = 0, and two seeded\n"
             "random rotations (the z method uses only those with β = 0).\n"
             "  orth   max|R Rᵀ - I| (exact up to --exact-max, above it the probe estimate\n"
             "         max|Rᵀ(R v) - v| over two seeded unit vectors; orth_exact says which)\n"
             "  hom    max|R(a)(R(b) v) - R(ab) v| over two unit probes, pairs of the set\n"
             "  ref    max|R - R_reference| (MPFR, ≥30 digits) up to --ref-max, else empty\n"
             "  broken true if the method overflowed (its numbers are then empty)\n",
    .opts = stability_opts,
    .notes = "JSON: {\"method\",\"precision\",\"convention\",\"lmax\",\"unit\" (of the Euler angles),\n"
             "       \"rotations\":[{name,euler}],\n"
             "       \"rows\":[{\"band\",\"orth\",\"orth_exact\",\"hom\",\"ref\",\"broken\"}]}\n",
};

/* ---- the sweep: item j is band j (--lmax) or the j-th of --bands ---- */

static int stops(const json_t *params, const json_t *row)
{
    const json_t *x = json_object_get(params, "stop_above"), *orth = json_object_get(row, "orth");
    return json_is_true(json_object_get(row, "broken")) ||
           (json_is_number(x) && json_is_number(orth) && json_number_value(orth) > json_number_value(x));
}

static json_t *finish(const json_t *params, json_t *rows)
{
    sh_rot_method method;
    sh_rotation set[SH_ROT_STABILITY_NSET];
    const char *names[SH_ROT_STABILITY_NSET];
    const int degrees = json_is_true(json_object_get(params, "degrees"));
    if (sh_rot_method_parse(json_string_value(json_object_get(params, "method")), &method) ||
        sh_rot_stability_set(set, names)) {
        json_decref(rows);
        return NULL;
    }
    json_t *rots = json_array();
    for (int k = 0; k < SH_ROT_STABILITY_NSET; k++) {
        if (method == SH_ROT_Z && set[k].beta != 0) continue;
        double e[3] = {cli_angle_out(set[k].alpha, degrees), cli_angle_out(set[k].beta, degrees),
                       cli_angle_out(set[k].gamma, degrees)};
        json_t *r = json_object();
        r = cli_put(r, "name", json_string(names[k]));
        r = cli_put(r, "euler", cli_json_array(e, 3));
        if (!r || json_array_append_new(rots, r)) { json_decref(rots); rots = NULL; break; }
    }
    json_t *root = json_object();
    static const char *const keys[] = {"method", "precision", "convention", "lmax"};
    for (int k = 0; k < 4; k++) root = cli_put(root, keys[k], json_incref(json_object_get(params, keys[k])));
    root = cli_put(root, "unit", json_string(cli_angle_unit(degrees)));
    root = cli_put(root, "rotations", rots);
    return cli_put(root, "rows", rows);
}

/* what a shard file of stability holds (merge checks it) */
static const cli_sweep_field params_fields[] = {
    {"method", CLI_FIELD_STRING, 0, 0, 0},        {"precision", CLI_FIELD_STRING, 0, 0, 0},
    {"convention", CLI_FIELD_STRING, 0, 0, 0},    {"lmax", CLI_FIELD_INT, 0, 0, STABILITY_MAX_BAND},
    {"bands", CLI_FIELD_INTS_OR_NULL, 0, 0, STABILITY_MAX_BAND},
    {"ref_max", CLI_FIELD_INT, 0, -1, 300},      {"exact_max", CLI_FIELD_INT, 0, -1, 1LL << 31},
    {"stop_above", CLI_FIELD_REAL_OR_NULL, 0, 0, 0}, {"degrees", CLI_FIELD_BOOL, 0, 0, 0},
    {NULL, 0, 0, 0, 0}};
static const cli_sweep_field row_fields[] = {
    {"band", CLI_FIELD_INT, 0, 0, STABILITY_MAX_BAND}, {"orth", CLI_FIELD_REAL_OR_NULL, 0, 0, 0},
    {"orth_exact", CLI_FIELD_BOOL, 0, 0, 0},        {"hom", CLI_FIELD_REAL_OR_NULL, 0, 0, 0},
    {"ref", CLI_FIELD_REAL_OR_NULL, 0, 0, 0},       {"broken", CLI_FIELD_BOOL, 0, 0, 0},
    {NULL, 0, 0, 0, 0}};

/* item j is band j (--lmax) or the j-th of --bands */
static int check_row(const json_t *params, long nitems, long j, const json_t *row, char *why, size_t n)
{
    const json_t *bands = json_object_get(params, "bands");
    const long want = json_is_array(bands) ? (long)json_integer_value(json_array_get(bands, (size_t)j)) : j;
    const long count = json_is_array(bands) ? (long)json_array_size(bands)
                                            : (long)json_integer_value(json_object_get(params, "lmax")) + 1;
    if (count != nitems) return snprintf(why, n, "the sweep has %ld items, its parameters %ld bands", nitems, count), 1;
    const long band = (long)json_integer_value(json_object_get(row, "band"));
    if (band != want) return snprintf(why, n, "band %ld, but item %ld is band %ld", band, j, want), 1;
    return 0;
}

const cli_sweep_kind sweep_stability = {"stability", finish, stops, NULL, params_fields, row_fields, check_row, 0};

static json_t *num_or_null(double x, int ok) { return ok ? json_real(x) : json_null(); }

typedef struct {
    cli_sweep *sw;
    const long *item; /* the sweep item of each band computed */
    long next;
    int fail;
} acc;

static int on_row(const sh_rot_stability_row *r, void *vctx)
{
    acc *a = vctx;
    json_t *o = json_object();
    o = cli_put(o, "band", json_integer(r->band));
    o = cli_put(o, "orth", num_or_null(r->orth, !r->broken));
    o = cli_put(o, "orth_exact", json_boolean(r->orth_exact));
    o = cli_put(o, "hom", num_or_null(r->hom, !r->broken));
    o = cli_put(o, "ref", num_or_null(r->ref, r->have_ref && !r->broken));
    o = cli_put(o, "broken", json_boolean(r->broken));
    /* a row that stops the sweep also stops sh_rot_stability (the same rule) */
    if (cli_sweep_add(a->sw, a->item[a->next++], o) == CLI_EXIT_USAGE) { a->fail = 1; return SH_ENOMEM; }
    return SH_OK;
}

/* What involves several options: a method (not auto), --lmax or --bands
 * (their last band as lmax), within the method's largest order. */
static int validate(stability_args *a, const cli_parsed *seen)
{
    if (!cli_given(seen, "method") || a->method == SH_ROT_AUTO) return cli_fail("stability: --method is required");
    if (a->bands.n && cli_given(seen, "lmax")) return cli_fail("stability: give --lmax or --bands, not both");
    if (a->bands.n) a->lmax = a->bands.v[a->bands.n - 1];
    else if (!cli_given(seen, "lmax")) return cli_fail("stability: --lmax (or --bands) is required");
    if (a->lmax + 1 > sh_rot_method_max_order(a->method))
        return cli_fail("stability: method %s is limited to order %d (lmax %d)", sh_rot_method_name(a->method),
                        sh_rot_method_max_order(a->method), sh_rot_method_max_order(a->method) - 1);
    return 0;
}

/* Everything the rows depend on: the whole sweep, whichever shard runs. */
static json_t *sweep_params(const stability_args *a)
{
    json_t *params = json_object(), *bl = a->bands.n ? json_array() : json_null();
    for (int q = 0; bl && a->bands.n && q < a->bands.n; q++)
        if (json_array_append_new(bl, json_integer(a->bands.v[q]))) { json_decref(bl); bl = NULL; }
    params = cli_put(params, "method", json_string(sh_rot_method_name(a->method)));
    params = cli_put(params, "precision", json_string(sh_precision_name(a->prec)));
    params = cli_put(params, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    params = cli_put(params, "lmax", json_integer(a->lmax));
    params = cli_put(params, "bands", bl);
    params = cli_put(params, "ref_max", json_integer(a->ref_max));
    params = cli_put(params, "exact_max", json_integer(a->exact_max));
    params = cli_put(params, "stop_above", a->stop_above > 0 ? json_real(a->stop_above) : json_null());
    return cli_put(params, "degrees", json_boolean(a->degrees));
}

/* This shard's bands (every band unsharded), increasing, through
 * sh_rot_stability; each row into the sweep.  0 or the exit code. */
static int compute(const stability_args *a, cli_sweep *sw)
{
    const long nitems = sw->nitems;
    int *mine = malloc((size_t)nitems * sizeof *mine);
    long *item = malloc((size_t)nitems * sizeof *item);
    int nm = 0;
    for (long j = 0; mine && item && j < nitems; j++)
        if (cli_sweep_owns(sw, j)) { item[nm] = j; mine[nm++] = a->bands.n ? a->bands.v[j] : (int)j; }
    acc ac = {sw, item, 0, 0};
    int st = !mine || !item ? sh_error(SH_ENOMEM, "stability: out of memory") : SH_OK;
    if (!st && nm > 0)
        st = sh_rot_stability(a->method, a->prec, (sh_convention)a->conv, mine[nm - 1], mine, nm, a->ref_max,
                              a->exact_max, a->stop_above, on_row, &ac);
    free(mine);
    free(item);
    if (ac.fail) return CLI_EXIT_USAGE;
    return st ? cli_fail_status(st) : 0;
}

static int run(int argc, char **argv)
{
    stability_args a = {0};
    cli_parsed seen;
    int rc = cli_args_parse(&stability_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen))) return rc;
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_stability, sweep_params(&a), a.bands.n ? a.bands.n : a.lmax + 1, &a.sweep, "bands");
    return cli_sweep_close(&sw, compute(&a, &sw));
}

const cli_command cmd_stability = {"stability", run,
                                   "a rotation method's error band by band (orthogonality, "
                                   "homomorphism, reference)", &stability_decl};
