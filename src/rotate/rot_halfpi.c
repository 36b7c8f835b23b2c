/* rot_halfpi.c — the `halfpi` method: every band rotated through d^l(π/2),
 * which is generated band by band from a closed-form seed row, O(l²) time
 * and O(l) memory per band (precision-generic, see rot_real.h).  Nothing is
 * kept between bands or between rotations: bands are independent, so the
 * all-band rotation streams with no memory beyond the vectors and runs on
 * threads across bands (rotation_stream.c).
 *
 * References
 *  [1] S. Trapani, J. Navaza, "Calculation of spherical harmonics and Wigner d
 *      functions by FFT", Acta Cryst. A 62 (2006) 262: d(β) = Δ e^{−ikβ} Δ
 *      with Δ = d(π/2), and Δ by a recursion.  The recursion used here is the
 *      three-term one in m' at fixed m (the J± relation at β = π/2), run
 *      downward from the closed-form row m' = l (the stable direction, see
 *      below), as in rot_zxzxz.c.
 *  [2] J. Kautz, P.-P. Sloan, J. Snyder, EGWR 2002 (the ZXZXZ decomposition,
 *      which is the same factorisation written with real X±90 blocks).
 *  [3] T. Risbo, J. Geodesy 70 (1996) 383; N. A. Gumerov, R. Duraiswami,
 *      "Recursive computation of spherical harmonic rotation coefficients of
 *      large degree" (2015): stability of Wigner-d recursions at large l.
 *  [4] Edmonds (4.1.23), as in rot_wigner.c, for d^l_{l,m}(π/2).
 *
 * The factorisation.  With Ry(β) = Rz(−90°) Ry(−90°) Rz(β) Ry(90°) Rz(90°)
 * (Ry(β) = Rx(−90°) Rz(β) Rx(90°) and Rx(θ) = Rz(−90°) Ry(θ) Rz(90°), see
 * rot_zxzxz.c), D(Rz(θ)) = diag(e^{−imθ}), d(−θ) = d(θ)ᵀ:
 *   d_{m'm}(β) = i^{m'−m} Σ_k Δ_{km'} Δ_{km} e^{−ikβ},   Δ = d^l(π/2).       (F)
 * Δ restricted to m', m ≥ 0 (written Δ⁺, (l+1)² values) determines all of Δ:
 *   Δ_{mk} = (−1)^{m−k} Δ_{km},  Δ_{k,−m} = (−1)^{l+k} Δ_{km},
 *   Δ_{−k,m} = (−1)^{l+m} Δ_{km}                                          (S)
 * and by the first of (S) only its lower triangle, the "wedge" m ≤ k
 * ((l+1)(l+2)/2 values, an eighth of the (2l+1)² of d), is generated.
 *
 * The band rotation in real arithmetic (derived from (F), (S) and the real
 * basis y^{±m} = (Y^m ± (−1)^m Y^{−m})/(√2 or i√2), CS phase): with the
 * coefficients c_m = x_m, s_m = x_{−m} (m > 0) of band l, σ_m = (−1)^⌊m/2⌋
 * and w_0 = ½, w_k = 1 (k > 0),
 *   A  Z(γ):  c'_m = c_m cos mγ − s_m sin mγ,  s'_m = c_m sin mγ + s_m cos mγ;
 *             zc_m = σ_m √2 c'_m, zs_m = σ_m √2 s'_m (m > 0), zc_0 = c_0, zs_0 = 0.
 *   3 for k = 0..l, with z = zc if k ≡ l (mod 2) else zs:
 *             E_k = Σ_{m even} Δ_{km} z_m,  O_k = Σ_{m odd} Δ_{km} z_m;
 *             t_k = E_k − i O_k (k ≡ l),  t_k = −O_k − i E_k (k ≢ l).
 *   B  t'_k = e^{−ikβ} t_k = ρ_k + i ι_k.
 *   5 for m' = 0..l:  U_{m'} = Σ_{k ≡ l} w_k Δ_{km'} (ρ_k if m' even, ι_k if odd),
 *                     V_{m'} = Σ_{k ≢ l} w_k Δ_{km'} (ι_k if m' even, ρ_k if odd);
 *             (R, I) = (U, V) for even m', (V, U) for odd m';
 *             a''_{m'} = 2 i^{m'} (R + i I).
 *   D  b = e^{−im'α} a'';  out c''_{m'} = √2 Re b, s''_{m'} = −√2 Im b (m' > 0),
 *             c''_0 = Re b_0.
 * (t_{−k} = (−1)^k conj(t_k) folds the negative k into the w_k-weighted sums.)
 * Stages 3 and 5 are each one pass over Δ⁺ ((l+1)² multiply-adds); over the
 * wedge, entry Δ_{rc} (c < r) serves both as (k, m) = (r, c) and, by (S), as
 * (c, r): in each stage a wedge row is one dot product and one axpy, whose
 * even and odd columns go to different sums.  Stage 5 needs every t'_k
 * first, so the wedge is generated a second time for it rather than stored
 * (64 MB a band at l = 4000; O(l) scratch instead of O(l²)).  Both stages
 * run over column blocks (hp_cols, rot_halfpi_cols.h): the recursion is
 * column by column, so a block of 32 columns (doubles) is generated down its
 * rows in registers, 64 rows at a time into a small buffer, and every job
 * (vector and rotation of a batch) takes those rows with its axpy
 * accumulators for the block in registers and its dot's partial sums in one
 * 8-lane vector a row: per element, a store and a load of the buffer
 * instead of three rows read and one written per pass.  Cost per band and
 * vector: 2(l+1)² multiply-adds (a multiply and an add each), like ZXZXZ's
 * two X products, plus 2·3·(l+1)²/2 flops (2 multiplies, 1 subtract an
 * element) for the two generations of Δ, shared by all vectors and rotations
 * of a batch.  A block's rows while all its entries are below HP_TINY
 * (beyond the turning point m² + r² ≈ l², where Δ decays like an Airy
 * function) are skipped by both stages.
 *
 * Generating Δ⁺ (the wedge, row r = m' from l down to 0, all m ≤ r at once):
 *   Δ_{l,m} = (−1)^{l−m} √C(2l, l+m) / 2^l                                  ([4])
 *     e_0² = Π_{k=1..l} (2k−1)/(2k),  e_m = e_{m−1} √((l−m+1)/(l+m)), in long
 *     double (relative error ~ l·5e-20);
 *   Δ_{r,m} = (2m Δ_{r+1,m} − B_{r+2} Δ_{r+2,m}) / B_{r+1},
 *     B_j = √((l+j)(l−j+1))  (B_{l+1} = 0)                                   ([1])
 *   the J± relation √((l−m')(l+m'+1)) d_{m'+1,m} + √((l+m')(l−m'+1)) d_{m'−1,m}
 *   = 2m d_{m'm} at cosβ = 0.  Downward in m' each column goes from the
 *   classically forbidden region (m² + m'² > l², where the wanted solution
 *   grows in the direction of the recursion) into the oscillatory one: the
 *   stable direction.  It runs on y_r = Δ_r·P_r, P_r = Π_{j=r+1..l} B_j:
 *     y_r = 2m y_{r+1} − B_{r+2}² y_{r+2},
 *   integer coefficients (exact), two multiplies and a subtract an element;
 *   the stages multiply each row's sums and factors by rs_r = 1/P_r (O(1) a
 *   row; P_r from P_r² in long double, divided by 2^HP_ROW_EXP, rows and
 *   P alike, when it grows past it).  Measured against the recursion above
 *   in binary128 the wedge is within 4.7e-16 (absolute) at l = 1000 (with
 *   the recursion on Δ itself, 3 multiplies an element: 7.1e-16).
 * Underflow: the seeds go down to 2^−l (m = l), below double's range for
 * l > 1022.  A column whose seed is below 2^HP_LOW_EXP is carried scaled:
 * the recursion keeps mantissa · 2^{kexp[m]} (the seed's mantissa, kexp =
 * −exponent), divides by 2^HP_RESCALE_EXP whenever it grows past it, and the
 * wedge receives value · 2^−kexp (0 while kexp > HP_FLUSH_K, i.e. while every
 * value of the column is below 2^−600: negligible next to the O(1) entries).
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

#include <stdlib.h>
#include <string.h>

SH__ROT_DECLARE_BLOCKS(halfpi);
SH__ROT_DECLARE_APPLY(halfpi);

#ifdef SH_REAL_FLOAT
#define HP_LOW_EXP (-60)
#define HP_RESCALE_EXP 30
#define HP_FLUSH_K 90
#define HP_ROW_EXP 60
#define HP_CHECK_MASK 0 /* the scaled columns checked every row */
#else
#define HP_LOW_EXP (-600)
#define HP_RESCALE_EXP 400
#define HP_FLUSH_K 1000
#define HP_ROW_EXP 400
#define HP_CHECK_MASK 7 /* every 8 rows */
#endif

/* One vector of HP_VBYTES: NL lanes (4 doubles or 8 floats), columns c,
 * c+1, … alternately even and odd (the stages' column blocks have their own
 * vectors, rot_halfpi_cols.h).  Lane arithmetic is defined element by
 * element (and ISO C mode keeps the compiler from contracting a·b + c into
 * an FMA), so the result does not depend on the instructions used: the
 * hot functions are compiled for AVX-512, AVX2 and the baseline
 * (HP_CLONES, chosen at load time) and all give the same bits. */
#define HP_VBYTES 32
#define NL ((int)(HP_VBYTES / sizeof(sh_real)))
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi" /* only inline helpers pass these vectors */
typedef sh_real SH_R(hp_v) __attribute__((vector_size(HP_VBYTES)));
#define VR SH_R(hp_v)
#define HP_INLINE static inline __attribute__((always_inline))
HP_INLINE VR SH_R(hp_ld)(const sh_real *p)
{
    VR v;
    memcpy(&v, p, sizeof v);
    return v;
}
HP_INLINE void SH_R(hp_st)(sh_real *p, VR v) { memcpy(p, &v, sizeof v); }
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define HP_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define HP_CLONES
#endif

/* The stages run over column blocks of HP_W columns (256 bytes), HP_R rows
 * at a time, a row's partial sums in HP_AL lanes (64 bytes) (hp_cols). */
#define HP_W ((int)(256 / sizeof(sh_real)))
#define HP_AL ((int)(64 / sizeof(sh_real)))
#define HP_R 64

/* HP_TINY: see hp_cols */
#ifdef SH_REAL_FLOAT
#define HP_TINY 0x1p-45f
typedef int32_t SH_R(hp_vi) __attribute__((vector_size(HP_VBYTES)));
#define HP_ABSMASK 0x7fffffff
#else
#define HP_TINY 0x1p-90
typedef int64_t SH_R(hp_vi) __attribute__((vector_size(HP_VBYTES)));
#define HP_ABSMASK 0x7fffffffffffffffLL
#endif

/* ---- scratch ------------------------------------------------------------ */
/* Per band l ≤ L and nj ≤ J jobs: three wedge rows, three recursion rows,
 * B², 2m, the row factors and thresholds, the column scales, the seed row
 * (values, mantissas, scales), ten per-job vectors, kexp and the seed's, the
 * row rescale flags: O(l), either precision. */
#ifndef SH_REAL_FLOAT
static size_t hp_nreal(int L, int J)
{
    const size_t n = (size_t)L + 1;
    /* per job: ten vectors padded to whole column blocks (≤ n + 64 reals of
     * either precision) and the dot's partial sums (64 bytes a row); the
     * block buffer: HP_R rows of 256 bytes (see hp_cols) */
    return 3 * n + 3 * n + (n + 1) + 2 * n + 2 * n + 3 * n + (10 * (n + 64) + 8 * n) * (size_t)J + 2048 + 16;
}
size_t sh__rot_halfpi_work_bytes(int L, int J)
{
    return hp_nreal(L, J) * sizeof(double) + 3 * ((size_t)L + 1) * sizeof(int) + 64;
}
#endif

typedef struct {
    int l, ms;          /* band; first scaled column (l+1: none) */
    sh_real *w[3];      /* wedge rows (true values) by r mod 3 */
    sh_real *rec[3];    /* recursion rows of the scaled columns, by r mod 3 */
    sh_real *C;         /* B_j² = (l+j)(l−j+1), j = 0..l+1 (integers) */
    sh_real *twom;      /* 2m */
    sh_real *rs, *tau;  /* row r: Δ = rs[r]·(stored value); HP_TINY / rs[r] */
    int *resc;          /* resc[r]: rows r+1, r+2 divided by 2^HP_ROW_EXP before row r */
    sh_real *scale;     /* 2^−kexp[m] (0: flushed) */
    int *kexp;
    sh_real *sw, *sx, *ssc; /* the seed row (hp_init): w, rec, scale of row l */
    int *skexp;             /* and kexp */
    sh_real *buf;       /* hp_cols' block of rows */
    sh_real *job;       /* per-job vectors */
    size_t np, js;      /* their length (n padded to whole blocks), a job's stride */
} SH_R(hp_gen);
#define HPGEN SH_R(hp_gen)

static void SH_R(hp_layout)(int l, int nj, void *work, HPGEN *g)
{
    const size_t n = (size_t)l + 1;
    sh_real *p = work;
    g->l = l;
    g->w[0] = p, p += n;
    g->w[1] = p, p += n;
    g->w[2] = p, p += n;
    g->rec[0] = p, p += n;
    g->rec[1] = p, p += n;
    g->rec[2] = p, p += n;
    g->C = p, p += n + 1;
    g->twom = p, p += n;
    g->rs = p, p += n;
    g->tau = p, p += n;
    g->scale = p, p += n;
    g->sw = p, p += n;
    g->sx = p, p += n;
    g->ssc = p, p += n;
    g->buf = p, p += HP_R * HP_W;
    g->np = (n + HP_W - 1) / HP_W * HP_W;
    g->js = 10 * g->np + HP_AL * n;
    g->job = p, p += g->js * (size_t)nj;
    g->kexp = (int *)(p + 1);
    g->skexp = g->kexp + n;
    g->resc = g->skexp + n;
}

/* The seed row Δ_{l,m} (long double, [4]) into sw, sx, ssc, skexp, and the
 * recursion coefficients: once per band (both generations start from it,
 * hp_start). */
static void SH_R(hp_init)(HPGEN *g)
{
    const int l = g->l;
    sh_real *w0 = g->sw;
    long double e2 = 1;
    int k = 1;
    for (; k + 3 <= l; k += 4) { /* four factors at once: numerator and denominator exact (< 2^53) */
        const long double a = (long double)((2.0 * k - 1) * (2.0 * k + 1)) * (long double)((2.0 * k + 3) * (2.0 * k + 5));
        const long double b = (long double)((2.0 * k) * (2.0 * k + 2)) * (long double)((2.0 * k + 4) * (2.0 * k + 6));
        e2 *= a / b;
    }
    for (; k <= l; k++) e2 *= (long double)(2 * k - 1) / (2 * k);
    long double e = sqrtl(e2);
    const long double low = ldexpl(1.0L, HP_LOW_EXP - 1);
    g->ms = l + 1;
    for (int m = 0; m <= l; m++) {
        if (m) e *= sqrtl((long double)(l - m + 1) / (l + m));
        const long double v = ((l - m) & 1) ? -e : e;
        g->twom[m] = (sh_real)(2 * m);
        /* frexpl's exponent ≥ HP_LOW_EXP  ⟺  |v| ≥ 2^(HP_LOW_EXP−1) */
        if (g->ms > l && e >= low) {
            w0[m] = (sh_real)v;
            g->sx[m] = 0;
            g->skexp[m] = 0;
            g->ssc[m] = 1;
        } else { /* seeds decrease with m: every later column is scaled too */
            int ex;
            const long double f = frexpl(v, &ex);
            if (g->ms > l) g->ms = m;
            g->skexp[m] = -ex;
            g->ssc[m] = g->skexp[m] > HP_FLUSH_K ? 0 : (sh_real)ldexp(1.0, -g->skexp[m]);
            g->sx[m] = (sh_real)f;
            w0[m] = (sh_real)f * g->ssc[m];
        }
    }
    for (int j = 0; j <= l + 1; j++) g->C[j] = (sh_real)((double)(l + j) * (double)(l - j + 1));
    /* the row factors: P_r = Π_{j=r+1..l} B_j · 2^{−HP_ROW_EXP·(rescales so
     * far)}, P_l = 1, from Q = P² in long double (times the integers B_j²:
     * relative error ≲ l·5e-20), then rs = 1/√Q in double (≲ 1.5 ulp) */
    long double Q = 1;
    const long double big2 = ldexpl(1.0L, 2 * HP_ROW_EXP), down2 = ldexpl(1.0L, -2 * HP_ROW_EXP);
    g->rs[l] = 1;
    g->tau[l] = HP_TINY;
    g->resc[l] = 0;
    for (int r = l - 1; r >= 0; r--) {
        g->resc[r] = Q > big2;
        if (g->resc[r]) Q *= down2;
        Q *= (long double)(l + r + 1) * (long double)(l - r);
        const double P = sqrt((double)Q);
        g->rs[r] = (sh_real)(1 / P);
        g->tau[r] = (sh_real)(HP_TINY * P);
    }
}

/* The generator at row l again (the seed row of hp_init, row l+1 zero). */
static void SH_R(hp_start)(HPGEN *g)
{
    const int l = g->l;
    const size_t n = (size_t)l + 1, ns = n - (size_t)g->ms;
    memcpy(g->w[l % 3], g->sw, n * sizeof(sh_real));
    memset(g->w[(l + 1) % 3], 0, n * sizeof(sh_real)); /* row l+1 */
    memcpy(g->rec[l % 3] + g->ms, g->sx + g->ms, ns * sizeof(sh_real));
    memset(g->rec[(l + 1) % 3] + g->ms, 0, ns * sizeof(sh_real));
    memcpy(g->scale, g->ssc, n * sizeof(sh_real));
    memcpy(g->kexp, g->skexp, n * sizeof(int));
}

/* out[m] = 2m·x1[m] − c·x2[m] for m in [m0, m1): the recursion, a vector
 * at a time (the same operations on every column). */
HP_INLINE void SH_R(hp_rec3)(int m0, int m1, const sh_real *tm, const sh_real *x1,
                             const sh_real *x2, sh_real c, sh_real *out)
{
    VR vc;
    for (int i = 0; i < NL; i++) vc[i] = c;
    int m = m0;
    for (; m + NL <= m1; m += NL)
        SH_R(hp_st)(out + m, SH_R(hp_ld)(tm + m) * SH_R(hp_ld)(x1 + m) - vc * SH_R(hp_ld)(x2 + m));
    for (; m < m1; m++) out[m] = tm[m] * x1[m] - c * x2[m];
}

/* x[m] *= f for m in [0, n) */
HP_INLINE void SH_R(hp_scal)(int n, sh_real f, sh_real *x)
{
    VR vf;
    for (int i = 0; i < NL; i++) vf[i] = f;
    int m = 0;
    for (; m + NL <= n; m += NL) SH_R(hp_st)(x + m, SH_R(hp_ld)(x + m) * vf);
    for (; m < n; m++) x[m] *= f;
}

/* Wedge row r < l from rows r+1 and r+2 (row l+1 is zero). */
HP_INLINE void SH_R(hp_row)(HPGEN *g, int r)
{
    const int nu = r + 1 < g->ms ? r + 1 : g->ms; /* unscaled columns 0..nu−1 */
    sh_real *w = g->w[r % 3];
    const sh_real c = g->C[r + 2];
    if (g->resc[r]) { /* rows r+1, r+2 (the columns still needed, 0..r) / 2^HP_ROW_EXP */
        const sh_real down = (sh_real)ldexp(1.0, -HP_ROW_EXP);
        SH_R(hp_scal)(nu, down, g->w[(r + 1) % 3]);
        SH_R(hp_scal)(nu, down, g->w[(r + 2) % 3]);
        for (int m = nu; m <= r; m++) { /* scaled columns: the exponent only */
            g->kexp[m] += HP_ROW_EXP;
            g->scale[m] = g->kexp[m] > HP_FLUSH_K ? 0 : g->scale[m] * down;
        }
    }
    /* Δ_{r,m} = (2m Δ_{r+1,m} − B_{r+2} Δ_{r+2,m}) / B_{r+1}, on the values
     * y_r = Δ_r·P_r (hp_init): y_r = 2m y_{r+1} − B_{r+2}² y_{r+2} */
    SH_R(hp_rec3)(0, nu, g->twom, g->w[(r + 1) % 3], g->w[(r + 2) % 3], c, w);
    if (nu > r) return;
    /* scaled columns ms..r: the same recursion on the mantissas */
    sh_real *x = g->rec[r % 3];
    SH_R(hp_rec3)(nu, r + 1, g->twom, g->rec[(r + 1) % 3], g->rec[(r + 2) % 3], c, x);
    /* a row grows by at most ~2√(2l)·B_{r+1} < 2^19.5 (l < 4097), so a check
     * every HP_CHECK_MASK+1 rows keeps the mantissas below
     * 2^(HP_RESCALE_EXP + 160) (double; float: 2^(HP_RESCALE_EXP + 20)),
     * far from overflow */
    if (!(r & HP_CHECK_MASK)) {
        const sh_real lim = (sh_real)ldexp(1.0, HP_RESCALE_EXP), down = (sh_real)ldexp(1.0, -HP_RESCALE_EXP);
        sh_real *y1 = g->rec[(r + 1) % 3];
        for (int m = nu; m <= r; m++)
            if (SH_FABS(x[m]) > lim) {
                x[m] *= down, y1[m] *= down;
                g->kexp[m] -= HP_RESCALE_EXP;
                g->scale[m] = g->kexp[m] > HP_FLUSH_K ? 0 : (sh_real)ldexp(1.0, -g->kexp[m]);
            }
    }
    int m = nu;
    for (; m + NL <= r + 1; m += NL)
        SH_R(hp_st)(w + m, SH_R(hp_ld)(x + m) * SH_R(hp_ld)(g->scale + m));
    for (; m <= r; m++) w[m] = x[m] * g->scale[m];
}

/* ---- the stages' column blocks -------------------------------------------- */
/* Stages 3 and 5 have one form: over the wedge, row r (values y = Δ_r/rs[r])
 * gives a dot product with z_q (q = r mod 2), whose even and odd columns are
 * summed apart, and an axpy T_q[c] += y_c·(kp[2r] for even c, kp[2r+1] for odd c);
 * the diagonal c = r goes to the dot (stage 3) or to the axpy (stage 5).
 * They run over blocks of HP_W columns: a block's recursion (every column
 * has its own, hp_init) runs from row l down to its first column, HP_R rows
 * at a time into g->buf, in registers; then every job takes those rows,
 * its axpy accumulators for the block's columns in registers and the dot's
 * partial sums in acc (NL lanes a row, one vector added per block).  Memory
 * traffic per element is the buffer's store and load, instead of three rows
 * read and one written per pass; the per-job arithmetic is the same whatever
 * nj, so a job's bits do not depend on its batch (nor on threads).
 * Skipped: a block's first rows while all its entries are below HP_TINY
 * (the classically forbidden region near r = l, where Δ grows downward; the
 * flushed scaled columns are 0): changes a stage's sums by less than
 * l·HP_TINY·max|z| (≤ 1e-23 relative). */
typedef struct {
    const sh_real *z[2];    /* the dot's inputs for even, odd r */
    sh_real *T[2];          /* the axpy's targets for even, odd r */
    const sh_real *kp;      /* its factors, row r: kp[2r] (even columns), kp[2r+1] (odd) */
    sh_real *acc;           /* the dot's partial sums, HP_AL a row */
} SH_R(hp_job);
#define HPJOB SH_R(hp_job)

/* Job j's ten vectors: zc (hE), zs (hO), E, O, GE, GO, U, V, kp (two: 2n
 * values, and up to HP_AL − 2 past them read but not used); acc. */
#define HP_JV(g, j, i) ((g)->job + (g)->js * (size_t)(j) + (g)->np * (size_t)(i))

#define HPC_VB 64
#define HPC(x) SH_R(hp_##x##_w)
#include "rotate/rot_halfpi_cols.h"
#undef HPC
#undef HPC_VB
#define HPC_VB 32
#define HPC(x) SH_R(hp_##x##_n)
#include "rotate/rot_halfpi_cols.h"
#undef HPC
#undef HPC_VB
#define HPC_VB 16
#define HPC(x) SH_R(hp_##x##_s)
#include "rotate/rot_halfpi_cols.h"
#undef HPC
#undef HPC_VB

/* Which instance of rot_halfpi_cols.h fits the registers: 64-byte vectors
 * with AVX-512, 32 with AVX2, else 16 (SSE2, NEON); all give the same bits. */
HP_INLINE uint64_t SH_R(hp_cols)(HPGEN *g, int nj, const HPJOB *J, int st5)
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    if (__builtin_cpu_supports("avx512f")) return SH_R(hp_cols_w)(g, nj, J, st5);
    if (__builtin_cpu_supports("avx2")) return SH_R(hp_cols_n)(g, nj, J, st5);
#endif
    return SH_R(hp_cols_s)(g, nj, J, st5);
}

/* The dot's sums of row r (even, odd columns) from acc. */
HP_INLINE void SH_R(hp_sums)(const sh_real *acc, int r, sh_real *se, sh_real *so)
{
    sh_real e = 0, o = 0;
    for (int i = 0; i < HP_AL; i += 2) e += acc[(size_t)HP_AL * r + i], o += acc[(size_t)HP_AL * r + i + 1];
    *se = e;
    *so = o;
}

/* ---- the band kernel ------------------------------------------------------ */
/* The stages of sh__rot_halfpi_band (the letters and numbers of the header
 * comment), each over every job; inlined (HP_INLINE) so that every clone of
 * the kernel (HP_CLONES) compiles them for its instruction set.  Job j keeps
 * its vectors at HP_JV (zc, zs, E, O, GE, GO, U, V, kp; stage B
 * overwrites zc, zs with hE, hO).  Each returns its multiplications. */

/* A: Z(γ), σ, √2 into zc, zs; E and O cleared. */
HP_INLINE uint64_t SH_R(hp_stage_a)(HPGEN *g, int nocs, int nj, const sh_real *const *cs, int M,
                                    const sh_real *const *in)
{
    const int l = g->l;
    const sh_real r2 = SH_SQRT((sh_real)2);
    uint64_t count = 0;
    for (int j = 0; j < nj; j++) {
        sh_real *zc = HP_JV(g, j, 0), *zs = HP_JV(g, j, 1);
        const sh_real *x = in[j] + l, *csg = cs[j] + 4 * (size_t)(M + 1);
        memset(zc, 0, g->js * sizeof *zc); /* the padding too */
        const sh_real fl = nocs ? -1 : 1;
        zc[0] = x[0];
        zs[0] = 0;
        for (int m = 1; m <= l; m++) {
            const sh_real f = (m & 1) ? fl : 1, c = f * x[m], s = f * x[-m];
            const sh_real cm = csg[2 * m], sm = csg[2 * m + 1], sg = (m & 2) ? -r2 : r2;
            zc[m] = sg * (c * cm - s * sm);
            zs[m] = sg * (c * sm + s * cm);
        }
        count += 6u * (uint64_t)l;
    }
    return count;
}

/* 3: the wedge generated (rows l..0, hp_cols), its dot products into E, O:
 * (k, m) = (r, c): the dot into E_r, O_r; (k, m) = (c, r), c < r, by (S):
 * (−1)^{r−c} Δ_{rc} z^{(c)}_r into E_c (r even) or O_c (r odd). */
HP_INLINE uint64_t SH_R(hp_stage3)(HPGEN *g, int nj, HPJOB *J)
{
    const int l = g->l;
    const size_t n = (size_t)l + 1;
    SH_R(hp_init)(g);
    SH_R(hp_start)(g);
    for (int j = 0; j < nj; j++) {
        sh_real *zc = HP_JV(g, j, 0), *zs = HP_JV(g, j, 1), *kp = HP_JV(g, j, 8);
        const sh_real *zev = (l & 1) ? zs : zc, *zod = (l & 1) ? zc : zs;
        J[j].z[0] = (l & 1) ? zs : zc; /* z = zs for l − r odd */
        J[j].z[1] = (l & 1) ? zc : zs;
        J[j].T[0] = HP_JV(g, j, 2), J[j].T[1] = HP_JV(g, j, 3);
        J[j].kp = kp, J[j].acc = HP_JV(g, j, 10);
        for (int r = 0; r <= l; r++) {
            const sh_real sr = (r & 1) ? -g->rs[r] : g->rs[r];
            kp[2 * r] = sr * zev[r], kp[2 * r + 1] = -sr * zod[r];
        }
        memset(J[j].acc, 0, HP_AL * n * sizeof(sh_real));
    }
    uint64_t count = SH_R(hp_cols)(g, nj, J, 0);
    for (int j = 0; j < nj; j++) {
        sh_real *E = HP_JV(g, j, 2), *O = HP_JV(g, j, 3);
        for (int r = 0; r <= l; r++) {
            sh_real se, so;
            SH_R(hp_sums)(J[j].acc, r, &se, &so);
            E[r] += g->rs[r] * se;
            O[r] += g->rs[r] * so;
        }
        count += 4 * n;
    }
    return count;
}

/* B: t_k, e^{−ikβ}, and the stage-5 coefficients h (hE for even m', hO
 * for odd m', w_k included) and G = (−1)^k h (U and V: cleared by A). */
HP_INLINE uint64_t SH_R(hp_stage_b)(HPGEN *g, int nj, const sh_real *const *cs, int M)
{
    const int l = g->l;
    uint64_t count = 0;
    for (int j = 0; j < nj; j++) {
        sh_real *E = HP_JV(g, j, 2), *O = HP_JV(g, j, 3);
        sh_real *hE = HP_JV(g, j, 0), *hO = HP_JV(g, j, 1), *GE = HP_JV(g, j, 4), *GO = HP_JV(g, j, 5);
        const sh_real *csb = cs[j] + 2 * (size_t)(M + 1);
        for (int k = 0; k <= l; k++) {
            const int same = !((l - k) & 1);
            const sh_real re = same ? E[k] : -O[k], im = same ? -O[k] : -E[k];
            const sh_real cb = csb[2 * k], sb = csb[2 * k + 1], wk = k ? 1 : (sh_real)0.5;
            const sh_real rho = wk * (cb * re + sb * im), iota = wk * (cb * im - sb * re);
            hE[k] = same ? rho : iota;
            hO[k] = same ? iota : rho;
            GE[k] = (k & 1) ? -hE[k] : hE[k];
            GO[k] = (k & 1) ? -hO[k] : hO[k];
        }
        count += 6u * (uint64_t)(l + 1);
    }
    return count;
}

/* 5: the wedge generated again (rows l..0, hp_cols), its sums into U, V:
 * (k, m') = (r, c): U/V_c += Δ_{rc} h_r (the axpy, into U for l − r even);
 * (k, m') = (c, r), c < r: (−1)^{r−c} Δ_{rc} h_c into U_r (c ≡ l) or V_r
 * (c ≢ l) (the dot, with G). */
HP_INLINE uint64_t SH_R(hp_stage5)(HPGEN *g, int nj, HPJOB *J)
{
    const int l = g->l;
    const size_t n = (size_t)l + 1;
    SH_R(hp_start)(g); /* hp_init: stage 3 */
    for (int j = 0; j < nj; j++) {
        const sh_real *hE = HP_JV(g, j, 0), *hO = HP_JV(g, j, 1);
        sh_real *kp = HP_JV(g, j, 8), *U = HP_JV(g, j, 6), *V = HP_JV(g, j, 7);
        J[j].z[0] = HP_JV(g, j, 4), J[j].z[1] = HP_JV(g, j, 5);
        J[j].T[0] = (l & 1) ? V : U; /* U for l − r even */
        J[j].T[1] = (l & 1) ? U : V;
        J[j].kp = kp, J[j].acc = HP_JV(g, j, 10);
        for (int r = 0; r <= l; r++) kp[2 * r] = g->rs[r] * hE[r], kp[2 * r + 1] = g->rs[r] * hO[r];
        memset(J[j].acc, 0, HP_AL * n * sizeof(sh_real));
    }
    uint64_t count = SH_R(hp_cols)(g, nj, J, 1);
    for (int j = 0; j < nj; j++) {
        sh_real *U = HP_JV(g, j, 6), *V = HP_JV(g, j, 7);
        for (int r = 0; r <= l; r++) {
            sh_real se, so;
            const sh_real sr = (r & 1) ? -g->rs[r] : g->rs[r];
            SH_R(hp_sums)(J[j].acc, r, &se, &so);
            if (l & 1) U[r] += sr * so, V[r] += sr * se;
            else U[r] += sr * se, V[r] += sr * so;
        }
        count += 4 * n;
    }
    return count;
}

/* D: a'' = 2 i^{m'} (R + iI), b = e^{−im'α} a'', out. */
HP_INLINE uint64_t SH_R(hp_stage_d)(HPGEN *g, int nocs, int nj, const sh_real *const *cs,
                                    sh_real *const *out)
{
    const int l = g->l;
    const sh_real r2 = SH_SQRT((sh_real)2);
    uint64_t count = 0;
    for (int j = 0; j < nj; j++) {
        const sh_real *U = HP_JV(g, j, 6), *V = HP_JV(g, j, 7);
        const sh_real *csa = cs[j];
        sh_real *y = out[j] + l;
        const sh_real fl = nocs ? -1 : 1, t2 = 2 * r2;
        y[0] = 2 * U[0];
        for (int m = 1; m <= l; m++) {
            /* even m': 2σ(R + iI); odd m': 2σ(−I + iR); σ, 2 and √2 in one factor */
            const sh_real R = (m & 1) ? V[m] : U[m], I = (m & 1) ? U[m] : V[m];
            const sh_real sg = ((m & 2) ? -t2 : t2) * ((m & 1) ? fl : 1);
            const sh_real ar = (m & 1) ? -I : R, ai = (m & 1) ? R : I;
            const sh_real ca = csa[2 * m], sa = csa[2 * m + 1];
            y[m] = sg * (ca * ar + sa * ai);
            y[-m] = -sg * (ca * ai - sa * ar);
        }
        count += 6u * (uint64_t)l;
    }
    return count;
}

/* Rotate band l of nj vectors: job j has the multiple-angle table cs[j]
 * (csa = cos, sin of mα at cs[j][2m], csb = of mβ at + 2(M+1), csg = of mγ at
 * + 4(M+1); M ≥ l), input in[j] and output out[j] (2l+1 values each; out
 * may equal in).  nocs: the vectors are in the nocs convention (odd m
 * negated on the way in and out).  work: sh__rot_halfpi_work_bytes(≥ l, ≥ nj). */
HP_CLONES void SH_R(sh__rot_halfpi_band)(int l, int nocs, int nj, const sh_real *const *cs, int M,
                               const sh_real *const *in, sh_real *const *out, void *work,
                               uint64_t *mults)
{
    HPGEN g;
    SH_R(hp_layout)(l, nj, work, &g);
    HPJOB jb[16], *J = nj <= 16 ? jb : malloc((size_t)nj * sizeof *J);
    if (!J) abort(); /* callers batch at most 16 */
    uint64_t count = 0;
    count += SH_R(hp_stage_a)(&g, nocs, nj, cs, M, in); /* Z(γ), σ, √2 */
    count += SH_R(hp_stage3)(&g, nj, J);                 /* × Δ (the wedge's first generation) */
    count += SH_R(hp_stage_b)(&g, nj, cs, M);            /* e^{−ikβ} */
    count += SH_R(hp_stage5)(&g, nj, J);                 /* × Δ (the second generation) */
    count += SH_R(hp_stage_d)(&g, nocs, nj, cs, out);    /* e^{−im'α}, out */
    if (J != jb) free(J);
    if (mults) *mults += count;
}

/* d^l_{m'm}(π/2) for m', m = 0..l into d[m'(l+1) + m] (the wedge generated
 * as for a rotation, the rest by (S)).  work: sh__rot_halfpi_work_bytes(l, 0). */
HP_CLONES void SH_R(sh__rot_halfpi_delta)(int l, void *work, sh_real *d)
{
    HPGEN g;
    SH_R(hp_layout)(l, 0, work, &g);
    SH_R(hp_init)(&g);
    SH_R(hp_start)(&g);
    const int n = l + 1;
    for (int r = l; r >= 0; r--) {
        if (r < l) SH_R(hp_row)(&g, r);
        for (int c = 0; c <= r; c++) {
            const sh_real v = g.rs[r] * g.w[r % 3][c];
            d[(size_t)r * n + c] = v;
            d[(size_t)c * n + r] = ((r - c) & 1) ? -v : v;
        }
    }
}

/* ---- the method's plan interface ---------------------------------------- */
#ifndef SH_REAL_FLOAT
/* cos, sin of m·θ, m = 0..M, to within an ulp or two for any m: the product
 * m·θ is split exactly into p + e (e = fma(m, θ, −p)) and
 * cos(p + e) = cos p − e sin p, sin(p + e) = sin p + e cos p (e ≤ ulp(p)/2,
 * so e² is below rounding).  The Chebyshev recurrence of rot_blocks.c, or
 * libm of the rounded product, would be off by ~m·θ·1e-16 (3e-13 at m =
 * 1000), the size of the whole rotation's error budget at high band. */
void sh__rot_halfpi_angles(double theta, int M, double *cs)
{
    for (int m = 0; m <= M; m++) {
        const double p = (double)m * theta, e = fma((double)m, theta, -p);
        const double c = cos(p), s = sin(p);
        cs[2 * m] = c - s * e;
        cs[2 * m + 1] = s + c * e;
    }
}

/* The per-rotation table of a job: α, β, γ, or for the inverse rotation
 * Rᵀ = Z(−γ) R_Y(−β) Z(−α) the angles −γ, −β, −α (exact negations). */
void sh__rot_halfpi_set_angles(const sh_rotation *rot, int inverse, int M, double *cs)
{
    const size_t s = 2 * (size_t)(M + 1);
    sh__rot_halfpi_angles(inverse ? rot->gamma : rot->alpha, M, cs);
    sh__rot_halfpi_angles(rot->beta, M, cs + s);
    sh__rot_halfpi_angles(inverse ? rot->alpha : rot->gamma, M, cs + 2 * s);
    if (inverse)
        for (size_t i = 1; i < 3 * s; i += 2) cs[i] = -cs[i];
}
#endif

static size_t hp_state_n(int order) { return 6 * (size_t)order; }

int SH_R(sh__rot_halfpi_set)(int order, const sh_rotation *rot, const void *tables, void *state,
                             uint64_t *mults)
{
#ifdef SH_REAL_FLOAT
    /* angles in double, then rounded: the table sits at the end of the state */
    float *cs = state;
    double *tmp = (double *)((char *)state + hp_state_n(order) * sizeof(float));
    tmp = (double *)(((uintptr_t)tmp + 7) & ~(uintptr_t)7);
    sh__rot_halfpi_set_angles(rot, 0, order - 1, tmp);
    for (size_t i = 0; i < hp_state_n(order); i++) cs[i] = (float)tmp[i];
#else
    sh__rot_halfpi_set_angles(rot, 0, order - 1, state);
#endif
    if (mults) *mults += 3u * 4u * (uint64_t)order;
    return SH_OK;
}

void SH_R(sh__rot_halfpi_apply)(int order, const void *tables, const void *state,
                                const sh_real *in, sh_real *out, void *work, uint64_t *mults)
{
    const sh_real *cs = state;
    for (int l = 0; l < order; l++) {
        const sh_real *x = in + (size_t)l * l;
        sh_real *y = out + (size_t)l * l;
        SH_R(sh__rot_halfpi_band)(l, 0, 1, &cs, order - 1, &x, &y, work, mults);
    }
}

/* The (2l+1)² block of band l: the band applied to its unit vectors, HP_JB
 * at a time.  cs: the angle table (M ≥ l); e, col: HP_JB vectors of stride
 * W ≥ 2l+1 each; bw: band work for HP_JB jobs. */
#define HP_JB 16
static void SH_R(hp_block)(int l, const sh_real *cs, int M, sh_real *B, sh_real *e, sh_real *col,
                           int W, void *bw, uint64_t *mults)
{
    const int w = 2 * l + 1;
    const sh_real *csj[HP_JB], *inj[HP_JB];
    sh_real *outj[HP_JB];
    for (int j0 = 0; j0 < w; j0 += HP_JB) {
        const int nj = w - j0 < HP_JB ? w - j0 : HP_JB;
        for (int j = 0; j < nj; j++) {
            sh_real *u = e + (size_t)j * W;
            for (int i = 0; i < w; i++) u[i] = 0;
            u[j0 + j] = 1;
            csj[j] = cs, inj[j] = u, outj[j] = col + (size_t)j * W;
        }
        SH_R(sh__rot_halfpi_band)(l, 0, nj, csj, M, inj, outj, bw, mults);
        for (int j = 0; j < nj; j++)
            for (int i = 0; i < w; i++) B[(size_t)i * w + j0 + j] = outj[j][i];
    }
}

/* work of the blocks: the angles (room for set_f's double table), e, col,
 * then the band work, 64-byte aligned */
static void *SH_R(hp_block_work)(int order, void *work, sh_real **cs, sh_real **e, sh_real **col)
{
    const size_t W = 2 * (size_t)order + 1;
    *cs = work, *e = *cs + 4 * hp_state_n(order), *col = *e + HP_JB * W;
    return (void *)(((uintptr_t)(*col + HP_JB * W) + 63) & ~(uintptr_t)63);
}

int SH_R(sh__rot_halfpi_blocks)(int order, const sh_rotation *rot, const void *tables,
                                sh_real *blocks, void *work, uint64_t *mults)
{
    sh_real *cs, *e, *col;
    void *bw = SH_R(hp_block_work)(order, work, &cs, &e, &col);
    SH_R(sh__rot_halfpi_set)(order, rot, NULL, cs, mults);
    for (int l = 0; l < order; l++)
        SH_R(hp_block)(l, cs, order - 1, blocks + sh_rot_block_offset(l), e, col, 2 * order + 1, bw, mults);
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static size_t hp_blocks_work(int order)
{
    const size_t W = 2 * (size_t)order + 1;
    return (4 * hp_state_n(order) + 2 * HP_JB * W) * sizeof(double) + 128 +
           sh__rot_halfpi_work_bytes(order - 1, HP_JB);
}
static size_t hp_work(int order) { return hp_blocks_work(order); }
static size_t hp_state(int order) { return 3 * hp_state_n(order) * sizeof(double) + 16; }

/* One band alone (the band iterator): the block of band l, O(l³). */
static size_t hp_band_work(int l) { return hp_blocks_work(l + 1); }
static int hp_band_d(int l, const sh_rotation *rot, double *block, void *work)
{
    double *cs, *e, *col;
    void *bw = hp_block_work_d(l + 1, work, &cs, &e, &col);
    sh__rot_halfpi_set_angles(rot, 0, l, cs);
    hp_block_d(l, cs, l, block, e, col, 2 * l + 3, bw, NULL);
    return SH_OK;
}

const sh__rot_ops sh__rot_halfpi_ops = {
    .name = "halfpi",
    .max_order = SHLAB_MAX_ORDER,
    .work_bytes = hp_work,
    .state_bytes = hp_state,
    .set_d = sh__rot_halfpi_set_d,
    .set_f = sh__rot_halfpi_set_f,
    .blocks_d = sh__rot_halfpi_blocks_d,
    .blocks_f = sh__rot_halfpi_blocks_f,
    .apply_d = sh__rot_halfpi_apply_d,
    .apply_f = sh__rot_halfpi_apply_f,
    .band_d = hp_band_d,
    .band_work_bytes = hp_band_work,
};
#endif
