/* cmd_render.c — `shlab render`: a picture of a scene shaded by SH lighting
 * through Green's transfer (camera rays through Embree, vertex colours
 * interpolated), and optionally the error image against the reference. */
#include "cli_scene.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_render;

static const char help[] =
    "Usage: shlab render (--mesh FILE | --scene SPEC) (--probe FILE | --light SPEC)\n"
    "                    --out FILE.exr [OPTIONS]\n"
    "\n"
    "Shade every vertex with SH lighting, B = Σ_{i<n²} L_i t_i (each colour\n"
    "channel; t the transfer of --transfer), and render: one camera ray per\n"
    "pixel through Embree, the three vertex colours of the triangle met\n"
    "interpolated barycentrically, the environment itself behind.  Written as\n"
    "a float EXR (linear) and, with --png, an 8-bit sRGB PNG (× --exposure).\n"
    "With --error-out/--error-png the reference (direct integration of the\n"
    "environment with ray-cast visibility, as `shlab scene-plan`; shadowed\n"
    "direct light) is computed at every vertex and |B_Y − ref| (luminance)\n"
    "rendered: the EXR holds the absolute error, the PNG a false-colour map\n"
    "(black 0 → blue → red → yellow → white at --error-max) of the error in\n"
    "units of the RMS reference radiance.\n"
    "\n"
    CLI_SCENE_HELP
    CLI_ENV_HELP
    "  --order N            number of bands (default 4; ≤ 32)\n"
    "  --transfer K         unshadowed | shadowed (default) | interreflected\n"
    "  --rays R             transfer rays per vertex (default 1024)\n"
    "  --albedo A           ρ (default 0.8)\n"
    "  --euler A,B,G        rotate the lighting, R = Rz(A)Ry(B)Rz(G) (also --quat,\n"
    "                       --matrix, --axis/--angle as `shlab rotate`)\n"
    "  --method M           rotation method for the lighting (default ivanic;\n"
    "                       taylor1, taylor1.5, taylor2 the approximations)\n"
    "  --out FILE           EXR of the shaded scene\n"
    "  --png FILE           PNG of the same\n"
    "  --exposure X         PNG scale (default: 0.9 / the 99th percentile of B_Y)\n"
    "  --error-out FILE     EXR of |B_Y − ref|\n"
    "  --error-png FILE     false-colour PNG of |B_Y − ref| / RMS(ref)\n"
    "  --error-max V        top of the false-colour scale (default: the largest)\n"
    "  --ref-samples S      reference blocks per replication (default 8192)\n"
    "  --replications R     reference replications (default 2)\n"
    "  --view X,Y,Z         camera direction from the scene's centre (default 1,-1.4,0.9)\n"
    "  --width W, --height H  pixels (default 640 × 480)\n"
    "  --fov DEG            vertical field of view (default 35)\n"
    "  --seed K             jitter seed (default 1)\n"
    "  --degrees            rotation angles in degrees\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"order\",\"transfer\",\"method\",\n"
    "       \"exr\",\"png\",\"width\",\"height\",\"exposure\",\"transfer_seconds\",\n"
    "       [\"error\":{\"exr\",\"png\",\"rel_l2\",\"rel_max\",\"ref_l2\",\"error_max\"}]}\n";

static int run(int argc, char **argv)
{
    enum { O_KIND = 0x301, O_RAYS, O_ALBEDO, O_OUT, O_PNG, O_EXPO, O_EOUT, O_EPNG, O_FOV, O_SEED, O_QUIET };
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPTS_SCENE,
                                         CLI_LONGOPTS_ENV,
                                         CLI_LONGOPTS_ROTATION,
                                         CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPTS_PICTURE,
                                         {"transfer", required_argument, 0, O_KIND},
                                         {"rays", required_argument, 0, O_RAYS},
                                         {"albedo", required_argument, 0, O_ALBEDO},
                                         {"out", required_argument, 0, O_OUT},
                                         {"png", required_argument, 0, O_PNG},
                                         {"exposure", required_argument, 0, O_EXPO},
                                         {"error-out", required_argument, 0, O_EOUT},
                                         {"error-png", required_argument, 0, O_EPNG},
                                         {"fov", required_argument, 0, O_FOV},
                                         {"seed", required_argument, 0, O_SEED},
                                         {"quiet", no_argument, 0, O_QUIET},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = CLI_SCENE_MAX_ORDER;
    cli_scene_args sa = {0};
    cli_rotation_args ra = {0};
    sh_transfer_opts to = {0};
    to.kind = SH_TRANSFER_SHADOWED;
    to.albedo = 0.8;
    to.seed = 1;
    sh_reference_opts ro = {0};
    cli_picture_args pa = CLI_PICTURE_DEFAULTS; /* render's own defaults: */
    pa.ref_samples = 8192;
    pa.replications = 2;
    pa.error_max = 0; /* the largest error */
    const char *out = NULL, *png = NULL, *eout = NULL, *epng = NULL;
    double exposure = 0, fov = 35;
    int quiet = 0, have_exposure = 0;
    long seed = 1;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int e = cli_scene_opt("render", o, optarg, &sa);
        if (e < 0) e = cli_picture_opt(o, optarg, &pa);
        if (e > 0) return e;
        if (e == 0) continue;
        e = cli_rotation_opt("render", o, optarg, &ra);
        if (e > 0) return e;
        if (e == 0) continue;
        switch (o) {
        case O_KIND:
            if (sh_transfer_kind_parse(optarg, &to.kind)) return cli_fail("--transfer: %s", sh_last_error());
            break;
        case O_RAYS:
            if (cli_long("--rays", optarg, &to.rays)) return CLI_EXIT_USAGE;
            if (to.rays < 1 || to.rays > 1L << 20) return cli_fail("--rays: out of range 1..1048576");
            break;
        case O_ALBEDO:
            if (cli_double("--albedo", optarg, &to.albedo)) return CLI_EXIT_USAGE;
            if (!(to.albedo > 0 && to.albedo <= 1)) return cli_fail("--albedo: must be in (0, 1]");
            break;
        case O_OUT: out = optarg; break;
        case O_PNG: png = optarg; break;
        case O_EOUT: eout = optarg; break;
        case O_EPNG: epng = optarg; break;
        case O_EXPO:
            if (cli_double("--exposure", optarg, &exposure)) return CLI_EXIT_USAGE;
            if (!(exposure > 0)) return cli_fail("--exposure: must be > 0");
            have_exposure = 1;
            break;
        case O_FOV:
            if (cli_double("--fov", optarg, &fov)) return CLI_EXIT_USAGE;
            if (!(fov > 1 && fov < 170)) return cli_fail("--fov: must be in (1, 170) degrees");
            break;
        case O_SEED:
            if (cli_long("--seed", optarg, &seed)) return CLI_EXIT_USAGE;
            if (seed < 0) return cli_fail("--seed: must be >= 0");
            to.seed = ro.seed = (unsigned long)seed;
            break;
        case O_QUIET: quiet = 1; break;
        default: {
            const int e2 = cli_common_opt(&cmd_render, o, argv, &com);
            if (e2 >= 0) return e2;
        }
        }
    }
    if (optind < argc) return cli_fail("render: unexpected argument '%s'", argv[optind]);
    if (!out) return cli_fail("render: --out FILE.exr is required");
    const int W = pa.width, H = pa.height;
    double emax = pa.error_max;
    ro.samples = pa.ref_samples;
    ro.replications = pa.replications;
    /* options that do not apply are refused, as transfer refuses them */
    if (cli_applies("render", have_exposure, "--exposure", png != NULL, "--png (it scales the PNG)") ||
        cli_picture_applies("render", &pa, CLI_PIC_EMAX, epng != NULL, "--error-png") ||
        cli_picture_applies("render", &pa, CLI_PIC_REFS | CLI_PIC_REPL, eout || epng,
                            "--error-out and --error-png (the reference)"))
        return CLI_EXIT_USAGE;
    to.order = com.order ? com.order : 4;
    int have_rot = 0;
    sh_rotation rot;
    int rc = cli_rotation_finish("render", &ra, com.degrees, 1, &have_rot, &rot);
    if (rc) return rc;
    if (cli_applies("render", com.have_method, "--method", have_rot, "a rotation of the lighting (--euler, --quat, --matrix, --axis/--angle)"))
        return CLI_EXIT_USAGE;
    const sh_rot_method method = com.have_method ? com.method : SH_ROT_IVANIC;
    if (have_rot && to.order > sh_rot_method_max_order(method))
        return cli_fail("render: --method %s accepts orders up to %d", sh_rot_method_name(method), sh_rot_method_max_order(method));
    if ((eout || epng) && to.kind == SH_TRANSFER_INTERREFLECTED)
        return cli_fail("render: the reference is of direct light; error images need --transfer shadowed or unshadowed");
    to.threads = ro.threads = sa.threads;
    ro.albedo = to.albedo;
    /* every output file is opened (as a temporary beside its target) before
     * any work, and renamed onto its target by cli_emit once the result is
     * on stdout: all of them or none, an existing file intact on any error */
    const char *paths[4] = {out, png, eout, epng}, *tmp[4] = {NULL, NULL, NULL, NULL};
    for (int k = 0; k < 4; k++)
        if (paths[k] && cli_out_open("render", paths[k], &tmp[k])) return CLI_EXIT_USAGE;

    sh_mesh m;
    sh_proc_scene ps;
    int is_proc;
    sh_scene *s;
    json_t *desc, *edesc;
    if ((rc = cli_scene_build("render", &sa, &m, &ps, &is_proc, &s, &desc))) return rc;
    sh_env *env;
    if ((rc = cli_env_build("render", &sa, com.degrees, 0, &env, &edesc))) {
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        return rc;
    }
    const int nv = m.nvert, n2 = to.order * to.order;
    double *T = malloc(sizeof(double) * (size_t)nv * n2), *L = malloc(sizeof(double) * 4 * n2);
    double *col = malloc(sizeof(double) * 3 * (size_t)nv), *Y = malloc(sizeof(double) * (size_t)nv * 4);
    double *ref = NULL, *se = NULL;
    sh_image img = {0}, eimg = {0}, cm = {0};
    json_t *root = NULL, *ej = NULL;
    int e = (!T || !L || !col || !Y) ? sh_error(SH_ENOMEM, "out of memory") : SH_OK;
    cli_progress prog;
    cli_progress_start(&prog, "render", quiet);
    to.progress = ro.progress = cli_progress_step;
    to.progress_ctx = ro.progress_ctx = &prog;
    sh_transfer_stats ts;
    if (!e) e = sh_transfer(s, &to, T, &ts);
    if (!e) e = sh_env_project(env, to.order, SH_CS, L);
    if (!e && have_rot) e = sh_scene_rotate_coeffs(to.order, SH_CS, method, &rot, 4, L, L);
    /* Y, R, G, B shading per vertex */
    for (int c = 0; c < 4 && !e; c++) {
        double *B = Y + (size_t)c * nv;
        e = sh_shade(nv, to.order, T, to.order, L + (size_t)c * n2, B);
        if (c > 0)
            for (int v = 0; v < nv; v++) col[3 * v + c - 1] = B[v];
    }
    if (!e && exposure == 0) {
        double *tmp = malloc(sizeof(double) * (size_t)nv);
        if (!tmp) e = sh_error(SH_ENOMEM, "out of memory");
        else {
            memcpy(tmp, Y, sizeof(double) * nv);
            qsort(tmp, (size_t)nv, sizeof(double), cli_cmp_double);
            const double p99 = tmp[(size_t)(0.99 * (nv - 1))];
            exposure = p99 > 0 ? 0.9 / p99 : 1;
            free(tmp);
        }
    }
    sh_camera cam;
    if (!e) e = sh_camera_frame(&m, pa.view, fov, W, H, &cam);
    if (!e) e = sh_render(s, &cam, 3, col, env, sa.threads, &img);
    if (!e && (eout || epng)) {
        ref = malloc(sizeof(double) * (size_t)nv);
        se = malloc(sizeof(double) * (size_t)nv);
        if (!ref || !se) e = sh_error(SH_ENOMEM, "out of memory");
        if (!e) e = sh_shade_reference(s, env, have_rot ? &rot : NULL, NULL, nv, &ro, ref, se, NULL);
        sh_shade_err er;
        if (!e) e = sh_shade_error(nv, Y, ref, se, &er);
        if (!e) {
            double r2 = 0, mx = 0;
            for (int v = 0; v < nv; v++) r2 += ref[v] * ref[v];
            const double rms = sqrt(r2 / nv);
            for (int v = 0; v < nv; v++) {
                ref[v] = fabs(Y[v] - ref[v]); /* the absolute error, rendered */
                mx = fmax(mx, ref[v] / rms);
            }
            if (emax == 0) emax = mx > 0 ? mx : 1;
            e = sh_render(s, &cam, 1, ref, NULL, sa.threads, &eimg);
            if (!e) {
                sh_image rel = eimg;
                rel.data = malloc(sizeof(float) * (size_t)W * H);
                if (!rel.data) e = sh_error(SH_ENOMEM, "out of memory");
                for (size_t k = 0; !e && k < (size_t)W * H; k++) rel.data[k] = (float)(eimg.data[k] / rms);
                if (!e) e = sh_image_colormap(&rel, emax, &cm);
                free(rel.data);
            }
            ej = json_object();
            ej = cli_put(ej, "exr", eout ? json_string(eout) : json_null());
            ej = cli_put(ej, "png", epng ? json_string(epng) : json_null());
            ej = cli_put(ej, "rel_l2", json_real(er.rel_l2));
            ej = cli_put(ej, "rel_max", json_real(er.rel_max));
            ej = cli_put(ej, "ref_l2", json_real(er.ref_l2));
            ej = cli_put(ej, "error_max", json_real(emax));
        }
    }
    /* files last, so that a failed computation writes none */
    if (!e) e = sh_exr_write(tmp[0], &img);
    if (!e && png) e = sh_png_write(tmp[1], &img, exposure);
    if (!e && eout) e = sh_exr_write(tmp[2], &eimg);
    if (!e && epng) e = sh_png_write(tmp[3], &cm, 1);
    if (!e) {
        root = json_object();
        root = cli_put(root, is_proc ? "scene" : "mesh", desc);
        desc = NULL;
        root = cli_put(root, "environment", edesc);
        edesc = NULL;
        root = cli_put(root, "order", json_integer(to.order));
        root = cli_put(root, "transfer", json_string(sh_transfer_kind_name(to.kind)));
        root = cli_put(root, "method", have_rot ? json_string(sh_rot_method_name(method)) : json_null());
        root = cli_put(root, "exr", json_string(out));
        root = cli_put(root, "png", png ? json_string(png) : json_null());
        root = cli_put(root, "width", json_integer(W));
        root = cli_put(root, "height", json_integer(H));
        root = cli_put(root, "exposure", json_real(exposure));
        root = cli_put(root, "transfer_seconds", json_real(ts.seconds));
        if (ej) { root = cli_put(root, "error", ej); ej = NULL; }
    }
    json_decref(ej);
    json_decref(desc);
    json_decref(edesc);
    sh_image_free(&img);
    sh_image_free(&eimg);
    sh_image_free(&cm);
    free(T); free(L); free(col); free(Y); free(ref); free(se);
    sh_env_free(env);
    sh_scene_free(s);
    sh_mesh_free(&m);
    if (e) {
        json_decref(root);
        return cli_fail_status(e);
    }
    return cli_emit(root, com.fmt);
}

const cli_command cmd_render = {"render", run, "picture of a scene under SH lighting (EXR, PNG) and its error image", help, NULL};
