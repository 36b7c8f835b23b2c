/* cli_peers.c — `shlab bench --peers` (and `make bench-peers`): shlab's
 * spherical harmonic transforms against libsharp's, timed interleaved in one
 * process on the same rings, with the ratio of every repeat and the
 * agreement of the results. */
#include "cli.h"

#include "measure/peers/peer_sharp.h"
#include "project/sht_internal.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char help[] =
    "Usage: shlab bench --peers [--lmax LIST] [--latlong W] [--repeat R] [--threads N]\n"
    "                           [OPTIONS]\n"
    "\n"
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
    "repeat; max_rel = max|shlab − libsharp| / max|libsharp|.\n"
    "\n"
    "  --lmax LIST        band limits (comma separated; default 255,511)\n"
    "  --latlong W        also a W × W/2 lat-long map of 3 channels (2..8192)\n"
    "  --repeat R         timed repeats (default 11)\n"
    "  --threads N        threads of both libraries (default 1; 0: all cores)\n"
    "  --kernel K         shlab's Legendre kernels: baseline, avx2+fma or avx512f\n"
    "                     (default: the widest this CPU runs)\n"
    "  --quiet            no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help             this text\n"
    "\n"
    "JSON: {\"peer\",\"threads\",\"repeat\",\"clock\",\"kernel\",\"rows\":[{\"lmax\",\"grid\",\n"
    "       \"channels\",\"transform\",\"shlab_ms\",\"peer_ms\",\"ratio\",\"ratio_min\",\n"
    "       \"ratio_max\",\"ratio_q1\",\"ratio_q3\",\"min_ratio\",\"agreement\",\"max_rel\"}]}\n";

/* With one thread both libraries run on the calling thread, so its CPU time
 * is what each call cost, whatever else the machine runs; with more, wall time. */
static clockid_t bench_clock = CLOCK_MONOTONIC;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(bench_clock, &t);
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

/* Time one case; rows[0] analysis, rows[1] synthesis. */
static int time_case(const peer_case *pc, int repeat, int threads, sht_isa isa, const char **kernel,
                     peer_row rows[2])
{
    const int lmax = pc->lmax, order = lmax + 1, nn = order * order, nc = pc->nchan;
    sh_peer_sharp *ps = NULL;
    sh_sht *p = NULL;
    int nr, np, st, rc = 0;
    double phi0 = 0.0, *x = NULL, *map = NULL, *map2 = NULL, *c = NULL, *c2 = NULL, *t = NULL;
    double *m1 = NULL, *k1 = NULL;
    sh_grid g;
    if (pc->width) {
        nr = pc->width / 2, np = pc->width;
        x = malloc(sizeof(double) * nr * 2);
        if (!x) return cli_fail("bench --peers: out of memory");
        sh_grid_latlong(np, nr, x, x + nr, &g);
        st = sh_peer_sharp_grid(lmax, &g, &ps);
    } else {
        st = sh_peer_sharp_gauss(lmax, &ps);
        if (!st) {
            sh_peer_sharp_rings(ps, &nr, &np, NULL, NULL, &phi0);
            x = malloc(sizeof(double) * nr * 2);
            if (!x) st = sh_error(SH_ENOMEM, "out of memory");
            else sh_peer_sharp_rings(ps, &nr, &np, x, x + nr, &phi0);
            g = (sh_grid){nr, np, x, x + nr, phi0};
        }
    }
    if (st) {
        rc = cli_fail_status(st);
        goto out;
    }
    const size_t nm = (size_t)nr * np;
    map = malloc(sizeof(double) * nm * nc);
    map2 = malloc(sizeof(double) * nm * nc);
    m1 = malloc(sizeof(double) * nm * nc);
    c = malloc(sizeof(double) * nn * nc);
    c2 = malloc(sizeof(double) * nn * nc);
    k1 = malloc(sizeof(double) * nn * nc);
    t = malloc(sizeof(double) * repeat * 6);
    if (!map || !map2 || !m1 || !c || !c2 || !k1 || !t) {
        rc = cli_fail("bench --peers: out of memory at lmax %d", lmax);
        goto out;
    }
    if ((st = sh_sht_create(order, &g, nc, threads, &p)) || (isa && (st = sh__sht_set_isa(p, isa)))) {
        rc = cli_fail_status(st);
        goto out;
    }
    *kernel = sh_sht_kernel_name(p);
    sh_peer_sharp_threads(threads);
    unsigned long seed = 12345; /* a seeded map and coefficient vector */
    for (size_t i = 0; i < nm * nc; i++) map[i] = lcg(&seed);
    for (size_t i = 0; i < (size_t)nn * nc; i++) c[i] = lcg(&seed);
    /* agreement: each side into its own buffers */
    if ((st = sh_sht_analysis(p, SH_CS, map, c2)) || (st = sh_sht_synthesis(p, SH_CS, c, map2))) {
        rc = cli_fail_status(st);
        goto out;
    }
    for (int ch = 0; ch < nc; ch++) {
        sh_peer_sharp_map2alm(ps, map + ch * nm);
        sh_peer_sharp_get_cs(ps, k1 + (size_t)ch * nn);
        sh_peer_sharp_set_cs(ps, c + (size_t)ch * nn);
        sh_peer_sharp_alm2map(ps, m1 + ch * nm);
    }
    sh_peer_agreement(c2, k1, (size_t)nn * nc, &rows[0].agree, &rows[0].max_rel);
    sh_peer_agreement(map2, m1, nm * nc, &rows[1].agree, &rows[1].max_rel);
    double *ts = t, *tp = t + repeat, *us = t + 2 * repeat, *up = t + 3 * repeat;
    double *ra = t + 4 * repeat, *rs = t + 5 * repeat;
    for (int r = -1; r < repeat; r++) { /* r = −1: warm-up */
        for (int side = 0; side < 2; side++) {
            const int first = (r & 1) ? !side : side; /* alternate who goes first */
            if (first == 0) {
                const double a0 = now_s();
                st = sh_sht_analysis(p, SH_CS, map, c2);
                const double a1 = now_s();
                st = st ? st : sh_sht_synthesis(p, SH_CS, c, map2);
                const double a2 = now_s();
                if (r >= 0) ts[r] = a1 - a0, us[r] = a2 - a1;
            } else {
                double ta = 0.0, tb = 0.0; /* libsharp's layout conversions not timed */
                for (int ch = 0; ch < nc; ch++) {
                    const double b0 = now_s();
                    sh_peer_sharp_map2alm(ps, map + ch * nm);
                    const double b1 = now_s();
                    sh_peer_sharp_set_cs(ps, c + (size_t)ch * nn);
                    const double b2 = now_s();
                    sh_peer_sharp_alm2map(ps, map2 + ch * nm);
                    const double b3 = now_s();
                    ta += b1 - b0;
                    tb += b3 - b2;
                }
                if (r >= 0) tp[r] = ta, up[r] = tb;
            }
            if (st) {
                rc = cli_fail_status(st);
                goto out;
            }
        }
        if (r >= 0) {
            ra[r] = ts[r] / tp[r];
            rs[r] = us[r] / up[r];
        }
    }
    for (int k = 0; k < 2; k++) {
        double *num = k ? us : ts, *den = k ? up : tp, *rat = k ? rs : ra;
        sh_bench_ratio q; /* quartiles of the per-repeat ratios (the engine's rule) */
        if (sh_bench_paired_ratio(num, den, repeat, 0, &q)) q.q1 = q.q3 = NAN;
        qsort(rat, (size_t)repeat, sizeof *rat, cli_cmp_double);
        rows[k].ratio_q1 = isnan(q.q1) ? rat[0] : q.q1;
        rows[k].ratio_q3 = isnan(q.q3) ? rat[repeat - 1] : q.q3;
        rows[k].ratio_min = rat[0];
        rows[k].ratio_max = rat[repeat - 1];
        rows[k].ratio = cli_median(rat, repeat);
        rows[k].shlab_ms = 1e3 * cli_median(num, repeat); /* sorts num, den */
        rows[k].peer_ms = 1e3 * cli_median(den, repeat);
        rows[k].min_ratio = num[0] / den[0];
    }
out:
    sh_sht_destroy(p);
    sh_peer_sharp_destroy(ps);
    free(x), free(map), free(map2), free(m1), free(c), free(c2), free(k1), free(t);
    return rc;
}

int cli_bench_peers(const cli_command *bench, int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         {"peers", no_argument, 0, 'P'},
                                         {"lmax", required_argument, 0, 'l'},
                                         {"repeat", required_argument, 0, 'r'},
                                         {"threads", required_argument, 0, 'T'},
                                         {"latlong", required_argument, 0, 'W'},
                                         {"kernel", required_argument, 0, 'K'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    int lmaxs[16] = {255, 511}, nl = 2, repeat = 11, threads = 1, quiet = 0, width = 0;
    sht_isa isa = SHT_ISA_AUTO;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'h': fputs(help, stdout); return fflush(stdout) ? CLI_EXIT_USAGE : CLI_EXIT_OK;
        case 'P': break;
        case 'l': {
            double *v;
            int n;
            if (cli_doubles("--lmax", optarg, &v, &n)) return CLI_EXIT_USAGE;
            if (n < 1 || n > 16) {
                free(v);
                return cli_fail("--lmax: give 1 to 16 values");
            }
            for (int k = 0; k < n; k++)
                if (!(v[k] >= 0 && v[k] <= SHLAB_MAX_ORDER - 1) || v[k] != floor(v[k])) {
                    free(v);
                    return cli_fail("--lmax: each value must be an integer in 0..%d", SHLAB_MAX_ORDER - 1);
                }
            for (int k = 0; k < n; k++) lmaxs[k] = (int)v[k];
            nl = n;
            free(v);
            break;
        }
        case 'r':
            if (cli_int("--repeat", optarg, &repeat)) return CLI_EXIT_USAGE;
            if (repeat < 1 || repeat > 1000) return cli_fail("--repeat must be in 1..1000, got %d", repeat);
            break;
        case 'T':
            if (cli_int("--threads", optarg, &threads)) return CLI_EXIT_USAGE;
            if (threads < 0 || threads > 1024) return cli_fail("--threads must be in 0..1024, got %d", threads);
            break;
        case 'W':
            if (cli_int("--latlong", optarg, &width)) return CLI_EXIT_USAGE;
            if (width < 2 || width > 8192) return cli_fail("--latlong must be in 2..8192, got %d", width);
            break;
        case 'K': {
            int found = 0;
            for (int k = SHT_ISA_BASE; k <= SHT_ISA_AVX512; k++)
                if (!strcmp(optarg, sh__sht_isa_name((sht_isa)k))) isa = (sht_isa)k, found = 1;
            if (!found) return cli_fail("--kernel: '%s' (expected baseline, avx2+fma or avx512f)", optarg);
            if (!sh__sht_isa_usable(isa)) return cli_fail("--kernel %s: not built in or not run by this CPU", optarg);
            break;
        }
        case 'q': quiet = 1; break;
        default: {
            const int r = cli_common_opt(bench, o, argv, &com);
            if (r >= 0) return r;
        }
        }
    }
    if (optind < argc) return cli_fail("bench: unexpected argument '%s'", argv[optind]);
    if (!sh_peer_sharp_available())
        return cli_fail("bench --peers: libsharp was not found when shlab was built (Debian: libsharp-dev)");
    bench_clock = threads == 1 ? CLOCK_THREAD_CPUTIME_ID : CLOCK_MONOTONIC;
    json_t *rows = json_array();
    const char *kernel = "";
    cli_progress prog;
    cli_progress_start(&prog, "bench", quiet);
    const int ncase = width ? 2 * nl : nl;
    for (int k = 0; k < ncase && rows; k++) {
        const peer_case pc = {lmaxs[k % nl], k < nl ? 0 : width, k < nl ? 1 : 3};
        peer_row pr[2];
        const int rc = time_case(&pc, repeat, threads, isa, &kernel, pr);
        if (rc) {
            json_decref(rows);
            return rc;
        }
        char grid[48];
        if (pc.width) snprintf(grid, sizeof grid, "latlong %dx%d", pc.width, pc.width / 2);
        else snprintf(grid, sizeof grid, "gauss %dx%d", pc.lmax + 1, 2 * pc.lmax + 2);
        for (int t = 0; t < 2 && rows; t++) {
            json_t *row = json_object();
            row = cli_put(row, "lmax", json_integer(pc.lmax));
            row = cli_put(row, "grid", json_string(grid));
            row = cli_put(row, "channels", json_integer(pc.nchan));
            row = cli_put(row, "transform", json_string(t ? "synthesis" : "analysis"));
            row = cli_put(row, "shlab_ms", json_real(pr[t].shlab_ms));
            row = cli_put(row, "peer_ms", json_real(pr[t].peer_ms));
            row = cli_put(row, "ratio", json_real(pr[t].ratio));
            row = cli_put(row, "ratio_min", json_real(pr[t].ratio_min));
            row = cli_put(row, "ratio_max", json_real(pr[t].ratio_max));
            row = cli_put(row, "ratio_q1", json_real(pr[t].ratio_q1));
            row = cli_put(row, "ratio_q3", json_real(pr[t].ratio_q3));
            row = cli_put(row, "min_ratio", json_real(pr[t].min_ratio));
            row = cli_put(row, "agreement", json_real(pr[t].agree));
            row = cli_put(row, "max_rel", json_real(pr[t].max_rel));
            if (!row || json_array_append_new(rows, row)) {
                json_decref(rows);
                rows = NULL;
            }
        }
        cli_progress_step(&prog, k + 1, ncase, "cases");
    }
    json_t *root = json_object();
    root = cli_put(root, "peer", json_string("libsharp"));
    root = cli_put(root, "threads", json_integer(threads));
    root = cli_put(root, "repeat", json_integer(repeat));
    root = cli_put(root, "clock", json_string(threads == 1 ? "thread-cpu" : "wall"));
    root = cli_put(root, "kernel", json_string(kernel));
    root = cli_put(root, "rows", rows);
    return cli_emit(root, com.fmt);
}
