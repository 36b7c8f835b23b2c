/* test_envmap.c — layouts, exact pixel solid angles, image projection.
 *
 * Truths used: 4π; a brute-force clipped tensor Gauss-Legendre cubature of
 * dΩ = π sin(πρ)/ρ du dv per probe pixel (an independent second method);
 * orthonormality ∫ y_i y_j = δ_ij; docs/CONVENTIONS.md's forward angle-map
 * formula; the Funk-Hecke closed form ∫ e^{κ s·a} y_i(s) dΩ = 4π i_l(κ) y_i(a)
 * with i_l from GSL (gsl_sf_bessel_il_scaled).
 */
#include <stdio.h>

#include "testutil.h"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_bessel.h>
#include <string.h>

static double sum(const double *w, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++) s += w[i];
    return s;
}

START_TEST(latlong_weights_sum_4pi)
{
    const int sizes[][2] = {{64, 32}, {37, 19}, {1, 1}, {1024, 512}};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        const int W = sizes[k][0], H = sizes[k][1];
        double *w = malloc(sizeof(double) * W * H);
        ck_assert_int_eq(sh_pixel_solid_angles(SH_LAYOUT_LATLONG, W, H, w), SH_OK);
        ck_close(sum(w, (size_t)W * H), 4.0 * M_PI, 1e-12, 1.0, "latlong %dx%d sum", W, H);
        free(w);
    }
}
END_TEST

START_TEST(probe_weights_sum_4pi)
{
    const int sizes[] = {1, 2, 3, 16, 17, 64, 255, 512};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        const int s = sizes[k];
        double *w = malloc(sizeof(double) * s * s);
        ck_assert_int_eq(sh_pixel_solid_angles(SH_LAYOUT_PROBE, s, s, w), SH_OK);
        ck_close(sum(w, (size_t)s * s), 4.0 * M_PI, 1e-6, 1.0, "probe %d sum", s);
        for (int i = 0; i < s * s; i++) ck_assert_msg(w[i] >= 0.0, "negative weight");
        /* corner pixels lie wholly outside the disc for s >= 4 */
        if (s >= 4) ck_assert(w[0] == 0.0 && w[s * s - 1] == 0.0);
        free(w);
    }
}
END_TEST

/* ---- brute force: clipped tensor Gauss-Legendre with subdivision ---- */
static const gsl_integration_glfixed_table *gl8;

static double dens(double u, double v)
{
    const double r = hypot(u, v);
    if (r > 1.0) return 0.0;
    if (r == 0.0) return M_PI * M_PI;
    return M_PI * sin(M_PI * r) / r;
}

static double cell(double u0, double u1, double v0, double v1, int depth)
{
    /* classify the cell against the unit circle */
    const double fu = fmax(fabs(u0), fabs(u1)), fv = fmax(fabs(v0), fabs(v1));
    const double nu = u0 > 0 ? u0 : (u1 < 0 ? u1 : 0), nv = v0 > 0 ? v0 : (v1 < 0 ? v1 : 0);
    if (nu * nu + nv * nv >= 1.0) return 0.0;
    const int inside = fu * fu + fv * fv <= 1.0;
    if (!inside && depth > 0) {
        const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
        return cell(u0, um, v0, vm, depth - 1) + cell(um, u1, v0, vm, depth - 1) +
               cell(u0, um, vm, v1, depth - 1) + cell(um, u1, vm, v1, depth - 1);
    }
    double s = 0.0, x, wx, y, wy;
    for (size_t a = 0; a < gl8->n; a++) {
        gsl_integration_glfixed_point(u0, u1, a, &x, &wx, gl8);
        for (size_t b = 0; b < gl8->n; b++) {
            gsl_integration_glfixed_point(v0, v1, b, &y, &wy, gl8);
            s += wx * wy * dens(x, y);
        }
    }
    return s;
}

START_TEST(probe_weights_vs_brute_force)
{
    gl8 = gsl_integration_glfixed_table_alloc(8);
    const int sizes[] = {8, 13};
    for (size_t k = 0; k < 2; k++) {
        const int s = sizes[k];
        double *w = malloc(sizeof(double) * s * s);
        ck_assert_int_eq(sh_pixel_solid_angles(SH_LAYOUT_PROBE, s, s, w), SH_OK);
        const double area = M_PI * M_PI * 4.0 / (s * s); /* scale of a central pixel */
        for (int y = 0; y < s; y++)
            for (int x = 0; x < s; x++) {
                const double u0 = 2.0 * x / s - 1, u1 = 2.0 * (x + 1) / s - 1;
                const double v0 = 2.0 * y / s - 1, v1 = 2.0 * (y + 1) / s - 1;
                const double ref = cell(u0, u1, v0, v1, 9);
                /* straddling cells: the brute force is O(4^-depth) accurate */
                ck_close(w[y * s + x], ref, 2e-6, area, "probe %d pixel (%d,%d)", s, x, y);
            }
        free(w);
    }
    gsl_integration_glfixed_table_free((gsl_integration_glfixed_table *)gl8);
}
END_TEST

/* max |Σ w y_i y_j − δ_ij| over an image grid */
static double ortho_error(sh_layout layout, int W, int H, int order)
{
    const int nn = order * order;
    double *w = malloc(sizeof(double) * W * H), *y = malloc(sizeof(double) * nn);
    double *G = calloc((size_t)nn * nn, sizeof(double));
    ck_assert_int_eq(sh_pixel_solid_angles(layout, W, H, w), SH_OK);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            const double om = w[j * W + i];
            if (om == 0.0) continue;
            double d[3];
            if (sh_pixel_dir(layout, W, H, i + 0.5, j + 0.5, d) != SH_OK) {
                /* a rim sliver: represented by the rim point (θ = π) */
                d[0] = d[1] = 0.0;
                d[2] = -1.0;
            }
            ck_assert_int_eq(sh_eval_dir(order, SH_CS, d, y), SH_OK);
            for (int a = 0; a < nn; a++)
                for (int b = 0; b < nn; b++) G[a * nn + b] += om * y[a] * y[b];
        }
    double err = 0.0;
    for (int a = 0; a < nn; a++)
        for (int b = 0; b < nn; b++) err = fmax(err, fabs(G[a * nn + b] - (a == b)));
    free(w); free(y); free(G);
    return err;
}

START_TEST(quadrature_orthonormal)
{
    const double e1 = ortho_error(SH_LAYOUT_LATLONG, 128, 64, 4);
    const double e2 = ortho_error(SH_LAYOUT_LATLONG, 256, 128, 4);
    ck_assert_msg(e1 < 2e-3 && e2 < 5e-4 && e2 < e1 / 3.0, "latlong ortho err %g %g", e1, e2);
    const double p1 = ortho_error(SH_LAYOUT_PROBE, 128, 128, 4);
    const double p2 = ortho_error(SH_LAYOUT_PROBE, 256, 256, 4);
    ck_assert_msg(p1 < 5e-3 && p2 < 2e-3 && p2 < p1, "probe ortho err %g %g", p1, p2);
}
END_TEST

/* ---- band-limited function built from sh_eval -------------------------- */
typedef struct { int order; const double *c; } bl_ctx;
static double bl_fn(const double dir[3], double th, double ph, void *vctx)
{
    const bl_ctx *b = vctx;
    double y[64];
    sh_eval(b->order, SH_CS, th, ph, y);
    double f = 0.0;
    for (int i = 0; i < b->order * b->order; i++) f += b->c[i] * y[i];
    return f;
}

static double proj_err(sh_layout layout, int W, int H, const double *c, int order)
{
    bl_ctx b = {order, c};
    sh_image img;
    ck_assert_int_eq(sh_image_from_fn(layout, W, H, bl_fn, &b, &img), SH_OK);
    double got[36];
    ck_assert_int_eq(sh_project_image(&img, layout, 6, SH_CS, got), SH_OK);
    double e = 0.0;
    for (int i = 0; i < 36; i++) e = fmax(e, fabs(got[i] - (i < order * order ? c[i] : 0.0)));
    sh_image_free(&img);
    return e;
}

START_TEST(project_band_limited)
{
    double c[16] = {0};
    c[0] = 0.5; c[2] = 0.7; c[5] = 0.3; c[10] = -0.2; c[15] = 0.25; c[9] = -0.1;
    const double a1 = proj_err(SH_LAYOUT_LATLONG, 64, 32, c, 4);
    const double a2 = proj_err(SH_LAYOUT_LATLONG, 256, 128, c, 4);
    /* midpoint rule in θ: O(1/H²) → a factor ~16 from 32 to 128 rows */
    ck_assert_msg(a1 < 5e-3 && a2 < 5e-4 && a2 < a1 / 8.0, "latlong projection err %g %g", a1, a2);
    const double p1 = proj_err(SH_LAYOUT_PROBE, 64, 64, c, 4);
    const double p2 = proj_err(SH_LAYOUT_PROBE, 256, 256, c, 4);
    ck_assert_msg(p1 < 2e-2 && p2 < 3e-3 && p2 < p1 / 2.0, "probe projection err %g %g", p1, p2);
}
END_TEST

START_TEST(probe_inverse_matches_forward)
{
    /* docs/CONVENTIONS.md: r = acos(dz)/(π√(dx²+dy²)), u = dx·r, v = dy·r,
     * x = (u+1)·size/2, y = (v+1)·size/2. */
    const int size = 200;
    for (int k = 0; k < 400; k++) {
        const double px = 1.0 + 198.0 * ((k * 37) % 101) / 100.0;
        const double py = 1.0 + 198.0 * ((k * 53) % 97) / 96.0;
        double d[3];
        const double u = 2 * px / size - 1, v = 2 * py / size - 1;
        if (hypot(u, v) > 0.999 || hypot(u, v) < 1e-9) continue;
        ck_assert_int_eq(sh_pixel_dir(SH_LAYOUT_PROBE, size, size, px, py, d), SH_OK);
        ck_close(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-14, 1.0, "|dir|");
        const double r = acos(d[2]) / (M_PI * sqrt(d[0] * d[0] + d[1] * d[1]));
        ck_close((d[0] * r + 1) * size / 2, px, 1e-11, 1.0, "x of (%g,%g)", px, py);
        ck_close((d[1] * r + 1) * size / 2, py, 1e-11, 1.0, "y of (%g,%g)", px, py);
    }
    /* the centre looks along +z; the pixel right of centre looks toward +x */
    double d[3];
    ck_assert_int_eq(sh_pixel_dir(SH_LAYOUT_PROBE, size, size, 100, 100, d), SH_OK);
    ck_close(d[2], 1.0, 0, 1.0, "centre");
    ck_assert_int_eq(sh_pixel_dir(SH_LAYOUT_PROBE, size, size, 150, 100, d), SH_OK);
    ck_close(d[0], 1.0, 1e-15, 1.0, "u=0.5 → +x (θ=π/2)");
    ck_assert_int_eq(sh_pixel_dir(SH_LAYOUT_PROBE, size, size, 0.0, 0.0, d), SH_EINVAL);
}
END_TEST

/* e^{κ s·a}: Funk-Hecke gives c_i = 4π i_l(κ) y_i(a) */
typedef struct { double k, a[3]; } exp_ctx;
static double exp_fn(const double d[3], double th, double ph, void *v)
{
    const exp_ctx *e = v;
    return exp(e->k * (d[0] * e->a[0] + d[1] * e->a[1] + d[2] * e->a[2]));
}

START_TEST(latlong_and_probe_agree_with_funk_hecke)
{
    exp_ctx e = {1.5, {0.48, -0.6, 0.64}};
    const int order = 6, nn = 36;
    double ya[36], truth[36], cl[36], cp[36];
    ck_assert_int_eq(sh_eval_dir(order, SH_CS, e.a, ya), SH_OK);
    for (int i = 0; i < nn; i++) {
        int l, m;
        sh_index_lm(i, &l, &m);
        truth[i] = 4.0 * M_PI * gsl_sf_bessel_il_scaled(l, e.k) * exp(e.k) * ya[i];
    }
    sh_image a, b;
    ck_assert_int_eq(sh_image_from_fn(SH_LAYOUT_LATLONG, 512, 256, exp_fn, &e, &a), SH_OK);
    ck_assert_int_eq(sh_image_from_fn(SH_LAYOUT_PROBE, 512, 512, exp_fn, &e, &b), SH_OK);
    ck_assert_int_eq(sh_project_image(&a, SH_LAYOUT_LATLONG, order, SH_CS, cl), SH_OK);
    ck_assert_int_eq(sh_project_image(&b, SH_LAYOUT_PROBE, order, SH_CS, cp), SH_OK);
    for (int i = 0; i < nn; i++) {
        ck_close(cl[i], truth[i], 5e-4, 1.0, "latlong c[%d]", i);
        ck_close(cp[i], truth[i], 2e-3, 1.0, "probe c[%d]", i);
        ck_close(cl[i], cp[i], 2e-3, 1.0, "latlong vs probe c[%d]", i);
    }
    /* nocs flips odd m */
    double cn[36];
    ck_assert_int_eq(sh_project_image(&a, SH_LAYOUT_LATLONG, order, SH_NOCS, cn), SH_OK);
    for (int i = 0; i < nn; i++) {
        int l, m;
        sh_index_lm(i, &l, &m);
        ck_close(cn[i], (abs(m) & 1) ? -cl[i] : cl[i], 1e-15, 1.0, "nocs c[%d]", i);
    }
    sh_image_free(&a);
    sh_image_free(&b);
}
END_TEST

START_TEST(project_multichannel_and_errors)
{
    /* 3-channel lat-long: channel c = (c+1)·constant → c_0 = (c+1)·√(4π) */
    const int W = 32, H = 16;
    sh_image img = {W, H, 3, {"R", "G", "B"}, malloc(sizeof(float) * W * H * 3)};
    for (int c = 0; c < 3; c++)
        for (int p = 0; p < W * H; p++) img.data[c * W * H + p] = (float)(c + 1);
    double co[3 * 9];
    ck_assert_int_eq(sh_project_image(&img, SH_LAYOUT_LATLONG, 3, SH_CS, co), SH_OK);
    for (int c = 0; c < 3; c++) {
        ck_close(co[c * 9], (c + 1) * sqrt(4 * M_PI), 1e-13, 1.0, "chan %d c0", c);
        /* m != 0: the φ sums vanish exactly; odd l: north-south symmetry;
         * c_2^0 is the O(1/H²) midpoint error of the θ sampling */
        for (int i = 1; i < 9; i++)
            ck_close(co[c * 9 + i], 0.0, i == 6 ? 0.015 : 1e-13, c + 1.0, "chan %d c%d", c, i);
    }
    /* a non-square probe is an error, as is a bad order */
    ck_assert_int_eq(sh_project_image(&img, SH_LAYOUT_PROBE, 3, SH_CS, co), SH_EINVAL);
    ck_assert(strstr(sh_last_error(), "square") != NULL);
    ck_assert_int_eq(sh_project_image(&img, SH_LAYOUT_LATLONG, 0, SH_CS, co), SH_EINVAL);
    double w[4];
    ck_assert_int_eq(sh_pixel_solid_angles(SH_LAYOUT_PROBE, 2, 3, w), SH_EINVAL);
    img.data[5] = NAN;
    ck_assert_int_eq(sh_project_image(&img, SH_LAYOUT_LATLONG, 3, SH_CS, co), SH_ENUM);
    sh_image_free(&img);
    sh_layout L;
    ck_assert_int_eq(sh_layout_parse("latlong", &L), SH_OK);
    ck_assert_int_eq(L, SH_LAYOUT_LATLONG);
    ck_assert_int_eq(sh_layout_parse("probe", &L), SH_OK);
    ck_assert_int_eq(L, SH_LAYOUT_PROBE);
    ck_assert_int_eq(sh_layout_parse("cube", &L), SH_EINVAL);
}
END_TEST

/* The projection against the obvious per-pixel sum Σ L Ω y_i(centre) (the
 * library groups probe pixels by symmetry orbits; this checks it does so
 * without changing the result), odd and even sizes, both conventions. */
START_TEST(project_matches_direct_pixel_sum)
{
    const int order = 5, nn = 25;
    for (int layout = 0; layout <= 1; layout++)
        for (int s = 31; s <= 32; s++) {
            const int W = layout ? s : 2 * s, H = s;
            sh_image img = {W, H, 2, {"R", "G"}, malloc(sizeof(float) * W * H * 2)};
            for (int i = 0; i < W * H * 2; i++) img.data[i] = (float)(sin(i * 12.9898) * 4.0 + 1.0);
            double *w = malloc(sizeof(double) * W * H);
            ck_assert_int_eq(sh_pixel_solid_angles(layout, W, H, w), SH_OK);
            for (int conv = 0; conv <= 1; conv++) {
                double got[50], ref[50] = {0}, y[25];
                ck_assert_int_eq(sh_project_image(&img, layout, order, conv, got), SH_OK);
                for (int py = 0; py < H; py++)
                    for (int px = 0; px < W; px++) {
                        const double om = w[py * W + px];
                        if (om == 0.0) continue;
                        double d[3];
                        if (sh_pixel_dir(layout, W, H, px + 0.5, py + 0.5, d) != SH_OK) {
                            d[0] = d[1] = 0.0; /* rim sliver → θ = π */
                            d[2] = -1.0;
                        }
                        ck_assert_int_eq(sh_eval_dir(order, conv, d, y), SH_OK);
                        for (int c = 0; c < 2; c++)
                            for (int i = 0; i < nn; i++)
                                ref[c * nn + i] += img.data[c * W * H + py * W + px] * om * y[i];
                    }
                for (int i = 0; i < 2 * nn; i++)
                    ck_close(got[i], ref[i], 1e-12, 1.0, "layout %d size %d conv %d c[%d]", layout, s,
                             conv, i);
            }
            free(w);
            sh_image_free(&img);
        }
}
END_TEST

static Suite *envmap_suite(void)
{
    Suite *s = suite_create("envmap");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, latlong_weights_sum_4pi);
    tcase_add_test(tc, probe_weights_sum_4pi);
    tcase_add_test(tc, probe_weights_vs_brute_force);
    tcase_add_test(tc, quadrature_orthonormal);
    tcase_add_test(tc, project_band_limited);
    tcase_add_test(tc, probe_inverse_matches_forward);
    tcase_add_test(tc, latlong_and_probe_agree_with_funk_hecke);
    tcase_add_test(tc, project_multichannel_and_errors);
    tcase_add_test(tc, project_matches_direct_pixel_sum);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(envmap_suite)
