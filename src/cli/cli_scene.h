/* cli_scene.h — options shared by the scene commands (transfer, scene-plan,
 * render): the mesh or procedural scene, the environment, threads. */
#ifndef SHLAB_CLI_SCENE_H
#define SHLAB_CLI_SCENE_H

#include "cli.h"

enum { CLI_OPT_MESH = 0x201, CLI_OPT_SCENE, CLI_OPT_UP, CLI_OPT_ALLOW_NM, CLI_OPT_COMPUTE_NORMALS, CLI_OPT_RES,
       CLI_OPT_THREADS, CLI_OPT_PROBE, CLI_OPT_LIGHT };
#define CLI_LONGOPTS_SCENE                                                                         \
    {"mesh", required_argument, 0, CLI_OPT_MESH}, {"scene", required_argument, 0, CLI_OPT_SCENE}, \
        {"up", required_argument, 0, CLI_OPT_UP},                                                  \
        {"allow-nonmanifold", no_argument, 0, CLI_OPT_ALLOW_NM},                                   \
        {"compute-normals", no_argument, 0, CLI_OPT_COMPUTE_NORMALS},                              \
        {"res", required_argument, 0, CLI_OPT_RES}, {"threads", required_argument, 0, CLI_OPT_THREADS}
#define CLI_LONGOPTS_ENV {"probe", required_argument, 0, CLI_OPT_PROBE}, {"light", required_argument, 0, CLI_OPT_LIGHT}

/* The help lines of those options. */
#define CLI_SCENE_HELP                                                                             \
    "  --mesh FILE          a triangle mesh (PLY, OBJ, … read by assimp); z up\n"                 \
    "  --scene SPEC         a procedural scene with closed-form answers:\n"                        \
    "                         sphere-plane[:R,H]  sphere (R 0.5) at height H (1) over a plane\n"   \
    "                         bowl                inside of the unit hemisphere, rim at z = 0\n"   \
    "                         box-open[:A]        inside of a box with a hole (half-width A 0.25)\n" \
    "                         box-closed          the same box, closed\n"                          \
    "  --res N              tessellation of --scene (default: the scene's)\n"                      \
    "  --up z|y             the mesh file's up axis (default z; y: turned to z up)\n"              \
    "  --compute-normals    ignore the file's normals (area-weighted face normals instead)\n"      \
    "  --allow-nonmanifold  report edges shared by > 2 triangles instead of refusing the mesh\n"   \
    "  --threads T          threads (default: every CPU)\n"
#define CLI_ENV_HELP                                                                               \
    "  --probe FILE         lat-long OpenEXR environment (e.g. data/probes/*.exr, `make probes`)\n" \
    "  --light SPEC         an analytic light instead (see `shlab project --help`; --degrees)\n"

/* The largest --order of the scene commands (transfer, render, cache,
 * scene-plan's --max-order); shadow-field's is SH_SF_MAX_ORDER. */
#define CLI_SCENE_MAX_ORDER 32

typedef struct {
    const char *mesh, *scene, *probe, *light;
    int flags, res, threads;
} cli_scene_args;

/* Handle a scene option: -1 if o is not one, 0 if handled, else an exit code. */
int cli_scene_opt(const char *cmd, int o, const char *arg, cli_scene_args *a);
/* Build the mesh (exactly one of --mesh/--scene) and its Embree scene; the
 * mesh's description goes to *desc (a JSON object).  ps is set for
 * procedural scenes (*is_proc = 1).  Returns 0 or an exit code. */
int cli_scene_build(const char *cmd, const cli_scene_args *a, sh_mesh *m, sh_proc_scene *ps, int *is_proc,
                    sh_scene **s, json_t **desc);
/* The environment (exactly one of --probe/--light, unless optional). */
int cli_env_build(const char *cmd, const cli_scene_args *a, int degrees, int optional, sh_env **e, json_t **desc);

/* Options of the scene commands that make pictures and judge against the
 * reference (cache, shadow-field): --view X,Y,Z (camera direction from the
 * scene's centre), --width, --height, --error-max (top of the false-colour
 * scale), --ref-samples, --replications. */
enum { CLI_OPT_VIEW = 0x221, CLI_OPT_WIDTH, CLI_OPT_HEIGHT, CLI_OPT_EMAX, CLI_OPT_REFS, CLI_OPT_REPL };
#define CLI_LONGOPTS_PICTURE                                                                           \
    {"view", required_argument, 0, CLI_OPT_VIEW}, {"width", required_argument, 0, CLI_OPT_WIDTH},     \
        {"height", required_argument, 0, CLI_OPT_HEIGHT}, {"error-max", required_argument, 0, CLI_OPT_EMAX}, \
        {"ref-samples", required_argument, 0, CLI_OPT_REFS},                                           \
        {"replications", required_argument, 0, CLI_OPT_REPL}
enum { CLI_PIC_VIEW = 1, CLI_PIC_WIDTH = 2, CLI_PIC_HEIGHT = 4, CLI_PIC_EMAX = 8, CLI_PIC_REFS = 16, CLI_PIC_REPL = 32 };
typedef struct {
    double view[3];
    int width, height;
    double error_max;
    long ref_samples;
    int replications;
    unsigned given; /* CLI_PIC_* of the options given (cli_applies: refused where they do not apply) */
} cli_picture_args;
#define CLI_PICTURE_DEFAULTS {{1, -1.4, 0.9}, 640, 480, 0.1, 16384, 4, 0}
/* Handle one of those options: -1 if o is not one, 0 if handled, else an exit code. */
int cli_picture_opt(int o, const char *arg, cli_picture_args *p);
/* cli_applies for each of the options in `bits` (CLI_PIC_*) that was given:
 * refused, naming it, unless `applies`. */
int cli_picture_applies(const char *cmd, const cli_picture_args *p, unsigned bits, int applies, const char *what);

#endif
