/* test_sht.c — the fast spherical harmonic transforms (src/project/sht.c).
 *
 * Truths used: the direct sums the transforms replaced (sh__*_direct, one
 * sh__legendre_core call and a direct sum in φ per ring); exactness of the
 * Gauss product rule (synthesis then analysis is the identity for band-limited
 * input); the addition theorem P_l(u·v) = 4π/(2l+1) Σ_m y_l^m(u) y_l^m(v), which
 * gives the coefficients of Σ_l a_l P_l(s·v) in closed form (P_l from GSL); the
 * adjoint identity ⟨A f, c⟩ = ⟨f, W S c⟩ between the analysis and synthesis
 * kernels; sh_eval (legendre.c, its own extended-exponent recursion) at high
 * order near the poles; every instruction set against the baseline kernels;
 * and bitwise equality across thread counts and chunkings. */
#include "testutil.h"

#include "project/sht_internal.h"

#include <string.h>

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffffff) / (double)0x1000000 - 0.5;
}

static double norm2(const double *a, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++) s += a[i] * a[i];
    return sqrt(s);
}

/* ‖a − b‖₂ / ‖b‖₂ (‖b‖ = 0: ‖a‖) */
static double rel_l2(const double *a, const double *b, size_t n)
{
    double d = 0.0;
    for (size_t i = 0; i < n; i++) d += (a[i] - b[i]) * (a[i] - b[i]);
    const double nb = norm2(b, n);
    return nb > 0.0 ? sqrt(d) / nb : sqrt(d);
}

/* max |a − b| / max(|b|, floor) */
static double rel_max(const double *a, const double *b, size_t n, double floor)
{
    double d = 0.0, m = floor;
    for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        m = fmax(m, fabs(b[i]));
    }
    return isfinite(d) ? d / m : INFINITY;
}

/* ---- a function with known coefficients: the Poisson kernel about v_k,
 *   P_r(u) = (1 − r²) / (4π (1 − 2ru + r²)^{3/2}) = Σ_l (2l+1)/(4π) r^l P_l(u),
 * so by the addition theorem f = Σ_k P_r(s·v_k) has c_l^m = Σ_k r^l y_l^m(v_k).
 * f is evaluated in closed form (a few ulps); the S-node Gauss rule
 * integrates f·y_l^m up to the tail r^{2S−l}. */
#define NKER 3
typedef struct {
    double r, v[NKER][3];
} kernel_fn;

static void kernel_init(kernel_fn *K, double r)
{
    K->r = r;
    const double ang[NKER][2] = {{0.3, 1.1}, {2.0, 4.0}, {1.5707963267948966, 0.2}};
    for (int k = 0; k < NKER; k++) sh_dir_from_angles(ang[k][0], ang[k][1], K->v[k]);
}

static double kernel_eval(const double d[3], double theta, double phi, void *ctx)
{
    const kernel_fn *K = ctx;
    double f = 0.0;
    for (int k = 0; k < NKER; k++) {
        const double u = d[0] * K->v[k][0] + d[1] * K->v[k][1] + d[2] * K->v[k][2];
        const double q = 1.0 - 2.0 * K->r * u + K->r * K->r;
        f += (1.0 - K->r * K->r) / (4.0 * M_PI * q * sqrt(q));
    }
    return f;
}

static void kernel_coeffs(const kernel_fn *K, int order, sh_convention conv, double *c)
{
    const int nn = order * order;
    double *y = malloc(sizeof(double) * nn);
    memset(c, 0, sizeof(double) * nn);
    for (int k = 0; k < NKER; k++) {
        ck_assert_int_eq(sh_eval_dir(order, conv, K->v[k], y), SH_OK);
        for (int i = 0; i < nn; i++) {
            int l, m;
            sh_index_lm(i, &l, &m);
            c[i] += pow(K->r, l) * y[i];
        }
    }
    free(y);
}

/* A Gauss grid of nr × np with a seeded map f and coefficient vector c (one
 * channel); free with case_free. */
typedef struct {
    int order, nr, np, nn;
    double *x, *f, *c;
    sh_grid g;
} rcase;

static rcase case_make(int order, int nr, int np, unsigned seed)
{
    rcase k = {order, nr, np, order * order, malloc(sizeof(double) * nr * 2),
               malloc(sizeof(double) * nr * np), malloc(sizeof(double) * order * order), {0}};
    ck_assert_int_eq(sh_grid_gauss(nr, np, k.x, k.x + nr, &k.g), SH_OK);
    for (int i = 0; i < nr * np; i++) k.f[i] = urand(&seed);
    for (int i = 0; i < k.nn; i++) k.c[i] = urand(&seed);
    return k;
}

static void case_free(rcase *k) { free(k->x), free(k->f), free(k->c); }

/* ------------------------------------------------------------------ tests */

/* sh_project (QUAD) against the direct sum on Green's kinked light: both
 * evaluate the same discrete sums, whatever the rule's own error; S < order
 * makes m ≥ 2S alias in φ, which the FFT path must fold like the direct sum. */
START_TEST(quad_matches_direct_sum)
{
    sh_light L;
    ck_assert_int_eq(sh_light_parse("green", 0, &L), SH_OK);
    const int orders[] = {1, 2, 7, 24};
    const long Ss[] = {1, 2, 5, 30, 31};
    double a[576], b[576];
    for (int io = 0; io < 4; io++)
        for (int is = 0; is < 5; is++)
            for (int conv = 0; conv < 2; conv++) {
                const int n = orders[io];
                ck_assert_int_eq(sh_project(n, conv, sh_light_fn, &L, SH_RULE_QUAD, Ss[is], 0, a), SH_OK);
                ck_assert_int_eq(sh__project_quad_direct(n, conv, sh_light_fn, &L, Ss[is], b), SH_OK);
                const double e = rel_max(a, b, (size_t)n * n, 1.0);
                ck_assert_msg(e <= 1e-14, "order %d S %ld conv %d: fast vs direct %.3g", n, Ss[is], conv, e);
            }
}
END_TEST

/* Lat-long projection against the direct per-row sum, odd and even sizes,
 * widths below 2·order (aliasing), 1 and 3 channels; orders 12 and 15 (the
 * AVX-512 ring stage takes m four at a time: 15 leaves three to the scalar
 * tail), with the grid's φ0 = half a pixel. */
START_TEST(latlong_matches_direct_sum)
{
    const int sizes[][2] = {{8, 4}, {9, 5}, {20, 7}, {33, 16}, {64, 32}};
    unsigned seed = 7;
    for (int k = 0; k < 10; k++)
        for (int nc = 1; nc <= 3; nc += 2)
            for (int conv = 0; conv < 2; conv++) {
                const int W = sizes[k % 5][0], H = sizes[k % 5][1], order = k < 5 ? 12 : 15, nn = order * order;
                sh_image img = {W, H, nc, {"R", "G", "B"}, malloc(sizeof(float) * W * H * nc)};
                for (int i = 0; i < W * H * nc; i++) img.data[i] = (float)(2.0 + urand(&seed));
                double *a = malloc(sizeof(double) * nn * nc), *b = malloc(sizeof(double) * nn * nc);
                ck_assert_int_eq(sh_project_image(&img, SH_LAYOUT_LATLONG, order, conv, a), SH_OK);
                ck_assert_int_eq(sh__project_latlong_direct(&img, order, conv, b), SH_OK);
                const double e = rel_max(a, b, (size_t)nn * nc, 1e-300);
                ck_assert_msg(e <= 1e-13, "%d×%d nchan %d conv %d: fast vs direct %.3g", W, H, nc, conv, e);
                free(a), free(b), sh_image_free(&img);
            }
}
END_TEST

/* Synthesis on the lat-long grid against the direct row synthesis, with a
 * window, widths from 2 (aliasing of every m > 0) to 65. */
START_TEST(synthesis_matches_direct_sum)
{
    const int widths[] = {2, 3, 8, 9, 64, 65};
    unsigned seed = 11;
    sh_window win;
    ck_assert_int_eq(sh_window_parse("hann:9", &win), SH_OK);
    for (int k = 0; k < 6; k++)
        for (int conv = 0; conv < 2; conv++) {
            const int order = 10, nn = order * order, W = widths[k], H = W / 2;
            double c[100], sig[10];
            for (int i = 0; i < nn; i++) c[i] = urand(&seed);
            for (int l = 0; l < order; l++) sig[l] = sh_window_factor(&win, l, order);
            double *x = malloc(sizeof(double) * H), *fast = malloc(sizeof(double) * W * H);
            double *ref = malloc(sizeof(double) * W * H);
            sh_grid g;
            sh_sht *p;
            ck_assert_int_eq(sh_grid_latlong(W, H, x, NULL, &g), SH_OK);
            ck_assert_int_eq(sh_sht_create(order, &g, 1, 1, &p), SH_OK);
            double cw[100];
            for (int i = 0; i < nn; i++) {
                int l, m;
                sh_index_lm(i, &l, &m);
                cw[i] = c[i] * sig[l];
            }
            ck_assert_int_eq(sh_sht_synthesis(p, conv, cw, fast), SH_OK);
            ck_assert_int_eq(sh__reconstruct_latlong_direct(order, conv, c, &win, W, ref), SH_OK);
            const double e = rel_max(fast, ref, (size_t)W * H, 1.0);
            ck_assert_msg(e <= 1e-13, "width %d conv %d: synthesis vs direct %.3g", W, conv, e);
            /* the float image is the same values rounded */
            sh_image img;
            ck_assert_int_eq(sh_reconstruct_latlong(order, conv, c, 1, &win, W, &img), SH_OK);
            for (int i = 0; i < W * H; i++)
                ck_assert_msg(fabs(img.data[i] - ref[i]) <= 1e-6 * fmax(1.0, fabs(ref[i])),
                              "width %d pixel %d: %g vs %g", W, i, img.data[i], ref[i]);
            sh_image_free(&img);
            sh_sht_destroy(p);
            free(x), free(fast), free(ref);
        }
}
END_TEST

/* Synthesis then analysis on a Gauss grid with nrings ≥ order and nphi ≥
 * 2·order − 1 is the identity on band-limited input (the rule is exact for
 * y_i·y_j), for odd and even ring counts and 1 or 3 channels. */
START_TEST(gauss_round_trip)
{
    const int cases[][3] = {{1, 1, 1}, {2, 2, 3}, {3, 3, 5}, {17, 17, 33}, {17, 20, 40},
                            {64, 64, 128}, {129, 130, 257}, {200, 201, 400}};
    unsigned seed = 3;
    for (int k = 0; k < 8; k++)
        for (int nc = 1; nc <= 3; nc += 2) {
            const int order = cases[k][0], nr = cases[k][1], np = cases[k][2], nn = order * order;
            double *x = malloc(sizeof(double) * nr * 2), *c = malloc(sizeof(double) * nn * nc);
            double *back = malloc(sizeof(double) * nn * nc), *map = malloc(sizeof(double) * nr * np * nc);
            for (int i = 0; i < nn * nc; i++) c[i] = urand(&seed);
            sh_grid g;
            sh_sht *p;
            ck_assert_int_eq(sh_grid_gauss(nr, np, x, x + nr, &g), SH_OK);
            ck_assert_int_eq(sh_sht_create(order, &g, nc, 1, &p), SH_OK);
            for (int conv = 0; conv < 2; conv++) {
                ck_assert_int_eq(sh_sht_synthesis(p, conv, c, map), SH_OK);
                ck_assert_int_eq(sh_sht_analysis(p, conv, map, back), SH_OK);
                const double e = rel_l2(back, c, (size_t)nn * nc);
                ck_assert_msg(e <= 5e-14, "order %d rings %d nphi %d nchan %d conv %d: round trip %.3g", order,
                              nr, np, nc, conv, e);
            }
            sh_sht_destroy(p);
            free(x), free(c), free(back), free(map);
        }
}
END_TEST

/* sh_project of the Poisson kernels (r = 0.55: the tail r^{2·64−l} < 1e−16
 * for every l < 64) on 64 Gauss nodes against the addition theorem's closed
 * form; and the analytic lights' closed forms (const exactly; the lobe's kink
 * at the equator and the cap's edge converge slowly, so the rule's own error
 * sets those tolerances, and the fast path must match the direct sum there to
 * rounding). */
START_TEST(closed_forms)
{
    kernel_fn K;
    kernel_init(&K, 0.55);
    const int order = 64, nn = order * order;
    double *c = malloc(sizeof(double) * nn), *ref = malloc(sizeof(double) * nn);
    for (int conv = 0; conv < 2; conv++) {
        kernel_coeffs(&K, order, conv, ref);
        ck_assert_int_eq(sh_project(order, conv, kernel_eval, &K, SH_RULE_QUAD, 64, 0, c), SH_OK);
        const double e2 = rel_l2(c, ref, nn), em = rel_max(c, ref, nn, 0.0);
        ck_assert_msg(e2 <= 1e-14 && em <= 1e-14, "kernel, conv %d: rel L2 %.3g, max %.3g", conv, e2, em);
    }
    const char *specs[] = {"const:2.5", "lobe:3", "cap:0.7"};
    const double tol[] = {1e-15, 1e-7, 2e-3};
    for (int k = 0; k < 3; k++) {
        sh_light L;
        ck_assert_int_eq(sh_light_parse(specs[k], 0, &L), SH_OK);
        double q[100], d[100], cf[100];
        ck_assert_int_eq(sh_light_closed_form(&L, 10, SH_CS, cf), SH_OK);
        ck_assert_int_eq(sh_project(10, SH_CS, sh_light_fn, &L, SH_RULE_QUAD, 400, 0, q), SH_OK);
        ck_assert_int_eq(sh__project_quad_direct(10, SH_CS, sh_light_fn, &L, 400, d), SH_OK);
        ck_assert_msg(rel_max(q, d, 100, 1.0) <= 1e-14, "%s: fast vs direct", specs[k]);
        ck_assert_msg(rel_max(q, cf, 100, 1.0) <= tol[k], "%s: quad vs closed form %.3g", specs[k],
                      rel_max(q, cf, 100, 1.0));
    }
    free(c), free(ref);
}
END_TEST

/* ⟨A f, c⟩ = ⟨f, W S c⟩: analysis A = Sᵀ·diag(w), so the analysis and the
 * synthesis kernels check each other (any grid, not only exact rules). */
START_TEST(adjoint_identity)
{
    unsigned seed = 5;
    for (int k = 0; k < 3; k++) {
        const int order = k == 2 ? 90 : 33, nc = k == 1 ? 3 : 1, nn = order * order;
        const int nr = k == 0 ? 21 : 64, np = k == 0 ? 50 : 128;
        double *x = malloc(sizeof(double) * nr * 2);
        sh_grid g;
        if (k == 0) ck_assert_int_eq(sh_grid_gauss(nr, np, x, x + nr, &g), SH_OK);
        else ck_assert_int_eq(sh_grid_latlong(np, nr, x, x + nr, &g), SH_OK);
        sh_sht *p;
        ck_assert_int_eq(sh_sht_create(order, &g, nc, 2, &p), SH_OK);
        const size_t nm = (size_t)nr * np * nc;
        double *f = malloc(sizeof(double) * nm), *Sc = malloc(sizeof(double) * nm);
        double *c = malloc(sizeof(double) * nn * nc), *Af = malloc(sizeof(double) * nn * nc);
        for (size_t i = 0; i < nm; i++) f[i] = urand(&seed);
        for (int i = 0; i < nn * nc; i++) c[i] = urand(&seed);
        for (int conv = 0; conv < 2; conv++) {
            ck_assert_int_eq(sh_sht_analysis(p, conv, f, Af), SH_OK);
            ck_assert_int_eq(sh_sht_synthesis(p, conv, c, Sc), SH_OK);
            double lhs = 0.0, rhs = 0.0, scale = 0.0;
            for (int i = 0; i < nn * nc; i++) lhs += Af[i] * c[i];
            for (size_t i = 0; i < nm; i++) {
                const double t = f[i] * x[nr + (i / np) % nr] * Sc[i];
                rhs += t;
                scale += fabs(t);
            }
            ck_assert_msg(fabs(lhs - rhs) <= 1e-14 * scale, "grid %d conv %d: <Af,c> %.17g <f,WSc> %.17g",
                          k, conv, lhs, rhs);
        }
        sh_sht_destroy(p);
        free(x), free(f), free(Sc), free(c), free(Af);
    }
}
END_TEST

/* Results do not depend on the number of threads (bitwise), with several
 * chunks of rings; and the chunking changes the analysis only by rounding
 * (chunks are summed in order) and the synthesis not at all. */
START_TEST(threads_bitwise)
{
    const int order = 80, nr = 150, np = 161, nc = 3, nn = order * order;
    unsigned seed = 9;
    double *x = malloc(sizeof(double) * nr * 2);
    sh_grid g;
    ck_assert_int_eq(sh_grid_latlong(np, nr, x, x + nr, &g), SH_OK);
    const size_t nm = (size_t)nr * np * nc;
    double *f = malloc(sizeof(double) * nm), *c = malloc(sizeof(double) * nn * nc);
    for (size_t i = 0; i < nm; i++) f[i] = urand(&seed);
    for (int i = 0; i < nn * nc; i++) c[i] = urand(&seed);
    double *A[4], *S[4];
    for (int t = 0; t < 4; t++) {
        sh_sht *p;
        ck_assert_int_eq(sh_sht_create(order, &g, nc, t == 3 ? 2 : t + 1, &p), SH_OK);
        if (t < 3) ck_assert_int_eq(sh__sht_set_chunk(p, SHT_LANES), SH_OK); /* 3 chunks */
        A[t] = malloc(sizeof(double) * nn * nc);
        S[t] = malloc(sizeof(double) * nm);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, f, A[t]), SH_OK);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, c, S[t]), SH_OK);
        sh_sht_destroy(p);
    }
    for (int t = 1; t < 3; t++) {
        ck_assert_msg(!memcmp(A[0], A[t], sizeof(double) * nn * nc), "analysis: %d threads differ", t + 1);
        ck_assert_msg(!memcmp(S[0], S[t], sizeof(double) * nm), "synthesis: %d threads differ", t + 1);
    }
    ck_assert_msg(rel_l2(A[3], A[0], (size_t)nn * nc) <= 1e-15, "analysis: one chunk vs three");
    ck_assert_msg(!memcmp(S[0], S[3], sizeof(double) * nm), "synthesis: one chunk vs three");
    for (int t = 0; t < 4; t++) free(A[t]), free(S[t]);
    free(x), free(f), free(c);
}
END_TEST

/* Regression: the kernels took the row stride of the chunk's lane arrays
 * from the padded lane count of the chunk, wrong for a last chunk narrower
 * than the others (found as sh_project at order 300 with 1154 nodes off by
 * 2e−3).  70 pairs in chunks of 64: the second holds 6 (32 padded). */
START_TEST(partial_last_chunk)
{
    rcase k = case_make(40, 140, 81, 21);
    const int nn = k.nn, nm = k.nr * k.np;
    double *a[2], *m[2];
    for (int t = 0; t < 2; t++) {
        sh_sht *p;
        ck_assert_int_eq(sh_sht_create(k.order, &k.g, 1, 1, &p), SH_OK);
        if (t) ck_assert_int_eq(sh__sht_set_chunk(p, 2 * SHT_LANES), SH_OK);
        a[t] = malloc(sizeof(double) * nn);
        m[t] = malloc(sizeof(double) * nm);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.f, a[t]), SH_OK);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, m[t]), SH_OK);
        sh_sht_destroy(p);
    }
    ck_assert_msg(rel_l2(a[1], a[0], nn) <= 1e-15, "analysis: two chunks vs one %.3g", rel_l2(a[1], a[0], nn));
    ck_assert_msg(!memcmp(m[0], m[1], sizeof(double) * nm), "synthesis: two chunks vs one");
    for (int t = 0; t < 2; t++) free(a[t]), free(m[t]);
    case_free(&k);
}
END_TEST

/* A plan of one chunk keeps the sectoral seeds of its first transform for
 * the next ones; a new chunking must drop them.  The truth is a fresh plan
 * with the same chunking: the same bytes.  Sequence on one plan: analysis
 * (seeds made), synthesis and analysis again (seeds kept), chunks of 64
 * pairs (70 pairs: two chunks), analysis, then one chunk again. */
START_TEST(seeds_kept_and_dropped)
{
    rcase k = case_make(40, 140, 81, 23);
    const int nn = k.nn, nm = k.nr * k.np;
    double *fresh[2], *m0 = malloc(sizeof(double) * nm), *m1 = malloc(sizeof(double) * nm);
    for (int t = 0; t < 2; t++) { /* fresh plans: one chunk, two chunks */
        sh_sht *q;
        ck_assert_int_eq(sh_sht_create(k.order, &k.g, 1, 1, &q), SH_OK);
        if (t) ck_assert_int_eq(sh__sht_set_chunk(q, 2 * SHT_LANES), SH_OK);
        fresh[t] = malloc(sizeof(double) * nn);
        ck_assert_int_eq(sh_sht_analysis(q, SH_CS, k.f, fresh[t]), SH_OK);
        if (!t) ck_assert_int_eq(sh_sht_synthesis(q, SH_CS, k.c, m0), SH_OK);
        sh_sht_destroy(q);
    }
    sh_sht *p;
    double *a = malloc(sizeof(double) * nn);
    ck_assert_int_eq(sh_sht_create(k.order, &k.g, 1, 1, &p), SH_OK);
    for (int step = 0; step < 4; step++) {
        if (step == 2) ck_assert_int_eq(sh__sht_set_chunk(p, 2 * SHT_LANES), SH_OK);
        if (step == 3) ck_assert_int_eq(sh__sht_set_chunk(p, 3 * SHT_LANES), SH_OK); /* one chunk again */
        if (step == 1) {
            ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, m1), SH_OK);
            ck_assert_msg(!memcmp(m0, m1, sizeof(double) * nm), "synthesis with the seeds kept");
        }
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.f, a), SH_OK);
        ck_assert_msg(!memcmp(a, fresh[step == 2], sizeof(double) * nn), "analysis at step %d", step);
    }
    sh_sht_destroy(p);
    free(a), free(m0), free(m1), free(fresh[0]), free(fresh[1]);
    case_free(&k);
}
END_TEST

/* Groups of lanes that never reach a live value up to lmax (the sectoral
 * seed sin^m θ below 2^−400 and no turning point l ≈ m / sin θ before lmax)
 * are flagged by the first transform and skipped by the next ones.  Skipping
 * must change no bit, for every instruction set, and a change of set must
 * drop the flags.  A block that starts below 2^−400 can reach O(1) values
 * only from lmax ≈ 753 on (m log₂(1/sin θ) > 400 and l ≥ m / sin θ), so the
 * test runs order 900 — on 64 ring pairs from θ = 0.02 to π/2, which makes
 * both kinds of block, and keeps it cheap. */
START_TEST(dead_groups_skipped)
{
    enum { order = 900, npair = 64, nr = 2 * npair, np = 2 * order };
    const int nn = order * order, nm = nr * np;
    double x[nr], w[nr];
    for (int k = 0; k < npair; k++) {
        const double th = 0.02 + k * (M_PI / 2 - 0.04) / (npair - 1);
        x[k] = cos(th), x[nr - 1 - k] = -x[k];
        w[k] = w[nr - 1 - k] = sin(th) * (M_PI / 2) / npair;
    }
    const sh_grid g = {nr, np, x, w, 0.0};
    unsigned seed = 31;
    double *f = malloc(sizeof(double) * nm), *c = malloc(sizeof(double) * nn);
    for (int i = 0; i < nm; i++) f[i] = urand(&seed);
    for (int i = 0; i < nn; i++) c[i] = urand(&seed);
    double *a0 = malloc(sizeof(double) * nn), *a1 = malloc(sizeof(double) * nn);
    double *s0 = malloc(sizeof(double) * nm), *s1 = malloc(sizeof(double) * nm);
    const sht_isa sets[] = {SHT_ISA_BASE, SHT_ISA_AVX2, SHT_ISA_AVX512};
    sh_sht *p;
    ck_assert_int_eq(sh_sht_create(order, &g, 1, 1, &p), SH_OK);
    for (int i = 0; i < 3; i++) {
        if (!sh__sht_isa_usable(sets[i])) continue;
        const char *isa = sh__sht_isa_name(sets[i]);
        ck_assert_int_eq(sh__sht_set_isa(p, sets[i]), SH_OK);
        ck_assert_int_eq(sh__sht_dead_groups(p), 0);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, f, a0), SH_OK);
        const int dead = sh__sht_dead_groups(p);
        ck_assert_msg(dead > 0, "%s: no group flagged", isa);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, f, a1), SH_OK);
        ck_assert_msg(!memcmp(a0, a1, sizeof(double) * nn), "%s: analysis with skips", isa);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, c, s0), SH_OK);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, c, s1), SH_OK);
        ck_assert_msg(!memcmp(s0, s1, sizeof(double) * nm), "%s: synthesis with skips", isa);
        ck_assert_int_ge(sh__sht_dead_groups(p), dead); /* the synthesis's blocks may be narrower */
    }
    sh_sht_destroy(p);
    free(f), free(c), free(a0), free(a1), free(s0), free(s1);
}
END_TEST

/* The same on the full Gauss grid of lmax 1023 (1024 × 2048, one channel:
 * the largest one-chunk plan the transforms are timed on, docs/high-bands.md),
 * on the kernels this CPU picks: a kept plan's second synthesis and analysis
 * skip groups and give the same bytes as the first (flags cleared by a
 * change of set), and the round trip returns the coefficients to 1e-12
 * normwise — Gauss quadrature with lmax + 1 rings is exact on band-limited
 * maps.  (test_sht_highband checks the same sizes against the truth; this
 * is the check that a kept plan's skips change nothing there.) */
START_TEST(dead_groups_full_grid)
{
    rcase k = case_make(1024, 1024, 2048, 37);
    const int nn = k.nn, nm = k.nr * k.np;
    double *a0 = malloc(sizeof(double) * nn), *a1 = malloc(sizeof(double) * nn);
    double *s1 = malloc(sizeof(double) * nm);
    sh_sht *p;
    ck_assert_int_eq(sh_sht_create(k.order, &k.g, 1, 1, &p), SH_OK);
    ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, k.f), SH_OK); /* no skips: k.f is the map */
    const int dead = sh__sht_dead_groups(p);
    ck_assert_msg(dead > 0, "no group flagged at lmax 1023");
    ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, s1), SH_OK);
    ck_assert_msg(!memcmp(k.f, s1, sizeof(double) * nm), "synthesis with skips");
    ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.f, a1), SH_OK);
    ck_assert_int_eq(sh__sht_set_isa(p, SHT_ISA_AUTO), SH_OK); /* the flags dropped */
    ck_assert_int_eq(sh__sht_dead_groups(p), 0);
    ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.f, a0), SH_OK);
    ck_assert_msg(!memcmp(a0, a1, sizeof(double) * nn), "analysis with skips");
    const double e = rel_l2(a1, k.c, (size_t)nn); /* normwise, the bound of test_sht_highband */
    printf("test_sht: lmax 1023 Gauss grid, %d dead groups; round trip with skips %.3g (relative L2)\n", dead, e);
    ck_assert_msg(e <= 1e-12, "round trip at lmax 1023: %.3g", e);
    sh_sht_destroy(p);
    free(a0), free(a1), free(s1);
    case_free(&k);
}
END_TEST

/* Every instruction set compiled in and usable here against the baseline
 * kernels (they differ by FMA rounding only). */
START_TEST(isa_kernels_agree)
{
    rcase k = case_make(150, 151, 300, 13);
    const int nn = k.nn, nm = k.nr * k.np;
    double *a0 = malloc(sizeof(double) * nn), *a1 = malloc(sizeof(double) * nn);
    double *s0 = malloc(sizeof(double) * nm), *s1 = malloc(sizeof(double) * nm);
    sh_sht *p;
    ck_assert_int_eq(sh_sht_create(k.order, &k.g, 1, 1, &p), SH_OK);
    ck_assert_int_eq(sh__sht_set_isa(p, SHT_ISA_BASE), SH_OK);
    ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.f, a0), SH_OK);
    ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, s0), SH_OK);
    int tried = 0;
    for (int isa = SHT_ISA_AVX2; isa <= SHT_ISA_AVX512; isa++) {
        if (!sh__sht_isa_usable(isa)) {
            ck_assert_int_eq(sh__sht_set_isa(p, isa), SH_ENOTSUP);
            continue;
        }
        tried++;
        ck_assert_int_eq(sh__sht_set_isa(p, isa), SH_OK);
        ck_assert_int_eq(sh_sht_analysis(p, SH_CS, k.f, a1), SH_OK);
        ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, k.c, s1), SH_OK);
        ck_assert_msg(rel_l2(a1, a0, nn) <= 1e-14, "%s analysis vs baseline %.3g", sh__sht_isa_name(isa),
                      rel_l2(a1, a0, nn));
        ck_assert_msg(rel_l2(s1, s0, nm) <= 1e-14, "%s synthesis vs baseline %.3g", sh__sht_isa_name(isa),
                      rel_l2(s1, s0, nm));
    }
    printf("test_sht: %d instruction set(s) beyond the baseline compared\n", tried);
    sh_sht_destroy(p);
    free(a0), free(a1), free(s0), free(s1);
    case_free(&k);
}
END_TEST

/* Order 2049 near the poles: sectoral seeds far below the double range
 * (sin θ^m at θ = 0.5°, m = 1500 is ~1e−3500) must be carried, not flushed,
 * until the values are representable again.  Checked against sh_eval, whose
 * legendre.c carries its own extended exponent; unpaired rings included. */
START_TEST(high_order_near_poles)
{
    const int order = 2049, nn = order * order, np = 3;
    const double th[] = {0.5, 10.0, 1.0, 170.0, 179.0}; /* degrees; 10/170 pair up, the others single */
    const int nr = 5;
    double x[5];
    for (int r = 0; r < nr; r++) x[r] = r == 3 ? -x[1] : cos(th[r] * M_PI / 180.0);
    const int lm[][2] = {{2048, 200}, {2048, -1500}, {2000, 1499}, {1700, -60}, {300, 10}, {2048, 0}};
    double *c = calloc(nn, sizeof(double)), *y = malloc(sizeof(double) * nn);
    for (int k = 0; k < 6; k++) c[sh_index(lm[k][0], lm[k][1])] = 1.0 + 0.1 * k;
    sh_grid g = {nr, np, x, NULL, 0.25};
    sh_sht *p;
    ck_assert_int_eq(sh_sht_create(order, &g, 1, 1, &p), SH_OK);
    double map[15];
    ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, c, map), SH_OK);
    for (int r = 0; r < nr; r++)
        for (int j = 0; j < np; j++) {
            ck_assert_int_eq(sh_eval(order, SH_CS, acos(x[r]), 0.25 + 2.0 * M_PI * j / np, y), SH_OK);
            double f = 0.0, s = 0.0;
            for (int k = 0; k < 6; k++) {
                const int i = sh_index(lm[k][0], lm[k][1]);
                f += c[i] * y[i];
                s += fabs(c[i] * y[i]);
            }
            ck_assert_msg(fabs(map[r * np + j] - f) <= 1e-12 * fmax(s, 1e-300),
                          "ring %g° point %d: %.17g vs sh_eval %.17g", th[r], j, map[r * np + j], f);
            ck_assert_msg(s > 1e-30, "ring %g°: values vanished (%g)", th[r], s);
        }
    sh_sht_destroy(p);
    free(c), free(y);
}
END_TEST

static double nan_fn(const double d[3], double theta, double phi, void *ctx)
{
    return theta > 2.0 ? NAN : 1.0;
}

START_TEST(errors)
{
    double c[16], x[4] = {0.5, 0.1, -0.1, -0.5}, w[4] = {1, 1, 1, 1};
    ck_assert_int_eq(sh_project(4, SH_CS, nan_fn, NULL, SH_RULE_QUAD, 10, 0, c), SH_ENUM);
    ck_assert_msg(strstr(sh_last_error(), "not finite") != NULL, "message: %s", sh_last_error());
    sh_grid g = {4, 8, x, NULL, 0.0};
    sh_sht *p;
    double map[32] = {0};
    ck_assert_int_eq(sh_sht_create(4, &g, 1, 1, &p), SH_OK);
    ck_assert_int_eq(sh_sht_analysis(p, SH_CS, map, c), SH_EINVAL); /* no weights */
    ck_assert_int_eq(sh_sht_synthesis(p, (sh_convention)7, c, map), SH_EINVAL);
    ck_assert_int_eq(sh_sht_synthesis(p, SH_CS, NULL, map), SH_EINVAL);
    sh_sht_destroy(p);
    sh_sht_destroy(NULL);
    g.weight = w;
    ck_assert_int_eq(sh_sht_create(0, &g, 1, 1, &p), SH_EINVAL);
    ck_assert_int_eq(sh_sht_create(4, &g, 0, 1, &p), SH_EINVAL);
    ck_assert_int_eq(sh_sht_create(4, &g, 5, 1, &p), SH_EINVAL);
    x[1] = 1.5;
    ck_assert_int_eq(sh_sht_create(4, &g, 1, 1, &p), SH_EINVAL);
    x[1] = 0.1;
    w[2] = NAN;
    ck_assert_int_eq(sh_sht_create(4, &g, 1, 1, &p), SH_EINVAL);
    ck_assert_int_eq(sh_sht_create(4, NULL, 1, 1, &p), SH_EINVAL);
    ck_assert_int_eq(sh_grid_gauss(0, 4, x, w, &g), SH_EINVAL);
    ck_assert_int_eq(sh_grid_latlong(4, 0, x, w, &g), SH_EINVAL);
    ck_assert_uint_eq(sh_sht_bytes(0, &g, 1, 1), 0);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("sht");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, quad_matches_direct_sum);
    tcase_add_test(tc, latlong_matches_direct_sum);
    tcase_add_test(tc, synthesis_matches_direct_sum);
    tcase_add_test(tc, gauss_round_trip);
    tcase_add_test(tc, closed_forms);
    tcase_add_test(tc, adjoint_identity);
    tcase_add_test(tc, threads_bitwise);
    tcase_add_test(tc, partial_last_chunk);
    tcase_add_test(tc, seeds_kept_and_dropped);
    tcase_add_test(tc, dead_groups_skipped);
    tcase_add_test(tc, dead_groups_full_grid);
    tcase_add_test(tc, isa_kernels_agree);
    tcase_add_test(tc, high_order_near_poles);
    tcase_add_test(tc, errors);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
