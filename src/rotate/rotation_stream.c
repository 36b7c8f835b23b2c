/* rotation_stream.c — all bands of many vectors by many rotations at high
 * order: the `halfpi` band kernel (rot_halfpi.c) run band by band, O(order²)
 * memory per thread, with OpenMP across bands and across batches of
 * rotations.
 *
 * Work items are (band l, batch of up to SH_STREAM_JB (rotation, vector)
 * jobs); each item generates d^l(π/2) itself (bands share nothing) and
 * applies it to its batch.  Items are handed out dynamically from the
 * highest band down (the largest first, so the last ones are short).  An item
 * computes the same numbers whichever thread runs it, in the same order, so
 * the result is bit for bit independent of the number of threads.
 */
#include "rotate/rot_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define SH_STREAM_JB 8 /* jobs per item: one generated Δ serves this many */

struct sh_rot_stream {
    int order, threads;
    sh_convention conv;
    size_t work_bytes;
    void **work; /* per thread */
    sh_progress_fn progress;
    void *progress_ctx;
};

int sh__rot_stream_resolve_threads(int threads)
{
#ifdef _OPENMP
    if (threads <= 0) threads = omp_get_max_threads();
#else
    threads = 1;
#endif
    return threads < 1 ? 1 : threads;
}

size_t sh_rot_stream_bytes(int order, int threads)
{
    if (order < 1) order = 1;
    threads = sh__rot_stream_resolve_threads(threads);
    return sizeof(sh_rot_stream) + (size_t)threads * (sizeof(void *) + sh__rot_halfpi_work_bytes(order - 1, SH_STREAM_JB));
}

int sh_rot_stream_create(int order, sh_convention conv, int threads, sh_rot_stream **out)
{
    *out = NULL;
    int st = sh_check_order(order);
    if (st) return st;
    if (conv != SH_CS && conv != SH_NOCS) return sh_error(SH_EINVAL, "rotation stream: unknown convention");
    threads = sh__rot_stream_resolve_threads(threads);
    char what[96];
    snprintf(what, sizeof what, "rotation stream (order %d, %d thread%s)", order, threads, threads > 1 ? "s" : "");
    if ((st = sh__mem_check((double)sh_rot_stream_bytes(order, threads), what))) return st;
    sh_rot_stream *s = calloc(1, sizeof *s);
    if (!s || !(s->work = calloc((size_t)threads, sizeof *s->work))) {
        free(s);
        return sh_error(SH_ENOMEM, "rotation stream: out of memory");
    }
    s->order = order;
    s->threads = threads;
    s->conv = conv;
    s->work_bytes = sh__rot_halfpi_work_bytes(order - 1, SH_STREAM_JB);
    for (int t = 0; t < threads; t++)
        if (!(s->work[t] = malloc(s->work_bytes))) {
            sh_rot_stream_free(s);
            return sh_error(SH_ENOMEM, "rotation stream: out of memory (order %d)", order);
        }
    *out = s;
    return SH_OK;
}

void sh_rot_stream_free(sh_rot_stream *s)
{
    if (!s) return;
    if (s->work)
        for (int t = 0; t < s->threads; t++) free(s->work[t]);
    free(s->work);
    free(s);
}

int sh_rot_stream_threads(const sh_rot_stream *s) { return s->threads; }

void sh_rot_stream_set_progress(sh_rot_stream *s, sh_progress_fn fn, void *ctx)
{
    s->progress = fn;
    s->progress_ctx = ctx;
}

int sh_rot_stream_apply(sh_rot_stream *s, int nrot, const sh_rotation *rots, int inverse, int nvec,
                        const double *in, double *out)
{
    if (nrot < 1 || nvec < 1) return sh_error(SH_EINVAL, "rotation stream: %d rotations, %d vectors", nrot, nvec);
    if (nrot > 1 && in == out) return sh_error(SH_EINVAL, "rotation stream: in-place needs one rotation");
    for (int r = 0; r < nrot; r++)
        if (!isfinite(rots[r].alpha) || !isfinite(rots[r].beta) || !isfinite(rots[r].gamma))
            return sh_error(SH_EINVAL, "rotation stream: rotation %d is not finite", r);
    const int order = s->order, M = order - 1;
    const size_t n2 = (size_t)order * order, na = 6 * (size_t)order;
    double *cs = malloc((size_t)nrot * na * sizeof *cs);
    if (!cs) return sh_error(SH_ENOMEM, "rotation stream: out of memory (angles of %d rotations)", nrot);
    for (int r = 0; r < nrot; r++) sh__rot_halfpi_set_angles(&rots[r], inverse, M, cs + (size_t)r * na);
    const long njobs = (long)nrot * nvec, nbatch = (njobs + SH_STREAM_JB - 1) / SH_STREAM_JB;
    const long nitems = (long)order * nbatch;
    const int nocs = s->conv == SH_NOCS;
    /* small jobs on one thread: waking the others costs more than the work
     * (≈ order³/3 multiply-adds a job; 2e6 is about a millisecond) */
    const double work = (double)order * order * order / 3 * (double)njobs;
    const int nt = work < 2e6 ? 1 : s->threads;
    long done = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
#endif
    for (long it = 0; it < nitems; it++) {
        int tid = 0;
#ifdef _OPENMP
        tid = omp_get_thread_num();
#endif
        const int l = M - (int)(it / nbatch);
        const long j0 = (it % nbatch) * SH_STREAM_JB;
        const int nj = njobs - j0 < SH_STREAM_JB ? (int)(njobs - j0) : SH_STREAM_JB;
        const double *csj[SH_STREAM_JB], *inj[SH_STREAM_JB];
        double *outj[SH_STREAM_JB];
        for (int j = 0; j < nj; j++) {
            const long q = j0 + j, r = q / nvec, v = q % nvec;
            csj[j] = cs + (size_t)r * na;
            inj[j] = in + (size_t)v * n2 + (size_t)l * l;
            outj[j] = out + (size_t)q * n2 + (size_t)l * l;
        }
        sh__rot_halfpi_band_d(l, nocs, nj, csj, M, inj, outj, s->work[tid], NULL);
        if (s->progress) {
#ifdef _OPENMP
#pragma omp critical(sh_rot_stream_progress)
#endif
            {
                done++;
                if (done % nbatch == 0 || done == nitems)
                    s->progress(s->progress_ctx, (int)(done / nbatch), order, "bands");
            }
        }
    }
    free(cs);
    return SH_OK;
}

int sh_rot_band_apply(int l, sh_convention conv, const sh_rotation *rot, int inverse, int nvec,
                      const double *in, double *out)
{
    int st = sh_check_order(l + 1);
    if (st) return st;
    if (nvec < 1) return sh_error(SH_EINVAL, "band rotation: %d vectors", nvec);
    if (!isfinite(rot->alpha) || !isfinite(rot->beta) || !isfinite(rot->gamma))
        return sh_error(SH_EINVAL, "band rotation: the rotation is not finite");
    const int J = nvec < SH_STREAM_JB ? nvec : SH_STREAM_JB;
    const size_t wb = sh__rot_halfpi_work_bytes(l, J), w = 2 * (size_t)l + 1;
    double *cs = malloc(6 * ((size_t)l + 1) * sizeof *cs);
    void *work = malloc(wb);
    if (!cs || !work) {
        free(cs);
        free(work);
        return sh_error(SH_ENOMEM, "band rotation: out of memory (band %d)", l);
    }
    sh__rot_halfpi_set_angles(rot, inverse, l, cs);
    for (int v0 = 0; v0 < nvec; v0 += J) {
        const int nj = nvec - v0 < J ? nvec - v0 : J;
        const double *csj[SH_STREAM_JB], *inj[SH_STREAM_JB];
        double *outj[SH_STREAM_JB];
        for (int j = 0; j < nj; j++) {
            csj[j] = cs;
            inj[j] = in + (size_t)(v0 + j) * w;
            outj[j] = out + (size_t)(v0 + j) * w;
        }
        sh__rot_halfpi_band_d(l, conv == SH_NOCS, nj, csj, l, inj, outj, work, NULL);
    }
    free(cs);
    free(work);
    return SH_OK;
}

int sh_wigner_d_halfpi(int l, double *d)
{
    int st = sh_check_order(l + 1);
    if (st) return st;
    void *work = malloc(sh__rot_halfpi_work_bytes(l, 0));
    if (!work) return sh_error(SH_ENOMEM, "d(pi/2): out of memory (band %d)", l);
    sh__rot_halfpi_delta_d(l, work, d);
    free(work);
    return SH_OK;
}
