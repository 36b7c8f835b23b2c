/* cmd_scale_scene.c — `shlab scale-scene`: SH scaling against ground truth
 * in the scenes of scale_scene.c (Wang et al. 2006, Sec. 3). */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_scale_scene;

#define SCENE_MAX_ORDER 16
#define SCENE_MAX_K 64
#define SCENE_DEFAULT_NODES 200

static const char help[] =
    "Usage: shlab scale-scene --scene sphere|cone|midrange --order N --k LIST [OPTIONS]\n"
    "\n"
    "SH scaling against ground truth (Wang et al. 2006, Sec. 3).  The scene's\n"
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
    "\n"
    "  --scene S            sphere | cone | midrange\n"
    "  --order N            number of bands (1..16)\n"
    "  --k LIST             comma-separated k values (at most 64)\n"
    "  --family F           only this family (default: every applicable one)\n"
    "  --size X             sphere ρ/r or cone rim height h/r (default 0.5)\n"
    "  --wobble E           cone rim modulation, |E| < 1 (default 0.3)\n"
    "  --occluder-angle T   cone occluder half-angle in (0, π/2) (default π/4)\n"
    "  --cone-angle T       θ0 of the cone family (defaults above)\n"
    "  --light SPEC         midrange environment: lobes (default; two smooth\n"
    "                       non-zonal lobes) or an analytic light as in shlab project\n"
    "  --probe FILE         midrange environment from a lat-long EXR (luminance)\n"
    "  --nodes S            midrange quadrature θ nodes (default 200; 8..4096)\n"
    "  --dir X,Y,Z          midrange displacement direction (default 0,0,1;\n"
    "                       normalised; finite and non-zero)\n"
    "  --rotation-method M  midrange, DIR ≠ +z: exact rotation method of the\n"
    "                       rotate → scale → rotate back (default zxzxz; ivanic,\n"
    "                       choi, blanco, wigner, reference)\n"
    "  --degrees            angles in degrees: the options above, the angles in\n"
    "                       --light SPEC, and the printed angles\n"
    "  --convention cs|nocs basis of the projections\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"scene\",\"order\",\"convention\",\"method\",[sphere, cone: \"size\",\n"
    "       cone: \"occluder_angle\",\"wobble\"; \"cone_family_angle\",\"unit\"],\n"
    "       [midrange: [\"unit\" (a SPEC with angles)],\"environment\",\"nodes\",\n"
    "       \"dir_x\",\"dir_y\",\"dir_z\" (unit vector),\n"
    "       \"rotation_method\" (\"none\" for +z)],\"rows\":[{\"k\",\"family\",\"energy\",\n"
    "       \"err_scaled\",\"err_geom\",\"err_trunc\"}]}\n";

static int run(int argc, char **argv)
{
    enum { O_SCENE = 0x201, O_K, O_FAMILY, O_SIZE, O_WOBBLE, O_OCC, O_CONE, O_LIGHT, O_PROBE, O_NODES, O_DIR, O_ROTM };
    static const struct option opts[] = {
        CLI_LONGOPTS_BASE,
        CLI_LONGOPT_ORDER,
        {"scene", required_argument, 0, O_SCENE},
        {"k", required_argument, 0, O_K},
        {"family", required_argument, 0, O_FAMILY},
        {"size", required_argument, 0, O_SIZE},
        {"wobble", required_argument, 0, O_WOBBLE},
        {"occluder-angle", required_argument, 0, O_OCC},
        {"cone-angle", required_argument, 0, O_CONE},
        {"light", required_argument, 0, O_LIGHT},
        {"probe", required_argument, 0, O_PROBE},
        {"nodes", required_argument, 0, O_NODES},
        {"dir", required_argument, 0, O_DIR},
        {"rotation-method", required_argument, 0, O_ROTM},
        CLI_LONGOPT_DEGREES,
        CLI_LONGOPT_CONVENTION,
        {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = SCENE_MAX_ORDER;
    const char *scene = NULL, *klist = NULL, *family = NULL, *light = NULL, *probe = NULL;
    double size = 0.5, wobble = 0.3, occ = -1, cone = -1;
    int nodes = SCENE_DEFAULT_NODES, have_dir = 0;
    double dir[3] = {0.0, 0.0, 0.0};
    const char *rotm = NULL;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case O_SCENE: scene = optarg; break;
        case O_K: klist = optarg; break;
        case O_FAMILY: family = optarg; break;
        case O_SIZE: if (cli_double("--size", optarg, &size)) return CLI_EXIT_USAGE; break;
        case O_WOBBLE: if (cli_double("--wobble", optarg, &wobble)) return CLI_EXIT_USAGE; break;
        case O_OCC: if (cli_double("--occluder-angle", optarg, &occ)) return CLI_EXIT_USAGE; break;
        case O_CONE: if (cli_double("--cone-angle", optarg, &cone)) return CLI_EXIT_USAGE; break;
        case O_LIGHT: light = optarg; break;
        case O_PROBE: probe = optarg; break;
        case O_NODES: if (cli_int("--nodes", optarg, &nodes)) return CLI_EXIT_USAGE; break;
        case O_DIR: if (cli_vec3("--dir", optarg, dir)) return CLI_EXIT_USAGE; have_dir = 1; break;
        case O_ROTM: rotm = optarg; break;
        default: {
            const int r = cli_common_opt(&cmd_scale_scene, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    if (optind < argc) return cli_fail("scale-scene: unexpected argument '%s'", argv[optind]);
    if (!scene) return cli_fail("scale-scene: --scene is required (sphere, cone, midrange)");
    sh_scale_scene sc;
    memset(&sc, 0, sizeof sc);
    if (sh_scale_scene_parse(scene, &sc.kind)) return cli_fail("--scene: %s", sh_last_error());
    const int order = com.order;
    if (!order) return cli_fail("scale-scene: --order is required");
    if (!klist) return cli_fail("scale-scene: --k is required (comma-separated list)");
    const double deg = com.degrees ? M_PI / 180.0 : 1.0;
    const int midrange = sc.kind == SH_SCENE_MIDRANGE;
    if (cli_applies("scale-scene", occ >= 0, "--occluder-angle", sc.kind == SH_SCENE_CONE, "--scene cone") ||
        cli_applies("scale-scene", light != NULL, "--light", midrange, "--scene midrange") ||
        cli_applies("scale-scene", probe != NULL, "--probe", midrange, "--scene midrange"))
        return CLI_EXIT_USAGE;
    if (light && probe) return cli_fail("scale-scene: give --light or --probe, not both");
    if (cli_applies("scale-scene", have_dir, "--dir", midrange, "--scene midrange (occluders lie along +z)") ||
        cli_applies("scale-scene", rotm != NULL, "--rotation-method", midrange, "--scene midrange (occluders lie along +z)"))
        return CLI_EXIT_USAGE;
    double unit[3] = {0.0, 0.0, 1.0};
    if (have_dir) {
        if (sh_scale_axis_unit(dir, unit)) return cli_fail("--dir: %s", sh_last_error());
        memcpy(sc.dir, unit, sizeof unit);
    }
    sc.rotation = SH_ROT_ZXZXZ;
    if (rotm) {
        if (cli_method(rotm, &sc.rotation)) return CLI_EXIT_USAGE;
        if (!sh_rot_method_is_exact(sc.rotation) || sc.rotation == SH_ROT_Z)
            return cli_fail("--rotation-method: %s is not an exact general rotation (zxzxz, ivanic, choi, blanco, "
                            "wigner, reference)", rotm);
        if (!sh_rot_method_max_order(sc.rotation))
            return cli_fail("--rotation-method: %s is not built in", rotm);
        if (order > sh_rot_method_max_order(sc.rotation))
            return cli_fail("--rotation-method: %s accepts orders up to %d", rotm, sh_rot_method_max_order(sc.rotation));
    }
    const int tilted = !sh_scale_axis_is_z(unit);
    sc.size = size;
    sc.wobble = sc.kind == SH_SCENE_CONE ? wobble : 0.0;
    sc.cone_angle = occ >= 0 ? occ * deg : M_PI / 4.0;
    sc.nodes = nodes;
    sh_light L;
    int light_angles = 0;
    sh_image img = {0};
    if (sc.kind == SH_SCENE_MIDRANGE) {
        if (probe) {
            if (cli_input("probe", probe)) return CLI_EXIT_USAGE;
            if (sh_exr_read(probe, &img, NULL)) return cli_fail("--probe: %s", sh_last_error());
            if (img.width != 2 * img.height) {
                sh_image_free(&img);
                return cli_fail("--probe: %s is %dx%d, not a 2:1 lat-long image", probe, img.width, img.height);
            }
            sc.probe = &img;
        } else if (light && strcmp(light, "lobes")) {
            if (sh_light_parse(light, com.degrees, &L)) return cli_fail("--light: %s", sh_last_error());
            cli_light_warn("scale-scene", &L, com.degrees);
            light_angles = cli_light_has_angles(&L);
            sc.light = sh_light_fn;
            sc.light_ctx = &L;
        } else {
            sc.light = sh_scale_scene_lobes_fn;
        }
    }
    double *ks = NULL;
    int nk = 0;
    int rc = CLI_EXIT_OK;
    if (cli_doubles("--k", klist, &ks, &nk)) { sh_image_free(&img); return CLI_EXIT_USAGE; }
    if (nk < 1 || nk > SCENE_MAX_K) { rc = cli_fail("--k: %d values (1..%d)", nk, SCENE_MAX_K); goto out; }
    for (int q = 0; q < nk; q++)
        if (sh_scale_scene_check(&sc, ks[q])) { rc = cli_fail("scale-scene: %s", sh_last_error()); goto out; }
    if (sh_scale_scene_check(&sc, sh_scale_scene_k_ref(&sc))) { rc = cli_fail("scale-scene: %s", sh_last_error()); goto out; }
    sh_scale_family fams[2];
    int nf = 0;
    if (family) {
        if (sh_scale_family_parse(family, &fams[0])) { rc = cli_fail("--family: %s", sh_last_error()); goto out; }
        nf = 1;
        if ((fams[0] == SH_SCALE_MIDRANGE) != (sc.kind == SH_SCENE_MIDRANGE)) {
            rc = cli_fail("scale-scene: family %s does not apply to the %s scene (%s)", family, scene,
                          sc.kind == SH_SCENE_MIDRANGE ? "midrange only" : "linear or cone");
            goto out;
        }
    } else if (sc.kind == SH_SCENE_MIDRANGE) {
        fams[nf++] = SH_SCALE_MIDRANGE;
    } else {
        fams[nf++] = SH_SCALE_LINEAR;
        fams[nf++] = SH_SCALE_CONE;
    }
    double fam_cone = cone >= 0 ? cone * deg : sc.kind == SH_SCENE_SPHERE ? acos(sc.size) : sc.cone_angle;
    if (cone >= 0 && !(fam_cone > 0 && fam_cone < M_PI)) { rc = cli_fail("--cone-angle: %g is outside (0, pi)", cone); goto out; }

    const int n = sh_ncoeff(order);
    double *Sr = malloc(sizeof(double) * (size_t)n);
    if (!Sr) { rc = cli_fail("out of memory"); goto out; }
    int st = sh_scale_scene_exact(&sc, order, com.conv, sh_scale_scene_k_ref(&sc), Sr);
    json_t *rows = json_array();
    for (int q = 0; q < nk && !st && rows; q++) {
        if (nk > 4) fprintf(stderr, "  scale-scene: k = %g (%d of %d)\n", ks[q], q + 1, nk);
        for (int f = 0; f < nf && !st; f++)
            for (int e = 0; e < 2 && !st; e++) {
                sh_scaling s = {fams[f], ks[q], fams[f] == SH_SCALE_CONE ? fam_cone : 0.0, e};
                sh_scale_scene_err er;
                st = sh_scale_scene_errors(&sc, order, com.conv, &s, ks[q], Sr, &er, NULL);
                if (st) break;
                json_t *r = json_object();
                r = cli_put(r, "k", json_real(ks[q]));
                r = cli_put(r, "family", json_string(sh_scale_family_name(fams[f])));
                r = cli_put(r, "energy", json_boolean(e));
                r = cli_put(r, "err_scaled", json_real(er.err_scaled));
                r = cli_put(r, "err_geom", json_real(er.err_geom));
                r = cli_put(r, "err_trunc", json_real(er.err_trunc));
                if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; break; }
            }
    }
    free(Sr);
    if (st) { json_decref(rows); rc = cli_fail("scale-scene: %s", sh_last_error()); goto out; }
    json_t *root = json_object();
    root = cli_put(root, "scene", json_string(sh_scale_scene_name(sc.kind)));
    root = cli_put(root, "order", json_integer(order));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "method", json_string(sc.kind == SH_SCENE_SPHERE ? "closed-form" :
                                               sc.kind == SH_SCENE_CONE ? "region-quadrature" : "quad"));
    if (sc.kind != SH_SCENE_MIDRANGE) root = cli_put(root, "size", json_real(sc.size));
    if (sc.kind == SH_SCENE_CONE) {
        root = cli_put(root, "occluder_angle", json_real(cli_angle_out(sc.cone_angle, com.degrees)));
        root = cli_put(root, "wobble", json_real(sc.wobble));
    }
    if (sc.kind != SH_SCENE_MIDRANGE) root = cli_put(root, "cone_family_angle", json_real(cli_angle_out(fam_cone, com.degrees)));
    if (sc.kind != SH_SCENE_MIDRANGE || light_angles)
        root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
    if (sc.kind == SH_SCENE_MIDRANGE) {
        root = cli_put(root, "environment", json_string(probe ? probe : light ? light : "lobes"));
        root = cli_put(root, "nodes", json_integer(nodes));
        root = cli_put(root, "dir_x", json_real(unit[0]));
        root = cli_put(root, "dir_y", json_real(unit[1]));
        root = cli_put(root, "dir_z", json_real(unit[2]));
        root = cli_put(root, "rotation_method", json_string(tilted ? sh_rot_method_name(sc.rotation) : "none"));
    }
    root = cli_put(root, "rows", rows);
    rc = cli_emit(root, com.fmt);
out:
    free(ks);
    sh_image_free(&img);
    return rc;
}

const cli_command cmd_scale_scene = {"scale-scene", run, "SH scaling against exact scenes (occluders, mid-range light)",
                                     help, NULL};
