/* cmd_shadow_field.c — `shlab shadow-field`: the sphere of the sphere-plane
 * scene as a shadow-field occluder (Wang et al. 2006, Sec. 3.1): its
 * occlusion sampled at one distance and scaled to every plane vertex,
 * against the closed-form transfer, ray-cast visibility and the reference
 * shading.  Logic in src/scene/shadowfield.c. */
#include "cli_scene.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_shadow_field;

#define SF_MAX_SAMPLES 16
#define SF_MAX_BINS 32
/* The most rays one run may cast, counted as vertices × --rays (receivers
 * only, or every vertex with pictures): about a quarter of an hour at 10⁷
 * rays a second.  --res 512 with the default 4096 rays would be 5.2·10¹⁰. */
#define SF_MAX_RAYS 8.6e9
#define SF_DEFAULT_RES 8 /* sphere-plane's (sh_proc_scene res 0) */

/* Progress of the fields: `nf` fields, each over every receiver. */
typedef struct { cli_progress *p; int field, nf; } field_progress;
static void on_receivers(void *ctx, int done, int total, const char *what)
{
    const field_progress *f = ctx;
    cli_progress_step(f->p, f->field * total + done, f->nf * total, "receivers of the fields");
}

static const char help[] =
    "Usage: shlab shadow-field [--scene sphere-plane[:R,H]] (--probe FILE | --light SPEC)\n"
    "                          [OPTIONS]\n"
    "\n"
    "Shadow fields (Wang et al. 2006, Sec. 3.1): the occlusion of the sphere\n"
    "(radius R, centre at height H over the plane) is sampled at one distance\n"
    "d0 — its exact cap, half-angle asin(R/d0), projected to the order — and\n"
    "scaled to every plane vertex's distance d with an SH scaling matrix M(k),\n"
    "k = d/d0:\n"
    "  exact   no scaling: the cap projected at d (a fully sampled field)\n"
    "  cone    Wang's cone family, half-angle --cone-angle\n"
    "  sphere  the sphere's own τ: the cap at d onto the cap at d0 and the rest\n"
    "          onto the rest, both linearly (exact geometry: only the\n"
    "          truncation of the sampled field remains)\n"
    "with M computed at every vertex (samples 0) or tabulated at `samples` k\n"
    "geometric over the vertices' range and interpolated linearly (Wang\n"
    "Sec. 2.2).  The field is placed on the direction to the centre and the\n"
    "plane's transfer is the SH product P_n((1 − O)·c⁺) (c⁺ the clamped\n"
    "cosine × ρ/π), as shadow fields combine visibility.  The plane's SH\n"
    "shading B = Σ L_i t_i (luminance) is compared with\n"
    "  closed  the closed-form transfer of the same order (the exact cap\n"
    "          subtracted from the cosine lobe: what SH of this order can give)\n"
    "  ray     Green's shadowed transfer by ray casting (--rays) on the mesh\n"
    "  ref     with --reference, the shading by direct integration\n"
    "rel_l2 = √Σ(B − B_x)² / √Σ B_x² over the plane vertices; shadow_rel =\n"
    "√Σ(B − B_closed)² / √Σ(B_unshadowed − B_closed)² (the error relative to\n"
    "the light the sphere takes away).  Distance bins: shadow_rel of each\n"
    "scaling (samples 0) among the vertices with k in the bin.\n"
    "\n"
    "  --scene SPEC         sphere-plane[:R,H] (the default; no other scene)\n"
    "  --res N              its tessellation\n"
    CLI_ENV_HELP
    "  --order N            bands (default 4; ≤ 16)\n"
    "  --field-distance D   d0 (default H: the nearest plane point)\n"
    "  --cone-angle A|tangent  cone half-angle (default 45°, radians unless\n"
    "                       --degrees); tangent: acos(R/d0), the cone through\n"
    "                       the silhouette seen from d0\n"
    "  --samples LIST       k-table sizes of the scaled fields (default 0,2,5,10,40)\n"
    "  --rays R             rays of the ray-cast transfer (default 4096)\n"
    "  --reference          compare with the reference shading too\n"
    "  --ref-samples S      reference blocks per replication (default 16384)\n"
    "  --replications R     (default 4)\n"
    "  --bins K             distance bins (default 5)\n"
    "  --png FILE           picture: the plane shaded by --picture, the sphere by rays\n"
    "  --ray-png FILE       the same with the plane by ray casting\n"
    "  --error-png FILE     false colour of |B − B_ray| / RMS(B_ray) on the plane\n"
    "  --picture S[:K]      scaling and samples pictured (default cone:0)\n"
    "  --error-max V        top of the false-colour scale (default 0.1)\n"
    "  --view X,Y,Z, --width W, --height H   camera (default 1,-1.4,0.9; 640 × 480)\n"
    "  --albedo A           ρ (default 0.8)\n"
    "  --seed K             ray jitter seed (default 1)\n"
    "  --threads T, --degrees, --quiet, --format table|csv|json, --help\n"
    "\n"
    "JSON: {\"scene\":{...},\"environment\":{...},\"order\",\"convention\",\"radius\",\"height\",\n"
    "       \"field_distance\",\"cone_angle\",\"units\",\"receivers\",\"kmin\",\"kmax\",\n"
    "       \"ray_vs_closed\",[\"closed_vs_ref\",\"ref_l2\"],\n"
    "       \"fields\":[{\"scaling\",\"samples\",\"rel_l2\",\"rel_max\",\"shadow_rel\",\n"
    "                  \"ray_rel_l2\",[\"ref_rel_l2\"],\"matrices\",\"seconds\"}],\n"
    "       \"bins\":[{\"k_lo\",\"k_hi\",\"vertices\",\"exact\",\"cone\",\"sphere\"}]}\n";

static int run(int argc, char **argv)
{
    enum { O_D0 = 0x301, O_CONE, O_SAMPLES, O_RAYS, O_REF, O_BINS, O_PNG, O_RPNG, O_EPNG, O_PIC, O_ALBEDO, O_SEED,
           O_QUIET };
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPTS_SCENE,
                                         CLI_LONGOPTS_ENV,
                                         CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPTS_PICTURE,
                                         {"field-distance", required_argument, 0, O_D0},
                                         {"cone-angle", required_argument, 0, O_CONE},
                                         {"samples", required_argument, 0, O_SAMPLES},
                                         {"rays", required_argument, 0, O_RAYS},
                                         {"reference", no_argument, 0, O_REF},
                                         {"bins", required_argument, 0, O_BINS},
                                         {"png", required_argument, 0, O_PNG},
                                         {"ray-png", required_argument, 0, O_RPNG},
                                         {"error-png", required_argument, 0, O_EPNG},
                                         {"picture", required_argument, 0, O_PIC},
                                         {"albedo", required_argument, 0, O_ALBEDO},
                                         {"seed", required_argument, 0, O_SEED},
                                         {"quiet", no_argument, 0, O_QUIET},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = SH_SF_MAX_ORDER;
    cli_scene_args sa = {0};
    cli_picture_args pa = CLI_PICTURE_DEFAULTS;
    double d0 = 0, cone = M_PI / 4, albedo = 0.8; /* cone: 45° unless --cone-angle */
    int have_cone = 0;
    int cone_tangent = 0, nsamp = 5, samples[SF_MAX_SAMPLES] = {0, 2, 5, 10, 40}, reference = 0, nbins = 5, quiet = 0;
    int pic_samples = 0, have_picture = 0;
    sh_sf_scaling pic_scaling = SH_SF_CONE;
    long rays = 4096, seed = 1;
    const char *png = NULL, *rpng = NULL, *epng = NULL;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int e = cli_scene_opt("shadow-field", o, optarg, &sa);
        if (e < 0) e = cli_picture_opt(o, optarg, &pa);
        if (e > 0) return e;
        if (e == 0) continue;
        switch (o) {
        case O_D0:
            if (cli_double("--field-distance", optarg, &d0)) return CLI_EXIT_USAGE;
            if (!(d0 > 0)) return cli_fail("--field-distance: must be > 0");
            break;
        case O_CONE:
            if (!strcmp(optarg, "tangent")) cone_tangent = 1;
            else {
                cone_tangent = 0;
                if (cli_double("--cone-angle", optarg, &cone)) return CLI_EXIT_USAGE;
                have_cone = 1;
            }
            break;
        case O_SAMPLES: {
            double *v = NULL;
            int n = 0;
            if (cli_doubles("--samples", optarg, &v, &n)) return CLI_EXIT_USAGE;
            if (n < 1 || n > SF_MAX_SAMPLES) { free(v); return cli_fail("--samples: give 1..%d values", SF_MAX_SAMPLES); }
            for (int k = 0; k < n; k++) {
                if (!(v[k] == floor(v[k]) && (v[k] == 0 || (v[k] >= 2 && v[k] <= 10000)))) {
                    free(v);
                    return cli_fail("--samples: each value must be 0 or an integer in 2..10000");
                }
                samples[k] = (int)v[k];
            }
            nsamp = n;
            free(v);
            break;
        }
        case O_RAYS:
            if (cli_long("--rays", optarg, &rays)) return CLI_EXIT_USAGE;
            if (rays < 1 || rays > 1L << 20) return cli_fail("--rays: out of range 1..1048576");
            break;
        case O_REF: reference = 1; break;
        case O_BINS:
            if (cli_int("--bins", optarg, &nbins)) return CLI_EXIT_USAGE;
            if (nbins < 1 || nbins > SF_MAX_BINS) return cli_fail("--bins: out of range 1..%d", SF_MAX_BINS);
            break;
        case O_PNG: png = optarg; break;
        case O_RPNG: rpng = optarg; break;
        case O_EPNG: epng = optarg; break;
        case O_PIC: {
            char buf[64];
            snprintf(buf, sizeof buf, "%s", optarg);
            char *colon = strchr(buf, ':');
            if (colon) *colon = 0;
            if (sh_sf_scaling_parse(buf, &pic_scaling)) return cli_fail("--picture: %s", sh_last_error());
            pic_samples = 0;
            if (colon && cli_int("--picture", colon + 1, &pic_samples)) return CLI_EXIT_USAGE;
            if (pic_samples < 0 || pic_samples == 1) return cli_fail("--picture: samples must be 0 or >= 2");
            if (pic_scaling == SH_SF_EXACT && pic_samples) return cli_fail("--picture: the exact field has no samples");
            have_picture = 1;
            break;
        }
        case O_ALBEDO:
            if (cli_double("--albedo", optarg, &albedo)) return CLI_EXIT_USAGE;
            if (!(albedo > 0 && albedo <= 1)) return cli_fail("--albedo: must be in (0, 1]");
            break;
        case O_SEED:
            if (cli_long("--seed", optarg, &seed)) return CLI_EXIT_USAGE;
            if (seed < 0) return cli_fail("--seed: must be >= 0");
            break;
        case O_QUIET: quiet = 1; break;
        default: {
            const int e2 = cli_common_opt(&cmd_shadow_field, o, argv, &com);
            if (e2 >= 0) return e2;
        }
        }
    }
    if (optind < argc) return cli_fail("shadow-field: unexpected argument '%s'", argv[optind]);
    if (sa.mesh) return cli_fail("shadow-field: the occluder is the sphere of --scene sphere-plane (no --mesh)");
    /* options that do not apply are refused, as transfer refuses them */
    const int any_picture = png || rpng || epng;
    if (cli_picture_applies("shadow-field", &pa, CLI_PIC_REFS | CLI_PIC_REPL, reference, "--reference") ||
        cli_applies("shadow-field", have_picture, "--picture", png || epng, "--png and --error-png") ||
        cli_picture_applies("shadow-field", &pa, CLI_PIC_EMAX, epng != NULL, "--error-png") ||
        cli_picture_applies("shadow-field", &pa, CLI_PIC_VIEW | CLI_PIC_WIDTH | CLI_PIC_HEIGHT, any_picture,
                            "the pictures (--png, --ray-png, --error-png)"))
        return CLI_EXIT_USAGE;
    if (!sa.scene) sa.scene = "sphere-plane";
    const int order = com.order ? com.order : 4;
    const double deg = com.degrees ? M_PI / 180 : 1.0;
    {
        sh_proc_scene chk;
        if (sh_proc_parse(sa.scene, &chk)) return cli_fail("--scene: %s", sh_last_error());
        if (chk.kind != SH_PROC_SPHERE_PLANE) return cli_fail("shadow-field: needs --scene sphere-plane[:R,H]");
        if (d0 == 0) d0 = chk.p[1];
        if (!(d0 > chk.p[0])) return cli_fail("--field-distance: %g must exceed the sphere's radius %g", d0, chk.p[0]);
        if (cone_tangent) cone = acos(chk.p[0] / d0);
        else if (have_cone) cone *= deg;
        if (!(cone > 0 && cone < M_PI))
            return cli_fail("--cone-angle: %g must be in (0, %s)", cone / deg, com.degrees ? "180" : "π");
        /* what the run will take, from the scene's size before it is built:
         * refused if absurd (rays: at most one set per vertex) or more than
         * the memory available (the mesh twice, Embree's ~100 bytes a
         * triangle, the arrays below) */
        long long nvert, ntri;
        chk.res = sa.res;
        if (sh_proc_size(&chk, &nvert, &ntri)) return cli_fail_status(SH_EINVAL);
        const double nrays = (double)nvert * (double)rays, n2 = (double)order * order;
        const double bytes = (double)nvert * (96 + 8 * (11 + 5 * n2 + 2 * reference)) + (double)ntri * 124;
        if (nrays > SF_MAX_RAYS)
            return cli_fail("shadow-field: --res %d makes %lld vertices; × --rays %ld that is up to %.2g rays, more "
                            "than the %.2g a run may cast (hours); lower --res or --rays",
                            sa.res ? sa.res : SF_DEFAULT_RES, nvert, rays, nrays, SF_MAX_RAYS);
        if (cli_mem_check("shadow-field", bytes, "the scene and its transfer vectors")) return CLI_EXIT_USAGE;
    }
    /* the pictures: temporaries beside their targets, renamed by cli_emit
     * once the result is out (all or none; cli_out_open) */
    const char *opng = NULL, *orpng = NULL, *oepng = NULL;
    if ((png && cli_out_open("shadow-field", png, &opng)) || (rpng && cli_out_open("shadow-field", rpng, &orpng)) ||
        (epng && cli_out_open("shadow-field", epng, &oepng)))
        return CLI_EXIT_USAGE;
    sh_mesh m;
    sh_proc_scene ps;
    int is_proc, rc;
    sh_scene *s;
    json_t *desc, *edesc;
    if ((rc = cli_scene_build("shadow-field", &sa, &m, &ps, &is_proc, &s, &desc))) return rc;
    sh_env *env;
    if ((rc = cli_env_build("shadow-field", &sa, com.degrees, 0, &env, &edesc))) {
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        return rc;
    }
    const double R = ps.p[0], Hc = ps.p[1], centre[3] = {0, 0, Hc};
    const int n2 = order * order, nv = m.nvert;
    const int pictures = png || rpng || epng;
    /* the receivers: plane vertices (z = 0, normal +z) */
    int *pv = malloc(sizeof(int) * nv), np = 0;
    for (int v = 0; pv && v < nv; v++)
        if (m.pos[3 * v + 2] == 0 && m.normal[3 * v + 2] == 1) pv[np++] = v;

    double *pos = malloc(sizeof(double) * 3 * nv), *nor = malloc(sizeof(double) * 3 * nv);
    double *Tc = malloc(sizeof(double) * nv * n2), *Tr = malloc(sizeof(double) * nv * n2), *Tf = malloc(sizeof(double) * nv * n2);
    double *U = malloc(sizeof(double) * nv * n2), *L = malloc(sizeof(double) * 4 * n2);
    double *Bc = malloc(sizeof(double) * nv), *Br = malloc(sizeof(double) * nv), *Bu = malloc(sizeof(double) * nv);
    double *Bf = malloc(sizeof(double) * nv), *kk = malloc(sizeof(double) * nv);
    double *ref = NULL, *se = NULL;
    json_t *root = NULL, *fields = NULL, *bins = NULL;
    int e = (!pv || !pos || !nor || !Tc || !Tr || !Tf || !U || !L || !Bc || !Br || !Bu || !Bf || !kk) ? sh_error(SH_ENOMEM, "out of memory") : SH_OK;
    if (!e && np == 0) e = sh_error(SH_EINVAL, "shadow-field: the scene has no plane vertices");
    cli_progress prog;
    cli_progress_start(&prog, "shadow-field", quiet);
    for (int k = 0; k < np && !e; k++) {
        memcpy(pos + 3 * k, m.pos + 3 * pv[k], sizeof(double) * 3);
        memcpy(nor + 3 * k, m.normal + 3 * pv[k], sizeof(double) * 3);
        int known;
        e = sh_proc_closed_form(&ps, &m, pv[k], order, SH_CS, albedo, 0, Tc + (size_t)k * n2, NULL, &known);
        if (!e && known != order)
            e = sh_error(SH_EINVAL, "shadow-field: plane vertex %d sees the sphere across its horizon (no closed form); lower R or raise H", pv[k]);
        if (!e) e = sh_transfer_unshadowed(order, SH_CS, albedo, nor + 3 * k, U + (size_t)k * n2);
        kk[k] = sqrt(pos[3 * k] * pos[3 * k] + pos[3 * k + 1] * pos[3 * k + 1] + Hc * Hc) / d0;
        cli_progress_step(&prog, k + 1, np, "closed forms");
    }
    if (!e) e = sh_env_project(env, order, SH_CS, L);
    /* ray-cast transfer: the plane vertices (every vertex for pictures) */
    sh_transfer_opts to = {0};
    to.kind = SH_TRANSFER_SHADOWED;
    to.order = order;
    to.rays = rays;
    to.seed = (unsigned long)seed;
    to.albedo = albedo;
    to.threads = sa.threads;
    to.verts = pictures ? NULL : pv;
    to.nverts = np;
    to.progress = cli_progress_step;
    to.progress_ctx = &prog;
    if (!e) e = sh_transfer(s, &to, Tr, NULL);
    double *Tray = NULL; /* pictures: every vertex by rays, kept */
    if (!e && pictures) {
        if (!(Tray = malloc(sizeof(double) * nv * n2))) e = sh_error(SH_ENOMEM, "out of memory");
        else memcpy(Tray, Tr, sizeof(double) * nv * n2);
        /* plane rows first, as the other arrays */
        for (int k = 0; k < np && !e; k++) memcpy(Tf + (size_t)k * n2, Tr + (size_t)pv[k] * n2, sizeof(double) * n2);
    }
    if (!e) {
        e = sh_shade(np, order, Tc, order, L, Bc);
        if (!e) e = sh_shade(np, order, pictures ? Tf : Tr, order, L, Br);
        if (!e) e = sh_shade(np, order, U, order, L, Bu);
    }
    sh_shade_err rvc = {0}, cvr = {0};
    if (!e) e = sh_shade_error(np, Br, Bc, NULL, &rvc);
    if (!e && reference) {
        sh_reference_opts ro = {0};
        ro.samples = pa.ref_samples;
        ro.replications = pa.replications;
        ref = malloc(sizeof(double) * np);
        se = malloc(sizeof(double) * np);
        if (!ref || !se) e = sh_error(SH_ENOMEM, "out of memory");
        ro.albedo = albedo;
        ro.seed = (unsigned long)seed;
        ro.threads = sa.threads;
        ro.progress = cli_progress_step;
        ro.progress_ctx = &prog;
        if (!e) e = sh_shade_reference(s, env, NULL, pv, np, &ro, ref, se, NULL);
        if (!e) e = sh_shade_error(np, Bc, ref, se, &cvr);
    }
    /* the fields: exact, then cone and sphere × samples */
    double bin_err[3][SF_MAX_BINS], bin_den[3][SF_MAX_BINS];
    int bin_n[SF_MAX_BINS] = {0};
    memset(bin_err, 0, sizeof bin_err);
    memset(bin_den, 0, sizeof bin_den);
    double kmin = INFINITY, kmax = 0;
    for (int k = 0; k < np; k++) {
        kmin = fmin(kmin, kk[k]);
        kmax = fmax(kmax, kk[k]);
    }
    if (!e) fields = json_array();
    const sh_sf_scaling sc[3] = {SH_SF_EXACT, SH_SF_CONE, SH_SF_SPHERE};
    field_progress fp = {&prog, 0, 1 + 2 * nsamp};
    for (int a = 0; a < 3 && !e; a++)
        for (int q = 0; q < (a ? nsamp : 1) && !e; q++) {
            sh_sf_opts so = {0};
            so.order = order;
            so.scaling = sc[a];
            so.cone_angle = cone;
            so.d0 = d0;
            so.samples = a ? samples[q] : 0;
            so.albedo = albedo;
            so.progress = on_receivers;
            so.progress_ctx = &fp;
            sh_sf_stats st;
            if ((e = sh_shadow_field_transfer(&so, centre, R, np, pos, nor, Tf, &st))) break;
            if ((e = sh_shade(np, order, Tf, order, L, Bf))) break;
            sh_shade_err ec, er, ef = {0};
            if ((e = sh_shade_error(np, Bf, Bc, NULL, &ec)) || (e = sh_shade_error(np, Bf, Br, NULL, &er))) break;
            if (reference && (e = sh_shade_error(np, Bf, ref, se, &ef))) break;
            double d2 = 0, s2 = 0;
            for (int k = 0; k < np; k++) {
                d2 += (Bf[k] - Bc[k]) * (Bf[k] - Bc[k]);
                s2 += (Bu[k] - Bc[k]) * (Bu[k] - Bc[k]);
            }
            if (!(s2 > 0)) { e = sh_error(SH_EINVAL, "shadow-field: the sphere casts no shadow on the plane"); break; }
            if (so.samples == 0)
                for (int k = 0; k < np; k++) {
                    int b = kmax > kmin ? (int)(nbins * log(kk[k] / kmin) / log(kmax / kmin)) : 0;
                    if (b >= nbins) b = nbins - 1;
                    bin_err[a][b] += (Bf[k] - Bc[k]) * (Bf[k] - Bc[k]);
                    bin_den[a][b] += (Bu[k] - Bc[k]) * (Bu[k] - Bc[k]);
                    if (a == 0) bin_n[b]++;
                }
            if (pictures && sc[a] == pic_scaling && so.samples == pic_samples) {
                /* the pictured field's shading goes into the plane rows of Tr */
                for (int k = 0; k < np; k++) memcpy(Tr + (size_t)pv[k] * n2, Tf + (size_t)k * n2, sizeof(double) * n2);
            }
            json_t *r = json_object();
            r = cli_put(r, "scaling", json_string(sh_sf_scaling_name(sc[a])));
            r = cli_put(r, "samples", json_integer(so.samples));
            r = cli_put(r, "rel_l2", json_real(ec.rel_l2));
            r = cli_put(r, "rel_max", json_real(ec.rel_max));
            r = cli_put(r, "shadow_rel", json_real(sqrt(d2 / s2)));
            r = cli_put(r, "ray_rel_l2", json_real(er.rel_l2));
            if (reference) r = cli_put(r, "ref_rel_l2", json_real(ef.rel_l2));
            r = cli_put(r, "matrices", json_integer(st.matrices));
            r = cli_put(r, "seconds", json_real(st.seconds));
            if (!r || json_array_append_new(fields, r)) { e = sh_error(SH_ENOMEM, "out of memory"); json_decref(r); }
            fp.field++;
        }
    /* pictures: every vertex by rays, the plane's rows replaced (Tr) */
    if (!e && pictures) {
        sh_camera cam;
        double *col = malloc(sizeof(double) * 3 * nv), *colr = malloc(sizeof(double) * 3 * nv),
               *Y = malloc(sizeof(double) * nv), *Yr = malloc(sizeof(double) * nv), *B = malloc(sizeof(double) * nv);
        sh_image img = {0}, cm = {0};
        if (!col || !colr || !Y || !Yr || !B) e = sh_error(SH_ENOMEM, "out of memory");
        for (int c = 0; c < 4 && !e; c++) {
            if ((e = sh_shade(nv, order, Tr, order, L + (size_t)c * n2, B))) break;
            for (int v = 0; v < nv; v++) { if (c) col[3 * v + c - 1] = B[v]; else Y[v] = B[v]; }
            if ((e = sh_shade(nv, order, Tray, order, L + (size_t)c * n2, B))) break;
            for (int v = 0; v < nv; v++) { if (c) colr[3 * v + c - 1] = B[v]; else Yr[v] = B[v]; }
        }
        double expo = 1, r2 = 0, ymax = 0;
        for (int v = 0; !e && v < nv; v++) { r2 += Yr[v] * Yr[v]; ymax = fmax(ymax, Yr[v]); }
        if (ymax > 0) expo = 0.9 / ymax;
        if (!e) e = sh_camera_frame(&m, pa.view, 35, pa.width, pa.height, &cam);
        if (!e && png) {
            if (!(e = sh_render(s, &cam, 3, col, env, sa.threads, &img))) e = sh_png_write(opng, &img, expo);
            sh_image_free(&img);
        }
        if (!e && rpng) {
            if (!(e = sh_render(s, &cam, 3, colr, env, sa.threads, &img))) e = sh_png_write(orpng, &img, expo);
            sh_image_free(&img);
        }
        if (!e && epng) {
            const double rms = sqrt(r2 / nv);
            for (int v = 0; v < nv; v++) B[v] = rms > 0 ? fabs(Y[v] - Yr[v]) / rms : 0;
            if (!(e = sh_render(s, &cam, 1, B, NULL, sa.threads, &img)) && !(e = sh_image_colormap(&img, pa.error_max, &cm)))
                e = sh_png_write(oepng, &cm, 1);
            sh_image_free(&img);
            sh_image_free(&cm);
        }
        free(col); free(colr); free(Y); free(Yr); free(B);
    }
    if (!e) {
        bins = json_array();
        for (int b = 0; b < nbins && bins; b++) {
            json_t *r = json_object();
            r = cli_put(r, "k_lo", json_real(kmin * pow(kmax / kmin, (double)b / nbins)));
            r = cli_put(r, "k_hi", json_real(kmin * pow(kmax / kmin, (double)(b + 1) / nbins)));
            r = cli_put(r, "vertices", json_integer(bin_n[b]));
            for (int a = 0; a < 3; a++)
                r = cli_put(r, sh_sf_scaling_name(sc[a]), bin_den[a][b] > 0 ? json_real(sqrt(bin_err[a][b] / bin_den[a][b])) : json_null());
            if (!r || json_array_append_new(bins, r)) { json_decref(bins); bins = NULL; }
        }
        root = json_object();
        root = cli_put(root, "scene", desc);
        desc = NULL;
        root = cli_put(root, "environment", edesc);
        edesc = NULL;
        root = cli_put(root, "order", json_integer(order));
        root = cli_put(root, "convention", json_string("cs"));
        root = cli_put(root, "radius", json_real(R));
        root = cli_put(root, "height", json_real(Hc));
        root = cli_put(root, "field_distance", json_real(d0));
        root = cli_put(root, "units", json_string(com.degrees ? "degrees" : "radians"));
        root = cli_put(root, "cone_angle", json_real(cone / deg));
        root = cli_put(root, "receivers", json_integer(np));
        root = cli_put(root, "kmin", json_real(kmin));
        root = cli_put(root, "kmax", json_real(kmax));
        root = cli_put(root, "ray_vs_closed", json_real(rvc.rel_l2));
        if (reference) {
            root = cli_put(root, "closed_vs_ref", json_real(cvr.rel_l2));
            root = cli_put(root, "ref_l2", json_real(cvr.ref_l2));
        }
        root = cli_put(root, "fields", fields);
        fields = NULL;
        root = cli_put(root, "bins", bins);
        bins = NULL;
    }
    json_decref(fields);
    json_decref(bins);
    json_decref(desc);
    json_decref(edesc);
    free(pv); free(pos); free(nor); free(Tc); free(Tr); free(Tf); free(U); free(L);
    free(Bc); free(Br); free(Bu); free(Bf); free(kk); free(ref); free(se); free(Tray);
    sh_env_free(env);
    sh_scene_free(s);
    sh_mesh_free(&m);
    if (e) {
        json_decref(root);
        return cli_fail_status(e);
    }
    return cli_emit(root, com.fmt);
}

const cli_command cmd_shadow_field = {"shadow-field", run,
                                      "shadow field of a sphere sampled at one distance, scaled to the others (Wang)", help, NULL};
