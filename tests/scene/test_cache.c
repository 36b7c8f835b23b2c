/* test_cache.c — the radiance cache: a record reused at its own vertex is
 * the direct computation; placement and use follow Ward's criterion,
 * recomputed here from its definition; the interpolated incident radiance
 * equals Eq. 1 recomputed with rotations composed through the world frame
 * by another method (wigner); the Taylor rotations stay within the largest
 * singular value of D(β) (sh_taylor_error's SVD); the incident radiance
 * matches the closed form of a hemisphere minus a sphere's cap within its
 * own standard error; the bounce inside the bowl; threads. */
#include "testutil.h"

#include <string.h>

#include "scene/scene_internal.h"

typedef struct {
    sh_mesh m;
    sh_proc_scene ps;
    sh_scene *s;
    sh_env *env;
} fixture;

static void fix_make(fixture *f, const char *spec, int res, const char *light)
{
    ck_assert_int_eq(sh_proc_parse(spec, &f->ps), SH_OK);
    f->ps.res = res;
    ck_assert_int_eq(sh_mesh_procedural(&f->ps, &f->m), SH_OK);
    ck_assert_int_eq(sh_scene_create(&f->m, 2, &f->s), SH_OK);
    sh_light L;
    ck_assert_int_eq(sh_light_parse(light, 0, &L), SH_OK);
    ck_assert_int_eq(sh_env_from_light(&L, &f->env), SH_OK);
}

static void fix_free(fixture *f)
{
    sh_env_free(f->env);
    sh_scene_free(f->s);
    sh_mesh_free(&f->m);
}

static sh_cache_opts small_opts(int order, double a)
{
    sh_cache_opts o = {0};
    o.order = order;
    o.a = a;
    o.env_samples = 256;
    o.rays = 64;
    o.albedo = 0.8;
    o.seed = 3;
    o.threads = 2;
    return o;
}

START_TEST(test_record_is_direct)
{
    fixture f;
    fix_make(&f, "sphere-plane", 2, "green");
    const int order = 4, n2 = 16, nv = f.m.nvert;
    sh_cache_opts o = small_opts(order, 0.3);
    sh_cache *c;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &o, &c), SH_OK);
    int nrec;
    const int *rec = sh_cache_records(c, &nrec);
    ck_assert_int_gt(nrec, 10);
    ck_assert_int_lt(nrec, nv);
    double *Ld = malloc(sizeof(double) * 3 * n2), *Lc = malloc(sizeof(double) * 3 * n2);
    double *Bd = malloc(sizeof(double) * 3 * nv), *Bc = malloc(sizeof(double) * 3 * nv);
    ck_assert_int_eq(sh_cache_shade_direct(c, o.seed, 0, Bd, NULL), SH_OK);
    const sh_rot_method meths[4] = {SH_ROT_ZXZXZ, SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};
    for (int k = 0; k < 4; k++) {
        const sh_cache_rot rot = {meths[k], 0, 0};
        ck_assert_int_eq(sh_cache_shade(c, &rot, 2, Bc, NULL), SH_OK);
        for (int r = 0; r < nrec; r++) {
            const int v = rec[r];
            ck_assert_int_eq(sh_incident_radiance(f.s, f.env, &o, &v, 1, Ld, NULL), SH_OK);
            ck_assert_int_eq(sh_cache_incident(c, &rot, v, Lc), SH_OK);
            /* the same streams: bit for bit */
            ck_assert_int_eq(memcmp(Ld, Lc, sizeof(double) * 3 * n2), 0);
            for (int ch = 0; ch < 3; ch++) ck_assert(Bc[3 * v + ch] == Bd[3 * v + ch]);
        }
    }
    free(Ld); free(Lc); free(Bd); free(Bc);
    sh_cache_free(c);
    fix_free(&f);
}
END_TEST

static double inv_w(const sh_mesh *m, int p, int i, double Ri)
{
    const double *a = m->pos + 3 * p, *b = m->pos + 3 * i, *na = m->normal + 3 * p, *nb = m->normal + 3 * i;
    const double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    return d / Ri + sqrt(fmax(0.0, 1 - (na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2])));
}

START_TEST(test_criterion)
{
    fixture f;
    fix_make(&f, "sphere-plane", 3, "green");
    const double a = 0.25;
    sh_cache_opts o = small_opts(3, a);
    sh_cache *c;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &o, &c), SH_OK);
    int nrec;
    const int *rec = sh_cache_records(c, &nrec);
    const double diag = sh_scene_diag(f.s);
    int rv[4096];
    double iw[4096];
    int ever_far = 0;
    for (int v = 0; v < f.m.nvert; v++) {
        const double R = sh_cache_radius(c, v);
        ck_assert(R >= 0.01 * diag * (1 - 1e-12) && R <= 0.25 * diag * (1 + 1e-12));
        ever_far |= R == 0.25 * diag;
        const int n = sh_cache_uses(c, v, 4096, rv, iw);
        ck_assert_int_ge(n, 1);
        ck_assert_int_le(n, 4096);
        for (int k = 0; k < n; k++) {
            const double w = inv_w(&f.m, v, rv[k], sh_cache_radius(c, rv[k]));
            ck_assert(w < a);
            ck_close(iw[k], w, 1e-12, 1e-12, "1/w of vertex %d, record %d", v, rv[k]);
        }
        /* complete: no other record satisfies the criterion */
        int listed = 0;
        for (int r = 0; r < nrec; r++) {
            int in = 0;
            for (int k = 0; k < n; k++) in |= rv[k] == rec[r];
            listed += in;
            if (!in) ck_assert(!(inv_w(&f.m, v, rec[r], sh_cache_radius(c, rec[r])) < a));
        }
        ck_assert_int_eq(listed, n);
    }
    /* the open plane far from the sphere sees no geometry: R clamped to rmax */
    ck_assert(ever_far);
    sh_cache_free(c);
    fix_free(&f);
}
END_TEST

/* Eq. 1 recomputed: records from sh_incident_radiance, rotated local_i →
 * world → local_v by the wigner method (R_sh(M_v)ᵀ R_sh(M_i)), weights
 * 1/(1/w) from the criterion's definition */
START_TEST(test_rotation_identity)
{
    fixture f;
    fix_make(&f, "sphere-plane", 2, "green");
    const int order = 5, n2 = 25;
    sh_cache_opts o = small_opts(order, 0.5);
    sh_cache *c;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &o, &c), SH_OK);
    const sh_cache_rot exact = {SH_ROT_ZXZXZ, 0, 0}, iv = {SH_ROT_IVANIC, 0, 0};
    double Lc[75], Li[75], Lv[75], acc[75], Lw[75], Lk[75];
    int rv[512];
    double iw[512];
    int checked = 0, multi = 0;
    for (int v = 0; v < f.m.nvert; v += 3) {
        const int n = sh_cache_uses(c, v, 512, rv, iw);
        ck_assert_int_le(n, 512);
        int alone = -1;
        for (int k = 0; k < n; k++)
            if (iw[k] == 0) alone = k;
        memset(acc, 0, sizeof acc);
        double ws = 0;
        double Mv[9];
        sh__tangent_frame(f.m.normal + 3 * v, Mv);
        for (int k = (alone >= 0 ? alone : 0); k < (alone >= 0 ? alone + 1 : n); k++) {
            ck_assert_int_eq(sh_incident_radiance(f.s, f.env, &o, &rv[k], 1, Li, NULL), SH_OK);
            double Mi[9], MvT[9];
            sh__tangent_frame(f.m.normal + 3 * rv[k], Mi);
            for (int p = 0; p < 3; p++)
                for (int q = 0; q < 3; q++) MvT[3 * p + q] = Mv[3 * q + p];
            sh_rotation ri, rvT;
            ck_assert_int_eq(sh_rotation_from_matrix(Mi, 0, &ri), SH_OK);
            ck_assert_int_eq(sh_rotation_from_matrix(MvT, 0, &rvT), SH_OK);
            ck_assert_int_eq(sh_scene_rotate_coeffs(order, SH_CS, SH_ROT_WIGNER, &ri, 3, Li, Lw), SH_OK);
            ck_assert_int_eq(sh_scene_rotate_coeffs(order, SH_CS, SH_ROT_WIGNER, &rvT, 3, Lw, Lv), SH_OK);
            const double w = alone >= 0 ? 1 : 1 / iw[k];
            for (int i = 0; i < 3 * n2; i++) acc[i] += w * Lv[i];
            ws += w;
        }
        for (int i = 0; i < 3 * n2; i++) acc[i] /= ws;
        ck_assert_int_eq(sh_cache_incident(c, &exact, v, Lc), SH_OK);
        ck_assert_int_eq(sh_cache_incident(c, &iv, v, Lk), SH_OK);
        double mx = 0;
        for (int i = 0; i < 3 * n2; i++) mx = fmax(mx, fabs(acc[i]));
        for (int i = 0; i < 3 * n2; i++) {
            ck_close(Lc[i], acc[i], 1e-12, mx, "vertex %d coefficient %d (zxzxz)", v, i);
            ck_close(Lk[i], acc[i], 1e-12, mx, "vertex %d coefficient %d (ivanic)", v, i);
        }
        checked++;
        multi += n > 1 && alone < 0;
    }
    ck_assert_int_gt(checked, 50);
    ck_assert_int_gt(multi, 10);
    sh_cache_free(c);
    fix_free(&f);
}
END_TEST

/* ‖Λ_T(v) − Λ_exact(v)‖ ≤ max_i σ_max(D(β_i)) ‖Λ_i‖: Eq. 1 is a convex
 * combination and R_T − R_exact = Z(α) D(β) Z(γ) has D's singular values */
START_TEST(test_taylor_bound)
{
    fixture f;
    fix_make(&f, "sphere-plane", 2, "green");
    const int order = 6, n2 = 36;
    sh_cache_opts o = small_opts(order, 0.6);
    sh_cache *c;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &o, &c), SH_OK);
    int nrec;
    const int *rec = sh_cache_records(c, &nrec);
    double Lmax = 0, L[108];
    for (int r = 0; r < nrec; r++) {
        ck_assert_int_eq(sh_incident_radiance(f.s, f.env, &o, &rec[r], 1, L, NULL), SH_OK);
        for (int ch = 0; ch < 3; ch++) {
            double q = 0;
            for (int i = 0; i < n2; i++) q += L[ch * n2 + i] * L[ch * n2 + i];
            Lmax = fmax(Lmax, sqrt(q));
        }
    }
    const sh_rot_method tm[3] = {SH_ROT_TAYLOR1, SH_ROT_TAYLOR15, SH_ROT_TAYLOR2};
    const sh_cache_rot exact = {SH_ROT_ZXZXZ, 0, 0};
    int rv[512], nontrivial = 0;
    double iw[512], Le[108], Lt[108];
    for (int v = 0; v < f.m.nvert; v += 2) {
        const int n = sh_cache_uses(c, v, 512, rv, iw);
        double bmax = 0;
        for (int k = 0; k < n; k++) {
            const double *a = f.m.normal + 3 * v, *b = f.m.normal + 3 * rv[k];
            bmax = fmax(bmax, acos(fmax(-1.0, fmin(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]))));
        }
        ck_assert_int_eq(sh_cache_incident(c, &exact, v, Le), SH_OK);
        for (int t = 0; t < 3; t++) {
            /* the largest σ over a fine β grid up to bmax (σ_max(β) need not be monotone) */
            double smax = 0;
            for (int j = 0; j <= 40; j++) {
                sh_taylor_err te;
                ck_assert_int_eq(sh_taylor_error(order, tm[t], bmax * j / 40, 7, &te), SH_OK);
                smax = fmax(smax, te.max);
            }
            const sh_cache_rot rot = {tm[t], 0, 0};
            ck_assert_int_eq(sh_cache_incident(c, &rot, v, Lt), SH_OK);
            for (int ch = 0; ch < 3; ch++) {
                double d2 = 0;
                for (int i = 0; i < n2; i++) d2 += (Lt[ch * n2 + i] - Le[ch * n2 + i]) * (Lt[ch * n2 + i] - Le[ch * n2 + i]);
                ck_assert_msg(sqrt(d2) <= smax * Lmax * (1 + 1e-9) + 1e-14, "vertex %d %s: %g > %g", v,
                              sh_rot_method_name(tm[t]), sqrt(d2), smax * Lmax);
                nontrivial += d2 > 0;
            }
        }
    }
    ck_assert_int_gt(nontrivial, 20);
    /* the fallback: with beta_lim below every β, Taylor equals zxzxz */
    const sh_cache_rot fb = {SH_ROT_TAYLOR1, 0, 1e-9};
    for (int v = 0; v < f.m.nvert; v += 7) {
        ck_assert_int_eq(sh_cache_incident(c, &exact, v, Le), SH_OK);
        ck_assert_int_eq(sh_cache_incident(c, &fb, v, Lt), SH_OK);
        for (int i = 0; i < 3 * n2; i++) ck_close(Lt[i], Le[i], 1e-13, 1e-3, "fallback vertex %d", v);
    }
    sh_cache_free(c);
    fix_free(&f);
}
END_TEST

/* Incident radiance under a constant light at plane vertices of
 * sphere-plane: the hemisphere minus the sphere's cap, in the vertex's frame
 *   Λ_lm = δ_m0 z^H_l − √(4π/(2l+1)) z^cap_l y_lm(u_local)
 * (z^H the hemisphere's zonal coefficients, cap of half-angle asin(r/d) from
 * the lifted ray origin, r between the tessellation's inscribed radius and
 * R), estimated over 16 seeds: |mean − truth| ≤ 5 SE + the cap's annulus. */
static void incident_truth(const char *light_or_image)
{
    fixture f;
    const int image = !strcmp(light_or_image, "image");
    fix_make(&f, "sphere-plane", 8, image ? "const:1" : light_or_image);
    if (image) {
        /* a constant lat-long image: the block estimator */
        sh_env_free(f.env);
        sh_image img = {.width = 64, .height = 32, .nchan = 3};
        img.data = malloc(sizeof(float) * 3 * 64 * 32);
        for (int k = 0; k < 3 * 64 * 32; k++) img.data[k] = 1.0f;
        snprintf(img.names[0], sizeof img.names[0], "R");
        snprintf(img.names[1], sizeof img.names[1], "G");
        snprintf(img.names[2], sizeof img.names[2], "B");
        ck_assert_int_eq(sh_env_from_image(&img, &f.env), SH_OK);
        free(img.data);
    }
    const int order = 4, n2 = 16, S = 16;
    const double R = f.ps.p[0], H = f.ps.p[1];
    /* the inscribed radius of the polyhedral sphere */
    double r_in = R;
    for (int t = 0; t < f.m.ntri; t++) {
        const double *a = f.m.pos + 3 * f.m.tri[3 * t], *b = f.m.pos + 3 * f.m.tri[3 * t + 1], *e = f.m.pos + 3 * f.m.tri[3 * t + 2];
        if (a[2] == 0 && b[2] == 0 && e[2] == 0) continue;
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {e[0] - a[0], e[1] - a[1], e[2] - a[2]};
        const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        r_in = fmin(r_in, fabs(g[0] * a[0] + g[1] * a[1] + g[2] * (a[2] - H)) / gl);
    }
    int verts[6], nvs = 0;
    for (int v = 0; v < f.m.nvert && nvs < 6; v++) {
        const double *p = f.m.pos + 3 * v;
        if (p[2] == 0 && fabs(p[0]) < 1.2 && fabs(p[1]) < 1.2 && (v % 5 == 0)) verts[nvs++] = v;
    }
    ck_assert_int_eq(nvs, 6);
    double *L = malloc(sizeof(double) * S * nvs * 3 * n2);
    for (int r = 0; r < S; r++) {
        sh_cache_opts o = small_opts(order, 0.2);
        o.env_samples = 4096;
        o.seed = 100 + r;
        ck_assert_int_eq(sh_incident_radiance(f.s, f.env, &o, verts, nvs, L + (size_t)r * nvs * 3 * n2, NULL), SH_OK);
    }
    double zH[4], zc[4], zci[4], y[16];
    ck_assert_int_eq(sh_cap_zonal(M_PI / 2, order, zH), SH_OK);
    const double lift = 1e-4 * sh_scene_diag(f.s);
    for (int k = 0; k < nvs; k++) {
        const double *p = f.m.pos + 3 * verts[k];
        double M[9];
        sh__tangent_frame(f.m.normal + 3 * verts[k], M);
        const double cw[3] = {-p[0], -p[1], H - lift};
        const double d = sqrt(cw[0] * cw[0] + cw[1] * cw[1] + cw[2] * cw[2]);
        /* the direction to the centre in the vertex's frame: Mᵀ c/d */
        const double u[3] = {(M[0] * cw[0] + M[3] * cw[1] + M[6] * cw[2]) / d, (M[1] * cw[0] + M[4] * cw[1] + M[7] * cw[2]) / d,
                             (M[2] * cw[0] + M[5] * cw[1] + M[8] * cw[2]) / d};
        ck_assert_int_eq(sh_cap_zonal(asin(R / d), order, zc), SH_OK);
        ck_assert_int_eq(sh_cap_zonal(asin(r_in / d), order, zci), SH_OK);
        ck_assert_int_eq(sh_eval_dir(order, SH_CS, u, y), SH_OK);
        for (int ch = 0; ch < 3; ch++)
            for (int l = 0; l < order; l++)
                for (int mm = -l; mm <= l; mm++) {
                    const int i = sh_index(l, mm);
                    const double f4 = sqrt(4 * M_PI / (2 * l + 1));
                    const double truth = (mm == 0 ? zH[l] : 0) - f4 * zc[l] * y[i];
                    const double annulus = fabs(f4 * (zc[l] - zci[l]) * y[i]);
                    double s = 0, s2 = 0;
                    for (int r = 0; r < S; r++) {
                        const double x = L[(((size_t)r * nvs + k) * 3 + ch) * n2 + i];
                        s += x;
                        s2 += x * x;
                    }
                    const double mean = s / S, se = sqrt(fmax(0.0, (s2 - S * mean * mean) / (S - 1)) / S);
                    ck_assert_msg(fabs(mean - truth) <= 5 * se + annulus + 1e-12,
                                  "%s vertex %d ch %d i %d: mean %g truth %g se %g annulus %g", light_or_image, verts[k], ch,
                                  i, mean, truth, se, annulus);
                }
    }
    free(L);
    fix_free(&f);
}

START_TEST(test_incident_closed_form)
{
    incident_truth("const:1");
    incident_truth("image");
}
END_TEST

/* one bounce inside the bowl under a constant sky: at the bottom the rim
 * (radius 1 at height 1) subtends 2π(1 − 1/√2); the rest is bowl of direct
 * exit radiance ρ/2 (half the cosine-weighted hemisphere is sky everywhere
 * inside a sphere), so Λ_00 = y00 [2π(1 − 1/√2) + (ρ/2) 2π/√2] */
START_TEST(test_bounce_bowl)
{
    fixture f;
    fix_make(&f, "bowl", 8, "const:1");
    const int order = 2, S = 24;
    const double rho = 0.6, y00 = 0.5 / sqrt(M_PI);
    int bottom = -1;
    for (int v = 0; v < f.m.nvert; v++)
        if (f.m.pos[3 * v + 2] == -1) bottom = v;
    ck_assert_int_ge(bottom, 0);
    double s = 0, s2 = 0, L[12];
    for (int r = 0; r < S; r++) {
        sh_cache_opts o = small_opts(order, 0.2);
        o.bounce = 1;
        o.albedo = rho;
        o.rays = 1024;
        o.env_samples = 1024;
        o.seed = 7 + r;
        ck_assert_int_eq(sh_incident_radiance(f.s, f.env, &o, &bottom, 1, L, NULL), SH_OK);
        s += L[0];
        s2 += L[0] * L[0];
    }
    const double mean = s / S, se = sqrt(fmax(0.0, (s2 - S * mean * mean) / (S - 1)) / S);
    const double truth = y00 * (2 * M_PI * (1 - M_SQRT1_2) + rho / 2 * 2 * M_PI * M_SQRT1_2);
    /* the polygonal rim (64 sides, inscribed: 1.6e-3 of the disc's area) */
    ck_assert_msg(fabs(mean - truth) <= 5 * se + 2e-3 * truth, "bowl bottom: %g vs %g (se %g)", mean, truth, se);
    fix_free(&f);
}
END_TEST

START_TEST(test_threads_and_errors)
{
    fixture f;
    fix_make(&f, "sphere-plane", 2, "green");
    const int nv = f.m.nvert;
    sh_cache_opts o = small_opts(3, 0.3);
    o.bounce = 1;
    double *B1 = malloc(sizeof(double) * 3 * nv), *B2 = malloc(sizeof(double) * 3 * nv);
    sh_cache *c1, *c2;
    o.threads = 1;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &o, &c1), SH_OK);
    o.threads = 2;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &o, &c2), SH_OK);
    const sh_cache_rot rot = {SH_ROT_TAYLOR15, 0, 0};
    ck_assert_int_eq(sh_cache_shade(c1, &rot, 1, B1, NULL), SH_OK);
    ck_assert_int_eq(sh_cache_shade(c2, &rot, 2, B2, NULL), SH_OK);
    ck_assert_int_eq(memcmp(B1, B2, sizeof(double) * 3 * nv), 0);
    /* bad arguments */
    const sh_cache_rot zrot = {SH_ROT_Z, 0, 0};
    ck_assert_int_eq(sh_cache_shade(c1, &zrot, 1, B1, NULL), SH_EINVAL);
    sh_cache *bad;
    sh_cache_opts b = o;
    b.a = -1;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &b, &bad), SH_EINVAL);
    b = o;
    b.order = 40;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &b, &bad), SH_EINVAL);
    b = o;
    b.rmin = 0.5;
    b.rmax = 0.1;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &b, &bad), SH_EINVAL);
    b = o;
    b.brdf.phong = 1;
    ck_assert_int_eq(sh_cache_create(f.s, f.env, &b, &bad), SH_EINVAL);
    ck_assert_int_eq(sh_cache_uses(c1, -1, 0, NULL, NULL), -1);
    sh_cache_free(c1);
    sh_cache_free(c2);
    free(B1);
    free(B2);
    fix_free(&f);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("cache");
    TCase *t = tcase_create("cache");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, test_record_is_direct);
    tcase_add_test(t, test_criterion);
    tcase_add_test(t, test_rotation_identity);
    tcase_add_test(t, test_taylor_bound);
    tcase_add_test(t, test_incident_closed_form);
    tcase_add_test(t, test_bounce_bowl);
    tcase_add_test(t, test_threads_and_errors);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
