/* cmd_scale_interp.c — `shlab scale-interp`: the error of interpolating the
 * scaling matrix over k from sampled values (Wang et al. 2006, Sec. 2.2). */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_sweep_kind sweep_scale_interp;

typedef struct {
    int order, samples, dense, energy, conv, degrees;
    sh_scale_family family;
    sh_scale_spacing spacing;
    sh_scale_interp_kind interp;
    double kmin, kmax, cone;
    cli_sweep_args sweep;
} scale_interp_args;

/* --family, --spacing, --interp: the library's names and its message */
static int family_value(const char *opt, const char *s, void *field)
{
    return sh_scale_family_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}
static int spacing_value(const char *opt, const char *s, void *field)
{
    return sh_scale_spacing_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}
static int interp_value(const char *opt, const char *s, void *field)
{
    return sh_scale_interp_parse(s, field) ? cli_fail("%s: %s", opt, sh_last_error()) : 0;
}

static const cli_opt scale_interp_opts[] = {
    CLI_ORDER(scale_interp_args, order, SH_SCALE_MAX_ORDER, NULL, "number of bands"),
    CLI_CUSTOM(scale_interp_args, family, "family", "F", family_value, NULL,
               "linear | cone | midrange (see shlab scale --help)"),
    CLI_INT(scale_interp_args, samples, "samples", "S", 0, 0, NULL, "sampled values of k (>= 2; >= 3 for cubic)"),
    CLI_CUSTOM(scale_interp_args, spacing, "spacing", "SP", spacing_value, NULL, "geometric (needs 0 < A) | uniform"),
    CLI_REAL(scale_interp_args, kmin, "kmin", "A", 0, 0, 0, NULL,
             "lower end of the k range (A < B, inside the family's\nvalid range)"),
    CLI_REAL(scale_interp_args, kmax, "kmax", "B", 0, 0, 0, NULL, "upper end of the k range"),
    CLI_CUSTOM(scale_interp_args, interp, "interp", "linear|cubic", interp_value, "linear",
               "linear or GSL natural cubic spline"),
    CLI_INT(scale_interp_args, dense, "dense", "D", 2, 100000, "400", "points of the dense check grid"),
    CLI_FLAG(scale_interp_args, energy, "energy", "energy-preserving scaling"),
    CLI_REAL(scale_interp_args, cone, "cone-angle", "T", 0, 0, 0, NULL, "cone family half-angle (default π/4)"),
    CLI_DEGREES(scale_interp_args, degrees, "--cone-angle and the printed cone_angle in degrees"),
    CLI_CHOICE(scale_interp_args, conv, "convention", "cs|nocs", cli_convention_names, "cs",
               "tag only (the matrix does not depend on it)"),
    CLI_GROUP(scale_interp_args, sweep, cli_sweep_opts),
    CLI_END,
};

static const cli_cmd scale_interp_decl = {
    .name = "scale-interp",
    .usage = "scale-interp --order N --family F --samples S --spacing SP --kmin A --kmax B [OPTIONS]",
    .about = "Interpolation of the SH scaling matrix over k (Wang et al. 2006, Sec. 2.2: 40\n"
             "samples of k in an exponential distribution, linear interpolation).  M(k) is\n"
             "tabulated at S values of k from A to B, every entry is interpolated in k, and\n"
             "the result is compared with M computed directly on a dense grid of k (same\n"
             "spacing, ends included).  Errors are absolute, over all entries with m_i = m_j.\n",
    .opts = scale_interp_opts,
    .notes = "JSON: {\"order\",\"family\",\"energy\",\"convention\",[\"cone_angle\",\"unit\" (cone\n"
             "       family)],\"samples\",\"spacing\",\"interp\",\n"
             "       \"kmin\",\"kmax\",\"dense\",\"max_error\",\"rms_error\",\"worst_k\"}\n",
};

/* the sweep: item d is point d of the dense k grid */
static json_t *finish(const json_t *params, json_t *rows)
{
    const size_t n = json_array_size(rows);
    sh_scale_interp_point *pts = malloc(sizeof *pts * (n ? n : 1));
    sh_scale_interp_result r;
    size_t i;
    json_t *row;
    json_array_foreach(rows, i, row) if (pts) {
        pts[i].k = json_real_value(json_object_get(row, "k"));
        pts[i].max_error = json_real_value(json_object_get(row, "max_error"));
        pts[i].sum_sq = json_real_value(json_object_get(row, "sum_sq"));
        pts[i].weight = json_real_value(json_object_get(row, "weight"));
    }
    const int st = pts && n ? sh_scale_interp_reduce(pts, (int)n, &r) : SH_ENOMEM;
    free(pts);
    json_decref(rows);
    if (st) return NULL;
    json_t *root = json_deep_copy(params);
    root = cli_put(root, "max_error", json_real(r.max_error));
    root = cli_put(root, "rms_error", json_real(r.rms_error));
    return cli_put(root, "worst_k", json_real(r.worst_k));
}

static const cli_sweep_field params_fields[] = {
    {"order", CLI_FIELD_INT, 0, 1, SH_SCALE_MAX_ORDER}, {"family", CLI_FIELD_STRING, 0, 0, 0},
    {"energy", CLI_FIELD_BOOL, 0, 0, 0},                {"convention", CLI_FIELD_STRING, 0, 0, 0},
    {"cone_angle", CLI_FIELD_REAL, 1, 0, 0},            {"unit", CLI_FIELD_STRING, 1, 0, 0},
    {"samples", CLI_FIELD_INT, 0, 0, 1LL << 31},       {"spacing", CLI_FIELD_STRING, 0, 0, 0},
    {"interp", CLI_FIELD_STRING, 0, 0, 0},              {"kmin", CLI_FIELD_REAL, 0, 0, 0},
    {"kmax", CLI_FIELD_REAL, 0, 0, 0},                  {"dense", CLI_FIELD_INT, 0, 2, 100000},
    {NULL, 0, 0, 0, 0}};
static const cli_sweep_field row_fields[] = {{"k", CLI_FIELD_REAL, 0, 0, 0}, {"max_error", CLI_FIELD_REAL, 0, 0, 0},
                                             {"sum_sq", CLI_FIELD_REAL, 0, 0, 0}, {"weight", CLI_FIELD_REAL, 0, 0, 0},
                                             {NULL, 0, 0, 0, 0}};

/* item d is point d of the dense grid, the library's sh_scale_grid_point */
static int check_row(const json_t *params, long nitems, long d, const json_t *row, char *why, size_t n)
{
    sh_scale_spacing sp;
    const long dense = (long)json_integer_value(json_object_get(params, "dense"));
    if (sh_scale_spacing_parse(json_string_value(json_object_get(params, "spacing")), &sp))
        return snprintf(why, n, "the parameters' spacing: %s", sh_last_error()), 1;
    if (nitems != dense) return snprintf(why, n, "the sweep has %ld items, its dense grid %ld points", nitems, dense), 1;
    const double want = sh_scale_grid_point(sp, json_real_value(json_object_get(params, "kmin")),
                                            json_real_value(json_object_get(params, "kmax")), (int)d, (int)dense);
    const double got = json_real_value(json_object_get(row, "k"));
    if (got != want) return snprintf(why, n, "k %.17g, but item %ld is the point k = %.17g", got, d, want), 1;
    return 0;
}

const cli_sweep_kind sweep_scale_interp = {"scale-interp", finish, NULL, NULL, params_fields, row_fields, check_row, 0};

/* What involves several options (the library checks the k range and the
 * samples): every input given, --cone-angle for the cone family only and
 * inside (0, π).  The scaling into *s. */
static int validate(const scale_interp_args *a, const cli_parsed *seen, sh_scaling *s)
{
    if (!cli_given(seen, "order")) return cli_fail("scale-interp: --order is required");
    if (!cli_given(seen, "family")) return cli_fail("scale-interp: --family is required (linear, cone, midrange)");
    if (!a->samples) return cli_fail("scale-interp: --samples is required");
    if (!cli_given(seen, "spacing")) return cli_fail("scale-interp: --spacing is required (geometric, uniform)");
    if (!cli_given(seen, "kmin") || !cli_given(seen, "kmax"))
        return cli_fail("scale-interp: --kmin and --kmax are required");
    *s = (sh_scaling){a->family, 1.0, 0.0, a->energy};
    if (cli_given(seen, "cone-angle")) {
        if (cli_applies("scale-interp", 1, "--cone-angle", s->family == SH_SCALE_CONE, "--family cone"))
            return CLI_EXIT_USAGE;
        s->cone_angle = a->degrees ? a->cone * M_PI / 180.0 : a->cone;
        if (!(s->cone_angle > 0.0 && s->cone_angle < M_PI))
            return cli_fail("--cone-angle: %g is outside (0, %s)", a->cone, a->degrees ? "180" : "pi");
    }
    return 0;
}

/* Everything the result depends on: the whole sweep, whichever shard runs. */
static json_t *sweep_params(const scale_interp_args *a, const sh_scaling *s)
{
    json_t *params = json_object();
    params = cli_put(params, "order", json_integer(a->order));
    params = cli_put(params, "family", json_string(sh_scale_family_name(s->family)));
    params = cli_put(params, "energy", json_boolean(s->energy));
    params = cli_put(params, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    if (s->family == SH_SCALE_CONE) {
        params = cli_put(params, "cone_angle",
                         json_real(cli_angle_out(s->cone_angle > 0 ? s->cone_angle : M_PI / 4.0, a->degrees)));
        params = cli_put(params, "unit", json_string(cli_angle_unit(a->degrees)));
    }
    params = cli_put(params, "samples", json_integer(a->samples));
    params = cli_put(params, "spacing", json_string(sh_scale_spacing_name(a->spacing)));
    params = cli_put(params, "interp", json_string(sh_scale_interp_name(a->interp)));
    params = cli_put(params, "kmin", json_real(a->kmin));
    params = cli_put(params, "kmax", json_real(a->kmax));
    return cli_put(params, "dense", json_integer(a->dense));
}

/* This shard's points of the dense grid (the library splits the work; every
 * shard also tabulates all the samples), each a row.  0 or the exit code. */
static int compute(const scale_interp_args *a, const sh_scaling *s, cli_sweep *sw)
{
    sh_scale_interp_point *pts = malloc(sizeof *pts * (size_t)a->dense);
    if (!pts) return cli_fail("out of memory");
    /* progress from the library, not from the rows */
    cli_progress prog;
    cli_progress_start(&prog, sw->label, a->sweep.quiet);
    sw->prog.quiet = 1;
    const int st = sh_scale_interp_points(a->order, s, a->samples, a->spacing, a->kmin, a->kmax, a->interp,
                                          a->dense, cli_sweep_items(sw), pts, cli_progress_step, &prog);
    if (st) { /* the library's message may already name the command */
        free(pts);
        const char *why = sh_last_error();
        if (!why || !*why) why = sh_strerror(st);
        return cli_fail(strncmp(why, "scale-interp: ", 14) ? "scale-interp: %s" : "%s", why);
    }
    for (int d = 0; d < a->dense; d++) {
        if (!cli_sweep_owns(sw, d)) continue;
        json_t *r = json_object();
        r = cli_put(r, "k", json_real(pts[d].k));
        r = cli_put(r, "max_error", json_real(pts[d].max_error));
        r = cli_put(r, "sum_sq", json_real(pts[d].sum_sq));
        r = cli_put(r, "weight", json_real(pts[d].weight));
        if (cli_sweep_add(sw, d, r) == CLI_EXIT_USAGE) { free(pts); return CLI_EXIT_USAGE; }
    }
    free(pts);
    return 0;
}

static int run(int argc, char **argv)
{
    scale_interp_args a = {0};
    cli_parsed seen;
    sh_scaling s;
    int rc = cli_args_parse(&scale_interp_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if ((rc = validate(&a, &seen, &s))) return rc;
    cli_sweep sw;
    cli_sweep_begin(&sw, &sweep_scale_interp, sweep_params(&a, &s), a.dense, &a.sweep, "points");
    return cli_sweep_close(&sw, compute(&a, &s, &sw));
}
const cli_command cmd_scale_interp = {"scale-interp", run,
                                      "error of interpolating the scaling matrix over k (Wang Sec. 2.2)", &scale_interp_decl};
