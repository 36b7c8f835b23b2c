/* convention.c — other people's SH conventions (shlab/convention.h): the
 * descriptor and its spec string, the user's basis at a direction, and the
 * conversions to and from shlab's real orthonormal cs basis.
 *
 * References: the real/complex relation and the Condon-Shortley phase as in
 * Varshalovich et al., "Quantum Theory of Angular Momentum" §5.2 and
 * Blanco, Flórez & Bermejo (1997) eq. 9; Schmidt semi-normalisation as in
 * Winch et al. (2005); ambisonics ACN/SN3D/N3D as in Nachbar, Zotter,
 * Deleflie & Sontacchi, "AmbiX — a suggested ambisonics format" (2011);
 * Furse-Malham (FuMa) weights and channel order as in Malham, "Higher order
 * Ambisonic systems" (2003), table of the FuMa set; HEALPix's a_lm order as
 * in Górski et al. (2005) and healpix_cxx's Alm_Base::index(l,m). */
#include "shlab.h"
#include "convention_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ axes */
/* u_i = sign_i · s_{perm[i]}: the user's coordinate i from shlab's formula
 * coordinates s. */
static const int axes_perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
static const int axes_parity[6] = {1, -1, -1, 1, 1, -1};

static int axes_sign(int axes, int i) { return ((axes % 8) >> i) & 1 ? -1 : 1; }

int sh_conv_axes_mirror(int axes)
{
    const int p = axes_parity[axes / 8] * axes_sign(axes, 0) * axes_sign(axes, 1) * axes_sign(axes, 2);
    return p < 0;
}

void sh_conv_axes_matrix(int axes, double S[9])
{
    /* s_{perm[i]} = sign_i u_i  ⇒  S[perm[i]][i] = sign_i */
    memset(S, 0, 9 * sizeof *S);
    for (int i = 0; i < 3; i++) S[axes_perm[axes / 8][i] * 3 + i] = axes_sign(axes, i);
}

static void axes_name(int axes, char out[8])
{
    for (int i = 0; i < 3; i++) {
        out[2 * i] = axes_sign(axes, i) < 0 ? '-' : '+';
        out[2 * i + 1] = "xyz"[axes_perm[axes / 8][i]];
    }
    out[6] = 0;
}

static int axes_parse(const char *t, int *axes)
{
    if (!strcmp(t, "z-up")) { *axes = 0; return 1; }
    if (!strcmp(t, "y-up")) { *axes = 12; return 1; }   /* +x+z-y */
    if (!strcmp(t, "y-up-lh")) { *axes = 8; return 1; } /* +x+z+y */
    if (strlen(t) != 6) return 0;
    for (int a = 0; a < SH_CONV_NAXES; a++) {
        char nm[8];
        axes_name(a, nm);
        if (!strcmp(nm, t)) { *axes = a; return 1; }
    }
    return 0;
}

/* ------------------------------------------------------------- the spec */
static const char *const kind_names[] = {"real", "complex", "complex-half"};
static const char *const norm_names[] = {"ortho", "4pi", "schmidt", "sn3d", "n3d", "fuma"};
static const char *const index_names[] = {"acn", "mdesc", "cossin", "fuma-order"};

sh_conv sh_conv_shlab(void)
{
    sh_conv c = {SH_KIND_REAL, 1, SH_CNORM_ORTHO, SH_CINDEX_ACN, 0, 0};
    return c;
}

static const struct {
    const char *name;
    sh_conv c;
} presets[] = {
    {"cs", {SH_KIND_REAL, 1, SH_CNORM_ORTHO, SH_CINDEX_ACN, 0, 0}},
    {"nocs", {SH_KIND_REAL, 0, SH_CNORM_ORTHO, SH_CINDEX_ACN, 0, 0}},
    {"4pi", {SH_KIND_REAL, 0, SH_CNORM_4PI, SH_CINDEX_ACN, 0, 0}},
    {"schmidt", {SH_KIND_REAL, 0, SH_CNORM_SCHMIDT, SH_CINDEX_ACN, 0, 0}},
    {"ambix", {SH_KIND_REAL, 0, SH_CNORM_SN3D, SH_CINDEX_ACN, 0, 0}},
    {"fuma", {SH_KIND_REAL, 0, SH_CNORM_FUMA, SH_CINDEX_FUMA, 0, 0}},
    {"healpix", {SH_KIND_COMPLEX_HALF, 1, SH_CNORM_ORTHO, SH_CINDEX_ACN, 0, 0}},
};
#define NPRESETS (int)(sizeof presets / sizeof *presets)

static int same(const sh_conv *a, const sh_conv *b)
{
    return a->kind == b->kind && a->cs == b->cs && a->norm == b->norm && a->index == b->index &&
           a->neg_cos == b->neg_cos && a->axes == b->axes;
}

const char *sh_conv_preset(const sh_conv *c)
{
    for (int k = 0; k < NPRESETS; k++)
        if (same(c, &presets[k].c)) return presets[k].name;
    return NULL;
}

static int find(const char *t, const char *const *names, int n)
{
    for (int k = 0; k < n; k++)
        if (!strcmp(t, names[k])) return k;
    return -1;
}

/* One token into its field; seen[f] counts fields set (each at most once). */
static int parse_token(const char *t, sh_conv *c, int seen[6])
{
    int k, f;
    if ((k = find(t, kind_names, 3)) >= 0) { c->kind = (sh_conv_kind)k; f = 0; }
    else if (!strcmp(t, "cs") || !strcmp(t, "nocs")) { c->cs = t[0] == 'c'; f = 1; }
    else if (!strcmp(t, "orthonormal") || (k = find(t, norm_names, 6)) >= 0) {
        c->norm = t[0] == 'o' ? SH_CNORM_ORTHO : (sh_conv_norm)k; f = 2;
    } else if ((k = find(t, index_names, 4)) >= 0) { c->index = (sh_conv_index)k; f = 3; }
    else if (!strcmp(t, "neg-sin") || !strcmp(t, "neg-cos")) { c->neg_cos = t[4] == 'c'; f = 4; }
    else if (axes_parse(t, &c->axes)) f = 5;
    else
        return sh_error(SH_EINVAL, "unknown convention token '%s' (kinds real, complex, complex-half; "
                        "cs, nocs; ortho, 4pi, schmidt, sn3d, n3d, fuma; acn, mdesc, cossin, fuma-order; "
                        "neg-sin, neg-cos; z-up, y-up, y-up-lh or axes like +x+z-y)", t);
    static const char *const field[] = {"kind", "phase", "normalisation", "index order", "m<0 function", "axes"};
    if (seen[f]++) return sh_error(SH_EINVAL, "convention token '%s': the %s is given twice", t, field[f]);
    return SH_OK;
}

int sh_conv_parse(const char *spec, sh_conv *out)
{
    if (!spec || !*spec) return sh_error(SH_EINVAL, "empty convention spec");
    for (int k = 0; k < NPRESETS; k++)
        if (!strcmp(spec, presets[k].name)) { *out = presets[k].c; return SH_OK; }
    char buf[256];
    if (strlen(spec) >= sizeof buf) return sh_error(SH_EINVAL, "convention spec longer than %zu characters", sizeof buf - 1);
    strcpy(buf, spec);
    sh_conv c = sh_conv_shlab();
    int seen[6] = {0};
    for (char *t = buf, *next; t; t = next) {
        next = strchr(t, ',');
        if (next) *next++ = 0;
        if (!*t) return sh_error(SH_EINVAL, "convention spec '%s' has an empty token", spec);
        int st = parse_token(t, &c, seen);
        if (st) return st;
    }
    if (c.kind != SH_KIND_REAL && (c.norm != SH_CNORM_ORTHO || c.index != SH_CINDEX_ACN || c.neg_cos))
        return sh_error(SH_EINVAL, "convention '%s': complex coefficients are orthonormal and have "
                        "their own layout (no normalisation, index order or neg-cos)", spec);
    *out = c;
    return SH_OK;
}

char *sh_conv_format(const sh_conv *c, char *buf, size_t n)
{
    char ax[8];
    axes_name(c->axes, ax);
    const char *axn = c->axes == 0 ? "z-up" : c->axes == 12 ? "y-up" : c->axes == 8 ? "y-up-lh" : ax;
    if (c->kind != SH_KIND_REAL)
        snprintf(buf, n, "%s,%s,%s", kind_names[c->kind], c->cs ? "cs" : "nocs", axn);
    else
        snprintf(buf, n, "real,%s,%s,%s,%s,%s", c->cs ? "cs" : "nocs", norm_names[c->norm],
                 index_names[c->index], c->neg_cos ? "neg-cos" : "neg-sin", axn);
    return buf;
}

static int valid(const sh_conv *c)
{
    return c && c->kind >= SH_KIND_REAL && c->kind <= SH_KIND_COMPLEX_HALF && c->norm >= SH_CNORM_ORTHO &&
           c->norm <= SH_CNORM_FUMA && c->index >= SH_CINDEX_ACN && c->index <= SH_CINDEX_FUMA &&
           c->axes >= 0 && c->axes < SH_CONV_NAXES;
}

int sh_conv_check(const sh_conv *c, int order)
{
    int st = sh_check_order(order);
    if (st) return st;
    if (!valid(c)) return sh_error(SH_EINVAL, "invalid convention descriptor");
    if ((c->norm == SH_CNORM_FUMA || c->index == SH_CINDEX_FUMA) && order > SH_CONV_FUMA_MAX_ORDER)
        return sh_error(SH_EINVAL, "FuMa covers orders up to %d (bands 0..3), not %d",
                        SH_CONV_FUMA_MAX_ORDER, order);
    return SH_OK;
}

/* ------------------------------------------------------------ the layout */
size_t sh_conv_ndoubles(const sh_conv *c, int order)
{
    const size_t n = (size_t)order;
    return c->kind == SH_KIND_REAL ? n * n : c->kind == SH_KIND_COMPLEX ? 2 * n * n : n * (n + 1);
}

int sh_conv_order_of(const sh_conv *c, size_t nd, int *order)
{
    for (int n = 1; n <= SHLAB_MAX_ORDER; n++) {
        const size_t k = sh_conv_ndoubles(c, n);
        if (k == nd) { *order = n; return SH_OK; }
        if (k > nd) break;
    }
    return sh_error(SH_EINVAL, "%zu numbers is not a whole order of %s coefficients (%s)", nd,
                    kind_names[c->kind],
                    c->kind == SH_KIND_REAL ? "n²" : c->kind == SH_KIND_COMPLEX ? "2n²: re,im of n²" : "n(n+1): re,im of n(n+1)/2");
}

/* HEALPix's m-major index of (l, m), m >= 0: m(2·lmax+1−m)/2 + l. */
static size_t half_index(int lmax, int l, int m) { return (size_t)m * (2 * lmax + 1 - m) / 2 + l; }

int sh_conv_band_of(const sh_conv *c, int order, size_t k)
{
    int l, m;
    if (c->kind == SH_KIND_COMPLEX) k /= 2;
    if (c->kind != SH_KIND_COMPLEX_HALF) {
        sh_index_lm((int)k, &l, &m); /* every real index order is band-major */
        return l;
    }
    k /= 2;
    for (m = 0; m < order; m++)
        if (k <= half_index(order - 1, order - 1, m)) return (int)(k - half_index(order - 1, m, m)) + m;
    return -1;
}

/* FuMa's channels W X Y Z R S T U V K L M N O P Q as ACN indices
 * (W=(0,0) Y=(1,−1) Z=(1,0) X=(1,1) V=(2,−2) T=(2,−1) R=(2,0) S=(2,1)
 * U=(2,2) Q=(3,−3) O=(3,−2) M=(3,−1) K=(3,0) L=(3,1) N=(3,2) P=(3,3)). */
static const int fuma_acn[16] = {0, 3, 1, 2, 6, 7, 5, 8, 4, 12, 13, 11, 14, 10, 15, 9};

/* FuMa's weight relative to SN3D for band l, |m| (Malham 2003): the maxN
 * scaling (each function's maximum is 1), with W = 1/√2. */
static double fuma_weight(int l, int am)
{
    static const double w[4][4] = {
        {M_SQRT1_2, 0, 0, 0},
        {1, 1, 0, 0},
        {1, 1.1547005383792515 /* 2/√3 */, 1.1547005383792515, 0},
        {1, 1.1858541225631423 /* √(45/32) */, 1.3416407864998738 /* 3/√5 */, 1.2649110640673518 /* √(8/5) */},
    };
    return w[l][am];
}

/* Band l's scale relative to orthonormal: U = scale · y (ortho 1, 4π/N3D
 * √(4π), Schmidt/SN3D √(4π/(2l+1)), FuMa SN3D × its weight). */
static double norm_scale(sh_conv_norm n, int l, int am)
{
    switch (n) {
    case SH_CNORM_4PI: case SH_CNORM_N3D: return sqrt(4.0 * M_PI);
    case SH_CNORM_SCHMIDT: case SH_CNORM_SN3D: return sqrt(4.0 * M_PI / (2.0 * l + 1.0));
    case SH_CNORM_FUMA: return sqrt(4.0 * M_PI / (2.0 * l + 1.0)) * fuma_weight(l, am);
    default: return 1.0;
    }
}

/* Real kinds: user entry k is U_k = w · y_i (shlab's cs function i at the
 * formula coordinates). */
void sh__conv_real_entry(const sh_conv *c, int k, int *i, double *w)
{
    int l, m, j;
    if (c->index == SH_CINDEX_FUMA) {
        sh_index_lm(fuma_acn[k], &l, &m);
    } else {
        sh_index_lm(k, &l, &m);
        j = k - l * l; /* position within the band */
        if (c->index == SH_CINDEX_MDESC) m = l - j;
        else if (c->index == SH_CINDEX_COSSIN) m = j == 0 ? 0 : (j & 1) ? (j + 1) / 2 : -j / 2;
    }
    const int am = abs(m);
    *i = sh_index(l, c->neg_cos ? -m : m);
    *w = norm_scale(c->norm, l, am) * ((!c->cs && (am & 1)) ? -1.0 : 1.0);
}

/* ------------------------------------------------------------- evaluation */
int sh_conv_eval_dir(const sh_conv *c, int order, const double d[3], double *values)
{
    int st = sh_conv_check(c, order);
    if (st) return st;
    double S[9], s[3];
    sh_conv_axes_matrix(c->axes, S);
    for (int r = 0; r < 3; r++) s[r] = S[3 * r] * d[0] + S[3 * r + 1] * d[1] + S[3 * r + 2] * d[2];
    const int n = order * order;
    double *y = malloc(sizeof(double) * n);
    if (!y) return sh_error(SH_ENOMEM, "out of memory (%d doubles)", n);
    if ((st = sh_eval_dir(order, SH_CS, s, y))) { free(y); return st; }
    if (c->kind == SH_KIND_REAL) {
        for (int k = 0; k < n; k++) {
            int i;
            double w;
            sh__conv_real_entry(c, k, &i, &w);
            values[k] = w * y[i];
        }
    } else {
        /* Y_l^m = (y_l^m + i y_l^{−m})/√2 (m > 0, cs), Y_l^0 = y_l^0,
         * Y_l^{−m} = (−1)^m conj(Y_l^m); nocs: Y_l^m · (−1)^m for m > 0. */
        for (int l = 0; l < order; l++)
            for (int m = 0; m <= l; m++) {
                double re = m ? y[sh_index(l, m)] * M_SQRT1_2 : y[sh_index(l, 0)];
                double im = m ? y[sh_index(l, -m)] * M_SQRT1_2 : 0.0;
                const double sg = (m & 1) ? -1.0 : 1.0;
                const double ph = c->cs ? 1.0 : sg;
                size_t j = c->kind == SH_KIND_COMPLEX ? (size_t)sh_index(l, m) : half_index(order - 1, l, m);
                values[2 * j] = ph * re;
                values[2 * j + 1] = ph * im;
                if (c->kind == SH_KIND_COMPLEX && m) {
                    j = (size_t)sh_index(l, -m);
                    values[2 * j] = sg * re;
                    values[2 * j + 1] = -sg * im;
                }
            }
    }
    free(y);
    return SH_OK;
}

/* ------------------------------------------------------------ conversions */
/* out = coefficients of d ↦ F(M d), F = Σ in_i y_i, for a signed
 * permutation M (row-major).  Improper M = −M' with M' proper: F(−M'd) =
 * F_p(M'd), F_p having coefficients (−1)^l in_i.  Proper: F(M d) = F(R⁻¹ d)
 * with R = Mᵀ, whose coefficients are R_sh(R)·in (docs/CONVENTIONS.md
 * "Rotations": g(s) = f(R⁻¹ s)). */
static int signed_perm_apply(int order, const double M[9], const double *in, double *out)
{
    const int n = order * order;
    const double det = M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
                       M[2] * (M[3] * M[7] - M[4] * M[6]);
    double R[9];
    int identity = 1;
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++) {
            R[3 * r + q] = (det < 0 ? -1.0 : 1.0) * M[3 * q + r];
            identity &= R[3 * r + q] == (r == q ? 1.0 : 0.0);
        }
    for (int i = 0; i < n; i++) {
        int l = (int)floor(sqrt((double)i));
        while (l * l > i) l--;
        while ((l + 1) * (l + 1) <= i) l++;
        out[i] = (det < 0 && (l & 1)) ? -in[i] : in[i];
    }
    if (identity) return SH_OK;
    sh_rot_plan *p = NULL;
    int st = sh_rot_plan_create(order, sh_rot_method_default(order, 0), SH_PREC_DOUBLE, SH_CS, &p);
    if (!st) st = sh_rot_plan_set_matrix(p, R);
    if (!st) st = sh_rot_plan_apply(p, out, out);
    sh_rot_plan_free(p);
    return st;
}

/* user → b: the coefficients on shlab's functions at the formula
 * coordinates (axes not yet applied).  Complex: b of the real part. */
static void user_to_formula(const sh_conv *c, int order, const double *user, double *b)
{
    if (c->kind == SH_KIND_REAL) {
        /* f = Σ c_k U_k = Σ c_k w_k y_i  ⇒  b_i = c_k w_k */
        for (int k = 0; k < order * order; k++) {
            int i;
            double w;
            sh__conv_real_entry(c, k, &i, &w);
            b[i] = user[k] * w;
        }
        return;
    }
    for (int l = 0; l < order; l++)
        for (int m = 0; m <= l; m++) {
            const double sg = (m & 1) ? -1.0 : 1.0, ph = c->cs ? 1.0 : sg; /* a_cs = ph · a (m > 0) */
            size_t j = c->kind == SH_KIND_COMPLEX ? (size_t)sh_index(l, m) : half_index(order - 1, l, m);
            double re = ph * user[2 * j], im = ph * user[2 * j + 1];
            if (c->kind == SH_KIND_COMPLEX && m) {
                /* Re f's coefficient: (a_m + (−1)^m conj(a_{−m}))/2 */
                const size_t q = (size_t)sh_index(l, -m);
                re = 0.5 * (re + sg * user[2 * q]);
                im = 0.5 * (im - sg * user[2 * q + 1]);
            }
            /* 2 Re(a Y_m) = √2 Re a · y_m − √2 Im a · y_{−m} */
            if (m) {
                b[sh_index(l, m)] = M_SQRT2 * re;
                b[sh_index(l, -m)] = -M_SQRT2 * im;
            } else {
                b[sh_index(l, 0)] = re;
            }
        }
}

static void formula_to_user(const sh_conv *c, int order, const double *b, double *user)
{
    if (c->kind == SH_KIND_REAL) {
        for (int k = 0; k < order * order; k++) {
            int i;
            double w;
            sh__conv_real_entry(c, k, &i, &w);
            user[k] = b[i] / w;
        }
        return;
    }
    for (int l = 0; l < order; l++)
        for (int m = 0; m <= l; m++) {
            /* a_m = (b_m − i b_{−m})/√2 (cs), a_{−m} = (−1)^m conj(a_m) */
            const double re = m ? b[sh_index(l, m)] * M_SQRT1_2 : b[sh_index(l, 0)];
            const double im = m ? -b[sh_index(l, -m)] * M_SQRT1_2 : 0.0;
            const double sg = (m & 1) ? -1.0 : 1.0, ph = c->cs ? 1.0 : sg;
            size_t j = c->kind == SH_KIND_COMPLEX ? (size_t)sh_index(l, m) : half_index(order - 1, l, m);
            user[2 * j] = ph * re;
            user[2 * j + 1] = ph * im;
            if (c->kind == SH_KIND_COMPLEX && m) {
                j = (size_t)sh_index(l, -m);
                user[2 * j] = sg * re;
                user[2 * j + 1] = -sg * im;
            }
        }
}

int sh_conv_to_shlab(const sh_conv *c, int order, const double *user, double *shlab)
{
    int st = sh_conv_check(c, order);
    if (st) return st;
    const size_t n = (size_t)order * order;
    double *b = malloc(sizeof(double) * n);
    if (!b) return sh_error(SH_ENOMEM, "out of memory (%zu doubles)", n);
    user_to_formula(c, order, user, b);
    /* Σ b_i y_i(S d) = Σ c'_j y_j(d): the function d ↦ F(S d) */
    double S[9];
    sh_conv_axes_matrix(c->axes, S);
    st = signed_perm_apply(order, S, b, shlab);
    free(b);
    return st;
}

int sh_conv_from_shlab(const sh_conv *c, int order, const double *shlab, double *user)
{
    int st = sh_conv_check(c, order);
    if (st) return st;
    const size_t n = (size_t)order * order;
    double *b = malloc(sizeof(double) * n);
    if (!b) return sh_error(SH_ENOMEM, "out of memory (%zu doubles)", n);
    /* F(s) = h(S⁻¹ s), S⁻¹ = Sᵀ */
    double S[9], St[9];
    sh_conv_axes_matrix(c->axes, S);
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++) St[3 * r + q] = S[3 * q + r];
    st = signed_perm_apply(order, St, shlab, b);
    if (!st) formula_to_user(c, order, b, user);
    free(b);
    return st;
}

int sh_conv_convert(const sh_conv *from, const sh_conv *to, int order, const double *in, double *out)
{
    int st = sh_conv_check(from, order);
    if (st || (st = sh_conv_check(to, order))) return st;
    const size_t n = (size_t)order * order;
    double *mid = malloc(sizeof(double) * n);
    if (!mid) return sh_error(SH_ENOMEM, "out of memory (%zu doubles)", n);
    st = sh_conv_to_shlab(from, order, in, mid);
    if (!st) st = sh_conv_from_shlab(to, order, mid, out);
    free(mid);
    return st;
}
