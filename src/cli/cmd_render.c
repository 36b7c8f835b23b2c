/* cmd_render.c — `shlab render`: a picture of a scene shaded by SH lighting
 * through Green's transfer (camera rays through Embree, vertex colours
 * interpolated), and optionally the error image against the reference. */
#include "cli_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_render;

typedef struct {
    cli_scene_input in;
    cli_picture_args pic;
    cli_reference_args ref;
    cli_rotation_args rot;
    sh_transfer_kind kind;
    sh_rot_method method; /* SH_ROT_AUTO: not given (ivanic) */
    int order, degrees, fmt;
    const char *out, *png, *eout, *epng;
    double exposure, fov; /* exposure 0: from the shading */
} render_args;

static const cli_opt render_opts[] = {
    CLI_STRING(render_args, out, "out", "FILE", "EXR of the shaded scene (required)"),
    CLI_STRING(render_args, png, "png", "FILE", "PNG of the same"),
    CLI_REAL(render_args, exposure, "exposure", "X", 0, INFINITY, CLI_LO_OPEN, NULL,
             "PNG scale (default: 0.9 / the 99th percentile of B_Y)"),
    CLI_STRING(render_args, eout, "error-out", "FILE", "EXR of |B_Y − ref|"),
    CLI_STRING(render_args, epng, "error-png", "FILE", "false-colour PNG of |B_Y − ref| / RMS(ref)"),
    CLI_SCENE_ORDER(render_args, order, CLI_SCENE_MAX_ORDER, "4", "number of bands"),
    CLI_CUSTOM(render_args, kind, "transfer", "K", cli_parse_transfer_kind, "shadowed",
               "unshadowed | shadowed | interreflected"),
    CLI_CUSTOM(render_args, method, "method", "M", cli_parse_method, "auto",
               "rotation method for the lighting (default ivanic;\ntaylor1, taylor1.5, taylor2 the approximations)"),
    CLI_REAL(render_args, fov, "fov", "DEG", 1, 170, CLI_LO_OPEN | CLI_HI_OPEN, "35",
             "vertical field of view, in degrees"),
    CLI_DEGREES(render_args, degrees, "rotation angles (and --light angles) in degrees"),
    CLI_FORMAT(render_args, fmt),
    CLI_GROUP(render_args, in.scene, cli_scene_opts),
    CLI_GROUP(render_args, in.env, cli_env_opts),
    CLI_GROUP(render_args, in.rays, cli_rays_opts),
    CLI_GROUP(render_args, pic, cli_picture_opts),
    CLI_GROUP(render_args, ref, cli_reference_opts),
    CLI_DEFAULT("ref-samples", "8192"),
    CLI_DEFAULT("replications", "2"),
    CLI_GROUP(render_args, rot, cli_rotation_opts),
    CLI_END,
};

static const cli_cmd render_decl = {
    .name = "render",
    .usage = "render (--mesh FILE | --scene SPEC) (--probe FILE | --light SPEC)\n"
             "                    --out FILE.exr [OPTIONS]",
    .about = "Shade every vertex with SH lighting, B = Σ_{i<n²} L_i t_i (each colour\n"
             "channel; t the transfer of --transfer), and render: one camera ray per\n"
             "pixel through Embree, the three vertex colours of the triangle met\n"
             "interpolated barycentrically, the environment itself behind.  Written as\n"
             "a float EXR (linear) and, with --png, an 8-bit sRGB PNG (× --exposure).\n"
             "With --error-out/--error-png the reference (direct integration of the\n"
             "environment with ray-cast visibility, as `shlab scene-plan`; shadowed\n"
             "direct light) is computed at every vertex and |B_Y − ref| (luminance)\n"
             "rendered: the EXR holds the absolute error, the PNG a false-colour map\n"
             "(black 0 → blue → red → yellow → white at --error-max) of the error in\n"
             "units of the RMS reference radiance; --error-max is by default the\n"
             "largest error.  The lighting may be rotated first (--euler, --quat,\n"
             "--matrix, --axis/--angle as `shlab rotate`; --method).\n",
    .opts = render_opts,
    .notes = "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"order\",\"transfer\",\"method\",\n"
             "       \"exr\",\"png\",\"width\",\"height\",\"exposure\",\"transfer_seconds\",\n"
             "       [\"error\":{\"exr\",\"png\",\"rel_l2\",\"rel_max\",\"ref_l2\",\"error_max\"}]}\n",
};

/* The run: the rotation of the lighting, the scene, the shading, the images. */
typedef struct {
    const render_args *a;
    sh_rotation rot;
    int have_rot;
    sh_rot_method method;
    unsigned long ref_seed; /* the reference's: --seed, or 0 when not given (the default seeds the transfer only) */
    cli_scene_session s;
    int nv, n2;
    double *T, *L, *col, *Y; /* transfer, lighting (Y, R, G, B), RGB per vertex, Y R G B shading */
    double exposure, emax;
    sh_transfer_stats ts;
    sh_camera cam;
    sh_image img, eimg, cm; /* the picture; the absolute error; its false colour */
    json_t *ej;             /* the error's summary */
} render_work;

/* The options that go together, and the rotation of the lighting. */
static int validate(render_args *a, const cli_parsed *seen, render_work *w)
{
    if (!a->out) return cli_fail("render: --out FILE.exr is required");
    if (cli_scene_applies("render", seen, "exposure", a->png != NULL, "--png (it scales the PNG)") ||
        cli_scene_applies("render", seen, "error-max", a->epng != NULL, "--error-png") ||
        cli_scene_applies("render", seen, "ref-samples replications", a->eout || a->epng,
                          "--error-out and --error-png (the reference)"))
        return CLI_EXIT_USAGE;
    int rc = cli_rotation_finish("render", &a->rot, a->degrees, 1, &w->have_rot, &w->rot);
    if (rc) return rc;
    if (cli_applies("render", a->method != SH_ROT_AUTO, "--method", w->have_rot,
                    "a rotation of the lighting (--euler, --quat, --matrix, --axis/--angle)"))
        return CLI_EXIT_USAGE;
    w->method = a->method == SH_ROT_AUTO ? SH_ROT_IVANIC : a->method;
    if (w->have_rot && a->order > sh_rot_method_max_order(w->method))
        return cli_fail("render: --method %s accepts orders up to %d", sh_rot_method_name(w->method),
                        sh_rot_method_max_order(w->method));
    if ((a->eout || a->epng) && a->kind == SH_TRANSFER_INTERREFLECTED)
        return cli_fail("render: the reference is of direct light; error images need --transfer shadowed or unshadowed");
    w->ref_seed = cli_given(seen, "seed") ? (unsigned long)a->in.rays.seed : 0;
    return 0;
}

/* B = Σ L_i t_i per vertex in Y, R, G, B (the lighting rotated first), and
 * the picture of R, G, B. */
static int shade(render_work *w)
{
    const render_args *a = w->a;
    const int nv = w->nv, n2 = w->n2, order = a->order;
    w->T = malloc(sizeof(double) * (size_t)nv * n2);
    w->L = malloc(sizeof(double) * 4 * n2);
    w->col = malloc(sizeof(double) * 3 * (size_t)nv);
    w->Y = malloc(sizeof(double) * (size_t)nv * 4);
    if (!w->T || !w->L || !w->col || !w->Y) return sh_error(SH_ENOMEM, "out of memory");
    const sh_transfer_opts to = cli_scene_transfer_opts(&w->s, &a->in.rays, a->kind, order);
    int e = sh_transfer(w->s.scene, &to, w->T, &w->ts);
    if (!e) e = sh_env_project(w->s.env, order, SH_CS, w->L);
    if (!e && w->have_rot) e = sh_scene_rotate_coeffs(order, SH_CS, w->method, &w->rot, 4, w->L, w->L);
    for (int c = 0; c < 4 && !e; c++) {
        double *B = w->Y + (size_t)c * nv;
        e = sh_shade(nv, order, w->T, order, w->L + (size_t)c * n2, B);
        if (c > 0)
            for (int v = 0; v < nv; v++) w->col[3 * v + c - 1] = B[v];
    }
    w->exposure = a->exposure;
    if (!e && w->exposure == 0) e = cli_scene_exposure(w->Y, nv, &w->exposure);
    if (!e) e = sh_camera_frame(&w->s.mesh, a->pic.view, a->fov, a->pic.width, a->pic.height, &w->cam);
    if (!e) e = sh_render(w->s.scene, &w->cam, 3, w->col, w->s.env, w->s.threads, &w->img);
    return e;
}

/* The reference at every vertex, |B_Y − ref| rendered (the EXR) and in
 * units of RMS(ref) in false colour (the PNG); the summary in w->ej. */
static int error_image(render_work *w)
{
    const render_args *a = w->a;
    const int nv = w->nv, W = a->pic.width, H = a->pic.height;
    sh_reference_opts ro = cli_scene_reference_opts(&w->s, &a->in.rays, &a->ref);
    ro.seed = w->ref_seed;
    double *ref = malloc(sizeof(double) * (size_t)nv), *se = malloc(sizeof(double) * (size_t)nv);
    sh_image rel = {0};
    sh_shade_err er;
    int e = (!ref || !se) ? sh_error(SH_ENOMEM, "out of memory") : SH_OK;
    if (!e) e = sh_shade_reference(w->s.scene, w->s.env, w->have_rot ? &w->rot : NULL, NULL, nv, &ro, ref, se, NULL);
    if (!e) e = sh_shade_error(nv, w->Y, ref, se, &er);
    if (!e) {
        double r2 = 0, mx = 0;
        for (int v = 0; v < nv; v++) r2 += ref[v] * ref[v];
        const double rms = sqrt(r2 / nv);
        for (int v = 0; v < nv; v++) {
            ref[v] = fabs(w->Y[v] - ref[v]); /* the absolute error, rendered */
            mx = fmax(mx, ref[v] / rms);
        }
        w->emax = a->pic.error_max > 0 ? a->pic.error_max : mx > 0 ? mx : 1;
        e = sh_render(w->s.scene, &w->cam, 1, ref, NULL, w->s.threads, &w->eimg);
        if (!e) {
            rel = w->eimg;
            rel.data = malloc(sizeof(float) * (size_t)W * H);
            if (!rel.data) e = sh_error(SH_ENOMEM, "out of memory");
            for (size_t k = 0; !e && k < (size_t)W * H; k++) rel.data[k] = (float)(w->eimg.data[k] / rms);
            if (!e) e = sh_image_colormap(&rel, w->emax, &w->cm);
            free(rel.data);
        }
        json_t *ej = json_object();
        ej = cli_put(ej, "exr", a->eout ? json_string(a->eout) : json_null());
        ej = cli_put(ej, "png", a->epng ? json_string(a->epng) : json_null());
        ej = cli_put(ej, "rel_l2", json_real(er.rel_l2));
        ej = cli_put(ej, "rel_max", json_real(er.rel_max));
        ej = cli_put(ej, "ref_l2", json_real(er.ref_l2));
        ej = cli_put(ej, "error_max", json_real(w->emax));
        w->ej = ej;
    }
    free(ref);
    free(se);
    return e;
}

/* The files, last: a failed computation writes none (the temporaries of
 * the session's outputs, renamed by cli_emit). */
static int write_files(const render_work *w)
{
    const render_args *a = w->a;
    int e = sh_exr_write(w->s.tmp[0], &w->img);
    if (!e && a->png) e = sh_png_write(w->s.tmp[1], &w->img, w->exposure);
    if (!e && a->eout) e = sh_exr_write(w->s.tmp[2], &w->eimg);
    if (!e && a->epng) e = sh_png_write(w->s.tmp[3], &w->cm, 1);
    return e;
}

static json_t *build_result(render_work *w)
{
    const render_args *a = w->a;
    json_t *root = cli_scene_session_result(&w->s);
    root = cli_put(root, "order", json_integer(a->order));
    root = cli_put(root, "transfer", json_string(sh_transfer_kind_name(a->kind)));
    root = cli_put(root, "method", w->have_rot ? json_string(sh_rot_method_name(w->method)) : json_null());
    root = cli_put(root, "exr", json_string(a->out));
    root = cli_put(root, "png", a->png ? json_string(a->png) : json_null());
    root = cli_put(root, "width", json_integer(a->pic.width));
    root = cli_put(root, "height", json_integer(a->pic.height));
    root = cli_put(root, "exposure", json_real(w->exposure));
    root = cli_put(root, "transfer_seconds", json_real(w->ts.seconds));
    if (w->ej) {
        root = cli_put(root, "error", w->ej);
        w->ej = NULL;
    }
    return root;
}

static void work_free(render_work *w)
{
    json_decref(w->ej);
    sh_image_free(&w->img);
    sh_image_free(&w->eimg);
    sh_image_free(&w->cm);
    free(w->T); free(w->L); free(w->col); free(w->Y);
    cli_scene_session_close(&w->s);
}

static int run(int argc, char **argv)
{
    render_args a;
    memset(&a, 0, sizeof a);
    cli_parsed seen;
    int rc = cli_args_parse(&render_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    render_work w = {.a = &a, .n2 = a.order * a.order};
    if ((rc = validate(&a, &seen, &w))) return rc;

    const char *outputs[4] = {a.out, a.png, a.eout, a.epng};
    if ((rc = cli_scene_session_open("render", &a.in, a.degrees, CLI_SCENE_NEEDS_ENV, outputs, 4, &w.s))) return rc;
    w.nv = w.s.mesh.nvert;
    int e = shade(&w);
    if (!e && (a.eout || a.epng)) e = error_image(&w);
    if (!e) e = write_files(&w);
    json_t *root = e ? NULL : build_result(&w);
    work_free(&w);
    if (e) return cli_fail_status(e);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_render = {"render", run, "picture of a scene under SH lighting (EXR, PNG) and its error image", &render_decl};
