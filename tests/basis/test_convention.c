/* test_convention.c — other people's conventions (shlab/convention.h) and
 * `identify` against truths written here, independently of the library's
 * basis code:
 *   - the orthonormal real SH for l <= 3 as Cartesian polynomials, without
 *     the Condon-Shortley phase (the table of Wikipedia's "Table of spherical
 *     harmonics", real section; y_1^{-1} = √(3/4π) y, ...);
 *   - the ambisonics SN3D functions in ACN order as polynomials (Nachbar et
 *     al. 2011, AmbiX, Table 1: 1; y, z, x; √3 xy, ...), N3D = √(2l+1)·SN3D;
 *   - FuMa's channels W..Q as polynomials from its maxN definition (each
 *     function's maximum on the sphere is 1, W = 1/√2) — checked here on a
 *     dense grid;
 *   - the complex Y_l^m from the real table: Y_l^m = (−1)^m (T_l^m + i T_l^{−m})/√2
 *     for m > 0 (Condon-Shortley), Y_l^{−m} = (−1)^m conj(Y_l^m).
 * For each convention a user basis is built from these, evaluated at the
 * fixture's directions (typed here as the integer quadruples of
 * data/fixtures/basis/directions.json) and given to identify. */
#include <string.h>

#include "testutil.h"

/* Orthonormal real SH without the phase (Wikipedia), l <= 3, m = −l..l. */
static double T(int l, int m, const double p[3])
{
    const double x = p[0], y = p[1], z = p[2], pi = M_PI;
    switch (l * 10 + (m + 3)) {
    case 3: return 0.5 * sqrt(1 / pi);
    case 12: return sqrt(3 / (4 * pi)) * y;
    case 13: return sqrt(3 / (4 * pi)) * z;
    case 14: return sqrt(3 / (4 * pi)) * x;
    case 21: return 0.5 * sqrt(15 / pi) * x * y;
    case 22: return 0.5 * sqrt(15 / pi) * y * z;
    case 23: return 0.25 * sqrt(5 / pi) * (3 * z * z - 1);
    case 24: return 0.5 * sqrt(15 / pi) * x * z;
    case 25: return 0.25 * sqrt(15 / pi) * (x * x - y * y);
    case 30: return 0.25 * sqrt(35 / (2 * pi)) * y * (3 * x * x - y * y);
    case 31: return 0.5 * sqrt(105 / pi) * x * y * z;
    case 32: return 0.25 * sqrt(21 / (2 * pi)) * y * (5 * z * z - 1);
    case 33: return 0.25 * sqrt(7 / pi) * (5 * z * z * z - 3 * z);
    case 34: return 0.25 * sqrt(21 / (2 * pi)) * x * (5 * z * z - 1);
    case 35: return 0.25 * sqrt(105 / pi) * (x * x - y * y) * z;
    case 36: return 0.25 * sqrt(35 / (2 * pi)) * x * (x * x - 3 * y * y);
    }
    ck_abort_msg("T(%d,%d)", l, m);
    return 0;
}

/* SN3D in ACN order (AmbiX Table 1). */
static double sn3d_acn(int acn, const double p[3])
{
    const double x = p[0], y = p[1], z = p[2];
    const double v[16] = {1, y, z, x, sqrt(3) * x * y, sqrt(3) * y * z, 0.5 * (3 * z * z - 1), sqrt(3) * x * z,
                          0.5 * sqrt(3) * (x * x - y * y), sqrt(5.0 / 8) * y * (3 * x * x - y * y),
                          sqrt(15) * x * y * z, sqrt(3.0 / 8) * y * (5 * z * z - 1), 0.5 * z * (5 * z * z - 3),
                          sqrt(3.0 / 8) * x * (5 * z * z - 1), 0.5 * sqrt(15) * z * (x * x - y * y),
                          sqrt(5.0 / 8) * x * (x * x - 3 * y * y)};
    return v[acn];
}

/* FuMa channels W X Y Z R S T U V K L M N O P Q (maxN, W = 1/√2), and the
 * (l, m) each one is (S = xz: (2,1); T = yz: (2,−1); ...). */
static const char fuma_letters[] = "WXYZRSTUVKLMNOPQ";
static const int fuma_lm[16][2] = {{0, 0}, {1, 1}, {1, -1}, {1, 0}, {2, 0}, {2, 1}, {2, -1}, {2, 2},
                                   {2, -2}, {3, 0}, {3, 1}, {3, -1}, {3, 2}, {3, -2}, {3, 3}, {3, -3}};
static double fuma_ch(int k, const double p[3])
{
    const double x = p[0], y = p[1], z = p[2];
    const double v[16] = {M_SQRT1_2, x, y, z, 0.5 * (3 * z * z - 1), 2 * x * z, 2 * y * z, x * x - y * y, 2 * x * y,
                          0.5 * z * (5 * z * z - 3), sqrt(135.0 / 256) * x * (5 * z * z - 1),
                          sqrt(135.0 / 256) * y * (5 * z * z - 1), 1.5 * sqrt(3) * z * (x * x - y * y),
                          3 * sqrt(3) * x * y * z, x * (x * x - 3 * y * y), y * (3 * x * x - y * y)};
    return v[k];
}
static double fuma_lm_fn(int l, int m, const double p[3])
{
    for (int k = 0; k < 16; k++)
        if (fuma_lm[k][0] == l && fuma_lm[k][1] == m) return fuma_ch(k, p);
    return NAN;
}

/* ---- a user's convention, written from the spec's words ---------------- */
typedef struct {
    int complex, half, cs, neg_cos;
    char norm[16], index[16];
    char axes[8]; /* "+x+z-y" */
} truth_conv;

static const char *const NORMS[] = {"ortho", "4pi", "schmidt", "sn3d", "n3d", "fuma"};
static const char *const INDEXES[] = {"acn", "mdesc", "cossin", "fuma-order"};

static void axes_text(int a, char out[8])
{
    /* an independent enumeration: all sign patterns of all permutations */
    static const char *const perms[6] = {"xyz", "xzy", "yxz", "yzx", "zxy", "zyx"};
    for (int i = 0; i < 3; i++) {
        out[2 * i] = ((a % 8) >> i) & 1 ? '-' : '+';
        out[2 * i + 1] = perms[a / 8][i];
    }
    out[6] = 0;
}

/* s: the formula's coordinates of the user's d, for axes "±a±b±c" meaning
 * u = (±s_a, ±s_b, ±s_c). */
static void formula_coords(const char *ax, const double d[3], double s[3])
{
    for (int i = 0; i < 3; i++) s[ax[2 * i + 1] - 'x'] = (ax[2 * i] == '-' ? -1 : 1) * d[i];
}

/* The real function of band l, label m, in the truth's normalisation, no phase. */
static double real_fn(const truth_conv *t, int l, int m, const double s[3])
{
    const int fm = t->neg_cos ? -m : m; /* which function the label m names */
    const int acn = l * (l + 1) + fm;
    double v;
    if (!strcmp(t->norm, "ortho")) v = T(l, fm, s);
    else if (!strcmp(t->norm, "4pi")) v = sqrt(4 * M_PI) * T(l, fm, s);
    else if (!strcmp(t->norm, "schmidt") || !strcmp(t->norm, "sn3d")) v = sn3d_acn(acn, s);
    else if (!strcmp(t->norm, "n3d")) v = sqrt(2.0 * l + 1) * sn3d_acn(acn, s);
    else v = fuma_lm_fn(l, fm, s);
    if (t->cs && (abs(m) & 1)) v = -v;
    return v;
}

/* (l, m) of entry k in the truth's index order. */
static void truth_lm(const truth_conv *t, int k, int *l, int *m)
{
    if (!strcmp(t->index, "fuma-order")) { *l = fuma_lm[k][0]; *m = fuma_lm[k][1]; return; }
    int L = 0;
    while ((L + 1) * (L + 1) <= k) L++;
    const int j = k - L * L;
    *l = L;
    if (!strcmp(t->index, "acn")) *m = j - L;
    else if (!strcmp(t->index, "mdesc")) *m = L - j;
    else *m = j == 0 ? 0 : (j % 2 ? (j + 1) / 2 : -(j / 2)); /* m=0, cos1, sin1, cos2, sin2 */
}

/* The user's basis at user coordinates d: n doubles (complex: re, im). */
static int truth_eval(const truth_conv *t, int order, const double d[3], double *out)
{
    double s[3];
    formula_coords(t->axes, d, s);
    if (!t->complex) {
        for (int k = 0; k < order * order; k++) {
            int l, m;
            truth_lm(t, k, &l, &m);
            out[k] = real_fn(t, l, m, s);
        }
        return order * order;
    }
    int n = 0;
    for (int l = 0; l < order; l++)
        for (int m = -l; m <= l; m++) {
            const int am = abs(m);
            /* CS: Y_l^m = (−1)^m (T_l^m + i T_l^{−m})/√2, m > 0 */
            double re = am ? T(l, am, s) * M_SQRT1_2 : T(l, 0, s), im = am ? T(l, -am, s) * M_SQRT1_2 : 0;
            if (m > 0 && t->cs && (am & 1)) re = -re, im = -im;
            if (m < 0) im = -im; /* Y_l^{−m} = (−1)^m conj(Y_l^m) = (T_l^m − i T_l^{−m})/√2, with or without CS */
            if (t->half && m < 0) continue;
            const int j = t->half ? am * (2 * (order - 1) + 1 - am) / 2 + l : l * (l + 1) + m;
            out[2 * j] = re;
            out[2 * j + 1] = im;
            n += 2;
        }
    return n;
}

static void truth_spec(const truth_conv *t, char *buf, size_t n)
{
    if (t->complex)
        snprintf(buf, n, "%s,%s,%s", t->half ? "complex-half" : "complex", t->cs ? "cs" : "nocs", t->axes);
    else
        snprintf(buf, n, "real,%s,%s,%s,%s,%s", t->cs ? "cs" : "nocs", t->norm, t->index,
                 t->neg_cos ? "neg-cos" : "neg-sin", t->axes);
}

/* The fixture's directions as typed from directions.json (integers / n). */
static const int fixture_dirs[32][4] = {
    {2, 3, 6, 7},     {-2, -3, -6, 7},  {-6, -2, 3, 7},   {-3, 6, -2, 7},  {3, -6, 2, 7},   {6, 2, -3, 7},
    {-8, 1, -4, 9},   {-4, -8, -1, 9},  {-1, -4, 8, 9},   {1, 4, -8, 9},   {4, 8, 1, 9},    {8, -1, 4, 9},
    {-12, 9, 8, 17},  {8, -12, -9, 17}, {-1, 8, 4, 9},    {4, -1, -8, 9},  {-4, 1, 8, 9},   {8, -4, -1, 9},
    {-6, -3, -2, 7},  {-3, 2, -6, 7},   {-2, -6, 3, 7},   {2, 6, -3, 7},   {3, -2, 6, 7},   {6, 3, 2, 7},
    {-23, 14, -2, 27}, {-2, -23, -14, 27}, {-2, 6, 9, 11}, {9, -2, -6, 11}, {-9, -8, 12, 17}, {8, 12, 9, 17},
    {9, 8, -12, 17},  {12, -9, 8, 17}};
static double D[32 * 3];

static void load_dirs(void)
{
    int exact[32][4];
    double lib[96];
    sh_identify_directions(lib, exact);
    for (int j = 0; j < 32; j++)
        for (int k = 0; k < 3; k++) {
            D[3 * j + k] = (double)fixture_dirs[j][k] / fixture_dirs[j][3];
            ck_assert_int_eq(exact[j][k], fixture_dirs[j][k]);
            ck_assert(D[3 * j + k] == lib[3 * j + k]);
        }
}

/* ---- the truths themselves --------------------------------------------- */
START_TEST(truth_tables)
{
    /* orthonormality of T by a product rule exact for degree 6 (8 Gauss
     * nodes in z would do; 24×48 midpoint in φ is exact for trig degree <
     * 48, and z by Gauss-Legendre from GSL-free nodes: use 200 midpoints
     * and a loose tolerance) — and SN3D = √(4π/(2l+1))·T (Schmidt's
     * definition), FuMa's maxima. */
    double mx[16] = {0};
    for (int a = 0; a < 400; a++)
        for (int b = 0; b < 800; b++) {
            const double th = M_PI * (a + 0.5) / 400, ph = 2 * M_PI * b / 800;
            const double p[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
            for (int k = 0; k < 16; k++) mx[k] = fmax(mx[k], fabs(fuma_ch(k, p)));
        }
    for (int k = 0; k < 16; k++)
        ck_close(mx[k], k == 0 ? M_SQRT1_2 : 1.0, 2e-4, 1.0, "FuMa %c max", fuma_letters[k]);
    const double p[3] = {0.36, -0.48, 0.8};
    for (int l = 0; l < 4; l++)
        for (int m = -l; m <= l; m++)
            ck_close(sn3d_acn(l * (l + 1) + m, p), sqrt(4 * M_PI / (2 * l + 1)) * T(l, m, p), 1e-14, 1.0,
                     "SN3D vs Schmidt-scaled T (%d,%d)", l, m);
}
END_TEST

/* ---- the library's basis against the truths, every combination --------- */
static int parse_truth(const truth_conv *t, sh_conv *c)
{
    char spec[96];
    truth_spec(t, spec, sizeof spec);
    const int st = sh_conv_parse(spec, c);
    ck_assert_msg(st == SH_OK, "parse %s: %s", spec, sh_last_error());
    return st;
}

static int all_truths(truth_conv *out)
{
    int n = 0;
    for (int cs = 0; cs < 2; cs++)
        for (int a = 0; a < 48; a++) {
            for (int nm = 0; nm < 6; nm++)
                for (int ix = 0; ix < 4; ix++)
                    for (int ng = 0; ng < 2; ng++) {
                        truth_conv t = {0, 0, cs, ng, "", "", ""};
                        strcpy(t.norm, NORMS[nm]);
                        strcpy(t.index, INDEXES[ix]);
                        axes_text(a, t.axes);
                        out[n++] = t;
                    }
            for (int h = 0; h < 2; h++) {
                truth_conv t = {1, h, cs, 0, "ortho", "acn", ""};
                axes_text(a, t.axes);
                out[n++] = t;
            }
        }
    return n;
}
#define NTRUTH (2 * 48 * (6 * 4 * 2 + 2))
static truth_conv truths[NTRUTH];

START_TEST(eval_matches_truth_every_combination)
{
    load_dirs();
    const int n = all_truths(truths), order = 4;
    double want[64], got[64];
    double worst = 0;
    for (int q = 0; q < n; q++) {
        sh_conv c;
        parse_truth(&truths[q], &c);
        ck_assert_int_eq((int)sh_conv_ndoubles(&c, order), truths[q].complex ? (truths[q].half ? 20 : 32) : 16);
        for (int j = 0; j < 32; j++) {
            const int nd = truth_eval(&truths[q], order, D + 3 * j, want);
            ck_assert_int_eq(sh_conv_eval_dir(&c, order, D + 3 * j, got), SH_OK);
            for (int k = 0; k < nd; k++) {
                worst = fmax(worst, fabs(got[k] - want[k]));
                if (!(fabs(got[k] - want[k]) <= 1e-14)) {
                    char spec[96];
                    truth_spec(&truths[q], spec, sizeof spec);
                    ck_abort_msg("%s: entry %d at direction %d: got %.17g want %.17g", spec, k, j, got[k], want[k]);
                }
            }
        }
    }
    printf("convention: %d conventions' bases at 32 directions to order 4: worst |error| %.3g\n", n, worst);
}
END_TEST

/* ---- conversions ------------------------------------------------------- */
/* Σ c'_i y_i(d) = Σ c_k U_k(d) with U from the truth and y from T with the
 * CS phase: conversion of a vector agrees with evaluating the user's basis;
 * and from_shlab(to_shlab(c)) = c. */
START_TEST(convert_keeps_function_and_round_trips)
{
    load_dirs();
    const int n = all_truths(truths), order = 4;
    double cu[64], cs[16], back[64], u[64];
    const truth_conv shl = {0, 0, 1, 0, "ortho", "acn", "+x+y+z"};
    for (int q = 0; q < n; q++) {
        sh_conv c;
        parse_truth(&truths[q], &c);
        const int nd = (int)sh_conv_ndoubles(&c, order);
        for (int k = 0; k < nd; k++) cu[k] = sin(1.3 * k + 0.1 * q + 0.2);
        if (truths[q].complex && !truths[q].half) {
            /* a real function's full complex vector: a_{l,−m} = (−1)^m conj(a_lm) (cs); nocs conj */
            for (int l = 0; l < order; l++) {
                cu[2 * (l * (l + 1)) + 1] = 0;
                for (int m = 1; m <= l; m++) {
                    const double sg = truths[q].cs && (m & 1) ? -1 : 1;
                    cu[2 * (l * (l + 1) - m)] = sg * cu[2 * (l * (l + 1) + m)];
                    cu[2 * (l * (l + 1) - m) + 1] = -sg * cu[2 * (l * (l + 1) + m) + 1];
                }
            }
        }
        if (truths[q].complex && truths[q].half)
            for (int l = 0; l < order; l++) cu[2 * l + 1] = 0; /* m = 0 entries are real */
        ck_assert_int_eq(sh_conv_to_shlab(&c, order, cu, cs), SH_OK);
        ck_assert_int_eq(sh_conv_from_shlab(&c, order, cs, back), SH_OK);
        char spec[96];
        truth_spec(&truths[q], spec, sizeof spec);
        for (int k = 0; k < nd; k++) ck_close(back[k], cu[k], 1e-13, 1.0, "%s round trip entry %d", spec, k);
        for (int j = 0; j < 32; j += 3) {
            truth_eval(&truths[q], order, D + 3 * j, u);
            double f = 0, g = 0;
            if (!truths[q].complex) {
                for (int k = 0; k < nd; k++) f += cu[k] * u[k];
            } else {
                for (int l = 0; l < order; l++)
                    for (int m = -l; m <= l; m++) {
                        /* Re Σ a Y; the half layout holds m >= 0 of a real function: 2 Re for m > 0 */
                        if (truths[q].half && m < 0) continue;
                        const int am = abs(m);
                        const int e = truths[q].half ? am * (2 * (order - 1) + 1 - am) / 2 + l : l * (l + 1) + m;
                        const double re = cu[2 * e] * u[2 * e] - cu[2 * e + 1] * u[2 * e + 1];
                        f += (truths[q].half && m > 0) ? 2 * re : re;
                    }
            }
            double y[16];
            truth_eval(&shl, order, D + 3 * j, y);
            for (int k = 0; k < 16; k++) g += cs[k] * y[k];
            ck_close(g, f, 1e-13, 1.0, "%s function at direction %d", spec, j);
        }
    }
}
END_TEST

/* The old names keep their meaning: sh_convert's norms. */
START_TEST(legacy_names)
{
    const char *names[] = {"cs", "nocs", "4pi", "schmidt"};
    const sh_norm norms[] = {SH_NORM_CS, SH_NORM_NOCS, SH_NORM_4PI, SH_NORM_SCHMIDT};
    double c[25], a[25], b[25];
    for (int i = 0; i < 25; i++) c[i] = cos(0.7 * i + 0.3);
    for (int f = 0; f < 4; f++)
        for (int t = 0; t < 4; t++) {
            sh_conv cf, ct;
            ck_assert_int_eq(sh_conv_parse(names[f], &cf), SH_OK);
            ck_assert_int_eq(sh_conv_parse(names[t], &ct), SH_OK);
            memcpy(a, c, sizeof c);
            ck_assert_int_eq(sh_convert(5, norms[f], norms[t], a), SH_OK);
            ck_assert_int_eq(sh_conv_convert(&cf, &ct, 5, c, b), SH_OK);
            for (int i = 0; i < 25; i++) ck_close(b[i], a[i], 1e-14, 1.0, "%s -> %s entry %d", names[f], names[t], i);
        }
    sh_conv x;
    char buf[96];
    ck_assert_int_eq(sh_conv_parse("real,nocs,sn3d,acn,z-up", &x), SH_OK);
    ck_assert_str_eq(sh_conv_preset(&x), "ambix");
    ck_assert_int_eq(sh_conv_parse("y-up,fuma,fuma-order", &x), SH_OK);
    ck_assert_str_eq(sh_conv_format(&x, buf, sizeof buf), "real,cs,fuma,fuma-order,neg-sin,y-up");
    ck_assert_int_ne(sh_conv_check(&x, 5), SH_OK);
    ck_assert_int_ne(sh_conv_parse("real,cs,nocs", &x), SH_OK);
    ck_assert_int_ne(sh_conv_parse("complex,4pi", &x), SH_OK);
    ck_assert_int_ne(sh_conv_parse("real,,cs", &x), SH_OK);
    ck_assert_int_ne(sh_conv_parse("+x+x+z", &x), SH_OK);
    ck_assert_int_ne(sh_conv_parse("bogus", &x), SH_OK);
}
END_TEST

/* The committed light: shlab's reference is Σ w_j y(d_j) with y from the
 * truth table (CS), at the light's exact rational directions. */
START_TEST(light_reference)
{
    const int L[3][4] = {{2, -3, 6, 7}, {-8, 4, 1, 9}, {9, -2, -6, 11}};
    const double w[3] = {1.0, 0.5, 0.25};
    double ref[16] = {0}, lib[16];
    const truth_conv shl = {0, 0, 1, 0, "ortho", "acn", "+x+y+z"};
    for (int j = 0; j < 3; j++) {
        const double d[3] = {(double)L[j][0] / L[j][3], (double)L[j][1] / L[j][3], (double)L[j][2] / L[j][3]};
        double y[16];
        truth_eval(&shl, 4, d, y);
        for (int i = 0; i < 16; i++) ref[i] += w[j] * y[i];
    }
    ck_assert_int_eq(sh_identify_light_coeffs(4, lib), SH_OK);
    for (int i = 0; i < 16; i++) ck_close(lib[i], ref[i], 1e-14, 1.0, "light coefficient %d", i);
}
END_TEST

/* ---- identify ---------------------------------------------------------- */
static int names_it(const sh_id_candidate *k, const sh_conv *c)
{
    double a[64], b[64];
    const double d[3] = {0.267, -0.535, 0.802};
    /* the class names c when one member is c, or is the same function */
    const sh_conv *m[SH_IDENTIFY_MAX_ALIASES + 1];
    int n = 0;
    m[n++] = &k->conv;
    for (int i = 0; i < k->naliases && i < SH_IDENTIFY_MAX_ALIASES; i++) m[n++] = &k->aliases[i];
    for (int i = 0; i < n; i++)
        if (!memcmp(m[i], c, sizeof *c)) return 1;
    /* sn3d/n3d and FuMa order: same functions under another name */
    if (k->conv.kind != c->kind) return 0;
    sh_conv_eval_dir(&k->conv, k->order, d, a);
    sh_conv_eval_dir(c, k->order, d, b);
    for (size_t i = 0; i < sh_conv_ndoubles(c, k->order); i++)
        if (fabs(a[i] - b[i]) > 1e-12) return 0;
    return 1;
}

static void identify_one(const truth_conv *t, int order, int *nid, int *namb)
{
    sh_conv c;
    parse_truth(t, &c);
    const size_t nd = sh_conv_ndoubles(&c, order);
    double *v = malloc(sizeof(double) * nd * 32);
    for (int j = 0; j < 32; j++) truth_eval(t, order, D + 3 * j, v + nd * j);
    sh_id_result r;
    ck_assert_int_eq(sh_identify_basis(32, D, nd, v, order, 1e-6, &r), SH_OK);
    char spec[96];
    truth_spec(t, spec, sizeof spec);
    ck_assert_msg(r.ncand >= 1 && r.verdict != SH_ID_NONE, "%s: no fit", spec);
    int found = 0;
    for (int i = 0; i < r.ncand; i++) found |= r.cand[i].fits && names_it(&r.cand[i], &c);
    ck_assert_msg(found, "%s at order %d: not among the %d fitting classes", spec, order, r.ncand);
    if (r.verdict == SH_ID_AMBIGUOUS) {
        ck_assert_msg(r.needs_order > order, "%s: ambiguous at order %d but no deciding order", spec, order);
        (*namb)++;
    } else {
        (*nid)++;
    }
    sh_identify_free(&r);
    free(v);
}

/* Every convention with z-up and every axes with four settings, at order 4:
 * identified (bands 0..3 tell them all apart). */
START_TEST(identify_from_basis)
{
    load_dirs();
    const int n = all_truths(truths);
    int nid = 0, namb = 0, tried = 0;
    for (int q = 0; q < n; q++) {
        const truth_conv *t = &truths[q];
        const int zup = !strcmp(t->axes, "+x+y+z");
        /* every axes: real acn ortho and fuma with the phase, complex with
         * and without; other mixes: one in 97 */
        const int sample = (!t->complex && t->cs && !strcmp(t->index, "acn") && !t->neg_cos &&
                            (!strcmp(t->norm, "ortho") || !strcmp(t->norm, "fuma"))) ||
                           (t->complex && !t->half);
        if (!zup && !sample && q % 97) continue;
        identify_one(t, 4, &nid, &namb);
        tried++;
    }
    printf("convention: identify at order 4 from basis values: %d conventions, %d identified, %d ambiguous\n",
           tried, nid, namb);
    ck_assert_int_eq(namb, 0);
}
END_TEST

/* Fewer bands: ambiguous with the order that decides.  At order 2 ACN and
 * m-descending differ by swapping x and y — a mirror — so mdesc z-up fits
 * ACN with axes +y+x+z too: needs band 2 (order 3). */
START_TEST(identify_needs_more_bands)
{
    load_dirs();
    truth_conv t = {0, 0, 1, 0, "ortho", "mdesc", "+x+y+z"};
    sh_conv c;
    parse_truth(&t, &c);
    double v[32 * 4];
    for (int j = 0; j < 32; j++) truth_eval(&t, 2, D + 3 * j, v + 4 * j);
    sh_id_result r;
    ck_assert_int_eq(sh_identify_basis(32, D, 4, v, 2, 1e-6, &r), SH_OK);
    ck_assert_int_eq(r.verdict, SH_ID_AMBIGUOUS);
    ck_assert_int_eq(r.needs_order, 3);
    int found = 0;
    for (int i = 0; i < r.ncand; i++) found |= names_it(&r.cand[i], &c);
    ck_assert(found);
    sh_identify_free(&r);
    /* at order 3 it is identified */
    double v3[32 * 9];
    for (int j = 0; j < 32; j++) truth_eval(&t, 3, D + 3 * j, v3 + 9 * j);
    ck_assert_int_eq(sh_identify_basis(32, D, 9, v3, 3, 1e-6, &r), SH_OK);
    ck_assert_int_eq(r.verdict, SH_ID_IDENTIFIED);
    ck_assert(names_it(&r.cand[0], &c));
    sh_identify_free(&r);
    /* a basis with a wrong sign in band 2 fits nothing; the nearest fit through order 2 */
    for (int j = 0; j < 32; j++) v3[9 * j + 6] = -v3[9 * j + 6];
    ck_assert_int_eq(sh_identify_basis(32, D, 9, v3, 3, 1e-6, &r), SH_OK);
    ck_assert_int_eq(r.verdict, SH_ID_NONE);
    ck_assert_int_ge(r.ncand, 1);
    ck_assert_int_eq(r.cand[0].fits_through, 2);
    sh_identify_free(&r);
}
END_TEST

/* From the projection of the committed light: user coefficients built from
 * the truth basis (c = G⁻¹ Σ w U(d), G the Gram diagonal ∫U² written per
 * normalisation: ortho 1, 4π 4π, Schmidt 4π/(2l+1), complex: conj), then
 * identify, and convert → shlab's reference. */
START_TEST(identify_from_projection)
{
    load_dirs();
    const int L[3][4] = {{2, -3, 6, 7}, {-8, 4, 1, 9}, {9, -2, -6, 11}};
    const double w[3] = {1.0, 0.5, 0.25};
    const int n = all_truths(truths), order = 4;
    double ref[16], cs[16];
    ck_assert_int_eq(sh_identify_light_coeffs(order, ref), SH_OK);
    int tried = 0, nid = 0;
    for (int q = 0; q < n; q++) {
        const truth_conv *t = &truths[q];
        if (!strcmp(t->norm, "fuma") || !strcmp(t->index, "fuma-order")) continue; /* Gram below has no FuMa row */
        const int zup = !strcmp(t->axes, "+x+y+z");
        if (!zup && q % 37) continue;
        sh_conv c;
        parse_truth(t, &c);
        const size_t nd = sh_conv_ndoubles(&c, order);
        double u[64], cu[64] = {0};
        for (int j = 0; j < 3; j++) {
            const double d[3] = {(double)L[j][0] / L[j][3], (double)L[j][1] / L[j][3], (double)L[j][2] / L[j][3]};
            truth_eval(t, order, d, u);
            for (size_t k = 0; k < nd; k++) {
                int l = 0, m = 0;
                if (!t->complex) truth_lm(t, (int)k, &l, &m);
                const double g = (t->complex || !strcmp(t->norm, "ortho")) ? 1.0
                                 : (!strcmp(t->norm, "4pi") || !strcmp(t->norm, "n3d")) ? 4 * M_PI
                                                                                          : 4 * M_PI / (2 * l + 1);
                cu[k] += w[j] * (t->complex && (k & 1) ? -u[k] : u[k]) / g;
            }
        }
        char spec[96];
        truth_spec(t, spec, sizeof spec);
        ck_assert_int_eq(sh_conv_to_shlab(&c, order, cu, cs), SH_OK);
        for (int i = 0; i < 16; i++) ck_close(cs[i], ref[i], 1e-13, 1.0, "%s: convert of the light, entry %d", spec, i);
        sh_id_result r;
        ck_assert_int_eq(sh_identify_projection(nd, cu, ref, order, order, 1e-6, &r), SH_OK);
        int found = 0;
        for (int i = 0; i < r.ncand; i++) found |= r.cand[i].fits && names_it(&r.cand[i], &c);
        ck_assert_msg(found, "%s: not among %d classes (verdict %d)", spec, r.ncand, r.verdict);
        nid += r.verdict == SH_ID_IDENTIFIED;
        ck_assert_msg(r.verdict == SH_ID_IDENTIFIED, "%s: verdict %d with %d classes", spec, r.verdict, r.ncand);
        sh_identify_free(&r);
        tried++;
    }
    printf("convention: identify from the light's projection: %d conventions, %d identified\n", tried, nid);
}
END_TEST

START_TEST(identify_bad_input)
{
    load_dirs();
    double v[32 * 5] = {0};
    sh_id_result r;
    ck_assert_int_eq(sh_identify_basis(32, D, 5, v, 0, 1e-6, &r), SH_EINVAL); /* 5: no kind */
    ck_assert_int_eq(sh_identify_basis(32, D, 4, v, 3, 1e-6, &r), SH_EINVAL); /* order 3 needs 9 */
    ck_assert_int_eq(sh_identify_basis(32, D, 4, v, 2, 0, &r), SH_EINVAL);
    ck_assert_int_eq(sh_identify_basis(32, D, 4, v, 17, 1e-6, &r), SH_EINVAL);
}
END_TEST

static Suite *convention_suite(void)
{
    Suite *s = suite_create("convention");
    TCase *t = tcase_create("convention");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, truth_tables);
    tcase_add_test(t, eval_matches_truth_every_combination);
    tcase_add_test(t, convert_keeps_function_and_round_trips);
    tcase_add_test(t, legacy_names);
    tcase_add_test(t, light_reference);
    tcase_add_test(t, identify_from_basis);
    tcase_add_test(t, identify_needs_more_bands);
    tcase_add_test(t, identify_from_projection);
    tcase_add_test(t, identify_bad_input);
    suite_add_tcase(s, t);
    return s;
}

SHLAB_TEST_MAIN(convention_suite)
