/* scene_internal.h — declarations shared by the files of src/scene/ (not
 * installed).  The only place Embree's types appear besides raytrace.c. */
#ifndef SHLAB_SCENE_INTERNAL_H
#define SHLAB_SCENE_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>

#include "core/shlab_internal.h"

struct sh_scene {
    RTCDevice dev;
    RTCScene scn;
    sh_mesh mesh;
    unsigned char *flip; /* per triangle: its winding disagrees with its vertex normals */
    int threads;
    double diag;
};

/* An environment (shade.c): a lat-long image or an analytic light. */
struct sh_env {
    int is_image;
    sh_light light;
    int w, h;
    float *lum, *rgb; /* w·h luminance; 3·w·h planar R, G, B */
    double *omega;    /* w·h pixel solid angles */
};

/* Pixel blocks of an environment image (shade.c): bs×bs pixels in scan
 * order, the last ones cut at the image's edges.  Running sums of |wt|
 * within each block go to cum (wt == cum allowed), the block totals to W
 * (may be NULL; one per block, row-major).  pick: the pixel of block
 * (bx, by) whose running sum first exceeds u (binary search).  sample: a
 * direction uniform in the solid angle of pixel (px, py) (cosθ uniform
 * between the rows' edges, φ uniform). */
void sh__env_block_sums(const sh_env *e, int bs, const double *wt, double *cum, double *W);
size_t sh__env_block_pick(const sh_env *e, int bs, const double *cum, int bx, int by, double u, int *px, int *py);
void sh__env_pixel_sample(const sh_env *e, int px, int py, uint64_t *x, double d[3]);

/* Work split over threads (pthreads): fn(ctx, thread, begin, end) is called
 * for chunks [begin, end) of [0, n) handed out dynamically; thread is in
 * [0, threads).  The calling thread works as thread 0 and alone calls
 * progress (items finished so far).  The first non-zero status stops the
 * others and is returned with its message.  threads ≤ 0: every online CPU. */
typedef int (*sh__work_fn)(void *ctx, int thread, int begin, int end);
int sh__parallel_for(int threads, int n, int chunk, sh__work_fn fn, void *ctx, sh_progress_fn progress,
                     void *progress_ctx, const char *what);
int sh__online_cpus(void);
/* The first Embree error of this thread (cleared) as SH_E* with one line
 * naming `what`; SH_OK if none. */
int sh__embree_status(const sh_scene *s, const char *what);

/* The orthonormal frame of unit n, M row-major with columns (t, b, n),
 * det M = +1 (Duff et al. 2017, "Building an orthonormal basis, revisited"),
 * so that world = M·local. */
void sh__tangent_frame(const double n[3], double M[9]);
/* out = R_sh(M)·in through a rotation plan (the matrix set directly,
 * sh_rot_plan_set_matrix): the one function the scenes rotate with. */
int sh__rotate_frame(sh_rot_plan *plan, const double M[9], const double *in, double *out);

/* Fast ray queries without error checks (call sh__embree_status after a
 * batch).  dir need not be normalised for occlusion; for intersect it must
 * be (t is then a distance). */
static inline int sh__occluded(const sh_scene *s, const double org[3], const double dir[3], float tfar)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay r;
    r.org_x = (float)org[0]; r.org_y = (float)org[1]; r.org_z = (float)org[2];
    r.dir_x = (float)dir[0]; r.dir_y = (float)dir[1]; r.dir_z = (float)dir[2];
    r.tnear = 0.0f;
    r.tfar = tfar;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(s->scn, &ctx, &r);
    return r.tfar < 0.0f; /* Embree sets tfar = −inf on a hit */
}
/* 0: no hit; else the triangle index + 1, barycentrics u, v, and whether
 * the side met is the front (the side its vertex normals face). */
int sh__intersect(const sh_scene *s, const double org[3], const double dir[3], float tfar, double *t,
                  double *u, double *v, int *front);

/* splitmix64: a seeded stream of 64-bit values; uniform doubles in [0,1). */
static inline uint64_t sh__splitmix(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static inline double sh__uniform(uint64_t *x) { return (double)(sh__splitmix(x) >> 11) * 0x1.0p-53; }

/* The jittered s×s grid mapped to the hemisphere with density cosθ/π
 * (Malley: disc point (√u cos 2πv, √u sin 2πv) lifted to z = √(1−u)),
 * d[3k..3k+2], k = i·s + j, jitter from seed. */
void sh__cosine_samples(int s, uint64_t seed, double *d);

double sh__now(void);

#endif
