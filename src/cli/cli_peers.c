/* cli_peers.c — `shlab bench --peers` (and `make bench-peers`): shlab's
 * spherical harmonic transforms against libsharp's, timed interleaved in one
 * process on the same rings, with the ratio of every repeat and the
 * agreement of the results. */
#include "cli.h"

#include "measure/peers/peer_sharp.h"
#include "project/sht_internal.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PEERS_MAX_LMAX 16 /* --lmax: values in one run */

typedef struct {
    int n, v[PEERS_MAX_LMAX];
} peers_lmax;

typedef struct {
    peers_lmax lmax;
    int latlong, repeat, threads, quiet, fmt, peers;
    sht_isa isa;
} peers_args;

static int parse_lmax(const char *opt, const char *s, void *field)
{
    peers_lmax *l = field;
    double *v;
    int n, rc = 0;
    if (cli_doubles(opt, s, &v, &n)) return CLI_EXIT_USAGE;
    if (n < 1 || n > PEERS_MAX_LMAX) rc = cli_fail("%s: give 1 to %d values", opt, PEERS_MAX_LMAX);
    for (int k = 0; k < n && !rc; k++)
        if (!(v[k] >= 0 && v[k] <= SHLAB_MAX_ORDER - 1) || v[k] != floor(v[k]))
            rc = cli_fail("%s: each value must be an integer in 0..%d", opt, SHLAB_MAX_ORDER - 1);
    for (int k = 0; k < n && !rc; k++) l->v[k] = (int)v[k];
    if (!rc) l->n = n;
    free(v);
    return rc;
}

/* --kernel: shlab's Legendre kernels by name, built in and run by this CPU */
static int parse_isa(const char *opt, const char *s, void *field)
{
    sht_isa *isa = field;
    for (int k = SHT_ISA_BASE; k <= SHT_ISA_AVX512; k++)
        if (!strcmp(s, sh__sht_isa_name((sht_isa)k))) {
            if (!sh__sht_isa_usable((sht_isa)k)) return cli_fail("%s %s: not built in or not run by this CPU", opt, s);
            *isa = (sht_isa)k;
            return 0;
        }
    return cli_fail("%s: '%s' (expected baseline, avx2+fma or avx512f)", opt, s);
}

static const cli_opt peers_opts[] = {
    CLI_FLAG(peers_args, peers, "peers", "this comparison"),
    CLI_CUSTOM(peers_args, lmax, "lmax", "LIST", parse_lmax, "255,511", "band limits (comma separated)"),
    CLI_INT(peers_args, latlong, "latlong", "W", 2, 8192, NULL, "also a W × W/2 lat-long map of 3 channels"),
    CLI_INT(peers_args, repeat, "repeat", "R", 1, 1000, "11", "timed repeats"),
    CLI_INT(peers_args, threads, "threads", "N", 0, 1024, "1", "threads of both libraries (0: all cores)"),
    CLI_CUSTOM(peers_args, isa, "kernel", "K", parse_isa, NULL,
               "shlab's Legendre kernels: baseline, avx2+fma or avx512f\n"
               "(default: the widest this CPU runs)"),
    CLI_FLAG(peers_args, quiet, "quiet", "no progress on stderr"),
    CLI_FORMAT(peers_args, fmt),
    CLI_END,
};

static const cli_cmd peers_decl = {
    .name = "bench",
    .usage = "bench --peers [--lmax LIST] [--latlong W] [--repeat R] [--threads N]\n"
             "                           [OPTIONS]",
    .about =
        "Time shlab's spherical harmonic transforms against libsharp's (the peer),\n"
        "interleaved in one process: analysis (shlab sh_sht_analysis, libsharp\n"
        "map2alm) and synthesis (sh_sht_synthesis, alm2map) of order lmax+1 on\n"
        "libsharp's Gauss-Legendre grid, lmax+1 rings × 2·lmax+2 points, both given\n"
        "exactly the same rings and map; with --latlong W also on the W × W/2\n"
        "lat-long grid of an environment map, 3 channels (shlab: one transform of\n"
        "3 channels; libsharp: 3 calls; libsharp gets θ = acos(cosθ) and recomputes\n"
        "cosθ, so its rings differ from shlab's by an ulp).  Each repeat times the calls once,\n"
        "alternating which library goes first; ms are medians over the repeats,\n"
        "ratio = shlab / libsharp per repeat (median, quartiles, min, max), so that\n"
        "a load shared by both sides cancels; min_ratio = the ratio of the fastest runs.\n"
        "With --threads 1 the clock is the thread's CPU time (both libraries run on\n"
        "the calling thread; time spent descheduled by other processes does not\n"
        "count), otherwise wall time.  agreement = ‖shlab − libsharp‖₂ / ‖libsharp‖₂\n"
        "of the coefficients (analysis) or map values (synthesis) of the first\n"
        "repeat; max_rel = max|shlab − libsharp| / max|libsharp|.\n",
    .opts = peers_opts,
    .notes = "JSON: {\"peer\",\"threads\",\"repeat\",\"clock\",\"kernel\",\"rows\":[{\"lmax\",\"grid\",\n"
             "       \"channels\",\"transform\",\"shlab_ms\",\"peer_ms\",\"ratio\",\"ratio_min\",\n"
             "       \"ratio_max\",\"ratio_q1\",\"ratio_q3\",\"min_ratio\",\"agreement\",\"max_rel\"}]}\n",
};

/* With one thread both libraries run on the calling thread, so its CPU time
 * is what each call cost, whatever else the machine runs; with more, wall time. */
static double now_s(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct {
    double shlab_ms, peer_ms, ratio, ratio_min, ratio_max, ratio_q1, ratio_q3, min_ratio, agree, max_rel;
} peer_row;

/* One case: libsharp's Gauss grid (width 0) or a lat-long width × width/2
 * environment map of nchan channels (libsharp: one call per channel). */
typedef struct {
    int lmax, width, nchan;
} peer_case;

static double lcg(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) * 0x1p-52 - 1.0; /* [-1, 1) */
}

/* One case set up: both libraries on the same rings, the seeded map and
 * coefficients (nc channels), and each side's outputs. */
typedef struct {
    sh_peer_sharp *ps;
    sh_sht *p;
    int nn, nc;
    size_t nm; /* points of one map */
    double *x; /* the rings: cosθ, then sinθ (or libsharp's) */
    double *map, *map2, *m1, *c, *c2, *k1;
} peer_ctx;

static void peer_free(peer_ctx *k)
{
    sh_sht_destroy(k->p);
    sh_peer_sharp_destroy(k->ps);
    free(k->x), free(k->map), free(k->map2), free(k->m1), free(k->c), free(k->c2), free(k->k1);
}

/* libsharp's Gauss grid (width 0) or the lat-long width × width/2 map. */
static int peer_grid(const peer_case *pc, peer_ctx *k, sh_grid *g)
{
    int nr, np, st;
    double phi0 = 0.0;
    if (pc->width) {
        nr = pc->width / 2, np = pc->width;
        if (!(k->x = malloc(sizeof(double) * nr * 2))) return sh_error(SH_ENOMEM, "out of memory");
        sh_grid_latlong(np, nr, k->x, k->x + nr, g);
        st = sh_peer_sharp_grid(pc->lmax, g, &k->ps);
    } else if (!(st = sh_peer_sharp_gauss(pc->lmax, &k->ps))) {
        sh_peer_sharp_rings(k->ps, &nr, &np, NULL, NULL, &phi0);
        if (!(k->x = malloc(sizeof(double) * nr * 2))) return sh_error(SH_ENOMEM, "out of memory");
        sh_peer_sharp_rings(k->ps, &nr, &np, k->x, k->x + nr, &phi0);
        *g = (sh_grid){nr, np, k->x, k->x + nr, phi0};
    }
    k->nm = st ? 0 : (size_t)nr * np;
    return st;
}

static int peer_setup(const peer_case *pc, int threads, sht_isa isa, peer_ctx *k)
{
    const int order = pc->lmax + 1;
    *k = (peer_ctx){.nn = order * order, .nc = pc->nchan};
    sh_grid g;
    int st = peer_grid(pc, k, &g);
    if (st) return cli_fail_status(st);
    const size_t nm = k->nm * k->nc, nn = (size_t)k->nn * k->nc;
    k->map = malloc(sizeof(double) * nm);
    k->map2 = malloc(sizeof(double) * nm);
    k->m1 = malloc(sizeof(double) * nm);
    k->c = malloc(sizeof(double) * nn);
    k->c2 = malloc(sizeof(double) * nn);
    k->k1 = malloc(sizeof(double) * nn);
    if (!k->map || !k->map2 || !k->m1 || !k->c || !k->c2 || !k->k1)
        return cli_fail("bench --peers: out of memory at lmax %d", pc->lmax);
    if ((st = sh_sht_create(order, &g, k->nc, threads, &k->p)) || (isa && (st = sh__sht_set_isa(k->p, isa))))
        return cli_fail_status(st);
    sh_peer_sharp_threads(threads);
    unsigned long seed = 12345; /* a seeded map and coefficient vector */
    for (size_t i = 0; i < nm; i++) k->map[i] = lcg(&seed);
    for (size_t i = 0; i < nn; i++) k->c[i] = lcg(&seed);
    return 0;
}

/* agreement: each side into its own buffers */
static int peer_agreement(peer_ctx *k, peer_row rows[2])
{
    int st = sh_sht_analysis(k->p, SH_CS, k->map, k->c2);
    if (!st) st = sh_sht_synthesis(k->p, SH_CS, k->c, k->map2);
    if (st) return cli_fail_status(st);
    for (int ch = 0; ch < k->nc; ch++) {
        sh_peer_sharp_map2alm(k->ps, k->map + ch * k->nm);
        sh_peer_sharp_get_cs(k->ps, k->k1 + (size_t)ch * k->nn);
        sh_peer_sharp_set_cs(k->ps, k->c + (size_t)ch * k->nn);
        sh_peer_sharp_alm2map(k->ps, k->m1 + ch * k->nm);
    }
    sh_peer_agreement(k->c2, k->k1, (size_t)k->nn * k->nc, &rows[0].agree, &rows[0].max_rel);
    sh_peer_agreement(k->map2, k->m1, k->nm * k->nc, &rows[1].agree, &rows[1].max_rel);
    return 0;
}

/* The repeats: t[0..4·repeat) = shlab analysis, libsharp analysis, shlab
 * synthesis, libsharp synthesis (seconds), the calls of each repeat in
 * alternating order (the first one untimed, a warm-up). */
static int peer_time(peer_ctx *k, int repeat, clockid_t clock, double *t)
{
    double *ts = t, *tp = t + repeat, *us = t + 2 * repeat, *up = t + 3 * repeat;
    for (int r = -1; r < repeat; r++) { /* r = −1: warm-up */
        for (int side = 0; side < 2; side++) {
            const int first = (r & 1) ? !side : side; /* alternate who goes first */
            if (first == 0) {
                const double a0 = now_s(clock);
                int st = sh_sht_analysis(k->p, SH_CS, k->map, k->c2);
                const double a1 = now_s(clock);
                st = st ? st : sh_sht_synthesis(k->p, SH_CS, k->c, k->map2);
                const double a2 = now_s(clock);
                if (st) return cli_fail_status(st);
                if (r >= 0) ts[r] = a1 - a0, us[r] = a2 - a1;
                continue;
            }
            double ta = 0.0, tb = 0.0; /* libsharp's layout conversions not timed */
            for (int ch = 0; ch < k->nc; ch++) {
                const double b0 = now_s(clock);
                sh_peer_sharp_map2alm(k->ps, k->map + ch * k->nm);
                const double b1 = now_s(clock);
                sh_peer_sharp_set_cs(k->ps, k->c + (size_t)ch * k->nn);
                const double b2 = now_s(clock);
                sh_peer_sharp_alm2map(k->ps, k->map2 + ch * k->nm);
                const double b3 = now_s(clock);
                ta += b1 - b0;
                tb += b3 - b2;
            }
            if (r >= 0) tp[r] = ta, up[r] = tb;
        }
    }
    return 0;
}

/* rows[0] analysis, rows[1] synthesis from the times (sorted in place). */
static void peer_stats(double *t, int repeat, peer_row rows[2])
{
    double rat[2][1000];
    for (int k = 0; k < 2; k++) {
        double *num = t + 2 * k * repeat, *den = num + repeat, *r = rat[k];
        for (int i = 0; i < repeat; i++) r[i] = num[i] / den[i];
        sh_bench_ratio q; /* quartiles of the per-repeat ratios (the engine's rule) */
        if (sh_bench_paired_ratio(num, den, repeat, 0, &q)) q.q1 = q.q3 = NAN;
        qsort(r, (size_t)repeat, sizeof *r, cli_cmp_double);
        rows[k].ratio_q1 = isnan(q.q1) ? r[0] : q.q1;
        rows[k].ratio_q3 = isnan(q.q3) ? r[repeat - 1] : q.q3;
        rows[k].ratio_min = r[0];
        rows[k].ratio_max = r[repeat - 1];
        rows[k].ratio = cli_median(r, repeat);
        rows[k].shlab_ms = 1e3 * cli_median(num, repeat); /* sorts num, den */
        rows[k].peer_ms = 1e3 * cli_median(den, repeat);
        rows[k].min_ratio = num[0] / den[0];
    }
}

/* Time one case; rows[0] analysis, rows[1] synthesis. */
static int time_case(const peer_case *pc, const peers_args *a, const char **kernel, peer_row rows[2])
{
    peer_ctx k;
    double *t = malloc(sizeof(double) * a->repeat * 4);
    int rc = t ? peer_setup(pc, a->threads, a->isa, &k) : cli_fail("bench --peers: out of memory");
    if (!rc) *kernel = sh_sht_kernel_name(k.p);
    if (!rc) rc = peer_agreement(&k, rows);
    if (!rc) rc = peer_time(&k, a->repeat, a->threads == 1 ? CLOCK_THREAD_CPUTIME_ID : CLOCK_MONOTONIC, t);
    if (!rc) peer_stats(t, a->repeat, rows);
    if (t) peer_free(&k);
    free(t);
    return rc;
}

static json_t *row_json(const peer_case *pc, int t, const peer_row *pr)
{
    char grid[48];
    if (pc->width) snprintf(grid, sizeof grid, "latlong %dx%d", pc->width, pc->width / 2);
    else snprintf(grid, sizeof grid, "gauss %dx%d", pc->lmax + 1, 2 * pc->lmax + 2);
    json_t *row = json_object();
    row = cli_put(row, "lmax", json_integer(pc->lmax));
    row = cli_put(row, "grid", json_string(grid));
    row = cli_put(row, "channels", json_integer(pc->nchan));
    row = cli_put(row, "transform", json_string(t ? "synthesis" : "analysis"));
    row = cli_put(row, "shlab_ms", json_real(pr->shlab_ms));
    row = cli_put(row, "peer_ms", json_real(pr->peer_ms));
    row = cli_put(row, "ratio", json_real(pr->ratio));
    row = cli_put(row, "ratio_min", json_real(pr->ratio_min));
    row = cli_put(row, "ratio_max", json_real(pr->ratio_max));
    row = cli_put(row, "ratio_q1", json_real(pr->ratio_q1));
    row = cli_put(row, "ratio_q3", json_real(pr->ratio_q3));
    row = cli_put(row, "min_ratio", json_real(pr->min_ratio));
    row = cli_put(row, "agreement", json_real(pr->agree));
    return cli_put(row, "max_rel", json_real(pr->max_rel));
}

int cli_bench_peers(const cli_command *bench, int argc, char **argv)
{
    (void)bench; /* its own declaration: --help here is this comparison's */
    peers_args a = {.isa = SHT_ISA_AUTO};
    cli_parsed seen;
    int rc = cli_args_parse(&peers_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!sh_peer_sharp_available())
        return cli_fail("bench --peers: libsharp was not found when shlab was built (Debian: libsharp-dev)");
    json_t *rows = json_array();
    const char *kernel = "";
    cli_progress prog;
    cli_progress_start(&prog, "bench", a.quiet);
    const int nl = a.lmax.n, ncase = a.latlong ? 2 * nl : nl;
    for (int k = 0; k < ncase && rows; k++) {
        const peer_case pc = {a.lmax.v[k % nl], k < nl ? 0 : a.latlong, k < nl ? 1 : 3};
        peer_row pr[2];
        if ((rc = time_case(&pc, &a, &kernel, pr))) {
            json_decref(rows);
            return rc;
        }
        for (int t = 0; t < 2 && rows; t++) {
            json_t *row = row_json(&pc, t, &pr[t]);
            if (!row || json_array_append_new(rows, row)) {
                json_decref(rows);
                rows = NULL;
            }
        }
        cli_progress_step(&prog, k + 1, ncase, "cases");
    }
    json_t *root = json_object();
    root = cli_put(root, "peer", json_string("libsharp"));
    root = cli_put(root, "threads", json_integer(a.threads));
    root = cli_put(root, "repeat", json_integer(a.repeat));
    root = cli_put(root, "clock", json_string(a.threads == 1 ? "thread-cpu" : "wall"));
    root = cli_put(root, "kernel", json_string(kernel));
    root = cli_put(root, "rows", rows);
    return cli_emit(root, (cli_format)a.fmt);
}
