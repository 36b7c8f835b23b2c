/* cmd_shadow_field.c — `shlab shadow-field`: the sphere of the sphere-plane
 * scene as a shadow-field occluder (Wang et al. 2006, Sec. 3.1): its
 * occlusion sampled at one distance and scaled to every plane vertex,
 * against the closed-form transfer, ray-cast visibility and the reference
 * shading.  Logic in src/scene/shadowfield.c. */
#include "cli_scene.h"

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

typedef struct {
    int v[SF_MAX_SAMPLES];
    int n;
} sample_list;
typedef struct {
    sh_sf_scaling scaling;
    int samples;
} sf_picture;
typedef struct {
    double angle; /* in the unit of --degrees */
    int tangent;  /* acos(R/d0) instead */
} sf_cone;

typedef struct {
    cli_scene_input in;
    cli_picture_args pic;
    cli_reference_args ref;
    sample_list samples;
    sf_picture picture;
    sf_cone cone;
    int order, degrees, fmt, reference, bins;
    double d0; /* 0: H */
    const char *png, *rpng, *epng;
} sf_args;

static int parse_cone(const char *opt, const char *s, void *field)
{
    sf_cone *c = field;
    c->tangent = !strcmp(s, "tangent");
    return c->tangent ? 0 : cli_double(opt, s, &c->angle);
}

static int parse_samples(const char *opt, const char *s, void *field)
{
    sample_list *l = field;
    double *v = NULL;
    int n = 0, rc = 0;
    if (cli_doubles(opt, s, &v, &n)) return CLI_EXIT_USAGE;
    if (n < 1 || n > SF_MAX_SAMPLES) rc = cli_fail("%s: give 1..%d values", opt, SF_MAX_SAMPLES);
    for (int k = 0; k < n && !rc; k++) {
        if (!(v[k] == floor(v[k]) && (v[k] == 0 || (v[k] >= 2 && v[k] <= 10000))))
            rc = cli_fail("%s: each value must be 0 or an integer in 2..10000", opt);
        else l->v[k] = (int)v[k];
    }
    if (!rc) l->n = n;
    free(v);
    return rc;
}

/* S[:K]: the scaling pictured and its samples */
static int parse_picture(const char *opt, const char *s, void *field)
{
    sf_picture *p = field;
    char buf[64];
    snprintf(buf, sizeof buf, "%s", s);
    char *colon = strchr(buf, ':');
    if (colon) *colon = 0;
    if (sh_sf_scaling_parse(buf, &p->scaling)) return cli_fail("%s: %s", opt, sh_last_error());
    p->samples = 0;
    if (colon && cli_int(opt, colon + 1, &p->samples)) return CLI_EXIT_USAGE;
    if (p->samples < 0 || p->samples == 1) return cli_fail("%s: samples must be 0 or >= 2", opt);
    if (p->scaling == SH_SF_EXACT && p->samples) return cli_fail("%s: the exact field has no samples", opt);
    return 0;
}

static const cli_opt sf_opts[] = {
    CLI_SCENE_ORDER(sf_args, order, SH_SF_MAX_ORDER, "4", "bands"),
    CLI_REAL(sf_args, d0, "field-distance", "D", 0, INFINITY, CLI_LO_OPEN, NULL,
             "d0 (default H: the nearest plane point)"),
    CLI_CUSTOM(sf_args, cone, "cone-angle", "A|tangent", parse_cone, NULL,
               "cone half-angle (default 45°, radians unless\n--degrees); tangent: acos(R/d0), the cone through\n"
               "the silhouette seen from d0"),
    CLI_CUSTOM(sf_args, samples, "samples", "LIST", parse_samples, "0,2,5,10,40", "k-table sizes of the scaled fields"),
    CLI_FLAG(sf_args, reference, "reference", "compare with the reference shading too"),
    CLI_INT(sf_args, bins, "bins", "K", 1, SF_MAX_BINS, "5", "distance bins"),
    CLI_STRING(sf_args, png, "png", "FILE", "picture: the plane shaded by --picture, the sphere by rays"),
    CLI_STRING(sf_args, rpng, "ray-png", "FILE", "the same with the plane by ray casting"),
    CLI_STRING(sf_args, epng, "error-png", "FILE", "false colour of |B − B_ray| / RMS(B_ray) on the plane"),
    CLI_CUSTOM(sf_args, picture, "picture", "S[:K]", parse_picture, "cone:0", "scaling and samples pictured"),
    CLI_DEGREES(sf_args, degrees, "--cone-angle (and --light angles) in degrees"),
    CLI_FORMAT(sf_args, fmt),
    CLI_GROUP(sf_args, in.scene, cli_scene_opts),
    CLI_DEFAULT("scene", "sphere-plane"),
    CLI_GROUP(sf_args, in.env, cli_env_opts),
    CLI_GROUP(sf_args, in.rays, cli_rays_opts),
    CLI_DEFAULT("rays", "4096"),
    CLI_GROUP(sf_args, pic, cli_picture_opts),
    CLI_DEFAULT("error-max", "0.1"),
    CLI_GROUP(sf_args, ref, cli_reference_opts),
    CLI_END,
};

static const cli_cmd sf_decl = {
    .name = "shadow-field",
    .usage = "shadow-field [--scene sphere-plane[:R,H]] (--probe FILE | --light SPEC)\n"
             "                          [OPTIONS]",
    .about = "Shadow fields (Wang et al. 2006, Sec. 3.1): the occlusion of the sphere\n"
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
             "The scene is sphere-plane[:R,H] (the default; no other scene, no --mesh).\n",
    .opts = sf_opts,
    .notes = "JSON: {\"scene\":{...},\"environment\":{...},\"order\",\"convention\",\"radius\",\"height\",\n"
             "       \"field_distance\",\"cone_angle\",\"units\",\"receivers\",\"kmin\",\"kmax\",\n"
             "       \"ray_vs_closed\",[\"closed_vs_ref\",\"ref_l2\"],\n"
             "       \"fields\":[{\"scaling\",\"samples\",\"rel_l2\",\"rel_max\",\"shadow_rel\",\n"
             "                  \"ray_rel_l2\",[\"ref_rel_l2\"],\"matrices\",\"seconds\"}],\n"
             "       \"bins\":[{\"k_lo\",\"k_hi\",\"vertices\",\"exact\",\"cone\",\"sphere\"}]}\n",
};

static const sh_sf_scaling scalings[3] = {SH_SF_EXACT, SH_SF_CONE, SH_SF_SPHERE};

/* The run.  Arrays over the receivers (the plane vertices pv[0..np)) unless
 * noted; Tr and Tray over every vertex. */
typedef struct {
    const sf_args *a;
    double deg, d0, cone; /* radians */
    int pictures;
    cli_scene_session s;
    int nv, n2, np, *pv;
    double R, Hc;
    double *pos, *nor, *kk;      /* receivers' positions, normals, k = d/d0 */
    double *Tc, *Tr, *Tf, *U, *L; /* closed form, rays, a field's, unshadowed; lighting (Y, R, G, B) */
    double *Bc, *Br, *Bu, *Bf;   /* their shadings */
    double *Tray;                /* pictures: every vertex by rays, kept */
    double *ref, *se;            /* --reference */
    sh_shade_err rvc, cvr;       /* rays against closed; closed against the reference */
    double kmin, kmax;
    double bin_err[3][SF_MAX_BINS], bin_den[3][SF_MAX_BINS];
    int bin_n[SF_MAX_BINS];
    json_t *fields;
} sf_work;

/* Progress of the fields: `nf` fields, each over every receiver. */
typedef struct { cli_progress *p; int field, nf; } field_progress;
static void on_receivers(void *ctx, int done, int total, const char *what)
{
    const field_progress *f = ctx;
    cli_progress_step(f->p, f->field * total + done, f->nf * total, "receivers of the fields");
}

/* What the run will take, from the scene's size before it is built:
 * refused if absurd (rays: at most one set per vertex) or more than the
 * memory available (the mesh twice, Embree's ~100 bytes a triangle, the
 * arrays below). */
static int size_check(const sf_args *a, sh_proc_scene *chk)
{
    long long nvert, ntri;
    chk->res = a->in.scene.res;
    if (sh_proc_size(chk, &nvert, &ntri)) return cli_fail_status(SH_EINVAL);
    const long rays = a->in.rays.rays;
    const double nrays = (double)nvert * (double)rays, n2 = (double)a->order * a->order;
    const double bytes = (double)nvert * (96 + 8 * (11 + 5 * n2 + 2 * a->reference)) + (double)ntri * 124;
    if (nrays > SF_MAX_RAYS)
        return cli_fail("shadow-field: --res %d makes %lld vertices; × --rays %ld that is up to %.2g rays, more "
                        "than the %.2g a run may cast (hours); lower --res or --rays",
                        a->in.scene.res ? a->in.scene.res : SF_DEFAULT_RES, nvert, rays, nrays, SF_MAX_RAYS);
    if (cli_mem_check("shadow-field", bytes, "the scene and its transfer vectors")) return CLI_EXIT_USAGE;
    return 0;
}

/* The options that go together; the field's distance and cone (radians). */
static int validate(const sf_args *a, const cli_parsed *seen, sf_work *w)
{
    if (a->in.scene.mesh) return cli_fail("shadow-field: the occluder is the sphere of --scene sphere-plane (no --mesh)");
    /* options that do not apply are refused, as transfer refuses them */
    w->pictures = a->png || a->rpng || a->epng;
    if (cli_scene_applies("shadow-field", seen, "ref-samples replications", a->reference, "--reference") ||
        cli_scene_applies("shadow-field", seen, "picture", a->png || a->epng, "--png and --error-png") ||
        cli_scene_applies("shadow-field", seen, "error-max", a->epng != NULL, "--error-png") ||
        cli_scene_applies("shadow-field", seen, "view width height", w->pictures,
                          "the pictures (--png, --ray-png, --error-png)"))
        return CLI_EXIT_USAGE;
    w->deg = a->degrees ? M_PI / 180 : 1.0;
    sh_proc_scene chk;
    if (sh_proc_parse(a->in.scene.scene, &chk)) return cli_fail("--scene: %s", sh_last_error());
    if (chk.kind != SH_PROC_SPHERE_PLANE) return cli_fail("shadow-field: needs --scene sphere-plane[:R,H]");
    w->d0 = a->d0 > 0 ? a->d0 : chk.p[1];
    if (!(w->d0 > chk.p[0]))
        return cli_fail("--field-distance: %g must exceed the sphere's radius %g", w->d0, chk.p[0]);
    w->cone = M_PI / 4; /* 45° unless --cone-angle */
    if (a->cone.tangent) w->cone = acos(chk.p[0] / w->d0);
    else if (cli_given(seen, "cone-angle")) w->cone = a->cone.angle * w->deg;
    if (!(w->cone > 0 && w->cone < M_PI))
        return cli_fail("--cone-angle: %g must be in (0, %s)", w->cone / w->deg, a->degrees ? "180" : "π");
    return size_check(a, &chk);
}

/* The receivers (plane vertices: z = 0, normal +z), their closed-form and
 * unshadowed transfer, k; the lighting. */
static int closed_forms(sf_work *w)
{
    const sf_args *a = w->a;
    const int nv = w->nv, n2 = w->n2, order = a->order;
    const double albedo = a->in.rays.albedo;
    const sh_mesh *m = &w->s.mesh;
    const size_t nt = (size_t)nv * n2;
    w->pv = malloc(sizeof(int) * nv);
    w->pos = malloc(sizeof(double) * 3 * nv); w->nor = malloc(sizeof(double) * 3 * nv);
    w->Tc = malloc(sizeof(double) * nt); w->Tr = malloc(sizeof(double) * nt); w->Tf = malloc(sizeof(double) * nt);
    w->U = malloc(sizeof(double) * nt); w->L = malloc(sizeof(double) * 4 * n2);
    w->Bc = malloc(sizeof(double) * nv); w->Br = malloc(sizeof(double) * nv); w->Bu = malloc(sizeof(double) * nv);
    w->Bf = malloc(sizeof(double) * nv); w->kk = malloc(sizeof(double) * nv);
    if (!w->pv || !w->pos || !w->nor || !w->Tc || !w->Tr || !w->Tf || !w->U || !w->L || !w->Bc || !w->Br || !w->Bu ||
        !w->Bf || !w->kk)
        return sh_error(SH_ENOMEM, "out of memory");
    for (int v = 0; v < nv; v++)
        if (m->pos[3 * v + 2] == 0 && m->normal[3 * v + 2] == 1) w->pv[w->np++] = v;
    if (w->np == 0) return sh_error(SH_EINVAL, "shadow-field: the scene has no plane vertices");
    int e = SH_OK;
    for (int k = 0; k < w->np && !e; k++) {
        const double *p = w->pos + 3 * k;
        memcpy(w->pos + 3 * k, m->pos + 3 * w->pv[k], sizeof(double) * 3);
        memcpy(w->nor + 3 * k, m->normal + 3 * w->pv[k], sizeof(double) * 3);
        int known;
        e = sh_proc_closed_form(&w->s.proc, m, w->pv[k], order, SH_CS, albedo, 0, w->Tc + (size_t)k * n2, NULL, &known);
        if (!e && known != order)
            e = sh_error(SH_EINVAL, "shadow-field: plane vertex %d sees the sphere across its horizon (no closed form); "
                         "lower R or raise H", w->pv[k]);
        if (!e) e = sh_transfer_unshadowed(order, SH_CS, albedo, w->nor + 3 * k, w->U + (size_t)k * n2);
        w->kk[k] = sqrt(p[0] * p[0] + p[1] * p[1] + w->Hc * w->Hc) / w->d0;
        cli_progress_step(&w->s.prog, k + 1, w->np, "closed forms");
    }
    if (!e) e = sh_env_project(w->s.env, order, SH_CS, w->L);
    w->kmin = INFINITY;
    w->kmax = 0;
    for (int k = 0; k < w->np; k++) {
        w->kmin = fmin(w->kmin, w->kk[k]);
        w->kmax = fmax(w->kmax, w->kk[k]);
    }
    return e;
}

/* Green's shadowed transfer by rays at the receivers (every vertex for the
 * pictures, kept in Tray); the closed, ray and unshadowed shadings; the
 * reference. */
static int rays_and_reference(sf_work *w)
{
    const sf_args *a = w->a;
    const int nv = w->nv, n2 = w->n2, np = w->np, order = a->order;
    sh_transfer_opts to = cli_scene_transfer_opts(&w->s, &a->in.rays, SH_TRANSFER_SHADOWED, order);
    to.verts = w->pictures ? NULL : w->pv;
    to.nverts = np;
    int e = sh_transfer(w->s.scene, &to, w->Tr, NULL);
    if (!e && w->pictures) {
        if (!(w->Tray = malloc(sizeof(double) * nv * n2))) return sh_error(SH_ENOMEM, "out of memory");
        memcpy(w->Tray, w->Tr, sizeof(double) * nv * n2);
        /* plane rows first, as the other arrays */
        for (int k = 0; k < np; k++) memcpy(w->Tf + (size_t)k * n2, w->Tr + (size_t)w->pv[k] * n2, sizeof(double) * n2);
    }
    if (!e) e = sh_shade(np, order, w->Tc, order, w->L, w->Bc);
    if (!e) e = sh_shade(np, order, w->pictures ? w->Tf : w->Tr, order, w->L, w->Br);
    if (!e) e = sh_shade(np, order, w->U, order, w->L, w->Bu);
    if (!e) e = sh_shade_error(np, w->Br, w->Bc, NULL, &w->rvc);
    if (e || !a->reference) return e;
    const sh_reference_opts ro = cli_scene_reference_opts(&w->s, &a->in.rays, &a->ref);
    w->ref = malloc(sizeof(double) * np);
    w->se = malloc(sizeof(double) * np);
    if (!w->ref || !w->se) return sh_error(SH_ENOMEM, "out of memory");
    e = sh_shade_reference(w->s.scene, w->s.env, NULL, w->pv, np, &ro, w->ref, w->se, NULL);
    if (!e) e = sh_shade_error(np, w->Bc, w->ref, w->se, &w->cvr);
    return e;
}

/* One field: scaling sc[ai] with `samples`; its row in w->fields, its
 * distance bins (samples 0), its transfer into the pictured rows of Tr. */
static int one_field(sf_work *w, int ai, int samples, field_progress *fp)
{
    const sf_args *a = w->a;
    const int np = w->np, n2 = w->n2, order = a->order;
    const double centre[3] = {0, 0, w->Hc};
    sh_sf_opts so = {0};
    so.order = order;
    so.scaling = scalings[ai];
    so.cone_angle = w->cone;
    so.d0 = w->d0;
    so.samples = samples;
    so.albedo = a->in.rays.albedo;
    so.progress = on_receivers;
    so.progress_ctx = fp;
    sh_sf_stats st;
    sh_shade_err ec, er, ef = {0};
    int e;
    if ((e = sh_shadow_field_transfer(&so, centre, w->R, np, w->pos, w->nor, w->Tf, &st))) return e;
    if ((e = sh_shade(np, order, w->Tf, order, w->L, w->Bf))) return e;
    if ((e = sh_shade_error(np, w->Bf, w->Bc, NULL, &ec)) || (e = sh_shade_error(np, w->Bf, w->Br, NULL, &er))) return e;
    if (a->reference && (e = sh_shade_error(np, w->Bf, w->ref, w->se, &ef))) return e;
    double d2 = 0, s2 = 0;
    for (int k = 0; k < np; k++) {
        d2 += (w->Bf[k] - w->Bc[k]) * (w->Bf[k] - w->Bc[k]);
        s2 += (w->Bu[k] - w->Bc[k]) * (w->Bu[k] - w->Bc[k]);
    }
    if (!(s2 > 0)) return sh_error(SH_EINVAL, "shadow-field: the sphere casts no shadow on the plane");
    if (samples == 0)
        for (int k = 0; k < np; k++) {
            int b = w->kmax > w->kmin ? (int)(a->bins * log(w->kk[k] / w->kmin) / log(w->kmax / w->kmin)) : 0;
            if (b >= a->bins) b = a->bins - 1;
            w->bin_err[ai][b] += (w->Bf[k] - w->Bc[k]) * (w->Bf[k] - w->Bc[k]);
            w->bin_den[ai][b] += (w->Bu[k] - w->Bc[k]) * (w->Bu[k] - w->Bc[k]);
            if (ai == 0) w->bin_n[b]++;
        }
    if (w->pictures && scalings[ai] == a->picture.scaling && samples == a->picture.samples) {
        /* the pictured field's shading goes into the plane rows of Tr */
        for (int k = 0; k < np; k++) memcpy(w->Tr + (size_t)w->pv[k] * n2, w->Tf + (size_t)k * n2, sizeof(double) * n2);
    }
    json_t *r = json_object();
    r = cli_put(r, "scaling", json_string(sh_sf_scaling_name(scalings[ai])));
    r = cli_put(r, "samples", json_integer(samples));
    r = cli_put(r, "rel_l2", json_real(ec.rel_l2));
    r = cli_put(r, "rel_max", json_real(ec.rel_max));
    r = cli_put(r, "shadow_rel", json_real(sqrt(d2 / s2)));
    r = cli_put(r, "ray_rel_l2", json_real(er.rel_l2));
    if (a->reference) r = cli_put(r, "ref_rel_l2", json_real(ef.rel_l2));
    r = cli_put(r, "matrices", json_integer(st.matrices));
    r = cli_put(r, "seconds", json_real(st.seconds));
    if (!r || json_array_append_new(w->fields, r)) return sh_error(SH_ENOMEM, "out of memory");
    return SH_OK;
}

/* The fields: exact, then cone and sphere × samples. */
static int fields(sf_work *w)
{
    const sample_list *sl = &w->a->samples;
    if (!(w->fields = json_array())) return sh_error(SH_ENOMEM, "out of memory");
    field_progress fp = {&w->s.prog, 0, 1 + 2 * sl->n};
    int e = SH_OK;
    for (int ai = 0; ai < 3 && !e; ai++)
        for (int q = 0; q < (ai ? sl->n : 1) && !e; q++, fp.field++) e = one_field(w, ai, ai ? sl->v[q] : 0, &fp);
    return e;
}

/* The pictures: every vertex by rays, the plane's rows replaced (Tr), and
 * every vertex by rays (Tray); the error between them. */
static int pictures(sf_work *w)
{
    const sf_args *a = w->a;
    const int nv = w->nv, n2 = w->n2, order = a->order;
    double *col = malloc(sizeof(double) * 3 * nv), *colr = malloc(sizeof(double) * 3 * nv),
           *Y = malloc(sizeof(double) * nv), *Yr = malloc(sizeof(double) * nv), *B = malloc(sizeof(double) * nv);
    int e = (!col || !colr || !Y || !Yr || !B) ? sh_error(SH_ENOMEM, "out of memory") : SH_OK;
    for (int c = 0; c < 4 && !e; c++) {
        if ((e = sh_shade(nv, order, w->Tr, order, w->L + (size_t)c * n2, B))) break;
        for (int v = 0; v < nv; v++) { if (c) col[3 * v + c - 1] = B[v]; else Y[v] = B[v]; }
        if ((e = sh_shade(nv, order, w->Tray, order, w->L + (size_t)c * n2, B))) break;
        for (int v = 0; v < nv; v++) { if (c) colr[3 * v + c - 1] = B[v]; else Yr[v] = B[v]; }
    }
    double expo = 1, r2 = 0, ymax = 0;
    for (int v = 0; !e && v < nv; v++) { r2 += Yr[v] * Yr[v]; ymax = fmax(ymax, Yr[v]); }
    if (ymax > 0) expo = 0.9 / ymax;
    sh_camera cam;
    if (!e) e = sh_camera_frame(&w->s.mesh, a->pic.view, 35, a->pic.width, a->pic.height, &cam);
    if (!e && a->png) e = cli_scene_picture(&w->s, &cam, 3, col, w->s.env, w->s.tmp[0], expo, 0);
    if (!e && a->rpng) e = cli_scene_picture(&w->s, &cam, 3, colr, w->s.env, w->s.tmp[1], expo, 0);
    if (!e && a->epng) {
        const double rms = sqrt(r2 / nv);
        for (int v = 0; v < nv; v++) B[v] = rms > 0 ? fabs(Y[v] - Yr[v]) / rms : 0;
        e = cli_scene_picture(&w->s, &cam, 1, B, NULL, w->s.tmp[2], 1, a->pic.error_max);
    }
    free(col); free(colr); free(Y); free(Yr); free(B);
    return e;
}

static json_t *bins_json(const sf_work *w)
{
    const int nbins = w->a->bins;
    const double kmin = w->kmin, kmax = w->kmax;
    json_t *bins = json_array();
    for (int b = 0; b < nbins && bins; b++) {
        json_t *r = json_object();
        r = cli_put(r, "k_lo", json_real(kmin * pow(kmax / kmin, (double)b / nbins)));
        r = cli_put(r, "k_hi", json_real(kmin * pow(kmax / kmin, (double)(b + 1) / nbins)));
        r = cli_put(r, "vertices", json_integer(w->bin_n[b]));
        for (int ai = 0; ai < 3; ai++)
            r = cli_put(r, sh_sf_scaling_name(scalings[ai]),
                        w->bin_den[ai][b] > 0 ? json_real(sqrt(w->bin_err[ai][b] / w->bin_den[ai][b])) : json_null());
        if (!r || json_array_append_new(bins, r)) { json_decref(bins); bins = NULL; }
    }
    return bins;
}

static json_t *build_result(sf_work *w)
{
    const sf_args *a = w->a;
    json_t *root = cli_scene_session_result(&w->s);
    root = cli_put(root, "order", json_integer(a->order));
    root = cli_put(root, "convention", json_string("cs"));
    root = cli_put(root, "radius", json_real(w->R));
    root = cli_put(root, "height", json_real(w->Hc));
    root = cli_put(root, "field_distance", json_real(w->d0));
    root = cli_put(root, "units", json_string(a->degrees ? "degrees" : "radians"));
    root = cli_put(root, "cone_angle", json_real(w->cone / w->deg));
    root = cli_put(root, "receivers", json_integer(w->np));
    root = cli_put(root, "kmin", json_real(w->kmin));
    root = cli_put(root, "kmax", json_real(w->kmax));
    root = cli_put(root, "ray_vs_closed", json_real(w->rvc.rel_l2));
    if (a->reference) {
        root = cli_put(root, "closed_vs_ref", json_real(w->cvr.rel_l2));
        root = cli_put(root, "ref_l2", json_real(w->cvr.ref_l2));
    }
    root = cli_put(root, "fields", w->fields);
    w->fields = NULL;
    return cli_put(root, "bins", bins_json(w));
}

static void work_free(sf_work *w)
{
    json_decref(w->fields);
    free(w->pv); free(w->pos); free(w->nor); free(w->Tc); free(w->Tr); free(w->Tf); free(w->U); free(w->L);
    free(w->Bc); free(w->Br); free(w->Bu); free(w->Bf); free(w->kk); free(w->ref); free(w->se); free(w->Tray);
    cli_scene_session_close(&w->s);
}

static int run(int argc, char **argv)
{
    sf_args a;
    memset(&a, 0, sizeof a);
    cli_parsed seen;
    int rc = cli_args_parse(&sf_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    sf_work w = {.a = &a, .n2 = a.order * a.order};
    if ((rc = validate(&a, &seen, &w))) return rc;

    /* the pictures: temporaries beside their targets, renamed by cli_emit
     * once the result is out (all or none; cli_out_open) */
    const char *outputs[3] = {a.png, a.rpng, a.epng};
    if ((rc = cli_scene_session_open("shadow-field", &a.in, a.degrees, CLI_SCENE_NEEDS_ENV, outputs, 3, &w.s)))
        return rc;
    w.nv = w.s.mesh.nvert;
    w.R = w.s.proc.p[0];
    w.Hc = w.s.proc.p[1];
    int e = closed_forms(&w);
    if (!e) e = rays_and_reference(&w);
    if (!e) e = fields(&w);
    if (!e && w.pictures) e = pictures(&w);
    json_t *root = e ? NULL : build_result(&w);
    work_free(&w);
    if (e) return cli_fail_status(e);
    return cli_emit(root, (cli_format)a.fmt);
}

const cli_command cmd_shadow_field = {"shadow-field", run,
                                      "shadow field of a sphere sampled at one distance, scaled to the others (Wang)", &sf_decl};
