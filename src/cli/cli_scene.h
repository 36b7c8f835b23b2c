/* cli_scene.h — what the scene commands share (transfer, scene-plan, render,
 * cache, shadow-field; scale-scene takes the environment's options): the
 * options, declared once as groups (cli_args.h), and the scene session that
 * builds the mesh, its Embree scene and the environment, and frees them.
 *
 * A command's argument struct holds a cli_scene_input (the scene, the
 * environment, the rays) and includes the groups it takes:
 *
 *   CLI_GROUP(render_args, in.scene, cli_scene_opts),
 *   CLI_GROUP(render_args, in.env, cli_env_opts),
 *   CLI_GROUP(render_args, in.rays, cli_rays_opts),
 *
 * a group it does not include stays zero (transfer: no environment).  A
 * command whose default of a shared option differs says so with
 * CLI_DEFAULT("rays", "4096") in its own table. */
#ifndef SHLAB_CLI_SCENE_H
#define SHLAB_CLI_SCENE_H

#include "cli.h"

/* The largest --order of the scene commands (transfer, render, cache,
 * scene-plan's --max-order); shadow-field's is SH_SF_MAX_ORDER. */
#define CLI_SCENE_MAX_ORDER 32
/* The most threads a scene command starts (--threads). */
#define CLI_SCENE_MAX_THREADS 256

/* --order of a scene command: 1..MAX, DEF when not given. */
#define CLI_SCENE_ORDER(S, F, MAX, DEF, HELP)                                                      \
    {.type = CLI_T_ORDER, .name = "order", .meta = "N", .off = offsetof(S, F), .lo = 1, .hi = MAX,  \
     .def = DEF, .help = HELP}

/* The scene: --mesh FILE or --scene SPEC (exactly one), --res of the
 * procedural scenes, --up, --compute-normals, --allow-nonmanifold of a mesh. */
typedef struct {
    const char *mesh, *scene;
    int res;             /* 0: the scene's own */
    int up;              /* 0: z, 1: y (SH_MESH_Y_UP) */
    int compute_normals; /* SH_MESH_COMPUTE_NORMALS */
    int allow_nonmanifold; /* SH_MESH_ALLOW_NONMANIFOLD */
} cli_scene_args;
extern const cli_opt cli_scene_opts[];

/* The environment: --probe FILE or --light SPEC. */
typedef struct {
    const char *probe, *light;
} cli_env_args;
extern const cli_opt cli_env_opts[];

/* The rays: --rays, --albedo, --seed, --threads, --quiet. */
typedef struct {
    long rays;
    double albedo;
    long seed;
    int threads; /* 0: every CPU */
    int quiet;
} cli_rays_args;
extern const cli_opt cli_rays_opts[];

/* The pictures of cache, render and shadow-field: --view X,Y,Z (the camera's
 * direction from the scene's centre), --width, --height, --error-max (the
 * top of the false-colour scale; render: 0, the largest error). */
typedef struct {
    double view[3];
    int width, height;
    double error_max;
} cli_picture_args;
extern const cli_opt cli_picture_opts[];

/* The reference (direct integration, sh_shade_reference): --ref-samples,
 * --replications. */
typedef struct {
    long samples;
    int replications;
} cli_reference_args;
extern const cli_opt cli_reference_opts[];

typedef struct {
    cli_scene_args scene;
    cli_env_args env;
    cli_rays_args rays;
} cli_scene_input;

/* --transfer K (sh_transfer_kind), for CLI_CUSTOM. */
int cli_parse_transfer_kind(const char *opt, const char *s, void *field);
/* "--seed" and the like: a long >= 0 ("OPT: must be >= 0"), for CLI_CUSTOM. */
int cli_parse_seed(const char *opt, const char *s, void *field);

/* For each option in `names` (space-separated, no dashes) that was given:
 * cli_applies, i.e. refused unless `applies` ("CMD: --NAME applies only to
 * WHAT").  Returns 0 or the exit code after the line. */
int cli_scene_applies(const char *cmd, const cli_parsed *seen, const char *names, int applies, const char *what);

/* ---- the scene session ---------------------------------------------------
 * Everything a scene command sets up before its work, and takes down after
 * it, in one place: the output files opened (cli_out_open, so that an
 * unwritable target fails before the work), the mesh read or the
 * procedural scene tessellated, its Embree scene, the environment, their
 * descriptions for the result, and the progress on stderr. */
#define CLI_SCENE_MAX_OUTPUTS 4
enum {
    CLI_SCENE_NEEDS_ENV = 1 /* exactly one of --probe/--light (else: none, or the one given) */
};
typedef struct {
    const char *cmd;
    sh_mesh mesh;
    sh_proc_scene proc; /* --scene: its kind and parameters (is_proc) */
    int is_proc;
    sh_scene *scene;
    sh_env *env; /* NULL: no environment */
    json_t *desc, *env_desc; /* {"vertices",...}, {"light"|"probe",...}: cli_scene_session_result takes them */
    const char *tmp[CLI_SCENE_MAX_OUTPUTS]; /* outputs[k]'s temporary (NULL for an output not given) */
    int threads;
    cli_progress prog; /* started once the scene is built (--quiet: silent) */
} cli_scene_session;

/* Open the session of command cmd: the outputs (n paths, NULL entries for
 * those not given), the scene, the environment (flags: CLI_SCENE_NEEDS_ENV;
 * degrees for --light's angles).  Returns 0, or the exit code after the
 * error line with nothing left to close. */
int cli_scene_session_open(const char *cmd, const cli_scene_input *in, int degrees, unsigned flags,
                           const char *const *outputs, int n, cli_scene_session *s);
/* The result's first fields: "scene" or "mesh" (the description) and
 * "environment" when there is one; a new object (NULL if out of memory). */
json_t *cli_scene_session_result(cli_scene_session *s);
/* Free what the session holds (safe on a zeroed session). */
void cli_scene_session_close(cli_scene_session *s);

/* The options of sh_transfer (kind, order) and of sh_shade_reference (the
 * reference's samples and replications) from the rays (--rays, --albedo,
 * --seed, --threads), with the session's progress. */
sh_transfer_opts cli_scene_transfer_opts(cli_scene_session *s, const cli_rays_args *rays, sh_transfer_kind kind,
                                         int order);
sh_reference_opts cli_scene_reference_opts(cli_scene_session *s, const cli_rays_args *rays,
                                           const cli_reference_args *ref);

/* *expo: the exposure that maps the 99th percentile of Y[0..n) to 0.9 (1 if
 * that is 0).  Returns a library status (SH_ENOMEM). */
int cli_scene_exposure(const double *Y, int n, double *expo);
/* Render nchan (3: RGB, 1: a value) vertex values with the camera and write
 * a PNG to png: RGB × exposure over the background bg (NULL: none), or one
 * channel in false colour up to vmax.  Returns a library status. */
int cli_scene_picture(const cli_scene_session *s, const sh_camera *cam, int nchan, const double *vals,
                      const sh_env *bg, const char *png, double exposure, double vmax);

#endif
