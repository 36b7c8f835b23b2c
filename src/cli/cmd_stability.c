/* cmd_stability.c — `shlab stability`: a method's accuracy band by band
 * (orthogonality, homomorphism, distance to the MPFR reference) over the fixed
 * rotation set with the extremes. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>

extern const cli_command cmd_stability;
extern const cli_sweep_kind sweep_stability;

/* Largest band: memory is 11 blocks of (2L+1)² doubles (1.4 GB at 2000,
 * 5.6 GB at 4000; halfpi needs none above --exact-max and --ref-max), time
 * depends on the method (and no method may go beyond its own largest order). */
#define STABILITY_MAX_BAND 4000

static const char help[] =
    "Usage: shlab stability --method M --lmax L [OPTIONS]\n"
    "\n"
    "Accuracy of a rotation method band by band, l = 0..L, as the maximum over a\n"
    "fixed set of 10 rotations: β = 0, 1e-12, π/2, π-1e-9, π, the gimbal-lock\n"
    "cases (0.9, 0, -0.9) and (π/2, π, π/2), β = 1e-7 with α+γ = 0, and two seeded\n"
    "random rotations (the z method uses only those with β = 0).\n"
    "  orth   max|R Rᵀ - I| (exact up to --exact-max, above it the probe estimate\n"
    "         max|Rᵀ(R v) - v| over two seeded unit vectors; orth_exact says which)\n"
    "  hom    max|R(a)(R(b) v) - R(ab) v| over two unit probes, pairs of the set\n"
    "  ref    max|R - R_reference| (MPFR, ≥30 digits) up to --ref-max, else empty\n"
    "  broken true if the method overflowed (its numbers are then empty)\n"
    "\n"
    "  --method M           z | ivanic | zxzxz | choi | blanco | wigner | halfpi\n"
    "                       | reference | taylor1 | taylor1.5 | taylor2 (halfpi forms\n"
    "                       no block above --exact-max and --ref-max: O(l²) a band)\n"
    "  --lmax L             every band 0..L (L <= 4000 and below the method's limit)\n"
    "  --bands L1,L2,...    only these bands (increasing, <= 4000); single-band\n"
    "                       methods then compute nothing else\n"
    "  --stop-above X       stop after the first band whose orth exceeds X\n"
    "  --precision P        double (default) | float\n"
    "  --ref-max R          compare with the reference up to band R (default 40)\n"
    "  --exact-max E        exact orthogonality up to band E (default 128)\n"
    "  --convention cs|nocs\n"
    "  --degrees            print the rotations' Euler angles in degrees\n"
    "  --quiet              no progress on stderr\n"
    CLI_SHARD_HELP
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"method\",\"precision\",\"convention\",\"lmax\",\"unit\" (of the Euler angles),\n"
    "       \"rotations\":[{name,euler}],\n"
    "       \"rows\":[{\"band\",\"orth\",\"orth_exact\",\"hom\",\"ref\",\"broken\"}]}\n";

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

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_CONVENTION,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_PRECISION,
                                         CLI_LONGOPT_SHARD,
                                         {"lmax", required_argument, 0, 'L'},
                                         {"ref-max", required_argument, 0, 'r'},
                                         {"exact-max", required_argument, 0, 'e'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"bands", required_argument, 0, 'B'},
                                         {"stop-above", required_argument, 0, 's'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    sh_rot_method method = SH_ROT_IVANIC;
    sh_precision prec = SH_PREC_DOUBLE;
    int lmax = -1, ref_max = 40, exact_max = 128, have_method = 0, quiet = 0, nb = 0;
    static int band_list[STABILITY_MAX_BAND + 1]; /* increasing, in 0..4000: at most 4001 */
    int *bands = NULL;
    double stop_above = 0;
    sh_shard shard = SH_SHARD_ALL;
    int have_shard = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'L':
            if (cli_int("--lmax", optarg, &lmax)) return CLI_EXIT_USAGE;
            if (lmax < 0 || lmax > STABILITY_MAX_BAND)
                return cli_fail("--lmax: %d out of range 0..%d", lmax, STABILITY_MAX_BAND);
            break;
        case 'r':
            if (cli_int("--ref-max", optarg, &ref_max)) return CLI_EXIT_USAGE;
            if (ref_max < -1 || ref_max > 300) return cli_fail("--ref-max: %d out of range -1..300", ref_max);
            break;
        case 'e':
            if (cli_int("--exact-max", optarg, &exact_max)) return CLI_EXIT_USAGE;
            if (exact_max < -1) return cli_fail("--exact-max: %d must be >= -1", exact_max);
            break;
        case 'q': quiet = 1; break;
        case 's':
            if (cli_double("--stop-above", optarg, &stop_above)) return CLI_EXIT_USAGE;
            if (!(stop_above > 0)) return cli_fail("--stop-above: must be > 0");
            break;
        case CLI_OPT_SHARD:
            if (cli_shard("--shard", optarg, &shard)) return CLI_EXIT_USAGE;
            have_shard = 1;
            break;
        case 'B': {
            double *v = NULL;
            if (cli_doubles("--bands", optarg, &v, &nb)) return CLI_EXIT_USAGE;
            for (int q = 0; q < nb; q++) {
                if (q > STABILITY_MAX_BAND || v[q] != floor(v[q]) || v[q] < 0 || v[q] > STABILITY_MAX_BAND ||
                    (q && v[q] <= v[q - 1])) {
                    free(v);
                    return cli_fail("--bands: need increasing integers in 0..%d", STABILITY_MAX_BAND);
                }
                band_list[q] = (int)v[q];
            }
            free(v);
            bands = band_list;
            break;
        }
        default: {
            const int e = cli_common_opt(&cmd_stability, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    method = com.method;
    prec = com.prec;
    have_method = com.have_method;
    if (optind < argc) return cli_fail("stability: unexpected argument '%s'", argv[optind]);
    if (!have_method) return cli_fail("stability: --method is required");
    if (bands && lmax >= 0) return cli_fail("stability: give --lmax or --bands, not both");
    if (bands) lmax = bands[nb - 1];
    if (lmax < 0) return cli_fail("stability: --lmax (or --bands) is required");
    if (lmax + 1 > sh_rot_method_max_order(method))
        return cli_fail("stability: method %s is limited to order %d (lmax %d)",
                        sh_rot_method_name(method), sh_rot_method_max_order(method),
                        sh_rot_method_max_order(method) - 1);
    /* everything the rows depend on: the whole sweep, whichever shard runs */
    json_t *params = json_object(), *bl = bands ? json_array() : json_null();
    for (int q = 0; bl && bands && q < nb; q++)
        if (json_array_append_new(bl, json_integer(bands[q]))) { json_decref(bl); bl = NULL; }
    params = cli_put(params, "method", json_string(sh_rot_method_name(method)));
    params = cli_put(params, "precision", json_string(sh_precision_name(prec)));
    params = cli_put(params, "convention", json_string(sh_convention_name(com.conv)));
    params = cli_put(params, "lmax", json_integer(lmax));
    params = cli_put(params, "bands", bl);
    params = cli_put(params, "ref_max", json_integer(ref_max));
    params = cli_put(params, "exact_max", json_integer(exact_max));
    params = cli_put(params, "stop_above", stop_above > 0 ? json_real(stop_above) : json_null());
    params = cli_put(params, "degrees", json_boolean(com.degrees));
    const long nitems = bands ? nb : lmax + 1;
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_stability, params, nitems, have_shard ? &shard : NULL, com.fmt, quiet, "bands");
    /* this shard's bands (every band unsharded), increasing */
    int *mine = malloc((size_t)nitems * sizeof *mine);
    long *item = malloc((size_t)nitems * sizeof *item);
    int nm = 0;
    for (long j = 0; mine && item && j < nitems; j++)
        if (cli_sweep_owns(&sw, j)) { item[nm] = j; mine[nm++] = bands ? bands[j] : (int)j; }
    acc a = {&sw, item, 0, 0};
    int st = !mine || !item ? sh_error(SH_ENOMEM, "stability: out of memory") : SH_OK;
    if (!st && nm > 0)
        st = sh_rot_stability(method, prec, com.conv, mine[nm - 1], mine, nm, ref_max, exact_max,
                              stop_above, on_row, &a);
    free(mine);
    free(item);
    if (a.fail) { cli_sweep_free(&sw); return CLI_EXIT_USAGE; }
    if (st) { cli_sweep_free(&sw); return cli_fail_status(st); }
    return cli_sweep_end(&sw);
}

const cli_command cmd_stability = {"stability", run,
                                   "a rotation method's error band by band (orthogonality, "
                                   "homomorphism, reference)",
                                   help, NULL};
