/* highband_peers — the all-band rotation and the transforms at high band
 * against their peers, HEALPix C++ rotate_alm and libsharp map2alm/alm2map.
 *
 * Deterministic part (computed through the library alone):
 *   memory of one all-band rotation for lmax 100..4000 — the streamed
 *   rotation's scratch (sh_rot_stream_bytes, 1 and 2 threads) plus the two
 *   coefficient vectors, against the plans that store the blocks of every
 *   band (sh_rot_plan_bytes of zxzxz, blanco, ivanic; the blocks alone are
 *   sh_rot_block_offset(order) doubles, Σ_l (2l+1)²);
 *   shlab's round trip (rotate, then rotate back with the exact inverse) at
 *   lmax 100, 300, 1000 on seeded N(0, 1) coefficients (the generator and
 *   the rotation of tests/peers/peer_healpix_bench.cc), with 1 and with 2
 *   threads, whose results must be the same bytes.
 * Kept part "peers" (regenerated only when both peers are there: the
 *   program build/peers/peer_healpix_bench, built by `make` when pkg-config
 *   finds healpix_cxx, and `shlab bench --peers`, which says when libsharp
 *   was not found): shlab's rotation against rotate_alm at lmax 100, 300,
 *   1000 (max abs difference, ‖Δ‖₂/‖x‖₂, one thread each), both round trips,
 *   and shlab's transforms against libsharp's at lmax 255, 511, 1023 (‖Δ‖₂/‖·‖₂
 *   of the first repeat).
 * Timing part: the ratios shlab / HEALPix (one-shot, stream kept, per
 *   rotation in a batch of 8; per repetition, interleaved in one process) at
 *   lmax 100, 300, 1000; shlab / libsharp (analysis, synthesis; thread CPU
 *   clock) at lmax 255, 511, 1023 on Gauss grids and on a 1024 × 512 lat-long map
 *   of 3 channels; the peak RSS of a process doing one one-shot rotation;
 *   shlab's speed-up from 1 to 2 threads (interleaved); the two high-band
 *   kernels' flop rates as a fraction of this core's measured peak (flops.dat,
 *   fma_peak below).  A speed claim is
 *   judged only when its run meets the noise criterion (the paired ratio's
 *   (q3 − q1)/median ≤ 0.05 and other processes using ≤ 0.25 CPUs during the
 *   peer program's run, /proc/stat minus the children's own CPU time), and
 *   then by exp_ratio_side.
 * The peers run as child processes (popen): peer_healpix_bench --tsv and
 * `$SHLAB bench --peers --format json` (read with jansson).
 */
#include "exp.h"

#include <jansson.h>
#if defined(__x86_64__)
#include <immintrin.h>
#endif
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

enum { NL = 3, MAXREP = 64, NSL = 3, NS = 4 * NSL };
static const int HP_LMAX[NL] = {100, 300, 1000};
static const int SH_LMAX[NSL] = {255, 511, 1023}; /* bench --peers: 4 rows each (2 grids × 2 transforms) */
static const double LOAD_MAX = 0.25, SPREAD_MAX = 0.05;
static const double GOAL_ONESHOT = 0.05, GOAL_REUSE = 0.1, GOAL_SHARP = 0.9, GOAL_SPEEDUP = 1.8, GOAL_RSS_MB = 64,
                    GOAL_ROUNDTRIP = 4e-13;

/* ---- seeded N(0, 1) coefficients: the generator of peer_healpix.h ------ */
static void gauss(unsigned long long seed, size_t n, double *x)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u1 = ((double)(seed >> 11) + 0.5) / 9007199254740992.0;
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u2 = ((double)(seed >> 11) + 0.5) / 9007199254740992.0;
        x[i] = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
    }
}

/* a peer program's output could not be used: stop with one line */
static void fail(const char *what)
{
    fprintf(stderr, "highband_peers: %s\n", what);
    exit(1);
}

static double mb(double bytes) { return bytes / 1e6; }

/* ---- deterministic: memory ----------------------------------------------- */
static void memory_part(void)
{
    static const int L[] = {100, 150, 200, 300, 400, 500, 700, 1000, 1500, 2000, 2500, 3000, 4000};
    const int nl = (int)(sizeof L / sizeof L[0]);
    FILE *f = exp_data("memory.dat",
                       "memory of one rotation of all bands 0..lmax (MB = 10^6 bytes; double precision): the streamed "
                       "rotation (sh_rot_stream_bytes) against plans that store every band's block (sh_rot_plan_bytes)",
                       "lmax order vector_MB stream_1thread_MB stream_2threads_MB one_rotation_MB halfpi_plan_MB "
                       "blocks_MB zxzxz_plan_MB blanco_plan_MB ivanic_plan_MB");
    double at1000[4] = {0};
    for (int i = 0; i < nl; i++) {
        const int order = L[i] + 1;
        const double vec = 8.0 * order * order, s1 = (double)sh_rot_stream_bytes(order, 1),
                     s2 = (double)sh_rot_stream_bytes(order, 2);
        const double hp = (double)sh_rot_plan_bytes(order, SH_ROT_HALFPI, SH_PREC_DOUBLE),
                     bl = 8.0 * (double)sh_rot_block_offset(order),
                     zx = (double)sh_rot_plan_bytes(order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE),
                     bn = (double)sh_rot_plan_bytes(order, SH_ROT_BLANCO, SH_PREC_DOUBLE),
                     iv = (double)sh_rot_plan_bytes(order, SH_ROT_IVANIC, SH_PREC_DOUBLE);
        if (!(s1 > 0 && s2 > 0 && hp > 0 && zx > 0 && bn > 0 && iv > 0)) fail("a memory size is 0");
        /* one rotation: the input and output vectors and the scratch */
        const double one = 2 * vec + s1;
        fprintf(f, "%d %d %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", L[i], order, mb(vec), mb(s1), mb(s2),
                mb(one), mb(hp), mb(bl), mb(zx), mb(bn), mb(iv));
        if (L[i] == 1000) at1000[0] = one, at1000[1] = s1, at1000[2] = zx, at1000[3] = bn;
        if (L[i] == 4000) {
            exp_index("Memory of one rotation of all bands 0..lmax in double precision, as the library sizes it "
                      "([memory.dat](memory.dat); MB = 10^6 bytes, GB = 10^9). The streamed rotation (`sh_rot_stream`, the "
                      "halfpi method: d^l(π/2) generated band by band, nothing kept between bands) needs its "
                      "O(order) scratch per thread (`sh_rot_stream_bytes`: %.2f MB on 1 thread and %.2f MB on 2 at "
                      "lmax 1000; %.2f MB and %.2f MB at lmax 4000) besides the input and output vectors "
                      "(%.1f MB each at lmax 1000, %.0f MB at 4000). The plans that store a block for every band "
                      "grow as lmax³ (`sh_rot_plan_bytes`): zxzxz %.2f GB, blanco %.1f GB at lmax 1000, and at "
                      "lmax 4000 zxzxz %.0f GB, blanco %.0f GB, ivanic %.0f GB (the blocks alone, Σ(2l+1)² "
                      "doubles: %.0f GB).\n\n![memory against lmax](highband_peers_memory.png)",
                      mb(at1000[1]), mb((double)sh_rot_stream_bytes(1001, 2)), mb(s1), mb(s2), mb(8.0 * 1001 * 1001),
                      mb(vec), at1000[2] / 1e9, at1000[3] / 1e9, zx / 1e9,
                      bn / 1e9, iv / 1e9, bl / 1e9);
        }
    }
    fclose(f);
    char meas[256];
    snprintf(meas, sizeof meas, "%.1f MB at lmax 1000 (2 vectors of %.1f MB + %.2f MB of scratch); zxzxz's plan %.0f MB",
             mb(at1000[0]), mb(8.0 * 1001 * 1001), mb(at1000[1]), mb(at1000[2]));
    exp_claim_judged("highband-memory-1000", "shlab goal",
                     "one rotation of all bands 0..1000 from scratch fits in 64 MB (peak RSS goal; here the library's "
                     "own sizing: vectors and scratch)",
                     "<= 64 MB", meas, "64 MB", mb(at1000[0]) <= GOAL_RSS_MB,
                     "highband_peers/memory.dat (the measured peak RSS: the timing part)",
                     "the vectors and scratch of one rotation at lmax 1000 exceed 64 MB.");
}

/* ---- deterministic: round trip, 1 and 2 threads ------------------------- */
static double RT_MAX[NL];

static void roundtrip_part(void)
{
    FILE *f = exp_data("roundtrip.dat",
                       "round trip of the streamed rotation (rotate by R = (0.3, 1.1, -0.7), then by R^T) on seeded "
                       "N(0,1) coefficients, all bands 0..lmax",
                       "lmax max_abs_error rel_l2_error same_bytes_1_vs_2_threads");
    sh_rotation r;
    exp_check(sh_rotation_from_euler(0.3, 1.1, -0.7, &r), "rotation");
    int all_same = 1;
    char tab[1024];
    size_t tl = (size_t)snprintf(tab, sizeof tab, "| lmax | max abs error | ‖error‖₂ / ‖x‖₂ | 2 threads: same bytes |\n|---|---|---|---|\n");
    for (int k = 0; k < NL; k++) {
        const int lmax = HP_LMAX[k], order = lmax + 1;
        const size_t n = (size_t)order * order;
        double *x = malloc(5 * n * sizeof *x);
        if (!x) exp_check(SH_ENOMEM, "vectors");
        double *y1 = x + n, *z1 = x + 2 * n, *y2 = x + 3 * n, *z2 = x + 4 * n;
        gauss(42, n, x);
        exp_progress("highband_peers: round trip at lmax %d on 1 and 2 threads", lmax);
        for (int t = 1; t <= 2; t++) {
            sh_rot_stream *s;
            exp_check(sh_rot_stream_create(order, SH_CS, t, &s), "stream");
            exp_check(sh_rot_stream_apply(s, 1, &r, 0, 1, x, t == 1 ? y1 : y2), "rotate");
            exp_check(sh_rot_stream_apply(s, 1, &r, 1, 1, t == 1 ? y1 : y2, t == 1 ? z1 : z2), "rotate back");
            sh_rot_stream_free(s);
        }
        const int same = !memcmp(y1, y2, n * sizeof *x) && !memcmp(z1, z2, n * sizeof *x);
        all_same &= same;
        double e = 0, ne = 0, nx = 0;
        for (size_t i = 0; i < n; i++) {
            e = fmax(e, fabs(z1[i] - x[i]));
            ne += (z1[i] - x[i]) * (z1[i] - x[i]);
            nx += x[i] * x[i];
        }
        RT_MAX[k] = e;
        fprintf(f, "%d %.3g %.3g %d\n", lmax, e, sqrt(ne / nx), same);
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "| %d | %.2g | %.2g | %s |\n", lmax, e, sqrt(ne / nx),
                               same ? "yes" : "no");
        free(x);
    }
    fclose(f);
    exp_index("Round trip of the streamed rotation ([roundtrip.dat](roundtrip.dat)): all bands 0..lmax of seeded "
              "N(0, 1) coefficients rotated by (α, β, γ) = (0.3, 1.1, −0.7) and back by the exact inverse "
              "(`sh_rot_stream_apply` with `inverse` = 1), on 1 thread; the same on 2 threads must give the same "
              "bytes, rotated and back (bands are independent work items, each computed by one thread in a fixed "
              "order).\n\n%s",
              tab);
    char meas[256];
    snprintf(meas, sizeof meas, "max abs error %.2g (lmax 100), %.2g (300), %.2g (1000)", RT_MAX[0], RT_MAX[1],
             RT_MAX[2]);
    exp_claim_judged("highband-roundtrip-1000", "shlab goal",
                     "the all-band rotation's round trip at lmax 1000 is at least as accurate as HEALPix's rotate_alm "
                     "(goal: max abs error <= 4e-13 on N(0,1) coefficients)",
                     "<= 4e-13", meas, "4e-13", RT_MAX[2] <= GOAL_ROUNDTRIP,
                     "highband_peers/roundtrip.dat (HEALPix's own: highband_peers/peers/)",
                     "the round trip's max abs error at lmax 1000 exceeds 4e-13.");
    exp_claim_judged("highband-threads-bitwise", "shlab goal",
                     "the streamed rotation gives the same bytes for any number of threads", "bitwise",
                     all_same ? "1 and 2 threads: the same bytes at lmax 100, 300, 1000 (rotated and back)"
                     : "1 and 2 threads differ (roundtrip.dat)",
                     "exact", all_same,
                     "highband_peers/roundtrip.dat",
                     "1 and 2 threads give different bytes.");
}

/* ---- the peers: child processes, and the load while they ran ----------- */
static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
static double children_cpu_s(void)
{
    struct rusage u;
    if (getrusage(RUSAGE_CHILDREN, &u)) return -1;
    return (double)u.ru_utime.tv_sec + (double)u.ru_stime.tv_sec +
           1e-6 * ((double)u.ru_utime.tv_usec + (double)u.ru_stime.tv_usec);
}
typedef struct {
    double load, seconds; /* CPUs used by other processes during the run; its wall time */
} run_noise;
typedef struct {
    double b, c, t;
} run_mark;
static run_mark mark(void) { return (run_mark){sh_machine_busy_s(), children_cpu_s(), now_s()}; }
static run_noise noise_since(run_mark m)
{
    const run_mark e = mark();
    run_noise z = {-1, e.t - m.t};
    if (m.b >= 0 && e.b >= 0 && m.c >= 0 && e.c >= 0 && z.seconds > 0.25)
        z.load = fmax(0, ((e.b - m.b) - (e.c - m.c)) / z.seconds);
    return z;
}

/* ---- the core's peak flop rate ---------------------------------------------
 * 16 independent chains a ← a·m + c of fused multiply-adds on the widest
 * vectors the CPU runs (two flops a lane; 16 chains cover 2 pipes × a latency
 * of up to 8), thread CPU clock, best of 5: what the FMA units deliver, the
 * limit the kernels' flop rates are compared with. */
static double thread_cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
#define FMA_CHAINS 16
#if defined(__x86_64__)
#define FMA_LOOP(T, SET1, FMADD, ADD, lanes)                                                 \
    T a[FMA_CHAINS], m = SET1(0.999999999), c = SET1(1e-9);                                  \
    for (int k = 0; k < FMA_CHAINS; k++) a[k] = SET1(1.0 + k);                               \
    for (long i = 0; i < iters; i++)                                                         \
        _Pragma("GCC unroll 16") /* the chains in registers */                               \
        for (int k = 0; k < FMA_CHAINS; k++) a[k] = FMADD(a[k], m, c);                      \
    for (int k = 1; k < FMA_CHAINS; k++) a[0] = ADD(a[0], a[k]);                             \
    double r[lanes];                                                                         \
    memcpy(r, &a[0], sizeof r);                                                              \
    return r[0]
__attribute__((target("avx512f"))) static double fma_run_avx512(long iters)
{
    FMA_LOOP(__m512d, _mm512_set1_pd, _mm512_fmadd_pd, _mm512_add_pd, 8);
}
__attribute__((target("avx2,fma"))) static double fma_run_avx2(long iters)
{
    FMA_LOOP(__m256d, _mm256_set1_pd, _mm256_fmadd_pd, _mm256_add_pd, 4);
}
#endif
/* GFlop/s and the instruction set in *isa ("avx512f", "avx2+fma"; 0 where
 * neither runs: no peak is claimed then). */
static double fma_peak(const char **isa)
{
    double (*run)(long) = NULL;
    int lanes = 0;
    *isa = "none";
#if defined(__x86_64__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f")) run = fma_run_avx512, lanes = 8, *isa = "avx512f";
    else if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) run = fma_run_avx2, lanes = 4, *isa = "avx2+fma";
#endif
    if (!run) return 0;
    const long iters = 4000000; /* 1 Gflop at 8 lanes: ~10 ms at 100 GFlop/s */
    double best = 0, sink = 0;
    for (int r = 0; r < 5; r++) {
        const double t0 = thread_cpu_s();
        sink += run(iters);
        const double t = thread_cpu_s() - t0;
        if (t > 0) best = fmax(best, 2.0 * lanes * FMA_CHAINS * (double)iters / t * 1e-9);
    }
    if (!isfinite(sink)) return 0;
    return best;
}

/* Nominal flops of the two high-band kernels:
 *   transform (one channel, npairs ring pairs): 7 a pair and (l, m) — the
 *     recursion's multiply and fused multiply-subtract (3), two fused
 *     multiply-adds into the sums or from the coefficients (4) — summed over
 *     0 ≤ m ≤ l ≤ lmax;
 *   all-band rotation (rot_halfpi.c): 2(l+1)² multiply-adds a band and
 *     vector (4 flops each) and 3(l+1)² flops for the two generations of Δ. */
static double flops_sht(int lmax, int npairs) { return 7.0 * npairs * (lmax + 1.0) * (lmax + 2.0) / 2; }
static double flops_rotation(int lmax)
{
    double f = 0;
    for (int l = 0; l <= lmax; l++) f += 7.0 * (l + 1.0) * (l + 1.0);
    return f;
}

/* "0.48", or "-" without a peak */
typedef struct {
    char s[16];
} frac_text;
static frac_text of_peak(double rate, double peak)
{
    frac_text t = {"-"};
    if (peak > 0) snprintf(t.s, sizeof t.s, "%.2f", rate / peak);
    return t;
}

/* peer_healpix_bench --tsv, parsed */
typedef struct {
    int nrep[NL], nsp[NL];
    double h[NL][MAXREP], o[NL][MAXREP], u[NL][MAXREP], b[NL][MAXREP];
    double w1[NL][MAXREP], w2[NL][MAXREP], c1[NL][MAXREP], c2[NL][MAXREP];
    double agree[NL][2], rt_shlab[NL][2], rt_healpix[NL][2], rss[NL];
    run_noise noise;
} hp_result;
/* shlab bench --peers --format json, parsed: SH_LMAX × gauss, latlong × analysis, synthesis */
typedef struct {
    int lmax, channels;
    char grid[48], transform[16];
    double shlab_ms, peer_ms, ratio, q1, q3, agreement, max_rel;
} sharp_row;
typedef struct {
    int nrow;
    sharp_row row[NS];
    char kernel[32];
    run_noise noise;
} sharp_result;

static int lmax_index(int lmax)
{
    for (int k = 0; k < NL; k++)
        if (HP_LMAX[k] == lmax) return k;
    return -1;
}

static int run_healpix(const char *bin, hp_result *hp)
{
    char cmd[4200], lm[64];
    snprintf(lm, sizeof lm, "%d,%d,%d", HP_LMAX[0], HP_LMAX[1], HP_LMAX[2]);
    snprintf(cmd, sizeof cmd, "'%s' --lmax %s --threads 1 --speedup 2 --tsv", bin, lm);
    memset(hp, 0, sizeof *hp);
    const run_mark m = mark();
    FILE *p = popen(cmd, "r");
    if (!p) return 0;
    char line[1024];
    int rows = 0;
    while (fgets(line, sizeof line, p)) {
        if (line[0] == '#') continue;
        char *f[10];
        int nf = 0;
        for (char *s = line, *t; nf < 10 && (t = strsep(&s, "\t\n"));)
            if (*t) f[nf++] = t;
        if (nf < 4) continue;
        const int k = lmax_index(atoi(f[1]));
        if (k < 0) continue;
        if (!strcmp(f[0], "time") && nf == 8 && hp->nrep[k] < MAXREP) {
            const int i = hp->nrep[k]++;
            hp->h[k][i] = strtod(f[4], NULL), hp->o[k][i] = strtod(f[5], NULL);
            hp->u[k][i] = strtod(f[6], NULL), hp->b[k][i] = strtod(f[7], NULL);
        } else if (!strcmp(f[0], "speedup") && nf == 8 && hp->nsp[k] < MAXREP) {
            const int i = hp->nsp[k]++;
            hp->w1[k][i] = strtod(f[4], NULL), hp->w2[k][i] = strtod(f[5], NULL);
            hp->c1[k][i] = strtod(f[6], NULL), hp->c2[k][i] = strtod(f[7], NULL);
        } else if (!strcmp(f[0], "agreement") && nf == 4) {
            hp->agree[k][0] = strtod(f[2], NULL), hp->agree[k][1] = strtod(f[3], NULL);
        } else if (!strcmp(f[0], "roundtrip") && nf == 5) {
            double *d = !strcmp(f[2], "shlab") ? hp->rt_shlab[k] : hp->rt_healpix[k];
            d[0] = strtod(f[3], NULL), d[1] = strtod(f[4], NULL);
        } else if (!strcmp(f[0], "rss") && nf == 4 && atoi(f[2]) == 1) {
            hp->rss[k] = strtod(f[3], NULL);
        } else continue;
        rows++;
    }
    const int rc = pclose(p);
    hp->noise = noise_since(m);
    if (rc != 0 || !rows) return 0;
    for (int k = 0; k < NL; k++)
        if (hp->nrep[k] < 1 || hp->nsp[k] < 1 || !(hp->rss[k] > 0) || !(hp->rt_healpix[k][0] > 0)) return 0;
    return 1;
}

static int run_sharp(const char *shlab, sharp_result *sr)
{
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "'%s' bench --peers --lmax %d,%d,%d --latlong 1024 --repeat 21 --threads 1 --quiet "
                              "--format json",
             shlab, SH_LMAX[0], SH_LMAX[1], SH_LMAX[2]);
    memset(sr, 0, sizeof *sr);
    const run_mark m = mark();
    FILE *p = popen(cmd, "r");
    if (!p) return 0;
    json_error_t err;
    json_t *root = json_loadf(p, 0, &err);
    const int rc = pclose(p);
    sr->noise = noise_since(m);
    json_t *rows = root ? json_object_get(root, "rows") : NULL;
    const char *kernel = root ? json_string_value(json_object_get(root, "kernel")) : NULL;
    snprintf(sr->kernel, sizeof sr->kernel, "%s", kernel ? kernel : "?");
    size_t i;
    json_t *row;
    json_array_foreach(rows, i, row)
    {
        if (sr->nrow >= NS) break;
        sharp_row *q = &sr->row[sr->nrow++];
        q->lmax = (int)json_integer_value(json_object_get(row, "lmax"));
        q->channels = (int)json_integer_value(json_object_get(row, "channels"));
        const char *g = json_string_value(json_object_get(row, "grid")),
                   *t = json_string_value(json_object_get(row, "transform"));
        snprintf(q->grid, sizeof q->grid, "%s", g ? g : "?");
        snprintf(q->transform, sizeof q->transform, "%s", t ? t : "?");
        q->shlab_ms = json_real_value(json_object_get(row, "shlab_ms"));
        q->peer_ms = json_real_value(json_object_get(row, "peer_ms"));
        q->ratio = json_real_value(json_object_get(row, "ratio"));
        q->q1 = json_real_value(json_object_get(row, "ratio_q1"));
        q->q3 = json_real_value(json_object_get(row, "ratio_q3"));
        q->agreement = json_real_value(json_object_get(row, "agreement"));
        q->max_rel = json_real_value(json_object_get(row, "max_rel"));
        if (!(q->ratio > 0 && q->q1 > 0 && q->q3 > 0 && q->agreement > 0)) sr->nrow = 0;
    }
    json_decref(root);
    return rc == 0 && sr->nrow == NS;
}

/* the row of (lmax, gauss or latlong, analysis or synthesis) */
static const sharp_row *sharp_find(const sharp_result *sr, int lmax, int latlong, int synthesis)
{
    for (int i = 0; i < sr->nrow; i++) {
        const sharp_row *q = &sr->row[i];
        if (q->lmax == lmax && !strncmp(q->grid, latlong ? "latlong" : "gauss", latlong ? 7 : 5) &&
            !strcmp(q->transform, synthesis ? "synthesis" : "analysis"))
            return q;
    }
    fail("shlab bench --peers: a row is missing");
    return NULL;
}

/* ---- kept part: agreement with the peers -------------------------------- */
static void peers_part(const hp_result *hp, const sharp_result *sr)
{
    exp_part("peers");
    FILE *f = exp_data("healpix.dat",
                       "shlab's all-band rotation against HEALPix C++ rotate_alm (one thread each; R = (0.3, 1.1, "
                       "-0.7) on seeded N(0,1) coefficients, build/peers/peer_healpix_bench --tsv)",
                       "lmax agreement_max_abs agreement_rel_l2 shlab_roundtrip_max shlab_roundtrip_rel_l2 "
                       "healpix_roundtrip_max healpix_roundtrip_rel_l2");
    char tab[2048];
    size_t tl = (size_t)snprintf(tab, sizeof tab,
                                 "| lmax | shlab − rotate_alm: max abs | ‖Δ‖₂/‖x‖₂ | round trip, shlab: max abs | "
                                 "HEALPix: max abs | shlab ‖·‖₂/‖x‖₂ | HEALPix ‖·‖₂/‖x‖₂ |\n|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < NL; k++) {
        fprintf(f, "%d %.2g %.2g %.2g %.2g %.2g %.2g\n", HP_LMAX[k], hp->agree[k][0], hp->agree[k][1],
                hp->rt_shlab[k][0], hp->rt_shlab[k][1], hp->rt_healpix[k][0], hp->rt_healpix[k][1]);
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl, "| %d | %.2g | %.2g | %.2g | %.2g | %.2g | %.2g |\n",
                               HP_LMAX[k], hp->agree[k][0], hp->agree[k][1], hp->rt_shlab[k][0],
                               hp->rt_healpix[k][0], hp->rt_shlab[k][1], hp->rt_healpix[k][1]);
    }
    fclose(f);
    f = exp_data("sharp.dat",
                 "shlab's transforms against libsharp's on the same rings (shlab bench --peers --format json, one "
                 "thread; agreement = ||shlab - libsharp||_2 / ||libsharp||_2, max_rel = max|diff| / max|libsharp|)",
                 "lmax grid channels transform agreement max_rel");
    char tab2[2048];
    size_t t2 = (size_t)snprintf(tab2, sizeof tab2, "| grid | lmax | channels | transform | ‖Δ‖₂/‖·‖₂ | max\\|Δ\\|/max |\n|---|---|---|---|---|---|\n");
    for (int i = 0; i < sr->nrow; i++) {
        const sharp_row *q = &sr->row[i];
        char g[48];
        snprintf(g, sizeof g, "%s", q->grid);
        for (char *c = g; *c; c++)
            if (*c == ' ') *c = '_';
        fprintf(f, "%d %s %d %s %.2g %.2g\n", q->lmax, g, q->channels, q->transform, q->agreement, q->max_rel);
        t2 += (size_t)snprintf(tab2 + t2, sizeof tab2 - t2, "| %s | %d | %d | %s | %.2g | %.2g |\n", q->grid, q->lmax,
                               q->channels, q->transform, q->agreement, q->max_rel);
    }
    fclose(f);
    exp_index("Against the peers (computed at code revision `%s`; regenerated when HEALPix C++ and libsharp are "
              "installed — Debian `libhealpix-cxx-dev`, `libsharp-dev` — and otherwise kept as they are). "
              "HEALPix's `rotate_alm` with the basis and angle maps of `tests/peers/peer_healpix.h` "
              "([healpix.dat](healpix.dat); one thread each, the rotation and coefficients of the round trip "
              "above):\n\n%s\n"
              "shlab's transforms (`sh_sht_analysis`, `sh_sht_synthesis`, kernels %s) against libsharp's "
              "`map2alm`, `alm2map` on exactly the same rings and seeded map or coefficients "
              "([sharp.dat](sharp.dat); `shlab bench --peers`):\n\n%s",
              exp_revision(), tab, sr->kernel, tab2);
    char meas[512];
    snprintf(meas, sizeof meas, "max abs %.2g at lmax 300 (%.2g at 100, %.2g at 1000); relative L2 %.2g", hp->agree[1][0],
             hp->agree[0][0], hp->agree[2][0], hp->agree[1][1]);
    exp_claim_judged("highband-healpix-agreement-300", "shlab goal",
                     "shlab's all-band rotation agrees with HEALPix C++ rotate_alm at lmax 300 (max abs difference on "
                     "N(0,1) coefficients)",
                     "<= 1e-12", meas, "1e-12", hp->agree[1][0] <= 1e-12,
                     "highband_peers/peers/healpix.dat (tests/peers/test_peer_healpix.cc checks ten rotations)",
                     "shlab and rotate_alm differ by more than 1e-12 at lmax 300.");
    const sharp_row *a255 = sharp_find(sr, 255, 0, 0), *a511 = sharp_find(sr, 511, 0, 0), *a1023 = sharp_find(sr, 1023, 0, 0);
    const sharp_row *s255 = sharp_find(sr, 255, 0, 1), *s511 = sharp_find(sr, 511, 0, 1), *s1023 = sharp_find(sr, 1023, 0, 1);
    snprintf(meas, sizeof meas,
             "analysis %.2g (lmax 255), %.2g (511), %.2g (1023); synthesis %.2g, %.2g, %.2g (relative L2; where the "
             "syntheses differ by more, it is libsharp's error: sht_accuracy's peers part)",
             a255->agreement, a511->agreement, a1023->agreement, s255->agreement, s511->agreement, s1023->agreement);
    exp_claim_judged("highband-sharp-agreement", "shlab goal",
                     "shlab's projection (analysis) agrees with libsharp map2alm on a Gauss grid at lmax 255, 511 and "
                     "1023 to 1e-13 (relative L2)",
                     "<= 1e-13", meas, "1e-13",
                     a255->agreement <= 1e-13 && a511->agreement <= 1e-13 && a1023->agreement <= 1e-13,
                     "highband_peers/peers/sharp.dat (shlab bench --peers --format json)",
                     "the analyses differ by more than 1e-13 (relative L2).");
    snprintf(meas, sizeof meas, "max abs: shlab %.2g, HEALPix %.2g at lmax 1000 (%.2g / %.2g at 300, %.2g / %.2g at 100)",
             hp->rt_shlab[2][0], hp->rt_healpix[2][0], hp->rt_shlab[1][0], hp->rt_healpix[1][0], hp->rt_shlab[0][0],
             hp->rt_healpix[0][0]);
    int better = 1;
    for (int k = 0; k < NL; k++) better &= hp->rt_shlab[k][0] <= hp->rt_healpix[k][0];
    exp_claim_judged("highband-roundtrip-vs-healpix", "shlab goal",
                     "the all-band rotation's round trip is at least as accurate as HEALPix's rotate_alm at lmax 100, 300, "
                     "1000",
                     "shlab <= HEALPix", meas, "-", better,
                     "highband_peers/peers/healpix.dat",
                     "HEALPix's round trip is more accurate at some lmax.");
    exp_part(NULL);
}

/* ---- timing part ---------------------------------------------------------- */
static sh_bench_ratio ratio_of(const double *a, const double *b, int n)
{
    sh_bench_ratio r;
    exp_check(sh_bench_paired_ratio(a, b, n, SPREAD_MAX, &r), "paired ratio");
    return r;
}
static double median_of(const double *v, int n)
{
    double s[MAXREP];
    memcpy(s, v, (size_t)n * sizeof *s);
    for (int i = 1; i < n; i++) /* insertion sort: n ≤ 64 */
        for (int j = i; j > 0 && s[j] < s[j - 1]; j--) {
            const double t = s[j];
            s[j] = s[j - 1], s[j - 1] = t;
        }
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}
/* verdict of a goal lo ≤ ratio ≤ hi: not-measured when noisy */
static const char *goal_verdict(const sh_bench_ratio *r, double lo, double hi, int noisy)
{
    if (noisy) return "not-measured";
    switch (exp_ratio_side(r, lo, hi)) {
    case EXP_INSIDE: return "reproduced";
    case EXP_OUTSIDE: return "differs";
    default: return "inconclusive";
    }
}

/* A speed claim against the goal lo ≤ ratio ≤ hi: the measured text is the
 * paired ratio, median [q1, q3], and detail; "not measured (noisy run: …)"
 * when the machine was loaded or the ratio spread (then no verdict). */
static void speed_claim(const char *id, const char *statement, const char *printed, const sh_bench_ratio *r,
                        const char *detail, int loaded, double load, double lo, double hi, const char *evidence)
{
    const int noisy = loaded || r->noisy;
    char meas[1536], tol[64], ev[256];
    snprintf(meas, sizeof meas, "%s%.3f [%.3f, %.3f] %s; other load %.2f CPUs%s", noisy ? "not measured (noisy run: " : "",
             r->median, r->q1, r->q3, detail, load, !noisy ? "" : loaded ? ", machine loaded)" : ", ratio spread)");
    snprintf(tol, sizeof tol, "%g (quartiles widened by 5%%)", isinf(hi) ? lo : hi);
    const char *v = goal_verdict(r, lo, hi, noisy);
    exp_claim(id, "shlab goal", statement, printed, meas, tol, v,
              exp_evidence(ev, sizeof ev, evidence, v, "the paired ratio lies wholly outside the goal."));
}

static void timing_part(const hp_result *hp, const sharp_result *sr)
{
    exp_part("timing");
    const int k1000 = 2;
    const int noisy_load_hp = !(hp->noise.load >= 0 && hp->noise.load <= LOAD_MAX);
    const int noisy_load_sh = !(sr->noise.load >= 0 && sr->noise.load <= LOAD_MAX);
    /* HEALPix ratios: blocks one-shot, reuse, batch */
    sh_bench_ratio R[NL][3], SP[NL], CP[NL];
    for (int k = 0; k < NL; k++) {
        const int n = hp->nrep[k];
        R[k][0] = ratio_of(hp->o[k], hp->h[k], n);
        R[k][1] = ratio_of(hp->u[k], hp->h[k], n);
        R[k][2] = ratio_of(hp->b[k], hp->h[k], n);
        SP[k] = ratio_of(hp->w1[k], hp->w2[k], hp->nsp[k]);
        CP[k] = ratio_of(hp->c2[k], hp->c1[k], hp->nsp[k]);
    }
    static const char *const QN[3] = {"one-shot", "reuse", "batch-of-8"};
    FILE *f = exp_data("healpix.dat",
                       "time ratio shlab / HEALPix rotate_alm per repetition (one thread, interleaved in one process: "
                       "peer_healpix_bench --tsv); one block per quantity: one-shot (create + apply + free), reuse "
                       "(stream kept, one rotation), batch-of-8 (per rotation)",
                       "lmax quantity ratio_median ratio_q1 ratio_q3 spread healpix_ms shlab_ms repetitions");
    for (int q = 0; q < 3; q++) {
        for (int k = 0; k < NL; k++) {
            const double *t = q == 0 ? hp->o[k] : q == 1 ? hp->u[k] : hp->b[k];
            fprintf(f, "%d %s %.4g %.4g %.4g %.3f %.4g %.4g %d\n", HP_LMAX[k], QN[q], R[k][q].median, R[k][q].q1,
                    R[k][q].q3, R[k][q].spread, 1e3 * median_of(hp->h[k], hp->nrep[k]),
                    1e3 * median_of(t, hp->nrep[k]), hp->nrep[k]);
        }
        fprintf(f, "\n\n");
    }
    fclose(f);
    f = exp_data("sharp.dat",
                 "time ratio shlab / libsharp per repeat (thread CPU clock, one thread, interleaved, alternating who "
                 "goes first: shlab bench --peers --format json); one block per grid and transform",
                 "lmax grid channels transform ratio_median ratio_q1 ratio_q3 spread shlab_ms libsharp_ms");
    for (int latlong = 0; latlong < 2; latlong++)
        for (int syn = 0; syn < 2; syn++) {
            for (int k = 0; k < NSL; k++) {
                const sharp_row *q = sharp_find(sr, SH_LMAX[k], latlong, syn);
                fprintf(f, "%d %s %d %s %.4g %.4g %.4g %.3f %.4g %.4g\n", q->lmax, latlong ? "latlong_1024x512" : "gauss",
                        q->channels, q->transform, q->ratio, q->q1, q->q3, (q->q3 - q->q1) / q->ratio, q->shlab_ms,
                        q->peer_ms);
            }
            fprintf(f, "\n\n");
        }
    fclose(f);
    f = exp_data("speedup.dat",
                 "shlab's all-band rotation on 2 threads: 1-thread wall time / 2-thread wall time per repetition "
                 "(interleaved), and the CPU time on 2 threads / on 1",
                 "lmax speedup_median speedup_q1 speedup_q3 spread cpu_ratio_median repetitions");
    for (int k = 0; k < NL; k++)
        fprintf(f, "%d %.4g %.4g %.4g %.3f %.4g %d\n", HP_LMAX[k], SP[k].median, SP[k].q1, SP[k].q3, SP[k].spread,
                CP[k].median, hp->nsp[k]);
    fclose(f);
    f = exp_data("rss.dat", "peak RSS (VmHWM) of a fresh process doing one one-shot rotation of all bands on 1 thread "
                            "(vectors and libraries included; MiB = 2^20 bytes)",
                 "lmax peak_rss_MiB");
    for (int k = 0; k < NL; k++) fprintf(f, "%d %.1f\n", HP_LMAX[k], hp->rss[k]);
    fclose(f);
    /* flop rates against the measured peak */
    const char *pisa;
    const double peak = fma_peak(&pisa);
    f = exp_data("flops.dat",
                 "nominal flops of the two high-band kernels (transform: 7 a ring pair and (l, m), one channel, Gauss "
                 "grid of lmax + 1 rings; rotation: 7 (l+1)^2 a band) over the median times above, against this "
                 "core's peak (16 chains of fused multiply-adds on the widest vectors, best of 5)",
                 "kernel lmax gflop ms gflop_per_s peak_gflop_per_s fraction_of_peak peak_isa");
    char ftab[2048];
    size_t fl = (size_t)snprintf(ftab, sizeof ftab,
                                 "| work | lmax | nominal GFlop | ms | GFlop/s | fraction of peak |\n|---|---|---|---|---|---|\n");
    for (int k = 1; k < NSL; k++)
        for (int syn = 0; syn < 2; syn++) {
            const sharp_row *q = sharp_find(sr, SH_LMAX[k], 0, syn);
            const double g = 1e-9 * flops_sht(q->lmax, (q->lmax + 2) / 2), r = g / (1e-3 * q->shlab_ms);
            fprintf(f, "%s %d %.4g %.4g %.4g %.4g %.3f %s\n", syn ? "synthesis" : "analysis", q->lmax, g, q->shlab_ms, r,
                    peak, peak > 0 ? r / peak : NAN, pisa);
            fl += (size_t)snprintf(ftab + fl, sizeof ftab - fl, "| %s (Gauss grid) | %d | %.3g | %.3g | %.1f | %s |\n",
                                   syn ? "synthesis" : "analysis", q->lmax, g, q->shlab_ms, r, of_peak(r, peak).s);
        }
    for (int q = 0; q < 2; q++) { /* one-shot, stream kept */
        const double g = 1e-9 * flops_rotation(HP_LMAX[k1000]), ms = 1e3 * median_of(q ? hp->u[k1000] : hp->o[k1000], hp->nrep[k1000]);
        const double r = g / (1e-3 * ms);
        fprintf(f, "%s %d %.4g %.4g %.4g %.4g %.3f %s\n", q ? "rotation_kept" : "rotation_oneshot", HP_LMAX[k1000], g, ms, r,
                peak, peak > 0 ? r / peak : NAN, pisa);
        fl += (size_t)snprintf(ftab + fl, sizeof ftab - fl, "| all-band rotation (%s) | %d | %.3g | %.3g | %.1f | %s |\n",
                               q ? "stream kept" : "one-shot", HP_LMAX[k1000], g, ms, r, of_peak(r, peak).s);
    }
    fclose(f);
    f = exp_data("noise.dat", "load of the machine while each peer program ran (CPUs used by other processes: "
                              "/proc/stat busy time minus the program's own CPU time)",
                 "program seconds load_cpus noisy_load");
    fprintf(f, "peer_healpix_bench %.1f %.2f %d\n", hp->noise.seconds, hp->noise.load, noisy_load_hp);
    fprintf(f, "shlab_bench_peers %.1f %.2f %d\n", sr->noise.seconds, sr->noise.load, noisy_load_sh);
    fclose(f);

    /* claims */
    char meas[1024];
    snprintf(meas, sizeof meas, "at lmax 1000 (%.3f at 300, %.3f at 100)", R[1][0].median, R[0][0].median);
    speed_claim("highband-rotate-oneshot-1000",
                "one rotation of all bands 0..1000 from scratch takes <= 0.05x the time of HEALPix rotate_alm (one thread)",
                "<= 0.05", &R[k1000][0], meas, noisy_load_hp, hp->noise.load, 0, GOAL_ONESHOT,
                "highband_peers/timing/healpix.dat, noise.dat");
    snprintf(meas, sizeof meas, "at lmax 1000 with the stream kept; per rotation in a batch of 8: %.3f [%.3f, %.3f]",
             R[k1000][2].median, R[k1000][2].q1, R[k1000][2].q3);
    speed_claim("highband-rotate-reuse-1000",
                "with its tables kept across rotations, a rotation of all bands 0..1000 takes <= 0.1x the time of "
                "HEALPix rotate_alm (one thread; judged on the kept stream, one rotation per call)",
                "<= 0.1", &R[k1000][1], meas, noisy_load_hp, hp->noise.load, 0, GOAL_REUSE,
                "highband_peers/timing/healpix.dat, noise.dat");
    for (int k = 1; k < NSL; k++) /* lmax 511 and 1023 */
        for (int syn = 0; syn < 2; syn++) {
            const sharp_row *q = sharp_find(sr, SH_LMAX[k], 0, syn);
            const double spread = (q->q3 - q->q1) / q->ratio;
            const sh_bench_ratio r = {q->ratio, q->q1, q->q3, spread, spread > SPREAD_MAX};
            char id[64], st[256];
            snprintf(id, sizeof id, "highband-sharp-%s-%d", syn ? "synthesis" : "analysis", SH_LMAX[k]);
            snprintf(st, sizeof st,
                     "%s on a Gauss grid at lmax %d takes <= 0.9x the time of libsharp %s (one thread, one map)",
                     syn ? "synthesis (sh_sht_synthesis)" : "projection (sh_sht_analysis)", SH_LMAX[k],
                     syn ? "alm2map" : "map2alm");
            snprintf(meas, sizeof meas, "(%.3g ms / %.3g ms, kernels %s)", q->shlab_ms, q->peer_ms, sr->kernel);
            speed_claim(id, st, "<= 0.9", &r, meas, noisy_load_sh, sr->noise.load, 0, GOAL_SHARP,
                        "highband_peers/timing/sharp.dat, noise.dat");
        }
    snprintf(meas, sizeof meas, "at lmax 1000; CPU time on 2 threads / on 1: %.2f", CP[k1000].median);
    speed_claim("highband-rotate-threads-1000", "two threads rotate all bands 0..1000 >= 1.8x as fast as one", ">= 1.8",
                &SP[k1000], meas, noisy_load_hp, hp->noise.load, GOAL_SPEEDUP, INFINITY,
                "highband_peers/timing/speedup.dat, noise.dat");
    snprintf(meas, sizeof meas, "%.1f MiB at lmax 1000 (%.1f MiB at 300, %.1f MiB at 100)", hp->rss[k1000], hp->rss[1],
             hp->rss[0]);
    exp_claim_judged("highband-rotate-rss-1000", "shlab goal",
                     "a process rotating all bands 0..1000 once from scratch peaks at <= 64 MB RSS", "<= 64 MB", meas,
                     "64 MB (10^6 bytes)", hp->rss[k1000] * 1.048576 <= GOAL_RSS_MB,
                     "highband_peers/timing/rss.dat (VmHWM of a child doing only the rotation)",
                     "the child's peak RSS (VmHWM) at lmax 1000 exceeds 64 MB.");

    /* index */
    char tab[4096];
    size_t tl = (size_t)snprintf(tab, sizeof tab,
                                 "| lmax | HEALPix ms | shlab one-shot ms | ratio | kept stream ms | ratio | batch of 8, "
                                 "ms/rotation | ratio | 2 threads: speed-up | peak RSS |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < NL; k++)
        tl += (size_t)snprintf(tab + tl, sizeof tab - tl,
                               "| %d | %.3g | %.3g | %.3f [%.3f, %.3f] | %.3g | %.3f [%.3f, %.3f] | %.3g | %.3f [%.3f, %.3f] | %.2f [%.2f, %.2f] | %.1f MiB |\n",
                               HP_LMAX[k], 1e3 * median_of(hp->h[k], hp->nrep[k]), 1e3 * median_of(hp->o[k], hp->nrep[k]),
                               R[k][0].median, R[k][0].q1, R[k][0].q3, 1e3 * median_of(hp->u[k], hp->nrep[k]),
                               R[k][1].median, R[k][1].q1, R[k][1].q3, 1e3 * median_of(hp->b[k], hp->nrep[k]),
                               R[k][2].median, R[k][2].q1, R[k][2].q3, SP[k].median, SP[k].q1, SP[k].q3, hp->rss[k]);
    char tab2[2048];
    size_t t2 = (size_t)snprintf(tab2, sizeof tab2, "| grid | lmax | channels | transform | shlab ms | libsharp ms | ratio |\n|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < sr->nrow; i++) {
        const sharp_row *q = &sr->row[i];
        t2 += (size_t)snprintf(tab2 + t2, sizeof tab2 - t2, "| %s | %d | %d | %s | %.3g | %.3g | %.3f [%.3f, %.3f] |\n",
                               q->grid, q->lmax, q->channels, q->transform, q->shlab_ms, q->peer_ms, q->ratio, q->q1, q->q3);
    }
    char noise_text[512];
    if (noisy_load_hp || noisy_load_sh)
        snprintf(noise_text, sizeof noise_text,
                 "**Noisy run**: other processes used %.2f CPUs on average while `peer_healpix_bench` ran (%.0f s) and "
                 "%.2f while `bench --peers` ran (%.0f s), above the criterion's %.2f, so the speed claims are "
                 "recorded as not measured; the ratios above are what this run saw, not verdicts",
                 hp->noise.load, hp->noise.seconds, sr->noise.load, sr->noise.seconds, LOAD_MAX);
    else
        snprintf(noise_text, sizeof noise_text,
                 "Other processes used %.2f CPUs on average while `peer_healpix_bench` ran (%.0f s) and %.2f while "
                 "`bench --peers` ran (%.0f s); a claim whose ratio spreads (quartiles) by more than 5%% of its "
                 "median is still recorded as not measured",
                 hp->noise.load, hp->noise.seconds, sr->noise.load, sr->noise.seconds);
    exp_index("shlab against its peers in one process each, ratio = shlab / peer per repetition (median "
              "[quartile 1, quartile 3]). The all-band rotation against HEALPix C++ `rotate_alm` "
              "(`build/peers/peer_healpix_bench --lmax 100,300,1000 --threads 1 --speedup 2 --tsv`; one thread, "
              "interleaved; %d, %d and %d repetitions; [healpix.dat](healpix.dat), [speedup.dat](speedup.dat), "
              "[rss.dat](rss.dat)): one-shot = `sh_rot_stream_create` + apply + free; kept stream = one rotation "
              "with the stream created once; batch of 8 = eight rotations of one vector in one call, time per "
              "rotation; the speed-up is shlab's 1-thread time over its 2-thread time, interleaved; peak RSS of a "
              "fresh process doing one one-shot rotation on 1 thread.\n\n%s\n"
              "The transforms against libsharp (`shlab bench --peers --lmax 255,511,1023 --latlong 1024 --repeat 21 "
              "--threads 1`; thread CPU clock, 21 repeats, alternating who goes first; shlab's kernels %s; "
              "[sharp.dat](sharp.dat)):\n\n%s\n"
              "![ratios against the peers](highband_peers_ratios.png)\n\n"
              "%s ([noise.dat](noise.dat)). Goals: one-shot ≤ 0.05, kept ≤ 0.1 at lmax 1000; ≤ 0.9 against "
              "libsharp at lmax 511 and 1023 (Gauss grid); ≥ 1.8 on 2 threads; peak RSS ≤ 64 MB.\n\n"
              "How close the two high-band kernels come to the core's limit ([flops.dat](flops.dat)): their nominal "
              "flops (a transform: 7 a ring pair and (l, m), the recursion's multiply and fused multiply-subtract "
              "and two fused multiply-adds; the rotation: 7 (l+1)² a band, rot_halfpi.c) over the median times "
              "above, against this core's peak as measured here, %.1f GFlop/s (%s: 16 independent chains of fused "
              "multiply-adds, best of 5). Nominal: both kernels skip work that adds nothing (rings and rows below "
              "their thresholds), and the times include the FFTs and reordering.\n\n%s",
              hp->nrep[0], hp->nrep[1], hp->nrep[2], tab, sr->kernel, tab2, noise_text, peak, pisa, ftab);
    exp_part(NULL);
}

/* The timing part when the peers are not there: a note, and no stale data. */
static void timing_absent(const char *why)
{
    exp_part("timing");
    static const char *const files[] = {"healpix.dat", "sharp.dat", "speedup.dat", "rss.dat", "noise.dat",
                                        "highband_peers_ratios.png"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char p[4200];
        snprintf(p, sizeof p, "%s/%s", exp_outdir(), files[i]);
        remove(p);
    }
    exp_index("Not measured on this machine: %s.", why);
    exp_part(NULL);
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    memory_part();
    roundtrip_part();

    const char *build = getenv("BUILD") && *getenv("BUILD") ? getenv("BUILD") : "build";
    const char *shlab = getenv("SHLAB") && *getenv("SHLAB") ? getenv("SHLAB") : "build/shlab";
    char hpbin[4096];
    if (getenv("PEER_HEALPIX_BENCH") && *getenv("PEER_HEALPIX_BENCH"))
        snprintf(hpbin, sizeof hpbin, "%s", getenv("PEER_HEALPIX_BENCH"));
    else
        snprintf(hpbin, sizeof hpbin, "%s/peers/peer_healpix_bench", build);
    /* libsharp: bench --peers says so (exit 2) when shlab was built without it */
    char probe[4200], out[512] = "";
    snprintf(probe, sizeof probe, "'%s' bench --peers --lmax 3 --repeat 1 --quiet --format json 2>&1", shlab);
    FILE *p = popen(probe, "r");
    const size_t got = p ? fread(out, 1, sizeof out - 1, p) : 0;
    out[got] = 0;
    const int sharp_rc = p ? pclose(p) : -1;
    const int have_hp = access(hpbin, X_OK) == 0, have_sharp = sharp_rc == 0;
    if (!have_hp || !have_sharp) {
        char why[512];
        snprintf(why, sizeof why, "%s%s%s not found (%s)", have_hp ? "" : "HEALPix C++",
                 !have_hp && !have_sharp ? " and " : "", have_sharp ? "" : "libsharp",
                 !have_hp ? "no peer_healpix_bench: `make` builds it when pkg-config finds healpix_cxx, Debian "
                            "libhealpix-cxx-dev"
                          : strstr(out, "libsharp") ? "`shlab bench --peers`: built without libsharp, Debian libsharp-dev"
                                                    : "`shlab bench --peers` failed");
        fprintf(stderr, "highband_peers: peers skipped: %s; peers/ kept as it is\n", why);
        timing_absent(why);
        return 0;
    }
    exp_progress("highband_peers: libsharp: shlab bench --peers --lmax 255,511 --latlong 1024 (a few seconds)");
    static sharp_result sr;
    if (!run_sharp(shlab, &sr)) fail("shlab bench --peers --format json failed or printed no usable rows");
    exp_progress("highband_peers: HEALPix C++: %s --lmax 100,300,1000 (about a minute; rotate_alm at lmax 1000 "
                 "takes seconds a call)", hpbin);
    static hp_result hp;
    if (!run_healpix(hpbin, &hp)) fail("peer_healpix_bench --tsv failed or printed no usable rows");
    peers_part(&hp, &sr);
    timing_part(&hp, &sr);
    return 0;
}
