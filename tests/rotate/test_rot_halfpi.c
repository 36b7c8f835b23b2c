/* test_rot_halfpi.c — the `halfpi` method (src/rotate/rot_halfpi.c) and the
 * threaded all-band rotation (src/rotate/rotation_stream.c).
 *
 * Truths: the MPFR reference (orders 1..10 at the extreme and random
 * rotations, both conventions and precisions; single bands 50, 200, 400),
 * the pointwise identity, d^l(π/2) in closed form at small l, by its
 * orthogonality to l = 4000 and against its recursion in binary128 (MPFR)
 * at l = 1000 and 2000, two other methods (zxzxz, and blanco's
 * O(l²) single band, an m-recursion at fixed l that shares no code with
 * halfpi, up to l = 2000), and the identities R(a)R(b) = R(ab) and the round
 * trip Rᵀ(R x) = x to lmax 1000 (and band 4096).  Threads: the result is
 * compared bit for bit with one thread. */
#include "rottest.h"

#include <mpfr.h>

#ifdef _OPENMP
#include <omp.h>
#endif

static void gauss(unsigned long long seed, size_t n, double *x)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u1 = ((seed >> 11) + 0.5) / 9007199254740992.0;
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u2 = ((seed >> 11) + 0.5) / 9007199254740992.0;
        x[i] = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
    }
}

START_TEST(test_reference_orders_1_10)
{
    double md, mf;
    rot_check_reference_all(SH_ROT_HALFPI, &md, &mf);
    fprintf(stderr, "halfpi vs reference, orders 1..10, all cases: double %.3g float %.3g\n", md, mf);
}
END_TEST

START_TEST(test_apply_pointwise_homomorphism)
{
    rot_check_apply(SH_ROT_HALFPI, SH_PREC_DOUBLE, 1e-14);
    rot_check_apply(SH_ROT_HALFPI, SH_PREC_FLOAT, 4 * ROT_TOL_F);
    rot_check_pointwise(SH_ROT_HALFPI);
    rot_check_orth_homomorphism(SH_ROT_HALFPI);
}
END_TEST

START_TEST(test_reference_bands)
{
    rot_check_band(SH_ROT_HALFPI, 50);
    rot_check_band(SH_ROT_HALFPI, 200);
}
END_TEST

/* Band 400 (the reference's limit) near β = π, one convention. */
START_TEST(test_reference_band_400)
{
    const int L = 400, w = 2 * L + 1;
    double *b = malloc((size_t)w * w * sizeof *b), *ref = malloc((size_t)w * w * sizeof *ref);
    const double e[1][3] = {{1.3, M_PI - 1e-9, -2.2}};
    double worst = 0;
    for (int k = 0; k < 1; k++) {
        sh_rotation r;
        sh_rotation_from_euler(e[k][0], e[k][1], e[k][2], &r);
        ck_assert_int_eq(sh_rot_band(L, SH_ROT_HALFPI, SH_PREC_DOUBLE, SH_CS, &r, b), SH_OK);
        ck_assert_int_eq(sh_rot_reference_band(L, SH_CS, &r, 32, ref, NULL), SH_OK);
        for (int i = 0; i < w * w; i++) worst = fmax(worst, fabs(b[i] - ref[i]));
    }
    fprintf(stderr, "halfpi band %d vs reference: %.3g\n", L, worst);
    ck_assert_msg(worst <= 1e-13, "band %d: %.3g", L, worst);
    free(b);
    free(ref);
}
END_TEST

/* d^l(π/2) in closed form: d^1 (Edmonds' table: d_11 = (1+cosβ)/2,
 * d_10 = −sinβ/√2, d_00 = cosβ) and the row m' = l, √C(2l, l+m)/2^l with
 * sign (−1)^{l−m}, at l = 30 (from lgamma, independent of the products). */
START_TEST(test_delta_closed_form)
{
    double d1[4];
    ck_assert_int_eq(sh_wigner_d_halfpi(1, d1), SH_OK);
    ck_close(d1[0], 0.0, 0, 1e-300, "d1_00");
    ck_close(d1[1], 1 / M_SQRT2, 1e-15, 0, "d1_01 = sin/√2");
    ck_close(d1[2], -1 / M_SQRT2, 1e-15, 0, "d1_10 = -sin/√2");
    ck_close(d1[3], 0.5, 1e-15, 0, "d1_11");
    const int l = 30, n = l + 1;
    double *d = malloc((size_t)n * n * sizeof *d);
    ck_assert_int_eq(sh_wigner_d_halfpi(l, d), SH_OK);
    for (int m = 0; m <= l; m++) {
        const double v = exp(0.5 * (lgamma(2 * l + 1) - lgamma(l + m + 1) - lgamma(l - m + 1)) - l * log(2.0));
        ck_close(d[(size_t)l * n + m], ((l - m) & 1) ? -v : v, 1e-13, 0, "d^%d_{%d,%d}", l, l, m);
    }
    free(d);
}
END_TEST

/* Orthogonality of the whole d^l(π/2) (2l+1 rows, from the m', m ≥ 0 part
 * by its symmetries) on two probes, at bands that cross the scaled-column
 * threshold (seeds below 2^-600 from l ≈ 600, below double's range from
 * l = 1023) up to 4000. */
/* d_{a,b}(π/2), a, b = −l..l, from the part m', m ≥ 0 (n = l+1 columns):
 * d_{k,−m} = (−1)^{l+k} d_{km}, d_{−k,m} = (−1)^{l+m} d_{km},
 * d_{−k,−m} = (−1)^{k+m} d_{km} */
static double dfull(const double *d, int l, int a, int b)
{
    const int k = abs(a), m = abs(b);
    const double v = d[(size_t)k * (l + 1) + m];
    int odd = 0;
    if (a >= 0 && b < 0) odd = (l + k) & 1;
    else if (a < 0 && b >= 0) odd = (l + m) & 1;
    else if (a < 0 && b < 0) odd = (k + m) & 1;
    return odd ? -v : v;
}

static double delta_probe(int l)
{
    const int n = l + 1, w = 2 * l + 1;
    double *d = malloc((size_t)n * n * sizeof *d), *v = malloc(3 * (size_t)w * sizeof *v);
    ck_assert_ptr_nonnull(d);
    ck_assert_int_eq(sh_wigner_d_halfpi(l, d), SH_OK);
    double *y = v + w, *z = v + 2 * w, worst = 0;
    for (int probe = 0; probe < 2; probe++) {
        gauss(100 + probe, w, v);
        for (int a = -l; a <= l; a++) {
            double s = 0;
            for (int b = -l; b <= l; b++) s += dfull(d, l, a, b) * v[b + l];
            y[a + l] = s;
        }
        for (int b = -l; b <= l; b++) {
            double s = 0;
            for (int a = -l; a <= l; a++) s += dfull(d, l, a, b) * y[a + l];
            z[b + l] = s;
        }
        double nv = 0;
        for (int i = 0; i < w; i++) nv = fmax(nv, fabs(v[i]));
        for (int i = 0; i < w; i++) worst = fmax(worst, fabs(z[i] - v[i]) / nv);
    }
    free(d);
    free(v);
    return worst;
}

START_TEST(test_delta_orthogonal_high)
{
    const int ls[] = {2, 3, 100, 601, 1100, 2500, 4000};
    for (size_t k = 0; k < sizeof ls / sizeof *ls; k++) {
        const double e = delta_probe(ls[k]);
        fprintf(stderr, "d^%d(pi/2): probe orthogonality %.3g\n", ls[k], e);
        ck_assert_msg(e <= 1e-13, "d^%d(pi/2) orthogonality %.3g", ls[k], e);
    }
}
END_TEST

/* d^l(π/2) (m', m ≥ 0) against the same three-term recursion carried out
 * here in binary128 (MPFR, 113 bits: no underflow, rounding 2^-113), written
 * from its definition (rot_halfpi.c's header): the seed row Δ_{l,m} =
 * (−1)^{l−m} √C(2l, l+m) / 2^l, then downward in m' for every column m,
 * Δ_{r,m} = (2m Δ_{r+1,m} − B_{r+2} Δ_{r+2,m}) / B_{r+1}, B_j =
 * √((l+j)(l−j+1)).  The difference is the double code's own rounding
 * (absolute: |Δ| ≤ 1). */
static double delta_vs_binary128(int l)
{
    const int n = l + 1;
    double *d = malloc((size_t)n * n * sizeof *d);
    ck_assert_ptr_nonnull(d);
    ck_assert_int_eq(sh_wigner_d_halfpi(l, d), SH_OK);
    mpfr_t e, t, b1, b2, x0, x1, x2;
    mpfr_inits2(113, e, t, b1, b2, x0, x1, x2, (mpfr_ptr)0);
    /* e_0² = Π_{k=1..l} (2k−1)/(2k) */
    mpfr_set_ui(e, 1, MPFR_RNDN);
    for (int k = 1; k <= l; k++) {
        mpfr_mul_ui(e, e, 2 * (unsigned)k - 1, MPFR_RNDN);
        mpfr_div_ui(e, e, 2 * (unsigned)k, MPFR_RNDN);
    }
    mpfr_sqrt(e, e, MPFR_RNDN);
    double worst = 0;
    for (int m = 0; m <= l; m++) {
        if (m) { /* e_m = e_{m−1} √((l−m+1)/(l+m)) */
            mpfr_set_ui(t, (unsigned)(l - m + 1), MPFR_RNDN);
            mpfr_div_ui(t, t, (unsigned)(l + m), MPFR_RNDN);
            mpfr_sqrt(t, t, MPFR_RNDN);
            mpfr_mul(e, e, t, MPFR_RNDN);
        }
        mpfr_set(x1, e, MPFR_RNDN); /* row l */
        if ((l - m) & 1) mpfr_neg(x1, x1, MPFR_RNDN);
        mpfr_set_ui(x2, 0, MPFR_RNDN); /* row l+1 */
        worst = fmax(worst, fabs(d[(size_t)l * n + m] - mpfr_get_d(x1, MPFR_RNDN)));
        for (int r = l - 1; r >= 0; r--) {
            mpfr_set_ui(b1, (unsigned)(l + r + 1), MPFR_RNDN); /* B_{r+1} */
            mpfr_mul_ui(b1, b1, (unsigned)(l - r), MPFR_RNDN);
            mpfr_sqrt(b1, b1, MPFR_RNDN);
            mpfr_set_ui(b2, (unsigned)(l + r + 2), MPFR_RNDN); /* B_{r+2} (0 at r+2 = l+1) */
            mpfr_mul_ui(b2, b2, (unsigned)(l - r - 1), MPFR_RNDN);
            mpfr_sqrt(b2, b2, MPFR_RNDN);
            mpfr_mul_ui(x0, x1, 2 * (unsigned)m, MPFR_RNDN);
            mpfr_mul(t, b2, x2, MPFR_RNDN);
            mpfr_sub(x0, x0, t, MPFR_RNDN);
            mpfr_div(x0, x0, b1, MPFR_RNDN);
            worst = fmax(worst, fabs(d[(size_t)r * n + m] - mpfr_get_d(x0, MPFR_RNDN)));
            mpfr_swap(x2, x1);
            mpfr_swap(x1, x0);
        }
    }
    mpfr_clears(e, t, b1, b2, x0, x1, x2, (mpfr_ptr)0);
    free(d);
    return worst;
}

START_TEST(test_delta_vs_binary128)
{
    const int ls[] = {1000, 2000};
    for (size_t k = 0; k < sizeof ls / sizeof *ls; k++) {
        const double e = delta_vs_binary128(ls[k]);
        fprintf(stderr, "d^%d(pi/2) against the recursion in binary128: %.2g (absolute)\n", ls[k], e);
        ck_assert_msg(e <= 1e-15, "d^%d(pi/2) off the binary128 recursion by %.3g", ls[k], e);
    }
}
END_TEST

/* The stream (any lmax, threads) against zxzxz and blanco plans at lmax
 * 64, both conventions, forward and inverse. */
START_TEST(test_stream_vs_plans)
{
    const int order = 65, n = order * order;
    double *x = malloc(3 * (size_t)n * sizeof *x), *y = x + n, *z = y + n;
    gauss(1, n, x);
    for (int k = 0; k < ROT_NCASES; k++) {
        sh_rotation r, ri;
        char name[160];
        rot_case(k, &r, name, sizeof name);
        sh_rotation_inverse(&r, &ri);
        for (int conv = 0; conv < 2; conv++) {
            sh_rot_stream *s;
            ck_assert_int_eq(sh_rot_stream_create(order, conv, 2, &s), SH_OK);
            for (int inv = 0; inv < 2; inv++) {
                ck_assert_int_eq(sh_rot_stream_apply(s, 1, &r, inv, 1, x, y), SH_OK);
                for (int m = 0; m < 2; m++) {
                    sh_rot_plan *p;
                    ck_assert_int_eq(sh_rot_plan_create(order, m ? SH_ROT_BLANCO : SH_ROT_ZXZXZ, SH_PREC_DOUBLE, conv, &p), SH_OK);
                    ck_assert_int_eq(sh_rot_plan_set(p, inv ? &ri : &r), SH_OK);
                    ck_assert_int_eq(sh_rot_plan_apply(p, x, z), SH_OK);
                    sh_rot_plan_free(p);
                    /* the other methods' blocks are off the reference by up to
                     * 3.5e-14 (zxzxz) and 1.7e-13 (blanco) at these bands
                     * (README "Exact rotation"); on N(0, 1) vectors (entries up to
                     * 4, 2l+1 terms a row) that is a few times more */
                    for (int i = 0; i < n; i++)
                        ck_close(y[i], z[i], m ? 1e-12 : 3e-13, 1.0, "%s conv %d inv %d vs %s i %d", name,
                                 conv, inv, m ? "blanco" : "zxzxz", i);
                }
            }
            sh_rot_stream_free(s);
        }
    }
    free(x);
}
END_TEST

/* High bands without any lower one: R v by halfpi (sh_rot_band_apply)
 * against blanco's single-band block (an m-recursion at fixed l) times v. */
START_TEST(test_band_vs_blanco_high)
{
    const int ls[] = {700, 1100, 2000};
    sh_rotation r;
    sh_rotation_from_euler(2.1, 1.2, -0.4, &r);
    for (size_t k = 0; k < sizeof ls / sizeof *ls; k++) {
        const int l = ls[k], w = 2 * l + 1;
        double *B = malloc((size_t)w * w * sizeof *B), *v = malloc(3 * (size_t)w * sizeof *v);
        double *y = v + w, *z = v + 2 * w;
        ck_assert_ptr_nonnull(B);
        ck_assert_int_eq(sh_rot_band(l, SH_ROT_BLANCO, SH_PREC_DOUBLE, SH_CS, &r, B), SH_OK);
        gauss(7, w, v);
        ck_assert_int_eq(sh_rot_band_apply(l, SH_CS, &r, 0, 1, v, y), SH_OK);
        double e = 0;
        for (int i = 0; i < w; i++) {
            double s = 0;
            for (int j = 0; j < w; j++) s += B[(size_t)i * w + j] * v[j];
            z[i] = s;
            e = fmax(e, fabs(y[i] - s));
        }
        fprintf(stderr, "band %d: halfpi vs blanco single band, R v on N(0,1): %.3g\n", l, e);
        ck_assert_msg(e <= 1e-11, "band %d: %.3g", l, e);
        free(B);
        free(v);
    }
}
END_TEST

/* Round trip Rᵀ(R x) = x and R(a)(R(b) x) = R(ab) x on every band to lmax
 * 1000, N(0, 1) coefficients; HEALPix's rotate_alm reaches 3–5e-13 (max
 * abs) on the same round trip (tests/peers). */
START_TEST(test_identities_lmax1000)
{
    const int order = 1001;
    const size_t n = (size_t)order * order;
    double *x = malloc(4 * n * sizeof *x), *y = x + n, *z = y + n, *u = z + n;
    ck_assert_ptr_nonnull(x);
    gauss(3, n, x);
    sh_rotation a, b, ab;
    sh_rotation_from_euler(0.3, 1.1, -0.7, &a);
    sh_rotation_from_euler(-2.5, 2.9, 1.4, &b);
    sh_rotation_compose(&a, &b, &ab);
    sh_rot_stream *s;
    ck_assert_int_eq(sh_rot_stream_create(order, SH_CS, 0, &s), SH_OK);
    ck_assert_int_eq(sh_rot_stream_apply(s, 1, &a, 0, 1, x, y), SH_OK);
    ck_assert_int_eq(sh_rot_stream_apply(s, 1, &a, 1, 1, y, z), SH_OK);
    double rt = 0;
    for (size_t i = 0; i < n; i++) rt = fmax(rt, fabs(z[i] - x[i]));
    ck_assert_int_eq(sh_rot_stream_apply(s, 1, &b, 0, 1, x, y), SH_OK);
    ck_assert_int_eq(sh_rot_stream_apply(s, 1, &a, 0, 1, y, z), SH_OK);
    ck_assert_int_eq(sh_rot_stream_apply(s, 1, &ab, 0, 1, x, u), SH_OK);
    double hom = 0;
    for (size_t i = 0; i < n; i++) hom = fmax(hom, fabs(z[i] - u[i]));
    sh_rot_stream_free(s);
    fprintf(stderr, "lmax 1000: round trip %.3g, R(a)R(b) - R(ab) %.3g (max abs, N(0,1))\n", rt, hom);
    ck_assert_msg(rt <= 4e-13, "round trip %.3g", rt);
    /* R(ab) is built from the product of the 3×3 matrices: its angles are
     * rounded (~1e-16), which turns coefficient m of band l by ~m·1e-16 —
     * up to ~1e-12 on N(0, 1) coefficients at l = 1000, whatever the method */
    ck_assert_msg(hom <= 5e-12, "homomorphism %.3g", hom);
    free(x);
}
END_TEST

/* The top band of the largest order alone: the round trip on a probe. */
START_TEST(test_round_trip_band_4096)
{
    const int l = SHLAB_MAX_ORDER - 1, w = 2 * l + 1;
    double *v = malloc(3 * (size_t)w * sizeof *v), *y = v + w, *z = y + w;
    gauss(5, w, v);
    sh_rotation r;
    sh_rotation_from_euler(-0.9, 0.8, 2.6, &r);
    ck_assert_int_eq(sh_rot_band_apply(l, SH_NOCS, &r, 0, 1, v, y), SH_OK);
    ck_assert_int_eq(sh_rot_band_apply(l, SH_NOCS, &r, 1, 1, y, z), SH_OK);
    double e = 0, ny = 0, nv = 0;
    for (int i = 0; i < w; i++) e = fmax(e, fabs(z[i] - v[i])), ny += y[i] * y[i], nv += v[i] * v[i];
    fprintf(stderr, "band %d: round trip %.3g, |Rv|/|v| - 1 = %.3g\n", l, e, sqrt(ny / nv) - 1);
    ck_assert_msg(e <= 2e-12, "band %d round trip %.3g", l, e);
    ck_close(sqrt(ny / nv), 1.0, 1e-13, 0, "band %d: norm kept", l);
    free(v);
}
END_TEST

/* Threads, batches, in place and one band alone all give the same bits. */
START_TEST(test_bitwise)
{
    const int order = 201, nrot = 3, nvec = 4;
    const size_t n = (size_t)order * order;
    double *x = malloc(nvec * n * sizeof *x), *y1 = malloc(nrot * nvec * n * sizeof *y1);
    double *y2 = malloc(nrot * nvec * n * sizeof *y2), *t = malloc(n * sizeof *t);
    gauss(9, nvec * n, x);
    sh_rotation r[3];
    sh_rotation_from_euler(0.3, 1.1, -0.7, &r[0]);
    sh_rotation_from_euler(2.0, M_PI, 0.1, &r[1]);
    sh_rotation_from_euler(-1.0, 0.2, 3.0, &r[2]);
    sh_rot_stream *s1, *s3;
    ck_assert_int_eq(sh_rot_stream_create(order, SH_NOCS, 1, &s1), SH_OK);
    ck_assert_int_eq(sh_rot_stream_create(order, SH_NOCS, 3, &s3), SH_OK);
#ifdef _OPENMP
    ck_assert_int_eq(sh_rot_stream_threads(s3), 3);
#endif
    ck_assert_int_eq(sh_rot_stream_apply(s1, nrot, r, 0, nvec, x, y1), SH_OK);
    ck_assert_int_eq(sh_rot_stream_apply(s3, nrot, r, 0, nvec, x, y2), SH_OK);
    ck_assert_msg(!memcmp(y1, y2, nrot * nvec * n * sizeof *y1), "3 threads differ from 1");
    for (int k = 0; k < nrot; k++)
        for (int v = 0; v < nvec; v++) {
            const double *want = y1 + ((size_t)k * nvec + v) * n;
            memcpy(t, x + (size_t)v * n, n * sizeof *t);
            ck_assert_int_eq(sh_rot_stream_apply(s3, 1, &r[k], 0, 1, t, t), SH_OK); /* alone, in place */
            ck_assert_msg(!memcmp(t, want, n * sizeof *t), "rotation %d vector %d alone differs", k, v);
            for (int l = 0; l < order; l += 50) {
                double b[2 * 201 + 1];
                ck_assert_int_eq(sh_rot_band_apply(l, SH_NOCS, &r[k], 0, 1, x + (size_t)v * n + (size_t)l * l, b), SH_OK);
                ck_assert_msg(!memcmp(b, want + (size_t)l * l, (2 * (size_t)l + 1) * sizeof *b), "band %d alone differs", l);
            }
        }
    ck_assert_int_eq(sh_rot_stream_apply(s1, 2, r, 0, 1, x, x), SH_EINVAL); /* in place needs one rotation */
    sh_rot_stream_free(s1);
    sh_rot_stream_free(s3);
    free(x), free(y1), free(y2), free(t);
}
END_TEST

START_TEST(test_refusals)
{
    sh_rot_stream *s = NULL;
    ck_assert_int_eq(sh_rot_stream_create(0, SH_CS, 1, &s), SH_EINVAL);
    ck_assert_int_eq(sh_rot_stream_create(SHLAB_MAX_ORDER + 1, SH_CS, 1, &s), SH_EINVAL);
    ck_assert_ptr_null(s);
    ck_assert_int_eq(sh_rot_stream_create(5, SH_CS, 1, &s), SH_OK);
    sh_rotation r;
    sh_rotation_from_euler(0.1, 0.2, 0.3, &r);
    r.beta = NAN;
    double x[25] = {0}, y[25];
    ck_assert_int_eq(sh_rot_stream_apply(s, 1, &r, 0, 1, x, y), SH_EINVAL);
    ck_assert_int_eq(sh_rot_stream_apply(s, 0, &r, 0, 1, x, y), SH_EINVAL);
    sh_rot_stream_free(s);
    /* plans sized by method: the sparse ones hold no blocks; a plan that
     * cannot fit is refused before anything is allocated */
    ck_assert_uint_lt(sh_rot_plan_bytes(2049, SH_ROT_Z, SH_PREC_DOUBLE), 200u << 20);
    ck_assert_uint_lt(sh_rot_plan_bytes(4097, SH_ROT_HALFPI, SH_PREC_DOUBLE), 400u << 20);
    ck_assert_uint_gt(sh_rot_plan_bytes(1001, SH_ROT_BLANCO, SH_PREC_DOUBLE), 10000u << 20);
    sh_rot_plan *p = NULL;
    ck_assert_int_eq(sh_rot_plan_create(SH_ROT_BLANCO_MAX_ORDER, SH_ROT_BLANCO, SH_PREC_DOUBLE, SH_CS, &p), SH_ENOMEM);
    ck_assert_ptr_null(p);
    ck_assert_msg(strstr(sh_last_error(), "GB") != NULL, "names the size: %s", sh_last_error());
    /* above a method's tested order: refused as such (docs/ranges.md) */
    ck_assert_int_eq(sh_rot_plan_create(SH_ROT_IVANIC_MAX_ORDER + 1, SH_ROT_IVANIC, SH_PREC_DOUBLE, SH_CS, &p), SH_EINVAL);
    ck_assert_ptr_null(p);
    /* defaults: exact methods at every band */
    ck_assert_int_eq(sh_rot_method_default(10, 0), SH_ROT_ZXZXZ);
    ck_assert_int_eq(sh_rot_method_default(1001, 0), SH_ROT_HALFPI);
    ck_assert_int_eq(sh_rot_method_default(1001, 1), SH_ROT_BLANCO);
}
END_TEST

/* sh_rot_stability's rows for halfpi above exact_max come from band
 * applications, not blocks: at a band where both are affordable the probe
 * estimate must equal the block estimate (the same probes, Rᵀ as a matrix
 * transpose there) to rounding, and far up the rows must still say
 * "orthogonal, homomorphic" at rounding level. */
typedef struct {
    sh_rot_stability_row row[2];
    int n;
} stab_rows;
static int keep_stab_row(const sh_rot_stability_row *r, void *ctx)
{
    stab_rows *s = ctx;
    if (s->n < 2) s->row[s->n++] = *r;
    return 0;
}
START_TEST(test_stability_without_blocks)
{
    const int l = 60, w = 2 * l + 1;
    const int bands[2] = {l, 2000};
    stab_rows got = {0};
    ck_assert_int_eq(sh_rot_stability(SH_ROT_HALFPI, SH_PREC_DOUBLE, SH_CS, 2000, bands, 2, -1, 10, 0,
                                      keep_stab_row, &got), SH_OK);
    ck_assert_int_eq(got.n, 2);
    ck_assert(!got.row[0].orth_exact && !got.row[0].have_ref && !got.row[0].broken);
    sh_rotation set[SH_ROT_STABILITY_NSET];
    ck_assert_int_eq(sh_rot_stability_set(set, NULL), SH_OK);
    double *B = malloc(sizeof *B * (size_t)w * w), blk = 0;
    ck_assert_ptr_nonnull(B);
    for (int k = 0; k < SH_ROT_STABILITY_NSET; k++) {
        ck_assert_int_eq(sh_rot_band(l, SH_ROT_HALFPI, SH_PREC_DOUBLE, SH_CS, &set[k], B), SH_OK);
        blk = fmax(blk, sh_rot_block_orthogonality(B, w, 0));
    }
    free(B);
    ck_assert_msg(fabs(got.row[0].orth - blk) <= 2e-15 && blk < 5e-15, "band %d: %.3g without blocks, %.3g with", l,
                  got.row[0].orth, blk);
    ck_assert_msg(got.row[0].hom < 2e-14, "band %d hom %.3g", l, got.row[0].hom);
    ck_assert_msg(got.row[1].band == 2000 && !got.row[1].broken && got.row[1].orth < 1e-14 && got.row[1].hom < 1e-13,
                  "band 2000: orth %.3g hom %.3g", got.row[1].orth, got.row[1].hom);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rot_halfpi");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, test_reference_orders_1_10);
    tcase_add_test(tc, test_apply_pointwise_homomorphism);
    tcase_add_test(tc, test_reference_bands);
    tcase_add_test(tc, test_reference_band_400);
    tcase_add_test(tc, test_delta_closed_form);
    tcase_add_test(tc, test_delta_orthogonal_high);
    tcase_add_test(tc, test_delta_vs_binary128);
    tcase_add_test(tc, test_stream_vs_plans);
    tcase_add_test(tc, test_band_vs_blanco_high);
    tcase_add_test(tc, test_identities_lmax1000);
    tcase_add_test(tc, test_round_trip_band_4096);
    tcase_add_test(tc, test_bitwise);
    tcase_add_test(tc, test_refusals);
    tcase_add_test(tc, test_stability_without_blocks);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)
