/* cmd_scale_scene.c — `shlab scale-scene`: SH scaling against ground truth
 * in the scenes of scale_scene.c (Wang et al. 2006, Sec. 3). */
#include "cli_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_scale_scene;

#define SCENE_MAX_ORDER 16
#define SCENE_MAX_K 64
#define SCENE_DEFAULT_NODES 200

/* --scene and --family as given (their names, for the messages) */
typedef struct {
    const char *name;
    sh_scale_scene_kind kind;
} scene_choice;
typedef struct {
    const char *name;
    sh_scale_family family;
} family_choice;
typedef struct {
    double v[SCENE_MAX_K];
    int n;
} k_list;

typedef struct {
    cli_env_args env; /* midrange: the environment (default: lobes) */
    scene_choice scene;
    family_choice family;
    k_list k;
    double size, wobble, occ, cone, dir[3]; /* occ, cone in the unit of --degrees */
    int order, nodes, degrees, conv, fmt;
    const char *rotm;
} scale_scene_args;

static int parse_scene(const char *opt, const char *s, void *field)
{
    scene_choice *c = field;
    if (sh_scale_scene_parse(s, &c->kind)) return cli_fail("%s: %s", opt, sh_last_error());
    c->name = s;
    return 0;
}

static int parse_family(const char *opt, const char *s, void *field)
{
    family_choice *c = field;
    if (sh_scale_family_parse(s, &c->family)) return cli_fail("%s: %s", opt, sh_last_error());
    c->name = s;
    return 0;
}

static int parse_k(const char *opt, const char *s, void *field)
{
    k_list *l = field;
    double *v = NULL;
    int n = 0, rc = 0;
    if (cli_doubles(opt, s, &v, &n)) return CLI_EXIT_USAGE;
    if (n < 1 || n > SCENE_MAX_K) rc = cli_fail("%s: %d values (1..%d)", opt, n, SCENE_MAX_K);
    else {
        memcpy(l->v, v, sizeof(double) * (size_t)n);
        l->n = n;
    }
    free(v);
    return rc;
}

static int parse_dir(const char *opt, const char *s, void *field) { return cli_vec3(opt, s, field); }

static const cli_opt scale_scene_opts[] = {
    CLI_CUSTOM(scale_scene_args, scene, "scene", "S", parse_scene, NULL, "sphere | cone | midrange (required)"),
    CLI_ORDER(scale_scene_args, order, SCENE_MAX_ORDER, NULL, "number of bands (required)"),
    CLI_CUSTOM(scale_scene_args, k, "k", "LIST", parse_k, NULL, "comma-separated k values (at most 64; required)"),
    CLI_CUSTOM(scale_scene_args, family, "family", "F", parse_family, NULL,
               "only this family (default: every applicable one)"),
    CLI_REAL(scale_scene_args, size, "size", "X", 0, 0, 0, "0.5", "sphere ρ/r or cone rim height h/r"),
    CLI_REAL(scale_scene_args, wobble, "wobble", "E", 0, 0, 0, "0.3", "cone rim modulation, |E| < 1"),
    CLI_REAL(scale_scene_args, occ, "occluder-angle", "T", 0, 0, 0, NULL,
             "cone occluder half-angle in (0, π/2) (default π/4)"),
    CLI_REAL(scale_scene_args, cone, "cone-angle", "T", 0, 0, 0, NULL, "θ0 of the cone family (defaults above)"),
    CLI_INT(scale_scene_args, nodes, "nodes", "S", 0, 0, "200", "midrange quadrature θ nodes (8..4096)"),
    CLI_CUSTOM(scale_scene_args, dir, "dir", "X,Y,Z", parse_dir, NULL,
               "midrange displacement direction (default 0,0,1;\nnormalised; finite and non-zero)"),
    CLI_STRING(scale_scene_args, rotm, "rotation-method", "M",
               "midrange, DIR ≠ +z: exact rotation method of the\nrotate → scale → rotate back (default zxzxz; ivanic,\n"
               "choi, blanco, wigner, reference)"),
    CLI_DEGREES(scale_scene_args, degrees,
                "angles in degrees: the options above, the angles in\n--light SPEC, and the printed angles"),
    CLI_CONVENTION(scale_scene_args, conv),
    CLI_FORMAT(scale_scene_args, fmt),
    CLI_GROUP(scale_scene_args, env, cli_env_opts),
    CLI_END,
};

static const cli_cmd scale_scene_decl = {
    .name = "scale-scene",
    .usage = "scale-scene --scene sphere|cone|midrange --order N --k LIST [OPTIONS]",
    .about = "SH scaling against ground truth (Wang et al. 2006, Sec. 3).  The scene's\n"
             "function is projected at the reference point, scaled to each k with every\n"
             "applicable family, plain and energy-preserving, and compared with the exact\n"
             "projection at k.  Errors are relative L2 over the coefficients:\n"
             "  err_scaled  |M S_r − E(k)|/|E(k)|        (what scaling gives)\n"
             "  err_geom    |P(F_r∘τ ψ/sinθ) − E(k)|/|E|  (the family's geometry alone)\n"
             "  err_trunc   |M S_r − P(F_r∘τ ψ/sinθ)|/|E| (the cost of truncating S_r)\n"
             "Scenes (occlusion 1 inside the occluder's silhouette; +z toward the occluder):\n"
             "  sphere    sphere of radius ρ = SIZE·r; exact cap arcsin(ρ/d), k = d/r > SIZE;\n"
             "            families linear (k) and cone (θ0 = arccos SIZE, the cone through\n"
             "            the silhouette seen from r, unless --cone-angle)\n"
             "  cone      solid cone, apex at the centre, half-angle --occluder-angle (π/4),\n"
             "            rim at height SIZE·r·(1 + WOBBLE cosφ); k = d/r beyond the rim;\n"
             "            families linear and cone (θ0 = the occluder's: exact geometry)\n"
             "  midrange  environment on a sphere of radius R seen from d·DIR (DIR = +z\n"
             "            unless --dir), k = d/R in [−0.999, 0.999], reference at the\n"
             "            centre; family midrange.  Exact radiance by ray-sphere\n"
             "            intersection; projections by the Gauss-Legendre × uniform-φ rule\n"
             "            with --nodes θ nodes.  For DIR ≠ +z the centre capture is\n"
             "            rotated so that DIR becomes +z, scaled, and rotated back\n"
             "            (--rotation-method); err_geom is then computed about DIR\n"
             "            directly, without SH rotations.\n"
             "The midrange environment: --light lobes (the default; two smooth non-zonal\n"
             "lobes) or an analytic light as in shlab project, or --probe, a lat-long EXR\n"
             "(luminance).\n",
    .opts = scale_scene_opts,
    .notes = "JSON: {\"scene\",\"order\",\"convention\",\"method\",[sphere, cone: \"size\",\n"
             "       cone: \"occluder_angle\",\"wobble\"; \"cone_family_angle\",\"unit\"],\n"
             "       [midrange: [\"unit\" (a SPEC with angles)],\"environment\",\"nodes\",\n"
             "       \"dir_x\",\"dir_y\",\"dir_z\" (unit vector),\n"
             "       \"rotation_method\" (\"none\" for +z)],\"rows\":[{\"k\",\"family\",\"energy\",\n"
             "       \"err_scaled\",\"err_geom\",\"err_trunc\"}]}\n",
};

/* The run: the scene, its environment, the families compared. */
typedef struct {
    const scale_scene_args *a;
    double deg, unit[3], fam_cone;
    int tilted, light_angles, nf;
    sh_scale_scene sc;
    sh_scale_family fams[2];
    sh_light L;
    sh_image img; /* --probe */
} scale_work;

/* The options that go together; the scene's geometry and rotation. */
static int validate(const scale_scene_args *a, const cli_parsed *seen, scale_work *w)
{
    if (!a->scene.name) return cli_fail("scale-scene: --scene is required (sphere, cone, midrange)");
    if (!a->order) return cli_fail("scale-scene: --order is required");
    if (!a->k.n) return cli_fail("scale-scene: --k is required (comma-separated list)");
    w->deg = a->degrees ? M_PI / 180.0 : 1.0;
    const sh_scale_scene_kind kind = a->scene.kind;
    const int midrange = kind == SH_SCENE_MIDRANGE;
    const char *along_z = "--scene midrange (occluders lie along +z)";
    if (cli_scene_applies("scale-scene", seen, "occluder-angle", kind == SH_SCENE_CONE, "--scene cone") ||
        cli_scene_applies("scale-scene", seen, "light probe", midrange, "--scene midrange"))
        return CLI_EXIT_USAGE;
    if (a->env.light && a->env.probe) return cli_fail("scale-scene: give --light or --probe, not both");
    if (cli_scene_applies("scale-scene", seen, "dir rotation-method", midrange, along_z)) return CLI_EXIT_USAGE;
    sh_scale_scene *sc = &w->sc;
    sc->kind = kind;
    w->unit[2] = 1.0;
    if (cli_given(seen, "dir")) {
        if (sh_scale_axis_unit(a->dir, w->unit)) return cli_fail("--dir: %s", sh_last_error());
        memcpy(sc->dir, w->unit, sizeof w->unit);
    }
    sc->rotation = SH_ROT_ZXZXZ;
    if (a->rotm) {
        const char *m = a->rotm;
        if (cli_method(m, &sc->rotation)) return CLI_EXIT_USAGE;
        if (!sh_rot_method_is_exact(sc->rotation) || sc->rotation == SH_ROT_Z)
            return cli_fail("--rotation-method: %s is not an exact general rotation (zxzxz, ivanic, choi, blanco, "
                            "wigner, reference)", m);
        if (!sh_rot_method_max_order(sc->rotation)) return cli_fail("--rotation-method: %s is not built in", m);
        if (a->order > sh_rot_method_max_order(sc->rotation))
            return cli_fail("--rotation-method: %s accepts orders up to %d", m, sh_rot_method_max_order(sc->rotation));
    }
    w->tilted = !sh_scale_axis_is_z(w->unit);
    sc->size = a->size;
    sc->wobble = kind == SH_SCENE_CONE ? a->wobble : 0.0;
    sc->cone_angle = cli_given(seen, "occluder-angle") ? a->occ * w->deg : M_PI / 4.0;
    sc->nodes = a->nodes;
    return 0;
}

/* The midrange scene's environment: --probe (a 2:1 lat-long image), a
 * --light, or the lobes. */
static int environment(const scale_scene_args *a, scale_work *w)
{
    if (a->scene.kind != SH_SCENE_MIDRANGE) return 0;
    const char *probe = a->env.probe, *light = a->env.light;
    if (probe) {
        if (cli_input("probe", probe)) return CLI_EXIT_USAGE;
        if (sh_exr_read(probe, &w->img, NULL)) return cli_fail("--probe: %s", sh_last_error());
        if (w->img.width != 2 * w->img.height)
            return cli_fail("--probe: %s is %dx%d, not a 2:1 lat-long image", probe, w->img.width, w->img.height);
        w->sc.probe = &w->img;
    } else if (light && strcmp(light, "lobes")) {
        if (sh_light_parse(light, a->degrees, &w->L)) return cli_fail("--light: %s", sh_last_error());
        cli_light_warn("scale-scene", &w->L, a->degrees);
        w->light_angles = cli_light_has_angles(&w->L);
        w->sc.light = sh_light_fn;
        w->sc.light_ctx = &w->L;
    } else {
        w->sc.light = sh_scale_scene_lobes_fn;
    }
    return 0;
}

/* Every k (and the reference point) in the scene's range; the families
 * compared and the cone family's angle. */
static int families(const scale_scene_args *a, const cli_parsed *seen, scale_work *w)
{
    const sh_scale_scene *sc = &w->sc;
    for (int q = 0; q < a->k.n; q++)
        if (sh_scale_scene_check(sc, a->k.v[q])) return cli_fail("scale-scene: %s", sh_last_error());
    if (sh_scale_scene_check(sc, sh_scale_scene_k_ref(sc))) return cli_fail("scale-scene: %s", sh_last_error());
    const int midrange = sc->kind == SH_SCENE_MIDRANGE;
    if (a->family.name) {
        w->fams[w->nf++] = a->family.family;
        if ((a->family.family == SH_SCALE_MIDRANGE) != midrange)
            return cli_fail("scale-scene: family %s does not apply to the %s scene (%s)", a->family.name, a->scene.name,
                            midrange ? "midrange only" : "linear or cone");
    } else if (midrange) {
        w->fams[w->nf++] = SH_SCALE_MIDRANGE;
    } else {
        w->fams[w->nf++] = SH_SCALE_LINEAR;
        w->fams[w->nf++] = SH_SCALE_CONE;
    }
    const int have_cone = cli_given(seen, "cone-angle");
    w->fam_cone = have_cone ? a->cone * w->deg : sc->kind == SH_SCENE_SPHERE ? acos(sc->size) : sc->cone_angle;
    if (have_cone && !(w->fam_cone > 0 && w->fam_cone < M_PI))
        return cli_fail("--cone-angle: %g is outside (0, pi)", a->cone);
    return 0;
}

/* The errors of every k × family × (plain, energy-preserving); NULL on
 * failure (after the error line, in *rc). */
static json_t *error_rows(const scale_scene_args *a, const scale_work *w, int *rc)
{
    const sh_scale_scene *sc = &w->sc;
    const int nk = a->k.n;
    double *Sr = malloc(sizeof(double) * (size_t)sh_ncoeff(a->order));
    if (!Sr) { *rc = cli_fail("out of memory"); return NULL; }
    int st = sh_scale_scene_exact(sc, a->order, (sh_convention)a->conv, sh_scale_scene_k_ref(sc), Sr);
    json_t *rows = json_array();
    for (int q = 0; q < nk && !st && rows; q++) {
        const double k = a->k.v[q];
        if (nk > 4) fprintf(stderr, "  scale-scene: k = %g (%d of %d)\n", k, q + 1, nk);
        for (int f = 0; f < w->nf && !st; f++)
            for (int e = 0; e < 2 && !st; e++) {
                sh_scaling s = {w->fams[f], k, w->fams[f] == SH_SCALE_CONE ? w->fam_cone : 0.0, e};
                sh_scale_scene_err er;
                if ((st = sh_scale_scene_errors(sc, a->order, (sh_convention)a->conv, &s, k, Sr, &er, NULL))) break;
                json_t *r = json_object();
                r = cli_put(r, "k", json_real(k));
                r = cli_put(r, "family", json_string(sh_scale_family_name(w->fams[f])));
                r = cli_put(r, "energy", json_boolean(e));
                r = cli_put(r, "err_scaled", json_real(er.err_scaled));
                r = cli_put(r, "err_geom", json_real(er.err_geom));
                r = cli_put(r, "err_trunc", json_real(er.err_trunc));
                if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; break; }
            }
    }
    free(Sr);
    if (st) {
        json_decref(rows);
        *rc = cli_fail("scale-scene: %s", sh_last_error());
        return NULL;
    }
    return rows; /* NULL if out of memory: cli_put, then cli_emit, report it */
}

static json_t *build_result(const scale_scene_args *a, const scale_work *w, json_t *rows)
{
    const sh_scale_scene *sc = &w->sc;
    const int midrange = sc->kind == SH_SCENE_MIDRANGE;
    json_t *root = json_object();
    root = cli_put(root, "scene", json_string(sh_scale_scene_name(sc->kind)));
    root = cli_put(root, "order", json_integer(a->order));
    root = cli_put(root, "convention", json_string(sh_convention_name((sh_convention)a->conv)));
    root = cli_put(root, "method", json_string(sc->kind == SH_SCENE_SPHERE ? "closed-form" :
                                               sc->kind == SH_SCENE_CONE ? "region-quadrature" : "quad"));
    if (!midrange) root = cli_put(root, "size", json_real(sc->size));
    if (sc->kind == SH_SCENE_CONE) {
        root = cli_put(root, "occluder_angle", json_real(cli_angle_out(sc->cone_angle, a->degrees)));
        root = cli_put(root, "wobble", json_real(sc->wobble));
    }
    if (!midrange) root = cli_put(root, "cone_family_angle", json_real(cli_angle_out(w->fam_cone, a->degrees)));
    if (!midrange || w->light_angles) root = cli_put(root, "unit", json_string(cli_angle_unit(a->degrees)));
    if (midrange) {
        const char *env = a->env.probe ? a->env.probe : a->env.light ? a->env.light : "lobes";
        root = cli_put(root, "environment", json_string(env));
        root = cli_put(root, "nodes", json_integer(a->nodes));
        root = cli_put(root, "dir_x", json_real(w->unit[0]));
        root = cli_put(root, "dir_y", json_real(w->unit[1]));
        root = cli_put(root, "dir_z", json_real(w->unit[2]));
        root = cli_put(root, "rotation_method", json_string(w->tilted ? sh_rot_method_name(sc->rotation) : "none"));
    }
    return cli_put(root, "rows", rows);
}

static int run(int argc, char **argv)
{
    scale_scene_args a;
    memset(&a, 0, sizeof a);
    cli_parsed seen;
    int rc = cli_args_parse(&scale_scene_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    scale_work w;
    memset(&w, 0, sizeof w);
    if ((rc = validate(&a, &seen, &w))) return rc;
    rc = environment(&a, &w);
    if (!rc) rc = families(&a, &seen, &w);
    json_t *rows = rc ? NULL : error_rows(&a, &w, &rc);
    if (!rc) rc = cli_emit(build_result(&a, &w, rows), (cli_format)a.fmt);
    sh_image_free(&w.img);
    return rc;
}

const cli_command cmd_scale_scene = {"scale-scene", run, "SH scaling against exact scenes (occluders, mid-range light)", &scale_scene_decl};
