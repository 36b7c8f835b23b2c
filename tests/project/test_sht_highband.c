/* test_sht_highband.c — the fast transforms (src/project/sht.c, sht_kern.c)
 * at the top of their documented range, on full-size grids, every point.
 *
 * Regression: a block of ring pairs whose sectoral seeds were all below
 * 2^−400 started the Legendre recursion one step early (step 0 turned the
 * seed into Q_{m−1}^m), which mixed the second solution of the recurrence in
 * before each (l, m)'s turning point: errors grew geometrically from
 * lmax ≈ 640 and were O(1) above lmax ≈ 740 (synthesis of y_1000^250 off by
 * 1.95 at cosθ = 0.967).  The tests that existed compared with libsharp up to
 * lmax 255 and checked order 2049 on 5 rings of 3 points, where the affected
 * values were all ~0; these run the full grids.
 *
 * Truths: Q_l^m from tests/legendre_truth.h (long double, extended exponent,
 * independent of legendre.c and of the kernels), itself bounded here against
 * MPFR at 256 bits; exactness of the Gauss product rule (analysis of a
 * band-limited map returns its coefficients); synthesis then analysis is the
 * identity on Gauss grids.  Agreement with libsharp at the same sizes is in
 * test_sht_sharp.c.
 *
 * Measures.  Synthesis: max over every grid point of |map − truth| divided by
 * max|truth|.  Coefficients: max|Δc| (the set coefficients are O(1)) and the
 * normwise ‖Δc‖₂/‖c‖₂ for random vectors (the transforms are backward stable
 * in that norm; the worst single coefficient of a random vector at lmax 2047
 * is off by ~3e−12 relative to max|c| in shlab and libsharp alike, at m ≤ 1
 * near the poles). */
#include "testutil.h"

#include "legendre_truth.h"
#include "project/sht_internal.h"

#include <string.h>

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffffff) / (double)0x1000000 - 0.5;
}

static const int LMAXES[] = {700, 1000, 1023, 2047, 2048}; /* 2048: order 2049; order 4097 (lmax 4096) is swept by experiments/sht_accuracy */
#define NLMAX ((int)(sizeof LMAXES / sizeof LMAXES[0]))

/* ------------------------------------------------- the truth bounded by MPFR */

/* truth_qlm against MPFR at l = 2047: near the pole, at the turning points
 * of large m, in the oscillating region and deep in the evanescent one. */
START_TEST(truth_vs_mpfr)
{
    const double xs[] = {0.9999694, 0.99, 0.9238795, 0.5, 0.1, -0.7};
    const int ms[] = {0, 1, 14, 100, 777, 1023, 1500, 2000, 2047};
    double worst = 0.0;
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
        for (size_t k = 0; k < sizeof ms / sizeof ms[0]; k++) {
            const double t = truth_qlm(2047, ms[k], xs[i]), r = truth_qlm_mpfr(2047, ms[k], xs[i], 256);
            const double e = fabs(t - r) / fmax(1.0, fabs(r));
            worst = fmax(worst, e);
            ck_assert_msg(e <= 1e-14 && (r == 0.0 || (t != 0.0 && (t > 0) == (r > 0)) || fabs(r) < 1e-290),
                          "Q_2047^%d(%.7f): long double %.17g, MPFR %.17g", ms[k], xs[i], t, r);
        }
    printf("test_sht_highband: truth vs MPFR at l = 2047: max error %.3g (relative to max(1, |Q|))\n", worst);
}
END_TEST

/* ------------------------------------------- single bands: every grid point */

/* The m of band L that a test sets: 0..3, L−3..L and about 40 between. */
static int band_ms(int L, int *ms)
{
    int n = 0;
    const int step = L / 40 > 1 ? L / 40 : 1;
    for (int m = 0; m <= L; m++)
        if (m <= 3 || m >= L - 3 || m % step == 0 || m == L / 2 || m == L / 4) ms[n++] = m;
    return n;
}

typedef struct {
    int L, nr, np, nm;
    double *x, *w, *c, *truth;
    sh_grid g;
    int ms[128];
    double a[128], b[128]; /* c_L^m, c_L^{−m} */
} band_case;

/* f = Σ_{m ∈ ms} √2 Q_L^m(x)(a_m cos mφ + b_m sin mφ) (m = 0: Q_L^0 a_0), the
 * map of the coefficient vector with c_L^{±m} = a_m, b_m in shlab's cs basis. */
static void band_truth(band_case *k)
{
    const size_t n = (size_t)k->nr * k->np;
    k->truth = calloc(n, sizeof(double));
    double *cs = malloc(sizeof(double) * 2 * k->np * k->nm);
    for (int i = 0; i < k->nm; i++)
        for (int j = 0; j < k->np; j++) {
            /* m φ_j = 2π (m j mod np)/np + m φ0, the integer part reduced exactly */
            const long mj = (long)k->ms[i] * j % k->np;
            const double arg = 2.0 * M_PI * mj / k->np + k->ms[i] * k->g.phi0;
            cs[(2 * i) * k->np + j] = cos(arg);
            cs[(2 * i + 1) * k->np + j] = sin(arg);
        }
    for (int r = 0; r < k->nr; r++) {
        double *row = k->truth + (size_t)r * k->np;
        for (int i = 0; i < k->nm; i++) {
            const int m = k->ms[i];
            const double q = truth_qlm(k->L, m, k->x[r]);
            if (q == 0.0) continue;
            const double A = (m ? M_SQRT2 : 1.0) * q * k->a[i], B = m ? M_SQRT2 * q * k->b[i] : 0.0;
            const double *co = cs + (size_t)(2 * i) * k->np, *si = co + k->np;
            for (int j = 0; j < k->np; j++) row[j] += A * co[j] + B * si[j];
        }
    }
    free(cs);
}

static band_case band_make(int L, int latlong, unsigned seed)
{
    band_case k = {L, L + 1, 2 * L + 2, 0, NULL, NULL, NULL, NULL, {0}, {0}, {0}, {0}};
    k.x = malloc(sizeof(double) * k.nr);
    k.w = malloc(sizeof(double) * k.nr);
    if (latlong) ck_assert_int_eq(sh_grid_latlong(k.np, k.nr, k.x, k.w, &k.g), SH_OK);
    else ck_assert_int_eq(sh_grid_gauss(k.nr, k.np, k.x, k.w, &k.g), SH_OK);
    k.nm = band_ms(L, k.ms);
    ck_assert_int_le(k.nm, 128);
    const int order = L + 1;
    k.c = calloc((size_t)order * order, sizeof(double));
    for (int i = 0; i < k.nm; i++) {
        k.a[i] = 1.0 + urand(&seed);
        k.b[i] = k.ms[i] ? 1.0 + urand(&seed) : 0.0;
        k.c[sh_index(L, k.ms[i])] = k.a[i];
        if (k.ms[i]) k.c[sh_index(L, -k.ms[i])] = k.b[i];
    }
    band_truth(&k);
    return k;
}

static void band_free(band_case *k) { free(k->x), free(k->w), free(k->c), free(k->truth); }

/* Synthesis of band L (about 45 m from 0 to L at once, cos and sin parts)
 * compared with the truth at every point; on the Gauss grid, analysis of the
 * true map returns exactly those coefficients and zero elsewhere. */
static void run_band(int L, int latlong)
{
    band_case k = band_make(L, latlong, 1000u + L);
    const int order = L + 1;
    const size_t n = (size_t)k.nr * k.np, nn = (size_t)order * order;
    sh_sht *p;
    ck_assert_int_eq(sh_sht_create(order, &k.g, 1, 1, &p), SH_OK);
    double *map = malloc(sizeof(double) * n);
    ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, map), SH_OK);
    double d = 0.0, mx = 0.0;
    size_t at = 0;
    for (size_t i = 0; i < n; i++) {
        const double e = fabs(map[i] - k.truth[i]);
        if (!(e <= d)) d = e, at = i; /* NaN is caught */
        mx = fmax(mx, fabs(k.truth[i]));
    }
    printf("test_sht_highband: %s %d×%d, band %d (%d m): synthesis max error %.3g of max|f| %.3g\n",
           latlong ? "lat-long" : "Gauss", k.nr, k.np, L, k.nm, d / mx, mx);
    ck_assert_msg(d <= 1e-12 * mx, "%s band %d: synthesis off by %.3g (max|f| %.3g) at ring %zu (cosθ %.6f) point %zu",
                  latlong ? "lat-long" : "Gauss", L, d, mx, at / k.np, k.x[at / k.np], at % k.np);
    if (!latlong) {
        double *c = malloc(sizeof(double) * nn);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.truth, c), SH_OK);
        double e = 0.0;
        int el = 0, em = 0;
        for (int l = 0; l <= L; l++)
            for (int m = -l; m <= l; m++) {
                const size_t i = sh_index(l, m);
                const double di = fabs(c[i] - k.c[i]);
                if (!(di <= e)) e = di, el = l, em = m;
            }
        printf("test_sht_highband: Gauss band %d: analysis of the true map, max coefficient error %.3g\n", L, e);
        ck_assert_msg(e <= 1e-12, "Gauss band %d: analysis off by %.3g at (%d, %d)", L, e, el, em);
        free(c);
    }
    sh_sht_destroy(p);
    free(map);
    band_free(&k);
}

START_TEST(band_gauss) { run_band(LMAXES[_i], 0); }
END_TEST

START_TEST(band_latlong) { run_band(LMAXES[_i], 1); }
END_TEST

/* ------------------------------------- random vectors: round trip, chunking */

/* Synthesis then analysis on the Gauss grid of lmax L is the identity
 * (‖Δc‖₂/‖c‖₂ ≤ 1e−12), with the plan's own chunks and with chunks of one
 * kernel block (SHT_LANES pairs), so that chunk boundaries fall at every
 * 32nd ring pair: the synthesis is bitwise the same (each ring pair is
 * computed alone), the analysis the same up to the order of the sums. */
START_TEST(round_trip_chunks)
{
    const int L = LMAXES[_i], order = L + 1, nr = L + 1, np = 2 * L + 2;
    const size_t nn = (size_t)order * order, n = (size_t)nr * np;
    double *x = malloc(sizeof(double) * nr * 2);
    sh_grid g;
    ck_assert_int_eq(sh_grid_gauss(nr, np, x, x + nr, &g), SH_OK);
    unsigned seed = 77u + L;
    double *c = malloc(sizeof(double) * nn), *map[2], *back[2];
    for (size_t i = 0; i < nn; i++) c[i] = urand(&seed);
    for (int t = 0; t < 2; t++) {
        sh_sht *p;
        ck_assert_int_eq(sh_sht_create(order, &g, 1, 1, &p), SH_OK);
        if (t) ck_assert_int_eq(sh__sht_set_chunk(p, SHT_LANES), SH_OK);
        map[t] = malloc(sizeof(double) * n);
        back[t] = malloc(sizeof(double) * nn);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, c, map[t]), SH_OK);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, map[t], back[t]), SH_OK);
        sh_sht_destroy(p);
        double d2 = 0.0, c2 = 0.0, dm = 0.0, cm = 0.0;
        for (size_t i = 0; i < nn; i++) {
            const double d = back[t][i] - c[i];
            d2 += d * d, c2 += c[i] * c[i];
            dm = fmax(dm, fabs(d)), cm = fmax(cm, fabs(c[i]));
        }
        const double rel = sqrt(d2 / c2);
        printf("test_sht_highband: Gauss lmax %d, %s: round trip ‖Δc‖/‖c‖ %.3g, max|Δc|/max|c| %.3g\n", L,
               t ? "chunks of 32 pairs" : "plan's chunks", rel, dm / cm);
        ck_assert_msg(isfinite(rel) && rel <= 1e-12, "lmax %d round trip %.3g", L, rel);
    }
    ck_assert_msg(!memcmp(map[0], map[1], sizeof(double) * n), "lmax %d: synthesis depends on the chunks", L);
    double d2 = 0.0, c2 = 0.0;
    for (size_t i = 0; i < nn; i++) d2 += (back[1][i] - back[0][i]) * (back[1][i] - back[0][i]), c2 += c[i] * c[i];
    ck_assert_msg(sqrt(d2 / c2) <= 1e-15, "lmax %d: analysis, chunks of 32 vs the plan's: %.3g", L, sqrt(d2 / c2));
    for (int t = 0; t < 2; t++) free(map[t]), free(back[t]);
    free(x), free(c);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("sht_highband");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, truth_vs_mpfr);
    tcase_add_loop_test(tc, band_gauss, 0, NLMAX);
    tcase_add_loop_test(tc, band_latlong, 0, NLMAX);
    tcase_add_loop_test(tc, round_trip_chunks, 0, NLMAX);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
