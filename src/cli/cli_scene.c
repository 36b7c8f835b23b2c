/* cli_scene.c — the options of the scene commands (cli_scene.h). */
#include "cli_scene.h"

#include <string.h>

int cli_scene_opt(const char *cmd, int o, const char *arg, cli_scene_args *a)
{
    switch (o) {
    case CLI_OPT_MESH:
        if (a->mesh) return cli_fail("%s: --mesh given twice", cmd);
        a->mesh = arg;
        return 0;
    case CLI_OPT_SCENE:
        if (a->scene) return cli_fail("%s: --scene given twice", cmd);
        a->scene = arg;
        return 0;
    case CLI_OPT_PROBE:
        if (a->probe) return cli_fail("%s: --probe given twice", cmd);
        a->probe = arg;
        return 0;
    case CLI_OPT_LIGHT:
        if (a->light) return cli_fail("%s: --light given twice", cmd);
        a->light = arg;
        return 0;
    case CLI_OPT_UP:
        if (!strcmp(arg, "y")) a->flags |= SH_MESH_Y_UP;
        else if (!strcmp(arg, "z")) a->flags &= ~SH_MESH_Y_UP;
        else return cli_fail("--up: expected z or y, got '%s'", arg);
        return 0;
    case CLI_OPT_ALLOW_NM: a->flags |= SH_MESH_ALLOW_NONMANIFOLD; return 0;
    case CLI_OPT_COMPUTE_NORMALS: a->flags |= SH_MESH_COMPUTE_NORMALS; return 0;
    case CLI_OPT_RES:
        if (cli_int("--res", arg, &a->res)) return CLI_EXIT_USAGE;
        if (a->res < 1 || a->res > 512) return cli_fail("--res: out of range 1..512");
        return 0;
    case CLI_OPT_THREADS:
        if (cli_int("--threads", arg, &a->threads)) return CLI_EXIT_USAGE;
        if (a->threads < 1 || a->threads > 256) return cli_fail("--threads: out of range 1..256");
        return 0;
    default: return -1;
    }
}

int cli_scene_build(const char *cmd, const cli_scene_args *a, sh_mesh *m, sh_proc_scene *ps, int *is_proc,
                    sh_scene **s, json_t **desc)
{
    *s = NULL;
    *desc = NULL;
    *is_proc = 0;
    memset(m, 0, sizeof *m);
    if (!a->mesh == !a->scene) return cli_fail("%s: give exactly one of --mesh FILE and --scene SPEC", cmd);
    if (cli_applies(cmd, a->flags & SH_MESH_Y_UP, "--up y", !a->scene, "--mesh") ||
        cli_applies(cmd, a->flags & SH_MESH_COMPUTE_NORMALS, "--compute-normals", !a->scene, "--mesh") ||
        cli_applies(cmd, a->flags & SH_MESH_ALLOW_NONMANIFOLD, "--allow-nonmanifold", !a->scene, "--mesh") ||
        cli_applies(cmd, a->res, "--res", !a->mesh, "--scene"))
        return CLI_EXIT_USAGE;
    sh_mesh_report rep;
    memset(&rep, 0, sizeof rep);
    int st;
    if (a->scene) {
        if ((st = sh_proc_parse(a->scene, ps))) return cli_fail("--scene: %s", sh_last_error());
        ps->res = a->res;
        if ((st = sh_mesh_procedural(ps, m))) return cli_fail_status(st);
        *is_proc = 1;
    } else if (cli_input("mesh", a->mesh)) {
        return CLI_EXIT_USAGE;
    } else if ((st = sh_mesh_load(a->mesh, a->flags, m, &rep))) {
        return cli_fail_status(st);
    }
    if ((st = sh_scene_create(m, a->threads, s))) {
        sh_mesh_free(m);
        return cli_fail_status(st);
    }
    json_t *d = json_object();
    d = cli_put(d, a->scene ? "scene" : "mesh", json_string(a->scene ? a->scene : a->mesh));
    d = cli_put(d, "vertices", json_integer(m->nvert));
    d = cli_put(d, "triangles", json_integer(m->ntri));
    if (a->mesh) {
        d = cli_put(d, "up", json_string(a->flags & SH_MESH_Y_UP ? "y" : "z"));
        d = cli_put(d, "normals_computed", json_boolean(rep.normals_computed));
        d = cli_put(d, "degenerate_removed", json_integer(rep.degenerate_removed));
        d = cli_put(d, "unused_removed", json_integer(rep.unused_removed));
        d = cli_put(d, "skipped_primitives", json_integer(rep.skipped_primitives));
        d = cli_put(d, "boundary_edges", json_integer(rep.boundary_edges));
        d = cli_put(d, "nonmanifold_edges", json_integer(rep.nonmanifold_edges));
    }
    d = cli_put(d, "diagonal", json_real(sh_scene_diag(*s)));
    if (!d) {
        sh_scene_free(*s);
        *s = NULL;
        sh_mesh_free(m);
        return cli_fail("out of memory");
    }
    *desc = d;
    return 0;
}

int cli_env_build(const char *cmd, const cli_scene_args *a, int degrees, int optional, sh_env **e, json_t **desc)
{
    *e = NULL;
    *desc = NULL;
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
        if ((st = sh_env_from_light(&L, e))) { json_decref(d); return cli_fail_status(st); }
        d = cli_put(d, "light", json_string(a->light));
    } else {
        sh_image img;
        if (cli_input("probe", a->probe)) { json_decref(d); return CLI_EXIT_USAGE; }
        if ((st = sh_exr_read(a->probe, &img, NULL))) { json_decref(d); return cli_fail_status(st); }
        st = sh_env_from_image(&img, e);
        d = cli_put(d, "probe", json_string(a->probe));
        d = cli_put(d, "width", json_integer(img.width));
        d = cli_put(d, "height", json_integer(img.height));
        sh_image_free(&img);
        if (st) { json_decref(d); return cli_fail("%s: %s", a->probe, sh_last_error()); }
    }
    if (!d) {
        sh_env_free(*e);
        *e = NULL;
        return cli_fail("out of memory");
    }
    *desc = d;
    return 0;
}

int cli_picture_applies(const char *cmd, const cli_picture_args *p, unsigned bits, int applies, const char *what)
{
    static const char *const name[] = {"--view", "--width", "--height", "--error-max", "--ref-samples", "--replications"};
    for (int k = 0; k < 6; k++)
        if (cli_applies(cmd, p->given & bits & (1u << k), name[k], applies, what)) return CLI_EXIT_USAGE;
    return 0;
}

int cli_picture_opt(int o, const char *arg, cli_picture_args *p)
{
    static const int bit[] = {[CLI_OPT_VIEW - CLI_OPT_VIEW] = CLI_PIC_VIEW, [CLI_OPT_WIDTH - CLI_OPT_VIEW] = CLI_PIC_WIDTH,
                              [CLI_OPT_HEIGHT - CLI_OPT_VIEW] = CLI_PIC_HEIGHT, [CLI_OPT_EMAX - CLI_OPT_VIEW] = CLI_PIC_EMAX,
                              [CLI_OPT_REFS - CLI_OPT_VIEW] = CLI_PIC_REFS, [CLI_OPT_REPL - CLI_OPT_VIEW] = CLI_PIC_REPL};
    if (o >= CLI_OPT_VIEW && o <= CLI_OPT_REPL) p->given |= (unsigned)bit[o - CLI_OPT_VIEW];
    switch (o) {
    case CLI_OPT_VIEW:
        if (cli_vec3("--view", arg, p->view)) return CLI_EXIT_USAGE;
        if (!(p->view[0] * p->view[0] + p->view[1] * p->view[1] + p->view[2] * p->view[2] > 0))
            return cli_fail("--view: must be a non-zero vector");
        return 0;
    case CLI_OPT_WIDTH:
        if (cli_int("--width", arg, &p->width)) return CLI_EXIT_USAGE;
        if (p->width < 8 || p->width > 8192) return cli_fail("--width: out of range 8..8192");
        return 0;
    case CLI_OPT_HEIGHT:
        if (cli_int("--height", arg, &p->height)) return CLI_EXIT_USAGE;
        if (p->height < 8 || p->height > 8192) return cli_fail("--height: out of range 8..8192");
        return 0;
    case CLI_OPT_EMAX:
        if (cli_double("--error-max", arg, &p->error_max)) return CLI_EXIT_USAGE;
        if (!(p->error_max > 0)) return cli_fail("--error-max: must be > 0");
        return 0;
    case CLI_OPT_REFS:
        if (cli_long("--ref-samples", arg, &p->ref_samples)) return CLI_EXIT_USAGE;
        if (p->ref_samples < 16 || p->ref_samples > 1L << 22) return cli_fail("--ref-samples: out of range 16..4194304");
        return 0;
    case CLI_OPT_REPL:
        if (cli_int("--replications", arg, &p->replications)) return CLI_EXIT_USAGE;
        if (p->replications < 2 || p->replications > 1000) return cli_fail("--replications: out of range 2..1000");
        return 0;
    default: return -1;
    }
}
