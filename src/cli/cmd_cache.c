/* cmd_cache.c — `shlab cache`: Křivánek et al.'s radiance cache on a scene:
 * records placed by Ward's criterion, reused at nearby vertices after a
 * rotation into each vertex's frame by each rotation method; shading error
 * against computing every vertex (and against the reference), time per
 * shading point, methods interleaved.  Logic in src/scene/cache.c. */
#include "cli_scene.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern const cli_command cmd_cache;

#define CACHE_MAX_METHODS 12

/* A rotation method of --methods ("ignore": not rotated). */
typedef struct {
    char name[16];
    sh_cache_rot rot;
} cache_method;
typedef struct {
    cache_method m[CACHE_MAX_METHODS];
    int n;
} cache_methods;

typedef struct {
    cli_scene_input in;
    cli_picture_args pic;
    cli_reference_args ref;
    cache_methods methods;
    sh_cache_brdf brdf;
    int order, degrees, fmt, bounce, repeat, noise, reference;
    double a, beta_lim, rmin, rmax; /* beta_lim in the unit of --degrees (0: never) */
    long env_samples;
    const char *png, *dpng, *epng, *pmeth;
} cache_args;

static int parse_methods(const char *opt, const char *s, void *field)
{
    cache_methods *ms = field;
    char **t;
    int nt, rc = 0;
    if (cli_split(opt, s, &t, &nt)) return CLI_EXIT_USAGE;
    ms->n = 0;
    for (int i = 0; i < nt && !rc; i++) {
        const char *tok = t[i];
        if (ms->n == CACHE_MAX_METHODS) { rc = cli_fail("%s: at most %d", opt, CACHE_MAX_METHODS); break; }
        cache_method *x = &ms->m[ms->n];
        memset(x, 0, sizeof *x);
        snprintf(x->name, sizeof x->name, "%s", tok);
        if (!strcmp(tok, "ignore")) x->rot.ignore = 1;
        else if (sh_rot_method_parse(tok, &x->rot.method)) rc = cli_fail("%s: %s", opt, sh_last_error());
        else if (x->rot.method == SH_ROT_Z) rc = cli_fail("%s: z rotates about z only", opt);
        for (int k = 0; k < ms->n && !rc; k++)
            if (!strcmp(ms->m[k].name, tok)) rc = cli_fail("%s: %s given twice", opt, tok);
        if (!rc) ms->n++;
    }
    free(t);
    return rc;
}

static int parse_brdf(const char *opt, const char *s, void *field)
{
    sh_cache_brdf *b = field;
    if (!strcmp(s, "diffuse")) {
        b->phong = 0;
        return 0;
    }
    if (strncmp(s, "phong:", 6)) return cli_fail("%s: expected diffuse or phong:E, got '%s'", opt, s);
    b->phong = 1;
    if (cli_double("--brdf phong:E", s + 6, &b->exponent)) return CLI_EXIT_USAGE;
    if (!(b->exponent > 0 && b->exponent <= 10000)) return cli_fail("%s: phong exponent must be in (0, 10000]", opt);
    return 0;
}

static const cli_opt cache_opts[] = {
    CLI_SCENE_ORDER(cache_args, order, CLI_SCENE_MAX_ORDER, "6", "bands"),
    CLI_REAL(cache_args, a, "allowed-error", "A", 0, 10, CLI_LO_OPEN, "0.2", "Ward's allowed error a"),
    CLI_CUSTOM(cache_args, methods, "methods", "LIST", parse_methods, "ignore,taylor1,taylor1.5,taylor2,zxzxz,ivanic",
               "rotation methods (ignore: none)"),
    CLI_REAL(cache_args, beta_lim, "beta-lim", "B", 0, INFINITY, CLI_LO_OPEN, NULL,
             "Taylor methods hand rotations with β > B to zxzxz\n(Křivánek: β_lim = 1.25a; default: never)"),
    CLI_CUSTOM(cache_args, brdf, "brdf", "diffuse|phong:E", parse_brdf, "diffuse", "the surfaces' BRDF"),
    CLI_FLAG(cache_args, bounce, "bounce", "add one bounce of the direct light (--rays per record)"),
    CLI_LONG(cache_args, env_samples, "env-samples", "S", 16, 1L << 22, "4096", "environment samples per record"),
    CLI_REAL(cache_args, rmin, "rmin", "F", 0, INFINITY, CLI_LO_OPEN, "0.01",
             "lower clamp of R_i, a fraction of the diagonal"),
    CLI_REAL(cache_args, rmax, "rmax", "F", 0, 100, CLI_LO_OPEN, "0.25",
             "upper clamp of R_i, a fraction of the diagonal"),
    CLI_INT(cache_args, repeat, "repeat", "K", 1, 1000, "5", "timing rounds"),
    CLI_FLAG(cache_args, noise, "noise",
             "also compute every vertex with the next seed: the\ndirect computation's own noise, noise_l2 = rel_l2\n"
             "between the two / √2"),
    CLI_INT(cache_args, reference, "reference", "K", 0, INT_MAX, "0",
            "diffuse shading against the reference (direct\nintegration, sh_shade_reference) at K seeded vertices\n"
            "(0: none; not with --bounce or phong)"),
    CLI_STRING(cache_args, png, "png", "FILE", "picture of the cache's shading (--picture-method)"),
    CLI_STRING(cache_args, dpng, "direct-png", "FILE", "picture of every vertex computed directly"),
    CLI_STRING(cache_args, epng, "error-png", "FILE", "false colour of |Y − Y_direct| / RMS(Y_direct)"),
    CLI_STRING(cache_args, pmeth, "picture-method", "M",
               "the method pictured (default: the first listed that\nis not ignore)"),
    CLI_DEGREES(cache_args, degrees, "--beta-lim and the beta statistics in degrees"),
    CLI_FORMAT(cache_args, fmt),
    CLI_GROUP(cache_args, in.scene, cli_scene_opts),
    CLI_GROUP(cache_args, in.env, cli_env_opts),
    CLI_GROUP(cache_args, in.rays, cli_rays_opts),
    CLI_GROUP(cache_args, pic, cli_picture_opts),
    CLI_DEFAULT("error-max", "0.1"),
    CLI_GROUP(cache_args, ref, cli_reference_opts),
    CLI_END,
};

static const cli_cmd cache_decl = {
    .name = "cache",
    .usage = "cache (--mesh FILE | --scene SPEC) (--probe FILE | --light SPEC) [OPTIONS]",
    .about = "A radiance cache (Křivánek et al. 2005, Sec. 4.2): the incident radiance\n"
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
             "model_ns_per_rotation: the cost model's figure for the method (one\n"
             "rotation from a matrix, set + one apply, double; as `shlab plan` costs it).\n"
             "\n"
             "--view is the camera: Phong's eye and the pictures'.  --seed seeds the\n"
             "placement and the rays.\n",
    .opts = cache_opts,
    .notes = "JSON: {\"scene\"|\"mesh\":{...},\"environment\":{...},\"order\",\"convention\",\n"
             "       \"allowed_error\",\"brdf\",\"bounce\",\"albedo\",\"vertices\",\"records\",\"uses\",\n"
             "       \"uses_per_vertex\",\"beta\":{\"units\",\"max\",\"mean\",\"p50\",\"p90\",\"p99\"},\n"
             "       \"radius_clamped\":{\"low\",\"high\"},\"seconds\":{\"placement\",\"records\",\n"
             "       \"direct\",\"threads\"},\"us_per_vertex\":{\"direct\",\"records\"},\"rounds\",\n"
             "       [\"noise_l2\"],[\"reference\":{\"vertices\",\"ref_l2\",\"direct_rel_l2\"}],\n"
             "       \"methods\":[{\"method\",\"beta_lim\",\"rotations\",\"fallbacks\",\"rel_l2\",\n"
             "       \"rel_max\",\"rot_rel_l2\",\"rot_rel_max\",[\"ref_rel_l2\"],\"ns_per_point\",\n"
             "       \"ns_per_point_min\",\"ns_per_point_max\",\"ns_per_use\",\"model_ns_per_rotation\",\"ratio_zxzxz\",\n"
             "       \"ratio_zxzxz_min\",\"ratio_zxzxz_max\"}]}\n",
};

/* A method's shading and timing. */
typedef struct {
    char name[16];
    sh_cache_rot rot;
    double *B, *Y; /* RGB and luminance at every vertex */
    sh_cache_timing t;
    double *sec; /* per round */
} meth;

/* The run. */
typedef struct {
    const cache_args *a;
    double deg;
    meth M[CACHE_MAX_METHODS];
    int nm, pic; /* methods; the one pictured (-1: none) */
    cli_scene_session s;
    sh_camera cam;
    sh_cache_opts co;
    sh_cache *c;
    sh_cache_info info;
    sh_transfer_stats ds;
    int nv;
    double *Bd, *Yd, *Bx, *Yx; /* every vertex directly; the cache with the exact rotation */
    double *ratio, *sec, *zsec, *msec;
    double noise_l2; /* -1: not measured */
    json_t *refj;
    double *ref, *se, *sub; /* the reference at the subset rv[0..nref) */
    int *rv, nref;
} cache_work;

/* The options that go together, each method's β limit, the method pictured. */
static int validate(const cache_args *a, const cli_parsed *seen, cache_work *w)
{
    w->deg = a->degrees ? M_PI / 180 : 1.0;
    const double beta_lim = a->beta_lim * w->deg;
    if (beta_lim > M_PI) return cli_fail("--beta-lim: must be <= π");
    if (a->rmin >= a->rmax) return cli_fail("--rmin must be below --rmax");
    if (a->reference && (a->bounce || a->brdf.phong))
        return cli_fail("cache: --reference judges diffuse direct light only (not with --bounce or phong)");
    /* options that do not apply are refused, as transfer refuses them */
    int approx = 0;
    for (int k = 0; k < a->methods.n; k++)
        approx |= !a->methods.m[k].rot.ignore && !sh_rot_method_is_exact(a->methods.m[k].rot.method);
    const int pictures = a->png || a->dpng || a->epng;
    if (cli_scene_applies("cache", seen, "rays", a->bounce, "--bounce (rays of the bounce)") ||
        cli_scene_applies("cache", seen, "ref-samples replications", a->reference > 0, "--reference K") ||
        cli_scene_applies("cache", seen, "picture-method", a->png || a->epng, "--png and --error-png") ||
        cli_scene_applies("cache", seen, "error-max", a->epng != NULL, "--error-png") ||
        cli_scene_applies("cache", seen, "width height", pictures, "the pictures (--png, --direct-png, --error-png)") ||
        cli_scene_applies("cache", seen, "view", pictures || a->brdf.phong, "the pictures and --brdf phong (the eye)") ||
        cli_scene_applies("cache", seen, "beta-lim", approx, "the Taylor methods in --methods"))
        return CLI_EXIT_USAGE;
    w->nm = a->methods.n;
    w->pic = -1;
    for (int k = 0; k < w->nm; k++) {
        meth *m = &w->M[k];
        snprintf(m->name, sizeof m->name, "%s", a->methods.m[k].name);
        m->rot = a->methods.m[k].rot;
        m->rot.beta_lim = sh_rot_method_is_exact(m->rot.method) || m->rot.ignore ? 0 : beta_lim;
        if (!m->rot.ignore && a->order > sh_rot_method_max_order(m->rot.method))
            return cli_fail("cache: %s accepts orders up to %d", m->name, sh_rot_method_max_order(m->rot.method));
        if (a->pmeth ? !strcmp(m->name, a->pmeth) : (w->pic < 0 && !m->rot.ignore)) w->pic = k;
    }
    if ((a->png || a->epng) && w->pic < 0)
        return cli_fail("cache: --picture-method %s is not among --methods", a->pmeth ? a->pmeth : "(none but ignore)");
    return 0;
}

/* The cache's options; the camera (Phong's eye, the pictures); the arrays. */
static int setup(cache_work *w)
{
    const cache_args *a = w->a;
    sh_cache_opts *co = &w->co;
    co->order = a->order;
    co->a = a->a;
    co->albedo = a->in.rays.albedo;
    co->seed = (unsigned long)a->in.rays.seed;
    co->rays = a->in.rays.rays;
    co->env_samples = a->env_samples;
    co->bounce = a->bounce;
    co->rmin = a->rmin;
    co->rmax = a->rmax;
    co->brdf = a->brdf;
    co->threads = a->in.rays.threads;
    co->progress = cli_progress_step;
    co->progress_ctx = &w->s.prog;
    int e = sh_camera_frame(&w->s.mesh, a->pic.view, 35, a->pic.width, a->pic.height, &w->cam);
    for (int k = 0; k < 3; k++) co->brdf.eye[k] = w->cam.eye[k];
    const size_t nv = (size_t)w->nv, nr = (size_t)a->repeat * (CACHE_MAX_METHODS + 1);
    w->Bd = malloc(sizeof(double) * 3 * nv);
    w->Yd = malloc(sizeof(double) * nv);
    w->Bx = malloc(sizeof(double) * 3 * nv);
    w->Yx = malloc(sizeof(double) * nv);
    w->ratio = malloc(sizeof(double) * nr);
    w->sec = malloc(sizeof(double) * nr);
    w->zsec = malloc(sizeof(double) * (size_t)a->repeat);
    w->msec = malloc(sizeof(double) * (size_t)a->repeat * w->nm);
    int ok = w->Bd && w->Yd && w->Bx && w->Yx && w->ratio && w->sec && w->zsec && w->msec;
    for (int k = 0; k < w->nm; k++) {
        w->M[k].B = malloc(sizeof(double) * 3 * nv);
        w->M[k].Y = malloc(sizeof(double) * nv);
        ok = ok && w->M[k].B && w->M[k].Y;
    }
    if (!e && !ok) e = sh_error(SH_ENOMEM, "out of memory");
    return e;
}

/* The cache; every vertex directly; the cache by the exact rotation (the
 * baseline of each method's rotation error); each method's shading, then
 * their timing (sh_cache_bench: the methods and an extra zxzxz, the
 * baseline of the per-round ratios, interleaved; ≥ 20 ms of CPU each). */
static int shade_and_time(cache_work *w)
{
    const cache_args *a = w->a;
    const int nv = w->nv, nm = w->nm, repeat = a->repeat;
    int e = sh_cache_create(w->s.scene, w->s.env, &w->co, &w->c);
    if (!e) e = sh_cache_info_get(w->c, &w->info);
    if (!e) e = sh_cache_shade_direct(w->c, w->co.seed, w->s.threads, w->Bd, &w->ds);
    if (!e) sh_rgb_luminance(nv, w->Bd, w->Yd);
    const sh_cache_rot exact = {SH_ROT_ZXZXZ, 0, 0};
    if (!e) e = sh_cache_shade(w->c, &exact, 1, w->Bx, NULL);
    if (!e) sh_rgb_luminance(nv, w->Bx, w->Yx);
    sh_cache_rot rots[CACHE_MAX_METHODS + 1];
    for (int k = 0; k < nm; k++) rots[k] = w->M[k].rot;
    rots[nm] = exact;
    for (int k = 0; k < nm && !e; k++) e = sh_cache_shade(w->c, &w->M[k].rot, 1, w->M[k].B, &w->M[k].t);
    if (e) return e;
    if (!a->in.rays.quiet) fprintf(stderr, "cache: timing, %d rounds of %d loops\n", repeat, nm + 1);
    if ((e = sh_cache_bench(w->c, rots, nm + 1, repeat, 0.02, w->sec))) return e;
    /* sec is round-major: sec[r·(nm+1) + k] */
    for (int r = 0; r < repeat; r++) {
        w->zsec[r] = w->sec[(size_t)r * (nm + 1) + nm];
        for (int k = 0; k < nm; k++) w->msec[(size_t)k * repeat + r] = w->sec[(size_t)r * (nm + 1) + k];
    }
    for (int k = 0; k < nm; k++) {
        w->M[k].sec = w->msec + (size_t)k * repeat;
        sh_rgb_luminance(nv, w->M[k].B, w->M[k].Y);
    }
    return SH_OK;
}

/* --noise: every vertex again with the next seed, two independent estimates. */
static int direct_noise(cache_work *w)
{
    const int nv = w->nv;
    double *B2 = malloc(sizeof(double) * 3 * nv), *Y2 = malloc(sizeof(double) * nv);
    int e = (!B2 || !Y2) ? sh_error(SH_ENOMEM, "out of memory") : SH_OK;
    if (!e) e = sh_cache_shade_direct(w->c, w->co.seed + 1, w->s.threads, B2, NULL);
    if (!e) {
        sh_rgb_luminance(nv, B2, Y2);
        sh_shade_err er;
        if (!(e = sh_shade_error(nv, Y2, w->Yd, NULL, &er))) w->noise_l2 = er.rel_l2 / sqrt(2.0);
    }
    free(B2);
    free(Y2);
    return e;
}

/* --reference K: the reference at a seeded subset of K vertices, against
 * the direct computation there. */
static int reference_subset(cache_work *w)
{
    const cache_args *a = w->a;
    const int nv = w->nv, K = a->reference < nv ? a->reference : nv;
    w->rv = malloc(sizeof(int) * nv);
    w->ref = malloc(sizeof(double) * K);
    w->se = malloc(sizeof(double) * K);
    w->sub = malloc(sizeof(double) * K);
    w->nref = K;
    if (!w->rv || !w->ref || !w->se || !w->sub) return sh_error(SH_ENOMEM, "out of memory");
    /* a seeded subset: partial Fisher-Yates (splitmix stream) */
    uint64_t x = (uint64_t)w->co.seed * 0x9E3779B97F4A7C15ull + 12345;
    for (int v = 0; v < nv; v++) w->rv[v] = v;
    for (int k = 0; k < K; k++) {
        x += 0x9E3779B97F4A7C15ull;
        uint64_t z = x;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        const int j = k + (int)((z >> 11) * 0x1.0p-53 * (nv - k));
        const int t = w->rv[k];
        w->rv[k] = w->rv[j];
        w->rv[j] = t;
    }
    const sh_reference_opts ro = cli_scene_reference_opts(&w->s, &a->in.rays, &a->ref);
    sh_transfer_stats rs;
    sh_shade_err er;
    int e = sh_shade_reference(w->s.scene, w->s.env, NULL, w->rv, K, &ro, w->ref, w->se, &rs);
    if (!e) {
        for (int k = 0; k < K; k++) w->sub[k] = w->Yd[w->rv[k]];
        e = sh_shade_error(K, w->sub, w->ref, w->se, &er);
    }
    if (!e) {
        w->refj = json_object();
        w->refj = cli_put(w->refj, "vertices", json_integer(K));
        w->refj = cli_put(w->refj, "ref_l2", json_real(er.ref_l2));
        w->refj = cli_put(w->refj, "direct_rel_l2", json_real(er.rel_l2));
    }
    return e;
}

/* The pictures: the cache's shading by the pictured method, every vertex
 * directly (both at the direct shading's exposure), and the error. */
static int pictures(cache_work *w)
{
    const cache_args *a = w->a;
    const int nv = w->nv;
    double expo = 1;
    int e = cli_scene_exposure(w->Yd, nv, &expo);
    if (!e && a->png) e = cli_scene_picture(&w->s, &w->cam, 3, w->M[w->pic].B, w->s.env, w->s.tmp[0], expo, 0);
    if (!e && a->dpng) e = cli_scene_picture(&w->s, &w->cam, 3, w->Bd, w->s.env, w->s.tmp[1], expo, 0);
    if (!e && a->epng) {
        double *Yc = malloc(sizeof(double) * nv), r2 = 0;
        if (!Yc) return sh_error(SH_ENOMEM, "out of memory");
        for (int v = 0; v < nv; v++) r2 += w->Yd[v] * w->Yd[v];
        const double rms = sqrt(r2 / nv);
        for (int v = 0; v < nv; v++) Yc[v] = rms > 0 ? fabs(w->M[w->pic].Y[v] - w->Yd[v]) / rms : 0;
        e = cli_scene_picture(&w->s, &w->cam, 1, Yc, NULL, w->s.tmp[2], 1, a->pic.error_max);
        free(Yc);
    }
    return e;
}

/* Method k's row: its errors (against the direct computation, the exact
 * rotation, the reference) and its time.  tig: the ignore loop's median
 * time (-1: not timed). */
static int method_row(cache_work *w, int k, double tig, json_t **row)
{
    const int nv = w->nv, repeat = w->a->repeat;
    const meth *m = &w->M[k];
    sh_shade_err ed, ex, er;
    int e;
    if ((e = sh_shade_error(nv, m->Y, w->Yd, NULL, &ed)) || (e = sh_shade_error(nv, m->Y, w->Yx, NULL, &ex))) return e;
    if (w->nref) {
        for (int q = 0; q < w->nref; q++) w->sub[q] = m->Y[w->rv[q]];
        if ((e = sh_shade_error(w->nref, w->sub, w->ref, w->se, &er))) return e;
    }
    double t[1000];
    for (int r = 0; r < repeat; r++) w->ratio[r] = w->zsec[r] / m->sec[r];
    memcpy(t, m->sec, sizeof(double) * repeat);
    const double tm = cli_median(t, repeat), tmin = t[0], tmax = t[repeat - 1];
    const double rmed = cli_median(w->ratio, repeat);
    json_t *r = json_object();
    r = cli_put(r, "method", json_string(m->name));
    r = cli_put(r, "beta_lim", m->rot.beta_lim > 0 ? json_real(m->rot.beta_lim / w->deg) : json_null());
    r = cli_put(r, "rotations", json_integer(m->t.rotations));
    r = cli_put(r, "fallbacks", json_integer(m->t.fallbacks));
    r = cli_put(r, "rel_l2", json_real(ed.rel_l2));
    r = cli_put(r, "rel_max", json_real(ed.rel_max));
    r = cli_put(r, "rot_rel_l2", json_real(ex.rel_l2));
    r = cli_put(r, "rot_rel_max", json_real(ex.rel_max));
    if (w->nref) r = cli_put(r, "ref_rel_l2", json_real(er.rel_l2));
    r = cli_put(r, "ns_per_point", json_real(1e9 * tm / nv));
    r = cli_put(r, "ns_per_point_min", json_real(1e9 * tmin / nv));
    r = cli_put(r, "ns_per_point_max", json_real(1e9 * tmax / nv));
    r = cli_put(r, "ns_per_use", tig >= 0 && w->info.uses > 0 && !m->rot.ignore
                                     ? json_real(1e9 * (tm - tig) / (double)w->info.uses)
                                     : json_null());
    /* the cost model's figure for one rotation on this path (matrix, double,
     * set + one apply; the cache applies three channels): the planner's costs */
    sh_cost mc;
    const int have_model = !m->rot.ignore && sh_cost_model(w->a->order, m->rot.method, SH_PREC_DOUBLE,
                                                           SH_BENCH_INPUT_MATRIX, SH_BENCH_PER_ROTATION, &mc) == SH_OK;
    r = cli_put(r, "model_ns_per_rotation", have_model ? json_real(mc.ns) : json_null());
    r = cli_put(r, "ratio_zxzxz", json_real(rmed));
    r = cli_put(r, "ratio_zxzxz_min", json_real(w->ratio[0]));
    r = cli_put(r, "ratio_zxzxz_max", json_real(w->ratio[repeat - 1]));
    *row = r;
    return SH_OK;
}

/* The cache as a whole: records, uses, β between the normals, times. */
static json_t *cache_summary(cache_work *w, json_t *root)
{
    const cache_args *a = w->a;
    const sh_cache_info *info = &w->info;
    const double deg = w->deg;
    const int nv = w->nv;
    root = cli_put(root, "order", json_integer(a->order));
    root = cli_put(root, "convention", json_string("cs"));
    root = cli_put(root, "allowed_error", json_real(a->a));
    char bd[64];
    if (a->brdf.phong) snprintf(bd, sizeof bd, "phong:%g", a->brdf.exponent);
    else snprintf(bd, sizeof bd, "diffuse");
    root = cli_put(root, "brdf", json_string(bd));
    root = cli_put(root, "bounce", json_boolean(a->bounce));
    root = cli_put(root, "albedo", json_real(w->co.albedo));
    root = cli_put(root, "vertices", json_integer(nv));
    root = cli_put(root, "records", json_integer(info->records));
    root = cli_put(root, "uses", json_integer(info->uses));
    root = cli_put(root, "uses_per_vertex", json_real(info->mean_uses));
    json_t *bj = json_object();
    bj = cli_put(bj, "units", json_string(a->degrees ? "degrees" : "radians"));
    bj = cli_put(bj, "max", json_real(info->beta_max / deg));
    bj = cli_put(bj, "mean", json_real(info->beta_mean / deg));
    bj = cli_put(bj, "p50", json_real(info->beta_p50 / deg));
    bj = cli_put(bj, "p90", json_real(info->beta_p90 / deg));
    bj = cli_put(bj, "p99", json_real(info->beta_p99 / deg));
    root = cli_put(root, "beta", bj);
    json_t *cj = json_object();
    cj = cli_put(cj, "low", json_real(info->harm_clamped_lo));
    cj = cli_put(cj, "high", json_real(info->harm_clamped_hi));
    root = cli_put(root, "radius_clamped", cj);
    json_t *sj = json_object();
    sj = cli_put(sj, "placement", json_real(info->seconds_placement));
    sj = cli_put(sj, "records", json_real(info->seconds_records));
    sj = cli_put(sj, "direct", json_real(w->ds.seconds));
    sj = cli_put(sj, "threads", json_integer(w->ds.threads));
    root = cli_put(root, "seconds", sj);
    json_t *uj = json_object();
    uj = cli_put(uj, "direct", json_real(1e6 * w->ds.seconds / nv));
    uj = cli_put(uj, "records", json_real(1e6 * (info->seconds_records + info->seconds_placement) / nv));
    root = cli_put(root, "us_per_vertex", uj);
    return cli_put(root, "rounds", json_integer(a->repeat));
}

static int build_result(cache_work *w, json_t **out)
{
    double tig = -1; /* the ignore loop's median time */
    for (int k = 0; k < w->nm; k++)
        if (w->M[k].rot.ignore) {
            double t[1000];
            memcpy(t, w->M[k].sec, sizeof(double) * w->a->repeat);
            tig = cli_median(t, w->a->repeat);
        }
    json_t *root = cache_summary(w, cli_scene_session_result(&w->s));
    if (w->noise_l2 >= 0) root = cli_put(root, "noise_l2", json_real(w->noise_l2));
    if (w->refj) {
        root = cli_put(root, "reference", w->refj);
        w->refj = NULL;
    }
    json_t *rows = json_array();
    int e = SH_OK;
    for (int k = 0; k < w->nm && rows && !e; k++) {
        json_t *r = NULL;
        if (!(e = method_row(w, k, tig, &r)) && (!r || json_array_append_new(rows, r))) {
            json_decref(rows);
            rows = NULL;
        }
    }
    root = cli_put(root, "methods", rows);
    if (e) json_decref(root);
    *out = e ? NULL : root;
    return e;
}

static void work_free(cache_work *w)
{
    json_decref(w->refj);
    for (int k = 0; k < w->nm; k++) {
        free(w->M[k].B);
        free(w->M[k].Y);
    }
    free(w->Bd); free(w->Yd); free(w->Bx); free(w->Yx); free(w->ratio); free(w->sec); free(w->zsec); free(w->msec);
    free(w->ref); free(w->se); free(w->sub); free(w->rv);
    sh_cache_free(w->c);
    cli_scene_session_close(&w->s);
}

static int run(int argc, char **argv)
{
    cache_args a;
    memset(&a, 0, sizeof a);
    cli_parsed seen;
    int rc = cli_args_parse(&cache_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    cache_work w = {.a = &a, .noise_l2 = -1};
    if ((rc = validate(&a, &seen, &w))) return rc;

    /* the pictures are written as temporaries beside their targets, renamed
     * by cli_emit once the result is out: all or none (cli_out_open) */
    const char *outputs[3] = {a.png, a.dpng, a.epng};
    if ((rc = cli_scene_session_open("cache", &a.in, a.degrees, CLI_SCENE_NEEDS_ENV, outputs, 3, &w.s))) return rc;
    w.nv = w.s.mesh.nvert;
    int e = setup(&w);
    if (!e) e = shade_and_time(&w);
    if (!e && a.noise) e = direct_noise(&w);
    if (!e && a.reference) e = reference_subset(&w);
    if (!e && (a.png || a.dpng || a.epng)) e = pictures(&w);
    json_t *root = NULL;
    if (!e) e = build_result(&w, &root);
    work_free(&w);
    if (e) return cli_fail_status(e);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_cache = {"cache", run,
                               "radiance cache: records rotated into each vertex's frame, error and time per method", &cache_decl};
