/* test_scene.c — meshes (assimp), rays (Embree), procedural scenes against
 * their closed forms, Green's transfer (closed form against an exact
 * hemisphere quadrature, Monte Carlo against the closed form within its own
 * standard error, the furnace), the reference shading, pictures. */
#include "testutil.h"

#include <png.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene_internal.h"

static char tmpdir[256];

static const char *tmp_file(const char *name, const char *text)
{
    static char path[8][512];
    static int k = 0;
    char *p = path[k++ % 8];
    if (!tmpdir[0]) {
        snprintf(tmpdir, sizeof tmpdir, "/tmp/shlab-test-scene.XXXXXX");
        ck_assert_ptr_nonnull(mkdtemp(tmpdir));
    }
    snprintf(p, 512, "%s/%s", tmpdir, name);
    if (text) {
        FILE *f = fopen(p, "w");
        ck_assert_ptr_nonnull(f);
        fputs(text, f);
        fclose(f);
    }
    return p;
}

/* a unit square in the plane z = 0 as two triangles, front +z */
static const char *square_obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
static const char *square_ply =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

/* ------------------------------------------------------------ meshes */

START_TEST(test_mesh_ply_obj_same)
{
    sh_mesh a, b;
    sh_mesh_report ra, rb;
    ck_assert_int_eq(sh_mesh_load(tmp_file("sq.obj", square_obj), 0, &a, &ra), SH_OK);
    ck_assert_int_eq(sh_mesh_load(tmp_file("sq.ply", square_ply), 0, &b, &rb), SH_OK);
    ck_assert_int_eq(a.ntri, 2);
    ck_assert_int_eq(b.ntri, 2);
    ck_assert_int_eq(a.nvert, 4);
    ck_assert_int_eq(b.nvert, 4);
    /* no normals in the files: computed, and for a flat square they are +z */
    ck_assert_int_eq(ra.normals_computed, 1);
    for (int v = 0; v < 4; v++) {
        ck_close(a.normal[3 * v + 2], 1.0, TOL0, 1, "obj normal z %d", v);
        ck_close(b.normal[3 * v + 2], 1.0, TOL0, 1, "ply normal z %d", v);
    }
    ck_assert_int_eq(ra.boundary_edges, 4);
    ck_assert_int_eq(ra.nonmanifold_edges, 0);
    /* same area from both readers */
    double area[2] = {0, 0};
    const sh_mesh *ms[2] = {&a, &b};
    for (int k = 0; k < 2; k++)
        for (int t = 0; t < ms[k]->ntri; t++) {
            const double *p = ms[k]->pos + 3 * ms[k]->tri[3 * t], *q = ms[k]->pos + 3 * ms[k]->tri[3 * t + 1],
                         *r = ms[k]->pos + 3 * ms[k]->tri[3 * t + 2];
            area[k] += 0.5 * fabs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
        }
    ck_close(area[0], 1.0, TOL0, 1, "obj area");
    ck_close(area[1], 1.0, TOL0, 1, "ply area");
    sh_mesh_free(&a);
    sh_mesh_free(&b);
}
END_TEST

START_TEST(test_mesh_errors)
{
    sh_mesh m;
    sh_mesh_report r;
    /* missing file */
    ck_assert_int_eq(sh_mesh_load("/nonexistent/dir/x.ply", 0, &m, &r), SH_EIO);
    ck_assert_ptr_nonnull(strstr(sh_last_error(), "x.ply"));
    /* a format no reader knows */
    ck_assert_int_eq(sh_mesh_load(tmp_file("junk.xyzzy", "this is not a mesh\n\x01\x02\n"), 0, &m, &r), SH_EFORMAT);
    ck_assert_ptr_null(strchr(sh_last_error(), '\n'));
    /* empty: vertices but no faces */
    ck_assert_int_eq(sh_mesh_load(tmp_file("empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), 0, &m, &r), SH_EFORMAT);
    /* only a degenerate triangle */
    ck_assert_int_eq(sh_mesh_load(tmp_file("degen.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), 0, &m, &r), SH_EFORMAT);
    ck_assert_ptr_nonnull(strstr(sh_last_error(), "degenerate"));
    /* one good and one degenerate triangle: the degenerate one removed */
    ck_assert_int_eq(sh_mesh_load(tmp_file("degen2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n"), 0, &m, &r),
                     SH_OK);
    ck_assert_int_eq(m.ntri, 1);
    ck_assert_int_eq(r.degenerate_removed, 1);
    ck_assert_int_eq(r.unused_removed, 1);
    sh_mesh_free(&m);
    /* three triangles on one edge: non-manifold, refused unless allowed */
    const char *fan = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    ck_assert_int_eq(sh_mesh_load(tmp_file("fan.obj", fan), 0, &m, &r), SH_EFORMAT);
    ck_assert_ptr_nonnull(strstr(sh_last_error(), "non-manifold"));
    ck_assert_int_eq(sh_mesh_load(tmp_file("fan.obj", NULL), SH_MESH_ALLOW_NONMANIFOLD, &m, &r), SH_OK);
    ck_assert_int_eq(r.nonmanifold_edges, 1);
    sh_mesh_free(&m);
    /* NaN vertex (in memory: a file reader may not even parse it) */
    double pos[9] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
    int tri[3] = {0, 1, 2};
    sh_mesh bad = {3, 1, malloc(sizeof pos), NULL, malloc(sizeof tri)};
    memcpy(bad.pos, pos, sizeof pos);
    memcpy(bad.tri, tri, sizeof tri);
    ck_assert_int_eq(sh_mesh_check(&bad, 0, &r), SH_EFORMAT);
    ck_assert_ptr_nonnull(strstr(sh_last_error(), "non-finite"));
    /* Embree would drop it silently: the scene refuses it too */
    double nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    bad.normal = nrm;
    sh_scene *s = NULL;
    ck_assert_int_eq(sh_scene_create(&bad, 1, &s), SH_EINVAL);
    ck_assert_ptr_null(s);
    bad.normal = NULL;
    /* index out of range */
    bad.pos[7] = 1;
    bad.tri[2] = 7;
    ck_assert_int_eq(sh_mesh_check(&bad, 0, &r), SH_EFORMAT);
    sh_mesh_free(&bad);
}
END_TEST

START_TEST(test_mesh_real_models)
{
    const char *ply = "data/models/Wuson.ply", *obj = "data/models/WusonOBJ.obj";
    if (access(ply, R_OK) || access(obj, R_OK)) {
        fprintf(stderr, "test_mesh_real_models: SKIPPED — no %s or %s (run `make models`)\n", ply, obj);
        return;
    }
    /* the same model in two formats (two files, two readers): the same
     * triangles, the same bounding box and area */
    sh_mesh a, b;
    sh_mesh_report ra, rb;
    ck_assert_int_eq(sh_mesh_load(ply, SH_MESH_Y_UP, &a, &ra), SH_OK);
    ck_assert_int_eq(sh_mesh_load(obj, SH_MESH_Y_UP, &b, &rb), SH_OK);
    ck_assert_int_eq(a.ntri, b.ntri);
    for (int k = 0; k < 3; k++) {
        ck_close(ra.bbox_min[k], rb.bbox_min[k], 1e-5, 1, "bbox min %d", k);
        ck_close(ra.bbox_max[k], rb.bbox_max[k], 1e-5, 1, "bbox max %d", k);
    }
    ck_assert(ra.bbox_min[2] > -0.01); /* y up turned to z up: the feet at z = 0 */
    sh_mesh_free(&a);
    sh_mesh_free(&b);
}
END_TEST

/* ------------------------------------------------------------ rays */

START_TEST(test_rays_square)
{
    sh_mesh m;
    ck_assert_int_eq(sh_mesh_load(tmp_file("sq2.obj", square_obj), 0, &m, NULL), SH_OK);
    sh_scene *s;
    ck_assert_int_eq(sh_scene_create(&m, 1, &s), SH_OK);
    /* a ray straight down at (0.25, 0.5) from height 2: t = 2, front */
    const double org[3] = {0.25, 0.5, 2}, down[3] = {0, 0, -3}, up[3] = {0, 0, 1};
    sh_hit h;
    ck_assert_int_eq(sh_scene_intersect(s, org, down, 0, INFINITY, &h), SH_OK);
    ck_assert_int_eq(h.hit, 1);
    ck_close(h.t, 2.0, 1e-6, 1, "t");
    ck_assert_int_eq(h.front, 1);
    /* the barycentrics reproduce the hit point */
    const int *c = m.tri + 3 * h.tri;
    for (int k = 0; k < 2; k++) {
        const double x = (1 - h.u - h.v) * m.pos[3 * c[0] + k] + h.u * m.pos[3 * c[1] + k] + h.v * m.pos[3 * c[2] + k];
        ck_close(x, org[k], 1e-6, 1, "barycentric %d", k);
    }
    int occ;
    ck_assert_int_eq(sh_scene_occluded(s, org, down, 0, INFINITY, &occ), SH_OK);
    ck_assert_int_eq(occ, 1);
    ck_assert_int_eq(sh_scene_occluded(s, org, down, 0, 1.5, &occ), SH_OK); /* stops short */
    ck_assert_int_eq(occ, 0);
    ck_assert_int_eq(sh_scene_occluded(s, org, up, 0, INFINITY, &occ), SH_OK);
    ck_assert_int_eq(occ, 0);
    /* from below: the back face */
    const double below[3] = {0.75, 0.5, -1};
    ck_assert_int_eq(sh_scene_intersect(s, below, up, 0, INFINITY, &h), SH_OK);
    ck_assert_int_eq(h.hit, 1);
    ck_assert_int_eq(h.front, 0);
    /* bad rays: one error line, no crash */
    const double nan3[3] = {NAN, 0, 0}, zero[3] = {0, 0, 0};
    ck_assert_int_eq(sh_scene_occluded(s, org, nan3, 0, INFINITY, &occ), SH_EINVAL);
    ck_assert_int_eq(sh_scene_intersect(s, org, zero, 0, INFINITY, &h), SH_EINVAL);
    ck_assert_int_eq(sh_scene_occluded(s, org, down, 2, 1, &occ), SH_EINVAL);
    sh_scene_free(s);
    sh_mesh_free(&m);
}
END_TEST

START_TEST(test_tangent_frame)
{
    uint64_t x = 42;
    for (int k = 0; k < 200; k++) {
        double n[3];
        if (k == 0) { n[0] = 0; n[1] = 0; n[2] = -1; }
        else if (k == 1) { n[0] = 0; n[1] = 0; n[2] = 1; }
        else {
            const double z = 2 * sh__uniform(&x) - 1, ph = 2 * M_PI * sh__uniform(&x), r = sqrt(1 - z * z);
            n[0] = r * cos(ph); n[1] = r * sin(ph); n[2] = z;
        }
        double M[9];
        sh__tangent_frame(n, M);
        for (int i = 0; i < 3; i++) {
            ck_close(M[3 * i + 2], n[i], TOL0, 1, "third column = n");
            for (int j = 0; j < 3; j++) {
                double d = 0;
                for (int r = 0; r < 3; r++) d += M[3 * r + i] * M[3 * r + j];
                ck_close(d, i == j, TOL2, 1, "MᵀM %d %d", i, j);
            }
        }
        const double det = M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
                           M[2] * (M[3] * M[7] - M[4] * M[6]);
        ck_close(det, 1.0, TOL2, 1, "det");
    }
}
END_TEST

/* ------------------------------------------------------------ transfer */

/* exact quadrature of ∫_H y_i(s) (n·s) ds in n's frame: Gauss-Legendre in
 * cosθ on [0,1] × uniform φ is exact for the polynomial integrand */
static void hemisphere_quadrature(int order, const double n[3], double *t)
{
    const int S = order + 2, P = 2 * order + 2, n2 = order * order;
    double x[64], w[64], M[9], *y = malloc(sizeof(double) * n2);
    ck_assert_int_eq(sh__gauss_legendre(S, x, w), SH_OK);
    sh__tangent_frame(n, M);
    for (int i = 0; i < n2; i++) t[i] = 0;
    for (int a = 0; a < S; a++) {
        const double c = 0.5 * (x[a] + 1), wc = 0.5 * w[a], sn = sqrt(1 - c * c);
        for (int b = 0; b < P; b++) {
            const double ph = 2 * M_PI * (b + 0.5) / P;
            const double l[3] = {sn * cos(ph), sn * sin(ph), c};
            const double d[3] = {M[0] * l[0] + M[1] * l[1] + M[2] * l[2], M[3] * l[0] + M[4] * l[1] + M[5] * l[2],
                                 M[6] * l[0] + M[7] * l[1] + M[8] * l[2]};
            ck_assert_int_eq(sh_eval_dir(order, SH_CS, d, y), SH_OK);
            for (int i = 0; i < n2; i++) t[i] += wc * (2 * M_PI / P) * c * y[i];
        }
    }
    free(y);
}

START_TEST(test_unshadowed_closed_form)
{
    uint64_t x = 7;
    for (int order = 1; order <= 10; order += 3)
        for (int k = 0; k < 20; k++) {
            const double z = 2 * sh__uniform(&x) - 1, ph = 2 * M_PI * sh__uniform(&x), r = sqrt(1 - z * z);
            const double n[3] = {r * cos(ph), r * sin(ph), z};
            double t[100], q[100];
            ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 0.8, n, t), SH_OK);
            hemisphere_quadrature(order, n, q);
            for (int i = 0; i < order * order; i++)
                ck_close(t[i], 0.8 / M_PI * q[i], 1e-12, 1, "order %d normal %d coeff %d", order, k, i);
        }
}
END_TEST

START_TEST(test_frame_rotation)
{
    /* the zonal local vector rotated by the frame's SH rotation equals the
     * addition-theorem form: the path the ray estimators take */
    uint64_t x = 9;
    const int order = 8;
    sh_rot_plan *plan;
    ck_assert_int_eq(sh_rot_plan_create(order, SH_ROT_IVANIC, SH_PREC_DOUBLE, SH_CS, &plan), SH_OK);
    const double up[3] = {0, 0, 1};
    double loc[64], t[64], w[64], M[9];
    ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 1, up, loc), SH_OK);
    for (int k = 0; k < 30; k++) {
        const double z = 2 * sh__uniform(&x) - 1, ph = 2 * M_PI * sh__uniform(&x), r = sqrt(1 - z * z);
        const double n[3] = {r * cos(ph), r * sin(ph), z};
        sh__tangent_frame(n, M);
        ck_assert_int_eq(sh__rotate_frame(plan, M, loc, t), SH_OK);
        ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 1, n, w), SH_OK);
        for (int i = 0; i < 64; i++) ck_close(t[i], w[i], 1e-12, 1, "normal %d coeff %d", k, i);
    }
    sh_rot_plan_free(plan);
}
END_TEST

typedef struct {
    sh_proc_scene ps;
    sh_mesh m;
    sh_scene *s;
} pscene;

static void pscene_make(pscene *p, const char *spec, int res)
{
    ck_assert_int_eq(sh_proc_parse(spec, &p->ps), SH_OK);
    p->ps.res = res;
    ck_assert_int_eq(sh_mesh_procedural(&p->ps, &p->m), SH_OK);
    ck_assert_int_eq(sh_scene_create(&p->m, 0, &p->s), SH_OK);
}

static void pscene_free(pscene *p)
{
    sh_scene_free(p->s);
    sh_mesh_free(&p->m);
}

/* R replications of a transfer (seeds 1..R): mean and standard error */
static void replicate(const pscene *p, sh_transfer_kind kind, int order, long rays, double albedo, int R, double *mean,
                      double *se)
{
    const size_t n = (size_t)p->m.nvert * order * order;
    double *T = malloc(sizeof(double) * n);
    memset(mean, 0, sizeof(double) * n);
    memset(se, 0, sizeof(double) * n);
    for (int r = 0; r < R; r++) {
        sh_transfer_opts o = {0};
        o.kind = kind;
        o.order = order;
        o.rays = rays;
        o.albedo = albedo;
        o.seed = (unsigned long)r + 1;
        ck_assert_int_eq(sh_transfer(p->s, &o, T, NULL), SH_OK);
        for (size_t i = 0; i < n; i++) {
            mean[i] += T[i] / R;
            se[i] += T[i] * T[i];
        }
    }
    for (size_t i = 0; i < n; i++) se[i] = sqrt(fmax(0.0, (se[i] - R * mean[i] * mean[i]) / (R - 1)) / R);
    free(T);
}

/* |mean − closed form| ≤ tessellation bound + 6 SE at every vertex with a
 * closed form; returns how many were compared.  With 16 replications the
 * studentised error has 15 degrees of freedom: P(|t| > 6) ≈ 2e-5 per
 * comparison, so hundreds of comparisons stay clear of chance failures. */
static int compare_closed_form(const pscene *p, int order, double albedo, const double *mean, const double *se)
{
    const int n2 = order * order;
    double t[64], b[64];
    int cnt = 0;
    for (int v = 0; v < p->m.nvert; v++) {
        int known;
        ck_assert_int_eq(sh_proc_closed_form(&p->ps, &p->m, v, order, SH_CS, albedo, 1e-4 * sh_scene_diag(p->s), t, b, &known), SH_OK);
        if (!known) continue;
        cnt++;
        for (int i = 0; i < known * known; i++) {
            const double err = fabs(mean[(size_t)v * n2 + i] - t[i]);
            if (!(err <= b[i] + 6 * se[(size_t)v * n2 + i] + 1e-12))
                ck_abort_msg("%s vertex %d coeff %d: |%.6g − %.6g| = %.3g > bound %.3g + 6·SE %.3g", sh_proc_name(p->ps.kind),
                             v, i, mean[(size_t)v * n2 + i], t[i], err, b[i], se[(size_t)v * n2 + i]);
        }
    }
    return cnt;
}

START_TEST(test_unshadowed_mc)
{
    /* the ray estimator of the unshadowed transfer against the closed form,
     * within 6 standard errors of 16 replications */
    pscene p;
    pscene_make(&p, "bowl", 4);
    const int order = 4, n2 = 16, R = 16;
    double *mean = malloc(sizeof(double) * p.m.nvert * n2), *se = malloc(sizeof(double) * p.m.nvert * n2);
    replicate(&p, SH_TRANSFER_UNSHADOWED, order, 256, 1, R, mean, se);
    double t[16];
    for (int v = 0; v < p.m.nvert; v += 7) {
        ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 1, p.m.normal + 3 * v, t), SH_OK);
        for (int i = 0; i < n2; i++)
            if (!(fabs(mean[v * n2 + i] - t[i]) <= 6 * se[v * n2 + i] + 1e-13))
                ck_abort_msg("vertex %d coeff %d: %.6g vs %.6g, SE %.3g", v, i, mean[v * n2 + i], t[i], se[v * n2 + i]);
    }
    /* the constant term is exact: the cosine-weighted estimator's mean of y_0 */
    for (int v = 0; v < p.m.nvert; v++) ck_close(mean[v * n2], 1 / sqrt(4 * M_PI), TOL2, 1, "t_0 vertex %d", v);
    free(mean);
    free(se);
    pscene_free(&p);
}
END_TEST

START_TEST(test_shadowed_sphere_plane)
{
    pscene p;
    pscene_make(&p, "sphere-plane", 4);
    const int order = 3, n2 = 9, R = 16;
    double *mean = malloc(sizeof(double) * p.m.nvert * n2), *se = malloc(sizeof(double) * p.m.nvert * n2);
    replicate(&p, SH_TRANSFER_SHADOWED, order, 400, 0.7, R, mean, se);
    const int cnt = compare_closed_form(&p, order, 0.7, mean, se);
    ck_assert_int_gt(cnt, 100);
    /* DC by the point-to-sphere form factor, without Gaunt coefficients:
     * t_0 √(4π)/ρ = 1 − sin²ω cos α (r and d from the geometry) */
    const double Rr = p.ps.p[0], H = p.ps.p[1];
    for (int v = 0; v < p.m.nvert; v++) {
        double t[9], b[9];
        int known;
        ck_assert_int_eq(sh_proc_closed_form(&p.ps, &p.m, v, order, SH_CS, 0.7, 0, t, b, &known), SH_OK);
        if (!known) continue;
        const double *q = p.m.pos + 3 * v, d = sqrt(q[0] * q[0] + q[1] * q[1] + H * H);
        ck_close(t[0] * sqrt(4 * M_PI) / 0.7, 1 - (Rr / d) * (Rr / d) * (H / d), 1e-12, 1, "form factor vertex %d", v);
    }
    free(mean);
    free(se);
    pscene_free(&p);
}
END_TEST

/* sh_proc_closed_forms (the sphere's inscribed radius once) against the
 * brute force, kept here as the independent truth: per vertex, every
 * triangle of the polyhedral sphere walked for its least distance from the
 * centre, and the bound of coefficient 0 from it, (ρ/π)·2π·(cos w_in −
 * cos w)/√(4π) (ρ/π times the cap's zonal difference, scaled to y_0^0). */
START_TEST(test_closed_forms_batch)
{
    pscene p;
    pscene_make(&p, "sphere-plane", 3);
    const int order = 3, n2 = 9, nv = p.m.nvert;
    const double rho = 0.7, lift = 1e-4 * sh_scene_diag(p.s), R = p.ps.p[0], H = p.ps.p[1];
    double *t = malloc(sizeof(double) * nv * n2), *b = malloc(sizeof(double) * nv * n2);
    int *known = malloc(sizeof(int) * nv), cnt = 0;
    ck_assert_int_eq(sh_proc_closed_forms(&p.ps, &p.m, nv, NULL, order, SH_CS, rho, lift, t, b, known), SH_OK);
    for (int v = 0; v < nv; v++) {
        double t1[9], b1[9];
        int k1;
        ck_assert_int_eq(sh_proc_closed_form(&p.ps, &p.m, v, order, SH_CS, rho, lift, t1, b1, &k1), SH_OK);
        ck_assert_int_eq(k1, known[v]);
        ck_assert_mem_eq(t1, t + (size_t)v * n2, sizeof t1);
        ck_assert_mem_eq(b1, b + (size_t)v * n2, sizeof b1);
        if (!known[v]) continue;
        cnt++;
        double r_in = R; /* brute force, for this vertex */
        for (int f = 0; f < p.m.ntri; f++) {
            const double *c[3];
            int on = 1;
            for (int j = 0; j < 3; j++) {
                c[j] = p.m.pos + 3 * p.m.tri[3 * f + j];
                on &= fabs(sqrt(c[j][0] * c[j][0] + c[j][1] * c[j][1] + (c[j][2] - H) * (c[j][2] - H)) - R) < 1e-9;
            }
            if (!on) continue;
            double e1[3], e2[3], g[3];
            for (int j = 0; j < 3; j++) e1[j] = c[1][j] - c[0][j], e2[j] = c[2][j] - c[0][j];
            g[0] = e1[1] * e2[2] - e1[2] * e2[1];
            g[1] = e1[2] * e2[0] - e1[0] * e2[2];
            g[2] = e1[0] * e2[1] - e1[1] * e2[0];
            const double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
            r_in = fmin(r_in, fabs(g[0] * c[0][0] + g[1] * c[0][1] + g[2] * (c[0][2] - H)) / gl);
        }
        const double *q = p.m.pos + 3 * v;
        const double d = sqrt(q[0] * q[0] + q[1] * q[1] + (H - lift) * (H - lift));
        const double want = rho / M_PI * 2 * M_PI * (cos(asin(r_in / d)) - cos(asin(R / d))) / sqrt(4 * M_PI);
        ck_close(b[(size_t)v * n2], want, 1e-12, 1, "bound of t_0 at vertex %d", v);
    }
    ck_assert_int_gt(cnt, 50);
    /* a subset by index, and no bound asked: the same vectors */
    int verts[3] = {nv - 1, 0, nv / 2}, k3[3];
    double t3[27];
    ck_assert_int_eq(sh_proc_closed_forms(&p.ps, &p.m, 3, verts, order, SH_CS, rho, lift, t3, NULL, k3), SH_OK);
    for (int k = 0; k < 3; k++) {
        ck_assert_int_eq(k3[k], known[verts[k]]);
        ck_assert_mem_eq(t3 + 9 * k, t + (size_t)verts[k] * n2, sizeof(double) * 9);
    }
    free(t);
    free(b);
    free(known);
    pscene_free(&p);
}
END_TEST

/* sh_proc_size counts what sh_mesh_procedural makes (vertices before the
 * mesh check drops unused ones: those inside box-open's hole) */
START_TEST(test_proc_size)
{
    const char *specs[] = {"sphere-plane", "sphere-plane:0.3,2", "bowl", "box-open", "box-open:0.5", "box-closed"};
    for (size_t k = 0; k < sizeof specs / sizeof *specs; k++)
        for (int res = 1; res <= 9; res += 4) {
            sh_proc_scene ps;
            sh_mesh m;
            long long nv, nt;
            ck_assert_int_eq(sh_proc_parse(specs[k], &ps), SH_OK);
            ps.res = res;
            ck_assert_int_eq(sh_proc_size(&ps, &nv, &nt), SH_OK);
            ck_assert_int_eq(sh_mesh_procedural(&ps, &m), SH_OK);
            ck_assert_msg(nv >= m.nvert && nv <= m.nvert + (res + 1) * (res + 1) && nt == m.ntri, "%s res %d: counted %lld/%lld, made %d/%d", specs[k], res,
                          nv, nt, m.nvert, m.ntri);
            sh_mesh_free(&m);
        }
}
END_TEST

START_TEST(test_shadowed_bowl_box)
{
    const char *specs[2] = {"bowl", "box-open"};
    for (int k = 0; k < 2; k++) {
        pscene p;
        pscene_make(&p, specs[k], 8);
        const int order = 2, n2 = 4, R = 16;
        double *mean = malloc(sizeof(double) * p.m.nvert * n2), *se = malloc(sizeof(double) * p.m.nvert * n2);
        replicate(&p, SH_TRANSFER_SHADOWED, order, 400, 1, R, mean, se);
        ck_assert_int_gt(compare_closed_form(&p, order, 1, mean, se), 20);
        free(mean);
        free(se);
        pscene_free(&p);
    }
}
END_TEST

START_TEST(test_furnace)
{
    /* interreflection under a constant environment: the closed-form radiance */
    const struct { const char *spec; double rho; } c[] = {{"bowl", 0.5}, {"bowl", 1}, {"box-open:0.5", 1}, {"sphere-plane", 1}};
    for (size_t k = 0; k < sizeof c / sizeof *c; k++) {
        pscene p;
        pscene_make(&p, c[k].spec, 4);
        double want;
        ck_assert_int_eq(sh_proc_furnace(&p.ps, c[k].rho, &want), SH_OK);
        sh_transfer_opts o = {0};
        o.kind = SH_TRANSFER_INTERREFLECTED;
        o.order = 2;
        o.rays = 256;
        o.albedo = c[k].rho;
        o.bounce_tol = 1e-12;
        o.max_bounces = 1000;
        double *T = malloc(sizeof(double) * 4 * p.m.nvert);
        sh_transfer_stats st;
        ck_assert_int_eq(sh_transfer(p.s, &o, T, &st), SH_OK);
        ck_assert_int_eq(st.converged, 1);
        ck_assert_int_eq(st.backface, 0);
        /* With ρ = 1 the answer is exact for the estimator too (each
         * vertex's weights sum to 1 over escaping and hitting rays).  With
         * ρ < 1 it depends on each vertex's sky fraction f(x), which the
         * estimator has only to Monte Carlo accuracy: B(x) − ρ/(2−ρ) =
         * ρ(f(x) − ½)(1 − B̄) + ρ(1 − f)(B̄_hits − B̄), so allow
         * 2ρ·max|f_MC − ½| with f_MC from the shadowed pass (same rays). */
        double tol = 1e-9;
        if (c[k].rho < 1) {
            double *S = malloc(sizeof(double) * 4 * p.m.nvert);
            o.kind = SH_TRANSFER_SHADOWED;
            ck_assert_int_eq(sh_transfer(p.s, &o, S, NULL), SH_OK);
            double dev = 0;
            for (int v = 0; v < p.m.nvert; v++)
                if (p.m.pos[3 * v + 2] < -1e-9) dev = fmax(dev, fabs(sqrt(4 * M_PI) * S[4 * v] / c[k].rho - 0.5));
            tol = 2 * c[k].rho * dev;
            ck_assert(tol < 0.05);
            free(S);
        }
        /* constant radiance 1: L_0 = √(4π), B = √(4π) t_0 */
        for (int v = 0; v < p.m.nvert; v++)
            if (c[k].rho == 1 || p.m.pos[3 * v + 2] < -1e-9) /* the bowl's rim sees half its hemisphere */
                ck_close(sqrt(4 * M_PI) * T[4 * v], want, tol, 1, "%s ρ=%g vertex %d", c[k].spec, c[k].rho, v);
        free(T);
        pscene_free(&p);
    }
    /* the closed white box: every ray of every vertex meets a front face, so
     * each bounce hands on all the energy (nothing escapes) */
    pscene p;
    pscene_make(&p, "box-closed", 4);
    sh_transfer_opts o = {0};
    o.kind = SH_TRANSFER_INTERREFLECTED;
    o.order = 1;
    o.rays = 256;
    o.max_bounces = 1;
    double *T = malloc(sizeof(double) * p.m.nvert);
    sh_transfer_stats st;
    ck_assert_int_eq(sh_transfer(p.s, &o, T, &st), SH_OK);
    ck_assert_int_eq(st.escaped, 0);
    ck_assert_int_eq(st.backface, 0);
    for (int v = 0; v < p.m.nvert; v++) ck_assert(T[v] == 0);
    free(T);
    pscene_free(&p);
}
END_TEST

START_TEST(test_threads_deterministic)
{
    pscene p;
    pscene_make(&p, "sphere-plane", 2);
    const int n = p.m.nvert * 9;
    double *a = malloc(sizeof(double) * n), *b = malloc(sizeof(double) * n);
    sh_transfer_opts o = {0};
    o.kind = SH_TRANSFER_INTERREFLECTED;
    o.order = 3;
    o.rays = 64;
    o.albedo = 0.6;
    o.threads = 1;
    ck_assert_int_eq(sh_transfer(p.s, &o, a, NULL), SH_OK);
    o.threads = 2;
    ck_assert_int_eq(sh_transfer(p.s, &o, b, NULL), SH_OK);
    ck_assert_int_eq(memcmp(a, b, sizeof(double) * n), 0);
    free(a);
    free(b);
    pscene_free(&p);
}
END_TEST

/* ------------------------------------------------------------ shading */

START_TEST(test_reference_constant_image)
{
    /* a constant lat-long environment (radiance 1): the reference on the
     * plane under the sphere is the form factor closed form */
    pscene p;
    pscene_make(&p, "sphere-plane", 4);
    sh_image img = {.width = 64, .height = 32, .nchan = 3};
    img.data = malloc(sizeof(float) * 3 * 64 * 32);
    for (int i = 0; i < 3 * 64 * 32; i++) img.data[i] = 1;
    sh_env *e;
    ck_assert_int_eq(sh_env_from_image(&img, &e), SH_OK);
    int verts[64], nv = 0;
    for (int v = 0; v < p.m.nvert && nv < 64; v += 5) {
        double t[1], b[1];
        int known;
        ck_assert_int_eq(sh_proc_closed_form(&p.ps, &p.m, v, 1, SH_CS, 1, 0, t, b, &known), SH_OK);
        if (known) verts[nv++] = v;
    }
    ck_assert_int_gt(nv, 20);
    sh_reference_opts o = {0};
    o.samples = 256;
    o.replications = 16;
    double B[64], se[64];
    ck_assert_int_eq(sh_shade_reference(p.s, e, NULL, verts, nv, &o, B, se, NULL), SH_OK);
    for (int k = 0; k < nv; k++) {
        double t[1], b[1];
        int known;
        sh_proc_closed_form(&p.ps, &p.m, verts[k], 1, SH_CS, 1, 1e-4 * sh_scene_diag(p.s), t, b, &known);
        const double want = sqrt(4 * M_PI) * t[0], bound = sqrt(4 * M_PI) * b[0];
        ck_assert_msg(fabs(B[k] - want) <= bound + 6 * se[k] + 1e-12, "vertex %d: %.6g vs %.6g (bound %.3g SE %.3g)",
                      verts[k], B[k], want, bound, se[k]);
        ck_assert(se[k] < 0.01);
    }
    sh_env_free(e);
    sh_image_free(&img);
    pscene_free(&p);
}
END_TEST

START_TEST(test_reference_sun_rotated)
{
    /* one bright pixel ("sun") in a black environment, the environment
     * rotated: at plane vertices far from the sphere's shadow the reference
     * is (ρ/π) L Ω cos(angle of the sun), the cosine varying only within the
     * pixel */
    pscene p;
    pscene_make(&p, "sphere-plane", 2);
    const int W = 256, H = 128, px = 40, py = 20;
    sh_image img = {.width = W, .height = H, .nchan = 1};
    strcpy(img.names[0], "Y");
    img.data = calloc((size_t)W * H, sizeof(float));
    img.data[py * W + px] = 1000;
    sh_env *e;
    ck_assert_int_eq(sh_env_from_image(&img, &e), SH_OK);
    sh_rotation rot;
    ck_assert_int_eq(sh_rotation_from_euler(0.3, 0.4, -0.2, &rot), SH_OK);
    double sun[3], w[3], omega[W * H];
    ck_assert_int_eq(sh_pixel_dir(SH_LAYOUT_LATLONG, W, H, px + 0.5, py + 0.5, sun), SH_OK);
    ck_assert_int_eq(sh_pixel_solid_angles(SH_LAYOUT_LATLONG, W, H, omega), SH_OK);
    for (int k = 0; k < 3; k++) w[k] = rot.R[3 * k] * sun[0] + rot.R[3 * k + 1] * sun[1] + rot.R[3 * k + 2] * sun[2];
    ck_assert(w[2] > 0.3);
    int verts[8] = {0, 1, 2, 3, 4, 5, 6, 7}; /* the plane's corner row y = −2: far from the sphere */
    sh_reference_opts o = {0};
    o.samples = 64;
    o.replications = 64;
    double B[8], se[8];
    ck_assert_int_eq(sh_shade_reference(p.s, e, &rot, verts, 8, &o, B, se, NULL), SH_OK);
    const double want = 1000 * omega[py * W + px] * w[2] / M_PI, dcos = 2 * M_PI / W;
    for (int k = 0; k < 8; k++) ck_close(B[k], want, dcos, 1e-300, "vertex %d", k);
    sh_env_free(e);
    sh_image_free(&img);
    pscene_free(&p);
}
END_TEST

START_TEST(test_rotate_lighting)
{
    /* shading a rotated light equals shading the inversely rotated normal:
     * Σ (R L)_i t_i(n) = Σ L_i t_i(Rᵀ n), for every exact method; the Taylor
     * methods equal the exact rotation at β = 0 */
    const int order = 5, n2 = 25;
    double L[25], RL[25], t[25], tr[25];
    sh_light light;
    ck_assert_int_eq(sh_light_parse("green", 0, &light), SH_OK);
    ck_assert_int_eq(sh_project(order, SH_CS, sh_light_fn, &light, SH_RULE_QUAD, 40, 0, L), SH_OK);
    sh_rotation rot, rot0;
    ck_assert_int_eq(sh_rotation_from_euler(0.4, 1.1, -0.8, &rot), SH_OK);
    ck_assert_int_eq(sh_rotation_from_euler(0.4, 0, -0.8, &rot0), SH_OK);
    const double n[3] = {0.36, -0.48, 0.8};
    const double rn[3] = {rot.R[0] * n[0] + rot.R[3] * n[1] + rot.R[6] * n[2], rot.R[1] * n[0] + rot.R[4] * n[1] + rot.R[7] * n[2],
                          rot.R[2] * n[0] + rot.R[5] * n[1] + rot.R[8] * n[2]};
    ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 1, n, t), SH_OK);
    ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 1, rn, tr), SH_OK);
    double want;
    ck_assert_int_eq(sh_shade(1, order, tr, order, L, &want), SH_OK);
    for (int m = 0; m < SH_ROT_NMETHODS; m++) {
        if (sh_rot_method_max_order(m) < order || m == SH_ROT_Z) continue; /* not built in, or below order 5 (direct) */
        if (sh_rot_method_is_exact(m)) {
            ck_assert_int_eq(sh_scene_rotate_coeffs(order, SH_CS, m, &rot, 1, L, RL), SH_OK);
            double got;
            sh_shade(1, order, t, order, RL, &got);
            ck_close(got, want, 1e-12, 1, "%s", sh_rot_method_name(m));
        } else {
            double ex[25];
            ck_assert_int_eq(sh_scene_rotate_coeffs(order, SH_CS, m, &rot0, 1, L, RL), SH_OK);
            ck_assert_int_eq(sh_scene_rotate_coeffs(order, SH_CS, SH_ROT_IVANIC, &rot0, 1, L, ex), SH_OK);
            for (int i = 0; i < n2; i++) ck_close(RL[i], ex[i], TOL2, 1, "%s β = 0 coeff %d", sh_rot_method_name(m), i);
        }
    }
}
END_TEST

START_TEST(test_shade_error)
{
    double ref[4] = {1, 2, 3, 4}, B[4], se[4] = {0.1, 0.1, 0.1, 0.1};
    for (int i = 0; i < 4; i++) B[i] = 1.01 * ref[i];
    sh_shade_err e;
    ck_assert_int_eq(sh_shade_error(4, B, ref, se, &e), SH_OK);
    ck_close(e.rel_l2, 0.01, TOL2, 1, "rel_l2");
    ck_close(e.rel_max, 0.04 / sqrt(30.0 / 4), TOL2, 1, "rel_max");
    ck_close(e.ref_l2, 0.2 / sqrt(30.0), TOL2, 1, "ref_l2");
    const double zero[4] = {0, 0, 0, 0};
    ck_assert_int_eq(sh_shade_error(4, B, zero, NULL, &e), SH_EINVAL);
}
END_TEST

/* ------------------------------------------------------------ pictures */

START_TEST(test_render_interpolation)
{
    /* vertex values linear in position are interpolated exactly: the image
     * shows the linear function at each hit point */
    pscene p;
    pscene_make(&p, "sphere-plane:0.5,1", 2);
    double *col = malloc(sizeof(double) * p.m.nvert);
    for (int v = 0; v < p.m.nvert; v++) col[v] = 3 + p.m.pos[3 * v] - 0.5 * p.m.pos[3 * v + 1];
    sh_camera cam;
    const double view[3] = {0, 0, 1};
    ck_assert_int_eq(sh_camera_frame(&p.m, view, 40, 48, 32, &cam), SH_OK);
    sh_image img;
    ck_assert_int_eq(sh_render(p.s, &cam, 1, col, NULL, 2, &img), SH_OK);
    /* looking straight down the z axis: pixel rays meet the sphere or the
     * plane; recompute the hit point for each and compare */
    int checked = 0;
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 48; x++) {
            const double ty = tan(20 * M_PI / 180), tx = ty * 48 / 32.0;
            const double sx = (2 * (x + 0.5) / 48 - 1) * tx, sy = (1 - 2 * (y + 0.5) / 32) * ty;
            /* fw = −z, up = +y, right = fw × up = +x */
            double d[3] = {sx, sy, -1};
            sh_hit h;
            ck_assert_int_eq(sh_scene_intersect(p.s, cam.eye, d, 0, INFINITY, &h), SH_OK);
            if (!h.hit) { ck_assert(img.data[y * 48 + x] == 0); continue; }
            const double len = sqrt(d[0] * d[0] + d[1] * d[1] + 1);
            const double hx = cam.eye[0] + h.t * d[0] / len, hy = cam.eye[1] + h.t * d[1] / len;
            ck_close(img.data[y * 48 + x], 3 + hx - 0.5 * hy, 1e-4, 1, "pixel %d %d", x, y);
            checked++;
        }
    ck_assert_int_gt(checked, 200);
    /* colour map ends and PNG output */
    sh_image cm;
    ck_assert_int_eq(sh_image_colormap(&img, 10, &cm), SH_OK);
    const char *png = tmp_file("r.png", NULL);
    ck_assert_int_eq(sh_png_write(png, &cm, 1), SH_OK);
    FILE *f = fopen(png, "rb");
    unsigned char sig[8];
    ck_assert_int_eq(fread(sig, 1, 8, f), 8);
    fclose(f);
    ck_assert_int_eq(png_sig_cmp(sig, 0, 8), 0);
    ck_assert_int_eq(sh_png_write("/nonexistent/dir/r.png", &cm, 1), SH_EIO);
    sh_image_free(&cm);
    sh_image_free(&img);
    free(col);
    pscene_free(&p);
}
END_TEST

START_TEST(test_colormap_ends)
{
    float v[3] = {0, 5, 100};
    sh_image in = {.width = 3, .height = 1, .nchan = 1, .data = v}, out;
    ck_assert_int_eq(sh_image_colormap(&in, 5, &out), SH_OK);
    for (int c = 0; c < 3; c++) {
        ck_assert(out.data[c * 3 + 0] == 0);
        ck_close(out.data[c * 3 + 1], 1.0, 1e-6, 1, "white at vmax");
        ck_close(out.data[c * 3 + 2], 1.0, 1e-6, 1, "clamped above vmax");
    }
    sh_image_free(&out);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("scene");
    TCase *t = tcase_create("scene");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, test_mesh_ply_obj_same);
    tcase_add_test(t, test_mesh_errors);
    tcase_add_test(t, test_mesh_real_models);
    tcase_add_test(t, test_rays_square);
    tcase_add_test(t, test_tangent_frame);
    tcase_add_test(t, test_unshadowed_closed_form);
    tcase_add_test(t, test_frame_rotation);
    tcase_add_test(t, test_unshadowed_mc);
    tcase_add_test(t, test_shadowed_sphere_plane);
    tcase_add_test(t, test_shadowed_bowl_box);
    tcase_add_test(t, test_closed_forms_batch);
    tcase_add_test(t, test_proc_size);
    tcase_add_test(t, test_furnace);
    tcase_add_test(t, test_threads_deterministic);
    tcase_add_test(t, test_reference_constant_image);
    tcase_add_test(t, test_reference_sun_rotated);
    tcase_add_test(t, test_rotate_lighting);
    tcase_add_test(t, test_shade_error);
    tcase_add_test(t, test_render_interpolation);
    tcase_add_test(t, test_colormap_ends);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
