/* peer_healpix_bench.cc — shlab's all-band rotation against HEALPix C++
 * rotate_alm, timed in one process, interleaved (`make bench-peers`).
 *
 * For each lmax and thread count, every repetition times, in turn:
 *   healpix   rotate_alm on its a_lm (the copy made outside the timing);
 *   one-shot  sh_rot_stream_create + sh_rot_stream_apply (1 rotation) + free;
 *   reuse     sh_rot_stream_apply with the stream kept (1 rotation);
 *   batch     sh_rot_stream_apply of 8 rotations at once, time per rotation;
 * the ratio shlab / healpix is taken per repetition (the two ran within
 * seconds of each other, so load from other processes hits both alike) and
 * reported as median and range.  Accuracy: the round trip (rotate, rotate
 * back: healpix with the negated angles, shlab with inverse = 1), as max abs
 * error on N(0, 1) coefficients and as ‖error‖₂ / ‖x‖₂.  Peak RSS of a child
 * process that only runs shlab's one-shot rotation (vectors included).
 * Agreement: shlab's rotation against rotate_alm's (one thread each), max
 * abs difference and ‖difference‖₂ / ‖x‖₂.
 *
 * Usage: peer_healpix_bench [--lmax 100,300,1000] [--threads 1,2] [--repeat R]
 *                           [--speedup T1,..] [--shlab-only] [--tsv]
 * (R default: 7; 3 at lmax ≥ 1000, where rotate_alm gets no warm-up call: a
 * call of seconds needs none).  Times in seconds, CLOCK_MONOTONIC.
 * --speedup: the thread counts of shlab's speed-up over 1 thread (default:
 * those of --threads other than 1), from max(R + 2, 15) interleaved pairs.
 * --shlab-only: no HEALPix (at lmax 4000 one rotate_alm takes many minutes):
 * shlab's times, its round trip and its peak RSS.
 * --tsv: machine-readable output instead of the table, every measurement
 * raw (one line per repetition; experiments/highband_peers reads it):
 *   time       lmax threads rep healpix_s oneshot_s reuse_s batch_per_rot_s
 *   speedup    lmax threads rep wall_1_s wall_T_s cpu_1_s cpu_T_s
 *   agreement  lmax max_abs rel_l2
 *   roundtrip  lmax shlab|healpix max_abs rel_l2
 *   rss        lmax threads peak_MB
 * tab-separated, '-' for what was not measured (HEALPix under --shlab-only);
 * lines starting with '#' are comments.
 */
#include "peer_healpix.h"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

static double now()
{
    timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
static double cpu()
{
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
static double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
static std::vector<int> ints(const char *s)
{
    std::vector<int> v;
    for (const char *p = s; *p;) {
        char *e;
        const long x = strtol(p, &e, 10);
        if (e == p) break;
        v.push_back((int)x);
        p = *e == ',' ? e + 1 : e;
    }
    return v;
}
static void fail(const char *what)
{
    fprintf(stderr, "peer_healpix_bench: %s: %s\n", what, sh_last_error());
    exit(2);
}

/* one shlab one-shot rotation, nothing else (run in a fresh process); prints
 * the peak RSS of this process (VmHWM, kB) */
static int rss_child(int lmax, int threads)
{
    const int order = lmax + 1;
    const size_t n = (size_t)order * order;
    std::vector<double> x(n), y(n);
    peer_gauss(1, n, x.data());
    sh_rotation r;
    sh_rotation_from_euler(0.3, 1.1, -0.7, &r);
    sh_rot_stream *s;
    if (sh_rot_stream_create(order, SH_CS, threads, &s) || sh_rot_stream_apply(s, 1, &r, 0, 1, x.data(), y.data()))
        return 1;
    sh_rot_stream_free(s);
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmHWM: %ld kB", &kb) == 1) break;
    if (f) fclose(f);
    printf("%ld\n", kb);
    return kb < 0;
}

/* peak RSS (MB) of a fresh process (this program, re-executed) running only
 * rss_child: the two vectors, the stream's scratch, the loaded libraries */
static double child_rss(int lmax, int threads)
{
    char self[4096], cmd[4200];
    const ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
    if (k <= 0) return -1;
    self[k] = 0;
    snprintf(cmd, sizeof cmd, "'%s' --rss-child %d %d", self, lmax, threads);
    FILE *p = popen(cmd, "r");
    long kb = -1;
    if (!p) return -1;
    if (fscanf(p, "%ld", &kb) != 1) kb = -1;
    if (pclose(p) != 0) return -1;
    return kb / 1024.0;
}

int main(int argc, char **argv)
{
    std::vector<int> lmaxes = {100, 300, 1000}, threads = {1, 2}, speedup;
    int repeat = 0, peer = 1, tsv = 0, have_speedup = 0;
    if (argc == 4 && !strcmp(argv[1], "--rss-child")) return rss_child(atoi(argv[2]), atoi(argv[3]));
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--lmax") && i + 1 < argc) lmaxes = ints(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = ints(argv[++i]);
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--speedup") && i + 1 < argc) speedup = ints(argv[++i]), have_speedup = 1;
        else if (!strcmp(argv[i], "--shlab-only")) peer = 0;
        else if (!strcmp(argv[i], "--tsv")) tsv = 1;
        else {
            fprintf(stderr, "usage: peer_healpix_bench [--lmax L1,L2,..] [--threads T1,T2,..] [--repeat R] "
                            "[--speedup T1,..] [--shlab-only] [--tsv]\n");
            return 2;
        }
    }
    if (!have_speedup)
        for (int t : threads)
            if (t != 1) speedup.push_back(t);
    /* a time, or '-' when not measured (tsv) */
    auto cell = [](double v) {
        char buf[32];
        if (std::isnan(v)) snprintf(buf, sizeof buf, "-");
        else snprintf(buf, sizeof buf, "%.9g", v);
        return std::string(buf);
    };
    if (tsv) {
        printf("# peer_healpix_bench --tsv: shlab halfpi (sh_rot_stream) vs HEALPix C++ rotate_alm; %d cores online\n",
               (int)sysconf(_SC_NPROCESSORS_ONLN));
        printf("# time lmax threads rep healpix_s oneshot_s reuse_s batch_per_rot_s\n"
               "# speedup lmax threads rep wall_1_s wall_T_s cpu_1_s cpu_T_s\n"
               "# agreement lmax max_abs rel_l2\n"
               "# roundtrip lmax shlab|healpix max_abs rel_l2\n"
               "# rss lmax threads peak_MB\n");
    } else {
        printf("# shlab halfpi (sh_rot_stream) vs HEALPix C++ rotate_alm, one process, interleaved\n");
        printf("# %d cores online; times in s (median of R); ratio = shlab / healpix per repetition: median [min, max]\n",
               (int)sysconf(_SC_NPROCESSORS_ONLN));
        printf("%5s %3s %2s %10s %10s %10s %10s  %-26s %-26s %-26s\n", "lmax", "thr", "R", "healpix", "one-shot",
               "reuse", "batch/rot", "ratio one-shot", "ratio reuse", "ratio batch");
    }
    const int nb = 8;
    for (int lmax : lmaxes) {
        const int order = lmax + 1;
        const size_t n = (size_t)order * order;
        std::vector<double> x(n), y(n), z(n), yb(n * nb);
        peer_gauss(42, n, x.data());
        sh_rotation r, rb[nb];
        sh_rotation_from_euler(0.3, 1.1, -0.7, &r);
        for (int k = 0; k < nb; k++) sh_rotation_from_euler(0.3 + 0.1 * k, 1.1 - 0.05 * k, -0.7 + 0.2 * k, &rb[k]);
        peer_alm a0(peer ? lmax : 0, peer ? lmax : 0), a(peer ? lmax : 0, peer ? lmax : 0);
        if (peer) peer_to_alm(lmax, x.data(), a0);
        const int R = repeat > 0 ? repeat : (lmax >= 1000 ? 3 : 7);
        for (int t : threads) {
            omp_set_num_threads(t);
            sh_rot_stream *keep;
            if (sh_rot_stream_create(order, SH_CS, t, &keep)) fail("create");
            /* warm-up: one of each (rotate_alm only below lmax 1000) */
            a = a0;
            if (peer && lmax < 1000) peer_rotate(a, r);
            if (sh_rot_stream_apply(keep, 1, &r, 0, 1, x.data(), y.data())) fail("apply");
            std::vector<double> th, t1, t2, t3, q1, q2, q3;
            for (int rep = 0; rep < R; rep++) {
                a = a0;
                double t0 = now();
                if (peer) peer_rotate(a, r);
                const double h = peer ? now() - t0 : NAN;
                t0 = now();
                sh_rot_stream *s;
                if (sh_rot_stream_create(order, SH_CS, t, &s) || sh_rot_stream_apply(s, 1, &r, 0, 1, x.data(), y.data()))
                    fail("one-shot");
                sh_rot_stream_free(s);
                const double o = now() - t0;
                t0 = now();
                if (sh_rot_stream_apply(keep, 1, &r, 0, 1, x.data(), y.data())) fail("reuse");
                const double u = now() - t0;
                t0 = now();
                if (sh_rot_stream_apply(keep, nb, rb, 0, 1, x.data(), yb.data())) fail("batch");
                const double b = (now() - t0) / nb;
                th.push_back(h), t1.push_back(o), t2.push_back(u), t3.push_back(b);
                if (tsv)
                    printf("time\t%d\t%d\t%d\t%s\t%s\t%s\t%s\n", lmax, t, rep, cell(h).c_str(), cell(o).c_str(),
                           cell(u).c_str(), cell(b).c_str());
                q1.push_back(o / h), q2.push_back(u / h), q3.push_back(b / h);
            }
            sh_rot_stream_free(keep);
            auto rng = [](const std::vector<double> &q) {
                char buf[64];
                snprintf(buf, sizeof buf, "%.3f [%.3f, %.3f]", median(q), *std::min_element(q.begin(), q.end()),
                         *std::max_element(q.begin(), q.end()));
                return std::string(buf);
            };
            if (!tsv)
                printf("%5d %3d %2d %10.4g %10.4g %10.4g %10.4g  %-26s %-26s %-26s\n", lmax, t, R, median(th),
                       median(t1), median(t2), median(t3), rng(q1).c_str(), rng(q2).c_str(), rng(q3).c_str());
            fflush(stdout);
        }
        /* thread scaling of shlab alone: 1 and T threads, interleaved */
        for (int t : speedup) {
            if (t == 1) continue;
            sh_rot_stream *s1, *st;
            if (sh_rot_stream_create(order, SH_CS, 1, &s1) || sh_rot_stream_create(order, SH_CS, t, &st)) fail("create");
            std::vector<double> q, qc;
            /* at least 15 pairs: shlab alone is cheap, and the second core of a
             * shared machine comes and goes, so a few pairs' median is a lottery */
            for (int rep = 0; rep < (R + 2 > 15 ? R + 2 : 15); rep++) {
                double t0 = now(), c0 = cpu();
                sh_rot_stream_apply(s1, 1, &r, 0, 1, x.data(), y.data());
                const double a1 = now() - t0, c1 = cpu() - c0;
                t0 = now(), c0 = cpu();
                sh_rot_stream_apply(st, 1, &r, 0, 1, x.data(), y.data());
                const double at = now() - t0, ct = cpu() - c0;
                q.push_back(a1 / at);
                qc.push_back(ct / c1);
                if (tsv)
                    printf("speedup\t%d\t%d\t%d\t%.9g\t%.9g\t%.9g\t%.9g\n", lmax, t, rep, a1, at, c1, ct);
            }
            sh_rot_stream_free(s1);
            sh_rot_stream_free(st);
            if (tsv) continue;
            printf("%5d shlab speed-up on %d threads (1-thread time / %d-thread time, interleaved): %.2f [%.2f, %.2f]\n",
                   lmax, t, t, median(q), *std::min_element(q.begin(), q.end()), *std::max_element(q.begin(), q.end()));
            /* the CPU time the threads spent (busy or spinning) against one
             * thread's: ~1 means no work was added by splitting, so on idle
             * cores the speed-up would be close to t / this */
            printf("%5d shlab CPU time on %d threads / on 1: %.2f [%.2f, %.2f]\n", lmax, t, median(qc),
                   *std::min_element(qc.begin(), qc.end()), *std::max_element(qc.begin(), qc.end()));
        }
        /* accuracy of the round trip, both sides */
        omp_set_num_threads(1);
        sh_rot_stream *s;
        if (sh_rot_stream_create(order, SH_CS, 1, &s)) fail("create");
        sh_rot_stream_apply(s, 1, &r, 0, 1, x.data(), y.data());
        sh_rot_stream_apply(s, 1, &r, 1, 1, y.data(), z.data());
        sh_rot_stream_free(s);
        std::vector<double> hz(n, NAN), hy(n, NAN);
        if (peer) {
            a = a0;
            peer_rotate(a, r);
            peer_from_alm(lmax, a, hy.data());
            peer_rotate(a, r, true);
            peer_from_alm(lmax, a, hz.data());
        }
        double ea = 0, na = 0; /* shlab's rotation against rotate_alm's */
        for (size_t i = 0; i < n; i++) {
            ea = std::fmax(ea, std::fabs(y[i] - hy[i]));
            na += (y[i] - hy[i]) * (y[i] - hy[i]);
        }
        double es = 0, eh = 0, ns = 0, nh = 0, nx = 0;
        for (size_t i = 0; i < n; i++) {
            es = std::fmax(es, std::fabs(z[i] - x[i]));
            eh = std::fmax(eh, std::fabs(hz[i] - x[i]));
            ns += (z[i] - x[i]) * (z[i] - x[i]);
            nh += (hz[i] - x[i]) * (hz[i] - x[i]);
            nx += x[i] * x[i];
        }
        if (tsv) {
            if (peer) printf("agreement\t%d\t%.3g\t%.3g\n", lmax, ea, std::sqrt(na / nx));
            printf("roundtrip\t%d\tshlab\t%.3g\t%.3g\n", lmax, es, std::sqrt(ns / nx));
            if (peer) printf("roundtrip\t%d\thealpix\t%.3g\t%.3g\n", lmax, eh, std::sqrt(nh / nx));
            for (int t : threads) printf("rss\t%d\t%d\t%.1f\n", lmax, t, child_rss(lmax, t));
        } else {
            if (peer) {
                printf("%5d round trip: shlab max %.3g rel-L2 %.3g | healpix max %.3g rel-L2 %.3g\n", lmax, es,
                       std::sqrt(ns / nx), eh, std::sqrt(nh / nx));
                printf("%5d shlab vs rotate_alm: max %.3g rel-L2 %.3g\n", lmax, ea, std::sqrt(na / nx));
            } else
                printf("%5d round trip: shlab max %.3g rel-L2 %.3g\n", lmax, es, std::sqrt(ns / nx));
            for (int t : threads)
                printf("%5d peak RSS of a shlab one-shot child, %d thread(s): %.1f MB\n", lmax, t, child_rss(lmax, t));
        }
        fflush(stdout);
    }
    return 0;
}
