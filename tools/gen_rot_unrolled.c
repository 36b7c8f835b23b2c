/* gen_rot_unrolled.c — writes src/rotate/rot_unrolled_gen.h, the straight-line
 * (unrolled) SH rotation kernels: ZXZXZ and the Taylor approximations 1, 1.5
 * and 2, one function per method and order 1..N.  Built and run by make:
 *
 *   make regen          rewrites src/rotate/rot_unrolled_gen.h
 *   make check          regenerates into build/ and fails if the committed
 *                       file differs (tests/cli/test_kernels.sh)
 *
 * With --shader glsl|hlsl --method M [--max-order N] it writes instead one
 * compute shader under shlab's shader convention (data/shaders/rot_*.glsl,
 * .hlsl; `make regen` rewrites them, tests/cli/test_shader_gen.sh compares
 * them): the same per-order bodies from the same emitter (the target
 * language is a parameter of every emit_* function's helpers), in float,
 * with the rotation's par computed in the shader (write_shader).
 *
 * The kernels are the loop kernels of rot_zxzxz.c and rot_taylor.c laid out
 * straight, with every table value folded into the code as a literal:
 *   - the same operations in the same order as the loops (so without FMA
 *     contraction the results are the same bit for bit, a test checks it);
 *   - products with a table entry that is exactly 0 are left out, and
 *     products with ±1 become a copy or a negation (this changes no value:
 *     x·1 = x, a + 0·x = a in IEEE arithmetic, up to the sign of a zero);
 *   - the +π of ZXZXZ (X₋₉₀ = Z(π)·X₊₉₀·Z(π), rot_zxzxz.c) is a sign flip of
 *     the odd-m z rotations, emitted as a negation of the pair's results.
 * The code is written for a value type `shk_t` (rot_simd.h): one real (one
 * rotation, one vector) or a SIMD vector whose lanes are independent
 * rotations or vectors (structure of arrays, lane stride K).  Literals are
 * written as SHK_C(x) with x printed to 17 significant digits, so that the
 * double a table holds is reproduced exactly and a float kernel gets
 * (float) of it, as the float tables do.
 *
 * Every multiplication is emitted as " * " (spaces around the star, and no
 * other star in a function body), so counting the multiplications of the
 * source is counting " * "; the banner and the table sh__unrolled_mults
 * record that count per function, and tests/test_unrolled.c compares it with
 * the source text and with what the plan reports.
 */
#include "shlab.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* rot_zxzxz.c (internal): the dense X₊₉₀ block of band l as the plan builds it */
int sh__rot_zxzxz_xplus_band(int l, double *X);
/* rot_ivanic.c (internal): the u, v', w tables of band l, 3(2l+1)² values */
void sh__rot_ivanic_coeffs(int l, double *t);

#define MAXN 16
enum { M_ZXZXZ, M_TAYLOR1, M_TAYLOR15, M_TAYLOR2, M_IVANIC, M_N };
static const char *const mname[M_N] = {"zxzxz", "taylor1", "taylor15", "taylor2", "ivanic"};
static const char *const mlabel[M_N] = {"zxzxz", "taylor1", "taylor1.5", "taylor2", "ivanic"};

/* ---- output: a growing buffer per function, so the count can be taken from
 * the text itself ---------------------------------------------------------- */
static char *buf;
static size_t blen, bcap;
static void out(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void out(const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        const int n = vsnprintf(buf + blen, bcap - blen, fmt, ap);
        va_end(ap);
        if (n < 0) { fprintf(stderr, "gen_rot_unrolled: output error\n"); exit(2); }
        if (blen + (size_t)n < bcap) { blen += (size_t)n; return; }
        bcap = 2 * bcap + (size_t)n + 1024;
        buf = realloc(buf, bcap);
        if (!buf) { fprintf(stderr, "gen_rot_unrolled: out of memory\n"); exit(2); }
    }
}
static unsigned long count_mults(const char *s)
{
    unsigned long k = 0;
    for (const char *p = s; (p = strstr(p, " * ")); p += 3) k++;
    return k;
}

/* ---- the target language: one emitter writes the C kernels (shk_t, the
 * SHK_* macros of rot_simd.h) and the compute shaders (GLSL, HLSL; float,
 * one rotation and one vector per invocation) --------------------------- */
enum { L_C, L_GLSL, L_HLSL };
static int lang = L_C;
/* the value type */
static const char *T(void) { return lang == L_C ? "shk_t" : "float"; }

/* a literal.  C: SHK_C(v) with 17 significant digits, which reproduce the
 * double exactly (a float kernel gets (float) of it).  Shaders: (float)v
 * with 9 significant digits, which reproduce that float exactly — the same
 * value the C float kernels use — always with a '.' or an exponent so that
 * GLSL reads a float, not an int. */
static const char *lit(double v)
{
    static char b[8][40];
    static int i;
    i = (i + 1) & 7;
    if (lang == L_C) snprintf(b[i], sizeof b[i], "SHK_C(%.17g)", v);
    else {
        snprintf(b[i], sizeof b[i], "%.9g", (double)(float)v);
        if (!strpbrk(b[i], ".e")) strcat(b[i], ".0");
    }
    return b[i];
}
/* the constants 1 and 0.5 */
static const char *one(void) { return lang == L_C ? "SHK_C(1)" : "1.0"; }
static const char *half(void) { return lang == L_C ? "SHK_C(0.5)" : "0.5"; }
/* coefficient i of the input vector; entry j of par */
static const char *ldin(int i)
{
    static char b[8][40];
    static int k;
    k = (k + 1) & 7;
    if (lang == L_C) snprintf(b[k], sizeof b[k], "SHK_LD(in, %d, K)", i);
    else snprintf(b[k], sizeof b[k], "x[b + %du]", i);
    return b[k];
}
static const char *ldpar(int j)
{
    static char b[8][40];
    static int k;
    k = (k + 1) & 7;
    if (lang == L_C) snprintf(b[k], sizeof b[k], "SHK_LD(par, %d, KP)", j);
    else snprintf(b[k], sizeof b[k], "par[%d]", j);
    return b[k];
}
/* a store of coefficient i of the output: st_open(i) EXPR st_close() */
static const char *st_open(int i)
{
    static char b[40];
    if (lang == L_C) snprintf(b, sizeof b, "SHK_ST(out, %d, K, ", i);
    else snprintf(b, sizeof b, "y[b + %du] = ", i);
    return b;
}
static const char *st_close(void) { return lang == L_C ? ")" : ""; }

/* names: x<l>_<m> (input of band l), u, t, v, w (intermediates of the band
 * in hand) of coefficient m; n for a negative m */
static const char *nmx(int l, int m)
{
    static char b[8][32];
    static int i;
    i = (i + 1) & 7;
    snprintf(b[i], sizeof b[i], m < 0 ? "x%d_n%d" : "x%d_%d", l, m < 0 ? -m : m);
    return b[i];
}
static const char *nm(char v, int m)
{
    static char b[16][16];
    static int i;
    i = (i + 1) & 15;
    if (m < 0) snprintf(b[i], sizeof b[i], "%c_n%d", v, -m);
    else snprintf(b[i], sizeof b[i], "%c_%d", v, m);
    return b[i];
}

/* the multiple angles: c<a>m, s<a>m for m = 1..mmax by the Chebyshev
 * recurrence of sh__rot_multiple_angles (c₀ = 1, s₀ = 0, 2c₁ exact as c₁ + c₁):
 *   c_m = 2c₁·c_{m−1} − c_{m−2},  s_m = 2c₁·s_{m−1} − s_{m−2} */
static void emit_angles(char a, int mmax)
{
    if (mmax < 2) return;
    out("    const %s t%c = c%c1 + c%c1;\n", T(), a, a, a);
    out("    const %s c%c2 = t%c * c%c1 - %s, s%c2 = t%c * s%c1;\n", T(), a, a, a, one(), a, a, a);
    for (int m = 3; m <= mmax; m++)
        out("    const %s c%c%d = t%c * c%c%d - c%c%d, s%c%d = t%c * s%c%d - s%c%d;\n", T(), a, m, a, a,
            m - 1, a, m - 2, a, m, a, a, m - 1, a, m - 2);
}

/* one z rotation of the pair (m, −m) of src into dst (declared const):
 *   dst_m = c·a − s·b,  dst_{−m} = s·a + c·b   (a = src_m, b = src_{−m}),
 * negated when flip (the (−1)^m of θ + π).  store: write to out[i] instead. */
static void emit_zpair(char a, int m, int flip, const char *am, const char *bm, char dst, int store,
                       int l)
{
    const char *ng = flip ? "-" : "";
    if (store) {
        const int ip = l * (l + 1) + m, in = l * (l + 1) - m;
        out("        %s%s(c%c%d * %s - s%c%d * %s)%s;\n", st_open(ip), ng, a, m, am, a, m, bm, st_close());
        out("        %s%s(s%c%d * %s + c%c%d * %s)%s;\n", st_open(in), ng, a, m, am, a, m, bm, st_close());
    } else {
        out("        const %s %s = %s(c%c%d * %s - s%c%d * %s);\n", T(), nm(dst, m), ng, a, m, am, a, m, bm);
        out("        const %s %s = %s(s%c%d * %s + c%c%d * %s);\n", T(), nm(dst, -m), ng, a, m, am, a, m,
            bm);
    }
}

/* u = Z(γ) x for band l (the first stage of zxzxz and the Taylor kernels) */
static void emit_zgamma(int l)
{
    char xp[32], xm[32];
    out("        const %s u_0 = %s;\n", T(), nmx(l, 0));
    for (int m = 1; m <= l; m++) {
        snprintf(xp, sizeof xp, "%s", nmx(l, m));
        snprintf(xm, sizeof xm, "%s", nmx(l, -m));
        emit_zpair('g', m, 0, xp, xm, 'u', 0, l);
    }
}

/* dst = X₊₉₀ src for band l: each row's non-zeros in ascending |m|, summed
 * left to right (rot_zxzxz.c's zx_mv) */
static void emit_xmul(int l, const double *X, char src, char dst)
{
    const int w = 2 * l + 1;
    for (int mp = -l; mp <= l; mp++) {
        int cols[2 * MAXN + 1], nc = 0;
        for (int am = 0; am <= l; am++)
            for (int sg = 1; sg >= -1; sg -= 2) {
                const int m = sg * am;
                if (am == 0 && sg < 0) continue;
                if (X[(size_t)(mp + l) * w + (size_t)(m + l)] != 0) cols[nc++] = m;
            }
        /* the zero pattern (rot_zxzxz.c): each row reads one class of m, so |m| is unique */
        for (int i = 1; i < nc; i++)
            if (abs(cols[i]) == abs(cols[i - 1])) {
                fprintf(stderr, "gen_rot_unrolled: band %d row %d: both m and -m non-zero\n", l, mp);
                exit(2);
            }
        out("        const %s %s = ", T(), nm(dst, mp));
        if (nc == 0) { fprintf(stderr, "gen_rot_unrolled: band %d row %d is zero\n", l, mp); exit(2); }
        for (int i = 0; i < nc; i++) {
            const double v = X[(size_t)(mp + l) * w + (size_t)(cols[i] + l)];
            const char *s = nm(src, cols[i]);
            if (i == 0) {
                if (v == 1) out("%s", s);
                else if (v == -1) out("-%s", s);
                else out("%s * %s", lit(v), s);
            } else {
                if (v == 1) out(" + %s", s);
                else if (v == -1) out(" - %s", s);
                else out(" + %s * %s", lit(v), s);
            }
        }
        out(";\n");
    }
}

static void emit_head(int meth, int n)
{
    if (lang == L_C) {
        out("/* %s, order %d (bands 0..%d) */\n", mlabel[meth], n, n - 1);
        out("static void %s_%d(const sh_real *par, size_t KP, const sh_real *in, sh_real *out, size_t K)\n{\n",
            mname[meth], n);
        out("    (void)KP;\n");
    } else {
        /* par as in C; the vector at x[b..], y[b..] (the convention's buffers) */
        out("// %s, order %d (bands 0..%d)\n", mlabel[meth], n, n - 1);
        out("void %s_%d(float par[7], uint b)\n{\n", mname[meth], n);
    }
}

/* the inputs of band l, loaded when the band starts: every store of a band
 * comes after all loads of that band, so in == out is safe */
static void emit_loads(int l)
{
    for (int m = -l; m <= l; m++) out("        const %s %s = %s;\n", T(), nmx(l, m), ldin(l * (l + 1) + m));
}

/* ZXZXZ of one vector: out = Z(α+π) X₊₉₀ Z(β+π) X₊₉₀ Z(γ) in, band by band */
static void gen_zxzxz(int n, double *X)
{
    emit_head(M_ZXZXZ, n);
    if (n > 1) {
        out("    const %s ca1 = %s, sa1 = %s;\n", T(), ldpar(0), ldpar(1));
        out("    const %s cb1 = %s, sb1 = %s;\n", T(), ldpar(2), ldpar(3));
        out("    const %s cg1 = %s, sg1 = %s;\n", T(), ldpar(4), ldpar(5));
        emit_angles('a', n - 1);
        emit_angles('b', n - 1);
        emit_angles('g', n - 1);
    }
    out("    %s%s%s;\n", st_open(0), ldin(0), st_close());
    for (int l = 1; l < n; l++) {
        if (sh__rot_zxzxz_xplus_band(l, X)) { fprintf(stderr, "gen_rot_unrolled: X+90 band %d\n", l); exit(2); }
        char xm[32], xp[32];
        out("    { /* band %d */\n", l);
        emit_loads(l);
        /* Z(γ): x → u */
        emit_zgamma(l);
        emit_xmul(l, X, 'u', 't'); /* X₊₉₀ */
        /* Z(β+π): t → v */
        out("        const %s v_0 = t_0;\n", T());
        for (int m = 1; m <= l; m++) {
            snprintf(xp, sizeof xp, "%s", nm('t', m));
            snprintf(xm, sizeof xm, "%s", nm('t', -m));
            emit_zpair('b', m, m & 1, xp, xm, 'v', 0, l);
        }
        emit_xmul(l, X, 'v', 'w'); /* X₊₉₀ */
        /* Z(α+π): w → out */
        out("        %sw_0%s;\n", st_open(l * (l + 1)), st_close());
        for (int m = 1; m <= l; m++) {
            snprintf(xp, sizeof xp, "%s", nm('w', m));
            snprintf(xm, sizeof xm, "%s", nm('w', -m));
            emit_zpair('a', m, m & 1, xp, xm, 0, 1, l);
        }
        out("    }\n");
    }
    out("}\n\n");
}

/* Taylor of one vector (rot_taylor.c, per band with positions j = m + l):
 *   y_j = x_j + β (s_j x_{j−1} − s_{j+1} x_{j+1})                          (1)
 *   y_j = x_j (1 + bb·J²_jj) + β (s_j x_{j−1} − s_{j+1} x_{j+1})          (1.5)
 *   y_j = (1.5) + bb (q_j x_{j−2} + q_{j+2} x_{j+2})                       (2)
 * between Z(γ) and Z(α); bb = ½β²; s, J²_jj, q from the closed form of J. */
static void gen_taylor(int meth, int n)
{
    emit_head(meth, n);
    if (n > 1) {
        out("    const %s ca1 = %s, sa1 = %s;\n", T(), ldpar(0), ldpar(1));
        out("    const %s cg1 = %s, sg1 = %s;\n", T(), ldpar(4), ldpar(5));
        out("    const %s beta = %s;\n", T(), ldpar(6));
        if (meth != M_TAYLOR1) out("    const %s bb = %s * beta * beta;\n", T(), half());
        emit_angles('a', n - 1);
        emit_angles('g', n - 1);
    }
    out("    %s%s%s;\n", st_open(0), ldin(0), st_close());
    double sd[2 * MAXN + 3];
    for (int l = 1; l < n; l++) {
        const int w = 2 * l + 1;
        sh_rot_deriv_J_subdiag(l, sd); /* s_0 .. s_{w−1}, s_0 = 0 */
        sd[w] = 0;
        char xm[32], xp[32];
        out("    { /* band %d */\n", l);
        emit_loads(l);
        emit_zgamma(l);
        for (int j = 0; j < w; j++) {
            const int m = j - l;
            const double s0 = sd[j], s1 = sd[j + 1];
            const double d = -sd[j] * sd[j] - sd[j + 1] * sd[j + 1];
            const double q0 = j >= 2 ? sd[j] * sd[j - 1] : 0;
            const double q2 = j + 2 < w ? sd[j + 2] * sd[j + 1] : 0;
            out("        const %s %s = ", T(), nm('t', m));
            if (meth == M_TAYLOR1) out("%s", nm('u', m));
            else out("%s * (%s + bb * %s)", nm('u', m), one(), lit(d));
            /* β (s_j x_{j−1} − s_{j+1} x_{j+1}), zero products left out */
            const int h0 = j > 0 && s0 != 0, h1 = j + 1 < w && s1 != 0;
            if (h0 && h1)
                out(" + beta * (%s * %s - %s * %s)", lit(s0), nm('u', m - 1), lit(s1), nm('u', m + 1));
            else if (h0) out(" + beta * (%s * %s)", lit(s0), nm('u', m - 1));
            else if (h1) out(" + beta * -(%s * %s)", lit(s1), nm('u', m + 1));
            if (meth == M_TAYLOR2) {
                const int g0 = q0 != 0, g2 = q2 != 0;
                if (g0 && g2)
                    out(" + bb * (%s * %s + %s * %s)", lit(q0), nm('u', m - 2), lit(q2), nm('u', m + 2));
                else if (g0) out(" + bb * (%s * %s)", lit(q0), nm('u', m - 2));
                else if (g2) out(" + bb * (%s * %s)", lit(q2), nm('u', m + 2));
            }
            out(";\n");
        }
        out("        %st_0%s;\n", st_open(l * (l + 1)), st_close());
        for (int m = 1; m <= l; m++) {
            snprintf(xp, sizeof xp, "%s", nm('t', m));
            snprintf(xm, sizeof xm, "%s", nm('t', -m));
            emit_zpair('a', m, 0, xp, xm, 0, 1, l);
        }
        out("    }\n");
    }
    out("}\n\n");
}

/* Ivanic-Ruedenberg of one vector (rot_ivanic.c): the blocks M^l band by
 * band from band 1 (the matrix, CS signs) by the recursion, every entry a
 * local, then out_l = M^l x_l (rows summed left to right as
 * sh__rot_blocks_apply).  par = R (row-major, 9 values).  The same products
 * and sums as ivanic_step; coefficients that are exactly ±1 or 0 become a
 * copy, a negation or nothing. */
static const char *nmb(int l, int m, int n)
{
    static char b[16][48];
    static int i;
    i = (i + 1) & 15;
    snprintf(b[i], sizeof b[i], "b%d_%s%d_%s%d", l, m < 0 ? "n" : "", m < 0 ? -m : m, n < 0 ? "n" : "",
             n < 0 ? -n : n);
    return b[i];
}
static const char *nmp(int l, int s, int a, int n)
{
    static char b[16][48];
    static int i;
    i = (i + 1) & 15;
    snprintf(b[i], sizeof b[i], "P%d%c_%s%d_%s%d", l, s ? 'm' : 'p', a < 0 ? "n" : "", a < 0 ? -a : a,
             n < 0 ? "n" : "", n < 0 ? -n : n);
    return b[i];
}
/* c·(expr) with the literal c; 1 and −1 without a product; 0: nothing (returns 0) */
static int term(int first, double c, const char *expr)
{
    if (c == 0) return 0;
    if (c == 1) out(first ? "%s" : " + %s", expr);
    else if (c == -1) out(first ? "-%s" : " - %s", expr);
    else out(first ? "%s * %s" : " + %s * %s", lit(c), expr);
    return 1;
}
static void gen_ivanic(int n)
{
    emit_head(M_IVANIC, n); /* C only */
    out("    SHK_ST(out, 0, K, SHK_LD(in, 0, K));\n");
    if (n < 2) { out("}\n\n"); return; }
    /* band 1: M1[i][j] = (−1)^{i+j} R[π(i)][π(j)], π(−1, 0, 1) = (y, z, x) */
    static const int perm[3] = {1, 2, 0};
    for (int i = -1; i <= 1; i++)
        for (int j = -1; j <= 1; j++)
            out("    const shk_t %s = %sSHK_LD(par, %d, KP);\n", nmb(1, i, j), ((i + j) & 1) ? "-" : "",
                perm[i + 1] * 3 + perm[j + 1]);
    double *t = malloc(3 * (size_t)(2 * n + 1) * (2 * n + 1) * sizeof *t);
    char e1[128], e2[128], e3[256];
    for (int l = 2; l < n; l++) {
        const int w = 2 * l + 1, lp = l - 1;
        const size_t ww = (size_t)w * w;
        sh__rot_ivanic_coeffs(l, t);
        out("    /* band %d */\n", l);
        /* _iP_{an}, i = ±1: |n| < l: R_{i0} M_{an}; n = ±l: the edge formulas */
        for (int sgn = 0; sgn < 2; sgn++) {
            const int i = sgn ? -1 : 1;
            for (int a = -lp; a <= lp; a++) {
                out("    const shk_t %s = %s * %s + %s * %s;\n", nmp(l, sgn, a, -l), nmb(1, i, 1), nmb(lp, a, -lp),
                    nmb(1, i, -1), nmb(lp, a, lp));
                for (int nn = -lp; nn <= lp; nn++)
                    out("    const shk_t %s = %s * %s;\n", nmp(l, sgn, a, nn), nmb(1, i, 0), nmb(lp, a, nn));
                out("    const shk_t %s = %s * %s - %s * %s;\n", nmp(l, sgn, a, l), nmb(1, i, 1), nmb(lp, a, lp),
                    nmb(1, i, -1), nmb(lp, a, -lp));
            }
        }
        for (int m = -l; m <= l; m++) {
            const int am = m < 0 ? -m : m;
            for (int nn = -l; nn <= l; nn++) {
                const size_t ix = (size_t)(m + l) * w + (size_t)(nn + l);
                const double cu = t[ix], cv = t[ww + ix], cw = t[2 * ww + ix];
                out("    const shk_t %s = ", nmb(l, m, nn));
                int any = 0;
                if (am < l) { /* u·U, U = _0P_{mn} */
                    if (nn == -l)
                        snprintf(e1, sizeof e1, "(%s * %s + %s * %s)", nmb(1, 0, 1), nmb(lp, m, -lp), nmb(1, 0, -1), nmb(lp, m, lp));
                    else if (nn == l)
                        snprintf(e1, sizeof e1, "(%s * %s - %s * %s)", nmb(1, 0, 1), nmb(lp, m, lp), nmb(1, 0, -1), nmb(lp, m, -lp));
                    else
                        snprintf(e1, sizeof e1, "(%s * %s)", nmb(1, 0, 0), nmb(lp, m, nn));
                    any |= term(!any, cu, e1);
                }
                /* v·V */
                if (m == 0) snprintf(e2, sizeof e2, "(%s + %s)", nmp(l, 0, 1, nn), nmp(l, 1, -1, nn));
                else if (m == 1) snprintf(e2, sizeof e2, "%s", nmp(l, 0, 0, nn));
                else if (m == -1) snprintf(e2, sizeof e2, "%s", nmp(l, 1, 0, nn));
                else if (m > 1) snprintf(e2, sizeof e2, "(%s - %s)", nmp(l, 0, m - 1, nn), nmp(l, 1, -m + 1, nn));
                else snprintf(e2, sizeof e2, "(%s + %s)", nmp(l, 0, m + 1, nn), nmp(l, 1, -m - 1, nn));
                any |= term(!any, cv, e2);
                /* w·W */
                if (m != 0 && am < l - 1) {
                    if (m > 0) snprintf(e3, sizeof e3, "(%s + %s)", nmp(l, 0, m + 1, nn), nmp(l, 1, -m - 1, nn));
                    else snprintf(e3, sizeof e3, "(%s - %s)", nmp(l, 0, m - 1, nn), nmp(l, 1, -m + 1, nn));
                    any |= term(!any, cw, e3);
                }
                if (!any) out("SHK_C(0)");
                out(";\n");
            }
        }
    }
    free(t);
    /* out_l = M^l x_l */
    for (int l = 1; l < n; l++) {
        out("    { /* band %d */\n", l);
        emit_loads(l);
        for (int m = -l; m <= l; m++) {
            out("        SHK_ST(out, %d, K, ", l * (l + 1) + m);
            for (int nn = -l; nn <= l; nn++) out("%s%s * %s", nn > -l ? " + " : "", nmb(l, m, nn), nmx(l, nn));
            out(");\n");
        }
        out("    }\n");
    }
    out("}\n\n");
}


/* ---- compute shaders (--shader glsl|hlsl --method M) -----------------------
 * One file per method and language under shlab's shader convention
 * (src/lab/shader.c; docs/check-your-kernel.md): local_size_x = 64, push
 * constants {order, count, form, pad}, set 0 bindings 0 rotations, 1 inputs,
 * 2 outputs, 3 status.  The per-order functions are the C kernels' bodies
 * from the same emitter, in float; main computes the rotation's par from
 * any of the three forms and dispatches on the order. */

/* The rotation's par, in the shader: the formulas of rot_fast.c
 * (SHK_PAR_MATRIX, shk_par_quat) in float, or cos and sin of the angles. */
static const char *const shader_par =
    "// β = atan2(s, c) ∈ [0, π] for s ≥ 0, as rot_fast.c's shk_beta: Abramowitz &\n"
    "// Stegun 4.4.49 (Hastings), atan x = x(1 + a₂x² + … + a₁₆x¹⁶) + ε with\n"
    "// |ε| ≤ 2·10⁻⁸ on [0, 1], on x = min(s, |c|)/max(s, |c|), then atan x,\n"
    "// π/2 − atan x, or π minus those for c < 0.  The device's atan is not\n"
    "// used: Vulkan allows it 4096 ulp, and lavapipe's was measured several\n"
    "// ulp off, which the Taylor kernels (output error ~ l·δβ) turned into\n"
    "// errors past the fixtures' float32 tolerance.\n"
    "float beta_of(float s, float c)\n"
    "{\n"
    "    const float ac = abs(c);\n"
    "    const bool swap = s > ac;\n"
    "    const float num = swap ? ac : s, den = swap ? s : ac;\n"
    "    const float xr = den > 0.0 ? num / den : 0.0, x2 = xr * xr;\n"
    "    const float a = ((((((((0.0028662257 * x2 - 0.0161657367) * x2 + 0.0429096138) * x2 - 0.0752896400) * x2 +\n"
    "                          0.1065626393) * x2 - 0.1420889944) * x2 + 0.1999355085) * x2 - 0.3333314528) * x2 + 1.0) * xr;\n"
    "    const float t = swap ? 1.57079633 - a : a;\n"
    "    return c >= 0.0 ? t : 3.14159265 - t;\n"
    "}\n\n"
    "// par = (cos α, sin α, cos β, sin β, cos γ, sin γ, β) of R = Rz(α) Ry(β) Rz(γ)\n"
    "// (ZYZ, active; docs/CONVENTIONS.md), what the kernels above read, from\n"
    "// the rotation in any of the convention's forms (pc.form).  The formulas\n"
    "// are those of shlab's C kernels (src/rotate/rot_fast.c), in float:\n"
    "//  matrix (form 0), no trigonometric call: cβ = R22 and\n"
    "//    sβ e^{iα} = R02 + i R12,\n"
    "//    (1 + cβ) e^{i(α+γ)} = (R00 + R11) + i (R10 − R01)   (taken when cβ ≥ 0),\n"
    "//    (1 − cβ) e^{i(α−γ)} = (R11 − R00) − i (R10 + R01)   (taken when cβ < 0),\n"
    "//    γ relative to the same α, so near β = 0 or π, where α alone is\n"
    "//    ill-conditioned, its error cancels in R; at sβ = 0 exactly α = 0.\n"
    "//  quaternion (w, x, y, z) (form 1): A = w + iz = cos(β/2) e^{i(α+γ)/2},\n"
    "//    B = y − ix = sin(β/2) e^{i(α−γ)/2}: cβ = (|A|² − |B|²)/|q|²,\n"
    "//    sβ = 2|A||B|/|q|², e^{iα} = AB/(|A||B|), e^{iγ} = AB̄/(|A||B|);\n"
    "//    |B| = 0: α = 0, e^{iγ} = A²/|A|²; |A| = 0: α = 0, e^{iγ} = B̄²/|B|².\n"
    "//  ZYZ angles α, β, γ in radians (form 2): cos and sin of each.\n"
    "// β itself (read by the Taylor kernels only): the given angle, or\n"
    "// beta_of(sβ, cβ) = atan2(sβ, cβ) ∈ [0, π] from a matrix or a quaternion.\n"
    "@TAYLOR_DOC@"
    "// SHLAB_NOCS (no Condon-Shortley phase): R_nocs = S R_cs S with\n"
    "// S = diag((−1)^m) = R_sh(Rz(π)), and Rz(π) Ry(β) Rz(π) = Ry(−β): the\n"
    "// same kernels with sβ and β negated.\n"
    "// Returns false for a form it does not know.\n"
    "bool rot_par(uint k, out float par[7])\n"
    "{\n"
    "    if (pc.form == 0u) {\n"
    "        const uint o = 9u * k;\n"
    "        const float r00 = rot[o], r01 = rot[o + 1u], r02 = rot[o + 2u];\n"
    "        const float r10 = rot[o + 3u], r11 = rot[o + 4u], r12 = rot[o + 5u], r22 = rot[o + 8u];\n"
    "        const float s2 = r02 * r02 + r12 * r12, sb = sqrt(s2);\n"
    "        const bool has = s2 > 0.0;\n"
    "        const float inv = has ? 1.0 / sb : 0.0;\n"
    "        const float ca = has ? r02 * inv : 1.0, sa = r12 * inv;\n"
    "        const bool up = r22 >= 0.0;\n"
    "        const float p = up ? r00 + r11 : r11 - r00, q = up ? r10 - r01 : -(r10 + r01);\n"
    "        const float nrm = 1.0 / sqrt(p * p + q * q);\n"
    "        const float cs = p * nrm, ss = q * nrm; // e^{i(α+γ)} or e^{i(α−γ)}\n"
    "        const float t = ss * ca - cs * sa;\n"
    "        par[0] = ca; par[1] = sa; par[2] = r22; par[3] = sb;\n"
    "        par[4] = cs * ca + ss * sa; par[5] = up ? t : -t;\n"
    "@TAYLOR_ROW@"
    "        par[6] = beta_of(sb, r22);\n"
    "    } else if (pc.form == 1u) {\n"
    "        const uint o = 4u * k;\n"
    "        const float qw = rot[o], qx = rot[o + 1u], qy = rot[o + 2u], qz = rot[o + 3u];\n"
    "        const float ww = qw * qw, zz = qz * qz, xx = qx * qx, yy = qy * qy;\n"
    "        const float a2 = ww + zz, b2 = xx + yy, in2 = 1.0 / (a2 + b2);\n"
    "        const float ab = sqrt(a2 * b2);\n"
    "        const bool has = ab > 0.0;\n"
    "        const float iab = has ? 1.0 / ab : 0.0;\n"
    "        const float wy = qw * qy, zx = qz * qx, zy = qz * qy, wx = qw * qx;\n"
    "        const bool up = a2 >= b2;\n"
    "        const float dn = 1.0 / (up ? a2 : b2);\n"
    "        const float dc = (up ? ww - zz : yy - xx) * dn;\n"
    "        const float ds = (up ? qw : qx) * (up ? qz : qy) * (dn + dn);\n"
    "        par[0] = has ? (wy + zx) * iab : 1.0;\n"
    "        par[1] = (zy - wx) * iab;\n"
    "        par[2] = (a2 - b2) * in2;\n"
    "        par[3] = (ab + ab) * in2;\n"
    "        par[4] = has ? (wy - zx) * iab : dc;\n"
    "        par[5] = has ? (wx + zy) * iab : ds;\n"
    "        par[6] = beta_of(par[3], par[2]);\n"
    "    } else if (pc.form == 2u) {\n"
    "        const uint o = 3u * k;\n"
    "        const float al = rot[o], be = rot[o + 1u], ga = rot[o + 2u];\n"
    "        par[0] = cos(al); par[1] = sin(al);\n"
    "        par[2] = cos(be); par[3] = sin(be);\n"
    "        par[4] = cos(ga); par[5] = sin(ga);\n"
    "        par[6] = be;\n"
    "    } else {\n"
    "        return false;\n"
    "    }\n"
    "#ifdef SHLAB_NOCS\n"
    "    par[3] = -par[3];\n"
    "    par[6] = -par[6];\n"
    "#endif\n"
    "    return true;\n"
    "}\n\n";

static int write_shader(int meth, int N, const char *langname)
{
    const int glsl = lang == L_GLSL;
    const char *ext = glsl ? "glsl" : "hlsl";
    double *X = malloc((size_t)(2 * N + 1) * (2 * N + 1) * sizeof *X);
    char *body[MAXN + 1] = {0};
    unsigned long mults[MAXN + 1] = {0};
    if (!X) return 2;
    for (int n = 1; n <= N; n++) {
        blen = 0;
        bcap = 0;
        buf = NULL;
        out("%s", "");
        if (meth == M_ZXZXZ) gen_zxzxz(n, X);
        else gen_taylor(meth, n);
        body[n] = buf;
        mults[n] = count_mults(buf);
    }
    free(X);
    if (glsl) printf("#version 450\n");
    printf("// rot_%s.%s — GENERATED FILE, DO NOT EDIT.\n"
           "//\n"
           "// Written by tools/gen_rot_unrolled.c:\n"
           "//   build/tools/gen_rot_unrolled --shader %s --method %s --max-order %d > data/shaders/rot_%s.%s\n"
           "// (`make regen`; `make check` fails if this file differs from the output).\n"
           "//\n",
           mname[meth], ext, langname, mlabel[meth], N, mname[meth], ext);
    if (meth == M_ZXZXZ)
        printf("// SH rotation by ZXZXZ (Kautz, Sloan, Snyder, EGWR 2002; shlab's zxzxz,\n"
               "// src/rotate/rot_zxzxz.c), exact:\n"
               "//   R_sh(Rz(α)Ry(β)Rz(γ)) = Z(α+π) X₊₉₀ Z(β+π) X₊₉₀ Z(γ),\n"
               "// Z(θ) turning each pair (m, −m) by mθ, X₊₉₀ = R_sh(Rx(90°)) a constant\n"
               "// table (its non-zeros folded in as literals, computed from d^l(π/2)),\n"
               "// the +π a sign (−1)^m of the odd-m pairs.\n");
    else
        printf("// SH rotation by Křivánek et al.'s Taylor approximation (IRISA PI 1728,\n"
               "// 2005; shlab's %s, src/rotate/rot_taylor.c), NOT exact (error\n"
               "// O(β²) for taylor1 and taylor1.5, O(β³) for taylor2):\n"
               "//   R_sh ≈ Z(α) T(β) Z(γ),  T = I + βJ%s\n"
               "// with J = dR_Y/dβ at 0 (the closed form of rotation_deriv.c), per band,\n"
               "// positions j = m + l, s_j = J[m][m−1]:\n"
               "//   y_j = x_j%s + β (s_j x_{j−1} − s_{j+1} x_{j+1})%s\n",
               mlabel[meth],
               meth == M_TAYLOR1 ? "" : meth == M_TAYLOR15 ? " + (β²/2) diag(J²)" : " + (β²/2) J²",
               meth == M_TAYLOR1 ? "" : " (1 + (β²/2) J²_jj)",
               meth == M_TAYLOR2 ? "\n//         + (β²/2) (s_j s_{j−1} x_{j−2} + s_{j+2} s_{j+1} x_{j+2})" : "");
    printf("// The per-order functions are those of src/rotate/rot_unrolled_gen.h (the\n"
           "// same emitter), in float: the same operations in the same order, the\n"
           "// table values rounded to float as shlab's float kernels round them.\n"
           "//\n"
           "// shlab's shader convention (docs/check-your-kernel.md): one invocation\n"
           "// rotates vector k = gl_GlobalInvocationID.x < count of order² real\n"
           "// orthonormal SH coefficients (index l(l+1)+m; the rotation acts on\n"
           "// functions, g(s) = f(R⁻¹s)) by rotation k, given as a 3×3 matrix (row-\n"
           "// major), a quaternion (w, x, y, z) or ZYZ angles (form 0, 1, 2).  Phase:\n"
           "// Condon-Shortley (cs), or without it (nocs) when compiled with SHLAB_NOCS.\n"
           "// Orders 1..%d; another order sets status 1 (not handled), an unknown\n"
           "// form status 2.\n"
           "// Checked against shlab's golden fixtures by tests/cli/test_shaders_shlab.sh:\n"
           "//   shlab verify --fixture data/fixtures/rotation/orders_1_10%s.json \\\n"
           "//     --shader data/shaders/rot_%s.%s --abi matrix --orders 1-%d [--define SHLAB_NOCS --convention nocs]\n"
           "//\n"
           "// Multiplications per vector (counted \" * \" in each function):",
           N, meth == M_ZXZXZ ? "" : meth == M_TAYLOR1 ? "_taylor1" : meth == M_TAYLOR15 ? "_taylor1.5" : "_taylor2",
           mname[meth], ext, N);
    for (int n = 1; n <= N; n++) printf(" %d:%lu", n, mults[n]);
    printf("\n\n");
    if (glsl)
        printf("layout(local_size_x = 64) in;\n"
               "layout(push_constant) uniform Params { uint order; uint count; uint form; uint pad; } pc;\n"
               "layout(std430, set = 0, binding = 0) readonly buffer Rotations { float rot[]; };\n"
               "layout(std430, set = 0, binding = 1) readonly buffer Inputs { float x[]; };\n"
               "layout(std430, set = 0, binding = 2) writeonly buffer Outputs { float y[]; };\n"
               "layout(std430, set = 0, binding = 3) buffer Status { uint status[]; };\n\n");
    else
        printf("struct Params { uint order; uint count; uint form; uint pad; };\n"
               "[[vk::push_constant]] ConstantBuffer<Params> pc;\n"
               "[[vk::binding(0, 0)]] StructuredBuffer<float> rot;\n"
               "[[vk::binding(1, 0)]] StructuredBuffer<float> x;\n"
               "[[vk::binding(2, 0)]] RWStructuredBuffer<float> y;\n"
               "[[vk::binding(3, 0)]] RWStructuredBuffer<uint> status;\n\n");
    for (int n = 1; n <= N; n++) {
        fputs(body[n], stdout);
        free(body[n]);
    }
    /* the Taylor kernels, from a matrix with cβ < 0: γ from the third row */
    static const char *const taylor_doc =
        "// Taylor kernels, matrix with cβ < 0: e^{iγ} = (−R20 + i R21)/|(R20, R21)|\n"
        "//    (R20 = −sβ cγ, R21 = sβ sγ) instead of (c).  Z(α) T(β) Z(γ) is not a\n"
        "//    function of R alone: away from β = 0 α and γ each matter (near\n"
        "//    β = 0, T ≈ I and only α + γ does, which (b) gives well), and the third\n"
        "//    column and row give each to the relative accuracy of those entries.\n"
        "//    Through (c), γ = α − (α−γ) carried 1-2 float ulps more, which T(β)\n"
        "//    amplifies near β = π (by ~l·|T|) past the Taylor fixtures' float32\n"
        "//    tolerance (measured on lavapipe: 3.4e-6 against 3.2e-6 at\n"
        "//    β = π − 1e-9).  (c) stays the fallback when R20 = R21 = 0.\n";
    static const char *const taylor_row =
        "        const float r20 = rot[o + 6u], r21 = rot[o + 7u], h2 = r20 * r20 + r21 * r21;\n"
        "        if (!up && h2 > 0.0) {\n"
        "            const float ih = 1.0 / sqrt(h2);\n"
        "            par[4] = -r20 * ih;\n"
        "            par[5] = r21 * ih;\n"
        "        }\n";
    for (const char *c = shader_par; *c;) {
        if (!strncmp(c, "@TAYLOR_ROW@", 12)) fputs(meth == M_ZXZXZ ? "" : taylor_row, stdout), c += 12;
        else if (!strncmp(c, "@TAYLOR_DOC@", 12)) fputs(meth == M_ZXZXZ ? "" : taylor_doc, stdout), c += 12;
        else putchar(*c++);
    }
    if (glsl) printf("void main()\n{\n    const uint k = gl_GlobalInvocationID.x;\n");
    else printf("[numthreads(64, 1, 1)]\nvoid main(uint3 id : SV_DispatchThreadID)\n{\n    const uint k = id.x;\n");
    printf("    if (k >= pc.count) return;\n"
           "    if (pc.order < 1u || pc.order > %du) {\n"
           "        status[k] = 1u;\n"
           "        return;\n"
           "    }\n"
           "    float par[7];\n"
           "    if (!rot_par(k, par)) {\n"
           "        status[k] = 2u;\n"
           "        return;\n"
           "    }\n"
           "    const uint b = k * pc.order * pc.order;\n"
           "    switch (pc.order) {\n",
           N);
    for (int n = 1; n <= N; n++) printf("    case %du: %s_%d(par, b); break;\n", n, mname[meth], n);
    printf("    default: break;\n    }\n}\n");
    return 0;
}

int main(int argc, char **argv)
{
    /* --max-order N: zxzxz and the Taylor kernels; --ivanic-max-order NI
     * (≤ N): ivanic, whose straight-line code grows like n⁴ and is slower
     * than the loop kernel once it outgrows the instruction cache (measured:
     * README "Rotation speed") */
    int N = 10, NI = 6;
    const char *shader = NULL, *method = NULL;
    for (int i = 1; i < argc; i++) {
        if (i + 1 < argc && !strcmp(argv[i], "--max-order")) N = atoi(argv[++i]);
        else if (i + 1 < argc && !strcmp(argv[i], "--ivanic-max-order")) NI = atoi(argv[++i]);
        else if (i + 1 < argc && !strcmp(argv[i], "--shader")) shader = argv[++i];
        else if (i + 1 < argc && !strcmp(argv[i], "--method")) method = argv[++i];
        else {
            fprintf(stderr, "usage: gen_rot_unrolled [--max-order N] [--ivanic-max-order NI]   (1 <= NI <= N <= %d)\n"
                            "       gen_rot_unrolled --shader glsl|hlsl --method zxzxz|taylor1|taylor1.5|taylor2 [--max-order N]\n",
                    MAXN);
            return 2;
        }
    }
    /* a compute shader: one method, one language, orders 1..N */
    if (shader || method) {
        int meth = -1;
        for (int m = 0; method && m < M_IVANIC; m++)
            if (!strcmp(method, mlabel[m])) meth = m;
        if (!shader || (strcmp(shader, "glsl") && strcmp(shader, "hlsl")) || meth < 0 || N < 1 || N > MAXN) {
            fprintf(stderr, "gen_rot_unrolled: --shader glsl|hlsl needs --method zxzxz|taylor1|taylor1.5|taylor2 and 1 <= --max-order <= %d\n", MAXN);
            return 2;
        }
        lang = strcmp(shader, "glsl") ? L_HLSL : L_GLSL;
        return write_shader(meth, N, shader);
    }
    if (N < 1 || N > MAXN || NI < 1 || NI > N) {
        fprintf(stderr, "gen_rot_unrolled: need 1 <= --ivanic-max-order <= --max-order <= %d\n", MAXN);
        return 2;
    }
    double *X = malloc((size_t)(2 * N + 1) * (2 * N + 1) * sizeof *X);
    char **body = calloc((size_t)M_N * (N + 1), sizeof *body);
    unsigned long mults[M_N][MAXN + 1] = {{0}};
    if (!X || !body) return 2;
    for (int meth = 0; meth < M_N; meth++)
        for (int n = 1; n <= (meth == M_IVANIC ? NI : N); n++) {
            blen = 0;
            bcap = 0;
            buf = NULL;
            out("%s", "");
            if (meth == M_ZXZXZ) gen_zxzxz(n, X);
            else if (meth == M_IVANIC) gen_ivanic(n);
            else gen_taylor(meth, n);
            body[meth * (N + 1) + n] = buf;
            mults[meth][n] = count_mults(buf);
        }
    char cmd[96];
    snprintf(cmd, sizeof cmd, "gen_rot_unrolled --max-order %d --ivanic-max-order %d", N, NI);
    printf("/* rot_unrolled_gen.h — GENERATED FILE, DO NOT EDIT.\n"
           " *\n"
           " * Written by tools/gen_rot_unrolled.c:\n"
           " *   build/tools/%s > src/rotate/rot_unrolled_gen.h\n"
           " * (`make regen`; `make check` fails if this file differs from the output).\n"
           " *\n"
           " * Straight-line SH rotation kernels, one per method and order, for one\n"
           " * rotation and one vector, or for SIMD lanes of rotations/vectors\n"
           " * (shk_t, rot_simd.h).  par = (cos α, sin α, cos β, sin β, cos γ, sin γ, β)\n"
           " * (ivanic: the matrix R, row-major) with lane stride KP; in, out: order²\n"
           " * coefficients with lane stride K.\n"
           " * The multiple angles are computed inside (Chebyshev); see the generator\n"
           " * for how the code relates to the loop kernels.\n"
           " *\n"
           " * Multiplications per call (counted \" * \" in each function):\n",
           cmd);
    for (int meth = 0; meth < M_N; meth++) {
        printf(" *   %-10s", mlabel[meth]);
        for (int n = 1; n <= (meth == M_IVANIC ? NI : N); n++) printf(" %d:%lu", n, mults[meth][n]);
        printf("\n");
    }
    printf(" */\n\n#define SH_UNROLLED_MAX_ORDER %d\n\n", N);
    for (int meth = 0; meth < M_N; meth++)
        for (int n = 1; n <= (meth == M_IVANIC ? NI : N); n++) {
            fputs(body[meth * (N + 1) + n], stdout);
            free(body[meth * (N + 1) + n]);
        }
    /* the table of counts and of functions, per method and order (the
     * including file defines SHK_FN_T, the function pointer type, and
     * SH__FAST_MAXO ≥ N) */
    printf("/* multiplications per call (the banner's numbers) */\n"
           "static const unsigned unrolled_mults[%d][SH__FAST_MAXO + 1] = {\n",
           M_N);
    for (int meth = 0; meth < M_N; meth++) {
        printf("    {0");
        for (int n = 1; n <= (meth == M_IVANIC ? NI : N); n++) printf(", %lu", mults[meth][n]);
        printf("}, /* %s */\n", mlabel[meth]);
    }
    printf("};\n\n");
    printf("static const SHK_FN_T unrolled_table[%d][SH__FAST_MAXO + 1] = {\n", M_N);
    for (int meth = 0; meth < M_N; meth++) {
        printf("    {0");
        for (int n = 1; n <= (meth == M_IVANIC ? NI : N); n++) printf(", %s_%d", mname[meth], n);
        printf("},\n");
    }
    printf("};\n");
    free(body);
    free(X);
    return 0;
}
