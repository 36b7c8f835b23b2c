/* cmd_cache.c — `shlab cache`: Křivánek et al.'s radiance cache on a scene:
 * records placed by Ward's criterion, reused at nearby vertices after a
 * rotation into each vertex's frame by each rotation method; shading error
 * against computing every vertex (and against the reference), time per
 * shading point, methods interleaved.  Logic in src/scene/cache.c. */
#include "cli_scene.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_cache;

#define CACHE_MAX_METHODS 12

static const char help[] =
    "Usage: shlab cache (--mesh FILE | --scene SPEC) (--probe FILE | --light SPEC) [OPTIONS]\n"
    "\n"
    "A radiance cache (Křivánek et al. 2005, Sec. 4.2): the incident radiance\n"
    "(R, G, B) is computed in SH at sparse records, each in its vertex's\n"
    "tangent frame — the environment with ray-cast visibility, plus one bounce\n"
    "with --bounce — and reused at every vertex v from the records i with\n"
    "  1/w_i(v) = |p_v − p_i|/R_i + √(1 − n_v·n_i) < a\n"
    "(Ward's weight; R_i the harmonic mean distance of 64 rays from p_i,\n"
    "clamped to [rmin, rmax] × the scene's diagonal), each rotated from its\n"
    "frame into v's by R_sh(M_vᵀ M_i), Λ(v) = Σ w_i R_i Λ_i / Σ w_i (no\n"
    "gradients).  Records are placed lazily: vertices in a seeded random\n"
    "order, one no record covers becomes a record.  Shading: diffuse,\n"
    "B = Σ t_i Λ_i with t the clamped cosine × ρ/π, or a Phong lobe about the\n"
    "mirror direction of the camera (--brdf phong:E).\n"
    "\n"
    "For each rotation method (ignore = no rotation, Křivánek's 'Ignore' row)\n"
    "every vertex is shaded from the cache and compared with every vertex\n"
    "computed directly (its own incident radiance, same random streams):\n"
    "  rel_l2 = √Σ(Y − Y_direct)² / √Σ Y_direct²,  rel_max = max|Y − Y_direct| / RMS\n"
    "(Y the luminance); rot_rel_l2, rot_rel_max: the same against the cache\n"
    "with the exact zxzxz rotation (the rotation's own error).  Timing: one\n"
    "thread, --repeat rounds, every method once per round in a rotated order,\n"
    "the thread's CPU time (time slices lost to other work do not count);\n"
    "ns_per_point the median over rounds of the interpolation and shading\n"
    "loop per vertex, ns_per_use = (T − T_ignore) / record uses (one rotation\n"
    "of three channels each; Křivánek's TPR), ratio_zxzxz the median of the\n"
    "per-round ratios T_zxzxz / T (both loops) with their range.  The machine's\n"
    "load shows in the ranges, not in the ratios' medians.\n"
    "\n"
    CLI_SCENE_HELP
    CLI_ENV_HELP
    "  --order N            bands (default 6; ≤ 32)\n"
    "  --allowed-error A    a (default 0.2)\n"
    "  --methods LIST       default ignore,taylor1,taylor1.5,taylor2,zxzxz,ivanic\n"
    "  --beta-lim B         Taylor methods hand rotations with β > B to zxzxz\n"
    "                       (Křivánek: β_lim = 1.25a; default: never)\n"
    "  --brdf diffuse|phong:E  (default diffuse)\n"
    "  --bounce             add one bounce of the direct light\n"
    "  --env-samples S      environment samples per record (default 4096)\n"
    "  --rays R             bounce rays per record (default 1024)\n"
    "  --albedo A           ρ (default 0.8)\n"
    "  --rmin F, --rmax F   clamp of R_i, fractions of the diagonal (0.01, 0.25)\n"
    "  --repeat K           timing rounds (default 5)\n"
    "  --noise              also compute every vertex with the next seed: the\n"
    "                       direct computation's own noise, noise_l2 = rel_l2\n"
    "                       between the two / √2\n"
    "  --reference K        diffuse shading against the reference (direct\n"
    "                       integration, sh_shade_reference) at K seeded vertices\n"
    "                       (default 0: none; not with --bounce or phong)\n"
    "  --ref-samples S      reference blocks per replication (default 16384)\n"
    "  --replications R     reference replications (default 4)\n"
    "  --view X,Y,Z         camera direction from the scene's centre: Phong's eye\n"
    "                       and the pictures (default 1,-1.4,0.9)\n"
    "  --png FILE           picture of the cache's shading (--picture-method)\n"
    "  --direct-png FILE    picture of every vertex computed directly\n"
    "  --error-png FILE     false colour of |Y − Y_direct| / RMS(Y_direct)\n"
    "  --picture-method M   the method pictured (default: the first listed that\n"
    "                       is not ignore)\n"
    "  --error-max V        top of the false-colour scale (default 0.1)\n"
    "  --width W, --height H  pixels (default 640 × 480)\n"
    "  --seed K             seed of the placement and the rays (default 1)\n"
    "  --degrees            --beta-lim and the beta statistics in degrees\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"order\",\"convention\",\n"
    "       \"allowed_error\",\"brdf\",\"bounce\",\"albedo\",\"vertices\",\"records\",\"uses\",\n"
    "       \"uses_per_vertex\",\"beta\":{\"units\",\"max\",\"mean\",\"p50\",\"p90\",\"p99\"},\n"
    "       \"radius_clamped\":{\"low\",\"high\"},\"seconds\":{\"placement\",\"records\",\n"
    "       \"direct\",\"threads\"},\"us_per_vertex\":{\"direct\",\"records\"},\"rounds\",\n"
    "       [\"noise_l2\"],[\"reference\":{\"vertices\",\"ref_l2\",\"direct_rel_l2\"}],\n"
    "       \"methods\":[{\"method\",\"beta_lim\",\"rotations\",\"fallbacks\",\"rel_l2\",\n"
    "       \"rel_max\",\"rot_rel_l2\",\"rot_rel_max\",[\"ref_rel_l2\"],\"ns_per_point\",\n"
    "       \"ns_per_point_min\",\"ns_per_point_max\",\"ns_per_use\",\"ratio_zxzxz\",\n"
    "       \"ratio_zxzxz_min\",\"ratio_zxzxz_max\"}]}\n";

typedef struct {
    char name[16];
    sh_cache_rot rot;
    double *B, *Y;
    sh_cache_timing t;
    double *sec; /* per round */
} meth;

static int parse_methods(const char *arg, meth *m, int *n)
{
    char **t;
    int nt, rc = 0;
    if (cli_split("--methods", arg, &t, &nt)) return CLI_EXIT_USAGE;
    *n = 0;
    for (int i = 0; i < nt && !rc; i++) {
        const char *tok = t[i];
        if (*n == CACHE_MAX_METHODS) { rc = cli_fail("--methods: at most %d", CACHE_MAX_METHODS); break; }
        meth *x = &m[*n];
        memset(x, 0, sizeof *x);
        snprintf(x->name, sizeof x->name, "%s", tok);
        if (!strcmp(tok, "ignore")) x->rot.ignore = 1;
        else if (sh_rot_method_parse(tok, &x->rot.method)) rc = cli_fail("--methods: %s", sh_last_error());
        else if (x->rot.method == SH_ROT_Z) rc = cli_fail("--methods: z rotates about z only");
        for (int k = 0; k < *n && !rc; k++)
            if (!strcmp(m[k].name, tok)) rc = cli_fail("--methods: %s given twice", tok);
        if (!rc) (*n)++;
    }
    free(t);
    return rc;
}

/* picture of 3-channel (or 1-channel) vertex values */
static int picture(sh_scene *s, const sh_camera *cam, int nchan, const double *vals, const sh_env *bg, int threads,
                   const char *png, double exposure, double vmax)
{
    sh_image img = {0}, cm = {0};
    int e = sh_render(s, cam, nchan, vals, bg, threads, &img);
    if (!e && nchan == 1) e = sh_image_colormap(&img, vmax, &cm);
    if (!e) e = sh_png_write(png, nchan == 1 ? &cm : &img, nchan == 1 ? 1 : exposure);
    sh_image_free(&img);
    sh_image_free(&cm);
    return e;
}

static int run(int argc, char **argv)
{
    enum { O_A = 0x301, O_METHODS, O_BLIM, O_BRDF, O_BOUNCE, O_ENVS, O_RAYS, O_ALBEDO, O_RMIN, O_RMAX, O_REPEAT,
           O_NOISE, O_REF, O_PNG, O_DPNG, O_EPNG, O_PMETH, O_SEED, O_QUIET };
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPTS_SCENE,
                                         CLI_LONGOPTS_ENV,
                                         CLI_LONGOPT_ORDER,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPTS_PICTURE,
                                         {"allowed-error", required_argument, 0, O_A},
                                         {"methods", required_argument, 0, O_METHODS},
                                         {"beta-lim", required_argument, 0, O_BLIM},
                                         {"brdf", required_argument, 0, O_BRDF},
                                         {"bounce", no_argument, 0, O_BOUNCE},
                                         {"env-samples", required_argument, 0, O_ENVS},
                                         {"rays", required_argument, 0, O_RAYS},
                                         {"albedo", required_argument, 0, O_ALBEDO},
                                         {"rmin", required_argument, 0, O_RMIN},
                                         {"rmax", required_argument, 0, O_RMAX},
                                         {"repeat", required_argument, 0, O_REPEAT},
                                         {"noise", no_argument, 0, O_NOISE},
                                         {"reference", required_argument, 0, O_REF},
                                         {"png", required_argument, 0, O_PNG},
                                         {"direct-png", required_argument, 0, O_DPNG},
                                         {"error-png", required_argument, 0, O_EPNG},
                                         {"picture-method", required_argument, 0, O_PMETH},
                                         {"seed", required_argument, 0, O_SEED},
                                         {"quiet", no_argument, 0, O_QUIET},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    com.max_order = CLI_SCENE_MAX_ORDER;
    cli_scene_args sa = {0};
    sh_cache_opts co = {0};
    co.a = 0.2;
    co.albedo = 0.8;
    co.seed = 1;
    cli_picture_args pa = CLI_PICTURE_DEFAULTS;
    meth M[CACHE_MAX_METHODS];
    int nm = 0, repeat = 5, nref = 0, noise = 0, quiet = 0, have_rays = 0;
    double beta_lim = 0;
    const char *png = NULL, *dpng = NULL, *epng = NULL, *pmeth = NULL;
    long seed = 1;
    if (parse_methods("ignore,taylor1,taylor1.5,taylor2,zxzxz,ivanic", M, &nm)) return CLI_EXIT_USAGE;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int e = cli_scene_opt("cache", o, optarg, &sa);
        if (e < 0) e = cli_picture_opt(o, optarg, &pa);
        if (e > 0) return e;
        if (e == 0) continue;
        switch (o) {
        case O_A:
            if (cli_double("--allowed-error", optarg, &co.a)) return CLI_EXIT_USAGE;
            if (!(co.a > 0 && co.a <= 10)) return cli_fail("--allowed-error: must be in (0, 10]");
            break;
        case O_METHODS:
            if (parse_methods(optarg, M, &nm)) return CLI_EXIT_USAGE;
            break;
        case O_BLIM:
            if (cli_double("--beta-lim", optarg, &beta_lim)) return CLI_EXIT_USAGE;
            if (!(beta_lim > 0)) return cli_fail("--beta-lim: must be > 0");
            break;
        case O_BRDF:
            if (!strcmp(optarg, "diffuse")) co.brdf.phong = 0;
            else if (!strncmp(optarg, "phong:", 6)) {
                co.brdf.phong = 1;
                if (cli_double("--brdf phong:E", optarg + 6, &co.brdf.exponent)) return CLI_EXIT_USAGE;
                if (!(co.brdf.exponent > 0 && co.brdf.exponent <= 10000)) return cli_fail("--brdf: phong exponent must be in (0, 10000]");
            } else return cli_fail("--brdf: expected diffuse or phong:E, got '%s'", optarg);
            break;
        case O_BOUNCE: co.bounce = 1; break;
        case O_ENVS:
            if (cli_long("--env-samples", optarg, &co.env_samples)) return CLI_EXIT_USAGE;
            if (co.env_samples < 16 || co.env_samples > 1L << 22) return cli_fail("--env-samples: out of range 16..4194304");
            break;
        case O_RAYS:
            if (cli_long("--rays", optarg, &co.rays)) return CLI_EXIT_USAGE;
            if (co.rays < 1 || co.rays > 1L << 20) return cli_fail("--rays: out of range 1..1048576");
            have_rays = 1;
            break;
        case O_ALBEDO:
            if (cli_double("--albedo", optarg, &co.albedo)) return CLI_EXIT_USAGE;
            if (!(co.albedo > 0 && co.albedo <= 1)) return cli_fail("--albedo: must be in (0, 1]");
            break;
        case O_RMIN:
            if (cli_double("--rmin", optarg, &co.rmin)) return CLI_EXIT_USAGE;
            if (!(co.rmin > 0)) return cli_fail("--rmin: must be > 0");
            break;
        case O_RMAX:
            if (cli_double("--rmax", optarg, &co.rmax)) return CLI_EXIT_USAGE;
            if (!(co.rmax > 0 && co.rmax <= 100)) return cli_fail("--rmax: must be in (0, 100]");
            break;
        case O_REPEAT:
            if (cli_int("--repeat", optarg, &repeat)) return CLI_EXIT_USAGE;
            if (repeat < 1 || repeat > 1000) return cli_fail("--repeat: out of range 1..1000");
            break;
        case O_NOISE: noise = 1; break;
        case O_REF:
            if (cli_int("--reference", optarg, &nref)) return CLI_EXIT_USAGE;
            if (nref < 0) return cli_fail("--reference: must be >= 0");
            break;
        case O_PNG: png = optarg; break;
        case O_DPNG: dpng = optarg; break;
        case O_EPNG: epng = optarg; break;
        case O_PMETH: pmeth = optarg; break;
        case O_SEED:
            if (cli_long("--seed", optarg, &seed)) return CLI_EXIT_USAGE;
            if (seed < 0) return cli_fail("--seed: must be >= 0");
            co.seed = (unsigned long)seed;
            break;
        case O_QUIET: quiet = 1; break;
        default: {
            const int e2 = cli_common_opt(&cmd_cache, o, argv, &com);
            if (e2 >= 0) return e2;
        }
        }
    }
    if (optind < argc) return cli_fail("cache: unexpected argument '%s'", argv[optind]);
    co.order = com.order ? com.order : 6;
    const double deg = com.degrees ? M_PI / 180 : 1.0;
    beta_lim *= deg;
    if (beta_lim > M_PI) return cli_fail("--beta-lim: must be <= π");
    if ((co.rmin > 0 ? co.rmin : 0.01) >= (co.rmax > 0 ? co.rmax : 0.25)) return cli_fail("--rmin must be below --rmax");
    if (nref && (co.bounce || co.brdf.phong))
        return cli_fail("cache: --reference judges diffuse direct light only (not with --bounce or phong)");
    /* options that do not apply are refused, as transfer refuses them */
    int approx = 0;
    for (int k = 0; k < nm; k++) approx |= !M[k].rot.ignore && !sh_rot_method_is_exact(M[k].rot.method);
    const int pictures = png || dpng || epng;
    if (cli_applies("cache", have_rays, "--rays", co.bounce, "--bounce (rays of the bounce)") ||
        cli_picture_applies("cache", &pa, CLI_PIC_REFS | CLI_PIC_REPL, nref > 0, "--reference K") ||
        cli_applies("cache", pmeth != NULL, "--picture-method", png || epng, "--png and --error-png") ||
        cli_picture_applies("cache", &pa, CLI_PIC_EMAX, epng != NULL, "--error-png") ||
        cli_picture_applies("cache", &pa, CLI_PIC_WIDTH | CLI_PIC_HEIGHT, pictures,
                            "the pictures (--png, --direct-png, --error-png)") ||
        cli_picture_applies("cache", &pa, CLI_PIC_VIEW, pictures || co.brdf.phong,
                            "the pictures and --brdf phong (the eye)") ||
        cli_applies("cache", beta_lim > 0, "--beta-lim", approx, "the Taylor methods in --methods"))
        return CLI_EXIT_USAGE;
    int pic = -1;
    for (int k = 0; k < nm; k++) {
        M[k].rot.beta_lim = sh_rot_method_is_exact(M[k].rot.method) || M[k].rot.ignore ? 0 : beta_lim;
        if (!M[k].rot.ignore && co.order > sh_rot_method_max_order(M[k].rot.method))
            return cli_fail("cache: %s accepts orders up to %d", M[k].name, sh_rot_method_max_order(M[k].rot.method));
        if (pmeth ? !strcmp(M[k].name, pmeth) : (pic < 0 && !M[k].rot.ignore)) pic = k;
    }
    if ((png || epng) && pic < 0)
        return cli_fail("cache: --picture-method %s is not among --methods", pmeth ? pmeth : "(none but ignore)");
    sh_reference_opts ro = {0};
    ro.samples = pa.ref_samples;
    ro.replications = pa.replications;
    ro.seed = co.seed;
    co.threads = ro.threads = sa.threads;
    ro.albedo = co.albedo;
    /* the pictures are written as temporaries beside their targets, renamed
     * by cli_emit once the result is out: all or none (cli_out_open) */
    const char *opng = NULL, *odpng = NULL, *oepng = NULL;
    if ((png && cli_out_open("cache", png, &opng)) || (dpng && cli_out_open("cache", dpng, &odpng)) ||
        (epng && cli_out_open("cache", epng, &oepng)))
        return CLI_EXIT_USAGE;

    sh_mesh m;
    sh_proc_scene ps;
    int is_proc, rc;
    sh_scene *s;
    json_t *desc, *edesc;
    if ((rc = cli_scene_build("cache", &sa, &m, &ps, &is_proc, &s, &desc))) return rc;
    sh_env *env;
    if ((rc = cli_env_build("cache", &sa, com.degrees, 0, &env, &edesc))) {
        json_decref(desc);
        sh_scene_free(s);
        sh_mesh_free(&m);
        return rc;
    }
    sh_camera cam;
    int e = sh_camera_frame(&m, pa.view, 35, pa.width, pa.height, &cam);
    for (int k = 0; k < 3; k++) co.brdf.eye[k] = cam.eye[k];
    cli_progress prog;
    cli_progress_start(&prog, "cache", quiet);
    co.progress = ro.progress = cli_progress_step;
    co.progress_ctx = ro.progress_ctx = &prog;
    const int nv = m.nvert;
    sh_cache *c = NULL;
    sh_cache_info info;
    double *Bd = malloc(sizeof(double) * 3 * nv), *Yd = malloc(sizeof(double) * nv), *Bx = malloc(sizeof(double) * 3 * nv),
           *Yx = malloc(sizeof(double) * nv), *ratio = malloc(sizeof(double) * repeat * (CACHE_MAX_METHODS + 1)),
           *sec = malloc(sizeof(double) * repeat * (CACHE_MAX_METHODS + 1));
    int ok_alloc = Bd && Yd && Bx && Yx && ratio && sec;
    for (int k = 0; k < nm; k++) {
        M[k].B = malloc(sizeof(double) * 3 * nv);
        M[k].Y = malloc(sizeof(double) * nv);
        ok_alloc = ok_alloc && M[k].B && M[k].Y;
    }
    if (!e && !ok_alloc) e = sh_error(SH_ENOMEM, "out of memory");
    if (!e) e = sh_cache_create(s, env, &co, &c);
    if (!e) e = sh_cache_info_get(c, &info);
    sh_transfer_stats ds;
    if (!e) e = sh_cache_shade_direct(c, co.seed, sa.threads, Bd, &ds);
    if (!e) sh_rgb_luminance(nv, Bd, Yd);
    /* the exact-rotation cache, the baseline of each method's rotation error */
    const sh_cache_rot exact = {SH_ROT_ZXZXZ, 0, 0};
    if (!e) e = sh_cache_shade(c, &exact, 1, Bx, NULL);
    if (!e) sh_rgb_luminance(nv, Bx, Yx);
    /* timing (sh_cache_bench): the methods and an extra zxzxz, the
     * baseline of the per-round ratios, interleaved; ≥ 20 ms of CPU each */
    sh_cache_rot rots[CACHE_MAX_METHODS + 1];
    for (int k = 0; k < nm; k++) rots[k] = M[k].rot;
    rots[nm] = exact;
    for (int k = 0; k < nm && !e; k++) e = sh_cache_shade(c, &M[k].rot, 1, M[k].B, &M[k].t);
    if (!e) {
        if (!quiet) fprintf(stderr, "cache: timing, %d rounds of %d loops\n", repeat, nm + 1);
        e = sh_cache_bench(c, rots, nm + 1, repeat, 0.02, sec);
    }
    /* sec is round-major: sec[r·(nm+1) + k] */
    double *zsec = malloc(sizeof(double) * repeat), *msec = malloc(sizeof(double) * repeat * nm);
    if (!e && (!zsec || !msec)) e = sh_error(SH_ENOMEM, "out of memory");
    for (int r = 0; r < repeat && !e; r++) {
        zsec[r] = sec[(size_t)r * (nm + 1) + nm];
        for (int k = 0; k < nm; k++) msec[(size_t)k * repeat + r] = sec[(size_t)r * (nm + 1) + k];
    }
    for (int k = 0; k < nm && !e; k++) M[k].sec = msec + (size_t)k * repeat;
    for (int k = 0; k < nm && !e; k++) sh_rgb_luminance(nv, M[k].B, M[k].Y);
    double noise_l2 = -1;
    if (!e && noise) {
        /* every vertex again with the next seed: two independent estimates */
        double *B2 = malloc(sizeof(double) * 3 * nv), *Y2 = malloc(sizeof(double) * nv);
        if (!B2 || !Y2) e = sh_error(SH_ENOMEM, "out of memory");
        if (!e) e = sh_cache_shade_direct(c, co.seed + 1, sa.threads, B2, NULL);
        if (!e) {
            sh_rgb_luminance(nv, B2, Y2);
            sh_shade_err er;
            if (!(e = sh_shade_error(nv, Y2, Yd, NULL, &er))) noise_l2 = er.rel_l2 / sqrt(2.0);
        }
        free(B2);
        free(Y2);
    }
    /* reference at a seeded subset */
    json_t *refj = NULL;
    double *ref = NULL, *se = NULL, *sub = NULL;
    int *rv = NULL;
    if (!e && nref) {
        const int K = nref < nv ? nref : nv;
        rv = malloc(sizeof(int) * nv);
        ref = malloc(sizeof(double) * K);
        se = malloc(sizeof(double) * K);
        sub = malloc(sizeof(double) * K);
        if (!rv || !ref || !se || !sub) e = sh_error(SH_ENOMEM, "out of memory");
        if (!e) {
            /* a seeded subset: partial Fisher-Yates (splitmix stream) */
            uint64_t x = (uint64_t)co.seed * 0x9E3779B97F4A7C15ull + 12345;
            for (int v = 0; v < nv; v++) rv[v] = v;
            for (int k = 0; k < K; k++) {
                x += 0x9E3779B97F4A7C15ull;
                uint64_t z = x;
                z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
                z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
                z ^= z >> 31;
                const int j = k + (int)((z >> 11) * 0x1.0p-53 * (nv - k));
                const int t = rv[k];
                rv[k] = rv[j];
                rv[j] = t;
            }
            sh_transfer_stats rs;
            e = sh_shade_reference(s, env, NULL, rv, K, &ro, ref, se, &rs);
        }
        sh_shade_err er;
        if (!e) {
            for (int k = 0; k < K; k++) sub[k] = Yd[rv[k]];
            e = sh_shade_error(K, sub, ref, se, &er);
        }
        if (!e) {
            refj = json_object();
            refj = cli_put(refj, "vertices", json_integer(K));
            refj = cli_put(refj, "ref_l2", json_real(er.ref_l2));
            refj = cli_put(refj, "direct_rel_l2", json_real(er.rel_l2));
        }
        nref = K;
    }
    /* pictures */
    if (!e && (png || dpng || epng)) {
        double *Yc = malloc(sizeof(double) * nv), *tmp = malloc(sizeof(double) * nv);
        if (!Yc || !tmp) e = sh_error(SH_ENOMEM, "out of memory");
        double expo = 1;
        if (!e) {
            memcpy(tmp, Yd, sizeof(double) * nv);
            qsort(tmp, (size_t)nv, sizeof(double), cli_cmp_double);
            const double p99 = tmp[(size_t)(0.99 * (nv - 1))];
            expo = p99 > 0 ? 0.9 / p99 : 1;
        }
        if (!e && png) e = picture(s, &cam, 3, M[pic].B, env, sa.threads, opng, expo, 0);
        if (!e && dpng) e = picture(s, &cam, 3, Bd, env, sa.threads, odpng, expo, 0);
        if (!e && epng) {
            double r2 = 0;
            for (int v = 0; v < nv; v++) r2 += Yd[v] * Yd[v];
            const double rms = sqrt(r2 / nv);
            for (int v = 0; v < nv; v++) Yc[v] = rms > 0 ? fabs(M[pic].Y[v] - Yd[v]) / rms : 0;
            e = picture(s, &cam, 1, Yc, NULL, sa.threads, oepng, 1, pa.error_max);
        }
        free(Yc);
        free(tmp);
    }
    json_t *root = NULL;
    if (!e) {
        double tig = -1;
        for (int k = 0; k < nm; k++) {
            if (M[k].rot.ignore) {
                double t[1000];
                memcpy(t, M[k].sec, sizeof(double) * repeat);
                tig = cli_median(t, repeat);
            }
        }
        root = json_object();
        root = cli_put(root, is_proc ? "scene" : "mesh", desc);
        desc = NULL;
        root = cli_put(root, "environment", edesc);
        edesc = NULL;
        root = cli_put(root, "order", json_integer(co.order));
        root = cli_put(root, "convention", json_string("cs"));
        root = cli_put(root, "allowed_error", json_real(co.a));
        char bd[64];
        if (co.brdf.phong) snprintf(bd, sizeof bd, "phong:%g", co.brdf.exponent);
        else snprintf(bd, sizeof bd, "diffuse");
        root = cli_put(root, "brdf", json_string(bd));
        root = cli_put(root, "bounce", json_boolean(co.bounce));
        root = cli_put(root, "albedo", json_real(co.albedo));
        root = cli_put(root, "vertices", json_integer(nv));
        root = cli_put(root, "records", json_integer(info.records));
        root = cli_put(root, "uses", json_integer(info.uses));
        root = cli_put(root, "uses_per_vertex", json_real(info.mean_uses));
        json_t *bj = json_object();
        bj = cli_put(bj, "units", json_string(com.degrees ? "degrees" : "radians"));
        bj = cli_put(bj, "max", json_real(info.beta_max / deg));
        bj = cli_put(bj, "mean", json_real(info.beta_mean / deg));
        bj = cli_put(bj, "p50", json_real(info.beta_p50 / deg));
        bj = cli_put(bj, "p90", json_real(info.beta_p90 / deg));
        bj = cli_put(bj, "p99", json_real(info.beta_p99 / deg));
        root = cli_put(root, "beta", bj);
        json_t *cj = json_object();
        cj = cli_put(cj, "low", json_real(info.harm_clamped_lo));
        cj = cli_put(cj, "high", json_real(info.harm_clamped_hi));
        root = cli_put(root, "radius_clamped", cj);
        json_t *sj = json_object();
        sj = cli_put(sj, "placement", json_real(info.seconds_placement));
        sj = cli_put(sj, "records", json_real(info.seconds_records));
        sj = cli_put(sj, "direct", json_real(ds.seconds));
        sj = cli_put(sj, "threads", json_integer(ds.threads));
        root = cli_put(root, "seconds", sj);
        json_t *uj = json_object();
        uj = cli_put(uj, "direct", json_real(1e6 * ds.seconds / nv));
        uj = cli_put(uj, "records", json_real(1e6 * (info.seconds_records + info.seconds_placement) / nv));
        root = cli_put(root, "us_per_vertex", uj);
        root = cli_put(root, "rounds", json_integer(repeat));
        if (noise_l2 >= 0) root = cli_put(root, "noise_l2", json_real(noise_l2));
        if (refj) {
            root = cli_put(root, "reference", refj);
            refj = NULL;
        }
        json_t *rows = json_array();
        for (int k = 0; k < nm && rows; k++) {
            sh_shade_err ed, ex;
            if ((e = sh_shade_error(nv, M[k].Y, Yd, NULL, &ed)) || (e = sh_shade_error(nv, M[k].Y, Yx, NULL, &ex))) break;
            double t[1000];
            for (int r = 0; r < repeat; r++) ratio[r] = zsec[r] / M[k].sec[r];
            memcpy(t, M[k].sec, sizeof(double) * repeat);
            const double tm = cli_median(t, repeat), tmin = t[0], tmax = t[repeat - 1];
            const double rmed = cli_median(ratio, repeat);
            json_t *r = json_object();
            r = cli_put(r, "method", json_string(M[k].name));
            r = cli_put(r, "beta_lim", M[k].rot.beta_lim > 0 ? json_real(M[k].rot.beta_lim / deg) : json_null());
            r = cli_put(r, "rotations", json_integer(M[k].t.rotations));
            r = cli_put(r, "fallbacks", json_integer(M[k].t.fallbacks));
            r = cli_put(r, "rel_l2", json_real(ed.rel_l2));
            r = cli_put(r, "rel_max", json_real(ed.rel_max));
            r = cli_put(r, "rot_rel_l2", json_real(ex.rel_l2));
            r = cli_put(r, "rot_rel_max", json_real(ex.rel_max));
            if (nref) {
                sh_shade_err er;
                for (int q = 0; q < nref; q++) sub[q] = M[k].Y[rv[q]];
                if ((e = sh_shade_error(nref, sub, ref, se, &er))) { json_decref(r); break; }
                r = cli_put(r, "ref_rel_l2", json_real(er.rel_l2));
            }
            r = cli_put(r, "ns_per_point", json_real(1e9 * tm / nv));
            r = cli_put(r, "ns_per_point_min", json_real(1e9 * tmin / nv));
            r = cli_put(r, "ns_per_point_max", json_real(1e9 * tmax / nv));
            r = cli_put(r, "ns_per_use", tig >= 0 && info.uses > 0 && !M[k].rot.ignore
                                             ? json_real(1e9 * (tm - tig) / (double)info.uses)
                                             : json_null());
            r = cli_put(r, "ratio_zxzxz", json_real(rmed));
            r = cli_put(r, "ratio_zxzxz_min", json_real(ratio[0]));
            r = cli_put(r, "ratio_zxzxz_max", json_real(ratio[repeat - 1]));
            if (!r || json_array_append_new(rows, r)) { json_decref(rows); rows = NULL; }
        }
        root = cli_put(root, "methods", rows);
    }
    json_decref(refj);
    json_decref(desc);
    json_decref(edesc);
    for (int k = 0; k < nm; k++) {
        free(M[k].B);
        free(M[k].Y);
    }
    free(Bd); free(Yd); free(Bx); free(Yx); free(ratio); free(sec); free(zsec); free(msec);
    free(ref); free(se); free(sub); free(rv);
    sh_cache_free(c);
    sh_env_free(env);
    sh_scene_free(s);
    sh_mesh_free(&m);
    if (e) {
        json_decref(root);
        return cli_fail_status(e);
    }
    return cli_emit(root, com.fmt);
}

const cli_command cmd_cache = {"cache", run, "radiance cache: records rotated into each vertex's frame, error and time per method",
                               help, NULL};
