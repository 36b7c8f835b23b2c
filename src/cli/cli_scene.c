/* cli_scene.c — the scene commands' shared options and their session
 * (cli_scene.h). */
#include "cli_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the groups ----------------------------------------------------------- */

static const char *const up_names[] = {"z", "y", NULL};

const cli_opt cli_scene_opts[] = {
    CLI_HEADING("The scene (one of --mesh and --scene):"),
    CLI_STRING(cli_scene_args, mesh, "mesh", "FILE", "a triangle mesh (PLY, OBJ, … read by assimp); z up"),
    CLI_STRING(cli_scene_args, scene, "scene", "SPEC",
               "a procedural scene with closed-form answers:\n"
               "  sphere-plane[:R,H]  sphere (R 0.5) at height H (1) over a plane\n"
               "  bowl                inside of the unit hemisphere, rim at z = 0\n"
               "  box-open[:A]        inside of a box with a hole (half-width A 0.25)\n"
               "  box-closed          the same box, closed"),
    CLI_INT(cli_scene_args, res, "res", "N", 1, 512, NULL, "tessellation of --scene (default: the scene's)"),
    CLI_CHOICE(cli_scene_args, up, "up", "z|y", up_names, "z", "the mesh file's up axis (y: turned to z up)"),
    CLI_FLAG(cli_scene_args, compute_normals, "compute-normals",
             "ignore the file's normals (area-weighted face normals instead)"),
    CLI_FLAG(cli_scene_args, allow_nonmanifold, "allow-nonmanifold",
             "report edges shared by > 2 triangles instead of refusing the mesh"),
    CLI_END,
};

const cli_opt cli_env_opts[] = {
    CLI_HEADING("The environment (one of --probe and --light):"),
    CLI_STRING(cli_env_args, probe, "probe", "FILE",
               "lat-long OpenEXR environment (e.g. data/probes/*.exr, `make probes`)"),
    CLI_STRING(cli_env_args, light, "light", "SPEC",
               "an analytic light instead (see `shlab project --help`; --degrees)"),
    CLI_END,
};

int cli_parse_transfer_kind(const char *opt, const char *s, void *field)
{
    if (sh_transfer_kind_parse(s, field)) return cli_fail("%s: %s", opt, sh_last_error());
    return 0;
}

int cli_parse_seed(const char *opt, const char *s, void *field)
{
    long v;
    if (cli_long(opt, s, &v)) return CLI_EXIT_USAGE;
    if (v < 0) return cli_fail("%s: must be >= 0", opt);
    *(long *)field = v;
    return 0;
}

const cli_opt cli_rays_opts[] = {
    CLI_HEADING("Rays:"),
    CLI_LONG(cli_rays_args, rays, "rays", "R", 1, 1L << 20, "1024", "rays per vertex"),
    CLI_REAL(cli_rays_args, albedo, "albedo", "A", 0, 1, CLI_LO_OPEN, "0.8", "ρ, the surfaces' albedo"),
    CLI_CUSTOM(cli_rays_args, seed, "seed", "K", cli_parse_seed, "1", "seed of the rays' jitter"),
    CLI_INT(cli_rays_args, threads, "threads", "T", 1, CLI_SCENE_MAX_THREADS, NULL, "threads (default: every CPU)"),
    CLI_FLAG(cli_rays_args, quiet, "quiet", "no progress on stderr"),
    CLI_END,
};

static int parse_view(const char *opt, const char *s, void *field)
{
    double *v = field;
    if (cli_vec3(opt, s, v)) return CLI_EXIT_USAGE;
    if (!(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] > 0)) return cli_fail("%s: must be a non-zero vector", opt);
    return 0;
}

const cli_opt cli_picture_opts[] = {
    CLI_HEADING("Pictures:"),
    CLI_CUSTOM(cli_picture_args, view, "view", "X,Y,Z", parse_view, "1,-1.4,0.9",
               "camera direction from the scene's centre"),
    CLI_INT(cli_picture_args, width, "width", "W", 8, 8192, "640", "pixels across"),
    CLI_INT(cli_picture_args, height, "height", "H", 8, 8192, "480", "pixels down"),
    CLI_REAL(cli_picture_args, error_max, "error-max", "V", 0, INFINITY, CLI_LO_OPEN, NULL,
             "top of the false-colour scale"),
    CLI_END,
};

const cli_opt cli_reference_opts[] = {
    CLI_HEADING("The reference (direct integration):"),
    CLI_LONG(cli_reference_args, samples, "ref-samples", "S", 16, 1L << 22, "16384",
             "reference blocks (rays) per replication"),
    CLI_INT(cli_reference_args, replications, "replications", "R", 2, 1000, "4", "reference replications"),
    CLI_END,
};

int cli_scene_applies(const char *cmd, const cli_parsed *seen, const char *names, int applies, const char *what)
{
    char name[64], opt[66];
    for (const char *p = names; *p;) {
        const size_t len = strcspn(p, " ");
        snprintf(name, sizeof name, "%.*s", (int)len, p);
        snprintf(opt, sizeof opt, "--%s", name);
        if (cli_applies(cmd, cli_given(seen, name), opt, applies, what)) return CLI_EXIT_USAGE;
        p += len;
        p += strspn(p, " ");
    }
    return 0;
}

/* ---- the session ------------------------------------------------------------ */

/* The mesh (exactly one of --mesh/--scene) and its Embree scene; s->desc
 * describes them. */
static int build_scene(cli_scene_session *s, const cli_scene_args *a, int threads)
{
    const char *cmd = s->cmd;
    if (!a->mesh == !a->scene) return cli_fail("%s: give exactly one of --mesh FILE and --scene SPEC", cmd);
    if (cli_applies(cmd, a->up, "--up y", !a->scene, "--mesh") ||
        cli_applies(cmd, a->compute_normals, "--compute-normals", !a->scene, "--mesh") ||
        cli_applies(cmd, a->allow_nonmanifold, "--allow-nonmanifold", !a->scene, "--mesh") ||
        cli_applies(cmd, a->res, "--res", !a->mesh, "--scene"))
        return CLI_EXIT_USAGE;
    const int flags = (a->up ? SH_MESH_Y_UP : 0) | (a->compute_normals ? SH_MESH_COMPUTE_NORMALS : 0) |
                      (a->allow_nonmanifold ? SH_MESH_ALLOW_NONMANIFOLD : 0);
    sh_mesh_report rep;
    memset(&rep, 0, sizeof rep);
    int st;
    if (a->scene) {
        if ((st = sh_proc_parse(a->scene, &s->proc))) return cli_fail("--scene: %s", sh_last_error());
        s->proc.res = a->res;
        if ((st = sh_mesh_procedural(&s->proc, &s->mesh))) return cli_fail_status(st);
        s->is_proc = 1;
    } else if (cli_input("mesh", a->mesh)) {
        return CLI_EXIT_USAGE;
    } else if ((st = sh_mesh_load(a->mesh, flags, &s->mesh, &rep))) {
        return cli_fail_status(st);
    }
    if ((st = sh_scene_create(&s->mesh, threads, &s->scene))) return cli_fail_status(st);
    json_t *d = json_object();
    d = cli_put(d, a->scene ? "scene" : "mesh", json_string(a->scene ? a->scene : a->mesh));
    d = cli_put(d, "vertices", json_integer(s->mesh.nvert));
    d = cli_put(d, "triangles", json_integer(s->mesh.ntri));
    if (a->mesh) {
        d = cli_put(d, "up", json_string(a->up ? "y" : "z"));
        d = cli_put(d, "normals_computed", json_boolean(rep.normals_computed));
        d = cli_put(d, "degenerate_removed", json_integer(rep.degenerate_removed));
        d = cli_put(d, "unused_removed", json_integer(rep.unused_removed));
        d = cli_put(d, "skipped_primitives", json_integer(rep.skipped_primitives));
        d = cli_put(d, "boundary_edges", json_integer(rep.boundary_edges));
        d = cli_put(d, "nonmanifold_edges", json_integer(rep.nonmanifold_edges));
    }
    d = cli_put(d, "diagonal", json_real(sh_scene_diag(s->scene)));
    if (!d) return cli_fail("out of memory");
    s->desc = d;
    return 0;
}

/* The environment (exactly one of --probe/--light, unless optional);
 * s->env_desc describes it. */
static int build_env(cli_scene_session *s, const cli_env_args *a, int degrees, int optional)
{
    const char *cmd = s->cmd;
    if (a->probe && a->light) return cli_fail("%s: give one of --probe FILE and --light SPEC", cmd);
    if (!a->probe && !a->light) {
        if (optional) return 0;
        return cli_fail("%s: an environment is needed: --probe FILE or --light SPEC", cmd);
    }
    int st;
    json_t *d = json_object();
    if (a->light) {
        sh_light L;
        if (sh_light_parse(a->light, degrees, &L)) { json_decref(d); return cli_fail("--light: %s", sh_last_error()); }
        if ((st = sh_env_from_light(&L, &s->env))) { json_decref(d); return cli_fail_status(st); }
        d = cli_put(d, "light", json_string(a->light));
    } else {
        sh_image img;
        if (cli_input("probe", a->probe)) { json_decref(d); return CLI_EXIT_USAGE; }
        if ((st = sh_exr_read(a->probe, &img, NULL))) { json_decref(d); return cli_fail_status(st); }
        st = sh_env_from_image(&img, &s->env);
        d = cli_put(d, "probe", json_string(a->probe));
        d = cli_put(d, "width", json_integer(img.width));
        d = cli_put(d, "height", json_integer(img.height));
        sh_image_free(&img);
        if (st) { json_decref(d); return cli_fail("%s: %s", a->probe, sh_last_error()); }
    }
    if (!d) return cli_fail("out of memory");
    s->env_desc = d;
    return 0;
}

int cli_scene_session_open(const char *cmd, const cli_scene_input *in, int degrees, unsigned flags,
                           const char *const *outputs, int n, cli_scene_session *s)
{
    memset(s, 0, sizeof *s);
    s->cmd = cmd;
    s->threads = in->rays.threads;
    /* every output is opened (as a temporary beside its target) before any
     * work, and renamed onto its target by cli_emit once the result is on
     * stdout: all of them or none, an existing file intact on any error */
    for (int k = 0; k < n && k < CLI_SCENE_MAX_OUTPUTS; k++)
        if (outputs[k] && cli_out_open(cmd, outputs[k], &s->tmp[k])) return CLI_EXIT_USAGE;
    int rc = build_scene(s, &in->scene, in->rays.threads);
    if (!rc) rc = build_env(s, &in->env, degrees, !(flags & CLI_SCENE_NEEDS_ENV));
    if (rc) {
        cli_scene_session_close(s);
        return rc;
    }
    cli_progress_start(&s->prog, cmd, in->rays.quiet);
    return 0;
}

json_t *cli_scene_session_result(cli_scene_session *s)
{
    json_t *root = json_object();
    root = cli_put(root, s->is_proc ? "scene" : "mesh", s->desc);
    s->desc = NULL;
    if (s->env_desc) {
        root = cli_put(root, "environment", s->env_desc);
        s->env_desc = NULL;
    }
    return root;
}

void cli_scene_session_close(cli_scene_session *s)
{
    json_decref(s->desc);
    json_decref(s->env_desc);
    sh_env_free(s->env);
    sh_scene_free(s->scene);
    sh_mesh_free(&s->mesh);
    memset(s, 0, sizeof *s);
}

sh_transfer_opts cli_scene_transfer_opts(cli_scene_session *s, const cli_rays_args *rays, sh_transfer_kind kind,
                                         int order)
{
    sh_transfer_opts to;
    memset(&to, 0, sizeof to);
    to.kind = kind;
    to.order = order;
    to.rays = rays->rays;
    to.albedo = rays->albedo;
    to.seed = (unsigned long)rays->seed;
    to.threads = rays->threads;
    to.progress = cli_progress_step;
    to.progress_ctx = &s->prog;
    return to;
}

sh_reference_opts cli_scene_reference_opts(cli_scene_session *s, const cli_rays_args *rays,
                                           const cli_reference_args *ref)
{
    sh_reference_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.samples = ref->samples;
    ro.replications = ref->replications;
    ro.seed = (unsigned long)rays->seed;
    ro.albedo = rays->albedo;
    ro.threads = rays->threads;
    ro.progress = cli_progress_step;
    ro.progress_ctx = &s->prog;
    return ro;
}

/* ---- pictures ------------------------------------------------------------------ */

int cli_scene_exposure(const double *Y, int n, double *expo)
{
    double *tmp = malloc(sizeof(double) * (size_t)n);
    if (!tmp) return sh_error(SH_ENOMEM, "out of memory");
    memcpy(tmp, Y, sizeof(double) * (size_t)n);
    qsort(tmp, (size_t)n, sizeof(double), cli_cmp_double);
    const double p99 = tmp[(size_t)(0.99 * (n - 1))];
    *expo = p99 > 0 ? 0.9 / p99 : 1;
    free(tmp);
    return SH_OK;
}

int cli_scene_picture(const cli_scene_session *s, const sh_camera *cam, int nchan, const double *vals,
                      const sh_env *bg, const char *png, double exposure, double vmax)
{
    sh_image img = {0}, cm = {0};
    int e = sh_render(s->scene, cam, nchan, vals, bg, s->threads, &img);
    if (!e && nchan == 1) e = sh_image_colormap(&img, vmax, &cm);
    if (!e) e = sh_png_write(png, nchan == 1 ? &cm : &img, nchan == 1 ? 1 : exposure);
    sh_image_free(&img);
    sh_image_free(&cm);
    return e;
}
