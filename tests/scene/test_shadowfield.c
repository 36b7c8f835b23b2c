/* test_shadowfield.c — shadow fields of a sphere: scaling at k = 1 is the
 * identity; the scaled fields against a GSL quadrature of the scaled
 * function (cone family and the sphere's τ); the product of shadow fields
 * against sh_triple_matrix_quad (a second method: product rule); the k
 * table reproduces M at its nodes; the product transfer approaches the
 * closed form as the order grows; bad input. */
#include "testutil.h"

#include <gsl/gsl_integration.h>
#include <string.h>

static sh_sf_opts opts(int order, sh_sf_scaling sc, double d0)
{
    sh_sf_opts o = {0};
    o.order = order;
    o.scaling = sc;
    o.d0 = d0;
    o.albedo = 1;
    return o;
}

START_TEST(test_identity_at_k1)
{
    const double R = 0.5, d0 = 1.3;
    double Oe[64], Oc[64], Os[64];
    for (int order = 1; order <= 8; order++) {
        sh_sf_opts e = opts(order, SH_SF_EXACT, d0), c = opts(order, SH_SF_CONE, d0), s = opts(order, SH_SF_SPHERE, d0);
        ck_assert_int_eq(sh_sf_field(&e, R, d0, Oe), SH_OK);
        ck_assert_int_eq(sh_sf_field(&c, R, d0, Oc), SH_OK);
        ck_assert_int_eq(sh_sf_field(&s, R, d0, Os), SH_OK);
        for (int i = 0; i < order * order; i++) {
            ck_close(Oc[i], Oe[i], 1e-13, 1, "cone at k = 1, order %d, i %d", order, i);
            ck_close(Os[i], Oe[i], 1e-13, 1, "sphere at k = 1, order %d, i %d", order, i);
        }
    }
}
END_TEST

/* o_l = 2π ∫ y_l0(θ) F(τ(θ)) sinθ dθ, F the sampled field's band-limited
 * zonal function Σ z0_l' y_l'0 — by GSL QAGS with τ evaluated here */
typedef struct {
    int order, l, cone;
    double k, theta0, w0, wd;
    const double *z0;
} qctx;

static double y_l0(int l, double theta)
{
    double y[256];
    sh_eval(l + 1, SH_CS, theta, 0, y);
    return y[l * (l + 1)];
}

static double integrand(double theta, void *vp)
{
    const qctx *q = vp;
    double tau;
    if (q->cone) {
        /* cot τ = (cot θ + (1 − k) cot θ0)/k (CONVENTIONS.md), τ in (0, π) */
        tau = atan2(q->k * sin(theta), cos(theta) + (1 - q->k) * sin(theta) / tan(q->theta0));
    } else {
        tau = theta <= q->wd ? theta * q->w0 / q->wd : q->w0 + (theta - q->wd) * (M_PI - q->w0) / (M_PI - q->wd);
    }
    double F = 0;
    for (int lp = 0; lp < q->order; lp++) F += q->z0[lp] * y_l0(lp, tau);
    return 2 * M_PI * y_l0(q->l, theta) * F * sin(theta);
}

/* (orders 6 and 16, `shadow-field --order`'s top: docs/ranges.md) */
START_TEST(test_scaled_field_quadrature)
{
    const double R = 0.5, d0 = 1.0;
    const int order = _i ? 16 : 6;
    double z0[16], O[256], worst = 0;
    ck_assert_int_eq(sh_cap_zonal(asin(R / d0), order, z0), SH_OK);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(2000);
    const double ds[4] = {0.7, 1.6, 2.5, 4.0};
    for (int cone = 0; cone < 2; cone++)
        for (int j = 0; j < 4; j++) {
            sh_sf_opts o = opts(order, cone ? SH_SF_CONE : SH_SF_SPHERE, d0);
            o.cone_angle = cone ? 0.6 : 0;
            ck_assert_int_eq(sh_sf_field(&o, R, ds[j], O), SH_OK);
            qctx q = {.order = order, .cone = cone, .k = ds[j] / d0, .theta0 = 0.6, .w0 = asin(R / d0),
                      .wd = asin(R / ds[j]), .z0 = z0};
            for (int l = 0; l < order; l++) {
                q.l = l;
                gsl_function F = {integrand, &q};
                double res = 0, err = 0, pts[3] = {0, q.wd, M_PI};
                if (cone) ck_assert_int_eq(gsl_integration_qags(&F, 0, M_PI, 1e-13, 1e-12, 2000, ws, &res, &err), 0);
                else ck_assert_int_eq(gsl_integration_qagp(&F, pts, 3, 1e-13, 1e-12, 2000, ws, &res, &err), 0);
                ck_close(O[l * (l + 1)], res, 1e-10, 1e-3, "%s d %g l %d", cone ? "cone" : "sphere", ds[j], l);
                worst = fmax(worst, fabs(O[l * (l + 1)] - res));
                for (int m = -l; m <= l; m++)
                    if (m) ck_assert(O[sh_index(l, m)] == 0);
            }
        }
    gsl_integration_workspace_free(ws);
    printf("shadow fields at order %d (cone, sphere; k = 0.7..4) vs QAGS of the scaled field: max abs %.3g\n", order,
           worst);
}
END_TEST

/* t = P_n(V c⁺) against M c⁺ with M_ij = ∫ V y_i y_j by the product rule */
typedef struct {
    int order;
    const double *V;
} vctx;

static double vfun(const double dir[3], double theta, double phi, void *vp)
{
    const vctx *c = vp;
    double y[256], s = 0;
    sh_eval(c->order, SH_CS, theta, phi, y);
    for (int i = 0; i < c->order * c->order; i++) s += c->V[i] * y[i];
    return s;
}

START_TEST(test_product_quadrature)
{
    const double R = 0.5, centre[3] = {0.2, -0.1, 1.1};
    const double pos[6] = {0.4, 0.3, 0, -0.7, 0.2, 0.1}, nor[6] = {0, 0, 1, 0.6, 0, 0.8};
    for (int order = 2; order <= 6; order += 2) {
        const int n2 = order * order;
        sh_sf_opts o = opts(order, SH_SF_EXACT, 1.0);
        o.albedo = 0.7;
        double T[2 * 36];
        ck_assert_int_eq(sh_shadow_field_transfer(&o, centre, R, 2, pos, nor, T, NULL), SH_OK);
        for (int p = 0; p < 2; p++) {
            const double *x = pos + 3 * p;
            const double cv[3] = {centre[0] - x[0], centre[1] - x[1], centre[2] - x[2]};
            const double d = sqrt(cv[0] * cv[0] + cv[1] * cv[1] + cv[2] * cv[2]), u[3] = {cv[0] / d, cv[1] / d, cv[2] / d};
            double z[6], y[36], V[36], c[36], M[36 * 36];
            ck_assert_int_eq(sh_cap_zonal(asin(R / d), order, z), SH_OK);
            ck_assert_int_eq(sh_eval_dir(order, SH_CS, u, y), SH_OK);
            for (int l = 0; l < order; l++)
                for (int m = -l; m <= l; m++) V[sh_index(l, m)] = -sqrt(4 * M_PI / (2 * l + 1)) * z[l] * y[sh_index(l, m)];
            V[0] += sqrt(4 * M_PI);
            ck_assert_int_eq(sh_transfer_unshadowed(order, SH_CS, 0.7, nor + 3 * p, c), SH_OK);
            vctx vc = {order, V};
            ck_assert_int_eq(sh_triple_matrix_quad(order, SH_CS, vfun, &vc, 2 * order + 2, M), SH_OK);
            for (int i = 0; i < n2; i++) {
                double t = 0;
                for (int j = 0; j < n2; j++) t += M[i * n2 + j] * c[j];
                ck_close(T[p * n2 + i], t, 1e-12, 1e-2, "order %d receiver %d i %d", order, p, i);
            }
        }
    }
}
END_TEST

START_TEST(test_table_nodes)
{
    /* receivers at k = kmin and kmax (d = k·d0 along −z of the centre) */
    const double R = 0.5, d0 = 1.0, centre[3] = {0, 0, 3}, kmin = 1.2, kmax = 2.7;
    const double pos[6] = {0, 0, 3 - kmin * d0, 0, 0, 3 - kmax * d0}, nor[6] = {0.3, 0, 0.9539392014169456, 0, 0, 1};
    const int order = 5, n2 = 25;
    for (int sc = 1; sc <= 2; sc++) {
        sh_sf_opts o = opts(order, (sh_sf_scaling)sc, d0);
        double Td[50], Tt[50];
        ck_assert_int_eq(sh_shadow_field_transfer(&o, centre, R, 2, pos, nor, Td, NULL), SH_OK);
        for (int S = 2; S <= 7; S += 5) {
            o.samples = S;
            o.kmin = kmin;
            o.kmax = kmax;
            sh_sf_stats st;
            ck_assert_int_eq(sh_shadow_field_transfer(&o, centre, R, 2, pos, nor, Tt, &st), SH_OK);
            ck_assert_int_eq(st.matrices, S);
            ck_close(st.kmin, kmin, 1e-12, 1, "receivers' kmin");
            for (int i = 0; i < 2 * n2; i++) ck_close(Tt[i], Td[i], 1e-12, 1e-3, "scaling %d samples %d i %d", sc, S, i);
        }
    }
}
END_TEST

/* the product transfer of the exact field approaches the closed form */
START_TEST(test_converges_to_closed_form)
{
    sh_proc_scene ps;
    sh_mesh m;
    ck_assert_int_eq(sh_proc_parse("sphere-plane", &ps), SH_OK);
    ps.res = 4;
    ck_assert_int_eq(sh_mesh_procedural(&ps, &m), SH_OK);
    const double centre[3] = {0, 0, ps.p[1]};
    double prev = INFINITY;
    for (int order = 3; order <= 12; order += 3) {
        const int n2 = order * order;
        double *T = malloc(sizeof(double) * n2), *C = malloc(sizeof(double) * n2);
        sh_sf_opts o = opts(order, SH_SF_EXACT, 1.0);
        double e2 = 0, c2 = 0;
        for (int v = 0; v < m.nvert; v += 3) {
            int known;
            ck_assert_int_eq(sh_proc_closed_form(&ps, &m, v, order, SH_CS, 1, 0, C, NULL, &known), SH_OK);
            if (known != order) continue;
            ck_assert_int_eq(sh_shadow_field_transfer(&o, centre, ps.p[0], 1, m.pos + 3 * v, m.normal + 3 * v, T, NULL), SH_OK);
            for (int i = 0; i < n2; i++) {
                e2 += (T[i] - C[i]) * (T[i] - C[i]);
                c2 += C[i] * C[i];
            }
        }
        const double rel = sqrt(e2 / c2);
        ck_assert_msg(rel < prev, "order %d: %g not below %g", order, rel, prev);
        prev = rel;
        free(T);
        free(C);
    }
    ck_assert(prev < 0.02);
    sh_mesh_free(&m);
}
END_TEST

START_TEST(test_errors)
{
    const double centre[3] = {0, 0, 1}, inside[3] = {0, 0, 0.8}, n[3] = {0, 0, 1};
    double T[16], O[16];
    sh_sf_opts o = opts(4, SH_SF_CONE, 1.0);
    ck_assert_int_eq(sh_shadow_field_transfer(&o, centre, 0.5, 1, inside, n, T, NULL), SH_EINVAL);
    o.samples = 1;
    ck_assert_int_eq(sh_shadow_field_transfer(&o, centre, 0.5, 0, inside, n, T, NULL), SH_EINVAL);
    o = opts(4, SH_SF_CONE, 0.4);
    ck_assert_int_eq(sh_sf_field(&o, 0.5, 2, O), SH_EINVAL);
    o = opts(4, SH_SF_EXACT, 1.0);
    o.samples = 5;
    ck_assert_int_eq(sh_sf_field(&o, 0.5, 2, O), SH_EINVAL);
    o = opts(17, SH_SF_CONE, 1.0);
    ck_assert_int_eq(sh_sf_field(&o, 0.5, 2, O), SH_EINVAL);
    sh_sf_scaling s;
    ck_assert_int_eq(sh_sf_scaling_parse("linear", &s), SH_EINVAL);
    ck_assert_int_eq(sh_sf_scaling_parse("sphere", &s), SH_OK);
    ck_assert_int_eq(s, SH_SF_SPHERE);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("shadowfield");
    TCase *t = tcase_create("shadowfield");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, test_identity_at_k1);
    tcase_add_loop_test(t, test_scaled_field_quadrature, 0, 2);
    tcase_add_test(t, test_product_quadrature);
    tcase_add_test(t, test_table_nodes);
    tcase_add_test(t, test_converges_to_closed_form);
    tcase_add_test(t, test_errors);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(suite)
